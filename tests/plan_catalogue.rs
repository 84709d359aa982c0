#![cfg(feature = "plan")]
//! The catalogue of approximations (`hairmath::plan::catalogue`), the data of the report's
//! approximation table and plots: its front is a Pareto front of traced compositions, the
//! plan is on it, its options are the planner's, and its lobe curves are the models' values.

use hairmath::bcsdf::{Bcsdf, ChiangFarField, FarFieldRule, Query};
use hairmath::diagnostics::lobe_curves;
use hairmath::geometry::local_direction;
use hairmath::models::ComposedHair;
use hairmath::plan::{
    catalogue, example_scenes, trace_composition, Catalogue, PlanSettings, CURVE_SAMPLES,
    CURVE_THETAS_DEG, EXAMPLE_SCENES,
};
use std::sync::OnceLock;

/// The catalogue of the black-hair example scene at the quick settings, computed once.
fn black() -> &'static Catalogue {
    static CATALOGUE: OnceLock<Catalogue> = OnceLock::new();
    CATALOGUE.get_or_init(|| {
        let scenes = example_scenes().expect("the example scenes parse");
        let (_, scene) = scenes
            .iter()
            .find(|(name, _)| *name == "black")
            .expect("a black scene");
        catalogue(scene, &PlanSettings::quick(), &|_, _| {}).expect("a catalogue")
    })
}

#[test]
fn every_example_scene_parses_with_its_budget() {
    let scenes = example_scenes().unwrap();
    assert_eq!(scenes.len(), EXAMPLE_SCENES.len());
    for (name, scene) in &scenes {
        assert!(scene.budget > 0.0 && scene.budget < 1.0, "{name}");
    }
}

/// Issue 16, item 6: each example scene is named after its hair's melanin as
/// `absorption::HAIR_COLOURS` names it (a space written as a dash), and the name is its file's
/// stem in `examples/scenes/`.
#[test]
fn example_scenes_are_named_by_their_melanin() {
    use hairmath::absorption::HAIR_COLOURS;
    use hairmath::plan::{HairKey, ParamRange};
    for ((name, text), (parsed_name, scene)) in EXAMPLE_SCENES.iter().zip(example_scenes().unwrap())
    {
        assert_eq!(*name, parsed_name);
        let (_, eumelanin, pheomelanin) = *HAIR_COLOURS
            .iter()
            .find(|(n, _, _)| n.replace(' ', "-") == *name)
            .unwrap_or_else(|| panic!("{name} is not a colour of HAIR_COLOURS"));
        assert_eq!(
            (
                scene.hair.get(HairKey::Eumelanin),
                scene.hair.get(HairKey::Pheomelanin)
            ),
            (ParamRange::Fixed(eumelanin), ParamRange::Fixed(pheomelanin)),
            "{name}"
        );
        let file = format!("{}/examples/scenes/{name}.toml", env!("CARGO_MANIFEST_DIR"));
        assert_eq!(std::fs::read_to_string(&file).unwrap(), *text, "{file}");
    }
}

#[test]
fn the_front_is_non_dominated_and_sorted_by_cost() {
    let c = black();
    assert!(c.front.len() >= 3, "{} points", c.front.len());
    assert!(c.combinations > c.front.len());
    for pair in c.front.windows(2) {
        assert!(pair[0].cost < pair[1].cost, "costs not increasing");
        assert!(pair[0].error > pair[1].error, "errors not decreasing");
    }
    for p in &c.front {
        assert!(p.error.is_finite() && p.error >= 0.0);
        assert!(p.cost.is_finite() && p.cost >= 0.0);
    }
}

#[test]
fn front_costs_are_the_traced_costs_of_their_compositions() {
    let c = black();
    let settings = PlanSettings::quick();
    for p in c.front.iter().step_by(3) {
        let graph =
            trace_composition(p.composition, &c.plan.worst_point, &c.plan.arguments).unwrap();
        let ops = hairmath::diagnostics::OpCounts::of(&graph);
        assert_eq!(ops, p.ops, "{}", p.composition.describe());
        assert_eq!(settings.weights.cost(&ops), p.cost);
    }
}

#[test]
fn no_front_point_within_the_budget_is_cheaper_than_the_plan() {
    let c = black();
    assert!(c.plan.error <= c.budget);
    let within: Vec<_> = c.front.iter().filter(|p| p.error <= c.budget).collect();
    assert!(
        !within.is_empty(),
        "the front has no point within the budget"
    );
    for p in within {
        assert!(
            p.cost >= c.plan.cost,
            "{} costs {} < the plan's {}",
            p.composition.describe(),
            p.cost,
            c.plan.cost
        );
    }
    // The plan's own cost and error are a point of the front or dominated by one no costlier.
    assert!(c
        .front
        .iter()
        .any(|p| p.cost <= c.plan.cost && p.error <= c.plan.error + 1e-12));
}

#[test]
fn the_options_cover_every_lobe_and_include_the_plans_choices() {
    let c = black();
    for lobe in ["R", "TT", "TRT", "residual"] {
        let of_lobe: Vec<_> = c.options.iter().filter(|o| o.lobe == lobe).collect();
        assert!(of_lobe.len() >= 2, "{lobe}: {} options", of_lobe.len());
        assert!(of_lobe.iter().any(|o| !o.kept), "{lobe} cannot be dropped");
    }
    for chosen in &c.plan.lobes {
        assert!(
            c.options.iter().any(|o| o.describe() == chosen.describe()
                && o.lobe == chosen.lobe
                && o.error == chosen.error),
            "{} {} not among the options",
            chosen.lobe,
            chosen.describe()
        );
    }
    for o in &c.options {
        assert!(o.error.is_finite() && o.error >= 0.0, "{}", o.describe());
        assert_eq!(o.far_field_nodes.is_some(), o.describe().contains("nodes)"));
        let (d, marschner) = (o.describe(), "Marschner table)");
        assert_eq!(
            o.table.is_some(),
            d.contains("table)") && !d.contains(marschner)
        );
        assert_eq!(o.marschner_table.is_some(), d.contains(marschner), "{d}");
    }
}

#[test]
fn every_published_model_is_compared_and_plotted() {
    let c = black();
    assert!(c.published.len() >= 6);
    let names: Vec<&str> = c.curves.iter().map(|m| m.model.as_str()).collect();
    assert_eq!(names[0], "reference");
    assert_eq!(names[1], "plan");
    for p in &c.published {
        assert!(names.contains(&p.model), "{} not plotted", p.model);
        assert_eq!(p.dominated, c.plan.cost <= p.cost && c.plan.error < p.error);
    }
    for m in &c.curves {
        assert_eq!(m.curves.len(), CURVE_THETAS_DEG.len());
        for curve in &m.curves {
            assert_eq!(curve.phi.len(), CURVE_SAMPLES);
            assert!(curve.value.iter().flatten().all(|v| v.is_finite()));
        }
    }
}

#[test]
fn lobe_curves_are_the_models_values_at_the_stated_directions() {
    let params = black().plan.worst_point.params;
    let rule = FarFieldRule::gauss_legendre(64).unwrap();
    let reference = ChiangFarField::<f64>::with_rule(&params, &rule);
    let plan = ComposedHair::new(&params, black().plan.composition).unwrap();
    let models: [&dyn Bcsdf<f64>; 2] = [&reference, &plan];
    for model in models {
        let curves = lobe_curves(model, &[0.0, 45.0], 9);
        assert_eq!(curves.len(), 2);
        for curve in &curves {
            assert_eq!(curve.phi.first(), Some(&-core::f64::consts::PI));
            assert_eq!(curve.phi.last(), Some(&core::f64::consts::PI));
            let theta = curve.theta_deg.to_radians();
            for (&phi, value) in curve.phi.iter().zip(&curve.value) {
                let wi = local_direction(theta.sin(), theta.cos(), phi);
                let wo = local_direction(-theta.sin(), theta.cos(), 0.0);
                assert_eq!(model.eval(&Query::far(wi, wo)), *value);
            }
        }
        // At least some of the curve is lit: S is not zero everywhere.
        assert!(curves[0].value.iter().flatten().any(|&v| v > 1e-3));
    }
}
