struct ScheuermannUniforms {
    kd: vec3<f32>,
    ks_primary: vec3<f32>,
    half_exponent_primary: f32,
    tangent_primary: f32,
    normal_primary: f32,
    ks_secondary: vec3<f32>,
    half_exponent_secondary: f32,
    tangent_secondary: f32,
    normal_secondary: f32,
    noise_mask: f32,
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

const uniforms: ScheuermannUniforms = ScheuermannUniforms(vec3<f32>(0.000098897275f, 0.000015974958f, 0.00000022135521f), vec3<f32>(0.027071713f, 0.027071713f, 0.027071713f), 23.637539f, 0.99939084f, -0.034899496f, vec3<f32>(0.0016160229f, 0.00045222277f, 0.000021840126f), 5.9093847f, 0.9975641f, 0.06975647f, 1f);
// 1e-30, the floor that keeps a denominator, a length or a width positive
const TINY: f32 = 0.000000000000000000000000000001f;
// 0.25, the bias of the diffuse's mix(0.25, 1, N.L) (Scheuermann 2004)
const DIFFUSE_BIAS: f32 = 0.25f;
// 0.75, the scale of the diffuse's mix(0.25, 1, N.L) = 0.25 + 0.75 N.L (Scheuermann 2004)
const DIFFUSE_SCALE: f32 = 0.75f;

// hair_bcsdf: `hairmath eval --model scheuermann`, Scheuermann 2004 (ATI) after the blog seed: two smoothstep(-1, 0, T.H) sin(T, H)^e lobes on shifted tangents, the second tinted and masked, and a scaled-and-biased Lambert diffuse
// (hairmath::registry::MODELS; Bcsdf::eval in the local frame, tangent +X, no cosine factor)
fn hair_bcsdf(wi: vec3<f32>, wo: vec3<f32>) -> vec3<f32> {
    let _e36 = min(sqrt(((wo.y * wo.y) + (wo.z * wo.z))), 1f);
    let _e37 = (TINY < _e36);
    let _e39 = (1f / max(_e36, TINY));
    let normal_y = select(1f, (wo.y * _e39), _e37);
    let normal_z = select(0f, (wo.z * _e39), _e37);
    let diffuse = min(max((DIFFUSE_BIAS + (DIFFUSE_SCALE * ((wi.y * normal_y) + (wi.z * normal_z)))), 0f), 1f);
    let _e53 = (wi.x + wo.x);
    let _e54 = (wi.y + wo.y);
    let _e55 = (wi.z + wo.z);
    let _e63 = (1f / max(sqrt((((_e53 * _e53) + (_e54 * _e54)) + (_e55 * _e55))), TINY));
    let half_t = (_e53 * _e63);
    let half_n = (((_e54 * normal_y) + (_e55 * normal_z)) * _e63);
    let _e73 = min(max(((uniforms.tangent_primary * half_t) + (uniforms.normal_primary * half_n)), -1f), 1f);
    let _e76 = min(max((_e73 + 1f), 0f), 1f);
    let _e84 = (1f - (_e73 * _e73));
    let _e91 = (((_e76 * _e76) * (3f - (2f * _e76))) * select(0f, exp((uniforms.half_exponent_primary * log(max(_e84, TINY)))), (0f < _e84)));
    let _e96 = min(max(((uniforms.tangent_secondary * half_t) + (uniforms.normal_secondary * half_n)), -1f), 1f);
    let _e99 = min(max((_e96 + 1f), 0f), 1f);
    let _e105 = (1f - (_e96 * _e96));
    let _e119 = (uniforms.noise_mask * (((_e99 * _e99) * (3f - (2f * _e99))) * select(0f, exp((uniforms.half_exponent_secondary * log(max(_e105, TINY)))), (0f < _e105))));
    return (((uniforms.kd * diffuse) + (uniforms.ks_primary * _e91)) + (uniforms.ks_secondary * _e119));
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

