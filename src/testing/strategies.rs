//! proptest strategies for a renderer's own property tests: valid hair parameters over their
//! physical ranges and queries that include the hard cases of `docs/ARCHITECTURE.md`.
//!
//! Each strategy mixes fixed hard values (drawn about a third of the time) with a uniform range,
//! so that a hundred proptest cases visit the ends of every domain; proptest shrinks a failing
//! case towards the low end of each range. The ranges:
//!
//! | parameter | hard values | range |
//! | --- | --- | --- |
//! | beta_m, beta_n ([`roughness`]) | 0.01 (variance 1e-4, where I0 overflows outside log space), 1 | [0.01, 1] |
//! | alpha ([`tilt`]) | 0, 2 degrees, +-10 degrees | [-10, 10] degrees |
//! | eta ([`index`]) | 1.001 (close to 1), 1.55 (human hair), 3 | [1.001, 3] |
//! | melanin ([`melanin`]) | 0, 8 | [0, 8] each |
//! | sigma_a ([`absorption`]) | 0 (the furnace's), 20 (very dark) | from melanin, or [0, 20] per channel |
//! | h ([`offset`]) | -1, 0, 1 | [-1, 1] |
//! | directions ([`direction`]) | along the tangent both ways, grazing, perpendicular ([`HARD_DIRECTIONS`]) | uniform on the sphere |
//!
//! [`query`] pairs two directions as the hard cases do: `wi = wo`, `wi = -wo`, the same
//! azimuth (phi = 0), opposite azimuths (phi = pi), or independent.
//!
//! ```
//! use hairmath::bcsdf::{Bcsdf, ChiangHair};
//! use hairmath::testing::strategies::{hair_params, query};
//! use proptest::prelude::*;
//!
//! proptest! {
//!     #![proptest_config(ProptestConfig::with_cases(32))]
//!     // In a renderer's test file this function carries `#[test]`.
//!     fn s_is_finite_and_non_negative(params in hair_params(), q in query()) {
//!         let s = ChiangHair::<f64>::new(&params).eval(&q);
//!         prop_assert!(s.iter().all(|v| v.is_finite() && *v >= 0.0), "{s:?}");
//!     }
//! }
//! s_is_finite_and_non_negative();
//! ```

use crate::absorption::Absorption;
use crate::bcsdf::{Query, RandomNumbers};
use crate::geometry::{local_direction, V3};
use crate::params::{
    AzimuthalRoughness, CuticleTilt, HairParams, LongitudinalRoughness, RefractiveIndex,
};
use core::f64::consts::PI;
use proptest::prelude::*;

/// The sine of the inclination of the grazing hard directions: `1 - 1e-6` (0.08 degrees from
/// the tangent).
pub const GRAZING_SIN_THETA: f64 = 1.0 - 1e-6;

/// The hard directions as (sin theta, phi) in the local frame (tangent +X): along the tangent
/// both ways, grazing both ways, perpendicular at phi = 0 and pi, and three ordinary ones
/// placed so that pairs of them have phi = 0 and phi = pi.
pub const HARD_DIRECTIONS: [(f64, f64); 9] = [
    (1.0, 0.0),
    (-1.0, 0.0),
    (GRAZING_SIN_THETA, 0.0),
    (-GRAZING_SIN_THETA, PI),
    (0.0, 0.0),
    (0.0, PI),
    (0.5, 0.3),
    (-0.5, 0.3 + PI),
    (0.5, 0.3 + PI),
];

/// The unit direction at inclination sine `sin_theta` and azimuth `phi` (local frame).
pub fn direction_at(sin_theta: f64, phi: f64) -> V3<f64> {
    let sin_theta = sin_theta.clamp(-1.0, 1.0);
    local_direction(sin_theta, (1.0 - sin_theta * sin_theta).sqrt(), phi)
}

/// A value from `hard` about a third of the time, otherwise uniform in `range`.
fn with_hard_values(
    hard: &[f64],
    range: core::ops::RangeInclusive<f64>,
) -> impl Strategy<Value = f64> + Clone {
    let hard = proptest::sample::select(hard.to_vec());
    prop_oneof![1 => hard, 2 => range]
}

/// Roughness beta (beta_m or beta_n): 0.01 and 1, or uniform in [0.01, 1].
pub fn roughness() -> impl Strategy<Value = f64> + Clone {
    with_hard_values(&[0.01, 1.0], 0.01..=1.0)
}

/// The cuticle tilt: 0, 2 degrees and +-10 degrees, or uniform in [-10, 10] degrees.
pub fn tilt() -> impl Strategy<Value = CuticleTilt> + Clone {
    with_hard_values(&[0.0, 2.0, -10.0, 10.0], -10.0..=10.0)
        .prop_filter_map("a tilt below 90 degrees", |d| {
            CuticleTilt::from_degrees(d).ok()
        })
}

/// The index of refraction: 1.001, 1.55 and 3, or uniform in [1.001, 3].
pub fn index() -> impl Strategy<Value = RefractiveIndex> + Clone {
    with_hard_values(&[1.001, 1.55, 3.0], 1.001..=3.0)
        .prop_filter_map("an index in (1, 3]", |e| RefractiveIndex::new(e).ok())
}

/// Melanin concentrations (eumelanin, pheomelanin), each 0 or 8 (the ends of hair's range:
/// blonde to black) or uniform in [0, 8].
pub fn melanin() -> impl Strategy<Value = (f64, f64)> + Clone {
    let concentration = || with_hard_values(&[0.0, 8.0], 0.0..=8.0);
    (concentration(), concentration())
}

/// Absorption: none, very dark (20 per channel), from [`melanin`], or any colour with each
/// channel in [0, 20].
pub fn absorption() -> impl Strategy<Value = Absorption> + Clone {
    let melanin = melanin().prop_filter_map("valid melanin", |(e, p)| {
        Absorption::from_melanin(e, p).ok()
    });
    let colour = [0.0..=20.0_f64, 0.0..=20.0_f64, 0.0..=20.0_f64]
        .prop_filter_map("valid sigma_a", |rgb| Absorption::new(rgb).ok());
    prop_oneof![
        Just(Absorption::NONE),
        Just(20.0).prop_filter_map("valid sigma_a", |s| Absorption::grey(s).ok()),
        melanin,
        colour
    ]
}

/// Valid [`HairParams`] over the physical ranges of the module's table.
pub fn hair_params() -> impl Strategy<Value = HairParams> + Clone {
    let beta_m = roughness().prop_filter_map("beta_m", |b| LongitudinalRoughness::new(b).ok());
    let beta_n = roughness().prop_filter_map("beta_n", |b| AzimuthalRoughness::new(b).ok());
    (beta_m, beta_n, tilt(), index(), absorption()).prop_map(
        |(beta_m, beta_n, alpha, eta, sigma_a)| HairParams {
            beta_m,
            beta_n,
            alpha,
            eta,
            sigma_a,
        },
    )
}

/// The offset h: -1, 0 and 1, or uniform in [-1, 1].
pub fn offset() -> impl Strategy<Value = f64> + Clone {
    with_hard_values(&[-1.0, 0.0, 1.0], -1.0..=1.0)
}

/// A unit direction in the local frame: one of [`HARD_DIRECTIONS`], or uniform on the sphere.
pub fn direction() -> impl Strategy<Value = V3<f64>> + Clone {
    let hard = proptest::sample::select(HARD_DIRECTIONS.to_vec())
        .prop_map(|(sin, phi)| direction_at(sin, phi));
    let uniform = (-1.0..=1.0_f64, -PI..=PI).prop_map(|(sin, phi)| direction_at(sin, phi));
    prop_oneof![1 => hard, 2 => uniform]
}

/// A query (wi, wo, h): a [`direction`] wo and, for wi, `wo` itself, `-wo`, a direction at
/// wo's azimuth (phi = 0) or the opposite one (phi = pi), or an independent [`direction`];
/// h from [`offset`].
pub fn query() -> impl Strategy<Value = Query<f64>> + Clone {
    let inclination = with_hard_values(&[-1.0, -GRAZING_SIN_THETA, 0.0, 1.0], -1.0..=1.0);
    let pair = (direction(), direction(), inclination, 0..5_u8).prop_map(
        |(wo, other, sin_i, relation)| {
            let phi_o = wo.z.atan2(wo.y);
            let wi = match relation {
                0 => wo,
                1 => wo.scale(-1.0),
                2 => direction_at(sin_i, phi_o),
                3 => direction_at(sin_i, phi_o + PI),
                _ => other,
            };
            (wi, wo)
        },
    );
    (pair, offset()).prop_map(|((wi, wo), h)| Query::new(wi, wo, h))
}

/// Uniform numbers in [0, 1) for [`SampledBcsdf::sample`](crate::bcsdf::SampledBcsdf::sample),
/// each 0 or the largest `f64` below 1 about a quarter of the time.
pub fn random_numbers() -> impl Strategy<Value = RandomNumbers<f64>> + Clone {
    let below_one = 1.0 - f64::EPSILON / 2.0;
    let u = || {
        let ends = proptest::sample::select(vec![0.0, below_one]);
        prop_oneof![1 => ends, 3 => 0.0..1.0_f64]
    };
    (u(), u(), u(), u()).prop_map(|(lobe, longitudinal, cone, offset)| RandomNumbers {
        lobe,
        longitudinal,
        cone,
        offset,
    })
}
