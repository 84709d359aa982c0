//! [`HostFarField`]: the fixed-node far field one query at a time, its mirrored pairs of
//! nodes spread over the lanes of the host's widest instruction set.

use super::chiang::{ChiangHair, CHIANG_LOBES};
use super::far_field::{ChiangFarField, OffsetNodes};
use super::host::{on_lanes, HostLanes, OnLanes};
use super::model::{Bcsdf, HairSample, Model, Query, RandomNumbers, SampledBcsdf};
use super::BatchLanes;
use crate::geometry::V3;
use crate::real::InstructionSet;
#[cfg(target_arch = "x86_64")]
use crate::real::{with_avx2, with_avx512};

/// The fixed-node far field evaluated one query at a time with its mirrored pairs of nodes in
/// SIMD lanes: the values of a [`ChiangFarField`] with the same rule, up to `f32` rounding,
/// for a renderer that shades one hit at a time.
///
/// The query is put in every lane, lane k sums the pairs `k, k + LANES, ...`, and the value,
/// the lobes and the pdf are the sums over the lanes; everything else is the far field's
/// generic code, compiled for the instruction set found at run time as
/// [`HostBatch`](super::HostBatch)'s kernels are. With 64 nodes on AVX-512 the 32 pairs take
/// two steps of sixteen lanes (9 times faster than scalar `f32` on the development machine,
/// README "Speed"). The lanes add the pairs in another order than the scalar loop and fuse
/// their multiply-adds, so the values differ from scalar `f32`'s by rounding; against the
/// same rule in `f64` they are within 2e-5 relative to the value + 1e-6 on every instruction
/// set (tests; 8.4e-6 measured at worst). [`Bcsdf::eval`] and
/// [`SampledBcsdf::pdf`] are inlined into the instruction set's copy; [`Bcsdf::eval_lobes`]
/// and [`SampledBcsdf::sample`] give the same values but call the lanes' intrinsics out of
/// line (slower).
///
/// # Examples
///
/// ```
/// use hairmath::bcsdf::{Bcsdf, ChiangFarField, FarFieldRule, HostFarField, Query};
/// use hairmath::geometry::V3;
/// use hairmath::params::HairParams;
///
/// let far = ChiangFarField::<f64>::with_rule(&HairParams::default(), &FarFieldRule::gauss_legendre(64)?);
/// let lanes = HostFarField::new(&far);
/// let s = lanes.eval(&Query::far(V3::new(-0.6, 0.0, 0.8), V3::new(0.6, 0.8, 0.0)));
/// let want = far.eval(&Query::far(V3::new(-0.6, 0.0, 0.8), V3::new(0.6, 0.8, 0.0)));
/// assert!((f64::from(s[0]) - want[0]).abs() < 2e-5 * want[0]);
/// println!("on {:?}", lanes.instruction_set());
/// # Ok::<(), hairmath::ParamError>(())
/// ```
pub struct HostFarField {
    lanes: HostLanes<ChiangFarField<f64>>,
}

impl HostFarField {
    /// `far` with its node pairs on the lanes of the host's widest instruction set
    /// ([`InstructionSet::host`]).
    pub fn new(far: &ChiangFarField<f64>) -> Self {
        Self::on(InstructionSet::host(), far)
    }

    /// `far` on the lanes of `set`, or of the widest set narrower than `set` that the CPU
    /// supports ([`HostFarField::instruction_set`] tells which). A query is one chain of
    /// dependent operations, so narrower lanes can be faster for a small rule: on the
    /// development machine's Zen 4, AVX2 beat AVX-512 up to 32 nodes and lost at 64 (README,
    /// "Speed").
    pub fn on(set: InstructionSet, far: &ChiangFarField<f64>) -> Self {
        HostFarField {
            lanes: HostLanes::on(set, &Spread(far)),
        }
    }

    /// The instruction set the evaluations run on.
    pub fn instruction_set(&self) -> InstructionSet {
        self.lanes.instruction_set()
    }
}

/// A far field to be put on lanes with its pairs spread over them.
struct Spread<'a>(&'a ChiangFarField<f64>);

impl OnLanes<ChiangFarField<f64>> for Spread<'_> {
    /// The far field on the lanes `L` with its pairs spread over them
    /// ([`OffsetNodes::spread_over_lanes`]).
    fn on_lanes<L: BatchLanes>(&self) -> ChiangFarField<L> {
        ChiangHair::with_offsets(
            *self.0.instantiate::<L>().uniforms(),
            OffsetNodes::spread_over_lanes(self.0.offsets()),
        )
    }
}

/// `x` in every lane.
#[inline(always)]
fn splat<L: BatchLanes>(x: f32) -> L {
    L::from_fn(
        #[inline(always)]
        |_| x,
    )
}

/// `v` in every lane.
#[inline(always)]
fn splat_v3<L: BatchLanes>(v: V3<f32>) -> V3<L> {
    V3::new(splat(v.x), splat(v.y), splat(v.z))
}

/// The query in every lane.
#[inline(always)]
fn splat_query<L: BatchLanes>(query: &Query<f32>) -> Query<L> {
    Query::new(splat_v3(query.wi), splat_v3(query.wo), splat(query.h))
}

/// The sum of the lanes: the far field from the parts of its pairs.
#[inline(always)]
fn lane_sum<L: BatchLanes>(x: L) -> f32 {
    (0..L::LANES).map(|k| x.lane(k)).sum()
}

impl Bcsdf<f32> for HostFarField {
    fn lobe_names(&self) -> &'static [&'static str] {
        &CHIANG_LOBES
    }

    fn uses_offset(&self) -> bool {
        false
    }

    fn eval(&self, query: &Query<f32>) -> [f32; 3] {
        on_lanes!(&self.lanes, |far| far
            .eval(&splat_query(query))
            .map(lane_sum))
    }

    fn eval_lobes(&self, query: &Query<f32>) -> Vec<[f32; 3]> {
        on_lanes!(&self.lanes, |far| far
            .eval_lobes(&splat_query(query))
            .into_iter()
            .map(|lobe| lobe.map(lane_sum))
            .collect())
    }
}

impl SampledBcsdf<f32> for HostFarField {
    fn pdf(&self, query: &Query<f32>) -> f32 {
        on_lanes!(&self.lanes, |far| lane_sum(far.pdf(&splat_query(query))))
    }

    /// The far field's sample ([`SampledBcsdf::sample`] of [`ChiangFarField`]): the node, lobe
    /// and direction chosen alike in every lane, the value and pdf summed over the lanes.
    fn sample(&self, wo: V3<f32>, h: f32, u: RandomNumbers<f32>) -> HairSample<f32> {
        on_lanes!(&self.lanes, |far| {
            let u = RandomNumbers {
                lobe: splat(u.lobe),
                longitudinal: splat(u.longitudinal),
                cone: splat(u.cone),
                offset: splat(u.offset),
            };
            let s = far.sample(splat_v3(wo), splat(h), u);
            HairSample {
                wi: V3::new(s.wi.x.lane(0), s.wi.y.lane(0), s.wi.z.lane(0)),
                value: s.value.map(lane_sum),
                pdf: lane_sum(s.pdf),
            }
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::bcsdf::batch::tests::{inputs, max_rel, v3};
    use crate::bcsdf::FarFieldRule;
    use crate::params::HairParams;
    use proptest::prelude::*;

    fn far(nodes: usize) -> ChiangFarField<f64> {
        let rule = FarFieldRule::gauss_legendre(nodes).unwrap();
        ChiangFarField::with_rule(&HairParams::default(), &rule)
    }

    fn supported() -> impl Iterator<Item = InstructionSet> {
        InstructionSet::ALL.into_iter().filter(|s| s.is_supported())
    }

    /// The largest of `|x - reference| / (|reference| + floor)` over `x`'s values.
    fn worst(x: &[f32], reference: &[f64], floor: f64) -> f64 {
        let rows = |v: &[f32]| v.iter().map(|&a| [a; 3]).collect::<Vec<_>>();
        let refs: Vec<[f64; 3]> = reference.iter().map(|&b| [b; 3]).collect();
        max_rel(&rows(x), &refs, floor).0
    }

    /// Every instruction set and node counts that fill the lanes, leave most of them empty,
    /// or are odd (the centre node with half its weight): the value, the lobes and the pdf
    /// against the same rule in `f64`, on random pairs and the hard cases (grazing, along the
    /// tangent, wi = wo, wi = -wo), within the batch's bound (2e-5 relative to the value +
    /// 1e-6). Measured on the AMD EPYC (Zen 4) development machine (printed): at most 7.66e-6
    /// for the value, 8.34e-6 for the lobes and 6.96e-6 for the pdf, all with 7 nodes on
    /// AVX-512 and AVX2; 2.5e-6, 3.5e-6 and 2.3e-6 with 64 nodes.
    #[test]
    fn every_instruction_set_matches_the_rule_in_f64() {
        const FLOOR: f64 = 1e-6;
        let (wi, wo, _) = inputs(1_500);
        for nodes in [1, 7, 8, 33, 64, 512] {
            let far64 = far(nodes);
            let queries64: Vec<Query<f64>> = (0..wi.len())
                .map(|k| Query::far(v3(wi[k]), v3(wo[k])))
                .collect();
            let queries32: Vec<Query<f32>> = (0..wi.len())
                .map(|k| Query::far(v3(wi[k]), v3(wo[k])))
                .collect();
            let want: Vec<[f64; 3]> = queries64.iter().map(|q| far64.eval(q)).collect();
            let want_lobes: Vec<Vec<[f64; 3]>> =
                queries64.iter().map(|q| far64.eval_lobes(q)).collect();
            let want_pdf: Vec<f64> = queries64.iter().map(|q| far64.pdf(q)).collect();
            for set in supported() {
                let lanes = HostFarField::on(set, &far64);
                assert_eq!(lanes.instruction_set(), set);
                let got: Vec<[f32; 3]> = queries32.iter().map(|q| lanes.eval(q)).collect();
                assert!(got.iter().flatten().all(|v| v.is_finite() && *v >= 0.0));
                let (value, k) = max_rel(&got, &want, FLOOR);
                let mut lobes = 0.0_f64;
                for (q, want) in queries32.iter().zip(&want_lobes) {
                    let got = lanes.eval_lobes(q);
                    assert_eq!(got.len(), want.len());
                    lobes = lobes.max(max_rel(&got, want, FLOOR).0);
                }
                let pdf: Vec<f32> = queries32.iter().map(|q| lanes.pdf(q)).collect();
                let pdf = worst(&pdf, &want_pdf, FLOOR);
                eprintln!(
                    "{nodes} nodes, {set:?}: value {value:.2e} (pair {k}), lobes {lobes:.2e}, \
                     pdf {pdf:.2e}"
                );
                assert!(value < 2e-5, "{nodes} nodes, {set:?}: {value:e} at {k}");
                assert!(lobes < 2e-5, "{nodes} nodes, {set:?}: lobes {lobes:e}");
                assert!(pdf < 2e-5, "{nodes} nodes, {set:?}: pdf {pdf:e}");
            }
        }
    }

    /// An instruction set the CPU does not run falls back to a narrower one it runs.
    #[test]
    fn unsupported_sets_fall_back() {
        for set in InstructionSet::ALL {
            let used = HostFarField::on(set, &far(8)).instruction_set();
            assert!(used.is_supported(), "{set:?} -> {used:?}");
            let order = |s| InstructionSet::ALL.iter().position(|x| *x == s);
            assert!(order(used) >= order(set), "{set:?} -> {used:?}");
        }
        assert_eq!(
            HostFarField::new(&far(8)).instruction_set(),
            InstructionSet::host()
        );
    }

    /// Sampling chooses what the rule in `f64` chooses (the same node, lobe and direction up
    /// to rounding), and returns the value and pdf of [`HostFarField::eval`] and
    /// [`HostFarField::pdf`] at the direction it returns.
    #[test]
    fn sampling_agrees_with_the_rule_and_with_eval() {
        let far64 = far(64);
        let (_, wo, _) = inputs(300);
        let mut rng = 0x9e37_79b9_u64;
        let mut uniform = move || {
            rng = rng.wrapping_mul(6_364_136_223_846_793_005).wrapping_add(1);
            ((rng >> 40) as f64 / (1u64 << 24) as f64).min(0.999_999)
        };
        for set in supported() {
            let lanes = HostFarField::on(set, &far64);
            for &wo in &wo {
                let u: [f64; 4] = core::array::from_fn(|_| uniform());
                let want = far64.sample(v3(wo), 0.0, numbers(u));
                let got = lanes.sample(v3(wo), 0.0, numbers(u));
                let wi = [got.wi.x, got.wi.y, got.wi.z];
                let distance = (0..3)
                    .map(|c| (f64::from(wi[c]) - [want.wi.x, want.wi.y, want.wi.z][c]).abs())
                    .fold(0.0, f64::max);
                assert!(distance < 1e-3, "{set:?}: {got:?} against {want:?}");
                let query = Query::far(got.wi, v3(wo));
                let (value, pdf) = (lanes.eval(&query), lanes.pdf(&query));
                for (got, value) in got.value.iter().zip(value) {
                    assert!(
                        (got - value).abs() <= 1e-5 * (value + 1e-6),
                        "{got} {value}"
                    );
                }
                assert!(
                    (got.pdf - pdf).abs() <= 1e-5 * (pdf + 1e-6),
                    "{got:?} {pdf}"
                );
                assert!(got.pdf.is_finite() && got.pdf >= 0.0);
            }
        }
    }

    /// `u` as the random numbers of a sample, in precision `R`.
    fn numbers<R: crate::real::Real>(u: [f64; 4]) -> RandomNumbers<R> {
        RandomNumbers {
            lobe: R::c(u[0]),
            longitudinal: R::c(u[1]),
            cone: R::c(u[2]),
            offset: R::c(u[3]),
        }
    }

    fn unit() -> impl Strategy<Value = [f32; 3]> {
        (
            -1.0_f32..=1.0,
            -core::f32::consts::PI..=core::f32::consts::PI,
        )
            .prop_map(|(x, a)| {
                let r = (1.0 - x * x).max(0.0).sqrt();
                [x, r * a.cos(), r * a.sin()]
            })
    }

    proptest! {
        /// Finite and non-negative over every pair of unit directions, on the host's set.
        #[test]
        fn finite_and_non_negative(wi in unit(), wo in unit()) {
            let lanes = HostFarField::new(&far(16));
            let query = Query::far(v3(wi), v3(wo));
            let s = lanes.eval(&query);
            prop_assert!(s.iter().all(|v| v.is_finite() && *v >= 0.0), "{s:?}");
            let pdf = lanes.pdf(&query);
            prop_assert!(pdf.is_finite() && pdf >= 0.0);
        }
    }
}
