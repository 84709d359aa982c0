//! Frostbite's approximations of the transmitted lobes (Tafuri 2019, "Strand-based Hair
//! Rendering in Frostbite", SIGGRAPH 2019 Advances in Real-Time Rendering course, slides
//! 13-21), regenerated and measured against Chiang et al. 2016's far-field model.
//!
//! Frostbite separates each azimuthal lobe `N_p = 1/2 int A_p(h) D_p(phi - Phi(p, h)) dh`
//! (slide 13) into an attenuation and a distribution, and approximates both:
//!
//! - the TT distribution (slides 18-19), a function of (phi, theta_o, beta_n), by one Gaussian
//!   `a exp(-b (|phi| - pi)^2)` per (theta_o, beta_n) slice, whose (a, b) fill a 2D table
//!   ([`TtGaussianTable`]);
//! - the TT and TRT attenuations (slides 17, 20, 21) by `A_p` at one offset, h = 0 for TT and
//!   h = sqrt(3)/2 for TRT, instead of the h-average ([`AttenuationProblem`]).
//!
//! Both closed forms are in [`crate::models`] ([`tt_gaussian`], [`offset_attenuation`]); this
//! module holds the references they approximate, the fits and the error tables.
//!
//! Conventions are hairmath's (README, "Conventions"): `phi = phi_i - phi_o` as in pbrt, so the
//! TT lobe peaks at |phi| = pi; sigma_a per unit fibre radius with the exact chord
//! `2 cos(gamma_t) / cos(theta_t)`; Chiang's attenuation ([`crate::azimuthal::attenuations`]) with the entry
//! Fresnel term at the true angle of incidence.

use super::{
    check_eta, is_coordinate_minimum, linear_least_squares, minimize, minimize_scalar, ConstValue,
    ConstantFit, FitError, FitOutput, FitSettings, GeneratedConst, Minimum,
};
use crate::absorption::Absorption;
use crate::azimuthal::{exit_angle_of_offset, trimmed_logistic};
use crate::bcsdf::logistic_scale;
use crate::error::ParamError;
use crate::models::{offset_attenuation, tt_gaussian, Transmitted};
use crate::params::AzimuthalRoughness;
use crate::quadrature::{gauss_legendre, integrate};
use crate::real::wrap_angle;
use core::f64::consts::{FRAC_PI_2, PI};

/// theta_o axis of the TT Gaussian table, degrees (0, 10, ..., 80).
pub const TT_THETA_O_DEG: [f64; 9] = [0.0, 10.0, 20.0, 30.0, 40.0, 50.0, 60.0, 70.0, 80.0];
/// beta_n axis of the TT Gaussian table (0.1, 0.2, ..., 1.0).
pub const TT_BETA_N: [f64; 10] = [0.1, 0.2, 0.3, 0.4, 0.5, 0.6, 0.7, 0.8, 0.9, 1.0];
/// Number of equally spaced phi in [0, pi] (endpoints included) at which each slice is fitted.
pub const TT_PHI_SAMPLES: usize = 181;
/// Gauss-Legendre panels (8 nodes each) per smooth piece of the D_TT integral. Doubling them
/// changes D_TT by at most 1.2e-9 of the peak over the table's grid at beta_n = 0.1, the
/// narrowest slices (measured by the tests), far below the Gaussians' errors (> 2e-3).
pub const TT_PANELS: usize = 48;
/// sigma_a axis of the attenuation error tables (per unit fibre radius).
pub const ATTENUATION_SIGMA_A: [f64; 7] = [0.0, 0.1, 0.25, 0.5, 1.0, 2.0, 4.0];
/// theta_d axis of the attenuation error tables, degrees.
pub const ATTENUATION_THETA_D_DEG: [f64; 7] = [0.0, 15.0, 30.0, 45.0, 60.0, 75.0, 85.0];
/// Frostbite's TT offset (slide 20): `A_TT` evaluated at h = 0
/// ([`Transmitted::published_offset`]).
pub const PUBLISHED_TT_OFFSET_H: f64 = Transmitted::Tt.published_offset();
/// Frostbite's TRT offset (slide 21, Karis 2016's constant): `A_TRT` at h = sqrt(3)/2
/// ([`Transmitted::published_offset`]).
pub const PUBLISHED_TRT_OFFSET_H: f64 = Transmitted::Trt.published_offset();

const SOURCE: &str = "Tafuri 2019, Strand-based Hair Rendering in Frostbite (SIGGRAPH course)";

fn check_theta(name: &'static str, theta: f64) -> Result<f64, ParamError> {
    ParamError::check(name, theta, "inclination must be in [-pi/2, pi/2]", |v| {
        v.abs() <= FRAC_PI_2
    })
}

// ---------------------------------------------------------------------------------------------
// The TT distribution
// ---------------------------------------------------------------------------------------------

/// One (theta_o, beta_n) slice of Frostbite's TT distribution (slides 18-19):
/// `D_TT(phi) = 1/2 int_{-1}^{1} D(phi - Phi(1, h)) dh`, D the trimmed logistic of scale
/// `s = logistic_scale(beta_n)` (Chiang et al. 2016, eqs. 8 and 13) and Phi(1, h) the TT exit
/// angle for a ray inclined at theta_o ([`exit_angle_of_offset`]): Chiang's far-field `N_TT`
/// with the attenuation left out, a density on the circle.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TtSlice {
    sin_theta_o: f64,
    eta: f64,
    s: f64,
}

impl TtSlice {
    /// The slice at inclination `theta_o` (radians) and azimuthal roughness `beta_n`, for
    /// refractive index `eta`.
    ///
    /// # Errors
    /// `theta_o` outside [-pi/2, pi/2], `beta_n` outside (0, 1], `eta` outside (1, 3].
    pub fn new(theta_o: f64, beta_n: f64, eta: f64) -> Result<Self, ParamError> {
        let theta_o = check_theta("theta_o", theta_o)?;
        let beta_n = AzimuthalRoughness::new(beta_n)?.get();
        Ok(TtSlice {
            sin_theta_o: theta_o.sin(),
            eta: check_eta(eta)?,
            s: logistic_scale(beta_n),
        })
    }

    /// `D_TT(phi)` (phi in radians, wrapped to [-pi, pi]) with [`TT_PANELS`] panels.
    pub fn distribution(&self, phi: f64) -> f64 {
        self.distribution_with(phi, TT_PANELS)
    }

    /// `D_TT(phi)` integrated in gamma = asin h (`dh = cos gamma dgamma`) by composite 8-point
    /// Gauss-Legendre with `panels` panels on each smooth piece of [-pi/2, pi/2]. Phi(1, gamma)
    /// decreases strictly (its derivative is `2 cos(gamma) / (eta' cos(gamma_t)) - 2 < 0`), so
    /// the peak `Phi = phi` and the kink of the wrap `Phi = phi + pi` each occur at most once;
    /// they split the interval, and on each piece the integrand is analytic.
    pub fn distribution_with(&self, phi: f64, panels: usize) -> f64 {
        let mut edges = vec![-FRAC_PI_2, FRAC_PI_2];
        edges.extend(self.crossing(phi));
        edges.extend(self.crossing(phi + PI));
        edges.sort_by(f64::total_cmp);
        let rule = gauss_legendre(8);
        edges
            .windows(2)
            .map(|w| integrate(&rule, panels, w[0], w[1], |g| self.integrand(phi, g)))
            .sum()
    }

    fn exit_angle(&self, gamma: f64) -> f64 {
        exit_angle_of_offset(1.0, gamma.sin(), self.eta, self.sin_theta_o)
    }

    fn integrand(&self, phi: f64, gamma: f64) -> f64 {
        let x = wrap_angle(phi - self.exit_angle(gamma));
        0.5 * gamma.cos() * trimmed_logistic(x, self.s)
    }

    /// The gamma in (-pi/2, pi/2) where Phi(1, gamma) = target (mod 2 pi), by bisection on the
    /// monotone Phi, which runs from pi + c down to pi - c with c < pi.
    fn crossing(&self, target: f64) -> Option<f64> {
        let t = PI + wrap_angle(target - PI);
        let (mut lo, mut hi) = (-FRAC_PI_2, FRAC_PI_2);
        if !(t < self.exit_angle(lo) && t > self.exit_angle(hi)) {
            return None;
        }
        for _ in 0..64 {
            let mid = 0.5 * (lo + hi);
            if self.exit_angle(mid) > t {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        Some(0.5 * (lo + hi))
    }
}

// ---------------------------------------------------------------------------------------------
// The per-slice Gaussian
// ---------------------------------------------------------------------------------------------

/// The Gaussian fitted to one slice, and its error relative to the slice's peak.
#[derive(Clone, Debug, PartialEq)]
pub struct GaussianSliceFit {
    /// Height a.
    pub a: f64,
    /// Sharpness b (rad^-2).
    pub b: f64,
    /// The largest sample of the data (the peak the errors are relative to).
    pub peak: f64,
    /// RMS of `g - data` over the samples, divided by `peak`.
    pub rms_error: f64,
    /// Largest `|g - data|` over the samples, divided by `peak`.
    pub max_error: f64,
    /// The Nelder-Mead run (argmin's termination text, iterations, loss).
    pub run: Minimum,
}

/// The least-squares loss of the Gaussian fit ([`tt_gaussian`]): mean squared residual divided
/// by `peak^2`.
pub fn gaussian_loss(phi: &[f64], values: &[f64], peak: f64, params: &[f64]) -> f64 {
    let sum: f64 = phi
        .iter()
        .zip(values)
        .map(|(&x, &v)| (tt_gaussian(x, params[0], params[1]) - v).powi(2))
        .sum();
    sum / (phi.len() as f64 * peak * peak)
}

/// Fits `a exp(-b (|phi| - pi)^2)` to `(phi, values)` by least squares with argmin's
/// Nelder-Mead ([`minimize`]). The start is the weighted log-linear fit
/// `v ln v ~ v (ln a - b (|phi| - pi)^2)` ([`linear_least_squares`], samples above 1e-6 of the
/// peak), whose weights make it close to the unweighted fit.
///
/// # Errors
/// [`FitError::Param`] for fewer than 3 samples, unequal lengths, a non-finite sample or no
/// positive value; the optimisers' errors otherwise.
pub fn fit_gaussian_slice(phi: &[f64], values: &[f64]) -> Result<GaussianSliceFit, FitError> {
    ParamError::check(
        "values.len()",
        values.len() as f64,
        "one value per phi, at least 3",
        |n| n as usize == phi.len() && n >= 3.0,
    )?;
    for &v in phi.iter().chain(values) {
        ParamError::check("sample", v, "samples must be finite", |_| true)?;
    }
    let peak = values.iter().fold(0.0_f64, |m, &v| m.max(v));
    ParamError::check("peak", peak, "some value must be positive", |p| p > 0.0)?;
    let start = log_linear_start(phi, values, peak)?;
    let loss = |p: &[f64]| gaussian_loss(phi, values, peak, p);
    let step = [0.05 * start[0], 0.05 * start[1].abs() + 1e-3];
    let run = minimize("Frostbite TT Gaussian slice", loss, &start, &step, 1e-16)?;
    let max_error = phi.iter().zip(values).fold(0.0_f64, |m, (&x, &v)| {
        m.max((tt_gaussian(x, run.params[0], run.params[1]) - v).abs())
    });
    Ok(GaussianSliceFit {
        a: run.params[0],
        b: run.params[1],
        peak,
        rms_error: run.loss.sqrt(),
        max_error: max_error / peak,
        run,
    })
}

fn log_linear_start(phi: &[f64], values: &[f64], peak: f64) -> Result<[f64; 2], FitError> {
    let (rows, targets): (Vec<Vec<f64>>, Vec<f64>) = phi
        .iter()
        .zip(values)
        .filter(|(_, &v)| v > 1e-6 * peak)
        .map(|(&x, &v)| (vec![v, -v * (x.abs() - PI).powi(2)], v * v.ln()))
        .unzip();
    let x = linear_least_squares("Frostbite TT Gaussian start", &rows, &targets)?;
    Ok([x[0].exp(), x[1]])
}

/// The [`TT_PHI_SAMPLES`] equally spaced phi in [0, pi] of the slice fits.
pub fn tt_phi_samples() -> Vec<f64> {
    let n = TT_PHI_SAMPLES - 1;
    (0..=n).map(|k| PI * k as f64 / n as f64).collect()
}

/// Samples `slice` at [`tt_phi_samples`] (D_TT is even in phi) and fits the Gaussian.
///
/// # Errors
/// As [`fit_gaussian_slice`].
pub fn fit_tt_slice(slice: &TtSlice) -> Result<GaussianSliceFit, FitError> {
    let phi = tt_phi_samples();
    let values: Vec<f64> = phi.iter().map(|&x| slice.distribution(x)).collect();
    fit_gaussian_slice(&phi, &values)
}

/// Frostbite's 2D table of TT Gaussians (slide 19): one [`GaussianSliceFit`] per
/// (theta_o, beta_n), rows theta_o, columns beta_n.
#[derive(Clone, Debug, PartialEq)]
pub struct TtGaussianTable {
    /// Refractive index of the fibre.
    pub eta: f64,
    /// Row axis: theta_o in radians.
    pub theta_o: Vec<f64>,
    /// Column axis: beta_n.
    pub beta_n: Vec<f64>,
    /// `slices[i][j]` fits `theta_o[i]`, `beta_n[j]`.
    pub slices: Vec<Vec<GaussianSliceFit>>,
    /// (row, column) of the slice with the largest `rms_error`.
    pub worst: (usize, usize),
}

impl TtGaussianTable {
    /// Fits every slice of the grid `theta_o` (radians) x `beta_n` for refractive index `eta`.
    ///
    /// # Errors
    /// An empty axis or an invalid value ([`TtSlice::new`]); a failed fit.
    pub fn compute(eta: f64, theta_o: &[f64], beta_n: &[f64]) -> Result<Self, FitError> {
        let cells = (theta_o.len() * beta_n.len()) as f64;
        ParamError::check("grid size", cells, "both axes must be non-empty", |n| {
            n > 0.0
        })?;
        let slices = theta_o
            .iter()
            .map(|&t| {
                beta_n
                    .iter()
                    .map(|&b| fit_tt_slice(&TtSlice::new(t, b, eta)?))
                    .collect::<Result<Vec<_>, FitError>>()
            })
            .collect::<Result<Vec<_>, FitError>>()?;
        let worst = worst_cell(&slices);
        Ok(TtGaussianTable {
            eta,
            theta_o: theta_o.to_vec(),
            beta_n: beta_n.to_vec(),
            slices,
            worst,
        })
    }

    /// Frostbite's grid: [`TT_THETA_O_DEG`] x [`TT_BETA_N`].
    ///
    /// # Errors
    /// As [`TtGaussianTable::compute`].
    pub fn frostbite(eta: f64) -> Result<Self, FitError> {
        let theta_o: Vec<f64> = TT_THETA_O_DEG.iter().map(|d| d.to_radians()).collect();
        Self::compute(eta, &theta_o, &TT_BETA_N)
    }

    /// One field of every slice as a table (rows theta_o, columns beta_n).
    pub fn field(&self, f: impl Fn(&GaussianSliceFit) -> f64) -> Vec<Vec<f64>> {
        self.slices
            .iter()
            .map(|row| row.iter().map(&f).collect())
            .collect()
    }

    /// The slice with the largest RMS error.
    pub fn worst_slice(&self) -> &GaussianSliceFit {
        &self.slices[self.worst.0][self.worst.1]
    }

    /// Mean of the slices' RMS errors.
    pub fn mean_rms_error(&self) -> f64 {
        let all: Vec<f64> = self.slices.iter().flatten().map(|s| s.rms_error).collect();
        all.iter().sum::<f64>() / all.len() as f64
    }
}

fn worst_cell(slices: &[Vec<GaussianSliceFit>]) -> (usize, usize) {
    let mut worst = (0, 0);
    for (i, row) in slices.iter().enumerate() {
        for (j, s) in row.iter().enumerate() {
            if s.rms_error > slices[worst.0][worst.1].rms_error {
                worst = (i, j);
            }
        }
    }
    worst
}

// ---------------------------------------------------------------------------------------------
// Single-offset attenuations
// ---------------------------------------------------------------------------------------------

/// The h-average `E_p = 1/2 int_{-1}^{1} A_p(h) dh` that the single offset
/// ([`offset_attenuation`]) replaces, for a ray inclined at `theta` (radians), as
/// `int_0^{pi/2} A_p(sin gamma) cos(gamma) dgamma` (A_p is even in h; the integrand is analytic
/// in gamma) with 8 panels of the 16-point Gauss-Legendre rule.
pub fn mean_attenuation(path: Transmitted, sigma_a: f64, theta: f64, eta: f64) -> f64 {
    let (sin_theta, cos_theta) = theta.sin_cos();
    integrate(&gauss_legendre(16), 8, 0.0, FRAC_PI_2, |g| {
        offset_attenuation(path, g.sin(), sigma_a, sin_theta, cos_theta, eta) * g.cos()
    })
}

/// The relative error of a single-offset attenuation over a grid of (sigma_a, theta_d):
/// `(A_p(h) - target) / target`, with `theta_o = theta_d` taken as the inclination of the ray
/// (the slides plot A against theta_d).
#[derive(Clone, Debug, PartialEq)]
pub struct AttenuationErrorTable {
    /// The lobe.
    pub path: Transmitted,
    /// The offset.
    pub h: f64,
    /// Row axis: sigma_a per unit radius.
    pub sigma_a: Vec<f64>,
    /// Column axis: theta_d in radians.
    pub theta_d: Vec<f64>,
    /// `relative_error[i][j]` at `sigma_a[i]`, `theta_d[j]`.
    pub relative_error: Vec<Vec<f64>>,
    /// RMS over the grid.
    pub rms: f64,
}

/// Targets of a single-offset attenuation over a (sigma_a, theta_d) grid: normally the
/// h-averages [`mean_attenuation`], or any positive table (tests use a synthetic one).
#[derive(Clone, Debug, PartialEq)]
pub struct AttenuationProblem {
    /// The lobe.
    pub path: Transmitted,
    /// Refractive index.
    pub eta: f64,
    /// Row axis: sigma_a per unit radius.
    pub sigma_a: Vec<f64>,
    /// Column axis: theta_d in radians (the ray's inclination).
    pub theta_d: Vec<f64>,
    /// `targets[i][j]` at `sigma_a[i]`, `theta_d[j]`.
    pub targets: Vec<Vec<f64>>,
}

impl AttenuationProblem {
    /// The problem against `targets(sigma_a, theta_d)`.
    ///
    /// # Errors
    /// An empty axis, `eta` outside (1, 3], sigma_a negative or non-finite, theta_d outside
    /// [-pi/2, pi/2], or a target that is not positive and finite.
    pub fn with_targets(
        path: Transmitted,
        eta: f64,
        sigma_a: &[f64],
        theta_d: &[f64],
        targets: impl Fn(f64, f64) -> f64,
    ) -> Result<Self, ParamError> {
        let eta = check_eta(eta)?;
        let cells = (sigma_a.len() * theta_d.len()) as f64;
        ParamError::check("grid size", cells, "both axes must be non-empty", |n| {
            n > 0.0
        })?;
        for &s in sigma_a {
            Absorption::grey(s)?;
        }
        for &t in theta_d {
            check_theta("theta_d", t)?;
        }
        let table = sigma_a
            .iter()
            .map(|&s| theta_d.iter().map(|&t| targets(s, t)).collect())
            .collect::<Vec<Vec<f64>>>();
        for &v in table.iter().flatten() {
            ParamError::check("target", v, "targets must be positive", |v| v > 0.0)?;
        }
        Ok(AttenuationProblem {
            path,
            eta,
            sigma_a: sigma_a.to_vec(),
            theta_d: theta_d.to_vec(),
            targets: table,
        })
    }

    /// The problem against the h-average [`mean_attenuation`].
    ///
    /// # Errors
    /// As [`AttenuationProblem::with_targets`].
    pub fn against_mean(
        path: Transmitted,
        eta: f64,
        sigma_a: &[f64],
        theta_d: &[f64],
    ) -> Result<Self, ParamError> {
        let e = check_eta(eta)?;
        Self::with_targets(path, eta, sigma_a, theta_d, |s, t| {
            mean_attenuation(path, s, t, e)
        })
    }

    /// The frostbite grid: [`ATTENUATION_SIGMA_A`] x [`ATTENUATION_THETA_D_DEG`].
    ///
    /// # Errors
    /// `eta` outside (1, 3].
    pub fn frostbite(path: Transmitted, eta: f64) -> Result<Self, ParamError> {
        let theta: Vec<f64> = ATTENUATION_THETA_D_DEG
            .iter()
            .map(|d| d.to_radians())
            .collect();
        Self::against_mean(path, eta, &ATTENUATION_SIGMA_A, &theta)
    }

    /// The relative errors of `A_p(h)` at every cell.
    pub fn error_table(&self, h: f64) -> AttenuationErrorTable {
        let relative_error: Vec<Vec<f64>> = self
            .sigma_a
            .iter()
            .zip(&self.targets)
            .map(|(&s, row)| {
                self.theta_d
                    .iter()
                    .zip(row)
                    .map(|(&t, &e)| {
                        offset_attenuation(self.path, h, s, t.sin(), t.cos(), self.eta) / e - 1.0
                    })
                    .collect()
            })
            .collect();
        let all: Vec<f64> = relative_error.iter().flatten().copied().collect();
        let rms = (all.iter().map(|x| x * x).sum::<f64>() / all.len() as f64).sqrt();
        AttenuationErrorTable {
            path: self.path,
            h,
            sigma_a: self.sigma_a.clone(),
            theta_d: self.theta_d.clone(),
            relative_error,
            rms,
        }
    }

    /// The RMS relative error of `A_p(h)` over the grid.
    pub fn rms_relative_error(&self, h: f64) -> f64 {
        self.error_table(h).rms
    }

    /// The h in [0, 1] with the smallest RMS relative error, by argmin's Brent method
    /// ([`minimize_scalar`], tolerance 1e-10).
    ///
    /// # Errors
    /// The optimiser's.
    pub fn refit(&self) -> Result<Minimum, FitError> {
        let what = format!("Frostbite {} offset h", self.path.name());
        minimize_scalar(&what, |h| self.rms_relative_error(h), 0.0, 1.0, 1e-10)
    }
}

/// A single offset as published and as refitted, with their error tables.
#[derive(Clone, Debug, PartialEq)]
pub struct OffsetReport {
    /// The errors of the published offset.
    pub published: AttenuationErrorTable,
    /// The errors of the refitted offset.
    pub refit: AttenuationErrorTable,
    /// The Brent run.
    pub run: Minimum,
}

impl OffsetReport {
    /// Refits the offset of `problem` and measures it beside `published`.
    ///
    /// # Errors
    /// As [`AttenuationProblem::refit`].
    pub fn compute(problem: &AttenuationProblem, published: f64) -> Result<Self, FitError> {
        let run = problem.refit()?;
        Ok(OffsetReport {
            published: problem.error_table(published),
            refit: problem.error_table(run.params[0]),
            run,
        })
    }
}

// ---------------------------------------------------------------------------------------------
// The family's output
// ---------------------------------------------------------------------------------------------

/// Everything the Frostbite fits measure: the TT Gaussian table and the two offsets.
#[derive(Clone, Debug, PartialEq)]
pub struct FrostbiteReport {
    /// Per-slice Gaussians of D_TT.
    pub tt_gaussian: TtGaussianTable,
    /// The TT offset (published h = 0).
    pub tt_offset: OffsetReport,
    /// The TRT offset (published h = sqrt(3)/2).
    pub trt_offset: OffsetReport,
}

/// Runs every Frostbite fit on Frostbite's grids for `settings`.
///
/// # Errors
/// [`FitError::Param`] for `eta` outside (1, 3]; a failed fit.
pub fn frostbite_report(settings: &FitSettings) -> Result<FrostbiteReport, FitError> {
    let eta = check_eta(settings.eta)?;
    let offset = |path, published| {
        OffsetReport::compute(&AttenuationProblem::frostbite(path, eta)?, published)
    };
    Ok(FrostbiteReport {
        tt_gaussian: TtGaussianTable::frostbite(eta)?,
        tt_offset: offset(Transmitted::Tt, PUBLISHED_TT_OFFSET_H)?,
        trt_offset: offset(Transmitted::Trt, PUBLISHED_TRT_OFFSET_H)?,
    })
}

/// The Frostbite family of `hairmath fit`: records `frostbite.tt_offset_h`,
/// `frostbite.trt_offset_h` and `frostbite.tt_gaussian.worst_rms`, and the generated constants
/// `FROSTBITE_TT_THETA_O`, `FROSTBITE_TT_BETA_N`, `FROSTBITE_TT_GAUSSIAN_A`,
/// `FROSTBITE_TT_GAUSSIAN_B`, `FROSTBITE_TT_OFFSET_H` and `FROSTBITE_TRT_OFFSET_H`.
///
/// # Errors
/// As [`frostbite_report`].
pub fn frostbite_fits(settings: &FitSettings) -> Result<FitOutput, FitError> {
    let report = frostbite_report(settings)?;
    Ok(FitOutput {
        records: report.records(),
        constants: report.constants(),
    })
}

impl FrostbiteReport {
    /// The rows of `hairmath fit`.
    pub fn records(&self) -> Vec<ConstantFit> {
        let table = &self.tt_gaussian;
        vec![
            offset_record(&self.tt_offset, "slides 17 and 20"),
            offset_record(&self.trt_offset, "slide 21"),
            ConstantFit {
                key: "frostbite.tt_gaussian.worst_rms".into(),
                source: format!("{SOURCE}, slides 18-19 (the fitted table is not printed)"),
                approximates: format!(
                    "a measured error, not a constant: the worst over the {} slices of the RMS \
                     error of the least-squares Gaussian a exp(-b (|phi| - pi)^2) against \
                     D_TT = 1/2 int D(phi - Phi(1, h)) dh (Chiang 2016 trimmed logistic); \
                     mean over slices {:.3e}, worst max error {:.3e}",
                    table.slices.iter().flatten().count(),
                    table.mean_rms_error(),
                    table.worst_slice().max_error,
                ),
                published: None,
                refit: table.worst_slice().rms_error,
                metric: gaussian_metric(table),
                published_error: None,
                refit_error: table.worst_slice().rms_error,
            },
        ]
    }

    /// The constants of the generated file.
    pub fn constants(&self) -> Vec<GeneratedConst> {
        let table = &self.tt_gaussian;
        let axes = format!(
            "Axes of FROSTBITE_TT_GAUSSIAN_A/B ({SOURCE}, slides 18-19), eta = {}.",
            table.eta
        );
        vec![
            GeneratedConst {
                name: "FROSTBITE_TT_THETA_O".into(),
                doc: vec![
                    axes.clone(),
                    "Rows: theta_o in radians (0 to 80 degrees).".into(),
                ],
                value: ConstValue::Array(table.theta_o.clone()),
            },
            GeneratedConst {
                name: "FROSTBITE_TT_BETA_N".into(),
                doc: vec![axes, "Columns: azimuthal roughness beta_n.".into()],
                value: ConstValue::Array(table.beta_n.clone()),
            },
            gaussian_const(table, "A", "a (the height)", |s| s.a),
            gaussian_const(table, "B", "b (rad^-2, the sharpness)", |s| s.b),
            offset_const(&self.tt_offset, "FROSTBITE_TT_OFFSET_H", "0"),
            offset_const(&self.trt_offset, "FROSTBITE_TRT_OFFSET_H", "sqrt(3)/2"),
        ]
    }
}

fn gaussian_metric(table: &TtGaussianTable) -> String {
    format!(
        "RMS of (g - D_TT) / max D_TT over {} equally spaced phi in [0, pi], per slice of \
         theta_o x beta_n = {} x {}, eta = {}",
        TT_PHI_SAMPLES,
        table.theta_o.len(),
        table.beta_n.len(),
        table.eta
    )
}

fn gaussian_const(
    table: &TtGaussianTable,
    suffix: &str,
    what: &str,
    field: impl Fn(&GaussianSliceFit) -> f64,
) -> GeneratedConst {
    let worst = table.worst_slice();
    GeneratedConst {
        name: format!("FROSTBITE_TT_GAUSSIAN_{suffix}"),
        doc: vec![
            format!(
                "Frostbite's TT distribution LUT ({SOURCE}, slide 19): {what} of \
                 g(phi) = a exp(-b (|phi| - pi)^2)"
            ),
            "fitted per slice to D_TT(phi; theta_o, beta_n) = 1/2 int_{-1}^{1} \
             D(phi - Phi(1, h)) dh, D Chiang 2016's trimmed logistic (eqs. 8, 13)."
                .into(),
            "Rows FROSTBITE_TT_THETA_O, columns FROSTBITE_TT_BETA_N; phi = phi_i - phi_o.".into(),
            format!("Metric: {}.", gaussian_metric(table)),
            format!(
                "Measured: mean RMS {:.3e}, worst RMS {:.3e} and max error {:.3e} (at theta_o \
                 = {:.0} deg, beta_n = {:.1}); the paper prints no values.",
                table.mean_rms_error(),
                worst.rms_error,
                worst.max_error,
                table.theta_o[table.worst.0].to_degrees(),
                table.beta_n[table.worst.1],
            ),
        ],
        value: ConstValue::Table(table.field(field)),
    }
}

fn offset_metric(table: &AttenuationErrorTable) -> String {
    format!(
        "RMS over sigma_a in {:?} x theta_d in {:?} deg (theta_o = theta_d) of \
         (A_{}(h) - E)/E, E = 1/2 int A dh, Chiang 2016 attenuation with chord transmittance",
        table.sigma_a,
        table
            .theta_d
            .iter()
            .map(|t| t.to_degrees().round())
            .collect::<Vec<_>>(),
        table.path.name()
    )
}

fn offset_record(report: &OffsetReport, slides: &str) -> ConstantFit {
    let name = report.refit.path.name();
    ConstantFit {
        key: format!("frostbite.{}_offset_h", name.to_lowercase()),
        source: format!("{SOURCE}, {slides}"),
        approximates: format!(
            "the single offset h at which A_{name}(h) stands in for its h-average; refit by \
             argmin Brent on [0, 1]"
        ),
        published: Some(report.published.h),
        refit: report.refit.h,
        metric: offset_metric(&report.refit),
        published_error: Some(report.published.rms),
        refit_error: report.refit.rms,
    }
}

fn offset_const(report: &OffsetReport, name: &str, published: &str) -> GeneratedConst {
    let path = report.refit.path.name();
    GeneratedConst {
        name: name.into(),
        doc: vec![
            format!(
                "The offset h at which Frostbite evaluates A_{path} instead of its h-average \
                 ({SOURCE}; published h = {published}), refitted."
            ),
            format!("Metric: {}.", offset_metric(&report.refit)),
            format!(
                "Measured: refit {:.3e}, published {:.3e}.",
                report.refit.rms, report.published.rms
            ),
        ],
        value: ConstValue::Scalar(report.refit.h),
    }
}

/// Whether the fitted Gaussian of `fit` is a coordinate-wise minimum of its loss on the data
/// (steps of `relative_step` of each parameter; [`is_coordinate_minimum`]).
pub fn is_gaussian_minimum(
    phi: &[f64],
    values: &[f64],
    fit: &GaussianSliceFit,
    relative_step: f64,
) -> bool {
    is_coordinate_minimum(
        |p| gaussian_loss(phi, values, fit.peak, p),
        &[fit.a, fit.b],
        relative_step,
    )
}
