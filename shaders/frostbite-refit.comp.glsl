#version 450 core
#extension GL_ARB_compute_shader : require
#extension GL_ARB_shader_storage_buffer_object : require
layout(local_size_x = 64, local_size_y = 1, local_size_z = 1) in;

struct FrostbiteUniforms {
    float width_r;
    float width_tt;
    float width_trt;
    float shift_r;
    float shift_tt;
    float shift_trt;
    float eta;
    vec3 sigma_a;
    float beta_n;
    float trt_scale;
};
struct FibreAngles {
    float sin_theta_i;
    float cos_theta_i;
    float sin_theta_o;
    float cos_theta_o;
    float phi;
};
struct FibrePath {
    float gamma_o;
    float gamma_t;
    float segment_length;
    float fresnel;
};
struct Attenuations {
    float r;
    float tt;
    float trt;
    float residual;
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
// theta_o at the first texel of lut0_frostbite_tt
const float LUT0_FROSTBITE_TT_THETA_O_MIN = 0.0;
// 1 / (1.3962634 - 0), theta_o to [0, 1] across lut0_frostbite_tt's texels
const float LUT0_FROSTBITE_TT_THETA_O_SCALE = 0.71619725;
// beta_n at the first texel of lut0_frostbite_tt
const float LUT0_FROSTBITE_TT_BETA_N_MIN = 0.1;
// 1 / (1 - 0.1), beta_n to [0, 1] across lut0_frostbite_tt's texels
const float LUT0_FROSTBITE_TT_BETA_N_SCALE = 1.1111112;
const FrostbiteUniforms uniforms = FrostbiteUniforms(0.27830222, 0.13915111, 0.55660444, 0.06979899, -0.03490481, -0.10467191, 1.55, vec3(0.5447, 0.9061, 1.781), 0.3, 1.0);
// sqrt(2 pi), the normalisation of the Gaussian
const float SQRT_TWO_PI = 2.5066283;
// pi
const float PI = 3.1415927;
// h_TT whose attenuation is closest to the h-average (hairmath's refit, eta 1.55)
const float REFIT_TT_OFFSET = 0.6002789;
// 1e-30, the floor that keeps a denominator, a length or a width positive
const float TINY = 1e-30;
// a, b of Karis' TRT distribution exp(a cos(phi) + b) (Karis 2016)
const float KARIS_D_TRT[2] = float[2](17.0, -16.78);
// h_TRT whose attenuation is closest to the h-average (hairmath's refit, eta 1.55)
const float REFIT_TRT_OFFSET = 0.71930504;

// lut0_frostbite_tt_texels: 9 x 10 texels (theta_o in [0, 1.3962634] along x, beta_n in [0.1, 1] along y); x, y = a, b; rgba32float, read with textureLoad
layout(binding = 2) uniform sampler2D _group_1_binding_0_cs;

layout(std430, binding = 0) readonly buffer type_7_block_0Compute { float _group_0_binding_0_cs[]; };

layout(std430, binding = 1) buffer type_7_block_1Compute { float _group_0_binding_1_cs[]; };


// table 0 (frostbite_tt): 2 axes, 2 channels; multilinear interpolation of texels read with textureLoad, in the operation order of hairmath::lut::Table::lookup_into: per axis t = clamp((x - MIN) * SCALE, 0, 1) * (n - 1) over its n texels
vec4 lut0_frostbite_tt(float theta_o, float beta_n) {
    float _e11 = (min(max(((theta_o - LUT0_FROSTBITE_TT_THETA_O_MIN) * LUT0_FROSTBITE_TT_THETA_O_SCALE), 0.0), 1.0) * 8.0);
    float _e14 = min(floor(_e11), 7.0);
    float _e15 = (_e11 - _e14);
    float _e16 = (1.0 - _e15);
    int _e20 = min(max(int(_e14), 0), 7);
    int _e22 = (_e20 + 1);
    float _e30 = (min(max(((beta_n - LUT0_FROSTBITE_TT_BETA_N_MIN) * LUT0_FROSTBITE_TT_BETA_N_SCALE), 0.0), 1.0) * 9.0);
    float _e32 = min(floor(_e30), 8.0);
    float _e33 = (_e30 - _e32);
    float _e34 = (1.0 - _e33);
    int _e37 = min(max(int(_e32), 0), 8);
    int _e38 = (_e37 + 1);
    vec4 _e42 = texelFetch(_group_1_binding_0_cs, ivec2(_e20, _e37), 0);
    vec4 _e46 = texelFetch(_group_1_binding_0_cs, ivec2(_e22, _e37), 0);
    vec4 _e51 = texelFetch(_group_1_binding_0_cs, ivec2(_e20, _e38), 0);
    vec4 _e56 = texelFetch(_group_1_binding_0_cs, ivec2(_e22, _e38), 0);
    return (((((_e16 * _e34) * _e42) + ((_e15 * _e34) * _e46)) + ((_e16 * _e33) * _e51)) + ((_e15 * _e33) * _e56));
}

// hairmath::geometry::fibre_angles -- the local frame of docs/ARCHITECTURE.md: sin theta = w.x, phi in the YZ plane
FibreAngles fibre_angles(vec3 wi_in, vec3 wo_in) {
    float _e27 = ((wi_in.y * wo_in.z) + -((wi_in.z * wo_in.y)));
    float _e30 = ((wi_in.y * wo_in.y) + (wi_in.z * wo_in.z));
    return FibreAngles(min(max(wi_in.x, -1.0), 1.0), min(sqrt(((wi_in.y * wi_in.y) + (wi_in.z * wi_in.z))), 1.0), min(max(wo_in.x, -1.0), 1.0), min(sqrt(((wo_in.y * wo_in.y) + (wo_in.z * wo_in.z))), 1.0), atan(_e27, ((0.0 < (abs(_e27) + abs(_e30))) ? _e30 : 1.0)));
}

// hairmath::lobe::gaussian::gaussian_lobe -- Marschner et al. 2003, eq. 6
float gaussian_lobe(float beta, float x) {
    float _e2 = (x / beta);
    return (exp(((-0.5 * _e2) * _e2)) / (beta * SQRT_TWO_PI));
}

// hairmath::fresnel::fresnel_schlick -- Schlick 1994, eq. 24
float fresnel_schlick(float cos_i, float eta) {
    float _e5 = ((eta - 1.0) / (eta + 1.0));
    float _e6 = (_e5 * _e5);
    float _e10 = (1.0 - min(max(cos_i, 0.0), 1.0));
    float _e11 = (_e10 * _e10);
    return (_e6 + ((((1.0 - _e6) * _e11) * _e11) * _e10));
}

// hairmath::models::frostbite::tt_gaussian -- Tafuri 2019, slide 19
float tt_gaussian(float phi, float a, float b) {
    float _e6 = (abs(phi) - PI);
    return (a * exp((-(b) * (_e6 * _e6))));
}

// hairmath::fresnel::fresnel_of_cosines -- Born and Wolf, section 1.5 (unpolarised dielectric reflectance, both cosines given)
float fresnel_of_cosines(float cos_i, float cos_t, float eta) {
    float _e4 = (eta * cos_i);
    float _e5 = (_e4 + -(cos_t));
    float _e6 = (_e4 + cos_t);
    float _e9 = ((-(eta) * cos_t) + cos_i);
    float _e11 = ((eta * cos_t) + cos_i);
    float _e12 = (_e6 * _e6);
    float _e13 = (_e11 * _e11);
    return min(((((_e9 * _e9) * _e12) + ((_e5 * _e5) * _e13)) / ((2.0 * _e12) * _e13)), 1.0);
}

// hairmath::azimuthal::path::fibre_path -- Chiang et al. 2016, sections 4.1 and 4.3 (Snell and Bravais; the chord 2 cos gamma_t / cos theta_t)
FibrePath fibre_path(float h, float cos_theta_o, float inv_eta, float inv_cos_theta_t, float cos_theta_t, float eta) {
    float _e9 = min(max(h, -(1.0)), 1.0);
    float _e12 = (((_e9 * cos_theta_o) * inv_eta) * inv_cos_theta_t);
    float _e18 = sqrt(max(((-(_e12) * _e12) + 1.0), 0.0));
    float _e23 = sqrt(max(((1.0 - _e9) * (1.0 + _e9)), 0.0));
    float _e26 = fresnel_of_cosines((cos_theta_o * _e23), (cos_theta_t * _e18), eta);
    return FibrePath(atan(_e9, _e23), atan(_e12, _e18), ((2.0 * _e18) * inv_cos_theta_t), _e26);
}

// hairmath::azimuthal::attenuation::attenuations -- Chiang et al. 2016, eqs. 3 and 6
Attenuations attenuations(float fresnel, float transmittance) {
    float _e3 = (1.0 - fresnel);
    float _e5 = ((_e3 * _e3) * transmittance);
    float _e6 = (fresnel * transmittance);
    float _e7 = (_e5 * _e6);
    return Attenuations(fresnel, _e5, _e7, ((_e7 * _e6) / max((1.0 - _e6), TINY)));
}

// hair_bcsdf: `hairmath eval --model frostbite-refit`, Frostbite 2019 with hairmath's refitted single offsets of the TT and TRT attenuations (h = 0.600 and 0.719), S(wi, wo)
// (hairmath::registry::MODELS; Bcsdf::eval in the local frame, tangent +X, no cosine factor)
vec3 hair_bcsdf(vec3 wi, vec3 wo) {
    FibreAngles _e23 = fibre_angles(wi, wo);
    float sum_of_sines = (_e23.sin_theta_i + _e23.sin_theta_o);
    float abs_theta_o = abs(atan(_e23.sin_theta_o, _e23.cos_theta_o));
    float cos_phi = cos(_e23.phi);
    float cos_half_phi = max(cos((0.5 * _e23.phi)), 0.0);
    float v_dot_l = (((wi.x * wo.x) + (wi.y * wo.y)) + (wi.z * wo.z));
    float _e42 = gaussian_lobe(uniforms.width_r, (sum_of_sines - uniforms.shift_r));
    float _e51 = fresnel_schlick(sqrt(min(max((0.5 + (0.5 * v_dot_l)), 0.0), 1.0)), uniforms.eta);
    float r_lobe = (_e42 * ((0.25 * cos_half_phi) * _e51));
    float _e55 = gaussian_lobe(uniforms.width_tt, (sum_of_sines - uniforms.shift_tt));
    vec4 _e56 = lut0_frostbite_tt(abs_theta_o, uniforms.beta_n);
    float _e59 = tt_gaussian(_e23.phi, _e56.x, _e56.y);
    float tt_lobe = (_e55 * _e59);
    float inv_eta = (1.0 / uniforms.eta);
    float _e62 = (_e23.sin_theta_o * inv_eta);
    float cos_theta_t = sqrt(max(((-(_e62) * _e62) + 1.0), 0.0));
    float inv_cos_theta_t = (1.0 / cos_theta_t);
    FibrePath _e70 = fibre_path(REFIT_TT_OFFSET, _e23.cos_theta_o, inv_eta, inv_cos_theta_t, cos_theta_t, uniforms.eta);
    float _e73 = -(uniforms.sigma_a.x);
    Attenuations _e76 = attenuations(_e70.fresnel, exp((_e73 * _e70.segment_length)));
    float _e78 = -(uniforms.sigma_a.y);
    Attenuations _e81 = attenuations(_e70.fresnel, exp((_e78 * _e70.segment_length)));
    float _e83 = -(uniforms.sigma_a.z);
    Attenuations _e86 = attenuations(_e70.fresnel, exp((_e83 * _e70.segment_length)));
    float _e92 = gaussian_lobe(uniforms.width_trt, (sum_of_sines - uniforms.shift_trt));
    float trt_lobe = (_e92 * (uniforms.trt_scale * exp((uniforms.trt_scale * ((KARIS_D_TRT[0] * cos_phi) + KARIS_D_TRT[1])))));
    FibrePath _e104 = fibre_path(REFIT_TRT_OFFSET, _e23.cos_theta_o, inv_eta, inv_cos_theta_t, cos_theta_t, uniforms.eta);
    Attenuations _e109 = attenuations(_e104.fresnel, exp((_e73 * _e104.segment_length)));
    Attenuations _e113 = attenuations(_e104.fresnel, exp((_e78 * _e104.segment_length)));
    Attenuations _e117 = attenuations(_e104.fresnel, exp((_e83 * _e104.segment_length)));
    return ((vec3(r_lobe) + (tt_lobe * vec3(_e76.tt, _e81.tt, _e86.tt))) + (trt_lobe * vec3(_e109.trt, _e113.trt, _e117.trt)));
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

