//! Evaluation of the real spherical harmonics `Y_lm(x, y, z)` on unit vectors.
//!
//! Convention (see [`crate::sh`]): real, orthonormal, Condon-Shortley phase, coefficient index
//! `l (l + 1) + m`, `cos(m phi)` for m > 0 and `sin(|m| phi)` for m < 0:
//!
//! ```text
//! Y_l0     = K_l0 P_l^0(z)
//! Y_l,+m   = sqrt(2) K_lm P_l^m(z) cos(m phi)      (m > 0)
//! Y_l,-m   = sqrt(2) K_lm P_l^m(z) sin(m phi)      (m > 0)
//! K_lm     = sqrt((2l + 1) / (4 pi) (l - m)! / (l + m)!)
//! P_l^m(z) = (-1)^m (1 - z^2)^(m/2) d^m/dz^m P_l(z)  (with the Condon-Shortley phase)
//! ```
//!
//! so `Y(1, -1) = -sqrt(3 / (4 pi)) y`, `Y(1, 0) = sqrt(3 / (4 pi)) z`, `Y(1, 1) = -sqrt(3 / (4 pi)) x`.
//!
//! Two evaluators:
//! - [`eval_sh`] (and [`eval_sh_into`]): up to [`MAX_FAST_BANDS`] bands, generic over
//!   [`Real`] (f32, f64, `f32x8`, traced), polynomial in `(x, y, z)`: no trigonometry, no
//!   division, all constants precomputed in f64. It follows Sloan 2013 ("Efficient Spherical
//!   Harmonic Evaluation", JCGT 2(2)): `Y_lm = Q_l^m(z) C_m(x, y)` (or `S_m`), with
//!   `C_m + i S_m = (x + i y)^m` from `C_m = x C_{m-1} - y S_{m-1}`, `S_m = x S_{m-1} + y C_{m-1}`,
//!   and `Q_l^m(z) = sqrt(2) K_lm (-1)^m P_l^(m)(z)` (the m-th derivative of the Legendre
//!   polynomial, normalisation folded in). `Q` is evaluated by Horner's rule in `z^2` while
//!   that costs at most 3 multiplies (degree `l - m <= 6`) and otherwise by the three-term
//!   recurrence `Q_l^m = a z Q_{l-1}^m + b Q_{l-2}^m` (3 multiplies). The multiply counts
//!   (measured by tracing, tests/sh_basis.rs) are at or below Sloan's published counts.
//! - [`eval_sh_f64`]: any band in f64 by the fully normalised associated Legendre recurrences
//!   (Holmes and Featherstone 2002, J. Geodesy 76, eqs. 11-13), which never form factorials,
//!   with a power-of-two exponent carried alongside the sectoral values so that nothing
//!   underflows before it is truly negligible.

use crate::error::ParamError;
use crate::real::Real;
use glam::DVec3;

/// Most bands [`eval_sh`] and [`eval_sh_into`] evaluate (`l <= 9`, 100 coefficients).
pub const MAX_FAST_BANDS: usize = 10;

/// Largest `lmax` [`eval_sh_f64`] accepts (its output has `(lmax + 1)^2` entries).
pub const MAX_LMAX: usize = 4096;

/// Number of coefficients of `bands` bands (`l < bands`): `bands^2`.
pub const fn coefficient_count(bands: usize) -> usize {
    bands * bands
}

/// Index of coefficient `(l, m)`: `l (l + 1) + m` (the crate's SH convention, [`crate::sh`]).
/// The inverse is [`crate::sh::index_to_lm`].
///
/// # Errors
/// [`ParamError::OutOfRange`] naming `m` if `|m| > l` (there is no such coefficient), or
/// naming `l` if the index does not fit in `usize` (l above about 4.3e9 on 64-bit targets).
pub const fn sh_index(l: usize, m: isize) -> Result<usize, ParamError> {
    if m.unsigned_abs() > l {
        return Err(ParamError::OutOfRange {
            name: "m",
            value: m as f64,
            allowed: "|m| must not exceed l",
        });
    }
    let index = match l.checked_add(1) {
        Some(next) => match l.checked_mul(next) {
            Some(band_centre) => band_centre.checked_add_signed(m),
            None => None,
        },
        None => None,
    };
    match index {
        Some(index) => Ok(index),
        None => Err(ParamError::OutOfRange {
            name: "l",
            value: l as f64,
            allowed: "l (l + 1) + m must fit in usize",
        }),
    }
}

/// Horner coefficients (ascending powers of `z^2`) of `Q_l^m(z) / z^((l - m) mod 2)` for
/// `0 <= m <= l <= 9`, entry `l (l + 1) / 2 + m`. Generated in f64 from the exact integer
/// coefficients of `d^m/dz^m P_l(z)` times `sqrt(2)^[m > 0] (-1)^m K_lm`; the unit test
/// `poly_table_matches_exact_formula` regenerates it.
const POLY: [[f64; 5]; 55] = [
    [0.28209479177387814, 0.0, 0.0, 0.0, 0.0], // l = 0, m = 0
    [0.4886025119029199, 0.0, 0.0, 0.0, 0.0],  // l = 1, m = 0
    [-0.4886025119029199, 0.0, 0.0, 0.0, 0.0], // l = 1, m = 1
    [-0.31539156525252005, 0.9461746957575601, 0.0, 0.0, 0.0], // l = 2, m = 0
    [-1.0925484305920792, 0.0, 0.0, 0.0, 0.0], // l = 2, m = 1
    [0.5462742152960396, 0.0, 0.0, 0.0, 0.0],  // l = 2, m = 2
    [-1.1195289977703462, 1.865881662950577, 0.0, 0.0, 0.0], // l = 3, m = 0
    [0.4570457994644658, -2.285228997322329, 0.0, 0.0, 0.0], // l = 3, m = 1
    [1.4453057213202771, 0.0, 0.0, 0.0, 0.0],  // l = 3, m = 2
    [-0.5900435899266435, 0.0, 0.0, 0.0, 0.0], // l = 3, m = 3
    [
        0.31735664074561293,
        -3.1735664074561294,
        3.7024941420321507,
        0.0,
        0.0,
    ], // l = 4, m = 0
    [2.007139630671867, -4.683325804901024, 0.0, 0.0, 0.0], // l = 4, m = 1
    [-0.47308734787878, 3.31161143515146, 0.0, 0.0, 0.0], // l = 4, m = 2
    [-1.7701307697799307, 0.0, 0.0, 0.0, 0.0], // l = 4, m = 3
    [0.6258357354491761, 0.0, 0.0, 0.0, 0.0],  // l = 4, m = 4
    [
        1.754254836801354,
        -8.186522571739651,
        7.367870314565687,
        0.0,
        0.0,
    ], // l = 5, m = 0
    [
        -0.45294665119569694,
        6.341253116739757,
        -9.511879675109636,
        0.0,
        0.0,
    ], // l = 5, m = 1
    [-2.396768392486662, 7.190305177459986, 0.0, 0.0, 0.0], // l = 5, m = 2
    [0.4892382994352504, -4.403144694917254, 0.0, 0.0, 0.0], // l = 5, m = 3
    [2.0756623148810416, 0.0, 0.0, 0.0, 0.0],  // l = 5, m = 4
    [-0.6563820568401701, 0.0, 0.0, 0.0, 0.0], // l = 5, m = 5
    [
        -0.3178460113381421,
        6.674766238100984,
        -20.024298714302954,
        14.684485723822165,
        0.0,
    ], // l = 6, m = 0
    [
        -2.9131068125936572,
        17.478640875561943,
        -19.226504963118135,
        0.0,
        0.0,
    ], // l = 6, m = 1
    [
        0.46060262975746175,
        -8.29084733563431,
        15.199886781996238,
        0.0,
        0.0,
    ], // l = 6, m = 2
    [2.7636157785447706, -10.133257854664159, 0.0, 0.0, 0.0], // l = 6, m = 3
    [-0.5045649007287242, 5.550213908015966, 0.0, 0.0, 0.0], // l = 6, m = 4
    [-2.366619162231752, 0.0, 0.0, 0.0, 0.0],  // l = 6, m = 5
    [0.6831841051919143, 0.0, 0.0, 0.0, 0.0],  // l = 6, m = 6
    [
        -2.3899496919201733,
        21.50954722728156,
        -47.32100390001943,
        29.293954795250123,
        0.0,
    ], // l = 7, m = 0
    [
        0.4516580379125866,
        -12.194767023639837,
        44.714145753346074,
        -38.75225965289993,
        0.0,
    ], // l = 7, m = 1
    [
        3.31899519333737,
        -24.339298084474045,
        31.64108750981626,
        0.0,
        0.0,
    ], // l = 7, m = 2
    [
        -0.46937680158688216,
        10.326289634911408,
        -22.37362754230805,
        0.0,
        0.0,
    ], // l = 7, m = 3
    [-3.113493472321562, 13.49180504672677, 0.0, 0.0, 0.0], // l = 7, m = 4
    [0.5189155787202603, -6.745902523363384, 0.0, 0.0, 0.0], // l = 7, m = 5
    [2.6459606618019005, 0.0, 0.0, 0.0, 0.0],  // l = 7, m = 6
    [-0.7071627325245963, 0.0, 0.0, 0.0, 0.0], // l = 7, m = 7
    [
        0.31803696720477487,
        -11.449330819371895,
        62.97131950654543,
        -109.15028714467873,
        58.47336811322075,
    ], // l = 8, m = 0
    [
        3.8164436064572986,
        -41.98087967103029,
        109.15028714467874,
        -77.96449081762768,
        0.0,
    ], // l = 8, m = 1
    [
        -0.4561522584349095,
        15.053024528352012,
        -65.22977295619205,
        65.22977295619205,
        0.0,
    ], // l = 8, m = 2
    [
        -3.705798465886632,
        32.116920037684146,
        -48.175380056526215,
        0.0,
        0.0,
    ], // l = 8, m = 3
    [
        0.4784165247593307,
        -12.438829643742599,
        31.097074109356495,
        0.0,
        0.0,
    ], // l = 8, m = 4
    [3.449910622098108, -17.24955311049054, 0.0, 0.0, 0.0], // l = 8, m = 5
    [-0.5323327660595426, 7.9849914908931385, 0.0, 0.0, 0.0], // l = 8, m = 6
    [-2.9157066406993195, 0.0, 0.0, 0.0, 0.0], // l = 8, m = 7
    [0.7289266601748299, 0.0, 0.0, 0.0, 0.0],  // l = 8, m = 8
    [
        3.0260245882817762,
        -44.381693961466055,
        173.08860644971762,
        -247.26943778531086,
        116.76612339861902,
    ], // l = 9, m = 0
    [
        -0.451093112065591,
        19.848096930886005,
        -129.01263005075904,
        258.0252601015181,
        -156.65819363306454,
    ], // l = 9, m = 1
    [
        -4.231628483960489,
        55.01117029148636,
        -165.03351087445907,
        133.59855642218116,
        0.0,
    ], // l = 9, m = 2
    [
        0.46170852001619445,
        -18.00663228063158,
        90.03316140315792,
        -102.03758292357897,
        0.0,
    ], // l = 9, m = 3
    [
        4.077699238729173,
        -40.776992387291735,
        69.32088705839595,
        0.0,
        0.0,
    ], // l = 9, m = 4
    [
        -0.4873782790390186,
        14.621348371170557,
        -41.427153718316575,
        0.0,
        0.0,
    ], // l = 9, m = 5
    [-3.7752159160427006, 21.392890190908638, 0.0, 0.0, 0.0], // l = 9, m = 6
    [0.5449054813440533, -9.263393182848905, 0.0, 0.0, 0.0], // l = 9, m = 7
    [3.1773176489546975, 0.0, 0.0, 0.0, 0.0],  // l = 9, m = 8
    [-0.7489009518531884, 0.0, 0.0, 0.0, 0.0], // l = 9, m = 9
];

/// Recurrence coefficients `(a, b)` with `Q_l^m = a z Q_{l-1}^m + b Q_{l-2}^m`, derived at
/// compile time from [`POLY`] (ratios of leading and trailing coefficients). Only entries with
/// `l - m >= 2` are meaningful.
const REC: [[f64; 2]; 55] = rec_table();

const fn tri(l: usize) -> usize {
    l * (l + 1) / 2
}

const fn rec_table() -> [[f64; 2]; 55] {
    let mut rec = [[0.0; 2]; 55];
    let mut l = 2;
    while l < MAX_FAST_BANDS {
        let mut m = 0;
        while m + 2 <= l {
            let d = l - m;
            let t = tri(l) + m;
            let t1 = tri(l - 1) + m;
            let t2 = tri(l - 2) + m;
            // Leading coefficient: lead(Q_l) = a lead(Q_{l-1}).
            let a = POLY[t][d / 2] / POLY[t1][(d - 1) / 2];
            // Lowest coefficient: even d: c0(Q_l) = b c0(Q_{l-2});
            // odd d: c0(Q_l) = a c0(Q_{l-1}) + b c0(Q_{l-2}).
            let b = if d % 2 == 0 {
                POLY[t][0] / POLY[t2][0]
            } else {
                (POLY[t][0] - a * POLY[t1][0]) / POLY[t2][0]
            };
            rec[t] = [a, b];
            m += 1;
        }
        l += 1;
    }
    rec
}

const fn bands_of(n: usize) -> usize {
    let mut b = 0;
    while b * b < n {
        b += 1;
    }
    b
}

/// The real SH basis of the first `sqrt(N)` bands at `(x, y, z)`, for `N` in
/// `{1, 4, 9, ..., 100}` (a non-square `N` or more than [`MAX_FAST_BANDS`] bands is a compile
/// error). Generic over [`Real`]: runs in f32, f64, `wide::f32x8` and traces to straight-line
/// shader code (all loops have fixed counts).
///
/// `(x, y, z)` should be a unit vector; otherwise the result is the harmonic polynomials'
/// values extended off the sphere (no normalisation is applied). Formulas: Sloan 2013,
/// "Efficient Spherical Harmonic Evaluation" (see the module documentation); multiply count
/// per band count, measured by tracing: 0, 3, 14, 28, 46, 69, 97, 130 for 1 to 8 bands
/// (Sloan: 14, 28, 47, 71 for 3 to 6 bands).
#[inline(always)]
pub fn eval_sh<R: Real, const N: usize>(x: R, y: R, z: R) -> [R; N] {
    let bands = const {
        let b = bands_of(N);
        assert!(
            b * b == N && b <= MAX_FAST_BANDS,
            "eval_sh: N must be a square band count^2 with at most MAX_FAST_BANDS bands"
        );
        b
    };
    let mut out = [R::c(0.0); N];
    eval_core(bands, x, y, z, &mut out);
    out
}

/// The real SH basis of the first `bands` bands at `(x, y, z)` written to `out[..bands^2]`
/// (same method and conventions as [`eval_sh`], with a run-time band count).
///
/// # Errors
/// [`ParamError::OutOfRange`] if `bands > MAX_FAST_BANDS` or `out` is shorter than
/// `bands^2`.
#[inline]
pub fn eval_sh_into<R: Real>(
    bands: usize,
    x: R,
    y: R,
    z: R,
    out: &mut [R],
) -> Result<(), ParamError> {
    ParamError::check(
        "bands",
        bands as f64,
        "must be at most MAX_FAST_BANDS = 10",
        |b| b <= MAX_FAST_BANDS as f64,
    )?;
    ParamError::check(
        "out.len()",
        out.len() as f64,
        "must be at least bands^2",
        |n| n >= (bands * bands) as f64,
    )?;
    eval_core(bands, x, y, z, out);
    Ok(())
}

#[inline(always)]
fn eval_core<R: Real>(bands: usize, x: R, y: R, z: R, out: &mut [R]) {
    if bands == 0 {
        return;
    }
    let z2 = z * z;
    let mut q = [R::c(0.0); 55];
    let (mut cm, mut sm) = (x, y);
    // The loops over m and l are written out (by this macro) so that the compiler unrolls
    // them completely when `bands` is a constant: every table index is then a constant.
    macro_rules! column {
        ($m:literal; $($l:literal)*) => {
            if $m < bands {
                if $m >= 2 {
                    let c = x * cm - y * sm;
                    let s = x * sm + y * cm;
                    cm = c;
                    sm = s;
                }
                $(
                    if $l < bands {
                        term(&mut q, out, $l, $m, z, z2, cm, sm);
                    }
                )*
            }
        };
    }
    column!(0; 0 1 2 3 4 5 6 7 8 9);
    column!(1; 1 2 3 4 5 6 7 8 9);
    column!(2; 2 3 4 5 6 7 8 9);
    column!(3; 3 4 5 6 7 8 9);
    column!(4; 4 5 6 7 8 9);
    column!(5; 5 6 7 8 9);
    column!(6; 6 7 8 9);
    column!(7; 7 8 9);
    column!(8; 8 9);
    column!(9; 9);
    let _ = (cm, sm);
}

/// `Y_l,+-m` from `Q_l^m(z)` and `C_m`, `S_m` (see [`eval_core`]).
#[inline(always)]
#[allow(clippy::too_many_arguments)]
fn term<R: Real>(q: &mut [R; 55], out: &mut [R], l: usize, m: usize, z: R, z2: R, cm: R, sm: R) {
    let d = l - m;
    let t = tri(l) + m;
    let p = &POLY[t];
    let v = match d {
        0 => R::c(p[0]),
        1 => R::c(p[0]) * z,
        2..=6 => {
            let mut acc = R::c(p[d / 2]);
            for k in (0..d / 2).rev() {
                acc = acc * z2 + R::c(p[k]);
            }
            if d % 2 == 1 {
                acc * z
            } else {
                acc
            }
        }
        _ => R::c(REC[t][0]) * z * q[tri(l - 1) + m] + R::c(REC[t][1]) * q[tri(l - 2) + m],
    };
    q[t] = v;
    let centre = l * (l + 1);
    if m == 0 {
        out[centre] = v;
    } else {
        out[centre + m] = v * cm;
        out[centre - m] = v * sm;
    }
}

/// The real SH basis for `l <= lmax` at the direction `dir` (normalised here), in f64, for
/// any `lmax <= MAX_LMAX`: `(lmax + 1)^2` values indexed `l (l + 1) + m`.
///
/// Method: the fully normalised associated Legendre functions
/// `Pbar_l^m = sqrt((2l+1)/(4 pi) (l-m)!/(l+m)!) P_l^m` by the recurrences (Holmes and
/// Featherstone 2002, eqs. 11-13; no factorials)
/// `Pbar_0^0 = 1/sqrt(4 pi)`, `Pbar_m^m = -sqrt((2m+1)/(2m)) sin(theta) Pbar_{m-1}^{m-1}`,
/// `Pbar_{m+1}^m = sqrt(2m+3) z Pbar_m^m`,
/// `Pbar_l^m = a_lm (z Pbar_{l-1}^m - b_lm Pbar_{l-2}^m)` with
/// `a_lm = sqrt((4l^2-1)/(l^2-m^2))`, `b_lm = sqrt(((l-1)^2-m^2)/(4(l-1)^2-1))`;
/// then `Y_l,+-m = sqrt(2) Pbar_l^m cos / sin(m phi)`. The sectoral values carry a separate
/// power-of-two exponent, so `sin(theta)^m` never underflows prematurely. Accuracy
/// (tests/sh_basis.rs, l <= 1000): `sum_m Y_lm^2 = (2l+1)/(4 pi)` to 2.3e-12 relative, `Y_l0`
/// against the Legendre three-term recurrence to 1.2e-12 of `sqrt((2l+1)/(4 pi))`.
///
/// # Errors
/// [`ParamError::OutOfRange`] if `lmax > MAX_LMAX`; [`ParamError::BadVector`] if `dir` is
/// zero or not finite.
pub fn eval_sh_f64(lmax: usize, dir: DVec3) -> Result<Vec<f64>, ParamError> {
    check_lmax(lmax)?;
    let mut out = vec![0.0; (lmax + 1) * (lmax + 1)];
    eval_sh_f64_into(lmax, dir, &mut out)?;
    Ok(out)
}

pub(crate) fn check_lmax(lmax: usize) -> Result<usize, ParamError> {
    ParamError::check(
        "lmax",
        lmax as f64,
        "must be at most MAX_LMAX = 4096",
        |l| l <= MAX_LMAX as f64,
    )?;
    Ok(lmax)
}

/// Normalises `dir`, or reports it as [`ParamError::BadVector`].
pub(crate) fn unit_direction(name: &'static str, dir: DVec3) -> Result<DVec3, ParamError> {
    let len = dir.length();
    if dir.is_finite() && len > 0.0 && len.is_finite() {
        Ok(dir / len)
    } else {
        Err(ParamError::BadVector {
            name,
            x: dir.x,
            y: dir.y,
            z: dir.z,
            allowed: "must be finite and non-zero",
        })
    }
}

/// [`eval_sh_f64`] writing into `out[..(lmax + 1)^2]` (no allocation).
///
/// # Errors
/// As [`eval_sh_f64`], and [`ParamError::OutOfRange`] if `out` is shorter than `(lmax + 1)^2`.
pub fn eval_sh_f64_into(lmax: usize, dir: DVec3, out: &mut [f64]) -> Result<(), ParamError> {
    check_lmax(lmax)?;
    let n = (lmax + 1) * (lmax + 1);
    ParamError::check(
        "out.len()",
        out.len() as f64,
        "must be at least (lmax + 1)^2",
        |len| len >= n as f64,
    )?;
    let d = unit_direction("dir", dir)?;
    // Near a pole the recurrence is sensitive to 1 - |z| (a systematic error of z is amplified
    // by about l^2: 3e-11 at l = 1000 one milliradian from the pole if z is merely rounded), so
    // there z p is computed as +-(p - gap p) with gap = 1 - |z| = s^2 / (1 + |z|), accurate to
    // rounding because s = sin(theta) is.
    let rho = d.x.hypot(d.y);
    let s = rho;
    let z = d.z.clamp(-1.0, 1.0);
    let gap = s * s / (1.0 + z.abs());
    let z_times = |p: f64| {
        if z > 0.7 {
            p - gap * p
        } else if z < -0.7 {
            gap * p - p
        } else {
            z * p
        }
    };
    let phi = if rho > 0.0 { d.y.atan2(d.x) } else { 0.0 };
    const BIG: f64 = 1.0715086071862673e301; // 2^1000
    const SMALL: f64 = 9.332636185032189e-302; // 2^-1000
                                               // Sectoral value Pbar_m^m = pmm * 2^(-1000 * pexp).
    let mut pmm = 0.5 / core::f64::consts::PI.sqrt();
    let mut pexp: i32 = 0;
    for m in 0..=lmax {
        if m > 0 {
            pmm *= -((2 * m + 1) as f64 / (2 * m) as f64).sqrt() * s;
            if pmm != 0.0 && pmm.abs() < SMALL {
                pmm *= BIG;
                pexp += 1;
            }
        }
        let (sin_m, cos_m) = if m == 0 {
            (0.0, 1.0)
        } else {
            (m as f64 * phi).sin_cos()
        };
        let mf = m as f64;
        let mut emit = |l: usize, value: f64, exp: i32| {
            let v = scale_down(value, exp);
            let c = l * (l + 1);
            if m == 0 {
                out[c] = v;
            } else {
                out[c + m] = core::f64::consts::SQRT_2 * v * cos_m;
                out[c - m] = core::f64::consts::SQRT_2 * v * sin_m;
            }
        };
        emit(m, pmm, pexp);
        if m == lmax {
            break;
        }
        let mut exp = pexp;
        let mut p2 = pmm;
        let mut p1 = (2.0 * mf + 3.0).sqrt() * z * pmm;
        emit(m + 1, p1, exp);
        for l in (m + 2)..=lmax {
            let lf = l as f64;
            let a = ((4.0 * lf * lf - 1.0) / ((lf - mf) * (lf + mf))).sqrt();
            let b = (((lf - 1.0 - mf) * (lf - 1.0 + mf)) / (4.0 * (lf - 1.0) * (lf - 1.0) - 1.0))
                .sqrt();
            let p = a * (z_times(p1) - b * p2);
            p2 = p1;
            p1 = p;
            if exp > 0 && p1.abs() > 3.273390607896142e150 {
                // 2^500: move the scale back towards the true magnitude.
                p1 *= SMALL;
                p2 *= SMALL;
                exp -= 1;
            }
            emit(l, p1, exp);
        }
    }
    Ok(())
}

/// `value * 2^(-1000 exp)` without intermediate underflow of the scale factor.
fn scale_down(mut value: f64, exp: i32) -> f64 {
    const SMALL: f64 = 9.332636185032189e-302; // 2^-1000
    for _ in 0..exp {
        value *= SMALL;
        if value == 0.0 {
            break;
        }
    }
    value
}

#[cfg(test)]
mod tests {
    use super::*;

    fn binom(n: u64, k: u64) -> u128 {
        let mut r: u128 = 1;
        for i in 0..k {
            r = r * (n - i) as u128 / (i + 1) as u128;
        }
        r
    }

    /// Regenerates [`POLY`] from the exact integer coefficients of d^m/dz^m P_l(z)
    /// (Rodrigues: P_l = 2^-l sum_k (-1)^k C(l,k) C(2l-2k,l) z^(l-2k)).
    #[test]
    fn poly_table_matches_exact_formula() {
        let fact = |n: u64| (1..=n).map(|k| k as f64).product::<f64>();
        for l in 0..MAX_FAST_BANDS as u64 {
            for m in 0..=l {
                let k2 =
                    (2 * l + 1) as f64 / (4.0 * core::f64::consts::PI) * fact(l - m) / fact(l + m);
                let mut norm = if m > 0 { (2.0 * k2).sqrt() } else { k2.sqrt() };
                if m % 2 == 1 {
                    norm = -norm;
                }
                let d = l - m;
                let mut c = [0.0f64; 5];
                let mut k = 0;
                while 2 * k + m <= l {
                    let p = l - 2 * k - m;
                    let falling: i128 =
                        (l - 2 * k - m + 1..=l - 2 * k).map(|v| v as i128).product();
                    let sign: i128 = if k % 2 == 0 { 1 } else { -1 };
                    let ic = sign * (binom(l, k) * binom(2 * l - 2 * k, l)) as i128 * falling;
                    c[((p - d % 2) / 2) as usize] = norm * ic as f64 / 2f64.powi(l as i32);
                    k += 1;
                }
                let t = tri(l as usize) + m as usize;
                for j in 0..5 {
                    assert!(
                        (c[j] - POLY[t][j]).abs() <= 4.0 * f64::EPSILON * c[j].abs(),
                        "l {l} m {m} j {j}: {} vs table {}",
                        c[j],
                        POLY[t][j]
                    );
                }
            }
        }
    }

    #[test]
    fn scale_down_handles_deep_exponents() {
        assert_eq!(scale_down(3.0, 0), 3.0);
        assert_eq!(scale_down(2f64.powi(900), 1), 2f64.powi(-100));
        assert_eq!(scale_down(1.0, 3), 0.0);
    }
}
