//! Bakers for the lookup tables of the real-time hair models, and the measured error of lookup
//! against direct evaluation. Reference-only `f64` code.

use core::f64::consts::{FRAC_PI_2, PI};

use super::table::{Axis, ParamValue, Table, TableMeta};
use super::{LutError, ShapeError};
use crate::absorption::Absorption;
use crate::azimuthal::{CausticParams, LOBES_WITH_RESIDUAL};
use crate::bcsdf::{ChiangHair, Marschner2003};
use crate::error::ParamError;
use crate::params::{
    AzimuthalRoughness, CuticleTilt, HairParams, LongitudinalRoughness, MarschnerLobes,
    RefractiveIndex,
};

/// A table recipe: the axes for given sizes, the channels, the parameters, and the direct
/// evaluation that [`bake`] samples on the grid and [`lookup_error`] compares against.
pub trait Baker {
    /// The kind written to the JSON description (for example `gerard`).
    fn kind(&self) -> &'static str;
    /// What the channels hold, in words (written to the JSON description).
    fn description(&self) -> String;
    /// Number of axes.
    fn dims(&self) -> usize;
    /// Default sizes, one per axis.
    fn default_sizes(&self) -> Vec<usize>;
    /// The axes for `sizes` (one per axis).
    ///
    /// # Errors
    /// [`LutError::Shape`] for the wrong number of sizes, [`LutError::Axis`] for a bad size.
    fn axes(&self, sizes: &[usize]) -> Result<Vec<Axis>, LutError>;
    /// Channel names.
    fn channels(&self) -> Vec<String>;
    /// The parameters, as written to the JSON description.
    fn parameters(&self) -> Vec<(String, ParamValue)>;
    /// Per channel, a fixed 8-bit scale, or `None` for the channel's maximum.
    fn png_scale(&self) -> Vec<Option<f32>> {
        vec![None; self.channels().len()]
    }
    /// The exact values of every channel at `coords` (one per axis, clamped to the axis ranges
    /// of [`Baker::axes`]), written to `out`.
    fn eval(&self, coords: &[f64], out: &mut [f64]);
    /// The most evaluations ([`Baker::eval`]) one [`bake`] (its samples) or one
    /// [`lookup_error`] (its points) may ask for: [`MAX_EVALUATIONS`] (2^24) by default, less
    /// for a costly baker, so that no call runs for more than about a minute.
    fn max_evaluations(&self) -> usize {
        MAX_EVALUATIONS
    }
    /// The measured cost of one evaluation, in words, for the error of
    /// [`Baker::max_evaluations`].
    fn evaluation_cost(&self) -> &'static str {
        "0.1 to 3 us"
    }
}

/// The default of [`Baker::max_evaluations`]: 2^24 (16.8 million, a 4096 x 4096 table). The
/// closed-form bakers cost 0.1 to 0.7 us per sample and about 3 us per error point (measured
/// in a release build on one core): at most 12 s for a bake and 50 s for the error points.
pub const MAX_EVALUATIONS: usize = 1 << 24;

/// [`LutError::TooMuchWork`] if `asked` evaluations of `baker` (`what`: "samples" or
/// "error points") exceed [`Baker::max_evaluations`]; a front end calls it before starting
/// work it would otherwise find refused only after a bake.
///
/// # Errors
/// As described.
pub fn check_evaluations(
    baker: &dyn Baker,
    asked: usize,
    what: &'static str,
) -> Result<(), LutError> {
    let max = baker.max_evaluations();
    if asked > max {
        return Err(LutError::TooMuchWork {
            kind: baker.kind(),
            what,
            asked,
            max,
            cost: baker.evaluation_cost(),
        });
    }
    Ok(())
}

fn check_sizes(kind: &'static str, sizes: &[usize], dims: usize) -> Result<(), LutError> {
    if sizes.len() != dims {
        return Err(LutError::Shape(ShapeError::Sizes {
            kind,
            axes: dims,
            sizes: sizes.len(),
        }));
    }
    Ok(())
}

fn caustic_parameters(out: &mut Vec<(String, ParamValue)>, caustic: &Option<CausticParams>) {
    out.push(("caustic".into(), ParamValue::Flag(caustic.is_some())));
    if let Some(c) = caustic {
        out.push(("glint_scale".into(), ParamValue::Number(c.glint_scale())));
        out.push((
            "caustic_width".into(),
            ParamValue::Number(c.caustic_width()),
        ));
        out.push(("fade_range".into(), ParamValue::Number(c.fade_range())));
        out.push((
            "caustic_limit".into(),
            ParamValue::Number(c.caustic_limit()),
        ));
    }
}

fn clamp_to(axis_min: f64, axis_max: f64, x: f64) -> f64 {
    if x.is_nan() {
        axis_min
    } else {
        x.clamp(axis_min, axis_max)
    }
}

/// Nguyen and Donnelly's M texture (GPU Gems 2, ch. 23, "Hair Animation and Rendering in the
/// Nalu Demo", 2005): Marschner et al. 2003's longitudinal lobes over
/// `(sin theta_i, sin theta_o)` in [-1, 1]^2 (axis 0 = sin theta_i, axis 1 = sin theta_o).
///
/// Channels, with theta = asin(sin theta), `theta_h = (theta_i + theta_o)/2`,
/// `theta_d = (theta_o - theta_i)/2`:
/// - `M_R`, `M_TT`, `M_TRT`: [`crate::lobe::gaussian_lobe`]`(beta_p, theta_h - alpha_p)` (unit area in
///   theta_h, units 1/radian), with Marschner's shifts and widths derived from (alpha_R,
///   beta_R): `alpha_TT = -alpha_R / 2`, `alpha_TRT = -3 alpha_R / 2`, `beta_TT = beta_R / 2`,
///   `beta_TRT = 2 beta_R` (Marschner 2003, Table 1);
/// - `cos_theta_d`: `cos theta_d` in [0, 1] (8-bit scale fixed at 1), so that a shader forms
///   `S = sum_p M_p N_p / cos^2 theta_d` with N from [`NguyenN`]. No cos theta_i factor.
///
/// The 8-bit scale of the M channels is each channel's maximum. (The slides in the seeds print
/// the M lookup as `lookup1(cosThetaI, cosThetaO)` right after computing sines; the texture is
/// indexed by the sines, as the pseudocode's vertex shader computes.)
#[derive(Clone, Copy, Debug, PartialEq, Default)]
pub struct NguyenM {
    lobes: MarschnerLobes,
}

impl NguyenM {
    /// The M texture of Marschner's lobes `lobes` (Marschner's table: beta_R 5 to 10
    /// degrees, alpha_R -10 to -5 degrees; the default is alpha_R = -5, beta_R = 7.5 degrees).
    pub fn new(lobes: MarschnerLobes) -> Self {
        NguyenM { lobes }
    }

    /// (alpha_p, beta_p) for p = R, TT, TRT ([`MarschnerLobes::lobes`]).
    pub fn lobes(&self) -> [(f64, f64); 3] {
        self.lobes.lobes()
    }
}

impl Baker for NguyenM {
    fn kind(&self) -> &'static str {
        "nguyen-m"
    }
    fn description(&self) -> String {
        "Nguyen-Donnelly M texture: Marschner 2003 Gaussian lobes M_p = g(beta_p, theta_h - alpha_p) \
         (unit area in theta_h, 1/radian) at theta_i = asin(axis 0), theta_o = asin(axis 1), \
         theta_h = (theta_i + theta_o)/2; channel 3 is cos theta_d, theta_d = (theta_o - theta_i)/2. \
         Shade with S = sum_p M_p N_p / cos^2 theta_d; no cos theta_i factor."
            .to_string()
    }
    fn dims(&self) -> usize {
        2
    }
    fn default_sizes(&self) -> Vec<usize> {
        vec![64, 64]
    }
    fn axes(&self, sizes: &[usize]) -> Result<Vec<Axis>, LutError> {
        check_sizes(self.kind(), sizes, 2)?;
        Ok(vec![
            Axis::new("sin_theta_i", -1.0, 1.0, sizes[0])?,
            Axis::new("sin_theta_o", -1.0, 1.0, sizes[1])?,
        ])
    }
    fn channels(&self) -> Vec<String> {
        ["M_R", "M_TT", "M_TRT", "cos_theta_d"]
            .map(String::from)
            .to_vec()
    }
    fn parameters(&self) -> Vec<(String, ParamValue)> {
        let [r, tt, trt] = self.lobes();
        vec![
            ("beta_r".into(), ParamValue::Number(self.lobes.beta_r.get())),
            (
                "alpha_r".into(),
                ParamValue::Number(self.lobes.alpha_r.get()),
            ),
            (
                "alpha_p".into(),
                ParamValue::Numbers(vec![r.0, tt.0, trt.0]),
            ),
            ("beta_p".into(), ParamValue::Numbers(vec![r.1, tt.1, trt.1])),
        ]
    }
    fn png_scale(&self) -> Vec<Option<f32>> {
        vec![None, None, None, Some(1.0)]
    }
    fn eval(&self, coords: &[f64], out: &mut [f64]) {
        let theta_i = clamp_to(-1.0, 1.0, coords[0]).asin();
        let theta_o = clamp_to(-1.0, 1.0, coords[1]).asin();
        let theta_h = 0.5 * (theta_i + theta_o);
        let theta_d = 0.5 * (theta_o - theta_i);
        out[..3].copy_from_slice(&self.lobes.longitudinal(theta_h));
        out[3] = theta_d.cos();
    }
}

/// Nguyen and Donnelly's N textures (GPU Gems 2, ch. 23): Marschner et al. 2003's azimuthal
/// functions over `(cos phi, cos theta_d)` (axis 0 = cos phi in [-1, 1], axis 1 =
/// cos theta_d in [0, 1]), with `phi = acos(cos phi)` (N_p is even in phi, tested) and
/// `sin theta_d = sqrt(1 - cos^2 theta_d)` (N_p depends on theta_d through sin^2 theta_d).
///
/// Channels: `N_TT_r, N_TT_g, N_TT_b, N_R` (the first texture: TT in RGB, R in alpha) and
/// `N_TRT_r, N_TRT_g, N_TRT_b` (the second texture), each
/// [`crate::azimuthal::marschner_np`]`(p, phi, sin theta_d, eta, sigma_a, caustic)`: per radian of phi, with
/// Marschner's path-length exponent `2 sigma_a (1 + cos 2 gamma_t) / cos theta_t`
/// (`PathLength::Marschner2003`, sigma_a per unit radius), **without** the `1 / cos^2 theta_d`
/// factor (take cos theta_d from the M texture) and without any cos theta_i factor. The caustic
/// treatment applies to TRT when enabled. 8-bit scales are each channel's maximum.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct NguyenN {
    model: Marschner2003,
}

impl NguyenN {
    /// The N textures of Marschner's model ([`Marschner2003::azimuthal`]) for index `eta`,
    /// absorption `sigma_a` and the TRT caustic treatment `caustic` (or `None`).
    pub fn new(eta: RefractiveIndex, sigma_a: Absorption, caustic: Option<CausticParams>) -> Self {
        NguyenN {
            model: Marschner2003 {
                lobes: MarschnerLobes::default(),
                eta,
                sigma_a,
                caustic,
            },
        }
    }
}

impl Baker for NguyenN {
    fn kind(&self) -> &'static str {
        "nguyen-n"
    }
    fn description(&self) -> String {
        "Nguyen-Donnelly N textures: Marschner 2003 N_p(phi) (cubic exit angle, caustic treatment \
         on TRT if enabled, Marschner2003 path length) per radian at phi = acos(axis 0), \
         sin theta_d = sqrt(1 - axis1^2); channels 0-3 are the first texture (N_TT rgb, N_R), \
         4-6 the second (N_TRT rgb). No 1/cos^2 theta_d and no cos theta_i factor."
            .to_string()
    }
    fn dims(&self) -> usize {
        2
    }
    fn default_sizes(&self) -> Vec<usize> {
        vec![64, 64]
    }
    fn axes(&self, sizes: &[usize]) -> Result<Vec<Axis>, LutError> {
        check_sizes(self.kind(), sizes, 2)?;
        Ok(vec![
            Axis::new("cos_phi", -1.0, 1.0, sizes[0])?,
            Axis::new("cos_theta_d", 0.0, 1.0, sizes[1])?,
        ])
    }
    fn channels(&self) -> Vec<String> {
        [
            "N_TT_r", "N_TT_g", "N_TT_b", "N_R", "N_TRT_r", "N_TRT_g", "N_TRT_b",
        ]
        .map(String::from)
        .to_vec()
    }
    fn parameters(&self) -> Vec<(String, ParamValue)> {
        let mut p = vec![
            ("eta".into(), ParamValue::Number(self.model.eta.get())),
            (
                "sigma_a".into(),
                ParamValue::Numbers(self.model.sigma_a.rgb().to_vec()),
            ),
            (
                "path_length".into(),
                ParamValue::Text("Marschner2003".into()),
            ),
        ];
        caustic_parameters(&mut p, &self.model.caustic);
        p
    }
    fn eval(&self, coords: &[f64], out: &mut [f64]) {
        let phi = clamp_to(-1.0, 1.0, coords[0]).acos();
        let c = clamp_to(0.0, 1.0, coords[1]);
        let sin_d = (1.0 - c * c).max(0.0).sqrt();
        let [r, tt, trt] = self.model.azimuthal(phi, sin_d);
        out[..3].copy_from_slice(&tt);
        out[3] = r[0];
        out[4..7].copy_from_slice(&trt);
    }
}

/// Gerard's `N_p,LUT(theta_d, phi)` ("Fast Real-Time Shading for Polygonal Hair", eq. 7-8):
/// Marschner et al. 2003's N_p with **zero absorption**, one channel per lobe (`N_R`, `N_TT`,
/// `N_TRT`), over axis 0 = phi in [0, pi] (N_p is even in phi, tested; look up |phi|) and
/// axis 1 = theta_d in [0, theta_d max] (N_p depends on sin^2 theta_d; look up |theta_d|).
/// Each value is [`crate::azimuthal::marschner_np`]`(p, phi, sin theta_d, eta, 0, caustic)`: per radian of phi,
/// without `1 / cos^2 theta_d` and without the absorption factor `T(sigma_a, h_max)^p` of
/// Gerard's eq. 7, which the shader multiplies in. 8-bit scales are each channel's maximum.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct GerardN {
    model: Marschner2003,
    theta_d_max: f64,
}

impl GerardN {
    /// The table of Marschner's N_p ([`Marschner2003::azimuthal`]) without absorption, for
    /// index `eta`, `theta_d_max` in (0, pi/2] radians and the TRT caustic treatment `caustic`
    /// (or `None`).
    ///
    /// # Errors
    /// [`ParamError::OutOfRange`] naming `theta_d_max`.
    pub fn new(
        eta: RefractiveIndex,
        theta_d_max: f64,
        caustic: Option<CausticParams>,
    ) -> Result<Self, ParamError> {
        Ok(GerardN {
            model: Marschner2003 {
                lobes: MarschnerLobes::default(),
                eta,
                sigma_a: Absorption::NONE,
                caustic,
            },
            theta_d_max: ParamError::check(
                "theta_d_max",
                theta_d_max,
                "must be in (0, pi/2] radians",
                |v| v > 0.0 && v <= FRAC_PI_2,
            )?,
        })
    }
}

impl Baker for GerardN {
    fn kind(&self) -> &'static str {
        "gerard"
    }
    fn description(&self) -> String {
        "Gerard N_p,LUT: Marschner 2003 N_p(phi) with sigma_a = 0 (cubic exit angle, caustic \
         treatment on TRT if enabled) per radian, at phi = axis 0 (even in phi: use |phi|) and \
         theta_d = axis 1 (use |theta_d|). Multiply by Gerard's absorption factor T^p and divide \
         by cos^2 theta_d in the shader; no cos theta_i factor."
            .to_string()
    }
    fn dims(&self) -> usize {
        2
    }
    fn default_sizes(&self) -> Vec<usize> {
        vec![64, 32]
    }
    fn axes(&self, sizes: &[usize]) -> Result<Vec<Axis>, LutError> {
        check_sizes(self.kind(), sizes, 2)?;
        Ok(vec![
            Axis::new("phi", 0.0, PI, sizes[0])?,
            Axis::new("theta_d", 0.0, self.theta_d_max, sizes[1])?,
        ])
    }
    fn channels(&self) -> Vec<String> {
        ["N_R", "N_TT", "N_TRT"].map(String::from).to_vec()
    }
    fn parameters(&self) -> Vec<(String, ParamValue)> {
        let mut p = vec![
            ("eta".into(), ParamValue::Number(self.model.eta.get())),
            ("sigma_a".into(), ParamValue::Numbers(vec![0.0; 3])),
            ("theta_d_max".into(), ParamValue::Number(self.theta_d_max)),
        ];
        caustic_parameters(&mut p, &self.model.caustic);
        p
    }
    fn eval(&self, coords: &[f64], out: &mut [f64]) {
        let phi = clamp_to(0.0, PI, coords[0]);
        let theta_d = clamp_to(0.0, self.theta_d_max, coords[1]);
        let n = self.model.azimuthal(phi, theta_d.sin());
        for (o, np) in out.iter_mut().zip(n) {
            *o = np[0];
        }
    }
}

/// Channel count of a [`FarFieldN`] table: (R, TT, TRT, TRRT+) x (r, g, b).
pub const FAR_FIELD_CHANNELS: usize = 3 * LOBES_WITH_RESIDUAL;

/// The far-field azimuthal function of Chiang et al. 2016 (pbrt-v4's `HairBxDF` averaged over
/// the offset h) at a chosen absorption, over axis 0 = phi in [0, pi], axis 1 = theta_o in
/// [0, pi/2] and axis 2 = beta_n in [beta_n min, beta_n max].
///
/// Channels `R_r, R_g, R_b, TT_r, ..., TRRT_b`: `A_p N_p = 1/2 int A_p(h) D(phi - Phi(p, h)) dh`
/// per radian of phi, from [`ChiangHair::far_field_azimuthal_reference`] (adaptive, to relative
/// tolerance `rel_tol`), with the exact chord path length. The inclination argument is
/// **theta_o** (pbrt refracts with the inclination of wo; Marschner's theta_d plays this role
/// in his model), and phi is `phi_i - phi_o` (N_p is even in phi, tested: look up |phi| and
/// |theta_o|). TRRT+ is `A_3 / (2 pi)` (no azimuthal structure). beta_m and alpha do not affect
/// N. Cost: about 0.2 ms per grid point (one reference integral), so a 32 x 16 x 8 table takes
/// about 1 s; 8-bit scales are each channel's maximum.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FarFieldN {
    eta: RefractiveIndex,
    sigma_a: Absorption,
    beta_n_min: AzimuthalRoughness,
    beta_n_max: AzimuthalRoughness,
    rel_tol: f64,
}

impl FarFieldN {
    /// The table for index `eta`, absorption `sigma_a`, beta_n from `beta_n_min` to
    /// `beta_n_max` and reference integrals to relative tolerance `rel_tol` in [1e-12, 1e-2].
    ///
    /// # Errors
    /// [`ParamError::OutOfRange`] naming `beta_n_max` when it is not above `beta_n_min`, or
    /// `rel_tol`.
    pub fn new(
        eta: RefractiveIndex,
        sigma_a: Absorption,
        beta_n_min: AzimuthalRoughness,
        beta_n_max: AzimuthalRoughness,
        rel_tol: f64,
    ) -> Result<Self, ParamError> {
        ParamError::check(
            "beta_n_max",
            beta_n_max.get(),
            "must be in (beta_n_min, 1]",
            |v| v > beta_n_min.get(),
        )?;
        Ok(FarFieldN {
            eta,
            sigma_a,
            beta_n_min,
            beta_n_max,
            rel_tol: ParamError::check("rel_tol", rel_tol, "must be in [1e-12, 1e-2]", |v| {
                (1e-12..=1e-2).contains(&v)
            })?,
        })
    }

    /// The reference model the table samples at `beta_n` (clamped to the table's range; beta_m
    /// and alpha do not affect N).
    fn hair(&self, beta_n: f64) -> ChiangHair<f64> {
        let (lo, hi) = (self.beta_n_min, self.beta_n_max);
        let beta_n = if beta_n.is_nan() {
            lo
        } else {
            AzimuthalRoughness::new(beta_n.clamp(lo.get(), hi.get())).unwrap_or(lo)
        };
        ChiangHair::new(&HairParams {
            beta_m: LongitudinalRoughness::new(0.3).unwrap_or_else(|_| unreachable!()),
            beta_n,
            alpha: CuticleTilt::new(0.0).unwrap_or_else(|_| unreachable!()),
            eta: self.eta,
            sigma_a: self.sigma_a,
        })
    }
}

/// [`Baker::max_evaluations`] of [`FarFieldN`]: 2^16 (65,536 samples, three times the
/// 64 x 32 x 10 tables of `hairmath::models::ComposedHair`). One sample costs about 0.16 ms at
/// the defaults (rel_tol 1e-6) and up to 4 ms at beta_n near 1e-16 with rel_tol 1e-12
/// (measured in a release build on one core): 10 s to 4 min at the limit.
pub const FAR_FIELD_MAX_EVALUATIONS: usize = 1 << 16;

impl Baker for FarFieldN {
    fn kind(&self) -> &'static str {
        "far-field"
    }
    fn max_evaluations(&self) -> usize {
        FAR_FIELD_MAX_EVALUATIONS
    }
    fn evaluation_cost(&self) -> &'static str {
        "0.16 to 4 ms"
    }
    fn description(&self) -> String {
        "Chiang 2016 far-field A_p N_p = 1/2 int A_p(h) D(phi - Phi(p, h)) dh per radian (exact \
         chord path length) for p = R, TT, TRT, TRRT+ (rgb each) at phi = axis 0 (use |phi|), \
         theta_o = axis 1 (use |theta_o|), beta_n = axis 2. No M_p and no cos theta_i factor."
            .to_string()
    }
    fn dims(&self) -> usize {
        3
    }
    fn default_sizes(&self) -> Vec<usize> {
        vec![16, 8, 4]
    }
    fn axes(&self, sizes: &[usize]) -> Result<Vec<Axis>, LutError> {
        check_sizes(self.kind(), sizes, 3)?;
        Ok(vec![
            Axis::new("phi", 0.0, PI, sizes[0])?,
            Axis::new("theta_o", 0.0, FRAC_PI_2, sizes[1])?,
            Axis::new(
                "beta_n",
                self.beta_n_min.get(),
                self.beta_n_max.get(),
                sizes[2],
            )?,
        ])
    }
    fn channels(&self) -> Vec<String> {
        let mut c = Vec::with_capacity(FAR_FIELD_CHANNELS);
        for lobe in ["R", "TT", "TRT", "TRRT"] {
            for ch in ["r", "g", "b"] {
                c.push(format!("{lobe}_{ch}"));
            }
        }
        c
    }
    fn parameters(&self) -> Vec<(String, ParamValue)> {
        vec![
            ("eta".into(), ParamValue::Number(self.eta.get())),
            (
                "sigma_a".into(),
                ParamValue::Numbers(self.sigma_a.rgb().to_vec()),
            ),
            (
                "beta_n_min".into(),
                ParamValue::Number(self.beta_n_min.get()),
            ),
            (
                "beta_n_max".into(),
                ParamValue::Number(self.beta_n_max.get()),
            ),
            ("rel_tol".into(), ParamValue::Number(self.rel_tol)),
            ("path_length".into(), ParamValue::Text("chord".into())),
        ]
    }
    fn eval(&self, coords: &[f64], out: &mut [f64]) {
        let phi = clamp_to(0.0, PI, coords[0]);
        let theta_o = clamp_to(0.0, FRAC_PI_2, coords[1]);
        let hair = self.hair(coords[2]);
        let (an, _) =
            hair.far_field_azimuthal_reference(theta_o.sin(), theta_o.cos(), phi, self.rel_tol);
        for (p, lobe) in an.iter().enumerate() {
            out[3 * p..3 * p + 3].copy_from_slice(lobe);
        }
    }
}

/// Bakes `baker` at `sizes` (one per axis): evaluates [`Baker::eval`] at every grid point in
/// f64 and rounds to f32. Deterministic: the same parameters give the same bits. Cost: one
/// evaluation per grid point (see [`Baker::max_evaluations`]).
///
/// # Errors
/// [`LutError::Shape`] or [`LutError::Axis`] for invalid sizes; [`LutError::TooMuchWork`]
/// for more grid points than [`Baker::max_evaluations`], before any evaluation.
pub fn bake(baker: &dyn Baker, sizes: &[usize]) -> Result<Table, LutError> {
    bake_with_progress(baker, sizes, &|_, _| {})
}

/// The most progress reports of a loop over `total` evaluations (and one at its end), so that
/// the callback costs nothing beside the evaluations.
const PROGRESS_REPORTS: usize = 1000;

/// Reports a loop's progress to a callback at most [`PROGRESS_REPORTS`] times, at equal
/// steps, and at its end.
struct Ticker<'a> {
    progress: &'a (dyn Fn(usize, usize) + Sync),
    total: usize,
    every: usize,
    next: usize,
}

impl<'a> Ticker<'a> {
    /// A ticker of a loop over `total` evaluations.
    fn new(progress: &'a (dyn Fn(usize, usize) + Sync), total: usize) -> Self {
        let every = total.div_ceil(PROGRESS_REPORTS).max(1);
        Ticker {
            progress,
            total,
            every,
            next: every,
        }
    }

    /// `done` evaluations are finished (called with 1, 2, ... `total`).
    fn tick(&mut self, done: usize) {
        if done >= self.next || done == self.total {
            (self.progress)(done, self.total);
            self.next = done + self.every;
        }
    }
}

/// [`bake`], calling `progress(done, total)` as grid points are evaluated (`total` the number
/// of grid points; at most about a thousand calls, at equal steps, from the calling thread,
/// `done` increasing, the last call `(total, total)`; none when the sizes are refused). The
/// table is the same as [`bake`]'s.
///
/// # Errors
/// As [`bake`].
pub fn bake_with_progress(
    baker: &dyn Baker,
    sizes: &[usize],
    progress: &(dyn Fn(usize, usize) + Sync),
) -> Result<Table, LutError> {
    let axes = baker.axes(sizes)?;
    let channels = baker.channels();
    let nc = channels.len();
    let total = Table::value_count(&axes, nc)?;
    check_evaluations(baker, total / nc, "samples")?;
    let mut data = Vec::with_capacity(total);
    let n: Vec<usize> = axes.iter().map(Axis::size).collect();
    let points = total / nc;
    let mut coords = vec![0.0; axes.len()];
    let mut values = vec![0.0; nc];
    let mut ticker = Ticker::new(progress, points);
    for flat in 0..points {
        let mut rest = flat;
        for (d, a) in axes.iter().enumerate() {
            coords[d] = a.sample(rest % n[d]);
            rest /= n[d];
        }
        baker.eval(&coords, &mut values);
        data.extend(values.iter().map(|&v| v as f32));
        ticker.tick(flat + 1);
    }
    let table = Table::new(axes, channels, data)?;
    let max = table.channel_max();
    let png_scale = baker
        .png_scale()
        .into_iter()
        .zip(max)
        .map(|(fixed, m)| fixed.unwrap_or(if m > 0.0 && m.is_finite() { m } else { 1.0 }))
        .collect();
    table.with_meta(TableMeta {
        kind: baker.kind().to_string(),
        description: baker.description(),
        parameters: baker.parameters(),
        png_scale,
    })
}

/// The error of [`Table::lookup`] against [`Baker::eval`] at off-grid points.
#[derive(Clone, Debug, PartialEq)]
pub struct ErrorStats {
    /// The table sizes, one per axis.
    pub sizes: Vec<usize>,
    /// Number of test points.
    pub points: usize,
    /// Largest absolute error over points and channels.
    pub max_abs: f64,
    /// Mean absolute error over points and channels.
    pub mean_abs: f64,
    /// Largest error relative to the channel's largest table value, over points and channels
    /// (channels that are zero everywhere are skipped).
    pub max_rel: f64,
    /// Mean of the relative errors.
    pub mean_rel: f64,
    /// The channel where `max_rel` occurs.
    pub worst_channel: usize,
}

/// Measures `table` (baked from `baker`) against direct evaluation at `points` off-grid points
/// spread over the whole domain (a Kronecker sequence). Coordinates are rounded to f32 first,
/// and the direct value is taken at the rounded coordinate, so the figures are interpolation
/// plus f32 storage error only.
///
/// Cost: one evaluation per point (see [`Baker::max_evaluations`]).
///
/// # Errors
/// [`LutError::Shape`] if the table's axes or channels do not match the baker's;
/// [`LutError::TooMuchWork`] for more points than [`Baker::max_evaluations`], before any
/// evaluation.
pub fn lookup_error(
    baker: &dyn Baker,
    table: &Table,
    points: usize,
) -> Result<ErrorStats, LutError> {
    lookup_error_with_progress(baker, table, points, &|_, _| {})
}

/// [`lookup_error`], calling `progress(done, points)` as points are measured (at most about a
/// thousand calls, at equal steps, from the calling thread, `done` increasing, the last call
/// `(points, points)`; none for zero points or a refused request). The figures are the same
/// as [`lookup_error`]'s.
///
/// # Errors
/// As [`lookup_error`].
pub fn lookup_error_with_progress(
    baker: &dyn Baker,
    table: &Table,
    points: usize,
    progress: &(dyn Fn(usize, usize) + Sync),
) -> Result<ErrorStats, LutError> {
    let dims = table.axes().len();
    let nc = table.channels().len();
    if dims != baker.dims() || nc != baker.channels().len() {
        return Err(LutError::Shape(ShapeError::BakerMismatch {
            axes: dims,
            channels: nc,
        }));
    }
    check_evaluations(baker, points, "error points")?;
    let scale = table.channel_max();
    let mut u = [0.0; 3];
    let mut c32 = vec![0.0f32; dims];
    let mut c64 = vec![0.0f64; dims];
    let mut exact = vec![0.0; nc];
    let mut got = vec![0.0f32; nc];
    let mut stats = ErrorStats {
        sizes: table.axes().iter().map(Axis::size).collect(),
        points,
        max_abs: 0.0,
        mean_abs: 0.0,
        max_rel: 0.0,
        mean_rel: 0.0,
        worst_channel: 0,
    };
    let (mut n_abs, mut n_rel) = (0usize, 0usize);
    let mut ticker = Ticker::new(progress, points);
    for k in 0..points {
        crate::quadrature::kronecker(k, dims, &mut u);
        for (d, a) in table.axes().iter().enumerate() {
            c32[d] = (a.min() + u[d] * (a.max() - a.min())) as f32;
            c64[d] = f64::from(c32[d]);
        }
        baker.eval(&c64, &mut exact);
        table.lookup_into(&c32, &mut got)?;
        for c in 0..nc {
            let err = (f64::from(got[c]) - exact[c]).abs();
            stats.max_abs = stats.max_abs.max(err);
            stats.mean_abs += err;
            n_abs += 1;
            if scale[c] > 0.0 {
                let rel = err / f64::from(scale[c]);
                if rel > stats.max_rel {
                    stats.max_rel = rel;
                    stats.worst_channel = c;
                }
                stats.mean_rel += rel;
                n_rel += 1;
            }
        }
        ticker.tick(k + 1);
    }
    stats.mean_abs /= n_abs.max(1) as f64;
    stats.mean_rel /= n_rel.max(1) as f64;
    Ok(stats)
}

/// Bakes `baker` at each entry of `resolutions` and measures it with [`lookup_error`].
///
/// # Errors
/// As [`bake`] and [`lookup_error`].
pub fn error_vs_resolution(
    baker: &dyn Baker,
    resolutions: &[Vec<usize>],
    points: usize,
) -> Result<Vec<ErrorStats>, LutError> {
    resolutions
        .iter()
        .map(|sizes| {
            let table = bake(baker, sizes)?;
            lookup_error(baker, &table, points)
        })
        .collect()
}
