//! The strands as occluders: each segment a solid cylinder of its thickness with an opacity,
//! in a bounding-volume hierarchy that finds every cylinder a ray crosses.
//!
//! This is the geometry of the transmittance of the issue that defines it:
//! `V(x, w) = prod (1 - opacity_s)` over the segments `s` that the ray `x + t w`, `t > 0`,
//! crosses, the segments of `x`'s own strand excluded, each segment a solid cylinder (flat
//! caps) around the line from its first to its second point with radius
//! `(thickness_0 + thickness_1) / 4` (the mean of its points' diameters, halved). A ray
//! "crosses" a cylinder when the set of `t > 0` inside it has positive length, so grazing
//! contacts (a set of measure zero among directions) count as misses. Neighbouring segments of
//! one strand are separate cylinders: a ray through the wedge where two of them overlap at a
//! bend crosses both.
//!
//! The hierarchy is built once by a binned surface-area heuristic over the cylinders'
//! bounding boxes (16 bins, leaves of at most [`LEAF_SIZE`] cylinders), deterministically.
//! Traversal visits every box the ray enters (all crossings are needed, not the nearest).
//! Arithmetic is f32, as the file stores the points: a crossing is misclassified only where
//! the ray passes within about 1e-7 head radii of a cylinder's surface.

use super::{Segment, Strands};
use crate::real::Real;
use core::ops::ControlFlow;
use glam::{Vec3, Vec3A};

/// The most cylinders in a leaf of the hierarchy.
pub const LEAF_SIZE: usize = 4;
/// Bins of the surface-area heuristic per axis.
const BINS: usize = 16;
/// Below this depth the hierarchy splits by the heuristic, from it on at the median, so its
/// depth stays below `MEDIAN_DEPTH + 32` for up to 2^32 cylinders, within the traversal
/// stack of [`STACK`] entries.
const MEDIAN_DEPTH: usize = 64;
/// Transmittances below this are returned as 0: an absolute error below 2^-24, under half an
/// f32 ulp of 1, while a dark ray stops early.
pub const NEGLIGIBLE_TRANSMITTANCE: f32 = 1.0 / (1 << 24) as f32;
/// Entries of the traversal stack (depth + 1 suffice).
const STACK: usize = 128;

/// Where each segment's opacity comes from.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Opacity {
    /// `1 -` the mean transparency of the segment's two points, as the file stores it.
    FromTransparency,
    /// The same opacity for every segment, in `[0, 1]`.
    Uniform(f32),
}

/// One segment as a cylinder.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Cylinder {
    /// The centre of its first cap (the segment's first point).
    pub base: Vec3,
    /// The unit axis, from the first point to the second (`Vec3::X` for a zero-length segment,
    /// whose length 0 makes it uncrossable).
    pub axis: Vec3,
    /// The distance between its points.
    pub length: f32,
    /// The radius.
    pub radius: f32,
    /// `1 - opacity`: the factor a crossing multiplies the transmittance by.
    pub transmission: f32,
    /// The strand it belongs to.
    pub strand: u32,
    /// The index of the segment's first point (its second is the next).
    pub start: u32,
}

impl Cylinder {
    /// The cylinder of segment `segment` of `strands` (a segment from `strands.segment_iter()`
    /// or of a strand's points), with the given opacity.
    ///
    /// # Panics
    /// If the segment's points are not points of `strands`, or its strand or point index
    /// exceeds `u32::MAX` (no `.hair` file or groom has that many).
    pub fn of_segment(strands: &Strands, segment: Segment, opacity: Opacity) -> Self {
        let (i, j) = (segment.start, segment.start + 1);
        let (base, end) = (strands.points()[i], strands.points()[j]);
        let transmission = match opacity {
            Opacity::FromTransparency => {
                0.5 * (strands.transparency().at(i) + strands.transparency().at(j))
            }
            Opacity::Uniform(a) => 1.0 - a,
        };
        Cylinder {
            base,
            axis: (end - base).try_normalize().unwrap_or(Vec3::X),
            length: base.distance(end),
            radius: 0.25 * (strands.thickness().at(i) + strands.thickness().at(j)),
            transmission,
            strand: u32::try_from(segment.strand).expect("strand counts fit in u32"),
            start: u32::try_from(segment.start).expect("point counts fit in u32"),
        }
    }

    /// The interval of ray parameters `t` inside the solid cylinder, for the ray
    /// `origin + t direction` (`direction` of unit length), or `None` if the ray's line misses
    /// it (see [`CrossingSetup::interval`]). The interval may extend to negative `t`.
    pub fn ray_interval(&self, origin: Vec3, direction: Vec3) -> Option<(f32, f32)> {
        let (lo, hi, hit) =
            CrossingSetup::new(self, origin).interval([direction.x, direction.y, direction.z]);
        hit.then_some((lo, hi))
    }

    /// The distance from `point` to the cylinder's axis segment (0 for a point on it).
    pub fn axis_distance(&self, point: Vec3) -> f32 {
        let along = (point - self.base).dot(self.axis).clamp(0.0, self.length);
        point.distance(self.base + self.axis * along)
    }

    /// Whether the ray `origin + t direction`, `t > 0`, crosses the cylinder (spends a
    /// positive length inside it).
    pub fn crossed_by(&self, origin: Vec3, direction: Vec3) -> bool {
        self.ray_interval(origin, direction)
            .is_some_and(|(_, hi)| hi > 0.0)
    }

    /// The cylinder's axis-aligned bounding box: the two caps' boxes (each a disc of `radius`
    /// across `axis`, whose extent along coordinate `k` is `radius sqrt(1 - axis_k^2)`).
    fn bounds(&self) -> Aabb {
        let across = (Vec3::ONE - self.axis * self.axis).max(Vec3::ZERO);
        let extent = Vec3::new(across.x.sqrt(), across.y.sqrt(), across.z.sqrt()) * self.radius;
        let end = self.base + self.axis * self.length;
        Aabb {
            min: (self.base.min(end) - extent).into(),
            max: (self.base.max(end) + extent).into(),
        }
    }
}

/// What the crossing test of one cylinder needs from one ray origin, in any precision or lanes
/// `R` (the scalar test of the exact baker and the eight-direction test of the fast baker's
/// near field are this one code).
#[derive(Clone, Copy, Debug)]
pub struct CrossingSetup<R> {
    axis: [R; 3],
    length: R,
    /// `(origin - base).axis`.
    w_axial: R,
    /// The component of `origin - base` across the axis.
    w_perp: [R; 3],
    /// `|w_perp|^2 - radius^2`.
    c: R,
}

/// Parameters beyond this magnitude stand for infinity in [`CrossingSetup::interval`].
const FAR: f64 = 1e30;

impl<R: Real> CrossingSetup<R> {
    /// The setup of `cylinder` for rays from `origin`.
    pub fn new(cylinder: &Cylinder, origin: Vec3) -> Self {
        let w = origin - cylinder.base;
        let w_axial = w.dot(cylinder.axis);
        let w_perp = w - cylinder.axis * w_axial;
        let c = w_perp.length_squared() - cylinder.radius * cylinder.radius;
        let r = |x: f32| R::c(f64::from(x));
        Self {
            axis: cylinder.axis.to_array().map(r),
            length: r(cylinder.length),
            w_axial: r(w_axial),
            w_perp: w_perp.to_array().map(r),
            c: r(c),
        }
    }

    /// The interval `(lo, hi)` of `t` for which `origin + t d` lies in the solid cylinder, and
    /// whether it is non-empty (`lo < hi`).
    ///
    /// The axial coordinate `(origin - base).axis + t d.axis` must lie in `[0, length]` (a
    /// slab), and the distance from the axis, `|w_perp + t d_perp|` with `d_perp` the component
    /// of `d` across the axis, at most `radius`: the quadratic `a t^2 + 2 b t + c <= 0` with
    /// `a = d_perp.d_perp`, `b = w_perp.d_perp`. A ray parallel to the axis (`a` below
    /// `1e-14`) is inside for every `t` or none, as is a ray across it (`d.axis = 0`) for the
    /// slab.
    pub fn interval(&self, d: [R; 3]) -> (R, R, R::Mask) {
        let [ax, ay, az] = self.axis;
        let d_axial = d[0] * ax + d[1] * ay + d[2] * az;
        let d_perp = [
            d[0] - ax * d_axial,
            d[1] - ay * d_axial,
            d[2] - az * d_axial,
        ];
        let a = d_perp[0].sqr() + d_perp[1].sqr() + d_perp[2].sqr();
        let b =
            self.w_perp[0] * d_perp[0] + self.w_perp[1] * d_perp[1] + self.w_perp[2] * d_perp[2];
        let (zero, one, far) = (R::c(0.0), R::c(1.0), R::c(FAR));
        let discriminant = b * b - a * self.c;
        let across = R::c(1e-14).lt(a);
        let root = discriminant.max(zero).sqrt();
        let a_safe = R::select(across, a, one);
        let quadratic_hit = (across & zero.lt(discriminant)) | (!across & self.c.le(zero));
        let q_lo = R::select(across, (-b - root) / a_safe, -far);
        let q_hi = R::select(across, (root - b) / a_safe, far);
        let crosses_slab = d_axial.abs().gt(zero);
        let d_safe = R::select(crosses_slab, d_axial, one);
        let t0 = -self.w_axial / d_safe;
        let t1 = (self.length - self.w_axial) / d_safe;
        let inside_slab = zero.le(self.w_axial) & self.w_axial.le(self.length);
        let slab_hit = crosses_slab | inside_slab;
        let s_lo = R::select(crosses_slab, t0.min(t1), -far);
        let s_hi = R::select(crosses_slab, t0.max(t1), far);
        let (lo, hi) = (q_lo.max(s_lo), q_hi.min(s_hi));
        (lo, hi, quadratic_hit & slab_hit & lo.lt(hi))
    }
}

/// An axis-aligned box (in SIMD-aligned vectors: the traversal's slab test is its hot loop).
#[derive(Clone, Copy, Debug, PartialEq)]
struct Aabb {
    min: Vec3A,
    max: Vec3A,
}

/// The reciprocals of `direction`'s components for the slab test, components below 1e-20 in
/// magnitude taken as 1e-20 so that the test never multiplies 0 by infinity.
fn safe_inverse(direction: Vec3) -> Vec3A {
    Vec3A::from(direction)
        .abs()
        .max(Vec3A::splat(1e-20))
        .copysign(direction.into())
        .recip()
}

impl Aabb {
    const EMPTY: Aabb = Aabb {
        min: Vec3A::splat(f32::INFINITY),
        max: Vec3A::splat(f32::NEG_INFINITY),
    };

    fn union(self, other: Aabb) -> Aabb {
        Aabb {
            min: self.min.min(other.min),
            max: self.max.max(other.max),
        }
    }

    fn centre(&self) -> Vec3A {
        0.5 * (self.min + self.max)
    }

    /// Half the surface area (the heuristic's measure; empty boxes have 0).
    fn half_area(&self) -> f32 {
        let d = (self.max - self.min).max(Vec3A::ZERO);
        d.x * d.y + d.y * d.z + d.z * d.x
    }

    /// The squared distance from `point` to the box (0 inside).
    fn distance_squared(&self, point: Vec3A) -> f32 {
        let outside = (self.min - point).max(point - self.max).max(Vec3A::ZERO);
        outside.length_squared()
    }

    /// Whether the ray (given by its origin and the reciprocals of its direction's
    /// components) enters the box at some `t >= 0`: the slab test.
    fn hit_by(&self, origin: Vec3A, inverse_direction: Vec3A) -> bool {
        let t0 = (self.min - origin) * inverse_direction;
        let t1 = (self.max - origin) * inverse_direction;
        let near = t0.min(t1).max_element().max(0.0);
        let far = t0.max(t1).min_element();
        near <= far
    }
}

/// A node of the hierarchy: a box, and either two children (`count == 0`, the left child at
/// `first`, the right at `first + 1`) or `count` cylinders from `first` on.
#[derive(Clone, Copy, Debug)]
struct Node {
    bounds: Aabb,
    first: u32,
    count: u32,
}

/// Every segment of a set of strands as a cylinder, in a bounding-volume hierarchy.
#[derive(Clone, Debug)]
pub struct Occluders {
    cylinders: Vec<Cylinder>,
    nodes: Vec<Node>,
}

impl Occluders {
    /// The cylinders of every segment of `strands` with the given opacity, and their
    /// hierarchy.
    ///
    /// # Panics
    /// Never for valid `Strands` (the strand count fits in `u32` for any groom or `.hair`
    /// file, whose header stores it as `u32`).
    pub fn new(strands: &Strands, opacity: Opacity) -> Self {
        let cylinders = strands
            .segment_iter()
            .map(|segment| Cylinder::of_segment(strands, segment, opacity))
            .collect();
        Self::from_cylinders(cylinders)
    }

    /// The hierarchy over `cylinders` (their order is changed).
    pub fn from_cylinders(cylinders: Vec<Cylinder>) -> Self {
        let boxes: Vec<(Aabb, Vec3A)> = cylinders
            .iter()
            .map(|c| {
                let b = c.bounds();
                (b, b.centre())
            })
            .collect();
        let mut nodes = Vec::with_capacity(2 * cylinders.len() / LEAF_SIZE + 1);
        nodes.push(Node {
            bounds: Aabb::EMPTY,
            first: 0,
            count: 0,
        });
        let mut order: Vec<usize> = (0..cylinders.len()).collect();
        build(&mut nodes, 0, &mut order, &boxes, 0, 0);
        let cylinders = order.iter().map(|&k| cylinders[k]).collect();
        Self { cylinders, nodes }
    }

    /// The cylinders, in the hierarchy's order.
    pub fn cylinders(&self) -> &[Cylinder] {
        &self.cylinders
    }

    /// The transmittance `V` along the ray `origin + t direction`, `t > 0`: the product of
    /// `1 - opacity` over the cylinders it crosses, those of strand `own_strand` excluded
    /// (`None` excludes nothing). `direction` must be finite and non-zero (its length does not
    /// change the crossings; a non-finite one gives meaningless ones). Returns 0 as soon as the
    /// product falls below [`NEGLIGIBLE_TRANSMITTANCE`] (an absolute error below that).
    pub fn transmittance(&self, origin: Vec3, direction: Vec3, own_strand: Option<u32>) -> f32 {
        let inverse = safe_inverse(direction);
        let ray_origin = Vec3A::from(origin);
        let own = own_strand.unwrap_or(u32::MAX);
        let mut v = 1.0_f32;
        self.visit(
            |bounds| bounds.hit_by(ray_origin, inverse),
            |leaf| {
                for cylinder in leaf {
                    if cylinder.strand != own && cylinder.crossed_by(origin, direction) {
                        v *= cylinder.transmission;
                    }
                }
                if v < NEGLIGIBLE_TRANSMITTANCE {
                    v = 0.0;
                    return ControlFlow::Break(());
                }
                ControlFlow::Continue(())
            },
        );
        v
    }

    /// The first cylinder the ray `origin + t direction` enters at `t > 0` and that `t` (the
    /// ray starting inside a cylinder enters it at `t = 0`), or `None` if it crosses none.
    pub fn first_hit(&self, origin: Vec3, direction: Vec3) -> Option<(f32, &Cylinder)> {
        self.first_where(origin, direction, |_, _| true)
    }

    /// The first cylinder not of strand `own_strand` that the ray `origin + t direction`
    /// enters from outside at `t > 0`, and that `t`: cylinders holding `origin` (fibres that
    /// overlap the one the ray leaves) are passed through, so a ray leaving a fibre of
    /// `own_strand` never stops where it starts.
    pub fn next_entry(
        &self,
        origin: Vec3,
        direction: Vec3,
        own_strand: Option<u32>,
    ) -> Option<(f32, &Cylinder)> {
        let own = own_strand.unwrap_or(u32::MAX);
        self.first_where(origin, direction, |c, lo| c.strand != own && lo > 0.0)
    }

    /// The first cylinder crossed at `t > 0` among those `accept(cylinder, entry)` accepts
    /// (`entry` the ray parameter where the line enters it, possibly negative).
    fn first_where(
        &self,
        origin: Vec3,
        direction: Vec3,
        accept: impl Fn(&Cylinder, f32) -> bool,
    ) -> Option<(f32, &Cylinder)> {
        let inverse = safe_inverse(direction);
        let ray_origin = Vec3A::from(origin);
        let mut best: Option<(f32, &Cylinder)> = None;
        self.visit(
            |bounds| bounds.hit_by(ray_origin, inverse),
            |leaf| {
                for cylinder in leaf {
                    let Some((lo, hi)) = cylinder.ray_interval(origin, direction) else {
                        continue;
                    };
                    let entry = lo.max(0.0);
                    if hi > 0.0 && accept(cylinder, lo) && best.is_none_or(|(t, _)| entry < t) {
                        best = Some((entry, cylinder));
                    }
                }
                ControlFlow::Continue(())
            },
        );
        best
    }

    /// Appends to `out` every cylinder not of strand `own_strand` whose surface comes within
    /// `radius` of `point` (its axis within `radius` plus its own radius).
    pub fn near(&self, point: Vec3, radius: f32, own_strand: Option<u32>, out: &mut Vec<Cylinder>) {
        let own = own_strand.unwrap_or(u32::MAX);
        let centre = Vec3A::from(point);
        self.visit(
            |bounds| bounds.distance_squared(centre) <= radius * radius,
            |leaf| {
                let near =
                    |c: &&Cylinder| c.strand != own && c.axis_distance(point) < radius + c.radius;
                out.extend(leaf.iter().filter(near));
                ControlFlow::Continue(())
            },
        );
    }

    /// Walks the hierarchy depth first into every node whose box `enters` accepts, calling
    /// `leaf` with each leaf's cylinders until it breaks.
    fn visit<'a>(
        &'a self,
        enters: impl Fn(&Aabb) -> bool,
        mut leaf: impl FnMut(&'a [Cylinder]) -> ControlFlow<()>,
    ) {
        let mut stack = [0u32; STACK];
        // Without cylinders the root is an empty leaf, whose count 0 would read as a branch.
        let mut depth = usize::from(!self.cylinders.is_empty());
        while depth > 0 {
            depth -= 1;
            let node = self.nodes[stack[depth] as usize];
            if !enters(&node.bounds) {
                continue;
            }
            if node.count == 0 {
                stack[depth] = node.first;
                stack[depth + 1] = node.first + 1;
                depth += 2;
                continue;
            }
            let range = node.first as usize..(node.first + node.count) as usize;
            if leaf(&self.cylinders[range]).is_break() {
                return;
            }
        }
    }
}

/// Builds node `index` over the cylinders `order[..]` (indices into `boxes`), splitting by the
/// binned surface-area heuristic along the axis of largest centroid extent (at the median from
/// [`MEDIAN_DEPTH`] on); `offset` is the position of `order[0]` among all cylinders.
fn build(
    nodes: &mut Vec<Node>,
    index: usize,
    order: &mut [usize],
    boxes: &[(Aabb, Vec3A)],
    offset: usize,
    depth: usize,
) {
    let bounds = order.iter().fold(Aabb::EMPTY, |b, &k| b.union(boxes[k].0));
    let split = if order.len() <= LEAF_SIZE {
        None
    } else if depth >= MEDIAN_DEPTH {
        Some(order.len() / 2)
    } else {
        Some(best_split(order, boxes))
    };
    let Some(mid) = split else {
        nodes[index] = Node {
            bounds,
            first: offset as u32,
            count: order.len() as u32,
        };
        return;
    };
    let left = nodes.len();
    nodes.push(Node {
        bounds: Aabb::EMPTY,
        first: 0,
        count: 0,
    });
    nodes.push(Node {
        bounds: Aabb::EMPTY,
        first: 0,
        count: 0,
    });
    nodes[index] = Node {
        bounds,
        first: left as u32,
        count: 0,
    };
    let (low, high) = order.split_at_mut(mid);
    build(nodes, left, low, boxes, offset, depth + 1);
    build(nodes, left + 1, high, boxes, offset + mid, depth + 1);
}

/// Reorders `order` so that its first `mid` cylinders form the left child, and returns `mid`
/// (the middle when every centroid is equal or the best cut leaves a side empty).
fn best_split(order: &mut [usize], boxes: &[(Aabb, Vec3A)]) -> usize {
    let centres = order.iter().fold(Aabb::EMPTY, |b, &k| {
        b.union(Aabb {
            min: boxes[k].1,
            max: boxes[k].1,
        })
    });
    let extent = centres.max - centres.min;
    let axis = extent.max_position();
    if extent[axis].is_nan() || extent[axis] <= 0.0 {
        // Every centroid equal: split in the middle so leaves stay small.
        return order.len() / 2;
    }
    let bin_of = |k: usize| {
        let t = (boxes[k].1[axis] - centres.min[axis]) / extent[axis];
        ((t * BINS as f32) as usize).min(BINS - 1)
    };
    let mut bins = [(Aabb::EMPTY, 0usize); BINS];
    for &k in order.iter() {
        let bin = &mut bins[bin_of(k)];
        *bin = (bin.0.union(boxes[k].0), bin.1 + 1);
    }
    let mut best = (f32::INFINITY, 0);
    for cut in 1..BINS {
        let (left, right) = bins.split_at(cut);
        let cost = |side: &[(Aabb, usize)]| {
            let (b, n) = side
                .iter()
                .fold((Aabb::EMPTY, 0), |(b, n), &(c, m)| (b.union(c), n + m));
            b.half_area() * n as f32
        };
        let total = cost(left) + cost(right);
        if total < best.0 {
            best = (total, cut);
        }
    }
    let cut = best.1;
    let mid = partition(order, |k| bin_of(k) < cut);
    if mid == 0 || mid == order.len() {
        order.len() / 2
    } else {
        mid
    }
}

/// Moves the elements satisfying `left` to the front, keeping each side's order (stable, so
/// the hierarchy does not depend on anything but the input); returns their count.
fn partition(order: &mut [usize], left: impl Fn(usize) -> bool) -> usize {
    let (mut low, high): (Vec<usize>, Vec<usize>) = order.iter().partition(|&&k| left(k));
    let mid = low.len();
    low.extend(high);
    order.copy_from_slice(&low);
    mid
}
