struct GerardUniforms {
    g_r: f32,
    g_tt: f32,
    g_trt: f32,
    lobe_scale_r: f32,
    lobe_scale_tt: f32,
    lobe_scale_trt: f32,
    alpha_r: f32,
    alpha_tt: f32,
    alpha_trt: f32,
    sigma_a: vec3<f32>,
    k_tt: f32,
    k_trt: f32,
    min_cos2_theta_d: f32,
}

const uniforms: GerardUniforms = GerardUniforms(0.76984614f, 0.8167546f, 0.69702667f, 1f, 1f, 1f, 0.034906585f, -0.017453292f, -0.05235988f, vec3<f32>(0.5447f, 0.9061f, 1.781f), 4f, 5.5f, 0.000000000001f);

// lut0_gerard_texels: 128 x 64 texels (phi in [0, 3.141592653589793] along x, theta_d in [0, 1.5707963267948966] along y); x, y, z = N_R, N_TT, N_TRT; rgba32float, read with textureLoad
@group(1) @binding(0) 
var lut0_gerard_texels: texture_2d<f32>;

// table 0 (gerard): 2 axes, 3 channels; multilinear interpolation of texels read with textureLoad, in the operation order of hairmath::lut::Table::lookup_into
fn lut0_gerard(phi: f32, theta_d: f32) -> vec4<f32> {
    let _e10 = (min(max(((phi - 0f) * 0.31830987f), 0f), 1f) * 127f);
    let _e13 = min(floor(_e10), 126f);
    let _e14 = (_e10 - _e13);
    let _e15 = (1f - _e14);
    let _e19 = clamp(i32(_e13), 0i, 126i);
    let _e21 = (_e19 + 1i);
    let _e28 = (min(max(((theta_d - 0f) * 0.63661975f), 0f), 1f) * 63f);
    let _e31 = min(floor(_e28), 62f);
    let _e32 = (_e28 - _e31);
    let _e33 = (1f - _e32);
    let _e36 = clamp(i32(_e31), 0i, 62i);
    let _e37 = (_e36 + 1i);
    let _e43 = textureLoad(lut0_gerard_texels, vec2<i32>(_e19, _e36), 0i);
    let _e49 = textureLoad(lut0_gerard_texels, vec2<i32>(_e21, _e36), 0i);
    let _e55 = textureLoad(lut0_gerard_texels, vec2<i32>(_e19, _e37), 0i);
    let _e61 = textureLoad(lut0_gerard_texels, vec2<i32>(_e21, _e37), 0i);
    return ((((vec4(0f) + (((1f * _e15) * _e33) * _e43)) + (((1f * _e14) * _e33) * _e49)) + (((1f * _e15) * _e32) * _e55)) + (((1f * _e14) * _e32) * _e61));
}

// hairmath::geometry::fibre_angles -- the local frame of DESIGN.md: sin theta = w.x, phi in the YZ plane
fn fibre_angles(wi_in: vec3<f32>, wo_in: vec3<f32>) -> array<f32, 5> {
    let _e38 = (((1f * ((wi_in.y * wo_in.z) - (wi_in.z * wo_in.y))) + (0f * ((wi_in.z * 0f) - (0f * wo_in.z)))) + (0f * ((0f * wo_in.y) - (wi_in.y * 0f))));
    let _e43 = (((0f * 0f) + (wi_in.y * wo_in.y)) + (wi_in.z * wo_in.z));
    return array<f32, 5>(min(max(wi_in.x, -1f), 1f), min(sqrt(((wi_in.y * wi_in.y) + (wi_in.z * wi_in.z))), 1f), min(max(wo_in.x, -1f), 1f), min(sqrt(((wo_in.y * wo_in.y) + (wo_in.z * wo_in.z))), 1f), atan2(_e38, select(1f, _e43, (0f < (abs(_e38) + abs(_e43))))));
}

// hair_bcsdf: `hairmath eval --model gerard`, Gerard's direct lighting (eq. 4-8): Henyey-Greenstein lobes, Marschner's N_p from a 128 x 64 table times e^(-k sigma_a), S(wi, wo)
// (hairmath::registry::MODELS; Bcsdf::eval in the local frame, tangent +X, no cosine factor)
fn hair_bcsdf(wi: vec3<f32>, wo: vec3<f32>) -> vec3<f32> {
    let _e41 = fibre_angles(wi, wo);
    let _e47 = atan2(_e41[0], _e41[1]);
    let _e48 = atan2(_e41[2], _e41[3]);
    let _e51 = ((_e47 + _e48) * 0.5f);
    let _e53 = ((_e48 - _e47) * 0.5f);
    let _e54 = cos(_e53);
    let _e57 = (_e41[1] / max((_e54 * _e54), uniforms.min_cos2_theta_d));
    let _e60 = lut0_gerard(abs(_e41[4]), abs(_e53));
    let _e67 = (uniforms.g_r * uniforms.g_r);
    let _e72 = ((1f + _e67) - ((2f * uniforms.g_r) * cos((_e51 - uniforms.alpha_r))));
    let _e81 = (((((1f - _e67) / ((12.566371f * _e72) * sqrt(_e72))) * uniforms.lobe_scale_r) * _e60.x) * _e57);
    let _e84 = (uniforms.g_tt * uniforms.g_tt);
    let _e88 = ((1f + _e84) - ((2f * uniforms.g_tt) * cos((_e51 - uniforms.alpha_tt))));
    let _e96 = (((((1f - _e84) / ((12.566371f * _e88) * sqrt(_e88))) * uniforms.lobe_scale_tt) * _e60.y) * _e57);
    let _e99 = (uniforms.g_trt * uniforms.g_trt);
    let _e103 = ((1f + _e99) - ((2f * uniforms.g_trt) * cos((_e51 - uniforms.alpha_trt))));
    let _e111 = (((((1f - _e99) / ((12.566371f * _e103) * sqrt(_e103))) * uniforms.lobe_scale_trt) * _e60.z) * _e57);
    let _e112 = -(uniforms.k_tt);
    let _e122 = -(uniforms.k_trt);
    return vec3<f32>(((_e81 + (_e96 * exp((_e112 * uniforms.sigma_a.x)))) + (_e111 * exp((_e122 * uniforms.sigma_a.x)))), ((_e81 + (_e96 * exp((_e112 * uniforms.sigma_a.y)))) + (_e111 * exp((_e122 * uniforms.sigma_a.y)))), ((_e81 + (_e96 * exp((_e112 * uniforms.sigma_a.z)))) + (_e111 * exp((_e122 * uniforms.sigma_a.z)))));
}

// hairmath::geometry::fibre_frame -- Duff et al. 2017, listing 3
fn fibre_frame(tangent_in: vec3<f32>) -> array<f32, 9> {
    let _e13 = (1f / max(sqrt((((tangent_in.x * tangent_in.x) + (tangent_in.y * tangent_in.y)) + (tangent_in.z * tangent_in.z))), 0.000000000000000000000000000001f));
    let _e14 = (tangent_in.x * _e13);
    let _e15 = (tangent_in.y * _e13);
    let _e16 = (tangent_in.z * _e13);
    let _e19 = -(1f);
    let _e20 = select(1f, _e19, (_e16 < 0f));
    let _e22 = (_e19 / (_e20 + _e16));
    let _e24 = ((_e14 * _e15) * _e22);
    return array<f32, 9>(_e14, _e15, _e16, (1f + (((_e20 * _e14) * _e14) * _e22)), (_e20 * _e24), (-(_e20) * _e14), _e24, (_e20 + ((_e15 * _e15) * _e22)), -(_e15));
}

// fibre_local_directions: hairmath::geometry::local_directions -- wi and wo in the fibre's frame
fn fibre_local_directions(tangent: vec3<f32>, wi: vec3<f32>, wo: vec3<f32>) -> array<f32, 6> {
    let _e12 = fibre_frame(tangent);
    return array<f32, 6>((((wi.x * _e12[0]) + (wi.y * _e12[1])) + (wi.z * _e12[2])), (((wi.x * _e12[3]) + (wi.y * _e12[4])) + (wi.z * _e12[5])), (((wi.x * _e12[6]) + (wi.y * _e12[7])) + (wi.z * _e12[8])), (((wo.x * _e12[0]) + (wo.y * _e12[1])) + (wo.z * _e12[2])), (((wo.x * _e12[3]) + (wo.y * _e12[4])) + (wo.z * _e12[5])), (((wo.x * _e12[6]) + (wo.y * _e12[7])) + (wo.z * _e12[8])));
}

// hair_bcsdf_world: hair_bcsdf of world-space directions, made local to the fibre by fibre_local_directions
fn hair_bcsdf_world(tangent: vec3<f32>, wi: vec3<f32>, wo: vec3<f32>) -> vec3<f32> {
    let _e3 = fibre_local_directions(tangent, wi, wo);
    let _e12 = hair_bcsdf(vec3<f32>(_e3[0], _e3[1], _e3[2]), vec3<f32>(_e3[3], _e3[4], _e3[5]));
    return _e12;
}

