struct KarisUniforms {
    width_r: f32,
    width_tt: f32,
    width_trt: f32,
    sigma_a: vec3<f32>,
    log_color: vec3<f32>,
}

const uniforms: KarisUniforms = KarisUniforms(0.27830222f, 0.13915111f, 0.55660444f, vec3<f32>(0.5447f, 0.9061f, 1.781f), vec3<f32>(-4.3458734f, -5.6051397f, -7.8583317f));

// hairmath::lobe::gaussian::gaussian_lobe -- Marschner et al. 2003, eq. 6
fn gaussian_lobe(beta: f32, x: f32) -> f32 {
    let _e2 = (x / beta);
    return (exp(((-0.5f * _e2) * _e2)) / (beta * 2.5066283f));
}

// hairmath::fresnel::fresnel_schlick -- Schlick 1994, eq. 24
fn fresnel_schlick(cos_i: f32, eta: f32) -> f32 {
    let _e5 = ((eta - 1f) / (eta + 1f));
    let _e6 = (_e5 * _e5);
    let _e10 = (1f - min(max(cos_i, 0f), 1f));
    let _e11 = (_e10 * _e10);
    return (_e6 + ((((1f - _e6) * _e11) * _e11) * _e10));
}

// hairmath::models::karis::scaled_eta_prime_karis -- Karis 2016 (Bravais' index times cos theta_d)
fn scaled_eta_prime_karis(cos_theta_d: f32) -> f32 {
    return (1.19f + ((0.36f * cos_theta_d) * cos_theta_d));
}

// hairmath::models::karis::h_tt_karis -- Karis 2016 (h_TT ~ (1 + a (c1 - c2 cos phi)) cos(phi/2))
fn h_tt_karis(a: f32, cos_phi: f32, cos_half_phi: f32) -> f32 {
    return ((1f + (a * (0.6f - (0.8f * cos_phi)))) * cos_half_phi);
}

// hairmath::models::karis::d_karis -- Karis 2016 (D ~ exp(a cos phi + b))
fn d_karis(cos_phi_1: f32) -> f32 {
    return exp(((-3.65f * cos_phi_1) + -3.98f));
}

// hairmath::models::karis::d_karis -- Karis 2016 (D ~ exp(a cos phi + b))
fn d_karis_2_(cos_phi_2: f32) -> f32 {
    return exp(((17f * cos_phi_2) + -16.78f));
}

// hair_bcsdf: `hairmath eval --model karis`, Karis 2016 as Unreal Engine 4.27's HairShading (R + TT + TRT) with UE's BaseColor (--color, inverted at beta_n = 0.3) and Roughness, S(wi, wo)
// (hairmath::registry::MODELS; Bcsdf::eval in the local frame, tangent +X, no cosine factor)
fn hair_bcsdf(wi: vec3<f32>, wo: vec3<f32>) -> vec3<f32> {
    let _e35 = -(1f);
    let _e37 = min(max(-(wi.x), _e35), 1f);
    let _e40 = min(max(-(wo.x), _e35), 1f);
    let _e44 = min(max(_e40, -1f), 1f);
    let _e51 = min(max(_e37, -1f), 1f);
    let _e73 = (((wi.y * wo.y) + (wi.z * wo.z)) / sqrt(((((wi.y * wi.y) + (wi.z * wi.z)) * ((wo.y * wo.y) + (wo.z * wo.z))) + 0.0001f)));
    let _e74 = (_e37 + _e40);
    let _e77 = max(cos((0.5f * abs((atan2(_e44, sqrt(max((1f - (_e44 * _e44)), 0f))) - atan2(_e51, sqrt(max((1f - (_e51 * _e51)), 0f))))))), 0.000000000000000000000000000001f);
    let _e82 = sqrt(min(max((0.5f + (0.5f * _e73)), 0f), 1f));
    let _e106 = gaussian_lobe(max((uniforms.width_r * (1.4142135f * _e82)), 0.000000000000000000000000000001f), (_e74 - ((2f * -0.06994285f) * (((0.997551f * _e82) * sqrt(max((1f - (_e40 * _e40)), 0f))) + (-0.06994285f * _e40)))));
    let _e115 = fresnel_schlick(sqrt(min(max((0.5f + (0.5f * (((wo.x * wi.x) + (wo.y * wi.y)) + (wo.z * wi.z)))), 0f), 1f)), 1.55f);
    let _e118 = max((_e106 * ((0.25f * _e82) * _e115)), 0f);
    let _e121 = gaussian_lobe(uniforms.width_tt, (_e74 - 0.035f));
    let _e122 = scaled_eta_prime_karis(_e77);
    let _e123 = (_e77 / _e122);
    let _e124 = h_tt_karis(_e123, _e73, _e82);
    let _e131 = fresnel_schlick((_e77 * sqrt(min(max((1f - (_e124 * _e124)), 0f), 1f))), 1.55f);
    let _e132 = (1f - _e131);
    let _e134 = d_karis(_e73);
    let _e136 = ((_e121 * _e134) * (_e132 * _e132));
    let _e137 = (_e124 * _e123);
    let _e142 = (2f * abs((1f - ((_e137 * _e137) / _e77))));
    let _e160 = gaussian_lobe(uniforms.width_trt, (_e74 - 0.14f));
    let _e162 = fresnel_schlick((_e77 * 0.5f), 1.55f);
    let _e163 = (1f - _e162);
    let _e166 = d_karis_2_(_e73);
    let _e168 = ((_e160 * _e166) * ((_e163 * _e163) * _e162));
    let _e170 = (0.8f / _e77);
    return vec3<f32>(max(((_e118 + max((_e136 * exp((-(uniforms.sigma_a.x) * _e142))), 0f)) + max((_e168 * exp((uniforms.log_color.x * _e170))), 0f)), 0f), max(((_e118 + max((_e136 * exp((-(uniforms.sigma_a.y) * _e142))), 0f)) + max((_e168 * exp((uniforms.log_color.y * _e170))), 0f)), 0f), max(((_e118 + max((_e136 * exp((-(uniforms.sigma_a.z) * _e142))), 0f)) + max((_e168 * exp((uniforms.log_color.z * _e170))), 0f)), 0f));
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

