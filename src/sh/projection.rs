//! Projection of functions on the sphere onto the real SH basis, `c_lm = int f Y_lm dw`, by
//! deterministic quadrature (plain f64 reference code).
//!
//! - [`project`]: a function given as a closure, by the product rule of Gauss-Legendre in
//!   `z = cos(theta)` with `lmax + 1` nodes times `2 lmax + 1` uniform nodes in `phi`. It is
//!   exact (to rounding) for every function of band limit `lmax`: the products `f Y_lm` are
//!   trigonometric polynomials of order at most `2 lmax` in `phi`, integrated exactly by the
//!   uniform rule, times `(1 - z^2)^(m) poly(z)` of total degree at most `2 lmax` in `z`
//!   (for equal `|m|`), integrated exactly by `lmax + 1` Gauss-Legendre nodes (degree
//!   `2 lmax + 1`).
//! - [`project_lat_long`] and [`project_cube_map`]: environment maps (any number of f32
//!   channels), treating each texel as constant over its exact solid angle and sampling
//!   `Y_lm` at the texel centre (the midpoint rule). They are exact only up to the map's
//!   resolution: the error of a coefficient is `O((lmax / resolution)^2)` relative to the map's
//!   magnitude; the texel solid angles sum to exactly `4 pi` (to rounding), so the
//!   `Y_00` coefficient of a constant map `c` is `sqrt(4 pi) c` to rounding.

use super::basis::{check_lmax, eval_sh_f64_into};
use crate::error::ParamError;
use crate::quadrature::gauss_legendre;
use core::f64::consts::PI;
use glam::DVec3;

/// The most work [`project`] and [`project_with_nodes`] do in one call: `n_theta n_phi
/// (lmax + 1)^2` (one evaluation of every coefficient's basis function at every node) at most
/// 2^28, about 2 s (7 ns per basis function and node, measured in a release build on one
/// core; `project(100)` takes 1.3 s).
pub const MAX_PROJECTION_WORK: usize = 1 << 28;

/// The largest `lmax` [`project`] accepts: 106, the largest whose `(lmax + 1) (2 lmax + 1)`
/// nodes times `(lmax + 1)^2` coefficients stay within [`MAX_PROJECTION_WORK`] (the cost
/// grows as `2 lmax^4`).
pub const MAX_PROJECT_LMAX: usize = 106;

/// SH coefficients (`(lmax + 1)^2`, index `l (l + 1) + m`) of `f` by the product rule
/// (Gauss-Legendre in `cos(theta)` with `lmax + 1` nodes, `2 lmax + 1` uniform nodes in `phi`),
/// exact for functions band-limited to `lmax` (see the module documentation). Cost: `f` at
/// `(lmax + 1) (2 lmax + 1)` nodes and about `2 lmax^4` basis-function evaluations (1.3 s at
/// lmax = 100, [`MAX_PROJECTION_WORK`]).
///
/// # Errors
/// [`ParamError::OutOfRange`] if `lmax > MAX_PROJECT_LMAX` (106).
///
/// # Examples
///
/// ```
/// use hairmath::sh::{project, reconstruct};
/// use hairmath::glam::DVec3;
///
/// // A band-limited function (degree 2 in the direction) is reproduced exactly at lmax = 2.
/// let f = |d: DVec3| 1.0 + d.z + d.x * d.y;
/// let coefficients = project(2, f)?;
/// let d = DVec3::new(0.48, 0.6, 0.64);
/// assert!((reconstruct(&coefficients, d)? - f(d)).abs() < 1e-12);
/// # Ok::<(), hairmath::ParamError>(())
/// ```
pub fn project(lmax: usize, f: impl FnMut(DVec3) -> f64) -> Result<Vec<f64>, ParamError> {
    ParamError::check(
        "lmax",
        lmax as f64,
        "project takes lmax <= 106 (MAX_PROJECT_LMAX: its cost grows as 2 lmax^4)",
        |l| l <= MAX_PROJECT_LMAX as f64,
    )?;
    project_with_nodes(lmax, lmax + 1, 2 * lmax + 1, f)
}

/// [`project`] with `n_theta` Gauss-Legendre nodes in `cos(theta)` and `n_phi` uniform nodes in
/// `phi`: exact when `f` is band-limited to `L` with `n_theta >= (L + lmax) / 2 + 1` and
/// `n_phi >= L + lmax + 1` (the product `f Y_lm` has band limit `L + lmax`). More nodes
/// integrate non-band-limited functions more accurately. Cost: `f` at `n_theta n_phi` nodes
/// and `n_theta n_phi (lmax + 1)^2` basis-function evaluations, at most
/// [`MAX_PROJECTION_WORK`] (about 2 s).
///
/// # Errors
/// [`ParamError::OutOfRange`] if `lmax > MAX_LMAX`, a node count is zero or above 10^6, or the
/// work `n_theta n_phi (lmax + 1)^2` exceeds [`MAX_PROJECTION_WORK`] (2^28).
pub fn project_with_nodes(
    lmax: usize,
    n_theta: usize,
    n_phi: usize,
    mut f: impl FnMut(DVec3) -> f64,
) -> Result<Vec<f64>, ParamError> {
    check_lmax(lmax)?;
    let count_ok = |n: f64| (1.0..=1e6).contains(&n);
    ParamError::check("n_theta", n_theta as f64, "must be in [1, 10^6]", count_ok)?;
    ParamError::check("n_phi", n_phi as f64, "must be in [1, 10^6]", count_ok)?;
    let work = (n_theta as f64) * (n_phi as f64) * ((lmax + 1) as f64).powi(2);
    ParamError::check(
        "n_theta n_phi (lmax + 1)^2",
        work,
        "the projection's work must be at most 2^28 (MAX_PROJECTION_WORK, about 2 s)",
        |w| w <= MAX_PROJECTION_WORK as f64,
    )?;
    let n = (lmax + 1) * (lmax + 1);
    let mut out = vec![0.0; n];
    let mut y = vec![0.0; n];
    let dphi = 2.0 * PI / n_phi as f64;
    for (z, wz) in gauss_legendre(n_theta) {
        let s = (1.0 - z * z).max(0.0).sqrt();
        for j in 0..n_phi {
            let phi = (j as f64 + 0.5) * dphi;
            let dir = DVec3::new(s * phi.cos(), s * phi.sin(), z);
            let w = wz * dphi * f(dir);
            eval_sh_f64_into(lmax, dir, &mut y)?;
            for (o, &yi) in out.iter_mut().zip(&y) {
                *o += w * yi;
            }
        }
    }
    Ok(out)
}

/// `sum_lm c_lm Y_lm(dir)` for `coefficients.len() = (lmax + 1)^2`.
///
/// # Errors
/// [`ParamError::OutOfRange`] if the length is not a square `(lmax + 1)^2` with
/// `lmax <= MAX_LMAX`; [`ParamError::BadVector`] for a zero or non-finite `dir`.
pub fn reconstruct(coefficients: &[f64], dir: DVec3) -> Result<f64, ParamError> {
    let lmax = lmax_of(coefficients.len())?;
    let y = super::basis::eval_sh_f64(lmax, dir)?;
    Ok(coefficients.iter().zip(&y).map(|(c, y)| c * y).sum())
}

/// The band limit `lmax` of a coefficient vector of length `n = (lmax + 1)^2`.
///
/// # Errors
/// [`ParamError::OutOfRange`] if `n` is zero or not a perfect square, or `lmax > MAX_LMAX`.
pub fn lmax_of(n: usize) -> Result<usize, ParamError> {
    let b = (n as f64).sqrt().round() as usize;
    ParamError::check(
        "coefficient count",
        n as f64,
        "must be (lmax + 1)^2 for some lmax >= 0",
        |_| b >= 1 && b * b == n,
    )?;
    check_lmax(b - 1)
}

/// Direction of the centre of texel (column `i`, row `j`) of a `width x height`
/// latitude-longitude map: row 0 is at the +Z pole, `theta = pi (j + 1/2) / height`; column 0
/// starts at `phi = 0` (the +X axis) and `phi = 2 pi (i + 1/2) / width` grows towards +Y;
/// direction `(sin theta cos phi, sin theta sin phi, cos theta)`. (For a Y-up map, rotate the
/// projected coefficients with [`crate::sh::rotate_bands012`] and the other rotations of [`crate::sh`].)
pub fn lat_long_direction(width: usize, height: usize, i: usize, j: usize) -> DVec3 {
    let theta = PI * (j as f64 + 0.5) / height as f64;
    let phi = 2.0 * PI * (i as f64 + 0.5) / width as f64;
    DVec3::new(
        theta.sin() * phi.cos(),
        theta.sin() * phi.sin(),
        theta.cos(),
    )
}

/// Exact solid angle of a latitude-longitude texel in row `j`:
/// `(2 pi / width) (cos theta_j - cos theta_{j+1})`, `theta_j = pi j / height`.
pub fn lat_long_texel_solid_angle(width: usize, height: usize, j: usize) -> f64 {
    let t0 = PI * j as f64 / height as f64;
    let t1 = PI * (j + 1) as f64 / height as f64;
    2.0 * PI / width as f64 * (t0.cos() - t1.cos())
}

fn check_map(lmax: usize, texels: usize, channels: usize, len: usize) -> Result<(), ParamError> {
    check_lmax(lmax)?;
    ParamError::check("texel count", texels as f64, "must be at least 1", |t| {
        t >= 1.0
    })?;
    ParamError::check("channels", channels as f64, "must be at least 1", |c| {
        c >= 1.0
    })?;
    ParamError::check(
        "data.len()",
        len as f64,
        "must equal the texel count times channels",
        |l| texels.checked_mul(channels) == Some(l as usize),
    )?;
    Ok(())
}

/// Accumulates `weight * texel * Y` into per-channel coefficient vectors.
fn accumulate(out: &mut [Vec<f64>], y: &[f64], weight: f64, texel: &[f32]) {
    for (coeffs, &value) in out.iter_mut().zip(texel) {
        let w = weight * value as f64;
        for (o, &yi) in coeffs.iter_mut().zip(y) {
            *o += w * yi;
        }
    }
}

/// Projects a latitude-longitude environment map: `data` holds `height` rows of `width`
/// texels of `channels` f32 values (row-major, channels interleaved: RGB is `channels = 3`),
/// mapped to directions by [`lat_long_direction`] and weighted by the exact texel solid angle
/// [`lat_long_texel_solid_angle`]. Returns one coefficient vector per channel.
///
/// Exact only up to the map's resolution (midpoint rule per texel): see the module
/// documentation.
///
/// # Errors
/// [`ParamError::OutOfRange`] if `lmax > MAX_LMAX`, `width`, `height` or `channels` is 0, or
/// `data.len() != width * height * channels`.
pub fn project_lat_long(
    lmax: usize,
    width: usize,
    height: usize,
    channels: usize,
    data: &[f32],
) -> Result<Vec<Vec<f64>>, ParamError> {
    let texels = width.checked_mul(height).unwrap_or(0);
    ParamError::check("width", width as f64, "must be at least 1", |w| w >= 1.0)?;
    ParamError::check("height", height as f64, "must be at least 1", |h| h >= 1.0)?;
    check_map(lmax, texels, channels, data.len())?;
    let n = (lmax + 1) * (lmax + 1);
    let mut out = vec![vec![0.0; n]; channels];
    let mut y = vec![0.0; n];
    for j in 0..height {
        let weight = lat_long_texel_solid_angle(width, height, j);
        for i in 0..width {
            eval_sh_f64_into(lmax, lat_long_direction(width, height, i, j), &mut y)?;
            let start = (j * width + i) * channels;
            accumulate(&mut out, &y, weight, &data[start..start + channels]);
        }
    }
    Ok(out)
}

/// Cube-map face order: +X, -X, +Y, -Y, +Z, -Z (the OpenGL / Direct3D order).
pub const CUBE_FACES: usize = 6;

/// Direction (not normalised) of the centre of texel (column `i`, row `j`) of cube face `face`
/// (0..6 = +X, -X, +Y, -Y, +Z, -Z) of a `size x size` face, with the OpenGL cube-map face
/// orientation (OpenGL 4.6 specification, table 8.19): `s = 2 (i + 1/2) / size - 1`,
/// `t = 2 (j + 1/2) / size - 1`, and
/// +X: `(1, -t, -s)`, -X: `(-1, -t, s)`, +Y: `(s, 1, t)`, -Y: `(s, -1, -t)`,
/// +Z: `(s, -t, 1)`, -Z: `(-s, -t, -1)`. A face index above 5 is treated as -Z.
pub fn cube_texel_direction(face: usize, size: usize, i: usize, j: usize) -> DVec3 {
    let s = 2.0 * (i as f64 + 0.5) / size as f64 - 1.0;
    let t = 2.0 * (j as f64 + 0.5) / size as f64 - 1.0;
    match face {
        0 => DVec3::new(1.0, -t, -s),
        1 => DVec3::new(-1.0, -t, s),
        2 => DVec3::new(s, 1.0, t),
        3 => DVec3::new(s, -1.0, -t),
        4 => DVec3::new(s, -t, 1.0),
        _ => DVec3::new(-s, -t, -1.0),
    }
}

/// Exact solid angle of texel `(i, j)` of a `size x size` cube face: with
/// `A(u, v) = atan2(u v, sqrt(u^2 + v^2 + 1))` (the solid angle of the face rectangle from the
/// face centre to `(u, v)`), the texel `[u0, u1] x [v0, v1]` subtends
/// `A(u0, v0) - A(u0, v1) - A(u1, v0) + A(u1, v1)` (Driscoll's formula, as used by
/// AMD CubeMapGen and Sloan 2008). The 6 size^2 texels sum to 4 pi.
pub fn cube_texel_solid_angle(size: usize, i: usize, j: usize) -> f64 {
    let a = |u: f64, v: f64| (u * v).atan2((u * u + v * v + 1.0).sqrt());
    let h = 2.0 / size as f64;
    let (u0, v0) = (i as f64 * h - 1.0, j as f64 * h - 1.0);
    let (u1, v1) = (u0 + h, v0 + h);
    a(u0, v0) - a(u0, v1) - a(u1, v0) + a(u1, v1)
}

/// Projects a cube map: `data` holds the 6 faces in the order +X, -X, +Y, -Y, +Z, -Z, each
/// `size` rows of `size` texels of `channels` f32 values (row-major, channels interleaved),
/// oriented as in [`cube_texel_direction`] and weighted by the exact texel solid angle
/// [`cube_texel_solid_angle`] (Gerard's hair shading projects a per-vertex transmittance cube
/// map this way). Returns one coefficient vector per channel.
///
/// Exact only up to the map's resolution (midpoint rule per texel): see the module
/// documentation.
///
/// # Errors
/// [`ParamError::OutOfRange`] if `lmax > MAX_LMAX`, `size` or `channels` is 0, or
/// `data.len() != 6 * size * size * channels`.
pub fn project_cube_map(
    lmax: usize,
    size: usize,
    channels: usize,
    data: &[f32],
) -> Result<Vec<Vec<f64>>, ParamError> {
    ParamError::check("size", size as f64, "must be at least 1", |s| s >= 1.0)?;
    let texels = size
        .checked_mul(size)
        .and_then(|t| t.checked_mul(CUBE_FACES))
        .unwrap_or(0);
    check_map(lmax, texels, channels, data.len())?;
    let n = (lmax + 1) * (lmax + 1);
    let mut out = vec![vec![0.0; n]; channels];
    let mut y = vec![0.0; n];
    for face in 0..CUBE_FACES {
        for j in 0..size {
            for i in 0..size {
                let weight = cube_texel_solid_angle(size, i, j);
                eval_sh_f64_into(lmax, cube_texel_direction(face, size, i, j), &mut y)?;
                let start = ((face * size + j) * size + i) * channels;
                accumulate(&mut out, &y, weight, &data[start..start + channels]);
            }
        }
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn texel_solid_angles_sum_to_four_pi() {
        let size = 7;
        let total: f64 = (0..size)
            .flat_map(|j| (0..size).map(move |i| (i, j)))
            .map(|(i, j)| cube_texel_solid_angle(size, i, j))
            .sum::<f64>()
            * 6.0;
        assert!((total - 4.0 * PI).abs() < 1e-12, "{total}");
        let ll: f64 = (0..9)
            .map(|j| 16.0 * lat_long_texel_solid_angle(16, 9, j))
            .sum();
        assert!((ll - 4.0 * PI).abs() < 1e-12, "{ll}");
    }

    #[test]
    fn unused_face_index_is_safe() {
        assert!(cube_texel_direction(9, 2, 0, 0).is_finite());
    }
}
