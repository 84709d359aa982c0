//! Complete single-fibre scattering models with evaluation, importance sampling and pdf.

pub mod batch;
mod chiang;

pub use batch::{batch_model, eval_batch, pdf_batch, BatchLengthError};
pub use chiang::{
    logistic_scale, longitudinal_variance, ChiangHair, ChiangParams, HairSample, CHIANG_CONSTANTS,
};
