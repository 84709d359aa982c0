//! `hairmath eval`: evaluate a model on rows of a simple CSV read from stdin.

use crate::CliError;
use clap::{ArgGroup, Args, ValueEnum};
use hairmath::absorption::{sigma_a_from_color, sigma_a_from_melanin, Rgb};
use hairmath::bcsdf::{ChiangFarField, ChiangHair, ChiangParams, FarFieldRule};
use hairmath::geometry::V3;
use std::io::{self, BufRead, BufWriter, Write};

/// Largest accepted deviation of a direction's length from 1.
const UNIT_TOLERANCE: f64 = 1e-3;

/// The columns the near-field models need, in the order the evaluation uses them; the
/// far-field model needs all but the last (`h`).
const REQUIRED: [&str; 7] = ["wi_x", "wi_y", "wi_z", "wo_x", "wo_y", "wo_z", "h"];

/// Default node count of `--model chiang-far`.
const DEFAULT_NODES: usize = 64;

/// Relative tolerance of `--model chiang-far --reference`.
const REFERENCE_REL_TOL: f64 = 1e-9;

/// The scattering models `eval` knows.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum Model {
    /// Chiang et al. 2016 (pbrt-v4 `HairBxDF`), the near-field reference.
    Chiang,
    /// The far field of Chiang et al. 2016: S(wi, wo) averaged over h uniform in [-1, 1]
    /// (no `h` column needed; one, if present, is passed through and ignored). Integrated
    /// over h with a fixed Gauss-Legendre rule of --nodes nodes, or with the adaptive
    /// reference integrator (--reference, relative tolerance 1e-9, about 0.2 ms per row).
    ChiangFar,
}

/// Arguments of `hairmath eval`.
#[derive(Args, Debug)]
#[command(group(
    ArgGroup::new("absorption")
        .required(true)
        .args(["sigma_a", "melanin", "color"])
))]
pub struct EvalArgs {
    /// The scattering model.
    #[arg(long, value_enum, default_value_t = Model::Chiang)]
    model: Model,
    /// Longitudinal roughness beta_m, in (0, 1].
    #[arg(long, value_name = "B", allow_hyphen_values = true)]
    beta_m: f64,
    /// Azimuthal roughness beta_n, in (0, 1].
    #[arg(long, value_name = "B", allow_hyphen_values = true)]
    beta_n: f64,
    /// Cuticle tilt alpha in degrees.
    #[arg(
        long,
        value_name = "A",
        default_value_t = 2.0,
        allow_hyphen_values = true
    )]
    alpha_deg: f64,
    /// Relative index of refraction eta, > 1.
    #[arg(
        long,
        value_name = "E",
        default_value_t = 1.55,
        allow_hyphen_values = true
    )]
    eta: f64,
    /// Absorption per unit fibre radius, linear RGB.
    #[arg(long, value_name = "R,G,B", value_parser = parse_floats::<3>, allow_hyphen_values = true)]
    sigma_a: Option<[f64; 3]>,
    /// Eumelanin and pheomelanin concentrations (sigma_a = eu * [0.419, 0.697, 1.37] +
    /// pheo * [0.187, 0.4, 1.05]).
    #[arg(long, value_name = "EU,PHEO", value_parser = parse_floats::<2>, allow_hyphen_values = true)]
    melanin: Option<[f64; 2]>,
    /// Approximate colour of a multiply-scattering hair volume, linear RGB in (0, 1]
    /// (inverted to sigma_a with beta_n, Chiang et al. 2016 section 4.2).
    #[arg(long, value_name = "R,G,B", value_parser = parse_floats::<3>, allow_hyphen_values = true)]
    color: Option<[f64; 3]>,
    /// chiang-far only: node count (1..=512) of the fixed rule over h [default: 64].
    #[arg(long, value_name = "N", conflicts_with = "reference")]
    nodes: Option<usize>,
    /// chiang-far only: integrate over h with the adaptive reference integrator (relative
    /// tolerance 1e-9) instead of the fixed rule.
    #[arg(long)]
    reference: bool,
}

/// Parses exactly `N` comma-separated numbers (clap value parser).
fn parse_floats<const N: usize>(text: &str) -> Result<[f64; N], String> {
    let fields: Vec<&str> = text.split(',').map(str::trim).collect();
    if fields.len() != N {
        return Err(format!(
            "expected {N} comma-separated numbers, found {}",
            fields.len()
        ));
    }
    let mut out = [0.0; N];
    for (slot, field) in out.iter_mut().zip(&fields) {
        *slot = field
            .parse()
            .map_err(|_| format!("{field:?} is not a number"))?;
    }
    Ok(out)
}

/// A model ready to evaluate (one variant per [`Model`] and integrator).
enum Evaluator {
    Chiang(ChiangHair<f64>),
    ChiangFar(ChiangFarField<f64>),
    ChiangFarReference(ChiangHair<f64>),
}

impl Evaluator {
    /// The input columns this model needs, in the order of [`Evaluator::eval`]'s arguments.
    fn columns(&self) -> &'static [&'static str] {
        match self {
            Evaluator::Chiang(_) => &REQUIRED,
            Evaluator::ChiangFar(_) | Evaluator::ChiangFarReference(_) => &REQUIRED[..6],
        }
    }

    /// `S(wi, wo, h)` per channel, no cosine factor (the far-field models ignore `h`).
    fn eval(&self, wi: V3<f64>, wo: V3<f64>, h: f64) -> [f64; 3] {
        match self {
            Evaluator::Chiang(hair) => hair.eval(wi, wo, h),
            Evaluator::ChiangFar(far) => far.eval(wi, wo),
            Evaluator::ChiangFarReference(hair) => {
                hair.far_field_reference(wi, wo, REFERENCE_REL_TOL).value
            }
        }
    }
}

impl EvalArgs {
    /// sigma_a from whichever of `--sigma-a`, `--melanin`, `--color` was given.
    fn sigma_a(&self) -> Result<Rgb, CliError> {
        let params = |e: hairmath::ParamError| CliError::Params(e.to_string());
        match (self.sigma_a, self.melanin, self.color) {
            (Some(s), _, _) => Ok(s),
            (_, Some([eu, pheo]), _) => sigma_a_from_melanin(eu, pheo).map_err(params),
            (_, _, Some(c)) => sigma_a_from_color(c, self.beta_n).map_err(params),
            // clap's ArgGroup makes this unreachable; report it rather than panic.
            _ => Err(CliError::Params(
                "one of --sigma-a, --melanin, --color is required".into(),
            )),
        }
    }

    /// Validates the parameters and builds the model.
    fn evaluator(&self) -> Result<Evaluator, CliError> {
        let sigma_a = self.sigma_a()?;
        let params = ChiangParams::new(
            self.beta_m,
            self.beta_n,
            self.alpha_deg.to_radians(),
            self.eta,
            sigma_a,
        )
        .map_err(|e| CliError::Params(e.to_string()))?;
        let hair = ChiangHair::new(&params);
        match self.model {
            Model::Chiang if self.nodes.is_some() || self.reference => Err(CliError::Params(
                "--nodes and --reference apply only to --model chiang-far".into(),
            )),
            Model::Chiang => Ok(Evaluator::Chiang(hair)),
            Model::ChiangFar if self.reference => Ok(Evaluator::ChiangFarReference(hair)),
            Model::ChiangFar => {
                let rule = FarFieldRule::gauss_legendre(self.nodes.unwrap_or(DEFAULT_NODES))
                    .map_err(|e| CliError::Params(e.to_string()))?;
                Ok(Evaluator::ChiangFar(ChiangFarField::new(hair, &rule)))
            }
        }
    }
}

/// Runs `hairmath eval`: stdin to stdout, flushing what was written even on error.
pub fn run(args: &EvalArgs) -> Result<(), CliError> {
    let model = args.evaluator()?;
    run_csv(|input, out| process(&model, input, out))
}

/// Runs a CSV filter `process` from stdin to stdout, flushing what was written even when it
/// fails (so the rows before a bad one reach the reader).
pub(crate) fn run_csv(
    process: impl FnOnce(io::StdinLock<'static>, &mut dyn Write) -> Result<(), CliError>,
) -> Result<(), CliError> {
    let mut out = BufWriter::new(io::stdout().lock());
    let result = process(io::stdin().lock(), &mut out);
    let flushed = out.flush();
    result?;
    flushed.map_err(CliError::Io)
}

/// Reads the header and the rows from `input`, writes the extended CSV to `out`.
fn process(model: &Evaluator, input: impl BufRead, out: &mut dyn Write) -> Result<(), CliError> {
    filter_csv(input, out, model.columns(), "f_r,f_g,f_b", |fields| {
        let row = parse_row(fields)?;
        let [r, g, b] = model.eval(row.wi, row.wo, row.h);
        Ok(format!("{r},{g},{b}"))
    })
}

/// The CSV loop shared by the subcommands: reads a header naming (at least) the columns
/// `names`, writes it with `,{appended}`; then for each non-blank row calls `row` with the
/// fields of `names` (in that order) and writes the row with `,{result}` appended. The first
/// error is returned with its line number (the header is line 1).
pub(crate) fn filter_csv(
    input: impl BufRead,
    out: &mut dyn Write,
    names: &[&str],
    appended: &str,
    mut row: impl FnMut(&[&str]) -> Result<String, String>,
) -> Result<(), CliError> {
    let mut lines = input.lines();
    let header = match lines.next() {
        None => return Err(CliError::input(1, "empty input: expected a header row")),
        Some(line) => line.map_err(|e| read_error(1, e))?,
    };
    let columns = Columns::from_header(&header, names).map_err(|m| CliError::input(1, m))?;
    writeln!(out, "{header},{appended}")?;
    for (index, line) in lines.enumerate() {
        let number = index + 2;
        let line = line.map_err(|e| read_error(number, e))?;
        if line.trim().is_empty() {
            continue;
        }
        let result = columns
            .select(&line)
            .and_then(|fields| row(&fields))
            .map_err(|m| CliError::input(number, m))?;
        writeln!(out, "{line},{result}")?;
    }
    Ok(())
}

/// A failed read, attributed to the line being read.
fn read_error(line: usize, e: io::Error) -> CliError {
    CliError::input(line, format!("cannot read input: {e}"))
}

/// Where the required columns are in the header.
struct Columns {
    /// Number of fields in the header (every row must have as many).
    count: usize,
    /// Field index of each required name, in the order the names were given.
    index: Vec<usize>,
}

/// One validated input row: unit directions and the offset (0 when not read).
struct Row {
    wi: V3<f64>,
    wo: V3<f64>,
    h: f64,
}

impl Columns {
    /// Finds the columns `required` in `header`; names a missing or duplicated one.
    fn from_header(header: &str, required: &[&str]) -> Result<Self, String> {
        let names: Vec<&str> = header.split(',').map(str::trim).collect();
        let mut index = Vec::with_capacity(required.len());
        let mut missing = Vec::new();
        for &name in required {
            let mut found = names.iter().enumerate().filter(|(_, n)| **n == name);
            match (found.next(), found.next()) {
                (Some((i, _)), None) => index.push(i),
                (Some(_), Some(_)) => return Err(format!("column {name} appears more than once")),
                (None, _) => missing.push(name),
            }
        }
        if !missing.is_empty() {
            return Err(format!(
                "header is missing column(s) {} (required: {})",
                missing.join(", "),
                required.join(",")
            ));
        }
        Ok(Columns {
            count: names.len(),
            index,
        })
    }

    /// The trimmed fields of the required columns of `line`, in the order they were named;
    /// checks that the row has as many fields as the header.
    fn select<'a>(&self, line: &'a str) -> Result<Vec<&'a str>, String> {
        let fields: Vec<&str> = line.split(',').map(str::trim).collect();
        if fields.len() != self.count {
            return Err(format!(
                "expected {} fields as in the header, found {}",
                self.count,
                fields.len()
            ));
        }
        Ok(self.index.iter().map(|&i| fields[i]).collect())
    }
}

/// Parses and validates the fields of [`REQUIRED`] (or of all but `h`) of one row.
fn parse_row(fields: &[&str]) -> Result<Row, String> {
    let mut v = [0.0; REQUIRED.len()];
    for ((slot, field), name) in v.iter_mut().zip(fields).zip(REQUIRED) {
        *slot = parse_number(name, field)?;
    }
    let wi = unit("wi", V3::new(v[0], v[1], v[2]))?;
    let wo = unit("wo", V3::new(v[3], v[4], v[5]))?;
    let h = v[6];
    if !(-1.0..=1.0).contains(&h) {
        return Err(format!("h = {h} is outside [-1, 1]"));
    }
    Ok(Row { wi, wo, h })
}

/// A finite number from the field of column `name`.
fn parse_number(name: &str, field: &str) -> Result<f64, String> {
    let value: f64 = field
        .parse()
        .map_err(|_| format!("column {name}: {field:?} is not a number"))?;
    if value.is_finite() {
        Ok(value)
    } else {
        Err(format!("column {name}: {field:?} is not a finite number"))
    }
}

/// `w` normalised, if its length is 1 within [`UNIT_TOLERANCE`].
fn unit(name: &str, w: V3<f64>) -> Result<V3<f64>, String> {
    let length = w.dot(w).sqrt();
    if (length - 1.0).abs() <= UNIT_TOLERANCE {
        Ok(w.scale(1.0 / length))
    } else {
        Err(format!(
            "{name} = ({}, {}, {}) has length {length}; directions must be unit vectors \
             (within {UNIT_TOLERANCE})",
            w.x, w.y, w.z
        ))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn model() -> Evaluator {
        let p = ChiangParams::new(0.3, 0.3, 0.035, 1.55, [0.5, 0.8, 1.4]).unwrap();
        Evaluator::Chiang(ChiangHair::new(&p))
    }

    fn run_on(input: &str) -> (String, Result<(), CliError>) {
        let mut out = Vec::new();
        let result = process(&model(), input.as_bytes(), &mut out);
        (String::from_utf8(out).unwrap(), result)
    }

    #[test]
    fn columns_in_any_order_with_pass_through() {
        let (out, result) = run_on("id, h,wo_z,wo_y,wo_x,wi_z,wi_y,wi_x\n7,0.1,0,1,0,0,0,1\n\n");
        assert!(result.is_ok());
        let lines: Vec<&str> = out.lines().collect();
        assert_eq!(lines[0], "id, h,wo_z,wo_y,wo_x,wi_z,wi_y,wi_x,f_r,f_g,f_b");
        assert!(lines[1].starts_with("7,0.1,0,1,0,0,0,1,"));
        assert_eq!(lines.len(), 2);
    }

    #[test]
    fn errors_name_the_line() {
        let (out, result) =
            run_on("wi_x,wi_y,wi_z,wo_x,wo_y,wo_z,h\n0,1,0,0,1,0,0\n0,1,0,0,2,0,0\n");
        assert_eq!(out.lines().count(), 2);
        let message = result.unwrap_err().to_string();
        assert!(message.starts_with("line 3: wo = "), "{message}");
        let (_, result) = run_on("wi_x,wi_y,wo_x,wo_y,wo_z,h\n");
        let message = result.unwrap_err().to_string();
        assert!(
            message.contains("line 1") && message.contains("wi_z"),
            "{message}"
        );
    }

    #[test]
    fn value_parser_counts_fields() {
        assert_eq!(parse_floats::<2>("1, -2").unwrap(), [1.0, -2.0]);
        assert!(parse_floats::<3>("1,2").is_err());
        assert!(parse_floats::<3>("1,x,2").is_err());
    }
}
