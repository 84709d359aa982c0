//! The test kit for renderers that implement hair scattering themselves (feature `testing`):
//! what a renderer needs to check its own hair BSDF against hairmath's.
//!
//! - [`Convention`]: the directions, offset and cosine factor of pbrt's and Mitsuba 3's hair
//!   BSDFs, converted to and from hairmath's ([`convention`]);
//! - [`mod@compare`]: another implementation's S against a hairmath model on the hard cases and
//!   quasi-random queries ([`test_queries`]), reported with its worst rows and their inputs;
//! - [`check`]: the same through CSV files, for implementations in other languages
//!   (`hairmath cases` writes the inputs, `hairmath check` reads the renderer's values);
//! - [`strategies`]: proptest strategies of valid parameters, directions, offsets and random
//!   numbers that include the hard cases, for a renderer's own property tests;
//! - harnesses, each returning a report with its worst case and inputs: [`mod@furnace`] (the
//!   white furnace by deterministic quadrature), [`sampling`] (sample weights against S / pdf,
//!   and Pearson's chi-square of the sampled directions against the pdf), [`values`]
//!   (finiteness and non-negativity over the whole domain, shrunk by proptest).
//!
//! Every harness takes a hairmath [`Bcsdf`](crate::bcsdf::Bcsdf) or
//! [`SampledBcsdf`](crate::bcsdf::SampledBcsdf); a renderer's BSDF given as closures becomes one
//! with [`from_eval`] or [`from_sampler`] ([`closures`]).

pub mod check;
pub mod closures;
pub mod compare;
pub mod convention;
pub mod furnace;
pub mod sampling;
pub mod strategies;
pub mod values;

pub use check::{cases_csv, check_csv, VALUE_COLUMNS};
pub use closures::{from_eval, from_sampler, EvalFn, SamplerFns};
pub use compare::{
    compare, compare_values, compare_with_model, hard_queries, test_queries, test_queries_from,
    Comparison, Row, RELATIVE_FLOOR,
};
pub use convention::{query_columns, Convention, ConventionQuery};
pub use furnace::{furnace, FurnaceReport, FurnaceSettings};
pub use sampling::{
    chi_square, default_views, sample_weights, ChiSquareReport, ChiSquareSettings, View,
    WeightReport, WeightSettings,
};
pub use values::{eval_values, hard_params, sampler_values, ValueReport, ValueSettings};
