//! Gerard's absorption exponents: the lobe energies, their quadrature, the derivation of
//! Gerard's 4 and 11/2 from Marschner's exponent, and the eight least-squares refits.

#![cfg(feature = "fit")]

use hairmath::absorption::{segment_transmittance, PathLength};
use hairmath::azimuthal::{attenuations, refracted_offset};
use hairmath::fit::constants_source;
use hairmath::fit::{
    absorption_fits, absorption_report, fit_exponent, lobe_energies, ratio_loss, Directions,
    EnergyRule, Lobe, RatioSamples, PATHS, TABLE_SIGMA_A,
};
use hairmath::fit::{is_coordinate_minimum, FitSettings};
use hairmath::models::{gerard_eq8_trt_corrected, gerard_eq8_trt_printed};
use hairmath::quadrature::adaptive;

const ETA: f64 = 1.55;

/// [A_TT, A_TRT] at offset h for theta = 0, from the crate's pieces directly.
fn attenuation_theta0(h: f64, sigma_a: f64, path: PathLength) -> [f64; 2] {
    let sin_gamma_t = refracted_offset(h, ETA, 0.0, 1.0);
    let cos_gamma_t = (1.0 - sin_gamma_t * sin_gamma_t).sqrt();
    let t = segment_transmittance(sigma_a, cos_gamma_t, 1.0, path);
    let a = attenuations(1.0, ETA, h, t);
    [a[1], a[2]]
}

/// 1/2 int_{-1}^{1} A_p dh by adaptive quadrature in h (a different variable and integrator).
fn energies_in_h(sigma_a: f64, path: PathLength) -> [f64; 2] {
    let (e, err) = adaptive(
        |h| attenuation_theta0(h, sigma_a, path).map(|a| 0.5 * a),
        -1.0,
        1.0,
        &[0.0],
        1e-13,
        0.0,
    );
    assert!(err < 1e-11, "adaptive error estimate {err}");
    e
}

#[test]
fn doubling_the_nodes_changes_no_energy_by_1e_12() {
    let n = EnergyRule::DEFAULT_NODES;
    let (base, fine) = (
        EnergyRule::default(),
        EnergyRule::new(2 * n, 2 * n).unwrap(),
    );
    let mut worst = 0.0_f64;
    for path in PATHS {
        for directions in Directions::ALL {
            for sigma_a in [0.0, 0.5, 1.0, 2.0] {
                let a = lobe_energies(ETA, sigma_a, path, directions, &base).unwrap();
                let b = lobe_energies(ETA, sigma_a, path, directions, &fine).unwrap();
                for (x, y) in a.iter().zip(&b) {
                    worst = worst.max(((x - y) / y).abs());
                }
            }
        }
    }
    println!(
        "largest relative change from {n} to {} nodes: {worst:.2e}",
        2 * n
    );
    assert!(worst < 1e-12, "{worst}");
}

#[test]
fn energies_match_adaptive_quadrature_in_h() {
    let rule = EnergyRule::default();
    for path in PATHS {
        for sigma_a in [0.0, 1.0] {
            let ours = lobe_energies(ETA, sigma_a, path, Directions::Theta0, &rule).unwrap();
            let reference = energies_in_h(sigma_a, path);
            for (x, y) in ours.iter().zip(&reference) {
                assert!(
                    ((x - y) / y).abs() < 1e-10,
                    "{path:?} {sigma_a}: {x} vs {y}"
                );
            }
        }
    }
    // Without absorption the path form does not matter.
    let m = lobe_energies(
        ETA,
        0.0,
        PathLength::Marschner2003,
        Directions::Averaged,
        &rule,
    );
    let c = lobe_energies(ETA, 0.0, PathLength::Chord, Directions::Averaged, &rule);
    assert_eq!(m.unwrap(), c.unwrap());
}

/// d ln E_TT / d sigma_a at 0 (Marschner form, theta = 0) is minus the (1 - f)^2-weighted mean
/// of 4 cos^2 gamma_t = 4 (1 - h^2 / eta^2), which lies between 4 (1 - 1/eta^2) and 4.
#[test]
fn small_absorption_slope_of_tt_is_the_weighted_mean_exponent() {
    let rule = EnergyRule::default();
    let path = PathLength::Marschner2003;
    let (e0, _) = adaptive(
        |h| {
            let a = attenuation_theta0(h, 0.0, path)[0];
            [a, a * 4.0 * (1.0 - h * h / (ETA * ETA))]
        },
        -1.0,
        1.0,
        &[0.0],
        1e-13,
        0.0,
    );
    let slope = e0[1] / e0[0];
    let d = 1e-5;
    let energy = |s| lobe_energies(ETA, s, path, Directions::Theta0, &rule).unwrap()[0];
    let numeric = -(energy(d).ln() - energy(-0.0).ln()) / d;
    println!("TT Marschner theta = 0: initial slope {slope:.6}, finite difference {numeric:.6}");
    assert!(
        (numeric - slope).abs() < 1e-4 * slope,
        "{numeric} vs {slope}"
    );
    assert!(slope > 4.0 * (1.0 - 1.0 / (ETA * ETA)) && slope < 4.0);
}

#[test]
fn gerard_exponents_are_marschners_at_h_0_and_h_sqrt3_over_2() {
    for sigma_a in [0.3, 1.0, 2.0] {
        let exponent = |h: f64, p: i32| {
            let sin_gamma_t = refracted_offset(h, ETA, 0.0, 1.0);
            let cos_gamma_t = (1.0 - sin_gamma_t * sin_gamma_t).sqrt();
            let t = segment_transmittance(sigma_a, cos_gamma_t, 1.0, PathLength::Marschner2003);
            -t.powi(p).ln() / sigma_a
        };
        // One segment through the centre: 4 per unit sigma_a (Gerard eqs. 8 and 12).
        assert!((exponent(0.0, 1) - 4.0).abs() < 1e-13);
        // Two segments at h = sqrt(3)/2: 8 (1 - 3/(4 eta^2)) = 5.50 (eq. 13's 11/2).
        let trt = exponent(0.75_f64.sqrt(), 2);
        assert!((trt - gerard_eq8_trt_corrected(ETA)).abs() < 1e-13, "{trt}");
    }
    let (printed, corrected) = (gerard_eq8_trt_printed(ETA), gerard_eq8_trt_corrected(ETA));
    println!("eq. 8 TRT exponent: printed {printed:.4}, corrected {corrected:.4}, eq. 13: 5.5");
    assert!((printed - 3.0052).abs() < 1e-4 && (corrected - 5.5026).abs() < 1e-4);
}

#[test]
fn the_fit_recovers_a_known_exponent() {
    for k0 in [0.5, 3.7, 5.5] {
        let samples = RatioSamples::from_fn(|s| (-k0 * s).exp());
        let m = fit_exponent("synthetic", &samples).unwrap();
        println!(
            "synthetic k0 = {k0}: recovered with error {:.1e}",
            m.params[0] - k0
        );
        assert!((m.params[0] - k0).abs() < 1e-8, "{k0}: {m:?}");
        assert_eq!(m.termination, "Solver converged");
        assert!(ratio_loss(k0, &samples) < 1e-30);
    }
}

#[test]
fn invalid_settings_are_errors() {
    let rule = EnergyRule::default();
    assert!(absorption_fits(&FitSettings { eta: 0.9 }).is_err());
    assert!(lobe_energies(ETA, -1.0, PathLength::Chord, Directions::Theta0, &rule).is_err());
    assert!(lobe_energies(f64::NAN, 1.0, PathLength::Chord, Directions::Theta0, &rule).is_err());
    assert!(EnergyRule::new(0, 4).is_err());
}

#[test]
fn eight_fits_converge_to_minima_and_beat_gerard() {
    let start = std::time::Instant::now();
    let report = absorption_report(&FitSettings::default()).unwrap();
    println!("absorption_report: {:.3} s", start.elapsed().as_secs_f64());
    assert_eq!(report.fits.len(), 8);
    for fit in &report.fits {
        assert_eq!(fit.minimum.termination, "Solver converged", "{}", fit.key());
        let loss = |p: &[f64]| ratio_loss(p[0], &fit.reference.samples);
        assert!(
            is_coordinate_minimum(loss, &[fit.k()], 1e-5),
            "{}",
            fit.key()
        );
        let refit = &fit.errors[0];
        assert!(
            fit.errors[1..].iter().all(|e| e.rms >= refit.rms),
            "{}",
            fit.key()
        );
        println!(
            "{:<22} k = {:.6} ({} Brent iterations)",
            fit.key(),
            fit.k(),
            fit.minimum.iterations
        );
        for e in &fit.errors {
            let rel: Vec<String> = e.relative.iter().map(|r| format!("{r:+.3e}")).collect();
            println!(
                "    {:<40} k = {:.4}: RMS {:.3e}, max {:.3e}; relative at sigma_a {:?}: [{}]",
                e.label,
                e.k,
                e.rms,
                e.max_abs,
                TABLE_SIGMA_A,
                rel.join(", ")
            );
        }
    }
}

#[test]
fn records_and_constants_are_complete_and_deterministic() {
    let settings = FitSettings::default();
    let first = absorption_fits(&settings).unwrap();
    let second = absorption_fits(&settings).unwrap();
    let render = |fits| constants_source(&settings, fits);
    assert_eq!(render(&first), render(&second));
    println!("{}", render(&first));
    let keys: Vec<&str> = first.records.iter().map(|r| r.key.as_str()).collect();
    for lobe in Lobe::ALL {
        for path in ["marschner", "chord"] {
            for dir in ["theta0", "averaged"] {
                let key = format!("gerard.absorption_k.{}.{path}.{dir}", lobe.key());
                assert!(keys.contains(&key.as_str()), "{key} missing from {keys:?}");
            }
        }
    }
    let eq8 = first
        .records
        .iter()
        .find(|r| r.key == "gerard.absorption_k.trt.eq8_printed")
        .unwrap();
    let trt0 = first
        .records
        .iter()
        .find(|r| r.key == "gerard.absorption_k.trt.marschner.theta0")
        .unwrap();
    assert_eq!(eq8.refit, trt0.refit);
    assert_eq!(eq8.published, Some(gerard_eq8_trt_printed(ETA)));
    for r in &first.records {
        println!(
            "{:<40} published {:?} (RMS {:.3e}), refit {:.6} (RMS {:.3e})",
            r.key,
            r.published,
            r.published_error.unwrap_or(f64::NAN),
            r.refit,
            r.refit_error
        );
    }
    let names: Vec<&str> = first.constants.iter().map(|c| c.name.as_str()).collect();
    assert_eq!(names, ["GERARD_ABSORPTION_K_TT", "GERARD_ABSORPTION_K_TRT"]);
}
