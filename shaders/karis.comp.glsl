#version 450 core
#extension GL_ARB_compute_shader : require
#extension GL_ARB_shader_storage_buffer_object : require
layout(local_size_x = 64, local_size_y = 1, local_size_z = 1) in;

struct KarisUniforms {
    float width_r;
    float width_tt;
    float width_trt;
    vec3 sigma_a;
    vec3 log_color;
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
const KarisUniforms uniforms = KarisUniforms(0.27830222, 0.13915111, 0.55660444, vec3(0.5447, 0.9061, 1.781), vec3(-4.3458734, -5.6051397, -7.8583317));
// 1e-4, the regulariser of UE's cos phi = Lp.Vp rsqrt(|Lp|^2 |Vp|^2 + 1e-4)
const float COS_PHI_EPSILON = 0.0001;
// 1e-30, the floor that keeps a denominator, a length or a width positive
const float TINY = 1e-30;
// sin and cos of -2 Shift, the R lobe's tilt (HairShading)
const float R_TILT_SIN_COS[2] = float[2](-0.06994285, 0.997551);
// sqrt(2)
const float SQRT_TWO = 1.4142135;
// sqrt(2 pi), the normalisation of the Gaussian
const float SQRT_TWO_PI = 2.5066283;
// 1.55, the refractive index of UE's Hair_F
const float ETA = 1.55;
// UE's Shift, the cuticle tilt in radians: the TT lobe's shift (HairShading)
const float SHIFT = 0.035;
// a, b of Karis' cos(theta_d) eta' ~ a + b cos^2(theta_d) (Karis 2016)
const float KARIS_ETA_PRIME[2] = float[2](1.19, 0.36);
// c1, c2 of Karis' TT offset (1 + a (c1 - c2 cos(phi))) cos(phi/2) (HairBsdf.ush)
const float KARIS_H_TT[2] = float[2](0.6, 0.8);
// a, b of Karis' TT distribution exp(a cos(phi) + b) (Karis 2016)
const float KARIS_D_TT[2] = float[2](-3.65, -3.98);
// 4 Shift, the TRT lobe's shift (HairShading)
const float TRT_SHIFT = 0.14;
// a, b of Karis' TRT distribution exp(a cos(phi) + b) (Karis 2016)
const float KARIS_D_TRT[2] = float[2](17.0, -16.78);
// 0.8, the TRT lobe's Tp = BaseColor^(0.8 / cos theta_d) (HairShading)
const float TRT_COLOR_EXPONENT = 0.8;

layout(std430, binding = 0) readonly buffer type_4_block_0Compute { float _group_0_binding_0_cs[]; };

layout(std430, binding = 1) buffer type_4_block_1Compute { float _group_0_binding_1_cs[]; };


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

// hairmath::models::karis::scaled_eta_prime_karis -- Karis 2016 (Bravais' index times cos theta_d)
float scaled_eta_prime_karis(float cos_theta_d, float a, float b) {
    return (a + ((b * cos_theta_d) * cos_theta_d));
}

// hairmath::models::karis::h_tt_karis -- Karis 2016 (h_TT ~ (1 + a (c1 - c2 cos phi)) cos(phi/2))
float h_tt_karis(float a, float cos_phi, float cos_half_phi, float c1_, float c2_) {
    return ((1.0 + (a * (c1_ - (c2_ * cos_phi)))) * cos_half_phi);
}

// hairmath::models::karis::d_karis -- Karis 2016 (D ~ exp(a cos phi + b))
float d_karis(float cos_phi, float a, float b) {
    return exp(((a * cos_phi) + b));
}

// hair_bcsdf: `hairmath eval --model karis`, Karis 2016 as Unreal Engine 4.27's HairShading (R + TT + TRT) with UE's BaseColor (--color, inverted at beta_n = 0.3) and Roughness, S(wi, wo)
// (hairmath::registry::MODELS; Bcsdf::eval in the local frame, tangent +X, no cosine factor)
vec3 hair_bcsdf(vec3 wi, vec3 wo) {
    float _e23 = -(1.0);
    float sin_l = min(max(-(wi.x), _e23), 1.0);
    float sin_v = min(max(-(wo.x), _e23), 1.0);
    float _e32 = min(max(sin_v, -1.0), 1.0);
    float _e39 = min(max(sin_l, -1.0), 1.0);
    float cos_phi = (((wi.y * wo.y) + (wi.z * wo.z)) / sqrt(((((wi.y * wi.y) + (wi.z * wi.z)) * ((wo.y * wo.y) + (wo.z * wo.z))) + COS_PHI_EPSILON)));
    float sum_of_sines = (sin_l + sin_v);
    float cos_theta_d = max(cos((0.5 * abs((atan(_e32, sqrt(max((1.0 - (_e32 * _e32)), 0.0))) - atan(_e39, sqrt(max((1.0 - (_e39 * _e39)), 0.0))))))), TINY);
    float cos_half_phi = sqrt(min(max((0.5 + (0.5 * cos_phi)), 0.0), 1.0));
    float v_dot_l = (((wo.x * wi.x) + (wo.y * wi.y)) + (wo.z * wi.z));
    float _e96 = gaussian_lobe(max((uniforms.width_r * (SQRT_TWO * cos_half_phi)), TINY), (sum_of_sines - ((2.0 * R_TILT_SIN_COS[0]) * (((R_TILT_SIN_COS[1] * cos_half_phi) * sqrt(max((1.0 - (sin_v * sin_v)), 0.0))) + (R_TILT_SIN_COS[0] * sin_v)))));
    float _e105 = fresnel_schlick(sqrt(min(max((0.5 + (0.5 * v_dot_l)), 0.0), 1.0)), ETA);
    float r_lobe = max((_e96 * ((0.25 * cos_half_phi) * _e105)), 0.0);
    float _e111 = gaussian_lobe(uniforms.width_tt, (sum_of_sines - SHIFT));
    float _e116 = scaled_eta_prime_karis(cos_theta_d, KARIS_ETA_PRIME[0], KARIS_ETA_PRIME[1]);
    float inv_eta_prime = (cos_theta_d / _e116);
    float _e122 = h_tt_karis(inv_eta_prime, cos_phi, cos_half_phi, KARIS_H_TT[0], KARIS_H_TT[1]);
    float _e129 = fresnel_schlick((cos_theta_d * sqrt(min(max((1.0 - (_e122 * _e122)), 0.0), 1.0))), ETA);
    float _e130 = (1.0 - _e129);
    float _e136 = d_karis(cos_phi, KARIS_D_TT[0], KARIS_D_TT[1]);
    float tt_lobe = ((_e111 * _e136) * (_e130 * _e130));
    float _e139 = (_e122 * inv_eta_prime);
    float tt_path = (2.0 * abs((1.0 - ((_e139 * _e139) / cos_theta_d))));
    float _e162 = gaussian_lobe(uniforms.width_trt, (sum_of_sines - TRT_SHIFT));
    float _e164 = fresnel_schlick((cos_theta_d * 0.5), ETA);
    float _e165 = (1.0 - _e164);
    float _e172 = d_karis(cos_phi, KARIS_D_TRT[0], KARIS_D_TRT[1]);
    float trt_lobe = ((_e162 * _e172) * ((_e165 * _e165) * _e164));
    float trt_exponent = (TRT_COLOR_EXPONENT / cos_theta_d);
    return max(((vec3(r_lobe) + max((tt_lobe * exp((-(uniforms.sigma_a) * tt_path))), vec3(0.0))) + max((trt_lobe * exp((uniforms.log_color * trt_exponent))), vec3(0.0))), vec3(0.0));
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

