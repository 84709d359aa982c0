//! Shader code whose parameters vary: a model's uniforms computed in the shader from (some of)
//! its inputs, so that a renderer can feed per-pixel values (a colour or roughness texture).
//!
//! A model's uniforms are derived from its named inputs by one generic function,
//! [`VaryingInputs::uniforms_in`], over [`InputsIn`]: every input's value in the working
//! precision. The `f64` instantiation is the model's own derivation (its `from_inputs`
//! validates the values, then derives the uniforms with the same code), the traced one runs
//! in shader code. [`trace_shader`] traces the model's `eval` as
//!
//! `fn(wi: vec3<f32>, wo: vec3<f32>[, h: f32], <varying>...) -> vec3<f32>`
//!
//! with one argument per varying input after the query's (`f32`, or `vec3<f32>` for an RGB
//! input, `sigma_a` and `color`), named as given, in the given order; the other inputs are
//! constants. Uniforms that depend on no varying input are baked, as literals, with the
//! `f64` model's values rounded once to `f32` (exactly the values [`trace_eval_with`] bakes
//! with [`UniformsIn::Constant`]); the others are computed by the shader from its arguments
//! with the CPU's formulas, in `f32`. With no varying input the graph is exactly
//! `trace_eval_with(model, UniformsIn::Constant)`. (The function's name is the one given to
//! [`Graph::to_wgsl`], `hair_bcsdf` for `hairmath shader`.)
//!
//! **Names.** A varying input is named as the command line's flag, in snake case: `beta_m`,
//! `roughness`, `kd`, ... An absorption (`--sigma-a R,G,B`, `--melanin EU,PHEO` or
//! `--color R,G,B`) varies in the form it was given in: `sigma_a` (a `vec3<f32>` per unit
//! radius), `color` (a `vec3<f32>`, inverted in the shader with the model's beta_n, Chiang et
//! al. 2016's eq. 9, [`crate::absorption::sigma_a_of_color`]) or `eumelanin` and `pheomelanin`
//! (scalars, [`crate::absorption::sigma_a_of_melanin`]; one of them may vary alone). Angles
//! are radians (the command line's `--NAME-deg` flags convert), as in
//! [`crate::bcsdf::InputValues`].
//!
//! **Domains.** Validation stays on the `f64` path: the model (and the baked values) are
//! built from validated inputs. A shader cannot return an error, so where the CPU rejects a
//! value, [`VaryingInputs::uniforms_in`] clamps it into the domain instead (documented per
//! model; for the common inputs: a roughness in [1e-16, 1] below 1e-16 ([`crate::params::MIN_BETA`])
//! or NaN is [`MIN_ROUGHNESS`], above 1 is 1; eta at or below 1 is [`MIN_ETA`], above 3 is 3; the tilt is clamped to +-pi/2; a
//! negative sigma_a or melanin concentration is 0; a colour channel above 1 is 1, at or below
//! 0 is [`crate::absorption::MIN_COLOR`]). Valid values pass unchanged (so the `f64`
//! derivation is the model's), and finite arguments give finite values (`tests/shader_varying.rs`
//! checks it on random arguments inside and outside the domains).
//!
//! **Accuracy.** A uniform the shader computes in `f32` can differ from the `f64` value
//! rounded to `f32` by a few units in the last place (each formula's own rounding; at most 5.2
//! measured over the registered models), which the model's evaluation then propagates;
//! `tests/shader_varying.rs` measures the effect per model and documents its tolerance. [`ShaderInputs::uniforms`] evaluates the shader's uniforms on
//! the CPU in any precision, bit for bit the shader's arithmetic in `f32`.

use super::inputs::{AbsorptionInput, Input, InputKind, InputValue, InputValues};
use super::model::{
    query_of, query_parameters, trace_eval_with, Bcsdf, Model, UniformBlock, UniformsIn,
};
use crate::absorption::{sigma_a_of_color, sigma_a_of_melanin};
use crate::error::ParamError;
use crate::real::{
    trace, trace_with, ArgType, Graph, Node, Parameter, Real, ResultType, Signature,
};

/// The value a roughness in [1e-16, 1] (beta_m, beta_n; [`crate::params::MIN_BETA`]) takes in
/// shader code where it is below 1e-16 (or NaN): the lowest roughness the crate tests its models at (docs/ARCHITECTURE.md, "very low
/// roughness"), where every model stays finite in `f32`.
pub const MIN_ROUGHNESS: f64 = 0.01;

/// The value an index of refraction in (1, 3] takes in shader code where it is at or below 1
/// (or NaN): `1 + 2^-20`, above 1 also in `f32` (at eta = 1 the refraction of a grazing ray is
/// 0/0).
pub const MIN_ETA: f64 = 1.0 + 1.0 / 1_048_576.0;

/// `x` in (lo, hi]: a value at or below `lo` (or NaN) is `floor`, one above `hi` is `hi`;
/// values in the domain pass unchanged.
#[inline(always)]
pub(crate) fn clamp_open_closed<R: Real>(x: R, lo: f64, hi: f64, floor: f64) -> R {
    R::select(R::c(lo).lt(x), x.min(R::c(hi)), R::c(floor))
}

/// `x` in [lo, hi]: a value below `lo` (or NaN) is `floor`, one above `hi` is `hi`; values in
/// the domain pass unchanged.
#[inline(always)]
pub(crate) fn clamp_closed_or<R: Real>(x: R, lo: f64, hi: f64, floor: f64) -> R {
    R::select(R::c(lo).le(x), x.min(R::c(hi)), R::c(floor))
}

/// `x` clamped to [lo, hi] (NaN is `lo`); values in the domain pass unchanged.
#[inline(always)]
pub(crate) fn clamp_closed<R: Real>(x: R, lo: f64, hi: f64) -> R {
    x.max(R::c(lo)).min(R::c(hi))
}

/// A roughness in [1e-16, 1] ([`MIN_ROUGHNESS`] below [`crate::params::MIN_BETA`] or NaN,
/// where the model's `f32` arithmetic would overflow).
#[inline(always)]
pub(crate) fn roughness_in<R: Real>(x: R) -> R {
    clamp_closed_or(x, crate::params::MIN_BETA, 1.0, MIN_ROUGHNESS)
}

/// An index of refraction in (1, 3] ([`MIN_ETA`] at or below 1).
#[inline(always)]
pub(crate) fn eta_in<R: Real>(x: R) -> R {
    clamp_open_closed(x, 1.0, 3.0, MIN_ETA)
}

/// A cuticle tilt clamped to [-pi/2, pi/2].
#[inline(always)]
pub(crate) fn tilt_in<R: Real>(x: R) -> R {
    let half_pi = core::f64::consts::FRAC_PI_2;
    clamp_closed(x, -half_pi, half_pi)
}

/// An absorption in the working precision, in the form it was given in
/// ([`AbsorptionInput`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum AbsorptionIn<R> {
    /// sigma_a per unit radius, linear RGB.
    SigmaA([R; 3]),
    /// Eumelanin and pheomelanin concentrations.
    Melanin {
        /// Eumelanin concentration.
        eumelanin: R,
        /// Pheomelanin concentration.
        pheomelanin: R,
    },
    /// The colour of a multiply-scattering hair volume, linear RGB.
    Color([R; 3]),
}

impl<R: Real> AbsorptionIn<R> {
    /// The absorption `input` with its values as constants of the working precision.
    pub fn of(input: AbsorptionInput) -> Self {
        match input {
            AbsorptionInput::SigmaA(s) => AbsorptionIn::SigmaA(s.map(R::c)),
            AbsorptionInput::Melanin {
                eumelanin,
                pheomelanin,
            } => AbsorptionIn::Melanin {
                eumelanin: R::c(eumelanin),
                pheomelanin: R::c(pheomelanin),
            },
            AbsorptionInput::Color(c) => AbsorptionIn::Color(c.map(R::c)),
        }
    }

    /// sigma_a per unit radius and channel, a colour inverted at azimuthal roughness `beta_n`
    /// ([`sigma_a_of_color`]; melanin by [`sigma_a_of_melanin`]): what
    /// [`AbsorptionInput::resolve`] computes in `f64`, with the shader's clamps (a negative
    /// sigma_a or concentration is 0, a colour outside (0, 1] is clamped into it).
    pub fn sigma_a(&self, beta_n: R) -> [R; 3] {
        match *self {
            AbsorptionIn::SigmaA(s) => s.map(|x| x.max(R::c(0.0))),
            AbsorptionIn::Melanin {
                eumelanin,
                pheomelanin,
            } => sigma_a_of_melanin(eumelanin, pheomelanin),
            AbsorptionIn::Color(c) => c.map(|x| sigma_a_of_color(x, beta_n)),
        }
    }
}

/// The value of one input in the working precision (inputs that vary are numbers, RGB
/// triples and absorptions; counts and switches are read from [`InputsIn::given`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum ValueIn<R> {
    /// A number (an angle in radians).
    Number(R),
    /// Three numbers, linear RGB.
    Rgb([R; 3]),
    /// An absorption.
    Absorption(AbsorptionIn<R>),
}

/// Every input's value in the working precision `R`: the given values as constants
/// ([`Real::c`]), except those replaced by [`InputsIn::vary`] (the shader's arguments when
/// `R` is [`crate::real::Traced`]).
#[derive(Clone, Debug, PartialEq)]
pub struct InputsIn<R> {
    given: InputValues,
    varying: Vec<(String, ValueIn<R>)>,
}

impl<R: Real> InputsIn<R> {
    /// The values `values`, each a constant of the working precision.
    pub fn constant(values: &InputValues) -> Self {
        InputsIn {
            given: values.clone(),
            varying: Vec::new(),
        }
    }

    /// The values as given (`f64`): what counts, switches and the inputs that never vary are
    /// read from.
    pub fn given(&self) -> &InputValues {
        &self.given
    }

    /// Replaces the value of input `name` by `value` (of the same kind).
    pub fn vary(&mut self, name: &str, value: ValueIn<R>) {
        match self.varying.iter_mut().find(|(n, _)| n == name) {
            Some(slot) => slot.1 = value,
            None => self.varying.push((name.to_string(), value)),
        }
    }

    /// The value of input `name`: the varied one, or the given one as constants.
    pub fn get(&self, name: &str) -> Option<ValueIn<R>> {
        if let Some((_, v)) = self.varying.iter().find(|(n, _)| n == name) {
            return Some(*v);
        }
        match self.given.get(name)? {
            InputValue::Number(v) => Some(ValueIn::Number(R::c(v))),
            InputValue::Rgb(v) => Some(ValueIn::Rgb(v.map(R::c))),
            InputValue::Absorption(a) => Some(ValueIn::Absorption(AbsorptionIn::of(a))),
            InputValue::Count(_) | InputValue::Switch(_) => None,
        }
    }

    /// The number `name` (an angle in radians).
    ///
    /// # Panics
    /// If `name` holds no number: the values are those the model was built from, which hold
    /// every input (a programming error otherwise).
    pub fn number(&self, name: &str) -> R {
        match self.get(name) {
            Some(ValueIn::Number(v)) => v,
            other => panic!("input {name} is not a number: {other:?}"),
        }
    }

    /// The RGB triple `name`.
    ///
    /// # Panics
    /// As [`InputsIn::number`].
    pub fn rgb(&self, name: &str) -> [R; 3] {
        match self.get(name) {
            Some(ValueIn::Rgb(v)) => v,
            other => panic!("input {name} is not an RGB triple: {other:?}"),
        }
    }

    /// The absorption `name`, in the form it was given in.
    ///
    /// # Panics
    /// As [`InputsIn::number`].
    pub fn absorption(&self, name: &str) -> AbsorptionIn<R> {
        match self.get(name) {
            Some(ValueIn::Absorption(v)) => v,
            other => panic!("input {name} is not an absorption: {other:?}"),
        }
    }

    /// The switch `name` (off when absent; switches never vary).
    ///
    /// # Panics
    /// As [`InputsIn::number`].
    pub fn switch(&self, name: &'static str) -> bool {
        self.given
            .switch(name)
            .unwrap_or_else(|e| panic!("input {name} is not a switch: {e}"))
    }
}

/// A model whose uniforms can be computed in shader code from (some of) its inputs.
///
/// Implementations derive the uniforms in [`VaryingInputs::uniforms_in`] with the same code
/// the model's `f64` constructor uses (instantiated in `f64` after validation), so that there
/// is one formula per uniform; `tests/shader_varying.rs` checks that `uniforms_in::<f64>` of
/// the values a model was built from is its [`Model::uniforms`] exactly.
pub trait VaryingInputs: Model {
    /// The model's name (the command line's `--model`).
    const NAME: &'static str;
    /// The model's named inputs (those of the [`crate::bcsdf::FromInputs`] type that builds
    /// it).
    const INPUTS: &'static [Input];
    /// The inputs that may vary, by the names of the module documentation (an absorption as
    /// `sigma_a`, `color`, `eumelanin` and `pheomelanin`).
    const VARYING: &'static [&'static str];
    /// Why each other input is baked: `(name, reason)` for every input of
    /// [`VaryingInputs::INPUTS`] not in [`VaryingInputs::VARYING`].
    const BAKED: &'static [(&'static str, &'static str)];

    /// Why input `name` of [`VaryingInputs::VARYING`] is baked for the values `values`
    /// anyway (a switch may select a formula that only runs in `f64`), or `None`.
    fn baked_for(values: &InputValues, name: &str) -> Option<&'static str> {
        let _ = (values, name);
        None
    }

    /// The uniforms in precision `R` from `inputs`, every input's value in `R` (varying or
    /// not), with the shader's clamps where a value is outside its domain (module
    /// documentation). For valid values in `f64` this is [`Model::uniforms`] of the model
    /// built from them.
    fn uniforms_in<R: Real>(inputs: &InputsIn<R>) -> Self::Uniforms<R>;
}

/// An input that cannot vary, or a model that has no shader form.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum ShaderInputError {
    /// A name that is no input of the model.
    #[error(
        "{model} has no input {name:?}; its inputs are {inputs} (an absorption varies as \
         sigma_a, color, eumelanin or pheomelanin, the form it is given in)"
    )]
    Unknown {
        /// The model.
        model: &'static str,
        /// The name given.
        name: String,
        /// The model's inputs, comma-separated.
        inputs: String,
    },
    /// An input of the model that is baked into its shader code.
    #[error(
        "{name} cannot vary in {model}'s shader code: {reason} (the inputs that can: {varying})"
    )]
    Baked {
        /// The model.
        model: &'static str,
        /// The input.
        name: String,
        /// Why it is baked.
        reason: &'static str,
        /// The inputs that can vary for these values, comma-separated.
        varying: String,
    },
    /// A name given twice.
    #[error("{name} is named twice among the varying inputs")]
    Duplicate {
        /// The name.
        name: String,
    },
    /// An absorption form other than the one the absorption was given in.
    #[error(
        "{name} cannot vary: the absorption was given as {given}, and it varies in that form \
         (as {varies_as})"
    )]
    AbsorptionForm {
        /// The name given.
        name: String,
        /// How the absorption was given (`--sigma-a`, `--melanin`, `--color`).
        given: &'static str,
        /// The names it can vary as.
        varies_as: &'static str,
    },
    /// A model that has no shader form at all.
    #[error("{model} has no shader form: {reason}")]
    NoShaderForm {
        /// The model (with the flag that selects the variant, if any).
        model: &'static str,
        /// Why.
        reason: &'static str,
    },
    /// The model cannot be built from the values.
    #[error(transparent)]
    Param(#[from] ParamError),
}

/// The names an absorption varies as besides its own (`sigma_a`).
const ABSORPTION_FORMS: [&str; 3] = ["color", "eumelanin", "pheomelanin"];

/// Where one varying argument goes: the input it replaces and how.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Slot {
    /// A number input.
    Number,
    /// An RGB input.
    Rgb,
    /// An absorption given as sigma_a.
    SigmaA,
    /// An absorption given as a colour.
    Color,
    /// The eumelanin of an absorption given as melanin.
    Eumelanin,
    /// Its pheomelanin.
    Pheomelanin,
}

impl Slot {
    /// The shader type of the argument.
    fn arg_type(self) -> ArgType {
        match self {
            Slot::Rgb | Slot::SigmaA | Slot::Color => ArgType::Vec3,
            Slot::Number | Slot::Eumelanin | Slot::Pheomelanin => ArgType::Scalar,
        }
    }
}

/// One checked varying input.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
struct Varying {
    /// Its name (as in [`VaryingInputs::VARYING`]).
    name: &'static str,
    /// The input it replaces.
    input: &'static str,
    /// How.
    slot: Slot,
}

/// How an absorption given as `input` is spelled on the command line, and the names it
/// varies as.
fn absorption_form(input: AbsorptionInput) -> (&'static str, &'static str) {
    match input {
        AbsorptionInput::SigmaA(_) => ("--sigma-a", "sigma_a"),
        AbsorptionInput::Melanin { .. } => ("--melanin", "eumelanin or pheomelanin"),
        AbsorptionInput::Color(_) => ("--color", "color"),
    }
}

/// The names of `names`, comma-separated.
fn list(names: impl IntoIterator<Item = &'static str>) -> String {
    names.into_iter().collect::<Vec<_>>().join(", ")
}

/// Why a name cannot vary (the error without its lists).
enum Rejection {
    /// No input of the model.
    Unknown,
    /// Baked, for this reason.
    Baked(&'static str),
    /// An absorption form other than the given one.
    Form(AbsorptionInput),
}

/// Checks `name` against model `M` with the values `values`.
fn check<M: VaryingInputs>(values: &InputValues, name: &str) -> Result<Varying, Rejection> {
    let absorption = M::INPUTS.iter().find(|i| i.kind == InputKind::Absorption);
    // The input `name` stands for, and how it would vary.
    let (input, slot) = match M::INPUTS.iter().find(|i| i.name == name) {
        Some(i) => {
            let slot = match i.kind {
                InputKind::Rgb => Slot::Rgb,
                InputKind::Absorption => Slot::SigmaA,
                // Counts and switches are never in VARYING: reported as baked below.
                InputKind::Number | InputKind::Angle | InputKind::Count | InputKind::Switch => {
                    Slot::Number
                }
            };
            (i, slot)
        }
        None => match (absorption, ABSORPTION_FORMS.iter().position(|f| *f == name)) {
            (Some(a), Some(k)) => (a, [Slot::Color, Slot::Eumelanin, Slot::Pheomelanin][k]),
            _ => return Err(Rejection::Unknown),
        },
    };
    let Some(&static_name) = M::VARYING.iter().find(|v| **v == name) else {
        let reason = M::BAKED
            .iter()
            .find(|(n, _)| *n == input.name)
            .map_or("it is baked", |(_, r)| *r);
        return Err(Rejection::Baked(reason));
    };
    if let Some(reason) = M::baked_for(values, name) {
        return Err(Rejection::Baked(reason));
    }
    if let Ok(given) = values.absorption(input.name) {
        let fits = matches!(
            (given, slot),
            (AbsorptionInput::SigmaA(_), Slot::SigmaA)
                | (AbsorptionInput::Color(_), Slot::Color)
                | (
                    AbsorptionInput::Melanin { .. },
                    Slot::Eumelanin | Slot::Pheomelanin
                )
        );
        if !fits {
            return Err(Rejection::Form(given));
        }
    }
    Ok(Varying {
        name: static_name,
        input: input.name,
        slot,
    })
}

/// Checks `name` against model `M` with the values `values`: the error names the model's
/// inputs, or those that can vary.
fn resolve<M: VaryingInputs>(
    values: &InputValues,
    name: &str,
) -> Result<Varying, ShaderInputError> {
    check::<M>(values, name).map_err(|rejection| match rejection {
        Rejection::Unknown => ShaderInputError::Unknown {
            model: M::NAME,
            name: name.to_string(),
            inputs: list(M::INPUTS.iter().map(|i| i.name)),
        },
        Rejection::Baked(reason) => ShaderInputError::Baked {
            model: M::NAME,
            name: name.to_string(),
            reason,
            varying: match varying_names::<M>(values) {
                names if names.is_empty() => "none".to_string(),
                names => list(names),
            },
        },
        Rejection::Form(given) => {
            let (given, varies_as) = absorption_form(given);
            ShaderInputError::AbsorptionForm {
                name: name.to_string(),
                given,
                varies_as,
            }
        }
    })
}

/// The names of [`VaryingInputs::VARYING`] that can vary for the values `values` (an
/// absorption only in the form it was given in).
pub fn varying_names<M: VaryingInputs>(values: &InputValues) -> Vec<&'static str> {
    M::VARYING
        .iter()
        .copied()
        .filter(|name| check::<M>(values, name).is_ok())
        .collect()
}

/// The varying inputs of one shader of model `M`: the names checked against the model and
/// the values it was built from, the shader arguments they are, and which uniforms they
/// determine.
#[derive(Clone, Debug)]
pub struct ShaderInputs<'m, M> {
    model: &'m M,
    values: InputValues,
    varying: Vec<Varying>,
    /// Per scalar of the uniforms: whether it depends on a varying input (else baked).
    derived: Vec<bool>,
}

impl<'m, M: VaryingInputs> ShaderInputs<'m, M> {
    /// The inputs `varying` (in this order) of `model`, built from `values`.
    ///
    /// # Errors
    /// [`ShaderInputError`]: a name that is no input of the model, that is baked (for these
    /// values), given twice, or an absorption form other than the given one.
    pub fn new(
        model: &'m M,
        values: &InputValues,
        varying: &[&str],
    ) -> Result<Self, ShaderInputError> {
        let mut checked: Vec<Varying> = Vec::with_capacity(varying.len());
        for (k, name) in varying.iter().enumerate() {
            if varying[..k].contains(name) {
                return Err(ShaderInputError::Duplicate {
                    name: name.to_string(),
                });
            }
            checked.push(resolve::<M>(values, name)?);
        }
        let mut inputs = ShaderInputs {
            model,
            values: values.clone(),
            varying: checked,
            derived: Vec::new(),
        };
        inputs.derived = inputs.dependencies();
        Ok(inputs)
    }

    /// The varying inputs' names, in argument order.
    pub fn names(&self) -> Vec<&'static str> {
        self.varying.iter().map(|v| v.name).collect()
    }

    /// The shader arguments of the varying inputs, in order (after the query's).
    pub fn parameters(&self) -> Vec<Parameter> {
        self.varying
            .iter()
            .map(|v| Parameter::argument(v.name, v.slot.arg_type()))
            .collect()
    }

    /// Number of scalars of the arguments of [`ShaderInputs::parameters`].
    pub fn argument_count(&self) -> usize {
        self.varying.iter().map(|v| v.slot.arg_type().width()).sum()
    }

    /// The arguments that give back the values the model was built from (flattened as
    /// [`ShaderInputs::uniforms`] reads them).
    pub fn given_arguments(&self) -> Vec<f64> {
        let mut out = Vec::with_capacity(self.argument_count());
        for v in &self.varying {
            match (self.values.get(v.input), v.slot) {
                (Some(InputValue::Number(x)), Slot::Number) => out.push(x),
                (Some(InputValue::Rgb(x)), Slot::Rgb)
                | (Some(InputValue::Absorption(AbsorptionInput::SigmaA(x))), Slot::SigmaA)
                | (Some(InputValue::Absorption(AbsorptionInput::Color(x))), Slot::Color) => {
                    out.extend_from_slice(&x)
                }
                (
                    Some(InputValue::Absorption(AbsorptionInput::Melanin {
                        eumelanin,
                        pheomelanin,
                    })),
                    slot,
                ) => out.push(match slot {
                    Slot::Eumelanin => eumelanin,
                    _ => pheomelanin,
                }),
                (other, slot) => unreachable!("{} checked as {slot:?}: {other:?}", v.name),
            }
        }
        out
    }

    /// Every input's value in precision `R`, the varying ones from `arguments` (one scalar per
    /// scalar of [`ShaderInputs::parameters`], in order).
    ///
    /// # Panics
    /// If `arguments` does not have [`ShaderInputs::argument_count`] scalars.
    pub fn inputs<R: Real>(&self, arguments: &[R]) -> InputsIn<R> {
        assert_eq!(
            arguments.len(),
            self.argument_count(),
            "one argument per scalar of the varying inputs"
        );
        let mut inputs = InputsIn::constant(&self.values);
        let mut rest = arguments;
        for v in &self.varying {
            let width = v.slot.arg_type().width();
            let (x, tail) = rest.split_at(width);
            rest = tail;
            let rgb = || [x[0], x[1], x[2]];
            let value = match v.slot {
                Slot::Number => ValueIn::Number(x[0]),
                Slot::Rgb => ValueIn::Rgb(rgb()),
                Slot::SigmaA => ValueIn::Absorption(AbsorptionIn::SigmaA(rgb())),
                Slot::Color => ValueIn::Absorption(AbsorptionIn::Color(rgb())),
                Slot::Eumelanin | Slot::Pheomelanin => {
                    let AbsorptionIn::Melanin {
                        mut eumelanin,
                        mut pheomelanin,
                    } = inputs.absorption(v.input)
                    else {
                        unreachable!("{} was checked to be given as melanin", v.name)
                    };
                    match v.slot {
                        Slot::Eumelanin => eumelanin = x[0],
                        _ => pheomelanin = x[0],
                    }
                    ValueIn::Absorption(AbsorptionIn::Melanin {
                        eumelanin,
                        pheomelanin,
                    })
                }
            };
            inputs.vary(v.input, value);
        }
        inputs
    }

    /// The uniforms the shader computes from `arguments`, in precision `R`: those that
    /// depend on a varying input by [`VaryingInputs::uniforms_in`], the others the `f64`
    /// model's rounded once to `R`. In `f32` this is bit for bit the shader's arithmetic
    /// ([`crate::real::Graph::eval_f32`] of [`ShaderInputs::trace`]).
    ///
    /// # Panics
    /// As [`ShaderInputs::inputs`].
    pub fn uniforms<R: Real>(&self, arguments: &[R]) -> M::Uniforms<R> {
        let baked = self.model.uniforms().to_values();
        let derived = match self.varying.is_empty() {
            true => Vec::new(),
            false => M::uniforms_in(&self.inputs(arguments)).to_values(),
        };
        let values: Vec<R> = baked
            .iter()
            .enumerate()
            .map(|(k, &b)| match self.derived.get(k) {
                Some(true) => derived[k],
                _ => R::c(b),
            })
            .collect();
        M::Uniforms::<R>::from_values(&values)
    }

    /// Per scalar of the uniforms, whether it depends on a varying input: each traced alone
    /// from symbolic arguments, it reads one of them.
    fn dependencies(&self) -> Vec<bool> {
        let width = self.model.uniforms().to_values().len();
        if self.varying.is_empty() {
            return vec![false; width];
        }
        (0..width)
            .map(|k| {
                let graph = trace(self.argument_count(), |x| {
                    vec![M::uniforms_in(&self.inputs(x)).to_values()[k]]
                });
                graph
                    .live_nodes()
                    .iter()
                    .any(|n| matches!(n, Node::Input(_)))
            })
            .collect()
    }

    /// Whether a scalar of the uniforms (in [`UniformBlock::to_values`] order) is computed by
    /// the shader (it depends on a varying input) rather than baked.
    pub fn derived(&self) -> &[bool] {
        &self.derived
    }

    /// The model's `eval` as the shader function `(wi: vec3<f32>, wo: vec3<f32>[, h: f32],
    /// <varying>...) -> vec3<f32>` (module documentation); with no varying input exactly
    /// `trace_eval_with(model, UniformsIn::Constant)`.
    pub fn trace(&self) -> Graph {
        if self.varying.is_empty() {
            return trace_eval_with(self.model, UniformsIn::Constant);
        }
        let mut parameters = query_parameters(self.model.uses_offset());
        let query: usize = parameters.iter().map(|p| p.ty.width()).sum();
        parameters.extend(self.parameters());
        let signature = Signature {
            parameters,
            result: ResultType::Vec3,
        };
        trace_with(signature, |x| {
            let uniforms = self.uniforms(&x[query..]);
            let model = self.model.with_uniforms(uniforms);
            model.eval(&query_of(&x[..query])).to_vec()
        })
    }
}

/// The shader of `model` (built from `values`) with the inputs `varying` as arguments
/// ([`ShaderInputs::trace`]; module documentation): `(wi: vec3<f32>, wo: vec3<f32>[, h: f32],
/// <varying>...) -> vec3<f32>`, every other input baked. With `varying` empty it is exactly
/// `trace_eval_with(model, UniformsIn::Constant)`.
///
/// # Errors
/// As [`ShaderInputs::new`].
pub fn trace_shader<M: VaryingInputs>(
    model: &M,
    values: &InputValues,
    varying: &[&str],
) -> Result<Graph, ShaderInputError> {
    Ok(ShaderInputs::new(model, values, varying)?.trace())
}
