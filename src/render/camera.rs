//! The orthographic camera and the first strand each pixel's ray meets.

use crate::error::ParamError;
use crate::strands::occluders::Occluders;
use crate::strands::Strands;
use glam::Vec3;
use rayon::prelude::*;

/// The largest image side.
pub const MAX_IMAGE_SIZE: usize = 4096;

/// An orthographic camera looking along -Z at the strands' bounding box.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Camera {
    /// Pixels per row and column (square images).
    pub size: usize,
    /// The world position of the image's top-left corner, in x and y.
    pub corner: [f32; 2],
    /// The side of a pixel.
    pub pixel: f32,
    /// The z of the rays' origins (above every strand).
    pub z: f32,
}

impl Camera {
    /// The camera framing every point of `strands` (a square around their x-y extent, 5%
    /// margin) with `size x size` pixels.
    ///
    /// # Errors
    /// [`ParamError::OutOfRange`] if `size` is outside `[1, MAX_IMAGE_SIZE]` (4096).
    pub fn framing(strands: &Strands, size: usize) -> Result<Self, ParamError> {
        ParamError::check("size", size as f64, "must be in [1, 4096]", |s| {
            (1.0..=MAX_IMAGE_SIZE as f64).contains(&s)
        })?;
        let (lo, hi) = strands.points().iter().fold(
            (Vec3::splat(f32::INFINITY), Vec3::splat(f32::NEG_INFINITY)),
            |(lo, hi), &p| (lo.min(p), hi.max(p)),
        );
        let centre = 0.5 * (lo + hi);
        let side = 1.05 * (hi - lo).truncate().max_element().max(1e-6);
        Ok(Self {
            size,
            corner: [centre.x - 0.5 * side, centre.y + 0.5 * side],
            pixel: side / size as f32,
            z: hi.z + 1.0,
        })
    }

    /// The origin of pixel `(column, row)`'s ray (through its centre; the direction is -Z).
    pub fn ray_origin(&self, column: usize, row: usize) -> Vec3 {
        Vec3::new(
            self.corner[0] + (column as f32 + 0.5) * self.pixel,
            self.corner[1] - (row as f32 + 0.5) * self.pixel,
            self.z,
        )
    }
}

/// Where a pixel's ray meets a strand.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Hit {
    /// The shading point: on the segment's axis.
    pub point: Vec3,
    /// The segment's unit axis (the tangent).
    pub tangent: Vec3,
    /// The strand.
    pub strand: u32,
    /// The segment's first point.
    pub start: u32,
    /// The shading point's position along the segment, in `[0, 1]`.
    pub along: f32,
}

/// The first strand each pixel's ray meets, row by row (`None` where it meets none).
pub fn first_hits(occluders: &Occluders, camera: &Camera) -> Vec<Option<Hit>> {
    (0..camera.size * camera.size)
        .into_par_iter()
        .map(|k| {
            let origin = camera.ray_origin(k % camera.size, k / camera.size);
            let (t, c) = occluders.first_hit(origin, Vec3::NEG_Z)?;
            let entry = origin + Vec3::NEG_Z * t;
            let along = (entry - c.base).dot(c.axis).clamp(0.0, c.length);
            Some(Hit {
                point: c.base + c.axis * along,
                tangent: c.axis,
                strand: c.strand,
                start: c.start,
                along: if c.length > 0.0 {
                    along / c.length
                } else {
                    0.0
                },
            })
        })
        .collect()
}
