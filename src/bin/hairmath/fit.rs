//! `hairmath fit`: regenerates every fitted constant and prints one table (or JSON), and can
//! write the generated constants file.

use std::io::{self, BufWriter, Write};
use std::path::PathBuf;

use clap::Args;
use hairmath::fit::generate::{all_fits, constants_source};
use hairmath::fit::{ConstantFit, FitOutput, FitSettings};

use crate::CliError;

/// Arguments of `hairmath fit`.
#[derive(Args, Debug)]
pub struct FitArgs {
    /// Relative index of refraction the fits are run for.
    #[arg(long, default_value_t = 1.55)]
    eta: f64,
    /// Print the table as JSON (keys in the README) instead of markdown.
    #[arg(long)]
    json: bool,
    /// Also write the generated Rust constants file to this path (the repository's copy is
    /// src/fit/constants.rs, for eta = 1.55).
    #[arg(long)]
    write_constants: Option<PathBuf>,
}

/// Runs every fit for the given settings.
pub fn fits(eta: f64) -> Result<(FitSettings, FitOutput), CliError> {
    let settings = FitSettings::new(eta).map_err(|e| CliError::Params(e.to_string()))?;
    let output = all_fits(&settings).map_err(|e| CliError::Params(e.to_string()))?;
    Ok((settings, output))
}

/// `hairmath fit`.
pub fn run(args: &FitArgs) -> Result<(), CliError> {
    let (settings, output) = fits(args.eta)?;
    if let Some(path) = &args.write_constants {
        std::fs::write(path, constants_source(&settings, &output))?;
    }
    let mut out = BufWriter::new(io::stdout().lock());
    if args.json {
        writeln!(out, "{}", json(&output.records))?;
    } else {
        table(&mut out, &output.records)?;
    }
    out.flush()?;
    Ok(())
}

/// A number for the table: 4 significant digits, or "-" when absent.
fn cell(x: Option<f64>) -> String {
    x.map_or_else(|| "-".into(), |v| format!("{v:.4}"))
}

/// An error for the table, in scientific notation.
fn error_cell(x: Option<f64>) -> String {
    x.map_or_else(|| "-".into(), |v| format!("{v:.2e}"))
}

/// The markdown table of every record.
pub fn table(out: &mut impl Write, records: &[ConstantFit]) -> io::Result<()> {
    writeln!(
        out,
        "| constant | source | published | refit | metric | error (published -> refit) |"
    )?;
    writeln!(out, "|---|---|---|---|---|---|")?;
    let escape = |text: &str| text.replace('|', "\\|");
    for r in records {
        writeln!(
            out,
            "| {} | {} | {} | {} | {} | {} -> {} |",
            r.key,
            escape(&r.source),
            cell(r.published),
            cell(Some(r.refit)),
            escape(&r.metric),
            error_cell(r.published_error),
            error_cell(Some(r.refit_error)),
        )?;
    }
    Ok(())
}

/// The records as a JSON array (keys documented in the README).
fn json(records: &[ConstantFit]) -> String {
    let rows: Vec<serde_json::Value> = records
        .iter()
        .map(|r| {
            serde_json::json!({
                "key": r.key,
                "source": r.source,
                "approximates": r.approximates,
                "published": r.published,
                "refit": r.refit,
                "metric": r.metric,
                "published_error": r.published_error,
                "refit_error": r.refit_error,
            })
        })
        .collect();
    serde_json::to_string_pretty(&rows).unwrap_or_else(|_| "[]".into())
}
