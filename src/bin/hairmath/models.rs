//! `hairmath models`: every real-time model against the reference, error and cost side by side
//! ([`hairmath::fit::compare_models`]), as a markdown table or JSON. This file only formats:
//! every number comes from the library.

use crate::flags::input_flag_values;
use crate::{with_stdout, CliError};
use clap::Args;
use hairmath::diagnostics::{ModelError, OpCounts};
use hairmath::fit::{
    approximation, compare_models, ComparisonSettings, ModelRow, ENERGY_THETA_O_DEG,
};
use serde_json::{json, Value};
use std::io::{self, Write};

/// Arguments of `hairmath models`.
#[derive(Args, Debug)]
pub struct ModelsArgs {
    /// Only dark brown hair (eumelanin 3) at beta_m = beta_n = 0.3, the README's table (the
    /// full grid has 36 hairs).
    #[arg(long)]
    dark_brown: bool,
    /// Only these models (repeat the flag; default: every real-time model).
    #[arg(long = "model", value_name = "NAME")]
    models: Vec<String>,
    /// Print the rows as a JSON array instead of markdown, for scripts.
    ///
    /// One object per model and hair, with the keys:
    ///
    /// - `model`, and the hair: `colour`, `eumelanin`, `pheomelanin`, `beta_m`, `beta_n`
    ///   (alpha is 2 degrees and eta 1.55 for every hair).
    /// - `error_mapped`, `error_fitted`: E against Chiang's far field at the mapped and at the
    ///   fitted inputs, and `error_mapped_half_pairs`, `error_fitted_half_pairs`: the same on
    ///   the first half of the pairs (the convergence check); `pairs`, `fit_pairs`.
    /// - `mapped_inputs`, `fitted_inputs`: objects keyed by the model's flag names without
    ///   dashes (`roughness`, `beta-m`, `alpha-deg` in degrees; an absorption as `color`,
    ///   `sigma-a` or `melanin`; RGB values as arrays of three).
    /// - `fit_iterations`, `fit_termination`: argmin's Nelder-Mead run.
    /// - `energy_error`, `energy_error_fitted`: the relative albedo error at
    ///   `energy_theta_o_deg` = [0, 45, 80] (arrays of three).
    /// - `ns_per_eval_f32`, `ns_per_eval_batch`: wall-clock nanoseconds per evaluation (they
    ///   vary from run to run; `cargo bench --bench models` has criterion's figures).
    /// - `ops`: the traced evaluation's counts `add_mul`, `div`, `sqrt`, `transcendental`,
    ///   `select`, `fetch` (texture samples).
    #[arg(long, verbatim_doc_comment)]
    json: bool,
}

/// Runs `hairmath models`.
pub fn run(args: &ModelsArgs) -> Result<(), CliError> {
    let mut settings = if args.dark_brown {
        ComparisonSettings::dark_brown()
    } else {
        ComparisonSettings::full()
    };
    if !args.models.is_empty() {
        settings.models = args
            .models
            .iter()
            .map(|name| approximation(name).map(|(m, _)| m.name))
            .collect::<Result<_, _>>()?;
    }
    let bar = crate::progress::bar("fitting models (rows)");
    let rows = compare_models(&settings, &crate::progress::callback(&bar));
    bar.finish_and_clear();
    let rows = rows?;
    with_stdout(|out| {
        if args.json {
            let rows: Vec<Value> = rows.iter().map(|r| row_json(r, &settings)).collect();
            let text = serde_json::to_string_pretty(&rows).expect("JSON of finite numbers");
            writeln!(out, "{text}")
        } else {
            markdown(out, &rows, &settings)
        }
        .map_err(CliError::stdout)
    })
}

pub(crate) fn row_json(r: &ModelRow, settings: &ComparisonSettings) -> Value {
    json!({
        "model": r.model,
        "colour": r.hair.colour,
        "eumelanin": r.hair.eumelanin,
        "pheomelanin": r.hair.pheomelanin,
        "beta_m": r.hair.beta_m,
        "beta_n": r.hair.beta_n,
        "error_mapped": finite(r.error_mapped.full),
        "error_mapped_half_pairs": finite(r.error_mapped.half),
        "error_fitted": finite(r.error_fitted.full),
        "error_fitted_half_pairs": finite(r.error_fitted.half),
        "pairs": settings.pairs,
        "fit_pairs": settings.fit_pairs,
        "mapped_inputs": input_flag_values(r.model, &r.mapped_inputs),
        "fitted_inputs": input_flag_values(r.model, &r.fit.values),
        "fit_iterations": r.fit.minimum.iterations,
        "fit_termination": r.fit.minimum.termination,
        "energy_theta_o_deg": ENERGY_THETA_O_DEG,
        "energy_error": r.energy_error.iter().map(|&e| finite(e)).collect::<Vec<_>>(),
        "energy_error_fitted": r.energy_error_fitted.iter().map(|&e| finite(e)).collect::<Vec<_>>(),
        "ns_per_eval_f32": r.cost.ns_per_eval_f32,
        "ns_per_eval_batch": r.cost.ns_per_eval_batch,
        "ops": ops_json(&r.cost.ops),
    })
}

/// A number, or `null` for an infinite one (JSON has no infinity).
fn finite(v: f64) -> Value {
    if v.is_finite() {
        json!(v)
    } else {
        Value::Null
    }
}

fn ops_json(o: &OpCounts) -> Value {
    json!({
        "add_mul": o.add_mul,
        "div": o.div,
        "sqrt": o.sqrt,
        "transcendental": o.transcendental,
        "select": o.select,
        "fetch": o.fetch,
    })
}

pub(crate) fn markdown(
    out: &mut impl Write,
    rows: &[ModelRow],
    settings: &ComparisonSettings,
) -> io::Result<()> {
    writeln!(
        out,
        "Error E against Chiang et al. 2016's far field ({} nodes in h) on {} direction pairs \
         (in brackets: on the first half); fits on {} pairs. Energy error: relative albedo \
         error at theta_o = 0, 45, 80 degrees (mapped inputs). ns: wall clock, f32 scalar / \
         SIMD batch. Ops: add+mul, div, sqrt, transcendental, select, texture fetch.\n",
        settings.reference_nodes, settings.pairs, settings.fit_pairs
    )?;
    writeln!(
        out,
        "| model | hair | beta_m | beta_n | E mapped | E fitted | fitted inputs | energy error | ns f32 / batch | ops |"
    )?;
    writeln!(out, "|---|---|---|---|---|---|---|---|---|---|")?;
    for r in rows {
        let inputs = input_flag_values(r.model, &r.fit.values);
        let inputs: Vec<String> = inputs
            .as_object()
            .map(|o| o.iter().map(|(k, v)| format!("{k} {v}")).collect())
            .unwrap_or_default();
        let energy: Vec<String> = r.energy_error.iter().map(|e| format!("{e:+.3}")).collect();
        let o = &r.cost.ops;
        writeln!(
            out,
            "| {} | {} | {} | {} | {} | {} | {} | {} | {:.0} / {:.1} | {} {} {} {} {} {} |",
            r.model,
            r.hair.colour,
            r.hair.beta_m,
            r.hair.beta_n,
            error_cell(&r.error_mapped),
            error_cell(&r.error_fitted),
            inputs.join(", "),
            energy.join(" "),
            r.cost.ns_per_eval_f32,
            r.cost.ns_per_eval_batch,
            o.add_mul,
            o.div,
            o.sqrt,
            o.transcendental,
            o.select,
            o.fetch
        )?;
    }
    Ok(())
}

fn error_cell(e: &ModelError) -> String {
    format!("{:.3} ({:.3})", e.full, e.half)
}
