struct FrostbiteUniforms {
    width_r: f32,
    width_tt: f32,
    width_trt: f32,
    shift_r: f32,
    shift_tt: f32,
    shift_trt: f32,
    eta: f32,
    sigma_a: vec3<f32>,
    beta_n: f32,
    trt_scale: f32,
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

struct FibreFrame {
    tangent: vec3<f32>,
    normal: vec3<f32>,
    binormal: vec3<f32>,
}

struct FibreLocalDirections {
    wi: vec3<f32>,
    wo: vec3<f32>,
}

// theta_o at the first texel of lut0_frostbite_tt
const LUT0_FROSTBITE_TT_THETA_O_MIN: f32 = 0f;
// 1 / (1.3962634 - 0), theta_o to [0, 1] across lut0_frostbite_tt's texels
const LUT0_FROSTBITE_TT_THETA_O_SCALE: f32 = 0.71619725f;
// beta_n at the first texel of lut0_frostbite_tt
const LUT0_FROSTBITE_TT_BETA_N_MIN: f32 = 0.1f;
// 1 / (1 - 0.1), beta_n to [0, 1] across lut0_frostbite_tt's texels
const LUT0_FROSTBITE_TT_BETA_N_SCALE: f32 = 1.1111112f;
const uniforms: FrostbiteUniforms = FrostbiteUniforms(0.27830222f, 0.13915111f, 0.55660444f, 0.06979899f, -0.03490481f, -0.10467191f, 1.55f, vec3<f32>(0.5447f, 0.9061f, 1.781f), 0.3f, 1f);
// sqrt(2 pi), the normalisation of the Gaussian
const SQRT_TWO_PI: f32 = 2.5066283f;
// pi
const PI: f32 = 3.1415927f;
// h_TT = 0, the offset of Frostbite's TT attenuation (Tafuri 2019, slide 20)
const TT_OFFSET: f32 = 0f;
// 1e-30, the floor that keeps a denominator, a length or a width positive
const TINY: f32 = 0.000000000000000000000000000001f;
// a, b of Karis' TRT distribution exp(a cos(phi) + b) (Karis 2016)
const KARIS_D_TRT: array<f32, 2> = array<f32, 2>(17f, -16.78f);
// h_TRT = sqrt(3)/2, the offset of Frostbite's TRT attenuation (slide 21)
const TRT_OFFSET: f32 = 0.8660254f;

// lut0_frostbite_tt_texels: 9 x 10 texels (theta_o in [0, 1.3962634] along x, beta_n in [0.1, 1] along y); x, y = a, b; rgba32float, read with textureLoad
@group(1) @binding(0) 
var lut0_frostbite_tt_texels: texture_2d<f32>;

// table 0 (frostbite_tt): 2 axes, 2 channels; multilinear interpolation of texels read with textureLoad, in the operation order of hairmath::lut::Table::lookup_into: per axis t = clamp((x - MIN) * SCALE, 0, 1) * (n - 1) over its n texels
fn lut0_frostbite_tt(theta_o: f32, beta_n: f32) -> vec4<f32> {
    let _e11 = (min(max(((theta_o - LUT0_FROSTBITE_TT_THETA_O_MIN) * LUT0_FROSTBITE_TT_THETA_O_SCALE), 0f), 1f) * 8f);
    let _e14 = min(floor(_e11), 7f);
    let _e15 = (_e11 - _e14);
    let _e16 = (1f - _e15);
    let _e20 = clamp(i32(_e14), 0i, 7i);
    let _e22 = (_e20 + 1i);
    let _e30 = (min(max(((beta_n - LUT0_FROSTBITE_TT_BETA_N_MIN) * LUT0_FROSTBITE_TT_BETA_N_SCALE), 0f), 1f) * 9f);
    let _e32 = min(floor(_e30), 8f);
    let _e33 = (_e30 - _e32);
    let _e34 = (1f - _e33);
    let _e37 = clamp(i32(_e32), 0i, 8i);
    let _e38 = (_e37 + 1i);
    let _e42 = textureLoad(lut0_frostbite_tt_texels, vec2<i32>(_e20, _e37), 0i);
    let _e46 = textureLoad(lut0_frostbite_tt_texels, vec2<i32>(_e22, _e37), 0i);
    let _e51 = textureLoad(lut0_frostbite_tt_texels, vec2<i32>(_e20, _e38), 0i);
    let _e56 = textureLoad(lut0_frostbite_tt_texels, vec2<i32>(_e22, _e38), 0i);
    return (((((_e16 * _e34) * _e42) + ((_e15 * _e34) * _e46)) + ((_e16 * _e33) * _e51)) + ((_e15 * _e33) * _e56));
}

// hairmath::geometry::fibre_angles -- the local frame of docs/ARCHITECTURE.md: sin theta = w.x, phi in the YZ plane
fn fibre_angles(wi_in: vec3<f32>, wo_in: vec3<f32>) -> FibreAngles {
    let _e27 = ((wi_in.y * wo_in.z) + -((wi_in.z * wo_in.y)));
    let _e30 = ((wi_in.y * wo_in.y) + (wi_in.z * wo_in.z));
    return FibreAngles(min(max(wi_in.x, -1f), 1f), min(sqrt(((wi_in.y * wi_in.y) + (wi_in.z * wi_in.z))), 1f), min(max(wo_in.x, -1f), 1f), min(sqrt(((wo_in.y * wo_in.y) + (wo_in.z * wo_in.z))), 1f), atan2(_e27, select(1f, _e30, (0f < (abs(_e27) + abs(_e30))))));
}

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

// hairmath::models::frostbite::tt_gaussian -- Tafuri 2019, slide 19
fn tt_gaussian(phi: f32, a: f32, b: f32) -> f32 {
    let _e6 = (abs(phi) - PI);
    return (a * exp((-(b) * (_e6 * _e6))));
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
fn fibre_path(h: f32, cos_theta_o: f32, inv_eta: f32, inv_cos_theta_t: f32, cos_theta_t: f32, eta: f32) -> FibrePath {
    let _e9 = min(max(h, -(1f)), 1f);
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

// hair_bcsdf: `hairmath eval --model frostbite`, Tafuri 2019 (Frostbite): Karis' R, TT from per-slice Gaussians in a 2D table attenuated at h = 0, TRT Karis' scaled by the roughness factor s_r and attenuated at h = sqrt(3)/2, S(wi, wo)
// (hairmath::registry::MODELS; Bcsdf::eval in the local frame, tangent +X, no cosine factor)
fn hair_bcsdf(wi: vec3<f32>, wo: vec3<f32>) -> vec3<f32> {
    let _e23 = fibre_angles(wi, wo);
    let sum_of_sines = (_e23.sin_theta_i + _e23.sin_theta_o);
    let abs_theta_o = abs(atan2(_e23.sin_theta_o, _e23.cos_theta_o));
    let cos_phi = cos(_e23.phi);
    let cos_half_phi = max(cos((0.5f * _e23.phi)), 0f);
    let v_dot_l = (((wi.x * wo.x) + (wi.y * wo.y)) + (wi.z * wo.z));
    let _e42 = gaussian_lobe(uniforms.width_r, (sum_of_sines - uniforms.shift_r));
    let _e51 = fresnel_schlick(sqrt(min(max((0.5f + (0.5f * v_dot_l)), 0f), 1f)), uniforms.eta);
    let r_lobe = (_e42 * ((0.25f * cos_half_phi) * _e51));
    let _e55 = gaussian_lobe(uniforms.width_tt, (sum_of_sines - uniforms.shift_tt));
    let _e56 = lut0_frostbite_tt(abs_theta_o, uniforms.beta_n);
    let _e59 = tt_gaussian(_e23.phi, _e56.x, _e56.y);
    let tt_lobe = (_e55 * _e59);
    let inv_eta = (1f / uniforms.eta);
    let _e62 = (_e23.sin_theta_o * inv_eta);
    let cos_theta_t = sqrt(max(((-(_e62) * _e62) + 1f), 0f));
    let inv_cos_theta_t = (1f / cos_theta_t);
    let _e70 = fibre_path(TT_OFFSET, _e23.cos_theta_o, inv_eta, inv_cos_theta_t, cos_theta_t, uniforms.eta);
    let _e73 = -(uniforms.sigma_a.x);
    let _e76 = attenuations(_e70.fresnel, exp((_e73 * _e70.segment_length)));
    let _e78 = -(uniforms.sigma_a.y);
    let _e81 = attenuations(_e70.fresnel, exp((_e78 * _e70.segment_length)));
    let _e83 = -(uniforms.sigma_a.z);
    let _e86 = attenuations(_e70.fresnel, exp((_e83 * _e70.segment_length)));
    let _e92 = gaussian_lobe(uniforms.width_trt, (sum_of_sines - uniforms.shift_trt));
    let trt_lobe = (_e92 * (uniforms.trt_scale * exp((uniforms.trt_scale * ((KARIS_D_TRT[0] * cos_phi) + KARIS_D_TRT[1])))));
    let _e104 = fibre_path(TRT_OFFSET, _e23.cos_theta_o, inv_eta, inv_cos_theta_t, cos_theta_t, uniforms.eta);
    let _e109 = attenuations(_e104.fresnel, exp((_e73 * _e104.segment_length)));
    let _e113 = attenuations(_e104.fresnel, exp((_e78 * _e104.segment_length)));
    let _e117 = attenuations(_e104.fresnel, exp((_e83 * _e104.segment_length)));
    return ((vec3(r_lobe) + (tt_lobe * vec3<f32>(_e76.tt, _e81.tt, _e86.tt))) + (trt_lobe * vec3<f32>(_e109.trt, _e113.trt, _e117.trt)));
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

