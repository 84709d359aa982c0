#![cfg(feature = "strands")]
//! The transmittance bakers against closed forms and against each other:
//!
//! - the crossing test of one cylinder against sampling points along the ray, and the
//!   hierarchy's transmittance against the product over every cylinder (proptest);
//! - an isolated vertex sees `V = 1`: only `Y_00`, `sqrt(4 pi)`, exactly, from both bakers;
//! - a vertex in the plane of `k` parallel strands, each hiding the same directions, sees
//!   `V = (1 - opacity)^k` there and 1 elsewhere: the exact baker converges to the projection of
//!   that indicator, computed here by Gauss-Legendre quadrature in coordinates fitted to the
//!   region (its own convergence checked);
//! - the fast baker's error against the exact one on a groom it was not tuned on holds the
//!   figure the README states;
//! - bakes do not depend on the thread count; invalid settings give a `ParamError`.

use core::f64::consts::PI;
use glam::{DMat3, DVec3, Vec3};
use hairmath::quadrature::gauss_legendre;
use hairmath::sh::{eval_sh_f64, rotate_low_order};
use hairmath::strands::groom::{groom, GroomKind, GroomSettings};
use hairmath::strands::occluders::{Cylinder, Occluders, Opacity};
use hairmath::strands::transmittance::{
    bake, compare, fibonacci_directions, BakeSettings, Baker, FastSettings, Transmittance,
};
use hairmath::strands::{PointAttribute, SegmentCounts, Strands};
use hairmath::ParamError;
use proptest::prelude::*;
use rand::{Rng, SeedableRng};
use rand_pcg::Pcg64Mcg;

fn quiet(_: usize, _: usize) {}

fn bake_all(
    strands: &Strands,
    vertices: core::ops::Range<usize>,
    settings: &BakeSettings,
) -> Transmittance {
    bake(strands, vertices, settings, &quiet).expect("valid settings")
}

fn exact(directions: usize, opacity: f32) -> BakeSettings {
    BakeSettings {
        lmax: 2,
        opacity: Opacity::Uniform(opacity),
        baker: Baker::Exact { directions },
    }
}

/// Strands of one segment each, from `(a, b)` pairs, with a thickness per strand.
fn segments(pairs: &[(Vec3, Vec3, f32)]) -> Strands {
    let points = pairs.iter().flat_map(|&(a, b, _)| [a, b]).collect();
    let thickness = pairs.iter().flat_map(|&(_, _, t)| [t, t]).collect();
    Strands::new(
        SegmentCounts::Uniform {
            strands: pairs.len(),
            segments: 1,
        },
        points,
        PointAttribute::PerPoint(thickness),
        PointAttribute::Uniform(0.0),
        PointAttribute::Uniform(Vec3::ONE),
    )
    .unwrap()
}

#[test]
fn an_isolated_vertex_sees_no_occlusion() {
    let strands = segments(&[(Vec3::ZERO, Vec3::new(0.0, -0.1, 0.0), 0.01)]);
    let expected = [
        (4.0 * PI).sqrt() as f32,
        0.0,
        0.0,
        0.0,
        0.0,
        0.0,
        0.0,
        0.0,
        0.0,
    ];
    for baker in [
        Baker::Exact { directions: 4096 },
        Baker::Fast(FastSettings::default()),
    ] {
        let settings = BakeSettings {
            lmax: 2,
            opacity: Opacity::Uniform(1.0),
            baker,
        };
        let baked = bake_all(&strands, 0..2, &settings);
        assert_eq!(baked.vertex(0), expected, "{baker:?}");
        assert_eq!(baked.vertex(1), expected, "{baker:?}");
    }
}

/// The sheet: `k` strands along X in the plane y = 0 at depths `d_j = 0.5 * 1.5^j` in front of
/// the vertex at the origin, each of radius `C d_j` and half-length `L d_j`, so that each hides
/// the same directions (the configuration is invariant under scaling from the origin); turned
/// by `rotation`.
const C: f64 = 0.1;
const L: f64 = 1.0;

fn sheet(k: usize, rotation: DMat3) -> Strands {
    let turn = |p: DVec3| (rotation * p).as_vec3();
    let mut pairs = vec![(Vec3::ZERO, turn(DVec3::new(0.0, -0.01, 0.0)), 0.001)];
    for j in 0..k {
        let d = 0.5 * 1.5f64.powi(j as i32);
        let (half, radius) = (L * d, C * d);
        let (a, b) = (DVec3::new(-half, 0.0, d), DVec3::new(half, 0.0, d));
        pairs.push((turn(a), turn(b), (2.0 * radius) as f32));
    }
    segments(&pairs)
}

/// `int_R Y_lm dw` over the directions `R` the unturned sheet hides, with `n x n`
/// Gauss-Legendre nodes. In `w = (sin b, cos b sin p, cos b cos p)` (`dw = cos b db dp`) a ray
/// crosses a strand iff `|sin p| < C`, `cos p > 0` and `|tan b| < L / (cos p - sqrt(C^2 -
/// sin^2 p))`; with `sin p = C sin u` the integrand is smooth in `u`.
fn hidden_projection(n: usize) -> [f64; 9] {
    let nodes = gauss_legendre(n);
    let mut out = [0.0; 9];
    for &(x, wx) in &nodes {
        let u = 0.5 * PI * x;
        let p = (C * u.sin()).asin();
        let dp_du = C * u.cos() / (1.0 - (C * u.sin()).powi(2)).sqrt();
        let gap = p.cos() - C * u.cos();
        let b_max = (L / gap).atan();
        for &(y, wy) in &nodes {
            let b = b_max * y;
            let w = DVec3::new(b.sin(), b.cos() * p.sin(), b.cos() * p.cos());
            let weight = wx * 0.5 * PI * dp_du * wy * b_max * b.cos();
            for (o, y) in out.iter_mut().zip(eval_sh_f64(2, w).unwrap()) {
                *o += weight * y;
            }
        }
    }
    out
}

/// Eight rotations from a fixed seed (axis uniform on the sphere, angle uniform).
fn rotations() -> Vec<DMat3> {
    let mut rng = Pcg64Mcg::seed_from_u64(0x5ee7);
    (0..8)
        .map(|_| {
            let z: f64 = rng.random_range(-1.0..1.0);
            let phi: f64 = rng.random_range(0.0..2.0 * PI);
            let s = (1.0 - z * z).sqrt();
            let axis = DVec3::new(s * phi.cos(), s * phi.sin(), z);
            DMat3::from_axis_angle(axis, rng.random_range(0.0..2.0 * PI))
        })
        .collect()
}

#[test]
fn the_exact_baker_converges_to_the_closed_form_of_a_sheet() {
    let hidden = hidden_projection(96);
    let check = hidden_projection(48);
    let quadrature_error = hidden
        .iter()
        .zip(&check)
        .map(|(a, b)| (a - b).abs())
        .fold(0.0, f64::max);
    assert!(
        quadrature_error < 1e-12,
        "the reference's own quadrature: {quadrature_error:e}"
    );
    let (k, opacity) = (3, 0.4f64);
    let occlusion = 1.0 - (1.0 - opacity).powi(k as i32);
    let unturned: [f64; 9] = core::array::from_fn(|j| {
        let constant = if j == 0 { (4.0 * PI).sqrt() } else { 0.0 };
        constant - occlusion * hidden[j]
    });
    let counts = [1024, 4096, 16_384, 65_536];
    let mut rms = vec![0.0; counts.len()];
    for rotation in rotations() {
        let strands = sheet(k, rotation);
        let expected = rotate_low_order(rotation, unturned).unwrap();
        for (r, &directions) in rms.iter_mut().zip(&counts) {
            let baked = bake_all(&strands, 0..1, &exact(directions, opacity as f32));
            *r += baked
                .vertex(0)
                .iter()
                .zip(&expected)
                .map(|(b, e)| (f64::from(*b) - e).powi(2))
                .sum::<f64>();
        }
    }
    let rms: Vec<f64> = rms.iter().map(|r| (r / (8.0 * 9.0)).sqrt()).collect();
    for (n, r) in counts.iter().zip(&rms) {
        println!("{n} directions: rms coefficient error over 8 rotations {r:.2e}");
    }
    // Measured (README): 3.3e-3, 1.3e-3, 5.9e-4 and 2.7e-4, about n^-0.6 (the rate of a
    // low-discrepancy rule on an indicator with a smooth boundary lies between n^-0.5 and
    // n^-0.75); each quadrupling must divide the error by at least 1.8.
    for pair in rms.windows(2) {
        assert!(pair[1] < pair[0] / 1.8, "no convergence: {rms:?}");
    }
    assert!(rms[2] < 8e-4, "16384 directions: {rms:?}");
    // The directions that cross the unturned sheet see (1 - opacity)^k, the others 1.
    let strands = sheet(k, DMat3::IDENTITY);
    let occluders = Occluders::new(&strands, Opacity::Uniform(opacity as f32));
    let (inside, outside) = (
        Vec3::new(0.3, 0.01, 1.0).normalize(),
        Vec3::new(0.0, 0.2, 1.0).normalize(),
    );
    let v = |w| occluders.transmittance(Vec3::ZERO, w, Some(0));
    assert!((f64::from(v(inside)) - (1.0 - opacity).powi(k as i32)).abs() < 1e-6);
    assert_eq!(v(outside), 1.0);
}

/// A cylinder from parts, for the crossing tests.
fn cylinder(base: [f32; 3], axis: [f32; 3], length: f32, radius: f32) -> Option<Cylinder> {
    let axis = Vec3::from(axis).try_normalize()?;
    Some(Cylinder {
        base: Vec3::from(base),
        axis,
        length,
        radius,
        transmission: 0.5,
        strand: 0,
        start: 0,
    })
}

fn inside(c: &Cylinder, p: Vec3) -> bool {
    let along = (p - c.base).dot(c.axis);
    let across = (p - c.base - c.axis * along).length();
    (0.0..=c.length).contains(&along) && across <= c.radius
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(2000))]

    #[test]
    fn the_crossing_interval_is_where_the_ray_is_inside(
        base in prop::array::uniform3(-1.0f32..1.0),
        axis in prop::array::uniform3(-1.0f32..1.0),
        length in 0.01f32..1.0,
        radius in 0.01f32..0.5,
        direction in prop::array::uniform3(-1.0f32..1.0),
        samples in prop::collection::vec(0.0f32..1.0, 8),
    ) {
        let Some(c) = cylinder(base, axis, length, radius) else { return Ok(()) };
        let Some(d) = Vec3::from(direction).try_normalize() else { return Ok(()) };
        let origin = Vec3::ZERO;
        match c.ray_interval(origin, d) {
            Some((lo, hi)) => {
                prop_assert!(lo < hi);
                // Points well inside the interval are inside, just outside it are outside.
                let margin = 1e-3 * (hi - lo);
                for &s in &samples {
                    let t = lo + margin + s * (hi - lo - 2.0 * margin);
                    prop_assert!(inside(&c, origin + d * t) || hi - lo < 1e-3, "t = {t} in ({lo}, {hi})");
                }
                let step = 1e-3f32.max(1e-3 * (hi - lo));
                prop_assert!(!inside(&c, origin + d * (lo - step)));
                prop_assert!(!inside(&c, origin + d * (hi + step)));
            }
            None => {
                for k in 0..400 {
                    let t = -4.0 + 8.0 * k as f32 / 400.0;
                    let p = origin + d * t;
                    let along = (p - c.base).dot(c.axis);
                    let across = (p - c.base - c.axis * along).length();
                    let deep = along > 1e-4 && along < c.length - 1e-4 && across < c.radius * (1.0 - 1e-3);
                    prop_assert!(!deep, "missed a point inside at t = {t}");
                }
            }
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    #[test]
    fn the_hierarchy_finds_every_crossing(
        seed in any::<u64>(),
        origin in prop::array::uniform3(-1.5f32..1.5),
        direction in prop::array::uniform3(-1.0f32..1.0),
        own in 0u32..60,
    ) {
        let strands = groom(&GroomSettings {
            thickness: 0.05,
            ..GroomSettings::new(GroomKind::Curly, 60, 12, seed)
        }).unwrap();
        let occluders = Occluders::new(&strands, Opacity::Uniform(0.3));
        let Some(d) = Vec3::from(direction).try_normalize() else { return Ok(()) };
        let origin = Vec3::from(origin);
        let brute: f64 = occluders
            .cylinders()
            .iter()
            .filter(|c| c.strand != own && c.crossed_by(origin, d))
            .map(|c| f64::from(c.transmission))
            .product();
        let v = f64::from(occluders.transmittance(origin, d, Some(own)));
        prop_assert!((v - brute).abs() <= 1e-6 * brute.max(1e-7) + 6e-8, "{v} against {brute}");
    }
}

#[test]
fn bakes_do_not_depend_on_the_thread_count() {
    let strands = groom(&GroomSettings::new(GroomKind::Wavy, 200, 16, 4)).unwrap();
    let vertices = 0..strands.strand_points(19).unwrap().end;
    for settings in [
        exact(256, 0.5),
        BakeSettings {
            baker: Baker::Fast(FastSettings::default()),
            ..exact(1, 0.5)
        },
    ] {
        let run = |threads| {
            rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .unwrap()
                .install(|| bake_all(&strands, vertices.clone(), &settings))
        };
        assert_eq!(run(1), run(2), "{:?}", settings.baker);
    }
}

#[test]
fn coefficients_are_those_of_a_transmittance() {
    // V is in [0, 1], so its mean, Y_00 / sqrt(4 pi), is too; and the bakers agree on it.
    let strands = groom(&GroomSettings::new(GroomKind::Straight, 400, 16, 9)).unwrap();
    let vertices = 0..strands.strand_points(9).unwrap().end;
    let exact_bake = bake_all(&strands, vertices.clone(), &exact(1024, 0.5));
    let fast = bake_all(
        &strands,
        vertices.clone(),
        &BakeSettings {
            baker: Baker::Fast(FastSettings::default()),
            ..exact(1, 0.5)
        },
    );
    let norm = (4.0 * PI).sqrt() as f32;
    for k in 0..vertices.len() {
        for baked in [&exact_bake, &fast] {
            let mean = baked.vertex(k)[0] / norm;
            assert!(
                (-1e-6..=1.0 + 1e-6).contains(&mean),
                "vertex {k}: mean V {mean}"
            );
            assert!(baked.vertex(k).iter().all(|c| c.is_finite()));
        }
    }
}

#[test]
fn fibonacci_directions_are_unit_and_balanced() {
    let d = fibonacci_directions(1000);
    assert!(d.iter().all(|w| (w.length() - 1.0).abs() < 1e-12));
    let mean = d.iter().fold(DVec3::ZERO, |s, w| s + *w) / 1000.0;
    assert!(mean.length() < 2e-3, "{mean}");
}

#[test]
fn compare_measures_coefficients_and_reconstructed_v() {
    let reference = Transmittance {
        lmax: 2,
        vertices: 3..5,
        coefficients: (0..18).map(|k| 0.1 * k as f32).collect(),
    };
    let mut shifted = reference.clone();
    let delta = 0.25f32;
    shifted.coefficients[9] += delta; // Y_00 of the second vertex
    let c = compare(&shifted, &reference, 16, 3).unwrap();
    let delta = f64::from(delta);
    assert_eq!(c.vertices, 2);
    assert!((c.coefficient_max - delta).abs() < 1e-6);
    assert!((c.coefficient_rms - (delta * delta / 18.0).sqrt()).abs() < 1e-6);
    // Y_00 = 1 / (2 sqrt(pi)) everywhere: the second vertex's V is off by that at every
    // direction, the first's not at all.
    let v = delta / (2.0 * PI.sqrt());
    assert!((c.v_max - v).abs() < 1e-6, "{c:?}");
    assert!((c.v_rms - (v * v / 2.0).sqrt()).abs() < 1e-6, "{c:?}");
    let mean = (0.0 + 0.9) / 2.0 / (4.0 * PI).sqrt();
    assert!((c.reference_mean_v - mean).abs() < 1e-6);
    let same = compare(&reference, &reference, 8, 0).unwrap();
    assert_eq!((same.coefficient_max, same.v_max), (0.0, 0.0));
    let other = Transmittance {
        lmax: 1,
        vertices: 3..5,
        coefficients: vec![0.0; 8],
    };
    assert!(compare(&other, &reference, 8, 0).is_err());
    assert!(compare(&reference, &reference, 0, 0).is_err());
}

/// The fast baker's error against the exact one, as the README states it per groom (measured
/// on the first 20 strands of the 10,000-strand curly, wavy and straight grooms of seeds 1, 2
/// and 3 against 16,384 directions: coefficient RMS at most 0.029), holds on grooms of other
/// seeds, which its defaults were not tuned on. The reference here has 4,096 directions (its own
/// RMS error, measured as its distance from 16,384, is 0.004), so the bound allows 0.035.
#[test]
fn the_fast_bakers_stated_error_holds_on_grooms_it_was_not_tuned_on() {
    for (kind, seed) in [(GroomKind::Wavy, 7), (GroomKind::Straight, 8)] {
        let strands = groom(&GroomSettings::new(kind, 10_000, 32, seed)).unwrap();
        let vertices = 0..strands.strand_points(3).unwrap().end;
        let reference = bake_all(&strands, vertices.clone(), &exact(4096, 0.5));
        let fast = bake_all(
            &strands,
            vertices,
            &BakeSettings {
                baker: Baker::Fast(FastSettings::default()),
                ..exact(1, 0.5)
            },
        );
        let c = compare(&fast, &reference, 64, 1).unwrap();
        println!("{kind:?} seed {seed}: {c:?}");
        assert!(c.coefficient_rms < 0.035, "{kind:?}: {c:?}");
        assert!(c.v_rms < 0.03, "{kind:?}: {c:?}");
    }
}

fn rejected(settings: BakeSettings, vertices: core::ops::Range<usize>) -> &'static str {
    let strands = sheet(1, DMat3::IDENTITY);
    match bake(&strands, vertices, &settings, &quiet) {
        Err(ParamError::OutOfRange { name, .. }) => name,
        other => panic!("{settings:?} gave {other:?}"),
    }
}

#[test]
fn invalid_settings_name_the_setting() {
    let base = exact(64, 0.5);
    assert_eq!(rejected(BakeSettings { lmax: 17, ..base }, 0..1), "lmax");
    assert_eq!(rejected(exact(0, 0.5), 0..1), "directions");
    assert_eq!(rejected(exact(64, 1.5), 0..1), "opacity");
    assert_eq!(rejected(exact(64, f32::NAN), 0..1), "opacity");
    assert_eq!(rejected(base, 0..5), "vertices.end");
    let fast = |f: FastSettings| BakeSettings {
        baker: Baker::Fast(f),
        ..base
    };
    let default = FastSettings::default();
    assert_eq!(
        rejected(
            fast(FastSettings {
                bands: 0,
                ..default
            }),
            0..1
        ),
        "bands"
    );
    assert_eq!(
        rejected(
            fast(FastSettings {
                near_samples: 17,
                ..default
            }),
            0..1
        ),
        "near_samples"
    );
    assert_eq!(
        rejected(
            fast(FastSettings {
                near_cells: -1.0,
                ..default
            }),
            0..1
        ),
        "near_cells"
    );
    assert_eq!(
        rejected(
            fast(FastSettings {
                grid_cells: 0,
                ..default
            }),
            0..1
        ),
        "grid_cells"
    );
    assert_eq!(
        rejected(
            fast(FastSettings {
                cone_steps: f32::NAN,
                ..default
            }),
            0..1
        ),
        "cone_steps"
    );
}
