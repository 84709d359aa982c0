//! Longitudinal scattering lobes M(theta): Marschner's Gaussian, the Henyey-Greenstein lobe as
//! Gerard uses it, and d'Eon's energy-conserving lobe with its log-space Bessel function.
//! Gerard's closed forms of the asymmetry g(beta) are in [`crate::models`].

mod bessel;
mod deon;
mod gaussian;
mod henyey_greenstein;

pub use bessel::{i0, i0e_split, i0e_split_reduced, log_i0, log_i0e, BesselForm};
pub use deon::{deon_lobe, deon_lobe_sample_cos_theta, DeonLobe};
pub use gaussian::gaussian_lobe;
pub use henyey_greenstein::{hg_circle_factor, hg_gerard_printed, HenyeyGreenstein};
