//! World space: every model evaluated, given a pdf and sampled from a world-space fibre
//! tangent and world-space directions, given as glam vectors ([`glam::Vec3`] in `f32`,
//! [`glam::DVec3`] in `f64`) or as the crate's [`V3`] in any precision.
//!
//! A renderer has a tangent (root to tip) and the directions towards the light (`wi`) and
//! towards the viewer (`wo`) in world space. The models ([`Bcsdf`], [`SampledBcsdf`]) work in
//! the fibre's local frame (tangent +X); this module puts the two together with the one frame
//! construction the crate has, [`crate::geometry::fibre_frame`] (Duff et al. 2017), the same
//! code the shaders' `hair_bcsdf_world` is traced from ([`crate::geometry::local_directions`]).
//! The local frame's normal is arbitrary about the tangent, which is harmless: every model
//! depends on the azimuths of `wi` and `wo` only through their difference, and on `h`, which is
//! measured across the fibre as `wo` sees it (Chiang et al. 2016, section 4).
//!
//! - [`WorldBcsdf::eval_world`], [`WorldSampledBcsdf::pdf_world`] and
//!   [`WorldSampledBcsdf::sample_world`] for any model, in `f32` with [`glam::Vec3`], in `f64`
//!   with [`glam::DVec3`], or in any [`Real`] with [`V3`]: unchecked, like [`Query::new`] (the
//!   hot path);
//! - [`world_query`]: the checked local query of untrusted world-space values;
//! - [`eval_batch_world`] and [`pdf_batch_world`]: the SIMD batch
//!   ([`crate::bcsdf::eval_batch`], [`crate::bcsdf::pdf_batch`]) from slices of
//!   [`glam::Vec3`], every sample checked.
//!
//! # Examples
//!
//! Brown hair (eumelanin 1.3) lit from above, seen from the side, in world space:
//!
//! ```
//! use hairmath::bcsdf::ChiangHair;
//! use hairmath::glam::DVec3;
//! use hairmath::params::HairParams;
//! use hairmath::world::WorldBcsdf;
//!
//! let hair = ChiangHair::new(&HairParams::default());
//! let tangent = DVec3::new(0.0, -1.0, 0.0); // the strand hangs down
//! let wi = DVec3::new(0.0, 0.6, 0.8); // towards the light
//! let wo = DVec3::new(1.0, 0.0, 0.0); // towards the camera
//! let s = hair.eval_world(tangent, wi, wo, 0.0);
//! assert!(s.iter().all(|v| v.is_finite() && *v > 0.0));
//! ```

use crate::bcsdf::{
    check_lengths, check_samples, eval_samples, pdf_samples, BatchError, BatchLanes, Bcsdf,
    HairSample, Query, RandomNumbers, SampledBcsdf,
};
#[cfg(doc)]
use crate::bcsdf::{eval_batch, pdf_batch};
use crate::error::ParamError;
use crate::geometry::{fibre_frame, local_directions, FibreFrame, V3};
use crate::real::Real;

/// A vector type the world-space API takes: [`glam::Vec3`] (`f32`), [`glam::DVec3`] (`f64`)
/// or the crate's [`V3`] in any precision.
pub trait WorldVector: Copy {
    /// The precision of its components.
    type Real: Real;
    /// The same vector as a [`V3`].
    fn to_v3(self) -> V3<Self::Real>;
    /// A [`V3`] as this type.
    fn from_v3(v: V3<Self::Real>) -> Self;
}

/// `WorldVector` for a glam vector type of precision `$real` (through its `From` conversions
/// with [`V3`]).
macro_rules! glam_world_vector {
    ($glam:ty, $real:ty) => {
        impl WorldVector for $glam {
            type Real = $real;
            fn to_v3(self) -> V3<$real> {
                self.into()
            }
            fn from_v3(v: V3<$real>) -> Self {
                v.into()
            }
        }
    };
}

glam_world_vector!(glam::Vec3, f32);
glam_world_vector!(glam::DVec3, f64);

impl<R: Real> WorldVector for V3<R> {
    type Real = R;
    fn to_v3(self) -> V3<R> {
        self
    }
    fn from_v3(v: V3<R>) -> Self {
        v
    }
}

/// The local query of world-space `tangent`, `wi`, `wo` and the offset `h`, unchecked like
/// [`Query::new`]: the directions expressed in the frame of
/// [`crate::geometry::fibre_frame`] by [`local_directions`] (what a world-space shader
/// computes). `tangent` need not be unit; it must be non-zero with a finite squared length.
pub fn local_query<V: WorldVector>(tangent: V, wi: V, wo: V, h: V::Real) -> Query<V::Real> {
    let [wi, wo] = local_directions(tangent.to_v3(), wi.to_v3(), wo.to_v3());
    Query::new(wi, wo, h)
}

/// The checked local query of untrusted world-space values: `tangent` any finite non-zero
/// vector however long or short ([`FibreFrame::new`]: the frame of
/// [`crate::geometry::fibre_frame`] after dividing the tangent by its largest component),
/// the directions and `h` checked as [`Query::checked`] does (after the rotation, which keeps
/// their lengths).
///
/// # Errors
/// [`ParamError::BadVector`] naming the tangent, or as [`Query::checked`].
pub fn world_query(
    tangent: glam::DVec3,
    wi: glam::DVec3,
    wo: glam::DVec3,
    h: f64,
) -> Result<Query<f64>, ParamError> {
    let frame = FibreFrame::new(tangent)?;
    let local = |w| V3::from(frame.to_local(w));
    Query::checked(local(wi), local(wo), h)
}

/// Evaluation of any model from world-space vectors (implemented for every [`Bcsdf`]).
pub trait WorldBcsdf<V: WorldVector> {
    /// `S(wi, wo, h)` per channel (no cosine factor) for the fibre of direction `tangent`, all
    /// in world space ([`local_query`]; unchecked: [`world_query`] checks untrusted values).
    fn eval_world(&self, tangent: V, wi: V, wo: V, h: V::Real) -> [V::Real; 3];
}

impl<V: WorldVector, M: Bcsdf<V::Real> + ?Sized> WorldBcsdf<V> for M {
    fn eval_world(&self, tangent: V, wi: V, wo: V, h: V::Real) -> [V::Real; 3] {
        self.eval(&local_query(tangent, wi, wo, h))
    }
}

/// One importance sample in world space ([`SampledBcsdf::sample`]'s [`HairSample`] with `wi`
/// turned back to world space).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct WorldSample<V: WorldVector> {
    /// The sampled direction towards the light, unit, in world space.
    pub wi: V,
    /// `S(wi, wo, h)` per channel (no cosine factor).
    pub value: [V::Real; 3],
    /// The solid-angle density of `wi`.
    pub pdf: V::Real,
}

impl<V: WorldVector> WorldSample<V> {
    /// The estimator weight `value / pdf` per channel ([`HairSample::weight`]).
    pub fn weight(&self) -> [V::Real; 3] {
        HairSample {
            wi: self.wi.to_v3(),
            value: self.value,
            pdf: self.pdf,
        }
        .weight()
    }
}

/// The pdf and importance sampling of any model from world-space vectors (implemented for
/// every [`SampledBcsdf`]).
pub trait WorldSampledBcsdf<V: WorldVector>: WorldBcsdf<V> {
    /// The solid-angle density with which [`WorldSampledBcsdf::sample_world`] chooses `wi`
    /// given `wo` and `h` (world space, unchecked as [`WorldBcsdf::eval_world`]).
    fn pdf_world(&self, tangent: V, wi: V, wo: V, h: V::Real) -> V::Real;

    /// Draws `wi` given the world-space `wo` and `h` from the uniform numbers `u`, returned in
    /// world space with S and the density there.
    fn sample_world(
        &self,
        tangent: V,
        wo: V,
        h: V::Real,
        u: RandomNumbers<V::Real>,
    ) -> WorldSample<V>;
}

impl<V: WorldVector, M: SampledBcsdf<V::Real> + ?Sized> WorldSampledBcsdf<V> for M {
    fn pdf_world(&self, tangent: V, wi: V, wo: V, h: V::Real) -> V::Real {
        self.pdf(&local_query(tangent, wi, wo, h))
    }

    fn sample_world(
        &self,
        tangent: V,
        wo: V,
        h: V::Real,
        u: RandomNumbers<V::Real>,
    ) -> WorldSample<V> {
        let [t, n, b] = fibre_frame(tangent.to_v3());
        let wo = wo.to_v3();
        let local_wo = V3::new(wo.dot(t), wo.dot(n), wo.dot(b));
        let HairSample { wi, value, pdf } = self.sample(local_wo, h, u);
        let world = t.scale(wi.x) + n.scale(wi.y) + b.scale(wi.z);
        WorldSample {
            wi: V::from_v3(world),
            value,
            pdf,
        }
    }
}

/// Samples per block of [`eval_batch_world`]: one block's directions are copied (and turned
/// into the local frame) into stack buffers.
const WORLD_BLOCK: usize = 256;

/// [`eval_batch`] from world-space slices: `S(wi[k], wo[k], h[k])` per channel into `out[k]`
/// for the fibre of direction `tangent[k]`, `L::LANES` samples at a time. Each tangent is
/// divided by its largest component and the directions expressed in its
/// [`crate::geometry::fibre_frame`] (as [`world_query`] does), in `f32`; then the model runs
/// as in [`eval_batch`].
///
/// # Errors
/// [`BatchError::Length`] or [`BatchError::TangentLength`] if the slices differ in length,
/// [`BatchError::Tangent`] for a zero or non-finite tangent, [`BatchError::Direction`] or
/// [`BatchError::Offset`] naming the first bad sample (directions checked in world space as
/// [`eval_batch`] checks them), with what `out` then holds as there.
pub fn eval_batch_world<L: BatchLanes, M: Bcsdf<L>>(
    model: &M,
    tangent: &[glam::Vec3],
    wi: &[glam::Vec3],
    wo: &[glam::Vec3],
    h: &[f32],
    out: &mut [[f32; 3]],
) -> Result<(), BatchError> {
    let samples = WorldSamples { tangent, wi, wo, h };
    world_batch(samples, out, |wi, wo, h, out| {
        eval_samples::<L, M, false>(model, wi, wo, h, out)
    })
}

/// [`pdf_batch`] from world-space slices, as [`eval_batch_world`] is [`eval_batch`]: the
/// density of `wi[k]` given `wo[k]` and `h[k]` for the fibre of direction `tangent[k]`.
///
/// # Errors
/// As [`eval_batch_world`].
pub fn pdf_batch_world<L: BatchLanes, M: SampledBcsdf<L>>(
    model: &M,
    tangent: &[glam::Vec3],
    wi: &[glam::Vec3],
    wo: &[glam::Vec3],
    h: &[f32],
    out: &mut [f32],
) -> Result<(), BatchError> {
    let samples = WorldSamples { tangent, wi, wo, h };
    world_batch(samples, out, |wi, wo, h, out| {
        pdf_samples::<L, M, false>(model, wi, wo, h, out)
    })
}

/// The inputs of a world-space batch.
#[derive(Clone, Copy)]
pub(crate) struct WorldSamples<'a> {
    pub(crate) tangent: &'a [glam::Vec3],
    pub(crate) wi: &'a [glam::Vec3],
    pub(crate) wo: &'a [glam::Vec3],
    pub(crate) h: &'a [f32],
}

/// Checks the samples of a world-space batch (lengths, tangents, directions in world space,
/// offsets) block by block, and runs `local` on each block's local directions with the
/// matching `out` right after its check (while it is in cache). At the first bad sample, the
/// samples before it are evaluated and its error returned, as in [`eval_batch`]. `local`
/// evaluates samples checked here, so it does not fail.
pub(crate) fn world_batch<T>(
    samples: WorldSamples,
    out: &mut [T],
    local: impl Fn(&[[f32; 3]], &[[f32; 3]], &[f32], &mut [T]) -> Result<(), BatchError>,
) -> Result<(), BatchError> {
    let WorldSamples { tangent, wi, wo, h } = samples;
    check_lengths(wi.len(), wo.len(), h.len(), out.len())?;
    if tangent.len() != wi.len() {
        return Err(BatchError::TangentLength {
            tangent: tangent.len(),
            samples: wi.len(),
        });
    }
    let mut block_wi = [[0.0_f32; 3]; WORLD_BLOCK];
    let mut block_wo = [[0.0_f32; 3]; WORLD_BLOCK];
    let outs = out.chunks_mut(WORLD_BLOCK);
    for ((start, block), out) in blocks(samples).zip(outs) {
        let valid = check_world_samples(block);
        let end = valid
            .as_ref()
            .map_or_else(|e| e.sample_index().unwrap_or(0), |()| block.h.len());
        for k in 0..end {
            let t = block.tangent[k] / block.tangent[k].abs().max_element();
            let [i, o] = local_directions(t.into(), block.wi[k].into(), block.wo[k].into());
            block_wi[k] = [i.x, i.y, i.z];
            block_wo[k] = [o.x, o.y, o.z];
        }
        local(
            &block_wi[..end],
            &block_wo[..end],
            &block.h[..end],
            &mut out[..end],
        )?;
        valid.map_err(|e| e.shifted(start))?;
    }
    Ok(())
}

/// The first bad sample of a block of world-space samples (at most [`WORLD_BLOCK`], lengths
/// already checked): a zero or non-finite tangent, or a sample [`check_samples`] refuses,
/// whichever comes first.
fn check_world_samples(block: WorldSamples) -> Result<(), BatchError> {
    let WorldSamples { tangent, wi, wo, h } = block;
    let bad_tangent = tangent.iter().position(|t| !usable_tangent(*t)).map(|k| {
        let t = tangent[k];
        let (x, y, z) = (t.x, t.y, t.z);
        BatchError::Tangent { index: k, x, y, z }
    });
    let mut block_wi = [[0.0_f32; 3]; WORLD_BLOCK];
    let mut block_wo = [[0.0_f32; 3]; WORLD_BLOCK];
    for k in 0..h.len() {
        block_wi[k] = wi[k].to_array();
        block_wo[k] = wo[k].to_array();
    }
    let bad_sample = check_samples(&block_wi[..h.len()], &block_wo[..h.len()], h).err();
    match [bad_tangent, bad_sample]
        .into_iter()
        .flatten()
        .min_by_key(BatchError::sample_index)
    {
        Some(error) => Err(error),
        None => Ok(()),
    }
}

/// The world-space samples in blocks of [`WORLD_BLOCK`], each with its first index.
fn blocks(samples: WorldSamples<'_>) -> impl Iterator<Item = (usize, WorldSamples<'_>)> {
    let WorldSamples { tangent, wi, wo, h } = samples;
    let chunks = |v| <[glam::Vec3]>::chunks(v, WORLD_BLOCK);
    let zipped = chunks(tangent)
        .zip(chunks(wi))
        .zip(chunks(wo).zip(h.chunks(WORLD_BLOCK)));
    let blocks = zipped.map(|((tangent, wi), (wo, h))| WorldSamples { tangent, wi, wo, h });
    (0..).step_by(WORLD_BLOCK).zip(blocks)
}

/// Whether a tangent has a frame: finite and non-zero.
fn usable_tangent(t: glam::Vec3) -> bool {
    t.is_finite() && t.abs().max_element() > 0.0
}
