//! `hairmath wigner3j` and `hairmath gaunt`: exact angular-momentum coefficients of the rows of
//! a CSV read from stdin ([`hairmath::csv::wigner3j_filter`], [`hairmath::csv::gaunt_filter`]).
//!
//! Both use the CSV conventions of `hairmath eval` (header row, columns found by name in any
//! order, other columns passed through, blank lines skipped, no quoting) and append one column,
//! `value`, printed in the shorter of Rust's shortest round-trip forms
//! ([`hairmath::csv::format_number`]: `-0.5773502691896257`, `0`, `1e-20`), so that parsing the
//! text gives back the exact `f64`.

use crate::eval::run_csv;
use crate::CliError;
use clap::Args;
use hairmath::csv::{gaunt_filter, wigner3j_filter};

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
    run_csv(wigner3j_filter)
}

/// Runs `hairmath gaunt`.
pub fn run_gaunt(args: &GauntArgs) -> Result<(), CliError> {
    let real = args.real;
    run_csv(|input, out| gaunt_filter(input, out, real))
}
