//! The model contract ([`Bcsdf`], [`SampledBcsdf`], [`Model`]), the generic consumers that come
//! with it (batch evaluation, tracing), and the reference models:
//! Chiang et al. 2016's near field ([`ChiangHair`]) and far field ([`ChiangFarField`],
//! [`ReferenceFarField`]; [`HostFarField`] runs the far field's nodes in SIMD lanes;
//! [`AlignedFarField`] places its nodes per lobe where the lobe lives), and
//! Marschner et al. 2003 ([`Marschner2003`]).
//!
//! # Adding a model
//!
//! A model is one file: its parameters (validated types from [`crate::params`]), its uniforms
//! ([`uniform_block!`](crate::uniform_block)), its physics ([`Bcsdf`], generic over
//! [`crate::real::Real`]), [`Model`] (uniforms from the parameters, the model from the
//! uniforms) and [`FromInputs`] (its name and named inputs); then one line in
//! [`crate::registry::MODELS`] makes `hairmath eval --model NAME` accept it. The README shows an
//! example. [`VaryingInputs`] (the uniforms derived once, generic over the precision, from the
//! inputs) gives it shader code with varying inputs ([`trace_shader`]) and, registered with
//! [`crate::registry::ModelEntry::with_shader`], a shader form in the registry.

mod aligned_far_field;
mod batch;
mod chiang;
mod far_field;
mod host;
mod host_far_field;
mod inputs;
mod marschner;
mod model;
mod varying;

pub use crate::real::InstructionSet;
pub use aligned_far_field::{
    AlignedFarField, ALIGNED_FAR_FIELD_ERROR_BOUNDS, MAX_NODES_PER_HALF_BRANCH,
};
pub(crate) use batch::{check as check_lengths, check_samples, eval_samples, pdf_samples};
pub use batch::{
    eval_batch, eval_batch_soa, pdf_batch, BatchError, BatchEval, BatchLanes, BatchLengthError,
    BatchReal, DirectionSlices, RgbSlices, LANES,
};
#[cfg(feature = "parallel")]
pub use batch::{par_eval_batch, par_eval_batch_soa, par_pdf_batch, PARALLEL_CHUNK};
pub use chiang::{
    logistic_scale, longitudinal_variance, AtOffset, AzimuthalFactors, ChiangHair, ChiangUniforms,
    LobeTerms, Offsets, OffsetsIn, Outgoing, CHIANG_LOBES,
};
pub(crate) use chiang::{variance_of, PairAngles, HAIR_VARYING};
pub use far_field::{
    ChiangFarField, FarField, FarFieldReference, FarFieldRule, OffsetNodes, ReferenceFarField,
    DEFAULT_FAR_FIELD_NODES, FAR_FIELD_ERROR_BOUNDS, MAX_FAR_FIELD_NODES, REFERENCE_NO_SHADER_FORM,
    REFERENCE_REL_TOL,
};
pub use host::HostBatch;
pub use host_far_field::HostFarField;
pub use inputs::{
    AbsorptionInput, FromInputs, Input, InputKind, InputValue, InputValues, HAIR_INPUTS,
};
pub use marschner::{Marschner2003, COLOR_BETA_N, MARSCHNER_LOBES};
pub use model::{
    query_of, query_parameters, sum_lobes, trace_eval, trace_eval_with, trace_model, traced_inputs,
    Bcsdf, HairSample, Model, Query, RandomNumbers, SampledBcsdf, UniformBlock, UniformField,
    UniformValue, UniformsIn, UNIT_TOLERANCE,
};
pub(crate) use varying::{clamp_closed, clamp_open_closed, eta_in, roughness_in, tilt_in};
pub use varying::{
    trace_shader, varying_names, AbsorptionIn, InputsIn, ShaderInputError, ShaderInputs, ValueIn,
    VaryingInputs, MIN_ETA, MIN_ROUGHNESS,
};
