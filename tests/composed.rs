//! The composed model (`models::ComposedHair`): its far field is Chiang's, its Frostbite
//! composition is the Frostbite model, every factor is finite and non-negative on the hard
//! cases and over the parameters' domains, its `f32` code is what its traced shader computes,
//! and compositions whose factors do not fit are typed errors.

use core::f64::consts::{FRAC_PI_2, PI};
use hairmath::absorption::Absorption;
use hairmath::bcsdf::{
    eval_batch, trace_eval_with, BatchReal, Bcsdf, ChiangFarField, FarFieldRule, HostBatch,
    InstructionSet, Model, Query, UniformsIn,
};
use hairmath::geometry::{local_direction, V3};
use hairmath::models::{
    far_field_lobe_table, gerard_lobe_table, nguyen_donnelly_lobe_table, Attenuation, Azimuthal,
    ComposedHair, ComposedLobe, Composition, CompositionError, Constants, Distribution, Frostbite,
    LobeFactors, LobeTableSize, Longitudinal, MarschnerTableSize,
};
use hairmath::params::{HairParams, HairValues, RefractiveIndex};
use proptest::prelude::*;

fn hair(beta_m: f64, beta_n: f64, alpha_deg: f64, eta: f64, sigma_a: f64) -> HairParams {
    HairParams::try_from(HairValues {
        beta_m,
        beta_n,
        alpha: alpha_deg.to_radians(),
        eta,
        sigma_a: [sigma_a, 0.5 * sigma_a, 0.25 * sigma_a],
    })
    .expect("valid parameters")
}

fn brown() -> HairParams {
    let sigma_a = Absorption::from_melanin(1.3, 0.0).expect("melanin").rgb();
    HairParams::try_from(HairValues {
        beta_m: 0.3,
        beta_n: 0.3,
        alpha: 2f64.to_radians(),
        eta: 1.55,
        sigma_a,
    })
    .expect("valid parameters")
}

fn direction(theta: f64, phi: f64) -> V3<f64> {
    local_direction(theta.sin(), theta.cos(), phi)
}

/// Along the tangent both ways, grazing, wi = wo, wi = -wo, phi = 0 and +-pi, generic pairs.
fn hard_pairs() -> Vec<(V3<f64>, V3<f64>)> {
    let along = V3::new(1.0, 0.0, 0.0);
    let against = V3::new(-1.0, 0.0, 0.0);
    let mut pairs = vec![
        (along, along),
        (along, against),
        (against, along),
        (
            direction(FRAC_PI_2 - 1e-7, 0.2),
            direction(-FRAC_PI_2 + 1e-7, 0.2),
        ),
    ];
    for (theta_i, theta_o) in [(0.0, 0.0), (0.4, -0.4), (-1.2, 0.3), (1.55, -1.55)] {
        for phi in [0.0, PI, -PI, 1.1] {
            pairs.push((direction(theta_i, phi), direction(theta_o, 0.0)));
        }
        let w = direction(theta_i, 0.7);
        pairs.push((w, w));
        pairs.push((w, V3::new(-w.x, -w.y, -w.z)));
    }
    pairs
}

/// Every factor set each lobe takes.
fn every_lobe_option(lobe: ComposedLobe) -> Vec<LobeFactors> {
    let constants = [Constants::Published, Constants::Refit];
    let mut azimuthals = vec![
        Azimuthal::FarField,
        Azimuthal::KarisReflection,
        Azimuthal::Table { absorption: None },
        Azimuthal::GerardTable { absorption: None },
        Azimuthal::NguyenDonnellyTable,
    ];
    let mut distributions: Vec<Distribution> = constants.map(Distribution::Karis).to_vec();
    distributions.extend([Distribution::FrostbiteTable, Distribution::FrostbiteScaled]);
    for distribution in distributions {
        for c in constants {
            for attenuation in [Attenuation::Offset(c), Attenuation::Exponential(c)] {
                azimuthals.push(Azimuthal::Separable {
                    distribution,
                    attenuation,
                });
            }
        }
    }
    for c in constants {
        for attenuation in [Attenuation::Offset(c), Attenuation::Exponential(c)] {
            azimuthals.push(Azimuthal::Table {
                absorption: Some(attenuation),
            });
            azimuthals.push(Azimuthal::GerardTable {
                absorption: Some(attenuation),
            });
        }
    }
    let ms = [
        Longitudinal::Deon,
        Longitudinal::DeonReduced,
        Longitudinal::SineGaussian,
        Longitudinal::ThetaHGaussian,
        Longitudinal::HenyeyGreenstein,
    ];
    let mut out = Vec::new();
    for longitudinal in ms {
        for &azimuthal in azimuthals.iter().filter(|&&a| lobe.accepts(a)) {
            out.push(LobeFactors {
                longitudinal,
                azimuthal,
            });
        }
    }
    out
}

/// One composition per lobe option (the lobe alone), plus the residual alone.
fn every_single_lobe_composition(nodes: usize) -> Vec<Composition> {
    let empty = Composition {
        r: None,
        tt: None,
        trt: None,
        residual: false,
        far_field_nodes: nodes,
        table: LobeTableSize::OFFERED[0],
        marschner_table: MarschnerTableSize::OFFERED[0],
    };
    let mut out = vec![Composition {
        residual: true,
        ..empty
    }];
    for lobe in ComposedLobe::ALL {
        for f in every_lobe_option(lobe) {
            out.push(empty.with_lobe(lobe, Some(f)));
        }
    }
    out
}

#[test]
fn every_lobe_takes_the_options_the_planner_offers() {
    // Five longitudinal factors, times 5 azimuthal ones for R and 22 for TT and TRT.
    assert_eq!(every_lobe_option(ComposedLobe::R).len(), 25);
    assert_eq!(every_lobe_option(ComposedLobe::Tt).len(), 110);
    assert_eq!(every_lobe_option(ComposedLobe::Trt).len(), 110);
}

#[test]
fn the_far_field_composition_is_chiangs_far_field() {
    let deon_far = Some(LobeFactors {
        longitudinal: Longitudinal::Deon,
        azimuthal: Azimuthal::FarField,
    });
    let composition = Composition {
        r: deon_far,
        tt: deon_far,
        trt: deon_far,
        residual: true,
        far_field_nodes: 32,
        table: LobeTableSize::OFFERED[0],
        marschner_table: MarschnerTableSize::OFFERED[0],
    };
    let params = brown();
    let composed = ComposedHair::new(&params, composition).expect("valid");
    let chiang = ChiangFarField::<f64>::with_rule(
        &params,
        &FarFieldRule::gauss_legendre(32).expect("nodes"),
    );
    for (wi, wo) in hard_pairs() {
        let q = Query::far(wi, wo);
        let (a, b) = (composed.eval(&q), chiang.eval(&q));
        for c in 0..3 {
            assert!(
                (a[c] - b[c]).abs() <= 1e-12 * b[c].abs() + 1e-300,
                "{a:?} vs {b:?} at {wi:?} {wo:?}"
            );
        }
    }
    // Its kernel is not inlined throughout (Model::INLINED_KERNEL), so the batch on the host's
    // instruction set runs the build's lanes whatever is asked, and agrees with eval_batch.
    for set in InstructionSet::ALL {
        let batch = HostBatch::on(set, &composed);
        assert_eq!(batch.instruction_set(), InstructionSet::Baseline);
        let (wi, wo) = ([[0.0, 0.6, 0.8]; 3], [[0.6, 0.8, 0.0]; 3]);
        let (mut got, mut want) = ([[0.0; 3]; 3], [[0.0; 3]; 3]);
        batch
            .eval(&wi, &wo, &[0.0; 3], &mut got)
            .expect("valid samples");
        eval_batch(
            &composed.instantiate::<BatchReal>(),
            &wi,
            &wo,
            &[0.0; 3],
            &mut want,
        )
        .expect("valid samples");
        assert_eq!(got, want);
    }
}

/// d'Eon's lobe with the reduced Bessel function differs from the full one by the reduced
/// I0's relative error alone (1.49e-4, `lobe::bessel`) at every hard pair and at beta_m from
/// 0.05 (Bessel arguments in the thousands) to 1 (arguments below 2.65); its f32 code is
/// checked with every other option's below.
#[test]
fn the_reduced_deon_lobe_is_within_the_reduced_bessel_error() {
    let with = |longitudinal| {
        let far = Some(LobeFactors {
            longitudinal,
            azimuthal: Azimuthal::FarField,
        });
        Composition {
            r: far,
            tt: far,
            trt: far,
            residual: false,
            far_field_nodes: 16,
            table: LobeTableSize::OFFERED[0],
            marschner_table: MarschnerTableSize::OFFERED[0],
        }
    };
    let mut worst: f64 = 0.0;
    for beta_m in [0.05, 0.3, 1.0] {
        let params = hair(beta_m, 0.3, 2.0, 1.55, 1.0);
        let full = ComposedHair::new(&params, with(Longitudinal::Deon)).expect("valid");
        let reduced = ComposedHair::new(&params, with(Longitudinal::DeonReduced)).expect("valid");
        for (wi, wo) in hard_pairs() {
            let q = Query::far(wi, wo);
            let (a, b) = (reduced.eval(&q), full.eval(&q));
            for c in 0..3 {
                let scale = b[c].abs() + 1e-300;
                worst = worst.max((a[c] - b[c]).abs() / scale);
                assert!(
                    (a[c] - b[c]).abs() <= 1.49e-4 * scale,
                    "{a:?} vs {b:?} at {wi:?} {wo:?}"
                );
            }
        }
    }
    assert!(worst > 1e-5, "the reduced form changed nothing: {worst:e}");
}

#[test]
fn the_frostbite_composition_is_the_frostbite_model() {
    let sine = |azimuthal| {
        Some(LobeFactors {
            longitudinal: Longitudinal::SineGaussian,
            azimuthal,
        })
    };
    let published = Attenuation::Offset(Constants::Published);
    let composition = Composition {
        r: sine(Azimuthal::KarisReflection),
        tt: sine(Azimuthal::Separable {
            distribution: Distribution::FrostbiteTable,
            attenuation: published,
        }),
        trt: sine(Azimuthal::Separable {
            distribution: Distribution::FrostbiteScaled,
            attenuation: published,
        }),
        residual: false,
        far_field_nodes: 1,
        table: LobeTableSize::OFFERED[0],
        marschner_table: MarschnerTableSize::OFFERED[0],
    };
    let params = brown();
    let composed = ComposedHair::new(&params, composition).expect("valid");
    let frostbite = Frostbite::<f64>::new(&params);
    for (wi, wo) in hard_pairs() {
        let q = Query::far(wi, wo);
        let (a, b) = (composed.eval(&q), frostbite.eval(&q));
        for c in 0..3 {
            assert!(
                (a[c] - b[c]).abs() <= 1e-12 * b[c].abs() + 1e-300,
                "{a:?} vs {b:?} at {wi:?} {wo:?}"
            );
        }
    }
}

#[test]
fn every_option_is_finite_and_non_negative_on_the_hard_cases() {
    let hairs = [
        brown(),
        hair(0.01, 0.01, 0.0, 1.0001, 0.0),
        hair(1.0, 1.0, -10.0, 3.0, 10.0),
        hair(0.05, 0.9, 10.0, 1.3, 1e3),
    ];
    for params in &hairs {
        for composition in every_single_lobe_composition(4) {
            let model = ComposedHair::new(params, composition).expect("valid");
            let single = model.instantiate::<f32>();
            for (wi, wo) in hard_pairs() {
                let s = model.eval(&Query::far(wi, wo));
                let q32 = Query::far(
                    V3::from_f64(wi.x, wi.y, wi.z),
                    V3::from_f64(wo.x, wo.y, wo.z),
                );
                let s32: [f32; 3] = single.eval(&q32);
                let ok = s.iter().all(|v| v.is_finite() && *v >= 0.0)
                    && s32.iter().all(|v| v.is_finite() && *v >= 0.0);
                assert!(
                    ok,
                    "{} at {wi:?} {wo:?}: {s:?} {s32:?}",
                    composition.describe()
                );
            }
        }
    }
}

#[test]
fn the_traced_shader_computes_the_f32_code_bit_for_bit() {
    let params = brown();
    for composition in every_single_lobe_composition(4) {
        let model = ComposedHair::new(&params, composition).expect("valid");
        let graph = trace_eval_with(&model, UniformsIn::Constant);
        let single = model.instantiate::<f32>();
        for (wi, wo) in hard_pairs() {
            let w = [wi.x, wi.y, wi.z, wo.x, wo.y, wo.z].map(|x| x as f32);
            let traced = graph.eval_f32(&w);
            let q = Query::far(V3::new(w[0], w[1], w[2]), V3::new(w[3], w[4], w[5]));
            let direct: [f32; 3] = single.eval(&q);
            let same = (0..3).all(|c| traced[c].to_bits() == direct[c].to_bits());
            assert!(
                same,
                "{}: traced {traced:?}, f32 {direct:?}",
                composition.describe()
            );
        }
    }
}

#[test]
fn factors_that_do_not_fit_their_lobe_are_errors() {
    let f = |longitudinal, azimuthal| {
        Some(LobeFactors {
            longitudinal,
            azimuthal,
        })
    };
    let empty = Composition {
        r: None,
        tt: None,
        trt: None,
        residual: false,
        far_field_nodes: 8,
        table: LobeTableSize::OFFERED[0],
        marschner_table: MarschnerTableSize::OFFERED[0],
    };
    let separable = Azimuthal::Separable {
        distribution: Distribution::Karis(Constants::Published),
        attenuation: Attenuation::Offset(Constants::Published),
    };
    let params = brown();
    let bad = [
        empty.with_lobe(ComposedLobe::R, f(Longitudinal::Deon, separable)),
        empty.with_lobe(
            ComposedLobe::Tt,
            f(Longitudinal::Deon, Azimuthal::KarisReflection),
        ),
        empty.with_lobe(
            ComposedLobe::Trt,
            f(
                Longitudinal::Deon,
                Azimuthal::Separable {
                    distribution: Distribution::FrostbiteTable,
                    attenuation: Attenuation::Offset(Constants::Refit),
                },
            ),
        ),
        empty.with_lobe(
            ComposedLobe::R,
            f(
                Longitudinal::Deon,
                Azimuthal::GerardTable {
                    absorption: Some(Attenuation::Offset(Constants::Refit)),
                },
            ),
        ),
        empty.with_lobe(
            ComposedLobe::Tt,
            f(
                Longitudinal::Deon,
                Azimuthal::GerardTable { absorption: None },
            ),
        ),
    ];
    for composition in bad {
        let error = ComposedHair::new(&params, composition).expect_err("rejected");
        assert!(
            matches!(error, CompositionError::Azimuthal { .. }),
            "{error}"
        );
        assert!(
            error
                .to_string()
                .contains("R takes FarField or KarisReflection"),
            "{error}"
        );
    }
    for nodes in [0, 513] {
        let composition = Composition {
            residual: true,
            far_field_nodes: nodes,
            ..empty
        };
        let error = ComposedHair::new(&params, composition).expect_err("rejected");
        assert_eq!(error, CompositionError::Nodes(nodes));
    }
    let nguyen = empty.with_lobe(
        ComposedLobe::R,
        f(Longitudinal::Deon, Azimuthal::NguyenDonnellyTable),
    );
    for size in [(1, 16), (32, 4097)] {
        let marschner_table = MarschnerTableSize {
            phi: size.0,
            theta_d: size.1,
        };
        let composition = Composition {
            marschner_table,
            ..nguyen
        };
        let error = ComposedHair::new(&params, composition).expect_err("rejected");
        assert_eq!(error, CompositionError::MarschnerTable(marschner_table));
        assert!(error.to_string().contains("2 to 4096 texels"), "{error}");
    }
    // Without a far field the node count is not read.
    let karis_r = empty.with_lobe(
        ComposedLobe::R,
        f(Longitudinal::Deon, Azimuthal::KarisReflection),
    );
    assert!(ComposedHair::new(
        &params,
        Composition {
            far_field_nodes: 0,
            ..karis_r
        }
    )
    .is_ok());
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(256))]

    #[test]
    fn every_option_is_finite_and_non_negative_over_the_domain(
        beta_m in 0.01f64..=1.0,
        beta_n in 0.01f64..=1.0,
        alpha_deg in -20f64..20.0,
        eta in 1.0001f64..3.0,
        sigma_a in 0f64..50.0,
        theta_i in -FRAC_PI_2..FRAC_PI_2,
        theta_o in -FRAC_PI_2..FRAC_PI_2,
        phi in -PI..PI,
        option in 0usize..246,
    ) {
        let compositions = every_single_lobe_composition(4);
        let composition = compositions[option % compositions.len()];
        let model = ComposedHair::new(&hair(beta_m, beta_n, alpha_deg, eta, sigma_a), composition)
            .expect("valid");
        let s = model.eval(&Query::far(direction(theta_i, phi), direction(theta_o, 0.0)));
        prop_assert!(s.iter().all(|v| v.is_finite() && *v >= 0.0), "{}: {:?}", composition.describe(), s);
    }
}

/// Gerard's table holds Marschner's `N_p` per radian of phi, as Chiang's far field holds its
/// own: at normal incidence and without absorption both R lobes integrate over phi to
/// `1/2 int F dh` and both TT lobes to `1/2 int (1 - F)^2 dh` (Marschner's cubic exit angle
/// and smooth fibre move the energy in phi, not its total), so the tables, baked by
/// different integrators of different models, agree on the totals. Nguyen and Donnelly's
/// table at zero absorption holds the same values as Gerard's.
#[test]
fn the_marschner_tables_carry_the_far_fields_lobe_energies() {
    let eta = RefractiveIndex::new(1.55).unwrap();
    let gerard = gerard_lobe_table(MarschnerTableSize::OFFERED[1], eta).unwrap();
    let far = far_field_lobe_table(LobeTableSize::OFFERED[2], eta).unwrap();
    let nguyen =
        nguyen_donnelly_lobe_table(MarschnerTableSize::OFFERED[1], eta, Absorption::NONE).unwrap();
    let n = 4000;
    let h = PI / n as f64;
    let total = |f: &dyn Fn(f64) -> [f64; 3]| {
        (0..=n).fold([0.0; 3], |acc, k| {
            let w = if k == 0 || k == n { 0.5 * h } else { h };
            let v = f(k as f64 * h);
            core::array::from_fn(|p| acc[p] + w * v[p])
        })
    };
    let g = total(&|phi| gerard.lookup_f64([phi, 0.0]));
    let c = total(&|phi| far.lookup_f64([phi, 0.0, 0.3]));
    for p in 0..2 {
        assert!(
            (g[p] - c[p]).abs() <= 5e-3 * c[p],
            "lobe {p}: {g:?} vs {c:?}"
        );
    }
    // Different axes (phi, theta_d against their cosines): agreement to the lookups' error,
    // away from phi = pi where the cosine axis resolves phi only to 0.18 rad.
    for phi in [0.0, 0.5, 1.7] {
        let a = gerard.lookup_f64([phi, 0.3]);
        let b = nguyen.lookup_f64([phi.cos(), 0.3f64.cos()]);
        assert!(
            (a[0] - b[3]).abs() <= 2e-2 * a[0].max(1e-3),
            "R {a:?} {b:?}"
        );
        assert!(
            (a[1] - b[0]).abs() <= 2e-2 * a[1].max(1e-3),
            "TT {a:?} {b:?}"
        );
    }
}

#[test]
fn the_lobe_table_interpolates_the_far_field_within_its_measured_error() {
    use hairmath::params::RefractiveIndex;
    let eta = RefractiveIndex::new(1.55).expect("eta");
    // Bounds about 1.4 times the worst error of any lobe measured (0.142, 0.060, 0.019).
    for (size, bound) in [
        (LobeTableSize::OFFERED[0], 0.2),
        (LobeTableSize::OFFERED[1], 0.085),
        (LobeTableSize::OFFERED[2], 0.028),
    ] {
        let table = far_field_lobe_table(size, eta).expect("baked");
        let mut worst = [0.0_f64; 3];
        for beta_n in [0.3, 0.45, 0.6] {
            let params = hair(0.3, beta_n, 0.0, 1.55, 0.0);
            let rule = FarFieldRule::gauss_legendre(256).expect("nodes");
            let far = ChiangFarField::<f64>::with_rule(&params, &rule);
            let mut peak = [0.0_f64; 3];
            let mut error = [0.0_f64; 3];
            for i in 0..97 {
                for j in 0..23 {
                    let (phi, theta_o) = (
                        PI * (i as f64 + 0.37) / 97.0,
                        FRAC_PI_2 * (j as f64 + 0.41) / 23.0,
                    );
                    let exact = far.azimuthal(theta_o.sin(), theta_o.cos(), phi).0;
                    let looked: [f64; 3] = table.sample([phi, theta_o, beta_n]);
                    for p in 0..3 {
                        peak[p] = peak[p].max(exact[p][0]);
                        error[p] = error[p].max((looked[p] - exact[p][0]).abs());
                    }
                }
            }
            for p in 0..3 {
                worst[p] = worst[p].max(error[p] / peak[p]);
            }
        }
        eprintln!(
            "{size:?}: worst |lookup - far field| / peak: R {:.3e}, TT {:.3e}, TRT {:.3e}",
            worst[0], worst[1], worst[2]
        );
        assert!(worst.iter().all(|w| *w <= bound), "{worst:?}");
    }
}
