//! Finiteness and non-negativity of a renderer's BSDF over the whole parameter domain: S (and,
//! for a sampler, the pdf and the sample) at the hard cases of `docs/ARCHITECTURE.md` for a set
//! of hard parameters, then at proptest cases of [`strategies`](super::strategies), a failure
//! shrunk by proptest to a small counterexample.
//!
//! The harness takes a *factory*, the renderer's model built from [`HairParams`], so that
//! the search covers parameters as well as directions.

use super::compare::hard_queries;
use super::strategies::{hair_params, query, random_numbers};
use crate::absorption::Absorption;
use crate::bcsdf::{Bcsdf, Query, RandomNumbers, SampledBcsdf};
use crate::params::{
    AzimuthalRoughness, CuticleTilt, HairParams, LongitudinalRoughness, RefractiveIndex,
};
use core::cell::Cell;
use core::fmt;
use proptest::test_runner::{Config, RngAlgorithm, TestError, TestRng, TestRunner};

/// The proptest cases and seed of a values check.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ValueSettings {
    /// proptest cases after the hard cases.
    pub cases: u32,
    /// The seed of proptest's generator (a report is reproducible).
    pub seed: u64,
}

impl Default for ValueSettings {
    /// 2,000 cases, seed 1.
    fn default() -> Self {
        ValueSettings {
            cases: 2_000,
            seed: 1,
        }
    }
}

/// One output of a model at one input, and whether it is allowed.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Output {
    /// What it is (`S_r`, `pdf`, `sample |wi|`, ...).
    pub name: &'static str,
    /// Its value.
    pub value: f64,
    /// What is allowed.
    pub allowed: &'static str,
    /// Whether the value is allowed.
    pub ok: bool,
}

/// The inputs of one check and the output that failed (or the lowest one).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ValueCase {
    /// The model's parameters.
    pub params: HairParams,
    /// The query.
    pub query: Query<f64>,
    /// The random numbers (samplers only).
    pub numbers: Option<RandomNumbers<f64>>,
    /// The output.
    pub output: Output,
}

impl fmt::Display for ValueCase {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let p = &self.params;
        let q = &self.query;
        write!(
            f,
            "{} = {:e} (allowed: {}) at beta_m {}, beta_n {}, alpha {} rad, eta {}, sigma_a \
             {:?}; wi ({}, {}, {}), wo ({}, {}, {}), h {}",
            self.output.name,
            self.output.value,
            self.output.allowed,
            p.beta_m.get(),
            p.beta_n.get(),
            p.alpha.get(),
            p.eta.get(),
            p.sigma_a.rgb(),
            q.wi.x,
            q.wi.y,
            q.wi.z,
            q.wo.x,
            q.wo.y,
            q.wo.z,
            q.h
        )?;
        if let Some(u) = self.numbers {
            write!(
                f,
                "; u = (lobe {}, longitudinal {}, cone {}, offset {})",
                u.lobe, u.longitudinal, u.cone, u.offset
            )?;
        }
        Ok(())
    }
}

/// The outcome of [`eval_values`] or [`sampler_values`].
#[derive(Clone, Debug, PartialEq)]
pub struct ValueReport {
    /// Inputs checked (hard cases and proptest cases, shrinking steps included).
    pub evaluated: usize,
    /// The first output not allowed (none if every output was allowed): at a hard case, or
    /// as proptest shrank it ([`ValueReport::at_hard_case`]).
    pub failure: Option<ValueCase>,
    /// Whether [`ValueReport::failure`] is at a hard case (else proptest found and shrank it).
    pub at_hard_case: bool,
    /// The lowest allowed value of S seen, with its inputs (a value of 0 far from every lobe
    /// is normal; a tiny negative one would have failed).
    pub lowest: Option<ValueCase>,
}

impl ValueReport {
    /// Whether every output was allowed.
    pub fn passes(&self) -> bool {
        self.failure.is_none()
    }
}

impl fmt::Display for ValueReport {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match &self.failure {
            Some(case) => writeln!(
                f,
                "FAILED after {} inputs ({}): {case}",
                self.evaluated,
                if self.at_hard_case {
                    "a hard case"
                } else {
                    "found and shrunk by proptest"
                }
            ),
            None => writeln!(
                f,
                "every output finite and allowed at {} inputs (hard cases, then proptest)",
                self.evaluated
            ),
        }?;
        if let Some(lowest) = &self.lowest {
            writeln!(f, "  lowest S: {lowest}")?;
        }
        Ok(())
    }
}

/// The hard parameters: brown hair ([`HairParams::default`]) and its variants at the ends of
/// each range: beta 0.01 and 1, no absorption and sigma_a = 20, eta = 1.001, no tilt and
/// +-10 degrees.
pub fn hard_params() -> Vec<HairParams> {
    let base = HairParams::default();
    let mut params = vec![base];
    let mut push = |changed: Result<HairParams, crate::ParamError>| {
        params.extend(changed.ok());
    };
    for beta in [0.01, 1.0] {
        push(LongitudinalRoughness::new(beta).and_then(|beta_m| {
            Ok(HairParams {
                beta_m,
                beta_n: AzimuthalRoughness::new(beta)?,
                ..base
            })
        }));
    }
    for sigma in [0.0, 20.0] {
        push(Absorption::grey(sigma).map(|sigma_a| HairParams { sigma_a, ..base }));
    }
    push(RefractiveIndex::new(1.001).map(|eta| HairParams { eta, ..base }));
    for degrees in [0.0, 10.0, -10.0] {
        push(CuticleTilt::from_degrees(degrees).map(|alpha| HairParams { alpha, ..base }));
    }
    params
}

/// The outputs of S: its three channels, each finite and >= 0.
fn s_outputs(s: [f64; 3]) -> [Output; 3] {
    let names = ["S_r", "S_g", "S_b"];
    core::array::from_fn(|c| non_negative(names[c], s[c]))
}

fn non_negative(name: &'static str, value: f64) -> Output {
    Output {
        name,
        value,
        allowed: "finite and >= 0",
        ok: value.is_finite() && value >= 0.0,
    }
}

/// Checks S of the model `make(params)` for every hard parameter set at every hard query, then
/// at `settings.cases` proptest cases of ([`hair_params`], [`query`]): every channel finite
/// and >= 0.
pub fn eval_values<M, F>(make: F, settings: &ValueSettings) -> ValueReport
where
    M: Bcsdf<f64>,
    F: Fn(&HairParams) -> M,
{
    search(
        make,
        |model: &M, query, _| s_outputs(model.eval(query)).to_vec(),
        false,
        settings,
    )
}

/// [`eval_values`] for a sampler: S, the pdf, and the sample at [`random_numbers`] (its
/// direction a finite unit vector, its value and pdf finite and >= 0).
pub fn sampler_values<M, F>(make: F, settings: &ValueSettings) -> ValueReport
where
    M: SampledBcsdf<f64>,
    F: Fn(&HairParams) -> M,
{
    search(
        make,
        |model: &M, query, u| {
            let mut outputs = s_outputs(model.eval(query)).to_vec();
            outputs.push(non_negative("pdf", model.pdf(query)));
            let sample = model.sample(query.wo, query.h, u);
            let length = sample.wi.dot(sample.wi).sqrt();
            outputs.push(Output {
                name: "sample |wi|",
                value: length,
                allowed: "1 within 1e-6",
                ok: (length - 1.0).abs() <= 1e-6,
            });
            let names = ["sample value_r", "sample value_g", "sample value_b"];
            outputs.extend((0..3).map(|c| non_negative(names[c], sample.value[c])));
            outputs.push(non_negative("sample pdf", sample.pdf));
            outputs
        },
        true,
        settings,
    )
}

/// The hard cases (each hard parameter set's model built once), then proptest over
/// (parameters, query, random numbers): the first output not allowed (shrunk), or none, and
/// the lowest S.
fn search<M, F, O>(make: F, outputs: O, sampled: bool, settings: &ValueSettings) -> ValueReport
where
    F: Fn(&HairParams) -> M,
    O: Fn(&M, &Query<f64>, RandomNumbers<f64>) -> Vec<Output>,
{
    let evaluated = Cell::new(0_usize);
    let lowest = Cell::new(None::<ValueCase>);
    let check = |model: &M, params: &HairParams, query: &Query<f64>, u: RandomNumbers<f64>| {
        evaluated.set(evaluated.get() + 1);
        let case = |output: Output| ValueCase {
            params: *params,
            query: *query,
            numbers: sampled.then_some(u),
            output,
        };
        let all = outputs(model, query, u);
        for output in all.iter().filter(|o| o.ok && o.name.starts_with("S_")) {
            if lowest.get().is_none_or(|l| output.value < l.output.value) {
                lowest.set(Some(case(*output)));
            }
        }
        all.into_iter().find(|o| !o.ok).map(case)
    };
    let middle = RandomNumbers {
        lobe: 0.5,
        longitudinal: 0.5,
        cone: 0.5,
        offset: 0.5,
    };
    let queries = hard_queries();
    let hard = hard_params().into_iter().find_map(|params| {
        let model = make(&params);
        queries
            .iter()
            .find_map(|query| check(&model, &params, query, middle))
    });
    let at_hard_case = hard.is_some();
    let failure = hard.or_else(|| {
        proptest_search(
            &|params: &HairParams, query: &Query<f64>, u| check(&make(params), params, query, u),
            settings,
        )
    });
    ValueReport {
        evaluated: evaluated.get(),
        failure,
        at_hard_case,
        lowest: lowest.get(),
    }
}

/// proptest's search for an input where `check` finds an output not allowed, shrunk.
fn proptest_search<C>(check: &C, settings: &ValueSettings) -> Option<ValueCase>
where
    C: Fn(&HairParams, &Query<f64>, RandomNumbers<f64>) -> Option<ValueCase>,
{
    let config = Config {
        cases: settings.cases,
        failure_persistence: None,
        ..Config::default()
    };
    let mut seed = [0_u8; 32];
    seed[..8].copy_from_slice(&settings.seed.to_le_bytes());
    let mut runner =
        TestRunner::new_with_rng(config, TestRng::from_seed(RngAlgorithm::ChaCha, &seed));
    let strategy = (hair_params(), query(), random_numbers());
    let result = runner.run(&strategy, |(params, query, u)| {
        match check(&params, &query, u) {
            None => Ok(()),
            Some(case) => Err(proptest::test_runner::TestCaseError::fail(case.to_string())),
        }
    });
    match result {
        Err(TestError::Fail(_, (params, query, u))) => check(&params, &query, u),
        _ => None,
    }
}
