struct TressFxUniforms {
    kd: vec3<f32>,
    ks_primary: vec3<f32>,
    exponent_primary: f32,
    cos_shift_primary: f32,
    sin_shift_primary: f32,
    ks_secondary: vec3<f32>,
    exponent_secondary: f32,
    cos_shift_secondary: f32,
    sin_shift_secondary: f32,
}

struct FibreFrame {
    tangent: vec3<f32>,
    normal: vec3<f32>,
    binormal: vec3<f32>,
}

struct FibreLocalDirections {
    wi: vec3<f32>,
    wo: vec3<f32>,
}

const uniforms: TressFxUniforms = TressFxUniforms(vec3<f32>(0.031746723f, 0.016240317f, 0.0032422696f), vec3<f32>(0.017417107f, 0.017417107f, 0.017417107f), 11.818769f, 0.9975641f, 0.06975647f, vec3<f32>(0.0010813378f, 0.00030259817f, 0.000014613996f), 2.9546924f, 0.99026805f, 0.1391731f);
// 1e-30, the floor that keeps a denominator, a length or a width positive
const TINY: f32 = 0.000000000000000000000000000001f;

// hair_bcsdf: `hairmath eval --model tressfx`, the two-cone Kajiya-Kay form of TressFX: a diffuse term, a primary cone shifted towards the root and a tinted secondary cone shifted towards the tip
// (hairmath::registry::MODELS; Bcsdf::eval in the local frame, tangent +X, no cosine factor)
fn hair_bcsdf(wi: vec3<f32>, wo: vec3<f32>) -> vec3<f32> {
    let _e31 = min(max(wi.x, -1f), 1f);
    let cos_theta_i = min(sqrt(((wi.y * wi.y) + (wi.z * wi.z))), 1f);
    let _e38 = min(max(wo.x, -1f), 1f);
    let _e43 = min(sqrt(((wo.y * wo.y) + (wo.z * wo.z))), 1f);
    let _e46 = ((cos_theta_i * _e43) - (_e31 * _e38));
    let _e49 = ((_e31 * _e43) + (cos_theta_i * _e38));
    let cos_primary = ((_e46 * uniforms.cos_shift_primary) + (_e49 * uniforms.sin_shift_primary));
    let cos_secondary = ((_e46 * uniforms.cos_shift_secondary) - (_e49 * uniforms.sin_shift_secondary));
    let _e65 = select(0f, exp((uniforms.exponent_primary * log(max(cos_primary, TINY)))), (0f < cos_primary));
    let _e74 = select(0f, exp((uniforms.exponent_secondary * log(max(cos_secondary, TINY)))), (0f < cos_secondary));
    return (((uniforms.kd * cos_theta_i) + (uniforms.ks_primary * _e65)) + (uniforms.ks_secondary * _e74));
}

// hairmath::geometry::fibre_frame -- Duff et al. 2017, listing 3
fn fibre_frame(tangent_in: vec3<f32>) -> FibreFrame {
    let _e13 = (1f / max(sqrt((((tangent_in.x * tangent_in.x) + (tangent_in.y * tangent_in.y)) + (tangent_in.z * tangent_in.z))), TINY));
    let _e14 = (tangent_in.x * _e13);
    let _e15 = (tangent_in.y * _e13);
    let _e16 = (tangent_in.z * _e13);
    let _e19 = -(1f);
    let _e20 = select(1f, _e19, (_e16 < 0f));
    let _e22 = (_e19 / (_e20 + _e16));
    let _e24 = ((_e14 * _e15) * _e22);
    return FibreFrame((tangent_in * _e13), vec3<f32>((1f + (((_e20 * _e14) * _e14) * _e22)), (_e20 * _e24), (-(_e20) * _e14)), vec3<f32>(_e24, (_e20 + ((_e15 * _e15) * _e22)), -(_e15)));
}

// fibre_local_directions: hairmath::geometry::local_directions -- wi and wo in the fibre's frame
fn fibre_local_directions(tangent: vec3<f32>, wi: vec3<f32>, wo: vec3<f32>) -> FibreLocalDirections {
    let _e12 = fibre_frame(tangent);
    return FibreLocalDirections((((wi.x * vec3<f32>(_e12.tangent.x, _e12.normal.x, _e12.binormal.x)) + (wi.y * vec3<f32>(_e12.tangent.y, _e12.normal.y, _e12.binormal.y))) + (wi.z * vec3<f32>(_e12.tangent.z, _e12.normal.z, _e12.binormal.z))), (((wo.x * vec3<f32>(_e12.tangent.x, _e12.normal.x, _e12.binormal.x)) + (wo.y * vec3<f32>(_e12.tangent.y, _e12.normal.y, _e12.binormal.y))) + (wo.z * vec3<f32>(_e12.tangent.z, _e12.normal.z, _e12.binormal.z))));
}

// hair_bcsdf_world: hair_bcsdf of world-space directions, made local to the fibre by fibre_local_directions
fn hair_bcsdf_world(tangent: vec3<f32>, wi: vec3<f32>, wo: vec3<f32>) -> vec3<f32> {
    let _e3 = fibre_local_directions(tangent, wi, wo);
    let _e6 = hair_bcsdf(_e3.wi, _e3.wo);
    return _e6;
}

