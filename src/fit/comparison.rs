//! Every real-time model against the reference, error and cost side by side on the same work:
//! the table of `hairmath models`.
//!
//! For each registered approximation ([`crate::registry::MODELS`] entries with an
//! [`ApproximationEntry`]) and each hair of a fixed grid ([`ComparisonSettings::full`]: four
//! hair colours by melanin, beta_m in {0.15, 0.3, 0.6}, beta_n in {0.3, 0.6, 0.9}, alpha = 2
//! degrees, eta = 1.55), a [`ModelRow`] holds:
//!
//! - E against Chiang et al. 2016's far field ([`ChiangFarField`] with
//!   [`ComparisonSettings::reference_nodes`] Gauss-Legendre nodes in h) on
//!   [`DirectionPairs::kronecker`] pairs ([`ReferenceSamples::relative_error`]), at the model's
//!   mapped inputs ([`Approximation::mapped_inputs`](crate::models::Approximation)) and at its
//!   fitted ones ([`fit_model_inputs`]), each with its value on half the pairs;
//! - the energy error at theta_o = 0, 45 and 80 degrees ([`EnergyReference::errors`]);
//! - the cost: nanoseconds per evaluation in `f32` and per sample of the SIMD batch (wall
//!   clock, indicative: `cargo bench --bench models` has the criterion figures) and the traced
//!   graph's operation counts ([`OpCounts`]).

use super::model_inputs::{fit_model_inputs, InputFit};
use super::optimise::FitError;
use crate::absorption::{Absorption, HAIR_COLOURS};
use crate::bcsdf::{ChiangFarField, FarFieldRule, InputValues};
use crate::diagnostics::{
    ns_per_batch_eval, ns_per_eval, DirectionPairs, EnergyReference, ModelError, OpCounts,
    ReferenceSamples,
};
use crate::params::{HairParams, HairValues};
use crate::quadrature::SphereRule;
use crate::registry::{ApproximationEntry, ModelEntry, MODELS};
use rayon::prelude::*;
use std::sync::atomic::{AtomicUsize, Ordering};

/// The hair colours of the comparison: name, eumelanin and pheomelanin concentrations
/// ([`Absorption::from_melanin`]), named as [`HAIR_COLOURS`] names them: blonde, red, dark
/// brown (eumelanin 3) and black.
pub const COMPARISON_COLOURS: [(&str, f64, f64); 4] = [
    HAIR_COLOURS[0],
    HAIR_COLOURS[1],
    HAIR_COLOURS[3],
    HAIR_COLOURS[4],
];
/// The longitudinal roughnesses of the comparison grid.
pub const COMPARISON_BETA_M: [f64; 3] = [0.15, 0.3, 0.6];
/// The azimuthal roughnesses of the comparison grid.
pub const COMPARISON_BETA_N: [f64; 3] = [0.3, 0.6, 0.9];
/// The cuticle tilt of every hair of the comparison, degrees.
pub const COMPARISON_ALPHA_DEG: f64 = 2.0;
/// The refractive index of every hair of the comparison.
pub const COMPARISON_ETA: f64 = 1.55;
/// The viewing inclinations of the energy error, degrees from the normal plane.
pub const ENERGY_THETA_O_DEG: [f64; 3] = [0.0, 45.0, 80.0];

/// One hair of the comparison.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ComparisonHair {
    /// Its colour's name (`dark brown`; [`HAIR_COLOURS`]).
    pub colour: &'static str,
    /// Eumelanin concentration.
    pub eumelanin: f64,
    /// Pheomelanin concentration.
    pub pheomelanin: f64,
    /// Longitudinal roughness beta_m.
    pub beta_m: f64,
    /// Azimuthal roughness beta_n.
    pub beta_n: f64,
}

impl ComparisonHair {
    /// The physical parameters: the melanin's absorption, alpha = 2 degrees, eta = 1.55.
    ///
    /// # Errors
    /// [`crate::ParamError`] for values outside the parameters' domains.
    pub fn params(&self) -> Result<HairParams, crate::ParamError> {
        HairParams::try_from(HairValues {
            beta_m: self.beta_m,
            beta_n: self.beta_n,
            alpha: COMPARISON_ALPHA_DEG.to_radians(),
            eta: COMPARISON_ETA,
            sigma_a: Absorption::from_melanin(self.eumelanin, self.pheomelanin)?.rgb(),
        })
    }
}

/// What the comparison computes, and on how much work.
#[derive(Clone, Debug, PartialEq)]
pub struct ComparisonSettings {
    /// The hairs.
    pub hairs: Vec<ComparisonHair>,
    /// The models by name (registered approximations).
    pub models: Vec<&'static str>,
    /// Direction pairs of the error E ([`DirectionPairs::kronecker`]).
    pub pairs: usize,
    /// Direction pairs of the fits' loss (the first of the `pairs`; E at the fitted inputs is
    /// then measured on all of them).
    pub fit_pairs: usize,
    /// Gauss-Legendre nodes in h of the reference far field.
    pub reference_nodes: usize,
    /// Sphere rule of the albedos: theta panels, order, azimuths ([`SphereRule::new`]).
    pub albedo_sphere: [usize; 3],
    /// Calls (and batch samples) of the timings; 0 skips them (the figures are then 0).
    pub timing_calls: usize,
}

/// Every registered approximation's name, in registry order.
pub fn approximation_names() -> Vec<&'static str> {
    MODELS
        .iter()
        .filter(|m| m.approximation.is_some())
        .map(|m| m.name)
        .collect()
}

impl ComparisonSettings {
    /// The grid: the four colours of [`COMPARISON_COLOURS`] by [`COMPARISON_BETA_M`]
    /// by [`COMPARISON_BETA_N`], every approximation, 2^19 pairs (fits on 2^12), a 64-node
    /// reference, albedos on 32 x 8 x 128 sphere nodes.
    pub fn full() -> Self {
        let mut hairs = Vec::new();
        for (colour, eumelanin, pheomelanin) in COMPARISON_COLOURS {
            for beta_m in COMPARISON_BETA_M {
                for beta_n in COMPARISON_BETA_N {
                    hairs.push(ComparisonHair {
                        colour,
                        eumelanin,
                        pheomelanin,
                        beta_m,
                        beta_n,
                    });
                }
            }
        }
        ComparisonSettings {
            hairs,
            models: approximation_names(),
            pairs: 1 << 19,
            fit_pairs: 1 << 12,
            reference_nodes: 64,
            albedo_sphere: [32, 8, 128],
            timing_calls: 200_000,
        }
    }

    /// The README's table: dark brown hair (eumelanin 3, [`HAIR_COLOURS`]) at beta_m =
    /// beta_n = 0.3 only, otherwise as [`ComparisonSettings::full`].
    pub fn dark_brown() -> Self {
        let (colour, eumelanin, pheomelanin) = HAIR_COLOURS[3];
        ComparisonSettings {
            hairs: vec![ComparisonHair {
                colour,
                eumelanin,
                pheomelanin,
                beta_m: 0.3,
                beta_n: 0.3,
            }],
            ..Self::full()
        }
    }
}

impl ComparisonSettings {
    /// [`ComparisonSettings::dark_brown`] on less work, for tests and `hairmath report
    /// --quick`: 2^12 pairs (fits on 2^10), albedos on 16 x 8 x 64 sphere nodes, short
    /// timings. The errors are then rough.
    pub fn quick() -> Self {
        ComparisonSettings {
            pairs: 1 << 12,
            fit_pairs: 1 << 10,
            albedo_sphere: [16, 8, 64],
            timing_calls: 20_000,
            ..Self::dark_brown()
        }
    }
}

/// One model on one hair.
#[derive(Clone, Debug, PartialEq)]
pub struct ModelRow {
    /// The model's name.
    pub model: &'static str,
    /// The hair.
    pub hair: ComparisonHair,
    /// The model's inputs by its documented mapping from the hair's parameters.
    pub mapped_inputs: InputValues,
    /// E at the mapped inputs.
    pub error_mapped: ModelError,
    /// The fit of the model's inputs (E at the fitted inputs on the fit's pairs).
    pub fit: InputFit,
    /// E at the fitted inputs on all the pairs.
    pub error_fitted: ModelError,
    /// Relative energy error at the mapped inputs, per [`ENERGY_THETA_O_DEG`].
    pub energy_error: Vec<f64>,
    /// Relative energy error at the fitted inputs, per [`ENERGY_THETA_O_DEG`].
    pub energy_error_fitted: Vec<f64>,
    /// The cost of the model.
    pub cost: ModelCost,
}

/// What one evaluation of a model costs.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ModelCost {
    /// Wall-clock nanoseconds per `f32` evaluation ([`ns_per_eval`]).
    pub ns_per_eval_f32: f64,
    /// Wall-clock nanoseconds per sample of the SIMD batch
    /// ([`crate::diagnostics::ns_per_batch_eval`]).
    pub ns_per_eval_batch: f64,
    /// The traced evaluation's operations.
    pub ops: OpCounts,
}

/// Why the comparison failed.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum ComparisonError {
    /// A model name that is not a registered approximation.
    #[error("{name} is not a registered real-time model (known: {known})")]
    UnknownModel {
        /// The name given.
        name: String,
        /// The registered approximations.
        known: String,
    },
    /// A fit failed, or a model rejected its mapped inputs.
    #[error(transparent)]
    Fit(#[from] FitError),
    /// A hair outside the parameters' domains.
    #[error(transparent)]
    Param(#[from] crate::ParamError),
}

/// The registered approximation `name`.
///
/// # Errors
/// [`ComparisonError::UnknownModel`].
pub fn approximation(
    name: &str,
) -> Result<(&'static ModelEntry, ApproximationEntry), ComparisonError> {
    MODELS
        .iter()
        .find(|m| m.name == name)
        .and_then(|m| m.approximation.map(|a| (m, a)))
        .ok_or_else(|| ComparisonError::UnknownModel {
            name: name.to_string(),
            known: approximation_names().join(", "),
        })
}

/// The reference of one hair: its far field's values on the pairs (all and the fit's), and
/// its albedos.
struct HairReference {
    samples: ReferenceSamples,
    fit_samples: ReferenceSamples,
    energy: EnergyReference,
}

impl HairReference {
    fn new(hair: &HairParams, settings: &ComparisonSettings) -> Result<Self, ComparisonError> {
        let rule = FarFieldRule::gauss_legendre(settings.reference_nodes)?;
        let reference = ChiangFarField::<f64>::with_rule(hair, &rule);
        let samples = ReferenceSamples::new(&reference, DirectionPairs::kronecker(settings.pairs));
        let fit_samples = samples.first(settings.fit_pairs);
        let [panels, order, azimuths] = settings.albedo_sphere;
        let sphere = SphereRule::new(panels, order, azimuths);
        let energy = EnergyReference::new(&reference, sphere, &ENERGY_THETA_O_DEG);
        Ok(HairReference {
            samples,
            fit_samples,
            energy,
        })
    }
}

/// The cost of `model` at inputs `values`.
fn cost(
    approximation: &ApproximationEntry,
    values: &InputValues,
    calls: usize,
) -> Result<ModelCost, ComparisonError> {
    let f32_model = (approximation.build_f32)(values)?;
    Ok(ModelCost {
        ns_per_eval_f32: ns_per_eval(f32_model.as_ref(), calls),
        ns_per_eval_batch: ns_per_batch_eval((approximation.build_batch)(values)?.as_ref(), calls),
        ops: OpCounts::of(&(approximation.trace)(values)?),
    })
}

/// One model on one hair.
fn row(
    model: &'static ModelEntry,
    approximation: &ApproximationEntry,
    hair: &ComparisonHair,
    reference: &HairReference,
    cost: ModelCost,
) -> Result<ModelRow, ComparisonError> {
    let mapped_inputs = (approximation.mapped_inputs)(&hair.params()?);
    let mapped = (model.build)(&mapped_inputs)?;
    let fit = fit_model_inputs(
        model,
        approximation.fitted_inputs,
        &mapped_inputs,
        &reference.fit_samples,
    )?;
    let fitted = (model.build)(&fit.values)?;
    Ok(ModelRow {
        model: model.name,
        hair: *hair,
        error_mapped: reference.samples.relative_error(mapped.as_ref()),
        error_fitted: reference.samples.relative_error(fitted.as_ref()),
        energy_error: reference.energy.errors(mapped.as_ref()),
        energy_error_fitted: reference.energy.errors(fitted.as_ref()),
        mapped_inputs,
        fit,
        cost,
    })
}

/// Every model of `settings` on every hair, in hair-major order, calling `progress(done,
/// total)` after each row. Hairs are compared in parallel (rayon); the timings are taken
/// first, alone.
///
/// # Errors
/// [`ComparisonError`] for an unknown model, a hair outside the domains, a model rejecting
/// its mapped inputs or a fit that does not converge.
pub fn compare_models(
    settings: &ComparisonSettings,
    progress: &(dyn Fn(usize, usize) + Sync),
) -> Result<Vec<ModelRow>, ComparisonError> {
    let models = settings
        .models
        .iter()
        .map(|name| approximation(name))
        .collect::<Result<Vec<_>, _>>()?;
    let dark_brown = ComparisonSettings::dark_brown().hairs[0].params()?;
    let costs = models
        .iter()
        .map(|(_, a)| cost(a, &(a.mapped_inputs)(&dark_brown), settings.timing_calls))
        .collect::<Result<Vec<_>, _>>()?;
    let total = models.len() * settings.hairs.len();
    let done = AtomicUsize::new(0);
    let per_hair = settings
        .hairs
        .par_iter()
        .map(|hair| {
            let reference = HairReference::new(&hair.params()?, settings)?;
            let mut rows = Vec::with_capacity(models.len());
            for ((model, approximation), cost) in models.iter().zip(&costs) {
                rows.push(row(model, approximation, hair, &reference, *cost)?);
                progress(done.fetch_add(1, Ordering::Relaxed) + 1, total);
            }
            Ok(rows)
        })
        .collect::<Result<Vec<_>, ComparisonError>>()?;
    Ok(per_hair.into_iter().flatten().collect())
}
