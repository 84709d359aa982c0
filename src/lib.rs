//! # hairmath
//!
//! The mathematics of hair shading, written once over the scalar trait [`real::Real`] and
//! instantiated in `f64` (the reference), `f32`, eight-lane SIMD and traced shader code.
//!
//! Start with [`bcsdf::ChiangHair`], the reference single-fibre model of Chiang et al. 2016 as
//! pbrt-v4 defines it. Conventions are documented in [`geometry`].

pub mod absorption;
pub mod azimuthal;
pub mod bcsdf;
pub mod error;
pub mod fresnel;
pub mod geometry;
pub mod lobe;
pub mod quadrature;
pub mod real;

pub use error::ParamError;
