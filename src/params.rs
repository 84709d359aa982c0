//! Validated physical parameters of a hair fibre, one type per quantity.
//!
//! Every physical parameter has exactly one domain, checked in one place (its constructor) with
//! one message, and every consumer (the models, the fits, the table bakers, the command line)
//! takes the validated type. A value of one of these types is valid by construction, and
//! because each quantity has its own type, passing the index of refraction where the tilt is
//! expected does not compile. [`HairParams`] gathers them as named fields:
//!
//! ```
//! use hairmath::absorption::Absorption;
//! use hairmath::params::{
//!     AzimuthalRoughness, CuticleTilt, HairParams, LongitudinalRoughness, RefractiveIndex,
//! };
//!
//! let brown = HairParams {
//!     beta_m: LongitudinalRoughness::new(0.3)?,
//!     beta_n: AzimuthalRoughness::new(0.3)?,
//!     alpha: CuticleTilt::from_degrees(2.0)?,
//!     eta: RefractiveIndex::new(1.55)?,
//!     sigma_a: Absorption::from_melanin(1.3, 0.0)?,
//! };
//! assert_eq!(brown, HairParams::default());
//! # Ok::<(), hairmath::ParamError>(())
//! ```
//!
//! Swapping two parameters of different kinds is a type error:
//!
//! ```compile_fail
//! use hairmath::params::{AzimuthalRoughness, HairParams, RefractiveIndex};
//!
//! let hair = HairParams {
//!     beta_n: RefractiveIndex::new(1.55)?, // a RefractiveIndex is not an AzimuthalRoughness
//!     eta: AzimuthalRoughness::new(0.3)?,
//!     ..HairParams::default()
//! };
//! # Ok::<(), hairmath::ParamError>(())
//! ```

use crate::absorption::Absorption;
use crate::error::ParamError;
use crate::real::Real;

/// Defines a validated `f64` quantity: the symbol its errors name, its domain in words, the
/// check, and the conversions.
macro_rules! scalar_parameter {
    (
        $(#[$doc:meta])*
        $name:ident, symbol $symbol:literal, allowed $allowed:literal, |$v:ident| $ok:expr
    ) => {
        $(#[$doc])*
        #[derive(Clone, Copy, Debug, PartialEq, PartialOrd)]
        pub struct $name(f64);

        impl $name {
            /// The symbol errors and documentation use for this quantity.
            pub const SYMBOL: &'static str = $symbol;
            /// The allowed domain, in words (the text of the error message).
            pub const ALLOWED: &'static str = $allowed;

            /// The validated value.
            ///
            /// # Errors
            /// [`ParamError::OutOfRange`] naming the quantity when `value` is outside its
            /// domain or not finite.
            pub fn new(value: f64) -> Result<Self, ParamError> {
                ParamError::check($symbol, value, $allowed, |$v| $ok).map(Self)
            }

            /// The value.
            pub fn get(self) -> f64 {
                self.0
            }
        }

        impl TryFrom<f64> for $name {
            type Error = ParamError;
            fn try_from(value: f64) -> Result<Self, ParamError> {
                Self::new(value)
            }
        }

        impl From<$name> for f64 {
            fn from(value: $name) -> f64 {
                value.0
            }
        }
    };
}

/// The smallest roughness (beta_m and beta_n) the crate accepts: `1e-16`. Chiang et al.
/// 2016's model is finite in `f64` down to beta_m = 2.1e-154 (below it the lobe variance
/// underflows) and in `f32`, in every path (the rounded uniforms, SIMD lanes, the uniforms a
/// shader derives), down to beta_m = 1.5e-19 and beta_n = 5.1e-38 (measured by bisection over
/// 15,150 direction pairs and offsets; tests/robustness.rs checks the domain's ends). 1e-16
/// keeps a factor of 1000 from the `f32` limit, where the variance of the TT lobe stays a
/// normal `f32` (1.3e-33), also on GPUs that flush subnormals to zero, and the largest value
/// of S stays near 1e32.
pub const MIN_BETA: f64 = 1e-16;

scalar_parameter! {
    /// Longitudinal roughness beta_m of Chiang et al. 2016 (dimensionless, in [1e-16, 1]:
    /// from [`MIN_BETA`], where the model is finite in `f32` and `f64`); the lobe variance follows from it by Chiang's eq. 7.
    LongitudinalRoughness, symbol "beta_m", allowed "the longitudinal roughness must be in [1e-16, 1]",
    |v| (MIN_BETA..=1.0).contains(&v)
}

scalar_parameter! {
    /// Azimuthal roughness beta_n of Chiang et al. 2016 (dimensionless, in [1e-16, 1]: from
    /// [`MIN_BETA`], where the model is finite in `f32` and `f64`); the logistic scale follows from it by Chiang's eq. 8.
    AzimuthalRoughness, symbol "beta_n", allowed "the azimuthal roughness must be in [1e-16, 1]",
    |v| (MIN_BETA..=1.0).contains(&v)
}

scalar_parameter! {
    /// The tilt alpha of the cuticle scales, in radians (human hair: about 2 to 3 degrees):
    /// finite with |alpha| < pi/2.
    CuticleTilt, symbol "alpha", allowed "the cuticle tilt must be finite with |alpha| < pi/2 radians",
    |v| v.abs() < core::f64::consts::FRAC_PI_2
}

scalar_parameter! {
    /// The fibre's index of refraction eta relative to its surroundings, in (1, 3] (human
    /// hair: 1.55).
    RefractiveIndex, symbol "eta", allowed "the relative index of refraction must be in (1, 3]",
    |v| v > 1.0 && v <= 3.0
}

scalar_parameter! {
    /// The longitudinal shift alpha_R of Marschner et al. 2003's R lobe, in radians (his
    /// Table 1: -10 to -5 degrees): |alpha_R| <= pi/8.
    LobeShift, symbol "alpha_r", allowed "the R lobe shift must satisfy |alpha_r| <= pi/8 radians",
    |v| v.abs() <= core::f64::consts::PI / 8.0
}

scalar_parameter! {
    /// The longitudinal width beta_R of Marschner et al. 2003's R lobe (the Gaussian's standard
    /// deviation), in radians (his Table 1: 5 to 10 degrees): in (0, pi/4].
    LobeWidth, symbol "beta_r", allowed "the R lobe width must be in (0, pi/4] radians",
    |v| v > 0.0 && v <= core::f64::consts::PI / 4.0
}

/// Marschner et al. 2003's longitudinal lobes, from the R lobe's shift and width; the others
/// follow by his Table 1 ([`MarschnerLobes::lobes`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MarschnerLobes {
    /// The R lobe's shift alpha_R.
    pub alpha_r: LobeShift,
    /// The R lobe's width beta_R.
    pub beta_r: LobeWidth,
}

impl MarschnerLobes {
    /// (alpha_p, beta_p) for p = R, TT, TRT: `alpha_TT = -alpha_R / 2`,
    /// `alpha_TRT = -3 alpha_R / 2`, `beta_TT = beta_R / 2`, `beta_TRT = 2 beta_R`
    /// (Marschner 2003, Table 1).
    pub fn lobes(&self) -> [(f64, f64); 3] {
        marschner_lobes(self.alpha_r.get(), self.beta_r.get())
    }
}

/// (alpha_p, beta_p) for p = R, TT, TRT from the R lobe's shift `alpha_r` and width `beta_r`
/// (radians): `alpha_TT = -alpha_R / 2`, `alpha_TRT = -3 alpha_R / 2`, `beta_TT = beta_R / 2`,
/// `beta_TRT = 2 beta_R` (Marschner 2003, Table 1), in the working precision.
pub fn marschner_lobes<R: Real>(alpha_r: R, beta_r: R) -> [(R, R); 3] {
    let (a, b, two) = (alpha_r, beta_r, R::c(2.0));
    [(a, b), (-a / two, b / two), (R::c(-1.5) * a, two * b)]
}

impl Default for MarschnerLobes {
    /// alpha_R = -5 degrees, beta_R = 7.5 degrees.
    fn default() -> Self {
        MarschnerLobes {
            alpha_r: LobeShift((-5.0_f64).to_radians()),
            beta_r: LobeWidth(7.5_f64.to_radians()),
        }
    }
}

impl CuticleTilt {
    /// The tilt of `degrees` degrees.
    ///
    /// # Errors
    /// As [`CuticleTilt::new`], for the converted value.
    pub fn from_degrees(degrees: f64) -> Result<Self, ParamError> {
        Self::new(degrees.to_radians())
    }
}

impl RefractiveIndex {
    /// 1.55, the index of human hair keratin every source document uses.
    pub const HUMAN_HAIR: RefractiveIndex = RefractiveIndex(1.55);
}

/// The physical parameters of a hair fibre, as named fields. Every hair model is built from
/// them (the reference directly, the real-time models through their documented mappings).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct HairParams {
    /// Longitudinal roughness.
    pub beta_m: LongitudinalRoughness,
    /// Azimuthal roughness.
    pub beta_n: AzimuthalRoughness,
    /// Cuticle tilt.
    pub alpha: CuticleTilt,
    /// Relative index of refraction.
    pub eta: RefractiveIndex,
    /// Absorption per unit fibre radius.
    pub sigma_a: Absorption,
}

/// The physical parameters of a hair fibre as plain numbers, by name (alpha in radians, sigma_a
/// per unit radius and RGB channel), for code that reads them from elsewhere (a file, a
/// material system): `HairParams::try_from(values)` validates each with its type's one check.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct HairValues {
    /// Longitudinal roughness beta_m.
    pub beta_m: f64,
    /// Azimuthal roughness beta_n.
    pub beta_n: f64,
    /// Cuticle tilt alpha, radians.
    pub alpha: f64,
    /// Relative index of refraction eta.
    pub eta: f64,
    /// Absorption per unit fibre radius, linear RGB.
    pub sigma_a: [f64; 3],
}

impl TryFrom<HairValues> for HairParams {
    type Error = ParamError;

    /// Validates every field (beta_m first, then beta_n, alpha, eta, sigma_a).
    fn try_from(v: HairValues) -> Result<Self, ParamError> {
        Ok(HairParams {
            beta_m: LongitudinalRoughness::new(v.beta_m)?,
            beta_n: AzimuthalRoughness::new(v.beta_n)?,
            alpha: CuticleTilt::new(v.alpha)?,
            eta: RefractiveIndex::new(v.eta)?,
            sigma_a: Absorption::new(v.sigma_a)?,
        })
    }
}

impl Default for HairParams {
    /// Brown hair: beta_m = beta_n = 0.3, a 2 degree tilt, eta = 1.55, eumelanin 1.3.
    fn default() -> Self {
        HairParams {
            beta_m: LongitudinalRoughness(0.3),
            beta_n: AzimuthalRoughness(0.3),
            alpha: CuticleTilt(2.0 * (core::f64::consts::PI / 180.0)),
            eta: RefractiveIndex::HUMAN_HAIR,
            sigma_a: Absorption::from_melanin(1.3, 0.0)
                .unwrap_or_else(|_| unreachable!("1.3 is a valid concentration")),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn domains_and_messages() {
        assert!(LongitudinalRoughness::new(1.0).is_ok());
        assert!(LongitudinalRoughness::new(MIN_BETA).is_ok());
        assert!(LongitudinalRoughness::new(MIN_BETA * 0.99).is_err());
        let allowed = format!("[{MIN_BETA:e}, 1]");
        assert!(LongitudinalRoughness::ALLOWED.ends_with(&allowed));
        assert!(AzimuthalRoughness::ALLOWED.ends_with(&allowed));
        let e = AzimuthalRoughness::new(0.0).unwrap_err().to_string();
        assert_eq!(
            e,
            "beta_n = 0 is not allowed: the azimuthal roughness must be in [1e-16, 1]"
        );
        assert!(RefractiveIndex::new(3.0).is_ok() && RefractiveIndex::new(1.0).is_err());
        assert!(RefractiveIndex::try_from(f64::NAN).is_err());
        assert!(CuticleTilt::from_degrees(-89.0).is_ok() && CuticleTilt::new(1.6).is_err());
        assert_eq!(f64::from(RefractiveIndex::HUMAN_HAIR), 1.55);
        assert_eq!(
            HairParams::default().alpha,
            CuticleTilt::from_degrees(2.0).unwrap()
        );
        let values = HairValues {
            beta_m: 0.3,
            beta_n: 0.3,
            alpha: 2f64.to_radians(),
            eta: 1.55,
            sigma_a: HairParams::default().sigma_a.rgb(),
        };
        assert_eq!(HairParams::try_from(values), Ok(HairParams::default()));
        let bad = HairParams::try_from(HairValues { eta: 1.0, ..values }).unwrap_err();
        assert_eq!(bad, RefractiveIndex::new(1.0).unwrap_err());
    }
}
