//! `hairmath eval`: evaluate a registered model on rows of a simple CSV read from stdin
//! ([`hairmath::csv::eval_filter`]).

use crate::flags::{model_names, ModelFlags};
use crate::{with_stdout, CliError};
use clap::builder::PossibleValuesParser;
use clap::Args;
use hairmath::bcsdf::Bcsdf;
use hairmath::csv::{eval_filter, CsvError};
use hairmath::registry::find_model;
use std::io::{self, Write};

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

/// Runs `hairmath eval`: stdin to stdout, flushing what was written even on error.
pub fn run(args: &EvalArgs) -> Result<(), CliError> {
    let model = args.model()?;
    run_csv(|input, out| eval_filter(model.as_ref(), input, out))
}

/// Runs a CSV filter `process` from stdin to stdout, flushing what was written even when it
/// fails (so the rows before a bad one reach the reader).
pub(crate) fn run_csv(
    process: impl FnOnce(io::StdinLock<'static>, &mut dyn Write) -> Result<(), CsvError>,
) -> Result<(), CliError> {
    with_stdout(|out| Ok(process(io::stdin().lock(), out)?))
}
