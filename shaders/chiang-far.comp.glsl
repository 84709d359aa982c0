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
struct FarFieldNodeElement {
    float h;
    float weight;
};
const ChiangUniforms uniforms = ChiangUniforms(0.08461118, 0.021152794, 0.3384447, 11.818769, 47.275078, 2.9546924, 11.818769, 47.275078, 2.9627328, 0.117159806, 8.535351, 1.0, 8.535351, 0.034899496, 0.99939084, 0.06975647, 0.9975641, 0.1391731, 0.99026805, 1.55, 0.6451613, vec3(0.5447, 0.9061, 1.781));
const FarFieldNodeElement FAR_FIELD_OFFSETS[64] = FarFieldNodeElement[64](FarFieldNodeElement(0.9999994, 1.5289318e-6), FarFieldNodeElement(0.9999835, 1.872458e-5), FarFieldNodeElement(0.99990034, 7.211129e-5), FarFieldNodeElement(0.99965745, 0.00018185156), FarFieldNodeElement(0.9991224, 0.0003673992), FarFieldNodeElement(0.99812496, 0.0006472144), FarFieldNodeElement(0.99645925, 0.0010384569), FarFieldNodeElement(0.9938865, 0.0015566545), FarFieldNodeElement(0.9901389, 0.00221535), FarFieldNodeElement(0.9849239, 0.0030257301), FarFieldNodeElement(0.9779291, 0.003996244), FarFieldNodeElement(0.9688285, 0.005132225), FarFieldNodeElement(0.9572886, 0.006435525), FarFieldNodeElement(0.94297606, 0.007904187), FarFieldNodeElement(0.92556554, 0.009532163), FarFieldNodeElement(0.904748, 0.011309116), FarFieldNodeElement(0.8802395, 0.013220307), FarFieldNodeElement(0.85178995, 0.015246595), FarFieldNodeElement(0.81919193, 0.017364576), FarFieldNodeElement(0.78228873, 0.019546852), FarFieldNodeElement(0.74098223, 0.021762462), FarFieldNodeElement(0.69523925, 0.023977457), FarFieldNodeElement(0.6450969, 0.02615561), FarFieldNodeElement(0.5906664, 0.028259275), FarFieldNodeElement(0.5321349, 0.030250335), FarFieldNodeElement(0.46976525, 0.032091226), FarFieldNodeElement(0.4038941, 0.033746015), FarFieldNodeElement(0.33492747, 0.035181463), FarFieldNodeElement(0.26333427, 0.036368046), FarFieldNodeElement(0.18963791, 0.03728089), FarFieldNodeElement(0.11440627, 0.037900586), FarFieldNodeElement(0.038240023, 0.03821382), FarFieldNodeElement(-0.038240023, 0.03821382), FarFieldNodeElement(-0.11440627, 0.037900586), FarFieldNodeElement(-0.18963791, 0.03728089), FarFieldNodeElement(-0.26333427, 0.036368046), FarFieldNodeElement(-0.33492747, 0.035181463), FarFieldNodeElement(-0.4038941, 0.033746015), FarFieldNodeElement(-0.46976525, 0.032091226), FarFieldNodeElement(-0.5321349, 0.030250335), FarFieldNodeElement(-0.5906664, 0.028259275), FarFieldNodeElement(-0.6450969, 0.02615561), FarFieldNodeElement(-0.69523925, 0.023977457), FarFieldNodeElement(-0.74098223, 0.021762462), FarFieldNodeElement(-0.78228873, 0.019546852), FarFieldNodeElement(-0.81919193, 0.017364576), FarFieldNodeElement(-0.85178995, 0.015246595), FarFieldNodeElement(-0.8802395, 0.013220307), FarFieldNodeElement(-0.904748, 0.011309116), FarFieldNodeElement(-0.92556554, 0.009532163), FarFieldNodeElement(-0.94297606, 0.007904187), FarFieldNodeElement(-0.9572886, 0.006435525), FarFieldNodeElement(-0.9688285, 0.005132225), FarFieldNodeElement(-0.9779291, 0.003996244), FarFieldNodeElement(-0.9849239, 0.0030257301), FarFieldNodeElement(-0.9901389, 0.00221535), FarFieldNodeElement(-0.9938865, 0.0015566545), FarFieldNodeElement(-0.99645925, 0.0010384569), FarFieldNodeElement(-0.99812496, 0.0006472144), FarFieldNodeElement(-0.9991224, 0.0003673992), FarFieldNodeElement(-0.99965745, 0.00018185156), FarFieldNodeElement(-0.99990034, 7.211129e-5), FarFieldNodeElement(-0.9999835, 1.872458e-5), FarFieldNodeElement(-0.9999994, 1.5289318e-6));

layout(std430, binding = 0) readonly buffer type_10_block_0Compute { float _group_0_binding_0_cs[]; };

layout(std430, binding = 1) buffer type_10_block_1Compute { float _group_0_binding_1_cs[]; };


// hairmath::geometry::fibre_angles -- the local frame of DESIGN.md: sin theta = w.x, phi in the YZ plane
float[5] fibre_angles(vec3 wi_in, vec3 wo_in) {
    float _e38 = (((1.0 * ((wi_in.y * wo_in.z) - (wi_in.z * wo_in.y))) + (0.0 * ((wi_in.z * 0.0) - (0.0 * wo_in.z)))) + (0.0 * ((0.0 * wo_in.y) - (wi_in.y * 0.0))));
    float _e43 = (((0.0 * 0.0) + (wi_in.y * wo_in.y)) + (wi_in.z * wo_in.z));
    return float[5](min(max(wi_in.x, -1.0), 1.0), min(sqrt(((wi_in.y * wi_in.y) + (wi_in.z * wi_in.z))), 1.0), min(max(wo_in.x, -1.0), 1.0), min(sqrt(((wo_in.y * wo_in.y) + (wo_in.z * wo_in.z))), 1.0), atan(_e38, ((0.0 < (abs(_e38) + abs(_e43))) ? _e43 : 1.0)));
}

// hairmath::fresnel::fresnel -- Born and Wolf, section 1.5 (unpolarised dielectric reflectance)
float fresnel(float cos_i, float eta, float inv_eta) {
    float _e11 = sqrt(max((1.0 - ((1.0 - (cos_i * cos_i)) * (inv_eta * inv_eta))), 0.0));
    float _e12 = (eta * cos_i);
    float _e13 = (_e12 - _e11);
    float _e14 = (_e12 + _e11);
    float _e15 = (eta * _e11);
    float _e16 = (cos_i - _e15);
    float _e17 = (cos_i + _e15);
    float _e18 = (_e14 * _e14);
    float _e19 = (_e17 * _e17);
    return min(((((_e13 * _e13) * _e19) + ((_e16 * _e16) * _e18)) / ((2.0 * _e18) * _e19)), 1.0);
}

// hairmath::azimuthal::path::fibre_path -- Chiang et al. 2016, sections 4.1 and 4.3 (Snell and Bravais; the chord 2 cos gamma_t / cos theta_t)
float[4] fibre_path(float h, float c2_, float inv_eta_1, float c3_, float eta_1) {
    float _e8 = min(max(h, -(1.0)), 1.0);
    float _e11 = (((_e8 * c2_) * inv_eta_1) * c3_);
    float _e16 = sqrt(max((1.0 - (_e11 * _e11)), 0.0));
    float _e20 = sqrt(max((1.0 - (_e8 * _e8)), 0.0));
    float _e22 = fresnel((c2_ * _e20), eta_1, inv_eta_1);
    return float[4](atan(_e8, _e20), atan(_e11, _e16), ((2.0 * _e16) * c3_), _e22);
}

// hairmath::azimuthal::attenuation::attenuations -- Chiang et al. 2016, eqs. 3 and 6
float[4] attenuations(float fresnel_in, float transmittance) {
    float _e3 = (1.0 - fresnel_in);
    float _e5 = ((_e3 * _e3) * transmittance);
    float _e7 = ((_e5 * fresnel_in) * transmittance);
    return float[4](fresnel_in, _e5, _e7, (((_e7 * fresnel_in) * transmittance) / max((1.0 - (fresnel_in * transmittance)), 1e-30)));
}

// hairmath::azimuthal::exit_angle::exit_angle -- Marschner et al. 2003, eq. 3
float exit_angle(float p, float gamma_i, float gamma_t) {
    return ((((2.0 * p) * gamma_t) - (2.0 * gamma_i)) + (p * 3.1415927));
}

// hairmath::bcsdf::chiang::trimmed_logistics -- Chiang et al. 2016, eq. 13
float[3] trimmed_logistics(float dphi_r, float dphi_tt, float dphi_trt, float logistic_inv_scale, float logistic_norm) {
    float _e8 = exp((-(abs(dphi_r)) * logistic_inv_scale));
    float _e10 = (1.0 + _e8);
    float _e11 = (_e10 * _e10);
    float _e15 = exp((-(abs(dphi_tt)) * logistic_inv_scale));
    float _e16 = (1.0 + _e15);
    float _e17 = (_e16 * _e16);
    float _e21 = exp((-(abs(dphi_trt)) * logistic_inv_scale));
    float _e22 = (1.0 + _e21);
    float _e23 = (_e22 * _e22);
    float _e27 = (logistic_norm / (((1.0 * _e11) * _e17) * _e23));
    float _e31 = (_e27 * _e11);
    return float[3]((_e8 * ((_e27 * _e17) * _e23)), (_e15 * (_e31 * _e23)), (_e21 * (_e31 * _e17)));
}

// hairmath::bcsdf::far_field::OffsetNodes::azimuthal -- Chiang et al. 2016, eq. 8 (N_p averaged over h), by Gauss-Legendre quadrature
float[12] far_field_node(float r_red_in, float r_green_in, float r_blue_in, float tt_red_in, float tt_green_in, float tt_blue_in, float trt_red_in, float trt_green_in, float trt_blue_in, float residual_red_in, float residual_green_in, float residual_blue_in, float h_1, float weight, float c0_, float inv_eta_2, float c2_1, float eta_2, float sigma_a_x, float sigma_a_y, float sigma_a_z, float c7_, float logistic_inv_scale_1, float logistic_norm_1) {
    float _e24 = (c0_ * inv_eta_2);
    float _e32[4] = fibre_path(h_1, c2_1, inv_eta_2, (1.0 / sqrt(max((1.0 - (_e24 * _e24)), 0.0))), eta_2);
    float _e40[4] = attenuations(_e32[3], exp((-(sigma_a_x) * _e32[2])));
    float _e48[4] = attenuations(_e32[3], exp((-(sigma_a_y) * _e32[2])));
    float _e56[4] = attenuations(_e32[3], exp((-(sigma_a_z) * _e32[2])));
    float _e61 = exit_angle(0.0, _e32[0], _e32[1]);
    float _e62 = (c7_ - _e61);
    float _e71 = exit_angle(1.0, _e32[0], _e32[1]);
    float _e72 = (c7_ - _e71);
    float _e79 = exit_angle(2.0, _e32[0], _e32[1]);
    float _e80 = (c7_ - _e79);
    float _e86[3] = trimmed_logistics((_e62 - (6.2831855 * floor(((_e62 + 3.1415927) * 0.15915494)))), (_e72 - (6.2831855 * floor(((_e72 + 3.1415927) * 0.15915494)))), (_e80 - (6.2831855 * floor(((_e80 + 3.1415927) * 0.15915494)))), logistic_inv_scale_1, logistic_norm_1);
    return float[12]((r_red_in + (weight * (_e40[0] * _e86[0]))), (r_green_in + (weight * (_e48[0] * _e86[0]))), (r_blue_in + (weight * (_e56[0] * _e86[0]))), (tt_red_in + (weight * (_e40[1] * _e86[1]))), (tt_green_in + (weight * (_e48[1] * _e86[1]))), (tt_blue_in + (weight * (_e56[1] * _e86[1]))), (trt_red_in + (weight * (_e40[2] * _e86[2]))), (trt_green_in + (weight * (_e48[2] * _e86[2]))), (trt_blue_in + (weight * (_e56[2] * _e86[2]))), (residual_red_in + (weight * (_e40[3] * 0.15915494))), (residual_green_in + (weight * (_e48[3] * 0.15915494))), (residual_blue_in + (weight * (_e56[3] * 0.15915494))));
}

// hairmath::lobe::deon::deon_lobe -- d'Eon et al. 2011, eq. 7
float deon_lobe(float sin_i, float cos_i_1, float sin_o, float cos_o, float inv_variance_r, float lobe_norm_r) {
    float _e7 = (cos_i_1 * cos_o);
    float _e9 = (_e7 - (sin_i * sin_o));
    float _e12 = ((sin_i * cos_o) + (cos_i_1 * sin_o));
    float _e22 = max((_e7 * inv_variance_r), 0.0);
    float _e27 = (min(_e22, 3.75) * 0.26666668);
    float _e28 = (_e27 * _e27);
    float _e47 = (1.0 / max(_e22, 3.75));
    float _e48 = (3.75 * _e47);
    bool _e76 = (_e22 < 3.75);
    return ((lobe_norm_r * (_e76 ? ((((((((((((0.0045813 * _e28) + 0.0360768) * _e28) + 0.2659732) * _e28) + 1.2067492) * _e28) + 3.0899425) * _e28) + 3.5156229) * _e28) + 1.0) : (((((((((((((((((0.00392377 * _e48) + -0.01647633) * _e48) + 0.02635537) * _e48) + -0.02057706) * _e48) + 0.00916281) * _e48) + -0.00157565) * _e48) + 0.00225319) * _e48) + 0.01328592) * _e48) + 0.3989423) * sqrt(_e47)))) * exp(((_e76 ? -(_e22) : 0.0) - (((0.0 < _e9) ? ((_e12 * _e12) / (1.0 + max(_e9, 0.0))) : (1.0 - _e9)) * inv_variance_r))));
}

// hair_bcsdf: `hairmath eval --model chiang-far`, the far field of Chiang et al. 2016: S(wi, wo) averaged over h uniform in [-1, 1], with a fixed Gauss-Legendre rule over h or the adaptive reference
// (hairmath::registry::MODELS; Bcsdf::eval in the local frame, tangent +X, no cosine factor)
vec3 hair_bcsdf(vec3 wi, vec3 wo) {
    float r_red = 0.0;
    float r_green = 0.0;
    float r_blue = 0.0;
    float tt_red = 0.0;
    float tt_green = 0.0;
    float tt_blue = 0.0;
    float trt_red = 0.0;
    float trt_green = 0.0;
    float trt_blue = 0.0;
    float residual_red = 0.0;
    float residual_green = 0.0;
    float residual_blue = 0.0;
    uint k = 0u;
    float _e50[5] = fibre_angles(wi, wo);
    r_red = 0.0;
    r_green = 0.0;
    r_blue = 0.0;
    tt_red = 0.0;
    tt_green = 0.0;
    tt_blue = 0.0;
    trt_red = 0.0;
    trt_green = 0.0;
    trt_blue = 0.0;
    residual_red = 0.0;
    residual_green = 0.0;
    residual_blue = 0.0;
    bool loop_init = true;
    while(true) {
        if (!loop_init) {
            uint _e104 = k;
            k = (_e104 + 1u);
        }
        loop_init = false;
        uint _e71 = k;
        if ((_e71 < 64u)) {
        } else {
            break;
        }
        uint _e75 = k;
        float _e77 = r_red;
        float _e78 = r_green;
        float _e79 = r_blue;
        float _e80 = tt_red;
        float _e81 = tt_green;
        float _e82 = tt_blue;
        float _e83 = trt_red;
        float _e84 = trt_green;
        float _e85 = trt_blue;
        float _e86 = residual_red;
        float _e87 = residual_green;
        float _e88 = residual_blue;
        float _e91[12] = far_field_node(_e77, _e78, _e79, _e80, _e81, _e82, _e83, _e84, _e85, _e86, _e87, _e88, FAR_FIELD_OFFSETS[_e75].h, FAR_FIELD_OFFSETS[_e75].weight, _e50[2], uniforms.inv_eta, _e50[3], uniforms.eta, uniforms.sigma_a.x, uniforms.sigma_a.y, uniforms.sigma_a.z, -(_e50[4]), uniforms.logistic_inv_scale, uniforms.logistic_norm);
        r_red = _e91[0];
        r_green = _e91[1];
        r_blue = _e91[2];
        tt_red = _e91[3];
        tt_green = _e91[4];
        tt_blue = _e91[5];
        trt_red = _e91[6];
        trt_green = _e91[7];
        trt_blue = _e91[8];
        residual_red = _e91[9];
        residual_green = _e91[10];
        residual_blue = _e91[11];
    }
    float _e107 = r_red;
    float _e108 = r_green;
    float _e109 = r_blue;
    float _e110 = tt_red;
    float _e111 = tt_green;
    float _e112 = tt_blue;
    float _e113 = trt_red;
    float _e114 = trt_green;
    float _e115 = trt_blue;
    float _e116 = residual_red;
    float _e117 = residual_green;
    float _e118 = residual_blue;
    float _e119 = -(uniforms.sin_2_alpha);
    float _e127 = deon_lobe(_e50[0], _e50[1], ((_e50[2] * uniforms.cos_2_alpha) + (_e50[3] * _e119)), abs(((_e50[3] * uniforms.cos_2_alpha) - (_e50[2] * _e119))), uniforms.inv_variance_r, uniforms.lobe_norm_r);
    float _e135 = deon_lobe(_e50[0], _e50[1], ((_e50[2] * uniforms.cos_alpha) + (_e50[3] * uniforms.sin_alpha)), abs(((_e50[3] * uniforms.cos_alpha) - (_e50[2] * uniforms.sin_alpha))), uniforms.inv_variance_tt, uniforms.lobe_norm_tt);
    float _e143 = deon_lobe(_e50[0], _e50[1], ((_e50[2] * uniforms.cos_4_alpha) + (_e50[3] * uniforms.sin_4_alpha)), abs(((_e50[3] * uniforms.cos_4_alpha) - (_e50[2] * uniforms.sin_4_alpha))), uniforms.inv_variance_trt, uniforms.lobe_norm_trt);
    float _e144 = deon_lobe(_e50[0], _e50[1], _e50[2], _e50[3], uniforms.inv_variance_trt, uniforms.lobe_norm_trt);
    return vec3(((((0.0 + (_e127 * _e107)) + (_e135 * _e110)) + (_e143 * _e113)) + (_e144 * _e116)), ((((0.0 + (_e127 * _e108)) + (_e135 * _e111)) + (_e143 * _e114)) + (_e144 * _e117)), ((((0.0 + (_e127 * _e109)) + (_e135 * _e112)) + (_e143 * _e115)) + (_e144 * _e118)));
}

// hairmath::geometry::fibre_frame -- Duff et al. 2017, listing 3
float[9] fibre_frame(vec3 tangent_in) {
    float _e13 = (1.0 / max(sqrt((((tangent_in.x * tangent_in.x) + (tangent_in.y * tangent_in.y)) + (tangent_in.z * tangent_in.z))), 1e-30));
    float _e14 = (tangent_in.x * _e13);
    float _e15 = (tangent_in.y * _e13);
    float _e16 = (tangent_in.z * _e13);
    float _e19 = -(1.0);
    float _e20 = ((_e16 < 0.0) ? _e19 : 1.0);
    float _e22 = (_e19 / (_e20 + _e16));
    float _e24 = ((_e14 * _e15) * _e22);
    return float[9](_e14, _e15, _e16, (1.0 + (((_e20 * _e14) * _e14) * _e22)), (_e20 * _e24), (-(_e20) * _e14), _e24, (_e20 + ((_e15 * _e15) * _e22)), -(_e15));
}

// fibre_local_directions: hairmath::geometry::local_directions -- wi and wo in the fibre's frame
float[6] fibre_local_directions(vec3 tangent, vec3 wi, vec3 wo) {
    float _e12[9] = fibre_frame(tangent);
    return float[6]((((wi.x * _e12[0]) + (wi.y * _e12[1])) + (wi.z * _e12[2])), (((wi.x * _e12[3]) + (wi.y * _e12[4])) + (wi.z * _e12[5])), (((wi.x * _e12[6]) + (wi.y * _e12[7])) + (wi.z * _e12[8])), (((wo.x * _e12[0]) + (wo.y * _e12[1])) + (wo.z * _e12[2])), (((wo.x * _e12[3]) + (wo.y * _e12[4])) + (wo.z * _e12[5])), (((wo.x * _e12[6]) + (wo.y * _e12[7])) + (wo.z * _e12[8])));
}

// hair_bcsdf_world: hair_bcsdf of world-space directions, made local to the fibre by fibre_local_directions
vec3 hair_bcsdf_world(vec3 tangent, vec3 wi, vec3 wo) {
    float _e3[6] = fibre_local_directions(tangent, wi, wo);
    vec3 _e12 = hair_bcsdf(vec3(_e3[0], _e3[1], _e3[2]), vec3(_e3[3], _e3[4], _e3[5]));
    return _e12;
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

