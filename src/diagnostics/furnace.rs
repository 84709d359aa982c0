//! The white furnace: the directional albedo of a model and its worst deviation from 1.

use super::accumulate;
use crate::bcsdf::{Bcsdf, Query};
use crate::geometry::{local_direction, V3};
use crate::quadrature::SphereRule;

/// The azimuth phi_o (radians) of every viewing direction of the diagnostics
/// ([`viewing_direction`]): away from 0 and +-pi, so the relative azimuths phi_i - phi_o of a
/// [`SphereRule`]'s nodes are not placed symmetrically about the lobes.
pub const VIEW_AZIMUTH: f64 = 0.3;

/// The unit viewing direction wo at inclination `theta_o_deg` degrees from the fibre's normal
/// plane and azimuth [`VIEW_AZIMUTH`], in the local frame (tangent +X,
/// [`local_direction`]).
pub fn viewing_direction(theta_o_deg: f64) -> V3<f64> {
    let t = theta_o_deg.to_radians();
    local_direction(t.sin(), t.cos(), VIEW_AZIMUTH)
}

/// The directional albedo `rho(wo, h) = int S(wi, wo, h) dwi` per channel (solid angle, no
/// cosine factor: the contract of [`Bcsdf::eval`]), by the sphere rule `rule`:
/// `sum_k w_k S(wi_k, wo, h)`. With sigma_a = 0 an energy-conserving model gives 1 up to the
/// rule's error. Far-field models ignore `h`.
pub fn albedo<M: Bcsdf<f64> + ?Sized>(
    model: &M,
    rule: &SphereRule,
    wo: V3<f64>,
    h: f64,
) -> [f64; 3] {
    let mut sum = [0.0; 3];
    for &(wi, weight) in &rule.nodes {
        accumulate(&mut sum, weight, model.eval(&Query::new(wi, wo, h)));
    }
    sum
}

/// One viewing configuration of a [`white_furnace`] check.
#[derive(Clone, Debug, PartialEq)]
pub struct FurnaceCase {
    /// Inclination theta_o of wo, degrees ([`viewing_direction`]).
    pub theta_o_deg: f64,
    /// The offset h (0 for a far-field model).
    pub h: f64,
    /// The albedo per channel ([`albedo`]).
    pub albedo: [f64; 3],
    /// `albedo - 1` of the channel where `|albedo - 1|` is largest (signed).
    pub error: f64,
}

/// The result of a [`white_furnace`] check.
#[derive(Clone, Debug, PartialEq)]
pub struct Furnace {
    /// Every configuration: theta_o outermost, then h, in the order given.
    pub cases: Vec<FurnaceCase>,
    /// The signed `albedo - 1` of largest magnitude over cases and channels (0 when there are
    /// no cases).
    pub worst_error: f64,
}

/// The white-furnace check of `model` (which should have sigma_a = 0): the [`albedo`] by
/// `rule` for wo at each inclination of `theta_o_deg` (degrees, [`viewing_direction`]) and
/// each offset of `offsets`, and the worst signed error `albedo - 1` over them and the
/// channels. A far-field model ([`Bcsdf::uses_offset`] false) is evaluated once per
/// inclination, at h = 0, whatever `offsets` holds.
pub fn white_furnace<M: Bcsdf<f64> + ?Sized>(
    model: &M,
    rule: &SphereRule,
    theta_o_deg: &[f64],
    offsets: &[f64],
) -> Furnace {
    let offsets: &[f64] = if model.uses_offset() { offsets } else { &[0.0] };
    let mut cases = Vec::with_capacity(theta_o_deg.len() * offsets.len());
    let mut worst_error = 0.0_f64;
    for &theta in theta_o_deg {
        let wo = viewing_direction(theta);
        for &h in offsets {
            let albedo = albedo(model, rule, wo, h);
            let error =
                albedo
                    .iter()
                    .map(|a| a - 1.0)
                    .fold(0.0_f64, |w, e| if e.abs() > w.abs() { e } else { w });
            if error.abs() > worst_error.abs() {
                worst_error = error;
            }
            cases.push(FurnaceCase {
                theta_o_deg: theta,
                h,
                albedo,
                error,
            });
        }
    }
    Furnace { cases, worst_error }
}
