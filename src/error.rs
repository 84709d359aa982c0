//! The typed error every fallible constructor and parser of the crate returns. Its messages
//! print numbers in the shorter of their exact decimal and exponent forms
//! ([`crate::csv::format_number`]: `1e308`, not 309 digits).

use crate::csv::format_number;

/// Invalid parameters: which one, the value given, and what is allowed.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum ParamError {
    /// A scalar parameter outside its domain (non-finite values included).
    #[error("{name} = {} is not allowed: {allowed}", format_number(*.value))]
    OutOfRange {
        /// The parameter's name as the documentation spells it (for example `beta_m`).
        name: &'static str,
        /// The rejected value.
        value: f64,
        /// The allowed domain, in words (for example "must be in (0, 1]").
        allowed: &'static str,
    },
    /// A direction or tangent that is zero or has a non-finite component.
    #[error(
        "{name} = ({}, {}, {}) is not allowed: {allowed}",
        format_number(*.x),
        format_number(*.y),
        format_number(*.z)
    )]
    BadVector {
        /// The vector's name.
        name: &'static str,
        /// Components as given.
        x: f64,
        /// Components as given.
        y: f64,
        /// Components as given.
        z: f64,
        /// The requirement, in words.
        allowed: &'static str,
    },
    /// A direction whose length is not 1 within [`crate::bcsdf::UNIT_TOLERANCE`]
    /// ([`crate::bcsdf::Query::checked`]).
    #[error(
        "{name} = ({}, {}, {}) has length {}; directions must be unit vectors (within \
         {tolerance})",
        format_number(*.x),
        format_number(*.y),
        format_number(*.z),
        format_number(*.length)
    )]
    NotUnit {
        /// The direction's name.
        name: &'static str,
        /// Components as given.
        x: f64,
        /// Components as given.
        y: f64,
        /// Components as given.
        z: f64,
        /// Its length.
        length: f64,
        /// The largest deviation from 1 allowed.
        tolerance: f64,
    },
    /// A required input was not given (see [`crate::bcsdf::InputValues`]).
    #[error("{name} is required")]
    Missing {
        /// The input's name.
        name: &'static str,
    },
}

impl ParamError {
    /// `value` if it is finite and `ok(value)` holds, otherwise [`ParamError::OutOfRange`]
    /// naming `name` with the domain `allowed` in words: the one check behind every validated
    /// parameter of the crate, for models' own parameters too.
    ///
    /// # Errors
    /// [`ParamError::OutOfRange`] as described.
    pub fn check(
        name: &'static str,
        value: f64,
        allowed: &'static str,
        ok: impl Fn(f64) -> bool,
    ) -> Result<f64, ParamError> {
        if value.is_finite() && ok(value) {
            Ok(value)
        } else {
            Err(ParamError::OutOfRange {
                name,
                value,
                allowed,
            })
        }
    }
}
