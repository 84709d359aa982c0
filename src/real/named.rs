//! Constants that keep their names in shader code.
//!
//! Generic code writes a constant as `R::c(1.55)`; the tracer records its value, and the shader
//! shows a bare literal. A constant that means something (pi, a floor that keeps a division
//! finite, a published coefficient table) is written instead as a [`NamedConstant`] read with
//! [`NamedConstant::get`] or [`NamedConstant::at`]: in `f32`, `f64` and SIMD code that is
//! `R::c(value)`, bit for bit; the tracer records a [`Node::Named`](super::Node::Named) node,
//! and the shader emitter declares one module-scope `const` per name (an `array<f32, N>` for a
//! table of coefficients) that the code reads by name.
//!
//! Declare them as `const` items, not `static`s: a batch kernel is compiled in the crate that
//! instantiates it, where a `static` of hairmath is an external symbol whose value the
//! optimiser cannot see (docs/ARCHITECTURE.md). The tracer identifies a constant by its name,
//! not its address.

use super::Real;

/// A named constant: one value, or a table of values (coefficients of a polynomial fit).
#[derive(Debug, PartialEq)]
pub struct NamedConstant {
    /// The constant's name in shader code (upper case, unique within a module).
    pub name: &'static str,
    /// What the value is, and where it comes from (a comment above it in shader code).
    pub meaning: &'static str,
    /// The value, or the table's values in order.
    pub values: &'static [f64],
}

impl NamedConstant {
    /// The value of a one-value constant, in precision `R`.
    ///
    /// # Panics
    /// If the constant is a table of more than one value (a programming error).
    #[inline(always)]
    pub fn get<R: Real>(&'static self) -> R {
        assert_eq!(
            self.values.len(),
            1,
            "{} is a table: read it with at",
            self.name
        );
        R::named(self, 0)
    }

    /// Value `index` of the table, in precision `R`.
    ///
    /// # Panics
    /// If `index` is beyond the table (a programming error).
    #[inline(always)]
    pub fn at<R: Real>(&'static self, index: usize) -> R {
        R::named(self, index)
    }
}

/// pi.
pub const PI: NamedConstant = NamedConstant {
    name: "PI",
    meaning: "pi",
    values: &[core::f64::consts::PI],
};

/// 2 pi.
pub const TWO_PI: NamedConstant = NamedConstant {
    name: "TWO_PI",
    meaning: "2 pi",
    values: &[core::f64::consts::TAU],
};

/// 4 pi: the solid angle of the sphere.
pub const FOUR_PI: NamedConstant = NamedConstant {
    name: "FOUR_PI",
    meaning: "4 pi, the solid angle of the sphere",
    values: &[4.0 * core::f64::consts::PI],
};

/// 1 / (2 pi): the uniform density over an angle of 2 pi.
pub const INV_TWO_PI: NamedConstant = NamedConstant {
    name: "INV_TWO_PI",
    meaning: "1 / (2 pi), the uniform density over a full turn",
    values: &[0.5 * core::f64::consts::FRAC_1_PI],
};

/// sqrt(2 pi): the normalisation of the Gaussian (`sqrt` of the `f64` nearest 2 pi, one ulp
/// below the `f64` nearest sqrt(2 pi); the fitted constants were computed with it).
pub const SQRT_TWO_PI: NamedConstant = NamedConstant {
    name: "SQRT_TWO_PI",
    meaning: "sqrt(2 pi), the normalisation of the Gaussian",
    values: &[2.506_628_274_631_000_2],
};

/// sqrt(2).
pub const SQRT_2: NamedConstant = NamedConstant {
    name: "SQRT_TWO",
    meaning: "sqrt(2)",
    values: &[core::f64::consts::SQRT_2],
};

/// The floor that keeps a denominator, a length or a width positive.
pub const TINY: NamedConstant = NamedConstant {
    name: "TINY",
    meaning: "1e-30, the floor that keeps a denominator, a length or a width positive",
    values: &[1e-30],
};

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn named_constants_are_their_values_rounded_once() {
        assert_eq!(PI.get::<f64>(), core::f64::consts::PI);
        assert_eq!(PI.get::<f32>(), core::f32::consts::PI);
        assert_eq!(
            SQRT_TWO_PI.get::<f64>(),
            (2.0 * core::f64::consts::PI).sqrt()
        );
        assert_eq!(INV_TWO_PI.get::<f32>(), 1.0 / core::f32::consts::TAU);
        assert_eq!(FOUR_PI.get::<f64>(), 2.0 * TWO_PI.get::<f64>());
    }

    #[test]
    #[should_panic(expected = "is a table")]
    fn a_table_is_not_read_as_one_value() {
        const TABLE: NamedConstant = NamedConstant {
            name: "TABLE",
            meaning: "two values",
            values: &[1.0, 2.0],
        };
        let _ = TABLE.get::<f64>();
    }
}
