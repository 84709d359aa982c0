//! `hairmath cases` and `hairmath check`: the test kit (`hairmath::testing`) for
//! implementations in other languages. The library writes the cases and compares; this file
//! parses flags and formats the verdict.

use crate::flags::{model_names, ModelFlags};
use crate::{with_stdout, CliError};
use clap::builder::PossibleValuesParser;
use clap::Args;
use hairmath::bcsdf::Bcsdf;
use hairmath::registry::find_model;
use hairmath::testing::{cases_csv, check_csv, Comparison, Convention, Row};
use serde_json::json;
use std::io::{self, Write};

fn convention_names() -> Vec<&'static str> {
    Convention::ALL.iter().map(|(_, name)| *name).collect()
}

#[derive(Args, Debug)]
pub struct CasesArgs {
    #[arg(long, default_value = "chiang", value_parser = PossibleValuesParser::new(model_names()))]
    model: String,
    #[command(flatten)]
    flags: ModelFlags,
    /// Quasi-random queries after the 243 hard cases.
    #[arg(long, default_value_t = 1000)]
    count: usize,
    #[arg(long, default_value = "hairmath", value_parser = PossibleValuesParser::new(convention_names()))]
    convention: String,
    /// Selects a disjoint block of the quasi-random sequence.
    #[arg(long, default_value_t = 0)]
    seed: u64,
}

#[derive(Args, Debug)]
pub struct CheckArgs {
    #[arg(long, default_value = "chiang", value_parser = PossibleValuesParser::new(model_names()))]
    model: String,
    #[command(flatten)]
    flags: ModelFlags,
    #[arg(long, default_value = "hairmath", value_parser = PossibleValuesParser::new(convention_names()))]
    convention: String,
    /// The largest row error that passes.
    #[arg(long, default_value_t = 1e-3)]
    tolerance: f64,
    /// The worst rows shown.
    #[arg(long, default_value_t = 5)]
    worst: usize,
    #[arg(long)]
    json: bool,
}

/// The largest count `cases` writes (about 100 MB of CSV).
const MAX_CASES: usize = 1 << 20;

fn model(name: &str, flags: &ModelFlags) -> Result<Box<dyn Bcsdf<f64>>, CliError> {
    let entry = find_model(name).ok_or_else(|| CliError::UnknownModel(name.to_string()))?;
    let values = flags.values_at_default_hair(entry)?;
    Ok((entry.build)(&values)?)
}

fn convention(name: &str) -> Convention {
    Convention::from_name(name).expect("clap checks the name")
}

pub fn run_cases(args: &CasesArgs) -> Result<(), CliError> {
    // The model's flags are checked as `check` will read them.
    model(&args.model, &args.flags)?;
    hairmath::ParamError::check("count", args.count as f64, "must be at most 1048576", |n| {
        n <= MAX_CASES as f64
    })?;
    let convention = convention(&args.convention);
    with_stdout(|out| cases_csv(convention, args.count, args.seed, out).map_err(CliError::stdout))
}

pub fn run_check(args: &CheckArgs) -> Result<(), CliError> {
    let tolerance = hairmath::ParamError::check(
        "tolerance",
        args.tolerance,
        "must be a finite number >= 0",
        |t| t >= 0.0,
    )?;
    let model = model(&args.model, &args.flags)?;
    let convention = convention(&args.convention);
    let report = check_csv(model.as_ref(), convention, io::stdin().lock(), args.worst)?;
    let passes = report.passes(tolerance);
    with_stdout(|out| {
        match args.json {
            true => writeln!(out, "{}", json_report(&report, tolerance, passes)),
            false => writeln!(
                out,
                "{report}{} at tolerance {tolerance:e}",
                if passes { "PASS" } else { "FAIL" }
            ),
        }
        .map_err(CliError::stdout)
    })?;
    match passes {
        true => Ok(()),
        false => Err(CliError::CheckFailed {
            max_rel_error: report.max_rel_error,
            tolerance,
        }),
    }
}

fn json_report(report: &Comparison, tolerance: f64, passes: bool) -> String {
    let row = |r: &Row| {
        let v = |w: hairmath::geometry::V3<f64>| [w.x, w.y, w.z];
        json!({
            "row": r.index,
            "wi": v(r.query.wi),
            "wo": v(r.query.wo),
            "h": r.query.h,
            "expected": r.expected,
            "actual": r.actual,
            "rel_error": finite_or_null(r.rel_error),
        })
    };
    let data = json!({
        "rows": report.rows,
        "max_rel_error": finite_or_null(report.max_rel_error),
        "mean_rel_error": finite_or_null(report.mean_rel_error),
        "worst_rows": report.worst_rows.iter().map(row).collect::<Vec<_>>(),
        "tolerance": tolerance,
        "passes": passes,
    });
    serde_json::to_string_pretty(&data).expect("JSON")
}

/// JSON has no infinity: an infinite error (a NaN or infinite value) is written as null.
fn finite_or_null(x: f64) -> serde_json::Value {
    if x.is_finite() {
        json!(x)
    } else {
        serde_json::Value::Null
    }
}
