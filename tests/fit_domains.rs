//! The public evaluators of the fits over their whole domains (proptest) and on the hard cases
//! of docs/ARCHITECTURE.md: grazing inclinations, h = +-1, sigma_a = 0 and very dark hair, eta close to 1,
//! very low azimuthal roughness. Each returns a finite value in its range, or a typed error
//! outside its domain; none panics or returns NaN.

#![cfg(feature = "fit")]

use hairmath::absorption::PathLength;
use hairmath::azimuthal::exit_angle_of_offset;
use hairmath::fit::{
    d_trt_reference, d_tt_reference, eta_prime_relative_error, h_tt_exact, h_tt_min_phi,
    CLAIMED_ETA_PRIME_ERROR, PUBLISHED_ETA_PRIME,
};
use hairmath::fit::{hg_l2_residual, HgReading};
use hairmath::fit::{lobe_energies, Directions, EnergyRule};
use hairmath::fit::{mean_attenuation, TtSlice};
use hairmath::fit::{FitError, FitSettings};
use hairmath::models::{h_tt_karis, offset_attenuation, Transmitted};
use hairmath::real::wrap_angle;
use proptest::prelude::*;
use std::f64::consts::{FRAC_PI_2, PI};

/// Refractive indices from just above 1 to the fits' limit 3.
fn eta() -> impl Strategy<Value = f64> {
    prop_oneof![Just(1.0001), Just(1.55), Just(3.0), 1.0001_f64..=3.0]
}

/// Inclinations including both grazing limits.
fn theta() -> impl Strategy<Value = f64> {
    prop_oneof![
        Just(FRAC_PI_2),
        Just(-FRAC_PI_2),
        Just(0.0),
        -FRAC_PI_2..=FRAC_PI_2
    ]
}

/// Absorption from none to very dark hair.
fn sigma_a() -> impl Strategy<Value = f64> {
    prop_oneof![Just(0.0), Just(10.0), Just(100.0), 0.0_f64..=20.0]
}

fn path() -> impl Strategy<Value = Transmitted> {
    prop_oneof![Just(Transmitted::Tt), Just(Transmitted::Trt)]
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(200))]

    #[test]
    fn single_offset_attenuation_is_a_fraction(
        p in path(),
        h in prop_oneof![Just(1.0), Just(-1.0), Just(0.0), -1.0_f64..=1.0],
        s in sigma_a(),
        t in theta(),
        e in eta(),
    ) {
        let a = offset_attenuation(p, h, s, t.sin(), t.cos(), e);
        prop_assert!(a.is_finite() && (0.0..=1.0).contains(&a), "{a}");
        let mean = mean_attenuation(p, s, t, e);
        prop_assert!(mean.is_finite() && (0.0..=1.0).contains(&mean), "{mean}");
    }

    #[test]
    fn tt_distribution_is_a_finite_density(
        t in theta(),
        beta_n in prop_oneof![Just(1e-3), Just(1.0), 1e-3_f64..=1.0],
        e in eta(),
        phi in -10.0_f64..=10.0,
    ) {
        let slice = TtSlice::new(t, beta_n, e).unwrap();
        let d = slice.distribution(phi);
        prop_assert!(d.is_finite() && d >= 0.0, "{d}");
        // Periodic in phi.
        let wrapped = slice.distribution(wrap_angle(phi));
        prop_assert!((d - wrapped).abs() <= 1e-9 * (1.0 + d), "{d} vs {wrapped}");
    }

    #[test]
    fn lobe_energies_are_fractions_that_fall_with_absorption(
        e in eta(),
        s in sigma_a(),
        marschner in any::<bool>(),
        averaged in any::<bool>(),
    ) {
        let path = if marschner { PathLength::Marschner2003 } else { PathLength::Chord };
        let dirs = if averaged { Directions::Averaged } else { Directions::Theta0 };
        let rule = EnergyRule::new(16, 16).unwrap();
        let at = lobe_energies(e, s, path, dirs, &rule).unwrap();
        let darker = lobe_energies(e, s + 0.5, path, dirs, &rule).unwrap();
        for (x, y) in at.iter().zip(darker) {
            prop_assert!(x.is_finite() && (0.0..=1.0).contains(x), "{at:?}");
            prop_assert!(y <= *x, "{y} > {x}");
        }
    }

    #[test]
    fn karis_references_are_bounded_by_their_peaks(phi in -10.0_f64..=10.0) {
        let tt = d_tt_reference(phi);
        let trt = d_trt_reference(phi);
        prop_assert!((0.0..=1.0 / (4.0 * 0.35) + 1e-12).contains(&tt), "{tt}");
        prop_assert!((0.0..=0.75 / (4.0 * 0.15) + 1e-12).contains(&trt), "{trt}");
    }

    #[test]
    fn exact_tt_offset_solves_the_exit_angle_equation(
        eta_prime in prop_oneof![Just(1.0001), Just(1.55), 1.0001_f64..=20.0],
        u in 0.0_f64..=1.0,
        negative in any::<bool>(),
    ) {
        let lo = h_tt_min_phi(eta_prime).unwrap();
        let phi = (lo + u * (PI - lo)) * if negative { -1.0 } else { 1.0 };
        let h = h_tt_exact(eta_prime, phi).unwrap();
        prop_assert!(h.is_finite() && h.abs() <= 1.0 + 1e-12, "{h}");
        // theta = 0, where eta' = eta.
        let exit = exit_angle_of_offset(1.0, h.clamp(-1.0, 1.0), eta_prime, 0.0);
        prop_assert!(wrap_angle(exit - phi).abs() < 1e-7, "exit {exit} phi {phi} h {h}");
        prop_assert!(h_tt_karis(1.0 / eta_prime, phi, [0.6, 0.8].into()).is_finite());
    }

    #[test]
    fn published_eta_prime_is_within_its_claim_everywhere(
        theta_d in 0.0_f64..FRAC_PI_2,
    ) {
        let [a, b] = PUBLISHED_ETA_PRIME;
        let err = eta_prime_relative_error(&FitSettings::default(), a, b, theta_d).unwrap();
        prop_assert!(err.abs() < CLAIMED_ETA_PRIME_ERROR, "{err} at {theta_d}");
    }

    #[test]
    fn hg_residual_is_finite_over_the_domain(
        g in -0.99_f64..0.99,
        deg in 0.1_f64..=60.0,
        literal in any::<bool>(),
    ) {
        let reading = if literal {
            HgReading::Literal
        } else {
            HgReading::Normalised { width_scale: 1.0 }
        };
        let r = hg_l2_residual(reading, g, deg.to_radians());
        prop_assert!(r.is_finite() && r > 0.0, "{r}");
    }
}

#[test]
fn outside_their_domains_the_evaluators_give_typed_errors() {
    for (theta_o, beta_n, eta) in [(0.0, 0.0, 1.55), (2.0, 0.5, 1.55), (0.0, 0.5, 1.0)] {
        let err = TtSlice::new(theta_o, beta_n, eta).unwrap_err();
        assert!(err.to_string().contains("not allowed"), "{err}");
    }
    let rule = EnergyRule::default();
    for (e, s) in [
        (1.0, 0.5),
        (1.55, -0.1),
        (1.55, f64::NAN),
        (f64::INFINITY, 0.0),
    ] {
        let result = lobe_energies(e, s, PathLength::Chord, Directions::Theta0, &rule);
        assert!(matches!(result, Err(FitError::Param(_))), "{e} {s}");
    }
    assert!(matches!(h_tt_exact(1.0, PI), Err(FitError::Param(_))));
    // Below the smallest TT exit angle there is no root.
    let lo = h_tt_min_phi(1.55).unwrap();
    assert!(matches!(
        h_tt_exact(1.55, 0.5 * lo),
        Err(FitError::Param(_))
    ));
    let settings = FitSettings::default();
    assert!(eta_prime_relative_error(&settings, 1.19, 0.36, FRAC_PI_2).is_err());
    assert!(eta_prime_relative_error(&settings, f64::NAN, 0.36, 0.1).is_err());
}

/// Near the smallest phi of a barely refracting fibre, h is within 1e-11 of 1, where asin(h)
/// magnifies the closed form's rounding: the exit angle must still match to 1e-7 (a CI run found
/// 1.6e-7 at eta' = 1.0001, u = 2.9e-4 before the denominator was written as a hypotenuse).
/// u runs over 10^0 .. 10^-16 in steps of 10^0.04, and 0.
#[test]
fn exact_tt_offset_near_the_smallest_angle_of_a_weak_fibre() {
    for eta_prime in [1.0001, 1.0003, 1.001, 1.01, 1.55] {
        let lo = h_tt_min_phi(eta_prime).unwrap();
        for k in 0..=400 {
            let u = if k == 400 {
                0.0
            } else {
                10f64.powf(-0.04 * k as f64)
            };
            let phi = lo + u * (PI - lo);
            let h = h_tt_exact(eta_prime, phi).unwrap();
            assert!(h.is_finite() && h <= 1.0 + 1e-12, "{h}");
            let exit = exit_angle_of_offset(1.0, h.min(1.0), eta_prime, 0.0);
            let error = wrap_angle(exit - phi).abs();
            assert!(
                error < 1e-7,
                "eta' {eta_prime} u {u}: exit {exit} phi {phi} h {h}"
            );
        }
    }
}
