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
struct FarFieldNodePairElement {
    float h;
    float weight;
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
struct FarFieldNodePair {
    vec3 r;
    vec3 tt;
    vec3 trt;
    vec3 residual;
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
const FarFieldNodePairElement FAR_FIELD_OFFSET_PAIRS[32] = FarFieldNodePairElement[32](FarFieldNodePairElement(0.9999994, 1.5289318e-6), FarFieldNodePairElement(0.9999835, 1.872458e-5), FarFieldNodePairElement(0.99990034, 7.211129e-5), FarFieldNodePairElement(0.99965745, 0.00018185156), FarFieldNodePairElement(0.9991224, 0.0003673992), FarFieldNodePairElement(0.99812496, 0.0006472144), FarFieldNodePairElement(0.99645925, 0.0010384569), FarFieldNodePairElement(0.9938865, 0.0015566545), FarFieldNodePairElement(0.9901389, 0.00221535), FarFieldNodePairElement(0.9849239, 0.0030257301), FarFieldNodePairElement(0.9779291, 0.003996244), FarFieldNodePairElement(0.9688285, 0.005132225), FarFieldNodePairElement(0.9572886, 0.006435525), FarFieldNodePairElement(0.94297606, 0.007904187), FarFieldNodePairElement(0.92556554, 0.009532163), FarFieldNodePairElement(0.904748, 0.011309116), FarFieldNodePairElement(0.8802395, 0.013220307), FarFieldNodePairElement(0.85178995, 0.015246595), FarFieldNodePairElement(0.81919193, 0.017364576), FarFieldNodePairElement(0.78228873, 0.019546852), FarFieldNodePairElement(0.74098223, 0.021762462), FarFieldNodePairElement(0.69523925, 0.023977457), FarFieldNodePairElement(0.6450969, 0.02615561), FarFieldNodePairElement(0.5906664, 0.028259275), FarFieldNodePairElement(0.5321349, 0.030250335), FarFieldNodePairElement(0.46976525, 0.032091226), FarFieldNodePairElement(0.4038941, 0.033746015), FarFieldNodePairElement(0.33492747, 0.035181463), FarFieldNodePairElement(0.26333427, 0.036368046), FarFieldNodePairElement(0.18963791, 0.03728089), FarFieldNodePairElement(0.11440627, 0.037900586), FarFieldNodePairElement(0.038240023, 0.03821382));

layout(std430, binding = 0) readonly buffer type_6_block_0Compute { float _group_0_binding_0_cs[]; };

layout(std430, binding = 1) buffer type_6_block_1Compute { float _group_0_binding_1_cs[]; };


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

// hairmath::bcsdf::far_field::OffsetNodes::azimuthal -- Chiang et al. 2016, eq. 8 (N_p averaged over h), by Gauss-Legendre quadrature, the nodes h and -h sharing A_p
FarFieldNodePair far_field_node_pair(vec3 r_in, vec3 tt_in, vec3 trt_in, vec3 residual_in, float h, float weight, float cos_theta_o, float inv_eta, float inv_cos_theta_t, float cos_theta_t, float eta, vec3 sigma_a, float phi, float logistic_inv_scale, float logistic_norm) {
    FibrePath _e27 = fibre_path(h, cos_theta_o, inv_eta, inv_cos_theta_t, cos_theta_t, eta);
    Attenuations _e36 = attenuations(_e27.fresnel, exp((-(sigma_a.x) * _e27.segment_length)));
    Attenuations _e45 = attenuations(_e27.fresnel, exp((-(sigma_a.y) * _e27.segment_length)));
    Attenuations _e54 = attenuations(_e27.fresnel, exp((-(sigma_a.z) * _e27.segment_length)));
    ExitAzimuths _e59 = exit_azimuths(phi, _e27.gamma_o, _e27.gamma_t);
    TrimmedLogistics _e63 = trimmed_logistics(_e59.r, _e59.tt, _e59.trt, logistic_inv_scale, logistic_norm);
    ExitAzimuths _e70 = exit_azimuths(phi, -(_e27.gamma_o), -(_e27.gamma_t));
    TrimmedLogistics _e74 = trimmed_logistics(_e70.r, _e70.tt, _e70.trt, logistic_inv_scale, logistic_norm);
    float _e78 = (_e63.r + _e74.r);
    float _e79 = (_e63.tt + _e74.tt);
    float _e80 = (_e63.trt + _e74.trt);
    float _e81 = (INV_TWO_PI + INV_TWO_PI);
    return FarFieldNodePair((r_in + (weight * (vec3(_e36.r, _e45.r, _e54.r) * _e78))), (tt_in + (weight * (vec3(_e36.tt, _e45.tt, _e54.tt) * _e79))), (trt_in + (weight * (vec3(_e36.trt, _e45.trt, _e54.trt) * _e80))), (residual_in + (weight * (vec3(_e36.residual, _e45.residual, _e54.residual) * _e81))));
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

// hair_bcsdf: `hairmath eval --model chiang-far`, the far field of Chiang et al. 2016: S(wi, wo) averaged over h uniform in [-1, 1], with a fixed Gauss-Legendre rule over h or the adaptive reference
// (hairmath::registry::MODELS; Bcsdf::eval in the local frame, tangent +X, no cosine factor)
vec3 hair_bcsdf(vec3 wi, vec3 wo) {
    vec3 r = vec3(0.0);
    vec3 tt = vec3(0.0);
    vec3 trt = vec3(0.0);
    vec3 residual = vec3(0.0);
    uint k = 0u;
    FibreAngles _e30 = fibre_angles(wi, wo);
    float phi = -(_e30.phi);
    float _e37 = (_e30.sin_theta_o * uniforms.inv_eta);
    float cos_theta_t = sqrt(max(((-(_e37) * _e37) + 1.0), 0.0));
    float inv_cos_theta_t = (1.0 / cos_theta_t);
    r = vec3(0.0);
    tt = vec3(0.0);
    trt = vec3(0.0);
    residual = vec3(0.0);
    bool loop_init = true;
    while(true) {
        if (!loop_init) {
            uint _e72 = k;
            k = (_e72 + 1u);
        }
        loop_init = false;
        uint _e55 = k;
        if ((_e55 < 32u)) {
        } else {
            break;
        }
        uint _e59 = k;
        vec3 _e61 = r;
        vec3 _e62 = tt;
        vec3 _e63 = trt;
        vec3 _e64 = residual;
        FarFieldNodePair _e67 = far_field_node_pair(_e61, _e62, _e63, _e64, FAR_FIELD_OFFSET_PAIRS[_e59].h, FAR_FIELD_OFFSET_PAIRS[_e59].weight, _e30.cos_theta_o, uniforms.inv_eta, inv_cos_theta_t, cos_theta_t, uniforms.eta, uniforms.sigma_a, phi, uniforms.logistic_inv_scale, uniforms.logistic_norm);
        r = _e67.r;
        tt = _e67.tt;
        trt = _e67.trt;
        residual = _e67.residual;
    }
    vec3 _e75 = r;
    vec3 _e76 = tt;
    vec3 _e77 = trt;
    vec3 _e78 = residual;
    float _e91 = -(uniforms.sin_2_alpha);
    float _e100 = deon_lobe(_e30.sin_theta_i, _e30.cos_theta_i, ((_e30.sin_theta_o * uniforms.cos_2_alpha) + (_e30.cos_theta_o * _e91)), abs(((_e30.cos_theta_o * uniforms.cos_2_alpha) + -((_e30.sin_theta_o * _e91)))), uniforms.inv_variance_r, uniforms.lobe_norm_r);
    float _e109 = deon_lobe(_e30.sin_theta_i, _e30.cos_theta_i, ((_e30.sin_theta_o * uniforms.cos_alpha) + (_e30.cos_theta_o * uniforms.sin_alpha)), abs(((_e30.cos_theta_o * uniforms.cos_alpha) + -((_e30.sin_theta_o * uniforms.sin_alpha)))), uniforms.inv_variance_tt, uniforms.lobe_norm_tt);
    float _e118 = deon_lobe(_e30.sin_theta_i, _e30.cos_theta_i, ((_e30.sin_theta_o * uniforms.cos_4_alpha) + (_e30.cos_theta_o * uniforms.sin_4_alpha)), abs(((_e30.cos_theta_o * uniforms.cos_4_alpha) + -((_e30.sin_theta_o * uniforms.sin_4_alpha)))), uniforms.inv_variance_trt, uniforms.lobe_norm_trt);
    float _e119 = deon_lobe(_e30.sin_theta_i, _e30.cos_theta_i, _e30.sin_theta_o, _e30.cos_theta_o, uniforms.inv_variance_trt, uniforms.lobe_norm_trt);
    return ((_e119 * _e78) + ((_e118 * _e77) + ((_e109 * _e76) + (_e100 * _e75))));
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

