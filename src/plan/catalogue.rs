//! The speed-against-error catalogue of a scene: every lobe option the planner offers with its
//! own error and cost, the Pareto front of the compositions (cost against error), the
//! published models beside them and the plan at the scene's budget; with the lobe curves of
//! the plan, the published models and the reference. The figures of `hairmath report`'s
//! speed-against-error section and plots.
//!
//! # The front
//!
//! Every composition the planner can build (one option per lobe, their far fields and tables
//! agreeing) has an exact error from the options' Gram matrices (the module documentation of
//! [`super::plan`]) and an additive cost estimate. The compositions that no other beats on
//! both are kept, each is traced for its exact weighted cost, and those that no other kept
//! composition beats on error and traced cost are the front. A composition off the estimated
//! front whose traced cost would put it on the true front is missed: the front is the traced
//! front of the estimate, an upper bound on the true one.

use super::published::{compare_published, PublishedComparison};
use super::scene::{Scene, SceneError};
use super::search::{
    trace_composition, Plan, PlanError, PlanSettings, PlannedLobe, SceneMeasurement, SLOTS,
};
use crate::bcsdf::{ChiangFarField, FarFieldRule};
use crate::diagnostics::{lobe_curves, LobeCurve, OpCounts};
use crate::models::{ComposedHair, Composition};
use crate::registry::MODELS;

/// The README's example scenes (`examples/scenes/`), `(name, scene file)`: blonde, dark brown
/// and black hair (eumelanin 0.3, 3 and 8, named as
/// [`HAIR_COLOURS`](crate::absorption::HAIR_COLOURS) names them; each name is its file's stem)
/// at beta_m = beta_n = 0.3, alpha = 2 degrees, eta = 1.55, budget 0.1, directional light.
/// The parameter sets of the report's front.
pub const EXAMPLE_SCENES: [(&str, &str); 3] = [
    ("blonde", include_str!("../../examples/scenes/blonde.toml")),
    (
        "dark-brown",
        include_str!("../../examples/scenes/dark-brown.toml"),
    ),
    ("black", include_str!("../../examples/scenes/black.toml")),
];

/// [`EXAMPLE_SCENES`], parsed, with their names.
///
/// # Errors
/// [`SceneError`] if a scene file does not parse (a test asserts they do).
pub fn example_scenes() -> Result<Vec<(&'static str, Scene)>, SceneError> {
    EXAMPLE_SCENES
        .iter()
        .map(|(name, text)| {
            Ok((
                *name,
                Scene::parse(text, &format!("examples/scenes/{name}.toml"))?,
            ))
        })
        .collect()
}

/// The inclinations of the catalogue's lobe curves, in degrees.
pub const CURVE_THETAS_DEG: [f64; 3] = [0.0, 30.0, 60.0];

/// Azimuths per lobe curve.
pub const CURVE_SAMPLES: usize = 181;

/// One composition on the front.
#[derive(Clone, Debug, PartialEq)]
pub struct FrontPoint {
    /// The composition.
    pub composition: Composition,
    /// Its error E, the worst over the scene's hairs (from the Gram matrices).
    pub error: f64,
    /// Its weighted traced cost.
    pub cost: f64,
    /// Its traced operation counts.
    pub ops: OpCounts,
}

/// One model's lobe curves.
#[derive(Clone, Debug, PartialEq)]
pub struct ModelCurves {
    /// `reference` (the far field the errors are measured against), `plan`, or a published
    /// model's registered name.
    pub model: String,
    /// One curve per [`CURVE_THETAS_DEG`].
    pub curves: Vec<LobeCurve>,
}

/// A scene's speed-against-error figures (module documentation).
#[derive(Clone, Debug)]
pub struct Catalogue {
    /// The scene's budget.
    pub budget: f64,
    /// The plan at the scene's budget.
    pub plan: Plan,
    /// Every lobe option (R, TT, TRT, then the residual): each factor choice, table size and
    /// node count, with published and refit constants, and the lobe dropped.
    pub options: Vec<PlannedLobe>,
    /// The front, by increasing cost and decreasing error.
    pub front: Vec<FrontPoint>,
    /// The compositions measured.
    pub combinations: usize,
    /// The published models, measured and costed as the plan is.
    pub published: Vec<PublishedComparison>,
    /// The lobe curves of the reference, the plan and the published models at the scene's
    /// last hair.
    pub curves: Vec<ModelCurves>,
}

/// The catalogue of `scene` (module documentation); `progress` as in [`super::plan`].
///
/// # Errors
/// As [`super::plan`].
pub fn catalogue(
    scene: &Scene,
    settings: &PlanSettings,
    progress: &(dyn Fn(usize, usize) + Sync),
) -> Result<Catalogue, PlanError> {
    let measured = SceneMeasurement::new(scene, settings, progress)?;
    let plan = measured.plan(scene.budget, settings)?;
    let options = (0..SLOTS)
        .flat_map(|slot| {
            let measured = &measured;
            (0..measured.options[slot].len()).map(move |i| measured.planned_lobe(slot, i))
        })
        .collect();
    let (front, combinations) = front(&measured, settings)?;
    let published = compare_published(&plan, settings)?;
    let curves = curves(&measured, &plan, settings)?;
    Ok(Catalogue {
        budget: scene.budget,
        plan,
        options,
        front,
        combinations,
        published,
        curves,
    })
}

/// Points `(cost, error, item)` none of which another beats on both, by increasing cost.
struct ParetoSet<T> {
    points: Vec<(f64, f64, T)>,
}

impl<T> ParetoSet<T> {
    fn new() -> Self {
        ParetoSet { points: Vec::new() }
    }

    /// Adds a point unless one no more costly has no more error; removes those it beats.
    fn insert(&mut self, cost: f64, error: f64, item: T) {
        let no_costlier = self.points.partition_point(|p| p.0 <= cost);
        if no_costlier > 0 && self.points[no_costlier - 1].1 <= error {
            return;
        }
        // Those of equal cost (they have more error) and the costlier ones with no less error.
        let start = self.points.partition_point(|p| p.0 < cost);
        let mut end = no_costlier;
        while end < self.points.len() && self.points[end].1 >= error {
            end += 1;
        }
        self.points.splice(start..end, [(cost, error, item)]);
    }
}

/// The traced front of the estimate (module documentation), and the number of compositions.
fn front(
    measured: &SceneMeasurement,
    settings: &PlanSettings,
) -> Result<(Vec<FrontPoint>, usize), PlanError> {
    let mut estimated = ParetoSet::new();
    let mut combinations = 0;
    measured.for_each_choice(|choice| {
        combinations += 1;
        estimated.insert(
            measured.estimate(choice),
            measured.choice_error(choice),
            choice,
        );
    });
    let mut traced = ParetoSet::new();
    for (_, error, choice) in estimated.points {
        let composition = measured.composition(choice);
        let graph = trace_composition(composition, measured.centre(), &measured.arguments)?;
        let ops = OpCounts::of(&graph);
        let cost = settings.weights.cost(&ops);
        traced.insert(
            cost,
            error,
            FrontPoint {
                composition,
                error,
                cost,
                ops,
            },
        );
    }
    let points = traced.points.into_iter().map(|p| p.2).collect();
    Ok((points, combinations))
}

/// The lobe curves of the reference, the plan and each published model at the last hair.
fn curves(
    measured: &SceneMeasurement,
    plan: &Plan,
    settings: &PlanSettings,
) -> Result<Vec<ModelCurves>, PlanError> {
    let params = &measured.centre().params;
    let rule = FarFieldRule::gauss_legendre(settings.reference_nodes)?;
    let of = |model: String, m: &dyn crate::bcsdf::Bcsdf<f64>| ModelCurves {
        model,
        curves: lobe_curves(m, &CURVE_THETAS_DEG, CURVE_SAMPLES),
    };
    let mut out = vec![
        of(
            "reference".into(),
            &ChiangFarField::<f64>::with_rule(params, &rule),
        ),
        of("plan".into(), &ComposedHair::new(params, plan.composition)?),
    ];
    for entry in MODELS.iter() {
        if let Some(approximation) = entry.approximation {
            let model = (entry.build)(&(approximation.mapped_inputs)(params))?;
            out.push(of(entry.name.to_string(), model.as_ref()));
        }
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::ParetoSet;
    use proptest::prelude::*;

    proptest! {
        /// The set after any insertions is exactly the non-dominated points, by brute force.
        #[test]
        fn pareto_set_keeps_exactly_the_non_dominated_points(
            points in prop::collection::vec((0u8..20, 0u8..20), 0..60)
        ) {
            let mut set = ParetoSet::new();
            for (i, &(cost, error)) in points.iter().enumerate() {
                set.insert(f64::from(cost), f64::from(error), i);
            }
            let dominated = |i: usize| {
                let (c, e) = points[i];
                points.iter().enumerate().any(|(j, &(cj, ej))| {
                    (cj <= c && ej <= e) && ((cj, ej) != (c, e) || j < i)
                })
            };
            let expected: Vec<usize> = (0..points.len()).filter(|&i| !dominated(i)).collect();
            let mut kept: Vec<usize> = set.points.iter().map(|p| p.2).collect();
            kept.sort_unstable();
            prop_assert_eq!(kept, expected);
            for pair in set.points.windows(2) {
                prop_assert!(pair[0].0 < pair[1].0 && pair[0].1 > pair[1].1);
            }
        }
    }
}
