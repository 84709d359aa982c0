//! The test kit for renderers that implement hair scattering themselves (feature `testing`):
//! what a renderer needs to check its own hair BSDF against hairmath's.
//!
//! - [`Convention`]: the directions, offset and cosine factor of pbrt's and Mitsuba 3's hair
//!   BSDFs, converted to and from hairmath's ([`convention`]);
//! - [`mod@compare`]: another implementation's S against a hairmath model on the hard cases and
//!   quasi-random queries ([`test_queries`]), reported with its worst rows and their inputs;
//! - [`check`]: the same through CSV files, for implementations in other languages
//!   (`hairmath cases` writes the inputs, `hairmath check` reads the renderer's values).

pub mod check;
pub mod compare;
pub mod convention;

pub use check::{cases_csv, check_csv, VALUE_COLUMNS};
pub use compare::{
    compare, compare_values, compare_with_model, hard_queries, test_queries, test_queries_from,
    Comparison, Row, RELATIVE_FLOOR,
};
pub use convention::{query_columns, Convention, ConventionQuery};
