#version 450 core
#extension GL_ARB_compute_shader : require
#extension GL_ARB_shader_storage_buffer_object : require
layout(local_size_x = 64, local_size_y = 1, local_size_z = 1) in;

struct NguyenDonnellyUniforms {
    float min_cos2_theta_d;
};
struct FibreFrame {
    vec3 tangent;
    vec3 normal;
    vec3 binormal;
};
struct FibreLocalDirections {
    vec3 wi;
    vec3 wo;
};
// sin_theta_i at the first texel of lut0_nguyen_m
const float LUT0_NGUYEN_M_SIN_THETA_I_MIN = -1.0;
// 1 / (1 - -1), sin_theta_i to [0, 1] across lut0_nguyen_m's texels
const float LUT0_NGUYEN_M_SIN_THETA_I_SCALE = 0.5;
// sin_theta_o at the first texel of lut0_nguyen_m
const float LUT0_NGUYEN_M_SIN_THETA_O_MIN = -1.0;
// 1 / (1 - -1), sin_theta_o to [0, 1] across lut0_nguyen_m's texels
const float LUT0_NGUYEN_M_SIN_THETA_O_SCALE = 0.5;
// cos_phi at the first texel of lut1_nguyen_n
const float LUT1_NGUYEN_N_COS_PHI_MIN = -1.0;
// 1 / (1 - -1), cos_phi to [0, 1] across lut1_nguyen_n's texels
const float LUT1_NGUYEN_N_COS_PHI_SCALE = 0.5;
// cos_theta_d at the first texel of lut1_nguyen_n
const float LUT1_NGUYEN_N_COS_THETA_D_MIN = 0.0;
// 1 / (1 - 0), cos_theta_d to [0, 1] across lut1_nguyen_n's texels
const float LUT1_NGUYEN_N_COS_THETA_D_SCALE = 1.0;
const NguyenDonnellyUniforms uniforms = NguyenDonnellyUniforms(1e-12);
// 1e-30, the floor that keeps a denominator, a length or a width positive
const float TINY = 1e-30;

// lut0_nguyen_m_texels: 128 x 128 texels (sin_theta_i in [-1, 1] along x, sin_theta_o in [-1, 1] along y); x, y, z, w = M_R, M_TT, M_TRT, cos_theta_d; rgba32float, read with textureLoad
layout(binding = 2) uniform sampler2D _group_1_binding_0_cs;

// lut1_nguyen_n_texels_a: 128 x 128 texels (cos_phi in [-1, 1] along x, cos_theta_d in [0, 1] along y); x, y, z, w = N_TT_r, N_TT_g, N_TT_b, N_R; rgba32float, read with textureLoad
layout(binding = 3) uniform sampler2D _group_1_binding_1_cs;

// lut1_nguyen_n_texels_b: 128 x 128 texels (cos_phi in [-1, 1] along x, cos_theta_d in [0, 1] along y); x, y, z = N_TRT_r, N_TRT_g, N_TRT_b; rgba32float, read with textureLoad
layout(binding = 4) uniform sampler2D _group_1_binding_2_cs;

layout(std430, binding = 0) readonly buffer type_7_block_0Compute { float _group_0_binding_0_cs[]; };

layout(std430, binding = 1) buffer type_7_block_1Compute { float _group_0_binding_1_cs[]; };


// table 0 (nguyen-m): 2 axes, 4 channels; multilinear interpolation of texels read with textureLoad, in the operation order of hairmath::lut::Table::lookup_into: per axis t = clamp((x - MIN) * SCALE, 0, 1) * (n - 1) over its n texels
vec4 lut0_nguyen_m(float sin_theta_i, float sin_theta_o) {
    float _e11 = (min(max(((sin_theta_i - LUT0_NGUYEN_M_SIN_THETA_I_MIN) * LUT0_NGUYEN_M_SIN_THETA_I_SCALE), 0.0), 1.0) * 127.0);
    float _e14 = min(floor(_e11), 126.0);
    float _e15 = (_e11 - _e14);
    float _e16 = (1.0 - _e15);
    int _e20 = min(max(int(_e14), 0), 126);
    int _e22 = (_e20 + 1);
    float _e29 = (min(max(((sin_theta_o - LUT0_NGUYEN_M_SIN_THETA_O_MIN) * LUT0_NGUYEN_M_SIN_THETA_O_SCALE), 0.0), 1.0) * 127.0);
    float _e31 = min(floor(_e29), 126.0);
    float _e32 = (_e29 - _e31);
    float _e33 = (1.0 - _e32);
    int _e35 = min(max(int(_e31), 0), 126);
    int _e36 = (_e35 + 1);
    vec4 _e40 = texelFetch(_group_1_binding_0_cs, ivec2(_e20, _e35), 0);
    vec4 _e44 = texelFetch(_group_1_binding_0_cs, ivec2(_e22, _e35), 0);
    vec4 _e49 = texelFetch(_group_1_binding_0_cs, ivec2(_e20, _e36), 0);
    vec4 _e54 = texelFetch(_group_1_binding_0_cs, ivec2(_e22, _e36), 0);
    return (((((_e16 * _e33) * _e40) + ((_e15 * _e33) * _e44)) + ((_e16 * _e32) * _e49)) + ((_e15 * _e32) * _e54));
}

// table 1 (nguyen-n): 2 axes, 7 channels; multilinear interpolation of texels read with textureLoad, in the operation order of hairmath::lut::Table::lookup_into: per axis t = clamp((x - MIN) * SCALE, 0, 1) * (n - 1) over its n texels
vec4[2] lut1_nguyen_n(float cos_phi, float cos_theta_d) {
    float _e11 = (min(max(((cos_phi - LUT1_NGUYEN_N_COS_PHI_MIN) * LUT1_NGUYEN_N_COS_PHI_SCALE), 0.0), 1.0) * 127.0);
    float _e14 = min(floor(_e11), 126.0);
    float _e15 = (_e11 - _e14);
    float _e16 = (1.0 - _e15);
    int _e20 = min(max(int(_e14), 0), 126);
    int _e22 = (_e20 + 1);
    float _e29 = (min(max(((cos_theta_d - LUT1_NGUYEN_N_COS_THETA_D_MIN) * LUT1_NGUYEN_N_COS_THETA_D_SCALE), 0.0), 1.0) * 127.0);
    float _e31 = min(floor(_e29), 126.0);
    float _e32 = (_e29 - _e31);
    float _e33 = (1.0 - _e32);
    int _e35 = min(max(int(_e31), 0), 126);
    int _e36 = (_e35 + 1);
    float _e39 = (_e16 * _e33);
    ivec2 _e40 = ivec2(_e20, _e35);
    vec4 _e41 = texelFetch(_group_1_binding_1_cs, _e40, 0);
    vec4 _e43 = texelFetch(_group_1_binding_2_cs, _e40, 0);
    float _e45 = (_e15 * _e33);
    ivec2 _e46 = ivec2(_e22, _e35);
    vec4 _e47 = texelFetch(_group_1_binding_1_cs, _e46, 0);
    vec4 _e50 = texelFetch(_group_1_binding_2_cs, _e46, 0);
    float _e53 = (_e16 * _e32);
    ivec2 _e54 = ivec2(_e20, _e36);
    vec4 _e55 = texelFetch(_group_1_binding_1_cs, _e54, 0);
    vec4 _e58 = texelFetch(_group_1_binding_2_cs, _e54, 0);
    float _e61 = (_e15 * _e32);
    ivec2 _e62 = ivec2(_e22, _e36);
    vec4 _e63 = texelFetch(_group_1_binding_1_cs, _e62, 0);
    vec4 _e66 = texelFetch(_group_1_binding_2_cs, _e62, 0);
    return vec4[2](((((_e39 * _e41) + (_e45 * _e47)) + (_e53 * _e55)) + (_e61 * _e63)), ((((_e39 * _e43) + (_e45 * _e50)) + (_e53 * _e58)) + (_e61 * _e66)));
}

// hair_bcsdf: `hairmath eval --model nguyen-donnelly`, Nguyen and Donnelly 2005 (GPU Gems 2 ch. 23): Marschner 2003 through 128 x 128 M and N lookup textures baked from the inputs, S(wi, wo)
// (hairmath::registry::MODELS; Bcsdf::eval in the local frame, tangent +X, no cosine factor)
vec3 hair_bcsdf(vec3 wi, vec3 wo) {
    float sin_theta_i = min(max(wi.x, -1.0), 1.0);
    float _e17 = ((wi.y * wi.y) + (wi.z * wi.z));
    float cos_theta_i = min(sqrt(_e17), 1.0);
    float sin_theta_o = min(max(wo.x, -1.0), 1.0);
    float _e24 = ((wo.y * wo.y) + (wo.z * wo.z));
    float cos_theta_o = min(sqrt(_e24), 1.0);
    vec4 _e27 = lut0_nguyen_m(sin_theta_i, sin_theta_o);
    float cos_theta_d = sqrt(max((((1.0 + (cos_theta_i * cos_theta_o)) + (sin_theta_i * sin_theta_o)) * 0.5), 0.0));
    float _e42 = (_e17 * _e24);
    bool _e43 = (0.0 < _e42);
    float cos_phi = min(max((_e43 ? (((wi.y * wo.y) + (wi.z * wo.z)) / sqrt((_e43 ? _e42 : 1.0))) : 1.0), -1.0), 1.0);
    vec4 _e50[2] = lut1_nguyen_n(cos_phi, cos_theta_d);
    float factor = (cos_theta_i / max((cos_theta_d * cos_theta_d), uniforms.min_cos2_theta_d));
    float _e64 = (_e27.y * factor);
    float _e65 = (_e27.z * factor);
    float _e66 = ((_e27.x * factor) * _e50[0].w);
    return ((vec3(_e66) + (_e64 * _e50[0].xyz)) + (_e65 * _e50[1].xyz));
}

// hairmath::geometry::fibre_frame -- Duff et al. 2017, listing 3
FibreFrame fibre_frame(vec3 tangent_in) {
    float _e13 = (1.0 / max(sqrt((((tangent_in.x * tangent_in.x) + (tangent_in.y * tangent_in.y)) + (tangent_in.z * tangent_in.z))), TINY));
    float _e14 = (tangent_in.x * _e13);
    float _e15 = (tangent_in.y * _e13);
    float _e16 = (tangent_in.z * _e13);
    float _e19 = -(1.0);
    float _e20 = ((_e16 < 0.0) ? _e19 : 1.0);
    float _e22 = (_e19 / (_e20 + _e16));
    float _e24 = ((_e14 * _e15) * _e22);
    return FibreFrame((tangent_in * _e13), vec3((1.0 + (((_e20 * _e14) * _e14) * _e22)), (_e20 * _e24), (-(_e20) * _e14)), vec3(_e24, (_e20 + ((_e15 * _e15) * _e22)), -(_e15)));
}

// fibre_local_directions: hairmath::geometry::local_directions -- wi and wo in the fibre's frame
FibreLocalDirections fibre_local_directions(vec3 tangent, vec3 wi, vec3 wo) {
    FibreFrame _e12 = fibre_frame(tangent);
    return FibreLocalDirections((((wi.x * vec3(_e12.tangent.x, _e12.normal.x, _e12.binormal.x)) + (wi.y * vec3(_e12.tangent.y, _e12.normal.y, _e12.binormal.y))) + (wi.z * vec3(_e12.tangent.z, _e12.normal.z, _e12.binormal.z))), (((wo.x * vec3(_e12.tangent.x, _e12.normal.x, _e12.binormal.x)) + (wo.y * vec3(_e12.tangent.y, _e12.normal.y, _e12.binormal.y))) + (wo.z * vec3(_e12.tangent.z, _e12.normal.z, _e12.binormal.z))));
}

// hair_bcsdf_world: hair_bcsdf of world-space directions, made local to the fibre by fibre_local_directions
vec3 hair_bcsdf_world(vec3 tangent, vec3 wi, vec3 wo) {
    FibreLocalDirections _e3 = fibre_local_directions(tangent, wi, wo);
    vec3 _e6 = hair_bcsdf(_e3.wi, _e3.wo);
    return _e6;
}

void main() {
    uvec3 id = gl_GlobalInvocationID;
    uint row = (id.x + ((id.y * 65535u) * 64u));
    if ((row >= (uint(_group_0_binding_1_cs.length()) / 3u))) {
        return;
    }
    uint first = (row * 6u);
    float _e19 = _group_0_binding_0_cs[(first + 0u)];
    float _e23 = _group_0_binding_0_cs[(first + 1u)];
    float _e27 = _group_0_binding_0_cs[(first + 2u)];
    float _e31 = _group_0_binding_0_cs[(first + 3u)];
    float _e35 = _group_0_binding_0_cs[(first + 4u)];
    float _e39 = _group_0_binding_0_cs[(first + 5u)];
    vec3 _e41 = hair_bcsdf(vec3(_e19, _e23, _e27), vec3(_e31, _e35, _e39));
    uint _e42 = (row * 3u);
    _group_0_binding_1_cs[(_e42 + 0u)] = _e41.x;
    _group_0_binding_1_cs[(_e42 + 1u)] = _e41.y;
    _group_0_binding_1_cs[(_e42 + 2u)] = _e41.z;
}

