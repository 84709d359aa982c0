//! The command-line flags of the registered models' inputs
//! ([`hairmath::registry::MODELS`]): one flag per input name, shared by every model
//! that has the input, spelled from the input's kind:
//!
//! | kind | flag |
//! | --- | --- |
//! | number | `--NAME X` |
//! | angle | `--NAME-deg DEGREES` |
//! | count | `--NAME N` |
//! | switch | `--NAME` |
//! | RGB | `--NAME R,G,B` (or one number for all three) |
//! | absorption | one of `--sigma-a R,G,B`, `--melanin EU,PHEO`, `--color R,G,B` |
//!
//! (`NAME` with `_` written `-`). A model's defaults fill what is not given; a flag of an input
//! the chosen model does not have is an error naming the models that have it.

use crate::CliError;
use clap::builder::PossibleValue;
use clap::{Arg, ArgAction, ArgGroup, ArgMatches, Args, Command, FromArgMatches};
use hairmath::bcsdf::{AbsorptionInput, Input, InputKind, InputValue, InputValues};
use hairmath::registry::{ModelEntry, MODELS};
use serde_json::json;

/// The ids of the three absorption flags, in the order the messages list them.
const ABSORPTION_FLAGS: [&str; 3] = ["sigma_a", "melanin", "color"];

/// The values given on the command line, by input name (absorption under its input's name).
#[derive(Clone, Debug, Default)]
pub struct ModelFlags {
    given: Vec<(&'static str, InputValue)>,
}

/// Every input of every registered model, once per name.
fn all_inputs() -> Vec<&'static Input> {
    let mut inputs: Vec<&'static Input> = Vec::new();
    for input in MODELS.iter().flat_map(|m| m.inputs) {
        if !inputs.iter().any(|i| i.name == input.name) {
            inputs.push(input);
        }
    }
    inputs
}

/// The flag of an input, as the user types it (`--alpha-deg`).
pub fn flag(input: &Input) -> String {
    let name = input.name.replace('_', "-");
    match input.kind {
        InputKind::Angle => format!("--{name}-deg"),
        InputKind::Absorption => "--sigma-a, --melanin or --color".to_string(),
        _ => format!("--{name}"),
    }
}

/// The long flag name (without dashes) of a non-absorption input.
fn long(input: &Input) -> String {
    flag(input).trim_start_matches("--").to_string()
}

/// The help text of an input: its own, the models that have it, and its default.
fn help(input: &Input) -> String {
    let models: Vec<&str> = models_with(input.name).iter().map(|m| m.name).collect();
    let default = match (input.kind, input.default) {
        (InputKind::Angle, Some(d)) => format!(" [default: {d} degrees]"),
        (_, Some(d)) => format!(" [default: {d}]"),
        _ => String::new(),
    };
    format!("{} (--model {}){default}", input.help, models.join(", "))
}

/// The registered models that have input `name`.
fn models_with(name: &str) -> Vec<&'static ModelEntry> {
    MODELS
        .iter()
        .filter(|m| m.inputs.iter().any(|i| i.name == name))
        .collect()
}

/// `--model`'s possible values: every registered model with its summary.
pub fn model_names() -> Vec<PossibleValue> {
    MODELS
        .iter()
        .map(|m| PossibleValue::new(m.name).help(m.summary))
        .collect()
}

/// Exactly `N` comma-separated numbers (clap value parser).
pub fn parse_floats<const N: usize>(text: &str) -> Result<[f64; N], String> {
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

/// Three comma-separated numbers, or one for all three channels (clap value parser).
pub fn parse_rgb(text: &str) -> Result<[f64; 3], String> {
    match parse_floats::<1>(text) {
        Ok([v]) => Ok([v; 3]),
        Err(_) => parse_floats::<3>(text),
    }
}

impl Args for ModelFlags {
    fn augment_args(mut cmd: Command) -> Command {
        for input in all_inputs() {
            let arg = match input.kind {
                InputKind::Absorption => {
                    cmd = absorption_args(cmd, input);
                    continue;
                }
                InputKind::Switch => Arg::new(input.name).action(ArgAction::SetTrue),
                InputKind::Rgb => Arg::new(input.name)
                    .value_name("R,G,B")
                    .value_parser(parse_rgb)
                    .allow_hyphen_values(true),
                InputKind::Count => Arg::new(input.name)
                    .value_name("N")
                    .value_parser(clap::value_parser!(usize)),
                InputKind::Number | InputKind::Angle => Arg::new(input.name)
                    .value_name(if input.kind == InputKind::Angle {
                        "DEGREES"
                    } else {
                        "X"
                    })
                    .value_parser(clap::value_parser!(f64))
                    .allow_hyphen_values(true),
            };
            cmd = cmd.arg(
                arg.long(long(input))
                    .help(help(input))
                    .conflicts_with_all(input.conflicts_with),
            );
        }
        cmd
    }

    fn augment_args_for_update(cmd: Command) -> Command {
        Self::augment_args(cmd)
    }
}

/// The three alternative absorption flags of `input`, in one group.
fn absorption_args(cmd: Command, input: &Input) -> Command {
    let models: Vec<&str> = models_with(input.name).iter().map(|m| m.name).collect();
    let models = models.join(", ");
    let rgb = |id: &'static str, long: &'static str, help: String| {
        Arg::new(id)
            .long(long)
            .value_name("R,G,B")
            .value_parser(parse_rgb)
            .allow_hyphen_values(true)
            .help(help)
    };
    cmd.arg(rgb(
        "sigma_a",
        "sigma-a",
        format!(
            "{}, linear RGB, or one value for all channels (--model {models})",
            input.help
        ),
    ))
    .arg(
        Arg::new("melanin")
            .long("melanin")
            .value_name("EU,PHEO")
            .value_parser(parse_floats::<2>)
            .allow_hyphen_values(true)
            .help(format!(
                "eumelanin and pheomelanin concentrations: sigma_a = eu * [0.419, 0.697, 1.37] \
                 + pheo * [0.187, 0.4, 1.05] (--model {models})"
            )),
    )
    .arg(rgb(
        "color",
        "color",
        format!(
            "approximate colour of a multiply-scattering hair volume, linear RGB in (0, 1], \
             inverted to sigma_a with beta_n (Chiang et al. 2016 section 4.2) (--model {models})"
        ),
    ))
    .group(
        ArgGroup::new("absorption")
            .args(ABSORPTION_FLAGS)
            .multiple(false),
    )
}

impl FromArgMatches for ModelFlags {
    fn from_arg_matches(m: &ArgMatches) -> Result<Self, clap::Error> {
        let mut given = Vec::new();
        for input in all_inputs() {
            let value = match input.kind {
                InputKind::Absorption => absorption_value(m).map(InputValue::Absorption),
                InputKind::Switch => m.get_flag(input.name).then_some(InputValue::Switch(true)),
                InputKind::Rgb => m
                    .get_one::<[f64; 3]>(input.name)
                    .map(|&v| InputValue::Rgb(v)),
                InputKind::Count => m
                    .get_one::<usize>(input.name)
                    .map(|&n| InputValue::Count(n)),
                InputKind::Number => m.get_one::<f64>(input.name).map(|&v| InputValue::Number(v)),
                InputKind::Angle => m
                    .get_one::<f64>(input.name)
                    .map(|&d| InputValue::Number(d.to_radians())),
            };
            if let Some(value) = value {
                given.push((input.name, value));
            }
        }
        Ok(ModelFlags { given })
    }

    fn update_from_arg_matches(&mut self, m: &ArgMatches) -> Result<(), clap::Error> {
        *self = Self::from_arg_matches(m)?;
        Ok(())
    }
}

/// The absorption flag given, if any.
fn absorption_value(m: &ArgMatches) -> Option<AbsorptionInput> {
    if let Some(&s) = m.get_one::<[f64; 3]>("sigma_a") {
        return Some(AbsorptionInput::SigmaA(s));
    }
    if let Some(&[eumelanin, pheomelanin]) = m.get_one::<[f64; 2]>("melanin") {
        return Some(AbsorptionInput::Melanin {
            eumelanin,
            pheomelanin,
        });
    }
    m.get_one::<[f64; 3]>("color")
        .map(|&c| AbsorptionInput::Color(c))
}

impl ModelFlags {
    /// The values of `model`'s inputs: the flags given, then the defaults.
    ///
    /// # Errors
    /// A flag of an input the model does not have ([`CliError::FlagsNotForModel`]), or a
    /// required input not given ([`CliError::MissingFlag`]).
    pub fn values_for(&self, model: &ModelEntry) -> Result<InputValues, CliError> {
        self.values_over(model, &InputValues::new())
    }

    /// The values of `model`'s inputs for the pictures (`render`, `plot`): the flags given,
    /// then the model's values at the default hair ([`ModelEntry::example_values`]: a
    /// real-time model's mapped inputs), then the defaults.
    ///
    /// # Errors
    /// As [`ModelFlags::values_for`].
    pub fn values_at_default_hair(&self, model: &ModelEntry) -> Result<InputValues, CliError> {
        self.values_over(model, &model.example_values())
    }

    /// [`ModelFlags::values_for`] with `base` before the defaults.
    fn values_over(&self, model: &ModelEntry, base: &InputValues) -> Result<InputValues, CliError> {
        if let Some((name, _)) = self
            .given
            .iter()
            .find(|(name, _)| !model.inputs.iter().any(|i| i.name == *name))
        {
            return Err(not_for_model(name));
        }
        let mut values = InputValues::new();
        for input in model.inputs {
            let given = self.given.iter().find(|(n, _)| *n == input.name);
            let value = given
                .map(|(_, v)| *v)
                .or_else(|| base.get(input.name))
                .or_else(|| input.default_value())
                .ok_or_else(|| CliError::MissingFlag {
                    model: model.name,
                    flag: flag(input),
                })?;
            values.set(input.name, value);
        }
        Ok(values)
    }
}

/// The error for a flag of input `name` given to a model without it: it names every flag that
/// belongs to exactly the same models (`--nodes and --reference apply only to --model
/// chiang-far`).
fn not_for_model(name: &str) -> CliError {
    let owners: Vec<&str> = models_with(name).iter().map(|m| m.name).collect();
    let same_owners: Vec<String> = all_inputs()
        .into_iter()
        .filter(|i| {
            let theirs: Vec<&str> = models_with(i.name).iter().map(|m| m.name).collect();
            theirs == owners
        })
        .map(flag)
        .collect();
    CliError::FlagsNotForModel {
        flags: same_owners,
        models: owners.iter().map(|m| m.to_string()).collect(),
    }
}

/// The values of `model`'s inputs as a JSON object keyed by their flags without the dashes
/// (`beta-m`, `alpha-deg` in degrees, `roughness`; an absorption under the flag it would be
/// given with: `sigma-a`, `melanin` or `color`; RGB values as arrays of three).
pub fn input_flag_values(model: &str, values: &InputValues) -> serde_json::Value {
    let mut object = serde_json::Map::new();
    let inputs = MODELS
        .iter()
        .find(|m| m.name == model)
        .map_or(&[][..], |m| m.inputs);
    for input in inputs {
        let (key, value) = match (input.kind, values.get(input.name)) {
            (_, None) => continue,
            (InputKind::Angle, Some(InputValue::Number(v))) => (long(input), json!(v.to_degrees())),
            (_, Some(InputValue::Number(v))) => (long(input), json!(v)),
            (_, Some(InputValue::Count(n))) => (long(input), json!(n)),
            (_, Some(InputValue::Switch(b))) => (long(input), json!(b)),
            (_, Some(InputValue::Rgb(c))) => (long(input), json!(c)),
            (_, Some(InputValue::Absorption(AbsorptionInput::SigmaA(s)))) => {
                ("sigma-a".to_string(), json!(s))
            }
            (_, Some(InputValue::Absorption(AbsorptionInput::Color(c)))) => {
                ("color".to_string(), json!(c))
            }
            (
                _,
                Some(InputValue::Absorption(AbsorptionInput::Melanin {
                    eumelanin,
                    pheomelanin,
                })),
            ) => ("melanin".to_string(), json!([eumelanin, pheomelanin])),
        };
        object.insert(key, value);
    }
    serde_json::Value::Object(object)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn inputs_of_the_same_name_are_declared_identically() {
        for a in MODELS.iter().flat_map(|m| m.inputs) {
            for b in MODELS.iter().flat_map(|m| m.inputs) {
                assert!(a.name != b.name || a == b, "{a:?} and {b:?} differ");
            }
        }
    }

    #[test]
    fn value_parsers_count_fields() {
        assert_eq!(parse_floats::<2>("1, -2").unwrap(), [1.0, -2.0]);
        assert!(parse_floats::<3>("1,2").is_err());
        assert!(parse_floats::<3>("1,x,2").is_err());
        assert_eq!(parse_rgb("0.5").unwrap(), [0.5; 3]);
        assert!(parse_rgb("1,2").is_err());
    }
}
