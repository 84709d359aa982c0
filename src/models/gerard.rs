//! Gerard, "Fast Real-Time Shading for Polygonal Hair": the Henyey-Greenstein asymmetry g(beta)
//! as closed forms in the lobe width, and the absorption exponents of his TT and TRT lobes.

use super::constants::{GERARD_HG_G_LITERAL_POLYNOMIAL, HG_G_NORMALISED_POLYNOMIAL};
use crate::real::{horner, Real, ShaderFunction};

/// Domain of the g(beta) closed forms [`gerard_hg_g`] and [`hg_g_normalised`], radians: 1 to
/// 45 degrees. Widths outside it are clamped.
pub const HG_G_BETA_DOMAIN: (f64, f64) = (
    1.0 * core::f64::consts::PI / 180.0,
    45.0 * core::f64::consts::PI / 180.0,
);

/// Gerard's g(beta) for the lobe exactly as he prints it (his eq. 6,
/// [`crate::lobe::hg_gerard_printed`]): the g whose printed lobe is closest in L2 over
/// [-pi/2, pi/2] to the unit-area Gaussian of standard deviation `beta` (radians; his section
/// 2.1 fits g "by minimizing the L2 norm of the difference"), as a polynomial in sqrt(beta)
/// fitted to those L2 fits (`hairmath::fit::hg`; coefficients
/// [`GERARD_HG_G_LITERAL_POLYNOMIAL`]).
///
/// Domain [`HG_G_BETA_DOMAIN`], beta in [1, 45] degrees; beta outside is clamped to it (so the
/// result is finite for every finite or infinite beta). A hot path traced to shader code, so
/// it rejects nothing: NaN counts as the lower end (1 degree) in `f32`, `f64` and SIMD lanes,
/// whose `max` returns the other operand (a shader's `max` of NaN is implementation-defined;
/// the models pass validated widths, [`crate::params::LobeWidth`]). Error: within
/// [`super::constants::GERARD_HG_G_LITERAL_POLYNOMIAL_MAX_ERROR`] (3.9e-4) of the fitted g
/// (tests/fit_hg.rs). This reading does not give Gerard's printed 0.865 and 0.578 (README,
/// erratum on g).
pub fn gerard_hg_g<R: Real>(beta: R) -> R {
    g_polynomial(beta, &GERARD_HG_G_LITERAL_POLYNOMIAL)
}

/// g(beta) for the circle-normalised lobe [`crate::lobe::HenyeyGreenstein`]: the g whose lobe
/// is closest in L2 over [-pi, pi] to the unit-area Gaussian of standard deviation `beta`
/// (radians), as a polynomial in sqrt(beta) ([`HG_G_NORMALISED_POLYNOMIAL`], fitted by
/// `hairmath::fit::hg`); the natural reading of Gerard's section 2.1 for a unit-integral lobe.
///
/// Domain [`HG_G_BETA_DOMAIN`], beta in [1, 45] degrees; beta outside is clamped, NaN counts
/// as 1 degree (as for [`gerard_hg_g`]). Error: within
/// [`super::constants::HG_G_NORMALISED_POLYNOMIAL_MAX_ERROR`] (1.1e-4) of the fitted g
/// (tests/fit_hg.rs).
pub fn hg_g_normalised<R: Real>(beta: R) -> R {
    g_polynomial(beta, &HG_G_NORMALISED_POLYNOMIAL)
}

fn g_polynomial<R: Real>(beta: R, coefficients: &[f64]) -> R {
    const FUNCTION: ShaderFunction = crate::shader_function!(
        hg_asymmetry,
        "Gerard et al. 2023, g(beta) as a polynomial in sqrt(beta)",
        [beta]
    );
    R::call(
        &FUNCTION,
        [beta],
        #[inline(always)]
        |[beta]| {
            let (lo, hi) = HG_G_BETA_DOMAIN;
            [horner(
                beta.max(R::c(lo)).min(R::c(hi)).sqrt(),
                coefficients,
            )]
        },
    )[0]
}

/// Gerard's absorption exponent of the TT lobe, `e^(-4 sigma_a)` (his eqs. 8 and 12): k = 4,
/// Marschner et al. 2003's exponent `4 sigma_a cos^2(gamma_t) / cos(theta_t)` of one internal
/// segment at h = 0, theta = 0 (sigma_a per unit fibre radius).
///
/// Error measured by `hairmath::fit::absorption_exponent` at eta = 1.55, as the RMS over
/// sigma_a in [0, 2] of `|e^(-k sigma_a) - E_TT(sigma_a) / E_TT(0)|` (E the lobe energy
/// averaged over offsets): 2.7e-2 against Marschner's exponent at theta = 0, 7.9e-3 averaged
/// over directions; 1.6e-1 and 1.4e-1 against the exact chord. The refits are
/// [`super::constants::GERARD_ABSORPTION_K_TT`].
pub const GERARD_K_TT: f64 = 4.0;

/// Gerard's absorption exponent of the TRT lobe, `e^(-11/2 sigma_a)` (his eq. 13): k = 11/2,
/// Marschner et al. 2003's exponent of two internal segments at h = sqrt(3)/2, theta = 0,
/// `8 (1 - 3 / (4 eta^2))` = 5.5026 at eta = 1.55 ([`gerard_eq8_trt_corrected`]).
///
/// Error measured by `hairmath::fit::absorption_exponent` at eta = 1.55 (metric of
/// [`GERARD_K_TT`]): 2.1e-2 against Marschner's exponent at theta = 0, 4.5e-2 averaged over
/// directions; 7.2e-2 and 4.7e-2 against the exact chord. The refits are
/// [`super::constants::GERARD_ABSORPTION_K_TRT`].
pub const GERARD_K_TRT: f64 = 5.5;

/// Gerard's attenuation of a lobe by absorption, `e^(-k sigma_a)` (his eqs. 8, 12 and 13), with
/// exponent `k` ([`GERARD_K_TT`], [`GERARD_K_TRT`], or a refit from
/// [`super::constants::GERARD_ABSORPTION_K_TT`] / `_TRT`) and absorption coefficient `sigma_a`
/// per unit fibre radius.
///
/// Domain: `k >= 0`, `sigma_a >= 0`; the result is in [0, 1] (it underflows to 0 for very dark
/// hair, never NaN). Its error against the exact lobe energies is documented with each `k`.
#[inline(always)]
pub fn gerard_attenuation<R: Real>(k: R, sigma_a: R) -> R {
    (-k * sigma_a).exp()
}

/// Gerard's eq. 8 TRT exponent as printed, `8 (1 - 3 / (2 eta^2))`: 3.0052 at eta = 1.55.
///
/// The printed form would need an offset h^2 = 3/2, outside the fibre; it is most likely a
/// misprint of [`gerard_eq8_trt_corrected`] (README, errata). Domain: eta > 0 (the fibres'
/// (1, 3]); negative (a gain) for eta < sqrt(3/2). Error at eta = 1.55 (metric of
/// [`GERARD_K_TT`], Marschner's exponent at theta = 0): 1.25e-1.
pub fn gerard_eq8_trt_printed<R: Real>(eta: R) -> R {
    R::c(8.0) * (R::c(1.0) - R::c(3.0) / (R::c(2.0) * eta * eta))
}

/// Gerard's eq. 8 TRT exponent corrected, `8 (1 - 3 / (4 eta^2))`: 5.5026 at eta = 1.55,
/// Marschner et al. 2003's two-segment exponent `4 p sigma_a (1 - h^2 / eta^2)` at
/// h = sqrt(3)/2, theta = 0 (Snell's law in the normal plane gives sin gamma_t = h / eta), which
/// agrees with eq. 13's 11/2 to 5e-4 relative.
///
/// Domain: eta > 0 (the fibres' (1, 3]). Error at eta = 1.55 (metric of [`GERARD_K_TT`],
/// Marschner's exponent at theta = 0): 2.1e-2.
pub fn gerard_eq8_trt_corrected<R: Real>(eta: R) -> R {
    R::c(8.0) * (R::c(1.0) - R::c(3.0) / (R::c(4.0) * eta * eta))
}
