//! `hairmath plan`: the cheapest composition of per-lobe factors that meets a scene's error
//! budget ([`hairmath::plan::plan`]), printed, as JSON, and with `--out DIR` its shader, tables
//! and `plan.json`. This file only formats what the library computes.

use crate::shader::languages;
use crate::{create_dir, with_stdout, write_file, CliError};
use clap::builder::PossibleValuesParser;
use clap::Args;
use hairmath::diagnostics::OpCounts;
use hairmath::models::{Azimuthal, LobeFactors};
use hairmath::plan::{
    compare_published, plan, plan_shader, CostMeasure, DeviceTiming, Plan, PlanSettings,
    PlannedLobe, PublishedComparison, Scene,
};
use hairmath::shader::{table_files, CommittedFile, Language, ModelShader};
use serde_json::{json, Value};
use std::io::Write;
use std::path::{Path, PathBuf};

/// Arguments of `hairmath plan`.
#[derive(Args, Debug)]
pub struct PlanArgs {
    /// The scene file (TOML; the README's "Scene plans" documents its keys).
    scene: PathBuf,
    /// Print the plan as one JSON object (keys choices, error, cost, shader, ...).
    #[arg(long)]
    json: bool,
    /// Write the plan's shader (`hair.<ext>`), its lookup tables and `plan.json` to DIR.
    #[arg(long, value_name = "DIR")]
    out: Option<PathBuf>,
    /// The language of the shader written with --out, as for `hairmath shader`.
    #[arg(long, default_value = "wgsl", value_parser = PossibleValuesParser::new(languages()))]
    lang: String,
}

/// The file extension of a shader in `language`.
fn extension(language: Language) -> &'static str {
    match language {
        Language::Wgsl | Language::WgslCompute | Language::WgslNagaOil => "wgsl",
        Language::Glsl => "glsl",
        Language::Hlsl => "hlsl",
        Language::Msl => "metal",
        Language::Spirv => "spv",
    }
}

/// Runs `hairmath plan`.
pub fn run(args: &PlanArgs) -> Result<(), CliError> {
    let scene = Scene::read(&args.scene).map_err(|e| CliError::Plan(e.to_string()))?;
    // An output folder that cannot be made is reported before the planning, not after it.
    if let Some(dir) = &args.out {
        create_dir(dir)?;
    }
    let bar = crate::progress::bar("measuring (hairs)");
    let settings = PlanSettings::default();
    let result = plan(&scene, &settings, &crate::progress::callback(&bar));
    bar.finish_and_clear();
    let plan = result.map_err(|e| CliError::Plan(e.to_string()))?;
    let published =
        compare_published(&plan, &settings).map_err(|e| CliError::Plan(e.to_string()))?;
    let language = Language::from_name(&args.lang).expect("clap checks the name");
    let shader = plan_shader(
        &format!(
            "the scene plan of {}: {}",
            args.scene.display(),
            plan.composition.describe()
        ),
        plan.graph.clone(),
    )?;
    let file = format!("hair.{}", extension(language));
    let data = plan_json(&scene, &plan, &published, &file, &args.lang);
    if let Some(dir) = &args.out {
        write_outputs(dir, &shader, language, &file, &data)?;
    }
    with_stdout(|out| {
        match args.json {
            true => writeln!(
                out,
                "{}",
                serde_json::to_string_pretty(&data).expect("JSON")
            ),
            false => write!(out, "{}", plan_text(&scene, &plan, &published)),
        }
        .map_err(CliError::stdout)
    })
}

/// Writes the shader, its tables and bindings, and `plan.json` into `dir`.
fn write_outputs(
    dir: &Path,
    shader: &ModelShader,
    language: Language,
    file: &str,
    data: &Value,
) -> Result<(), CliError> {
    create_dir(dir)?;
    write_file(&dir.join(file), shader.write(language)?)?;
    let (tables, mut files) = table_files("hair", shader);
    if !shader.module.bindings().is_empty() {
        files.push(CommittedFile {
            name: "hair.bindings.json".to_string(),
            contents: shader.bindings_json(&tables).into_bytes(),
        });
    }
    for f in files {
        write_file(&dir.join(&f.name), &f.contents)?;
    }
    let text = serde_json::to_string_pretty(data).expect("JSON") + "\n";
    write_file(&dir.join("plan.json"), text)
}

/// The factors of one lobe as JSON.
fn factors_json(factors: Option<LobeFactors>, nodes: usize) -> Value {
    let Some(f) = factors else {
        return Value::Null;
    };
    let (distribution, attenuation) = match f.azimuthal {
        Azimuthal::Separable {
            distribution,
            attenuation,
        } => (json!(distribution.name()), json!(attenuation.name())),
        _ => (Value::Null, Value::Null),
    };
    json!({
        "longitudinal": f.longitudinal.name(),
        "azimuthal": f.azimuthal.name(),
        "distribution": distribution,
        "attenuation": attenuation,
        "far_field_nodes": if f.azimuthal == Azimuthal::FarField { json!(nodes) } else { Value::Null },
        "description": f.describe(),
    })
}

/// A lobe's choice as JSON.
fn lobe_json(lobe: &PlannedLobe, nodes: usize) -> Value {
    json!({
        "lobe": lobe.lobe,
        "kept": lobe.kept,
        "factors": factors_json(lobe.factors, nodes),
        "table": lobe.table.map(|t| json!({
            "phi": t.phi, "theta_o": t.theta_o, "beta_n": t.beta_n,
        })),
        "marschner_table": lobe.marschner_table.map(|t| json!({
            "phi": t.phi, "theta_d": t.theta_d,
        })),
        "error": lobe.error,
        "cost": lobe.cost,
    })
}

fn ops_json(o: &OpCounts) -> Value {
    json!({
        "add_mul": o.add_mul, "div": o.div, "sqrt": o.sqrt,
        "transcendental": o.transcendental, "select": o.select, "fetch": o.fetch,
    })
}

/// The name of a cost measure in the scene file and the JSON.
fn measure_name(measure: CostMeasure) -> &'static str {
    match measure {
        CostMeasure::Ops => "ops",
        CostMeasure::Llvmpipe => "llvmpipe",
    }
}

/// The timed candidates of a `cost = "llvmpipe"` plan as JSON (null for `cost = "ops"`).
fn timing_json(timing: Option<&DeviceTiming>) -> Value {
    let Some(t) = timing else {
        return Value::Null;
    };
    json!({
        "adapter": t.adapter,
        "rows": t.rows,
        "repetitions": t.repetitions,
        "fastest": t.fastest(),
        "candidates": t.candidates.iter().map(|c| json!({
            "composition": c.composition.describe(),
            "ops_cost": c.ops_cost,
            "error": c.error,
            "ns_per_eval": c.ns_per_eval,
        })).collect::<Vec<_>>(),
    })
}

/// The plan as JSON: `choices`, `error`, `cost` (in the unit of `cost_measure`), `shader` and
/// the measurement's context.
fn plan_json(
    scene: &Scene,
    plan: &Plan,
    published: &[PublishedComparison],
    file: &str,
    lang: &str,
) -> Value {
    let nodes = plan.composition.far_field_nodes;
    let point: serde_json::Map<String, Value> = plan
        .worst_point
        .values
        .iter()
        .map(|(k, v)| (k.name().to_string(), json!(v)))
        .collect();
    let arguments: Vec<&str> = ["wi", "wo"]
        .into_iter()
        .chain(plan.arguments.iter().copied())
        .collect();
    json!({
        "budget": scene.budget,
        "composition": plan.composition.describe(),
        "choices": plan.lobes.iter().map(|l| lobe_json(l, nodes)).collect::<Vec<_>>(),
        "far_field_nodes": if plan.composition.uses_far_field() { json!(nodes) } else { Value::Null },
        "error": plan.error,
        "worst_point": point,
        "cost": plan.cost,
        "cost_measure": measure_name(plan.measure),
        "cost_unit": match plan.measure {
            CostMeasure::Ops => "weighted operations",
            CostMeasure::Llvmpipe => "nanoseconds per evaluation on llvmpipe",
        },
        "ops_cost": plan.ops_cost,
        "ops": ops_json(&plan.ops),
        "shader": {
            "file": file,
            "language": lang,
            "function": "hair_bcsdf",
            "arguments": arguments,
        },
        "published": published.iter().map(|p| json!({
            "model": p.model, "error": p.error, "cost": p.cost, "ops": ops_json(&p.ops),
            "dominated": p.dominated,
        })).collect::<Vec<_>>(),
        "points": plan.points.len(),
        "combinations": plan.combinations,
        "feasible": plan.feasible,
        "device": timing_json(plan.timing.as_ref()),
    })
}

/// The plan as text: a line per lobe, the totals, the published models beside it.
fn plan_text(scene: &Scene, plan: &Plan, published: &[PublishedComparison]) -> String {
    let mut s = format!(
        "plan for budget E <= {} over {} hairs ({} combinations, {} within the budget)\n",
        scene.budget,
        plan.points.len(),
        plan.combinations,
        plan.feasible
    );
    s += "| lobe | factors | own error | cost alone |\n| --- | --- | ---: | ---: |\n";
    for lobe in &plan.lobes {
        s += &format!(
            "| {} | {} | {:.3e} | {} |\n",
            lobe.lobe,
            lobe.describe(),
            lobe.error,
            lobe.cost
        );
    }
    let worst: Vec<String> = plan
        .worst_point
        .values
        .iter()
        .map(|(k, v)| format!("{} = {v}", k.name()))
        .collect();
    let o = &plan.ops;
    if let Some(t) = &plan.timing {
        s += &format!(
            "cost = {:.2} ns per evaluation on llvmpipe, the fastest measured of the {} cheapest \
             by weighted operations within the budget (median of {} dispatches of {} rows on \
             {}):\n| composition | weighted ops | E | ns per evaluation |\n| --- | ---: | ---: | ---: |\n",
            plan.cost,
            t.candidates.len(),
            t.repetitions,
            t.rows,
            t.adapter
        );
        for c in &t.candidates {
            s += &format!(
                "| {} | {} | {:.4} | {:.2} |\n",
                c.composition.describe(),
                c.ops_cost,
                c.error,
                c.ns_per_eval
            );
        }
    }
    let label = match plan.measure {
        CostMeasure::Ops => "cost",
        CostMeasure::Llvmpipe => "weighted operations",
    };
    s += &format!(
        "error E = {:.4e} (worst at {})\n{label} = {} (add+mul {}, div {}, sqrt {}, transc. {}, \
         select {}, fetch {})\nshader: hair_bcsdf(wi, wo{})\n",
        plan.error,
        worst.join(", "),
        plan.ops_cost,
        o.add_mul,
        o.div,
        o.sqrt,
        o.transcendental,
        o.select,
        o.fetch,
        plan.arguments
            .iter()
            .map(|a| format!(", {a}"))
            .collect::<String>(),
    );
    s += "\npublished models at their mapped inputs, on the same hairs and pairs:\n";
    s += "| model | E | cost | the plan costs no more, with lower E |\n| --- | ---: | ---: | --- |\n";
    for p in published {
        let verdict = if p.dominated { "yes" } else { "no" };
        s += &format!(
            "| {} | {:.4} | {} | {verdict} |\n",
            p.model, p.error, p.cost
        );
    }
    s
}
