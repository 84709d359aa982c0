//! `hairmath wigner3j` and `hairmath gaunt`: exact angular-momentum coefficients of the rows of
//! a CSV read from stdin.
//!
//! Both use the CSV conventions of `hairmath eval` (header row, columns found by name in any
//! order, other columns passed through, blank lines skipped, no quoting) and append one column,
//! `value`, printed in Rust's shortest round-trip form (`{}` of `f64`: `-0.5773502691896257`,
//! `0`, `1e-20`), so that parsing the text gives back the exact `f64`.

use crate::eval::{filter_csv, run_csv};
use crate::CliError;
use clap::Args;
use hairmath::sh::{gaunt_complex, gaunt_real};
use hairmath::sh::{wigner_3j, HalfInt};

/// Columns of `hairmath wigner3j`.
const WIGNER_COLUMNS: [&str; 6] = ["j1", "j2", "j3", "m1", "m2", "m3"];
/// Columns of `hairmath gaunt`.
const GAUNT_COLUMNS: [&str; 6] = ["l1", "m1", "l2", "m2", "l3", "m3"];

/// Arguments of `hairmath wigner3j` (none besides the input).
#[derive(Args, Debug)]
pub struct Wigner3jArgs {}

/// Arguments of `hairmath gaunt`.
#[derive(Args, Debug)]
pub struct GauntArgs {
    /// Real spherical harmonics of the crate's convention instead of complex ones
    /// (Condon-Shortley phase).
    #[arg(long)]
    real: bool,
}

/// Runs `hairmath wigner3j`.
pub fn run_wigner3j(_args: &Wigner3jArgs) -> Result<(), CliError> {
    run_csv(|input, out| filter_csv(input, out, &WIGNER_COLUMNS, "value", wigner_row))
}

/// Runs `hairmath gaunt`.
pub fn run_gaunt(args: &GauntArgs) -> Result<(), CliError> {
    let real = args.real;
    run_csv(|input, out| filter_csv(input, out, &GAUNT_COLUMNS, "value", |f| gaunt_row(f, real)))
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
    Ok(format_value(value))
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
    Ok(format_value(value))
}

/// The field of column `name` as an integer of type `T`, or an error saying it must be `what`.
fn parse_int<T: std::str::FromStr>(name: &str, field: &str, what: &str) -> Result<T, String> {
    field
        .parse()
        .map_err(|_| format!("column {name}: {field:?} is not {what}"))
}

/// Shortest round-trip text of `value`, with any zero printed as `0`.
fn format_value(value: f64) -> String {
    if value == 0.0 {
        "0".to_string()
    } else {
        format!("{value}")
    }
}

#[cfg(test)]
mod tests {
    use super::*;

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
}
