//! Images as 8-bit sRGB: several side by side in one row, and PNG files (feature `png`).

use super::image::Image;

/// `images` (all of `images[0]`'s size) side by side left to right as one 8-bit sRGB image
/// ([`Image::to_srgb8`] with `exposure`), row by row: its width is `images.len()` times the
/// size, its height the size. Images of another size are left black.
pub fn side_by_side(images: &[&Image], exposure: f64) -> Vec<u8> {
    let size = images.first().map_or(0, |i| i.size);
    let width = size * images.len();
    let mut rgb = vec![0u8; 3 * width * size];
    for (k, image) in images.iter().enumerate() {
        if image.size != size || image.pixels.len() != size * size {
            continue;
        }
        let bytes = image.to_srgb8(exposure);
        for row in 0..size {
            let to = 3 * (row * width + k * size);
            rgb[to..to + 3 * size].copy_from_slice(&bytes[3 * row * size..3 * (row + 1) * size]);
        }
    }
    rgb
}

/// Writes `rgb` (8-bit RGB, row by row, `width x height` pixels) as a PNG file.
///
/// # Errors
/// The file's I/O error, or [`std::io::ErrorKind::InvalidInput`] if `rgb` does not hold
/// `3 width height` bytes or a side exceeds `u32::MAX`.
#[cfg(feature = "png")]
pub fn write_png(
    path: &std::path::Path,
    width: usize,
    height: usize,
    rgb: &[u8],
) -> std::io::Result<()> {
    use std::io::{Error, ErrorKind};
    let invalid = |what: &str| Error::new(ErrorKind::InvalidInput, what.to_string());
    if width.checked_mul(height).and_then(|n| n.checked_mul(3)) != Some(rgb.len()) {
        return Err(invalid("the pixels do not fill width x height"));
    }
    let side = |n: usize| u32::try_from(n).map_err(|_| invalid("an image side exceeds u32"));
    let file = std::fs::File::create(path)?;
    let mut encoder = png::Encoder::new(std::io::BufWriter::new(file), side(width)?, side(height)?);
    encoder.set_color(png::ColorType::Rgb);
    encoder.set_depth(png::BitDepth::Eight);
    let mut writer = encoder.write_header().map_err(Error::other)?;
    writer.write_image_data(rgb).map_err(Error::other)?;
    writer.finish().map_err(Error::other)
}
