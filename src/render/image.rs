//! Images, their rendering in parallel, their error against a reference and their 8-bit form.

use super::camera::Hit;
use crate::error::ParamError;
use rayon::prelude::*;
use std::sync::atomic::{AtomicUsize, Ordering};

/// An image: linear RGB per pixel, row by row, and whether a strand covers the pixel.
#[derive(Clone, Debug, PartialEq)]
pub struct Image {
    /// Pixels per row and column.
    pub size: usize,
    /// The radiance per pixel (0 where no strand is hit).
    pub pixels: Vec<[f64; 3]>,
    /// Whether the pixel shows a strand.
    pub covered: Vec<bool>,
}

/// Shades every hit with `shade` in parallel; `progress(done, total)` as rows complete.
///
/// # Errors
/// The first error `shade` returns.
pub fn render(
    size: usize,
    hits: &[Option<Hit>],
    shade: impl Fn(&Hit) -> Result<[f64; 3], ParamError> + Sync,
    progress: &(dyn Fn(usize, usize) + Sync),
) -> Result<Image, ParamError> {
    let done = AtomicUsize::new(0);
    let rows: Vec<Result<Vec<[f64; 3]>, ParamError>> = hits
        .par_chunks(size.max(1))
        .map(|row| {
            let shaded = row
                .iter()
                .map(|hit| hit.as_ref().map_or(Ok([0.0; 3]), &shade))
                .collect();
            progress(done.fetch_add(1, Ordering::Relaxed) + 1, size);
            shaded
        })
        .collect();
    let mut pixels = Vec::with_capacity(hits.len());
    for row in rows {
        pixels.extend(row?);
    }
    Ok(Image {
        size,
        pixels,
        covered: hits.iter().map(Option::is_some).collect(),
    })
}

/// How far an image is from a reference, over the pixels the strands cover.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ImageError {
    /// The root mean square over covered pixels and channels of the difference.
    pub rmse: f64,
    /// `sqrt(sum of squared differences / sum of squared reference values)`.
    pub relative_error: f64,
}

/// The error of `image` against `reference` (the same size and coverage).
///
/// # Errors
/// [`ParamError::OutOfRange`] if the sizes differ.
pub fn image_error(image: &Image, reference: &Image) -> Result<ImageError, ParamError> {
    check_same_size(image, reference)?;
    let (mut squares, mut norm, mut count) = (0.0, 0.0, 0usize);
    for ((a, b), &covered) in image
        .pixels
        .iter()
        .zip(&reference.pixels)
        .zip(&reference.covered)
    {
        if covered {
            for c in 0..3 {
                squares += (a[c] - b[c]).powi(2);
                norm += b[c] * b[c];
            }
            count += 3;
        }
    }
    Ok(ImageError {
        rmse: (squares / count.max(1) as f64).sqrt(),
        relative_error: if norm > 0.0 {
            (squares / norm).sqrt()
        } else {
            0.0
        },
    })
}

impl Image {
    /// The per-channel absolute difference `|self - other|` (the same size).
    ///
    /// # Errors
    /// [`ParamError::OutOfRange`] if the sizes differ.
    pub fn difference(&self, other: &Image) -> Result<Image, ParamError> {
        check_same_size(self, other)?;
        Ok(Image {
            size: self.size,
            pixels: self
                .pixels
                .iter()
                .zip(&other.pixels)
                .map(|(a, b)| core::array::from_fn(|c| (a[c] - b[c]).abs()))
                .collect(),
            covered: self.covered.clone(),
        })
    }

    /// The mean radiance per channel over the covered pixels (0 if none is covered).
    pub fn mean(&self) -> [f64; 3] {
        let covered = self.pixels.iter().zip(&self.covered).filter(|(_, &c)| c);
        let (sum, n) = covered.fold(([0.0; 3], 0usize), |(s, n), (p, _)| {
            ([s[0] + p[0], s[1] + p[1], s[2] + p[2]], n + 1)
        });
        sum.map(|s| if n > 0 { s / n as f64 } else { 0.0 })
    }

    /// The exposure that maps the image's 99th percentile of the brightest channel over the
    /// covered pixels to 1 (1 for an image with nothing covered or all black).
    pub fn exposure(&self) -> f64 {
        let mut peaks: Vec<f64> = self
            .pixels
            .iter()
            .zip(&self.covered)
            .filter(|(_, &covered)| covered)
            .map(|(p, _)| p[0].max(p[1]).max(p[2]))
            .collect();
        peaks.sort_by(f64::total_cmp);
        match peaks.get(peaks.len() * 99 / 100) {
            Some(&p) if p > 0.0 && p.is_finite() => 1.0 / p,
            _ => 1.0,
        }
    }

    /// The image as 8-bit sRGB, row by row, three bytes per pixel: each channel times
    /// `exposure`, clamped to `[0, 1]` and encoded with the sRGB transfer function (IEC
    /// 61966-2-1); pixels with no strand are black.
    pub fn to_srgb8(&self, exposure: f64) -> Vec<u8> {
        self.pixels
            .iter()
            .flat_map(|p| p.map(|v| srgb8(v * exposure)))
            .collect()
    }
}

/// The 8-bit sRGB code of the linear value `v` (clamped to `[0, 1]`; NaN gives 0).
fn srgb8(v: f64) -> u8 {
    let v = if v.is_nan() { 0.0 } else { v.clamp(0.0, 1.0) };
    let encoded = if v <= 0.003_130_8 {
        12.92 * v
    } else {
        1.055 * v.powf(1.0 / 2.4) - 0.055
    };
    (encoded * 255.0).round() as u8
}

fn check_same_size(image: &Image, reference: &Image) -> Result<(), ParamError> {
    ParamError::check(
        "image size",
        image.size as f64,
        "must equal the reference's",
        |s| s == reference.size as f64 && image.pixels.len() == reference.pixels.len(),
    )?;
    Ok(())
}
