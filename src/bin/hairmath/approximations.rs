//! The speed-against-error section of `hairmath report`: the catalogues of the example
//! scenes ([`hairmath::plan::catalogue`]) as one markdown table (every approximation: the
//! published models, the plans, every lobe option of the planner), each scene's Pareto front,
//! and as JSON. This file only formats.

use crate::CliError;
use hairmath::plan::{catalogue, example_scenes, Catalogue, PlanSettings};
use serde_json::{json, Value};
use std::io::{self, Write};

/// The catalogue of every example scene (the last stage of `hairmath report`), with a
/// progress bar per scene on a terminal's standard error (the hairs measured,
/// [`crate::progress`]).
pub fn catalogues(settings: &PlanSettings) -> Result<Vec<(&'static str, Catalogue)>, CliError> {
    let scenes = example_scenes().map_err(|e| CliError::Plan(e.to_string()))?;
    let count = scenes.len();
    let mut out = Vec::new();
    for (k, (name, scene)) in scenes.into_iter().enumerate() {
        let bar = crate::progress::bar(format!(
            "report 4/4: catalogue {}/{count} {name} (hairs)",
            k + 1
        ));
        let c = catalogue(&scene, settings, &crate::progress::callback(&bar));
        bar.finish_and_clear();
        out.push((name, c.map_err(|e| CliError::Plan(e.to_string()))?));
    }
    Ok(out)
}

/// One row of the table: what kind of approximation, its name, and per scene `(E, cost)`.
struct Row {
    kind: &'static str,
    name: String,
    cells: Vec<Option<(f64, f64)>>,
}

/// The rows of every approximation over the scenes, in the order first seen.
fn rows(catalogues: &[(&str, Catalogue)]) -> Vec<Row> {
    let mut rows: Vec<Row> = Vec::new();
    let scenes = catalogues.len();
    let mut put = |kind: &'static str, name: String, scene: usize, cell: (f64, f64)| {
        let at = match rows.iter().position(|r| r.kind == kind && r.name == name) {
            Some(i) => i,
            None => {
                rows.push(Row {
                    kind,
                    name,
                    cells: vec![None; scenes],
                });
                rows.len() - 1
            }
        };
        rows[at].cells[scene] = Some(cell);
    };
    for (s, (_, c)) in catalogues.iter().enumerate() {
        put(
            "plan",
            format!("plan at budget {}", c.budget),
            s,
            (c.plan.error, c.plan.cost),
        );
        for p in &c.published {
            put("published", p.model.to_string(), s, (p.error, p.cost));
        }
    }
    for (s, (_, c)) in catalogues.iter().enumerate() {
        for o in &c.options {
            put(lobe_kind(o.lobe), o.describe(), s, (o.error, o.cost));
        }
    }
    rows
}

/// The kind of a lobe option's row.
fn lobe_kind(lobe: &str) -> &'static str {
    match lobe {
        "R" => "R option",
        "TT" => "TT option",
        "TRT" => "TRT option",
        _ => "residual option",
    }
}

/// The section as markdown.
pub fn markdown(out: &mut impl Write, catalogues: &[(&str, Catalogue)]) -> io::Result<()> {
    writeln!(
        out,
        "\n## Speed against error (`hairmath plan`'s choices)\n"
    )?;
    writeln!(
        out,
        "Every approximation against the Chiang far field: E over the planner's direction \
         pairs and its weighted traced cost, for the example scenes (`examples/scenes/`). A \
         lobe option's E is its own lobe's error relative to the whole reference (a dropped \
         lobe's is its share of it), its cost that of a shader of the lobe alone.\n"
    )?;
    let mut header = "| kind | approximation |".to_string();
    let mut rule = "| --- | --- |".to_string();
    for (name, _) in catalogues {
        header += &format!(" E {name} | cost {name} |");
        rule += " ---: | ---: |";
    }
    writeln!(out, "{header}\n{rule}")?;
    for row in rows(catalogues) {
        let mut line = format!("| {} | {} |", row.kind, row.name);
        for cell in &row.cells {
            line += &match cell {
                Some((e, c)) => format!(" {e:.4} | {c} |"),
                None => " | |".to_string(),
            };
        }
        writeln!(out, "{line}")?;
    }
    for (name, c) in catalogues {
        writeln!(
            out,
            "\n### {name} hair: the Pareto front ({} compositions; plan: {})\n",
            c.combinations,
            c.plan.composition.describe()
        )?;
        writeln!(out, "| E | cost | composition |\n| ---: | ---: | --- |")?;
        for p in &c.front {
            writeln!(
                out,
                "| {:.4} | {} | {} |",
                p.error,
                p.cost,
                p.composition.describe()
            )?;
        }
    }
    Ok(())
}

/// The section as JSON: one object per scene.
pub fn json(catalogues: &[(&str, Catalogue)]) -> Value {
    catalogues
        .iter()
        .map(|(name, c)| {
            json!({
                "scene": name,
                "budget": c.budget,
                "combinations": c.combinations,
                "plan": {
                    "composition": c.plan.composition.describe(),
                    "error": c.plan.error,
                    "cost": c.plan.cost,
                },
                "published": c.published.iter().map(|p| json!({
                    "model": p.model, "error": p.error, "cost": p.cost, "dominated": p.dominated,
                })).collect::<Vec<_>>(),
                "options": c.options.iter().map(|o| json!({
                    "lobe": o.lobe, "option": o.describe(), "kept": o.kept,
                    "far_field_nodes": o.far_field_nodes,
                    "table": o.table.map(|t| json!({
                        "phi": t.phi, "theta_o": t.theta_o, "beta_n": t.beta_n,
                    })),
                    "marschner_table": o.marschner_table.map(|t| json!({
                        "phi": t.phi, "theta_d": t.theta_d,
                    })),
                    "error": o.error, "cost": o.cost,
                })).collect::<Vec<_>>(),
                "front": c.front.iter().map(|p| json!({
                    "composition": p.composition.describe(), "error": p.error, "cost": p.cost,
                })).collect::<Vec<_>>(),
            })
        })
        .collect()
}
