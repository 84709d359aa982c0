struct KajiyaKayUniforms {
    kd: vec3<f32>,
    ks: vec3<f32>,
    exponent: f32,
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

const uniforms: KajiyaKayUniforms = KajiyaKayUniforms(vec3<f32>(0.031746723f, 0.016240317f, 0.0032422696f), vec3<f32>(0.019221237f, 0.017891414f, 0.017399637f), 11.818769f);
// 1e-30, the floor that keeps a denominator, a length or a width positive
const TINY: f32 = 0.000000000000000000000000000001f;

// hair_bcsdf: `hairmath eval --model kajiya-kay`, Kajiya and Kay 1989 as the survey writes it: a diffuse k_d cos(theta_i) and one specular cone k_s cos^n(theta_i + theta_o), no cosine factor
// (hairmath::registry::MODELS; Bcsdf::eval in the local frame, tangent +X, no cosine factor)
fn hair_bcsdf(wi: vec3<f32>, wo: vec3<f32>) -> vec3<f32> {
    let cos_theta_i = min(sqrt(((wi.y * wi.y) + (wi.z * wi.z))), 1f);
    let cos_sum = ((cos_theta_i * min(sqrt(((wo.y * wo.y) + (wo.z * wo.z))), 1f)) - (min(max(wi.x, -1f), 1f) * min(max(wo.x, -1f), 1f)));
    let _e47 = select(0f, exp((uniforms.exponent * log(max(cos_sum, TINY)))), (0f < cos_sum));
    return ((uniforms.kd * cos_theta_i) + (uniforms.ks * _e47));
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

