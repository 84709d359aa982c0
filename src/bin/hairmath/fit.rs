//! `hairmath fit`: regenerates every fitted constant and prints one table (or JSON), and can
//! write the generated constants file.

use std::io::{self, Write};
use std::path::{Path, PathBuf};

use clap::Args;
use hairmath::fit::{absorption_report, AbsorptionReport, FrostbiteReport, TABLE_SIGMA_A};
use hairmath::fit::{all_fits_with_progress, constants_source};
use hairmath::fit::{frostbite_report, AttenuationErrorTable, TtGaussianTable};
use hairmath::fit::{ConstantFit, FitOutput, FitSettings};

use crate::{with_stdout, CliError};

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
    /// src/models/constants.rs, for eta = 1.55).
    #[arg(long)]
    write_constants: Option<PathBuf>,
    /// After the table, print each family's error tables (markdown): the absorption
    /// exponents' relative errors by sigma_a, Frostbite's single-offset attenuation errors over
    /// (sigma_a, theta_d) and its per-slice Gaussian errors over (theta_o, beta_n).
    #[arg(long, conflicts_with = "json")]
    details: bool,
}

/// Runs every fit for the given settings, with a progress bar on a terminal's stderr.
pub fn fits(eta: f64) -> Result<(FitSettings, FitOutput), CliError> {
    let bar = crate::progress::bar("fitting (families)");
    let fits = fits_with_progress(eta, &crate::progress::callback(&bar));
    bar.finish_and_clear();
    fits
}

/// Runs every fit for the given settings, calling `progress(done, total)` after each family.
pub fn fits_with_progress(
    eta: f64,
    progress: &(dyn Fn(usize, usize) + Sync),
) -> Result<(FitSettings, FitOutput), CliError> {
    let settings = FitSettings::new(eta)?;
    let output = all_fits_with_progress(&settings, progress)?;
    Ok((settings, output))
}

/// `hairmath fit`. The constants file of --write-constants is opened before the fits run, so
/// that a path that cannot be written is reported at once, not after the fits.
pub fn run(args: &FitArgs) -> Result<(), CliError> {
    FitSettings::new(args.eta)?;
    let target = args
        .write_constants
        .as_deref()
        .map(OutputFile::open)
        .transpose()?;
    let (settings, output) = match fits(args.eta) {
        Ok(done) => done,
        Err(e) => {
            if let Some(target) = target {
                target.abandon();
            }
            return Err(e);
        }
    };
    if let Some(target) = target {
        target.write(constants_source(&settings, &output).as_bytes())?;
    }
    with_stdout(|out| print(args, &settings, &output, out))
}

/// The table (or JSON) and, with --details, the error tables, to `out` (standard output).
fn print(
    args: &FitArgs,
    settings: &FitSettings,
    output: &FitOutput,
    out: &mut impl Write,
) -> Result<(), CliError> {
    if args.json {
        writeln!(out, "{}", json(&output.records)).map_err(CliError::stdout)?;
    } else {
        table(out, &output.records).map_err(CliError::stdout)?;
    }
    if args.details {
        details(out, settings)?;
    }
    Ok(())
}

/// A file opened for writing before the work whose result it receives: opening it finds an
/// unwritable path at once. A file it created is removed if the work fails.
struct OutputFile<'a> {
    path: &'a Path,
    file: std::fs::File,
    created: bool,
}

impl<'a> OutputFile<'a> {
    /// Opens (creating, not yet truncating) `path`.
    fn open(path: &'a Path) -> Result<Self, CliError> {
        let created = !path.exists();
        let file = std::fs::OpenOptions::new()
            .write(true)
            .create(true)
            .truncate(false)
            .open(path)
            .map_err(|e| CliError::io(path, e))?;
        Ok(OutputFile {
            path,
            file,
            created,
        })
    }

    /// Replaces the file's contents with `bytes`.
    fn write(mut self, bytes: &[u8]) -> Result<(), CliError> {
        let io = |e| CliError::io(self.path, e);
        self.file.set_len(0).map_err(io)?;
        self.file.write_all(bytes).map_err(io)?;
        self.file.flush().map_err(io)
    }

    /// Leaves the file as it was: removes it if [`OutputFile::open`] created it.
    fn abandon(self) {
        if self.created {
            let _ = std::fs::remove_file(self.path);
        }
    }
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
    serde_json::to_string_pretty(&json_rows(records)).unwrap_or_else(|_| "[]".into())
}

/// The records as a JSON array value: one object per record with the keys key, source,
/// approximates, published, refit, metric, published_error, refit_error (also the
/// `fitted_constants` of `hairmath report --json`).
pub fn json_rows(records: &[ConstantFit]) -> serde_json::Value {
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
    serde_json::Value::Array(rows)
}

/// The error tables behind the summary rows.
fn details(out: &mut impl Write, settings: &FitSettings) -> Result<(), CliError> {
    let absorption = absorption_report(settings)?;
    let frostbite = frostbite_report(settings)?;
    write_details(out, &absorption, &frostbite).map_err(CliError::stdout)
}

/// Writes the error tables of [`details`].
fn write_details(
    out: &mut impl Write,
    absorption: &AbsorptionReport,
    frostbite: &FrostbiteReport,
) -> io::Result<()> {
    writeln!(
        out,
        "\n## Absorption exponents: (e^(-k sigma_a) - E(sigma_a)/E(0)) / (E(sigma_a)/E(0))\n"
    )?;
    let header: Vec<String> = TABLE_SIGMA_A
        .iter()
        .map(|s| format!("sigma_a {s}"))
        .collect();
    writeln!(
        out,
        "| fit | exponent | k | RMS | max | {} |",
        header.join(" | ")
    )?;
    writeln!(out, "|---|---|---|---|---|{}", "---|".repeat(header.len()))?;
    for fit in &absorption.fits {
        for e in &fit.errors {
            let rel: Vec<String> = e.relative.iter().map(|r| format!("{r:+.3}")).collect();
            writeln!(
                out,
                "| {} | {} | {:.4} | {:.2e} | {:.2e} | {} |",
                fit.key(),
                e.label,
                e.k,
                e.rms,
                e.max_abs,
                rel.join(" | ")
            )?;
        }
    }
    for offset in [&frostbite.tt_offset, &frostbite.trt_offset] {
        for (label, table) in [("published", &offset.published), ("refit", &offset.refit)] {
            attenuation_table(out, label, table)?;
        }
    }
    gaussian_table(out, &frostbite.tt_gaussian)?;
    Ok(())
}

/// A Frostbite single-offset attenuation error table: rows sigma_a, columns theta_d.
fn attenuation_table(
    out: &mut impl Write,
    label: &str,
    table: &AttenuationErrorTable,
) -> io::Result<()> {
    writeln!(
        out,
        "\n## Frostbite {:?} attenuation at h = {:.4} ({label}): (A(h) - E) / E, RMS {:.3}\n",
        table.path, table.h, table.rms
    )?;
    let columns: Vec<String> = table
        .theta_d
        .iter()
        .map(|t| format!("{:.0} deg", t.to_degrees()))
        .collect();
    writeln!(out, "| sigma_a \\ theta_d | {} |", columns.join(" | "))?;
    writeln!(out, "|---|{}", "---|".repeat(columns.len()))?;
    for (sigma_a, row) in table.sigma_a.iter().zip(&table.relative_error) {
        let cells: Vec<String> = row.iter().map(|e| format!("{e:+.3}")).collect();
        writeln!(out, "| {sigma_a} | {} |", cells.join(" | "))?;
    }
    Ok(())
}

/// RMS error of each TT Gaussian slice relative to its peak: rows theta_o, columns beta_n.
fn gaussian_table(out: &mut impl Write, table: &TtGaussianTable) -> io::Result<()> {
    writeln!(
        out,
        "\n## Frostbite TT Gaussians a exp(-b (|phi| - pi)^2): RMS error / peak per slice\n"
    )?;
    let columns: Vec<String> = table.beta_n.iter().map(|b| format!("{b}")).collect();
    writeln!(out, "| theta_o \\ beta_n | {} |", columns.join(" | "))?;
    writeln!(out, "|---|{}", "---|".repeat(columns.len()))?;
    for (theta_o, row) in table.theta_o.iter().zip(&table.slices) {
        let cells: Vec<String> = row.iter().map(|f| format!("{:.1e}", f.rms_error)).collect();
        writeln!(
            out,
            "| {:.0} deg | {} |",
            theta_o.to_degrees(),
            cells.join(" | ")
        )?;
    }
    Ok(())
}
