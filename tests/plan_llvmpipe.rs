#![cfg(feature = "plan")]
//! The planner's `cost = "llvmpipe"` on the README's blonde scene: the plan meets its budget
//! (as reported and re-measured), is the fastest of the candidates it timed, and those are the
//! cheapest by weighted operations that meet the budget, the first of them the `cost = "ops"`
//! plan.
//!
//! Under `CI=true` (CI installs `mesa-vulkan-drivers`) a missing llvmpipe fails the test, as in
//! `tests/shader/gpu.rs`; elsewhere it is skipped with a message on stderr.

use hairmath::bcsdf::{ChiangFarField, FarFieldRule};
use hairmath::device::DeviceError;
use hairmath::diagnostics::{DirectionPairs, OpCounts, ReferenceSamples};
use hairmath::models::ComposedHair;
use hairmath::plan::{
    example_scenes, plan, scene_points, trace_composition, worst_error, CostMeasure, LightMeasure,
    Plan, PlanError, PlanSettings, Scene,
};

/// Whether the environment variable `CI` is `true`: a missing device is a failure.
fn in_ci() -> bool {
    std::env::var("CI").is_ok_and(|value| value == "true")
}

/// The README's blonde scene (`examples/scenes/blonde.toml`) with `cost`.
fn blonde(cost: CostMeasure) -> Scene {
    let (_, mut scene) = example_scenes()
        .expect("the example scenes parse")
        .into_iter()
        .find(|(name, _)| *name == "blonde")
        .expect("the blonde scene");
    scene.cost = cost;
    scene
}

#[test]
fn the_llvmpipe_plan_is_the_fastest_timed_of_the_cheapest_by_ops_within_the_budget() {
    let settings = PlanSettings::quick();
    let scene = blonde(CostMeasure::Llvmpipe);
    let timed: Plan = match plan(&scene, &settings, &|_, _| {}) {
        Err(PlanError::NoDevice(e)) if !in_ci() => {
            eprintln!("no llvmpipe, the test is skipped: {e}");
            return;
        }
        other => other.expect("a plan timed on llvmpipe"),
    };
    let timing = timed.timing.as_ref().expect("the timed candidates");
    eprintln!(
        "on {}, {} rows, median of {}:",
        timing.adapter, timing.rows, timing.repetitions
    );
    for c in &timing.candidates {
        eprintln!(
            "  {:.2} ns, ops {}, E {:.4}: {}",
            c.ns_per_eval,
            c.ops_cost,
            c.error,
            c.composition.describe()
        );
    }
    assert_eq!(timed.measure, CostMeasure::Llvmpipe);
    assert_eq!(timing.rows, settings.device_rows);
    assert_eq!(timing.repetitions, settings.device_repetitions);

    // (a) The plan meets the budget: as reported, and re-measured here with the reference
    // samples of the planner's pairs and reference (the scene is one hair).
    assert!(timed.error <= scene.budget, "reported E = {}", timed.error);
    let points = scene_points(&scene.hair, settings.interior_points).expect("the points");
    assert_eq!(points.len(), 1);
    let rule = FarFieldRule::gauss_legendre(settings.reference_nodes).expect("nodes");
    let reference = ChiangFarField::<f64>::with_rule(&points[0].params, &rule);
    let samples = ReferenceSamples::new(&reference, DirectionPairs::kronecker(settings.pairs));
    let model = ComposedHair::new(&points[0].params, timed.composition).expect("composed");
    let remeasured = samples.relative_error(&model).full;
    eprintln!(
        "llvmpipe plan: {:.2} ns, ops {}, E {:.4} (re-measured {remeasured:.4}): {}",
        timed.cost,
        timed.ops_cost,
        timed.error,
        timed.composition.describe()
    );
    assert!(remeasured <= scene.budget, "re-measured E = {remeasured}");
    assert!(
        (remeasured - timed.error).abs() <= 1e-12,
        "{remeasured} vs {}",
        timed.error
    );

    // (b) Its cost is its measured time, the least of the candidates timed.
    let fastest = &timing.candidates[timing.fastest()];
    assert!(timing
        .candidates
        .iter()
        .all(|c| c.ns_per_eval.is_finite() && c.ns_per_eval > 0.0));
    let least = timing
        .candidates
        .iter()
        .map(|c| c.ns_per_eval)
        .fold(f64::INFINITY, f64::min);
    assert_eq!(timed.cost, least);
    assert_eq!(fastest.ns_per_eval, least);
    assert_eq!(timed.composition, fastest.composition);
    assert_eq!(timed.ops_cost, fastest.ops_cost);
    assert_eq!(timed.error, fastest.error);

    // (c) Every candidate meets the budget (re-measured as a whole), its weighted cost is its
    // traced shader's, and they are the K cheapest in the order of the ops ranking: the first
    // is the `cost = "ops"` plan.
    assert_eq!(timing.candidates.len(), settings.device_candidates);
    for c in &timing.candidates {
        assert!(c.error <= scene.budget, "{c:?}");
        let lights = [LightMeasure::Directional(DirectionPairs::kronecker(
            settings.pairs,
        ))];
        let (error, _) = worst_error(c.composition, &points, &lights, settings.reference_nodes)
            .expect("measured");
        assert_eq!(error, c.error);
        let graph = trace_composition(c.composition, &points[0], &[]).expect("traced");
        assert_eq!(settings.weights.cost(&OpCounts::of(&graph)), c.ops_cost);
    }
    for pair in timing.candidates.windows(2) {
        assert!(pair[0].ops_cost <= pair[1].ops_cost, "{pair:?}");
    }
    let by_ops = plan(&blonde(CostMeasure::Ops), &settings, &|_, _| {}).expect("the ops plan");
    eprintln!(
        "ops plan: ops {}, E {:.4}: {}",
        by_ops.cost,
        by_ops.error,
        by_ops.composition.describe()
    );
    assert_eq!(by_ops.measure, CostMeasure::Ops);
    assert!(by_ops.timing.is_none());
    assert_eq!(by_ops.cost, by_ops.ops_cost);
    assert_eq!(timing.candidates[0].composition, by_ops.composition);
    assert_eq!(timing.candidates[0].ops_cost, by_ops.cost);
    assert!(timed.ops_cost >= by_ops.cost);
    assert_eq!(
        (timed.feasible, timed.combinations),
        (by_ops.feasible, by_ops.combinations)
    );
}

/// The error of a machine without llvmpipe names the package that provides it.
#[test]
fn a_missing_device_names_mesa_vulkan_drivers() {
    let message = PlanError::NoDevice(DeviceError::NoAdapter("no Vulkan adapter".into()));
    let text = message.to_string();
    assert!(
        text.contains("no llvmpipe Vulkan device was found"),
        "{text}"
    );
    assert!(text.contains("mesa-vulkan-drivers"), "{text}");
}
