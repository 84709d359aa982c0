//! Frostbite's TT Gaussian table and single-offset attenuations (hairmath::fit::frostbite):
//! the integrals against independent quadrature, the fits against synthetic data with known
//! parameters, and the published constants against the refits. Run with `--nocapture` to see
//! the measured numbers.
#![cfg(feature = "fit")]

use hairmath::azimuthal::{exit_angle_of_offset, trimmed_logistic};
use hairmath::bcsdf::logistic_scale;
use hairmath::fit::*;
use hairmath::fit::{FitError, FitSettings};
use hairmath::models::{offset_attenuation, tt_gaussian, Transmitted};
use hairmath::real::wrap_angle;
use std::f64::consts::PI;
use std::time::Instant;

const ETA: f64 = 1.55;
const CONVERGED: &str = "Solver converged";

fn slice(theta_deg: f64, beta_n: f64) -> TtSlice {
    TtSlice::new(theta_deg.to_radians(), beta_n, ETA).unwrap()
}

/// Midpoint rule on [-pi, pi] with `n` nodes: spectrally accurate for smooth periodic functions.
fn circle_integral(n: usize, f: impl Fn(f64) -> f64) -> f64 {
    let dx = 2.0 * PI / n as f64;
    (0..n).map(|k| f(-PI + (k as f64 + 0.5) * dx)).sum::<f64>() * dx
}

#[test]
fn d_tt_integrates_to_one_over_the_circle() {
    for theta in [0.0, 40.0, 80.0] {
        for beta in [0.1, 0.4, 1.0] {
            let s = slice(theta, beta);
            let mass = circle_integral(1024, |phi| s.distribution(phi));
            assert!(
                (mass - 1.0).abs() < 1e-9,
                "theta {theta} beta {beta}: {mass}"
            );
        }
    }
}

#[test]
fn d_tt_converges_when_the_panels_double() {
    let mut worst = 0.0_f64;
    for theta in TT_THETA_O_DEG {
        let s = slice(theta, 0.1);
        let peak = s.distribution(PI);
        for phi in tt_phi_samples().into_iter().step_by(6) {
            let d = s.distribution_with(phi, TT_PANELS);
            let d2 = s.distribution_with(phi, 2 * TT_PANELS);
            worst = worst.max((d - d2).abs() / peak);
        }
    }
    println!("D_TT, beta_n = 0.1: doubling the panels changes it by {worst:.3e} of the peak");
    assert!(worst < 1e-8, "{worst}");
}

/// Brute force in h, independent of the gamma substitution and the breakpoints: the midpoint
/// rule with 2^20 nodes (its error near h = +-1, where dPhi/dh is infinite, is O(n^-1.5)).
fn brute_force(theta_deg: f64, beta_n: f64, phi: f64) -> f64 {
    let (n, sin_o, s) = (
        1 << 20,
        theta_deg.to_radians().sin(),
        logistic_scale(beta_n),
    );
    let dh = 2.0 / n as f64;
    let sum: f64 = (0..n)
        .map(|k| {
            let h = -1.0 + (k as f64 + 0.5) * dh;
            trimmed_logistic(
                wrap_angle(phi - exit_angle_of_offset(1.0, h, ETA, sin_o)),
                s,
            )
        })
        .sum();
    0.5 * sum * dh
}

#[test]
fn d_tt_matches_a_brute_force_sum_in_h() {
    let mut worst = 0.0_f64;
    for (theta, beta) in [
        (0.0, 0.1),
        (30.0, 0.1),
        (80.0, 0.1),
        (50.0, 0.3),
        (20.0, 1.0),
    ] {
        let s = slice(theta, beta);
        let peak = s.distribution(PI);
        for phi in [0.0, 1.0, 1.6, 2.2, 2.9, PI] {
            let err = (s.distribution(phi) - brute_force(theta, beta, phi)).abs() / peak;
            worst = worst.max(err);
        }
    }
    println!("D_TT against the brute-force midpoint sum in h: {worst:.3e} of the peak");
    assert!(worst < 1e-6, "{worst}");
}

#[test]
fn gaussian_fit_recovers_known_parameters() {
    let phi = tt_phi_samples();
    for (a, b) in [(0.7, 1.3), (0.16, 0.02), (2.5, 8.0)] {
        let values: Vec<f64> = phi.iter().map(|&x| tt_gaussian(x, a, b)).collect();
        let fit = fit_gaussian_slice(&phi, &values).unwrap();
        assert_eq!(fit.run.termination, CONVERGED);
        assert!(
            (fit.a / a - 1.0).abs() < 1e-6 && (fit.b / b - 1.0).abs() < 1e-5,
            "a {a} b {b}: {fit:?}"
        );
        assert!(fit.rms_error < 1e-6 && fit.max_error < 1e-5, "{fit:?}");
    }
}

#[test]
fn gaussian_fit_rejects_invalid_data() {
    let phi = tt_phi_samples();
    let err = |e: Result<GaussianSliceFit, FitError>| matches!(e, Err(FitError::Param(_)));
    assert!(err(fit_gaussian_slice(&phi, &phi[1..])));
    assert!(err(fit_gaussian_slice(&phi, &vec![0.0; phi.len()])));
    assert!(err(fit_gaussian_slice(&phi[..2], &phi[..2])));
    let mut nan = phi.clone();
    nan[3] = f64::NAN;
    assert!(err(fit_gaussian_slice(&phi, &nan)));
    assert!(TtSlice::new(0.0, 0.0, ETA).is_err());
    assert!(TtSlice::new(2.0, 0.3, ETA).is_err());
    assert!(TtSlice::new(0.0, 0.3, 1.0).is_err());
    let bad = FitSettings { eta: 0.9 };
    assert!(matches!(frostbite_fits(&bad), Err(FitError::Param(_))));
}

fn print_table(title: &str, rows: &[f64], columns: &[f64], values: &[Vec<f64>]) {
    println!("{title}");
    let header: Vec<String> = columns.iter().map(|c| format!("{c:>10.3}")).collect();
    println!("{:>8} {}", "", header.join(""));
    for (r, row) in rows.iter().zip(values) {
        let cells: Vec<String> = row.iter().map(|v| format!("{v:>10.3e}")).collect();
        println!("{r:>8.3} {}", cells.join(""));
    }
}

#[test]
fn tt_gaussian_table_fits_every_slice_to_a_minimum() {
    let start = Instant::now();
    let table = TtGaussianTable::frostbite(ETA).unwrap();
    println!("TT Gaussian table: {:.2?}", start.elapsed());
    let phi = tt_phi_samples();
    let theta_deg: Vec<f64> = table.theta_o.iter().map(|t| t.to_degrees()).collect();
    for (i, row) in table.slices.iter().enumerate() {
        for (j, fit) in row.iter().enumerate() {
            let s = TtSlice::new(table.theta_o[i], table.beta_n[j], ETA).unwrap();
            let values: Vec<f64> = phi.iter().map(|&x| s.distribution(x)).collect();
            assert_eq!(fit.run.termination, CONVERGED);
            assert!(
                is_gaussian_minimum(&phi, &values, fit, 1e-4),
                "slice {i} {j}: {fit:?}"
            );
        }
    }
    print_table(
        "a (rows theta_o deg, columns beta_n)",
        &theta_deg,
        &table.beta_n,
        &table.field(|s| s.a),
    );
    print_table("b", &theta_deg, &table.beta_n, &table.field(|s| s.b));
    print_table(
        "RMS error / peak",
        &theta_deg,
        &table.beta_n,
        &table.field(|s| s.rms_error),
    );
    print_table(
        "max error / peak",
        &theta_deg,
        &table.beta_n,
        &table.field(|s| s.max_error),
    );
    let worst = table.worst_slice();
    println!(
        "worst slice theta_o {:.0} deg beta_n {:.1}: RMS {:.3e} max {:.3e}; mean RMS {:.3e}",
        theta_deg[table.worst.0],
        table.beta_n[table.worst.1],
        worst.rms_error,
        worst.max_error,
        table.mean_rms_error()
    );
}

#[test]
fn mean_attenuation_matches_a_brute_force_sum_in_h() {
    for path in [Transmitted::Tt, Transmitted::Trt] {
        for (sigma_a, theta_deg) in [(0.0, 0.0), (0.5, 45.0), (4.0, 85.0)] {
            let theta = f64::to_radians(theta_deg);
            let n = 1 << 20;
            let dh = 1.0 / n as f64;
            let brute: f64 = (0..n)
                .map(|k| {
                    let h = (k as f64 + 0.5) * dh;
                    offset_attenuation(path, h, sigma_a, theta.sin(), theta.cos(), ETA)
                })
                .sum::<f64>()
                * dh;
            let e = mean_attenuation(path, sigma_a, theta, ETA);
            assert!(
                (e / brute - 1.0).abs() < 1e-7,
                "{path:?} {sigma_a} {theta_deg}: {e} {brute}"
            );
        }
    }
}

fn frostbite_theta_d() -> Vec<f64> {
    ATTENUATION_THETA_D_DEG
        .iter()
        .map(|d| d.to_radians())
        .collect()
}

fn assert_scalar_minimum(problem: &AttenuationProblem, h: f64) {
    let at = problem.rms_relative_error(h);
    for dh in [-1e-4, 1e-4] {
        let moved = (h + dh).clamp(0.0, 1.0);
        if moved != h {
            assert!(problem.rms_relative_error(moved) > at, "h {h} dh {dh}");
        }
    }
}

#[test]
fn offset_refit_recovers_a_known_offset() {
    for (path, h) in [(Transmitted::Tt, 0.4), (Transmitted::Trt, 0.7)] {
        let problem = AttenuationProblem::with_targets(
            path,
            ETA,
            &ATTENUATION_SIGMA_A,
            &frostbite_theta_d(),
            |s, t| offset_attenuation(path, h, s, t.sin(), t.cos(), ETA),
        )
        .unwrap();
        let run = problem.refit().unwrap();
        assert_eq!(run.termination, CONVERGED);
        assert!((run.params[0] - h).abs() < 1e-8, "{path:?}: {run:?}");
        assert!(run.loss < 1e-8, "{run:?}");
        assert_scalar_minimum(&problem, run.params[0]);
    }
}

#[test]
fn refitted_offsets_beat_the_published_ones() {
    for (path, published) in [
        (Transmitted::Tt, PUBLISHED_TT_OFFSET_H),
        (Transmitted::Trt, PUBLISHED_TRT_OFFSET_H),
    ] {
        let problem = AttenuationProblem::frostbite(path, ETA).unwrap();
        let report = OffsetReport::compute(&problem, published).unwrap();
        assert_eq!(report.run.termination, CONVERGED);
        assert_scalar_minimum(&problem, report.refit.h);
        assert!(report.refit.rms <= report.published.rms);
        // Brent found the global minimum: no h of a fine scan does better.
        let scan = (0..=200).map(|k| problem.rms_relative_error(k as f64 / 200.0));
        assert!(scan.fold(f64::INFINITY, f64::min) >= report.refit.rms);
        let deg: Vec<f64> = ATTENUATION_THETA_D_DEG.to_vec();
        for table in [&report.published, &report.refit] {
            let title = format!(
                "{} relative error of A(h = {:.6}) vs E (rows sigma_a, columns theta_d deg); RMS {:.3e}",
                path.name(),
                table.h,
                table.rms
            );
            print_table(&title, &table.sigma_a, &deg, &table.relative_error);
        }
    }
}

#[test]
fn frostbite_fits_returns_records_and_constants() {
    let start = Instant::now();
    let out = frostbite_fits(&FitSettings::default()).unwrap();
    println!("frostbite_fits: {:.2?}", start.elapsed());
    let keys: Vec<&str> = out.records.iter().map(|r| r.key.as_str()).collect();
    assert_eq!(
        keys,
        [
            "frostbite.tt_offset_h",
            "frostbite.trt_offset_h",
            "frostbite.tt_gaussian.worst_rms"
        ]
    );
    for r in &out.records {
        println!(
            "{}: published {:?} (error {:?}), refit {:.6} (error {:.3e})",
            r.key, r.published, r.published_error, r.refit, r.refit_error
        );
    }
    let names: Vec<&str> = out.constants.iter().map(|c| c.name.as_str()).collect();
    assert_eq!(
        names,
        [
            "FROSTBITE_TT_THETA_O",
            "FROSTBITE_TT_BETA_N",
            "FROSTBITE_TT_GAUSSIAN_A",
            "FROSTBITE_TT_GAUSSIAN_B",
            "FROSTBITE_TT_OFFSET_H",
            "FROSTBITE_TRT_OFFSET_H"
        ]
    );
    for c in &out.constants {
        println!("{}:\n  {}", c.name, c.doc.join("\n  "));
    }
    // The generated file is compared as text: a second run must give identical output.
    assert_eq!(frostbite_fits(&FitSettings::default()).unwrap(), out);
}
