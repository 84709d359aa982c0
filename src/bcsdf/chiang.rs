//! The near-field hair BCSDF of Chiang et al. 2016 ("A Practical and Controllable Hair and Fur
//! Model for Production Path Tracing") as pbrt-v4 defines it (`HairBxDF`).
//!
//! `S(wi, wo, h) = sum_{p=0}^{2} M_p(theta_i; theta_o^(p)) A_p(h) N_p(phi)
//!               + M_3(theta_i; theta_o) A_3+(h) / (2 pi)`
//!
//! - `M_p` is d'Eon's lobe ([`crate::lobe::DeonLobe`]) with variances v_0 from beta_m
//!   (Chiang eq. 7), v_1 = v_0 / 4, v_2 = v_3 = 4 v_0; the cuticle tilt alpha rotates theta_o by
//!   -2 alpha for R, +alpha for TT and +4 alpha for TRT (pbrt-v4).
//! - `A_p` are the attenuations of the path through the fibre
//!   ([`crate::azimuthal::Refraction::path`], [`crate::azimuthal::FibrePath::attenuations`])
//!   with the exact chord transmittance `exp(-sigma_a 2 cos gamma_t / cos theta_t)`.
//! - `N_p(phi) = D(phi - Phi(p, gamma_o, gamma_t))`, D the trimmed logistic
//!   ([`crate::azimuthal::TrimmedLogistic`]) of scale s from beta_n (Chiang eq. 8).
//!
//! **Contract.** `S` carries no cosine factor of any kind: with sigma_a = 0 its integral over all
//! directions wi (solid angle) is 1 for every wo and h. pbrt's `f` equals `S / |cos theta_i|`
//! with theta_i measured to the shading normal; Mitsuba 3's `hair` BSDF returns `S`.
//!
//! **Conventions (pbrt's, converted here).** Directions are in the local frame with the tangent
//! along +X. The offset `h` in [-1, 1] locates the point where `wo`'s ray meets the fibre
//! (gamma_o = asin h), and the relative azimuth of the lobes is phi_i - phi_o, the negative of
//! [`crate::geometry::FibreAngles::phi`].
//!
//! **Varying in shader code** ([`crate::bcsdf::VaryingInputs`]): every input, `beta_m`,
//! `beta_n`, `alpha`, `eta` and the absorption (`sigma_a`, `color` or `eumelanin` and
//! `pheomelanin`, the form it is given in); nothing is baked. The shader then derives all of
//! [`ChiangUniforms`] (variances and d'Eon normalisations, the logistic's scale and mass, the
//! tilt's sines and cosines, a colour's inversion at the varying beta_n).

use super::inputs::{FromInputs, InputValues, HAIR_INPUTS};
use super::model::{Bcsdf, HairSample, Model, Query, RandomNumbers, SampledBcsdf};
use super::varying::{eta_in, roughness_in, tilt_in, InputsIn, VaryingInputs};
use crate::absorption::PathLength;
use crate::azimuthal::{
    azimuths_from_exit_angles, exit_angle, FibrePath, Refraction, TrimmedLogistic,
    LOBES_WITH_RESIDUAL,
};
use crate::error::ParamError;
use crate::geometry::{
    azimuth_between, local_direction, local_fibre_angles, local_sin_cos_theta, V3,
};
use crate::lobe::{deon_lobe_sample_cos_theta, BesselForm, DeonLobe};
use crate::params::HairParams;
use crate::real::{
    array_from_fn, map_array, pi, powi, safe_sqrt, wrap_angle, Real, ShaderFunction, INV_TWO_PI,
};

/// The names of the four lobes, in the order of every per-lobe array of the Chiang models.
pub const CHIANG_LOBES: [&str; LOBES_WITH_RESIDUAL] = ["R", "TT", "TRT", "residual"];

/// Longitudinal variance of the R lobe from beta_m (Chiang et al. 2016, eq. 7):
/// `v = (0.726 b + 0.812 b^2 + 3.7 b^20)^2`, for beta_m in [1e-16, 1].
pub fn longitudinal_variance(beta_m: f64) -> f64 {
    variance_of(beta_m)
}

/// [`longitudinal_variance`] in precision `R` (Chiang et al. 2016, eq. 7).
pub(crate) fn variance_of<R: Real>(beta_m: R) -> R {
    let b = beta_m;
    (R::c(0.726) * b + R::c(0.812) * b * b + R::c(3.7) * powi(b, 20)).sqr()
}

/// Logistic scale from beta_n (Chiang et al. 2016, eq. 8):
/// `s = sqrt(pi/8) (0.265 b + 1.194 b^2 + 5.372 b^22)`, for beta_n in [1e-16, 1].
pub fn logistic_scale(beta_n: f64) -> f64 {
    logistic_scale_of(beta_n)
}

/// [`logistic_scale`] in precision `R` (Chiang et al. 2016, eq. 8).
pub(crate) fn logistic_scale_of<R: Real>(beta_n: R) -> R {
    let b = beta_n;
    R::c((core::f64::consts::PI / 8.0).sqrt())
        * (R::c(0.265) * b + R::c(1.194) * b * b + R::c(5.372) * powi(b, 22))
}

crate::uniform_block! {
    /// The derived constants of the Chiang 2016 model ([`ChiangUniforms::new`]): what CPU
    /// instantiations, SIMD batches and shader code read. Lobe constants are those of d'Eon's
    /// lobe ([`DeonLobe`]); the residual lobe shares TRT's variance (v_3 = v_2 = 4 v_0).
    pub struct ChiangUniforms<R> {
        /// Longitudinal variance of R, v_0 (Chiang eq. 7).
        pub variance_r: R,
        /// Longitudinal variance of TT, v_0 / 4.
        pub variance_tt: R,
        /// Longitudinal variance of TRT and the residual, 4 v_0.
        pub variance_trt: R,
        /// 1 / v_0.
        pub inv_variance_r: R,
        /// 1 / v_1.
        pub inv_variance_tt: R,
        /// 1 / v_2.
        pub inv_variance_trt: R,
        /// d'Eon's normalisation 1 / (v (1 - e^(-2/v))) of R.
        pub lobe_norm_r: R,
        /// The same for TT.
        pub lobe_norm_tt: R,
        /// The same for TRT and the residual.
        pub lobe_norm_trt: R,
        /// Logistic scale s (Chiang eq. 8).
        pub logistic_scale: R,
        /// 1 / s.
        pub logistic_inv_scale: R,
        /// The logistic's mass on [-pi, pi].
        pub logistic_mass: R,
        /// 1 / (s mass).
        pub logistic_norm: R,
        /// sin alpha.
        pub sin_alpha: R,
        /// cos alpha.
        pub cos_alpha: R,
        /// sin 2 alpha.
        pub sin_2_alpha: R,
        /// cos 2 alpha.
        pub cos_2_alpha: R,
        /// sin 4 alpha.
        pub sin_4_alpha: R,
        /// cos 4 alpha.
        pub cos_4_alpha: R,
        /// Relative index of refraction eta.
        pub eta: R,
        /// 1 / eta.
        pub inv_eta: R,
        /// Absorption per unit radius, linear RGB.
        pub sigma_a: [R; 3],
    }
}

impl ChiangUniforms<f64> {
    /// Derives the constants from the physical parameters (pbrt-v4 `HairBxDF` constructor),
    /// in `f64` (the derivation shader code with varying inputs uses too).
    pub fn new(params: &HairParams) -> Self {
        ChiangUniforms::derive(
            params.beta_m.get(),
            params.beta_n.get(),
            params.alpha.get(),
            params.eta.get(),
            params.sigma_a.rgb(),
        )
    }
}

impl<R: Real> ChiangUniforms<R> {
    /// Derives the constants from the physical parameters in precision `R` (pbrt-v4
    /// `HairBxDF` constructor): the variances of Chiang et al. 2016's eq. 7 and their d'Eon
    /// normalisations, the logistic scale of eq. 8 and its mass, the tilt's sines and cosines
    /// by the double-angle formulas. The one derivation of the uniforms: [`ChiangUniforms::new`]
    /// in `f64` and shader code with varying inputs ([`crate::bcsdf::VaryingInputs`]) use it.
    /// Domain as [`HairParams`]: beta_m and beta_n in [1e-16, 1], |alpha| < pi/2, eta in (1, 3],
    /// sigma_a >= 0 per unit radius.
    pub(crate) fn derive(beta_m: R, beta_n: R, alpha: R, eta: R, sigma_a: [R; 3]) -> Self {
        let v0 = variance_of(beta_m);
        let lobes = [v0, R::c(0.25) * v0, R::c(4.0) * v0].map(DeonLobe::<R>::new);
        let logistic = TrimmedLogistic::<R>::new(logistic_scale_of(beta_n));
        // sin and cos of alpha, 2 alpha and 4 alpha by the double-angle formulas.
        let s1 = alpha.sin();
        let c1 = safe_sqrt(R::c(1.0) - s1 * s1);
        let two = R::c(2.0);
        let (s2, c2) = (two * c1 * s1, c1 * c1 - s1 * s1);
        let (s4, c4) = (two * c2 * s2, c2 * c2 - s2 * s2);
        ChiangUniforms {
            variance_r: v0,
            variance_tt: R::c(0.25) * v0,
            variance_trt: R::c(4.0) * v0,
            inv_variance_r: lobes[0].inv_v,
            inv_variance_tt: lobes[1].inv_v,
            inv_variance_trt: lobes[2].inv_v,
            lobe_norm_r: lobes[0].norm,
            lobe_norm_tt: lobes[1].norm,
            lobe_norm_trt: lobes[2].norm,
            logistic_scale: logistic.scale,
            logistic_inv_scale: logistic.inv_scale,
            logistic_mass: logistic.mass,
            logistic_norm: logistic.norm,
            sin_alpha: s1,
            cos_alpha: c1,
            sin_2_alpha: s2,
            cos_2_alpha: c2,
            sin_4_alpha: s4,
            cos_4_alpha: c4,
            eta,
            inv_eta: R::c(1.0) / eta,
            sigma_a,
        }
    }
}

/// The Chiang 2016 model in the working precision `R`, reading its [`ChiangUniforms`], with the
/// azimuthal factors taken across the fibre's width by the rule `O`: at the query's offset h
/// ([`AtOffset`], the near field, the default) or averaged over fixed offsets
/// ([`crate::bcsdf::OffsetNodes`], the far field [`crate::bcsdf::ChiangFarField`]). Evaluation, lobes, pdf
/// and sampling are written once for both.
#[derive(Clone, Debug, PartialEq)]
pub struct ChiangHair<R, O = AtOffset> {
    uniforms: ChiangUniforms<R>,
    offsets: O,
}

/// What the azimuthal factors of a Chiang model depend on: wo's inclination (sine and cosine),
/// the relative azimuth `phi = phi_i - phi_o` of the lobes and the offset h where wo's ray
/// meets the fibre (which the far field replaces by its nodes).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Outgoing<R> {
    /// sin theta_o.
    pub sin_o: R,
    /// cos theta_o >= 0.
    pub cos_o: R,
    /// phi_i - phi_o.
    pub phi: R,
    /// The offset h in [-1, 1].
    pub h: R,
}

/// `(A_p N_p per channel, w_p N_p)` for the lobes R, TT, TRT and the residual: the azimuthal
/// factors of the value and of the pdf (w_p the lobe-choice probabilities).
pub type AzimuthalFactors<R> = ([[R; 3]; LOBES_WITH_RESIDUAL], [R; LOBES_WITH_RESIDUAL]);

/// How a Chiang model takes the azimuthal factors across the fibre's width.
pub trait Offsets<R: Real>: Clone {
    /// Whether S depends on the query's offset h (the near field).
    const NEAR_FIELD: bool;

    /// The factors of every lobe of `hair` for `at`: the azimuthal ones at `at`'s offset or
    /// averaged over offsets, then the longitudinal ones from `longitudinal` (`M_p` of R, TT,
    /// TRT and the residual); the pdf's only `WITH_PDF` (zero otherwise: evaluation skips the
    /// lobe-choice divisions). The azimuthal factors come first because their chain of
    /// dependent operations (the path's square roots and division, the exit angles, the
    /// logistics' exponentials) is the longer: begun first, it overlaps with the independent
    /// longitudinal lobes (in this order the AVX-512 batch took 2.4% less time per sample,
    /// README, speed section).
    fn lobe_terms<O, const WITH_PDF: bool>(
        &self,
        hair: &ChiangHair<R, O>,
        at: Outgoing<R>,
        longitudinal: impl FnOnce() -> [R; LOBES_WITH_RESIDUAL],
    ) -> LobeTerms<R>;

    /// The offset importance sampling draws at: `h` itself, or a node chosen by `u` in [0, 1).
    fn sample_offset(&self, h: R, u: R) -> R;
}

/// An offset rule built in `f64` that can be rebuilt in any precision (what [`Model`] needs).
pub trait OffsetsIn: Offsets<f64> {
    /// The same rule in precision `S`.
    type In<S: Real>: Offsets<S>;
    /// The rule in precision `S` (its constants rounded once, or folded into traced code).
    fn cast<S: Real>(&self) -> Self::In<S>;
}

/// The near field: the azimuthal factors at the query's offset h.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct AtOffset;

impl OffsetsIn for AtOffset {
    type In<S: Real> = AtOffset;
    fn cast<S: Real>(&self) -> AtOffset {
        AtOffset
    }
}

impl<R: Real> Offsets<R> for AtOffset {
    const NEAR_FIELD: bool = true;

    fn sample_offset(&self, h: R, _u: R) -> R {
        h
    }

    #[inline(always)]
    fn lobe_terms<O, const WITH_PDF: bool>(
        &self,
        hair: &ChiangHair<R, O>,
        at: Outgoing<R>,
        longitudinal: impl FnOnce() -> [R; LOBES_WITH_RESIDUAL],
    ) -> LobeTerms<R> {
        hair.lobe_terms_at::<WITH_PDF>(at, longitudinal)
    }
}

/// The factors of every lobe for one direction pair, grouped as the value, the pdf and the
/// per-lobe split read them: `M_p A_p N_p = weight_p channels_p` per channel and
/// `M_p w_p N_p = weight_p choice_p` (w_p the lobe-choice probability of sampling; the sum
/// `S = sum_p M_p A_p N_p` is the lobe sum of Chiang et al. 2016 and pbrt-v4's `HairBxDF::f`,
/// the pdf that of `HairBxDF::PDF`).
///
/// The near field puts the factor its channels share into the weight: `weight_p = M_p N_p`,
/// `channels_p = A_p`, `choice_p = w_p`, so the sum over the lobes takes one multiply-add per
/// lobe and channel (multiplying `A_p N_p` first took one more multiplication per lobe and
/// channel). The far field averages `A_p N_p` over its offsets, which does not factor:
/// `weight_p = M_p`, and `channels_p` and `choice_p` are the averages of `A_p N_p` and
/// `w_p N_p`.
#[derive(Clone, Copy, Debug)]
pub struct LobeTerms<R> {
    /// The factor of lobe p shared by its channels (R, TT, TRT, residual).
    pub weight: [R; LOBES_WITH_RESIDUAL],
    /// The factors of lobe p per channel.
    pub channels: [[R; 3]; LOBES_WITH_RESIDUAL],
    /// The lobe-choice factor of the pdf of lobe p.
    pub choice: [R; LOBES_WITH_RESIDUAL],
}

impl<R: Real> LobeTerms<R> {
    /// `S = sum_p M_p A_p N_p` per channel.
    #[inline(always)]
    pub fn value(&self) -> [R; 3] {
        array_from_fn(
            #[inline(always)]
            |c| weighted_sum(&self.weight, |p| self.channels[p][c]),
        )
    }

    /// `pdf = sum_p M_p w_p N_p`.
    #[inline(always)]
    pub fn pdf(&self) -> R {
        weighted_sum(&self.weight, |p| self.choice[p])
    }

    /// `M_p A_p N_p` per lobe and channel.
    pub fn per_lobe(&self) -> Vec<[R; 3]> {
        (0..LOBES_WITH_RESIDUAL)
            .map(|p| self.channels[p].map(|x| self.weight[p] * x))
            .collect()
    }
}

/// `sum_p weight_p factor(p)` by multiply-adds, from the first lobe's product (adding it to 0
/// would cost an addition: `0 + x` is not `x` for `x = -0`).
#[inline(always)]
fn weighted_sum<R: Real>(weight: &[R; LOBES_WITH_RESIDUAL], factor: impl Fn(usize) -> R) -> R {
    let mut sum = weight[0] * factor(0);
    for (p, w) in weight.iter().enumerate().skip(1) {
        sum = w.mul_add(factor(p), sum);
    }
    sum
}

/// sin and cos of theta_i, and what the azimuthal factors depend on ([`Outgoing`]).
#[derive(Clone, Copy, Debug)]
pub(crate) struct PairAngles<R> {
    pub sin_i: R,
    pub cos_i: R,
    pub out: Outgoing<R>,
}

impl<R: Real> PairAngles<R> {
    /// The angles of a query's directions ([`local_fibre_angles`]; its phi_o - phi_i negated).
    #[inline(always)]
    pub fn of(query: &Query<R>) -> Self {
        let a = local_fibre_angles(query.wi, query.wo);
        PairAngles {
            sin_i: a.sin_theta_i,
            cos_i: a.cos_theta_i,
            out: Outgoing {
                sin_o: a.sin_theta_o,
                cos_o: a.cos_theta_o,
                phi: (-a.phi).label("phi"),
                h: query.h,
            },
        }
    }
}

impl<R: Real> ChiangHair<R> {
    /// The near-field model of `params`: the uniforms derived once in `f64`
    /// ([`ChiangUniforms::new`]) and rounded to `R`.
    ///
    /// # Examples
    ///
    /// ```
    /// use hairmath::bcsdf::{Bcsdf, ChiangHair, Query, SampledBcsdf};
    /// use hairmath::geometry::V3;
    /// use hairmath::params::HairParams;
    ///
    /// let hair = ChiangHair::<f64>::new(&HairParams::default());
    /// // Local frame, tangent +X: wi towards the light, wo towards the viewer, offset h.
    /// let query = Query::checked(V3::new(-0.6, 0.0, 0.8), V3::new(0.6, 0.8, 0.0), 0.25)?;
    /// let s = hair.eval(&query);
    /// assert!(s.iter().all(|v| *v > 0.0));
    /// assert!(hair.pdf(&query) > 0.0);
    /// # Ok::<(), hairmath::ParamError>(())
    /// ```
    pub fn new(params: &HairParams) -> Self {
        ChiangHair::<f64>::from_uniforms(ChiangUniforms::new(params)).instantiate()
    }

    /// The near-field model reading `uniforms` (rounded or symbolic: shader code receives them
    /// this way).
    pub fn from_uniforms(uniforms: ChiangUniforms<R>) -> Self {
        ChiangHair {
            uniforms,
            offsets: AtOffset,
        }
    }
}

impl<R: Real, O> ChiangHair<R, O> {
    /// The model reading `uniforms` with the offset rule `offsets`.
    pub(crate) fn with_offsets(uniforms: ChiangUniforms<R>, offsets: O) -> Self {
        ChiangHair { uniforms, offsets }
    }

    /// The model's offset rule.
    pub fn offsets(&self) -> &O {
        &self.offsets
    }

    /// The model's uniforms.
    pub fn uniforms(&self) -> &ChiangUniforms<R> {
        &self.uniforms
    }

    /// Relative index of refraction.
    pub fn eta(&self) -> R {
        self.uniforms.eta
    }

    /// d'Eon's lobe and its variance for lobe p (the residual shares TRT's).
    #[inline(always)]
    fn lobe(&self, p: usize) -> (DeonLobe<R>, R) {
        let u = &self.uniforms;
        let (inv_v, norm, v) = match p {
            0 => (u.inv_variance_r, u.lobe_norm_r, u.variance_r),
            1 => (u.inv_variance_tt, u.lobe_norm_tt, u.variance_tt),
            _ => (u.inv_variance_trt, u.lobe_norm_trt, u.variance_trt),
        };
        (DeonLobe { inv_v, norm }, v)
    }

    /// The azimuthal distribution.
    #[inline(always)]
    pub(crate) fn logistic(&self) -> TrimmedLogistic<R> {
        let u = &self.uniforms;
        TrimmedLogistic {
            scale: u.logistic_scale,
            inv_scale: u.logistic_inv_scale,
            mass: u.logistic_mass,
            norm: u.logistic_norm,
        }
    }

    /// theta_o rotated by the tilt of lobe p: -2 alpha (R), +alpha (TT), +4 alpha (TRT), none
    /// for the residual. Returns (sin, |cos|).
    #[inline(always)]
    fn tilted(&self, p: usize, sin_o: R, cos_o: R) -> (R, R) {
        let u = &self.uniforms;
        let (s, c) = match p {
            0 => (-u.sin_2_alpha, u.cos_2_alpha),
            1 => (u.sin_alpha, u.cos_alpha),
            2 => (u.sin_4_alpha, u.cos_4_alpha),
            _ => return (sin_o, cos_o),
        };
        (
            sin_o.mul_add(c, cos_o * s),
            cos_o.mul_add(c, -(sin_o * s)).abs(),
        )
    }

    /// The refraction into the fibre of wo's ray, inclined at theta_o (sine and cosine): what
    /// the paths at every offset share.
    #[inline(always)]
    pub(crate) fn refraction(&self, sin_o: R, cos_o: R) -> Refraction<R> {
        let u = &self.uniforms;
        Refraction::new(sin_o, cos_o, u.eta, u.inv_eta)
    }

    /// The path through the fibre for wo's refraction and offset `h` (clamped to [-1, 1]),
    /// and `A_p` per lobe and channel.
    #[inline(always)]
    fn attenuations_at(
        &self,
        refraction: &Refraction<R>,
        h: R,
    ) -> (FibrePath<R>, [[R; 3]; LOBES_WITH_RESIDUAL]) {
        let path = refraction.path(h, PathLength::Chord);
        let per_channel = map_array(
            self.uniforms.sigma_a,
            #[inline(always)]
            |sa| path.attenuations(sa),
        );
        let a = array_from_fn(
            #[inline(always)]
            |p| [per_channel[0][p], per_channel[1][p], per_channel[2][p]],
        );
        (path, a)
    }

    /// M_p for p = 0..3 with the tilt of each lobe.
    #[inline(always)]
    pub(crate) fn longitudinal(&self, angles: &PairAngles<R>) -> [R; LOBES_WITH_RESIDUAL] {
        array_from_fn(
            #[inline(always)]
            |p| self.longitudinal_lobe(p, BesselForm::Full, angles),
        )
    }

    /// M_p of lobe `p` with its tilt, its Bessel function by `form`.
    #[inline(always)]
    pub(crate) fn longitudinal_lobe(
        &self,
        p: usize,
        form: BesselForm,
        angles: &PairAngles<R>,
    ) -> R {
        let (sin_op, cos_op) = self.tilted(p, angles.out.sin_o, angles.out.cos_o);
        self.lobe(p)
            .0
            .eval_with(form, angles.sin_i, angles.cos_i, sin_op, cos_op)
    }

    /// The azimuthal factors at `at`'s offset (clamped to [-1, 1]) and relative azimuth
    /// `phi = phi_i - phi_o`: `(A_p N_p per channel, w_p N_p)`.
    /// `N_p` is the trimmed logistic about the exit angle Phi(p) for p < 3
    /// ([`TrimmedLogistic::densities`]) and `1 / (2 pi)` for the residual; `w_p` are
    /// the lobe-choice probabilities of sampling, computed only `WITH_PDF` (a type-level
    /// constant, so the traced code has no data-dependent branch; evaluation needs no pdf).
    #[inline(always)]
    pub(crate) fn azimuthal_at<const WITH_PDF: bool>(
        &self,
        at: Outgoing<R>,
    ) -> AzimuthalFactors<R> {
        let (path, a) = self.attenuations_at(&self.refraction(at.sin_o, at.cos_o), at.h);
        let n = self.distributions(at.phi, path.gamma_o, path.gamma_t);
        azimuthal_factors::<R, WITH_PDF>(&a, n)
    }

    /// The near field's [`LobeTerms`] at `at`'s offset (clamped to [-1, 1]) and relative
    /// azimuth, the longitudinal factors `M_p` from `longitudinal` after the azimuthal ones
    /// ([`Offsets::lobe_terms`]): `weight_p = M_p N_p`, `channels_p = A_p`, `choice_p = w_p`
    /// (the lobe-choice probabilities, only `WITH_PDF`).
    #[inline(always)]
    fn lobe_terms_at<const WITH_PDF: bool>(
        &self,
        at: Outgoing<R>,
        longitudinal: impl FnOnce() -> [R; LOBES_WITH_RESIDUAL],
    ) -> LobeTerms<R> {
        let (path, a) = self.attenuations_at(&self.refraction(at.sin_o, at.cos_o), at.h);
        let n = self.distributions(at.phi, path.gamma_o, path.gamma_t);
        let m = longitudinal();
        LobeTerms {
            weight: array_from_fn(
                #[inline(always)]
                |p| m[p] * n[p],
            ),
            channels: a,
            choice: match WITH_PDF {
                true => lobe_weights(&a),
                false => [R::c(0.0); LOBES_WITH_RESIDUAL],
            },
        }
    }

    /// The azimuthal factors of the offsets `h` and `-h` together (`at.h` in [0, 1]):
    /// `(A_p (N_p(h) + N_p(-h)) per channel, w_p (N_p(h) + N_p(-h)))`, for the far field's
    /// symmetric nodes. The path's segment length and entry Fresnel term depend on `h^2`
    /// only, so `A_p` is even in h; gamma_o = asin h and gamma_t are odd, so the exit angles
    /// at `-h` are those of the negated angles (Marschner et al. 2003, eq. 3). One path for
    /// two offsets. `refraction` is that of wo's ray ([`ChiangHair::refraction`]), which the
    /// far field computes once for all its nodes.
    #[inline(always)]
    pub(crate) fn azimuthal_mirrored_at<const WITH_PDF: bool>(
        &self,
        refraction: &Refraction<R>,
        at: Outgoing<R>,
    ) -> AzimuthalFactors<R> {
        let (path, a) = self.attenuations_at(refraction, at.h);
        let n = self.distributions(at.phi, path.gamma_o, path.gamma_t);
        let mirrored = self.distributions(at.phi, -path.gamma_o, -path.gamma_t);
        let sum = array_from_fn(
            #[inline(always)]
            |p| n[p] + mirrored[p],
        );
        azimuthal_factors::<R, WITH_PDF>(&a, sum)
    }

    /// `N_p` for p = 0..3 at the relative azimuth `phi` of the path entering at gamma_o and
    /// refracting to gamma_t: the trimmed logistic about the exit angle Phi(p) for R, TT and
    /// TRT ([`TrimmedLogistic::densities`]), `1 / (2 pi)` for the residual.
    #[inline(always)]
    fn distributions(&self, phi: R, gamma_o: R, gamma_t: R) -> [R; LOBES_WITH_RESIDUAL] {
        let dphi = azimuths_from_exit_angles(phi, gamma_o, gamma_t);
        // N_p of R, TT and TRT about their exit angles, as one shader function.
        const DISTRIBUTIONS: ShaderFunction = crate::shader_function!(
            trimmed_logistics,
            "Chiang et al. 2016, eq. 13",
            [dphi_r, dphi_tt, dphi_trt] -> {r, tt, trt}
        );
        let [n0, n1, n2] = R::call(
            &DISTRIBUTIONS,
            dphi,
            #[inline(always)]
            |dphi| self.logistic().densities(dphi),
        );
        [n0, n1, n2, INV_TWO_PI.get()]
    }

    /// The direction [`SampledBcsdf::sample`] draws at offset `h`, without evaluating S and
    /// the pdf there (`u.offset` is not used here).
    pub(crate) fn sample_direction(&self, wo: V3<R>, h: R, u: &RandomNumbers<R>) -> V3<R> {
        let one = R::c(1.0);
        let (sin_o, cos_o) = local_sin_cos_theta(wo);
        let (path, a) = self.attenuations_at(&self.refraction(sin_o, cos_o), h);
        let w = lobe_weights(&a);

        // Choose p: the first lobe whose cumulative weight exceeds uc; remap uc into it.
        let uc = u.lobe.clamp(R::c(0.0), one);
        let mut lower = R::c(0.0);
        let mut chosen = [R::c(0.0); 6]; // p, lower, width, sin_op, cos_op, v_p
        for (p, &weight) in w.iter().enumerate() {
            // The intervals [lower, upper) partition [0, 1]; the last one takes the rest.
            let upper = if p == LOBES_WITH_RESIDUAL - 1 {
                R::c(2.0)
            } else {
                lower + weight
            };
            let here = !uc.lt(lower) & uc.lt(upper);
            let (sin_op, cos_op) = self.tilted(p, sin_o, cos_o);
            let candidate = [
                R::c(p as f64),
                lower,
                weight,
                sin_op,
                cos_op,
                self.lobe(p).1,
            ];
            for (slot, value) in chosen.iter_mut().zip(candidate) {
                *slot = R::select(here, value, *slot);
            }
            lower += weight;
        }
        let [p, lower, width, sin_op, cos_op, v] = chosen;
        let uc = ((uc - lower) / width.max(R::c(1e-30))).clamp(R::c(0.0), R::c(1.0 - 1e-7));

        // Longitudinal: sample the lobe about its axis, then rotate about the cone.
        let cos_theta = deon_lobe_sample_cos_theta(v, u.longitudinal);
        let sin_theta = safe_sqrt(one - cos_theta * cos_theta);
        // cos(2 pi u1), with the argument kept in [-pi, pi] for GPU accuracy.
        let cos_phi = -(R::c(2.0) * pi::<R>() * u.cone - pi::<R>()).cos();
        let sin_i = (-cos_theta * sin_op + sin_theta * cos_phi * cos_op).clamp(-one, one);
        let cos_i = safe_sqrt(one - sin_i * sin_i);

        // Azimuthal: logistic about Phi(p) for p < 3, uniform for the residual.
        let is_residual = R::c(2.5).lt(p);
        let dphi = R::select(
            is_residual,
            R::c(2.0) * pi::<R>() * uc,
            exit_angle(p, path.gamma_o, path.gamma_t) + self.logistic().sample(uc),
        );
        let phi_o = azimuth_between(V3::from_f64(1.0, 0.0, 0.0), V3::from_f64(0.0, 1.0, 0.0), wo);
        local_direction(sin_i, cos_i, wrap_angle(phi_o + wrap_angle(dphi)))
    }
}

/// Probability of choosing each lobe when sampling from wo: the channel-averaged A_p,
/// normalised (pbrt-v4 `ApPDF`).
#[inline(always)]
fn lobe_weights<R: Real>(a: &[[R; 3]; LOBES_WITH_RESIDUAL]) -> [R; LOBES_WITH_RESIDUAL] {
    let avg = map_array(
        *a,
        #[inline(always)]
        |ch| (ch[0] + ch[1] + ch[2]) * R::c(1.0 / 3.0),
    );
    let total = (avg[0] + avg[1] + avg[2] + avg[3]).max(R::c(1e-30));
    map_array(
        avg,
        #[inline(always)]
        |x| x / total,
    )
}

/// `(A_p N_p per channel, w_p N_p)` from the attenuations `a` and the distributions `n`; the
/// lobe-choice probabilities `w_p` ([`lobe_weights`]) only `WITH_PDF`.
#[inline(always)]
fn azimuthal_factors<R: Real, const WITH_PDF: bool>(
    a: &[[R; 3]; LOBES_WITH_RESIDUAL],
    n: [R; LOBES_WITH_RESIDUAL],
) -> AzimuthalFactors<R> {
    let wn = if WITH_PDF {
        let w = lobe_weights(a);
        array_from_fn(
            #[inline(always)]
            |p| w[p] * n[p],
        )
    } else {
        [R::c(0.0); LOBES_WITH_RESIDUAL]
    };
    let an = array_from_fn(
        #[inline(always)]
        |p| {
            map_array(
                a[p],
                #[inline(always)]
                |x| x * n[p],
            )
        },
    );
    (an, wn)
}

impl<R: Real, O: Offsets<R>> ChiangHair<R, O> {
    /// The lobe factors of a query, the azimuthal ones by the offset rule (those of the pdf
    /// only `WITH_PDF`).
    #[inline(always)]
    fn terms<const WITH_PDF: bool>(&self, query: &Query<R>) -> LobeTerms<R> {
        let angles = PairAngles::of(query);
        self.offsets.lobe_terms::<O, WITH_PDF>(
            self,
            angles.out,
            #[inline(always)]
            || self.longitudinal(&angles),
        )
    }
}

impl<R: Real, O: Offsets<R>> Bcsdf<R> for ChiangHair<R, O> {
    fn lobe_names(&self) -> &'static [&'static str] {
        &CHIANG_LOBES
    }

    fn uses_offset(&self) -> bool {
        O::NEAR_FIELD
    }

    /// `S(wi, wo, h)` per channel for unit `wi`, `wo` in the local frame and offset `h` in
    /// [-1, 1] (clamped; ignored by the far field). No cosine factor (see the module
    /// documentation). Finite and non-negative for every finite input. Inlined into the
    /// batch kernels' copies per instruction set ([`crate::real::InstructionSet`]).
    #[inline(always)]
    fn eval(&self, query: &Query<R>) -> [R; 3] {
        self.terms::<false>(query).value()
    }

    /// `M_p A_p N_p` of each lobe (R, TT, TRT, residual) per channel.
    fn eval_lobes(&self, query: &Query<R>) -> Vec<[R; 3]> {
        self.terms::<false>(query).per_lobe()
    }
}

impl<R: Real, O: Offsets<R>> SampledBcsdf<R> for ChiangHair<R, O> {
    /// The density of [`SampledBcsdf::sample`]: `sum_p M_p w_p N_p` with the lobe-choice
    /// probabilities w_p of pbrt-v4's `ApPDF` (averaged over the offsets for the far field).
    #[inline(always)]
    fn pdf(&self, query: &Query<R>) -> R {
        self.terms::<true>(query).pdf()
    }

    /// Importance-samples wi given wo and h (d'Eon 2013; pbrt-v4 `Sample_f`): the far field
    /// first picks an offset node with `u.offset`; then `u.lobe` chooses the lobe (and,
    /// remapped, the azimuth), `u.longitudinal` the angle about the lobe's axis, `u.cone` the
    /// azimuth of the longitudinal cone. Branch-free, so it traces.
    fn sample(&self, wo: V3<R>, h: R, u: RandomNumbers<R>) -> HairSample<R> {
        let wi = self.sample_direction(wo, self.offsets.sample_offset(h, u.offset), &u);
        let terms = self.terms::<true>(&Query::new(wi, wo, h));
        HairSample {
            wi,
            value: terms.value(),
            pdf: terms.pdf(),
        }
    }
}

impl<O: OffsetsIn> Model for ChiangHair<f64, O> {
    type Uniforms<R: Real> = ChiangUniforms<R>;
    type In<R: Real> = ChiangHair<R, O::In<R>>;
    const INLINED_KERNEL: bool = true;

    fn uniforms(&self) -> ChiangUniforms<f64> {
        self.uniforms
    }

    /// The model reading `uniforms`; the offset rule's constants (the far field's nodes) are
    /// rounded to `R` (folded into traced code).
    fn with_uniforms<R: Real>(&self, uniforms: ChiangUniforms<R>) -> ChiangHair<R, O::In<R>> {
        ChiangHair {
            uniforms,
            offsets: self.offsets.cast(),
        }
    }
}

impl FromInputs for ChiangHair<f64> {
    const NAME: &'static str = "chiang";
    const SUMMARY: &'static str =
        "Chiang et al. 2016 (pbrt-v4 HairBxDF): the near-field reference, S(wi, wo, h)";
    const INPUTS: &'static [super::inputs::Input] = &HAIR_INPUTS;

    fn from_inputs(values: &InputValues) -> Result<Self, ParamError> {
        HairParams::from_inputs(values)?;
        Ok(ChiangHair::from_uniforms(Self::uniforms_in(
            &InputsIn::constant(values),
        )))
    }
}

/// The inputs of [`HAIR_INPUTS`] that vary in shader code: all of them, the absorption in
/// each of its forms.
pub(crate) const HAIR_VARYING: [&str; 8] = [
    "beta_m",
    "beta_n",
    "alpha",
    "eta",
    "sigma_a",
    "color",
    "eumelanin",
    "pheomelanin",
];

/// The uniforms of the Chiang models from the values of [`HAIR_INPUTS`] in precision `R`
/// ([`ChiangUniforms::derive`], a colour inverted at the hair's beta_n), with the shader's
/// clamps (`crate::bcsdf::varying`'s module documentation): beta_m and beta_n below 1e-16
/// (or NaN) are [`crate::bcsdf::MIN_ROUGHNESS`], above 1 are 1; alpha is clamped to +-pi/2; eta at or
/// below 1 is [`crate::bcsdf::MIN_ETA`], above 3 is 3; sigma_a and melanin are at least 0 and
/// colours in (0, 1].
pub(crate) fn chiang_uniforms_in<R: Real>(inputs: &InputsIn<R>) -> ChiangUniforms<R> {
    let beta_n = roughness_in(inputs.number("beta_n"));
    ChiangUniforms::derive(
        roughness_in(inputs.number("beta_m")),
        beta_n,
        tilt_in(inputs.number("alpha")),
        eta_in(inputs.number("eta")),
        inputs.absorption("sigma_a").sigma_a(beta_n),
    )
}

impl VaryingInputs for ChiangHair<f64> {
    const NAME: &'static str = <Self as FromInputs>::NAME;
    const INPUTS: &'static [super::inputs::Input] = &HAIR_INPUTS;
    const VARYING: &'static [&'static str] = &HAIR_VARYING;
    const BAKED: &'static [(&'static str, &'static str)] = &[];

    fn uniforms_in<R: Real>(inputs: &InputsIn<R>) -> ChiangUniforms<R> {
        chiang_uniforms_in(inputs)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::bcsdf::batch::tests::unit;
    use crate::bcsdf::{BatchLanes, BatchReal};
    use crate::params::HairValues;
    use rand::{Rng, SeedableRng};
    use rand_pcg::Pcg64Mcg;

    /// A direction uniform on the sphere in every lane ([`unit`]).
    fn uniform_directions(rng: &mut Pcg64Mcg) -> V3<BatchReal> {
        let lanes: Vec<[f32; 3]> = (0..BatchReal::LANES).map(|_| unit(rng)).collect();
        let component = |c: usize| BatchReal::from_fn(|k| lanes[k][c]);
        V3::new(component(0), component(1), component(2))
    }

    /// Whether any lane of `x` is subnormal (non-zero and below the smallest normal `f32`).
    fn any_subnormal(x: BatchReal) -> bool {
        (0..BatchReal::LANES).any(|k| x.lane(k) != 0.0 && x.lane(k).abs() < f32::MIN_POSITIVE)
    }

    /// The lanes' factors in [0, 1] below e^-36 are 0 ([`Real::negligible_to_zero`]), which
    /// keeps every value the near field's lobe sum rounds normal: `M_p`, `N_p`, `A_p` per
    /// channel, `M_p N_p` and the first lobe's product with `A_0` (the sum's one
    /// multiplication; the other lobes enter by fused multiply-adds, whose products are not
    /// rounded). Tested on random direction pairs and offsets for roughnesses from 0.05 to 1,
    /// tilts of 0 and 5 degrees and absorptions from none to black hair's: no lane of them is
    /// subnormal, and S itself (where every lobe is negligible at once) in fewer than 1 in
    /// 5,000 values. With the exponentials instead, 2% of the samples of the speed
    /// benchmark's material (`benches/bcsdf.rs`) had a subnormal `M_1 N_1` or `M_1 N_1 A_1`,
    /// and an x86 core takes a microcode assist for each instruction that gives one.
    #[test]
    fn lobe_factors_on_lanes_are_never_subnormal() {
        let mut rng = Pcg64Mcg::seed_from_u64(24);
        let absorptions = [
            [0.0; 3],
            [0.5, 0.8, 1.4],
            [3.0, 5.0, 9.0],
            [8.0, 12.0, 20.0],
        ];
        let (mut checked, mut subnormal_sums) = (0, 0);
        for beta_m in [0.05, 0.3, 1.0] {
            for beta_n in [0.05, 0.3, 1.0] {
                for (k, sigma_a) in absorptions.into_iter().enumerate() {
                    let alpha = [0.0, 5.0_f64.to_radians()][k % 2];
                    let values = HairValues {
                        beta_m,
                        beta_n,
                        alpha,
                        eta: 1.55,
                        sigma_a,
                    };
                    let params = HairParams::try_from(values).expect("valid parameters");
                    let hair = ChiangHair::<f64>::new(&params).instantiate::<BatchReal>();
                    for _ in 0..400 {
                        let (wi, wo) = (uniform_directions(&mut rng), uniform_directions(&mut rng));
                        let h = BatchReal::from_fn(|_| rng.random_range(-1.0..=1.0));
                        let query = Query::new(wi, wo, h);
                        let angles = PairAngles::of(&query);
                        let at = angles.out;
                        let refraction = hair.refraction(at.sin_o, at.cos_o);
                        let (path, a) = hair.attenuations_at(&refraction, at.h);
                        let n = hair.distributions(at.phi, path.gamma_o, path.gamma_t);
                        let m = hair.longitudinal(&angles);
                        let weights: [BatchReal; LOBES_WITH_RESIDUAL] =
                            core::array::from_fn(|p| m[p] * n[p]);
                        let factors = [m, n, weights]
                            .into_iter()
                            .flatten()
                            .chain(a.into_iter().flatten())
                            .chain(a[0].map(|a| weights[0] * a));
                        for (index, value) in factors.enumerate() {
                            assert!(
                                !any_subnormal(value),
                                "beta_m {beta_m}, beta_n {beta_n}, sigma_a {sigma_a:?}, value \
                                 {index}: {value:?}"
                            );
                        }
                        for s in hair.eval(&query) {
                            subnormal_sums += (0..BatchReal::LANES)
                                .filter(|&k| s.lane(k) != 0.0 && s.lane(k) < f32::MIN_POSITIVE)
                                .count();
                        }
                        checked += BatchReal::LANES;
                    }
                }
            }
        }
        eprintln!("{checked} samples, no subnormal factor, {subnormal_sums} subnormal S");
        assert!(
            subnormal_sums * 5_000 < 3 * checked,
            "{subnormal_sums} of {checked}"
        );
    }
}
