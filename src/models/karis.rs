//! Karis 2016, "Physically Based Hair Shading in Unreal" (SIGGRAPH course; Unreal Engine 4's
//! `HairBsdf.ush`): the closed forms of Bravais' index, of the TT and TRT azimuthal
//! distributions and of the TT offset, with Karis' published coefficients and hairmath's
//! refits ([`super::constants`]).
//!
//! The references they approximate, the error metrics and the refits are in
//! `hairmath::fit::karis`; the errors quoted here are its measurements at eta = 1.55.
//!
//! # Coefficients in shader code
//!
//! Each coefficient set is a [`NamedConstant`] table (`KARIS_D_TT`, `REFIT_D_TT`, ...), the
//! one place its values are written. The closed forms take their coefficients in precision `R`
//! (`ExpCosCoefficients<R>`) and pass them to their shader functions as arguments: a model
//! reads them from the table ([`ExpCosCoefficients::named`]), so that shader code declares the
//! table as a constant and calls one `d_karis(cos_phi, a, b)` for TT and TRT; fits and tests
//! give plain `f64` values ([`ExpCosCoefficients::to_real`] for other precisions).

use super::constants::{KARIS_D_TRT, KARIS_D_TT, KARIS_ETA_PRIME, KARIS_H_TT};
use crate::real::{NamedConstant, Real, ShaderFunction};

/// Defines a pair of coefficients `{first, second}` generic in their precision (`f64` unless
/// said), with its conversions from an `[f64; 2]`, from a named table and to another precision.
macro_rules! coefficient_pair {
    ($(#[$doc:meta])* $name:ident { $(#[$first_doc:meta])* $first:ident, $(#[$second_doc:meta])* $second:ident }) => {
        $(#[$doc])*
        #[derive(Clone, Copy, Debug, PartialEq)]
        pub struct $name<T = f64> {
            $(#[$first_doc])*
            pub $first: T,
            $(#[$second_doc])*
            pub $second: T,
        }

        impl $name {
            #[doc = concat!("The `[", stringify!($first), ", ", stringify!($second), "]` of a named table, as `f64`.")]
            const fn of_table(table: &'static NamedConstant) -> Self {
                Self { $first: table.values[0], $second: table.values[1] }
            }

            /// The same coefficients in precision `R`, as literals in shader code.
            pub fn to_real<R: Real>(self) -> $name<R> {
                $name { $first: R::c(self.$first), $second: R::c(self.$second) }
            }
        }

        impl<R: Real> $name<R> {
            #[doc = concat!("The `[", stringify!($first), ", ", stringify!($second), "]` of a named table in precision `R`: in shader code, reads of the table's constant.")]
            ///
            /// # Panics
            /// If the table has fewer than two values (a programming error).
            pub fn named(table: &'static NamedConstant) -> Self {
                Self { $first: table.at(0), $second: table.at(1) }
            }
        }

        impl From<[f64; 2]> for $name {
            #[doc = concat!("`[", stringify!($first), ", ", stringify!($second), "]`, the order of Karis' paper and of the named tables.")]
            fn from([$first, $second]: [f64; 2]) -> Self {
                Self { $first, $second }
            }
        }
    };
}

coefficient_pair!(
    /// The coefficients `(a, b)` of Karis' Bravais index `eta' ~ a / cos theta_d + b cos theta_d`
    /// ([`scaled_eta_prime_karis`], [`inverse_eta_prime_karis`]).
    EtaPrimeCoefficients {
        /// The coefficient of `1 / cos theta_d`.
        a,
        /// The coefficient of `cos theta_d`.
        b
    }
);

coefficient_pair!(
    /// The coefficients `(a, b)` of Karis' azimuthal distributions `D ~ exp(a cos phi + b)`
    /// ([`d_karis`]).
    ExpCosCoefficients {
        /// The coefficient of `cos phi`.
        a,
        /// The constant term of the exponent.
        b
    }
);

coefficient_pair!(
    /// The coefficients `(c1, c2)` of Karis' TT offset `h_TT ~ (1 + a (c1 - c2 cos phi))
    /// cos(phi/2)` ([`h_tt_karis`]).
    HTtCoefficients {
        /// The constant inside the bracket.
        c1,
        /// The coefficient of `cos phi` inside the bracket.
        c2
    }
);

/// Karis' published Bravais coefficients, [`EtaPrimeCoefficients::PUBLISHED`].
pub const KARIS_ETA_PRIME_TABLE: NamedConstant = NamedConstant {
    name: "KARIS_ETA_PRIME",
    meaning: "a, b of Karis' cos(theta_d) eta' ~ a + b cos^2(theta_d) (Karis 2016)",
    values: &[1.19, 0.36],
};
/// hairmath's refit of the Bravais coefficients, [`EtaPrimeCoefficients::REFIT`].
pub const REFIT_ETA_PRIME_TABLE: NamedConstant = NamedConstant {
    name: "REFIT_ETA_PRIME",
    meaning: "a, b of cos(theta_d) eta' ~ a + b cos^2(theta_d), hairmath's minimax refit",
    values: &KARIS_ETA_PRIME,
};
/// Karis' published TT distribution, [`ExpCosCoefficients::PUBLISHED_D_TT`].
pub const KARIS_D_TT_TABLE: NamedConstant = NamedConstant {
    name: "KARIS_D_TT",
    meaning: "a, b of Karis' TT distribution exp(a cos(phi) + b) (Karis 2016)",
    values: &[-3.65, -3.98],
};
/// hairmath's refit of the TT distribution, [`ExpCosCoefficients::REFIT_D_TT`].
pub const REFIT_D_TT_TABLE: NamedConstant = NamedConstant {
    name: "REFIT_D_TT",
    meaning: "a, b of the TT distribution exp(a cos(phi) + b), hairmath's least-squares refit",
    values: &KARIS_D_TT,
};
/// Karis' published TRT distribution, [`ExpCosCoefficients::PUBLISHED_D_TRT`].
pub const KARIS_D_TRT_TABLE: NamedConstant = NamedConstant {
    name: "KARIS_D_TRT",
    meaning: "a, b of Karis' TRT distribution exp(a cos(phi) + b) (Karis 2016)",
    values: &[17.0, -16.78],
};
/// hairmath's refit of the TRT distribution, [`ExpCosCoefficients::REFIT_D_TRT`].
pub const REFIT_D_TRT_TABLE: NamedConstant = NamedConstant {
    name: "REFIT_D_TRT",
    meaning: "a, b of the TRT distribution exp(a cos(phi) + b), hairmath's least-squares refit",
    values: &KARIS_D_TRT,
};
/// Karis' published TT offset, [`HTtCoefficients::PUBLISHED`].
pub const KARIS_H_TT_TABLE: NamedConstant = NamedConstant {
    name: "KARIS_H_TT",
    meaning: "c1, c2 of Karis' TT offset (1 + a (c1 - c2 cos(phi))) cos(phi/2) (HairBsdf.ush)",
    values: &[0.6, 0.8],
};
/// hairmath's refit of the TT offset, [`HTtCoefficients::REFIT`].
pub const REFIT_H_TT_TABLE: NamedConstant = NamedConstant {
    name: "REFIT_H_TT",
    meaning: "c1, c2 of the TT offset (1 + a (c1 - c2 cos(phi))) cos(phi/2), hairmath's refit",
    values: &KARIS_H_TT,
};

impl EtaPrimeCoefficients {
    /// Karis' published `a = 1.19`, `b = 0.36` (for eta = 1.55), with his claimed "error <
    /// 0.68%". Measured: maximum relative error 6.75e-3 over theta_d in [0, 90 deg) (worst
    /// near 45 degrees; 4.8e-3 at the grazing limit), so the claim holds.
    pub const PUBLISHED: Self = Self::of_table(&KARIS_ETA_PRIME_TABLE);
    /// hairmath's minimax refit [`KARIS_ETA_PRIME`] (eta = 1.55): maximum relative error
    /// 4.51e-3 over theta_d in [0, 90 deg).
    pub const REFIT: Self = Self::of_table(&REFIT_ETA_PRIME_TABLE);
}

impl ExpCosCoefficients {
    /// Karis' published `D_TT ~ exp(-3.65 cos phi - 3.98)`. Measured against Pixar's logistic
    /// `D(phi, 0.35, pi)`: RMS error over phi in [0, pi] 1.32e-2 of the reference's peak.
    pub const PUBLISHED_D_TT: Self = Self::of_table(&KARIS_D_TT_TABLE);
    /// Karis' published `D_TRT ~ exp(17 cos phi - 16.78)`. Measured against
    /// `3/4 D(phi, 0.15, 0)`: RMS error over phi in [0, pi] 1.43e-2 of the reference's peak.
    pub const PUBLISHED_D_TRT: Self = Self::of_table(&KARIS_D_TRT_TABLE);
    /// hairmath's least-squares refit of `D_TT`, [`KARIS_D_TT`]: RMS error 9.96e-3 of the peak.
    pub const REFIT_D_TT: Self = Self::of_table(&REFIT_D_TT_TABLE);
    /// hairmath's least-squares refit of `D_TRT`, [`KARIS_D_TRT`]: RMS error 1.04e-2 of the
    /// peak.
    pub const REFIT_D_TRT: Self = Self::of_table(&REFIT_D_TRT_TABLE);
}

impl HTtCoefficients {
    /// Karis' published `c1 = 0.6`, `c2 = 0.8` (`HairBsdf.ush`). Measured against the exact
    /// offset over theta_d in [0, 80 deg] and the azimuths where it exists: RMS error 6.65e-2,
    /// maximum 1.54e-1.
    pub const PUBLISHED: Self = Self::of_table(&KARIS_H_TT_TABLE);
    /// hairmath's linear least-squares refit [`KARIS_H_TT`] (eta = 1.55): RMS error 3.70e-2,
    /// maximum 8.89e-2.
    pub const REFIT: Self = Self::of_table(&REFIT_H_TT_TABLE);
}

/// Karis' Bravais index `eta' ~ a / cos theta_d + b cos theta_d` (Karis 2016, after Marschner
/// et al. 2003's `eta' = sqrt(eta^2 - sin^2 theta_d) / cos theta_d`, appendix B), multiplied by
/// `cos theta_d`: `cos theta_d * eta' ~ a + b cos^2 theta_d`, for `cos_theta_d` in [0, 1].
///
/// The scaled form is what stays finite: at grazing (`cos theta_d = 0`) eta' itself diverges,
/// as Bravais' exact index does, while `cos theta_d * eta'` tends to `a` (the exact value is
/// `sqrt(eta^2 - 1)`, so the relative error at grazing is `a / sqrt(eta^2 - 1) - 1`, 4.8e-3 for
/// the published constants at eta = 1.55). Divide by `cos theta_d` where it is known to be
/// positive, or use [`inverse_eta_prime_karis`]. The relative error is that of eta' (see
/// [`EtaPrimeCoefficients::PUBLISHED`] and [`EtaPrimeCoefficients::REFIT`]).
pub fn scaled_eta_prime_karis<R: Real>(cos_theta_d: R, c: EtaPrimeCoefficients<R>) -> R {
    const FUNCTION: ShaderFunction = crate::shader_function!(
        scaled_eta_prime_karis,
        "Karis 2016 (Bravais' index times cos theta_d)",
        [cos_theta_d, a, b]
    );
    R::call(
        &FUNCTION,
        [cos_theta_d, c.a, c.b],
        #[inline(always)]
        |[cos_theta_d, a, b]| [a + b * cos_theta_d * cos_theta_d],
    )[0]
}

/// `1 / eta'` of Karis' Bravais index ([`scaled_eta_prime_karis`]):
/// `cos theta_d / (a + b cos^2 theta_d)` (Karis 2016), the `a` of [`h_tt_karis`] and the
/// factor of Snell's law `sin gamma_t = h / eta'`, for `cos_theta_d` in [0, 1].
///
/// Finite everywhere for coefficients with `a > 0` and `a + b > 0` (Karis' and the refit): at
/// grazing (`cos theta_d = 0`) it is exactly 0, the limit of the exact `1 / eta'`. Relative
/// error `1 / (1 + e) - 1` where `e` is that of eta'.
pub fn inverse_eta_prime_karis<R: Real>(cos_theta_d: R, c: EtaPrimeCoefficients<R>) -> R {
    cos_theta_d / scaled_eta_prime_karis(cos_theta_d, c)
}

/// Karis' azimuthal distributions `D(phi) ~ exp(a cos phi + b)` (Karis 2016): with
/// [`ExpCosCoefficients::PUBLISHED_D_TT`] the TT lobe `exp(-3.65 cos phi - 3.98)`, which
/// replaces Pixar's logistic `D(phi, 0.35, pi)`, and with
/// [`ExpCosCoefficients::PUBLISHED_D_TRT`] the TRT lobe `exp(17 cos phi - 16.78)`, which
/// replaces `3/4 D(phi, 0.15, 0)`. `phi` is the relative azimuth, radians.
///
/// Domain: every finite phi (even and 2 pi-periodic); the result is positive and finite for
/// finite coefficients. Errors (RMS over phi in [0, pi], relative to the reference's peak) are
/// documented with the coefficient sets.
pub fn d_karis<R: Real>(phi: R, c: ExpCosCoefficients<R>) -> R {
    d_karis_of_cos(phi.cos(), c)
}

/// [`d_karis`] from `cos phi` in [-1, 1], as `HairBsdf.ush` evaluates it (UE computes cos phi
/// from the projected vectors and never phi itself): `exp(a cos phi + b)` (Karis 2016).
pub fn d_karis_of_cos<R: Real>(cos_phi: R, c: ExpCosCoefficients<R>) -> R {
    const FUNCTION: ShaderFunction = crate::shader_function!(
        d_karis,
        "Karis 2016 (D ~ exp(a cos phi + b))",
        [cos_phi, a, b]
    );
    R::call(
        &FUNCTION,
        [cos_phi, c.a, c.b],
        #[inline(always)]
        |[cos_phi, a, b]| [(a * cos_phi + b).exp()],
    )[0]
}

/// Karis' TT offset `h_TT ~ (1 + a (c1 - c2 cos phi)) cos(phi/2)` (Karis 2016; `HairBsdf.ush`
/// with [`HTtCoefficients::PUBLISHED`], c1 = 0.6, c2 = 0.8), where `a = 1/eta'`
/// ([`inverse_eta_prime_karis`]) and `phi` is the relative azimuth in [-pi, pi], radians.
///
/// It approximates |h_TT|, the offset whose TT exit angle `Phi(1, h)` is phi (Marschner et al.
/// 2003 eq. 3), which is even in phi and exists only for `|phi| >= 2 asin(a)`; the
/// approximation is finite for every phi and a. Errors over theta_d in [0, 80 deg] and the
/// azimuths where the root exists are documented with the coefficient sets.
pub fn h_tt_karis<R: Real>(a: R, phi: R, c: HTtCoefficients<R>) -> R {
    h_tt_karis_of_cos(a, phi.cos(), (R::c(0.5) * phi).cos(), c)
}

/// [`h_tt_karis`] from `cos phi` and `cos(phi/2)` (in [-1, 1] and [0, 1]), as `HairBsdf.ush`
/// evaluates it: `(1 + a (c1 - c2 cos phi)) cos(phi/2)` (Karis 2016).
pub fn h_tt_karis_of_cos<R: Real>(a: R, cos_phi: R, cos_half_phi: R, c: HTtCoefficients<R>) -> R {
    const FUNCTION: ShaderFunction = crate::shader_function!(
        h_tt_karis,
        "Karis 2016 (h_TT ~ (1 + a (c1 - c2 cos phi)) cos(phi/2))",
        [a, cos_phi, cos_half_phi, c1, c2]
    );
    let args = [a, cos_phi, cos_half_phi, c.c1, c.c2];
    R::call(
        &FUNCTION,
        args,
        #[inline(always)]
        |[a, cos_phi, cos_half_phi, c1, c2]| [(R::c(1.0) + a * (c1 - c2 * cos_phi)) * cos_half_phi],
    )[0]
}
