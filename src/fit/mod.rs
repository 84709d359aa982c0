//! Fitted constants of the source documents, regenerated and measured.
//!
//! The real-time models copy constants that their papers fitted without saying exactly to
//! what: Gerard's Henyey-Greenstein g(beta) and absorption exponents, Karis' closed forms,
//! Frostbite's per-slice Gaussians. Each submodule states what is fitted to what (reference,
//! metric, domain), refits it with argmin and measures the error of both the published and the
//! refitted value. The closed forms themselves live in [`crate::models`], which this module
//! calls and never the reverse. The results ship in [`crate::models`] (`src/models/constants.rs`), a generated
//! file that needs none of the fitting machinery: it is always compiled, while the fitter
//! itself is behind the `fit` feature (on by default).

#[cfg(feature = "fit")]
mod absorption_exponent;
#[cfg(feature = "fit")]
mod frostbite;
#[cfg(feature = "fit")]
mod generate;
#[cfg(feature = "fit")]
mod hg;
#[cfg(feature = "fit")]
mod karis;

#[cfg(feature = "fit")]
mod comparison;
#[cfg(feature = "fit")]
mod model_inputs;
#[cfg(feature = "fit")]
mod optimise;

#[cfg(feature = "fit")]
pub use absorption_exponent::*;
#[cfg(feature = "fit")]
pub use comparison::*;
#[cfg(feature = "fit")]
pub use frostbite::*;
#[cfg(feature = "fit")]
pub use generate::*;
#[cfg(feature = "fit")]
pub use hg::*;
#[cfg(feature = "fit")]
pub use karis::*;
#[cfg(feature = "fit")]
pub use model_inputs::*;
#[cfg(feature = "fit")]
pub use optimise::{
    is_coordinate_minimum, linear_least_squares, minimize, minimize_scalar, FitError, Minimum,
};

/// One regenerated constant: what a paper prints beside what hairmath fits, each with its
/// error under one stated measure.
#[derive(Clone, Debug, PartialEq)]
pub struct ConstantFit {
    /// Stable key, for example `gerard.hg_g.literal.beta_10deg` (the README lists them).
    pub key: String,
    /// Where the published value comes from: paper and equation.
    pub source: String,
    /// What the constant approximates, and how the refit was obtained.
    pub approximates: String,
    /// The value the paper prints, if it prints one.
    pub published: Option<f64>,
    /// hairmath's fitted value.
    pub refit: f64,
    /// The error measure of `published_error` and `refit_error`, with its domain.
    pub metric: String,
    /// The error of the published value under `metric`.
    pub published_error: Option<f64>,
    /// The error of the refitted value under `metric`.
    pub refit_error: f64,
}

/// A constant for the generated file [`crate::models`] (`src/models/constants.rs`): its Rust name, its documentation (what it
/// approximates, the metric, the domain and the measured error) and its value.
#[derive(Clone, Debug, PartialEq)]
pub struct GeneratedConst {
    /// The Rust identifier, SCREAMING_SNAKE_CASE.
    pub name: String,
    /// Documentation lines (without the `///`).
    pub doc: Vec<String>,
    /// The value.
    pub value: ConstValue,
}

/// The value of a [`GeneratedConst`].
#[derive(Clone, Debug, PartialEq)]
pub enum ConstValue {
    /// `f64`.
    Scalar(f64),
    /// `[f64; N]`.
    Array(Vec<f64>),
    /// `[[f64; M]; N]`, rows of equal length.
    Table(Vec<Vec<f64>>),
}

/// What one family of fits produces: the rows of `hairmath fit`'s table and the constants of
/// the generated file.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct FitOutput {
    /// Published against refitted values, with errors.
    pub records: Vec<ConstantFit>,
    /// Constants for [`crate::models`] (`src/models/constants.rs`).
    pub constants: Vec<GeneratedConst>,
}

/// The physical parameters the fits are run for.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FitSettings {
    /// Refractive index of the fibre (the papers use 1.55).
    pub eta: f64,
}

impl Default for FitSettings {
    fn default() -> Self {
        FitSettings { eta: 1.55 }
    }
}

impl FitSettings {
    /// Settings for refractive index `eta`.
    ///
    /// # Errors
    /// `eta` outside (1, 3].
    pub fn new(eta: f64) -> Result<Self, crate::error::ParamError> {
        Ok(FitSettings {
            eta: check_eta(eta)?,
        })
    }
}

/// The refractive indices the fits accept: those of [`crate::params::RefractiveIndex`], whose
/// domain and message every consumer shares.
///
/// # Errors
/// [`crate::error::ParamError::OutOfRange`] naming `eta` otherwise.
pub(crate) fn check_eta(eta: f64) -> Result<f64, crate::error::ParamError> {
    crate::params::RefractiveIndex::new(eta).map(f64::from)
}
