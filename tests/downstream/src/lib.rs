//! What a renderer does with hairmath, compiled against the library with no default features:
//! shade a hair point from its world-space tangent and directions with glam vectors, sample
//! the next direction, and shade a batch of points at once.

use hairmath::bcsdf::{BatchReal, ChiangHair, Model, RandomNumbers};
use hairmath::glam::{Vec3, Vec3A};
use hairmath::params::HairParams;
use hairmath::world::{eval_batch_world, WorldBcsdf, WorldSampledBcsdf};

/// The renderer's hair material: brown hair at hairmath's defaults, in `f32`.
pub struct HairMaterial {
    model: ChiangHair<f32>,
    lanes: ChiangHair<BatchReal>,
}

impl Default for HairMaterial {
    fn default() -> Self {
        let reference = ChiangHair::new(&HairParams::default());
        HairMaterial {
            model: reference.instantiate(),
            lanes: reference.instantiate(),
        }
    }
}

impl HairMaterial {
    /// Radiance scattered towards `to_camera` from a light in direction `to_light` of
    /// radiance `light`, at a strand point with tangent `tangent` (the cosine factor of the
    /// rendering equation included).
    pub fn shade(&self, tangent: Vec3, to_light: Vec3, to_camera: Vec3, light: Vec3) -> Vec3 {
        let s = self.model.eval_world(tangent, to_light, to_camera, 0.0);
        let cos = (1.0 - to_light.dot(tangent.normalize()).powi(2))
            .max(0.0)
            .sqrt();
        Vec3::from(s) * light * cos
    }

    /// The next path direction and its throughput weight, from four uniform numbers.
    pub fn sample(&self, tangent: Vec3, to_camera: Vec3, h: f32, u: [f32; 4]) -> (Vec3, Vec3) {
        let u = RandomNumbers {
            lobe: u[0],
            longitudinal: u[1],
            cone: u[2],
            offset: u[3],
        };
        let sample = self.model.sample_world(tangent, to_camera, h, u);
        (sample.wi, Vec3::from(sample.weight()))
    }

    /// [`HairMaterial::shade`]'s S for many points at once (SIMD lanes).
    ///
    /// # Errors
    /// hairmath's batch error, naming the first bad sample.
    pub fn eval_many(
        &self,
        tangents: &[Vec3],
        to_light: &[Vec3],
        to_camera: &[Vec3],
    ) -> Result<Vec<Vec3A>, hairmath::bcsdf::BatchError> {
        let h = vec![0.0; tangents.len()];
        let mut out = vec![[0.0; 3]; tangents.len()];
        eval_batch_world(&self.lanes, tangents, to_light, to_camera, &h, &mut out)?;
        Ok(out.into_iter().map(Vec3A::from).collect())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_renderer_shades_samples_and_batches_in_world_space() {
        let material = HairMaterial::default();
        let tangent = Vec3::new(0.0, -2.0, 0.0); // any length
        let to_light = Vec3::new(0.0, 0.6, 0.8);
        let to_camera = Vec3::new(1.0, 0.0, 0.0);
        let colour = material.shade(tangent, to_light, to_camera, Vec3::ONE);
        assert!(colour.is_finite() && colour.min_element() > 0.0, "{colour}");
        // Brown hair reflects more red than blue.
        assert!(colour.x > colour.z, "{colour}");

        let (wi, weight) = material.sample(tangent, to_camera, 0.2, [0.3, 0.5, 0.7, 0.1]);
        assert!((wi.length() - 1.0).abs() < 1e-5, "{wi}");
        assert!(
            weight.is_finite() && weight.min_element() >= 0.0,
            "{weight}"
        );

        let many = material
            .eval_many(&[tangent; 9], &[to_light; 9], &[to_camera; 9])
            .unwrap();
        let single = Vec3A::from(material.model.eval_world(tangent, to_light, to_camera, 0.0));
        for value in many {
            assert!((value - single).abs().max_element() <= 1e-3 * single.max_element());
        }
        let error = material
            .eval_many(&[Vec3::ZERO], &[to_light], &[to_camera])
            .unwrap_err();
        assert!(error.to_string().contains("tangent"), "{error}");
    }
}
