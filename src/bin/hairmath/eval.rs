//! `hairmath eval`: evaluate a registered model on rows of a simple CSV read from stdin.

use crate::flags::{model_names, ModelFlags};
use crate::CliError;
use clap::builder::PossibleValuesParser;
use clap::Args;
use hairmath::bcsdf::{Bcsdf, Query};
use hairmath::geometry::V3;
use hairmath::registry::find_model;
use std::io::{self, BufRead, BufWriter, Write};

/// Largest accepted deviation of a direction's length from 1.
const UNIT_TOLERANCE: f64 = 1e-3;

/// The columns the near-field models need, in the order the evaluation uses them; the
/// far-field models need all but the last (`h`).
const REQUIRED: [&str; 7] = ["wi_x", "wi_y", "wi_z", "wo_x", "wo_y", "wo_z", "h"];

/// Arguments of `hairmath eval`.
#[derive(Args, Debug)]
pub struct EvalArgs {
    /// The scattering model (`hairmath::registry::MODELS`).
    #[arg(long, default_value = "chiang", value_parser = PossibleValuesParser::new(model_names()))]
    model: String,
    /// The models' inputs.
    #[command(flatten)]
    flags: ModelFlags,
}

impl EvalArgs {
    /// Validates the flags and builds the model.
    fn model(&self) -> Result<Box<dyn Bcsdf<f64>>, CliError> {
        let entry =
            find_model(&self.model).ok_or_else(|| CliError::UnknownModel(self.model.clone()))?;
        let values = self.flags.values_for(entry)?;
        Ok((entry.build)(&values)?)
    }
}

/// The input columns `model` needs, in the order of [`Query`]'s fields.
fn columns(model: &dyn Bcsdf<f64>) -> &'static [&'static str] {
    if model.uses_offset() {
        &REQUIRED
    } else {
        &REQUIRED[..6]
    }
}

/// Runs `hairmath eval`: stdin to stdout, flushing what was written even on error.
pub fn run(args: &EvalArgs) -> Result<(), CliError> {
    let model = args.model()?;
    run_csv(|input, out| process(model.as_ref(), input, out))
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
fn process(
    model: &dyn Bcsdf<f64>,
    input: impl BufRead,
    out: &mut dyn Write,
) -> Result<(), CliError> {
    filter_csv(input, out, columns(model), "f_r,f_g,f_b", |fields| {
        let [r, g, b] = model.eval(&parse_row(fields)?);
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

/// Parses and validates the fields of [`REQUIRED`] (or of all but `h`, which is then 0) of one
/// row.
fn parse_row(fields: &[&str]) -> Result<Query<f64>, String> {
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
    Ok(Query::new(wi, wo, h))
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

    use hairmath::bcsdf::ChiangHair;
    use hairmath::params::HairParams;

    fn model() -> ChiangHair<f64> {
        ChiangHair::new(&HairParams::default())
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
}
