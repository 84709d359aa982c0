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

const uniforms: FrostbiteUniforms = FrostbiteUniforms(0.27830222f, 0.13915111f, 0.55660444f, 0.06979899f, -0.03490481f, -0.10467191f, 1.55f, vec3<f32>(0.5447f, 0.9061f, 1.781f), 0.3f, 1f);
// sqrt(2 pi), the normalisation of the Gaussian
const SQRT_TWO_PI: f32 = 2.5066283f;
// pi
const PI: f32 = 3.1415927f;
// 1e-30, the floor that keeps a denominator, a length or a width positive
const TINY: f32 = 0.000000000000000000000000000001f;

// lut0_frostbite_tt_texels: 9 x 10 texels (theta_o in [0, 1.3962634] along x, beta_n in [0.1, 1] along y); x, y = a, b; rgba32float, read with textureLoad
@group(1) @binding(0) 
var lut0_frostbite_tt_texels: texture_2d<f32>;

// table 0 (frostbite_tt): 2 axes, 2 channels; multilinear interpolation of texels read with textureLoad, in the operation order of hairmath::lut::Table::lookup_into
fn lut0_frostbite_tt(theta_o: f32, beta_n: f32) -> vec4<f32> {
    let _e10 = (min(max(((theta_o - 0f) * 0.71619725f), 0f), 1f) * 8f);
    let _e13 = min(floor(_e10), 7f);
    let _e14 = (_e10 - _e13);
    let _e15 = (1f - _e14);
    let _e19 = clamp(i32(_e13), 0i, 7i);
    let _e21 = (_e19 + 1i);
    let _e29 = (min(max(((beta_n - 0.1f) * 1.1111112f), 0f), 1f) * 9f);
    let _e31 = min(floor(_e29), 8f);
    let _e32 = (_e29 - _e31);
    let _e33 = (1f - _e32);
    let _e36 = clamp(i32(_e31), 0i, 8i);
    let _e37 = (_e36 + 1i);
    let _e43 = textureLoad(lut0_frostbite_tt_texels, vec2<i32>(_e19, _e36), 0i);
    let _e49 = textureLoad(lut0_frostbite_tt_texels, vec2<i32>(_e21, _e36), 0i);
    let _e55 = textureLoad(lut0_frostbite_tt_texels, vec2<i32>(_e19, _e37), 0i);
    let _e61 = textureLoad(lut0_frostbite_tt_texels, vec2<i32>(_e21, _e37), 0i);
    return ((((vec4(0f) + (((1f * _e15) * _e33) * _e43)) + (((1f * _e14) * _e33) * _e49)) + (((1f * _e15) * _e32) * _e55)) + (((1f * _e14) * _e32) * _e61));
}

// hairmath::geometry::fibre_angles -- the local frame of DESIGN.md: sin theta = w.x, phi in the YZ plane
fn fibre_angles(wi_in: vec3<f32>, wo_in: vec3<f32>) -> FibreAngles {
    let _e38 = (((1f * ((wi_in.y * wo_in.z) - (wi_in.z * wo_in.y))) + (0f * ((wi_in.z * 0f) - (0f * wo_in.z)))) + (0f * ((0f * wo_in.y) - (wi_in.y * 0f))));
    let _e43 = (((0f * 0f) + (wi_in.y * wo_in.y)) + (wi_in.z * wo_in.z));
    return FibreAngles(min(max(wi_in.x, -1f), 1f), min(sqrt(((wi_in.y * wi_in.y) + (wi_in.z * wi_in.z))), 1f), min(max(wo_in.x, -1f), 1f), min(sqrt(((wo_in.y * wo_in.y) + (wo_in.z * wo_in.z))), 1f), atan2(_e38, select(1f, _e43, (0f < (abs(_e38) + abs(_e43))))));
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

// hairmath::fresnel::fresnel -- Born and Wolf, section 1.5 (unpolarised dielectric reflectance)
fn fresnel(cos_i_1: f32, eta_1: f32, inv_eta: f32) -> f32 {
    let _e11 = sqrt(max((1f - ((1f - (cos_i_1 * cos_i_1)) * (inv_eta * inv_eta))), 0f));
    let _e12 = (eta_1 * cos_i_1);
    let _e13 = (_e12 - _e11);
    let _e14 = (_e12 + _e11);
    let _e15 = (eta_1 * _e11);
    let _e16 = (cos_i_1 - _e15);
    let _e17 = (cos_i_1 + _e15);
    let _e18 = (_e14 * _e14);
    let _e19 = (_e17 * _e17);
    return min(((((_e13 * _e13) * _e19) + ((_e16 * _e16) * _e18)) / ((2f * _e18) * _e19)), 1f);
}

// hairmath::azimuthal::path::fibre_path -- Chiang et al. 2016, sections 4.1 and 4.3 (Snell and Bravais; the chord 2 cos gamma_t / cos theta_t)
fn fibre_path(h: f32, c0_: f32, c1_: f32, c2_: f32, eta_2: f32) -> FibrePath {
    let _e8 = min(max(h, -(1f)), 1f);
    let _e11 = (((_e8 * c0_) * c1_) * c2_);
    let _e16 = sqrt(max((1f - (_e11 * _e11)), 0f));
    let _e20 = sqrt(max((1f - (_e8 * _e8)), 0f));
    let _e22 = fresnel((c0_ * _e20), eta_2, c1_);
    return FibrePath(atan2(_e8, _e20), atan2(_e11, _e16), ((2f * _e16) * c2_), _e22);
}

// hairmath::azimuthal::attenuation::attenuations -- Chiang et al. 2016, eqs. 3 and 6
fn attenuations(fresnel_in: f32, transmittance: f32) -> Attenuations {
    let _e3 = (1f - fresnel_in);
    let _e5 = ((_e3 * _e3) * transmittance);
    let _e7 = ((_e5 * fresnel_in) * transmittance);
    return Attenuations(fresnel_in, _e5, _e7, (((_e7 * fresnel_in) * transmittance) / max((1f - (fresnel_in * transmittance)), TINY)));
}

// hair_bcsdf: `hairmath eval --model frostbite`, Tafuri 2019 (Frostbite): Karis' R, TT from per-slice Gaussians in a 2D table attenuated at h = 0, TRT Karis' scaled by the roughness factor s_r and attenuated at h = sqrt(3)/2, S(wi, wo)
// (hairmath::registry::MODELS; Bcsdf::eval in the local frame, tangent +X, no cosine factor)
fn hair_bcsdf(wi: vec3<f32>, wo: vec3<f32>) -> vec3<f32> {
    let _e23 = fibre_angles(wi, wo);
    let _e28 = (_e23.sin_theta_i + _e23.sin_theta_o);
    let _e42 = gaussian_lobe(uniforms.width_r, (_e28 - uniforms.shift_r));
    let _e51 = fresnel_schlick(sqrt(min(max((0.5f + (0.5f * (((wi.x * wo.x) + (wi.y * wo.y)) + (wi.z * wo.z)))), 0f), 1f)), uniforms.eta);
    let _e53 = (_e42 * ((0.25f * max(cos((0.5f * _e23.phi)), 0f)) * _e51));
    let _e55 = gaussian_lobe(uniforms.width_tt, (_e28 - uniforms.shift_tt));
    let _e56 = lut0_frostbite_tt(abs(atan2(_e23.sin_theta_o, _e23.cos_theta_o)), uniforms.beta_n);
    let _e59 = tt_gaussian(_e23.phi, _e56.x, _e56.y);
    let _e60 = (_e55 * _e59);
    let _e61 = (1f / uniforms.eta);
    let _e62 = (_e23.sin_theta_o * _e61);
    let _e67 = (1f / sqrt(max((1f - (_e62 * _e62)), 0f)));
    let _e68 = fibre_path(0f, _e23.cos_theta_o, _e61, _e67, uniforms.eta);
    let _e71 = -(uniforms.sigma_a.x);
    let _e74 = attenuations(_e68.fresnel, exp((_e71 * _e68.segment_length)));
    let _e76 = -(uniforms.sigma_a.y);
    let _e79 = attenuations(_e68.fresnel, exp((_e76 * _e68.segment_length)));
    let _e81 = -(uniforms.sigma_a.z);
    let _e84 = attenuations(_e68.fresnel, exp((_e81 * _e68.segment_length)));
    let _e90 = gaussian_lobe(uniforms.width_trt, (_e28 - uniforms.shift_trt));
    let _e98 = (_e90 * (uniforms.trt_scale * exp((uniforms.trt_scale * ((17f * cos(_e23.phi)) + -16.78f)))));
    let _e100 = fibre_path(0.8660254f, _e23.cos_theta_o, _e61, _e67, uniforms.eta);
    let _e105 = attenuations(_e100.fresnel, exp((_e71 * _e100.segment_length)));
    let _e109 = attenuations(_e100.fresnel, exp((_e76 * _e100.segment_length)));
    let _e113 = attenuations(_e100.fresnel, exp((_e81 * _e100.segment_length)));
    return vec3<f32>(((_e53 + (_e60 * _e74.tt)) + (_e98 * _e105.trt)), ((_e53 + (_e60 * _e79.tt)) + (_e98 * _e109.trt)), ((_e53 + (_e60 * _e84.tt)) + (_e98 * _e113.trt)));
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

