//! The kit's proptest strategies give valid values over their documented ranges and visit
//! every hard case of `docs/ARCHITECTURE.md` within a few hundred draws.

use hairmath::absorption::Absorption;
use hairmath::geometry::V3;
use hairmath::testing::strategies::{
    hair_params, melanin, query, random_numbers, GRAZING_SIN_THETA,
};
use proptest::strategy::{Strategy, ValueTree};
use proptest::test_runner::{Config, RngAlgorithm, TestRng, TestRunner};

/// `count` values of `strategy` from a fixed seed.
fn draw<S: Strategy>(strategy: S, count: usize) -> Vec<S::Value> {
    let rng = TestRng::from_seed(RngAlgorithm::ChaCha, &[3; 32]);
    let mut runner = TestRunner::new_with_rng(Config::default(), rng);
    (0..count)
        .map(|_| strategy.new_tree(&mut runner).unwrap().current())
        .collect()
}

#[test]
fn parameters_are_in_range_and_include_the_ends() {
    let params = draw(hair_params(), 600);
    for p in &params {
        assert!((0.01..=1.0).contains(&p.beta_m.get()), "{p:?}");
        assert!((0.01..=1.0).contains(&p.beta_n.get()), "{p:?}");
        assert!(p.alpha.get().abs() <= 10f64.to_radians() + 1e-15, "{p:?}");
        assert!((1.001..=3.0).contains(&p.eta.get()), "{p:?}");
        assert!(
            p.sigma_a.rgb().iter().all(|s| (0.0..=20.0).contains(s)),
            "{p:?}"
        );
    }
    let has = |f: &dyn Fn(&hairmath::params::HairParams) -> bool| params.iter().any(f);
    assert!(has(&|p| p.beta_m.get() == 0.01) && has(&|p| p.beta_m.get() == 1.0));
    assert!(has(&|p| p.beta_n.get() == 0.01) && has(&|p| p.beta_n.get() == 1.0));
    assert!(has(&|p| p.alpha.get() == 0.0));
    assert!(has(&|p| (p.alpha.get().to_degrees() + 10.0).abs() < 1e-12));
    assert!(has(&|p| p.eta.get() == 1.001) && has(&|p| p.eta.get() == 3.0));
    assert!(has(&|p| p.sigma_a == Absorption::NONE));
    assert!(has(&|p| p.sigma_a.rgb() == [20.0; 3]));
}

#[test]
fn queries_are_unit_and_include_the_hard_cases() {
    let queries = draw(query(), 600);
    let unit = |w: V3<f64>| (w.dot(w).sqrt() - 1.0).abs() < 1e-12;
    for q in &queries {
        assert!(
            unit(q.wi) && unit(q.wo) && (-1.0..=1.0).contains(&q.h),
            "{q:?}"
        );
    }
    let has = |f: &dyn Fn(&hairmath::bcsdf::Query<f64>) -> bool| queries.iter().any(f);
    let same = |a: V3<f64>, b: V3<f64>| (a - b).dot(a - b) < 1e-24;
    assert!(has(&|q| same(q.wi, q.wo)), "wi = wo");
    assert!(has(&|q| same(q.wi, q.wo.scale(-1.0))), "wi = -wo");
    assert!(has(&|q| q.wi.x.abs() == 1.0), "along the tangent");
    assert!(has(&|q| q.wo.x == GRAZING_SIN_THETA), "grazing");
    assert!(has(&|q| q.h == 1.0) && has(&|q| q.h == -1.0) && has(&|q| q.h == 0.0));
    // phi = 0 and pi between two directions off the tangent and not equal or opposite.
    let azimuth = |w: V3<f64>| w.z.atan2(w.y);
    let general = |q: &hairmath::bcsdf::Query<f64>| {
        q.wi.x.abs() < 0.99 && q.wo.x.abs() < 0.99 && (q.wi.x - q.wo.x).abs() > 1e-3
    };
    let relative = |q: &hairmath::bcsdf::Query<f64>| {
        let d = azimuth(q.wi) - azimuth(q.wo);
        d.sin().atan2(d.cos())
    };
    assert!(has(&|q| general(q) && relative(q).abs() < 1e-12), "phi = 0");
    assert!(has(
        &|q| general(q) && (relative(q).abs() - std::f64::consts::PI).abs() < 1e-12
    ));
}

#[test]
fn random_numbers_are_in_the_unit_interval_and_include_its_ends() {
    let numbers = draw(random_numbers(), 400);
    let all: Vec<f64> = numbers
        .iter()
        .flat_map(|u| [u.lobe, u.longitudinal, u.cone, u.offset])
        .collect();
    assert!(all.iter().all(|u| (0.0..1.0).contains(u)));
    assert!(all.contains(&0.0));
    assert!(all.contains(&(1.0 - f64::EPSILON / 2.0)));
}

#[test]
fn melanin_is_in_hairs_range_and_includes_its_ends() {
    let pairs = draw(melanin(), 300);
    let all: Vec<f64> = pairs.iter().flat_map(|&(e, p)| [e, p]).collect();
    assert!(all.iter().all(|c| (0.0..=8.0).contains(c)));
    assert!(pairs.iter().any(|&(e, _)| e == 0.0) && pairs.iter().any(|&(e, _)| e == 8.0));
    assert!(pairs.iter().any(|&(_, p)| p == 0.0) && pairs.iter().any(|&(_, p)| p == 8.0));
}
