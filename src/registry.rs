//! Every model the command line (and any other front end that works by name) can build: one
//! line per model, the reference models of [`crate::bcsdf`] and the real-time approximations
//! of [`crate::models`], each with its shader form ([`ShaderEntry`]) where it has one.

use crate::bcsdf::REFERENCE_NO_SHADER_FORM;
use crate::bcsdf::{
    trace_eval, BatchEval, ChiangFarField, HostBatch, ShaderInputError, ShaderInputs,
};
use crate::bcsdf::{trace_shader, varying_names, InputsIn, UniformBlock, VaryingInputs};
use crate::bcsdf::{Bcsdf, ChiangHair, FarField, FromInputs, Input, InputValues, Marschner2003};
use crate::error::ParamError;
use crate::models::Approximation;
use crate::params::HairParams;
use crate::real::Graph;

/// Builds a model from its input values, evaluated in `f64`.
pub type BuildModel = fn(&InputValues) -> Result<Box<dyn Bcsdf<f64>>, ParamError>;

/// A model that can be built by name from [`InputValues`].
#[derive(Clone, Copy, Debug)]
pub struct ModelEntry {
    /// The model's name ([`FromInputs::NAME`]).
    pub name: &'static str,
    /// What it is ([`FromInputs::SUMMARY`]).
    pub summary: &'static str,
    /// Its inputs ([`FromInputs::INPUTS`]).
    pub inputs: &'static [Input],
    /// Builds it, evaluated in `f64`.
    pub build: BuildModel,
    /// What the comparison with the reference needs, for a real-time approximation
    /// ([`ModelEntry::approximation`]); `None` for the reference models.
    pub approximation: Option<ApproximationEntry>,
    /// The model's shader code, baked or with varying inputs
    /// ([`crate::bcsdf::VaryingInputs`]); `None` for a model that has no shader form
    /// ([`ModelEntry::shader`] says why).
    pub shader: Option<ShaderEntry>,
}

/// The shader side of a registered model, type-erased: `hairmath shader` and the tests use
/// it for every model.
#[derive(Clone, Copy, Debug)]
pub struct ShaderEntry {
    /// Traces `eval` with the named inputs as arguments ([`crate::bcsdf::trace_shader`]):
    /// `(wi: vec3<f32>, wo: vec3<f32>[, h: f32], <varying>...) -> vec3<f32>`, every other input
    /// baked.
    pub trace: TraceShader,
    /// The inputs that can vary for the values ([`crate::bcsdf::varying_names`]).
    pub varying: fn(&InputValues) -> Vec<&'static str>,
    /// The model in `f32` two ways, for checking the shader on the CPU ([`CpuShader`]).
    pub cpu: CpuShaderOf,
}

/// Traces a model built from its values with the named inputs varying.
pub type TraceShader = fn(&InputValues, &[&str]) -> Result<Graph, ShaderInputError>;

/// The [`CpuShader`] of a model built from its values, with the named inputs varying and
/// their arguments' values (`None`: those that give back the values,
/// [`CpuShader::given_arguments`]).
pub type CpuShaderOf =
    fn(&InputValues, &[&str], Option<&[f32]>) -> Result<CpuShader, ShaderInputError>;

/// A model in `f32` as the shader computes it and as the CPU instantiates it.
pub struct CpuShader {
    /// The model reading the uniforms the shader computes from the arguments
    /// ([`crate::bcsdf::ShaderInputs::uniforms`]): its `eval` is bit for bit the shader
    /// graph's [`Graph::eval_f32`].
    pub shader: Box<dyn Bcsdf<f32>>,
    /// Those uniforms, flattened ([`UniformBlock::to_values`]).
    pub shader_uniforms: Vec<f32>,
    /// The model's `f64` uniforms rounded once ([`crate::bcsdf::Model::instantiate`]).
    pub rounded: Box<dyn Bcsdf<f32>>,
    /// Those uniforms, flattened.
    pub rounded_uniforms: Vec<f32>,
    /// The arguments that give back the values the model was built from
    /// ([`crate::bcsdf::ShaderInputs::given_arguments`]).
    pub given_arguments: Vec<f64>,
    /// The arguments the shader uniforms were computed from.
    pub arguments: Vec<f32>,
    /// The model's `f64` uniforms ([`crate::bcsdf::Model::uniforms`]), flattened.
    pub uniforms_f64: Vec<f64>,
    /// [`VaryingInputs::uniforms_in`] in `f64` of the values the model was built from: the
    /// same as [`CpuShader::uniforms_f64`] (one derivation of the uniforms).
    pub uniforms_in_f64: Vec<f64>,
}

impl core::fmt::Debug for CpuShader {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.debug_struct("CpuShader")
            .field("shader_uniforms", &self.shader_uniforms)
            .field("rounded_uniforms", &self.rounded_uniforms)
            .field("given_arguments", &self.given_arguments)
            .field("arguments", &self.arguments)
            .field("uniforms_f64", &self.uniforms_f64)
            .field("uniforms_in_f64", &self.uniforms_in_f64)
            .finish_non_exhaustive()
    }
}

impl ShaderEntry {
    /// The entry of model `M`, built by its [`FromInputs`].
    pub const fn of<M: VaryingInputs + FromInputs + 'static>() -> Self
    where
        M::In<f32>: 'static,
    {
        ShaderEntry {
            trace: shader_trace::<M>,
            varying: varying_names::<M>,
            cpu: shader_cpu::<M>,
        }
    }
}

fn shader_trace<M: VaryingInputs + FromInputs>(
    values: &InputValues,
    varying: &[&str],
) -> Result<Graph, ShaderInputError> {
    trace_shader(&M::from_inputs(values)?, values, varying)
}

fn shader_cpu<M: VaryingInputs + FromInputs>(
    values: &InputValues,
    varying: &[&str],
    arguments: Option<&[f32]>,
) -> Result<CpuShader, ShaderInputError>
where
    M::In<f32>: 'static,
{
    cpu_shader(&M::from_inputs(values)?, values, varying, arguments)
}

/// [`CpuShader`] of `model`.
fn cpu_shader<M: VaryingInputs>(
    model: &M,
    values: &InputValues,
    varying: &[&str],
    arguments: Option<&[f32]>,
) -> Result<CpuShader, ShaderInputError>
where
    M::In<f32>: 'static,
{
    let inputs = ShaderInputs::new(model, values, varying)?;
    let given = inputs.given_arguments();
    let arguments = match arguments {
        Some(a) => a.to_vec(),
        None => given.iter().map(|&v| v as f32).collect(),
    };
    let uniforms = inputs.uniforms::<f32>(&arguments);
    let rounded = model.instantiate::<f32>();
    Ok(CpuShader {
        arguments,
        uniforms_f64: model.uniforms().to_values(),
        uniforms_in_f64: M::uniforms_in(&InputsIn::constant(values)).to_values(),
        shader: Box::new(model.with_uniforms(uniforms)),
        shader_uniforms: uniforms.to_values(),
        rounded_uniforms: model
            .uniforms()
            .to_values()
            .into_iter()
            .map(|v| v as f32)
            .collect(),
        rounded: Box::new(rounded),
        given_arguments: given,
    })
}

/// The far field's fixed rule, or the reason `--reference` has no shader form.
fn far_field_rule(values: &InputValues) -> Result<ChiangFarField<f64>, ShaderInputError> {
    match FarField::from_inputs(values)? {
        FarField::Rule(model) => Ok(model),
        FarField::Reference(_) => Err(ShaderInputError::NoShaderForm {
            model: "chiang-far --reference",
            reason: REFERENCE_NO_SHADER_FORM,
        }),
    }
}

fn far_field_trace(values: &InputValues, varying: &[&str]) -> Result<Graph, ShaderInputError> {
    trace_shader(&far_field_rule(values)?, values, varying)
}

fn far_field_varying(values: &InputValues) -> Vec<&'static str> {
    match values.switch("reference") {
        Ok(true) => Vec::new(),
        _ => varying_names::<ChiangFarField<f64>>(values),
    }
}

fn far_field_cpu(
    values: &InputValues,
    varying: &[&str],
    arguments: Option<&[f32]>,
) -> Result<CpuShader, ShaderInputError> {
    cpu_shader(&far_field_rule(values)?, values, varying, arguments)
}

/// The shader entry of `chiang-far`: its fixed rule ([`ChiangFarField`]); `--reference` is a
/// [`ShaderInputError::NoShaderForm`].
const FAR_FIELD_SHADER: ShaderEntry = ShaderEntry {
    trace: far_field_trace,
    varying: far_field_varying,
    cpu: far_field_cpu,
};

/// Why `marschner` has no shader form.
pub const MARSCHNER_NO_SHADER_FORM: &str = "its N_p sums over the offsets h where Phi(p, h) = \
    phi, found by solving Marschner's cubic per lobe (a data-dependent number of real roots) \
    and refined for the TRT caustic, which shader code does not do; nguyen-donnelly is the \
    same model through lookup textures";

/// The registered models without a shader form, and why.
pub const WITHOUT_SHADER_FORM: &[(&str, &str)] = &[("marschner", MARSCHNER_NO_SHADER_FORM)];

/// Builds a model from its input values, evaluated in `f32` (the uniforms rounded once).
pub type BuildModelF32 = fn(&InputValues) -> Result<Box<dyn Bcsdf<f32>>, ParamError>;

/// Traces a model built from its input values: [`trace_eval`]'s graph.
pub type TraceModel = fn(&InputValues) -> Result<Graph, ParamError>;

/// The [`Approximation`] side of a registered model, type-erased.
#[derive(Clone, Copy, Debug)]
pub struct ApproximationEntry {
    /// [`Approximation::mapped_inputs`].
    pub mapped_inputs: fn(&HairParams) -> InputValues,
    /// [`Approximation::FITTED_INPUTS`].
    pub fitted_inputs: &'static [&'static str],
    /// Builds the model in `f32`.
    pub build_f32: BuildModelF32,
    /// Traces its evaluation.
    pub trace: TraceModel,
    /// Builds it on the SIMD lanes of the host's instruction set ([`HostBatch`]).
    pub build_batch: BuildModelBatch,
}

/// Builds a model from its input values on the SIMD lanes of the host's instruction set
/// ([`HostBatch`]; the uniforms rounded once to `f32`).
pub type BuildModelBatch = fn(&InputValues) -> Result<Box<dyn BatchEval>, ParamError>;

impl ModelEntry {
    /// The entry of model `M`.
    pub const fn of<M: FromInputs + Bcsdf<f64> + 'static>() -> Self {
        ModelEntry {
            name: M::NAME,
            summary: M::SUMMARY,
            inputs: M::INPUTS,
            build: build::<M>,
            approximation: None,
            shader: None,
        }
    }

    /// The entry with the shader form `shader`.
    pub const fn with_shader(self, shader: ShaderEntry) -> Self {
        ModelEntry {
            shader: Some(shader),
            ..self
        }
    }

    /// The model's shader form, or [`ShaderInputError::NoShaderForm`] saying why it has none
    /// ([`WITHOUT_SHADER_FORM`]).
    ///
    /// # Errors
    /// As described.
    pub fn shader(&self) -> Result<&ShaderEntry, ShaderInputError> {
        self.shader
            .as_ref()
            .ok_or_else(|| ShaderInputError::NoShaderForm {
                model: self.name,
                reason: WITHOUT_SHADER_FORM
                    .iter()
                    .find(|(name, _)| *name == self.name)
                    .map_or("it is not traceable", |(_, reason)| *reason),
            })
    }

    /// Traces the model built from `values` with the inputs `varying` as arguments
    /// ([`ShaderEntry::trace`]).
    ///
    /// # Errors
    /// [`ShaderInputError`]: no shader form, a name that cannot vary, or invalid values.
    pub fn trace_shader(
        &self,
        values: &InputValues,
        varying: &[&str],
    ) -> Result<Graph, ShaderInputError> {
        (self.shader()?.trace)(values, varying)
    }

    /// The entry of the real-time approximation `M`.
    pub const fn approximation<M: Approximation + 'static>() -> Self
    where
        M::In<f32>: 'static,
        HostBatch<M>: 'static,
    {
        ModelEntry {
            approximation: Some(ApproximationEntry {
                mapped_inputs: M::mapped_inputs,
                fitted_inputs: M::FITTED_INPUTS,
                build_f32: build_f32::<M>,
                trace: trace::<M>,
                build_batch: build_batch::<M>,
            }),
            ..Self::of::<M>()
        }
    }
}

fn build_f32<M: Approximation>(values: &InputValues) -> Result<Box<dyn Bcsdf<f32>>, ParamError>
where
    M::In<f32>: 'static,
{
    Ok(Box::new(M::from_inputs(values)?.instantiate::<f32>()))
}

fn build_batch<M: Approximation>(values: &InputValues) -> Result<Box<dyn BatchEval>, ParamError>
where
    HostBatch<M>: 'static,
{
    Ok(Box::new(HostBatch::new(&M::from_inputs(values)?)))
}

fn trace<M: Approximation>(values: &InputValues) -> Result<Graph, ParamError> {
    Ok(trace_eval(&M::from_inputs(values)?))
}

fn build<M: FromInputs + Bcsdf<f64> + 'static>(
    values: &InputValues,
) -> Result<Box<dyn Bcsdf<f64>>, ParamError> {
    Ok(Box::new(M::from_inputs(values)?))
}

/// The registered models, in the order the command line lists them.
pub const MODELS: &[ModelEntry] = &[
    ModelEntry::of::<ChiangHair<f64>>().with_shader(ShaderEntry::of::<ChiangHair<f64>>()),
    ModelEntry::of::<FarField>().with_shader(FAR_FIELD_SHADER),
    ModelEntry::of::<Marschner2003>(),
    traced_approximation::<crate::models::Karis<f64>>(),
    traced_approximation::<crate::models::KarisRefit<f64>>(),
    traced_approximation::<crate::models::KajiyaKay<f64>>(),
    traced_approximation::<crate::models::TressFx<f64>>(),
    traced_approximation::<crate::models::Scheuermann<f64>>(),
    traced_approximation::<crate::models::NguyenDonnelly<f64>>(),
    traced_approximation::<crate::models::Gerard<f64>>(),
    traced_approximation::<crate::models::Frostbite<f64>>(),
    traced_approximation::<crate::models::FrostbiteRefit<f64>>(),
];

/// The entry of the real-time approximation `M` with its shader form.
const fn traced_approximation<M: Approximation + VaryingInputs + 'static>() -> ModelEntry
where
    M::In<f32>: 'static,
    HostBatch<M>: 'static,
{
    ModelEntry::approximation::<M>().with_shader(ShaderEntry::of::<M>())
}

impl ModelEntry {
    /// The values of the model's inputs when none is given: each input's default, and for the
    /// inputs without one (the physical parameters, the absorption) the default hair's
    /// (`HairParams::default()`), through the model's mapping for a real-time model (whose
    /// mapped values also replace the defaults). What the committed shaders are emitted at.
    pub fn example_values(&self) -> InputValues {
        self.values_at(&HairParams::default())
    }

    /// The values of the model's inputs for the hair `hair`: a real-time model's mapped
    /// inputs ([`ApproximationEntry::mapped_inputs`]), a reference model's the hair's own
    /// ([`HairParams::to_inputs`]), and each other input's default.
    pub fn values_at(&self, hair: &HairParams) -> InputValues {
        let given = match self.approximation {
            Some(a) => (a.mapped_inputs)(hair),
            None => hair.to_inputs(),
        };
        let mut values = InputValues::new();
        for input in self.inputs {
            if let Some(value) = given.get(input.name).or_else(|| input.default_value()) {
                values.set(input.name, value);
            }
        }
        values
    }
}

/// The registered model called `name`.
///
/// # Examples
///
/// ```
/// use hairmath::bcsdf::{InputValue, Query};
/// use hairmath::geometry::V3;
///
/// let karis = hairmath::registry::find_model("karis").expect("registered");
/// let mut values = karis.example_values(); // the default hair through Karis' mapping
/// values.set("roughness", InputValue::Number(0.4));
/// let model = (karis.build)(&values)?;
/// let s = model.eval(&Query::far(V3::new(-0.3, 0.2, 0.93), V3::new(0.3, 0.1, 0.95)));
/// assert!(s.iter().all(|v| v.is_finite()));
/// # Ok::<(), hairmath::ParamError>(())
/// ```
pub fn find_model(name: &str) -> Option<&'static ModelEntry> {
    MODELS.iter().find(|m| m.name == name)
}
