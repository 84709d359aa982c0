//! The swatch's light: a constant environment and, optionally, a spherical area light
//! outside the swatch that can be sampled (uniformly within the cone it subtends: Shirley
//! and Wang 1992, "Distribution ray tracing: theory and practice"; pbrt-v4 `Sphere::Sample`
//! for a reference point outside the sphere). The sphere hides the environment behind it.

use crate::error::ParamError;
use glam::DVec3;

/// A spherical light emitting `radiance` from every point of its surface, towards every side.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SphereLight {
    /// Its centre.
    pub centre: DVec3,
    /// Its radius, positive.
    pub radius: f64,
    /// Its radiance per linear RGB channel, finite and non-negative.
    pub radiance: [f64; 3],
}

/// The light of a swatch render.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SwatchLight {
    /// The environment's radiance from every direction (linear RGB, finite, non-negative).
    pub environment: [f64; 3],
    /// The area light, if any. It must lie outside the box `[-2, 2]^3`, which holds the
    /// swatch ([`SwatchLight::check`]), so that every ray from a fibre towards it meets the
    /// fibres (if at all) before it.
    pub sphere: Option<SphereLight>,
}

impl Default for SwatchLight {
    /// A dim grey-blue environment and a warm key light of radius 1, about 8 away towards the
    /// upper right in front of the swatch.
    fn default() -> Self {
        Self {
            environment: [0.25, 0.27, 0.3],
            sphere: Some(SphereLight {
                centre: DVec3::new(3.0, 4.0, 6.0),
                radius: 1.0,
                radiance: [40.0, 37.0, 32.0],
            }),
        }
    }
}

/// The half-extent of the box the light must lie outside of.
pub const SWATCH_BOX: f64 = 2.0;

/// A direction towards the light with its solid-angle density.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LightSample {
    /// The unit direction.
    pub direction: DVec3,
    /// Its density over solid angle.
    pub pdf: f64,
}

impl SwatchLight {
    /// A constant environment of `radiance` and no area light (the white furnace when it is
    /// 1 and the hair absorbs nothing).
    pub fn environment_only(radiance: [f64; 3]) -> Self {
        Self {
            environment: radiance,
            sphere: None,
        }
    }

    /// Checks the radiances and the sphere's place.
    ///
    /// # Errors
    /// [`ParamError::OutOfRange`] for a negative or non-finite radiance, a radius that is not
    /// positive and finite, or a sphere reaching into the box `[-2, 2]^3`.
    pub fn check(&self) -> Result<(), ParamError> {
        let rgb = |name, c: [f64; 3]| {
            c.iter().try_for_each(|&v| {
                ParamError::check(name, v, "must be finite and >= 0", |v| v >= 0.0).map(|_| ())
            })
        };
        rgb("environment radiance", self.environment)?;
        if let Some(s) = self.sphere {
            rgb("light radiance", s.radiance)?;
            ParamError::check("light radius", s.radius, "must be positive", |r| r > 0.0)?;
            let outside = (s.centre.abs() - DVec3::splat(SWATCH_BOX)).max(DVec3::ZERO);
            let gap = outside.length() - s.radius;
            ParamError::check(
                "light distance from the swatch box",
                gap,
                "the sphere must lie outside the box [-2, 2]^3",
                |g| g > 0.0,
            )?;
        }
        Ok(())
    }

    /// The radiance arriving along a ray leaving the swatch in direction `w` from `from`: the
    /// light's if the ray meets the sphere, the environment's otherwise.
    pub fn escaped(&self, from: DVec3, w: DVec3) -> [f64; 3] {
        match self.sphere {
            Some(s) if s.pdf(from, w) > 0.0 => s.radiance,
            _ => self.environment,
        }
    }
}

impl SphereLight {
    /// `1 - cos` of the half-angle of the cone the sphere subtends from `from`, and the unit
    /// direction to its centre (`None` from inside the sphere).
    fn cone(&self, from: DVec3) -> Option<(f64, DVec3)> {
        let to_centre = self.centre - from;
        let d2 = to_centre.length_squared();
        let sin2 = self.radius * self.radius / d2;
        if sin2.is_nan() || sin2 >= 1.0 {
            return None;
        }
        // 1 - cos = sin^2 / (1 + cos), accurate for a small, far light.
        let one_minus_cos = sin2 / (1.0 + (1.0 - sin2).sqrt());
        Some((one_minus_cos, to_centre / d2.sqrt()))
    }

    /// The solid angle the sphere subtends from `from` (0 from inside it).
    pub fn solid_angle(&self, from: DVec3) -> f64 {
        self.cone(from).map_or(0.0, |(one_minus_cos, _)| {
            core::f64::consts::TAU * one_minus_cos
        })
    }

    /// The density of [`SphereLight::sample`] at direction `w` (unit) from `from`: one over
    /// the cone's solid angle inside the cone, 0 outside.
    pub fn pdf(&self, from: DVec3, w: DVec3) -> f64 {
        match self.cone(from) {
            Some((one_minus_cos, axis)) if 1.0 - w.dot(axis) < one_minus_cos => {
                1.0 / (core::f64::consts::TAU * one_minus_cos)
            }
            _ => 0.0,
        }
    }

    /// A direction uniform within the cone the sphere subtends from `from`, from the uniform
    /// numbers `u` in `[0, 1)` (`None` from inside the sphere).
    pub fn sample(&self, from: DVec3, u: [f64; 2]) -> Option<LightSample> {
        let (one_minus_cos, axis) = self.cone(from)?;
        Some(LightSample {
            direction: cone_direction(axis, one_minus_cos * u[0], u[1]),
            pdf: 1.0 / (core::f64::consts::TAU * one_minus_cos),
        })
    }

    /// `n` fixed directions covering the cone from `from` evenly (a Fibonacci spiral on the
    /// cap: equal areas, each standing for `solid_angle / n`), for deterministic quadrature.
    pub fn cone_directions(&self, from: DVec3, n: usize) -> Vec<DVec3> {
        let Some((one_minus_cos, axis)) = self.cone(from) else {
            return Vec::new();
        };
        let golden = 0.5 * (3.0 - 5f64.sqrt());
        (0..n)
            .map(|k| {
                let v = one_minus_cos * (k as f64 + 0.5) / n as f64;
                cone_direction(axis, v, (k as f64 * golden).fract())
            })
            .collect()
    }
}

/// The unit direction at `1 - cos(theta) = one_minus_cos` from `axis` and azimuth
/// `2 pi turn` about it.
fn cone_direction(axis: DVec3, one_minus_cos: f64, turn: f64) -> DVec3 {
    let cos = 1.0 - one_minus_cos;
    let sin = (one_minus_cos * (2.0 - one_minus_cos)).max(0.0).sqrt();
    let (s, c) = (core::f64::consts::TAU * turn).sin_cos();
    let (a, b) = axis.any_orthonormal_pair();
    (axis * cos + a * (sin * c) + b * (sin * s)).normalize()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn samples_lie_in_the_cone_with_the_pdf() {
        let light = SwatchLight::default().sphere.unwrap();
        let from = DVec3::new(0.1, -0.2, 0.0);
        let s = light.sample(from, [0.3, 0.7]).unwrap();
        assert!((light.pdf(from, s.direction) - s.pdf).abs() < 1e-12 * s.pdf);
        assert_eq!(light.pdf(from, -s.direction), 0.0);
        assert!((s.pdf * light.solid_angle(from) - 1.0).abs() < 1e-12);
        for w in light.cone_directions(from, 16) {
            assert!(light.pdf(from, w) > 0.0);
        }
    }

    #[test]
    fn bad_lights_are_refused() {
        let mut light = SwatchLight::default();
        assert!(light.check().is_ok());
        light.environment[1] = -1.0;
        assert!(light.check().is_err());
        let mut inside = SwatchLight::default();
        inside.sphere.as_mut().unwrap().centre = DVec3::new(0.0, 0.0, 2.5);
        assert!(inside.check().is_err());
    }
}
