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
const KarisUniforms uniforms = KarisUniforms(0.27830222, 0.13915111, 0.55660444, vec3(0.5447, 0.9061, 1.781), vec3(-4.3458734, -5.6051397, -7.8583317));

layout(std430, binding = 0) readonly buffer type_5_block_0Compute { float _group_0_binding_0_cs[]; };

layout(std430, binding = 1) buffer type_5_block_1Compute { float _group_0_binding_1_cs[]; };


// hairmath::lobe::gaussian::gaussian_lobe -- Marschner et al. 2003, eq. 6
float gaussian_lobe(float beta, float x) {
    float _e2 = (x / beta);
    return (exp(((-0.5 * _e2) * _e2)) / (beta * 2.5066283));
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
float scaled_eta_prime_karis(float cos_theta_d) {
    return (1.19 + ((0.36 * cos_theta_d) * cos_theta_d));
}

// hairmath::models::karis::h_tt_karis -- Karis 2016 (h_TT ~ (1 + a (c1 - c2 cos phi)) cos(phi/2))
float h_tt_karis(float a, float cos_phi, float cos_half_phi) {
    return ((1.0 + (a * (0.6 - (0.8 * cos_phi)))) * cos_half_phi);
}

// hairmath::models::karis::d_karis -- Karis 2016 (D ~ exp(a cos phi + b))
float d_karis(float cos_phi_1) {
    return exp(((-3.65 * cos_phi_1) + -3.98));
}

// hairmath::models::karis::d_karis -- Karis 2016 (D ~ exp(a cos phi + b))
float d_karis_2_(float cos_phi_2) {
    return exp(((17.0 * cos_phi_2) + -16.78));
}

// hair_bcsdf: `hairmath eval --model karis`, Karis 2016 as Unreal Engine 4.27's HairShading (R + TT + TRT) with UE's BaseColor (--color, inverted at beta_n = 0.3) and Roughness, S(wi, wo)
// (hairmath::registry::MODELS; Bcsdf::eval in the local frame, tangent +X, no cosine factor)
vec3 hair_bcsdf(vec3 wi, vec3 wo) {
    float _e35 = -(1.0);
    float _e37 = min(max(-(wi.x), _e35), 1.0);
    float _e40 = min(max(-(wo.x), _e35), 1.0);
    float _e44 = min(max(_e40, -1.0), 1.0);
    float _e51 = min(max(_e37, -1.0), 1.0);
    float _e73 = (((wi.y * wo.y) + (wi.z * wo.z)) / sqrt(((((wi.y * wi.y) + (wi.z * wi.z)) * ((wo.y * wo.y) + (wo.z * wo.z))) + 0.0001)));
    float _e74 = (_e37 + _e40);
    float _e77 = max(cos((0.5 * abs((atan(_e44, sqrt(max((1.0 - (_e44 * _e44)), 0.0))) - atan(_e51, sqrt(max((1.0 - (_e51 * _e51)), 0.0))))))), 1e-30);
    float _e82 = sqrt(min(max((0.5 + (0.5 * _e73)), 0.0), 1.0));
    float _e106 = gaussian_lobe(max((uniforms.width_r * (1.4142135 * _e82)), 1e-30), (_e74 - ((2.0 * -0.06994285) * (((0.997551 * _e82) * sqrt(max((1.0 - (_e40 * _e40)), 0.0))) + (-0.06994285 * _e40)))));
    float _e115 = fresnel_schlick(sqrt(min(max((0.5 + (0.5 * (((wo.x * wi.x) + (wo.y * wi.y)) + (wo.z * wi.z)))), 0.0), 1.0)), 1.55);
    float _e118 = max((_e106 * ((0.25 * _e82) * _e115)), 0.0);
    float _e121 = gaussian_lobe(uniforms.width_tt, (_e74 - 0.035));
    float _e122 = scaled_eta_prime_karis(_e77);
    float _e123 = (_e77 / _e122);
    float _e124 = h_tt_karis(_e123, _e73, _e82);
    float _e131 = fresnel_schlick((_e77 * sqrt(min(max((1.0 - (_e124 * _e124)), 0.0), 1.0))), 1.55);
    float _e132 = (1.0 - _e131);
    float _e134 = d_karis(_e73);
    float _e136 = ((_e121 * _e134) * (_e132 * _e132));
    float _e137 = (_e124 * _e123);
    float _e142 = (2.0 * abs((1.0 - ((_e137 * _e137) / _e77))));
    float _e160 = gaussian_lobe(uniforms.width_trt, (_e74 - 0.14));
    float _e162 = fresnel_schlick((_e77 * 0.5), 1.55);
    float _e163 = (1.0 - _e162);
    float _e166 = d_karis_2_(_e73);
    float _e168 = ((_e160 * _e166) * ((_e163 * _e163) * _e162));
    float _e170 = (0.8 / _e77);
    return vec3(max(((_e118 + max((_e136 * exp((-(uniforms.sigma_a.x) * _e142))), 0.0)) + max((_e168 * exp((uniforms.log_color.x * _e170))), 0.0)), 0.0), max(((_e118 + max((_e136 * exp((-(uniforms.sigma_a.y) * _e142))), 0.0)) + max((_e168 * exp((uniforms.log_color.y * _e170))), 0.0)), 0.0), max(((_e118 + max((_e136 * exp((-(uniforms.sigma_a.z) * _e142))), 0.0)) + max((_e168 * exp((uniforms.log_color.z * _e170))), 0.0)), 0.0));
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

