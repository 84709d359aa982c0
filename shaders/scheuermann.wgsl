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

const uniforms: ScheuermannUniforms = ScheuermannUniforms(vec3<f32>(0.000098897275f, 0.000015974958f, 0.00000022135521f), vec3<f32>(0.027071713f, 0.027071713f, 0.027071713f), 23.637539f, 0.99939084f, -0.034899496f, vec3<f32>(0.0016160229f, 0.00045222277f, 0.000021840126f), 5.9093847f, 0.9975641f, 0.06975647f, 1f);

// hair_bcsdf: `hairmath eval --model scheuermann`, Scheuermann 2004 (ATI) after the blog seed: two smoothstep(-1, 0, T.H) sin(T, H)^e lobes on shifted tangents, the second tinted and masked, and a scaled-and-biased Lambert diffuse
// (hairmath::registry::MODELS; Bcsdf::eval in the local frame, tangent +X, no cosine factor)
fn hair_bcsdf(wi: vec3<f32>, wo: vec3<f32>) -> vec3<f32> {
    let _e57 = min(sqrt(((wo.y * wo.y) + (wo.z * wo.z))), 1f);
    let _e58 = (0.000000000000000000000000000001f < _e57);
    let _e60 = (1f / max(_e57, 0.000000000000000000000000000001f));
    let _e62 = select(1f, (wo.y * _e60), _e58);
    let _e64 = select(0f, (wo.z * _e60), _e58);
    let _e73 = min(max((0.25f + (0.75f * ((wi.y * _e62) + (wi.z * _e64)))), 0f), 1f);
    let _e74 = (wi.x + wo.x);
    let _e75 = (wi.y + wo.y);
    let _e76 = (wi.z + wo.z);
    let _e84 = (1f / max(sqrt((((_e74 * _e74) + (_e75 * _e75)) + (_e76 * _e76))), 0.000000000000000000000000000001f));
    let _e85 = (_e74 * _e84);
    let _e89 = (((_e75 * _e62) + (_e76 * _e64)) * _e84);
    let _e94 = min(max(((uniforms.tangent_primary * _e85) + (uniforms.normal_primary * _e89)), -1f), 1f);
    let _e97 = min(max((_e94 + 1f), 0f), 1f);
    let _e105 = (1f - (_e94 * _e94));
    let _e112 = (((_e97 * _e97) * (3f - (2f * _e97))) * select(0f, exp((uniforms.half_exponent_primary * log(max(_e105, 0.000000000000000000000000000001f)))), (0f < _e105)));
    let _e117 = min(max(((uniforms.tangent_secondary * _e85) + (uniforms.normal_secondary * _e89)), -1f), 1f);
    let _e120 = min(max((_e117 + 1f), 0f), 1f);
    let _e126 = (1f - (_e117 * _e117));
    let _e140 = (uniforms.noise_mask * (((_e120 * _e120) * (3f - (2f * _e120))) * select(0f, exp((uniforms.half_exponent_secondary * log(max(_e126, 0.000000000000000000000000000001f)))), (0f < _e126))));
    return vec3<f32>((((uniforms.kd.x * _e73) + (uniforms.ks_primary.x * _e112)) + (uniforms.ks_secondary.x * _e140)), (((uniforms.kd.y * _e73) + (uniforms.ks_primary.y * _e112)) + (uniforms.ks_secondary.y * _e140)), (((uniforms.kd.z * _e73) + (uniforms.ks_primary.z * _e112)) + (uniforms.ks_secondary.z * _e140)));
}

// hairmath::geometry::fibre_frame -- Duff et al. 2017, listing 3
fn fibre_frame(tangent_in: vec3<f32>) -> array<f32, 9> {
    let _e13 = (1f / max(sqrt((((tangent_in.x * tangent_in.x) + (tangent_in.y * tangent_in.y)) + (tangent_in.z * tangent_in.z))), 0.000000000000000000000000000001f));
    let _e14 = (tangent_in.x * _e13);
    let _e15 = (tangent_in.y * _e13);
    let _e16 = (tangent_in.z * _e13);
    let _e19 = -(1f);
    let _e20 = select(1f, _e19, (_e16 < 0f));
    let _e22 = (_e19 / (_e20 + _e16));
    let _e24 = ((_e14 * _e15) * _e22);
    return array<f32, 9>(_e14, _e15, _e16, (1f + (((_e20 * _e14) * _e14) * _e22)), (_e20 * _e24), (-(_e20) * _e14), _e24, (_e20 + ((_e15 * _e15) * _e22)), -(_e15));
}

// fibre_local_directions: hairmath::geometry::local_directions -- wi and wo in the fibre's frame
fn fibre_local_directions(tangent: vec3<f32>, wi: vec3<f32>, wo: vec3<f32>) -> array<f32, 6> {
    let _e12 = fibre_frame(tangent);
    return array<f32, 6>((((wi.x * _e12[0]) + (wi.y * _e12[1])) + (wi.z * _e12[2])), (((wi.x * _e12[3]) + (wi.y * _e12[4])) + (wi.z * _e12[5])), (((wi.x * _e12[6]) + (wi.y * _e12[7])) + (wi.z * _e12[8])), (((wo.x * _e12[0]) + (wo.y * _e12[1])) + (wo.z * _e12[2])), (((wo.x * _e12[3]) + (wo.y * _e12[4])) + (wo.z * _e12[5])), (((wo.x * _e12[6]) + (wo.y * _e12[7])) + (wo.z * _e12[8])));
}

// hair_bcsdf_world: hair_bcsdf of world-space directions, made local to the fibre by fibre_local_directions
fn hair_bcsdf_world(tangent: vec3<f32>, wi: vec3<f32>, wo: vec3<f32>) -> vec3<f32> {
    let _e3 = fibre_local_directions(tangent, wi, wo);
    let _e12 = hair_bcsdf(vec3<f32>(_e3[0], _e3[1], _e3[2]), vec3<f32>(_e3[3], _e3[4], _e3[5]));
    return _e12;
}

