//! The single-scattering direct-light shader of the swatch: at each pixel's first hit,
//! `int S(wi, wo, h) L(wi) V(wi) dwi` over the sphere with the exact binary visibility `V`
//! (rays through the fibres, the hit's own fibre excluded), by deterministic quadrature: the
//! environment on a spherical Fibonacci set of equal weights (the directions that meet the
//! sphere light excluded: it hides the environment there) and the light on a Fibonacci
//! spiral over the cone it subtends ([`super::light::SphereLight::cone_directions`]), each
//! direction weighing the cone's solid angle over their count. This is the path tracer's
//! first bounce ([`super::path`]) without the light from other fibres, and Gerard's
//! "path-traced reference render using the single scattering approximation" made
//! deterministic.
//!
//! The visibility is computed once ([`DirectLighting::new`], in parallel); shading with a
//! model ([`DirectLighting::shade`]) then only evaluates `S`, so every model of
//! [`crate::registry::MODELS`] and the reference far and near fields are shaded on the same
//! hits from the same directions with the same visibility: their images differ only by `S`.

use super::light::SwatchLight;
use super::{Swatch, SwatchHit};
use crate::bcsdf::Bcsdf;
use crate::error::ParamError;
use crate::quadrature::fibonacci_directions;
use crate::render::camera::Camera;
use crate::render::Image;
use crate::world::WorldBcsdf;
use glam::DVec3;
use rayon::prelude::*;

/// The direct shader's quadrature. Every field is checked by [`DirectLighting::new`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DirectSettings {
    /// Environment directions (spherical Fibonacci set), in `[1, 65536]`.
    pub environment_directions: usize,
    /// Directions over the light's cone, in `[1, 4096]`.
    pub light_directions: usize,
}

impl Default for DirectSettings {
    /// 256 environment directions and 16 over the light.
    fn default() -> Self {
        Self {
            environment_directions: 256,
            light_directions: 16,
        }
    }
}

/// The lit directions of every pixel's first hit, ready to shade with any model.
#[derive(Clone, Debug)]
pub struct DirectLighting {
    size: usize,
    /// Per pixel: the hit and its unoccluded directions with `weight * radiance`.
    pixels: Vec<Option<(SwatchHit, Vec<Incoming>)>>,
    environment: [f64; 3],
}

/// One lit direction: `weight * radiance` arrives along `direction`.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Incoming {
    direction: DVec3,
    radiance: [f64; 3],
}

impl DirectLighting {
    /// The lit directions of the first hits of `camera`'s pixels on `swatch` under `light`.
    ///
    /// # Errors
    /// [`ParamError::OutOfRange`] naming a direction count outside its domain
    /// ([`DirectSettings`]) or a bad light ([`SwatchLight::check`]).
    pub fn new(
        swatch: &Swatch,
        camera: &Camera,
        light: &SwatchLight,
        settings: &DirectSettings,
    ) -> Result<Self, ParamError> {
        light.check()?;
        let n = settings.environment_directions;
        ParamError::check(
            "environment_directions",
            n as f64,
            "must be in [1, 65536]",
            |n| (1.0..=65536.0).contains(&n),
        )?;
        let m = settings.light_directions;
        ParamError::check("light_directions", m as f64, "must be in [1, 4096]", |m| {
            (1.0..=4096.0).contains(&m)
        })?;
        let sphere_rule = fibonacci_directions(n);
        let pixels = swatch
            .camera_hits(camera)
            .into_par_iter()
            .map(|hit| hit.map(|h| (h, incoming(swatch, &h, light, &sphere_rule, m))))
            .collect();
        Ok(Self {
            size: camera.size,
            pixels,
            environment: light.environment,
        })
    }

    /// The image of `model` (world-space evaluation, [`WorldBcsdf::eval_world`], with each
    /// hit's `h`; far-field models ignore it); pixels without a fibre show the environment.
    pub fn shade(&self, model: &dyn Bcsdf<f64>) -> Image {
        let pixels = self.pixels.iter().map(|p| self.pixel(model, p)).collect();
        self.image(pixels)
    }

    /// [`DirectLighting::shade`] on rayon's threads, for a model that is `Sync`.
    pub fn par_shade(&self, model: &(dyn Bcsdf<f64> + Sync)) -> Image {
        let pixels = self
            .pixels
            .par_iter()
            .map(|p| self.pixel(model, p))
            .collect();
        self.image(pixels)
    }

    fn image(&self, pixels: Vec<[f64; 3]>) -> Image {
        Image {
            size: self.size,
            pixels,
            covered: self.pixels.iter().map(Option::is_some).collect(),
        }
    }

    fn pixel(
        &self,
        model: &dyn Bcsdf<f64>,
        pixel: &Option<(SwatchHit, Vec<Incoming>)>,
    ) -> [f64; 3] {
        let Some((hit, lit)) = pixel else {
            return self.environment;
        };
        let mut out = [0.0; 3];
        for l in lit {
            let s = model.eval_world(hit.tangent, l.direction, DVec3::Z, hit.h);
            for c in 0..3 {
                out[c] += s[c] * l.radiance[c];
            }
        }
        out
    }
}

/// The unoccluded directions at `hit` with `weight * radiance`: the environment's (those not
/// towards the light) and the light's.
fn incoming(
    swatch: &Swatch,
    hit: &SwatchHit,
    light: &SwatchLight,
    sphere_rule: &[DVec3],
    light_directions: usize,
) -> Vec<Incoming> {
    let weight = 4.0 * core::f64::consts::PI / sphere_rule.len() as f64;
    let visible = |w: DVec3| swatch.unoccluded(hit.point, w, hit.strand);
    let mut out: Vec<Incoming> = sphere_rule
        .iter()
        .filter(|&&w| light.sphere.is_none_or(|s| s.pdf(hit.point, w) == 0.0))
        .filter(|&&w| visible(w))
        .map(|&w| Incoming {
            direction: w,
            radiance: light.environment.map(|l| l * weight),
        })
        .collect();
    if let Some(sphere) = light.sphere {
        let each = sphere.solid_angle(hit.point) / light_directions as f64;
        out.extend(
            sphere
                .cone_directions(hit.point, light_directions)
                .into_iter()
                .filter(|&w| visible(w))
                .map(|w| Incoming {
                    direction: w,
                    radiance: sphere.radiance.map(|l| l * each),
                }),
        );
    }
    out
}
