struct NguyenDonnellyUniforms {
    min_cos2_theta_d: f32,
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

// sin_theta_i at the first texel of lut0_nguyen_m
const LUT0_NGUYEN_M_SIN_THETA_I_MIN: f32 = -1f;
// 1 / (1 - -1), sin_theta_i to [0, 1] across lut0_nguyen_m's texels
const LUT0_NGUYEN_M_SIN_THETA_I_SCALE: f32 = 0.5f;
// sin_theta_o at the first texel of lut0_nguyen_m
const LUT0_NGUYEN_M_SIN_THETA_O_MIN: f32 = -1f;
// 1 / (1 - -1), sin_theta_o to [0, 1] across lut0_nguyen_m's texels
const LUT0_NGUYEN_M_SIN_THETA_O_SCALE: f32 = 0.5f;
// cos_phi at the first texel of lut1_nguyen_n
const LUT1_NGUYEN_N_COS_PHI_MIN: f32 = -1f;
// 1 / (1 - -1), cos_phi to [0, 1] across lut1_nguyen_n's texels
const LUT1_NGUYEN_N_COS_PHI_SCALE: f32 = 0.5f;
// cos_theta_d at the first texel of lut1_nguyen_n
const LUT1_NGUYEN_N_COS_THETA_D_MIN: f32 = 0f;
// 1 / (1 - 0), cos_theta_d to [0, 1] across lut1_nguyen_n's texels
const LUT1_NGUYEN_N_COS_THETA_D_SCALE: f32 = 1f;
const uniforms: NguyenDonnellyUniforms = NguyenDonnellyUniforms(0.000000000001f);
// 1e-30, the floor that keeps a denominator, a length or a width positive
const TINY: f32 = 0.000000000000000000000000000001f;

// lut0_nguyen_m_texels: 128 x 128 texels (sin_theta_i in [-1, 1] along x, sin_theta_o in [-1, 1] along y); x, y, z, w = M_R, M_TT, M_TRT, cos_theta_d; rgba32float, read with textureLoad
@group(1) @binding(0) 
var lut0_nguyen_m_texels: texture_2d<f32>;
// lut1_nguyen_n_texels_a: 128 x 128 texels (cos_phi in [-1, 1] along x, cos_theta_d in [0, 1] along y); x, y, z, w = N_TT_r, N_TT_g, N_TT_b, N_R; rgba32float, read with textureLoad
@group(1) @binding(1) 
var lut1_nguyen_n_texels_a: texture_2d<f32>;
// lut1_nguyen_n_texels_b: 128 x 128 texels (cos_phi in [-1, 1] along x, cos_theta_d in [0, 1] along y); x, y, z = N_TRT_r, N_TRT_g, N_TRT_b; rgba32float, read with textureLoad
@group(1) @binding(2) 
var lut1_nguyen_n_texels_b: texture_2d<f32>;

// table 0 (nguyen-m): 2 axes, 4 channels; multilinear interpolation of texels read with textureLoad, in the operation order of hairmath::lut::Table::lookup_into: per axis t = clamp((x - MIN) * SCALE, 0, 1) * (n - 1) over its n texels
fn lut0_nguyen_m(sin_theta_i: f32, sin_theta_o: f32) -> vec4<f32> {
    let _e11 = (min(max(((sin_theta_i - LUT0_NGUYEN_M_SIN_THETA_I_MIN) * LUT0_NGUYEN_M_SIN_THETA_I_SCALE), 0f), 1f) * 127f);
    let _e14 = min(floor(_e11), 126f);
    let _e15 = (_e11 - _e14);
    let _e16 = (1f - _e15);
    let _e20 = clamp(i32(_e14), 0i, 126i);
    let _e22 = (_e20 + 1i);
    let _e29 = (min(max(((sin_theta_o - LUT0_NGUYEN_M_SIN_THETA_O_MIN) * LUT0_NGUYEN_M_SIN_THETA_O_SCALE), 0f), 1f) * 127f);
    let _e31 = min(floor(_e29), 126f);
    let _e32 = (_e29 - _e31);
    let _e33 = (1f - _e32);
    let _e35 = clamp(i32(_e31), 0i, 126i);
    let _e36 = (_e35 + 1i);
    let _e40 = textureLoad(lut0_nguyen_m_texels, vec2<i32>(_e20, _e35), 0i);
    let _e44 = textureLoad(lut0_nguyen_m_texels, vec2<i32>(_e22, _e35), 0i);
    let _e49 = textureLoad(lut0_nguyen_m_texels, vec2<i32>(_e20, _e36), 0i);
    let _e54 = textureLoad(lut0_nguyen_m_texels, vec2<i32>(_e22, _e36), 0i);
    return (((((_e16 * _e33) * _e40) + ((_e15 * _e33) * _e44)) + ((_e16 * _e32) * _e49)) + ((_e15 * _e32) * _e54));
}

// table 1 (nguyen-n): 2 axes, 7 channels; multilinear interpolation of texels read with textureLoad, in the operation order of hairmath::lut::Table::lookup_into: per axis t = clamp((x - MIN) * SCALE, 0, 1) * (n - 1) over its n texels
fn lut1_nguyen_n(cos_phi: f32, cos_theta_d: f32) -> array<vec4<f32>, 2> {
    let _e11 = (min(max(((cos_phi - LUT1_NGUYEN_N_COS_PHI_MIN) * LUT1_NGUYEN_N_COS_PHI_SCALE), 0f), 1f) * 127f);
    let _e14 = min(floor(_e11), 126f);
    let _e15 = (_e11 - _e14);
    let _e16 = (1f - _e15);
    let _e20 = clamp(i32(_e14), 0i, 126i);
    let _e22 = (_e20 + 1i);
    let _e29 = (min(max(((cos_theta_d - LUT1_NGUYEN_N_COS_THETA_D_MIN) * LUT1_NGUYEN_N_COS_THETA_D_SCALE), 0f), 1f) * 127f);
    let _e31 = min(floor(_e29), 126f);
    let _e32 = (_e29 - _e31);
    let _e33 = (1f - _e32);
    let _e35 = clamp(i32(_e31), 0i, 126i);
    let _e36 = (_e35 + 1i);
    let _e39 = (_e16 * _e33);
    let _e40 = vec2<i32>(_e20, _e35);
    let _e41 = textureLoad(lut1_nguyen_n_texels_a, _e40, 0i);
    let _e43 = textureLoad(lut1_nguyen_n_texels_b, _e40, 0i);
    let _e45 = (_e15 * _e33);
    let _e46 = vec2<i32>(_e22, _e35);
    let _e47 = textureLoad(lut1_nguyen_n_texels_a, _e46, 0i);
    let _e50 = textureLoad(lut1_nguyen_n_texels_b, _e46, 0i);
    let _e53 = (_e16 * _e32);
    let _e54 = vec2<i32>(_e20, _e36);
    let _e55 = textureLoad(lut1_nguyen_n_texels_a, _e54, 0i);
    let _e58 = textureLoad(lut1_nguyen_n_texels_b, _e54, 0i);
    let _e61 = (_e15 * _e32);
    let _e62 = vec2<i32>(_e22, _e36);
    let _e63 = textureLoad(lut1_nguyen_n_texels_a, _e62, 0i);
    let _e66 = textureLoad(lut1_nguyen_n_texels_b, _e62, 0i);
    return array<vec4<f32>, 2>(((((_e39 * _e41) + (_e45 * _e47)) + (_e53 * _e55)) + (_e61 * _e63)), ((((_e39 * _e43) + (_e45 * _e50)) + (_e53 * _e58)) + (_e61 * _e66)));
}

// hair_bcsdf: `hairmath eval --model nguyen-donnelly`, Nguyen and Donnelly 2005 (GPU Gems 2 ch. 23): Marschner 2003 through 128 x 128 M and N lookup textures baked from the inputs, S(wi, wo)
// (hairmath::registry::MODELS; Bcsdf::eval in the local frame, tangent +X, no cosine factor)
fn hair_bcsdf(wi: vec3<f32>, wo: vec3<f32>) -> vec3<f32> {
    let sin_theta_i = min(max(wi.x, -1f), 1f);
    let _e17 = ((wi.y * wi.y) + (wi.z * wi.z));
    let cos_theta_i = min(sqrt(_e17), 1f);
    let sin_theta_o = min(max(wo.x, -1f), 1f);
    let _e24 = ((wo.y * wo.y) + (wo.z * wo.z));
    let cos_theta_o = min(sqrt(_e24), 1f);
    let _e27 = lut0_nguyen_m(sin_theta_i, sin_theta_o);
    let cos_theta_d = sqrt(max((((1f + (cos_theta_i * cos_theta_o)) + (sin_theta_i * sin_theta_o)) * 0.5f), 0f));
    let _e42 = (_e17 * _e24);
    let _e43 = (0f < _e42);
    let cos_phi = min(max(select(1f, (((wi.y * wo.y) + (wi.z * wo.z)) / sqrt(select(1f, _e42, _e43))), _e43), -1f), 1f);
    let _e50 = lut1_nguyen_n(cos_phi, cos_theta_d);
    let factor = (cos_theta_i / max((cos_theta_d * cos_theta_d), uniforms.min_cos2_theta_d));
    let _e64 = (_e27.y * factor);
    let _e65 = (_e27.z * factor);
    let _e66 = ((_e27.x * factor) * _e50[0].w);
    return ((vec3(_e66) + (_e64 * _e50[0].xyz)) + (_e65 * _e50[1].xyz));
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

