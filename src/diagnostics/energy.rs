//! Lobe energies: the integral of each lobe over the sphere, averaged over the offset.

use super::accumulate;
use crate::bcsdf::{Bcsdf, FarFieldRule, Query};
use crate::geometry::V3;
use crate::quadrature::SphereRule;

/// The energy of each lobe of a model for one viewing direction ([`lobe_energies`]).
#[derive(Clone, Debug, PartialEq)]
pub struct LobeEnergies {
    /// The lobes, as the model names them ([`Bcsdf::lobe_names`]).
    pub names: &'static [&'static str],
    /// Energy of each lobe of `names` per channel (linear RGB).
    pub lobes: Vec<[f64; 3]>,
    /// The sum of the lobes per channel: the albedo averaged over h.
    pub total: [f64; 3],
}

impl LobeEnergies {
    /// The energy of the lobe called `name`, if the model has one.
    pub fn lobe(&self, name: &str) -> Option<[f64; 3]> {
        self.names
            .iter()
            .position(|n| *n == name)
            .map(|p| self.lobes[p])
    }

    /// The largest absolute difference from `other` over lobes and channels, lobes matched by
    /// name; a lobe only one of the two tables has counts as zero energy in the other.
    pub fn max_difference(&self, other: &LobeEnergies) -> f64 {
        let mut worst = 0.0_f64;
        for name in self.names.iter().chain(other.names) {
            let (a, b) = (self.lobe(name), other.lobe(name));
            let (a, b) = (a.unwrap_or([0.0; 3]), b.unwrap_or([0.0; 3]));
            for (x, y) in a.iter().zip(b) {
                worst = worst.max((x - y).abs());
            }
        }
        worst
    }
}

/// The energy of each lobe and channel of `model` seen from `wo`:
///
/// `E_p = sum_k P_k sum_j w_j S_p(wi_j, wo, h_k)`,
///
/// the integral over all incident directions of the lobe's `S_p` ([`Bcsdf::eval_lobes`]; the
/// sphere rule `sphere`'s nodes wi_j and weights w_j), averaged over h uniform in [-1, 1] with
/// the nodes (h_k, P_k) of `offsets` (a [`FarFieldRule`]: Gauss-Legendre in gamma = asin h,
/// where the integrand is smooth at the fibre's edges). A far-field model
/// ([`Bcsdf::uses_offset`] false) already averages over h: it is evaluated at the single node
/// h = 0 of weight 1 and `offsets` is not used.
pub fn lobe_energies<M: Bcsdf<f64> + ?Sized>(
    model: &M,
    sphere: &SphereRule,
    wo: V3<f64>,
    offsets: &FarFieldRule,
) -> LobeEnergies {
    let nodes: &[(f64, f64)] = if model.uses_offset() {
        offsets.nodes()
    } else {
        &[(0.0, 1.0)]
    };
    let names = model.lobe_names();
    let mut lobes = vec![[0.0; 3]; names.len()];
    for &(h, h_weight) in nodes {
        for &(wi, weight) in &sphere.nodes {
            let values = model.eval_lobes(&Query::new(wi, wo, h));
            for (energy, value) in lobes.iter_mut().zip(values) {
                accumulate(energy, h_weight * weight, value);
            }
        }
    }
    let mut total = [0.0; 3];
    for lobe in &lobes {
        accumulate(&mut total, 1.0, *lobe);
    }
    LobeEnergies {
        names,
        lobes,
        total,
    }
}
