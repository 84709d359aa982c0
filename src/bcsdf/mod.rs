//! Complete single-fibre scattering models with evaluation, importance sampling and pdf.

pub mod batch;
mod chiang;
mod far_field;

pub use batch::{batch_model, eval_batch, pdf_batch, BatchLengthError};
pub use chiang::{
    logistic_scale, longitudinal_variance, ChiangHair, ChiangParams, HairSample, CHIANG_CONSTANTS,
};
pub use far_field::{
    ChiangFarField, FarFieldReference, FarFieldRule, FAR_FIELD_ERROR_BOUNDS, MAX_FAR_FIELD_NODES,
};
