//! A model's outgoing radiance under environments of spherical harmonics, against a
//! reference's: the error measure of a scene lit by an SH environment (`environment = "sh"`
//! of `hairmath plan`).
//!
//! # The measure
//!
//! An environment band-limited to `l <= L`, in the fibre's local frame, is
//! `L(wi) = sum_{l <= L, m} c_lm Y_lm(wi)`, and a model's outgoing radiance toward `wo` is
//! `L_o(wo) = int S(wi, wo) L(wi) dwi` (the crate's S, with no cosine factor), linear in the
//! coefficients: `L_o(wo) = sum_lm c_lm T_lm(wo)` with the transfer
//! `T_lm(wo) = int S(wi, wo) Y_lm(wi) dwi` per channel. A model's error against a reference is
//! the relative norm of the transfers' difference,
//!
//! `E_env = sqrt( sum_lm,RGB int (T_lm - T_ref,lm)^2 dwo / sum_lm,RGB int T_ref,lm^2 dwo )`,
//!
//! the root-mean-square relative error of the outgoing radiance over environments whose
//! coefficients are independent with equal variance (the band's Y_lm are orthonormal).
//!
//! Every model measured is invariant under rotations about the fibre axis, and a rotation
//! about the axis maps the band onto itself orthogonally, so the sum over `lm` of `T_lm(wo)^2`
//! depends on `wo` only through its inclination: the integral over `wo` is one over
//! `theta_o`, by [`EnvironmentRule::viewers`] Gauss-Legendre nodes at azimuth 0 (in theta_o
//! rather than its sine: the transfer is steepest at grazing, and nodes in the sine converged
//! to 2% where these reach 3e-4). The
//! integrals over `wi` are a [`SphereRule`] of [`EnvironmentRule`]'s size, the same for the
//! model and the reference; `tests/environment.rs` measures how far E_env has converged.

use crate::bcsdf::{Bcsdf, Query};
use crate::error::ParamError;
use crate::geometry::{local_direction, V3};
use crate::quadrature::{gauss_legendre, SphereRule};
use crate::sh::eval_sh_f64;
use glam::DVec3;

/// The quadrature of an [`ShEnvironment`]: a [`SphereRule`] over `wi` and Gauss-Legendre
/// nodes in `theta_o`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct EnvironmentRule {
    /// Panels of the rule in theta_i.
    pub theta_panels: usize,
    /// Gauss-Legendre nodes per panel.
    pub order: usize,
    /// Azimuths of wi.
    pub azimuths: usize,
    /// Inclinations of wo.
    pub viewers: usize,
}

impl Default for EnvironmentRule {
    /// 16 panels of 4 nodes in theta_i, 48 azimuths, 16 viewers: E_env of a composition of
    /// Karis' factors at beta_m = 0.3 within 3e-4 (relative) of a rule 4 times finer in
    /// theta_i and theta_o and 2.7 times in the azimuth, for bands up to 0, 2 and 8
    /// (measured; `tests/environment.rs` asserts 2e-3 against a rule twice as fine).
    fn default() -> Self {
        EnvironmentRule {
            theta_panels: 16,
            order: 4,
            azimuths: 48,
            viewers: 16,
        }
    }
}

/// The transfer of models under the environments of bands `l <= lmax` (module
/// documentation).
#[derive(Clone, Debug)]
pub struct ShEnvironment {
    /// The wi nodes with their weights and `Y_lm(wi)`, band by band.
    incoming: Vec<(V3<f64>, f64, Vec<f64>)>,
    /// The wo nodes with the square roots of their weights.
    viewers: Vec<(V3<f64>, f64)>,
    /// `(lmax + 1)^2`.
    coefficients: usize,
}

impl ShEnvironment {
    /// The measure of bands `l <= lmax` by `rule`.
    ///
    /// # Errors
    /// [`ParamError::OutOfRange`] naming `lmax` above 8 (the scenes' largest band) or a rule
    /// count of 0.
    pub fn new(lmax: usize, rule: EnvironmentRule) -> Result<Self, ParamError> {
        ParamError::check("lmax", lmax as f64, "must be at most 8", |l| l <= 8.0)?;
        for (name, n) in [
            ("theta_panels", rule.theta_panels),
            ("order", rule.order),
            ("azimuths", rule.azimuths),
            ("viewers", rule.viewers),
        ] {
            ParamError::check(name, n as f64, "must be at least 1", |n| n >= 1.0)?;
        }
        let sphere = SphereRule::new(rule.theta_panels, rule.order, rule.azimuths);
        let incoming = sphere
            .nodes
            .iter()
            .map(|&(wi, weight)| {
                let y = eval_sh_f64(lmax, DVec3::new(wi.x, wi.y, wi.z))?;
                Ok((wi, weight, y))
            })
            .collect::<Result<_, ParamError>>()?;
        // int over the sphere of f(theta_o) = 2 pi int f cos(theta_o) d theta_o, the nodes in
        // theta_o rather than its sine: the transfer is steepest at grazing.
        let half_pi = core::f64::consts::FRAC_PI_2;
        let viewers = gauss_legendre(rule.viewers)
            .into_iter()
            .map(|(x, w)| {
                let theta = half_pi * x;
                let wo = local_direction(theta.sin(), theta.cos(), 0.0);
                (
                    wo,
                    (core::f64::consts::TAU * half_pi * w * theta.cos()).sqrt(),
                )
            })
            .collect();
        Ok(ShEnvironment {
            incoming,
            viewers,
            coefficients: (lmax + 1) * (lmax + 1),
        })
    }

    /// The length of a transfer vector: viewers x coefficients x RGB.
    pub fn len(&self) -> usize {
        self.viewers.len() * self.coefficients * 3
    }

    /// Whether the vectors are empty (never: every count is at least 1).
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// `sqrt(w_o) T_lm(wo)` per viewer, coefficient and channel, flattened in that order, for
    /// each of `values`' outputs: `values(wi, wo)` gives S per output (one per lobe, or the
    /// sum).
    fn transfers(
        &self,
        outputs: usize,
        values: impl Fn(V3<f64>, V3<f64>, &mut [[f64; 3]]),
    ) -> Vec<Vec<f64>> {
        let mut out = vec![vec![0.0; self.len()]; outputs];
        let mut s = vec![[0.0; 3]; outputs];
        for (j, &(wo, root)) in self.viewers.iter().enumerate() {
            let base = j * self.coefficients * 3;
            for (wi, weight, y) in &self.incoming {
                values(*wi, wo, &mut s);
                for (transfer, value) in out.iter_mut().zip(&s) {
                    let block = &mut transfer[base..base + self.coefficients * 3];
                    for (k, &y_lm) in y.iter().enumerate() {
                        let scale = root * weight * y_lm;
                        for c in 0..3 {
                            block[3 * k + c] += scale * value[c];
                        }
                    }
                }
            }
        }
        out
    }

    /// The transfer vector of `model` (its [`Bcsdf::eval`]), weighted for
    /// [`ShEnvironment::relative_error`]: the squared norm of a difference of two is the
    /// numerator of E_env.
    pub fn transfer<M: Bcsdf<f64> + ?Sized>(&self, model: &M) -> Vec<f64> {
        self.transfer_of(|wi, wo| model.eval(&Query::far(wi, wo)))
    }

    /// The transfer vector of any evaluation `s(wi, wo)` (RGB, no cosine factor): of a model
    /// in another precision, or of a shader's outputs at these directions.
    pub fn transfer_of(&self, s: impl Fn(V3<f64>, V3<f64>) -> [f64; 3]) -> Vec<f64> {
        let mut out = self.transfers(1, |wi, wo, values| values[0] = s(wi, wo));
        out.pop().unwrap_or_default()
    }

    /// The transfer vector of each of `model`'s lobes ([`Bcsdf::eval_lobes`]), in its order.
    pub fn lobe_transfers<M: Bcsdf<f64> + ?Sized>(&self, model: &M) -> Vec<Vec<f64>> {
        let lobes = model.lobe_names().len();
        self.transfers(lobes, |wi, wo, s| {
            for (out, lobe) in s.iter_mut().zip(model.eval_lobes(&Query::far(wi, wo))) {
                *out = lobe;
            }
        })
    }

    /// E_env of `model` against the reference whose [`ShEnvironment::transfer`] is
    /// `reference`: 0 for the reference itself, 1 for a model that is 0 everywhere, infinite
    /// (never NaN) for a model with a non-finite value.
    pub fn relative_error<M: Bcsdf<f64> + ?Sized>(&self, model: &M, reference: &[f64]) -> f64 {
        relative_norm(&self.transfer(model), reference)
    }
}

/// `|a - b| / |b|` of two vectors (a transfer or a measure's vector against the reference's):
/// 0 when both are 0, infinite (never NaN) when `a` is not finite or `b` is 0 alone.
pub fn relative_norm(a: &[f64], b: &[f64]) -> f64 {
    let difference: f64 = a.iter().zip(b).map(|(x, y)| (x - y) * (x - y)).sum();
    let reference: f64 = b.iter().map(|y| y * y).sum();
    match (difference.is_finite(), reference > 0.0) {
        (false, _) => f64::INFINITY,
        (true, true) => (difference / reference).sqrt(),
        (true, false) if difference == 0.0 => 0.0,
        (true, false) => f64::INFINITY,
    }
}
