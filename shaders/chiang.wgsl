struct ChiangUniforms {
    variance_r: f32,
    variance_tt: f32,
    variance_trt: f32,
    inv_variance_r: f32,
    inv_variance_tt: f32,
    inv_variance_trt: f32,
    lobe_norm_r: f32,
    lobe_norm_tt: f32,
    lobe_norm_trt: f32,
    logistic_scale: f32,
    logistic_inv_scale: f32,
    logistic_mass: f32,
    logistic_norm: f32,
    sin_alpha: f32,
    cos_alpha: f32,
    sin_2_alpha: f32,
    cos_2_alpha: f32,
    sin_4_alpha: f32,
    cos_4_alpha: f32,
    eta: f32,
    inv_eta: f32,
    sigma_a: vec3<f32>,
}

const uniforms: ChiangUniforms = ChiangUniforms(0.08461118f, 0.021152794f, 0.3384447f, 11.818769f, 47.275078f, 2.9546924f, 11.818769f, 47.275078f, 2.9627328f, 0.117159806f, 8.535351f, 1f, 8.535351f, 0.034899496f, 0.99939084f, 0.06975647f, 0.9975641f, 0.1391731f, 0.99026805f, 1.55f, 0.6451613f, vec3<f32>(0.5447f, 0.9061f, 1.781f));

// hairmath::geometry::fibre_angles -- the local frame of DESIGN.md: sin theta = w.x, phi in the YZ plane
fn fibre_angles(wi_in: vec3<f32>, wo_in: vec3<f32>) -> array<f32, 5> {
    let _e38 = (((1f * ((wi_in.y * wo_in.z) - (wi_in.z * wo_in.y))) + (0f * ((wi_in.z * 0f) - (0f * wo_in.z)))) + (0f * ((0f * wo_in.y) - (wi_in.y * 0f))));
    let _e43 = (((0f * 0f) + (wi_in.y * wo_in.y)) + (wi_in.z * wo_in.z));
    return array<f32, 5>(min(max(wi_in.x, -1f), 1f), min(sqrt(((wi_in.y * wi_in.y) + (wi_in.z * wi_in.z))), 1f), min(max(wo_in.x, -1f), 1f), min(sqrt(((wo_in.y * wo_in.y) + (wo_in.z * wo_in.z))), 1f), atan2(_e38, select(1f, _e43, (0f < (abs(_e38) + abs(_e43))))));
}

// hairmath::fresnel::fresnel -- Born and Wolf, section 1.5 (unpolarised dielectric reflectance)
fn fresnel(cos_i: f32, eta: f32, inv_eta: f32) -> f32 {
    let _e11 = sqrt(max((1f - ((1f - (cos_i * cos_i)) * (inv_eta * inv_eta))), 0f));
    let _e12 = (eta * cos_i);
    let _e13 = (_e12 - _e11);
    let _e14 = (_e12 + _e11);
    let _e15 = (eta * _e11);
    let _e16 = (cos_i - _e15);
    let _e17 = (cos_i + _e15);
    let _e18 = (_e14 * _e14);
    let _e19 = (_e17 * _e17);
    return min(((((_e13 * _e13) * _e19) + ((_e16 * _e16) * _e18)) / ((2f * _e18) * _e19)), 1f);
}

// hairmath::azimuthal::path::fibre_path -- Chiang et al. 2016, sections 4.1 and 4.3 (Snell and Bravais; the chord 2 cos gamma_t / cos theta_t)
fn fibre_path(h_in: f32, c0_: f32, inv_eta_1: f32, c2_: f32, eta_1: f32) -> array<f32, 4> {
    let _e8 = min(max(h_in, -(1f)), 1f);
    let _e11 = (((_e8 * c0_) * inv_eta_1) * c2_);
    let _e16 = sqrt(max((1f - (_e11 * _e11)), 0f));
    let _e20 = sqrt(max((1f - (_e8 * _e8)), 0f));
    let _e22 = fresnel((c0_ * _e20), eta_1, inv_eta_1);
    return array<f32, 4>(atan2(_e8, _e20), atan2(_e11, _e16), ((2f * _e16) * c2_), _e22);
}

// hairmath::azimuthal::attenuation::attenuations -- Chiang et al. 2016, eqs. 3 and 6
fn attenuations(fresnel_in: f32, transmittance: f32) -> array<f32, 4> {
    let _e3 = (1f - fresnel_in);
    let _e5 = ((_e3 * _e3) * transmittance);
    let _e7 = ((_e5 * fresnel_in) * transmittance);
    return array<f32, 4>(fresnel_in, _e5, _e7, (((_e7 * fresnel_in) * transmittance) / max((1f - (fresnel_in * transmittance)), 0.000000000000000000000000000001f)));
}

// hairmath::azimuthal::exit_angle::exit_angle -- Marschner et al. 2003, eq. 3
fn exit_angle(p: f32, gamma_i: f32, gamma_t: f32) -> f32 {
    return ((((2f * p) * gamma_t) - (2f * gamma_i)) + (p * 3.1415927f));
}

// hairmath::bcsdf::chiang::trimmed_logistics -- Chiang et al. 2016, eq. 13
fn trimmed_logistics(dphi_r: f32, dphi_tt: f32, dphi_trt: f32, logistic_inv_scale: f32, logistic_norm: f32) -> array<f32, 3> {
    let _e8 = exp((-(abs(dphi_r)) * logistic_inv_scale));
    let _e10 = (1f + _e8);
    let _e11 = (_e10 * _e10);
    let _e15 = exp((-(abs(dphi_tt)) * logistic_inv_scale));
    let _e16 = (1f + _e15);
    let _e17 = (_e16 * _e16);
    let _e21 = exp((-(abs(dphi_trt)) * logistic_inv_scale));
    let _e22 = (1f + _e21);
    let _e23 = (_e22 * _e22);
    let _e27 = (logistic_norm / (((1f * _e11) * _e17) * _e23));
    let _e31 = (_e27 * _e11);
    return array<f32, 3>((_e8 * ((_e27 * _e17) * _e23)), (_e15 * (_e31 * _e23)), (_e21 * (_e31 * _e17)));
}

// hairmath::lobe::deon::deon_lobe -- d'Eon et al. 2011, eq. 7
fn deon_lobe(sin_i: f32, cos_i_1: f32, sin_o: f32, cos_o: f32, inv_variance_r: f32, lobe_norm_r: f32) -> f32 {
    let _e7 = (cos_i_1 * cos_o);
    let _e9 = (_e7 - (sin_i * sin_o));
    let _e12 = ((sin_i * cos_o) + (cos_i_1 * sin_o));
    let _e22 = max((_e7 * inv_variance_r), 0f);
    let _e27 = (min(_e22, 3.75f) * 0.26666668f);
    let _e28 = (_e27 * _e27);
    let _e47 = (1f / max(_e22, 3.75f));
    let _e48 = (3.75f * _e47);
    let _e76 = (_e22 < 3.75f);
    return ((lobe_norm_r * select((((((((((((((((((0.00392377f * _e48) + -0.01647633f) * _e48) + 0.02635537f) * _e48) + -0.02057706f) * _e48) + 0.00916281f) * _e48) + -0.00157565f) * _e48) + 0.00225319f) * _e48) + 0.01328592f) * _e48) + 0.3989423f) * sqrt(_e47)), ((((((((((((0.0045813f * _e28) + 0.0360768f) * _e28) + 0.2659732f) * _e28) + 1.2067492f) * _e28) + 3.0899425f) * _e28) + 3.5156229f) * _e28) + 1f), _e76)) * exp((select(0f, -(_e22), _e76) - (select((1f - _e9), ((_e12 * _e12) / (1f + max(_e9, 0f))), (0f < _e9)) * inv_variance_r))));
}

// hair_bcsdf: `hairmath eval --model chiang`, Chiang et al. 2016 (pbrt-v4 HairBxDF): the near-field reference, S(wi, wo, h)
// (hairmath::registry::MODELS; Bcsdf::eval in the local frame, tangent +X, no cosine factor)
fn hair_bcsdf(wi: vec3<f32>, wo: vec3<f32>, h: f32) -> vec3<f32> {
    let _e50 = fibre_angles(wi, wo);
    let _e56 = -(_e50[4]);
    let _e57 = (_e50[2] * uniforms.inv_eta);
    let _e65 = fibre_path(h, _e50[3], uniforms.inv_eta, (1f / sqrt(max((1f - (_e57 * _e57)), 0f))), uniforms.eta);
    let _e73 = attenuations(_e65[3], exp((-(uniforms.sigma_a.x) * _e65[2])));
    let _e81 = attenuations(_e65[3], exp((-(uniforms.sigma_a.y) * _e65[2])));
    let _e89 = attenuations(_e65[3], exp((-(uniforms.sigma_a.z) * _e65[2])));
    let _e94 = exit_angle(0f, _e65[0], _e65[1]);
    let _e95 = (_e56 - _e94);
    let _e104 = exit_angle(1f, _e65[0], _e65[1]);
    let _e105 = (_e56 - _e104);
    let _e112 = exit_angle(2f, _e65[0], _e65[1]);
    let _e113 = (_e56 - _e112);
    let _e119 = trimmed_logistics((_e95 - (6.2831855f * floor(((_e95 + 3.1415927f) * 0.15915494f)))), (_e105 - (6.2831855f * floor(((_e105 + 3.1415927f) * 0.15915494f)))), (_e113 - (6.2831855f * floor(((_e113 + 3.1415927f) * 0.15915494f)))), uniforms.logistic_inv_scale, uniforms.logistic_norm);
    let _e135 = -(uniforms.sin_2_alpha);
    let _e143 = deon_lobe(_e50[0], _e50[1], ((_e50[2] * uniforms.cos_2_alpha) + (_e50[3] * _e135)), abs(((_e50[3] * uniforms.cos_2_alpha) - (_e50[2] * _e135))), uniforms.inv_variance_r, uniforms.lobe_norm_r);
    let _e151 = deon_lobe(_e50[0], _e50[1], ((_e50[2] * uniforms.cos_alpha) + (_e50[3] * uniforms.sin_alpha)), abs(((_e50[3] * uniforms.cos_alpha) - (_e50[2] * uniforms.sin_alpha))), uniforms.inv_variance_tt, uniforms.lobe_norm_tt);
    let _e159 = deon_lobe(_e50[0], _e50[1], ((_e50[2] * uniforms.cos_4_alpha) + (_e50[3] * uniforms.sin_4_alpha)), abs(((_e50[3] * uniforms.cos_4_alpha) - (_e50[2] * uniforms.sin_4_alpha))), uniforms.inv_variance_trt, uniforms.lobe_norm_trt);
    let _e160 = deon_lobe(_e50[0], _e50[1], _e50[2], _e50[3], uniforms.inv_variance_trt, uniforms.lobe_norm_trt);
    return vec3<f32>(((((0f + (_e143 * (_e73[0] * _e119[0]))) + (_e151 * (_e73[1] * _e119[1]))) + (_e159 * (_e73[2] * _e119[2]))) + (_e160 * (_e73[3] * 0.15915494f))), ((((0f + (_e143 * (_e81[0] * _e119[0]))) + (_e151 * (_e81[1] * _e119[1]))) + (_e159 * (_e81[2] * _e119[2]))) + (_e160 * (_e81[3] * 0.15915494f))), ((((0f + (_e143 * (_e89[0] * _e119[0]))) + (_e151 * (_e89[1] * _e119[1]))) + (_e159 * (_e89[2] * _e119[2]))) + (_e160 * (_e89[3] * 0.15915494f))));
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
fn hair_bcsdf_world(tangent: vec3<f32>, wi: vec3<f32>, wo: vec3<f32>, h: f32) -> vec3<f32> {
    let _e4 = fibre_local_directions(tangent, wi, wo);
    let _e13 = hair_bcsdf(vec3<f32>(_e4[0], _e4[1], _e4[2]), vec3<f32>(_e4[3], _e4[4], _e4[5]), h);
    return _e13;
}

