#version 450 core
#extension GL_ARB_compute_shader : require
#extension GL_ARB_shader_storage_buffer_object : require
layout(local_size_x = 64, local_size_y = 1, local_size_z = 1) in;

struct KajiyaKayUniforms {
    vec3 kd;
    vec3 ks;
    float exponent;
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
const KajiyaKayUniforms uniforms = KajiyaKayUniforms(vec3(0.031746723, 0.016240317, 0.0032422696), vec3(0.019221237, 0.017891414, 0.017399637), 11.818769);
// 1e-30, the floor that keeps a denominator, a length or a width positive
const float TINY = 1e-30;

layout(std430, binding = 0) readonly buffer type_3_block_0Compute { float _group_0_binding_0_cs[]; };

layout(std430, binding = 1) buffer type_3_block_1Compute { float _group_0_binding_1_cs[]; };


// hair_bcsdf: `hairmath eval --model kajiya-kay`, Kajiya and Kay 1989 as the survey writes it: a diffuse k_d cos(theta_i) and one specular cone k_s cos^n(theta_i + theta_o), no cosine factor
// (hairmath::registry::MODELS; Bcsdf::eval in the local frame, tangent +X, no cosine factor)
vec3 hair_bcsdf(vec3 wi, vec3 wo) {
    float cos_theta_i = min(sqrt(((wi.y * wi.y) + (wi.z * wi.z))), 1.0);
    float cos_sum = ((cos_theta_i * min(sqrt(((wo.y * wo.y) + (wo.z * wo.z))), 1.0)) - (min(max(wi.x, -1.0), 1.0) * min(max(wo.x, -1.0), 1.0)));
    float _e47 = ((0.0 < cos_sum) ? exp((uniforms.exponent * log(max(cos_sum, TINY)))) : 0.0);
    return ((uniforms.kd * cos_theta_i) + (uniforms.ks * _e47));
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

