struct KajiyaKayUniforms {
    kd: vec3<f32>,
    ks: vec3<f32>,
    exponent: f32,
}

const uniforms: KajiyaKayUniforms = KajiyaKayUniforms(vec3<f32>(0.031746723f, 0.016240317f, 0.0032422696f), vec3<f32>(0.019221237f, 0.017891414f, 0.017399637f), 11.818769f);

// hair_bcsdf: `hairmath eval --model kajiya-kay`, Kajiya and Kay 1989 as the survey writes it: a diffuse k_d cos(theta_i) and one specular cone k_s cos^n(theta_i + theta_o), no cosine factor
// (hairmath::registry::MODELS; Bcsdf::eval in the local frame, tangent +X, no cosine factor)
fn hair_bcsdf(wi: vec3<f32>, wo: vec3<f32>) -> vec3<f32> {
    let _e37 = min(sqrt(((wi.y * wi.y) + (wi.z * wi.z))), 1f);
    let _e47 = ((_e37 * min(sqrt(((wo.y * wo.y) + (wo.z * wo.z))), 1f)) - (min(max(wi.x, -1f), 1f) * min(max(wo.x, -1f), 1f)));
    let _e57 = select(0f, exp((uniforms.exponent * log(max(_e47, 0.000000000000000000000000000001f)))), (0f < _e47));
    return vec3<f32>(((uniforms.kd.x * _e37) + (uniforms.ks.x * _e57)), ((uniforms.kd.y * _e37) + (uniforms.ks.y * _e57)), ((uniforms.kd.z * _e37) + (uniforms.ks.z * _e57)));
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

