//! The light of the images: a procedural sky and a directional light.

use crate::error::ParamError;
use crate::sh::project_with_nodes;
use glam::DVec3;

/// Up in the grooms' frame: the sky's radiance steps from the ground's to the horizon's where
/// a direction crosses the plane orthogonal to it.
pub const UP: DVec3 = DVec3::Y;

/// A procedural sky: a gradient from the ground's colour below the horizon to the zenith's
/// above (in `y`, the grooms' up), and a sun glow `sun_radiance max(0, w.sun)^sun_exponent`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Sky {
    /// The radiance straight up.
    pub zenith: [f64; 3],
    /// The radiance at the horizon.
    pub horizon: [f64; 3],
    /// The radiance below the horizon.
    pub ground: [f64; 3],
    /// Towards the sun (unit length).
    pub sun: DVec3,
    /// The glow's peak radiance.
    pub sun_radiance: [f64; 3],
    /// The glow's exponent (its width).
    pub sun_exponent: f64,
}

impl Default for Sky {
    /// A blue sky over a dark brown ground with a warm glow around a sun 40 degrees up.
    fn default() -> Self {
        Self {
            zenith: [0.25, 0.45, 0.9],
            horizon: [0.8, 0.85, 0.9],
            ground: [0.15, 0.12, 0.1],
            sun: DVec3::new(0.5, 0.64, 0.58).normalize(),
            sun_radiance: [3.0, 2.6, 2.0],
            sun_exponent: 16.0,
        }
    }
}

impl Sky {
    /// The radiance arriving from direction `w`.
    pub fn radiance(&self, w: DVec3) -> [f64; 3] {
        let up = w.dot(UP).clamp(-1.0, 1.0);
        let glow = w.dot(self.sun).max(0.0).powf(self.sun_exponent);
        core::array::from_fn(|c| {
            let base = if up >= 0.0 {
                self.horizon[c] + (self.zenith[c] - self.horizon[c]) * up.sqrt()
            } else {
                self.ground[c]
            };
            base + self.sun_radiance[c] * glow
        })
    }

    /// Its coefficients per channel for bands `l <= lmax` (the crate's convention), by the
    /// product rule with 256 x 512 nodes (the sky's step at the horizon makes it not
    /// band-limited; the tests measure the rule's convergence).
    ///
    /// # Errors
    /// As [`project_with_nodes`].
    pub fn coefficients(&self, lmax: usize) -> Result<[Vec<f64>; 3], ParamError> {
        let channel = |c: usize| project_with_nodes(lmax, 256, 512, |w| self.radiance(w)[c]);
        Ok([channel(0)?, channel(1)?, channel(2)?])
    }
}

/// A directional light.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DirectionalLight {
    /// Towards the light (unit length).
    pub direction: DVec3,
    /// Its radiance per channel (times the solid angle it subtends).
    pub radiance: [f64; 3],
}

impl Default for DirectionalLight {
    /// A warm key light from the upper right, in front of the strands (towards the camera,
    /// `+Z`).
    fn default() -> Self {
        Self {
            direction: DVec3::new(0.6, 0.6, 0.5).normalize(),
            radiance: [2.0, 1.9, 1.7],
        }
    }
}
