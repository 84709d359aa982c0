//! A renderer's values read as CSV and checked against a hairmath model: what `hairmath cases`
//! writes and `hairmath check` reads, for implementations in other languages.
//!
//! [`cases_csv`] writes the inputs ([`super::test_queries`], the hard cases first) in a
//! [`Convention`]'s meaning; the renderer appends `f_r,f_g,f_b` (its `f`, in the same
//! convention's meaning); [`check_csv`] reads that back, converts each row to hairmath's query
//! and S ([`Convention::to_hairmath`], [`Convention::s_of_f`]) and compares it with the model
//! ([`super::compare_values`]).

use super::compare::{compare_values, test_queries_from, Comparison};
use super::convention::{query_columns, Convention, ConventionQuery};
use crate::bcsdf::{Bcsdf, Query};
use crate::csv::{finite_number, format_number, read_rows, CsvError};
use glam::DVec3;
use std::io::{BufRead, Write};

/// The value columns [`check_csv`] reads after the query's.
pub const VALUE_COLUMNS: [&str; 3] = ["f_r", "f_g", "f_b"];

/// Writes the hard cases and `random` quasi-random queries (starting at index
/// `seed * random` of the sequence, so that seeds give disjoint sets) as CSV in `convention`'s
/// meaning: columns [`query_columns`].
///
/// # Errors
/// The writer's error.
pub fn cases_csv(
    convention: Convention,
    random: usize,
    seed: u64,
    out: &mut dyn Write,
) -> std::io::Result<()> {
    let columns = query_columns(convention);
    writeln!(out, "{}", columns.join(","))?;
    let start = (seed as usize).saturating_mul(random);
    for query in test_queries_from(random, start) {
        let c = convention.from_hairmath(&query);
        let mut fields: Vec<f64> = [c.wi, c.wo].iter().flat_map(|w| w.to_array()).collect();
        fields.extend(c.h);
        let text: Vec<String> = fields.into_iter().map(format_number).collect();
        writeln!(out, "{}", text.join(","))?;
    }
    Ok(())
}

/// Reads rows of a query in `convention` ([`query_columns`]) and the renderer's `f`
/// ([`VALUE_COLUMNS`]) and compares them with `model` ([`fn@super::compare`], keeping `worst_rows`).
/// The rows are kept in memory (the worst rows and the set's largest value need all of them).
///
/// # Errors
/// [`CsvError::Input`] naming the first bad line: a missing column, a field that is not a
/// finite number, or a query [`Convention::to_hairmath`] refuses.
pub fn check_csv(
    model: &dyn Bcsdf<f64>,
    convention: Convention,
    input: impl BufRead,
    worst_rows: usize,
) -> Result<Comparison, CsvError> {
    let query_names = query_columns(convention);
    let names: Vec<&str> = query_names.iter().chain(&VALUE_COLUMNS).copied().collect();
    let mut rows: Vec<(Query<f64>, [f64; 3])> = Vec::new();
    read_rows(input, &names, |_, fields| {
        let mut v = Vec::with_capacity(fields.len());
        for (name, field) in names.iter().zip(fields) {
            v.push(finite_number(name, field)?);
        }
        let foreign = ConventionQuery {
            wi: DVec3::new(v[0], v[1], v[2]),
            wo: DVec3::new(v[3], v[4], v[5]),
            h: convention.has_offset().then(|| v[6]),
        };
        let query = convention
            .to_hairmath(&foreign)
            .map_err(|e| e.to_string())?;
        let f = [v[names.len() - 3], v[names.len() - 2], v[names.len() - 1]];
        rows.push((query, convention.s_of_f(f, &query)));
        Ok(())
    })?;
    let queries: Vec<Query<f64>> = rows.iter().map(|(q, _)| *q).collect();
    let values: Vec<([f64; 3], [f64; 3])> = rows.iter().map(|(q, s)| (model.eval(q), *s)).collect();
    Ok(compare_values(&queries, &values, worst_rows))
}
