//! A pencil of great circles of directions, and where each crosses the strands' cylinders: the
//! visibility `V(x, w)` of [`crate::strands::occluders`] along whole circles of directions in
//! closed form, so that a reference can integrate it exactly along each circle instead of
//! sampling it at points (the strands are thinner than any practical spacing of directions).
//!
//! The pencil of `n` circles through a pole `a` at an origin `x`: circle `j` holds the
//! directions `d(u) = cos u a + sin u e_j`, `u` in `[0, 2 pi)`, with `e_j = cos psi_j b1 +
//! sin psi_j b2` and `psi_j = (j + 1/2) pi / n`; the rays from `x` along circle `j` fill the
//! plane through `x` spanned by `a` and `e_j`. The pencil covers the sphere once, with
//! `dw = |sin u| du dpsi`.
//!
//! Along one circle, the rays crossing a cylinder form one arc ([`Crossing`]): the plane's
//! section of the solid cylinder is convex and, for an origin outside the cylinder, seen under
//! less than half a turn. The arc's ends are the rays that touch the section, at a point of
//! its curved side (a ray tangent to the infinite cylinder, touching within the caps) or at a
//! corner (where the plane cuts a cap's rim); the arc is the angular hull of those points.
//! Grazing contacts count as misses in the ray test and as arc ends here, a difference of
//! measure zero.

use super::occluders::Cylinder;
use crate::error::ParamError;
use core::f64::consts::PI;
use glam::{DVec3, Vec3};

/// Squared lengths below this are taken as zero (parallel directions).
const DEGENERATE: f64 = 1e-24;

/// One great circle of directions from an origin: `d(u) = cos u pole + sin u across`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct GreatCircle {
    /// Where the rays start.
    pub origin: DVec3,
    /// The direction at `u = 0`.
    pub pole: DVec3,
    /// The direction at `u = pi / 2`, orthogonal to `pole`.
    pub across: DVec3,
}

/// Where the rays along a [`GreatCircle`] cross one cylinder.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Crossing {
    /// No ray of the circle crosses it.
    None,
    /// Every ray from the origin crosses it (the origin is inside).
    All,
    /// The rays of `u` in `(start, end)` cross it, `start < end < start + pi`, `start` in
    /// `[-pi, pi]` (the angles are taken modulo `2 pi`).
    Arc {
        /// The arc's first angle.
        start: f64,
        /// Its last.
        end: f64,
    },
}

/// A cylinder in f64.
struct Solid {
    base: DVec3,
    axis: DVec3,
    length: f64,
    radius: f64,
}

impl Solid {
    /// The cylinder in f64, its axis normalised again: the f32 axis is unit only to about
    /// 1e-7, which at a distance `D` moves the squared distance across it by about
    /// `1e-7 D^2`, a percent of a strand's squared radius at `D = 1`.
    fn of(cylinder: &Cylinder) -> Self {
        Self {
            base: cylinder.base.as_dvec3(),
            axis: cylinder.axis.as_dvec3().normalize_or(DVec3::X),
            length: f64::from(cylinder.length),
            radius: f64::from(cylinder.radius),
        }
    }

    /// The component of `v` across the axis.
    fn across(&self, v: DVec3) -> DVec3 {
        v - self.axis * v.dot(self.axis)
    }

    fn contains(&self, point: DVec3) -> bool {
        let w = point - self.base;
        let along = w.dot(self.axis);
        (0.0..=self.length).contains(&along)
            && self.across(w).length_squared() < self.radius * self.radius
    }
}

impl GreatCircle {
    /// The direction at angle `u`.
    pub fn direction(&self, u: f64) -> DVec3 {
        let (s, c) = u.sin_cos();
        self.pole * c + self.across * s
    }

    /// The coordinates of a vector `v` in the circle's plane: `(v.pole, v.across)`.
    fn coordinates(&self, v: DVec3) -> [f64; 2] {
        [v.dot(self.pole), v.dot(self.across)]
    }

    /// Where the circle's rays cross `cylinder` (module documentation).
    pub fn crossing(&self, cylinder: &Cylinder) -> Crossing {
        let solid = Solid::of(cylinder);
        if cylinder.length <= 0.0 {
            return Crossing::None;
        }
        if solid.contains(self.origin) {
            return Crossing::All;
        }
        let mut points = [[0.0; 2]; 8];
        let mut count = 0;
        for point in self
            .tangent_points(&solid)
            .into_iter()
            .chain(self.rim_points(&solid))
            .flatten()
        {
            points[count] = self.coordinates(point - self.origin);
            count += 1;
        }
        angular_hull(&points[..count])
    }

    /// The points where a ray of the circle touches the cylinder's curved side between its
    /// caps. The ray `x + t d` meets the infinite cylinder where
    /// `|w_p + t d_p|^2 = r^2` (`_p`: across the axis, `w = x - base`); it touches it where
    /// that quadratic's discriminant `(w_p.d)^2 - |d_p|^2 (|w_p|^2 - r^2)` vanishes, a
    /// quadratic form in `(cos u, sin u)` with matrix `[[p, q], [q, r]]`: in its eigenvectors'
    /// frame `high c^2 + low s^2`, zero where `tan^2 = -high / low`.
    fn tangent_points(&self, solid: &Solid) -> [Option<DVec3>; 4] {
        let w = self.origin - solid.base;
        let w_p = solid.across(w);
        let c = w_p.length_squared() - solid.radius * solid.radius;
        let (pole_p, across_p) = (solid.across(self.pole), solid.across(self.across));
        let (alpha, beta) = (w_p.dot(self.pole), w_p.dot(self.across));
        let p = alpha * alpha - c * pole_p.length_squared();
        let q = alpha * beta - c * pole_p.dot(across_p);
        let r = beta * beta - c * across_p.length_squared();
        let mean = 0.5 * (p + r);
        let spread = (0.25 * (p - r) * (p - r) + q * q).sqrt();
        let (high, low) = (mean + spread, mean - spread);
        if high < 0.0 || low > 0.0 || spread <= 0.0 {
            return [None; 4];
        }
        // The eigenvector of `high`, from the better conditioned row of `M - high I`.
        let principal = if p >= r { [high - r, q] } else { [q, high - p] };
        let norm = principal[0].hypot(principal[1]);
        let [e0, e1] = [principal[0] / norm, principal[1] / norm];
        let (cos_zero, sin_zero) = (
            (-low / (2.0 * spread)).sqrt(),
            (high / (2.0 * spread)).sqrt(),
        );
        let mut out = [None; 4];
        for (k, (sign_a, sign_b)) in [(1.0, 1.0), (1.0, -1.0), (-1.0, 1.0), (-1.0, -1.0)]
            .into_iter()
            .enumerate()
        {
            let (a, b) = (sign_a * cos_zero, sign_b * sin_zero);
            let d = self.pole * (a * e0 - b * e1) + self.across * (a * e1 + b * e0);
            let d_p = solid.across(d);
            let a = d_p.length_squared();
            let t = -w_p.dot(d) / a;
            let along = w.dot(solid.axis) + t * d.dot(solid.axis);
            if a > DEGENERATE && t > 0.0 && (0.0..=solid.length).contains(&along) {
                out[k] = Some(self.origin + d * t);
            }
        }
        out
    }

    /// The points where the circle's plane cuts the rims of the cylinder's two caps.
    fn rim_points(&self, solid: &Solid) -> [Option<DVec3>; 4] {
        let w = self.origin - solid.base;
        let slope = [self.pole.dot(solid.axis), self.across.dot(solid.axis)];
        let slope_squared = slope[0] * slope[0] + slope[1] * slope[1];
        let mut out = [None; 4];
        if slope_squared < DEGENERATE {
            return out;
        }
        let line = (self.across * slope[0] - self.pole * slope[1]) / slope_squared.sqrt();
        for (k, cap) in [0.0, solid.length].into_iter().enumerate() {
            let offset = (cap - w.dot(solid.axis)) / slope_squared;
            let foot = (self.pole * slope[0] + self.across * slope[1]) * offset;
            let (centre, line_p) = (solid.across(w + foot), solid.across(line));
            let a = line_p.length_squared();
            let b = centre.dot(line_p);
            let discriminant = b * b - a * (centre.length_squared() - solid.radius.powi(2));
            if a < DEGENERATE || discriminant < 0.0 {
                continue;
            }
            let root = discriminant.sqrt();
            for (i, s) in [(-b - root) / a, (root - b) / a].into_iter().enumerate() {
                let v = foot + line * s;
                out[2 * k + i] = (v.length_squared() > DEGENERATE).then(|| self.origin + v);
            }
        }
        out
    }
}

/// The smallest arc holding every vector of `points` (plane coordinates, all within half a
/// turn of each other): its ends are the most clockwise and the most anticlockwise vector.
fn angular_hull(points: &[[f64; 2]]) -> Crossing {
    let Some(&first) = points.first() else {
        return Crossing::None;
    };
    let cross = |a: [f64; 2], b: [f64; 2]| a[0] * b[1] - a[1] * b[0];
    let (mut lo, mut hi) = (first, first);
    for &v in points {
        if cross(lo, v) < 0.0 {
            lo = v;
        }
        if cross(hi, v) > 0.0 {
            hi = v;
        }
    }
    let start = lo[1].atan2(lo[0]);
    let span = cross(lo, hi).atan2(lo[0] * hi[0] + lo[1] * hi[1]);
    if span > 0.0 {
        Crossing::Arc {
            start,
            end: start + span,
        }
    } else {
        Crossing::None
    }
}

/// Which circles of a [`Pencil`] may cross a cylinder.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum CircleSpan {
    /// Every circle.
    All,
    /// `count` circles from `first` on, the indices taken modulo the pencil's circles.
    Range {
        /// The first circle.
        first: usize,
        /// How many.
        count: usize,
    },
}

/// `n` great circles through a pole at an origin (module documentation).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Pencil {
    origin: DVec3,
    pole: DVec3,
    basis: [DVec3; 2],
    circles: usize,
}

impl Pencil {
    /// The pencil of `circles` circles through `pole` at `origin`.
    ///
    /// # Errors
    /// [`ParamError::OutOfRange`] if `circles` is 0 or `pole` is not finite and non-zero.
    pub fn new(origin: Vec3, pole: DVec3, circles: usize) -> Result<Self, ParamError> {
        ParamError::check("circles", circles as f64, "must be at least 1", |n| {
            n >= 1.0
        })?;
        let pole = pole.try_normalize().ok_or(ParamError::BadVector {
            name: "pole",
            x: pole.x,
            y: pole.y,
            z: pole.z,
            allowed: "must be finite and non-zero",
        })?;
        let (b1, b2) = pole.any_orthonormal_pair();
        Ok(Self {
            origin: origin.as_dvec3(),
            pole,
            basis: [b1, b2],
            circles,
        })
    }

    /// The number of circles.
    pub fn circles(&self) -> usize {
        self.circles
    }

    /// The pencil's angle `psi_j = (j + 1/2) pi / n` of circle `j`.
    pub fn psi(&self, j: usize) -> f64 {
        (j as f64 + 0.5) * PI / self.circles as f64
    }

    /// Circle `j` (`j` below [`Self::circles`]).
    pub fn circle(&self, j: usize) -> GreatCircle {
        let (s, c) = self.psi(j).sin_cos();
        GreatCircle {
            origin: self.origin,
            pole: self.pole,
            across: self.basis[0] * c + self.basis[1] * s,
        }
    }

    /// The circles whose plane may meet `cylinder`: those whose angle `psi` lies, modulo
    /// `pi`, within the angles under which the cylinder's bounding capsule is seen from the
    /// pole's line (its axis segment's, widened by `asin(radius / distance)`).
    pub fn circles_meeting(&self, cylinder: &Cylinder) -> CircleSpan {
        let solid = Solid::of(cylinder);
        let project = |p: DVec3| {
            let v = p - self.origin;
            [v.dot(self.basis[0]), v.dot(self.basis[1])]
        };
        let q0 = project(solid.base);
        let q1 = project(solid.base + solid.axis * solid.length);
        let distance = segment_distance_to_origin(q0, q1);
        let radius = solid.radius * (1.0 + 1e-9) + 1e-12;
        if distance <= radius {
            return CircleSpan::All;
        }
        let (a0, a1) = (q0[1].atan2(q0[0]), q1[1].atan2(q1[0]));
        let turn = a1 - a0 - 2.0 * PI * ((a1 - a0) / (2.0 * PI)).round();
        let margin = (radius / distance).asin();
        let (lo, hi) = (a0.min(a0 + turn) - margin, a0.max(a0 + turn) + margin);
        let n = self.circles as f64;
        if hi - lo >= PI {
            return CircleSpan::All;
        }
        let first = (lo * n / PI - 0.5).ceil();
        let last = (hi * n / PI - 0.5).floor();
        if last < first {
            return CircleSpan::Range { first: 0, count: 0 };
        }
        CircleSpan::Range {
            first: first.rem_euclid(n) as usize,
            count: ((last - first) as usize + 1).min(self.circles),
        }
    }
}

/// The distance from the origin to the segment from `q0` to `q1` in the plane.
fn segment_distance_to_origin(q0: [f64; 2], q1: [f64; 2]) -> f64 {
    let d = [q1[0] - q0[0], q1[1] - q0[1]];
    let length_squared = d[0] * d[0] + d[1] * d[1];
    let s = if length_squared > 0.0 {
        (-(q0[0] * d[0] + q0[1] * d[1]) / length_squared).clamp(0.0, 1.0)
    } else {
        0.0
    };
    (q0[0] + s * d[0]).hypot(q0[1] + s * d[1])
}
