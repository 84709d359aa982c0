//! How the error of a scene's light is measured: each light of a scene gives one
//! [`LightMeasure`], a linear map from a model to a vector whose norm, relative to the
//! reference's, is the error E under that light. The planner takes the worst over the scene's
//! lights, as it takes the worst over its hairs.
//!
//! - **Directional light** ([`LightMeasure::Directional`]): E of the models issue over
//!   direction pairs ([`DirectionPairs::kronecker`]), the vector `sqrt(w) S(wi, wo)` per pair
//!   and channel ([`crate::diagnostics::ReferenceSamples::relative_error`] is the same E).
//! - **SH environment** ([`LightMeasure::Environment`]): E_env of
//!   [`crate::diagnostics::ShEnvironment`], the vector the model's transfer of the bands
//!   `l <= lmax` (the root-mean-square relative error of the outgoing radiance over the
//!   environments of those bands).
//!
//! Both are linear in the model, so the vector of a sum of lobes is the sum of the lobes'
//! vectors: the planner's Gram matrices hold for either.

use super::scene::{Environment, Scene};
use super::search::PlanSettings;
use crate::bcsdf::{Bcsdf, Query};
use crate::diagnostics::{DirectionPairs, ShEnvironment};
use crate::error::ParamError;

/// One light of a scene, measured (module documentation).
#[derive(Clone, Debug)]
pub enum LightMeasure {
    /// Directional light, on direction pairs.
    Directional(DirectionPairs),
    /// An SH environment, by transfers.
    Environment(ShEnvironment),
}

impl LightMeasure {
    /// The measures of `scene`'s lights with `settings`' pairs and environment rule.
    ///
    /// # Errors
    /// [`ParamError`] for an environment band above 8 (the scene parser allows none).
    pub fn of(scene: &Scene, settings: &PlanSettings) -> Result<Vec<Self>, ParamError> {
        let mut out = Vec::new();
        if scene.lights.directional {
            let pairs = DirectionPairs::kronecker(settings.pairs);
            out.push(LightMeasure::Directional(pairs));
        }
        if let Environment::Sh { lmax } = scene.lights.environment {
            let environment = ShEnvironment::new(lmax as usize, settings.environment)?;
            out.push(LightMeasure::Environment(environment));
        }
        Ok(out)
    }

    /// The vector of each of `model`'s lobes ([`Bcsdf::eval_lobes`]), in its order.
    pub fn lobes<M: Bcsdf<f64> + ?Sized>(&self, model: &M) -> Vec<Vec<f64>> {
        match self {
            LightMeasure::Directional(pairs) => {
                let mut out = vec![Vec::with_capacity(3 * pairs.len()); model.lobe_names().len()];
                for (&(wi, wo), &w) in pairs.pairs().iter().zip(pairs.weights()) {
                    let root = w.sqrt();
                    let lobes = model.eval_lobes(&Query::far(wi, wo));
                    for (vector, lobe) in out.iter_mut().zip(&lobes) {
                        vector.extend(lobe.iter().map(|v| root * v));
                    }
                }
                out
            }
            LightMeasure::Environment(environment) => environment.lobe_transfers(model),
        }
    }

    /// The vector of `model` ([`Bcsdf::eval`]).
    pub fn vector<M: Bcsdf<f64> + ?Sized>(&self, model: &M) -> Vec<f64> {
        match self {
            LightMeasure::Directional(pairs) => pairs
                .pairs()
                .iter()
                .zip(pairs.weights())
                .flat_map(|(&(wi, wo), &w)| {
                    let root = w.sqrt();
                    model.eval(&Query::far(wi, wo)).map(|v| root * v)
                })
                .collect(),
            LightMeasure::Environment(environment) => environment.transfer(model),
        }
    }

    /// E of `model` against the reference whose [`LightMeasure::vector`] is `reference`: 0
    /// for the reference, 1 for a model that is 0 everywhere, infinite (never NaN) for a
    /// model with a non-finite value.
    pub fn relative_error<M: Bcsdf<f64> + ?Sized>(&self, model: &M, reference: &[f64]) -> f64 {
        crate::diagnostics::relative_norm(&self.vector(model), reference)
    }

    /// `directional` or `environment`.
    pub fn name(&self) -> &'static str {
        match self {
            LightMeasure::Directional(_) => "directional",
            LightMeasure::Environment(_) => "environment",
        }
    }
}
