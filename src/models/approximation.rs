//! What makes a model a real-time *approximation* of the physical hair: a documented mapping
//! from the physical parameters to its own inputs, and the inputs a fit may vary to make it
//! match the reference best.
//!
//! [`crate::registry::MODELS`] lists every approximation with these, and the comparison
//! (`hairmath models`: the error against Chiang et al. 2016's far field, at the mapped inputs
//! and at fitted ones; the energy error; the cost) works on any model through them.

use crate::bcsdf::{FromInputs, InputValues, Model};
use crate::params::HairParams;

/// A real-time model of hair scattering that approximates the physical fibre of
/// [`HairParams`] (the reference being Chiang et al. 2016's far field).
pub trait Approximation: FromInputs + Model {
    /// The model's inputs for the physical hair `hair`, by the mapping its module documents
    /// (and justifies): every input of [`FromInputs::INPUTS`] present, so that
    /// [`FromInputs::from_inputs`] of the result succeeds for every valid `hair`.
    fn mapped_inputs(hair: &HairParams) -> InputValues;

    /// The names of the inputs a fit to the reference varies (numbers, RGB triples or an
    /// absorption given as a colour), starting from [`Approximation::mapped_inputs`]; the
    /// others keep their mapped values.
    const FITTED_INPUTS: &'static [&'static str];
}
