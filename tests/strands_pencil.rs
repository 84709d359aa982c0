//! The pencil of great circles (`hairmath::strands::pencil`) against ray tests, the
//! independent definition of a crossing:
//! - along a circle, a ray crosses a cylinder exactly when its angle lies in the arc the
//!   pencil computes, for random cylinders, origins and circles, grazing circles and circles
//!   along the axis included: against the crossing computed in f64 for each ray (away from the
//!   arc's ends by 1e-9), and on well-conditioned sections against the occluders' own f32 ray
//!   test (`Cylinder::crossed_by`, whose f32 arithmetic blurs the surface by about
//!   `1e-7 D^2 / r` at a distance `D`: a percent of a thin strand's radius at `D = 1`);
//! - the circles a pencil does not list for a cylinder cross it nowhere;
//! - an origin inside a cylinder is crossed in every direction.

use core::f64::consts::TAU;
use glam::{DVec3, Vec3};
use hairmath::strands::occluders::Cylinder;
use hairmath::strands::pencil::{CircleSpan, Crossing, GreatCircle, Pencil};
use proptest::prelude::*;

fn unit(v: [f64; 3]) -> Option<DVec3> {
    DVec3::from_array(v).try_normalize()
}

fn cylinder(base: [f64; 3], axis: DVec3, length: f64, radius: f64) -> Cylinder {
    Cylinder {
        base: DVec3::from_array(base).as_vec3(),
        axis: axis.as_vec3(),
        length: length as f32,
        radius: radius as f32,
        transmission: 0.3,
        strand: 1,
        start: 0,
    }
}

/// Whether `u` lies in the arc, modulo 2 pi, and its angular distance to the arc's ends.
fn in_arc(crossing: Crossing, u: f64) -> (bool, f64) {
    match crossing {
        Crossing::None => (false, f64::INFINITY),
        Crossing::All => (true, f64::INFINITY),
        Crossing::Arc { start, end } => {
            let from_start = (u - start).rem_euclid(TAU);
            let length = end - start;
            let to_end = (from_start - length).abs();
            let inside = from_start < length;
            (inside, from_start.min(to_end).min(TAU - from_start))
        }
    }
}

/// Whether the ray `origin + t d`, `t > 0`, spends a positive length inside the solid
/// cylinder (the occluders' definition), in f64 with the axis normalised: the infinite
/// cylinder's quadratic in `t` intersected with the slab between the caps.
fn crossed_in_f64(c: &Cylinder, origin: DVec3, d: DVec3) -> bool {
    let (base, axis) = (c.base.as_dvec3(), c.axis.as_dvec3().normalize());
    let (length, r) = (f64::from(c.length), f64::from(c.radius));
    let w = origin - base;
    let (w_axial, d_axial) = (w.dot(axis), d.dot(axis));
    let (w_p, d_p) = (w - axis * w_axial, d - axis * d_axial);
    let (a, b, c) = (
        d_p.length_squared(),
        w_p.dot(d_p),
        w_p.length_squared() - r * r,
    );
    let (mut lo, mut hi) = if a > 1e-300 {
        let discriminant = b * b - a * c;
        if discriminant <= 0.0 {
            return false;
        }
        let root = discriminant.sqrt();
        ((-b - root) / a, (root - b) / a)
    } else if c < 0.0 {
        (f64::NEG_INFINITY, f64::INFINITY)
    } else {
        return false;
    };
    if d_axial != 0.0 {
        let (t0, t1) = (-w_axial / d_axial, (length - w_axial) / d_axial);
        lo = lo.max(t0.min(t1));
        hi = hi.min(t0.max(t1));
    } else if !(0.0..=length).contains(&w_axial) {
        return false;
    }
    lo < hi && hi > 0.0
}

/// Which ray test [`mismatches`] uses.
#[derive(Clone, Copy)]
enum RayTest {
    F64,
    OccludersF32,
}

/// The mismatches between the ray test and the arc over `n` angles of the circle, counting
/// only angles farther than `margin` from the arc's ends; and how many rays crossed.
fn mismatches(
    circle: &GreatCircle,
    cylinder: &Cylinder,
    (n, margin): (usize, f64),
    test: RayTest,
) -> (usize, usize) {
    let crossing = circle.crossing(cylinder);
    let (mut wrong, mut crossed) = (0, 0);
    for k in 0..n {
        let u = (k as f64 + 0.37) * TAU / n as f64;
        let d = circle.direction(u);
        let by_ray = match test {
            RayTest::F64 => crossed_in_f64(cylinder, circle.origin, d),
            RayTest::OccludersF32 => cylinder.crossed_by(circle.origin.as_vec3(), d.as_vec3()),
        };
        crossed += usize::from(by_ray);
        let (inside, distance) = in_arc(crossing, u);
        if distance > margin && inside != by_ray {
            wrong += 1;
        }
    }
    (wrong, crossed)
}

fn circle_through(origin: DVec3, pole: DVec3, toward: DVec3) -> Option<GreatCircle> {
    let across = (toward - pole * toward.dot(pole)).try_normalize()?;
    Some(GreatCircle {
        origin,
        pole,
        across,
    })
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(400))]

    /// Random cylinders and circles, most of them through the cylinder (the circle's plane
    /// holds a point of the axis).
    #[test]
    fn arcs_match_the_ray_test(
        base in prop::array::uniform3(-1.0..1.0f64),
        axis in prop::array::uniform3(-1.0..1.0f64),
        length in 0.05..2.0f64,
        radius in 0.002..0.4f64,
        origin in prop::array::uniform3(-2.0..2.0f64),
        pole in prop::array::uniform3(-1.0..1.0f64),
        along in 0.0..1.0f64,
        offset in -1.5..1.5f64,
    ) {
        let (Some(axis), Some(pole)) = (unit(axis), unit(pole)) else { return Ok(()) };
        let c = cylinder(base, axis, length, radius);
        let origin = DVec3::from_array(origin);
        prop_assume!(c.axis_distance(origin.as_vec3()) > 1.01 * c.radius);
        // Through a point near the axis: inside the cylinder for |offset| < 1, a grazing
        // plane near 1.
        let target = DVec3::from_array(base) + axis * (along * length)
            + pole.cross(axis).normalize_or_zero() * (offset * radius);
        let Some(circle) = circle_through(origin, pole, target - origin) else { return Ok(()) };
        let (wrong, _) = mismatches(&circle, &c, (4000, 1e-9), RayTest::F64);
        prop_assert_eq!(wrong, 0, "{:?}", circle.crossing(&c));
    }

    /// Circles of a pencil that it does not list for a cylinder cross it nowhere.
    #[test]
    fn unlisted_circles_miss(
        base in prop::array::uniform3(-1.0..1.0f64),
        axis in prop::array::uniform3(-1.0..1.0f64),
        length in 0.01..1.0f64,
        radius in 0.002..0.2f64,
        pole in prop::array::uniform3(-1.0..1.0f64),
        circles in 1usize..64,
    ) {
        let (Some(axis), Some(pole)) = (unit(axis), unit(pole)) else { return Ok(()) };
        let c = cylinder(base, axis, length, radius);
        prop_assume!(c.axis_distance(Vec3::ZERO) > 1.01 * c.radius);
        let pencil = Pencil::new(Vec3::ZERO, pole, circles).unwrap();
        let listed: Vec<bool> = match pencil.circles_meeting(&c) {
            CircleSpan::All => vec![true; circles],
            CircleSpan::Range { first, count } => {
                (0..circles).map(|j| (j + circles - first) % circles < count).collect()
            }
        };
        for (j, &listed) in listed.iter().enumerate() {
            if !listed {
                let circle = pencil.circle(j);
                prop_assert_eq!(circle.crossing(&c), Crossing::None, "circle {}", j);
                prop_assert_eq!(mismatches(&circle, &c, (2000, 0.0), RayTest::F64).1, 0);
            }
        }
    }
}

/// Circles in the plane of the axis (the section a rectangle), across it (an ellipse) and
/// parallel to the caps (a disc): the arcs against the ray test and the angles they subtend in
/// closed form (to 1e-8: the cylinder is stored in f32).
#[test]
fn special_sections() {
    let c = cylinder([0.0, 0.0, 0.0], DVec3::Z, 1.0, 0.1);
    let origin = DVec3::new(2.0, 0.0, 0.5);
    // The plane y = 0 holds the axis: the rectangle |x| <= 0.1, 0 <= z <= 1 seen from
    // (2, 0, 0.5); its ends are the near corners (0.1, 0 or 1).
    let circle = circle_through(origin, DVec3::Z, DVec3::NEG_X).unwrap();
    let Crossing::Arc { start, end } = circle.crossing(&c) else {
        panic!("no arc")
    };
    let expected = 2.0 * (0.5_f64).atan2(1.9);
    assert!((end - start - expected).abs() < 1e-8, "{}", end - start);
    for test in [RayTest::F64, RayTest::OccludersF32] {
        assert_eq!(mismatches(&circle, &c, (20000, 1e-5), test).0, 0);
    }
    // The plane z = 0.5 is parallel to the caps: a disc of radius 0.1 at distance 2.
    let circle = circle_through(origin, DVec3::X, DVec3::Y).unwrap();
    let Crossing::Arc { start, end } = circle.crossing(&c) else {
        panic!("no arc")
    };
    assert!((end - start - 2.0 * (0.05_f64).asin()).abs() < 1e-8);
    for test in [RayTest::F64, RayTest::OccludersF32] {
        assert_eq!(mismatches(&circle, &c, (20000, 1e-5), test).0, 0);
    }
    // The plane z = 1.5 misses it.
    let above = GreatCircle {
        origin: DVec3::new(2.0, 0.0, 1.5),
        ..circle
    };
    assert_eq!(above.crossing(&c), Crossing::None);
    // Inside: every direction.
    let inside = GreatCircle {
        origin: DVec3::new(0.05, 0.0, 0.5),
        ..circle
    };
    assert_eq!(inside.crossing(&c), Crossing::All);
    for test in [RayTest::F64, RayTest::OccludersF32] {
        assert_eq!(mismatches(&inside, &c, (1000, 0.0), test), (0, 1000));
    }
    // A pencil around the axis at an origin on the axis' line outside it sees it from every
    // circle.
    let pencil = Pencil::new(Vec3::new(0.0, 0.0, 3.0), DVec3::Z, 8).unwrap();
    assert_eq!(pencil.circles_meeting(&c), CircleSpan::All);
}

#[test]
fn pencil_errors() {
    assert!(Pencil::new(Vec3::ZERO, DVec3::Z, 0).is_err());
    assert!(Pencil::new(Vec3::ZERO, DVec3::ZERO, 4).is_err());
    assert!(Pencil::new(Vec3::ZERO, DVec3::new(f64::NAN, 0.0, 1.0), 4).is_err());
}
