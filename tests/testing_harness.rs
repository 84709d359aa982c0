//! The harnesses of `hairmath::testing` pass hairmath's own reference and catch deliberately
//! broken variants, each with a report a renderer author understands: a model that gains or
//! loses energy (the furnace), a sampler whose weight disagrees with its pdf (sample weights),
//! a pdf off by a constant (chi-square), and negative or NaN values (the values search, at a
//! hard case or found and shrunk by proptest).

use hairmath::absorption::Absorption;
use hairmath::bcsdf::{Bcsdf, ChiangHair, HairSample, Query, SampledBcsdf};
use hairmath::diagnostics::SphereSize;
use hairmath::params::{AzimuthalRoughness, HairParams, LongitudinalRoughness};
use hairmath::testing::{
    chi_square, eval_values, from_eval, from_sampler, furnace, hard_params, sample_weights,
    sampler_values, ChiSquareSettings, FurnaceSettings, ValueSettings, View, WeightSettings,
};

fn white(beta_m: f64, beta_n: f64) -> ChiangHair<f64> {
    ChiangHair::new(&HairParams {
        beta_m: LongitudinalRoughness::new(beta_m).unwrap(),
        beta_n: AzimuthalRoughness::new(beta_n).unwrap(),
        sigma_a: Absorption::NONE,
        ..HairParams::default()
    })
}

fn brown() -> ChiangHair<f64> {
    ChiangHair::new(&HairParams::default())
}

/// The furnace's stated accuracy (`hairmath::testing::furnace`): at the default settings the
/// reference's albedo is 1 within 1e-6 for beta_m, beta_n in [0.1, 1] at every view.
#[test]
fn the_reference_passes_the_furnace_within_its_stated_accuracy() {
    let settings = FurnaceSettings::default();
    for (beta_m, beta_n) in [(0.1, 0.1), (0.1, 1.0), (0.3, 0.3), (1.0, 0.1), (1.0, 1.0)] {
        let report = furnace(&white(beta_m, beta_n), &settings);
        println!("beta_m {beta_m}, beta_n {beta_n}: {report}");
        assert_eq!(report.furnace.cases.len(), 4 * 5);
        assert!(report.passes(1e-6), "{report}");
    }
}

/// Energy gained by 5% everywhere, or lost by dropping the residual lobe (p >= 3, what a
/// renderer that stops at TRT does): the report gives the signed error and the worst view.
#[test]
fn a_model_that_gains_or_loses_energy_fails_the_furnace() {
    let reference = white(0.3, 0.3);
    let settings = FurnaceSettings {
        sphere: SphereSize::new(16, 8, 256),
        ..FurnaceSettings::default()
    };
    let brighter = from_eval(|q: &Query<f64>| reference.eval(q).map(|s| 1.05 * s), true);
    let report = furnace(&brighter, &settings);
    println!("5% brighter: {report}");
    assert!(!report.passes(1e-3));
    let worst = report.worst_case().unwrap();
    assert!((worst.error - 0.05).abs() < 1e-4, "{report}");
    assert!(report.to_string().contains("gained"), "{report}");

    let residual = reference.lobe_names().len() - 1;
    assert_eq!(reference.lobe_names()[residual], "residual");
    let without_residual = from_eval(
        |q: &Query<f64>| {
            let lobes = reference.eval_lobes(q);
            core::array::from_fn(|c| lobes[..residual].iter().map(|l| l[c]).sum())
        },
        true,
    );
    let report = furnace(&without_residual, &settings);
    println!("no residual lobe: {report}");
    let worst = report.worst_case().unwrap();
    assert!(worst.error < -0.01, "{report}");
    assert!(report.to_string().contains("lost"), "{report}");
}

/// The reference's sampler returns exactly S / pdf: measured worst relative error 0 to
/// rounding over the default 40,000 samples (bound 1e-9).
#[test]
fn the_reference_sampler_passes_the_weight_and_chi_square_tests() {
    for model in [brown(), white(0.1, 0.1), white(1.0, 1.0)] {
        let weights = sample_weights(&model, &WeightSettings::default());
        println!("{weights}");
        assert_eq!(weights.comparison.rows, 40_000);
        assert!(weights.passes(1e-9), "{weights}");
        for view in [View::at(30.0, 0.3), View::at(-75.0, -0.95)] {
            let settings = ChiSquareSettings {
                view,
                ..ChiSquareSettings::default()
            };
            let report = chi_square(&model, &settings);
            println!("{report}");
            assert!(report.passes(1e-3), "{report}");
            assert!((report.pdf_integral - 1.0).abs() < 2e-5, "{report}");
        }
    }
}

/// A sampler that returns a pdf 1.5 times its density but evaluates S correctly: its weights
/// are 2/3 of S / pdf, and the report names the error (1/3) and the random numbers.
#[test]
fn a_sampler_whose_weight_disagrees_with_its_pdf_fails() {
    let hair = brown();
    let inconsistent = from_sampler(
        |q: &Query<f64>| hair.eval(q),
        |q: &Query<f64>| hair.pdf(q),
        |wo, h, u| HairSample {
            pdf: 1.5 * hair.sample(wo, h, u).pdf,
            ..hair.sample(wo, h, u)
        },
        true,
    );
    let report = sample_weights(&inconsistent, &WeightSettings::default());
    println!("{report}");
    assert!(!report.passes(1e-3));
    let error = report.comparison.max_rel_error;
    // 1/3 less the floor's share (1e-6 of the largest weight) of the row's error measure.
    assert!((error - 1.0 / 3.0).abs() < 1e-6, "{report}");
    assert_eq!(report.worst_numbers.len(), 5);
    assert!(report.to_string().contains("drew u = (lobe "), "{report}");
}

/// A pdf off by a constant in the sampler and the pdf alike is consistent with itself (the
/// weights agree) but is not a density: the chi-square test fails, and its report says the
/// pdf integrates to 1.5.
#[test]
fn a_pdf_off_by_a_constant_fails_the_chi_square() {
    let hair = brown();
    let scaled = from_sampler(
        |q: &Query<f64>| hair.eval(q),
        |q: &Query<f64>| 1.5 * hair.pdf(q),
        |wo, h, u| {
            let s = hair.sample(wo, h, u);
            HairSample {
                pdf: 1.5 * s.pdf,
                ..s
            }
        },
        true,
    );
    let weights = sample_weights(&scaled, &WeightSettings::default());
    assert!(weights.passes(1e-9), "{weights}");
    let report = chi_square(&scaled, &ChiSquareSettings::default());
    println!("{report}");
    assert!(!report.passes(1e-3));
    assert!((report.pdf_integral - 1.5).abs() < 1e-4, "{report}");
    assert!(report.p_value < 1e-100, "{report}");
    assert!(report.to_string().contains("integrates to 1.5"), "{report}");
}

/// A sampler that draws directions from a different lobe width than its pdf states (beta_m
/// 0.25 sampled, 0.3 claimed): the pdf integrates to 1, but the histogram disagrees.
#[test]
fn a_sampler_that_does_not_follow_its_pdf_fails_the_chi_square() {
    let claimed = brown();
    let sampled = ChiangHair::<f64>::new(&HairParams {
        beta_m: LongitudinalRoughness::new(0.25).unwrap(),
        ..HairParams::default()
    });
    let mismatched = from_sampler(
        |q: &Query<f64>| claimed.eval(q),
        |q: &Query<f64>| claimed.pdf(q),
        |wo, h, u| sampled.sample(wo, h, u),
        true,
    );
    let report = chi_square(&mismatched, &ChiSquareSettings::default());
    println!("{report}");
    assert!((report.pdf_integral - 1.0).abs() < 2e-5, "{report}");
    assert!(!report.passes(1e-3) && report.p_value < 1e-6, "{report}");
    let worst = report.worst_bin.unwrap();
    assert!(worst.observed > worst.expected, "narrower lobes: {report}");
}

/// The reference's S, pdf and samples are finite and allowed over the hard cases of every hard
/// parameter set and 300 proptest cases.
#[test]
fn the_reference_passes_the_values_search() {
    let settings = ValueSettings {
        cases: 300,
        seed: 7,
    };
    let report = sampler_values(ChiangHair::<f64>::new, &settings);
    println!("{report}");
    assert!(report.passes(), "{report}");
    assert!(
        report.evaluated >= 243 * hard_params().len() + 300,
        "{report}"
    );
    assert!(report.lowest.unwrap().output.value >= 0.0);
}

/// S divided by cos theta_i (pbrt's f passed as S) is infinite along the tangent: found at a
/// hard case, named with its inputs.
#[test]
fn an_infinite_value_along_the_tangent_is_found_at_a_hard_case() {
    let report = eval_values(
        |params: &HairParams| {
            let hair = ChiangHair::<f64>::new(params);
            from_eval(
                move |q: &Query<f64>| {
                    let cos = (1.0 - q.wi.x * q.wi.x).max(0.0).sqrt();
                    hair.eval(q).map(|s| s / cos)
                },
                true,
            )
        },
        &ValueSettings::default(),
    );
    println!("{report}");
    assert!(!report.passes() && report.at_hard_case, "{report}");
    let failure = report.failure.unwrap();
    assert_eq!(failure.query.wi.x.abs(), 1.0, "{report}");
    assert!(report.to_string().contains("a hard case"), "{report}");
}

/// A negative S in one range of beta_n only (as a renderer's lookup table wrong in one range
/// would give), away from every hard value: proptest finds it, and shrinks the inputs that do
/// not matter to their simplest values (proptest 1.9 shrinks a float to the low end of its
/// range only, and keeps it where it was found when that end passes, as beta_n's does here).
#[test]
fn a_negative_value_inside_the_domain_is_found_by_proptest() {
    let broken = |beta_n: f64| (0.4..0.8).contains(&beta_n);
    let report = eval_values(
        |params: &HairParams| {
            let hair = ChiangHair::<f64>::new(params);
            let offset = if broken(params.beta_n.get()) {
                1.0
            } else {
                0.0
            };
            from_eval(move |q: &Query<f64>| hair.eval(q).map(|v| v - offset), true)
        },
        &ValueSettings::default(),
    );
    println!("{report}");
    assert!(!report.passes() && !report.at_hard_case, "{report}");
    assert!(report.evaluated > 243 * hard_params().len(), "{report}");
    let failure = report.failure.unwrap();
    assert!(broken(failure.params.beta_n.get()), "{report}");
    assert!(failure.output.value < 0.0, "{report}");
    assert_eq!(
        failure.params.beta_m.get(),
        0.01,
        "shrunk to the low end: {report}"
    );
    assert!(
        report.to_string().contains("shrunk by proptest"),
        "{report}"
    );
}

/// Degenerate settings give a report that fails (never a panic, never a vacuous pass): no
/// views, no samples, no bins, an empty sphere rule.
#[test]
fn degenerate_settings_fail_without_panicking() {
    let hair = brown();
    let no_views = FurnaceSettings {
        theta_o_deg: vec![],
        ..FurnaceSettings::default()
    };
    assert!(!furnace(&hair, &no_views).passes(1.0));
    let empty_rule = FurnaceSettings {
        sphere: SphereSize::new(0, 8, 512),
        ..FurnaceSettings::default()
    };
    let report = furnace(&hair, &empty_rule);
    assert!(!report.passes(0.5), "{report}");
    let no_samples = WeightSettings {
        samples_per_view: 0,
        ..WeightSettings::default()
    };
    assert!(!sample_weights(&hair, &no_samples).passes(1.0));
    for (samples, theta_bins, phi_bins) in [(0, 32, 64), (1000, 0, 64), (1000, 32, 0)] {
        let settings = ChiSquareSettings {
            samples,
            theta_bins,
            phi_bins,
            ..ChiSquareSettings::default()
        };
        let report = chi_square(&hair, &settings);
        println!("{report}");
        assert!(!report.passes(0.0), "{report}");
    }
}
