//! A model's best inputs: the values of its fitted inputs
//! ([`crate::models::Approximation::FITTED_INPUTS`]) that minimise its error E against a
//! reference ([`ReferenceSamples::relative_error`]), found with argmin's Nelder-Mead simplex.
//!
//! One mechanism for every model: the fitted inputs are flattened into a vector (a number is
//! one coordinate, an RGB triple or an absorption given as a colour or as sigma_a three,
//! melanin two; a colour's channels enter as their optical densities `-ln c`, which spread the
//! dark colours of real hair, 1e-3 to 1e-12 per channel, over a scale the simplex can step
//! on), the simplex moves in that space, and a point whose inputs the model rejects
//! ([`crate::bcsdf::FromInputs::from_inputs`] fails) costs [`INFEASIBLE_LOSS`], so the search
//! stays inside each input's domain without the fit knowing it.

use super::optimise::{minimize, FitError, Minimum};
use crate::bcsdf::{AbsorptionInput, InputValue, InputValues};
use crate::diagnostics::{ModelError, ReferenceSamples};
use crate::registry::ModelEntry;

/// The loss of inputs the model rejects: far above any E of a valid model (E = 1 for a model
/// that is 0 everywhere).
pub const INFEASIBLE_LOSS: f64 = 1.0e6;

/// Standard deviation of the simplex's losses at which the fit stops: E is reported to two or
/// three significant digits; at this tolerance the fitted inputs are within about 1e-4
/// relative of the minimum (a closed-form check in tests/comparison.rs).
pub const INPUT_FIT_TOLERANCE: f64 = 1.0e-9;

/// The result of [`fit_model_inputs`].
#[derive(Clone, Debug, PartialEq)]
pub struct InputFit {
    /// Every input of the model: the fitted ones at the minimum, the others as given.
    pub values: InputValues,
    /// E at the minimum, on the pairs of the fit.
    pub error: ModelError,
    /// The optimiser's run (its parameters are the flattened fitted inputs).
    pub minimum: Minimum,
}

/// The flattened coordinates of input `name` of `values`.
fn flatten(values: &InputValues, name: &'static str) -> Result<Vec<f64>, FitError> {
    let not_fittable = |what: &str| FitError::Degenerate {
        what: format!("input {name}"),
        reason: format!("{what} cannot be fitted"),
    };
    match values.get(name) {
        Some(InputValue::Number(v)) => Ok(vec![v]),
        Some(InputValue::Rgb(c)) | Some(InputValue::Absorption(AbsorptionInput::SigmaA(c))) => {
            Ok(c.to_vec())
        }
        Some(InputValue::Absorption(AbsorptionInput::Color(c))) => {
            Ok(c.iter().map(|v| -v.ln()).collect())
        }
        Some(InputValue::Absorption(AbsorptionInput::Melanin {
            eumelanin,
            pheomelanin,
        })) => Ok(vec![eumelanin, pheomelanin]),
        Some(InputValue::Count(_)) => Err(not_fittable("a count")),
        Some(InputValue::Switch(_)) => Err(not_fittable("a switch")),
        None => Err(not_fittable("an absent input")),
    }
}

/// `values` with input `name` replaced by the next coordinates of `x` (the shape of its
/// current value).
fn unflatten(values: &mut InputValues, name: &'static str, x: &mut core::slice::Iter<'_, f64>) {
    let mut next = || *x.next().expect("one coordinate per flattened value");
    let mut rgb = || [next(), next(), next()];
    let value = match values.get(name) {
        Some(InputValue::Number(_)) => InputValue::Number(next()),
        Some(InputValue::Rgb(_)) => InputValue::Rgb(rgb()),
        Some(InputValue::Absorption(AbsorptionInput::Color(_))) => InputValue::Absorption(
            AbsorptionInput::Color(rgb().map(|density| (-density).exp())),
        ),
        Some(InputValue::Absorption(AbsorptionInput::SigmaA(_))) => {
            InputValue::Absorption(AbsorptionInput::SigmaA(rgb()))
        }
        Some(InputValue::Absorption(AbsorptionInput::Melanin { .. })) => {
            let (eumelanin, pheomelanin) = (next(), next());
            InputValue::Absorption(AbsorptionInput::Melanin {
                eumelanin,
                pheomelanin,
            })
        }
        _ => return,
    };
    values.set(name, value);
}

/// The inputs `start` with the fitted inputs `names` set from the flattened vector `x`.
pub fn inputs_at(start: &InputValues, names: &[&'static str], x: &[f64]) -> InputValues {
    let mut values = start.clone();
    let mut coordinates = x.iter();
    for &name in names {
        unflatten(&mut values, name, &mut coordinates);
    }
    values
}

/// The flattened vector of the fitted inputs `names` of `values`.
///
/// # Errors
/// [`FitError::Degenerate`] for an input that is absent, a count or a switch.
pub fn flattened_inputs(
    values: &InputValues,
    names: &[&'static str],
) -> Result<Vec<f64>, FitError> {
    let mut x = Vec::new();
    for &name in names {
        x.extend(flatten(values, name)?);
    }
    Ok(x)
}

/// E of `model` built from `values` on `reference`, or [`INFEASIBLE_LOSS`] if the model
/// rejects them.
pub fn input_loss(model: &ModelEntry, values: &InputValues, reference: &ReferenceSamples) -> f64 {
    match (model.build)(values) {
        Ok(m) => reference
            .relative_error(m.as_ref())
            .full
            .min(INFEASIBLE_LOSS),
        Err(_) => INFEASIBLE_LOSS,
    }
}

/// Most Nelder-Mead runs of one fit ([`fit_model_inputs`]).
pub const MAX_INPUT_FIT_RUNS: usize = 40;

/// A fit stops when a restarted simplex improves E by less than this fraction of E.
pub const RESTART_IMPROVEMENT: f64 = 1.0e-6;

/// The first steps of a simplex around `x`.
fn simplex_steps(x: &[f64]) -> Vec<f64> {
    x.iter()
        .map(|v| if v.abs() > 0.5 { 0.1 * v } else { 0.05 })
        .collect()
}

/// The values of `fitted` (input names of `model`) that minimise E of `model` against
/// `reference`, starting from `start` (every input of the model; the others are kept).
///
/// Nelder-Mead simplices ([`minimize`]) run to [`INPUT_FIT_TOLERANCE`], each restarted from
/// the previous one's best point with a fresh simplex (steps of a tenth of each coordinate, or
/// 0.05 below 0.5) until a run improves E by less than [`RESTART_IMPROVEMENT`] of itself (at
/// most [`MAX_INPUT_FIT_RUNS`] runs): a single simplex on inputs of very different scales
/// (weights near 0.05, exponents near 10), or with a weight pressed against its bound 0, often
/// collapses before the minimum, which a restart detects and resumes. The returned
/// [`Minimum::iterations`] counts every run's iterations.
///
/// # Errors
/// [`FitError::Degenerate`] for an input that cannot be fitted or a start the model rejects;
/// [`FitError::NotConverged`] if a simplex does not converge, or if the runs still improve E
/// after [`MAX_INPUT_FIT_RUNS`].
pub fn fit_model_inputs(
    model: &ModelEntry,
    fitted: &[&'static str],
    start: &InputValues,
    reference: &ReferenceSamples,
) -> Result<InputFit, FitError> {
    (model.build)(start)?;
    let loss = |x: &[f64]| input_loss(model, &inputs_at(start, fitted, x), reference);
    let what = format!("the inputs of {}", model.name);
    let mut x = flattened_inputs(start, fitted)?;
    let mut best = loss(&x);
    let mut iterations = 0;
    for _ in 0..MAX_INPUT_FIT_RUNS {
        let run = minimize(&what, loss, &x, &simplex_steps(&x), INPUT_FIT_TOLERANCE)?;
        iterations += run.iterations;
        let improvement = best - run.loss;
        if run.loss < best {
            x = run.params.clone();
            best = run.loss;
        }
        if improvement < RESTART_IMPROVEMENT * best {
            let values = inputs_at(start, fitted, &x);
            let error = reference.relative_error((model.build)(&values)?.as_ref());
            let minimum = Minimum {
                params: x,
                loss: best,
                iterations,
                ..run
            };
            return Ok(InputFit {
                values,
                error,
                minimum,
            });
        }
    }
    Err(FitError::NotConverged {
        what,
        reason: format!("E still improved after {MAX_INPUT_FIT_RUNS} restarted simplices"),
    })
}
