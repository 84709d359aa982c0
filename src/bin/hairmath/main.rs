//! `hairmath`: command-line access to the hair-shading models of the `hairmath` crate.
//!
//! - `hairmath eval` evaluates a scattering model on directions read as CSV from stdin.
//! - `hairmath report` prints lobe energies of a few hair colours, a white-furnace check and
//!   an indicative evaluation speed, as markdown or (`--json`) JSON.
//! - `hairmath models` measures every real-time model against the reference: error at its
//!   mapped and at its fitted inputs, energy error and cost, one row per model and hair.
//! - `hairmath lut` bakes a lookup table and writes it as raw f32 + JSON (and PNG).
//! - `hairmath fit` regenerates the fitted constants of the source documents and prints them
//!   beside the published values, with errors; it can write the generated constants file.
//! - `hairmath plan` finds the cheapest composition of per-lobe factors whose error over a
//!   scene's hair stays within a budget, and writes its shader.
//! - `hairmath groom` writes a procedural groom as a `.hair` file, and `hairmath bake` bakes
//!   the per-vertex SH transmittance of a `.hair` file.
//! - `hairmath render` writes a PNG of a procedural hair swatch (path-traced with `chiang`,
//!   single scattering with any other model), and `hairmath plot` plots a model's S beside
//!   the reference's (PNG or SVG).
//! - `hairmath wigner3j` and `hairmath gaunt` compute Wigner 3-j symbols and Gaunt coefficients
//!   of rows read as CSV from stdin.
//!
//! Errors in the input or the parameters are reported on stderr and end the program with exit
//! status 2; argument errors found by clap keep clap's own status. Every option that takes a
//! number takes a negative one as `--opt -1` (as well as `--opt=-1`). Output that cannot be
//! written is an error naming the file (or standard output) with status 2, except that a
//! reader that closed standard output early (`hairmath ... | head`) ends the program quietly
//! with status 0.

mod approximations;
mod eval;
mod fit;
mod flags;
mod kit;
mod lut;
mod models;
mod plan;
mod plot;
mod plots;
mod progress;
mod render;
mod report;
mod sh;
mod shader;
mod strands;
mod swatch;

use clap::{CommandFactory, FromArgMatches, Parser, Subcommand};
use std::fmt;
use std::io::{self, BufWriter, Write};
use std::path::Path;
use std::process::ExitCode;

/// The mathematics of hair shading, from the command line.
#[derive(Parser, Debug)]
#[command(name = "hairmath", version)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand, Debug)]
enum Command {
    /// Evaluate a scattering model S(wi, wo, h) on directions read as CSV from stdin.
    ///
    /// The model is any of the library's registered models (--model); each takes its own
    /// flags, and a flag means the same (unit, domain, message) for every model that takes it.
    ///
    /// Reads CSV on stdin. The first line is a header that must name the columns
    /// wi_x, wi_y, wi_z, wo_x, wo_y, wo_z and, for near-field models (chiang), h, in any
    /// order (far-field models ignore h); other columns are passed through unchanged, in
    /// place. Directions are in the fibre's local frame (tangent +X), point away
    /// from the fibre, and must be unit vectors within 1e-3 (they are normalised before
    /// evaluation); h must be in [-1, 1].
    ///
    /// Writes the header with ",f_r,f_g,f_b" appended, then each row with the three values of
    /// S appended (no cosine factor; shortest round-trip formatting). Blank lines are skipped.
    ///
    /// The CSV is deliberately simple: fields are split on every comma and trimmed of
    /// whitespace; quoting is NOT supported, so no field may contain a comma.
    ///
    /// On the first bad row the program reports the line number (the header is line 1) on
    /// stderr and exits with status 2; rows before it have already been written.
    Eval(eval::EvalArgs),
    /// Print a report (markdown, or JSON with --json): lobe energies of a few hair colours, a white-furnace check of
    /// the model and an indicative evaluation speed, for the near and the far field, and the
    /// accuracy and cost of the far field's fixed-node integrator against its reference.
    ///
    /// Lobe energies are integrals of each lobe's S_p over all incident directions (solid
    /// angle), averaged over h uniform in [-1, 1], for a viewing direction perpendicular to
    /// the fibre. Every figure comes from `hairmath::diagnostics::report`. Takes about a
    /// minute in a release build (a progress bar per stage shows on a terminal's stderr);
    /// --quick shrinks every quadrature (half a minute); --json prints the same figures as one
    /// JSON object.
    Report(report::ReportArgs),
    /// Measure every real-time model against the reference (Chiang et al. 2016's far field):
    /// one row per model and hair of a fixed grid, with the error E at the model's mapped
    /// inputs and at inputs fitted with argmin (and those inputs), the energy error and the
    /// cost (ns per evaluation, operation counts of the traced code).
    ///
    /// E = sqrt(sum over direction pairs and RGB of (S_model - S_ref)^2 / sum of S_ref^2), on
    /// a fixed low-discrepancy set of pairs uniform on the product of two spheres; each E comes
    /// with its value on half the pairs. The full grid (4 colours x 3 beta_m x 3 beta_n) takes
    /// several minutes in a release build (a progress bar shows on a terminal's stderr);
    /// --dark-brown computes the README's row set only.
    Models(models::ModelsArgs),
    /// Bake a lookup table (Nguyen-Donnelly M or N textures, Gerard's N_p LUT, or a far-field
    /// N_p table), write it as raw little-endian f32 with a JSON description (and 8-bit PNG
    /// for 2D tables) to --out, and print the error of lookup against direct evaluation. The
    /// bake and the error points show a progress bar on a terminal's stderr.
    Lut(lut::LutArgs),
    /// Regenerate every fitted constant (Gerard's Henyey-Greenstein g and absorption
    /// exponents, Karis' closed forms, Frostbite's TT Gaussians and single-offset
    /// attenuations) and print one table: constant, source, published value, refit value,
    /// metric and the error of each.
    ///
    /// --json prints the same rows as a JSON array with the keys key, source, approximates,
    /// published, refit, metric, published_error, refit_error (null where the paper prints
    /// nothing). --write-constants PATH also writes the generated Rust file of fitted
    /// constants. Takes a few seconds in a release build (a progress bar by family of fits
    /// shows on a terminal's stderr).
    Fit(fit::FitArgs),
    /// Wigner 3-j symbols (j1 j2 j3; m1 m2 m3) of rows read as CSV from stdin.
    ///
    /// The header must name the columns j1, j2, j3, m1, m2, m3 (any order, other columns
    /// passed through, CSV conventions as for `eval`); values are integers or half-integers
    /// written 3, -2, 1/2, -3/2 or 1.5. Writes each row with ",value" appended: the symbol
    /// correctly rounded to f64, in shortest round-trip form; selection-rule zeros print 0.
    /// A malformed row (not a half-integer, j and m of different kinds, negative j, ...) is
    /// reported with its line number and exit status 2, after the rows before it.
    #[command(name = "wigner3j")]
    Wigner3j(sh::Wigner3jArgs),
    /// Gaunt coefficients (integrals of three spherical harmonics) of rows read as CSV from
    /// stdin.
    ///
    /// The header must name the columns l1, m1, l2, m2, l3, m3 (integers; any order, other
    /// columns passed through, CSV conventions as for `eval`). Writes each row with ",value"
    /// appended: the integral of Y_l1^m1 Y_l2^m2 Y_l3^m3 over the sphere for complex SH
    /// (Condon-Shortley phase, no conjugates), or of the crate's real SH with --real; shortest
    /// round-trip form, exact zeros print 0. Errors as for `wigner3j`.
    Gaunt(sh::GauntArgs),
    /// Write a model's shader module, generated from the same Rust code as the CPU evaluation.
    ///
    /// The module defines `hair_bcsdf(wi: vec3<f32>, wo: vec3<f32>) -> vec3<f32>` in the local
    /// frame (tangent +X, wi towards the light, wo towards the viewer; near-field models take
    /// `h: f32` third), returning S with no cosine factor: what `eval` returns for the same
    /// flags. `hair_bcsdf_world(tangent, wi, wo, ...)` takes world-space directions and builds
    /// the local frame as the CPU code does. Every model input is baked as a constant unless
    /// --varying names it: those become arguments after wo (and h), in the given order.
    ///
    /// --lang wgsl writes the functions (and the table bindings) only; wgsl-compute,
    /// glsl, hlsl, msl and spirv add the compute entry point `hair_main`, which evaluates
    /// hair_bcsdf over `@group(0) @binding(0)` (rows of the arguments' f32: wi.xyz, wo.xyz,
    /// then h and the varying inputs) into `@binding(1)` (RGB rows). Models with lookup
    /// tables bind them as rgba32float textures in `@group(1)`, read with textureLoad and
    /// interpolated in shader arithmetic; --out is then required, and the tables and a JSON
    /// description of the bindings are written beside the module.
    Shader(shader::ShaderArgs),
    /// Plan a scene: the cheapest composition of per-lobe, per-factor choices (longitudinal M,
    /// azimuthal N, attenuation A, or the lobe dropped) whose error E against Chiang et al.
    /// 2016's far field stays within the scene's budget over the scene's hair.
    ///
    /// Reads a TOML scene file (budget, cost, [hair] with each parameter fixed, a [min, max]
    /// range or { varying = [min, max] }, [lights]; the README documents the keys). Measures
    /// every composition at the corners of the parameters' box and at interior points (the
    /// worst taken), prints the plan (each lobe's factors with its own error and cost, the
    /// total error measured on the composed model as a whole, its weighted operation count),
    /// or JSON with --json; --out DIR writes the shader hair.<ext> (--lang as for `shader`;
    /// hair_bcsdf takes the scene's non-fixed parameters after wo, in the file's order), its
    /// lookup tables and plan.json. A malformed scene file is reported with its line and key.
    Plan(plan::PlanArgs),
    /// Grow a procedural groom (strands on a scalp, the unit sphere's cap around +Y; straight,
    /// wavy or curly; seeded and deterministic) and write it as a `.hair` file.
    Groom(strands::GroomArgs),
    /// Bake the per-vertex transmittance of a `.hair` file to spherical harmonics (Gerard's
    /// V(x, w): the product of 1 - opacity over the segments a ray from the vertex crosses,
    /// the vertex's own strand excluded).
    ///
    /// Writes DIR/transmittance.f32 (little-endian f32, vertex-major, (L + 1)^2 coefficients
    /// per vertex in the crate's SH convention, vertices in the file's order) and
    /// DIR/transmittance.json (vertex count, lmax, SH convention, baker, opacity, timing). The
    /// fast baker (default) crosses the strands near each vertex exactly and treats the rest
    /// as a medium; --exact casts rays through a bounding-volume hierarchy (the reference, about
    /// a hundred times slower). A progress bar shows on a terminal's stderr.
    Bake(strands::BakeArgs),
    /// Render a `.hair` file with Gerard's spherical-harmonic shading and against the
    /// reference (Gerard's "ground truth": single scattering, the exact transmittance of the
    /// strands' cylinders and the Chiang far field, integrated over the sphere per pixel along
    /// great circles, the transmittance in closed form along each), lit by a procedural
    /// sky and one directional light; also Kajiya-Kay at its best-fit inputs given the same
    /// inputs as Gerard's. Orthographic, looking along -Z.
    ///
    /// Writes DIR/reference.png, DIR/gerard.png, DIR/kajiya_kay.png, DIR/difference.png
    /// (|gerard - reference|, four times brighter), DIR/side_by_side.png and DIR/errors.json
    /// (rmse and relative_error of Gerard's image against the reference, the same under
    /// kajiya_kay, and the reference's convergence against half its circles). A progress
    /// bar shows on a terminal's stderr.
    RenderGerard(render::RenderArgs),
    /// Render a procedural hair swatch (300 gently wavy fibres in three layers, seen face on,
    /// orthographic) under a grey sky and a spherical key light, and write it as a PNG.
    ///
    /// `--model chiang` (the reference's near field, h from each hit) is path-traced: multiple
    /// scattering, multiple importance sampling of the light and the BCSDF (power heuristic),
    /// Russian roulette, --samples paths per pixel (unbiased; noisy at few samples). Every
    /// other model is shaded with single scattering: the direct light and sky at the first
    /// hit with exact visibility, by a fixed quadrature (noise-free). Model flags as for
    /// `eval`; inputs not given take the default hair's values. Prints the mean radiance over
    /// the fibres.
    Render(swatch::SwatchArgs),
    /// Plot a model's S beside the reference (Chiang's far field): against phi at theta_i =
    /// 0, 30 and 60 degrees (theta_o = -theta_i), and against theta_i at phi = 0, 90 and 180
    /// degrees (theta_o = 0); S is the mean over RGB.
    ///
    /// Writes SVG (titles, axes, legend) when --out ends in .svg, otherwise a PNG of the six
    /// panels (grey frames, the reference black, the model red, no text).
    Plot(plot::PlotArgs),
    /// Write test inputs for another renderer's hair BSDF as CSV (the test kit,
    /// `hairmath::testing`): the 243 hard cases (along the tangent, grazing, wi = wo,
    /// wi = -wo, phi = 0 and pi, h = -1, 0, 1), then --count quasi-random queries.
    ///
    /// Columns wi_x, wi_y, wi_z, wo_x, wo_y, wo_z and, where the convention takes it, h, in
    /// the meaning of --convention: hairmath (tangent +X, wi towards the light), pbrt (the
    /// same; its f is S / |wi.z|) or mitsuba (tangent +Y, wi = si.wi towards the camera, wo
    /// towards the light, h implied by wi). Append f_r, f_g, f_b computed by your renderer
    /// and give the file to `hairmath check`.
    Cases(kit::CasesArgs),
    /// Check another renderer's values against hairmath's model (the test kit): reads the
    /// CSV of `hairmath cases` with f_r, f_g, f_b appended (the renderer's f in the meaning
    /// of --convention) on stdin, and reports the worst and mean relative error (relative to
    /// the value + 1e-6 of the set's largest) against the model in f64, the worst rows with
    /// their inputs, and PASS or FAIL at --tolerance (exit status 1 on FAIL). Model flags as
    /// for `eval`; inputs not given take the default hair's values (as `render` does).
    Check(kit::CheckArgs),
}

/// Why a subcommand failed.
#[derive(Debug)]
pub enum CliError {
    /// A problem with the input on a given line (1-based; the header is line 1).
    Input {
        /// The line number.
        line: usize,
        /// What is wrong with it.
        message: String,
    },
    /// Invalid parameters.
    Params(hairmath::ParamError),
    /// A lookup table could not be built or written.
    Lut(hairmath::lut::LutError),
    /// A fit failed.
    Fit(hairmath::fit::FitError),
    /// `--model` names no registered model (clap's value check makes this unreachable from
    /// the command line).
    UnknownModel(String),
    /// The chosen model needs a flag that was not given.
    MissingFlag {
        /// The model.
        model: &'static str,
        /// The flag (or the alternatives).
        flag: String,
    },
    /// Flags given that the chosen model does not take.
    FlagsNotForModel {
        /// The flags, with every other flag of exactly the same models.
        flags: Vec<String>,
        /// The models that take them.
        models: Vec<String>,
    },
    /// The model comparison failed.
    Comparison(hairmath::fit::ComparisonError),
    /// A shader could not be made.
    Shader(String),
    /// A scene could not be read or planned.
    Plan(String),
    /// A `.hair` file could not be read or written, or a bake's output could not be written.
    Strands(String),
    /// `hairmath check`: a row's error is above the tolerance.
    CheckFailed {
        /// The largest row error.
        max_rel_error: f64,
        /// The tolerance.
        tolerance: f64,
    },
    /// Reading or writing a file (or standard output) failed.
    Io {
        /// The file, or "standard output".
        path: String,
        /// What failed.
        error: io::Error,
    },
}

impl CliError {
    /// An input error on `line`.
    pub fn input(line: usize, message: impl Into<String>) -> Self {
        CliError::Input {
            line,
            message: message.into(),
        }
    }

    /// An I/O error on the file (or folder) `path`.
    pub fn io(path: &Path, error: io::Error) -> Self {
        CliError::Io {
            path: path.display().to_string(),
            error,
        }
    }

    /// An I/O error writing standard output (a closed pipe among them, which [`main`] ends
    /// quietly).
    pub fn stdout(error: io::Error) -> Self {
        CliError::Io {
            path: STDOUT.to_string(),
            error,
        }
    }
}

/// How errors name standard output.
const STDOUT: &str = "standard output";

/// Runs `print` on buffered standard output and flushes it, also when `print` fails (so that
/// what was written before an error reaches the reader); write errors name standard output.
pub fn with_stdout(
    print: impl FnOnce(&mut BufWriter<io::StdoutLock<'static>>) -> Result<(), CliError>,
) -> Result<(), CliError> {
    let mut out = BufWriter::new(io::stdout().lock());
    let result = print(&mut out);
    let flushed = out.flush();
    result?;
    flushed.map_err(CliError::stdout)
}

/// Writes `bytes` to the file `path`, naming it in the error.
pub fn write_file(path: &Path, bytes: impl AsRef<[u8]>) -> Result<(), CliError> {
    std::fs::write(path, bytes).map_err(|e| CliError::io(path, e))
}

/// Creates the folder `path` and its parents, naming it in the error.
pub fn create_dir(path: &Path) -> Result<(), CliError> {
    std::fs::create_dir_all(path).map_err(|e| CliError::io(path, e))
}

impl From<hairmath::csv::CsvError> for CliError {
    fn from(e: hairmath::csv::CsvError) -> Self {
        match e {
            hairmath::csv::CsvError::Input { line, message } => CliError::Input { line, message },
            hairmath::csv::CsvError::Write(e) => CliError::stdout(e),
            other => CliError::input(0, other.to_string()),
        }
    }
}

impl fmt::Display for CliError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            CliError::Input { line, message } => write!(f, "line {line}: {message}"),
            CliError::CheckFailed {
                max_rel_error,
                tolerance,
            } => write!(
                f,
                "check failed: worst relative error {max_rel_error:e} above the tolerance \
                 {tolerance:e}"
            ),
            CliError::Params(e) => write!(f, "invalid parameters: {e}"),
            CliError::Lut(e) => write!(f, "lookup table: {e}"),
            CliError::Fit(e) => write!(f, "{e}"),
            CliError::UnknownModel(name) => write!(f, "no model is called {name:?}"),
            CliError::MissingFlag { model, flag } => {
                write!(f, "--model {model} requires {flag}")
            }
            CliError::FlagsNotForModel { flags, models } => {
                let verb = if flags.len() == 1 { "applies" } else { "apply" };
                write!(
                    f,
                    "{} {verb} only to --model {}",
                    flags.join(" and "),
                    models.join(", ")
                )
            }
            CliError::Comparison(e) => write!(f, "{e}"),
            CliError::Shader(e) | CliError::Plan(e) | CliError::Strands(e) => write!(f, "{e}"),
            CliError::Io { path, error } => write!(f, "I/O error on {path}: {error}"),
        }
    }
}

impl From<hairmath::ParamError> for CliError {
    fn from(e: hairmath::ParamError) -> Self {
        CliError::Params(e)
    }
}

impl From<hairmath::lut::LutError> for CliError {
    fn from(e: hairmath::lut::LutError) -> Self {
        match e {
            hairmath::lut::LutError::Param(p) => CliError::Params(p),
            other => CliError::Lut(other),
        }
    }
}

impl From<hairmath::fit::FitError> for CliError {
    fn from(e: hairmath::fit::FitError) -> Self {
        match e {
            hairmath::fit::FitError::Param(p) => CliError::Params(p),
            other => CliError::Fit(other),
        }
    }
}

impl From<hairmath::fit::ComparisonError> for CliError {
    fn from(e: hairmath::fit::ComparisonError) -> Self {
        match e {
            hairmath::fit::ComparisonError::Param(p) => CliError::Params(p),
            hairmath::fit::ComparisonError::Fit(f) => f.into(),
            other => CliError::Comparison(other),
        }
    }
}

impl From<hairmath::shader::ModelShaderError> for CliError {
    fn from(e: hairmath::shader::ModelShaderError) -> Self {
        CliError::Shader(e.to_string())
    }
}

impl From<hairmath::shader::ShaderError> for CliError {
    fn from(e: hairmath::shader::ShaderError) -> Self {
        CliError::Shader(e.to_string())
    }
}

/// The command line, every subcommand taking negative numbers as option values.
fn parse() -> Cli {
    let command = Cli::command().mut_subcommands(|c| c.allow_negative_numbers(true));
    let matches = command.get_matches();
    Cli::from_arg_matches(&matches).unwrap_or_else(|e| e.exit())
}

fn main() -> ExitCode {
    let cli = parse();
    let result = match &cli.command {
        Command::Eval(args) => eval::run(args),
        Command::Report(args) => report::run(args),
        Command::Models(args) => models::run(args),
        Command::Lut(args) => lut::run(args),
        Command::Fit(args) => fit::run(args),
        Command::Wigner3j(args) => sh::run_wigner3j(args),
        Command::Gaunt(args) => sh::run_gaunt(args),
        Command::Shader(args) => shader::run(args),
        Command::Plan(args) => plan::run(args),
        Command::Groom(args) => strands::run_groom(args),
        Command::Bake(args) => strands::run_bake(args),
        Command::RenderGerard(args) => render::run(args),
        Command::Render(args) => swatch::run(args),
        Command::Plot(args) => plot::run(args),
        Command::Cases(args) => kit::run_cases(args),
        Command::Check(args) => kit::run_check(args),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        // The reader of our output went away (`hairmath eval ... | head`): stop quietly.
        Err(CliError::Io { path, error })
            if path == STDOUT && error.kind() == io::ErrorKind::BrokenPipe =>
        {
            ExitCode::SUCCESS
        }
        // The verdict is on stdout; status 1 tells a script the check failed.
        Err(e @ CliError::CheckFailed { .. }) => {
            let _ = writeln!(io::stderr(), "hairmath: {e}");
            ExitCode::from(1)
        }
        Err(e) => {
            // Nothing more to do if stderr cannot be written either.
            let _ = writeln!(io::stderr(), "hairmath: error: {e}");
            ExitCode::from(2)
        }
    }
}
