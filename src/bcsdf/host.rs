//! Batch evaluation on the host's widest instruction set, chosen at run time.
//!
//! [`HostBatch::new`] detects the CPU's instruction sets once ([`InstructionSet::host`]) and
//! instantiates the model on that set's lanes: sixteen per AVX-512 register, eight per AVX2
//! register (both with fused multiply-adds), or the build's [`BatchReal`] on any other CPU.
//! Its evaluations run the same generic kernel as [`eval_batch`], inlined into a function
//! compiled with the set's target features, so a default build (no `RUSTFLAGS`) runs the
//! machine's instructions instead of the x86-64 baseline's SSE2.
//!
//! **Accuracy.** Each instruction set rounds differently (fused multiply-adds), so the lanes
//! differ from each other and from the scalar `f32` path by a few ulp; the tests hold every
//! set to the bounds of the `wide` lanes against `f64` and scalar `f32`
//! ([`eval_batch`]'s module documentation).

use super::batch::{
    check, check_soa_lengths, eval_samples, eval_soa_samples, BatchError, BatchEval, BatchLanes,
    BatchReal, DirectionSlices, RgbSlices,
};
use super::model::Model;
use crate::real::InstructionSet;
#[cfg(target_arch = "x86_64")]
use crate::real::{with_avx2, with_avx512, Avx2Lanes, Avx512Lanes};
use crate::world::{world_batch, WorldSamples};

/// A model instantiated on the lanes of one instruction set, normally the host's widest:
/// batch evaluation that needs no `-C target-cpu` flag to use AVX-512 or AVX2. Models whose
/// kernel is not inlined throughout ([`Model::INLINED_KERNEL`]: so far only
/// [`ComposedHair`](crate::models::ComposedHair)) run on the build's lanes.
///
/// # Examples
///
/// ```
/// use hairmath::bcsdf::{ChiangHair, HostBatch};
/// use hairmath::params::HairParams;
///
/// let batch = HostBatch::new(&ChiangHair::new(&HairParams::default()));
/// let (wi, wo) = ([[-0.6, 0.8, 0.0]; 20], [[0.6, 0.0, 0.8]; 20]);
/// let mut out = [[0.0_f32; 3]; 20];
/// batch.eval(&wi, &wo, &[0.1; 20], &mut out)?;
/// assert!(out.iter().all(|s| s == &out[0] && s[0] > 0.0));
/// println!("evaluated with {:?}", batch.instruction_set());
/// # Ok::<(), hairmath::bcsdf::BatchError>(())
/// ```
pub struct HostBatch<M: Model> {
    lanes: HostLanes<M>,
}

/// The model on the lanes of its instruction set. A variant for AVX-512 or AVX2 is only built
/// on a CPU that supports it: their lanes execute those instructions (`crate::real::isa`).
pub(super) enum HostLanes<M: Model> {
    #[cfg(target_arch = "x86_64")]
    Avx512(M::In<Avx512Lanes>),
    #[cfg(target_arch = "x86_64")]
    Avx2(M::In<Avx2Lanes>),
    Baseline(M::In<BatchReal>),
}

/// `$body` with `$model` bound to the instantiated model, inlined into the function compiled
/// for its instruction set.
macro_rules! on_lanes {
    ($lanes:expr, |$model:ident| $body:expr) => {
        match $lanes {
            #[cfg(target_arch = "x86_64")]
            HostLanes::Avx512($model) => {
                // SAFETY: the variant exists only on a CPU with AVX-512 (`HostBatch::on`).
                unsafe {
                    with_avx512(
                        #[inline(always)]
                        || $body,
                    )
                }
            }
            #[cfg(target_arch = "x86_64")]
            HostLanes::Avx2($model) => {
                // SAFETY: the variant exists only on a CPU with AVX2 and FMA.
                unsafe {
                    with_avx2(
                        #[inline(always)]
                        || $body,
                    )
                }
            }
            HostLanes::Baseline($model) => $body,
        }
    };
}

pub(super) use on_lanes;

/// How a model is put on lanes: [`Model::instantiate`] for [`HostBatch`], the far field with
/// its node pairs spread over the lanes for [`HostFarField`](super::HostFarField).
pub(super) trait OnLanes<M: Model> {
    /// The model on the lanes `L`.
    fn on_lanes<L: BatchLanes>(&self) -> M::In<L>;
}

impl<M: Model> OnLanes<M> for M {
    fn on_lanes<L: BatchLanes>(&self) -> M::In<L> {
        self.instantiate()
    }
}

impl<M: Model> HostLanes<M> {
    /// `model` on the lanes of `set`, or of the widest set narrower than `set` that the CPU
    /// supports; on the baseline if its kernel is not inlined throughout
    /// ([`Model::INLINED_KERNEL`]).
    pub(super) fn on(set: InstructionSet, model: &impl OnLanes<M>) -> Self {
        let run = InstructionSet::ALL
            .into_iter()
            .skip_while(|s| *s != set)
            .find(|s| s.is_supported() && (M::INLINED_KERNEL || *s == InstructionSet::Baseline))
            .unwrap_or(InstructionSet::Baseline);
        match run {
            #[cfg(target_arch = "x86_64")]
            InstructionSet::Avx512 => HostLanes::Avx512(model.on_lanes()),
            #[cfg(target_arch = "x86_64")]
            InstructionSet::Avx2 => HostLanes::Avx2(model.on_lanes()),
            _ => HostLanes::Baseline(model.on_lanes()),
        }
    }

    /// The instruction set of the lanes.
    pub(super) fn instruction_set(&self) -> InstructionSet {
        match self {
            #[cfg(target_arch = "x86_64")]
            HostLanes::Avx512(_) => InstructionSet::Avx512,
            #[cfg(target_arch = "x86_64")]
            HostLanes::Avx2(_) => InstructionSet::Avx2,
            HostLanes::Baseline(_) => InstructionSet::Baseline,
        }
    }
}

impl<M: Model> HostBatch<M> {
    /// `model` on the lanes of the host's widest instruction set ([`InstructionSet::host`]).
    pub fn new(model: &M) -> Self {
        Self::on(InstructionSet::host(), model)
    }

    /// `model` on the lanes of `set`, or of the widest set narrower than `set` that the CPU
    /// supports ([`HostBatch::instruction_set`] tells which): for comparing instruction sets.
    /// A model whose kernel is not inlined throughout ([`Model::INLINED_KERNEL`]) runs on the
    /// build's lanes ([`InstructionSet::Baseline`]).
    pub fn on(set: InstructionSet, model: &M) -> Self {
        HostBatch {
            lanes: HostLanes::on(set, model),
        }
    }

    /// The instruction set the evaluations run on.
    pub fn instruction_set(&self) -> InstructionSet {
        self.lanes.instruction_set()
    }

    /// [`eval_batch`](super::eval_batch) on this instruction set's lanes: `S(wi[k], wo[k],
    /// h[k])` per channel into `out[k]`, every sample checked before it is evaluated.
    ///
    /// # Errors
    /// As [`eval_batch`](super::eval_batch), with what `out` then holds.
    pub fn eval(
        &self,
        wi: &[[f32; 3]],
        wo: &[[f32; 3]],
        h: &[f32],
        out: &mut [[f32; 3]],
    ) -> Result<(), BatchError> {
        check(wi.len(), wo.len(), h.len(), out.len())?;
        // Checked on the lanes' instruction set too, block by block before the evaluation.
        on_lanes!(&self.lanes, |model| {
            eval_samples::<_, _, true>(model, wi, wo, h, out)
        })
    }

    /// [`eval_batch_soa`](super::eval_batch_soa) on this instruction set's lanes.
    ///
    /// # Errors
    /// As [`eval_batch_soa`](super::eval_batch_soa), with what `out` then holds.
    pub fn eval_soa(
        &self,
        wi: DirectionSlices<'_>,
        wo: DirectionSlices<'_>,
        h: &[f32],
        out: RgbSlices<'_>,
    ) -> Result<(), BatchError> {
        check_soa_lengths(&wi, &wo, h, &out)?;
        // Checked on the lanes' instruction set too, as in [`HostBatch::eval`].
        on_lanes!(&self.lanes, |model| {
            eval_soa_samples(model, wi, wo, h, out)
        })
    }

    /// [`crate::world::eval_batch_world`] on this instruction set's lanes: `S(wi[k], wo[k],
    /// h[k])` per channel into `out[k]` for the fibre of direction `tangent[k]`, all in world
    /// space, every sample checked first.
    ///
    /// # Errors
    /// As [`crate::world::eval_batch_world`]; `out` is then untouched.
    pub fn eval_world(
        &self,
        tangent: &[glam::Vec3],
        wi: &[glam::Vec3],
        wo: &[glam::Vec3],
        h: &[f32],
        out: &mut [[f32; 3]],
    ) -> Result<(), BatchError> {
        let samples = WorldSamples { tangent, wi, wo, h };
        world_batch(samples, out, |wi, wo, h, out| {
            on_lanes!(&self.lanes, |model| {
                eval_samples::<_, _, false>(model, wi, wo, h, out)
            })
        })
    }

    /// [`HostBatch::eval`] on every thread of rayon's current pool, in chunks of
    /// [`super::PARALLEL_CHUNK`] samples: the values of [`HostBatch::eval`], bit for bit,
    /// whatever the thread count.
    ///
    /// # Errors
    /// As [`par_eval_batch`](super::par_eval_batch), with what `out` then holds.
    #[cfg(feature = "parallel")]
    pub fn par_eval(
        &self,
        wi: &[[f32; 3]],
        wo: &[[f32; 3]],
        h: &[f32],
        out: &mut [[f32; 3]],
    ) -> Result<(), BatchError>
    where
        Self: Sync,
    {
        check(wi.len(), wo.len(), h.len(), out.len())?;
        super::batch::for_each_parallel_chunk(wi, wo, h, out, |wi, wo, h, out| {
            on_lanes!(&self.lanes, |model| {
                eval_samples::<_, _, true>(model, wi, wo, h, out)
            })
        })
    }

    /// [`HostBatch::eval_soa`] on every thread of rayon's current pool, in chunks of
    /// [`super::PARALLEL_CHUNK`] samples: the values of [`HostBatch::eval_soa`], bit for bit,
    /// whatever the thread count.
    ///
    /// # Errors
    /// As [`par_eval_batch_soa`](super::par_eval_batch_soa), with what `out` then holds.
    #[cfg(feature = "parallel")]
    pub fn par_eval_soa(
        &self,
        wi: DirectionSlices<'_>,
        wo: DirectionSlices<'_>,
        h: &[f32],
        out: RgbSlices<'_>,
    ) -> Result<(), BatchError>
    where
        Self: Sync,
    {
        check_soa_lengths(&wi, &wo, h, &out)?;
        super::batch::for_each_parallel_soa_chunk(wi, wo, h, out, |wi, wo, h, out| {
            on_lanes!(&self.lanes, |model| {
                eval_soa_samples(model, wi, wo, h, out)
            })
        })
    }
}

impl<M: Model> BatchEval for HostBatch<M> {
    fn eval_batch_lanes(
        &self,
        wi: &[[f32; 3]],
        wo: &[[f32; 3]],
        h: &[f32],
        out: &mut [[f32; 3]],
    ) -> Result<(), BatchError> {
        self.eval(wi, wo, h, out)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::bcsdf::batch::tests::{inputs, layouts_agree, max_rel, model, v3};
    use crate::bcsdf::{eval_batch, Bcsdf, ChiangHair, Query};

    fn supported() -> impl Iterator<Item = InstructionSet> {
        InstructionSet::ALL.into_iter().filter(|s| s.is_supported())
    }

    /// Every instruction set this CPU runs, against `f64` and scalar `f32` on 100k random
    /// samples and the hard cases, with the bounds of the `wide` lanes
    /// (`batch_matches_scalar_and_reference`). Measured on the AMD EPYC (Zen 4) development
    /// machine, default build: against f64 8.99e-6 with AVX-512 and AVX2, 8.75e-6 on the
    /// baseline, all at the same sample; against scalar f32 1.15e-5 with AVX-512 and AVX2 and
    /// 1.13e-5 on the baseline (the lanes fuse their multiply-adds, scalar `f32` rounds
    /// twice, and each is within 9e-6 of `f64`).
    #[test]
    fn every_instruction_set_matches_scalar_and_reference() {
        const FLOOR: f64 = 1e-6;
        let (hair32, hair64) = (model().instantiate::<f32>(), model());
        let (wi, wo, h) = inputs(100_000);
        let n = wi.len();
        let mut scalar = Vec::with_capacity(n);
        let mut reference = Vec::with_capacity(n);
        for k in 0..n {
            let f32_value = hair32.eval(&Query::new(v3(wi[k]), v3(wo[k]), h[k]));
            scalar.push(f32_value.map(f64::from));
            reference.push(hair64.eval(&Query::new(v3(wi[k]), v3(wo[k]), h[k] as f64)));
        }
        assert!(InstructionSet::host().is_supported());
        assert!(InstructionSet::Baseline.is_supported());
        assert_eq!(
            HostBatch::new(&model()).instruction_set(),
            InstructionSet::host()
        );
        for set in supported() {
            let batch = HostBatch::on(set, &model());
            assert_eq!(batch.instruction_set(), set);
            let mut out = vec![[f32::NAN; 3]; n];
            batch.eval(&wi, &wo, &h, &mut out).unwrap();
            assert!(out.iter().flatten().all(|v| v.is_finite() && *v >= 0.0));
            let (vs_f64, k64) = max_rel(&out, &reference, FLOOR);
            let (vs_f32, k32) = max_rel(&out, &scalar, FLOOR);
            eprintln!(
                "{set:?}: vs f64 {vs_f64:.3e} (sample {k64}), vs f32 {vs_f32:.3e} (sample {k32})"
            );
            assert!(vs_f64 < 2e-5, "{set:?} vs f64: {vs_f64:e} at {k64}");
            assert!(vs_f32 < 1.2e-5, "{set:?} vs f32: {vs_f32:e} at {k32}");
        }
    }

    /// The baseline is `eval_batch` on [`BatchReal`], bit for bit; an instruction set the CPU
    /// does not run falls back to a narrower one it runs (a model whose kernel is not inlined
    /// throughout runs the baseline: `tests/composed.rs`).
    #[test]
    fn the_baseline_is_eval_batch_and_unsupported_sets_fall_back() {
        let (wi, wo, h) = inputs(300);
        let mut want = vec![[0.0; 3]; wi.len()];
        eval_batch(&model().instantiate::<BatchReal>(), &wi, &wo, &h, &mut want).unwrap();
        let mut got = vec![[f32::NAN; 3]; wi.len()];
        let baseline = HostBatch::on(InstructionSet::Baseline, &model());
        baseline.eval(&wi, &wo, &h, &mut got).unwrap();
        assert_eq!(got, want);
        for set in InstructionSet::ALL {
            let used = HostBatch::on(set, &model()).instruction_set();
            assert!(used.is_supported(), "{set:?} -> {used:?}");
            let order = |s| InstructionSet::ALL.iter().position(|x| *x == s);
            assert!(order(used) >= order(set), "{set:?} -> {used:?}");
            assert_eq!(used == set, set.is_supported());
        }
    }

    /// The structure-of-arrays and parallel entry points give [`HostBatch::eval`]'s values bit
    /// for bit on every instruction set, at every tail length; errors are `eval_batch`'s, with
    /// the values of the samples before the bad one in `out`.
    #[test]
    fn every_entry_point_agrees_and_errors_are_typed() {
        let (wi, wo, h) = inputs(300);
        for set in supported() {
            let batch = HostBatch::on(set, &ChiangHair::new(&Default::default()));
            layouts_agree(
                &|wi, wo, h, out| batch.eval(wi, wo, h, out),
                &|wi, wo, h, out| batch.eval_soa(wi, wo, h, out),
            );
            #[cfg(feature = "parallel")]
            layouts_agree(
                &|wi, wo, h, out| batch.eval(wi, wo, h, out),
                &|wi, wo, h, out| {
                    let n = h.len();
                    let mut aos = vec![[0.0; 3]; n];
                    let rows = |d: &DirectionSlices| -> Vec<[f32; 3]> {
                        (0..n).map(|k| [d.x[k], d.y[k], d.z[k]]).collect()
                    };
                    batch.par_eval(&rows(&wi), &rows(&wo), h, &mut aos)?;
                    for (k, v) in aos.iter().enumerate() {
                        (out.r[k], out.g[k], out.b[k]) = (v[0], v[1], v[2]);
                    }
                    Ok(())
                },
            );
            let mut out = [[7.0; 3]; 2];
            let short = batch.eval(&wi[..2], &wo[..1], &h[..2], &mut out);
            assert!(matches!(short, Err(BatchError::Length(_))));
            let bad = batch.eval(&[[0.0; 3], wi[0]], &wo[..2], &h[..2], &mut out);
            assert!(matches!(
                bad,
                Err(BatchError::Direction {
                    index: 0,
                    name: "wi",
                    ..
                })
            ));
            #[cfg(feature = "parallel")]
            let nan = batch.par_eval(&wi[..2], &wo[..2], &[0.0, f32::NAN], &mut out);
            #[cfg(not(feature = "parallel"))]
            let nan = batch.eval(&wi[..2], &wo[..2], &[0.0, f32::NAN], &mut out);
            assert!(matches!(nan, Err(BatchError::Offset { index: 1, .. })));
            let mut first = [[0.0; 3]];
            batch.eval(&wi[..1], &wo[..1], &[0.0], &mut first).unwrap();
            assert_eq!(out[0], first[0]);
        }
    }
}
