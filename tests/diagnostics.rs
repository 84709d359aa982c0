//! The values of `hairmath::diagnostics` (the figures of `hairmath report`) against independent
//! references: the white furnace against 1, the lobe energies against a 1-D average of the
//! attenuations, the far field's energies against the near field's h-average, the integrator
//! table against the documented error bounds, and the report's internal consistency.
//!
//! Measured values quoted in comments come from `cargo test --test diagnostics` (the test
//! profile is optimised; the quadrature is deterministic, so they do not vary between runs).

use hairmath::absorption::{Absorption, PathLength};
use hairmath::azimuthal::attenuations_at_offset;
use hairmath::bcsdf::{
    Bcsdf, ChiangFarField, ChiangHair, FarFieldRule, Marschner2003, FAR_FIELD_ERROR_BOUNDS,
};
use hairmath::diagnostics::{
    albedo, integrator_table, lobe_energies, ns_per_eval, report, report_hair, viewing_direction,
    white_furnace, Furnace, IntegratorSettings, LobeEnergies, ReportDetail, ReportSettings,
    SphereSize, FAR_NODES, FURNACE_BETAS, INTEGRATOR_SIGMA_A, REPORT_BETA, REPORT_ETA,
    REPORT_HAIRS,
};
use hairmath::params::HairParams;
use hairmath::quadrature::{gauss_legendre, integrate, SphereRule};

/// The settings of the full report (`hairmath report`).
fn full() -> ReportSettings {
    ReportSettings::new(ReportDetail::Full)
}

/// The report's white hair (sigma_a = 0) with beta_m = beta_n = `beta`.
fn white(beta: f64) -> HairParams {
    report_hair(beta, beta, [0.0; 3]).unwrap()
}

/// The near field's furnace at `beta` with the full report's inclinations and offsets.
fn near_furnace(beta: f64, sphere: SphereSize) -> Furnace {
    let s = full();
    let model = ChiangHair::<f64>::new(&white(beta));
    white_furnace(&model, &sphere.rule(), &s.furnace_theta_o_deg, &s.furnace_h)
}

/// The far field's furnace (the report's node count) at `beta`.
fn far_furnace(beta: f64, sphere: SphereSize) -> Furnace {
    let s = full();
    let rule = FarFieldRule::gauss_legendre(FAR_NODES).unwrap();
    let model = ChiangFarField::<f64>::with_rule(&white(beta), &rule);
    white_furnace(&model, &sphere.rule(), &s.furnace_theta_o_deg, &s.furnace_h)
}

/// Largest absolute difference between per-lobe tables.
fn max_abs_difference(a: &[[f64; 3]], b: &[[f64; 3]]) -> f64 {
    assert_eq!(a.len(), b.len());
    a.iter()
        .flatten()
        .zip(b.iter().flatten())
        .map(|(x, y)| (x - y).abs())
        .fold(0.0, f64::max)
}

// ---------------------------------------------------------------------------------------------
// White furnace.

/// With sigma_a = 0 the albedo is 1 within 1e-6 at the full report's quadrature, for every
/// inclination and offset the report searches and every roughness of the report. (With the
/// report's earlier SphereRule::new(32, 8, 256) beta 0.9 missed the bound, -3.8e-6: see
/// `near_field_furnace_at_beta_0_9_is_the_azimuthal_rule_error`; the report now uses
/// SphereRule::new(16, 8, 512), the same number of nodes.)
#[test]
fn near_field_furnace_is_within_1e_6_at_the_report_quadrature() {
    let s = full();
    for beta in FURNACE_BETAS {
        let f = near_furnace(beta, s.furnace_sphere_for(beta));
        assert_eq!(
            f.cases.len(),
            s.furnace_theta_o_deg.len() * s.furnace_h.len()
        );
        for case in &f.cases {
            for a in case.albedo {
                assert!((a - 1.0).abs() < 1e-6, "beta {beta}: {case:?}");
            }
        }
        assert!(f.worst_error.abs() < 1e-6, "beta {beta}: {}", f.worst_error);
    }
}

/// The far field's albedo is 1 within 1e-6 at the report's quadrature for every beta of the
/// report. Measured worst errors: beta 0.1 +6.1e-12, 0.3 -6.1e-15, 0.5 -2.1e-10, 0.7 -1.1e-8,
/// 0.9 -7.3e-8 (the fixed rule's weights sum to 1; what remains is the sphere rule's error,
/// smaller than the near field's because averaging over h smooths the kinks of N_p).
#[test]
fn far_field_furnace_is_within_1e_6_at_the_report_quadrature() {
    let s = full();
    for beta in FURNACE_BETAS {
        let f = far_furnace(beta, s.furnace_sphere_for(beta));
        // A far-field model is evaluated once per inclination, at h = 0.
        assert_eq!(f.cases.len(), s.furnace_theta_o_deg.len());
        assert!(f.cases.iter().all(|c| c.h == 0.0));
        assert!(f.worst_error.abs() < 1e-6, "beta {beta}: {:?}", f.cases);
    }
}

/// At beta = 0.9 the near field's furnace error at the report's SphereRule::new(32, 8, 256) is
/// -3.80e-6, above the 1e-6 bound. The cause is the quadrature, not the model: the trimmed
/// logistic D(phi - Phi_p) is continuous at +-pi from its centre but its derivative jumps
/// there, so the midpoint rule in phi converges only as 1/azimuths^2, and at beta_n = 0.9 the
/// logistic is wide enough for the jump to matter. Measured: refining theta (64 panels, or
/// order 16) leaves the error at -3.801e-6; doubling the azimuths gives -7.34e-7 (512),
/// -1.65e-7 (1024), -3.89e-8 (2048): ratios 5.2, 4.4, 4.2, second order. With 512 azimuths
/// (also as SphereRule::new(16, 8, 512), the same number of nodes as the report's rule) every
/// beta meets 1e-6.
#[test]
fn near_field_furnace_at_beta_0_9_is_the_azimuthal_rule_error() {
    let report_rule = near_furnace(0.9, SphereSize::new(32, 8, 256)).worst_error;
    assert!(
        report_rule < -1e-6 && report_rule > -1e-5,
        "report's rule: {report_rule:e}"
    );
    // Not the theta rule: twice the panels changes nothing at this level.
    let finer_theta = near_furnace(0.9, SphereSize::new(64, 8, 256)).worst_error;
    assert!(
        (finer_theta - report_rule).abs() < 1e-9,
        "{finer_theta:e} vs {report_rule:e}"
    );
    // The azimuthal rule, at second order: each doubling divides the error by about 4.
    let e512 = near_furnace(0.9, SphereSize::new(32, 8, 512)).worst_error;
    let e1024 = near_furnace(0.9, SphereSize::new(32, 8, 1024)).worst_error;
    for (coarse, fine) in [(report_rule, e512), (e512, e1024)] {
        let ratio = coarse / fine;
        assert!(
            (3.0..7.0).contains(&ratio),
            "{coarse:e} / {fine:e} = {ratio}"
        );
    }
    assert!(e512.abs() < 1e-6, "{e512:e}");
    // The same number of nodes as the report's rule, spent on phi: within the bound.
    let rebalanced = near_furnace(0.9, SphereSize::new(16, 8, 512)).worst_error;
    assert!(rebalanced.abs() < 1e-6, "{rebalanced:e}");
}

/// `albedo` is the sphere rule's sum of `eval`, and the furnace's worst error is the signed
/// error of largest magnitude over its cases.
#[test]
fn furnace_worst_error_is_the_largest_case() {
    let model = ChiangHair::<f64>::new(&white(0.5));
    let rule = SphereRule::new(8, 4, 32);
    let f = white_furnace(&model, &rule, &[0.0, 60.0], &[-0.5, 0.7]);
    let largest =
        f.cases
            .iter()
            .map(|c| c.error)
            .fold(0.0_f64, |w, e| if e.abs() > w.abs() { e } else { w });
    assert_eq!(f.worst_error, largest);
    let case = &f.cases[3];
    assert_eq!((case.theta_o_deg, case.h), (60.0, 0.7));
    let direct = albedo(&model, &rule, viewing_direction(60.0), 0.7);
    assert_eq!(case.albedo, direct);
    let by_hand: f64 = rule
        .nodes
        .iter()
        .map(|&(wi, w)| {
            w * model.eval(&hairmath::bcsdf::Query::new(
                wi,
                viewing_direction(60.0),
                0.7,
            ))[1]
        })
        .sum();
    assert!((direct[1] - by_hand).abs() < 1e-15);
}

// ---------------------------------------------------------------------------------------------
// Lobe energies.

/// The h-average of `A_p(h)` at theta_o = 0 per lobe and channel, by a composite 8-point
/// Gauss-Legendre rule in gamma = asin h with `panels` panels:
/// `1/2 int_{-1}^{1} A_p(h) dh = 1/2 int_{-pi/2}^{pi/2} A_p(sin gamma) cos gamma d gamma`.
fn attenuation_average(sigma_a: [f64; 3], panels: usize) -> Vec<[f64; 3]> {
    let rule = gauss_legendre(8);
    let half_pi = core::f64::consts::FRAC_PI_2;
    (0..4)
        .map(|p| {
            core::array::from_fn(|c| {
                let a = |g: f64| {
                    let h = g.sin();
                    attenuations_at_offset(h, 0.0, 1.0, REPORT_ETA, sigma_a[c], PathLength::Chord)
                        [p]
                        * g.cos()
                };
                0.5 * integrate(&rule, panels, -half_pi, half_pi, a)
            })
        })
        .collect()
}

/// At theta_o = 0 the energy of lobe p is the h-average of A_p(h): d'Eon's M_p integrates to 1
/// over theta_i (cos theta_i d theta_i) for every tilted theta_o, the trimmed logistic to 1 over
/// phi on the circle, and the residual's 1 / (2 pi) too; A_p depends on h and theta_o only.
/// So `lobe_energies` of `ChiangHair` at the report's sphere rule must match the independent
/// 1-D average of `attenuations_at_offset`, up to the two quadratures' errors.
///
/// Convergence measured (largest difference over lobes and channels; the reference changes by
/// at most 1.2e-14 from 64 to 128 panels): with 16 nodes in h 1.36e-6 (blonde), 1.3e-7 (red),
/// 9.9e-8 (brown), 1.6e-9 (dark brown), 9.4e-11 (black); with 32 nodes 2.1e-9 (blonde), <= 5e-13
/// (the others); with 64 nodes <= 1.7e-12 (every hair), which is the rounding of sums of 4
/// million terms (128 nodes give 3.5e-12, not less). The sphere rule's own error at beta 0.3
/// is about 1e-12 (the report's convergence check). Tolerances: 2e-6 for 16 nodes, 5e-9 for 32
/// and 1e-10 for 64, above what was measured and far below the 16-node error.
#[test]
fn lobe_energies_at_theta_0_are_the_h_average_of_the_attenuations() {
    let sphere = full().sphere.rule();
    let wo = viewing_direction(0.0);
    for (name, eu, pheo) in REPORT_HAIRS {
        let sigma_a = Absorption::from_melanin(eu, pheo).unwrap().rgb();
        let model =
            ChiangHair::<f64>::new(&report_hair(REPORT_BETA, REPORT_BETA, sigma_a).unwrap());
        let reference = attenuation_average(sigma_a, 128);
        let converged = max_abs_difference(&reference, &attenuation_average(sigma_a, 64));
        assert!(converged < 1e-13, "{name}: reference {converged:e}");
        for (nodes, tolerance) in [(16, 2e-6), (32, 5e-9), (64, 1e-10)] {
            let offsets = FarFieldRule::gauss_legendre(nodes).unwrap();
            let energies = lobe_energies(&model, &sphere, wo, &offsets);
            assert_eq!(energies.names, &["R", "TT", "TRT", "residual"]);
            let d = max_abs_difference(&energies.lobes, &reference);
            assert!(d < tolerance, "{name}, {nodes} nodes: {d:e}");
        }
    }
}

/// The far field is the near field averaged over h with the same nodes, so the far field's
/// energies equal the near field's h-average with the rule's nodes: measured difference
/// <= 1.7e-12 (blonde; 8e-13 red and brown, 2.3e-13 dark brown and black), the rounding of the two
/// summation orders. With the report's 16 nodes in the near table the difference is the h
/// rule's error (`far_vs_near`, measured 1.36e-6 for blonde, as the report prints).
#[test]
fn far_field_energies_are_the_near_field_h_average() {
    let s = full();
    let sphere = s.sphere.rule();
    let wo = viewing_direction(0.0);
    let rule = FarFieldRule::gauss_legendre(FAR_NODES).unwrap();
    let report_offsets = FarFieldRule::gauss_legendre(s.offset_nodes).unwrap();
    for (name, eu, pheo) in REPORT_HAIRS {
        let sigma_a = Absorption::from_melanin(eu, pheo).unwrap().rgb();
        let params = report_hair(REPORT_BETA, REPORT_BETA, sigma_a).unwrap();
        let near = lobe_energies(&ChiangHair::<f64>::new(&params), &sphere, wo, &rule);
        let far_model = ChiangFarField::<f64>::with_rule(&params, &rule);
        // The far field ignores the offsets it is given.
        let far = lobe_energies(&far_model, &sphere, wo, &report_offsets);
        let d = far.max_difference(&near);
        assert!(d < 1e-11, "{name}: {d:e}");
        let coarse = lobe_energies(
            &ChiangHair::<f64>::new(&params),
            &sphere,
            wo,
            &report_offsets,
        );
        assert!(far.max_difference(&coarse) < 2e-6, "{name}");
    }
}

/// Totals are the sums of the lobes; `lobe` finds a lobe by name; `max_difference` matches lobes
/// by name and counts a missing lobe as zero energy. Works for any model behind `dyn Bcsdf`,
/// with any number of lobes (Marschner 2003 has three).
#[test]
fn lobe_energies_work_for_any_model() {
    let sphere = SphereRule::new(8, 4, 32);
    let wo = viewing_direction(20.0);
    let offsets = FarFieldRule::gauss_legendre(4).unwrap();
    let chiang: Box<dyn Bcsdf<f64>> = Box::new(ChiangHair::<f64>::new(&HairParams::default()));
    let marschner: Box<dyn Bcsdf<f64>> = Box::new(Marschner2003 {
        lobes: Default::default(),
        eta: hairmath::params::RefractiveIndex::HUMAN_HAIR,
        sigma_a: Absorption::from_melanin(1.3, 0.0).unwrap(),
        caustic: None,
    });
    let c = lobe_energies(chiang.as_ref(), &sphere, wo, &offsets);
    let m = lobe_energies(marschner.as_ref(), &sphere, wo, &offsets);
    assert_eq!(m.names, &["R", "TT", "TRT"]);
    for e in [&c, &m] {
        for ch in 0..3 {
            let sum: f64 = e.lobes.iter().map(|l| l[ch]).sum();
            assert!((e.total[ch] - sum).abs() < 1e-15);
            assert!(e.total[ch].is_finite() && e.total[ch] > 0.0);
        }
    }
    let by_hand = ["R", "TT", "TRT"]
        .iter()
        .flat_map(|n| {
            let (a, b) = (c.lobe(n).unwrap(), m.lobe(n).unwrap());
            (0..3).map(move |k| (a[k] - b[k]).abs())
        })
        .chain(c.lobe("residual").unwrap().map(f64::abs))
        .fold(0.0, f64::max);
    assert_eq!(c.max_difference(&m), by_hand);
    assert_eq!(m.max_difference(&c), by_hand);
    assert_eq!(c.max_difference(&c), 0.0);
    assert_eq!(c.lobe("TRRT"), None);
    // The albedo of every model comes through the same trait.
    let a = albedo(marschner.as_ref(), &sphere, wo, 0.0);
    assert!(a.iter().all(|x| x.is_finite() && *x > 0.0), "{a:?}");
}

// ---------------------------------------------------------------------------------------------
// Far-field integrator.

/// The integrator table of the full report (plus 512 nodes, so that every documented bound has
/// an entry) is within `FAR_FIELD_ERROR_BOUNDS` wherever the table has the bound's
/// (beta_n, nodes). The table also measures the residual lobe, which the bounds do not name;
/// it stays within them. Measured (max errors): 1.0e-3 (0.05, 512), 4.3e-2 (0.1, 128),
/// 1.4e-2 (0.3, 32), 1.4e-5 (0.3, 64), 1.8e-6 (0.5, 32), 2.0e-4 (1, 32), 1.9e-5 (1, 128); the
/// reference's own error is at most 1.1e-12 (beta_n 0.5).
#[test]
fn integrator_table_is_within_the_documented_bounds() {
    let mut settings: IntegratorSettings = full().integrator;
    settings.nodes.push(512);
    settings.timing_node_evals = 0;
    let hair = report_hair(REPORT_BETA, REPORT_BETA, INTEGRATOR_SIGMA_A).unwrap();
    let table = integrator_table(&hair, &settings).unwrap();
    assert_eq!(table.rows.len(), settings.beta_n.len());
    let mut checked = 0;
    for &(beta_n, nodes, bound) in FAR_FIELD_ERROR_BOUNDS {
        let Some(row) = table.rows.iter().find(|r| r.beta_n == beta_n) else {
            continue;
        };
        let Some(errors) = row.errors_at(nodes) else {
            continue;
        };
        assert!(
            errors.max <= bound && errors.mean <= errors.max,
            "beta_n {beta_n}, {nodes} nodes: {errors:?} vs {bound}"
        );
        checked += 1;
    }
    assert_eq!(checked, FAR_FIELD_ERROR_BOUNDS.len());
    for row in &table.rows {
        assert!(row.reference_refinement < 1e-11, "{row:?}");
        assert!(row.reference_us.is_finite() && row.reference_us > 0.0);
        assert_eq!(row.errors.len(), settings.nodes.len());
    }
    // Convergence where the integrand is smooth enough: beta_n = 0.3 reaches rounding at 128.
    let smooth = table.rows.iter().find(|r| r.beta_n == 0.3).unwrap();
    assert!(smooth.errors_at(128).unwrap().max < 1e-10);
    assert!(table
        .timings
        .iter()
        .all(|t| t.ns.is_finite() && t.ns >= 0.0));
}

/// A node count outside 1..=512 or a beta_n outside (0, 1] is a typed error.
#[test]
fn integrator_table_rejects_bad_settings() {
    let hair = report_hair(REPORT_BETA, REPORT_BETA, INTEGRATOR_SIGMA_A).unwrap();
    let mut settings = ReportSettings::new(ReportDetail::Quick).integrator;
    settings.nodes = vec![0];
    assert!(integrator_table(&hair, &settings).is_err());
    settings.nodes = vec![8];
    settings.beta_n = vec![1.5];
    assert!(integrator_table(&hair, &settings).is_err());
}

// ---------------------------------------------------------------------------------------------
// Timing and the report.

/// Timings of any model in f64 and f32 are finite and non-negative; zero calls give 0.
#[test]
fn timings_are_finite() {
    let params = HairParams::default();
    let t64 = ns_per_eval(&ChiangHair::<f64>::new(&params), 2000);
    let t32 = ns_per_eval(&ChiangHair::<f32>::new(&params), 2000);
    let far: &dyn Bcsdf<f32> =
        &ChiangFarField::<f32>::with_rule(&params, &FarFieldRule::gauss_legendre(8).unwrap());
    let t_far = ns_per_eval(far, 200);
    for t in [t64, t32, t_far] {
        assert!(t.is_finite() && t > 0.0, "{t}");
    }
    assert_eq!(ns_per_eval(&ChiangHair::<f64>::new(&params), 0), 0.0);
}

/// The quick report runs; every number is finite, totals are sums of the lobes, every furnace
/// beta, hair colour, beta_n and node count has its entry, and `far_vs_near` is the tables'
/// difference.
#[test]
fn quick_report_is_finite_and_consistent() {
    let settings = ReportSettings::new(ReportDetail::Quick);
    let r = report(&settings).unwrap();
    assert_eq!(r.settings, settings);
    assert_eq!(r.hairs.len(), REPORT_HAIRS.len());
    let check = |e: &LobeEnergies| {
        assert_eq!(e.lobes.len(), e.names.len());
        for c in 0..3 {
            let sum: f64 = e.lobes.iter().map(|l| l[c]).sum();
            assert!((e.total[c] - sum).abs() <= 1e-15, "{e:?}");
            // Absorbing hair: energy in (0, 1).
            assert!(e.total[c] > 0.0 && e.total[c] < 1.0, "{e:?}");
        }
        assert!(e.lobes.iter().flatten().all(|x| x.is_finite() && *x >= 0.0));
    };
    for (hair, (name, eu, pheo)) in r.hairs.iter().zip(REPORT_HAIRS) {
        assert_eq!(
            (hair.name, hair.eumelanin, hair.pheomelanin),
            (name, eu, pheo)
        );
        assert_eq!(
            hair.sigma_a,
            Absorption::from_melanin(eu, pheo).unwrap().rgb()
        );
        check(&hair.near);
        check(&hair.far);
        assert_eq!(hair.far_vs_near, hair.far.max_difference(&hair.near));
        // Quick: 4 nodes in h against the far field's 64 (measured up to 6.8e-3).
        assert!(hair.far_vs_near > 0.0 && hair.far_vs_near < 1e-2);
    }
    // Blonde reflects the most, black the least; the R lobe does not depend on the absorption.
    let green: Vec<f64> = r.hairs.iter().map(|h| h.near.total[1]).collect();
    let (first, last) = (green[0], green[green.len() - 1]);
    assert!(green.iter().all(|&g| g <= first && g >= last), "{green:?}");
    let r_lobes: Vec<[f64; 3]> = r.hairs.iter().map(|h| h.near.lobes[0]).collect();
    assert!(r_lobes
        .windows(2)
        .all(|w| max_abs_difference(&w[..1], &w[1..]) < 1e-15));
    assert_eq!(r.convergence.hair, REPORT_HAIRS[0].0);
    assert!(r.convergence.fine_sphere_change.is_finite());
    assert!(r.convergence.fine_offset_change.is_finite());

    let betas: Vec<f64> = r.furnace.iter().map(|f| f.beta).collect();
    assert_eq!(betas, FURNACE_BETAS);
    for f in &r.furnace {
        assert_eq!(f.sphere, settings.furnace_sphere_for(f.beta));
        let cases = settings.furnace_theta_o_deg.len() * settings.furnace_h.len();
        assert_eq!(f.near.cases.len(), cases);
        assert_eq!(f.far.cases.len(), settings.furnace_theta_o_deg.len());
        for furnace in [&f.near, &f.far] {
            assert!(furnace.worst_error.is_finite());
            // Coarse quadrature: rough, but close to 1 (measured worst -1.3e-1 at beta 0.1).
            assert!(furnace.worst_error.abs() < 0.2, "{f:?}");
        }
    }

    assert_eq!(r.timing.calls, settings.timing_calls);
    assert!(r.timing.ns_f64 > 0.0 && r.timing.ns_f64.is_finite());
    assert!(r.timing.ns_f32 > 0.0 && r.timing.ns_f32.is_finite());

    let beta_n: Vec<f64> = r.integrator.rows.iter().map(|row| row.beta_n).collect();
    assert_eq!(beta_n, settings.integrator.beta_n);
    for row in &r.integrator.rows {
        let nodes: Vec<usize> = row.errors.iter().map(|e| e.nodes).collect();
        assert_eq!(nodes, settings.integrator.nodes);
        assert!(row
            .errors
            .iter()
            .all(|e| e.max.is_finite() && e.mean <= e.max));
        assert!(row.reference_refinement.is_finite());
    }
    let timed: Vec<usize> = r.integrator.timings.iter().map(|t| t.nodes).collect();
    assert_eq!(timed, settings.integrator.nodes);
}
