#version 450 core
#extension GL_ARB_compute_shader : require
#extension GL_ARB_shader_storage_buffer_object : require
layout(local_size_x = 64, local_size_y = 1, local_size_z = 1) in;

struct ScheuermannUniforms {
    vec3 kd;
    vec3 ks_primary;
    float half_exponent_primary;
    float tangent_primary;
    float normal_primary;
    vec3 ks_secondary;
    float half_exponent_secondary;
    float tangent_secondary;
    float normal_secondary;
    float noise_mask;
};
const ScheuermannUniforms uniforms = ScheuermannUniforms(vec3(9.8897275e-5, 1.5974958e-5, 2.2135521e-7), vec3(0.027071713, 0.027071713, 0.027071713), 23.637539, 0.99939084, -0.034899496, vec3(0.0016160229, 0.00045222277, 2.1840126e-5), 5.9093847, 0.9975641, 0.06975647, 1.0);

layout(std430, binding = 0) readonly buffer type_5_block_0Compute { float _group_0_binding_0_cs[]; };

layout(std430, binding = 1) buffer type_5_block_1Compute { float _group_0_binding_1_cs[]; };


// hair_bcsdf: `hairmath eval --model scheuermann`, Scheuermann 2004 (ATI) after the blog seed: two smoothstep(-1, 0, T.H) sin(T, H)^e lobes on shifted tangents, the second tinted and masked, and a scaled-and-biased Lambert diffuse
// (hairmath::registry::MODELS; Bcsdf::eval in the local frame, tangent +X, no cosine factor)
vec3 hair_bcsdf(vec3 wi, vec3 wo) {
    float _e57 = min(sqrt(((wo.y * wo.y) + (wo.z * wo.z))), 1.0);
    bool _e58 = (1e-30 < _e57);
    float _e60 = (1.0 / max(_e57, 1e-30));
    float _e62 = (_e58 ? (wo.y * _e60) : 1.0);
    float _e64 = (_e58 ? (wo.z * _e60) : 0.0);
    float _e73 = min(max((0.25 + (0.75 * ((wi.y * _e62) + (wi.z * _e64)))), 0.0), 1.0);
    float _e74 = (wi.x + wo.x);
    float _e75 = (wi.y + wo.y);
    float _e76 = (wi.z + wo.z);
    float _e84 = (1.0 / max(sqrt((((_e74 * _e74) + (_e75 * _e75)) + (_e76 * _e76))), 1e-30));
    float _e85 = (_e74 * _e84);
    float _e89 = (((_e75 * _e62) + (_e76 * _e64)) * _e84);
    float _e94 = min(max(((uniforms.tangent_primary * _e85) + (uniforms.normal_primary * _e89)), -1.0), 1.0);
    float _e97 = min(max((_e94 + 1.0), 0.0), 1.0);
    float _e105 = (1.0 - (_e94 * _e94));
    float _e112 = (((_e97 * _e97) * (3.0 - (2.0 * _e97))) * ((0.0 < _e105) ? exp((uniforms.half_exponent_primary * log(max(_e105, 1e-30)))) : 0.0));
    float _e117 = min(max(((uniforms.tangent_secondary * _e85) + (uniforms.normal_secondary * _e89)), -1.0), 1.0);
    float _e120 = min(max((_e117 + 1.0), 0.0), 1.0);
    float _e126 = (1.0 - (_e117 * _e117));
    float _e140 = (uniforms.noise_mask * (((_e120 * _e120) * (3.0 - (2.0 * _e120))) * ((0.0 < _e126) ? exp((uniforms.half_exponent_secondary * log(max(_e126, 1e-30)))) : 0.0)));
    return vec3((((uniforms.kd.x * _e73) + (uniforms.ks_primary.x * _e112)) + (uniforms.ks_secondary.x * _e140)), (((uniforms.kd.y * _e73) + (uniforms.ks_primary.y * _e112)) + (uniforms.ks_secondary.y * _e140)), (((uniforms.kd.z * _e73) + (uniforms.ks_primary.z * _e112)) + (uniforms.ks_secondary.z * _e140)));
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

