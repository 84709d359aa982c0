//! Gaunt coefficients: integrals of products of three spherical harmonics, complex and real.
//!
//! Complex SH (Condon-Shortley phase, `Y_l^{-m} = (-1)^m conj(Y_l^m)`), Gaunt 1929; Edmonds 1957
//! eq. 4.6.3:
//!
//! ```text
//! ∫ Y_l1^m1 Y_l2^m2 Y_l3^m3 dΩ = sqrt((2l1+1)(2l2+1)(2l3+1) / (4π)) (l1 l2 l3; 0 0 0) (l1 l2 l3; m1 m2 m3)
//! ```
//!
//! Real SH in the crate convention ([`crate::sh`]: Sloan's, with the Condon-Shortley phase kept)
//! are, for `μ = |m| > 0`,
//!
//! ```text
//! Y_{l,m}  = sqrt(2) Re Y_l^μ = (Y_l^μ + (-1)^μ Y_l^{-μ}) / sqrt(2)        (m > 0)
//! Y_{l,-μ} = sqrt(2) Im Y_l^μ = -i (Y_l^μ - (-1)^μ Y_l^{-μ}) / sqrt(2)     (m < 0)
//! ```
//!
//! (check: `sqrt(2) Im Y_1^1 = -sqrt(3/(4π)) y`, the documented `Y(1,-1) = -0.4886025 y`).
//! Expanding the three real functions gives up to eight complex Gaunt integrals; only patterns
//! with `s1 μ1 + s2 μ2 + s3 μ3 = 0` survive. All surviving patterns are one complex integral
//! `G` or its sign flip `G(-m) = (-1)^(l1+l2+l3) G(m) = G(m)` (the sum of the l's is even for a
//! non-zero `(l1 l2 l3; 0 0 0)`), so the real integral is `c G / sqrt(2)^n` with `c` the
//! (real, integer) sum of the patterns' phase factors and `n` the number of non-zero `m`s
//! (compare Homeier and Steinborn 1996, J. Mol. Struct. 368, 31). The value is computed exactly
//! (`±sqrt(rational)`) with the exact 3-j machinery of [`super::wigner`], rounded once, and
//! divided by `sqrt(4π)`: mathematically equal coefficients are bitwise equal `f64`s, and
//! mathematical zeros are exact zeros.

use super::wigner::{int_args, racah_checked, Exact};
use crate::error::ParamError;

/// `sqrt(4 π)` rounded to `f64`.
const SQRT_4PI: f64 = 3.544_907_701_811_032;

/// The integral of `Y_l1^m1 Y_l2^m2 Y_l3^m3` (complex SH, Condon-Shortley phase, no complex
/// conjugates) over the unit sphere: `sqrt((2l1+1)(2l2+1)(2l3+1)/(4π)) (l1 l2 l3; 0 0 0)
/// (l1 l2 l3; m1 m2 m3)` (Edmonds 1957, eq. 4.6.3). Within about 1.5 ulp (one rounding of the
/// exact square root, one division by `sqrt(4π)`). Zero unless `m1 + m2 + m3 = 0`, the `l`s
/// satisfy the triangle condition, `l1 + l2 + l3` is even and `|m_i| <= l_i`.
///
/// # Errors
/// [`ParamError::OutOfRange`] if an `l` or `|m|` exceeds 10000.
pub fn gaunt_complex(
    l1: u32,
    m1: i32,
    l2: u32,
    m2: i32,
    l3: u32,
    m3: i32,
) -> Result<f64, ParamError> {
    Ok(match complex_exact(l1, m1, l2, m2, l3, m3)? {
        None => 0.0,
        Some(e) => e.to_f64() / SQRT_4PI,
    })
}

/// `sqrt(4π) G` exactly, `None` when zero.
fn complex_exact(
    l1: u32,
    m1: i32,
    l2: u32,
    m2: i32,
    l3: u32,
    m3: i32,
) -> Result<Option<Exact>, ParamError> {
    let (tj, tm) = int_args(l1, l2, l3, m1, m2, m3)?;
    if (l1 + l2 + l3) % 2 == 1 {
        return Ok(None);
    }
    let Some(w) = racah_checked(tj, tm)? else {
        return Ok(None);
    };
    let Some(w0) = racah_checked(tj, [0; 3])? else {
        return Ok(None);
    };
    let mut e = w.mul(&w0);
    for l in [l1, l2, l3] {
        e.mul_sqrt_ratio(2 * l + 1, 1);
    }
    Ok(Some(e))
}

/// The integral of the product of three **real** SH of the crate convention ([`crate::sh`]):
/// `∫ Y_{l1,m1} Y_{l2,m2} Y_{l3,m3} dΩ`, from the complex Gaunt coefficient by the unitary change
/// of basis derived in the module docs. Within about 1.5 ulp; exact zeros where the integral
/// vanishes, and bitwise-equal values where the integrals are equal. Symmetric under every
/// permutation of the three `(l, m)` pairs.
///
/// # Errors
/// [`ParamError::OutOfRange`] if an `l` or `|m|` exceeds 10000.
pub fn gaunt_real(l1: u32, m1: i32, l2: u32, m2: i32, l3: u32, m3: i32) -> Result<f64, ParamError> {
    Ok(match real_exact(l1, m1, l2, m2, l3, m3)? {
        None => 0.0,
        Some(e) => e.to_f64() / SQRT_4PI,
    })
}

/// Phase factor of `Y_l^{s μ}` in the real function `Y_{l,m}` as a Gaussian integer
/// `(re, im)`, without the `1/sqrt(2)` (see the module docs).
fn phase(m: i32, s: i32) -> (i64, i64) {
    let mu = m.unsigned_abs();
    let parity = if mu.is_multiple_of(2) { 1 } else { -1 };
    match (m.signum(), s) {
        (0, _) => (1, 0),
        (1, 1) => (1, 0),
        (1, _) => (parity, 0),
        (_, 1) => (0, -1),
        (_, _) => (0, parity),
    }
}

fn real_exact(
    l1: u32,
    m1: i32,
    l2: u32,
    m2: i32,
    l3: u32,
    m3: i32,
) -> Result<Option<Exact>, ParamError> {
    int_args(l1, l2, l3, m1, m2, m3)?;
    let ms = [m1, m2, m3];
    let ls = [l1, l2, l3];
    if (0..3).any(|i| ms[i].unsigned_abs() > ls[i]) || (l1 + l2 + l3) % 2 == 1 {
        return Ok(None);
    }
    // An odd number of sines integrates to zero over phi.
    if ms.iter().filter(|&&m| m < 0).count() % 2 == 1 {
        return Ok(None);
    }
    let signs = |m: i32| if m == 0 { &[1][..] } else { &[1, -1][..] };
    let mut c = (0i64, 0i64);
    let mut rep: Option<[i32; 3]> = None;
    for &s1 in signs(m1) {
        for &s2 in signs(m2) {
            for &s3 in signs(m3) {
                let mm = [s1 * m1.abs(), s2 * m2.abs(), s3 * m3.abs()];
                if mm[0] + mm[1] + mm[2] != 0 {
                    continue;
                }
                let mut z = (1i64, 0i64);
                for (m, s) in [(m1, s1), (m2, s2), (m3, s3)] {
                    let u = phase(m, s);
                    z = (z.0 * u.0 - z.1 * u.1, z.0 * u.1 + z.1 * u.0);
                }
                c = (c.0 + z.0, c.1 + z.1);
                rep.get_or_insert(mm);
            }
        }
    }
    let Some(mm) = rep else {
        return Ok(None);
    };
    // The integral of real functions is real: c.1 = 0 whenever G != 0 (checked in tests).
    if c.0 == 0 {
        return Ok(None);
    }
    let Some(mut e) = complex_exact(l1, mm[0], l2, mm[1], l3, mm[2])? else {
        return Ok(None);
    };
    e.mul_int(c.0);
    let n = ms.iter().filter(|&&m| m != 0).count() as u32;
    e.mul_sqrt_ratio(1, 1 << n);
    Ok(Some(e))
}

/// The largest band `l` [`index_to_lm`] returns: `(l, m)` are `(u32, i32)`, so `|m| <= l` must
/// fit in `i32`.
pub const MAX_INDEX_L: usize = i32::MAX as usize;

/// `l (l + 1) + m` to `(l, m)`: the inverse of [`crate::sh::sh_index`], with the integer
/// square root `l = floor(sqrt(index))` (exact for every index).
///
/// # Errors
/// [`ParamError::OutOfRange`] naming `index` if `l` would exceed [`MAX_INDEX_L`] (index
/// `>= 2^62`), where `m` no longer fits in `i32`.
pub fn index_to_lm(index: usize) -> Result<(u32, i32), ParamError> {
    let l = index.isqrt();
    if l > MAX_INDEX_L {
        return Err(ParamError::OutOfRange {
            name: "index",
            value: index as f64,
            allowed: "must be below 2^62 (l and m must fit in i32)",
        });
    }
    // l <= 2^31 - 1, so l (l + 1) fits and m = index - l (l + 1) is in [-l, l].
    let m = index as i64 - (l * (l + 1)) as i64;
    Ok((l as u32, m as i32))
}

/// One non-zero entry of the real Gaunt tensor: `value = ∫ Y_i Y_j Y_k dΩ` with `i, j, k` the
/// indices `l (l + 1) + m` of real SH (crate convention).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct GauntEntry {
    /// First index.
    pub i: u32,
    /// Second index.
    pub j: u32,
    /// Third index.
    pub k: u32,
    /// The integral (see [`gaunt_real`]).
    pub value: f64,
}

/// The sparse real Gaunt tensor `T_ijk = ∫ Y_i Y_j Y_k dΩ` for all indices below `n_bands^2`
/// (bands `l < n_bands`).
///
/// `T` is symmetric under all permutations of `(i, j, k)`; each non-zero is stored **once**,
/// with `i <= j <= k`, sorted by `(i, j, k)`. [`GauntTensor::all`] expands the permutations.
#[derive(Clone, Debug, PartialEq)]
pub struct GauntTensor {
    n_bands: usize,
    entries: Vec<GauntEntry>,
}

/// Largest band count accepted by [`GauntTensor::new`]: 16 (l <= 15). The tensor is built
/// from exact (correctly rounded) Gaunt coefficients, and its cost grows about as
/// `n_bands^5.5`: measured (release build, one core) 8 ms and 2,300 entries at 8 bands, 0.22 s
/// and 75,000 entries at 16, 0.9 s at 20 and 30 s at 40 (the former limit).
pub const MAX_TENSOR_BANDS: usize = 16;

impl GauntTensor {
    /// Computes the tensor for bands `l < n_bands` with [`gaunt_real`]; the cost is stated on
    /// [`MAX_TENSOR_BANDS`] (0.22 s at its 16 bands).
    ///
    /// # Errors
    /// [`ParamError::OutOfRange`] unless `1 <= n_bands <= MAX_TENSOR_BANDS` (16).
    pub fn new(n_bands: usize) -> Result<Self, ParamError> {
        if n_bands == 0 || n_bands > MAX_TENSOR_BANDS {
            return Err(ParamError::OutOfRange {
                name: "n_bands",
                value: n_bands as f64,
                allowed: "must be in 1..=16 (MAX_TENSOR_BANDS; the cost grows as n_bands^5.5)",
            });
        }
        let n = n_bands * n_bands;
        let lm = (0..n).map(index_to_lm).collect::<Result<Vec<_>, _>>()?;
        let mut entries = Vec::new();
        for (i, &(l1, m1)) in lm.iter().enumerate() {
            for (j, &(l2, m2)) in lm.iter().enumerate().skip(i) {
                let lo = l1.abs_diff(l2);
                let hi = (l1 + l2).min(n_bands as u32 - 1);
                for l3 in (lo..=hi).step_by(2) {
                    let (a, b) = (m1.unsigned_abs(), m2.unsigned_abs());
                    let mus = [a + b, a.abs_diff(b)];
                    let distinct = if a.min(b) == 0 { 1 } else { 2 };
                    for &mu in &mus[..distinct] {
                        if mu > l3 {
                            continue;
                        }
                        let neg = (m1 < 0) as u32 + (m2 < 0) as u32;
                        let m3 = if mu == 0 {
                            if neg % 2 == 1 {
                                continue;
                            }
                            0
                        } else if neg % 2 == 1 {
                            -(mu as i32)
                        } else {
                            mu as i32
                        };
                        let k = (l3 * (l3 + 1)) as i32 + m3;
                        let k = k as usize;
                        if k < j {
                            continue;
                        }
                        let value = gaunt_real(l1, m1, l2, m2, l3, m3)?;
                        if value != 0.0 {
                            entries.push(GauntEntry {
                                i: i as u32,
                                j: j as u32,
                                k: k as u32,
                                value,
                            });
                        }
                    }
                }
            }
        }
        entries.sort_by_key(|e| (e.i, e.j, e.k));
        entries.dedup_by_key(|e| (e.i, e.j, e.k));
        Ok(GauntTensor { n_bands, entries })
    }

    /// The band count `n_bands` (indices `< n_bands^2`).
    pub fn n_bands(&self) -> usize {
        self.n_bands
    }

    /// The non-zeros with `i <= j <= k`, each once.
    pub fn entries(&self) -> &[GauntEntry] {
        &self.entries
    }

    /// Every non-zero `T_ijk` with all distinct permutations of the stored entries.
    pub fn all(&self) -> Vec<GauntEntry> {
        let mut out = Vec::new();
        for e in &self.entries {
            let perms = [
                (e.i, e.j, e.k),
                (e.i, e.k, e.j),
                (e.j, e.i, e.k),
                (e.j, e.k, e.i),
                (e.k, e.i, e.j),
                (e.k, e.j, e.i),
            ];
            let start = out.len();
            for (i, j, k) in perms {
                let entry = GauntEntry {
                    i,
                    j,
                    k,
                    value: e.value,
                };
                if !out[start..].contains(&entry) {
                    out.push(entry);
                }
            }
        }
        out
    }
}
