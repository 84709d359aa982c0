//! Batch evaluation of any model over slices, eight or sixteen samples per instruction.
//!
//! There is no separate SIMD implementation of a model: [`eval_batch`] and [`pdf_batch`] call
//! the very same generic [`Bcsdf::eval`] and [`SampledBcsdf::pdf`] that the scalar `f64` and
//! `f32` paths use, instantiated with a lane type `L` ([`wide::f32x8`] or [`wide::f32x16`], see
//! [`crate::real::simd`]) by [`Model::instantiate`](super::Model::instantiate). The only code
//! here moves data: it transposes `L::LANES` array-of-structures samples into
//! structure-of-arrays lanes, evaluates, and transposes back.
//!
//! **Which width.** [`wide::f32x8`] is compatible with every x86-64 target; [`BatchReal`]
//! names the faster width for the compilation target: [`wide::f32x16`] (one AVX-512 register)
//! when the crate is compiled with `avx512f`, e.g. under `RUSTFLAGS="-C target-cpu=native"` on
//! an AVX-512 machine, [`wide::f32x8`] otherwise. For example
//! `model.instantiate::<BatchReal>()` for a `ChiangHair<f64>` model. `wide`'s lanes run the
//! build's instructions; [`super::HostBatch`] runs the CPU's widest (AVX-512 or AVX2), chosen at
//! run time, with the same functions of this module.
//!
//! **Accuracy.** `wide`'s `exp`, `ln` and `atan2` are vectorised polynomial approximations, so
//! the lanes differ from the scalar `f32` instantiation (which calls libm) by a few ulp per
//! call. The module tests measure both widths against scalar `f32` and the `f64` reference over
//! 100k random inputs plus the hard cases: both are within 9e-6 of `f64` (relative to the value
//! plus 1e-6), and within 1.2e-5 of each other. The lanes also set the factors of a lobe sum
//! that fall below e^-36 (decays, transmittances, attenuations) to exactly 0
//! ([`Real::negligible_to_zero`]), so that the factors and their products are not subnormal
//! numbers, each of which costs an x86 core a microcode assist (S itself still is where every
//! lobe is negligible at once, rarely); what they drop is below 2.3e-16 of a lobe's scale.
//!
//! **Tail.** A length that is not a multiple of the lane count is handled by padding the last
//! chunk with the harmless sample `wi = wo = (0, 1, 0)`, `h = 0` and discarding the padded
//! lanes, so every input goes through the same vector code.

use wide::{f32x16, f32x8};

#[cfg(target_arch = "x86_64")]
use crate::real::{Avx2Lanes, Avx512Lanes};

use super::model::{Bcsdf, Query, SampledBcsdf};
use crate::geometry::V3;
use crate::real::Real;

pub use crate::real::BatchReal;

/// Lanes per [`f32x8`] value.
pub const LANES: usize = 8;
/// The most lanes of any [`BatchLanes`] type.
const MAX_LANES: usize = 16;

/// A SIMD lane type batch evaluation runs on: [`f32x8`] or [`f32x16`].
pub trait BatchLanes: Real + sealed::Sealed {
    /// Samples per value.
    const LANES: usize;
    /// The value whose lane `k` is `f(k)`.
    fn from_fn(f: impl FnMut(usize) -> f32) -> Self;
    /// Writes the first `out.len()` (at most `LANES`) lanes to `out`.
    fn store(self, out: &mut [f32]);
    /// Lane `k`.
    fn lane(self, k: usize) -> f32;
}

mod sealed {
    pub trait Sealed {}
    impl Sealed for wide::f32x8 {}
    impl Sealed for wide::f32x16 {}
    #[cfg(target_arch = "x86_64")]
    impl Sealed for crate::real::Avx512Lanes {}
    #[cfg(target_arch = "x86_64")]
    impl Sealed for crate::real::Avx2Lanes {}
}

macro_rules! impl_batch_lanes {
    ($t:ident, $n:expr) => {
        impl BatchLanes for $t {
            const LANES: usize = $n;
            #[inline(always)]
            fn from_fn(f: impl FnMut(usize) -> f32) -> Self {
                $t::from(crate::real::array_from_fn::<f32, $n>(f))
            }
            #[inline(always)]
            fn store(self, out: &mut [f32]) {
                let a = self.to_array();
                // A full chunk as one fixed-size copy (a vector store), a tail lane by lane.
                match <&mut [f32; $n]>::try_from(&mut *out) {
                    Ok(full) => *full = a,
                    Err(_) => out.copy_from_slice(&a[..out.len()]),
                }
            }
            #[inline(always)]
            fn lane(self, k: usize) -> f32 {
                self.to_array()[k]
            }
        }
    };
}

impl_batch_lanes!(f32x8, 8);
impl_batch_lanes!(f32x16, 16);
#[cfg(target_arch = "x86_64")]
impl_batch_lanes!(Avx512Lanes, 16);
#[cfg(target_arch = "x86_64")]
impl_batch_lanes!(Avx2Lanes, 8);

/// The slices handed to a batch function do not all have the same length.
#[derive(Clone, Copy, Debug, PartialEq, Eq, thiserror::Error)]
#[error("batch slices must have equal lengths: wi {wi}, wo {wo}, h {h}, out {out}")]
#[non_exhaustive]
pub struct BatchLengthError {
    /// Length of `wi`.
    pub wi: usize,
    /// Length of `wo`.
    pub wo: usize,
    /// Length of `h`.
    pub h: usize,
    /// Length of the output slice.
    pub out: usize,
}

/// Why a batch was refused ([`eval_batch`], [`pdf_batch`]); see [`eval_batch`] for what `out`
/// then holds.
#[derive(Clone, Copy, Debug, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum BatchError {
    /// The slices differ in length.
    #[error(transparent)]
    Length(#[from] BatchLengthError),
    /// A direction that is not a unit vector within [`super::UNIT_TOLERANCE`] (zero, infinite
    /// and NaN components included).
    #[error(
        "sample {index}: {name} = ({x}, {y}, {z}) must be a unit vector (length 1 within \
         {tolerance}) with finite components"
    )]
    Direction {
        /// The sample's index.
        index: usize,
        /// `wi` or `wo`.
        name: &'static str,
        /// Components as given.
        x: f32,
        /// Components as given.
        y: f32,
        /// Components as given.
        z: f32,
        /// [`super::UNIT_TOLERANCE`].
        tolerance: f64,
    },
    /// The tangents of a world-space batch ([`crate::world::eval_batch_world`]) are not one per
    /// sample.
    #[error("batch slices must have equal lengths: tangent {tangent}, samples {samples}")]
    TangentLength {
        /// Length of `tangent`.
        tangent: usize,
        /// Length of `wi`.
        samples: usize,
    },
    /// A tangent of a world-space batch that is zero or has a non-finite component.
    #[error("sample {index}: tangent = ({x}, {y}, {z}) must be non-zero with finite components")]
    Tangent {
        /// The sample's index.
        index: usize,
        /// Components as given.
        x: f32,
        /// Components as given.
        y: f32,
        /// Components as given.
        z: f32,
    },
    /// A component slice of a structure-of-arrays batch ([`eval_batch_soa`]) whose length is
    /// not the offsets' (the number of samples).
    #[error("batch slices must have equal lengths: {name} has {length}, h has {samples}")]
    ComponentLength {
        /// The slice: `wi.x`, `wi.y`, ..., `out.b`.
        name: &'static str,
        /// Its length.
        length: usize,
        /// The number of samples (the length of `h`).
        samples: usize,
    },
    /// An offset that is NaN (finite or infinite ones are clamped to [-1, 1]).
    #[error("sample {index}: h = {h} must be a number (offsets outside [-1, 1] are clamped)")]
    Offset {
        /// The sample's index.
        index: usize,
        /// The offset as given.
        h: f32,
    },
}

impl BatchError {
    /// The index of the sample the error names (a bad direction, offset or tangent); `None`
    /// for an error of lengths.
    pub fn sample_index(&self) -> Option<usize> {
        match *self {
            BatchError::Direction { index, .. }
            | BatchError::Offset { index, .. }
            | BatchError::Tangent { index, .. } => Some(index),
            _ => None,
        }
    }

    /// The error of a check of the samples from `start` on, with the sample index of the whole
    /// batch (an error that names no sample is unchanged).
    pub(crate) fn shifted(self, start: usize) -> BatchError {
        match self {
            BatchError::Direction {
                index,
                name,
                x,
                y,
                z,
                tolerance,
            } => BatchError::Direction {
                index: start + index,
                name,
                x,
                y,
                z,
                tolerance,
            },
            BatchError::Offset { index, h } => BatchError::Offset {
                index: start + index,
                h,
            },
            BatchError::Tangent { index, x, y, z } => BatchError::Tangent {
                index: start + index,
                x,
                y,
                z,
            },
            other => other,
        }
    }
}

/// The bounds of a unit direction's squared length, `(1 -+ tolerance)^2` (in `f32`).
const UNIT_SQUARED_LENGTH: [f32; 2] = [
    ((1.0 - super::UNIT_TOLERANCE) * (1.0 - super::UNIT_TOLERANCE)) as f32,
    ((1.0 + super::UNIT_TOLERANCE) * (1.0 + super::UNIT_TOLERANCE)) as f32,
];

/// Whether `w` is a unit vector within [`super::UNIT_TOLERANCE`]: its squared length within
/// [`UNIT_SQUARED_LENGTH`], no square root (false for non-finite components: a comparison
/// with NaN fails, and an infinite square is above the bound). [`lanes_ok`] decides the
/// same, lane by lane, bit for bit.
#[inline(always)]
fn is_unit(w: &[f32; 3]) -> bool {
    let [lowest, highest] = UNIT_SQUARED_LENGTH;
    let square = w[0] * w[0] + w[1] * w[1] + w[2] * w[2];
    (lowest <= square) & (square <= highest)
}

/// [`sample_ok`] of the samples in the lanes: the same operations, rounded as `f32` rounds
/// (separate multiplications and additions), so each lane's answer is [`sample_ok`]'s.
#[inline(always)]
fn lanes_ok<L: BatchLanes>(wi: &V3<L>, wo: &V3<L>, h: L) -> L::Mask {
    // A function, not a closure: closures are not always inlined into the instruction sets'
    // copies ([`super::HostBatch`]), and their lane operations then become calls.
    #[inline(always)]
    fn unit<L: BatchLanes>(w: &V3<L>) -> L::Mask {
        let [lowest, highest] = UNIT_SQUARED_LENGTH;
        let square = w.x * w.x + w.y * w.y + w.z * w.z;
        L::c(f64::from(lowest)).le(square) & square.le(L::c(f64::from(highest)))
    }
    // `h <= h` fails only for NaN.
    unit(wi) & unit(wo) & h.le(h)
}

/// Whether sample `(wi, wo, h)` has unit directions and an offset that is not NaN.
#[inline(always)]
fn sample_ok(((wi, wo), h): ((&[f32; 3], &[f32; 3]), &f32)) -> bool {
    is_unit(wi) & is_unit(wo) & !h.is_nan()
}

/// [`BatchError`] for the first sample with a direction that is not unit or a NaN offset. A
/// branch-free pass over the samples first (always inlined, so that [`super::HostBatch`] runs
/// it on its instruction set), then, only if one is bad, a search for it. The batches check
/// their full chunks on the lanes instead ([`lanes_ok`]), and this the last, partial chunk,
/// a chunk the lanes found bad, and world-space blocks.
#[inline(always)]
pub(crate) fn check_samples(wi: &[[f32; 3]], wo: &[[f32; 3]], h: &[f32]) -> Result<(), BatchError> {
    let all_ok = wi
        .iter()
        .zip(wo)
        .zip(h)
        .fold(true, |ok, sample| ok & sample_ok(sample));
    if all_ok {
        Ok(())
    } else {
        Err(first_bad_sample(wi, wo, h))
    }
}

/// The error of [`check_samples`] once a sample failed.
#[cold]
fn first_bad_sample(wi: &[[f32; 3]], wo: &[[f32; 3]], h: &[f32]) -> BatchError {
    let index = wi
        .iter()
        .zip(wo)
        .zip(h)
        .position(|sample| !sample_ok(sample))
        .unwrap_or(0);
    let direction = |name, w: [f32; 3]| BatchError::Direction {
        index,
        name,
        x: w[0],
        y: w[1],
        z: w[2],
        tolerance: super::UNIT_TOLERANCE,
    };
    if !is_unit(&wi[index]) {
        direction("wi", wi[index])
    } else if !is_unit(&wo[index]) {
        direction("wo", wo[index])
    } else {
        BatchError::Offset { index, h: h[index] }
    }
}

/// The padding sample: wi = wo = (0, 1, 0) (perpendicular to the fibre), h = 0.
const PAD_DIR: [f32; 3] = [0.0, 1.0, 0.0];
const PAD_H: f32 = 0.0;

/// The length check of every array-of-structures batch: `wi`, `wo`, `h` and `out` equal.
pub(crate) fn check(wi: usize, wo: usize, h: usize, out: usize) -> Result<(), BatchLengthError> {
    if wi == wo && wo == h && h == out {
        Ok(())
    } else {
        Err(BatchLengthError { wi, wo, h, out })
    }
}

/// `L::LANES` directions (array of structures; exactly that many) as one vector of lanes.
#[inline(always)]
fn load_dirs<L: BatchLanes>(d: &[[f32; 3]]) -> V3<L> {
    V3::new(
        L::from_fn(
            #[inline(always)]
            |k| d[k][0],
        ),
        L::from_fn(
            #[inline(always)]
            |k| d[k][1],
        ),
        L::from_fn(
            #[inline(always)]
            |k| d[k][2],
        ),
    )
}

/// Runs `f` on every chunk of `L::LANES` samples, padding the last chunk. `f` receives the
/// lanes and the valid lanes' output slots to fill. `CHECK`: each chunk is checked as its
/// lanes are loaded ([`lanes_ok`], a few operations per chunk), and at the first chunk with a
/// bad sample the samples before it are evaluated and its error returned
/// ([`check_samples`]'s); without, the samples were checked before (a world-space batch).
#[inline(always)]
fn for_each_chunk<L: BatchLanes, T: Copy, const CHECK: bool>(
    wi: &[[f32; 3]],
    wo: &[[f32; 3]],
    h: &[f32],
    out: &mut [T],
    mut f: impl FnMut(V3<L>, V3<L>, L, &mut [T]),
) -> Result<(), BatchError> {
    let n = L::LANES;
    let full = wi.len() / n * n;
    let out_lines = out.as_ptr();
    let chunks = wi[..full]
        .chunks_exact(n)
        .zip(wo[..full].chunks_exact(n))
        .zip(h[..full].chunks_exact(n))
        .zip(out[..full].chunks_exact_mut(n))
        .enumerate();
    for (chunk, (((wi_k, wo_k), h_k), out_k)) in chunks {
        let ahead = chunk * n + PREFETCH_AHEAD;
        prefetch(wi.as_ptr().wrapping_add(ahead), n);
        prefetch(wo.as_ptr().wrapping_add(ahead), n);
        prefetch(h.as_ptr().wrapping_add(ahead), n);
        prefetch(out_lines.wrapping_add(ahead), n);
        let (i, o) = (load_dirs(wi_k), load_dirs(wo_k));
        let h_lanes = L::from_fn(
            #[inline(always)]
            |k| h_k[k],
        );
        if CHECK && !L::every_lane(lanes_ok(&i, &o, h_lanes)) {
            let start = chunk * n;
            return padded::<L, T, CHECK>((wi_k, wo_k, h_k), out_k, &mut f)
                .map_err(|e| e.shifted(start));
        }
        f(i, o, h_lanes, out_k);
    }
    let rest = (&wi[full..], &wo[full..], &h[full..]);
    padded::<L, T, CHECK>(rest, &mut out[full..], &mut f).map_err(|e| e.shifted(full))
}

/// How far ahead of the chunk it evaluates a batch loop asks for its slices' memory
/// ([`prefetch`]), in samples: eight chunks of sixteen lanes. The batch streams four slices
/// (array of structures) or ten (structure of arrays) through the caches, which the CPU's own
/// prefetchers follow less well: without it, on 2 million samples, one thread, AVX-512, an
/// Intel Xeon (README, speed section), the structure of arrays took 14% longer per sample
/// than on 50,000 in cache (10.01 against 8.79 ns); with it, 8% less than without. 64, 128
/// and 256 samples ahead measured alike, 32 less well.
const PREFETCH_AHEAD: usize = 128;

/// Asks the CPU to bring the cache lines of the `count` values from `first` into its caches
/// (`prefetcht0`, SSE: every x86-64 CPU). A hint, not an access: any address will do, past
/// the end of a slice included, and nothing is read. Nothing on other architectures.
#[inline(always)]
fn prefetch<T>(first: *const T, count: usize) {
    #[cfg(target_arch = "x86_64")]
    {
        use core::arch::x86_64::{_mm_prefetch, _MM_HINT_T0};
        let first = first.cast::<i8>();
        for byte in (0..count * core::mem::size_of::<T>()).step_by(64) {
            // SAFETY: a prefetch reads nothing and cannot fault, whatever the address; SSE is
            // part of x86-64.
            unsafe { _mm_prefetch::<_MM_HINT_T0>(first.wrapping_add(byte)) };
        }
    }
    #[cfg(not(target_arch = "x86_64"))]
    let _ = (first, count);
}

/// At most `L::LANES` samples through `f`, padded with [`PAD_DIR`] and [`PAD_H`]; `CHECK`:
/// only those before the first bad sample, whose error ([`check_samples`]) is returned.
fn padded<L: BatchLanes, T: Copy, const CHECK: bool>(
    (wi, wo, h): (&[[f32; 3]], &[[f32; 3]], &[f32]),
    out: &mut [T],
    f: &mut impl FnMut(V3<L>, V3<L>, L, &mut [T]),
) -> Result<(), BatchError> {
    let valid = match CHECK {
        true => check_samples(wi, wo, h),
        false => Ok(()),
    };
    let end = valid
        .as_ref()
        .err()
        .map_or(h.len(), |e| e.sample_index().unwrap_or(0));
    if end > 0 {
        let pad = |d: &[[f32; 3]]| -> Vec<[f32; 3]> {
            let mut v = vec![PAD_DIR; L::LANES];
            v[..end].copy_from_slice(&d[..end]);
            v
        };
        let (pwi, pwo) = (pad(wi), pad(wo));
        let ph = L::from_fn(|k| if k < end { h[k] } else { PAD_H });
        f(load_dirs(&pwi), load_dirs(&pwo), ph, &mut out[..end]);
    }
    valid
}

/// `S(wi[k], wo[k], h[k])` per channel into `out[k]`, `L::LANES` samples at a time.
///
/// This is the model's [`Bcsdf::eval`] itself, the same generic code as the scalar `f64`/`f32`
/// paths, instantiated with the lane type `L`; results agree with the `f32` instantiation up
/// to the accuracy of `wide`'s transcendental approximations (see the module documentation).
/// Conventions (local frame, tangent +X, unit directions, `h` in [-1, 1] clamped) are those of
/// [`Query`]; far-field models ignore `h`. Every sample is checked before it is evaluated
/// (directions unit within [`super::UNIT_TOLERANCE`] and evaluated as given, `h` not NaN),
/// on the lanes as they are loaded: a few operations per chunk, where a pass over every sample
/// before any evaluation had cost a tenth of the batch's time.
///
/// # Errors
/// [`BatchError::Length`] if `wi`, `wo`, `h` and `out` differ in length, and `out` is
/// untouched; [`BatchError::Direction`] or [`BatchError::Offset`] naming the first bad sample
/// ([`BatchError::sample_index`]), and `out` holds the values of the samples before it and is
/// untouched from it on (the parallel batches, [`par_eval_batch`], may have written any of
/// the rest).
///
/// # Examples
///
/// ```
/// use hairmath::bcsdf::{eval_batch, BatchError, BatchReal, ChiangHair, Model};
/// use hairmath::params::HairParams;
///
/// let lanes = ChiangHair::new(&HairParams::default()).instantiate::<BatchReal>();
/// let (wi, wo) = ([[-0.6, 0.8, 0.0]; 20], [[0.6, 0.0, 0.8]; 20]);
/// let mut out = [[0.0_f32; 3]; 20];
/// eval_batch(&lanes, &wi, &wo, &[0.1; 20], &mut out)?;
/// assert!(out.iter().all(|s| s == &out[0] && s[0] > 0.0));
/// // A direction that is not unit is refused, naming the sample.
/// let bad = eval_batch(&lanes, &[[0.0; 3]], &wo[..1], &[0.0], &mut out[..1]);
/// assert!(matches!(bad, Err(BatchError::Direction { index: 0, name: "wi", .. })));
/// # Ok::<(), BatchError>(())
/// ```
pub fn eval_batch<L: BatchLanes, M: Bcsdf<L>>(
    model: &M,
    wi: &[[f32; 3]],
    wo: &[[f32; 3]],
    h: &[f32],
    out: &mut [[f32; 3]],
) -> Result<(), BatchError> {
    check(wi.len(), wo.len(), h.len(), out.len())?;
    eval_samples::<L, M, true>(model, wi, wo, h, out)
}

/// [`eval_batch`] of samples of equal lengths, each chunk checked as it is loaded (`CHECK`,
/// [`for_each_chunk`]) or all checked before (not `CHECK`: then it never fails). Always
/// inlined, with its closure, into the per-instruction-set copies of [`super::HostBatch`].
#[inline(always)]
pub(crate) fn eval_samples<L: BatchLanes, M: Bcsdf<L>, const CHECK: bool>(
    model: &M,
    wi: &[[f32; 3]],
    wo: &[[f32; 3]],
    h: &[f32],
    out: &mut [[f32; 3]],
) -> Result<(), BatchError> {
    for_each_chunk::<L, _, CHECK>(
        wi,
        wo,
        h,
        out,
        #[inline(always)]
        |wi, wo, h, out| {
            let mut rgb = [[0.0_f32; MAX_LANES]; 3];
            for (lanes, value) in rgb.iter_mut().zip(model.eval(&Query::new(wi, wo, h))) {
                value.store(&mut lanes[..L::LANES]);
            }
            for (k, slot) in out.iter_mut().enumerate().take(L::LANES) {
                *slot = [rgb[0][k], rgb[1][k], rgb[2][k]];
            }
        },
    )
}

/// Directions as a structure of arrays: sample `k` is `(x[k], y[k], z[k])` (local frame, as
/// in [`Query`]).
#[derive(Clone, Copy, Debug)]
pub struct DirectionSlices<'a> {
    /// The components along the tangent.
    pub x: &'a [f32],
    /// The second components.
    pub y: &'a [f32],
    /// The third components.
    pub z: &'a [f32],
}

impl<'a> DirectionSlices<'a> {
    /// The samples in `range` of every component.
    ///
    /// # Panics
    /// If `range` is outside a component (callers check the lengths first).
    pub(crate) fn range(&self, range: core::ops::Range<usize>) -> DirectionSlices<'a> {
        DirectionSlices {
            x: &self.x[range.clone()],
            y: &self.y[range.clone()],
            z: &self.z[range],
        }
    }
}

/// Per-channel outputs as a structure of arrays: sample `k`'s S is `(r[k], g[k], b[k])`.
#[derive(Debug)]
pub struct RgbSlices<'a> {
    /// Red.
    pub r: &'a mut [f32],
    /// Green.
    pub g: &'a mut [f32],
    /// Blue.
    pub b: &'a mut [f32],
}

/// [`eval_batch`] of samples stored as a structure of arrays, the layout of the lanes
/// themselves: each chunk of `L::LANES` samples is loaded and stored contiguously, with no
/// transposition. The values are [`eval_batch`]'s, bit for bit (the same lanes go through the
/// same code). Every sample is checked before it is evaluated, as in [`eval_batch`].
///
/// # Errors
/// [`BatchError::ComponentLength`] naming the first slice whose length is not `h.len()`;
/// [`BatchError::Direction`] or [`BatchError::Offset`] naming the first bad sample; `out` then
/// holds what [`eval_batch`] says.
///
/// # Examples
///
/// ```
/// use hairmath::bcsdf::{eval_batch_soa, BatchReal, ChiangHair, DirectionSlices, Model, RgbSlices};
/// use hairmath::params::HairParams;
///
/// let lanes = ChiangHair::new(&HairParams::default()).instantiate::<BatchReal>();
/// let n = 20;
/// let wi = DirectionSlices { x: &vec![-0.6; n], y: &vec![0.8; n], z: &vec![0.0; n] };
/// let wo = DirectionSlices { x: &vec![0.6; n], y: &vec![0.0; n], z: &vec![0.8; n] };
/// let (mut r, mut g, mut b) = (vec![0.0; n], vec![0.0; n], vec![0.0; n]);
/// let out = RgbSlices { r: &mut r, g: &mut g, b: &mut b };
/// eval_batch_soa(&lanes, wi, wo, &vec![0.1; n], out)?;
/// assert!(r.iter().all(|&s| s == r[0] && s > 0.0));
/// # Ok::<(), hairmath::bcsdf::BatchError>(())
/// ```
pub fn eval_batch_soa<L: BatchLanes, M: Bcsdf<L>>(
    model: &M,
    wi: DirectionSlices<'_>,
    wo: DirectionSlices<'_>,
    h: &[f32],
    out: RgbSlices<'_>,
) -> Result<(), BatchError> {
    check_soa_lengths(&wi, &wo, h, &out)?;
    eval_soa_samples(model, wi, wo, h, out)
}

/// The length checks of [`eval_batch_soa`].
pub(crate) fn check_soa_lengths(
    wi: &DirectionSlices,
    wo: &DirectionSlices,
    h: &[f32],
    out: &RgbSlices,
) -> Result<(), BatchError> {
    let outputs = [
        ("out.r", out.r.len()),
        ("out.g", out.g.len()),
        ("out.b", out.b.len()),
    ];
    check_components(wi, wo, h, &outputs)
}

/// [`eval_batch_soa`] of samples of equal lengths, each chunk checked as it is loaded
/// ([`lanes_ok`]): at the first chunk with a bad sample, the samples before it are stored and
/// its error ([`check_soa_samples`]'s) returned. Always inlined, as [`eval_samples`].
#[inline(always)]
pub(crate) fn eval_soa_samples<L: BatchLanes, M: Bcsdf<L>>(
    model: &M,
    wi: DirectionSlices<'_>,
    wo: DirectionSlices<'_>,
    h: &[f32],
    out: RgbSlices<'_>,
) -> Result<(), BatchError> {
    let len = h.len();
    for start in (0..len).step_by(L::LANES) {
        let ahead = start + PREFETCH_AHEAD;
        for slice in [wi.x, wi.y, wi.z, wo.x, wo.y, wo.z, h, out.r, out.g, out.b] {
            prefetch(slice.as_ptr().wrapping_add(ahead), L::LANES);
        }
        let (i, o) = (soa_direction(&wi, start), soa_direction(&wo, start));
        let h_lanes = soa_lanes(h, start, PAD_H);
        let end = (start + L::LANES).min(len);
        let valid = match L::every_lane(lanes_ok(&i, &o, h_lanes)) {
            true => Ok(()),
            false => first_bad_in(&wi, &wo, h, start..end),
        };
        let end = valid
            .as_ref()
            .map_or_else(|e| e.sample_index().unwrap_or(start), |()| end);
        let value = model.eval(&Query::new(i, o, h_lanes));
        for (channel, v) in [&mut *out.r, &mut *out.g, &mut *out.b]
            .into_iter()
            .zip(value)
        {
            v.store(&mut channel[start..end]);
        }
        valid?;
    }
    Ok(())
}

/// [`check_soa_samples`] of the samples of `range`, the error's index counted from the
/// batch's start.
#[cold]
fn first_bad_in(
    wi: &DirectionSlices,
    wo: &DirectionSlices,
    h: &[f32],
    range: core::ops::Range<usize>,
) -> Result<(), BatchError> {
    let start = range.start;
    check_soa_samples(
        &wi.range(range.clone()),
        &wo.range(range.clone()),
        &h[range],
    )
    .map_err(|e| e.shifted(start))
}

/// `L::LANES` directions of `d` from `start`, padded with [`PAD_DIR`] past its end.
#[inline(always)]
fn soa_direction<L: BatchLanes>(d: &DirectionSlices, start: usize) -> V3<L> {
    V3::new(
        soa_lanes(d.x, start, PAD_DIR[0]),
        soa_lanes(d.y, start, PAD_DIR[1]),
        soa_lanes(d.z, start, PAD_DIR[2]),
    )
}

/// `L::LANES` values of `s` from `start`, padded with `fill` past its end.
#[inline(always)]
fn soa_lanes<L: BatchLanes>(s: &[f32], start: usize, fill: f32) -> L {
    match s.get(start..start + L::LANES) {
        Some(chunk) => L::from_fn(
            #[inline(always)]
            |k| chunk[k],
        ),
        None => L::from_fn(|k| s.get(start + k).copied().unwrap_or(fill)),
    }
}

/// [`BatchError::ComponentLength`] for the first component or output slice whose length is
/// not `h.len()`.
fn check_components(
    wi: &DirectionSlices,
    wo: &DirectionSlices,
    h: &[f32],
    outputs: &[(&'static str, usize)],
) -> Result<(), BatchError> {
    let inputs = [
        ("wi.x", wi.x.len()),
        ("wi.y", wi.y.len()),
        ("wi.z", wi.z.len()),
        ("wo.x", wo.x.len()),
        ("wo.y", wo.y.len()),
        ("wo.z", wo.z.len()),
    ];
    match inputs
        .iter()
        .chain(outputs)
        .find(|(_, length)| *length != h.len())
    {
        Some(&(name, length)) => Err(BatchError::ComponentLength {
            name,
            length,
            samples: h.len(),
        }),
        None => Ok(()),
    }
}

/// [`check_samples`] of a structure of arrays (lengths already checked): a branch-free pass
/// first, as there (always inlined), then the search for the first bad sample.
#[inline(always)]
pub(crate) fn check_soa_samples(
    wi: &DirectionSlices,
    wo: &DirectionSlices,
    h: &[f32],
) -> Result<(), BatchError> {
    // Cut to h's length, so that the pass has no bounds checks and vectorises.
    let n = h.len();
    let (ix, iy, iz) = (&wi.x[..n], &wi.y[..n], &wi.z[..n]);
    let (ox, oy, oz) = (&wo.x[..n], &wo.y[..n], &wo.z[..n]);
    let mut all_ok = true;
    for k in 0..n {
        let sample = ([ix[k], iy[k], iz[k]], [ox[k], oy[k], oz[k]]);
        all_ok &= sample_ok(((&sample.0, &sample.1), &h[k]));
    }
    match all_ok {
        true => Ok(()),
        false => Err(first_bad_soa_sample(wi, wo, h)),
    }
}

/// Sample `k` of a structure of arrays (lengths already checked) as [`sample_ok`] sees it.
#[inline(always)]
fn soa_sample(wi: &DirectionSlices, wo: &DirectionSlices, k: usize) -> ([f32; 3], [f32; 3]) {
    ([wi.x[k], wi.y[k], wi.z[k]], [wo.x[k], wo.y[k], wo.z[k]])
}

/// Whether sample `k` of a structure of arrays passes [`check_samples`].
#[inline(always)]
fn soa_sample_ok(wi: &DirectionSlices, wo: &DirectionSlices, h: &[f32], k: usize) -> bool {
    let (a, b) = soa_sample(wi, wo, k);
    sample_ok(((&a, &b), &h[k]))
}

/// The error of [`check_soa_samples`] once a sample failed.
#[cold]
fn first_bad_soa_sample(wi: &DirectionSlices, wo: &DirectionSlices, h: &[f32]) -> BatchError {
    let k = (0..h.len())
        .position(|k| !soa_sample_ok(wi, wo, h, k))
        .unwrap_or(0);
    let (a, b) = soa_sample(wi, wo, k);
    first_bad_sample(&[a], &[b], &h[k..=k]).shifted(k)
}

/// A model instantiated on the lanes of [`BatchReal`], behind a trait object: what a caller
/// that chooses the model at run time (the registry, the benchmarks) batch-evaluates.
/// Implemented by every `Bcsdf<BatchReal>`.
pub trait BatchEval {
    /// [`eval_batch`] with the lanes of [`BatchReal`].
    ///
    /// # Errors
    /// As [`eval_batch`].
    fn eval_batch_lanes(
        &self,
        wi: &[[f32; 3]],
        wo: &[[f32; 3]],
        h: &[f32],
        out: &mut [[f32; 3]],
    ) -> Result<(), BatchError>;
}

impl<M: Bcsdf<BatchReal>> BatchEval for M {
    fn eval_batch_lanes(
        &self,
        wi: &[[f32; 3]],
        wo: &[[f32; 3]],
        h: &[f32],
        out: &mut [[f32; 3]],
    ) -> Result<(), BatchError> {
        eval_batch::<BatchReal, M>(self, wi, wo, h, out)
    }
}

/// [`SampledBcsdf::pdf`] of `wi[k]` given `wo[k]`, `h[k]` into `out[k]`, `L::LANES` samples at
/// a time (the same generic code as the scalar path, instantiated with `L`), every sample
/// checked before it is evaluated, as in [`eval_batch`].
///
/// # Errors
/// As [`eval_batch`].
pub fn pdf_batch<L: BatchLanes, M: SampledBcsdf<L>>(
    model: &M,
    wi: &[[f32; 3]],
    wo: &[[f32; 3]],
    h: &[f32],
    out: &mut [f32],
) -> Result<(), BatchError> {
    check(wi.len(), wo.len(), h.len(), out.len())?;
    pdf_samples::<L, M, true>(model, wi, wo, h, out)
}

/// [`pdf_batch`] of samples of equal lengths, checked as [`eval_samples`] says.
pub(crate) fn pdf_samples<L: BatchLanes, M: SampledBcsdf<L>, const CHECK: bool>(
    model: &M,
    wi: &[[f32; 3]],
    wo: &[[f32; 3]],
    h: &[f32],
    out: &mut [f32],
) -> Result<(), BatchError> {
    for_each_chunk::<L, _, CHECK>(
        wi,
        wo,
        h,
        out,
        #[inline(always)]
        |wi, wo, h, out| {
            let n = out.len().min(L::LANES);
            model.pdf(&Query::new(wi, wo, h)).store(&mut out[..n]);
        },
    )
}

/// Samples per task of the parallel batch, a multiple of every lane count: tens of
/// microseconds of work per task for the models here, against rayon's per-task overhead of
/// about a microsecond, and still enough tasks to balance the threads on a few thousand
/// samples (`benches/bcsdf.rs`, group `parallel_batch`, measures the scaling).
#[cfg(feature = "parallel")]
pub const PARALLEL_CHUNK: usize = 1024;

/// [`eval_batch`] on every thread of rayon's current pool: the samples split into chunks of
/// [`PARALLEL_CHUNK`], each evaluated by [`eval_batch`]. The results are those of
/// [`eval_batch`], bit for bit, whatever the thread count (the chunks start at multiples of
/// the lane count, so every sample is in the same lane of the same vector). Run it inside
/// `rayon::ThreadPool::install` to choose the threads.
///
/// # Errors
/// As [`eval_batch`]: the first bad sample, and the values of the samples before it in `out`;
/// the rest of `out` may have been written.
#[cfg(feature = "parallel")]
pub fn par_eval_batch<L: BatchLanes, M: Bcsdf<L> + Sync>(
    model: &M,
    wi: &[[f32; 3]],
    wo: &[[f32; 3]],
    h: &[f32],
    out: &mut [[f32; 3]],
) -> Result<(), BatchError> {
    check(wi.len(), wo.len(), h.len(), out.len())?;
    for_each_parallel_chunk(wi, wo, h, out, |wi, wo, h, out| {
        eval_samples::<L, M, true>(model, wi, wo, h, out)
    })
}

/// [`pdf_batch`] on every thread of rayon's current pool, as [`par_eval_batch`] is
/// [`eval_batch`]'s: the same values, bit for bit.
///
/// # Errors
/// As [`par_eval_batch`].
#[cfg(feature = "parallel")]
pub fn par_pdf_batch<L: BatchLanes, M: SampledBcsdf<L> + Sync>(
    model: &M,
    wi: &[[f32; 3]],
    wo: &[[f32; 3]],
    h: &[f32],
    out: &mut [f32],
) -> Result<(), BatchError> {
    check(wi.len(), wo.len(), h.len(), out.len())?;
    for_each_parallel_chunk(wi, wo, h, out, |wi, wo, h, out| {
        pdf_samples::<L, M, true>(model, wi, wo, h, out)
    })
}

/// Runs `f`, a checked evaluation ([`eval_samples`]), on chunks of [`PARALLEL_CHUNK`]
/// samples in parallel (lengths already checked), and returns the error of the first chunk
/// that fails, its index counted from the batch's start ([`first_error`]).
#[cfg(feature = "parallel")]
pub(crate) fn for_each_parallel_chunk<T: Send>(
    wi: &[[f32; 3]],
    wo: &[[f32; 3]],
    h: &[f32],
    out: &mut [T],
    f: impl Fn(&[[f32; 3]], &[[f32; 3]], &[f32], &mut [T]) -> Result<(), BatchError> + Sync,
) -> Result<(), BatchError> {
    use rayon::prelude::*;
    let chunks = wi
        .par_chunks(PARALLEL_CHUNK)
        .zip(wo.par_chunks(PARALLEL_CHUNK))
        .zip(h.par_chunks(PARALLEL_CHUNK))
        .zip(out.par_chunks_mut(PARALLEL_CHUNK))
        .enumerate()
        .map(|(chunk, (((wi, wo), h), out))| (chunk, f(wi, wo, h, out)));
    first_error(chunks)
}

/// The first error of the chunks' results, in the order of the chunks, with the sample index
/// counted from the batch's start. Finding the first error runs every chunk before it, so
/// the samples before the bad one are all evaluated, as in the sequential batch.
#[cfg(feature = "parallel")]
fn first_error(
    chunks: impl rayon::iter::IndexedParallelIterator<Item = (usize, Result<(), BatchError>)>,
) -> Result<(), BatchError> {
    use rayon::prelude::*;
    chunks
        .map(|(chunk, result)| result.map_err(|e| e.shifted(chunk * PARALLEL_CHUNK)))
        .find_first(Result::is_err)
        .unwrap_or(Ok(()))
}

/// [`eval_batch_soa`] on every thread of rayon's current pool, as [`par_eval_batch`] is
/// [`eval_batch`]'s: the same values, bit for bit, whatever the thread count.
///
/// # Errors
/// As [`par_eval_batch`].
#[cfg(feature = "parallel")]
pub fn par_eval_batch_soa<L: BatchLanes, M: Bcsdf<L> + Sync>(
    model: &M,
    wi: DirectionSlices<'_>,
    wo: DirectionSlices<'_>,
    h: &[f32],
    out: RgbSlices<'_>,
) -> Result<(), BatchError> {
    check_soa_lengths(&wi, &wo, h, &out)?;
    for_each_parallel_soa_chunk(wi, wo, h, out, |wi, wo, h, out| {
        eval_soa_samples(model, wi, wo, h, out)
    })
}

/// [`for_each_parallel_chunk`] of a structure of arrays: `f` a checked evaluation
/// ([`eval_soa_samples`]) of each chunk.
#[cfg(feature = "parallel")]
pub(crate) fn for_each_parallel_soa_chunk(
    wi: DirectionSlices<'_>,
    wo: DirectionSlices<'_>,
    h: &[f32],
    out: RgbSlices<'_>,
    f: impl Fn(
            DirectionSlices<'_>,
            DirectionSlices<'_>,
            &[f32],
            RgbSlices<'_>,
        ) -> Result<(), BatchError>
        + Sync,
) -> Result<(), BatchError> {
    use rayon::prelude::*;
    let chunks = out
        .r
        .par_chunks_mut(PARALLEL_CHUNK)
        .zip(out.g.par_chunks_mut(PARALLEL_CHUNK))
        .zip(out.b.par_chunks_mut(PARALLEL_CHUNK))
        .enumerate()
        .map(|(chunk, ((r, g), b))| {
            let start = chunk * PARALLEL_CHUNK;
            let range = start..start + r.len();
            let (wi, wo) = (wi.range(range.clone()), wo.range(range.clone()));
            (chunk, f(wi, wo, &h[range], RgbSlices { r, g, b }))
        });
    first_error(chunks)
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;
    use crate::bcsdf::{ChiangHair, Model};
    use crate::params::HairParams;
    use rand::{Rng, SeedableRng};
    use rand_pcg::Pcg64Mcg;

    /// beta_m = beta_n = 0.3, a 2 degree tilt, eta = 1.55, eumelanin 1.3.
    pub(crate) fn model() -> ChiangHair<f64> {
        ChiangHair::new(&HairParams::default())
    }

    /// A direction uniform on the sphere.
    pub(crate) fn unit(rng: &mut Pcg64Mcg) -> [f32; 3] {
        let z: f64 = rng.random_range(-1.0..=1.0);
        let phi: f64 = rng.random_range(0.0..core::f64::consts::TAU);
        let r = (1.0 - z * z).max(0.0).sqrt();
        [(r * phi.cos()) as f32, (r * phi.sin()) as f32, z as f32]
    }

    pub(crate) fn v3<R: crate::real::Real>(d: [f32; 3]) -> V3<R> {
        V3::from_f64(d[0] as f64, d[1] as f64, d[2] as f64)
    }

    /// Random directions and offsets followed by the hard cases: grazing wi/wo (x = +-1),
    /// h = +-1, wi = wo, wi = -wo. An odd length exercises the padded tail.
    pub(crate) fn inputs(n: usize) -> (Vec<[f32; 3]>, Vec<[f32; 3]>, Vec<f32>) {
        let mut rng = Pcg64Mcg::seed_from_u64(0x5eed);
        let (mut wi, mut wo, mut h) = (Vec::new(), Vec::new(), Vec::new());
        for _ in 0..n {
            wi.push(unit(&mut rng));
            wo.push(unit(&mut rng));
            h.push(rng.random_range(-1.0f32..=1.0));
        }
        let specials: [[f32; 3]; 6] = [
            [1.0, 0.0, 0.0],
            [-1.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            [0.6, 0.0, 0.8],
            [-0.28, 0.96, 0.0],
            [0.0, -0.6, 0.8],
        ];
        for &a in &specials {
            for &b in &specials {
                for &hh in &[-1.0f32, -0.3, 0.0, 1.0] {
                    wi.push(a);
                    wo.push(b);
                    h.push(hh);
                    // wi = wo and wi = -wo
                    wi.push(a);
                    wo.push(a);
                    h.push(hh);
                    wi.push(a.map(|c| -c));
                    wo.push(a);
                    h.push(hh);
                }
            }
        }
        for k in 0..n.min(500) {
            // grazing and edge-on variants of random inputs
            wi.push([if k % 2 == 0 { 1.0 } else { -1.0 }, 0.0, 0.0]);
            wo.push(wo[k]);
            h.push(if k % 3 == 0 { 1.0 } else { -1.0 });
            wi.push(wo[k]);
            wo.push(wo[k]);
            h.push(h[k]);
            wi.push(wo[k].map(|c| -c));
            wo.push(wo[k]);
            h.push(h[k]);
        }
        if wi.len() % MAX_LANES == 0 {
            wi.push([0.0, 0.0, 1.0]);
            wo.push([0.0, 0.0, 1.0]);
            h.push(0.5);
        }
        (wi, wo, h)
    }

    /// max over samples and channels of |x - ref| / (|ref| + floor).
    pub(crate) fn max_rel(x: &[[f32; 3]], reference: &[[f64; 3]], floor: f64) -> (f64, usize) {
        let mut worst = (0.0, 0);
        for (k, (a, b)) in x.iter().zip(reference).enumerate() {
            for c in 0..3 {
                let e = (a[c] as f64 - b[c]).abs() / (b[c].abs() + floor);
                if e > worst.0 {
                    worst = (e, k);
                }
            }
        }
        worst
    }

    #[test]
    fn length_mismatch_is_a_typed_error() {
        let hair = model().instantiate::<f32x8>();
        let d = [[0.0, 1.0, 0.0]; 3];
        let mut out = [[7.0; 3]; 3];
        let err = eval_batch(&hair, &d, &d[..2], &[0.0; 3], &mut out).unwrap_err();
        assert_eq!(
            err,
            BatchError::Length(BatchLengthError {
                wi: 3,
                wo: 2,
                h: 3,
                out: 3
            })
        );
        assert_eq!(out, [[7.0; 3]; 3]);
        let mut p = [0.0; 2];
        assert!(pdf_batch(&hair, &d, &d, &[0.0; 3], &mut p).is_err());
        assert!(eval_batch(&hair, &[], &[], &[], &mut []).is_ok());
    }

    #[test]
    fn bad_directions_and_nan_offsets_are_typed_errors_naming_the_sample() {
        let hair = model().instantiate::<f32x8>();
        let good = [0.0, 0.6, 0.8];
        for (bad, name) in [
            ([0.0, 1.2, 1.6], "wi"),
            ([0.0; 3], "wi"),
            ([f32::NAN, 0.0, 1.0], "wi"),
            ([f32::INFINITY, 0.0, 0.0], "wi"),
        ] {
            let wi = [good, good, good, bad, good];
            let mut out = [[7.0; 3]; 5];
            let err = eval_batch(&hair, &wi, &[good; 5], &[0.0; 5], &mut out).unwrap_err();
            assert!(
                matches!(err, BatchError::Direction { index: 3, name: n, .. } if n == name),
                "{err:?}"
            );
            // The samples before the bad one are evaluated, none from it on.
            let mut before = [[0.0; 3]; 3];
            eval_batch(&hair, &wi[..3], &[good; 3], &[0.0; 3], &mut before).unwrap();
            assert_eq!(out[..3], before);
            assert_eq!(out[3..], [[7.0; 3]; 2]);
            assert_eq!(err.sample_index(), Some(3));
            let mut p = [7.0; 5];
            let err = pdf_batch(&hair, &[good; 5], &wi, &[0.0; 5], &mut p).unwrap_err();
            assert!(matches!(
                err,
                BatchError::Direction {
                    index: 3,
                    name: "wo",
                    ..
                }
            ));
            let mut p_before = [0.0; 3];
            pdf_batch(&hair, &[good; 3], &wi[..3], &[0.0; 3], &mut p_before).unwrap();
            assert_eq!(p[..3], p_before);
            assert_eq!(p[3..], [7.0; 2]);
        }
        let mut out = [[0.0; 3]; 2];
        let err = eval_batch(&hair, &[good; 2], &[good; 2], &[0.0, f32::NAN], &mut out);
        assert!(matches!(err, Err(BatchError::Offset { index: 1, .. })));
        // Within the tolerance a direction is evaluated as given; h beyond [-1, 1] is clamped.
        let nearly = [0.0, 0.6, 0.8005];
        assert!(eval_batch(&hair, &[nearly; 2], &[good; 2], &[5.0, -1.0], &mut out).is_ok());
    }

    /// Measured (100_000 random samples plus 3 x 144 hard cases plus 1_500 grazing / wi = wo /
    /// wi = -wo variants, 101_932 in all, seed 0x5eed, wide 1.7.1, x86_64 default target; the
    /// same for 8 and 16 lanes), error = |x - ref| / (|ref| + 1e-6), max over samples and RGB:
    /// - batch vs f64: 8.75e-6; scalar f32 vs f64: 8.77e-6 (7.1e-5 while `cos gamma_o` was
    ///   formed from `1 - h^2`, which loses digits in single precision at |h| -> 1);
    /// - batch vs scalar f32: 1.13e-5 (the `wide` approximations);
    /// - pdf batch vs f64: 8.8e-6.
    ///
    /// Bounds asserted: 2e-5 against f64, 1.2e-5 against scalar f32.
    #[test]
    fn batch_matches_scalar_and_reference() {
        batch_matches_scalar_and_reference_for(model().instantiate::<f32x8>());
    }

    #[test]
    fn sixteen_lanes_match_scalar_and_reference() {
        batch_matches_scalar_and_reference_for(model().instantiate::<f32x16>());
    }

    fn batch_matches_scalar_and_reference_for<L: BatchLanes>(hair8: ChiangHair<L>) {
        const FLOOR: f64 = 1e-6;
        const BOUND_VS_F64: f64 = 2e-5;
        const BOUND_VS_F32: f64 = 1.2e-5;
        let hair32 = model().instantiate::<f32>();
        let hair64 = model();
        let (wi, wo, h) = inputs(100_000);
        let n = wi.len();
        assert_ne!(n % L::LANES, 0, "the tail must be exercised");
        let mut batch = vec![[f32::NAN; 3]; n];
        eval_batch(&hair8, &wi, &wo, &h, &mut batch).unwrap();
        let mut scalar = Vec::with_capacity(n);
        let mut reference = Vec::with_capacity(n);
        for k in 0..n {
            scalar.push(hair32.eval(&Query::new(v3(wi[k]), v3(wo[k]), h[k])));
            reference.push(hair64.eval(&Query::new(v3(wi[k]), v3(wo[k]), h[k] as f64)));
        }
        for (k, s) in batch.iter().enumerate() {
            assert!(
                s.iter().all(|v| v.is_finite() && *v >= 0.0),
                "sample {k}: {s:?} for wi {:?} wo {:?} h {}",
                wi[k],
                wo[k],
                h[k]
            );
        }
        let scalar64: Vec<[f64; 3]> = scalar.iter().map(|s| s.map(f64::from)).collect();
        let (e_batch, k_batch) = max_rel(&batch, &reference, FLOOR);
        let (e_scalar, _) = max_rel(&scalar, &reference, FLOOR);
        let (e_vs_f32, k_vs) = max_rel(&batch, &scalar64, FLOOR);
        eprintln!(
            "{} lanes, n {n}: batch vs f64 {e_batch:.3e} (sample {k_batch}), f32 vs f64 {e_scalar:.3e}, \
             batch vs f32 {e_vs_f32:.3e} (sample {k_vs})",
            L::LANES
        );
        assert!(
            e_batch < BOUND_VS_F64,
            "batch vs f64: {e_batch:e} at {k_batch}"
        );
        assert!(e_scalar < BOUND_VS_F64, "f32 vs f64: {e_scalar:e}");
        assert!(
            e_vs_f32 < BOUND_VS_F32,
            "batch vs f32: {e_vs_f32:e} at {k_vs}"
        );

        // pdf through the same path.
        let mut pdf = vec![f32::NAN; n];
        pdf_batch(&hair8, &wi, &wo, &h, &mut pdf).unwrap();
        let mut worst = 0.0_f64;
        for k in 0..n {
            let r = hair64.pdf(&Query::new(v3(wi[k]), v3(wo[k]), h[k] as f64));
            worst = worst.max((pdf[k] as f64 - r).abs() / (r.abs() + FLOOR));
        }
        eprintln!("pdf batch vs f64 {worst:.3e}");
        assert!(worst < BOUND_VS_F64, "pdf batch vs f64: {worst:e}");
    }

    /// Every tail length 1..=33 gives the same values as evaluating the samples inside a full
    /// chunk, i.e. the padding never leaks into valid lanes.
    /// The structure-of-arrays batch gives the array-of-structures batch's values bit for bit,
    /// at every tail length and on the hard inputs, for both widths.
    #[test]
    fn structure_of_arrays_is_the_same_batch() {
        soa_agrees::<f32x8>();
        soa_agrees::<f32x16>();
    }

    fn soa_agrees<L: BatchLanes>() {
        let hair = model().instantiate::<L>();
        layouts_agree(
            &|wi, wo, h, out| eval_batch(&hair, wi, wo, h, out),
            &|wi, wo, h, out| eval_batch_soa(&hair, wi, wo, h, out),
        );
    }

    /// An array-of-structures batch function.
    pub(crate) type AosEval<'a> =
        dyn Fn(&[[f32; 3]], &[[f32; 3]], &[f32], &mut [[f32; 3]]) -> Result<(), BatchError> + 'a;
    /// A structure-of-arrays batch function.
    pub(crate) type SoaEval<'a> =
        dyn Fn(DirectionSlices, DirectionSlices, &[f32], RgbSlices) -> Result<(), BatchError> + 'a;

    /// `soa` gives `aos`'s values bit for bit on the random and hard inputs at every length
    /// 0..=33 and the whole set.
    pub(crate) fn layouts_agree(aos: &AosEval, soa: &SoaEval) {
        let (wi, wo, h) = inputs(300);
        let component = |d: &[[f32; 3]], c: usize| -> Vec<f32> { d.iter().map(|w| w[c]).collect() };
        let (wix, wiy, wiz) = (component(&wi, 0), component(&wi, 1), component(&wi, 2));
        let (wox, woy, woz) = (component(&wo, 0), component(&wo, 1), component(&wo, 2));
        for len in (0..=33).chain([wi.len()]) {
            let mut want = vec![[0.0; 3]; len];
            aos(&wi[..len], &wo[..len], &h[..len], &mut want).unwrap();
            let (mut r, mut g, mut b) = (
                vec![f32::NAN; len],
                vec![f32::NAN; len],
                vec![f32::NAN; len],
            );
            soa(
                DirectionSlices {
                    x: &wix[..len],
                    y: &wiy[..len],
                    z: &wiz[..len],
                },
                DirectionSlices {
                    x: &wox[..len],
                    y: &woy[..len],
                    z: &woz[..len],
                },
                &h[..len],
                RgbSlices {
                    r: &mut r,
                    g: &mut g,
                    b: &mut b,
                },
            )
            .unwrap();
            for k in 0..len {
                let got = [r[k], g[k], b[k]];
                assert_eq!(
                    got.map(f32::to_bits),
                    want[k].map(f32::to_bits),
                    "length {len}, sample {k}"
                );
            }
        }
    }

    /// Slices of other lengths and bad samples are typed errors naming the slice or the sample.
    #[test]
    fn structure_of_arrays_errors_name_the_slice_or_the_sample() {
        let hair = model().instantiate::<f32x8>();
        let ones = [1.0_f32; 20];
        let zeros = [0.0_f32; 20];
        let along = DirectionSlices {
            x: &ones,
            y: &zeros,
            z: &zeros,
        };
        let (mut r, mut g, mut b) = ([0.0; 20], [0.0; 20], [0.0; 20]);
        let short = DirectionSlices {
            y: &zeros[..19],
            ..along
        };
        let error = eval_batch_soa(
            &hair,
            along,
            short,
            &zeros,
            RgbSlices {
                r: &mut r,
                g: &mut g,
                b: &mut b,
            },
        );
        assert_eq!(
            error,
            Err(BatchError::ComponentLength {
                name: "wo.y",
                length: 19,
                samples: 20
            })
        );
        let error = eval_batch_soa(
            &hair,
            along,
            along,
            &zeros,
            RgbSlices {
                r: &mut r,
                g: &mut g[..3],
                b: &mut b,
            },
        );
        assert!(matches!(
            error,
            Err(BatchError::ComponentLength {
                name: "out.g",
                length: 3,
                ..
            })
        ));
        let mut tilted = ones;
        tilted[13] = 0.5;
        let bad = DirectionSlices {
            x: &tilted,
            ..along
        };
        let error = eval_batch_soa(
            &hair,
            along,
            bad,
            &zeros,
            RgbSlices {
                r: &mut r,
                g: &mut g,
                b: &mut b,
            },
        );
        assert!(
            matches!(
                error,
                Err(BatchError::Direction {
                    index: 13,
                    name: "wo",
                    ..
                })
            ),
            "{error:?}"
        );
        let mut offsets = zeros;
        offsets[17] = f32::NAN;
        let error = eval_batch_soa(
            &hair,
            along,
            along,
            &offsets,
            RgbSlices {
                r: &mut r,
                g: &mut g,
                b: &mut b,
            },
        );
        assert!(
            matches!(error, Err(BatchError::Offset { index: 17, .. })),
            "{error:?}"
        );
        // The samples before the bad one are evaluated, none from it on.
        let (mut r17, mut g17, mut b17) = ([0.0; 17], [0.0; 17], [0.0; 17]);
        let out17 = RgbSlices {
            r: &mut r17,
            g: &mut g17,
            b: &mut b17,
        };
        let along17 = along.range(0..17);
        eval_batch_soa(&hair, along17, along17, &zeros[..17], out17).unwrap();
        assert_eq!(
            (&r[..17], &g[..17], &b[..17]),
            (&r17[..], &g17[..], &b17[..])
        );
        assert!(
            r[17..].iter().all(|&v| v == 0.0),
            "out untouched from the bad sample"
        );
    }

    #[test]
    fn tails_of_every_length_agree_with_full_chunks() {
        tails_agree::<f32x8>();
        tails_agree::<f32x16>();
    }

    fn tails_agree<L: BatchLanes>() {
        let hair = model().instantiate::<L>();
        let (wi, wo, h) = inputs(48);
        let mut full = vec![[0.0; 3]; 48];
        eval_batch(&hair, &wi[..48], &wo[..48], &h[..48], &mut full).unwrap();
        for len in 1..=33 {
            let mut part = vec![[f32::NAN; 3]; len];
            eval_batch(&hair, &wi[..len], &wo[..len], &h[..len], &mut part).unwrap();
            assert_eq!(part[..], full[..len], "length {len}");
        }
    }

    /// The parallel batch is the sequential one bit for bit, in pools of one to three threads,
    /// on a length that is no multiple of the chunk or the lanes; a bad sample anywhere is the
    /// sequential batch's error, with the values of the samples before it in `out`.
    #[cfg(feature = "parallel")]
    #[test]
    fn the_parallel_batch_is_the_sequential_one() {
        let (wi, wo, h) = inputs(3 * PARALLEL_CHUNK + 5);
        let n = wi.len();
        let hair = model().instantiate::<BatchReal>();
        let mut expected = vec![[0.0_f32; 3]; n];
        eval_batch(&hair, &wi, &wo, &h, &mut expected).unwrap();
        let mut expected_pdf = vec![0.0_f32; n];
        pdf_batch(&hair, &wi, &wo, &h, &mut expected_pdf).unwrap();
        for threads in 1..=3 {
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .unwrap();
            let mut out = vec![[0.0_f32; 3]; n];
            pool.install(|| par_eval_batch(&hair, &wi, &wo, &h, &mut out))
                .unwrap();
            let bits =
                |v: &[[f32; 3]]| -> Vec<u32> { v.iter().flatten().map(|x| x.to_bits()).collect() };
            assert_eq!(bits(&out), bits(&expected), "{threads} threads");
            let mut pdf = vec![0.0_f32; n];
            pool.install(|| par_pdf_batch(&hair, &wi, &wo, &h, &mut pdf))
                .unwrap();
            let pdf_bits: Vec<u32> = pdf.iter().map(|x| x.to_bits()).collect();
            let expected_bits: Vec<u32> = expected_pdf.iter().map(|x| x.to_bits()).collect();
            assert_eq!(pdf_bits, expected_bits, "{threads} threads");
        }
        // Two bad samples in different chunks: the error is the first one's.
        let mut bad = wi.clone();
        bad[2 * PARALLEL_CHUNK + 1] = [f32::NAN, 0.0, 1.0];
        bad[3 * PARALLEL_CHUNK + 3] = [0.0; 3];
        let first = 2 * PARALLEL_CHUNK + 1;
        let mut sequential_out = vec![[7.0_f32; 3]; n];
        let sequential = eval_batch(&hair, &bad, &wo, &h, &mut sequential_out).unwrap_err();
        assert_eq!(sequential_out[..first], expected[..first]);
        assert!(sequential_out[first..].iter().flatten().all(|&x| x == 7.0));
        for threads in 1..=3 {
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .unwrap();
            let mut out = vec![[7.0_f32; 3]; n];
            let parallel = pool
                .install(|| par_eval_batch(&hair, &bad, &wo, &h, &mut out))
                .unwrap_err();
            // Debug output, not PartialEq: the error holds the NaN.
            assert_eq!(format!("{parallel:?}"), format!("{sequential:?}"));
            assert_eq!(out[..first], expected[..first], "{threads} threads");
        }
        let mut out = vec![[7.0_f32; 3]; n];
        let short = par_eval_batch(&hair, &wi[1..], &wo, &h, &mut out).unwrap_err();
        assert_eq!(
            short,
            eval_batch(&hair, &wi[1..], &wo, &h, &mut expected).unwrap_err()
        );
    }

    /// A structure of arrays as owned components: `[wi.x, wi.y, wi.z, wo.x, wo.y, wo.z]`.
    #[cfg(feature = "parallel")]
    fn soa_components(wi: &[[f32; 3]], wo: &[[f32; 3]]) -> [Vec<f32>; 6] {
        let component = |d: &[[f32; 3]], c: usize| d.iter().map(|w| w[c]).collect();
        [
            component(wi, 0),
            component(wi, 1),
            component(wi, 2),
            component(wo, 0),
            component(wo, 1),
            component(wo, 2),
        ]
    }

    /// The parallel structure-of-arrays batch ([`par_eval_batch_soa`] and
    /// [`crate::bcsdf::HostBatch::par_eval_soa`] on every instruction set the CPU runs) is the
    /// sequential one bit for bit, in pools of one to three threads, on a length that is no
    /// multiple of the chunk or the lanes; bad samples in the third and fourth chunks are the
    /// sequential batch's error (the first), with the values of the samples before it in
    /// `out` (and, sequentially, nothing written from it on).
    #[cfg(feature = "parallel")]
    #[test]
    fn the_parallel_structure_of_arrays_batch_is_the_sequential_one() {
        use crate::bcsdf::HostBatch;
        use crate::real::InstructionSet;
        type SoaEval<'a> = dyn Fn(DirectionSlices, DirectionSlices, &[f32], RgbSlices) -> Result<(), BatchError>
            + Sync
            + 'a;
        let (wi, wo, h) = inputs(3 * PARALLEL_CHUNK + 5);
        let n = h.len();
        let c = soa_components(&wi, &wo);
        let mut bad = c.clone();
        bad[1][2 * PARALLEL_CHUNK + 1] = f32::NAN;
        bad[3][3 * PARALLEL_CHUNK + 3] = 0.0;
        fn directions(c: &[Vec<f32>; 6]) -> (DirectionSlices<'_>, DirectionSlices<'_>) {
            let slices = |k: usize| DirectionSlices {
                x: &c[k],
                y: &c[k + 1],
                z: &c[k + 2],
            };
            (slices(0), slices(3))
        }
        // Every value as bits, or the error's Debug text (it may hold a NaN) with the bits of
        // the values before the bad sample; `sequential` also checks that nothing from the bad
        // sample on was written.
        let run = |eval: &SoaEval, c: &[Vec<f32>; 6], sequential: bool| {
            let mut rgb = [vec![7.0_f32; n], vec![7.0_f32; n], vec![7.0_f32; n]];
            let (wi, wo) = directions(c);
            let [r, g, b] = &mut rgb;
            let result = eval(wi, wo, &h, RgbSlices { r, g, b });
            let bits = |end: usize| -> Vec<u32> {
                rgb.iter()
                    .flat_map(|channel| &channel[..end])
                    .map(|x| x.to_bits())
                    .collect()
            };
            match result {
                Ok(()) => Ok(bits(n)),
                Err(e) => {
                    let first = e.sample_index().unwrap();
                    let after = rgb.iter().flat_map(|channel| &channel[first..]);
                    assert!(!sequential || after.into_iter().all(|&x| x == 7.0));
                    Err((format!("{e:?}"), bits(first)))
                }
            }
        };
        let hair = model().instantiate::<BatchReal>();
        let hosts: Vec<HostBatch<ChiangHair<f64>>> = InstructionSet::ALL
            .into_iter()
            .filter(|set| set.is_supported())
            .map(|set| HostBatch::on(set, &model()))
            .collect();
        let mut pairs: Vec<(Box<SoaEval>, Box<SoaEval>)> = vec![(
            Box::new(|wi, wo, h, out| eval_batch_soa(&hair, wi, wo, h, out)),
            Box::new(|wi, wo, h, out| par_eval_batch_soa(&hair, wi, wo, h, out)),
        )];
        for host in &hosts {
            pairs.push((
                Box::new(|wi, wo, h, out| host.eval_soa(wi, wo, h, out)),
                Box::new(|wi, wo, h, out| host.par_eval_soa(wi, wo, h, out)),
            ));
        }
        for (sequential, parallel) in &pairs {
            let (sequential, parallel) = (&**sequential, &**parallel);
            let (expected, expected_bad) = (run(sequential, &c, true), run(sequential, &bad, true));
            let (Ok(values), Err((_, before))) = (&expected, &expected_bad) else {
                panic!("the good batch must pass and the bad one fail");
            };
            // The values before the bad sample are those of the good batch.
            let first = 2 * PARALLEL_CHUNK + 1;
            let good_before: Vec<u32> = values
                .chunks(n)
                .flat_map(|c| &c[..first])
                .copied()
                .collect();
            assert_eq!(before, &good_before);
            for threads in 1..=3 {
                let pool = rayon::ThreadPoolBuilder::new()
                    .num_threads(threads)
                    .build()
                    .unwrap();
                pool.install(|| {
                    assert_eq!(run(parallel, &c, false), expected, "{threads} threads");
                    assert_eq!(
                        run(parallel, &bad, false),
                        expected_bad,
                        "{threads} threads"
                    );
                });
            }
        }
    }
}
