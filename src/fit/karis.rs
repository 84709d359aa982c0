//! Karis' closed forms (Unreal Engine 4, "Physically Based Hair Shading in Unreal", 2016;
//! `HairBsdf.ush`), each measured against its exact reference and refitted under one stated
//! metric. The closed forms and their coefficients are in [`crate::models`]
//! ([`scaled_eta_prime_karis`], [`d_karis`], [`h_tt_karis`]); this module holds the exact
//! references, the metrics and the fits:
//!
//! - Bravais' index `eta' ~ a / cos theta_d + b cos theta_d` (published a = 1.19, b = 0.36,
//!   claimed "error < 0.68%"): maximum relative error over theta_d in [0, 90 deg) with the
//!   grazing limit, refitted minimax by Nelder-Mead.
//! - `D_TT ~ exp(a cos phi + b)` (published -3.65, -3.98) for the logistic `D(phi, 0.35, pi)`
//!   and `D_TRT ~ exp(a cos phi + b)` (published 17, -16.78) for `3/4 D(phi, 0.15, 0)`: RMS over
//!   phi in [0, pi] relative to the reference's peak, refitted by Nelder-Mead.
//! - The TT offset `h_TT ~ (1 + a (c1 - c2 cos phi)) cos(phi/2)`, a = 1/eta' (published
//!   c1 = 0.6, c2 = 0.8), against the exact root of `Phi(1, h) = phi`: RMS over theta_d in
//!   [0, 80 deg] and the azimuths where the root exists, refitted by linear least squares.

use super::{
    linear_least_squares, minimize, ConstValue, ConstantFit, FitError, FitOutput, FitSettings,
    GeneratedConst, Minimum,
};
use crate::azimuthal::logistic;
use crate::error::ParamError;
use crate::fresnel::bravais_eta_perpendicular;
use crate::models::{
    d_karis, h_tt_karis, scaled_eta_prime_karis, EtaPrimeCoefficients, ExpCosCoefficients,
    HTtCoefficients,
};
use crate::quadrature::{gauss_legendre, integrate};
use core::f64::consts::{FRAC_PI_2, PI};

/// Where every published constant comes from.
const SOURCE: &str = "Karis 2016 (UE4 HairBsdf.ush)";

/// Karis' published `(a, b)` of `eta' ~ a / cos theta_d + b cos theta_d`
/// ([`EtaPrimeCoefficients::PUBLISHED`] as an array, the fits' parameter vector).
pub const PUBLISHED_ETA_PRIME: [f64; 2] = [
    EtaPrimeCoefficients::PUBLISHED.a,
    EtaPrimeCoefficients::PUBLISHED.b,
];
/// Karis' claimed bound on the relative error of `eta'`: "error < 0.68%".
pub const CLAIMED_ETA_PRIME_ERROR: f64 = 0.0068;
/// Karis' published `(a, b)` of `D_TT ~ exp(a cos phi + b)`
/// ([`ExpCosCoefficients::PUBLISHED_D_TT`] as an array).
pub const PUBLISHED_D_TT: [f64; 2] = [
    ExpCosCoefficients::PUBLISHED_D_TT.a,
    ExpCosCoefficients::PUBLISHED_D_TT.b,
];
/// Karis' published `(a, b)` of `D_TRT ~ exp(a cos phi + b)`
/// ([`ExpCosCoefficients::PUBLISHED_D_TRT`] as an array).
pub const PUBLISHED_D_TRT: [f64; 2] = [
    ExpCosCoefficients::PUBLISHED_D_TRT.a,
    ExpCosCoefficients::PUBLISHED_D_TRT.b,
];
/// Karis' published `(c1, c2)` of `h_TT ~ (1 + a (c1 - c2 cos phi)) cos(phi/2)`
/// ([`HTtCoefficients::PUBLISHED`] as an array).
pub const PUBLISHED_H_TT: [f64; 2] = [HTtCoefficients::PUBLISHED.c1, HTtCoefficients::PUBLISHED.c2];

/// Logistic scale of Karis' `D_TT = D(phi, 0.35, pi)`.
pub const D_TT_SCALE: f64 = 0.35;
/// Logistic scale of Karis' `D_TRT = 3/4 D(phi, 0.15, 0)`.
pub const D_TRT_SCALE: f64 = 0.15;
/// Largest theta_d of the `h_TT` domain, 80 degrees.
pub const H_TT_MAX_THETA_D: f64 = 80.0 * PI / 180.0;

/// Nodes in theta_d in [0, 90 deg] of the `eta'` grid (the last one is the grazing limit).
const ETA_PRIME_NODES: usize = 4001;
/// Panels of the 16-point Gauss-Legendre rule on [0, pi] for the `D` fits.
const D_PANELS: usize = 64;
/// Grid of the `h_TT` metric: nodes in theta_d and in phi.
const H_TT_THETA_NODES: usize = 81;
const H_TT_PHI_NODES: usize = 201;

/// Nelder-Mead loss tolerance (standard deviation of the simplex's losses).
const LOSS_TOL: f64 = 1e-15;

fn finite(name: &'static str, value: f64) -> Result<f64, ParamError> {
    ParamError::check(name, value, "must be finite", |_| true)
}

fn checked(settings: &FitSettings) -> Result<FitSettings, FitError> {
    Ok(FitSettings::new(settings.eta)?)
}

// ---------------------------------------------------------------------------------------------
// eta'
// ---------------------------------------------------------------------------------------------

/// `x eta'(x)` for `x = cos theta_d`: `sqrt(eta^2 - 1 + x^2)`, Bravais' index
/// `eta' = sqrt(eta^2 - sin^2 theta_d) / cos theta_d` (Marschner 2003, appendix B) times
/// `cos theta_d`, finite at the grazing limit x = 0.
fn scaled_bravais(eta: f64, x: f64) -> f64 {
    (eta * eta - 1.0 + x * x).sqrt()
}

/// `|(a + b x^2) / reference(x) - 1|`, the relative error of `a / x + b x` against
/// `reference(x) / x`, where `reference(x) = x eta'(x)` with x = cos theta_d: both sides
/// multiplied by x, Karis' side by [`scaled_eta_prime_karis`].
fn scaled_relative_error(reference: &impl Fn(f64) -> f64, a: f64, b: f64, x: f64) -> f64 {
    (scaled_eta_prime_karis(x, EtaPrimeCoefficients { a, b }) / reference(x) - 1.0).abs()
}

/// x = cos theta_d of node `i` of the uniform theta_d grid on [0, 90 deg]; the last node is
/// exactly 0 (the grazing limit).
fn eta_prime_node(i: usize) -> f64 {
    if i + 1 == ETA_PRIME_NODES {
        0.0
    } else {
        (FRAC_PI_2 * i as f64 / (ETA_PRIME_NODES - 1) as f64).cos()
    }
}

/// The largest relative error of `a / cos theta_d + b cos theta_d` against `reference(x) / x`
/// (x = cos theta_d, `reference(x) = x eta'(x)` finite at x = 0) on 4001 uniform theta_d nodes
/// in [0, 90 deg], the last node being the grazing limit x -> 0, where the error tends to
/// `|a / reference(0) - 1|`.
pub fn max_scaled_relative_error(reference: impl Fn(f64) -> f64, a: f64, b: f64) -> f64 {
    (0..ETA_PRIME_NODES)
        .map(|i| scaled_relative_error(&reference, a, b, eta_prime_node(i)))
        .fold(0.0, f64::max)
}

/// The relative error `|(a / cos theta_d + b cos theta_d) / eta' - 1|` of Karis' form of
/// Bravais' index at one theta_d in [0, 90 deg) (exact: `eta' = sqrt(eta^2 - sin^2 theta_d) /
/// cos theta_d`, Marschner 2003 appendix B; [`bravais_eta_perpendicular`]).
///
/// # Errors
/// Invalid `settings.eta`, non-finite `a` or `b`, `theta_d` outside [0, 90 deg).
pub fn eta_prime_relative_error(
    settings: &FitSettings,
    a: f64,
    b: f64,
    theta_d: f64,
) -> Result<f64, FitError> {
    let eta = checked(settings)?.eta;
    let (a, b) = (finite("a", a)?, finite("b", b)?);
    let theta_d = ParamError::check("theta_d", theta_d, "must be in [0, pi/2)", |t| {
        (0.0..FRAC_PI_2).contains(&t)
    })?;
    let exact = bravais_eta_perpendicular(eta, theta_d.sin());
    let cos_theta_d = theta_d.cos();
    let approx = scaled_eta_prime_karis(cos_theta_d, EtaPrimeCoefficients { a, b }) / cos_theta_d;
    Ok((approx / exact - 1.0).abs())
}

/// The metric of Karis' `eta' ~ a / cos theta_d + b cos theta_d` (Karis 2016, after Marschner
/// 2003's Bravais index `eta' = sqrt(eta^2 - sin^2 theta_d) / cos theta_d`): the maximum
/// relative error over theta_d in [0, 90 deg) including the grazing limit
/// ([`max_scaled_relative_error`] with `reference(x) = sqrt(eta^2 - 1 + x^2)`).
///
/// # Errors
/// Invalid `settings.eta`, non-finite `a` or `b`.
pub fn eta_prime_max_relative_error(
    settings: &FitSettings,
    a: f64,
    b: f64,
) -> Result<f64, FitError> {
    let eta = checked(settings)?.eta;
    let (a, b) = (finite("a", a)?, finite("b", b)?);
    Ok(max_scaled_relative_error(|x| scaled_bravais(eta, x), a, b))
}

/// Minimax fit of `(a, b)` in `a / x + b x` to `reference(x) / x` (x = cos theta_d, `reference`
/// finite at 0): Nelder-Mead on [`max_scaled_relative_error`] from `start`, restarted from its
/// own result until a restart no longer improves the loss (the loss has kinks, where a single
/// simplex can stall).
///
/// # Errors
/// Non-finite `start`; the optimiser's errors.
pub fn minimax_scaled_index(
    reference: impl Fn(f64) -> f64,
    start: [f64; 2],
) -> Result<Minimum, FitError> {
    let start = [finite("a", start[0])?, finite("b", start[1])?];
    let loss = |p: &[f64]| max_scaled_relative_error(&reference, p[0], p[1]);
    let mut best = minimize(
        "Karis eta' (minimax)",
        loss,
        &start,
        &[0.01, 0.01],
        LOSS_TOL,
    )?;
    for _ in 0..MAX_RESTARTS {
        let step: Vec<f64> = best
            .params
            .iter()
            .map(|p| 1e-3 * p.abs().max(1e-3))
            .collect();
        let next = minimize("Karis eta' (minimax)", loss, &best.params, &step, LOSS_TOL)?;
        if next.loss >= best.loss {
            break;
        }
        best = next;
    }
    Ok(best)
}

/// Restarts of the minimax Nelder-Mead at most.
const MAX_RESTARTS: usize = 20;

/// Karis' Bravais index, published against refitted.
#[derive(Clone, Debug, PartialEq)]
pub struct EtaPrimeFit {
    /// Published `(a, b)` = (1.19, 0.36).
    pub published: [f64; 2],
    /// Minimax refit of `(a, b)`.
    pub refit: [f64; 2],
    /// Maximum relative error of the published constants over theta_d in [0, 90 deg).
    pub published_error: f64,
    /// Maximum relative error of the refit over the same domain.
    pub refit_error: f64,
    /// theta_d (radians) where the published constants' relative error is largest.
    pub published_worst_theta_d: f64,
    /// The largest theta_d (radians, on the metric's grid) up to which the published
    /// constants' error stays below the claimed 0.68%: pi/2 when the claim holds everywhere.
    pub claim_holds_up_to: f64,
    /// The last Nelder-Mead run.
    pub minimum: Minimum,
}

/// theta_d (radians) of node `i` of the `eta'` grid.
fn eta_prime_theta(i: usize) -> f64 {
    FRAC_PI_2 * i as f64 / (ETA_PRIME_NODES - 1) as f64
}

/// (theta_d of the largest error, largest theta_d below which the error stays under the
/// claimed bound) of the published constants on the metric's grid.
fn published_eta_prime_extent(eta: f64) -> (f64, f64) {
    let [a, b] = PUBLISHED_ETA_PRIME;
    let errors: Vec<f64> = (0..ETA_PRIME_NODES)
        .map(|i| scaled_relative_error(&|x| scaled_bravais(eta, x), a, b, eta_prime_node(i)))
        .collect();
    let worst = (0..ETA_PRIME_NODES)
        .max_by(|&i, &j| errors[i].total_cmp(&errors[j]))
        .unwrap_or(0);
    let first_over = errors.iter().position(|&e| e >= CLAIMED_ETA_PRIME_ERROR);
    let holds = first_over.map_or(FRAC_PI_2, |i| eta_prime_theta(i.saturating_sub(1)));
    (eta_prime_theta(worst), holds)
}

/// Measures Karis' `eta' ~ 1.19 / cos theta_d + 0.36 cos theta_d` at `settings.eta` and refits
/// it minimax ([`eta_prime_max_relative_error`], [`minimax_scaled_index`]).
///
/// # Errors
/// Invalid `settings.eta`; the optimiser's errors.
pub fn fit_eta_prime(settings: &FitSettings) -> Result<EtaPrimeFit, FitError> {
    let eta = checked(settings)?.eta;
    let minimum = minimax_scaled_index(|x| scaled_bravais(eta, x), PUBLISHED_ETA_PRIME)?;
    let [a, b] = PUBLISHED_ETA_PRIME;
    let (published_worst_theta_d, claim_holds_up_to) = published_eta_prime_extent(eta);
    Ok(EtaPrimeFit {
        published: PUBLISHED_ETA_PRIME,
        refit: [minimum.params[0], minimum.params[1]],
        published_error: eta_prime_max_relative_error(settings, a, b)?,
        refit_error: minimum.loss,
        published_worst_theta_d,
        claim_holds_up_to,
        minimum,
    })
}

// ---------------------------------------------------------------------------------------------
// D_TT and D_TRT
// ---------------------------------------------------------------------------------------------

/// Karis' `D_TT(phi) = D(phi, 0.35, pi)`, the untrimmed logistic of Pixar (Karis 2016;
/// `D(phi, s, mu) = e^((phi - mu)/s) / (s (1 + e^((phi - mu)/s))^2)`), evaluated at the distance
/// `|phi| - pi` since it is even in phi. Peak `1 / (4 s)` at phi = pi.
pub fn d_tt_reference(phi: f64) -> f64 {
    logistic(phi.abs() - PI, D_TT_SCALE)
}

/// Karis' `D_TRT(phi) = 3/4 D(phi, 0.15, 0)` (Karis 2016), the untrimmed logistic scaled by
/// 3/4. Peak `3 / (16 s)` at phi = 0.
pub fn d_trt_reference(phi: f64) -> f64 {
    0.75 * logistic(phi, D_TRT_SCALE)
}

/// The metric of the `D` fits: `sqrt(1/pi int_0^pi (exp(a cos phi + b) - reference(phi))^2
/// dphi) / peak` ([`d_karis`]), the RMS error over phi in [0, pi] relative to the reference's
/// peak, by 64 panels of the 16-point Gauss-Legendre rule.
pub fn exp_cos_rms_error(reference: impl Fn(f64) -> f64, peak: f64, a: f64, b: f64) -> f64 {
    let rule = gauss_legendre(16);
    let c = ExpCosCoefficients { a, b };
    let square = |phi: f64| (d_karis(phi, c) - reference(phi)).powi(2);
    (integrate(&rule, D_PANELS, 0.0, PI, square) / PI).sqrt() / peak
}

/// [`exp_cos_rms_error`] of Karis' `D_TT ~ exp(a cos phi + b)` against [`d_tt_reference`]
/// (peak `1 / (4 * 0.35)`).
///
/// # Errors
/// Non-finite `a` or `b`.
pub fn d_tt_rms_error(a: f64, b: f64) -> Result<f64, FitError> {
    let (a, b) = (finite("a", a)?, finite("b", b)?);
    Ok(exp_cos_rms_error(d_tt_reference, d_tt_peak(), a, b))
}

/// [`exp_cos_rms_error`] of Karis' `D_TRT ~ exp(a cos phi + b)` against [`d_trt_reference`]
/// (peak `3 / (16 * 0.15)`).
///
/// # Errors
/// Non-finite `a` or `b`.
pub fn d_trt_rms_error(a: f64, b: f64) -> Result<f64, FitError> {
    let (a, b) = (finite("a", a)?, finite("b", b)?);
    Ok(exp_cos_rms_error(d_trt_reference, d_trt_peak(), a, b))
}

fn d_tt_peak() -> f64 {
    1.0 / (4.0 * D_TT_SCALE)
}

fn d_trt_peak() -> f64 {
    0.75 / (4.0 * D_TRT_SCALE)
}

/// Least-squares fit of `(a, b)` in `exp(a cos phi + b)` to `reference` on [0, pi]: Nelder-Mead
/// on [`exp_cos_rms_error`] from `start`.
///
/// # Errors
/// Non-finite `start` or `peak <= 0`; the optimiser's errors.
pub fn fit_exp_cos(
    what: &str,
    reference: impl Fn(f64) -> f64,
    peak: f64,
    start: [f64; 2],
) -> Result<Minimum, FitError> {
    let start = [finite("a", start[0])?, finite("b", start[1])?];
    let peak = ParamError::check("peak", peak, "must be positive", |p| p > 0.0)?;
    let loss = |p: &[f64]| exp_cos_rms_error(&reference, peak, p[0], p[1]);
    minimize(what, loss, &start, &[0.1, 0.1], LOSS_TOL)
}

/// One `exp(a cos phi + b)` lobe of Karis, published against refitted.
#[derive(Clone, Debug, PartialEq)]
pub struct ExpCosFit {
    /// Published `(a, b)`.
    pub published: [f64; 2],
    /// Refitted `(a, b)`.
    pub refit: [f64; 2],
    /// [`exp_cos_rms_error`] of the published constants.
    pub published_error: f64,
    /// [`exp_cos_rms_error`] of the refit.
    pub refit_error: f64,
    /// The Nelder-Mead run.
    pub minimum: Minimum,
}

fn fit_lobe(
    what: &str,
    reference: fn(f64) -> f64,
    peak: f64,
    published: [f64; 2],
) -> Result<ExpCosFit, FitError> {
    let minimum = fit_exp_cos(what, reference, peak, published)?;
    Ok(ExpCosFit {
        published,
        refit: [minimum.params[0], minimum.params[1]],
        published_error: exp_cos_rms_error(reference, peak, published[0], published[1]),
        refit_error: minimum.loss,
        minimum,
    })
}

/// Measures and refits Karis' `D_TT ~ exp(-3.65 cos phi - 3.98)` against `D(phi, 0.35, pi)`
/// ([`d_tt_rms_error`], [`fit_exp_cos`]).
///
/// # Errors
/// The optimiser's errors.
pub fn fit_d_tt() -> Result<ExpCosFit, FitError> {
    fit_lobe("Karis D_TT", d_tt_reference, d_tt_peak(), PUBLISHED_D_TT)
}

/// Measures and refits Karis' `D_TRT ~ exp(17 cos phi - 16.78)` against `3/4 D(phi, 0.15, 0)`
/// ([`d_trt_rms_error`], [`fit_exp_cos`]).
///
/// # Errors
/// The optimiser's errors.
pub fn fit_d_trt() -> Result<ExpCosFit, FitError> {
    fit_lobe(
        "Karis D_TRT",
        d_trt_reference,
        d_trt_peak(),
        PUBLISHED_D_TRT,
    )
}

// ---------------------------------------------------------------------------------------------
// h_TT
// ---------------------------------------------------------------------------------------------

/// The smallest |phi| at which the TT root exists: `|Phi(1, +-1) - 2 pi k| = 2 asin(1/eta')`
/// (Phi(1, h) = 2 gamma_t - 2 gamma_i + pi, Marschner 2003 eq. 3, at h = 1: gamma_i = pi/2,
/// gamma_t = asin(1/eta')).
///
/// # Errors
/// `eta_prime <= 1` or not finite.
pub fn h_tt_min_phi(eta_prime: f64) -> Result<f64, FitError> {
    let eta_prime = ParamError::check("eta_prime", eta_prime, "must be > 1", |e| e > 1.0)?;
    Ok(min_phi(1.0 / eta_prime))
}

fn min_phi(a: f64) -> f64 {
    2.0 * a.asin()
}

/// The exact TT offset: the h in [-1, 1] with `Phi(1, h) = phi (mod 2 pi)`, where
/// `Phi(1, h) = 2 gamma_t - 2 gamma_i + pi`, sin gamma_i = h, sin gamma_t = a h, a = 1/eta'
/// (Marschner 2003 eq. 3): `h = sign(phi) cos(phi/2) / sqrt(1 + a^2 - 2 a sin(|phi|/2))`
/// (Karis 2016). Derivation: with delta = gamma_i - gamma_t = (pi - Phi)/2, `a sin gamma_i =
/// sin(gamma_i - delta)` gives `tan gamma_i = sin delta / (cos delta - a)` (cos delta >= a for
/// a < 1). Sign convention: phi is the relative azimuth in [-pi, pi] and h > 0 exits at
/// phi > 0 (Phi(1, h) in (0, pi)); phi < 0 is Phi - 2 pi.
///
/// # Errors
/// `eta_prime <= 1`; `phi` outside [-pi, pi] or |phi| < [`h_tt_min_phi`] (no root).
pub fn h_tt_exact(eta_prime: f64, phi: f64) -> Result<f64, FitError> {
    let lo = h_tt_min_phi(eta_prime)?;
    let phi = ParamError::check(
        "phi",
        phi,
        "must satisfy 2 asin(1/eta') <= |phi| <= pi (where the TT root exists)",
        |p| (lo..=PI).contains(&p.abs()),
    )?;
    Ok(signed_h_tt(1.0 / eta_prime, phi))
}

/// [`h_tt_exact`]'s closed form with its denominator as a hypotenuse: with x = |phi|/2,
/// `1 + a^2 - 2 a sin x = cos^2 x + (sin x - a)^2`, so `h = cos x / hypot(cos x, sin x - a)`
/// (and `sqrt(1 - h^2) = cos gamma_i = (sin x - a) / hypot`). Near the smallest phi, sin x - a
/// is near 0 and h near 1, where the expanded form loses 12 digits to cancellation at
/// eta' = 1.0001 and asin(h) magnifies the loss to 2e-7 rad in the exit angle; the hypotenuse
/// keeps h within a few ulps.
fn signed_h_tt(a: f64, phi: f64) -> f64 {
    let (sin_x, cos_x) = (0.5 * phi.abs()).sin_cos();
    (cos_x / cos_x.hypot(sin_x - a)).copysign(phi)
}

/// The `h_TT` metric's grid: (a = 1/eta', phi) on 81 uniform theta_d in [0, 80 deg] (eta' from
/// `eta`) times 201 uniform phi in [2 asin a, pi] (the positive half: the forms are even).
fn h_tt_grid(eta: f64) -> Vec<(f64, f64)> {
    let mut grid = Vec::with_capacity(H_TT_THETA_NODES * H_TT_PHI_NODES);
    for i in 0..H_TT_THETA_NODES {
        let theta_d = H_TT_MAX_THETA_D * i as f64 / (H_TT_THETA_NODES - 1) as f64;
        let a = 1.0 / bravais_eta_perpendicular(eta, theta_d.sin());
        let lo = min_phi(a);
        for j in 0..H_TT_PHI_NODES {
            let phi = lo + (PI - lo) * j as f64 / (H_TT_PHI_NODES - 1) as f64;
            grid.push((a, phi));
        }
    }
    grid
}

/// Errors of an `h_TT` approximation over the metric's domain.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct HTtError {
    /// RMS of `|h_approx - |h_exact||` over the grid.
    pub rms: f64,
    /// Maximum of `|h_approx - |h_exact||` over the grid.
    pub max: f64,
}

/// Errors of `(1 + a (c1 - c2 cos phi)) cos(phi/2)` against `reference(a, phi)` on the grid of
/// [`h_tt_errors`].
fn h_tt_errors_against(reference: &impl Fn(f64, f64) -> f64, eta: f64, c: [f64; 2]) -> HTtError {
    let grid = h_tt_grid(eta);
    let c = HTtCoefficients::from(c);
    let (sum, max) = grid.iter().fold((0.0, 0.0_f64), |(sum, max), &(a, phi)| {
        let e = (h_tt_karis(a, phi, c) - reference(a, phi)).abs();
        (sum + e * e, max.max(e))
    });
    HTtError {
        rms: (sum / grid.len() as f64).sqrt(),
        max,
    }
}

/// The metric of Karis' `h_TT ~ (1 + a (c1 - c2 cos phi)) cos(phi/2)` ([`h_tt_karis`]) against
/// |[`h_tt_exact`]|: RMS and maximum of the absolute difference over a uniform grid of 81
/// theta_d in [0, 80 deg] (eta' = Bravais' index of `settings.eta`, a = 1/eta') times 201 phi
/// in [2 asin a, pi], the azimuths where the TT root exists (each theta_d weighted equally).
///
/// # Errors
/// Invalid `settings.eta`; non-finite `c1`, `c2`.
pub fn h_tt_errors(settings: &FitSettings, c1: f64, c2: f64) -> Result<HTtError, FitError> {
    let eta = checked(settings)?.eta;
    let c = [finite("c1", c1)?, finite("c2", c2)?];
    let exact = |a: f64, phi: f64| signed_h_tt(a, phi).abs();
    Ok(h_tt_errors_against(&exact, eta, c))
}

/// Linear least-squares fit of `(c1, c2)` in `(1 + a (c1 - c2 cos phi)) cos(phi/2)` to
/// `reference(a, phi)` on the grid of [`h_tt_errors`] for `settings.eta` (nalgebra SVD): the
/// residual `reference - cos(phi/2)` against the columns `a cos(phi/2)`, `-a cos phi
/// cos(phi/2)`, which minimises the RMS of [`h_tt_errors`]. (The columns are the partial
/// derivatives of [`h_tt_karis`], which is affine in `(c1, c2)`, not a second evaluator.)
///
/// # Errors
/// Invalid `settings.eta`; a degenerate design matrix.
pub fn fit_h_tt_to(
    settings: &FitSettings,
    reference: impl Fn(f64, f64) -> f64,
) -> Result<[f64; 2], FitError> {
    let grid = h_tt_grid(checked(settings)?.eta);
    let rows: Vec<Vec<f64>> = grid
        .iter()
        .map(|&(a, phi)| {
            let half = (0.5 * phi).cos();
            vec![a * half, -a * phi.cos() * half]
        })
        .collect();
    let targets: Vec<f64> = grid
        .iter()
        .map(|&(a, phi)| reference(a, phi) - (0.5 * phi).cos())
        .collect();
    let c = linear_least_squares("Karis h_TT", &rows, &targets)?;
    Ok([c[0], c[1]])
}

/// Karis' TT offset, published against refitted.
#[derive(Clone, Debug, PartialEq)]
pub struct HTtFit {
    /// Published `(c1, c2)` = (0.6, 0.8).
    pub published: [f64; 2],
    /// Least-squares refit of `(c1, c2)`.
    pub refit: [f64; 2],
    /// [`h_tt_errors`] of the published constants.
    pub published_error: HTtError,
    /// [`h_tt_errors`] of the refit.
    pub refit_error: HTtError,
}

/// Measures Karis' `h_TT ~ (1 + a (0.6 - 0.8 cos phi)) cos(phi/2)` against the exact offset
/// ([`h_tt_exact`]) at `settings.eta` and refits `(c1, c2)` ([`fit_h_tt_to`]).
///
/// # Errors
/// Invalid `settings.eta`; a degenerate design matrix.
pub fn fit_h_tt(settings: &FitSettings) -> Result<HTtFit, FitError> {
    let refit = fit_h_tt_to(settings, |a, phi| signed_h_tt(a, phi).abs())?;
    let [c1, c2] = PUBLISHED_H_TT;
    Ok(HTtFit {
        published: PUBLISHED_H_TT,
        refit,
        published_error: h_tt_errors(settings, c1, c2)?,
        refit_error: h_tt_errors(settings, refit[0], refit[1])?,
    })
}

// ---------------------------------------------------------------------------------------------
// Records and generated constants
// ---------------------------------------------------------------------------------------------

/// What one closed form contributes to [`FitOutput`].
struct Family<'a> {
    key: &'a str,
    names: [&'a str; 2],
    constant: &'a str,
    formula: &'a str,
    approximates: String,
    metric: String,
    published: [f64; 2],
    refit: [f64; 2],
    published_error: f64,
    refit_error: f64,
    /// Extra documentation lines (for example a maximum error besides the RMS).
    extra: Vec<String>,
}

impl Family<'_> {
    fn records(&self) -> Vec<ConstantFit> {
        (0..2)
            .map(|i| ConstantFit {
                key: format!("karis.{}.{}", self.key, self.names[i]),
                source: SOURCE.into(),
                approximates: self.approximates.clone(),
                published: Some(self.published[i]),
                refit: self.refit[i],
                metric: self.metric.clone(),
                published_error: Some(self.published_error),
                refit_error: self.refit_error,
            })
            .collect()
    }

    fn constant(&self) -> GeneratedConst {
        let mut doc = vec![
            format!("`{}` ({SOURCE}), refitted.", self.formula),
            format!("Approximates {}.", self.approximates),
            format!("Metric: {}.", self.metric),
            format!(
                "Error of this refit: {:.3e}; of Karis' published [{}, {}]: {:.3e}.",
                self.refit_error, self.published[0], self.published[1], self.published_error
            ),
        ];
        doc.extend(self.extra.iter().cloned());
        GeneratedConst {
            name: self.constant.into(),
            doc,
            value: ConstValue::Array(self.refit.to_vec()),
        }
    }
}

fn eta_prime_family(eta: f64, fit: &EtaPrimeFit) -> Family<'static> {
    Family {
        key: "eta_prime",
        names: ["a", "b"],
        constant: "KARIS_ETA_PRIME",
        formula: "eta' ~ a / cos theta_d + b cos theta_d",
        approximates: format!(
            "eta' = sqrt(eta^2 - sin^2 theta_d) / cos theta_d at eta = {eta} (minimax refit, Nelder-Mead)"
        ),
        metric: "max |approx / exact - 1| over theta_d in [0, 90 deg) with the grazing limit"
            .into(),
        published: fit.published,
        refit: fit.refit,
        published_error: fit.published_error,
        refit_error: fit.refit_error,
        extra: vec![format!(
            "Karis claims error < 0.68%; the published constants stay below it up to theta_d = {:.3e} deg (worst at {:.3e} deg).",
            fit.claim_holds_up_to.to_degrees(),
            fit.published_worst_theta_d.to_degrees()
        )],
    }
}

fn lobe_family<'a>(
    key: &'a str,
    constant: &'a str,
    approximates: &str,
    fit: &ExpCosFit,
) -> Family<'a> {
    Family {
        key,
        names: ["a", "b"],
        constant,
        formula: "D ~ exp(a cos phi + b)",
        approximates: format!("{approximates} (least-squares refit, Nelder-Mead)"),
        metric: "RMS error over phi in [0, pi] / the reference's peak".into(),
        published: fit.published,
        refit: fit.refit,
        published_error: fit.published_error,
        refit_error: fit.refit_error,
        extra: Vec::new(),
    }
}

fn h_tt_family(eta: f64, fit: &HTtFit) -> Family<'static> {
    Family {
        key: "h_tt",
        names: ["c1", "c2"],
        constant: "KARIS_H_TT",
        formula: "h_TT ~ (1 + a (c1 - c2 cos phi)) cos(phi/2), a = 1/eta'",
        approximates: format!(
            "|h_TT| = cos(phi/2) / sqrt(1 + a^2 - 2 a sin(|phi|/2)), the root of Phi(1, h) = phi, at eta = {eta} (linear least squares)"
        ),
        metric: "RMS |h - h_exact| over theta_d in [0, 80 deg] x |phi| in [2 asin(1/eta'), pi]"
            .into(),
        published: fit.published,
        refit: fit.refit,
        published_error: fit.published_error.rms,
        refit_error: fit.refit_error.rms,
        extra: vec![format!(
            "Maximum |h - h_exact| of this refit: {:.3e}; of the published constants: {:.3e}.",
            fit.refit_error.max, fit.published_error.max
        )],
    }
}

/// Karis' four closed forms (Karis 2016, `HairBsdf.ush`): Bravais' index, `D_TT`, `D_TRT` and
/// the TT offset, each measured and refitted ([`fit_eta_prime`], [`fit_d_tt`], [`fit_d_trt`],
/// [`fit_h_tt`]). Records `karis.{eta_prime,d_tt,d_trt}.{a,b}` and `karis.h_tt.{c1,c2}`;
/// constants `KARIS_ETA_PRIME`, `KARIS_D_TT`, `KARIS_D_TRT`, `KARIS_H_TT` (refitted
/// coefficients in the published order).
///
/// # Errors
/// Invalid `settings.eta`; any fit's errors.
pub fn karis_fits(settings: &FitSettings) -> Result<FitOutput, FitError> {
    let eta = checked(settings)?.eta;
    let (d_tt, d_trt) = (fit_d_tt()?, fit_d_trt()?);
    let families = [
        eta_prime_family(eta, &fit_eta_prime(settings)?),
        lobe_family("d_tt", "KARIS_D_TT", "D_TT = D(phi, 0.35, pi)", &d_tt),
        lobe_family(
            "d_trt",
            "KARIS_D_TRT",
            "D_TRT = 3/4 D(phi, 0.15, 0)",
            &d_trt,
        ),
        h_tt_family(eta, &fit_h_tt(settings)?),
    ];
    Ok(FitOutput {
        records: families.iter().flat_map(Family::records).collect(),
        constants: families.iter().map(Family::constant).collect(),
    })
}
