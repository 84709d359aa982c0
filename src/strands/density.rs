//! The strands as a participating medium: the far field of the fast transmittance baker
//! ([`super::transmittance::FastSettings`]), after Frostbite's fallback of a voxel density
//! with Beer-Lambert optical depth (Tafuri 2019).
//!
//! A ray through randomly placed cylinders of radius `r`, length `L` and unit axis `t`, `n`
//! of them per unit volume, meets on average `n 2 r L |sin(w, t)|` of them per unit length
//! (`2 r L |sin|` is a cylinder's projected area, its caps neglected). If the number of
//! crossings along a ray is Poisson distributed with mean `mu`, the expected transmittance
//! `E[(1 - a)^N]` is `exp(-a mu)` for opacity `a`; so the medium's extinction coefficient in
//! direction `w` is `sigma(w) = sum a_i 2 r_i L_i |sin(w, t_i)| / volume` over the segments in
//! a volume, and the far-field transmittance is `exp(-int sigma dt)`.
//!
//! The grid stores at each node the moments `A = sum w_i` and `T = sum w_i t_i t_i^T` with
//! `w_i = a_i 2 r_i L_i / h^3`, splatted trilinearly from points spaced at most half a cell
//! along every segment. `|sin(w, t)| = sqrt(1 - (w.t)^2)` is replaced by
//! `sqrt(1 - w^T T w / A)` of the interpolated moments (exact where the segments around a point
//! are parallel, an overestimate by Jensen's inequality elsewhere).
//!
//! [`ExtinctionGrid::optical_depth`] marches a ray by the midpoint rule with steps that grow
//! with the distance like a cone's width (`max(h, t cone)`, as voxel cone tracing does): the
//! far field only needs the resolution of the solid angle a direction stands for. A step of
//! `2^l h` or more reads level `l` of a pyramid of grids, each node-centred level filtered from
//! the one below with the tent `(1/4, 1/2, 1/4)` per axis (the moments are densities, so they
//! average), which keeps long steps from aliasing and their reads in cache.

use super::occluders::Cylinder;
use crate::error::ParamError;
use glam::Vec3;
use wide::f32x8;

/// The moments at a node: `A`, then `T`'s xx, yy, zz, xy, xz, yz, and a zero, in eight lanes.
type Moments = f32x8;

/// The most cells along the longest side of an [`ExtinctionGrid`].
pub const MAX_GRID_CELLS: usize = 256;

/// `sigma_w = sqrt(A (A - w^T T w))` of the moments `m` (0 where `A <= 0`).
fn extinction(m: Moments, w: Vec3) -> f32 {
    let [a, xx, yy, zz, xy, xz, yz, _] = m.to_array();
    if a <= 0.0 {
        return 0.0;
    }
    let along = w.x * w.x * xx
        + w.y * w.y * yy
        + w.z * w.z * zz
        + 2.0 * (w.x * w.y * xy + w.x * w.z * xz + w.y * w.z * yz);
    (a * (a - along).max(0.0)).sqrt()
}

/// A pyramid of grids of extinction moments over a box: level `l` has node spacing `2^l h`.
#[derive(Clone, Debug)]
pub struct ExtinctionGrid {
    levels: Vec<Level>,
}

/// How [`ExtinctionGrid::optical_depth`] marches.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct March {
    /// Where the march starts along the ray.
    pub start: f32,
    /// Steps are `max(h, t cone)` at distance `t`.
    pub cone: f32,
    /// The march stops once the depth exceeds this.
    pub cutoff: f32,
}

/// The moments one strand deposited into level 0 of an [`ExtinctionGrid`]: per node, and the
/// cells that have such a node as a corner, each in an open-addressing hash table (at most
/// half full, so a lookup probes about once).
#[derive(Clone, Debug)]
pub struct StrandMoments {
    nodes: HashTable<Moments>,
    cells: HashTable<()>,
}

impl StrandMoments {
    /// The tables of the `(node, moments)` contributions on `level`, summed per node.
    fn new(level: &Level, contributions: &[(usize, Moments)]) -> Self {
        let mut nodes = HashTable::with_capacity(contributions.len());
        let mut cells = HashTable::with_capacity(8 * contributions.len());
        for &(node, m) in contributions {
            *nodes.entry(node) += m;
            let [x, y, z] = level.layout.coordinates(node);
            for k in 0..8 {
                let (dx, dy, dz) = (k & 1, (k >> 1) & 1, k >> 2);
                if x >= dx && y >= dy && z >= dz {
                    cells.entry(level.layout.index([x - dx, y - dy, z - dz]));
                }
            }
        }
        Self { nodes, cells }
    }

    /// The strand's moments at `p`, interpolated trilinearly on `level` (level 0 of the grid
    /// they were deposited in); one lookup when the cell of `p` has none of them.
    fn moments_at(&self, level: &Level, p: Vec3) -> Moments {
        let Some((base, f)) = level.cell_of(p) else {
            return f32x8::ZERO;
        };
        if self.cells.get(level.layout.index(base)).is_none() {
            return f32x8::ZERO;
        }
        let mut m = f32x8::ZERO;
        for (node, weight) in level.corners(base, f) {
            if let Some(value) = self.nodes.get(node) {
                m += *value * weight;
            }
        }
        m
    }
}

/// A hash table from node or cell indices to `T`, open addressing with linear probing.
#[derive(Clone, Debug)]
struct HashTable<T> {
    /// `(key + 1, value)`; key 0 marks an empty slot.
    slots: Vec<(usize, T)>,
}

impl<T: Copy + Default> HashTable<T> {
    /// A table for up to `capacity` keys, at most half full.
    fn with_capacity(capacity: usize) -> Self {
        let size = (2 * capacity).next_power_of_two().max(8);
        Self {
            slots: vec![(0, T::default()); size],
        }
    }

    /// The slot holding `key`, or the empty slot where it belongs.
    fn slot(&self, key: usize) -> usize {
        let mask = self.slots.len() - 1;
        let mut slot = ((key as u64).wrapping_mul(0x9e37_79b9_7f4a_7c15) >> 32) as usize & mask;
        while self.slots[slot].0 != 0 && self.slots[slot].0 != key + 1 {
            slot = (slot + 1) & mask;
        }
        slot
    }

    /// The value of `key`, inserted as `T::default()` if absent.
    fn entry(&mut self, key: usize) -> &mut T {
        let slot = self.slot(key);
        self.slots[slot].0 = key + 1;
        &mut self.slots[slot].1
    }

    /// The value of `key`, if present.
    fn get(&self, key: usize) -> Option<&T> {
        let (stored, value) = &self.slots[self.slot(key)];
        (*stored != 0).then_some(value)
    }
}

/// One grid of the pyramid.
#[derive(Clone, Debug)]
struct Level {
    /// The position of node (0, 0, 0).
    origin: Vec3,
    /// The node spacing.
    cell: f32,
    /// Where each node's moments are stored.
    layout: Layout,
    moments: Vec<Moments>,
}

/// The storage order of a grid's nodes: bricks of 4 x 4 x 4 nodes, x fastest within a brick
/// and among bricks, so that the eight corners of a cell are mostly in one 2 KiB brick (one
/// or two cache misses where a row-major layout, whose z neighbours are a slice apart, takes
/// four).
#[derive(Clone, Copy, Debug, PartialEq)]
struct Layout {
    /// Nodes per axis.
    nodes: [usize; 3],
    /// Bricks per axis.
    bricks: [usize; 3],
}

impl Layout {
    fn new(nodes: [usize; 3]) -> Self {
        Self {
            nodes,
            bricks: nodes.map(|n| n.div_ceil(4)),
        }
    }

    /// The number of stored nodes (the bricks' nodes past the grid's end included).
    fn len(&self) -> usize {
        64 * self.bricks[0] * self.bricks[1] * self.bricks[2]
    }

    /// Where node `(x, y, z)` is stored.
    fn index(&self, [x, y, z]: [usize; 3]) -> usize {
        let brick = ((z >> 2) * self.bricks[1] + (y >> 2)) * self.bricks[0] + (x >> 2);
        64 * brick + ((z & 3) << 4 | (y & 3) << 2 | (x & 3))
    }

    /// The node stored at `index` (the inverse of [`Layout::index`]; past the grid's end for
    /// the padding of the last bricks).
    fn coordinates(&self, index: usize) -> [usize; 3] {
        let (brick, within) = (index / 64, index % 64);
        let [bx, by] = [
            brick % self.bricks[0],
            (brick / self.bricks[0]) % self.bricks[1],
        ];
        let bz = brick / (self.bricks[0] * self.bricks[1]);
        [
            4 * bx + (within & 3),
            4 * by + ((within >> 2) & 3),
            4 * bz + (within >> 4),
        ]
    }
}

impl ExtinctionGrid {
    /// The pyramid over the box `[min, max]` with `cells` cells along its longest side at
    /// level 0, from `cylinders` (their opacity is `1 - transmission`); levels are added while
    /// a grid has more than 2 nodes along some axis. Level 0 takes up to `(cells + 3)^3` nodes
    /// of 32 bytes: 74 MB at 128 cells, 570 MB at 256.
    ///
    /// # Errors
    /// [`ParamError::OutOfRange`] if `cells` is outside `[1, MAX_GRID_CELLS]` or the box is
    /// not finite with `min <= max`.
    pub fn new(
        cylinders: &[Cylinder],
        min: Vec3,
        max: Vec3,
        cells: usize,
    ) -> Result<Self, ParamError> {
        ParamError::check("grid_cells", cells as f64, "must be in [1, 256]", |c| {
            (1.0..=MAX_GRID_CELLS as f64).contains(&c)
        })?;
        let extent = max - min;
        let valid_box = min.is_finite() && max.is_finite() && extent.min_element() >= 0.0;
        if !valid_box {
            return Err(ParamError::BadVector {
                name: "box extent",
                x: f64::from(extent.x),
                y: f64::from(extent.y),
                z: f64::from(extent.z),
                allowed: "the box's corners must be finite with min <= max",
            });
        }
        let cell = (extent.max_element() / cells as f32).max(f32::MIN_POSITIVE);
        let count = |extent: f32| (extent / cell).ceil() as usize + 3;
        let layout = Layout::new([count(extent.x), count(extent.y), count(extent.z)]);
        let mut finest = Level {
            origin: min - Vec3::splat(cell),
            cell,
            layout,
            moments: vec![f32x8::ZERO; layout.len()],
        };
        let mut moments = core::mem::take(&mut finest.moments);
        for cylinder in cylinders {
            finest.splat(cylinder, |node, m| moments[node] += m);
        }
        finest.moments = moments;
        let mut levels = vec![finest];
        while let Some(coarser) = levels.last().and_then(Level::coarser) {
            levels.push(coarser);
        }
        Ok(Self { levels })
    }

    /// The node spacing `h` of level 0.
    pub fn cell(&self) -> f32 {
        self.levels[0].cell
    }

    /// `sigma_w` at `p` from level 0 (0 outside the grid).
    pub fn extinction_at(&self, p: Vec3, w: Vec3) -> f32 {
        let finest = &self.levels[0];
        finest.moments_at(p).map_or(0.0, |m| extinction(m, w))
    }

    /// The moments the cylinders `cylinders` (one strand's) deposit at level 0, to subtract
    /// from the grid's (see [`ExtinctionGrid::optical_depth`]).
    pub fn strand_moments<'a>(
        &self,
        cylinders: impl Iterator<Item = &'a Cylinder>,
    ) -> StrandMoments {
        let finest = &self.levels[0];
        let mut contributions = Vec::new();
        for cylinder in cylinders {
            finest.splat(cylinder, |node, m| contributions.push((node, m)));
        }
        StrandMoments::new(finest, &contributions)
    }

    /// The optical depth `int sigma_w dt` along `origin + t w` (`w` of unit length) from
    /// `t = start` to where the ray leaves the grid, by the midpoint rule with steps
    /// `max(h, t cone)`, each read from the coarsest level whose spacing is at most the step,
    /// less the moments of `without` (the medium without that strand); it stops once the
    /// depth exceeds `cutoff`.
    pub fn optical_depth(
        &self,
        origin: Vec3,
        w: Vec3,
        march: March,
        without: Option<&StrandMoments>,
    ) -> f32 {
        let March {
            start,
            cone,
            cutoff,
        } = march;
        let finest = &self.levels[0];
        let Some(end) = finest.exit_distance(origin, w) else {
            return 0.0;
        };
        let mut depth = 0.0;
        let mut t = start;
        let mut level = 0;
        while t < end && depth < cutoff {
            let step = finest.cell.max(t * cone);
            while level + 1 < self.levels.len() && self.levels[level + 1].cell <= step {
                level += 1;
            }
            let grid = &self.levels[level];
            let p = origin + w * (t + 0.5 * step);
            if let Some(mut m) = grid.moments_at(p) {
                if let Some(own) = without.filter(|_| level == 0) {
                    m -= own.moments_at(grid, p);
                }
                depth += extinction(m, w) * step;
            }
            t += step;
        }
        depth
    }
}

impl Level {
    /// The next level: every other node, each the tent-filtered average of its 27
    /// neighbours (weights `(1/4, 1/2, 1/4)` per axis, renormalised at the borders); `None`
    /// once no axis has more than 2 nodes.
    fn coarser(&self) -> Option<Level> {
        if self.layout.nodes.iter().all(|&n| n <= 2) {
            return None;
        }
        let layout = Layout::new(self.layout.nodes.map(|n| n.div_ceil(2)));
        let mut moments = vec![f32x8::ZERO; layout.len()];
        for (fine, m) in self.moments.iter().enumerate() {
            self.tent_targets(fine, &layout, |coarse, weight| {
                moments[coarse] += *m * weight
            });
        }
        Some(Level {
            origin: self.origin,
            cell: 2.0 * self.cell,
            layout,
            moments,
        })
    }

    /// Calls `add(coarse node, weight)` for every node of the next level that fine node `fine`
    /// feeds: per axis, fine `i` feeds coarse `i / 2` with 1/2 if `i` is even, coarse
    /// `(i - 1) / 2` and `(i + 1) / 2` with 1/4 each if odd; each weight divided by the coarse
    /// node's total weight (1 inside, less where a neighbour is past the border). Padding
    /// nodes feed nothing.
    fn tent_targets(&self, fine: usize, coarse: &Layout, mut add: impl FnMut(usize, f32)) {
        let index = self.layout.coordinates(fine);
        if (0..3).any(|axis| index[axis] >= self.layout.nodes[axis]) {
            return;
        }
        let coarse_nodes = coarse.nodes;
        let mut per_axis = [[(0usize, 0.0f32); 2]; 3];
        let mut counts = [0usize; 3];
        for axis in 0..3 {
            let (i, n) = (index[axis], self.layout.nodes[axis]);
            let candidates: &[(usize, f32)] = if i % 2 == 0 {
                &[(i / 2, 0.5)]
            } else {
                &[((i - 1) / 2, 0.25), (i.div_ceil(2), 0.25)]
            };
            for &(c, w) in candidates {
                if c < coarse_nodes[axis] {
                    let total = 1.0
                        - if c == 0 { 0.25 } else { 0.0 }
                        - if 2 * c + 1 >= n { 0.25 } else { 0.0 };
                    per_axis[axis][counts[axis]] = (c, w / total);
                    counts[axis] += 1;
                }
            }
        }
        for &(x, wx) in &per_axis[0][..counts[0]] {
            for &(y, wy) in &per_axis[1][..counts[1]] {
                for &(z, wz) in &per_axis[2][..counts[2]] {
                    add(coarse.index([x, y, z]), wx * wy * wz);
                }
            }
        }
    }

    /// Calls `add(node, moments)` for one cylinder's moments, splatted trilinearly from points
    /// at most half a cell apart along its axis.
    fn splat(&self, cylinder: &Cylinder, mut add: impl FnMut(usize, Moments)) {
        let opacity = 1.0 - cylinder.transmission;
        if opacity <= 0.0 || cylinder.length <= 0.0 {
            return;
        }
        let pieces = (2.0 * cylinder.length / self.cell).ceil().max(1.0);
        let piece = cylinder.length / pieces;
        let w = opacity * 2.0 * cylinder.radius * piece / self.cell.powi(3);
        let t = cylinder.axis;
        let outer = f32x8::new([
            1.0,
            t.x * t.x,
            t.y * t.y,
            t.z * t.z,
            t.x * t.y,
            t.x * t.z,
            t.y * t.z,
            0.0,
        ]);
        for k in 0..pieces as usize {
            let p = cylinder.base + t * ((k as f32 + 0.5) * piece);
            let Some((base, f)) = self.cell_of(p) else {
                continue;
            };
            for (node, corner) in self.corners(base, f) {
                add(node, outer * (w * corner));
            }
        }
    }

    /// The lowest corner of the cell holding `p` and `p`'s position in it, or `None` if the
    /// cell is not inside the grid.
    fn cell_of(&self, p: Vec3) -> Option<([usize; 3], Vec3)> {
        let g = (p - self.origin) / self.cell;
        if !g.cmpge(Vec3::ZERO).all() {
            return None;
        }
        // Truncation is the floor for these non-negative coordinates (and, unlike `floor`,
        // no library call on baseline x86-64).
        let base = [g.x as usize, g.y as usize, g.z as usize];
        let nodes = self.layout.nodes;
        let inside = (0..3).all(|axis| base[axis] + 1 < nodes[axis]);
        inside.then(|| {
            let corner = Vec3::new(base[0] as f32, base[1] as f32, base[2] as f32);
            (base, g - corner)
        })
    }

    /// The eight nodes of the cell whose lowest corner is `base`, with their trilinear
    /// weights at the position `f` in it.
    fn corners(&self, [x, y, z]: [usize; 3], f: Vec3) -> [(usize, f32); 8] {
        core::array::from_fn(|k| {
            let (dx, dy, dz) = (k & 1, (k >> 1) & 1, (k >> 2) & 1);
            let pick = |d: usize, f: f32| if d == 1 { f } else { 1.0 - f };
            let weight = pick(dx, f.x) * pick(dy, f.y) * pick(dz, f.z);
            (self.layout.index([x + dx, y + dy, z + dz]), weight)
        })
    }

    /// The moments at `p`, interpolated trilinearly, or `None` outside the grid.
    #[inline]
    fn moments_at(&self, p: Vec3) -> Option<Moments> {
        let (base, f) = self.cell_of(p)?;
        let mut m = f32x8::ZERO;
        for (node, weight) in self.corners(base, f) {
            m += self.moments[node] * weight;
        }
        Some(m)
    }

    /// The distance along `origin + t w` at which the ray leaves the grid's box, or `None`
    /// if it never meets it.
    fn exit_distance(&self, origin: Vec3, w: Vec3) -> Option<f32> {
        let [nx, ny, nz] = self.layout.nodes;
        let last = Vec3::new(nx as f32, ny as f32, nz as f32) - Vec3::ONE;
        let max = self.origin + self.cell * last;
        let inverse = w.abs().max(Vec3::splat(1e-20)).copysign(w).recip();
        let t0 = (self.origin - origin) * inverse;
        let t1 = (max - origin) * inverse;
        let far = t0.max(t1).min_element();
        let near = t0.min(t1).max_element();
        (far >= near.max(0.0)).then_some(far)
    }
}
