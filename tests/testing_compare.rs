//! `hairmath::testing::compare` catches real mistakes and passes correct implementations:
//! hairmath's own models pass (f64 exactly, f32 within the crate's stated f32 bound), and
//! deliberately broken variants fail with a report naming the worst inputs: a missing cosine
//! factor, pbrt's `f` (divided by the cosine) passed as S, the cuticle tilt with the wrong sign
//! (what applying it to the other direction does to the lobe), and a NaN.

use hairmath::bcsdf::{Bcsdf, ChiangFarField, ChiangHair, FarFieldRule, Model, Query};
use hairmath::geometry::V3;
use hairmath::params::{CuticleTilt, HairParams};
use hairmath::testing::{compare_with_model, hard_queries, test_queries};

fn reference() -> ChiangHair<f64> {
    ChiangHair::new(&HairParams::default())
}

#[test]
fn the_queries_are_the_hard_cases_then_quasi_random_ones() {
    let hard = hard_queries();
    let all = test_queries(1000);
    assert_eq!(all.len(), hard.len() + 1000);
    assert_eq!(&all[..hard.len()], &hard[..]);
    for q in &all {
        for w in [q.wi, q.wo] {
            assert!((w.dot(w).sqrt() - 1.0).abs() < 1e-12);
        }
        assert!((-1.0..=1.0).contains(&q.h));
    }
    // The hard cases include wi = wo, wi = -wo, both along the tangent, and h = +-1.
    let has = |f: &dyn Fn(&Query<f64>) -> bool| hard.iter().any(f);
    let eq = |a: V3<f64>, b: V3<f64>| (a - b).dot(a - b) < 1e-24;
    assert!(has(&|q| eq(q.wi, q.wo)));
    assert!(has(&|q| eq(q.wi, q.wo.scale(-1.0))));
    assert!(has(&|q| q.wi.x == 1.0 && q.wo.x == -1.0));
    assert!(has(&|q| q.h == 1.0) && has(&|q| q.h == -1.0));
}

#[test]
fn correct_implementations_pass() {
    let hair = reference();
    let queries = test_queries(4000);
    let same = compare_with_model(&hair, &queries, |q| hair.eval(q), 5);
    assert_eq!(same.max_rel_error, 0.0);
    assert!(same.passes(0.0));
    // The model in single precision, as a renderer would write it in f32.
    let single = hair.instantiate::<f32>();
    let f32_values = |q: &Query<f64>| {
        let v = |w: V3<f64>| V3::new(w.x as f32, w.y as f32, w.z as f32);
        single
            .eval(&Query::new(v(q.wi), v(q.wo), q.h as f32))
            .map(f64::from)
    };
    let report = compare_with_model(&hair, &queries, f32_values, 5);
    println!("f32 Chiang: {report}");
    assert!(report.passes(3e-4), "{report}");
}

#[test]
fn a_missing_or_extra_cosine_fails_with_its_worst_inputs() {
    let hair = reference();
    let queries = test_queries(4000);
    let cos_i = |q: &Query<f64>| (1.0 - q.wi.x * q.wi.x).max(0.0).sqrt();
    let missing = compare_with_model(&hair, &queries, |q| hair.eval(q).map(|s| s * cos_i(q)), 3);
    println!("S times cos theta_i: {missing}");
    assert!(
        !missing.passes(1e-2) && missing.max_rel_error > 0.5,
        "{missing}"
    );
    // The worst rows are grazing lights, where the cosine is smallest.
    assert!(missing.worst_rows[0].query.wi.x.abs() > 0.99, "{missing}");
    let pbrt_f = compare_with_model(
        &hair,
        &queries,
        |q| {
            let cos = q.wi.z.abs();
            hair.eval(q).map(|s| if cos > 0.0 { s / cos } else { s })
        },
        3,
    );
    println!("pbrt's f as S: {pbrt_f}");
    assert!(!pbrt_f.passes(1e-2), "{pbrt_f}");
    assert!(
        pbrt_f.to_string().contains("row "),
        "the report names rows: {pbrt_f}"
    );
}

#[test]
fn a_tilt_of_the_wrong_sign_fails() {
    let hair = reference();
    let flipped = HairParams {
        alpha: CuticleTilt::from_degrees(-2.0).unwrap(),
        ..HairParams::default()
    };
    let wrong = ChiangHair::<f64>::new(&flipped);
    let report = compare_with_model(&hair, &test_queries(4000), |q| wrong.eval(q), 3);
    println!("tilt -2 degrees instead of 2: {report}");
    assert!(
        !report.passes(1e-2) && report.max_rel_error > 0.1,
        "{report}"
    );
}

#[test]
fn a_far_field_with_few_nodes_shows_its_error_and_nan_is_infinite() {
    // A legitimate approximation: the far field with 8 nodes against the 64-node one, whose
    // error the report measures (no tolerance is claimed here), and a NaN is never hidden.
    let params = HairParams::default();
    let fine =
        ChiangFarField::<f64>::with_rule(&params, &FarFieldRule::gauss_legendre(64).unwrap());
    let coarse =
        ChiangFarField::<f64>::with_rule(&params, &FarFieldRule::gauss_legendre(8).unwrap());
    let queries = test_queries(1000);
    let report = compare_with_model(&fine, &queries, |q| coarse.eval(q), 1);
    println!("far field 8 against 64 nodes: {report}");
    assert!(report.max_rel_error > 0.0 && report.max_rel_error.is_finite());
    let nan = compare_with_model(
        &fine,
        &queries,
        |q| {
            if q.h == 1.0 {
                [f64::NAN; 3]
            } else {
                fine.eval(q)
            }
        },
        2,
    );
    assert_eq!(nan.max_rel_error, f64::INFINITY);
    assert_eq!(nan.worst_rows[0].query.h, 1.0);
    assert!(nan.mean_rel_error.is_infinite());
}
