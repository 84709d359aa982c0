//! The test kit for renderers that implement hair scattering themselves (feature `testing`):
//! what a renderer needs to check its own hair BSDF against hairmath's.
//!
//! - [`Convention`]: the directions, offset and cosine factor of pbrt's and Mitsuba 3's hair
//!   BSDFs, converted to and from hairmath's ([`convention`]).

pub mod convention;

pub use convention::{Convention, ConventionQuery};
