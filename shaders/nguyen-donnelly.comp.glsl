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


// table 0 (nguyen-m): 2 axes, 4 channels; multilinear interpolation of texels read with textureLoad, in the operation order of hairmath::lut::Table::lookup_into
vec4 lut0_nguyen_m(float sin_theta_i, float sin_theta_o) {
    float _e11 = (min(max(((sin_theta_i - -1.0) * 0.5), 0.0), 1.0) * 127.0);
    float _e14 = min(floor(_e11), 126.0);
    float _e15 = (_e11 - _e14);
    float _e16 = (1.0 - _e15);
    int _e20 = min(max(int(_e14), 0), 126);
    int _e22 = (_e20 + 1);
    float _e27 = (min(max(((sin_theta_o - -1.0) * 0.5), 0.0), 1.0) * 127.0);
    float _e29 = min(floor(_e27), 126.0);
    float _e30 = (_e27 - _e29);
    float _e31 = (1.0 - _e30);
    int _e33 = min(max(int(_e29), 0), 126);
    int _e34 = (_e33 + 1);
    vec4 _e40 = texelFetch(_group_1_binding_0_cs, ivec2(_e20, _e33), 0);
    vec4 _e46 = texelFetch(_group_1_binding_0_cs, ivec2(_e22, _e33), 0);
    vec4 _e52 = texelFetch(_group_1_binding_0_cs, ivec2(_e20, _e34), 0);
    vec4 _e58 = texelFetch(_group_1_binding_0_cs, ivec2(_e22, _e34), 0);
    return ((((vec4(0.0) + (((1.0 * _e16) * _e31) * _e40)) + (((1.0 * _e15) * _e31) * _e46)) + (((1.0 * _e16) * _e30) * _e52)) + (((1.0 * _e15) * _e30) * _e58));
}

// table 1 (nguyen-n): 2 axes, 7 channels; multilinear interpolation of texels read with textureLoad, in the operation order of hairmath::lut::Table::lookup_into
vec4[2] lut1_nguyen_n(float cos_phi, float cos_theta_d) {
    float _e11 = (min(max(((cos_phi - -1.0) * 0.5), 0.0), 1.0) * 127.0);
    float _e14 = min(floor(_e11), 126.0);
    float _e15 = (_e11 - _e14);
    float _e16 = (1.0 - _e15);
    int _e20 = min(max(int(_e14), 0), 126);
    int _e22 = (_e20 + 1);
    float _e27 = (min(max(((cos_theta_d - 0.0) * 1.0), 0.0), 1.0) * 127.0);
    float _e29 = min(floor(_e27), 126.0);
    float _e30 = (_e27 - _e29);
    float _e31 = (1.0 - _e30);
    int _e33 = min(max(int(_e29), 0), 126);
    int _e34 = (_e33 + 1);
    float _e40 = ((1.0 * _e16) * _e31);
    ivec2 _e41 = ivec2(_e20, _e33);
    vec4 _e42 = texelFetch(_group_1_binding_1_cs, _e41, 0);
    vec4 _e45 = texelFetch(_group_1_binding_2_cs, _e41, 0);
    float _e49 = ((1.0 * _e15) * _e31);
    ivec2 _e50 = ivec2(_e22, _e33);
    vec4 _e51 = texelFetch(_group_1_binding_1_cs, _e50, 0);
    vec4 _e54 = texelFetch(_group_1_binding_2_cs, _e50, 0);
    float _e58 = ((1.0 * _e16) * _e30);
    ivec2 _e59 = ivec2(_e20, _e34);
    vec4 _e60 = texelFetch(_group_1_binding_1_cs, _e59, 0);
    vec4 _e63 = texelFetch(_group_1_binding_2_cs, _e59, 0);
    float _e67 = ((1.0 * _e15) * _e30);
    ivec2 _e68 = ivec2(_e22, _e34);
    vec4 _e69 = texelFetch(_group_1_binding_1_cs, _e68, 0);
    vec4 _e72 = texelFetch(_group_1_binding_2_cs, _e68, 0);
    return vec4[2](((((vec4(0.0) + (_e40 * _e42)) + (_e49 * _e51)) + (_e58 * _e60)) + (_e67 * _e69)), ((((vec4(0.0) + (_e40 * _e45)) + (_e49 * _e54)) + (_e58 * _e63)) + (_e67 * _e72)));
}

// hair_bcsdf: `hairmath eval --model nguyen-donnelly`, Nguyen and Donnelly 2005 (GPU Gems 2 ch. 23): Marschner 2003 through 128 x 128 M and N lookup textures baked from the inputs, S(wi, wo)
// (hairmath::registry::MODELS; Bcsdf::eval in the local frame, tangent +X, no cosine factor)
vec3 hair_bcsdf(vec3 wi, vec3 wo) {
    float _e14 = min(max(wi.x, -1.0), 1.0);
    float _e17 = ((wi.y * wi.y) + (wi.z * wi.z));
    float _e19 = min(sqrt(_e17), 1.0);
    float _e21 = min(max(wo.x, -1.0), 1.0);
    float _e24 = ((wo.y * wo.y) + (wo.z * wo.z));
    vec4 _e27 = lut0_nguyen_m(_e14, _e21);
    float _e38 = sqrt(max((((1.0 + (_e19 * min(sqrt(_e24), 1.0))) + (_e14 * _e21)) * 0.5), 0.0));
    float _e42 = (_e17 * _e24);
    bool _e43 = (0.0 < _e42);
    vec4 _e50[2] = lut1_nguyen_n(min(max((_e43 ? (((wi.y * wo.y) + (wi.z * wo.z)) / sqrt((_e43 ? _e42 : 1.0))) : 1.0), -1.0), 1.0), _e38);
    float _e67 = (_e19 / max((_e38 * _e38), uniforms.min_cos2_theta_d));
    float _e69 = (_e27.y * _e67);
    float _e70 = (_e27.z * _e67);
    float _e71 = ((_e27.x * _e67) * _e50[0].w);
    return vec3(((_e71 + (_e69 * _e50[0].x)) + (_e70 * _e50[1].x)), ((_e71 + (_e69 * _e50[0].y)) + (_e70 * _e50[1].y)), ((_e71 + (_e69 * _e50[0].z)) + (_e70 * _e50[1].z)));
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
    return FibreFrame(vec3(_e14, _e15, _e16), vec3((1.0 + (((_e20 * _e14) * _e14) * _e22)), (_e20 * _e24), (-(_e20) * _e14)), vec3(_e24, (_e20 + ((_e15 * _e15) * _e22)), -(_e15)));
}

// fibre_local_directions: hairmath::geometry::local_directions -- wi and wo in the fibre's frame
FibreLocalDirections fibre_local_directions(vec3 tangent, vec3 wi, vec3 wo) {
    FibreFrame _e12 = fibre_frame(tangent);
    return FibreLocalDirections(vec3((((wi.x * _e12.tangent.x) + (wi.y * _e12.tangent.y)) + (wi.z * _e12.tangent.z)), (((wi.x * _e12.normal.x) + (wi.y * _e12.normal.y)) + (wi.z * _e12.normal.z)), (((wi.x * _e12.binormal.x) + (wi.y * _e12.binormal.y)) + (wi.z * _e12.binormal.z))), vec3((((wo.x * _e12.tangent.x) + (wo.y * _e12.tangent.y)) + (wo.z * _e12.tangent.z)), (((wo.x * _e12.normal.x) + (wo.y * _e12.normal.y)) + (wo.z * _e12.normal.z)), (((wo.x * _e12.binormal.x) + (wo.y * _e12.binormal.y)) + (wo.z * _e12.binormal.z))));
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

