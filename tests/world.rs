//! The world-space API (`hairmath::world`): every registered model evaluated from world-space
//! glam vectors equals the model in its local frame, whatever rotation carries one to the
//! other (the models depend on the azimuths only through their difference), including
//! tangents almost parallel to a direction and tangents across the frame's branch plane z = 0;
//! sampling and pdf round trips; the SIMD batch from glam slices; typed errors.

use hairmath::bcsdf::{
    BatchError, BatchReal, Bcsdf, ChiangHair, HostBatch, InstructionSet, Model, Query,
    RandomNumbers, SampledBcsdf,
};
use hairmath::geometry::V3;
use hairmath::glam::{DQuat, DVec3, Vec3};
use hairmath::params::HairParams;
use hairmath::registry::MODELS;
use hairmath::world::{
    eval_batch_world, pdf_batch_world, world_query, WorldBcsdf, WorldSampledBcsdf,
};
use hairmath::ParamError;
use proptest::prelude::*;
use rand::{Rng, SeedableRng};
use rand_pcg::Pcg64Mcg;

/// A uniformly random unit vector.
fn unit(rng: &mut Pcg64Mcg) -> DVec3 {
    let z: f64 = rng.random_range(-1.0..=1.0);
    let phi: f64 = rng.random_range(0.0..core::f64::consts::TAU);
    let r = (1.0 - z * z).max(0.0).sqrt();
    DVec3::new(r * phi.cos(), r * phi.sin(), z)
}

/// A local configuration (tangent +X) and a rotation taking it to world space.
struct Case {
    rotation: DQuat,
    wi: DVec3,
    wo: DVec3,
    h: f64,
}

impl Case {
    fn world(&self) -> [DVec3; 3] {
        [DVec3::X, self.wi, self.wo].map(|v| self.rotation * v)
    }
}

/// Random rotations and local directions, then the hard ones: wi within 1e-6 and 1e-3 of the
/// tangent (either way), wi = wo, wi = -wo, grazing wo, and rotations whose tangent lies on or
/// next to the plane z = 0 where Duff et al.'s frame switches branch.
fn cases(n: usize) -> Vec<Case> {
    let mut rng = Pcg64Mcg::seed_from_u64(0x3071d);
    let mut cases = Vec::new();
    for _ in 0..n {
        let rotation = DQuat::from_axis_angle(unit(&mut rng), rng.random_range(0.0..6.3));
        let h = rng.random_range(-1.0..=1.0);
        cases.push(Case {
            rotation,
            wi: unit(&mut rng),
            wo: unit(&mut rng),
            h,
        });
    }
    let near_tangent = |e: f64, s: f64| DVec3::new(s * (1.0 - e * e).sqrt(), e, 0.0);
    let locals = [
        (
            near_tangent(1e-6, 1.0),
            DVec3::new(0.3, 0.8, 0.52).normalize(),
        ),
        (
            near_tangent(1e-3, -1.0),
            DVec3::new(-0.2, -0.6, 0.77).normalize(),
        ),
        (
            DVec3::new(0.1, 0.7, 0.7).normalize(),
            DVec3::new(0.1, 0.7, 0.7).normalize(),
        ),
        (
            DVec3::new(0.1, 0.7, 0.7).normalize(),
            DVec3::new(-0.1, -0.7, -0.7).normalize(),
        ),
        (
            DVec3::new(0.5, 0.5, 0.7).normalize(),
            DVec3::new(0.999, 0.0447, 0.0).normalize(),
        ),
    ];
    // Tangents in the plane z = 0 and just either side of it.
    let tangents = [
        DVec3::new(1.0, 0.0, 0.0),
        DVec3::new(0.0, 1.0, 0.0),
        DVec3::new(0.6, 0.8, 1e-12),
        DVec3::new(0.6, 0.8, -1e-12),
        DVec3::new(0.0, 0.0, -1.0),
        DVec3::new(0.0, 0.0, 1.0),
    ];
    for (k, (wi, wo)) in locals.into_iter().enumerate() {
        for tangent in tangents {
            let rotation = DQuat::from_rotation_arc(DVec3::X, tangent.normalize());
            let h = [0.0, 0.9, -1.0, 1.0, 0.3][k];
            cases.push(Case {
                rotation,
                wi,
                wo,
                h,
            });
        }
    }
    cases
}

/// Largest |a - b| relative to max(|a|, |b|, floor) over the channels.
fn relative(a: [f64; 3], b: [f64; 3], floor: f64) -> f64 {
    a.iter()
        .zip(&b)
        .map(|(x, y)| (x - y).abs() / x.abs().max(y.abs()).max(floor))
        .fold(0.0, f64::max)
}

#[test]
fn every_model_in_world_space_is_the_model_in_its_local_frame() {
    let cases = cases(400);
    for entry in MODELS {
        let model = (entry.build)(&entry.example_values()).unwrap();
        let mut worst = 0.0_f64;
        for case in &cases {
            let local = model.eval(&Query::new(case.wi.into(), case.wo.into(), case.h));
            let [tangent, wi, wo] = case.world();
            let world = model.eval_world(tangent, wi, wo, case.h);
            let floor = 1e-9 * local.iter().fold(1e-300_f64, |m, v| m.max(v.abs()));
            worst = worst.max(relative(world, local, floor));
        }
        // The rotation and the frame round at 1e-16. Most models then differ by 1e-9 or
        // less; Karis' azimuthal terms take a square root of 1 + cos(phi) (as UE ships them),
        // which turns a rounding of 1e-16 at wi = -wo (phi = pi) into one of 1e-8: measured
        // 7.8e-8 there, for the rotation's rounding alone.
        assert!(
            worst < 2e-7,
            "{}: worst relative difference {worst:e}",
            entry.name
        );
    }
}

/// Whether both directions are more than 1e-3 rad from the tangent. Closer, the azimuth of a
/// direction given in `f32` world coordinates is determined only to about 6e-8 / angle (their
/// rounding, before any frame is built), and S depends on it: those cases are checked in `f64`
/// (`every_model_in_world_space_is_the_model_in_its_local_frame`).
fn well_conditioned_in_f32(case: &Case) -> bool {
    let angle = |w: DVec3| w.x.clamp(-1.0, 1.0).abs().acos();
    angle(case.wi) > 1e-3 && angle(case.wo) > 1e-3
}

#[test]
fn the_f32_glam_path_agrees_with_f64() {
    let hair = ChiangHair::new(&HairParams::default());
    let single = hair.instantiate::<f32>();
    let mut worst = 0.0_f64;
    let mut peak = 0.0_f64;
    let mut pairs = Vec::new();
    for case in cases(2000).iter().filter(|c| well_conditioned_in_f32(c)) {
        let [t, wi, wo] = case.world();
        let reference = hair.eval_world(t, wi, wo, case.h);
        let f = |v: DVec3| v.as_vec3();
        let value = single.eval_world(f(t), f(wi), f(wo), case.h as f32);
        peak = reference.iter().fold(peak, |m, v| m.max(*v));
        pairs.push((reference, value.map(f64::from)));
    }
    for (reference, value) in pairs {
        for (r, v) in reference.iter().zip(value) {
            worst = worst.max((r - v).abs() / (r.abs() + 1e-6 * peak));
        }
    }
    // The crate's f32 bound against f64 (relative to value + 1e-6 of the peak) is 3e-4; the
    // world path adds the frame's rounding in f32.
    assert!(worst < 1e-3, "f32 world path: worst {worst:e}");
}

#[test]
fn sampling_in_world_space_rotates_the_local_sample() {
    let hair = ChiangHair::new(&HairParams::default());
    let mut rng = Pcg64Mcg::seed_from_u64(7);
    for case in cases(300) {
        let [tangent, _, wo] = case.world();
        let u = RandomNumbers {
            lobe: rng.random_range(0.0..1.0),
            longitudinal: rng.random_range(0.0..1.0),
            cone: rng.random_range(0.0..1.0),
            offset: rng.random_range(0.0..1.0),
        };
        let sample = hair.sample_world(tangent, wo, case.h, u);
        let local = hair.sample(case.wo.into(), case.h, u);
        let expected = case.rotation * DVec3::from(local.wi);
        assert!(
            (sample.wi - expected).length() < 1e-9,
            "{:?} against {expected:?}",
            sample.wi
        );
        assert!((sample.wi.length() - 1.0).abs() < 1e-12);
        let pdf = hair.pdf_world(tangent, sample.wi, wo, case.h);
        assert!(
            (pdf - sample.pdf).abs() <= 1e-6 * sample.pdf.max(1e-12),
            "{pdf} vs {}",
            sample.pdf
        );
        let weight = sample.weight();
        for (w, v) in weight.iter().zip(sample.value) {
            if sample.pdf > 0.0 {
                assert!((w - v / sample.pdf).abs() <= 1e-12 * w.abs().max(1.0));
            } else {
                assert_eq!(*w, 0.0);
            }
        }
    }
}

/// Batch inputs in world space: the well-conditioned ones of [`cases`] (about 700: two
/// blocks of 256 and a tail).
struct WorldBatch {
    tangent: Vec<Vec3>,
    wi: Vec<Vec3>,
    wo: Vec<Vec3>,
    h: Vec<f32>,
    cases: Vec<Case>,
}

fn batch_inputs() -> WorldBatch {
    let cases: Vec<Case> = cases(680)
        .into_iter()
        .filter(well_conditioned_in_f32)
        .collect();
    let world: Vec<[DVec3; 3]> = cases.iter().map(Case::world).collect();
    WorldBatch {
        // Tangents of any length.
        tangent: world.iter().map(|w| (w[0] * 1e3).as_vec3()).collect(),
        wi: world.iter().map(|w| w[1].as_vec3()).collect(),
        wo: world.iter().map(|w| w[2].as_vec3()).collect(),
        h: cases.iter().map(|c| c.h as f32).collect(),
        cases,
    }
}

#[test]
fn the_world_batch_agrees_with_the_f64_model() {
    let hair = ChiangHair::new(&HairParams::default());
    let lanes = hair.instantiate::<BatchReal>();
    let WorldBatch {
        tangent,
        wi,
        wo,
        h,
        cases,
    } = batch_inputs();
    let mut out = vec![[0.0_f32; 3]; wi.len()];
    eval_batch_world(&lanes, &tangent, &wi, &wo, &h, &mut out).unwrap();
    let reference: Vec<[f64; 3]> = cases
        .iter()
        .map(|c| hair.eval(&Query::new(c.wi.into(), c.wo.into(), c.h)))
        .collect();
    let peak = reference.iter().flatten().fold(0.0_f64, |m, v| m.max(*v));
    let worst_of = |out: &[[f32; 3]]| {
        let mut worst = 0.0_f64;
        for (r, v) in reference.iter().zip(out) {
            for (r, v) in r.iter().zip(v) {
                worst = worst.max((r - f64::from(*v)).abs() / (r.abs() + 1e-6 * peak));
            }
        }
        worst
    };
    let worst = worst_of(&out);
    assert!(worst < 1e-3, "world batch: worst {worst:e}");
    // The same on every instruction set this CPU runs (HostBatch::eval_world).
    for set in InstructionSet::ALL.into_iter().filter(|s| s.is_supported()) {
        let mut host = vec![[f32::NAN; 3]; wi.len()];
        HostBatch::on(set, &hair)
            .eval_world(&tangent, &wi, &wo, &h, &mut host)
            .unwrap();
        let worst = worst_of(&host);
        assert!(worst < 1e-3, "world batch on {set:?}: worst {worst:e}");
    }
}

#[test]
fn the_world_pdf_batch_agrees_with_the_f64_pdf() {
    let hair = ChiangHair::new(&HairParams::default());
    let lanes = hair.instantiate::<BatchReal>();
    let WorldBatch {
        tangent,
        wi,
        wo,
        h,
        cases,
    } = batch_inputs();
    let mut out = vec![0.0_f32; wi.len()];
    pdf_batch_world(&lanes, &tangent, &wi, &wo, &h, &mut out).unwrap();
    let reference: Vec<f64> = cases
        .iter()
        .map(|c| hair.pdf(&Query::new(c.wi.into(), c.wo.into(), c.h)))
        .collect();
    let peak = reference.iter().fold(0.0_f64, |m, v| m.max(*v));
    let worst = reference
        .iter()
        .zip(&out)
        .map(|(r, v)| (r - f64::from(*v)).abs() / (r.abs() + 1e-6 * peak))
        .fold(0.0, f64::max);
    assert!(worst < 1e-3, "world pdf batch: worst {worst:e}");
    let mut bad = tangent.clone();
    bad[2] = Vec3::ZERO;
    let good = out.clone();
    let mut out = vec![7.0_f32; wi.len()];
    let error = pdf_batch_world(&lanes, &bad, &wi, &wo, &h, &mut out).unwrap_err();
    assert!(
        matches!(error, BatchError::Tangent { index: 2, .. }),
        "{error}"
    );
    // The samples before the bad one are evaluated, none from it on.
    assert_eq!(out[..2], good[..2]);
    assert!(out[2..].iter().all(|&p| p == 7.0));
}

/// A bad sample is named, the samples before it are evaluated and nothing from it on is
/// written, on the build's lanes and the host's.
#[test]
fn the_world_batch_names_the_bad_sample_and_evaluates_only_those_before_it() {
    let hair = ChiangHair::new(&HairParams::default()).instantiate::<BatchReal>();
    let WorldBatch {
        tangent, wi, wo, h, ..
    } = batch_inputs();
    let untouched = vec![[7.0_f32; 3]; wi.len()];
    let host = HostBatch::new(&ChiangHair::new(&HairParams::default()));
    let mut good = untouched.clone();
    eval_batch_world(&hair, &tangent, &wi, &wo, &h, &mut good).unwrap();
    let mut good_on_host = untouched.clone();
    host.eval_world(&tangent, &wi, &wo, &h, &mut good_on_host)
        .unwrap();
    let run = |tangent: &[Vec3], wi: &[Vec3], h: &[f32]| {
        let mut out = untouched.clone();
        let result = eval_batch_world(&hair, tangent, wi, &wo, h, &mut out);
        let mut on_host_out = untouched.clone();
        let on_host = host.eval_world(tangent, wi, &wo, h, &mut on_host_out);
        assert_eq!(format!("{on_host:?}"), format!("{result:?}"));
        let error = result.unwrap_err();
        let first = error.sample_index().unwrap_or(0);
        assert_eq!(out[..first], good[..first]);
        assert_eq!(on_host_out[..first], good_on_host[..first]);
        assert_eq!(out[first..], untouched[first..]);
        assert_eq!(on_host_out[first..], untouched[first..]);
        error
    };
    let mut bad = tangent.clone();
    bad[600] = Vec3::ZERO;
    assert!(matches!(
        run(&bad, &wi, &h),
        BatchError::Tangent { index: 600, .. }
    ));
    bad[600] = Vec3::new(f32::NAN, 1.0, 0.0);
    assert!(matches!(
        run(&bad, &wi, &h),
        BatchError::Tangent { index: 600, .. }
    ));
    let mut bad = wi.clone();
    bad[513] = Vec3::new(0.0, 2.0, 0.0);
    // With a bad tangent after it in the same block, the direction is still the first.
    let mut bad_tangent = tangent.clone();
    bad_tangent[600] = Vec3::ZERO;
    for tangent in [&tangent, &bad_tangent] {
        let error = run(tangent, &bad, &h);
        assert!(
            matches!(
                error,
                BatchError::Direction {
                    index: 513,
                    name: "wi",
                    ..
                }
            ),
            "{error}"
        );
    }
    let mut bad = h.clone();
    bad[300] = f32::NAN;
    assert!(matches!(
        run(&tangent, &wi, &bad),
        BatchError::Offset { index: 300, .. }
    ));
    let error = run(&tangent[1..], &wi, &h);
    assert_eq!(
        error,
        BatchError::TangentLength {
            tangent: wi.len() - 1,
            samples: wi.len()
        }
    );
    assert!(wi.len() > 2 * 256, "three blocks: {}", wi.len());
    assert!(matches!(run(&tangent, &wi, &h[1..]), BatchError::Length(_)));
}

#[test]
fn world_query_checks_the_tangent_and_the_directions() {
    let wi = DVec3::new(0.0, 0.6, 0.8);
    let wo = DVec3::new(0.0, 1.0, 0.0);
    for bad in [
        DVec3::ZERO,
        DVec3::new(f64::NAN, 0.0, 1.0),
        DVec3::new(f64::INFINITY, 0.0, 0.0),
    ] {
        let error = world_query(bad, wi, wo, 0.0).unwrap_err();
        assert!(
            matches!(
                error,
                ParamError::BadVector {
                    name: "tangent",
                    ..
                }
            ),
            "{error}"
        );
    }
    // Tangents of any finite length have the same frame.
    let base = world_query(DVec3::new(0.3, -0.2, 0.9), wi, wo, 0.1).unwrap();
    for scale in [1e-300, 1e300] {
        let query = world_query(DVec3::new(0.3, -0.2, 0.9) * scale, wi, wo, 0.1).unwrap();
        for (a, b) in [(query.wi, base.wi), (query.wo, base.wo)] {
            assert!((DVec3::from(a) - DVec3::from(b)).length() < 1e-15);
        }
    }
    let error = world_query(DVec3::X, wi * 2.0, wo, 0.0).unwrap_err();
    assert!(
        matches!(error, ParamError::NotUnit { name: "wi", .. }),
        "{error}"
    );
    let error = world_query(DVec3::X, wi, wo, 1.5).unwrap_err();
    assert!(matches!(error, ParamError::OutOfRange { .. }), "{error}");
}

#[test]
fn glam_and_v3_convert_both_ways() {
    let v = DVec3::new(1.5, -2.0, 3.25);
    assert_eq!(DVec3::from(V3::from(v)), v);
    let w = Vec3::new(1.5, -2.0, 3.25);
    assert_eq!(Vec3::from(V3::from(w)), w);
    let v3: V3<f64> = v.into();
    assert_eq!((v3.x, v3.y, v3.z), (1.5, -2.0, 3.25));
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(256))]

    /// Over the whole domain (any non-zero tangent, any unit directions, any h), world-space
    /// evaluation is finite and equals the local model.
    #[test]
    fn world_evaluation_is_finite_and_local(
        axis in (-1.0..1.0f64, -1.0..1.0f64, -1.0..1.0f64),
        angle in 0.0..6.3f64,
        wi in (-1.0..1.0f64, -1.0..1.0f64, -1.0..1.0f64),
        wo in (-1.0..1.0f64, -1.0..1.0f64, -1.0..1.0f64),
        h in -1.0..=1.0f64,
    ) {
        let v = |(x, y, z): (f64, f64, f64)| DVec3::new(x, y, z);
        prop_assume!(v(axis).length() > 1e-3 && v(wi).length() > 1e-3 && v(wo).length() > 1e-3);
        let rotation = DQuat::from_axis_angle(v(axis).normalize(), angle);
        let (wi, wo) = (v(wi).normalize(), v(wo).normalize());
        let hair = ChiangHair::new(&HairParams::default());
        let local = hair.eval(&Query::new(wi.into(), wo.into(), h));
        let world = hair.eval_world(rotation * DVec3::X, rotation * wi, rotation * wo, h);
        let floor = 1e-9 * local.iter().fold(1e-300_f64, |m, x| m.max(*x));
        prop_assert!(world.iter().all(|x| x.is_finite()));
        prop_assert!(relative(world, local, floor) < 1e-8, "{world:?} vs {local:?}");
    }
}
