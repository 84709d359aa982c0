#![doc = include_str!("../README.md")]
#![warn(missing_docs)]

pub mod absorption;
pub mod azimuthal;
pub mod bcsdf;
pub mod csv;
#[cfg(feature = "gpu")]
pub mod device;
pub mod diagnostics;
pub mod error;
pub mod fit;
pub mod fresnel;
pub mod geometry;
pub mod lobe;
pub mod lut;
pub mod models;
pub mod params;
#[cfg(feature = "plan")]
pub mod plan;
pub mod quadrature;
#[cfg(any(feature = "strands", feature = "testing"))]
mod random;
pub mod real;
pub mod registry;
#[cfg(feature = "strands")]
pub mod render;
pub mod sh;
#[cfg(feature = "shader")]
pub mod shader;
#[cfg(feature = "strands")]
pub mod strands;
#[cfg(feature = "testing")]
pub mod testing;
pub mod world;

/// The vector types of the API ([`glam::Vec3`], [`glam::DVec3`]), re-exported so a renderer
/// uses the version hairmath is built with.
pub use glam;

pub use error::ParamError;
