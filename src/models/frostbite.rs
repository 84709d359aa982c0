//! Tafuri 2019, "Strand-based Hair Rendering in Frostbite" (SIGGRAPH 2019 Advances in Real-Time
//! Rendering course, slides 13-21): the per-slice Gaussian of the TT distribution and the
//! attenuations of the transmitted lobes at a single offset.
//!
//! Conventions are hairmath's (README, "Conventions"): `phi = phi_i - phi_o` as in pbrt, so the
//! TT lobe peaks at |phi| = pi; sigma_a per unit fibre radius. The references they approximate
//! (Chiang et al. 2016's far-field integrals), the tables and the refits are in
//! `hairmath::fit::frostbite`; the errors quoted here are its measurements at eta = 1.55.

use super::constants::{FROSTBITE_TRT_OFFSET_H, FROSTBITE_TT_OFFSET_H};
use crate::absorption::PathLength;
use crate::azimuthal::attenuations_at_offset;
use crate::real::{pi, Real, ShaderFunction};

/// Frostbite's per-slice model of the TT distribution (slide 19): `a exp(-b (|phi| - pi)^2)`,
/// with the height `a` and the sharpness `b` (rad^-2) looked up per (theta_o, beta_n) in the
/// fitted tables [`super::constants::FROSTBITE_TT_GAUSSIAN_A`] and
/// [`super::constants::FROSTBITE_TT_GAUSSIAN_B`]; `phi` is the relative azimuth, radians.
///
/// Domain: phi in [-pi, pi] (wrap it first, [`crate::real::wrap_angle`]), `b >= 0`; the
/// result is finite. Error of the fitted tables against Chiang et al. 2016's `D_TT` (RMS over
/// phi in [0, pi] relative to each slice's peak): 1.48e-2 on average over the 9 x 10 slices,
/// 4.84e-2 at worst (theta_o = 80 deg, beta_n = 0.1).
pub fn tt_gaussian<R: Real>(phi: R, a: R, b: R) -> R {
    const FUNCTION: ShaderFunction =
        crate::shader_function!(tt_gaussian, "Tafuri 2019, slide 19", [phi, a, b]);
    R::call(
        &FUNCTION,
        [phi, a, b],
        #[inline(always)]
        |[phi, a, b]| [a * (-b * (phi.abs() - pi::<R>()).sqr()).exp()],
    )[0]
}

/// A transmitted lobe whose attenuation Frostbite evaluates at a single offset.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Transmitted {
    /// p = 1.
    Tt,
    /// p = 2.
    Trt,
}

impl Transmitted {
    /// The path's index p (its number of internal segments).
    pub fn p(self) -> usize {
        match self {
            Transmitted::Tt => 1,
            Transmitted::Trt => 2,
        }
    }

    /// "TT" or "TRT".
    pub fn name(self) -> &'static str {
        match self {
            Transmitted::Tt => "TT",
            Transmitted::Trt => "TRT",
        }
    }

    /// The offset Frostbite evaluates the lobe's attenuation at: h = 0 for TT (slide 20), and
    /// h = sqrt(3)/2 for TRT (slide 21, Karis 2016's constant).
    pub const fn published_offset(self) -> f64 {
        match self {
            Transmitted::Tt => 0.0,
            Transmitted::Trt => 0.866_025_403_784_438_6,
        }
    }

    /// hairmath's refitted offset, [`FROSTBITE_TT_OFFSET_H`] or [`FROSTBITE_TRT_OFFSET_H`]:
    /// the h whose attenuation is closest to the h-average (eta = 1.55).
    pub const fn refit_offset(self) -> f64 {
        match self {
            Transmitted::Tt => FROSTBITE_TT_OFFSET_H,
            Transmitted::Trt => FROSTBITE_TRT_OFFSET_H,
        }
    }
}

/// Frostbite's attenuation of a transmitted lobe at a single offset (slides 17, 20 and 21):
/// Chiang et al. 2016's `A_p(h)` (eqs. 3 and 6; [`attenuations_at_offset`]) for a ray whose
/// inclination theta has sine `sin_theta` and cosine `cos_theta`, refractive index `eta` and
/// absorption `sigma_a` per unit radius with the chord transmittance
/// `exp(-sigma_a 2 cos(gamma_t) / cos(theta_t))`
/// ([`crate::absorption::segment_transmittance`]), standing in for the h-average
/// `1/2 int_{-1}^{1} A_p(h) dh`. Evaluate it at [`Transmitted::published_offset`] or
/// [`Transmitted::refit_offset`].
///
/// Domain: h in [-1, 1], sigma_a >= 0, `cos_theta >= 0` with `sin^2 + cos^2 = 1` (grazing
/// included), eta > 1; the result is in [0, 1]. Error against the h-average (RMS relative error
/// over sigma_a in [0, 4] x theta_d in [0, 85 deg]): at the published offsets 2.31e-1 (TT) and
/// 7.16e-1 (TRT), at the refitted ones 5.46e-2 and 1.51e-1.
pub fn offset_attenuation<R: Real>(
    path: Transmitted,
    h: R,
    sigma_a: R,
    sin_theta: R,
    cos_theta: R,
    eta: R,
) -> R {
    attenuations_at_offset(h, sin_theta, cos_theta, eta, sigma_a, PathLength::Chord)[path.p()]
}
