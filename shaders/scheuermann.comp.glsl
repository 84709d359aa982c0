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
struct FibreFrame {
    vec3 tangent;
    vec3 normal;
    vec3 binormal;
};
struct FibreLocalDirections {
    vec3 wi;
    vec3 wo;
};
const ScheuermannUniforms uniforms = ScheuermannUniforms(vec3(9.8897275e-5, 1.5974958e-5, 2.2135521e-7), vec3(0.027071713, 0.027071713, 0.027071713), 23.637539, 0.99939084, -0.034899496, vec3(0.0016160229, 0.00045222277, 2.1840126e-5), 5.9093847, 0.9975641, 0.06975647, 1.0);
// 1e-30, the floor that keeps a denominator, a length or a width positive
const float TINY = 1e-30;
// 0.25, the bias of the diffuse's mix(0.25, 1, N.L) (Scheuermann 2004)
const float DIFFUSE_BIAS = 0.25;
// 0.75, the scale of the diffuse's mix(0.25, 1, N.L) = 0.25 + 0.75 N.L (Scheuermann 2004)
const float DIFFUSE_SCALE = 0.75;

layout(std430, binding = 0) readonly buffer type_3_block_0Compute { float _group_0_binding_0_cs[]; };

layout(std430, binding = 1) buffer type_3_block_1Compute { float _group_0_binding_1_cs[]; };


// hair_bcsdf: `hairmath eval --model scheuermann`, Scheuermann 2004 (ATI) after the blog seed: two smoothstep(-1, 0, T.H) sin(T, H)^e lobes on shifted tangents, the second tinted and masked, and a scaled-and-biased Lambert diffuse
// (hairmath::registry::MODELS; Bcsdf::eval in the local frame, tangent +X, no cosine factor)
vec3 hair_bcsdf(vec3 wi, vec3 wo) {
    float _e36 = min(sqrt(((wo.y * wo.y) + (wo.z * wo.z))), 1.0);
    bool _e37 = (TINY < _e36);
    float _e39 = (1.0 / max(_e36, TINY));
    float normal_y = (_e37 ? (wo.y * _e39) : 1.0);
    float normal_z = (_e37 ? (wo.z * _e39) : 0.0);
    float diffuse = min(max((DIFFUSE_BIAS + (DIFFUSE_SCALE * ((wi.y * normal_y) + (wi.z * normal_z)))), 0.0), 1.0);
    float _e53 = (wi.x + wo.x);
    float _e54 = (wi.y + wo.y);
    float _e55 = (wi.z + wo.z);
    float _e63 = (1.0 / max(sqrt((((_e53 * _e53) + (_e54 * _e54)) + (_e55 * _e55))), TINY));
    float half_t = (_e53 * _e63);
    float half_n = (((_e54 * normal_y) + (_e55 * normal_z)) * _e63);
    float _e73 = min(max(((uniforms.tangent_primary * half_t) + (uniforms.normal_primary * half_n)), -1.0), 1.0);
    float _e76 = min(max((_e73 + 1.0), 0.0), 1.0);
    float _e84 = (1.0 - (_e73 * _e73));
    float _e91 = (((_e76 * _e76) * (3.0 - (2.0 * _e76))) * ((0.0 < _e84) ? exp((uniforms.half_exponent_primary * log(max(_e84, TINY)))) : 0.0));
    float _e96 = min(max(((uniforms.tangent_secondary * half_t) + (uniforms.normal_secondary * half_n)), -1.0), 1.0);
    float _e99 = min(max((_e96 + 1.0), 0.0), 1.0);
    float _e105 = (1.0 - (_e96 * _e96));
    float _e119 = (uniforms.noise_mask * (((_e99 * _e99) * (3.0 - (2.0 * _e99))) * ((0.0 < _e105) ? exp((uniforms.half_exponent_secondary * log(max(_e105, TINY)))) : 0.0)));
    return (((uniforms.kd * diffuse) + (uniforms.ks_primary * _e91)) + (uniforms.ks_secondary * _e119));
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

