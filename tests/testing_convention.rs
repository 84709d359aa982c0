//! `hairmath::testing::Convention` against the other renderers' own parameterisations, stated
//! here independently from their source (pbrt-v4 `HairBxDF::f`; Mitsuba 3 `hair.cpp`:
//! `sincos_theta`, `azimuthal_angle`, `gamma`, `delta_phi = phi_o - phi_i`): the angles and
//! the offset each renderer computes from the converted directions are hairmath's, and the
//! conversions go both ways.

use hairmath::bcsdf::{Bcsdf, ChiangHair, Query};
use hairmath::glam::DVec3;
use hairmath::params::HairParams;
use hairmath::testing::{Convention, ConventionQuery};
use hairmath::ParamError;
use rand::{Rng, SeedableRng};
use rand_pcg::Pcg64Mcg;
use std::f64::consts::{PI, TAU};

fn unit(rng: &mut Pcg64Mcg) -> DVec3 {
    let z: f64 = rng.random_range(-1.0..=1.0);
    let phi: f64 = rng.random_range(0.0..TAU);
    let r = (1.0 - z * z).max(0.0).sqrt();
    DVec3::new(r * phi.cos(), r * phi.sin(), z)
}

/// Random hairmath queries, then the hard ones: h = +-1 and 0, wi = wo, wi = -wo, grazing.
fn queries() -> Vec<Query<f64>> {
    let mut rng = Pcg64Mcg::seed_from_u64(0xc0);
    let mut out: Vec<Query<f64>> = (0..500)
        .map(|_| {
            let h = rng.random_range(-1.0..=1.0);
            Query::new(unit(&mut rng).into(), unit(&mut rng).into(), h)
        })
        .collect();
    let w = DVec3::new(0.3, -0.4, 0.866).normalize();
    let grazing = DVec3::new(0.999, 0.0447, 0.0).normalize();
    for (wi, wo) in [(w, w), (-w, w), (grazing, w), (w, grazing)] {
        for h in [-1.0, 0.0, 1.0, 0.5] {
            out.push(Query::new(wi.into(), wo.into(), h));
        }
    }
    out
}

/// The difference of two angles wrapped to [-pi, pi].
fn angle_difference(a: f64, b: f64) -> f64 {
    let d = (a - b).rem_euclid(TAU);
    if d > PI {
        d - TAU
    } else {
        d
    }
}

/// Mitsuba 3's `gamma(w)`: the angle of w's projection on XZ from +Z, positive where x < 0.
fn mitsuba_gamma(w: DVec3) -> f64 {
    let projection = (w.x * w.x + w.z * w.z).sqrt();
    if projection == 0.0 {
        return 0.0;
    }
    let gamma = (w.z / projection).clamp(-1.0, 1.0).acos();
    if w.x < 0.0 {
        gamma
    } else {
        -gamma
    }
}

#[test]
fn mitsuba_reads_hairmaths_angles_and_offset_from_the_converted_directions() {
    for query in queries() {
        let m = Convention::Mitsuba.from_hairmath(&query);
        assert_eq!(m.h, None);
        let (camera, light) = (m.wi, m.wo);
        let (wi, wo) = (DVec3::from(query.wi), DVec3::from(query.wo));
        // Mitsuba: sin theta = w.y; hairmath: w.x.
        assert!((light.y - wi.x).abs() < 1e-12 && (camera.y - wo.x).abs() < 1e-12);
        // Mitsuba's h = sin(gamma(si.wi)).
        let h = mitsuba_gamma(camera).sin();
        let perpendicular = (wo.y * wo.y + wo.z * wo.z).sqrt();
        if perpendicular > 1e-9 {
            assert!((h - query.h).abs() < 1e-9, "h {h} against {}", query.h);
        }
        // Mitsuba's delta_phi = phi_o - phi_i (light minus camera) is pbrt's and hairmath's
        // lobe azimuth phi_i - phi_o.
        let mitsuba = light.z.atan2(light.x) - camera.z.atan2(camera.x);
        let hairmath = wi.z.atan2(wi.y) - wo.z.atan2(wo.y);
        let along_tangent = wi.x.abs() > 1.0 - 1e-15 || wo.x.abs() > 1.0 - 1e-15;
        if !along_tangent {
            let d = angle_difference(mitsuba, hairmath);
            assert!(d.abs() < 1e-9, "delta phi {mitsuba} against {hairmath}");
        }
    }
}

#[test]
fn conversions_go_both_ways() {
    let hair = ChiangHair::<f64>::new(&HairParams::default());
    for query in queries() {
        for (convention, _) in Convention::ALL {
            let converted = convention.from_hairmath(&query);
            let back = convention.to_hairmath(&converted).unwrap();
            // The same evaluation: S and h (Mitsuba's rotation about the tangent changes
            // neither).
            assert!((back.h - query.h.clamp(-1.0, 1.0)).abs() < 1e-9 || wo_along_tangent(&query));
            let (s, t) = (hair.eval(&query), hair.eval(&back));
            let scale = s.iter().chain(&t).fold(1e-300_f64, |m, v| m.max(v.abs()));
            for (a, b) in s.iter().zip(t) {
                assert!(
                    (a - b).abs() <= 1e-9 * scale || wo_along_tangent(&query),
                    "{convention:?}"
                );
            }
            // And back again: the convention's query is a fixed point.
            let again = convention.from_hairmath(&back);
            for (a, b) in [(again.wi, converted.wi), (again.wo, converted.wo)] {
                assert!((a - b).length() < 1e-9, "{convention:?}: {a} against {b}");
            }
        }
    }
}

fn wo_along_tangent(query: &Query<f64>) -> bool {
    query.wo.x.abs() > 1.0 - 1e-15
}

#[test]
fn pbrt_divides_by_the_cosine_to_its_normal() {
    let hair = ChiangHair::<f64>::new(&HairParams::default());
    for query in queries() {
        let s = hair.eval(&query);
        let f = Convention::Pbrt.f_of_s(s, &query);
        let cos = query.wi.z.abs();
        for (fc, sc) in f.iter().zip(s) {
            let expected = if cos > 0.0 { sc / cos } else { sc };
            assert!((fc - expected).abs() <= 1e-15 * expected.abs());
        }
        let back = Convention::Pbrt.s_of_f(f, &query);
        for (a, b) in back.iter().zip(s) {
            assert!((a - b).abs() <= 1e-14 * b.abs());
        }
        assert_eq!(Convention::Mitsuba.f_of_s(s, &query), s);
        assert_eq!(Convention::Hairmath.f_of_s(s, &query), s);
    }
}

#[test]
fn bad_queries_are_typed_errors() {
    let w = DVec3::new(0.0, 0.6, 0.8);
    let missing = ConventionQuery {
        wi: w,
        wo: w,
        h: None,
    };
    for convention in [Convention::Hairmath, Convention::Pbrt] {
        let error = convention.to_hairmath(&missing).unwrap_err();
        assert_eq!(error, ParamError::Missing { name: "h" });
    }
    let with_h = ConventionQuery {
        h: Some(0.5),
        ..missing
    };
    let error = Convention::Mitsuba.to_hairmath(&with_h).unwrap_err();
    assert!(error.to_string().contains("implies h"), "{error}");
    let long = ConventionQuery {
        wi: w * 2.0,
        ..with_h
    };
    let error = Convention::Pbrt.to_hairmath(&long).unwrap_err();
    assert!(matches!(error, ParamError::NotUnit { .. }), "{error}");
    for (convention, name) in Convention::ALL {
        assert_eq!(Convention::from_name(name), Some(convention));
        assert_eq!(convention.name(), name);
    }
    assert_eq!(Convention::from_name("cycles"), None);
}
