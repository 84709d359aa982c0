#version 450 core
#extension GL_ARB_compute_shader : require
#extension GL_ARB_shader_storage_buffer_object : require
layout(local_size_x = 64, local_size_y = 1, local_size_z = 1) in;

struct ChiangUniforms {
    float variance_r;
    float variance_tt;
    float variance_trt;
    float inv_variance_r;
    float inv_variance_tt;
    float inv_variance_trt;
    float lobe_norm_r;
    float lobe_norm_tt;
    float lobe_norm_trt;
    float logistic_scale;
    float logistic_inv_scale;
    float logistic_mass;
    float logistic_norm;
    float sin_alpha;
    float cos_alpha;
    float sin_2_alpha;
    float cos_2_alpha;
    float sin_4_alpha;
    float cos_4_alpha;
    float eta;
    float inv_eta;
    vec3 sigma_a;
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
struct ExitAzimuths {
    float r;
    float tt;
    float trt;
};
struct TrimmedLogistics {
    float r;
    float tt;
    float trt;
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
const ChiangUniforms uniforms = ChiangUniforms(0.08461118, 0.021152794, 0.3384447, 11.818769, 47.275078, 2.9546924, 11.818769, 47.275078, 2.9627328, 0.117159806, 8.535351, 1.0, 8.535351, 0.034899496, 0.99939084, 0.06975647, 0.9975641, 0.1391731, 0.99026805, 1.55, 0.6451613, vec3(0.5447, 0.9061, 1.781));
// 1e-30, the floor that keeps a denominator, a length or a width positive
const float TINY = 1e-30;
// pi
const float PI = 3.1415927;
// 1 / (2 pi), the uniform density over a full turn
const float INV_TWO_PI = 0.15915494;
// 2 pi
const float TWO_PI = 6.2831855;
// 3.75, where I0 switches from Abramowitz and Stegun 9.8.1 to 9.8.2
const float BESSEL_I0_SWITCH = 3.75;
// 1 / 3.75, the argument scale of Abramowitz and Stegun 9.8.1
const float BESSEL_I0_INV_SWITCH = 0.26666668;
// Abramowitz and Stegun 9.8.1: I0(x) = sum a_k (x/3.75)^(2k), |x| <= 3.75
const float BESSEL_I0_NEAR[7] = float[7](1.0, 3.5156229, 3.0899425, 1.2067492, 0.2659732, 0.0360768, 0.0045813);
// Abramowitz and Stegun 9.8.2: sqrt(x) e^-x I0(x) = sum b_k (3.75/x)^k, x >= 3.75
const float BESSEL_I0_FAR[9] = float[9](0.3989423, 0.01328592, 0.00225319, -0.00157565, 0.00916281, -0.02057706, 0.02635537, -0.01647633, 0.00392377);

layout(std430, binding = 0) readonly buffer type_5_block_0Compute { float _group_0_binding_0_cs[]; };

layout(std430, binding = 1) buffer type_5_block_1Compute { float _group_0_binding_1_cs[]; };


// hairmath::geometry::fibre_angles -- the local frame of docs/ARCHITECTURE.md: sin theta = w.x, phi in the YZ plane
FibreAngles fibre_angles(vec3 wi_in, vec3 wo_in) {
    float _e27 = ((wi_in.y * wo_in.z) + -((wi_in.z * wo_in.y)));
    float _e30 = ((wi_in.y * wo_in.y) + (wi_in.z * wo_in.z));
    return FibreAngles(min(max(wi_in.x, -1.0), 1.0), min(sqrt(((wi_in.y * wi_in.y) + (wi_in.z * wi_in.z))), 1.0), min(max(wo_in.x, -1.0), 1.0), min(sqrt(((wo_in.y * wo_in.y) + (wo_in.z * wo_in.z))), 1.0), atan(_e27, ((0.0 < (abs(_e27) + abs(_e30))) ? _e30 : 1.0)));
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
FibrePath fibre_path(float h_in, float cos_theta_o, float inv_eta, float inv_cos_theta_t, float cos_theta_t, float eta) {
    float _e9 = min(max(h_in, -(1.0)), 1.0);
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

// hairmath::azimuthal::exit_angle::exit_azimuths -- Marschner et al. 2003, eq. 3: phi - Phi(p) for p = 0, 1, 2, wrapped into [-pi, pi]
ExitAzimuths exit_azimuths(float phi, float gamma_i, float gamma_t) {
    float _e5 = ((2.0 * gamma_i) + phi);
    float _e8 = ((2.0 * gamma_t) + PI);
    float _e9 = (_e5 - _e8);
    float _e12 = ((-2.0 * _e8) + _e5);
    float _e19 = -(TWO_PI);
    return ExitAzimuths(((floor(((_e5 * INV_TWO_PI) + 0.5)) * _e19) + _e5), ((floor(((_e9 * INV_TWO_PI) + 0.5)) * _e19) + _e9), ((floor(((_e12 * INV_TWO_PI) + 0.5)) * _e19) + _e12));
}

// hairmath::bcsdf::chiang::trimmed_logistics -- Chiang et al. 2016, eq. 13
TrimmedLogistics trimmed_logistics(float dphi_r, float dphi_tt, float dphi_trt, float logistic_inv_scale, float logistic_norm) {
    float _e8 = exp((-(abs(dphi_r)) * logistic_inv_scale));
    float _e10 = (1.0 + _e8);
    float _e17 = exp((-(abs(dphi_tt)) * logistic_inv_scale));
    float _e18 = (1.0 + _e17);
    float _e25 = exp((-(abs(dphi_trt)) * logistic_inv_scale));
    float _e26 = (1.0 + _e25);
    return TrimmedLogistics(((_e8 * logistic_norm) / (_e10 * _e10)), ((_e17 * logistic_norm) / (_e18 * _e18)), ((_e25 * logistic_norm) / (_e26 * _e26)));
}

// hairmath::lobe::deon::deon_lobe -- d'Eon et al. 2011, eq. 7
float deon_lobe(float sin_i, float cos_i, float sin_o, float cos_o, float inv_variance_r, float lobe_norm_r) {
    float _e7 = (cos_i * cos_o);
    float _e10 = ((-(sin_i) * sin_o) + _e7);
    float _e13 = ((sin_i * cos_o) + (cos_i * sin_o));
    float _e14 = abs(_e10);
    float _e23 = max((_e7 * inv_variance_r), 0.0);
    bool _e24 = (_e23 < BESSEL_I0_SWITCH);
    float _e27 = (min(_e23, BESSEL_I0_SWITCH) * BESSEL_I0_INV_SWITCH);
    float _e28 = (_e27 * _e27);
    float _e56 = (1.0 / max(_e23, BESSEL_I0_SWITCH));
    float _e57 = (BESSEL_I0_SWITCH * _e56);
    return ((lobe_norm_r * (_e24 ? ((((((((((((BESSEL_I0_NEAR[6] * _e28) + BESSEL_I0_NEAR[5]) * _e28) + BESSEL_I0_NEAR[4]) * _e28) + BESSEL_I0_NEAR[3]) * _e28) + BESSEL_I0_NEAR[2]) * _e28) + BESSEL_I0_NEAR[1]) * _e28) + BESSEL_I0_NEAR[0]) : (((((((((((((((((BESSEL_I0_FAR[8] * _e57) + BESSEL_I0_FAR[7]) * _e57) + BESSEL_I0_FAR[6]) * _e57) + BESSEL_I0_FAR[5]) * _e57) + BESSEL_I0_FAR[4]) * _e57) + BESSEL_I0_FAR[3]) * _e57) + BESSEL_I0_FAR[2]) * _e57) + BESSEL_I0_FAR[1]) * _e57) + BESSEL_I0_FAR[0]) * sqrt(_e56)))) * exp(((-((((_e13 * _e13) / (1.0 + _e14)) + (_e14 - _e10))) * inv_variance_r) + (_e24 ? -(_e23) : 0.0))));
}

// hair_bcsdf: `hairmath eval --model chiang`, Chiang et al. 2016 (pbrt-v4 HairBxDF): the near-field reference, S(wi, wo, h)
// (hairmath::registry::MODELS; Bcsdf::eval in the local frame, tangent +X, no cosine factor)
vec3 hair_bcsdf(vec3 wi, vec3 wo, float h) {
    FibreAngles _e30 = fibre_angles(wi, wo);
    float phi = -(_e30.phi);
    float _e37 = (_e30.sin_theta_o * uniforms.inv_eta);
    float cos_theta_t = sqrt(max(((-(_e37) * _e37) + 1.0), 0.0));
    float inv_cos_theta_t = (1.0 / cos_theta_t);
    FibrePath _e46 = fibre_path(h, _e30.cos_theta_o, uniforms.inv_eta, inv_cos_theta_t, cos_theta_t, uniforms.eta);
    Attenuations _e54 = attenuations(_e46.fresnel, exp((-(uniforms.sigma_a.x) * _e46.segment_length)));
    Attenuations _e62 = attenuations(_e46.fresnel, exp((-(uniforms.sigma_a.y) * _e46.segment_length)));
    Attenuations _e70 = attenuations(_e46.fresnel, exp((-(uniforms.sigma_a.z) * _e46.segment_length)));
    ExitAzimuths _e75 = exit_azimuths(phi, _e46.gamma_o, _e46.gamma_t);
    TrimmedLogistics _e79 = trimmed_logistics(_e75.r, _e75.tt, _e75.trt, uniforms.logistic_inv_scale, uniforms.logistic_norm);
    float _e84 = -(uniforms.sin_2_alpha);
    float _e93 = deon_lobe(_e30.sin_theta_i, _e30.cos_theta_i, ((_e30.sin_theta_o * uniforms.cos_2_alpha) + (_e30.cos_theta_o * _e84)), abs(((_e30.cos_theta_o * uniforms.cos_2_alpha) + -((_e30.sin_theta_o * _e84)))), uniforms.inv_variance_r, uniforms.lobe_norm_r);
    float _e102 = deon_lobe(_e30.sin_theta_i, _e30.cos_theta_i, ((_e30.sin_theta_o * uniforms.cos_alpha) + (_e30.cos_theta_o * uniforms.sin_alpha)), abs(((_e30.cos_theta_o * uniforms.cos_alpha) + -((_e30.sin_theta_o * uniforms.sin_alpha)))), uniforms.inv_variance_tt, uniforms.lobe_norm_tt);
    float _e111 = deon_lobe(_e30.sin_theta_i, _e30.cos_theta_i, ((_e30.sin_theta_o * uniforms.cos_4_alpha) + (_e30.cos_theta_o * uniforms.sin_4_alpha)), abs(((_e30.cos_theta_o * uniforms.cos_4_alpha) + -((_e30.sin_theta_o * uniforms.sin_4_alpha)))), uniforms.inv_variance_trt, uniforms.lobe_norm_trt);
    float _e112 = deon_lobe(_e30.sin_theta_i, _e30.cos_theta_i, _e30.sin_theta_o, _e30.cos_theta_o, uniforms.inv_variance_trt, uniforms.lobe_norm_trt);
    float _e113 = (_e93 * _e79.r);
    float _e114 = (_e102 * _e79.tt);
    float _e115 = (_e111 * _e79.trt);
    float _e116 = (_e112 * INV_TWO_PI);
    return ((_e116 * vec3(_e54.residual, _e62.residual, _e70.residual)) + ((_e115 * vec3(_e54.trt, _e62.trt, _e70.trt)) + ((_e114 * vec3(_e54.tt, _e62.tt, _e70.tt)) + (_e113 * vec3(_e54.r, _e62.r, _e70.r)))));
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
vec3 hair_bcsdf_world(vec3 tangent, vec3 wi, vec3 wo, float h) {
    FibreLocalDirections _e4 = fibre_local_directions(tangent, wi, wo);
    vec3 _e7 = hair_bcsdf(_e4.wi, _e4.wo, h);
    return _e7;
}

void main() {
    uvec3 id = gl_GlobalInvocationID;
    uint row = (id.x + ((id.y * 65535u) * 64u));
    if ((row >= (uint(_group_0_binding_1_cs.length()) / 3u))) {
        return;
    }
    uint first = (row * 7u);
    float _e19 = _group_0_binding_0_cs[(first + 0u)];
    float _e23 = _group_0_binding_0_cs[(first + 1u)];
    float _e27 = _group_0_binding_0_cs[(first + 2u)];
    float _e31 = _group_0_binding_0_cs[(first + 3u)];
    float _e35 = _group_0_binding_0_cs[(first + 4u)];
    float _e39 = _group_0_binding_0_cs[(first + 5u)];
    float _e44 = _group_0_binding_0_cs[(first + 6u)];
    vec3 _e45 = hair_bcsdf(vec3(_e19, _e23, _e27), vec3(_e31, _e35, _e39), _e44);
    uint _e46 = (row * 3u);
    _group_0_binding_1_cs[(_e46 + 0u)] = _e45.x;
    _group_0_binding_1_cs[(_e46 + 1u)] = _e45.y;
    _group_0_binding_1_cs[(_e46 + 2u)] = _e45.z;
}

