//! Another implementation's S against a hairmath model on a set of queries, with the worst
//! rows and their inputs: the check behind a renderer's test file (and `hairmath check`).
//!
//! **The error measure.** Per row, the largest over the channels of
//! `|actual - expected| / (|expected| + floor)`, with `floor` = [`RELATIVE_FLOOR`] times the
//! largest `|expected|` of the whole set, so that rows where S is tiny (far from every lobe)
//! do not dominate with relative errors of rounding noise. A non-finite value is an error of
//! infinity.
//!
//! **Directions along the tangent.** A direction exactly along the fibre (`w = (+-1, 0, 0)`)
//! has no azimuth, and S there is the limit of values that depend on the side the direction
//! approaches from: renderers legitimately disagree (hairmath takes the relative azimuth 0,
//! pbrt's `atan2(0, 0)` gives the other direction's azimuth, and the two differ by a factor of
//! 1e6 at some hard cases, `tests/testing_pbrt_port.rs`). At a row where wi or wo lies along
//! the tangent the measure therefore checks only that the value is finite and non-negative
//! (error 0, or infinity); the grazing hard cases, 0.08 degrees from the tangent, compare
//! values.
//!
//! **The queries.** [`test_queries`]: the hard cases of `docs/ARCHITECTURE.md` first (along
//! the tangent, grazing, `wi = wo`, `wi = -wo`, `phi = 0` and `pi`, `h = -1, 0, 1`), then
//! quasi-random directions and offsets (the crate's Kronecker sequence), so that a report's
//! worst row is reproducible.

use super::strategies::{direction_at, HARD_DIRECTIONS};
use crate::bcsdf::{Bcsdf, Query};
use crate::geometry::V3;
use crate::quadrature::kronecker;
use core::f64::consts::TAU;

/// The floor of the relative error, as a fraction of the set's largest value: `1e-6`.
pub const RELATIVE_FLOOR: f64 = 1e-6;

/// One row of a comparison: the query, both values and the row's relative error.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Row {
    /// Its index in the queries.
    pub index: usize,
    /// The inputs (hairmath's convention).
    pub query: Query<f64>,
    /// The hairmath model's S.
    pub expected: [f64; 3],
    /// The implementation's S.
    pub actual: [f64; 3],
    /// The row's error (the module documentation).
    pub rel_error: f64,
}

/// The outcome of [`compare`].
#[derive(Clone, Debug, PartialEq)]
pub struct Comparison {
    /// The rows compared.
    pub rows: usize,
    /// The largest row error.
    pub max_rel_error: f64,
    /// The mean row error.
    pub mean_rel_error: f64,
    /// The worst rows, worst first.
    pub worst_rows: Vec<Row>,
}

impl Comparison {
    /// Whether every row's error is at most `tolerance`.
    pub fn passes(&self, tolerance: f64) -> bool {
        self.max_rel_error <= tolerance
    }
}

impl core::fmt::Display for Comparison {
    /// A report a reader understands: the verdict's numbers and the worst rows with inputs.
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        writeln!(
            f,
            "{} rows: worst relative error {:.3e}, mean {:.3e} (relative to the value + {} of \
             the largest value)",
            self.rows, self.max_rel_error, self.mean_rel_error, RELATIVE_FLOOR
        )?;
        for r in &self.worst_rows {
            let v = |w: V3<f64>| format!("({:.6}, {:.6}, {:.6})", w.x, w.y, w.z);
            writeln!(
                f,
                "  row {}: wi {} wo {} h {:.6}: expected {:?}, got {:?} (error {:.3e})",
                r.index,
                v(r.query.wi),
                v(r.query.wo),
                r.query.h,
                r.expected,
                r.actual,
                r.rel_error
            )?;
        }
        Ok(())
    }
}

/// `actual` against `expected` on `queries` (the module documentation), keeping the
/// `worst_rows` worst rows.
pub fn compare<E, A>(
    queries: &[Query<f64>],
    expected: E,
    actual: A,
    worst_rows: usize,
) -> Comparison
where
    E: Fn(&Query<f64>) -> [f64; 3],
    A: Fn(&Query<f64>) -> [f64; 3],
{
    let values: Vec<([f64; 3], [f64; 3])> =
        queries.iter().map(|q| (expected(q), actual(q))).collect();
    compare_values(queries, &values, worst_rows)
}

/// [`compare`] of values already computed: `values[k]` is (expected, actual) at
/// `queries[k]`.
///
/// # Panics
/// If `values` and `queries` differ in length (a caller's bug, not an input).
pub fn compare_values(
    queries: &[Query<f64>],
    values: &[([f64; 3], [f64; 3])],
    worst_rows: usize,
) -> Comparison {
    assert_eq!(queries.len(), values.len(), "one value pair per query");
    let peak = values
        .iter()
        .flat_map(|(e, _)| e.iter())
        .fold(
            0.0_f64,
            |m, v| if v.is_finite() { m.max(v.abs()) } else { m },
        );
    let floor = RELATIVE_FLOOR * peak;
    let mut rows: Vec<Row> = queries
        .iter()
        .zip(values)
        .enumerate()
        .map(|(index, (query, &(expected, actual)))| Row {
            index,
            query: *query,
            expected,
            actual,
            rel_error: if along_tangent(query) {
                defined_error(actual)
            } else {
                row_error(expected, actual, floor)
            },
        })
        .collect();
    let count = rows.len();
    let mean = rows.iter().map(|r| r.rel_error).sum::<f64>() / count.max(1) as f64;
    rows.sort_by(|a, b| b.rel_error.total_cmp(&a.rel_error));
    Comparison {
        rows: count,
        max_rel_error: rows.first().map_or(0.0, |r| r.rel_error),
        mean_rel_error: mean,
        worst_rows: rows.into_iter().take(worst_rows).collect(),
    }
}

/// [`compare`] with a hairmath model as the expected side.
pub fn compare_with_model<M, A>(
    model: &M,
    queries: &[Query<f64>],
    actual: A,
    worst_rows: usize,
) -> Comparison
where
    M: Bcsdf<f64> + ?Sized,
    A: Fn(&Query<f64>) -> [f64; 3],
{
    compare(queries, |q| model.eval(q), actual, worst_rows)
}

/// Whether wi or wo lies exactly along the tangent, where the azimuth is undefined (the module
/// documentation).
fn along_tangent(query: &Query<f64>) -> bool {
    [query.wi, query.wo]
        .iter()
        .any(|w| w.y == 0.0 && w.z == 0.0)
}

/// The error of a row along the tangent: 0 if every channel is finite and non-negative, else
/// infinity.
fn defined_error(actual: [f64; 3]) -> f64 {
    if actual.iter().all(|v| v.is_finite() && *v >= 0.0) {
        0.0
    } else {
        f64::INFINITY
    }
}

/// The largest channel error of one row (infinite for a non-finite value or a NaN error).
fn row_error(expected: [f64; 3], actual: [f64; 3], floor: f64) -> f64 {
    expected
        .iter()
        .zip(actual)
        .map(|(e, a)| {
            let error = (a - e).abs() / (e.abs() + floor);
            if error.is_finite() {
                error
            } else if a == *e {
                0.0
            } else {
                f64::INFINITY
            }
        })
        .fold(0.0, f64::max)
}

/// The hard cases (module documentation) followed by `random` quasi-random queries: unit
/// directions in hairmath's local frame and offsets in [-1, 1].
pub fn test_queries(random: usize) -> Vec<Query<f64>> {
    test_queries_from(random, 0)
}

/// [`test_queries`] with the quasi-random queries taken from index `start` of the sequence.
pub fn test_queries_from(random: usize, start: usize) -> Vec<Query<f64>> {
    let mut queries = hard_queries();
    let mut x = [0.0; 5];
    for k in start..start.saturating_add(random) {
        kronecker(k, 5, &mut x);
        let wi = direction_at(2.0 * x[0] - 1.0, TAU * x[1]);
        let wo = direction_at(2.0 * x[2] - 1.0, TAU * x[3]);
        queries.push(Query::new(wi, wo, 2.0 * x[4] - 1.0));
    }
    queries
}

/// The hard cases: every pair of [`HARD_DIRECTIONS`] (along the tangent both ways, grazing,
/// perpendicular, ordinary, and the reflections `wi = wo`, `wi = -wo`, phi = 0 and pi among
/// them) at h = -1, 0 and 1.
pub fn hard_queries() -> Vec<Query<f64>> {
    let mut queries = Vec::new();
    for &(sin_a, phi_a) in &HARD_DIRECTIONS {
        for &(sin_b, phi_b) in &HARD_DIRECTIONS {
            for h in [-1.0, 0.0, 1.0] {
                queries.push(Query::new(
                    direction_at(sin_a, phi_a),
                    direction_at(sin_b, phi_b),
                    h,
                ));
            }
        }
    }
    queries
}
