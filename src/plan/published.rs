//! A plan against the published real-time models: each registered approximation
//! ([`crate::registry::MODELS`]) measured on the plan's hairs and lights with the plan's
//! reference, at its documented mapping from the physical parameters
//! ([`crate::models::Approximation::mapped_inputs`]), and costed as the plan is.

use super::search::{Plan, PlanError, PlanSettings, ScenePoint};
use crate::bcsdf::{ChiangFarField, FarFieldRule};
use crate::diagnostics::OpCounts;
use crate::registry::MODELS;

/// One published model beside a plan.
#[derive(Clone, Debug, PartialEq)]
pub struct PublishedComparison {
    /// The model's registered name.
    pub model: &'static str,
    /// Its E at its mapped inputs, the worst over the plan's hairs and lights.
    pub error: f64,
    /// Its weighted cost ([`super::OpWeights`]): the shader with every input baked at the hair of
    /// the plan's last point (for a scene whose parameters vary this is below what a shader
    /// computing the model's inputs per pixel would cost; the published models have no
    /// per-pixel mapping from the physical parameters).
    pub cost: f64,
    /// Its operation counts.
    pub ops: OpCounts,
    /// Whether the plan costs no more by weighted operations ([`super::Plan::ops_cost`],
    /// whatever the scene's cost measure) and has a lower error.
    pub dominated: bool,
}

/// Every registered approximation with a shader form beside `plan`, measured under the plan's
/// lights with `settings`' reference and weights.
///
/// # Errors
/// [`PlanError::Param`] if a model rejects its mapped inputs; [`PlanError::Argument`] if one
/// has no shader form.
pub fn compare_published(
    plan: &Plan,
    settings: &PlanSettings,
) -> Result<Vec<PublishedComparison>, PlanError> {
    let rule = FarFieldRule::gauss_legendre(settings.reference_nodes)?;
    // Per point, per light, the reference's vector.
    let references: Vec<Vec<Vec<f64>>> = plan
        .points
        .iter()
        .map(|p| {
            let reference = ChiangFarField::<f64>::with_rule(&p.params, &rule);
            plan.lights.iter().map(|l| l.vector(&reference)).collect()
        })
        .collect();
    let mut out = Vec::new();
    for entry in MODELS.iter() {
        let Some(approximation) = entry.approximation else {
            continue;
        };
        let mut error: f64 = 0.0;
        for (point, vectors) in plan.points.iter().zip(&references) {
            let model = (entry.build)(&(approximation.mapped_inputs)(&point.params))?;
            for (light, reference) in plan.lights.iter().zip(vectors) {
                error = error.max(light.relative_error(model.as_ref(), reference));
            }
        }
        let last: &ScenePoint = plan.points.last().unwrap_or(&plan.worst_point);
        let graph = entry.trace_shader(&(approximation.mapped_inputs)(&last.params), &[])?;
        let ops = OpCounts::of(&graph);
        let cost = settings.weights.cost(&ops);
        out.push(PublishedComparison {
            model: entry.name,
            error,
            cost,
            ops,
            dominated: plan.ops_cost <= cost && plan.error < error,
        });
    }
    Ok(out)
}
