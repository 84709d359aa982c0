//! The white furnace of a renderer's BSDF: with no absorption, the integral of S over all
//! incident directions is 1 for every view, by deterministic quadrature
//! ([`crate::diagnostics::white_furnace`]), reported with its worst view.
//!
//! **Accuracy.** The quadrature's own error bounds what the furnace can resolve. At
//! [`FurnaceSettings::default`] (the sphere rule (32, 8, 512): 131,072 directions) hairmath's
//! reference `ChiangHair` gives `|albedo - 1| <= 1e-6` for beta_m and beta_n in [0.1, 1] at
//! every view of the settings (`tests/testing_harness.rs`; measured worst -2.1e-7 at
//! beta_n = 1, h = 1, the midpoint rule in phi meeting the logistic's kink at +-pi; below
//! 1e-11 at beta_n = 0.1 and 0.3); narrower lobes need a finer rule
//! ([`FurnaceSettings::sphere`]). A model that loses or gains energy by more than
//! about 1e-5 is therefore caught, whatever its lobes.

use crate::bcsdf::Bcsdf;
use crate::diagnostics::{white_furnace, Furnace, FurnaceCase, SphereSize};
use core::fmt;

/// The quadrature and the views of a [`furnace`] check.
#[derive(Clone, Debug, PartialEq)]
pub struct FurnaceSettings {
    /// The sphere rule over wi.
    pub sphere: SphereSize,
    /// The inclinations theta_o of wo, degrees (its azimuth is
    /// [`crate::diagnostics::VIEW_AZIMUTH`]).
    pub theta_o_deg: Vec<f64>,
    /// The offsets h (a far-field model is evaluated at h = 0 only).
    pub offsets: Vec<f64>,
}

impl Default for FurnaceSettings {
    /// The sphere rule (32, 8, 512); theta_o = 0, 30, -60 and 85 degrees; h = -1, -0.9, 0, 0.5
    /// and 1 (the module documentation states the rule's accuracy).
    fn default() -> Self {
        FurnaceSettings {
            sphere: SphereSize::new(32, 8, 512),
            theta_o_deg: vec![0.0, 30.0, -60.0, 85.0],
            offsets: vec![-1.0, -0.9, 0.0, 0.5, 1.0],
        }
    }
}

/// The outcome of a [`furnace`] check.
#[derive(Clone, Debug, PartialEq)]
pub struct FurnaceReport {
    /// The albedo of every view and the worst signed error.
    pub furnace: Furnace,
    /// The sphere rule used.
    pub sphere: SphereSize,
}

impl FurnaceReport {
    /// The view whose `albedo - 1` is largest in magnitude (none without views).
    pub fn worst_case(&self) -> Option<&FurnaceCase> {
        self.furnace
            .cases
            .iter()
            .max_by(|a, b| a.error.abs().total_cmp(&b.error.abs()))
    }

    /// Whether there was a view and every view's albedo is 1 within `tolerance` in every
    /// channel (a NaN fails).
    pub fn passes(&self, tolerance: f64) -> bool {
        !self.furnace.cases.is_empty()
            && self
                .furnace
                .cases
                .iter()
                .flat_map(|c| c.albedo)
                .all(|a| (a - 1.0).abs() <= tolerance)
    }
}

impl fmt::Display for FurnaceReport {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "white furnace (sigma_a = 0) over {} views, sphere rule {}: ",
            self.furnace.cases.len(),
            self.sphere
        )?;
        match self.worst_case() {
            None => write!(f, "no views"),
            Some(c) => write!(
                f,
                "worst albedo - 1 = {:+.3e} at theta_o {} degrees, h {} (albedo per channel \
                 {:?}; energy is {})",
                c.error,
                c.theta_o_deg,
                c.h,
                c.albedo,
                if c.error > 0.0 { "gained" } else { "lost" }
            ),
        }
    }
}

/// The white furnace of `model`, which must be built with no absorption (sigma_a = 0): the
/// albedo `int S(wi, wo, h) dwi` at every view of `settings`. A BSDF given as a closure goes
/// through [`from_eval`](super::from_eval).
pub fn furnace<M: Bcsdf<f64> + ?Sized>(model: &M, settings: &FurnaceSettings) -> FurnaceReport {
    FurnaceReport {
        furnace: white_furnace(
            model,
            &settings.sphere.rule(),
            &settings.theta_o_deg,
            &settings.offsets,
        ),
        sphere: settings.sphere,
    }
}
