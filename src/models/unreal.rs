//! Karis 2016 as Unreal Engine 4.27 ships it: `HairShading` of `HairBsdf.ush`, R + TT + TRT
//! ([`Karis`], `--model karis`), and the same code with hairmath's refitted constants and
//! Chiang's colour mapping at the hair's own beta_n ([`KarisRefit`], `--model karis-refit`).
//!
//! # Source
//!
//! The listing of Unreal Engine 4.27's `HairBsdf.ush` ("UE4.27 源码 / 核心代码") quoted by the
//! survey of hair models from Kajiya-Kay and Marschner to Weta and UE4 that the project started
//! from, with the configuration UE's
//! deferred `HairBxDF` uses for direct lighting: `Specular` = 0.5 (so the R factor
//! `Specular * 2` is 1), `Backlit` = 1 (so `lerp(1, Backlit, saturate(-VoL))` is 1), `Area` = 0,
//! separable R on (`BScale = sqrt(2) CosHalfPhi`), the non-legacy absorption, no multiple
//! scattering and no Kajiya-Kay diffuse, and the final `S = -min(-S, 0)`, i.e. `max(S, 0)`.
//! `asinFast` is replaced by the exact `asin` ([`safe_asin`]). Per lobe, with
//! `s = sin theta_L + sin theta_V` (UE's angles, see the frame below), `c_phi = cos phi`,
//! `c_h = cos(phi/2) = sqrt(saturate(1/2 + c_phi/2))` and `VoL = wo . wi`:
//!
//! - `Hair_g(B, x) = exp(-x^2 / (2 B^2)) / (sqrt(2 pi) B)` ([`gaussian_lobe`]) and Schlick's
//!   `Hair_F(x) = F0 + (1 - F0)(1 - x)^5` with eta = 1.55 ([`fresnel_schlick`]);
//! - widths `B = (r^2, r^2 / 2, 2 r^2)` for R, TT, TRT, `r` the Roughness clamped to
//!   [1/255, 1]; UE's `Shift` = 0.035 rad, lobe shifts `(-2, 1, 4) Shift`;
//! - **R**: `Hair_g(sqrt 2 c_h B_R, s - 2 sin a0 (cos a0 c_h cos theta_V + sin a0 sin theta_V))`
//!   `* c_h / 4 * Hair_F(sqrt(saturate(1/2 + VoL/2)))`, `a0 = Alpha[0] = -2 Shift`;
//! - **TT**: `Hair_g(B_TT, s - Shift) * exp(-3.65 c_phi - 3.98) * (1 - f)^2 * T` with
//!   `a = 1/eta'` ([`inverse_eta_prime_karis`]: `eta' = 1.19 / cos theta_d + 0.36 cos theta_d`),
//!   `h = c_h (1 + a (0.6 - 0.8 c_phi))` ([`h_tt_karis_of_cos`]),
//!   `f = Hair_F(cos theta_d sqrt(saturate(1 - h^2)))` and
//!   `T = exp(-sigma_a 2 |1 - (h a)^2 / cos theta_d|)`, `sigma_a` =
//!   `HairColorToAbsorption(BaseColor)`, Chiang et al. 2016's colour mapping at beta_n = 0.3
//!   ([`Absorption::from_color`]);
//! - **TRT**: `Hair_g(B_TRT, s - 4 Shift) * exp(17 c_phi - 16.78) * (1 - f)^2 f *
//!   BaseColor^(0.8 / cos theta_d)` with `f = Hair_F(cos theta_d / 2)`.
//!
//! The distributions `exp(a c_phi + b)` are [`d_karis_of_cos`]. Three slips of the listing are
//! ported as they are and listed in the README's errata: the TT path `2 |1 - (h a)^2 /
//! cos theta_d|` is not a path length (the legacy branch's `sqrt(1 - (h a)^2) / cos theta_d`
//! is); TRT reads `BaseColor` as a transmittance where TT reads it as the colour of the
//! multiply-scattering volume; and R's exact tilted-cone shift takes the lobe shift
//! `Alpha[0] = -2 Shift` where its formula expects the cuticle tilt, so R is shifted twice as
//! far as the `Alpha` table says (`sin(-4 Shift)` in `s` at normal incidence, against the
//! `-2 Shift` that TT's and TRT's reading of the table gives).
//!
//! # Frame
//!
//! UE's `N` is the tangent pointing to the **root**, the opposite of hairmath's `u` (+X, root
//! to tip), so `N = -X`, `sin theta_L = -wi.x` and `sin theta_V = -wo.x` (UE's `L` is `wi`,
//! its `V` is `wo`). With UE's negative R shift this puts the R peak at
//! `sin theta_i + sin theta_o = sin(4 Shift)` (at theta_o = 0) in hairmath's angles, towards
//! the tip, the side where Chiang's tilt alpha > 0 puts it. `Lp = L - sin theta_L N` is `(0, wi.y, wi.z)` in the local
//! frame (the first component cancels exactly for unit vectors), and UE's
//! `cos phi = Lp . Vp / sqrt(|Lp|^2 |Vp|^2 + 1e-4)` keeps its `1e-4`, which also makes the
//! projections of directions along the tangent harmless (`cos phi = 0` there).
//!
//! # Cosine factors
//!
//! UE's `HairBxDF` returns `FalloffColor * Falloff * HairShading(...)` as the transmission
//! term: the light's irradiance at normal incidence times the shading result, with **no**
//! `N.L` (unlike its surface BxDFs, which multiply by `NoL`), and `Hair_g` is normalised in
//! `sin theta_i`, the measure `cos theta_i d theta_i` of the solid angle. So UE's result is
//! already the crate's S (radiance = integral of S L_i over solid angle): [`Bcsdf::eval`]
//! returns it unchanged.
//!
//! # Inputs
//!
//! - `sigma_a` (kind Absorption): the absorption per unit radius. `--color R,G,B` is UE's
//!   `BaseColor` (linear RGB, each channel in (0, 1]), inverted with Chiang's mapping at
//!   beta_n = 0.3 ([`crate::bcsdf::COLOR_BETA_N`]) as `HairColorToAbsorption` does;
//!   `--sigma-a` or `--melanin` give sigma_a, and the BaseColor TRT uses is then the colour
//!   whose inversion gives it ([`Absorption::to_color`]). Absorption above 1e30 per radius is
//!   clamped there, so that single-precision uniforms stay finite.
//! - `roughness` (Number): UE's Roughness in (0, 1], clamped below at 1/255 as UE does.
//! - `karis-refit` only: `beta_n` (Chiang's azimuthal roughness, in (0, 1]) with which the
//!   colour is inverted instead of 0.3.
//!
//! # Mapping from the physical parameters ([`Approximation::mapped_inputs`])
//!
//! - **BaseColor**: the colour whose Chiang mapping at beta_n = 0.3 gives the hair's sigma_a
//!   (`Absorption::to_color(0.3)`), so TT absorbs with exactly the hair's sigma_a; `karis-refit`
//!   maps at the hair's own beta_n (and takes that beta_n).
//! - **Roughness** from beta_m: UE's `Hair_g(B, s)` is a Gaussian of standard deviation `B`
//!   in the sum of **sines** `s`, normalised in `sin theta_i` (the measure
//!   `cos theta_i d theta_i`); Chiang's longitudinal lobe is d'Eon's with variance `v(beta_m)`
//!   (Chiang eq. 7, [`crate::bcsdf::longitudinal_variance`]), normalised in the same measure,
//!   whose variance parameter is not a variance of either variable (for small v it is the
//!   variance of `theta_i + theta_o`). The mapping matches the two R lobes' second moments in
//!   `sin theta_i` at normal incidence (theta_o = 0, where `s = sin theta_i`). d'Eon's lobe is
//!   a von Mises-Fisher distribution on the sphere of concentration `1/v` integrated over the
//!   cone's azimuth, so there `E[sin^2 theta_i] = v coth(1/v) - v^2` exactly (the vMF's
//!   variance along an axis perpendicular to its mean); hence
//!   `Roughness^4 = B_R^2 = v coth(1/v) - v^2` ([`UnrealRoughness::from_beta_m`]), which is
//!   `v (1 - v)` to within `e^(-2/v)` for small v and tends to 1/3 (the uniform sphere) for
//!   large v, so Roughness stays below 0.76 for every beta_m (and is clamped to UE's 1/255
//!   below). At beta_m = 0.3: `v = 0.0846`, `B_R = 0.278`, Roughness 0.528; the scales differ,
//!   a naive `Roughness = beta_m` would make the lobe 3.1 times narrower. TT and TRT keep UE's
//!   ratios B/2 and 2B, which are Chiang's (variances v/4 and 4v) in the small-v limit. At
//!   inclination theta_o, near the cone `s ~ cos theta_o (theta_i + theta_o)`: Chiang's lobe
//!   narrows in `s` with `cos theta_o`, UE's does not, so UE's lobe is `1/cos theta_o` times
//!   wider in angle there; the fit ([`Approximation::FITTED_INPUTS`]) measures what that
//!   costs.
//! - alpha and eta are not inputs: UE fixes `Shift` = 0.035 rad and eta = 1.55. TT and TRT
//!   peak where Chiang's lobes peak for alpha = `Shift` = 2.0 degrees (theta_h shifted by
//!   `-alpha/2` and `-2 alpha`), R at twice Chiang's shift for that alpha (the third slip
//!   above).
//!
//! # Varying in shader code
//!
//! ([`crate::bcsdf::VaryingInputs`]) Every input: `roughness`, the absorption (`sigma_a`,
//! `color` or `eumelanin` and `pheomelanin`, the form it is given in; the shader inverts a
//! colour and takes the logarithm of BaseColor as [`KarisHair::new`] does) and, for
//! `karis-refit`, `beta_n`; nothing is baked. Out of its domain the Roughness is clamped to
//! [1/255, 1] (UE's own lower clamp) and beta_n as Chiang's ([`crate::bcsdf::MIN_ROUGHNESS`]).

use core::marker::PhantomData;

use super::approximation::Approximation;
use super::karis::{
    d_karis_of_cos, h_tt_karis_of_cos, inverse_eta_prime_karis, EtaPrimeCoefficients,
    ExpCosCoefficients, HTtCoefficients, KARIS_D_TRT_TABLE, KARIS_D_TT_TABLE,
    KARIS_ETA_PRIME_TABLE, KARIS_H_TT_TABLE, REFIT_D_TRT_TABLE, REFIT_D_TT_TABLE,
    REFIT_ETA_PRIME_TABLE, REFIT_H_TT_TABLE,
};
use crate::absorption::log_color_of_sigma_a;
use crate::absorption::Absorption;
use crate::bcsdf::{
    roughness_in, variance_of, AbsorptionInput, Bcsdf, FromInputs, Input, InputKind, InputValue,
    InputValues, InputsIn, Model, Query, VaryingInputs, COLOR_BETA_N, HAIR_INPUTS,
};
use crate::error::ParamError;
use crate::fresnel::fresnel_schlick;
use crate::lobe::gaussian_lobe;
use crate::params::{AzimuthalRoughness, HairParams, LongitudinalRoughness};
use crate::real::MapInline;
use crate::real::{horner, safe_asin, safe_sqrt, NamedConstant, Real, SQRT_2, TINY};

/// The lobes of the Unreal models, in the order of [`Bcsdf::eval_lobes`].
pub const KARIS_LOBES: [&str; 3] = ["R", "TT", "TRT"];

/// UE's `Shift`, the cuticle tilt in radians (`HairShading`): R is shifted by `-2 Shift`, TT
/// by `Shift`, TRT by `4 Shift` ([`TRT_SHIFT`]).
const SHIFT: NamedConstant = NamedConstant {
    name: "SHIFT",
    meaning: "UE's Shift, the cuticle tilt in radians: the TT lobe's shift (HairShading)",
    values: &[0.035],
};
/// `4 Shift`, the TRT lobe's shift.
const TRT_SHIFT: NamedConstant = NamedConstant {
    name: "TRT_SHIFT",
    meaning: "4 Shift, the TRT lobe's shift (HairShading)",
    values: &[4.0 * 0.035],
};
/// `sin` and `cos` of the R lobe's tilt `-2 Shift` (the tests check them against `f64`).
const R_TILT_SIN_COS: NamedConstant = NamedConstant {
    name: "R_TILT_SIN_COS",
    meaning: "sin and cos of -2 Shift, the R lobe's tilt (HairShading)",
    values: &[-0.06994284733753277, 0.9975510002532796],
};
/// The refractive index of `Hair_F` (Schlick's F0 = ((1 - 1.55) / (1 + 1.55))^2).
const ETA: NamedConstant = NamedConstant {
    name: "ETA",
    meaning: "1.55, the refractive index of UE's Hair_F",
    values: &[1.55],
};
/// The TRT lobe's absorption as a power of the BaseColor: `Tp = BaseColor^(0.8 / cos theta_d)`
/// (`HairShading`; exponentiated as `exp(log_color * 0.8 / cos theta_d)`).
const TRT_COLOR_EXPONENT: NamedConstant = NamedConstant {
    name: "TRT_COLOR_EXPONENT",
    meaning: "0.8, the TRT lobe's Tp = BaseColor^(0.8 / cos theta_d) (HairShading)",
    values: &[0.8],
};
/// UE's lower clamp of the Roughness, `1/255`.
const MIN_ROUGHNESS: f64 = 1.0 / 255.0;
/// The regulariser of UE's `cos phi = Lp . Vp * rsqrt(|Lp|^2 |Vp|^2 + 1e-4)`.
const COS_PHI_EPSILON: NamedConstant = NamedConstant {
    name: "COS_PHI_EPSILON",
    meaning: "1e-4, the regulariser of UE's cos phi = Lp.Vp rsqrt(|Lp|^2 |Vp|^2 + 1e-4)",
    values: &[1e-4],
};
/// Absorption above this (per radius) is clamped, so that `f32` uniforms stay finite.
const MAX_SIGMA_A: f64 = 1e30;

/// The fitted constants of one variant of Karis' closed forms: named tables of two
/// coefficients each, which shader code declares as constants.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct KarisConstants {
    /// Bravais' index `eta' ~ a / cos theta_d + b cos theta_d`: `[a, b]`
    /// ([`EtaPrimeCoefficients`]).
    pub eta_prime: &'static NamedConstant,
    /// The TT distribution `exp(a cos phi + b)`: `[a, b]` ([`ExpCosCoefficients`]).
    pub d_tt: &'static NamedConstant,
    /// The TRT distribution `exp(a cos phi + b)`: `[a, b]` ([`ExpCosCoefficients`]).
    pub d_trt: &'static NamedConstant,
    /// The TT offset `(1 + a (c1 - c2 cos phi)) cos(phi/2)`: `[c1, c2]` ([`HTtCoefficients`]).
    pub h_tt: &'static NamedConstant,
}

impl KarisConstants {
    /// UE 4.27's constants (Karis 2016): `1.19, 0.36`; `-3.65, -3.98`; `17, -16.78`;
    /// `0.6, 0.8` ([`EtaPrimeCoefficients::PUBLISHED`] and the other `PUBLISHED` sets).
    pub const PUBLISHED: Self = Self {
        eta_prime: &KARIS_ETA_PRIME_TABLE,
        d_tt: &KARIS_D_TT_TABLE,
        d_trt: &KARIS_D_TRT_TABLE,
        h_tt: &KARIS_H_TT_TABLE,
    };
    /// hairmath's refits of the same closed forms against their exact references
    /// (`src/models/constants.rs`, `hairmath fit`; [`EtaPrimeCoefficients::REFIT`] and the
    /// other `REFIT` sets).
    pub const REFIT: Self = Self {
        eta_prime: &REFIT_ETA_PRIME_TABLE,
        d_tt: &REFIT_D_TT_TABLE,
        d_trt: &REFIT_D_TRT_TABLE,
        h_tt: &REFIT_H_TT_TABLE,
    };
}

/// A variant of the Unreal model: which constants it uses (a type, so that each variant is a
/// model of its own with its own name and inputs, and the constants fold into shader code).
pub trait KarisVariant: Copy + core::fmt::Debug + 'static {
    /// The constants of the closed forms.
    const CONSTANTS: KarisConstants;
}

/// UE 4.27's published constants ([`KarisConstants::PUBLISHED`]): [`Karis`].
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Published;

impl KarisVariant for Published {
    const CONSTANTS: KarisConstants = KarisConstants::PUBLISHED;
}

/// hairmath's refitted constants ([`KarisConstants::REFIT`]): [`KarisRefit`].
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Refitted;

impl KarisVariant for Refitted {
    const CONSTANTS: KarisConstants = KarisConstants::REFIT;
}

/// The series of `(x coth x - 1) / x^2 = 1/3 - x^2/45 + 2 x^4/945 - ...` in `x^2`: its
/// coefficients `2^(2k+2) B_(2k+2) / (2k+2)!` (B the Bernoulli numbers), k = 0 to 9; the
/// next term is below 7e-17 of the sum for x <= 1/2.
const COTH_SERIES: [f64; 10] = [
    1.0 / 3.0,
    -1.0 / 45.0,
    2.0 / 945.0,
    -1.0 / 4725.0,
    2.0 / 93555.0,
    -1382.0 / 638_512_875.0,
    4.0 / 18_243_225.0,
    -3617.0 / 162_820_783_125.0,
    87734.0 / 38_979_295_480_125.0,
    -349_222.0 / 1_531_329_465_290_625.0,
];

/// The standard deviation in `sin theta_i` of Chiang's R lobe at normal incidence (theta_o =
/// 0), `sqrt(v coth(1/v) - v^2)` with `v` from beta_m by Chiang's eq. 7: the second moment of
/// a von Mises-Fisher distribution of concentration `1/v` along an axis perpendicular to its
/// mean (the module documentation derives it). The width a Gaussian in the sum of sines
/// needs to match Chiang's lobe there; below 1/sqrt(3) for every beta_m.
///
/// With `x = 1/v`, `v coth(1/v) - v^2 = (x coth x - 1) / x^2`: for `x >= 1/2` as
/// `v ((1 + e) / (1 - e) - v)`, `e = exp(-2x)` (which loses at most a factor 13 to
/// cancellation, at x = 1/2), below by its series ([`COTH_SERIES`]), where the difference
/// cancels (it tends to 1/3 as v grows while both terms grow like v^2).
pub(crate) fn chiang_r_width_in_sines<R: Real>(beta_m: R) -> R {
    let one = R::c(1.0);
    let v = variance_of(beta_m);
    let x = one / v;
    let e = (R::c(-2.0) * x).exp();
    let direct = v * ((one + e) / (one - e.min(R::c(0.5))) - v);
    let small = x.min(R::c(0.5));
    let series = horner(small * small, &COTH_SERIES);
    safe_sqrt(R::select(x.lt(R::c(0.5)), series, direct))
}

/// Karis 2016's azimuthal R factor `N_R = D_R A_R` as `HairShading` evaluates it:
/// `D_R = cos(phi/2) / 4` and `A_R = F(eta, sqrt(1/2 + wi.wo / 2))`, Schlick's Fresnel
/// ([`fresnel_schlick`]) at the cosine of half the angle between the 3D directions (the angle
/// of incidence of the mirror reflection), from `cos_half_phi = cos(phi/2)` in [0, 1] and
/// `v_dot_l = wi . wo`. Tafuri 2019 (slide 14) takes it unchanged.
#[inline(always)]
pub(crate) fn r_azimuthal<R: Real>(cos_half_phi: R, v_dot_l: R, eta: R) -> R {
    let np = R::c(0.25) * cos_half_phi;
    let fp = fresnel_schlick(saturate(R::c(0.5) + R::c(0.5) * v_dot_l).sqrt(), eta);
    np * fp
}

/// UE's hair Roughness, validated: in (0, 1].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct UnrealRoughness(f64);

impl UnrealRoughness {
    /// The Roughness `r`.
    ///
    /// # Errors
    /// [`ParamError::OutOfRange`] naming `roughness` outside (0, 1] or not finite.
    pub fn new(r: f64) -> Result<Self, ParamError> {
        let allowed = "Unreal's hair roughness must be in (0, 1]";
        ParamError::check("roughness", r, allowed, |r| r > 0.0 && r <= 1.0).map(Self)
    }

    /// The value.
    pub fn get(self) -> f64 {
        self.0
    }

    /// The Roughness whose R lobe has the second moment of Chiang's in `sin theta_i` at normal
    /// incidence: `Roughness^4 = v coth(1/v) - v^2`, `v` from beta_m by Chiang's eq. 7,
    /// clamped to [1/255, 1] (the module documentation derives it; the value never exceeds
    /// 0.76).
    pub fn from_beta_m(beta_m: LongitudinalRoughness) -> Self {
        let width = chiang_r_width_in_sines(beta_m.get());
        UnrealRoughness(width.sqrt().clamp(MIN_ROUGHNESS, 1.0))
    }
}

/// The Unreal models' uniforms in precision `R` from the absorption `sigma_a` per radius (UE's
/// BaseColor its colour at `color_beta_n`) and the Roughness `roughness`: `B_R = clamp(r,
/// 1/255, 1)^2` (UE's `Hair_g` widths `B_R`, `B_R / 2`, `2 B_R`), sigma_a clamped at 1e30 and
/// `ln BaseColor = -sqrt(sigma_a) D(beta_n)` ([`log_color_of_sigma_a`]). The one derivation of
/// [`KarisHair::new`] and of shader code with varying inputs.
fn karis_uniforms<R: Real>(sigma_a: [R; 3], color_beta_n: R, roughness: R) -> KarisUniforms<R> {
    let sigma_a = sigma_a.map_inline(
        #[inline(always)]
        |s| s.min(R::c(MAX_SIGMA_A)),
    );
    let width = roughness.clamp(R::c(MIN_ROUGHNESS), R::c(1.0)).sqr();
    KarisUniforms {
        width_r: width,
        width_tt: R::c(0.5) * width,
        width_trt: R::c(2.0) * width,
        sigma_a,
        log_color: sigma_a.map_inline(
            #[inline(always)]
            |s| log_color_of_sigma_a(s, color_beta_n),
        ),
    }
}

crate::uniform_block! {
    /// The derived constants of the Unreal models ([`KarisHair::new`]).
    pub struct KarisUniforms<R> {
        /// `B[0] = Roughness^2`, the R lobe's standard deviation in `sin theta_i +
        /// sin theta_o` (before UE's separable scale `sqrt(2) cos(phi/2)`).
        pub width_r: R,
        /// `B[1] = Roughness^2 / 2`, TT's.
        pub width_tt: R,
        /// `B[2] = 2 Roughness^2`, TRT's.
        pub width_trt: R,
        /// `HairColorToAbsorption(BaseColor)`: the absorption per radius TT uses.
        pub sigma_a: [R; 3],
        /// `ln BaseColor`, TRT's `pow(BaseColor, 0.8 / cos theta_d)` as `exp(0.8 ln C /
        /// cos theta_d)`.
        pub log_color: [R; 3],
    }
}

/// UE 4.27's `HairShading` (R + TT + TRT) with the constants of the variant `V`
/// ([`KarisVariant`]); the module documentation gives the equations, the frame, the inputs
/// and the mapping from the physical parameters.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct KarisHair<R, V> {
    uniforms: KarisUniforms<R>,
    variant: PhantomData<V>,
}

/// UE 4.27's hair shading as shipped (`--model karis`).
pub type Karis<R> = KarisHair<R, Published>;

/// The same with hairmath's refitted constants and the colour inverted at the hair's own
/// beta_n (`--model karis-refit`).
pub type KarisRefit<R> = KarisHair<R, Refitted>;

impl<V: KarisVariant> KarisHair<f64, V> {
    /// The model of absorption `sigma_a` (UE's BaseColor is its colour at `color_beta_n`,
    /// [`Absorption::to_color`]) and Roughness `roughness`.
    pub fn new(
        sigma_a: Absorption,
        color_beta_n: AzimuthalRoughness,
        roughness: UnrealRoughness,
    ) -> Self {
        KarisHair {
            uniforms: karis_uniforms(sigma_a.rgb(), color_beta_n.get(), roughness.get()),
            variant: PhantomData,
        }
    }

    /// The model from the values of `sigma_a` and `roughness`, a colour inverted at
    /// `color_beta_n`.
    fn from_values(
        values: &InputValues,
        color_beta_n: AzimuthalRoughness,
    ) -> Result<Self, ParamError> {
        let sigma_a = values.absorption("sigma_a")?.resolve(color_beta_n)?;
        let roughness = UnrealRoughness::new(values.number("roughness")?)?;
        Ok(Self::new(sigma_a, color_beta_n, roughness))
    }

    /// The mapped inputs ([`Approximation::mapped_inputs`]) with the colour at `color_beta_n`.
    fn mapped(hair: &HairParams, color_beta_n: AzimuthalRoughness) -> InputValues {
        let mut values = InputValues::new();
        let color = hair.sigma_a.to_color(color_beta_n);
        let sigma_a = InputValue::Absorption(AbsorptionInput::Color(color));
        values.set("sigma_a", sigma_a);
        let roughness = UnrealRoughness::from_beta_m(hair.beta_m).get();
        values.set("roughness", InputValue::Number(roughness));
        values
    }
}

/// The angles of one query as `HairShading` computes them.
struct UnrealAngles<R> {
    /// `sin theta_L + sin theta_V` in UE's angles (`N` towards the root).
    sum_of_sines: R,
    /// `sin theta_V`.
    sin_v: R,
    /// `cos theta_d = cos(|asin sin theta_V - asin sin theta_L| / 2)`, floored at 1e-30.
    cos_theta_d: R,
    /// UE's regularised `cos phi`.
    cos_phi: R,
    /// `cos(phi/2) = sqrt(saturate(1/2 + cos phi / 2))`.
    cos_half_phi: R,
    /// `V . L`.
    v_dot_l: R,
}

impl<R: Real> UnrealAngles<R> {
    /// The angles of `query` (module documentation, "Frame").
    #[inline(always)]
    fn of(query: &Query<R>) -> Self {
        let (wi, wo) = (query.wi, query.wo);
        let one = R::c(1.0);
        let sin_l = (-wi.x).clamp(-one, one).label("sin_l");
        let sin_v = (-wo.x).clamp(-one, one).label("sin_v");
        let theta_d = R::c(0.5) * (safe_asin(sin_v) - safe_asin(sin_l)).abs();
        let projected = wi.y * wo.y + wi.z * wo.z;
        let (lp2, vp2) = (wi.y * wi.y + wi.z * wi.z, wo.y * wo.y + wo.z * wo.z);
        let cos_phi = (projected / (lp2 * vp2 + COS_PHI_EPSILON.get()).sqrt()).label("cos_phi");
        UnrealAngles {
            sum_of_sines: (sin_l + sin_v).label("sum_of_sines"),
            sin_v,
            // Floored before it divides: at `wi = -wo` along the tangent theta_d = 90 degrees,
            // where single precision rounds `cos(pi/2)` to a negative number.
            cos_theta_d: theta_d.cos().max(TINY.get()).label("cos_theta_d"),
            cos_phi,
            cos_half_phi: saturate(R::c(0.5) + R::c(0.5) * cos_phi)
                .sqrt()
                .label("cos_half_phi"),
            v_dot_l: wo.dot(wi).label("v_dot_l"),
        }
    }
}

/// HLSL's `saturate`: the value clamped to [0, 1].
fn saturate<R: Real>(x: R) -> R {
    x.clamp(R::c(0.0), R::c(1.0))
}

/// The three lobes of one evaluation.
struct KarisLobes<R> {
    /// R, the same in every channel.
    r: R,
    /// TT per channel.
    tt: [R; 3],
    /// TRT per channel.
    trt: [R; 3],
}

impl<R: Real, V: KarisVariant> KarisHair<R, V> {
    /// The R lobe: `Mp Np Fp` with the exact tilted-cone shift and the separable width.
    #[inline(always)]
    fn r(&self, a: &UnrealAngles<R>) -> R {
        let (sa, ca) = (R_TILT_SIN_COS.at::<R>(0), R_TILT_SIN_COS.at::<R>(1));
        let cos_v = safe_sqrt(R::c(1.0) - a.sin_v * a.sin_v);
        let shift = R::c(2.0) * sa * (ca * a.cos_half_phi * cos_v + sa * a.sin_v);
        let b_scale = SQRT_2.get::<R>() * a.cos_half_phi;
        // The R lobe's width `sqrt(2) cos(phi/2) B_R` is floored (UE's `1e-4` already keeps
        // `cos(phi/2)` above 0.005; the floor makes the division safe by construction).
        let width = (self.uniforms.width_r * b_scale).max(TINY.get());
        let mp = gaussian_lobe(width, a.sum_of_sines - shift);
        mp * r_azimuthal(a.cos_half_phi, a.v_dot_l, ETA.get())
    }

    /// The TT lobe per channel: `Mp Np Fp Tp` at Karis' offset h_TT.
    #[inline(always)]
    fn tt(&self, a: &UnrealAngles<R>) -> [R; 3] {
        let c = V::CONSTANTS;
        let one = R::c(1.0);
        let mp = gaussian_lobe(self.uniforms.width_tt, a.sum_of_sines - SHIFT.get());
        let eta_prime = EtaPrimeCoefficients::named(c.eta_prime);
        let inv_eta_prime =
            inverse_eta_prime_karis(a.cos_theta_d, eta_prime).label("inv_eta_prime");
        let h_tt = HTtCoefficients::named(c.h_tt);
        let h = h_tt_karis_of_cos(inv_eta_prime, a.cos_phi, a.cos_half_phi, h_tt).label("h_tt");
        let f = fresnel_schlick(a.cos_theta_d * saturate(one - h * h).sqrt(), ETA.get());
        let fp = (one - f).sqr();
        let np = d_karis_of_cos(a.cos_phi, ExpCosCoefficients::named(c.d_tt));
        let lobe = (mp * np * fp).label("tt_lobe");
        // The listing's path (README errata): 2 |1 - (h a)^2 / cos theta_d|.
        let path =
            (R::c(2.0) * (one - (h * inv_eta_prime).sqr() / a.cos_theta_d).abs()).label("tt_path");
        self.uniforms.sigma_a.map_inline(
            #[inline(always)]
            |s| lobe * (-s * path).exp(),
        )
    }

    /// The TRT lobe per channel: `Mp Np Fp Tp` at h = sqrt(3)/2.
    #[inline(always)]
    fn trt(&self, a: &UnrealAngles<R>) -> [R; 3] {
        let c = V::CONSTANTS;
        let mp = gaussian_lobe(self.uniforms.width_trt, a.sum_of_sines - TRT_SHIFT.get());
        let f = fresnel_schlick(a.cos_theta_d * R::c(0.5), ETA.get());
        let fp = (R::c(1.0) - f).sqr() * f;
        let np = d_karis_of_cos(a.cos_phi, ExpCosCoefficients::named(c.d_trt));
        let lobe = (mp * np * fp).label("trt_lobe");
        let exponent = (TRT_COLOR_EXPONENT.get::<R>() / a.cos_theta_d).label("trt_exponent");
        self.uniforms.log_color.map_inline(
            #[inline(always)]
            |l| lobe * (l * exponent).exp(),
        )
    }

    /// The three lobes, each clamped at 0 (UE's `max(S, 0)`, which their sum then needs no
    /// more: every factor is non-negative).
    #[inline(always)]
    fn lobes(&self, query: &Query<R>) -> KarisLobes<R> {
        let a = UnrealAngles::of(query);
        let zero = R::c(0.0);
        KarisLobes {
            r: self.r(&a).max(zero).label("r_lobe"),
            tt: self.tt(&a).map_inline(
                #[inline(always)]
                |v| v.max(zero),
            ),
            trt: self.trt(&a).map_inline(
                #[inline(always)]
                |v| v.max(zero),
            ),
        }
    }
}

impl<R: Real, V: KarisVariant> Bcsdf<R> for KarisHair<R, V> {
    fn lobe_names(&self) -> &'static [&'static str] {
        &KARIS_LOBES
    }

    /// `[R, TT, TRT]` per channel.
    fn eval_lobes(&self, query: &Query<R>) -> Vec<[R; 3]> {
        let l = self.lobes(query);
        vec![[l.r; 3], l.tt, l.trt]
    }

    /// UE's `HairShading` result, which is the crate's S (no cosine factor; module
    /// documentation): `max(R + TT + TRT, 0)` per channel.
    #[inline(always)]
    fn eval(&self, query: &Query<R>) -> [R; 3] {
        let l = self.lobes(query);
        crate::real::array_from_fn(
            #[inline(always)]
            |c| (l.r + l.tt[c] + l.trt[c]).max(R::c(0.0)),
        )
    }
}

impl<V: KarisVariant> Model for KarisHair<f64, V> {
    const INLINED_KERNEL: bool = true;
    type Uniforms<R: Real> = KarisUniforms<R>;
    type In<R: Real> = KarisHair<R, V>;

    fn uniforms(&self) -> KarisUniforms<f64> {
        self.uniforms
    }

    fn with_uniforms<R: Real>(&self, uniforms: KarisUniforms<R>) -> KarisHair<R, V> {
        KarisHair {
            uniforms,
            variant: PhantomData,
        }
    }
}

/// UE's Roughness input.
const ROUGHNESS: Input = Input {
    name: "roughness",
    kind: InputKind::Number,
    help: "Unreal's hair Roughness, in (0, 1] (clamped below at 1/255): the R lobe's standard \
           deviation in sin(theta_i) + sin(theta_o) is Roughness^2",
    default: None,
    conflicts_with: &[],
};

/// The inputs of [`Karis`]: the absorption (`--color` is UE's BaseColor) and the Roughness.
const KARIS_INPUTS: [Input; 2] = [HAIR_INPUTS[4], ROUGHNESS];

/// The inputs of [`KarisRefit`]: those of [`Karis`] and the beta_n of the colour inversion.
const KARIS_REFIT_INPUTS: [Input; 3] = [HAIR_INPUTS[4], ROUGHNESS, HAIR_INPUTS[1]];

/// Chiang's colour mapping at beta_n = 0.3, as `HairColorToAbsorption` uses it.
fn unreal_color_beta_n() -> AzimuthalRoughness {
    AzimuthalRoughness::new(COLOR_BETA_N).expect("COLOR_BETA_N is a valid beta_n")
}

impl FromInputs for Karis<f64> {
    const NAME: &'static str = "karis";
    const SUMMARY: &'static str = "Karis 2016 as Unreal Engine 4.27's HairShading (R + TT + TRT) \
        with UE's BaseColor (--color, inverted at beta_n = 0.3) and Roughness, S(wi, wo)";
    const INPUTS: &'static [Input] = &KARIS_INPUTS;

    fn from_inputs(values: &InputValues) -> Result<Self, ParamError> {
        Self::from_values(values, unreal_color_beta_n())
    }
}

impl FromInputs for KarisRefit<f64> {
    const NAME: &'static str = "karis-refit";
    const SUMMARY: &'static str = "Unreal's HairShading with hairmath's refitted constants and \
        the colour inverted at the hair's beta_n, S(wi, wo)";
    const INPUTS: &'static [Input] = &KARIS_REFIT_INPUTS;

    fn from_inputs(values: &InputValues) -> Result<Self, ParamError> {
        let beta_n = AzimuthalRoughness::new(values.number("beta_n")?)?;
        Self::from_values(values, beta_n)
    }
}

/// The Unreal models' uniforms from their inputs in precision `R`, a colour inverted at
/// `color_beta_n` ([`karis_uniforms`]; a negative sigma_a or concentration is 0, a colour is
/// clamped into (0, 1]).
fn karis_uniforms_in<R: Real>(inputs: &InputsIn<R>, color_beta_n: R) -> KarisUniforms<R> {
    let sigma_a = inputs.absorption("sigma_a").sigma_a(color_beta_n);
    karis_uniforms(sigma_a, color_beta_n, inputs.number("roughness"))
}

/// The absorption in each of its forms.
const ABSORPTION_VARYING: [&str; 4] = ["sigma_a", "color", "eumelanin", "pheomelanin"];

impl VaryingInputs for Karis<f64> {
    const NAME: &'static str = <Self as FromInputs>::NAME;
    const INPUTS: &'static [Input] = &KARIS_INPUTS;
    const VARYING: &'static [&'static str] = &[
        "roughness",
        ABSORPTION_VARYING[0],
        ABSORPTION_VARYING[1],
        ABSORPTION_VARYING[2],
        ABSORPTION_VARYING[3],
    ];
    const BAKED: &'static [(&'static str, &'static str)] = &[];

    fn uniforms_in<R: Real>(inputs: &InputsIn<R>) -> KarisUniforms<R> {
        karis_uniforms_in(inputs, R::c(COLOR_BETA_N))
    }
}

impl VaryingInputs for KarisRefit<f64> {
    const NAME: &'static str = <Self as FromInputs>::NAME;
    const INPUTS: &'static [Input] = &KARIS_REFIT_INPUTS;
    const VARYING: &'static [&'static str] = &[
        "roughness",
        "beta_n",
        ABSORPTION_VARYING[0],
        ABSORPTION_VARYING[1],
        ABSORPTION_VARYING[2],
        ABSORPTION_VARYING[3],
    ];
    const BAKED: &'static [(&'static str, &'static str)] = &[];

    fn uniforms_in<R: Real>(inputs: &InputsIn<R>) -> KarisUniforms<R> {
        karis_uniforms_in(inputs, roughness_in(inputs.number("beta_n")))
    }
}

impl Approximation for Karis<f64> {
    /// BaseColor: the colour whose Chiang mapping at beta_n = 0.3 is the hair's sigma_a;
    /// Roughness: [`UnrealRoughness::from_beta_m`].
    fn mapped_inputs(hair: &HairParams) -> InputValues {
        Self::mapped(hair, unreal_color_beta_n())
    }

    const FITTED_INPUTS: &'static [&'static str] = &["sigma_a", "roughness"];
}

impl Approximation for KarisRefit<f64> {
    /// As [`Karis`], with the colour at the hair's own beta_n (which it takes as `beta_n`).
    fn mapped_inputs(hair: &HairParams) -> InputValues {
        let mut values = Self::mapped(hair, hair.beta_n);
        values.set("beta_n", InputValue::Number(hair.beta_n.get()));
        values
    }

    const FITTED_INPUTS: &'static [&'static str] = &["sigma_a", "roughness"];
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The R lobe's tilt is written as its sine and cosine; they are those of `-2 Shift`.
    #[test]
    fn the_r_tilt_is_minus_twice_the_shift() {
        let alpha = -2.0 * SHIFT.values[0];
        assert_eq!(R_TILT_SIN_COS.values, &[alpha.sin(), alpha.cos()]);
        assert_eq!(TRT_SHIFT.values[0], 4.0 * SHIFT.values[0]);
    }
}
