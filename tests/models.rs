//! The closed forms of `hairmath::models` over their whole domains (proptest; hard cases:
//! grazing cos theta_d = 0, phi = 0 and +-pi, sigma_a = 0 and very dark hair, eta near 1,
//! h = +-1), their documented values, and (with the `fit` feature) that the fits evaluate
//! exactly these functions rather than copies of them.
//!
//! Everything but the last section needs only the always-compiled models.

use hairmath::models::{
    d_karis, gerard_attenuation, gerard_eq8_trt_corrected, gerard_eq8_trt_printed, gerard_hg_g,
    h_tt_karis, hg_g_normalised, inverse_eta_prime_karis, offset_attenuation,
    scaled_eta_prime_karis, tt_gaussian, EtaPrimeCoefficients, ExpCosCoefficients, HTtCoefficients,
    Transmitted, GERARD_K_TRT, GERARD_K_TT, HG_G_BETA_DOMAIN,
};
use hairmath::models::{
    FROSTBITE_TRT_OFFSET_H, FROSTBITE_TT_OFFSET_H, KARIS_D_TRT, KARIS_D_TT, KARIS_ETA_PRIME,
    KARIS_H_TT,
};
use proptest::prelude::*;
use std::f64::consts::{FRAC_PI_2, PI};

/// Refractive indices from just above 1 to 3.
fn eta() -> impl Strategy<Value = f64> {
    prop_oneof![Just(1.0001), Just(1.55), Just(3.0), 1.0001_f64..=3.0]
}

/// cos theta_d in [0, 1], grazing (0) and normal (1) included.
fn cos_theta_d() -> impl Strategy<Value = f64> {
    prop_oneof![Just(0.0), Just(1.0), 0.0_f64..=1.0]
}

/// Relative azimuths in [-pi, pi], 0 and +-pi included.
fn phi() -> impl Strategy<Value = f64> {
    prop_oneof![Just(0.0), Just(PI), Just(-PI), -PI..=PI]
}

/// Absorption from none to very dark hair.
fn sigma_a() -> impl Strategy<Value = f64> {
    prop_oneof![Just(0.0), Just(10.0), Just(100.0), 0.0_f64..=20.0]
}

fn eta_prime_sets() -> [EtaPrimeCoefficients; 2] {
    [EtaPrimeCoefficients::PUBLISHED, EtaPrimeCoefficients::REFIT]
}

fn exp_cos_sets() -> [ExpCosCoefficients; 4] {
    [
        ExpCosCoefficients::PUBLISHED_D_TT,
        ExpCosCoefficients::PUBLISHED_D_TRT,
        ExpCosCoefficients::REFIT_D_TT,
        ExpCosCoefficients::REFIT_D_TRT,
    ]
}

fn h_tt_sets() -> [HTtCoefficients; 2] {
    [HTtCoefficients::PUBLISHED, HTtCoefficients::REFIT]
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(256))]

    #[test]
    fn hg_g_is_an_asymmetry_for_every_width(
        beta in prop_oneof![
            Just(0.0), Just(-1.0), Just(1e-9), Just(HG_G_BETA_DOMAIN.0), Just(HG_G_BETA_DOMAIN.1),
            Just(100.0), Just(f64::INFINITY), -1.0_f64..=3.0
        ],
    ) {
        for g in [gerard_hg_g(beta), hg_g_normalised(beta)] {
            prop_assert!(g.is_finite() && g > 0.0 && g < 1.0, "{beta}: {g}");
        }
        for g in [gerard_hg_g(beta as f32), hg_g_normalised(beta as f32)] {
            prop_assert!(g.is_finite() && g > 0.0 && g < 1.0, "{beta}: {g}");
        }
        // Clamped to the domain.
        let clamped = beta.clamp(HG_G_BETA_DOMAIN.0, HG_G_BETA_DOMAIN.1);
        prop_assert_eq!(gerard_hg_g(beta), gerard_hg_g(clamped));
        prop_assert_eq!(hg_g_normalised(beta), hg_g_normalised(clamped));
    }

    #[test]
    fn gerard_attenuation_is_a_fraction_that_falls_with_absorption(
        k in prop_oneof![Just(0.0), Just(GERARD_K_TT), Just(GERARD_K_TRT), 0.0_f64..=16.0],
        s in sigma_a(),
    ) {
        let t = gerard_attenuation(k, s);
        prop_assert!(t.is_finite() && (0.0..=1.0).contains(&t), "{t}");
        prop_assert!(gerard_attenuation(k, s + 0.5) <= t);
        prop_assert_eq!(gerard_attenuation(k, 0.0), 1.0);
        let single = gerard_attenuation(k as f32, s as f32);
        prop_assert!(single.is_finite() && (0.0..=1.0).contains(&single), "{single}");
    }

    #[test]
    fn eq8_exponents_are_finite_and_ordered(e in eta()) {
        let (printed, corrected) = (gerard_eq8_trt_printed(e), gerard_eq8_trt_corrected(e));
        prop_assert!(printed.is_finite() && corrected.is_finite());
        // 8 (1 - 3/(4 eta^2)) lies in (2, 8) for eta > 1 and exceeds the printed form.
        prop_assert!(corrected > 2.0 && corrected < 8.0 && printed < corrected, "{printed} {corrected}");
        prop_assert!(gerard_eq8_trt_printed(e as f32).is_finite());
        prop_assert!(gerard_eq8_trt_corrected(e as f32).is_finite());
    }

    #[test]
    fn karis_eta_prime_is_finite_up_to_grazing(x in cos_theta_d()) {
        for c in eta_prime_sets() {
            let scaled = scaled_eta_prime_karis(x, c);
            let inverse = inverse_eta_prime_karis(x, c);
            prop_assert!(scaled.is_finite() && scaled >= c.a, "{scaled}");
            prop_assert!(inverse.is_finite() && (0.0..1.0).contains(&inverse), "{inverse}");
            prop_assert!((scaled * inverse - x).abs() <= 1e-15, "{scaled} {inverse} {x}");
            let single = inverse_eta_prime_karis(x as f32, c.to_real());
            prop_assert!(single.is_finite() && (0.0..1.0).contains(&single), "{single}");
            prop_assert!(scaled_eta_prime_karis(x as f32, c.to_real()).is_finite());
        }
    }

    #[test]
    fn karis_eta_prime_is_within_its_claim_at_eta_1_55(x in cos_theta_d()) {
        // Bravais' exact index times cos theta_d: sqrt(eta^2 - 1 + cos^2 theta_d).
        let exact = (1.55_f64 * 1.55 - 1.0 + x * x).sqrt();
        for c in eta_prime_sets() {
            let error = (scaled_eta_prime_karis(x, c) / exact - 1.0).abs();
            // Karis' claim "error < 0.68%" (both sets are measured below it).
            prop_assert!(error < 0.0068, "{c:?} at cos theta_d = {x}: {error}");
        }
    }

    #[test]
    fn karis_d_is_positive_even_and_periodic(p in prop_oneof![phi(), -10.0_f64..=10.0]) {
        for c in exp_cos_sets() {
            let d = d_karis(p, c);
            prop_assert!(d.is_finite() && d > 0.0, "{c:?} {p}: {d}");
            prop_assert_eq!(d_karis(-p, c), d);
            prop_assert!((d_karis(p + 2.0 * PI, c) - d).abs() <= 1e-12 * d, "{c:?} {p}");
            // Bounded by the value at the peak: phi = pi for TT (a < 0), 0 for TRT (a > 0).
            let peak = (c.a.abs() + c.b).exp();
            prop_assert!(d <= peak * (1.0 + 1e-15), "{d} > {peak}");
            prop_assert!(d_karis(p as f32, c.to_real()).is_finite());
        }
    }

    #[test]
    fn karis_h_tt_is_finite_even_and_bounded(
        a in prop_oneof![Just(0.0), Just(1.0 / 1.55), Just(0.9999), 0.0_f64..1.0],
        p in phi(),
    ) {
        for c in h_tt_sets() {
            let h = h_tt_karis(a, p, c);
            prop_assert!(h.is_finite(), "{h}");
            prop_assert_eq!(h_tt_karis(a, -p, c), h);
            prop_assert!(h.abs() <= 1.0 + a * (c.c1.abs() + c.c2.abs()), "{h}");
            // a = 0 (grazing, 1/eta' = 0): the offset is cos(phi/2).
            prop_assert_eq!(h_tt_karis(0.0, p, c), (0.5 * p).cos());
            prop_assert!(h_tt_karis(a as f32, p as f32, c.to_real()).is_finite());
        }
    }

    #[test]
    fn karis_h_tt_of_the_index_is_finite_up_to_grazing(x in cos_theta_d(), p in phi()) {
        for (e, c) in eta_prime_sets().into_iter().zip(h_tt_sets()) {
            let h = h_tt_karis(inverse_eta_prime_karis(x, e), p, c);
            prop_assert!(h.is_finite(), "{h}");
            let single = h_tt_karis(inverse_eta_prime_karis(x as f32, e.to_real()), p as f32, c.to_real());
            prop_assert!(single.is_finite(), "{single}");
        }
    }

    #[test]
    fn tt_gaussian_is_bounded_by_its_height(
        p in phi(),
        a in prop_oneof![Just(0.0), Just(1.0), 0.0_f64..=1.0],
        b in prop_oneof![Just(0.0), Just(1.47), 0.0_f64..=2.0],
    ) {
        let g = tt_gaussian(p, a, b);
        prop_assert!(g.is_finite() && (0.0..=a).contains(&g), "{g}");
        prop_assert_eq!(tt_gaussian(-p, a, b), g);
        prop_assert_eq!(tt_gaussian(PI, a, b), a);
        let single = tt_gaussian(p as f32, a as f32, b as f32);
        prop_assert!(single.is_finite() && single >= 0.0, "{single}");
    }

    #[test]
    fn offset_attenuation_is_a_fraction(
        tt in any::<bool>(),
        h in prop_oneof![Just(1.0), Just(-1.0), Just(0.0), -1.0_f64..=1.0],
        s in sigma_a(),
        theta in prop_oneof![Just(FRAC_PI_2), Just(-FRAC_PI_2), Just(0.0), -FRAC_PI_2..=FRAC_PI_2],
        e in eta(),
    ) {
        let path = if tt { Transmitted::Tt } else { Transmitted::Trt };
        let (sin, cos) = theta.sin_cos();
        let a = offset_attenuation(path, h, s, sin, cos, e);
        prop_assert!(a.is_finite() && (0.0..=1.0).contains(&a), "{a}");
        // Even in h, and darker hair attenuates more.
        prop_assert_eq!(offset_attenuation(path, -h, s, sin, cos, e), a);
        prop_assert!(offset_attenuation(path, h, s + 0.5, sin, cos, e) <= a);
        let single = offset_attenuation(path, h as f32, s as f32, sin as f32, cos as f32, e as f32);
        prop_assert!(single.is_finite() && (0.0..=1.0).contains(&single), "{single}");
    }
}

#[test]
fn gerard_values_are_the_documented_ones() {
    assert_eq!((GERARD_K_TT, GERARD_K_TRT), (4.0, 5.5));
    let (printed, corrected) = (
        gerard_eq8_trt_printed(1.55_f64),
        gerard_eq8_trt_corrected(1.55_f64),
    );
    assert!((printed - 3.0052).abs() < 1e-4, "{printed}");
    assert!((corrected - 5.5026).abs() < 1e-4, "{corrected}");
    // The corrected eq. 8 agrees with eq. 13's 11/2 to 5e-4 relative.
    assert!((corrected / GERARD_K_TRT - 1.0).abs() < 5e-4);
    assert_eq!(gerard_attenuation(GERARD_K_TT, 0.25), (-1.0_f64).exp());
    let degree = PI / 180.0;
    assert!((HG_G_BETA_DOMAIN.0 - degree).abs() < 1e-17);
    assert!((HG_G_BETA_DOMAIN.1 - 45.0 * degree).abs() < 1e-15);
}

#[test]
fn karis_values_are_the_documented_ones() {
    let published = EtaPrimeCoefficients::PUBLISHED;
    assert_eq!((published.a, published.b), (1.19, 0.36));
    let (tt, trt) = (
        ExpCosCoefficients::PUBLISHED_D_TT,
        ExpCosCoefficients::PUBLISHED_D_TRT,
    );
    assert_eq!([tt.a, tt.b, trt.a, trt.b], [-3.65, -3.98, 17.0, -16.78]);
    let h = HTtCoefficients::PUBLISHED;
    assert_eq!((h.c1, h.c2), (0.6, 0.8));
    // The refits are the generated constants, in the published order.
    assert_eq!(EtaPrimeCoefficients::REFIT, KARIS_ETA_PRIME.into());
    assert_eq!(ExpCosCoefficients::REFIT_D_TT, KARIS_D_TT.into());
    assert_eq!(ExpCosCoefficients::REFIT_D_TRT, KARIS_D_TRT.into());
    assert_eq!(HTtCoefficients::REFIT, KARIS_H_TT.into());
    // Grazing: cos theta_d * eta' tends to a, 1/eta' is 0; the relative error there is
    // a / sqrt(eta^2 - 1) - 1 = 4.8e-3 for the published constants at eta = 1.55.
    assert_eq!(scaled_eta_prime_karis(0.0, published), 1.19);
    assert_eq!(inverse_eta_prime_karis(0.0, published), 0.0);
    assert_eq!(inverse_eta_prime_karis(0.0_f32, published.to_real()), 0.0);
    let grazing = 1.19 / (1.55_f64 * 1.55 - 1.0).sqrt() - 1.0;
    assert!((grazing - 4.8e-3).abs() < 5e-5, "{grazing}");
    // Normal incidence: eta' = a + b.
    assert!((scaled_eta_prime_karis(1.0_f64, published) - 1.55).abs() < 1e-15);
    // The published D_TT peaks at phi = pi with exp(3.65 - 3.98).
    assert_eq!(d_karis(PI, tt), (3.65_f64 - 3.98).exp());
    assert_eq!(d_karis(0.0, trt), (17.0_f64 - 16.78).exp());
}

#[test]
fn frostbite_values_are_the_documented_ones() {
    assert_eq!(Transmitted::Tt.published_offset(), 0.0);
    assert_eq!(Transmitted::Trt.published_offset(), 0.75_f64.sqrt());
    assert_eq!(Transmitted::Tt.refit_offset(), FROSTBITE_TT_OFFSET_H);
    assert_eq!(Transmitted::Trt.refit_offset(), FROSTBITE_TRT_OFFSET_H);
    assert_eq!((Transmitted::Tt.p(), Transmitted::Trt.p()), (1, 2));
    assert_eq!(
        (Transmitted::Tt.name(), Transmitted::Trt.name()),
        ("TT", "TRT")
    );
    // Without absorption, at normal incidence and h = 0, TT is (1 - f)^2 with the normal
    // Fresnel reflectance f = ((eta - 1) / (eta + 1))^2.
    let f = ((1.55_f64 - 1.0) / 2.55).powi(2);
    let a = offset_attenuation(Transmitted::Tt, 0.0, 0.0, 0.0, 1.0, 1.55);
    assert!((a - (1.0 - f).powi(2)).abs() < 1e-14, "{a}");
}

/// The fits evaluate the models' closed forms, not copies: wherever a fit exposes a value
/// built from a closed form, it equals the models' f64 evaluation exactly.
#[cfg(feature = "fit")]
mod shared_with_the_fits {
    use super::*;
    use hairmath::fit::FitSettings;
    use hairmath::fit::{
        eta_prime_relative_error, exp_cos_rms_error, fit_h_tt_to, PUBLISHED_D_TRT, PUBLISHED_D_TT,
        PUBLISHED_ETA_PRIME, PUBLISHED_H_TT,
    };
    use hairmath::fit::{
        gaussian_loss, AttenuationProblem, ATTENUATION_SIGMA_A, PUBLISHED_TRT_OFFSET_H,
        PUBLISHED_TT_OFFSET_H,
    };
    use hairmath::fit::{ratio_loss, ApproximationError, Lobe, RatioReference, RatioSamples};
    use hairmath::fresnel::bravais_eta_perpendicular;

    #[test]
    fn published_constants_are_defined_once() {
        let e = EtaPrimeCoefficients::PUBLISHED;
        assert_eq!(PUBLISHED_ETA_PRIME, [e.a, e.b]);
        let (tt, trt) = (
            ExpCosCoefficients::PUBLISHED_D_TT,
            ExpCosCoefficients::PUBLISHED_D_TRT,
        );
        assert_eq!(
            (PUBLISHED_D_TT, PUBLISHED_D_TRT),
            ([tt.a, tt.b], [trt.a, trt.b])
        );
        let h = HTtCoefficients::PUBLISHED;
        assert_eq!(PUBLISHED_H_TT, [h.c1, h.c2]);
        assert_eq!(PUBLISHED_TT_OFFSET_H, Transmitted::Tt.published_offset());
        assert_eq!(PUBLISHED_TRT_OFFSET_H, Transmitted::Trt.published_offset());
        assert_eq!(
            (Lobe::Tt.gerard_k(), Lobe::Trt.gerard_k()),
            (GERARD_K_TT, GERARD_K_TRT)
        );
    }

    #[test]
    fn absorption_fits_use_gerard_attenuation() {
        let samples = RatioSamples::from_fn(|s| 0.5 / (1.0 + s));
        for k in [0.0, GERARD_K_TT, GERARD_K_TRT, 7.3] {
            let by_hand: f64 = samples
                .sigma_a
                .iter()
                .zip(&samples.weight)
                .zip(&samples.ratio)
                .map(|((&s, w), r)| w * (gerard_attenuation(k, s) - r).powi(2))
                .sum();
            assert_eq!(ratio_loss(k, &samples), by_hand, "k = {k}");
            // A reference that is the closed form itself has no error.
            let exact = RatioReference {
                samples: RatioSamples::from_fn(|s| gerard_attenuation(k, s)),
                grid: (0..=20)
                    .map(|i| {
                        let s = 0.1 * i as f64;
                        (s, gerard_attenuation(k, s))
                    })
                    .collect(),
                table: [0.25, 0.5, 1.0, 2.0].map(|s| gerard_attenuation(k, s)),
            };
            let error = ApproximationError::measure("models", k, &exact);
            assert_eq!((error.rms, error.max_abs), (0.0, 0.0), "k = {k}");
            assert_eq!(error.relative, [0.0; 4], "k = {k}");
        }
    }

    #[test]
    fn karis_fits_use_the_closed_forms() {
        let settings = FitSettings::default();
        for c in eta_prime_sets() {
            for theta_d in [0.0, 0.3, 1.0, 1.5, 1.57] {
                let x = f64::cos(theta_d);
                let exact = bravais_eta_perpendicular(settings.eta, theta_d.sin());
                let by_hand = (scaled_eta_prime_karis(x, c) / x / exact - 1.0).abs();
                let fit = eta_prime_relative_error(&settings, c.a, c.b, theta_d).unwrap();
                assert_eq!(fit, by_hand, "{c:?} at {theta_d}");
            }
        }
        for c in exp_cos_sets() {
            assert_eq!(
                exp_cos_rms_error(|p| d_karis(p, c), 1.0, c.a, c.b),
                0.0,
                "{c:?}"
            );
        }
        for c in h_tt_sets() {
            let refit = fit_h_tt_to(&settings, |a, p| h_tt_karis(a, p, c)).unwrap();
            assert!((refit[0] - c.c1).abs() < 1e-12 && (refit[1] - c.c2).abs() < 1e-12);
        }
    }

    #[test]
    fn frostbite_fits_use_the_closed_forms() {
        let phi: Vec<f64> = (0..=36).map(|k| PI * k as f64 / 36.0).collect();
        for (a, b) in [(0.678, 1.47), (0.16, 0.0055)] {
            let values: Vec<f64> = phi.iter().map(|&p| tt_gaussian(p, a, b)).collect();
            assert_eq!(gaussian_loss(&phi, &values, a, &[a, b]), 0.0);
        }
        let theta: Vec<f64> = [0.0, 30.0, 85.0].map(f64::to_radians).to_vec();
        for (path, h) in [(Transmitted::Tt, 0.3), (Transmitted::Trt, 0.8)] {
            let targets = |s: f64, t: f64| offset_attenuation(path, h, s, t.sin(), t.cos(), 1.55);
            let problem =
                AttenuationProblem::with_targets(path, 1.55, &ATTENUATION_SIGMA_A, &theta, targets)
                    .unwrap();
            let table = problem.error_table(h);
            assert!(
                table.relative_error.iter().flatten().all(|&e| e == 0.0),
                "{table:?}"
            );
        }
    }
}
