//! Trace test of the crossing test of the transmittance bakers
//! (`hairmath::strands::occluders::CrossingSetup`): the interval of a ray inside a cylinder, for
//! cylinders along an axis and oblique, from origins outside, inside and on the axis' line
//! beyond a cap, over the hard directions (along the axis, where the quadratic degenerates;
//! across it, where the slab does) and random ones.

use super::*;
use glam::Vec3;
use hairmath::strands::occluders::{CrossingSetup, Cylinder};

/// `(lo, hi, 1 if the interval is non-empty else 0)` of the ray from `origin` in direction `x`.
fn crossing<R: Real>(cylinder: &Cylinder, origin: Vec3, x: &[R]) -> Vec<R> {
    let setup = CrossingSetup::<R>::new(cylinder, origin);
    let (lo, hi, hit) = setup.interval([x[0], x[1], x[2]]);
    vec![lo, hi, R::select(hit, R::c(1.0), R::c(0.0))]
}

/// (cylinder, origin): along X seen from outside, oblique seen from inside, along X seen from
/// its axis' line beyond the cap.
fn configurations() -> Vec<(Cylinder, Vec3)> {
    let cylinder = |base: Vec3, axis: Vec3| Cylinder {
        base,
        axis: axis.normalize(),
        length: 0.5,
        radius: 0.1,
        transmission: 0.5,
        strand: 1,
        start: 0,
    };
    vec![
        (cylinder(Vec3::new(-0.25, 0.0, 1.0), Vec3::X), Vec3::ZERO),
        (
            cylinder(Vec3::new(-0.1, -0.2, 0.05), Vec3::new(1.0, 2.0, 0.5)),
            Vec3::ZERO,
        ),
        (cylinder(Vec3::new(1.0, 0.0, 0.0), Vec3::X), Vec3::ZERO),
    ]
}

traced_tests! {
    strands_crossing ["CrossingSetup::new", "CrossingSetup::interval"] {
        for (k, (cylinder, origin)) in configurations().into_iter().enumerate() {
            case!(format!("CrossingSetup::interval ({k})"), sh_direction_rows(), |x| {
                crossing(&cylinder, origin, x)
            });
        }
    }
}
