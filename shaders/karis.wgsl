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
// 4 Shift, the TRT lobe's shift (HairShading)
const TRT_SHIFT: f32 = 0.14f;

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
    let _e23 = -(1f);
    let _e25 = min(max(-(wi.x), _e23), 1f);
    let _e28 = min(max(-(wo.x), _e23), 1f);
    let _e32 = min(max(_e28, -1f), 1f);
    let _e39 = min(max(_e25, -1f), 1f);
    let _e61 = (((wi.y * wo.y) + (wi.z * wo.z)) / sqrt(((((wi.y * wi.y) + (wi.z * wi.z)) * ((wo.y * wo.y) + (wo.z * wo.z))) + COS_PHI_EPSILON)));
    let _e62 = (_e25 + _e28);
    let _e65 = max(cos((0.5f * abs((atan2(_e32, sqrt(max((1f - (_e32 * _e32)), 0f))) - atan2(_e39, sqrt(max((1f - (_e39 * _e39)), 0f))))))), TINY);
    let _e70 = sqrt(min(max((0.5f + (0.5f * _e61)), 0f), 1f));
    let _e96 = gaussian_lobe(max((uniforms.width_r * (SQRT_TWO * _e70)), TINY), (_e62 - ((2f * R_TILT_SIN_COS[0]) * (((R_TILT_SIN_COS[1] * _e70) * sqrt(max((1f - (_e28 * _e28)), 0f))) + (R_TILT_SIN_COS[0] * _e28)))));
    let _e105 = fresnel_schlick(sqrt(min(max((0.5f + (0.5f * (((wo.x * wi.x) + (wo.y * wi.y)) + (wo.z * wi.z)))), 0f), 1f)), ETA);
    let _e108 = max((_e96 * ((0.25f * _e70) * _e105)), 0f);
    let _e111 = gaussian_lobe(uniforms.width_tt, (_e62 - SHIFT));
    let _e112 = scaled_eta_prime_karis(_e65);
    let _e113 = (_e65 / _e112);
    let _e114 = h_tt_karis(_e113, _e61, _e70);
    let _e121 = fresnel_schlick((_e65 * sqrt(min(max((1f - (_e114 * _e114)), 0f), 1f))), ETA);
    let _e122 = (1f - _e121);
    let _e124 = d_karis(_e61);
    let _e126 = ((_e111 * _e124) * (_e122 * _e122));
    let _e127 = (_e114 * _e113);
    let _e132 = (2f * abs((1f - ((_e127 * _e127) / _e65))));
    let _e150 = gaussian_lobe(uniforms.width_trt, (_e62 - TRT_SHIFT));
    let _e152 = fresnel_schlick((_e65 * 0.5f), ETA);
    let _e153 = (1f - _e152);
    let _e156 = d_karis_2_(_e61);
    let _e158 = ((_e150 * _e156) * ((_e153 * _e153) * _e152));
    let _e160 = (0.8f / _e65);
    return vec3<f32>(max(((_e108 + max((_e126 * exp((-(uniforms.sigma_a.x) * _e132))), 0f)) + max((_e158 * exp((uniforms.log_color.x * _e160))), 0f)), 0f), max(((_e108 + max((_e126 * exp((-(uniforms.sigma_a.y) * _e132))), 0f)) + max((_e158 * exp((uniforms.log_color.y * _e160))), 0f)), 0f), max(((_e108 + max((_e126 * exp((-(uniforms.sigma_a.z) * _e132))), 0f)) + max((_e158 * exp((uniforms.log_color.z * _e160))), 0f)), 0f));
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
    return FibreFrame(vec3<f32>(_e14, _e15, _e16), vec3<f32>((1f + (((_e20 * _e14) * _e14) * _e22)), (_e20 * _e24), (-(_e20) * _e14)), vec3<f32>(_e24, (_e20 + ((_e15 * _e15) * _e22)), -(_e15)));
}

// fibre_local_directions: hairmath::geometry::local_directions -- wi and wo in the fibre's frame
fn fibre_local_directions(tangent: vec3<f32>, wi: vec3<f32>, wo: vec3<f32>) -> FibreLocalDirections {
    let _e12 = fibre_frame(tangent);
    return FibreLocalDirections(vec3<f32>((((wi.x * _e12.tangent.x) + (wi.y * _e12.tangent.y)) + (wi.z * _e12.tangent.z)), (((wi.x * _e12.normal.x) + (wi.y * _e12.normal.y)) + (wi.z * _e12.normal.z)), (((wi.x * _e12.binormal.x) + (wi.y * _e12.binormal.y)) + (wi.z * _e12.binormal.z))), vec3<f32>((((wo.x * _e12.tangent.x) + (wo.y * _e12.tangent.y)) + (wo.z * _e12.tangent.z)), (((wo.x * _e12.normal.x) + (wo.y * _e12.normal.y)) + (wo.z * _e12.normal.z)), (((wo.x * _e12.binormal.x) + (wo.y * _e12.binormal.y)) + (wo.z * _e12.binormal.z))));
}

// hair_bcsdf_world: hair_bcsdf of world-space directions, made local to the fibre by fibre_local_directions
fn hair_bcsdf_world(tangent: vec3<f32>, wi: vec3<f32>, wo: vec3<f32>) -> vec3<f32> {
    let _e3 = fibre_local_directions(tangent, wi, wo);
    let _e6 = hair_bcsdf(_e3.wi, _e3.wo);
    return _e6;
}

