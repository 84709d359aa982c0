//! A model's best inputs: the values of its fitted inputs
//! ([`crate::models::Approximation::FITTED_INPUTS`]) that minimise its error E against a
//! reference ([`ReferenceSamples::relative_error`]), found with argmin's Nelder-Mead simplex.
//!
//! One mechanism for every model: the fitted inputs are flattened into a vector (a number is
//! one coordinate, an RGB triple or an absorption given as a colour or as sigma_a three,
//! melanin two), the simplex moves in that space, and a point whose inputs the model rejects
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
        Some(InputValue::Rgb(c))
        | Some(InputValue::Absorption(AbsorptionInput::Color(c)))
        | Some(InputValue::Absorption(AbsorptionInput::SigmaA(c))) => Ok(c.to_vec()),
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
        Some(InputValue::Absorption(AbsorptionInput::Color(_))) => {
            InputValue::Absorption(AbsorptionInput::Color(rgb()))
        }
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

/// The values of `fitted` (input names of `model`) that minimise E of `model` against
/// `reference`, starting from `start` (every input of the model; the others are kept): a
/// Nelder-Mead simplex whose first steps are a tenth of each coordinate (0.05 for a
/// coordinate near 0), run to [`INPUT_FIT_TOLERANCE`].
///
/// # Errors
/// [`FitError::Degenerate`] for an input that cannot be fitted or a start the model rejects;
/// [`FitError::NotConverged`] if the simplex does not converge.
pub fn fit_model_inputs(
    model: &ModelEntry,
    fitted: &[&'static str],
    start: &InputValues,
    reference: &ReferenceSamples,
) -> Result<InputFit, FitError> {
    (model.build)(start)?;
    let x0 = flattened_inputs(start, fitted)?;
    let step: Vec<f64> = x0
        .iter()
        .map(|v| if v.abs() > 0.5 { 0.1 * v } else { 0.05 })
        .collect();
    let loss = |x: &[f64]| input_loss(model, &inputs_at(start, fitted, x), reference);
    let what = format!("the inputs of {}", model.name);
    let minimum = minimize(&what, loss, &x0, &step, INPUT_FIT_TOLERANCE)?;
    let values = inputs_at(start, fitted, &minimum.params);
    let error = reference.relative_error((model.build)(&values)?.as_ref());
    Ok(InputFit {
        values,
        error,
        minimum,
    })
}
