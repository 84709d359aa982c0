//! Rotation of real SH coefficient vectors.
//!
//! Rotating a function `f` by the rotation matrix `R` gives `g(x) = f(R^T x)` (the function is
//! carried along with the rotation: a lobe around `d` becomes a lobe around `R d`). Its
//! coefficients are `c'_l = D_l(R) c_l` band by band, with `D_l` an orthogonal
//! `(2l + 1) x (2l + 1)` matrix and `D_l(R1 R2) = D_l(R1) D_l(R2)`.
//!
//! - Band 1 ([`rotate_band1`]): `Y_1,(-1,0,1) = sqrt(3/(4 pi)) (-y, z, -x)`, so `D_1` is `R`
//!   permuted to the order `(y, z, x)` and conjugated by `diag(-1, 1, -1)` (the Condon-Shortley
//!   signs): `D_1 = [[R_yy, -R_yz, R_yx], [-R_zy, R_zz, -R_zx], [R_xy, -R_xz, R_xx]]`.
//! - Band 2 ([`rotate_band2`]): band 2 is the space of traceless quadratic forms:
//!   `sum_m c_m Y_2m(v) = (k/2) v^T A v` with `k = sqrt(15/(4 pi))` and
//!   `A = [[c_2 - c_0/sqrt 3, c_-2, -c_1], [c_-2, -c_2 - c_0/sqrt 3, -c_-1],
//!   [-c_1, -c_-1, 2 c_0/sqrt 3]]`; the rotated form is `B = R A R^T`, of which only
//!   `B_xx, B_yy, B_xy, B_xz, B_yz` are needed (`B` is traceless):
//!   36 multiplies (45 for bands 0..2 with band 1), below the 57 to 93 of published
//!   written-out band-2 rotations.
//! - Any band ([`ShRotation`]): the recurrences of Ivanic and Ruedenberg, "Rotation Matrices
//!   for Real Spherical Harmonics. Direct Determination by Recursion", J. Phys. Chem. 100
//!   (1996) 6342, with the corrections of the 1998 erratum (J. Phys. Chem. A 102, 9099:
//!   the factor `(1 - 2 delta_m0)` of `v` and the `m = +-1` cases of `V`), computed for the
//!   basis without the Condon-Shortley phase and converted by `D_mn -> (-1)^(m+n) D_mn`.
//! - Zonal functions ([`rotate_zonal`]): a function symmetric about +z with coefficients
//!   `z_l` (of `Y_l0`), rotated so that +z goes to `d`, has
//!   `c_lm = sqrt(4 pi / (2l + 1)) z_l Y_lm(d)` (the addition theorem).

use super::basis::{eval_sh_f64, eval_sh_into, unit_direction};
use super::projection::lmax_of;
use crate::error::ParamError;
use crate::real::Real;
use glam::{DMat3, DVec3};

/// Largest `lmax` [`ShRotation::new`] accepts (the matrices hold about `4/3 lmax^3` values).
pub const MAX_ROTATION_LMAX: usize = 256;

/// Checks that `r` is a rotation (finite, `|R^T R - I| <= 1e-6` entrywise, `det R > 0`) and
/// returns it row-major: `m[i][j] = R_ij` (glam stores columns: `R_ij = r.col(j)[i]`).
///
/// # Errors
/// [`ParamError::OutOfRange`] naming `rotation` if the matrix is not finite, not orthogonal
/// within 1e-6, or has a non-positive determinant (a reflection).
pub fn check_rotation(r: DMat3) -> Result<[[f64; 3]; 3], ParamError> {
    let rows = [r.row(0), r.row(1), r.row(2)];
    let finite = rows.iter().all(|row| row.is_finite());
    let gram = r.transpose() * r;
    let err = (gram - DMat3::IDENTITY)
        .to_cols_array()
        .iter()
        .fold(0.0_f64, |a, &e| a.max(e.abs()));
    let det = r.determinant();
    let orthogonal = finite && err <= 1e-6;
    if !(orthogonal && det > 0.0) {
        return Err(ParamError::OutOfRange {
            name: "rotation",
            value: if orthogonal { det } else { err },
            allowed: "must be a rotation matrix: |R^T R - I| <= 1e-6 and det R > 0 \
                      (value shown: the orthogonality error, or the determinant)",
        });
    }
    Ok(rows.map(|row| row.to_array()))
}

/// Rotates band-1 coefficients `(c_-1, c_0, c_1)` by the row-major rotation `r`
/// (`r[i][j] = R_ij`): `c' = D_1 c` with `D_1` of the module documentation. 9 multiplies.
/// `r` is assumed orthonormal (see [`check_rotation`]).
#[inline(always)]
pub fn rotate_band1<R: Real>(r: &[[R; 3]; 3], c: [R; 3]) -> [R; 3] {
    // In (x, y, z) order the band-1 function is k a.v with a = (-c_1, -c_-1, c_0), rotated to
    // R a; b = R (c_1, c_-1, -c_0) = -R a, so c'_-1 = b_y, c'_0 = -b_z, c'_1 = b_x.
    let [cy, cz, cx] = c;
    let bx = r[0][0] * cx + r[0][1] * cy - r[0][2] * cz;
    let by = r[1][0] * cx + r[1][1] * cy - r[1][2] * cz;
    let bz = r[2][0] * cx + r[2][1] * cy - r[2][2] * cz;
    [by, -bz, bx]
}

/// Rotates band-2 coefficients `(c_-2, .., c_2)` by the row-major rotation `r`, written out
/// through the traceless quadratic form `B = R A R^T` (module documentation): 36 multiplies.
/// `r` is assumed orthonormal (see [`check_rotation`]).
#[inline(always)]
pub fn rotate_band2<R: Real>(r: &[[R; 3]; 3], c: [R; 5]) -> [R; 5] {
    let [cm2, cm1, c0, c1, c2] = c;
    let t = R::c(1.0 / 3f64.sqrt()) * c0;
    let (axx, ayy, azz) = (c2 - t, -c2 - t, t + t);
    let (axy, ayz, axz) = (cm2, -cm1, -c1);
    let av = |v: &[R; 3]| {
        [
            axx * v[0] + axy * v[1] + axz * v[2],
            axy * v[0] + ayy * v[1] + ayz * v[2],
            axz * v[0] + ayz * v[1] + azz * v[2],
        ]
    };
    let dot = |a: &[R; 3], b: [R; 3]| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
    let a0 = av(&r[0]);
    let a1 = av(&r[1]);
    let bxx = dot(&r[0], a0);
    let byy = dot(&r[1], a1);
    let bxy = dot(&r[0], a1);
    let bxz = dot(&r[2], a0);
    let byz = dot(&r[2], a1);
    [
        bxy,
        -byz,
        R::c(-0.5 * 3f64.sqrt()) * (bxx + byy),
        -bxz,
        R::c(0.5) * (bxx - byy),
    ]
}

/// Rotates the 9 coefficients of bands 0..2 ([`rotate_band1`], [`rotate_band2`]; band 0 is
/// invariant): 45 multiplies. `r` (row-major) is assumed orthonormal.
#[inline(always)]
pub fn rotate_bands012<R: Real>(r: &[[R; 3]; 3], c: [R; 9]) -> [R; 9] {
    let b1 = rotate_band1(r, [c[1], c[2], c[3]]);
    let b2 = rotate_band2(r, [c[4], c[5], c[6], c[7], c[8]]);
    [c[0], b1[0], b1[1], b1[2], b2[0], b2[1], b2[2], b2[3], b2[4]]
}

/// [`rotate_bands012`] in f64 with a validated `glam::DMat3`.
///
/// # Errors
/// As [`check_rotation`].
pub fn rotate_low_order(rotation: DMat3, c: [f64; 9]) -> Result<[f64; 9], ParamError> {
    let r = check_rotation(rotation)?;
    Ok(rotate_bands012(&r, c))
}

/// The SH rotation matrices `D_0 .. D_lmax` of one rotation, by the Ivanic-Ruedenberg
/// recurrences (module documentation). Accuracy in f64 at l = 30 (tests/sh_rotation.rs):
/// orthogonality 3e-14, composition 2e-14, point identity 9e-15 for a unit coefficient vector.
#[derive(Clone, Debug, PartialEq)]
pub struct ShRotation {
    blocks: Vec<Vec<f64>>,
}

impl ShRotation {
    /// The rotation matrices of bands `0..=lmax` for the rotation `rotation`.
    ///
    /// # Errors
    /// As [`check_rotation`], and [`ParamError::OutOfRange`] if
    /// `lmax > MAX_ROTATION_LMAX`.
    pub fn new(rotation: DMat3, lmax: usize) -> Result<Self, ParamError> {
        let r = check_rotation(rotation)?;
        ParamError::check(
            "lmax",
            lmax as f64,
            "must be at most MAX_ROTATION_LMAX = 256",
            |l| l <= MAX_ROTATION_LMAX as f64,
        )?;
        Ok(ShRotation {
            blocks: rotation_blocks(&r, lmax),
        })
    }

    /// Highest band held.
    pub fn lmax(&self) -> usize {
        self.blocks.len() - 1
    }

    /// `D_l` row-major: entry `(m + l) (2l + 1) + (n + l)` is `D_mn`; `None` if `l > lmax`.
    pub fn band(&self, l: usize) -> Option<&[f64]> {
        self.blocks.get(l).map(|b| b.as_slice())
    }

    /// Rotated coefficients `c'_l = D_l c_l` of `coefficients` (length `(L + 1)^2` with
    /// `L <= lmax`).
    ///
    /// # Errors
    /// [`ParamError::OutOfRange`] if the length is not a square or needs bands above `lmax`.
    pub fn apply(&self, coefficients: &[f64]) -> Result<Vec<f64>, ParamError> {
        let mut out = vec![0.0; coefficients.len()];
        self.apply_into(coefficients, &mut out)?;
        Ok(out)
    }

    /// [`ShRotation::apply`] into `out` (same length as `coefficients`).
    ///
    /// # Errors
    /// As [`ShRotation::apply`], and if `out.len() != coefficients.len()`.
    pub fn apply_into(&self, coefficients: &[f64], out: &mut [f64]) -> Result<(), ParamError> {
        let l_in = lmax_of(coefficients.len())?;
        ParamError::check(
            "coefficient lmax",
            l_in as f64,
            "must not exceed the rotation's lmax",
            |l| l <= self.lmax() as f64,
        )?;
        ParamError::check(
            "out.len()",
            out.len() as f64,
            "must equal coefficients.len()",
            |n| n == coefficients.len() as f64,
        )?;
        for l in 0..=l_in {
            let w = 2 * l + 1;
            let start = l * l;
            let block = &self.blocks[l];
            let src = &coefficients[start..start + w];
            for (i, o) in out[start..start + w].iter_mut().enumerate() {
                *o = block[i * w..(i + 1) * w]
                    .iter()
                    .zip(src)
                    .map(|(d, c)| d * c)
                    .sum();
            }
        }
        Ok(())
    }
}

/// The band matrices `D_0 .. D_lmax` of the rotation `r` (row-major, `r[i][j] = R_ij`,
/// assumed orthonormal), each row-major with entry `(m + l) (2l + 1) + (n + l)` = `D_mn`, in
/// any precision or as traced shader code: the Ivanic-Ruedenberg recurrences (module
/// documentation), whose branches depend on the band and the indices only. [`ShRotation`] is
/// these blocks in `f64`; [`rotate_with_blocks`] applies them.
pub fn rotation_blocks<R: Real>(r: &[[R; 3]; 3], lmax: usize) -> Vec<Vec<R>> {
    // Band 1 of the basis without Condon-Shortley phase: R permuted to (y, z, x).
    const P: [usize; 3] = [1, 2, 0];
    let r1: Vec<R> = (0..9).map(|k| r[P[k / 3]][P[k % 3]]).collect();
    let mut blocks = vec![vec![R::c(1.0)]];
    if lmax >= 1 {
        blocks.push(r1.clone());
    }
    for l in 2..=lmax {
        let next = ir_band(l, &r1, &blocks[l - 1]);
        blocks.push(next);
    }
    // Convert to the Condon-Shortley basis: Y_lm = (-1)^m Y^IR_lm.
    for (l, block) in blocks.iter_mut().enumerate() {
        let w = 2 * l + 1;
        for (k, value) in block.iter_mut().enumerate() {
            if (k / w + k % w) % 2 == 1 {
                *value = -*value;
            }
        }
    }
    blocks
}

/// `out_l = D_l c_l` band by band for the blocks of [`rotation_blocks`]; `coefficients` and
/// `out` hold the same bands `l <= blocks.len() - 1` (their common length `(L + 1)^2` decides
/// how many are rotated).
///
/// # Panics
/// If `out` is shorter than `coefficients`, or `coefficients` needs more bands than `blocks`
/// holds.
pub fn rotate_with_blocks<R: Real>(blocks: &[Vec<R>], coefficients: &[R], out: &mut [R]) {
    let mut l = 0;
    while (l + 1) * (l + 1) <= coefficients.len() {
        let (w, start) = (2 * l + 1, l * l);
        let source = &coefficients[start..start + w];
        for (i, o) in out[start..start + w].iter_mut().enumerate() {
            let row = &blocks[l][i * w..(i + 1) * w];
            let mut terms = row.iter().zip(source).map(|(&d, &c)| d * c);
            let first = terms.next().expect("a band has at least one coefficient");
            *o = terms.fold(first, |sum, term| sum + term);
        }
        l += 1;
    }
}

/// One Ivanic-Ruedenberg step: `M^l` from `R^1` (3x3, indices -1..1) and `M^{l-1}`.
fn ir_band<R: Real>(l: usize, r1: &[R], prev: &[R]) -> Vec<R> {
    let li = l as i64;
    let w = 2 * l + 1;
    let pw = 2 * l - 1;
    let r = |i: i64, j: i64| r1[((i + 1) * 3 + (j + 1)) as usize];
    let m_prev = |a: i64, b: i64| prev[((a + li - 1) * pw as i64 + (b + li - 1)) as usize];
    // P(i, a, b) of Ivanic and Ruedenberg (Table 2).
    let p = |i: i64, a: i64, b: i64| -> R {
        if b == li {
            r(i, 1) * m_prev(a, li - 1) - r(i, -1) * m_prev(a, -li + 1)
        } else if b == -li {
            r(i, 1) * m_prev(a, -li + 1) + r(i, -1) * m_prev(a, li - 1)
        } else {
            r(i, 0) * m_prev(a, b)
        }
    };
    let mut out = Vec::with_capacity(w * w);
    for m in -li..=li {
        for n in -li..=li {
            let d = if m == 0 { 1.0 } else { 0.0 };
            let am = m.abs();
            let denom = if n.abs() == li {
                (2 * li * (2 * li - 1)) as f64
            } else {
                ((li + n) * (li - n)) as f64
            };
            let u = (((li + m) * (li - m)) as f64 / denom).sqrt();
            let v = 0.5
                * ((1.0 + d) * ((li + am - 1) * (li + am)) as f64 / denom).sqrt()
                * (1.0 - 2.0 * d);
            let wc = -0.5 * (((li - am - 1) * (li - am)) as f64 / denom).sqrt() * (1.0 - d);
            // Terms with a zero factor are left out and unit factors not multiplied, so that
            // traced code holds only the arithmetic that matters.
            let mut terms: Vec<R> = Vec::with_capacity(3);
            if u != 0.0 {
                terms.push(R::c(u) * p(0, m, n));
            }
            if v != 0.0 {
                let (a, b) = if m == 0 {
                    ((1.0, p(1, 1, n)), (1.0, p(-1, -1, n)))
                } else if m > 0 {
                    let d1 = if m == 1 { 1.0 } else { 0.0 };
                    (
                        (2f64.sqrt().powf(d1), p(1, m - 1, n)),
                        (d1 - 1.0, p(-1, -m + 1, n)),
                    )
                } else {
                    let d1 = if m == -1 { 1.0 } else { 0.0 };
                    (
                        (1.0 - d1, p(1, m + 1, n)),
                        (2f64.sqrt().powf(d1), p(-1, -m - 1, n)),
                    )
                };
                let vv = weighted_sum(&[a, b]);
                terms.push(R::c(v) * vv);
            }
            if wc != 0.0 {
                let ww = if m > 0 {
                    p(1, m + 1, n) + p(-1, -m - 1, n)
                } else {
                    p(1, m - 1, n) - p(-1, -m + 1, n)
                };
                terms.push(R::c(wc) * ww);
            }
            let first = terms.first().copied().unwrap_or(R::c(0.0));
            out.push(terms.iter().skip(1).fold(first, |sum, &t| sum + t));
        }
    }
    out
}

/// `sum_k c_k x_k` over the `(c_k, x_k)` with `c_k != 0`, unit factors not multiplied; 0 if
/// every `c_k` is 0.
fn weighted_sum<R: Real>(terms: &[(f64, R)]) -> R {
    let scaled = terms
        .iter()
        .filter(|(c, _)| *c != 0.0)
        .map(|&(c, x)| match c {
            1.0 => x,
            -1.0 => -x,
            _ => R::c(c) * x,
        });
    scaled.reduce(|sum, t| sum + t).unwrap_or(R::c(0.0))
}

/// Coefficients of the zonal function with coefficients `zonal[l]` (of `Y_l0`, symmetric
/// about +z) rotated so that +z goes to `dir`: `c_lm = sqrt(4 pi / (2l + 1)) z_l Y_lm(dir)`
/// (Sloan 2008, "Stupid Spherical Harmonics Tricks", from the addition theorem). Any
/// `zonal.len() - 1 <= MAX_LMAX`; returns `zonal.len()^2` coefficients.
///
/// # Errors
/// [`ParamError::OutOfRange`] if `zonal` is empty or too long; [`ParamError::BadVector`] for
/// a zero or non-finite `dir`.
pub fn rotate_zonal(zonal: &[f64], dir: DVec3) -> Result<Vec<f64>, ParamError> {
    ParamError::check(
        "zonal.len()",
        zonal.len() as f64,
        "must be at least 1",
        |n| n >= 1.0,
    )?;
    let lmax = zonal.len() - 1;
    let mut y = eval_sh_f64(lmax, dir)?;
    for (l, &zl) in zonal.iter().enumerate() {
        let scale = (4.0 * core::f64::consts::PI / (2 * l + 1) as f64).sqrt() * zl;
        for v in &mut y[l * l..(l + 1) * (l + 1)] {
            *v *= scale;
        }
    }
    Ok(y)
}

/// [`rotate_zonal`] for up to [`super::basis::MAX_FAST_BANDS`] bands, generic over [`Real`] (shader-ready,
/// built on [`super::basis::eval_sh_into`]); `(x, y, z)` is assumed to be a unit vector.
/// Writes `zonal.len()^2` values to `out`.
///
/// # Errors
/// [`ParamError::OutOfRange`] if `zonal.len() > MAX_FAST_BANDS` or `out` is shorter than
/// `zonal.len()^2`.
pub fn rotate_zonal_into<R: Real>(
    zonal: &[R],
    x: R,
    y: R,
    z: R,
    out: &mut [R],
) -> Result<(), ParamError> {
    let bands = zonal.len();
    eval_sh_into(bands, x, y, z, out)?;
    for (l, &zl) in zonal.iter().enumerate() {
        let scale = R::c((4.0 * core::f64::consts::PI / (2 * l + 1) as f64).sqrt()) * zl;
        for v in &mut out[l * l..(l + 1) * (l + 1)] {
            *v *= scale;
        }
    }
    Ok(())
}

/// The rotation taking +z to the unit vector `dir` by the shortest arc (helper for tests and
/// for callers of [`rotate_zonal`] who need the full matrix).
///
/// # Errors
/// [`ParamError::BadVector`] for a zero or non-finite `dir`.
pub fn rotation_z_to(dir: DVec3) -> Result<DMat3, ParamError> {
    let d = unit_direction("dir", dir)?;
    Ok(DMat3::from_quat(glam::DQuat::from_rotation_arc(
        DVec3::Z,
        d,
    )))
}
