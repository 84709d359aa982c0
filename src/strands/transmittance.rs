//! Gerard's per-vertex transmittance: `V(x, w)` of every vertex `x` of a set of strands,
//! projected onto real spherical harmonics (the crate's convention, [`crate::sh`]) and
//! stored per vertex, as Gerard et al.'s "Fast real-time shading for polygonal hair"
//! (section 2.2) stores it in the vertex attributes in place of deep opacity maps.
//!
//! `V(x, w)` is the product of `1 - opacity` over the segments the ray `x + t w`, `t > 0`,
//! crosses, the vertex's own strand excluded ([`super::occluders`] defines the cylinders).
//! Two bakers project it:
//!
//! - [`Baker::Exact`], the reference: rays cast through the bounding-volume hierarchy in `n`
//!   directions of a spherical Fibonacci set, equal weights `4 pi / n`. `V` is piecewise
//!   constant with jumps along the cylinders' silhouettes, so no quadrature is exact for it:
//!   the error falls about like `1 / n` (measured against a closed form in the tests, and as
//!   the change between `n` and `4 n` on grooms in the README).
//! - [`Baker::Fast`]: exact near, statistical far ([`FastSettings`]). The sphere is cut into
//!   `2 n^2` equal-area cells (`n` bands of equal height in `z`, `2 n` equal sectors in
//!   azimuth). Within `near_cells` grid cells of the vertex, the cylinders found by one query
//!   of the hierarchy are crossed exactly by `s x s` rays per cell (stratified in `z` and
//!   azimuth, eight rays at a time in SIMD lanes), their transmittances averaged; beyond it
//!   the strands are a medium ([`super::density`]) whose optical depth is marched through a
//!   pyramid of grids once per cell, along the cell's central direction. The cell's `V` is
//!   the product of the two, and the projection is the midpoint rule over the cells. Its
//!   error against the exact baker is dominated by the number of cells (it falls about like
//!   `1 / n`); the README states it per groom.
//!
//! Both project `1 - V` by their rule and subtract it from the exact projection of the
//! constant 1 (`sqrt(4 pi)` in `Y_00`, 0 elsewhere): an unoccluded vertex gives exactly that,
//! and the rule's error applies to the occlusion only.
//!
//! Both run in parallel with rayon, vertex by vertex; each vertex's coefficients are computed
//! by one thread in a fixed order, so the output does not depend on the thread count.

use super::density::{ExtinctionGrid, March, StrandMoments, MAX_GRID_CELLS};
use super::occluders::{CrossingSetup, Cylinder, Occluders, Opacity};
use super::{Segment, Strands};
use crate::error::ParamError;
use crate::real::Real;
use crate::sh::{eval_sh_f64, eval_sh_f64_into};
use core::ops::Range;
use glam::{DVec3, Vec3};
use rand_pcg::rand_core::{RngCore, SeedableRng};
use rand_pcg::Pcg64Mcg;
use rayon::prelude::*;
use std::sync::atomic::{AtomicUsize, Ordering};
use wide::f32x8;

/// The highest band a bake may ask for.
pub const MAX_BAKE_LMAX: usize = 16;
/// The most coefficients a bake may produce (vertices times `(lmax + 1)^2`): 2^28, 1 GiB of
/// f32.
pub const MAX_BAKE_VALUES: usize = 1 << 28;
/// The most directions per vertex of the exact baker.
pub const MAX_DIRECTIONS: usize = 1 << 22;

/// How to project `V`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Baker {
    /// Rays in `directions` directions of a spherical Fibonacci set, equal weights.
    Exact {
        /// The number of directions per vertex, in `[1, MAX_DIRECTIONS]`.
        directions: usize,
    },
    /// Exact crossings near the vertex, a medium beyond.
    Fast(FastSettings),
}

/// The settings of the fast baker (see the module documentation).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FastSettings {
    /// `n`: the sphere is cut into `2 n^2` cells, in `[1, 64]`.
    pub bands: usize,
    /// `s`: near-field rays per cell, `s x s`, in `[1, 16]`.
    pub near_samples: usize,
    /// The radius within which cylinders are crossed exactly, in cells of the extinction
    /// grid (so that the settings do not depend on the file's units), in `[0, 16]`.
    pub near_cells: f32,
    /// Cells of the extinction grid along the longest side of the strands' bounding box, in
    /// `[1, 256]` (see [`ExtinctionGrid::new`] for its memory).
    pub grid_cells: usize,
    /// The far-field march's step at distance `t` is `max(h, t cone_steps sqrt(4 pi / K))`
    /// for `K` cells (a cone of a cell's solid angle, times this), in `[0, 4]`.
    pub cone_steps: f32,
}

impl Default for FastSettings {
    fn default() -> Self {
        Self {
            bands: 8,
            near_samples: 2,
            near_cells: 2.0,
            grid_cells: 112,
            cone_steps: 0.6,
        }
    }
}

impl Baker {
    /// The exact baker's default direction count (its error is measured in the tests and the
    /// README).
    pub const EXACT_DIRECTIONS: usize = 16_384;

    /// The baker's name, as `transmittance.json` writes it.
    pub fn name(&self) -> &'static str {
        match self {
            Baker::Exact { .. } => "exact",
            Baker::Fast(_) => "fast",
        }
    }
}

/// What to bake.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BakeSettings {
    /// The highest SH band, in `[0, MAX_BAKE_LMAX]`: `(lmax + 1)^2` coefficients per vertex.
    pub lmax: usize,
    /// Where the segments' opacities come from.
    pub opacity: Opacity,
    /// The method.
    pub baker: Baker,
}

/// The baked coefficients: `(lmax + 1)^2` per vertex, vertex-major, index `l (l + 1) + m`
/// within a vertex, for the vertices `vertices` of the strands.
#[derive(Clone, Debug, PartialEq)]
pub struct Transmittance {
    /// The highest band.
    pub lmax: usize,
    /// The point indices baked, in order.
    pub vertices: Range<usize>,
    /// The coefficients.
    pub coefficients: Vec<f32>,
}

impl Transmittance {
    /// Coefficients per vertex, `(lmax + 1)^2`.
    pub fn stride(&self) -> usize {
        (self.lmax + 1) * (self.lmax + 1)
    }

    /// The coefficients of the `k`-th vertex baked (point `vertices.start + k`).
    ///
    /// # Panics
    /// If `k >= vertices.len()`.
    pub fn vertex(&self, k: usize) -> &[f32] {
        let n = self.stride();
        &self.coefficients[k * n..(k + 1) * n]
    }
}

/// How far one bake is from another (the reference) at the same vertices.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BakeComparison {
    /// The number of vertices compared.
    pub vertices: usize,
    /// The root mean square over vertices and coefficients of the coefficients' difference.
    pub coefficient_rms: f64,
    /// The largest difference of one coefficient.
    pub coefficient_max: f64,
    /// The root mean square over vertices and random directions of the difference of the
    /// reconstructed `V` (`sum c_lm Y_lm(w)`).
    pub v_rms: f64,
    /// The largest difference of the reconstructed `V` at one vertex and direction.
    pub v_max: f64,
    /// The reference's mean `V` (its mean `Y_00` coefficient over `sqrt(4 pi)`), for scale.
    pub reference_mean_v: f64,
}

/// Compares `baked` with `reference`: their coefficients, and the `V` they reconstruct at
/// `directions` random directions per vertex (uniform on the sphere, from a PCG stream seeded
/// by `seed`, the same directions for both).
///
/// # Errors
/// [`ParamError::OutOfRange`] if the bakes differ in band limit or vertices, or `directions`
/// is 0 or above 10^6.
pub fn compare(
    baked: &Transmittance,
    reference: &Transmittance,
    directions: usize,
    seed: u64,
) -> Result<BakeComparison, ParamError> {
    let same_shape = baked.lmax == reference.lmax && baked.vertices == reference.vertices;
    ParamError::check(
        "reference lmax",
        reference.lmax as f64,
        "must equal the bake's lmax, over the same vertices",
        |_| same_shape,
    )?;
    ParamError::check(
        "directions",
        directions as f64,
        "must be in [1, 10^6]",
        |n| (1.0..=1e6).contains(&n),
    )?;
    let mut rng = Pcg64Mcg::seed_from_u64(seed);
    let mut uniform = || (rng.next_u64() >> 11) as f64 / (1u64 << 53) as f64;
    let bases: Vec<Vec<f64>> = (0..directions)
        .map(|_| {
            let z = 2.0 * uniform() - 1.0;
            let phi = core::f64::consts::TAU * uniform();
            let s = (1.0 - z * z).max(0.0).sqrt();
            eval_sh_f64(baked.lmax, DVec3::new(s * phi.cos(), s * phi.sin(), z))
        })
        .collect::<Result<_, _>>()?;
    let vertices = baked.vertices.len();
    let (mut squares, mut largest, mut v_squares, mut v_largest, mut mean) =
        (0.0, 0.0f64, 0.0, 0.0f64, 0.0);
    for k in 0..vertices {
        let (a, b) = (baked.vertex(k), reference.vertex(k));
        let difference: Vec<f64> = a
            .iter()
            .zip(b)
            .map(|(a, b)| f64::from(*a) - f64::from(*b))
            .collect();
        squares += difference.iter().map(|d| d * d).sum::<f64>();
        largest = difference.iter().fold(largest, |m, d| m.max(d.abs()));
        for y in &bases {
            let dv: f64 = difference.iter().zip(y).map(|(d, y)| d * y).sum();
            v_squares += dv * dv;
            v_largest = v_largest.max(dv.abs());
        }
        mean += f64::from(b[0]);
    }
    let count = vertices.max(1) as f64;
    Ok(BakeComparison {
        vertices,
        coefficient_rms: (squares / (count * baked.stride() as f64)).sqrt(),
        coefficient_max: largest,
        v_rms: (v_squares / (count * directions as f64)).sqrt(),
        v_max: v_largest,
        reference_mean_v: mean / count / (4.0 * core::f64::consts::PI).sqrt(),
    })
}

pub use crate::quadrature::fibonacci_directions;

/// The SH projection of `V` at the vertices `vertices` of `strands`; `progress(done, total)`
/// is called as vertices complete (from any thread).
///
/// # Errors
/// [`ParamError::OutOfRange`] if `settings.lmax > MAX_BAKE_LMAX`, the direction count is
/// outside `[1, MAX_DIRECTIONS]`, a uniform opacity is outside `[0, 1]`, `vertices` is not a
/// range of the strands' points, or the output would exceed `MAX_BAKE_VALUES` values.
pub fn bake(
    strands: &Strands,
    vertices: Range<usize>,
    settings: &BakeSettings,
    progress: &(dyn Fn(usize, usize) + Sync),
) -> Result<Transmittance, ParamError> {
    check(strands, &vertices, settings)?;
    let occluders = Occluders::new(strands, settings.opacity);
    let coefficients = match settings.baker {
        Baker::Exact { directions } => {
            let rule = WeightedBasis::new(settings.lmax, &fibonacci_directions(directions))?;
            let transmittance = |points: Range<usize>, values: &mut [f32]| {
                let rows = values.chunks_exact_mut(rule.directions.len());
                for (point, row) in points.zip(rows) {
                    let origin = strands.points()[point];
                    let own = own_strand(strands, point);
                    for (v, &d) in row.iter_mut().zip(&rule.directions) {
                        *v = occluders.transmittance(origin, d, own);
                    }
                }
            };
            project_vertices(&vertices, &rule, transmittance, progress)
        }
        Baker::Fast(fast) => {
            let cells = EqualAreaCells::new(fast.bands);
            let rule = WeightedBasis::new(settings.lmax, &cells.centres())?;
            let (min, max) = bounding_box(strands.points());
            let grid = ExtinctionGrid::new(occluders.cylinders(), min, max, fast.grid_cells)?;
            let baker = FastBaker {
                fast,
                directions: &rule.directions,
                near_groups: DirectionGroup::all(
                    (0..cells.count()).flat_map(|k| cells.samples(k, fast.near_samples)),
                ),
                grid,
                occluders: &occluders,
                strands,
                opacity: settings.opacity,
            };
            let transmittance =
                |points: Range<usize>, values: &mut [f32]| baker.transmittance(points, values);
            project_vertices(&vertices, &rule, transmittance, progress)
        }
    };
    Ok(Transmittance {
        lmax: settings.lmax,
        vertices,
        coefficients,
    })
}

/// The coefficients of every vertex in `vertices`, in parallel, in runs of [`RUN`]
/// consecutive vertices: `transmittance(points, values)` writes `V` at the rule's nodes for
/// the run's points, point-major (a run's points are its own, so the result does not depend on
/// how runs are spread over threads).
fn project_vertices(
    vertices: &Range<usize>,
    rule: &WeightedBasis,
    transmittance: impl Fn(Range<usize>, &mut [f32]) + Sync,
    progress: &(dyn Fn(usize, usize) + Sync),
) -> Vec<f32> {
    let (stride, nodes) = (rule.stride, rule.directions.len());
    let mut coefficients = vec![0.0f32; vertices.len() * stride];
    let done = AtomicUsize::new(0);
    let total = vertices.len();
    coefficients
        .par_chunks_mut(RUN * stride)
        .enumerate()
        .for_each(|(run, out)| {
            let first = vertices.start + run * RUN;
            let count = out.len() / stride;
            let mut values = vec![0.0f32; count * nodes];
            transmittance(first..first + count, &mut values);
            for (c, v) in out.chunks_exact_mut(stride).zip(values.chunks_exact(nodes)) {
                rule.project(v, c);
            }
            progress(done.fetch_add(count, Ordering::Relaxed) + count, total);
        });
    coefficients
}

/// Vertices per run of [`project_vertices`].
const RUN: usize = 16;

/// The strand of `point` (excluded from its transmittance).
fn own_strand(strands: &Strands, point: usize) -> Option<u32> {
    strands.strand_of_point(point).map(|s| s as u32)
}

/// The smallest box holding every point.
fn bounding_box(points: &[Vec3]) -> (Vec3, Vec3) {
    points.iter().fold(
        (Vec3::splat(f32::INFINITY), Vec3::splat(f32::NEG_INFINITY)),
        |(lo, hi), &p| (lo.min(p), hi.max(p)),
    )
}

/// The sphere cut into `2 n^2` cells of equal area: `n` bands of equal height in `z` (from
/// `z = 1` down), each of `2 n` equal sectors in azimuth (from the +X axis towards +Y).
#[derive(Clone, Copy, Debug)]
struct EqualAreaCells {
    bands: usize,
}

impl EqualAreaCells {
    fn new(bands: usize) -> Self {
        Self { bands }
    }

    fn count(&self) -> usize {
        2 * self.bands * self.bands
    }

    /// The direction at fractional position `(u, v)` in `[0, 1]^2` of cell `k`.
    fn direction(&self, k: usize, u: f64, v: f64) -> DVec3 {
        let sectors = 2 * self.bands;
        let (band, sector) = (k / sectors, k % sectors);
        let z = 1.0 - 2.0 * (band as f64 + u) / self.bands as f64;
        let phi = core::f64::consts::TAU * (sector as f64 + v) / sectors as f64;
        let s = (1.0 - z * z).max(0.0).sqrt();
        DVec3::new(s * phi.cos(), s * phi.sin(), z)
    }

    fn centres(&self) -> Vec<DVec3> {
        (0..self.count())
            .map(|k| self.direction(k, 0.5, 0.5))
            .collect()
    }

    /// The `s x s` stratified directions of cell `k` (midpoints of its sub-cells).
    fn samples(&self, k: usize, s: usize) -> impl Iterator<Item = Vec3> + '_ {
        (0..s * s).map(move |j| {
            let (a, b) = (j / s, j % s);
            let u = (a as f64 + 0.5) / s as f64;
            let v = (b as f64 + 0.5) / s as f64;
            self.direction(k, u, v).as_vec3()
        })
    }
}

/// The fast baker's state shared by every vertex.
struct FastBaker<'a> {
    fast: FastSettings,
    /// The cells' central directions.
    directions: &'a [Vec3],
    /// The near field's `s x s` directions per cell, cell after cell, eight to a group.
    near_groups: Vec<DirectionGroup>,
    grid: ExtinctionGrid,
    occluders: &'a Occluders,
    strands: &'a Strands,
    opacity: Opacity,
}

impl FastBaker<'_> {
    /// Far-field optical depths above this are taken as opaque (`e^-17 < 2^-24`).
    const DEPTH_CUTOFF: f32 = 17.0;

    /// `V` per cell at each of `points`, point-major: the near field's transmittance times
    /// the far field's.
    fn transmittance(&self, points: Range<usize>, values: &mut [f32]) {
        let cells = self.directions.len();
        let mut own: Option<(u32, StrandMoments)> = None;
        let mut near = NearScratch::default();
        for (point, row) in points.zip(values.chunks_exact_mut(cells)) {
            let strand = own_strand(self.strands, point);
            if own.as_ref().map(|(s, _)| *s) != strand {
                own = strand.map(|s| (s, self.strand_moments(s)));
            }
            self.near_field(point, strand, &mut near, row);
            self.far_field(point, own.as_ref().map(|(_, m)| m), row);
        }
    }

    /// The near field's transmittance per cell at `point` (the mean over the cell's rays).
    fn near_field(
        &self,
        point: usize,
        own: Option<u32>,
        scratch: &mut NearScratch,
        row: &mut [f32],
    ) {
        let origin = self.strands.points()[point];
        let radius = self.near_radius();
        scratch.cylinders.clear();
        self.occluders
            .near(origin, radius, own, &mut scratch.cylinders);
        scratch.lanes.clear();
        scratch.lanes.resize(self.near_groups.len(), f32x8::ONE);
        near_field(
            &scratch.cylinders,
            origin,
            radius,
            &self.near_groups,
            &mut scratch.lanes,
        );
        let per_cell = self.fast.near_samples * self.fast.near_samples;
        let mut samples = scratch.lanes.iter().flat_map(|l| l.to_array());
        for v in row.iter_mut() {
            *v = samples.by_ref().take(per_cell).sum::<f32>() / per_cell as f32;
        }
    }

    /// Multiplies each cell's value in `row` by the far field's transmittance from `point`
    /// along the cell's central direction, the medium without the moments `own`.
    fn far_field(&self, point: usize, own: Option<&StrandMoments>, row: &mut [f32]) {
        let origin = self.strands.points()[point];
        let march = March {
            start: self.near_radius(),
            cone: self.fast.cone_steps * (4.0 * core::f32::consts::PI / row.len() as f32).sqrt(),
            cutoff: Self::DEPTH_CUTOFF,
        };
        for (v, &w) in row.iter_mut().zip(self.directions) {
            if *v > 0.0 {
                *v *= (-self.grid.optical_depth(origin, w, march, own)).exp();
            }
        }
    }

    /// The radius of the near field.
    fn near_radius(&self) -> f32 {
        self.fast.near_cells * self.grid.cell()
    }

    /// The moments strand `strand` deposited into the grid.
    fn strand_moments(&self, strand: u32) -> StrandMoments {
        let points = self.strands.strand_points(strand as usize).unwrap_or(0..0);
        let cylinders: Vec<Cylinder> = (points.start..points.end.saturating_sub(1))
            .map(|start| {
                let segment = Segment {
                    strand: strand as usize,
                    start,
                };
                Cylinder::of_segment(self.strands, segment, self.opacity)
            })
            .collect();
        self.grid.strand_moments(cylinders.iter())
    }
}

/// The near field's buffers, kept from vertex to vertex.
#[derive(Default)]
struct NearScratch {
    cylinders: Vec<Cylinder>,
    lanes: Vec<f32x8>,
}

/// Multiplies each direction's lane of `out` (1 to start with) by the transmission of every
/// cylinder in `near` that the ray from `origin` in that direction enters at some
/// `0 <= t < radius`. A group of directions is skipped for a cylinder when the cone around
/// the group's directions misses the cone from `origin` around the cylinder's bounding sphere.
fn near_field(
    near: &[Cylinder],
    origin: Vec3,
    radius: f32,
    groups: &[DirectionGroup],
    out: &mut [f32x8],
) {
    let (zero, radius) = (f32x8::ZERO, f32x8::splat(radius));
    for cylinder in near {
        let setup = CrossingSetup::<f32x8>::new(cylinder, origin);
        let transmission = f32x8::splat(cylinder.transmission);
        let bounds = BoundingCone::of(cylinder, origin);
        for (o, group) in out.iter_mut().zip(groups) {
            if bounds.as_ref().is_some_and(|b| b.misses(group)) {
                continue;
            }
            let (lo, hi, hit) = setup.interval(group.lanes);
            let crossed = hit & zero.lt(hi) & lo.max(zero).lt(radius);
            *o = crossed.select(*o * transmission, *o);
        }
    }
}

/// Eight directions in lanes (x, y, z), with the cone that holds them: its axis and the cosine
/// and sine of its half-angle.
struct DirectionGroup {
    lanes: [f32x8; 3],
    axis: Vec3,
    cos: f32,
    sin: f32,
}

impl DirectionGroup {
    /// `directions` eight to a group, the last group padded with its first direction.
    fn all(directions: impl Iterator<Item = Vec3>) -> Vec<Self> {
        let directions: Vec<Vec3> = directions.collect();
        directions.chunks(8).map(Self::new).collect()
    }

    fn new(chunk: &[Vec3]) -> Self {
        let lane = |k: usize| chunk.get(k).copied().unwrap_or(chunk[0]);
        let component = |axis: usize| f32x8::new(core::array::from_fn(|k| lane(k)[axis]));
        let axis = chunk
            .iter()
            .sum::<Vec3>()
            .try_normalize()
            .unwrap_or(chunk[0]);
        // The cone's cosine, lowered by a margin so that rounding never drops a direction.
        let cos = chunk.iter().map(|d| d.dot(axis)).fold(1.0f32, f32::min) - 1e-4;
        let cos = cos.max(-1.0);
        Self {
            lanes: [component(0), component(1), component(2)],
            axis,
            cos,
            sin: (1.0 - cos * cos).max(0.0).sqrt(),
        }
    }
}

/// The cone of directions from a point that can meet a cylinder: around the direction of its
/// bounding sphere's centre, of half-angle `asin(sphere radius / distance)`.
struct BoundingCone {
    axis: Vec3,
    cos: f32,
    sin: f32,
}

impl BoundingCone {
    /// The cone from `origin` around `cylinder`, or `None` when `origin` is inside its bounding
    /// sphere (every direction may meet it).
    fn of(cylinder: &Cylinder, origin: Vec3) -> Option<Self> {
        let centre = cylinder.base + cylinder.axis * (0.5 * cylinder.length);
        let sphere =
            (0.25 * cylinder.length * cylinder.length + cylinder.radius * cylinder.radius).sqrt();
        let to_centre = centre - origin;
        let distance = to_centre.length();
        let sin = sphere * 1.0001 / distance;
        (sin < 1.0).then(|| Self {
            axis: to_centre / distance,
            cos: (1.0 - sin * sin).sqrt(),
            sin,
        })
    }

    /// Whether every direction of `group` is outside the cone: the angle between the axes
    /// exceeds the sum of the half-angles (both below a right angle, so the sum is below pi).
    fn misses(&self, group: &DirectionGroup) -> bool {
        let cos_sum = self.cos * group.cos - self.sin * group.sin;
        self.axis.dot(group.axis) < cos_sum
    }
}

fn check(
    strands: &Strands,
    vertices: &Range<usize>,
    settings: &BakeSettings,
) -> Result<(), ParamError> {
    ParamError::check("lmax", settings.lmax as f64, "must be in [0, 16]", |l| {
        l <= MAX_BAKE_LMAX as f64
    })?;
    if let Opacity::Uniform(a) = settings.opacity {
        ParamError::check("opacity", f64::from(a), "must be in [0, 1]", |a| {
            (0.0..=1.0).contains(&a)
        })?;
    }
    match settings.baker {
        Baker::Exact { directions } => {
            ParamError::check(
                "directions",
                directions as f64,
                "must be in [1, 4194304]",
                |n| n >= 1.0 && n <= MAX_DIRECTIONS as f64,
            )?;
        }
        Baker::Fast(fast) => fast.check()?,
    }
    let points = strands.point_count() as f64;
    ParamError::check(
        "vertices.end",
        vertices.end as f64,
        "must be at most the point count, and at least vertices.start",
        |end| end <= points && vertices.start <= vertices.end,
    )?;
    let values = vertices.len() as f64 * ((settings.lmax + 1) * (settings.lmax + 1)) as f64;
    ParamError::check(
        "vertices x (lmax + 1)^2",
        values,
        "must be at most 2^28 (bake fewer vertices or bands)",
        |n| n <= MAX_BAKE_VALUES as f64,
    )?;
    Ok(())
}

impl FastSettings {
    fn check(&self) -> Result<(), ParamError> {
        let in_range = |lo: f64, hi: f64| move |x: f64| (lo..=hi).contains(&x);
        ParamError::check(
            "bands",
            self.bands as f64,
            "must be in [1, 64]",
            in_range(1.0, 64.0),
        )?;
        ParamError::check(
            "near_samples",
            self.near_samples as f64,
            "must be in [1, 16]",
            in_range(1.0, 16.0),
        )?;
        ParamError::check(
            "near_cells",
            f64::from(self.near_cells),
            "must be in [0, 16]",
            in_range(0.0, 16.0),
        )?;
        ParamError::check(
            "grid_cells",
            self.grid_cells as f64,
            "must be in [1, 256]",
            in_range(1.0, MAX_GRID_CELLS as f64),
        )?;
        ParamError::check(
            "cone_steps",
            f64::from(self.cone_steps),
            "must be in [0, 4]",
            in_range(0.0, 4.0),
        )?;
        Ok(())
    }
}

/// A quadrature rule on the sphere with the SH basis weighted at its nodes: projecting values
/// at the nodes is one dot product per coefficient.
struct WeightedBasis {
    /// The nodes, in f32 for the ray caster.
    directions: Vec<Vec3>,
    /// `w_k Y_j(d_k)`, node-major.
    weighted: Vec<f64>,
    stride: usize,
}

impl WeightedBasis {
    /// The equal-weight rule on `nodes` (weights `4 pi / n`).
    fn new(lmax: usize, nodes: &[DVec3]) -> Result<Self, ParamError> {
        let stride = (lmax + 1) * (lmax + 1);
        let weight = 4.0 * core::f64::consts::PI / nodes.len() as f64;
        let mut weighted = vec![0.0; nodes.len() * stride];
        for (node, y) in nodes.iter().zip(weighted.chunks_exact_mut(stride)) {
            eval_sh_f64_into(lmax, *node, y)?;
            y.iter_mut().for_each(|y| *y *= weight);
        }
        Ok(Self {
            directions: nodes.iter().map(|d| d.as_vec3()).collect(),
            weighted,
            stride,
        })
    }

    /// The projection of the function with `values` at the nodes: the exact projection of 1
    /// (`sqrt(4 pi)` in `Y_00`) minus the rule's `sum_k w_k Y_j(d_k) (1 - values_k)`.
    fn project(&self, values: &[f32], out: &mut [f32]) {
        let mut sum = vec![0.0f64; self.stride];
        sum[0] = (4.0 * core::f64::consts::PI).sqrt();
        for (&v, y) in values.iter().zip(self.weighted.chunks_exact(self.stride)) {
            if v != 1.0 {
                let occlusion = 1.0 - f64::from(v);
                sum.iter_mut().zip(y).for_each(|(s, y)| *s -= occlusion * y);
            }
        }
        out.iter_mut().zip(&sum).for_each(|(o, s)| *o = *s as f32);
    }
}
