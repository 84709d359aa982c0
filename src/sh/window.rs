//! Windowing (sigma factors) against ringing: truncating an SH expansion at band `lmax`
//! overshoots near discontinuities (the Gibbs phenomenon) and can go negative; scaling band
//! `l` by a factor `sigma_l` that falls smoothly to 0 trades sharpness for less ringing
//! (Sloan 2008, "Stupid Spherical Harmonics (SH) Tricks", GDC, section "Windowing"; the same
//! factors as in Fourier series, Hamming 1973 and Lanczos 1956).
//!
//! The window width `w` is the band at which the factor reaches zero; `w = lmax + 1` keeps
//! every band `l <= lmax` positive and is the usual choice.

use crate::error::ParamError;
use core::f64::consts::PI;

fn check(lmax: usize, w: f64) -> Result<(), ParamError> {
    super::basis::check_lmax(lmax)?;
    ParamError::check("w", w, "must be finite and > 0", |w| w > 0.0)?;
    Ok(())
}

/// Hanning (von Hann) sigma factors for `l = 0..=lmax`:
/// `sigma_l = (1 + cos(pi l / w)) / 2` for `l < w`, 0 for `l >= w` (Sloan 2008).
///
/// # Errors
/// [`ParamError::OutOfRange`] if `w` is not finite and positive or `lmax > MAX_LMAX`.
pub fn hanning(lmax: usize, w: f64) -> Result<Vec<f64>, ParamError> {
    check(lmax, w)?;
    Ok((0..=lmax)
        .map(|l| {
            let l = l as f64;
            if l < w {
                0.5 * (1.0 + (PI * l / w).cos())
            } else {
                0.0
            }
        })
        .collect())
}

/// Lanczos sigma factors for `l = 0..=lmax`:
/// `sigma_l = sin(pi l / w) / (pi l / w)` (`sigma_0 = 1`) for `l < w`, 0 for `l >= w`
/// (Sloan 2008).
///
/// # Errors
/// [`ParamError::OutOfRange`] if `w` is not finite and positive or `lmax > MAX_LMAX`.
pub fn lanczos(lmax: usize, w: f64) -> Result<Vec<f64>, ParamError> {
    check(lmax, w)?;
    Ok((0..=lmax)
        .map(|l| {
            let x = PI * l as f64 / w;
            if l == 0 {
                1.0
            } else if (l as f64) < w {
                x.sin() / x
            } else {
                0.0
            }
        })
        .collect())
}

/// Scales every coefficient of band `l` by `window[l]`, in place: `c_lm <- sigma_l c_lm`.
///
/// # Errors
/// [`ParamError::OutOfRange`] if `coefficients.len()` is not `(lmax + 1)^2` or `window` has
/// fewer than `lmax + 1` entries.
pub fn apply_window(coefficients: &mut [f64], window: &[f64]) -> Result<(), ParamError> {
    let lmax = super::projection::lmax_of(coefficients.len())?;
    ParamError::check(
        "window.len()",
        window.len() as f64,
        "must be at least lmax + 1",
        |n| n >= (lmax + 1) as f64,
    )?;
    for (l, &s) in window.iter().take(lmax + 1).enumerate() {
        for c in &mut coefficients[l * l..(l + 1) * (l + 1)] {
            *c *= s;
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn windows_start_at_one_and_fall_to_zero() {
        let h = hanning(4, 5.0).unwrap();
        let s = lanczos(4, 5.0).unwrap();
        assert_eq!(h[0], 1.0);
        assert_eq!(s[0], 1.0);
        assert!(h.windows(2).all(|p| p[1] < p[0]) && s.windows(2).all(|p| p[1] < p[0]));
        assert!((h[2] - 0.5 * (1.0 + (0.4 * PI).cos())).abs() < 1e-15);
        assert_eq!(hanning(3, 2.0).unwrap()[2], 0.0);
        assert!(hanning(3, 0.0).is_err() && lanczos(3, f64::NAN).is_err());
        let mut c = vec![1.0; 4];
        assert!(apply_window(&mut c, &[1.0]).is_err());
        apply_window(&mut c, &[1.0, 0.5]).unwrap();
        assert_eq!(c, vec![1.0, 0.5, 0.5, 0.5]);
    }
}
