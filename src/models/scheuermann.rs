//! Scheuermann 2004 (ATI, "Practical Real-Time Hair Rendering and Shading") as the Scheuermann
//! blog seed gives it ([`Scheuermann`], `--model scheuermann`): two specular lobes on shifted
//! tangents, the second tinted and masked by a noise texture, and a scaled-and-biased Lambert
//! diffuse.
//!
//! # The source
//!
//! The blog seed (`scheuermann-shading-model-blog.txt`, its GLSL listing) computes, for the
//! unit tangent T (root to tip), the normal N, L towards the light, V towards the viewer and
//! `H = normalize(L + V)`:
//!
//! - `shiftTangent(shift) = normalize(T + shift * N)`, with `t1 = shiftTangent(PRIMARY_SHIFT +
//!   baseShift)` and `t2 = shiftTangent(SECONDARY_SHIFT + baseShift)`, where `baseShift` is the
//!   shift texture's value minus 0.5;
//! - `calcStrandSpecularLighting(T, e) = smoothstep(-1, 0, T.H) * pow(sqrt(1 - (T.H)^2), e)`,
//!   that is `smoothstep(-1, 0, T.H) sin(T, H)^e`;
//! - `diffuse = clamp(mix(0.25, 1, N.L), 0, 1) * DIFFUSE_COLOR`;
//! - `(diffuse + specular1 + mask * specular2) * color`, with `specular1` weighted by the
//!   specular map, `specular2` by `SECONDARY_SPECULAR_COLOR` and `mask` the noise texture.
//!
//! Here: `S = k_d clamp(0.25 + 0.75 N.L, 0, 1) + k_1 lobe(t1, e_1) + m k_2 lobe(t2, e_2)`.
//! The textures are numbers (`shift_texture`, `noise_mask`); the base texture `color` and the
//! light colour, which multiply every term, are folded into the three weights. The blog's
//! constants are `PRIMARY_SHIFT = -1`, `SECONDARY_SHIFT = 1.5`, exponents 0.98 and 0.49, and
//! `DIFFUSE_COLOR = SECONDARY_SPECULAR_COLOR = (0.416, 0.424, 0.431)` ([`ScheuermannParams::BLOG`]).
//!
//! **The scale and bias of the diffuse.** `mix(0.25, 1, x) = 0.25 + 0.75 x`: scale 0.75, bias
//! 0.25. The term is 1 facing the light, 0.25 at the terminator and reaches 0 at N.L = -1/3
//! (109.5 degrees from the normal), so it wraps the lighting a third of the way past the
//! terminator, the "brighten up areas facing away from the light" of the blog; the upper clamp
//! never acts. Its albedo is `int clamp(0.25 + 0.75 N.wi, 0, 1) dwi = 2 pi int_{-1/3}^{1}
//! (0.25 + 0.75 mu) d mu = 4 pi / 3` for every wo.
//!
//! **Cosine factors.** None to convert: the shader's value multiplies the light's colour (its
//! irradiance at normal incidence) to give the radiance, which is what the crate's S gives for a
//! directional light (`L_o = int S L_i dw_i = S E`). The N.L of the diffuse is part of the
//! model (the cosine to the normal), not a projection factor.
//!
//! # The normal in the fibre frame
//!
//! A mesh shader reads N from a normal map; a fibre has no normal of its own. Scheuermann
//! assumes the hair's normal lies in the plane of T and V (the survey seed's ATI section, and
//! the blog: "we can assume that it lies in a plane spanned by the associated tangent and the
//! view vector"), so here N is V's component across the fibre, normalised: in the local frame
//! `N = (0, wo.y, wo.z) / cos(theta_o)`. It depends only on the fibre and wo, so the model is
//! rotationally symmetric about the fibre (a far-field model). Where wo runs along the tangent
//! that normal is undefined and N = +Y is taken (a choice: every normal is as good there). Then
//! `N.L = cos(theta_i) cos(phi)` and, with `t = a u + b N`, `a = 1 / sqrt(1 + s^2)`,
//! `b = s a` (u and N are orthogonal, so this is `normalize(u + s N)`),
//! `t.H = (a (wi + wo).x + b N.(wi + wo)) / |wi + wo|`. At wi = -wo, where the half vector is
//! undefined, `H = 0` is taken (t.H = 0, each lobe at its maximum): the value is finite there but,
//! as for every half-vector model, has no limit.
//!
//! A shift s moves a lobe's peak (in the plane of u and N) to `tan(theta_h) = -s`, theta_h the
//! half angle: the blog's negative primary shift puts it at theta_h > 0 (where the reference's
//! R lies for alpha > 0) and the positive secondary at theta_h < 0 (TRT), as
//! [`super::TressFx`]'s cones.
//!
//! # Inputs
//!
//! | input | meaning | unit, domain |
//! | --- | --- | --- |
//! | `kd` | diffuse weight (`DIFFUSE_COLOR` times the base colour) | linear RGB, each channel in [0, 1e6] |
//! | `ks_primary` | primary lobe weight (the specular map) | linear RGB, [0, 1e6] |
//! | `exponent_primary` | e_1 of `sin(t1, H)^e_1` | (0, 1e6] |
//! | `tangent_shift_primary` | `PRIMARY_SHIFT`, along N | dimensionless, finite |
//! | `ks_secondary` | secondary lobe weight (`SECONDARY_SPECULAR_COLOR`) | linear RGB, [0, 1e6] |
//! | `exponent_secondary` | e_2 | (0, 1e6] |
//! | `tangent_shift_secondary` | `SECONDARY_SHIFT` | dimensionless, finite |
//! | `shift_texture` | the shift texture's value (0.5: no extra shift) | [0, 1], default 0.5 |
//! | `noise_mask` | the noise texture's value masking the secondary | [0, 1], default 1 |
//!
//! # Mapping from the physical parameters ([`Approximation::mapped_inputs`])
//!
//! - **Exponents.** Near its peak `sin(t, H)^e = cos^e x ~ exp(-e x^2 / 2)` in the angle x of H
//!   from the plane normal to t; in the plane of u and N, x is the half angle's distance from
//!   the peak, `(theta_i + theta_o) / 2 - theta_peak`, so the lobe is a Gaussian in theta_i of
//!   variance `4 / e`. Matched to the reference's d'Eon lobes (variance v_0 of Chiang's eq. 7 for
//!   R, 4 v_0 for TRT; [`crate::bcsdf::longitudinal_variance`]): `e_1 = 4 / v_0`,
//!   `e_2 = 1 / v_0`, capped at 1e6.
//! - **Shifts.** The reference's R peaks at theta_h = alpha and TRT at theta_h = -2 alpha, so
//!   `tangent_shift_primary = -tan(alpha)`, `tangent_shift_secondary = tan(2 alpha)`,
//!   `shift_texture = 0.5`; `noise_mask = 1`.
//! - **Weights.** As for Kajiya-Kay ([`super::KajiyaKay`]): each term gets the reference
//!   energies it stands for at theta_o = 0 (`E_p = 1/2 int A_p(h) dh`, per channel): R for the
//!   primary (white), TRT for the secondary (tinted by the absorption), the residual (the
//!   longer internal paths) for the diffuse, divided by the term's albedo with unit weight.
//!   TT has no counterpart: the diffuse faces the light (`N.L = cos theta_i cos phi` is largest
//!   at phi = 0, light and viewer on the same side), while TT scatters forward (phi near pi),
//!   and, as the blog says, "TT isn't quite represented in our shader". Giving the diffuse TT's
//!   energy too puts it on the wrong side of the fibre: for brown hair (beta_m = 0.3) it raises
//!   the relative L2 error against the reference from 0.94 to 1.00 (the metric and pairs of
//!   the Kajiya-Kay module's mapping note). The diffuse's albedo with unit weight is
//!   4 pi / 3; a lobe's, with wi written through its half vector (`dwi = 4 (wo.H) dH`, H at
//!   angle x from the plane normal to t and azimuth psi about t), is
//!   `int smoothstep(-1, 0, sin x) cos^e x  4 G(x) cos x dx`, where
//!   `G(x) = int max(wo.H, 0) d psi` is closed-form (`wo.H = A sin x + B cos x cos psi`, A and B
//!   the components of wo along and across t), by adaptive quadrature in x.
//!
//! **Fitted inputs** ([`Approximation::FITTED_INPUTS`]): the weights, exponents and tangent
//! shifts (the two textures only rescale the secondary weight and offset both shifts, so they
//! are not fitted).
//!
//! **Varying in shader code** ([`crate::bcsdf::VaryingInputs`]): every input, the two
//! textures included (a renderer samples them per pixel); nothing is baked. Out of their
//! domains weights and exponents are clamped as Kajiya-Kay's ([`super::KajiyaKay`]) and the
//! texture values to [0, 1].

use super::approximation::Approximation;
use super::kajiya_kay::{
    exponent_in, exponent_input, finite_input, lobe_window, positive_power, scale3, weight_for,
    weight_in, weight_input, ReferenceEnergies, EXPONENT_PRIMARY, EXPONENT_SECONDARY, KD,
    KS_PRIMARY, KS_SECONDARY, MAX_EXPONENT,
};
use crate::absorption::Rgb;
use crate::bcsdf::{
    longitudinal_variance, sum_lobes, Bcsdf, FromInputs, Input, InputKind, InputValue, InputValues,
    InputsIn, Model, Query, VaryingInputs,
};
use crate::error::ParamError;
use crate::geometry::local_sin_cos_theta;
use crate::params::HairParams;
use crate::quadrature::adaptive;
use crate::real::{NamedConstant, Real, TINY};
use core::f64::consts::PI;

/// The lobes of [`Scheuermann`], in the order of [`Bcsdf::eval_lobes`].
pub const SCHEUERMANN_LOBES: [&str; 3] = ["diffuse", "primary", "secondary"];

/// The scale of the diffuse's scaled-and-biased Lambert term: `mix(0.25, 1, x) = 0.25 +
/// 0.75 x`.
const DIFFUSE_SCALE: NamedConstant = NamedConstant {
    name: "DIFFUSE_SCALE",
    meaning:
        "0.75, the scale of the diffuse's mix(0.25, 1, N.L) = 0.25 + 0.75 N.L (Scheuermann 2004)",
    values: &[0.75],
};
/// Its bias.
const DIFFUSE_BIAS: NamedConstant = NamedConstant {
    name: "DIFFUSE_BIAS",
    meaning: "0.25, the bias of the diffuse's mix(0.25, 1, N.L) (Scheuermann 2004)",
    values: &[0.25],
};

/// The albedo of the diffuse term of unit weight, `4 pi / 3` (module docs).
const DIFFUSE_ALBEDO: f64 = 4.0 * PI / 3.0;

crate::uniform_block! {
    /// The uniforms of [`Scheuermann`]. Each shifted tangent is `t = a u + b N` with
    /// `a = 1 / sqrt(1 + s^2)`, `b = s a` and s the lobe's shift plus the shift texture's value
    /// minus 0.5.
    pub struct ScheuermannUniforms<R> {
        /// Diffuse weight per channel.
        pub kd: [R; 3],
        /// Primary lobe weight per channel.
        pub ks_primary: [R; 3],
        /// Half the primary exponent: `sin^e = (1 - (t.H)^2)^(e/2)`.
        pub half_exponent_primary: R,
        /// a of the primary tangent.
        pub tangent_primary: R,
        /// b of the primary tangent.
        pub normal_primary: R,
        /// Secondary lobe weight per channel.
        pub ks_secondary: [R; 3],
        /// Half the secondary exponent.
        pub half_exponent_secondary: R,
        /// a of the secondary tangent.
        pub tangent_secondary: R,
        /// b of the secondary tangent.
        pub normal_secondary: R,
        /// The noise texture's value that masks the secondary lobe.
        pub noise_mask: R,
    }
}

/// One specular lobe of [`Scheuermann`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct StrandLobe {
    /// Weight per channel, each in [0, 1e6].
    pub weight: Rgb,
    /// Exponent of `sin(t, H)`, in (0, 1e6].
    pub exponent: f64,
    /// The tangent's shift along the normal (finite): `t = normalize(T + shift N)`.
    pub tangent_shift: f64,
}

/// The validated inputs of [`Scheuermann`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ScheuermannParams {
    /// Diffuse weight per channel, each in [0, 1e6].
    pub kd: Rgb,
    /// The primary lobe.
    pub primary: StrandLobe,
    /// The secondary lobe (tinted, masked).
    pub secondary: StrandLobe,
    /// The shift texture's value in [0, 1]: adds `value - 0.5` to both shifts.
    pub shift_texture: f64,
    /// The noise texture's value in [0, 1] that multiplies the secondary lobe.
    pub noise_mask: f64,
}

impl ScheuermannParams {
    /// The blog's constants: `DIFFUSE_COLOR = SECONDARY_SPECULAR_COLOR = (0.416, 0.424,
    /// 0.431)`, shifts -1 and 1.5, exponents 0.98 and 0.49, a white specular map and the two
    /// textures at their neutral values (0.5, 1).
    pub const BLOG: ScheuermannParams = ScheuermannParams {
        kd: [0.416, 0.424, 0.431],
        primary: StrandLobe {
            weight: [1.0; 3],
            exponent: 0.98,
            tangent_shift: -1.0,
        },
        secondary: StrandLobe {
            weight: [0.416, 0.424, 0.431],
            exponent: 0.49,
            tangent_shift: 1.5,
        },
        shift_texture: 0.5,
        noise_mask: 1.0,
    };
}

/// Scheuermann's hair shader as a far-field model (module docs):
/// `S = k_d clamp(0.25 + 0.75 N.L, 0, 1) + k_1 lobe(t1, e_1) + m k_2 lobe(t2, e_2)`,
/// `lobe(t, e) = smoothstep(-1, 0, t.H) sin(t, H)^e`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Scheuermann<R> {
    uniforms: ScheuermannUniforms<R>,
}

impl Scheuermann<f64> {
    /// The model of `params`.
    ///
    /// # Errors
    /// [`ParamError::OutOfRange`] naming the first input outside its domain.
    pub fn new(params: &ScheuermannParams) -> Result<Self, ParamError> {
        Self::from_inputs(&scheuermann_values(params))
    }
}

/// The input values of `params`.
fn scheuermann_values(params: &ScheuermannParams) -> InputValues {
    let mut values = InputValues::new();
    values.set("kd", InputValue::Rgb(params.kd));
    for (lobe, [weight, exponent, shift]) in [
        (
            params.primary,
            ["ks_primary", "exponent_primary", "tangent_shift_primary"],
        ),
        (
            params.secondary,
            [
                "ks_secondary",
                "exponent_secondary",
                "tangent_shift_secondary",
            ],
        ),
    ] {
        values.set(weight, InputValue::Rgb(lobe.weight));
        values.set(exponent, InputValue::Number(lobe.exponent));
        values.set(shift, InputValue::Number(lobe.tangent_shift));
    }
    values.set("shift_texture", InputValue::Number(params.shift_texture));
    values.set("noise_mask", InputValue::Number(params.noise_mask));
    values
}

/// `(a, b)` of the tangent `normalize(u + s N) = a u + b N` (u and N orthogonal unit vectors),
/// without overflow for large s: `(1, s) / sqrt(1 + s^2)`, computed as `(1/m, s/m)` divided
/// by its length, `m = max(1, |s|)`.
fn shifted_tangent<R: Real>(s: R) -> (R, R) {
    let one = R::c(1.0);
    let m = s.abs().max(one);
    let (a, b) = (one / m, s / m);
    let inv_length = one / (a * a + b * b).sqrt();
    (a * inv_length, b * inv_length)
}

/// `smoothstep(-1, 0, x) = t^2 (3 - 2 t)`, `t = clamp(x + 1, 0, 1)`.
#[inline(always)]
fn smoothstep_from_minus_one<R: Real>(x: R) -> R {
    let t = (x + R::c(1.0)).clamp(R::c(0.0), R::c(1.0));
    t * t * (R::c(3.0) - R::c(2.0) * t)
}

/// `smoothstep(-1, 0, t.H) (1 - (t.H)^2)^(e/2)` for `t.H = a h_t + b h_n` (clamped to
/// [-1, 1]).
#[inline(always)]
fn strand_lobe<R: Real>(h_t: R, h_n: R, a: R, b: R, half_exponent: R) -> R {
    let t_dot_h = (a * h_t + b * h_n).clamp(R::c(-1.0), R::c(1.0));
    smoothstep_from_minus_one(t_dot_h)
        * positive_power(R::c(1.0) - t_dot_h * t_dot_h, half_exponent)
}

impl<R: Real> Scheuermann<R> {
    /// `[diffuse, primary, secondary]` per channel.
    #[inline(always)]
    fn terms(&self, query: &Query<R>) -> [[R; 3]; 3] {
        let u = &self.uniforms;
        let (wi, wo) = (query.wi, query.wo);
        // Below `tiny` a direction's projection across the fibre, and `|wi + wo|`, count as 0.
        let (zero, one, tiny) = (R::c(0.0), R::c(1.0), TINY.get::<R>());
        // The normal: wo's direction across the fibre (+Y where wo runs along it).
        let (_, cos_o) = local_sin_cos_theta(wo);
        let defined = tiny.lt(cos_o);
        let inv_cos_o = one / cos_o.max(tiny);
        let n_y = R::select(defined, wo.y * inv_cos_o, one).label("normal_y");
        let n_z = R::select(defined, wo.z * inv_cos_o, zero).label("normal_z");
        let n_dot_l = wi.y * n_y + wi.z * n_z;
        let diffuse = (DIFFUSE_BIAS.get::<R>() + DIFFUSE_SCALE.get::<R>() * n_dot_l)
            .clamp(zero, one)
            .label("diffuse");
        // The half vector's components along u and N (0 where wi = -wo).
        let (sx, sy, sz) = (wi.x + wo.x, wi.y + wo.y, wi.z + wo.z);
        let inv_length = one / (sx * sx + sy * sy + sz * sz).sqrt().max(tiny);
        let h_t = (sx * inv_length).label("half_t");
        let h_n = ((sy * n_y + sz * n_z) * inv_length).label("half_n");
        let primary = strand_lobe(
            h_t,
            h_n,
            u.tangent_primary,
            u.normal_primary,
            u.half_exponent_primary,
        );
        let secondary = strand_lobe(
            h_t,
            h_n,
            u.tangent_secondary,
            u.normal_secondary,
            u.half_exponent_secondary,
        );
        [
            scale3(u.kd, diffuse),
            scale3(u.ks_primary, primary),
            scale3(u.ks_secondary, u.noise_mask * secondary),
        ]
    }
}

impl<R: Real> Bcsdf<R> for Scheuermann<R> {
    fn lobe_names(&self) -> &'static [&'static str] {
        &SCHEUERMANN_LOBES
    }

    fn eval_lobes(&self, query: &Query<R>) -> Vec<[R; 3]> {
        self.terms(query).to_vec()
    }

    #[inline(always)]
    fn eval(&self, query: &Query<R>) -> [R; 3] {
        sum_lobes(&self.terms(query))
    }
}

impl Model for Scheuermann<f64> {
    const INLINED_KERNEL: bool = true;
    type Uniforms<R: Real> = ScheuermannUniforms<R>;
    type In<R: Real> = Scheuermann<R>;

    fn uniforms(&self) -> ScheuermannUniforms<f64> {
        self.uniforms
    }

    fn with_uniforms<R: Real>(&self, uniforms: ScheuermannUniforms<R>) -> Scheuermann<R> {
        Scheuermann { uniforms }
    }
}

/// A texture's value in [0, 1].
fn texture_input(values: &InputValues, name: &'static str) -> Result<f64, ParamError> {
    ParamError::check(
        name,
        values.number(name)?,
        "texture values must be in [0, 1]",
        |v| (0.0..=1.0).contains(&v),
    )
}

impl FromInputs for Scheuermann<f64> {
    const NAME: &'static str = "scheuermann";
    const SUMMARY: &'static str = "Scheuermann 2004 (ATI) after the blog seed: two \
        smoothstep(-1, 0, T.H) sin(T, H)^e lobes on shifted tangents, the second tinted and \
        masked, and a scaled-and-biased Lambert diffuse";
    const INPUTS: &'static [Input] = &[
        KD,
        KS_PRIMARY,
        EXPONENT_PRIMARY,
        Input {
            name: "tangent_shift_primary",
            kind: InputKind::Number,
            help: "shift of the primary lobe's tangent along the normal, T' = normalize(T + s N) \
                   (the blog's PRIMARY_SHIFT, -1), finite",
            default: None,
            conflicts_with: &[],
        },
        KS_SECONDARY,
        EXPONENT_SECONDARY,
        Input {
            name: "tangent_shift_secondary",
            kind: InputKind::Number,
            help: "shift of the secondary lobe's tangent along the normal (the blog's \
                   SECONDARY_SHIFT, 1.5), finite",
            default: None,
            conflicts_with: &[],
        },
        Input {
            name: "shift_texture",
            kind: InputKind::Number,
            help: "the shift texture's value in [0, 1], adding value - 0.5 to both tangent \
                   shifts",
            default: Some(0.5),
            conflicts_with: &[],
        },
        Input {
            name: "noise_mask",
            kind: InputKind::Number,
            help: "the noise texture's value in [0, 1] that masks the secondary lobe",
            default: Some(1.0),
            conflicts_with: &[],
        },
    ];

    fn from_inputs(values: &InputValues) -> Result<Self, ParamError> {
        let allowed = "the tangent shift must be finite";
        finite_input(values, "tangent_shift_primary", allowed)?;
        finite_input(values, "tangent_shift_secondary", allowed)?;
        texture_input(values, "shift_texture")?;
        for name in ["kd", "ks_primary", "ks_secondary"] {
            weight_input(values, name)?;
        }
        exponent_input(values, "exponent_primary")?;
        exponent_input(values, "exponent_secondary")?;
        texture_input(values, "noise_mask")?;
        Ok(Scheuermann {
            uniforms: Self::uniforms_in(&InputsIn::constant(values)),
        })
    }
}

impl VaryingInputs for Scheuermann<f64> {
    const NAME: &'static str = <Self as FromInputs>::NAME;
    const INPUTS: &'static [Input] = <Self as FromInputs>::INPUTS;
    const VARYING: &'static [&'static str] = &[
        "kd",
        "ks_primary",
        "exponent_primary",
        "tangent_shift_primary",
        "ks_secondary",
        "exponent_secondary",
        "tangent_shift_secondary",
        "shift_texture",
        "noise_mask",
    ];
    const BAKED: &'static [(&'static str, &'static str)] = &[];

    /// Half of each exponent, the shifted tangents `normalize(u + (shift + texture - 1/2) N)`
    /// ([`ScheuermannUniforms`]) and the weights and mask themselves.
    fn uniforms_in<R: Real>(inputs: &InputsIn<R>) -> ScheuermannUniforms<R> {
        let texture = |name| inputs.number(name).clamp(R::c(0.0), R::c(1.0));
        let base_shift = texture("shift_texture") - R::c(0.5);
        let tangent = |name| shifted_tangent(inputs.number(name) + base_shift);
        let (tangent_primary, normal_primary) = tangent("tangent_shift_primary");
        let (tangent_secondary, normal_secondary) = tangent("tangent_shift_secondary");
        let half = R::c(0.5);
        ScheuermannUniforms {
            kd: weight_in(inputs, "kd"),
            ks_primary: weight_in(inputs, "ks_primary"),
            half_exponent_primary: half * exponent_in(inputs, "exponent_primary"),
            tangent_primary,
            normal_primary,
            ks_secondary: weight_in(inputs, "ks_secondary"),
            half_exponent_secondary: half * exponent_in(inputs, "exponent_secondary"),
            tangent_secondary,
            normal_secondary,
            noise_mask: texture("noise_mask"),
        }
    }
}

/// The albedo at theta_o = 0 (wo = +Y, so N = +Y) of a lobe of unit weight, exponent
/// `exponent` and tangent `t = a u + b N` (module docs): with `A = wo.t = b`, `B = a`,
/// `int smoothstep(-1, 0, sin x) cos^e x 4 G(x) cos x dx` over the window where the lobe is not
/// negligible, `G(x) = int_0^{2 pi} max(A sin x + B cos x cos psi, 0) d psi`
/// `= 2 (p acos(-p/q) + sqrt(q^2 - p^2))` for `|p| < q` (`p = A sin x`, `q = B cos x`), else
/// `2 pi max(p, 0)`.
fn strand_lobe_albedo(exponent: f64, a: f64, b: f64) -> f64 {
    let width = lobe_window(exponent);
    // Where q = |p|: G has a kink there.
    let kink = a.atan2(b.abs());
    let integrand = |x: f64| {
        let (s, c) = x.sin_cos();
        let t = (s + 1.0).clamp(0.0, 1.0);
        let lobe = t * t * (3.0 - 2.0 * t) * c.max(0.0).powf(exponent);
        let (p, q) = (b * s, a * c);
        let g = if q <= p.abs() {
            2.0 * PI * p.max(0.0)
        } else {
            2.0 * (p * (-p / q).acos() + (q * q - p * p).sqrt())
        };
        [lobe * 4.0 * g * c]
    };
    let (value, _) = adaptive(integrand, -width, width, &[0.0, kink, -kink], 1e-10, 0.0);
    value[0]
}

impl Approximation for Scheuermann<f64> {
    /// The module's mapping: `e_1 = 4 / v_0`, `e_2 = 1 / v_0`, shifts `-tan(alpha)` and
    /// `tan(2 alpha)`, weights from the reference's lobe energies at theta_o = 0 (R, TRT and
    /// the residual).
    fn mapped_inputs(hair: &HairParams) -> InputValues {
        let energies = ReferenceEnergies::of(hair);
        let v0 = longitudinal_variance(hair.beta_m.get());
        let alpha = hair.alpha.get();
        let lobe = |energy: Rgb, exponent: f64, tangent_shift: f64| {
            let exponent = exponent.min(MAX_EXPONENT);
            let (a, b) = shifted_tangent(tangent_shift);
            StrandLobe {
                weight: weight_for(energy, strand_lobe_albedo(exponent, a, b)),
                exponent,
                tangent_shift,
            }
        };
        scheuermann_values(&ScheuermannParams {
            kd: weight_for(energies.residual, DIFFUSE_ALBEDO),
            primary: lobe(energies.r, 4.0 / v0, -alpha.tan()),
            secondary: lobe(energies.trt, 1.0 / v0, (2.0 * alpha).tan()),
            shift_texture: 0.5,
            noise_mask: 1.0,
        })
    }

    const FITTED_INPUTS: &'static [&'static str] = &[
        "kd",
        "ks_primary",
        "exponent_primary",
        "tangent_shift_primary",
        "ks_secondary",
        "exponent_secondary",
        "tangent_shift_secondary",
    ];
}
