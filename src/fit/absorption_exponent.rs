//! Gerard's absorption exponents, refitted and measured.
//!
//! Gerard (Fast Real-Time Shading for Polygonal Hair) scales the TT and TRT lobes by
//! `exp(-4 sigma_a)` (eqs. 8 and 12) and `exp(-11/2 sigma_a)` (eq. 13), and prints eq. 8's TRT
//! exponent as `8 sigma_a (1 - 3 / (2 eta^2))`; these closed forms are in [`crate::models`]
//! ([`gerard_attenuation`], [`GERARD_K_TT`], [`GERARD_K_TRT`], [`gerard_eq8_trt_printed`],
//! [`gerard_eq8_trt_corrected`]), and this module measures and refits them. They come from Marschner et al. 2003's exponent
//! `2 sigma_a (1 + cos 2 gamma_t) / cos theta_t = 4 sigma_a cos^2(gamma_t) / cos theta_t` per
//! internal segment ([`PathLength::Marschner2003`]). At theta = 0 Snell's law in the normal plane
//! gives `sin gamma_t = h / eta`, so p segments at offset h carry
//! `4 p sigma_a (1 - h^2 / eta^2)`:
//!
//! - TT (p = 1) at h = 0: `4 sigma_a`, Gerard's 4.
//! - TRT (p = 2) at h = sqrt(3)/2: `8 sigma_a (1 - 3 / (4 eta^2))` = 5.5026 sigma_a at
//!   eta = 1.55, Gerard's 11/2. The printed `8 (1 - 3 / (2 eta^2))` = 3.0052 would need
//!   h^2 = 3/2, an offset outside the fibre; with 4 in place of the printed 2, eq. 8 agrees
//!   with eq. 13 to 5e-4 relative, so the 2 is most likely a misprint.
//!
//! Here the attenuation of a whole lobe is its energy over the offsets
//! `E_p(sigma_a; theta) = 1/2 int_{-1}^{1} A_p(h; sigma_a, theta) dh` (A_p from
//! [`crate::azimuthal::attenuations`], as in [`crate::bcsdf`]), and k is fitted by least squares
//! to `E_p(sigma_a) / E_p(0)` over sigma_a in [0, 2], for both path-length forms and for two
//! direction settings ([`Directions`]).

use crate::absorption::Absorption;
use crate::absorption::PathLength;
use crate::azimuthal::attenuations_at_offset;
use crate::error::ParamError;
use crate::fit::{
    minimize_scalar, ConstValue, ConstantFit, FitError, FitOutput, FitSettings, GeneratedConst,
    Minimum,
};
use crate::models::{
    gerard_attenuation, gerard_eq8_trt_corrected, gerard_eq8_trt_printed, GERARD_K_TRT, GERARD_K_TT,
};
use crate::quadrature::gauss_legendre;
use core::f64::consts::FRAC_PI_2;

/// The lobes Gerard attenuates: TT (one internal segment) and TRT (two).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Lobe {
    /// Transmission-transmission, p = 1.
    Tt,
    /// Transmission-reflection-transmission, p = 2.
    Trt,
}

impl Lobe {
    /// Both lobes, in the order of every table of this module.
    pub const ALL: [Lobe; 2] = [Lobe::Tt, Lobe::Trt];

    /// Index p of the lobe in [`crate::azimuthal::attenuations`] (its number of internal
    /// segments).
    pub fn index(self) -> usize {
        match self {
            Lobe::Tt => 1,
            Lobe::Trt => 2,
        }
    }

    /// `tt` or `trt`, as in the record keys.
    pub fn key(self) -> &'static str {
        match self {
            Lobe::Tt => "tt",
            Lobe::Trt => "trt",
        }
    }

    /// Gerard's exponent: 4 for TT (eq. 12), 11/2 for TRT (eq. 13) ([`GERARD_K_TT`],
    /// [`GERARD_K_TRT`]).
    pub fn gerard_k(self) -> f64 {
        match self {
            Lobe::Tt => GERARD_K_TT,
            Lobe::Trt => GERARD_K_TRT,
        }
    }

    /// Where [`Lobe::gerard_k`] is printed.
    fn gerard_source(self) -> &'static str {
        match self {
            Lobe::Tt => {
                "Gerard, Fast Real-Time Shading for Polygonal Hair, eqs. 8 and 12: e^{-4 sigma_a}"
            }
            Lobe::Trt => {
                "Gerard, Fast Real-Time Shading for Polygonal Hair, eq. 13: e^{-11/2 sigma_a}"
            }
        }
    }
}

/// The directions of the incident ray over which the lobe energy is taken.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Directions {
    /// The ray in the fibre's normal plane, theta = 0.
    Theta0,
    /// The energy averaged uniformly in solid angle over all directions: over theta in
    /// [-pi/2, pi/2] with weight cos(theta) / 2 (the energy does not depend on the azimuth).
    Averaged,
}

impl Directions {
    /// Both settings, in the order of every table of this module.
    pub const ALL: [Directions; 2] = [Directions::Theta0, Directions::Averaged];

    /// `theta0` or `averaged`, as in the record keys.
    pub fn key(self) -> &'static str {
        match self {
            Directions::Theta0 => "theta0",
            Directions::Averaged => "averaged",
        }
    }
}

/// Both path-length forms, in the order of every table of this module.
pub const PATHS: [PathLength; 2] = [PathLength::Marschner2003, PathLength::Chord];

/// `marschner` or `chord`, as in the record keys.
pub(crate) fn path_key(path: PathLength) -> &'static str {
    match path {
        PathLength::Marschner2003 => "marschner",
        PathLength::Chord => "chord",
    }
}

/// Gauss-Legendre nodes of the lobe-energy integral: in gamma = asin h over [0, pi/2] (the
/// integrand `A_p(sin gamma) cos gamma` is even and analytic in gamma, unlike the
/// square-root behaviour of `A_p(h)` at h = +-1), and in theta over [0, pi/2] for
/// [`Directions::Averaged`] (the weighted energy is even and analytic in theta).
#[derive(Clone, Debug, PartialEq)]
pub struct EnergyRule {
    gamma: Vec<(f64, f64)>,
    theta: Vec<(f64, f64)>,
}

impl EnergyRule {
    /// The node counts [`EnergyRule::default`] uses; doubling them changes every energy of
    /// the fits by less than 1e-12 relative (tested).
    pub const DEFAULT_NODES: usize = 32;

    /// The rule with `gamma_nodes` nodes in gamma and `theta_nodes` in theta.
    ///
    /// # Errors
    /// A node count of 0 or above 10,000.
    pub fn new(gamma_nodes: usize, theta_nodes: usize) -> Result<Self, ParamError> {
        let allowed = "node counts must be in [1, 10000]";
        let check = |name, n: usize| {
            ParamError::check(name, n as f64, allowed, |v| (1.0..=1.0e4).contains(&v))
        };
        check("gamma_nodes", gamma_nodes)?;
        check("theta_nodes", theta_nodes)?;
        Ok(Self::unchecked(gamma_nodes, theta_nodes))
    }

    fn unchecked(gamma_nodes: usize, theta_nodes: usize) -> Self {
        EnergyRule {
            gamma: quarter_circle_rule(gamma_nodes),
            theta: quarter_circle_rule(theta_nodes),
        }
    }
}

impl Default for EnergyRule {
    /// [`EnergyRule::DEFAULT_NODES`] nodes in gamma and in theta.
    fn default() -> Self {
        Self::unchecked(Self::DEFAULT_NODES, Self::DEFAULT_NODES)
    }
}

/// The n-point Gauss-Legendre rule mapped to [0, pi/2].
fn quarter_circle_rule(n: usize) -> Vec<(f64, f64)> {
    let half = 0.5 * FRAC_PI_2;
    gauss_legendre(n)
        .into_iter()
        .map(|(x, w)| (half * (1.0 + x), half * w))
        .collect()
}

/// [E_TT, E_TRT] of a ray inclined at theta (sine and cosine, cos >= 0), unvalidated:
/// `int_0^{pi/2} A_p(sin gamma) cos gamma d gamma`, which is `1/2 int_{-1}^{1} A_p(h) dh`.
/// The geometry is [`crate::bcsdf::ChiangHair`]'s: cos theta_t from Snell's law, sin gamma_t
/// from [`crate::azimuthal::refracted_offset`] (Bravais), the entry Fresnel term at cos theta cos gamma.
fn energies_at(
    eta: f64,
    sigma_a: f64,
    path: PathLength,
    (sin_theta, cos_theta): (f64, f64),
    rule: &EnergyRule,
) -> [f64; 2] {
    let mut sum = [0.0; 2];
    for &(gamma, w) in &rule.gamma {
        let (h, cos_gamma) = gamma.sin_cos();
        let a = attenuations_at_offset(h, sin_theta, cos_theta, eta, sigma_a, path);
        for (s, lobe) in sum.iter_mut().zip(Lobe::ALL) {
            *s += w * cos_gamma * a[lobe.index()];
        }
    }
    sum
}

/// [E_TT, E_TRT] for a direction setting, unvalidated.
fn energies(
    eta: f64,
    sigma_a: f64,
    path: PathLength,
    directions: Directions,
    rule: &EnergyRule,
) -> [f64; 2] {
    match directions {
        Directions::Theta0 => energies_at(eta, sigma_a, path, (0.0, 1.0), rule),
        // 1/2 int_{-pi/2}^{pi/2} E cos theta d theta = int_0^{pi/2} E cos theta d theta.
        Directions::Averaged => rule.theta.iter().fold([0.0; 2], |acc, &(theta, w)| {
            let (sin, cos) = theta.sin_cos();
            let e = energies_at(eta, sigma_a, path, (sin, cos), rule);
            [acc[0] + w * cos * e[0], acc[1] + w * cos * e[1]]
        }),
    }
}

/// The lobe energies `[E_TT, E_TRT]`, `E_p(sigma_a) = 1/2 int_{-1}^{1} A_p(h; sigma_a, theta) dh`
/// (Chiang et al. 2016 attenuations, eqs. 3 and 6, with the internal path of `path`), at
/// theta = 0 or averaged over directions (see [`Directions`]), integrated with `rule`.
/// sigma_a is per unit fibre radius.
///
/// # Errors
/// `eta` outside (1, 3], or `sigma_a` negative or not finite.
pub fn lobe_energies(
    eta: f64,
    sigma_a: f64,
    path: PathLength,
    directions: Directions,
    rule: &EnergyRule,
) -> Result<[f64; 2], FitError> {
    let eta = FitSettings::new(eta)?.eta;
    let sigma_a = Absorption::grey(sigma_a)?.rgb()[0];
    Ok(energies(eta, sigma_a, path, directions, rule))
}

/// Upper end of the fitted absorption range [0, 2] (per unit radius).
pub const SIGMA_A_MAX: f64 = 2.0;

/// Panels and order of the composite Gauss-Legendre rule in sigma_a of the least-squares
/// loss: 8 panels of 8 nodes on [0, 2].
const LOSS_PANELS: usize = 8;
const LOSS_ORDER: usize = 8;

/// Points of the uniform grid on [0, 2] (step 0.01) over which the maximum error is taken.
pub const MAX_GRID_POINTS: usize = 201;

/// The absorptions of the small relative-error table.
pub const TABLE_SIGMA_A: [f64; 4] = [0.25, 0.5, 1.0, 2.0];

/// A target ratio `r(sigma_a)` sampled at the nodes of the composite Gauss-Legendre rule of
/// the loss (8 panels of 8 nodes on [0, 2]), with weights summing to 1 so that weighted sums are
/// means over [0, 2].
#[derive(Clone, Debug, PartialEq)]
pub struct RatioSamples {
    /// The nodes sigma_a.
    pub sigma_a: Vec<f64>,
    /// The weights (sum 1).
    pub weight: Vec<f64>,
    /// `r(sigma_a)` at the nodes.
    pub ratio: Vec<f64>,
}

impl RatioSamples {
    /// Samples `ratio` at the loss nodes.
    pub fn from_fn(ratio: impl Fn(f64) -> f64) -> Self {
        let nodes = loss_nodes();
        RatioSamples {
            ratio: nodes.iter().map(|&(s, _)| ratio(s)).collect(),
            sigma_a: nodes.iter().map(|&(s, _)| s).collect(),
            weight: nodes.iter().map(|&(_, w)| w).collect(),
        }
    }
}

/// (sigma_a, weight) of the loss rule, weights summing to 1.
fn loss_nodes() -> Vec<(f64, f64)> {
    let rule = gauss_legendre(LOSS_ORDER);
    let width = SIGMA_A_MAX / LOSS_PANELS as f64;
    (0..LOSS_PANELS)
        .flat_map(|k| {
            let centre = (k as f64 + 0.5) * width;
            rule.iter()
                .map(move |&(x, w)| (centre + 0.5 * width * x, 0.5 * width * w / SIGMA_A_MAX))
        })
        .collect()
}

/// The least-squares loss of exponent k: the mean over sigma_a in [0, 2] of
/// `(exp(-k sigma_a) - r(sigma_a))^2` ([`gerard_attenuation`]), by the Gauss-Legendre rule of
/// `samples`. Its square root is the RMS error of the approximation.
pub fn ratio_loss(k: f64, samples: &RatioSamples) -> f64 {
    samples
        .sigma_a
        .iter()
        .zip(&samples.weight)
        .zip(&samples.ratio)
        .map(|((&s, w), r)| w * (gerard_attenuation(k, s) - r).powi(2))
        .sum()
}

/// Brent's search interval for k, its absolute tolerance, and the half-width of the
/// polishing interval around the first minimum.
const K_RANGE: (f64, f64) = (0.0, 16.0);
const K_TOL: f64 = 1e-12;
const POLISH_HALF_WIDTH: f64 = 1e-5;

/// The k minimising [`ratio_loss`] on [0, 16], by argmin's Brent ([`minimize_scalar`]) run
/// twice: on k in [0, 16], then on the offset u in [-1e-5, 1e-5] of `k_1 + u` around the first
/// minimum k_1. [`minimize_scalar`] stops at a relative tolerance of 1.5e-8 |parameter|, which
/// for k near 4 leaves k uncertain by about 1e-7; in the offset it no longer limits. The
/// returned [`Minimum`] holds `k_1 + u`, the iterations of both runs and the second run's
/// termination reason.
///
/// # Errors
/// As [`minimize_scalar`], from either run.
pub fn fit_exponent(what: &str, samples: &RatioSamples) -> Result<Minimum, FitError> {
    let loss = |k: f64| ratio_loss(k, samples);
    let first = minimize_scalar(what, loss, K_RANGE.0, K_RANGE.1, K_TOL)?;
    let k1 = first.params[0];
    let polish = minimize_scalar(
        what,
        |u| loss(k1 + u),
        -POLISH_HALF_WIDTH,
        POLISH_HALF_WIDTH,
        K_TOL,
    )?;
    Ok(Minimum {
        params: vec![k1 + polish.params[0]],
        loss: polish.loss,
        iterations: first.iterations + polish.iterations,
        termination: polish.termination,
    })
}

/// The exact ratio `E_p(sigma_a) / E_p(0)` of one lobe and setting where the errors are
/// measured: at the loss nodes, on the uniform grid and at [`TABLE_SIGMA_A`].
#[derive(Clone, Debug, PartialEq)]
pub struct RatioReference {
    /// At the loss nodes (what k is fitted to).
    pub samples: RatioSamples,
    /// (sigma_a, ratio) on the uniform grid of [`MAX_GRID_POINTS`] points on [0, 2].
    pub grid: Vec<(f64, f64)>,
    /// The ratio at [`TABLE_SIGMA_A`].
    pub table: [f64; 4],
}

/// The references of both lobes, [TT, TRT], for one path form and direction setting.
fn references(
    eta: f64,
    path: PathLength,
    directions: Directions,
    rule: &EnergyRule,
) -> [RatioReference; 2] {
    let e0 = energies(eta, 0.0, path, directions, rule);
    let ratio = |sigma_a: f64| {
        let e = energies(eta, sigma_a, path, directions, rule);
        [e[0] / e0[0], e[1] / e0[1]]
    };
    let nodes = loss_nodes();
    let at_nodes: Vec<[f64; 2]> = nodes.iter().map(|&(s, _)| ratio(s)).collect();
    let grid_sigma = (0..MAX_GRID_POINTS)
        .map(|i| SIGMA_A_MAX * i as f64 / (MAX_GRID_POINTS - 1) as f64)
        .collect::<Vec<_>>();
    let at_grid: Vec<[f64; 2]> = grid_sigma.iter().map(|&s| ratio(s)).collect();
    let at_table = TABLE_SIGMA_A.map(ratio);
    core::array::from_fn(|p| RatioReference {
        samples: RatioSamples {
            sigma_a: nodes.iter().map(|&(s, _)| s).collect(),
            weight: nodes.iter().map(|&(_, w)| w).collect(),
            ratio: at_nodes.iter().map(|r| r[p]).collect(),
        },
        grid: grid_sigma
            .iter()
            .zip(&at_grid)
            .map(|(&s, r)| (s, r[p]))
            .collect(),
        table: at_table.map(|r| r[p]),
    })
}

/// The error of one approximation `exp(-k sigma_a)` of a ratio `E_p(sigma_a) / E_p(0)`.
#[derive(Clone, Debug, PartialEq)]
pub struct ApproximationError {
    /// What the exponent is (for example "refit" or "Gerard eq. 13, 11/2").
    pub label: String,
    /// The exponent k.
    pub k: f64,
    /// RMS of `|exp(-k sigma_a) - r(sigma_a)|` over sigma_a in [0, 2] (the square root of
    /// [`ratio_loss`]).
    pub rms: f64,
    /// Maximum of `|exp(-k sigma_a) - r(sigma_a)|` over the uniform grid of
    /// [`MAX_GRID_POINTS`] points on [0, 2].
    pub max_abs: f64,
    /// `(exp(-k sigma_a) - r) / r` at [`TABLE_SIGMA_A`].
    pub relative: [f64; 4],
}

impl ApproximationError {
    /// Measures `exp(-k sigma_a)` ([`gerard_attenuation`]) against `reference`.
    pub fn measure(label: &str, k: f64, reference: &RatioReference) -> Self {
        let approx = |s: f64| gerard_attenuation(k, s);
        let max_abs = reference
            .grid
            .iter()
            .fold(0.0_f64, |m, &(s, r)| m.max((approx(s) - r).abs()));
        ApproximationError {
            label: label.into(),
            k,
            rms: ratio_loss(k, &reference.samples).sqrt(),
            max_abs,
            relative: core::array::from_fn(|i| {
                (approx(TABLE_SIGMA_A[i]) - reference.table[i]) / reference.table[i]
            }),
        }
    }
}

/// One of the eight fits: a lobe, a path form and a direction setting.
#[derive(Clone, Debug, PartialEq)]
pub struct ExponentFit {
    /// The lobe.
    pub lobe: Lobe,
    /// The path-length form of the reference.
    pub path: PathLength,
    /// The direction setting of the reference.
    pub directions: Directions,
    /// The exact ratio.
    pub reference: RatioReference,
    /// argmin's Brent run; `params[0]` is the fitted k.
    pub minimum: Minimum,
    /// The errors of the refit first, then of Gerard's eq. 12 or 13 value, and for TRT of
    /// eq. 8 as printed and as corrected.
    pub errors: Vec<ApproximationError>,
}

impl ExponentFit {
    /// The fitted exponent.
    pub fn k(&self) -> f64 {
        self.minimum.params[0]
    }

    /// `tt.marschner.theta0` and so on: the key without its `gerard.absorption_k.` prefix.
    pub fn key(&self) -> String {
        fit_key(self.lobe, self.path, self.directions)
    }
}

/// `lobe.path.directions`, for example `tt.marschner.theta0`.
fn fit_key(lobe: Lobe, path: PathLength, directions: Directions) -> String {
    format!("{}.{}.{}", lobe.key(), path_key(path), directions.key())
}

/// The approximations each lobe is compared with: (label, k).
fn gerard_exponents(lobe: Lobe, eta: f64) -> Vec<(&'static str, f64)> {
    match lobe {
        Lobe::Tt => vec![("Gerard eq. 12, 4", GERARD_K_TT)],
        Lobe::Trt => vec![
            ("Gerard eq. 13, 11/2", GERARD_K_TRT),
            (
                "Gerard eq. 8 printed, 8(1-3/(2eta^2))",
                gerard_eq8_trt_printed(eta),
            ),
            (
                "eq. 8 corrected, 8(1-3/(4eta^2))",
                gerard_eq8_trt_corrected(eta),
            ),
        ],
    }
}

/// Fits one lobe against its reference and measures every approximation.
fn fit_one(
    eta: f64,
    lobe: Lobe,
    path: PathLength,
    directions: Directions,
    reference: RatioReference,
) -> Result<ExponentFit, FitError> {
    let what = format!("gerard.absorption_k.{}", fit_key(lobe, path, directions));
    let minimum = fit_exponent(&what, &reference.samples)?;
    let mut errors = vec![ApproximationError::measure(
        "refit",
        minimum.params[0],
        &reference,
    )];
    for (label, k) in gerard_exponents(lobe, eta) {
        errors.push(ApproximationError::measure(label, k, &reference));
    }
    Ok(ExponentFit {
        lobe,
        path,
        directions,
        reference,
        minimum,
        errors,
    })
}

/// All eight fits and their error tables, for the CLI.
#[derive(Clone, Debug, PartialEq)]
pub struct AbsorptionReport {
    /// The refractive index they were run for.
    pub eta: f64,
    /// TT then TRT; within a lobe [marschner theta0, marschner averaged, chord theta0,
    /// chord averaged].
    pub fits: Vec<ExponentFit>,
}

/// Runs the eight fits (TT, TRT x [`PATHS`] x [`Directions::ALL`]) for `settings.eta` with the
/// default [`EnergyRule`].
///
/// # Errors
/// `eta` outside (1, 3]; a Brent run that does not converge.
pub fn absorption_report(settings: &FitSettings) -> Result<AbsorptionReport, FitError> {
    let eta = FitSettings::new(settings.eta)?.eta;
    let rule = EnergyRule::default();
    let mut per_lobe: [Vec<ExponentFit>; 2] = [Vec::new(), Vec::new()];
    for path in PATHS {
        for directions in Directions::ALL {
            let refs = references(eta, path, directions, &rule);
            for ((fits, lobe), reference) in per_lobe.iter_mut().zip(Lobe::ALL).zip(refs) {
                fits.push(fit_one(eta, lobe, path, directions, reference)?);
            }
        }
    }
    let [tt, trt] = per_lobe;
    Ok(AbsorptionReport {
        eta,
        fits: tt.into_iter().chain(trt).collect(),
    })
}

/// The records and generated constants of Gerard's absorption exponents for `settings.eta`:
/// see [`absorption_report`] for the fits and the module documentation for their derivation.
///
/// # Errors
/// As [`absorption_report`].
pub fn absorption_fits(settings: &FitSettings) -> Result<FitOutput, FitError> {
    let report = absorption_report(settings)?;
    let mut records: Vec<ConstantFit> = report.fits.iter().map(record).collect();
    records.extend(eq8_record(&report));
    let constants = Lobe::ALL
        .iter()
        .map(|&lobe| generated(&report, lobe))
        .collect();
    Ok(FitOutput { records, constants })
}

/// The metric of every record.
const METRIC: &str = "RMS over sigma_a in [0, 2] of |exp(-k sigma_a) - E_p(sigma_a)/E_p(0)| \
                      (64-node composite Gauss-Legendre in sigma_a)";

/// What the reference of `fit` is, in words.
fn approximates(fit: &ExponentFit) -> String {
    let path = match fit.path {
        PathLength::Marschner2003 => {
            "Marschner 2003's exponent 4 sigma_a cos^2 gamma_t / cos theta_t"
        }
        PathLength::Chord => "the exact chord 2 cos gamma_t / cos theta_t",
    };
    let directions = match fit.directions {
        Directions::Theta0 => "at theta = 0",
        Directions::Averaged => "averaged uniformly in solid angle over directions",
    };
    format!(
        "E_p(sigma_a)/E_p(0) for p = {}, E_p = 1/2 int_{{-1}}^{{1}} A_p(h) dh with {path} per \
         segment, {directions}; refit by least squares over sigma_a in [0, 2] (argmin Brent)",
        fit.lobe.key().to_uppercase()
    )
}

/// The record of one fit against Gerard's eq. 12 or 13 value.
fn record(fit: &ExponentFit) -> ConstantFit {
    ConstantFit {
        key: format!("gerard.absorption_k.{}", fit.key()),
        source: fit.lobe.gerard_source().into(),
        approximates: approximates(fit),
        published: Some(fit.lobe.gerard_k()),
        refit: fit.k(),
        metric: METRIC.into(),
        published_error: Some(fit.errors[1].rms),
        refit_error: fit.errors[0].rms,
    }
}

/// The record of eq. 8's printed TRT exponent against the Marschner theta = 0 TRT refit.
fn eq8_record(report: &AbsorptionReport) -> Option<ConstantFit> {
    let fit = report.fits.iter().find(|f| {
        f.lobe == Lobe::Trt
            && f.path == PathLength::Marschner2003
            && f.directions == Directions::Theta0
    })?;
    Some(ConstantFit {
        key: "gerard.absorption_k.trt.eq8_printed".into(),
        source: "Gerard, Fast Real-Time Shading for Polygonal Hair, eq. 8 as printed: \
                 8 (1 - 3/(2 eta^2)); with 3/(4 eta^2) it is Marschner's TRT exponent at \
                 h = sqrt(3)/2, theta = 0"
            .into(),
        approximates: approximates(fit),
        published: Some(gerard_eq8_trt_printed(report.eta)),
        refit: fit.k(),
        metric: METRIC.into(),
        published_error: Some(fit.errors[2].rms),
        refit_error: fit.errors[0].rms,
    })
}

/// `GERARD_ABSORPTION_K_TT` or `_TRT`: the four fits of `lobe` in the order of
/// [`AbsorptionReport::fits`], documented with their errors.
fn generated(report: &AbsorptionReport, lobe: Lobe) -> GeneratedConst {
    let fits: Vec<&ExponentFit> = report.fits.iter().filter(|f| f.lobe == lobe).collect();
    let name = lobe.key().to_uppercase();
    let mut doc = vec![
        format!(
            "Exponents k of exp(-k sigma_a) approximating the {name} lobe's absorption \
             E_p(sigma_a)/E_p(0) (Gerard, Fast Real-Time Shading for Polygonal Hair, \
             prints k = {}), refitted for eta = {:.3}.",
            lobe.gerard_k(),
            report.eta
        ),
        "E_p = 1/2 int_{-1}^{1} A_p(h) dh (Chiang 2016 attenuations; \
         hairmath::fit::absorption_exponent); sigma_a per unit fibre radius."
            .into(),
        "Order: [Marschner 2003 exponent at theta = 0, Marschner averaged over directions \
         (uniform in solid angle), exact chord at theta = 0, chord averaged]."
            .into(),
        format!("Fit: least squares on sigma_a in [0, 2], argmin Brent. Errors: {METRIC}."),
    ];
    doc.extend(fits.iter().map(|f| doc_line(f)));
    GeneratedConst {
        name: format!("GERARD_ABSORPTION_K_{name}"),
        doc,
        value: ConstValue::Array(fits.iter().map(|f| f.k()).collect()),
    }
}

/// `- tt.marschner.theta0: refit (k = ...): RMS ..., max ...; Gerard eq. 12, 4 (k = ...): ...`.
fn doc_line(fit: &ExponentFit) -> String {
    let errors: Vec<String> = fit
        .errors
        .iter()
        .map(|e| {
            format!(
                "{} (k = {:.4e}): RMS {:.3e}, max {:.3e}",
                e.label, e.k, e.rms, e.max_abs
            )
        })
        .collect();
    format!("- {}: {}.", fit.key(), errors.join("; "))
}
