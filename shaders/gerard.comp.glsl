#version 450 core
#extension GL_ARB_compute_shader : require
#extension GL_ARB_shader_storage_buffer_object : require
layout(local_size_x = 64, local_size_y = 1, local_size_z = 1) in;

struct GerardUniforms {
    float g_r;
    float g_tt;
    float g_trt;
    float lobe_scale_r;
    float lobe_scale_tt;
    float lobe_scale_trt;
    float alpha_r;
    float alpha_tt;
    float alpha_trt;
    vec3 sigma_a;
    float k_tt;
    float k_trt;
    float min_cos2_theta_d;
};
struct FibreAngles {
    float sin_theta_i;
    float cos_theta_i;
    float sin_theta_o;
    float cos_theta_o;
    float phi;
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
// phi at the first texel of lut0_gerard
const float LUT0_GERARD_PHI_MIN = 0.0;
// 1 / (3.141592653589793 - 0), phi to [0, 1] across lut0_gerard's texels
const float LUT0_GERARD_PHI_SCALE = 0.31830987;
// theta_d at the first texel of lut0_gerard
const float LUT0_GERARD_THETA_D_MIN = 0.0;
// 1 / (1.5707963267948966 - 0), theta_d to [0, 1] across lut0_gerard's texels
const float LUT0_GERARD_THETA_D_SCALE = 0.63661975;
const GerardUniforms uniforms = GerardUniforms(0.76984614, 0.8167546, 0.69702667, 1.0, 1.0, 1.0, 0.034906585, -0.017453292, -0.05235988, vec3(0.5447, 0.9061, 1.781), 4.0, 5.5, 1e-12);
// 4 pi, the solid angle of the sphere
const float FOUR_PI = 12.566371;
// 1e-30, the floor that keeps a denominator, a length or a width positive
const float TINY = 1e-30;

// lut0_gerard_texels: 128 x 64 texels (phi in [0, 3.141592653589793] along x, theta_d in [0, 1.5707963267948966] along y); x, y, z = N_R, N_TT, N_TRT; rgba32float, read with textureLoad
layout(binding = 2) uniform sampler2D _group_1_binding_0_cs;

layout(std430, binding = 0) readonly buffer type_6_block_0Compute { float _group_0_binding_0_cs[]; };

layout(std430, binding = 1) buffer type_6_block_1Compute { float _group_0_binding_1_cs[]; };


// table 0 (gerard): 2 axes, 3 channels; multilinear interpolation of texels read with textureLoad, in the operation order of hairmath::lut::Table::lookup_into: per axis t = clamp((x - MIN) * SCALE, 0, 1) * (n - 1) over its n texels
vec4 lut0_gerard(float phi, float theta_d) {
    float _e11 = (min(max(((phi - LUT0_GERARD_PHI_MIN) * LUT0_GERARD_PHI_SCALE), 0.0), 1.0) * 127.0);
    float _e14 = min(floor(_e11), 126.0);
    float _e15 = (_e11 - _e14);
    float _e16 = (1.0 - _e15);
    int _e20 = min(max(int(_e14), 0), 126);
    int _e22 = (_e20 + 1);
    float _e30 = (min(max(((theta_d - LUT0_GERARD_THETA_D_MIN) * LUT0_GERARD_THETA_D_SCALE), 0.0), 1.0) * 63.0);
    float _e33 = min(floor(_e30), 62.0);
    float _e34 = (_e30 - _e33);
    float _e35 = (1.0 - _e34);
    int _e38 = min(max(int(_e33), 0), 62);
    int _e39 = (_e38 + 1);
    vec4 _e43 = texelFetch(_group_1_binding_0_cs, ivec2(_e20, _e38), 0);
    vec4 _e47 = texelFetch(_group_1_binding_0_cs, ivec2(_e22, _e38), 0);
    vec4 _e52 = texelFetch(_group_1_binding_0_cs, ivec2(_e20, _e39), 0);
    vec4 _e57 = texelFetch(_group_1_binding_0_cs, ivec2(_e22, _e39), 0);
    return (((((_e16 * _e35) * _e43) + ((_e15 * _e35) * _e47)) + ((_e16 * _e34) * _e52)) + ((_e15 * _e34) * _e57));
}

// hairmath::geometry::fibre_angles -- the local frame of docs/ARCHITECTURE.md: sin theta = w.x, phi in the YZ plane
FibreAngles fibre_angles(vec3 wi_in, vec3 wo_in) {
    float _e27 = ((wi_in.y * wo_in.z) + -((wi_in.z * wo_in.y)));
    float _e30 = ((wi_in.y * wo_in.y) + (wi_in.z * wo_in.z));
    return FibreAngles(min(max(wi_in.x, -1.0), 1.0), min(sqrt(((wi_in.y * wi_in.y) + (wi_in.z * wi_in.z))), 1.0), min(max(wo_in.x, -1.0), 1.0), min(sqrt(((wo_in.y * wo_in.y) + (wo_in.z * wo_in.z))), 1.0), atan(_e27, ((0.0 < (abs(_e27) + abs(_e30))) ? _e30 : 1.0)));
}

// hair_bcsdf: `hairmath eval --model gerard`, Gerard's direct lighting (eq. 4-8): Henyey-Greenstein lobes, Marschner's N_p from a 128 x 64 table times e^(-k sigma_a), S(wi, wo)
// (hairmath::registry::MODELS; Bcsdf::eval in the local frame, tangent +X, no cosine factor)
vec3 hair_bcsdf(vec3 wi, vec3 wo) {
    FibreAngles _e25 = fibre_angles(wi, wo);
    float theta_i = atan(_e25.sin_theta_i, _e25.cos_theta_i);
    float theta_o = atan(_e25.sin_theta_o, _e25.cos_theta_o);
    float theta_h = ((theta_i + theta_o) * 0.5);
    float theta_d = ((theta_o - theta_i) * 0.5);
    float cos_theta_d = cos(theta_d);
    float factor = (_e25.cos_theta_i / max((cos_theta_d * cos_theta_d), uniforms.min_cos2_theta_d));
    vec4 _e44 = lut0_gerard(abs(_e25.phi), abs(theta_d));
    float _e51 = (uniforms.g_r * uniforms.g_r);
    float _e56 = ((1.0 + _e51) - ((2.0 * uniforms.g_r) * cos((theta_h - uniforms.alpha_r))));
    float _e65 = (((((1.0 - _e51) / ((FOUR_PI * _e56) * sqrt(_e56))) * uniforms.lobe_scale_r) * _e44.x) * factor);
    float _e68 = (uniforms.g_tt * uniforms.g_tt);
    float _e72 = ((1.0 + _e68) - ((2.0 * uniforms.g_tt) * cos((theta_h - uniforms.alpha_tt))));
    float _e80 = (((((1.0 - _e68) / ((FOUR_PI * _e72) * sqrt(_e72))) * uniforms.lobe_scale_tt) * _e44.y) * factor);
    float _e83 = (uniforms.g_trt * uniforms.g_trt);
    float _e87 = ((1.0 + _e83) - ((2.0 * uniforms.g_trt) * cos((theta_h - uniforms.alpha_trt))));
    float _e95 = (((((1.0 - _e83) / ((FOUR_PI * _e87) * sqrt(_e87))) * uniforms.lobe_scale_trt) * _e44.z) * factor);
    float _e96 = -(uniforms.k_tt);
    float _e106 = -(uniforms.k_trt);
    return ((vec3(_e65) + (_e80 * exp((_e96 * uniforms.sigma_a)))) + (_e95 * exp((_e106 * uniforms.sigma_a))));
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

