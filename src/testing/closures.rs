//! A renderer's BSDF given as closures, as a hairmath model: what lets every harness of the kit
//! take either a [`Bcsdf`] / [`SampledBcsdf`] or plain functions.
//!
//! The closures work in hairmath's convention (S with no cosine factor, `wi` towards the
//! light, tangent +X); a renderer with another convention converts at the boundary with
//! [`Convention`](super::Convention).

use crate::bcsdf::{Bcsdf, HairSample, Query, RandomNumbers, SampledBcsdf};
use crate::geometry::V3;

/// A model from its evaluation closure ([`from_eval`]).
#[derive(Clone, Copy, Debug)]
pub struct EvalFn<E> {
    eval: E,
    uses_offset: bool,
}

/// The model whose S is `eval(query)`; `uses_offset` says whether it reads `query.h` (a
/// near-field model) or not (far field: the harnesses then evaluate it at h = 0 only).
pub fn from_eval<E>(eval: E, uses_offset: bool) -> EvalFn<E>
where
    E: Fn(&Query<f64>) -> [f64; 3],
{
    EvalFn { eval, uses_offset }
}

impl<E: Fn(&Query<f64>) -> [f64; 3]> Bcsdf<f64> for EvalFn<E> {
    fn lobe_names(&self) -> &'static [&'static str] {
        &["S"]
    }

    fn eval_lobes(&self, query: &Query<f64>) -> Vec<[f64; 3]> {
        vec![(self.eval)(query)]
    }

    fn uses_offset(&self) -> bool {
        self.uses_offset
    }

    fn eval(&self, query: &Query<f64>) -> [f64; 3] {
        (self.eval)(query)
    }
}

/// A model with importance sampling from its closures ([`from_sampler`]).
#[derive(Clone, Copy, Debug)]
pub struct SamplerFns<E, P, S> {
    model: EvalFn<E>,
    pdf: P,
    sample: S,
}

/// The model with S = `eval(query)`, density `pdf(query)` of wi given wo and h, and sampler
/// `sample(wo, h, u)` ([`SampledBcsdf`]'s contract); `uses_offset` as in [`from_eval`].
pub fn from_sampler<E, P, S>(eval: E, pdf: P, sample: S, uses_offset: bool) -> SamplerFns<E, P, S>
where
    E: Fn(&Query<f64>) -> [f64; 3],
    P: Fn(&Query<f64>) -> f64,
    S: Fn(V3<f64>, f64, RandomNumbers<f64>) -> HairSample<f64>,
{
    SamplerFns {
        model: from_eval(eval, uses_offset),
        pdf,
        sample,
    }
}

impl<E, P, S> Bcsdf<f64> for SamplerFns<E, P, S>
where
    E: Fn(&Query<f64>) -> [f64; 3],
{
    fn lobe_names(&self) -> &'static [&'static str] {
        self.model.lobe_names()
    }

    fn eval_lobes(&self, query: &Query<f64>) -> Vec<[f64; 3]> {
        self.model.eval_lobes(query)
    }

    fn uses_offset(&self) -> bool {
        self.model.uses_offset
    }

    fn eval(&self, query: &Query<f64>) -> [f64; 3] {
        self.model.eval(query)
    }
}

impl<E, P, S> SampledBcsdf<f64> for SamplerFns<E, P, S>
where
    E: Fn(&Query<f64>) -> [f64; 3],
    P: Fn(&Query<f64>) -> f64,
    S: Fn(V3<f64>, f64, RandomNumbers<f64>) -> HairSample<f64>,
{
    fn pdf(&self, query: &Query<f64>) -> f64 {
        (self.pdf)(query)
    }

    fn sample(&self, wo: V3<f64>, h: f64, u: RandomNumbers<f64>) -> HairSample<f64> {
        (self.sample)(wo, h, u)
    }
}
