//! Kajiya and Kay 1989 as the survey seed writes it ([`KajiyaKay`], `--model kajiya-kay`), and
//! its two-cone form with highlights shifted towards the root and the tip ([`TressFx`],
//! `--model tressfx`).
//!
//! # The source and its cosine factor
//!
//! The survey seed (`hair-models-survey-kajiya-marschner-weta-ue4.txt`, section "Kajiya-Kay
//! Model", after "Physically-Accurate Fur Reflectance") writes
//!
//! `S_M(theta_i, theta_o) = k_d + k_s cos^n(theta_o + theta_i) / cos(theta_i)`
//!
//! with theta measured from the fibre's normal plane (sin theta = w . u, both directions
//! pointing away from the fibre, so the mirror cone of wi is theta_o = -theta_i and the peak is
//! at theta_i + theta_o = 0). It is written in Marschner's convention, where the radiance is
//! `L_o = int S_M L_i cos(theta_i) dw_i` (the cos theta_i is the fibre's width projected towards
//! the light). The crate's S has no cosine factor (`L_o = int S L_i dw_i`), so
//! `S = S_M cos(theta_i)`:
//!
//! `S = k_d cos(theta_i) + k_s max(cos(theta_i + theta_o), 0)^n`.
//!
//! The survey's `1 / cos theta_i` only cancels Marschner's projection factor: Kajiya-Kay's
//! specular, as in the classic shader, carries no cosine at all, and the constant diffuse k_d
//! of `S_M` becomes `k_d cos(theta_i) = k_d sin(T, L)`, the classic Kajiya-Kay diffuse
//! (cos theta_i is the sine of the angle between the tangent T and the light L). Nothing is
//! divided, so S is finite at grazing incidence (theta_i = +-90 degrees), where the survey's
//! `S_M` diverges. The clamp `max(cos, 0)` is not in the survey's formula, which goes negative
//! (or is undefined for fractional n) when |theta_i + theta_o| > 90 degrees (README, errata);
//! Kajiya and Kay's specular term exists only within a quarter turn of the mirror cone.
//!
//! Both cosines come from the sines and cosines of the local frame:
//! `cos(theta_i + theta_o) = cos theta_i cos theta_o - sin theta_i sin theta_o`.
//!
//! # The two-cone form (TressFX)
//!
//! No seed document lists the TressFX shader; its form follows from Kajiya-Kay's: a cone
//! deviated from the mirror cone by an angle `d` peaks at `theta_i + theta_o = d`, and its
//! specular is `cos^n(theta_i + theta_o - d)`. [`TressFx`] has two such cones, each with its
//! own weight (per channel: the secondary is tinted), exponent and deviation:
//!
//! `S = k_d cos theta_i + k_1 max(cos(theta_i + theta_o - d_1), 0)^n_1
//!                      + k_2 max(cos(theta_i + theta_o + d_2), 0)^n_2`
//!
//! with `cos(x -+ d) = cos x cos d +- sin x sin d`, `sin(theta_i + theta_o) = sin theta_i
//! cos theta_o + cos theta_i sin theta_o` (cos d, sin d are uniforms). The primary
//! (`shift_primary = d_1`) is shifted "towards the root" and the secondary
//! (`shift_secondary = d_2`) "towards the tip", as the sources say of R and TRT; the signs are
//! fixed here in the local frame so that positive shifts sit where the reference puts R and
//! TRT for a positive cuticle tilt alpha (`bcsdf::ChiangHair`: R rotated by -2 alpha, so its
//! peak is at theta_i + theta_o = 2 alpha; TRT by +4 alpha, peak at -4 alpha). On a strand
//! lying over a convex head, a lobe tilted towards +u (d > 0) lights the part of the strand
//! whose tangent leans towards the half vector, nearer the root: the sources' "shifted towards
//! the root". Scheuermann's shader ([`super::Scheuermann`]) shifts its tangents the same way
//! (its primary shift is negative, its secondary positive).
//!
//! # Inputs
//!
//! | input | meaning | unit, domain |
//! | --- | --- | --- |
//! | `kd` | diffuse weight k_d | linear RGB, each channel in [0, 1e6] |
//! | `ks` (Kajiya-Kay) | specular weight k_s | linear RGB, each channel in [0, 1e6] |
//! | `exponent` (Kajiya-Kay) | specular exponent n | (0, 1e6] |
//! | `ks_primary`, `ks_secondary` (TressFX) | the cones' weights k_1, k_2 | linear RGB, [0, 1e6] |
//! | `exponent_primary`, `exponent_secondary` (TressFX) | n_1, n_2 | (0, 1e6] |
//! | `shift_primary`, `shift_secondary` (TressFX) | d_1 (towards +u), d_2 (towards -u) | angle, finite (`--shift-primary-deg`) |
//!
//! `ks` is a colour, not a number: Kajiya and Kay give every coefficient per colour channel,
//! renderers tint the specular, and a fit against the reference needs a tinted cone when the
//! single cone stands for R and the coloured TRT together (one value on the command line sets
//! all three channels). The bounds 1e6 keep the `f32` instantiation finite (an exponent of 1e6
//! is a cone 1e-3 rad wide, below what `f32` cosines resolve).
//!
//! # Mapping from the physical parameters ([`Approximation::mapped_inputs`])
//!
//! - **Exponents.** Near its peak `cos^n x = exp(n ln cos x) ~ exp(-n x^2 / 2)`, a Gaussian in
//!   theta_i of variance 1/n, while the reference's d'Eon lobe `M_p` is, to the same order,
//!   `exp(-(1 - cos x) / v_p) ~ exp(-x^2 / (2 v_p))` with Chiang's variances v_0 (eq. 7,
//!   [`crate::bcsdf::longitudinal_variance`] of beta_m), v_TT = v_0 / 4, v_TRT = 4 v_0. So
//!   `n = 1 / v_0` for Kajiya-Kay's one cone and TressFX's primary (R), `n_2 = 1 / (4 v_0)`
//!   for the secondary (TRT), capped at 1e6.
//! - **Shifts.** `d_1 = 2 alpha` and `d_2 = 4 alpha`: the reference's R and TRT peaks.
//! - **Weights.** Each term gets the energy of the reference lobes it stands for, for the
//!   hair seen side-on (theta_o = 0): the reference's lobe albedo there is
//!   `E_p = 1/2 int A_p(h) dh` (its longitudinal and azimuthal factors integrate to 1; the
//!   attenuations of [`crate::azimuthal::attenuations_at_offset`] with the exact chord and the
//!   hair's eta and sigma_a per channel, so the weights carry the hair's colour). A cone's albedo
//!   with unit weight at theta_o = 0 is `2 pi int max(cos(theta - d), 0)^n cos theta d theta`
//!   (computed by adaptive quadrature) and the diffuse's is `int cos theta_i dw_i = pi^2`.
//!   Kajiya-Kay: `k_s = (E_R + E_TRT) / albedo`, `k_d = (E_TT + E_residual) / pi^2`. TressFX:
//!   `k_1 = E_R / albedo_1` (white: R is Fresnel only), `k_2 = E_TRT / albedo_2` (tinted by the
//!   absorption), `k_d` as Kajiya-Kay's. Neither model has a forward-scattering lobe, so the
//!   diffuse term, the same for every azimuth, carries TT's energy: for brown hair
//!   (beta_m = 0.3) that lowers Kajiya-Kay's relative L2 error against the reference from 0.93
//!   (the residual alone) to 0.89 (relative L2 over all RGB values, 50,000 low-discrepancy
//!   direction pairs uniform on the two spheres).
//!
//! **Fitted inputs** ([`Approximation::FITTED_INPUTS`]): every weight, exponent and shift.
//!
//! **Varying in shader code** ([`crate::bcsdf::VaryingInputs`]): every input (Kajiya-Kay:
//! `kd`, `ks`, `exponent`; TressFX: `kd`, `ks_primary`, `exponent_primary`, `shift_primary`,
//! `ks_secondary`, `exponent_secondary`, `shift_secondary`); nothing is baked. Out of their
//! domains a weight is clamped to [0, 1e6], an exponent at or below 0 is 1e-6 and above 1e6
//! is 1e6; a shift is wrapped into [-pi, pi] before its sine and cosine (which changes neither).

use super::approximation::Approximation;
use crate::absorption::{PathLength, Rgb};
use crate::azimuthal::attenuations_at_offset;
use crate::bcsdf::{
    longitudinal_variance, sum_lobes, Bcsdf, FromInputs, Input, InputKind, InputValue, InputValues,
    Model, Query,
};
use crate::bcsdf::{InputsIn, VaryingInputs};
use crate::error::ParamError;
use crate::geometry::{local_sin_cos_theta, V3};
use crate::params::HairParams;
use crate::quadrature::{adaptive, gauss_legendre, integrate};
use crate::real::MapInline;
use crate::real::{wrap_angle, Real, TINY};
use core::f64::consts::{FRAC_PI_2, PI};

/// The lobes of [`KajiyaKay`], in the order of [`Bcsdf::eval_lobes`].
pub const KAJIYA_KAY_LOBES: [&str; 2] = ["diffuse", "specular"];

/// The lobes of [`TressFx`], in the order of [`Bcsdf::eval_lobes`].
pub const TRESSFX_LOBES: [&str; 3] = ["diffuse", "primary", "secondary"];

/// Largest weight per channel and largest exponent an input accepts: keeps the `f32`
/// instantiation finite.
pub(crate) const MAX_WEIGHT: f64 = 1e6;
/// See [`MAX_WEIGHT`].
pub(crate) const MAX_EXPONENT: f64 = 1e6;

/// `max(base, 0)^exponent` for `exponent > 0`, as `exp(exponent ln base)`: exactly 0 for
/// `base <= 0`, 1 for `base = 1`, and never `ln 0` (the logarithm's argument is floored at
/// [`TINY`], finite in `f32`; both arms are safe to evaluate).
#[inline(always)]
pub(crate) fn positive_power<R: Real>(base: R, exponent: R) -> R {
    let powered = (exponent * base.max(TINY.get()).ln()).exp();
    R::select(R::c(0.0).lt(base), powered, R::c(0.0))
}

/// `a * s` per channel.
#[inline(always)]
pub(crate) fn scale3<R: Real>(a: [R; 3], s: R) -> [R; 3] {
    [a[0] * s, a[1] * s, a[2] * s]
}

/// `cos(theta_i + theta_o)` and `sin(theta_i + theta_o)` of unit directions in the local frame.
#[inline(always)]
fn sum_angle<R: Real>(wi: V3<R>, wo: V3<R>) -> (R, R) {
    let (sin_i, cos_i) = local_sin_cos_theta(wi);
    let (sin_o, cos_o) = local_sin_cos_theta(wo);
    (cos_i * cos_o - sin_i * sin_o, sin_i * cos_o + cos_i * sin_o)
}

// ---------------------------------------------------------------------------------------------
// Inputs (shared by name with Scheuermann's model: one declaration each).

/// The diffuse weight k_d.
pub(crate) const KD: Input = Input {
    name: "kd",
    kind: InputKind::Rgb,
    help: "diffuse weight k_d, linear RGB, each channel in [0, 1e6]",
    default: None,
    conflicts_with: &[],
};
/// The primary lobe's weight.
pub(crate) const KS_PRIMARY: Input = Input {
    name: "ks_primary",
    kind: InputKind::Rgb,
    help: "weight of the primary specular lobe, linear RGB, each channel in [0, 1e6]",
    default: None,
    conflicts_with: &[],
};
/// The secondary lobe's weight (its tint).
pub(crate) const KS_SECONDARY: Input = Input {
    name: "ks_secondary",
    kind: InputKind::Rgb,
    help: "weight (tint) of the secondary specular lobe, linear RGB, each channel in [0, 1e6]",
    default: None,
    conflicts_with: &[],
};
/// The primary lobe's exponent.
pub(crate) const EXPONENT_PRIMARY: Input = Input {
    name: "exponent_primary",
    kind: InputKind::Number,
    help: "exponent of the primary specular lobe, in (0, 1e6]",
    default: None,
    conflicts_with: &[],
};
/// The secondary lobe's exponent.
pub(crate) const EXPONENT_SECONDARY: Input = Input {
    name: "exponent_secondary",
    kind: InputKind::Number,
    help: "exponent of the secondary specular lobe, in (0, 1e6]",
    default: None,
    conflicts_with: &[],
};

/// A weight per channel, each in [0, [`MAX_WEIGHT`]].
pub(crate) fn weight_input(values: &InputValues, name: &'static str) -> Result<Rgb, ParamError> {
    let rgb = values.rgb(name)?;
    for &v in &rgb {
        ParamError::check(
            name,
            v,
            "weights must be in [0, 1e6] in every channel",
            |v| (0.0..=MAX_WEIGHT).contains(&v),
        )?;
    }
    Ok(rgb)
}

/// An exponent in (0, [`MAX_EXPONENT`]].
pub(crate) fn exponent_input(values: &InputValues, name: &'static str) -> Result<f64, ParamError> {
    ParamError::check(
        name,
        values.number(name)?,
        "exponents must be in (0, 1e6]",
        |v| v > 0.0 && v <= MAX_EXPONENT,
    )
}

/// The smallest exponent shader code uses: an exponent at or below 0, which the CPU rejects,
/// is this there.
pub(crate) const MIN_EXPONENT: f64 = 1e-6;

/// A weight per channel in shader code: clamped to [0, [`MAX_WEIGHT`]].
#[inline(always)]
pub(crate) fn weight_in<R: Real>(inputs: &InputsIn<R>, name: &str) -> [R; 3] {
    inputs.rgb(name).map_inline(
        #[inline(always)]
        |w| w.max(R::c(0.0)).min(R::c(MAX_WEIGHT)),
    )
}

/// An exponent in shader code: in (0, [`MAX_EXPONENT`]], [`MIN_EXPONENT`] at or below 0.
#[inline(always)]
pub(crate) fn exponent_in<R: Real>(inputs: &InputsIn<R>, name: &str) -> R {
    let e = inputs.number(name);
    R::select(
        R::c(0.0).lt(e),
        e.min(R::c(MAX_EXPONENT)),
        R::c(MIN_EXPONENT),
    )
}

/// A finite number (an angle in radians).
pub(crate) fn finite_input(
    values: &InputValues,
    name: &'static str,
    allowed: &'static str,
) -> Result<f64, ParamError> {
    ParamError::check(name, values.number(name)?, allowed, |_| true)
}

// ---------------------------------------------------------------------------------------------
// The reference's lobe energies and the unit albedos of the mapping.

/// The reference's lobe energies per channel for the hair seen side-on (theta_o = 0):
/// `E_p = 1/2 int_{-1}^{1} A_p(h) dh` (Chiang et al. 2016's attenuations with the exact chord,
/// [`attenuations_at_offset`]), which is the albedo of each lobe of the far field there (its
/// longitudinal and azimuthal factors integrate to 1). Integrated in gamma = asin h, where the
/// integrand is smooth at the fibre's edges.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct ReferenceEnergies {
    /// R.
    pub r: Rgb,
    /// TT.
    pub tt: Rgb,
    /// TRT.
    pub trt: Rgb,
    /// All longer paths.
    pub residual: Rgb,
}

impl ReferenceEnergies {
    /// The energies of `hair`.
    pub(crate) fn of(hair: &HairParams) -> Self {
        let rule = gauss_legendre(16);
        let eta = hair.eta.get();
        let energy = |p: usize, sigma_a: f64| {
            let a = |gamma: f64| {
                let h = gamma.sin();
                attenuations_at_offset(h, 0.0, 1.0, eta, sigma_a, PathLength::Chord)[p]
                    * gamma.cos()
            };
            0.5 * integrate(&rule, 16, -FRAC_PI_2, FRAC_PI_2, a)
        };
        let sigma_a = hair.sigma_a.rgb();
        let lobe = |p: usize| {
            sigma_a.map_inline(
                #[inline(always)]
                |s| energy(p, s),
            )
        };
        ReferenceEnergies {
            r: lobe(0),
            tt: lobe(1),
            trt: lobe(2),
            residual: lobe(3),
        }
    }
}

/// `a + b` per channel.
fn add_rgb(a: Rgb, b: Rgb) -> Rgb {
    [a[0] + b[0], a[1] + b[1], a[2] + b[2]]
}

/// The weight per channel that gives a term of unit albedo `albedo` the energy `energy`,
/// capped at [`MAX_WEIGHT`] (0 where the term has no albedo at all).
pub(crate) fn weight_for(energy: Rgb, albedo: f64) -> Rgb {
    energy.map_inline(
        #[inline(always)]
        |e| {
            if albedo > 0.0 {
                (e / albedo).min(MAX_WEIGHT)
            } else {
                0.0
            }
        },
    )
}

/// The width of the window outside which `cos^n x <= exp(-n x^2 / 2)` is below e^-72 of its
/// peak (at most a quarter turn).
pub(crate) fn lobe_window(exponent: f64) -> f64 {
    (12.0 / exponent.sqrt()).min(FRAC_PI_2)
}

/// The albedo at theta_o = 0 of a Kajiya-Kay cone of unit weight, exponent `exponent` and
/// deviation `deviation` (radians): `int max(cos(theta_i - d), 0)^n dw_i`
/// `= 2 pi int_{-pi/2}^{pi/2} max(cos(theta - d), 0)^n cos(theta) d theta`, by adaptive
/// quadrature over the window where the cone is not negligible ([`lobe_window`]).
pub(crate) fn cone_albedo(exponent: f64, deviation: f64) -> f64 {
    let centre = wrap_angle(deviation);
    let width = lobe_window(exponent);
    let (lo, hi) = (
        (centre - width).max(-FRAC_PI_2),
        (centre + width).min(FRAC_PI_2),
    );
    if lo >= hi {
        return 0.0;
    }
    let cone = |t: f64| [(t - centre).cos().max(0.0).powf(exponent) * t.cos()];
    let (value, _) = adaptive(cone, lo, hi, &[centre], 1e-10, 0.0);
    2.0 * PI * value[0]
}

/// The albedo of the diffuse term `cos(theta_i)` of unit weight: `int cos theta_i dw_i`
/// `= 2 pi int_{-pi/2}^{pi/2} cos^2 theta d theta = pi^2`, for every wo.
pub(crate) const KAJIYA_KAY_DIFFUSE_ALBEDO: f64 = PI * PI;

// ---------------------------------------------------------------------------------------------
// Kajiya-Kay.

crate::uniform_block! {
    /// The uniforms of [`KajiyaKay`].
    pub struct KajiyaKayUniforms<R> {
        /// Diffuse weight k_d per channel.
        pub kd: [R; 3],
        /// Specular weight k_s per channel.
        pub ks: [R; 3],
        /// Specular exponent n.
        pub exponent: R,
    }
}

/// The validated inputs of [`KajiyaKay`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct KajiyaKayParams {
    /// Diffuse weight k_d per channel, each in [0, 1e6].
    pub kd: Rgb,
    /// Specular weight k_s per channel, each in [0, 1e6].
    pub ks: Rgb,
    /// Specular exponent n in (0, 1e6].
    pub exponent: f64,
}

/// Kajiya and Kay 1989 in the crate's contract:
/// `S = k_d cos(theta_i) + k_s max(cos(theta_i + theta_o), 0)^n` (module docs: the survey's
/// `S_M = k_d + k_s cos^n(theta_o + theta_i) / cos theta_i` times cos theta_i).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct KajiyaKay<R> {
    uniforms: KajiyaKayUniforms<R>,
}

impl KajiyaKay<f64> {
    /// The model of `params`.
    ///
    /// # Errors
    /// [`ParamError::OutOfRange`] naming the first input outside its domain.
    pub fn new(params: &KajiyaKayParams) -> Result<Self, ParamError> {
        let mut values = InputValues::new();
        values.set("kd", InputValue::Rgb(params.kd));
        values.set("ks", InputValue::Rgb(params.ks));
        values.set("exponent", InputValue::Number(params.exponent));
        Self::from_inputs(&values)
    }
}

impl<R: Real> KajiyaKay<R> {
    /// `[diffuse, specular]` per channel.
    #[inline(always)]
    fn terms(&self, query: &Query<R>) -> [[R; 3]; 2] {
        let u = &self.uniforms;
        let (_, cos_i) = local_sin_cos_theta(query.wi);
        let (cos_sum, _) = sum_angle(query.wi, query.wo);
        let (cos_i, cos_sum) = (cos_i.label("cos_theta_i"), cos_sum.label("cos_sum"));
        [
            scale3(u.kd, cos_i),
            scale3(u.ks, positive_power(cos_sum, u.exponent)),
        ]
    }
}

impl<R: Real> Bcsdf<R> for KajiyaKay<R> {
    fn lobe_names(&self) -> &'static [&'static str] {
        &KAJIYA_KAY_LOBES
    }

    fn eval_lobes(&self, query: &Query<R>) -> Vec<[R; 3]> {
        self.terms(query).to_vec()
    }

    #[inline(always)]
    fn eval(&self, query: &Query<R>) -> [R; 3] {
        sum_lobes(&self.terms(query))
    }
}

impl Model for KajiyaKay<f64> {
    const INLINED_KERNEL: bool = true;
    type Uniforms<R: Real> = KajiyaKayUniforms<R>;
    type In<R: Real> = KajiyaKay<R>;

    fn uniforms(&self) -> KajiyaKayUniforms<f64> {
        self.uniforms
    }

    fn with_uniforms<R: Real>(&self, uniforms: KajiyaKayUniforms<R>) -> KajiyaKay<R> {
        KajiyaKay { uniforms }
    }
}

impl FromInputs for KajiyaKay<f64> {
    const NAME: &'static str = "kajiya-kay";
    const SUMMARY: &'static str = "Kajiya and Kay 1989 as the survey writes it: a diffuse k_d \
        cos(theta_i) and one specular cone k_s cos^n(theta_i + theta_o), no cosine factor";
    const INPUTS: &'static [Input] = &[
        KD,
        Input {
            name: "ks",
            kind: InputKind::Rgb,
            help: "specular weight k_s, linear RGB, each channel in [0, 1e6]",
            default: None,
            conflicts_with: &[],
        },
        Input {
            name: "exponent",
            kind: InputKind::Number,
            help: "specular exponent n of cos^n(theta_i + theta_o), in (0, 1e6]",
            default: None,
            conflicts_with: &[],
        },
    ];

    fn from_inputs(values: &InputValues) -> Result<Self, ParamError> {
        weight_input(values, "kd")?;
        weight_input(values, "ks")?;
        exponent_input(values, "exponent")?;
        Ok(KajiyaKay {
            uniforms: Self::uniforms_in(&InputsIn::constant(values)),
        })
    }
}

impl VaryingInputs for KajiyaKay<f64> {
    const NAME: &'static str = <Self as FromInputs>::NAME;
    const INPUTS: &'static [Input] = <Self as FromInputs>::INPUTS;
    const VARYING: &'static [&'static str] = &["kd", "ks", "exponent"];
    const BAKED: &'static [(&'static str, &'static str)] = &[];

    /// The inputs themselves (a weight clamped to [0, 1e6], an exponent to (0, 1e6]).
    fn uniforms_in<R: Real>(inputs: &InputsIn<R>) -> KajiyaKayUniforms<R> {
        KajiyaKayUniforms {
            kd: weight_in(inputs, "kd"),
            ks: weight_in(inputs, "ks"),
            exponent: exponent_in(inputs, "exponent"),
        }
    }
}

impl Approximation for KajiyaKay<f64> {
    /// The module's mapping: `n = 1 / v_0`, `k_s` the energy of R and TRT, `k_d` that of TT
    /// and the residual, at theta_o = 0.
    fn mapped_inputs(hair: &HairParams) -> InputValues {
        let energies = ReferenceEnergies::of(hair);
        let exponent = (1.0 / longitudinal_variance(hair.beta_m.get())).min(MAX_EXPONENT);
        let ks = weight_for(
            add_rgb(energies.r, energies.trt),
            cone_albedo(exponent, 0.0),
        );
        let kd = weight_for(
            add_rgb(energies.tt, energies.residual),
            KAJIYA_KAY_DIFFUSE_ALBEDO,
        );
        let mut values = InputValues::new();
        values.set("kd", InputValue::Rgb(kd));
        values.set("ks", InputValue::Rgb(ks));
        values.set("exponent", InputValue::Number(exponent));
        values
    }

    const FITTED_INPUTS: &'static [&'static str] = &["kd", "ks", "exponent"];
}

// ---------------------------------------------------------------------------------------------
// TressFX.

crate::uniform_block! {
    /// The uniforms of [`TressFx`].
    pub struct TressFxUniforms<R> {
        /// Diffuse weight k_d per channel.
        pub kd: [R; 3],
        /// The primary cone's weight per channel.
        pub ks_primary: [R; 3],
        /// The primary cone's exponent.
        pub exponent_primary: R,
        /// cos d_1 of the primary cone's deviation.
        pub cos_shift_primary: R,
        /// sin d_1.
        pub sin_shift_primary: R,
        /// The secondary cone's weight per channel.
        pub ks_secondary: [R; 3],
        /// The secondary cone's exponent.
        pub exponent_secondary: R,
        /// cos d_2 of the secondary cone's deviation.
        pub cos_shift_secondary: R,
        /// sin d_2.
        pub sin_shift_secondary: R,
    }
}

/// One specular cone of [`TressFx`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TressFxCone {
    /// Weight per channel, each in [0, 1e6].
    pub weight: Rgb,
    /// Exponent in (0, 1e6].
    pub exponent: f64,
    /// Deviation from the mirror cone, radians (finite): towards +u for the primary, towards
    /// -u for the secondary (module docs).
    pub shift: f64,
}

/// The validated inputs of [`TressFx`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TressFxParams {
    /// Diffuse weight k_d per channel, each in [0, 1e6].
    pub kd: Rgb,
    /// The primary cone, peak at theta_i + theta_o = +shift.
    pub primary: TressFxCone,
    /// The secondary (tinted) cone, peak at theta_i + theta_o = -shift.
    pub secondary: TressFxCone,
}

/// The two-cone Kajiya-Kay form (TressFX):
/// `S = k_d cos theta_i + k_1 max(cos(theta_i + theta_o - d_1), 0)^n_1
///      + k_2 max(cos(theta_i + theta_o + d_2), 0)^n_2` (module docs).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TressFx<R> {
    uniforms: TressFxUniforms<R>,
}

impl TressFx<f64> {
    /// The model of `params`.
    ///
    /// # Errors
    /// [`ParamError::OutOfRange`] naming the first input outside its domain.
    pub fn new(params: &TressFxParams) -> Result<Self, ParamError> {
        Self::from_inputs(&tressfx_values(params))
    }
}

/// The input values of `params`.
fn tressfx_values(params: &TressFxParams) -> InputValues {
    let mut values = InputValues::new();
    values.set("kd", InputValue::Rgb(params.kd));
    for (cone, [weight, exponent, shift]) in [
        (
            params.primary,
            ["ks_primary", "exponent_primary", "shift_primary"],
        ),
        (
            params.secondary,
            ["ks_secondary", "exponent_secondary", "shift_secondary"],
        ),
    ] {
        values.set(weight, InputValue::Rgb(cone.weight));
        values.set(exponent, InputValue::Number(cone.exponent));
        values.set(shift, InputValue::Number(cone.shift));
    }
    values
}

impl<R: Real> TressFx<R> {
    /// `[diffuse, primary, secondary]` per channel.
    #[inline(always)]
    fn terms(&self, query: &Query<R>) -> [[R; 3]; 3] {
        let u = &self.uniforms;
        let (_, cos_i) = local_sin_cos_theta(query.wi);
        let (cos_sum, sin_sum) = sum_angle(query.wi, query.wo);
        let cos_i = cos_i.label("cos_theta_i");
        // cos(theta_i + theta_o - d_1) and cos(theta_i + theta_o + d_2).
        let primary =
            (cos_sum * u.cos_shift_primary + sin_sum * u.sin_shift_primary).label("cos_primary");
        let secondary = (cos_sum * u.cos_shift_secondary - sin_sum * u.sin_shift_secondary)
            .label("cos_secondary");
        [
            scale3(u.kd, cos_i),
            scale3(u.ks_primary, positive_power(primary, u.exponent_primary)),
            scale3(
                u.ks_secondary,
                positive_power(secondary, u.exponent_secondary),
            ),
        ]
    }
}

impl<R: Real> Bcsdf<R> for TressFx<R> {
    fn lobe_names(&self) -> &'static [&'static str] {
        &TRESSFX_LOBES
    }

    fn eval_lobes(&self, query: &Query<R>) -> Vec<[R; 3]> {
        self.terms(query).to_vec()
    }

    #[inline(always)]
    fn eval(&self, query: &Query<R>) -> [R; 3] {
        sum_lobes(&self.terms(query))
    }
}

impl Model for TressFx<f64> {
    const INLINED_KERNEL: bool = true;
    type Uniforms<R: Real> = TressFxUniforms<R>;
    type In<R: Real> = TressFx<R>;

    fn uniforms(&self) -> TressFxUniforms<f64> {
        self.uniforms
    }

    fn with_uniforms<R: Real>(&self, uniforms: TressFxUniforms<R>) -> TressFx<R> {
        TressFx { uniforms }
    }
}

impl FromInputs for TressFx<f64> {
    const NAME: &'static str = "tressfx";
    const SUMMARY: &'static str = "the two-cone Kajiya-Kay form of TressFX: a diffuse term, a \
        primary cone shifted towards the root and a tinted secondary cone shifted towards the tip";
    const INPUTS: &'static [Input] = &[
        KD,
        KS_PRIMARY,
        EXPONENT_PRIMARY,
        Input {
            name: "shift_primary",
            kind: InputKind::Angle,
            help: "deviation of the primary cone from the mirror cone, towards the root: its \
                   peak is at theta_i + theta_o = shift (finite)",
            default: None,
            conflicts_with: &[],
        },
        KS_SECONDARY,
        EXPONENT_SECONDARY,
        Input {
            name: "shift_secondary",
            kind: InputKind::Angle,
            help: "deviation of the secondary cone from the mirror cone, towards the tip: its \
                   peak is at theta_i + theta_o = -shift (finite)",
            default: None,
            conflicts_with: &[],
        },
    ];

    fn from_inputs(values: &InputValues) -> Result<Self, ParamError> {
        let allowed = "the shift must be a finite angle";
        finite_input(values, "shift_primary", allowed)?;
        finite_input(values, "shift_secondary", allowed)?;
        for name in ["kd", "ks_primary", "ks_secondary"] {
            weight_input(values, name)?;
        }
        exponent_input(values, "exponent_primary")?;
        exponent_input(values, "exponent_secondary")?;
        Ok(TressFx {
            uniforms: Self::uniforms_in(&InputsIn::constant(values)),
        })
    }
}

impl VaryingInputs for TressFx<f64> {
    const NAME: &'static str = <Self as FromInputs>::NAME;
    const INPUTS: &'static [Input] = <Self as FromInputs>::INPUTS;
    const VARYING: &'static [&'static str] = &[
        "kd",
        "ks_primary",
        "exponent_primary",
        "shift_primary",
        "ks_secondary",
        "exponent_secondary",
        "shift_secondary",
    ];
    const BAKED: &'static [(&'static str, &'static str)] = &[];

    /// The weights and exponents themselves (clamped as Kajiya-Kay's), the cosine and sine
    /// of each shift wrapped into [-pi, pi] ([`wrap_angle`]: exact for shifts already there,
    /// and the range where shader `sin` and `cos` are accurate).
    fn uniforms_in<R: Real>(inputs: &InputsIn<R>) -> TressFxUniforms<R> {
        let shift_primary = wrap_angle(inputs.number("shift_primary"));
        let shift_secondary = wrap_angle(inputs.number("shift_secondary"));
        TressFxUniforms {
            kd: weight_in(inputs, "kd"),
            ks_primary: weight_in(inputs, "ks_primary"),
            exponent_primary: exponent_in(inputs, "exponent_primary"),
            cos_shift_primary: shift_primary.cos(),
            sin_shift_primary: shift_primary.sin(),
            ks_secondary: weight_in(inputs, "ks_secondary"),
            exponent_secondary: exponent_in(inputs, "exponent_secondary"),
            cos_shift_secondary: shift_secondary.cos(),
            sin_shift_secondary: shift_secondary.sin(),
        }
    }
}

impl Approximation for TressFx<f64> {
    /// The module's mapping: `n_1 = 1 / v_0`, `n_2 = 1 / (4 v_0)`, `d_1 = 2 alpha`,
    /// `d_2 = 4 alpha`, `k_1` the energy of R, `k_2` that of TRT, `k_d` that of TT and the
    /// residual, at theta_o = 0.
    fn mapped_inputs(hair: &HairParams) -> InputValues {
        let energies = ReferenceEnergies::of(hair);
        let v0 = longitudinal_variance(hair.beta_m.get());
        let alpha = hair.alpha.get();
        let cone = |energy: Rgb, variance: f64, shift: f64, sign: f64| {
            let exponent = (1.0 / variance).min(MAX_EXPONENT);
            TressFxCone {
                weight: weight_for(energy, cone_albedo(exponent, sign * shift)),
                exponent,
                shift,
            }
        };
        tressfx_values(&TressFxParams {
            kd: weight_for(
                add_rgb(energies.tt, energies.residual),
                KAJIYA_KAY_DIFFUSE_ALBEDO,
            ),
            primary: cone(energies.r, v0, 2.0 * alpha, 1.0),
            secondary: cone(energies.trt, 4.0 * v0, 4.0 * alpha, -1.0),
        })
    }

    const FITTED_INPUTS: &'static [&'static str] = &[
        "kd",
        "ks_primary",
        "exponent_primary",
        "shift_primary",
        "ks_secondary",
        "exponent_secondary",
        "shift_secondary",
    ];
}
