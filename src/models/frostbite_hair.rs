//! Tafuri 2019, "Strand-based Hair Rendering in Frostbite" (SIGGRAPH 2019 Advances in
//! Real-Time Rendering course, seed `frostbite-strand-hair-siggraph2019.txt`, slides 12-21):
//! R + TT + TRT with Karis' R, a per-slice Gaussian TT distribution read from a 2D table and
//! Karis' TRT distribution scaled by the azimuthal roughness, the transmitted lobes attenuated
//! at a single offset h. One structure ([`FrostbiteHair`]) in two variants: the slides'
//! offsets ([`Frostbite`], `--model frostbite`) and hairmath's refitted ones
//! ([`FrostbiteRefit`], `--model frostbite-refit`).
//!
//! # Source equations
//!
//! With `s = sin theta_i + sin theta_o`, the relative azimuth phi and the hair's beta_m,
//! beta_n, alpha, eta and sigma_a, each lobe is `M_p N_p`:
//!
//! - **Longitudinal** (slide 12): one Gaussian per path with Marschner's widths and shifts,
//!   `M_R = g(beta; theta_h - alpha)`, `M_TT = g(beta/2; theta_h + alpha/2)`,
//!   `M_TRT = g(2 beta; theta_h + 3 alpha/2)`. hairmath evaluates them as Karis 2016 does
//!   (`Hair_g` of UE's `HairShading`, [`crate::models::Karis`]): Gaussians
//!   [`gaussian_lobe`]`(B_p, s - c_p)` in the sum of sines, with `B_R = B`, `B_TT = B/2`,
//!   `B_TRT = 2 B` and centres `c_p = 2 sin(alpha_p)` for `alpha_R = alpha`,
//!   `alpha_TT = -alpha/2`, `alpha_TRT = -3 alpha/2` (the sum of sines at theta_h = alpha_p,
//!   theta_d = 0; `s = 2 sin theta_h cos theta_d`, so for small angles
//!   `g(B_p; s - c_p) = g(B_p/2; theta_h - alpha_p) / 2`: the slides' lobe, normalised, see
//!   "Cosine factors"). `B` follows from beta_m ("Inputs").
//! - **R** (slide 14): `N_R = D_R A_R`, `D_R = cos(phi/2) / 4` (Karis 2016) and
//!   `A_R = F(eta, sqrt(1/2 (1 + wi . wo)))`, Schlick's Fresnel at the cosine of half the
//!   angle between the 3D directions, the exact angle of incidence of the mirror reflection.
//!   This is `HairShading`'s R factor unchanged (UE already evaluates `Hair_F` on the 3D
//!   vectors), shared with the `karis` model; the separable width `sqrt(2) cos(phi/2)` and the
//!   tilted-cone shift of UE's R are UE's, not the slides', and are left out.
//! - **TT** (slides 17-20): `N_TT = A_TT(h_TT) D_TT(phi)`. `A_TT` is Chiang et al. 2016's
//!   attenuation `A_1(h)` for the ray inclined at theta_o (the inclination Chiang's far field
//!   evaluates it at) with the chord transmittance ([`super::offset_attenuation`]; the path
//!   through the fibre is traced once for the three channels), at h_TT = 0 for
//!   `frostbite` (slide 20) and the refit [`crate::models::FROSTBITE_TT_OFFSET_H`] for
//!   `frostbite-refit`. `D_TT = a exp(-b (|phi| - pi)^2)` ([`tt_gaussian`], slide 19), `(a, b)`
//!   looked up at `(|theta_o|, beta_n)` in the 9 x 10 table of the fitted slices
//!   ([`crate::models::FROSTBITE_TT_GAUSSIAN_A`], `_B`; theta_o in 0..80 degrees, beta_n in
//!   0.1..1), one fetch of a two-channel texture ([`frostbite_tt_table`], bilinear, clamped
//!   to the edge: theta_o beyond 80 degrees reads the 80-degree slice, beta_n below 0.1 the
//!   0.1 column). `D_TT` is even in theta_o (Bravais' index is), hence `|theta_o|`.
//! - **TRT** (slide 21): `N_TRT = A_TRT(h_TRT) D_TRT(phi)`, `A_TRT = A_2(h)` at
//!   h_TRT = sqrt(3)/2 (`frostbite`) or the refit [`crate::models::FROSTBITE_TRT_OFFSET_H`]
//!   (`frostbite-refit`), and `D_TRT = s_r exp(s_r (17 cos phi - 16.78))` ([`d_trt_frostbite`]
//!   with Karis' published D_TRT), `s_r = clamp(1.5 (1 - beta_n), 0, 1)`
//!   ([`frostbite_trt_scale`]). `s_r` scales the lobe's height with its exponent, so the TRT
//!   energy falls with beta_n and vanishes at beta_n = 1 (README errata).
//!
//! # Frame
//!
//! hairmath's (README, "Conventions"): tangent +X from root to tip, `sin theta = w.x`,
//! phi = phi_o - phi_i in [-pi, pi] ([`local_fibre_angles`]; 0 when a direction is along the
//! tangent), `wi` towards the light and `wo` towards the viewer. The slides' alpha is Chiang's
//! (positive, 2 degrees typical): in this frame Chiang's R lobe peaks at theta_h = +alpha, TT
//! at -alpha/2, TRT at -2 alpha; the slides' (Marschner's) TRT at -3 alpha / 2.
//!
//! # Cosine factors
//!
//! The slides write each lobe as the product of slide 12's `M_p` and slide 13's
//! `N_p = 1/2 int A_p(h) D_p(phi - Phi(p, h)) dh`, which is Chiang et al. 2016's azimuthal
//! function, the one of Chiang's `S = sum_p M_p N_p` (pbrt's `f = S / |cos theta_i|`), whose
//! radiance is `int S L_i dw_i`: no `cos theta_i`, and no Marschner `1 / cos^2 theta_d`
//! (the slides show neither). In that product `M_p` must be a density in `sin theta_i` (the
//! measure `cos theta_i d theta_i` of the solid angle), as d'Eon's lobe in Chiang's S is.
//! Karis' Gaussian in the sum of sines is one (to the truncation of its tails at |s| = 2), so
//! [`Bcsdf::eval`] returns `sum_p M_p N_p` as it stands, the crate's S. The slides' unit-area
//! Gaussian in theta_h read literally in the same product would carry
//! `int M cos theta_i d theta_i -> 2` (theta_h moves at half the rate of theta_i): twice
//! Chiang's longitudinal energy at theta_o = 0 (README errata).
//!
//! # Inputs
//!
//! Exactly [`HAIR_INPUTS`], the flags of `--model chiang-far`: `beta_m` and `beta_n` (Chiang's
//! roughnesses, in [1e-16, 1]), `alpha` (cuticle tilt, |alpha| < 90 degrees), `eta` ((1, 3]),
//! `sigma_a` (absorption per unit fibre radius; a colour is inverted with Chiang's mapping at
//! the given beta_n). The slides use Chiang's parameters by name (beta_m, beta_n of the
//! Disney reference they compare with at equal values; the TT table is fitted to Chiang's
//! D_TT over Chiang's beta_n), and hairmath gives them Chiang's meaning:
//!
//! - beta_n is the TT table's coordinate and gives `s_r`, as on slides 19 and 21.
//! - beta_m gives the longitudinal width. The slides write `g(beta_m; theta_h - alpha)`
//!   without saying how their beta_m becomes a Gaussian's standard deviation; taken as radians
//!   of theta_h it would make the lobe 2.2 times wider than Chiang's at beta_m = 0.3 (0.3
//!   against 0.14). hairmath uses the width that matches Chiang's R lobe, the mapping of the
//!   `karis` model's Roughness (its module documentation derives it): the standard deviation
//!   in `sin theta_i` of Chiang's R lobe at normal incidence, `B = sqrt(v coth(1/v) - v^2)`,
//!   `v` = [`crate::bcsdf::longitudinal_variance`] (Chiang eq. 7); in theta_h that is
//!   `B / 2 ~ sqrt(v) / 2`, the width Marschner's lobe needs (as `marschner_inputs_of`
//!   maps it). `B` is floored at 1e-6 (the lobe stays finite in `f32`). At beta_m = 0.3:
//!   `v = 0.0846`, `B = 0.278`. Chiang's TT and TRT variances v/4 and 4v are Marschner's
//!   B/2 and 2B in the small-v limit. Like UE's, the lobe does not narrow in `s` with
//!   `cos theta_o` as Chiang's does.
//! - alpha shifts the lobes (above), eta is Schlick's `F0 = ((eta - 1)/(eta + 1))^2` in `A_R`
//!   and the index of the attenuations (floored at `1 + 2^-20`, so that it stays above 1 in
//!   `f32`); sigma_a absorbs in `A_TT` and `A_TRT`, clamped at 1e30 per radius (the uniforms
//!   stay finite in `f32`).
//!
//! # Accuracy
//!
//! Against Chiang's far field (`hairmath models --dark-brown`: dark brown hair, eumelanin 3,
//! beta_m = beta_n = 0.3), E = 0.69 at the mapped inputs for both variants, 0.59 at the fitted
//! ones (beta_m 0.14, beta_n 0.44). Nearly all of it is the R lobe at grazing theta_o (70% of
//! the squared error from theta_o > 70 degrees), where Chiang's lobe narrows in `s` and the
//! Gaussian of fixed width does not; the albedo is 13%, 25% and 75% low at theta_o = 0, 45 and
//! 80 degrees. TT's error is 0.21 of its own size, so the refitted offsets change E in the
//! third digit. (A Gaussian in theta_h itself, halved and converted with Marschner's
//! `cos theta_i / cos^2 theta_d`, measured 0.36 for dark brown hair and better at
//! beta_m <= 0.3, but worse at beta_m = 0.6 and divergent where theta_d -> 90 degrees; hairmath
//! keeps Karis' form.)
//!
//! # Mapping from the physical parameters ([`Approximation::mapped_inputs`])
//!
//! The hair's own parameters (sigma_a as given, [`AbsorptionInput::SigmaA`]): the inputs
//! already have Chiang's meaning and the model converts them as above.
//! [`Approximation::FITTED_INPUTS`]: `beta_m`, `beta_n`, `sigma_a` (the three that shape the
//! lobes' widths, the TT and TRT distributions and the colour; alpha and eta only shift the
//! lobes and scale the Fresnel terms).
//!
//! # Varying in shader code
//!
//! ([`crate::bcsdf::VaryingInputs`]) Every input: `beta_m`, `beta_n` (also the TT table's
//! coordinate, read where the shader computes it), `alpha`, `eta` and the absorption
//! (`sigma_a`, `color` or `eumelanin` and `pheomelanin`, the form it is given in); nothing is
//! baked (the TT table is the same for every hair). Out of their domains the inputs are
//! clamped as Chiang's ([`crate::bcsdf::ChiangHair`]).

use core::marker::PhantomData;
use std::sync::OnceLock;

use super::approximation::Approximation;
use super::constants::{
    FROSTBITE_TT_BETA_N, FROSTBITE_TT_GAUSSIAN_A, FROSTBITE_TT_GAUSSIAN_B, FROSTBITE_TT_THETA_O,
};
use super::frostbite::{tt_gaussian, Transmitted};
use super::karis::{ExpCosCoefficients, KARIS_D_TRT_TABLE};
use super::unreal::{chiang_r_width_in_sines, r_azimuthal, Published, Refitted};
use crate::absorption::PathLength;
use crate::azimuthal::Refraction;
use crate::bcsdf::{
    eta_in, roughness_in, sum_lobes, tilt_in, Bcsdf, FromInputs, Input, InputValues, InputsIn,
    Model, Query, VaryingInputs, HAIR_INPUTS,
};
use crate::error::ParamError;
use crate::geometry::local_fibre_angles;
use crate::lobe::gaussian_lobe;
use crate::lut::{Axis, ParamValue, SharedTable, Table, TableMeta};
use crate::params::{AzimuthalRoughness, HairParams};
use crate::real::MapInline;
use crate::real::{NamedConstant, Real};

/// The lobes of the Frostbite models, in the order of [`Bcsdf::eval_lobes`].
pub const FROSTBITE_LOBES: [&str; 3] = ["R", "TT", "TRT"];

/// The R lobe's width `B` in the sum of sines is floored here (module documentation, "Inputs").
const MIN_WIDTH: f64 = 1e-6;
/// Absorption above this (per radius) is clamped, so that `f32` uniforms stay finite.
const MAX_SIGMA_A: f64 = 1e30;
/// eta is floored here, `1 + 2^-20`, so that it stays above 1 when the uniforms are rounded to
/// `f32` (at eta = 1 the refraction of a grazing ray is 0/0 in the attenuations).
const MIN_ETA: f64 = 1.0 + 1.0 / 1_048_576.0;

/// A variant of the Frostbite model: the offsets at which the transmitted lobes' attenuations
/// are evaluated (a type, so that each variant is a model of its own with its own name, and
/// the offsets are named constants of its shader code).
pub trait FrostbiteVariant: Copy + core::fmt::Debug + 'static {
    /// h of `A_TT`.
    const TT_OFFSET: &'static NamedConstant;
    /// h of `A_TRT`.
    const TRT_OFFSET: &'static NamedConstant;
}

/// The slides' h_TT = 0 ([`Transmitted::published_offset`]).
const SLIDES_TT_OFFSET: NamedConstant = NamedConstant {
    name: "TT_OFFSET",
    meaning: "h_TT = 0, the offset of Frostbite's TT attenuation (Tafuri 2019, slide 20)",
    values: &[Transmitted::Tt.published_offset()],
};
/// The slides' h_TRT = sqrt(3)/2 ([`Transmitted::published_offset`]).
const SLIDES_TRT_OFFSET: NamedConstant = NamedConstant {
    name: "TRT_OFFSET",
    meaning: "h_TRT = sqrt(3)/2, the offset of Frostbite's TRT attenuation (slide 21)",
    values: &[Transmitted::Trt.published_offset()],
};
/// hairmath's refitted h_TT ([`Transmitted::refit_offset`]).
const REFIT_TT_OFFSET: NamedConstant = NamedConstant {
    name: "REFIT_TT_OFFSET",
    meaning: "h_TT whose attenuation is closest to the h-average (hairmath's refit, eta 1.55)",
    values: &[Transmitted::Tt.refit_offset()],
};
/// hairmath's refitted h_TRT ([`Transmitted::refit_offset`]).
const REFIT_TRT_OFFSET: NamedConstant = NamedConstant {
    name: "REFIT_TRT_OFFSET",
    meaning: "h_TRT whose attenuation is closest to the h-average (hairmath's refit, eta 1.55)",
    values: &[Transmitted::Trt.refit_offset()],
};

/// The slides' offsets, h_TT = 0 and h_TRT = sqrt(3)/2 ([`Transmitted::published_offset`]):
/// [`Frostbite`].
impl FrostbiteVariant for Published {
    const TT_OFFSET: &'static NamedConstant = &SLIDES_TT_OFFSET;
    const TRT_OFFSET: &'static NamedConstant = &SLIDES_TRT_OFFSET;
}

/// hairmath's refitted offsets, 0.600 and 0.719 ([`Transmitted::refit_offset`]):
/// [`FrostbiteRefit`].
impl FrostbiteVariant for Refitted {
    const TT_OFFSET: &'static NamedConstant = &REFIT_TT_OFFSET;
    const TRT_OFFSET: &'static NamedConstant = &REFIT_TRT_OFFSET;
}

/// Frostbite's TRT roughness factor `s_r = clamp(1.5 (1 - beta_n), 0, 1)` (Tafuri 2019,
/// slide 21, "manually fitted to approximate the effect of roughness"; the slide's one-argument
/// `clamp` read as HLSL's `saturate`): 1 for beta_n <= 1/3, falling linearly to 0 at
/// beta_n = 1.
pub fn frostbite_trt_scale(beta_n: AzimuthalRoughness) -> f64 {
    trt_scale_of(beta_n.get())
}

/// [`frostbite_trt_scale`] in precision `R` (Tafuri 2019, slide 21).
pub(crate) fn trt_scale_of<R: Real>(beta_n: R) -> R {
    (R::c(1.5) * (R::c(1.0) - beta_n)).clamp(R::c(0.0), R::c(1.0))
}

/// Frostbite's TRT distribution `D_TRT(phi) = s_r exp(s_r (a cos phi + b))` (Tafuri 2019,
/// slide 21): Karis' `exp(a cos phi + b)` ([`crate::models::d_karis_of_cos`]; slide 21 uses
/// [`ExpCosCoefficients::PUBLISHED_D_TRT`], `17 cos phi - 16.78`) with its exponent and its
/// height scaled by `s_r` ([`frostbite_trt_scale`]), from `cos_phi` in [-1, 1].
///
/// Domain: `s_r` in [0, 1]; the result is finite and non-negative, 0 at `s_r = 0`. Its
/// integral over phi is `2 pi s_r I0(a s_r) e^(b s_r)`: 0.763 at `s_r = 1` (Karis'
/// lobe), 0.544 at 0.6 (beta_n = 0.6), 0.260 at 0.15 (beta_n = 0.9).
#[inline(always)]
pub fn d_trt_frostbite<R: Real>(cos_phi: R, s_r: R, c: ExpCosCoefficients<R>) -> R {
    s_r * (s_r * (c.a * cos_phi + c.b)).exp()
}

/// The 2D table of Frostbite's TT Gaussians (slide 19): channels `a` and `b` of
/// [`tt_gaussian`] over `theta_o` (radians, axis 0, [`FROSTBITE_TT_THETA_O`]) and `beta_n`
/// (axis 1, [`FROSTBITE_TT_BETA_N`]), from [`FROSTBITE_TT_GAUSSIAN_A`] and
/// [`FROSTBITE_TT_GAUSSIAN_B`] rounded to `f32`. Built once and shared: every Frostbite model
/// reads the same texture.
pub fn frostbite_tt_table() -> SharedTable<2, 2> {
    static TABLE: OnceLock<SharedTable<2, 2>> = OnceLock::new();
    TABLE.get_or_init(build_tt_table).clone()
}

fn build_tt_table() -> SharedTable<2, 2> {
    let (theta_o, beta_n) = (&FROSTBITE_TT_THETA_O, &FROSTBITE_TT_BETA_N);
    let axis = |name: &str, v: &[f64]| Axis::new(name, v[0], v[v.len() - 1], v.len());
    let axes = axis("theta_o", theta_o).and_then(|t| Ok(vec![t, axis("beta_n", beta_n)?]));
    let mut data = Vec::with_capacity(theta_o.len() * beta_n.len() * 2);
    for j in 0..beta_n.len() {
        for i in 0..theta_o.len() {
            data.push(FROSTBITE_TT_GAUSSIAN_A[i][j] as f32);
            data.push(FROSTBITE_TT_GAUSSIAN_B[i][j] as f32);
        }
    }
    let meta = TableMeta {
        kind: "frostbite_tt".to_string(),
        description: "Frostbite's TT distribution a exp(-b (|phi| - pi)^2) per (theta_o, \
                      beta_n) slice (Tafuri 2019, slide 19): a, b (rad^-2)"
            .to_string(),
        parameters: vec![("eta".to_string(), ParamValue::Number(1.55))],
        png_scale: Vec::new(),
    };
    axes.and_then(|axes| Table::new(axes, vec!["a".into(), "b".into()], data))
        .and_then(|table| table.with_meta(meta))
        .and_then(SharedTable::new)
        .unwrap_or_else(|e| unreachable!("the fitted tables have a valid shape: {e}"))
}

crate::uniform_block! {
    /// The derived constants of the Frostbite models ([`FrostbiteHair::new`]).
    pub struct FrostbiteUniforms<R> {
        /// `B`, the R lobe's standard deviation in `sin theta_i + sin theta_o`.
        pub width_r: R,
        /// `B / 2`, TT's.
        pub width_tt: R,
        /// `2 B`, TRT's.
        pub width_trt: R,
        /// `2 sin(alpha)`, the R lobe's centre in the sum of sines.
        pub shift_r: R,
        /// `-2 sin(alpha / 2)`, TT's.
        pub shift_tt: R,
        /// `-2 sin(3 alpha / 2)`, TRT's.
        pub shift_trt: R,
        /// The relative index of refraction (floored at `1 + 2^-20`).
        pub eta: R,
        /// Absorption per unit radius (clamped at 1e30).
        pub sigma_a: [R; 3],
        /// beta_n, the TT table's second coordinate.
        pub beta_n: R,
        /// `s_r` of the TRT distribution ([`frostbite_trt_scale`]).
        pub trt_scale: R,
    }
}

/// Frostbite's hair shading (R + TT + TRT) with the offsets of the variant `V`
/// ([`FrostbiteVariant`]); the module documentation gives the equations, the cosine factors,
/// the inputs and the mapping.
#[derive(Clone, Debug, PartialEq)]
pub struct FrostbiteHair<R, V> {
    uniforms: FrostbiteUniforms<R>,
    /// `a`, `b` of the TT Gaussian over (theta_o, beta_n).
    tt_table: SharedTable<2, 2>,
    variant: PhantomData<V>,
}

/// Frostbite 2019 as the slides give it (`--model frostbite`).
pub type Frostbite<R> = FrostbiteHair<R, Published>;

/// The same with the refitted single offsets (`--model frostbite-refit`).
pub type FrostbiteRefit<R> = FrostbiteHair<R, Refitted>;

impl<V: FrostbiteVariant> FrostbiteHair<f64, V> {
    /// The model of the hair `hair`.
    pub fn new(hair: &HairParams) -> Self {
        Self::with_uniforms_of(frostbite_uniforms(
            hair.beta_m.get(),
            hair.beta_n.get(),
            hair.alpha.get(),
            hair.eta.get(),
            hair.sigma_a.rgb(),
        ))
    }

    /// The model reading `uniforms` and the shared TT table.
    fn with_uniforms_of(uniforms: FrostbiteUniforms<f64>) -> Self {
        FrostbiteHair {
            uniforms,
            tt_table: frostbite_tt_table(),
            variant: PhantomData,
        }
    }
}

/// The Frostbite models' uniforms in precision `R` from the hair's parameters (module
/// documentation: the widths from beta_m as Karis' Roughness mapping, the centres
/// `2 sin(alpha_p)`, eta floored at `1 + 2^-20`, sigma_a clamped at 1e30, beta_n and `s_r`):
/// the one derivation of [`FrostbiteHair::new`] and of shader code with varying inputs.
fn frostbite_uniforms<R: Real>(
    beta_m: R,
    beta_n: R,
    alpha: R,
    eta: R,
    sigma_a: [R; 3],
) -> FrostbiteUniforms<R> {
    let width = chiang_r_width_in_sines(beta_m).max(R::c(MIN_WIDTH));
    let two = R::c(2.0);
    FrostbiteUniforms {
        width_r: width,
        width_tt: R::c(0.5) * width,
        width_trt: two * width,
        shift_r: two * alpha.sin(),
        shift_tt: R::c(-2.0) * (R::c(0.5) * alpha).sin(),
        shift_trt: R::c(-2.0) * (R::c(1.5) * alpha).sin(),
        eta: eta.max(R::c(MIN_ETA)),
        sigma_a: sigma_a.map_inline(
            #[inline(always)]
            |s| s.min(R::c(MAX_SIGMA_A)),
        ),
        beta_n,
        trt_scale: trt_scale_of(beta_n),
    }
}

/// The Frostbite models' uniforms from the values of [`HAIR_INPUTS`], clamped as Chiang's.
fn frostbite_uniforms_in<R: Real>(inputs: &InputsIn<R>) -> FrostbiteUniforms<R> {
    let beta_n = roughness_in(inputs.number("beta_n"));
    frostbite_uniforms(
        roughness_in(inputs.number("beta_m")),
        beta_n,
        tilt_in(inputs.number("alpha")),
        eta_in(inputs.number("eta")),
        inputs.absorption("sigma_a").sigma_a(beta_n),
    )
}

impl<R, V> FrostbiteHair<R, V> {
    /// The TT table ([`frostbite_tt_table`]).
    pub fn tt_table(&self) -> &SharedTable<2, 2> {
        &self.tt_table
    }
}

/// The angles of one query that the lobes read.
struct FrostbiteAngles<R> {
    /// `sin theta_i + sin theta_o`.
    sum_of_sines: R,
    /// `sin theta_o`.
    sin_o: R,
    /// `cos theta_o >= 0`.
    cos_o: R,
    /// `|theta_o|`, the TT table's first coordinate.
    abs_theta_o: R,
    /// phi in [-pi, pi].
    phi: R,
    /// `cos phi`.
    cos_phi: R,
    /// `cos(phi / 2) >= 0`.
    cos_half_phi: R,
    /// `wi . wo`.
    v_dot_l: R,
}

impl<R: Real> FrostbiteAngles<R> {
    #[inline(always)]
    fn of(query: &Query<R>) -> Self {
        let a = local_fibre_angles(query.wi, query.wo);
        FrostbiteAngles {
            sum_of_sines: (a.sin_theta_i + a.sin_theta_o).label("sum_of_sines"),
            sin_o: a.sin_theta_o,
            cos_o: a.cos_theta_o,
            abs_theta_o: a.theta_o().abs().label("abs_theta_o"),
            phi: a.phi,
            cos_phi: a.phi.cos().label("cos_phi"),
            cos_half_phi: (R::c(0.5) * a.phi)
                .cos()
                .max(R::c(0.0))
                .label("cos_half_phi"),
            v_dot_l: query.wi.dot(query.wo).label("v_dot_l"),
        }
    }
}

/// The three lobes of one evaluation.
struct FrostbiteLobes<R> {
    /// R, the same in every channel.
    r: R,
    /// TT per channel.
    tt: [R; 3],
    /// TRT per channel.
    trt: [R; 3],
}

impl<R: Real, V: FrostbiteVariant> FrostbiteHair<R, V> {
    /// `M_R N_R` (slides 12 and 14).
    #[inline(always)]
    fn r(&self, a: &FrostbiteAngles<R>) -> R {
        let u = &self.uniforms;
        let mp = gaussian_lobe(u.width_r, a.sum_of_sines - u.shift_r);
        (mp * r_azimuthal(a.cos_half_phi, a.v_dot_l, u.eta)).label("r_lobe")
    }

    /// `A_p(h)` per channel for the ray inclined at theta_o: [`super::offset_attenuation`]'s value,
    /// with the path through the fibre (which does not depend on the channel) traced once.
    #[inline(always)]
    fn attenuation(
        &self,
        path: Transmitted,
        h: &'static NamedConstant,
        a: &FrostbiteAngles<R>,
    ) -> [R; 3] {
        let u = &self.uniforms;
        let inv_eta = (R::c(1.0) / u.eta).label("inv_eta");
        let refraction = Refraction::new(a.sin_o, a.cos_o, u.eta, inv_eta);
        let through = refraction.path(h.get(), PathLength::Chord);
        u.sigma_a.map_inline(
            #[inline(always)]
            |s| through.attenuations(s)[path.p()],
        )
    }

    /// `M_TT A_TT(h_TT) D_TT(phi)` per channel (slides 12, 17-20).
    #[inline(always)]
    fn tt(&self, a: &FrostbiteAngles<R>) -> [R; 3] {
        let u = &self.uniforms;
        let mp = gaussian_lobe(u.width_tt, a.sum_of_sines - u.shift_tt);
        let [height, sharpness] = self.tt_table.sample([a.abs_theta_o, u.beta_n]);
        let lobe = (mp * tt_gaussian(a.phi, height, sharpness)).label("tt_lobe");
        self.attenuation(Transmitted::Tt, V::TT_OFFSET, a)
            .map_inline(
                #[inline(always)]
                |t| lobe * t,
            )
    }

    /// `M_TRT A_TRT(h_TRT) D_TRT(phi)` per channel (slides 12 and 21).
    #[inline(always)]
    fn trt(&self, a: &FrostbiteAngles<R>) -> [R; 3] {
        let u = &self.uniforms;
        let mp = gaussian_lobe(u.width_trt, a.sum_of_sines - u.shift_trt);
        let d = d_trt_frostbite(
            a.cos_phi,
            u.trt_scale,
            ExpCosCoefficients::named(&KARIS_D_TRT_TABLE),
        );
        let lobe = (mp * d).label("trt_lobe");
        self.attenuation(Transmitted::Trt, V::TRT_OFFSET, a)
            .map_inline(
                #[inline(always)]
                |t| lobe * t,
            )
    }

    #[inline(always)]
    fn lobes(&self, query: &Query<R>) -> FrostbiteLobes<R> {
        let a = FrostbiteAngles::of(query);
        FrostbiteLobes {
            r: self.r(&a),
            tt: self.tt(&a),
            trt: self.trt(&a),
        }
    }
}

impl<R: Real, V: FrostbiteVariant> Bcsdf<R> for FrostbiteHair<R, V> {
    fn lobe_names(&self) -> &'static [&'static str] {
        &FROSTBITE_LOBES
    }

    /// `[R, TT, TRT]` per channel.
    fn eval_lobes(&self, query: &Query<R>) -> Vec<[R; 3]> {
        let l = self.lobes(query);
        vec![[l.r; 3], l.tt, l.trt]
    }

    /// `sum_p M_p N_p` per channel, the crate's S as it stands (no cosine factor; module
    /// documentation), without allocating.
    #[inline(always)]
    fn eval(&self, query: &Query<R>) -> [R; 3] {
        let l = self.lobes(query);
        sum_lobes(&[[l.r; 3], l.tt, l.trt])
    }
}

impl<V: FrostbiteVariant> Model for FrostbiteHair<f64, V> {
    const INLINED_KERNEL: bool = true;
    type Uniforms<R: Real> = FrostbiteUniforms<R>;
    type In<R: Real> = FrostbiteHair<R, V>;

    fn uniforms(&self) -> FrostbiteUniforms<f64> {
        self.uniforms
    }

    fn with_uniforms<R: Real>(&self, uniforms: FrostbiteUniforms<R>) -> FrostbiteHair<R, V> {
        FrostbiteHair {
            uniforms,
            tt_table: self.tt_table.clone(),
            variant: PhantomData,
        }
    }
}

impl FromInputs for Frostbite<f64> {
    const NAME: &'static str = "frostbite";
    const SUMMARY: &'static str = "Tafuri 2019 (Frostbite): Karis' R, TT from per-slice Gaussians \
        in a 2D table attenuated at h = 0, TRT Karis' scaled by the roughness factor s_r and \
        attenuated at h = sqrt(3)/2, S(wi, wo)";
    const INPUTS: &'static [Input] = &HAIR_INPUTS;

    fn from_inputs(values: &InputValues) -> Result<Self, ParamError> {
        HairParams::from_inputs(values)?;
        Ok(Self::with_uniforms_of(Self::uniforms_in(
            &InputsIn::constant(values),
        )))
    }
}

impl FromInputs for FrostbiteRefit<f64> {
    const NAME: &'static str = "frostbite-refit";
    const SUMMARY: &'static str = "Frostbite 2019 with hairmath's refitted single offsets of the \
        TT and TRT attenuations (h = 0.600 and 0.719), S(wi, wo)";
    const INPUTS: &'static [Input] = &HAIR_INPUTS;

    fn from_inputs(values: &InputValues) -> Result<Self, ParamError> {
        HairParams::from_inputs(values)?;
        Ok(Self::with_uniforms_of(Self::uniforms_in(
            &InputsIn::constant(values),
        )))
    }
}

/// The inputs of [`HAIR_INPUTS`] in shader code: all of them, the absorption in each form.
const FROSTBITE_VARYING: [&str; 8] = [
    "beta_m",
    "beta_n",
    "alpha",
    "eta",
    "sigma_a",
    "color",
    "eumelanin",
    "pheomelanin",
];

impl VaryingInputs for Frostbite<f64> {
    const NAME: &'static str = <Self as FromInputs>::NAME;
    const INPUTS: &'static [Input] = &HAIR_INPUTS;
    const VARYING: &'static [&'static str] = &FROSTBITE_VARYING;
    const BAKED: &'static [(&'static str, &'static str)] = &[];

    fn uniforms_in<R: Real>(inputs: &InputsIn<R>) -> FrostbiteUniforms<R> {
        frostbite_uniforms_in(inputs)
    }
}

impl VaryingInputs for FrostbiteRefit<f64> {
    const NAME: &'static str = <Self as FromInputs>::NAME;
    const INPUTS: &'static [Input] = &HAIR_INPUTS;
    const VARYING: &'static [&'static str] = &FROSTBITE_VARYING;
    const BAKED: &'static [(&'static str, &'static str)] = &[];

    fn uniforms_in<R: Real>(inputs: &InputsIn<R>) -> FrostbiteUniforms<R> {
        frostbite_uniforms_in(inputs)
    }
}

/// The inputs a fit varies: the roughnesses and the absorption.
const FROSTBITE_FITTED_INPUTS: [&str; 3] = ["beta_m", "beta_n", "sigma_a"];

impl Approximation for Frostbite<f64> {
    /// The hair's own parameters (module documentation).
    fn mapped_inputs(hair: &HairParams) -> InputValues {
        hair.to_inputs()
    }

    const FITTED_INPUTS: &'static [&'static str] = &FROSTBITE_FITTED_INPUTS;
}

impl Approximation for FrostbiteRefit<f64> {
    /// The hair's own parameters (module documentation).
    fn mapped_inputs(hair: &HairParams) -> InputValues {
        hair.to_inputs()
    }

    const FITTED_INPUTS: &'static [&'static str] = &FROSTBITE_FITTED_INPUTS;
}
