struct KarisUniforms {
    width_r: f32,
    width_tt: f32,
    width_trt: f32,
    sigma_a: vec3<f32>,
    log_color: vec3<f32>,
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

const uniforms: KarisUniforms = KarisUniforms(0.27830222f, 0.13915111f, 0.55660444f, vec3<f32>(0.5447f, 0.9061f, 1.781f), vec3<f32>(-4.3458734f, -5.6051397f, -7.8583317f));
// 1e-4, the regulariser of UE's cos phi = Lp.Vp rsqrt(|Lp|^2 |Vp|^2 + 1e-4)
const COS_PHI_EPSILON: f32 = 0.0001f;
// 1e-30, the floor that keeps a denominator, a length or a width positive
const TINY: f32 = 0.000000000000000000000000000001f;
// sin and cos of -2 Shift, the R lobe's tilt (HairShading)
const R_TILT_SIN_COS: array<f32, 2> = array<f32, 2>(-0.06994285f, 0.997551f);
// sqrt(2)
const SQRT_TWO: f32 = 1.4142135f;
// sqrt(2 pi), the normalisation of the Gaussian
const SQRT_TWO_PI: f32 = 2.5066283f;
// 1.55, the refractive index of UE's Hair_F
const ETA: f32 = 1.55f;
// UE's Shift, the cuticle tilt in radians: the TT lobe's shift (HairShading)
const SHIFT: f32 = 0.035f;
// a, b of Karis' cos(theta_d) eta' ~ a + b cos^2(theta_d) (Karis 2016)
const KARIS_ETA_PRIME: array<f32, 2> = array<f32, 2>(1.19f, 0.36f);
// c1, c2 of Karis' TT offset (1 + a (c1 - c2 cos(phi))) cos(phi/2) (HairBsdf.ush)
const KARIS_H_TT: array<f32, 2> = array<f32, 2>(0.6f, 0.8f);
// a, b of Karis' TT distribution exp(a cos(phi) + b) (Karis 2016)
const KARIS_D_TT: array<f32, 2> = array<f32, 2>(-3.65f, -3.98f);
// 4 Shift, the TRT lobe's shift (HairShading)
const TRT_SHIFT: f32 = 0.14f;
// a, b of Karis' TRT distribution exp(a cos(phi) + b) (Karis 2016)
const KARIS_D_TRT: array<f32, 2> = array<f32, 2>(17f, -16.78f);
// 0.8, the TRT lobe's Tp = BaseColor^(0.8 / cos theta_d) (HairShading)
const TRT_COLOR_EXPONENT: f32 = 0.8f;

// hairmath::lobe::gaussian::gaussian_lobe -- Marschner et al. 2003, eq. 6
fn gaussian_lobe(beta: f32, x: f32) -> f32 {
    let _e2 = (x / beta);
    return (exp(((-0.5f * _e2) * _e2)) / (beta * SQRT_TWO_PI));
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
fn scaled_eta_prime_karis(cos_theta_d: f32, a: f32, b: f32) -> f32 {
    return (a + ((b * cos_theta_d) * cos_theta_d));
}

// hairmath::models::karis::h_tt_karis -- Karis 2016 (h_TT ~ (1 + a (c1 - c2 cos phi)) cos(phi/2))
fn h_tt_karis(a: f32, cos_phi: f32, cos_half_phi: f32, c1_: f32, c2_: f32) -> f32 {
    return ((1f + (a * (c1_ - (c2_ * cos_phi)))) * cos_half_phi);
}

// hairmath::models::karis::d_karis -- Karis 2016 (D ~ exp(a cos phi + b))
fn d_karis(cos_phi: f32, a: f32, b: f32) -> f32 {
    return exp(((a * cos_phi) + b));
}

// hair_bcsdf: `hairmath eval --model karis`, Karis 2016 as Unreal Engine 4.27's HairShading (R + TT + TRT) with UE's BaseColor (--color, inverted at beta_n = 0.3) and Roughness, S(wi, wo)
// (hairmath::registry::MODELS; Bcsdf::eval in the local frame, tangent +X, no cosine factor)
fn hair_bcsdf(wi: vec3<f32>, wo: vec3<f32>) -> vec3<f32> {
    let _e23 = -(1f);
    let sin_l = min(max(-(wi.x), _e23), 1f);
    let sin_v = min(max(-(wo.x), _e23), 1f);
    let _e32 = min(max(sin_v, -1f), 1f);
    let _e39 = min(max(sin_l, -1f), 1f);
    let cos_phi = (((wi.y * wo.y) + (wi.z * wo.z)) / sqrt(((((wi.y * wi.y) + (wi.z * wi.z)) * ((wo.y * wo.y) + (wo.z * wo.z))) + COS_PHI_EPSILON)));
    let sum_of_sines = (sin_l + sin_v);
    let cos_theta_d = max(cos((0.5f * abs((atan2(_e32, sqrt(max((1f - (_e32 * _e32)), 0f))) - atan2(_e39, sqrt(max((1f - (_e39 * _e39)), 0f))))))), TINY);
    let cos_half_phi = sqrt(min(max((0.5f + (0.5f * cos_phi)), 0f), 1f));
    let v_dot_l = (((wo.x * wi.x) + (wo.y * wi.y)) + (wo.z * wi.z));
    let _e96 = gaussian_lobe(max((uniforms.width_r * (SQRT_TWO * cos_half_phi)), TINY), (sum_of_sines - ((2f * R_TILT_SIN_COS[0]) * (((R_TILT_SIN_COS[1] * cos_half_phi) * sqrt(max((1f - (sin_v * sin_v)), 0f))) + (R_TILT_SIN_COS[0] * sin_v)))));
    let _e105 = fresnel_schlick(sqrt(min(max((0.5f + (0.5f * v_dot_l)), 0f), 1f)), ETA);
    let r_lobe = max((_e96 * ((0.25f * cos_half_phi) * _e105)), 0f);
    let _e111 = gaussian_lobe(uniforms.width_tt, (sum_of_sines - SHIFT));
    let _e116 = scaled_eta_prime_karis(cos_theta_d, KARIS_ETA_PRIME[0], KARIS_ETA_PRIME[1]);
    let inv_eta_prime = (cos_theta_d / _e116);
    let _e122 = h_tt_karis(inv_eta_prime, cos_phi, cos_half_phi, KARIS_H_TT[0], KARIS_H_TT[1]);
    let _e129 = fresnel_schlick((cos_theta_d * sqrt(min(max((1f - (_e122 * _e122)), 0f), 1f))), ETA);
    let _e130 = (1f - _e129);
    let _e136 = d_karis(cos_phi, KARIS_D_TT[0], KARIS_D_TT[1]);
    let tt_lobe = ((_e111 * _e136) * (_e130 * _e130));
    let _e139 = (_e122 * inv_eta_prime);
    let tt_path = (2f * abs((1f - ((_e139 * _e139) / cos_theta_d))));
    let _e162 = gaussian_lobe(uniforms.width_trt, (sum_of_sines - TRT_SHIFT));
    let _e164 = fresnel_schlick((cos_theta_d * 0.5f), ETA);
    let _e165 = (1f - _e164);
    let _e172 = d_karis(cos_phi, KARIS_D_TRT[0], KARIS_D_TRT[1]);
    let trt_lobe = ((_e162 * _e172) * ((_e165 * _e165) * _e164));
    let trt_exponent = (TRT_COLOR_EXPONENT / cos_theta_d);
    return max(((vec3(r_lobe) + max((tt_lobe * exp((-(uniforms.sigma_a) * tt_path))), vec3(0f))) + max((trt_lobe * exp((uniforms.log_color * trt_exponent))), vec3(0f))), vec3(0f));
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

