//! Every model the command line (and any other front end that works by name) can build: one
//! line per model.

use super::far_field::FarField;
use super::inputs::{FromInputs, Input, InputValues};
use super::marschner::Marschner2003;
use super::model::Bcsdf;
use super::ChiangHair;
use crate::error::ParamError;

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
}

impl ModelEntry {
    /// The entry of model `M`.
    pub const fn of<M: FromInputs + Bcsdf<f64> + 'static>() -> Self {
        ModelEntry {
            name: M::NAME,
            summary: M::SUMMARY,
            inputs: M::INPUTS,
            build: build::<M>,
        }
    }
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
];

/// The registered model called `name`.
pub fn find_model(name: &str) -> Option<&'static ModelEntry> {
    MODELS.iter().find(|m| m.name == name)
}
