struct ChiangUniforms {
    variance_r: f32,
    variance_tt: f32,
    variance_trt: f32,
    inv_variance_r: f32,
    inv_variance_tt: f32,
    inv_variance_trt: f32,
    lobe_norm_r: f32,
    lobe_norm_tt: f32,
    lobe_norm_trt: f32,
    logistic_scale: f32,
    logistic_inv_scale: f32,
    logistic_mass: f32,
    logistic_norm: f32,
    sin_alpha: f32,
    cos_alpha: f32,
    sin_2_alpha: f32,
    cos_2_alpha: f32,
    sin_4_alpha: f32,
    cos_4_alpha: f32,
    eta: f32,
    inv_eta: f32,
    sigma_a: vec3<f32>,
}

struct FarFieldNodeElement {
    h: f32,
    weight: f32,
}

const uniforms: ChiangUniforms = ChiangUniforms(0.08461118f, 0.021152794f, 0.3384447f, 11.818769f, 47.275078f, 2.9546924f, 11.818769f, 47.275078f, 2.9627328f, 0.117159806f, 8.535351f, 1f, 8.535351f, 0.034899496f, 0.99939084f, 0.06975647f, 0.9975641f, 0.1391731f, 0.99026805f, 1.55f, 0.6451613f, vec3<f32>(0.5447f, 0.9061f, 1.781f));
const FAR_FIELD_OFFSETS: array<FarFieldNodeElement, 64> = array<FarFieldNodeElement, 64>(FarFieldNodeElement(0.9999994f, 0.0000015289318f), FarFieldNodeElement(0.9999835f, 0.00001872458f), FarFieldNodeElement(0.99990034f, 0.00007211129f), FarFieldNodeElement(0.99965745f, 0.00018185156f), FarFieldNodeElement(0.9991224f, 0.0003673992f), FarFieldNodeElement(0.99812496f, 0.0006472144f), FarFieldNodeElement(0.99645925f, 0.0010384569f), FarFieldNodeElement(0.9938865f, 0.0015566545f), FarFieldNodeElement(0.9901389f, 0.00221535f), FarFieldNodeElement(0.9849239f, 0.0030257301f), FarFieldNodeElement(0.9779291f, 0.003996244f), FarFieldNodeElement(0.9688285f, 0.005132225f), FarFieldNodeElement(0.9572886f, 0.006435525f), FarFieldNodeElement(0.94297606f, 0.007904187f), FarFieldNodeElement(0.92556554f, 0.009532163f), FarFieldNodeElement(0.904748f, 0.011309116f), FarFieldNodeElement(0.8802395f, 0.013220307f), FarFieldNodeElement(0.85178995f, 0.015246595f), FarFieldNodeElement(0.81919193f, 0.017364576f), FarFieldNodeElement(0.78228873f, 0.019546852f), FarFieldNodeElement(0.74098223f, 0.021762462f), FarFieldNodeElement(0.69523925f, 0.023977457f), FarFieldNodeElement(0.6450969f, 0.02615561f), FarFieldNodeElement(0.5906664f, 0.028259275f), FarFieldNodeElement(0.5321349f, 0.030250335f), FarFieldNodeElement(0.46976525f, 0.032091226f), FarFieldNodeElement(0.4038941f, 0.033746015f), FarFieldNodeElement(0.33492747f, 0.035181463f), FarFieldNodeElement(0.26333427f, 0.036368046f), FarFieldNodeElement(0.18963791f, 0.03728089f), FarFieldNodeElement(0.11440627f, 0.037900586f), FarFieldNodeElement(0.038240023f, 0.03821382f), FarFieldNodeElement(-0.038240023f, 0.03821382f), FarFieldNodeElement(-0.11440627f, 0.037900586f), FarFieldNodeElement(-0.18963791f, 0.03728089f), FarFieldNodeElement(-0.26333427f, 0.036368046f), FarFieldNodeElement(-0.33492747f, 0.035181463f), FarFieldNodeElement(-0.4038941f, 0.033746015f), FarFieldNodeElement(-0.46976525f, 0.032091226f), FarFieldNodeElement(-0.5321349f, 0.030250335f), FarFieldNodeElement(-0.5906664f, 0.028259275f), FarFieldNodeElement(-0.6450969f, 0.02615561f), FarFieldNodeElement(-0.69523925f, 0.023977457f), FarFieldNodeElement(-0.74098223f, 0.021762462f), FarFieldNodeElement(-0.78228873f, 0.019546852f), FarFieldNodeElement(-0.81919193f, 0.017364576f), FarFieldNodeElement(-0.85178995f, 0.015246595f), FarFieldNodeElement(-0.8802395f, 0.013220307f), FarFieldNodeElement(-0.904748f, 0.011309116f), FarFieldNodeElement(-0.92556554f, 0.009532163f), FarFieldNodeElement(-0.94297606f, 0.007904187f), FarFieldNodeElement(-0.9572886f, 0.006435525f), FarFieldNodeElement(-0.9688285f, 0.005132225f), FarFieldNodeElement(-0.9779291f, 0.003996244f), FarFieldNodeElement(-0.9849239f, 0.0030257301f), FarFieldNodeElement(-0.9901389f, 0.00221535f), FarFieldNodeElement(-0.9938865f, 0.0015566545f), FarFieldNodeElement(-0.99645925f, 0.0010384569f), FarFieldNodeElement(-0.99812496f, 0.0006472144f), FarFieldNodeElement(-0.9991224f, 0.0003673992f), FarFieldNodeElement(-0.99965745f, 0.00018185156f), FarFieldNodeElement(-0.99990034f, 0.00007211129f), FarFieldNodeElement(-0.9999835f, 0.00001872458f), FarFieldNodeElement(-0.9999994f, 0.0000015289318f));

// hairmath::geometry::fibre_angles -- the local frame of DESIGN.md: sin theta = w.x, phi in the YZ plane
fn fibre_angles(wi_in: vec3<f32>, wo_in: vec3<f32>) -> array<f32, 5> {
    let _e38 = (((1f * ((wi_in.y * wo_in.z) - (wi_in.z * wo_in.y))) + (0f * ((wi_in.z * 0f) - (0f * wo_in.z)))) + (0f * ((0f * wo_in.y) - (wi_in.y * 0f))));
    let _e43 = (((0f * 0f) + (wi_in.y * wo_in.y)) + (wi_in.z * wo_in.z));
    return array<f32, 5>(min(max(wi_in.x, -1f), 1f), min(sqrt(((wi_in.y * wi_in.y) + (wi_in.z * wi_in.z))), 1f), min(max(wo_in.x, -1f), 1f), min(sqrt(((wo_in.y * wo_in.y) + (wo_in.z * wo_in.z))), 1f), atan2(_e38, select(1f, _e43, (0f < (abs(_e38) + abs(_e43))))));
}

// hairmath::fresnel::fresnel -- Born and Wolf, section 1.5 (unpolarised dielectric reflectance)
fn fresnel(cos_i: f32, eta: f32, inv_eta: f32) -> f32 {
    let _e11 = sqrt(max((1f - ((1f - (cos_i * cos_i)) * (inv_eta * inv_eta))), 0f));
    let _e12 = (eta * cos_i);
    let _e13 = (_e12 - _e11);
    let _e14 = (_e12 + _e11);
    let _e15 = (eta * _e11);
    let _e16 = (cos_i - _e15);
    let _e17 = (cos_i + _e15);
    let _e18 = (_e14 * _e14);
    let _e19 = (_e17 * _e17);
    return min(((((_e13 * _e13) * _e19) + ((_e16 * _e16) * _e18)) / ((2f * _e18) * _e19)), 1f);
}

// hairmath::azimuthal::path::fibre_path -- Chiang et al. 2016, sections 4.1 and 4.3 (Snell and Bravais; the chord 2 cos gamma_t / cos theta_t)
fn fibre_path(h: f32, c2_: f32, inv_eta_1: f32, c3_: f32, eta_1: f32) -> array<f32, 4> {
    let _e8 = min(max(h, -(1f)), 1f);
    let _e11 = (((_e8 * c2_) * inv_eta_1) * c3_);
    let _e16 = sqrt(max((1f - (_e11 * _e11)), 0f));
    let _e20 = sqrt(max((1f - (_e8 * _e8)), 0f));
    let _e22 = fresnel((c2_ * _e20), eta_1, inv_eta_1);
    return array<f32, 4>(atan2(_e8, _e20), atan2(_e11, _e16), ((2f * _e16) * c3_), _e22);
}

// hairmath::azimuthal::attenuation::attenuations -- Chiang et al. 2016, eqs. 3 and 6
fn attenuations(fresnel_in: f32, transmittance: f32) -> array<f32, 4> {
    let _e3 = (1f - fresnel_in);
    let _e5 = ((_e3 * _e3) * transmittance);
    let _e7 = ((_e5 * fresnel_in) * transmittance);
    return array<f32, 4>(fresnel_in, _e5, _e7, (((_e7 * fresnel_in) * transmittance) / max((1f - (fresnel_in * transmittance)), 0.000000000000000000000000000001f)));
}

// hairmath::azimuthal::exit_angle::exit_angle -- Marschner et al. 2003, eq. 3
fn exit_angle(p: f32, gamma_i: f32, gamma_t: f32) -> f32 {
    return ((((2f * p) * gamma_t) - (2f * gamma_i)) + (p * 3.1415927f));
}

// hairmath::bcsdf::chiang::trimmed_logistics -- Chiang et al. 2016, eq. 13
fn trimmed_logistics(dphi_r: f32, dphi_tt: f32, dphi_trt: f32, logistic_inv_scale: f32, logistic_norm: f32) -> array<f32, 3> {
    let _e8 = exp((-(abs(dphi_r)) * logistic_inv_scale));
    let _e10 = (1f + _e8);
    let _e11 = (_e10 * _e10);
    let _e15 = exp((-(abs(dphi_tt)) * logistic_inv_scale));
    let _e16 = (1f + _e15);
    let _e17 = (_e16 * _e16);
    let _e21 = exp((-(abs(dphi_trt)) * logistic_inv_scale));
    let _e22 = (1f + _e21);
    let _e23 = (_e22 * _e22);
    let _e27 = (logistic_norm / (((1f * _e11) * _e17) * _e23));
    let _e31 = (_e27 * _e11);
    return array<f32, 3>((_e8 * ((_e27 * _e17) * _e23)), (_e15 * (_e31 * _e23)), (_e21 * (_e31 * _e17)));
}

// hairmath::bcsdf::far_field::OffsetNodes::azimuthal -- Chiang et al. 2016, eq. 8 (N_p averaged over h), by Gauss-Legendre quadrature
fn far_field_node(r_red_in: f32, r_green_in: f32, r_blue_in: f32, tt_red_in: f32, tt_green_in: f32, tt_blue_in: f32, trt_red_in: f32, trt_green_in: f32, trt_blue_in: f32, residual_red_in: f32, residual_green_in: f32, residual_blue_in: f32, h_1: f32, weight: f32, c0_: f32, inv_eta_2: f32, c2_1: f32, eta_2: f32, sigma_a_x: f32, sigma_a_y: f32, sigma_a_z: f32, c7_: f32, logistic_inv_scale_1: f32, logistic_norm_1: f32) -> array<f32, 12> {
    let _e24 = (c0_ * inv_eta_2);
    let _e32 = fibre_path(h_1, c2_1, inv_eta_2, (1f / sqrt(max((1f - (_e24 * _e24)), 0f))), eta_2);
    let _e40 = attenuations(_e32[3], exp((-(sigma_a_x) * _e32[2])));
    let _e48 = attenuations(_e32[3], exp((-(sigma_a_y) * _e32[2])));
    let _e56 = attenuations(_e32[3], exp((-(sigma_a_z) * _e32[2])));
    let _e61 = exit_angle(0f, _e32[0], _e32[1]);
    let _e62 = (c7_ - _e61);
    let _e71 = exit_angle(1f, _e32[0], _e32[1]);
    let _e72 = (c7_ - _e71);
    let _e79 = exit_angle(2f, _e32[0], _e32[1]);
    let _e80 = (c7_ - _e79);
    let _e86 = trimmed_logistics((_e62 - (6.2831855f * floor(((_e62 + 3.1415927f) * 0.15915494f)))), (_e72 - (6.2831855f * floor(((_e72 + 3.1415927f) * 0.15915494f)))), (_e80 - (6.2831855f * floor(((_e80 + 3.1415927f) * 0.15915494f)))), logistic_inv_scale_1, logistic_norm_1);
    return array<f32, 12>((r_red_in + (weight * (_e40[0] * _e86[0]))), (r_green_in + (weight * (_e48[0] * _e86[0]))), (r_blue_in + (weight * (_e56[0] * _e86[0]))), (tt_red_in + (weight * (_e40[1] * _e86[1]))), (tt_green_in + (weight * (_e48[1] * _e86[1]))), (tt_blue_in + (weight * (_e56[1] * _e86[1]))), (trt_red_in + (weight * (_e40[2] * _e86[2]))), (trt_green_in + (weight * (_e48[2] * _e86[2]))), (trt_blue_in + (weight * (_e56[2] * _e86[2]))), (residual_red_in + (weight * (_e40[3] * 0.15915494f))), (residual_green_in + (weight * (_e48[3] * 0.15915494f))), (residual_blue_in + (weight * (_e56[3] * 0.15915494f))));
}

// hairmath::lobe::deon::deon_lobe -- d'Eon et al. 2011, eq. 7
fn deon_lobe(sin_i: f32, cos_i_1: f32, sin_o: f32, cos_o: f32, inv_variance_r: f32, lobe_norm_r: f32) -> f32 {
    let _e7 = (cos_i_1 * cos_o);
    let _e9 = (_e7 - (sin_i * sin_o));
    let _e12 = ((sin_i * cos_o) + (cos_i_1 * sin_o));
    let _e22 = max((_e7 * inv_variance_r), 0f);
    let _e27 = (min(_e22, 3.75f) * 0.26666668f);
    let _e28 = (_e27 * _e27);
    let _e47 = (1f / max(_e22, 3.75f));
    let _e48 = (3.75f * _e47);
    let _e76 = (_e22 < 3.75f);
    return ((lobe_norm_r * select((((((((((((((((((0.00392377f * _e48) + -0.01647633f) * _e48) + 0.02635537f) * _e48) + -0.02057706f) * _e48) + 0.00916281f) * _e48) + -0.00157565f) * _e48) + 0.00225319f) * _e48) + 0.01328592f) * _e48) + 0.3989423f) * sqrt(_e47)), ((((((((((((0.0045813f * _e28) + 0.0360768f) * _e28) + 0.2659732f) * _e28) + 1.2067492f) * _e28) + 3.0899425f) * _e28) + 3.5156229f) * _e28) + 1f), _e76)) * exp((select(0f, -(_e22), _e76) - (select((1f - _e9), ((_e12 * _e12) / (1f + max(_e9, 0f))), (0f < _e9)) * inv_variance_r))));
}

// hair_bcsdf: `hairmath eval --model chiang-far`, the far field of Chiang et al. 2016: S(wi, wo) averaged over h uniform in [-1, 1], with a fixed Gauss-Legendre rule over h or the adaptive reference
// (hairmath::registry::MODELS; Bcsdf::eval in the local frame, tangent +X, no cosine factor)
fn hair_bcsdf(wi: vec3<f32>, wo: vec3<f32>) -> vec3<f32> {
    var r_red: f32;
    var r_green: f32;
    var r_blue: f32;
    var tt_red: f32;
    var tt_green: f32;
    var tt_blue: f32;
    var trt_red: f32;
    var trt_green: f32;
    var trt_blue: f32;
    var residual_red: f32;
    var residual_green: f32;
    var residual_blue: f32;
    var k: u32 = 0u;

    let _e50 = fibre_angles(wi, wo);
    r_red = 0f;
    r_green = 0f;
    r_blue = 0f;
    tt_red = 0f;
    tt_green = 0f;
    tt_blue = 0f;
    trt_red = 0f;
    trt_green = 0f;
    trt_blue = 0f;
    residual_red = 0f;
    residual_green = 0f;
    residual_blue = 0f;
    loop {
        let _e71 = k;
        if (_e71 < 64u) {
        } else {
            break;
        }
        let _e75 = k;
        let _e77 = r_red;
        let _e78 = r_green;
        let _e79 = r_blue;
        let _e80 = tt_red;
        let _e81 = tt_green;
        let _e82 = tt_blue;
        let _e83 = trt_red;
        let _e84 = trt_green;
        let _e85 = trt_blue;
        let _e86 = residual_red;
        let _e87 = residual_green;
        let _e88 = residual_blue;
        let _e91 = far_field_node(_e77, _e78, _e79, _e80, _e81, _e82, _e83, _e84, _e85, _e86, _e87, _e88, FAR_FIELD_OFFSETS[_e75].h, FAR_FIELD_OFFSETS[_e75].weight, _e50[2], uniforms.inv_eta, _e50[3], uniforms.eta, uniforms.sigma_a.x, uniforms.sigma_a.y, uniforms.sigma_a.z, -(_e50[4]), uniforms.logistic_inv_scale, uniforms.logistic_norm);
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
        continuing {
            let _e104 = k;
            k = (_e104 + 1u);
        }
    }
    let _e107 = r_red;
    let _e108 = r_green;
    let _e109 = r_blue;
    let _e110 = tt_red;
    let _e111 = tt_green;
    let _e112 = tt_blue;
    let _e113 = trt_red;
    let _e114 = trt_green;
    let _e115 = trt_blue;
    let _e116 = residual_red;
    let _e117 = residual_green;
    let _e118 = residual_blue;
    let _e119 = -(uniforms.sin_2_alpha);
    let _e127 = deon_lobe(_e50[0], _e50[1], ((_e50[2] * uniforms.cos_2_alpha) + (_e50[3] * _e119)), abs(((_e50[3] * uniforms.cos_2_alpha) - (_e50[2] * _e119))), uniforms.inv_variance_r, uniforms.lobe_norm_r);
    let _e135 = deon_lobe(_e50[0], _e50[1], ((_e50[2] * uniforms.cos_alpha) + (_e50[3] * uniforms.sin_alpha)), abs(((_e50[3] * uniforms.cos_alpha) - (_e50[2] * uniforms.sin_alpha))), uniforms.inv_variance_tt, uniforms.lobe_norm_tt);
    let _e143 = deon_lobe(_e50[0], _e50[1], ((_e50[2] * uniforms.cos_4_alpha) + (_e50[3] * uniforms.sin_4_alpha)), abs(((_e50[3] * uniforms.cos_4_alpha) - (_e50[2] * uniforms.sin_4_alpha))), uniforms.inv_variance_trt, uniforms.lobe_norm_trt);
    let _e144 = deon_lobe(_e50[0], _e50[1], _e50[2], _e50[3], uniforms.inv_variance_trt, uniforms.lobe_norm_trt);
    return vec3<f32>(((((0f + (_e127 * _e107)) + (_e135 * _e110)) + (_e143 * _e113)) + (_e144 * _e116)), ((((0f + (_e127 * _e108)) + (_e135 * _e111)) + (_e143 * _e114)) + (_e144 * _e117)), ((((0f + (_e127 * _e109)) + (_e135 * _e112)) + (_e143 * _e115)) + (_e144 * _e118)));
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

