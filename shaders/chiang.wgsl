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

struct FibreAngles {
    sin_theta_i: f32,
    cos_theta_i: f32,
    sin_theta_o: f32,
    cos_theta_o: f32,
    phi: f32,
}

struct FibrePath {
    gamma_o: f32,
    gamma_t: f32,
    segment_length: f32,
    fresnel: f32,
}

struct Attenuations {
    r: f32,
    tt: f32,
    trt: f32,
    residual: f32,
}

struct ExitAzimuths {
    r: f32,
    tt: f32,
    trt: f32,
}

struct TrimmedLogistics {
    r: f32,
    tt: f32,
    trt: f32,
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

const uniforms: ChiangUniforms = ChiangUniforms(0.08461118f, 0.021152794f, 0.3384447f, 11.818769f, 47.275078f, 2.9546924f, 11.818769f, 47.275078f, 2.9627328f, 0.117159806f, 8.535351f, 1f, 8.535351f, 0.034899496f, 0.99939084f, 0.06975647f, 0.9975641f, 0.1391731f, 0.99026805f, 1.55f, 0.6451613f, vec3<f32>(0.5447f, 0.9061f, 1.781f));
// 1e-30, the floor that keeps a denominator, a length or a width positive
const TINY: f32 = 0.000000000000000000000000000001f;
// pi
const PI: f32 = 3.1415927f;
// 1 / (2 pi), the uniform density over a full turn
const INV_TWO_PI: f32 = 0.15915494f;
// 2 pi
const TWO_PI: f32 = 6.2831855f;
// 3.75, where I0 switches from Abramowitz and Stegun 9.8.1 to 9.8.2
const BESSEL_I0_SWITCH: f32 = 3.75f;
// 1 / 3.75, the argument scale of Abramowitz and Stegun 9.8.1
const BESSEL_I0_INV_SWITCH: f32 = 0.26666668f;
// Abramowitz and Stegun 9.8.1: I0(x) = sum a_k (x/3.75)^(2k), |x| <= 3.75
const BESSEL_I0_NEAR: array<f32, 7> = array<f32, 7>(1f, 3.5156229f, 3.0899425f, 1.2067492f, 0.2659732f, 0.0360768f, 0.0045813f);
// Abramowitz and Stegun 9.8.2: sqrt(x) e^-x I0(x) = sum b_k (3.75/x)^k, x >= 3.75
const BESSEL_I0_FAR: array<f32, 9> = array<f32, 9>(0.3989423f, 0.01328592f, 0.00225319f, -0.00157565f, 0.00916281f, -0.02057706f, 0.02635537f, -0.01647633f, 0.00392377f);

// hairmath::geometry::fibre_angles -- the local frame of docs/ARCHITECTURE.md: sin theta = w.x, phi in the YZ plane
fn fibre_angles(wi_in: vec3<f32>, wo_in: vec3<f32>) -> FibreAngles {
    let _e27 = ((wi_in.y * wo_in.z) + -((wi_in.z * wo_in.y)));
    let _e30 = ((wi_in.y * wo_in.y) + (wi_in.z * wo_in.z));
    return FibreAngles(min(max(wi_in.x, -1f), 1f), min(sqrt(((wi_in.y * wi_in.y) + (wi_in.z * wi_in.z))), 1f), min(max(wo_in.x, -1f), 1f), min(sqrt(((wo_in.y * wo_in.y) + (wo_in.z * wo_in.z))), 1f), atan2(_e27, select(1f, _e30, (0f < (abs(_e27) + abs(_e30))))));
}

// hairmath::fresnel::fresnel_of_cosines -- Born and Wolf, section 1.5 (unpolarised dielectric reflectance, both cosines given)
fn fresnel_of_cosines(cos_i: f32, cos_t: f32, eta: f32) -> f32 {
    let _e4 = (eta * cos_i);
    let _e5 = (_e4 + -(cos_t));
    let _e6 = (_e4 + cos_t);
    let _e9 = ((-(eta) * cos_t) + cos_i);
    let _e11 = ((eta * cos_t) + cos_i);
    let _e12 = (_e6 * _e6);
    let _e13 = (_e11 * _e11);
    return min(((((_e9 * _e9) * _e12) + ((_e5 * _e5) * _e13)) / ((2f * _e12) * _e13)), 1f);
}

// hairmath::azimuthal::path::fibre_path -- Chiang et al. 2016, sections 4.1 and 4.3 (Snell and Bravais; the chord 2 cos gamma_t / cos theta_t)
fn fibre_path(h_in: f32, cos_theta_o: f32, inv_eta: f32, inv_cos_theta_t: f32, cos_theta_t: f32, eta: f32) -> FibrePath {
    let _e9 = min(max(h_in, -(1f)), 1f);
    let _e12 = (((_e9 * cos_theta_o) * inv_eta) * inv_cos_theta_t);
    let _e18 = sqrt(max(((-(_e12) * _e12) + 1f), 0f));
    let _e23 = sqrt(max(((1f - _e9) * (1f + _e9)), 0f));
    let _e26 = fresnel_of_cosines((cos_theta_o * _e23), (cos_theta_t * _e18), eta);
    return FibrePath(atan2(_e9, _e23), atan2(_e12, _e18), ((2f * _e18) * inv_cos_theta_t), _e26);
}

// hairmath::azimuthal::attenuation::attenuations -- Chiang et al. 2016, eqs. 3 and 6
fn attenuations(fresnel: f32, transmittance: f32) -> Attenuations {
    let _e3 = (1f - fresnel);
    let _e5 = ((_e3 * _e3) * transmittance);
    let _e6 = (fresnel * transmittance);
    let _e7 = (_e5 * _e6);
    return Attenuations(fresnel, _e5, _e7, ((_e7 * _e6) / max((1f - _e6), TINY)));
}

// hairmath::azimuthal::exit_angle::exit_azimuths -- Marschner et al. 2003, eq. 3: phi - Phi(p) for p = 0, 1, 2, wrapped into [-pi, pi]
fn exit_azimuths(phi: f32, gamma_i: f32, gamma_t: f32) -> ExitAzimuths {
    let _e5 = ((2f * gamma_i) + phi);
    let _e8 = ((2f * gamma_t) + PI);
    let _e9 = (_e5 - _e8);
    let _e12 = ((-2f * _e8) + _e5);
    let _e19 = -(TWO_PI);
    return ExitAzimuths(((floor(((_e5 * INV_TWO_PI) + 0.5f)) * _e19) + _e5), ((floor(((_e9 * INV_TWO_PI) + 0.5f)) * _e19) + _e9), ((floor(((_e12 * INV_TWO_PI) + 0.5f)) * _e19) + _e12));
}

// hairmath::bcsdf::chiang::trimmed_logistics -- Chiang et al. 2016, eq. 13
fn trimmed_logistics(dphi_r: f32, dphi_tt: f32, dphi_trt: f32, logistic_inv_scale: f32, logistic_norm: f32) -> TrimmedLogistics {
    let _e8 = exp((-(abs(dphi_r)) * logistic_inv_scale));
    let _e10 = (1f + _e8);
    let _e17 = exp((-(abs(dphi_tt)) * logistic_inv_scale));
    let _e18 = (1f + _e17);
    let _e25 = exp((-(abs(dphi_trt)) * logistic_inv_scale));
    let _e26 = (1f + _e25);
    return TrimmedLogistics(((_e8 * logistic_norm) / (_e10 * _e10)), ((_e17 * logistic_norm) / (_e18 * _e18)), ((_e25 * logistic_norm) / (_e26 * _e26)));
}

// hairmath::lobe::deon::deon_lobe -- d'Eon et al. 2011, eq. 7
fn deon_lobe(sin_i: f32, cos_i: f32, sin_o: f32, cos_o: f32, inv_variance_r: f32, lobe_norm_r: f32) -> f32 {
    let _e7 = (cos_i * cos_o);
    let _e10 = ((-(sin_i) * sin_o) + _e7);
    let _e13 = ((sin_i * cos_o) + (cos_i * sin_o));
    let _e14 = abs(_e10);
    let _e23 = max((_e7 * inv_variance_r), 0f);
    let _e24 = (_e23 < BESSEL_I0_SWITCH);
    let _e27 = (min(_e23, BESSEL_I0_SWITCH) * BESSEL_I0_INV_SWITCH);
    let _e28 = (_e27 * _e27);
    let _e56 = (1f / max(_e23, BESSEL_I0_SWITCH));
    let _e57 = (BESSEL_I0_SWITCH * _e56);
    return ((lobe_norm_r * select((((((((((((((((((BESSEL_I0_FAR[8] * _e57) + BESSEL_I0_FAR[7]) * _e57) + BESSEL_I0_FAR[6]) * _e57) + BESSEL_I0_FAR[5]) * _e57) + BESSEL_I0_FAR[4]) * _e57) + BESSEL_I0_FAR[3]) * _e57) + BESSEL_I0_FAR[2]) * _e57) + BESSEL_I0_FAR[1]) * _e57) + BESSEL_I0_FAR[0]) * sqrt(_e56)), ((((((((((((BESSEL_I0_NEAR[6] * _e28) + BESSEL_I0_NEAR[5]) * _e28) + BESSEL_I0_NEAR[4]) * _e28) + BESSEL_I0_NEAR[3]) * _e28) + BESSEL_I0_NEAR[2]) * _e28) + BESSEL_I0_NEAR[1]) * _e28) + BESSEL_I0_NEAR[0]), _e24)) * exp(((-((((_e13 * _e13) / (1f + _e14)) + (_e14 - _e10))) * inv_variance_r) + select(0f, -(_e23), _e24))));
}

// hair_bcsdf: `hairmath eval --model chiang`, Chiang et al. 2016 (pbrt-v4 HairBxDF): the near-field reference, S(wi, wo, h)
// (hairmath::registry::MODELS; Bcsdf::eval in the local frame, tangent +X, no cosine factor)
fn hair_bcsdf(wi: vec3<f32>, wo: vec3<f32>, h: f32) -> vec3<f32> {
    let _e30 = fibre_angles(wi, wo);
    let phi = -(_e30.phi);
    let _e37 = (_e30.sin_theta_o * uniforms.inv_eta);
    let cos_theta_t = sqrt(max(((-(_e37) * _e37) + 1f), 0f));
    let inv_cos_theta_t = (1f / cos_theta_t);
    let _e46 = fibre_path(h, _e30.cos_theta_o, uniforms.inv_eta, inv_cos_theta_t, cos_theta_t, uniforms.eta);
    let _e54 = attenuations(_e46.fresnel, exp((-(uniforms.sigma_a.x) * _e46.segment_length)));
    let _e62 = attenuations(_e46.fresnel, exp((-(uniforms.sigma_a.y) * _e46.segment_length)));
    let _e70 = attenuations(_e46.fresnel, exp((-(uniforms.sigma_a.z) * _e46.segment_length)));
    let _e75 = exit_azimuths(phi, _e46.gamma_o, _e46.gamma_t);
    let _e79 = trimmed_logistics(_e75.r, _e75.tt, _e75.trt, uniforms.logistic_inv_scale, uniforms.logistic_norm);
    let _e84 = -(uniforms.sin_2_alpha);
    let _e93 = deon_lobe(_e30.sin_theta_i, _e30.cos_theta_i, ((_e30.sin_theta_o * uniforms.cos_2_alpha) + (_e30.cos_theta_o * _e84)), abs(((_e30.cos_theta_o * uniforms.cos_2_alpha) + -((_e30.sin_theta_o * _e84)))), uniforms.inv_variance_r, uniforms.lobe_norm_r);
    let _e102 = deon_lobe(_e30.sin_theta_i, _e30.cos_theta_i, ((_e30.sin_theta_o * uniforms.cos_alpha) + (_e30.cos_theta_o * uniforms.sin_alpha)), abs(((_e30.cos_theta_o * uniforms.cos_alpha) + -((_e30.sin_theta_o * uniforms.sin_alpha)))), uniforms.inv_variance_tt, uniforms.lobe_norm_tt);
    let _e111 = deon_lobe(_e30.sin_theta_i, _e30.cos_theta_i, ((_e30.sin_theta_o * uniforms.cos_4_alpha) + (_e30.cos_theta_o * uniforms.sin_4_alpha)), abs(((_e30.cos_theta_o * uniforms.cos_4_alpha) + -((_e30.sin_theta_o * uniforms.sin_4_alpha)))), uniforms.inv_variance_trt, uniforms.lobe_norm_trt);
    let _e112 = deon_lobe(_e30.sin_theta_i, _e30.cos_theta_i, _e30.sin_theta_o, _e30.cos_theta_o, uniforms.inv_variance_trt, uniforms.lobe_norm_trt);
    let _e113 = (_e93 * _e79.r);
    let _e114 = (_e102 * _e79.tt);
    let _e115 = (_e111 * _e79.trt);
    let _e116 = (_e112 * INV_TWO_PI);
    return ((_e116 * vec3<f32>(_e54.residual, _e62.residual, _e70.residual)) + ((_e115 * vec3<f32>(_e54.trt, _e62.trt, _e70.trt)) + ((_e114 * vec3<f32>(_e54.tt, _e62.tt, _e70.tt)) + (_e113 * vec3<f32>(_e54.r, _e62.r, _e70.r)))));
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
fn hair_bcsdf_world(tangent: vec3<f32>, wi: vec3<f32>, wo: vec3<f32>, h: f32) -> vec3<f32> {
    let _e4 = fibre_local_directions(tangent, wi, wo);
    let _e7 = hair_bcsdf(_e4.wi, _e4.wo, h);
    return _e7;
}

