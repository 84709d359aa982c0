//! The typed error every fallible constructor and parser of the crate returns.

/// Invalid parameters: which one, the value given, and what is allowed.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum ParamError {
    /// A scalar parameter outside its domain (non-finite values included).
    #[error("{name} = {value} is not allowed: {allowed}")]
    OutOfRange {
        /// The parameter's name as the documentation spells it (for example `beta_m`).
        name: &'static str,
        /// The rejected value.
        value: f64,
        /// The allowed domain, in words (for example "must be in (0, 1]").
        allowed: &'static str,
    },
    /// A direction or tangent that is zero or has a non-finite component.
    #[error("{name} = ({x}, {y}, {z}) is not allowed: {allowed}")]
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
