//! Complete single-fibre scattering models with evaluation, importance sampling and pdf.

mod chiang;

pub use chiang::{
    logistic_scale, longitudinal_variance, ChiangHair, ChiangParams, HairSample, CHIANG_CONSTANTS,
};
