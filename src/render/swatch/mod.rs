//! A procedural hair swatch and two renderers of it (issue 16): a path tracer with the Chiang
//! model ([`path`]) and a single-scattering direct-light shader for any model ([`direct`]),
//! under the same light ([`light`]), seen by the orthographic camera of [`crate::render`].
//!
//! The swatch: `fibres` gently wavy fibres hanging from `y = 1` to `y = -1` (their tangent,
//! root to tip, is about `-Y`), spread over `x` in `[-1, 1]` in `layers` layers one behind the
//! other (`-Z`), each a polyline of capsule-free cylinders ([`Occluders`], opaque). The camera
//! looks along `-Z` ([`Camera::framing`]), so the swatch is seen face on.
//!
//! **The offset h.** Chiang et al. 2016 (section 4) and pbrt-v4 (`HairBxDF`, whose geometry
//! the crate's [`crate::bcsdf::ChiangHair`] follows) take `h = sin(gamma_o)` in `[-1, 1]`: where
//! the ray from the viewer meets the fibre across its width, in units of its radius. With the
//! crate's local frame (tangent `+X`, azimuth `atan2(w.z, w.y)`) and `wo` along `+Z`, pbrt's
//! curve puts `h` along `+Y` (the surface normal at the hit is `(0, h, sqrt(1 - h^2))`); in
//! world space that axis is `wo x tangent`, so `h` is the hit's offset from the axis along
//! `normalize(wo x tangent)`, divided by the radius ([`offset_of`]; a test checks that the R
//! lobe then peaks at the mirror direction of the surface normal there).

pub mod direct;
pub mod light;
pub mod path;

use super::camera::Camera;
use crate::error::ParamError;
use crate::strands::occluders::{Cylinder, Occluders, Opacity};
use crate::strands::{PointAttribute, SegmentCounts, Strands};
use glam::{DVec3, Vec3};
use rand_pcg::rand_core::{RngCore, SeedableRng};
use rand_pcg::Pcg64Mcg;
use rayon::prelude::*;

/// The largest fibre count of a swatch.
pub const MAX_FIBRES: usize = 65_536;

/// What swatch to build. Every field is checked by [`Swatch::new`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SwatchSettings {
    /// The number of fibres, in `[1, 65536]`.
    pub fibres: usize,
    /// The layers the fibres are dealt into, one behind the other, in `[1, 64]`.
    pub layers: usize,
    /// Points per fibre (segments + 1), in `[2, 1024]`.
    pub points: usize,
    /// The fibres' diameter (the swatch is 2 wide and 2 tall), in `(0, 0.2]`.
    pub thickness: f32,
    /// The distance between layers along `z`, in `[0, 1]`.
    pub layer_spacing: f32,
    /// The amplitude of each fibre's sine wave across `x`, in `[0, 0.5]`.
    pub wave_amplitude: f32,
    /// Waves along a fibre's length, in `[0, 16]`.
    pub waves: f32,
    /// The seed of the fibres' jitter and phases.
    pub seed: u64,
}

impl Default for SwatchSettings {
    /// 300 fibres of diameter 0.012 in three layers 0.012 apart, 1.5 waves of amplitude 0.03
    /// each, 24 points per fibre: the layers overlap so that little background shows through.
    fn default() -> Self {
        Self {
            fibres: 300,
            layers: 3,
            points: 24,
            thickness: 0.012,
            layer_spacing: 0.012,
            wave_amplitude: 0.03,
            waves: 1.5,
            seed: 1,
        }
    }
}

impl SwatchSettings {
    fn check(&self) -> Result<(), ParamError> {
        let count = |name, v: usize, lo: usize, hi: usize, allowed| {
            ParamError::check(name, v as f64, allowed, |v| {
                (lo as f64..=hi as f64).contains(&v)
            })
        };
        count(
            "fibres",
            self.fibres,
            1,
            MAX_FIBRES,
            "must be in [1, 65536]",
        )?;
        count("layers", self.layers, 1, 64, "must be in [1, 64]")?;
        count("points", self.points, 2, 1024, "must be in [2, 1024]")?;
        let real = |name, v: f32, lo: f64, hi: f64, allowed| {
            ParamError::check(name, f64::from(v), allowed, |v| v >= lo && v <= hi)
        };
        real(
            "thickness",
            self.thickness,
            1e-6,
            0.2,
            "must be in (0, 0.2]",
        )?;
        real(
            "layer_spacing",
            self.layer_spacing,
            0.0,
            1.0,
            "must be in [0, 1]",
        )?;
        real(
            "wave_amplitude",
            self.wave_amplitude,
            0.0,
            0.5,
            "must be in [0, 0.5]",
        )?;
        real("waves", self.waves, 0.0, 16.0, "must be in [0, 16]")?;
        Ok(())
    }
}

/// A swatch: its fibres and their cylinders in a bounding-volume hierarchy.
#[derive(Clone, Debug)]
pub struct Swatch {
    /// The fibres.
    pub strands: Strands,
    /// The fibres as opaque cylinders, for ray casting.
    pub occluders: Occluders,
}

/// Where a ray meets a fibre of the swatch, with what the models need there.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SwatchHit {
    /// Where the ray enters the fibre's cylinder.
    pub point: DVec3,
    /// The fibre's unit tangent there (root to tip).
    pub tangent: DVec3,
    /// The offset across the fibre, in `[-1, 1]` (module documentation, [`offset_of`]).
    pub h: f64,
    /// The fibre.
    pub strand: u32,
}

impl Swatch {
    /// The swatch `settings` describes (deterministic in `settings.seed`).
    ///
    /// # Errors
    /// [`ParamError::OutOfRange`] naming the setting outside its domain ([`SwatchSettings`]).
    pub fn new(settings: &SwatchSettings) -> Result<Self, ParamError> {
        settings.check()?;
        let mut points = Vec::with_capacity(settings.fibres * settings.points);
        for fibre in 0..settings.fibres {
            fibre_points(settings, fibre, &mut points);
        }
        let strands = Strands::new(
            SegmentCounts::Uniform {
                strands: settings.fibres,
                segments: (settings.points - 1) as u16,
            },
            points,
            PointAttribute::Uniform(settings.thickness),
            PointAttribute::Uniform(0.0),
            PointAttribute::Uniform(Vec3::new(0.35, 0.22, 0.12)),
        )
        .map_err(|e| unreachable!("a swatch is valid by construction: {e}"))?;
        let occluders = Occluders::new(&strands, Opacity::Uniform(1.0));
        Ok(Self { strands, occluders })
    }

    /// The camera framing the swatch with `size x size` pixels ([`Camera::framing`]).
    ///
    /// # Errors
    /// As [`Camera::framing`] (a size outside `[1, 4096]`).
    pub fn camera(&self, size: usize) -> Result<Camera, ParamError> {
        Camera::framing(&self.strands, size)
    }

    /// The first fibre the ray `origin + t direction` (unit `direction`) enters at `t > 0`,
    /// fibre `own` excluded (the one the ray leaves) and fibres holding `origin` passed
    /// through ([`Occluders::next_entry`]: where fibres overlap, a ray leaving one from
    /// inside another would otherwise stop where it starts, and a path could bounce between
    /// the two forever).
    pub fn first_hit(
        &self,
        origin: DVec3,
        direction: DVec3,
        own: Option<u32>,
    ) -> Option<SwatchHit> {
        let (o, d) = (origin.as_vec3(), direction.as_vec3());
        let (t, cylinder) = self.occluders.next_entry(o, d, own)?;
        let point = origin + direction * f64::from(t);
        Some(SwatchHit {
            point,
            tangent: cylinder.axis.as_dvec3(),
            h: offset_of(cylinder, point, -direction),
            strand: cylinder.strand,
        })
    }

    /// Whether the ray `origin + t direction`, `t > 0`, enters no fibre but `own` (as
    /// [`Swatch::first_hit`] finds them).
    pub fn unoccluded(&self, origin: DVec3, direction: DVec3, own: u32) -> bool {
        let (o, d) = (origin.as_vec3(), direction.as_vec3());
        self.occluders.next_entry(o, d, Some(own)).is_none()
    }

    /// The first hit of every pixel's ray of `camera` (through the pixel's centre, along
    /// `-Z`), row by row.
    pub fn camera_hits(&self, camera: &Camera) -> Vec<Option<SwatchHit>> {
        (0..camera.size * camera.size)
            .into_par_iter()
            .map(|k| {
                let origin = camera.ray_origin(k % camera.size, k / camera.size);
                self.first_hit(origin.as_dvec3(), DVec3::NEG_Z, None)
            })
            .collect()
    }
}

/// The offset `h` in `[-1, 1]` of `point` (on the surface of `cylinder`) seen from `wo`: its
/// distance from the axis along `normalize(wo x axis)`, over the radius (module
/// documentation); 0 when `wo` is along the axis.
pub fn offset_of(cylinder: &Cylinder, point: DVec3, wo: DVec3) -> f64 {
    let axis = cylinder.axis.as_dvec3();
    let base = cylinder.base.as_dvec3();
    let along = (point - base)
        .dot(axis)
        .clamp(0.0, f64::from(cylinder.length));
    let across = wo.cross(axis).normalize_or_zero();
    let radius = f64::from(cylinder.radius).max(1e-30);
    ((point - base - axis * along).dot(across) / radius).clamp(-1.0, 1.0)
}

/// Appends the points of fibre `fibre`: its own PCG stream draws an `x` jitter of a third of
/// the spacing, a phase and a depth jitter of a tenth of the thickness.
fn fibre_points(settings: &SwatchSettings, fibre: usize, points: &mut Vec<Vec3>) {
    let mut rng =
        Pcg64Mcg::seed_from_u64(settings.seed ^ (fibre as u64).wrapping_mul(0x9E37_79B9_7F4A_7C15));
    let mut uniform = || (rng.next_u64() >> 40) as f32 / (1u64 << 24) as f32;
    let per_layer = settings.fibres.div_ceil(settings.layers);
    let (layer, slot) = (fibre % settings.layers, fibre / settings.layers);
    let spacing = 2.0 / per_layer as f32;
    // Layers are shifted by a fraction of the spacing so that they fill each other's gaps.
    let shift = layer as f32 / settings.layers as f32;
    let x0 =
        -1.0 + (slot as f32 + 0.5 * shift + 0.25) * spacing + (uniform() - 0.5) * spacing / 3.0;
    let z0 =
        -(layer as f32) * settings.layer_spacing + (uniform() - 0.5) * 0.1 * settings.thickness;
    let phase = core::f32::consts::TAU * uniform();
    for k in 0..settings.points {
        let s = k as f32 / (settings.points - 1) as f32;
        let wave =
            settings.wave_amplitude * (core::f32::consts::TAU * settings.waves * s + phase).sin();
        points.push(Vec3::new(x0 + wave, 1.0 - 2.0 * s, z0));
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::bcsdf::ChiangHair;
    use crate::params::{AzimuthalRoughness, HairParams, LongitudinalRoughness};
    use crate::world::WorldBcsdf;

    #[test]
    fn settings_are_checked() {
        for bad in [
            SwatchSettings {
                fibres: 0,
                ..Default::default()
            },
            SwatchSettings {
                points: 1,
                ..Default::default()
            },
            SwatchSettings {
                thickness: f32::NAN,
                ..Default::default()
            },
            SwatchSettings {
                layers: 65,
                ..Default::default()
            },
        ] {
            assert!(Swatch::new(&bad).is_err(), "{bad:?}");
        }
    }

    /// The sign of h: a smooth fibre's R lobe at the offset of a hit peaks at the mirror
    /// direction of the cylinder's surface normal there.
    #[test]
    fn the_r_lobe_peaks_at_the_mirror_direction_of_the_hit_normal() {
        let cylinder = Cylinder {
            base: Vec3::new(0.0, 1.0, 0.0),
            axis: Vec3::NEG_Y,
            length: 2.0,
            radius: 0.1,
            transmission: 0.0,
            strand: 0,
            start: 0,
        };
        let hair = ChiangHair::new(&HairParams {
            beta_m: LongitudinalRoughness::new(0.3).unwrap(),
            beta_n: AzimuthalRoughness::new(0.08).unwrap(),
            ..HairParams::default()
        });
        for x in [-0.06, 0.03, 0.07] {
            let origin = DVec3::new(x, 0.0, 5.0);
            let occluders = Occluders::from_cylinders(vec![cylinder]);
            let (t, c) = occluders.first_hit(origin.as_vec3(), Vec3::NEG_Z).unwrap();
            let point = origin + DVec3::NEG_Z * f64::from(t);
            let wo = DVec3::Z;
            let h = offset_of(c, point, wo);
            let normal = DVec3::new(point.x, 0.0, point.z).normalize();
            let mirror = 2.0 * normal.dot(wo) * normal - wo;
            let tangent = DVec3::NEG_Y;
            let at = |w: DVec3| hair.eval_world(tangent, w, wo, h)[1];
            // The mirror direction against directions turned about the fibre either way.
            for angle in [-0.3f64, 0.3] {
                let (s, c) = angle.sin_cos();
                let turned = DVec3::new(
                    mirror.x * c - mirror.z * s,
                    0.0,
                    mirror.x * s + mirror.z * c,
                );
                assert!(
                    at(mirror) > at(turned),
                    "h {h}: {} vs {}",
                    at(mirror),
                    at(turned)
                );
            }
        }
    }
}
