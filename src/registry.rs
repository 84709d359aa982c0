//! Every model the command line (and any other front end that works by name) can build: one
//! line per model, the reference models of [`crate::bcsdf`] and the real-time approximations
//! of [`crate::models`].

use crate::bcsdf::{trace_eval, BatchEval};
use crate::bcsdf::{Bcsdf, ChiangHair, FarField, FromInputs, Input, InputValues, Marschner2003};
use crate::error::ParamError;
use crate::models::Approximation;
use crate::params::HairParams;
use crate::real::{BatchReal, Graph};

/// Builds a model from its input values, evaluated in `f64`.
pub type BuildModel = fn(&InputValues) -> Result<Box<dyn Bcsdf<f64>>, ParamError>;

/// A model that can be built by name from [`InputValues`].
#[derive(Clone, Copy, Debug)]
pub struct ModelEntry {
    /// The model's name ([`FromInputs::NAME`]).
    pub name: &'static str,
    /// What it is ([`FromInputs::SUMMARY`]).
    pub summary: &'static str,
    /// Its inputs ([`FromInputs::INPUTS`]).
    pub inputs: &'static [Input],
    /// Builds it, evaluated in `f64`.
    pub build: BuildModel,
    /// What the comparison with the reference needs, for a real-time approximation
    /// ([`ModelEntry::approximation`]); `None` for the reference models.
    pub approximation: Option<ApproximationEntry>,
}

/// Builds a model from its input values, evaluated in `f32` (the uniforms rounded once).
pub type BuildModelF32 = fn(&InputValues) -> Result<Box<dyn Bcsdf<f32>>, ParamError>;

/// Traces a model built from its input values: [`trace_eval`]'s graph.
pub type TraceModel = fn(&InputValues) -> Result<Graph, ParamError>;

/// The [`Approximation`] side of a registered model, type-erased.
#[derive(Clone, Copy, Debug)]
pub struct ApproximationEntry {
    /// [`Approximation::mapped_inputs`].
    pub mapped_inputs: fn(&HairParams) -> InputValues,
    /// [`Approximation::FITTED_INPUTS`].
    pub fitted_inputs: &'static [&'static str],
    /// Builds the model in `f32`.
    pub build_f32: BuildModelF32,
    /// Traces its evaluation.
    pub trace: TraceModel,
    /// Builds it on the SIMD lanes of [`BatchReal`].
    pub build_batch: BuildModelBatch,
}

/// Builds a model from its input values on the SIMD lanes of [`BatchReal`] (the uniforms
/// rounded once to `f32`).
pub type BuildModelBatch = fn(&InputValues) -> Result<Box<dyn BatchEval>, ParamError>;

impl ModelEntry {
    /// The entry of model `M`.
    pub const fn of<M: FromInputs + Bcsdf<f64> + 'static>() -> Self {
        ModelEntry {
            name: M::NAME,
            summary: M::SUMMARY,
            inputs: M::INPUTS,
            build: build::<M>,
            approximation: None,
        }
    }

    /// The entry of the real-time approximation `M`.
    pub const fn approximation<M: Approximation + 'static>() -> Self
    where
        M::In<f32>: 'static,
        M::In<BatchReal>: 'static,
    {
        ModelEntry {
            approximation: Some(ApproximationEntry {
                mapped_inputs: M::mapped_inputs,
                fitted_inputs: M::FITTED_INPUTS,
                build_f32: build_f32::<M>,
                trace: trace::<M>,
                build_batch: build_batch::<M>,
            }),
            ..Self::of::<M>()
        }
    }
}

fn build_f32<M: Approximation>(values: &InputValues) -> Result<Box<dyn Bcsdf<f32>>, ParamError>
where
    M::In<f32>: 'static,
{
    Ok(Box::new(M::from_inputs(values)?.instantiate::<f32>()))
}

fn build_batch<M: Approximation>(values: &InputValues) -> Result<Box<dyn BatchEval>, ParamError>
where
    M::In<BatchReal>: 'static,
{
    Ok(Box::new(M::from_inputs(values)?.instantiate::<BatchReal>()))
}

fn trace<M: Approximation>(values: &InputValues) -> Result<Graph, ParamError> {
    Ok(trace_eval(&M::from_inputs(values)?))
}

fn build<M: FromInputs + Bcsdf<f64> + 'static>(
    values: &InputValues,
) -> Result<Box<dyn Bcsdf<f64>>, ParamError> {
    Ok(Box::new(M::from_inputs(values)?))
}

/// The registered models, in the order the command line lists them.
pub const MODELS: &[ModelEntry] = &[
    ModelEntry::of::<ChiangHair<f64>>(),
    ModelEntry::of::<FarField>(),
    ModelEntry::of::<Marschner2003>(),
    ModelEntry::approximation::<crate::models::Karis<f64>>(),
    ModelEntry::approximation::<crate::models::KarisRefit<f64>>(),
    ModelEntry::approximation::<crate::models::KajiyaKay<f64>>(),
    ModelEntry::approximation::<crate::models::TressFx<f64>>(),
    ModelEntry::approximation::<crate::models::Scheuermann<f64>>(),
    ModelEntry::approximation::<crate::models::NguyenDonnelly<f64>>(),
    ModelEntry::approximation::<crate::models::Gerard<f64>>(),
    ModelEntry::approximation::<crate::models::Frostbite<f64>>(),
    ModelEntry::approximation::<crate::models::FrostbiteRefit<f64>>(),
];

/// The registered model called `name`.
impl ModelEntry {
    /// The values of the model's inputs when none is given: each input's default, and for the
    /// inputs without one (the physical parameters, the absorption) the default hair's
    /// (`HairParams::default()`), through the model's mapping for a real-time model (whose
    /// mapped values also replace the defaults). What the committed shaders are emitted at.
    pub fn example_values(&self) -> InputValues {
        let hair = HairParams::default();
        let given = match self.approximation {
            Some(a) => (a.mapped_inputs)(&hair),
            None => hair.to_inputs(),
        };
        let mut values = InputValues::new();
        for input in self.inputs {
            if let Some(value) = given.get(input.name).or_else(|| input.default_value()) {
                values.set(input.name, value);
            }
        }
        values
    }
}

pub fn find_model(name: &str) -> Option<&'static ModelEntry> {
    MODELS.iter().find(|m| m.name == name)
}
