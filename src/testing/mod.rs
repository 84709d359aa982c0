//! The test kit for renderers that implement hair scattering themselves (feature `testing`):
//! what a renderer needs to check its own hair BSDF against hairmath's.
//!
//! - [`Convention`]: the directions, offset and cosine factor of pbrt's and Mitsuba 3's hair
//!   BSDFs, converted to and from hairmath's ([`convention`]);
//! - [`compare`]: another implementation's S against a hairmath model on the hard cases and
//!   quasi-random queries ([`test_queries`]), reported with its worst rows and their inputs.

pub mod compare;
pub mod convention;

pub use compare::{
    compare, compare_with_model, hard_queries, test_queries, Comparison, Row, RELATIVE_FLOOR,
};
pub use convention::{Convention, ConventionQuery};
