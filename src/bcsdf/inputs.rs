//! A model's named inputs: what the command line (and any other front end) needs to build a
//! model from values given by name, without knowing the model.
//!
//! Each input has a name (`beta_m`), a [`InputKind`] that fixes its unit and how it is spelled
//! on the command line, a help text and a default. [`FromInputs`] builds a model from
//! [`InputValues`]; validation stays with the parameter types ([`crate::params`]), so an invalid
//! value gives the same message whichever way it enters. Inputs of the same name mean the same
//! thing in every model (a test checks that they are declared identically).

use crate::absorption::{Absorption, Rgb};
use crate::error::ParamError;
use crate::params::{
    AzimuthalRoughness, CuticleTilt, HairParams, LongitudinalRoughness, RefractiveIndex,
};

/// The kind of value an input takes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum InputKind {
    /// A real number.
    Number,
    /// An angle: radians in [`InputValues`], degrees on the command line (`--NAME-deg`).
    Angle,
    /// A non-negative integer.
    Count,
    /// A flag, off unless given.
    Switch,
    /// Three numbers, linear RGB (`--NAME R,G,B` on the command line, or one number for all
    /// three channels); the default is grey.
    Rgb,
    /// An absorption, given as sigma_a per channel, as melanin concentrations or as a colour
    /// (inverted with the model's beta_n): [`AbsorptionInput`].
    Absorption,
}

/// One named input of a model.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Input {
    /// The name, snake case (`beta_m`); the command line spells it `--beta-m`.
    pub name: &'static str,
    /// What kind of value it takes.
    pub kind: InputKind,
    /// What it is, its unit and its domain, in words.
    pub help: &'static str,
    /// The value taken when none is given (degrees for angles), or `None` when the input is
    /// required (switches are off by default).
    pub default: Option<f64>,
    /// Inputs that cannot be given together with this one.
    pub conflicts_with: &'static [&'static str],
}

/// How an absorption was specified.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum AbsorptionInput {
    /// sigma_a per unit radius, linear RGB.
    SigmaA(Rgb),
    /// Eumelanin and pheomelanin concentrations ([`Absorption::from_melanin`]).
    Melanin {
        /// Eumelanin concentration.
        eumelanin: f64,
        /// Pheomelanin concentration.
        pheomelanin: f64,
    },
    /// The colour of a multiply-scattering hair volume, linear RGB
    /// ([`Absorption::from_color`], with the model's beta_n).
    Color(Rgb),
}

impl AbsorptionInput {
    /// The absorption, for a model of azimuthal roughness `beta_n` (which only the colour
    /// inversion uses).
    ///
    /// # Errors
    /// As the constructors of [`Absorption`].
    pub fn resolve(self, beta_n: AzimuthalRoughness) -> Result<Absorption, ParamError> {
        match self {
            AbsorptionInput::SigmaA(s) => Absorption::new(s),
            AbsorptionInput::Melanin {
                eumelanin,
                pheomelanin,
            } => Absorption::from_melanin(eumelanin, pheomelanin),
            AbsorptionInput::Color(c) => Absorption::from_color(c, beta_n),
        }
    }
}

/// The value of one input.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum InputValue {
    /// A number; an angle in radians.
    Number(f64),
    /// A count.
    Count(usize),
    /// A switch.
    Switch(bool),
    /// Three numbers, linear RGB.
    Rgb(Rgb),
    /// An absorption.
    Absorption(AbsorptionInput),
}

/// Input values by name.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct InputValues {
    values: Vec<(String, InputValue)>,
}

impl InputValues {
    /// No values.
    pub fn new() -> Self {
        Self::default()
    }

    /// Sets (or replaces) the value of `name`.
    pub fn set(&mut self, name: &str, value: InputValue) {
        match self.values.iter_mut().find(|(n, _)| n == name) {
            Some(slot) => slot.1 = value,
            None => self.values.push((name.to_string(), value)),
        }
    }

    /// The value of `name`, if given.
    pub fn get(&self, name: &str) -> Option<InputValue> {
        self.values.iter().find(|(n, _)| n == name).map(|(_, v)| *v)
    }

    /// The number `name` (an angle in radians).
    ///
    /// # Errors
    /// [`ParamError::Missing`] if absent or not a number.
    pub fn number(&self, name: &'static str) -> Result<f64, ParamError> {
        match self.get(name) {
            Some(InputValue::Number(v)) => Ok(v),
            _ => Err(ParamError::Missing { name }),
        }
    }

    /// The count `name`.
    ///
    /// # Errors
    /// [`ParamError::Missing`] if absent or not a count.
    pub fn count(&self, name: &'static str) -> Result<usize, ParamError> {
        match self.get(name) {
            Some(InputValue::Count(v)) => Ok(v),
            _ => Err(ParamError::Missing { name }),
        }
    }

    /// The switch `name` (off when absent).
    ///
    /// # Errors
    /// [`ParamError::Missing`] if `name` holds a value that is not a switch.
    pub fn switch(&self, name: &'static str) -> Result<bool, ParamError> {
        match self.get(name) {
            Some(InputValue::Switch(v)) => Ok(v),
            None => Ok(false),
            Some(_) => Err(ParamError::Missing { name }),
        }
    }

    /// The RGB triple `name`.
    ///
    /// # Errors
    /// [`ParamError::Missing`] if absent or not an RGB triple.
    pub fn rgb(&self, name: &'static str) -> Result<Rgb, ParamError> {
        match self.get(name) {
            Some(InputValue::Rgb(v)) => Ok(v),
            _ => Err(ParamError::Missing { name }),
        }
    }

    /// The absorption `name`.
    ///
    /// # Errors
    /// [`ParamError::Missing`] if absent or not an absorption.
    pub fn absorption(&self, name: &'static str) -> Result<AbsorptionInput, ParamError> {
        match self.get(name) {
            Some(InputValue::Absorption(v)) => Ok(v),
            _ => Err(ParamError::Missing { name }),
        }
    }
}

/// A model that can be built from named inputs.
pub trait FromInputs: Sized {
    /// The model's name on the command line (`chiang-far`).
    const NAME: &'static str;
    /// What the model is, in one sentence.
    const SUMMARY: &'static str;
    /// Its inputs.
    const INPUTS: &'static [Input];

    /// The model from values of its inputs (every input with a default present).
    ///
    /// # Errors
    /// [`ParamError::Missing`] for an absent input, or the validation error of an invalid
    /// value.
    fn from_inputs(values: &InputValues) -> Result<Self, ParamError>;
}

/// The inputs of [`HairParams`], in the order of its fields.
pub const HAIR_INPUTS: [Input; 5] = [
    Input {
        name: "beta_m",
        kind: InputKind::Number,
        help: "longitudinal roughness beta_m of Chiang et al. 2016, in [1e-16, 1]",
        default: None,
        conflicts_with: &[],
    },
    Input {
        name: "beta_n",
        kind: InputKind::Number,
        help: "azimuthal roughness beta_n of Chiang et al. 2016, in [1e-16, 1]",
        default: None,
        conflicts_with: &[],
    },
    Input {
        name: "alpha",
        kind: InputKind::Angle,
        help: "cuticle tilt alpha, |alpha| < 90 degrees",
        default: Some(2.0),
        conflicts_with: &[],
    },
    Input {
        name: "eta",
        kind: InputKind::Number,
        help: "relative index of refraction eta, in (1, 3]",
        default: Some(1.55),
        conflicts_with: &[],
    },
    Input {
        name: "sigma_a",
        kind: InputKind::Absorption,
        help: "absorption per unit fibre radius",
        default: None,
        conflicts_with: &[],
    },
];

impl HairParams {
    /// The parameters from the values of [`HAIR_INPUTS`] (a colour is inverted with the given
    /// beta_n).
    ///
    /// # Errors
    /// [`ParamError::Missing`] for an absent input, or the validation error of an invalid
    /// value.
    pub fn from_inputs(values: &InputValues) -> Result<Self, ParamError> {
        let beta_m = LongitudinalRoughness::new(values.number("beta_m")?)?;
        let beta_n = AzimuthalRoughness::new(values.number("beta_n")?)?;
        Ok(HairParams {
            beta_m,
            beta_n,
            alpha: CuticleTilt::new(values.number("alpha")?)?,
            eta: RefractiveIndex::new(values.number("eta")?)?,
            sigma_a: values.absorption("sigma_a")?.resolve(beta_n)?,
        })
    }

    /// The values of [`HAIR_INPUTS`] of these parameters, the absorption as sigma_a: the
    /// inverse of [`HairParams::from_inputs`].
    pub fn to_inputs(&self) -> InputValues {
        let mut values = InputValues::new();
        values.set("beta_m", InputValue::Number(self.beta_m.get()));
        values.set("beta_n", InputValue::Number(self.beta_n.get()));
        values.set("alpha", InputValue::Number(self.alpha.get()));
        values.set("eta", InputValue::Number(self.eta.get()));
        let sigma_a = AbsorptionInput::SigmaA(self.sigma_a.rgb());
        values.set("sigma_a", InputValue::Absorption(sigma_a));
        values
    }
}

impl Input {
    /// The value taken when the input is not given: its default (an angle's converted from
    /// degrees to radians, an RGB default as grey), off for a switch, `None` for a required
    /// input.
    pub fn default_value(&self) -> Option<InputValue> {
        match (self.kind, self.default) {
            (InputKind::Switch, _) => Some(InputValue::Switch(false)),
            (InputKind::Angle, Some(d)) => Some(InputValue::Number(d.to_radians())),
            (InputKind::Count, Some(d)) => Some(InputValue::Count(d as usize)),
            (InputKind::Rgb, Some(d)) => Some(InputValue::Rgb([d; 3])),
            (_, Some(d)) => Some(InputValue::Number(d)),
            (_, None) => None,
        }
    }
}
