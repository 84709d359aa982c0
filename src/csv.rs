//! The simple CSV of the command line's filters (`hairmath eval`, `wigner3j`, `gaunt`): a
//! header row naming the columns, one row per line, a value appended to each row. In the
//! library so that every front end (and the fuzz tests) read it the same way.
//!
//! **Format.** The first line is a header; the columns a filter needs are found by name, in
//! any order, and every other column is passed through unchanged, in place. Fields are split
//! on every comma and trimmed of whitespace; quoting is not supported, so no field may contain
//! a comma. Lines end with LF, CRLF or a lone CR; blank lines are skipped. A UTF-8 byte-order
//! mark before the header is dropped (spreadsheet programs write one). Every line must be
//! valid UTF-8 and at most [`MAX_LINE_BYTES`] long, so memory stays flat in the input's size:
//! one line, and the output is written as each row is read.
//!
//! **Errors.** The first bad line ends the filter with [`CsvError::Input`] naming the line (the
//! header is line 1); the rows before it have been written.
//!
//! **Numbers** are written by [`format_number`]: the shorter of Rust's shortest round-trip
//! decimal and exponent forms, so parsing the text gives back the exact `f64`.

use crate::bcsdf::{Bcsdf, Query};
use crate::geometry::V3;
use crate::sh::{gaunt_complex, gaunt_real, wigner_3j, HalfInt};
use std::io::{self, BufRead, Write};

/// The longest line accepted, in bytes (1 MiB): far more than any row of numbers needs.
pub const MAX_LINE_BYTES: usize = 1 << 20;

/// Why a CSV filter stopped.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum CsvError {
    /// A problem with the input on a given line (1-based; the header is line 1), reading it
    /// included.
    #[error("line {line}: {message}")]
    Input {
        /// The line number.
        line: usize,
        /// What is wrong with it.
        message: String,
    },
    /// Writing the output failed.
    #[error("cannot write the output: {0}")]
    Write(#[source] io::Error),
}

impl CsvError {
    fn input(line: usize, message: impl Into<String>) -> Self {
        CsvError::Input {
            line,
            message: message.into(),
        }
    }
}

/// Reads lines of at most [`MAX_LINE_BYTES`] bytes, ended by LF, CRLF or a lone CR.
struct Lines<R> {
    input: R,
    bytes: Vec<u8>,
    number: usize,
}

impl<R: BufRead> Lines<R> {
    fn new(input: R) -> Self {
        Lines {
            input,
            bytes: Vec::new(),
            number: 0,
        }
    }

    /// The next line (without its ending) and its number, `None` at the end of the input.
    fn next_line(&mut self) -> Result<Option<(usize, &str)>, CsvError> {
        self.number += 1;
        let number = self.number;
        let read_error = |e: io::Error| CsvError::input(number, format!("cannot read input: {e}"));
        self.bytes.clear();
        let mut ended = false;
        let mut any = false;
        while !ended {
            let available = self.input.fill_buf().map_err(read_error)?;
            if available.is_empty() {
                break;
            }
            any = true;
            let end = available.iter().position(|&b| b == b'\n' || b == b'\r');
            let take = end.unwrap_or(available.len());
            if self.bytes.len() + take > MAX_LINE_BYTES {
                return Err(CsvError::input(
                    number,
                    format!("the line is longer than {MAX_LINE_BYTES} bytes (the limit of a line)"),
                ));
            }
            self.bytes.extend_from_slice(&available[..take]);
            let carriage_return = end.is_some_and(|e| available[e] == b'\r');
            ended = end.is_some();
            self.input.consume(take + usize::from(ended));
            if carriage_return {
                let next = self.input.fill_buf().map_err(read_error)?;
                if next.first() == Some(&b'\n') {
                    self.input.consume(1);
                }
            }
        }
        if !any {
            return Ok(None);
        }
        let text = std::str::from_utf8(&self.bytes)
            .map_err(|e| CsvError::input(number, format!("not valid UTF-8 ({e})")))?;
        Ok(Some((number, text)))
    }
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

/// The CSV loop every filter shares: reads a header naming (at least) the columns `names`,
/// writes it with `,{appended}`; then for each non-blank row calls `row` with the fields of
/// `names` (in that order) and writes the row with `,{result}` appended.
///
/// # Errors
/// [`CsvError::Input`] for the first bad line (an empty input, a header without the columns,
/// a row with another number of fields, a line too long or not UTF-8, or `row`'s message), or
/// [`CsvError::Write`].
pub fn filter(
    input: impl BufRead,
    out: &mut dyn Write,
    names: &[&str],
    appended: &str,
    mut row: impl FnMut(&[&str]) -> Result<String, String>,
) -> Result<(), CsvError> {
    let mut lines = Lines::new(input);
    let Some((_, header)) = lines.next_line()? else {
        return Err(CsvError::input(1, "empty input: expected a header row"));
    };
    let header = header
        .strip_prefix('\u{feff}')
        .unwrap_or(header)
        .to_string();
    let columns = Columns::from_header(&header, names).map_err(|m| CsvError::input(1, m))?;
    writeln!(out, "{header},{appended}").map_err(CsvError::Write)?;
    while let Some((number, line)) = lines.next_line()? {
        if line.trim().is_empty() {
            continue;
        }
        let result = columns
            .select(line)
            .and_then(|fields| row(&fields))
            .map_err(|m| CsvError::input(number, m))?;
        writeln!(out, "{line},{result}").map_err(CsvError::Write)?;
    }
    Ok(())
}

/// Reads a CSV with a header naming (at least) the columns `names` and calls `row` with the
/// line number and the fields of `names` (in that order) of every non-blank row: the reading
/// half of [`filter`], for front ends that report on all the rows at the end.
///
/// # Errors
/// [`CsvError::Input`] for the first bad line, as [`filter`].
pub fn read_rows(
    input: impl BufRead,
    names: &[&str],
    mut row: impl FnMut(usize, &[&str]) -> Result<(), String>,
) -> Result<(), CsvError> {
    let mut lines = Lines::new(input);
    let Some((_, header)) = lines.next_line()? else {
        return Err(CsvError::input(1, "empty input: expected a header row"));
    };
    let header = header.strip_prefix('\u{feff}').unwrap_or(header);
    let columns = Columns::from_header(header, names).map_err(|m| CsvError::input(1, m))?;
    while let Some((number, line)) = lines.next_line()? {
        if line.trim().is_empty() {
            continue;
        }
        columns
            .select(line)
            .and_then(|fields| row(number, &fields))
            .map_err(|m| CsvError::input(number, m))?;
    }
    Ok(())
}

/// `value` as the shorter of Rust's shortest round-trip forms, decimal (`{}`) and exponent
/// (`{:e}`), the decimal one on a tie; any zero is `0`. `1e308` rather than 309 digits,
/// `1.5e-90` rather than 90 zeros, `0.25` and `-0.5773502691896257` as they are. Parsing the
/// text gives back `value` exactly.
pub fn format_number(value: f64) -> String {
    if value == 0.0 {
        return "0".to_string();
    }
    let decimal = format!("{value}");
    let exponent = format!("{value:e}");
    if exponent.len() < decimal.len() {
        exponent
    } else {
        decimal
    }
}

/// The columns [`eval_filter`] reads for a near-field model; a far-field model reads all but
/// the last (`h`, then 0).
pub const EVAL_COLUMNS: [&str; 7] = ["wi_x", "wi_y", "wi_z", "wo_x", "wo_y", "wo_z", "h"];

/// `hairmath eval`: S of `model` for every row (columns [`EVAL_COLUMNS`]; `h` only for
/// near-field models, [`Bcsdf::uses_offset`]), appended as `f_r,f_g,f_b` ([`format_number`]).
/// Each row is validated by [`Query::checked`]: finite numbers, directions of unit length
/// within [`crate::bcsdf::UNIT_TOLERANCE`] (normalised), `h` in [-1, 1].
///
/// # Errors
/// As [`filter`].
pub fn eval_filter(
    model: &dyn Bcsdf<f64>,
    input: impl BufRead,
    out: &mut dyn Write,
) -> Result<(), CsvError> {
    let columns = if model.uses_offset() {
        &EVAL_COLUMNS[..]
    } else {
        &EVAL_COLUMNS[..6]
    };
    filter(input, out, columns, "f_r,f_g,f_b", |fields| {
        let [r, g, b] = model.eval(&eval_query(fields)?);
        Ok(format!(
            "{},{},{}",
            format_number(r),
            format_number(g),
            format_number(b)
        ))
    })
}

/// The query of one row's fields of [`EVAL_COLUMNS`] (or of all but `h`, which is then 0).
fn eval_query(fields: &[&str]) -> Result<Query<f64>, String> {
    let mut v = [0.0; EVAL_COLUMNS.len()];
    for ((slot, field), name) in v.iter_mut().zip(fields).zip(EVAL_COLUMNS) {
        *slot = finite_number(name, field)?;
    }
    let wi = V3::new(v[0], v[1], v[2]);
    let wo = V3::new(v[3], v[4], v[5]);
    Query::checked(wi, wo, v[6]).map_err(|e| e.to_string())
}

/// A finite number from the field of column `name`.
///
/// # Errors
/// A message naming the column, for a field that is not a finite number.
pub fn finite_number(name: &str, field: &str) -> Result<f64, String> {
    let value: f64 = field
        .parse()
        .map_err(|_| format!("column {name}: {field:?} is not a number"))?;
    if value.is_finite() {
        Ok(value)
    } else {
        Err(format!("column {name}: {field:?} is not a finite number"))
    }
}

/// The columns of [`wigner3j_filter`].
pub const WIGNER_COLUMNS: [&str; 6] = ["j1", "j2", "j3", "m1", "m2", "m3"];

/// `hairmath wigner3j`: the 3-j symbol of every row (columns [`WIGNER_COLUMNS`], integers or
/// half-integers as [`HalfInt`] parses them), appended as `value` ([`format_number`]; the
/// symbol correctly rounded, selection-rule zeros `0`). One row costs at most about 0.1 s
/// (j = 10,000, the largest [`wigner_3j`] accepts).
///
/// # Errors
/// As [`filter`].
pub fn wigner3j_filter(input: impl BufRead, out: &mut dyn Write) -> Result<(), CsvError> {
    filter(input, out, &WIGNER_COLUMNS, "value", wigner_row)
}

/// The 3-j symbol of the fields `j1, j2, j3, m1, m2, m3`, formatted.
fn wigner_row(fields: &[&str]) -> Result<String, String> {
    let mut v = [HalfInt::default(); 6];
    for ((slot, field), name) in v.iter_mut().zip(fields).zip(WIGNER_COLUMNS) {
        *slot = field.parse().map_err(|e| format!("column {name}: {e}"))?;
    }
    let [j1, j2, j3, m1, m2, m3] = v;
    let value = wigner_3j(j1, j2, j3, m1, m2, m3)
        .map_err(|e| format!("({j1} {j2} {j3}; {m1} {m2} {m3}): {e}"))?;
    Ok(format_number(value))
}

/// The columns of [`gaunt_filter`].
pub const GAUNT_COLUMNS: [&str; 6] = ["l1", "m1", "l2", "m2", "l3", "m3"];

/// `hairmath gaunt`: the Gaunt coefficient of every row (columns [`GAUNT_COLUMNS`],
/// integers), complex ([`gaunt_complex`]) or, with `real`, of the crate's real SH
/// ([`gaunt_real`]), appended as `value` ([`format_number`]).
///
/// # Errors
/// As [`filter`].
pub fn gaunt_filter(input: impl BufRead, out: &mut dyn Write, real: bool) -> Result<(), CsvError> {
    filter(input, out, &GAUNT_COLUMNS, "value", |f| gaunt_row(f, real))
}

/// The Gaunt coefficient of the fields `l1, m1, l2, m2, l3, m3`, formatted.
fn gaunt_row(fields: &[&str], real: bool) -> Result<String, String> {
    let mut l = [0_u32; 3];
    let mut m = [0_i32; 3];
    for (k, (l, m)) in l.iter_mut().zip(&mut m).enumerate() {
        *l = parse_int(
            GAUNT_COLUMNS[2 * k],
            fields[2 * k],
            "a non-negative integer",
        )?;
        *m = parse_int(GAUNT_COLUMNS[2 * k + 1], fields[2 * k + 1], "an integer")?;
    }
    let gaunt = if real { gaunt_real } else { gaunt_complex };
    let value = gaunt(l[0], m[0], l[1], m[1], l[2], m[2]).map_err(|e| {
        format!(
            "(l, m) = ({}, {}), ({}, {}), ({}, {}): {e}",
            l[0], m[0], l[1], m[1], l[2], m[2]
        )
    })?;
    Ok(format_number(value))
}

/// The field of column `name` as an integer of type `T`, or an error saying it must be `what`.
fn parse_int<T: std::str::FromStr>(name: &str, field: &str, what: &str) -> Result<T, String> {
    field
        .parse()
        .map_err(|_| format!("column {name}: {field:?} is not {what}"))
}

#[cfg(test)]
mod tests {
    use super::*;

    use crate::bcsdf::ChiangHair;
    use crate::params::HairParams;

    fn run_eval(input: &str) -> (String, Result<(), CsvError>) {
        let model = ChiangHair::<f64>::new(&HairParams::default());
        let mut out = Vec::new();
        let result = eval_filter(&model, input.as_bytes(), &mut out);
        (String::from_utf8(out).unwrap(), result)
    }

    #[test]
    fn columns_in_any_order_with_pass_through() {
        let (out, result) = run_eval("id, h,wo_z,wo_y,wo_x,wi_z,wi_y,wi_x\n7,0.1,0,1,0,0,0,1\n\n");
        assert!(result.is_ok());
        let lines: Vec<&str> = out.lines().collect();
        assert_eq!(lines[0], "id, h,wo_z,wo_y,wo_x,wi_z,wi_y,wi_x,f_r,f_g,f_b");
        assert!(lines[1].starts_with("7,0.1,0,1,0,0,0,1,"));
        assert_eq!(lines.len(), 2);
    }

    #[test]
    fn errors_name_the_line() {
        let (out, result) =
            run_eval("wi_x,wi_y,wi_z,wo_x,wo_y,wo_z,h\n0,1,0,0,1,0,0\n0,1,0,0,2,0,0\n");
        assert_eq!(out.lines().count(), 2);
        let message = result.unwrap_err().to_string();
        assert!(message.starts_with("line 3: wo = "), "{message}");
        let (_, result) = run_eval("wi_x,wi_y,wo_x,wo_y,wo_z,h\n");
        let message = result.unwrap_err().to_string();
        assert!(
            message.contains("line 1") && message.contains("wi_z"),
            "{message}"
        );
    }

    #[test]
    fn line_endings_byte_order_mark_and_long_lines() {
        let header = "wi_x,wi_y,wi_z,wo_x,wo_y,wo_z,h";
        let row = "0,1,0,0,1,0,0";
        let lf = run_eval(&format!("{header}\n{row}\n{row}"));
        for input in [
            format!("\u{feff}{header}\n{row}\n{row}\n"),
            format!("{header}\r\n{row}\r\n{row}\r\n"),
            format!("{header}\r{row}\r{row}\r"),
            format!("{header}\r{row}\n{row}"),
        ] {
            let got = run_eval(&input);
            assert!(got.1.is_ok(), "{input:?}: {:?}", got.1);
            assert_eq!(got.0, lf.0, "{input:?}");
        }
        let long = format!("{header}\n{}\n", "1".repeat(MAX_LINE_BYTES + 1));
        let message = run_eval(&long).1.unwrap_err().to_string();
        assert!(
            message.starts_with("line 2: the line is longer than 1048576"),
            "{message}"
        );
        let model = ChiangHair::<f64>::new(&HairParams::default());
        let invalid = eval_filter(&model, &b"wi_x,\xff\n"[..], &mut Vec::new());
        let message = invalid.unwrap_err().to_string();
        assert!(message.starts_with("line 1: not valid UTF-8"), "{message}");
    }

    #[test]
    fn rows_give_values_and_errors() {
        // -1/sqrt(3), correctly rounded (1.0 / 3f64.sqrt() rounds twice and is one ulp off).
        assert_eq!(
            wigner_row(&["1", "1", "0", "0", "0", "0"]).unwrap(),
            "-0.5773502691896257"
        );
        assert_eq!(wigner_row(&["1", "1", "5", "0", "0", "0"]).unwrap(), "0");
        assert!(wigner_row(&["1", "x", "0", "0", "0", "0"])
            .unwrap_err()
            .starts_with("column j2: "));
        let y00: f64 = gaunt_row(&["0", "0", "0", "0", "0", "0"], true)
            .unwrap()
            .parse()
            .unwrap();
        assert!((y00 * (4.0 * std::f64::consts::PI).sqrt() - 1.0).abs() < 1e-15);
        assert!(gaunt_row(&["-1", "0", "1", "0", "0", "0"], false)
            .unwrap_err()
            .contains("column l1"));
    }

    #[test]
    fn numbers_print_in_the_shorter_exact_form() {
        for (v, text) in [
            (1e308, "1e308"),
            (1.5e-90, "1.5e-90"),
            (0.25, "0.25"),
            (-0.5773502691896257, "-0.5773502691896257"),
            (0.0, "0"),
            (-0.0, "0"),
            (123456.0, "123456"),
            (1e21, "1e21"),
        ] {
            assert_eq!(format_number(v), text);
            assert_eq!(text.parse::<f64>().unwrap(), v);
        }
    }
}
