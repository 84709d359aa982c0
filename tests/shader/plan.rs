//! A scene plan's emitted shader, run on the device: over a grid of the scene's varying
//! parameters (passed as the shader's arguments) and more direction pairs than the planner
//! used, its error against the `f64` far field stays within the scene's budget.

use crate::gpu::{device, textures_of};
use hairmath::bcsdf::{Bcsdf, ChiangFarField, FarFieldRule, Query};
use hairmath::diagnostics::DirectionPairs;
use hairmath::plan::{plan, scene_points, PlanSettings, Scene};
use hairmath::shader::graph_shader;

/// Melanin as a range and beta_n per pixel: both are arguments of `hair_bcsdf`.
const SCENE: &str = "budget = 0.1\n[hair]\neumelanin = [0.5, 1.5]\nbeta_m = 0.3\n\
                     beta_n = { varying = [0.3, 0.6] }\n";

#[test]
fn the_planned_shader_meets_the_budget_on_the_device() {
    let Some(device) = device() else { return };
    let scene = Scene::parse(SCENE, "scene.toml").expect("a valid scene");
    let planned = plan(&scene, &PlanSettings::default(), &|_, _| {}).expect("a plan");
    assert_eq!(planned.arguments, ["eumelanin", "beta_n"]);
    let shader = graph_shader(
        "plan",
        "test",
        "tests/shader/plan.rs",
        planned.graph.clone(),
    )
    .expect("a module");
    let compute = shader.compute().expect("a compute module");
    let stride = compute.stride().expect("a stride");
    assert_eq!(stride, 8);
    let wgsl = compute.wgsl().expect("WGSL");
    let pairs = DirectionPairs::kronecker(1 << 13);
    let rule = FarFieldRule::gauss_legendre(128).expect("nodes");
    let mut worst: f64 = 0.0;
    for eumelanin in [0.5, 1.0, 1.5] {
        for beta_n in [0.3, 0.45, 0.6] {
            let text = format!(
                "budget = 0.1\n[hair]\neumelanin = {eumelanin}\nbeta_m = 0.3\nbeta_n = {beta_n}\n"
            );
            let hair = Scene::parse(&text, "point.toml")
                .expect("a valid scene")
                .hair;
            let point = &scene_points(&hair, 0).expect("a point")[0];
            let reference = ChiangFarField::<f64>::with_rule(&point.params, &rule);
            let mut rows = Vec::with_capacity(pairs.len() * stride);
            for &(wi, wo) in pairs.pairs() {
                rows.extend([wi.x, wi.y, wi.z, wo.x, wo.y, wo.z].map(|x| x as f32));
                rows.extend([eumelanin as f32, beta_n as f32]);
            }
            let gpu = device
                .run(
                    &wgsl,
                    "hair_main",
                    &rows,
                    stride,
                    &textures_of(&shader.module),
                )
                .expect("the dispatch runs");
            let (mut difference, mut norm) = (0.0, 0.0);
            for (k, (&(wi, wo), &w)) in pairs.pairs().iter().zip(pairs.weights()).enumerate() {
                let r = reference.eval(&Query::far(wi, wo));
                for c in 0..3 {
                    difference += w * (f64::from(gpu[3 * k + c]) - r[c]).powi(2);
                    norm += w * r[c] * r[c];
                }
            }
            worst = worst.max((difference / norm).sqrt());
        }
    }
    eprintln!(
        "planner E = {:.4}, on the device E = {worst:.4}, budget {}",
        planned.error, scene.budget
    );
    assert!(worst <= scene.budget, "E on the device = {worst}");
}
