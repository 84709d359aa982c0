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

const uniforms: TressFxUniforms = TressFxUniforms(vec3<f32>(0.031746723f, 0.016240317f, 0.0032422696f), vec3<f32>(0.017417107f, 0.017417107f, 0.017417107f), 11.818769f, 0.9975641f, 0.06975647f, vec3<f32>(0.0010813378f, 0.00030259817f, 0.000014613996f), 2.9546924f, 0.99026805f, 0.1391731f);

// hair_bcsdf: `hairmath eval --model tressfx`, the two-cone Kajiya-Kay form of TressFX: a diffuse term, a primary cone shifted towards the root and a tinted secondary cone shifted towards the tip
// (hairmath::registry::MODELS; Bcsdf::eval in the local frame, tangent +X, no cosine factor)
fn hair_bcsdf(wi: vec3<f32>, wo: vec3<f32>) -> vec3<f32> {
    let _e51 = min(max(wi.x, -1f), 1f);
    let _e56 = min(sqrt(((wi.y * wi.y) + (wi.z * wi.z))), 1f);
    let _e58 = min(max(wo.x, -1f), 1f);
    let _e63 = min(sqrt(((wo.y * wo.y) + (wo.z * wo.z))), 1f);
    let _e66 = ((_e56 * _e63) - (_e51 * _e58));
    let _e69 = ((_e51 * _e63) + (_e56 * _e58));
    let _e72 = ((_e66 * uniforms.cos_shift_primary) + (_e69 * uniforms.sin_shift_primary));
    let _e75 = ((_e66 * uniforms.cos_shift_secondary) - (_e69 * uniforms.sin_shift_secondary));
    let _e85 = select(0f, exp((uniforms.exponent_primary * log(max(_e72, 0.000000000000000000000000000001f)))), (0f < _e72));
    let _e94 = select(0f, exp((uniforms.exponent_secondary * log(max(_e75, 0.000000000000000000000000000001f)))), (0f < _e75));
    return vec3<f32>((((uniforms.kd.x * _e56) + (uniforms.ks_primary.x * _e85)) + (uniforms.ks_secondary.x * _e94)), (((uniforms.kd.y * _e56) + (uniforms.ks_primary.y * _e85)) + (uniforms.ks_secondary.y * _e94)), (((uniforms.kd.z * _e56) + (uniforms.ks_primary.z * _e85)) + (uniforms.ks_secondary.z * _e94)));
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

