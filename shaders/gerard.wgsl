struct GerardUniforms {
    g_r: f32,
    g_tt: f32,
    g_trt: f32,
    lobe_scale_r: f32,
    lobe_scale_tt: f32,
    lobe_scale_trt: f32,
    alpha_r: f32,
    alpha_tt: f32,
    alpha_trt: f32,
    sigma_a: vec3<f32>,
    k_tt: f32,
    k_trt: f32,
    min_cos2_theta_d: f32,
}

struct FibreAngles {
    sin_theta_i: f32,
    cos_theta_i: f32,
    sin_theta_o: f32,
    cos_theta_o: f32,
    phi: f32,
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

// phi at the first texel of lut0_gerard
const LUT0_GERARD_PHI_MIN: f32 = 0f;
// 1 / (3.141592653589793 - 0), phi to [0, 1] across lut0_gerard's texels
const LUT0_GERARD_PHI_SCALE: f32 = 0.31830987f;
// theta_d at the first texel of lut0_gerard
const LUT0_GERARD_THETA_D_MIN: f32 = 0f;
// 1 / (1.5707963267948966 - 0), theta_d to [0, 1] across lut0_gerard's texels
const LUT0_GERARD_THETA_D_SCALE: f32 = 0.63661975f;
const uniforms: GerardUniforms = GerardUniforms(0.76984614f, 0.8167546f, 0.69702667f, 1f, 1f, 1f, 0.034906585f, -0.017453292f, -0.05235988f, vec3<f32>(0.5447f, 0.9061f, 1.781f), 4f, 5.5f, 0.000000000001f);
// 4 pi, the solid angle of the sphere
const FOUR_PI: f32 = 12.566371f;
// 1e-30, the floor that keeps a denominator, a length or a width positive
const TINY: f32 = 0.000000000000000000000000000001f;

// lut0_gerard_texels: 128 x 64 texels (phi in [0, 3.141592653589793] along x, theta_d in [0, 1.5707963267948966] along y); x, y, z = N_R, N_TT, N_TRT; rgba32float, read with textureLoad
@group(1) @binding(0) 
var lut0_gerard_texels: texture_2d<f32>;

// table 0 (gerard): 2 axes, 3 channels; multilinear interpolation of texels read with textureLoad, in the operation order of hairmath::lut::Table::lookup_into: per axis t = clamp((x - MIN) * SCALE, 0, 1) * (n - 1) over its n texels
fn lut0_gerard(phi: f32, theta_d: f32) -> vec4<f32> {
    let _e11 = (min(max(((phi - LUT0_GERARD_PHI_MIN) * LUT0_GERARD_PHI_SCALE), 0f), 1f) * 127f);
    let _e14 = min(floor(_e11), 126f);
    let _e15 = (_e11 - _e14);
    let _e16 = (1f - _e15);
    let _e20 = clamp(i32(_e14), 0i, 126i);
    let _e22 = (_e20 + 1i);
    let _e30 = (min(max(((theta_d - LUT0_GERARD_THETA_D_MIN) * LUT0_GERARD_THETA_D_SCALE), 0f), 1f) * 63f);
    let _e33 = min(floor(_e30), 62f);
    let _e34 = (_e30 - _e33);
    let _e35 = (1f - _e34);
    let _e38 = clamp(i32(_e33), 0i, 62i);
    let _e39 = (_e38 + 1i);
    let _e43 = textureLoad(lut0_gerard_texels, vec2<i32>(_e20, _e38), 0i);
    let _e47 = textureLoad(lut0_gerard_texels, vec2<i32>(_e22, _e38), 0i);
    let _e52 = textureLoad(lut0_gerard_texels, vec2<i32>(_e20, _e39), 0i);
    let _e57 = textureLoad(lut0_gerard_texels, vec2<i32>(_e22, _e39), 0i);
    return (((((_e16 * _e35) * _e43) + ((_e15 * _e35) * _e47)) + ((_e16 * _e34) * _e52)) + ((_e15 * _e34) * _e57));
}

// hairmath::geometry::fibre_angles -- the local frame of docs/ARCHITECTURE.md: sin theta = w.x, phi in the YZ plane
fn fibre_angles(wi_in: vec3<f32>, wo_in: vec3<f32>) -> FibreAngles {
    let _e27 = ((wi_in.y * wo_in.z) + -((wi_in.z * wo_in.y)));
    let _e30 = ((wi_in.y * wo_in.y) + (wi_in.z * wo_in.z));
    return FibreAngles(min(max(wi_in.x, -1f), 1f), min(sqrt(((wi_in.y * wi_in.y) + (wi_in.z * wi_in.z))), 1f), min(max(wo_in.x, -1f), 1f), min(sqrt(((wo_in.y * wo_in.y) + (wo_in.z * wo_in.z))), 1f), atan2(_e27, select(1f, _e30, (0f < (abs(_e27) + abs(_e30))))));
}

// hair_bcsdf: `hairmath eval --model gerard`, Gerard's direct lighting (eq. 4-8): Henyey-Greenstein lobes, Marschner's N_p from a 128 x 64 table times e^(-k sigma_a), S(wi, wo)
// (hairmath::registry::MODELS; Bcsdf::eval in the local frame, tangent +X, no cosine factor)
fn hair_bcsdf(wi: vec3<f32>, wo: vec3<f32>) -> vec3<f32> {
    let _e25 = fibre_angles(wi, wo);
    let theta_i = atan2(_e25.sin_theta_i, _e25.cos_theta_i);
    let theta_o = atan2(_e25.sin_theta_o, _e25.cos_theta_o);
    let theta_h = ((theta_i + theta_o) * 0.5f);
    let theta_d = ((theta_o - theta_i) * 0.5f);
    let cos_theta_d = cos(theta_d);
    let factor = (_e25.cos_theta_i / max((cos_theta_d * cos_theta_d), uniforms.min_cos2_theta_d));
    let _e44 = lut0_gerard(abs(_e25.phi), abs(theta_d));
    let _e51 = (uniforms.g_r * uniforms.g_r);
    let _e56 = ((1f + _e51) - ((2f * uniforms.g_r) * cos((theta_h - uniforms.alpha_r))));
    let _e65 = (((((1f - _e51) / ((FOUR_PI * _e56) * sqrt(_e56))) * uniforms.lobe_scale_r) * _e44.x) * factor);
    let _e68 = (uniforms.g_tt * uniforms.g_tt);
    let _e72 = ((1f + _e68) - ((2f * uniforms.g_tt) * cos((theta_h - uniforms.alpha_tt))));
    let _e80 = (((((1f - _e68) / ((FOUR_PI * _e72) * sqrt(_e72))) * uniforms.lobe_scale_tt) * _e44.y) * factor);
    let _e83 = (uniforms.g_trt * uniforms.g_trt);
    let _e87 = ((1f + _e83) - ((2f * uniforms.g_trt) * cos((theta_h - uniforms.alpha_trt))));
    let _e95 = (((((1f - _e83) / ((FOUR_PI * _e87) * sqrt(_e87))) * uniforms.lobe_scale_trt) * _e44.z) * factor);
    let _e96 = -(uniforms.k_tt);
    let _e106 = -(uniforms.k_trt);
    return ((vec3(_e65) + (_e80 * exp((_e96 * uniforms.sigma_a)))) + (_e95 * exp((_e106 * uniforms.sigma_a))));
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

