#![cfg(feature = "plan")]
//! Scenes lit by an SH environment (`environment = "sh"`): the plan meets its budget when its
//! composition's `f32` model (the shader's CPU twin) is re-measured with a finer environment
//! rule on a grid of the scene's range, and a scene with both lights is planned within the
//! budget under each.

use hairmath::bcsdf::{Bcsdf, ChiangFarField, FarFieldRule, Model, Query};
use hairmath::diagnostics::{relative_norm, EnvironmentRule, ShEnvironment};
use hairmath::geometry::V3;
use hairmath::models::ComposedHair;
use hairmath::plan::{plan, scene_points, LightMeasure, Plan, PlanSettings, Scene};

fn scene(text: &str) -> Scene {
    Scene::parse(text, "test.toml").expect("a valid scene")
}

/// Far fields of 4 and 16 nodes only: the environment's transfers of every option are the
/// planner's largest cost.
fn settings() -> PlanSettings {
    PlanSettings {
        far_field_nodes: vec![4, 16],
        ..PlanSettings::default()
    }
}

fn planned(scene: &Scene) -> Plan {
    plan(scene, &settings(), &|_, _| {}).expect("a plan")
}

/// Blonde hair whose eumelanin is a range, lit by `lights`.
fn blonde(lights: &str) -> String {
    format!(
        "budget = 0.1\n[hair]\neumelanin = [0.2, 0.4]\nbeta_m = 0.3\nbeta_n = 0.3\n\
         [lights]\n{lights}\n"
    )
}

/// The worst E_env over a grid of 5 eumelanins of `scene`'s range [0.2, 0.4] (the planner
/// measured the ends and 4 Kronecker points), with `rule` and the planner's 64-node reference,
/// of the `f32` model the shader computes.
fn environment_error(plan: &Plan, lmax: usize, rule: EnvironmentRule) -> f64 {
    let environment = ShEnvironment::new(lmax, rule).unwrap();
    let reference_rule = FarFieldRule::gauss_legendre(64).unwrap();
    (0..5)
        .map(|i| {
            let text = format!(
                "budget = 0.1\n[hair]\neumelanin = {}\nbeta_m = 0.3\nbeta_n = 0.3\n",
                0.2 + 0.05 * i as f64
            );
            let point = &scene_points(&scene(&text).hair, 0).unwrap()[0];
            let reference = ChiangFarField::with_rule(&point.params, &reference_rule);
            let model = ComposedHair::new(&point.params, plan.composition).unwrap();
            let single = model.instantiate::<f32>();
            let transfer = environment.transfer_of(|wi, wo| {
                let q = Query::far(
                    V3::from_f64(wi.x, wi.y, wi.z),
                    V3::from_f64(wo.x, wo.y, wo.z),
                );
                single.eval(&q).map(f64::from)
            });
            let reference = environment.transfer(&reference);
            relative_norm(&transfer, &reference)
        })
        .fold(0.0, f64::max)
}

/// 1.5 times the planner's rule in every direction.
const FINER: EnvironmentRule = EnvironmentRule {
    theta_panels: 24,
    order: 4,
    azimuths: 72,
    viewers: 24,
};

#[test]
fn an_environment_plan_meets_its_budget_on_a_finer_measurement() {
    for lmax in [0, 2] {
        let s = scene(&blonde(&format!(
            "directional = false\nenvironment = \"sh\"\nenvironment_sh_lmax = {lmax}"
        )));
        let p = planned(&s);
        let finer = environment_error(&p, lmax, FINER);
        eprintln!(
            "lmax {lmax}: {} costs {}, E_env {:.4} (planner), {finer:.4} (finer rule, 5 hairs)",
            p.composition.describe(),
            p.cost,
            p.error
        );
        assert_eq!(p.lights.len(), 1);
        assert!(matches!(p.lights[0], LightMeasure::Environment(_)));
        assert!(p.error <= s.budget);
        // The planner's rule has converged to 2e-3 (tests/environment.rs).
        assert!(finer <= s.budget * (1.0 + 2e-3), "lmax {lmax}: {finer}");
    }
}

#[test]
fn a_scene_with_both_lights_meets_the_budget_under_each() {
    let both = scene(&blonde(
        "directional = true\nenvironment = \"sh\"\nenvironment_sh_lmax = 2",
    ));
    let p = planned(&both);
    assert_eq!(p.lights.len(), 2);
    let directional = scene(&blonde("directional = true"));
    let alone = planned(&directional);
    eprintln!(
        "both lights: {} costs {} (E {:.4}); directional alone costs {} (E {:.4})",
        p.composition.describe(),
        p.cost,
        p.error,
        alone.cost,
        alone.error
    );
    let under_environment = environment_error(&p, 2, FINER);
    assert!(
        under_environment <= both.budget * (1.0 + 2e-3),
        "{under_environment}"
    );
    // Under the directional light alone, the same composition as the planner measures it.
    let rule = FarFieldRule::gauss_legendre(settings().reference_nodes).unwrap();
    let pairs = hairmath::diagnostics::DirectionPairs::kronecker(settings().pairs);
    let light = LightMeasure::Directional(pairs);
    for point in &p.points {
        let reference = ChiangFarField::with_rule(&point.params, &rule);
        let model = ComposedHair::new(&point.params, p.composition).unwrap();
        let e = light.relative_error(&model, &light.vector(&reference));
        assert!(e <= p.error && p.error <= both.budget, "{e} {}", p.error);
    }
}
