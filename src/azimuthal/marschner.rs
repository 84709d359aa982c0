//! Marschner et al. 2003's azimuthal scattering function N_p for a smooth circular fibre
//! (Marschner, Jensen, Cammarano, Worley, Hanrahan, "Light Scattering from Human Hair Fibers",
//! SIGGRAPH 2003, section 4 and Table 1). Reference-only `f64` code: it solves cubics with
//! data-dependent branches and is not generic over [`crate::real::Real`].
//!
//! # Geometry and conventions
//!
//! `phi` is the relative azimuth `phi_o - phi_i` (Marschner's `phi_r - phi_i`) in radians; every
//! function here is 2 pi periodic in it, so any real value is accepted. `gamma` is the angle of
//! incidence in the normal plane, `h = sin gamma` the offset in units of the fibre radius.
//! Like Marschner, the azimuthal problem is solved at the inclination theta_d (the half
//! difference angle): the in-plane Snell law uses Bravais' index
//! `eta' = sqrt(eta^2 - sin^2 theta_d) / cos theta_d` ([`bravais_eta_perpendicular`]) and the
//! p-polarised Fresnel term `eta'' = eta^2 cos theta_d / sqrt(eta^2 - sin^2 theta_d)`
//! ([`bravais_eta_parallel`]). `sigma_a` is per unit fibre radius.
//!
//! # The cubic exit angle (Marschner eq. 10), derived
//!
//! The exact exit angle is `Phi(p, h) = 2 p gamma_t - 2 gamma_i + p pi` (eq. 3,
//! [`crate::azimuthal::exit_angle`]), `gamma_i = asin h`, `gamma_t = asin(h / eta')`. Marschner
//! replaces `gamma_t(gamma_i)` by the odd cubic `(3 c / pi) g - (4 c / pi^3) g^3`,
//! `c = asin(1 / eta')`: the unique odd cubic `alpha g + beta g^3` with the exact end value
//! `gamma_t(pi/2) = c` and the exact end slope `d gamma_t / d gamma_i (pi/2) = cos gamma_i /
//! (eta' cos gamma_t) = 0` (solve `alpha pi/2 + beta pi^3/8 = c`, `alpha + 3 beta pi^2/4 = 0`).
//! Substituting gives
//! `Phi~(p, g) = (6 p c / pi - 2) g - (8 p c / pi^3) g^3 + p pi`, exact at `g = 0, +-pi/2`,
//! with `dPhi~/dg = -2` at `g = +-pi/2` for every p and eta'. Over eta' in [1.2, 3] the cubic
//! differs from the exact Phi by at most 0.0965 p radians (measured in `tests/marschner.rs`;
//! the worst case is eta' = 1.2, |h| ~ 0.64; 0.0188 p at eta' = 1.55).
//!
//! # N_p (Marschner eq. 8) and energy
//!
//! `N_p(phi) = sum over roots h_r of Phi~(p, h) = phi (mod 2 pi) of A(p, h_r) / |2 dPhi/dh|`,
//! with `dPhi/dh = (dPhi~/dg) / cos g` (chain rule through `g = asin h`, as the paper does).
//! Because every root of the cubic map is summed, the change of variables `phi = Phi~(p, h)`
//! gives the identity `int_{-pi}^{pi} N_p dphi = (1/2) int_{-1}^{1} A(p, h) dh` exactly for the
//! cubic map (tested by quadrature).
//!
//! At a caustic (dPhi/dh = 0, only TRT for eta' < 2 with the cubic) `1/|dPhi/dh|` is an
//! integrable `1/sqrt` singularity; the code floors `|dPhi/dh|` at [`MIN_DPHI_DH`] so that
//! values stay finite (at most `A / (2 MIN_DPHI_DH)`). At a caustic the floor only acts within
//! about `MIN_DPHI_DH^2 / |Phi''|` radians of the singular angle, far below f64 resolution of
//! phi, so integrals are unaffected. At eta' = 2 the two TRT caustics merge into a cusp
//! (`Phi~ - 2 pi ~ a g^3`, `N ~ |phi|^(-2/3)`): there the floor acts within ~1e-18 rad and
//! removes a relative ~2e-7 of the TRT energy (measured in `tests/marschner.rs`).

use core::f64::consts::{FRAC_PI_2, PI, TAU};

use crate::absorption::{segment_transmittance, PathLength};
use crate::error::ParamError;
use crate::fresnel::{bravais_eta_parallel, bravais_eta_perpendicular};

/// The largest path index accepted: Marschner's model has R (p = 0), TT (1) and TRT (2); p = 3
/// is accepted because the same cubic construction applies. Larger p would need more root
/// capacity than [`ROOT_CAPACITY`].
pub const MARSCHNER_MAX_P: u32 = 3;

/// A scattering path of Marschner's model: the number p of internal segments, as a type, so
/// that root solving cannot be asked for a path it does not model.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum MarschnerPath {
    /// p = 0: surface reflection.
    R,
    /// p = 1: transmission through the fibre.
    TT,
    /// p = 2: one internal reflection.
    TRT,
    /// p = 3: two internal reflections.
    TRRT,
}

impl MarschnerPath {
    /// The paths in order of p.
    pub const ALL: [MarschnerPath; 4] = [Self::R, Self::TT, Self::TRT, Self::TRRT];

    /// The path with `p` internal segments.
    ///
    /// # Errors
    /// `p` greater than [`MARSCHNER_MAX_P`].
    pub fn from_p(p: u32) -> Result<Self, crate::error::ParamError> {
        crate::error::ParamError::check(
            "p",
            f64::from(p),
            "the path count p must be 0, 1, 2 or 3",
            |v| v <= f64::from(MARSCHNER_MAX_P),
        )?;
        Ok(Self::ALL[p as usize])
    }

    /// The number of internal segments p.
    pub fn p(self) -> u32 {
        self as u32
    }
}

/// Capacity of a [`RootList`]. Phi~ has at most two critical points, so [-pi/2, pi/2] splits
/// into at most three monotone pieces; the total variation of Phi~ is at most
/// `4 p c + 2 pi <= 2 pi (p + 1)`, so the pieces meet the levels `phi + 2 pi k` at most
/// `p + 4 <= 7` times for p <= 3.
pub const ROOT_CAPACITY: usize = 8;

/// Floor on `|dPhi/dh|` in the weight `1 / |2 dPhi/dh|` of a root (see the module docs):
/// caps the contribution of a root exactly at a caustic at `A / (2 MIN_DPHI_DH)`.
pub const MIN_DPHI_DH: f64 = 1e-12;

/// Two roots from the same cubic closer than this (radians) are one double root. A double
/// root computed in f64 is only determined to about `sqrt(epsilon) ~ 1.5e-8`, so closer pairs
/// cannot be told apart; they occur only within ~1e-14 rad of phi of the caustic.
const DOUBLE_ROOT_TOLERANCE: f64 = 1e-7;

/// Roots within this distance outside [-pi/2, pi/2] are clamped to the interval.
const EDGE_TOLERANCE: f64 = 1e-10;

/// The roots gamma in [-pi/2, pi/2] of `Phi~(p, gamma) = phi (mod 2 pi)`, sorted ascending,
/// without allocation. Dereferences to `&[f64]`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RootList {
    roots: [f64; ROOT_CAPACITY],
    len: usize,
}

impl RootList {
    fn new() -> Self {
        RootList {
            roots: [0.0; ROOT_CAPACITY],
            len: 0,
        }
    }

    fn push(&mut self, gamma: f64) {
        assert!(self.len < ROOT_CAPACITY, "RootList capacity exceeded");
        self.roots[self.len] = gamma;
        self.len += 1;
    }

    /// The roots as a slice.
    pub fn as_slice(&self) -> &[f64] {
        &self.roots[..self.len]
    }
}

impl core::ops::Deref for RootList {
    type Target = [f64];
    fn deref(&self) -> &[f64] {
        self.as_slice()
    }
}

/// `c = asin(1 / eta')`, the critical angle of the virtual index (Marschner eq. 10); `eta'`
/// below 1 is treated as 1.
pub fn marschner_critical_angle(eta_prime: f64) -> f64 {
    (1.0 / eta_prime.max(1.0)).min(1.0).asin()
}

/// Coefficients (a, b) of `Phi~(p, g) = a g^3 + b g + p pi`.
fn cubic_coefficients(p: u32, eta_prime: f64) -> (f64, f64) {
    let c = marschner_critical_angle(eta_prime);
    let p = f64::from(p);
    (-8.0 * p * c / (PI * PI * PI), 6.0 * p * c / PI - 2.0)
}

/// Marschner's cubic exit angle `Phi~(p, gamma) = (6 p c / pi - 2) gamma - (8 p c / pi^3)
/// gamma^3 + p pi`, `c = asin(1 / eta')` (Marschner 2003, eq. 10; derivation in the module
/// docs). Not wrapped.
pub fn marschner_exit_angle(p: u32, gamma: f64, eta_prime: f64) -> f64 {
    let (a, b) = cubic_coefficients(p, eta_prime);
    (a * gamma * gamma + b) * gamma + f64::from(p) * PI
}

/// `dPhi~/dgamma = (6 p c / pi - 2) - (24 p c / pi^3) gamma^2`.
pub fn marschner_exit_angle_derivative(p: u32, gamma: f64, eta_prime: f64) -> f64 {
    let (a, b) = cubic_coefficients(p, eta_prime);
    3.0 * a * gamma * gamma + b
}

/// Real roots of `a g^3 + b g + d` (no quadratic term), not yet polished or filtered.
/// Returns up to three values in `out` and their count.
fn depressed_cubic_roots(a: f64, b: f64, d: f64, out: &mut [f64; 3]) -> usize {
    // The cubic term is negligible on |g| <= pi/2: the other two roots lie at
    // |g| ~ sqrt(|b / a|) > 1e6, far outside the interval. Solve the linear equation.
    if a.abs() * FRAC_PI_2 * FRAC_PI_2 <= 1e-13 * b.abs() {
        out[0] = -d / b;
        return 1;
    }
    // t^3 + P t + Q = 0.
    let p = b / a;
    let q = d / a;
    if p == 0.0 {
        out[0] = -q.cbrt();
        return 1;
    }
    if p < 0.0 {
        let m = (-p / 3.0).sqrt();
        // r = (3 Q / (2 P)) sqrt(-3 / P); three real roots iff |r| <= 1 (4 P^3 + 27 Q^2 <= 0).
        let r = -q / (2.0 * m * m * m);
        // |r| within 1e-13 of 1 is a double root whose discriminant sign is lost to rounding:
        // take the trigonometric branch with r clamped, so the double root is not dropped.
        if r.abs() <= 1.0 + 1e-13 {
            // Trigonometric (Viete) form: t_k = 2 m cos(acos(r) / 3 - 2 pi k / 3).
            let theta = r.clamp(-1.0, 1.0).acos() / 3.0;
            for (k, o) in out.iter_mut().enumerate() {
                *o = 2.0 * m * (theta - TAU * k as f64 / 3.0).cos();
            }
            3
        } else {
            // One real root, hyperbolic form of Cardano's formula (no cancellation between
            // the two cube roots): t = -2 sign(Q) m cosh(acosh(|r|) / 3).
            out[0] = -2.0 * q.signum() * m * (r.abs().acosh() / 3.0).cosh();
            1
        }
    } else {
        // P > 0: one real root, t = -2 m sinh(asinh(Q / (2 m^3)) / 3); accurate also when
        // Q / (2 m^3) is tiny (then t ~ -Q / P).
        let m = (p / 3.0).sqrt();
        out[0] = -2.0 * m * ((q / (2.0 * m * m * m)).asinh() / 3.0).sinh();
        1
    }
}

/// Newton steps on `a g^3 + b g + d`, each accepted only if it lowers the residual.
fn polish(a: f64, b: f64, d: f64, mut g: f64) -> f64 {
    let f = |g: f64| (a * g * g + b) * g + d;
    let mut fg = f(g);
    for _ in 0..3 {
        let df = 3.0 * a * g * g + b;
        if fg == 0.0 || df == 0.0 {
            break;
        }
        let next = g - fg / df;
        let fnext = f(next);
        if fnext.abs() < fg.abs() {
            g = next;
            fg = fnext;
        } else {
            break;
        }
    }
    g
}

/// All gamma in [-pi/2, pi/2] with `Phi~(p, gamma) = phi (mod 2 pi)` for Marschner's cubic
/// exit angle ([`marschner_exit_angle`]), sorted ascending.
///
/// Method: the range of Phi~ on [-pi/2, pi/2] (end values and interior critical values
/// `g* = +-sqrt(-b / (3 a))`) gives the shifts k for which `phi + 2 pi k` can be reached; each
/// shift is the depressed cubic `a g^3 + b g + (p pi - phi - 2 pi k) = 0`, solved in closed
/// form (Viete's trigonometric form for three real roots, the hyperbolic form of Cardano's
/// formula for one, the linear equation when the cubic term is negligible, e.g. p = 0), then
/// polished by safeguarded Newton steps. Roots within 1e-10 outside the interval are clamped
/// to its ends; roots of one shift closer than 1e-7 to each other are merged into one multiple
/// root (their mean). For p = 0 the single root is `gamma = -phi / 2` (wrapped).
///
pub fn marschner_roots(path: MarschnerPath, phi: f64, eta_prime: f64) -> RootList {
    let p = path.p();
    let (a, b) = cubic_coefficients(p, eta_prime);
    let pp = f64::from(p) * PI;
    let value = |g: f64| (a * g * g + b) * g + pp;
    let (mut lo, mut hi) = {
        let (u, v) = (value(-FRAC_PI_2), value(FRAC_PI_2));
        (u.min(v), u.max(v))
    };
    if a != 0.0 && -b / (3.0 * a) > 0.0 {
        let gc = (-b / (3.0 * a)).sqrt();
        if gc < FRAC_PI_2 {
            for g in [-gc, gc] {
                lo = lo.min(value(g));
                hi = hi.max(value(g));
            }
        }
    }
    let tol = 1e-12 * (1.0 + lo.abs().max(hi.abs()));
    let k_min = ((lo - tol - phi) / TAU).ceil() as i64;
    let k_max = ((hi + tol - phi) / TAU).floor() as i64;
    let mut list = RootList::new();
    for k in k_min..=k_max {
        let d = pp - phi - TAU * k as f64;
        let mut raw = [0.0; 3];
        let n = depressed_cubic_roots(a, b, d, &mut raw);
        let mut kept = [0.0; 3];
        let mut n_kept = 0;
        for &g0 in &raw[..n] {
            let g = polish(a, b, d, g0);
            if !g.is_finite() || g.abs() > FRAC_PI_2 + EDGE_TOLERANCE {
                continue;
            }
            let g = g.clamp(-FRAC_PI_2, FRAC_PI_2);
            // Guard against garbage from a degenerate closed form: the residual of a true root
            // is at rounding level (plus at most 2e-10 from clamping at the ends).
            let residual = ((a * g * g + b) * g + d).abs();
            if residual > 1e-8 * (1.0 + d.abs()) {
                continue;
            }
            kept[n_kept] = g;
            n_kept += 1;
        }
        let kept = &mut kept[..n_kept];
        kept.sort_by(f64::total_cmp);
        // Merge clusters of roots closer than DOUBLE_ROOT_TOLERANCE (a double root, or the
        // triple root of p = 2 at eta' = 2, phi = 0) into their mean.
        let mut i = 0;
        while i < kept.len() {
            let mut j = i + 1;
            while j < kept.len() && kept[j] - kept[j - 1] <= DOUBLE_ROOT_TOLERANCE {
                j += 1;
            }
            list.push(kept[i..j].iter().sum::<f64>() / (j - i) as f64);
            i = j;
        }
    }
    list.roots[..list.len].sort_by(f64::total_cmp);
    list
}

/// The polarisations of Fresnel's equations.
#[derive(Clone, Copy)]
enum Polarisation {
    /// s (perpendicular): `r_s = (cos_i - n cos_t) / (cos_i + n cos_t)`.
    S,
    /// p (parallel): `r_p = (n cos_i - cos_t) / (n cos_i + cos_t)`.
    P,
}

/// The reflectance `r^2` of one polarisation for relative index `n` (transmitted over
/// incident) at an angle of incidence with sine `sin_i`, Snell `sin_t = sin_i / n`; 1 under
/// total internal reflection.
fn reflectance(polarisation: Polarisation, n: f64, sin_i: f64) -> f64 {
    let cos_i = (1.0 - sin_i * sin_i).max(0.0).sqrt();
    let sin_t = sin_i / n;
    if sin_t.abs() >= 1.0 {
        return 1.0;
    }
    let cos_t = (1.0 - sin_t * sin_t).sqrt();
    let (num, den) = match polarisation {
        Polarisation::S => (cos_i - n * cos_t, cos_i + n * cos_t),
        Polarisation::P => (n * cos_i - cos_t, n * cos_i + cos_t),
    };
    if den <= 0.0 {
        return 1.0;
    }
    (num / den).powi(2).min(1.0)
}

/// Marschner's two-index Fresnel factor `F(eta', eta'', gamma)` (Marschner 2003, appendix B):
/// the mean of the s-polarised reflectance computed with `eta_perp` (eta') and the
/// p-polarised reflectance computed with `eta_par` (eta''), both at the in-plane angle of
/// incidence with sine `sin_gamma`, each with its own Snell law `sin_t = sin_gamma / n`
/// (total internal reflection gives 1 for that polarisation). For light inside the fibre
/// pass the reciprocals `1 / eta'`, `1 / eta''` and `sin gamma_t`. With `eta_perp = eta_par =
/// eta` this is the ordinary unpolarised Fresnel reflectance
/// ([`crate::fresnel::fresnel_dielectric`]).
///
/// Note: eta'' < 1 when `sin^2 theta_d > eta^2 / (eta^2 + 1)` (theta_d > 57 degrees for
/// eta = 1.55); the p-polarised entry term then "totally reflects" for `h > eta''`. This is
/// a property of the virtual-index construction, kept as published.
pub fn marschner_fresnel(eta_perp: f64, eta_par: f64, sin_gamma: f64) -> f64 {
    0.5 * (reflectance(Polarisation::S, eta_perp, sin_gamma)
        + reflectance(Polarisation::P, eta_par, sin_gamma))
}

/// The indices and cosine Marschner's azimuthal problem uses at inclination theta_d.
#[derive(Clone, Copy, Debug)]
struct Medium {
    eta_perp: f64,
    eta_par: f64,
    cos_theta_t: f64,
}

impl Medium {
    fn new(eta: f64, sin_theta_d: f64) -> Self {
        let s = sin_theta_d.clamp(-1.0, 1.0);
        Medium {
            eta_perp: bravais_eta_perpendicular(eta, s),
            eta_par: bravais_eta_parallel(eta, s),
            // sin theta_t = sin theta_d / eta (Snell along the fibre axis).
            cos_theta_t: (1.0 - s * s / (eta * eta)).max(0.0).sqrt(),
        }
    }

    /// A(p, h) per channel (see [`marschner_attenuation`]).
    fn attenuation(&self, p: u32, h: f64, sigma_a: [f64; 3]) -> [f64; 3] {
        let f_entry = marschner_fresnel(self.eta_perp, self.eta_par, h);
        if p == 0 {
            return [f_entry; 3];
        }
        let sin_gamma_t = (h / self.eta_perp).clamp(-1.0, 1.0);
        let cos_gamma_t = (1.0 - sin_gamma_t * sin_gamma_t).sqrt();
        let f_inside = marschner_fresnel(1.0 / self.eta_perp, 1.0 / self.eta_par, sin_gamma_t);
        let fresnel = (1.0 - f_entry) * (1.0 - f_inside) * f_inside.powi(p as i32 - 1);
        sigma_a.map(|s| {
            let t =
                segment_transmittance(s, cos_gamma_t, self.cos_theta_t, PathLength::Marschner2003);
            fresnel * t.powi(p as i32)
        })
    }
}

/// Marschner's attenuation A(p, h) per RGB channel (Marschner 2003, section 4.2 and
/// appendix B), for offset `h` in [-1, 1], relative index `eta > 1`, inclination theta_d
/// (its sine) and absorption `sigma_a` per unit radius:
///
/// - `A(0, h) = F(eta', eta'', gamma_i)`;
/// - `A(p, h) = (1 - F(eta', eta'', gamma_i)) (1 - F(1/eta', 1/eta'', gamma_t))
///   F(1/eta', 1/eta'', gamma_t)^(p-1) T^p` for p >= 1,
///
/// with `gamma_i = asin h`, `gamma_t = asin(h / eta')`, F from [`marschner_fresnel`] and
/// `T = exp(-2 sigma_a' (1 + cos 2 gamma_t))`, `sigma_a' = sigma_a / cos theta_t`,
/// `sin theta_t = sin theta_d / eta`. Since `1 + cos 2 gamma_t = 2 cos^2 gamma_t`,
/// `T = exp(-4 sigma_a cos^2 gamma_t / cos theta_t)`, which is exactly
/// `segment_transmittance(sigma_a, cos gamma_t, cos theta_t, PathLength::Marschner2003)`
/// (checked by a unit test). The exit factor `1 - F(1/eta', 1/eta'', gamma_t)` equals the
/// entry factor for the s term but not exactly for the p term (gamma_t comes from eta', not
/// eta''), so both are evaluated.
pub fn marschner_attenuation(
    p: u32,
    h: f64,
    eta: f64,
    sin_theta_d: f64,
    sigma_a: [f64; 3],
) -> [f64; 3] {
    Medium::new(eta, sin_theta_d).attenuation(p, h.clamp(-1.0, 1.0), sigma_a)
}

/// Parameters of Marschner's TRT caustic treatment (Marschner 2003, section 4.3 and Table 1).
/// Angles in radians. Construct with [`CausticParams::new`] or take the defaults.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CausticParams {
    glint_scale: f64,
    caustic_width: f64,
    fade_range: f64,
    caustic_limit: f64,
}

impl Default for CausticParams {
    /// k_G = 0.5, w_c = 15 degrees, Delta eta* = 0.3, Delta h_M = 0.5 (within Marschner's
    /// Table 1 ranges; Delta h_M is the paper's value).
    fn default() -> Self {
        CausticParams {
            glint_scale: 0.5,
            caustic_width: 15f64.to_radians(),
            fade_range: 0.3,
            caustic_limit: 0.5,
        }
    }
}

/// The parameters of Marschner's caustic treatment by name, before validation
/// ([`CausticParams::new`]); angles in radians.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CausticSettings {
    /// k_G >= 0 (Table 1 suggests 0.5 to 5).
    pub glint_scale: f64,
    /// w_c in (0, pi] radians: the standard deviation of the Gaussian that replaces the
    /// caustic (Table 1: 10 to 25 degrees).
    pub caustic_width: f64,
    /// Delta eta* > 0: the range of eta' above 2 over which the merged caustic fades out
    /// (Table 1: 0.2 to 0.4).
    pub fade_range: f64,
    /// Delta h_M in (0, 2]: the largest width in h the glint may take (Table 1: 0.5).
    pub caustic_limit: f64,
}

impl CausticParams {
    /// Validated parameters (domains in [`CausticSettings`]).
    ///
    /// # Errors
    /// [`ParamError::OutOfRange`] naming the first parameter outside its domain (NaN and
    /// infinities included).
    pub fn new(settings: &CausticSettings) -> Result<Self, ParamError> {
        let s = settings;
        Ok(CausticParams {
            glint_scale: ParamError::check("glint_scale", s.glint_scale, "must be >= 0", |v| {
                v >= 0.0
            })?,
            caustic_width: ParamError::check(
                "caustic_width",
                s.caustic_width,
                "must be in (0, pi] radians",
                |v| v > 0.0 && v <= PI,
            )?,
            fade_range: ParamError::check("fade_range", s.fade_range, "must be > 0", |v| v > 0.0)?,
            caustic_limit: ParamError::check(
                "caustic_limit",
                s.caustic_limit,
                "must be in (0, 2]",
                |v| v > 0.0 && v <= 2.0,
            )?,
        })
    }

    /// k_G.
    pub fn glint_scale(&self) -> f64 {
        self.glint_scale
    }
    /// w_c in radians.
    pub fn caustic_width(&self) -> f64 {
        self.caustic_width
    }
    /// Delta eta*.
    pub fn fade_range(&self) -> f64 {
        self.fade_range
    }
    /// Delta h_M.
    pub fn caustic_limit(&self) -> f64 {
        self.caustic_limit
    }
}

/// The TRT caustic quantities of Marschner's procedure for one eta'.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TrtCaustic {
    /// Offset of the caustic, h_c (0 when eta' >= 2).
    pub h_c: f64,
    /// Azimuth of the caustic, phi_c >= 0 (the caustics are at +-phi_c).
    pub phi_c: f64,
    /// Width in h of the glint, Delta h.
    pub delta_h: f64,
    /// Blend weight t in [0, 1] of the caustic treatment.
    pub t: f64,
}

/// `x` wrapped into [-pi, pi].
fn wrap_pi(x: f64) -> f64 {
    x - TAU * (x / TAU).round()
}

fn smoothstep(e0: f64, e1: f64, x: f64) -> f64 {
    let u = ((x - e0) / (e1 - e0)).clamp(0.0, 1.0);
    u * u * (3.0 - 2.0 * u)
}

/// Marschner's TRT caustic quantities (section 4.3), derived with the exact Phi:
///
/// - eta' < 2: `dPhi/dh = 4 / sqrt(eta'^2 - h^2) - 2 / sqrt(1 - h^2) = 0` gives
///   `4 (1 - h^2) = eta'^2 - h^2`, i.e. `h_c = sqrt((4 - eta'^2) / 3)`; `phi_c = |Phi(2, h_c)|`
///   wrapped to [0, pi]. With `1 - h_c^2 = (eta'^2 - 1)/3` and `eta'^2 - h_c^2 = 4 (eta'^2 - 1)/3`,
///   `d^2Phi/dh^2 (h_c) = 4 h_c / (eta'^2 - h_c^2)^(3/2) - 2 h_c / (1 - h_c^2)^(3/2)
///   = -(3/2) h_c (3 / (eta'^2 - 1))^(3/2)`. Near the caustic `Phi ~ phi_c + Phi'' (h - h_c)^2 / 2`,
///   so the offsets whose exit angle lies within w_c of phi_c span
///   `2 sqrt(2 w_c / |Phi''|)`: `Delta h = min(Delta h_M, 2 sqrt(2 w_c / |Phi''(h_c)|))`; t = 1.
/// - eta' >= 2: the two caustics have merged at phi = 0 (h_c -> 0 as eta' -> 2) and Phi(2, h)
///   is monotone; `phi_c = 0`, `Delta h = Delta h_M`, `t = 1 - smoothstep(2, 2 + Delta eta*, eta')`,
///   and h_c = 0 (where |dPhi/dh| is smallest; our choice for evaluating A(2, h_c)).
///
/// Every quantity is continuous at eta' = 2 (h_c -> 0, phi_c -> 0, |Phi''| -> 0 so
/// Delta h -> Delta h_M, t = 1). eta' below 1 is treated as 1.
pub fn trt_caustic(eta_prime: f64, params: &CausticParams) -> TrtCaustic {
    let e = eta_prime.max(1.0);
    if e < 2.0 {
        let h_c = ((4.0 - e * e) / 3.0).sqrt().min(1.0);
        let phi = 4.0 * (h_c / e).asin() - 2.0 * h_c.asin() + 2.0 * PI;
        let curvature = 1.5 * h_c * (3.0 / (e * e - 1.0)).powf(1.5);
        let delta_h = params
            .caustic_limit
            .min(2.0 * (2.0 * params.caustic_width / curvature).sqrt());
        TrtCaustic {
            h_c,
            phi_c: wrap_pi(phi).abs(),
            delta_h,
            t: 1.0,
        }
    } else {
        TrtCaustic {
            h_c: 0.0,
            phi_c: 0.0,
            delta_h: params.caustic_limit,
            t: 1.0 - smoothstep(2.0, 2.0 + params.fade_range, e),
        }
    }
}

/// Marschner's azimuthal scattering function N_p(phi) per RGB channel for path p (0 = R,
/// 1 = TT, 2 = TRT; 3 accepted), relative azimuth `phi` (radians, any real; 2 pi periodic),
/// inclination theta_d given by its sine, relative index `eta > 1` and absorption `sigma_a`
/// per unit radius:
///
/// `N_p(phi) = sum_r A(p, h_r) / |2 dPhi/dh (h_r)|` (Marschner eq. 8) over the roots of the
/// cubic exit angle ([`marschner_roots`], eta' = eta'(theta_d)), A from
/// [`marschner_attenuation`], `|dPhi/dh|` floored at [`MIN_DPHI_DH`]. Units: per radian of
/// phi; without the `1 / cos^2 theta_d` and longitudinal factors of Marschner's eq. 1, and
/// without any cos(theta_i) projection factor.
///
/// With `caustic = Some(params)` and p = 2, Marschner's caustic treatment (section 4.3) is
/// applied with the quantities of [`trt_caustic`] and the unit-area Gaussian
/// `g(w, x) = exp(-x^2 / (2 w^2)) / (w sqrt(2 pi))`:
///
/// `N_TRT (1 - t g(w_c, phi - phi_c) / g(w_c, 0)) (1 - t g(w_c, phi + phi_c) / g(w_c, 0))
///  + t k_G A(2, h_c) Delta h (g(w_c, phi - phi_c) + g(w_c, phi + phi_c))`,
///
/// with `phi -+ phi_c` wrapped to [-pi, pi]. The first factor removes the singular peaks
/// (notice the caustic angle is the exact one while N_TRT's singularities sit at the cubic's
/// caustic, 0.105 rad away at eta' = 1.2, 0.033 rad at 1.55), the second adds a smooth
/// glint. The treatment does not conserve energy. For p != 2, `caustic` is ignored.
///
/// Uncertain details of the published procedure (see also [`trt_caustic`]): the fade weight
/// for eta' >= 2 is used as `1 - smoothstep(2, 2 + Delta eta*, eta')`, which is continuous at
/// eta' = 2 (a printed `smoothstep(2, 2 + Delta eta*, eta')` would switch the glint off at
/// eta' = 2 and on again above it); h_c = 0 for eta' >= 2; the wrapping of `phi -+ phi_c`;
/// and A(2, h_c) is evaluated with the same absorption and Fresnel factors as N_TRT.
///
pub fn marschner_np(
    path: MarschnerPath,
    phi: f64,
    sin_theta_d: f64,
    eta: f64,
    sigma_a: [f64; 3],
    caustic: Option<&CausticParams>,
) -> [f64; 3] {
    let medium = Medium::new(eta, sin_theta_d);
    let eta_prime = medium.eta_perp;
    let mut n = [0.0; 3];
    let p = path.p();
    for &g in marschner_roots(path, phi, eta_prime).iter() {
        let cos_g = g.cos().max(0.0);
        let slope = marschner_exit_angle_derivative(p, g, eta_prime).abs();
        // 1 / |2 dPhi/dh| = cos g / (2 |dPhi~/dg|), with |dPhi/dh| >= MIN_DPHI_DH; at g = +-pi/2
        // (cos g = 0, dPhi~/dg = -2) the weight is 0.
        let weight = cos_g / (2.0 * slope.max(MIN_DPHI_DH * cos_g));
        if weight == 0.0 {
            continue;
        }
        let a = medium.attenuation(p, g.sin(), sigma_a);
        for (ni, ai) in n.iter_mut().zip(a) {
            *ni += ai * weight;
        }
    }
    match caustic {
        Some(params) if p == 2 => {
            let c = trt_caustic(eta_prime, params);
            let w = params.caustic_width;
            let ratio = |x: f64| (-0.5 * (x / w).powi(2)).exp();
            let (r1, r2) = (ratio(wrap_pi(phi - c.phi_c)), ratio(wrap_pi(phi + c.phi_c)));
            let g0 = 1.0 / (w * TAU.sqrt());
            let suppress = (1.0 - c.t * r1) * (1.0 - c.t * r2);
            let a_c = medium.attenuation(2, c.h_c, sigma_a);
            let glint = c.t * params.glint_scale * c.delta_h * g0 * (r1 + r2);
            core::array::from_fn(|i| n[i] * suppress + glint * a_c[i])
        }
        _ => n,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fresnel::fresnel_dielectric;

    #[test]
    fn cubic_solver_matches_expanded_polynomials() {
        // (g - r1)(g - r2)(g - r3) with r1 + r2 + r3 = 0 has no quadratic term. A double root
        // comes back as two roots within ~sqrt(epsilon) of each other.
        for &(r1, r2) in &[
            (0.3, -0.9),
            (1.2, 0.1),
            (-0.5, -0.5),
            (0.7, 0.7),
            (1e-4, 2e-4),
        ] {
            let r3 = -(r1 + r2);
            let a = -0.37;
            let b = a * (r1 * r2 + r2 * r3 + r3 * r1);
            let d = -a * r1 * r2 * r3;
            let mut out = [0.0; 3];
            let n = depressed_cubic_roots(a, b, d, &mut out);
            let got: Vec<f64> = out[..n].iter().map(|&g| polish(a, b, d, g)).collect();
            assert_eq!(n, 3);
            for w in [r1, r2, r3] {
                let tol = if r1 == r2 { 2e-8 } else { 1e-12 };
                assert!(got.iter().any(|g| (g - w).abs() < tol), "{got:?} lacks {w}");
            }
        }
        // One real root, both signs of P, and the linear limit.
        for &(a, b, d) in &[
            (-0.3, -0.5, 3.0),
            (-0.3, 0.5, -1.0),
            (0.0, -2.0, 1.0),
            (-1e-20, -2.0, 1.0),
        ] {
            let mut out = [0.0; 3];
            let n = depressed_cubic_roots(a, b, d, &mut out);
            let g = polish(a, b, d, out[0]);
            assert!(
                n >= 1 && ((a * g * g + b) * g + d).abs() < 1e-14,
                "{a} {b} {d}: {g}"
            );
        }
    }

    #[test]
    fn cubic_is_exact_at_centre_and_edges() {
        for &e in &[1.2, 1.55, 2.0, 3.0] {
            for p in 0..=3 {
                for &h in &[-1.0, 0.0, 1.0] {
                    let exact = crate::azimuthal::exit_angle_of_offset(f64::from(p), h, e, 0.0);
                    let cubic = marschner_exit_angle(p, f64::asin(h), e);
                    assert!((exact - cubic).abs() < 1e-13, "p {p} eta' {e} h {h}");
                }
                let end = marschner_exit_angle_derivative(p, FRAC_PI_2, e);
                assert!((end + 2.0).abs() < 1e-14);
            }
        }
    }

    #[test]
    fn two_index_fresnel_reduces_to_unpolarised() {
        for &eta in &[1.33, 1.55, 2.4] {
            for &h in &[0.0, 0.3, 0.8, 0.999, 1.0] {
                let cos = (1.0f64 - h * h).sqrt();
                let outside = marschner_fresnel(eta, eta, h);
                assert!((outside - fresnel_dielectric(cos, eta)).abs() < 1e-14);
                if h == 1.0 {
                    // Exactly grazing exit: TIR or not is decided by rounding; both give ~1.
                    continue;
                }
                let st = h / eta;
                let inside = marschner_fresnel(1.0 / eta, 1.0 / eta, st);
                let ref_in = fresnel_dielectric(-(1.0 - st * st).sqrt(), eta);
                assert!(
                    (inside - ref_in).abs() < 1e-12,
                    "{eta} {h}: {inside} {ref_in}"
                );
            }
        }
    }

    #[test]
    fn transmittance_is_marschners_exponent() {
        let (sigma, eta, sin_td) = (0.7, 1.55, 0.4);
        let m = Medium::new(eta, sin_td);
        for &h in &[0.0, 0.5, 0.9] {
            let gt = f64::asin(h / m.eta_perp);
            let sigma_prime = sigma / m.cos_theta_t;
            let paper = (-2.0 * sigma_prime * (1.0 + (2.0 * gt).cos())).exp();
            let ours =
                segment_transmittance(sigma, gt.cos(), m.cos_theta_t, PathLength::Marschner2003);
            assert!((paper - ours).abs() < 1e-15);
            // A(1, h) with sigma = 0 and sigma > 0 differ by exactly that factor.
            let a0 = m.attenuation(1, h, [0.0; 3])[0];
            let a1 = m.attenuation(1, h, [sigma; 3])[0];
            assert!((a1 - a0 * paper).abs() < 1e-15);
        }
    }

    #[test]
    fn caustic_offset_is_stationary_and_curvature_closed_form() {
        for &e in &[1.2, 1.55, 1.9] {
            let c = trt_caustic(e, &CausticParams::default());
            let phi = |h: f64| crate::azimuthal::exit_angle_of_offset(2.0, h, e, 0.0);
            let dh = 1e-5;
            let d1 = (phi(c.h_c + dh) - phi(c.h_c - dh)) / (2.0 * dh);
            // Central difference: truncation error Phi''' dh^2 / 6 ~ 1e-8 at eta' = 1.2.
            assert!(d1.abs() < 1e-7, "eta' {e}: dPhi/dh = {d1}");
            let d2 = (phi(c.h_c + dh) - 2.0 * phi(c.h_c) + phi(c.h_c - dh)) / (dh * dh);
            let closed = -1.5 * c.h_c * (3.0 / (e * e - 1.0)).powf(1.5);
            assert!(
                (d2 - closed).abs() < 1e-4 * closed.abs(),
                "{d2} vs {closed}"
            );
            assert!((c.phi_c - wrap_pi(phi(c.h_c)).abs()).abs() < 1e-15);
        }
    }
}
