//! The near-field hair BCSDF of Chiang et al. 2016 ("A Practical and Controllable Hair and Fur
//! Model for Production Path Tracing") as pbrt-v4 defines it (`HairBxDF`).
//!
//! `S(wi, wo, h) = sum_{p=0}^{2} M_p(theta_i; theta_o^(p)) A_p(h) N_p(phi)
//!               + M_3(theta_i; theta_o) A_3+(h) / (2 pi)`
//!
//! - `M_p` is d'Eon's lobe ([`crate::lobe::deon_lobe`]) with variances v_0 from beta_m
//!   (Chiang eq. 7), v_1 = v_0 / 4, v_2 = v_3 = 4 v_0; the cuticle tilt alpha rotates theta_o by
//!   -2 alpha for R, +alpha for TT and +4 alpha for TRT (pbrt-v4).
//! - `A_p` are the attenuations of [`crate::azimuthal::attenuations`] with the exact chord
//!   transmittance `exp(-sigma_a 2 cos gamma_t / cos theta_t)`.
//! - `N_p(phi) = D(phi - Phi(p, gamma_o, gamma_t))`, D the trimmed logistic of scale s from
//!   beta_n (Chiang eq. 8).
//!
//! **Contract.** `S` carries no cosine factor of any kind: with sigma_a = 0 its integral over all
//! directions wi (solid angle) is 1 for every wo and h. pbrt's `f` equals `S / |cos theta_i|`
//! with theta_i measured to the shading normal; Mitsuba 3's `hair` BSDF returns `S`.
//!
//! **Conventions (pbrt's, converted here).** Directions are in the local frame with the tangent
//! along +X. The offset `h` in [-1, 1] locates the point where `wo`'s ray meets the fibre
//! (gamma_o = asin h), and the relative azimuth of the lobes is phi_i - phi_o, the negative of
//! [`crate::geometry::FibreAngles::phi`].

use crate::absorption::Rgb;
use crate::azimuthal::{
    attenuations_from_fresnel, exit_angle, sample_trimmed_logistic, trimmed_mass, LOBES,
};
use crate::error::ParamError;
use crate::geometry::{azimuth_between, local_direction, local_sin_cos_theta, V3};
use crate::lobe::{deon_lobe_sample_cos_theta, DeonLobe};
use crate::real::{pi, safe_sqrt, wrap_angle, Real};

/// Validated parameters of the Chiang 2016 model.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ChiangParams {
    beta_m: f64,
    beta_n: f64,
    alpha: f64,
    eta: f64,
    sigma_a: Rgb,
}

impl ChiangParams {
    /// Checks and stores the parameters.
    ///
    /// - `beta_m`, `beta_n`: longitudinal and azimuthal roughness in (0, 1].
    /// - `alpha`: cuticle tilt in radians, |alpha| < pi/2 (hair: about 2 degrees).
    /// - `eta`: relative index of refraction, > 1 (hair: 1.55).
    /// - `sigma_a`: absorption per unit fibre radius, finite and >= 0 per channel.
    ///
    /// # Errors
    /// [`ParamError::OutOfRange`] naming the first parameter outside its domain.
    pub fn new(
        beta_m: f64,
        beta_n: f64,
        alpha: f64,
        eta: f64,
        sigma_a: Rgb,
    ) -> Result<Self, ParamError> {
        let roughness = "roughness must be in (0, 1]";
        let beta_m = ParamError::check("beta_m", beta_m, roughness, |v| v > 0.0 && v <= 1.0)?;
        let beta_n = ParamError::check("beta_n", beta_n, roughness, |v| v > 0.0 && v <= 1.0)?;
        let alpha = ParamError::check(
            "alpha",
            alpha,
            "the tilt must be finite with |alpha| < pi/2 radians",
            |v| v.abs() < core::f64::consts::FRAC_PI_2,
        )?;
        let eta = ParamError::check(
            "eta",
            eta,
            "the relative index of refraction must be > 1",
            |v| v > 1.0,
        )?;
        let sigma_a = crate::absorption::validate_sigma_a(sigma_a)?;
        Ok(ChiangParams {
            beta_m,
            beta_n,
            alpha,
            eta,
            sigma_a,
        })
    }

    /// Longitudinal roughness beta_m.
    pub fn beta_m(&self) -> f64 {
        self.beta_m
    }
    /// Azimuthal roughness beta_n.
    pub fn beta_n(&self) -> f64 {
        self.beta_n
    }
    /// Cuticle tilt alpha, radians.
    pub fn alpha(&self) -> f64 {
        self.alpha
    }
    /// Relative index of refraction eta.
    pub fn eta(&self) -> f64 {
        self.eta
    }
    /// Absorption per unit radius.
    pub fn sigma_a(&self) -> Rgb {
        self.sigma_a
    }
}

/// Longitudinal variance of the R lobe from beta_m (Chiang et al. 2016, eq. 7):
/// `v = (0.726 b + 0.812 b^2 + 3.7 b^20)^2`.
pub fn longitudinal_variance(beta_m: f64) -> f64 {
    (0.726 * beta_m + 0.812 * beta_m * beta_m + 3.7 * beta_m.powi(20)).powi(2)
}

/// Logistic scale from beta_n (Chiang et al. 2016, eq. 8):
/// `s = sqrt(pi/8) (0.265 b + 1.194 b^2 + 5.372 b^22)`.
pub fn logistic_scale(beta_n: f64) -> f64 {
    (core::f64::consts::PI / 8.0).sqrt()
        * (0.265 * beta_n + 1.194 * beta_n * beta_n + 5.372 * beta_n.powi(22))
}

/// Number of per-material constants of [`ChiangHair`] ([`ChiangHair::constants`]).
pub const CHIANG_CONSTANTS: usize = 21;

/// The Chiang 2016 model ready to evaluate in the working precision `R`: the per-material
/// constants are derived once in `f64` and rounded to `R`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ChiangHair<R> {
    /// Longitudinal variances v_p for p = 0..3.
    v: [R; LOBES],
    /// d'Eon's lobe of each variance, normalisation precomputed.
    lobe: [DeonLobe<R>; LOBES],
    /// Logistic scale s.
    s: R,
    /// 1 / (the logistic's mass on [-pi, pi]).
    inv_mass: R,
    /// sin and cos of alpha, 2 alpha and 4 alpha.
    sin_2k_alpha: [R; 3],
    cos_2k_alpha: [R; 3],
    eta: R,
    sigma_a: [R; 3],
    /// Derived in [`ChiangHair::from_constants`] (not part of [`ChiangHair::constants`]): 1 / eta,
    /// 1 / s and 1 / (s mass), so that evaluation multiplies instead of dividing.
    inv_eta: R,
    inv_s: R,
    logistic_norm: R,
}

/// One importance sample of [`ChiangHair::sample`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct HairSample<R> {
    /// The sampled incident direction (unit, local frame).
    pub wi: V3<R>,
    /// `S(wi, wo, h)` per channel (no cosine factor).
    pub value: [R; 3],
    /// The solid-angle density of `wi`; the estimator weight is `value / pdf`.
    pub pdf: R,
}

/// The factors of every lobe for one direction pair: the longitudinal `M_p`, and the azimuthal
/// factors at one offset (near field) or averaged over offsets (far field). Evaluation, the pdf
/// and the per-lobe split are sums over them.
#[derive(Clone, Copy, Debug)]
pub(crate) struct LobeTerms<R> {
    /// M_p, tilted, for p = 0..3.
    pub m: [R; LOBES],
    /// A_p N_p per channel (N_3 = 1 / 2 pi).
    pub an: [[R; 3]; LOBES],
    /// (probability of choosing lobe p) N_p.
    pub wn: [R; LOBES],
}

impl<R: Real> LobeTerms<R> {
    /// `S = sum_p M_p A_p N_p` per channel.
    pub fn value(&self) -> [R; 3] {
        core::array::from_fn(|c| {
            let mut sum = R::c(0.0);
            for (m, an) in self.m.iter().zip(&self.an) {
                sum += *m * an[c];
            }
            sum
        })
    }

    /// `pdf = sum_p M_p w_p N_p`.
    pub fn pdf(&self) -> R {
        let mut pdf = R::c(0.0);
        for (m, wn) in self.m.iter().zip(&self.wn) {
            pdf += *m * *wn;
        }
        pdf
    }

    /// `M_p A_p N_p` per lobe and channel.
    pub fn per_lobe(&self) -> [[R; 3]; LOBES] {
        core::array::from_fn(|p| self.an[p].map(|an| self.m[p] * an))
    }
}

impl<R: Real> ChiangHair<R> {
    /// Derives the model constants (pbrt-v4 `HairBxDF` constructor).
    pub fn new(params: &ChiangParams) -> Self {
        let v0 = longitudinal_variance(params.beta_m);
        let v = [v0, 0.25 * v0, 4.0 * v0, 4.0 * v0];
        let lobe = v.map(DeonLobe::new);
        let s = logistic_scale(params.beta_n);
        let mut sin = [params.alpha.sin(), 0.0, 0.0];
        let mut cos = [(1.0 - sin[0] * sin[0]).max(0.0).sqrt(), 0.0, 0.0];
        for k in 1..3 {
            sin[k] = 2.0 * cos[k - 1] * sin[k - 1];
            cos[k] = cos[k - 1] * cos[k - 1] - sin[k - 1] * sin[k - 1];
        }
        let constants: [f64; CHIANG_CONSTANTS] = [
            v[0],
            v[1],
            v[2],
            v[3],
            lobe[0].inv_v,
            lobe[1].inv_v,
            lobe[2].inv_v,
            lobe[3].inv_v,
            lobe[0].norm,
            lobe[1].norm,
            lobe[2].norm,
            lobe[3].norm,
            s,
            1.0 / trimmed_mass(s),
            sin[0],
            sin[1],
            sin[2],
            cos[0],
            cos[1],
            cos[2],
            params.eta,
        ];
        Self::from_constants(constants.map(R::c), params.sigma_a.map(R::c))
    }

    /// The model from constants in the order of [`ChiangHair::constants`] and the absorption
    /// per unit radius. Shader code receives both as uniforms this way.
    pub fn from_constants(c: [R; CHIANG_CONSTANTS], sigma_a: [R; 3]) -> Self {
        let one = R::c(1.0);
        let inv_s = one / c[12];
        ChiangHair {
            inv_eta: one / c[20],
            inv_s,
            logistic_norm: inv_s * c[13],
            v: [c[0], c[1], c[2], c[3]],
            lobe: core::array::from_fn(|p| DeonLobe {
                inv_v: c[4 + p],
                norm: c[8 + p],
            }),
            s: c[12],
            inv_mass: c[13],
            sin_2k_alpha: [c[14], c[15], c[16]],
            cos_2k_alpha: [c[17], c[18], c[19]],
            eta: c[20],
            sigma_a,
        }
    }

    /// Absorption per unit radius.
    pub fn sigma_a(&self) -> [R; 3] {
        self.sigma_a
    }

    /// Relative index of refraction.
    pub fn eta(&self) -> R {
        self.eta
    }

    /// `[v_0..v_3, 1/v_0..1/v_3, the four d'Eon normalisations, s, 1/(logistic mass),
    /// sin alpha, sin 2alpha, sin 4alpha, cos alpha, cos 2alpha, cos 4alpha, eta]`: the
    /// material constants (sigma_a travels separately).
    pub fn constants(&self) -> [R; CHIANG_CONSTANTS] {
        [
            self.v[0],
            self.v[1],
            self.v[2],
            self.v[3],
            self.lobe[0].inv_v,
            self.lobe[1].inv_v,
            self.lobe[2].inv_v,
            self.lobe[3].inv_v,
            self.lobe[0].norm,
            self.lobe[1].norm,
            self.lobe[2].norm,
            self.lobe[3].norm,
            self.s,
            self.inv_mass,
            self.sin_2k_alpha[0],
            self.sin_2k_alpha[1],
            self.sin_2k_alpha[2],
            self.cos_2k_alpha[0],
            self.cos_2k_alpha[1],
            self.cos_2k_alpha[2],
            self.eta,
        ]
    }

    /// theta_o rotated by the tilt of lobe p: -2 alpha (R), +alpha (TT), +4 alpha (TRT), none
    /// for the residual. Returns (sin, |cos|).
    fn tilted(&self, p: usize, sin_o: R, cos_o: R) -> (R, R) {
        let (k, sign) = match p {
            0 => (1, -1.0),
            1 => (0, 1.0),
            2 => (2, 1.0),
            _ => return (sin_o, cos_o),
        };
        let (s, c) = (self.sin_2k_alpha[k] * R::c(sign), self.cos_2k_alpha[k]);
        (sin_o * c + cos_o * s, (cos_o * c - sin_o * s).abs())
    }

    /// Geometry of the path through the fibre for wo and h: (gamma_o, gamma_t, per-channel
    /// segment transmittance, entry Fresnel reflectance).
    ///
    /// `h` must lie in [-1, 1]. The same quantities as [`crate::azimuthal::refracted_offset`],
    /// [`crate::absorption::segment_transmittance`] (chord),
    /// [`crate::fresnel::fresnel_dielectric`] and [`crate::real::safe_asin`] compute, with
    /// the square roots and divisions they would repeat shared: `sqrt(eta^2 - sin_o^2) =
    /// eta cos_t`, one reciprocal of cos_t serves the offset and the chord, and the asines
    /// reuse the cosines `sqrt(1 - h^2)` and `cos gamma_t` (`safe_asin` computes them the same
    /// way; the arguments lie in [-1, 1] so its clamp is idle).
    fn path(&self, sin_o: R, cos_o: R, h: R) -> (R, R, [R; 3], R) {
        let one = R::c(1.0);
        let sin_t = sin_o * self.inv_eta;
        // cos_t >= sqrt(1 - 1/eta^2) > 0 for eta > 1.
        let cos_t = safe_sqrt(one - sin_t * sin_t);
        let inv_cos_t = one / cos_t;
        let sin_gamma_t = h * cos_o * self.inv_eta * inv_cos_t;
        let cos_gamma_t = safe_sqrt(one - sin_gamma_t * sin_gamma_t);
        let chord = R::c(2.0) * cos_gamma_t * inv_cos_t;
        let transmittance = self.sigma_a.map(|sa| (-sa * chord).exp());
        let cos_gamma_o = safe_sqrt(one - h * h);
        let fresnel = self.fresnel_from_outside(cos_o * cos_gamma_o);
        let gamma_o = h.atan2(cos_gamma_o);
        let gamma_t = sin_gamma_t.atan2(cos_gamma_t);
        (gamma_o, gamma_t, transmittance, fresnel)
    }

    /// [`crate::fresnel::fresnel_dielectric`] for light arriving from outside, `cos_i` in
    /// [0, 1]: with eta > 1 there is no total internal reflection (and cos_t > 0), and the two
    /// amplitude ratios share one division,
    /// `(r_par^2 + r_perp^2) / 2 = (a^2 d^2 + c^2 b^2) / (2 b^2 d^2)` with `r_par = a / b`,
    /// `r_perp = c / d` (b, d >= cos_t > 0).
    fn fresnel_from_outside(&self, cos_i: R) -> R {
        let one = R::c(1.0);
        let eta = self.eta;
        let sin2_t = (one - cos_i * cos_i) * (self.inv_eta * self.inv_eta);
        let cos_t = safe_sqrt(one - sin2_t);
        let (a, b) = (eta * cos_i - cos_t, eta * cos_i + cos_t);
        let (c, d) = (cos_i - eta * cos_t, cos_i + eta * cos_t);
        let (bb, dd) = (b * b, d * d);
        let r = (a * a * dd + c * c * bb) / (R::c(2.0) * bb * dd);
        r.min(one)
    }

    /// M_p for p = 0..3 with the tilt of each lobe.
    pub(crate) fn longitudinal(&self, sin_i: R, cos_i: R, sin_o: R, cos_o: R) -> [R; LOBES] {
        core::array::from_fn(|p| {
            let (sin_op, cos_op) = self.tilted(p, sin_o, cos_o);
            self.lobe[p].eval(sin_i, cos_i, sin_op, cos_op)
        })
    }

    /// The azimuthal factors at offset `h` (clamped to [-1, 1]) for relative azimuth
    /// `phi = phi_i - phi_o`: `(A_p N_p per channel, w_p N_p)`.
    pub(crate) fn azimuthal(
        &self,
        sin_o: R,
        cos_o: R,
        phi: R,
        h: R,
    ) -> ([[R; 3]; LOBES], [R; LOBES]) {
        let (a, n) = self.attenuations_and_azimuths(sin_o, cos_o, phi, h);
        let w = Self::lobe_weights(&a);
        (
            core::array::from_fn(|p| a[p].map(|x| x * n[p])),
            core::array::from_fn(|p| w[p] * n[p]),
        )
    }

    /// `A_p` per channel and `N_p` at offset `h` (clamped to [-1, 1]) for relative azimuth
    /// `phi`: the part of [`ChiangHair::azimuthal`] that evaluation needs (it skips the lobe
    /// weights of sampling).
    /// gamma_o, gamma_t and `A_p` per lobe and channel at offset `h` (clamped to [-1, 1]).
    fn attenuations_at(&self, sin_o: R, cos_o: R, h: R) -> (R, R, [[R; 3]; LOBES]) {
        let h = h.clamp(R::c(-1.0), R::c(1.0));
        let (gamma_o, gamma_t, transmittance, fresnel) = self.path(sin_o, cos_o, h);
        let per_channel = transmittance.map(|t| attenuations_from_fresnel(fresnel, t));
        let a = core::array::from_fn(|p| [per_channel[0][p], per_channel[1][p], per_channel[2][p]]);
        (gamma_o, gamma_t, a)
    }

    fn attenuations_and_azimuths(
        &self,
        sin_o: R,
        cos_o: R,
        phi: R,
        h: R,
    ) -> ([[R; 3]; LOBES], [R; LOBES]) {
        let (gamma_o, gamma_t, a) = self.attenuations_at(sin_o, cos_o, h);
        // N_p = logistic(dphi_p, s) / (trimmed mass) = e_p / (s mass (1 + e_p)^2) with
        // e_p = exp(-|dphi_p| / s): 1/s and 1/(s mass) are precomputed, and the three
        // denominators (each in [1, 4]) share one division.
        let e: [R; 3] = core::array::from_fn(|p| {
            let dphi = wrap_angle(phi - exit_angle(R::c(p as f64), gamma_o, gamma_t));
            (-dphi.abs() * self.inv_s).exp()
        });
        let d = e.map(|e| (R::c(1.0) + e).sqr());
        let r = self.logistic_norm / (d[0] * d[1] * d[2]);
        let n = [
            e[0] * (r * (d[1] * d[2])),
            e[1] * (r * (d[0] * d[2])),
            e[2] * (r * (d[0] * d[1])),
            R::c(0.5 * core::f64::consts::FRAC_1_PI),
        ];
        (a, n)
    }

    /// The angles of a direction pair: (sin_i, cos_i, sin_o, cos_o, phi_i - phi_o).
    pub(crate) fn angles(wi: V3<R>, wo: V3<R>) -> (R, R, R, R, R) {
        let (sin_o, cos_o) = local_sin_cos_theta(wo);
        let (sin_i, cos_i) = local_sin_cos_theta(wi);
        let phi = azimuth_between(V3::c(1.0, 0.0, 0.0), normal_plane(wo), normal_plane(wi));
        (sin_i, cos_i, sin_o, cos_o, phi)
    }

    /// The lobe factors for a direction pair and an azimuthal part computed by `azimuthal`
    /// from (sin_o, cos_o, phi).
    pub(crate) fn terms_with(
        &self,
        wi: V3<R>,
        wo: V3<R>,
        azimuthal: impl FnOnce(R, R, R) -> ([[R; 3]; LOBES], [R; LOBES]),
    ) -> LobeTerms<R> {
        let (sin_i, cos_i, sin_o, cos_o, phi) = Self::angles(wi, wo);
        let (an, wn) = azimuthal(sin_o, cos_o, phi);
        LobeTerms {
            m: self.longitudinal(sin_i, cos_i, sin_o, cos_o),
            an,
            wn,
        }
    }

    fn terms(&self, wi: V3<R>, wo: V3<R>, h: R) -> LobeTerms<R> {
        self.terms_with(wi, wo, |sin_o, cos_o, phi| {
            self.azimuthal(sin_o, cos_o, phi, h)
        })
    }

    /// `S(wi, wo, h)` per channel, for unit `wi`, `wo` in the local frame and offset `h` in
    /// [-1, 1] (clamped). No cosine factor (see the module documentation). Finite and
    /// non-negative for every finite input.
    pub fn eval(&self, wi: V3<R>, wo: V3<R>, h: R) -> [R; 3] {
        // `terms(..).value()` without the lobe weights, which only the pdf needs.
        let (sin_i, cos_i, sin_o, cos_o, phi) = Self::angles(wi, wo);
        let (a, n) = self.attenuations_and_azimuths(sin_o, cos_o, phi, h);
        LobeTerms {
            m: self.longitudinal(sin_i, cos_i, sin_o, cos_o),
            an: core::array::from_fn(|p| a[p].map(|x| x * n[p])),
            wn: [R::c(0.0); LOBES],
        }
        .value()
    }

    /// The contribution `M_p A_p N_p` of each lobe (R, TT, TRT, residual) per channel; they sum
    /// to [`ChiangHair::eval`].
    pub fn eval_lobes(&self, wi: V3<R>, wo: V3<R>, h: R) -> [[R; 3]; LOBES] {
        self.terms(wi, wo, h).per_lobe()
    }

    /// Probability of choosing each lobe when sampling from wo: the channel-averaged A_p,
    /// normalised (pbrt-v4 `ApPDF`).
    fn lobe_weights(a: &[[R; 3]; LOBES]) -> [R; LOBES] {
        let avg = a.map(|ch| (ch[0] + ch[1] + ch[2]) * R::c(1.0 / 3.0));
        let total = (avg[0] + avg[1] + avg[2] + avg[3]).max(R::c(1e-30));
        avg.map(|x| x / total)
    }

    /// Solid-angle density of [`ChiangHair::sample`] choosing `wi` given `wo` and `h`.
    pub fn pdf(&self, wi: V3<R>, wo: V3<R>, h: R) -> R {
        self.terms(wi, wo, h).pdf()
    }

    /// Importance-samples wi given wo and h from three uniforms in [0, 1): `uc` chooses the lobe
    /// (and, remapped, the azimuth), `u[0]` the longitudinal angle, `u[1]` the azimuth of the
    /// longitudinal cone (d'Eon 2013; pbrt-v4 `Sample_f`). Branch-free, so it traces.
    pub fn sample(&self, wo: V3<R>, h: R, u: [R; 2], uc: R) -> HairSample<R> {
        let wi = self.sample_direction(wo, h, u, uc);
        let terms = self.terms(wi, wo, h);
        HairSample {
            wi,
            value: terms.value(),
            pdf: terms.pdf(),
        }
    }

    /// The direction [`ChiangHair::sample`] draws, without evaluating S and the pdf there.
    pub(crate) fn sample_direction(&self, wo: V3<R>, h: R, u: [R; 2], uc: R) -> V3<R> {
        let one = R::c(1.0);
        let (sin_o, cos_o) = local_sin_cos_theta(wo);
        let (gamma_o, gamma_t, a) = self.attenuations_at(sin_o, cos_o, h);
        let w = Self::lobe_weights(&a);

        // Choose p: the first lobe whose cumulative weight exceeds uc; remap uc into it.
        let uc = uc.clamp(R::c(0.0), one);
        let mut lower = R::c(0.0);
        let mut chosen = [R::c(0.0); 6]; // p, lower, width, sin_op, cos_op, v_p
        for (p, &weight) in w.iter().enumerate() {
            // The intervals [lower, upper) partition [0, 1]; the last one takes the rest.
            let upper = if p == LOBES - 1 {
                R::c(2.0)
            } else {
                lower + weight
            };
            let here = !uc.lt(lower) & uc.lt(upper);
            let (sin_op, cos_op) = self.tilted(p, sin_o, cos_o);
            let candidate = [R::c(p as f64), lower, weight, sin_op, cos_op, self.v[p]];
            for (slot, value) in chosen.iter_mut().zip(candidate) {
                *slot = R::select(here, value, *slot);
            }
            lower += weight;
        }
        let [p, lower, width, sin_op, cos_op, v] = chosen;
        let uc = ((uc - lower) / width.max(R::c(1e-30))).clamp(R::c(0.0), R::c(1.0 - 1e-7));

        // Longitudinal: sample the lobe about its axis, then rotate about the cone.
        let cos_theta = deon_lobe_sample_cos_theta(v, u[0]);
        let sin_theta = safe_sqrt(one - cos_theta * cos_theta);
        // cos(2 pi u1), with the argument kept in [-pi, pi] for GPU accuracy.
        let cos_phi = -(R::c(2.0) * pi::<R>() * u[1] - pi::<R>()).cos();
        let sin_i = (-cos_theta * sin_op + sin_theta * cos_phi * cos_op).clamp(-one, one);
        let cos_i = safe_sqrt(one - sin_i * sin_i);

        // Azimuthal: logistic about Phi(p) for p < 3, uniform for the residual.
        let is_residual = R::c(2.5).lt(p);
        let dphi = R::select(
            is_residual,
            R::c(2.0) * pi::<R>() * uc,
            exit_angle(p, gamma_o, gamma_t) + sample_trimmed_logistic(uc, self.s),
        );
        let phi_o = azimuth_between(V3::c(1.0, 0.0, 0.0), V3::c(0.0, 1.0, 0.0), wo);
        local_direction(sin_i, cos_i, wrap_angle(phi_o + wrap_angle(dphi)))
    }
}

/// The projection of a local direction onto the fibre's normal plane (YZ).
fn normal_plane<R: Real>(w: V3<R>) -> V3<R> {
    V3::new(R::c(0.0), w.y, w.z)
}
