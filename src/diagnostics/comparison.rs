//! How far a model is from a reference, and what it costs: the figures of `hairmath models`.
//!
//! - **Error** ([`ReferenceSamples::relative_error`]): over pairs of directions (wi, wo)
//!   uniform on the product of two spheres,
//!   `E = sqrt( sum over pairs and RGB of (S_model - S_ref)^2 / sum of S_ref^2 )`.
//!   The pairs are a fixed, weighted low-discrepancy set ([`DirectionPairs::kronecker`]); the first half
//!   of a set is the set of half the size, so the error on the first half
//!   ([`ModelError::half`]) comes with every figure and shows how far it has converged.
//! - **Energy error** ([`EnergyReference::errors`]): the directional albedo of the model
//!   against the reference's at fixed viewing inclinations.
//! - **Operation counts** ([`OpCounts::of`]): what a traced evaluation computes, table
//!   fetches included.

use super::furnace::{albedo, viewing_direction};
use crate::bcsdf::{Bcsdf, Query};
use crate::geometry::{local_direction, V3};
use crate::quadrature::{kronecker, SphereRule};
use crate::real::{Binary, Graph, Node, Unary};

/// Pairs of unit directions (wi, wo) in the fibre's local frame with weights: a rule for
/// integrals over the product of two spheres (solid angle in each).
#[derive(Clone, Debug, PartialEq)]
pub struct DirectionPairs {
    pairs: Vec<(V3<f64>, V3<f64>)>,
    weights: Vec<f64>,
}

impl DirectionPairs {
    /// The first `n` points `u` of the 3-dimensional [`kronecker`] sequence as the
    /// inclinations `theta_i = pi (u_0 - 1/2)`, `theta_o = pi (u_1 - 1/2)` and the relative
    /// azimuth `phi = 2 pi u_2 - pi` (wo at azimuth 0, wi at phi), each pair weighted by the
    /// solid-angle density `cos theta_i cos theta_o` (normalised to mean 1).
    ///
    /// Every model compared here is invariant under rotations about the fibre axis (a far
    /// field depends on the azimuths only through their difference), so the product of two
    /// spheres reduces to these three coordinates. Points uniform in theta rather than in
    /// sin theta (which would be uniform on the sphere without weights) put more of them near
    /// grazing, where the reference's lobes are tallest: forward scattering along the tangent
    /// (wi near -wo near +-X) dominates sums of S^2, and uniform points in the sines make such
    /// sums converge visibly slower (E of Kajiya-Kay for dark brown hair, eumelanin 3, at
    /// beta_m = beta_n = 0.3: 0.9006 and 0.9092 on 2^15 and 2^16 points uniform in the sines,
    /// 0.8926 and 0.8933 on these). The set for `n / 2` is the first half of the set for `n`.
    pub fn kronecker(n: usize) -> Self {
        let direction = |theta: f64, phi: f64| local_direction(theta.sin(), theta.cos(), phi);
        let mut pairs = Vec::with_capacity(n);
        let mut weights = Vec::with_capacity(n);
        for k in 0..n {
            let mut u = [0.0; 3];
            kronecker(k, 3, &mut u);
            let theta_i = core::f64::consts::PI * (u[0] - 0.5);
            let theta_o = core::f64::consts::PI * (u[1] - 0.5);
            let phi = core::f64::consts::TAU * u[2] - core::f64::consts::PI;
            pairs.push((direction(theta_i, phi), direction(theta_o, 0.0)));
            // The mean of cos over theta uniform in [-pi/2, pi/2] is 2/pi.
            weights.push(theta_i.cos() * theta_o.cos() * (core::f64::consts::PI / 2.0).powi(2));
        }
        DirectionPairs { pairs, weights }
    }

    /// The number of pairs.
    pub fn len(&self) -> usize {
        self.pairs.len()
    }

    /// Whether there are no pairs.
    pub fn is_empty(&self) -> bool {
        self.pairs.is_empty()
    }

    /// The pairs `(wi, wo)`.
    pub fn pairs(&self) -> &[(V3<f64>, V3<f64>)] {
        &self.pairs
    }

    /// The weight of each pair (mean 1 for a large set): the sum of `weight f(wi, wo)` over
    /// the pairs divided by their number approximates the mean of `f` over the product of
    /// two spheres.
    pub fn weights(&self) -> &[f64] {
        &self.weights
    }

    /// The first `n` pairs (all of them if there are fewer).
    pub fn first(&self, n: usize) -> Self {
        let n = n.min(self.pairs.len());
        DirectionPairs {
            pairs: self.pairs[..n].to_vec(),
            weights: self.weights[..n].to_vec(),
        }
    }
}

/// A reference model's values on a set of direction pairs, against which models are measured.
#[derive(Clone, Debug, PartialEq)]
pub struct ReferenceSamples {
    pairs: DirectionPairs,
    values: Vec<[f64; 3]>,
}

/// The relative error E of a model on a set of pairs and on its first half.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ModelError {
    /// E on every pair.
    pub full: f64,
    /// E on the first half of the pairs (the set of half the size): `|full - half|` is the
    /// convergence check of the figure.
    pub half: f64,
}

impl ModelError {
    /// The figure's change from half the pairs to all of them, relative to the figure:
    /// below 5e-3 the figure is converged to two significant digits at the first.
    pub fn relative_change(&self) -> f64 {
        (self.full - self.half).abs() / self.full.abs().max(f64::MIN_POSITIVE)
    }
}

/// Sums of squares over pairs: `(sum (S - S_ref)^2, sum S_ref^2)`.
#[derive(Clone, Copy, Debug, Default)]
struct Squares {
    difference: f64,
    reference: f64,
}

impl Squares {
    fn error(self) -> f64 {
        if self.reference > 0.0 {
            (self.difference / self.reference).sqrt()
        } else if self.difference == 0.0 {
            0.0
        } else {
            f64::INFINITY
        }
    }
}

impl ReferenceSamples {
    /// The reference's [`Bcsdf::eval`] on every pair (far-field queries, h = 0).
    pub fn new<M: Bcsdf<f64> + ?Sized>(reference: &M, pairs: DirectionPairs) -> Self {
        let values = pairs
            .pairs
            .iter()
            .map(|&(wi, wo)| reference.eval(&Query::far(wi, wo)))
            .collect();
        ReferenceSamples { pairs, values }
    }

    /// The samples of the first `n` pairs (all of them if there are fewer): the reference on
    /// [`DirectionPairs::kronecker`]`(n)` when these are Kronecker pairs.
    pub fn first(&self, n: usize) -> Self {
        let n = n.min(self.values.len());
        ReferenceSamples {
            pairs: self.pairs.first(n),
            values: self.values[..n].to_vec(),
        }
    }

    /// The pairs.
    pub fn pairs(&self) -> &DirectionPairs {
        &self.pairs
    }

    /// The reference's values, one per pair.
    pub fn values(&self) -> &[[f64; 3]] {
        &self.values
    }

    /// `E = sqrt( sum over pairs and RGB of (S_model - S_ref)^2 / sum of S_ref^2 )` on all the
    /// pairs and on their first half, each pair's terms multiplied by its weight
    /// ([`DirectionPairs::weights`]): the ratio of the two integrals over the product of two
    /// spheres. A non-finite model value makes E infinite (never NaN);
    /// E is 0 for a model equal to the reference, and 1 for a model that is 0 everywhere.
    pub fn relative_error<M: Bcsdf<f64> + ?Sized>(&self, model: &M) -> ModelError {
        let half_len = self.values.len() / 2;
        let mut half = Squares::default();
        let mut full = Squares::default();
        let weighted = self.pairs.pairs.iter().zip(&self.pairs.weights);
        for (k, ((&(wi, wo), &w), reference)) in weighted.zip(&self.values).enumerate() {
            if k == half_len {
                half = full;
            }
            let value = model.eval(&Query::far(wi, wo));
            for (s, r) in value.iter().zip(reference) {
                let d = s - r;
                full.difference += if d.is_finite() {
                    w * d * d
                } else {
                    f64::INFINITY
                };
                full.reference += w * r * r;
            }
        }
        ModelError {
            full: full.error(),
            half: half.error(),
        }
    }
}

/// The reference's directional albedo at a few viewing inclinations, against which a model's
/// energy is measured.
#[derive(Clone, Debug)]
pub struct EnergyReference {
    rule: SphereRule,
    theta_o_deg: Vec<f64>,
    albedos: Vec<[f64; 3]>,
}

impl EnergyReference {
    /// The albedo [`albedo`]`(reference, rule, wo)` per channel at the viewing directions
    /// [`viewing_direction`]`(theta_o)` for each of `theta_o_deg` (degrees from the normal
    /// plane).
    pub fn new<M: Bcsdf<f64> + ?Sized>(
        reference: &M,
        rule: SphereRule,
        theta_o_deg: &[f64],
    ) -> Self {
        let albedos = theta_o_deg
            .iter()
            .map(|&t| albedo(reference, &rule, viewing_direction(t), 0.0))
            .collect();
        EnergyReference {
            rule,
            theta_o_deg: theta_o_deg.to_vec(),
            albedos,
        }
    }

    /// The viewing inclinations, degrees.
    pub fn theta_o_deg(&self) -> &[f64] {
        &self.theta_o_deg
    }

    /// The reference's albedos per channel, one per inclination.
    pub fn albedos(&self) -> &[[f64; 3]] {
        &self.albedos
    }

    /// Per inclination, the relative energy error of `model`: `(a_model - a_ref) / a_ref` where
    /// `a` is the albedo averaged over the three channels (positive: the model reflects too
    /// much). Infinite where the reference's albedo is 0 and the model's is not.
    pub fn errors<M: Bcsdf<f64> + ?Sized>(&self, model: &M) -> Vec<f64> {
        self.theta_o_deg
            .iter()
            .zip(&self.albedos)
            .map(|(&t, reference)| {
                let mean = |a: [f64; 3]| (a[0] + a[1] + a[2]) / 3.0;
                let model = mean(albedo(model, &self.rule, viewing_direction(t), 0.0));
                let reference = mean(*reference);
                if reference > 0.0 {
                    (model - reference) / reference
                } else if model == 0.0 {
                    0.0
                } else {
                    f64::INFINITY
                }
            })
            .collect()
    }
}

/// What a traced evaluation computes, by kind of operation.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct OpCounts {
    /// Additions, subtractions, multiplications and negations.
    pub add_mul: usize,
    /// Divisions.
    pub div: usize,
    /// Square roots.
    pub sqrt: usize,
    /// Transcendental calls: exp, log, sin, cos, atan2.
    pub transcendental: usize,
    /// min, max, abs, floor, comparisons and selects.
    pub select: usize,
    /// Texture samples ([`Graph::count_texture_samples`]: distinct fetches per texture of at
    /// most four channels).
    pub fetch: usize,
}

impl OpCounts {
    /// The counts of the graph's live nodes ([`Graph::live_nodes`]: what the outputs depend
    /// on, each computed value once).
    pub fn of(graph: &Graph) -> Self {
        let mut counts = OpCounts {
            fetch: graph.count_texture_samples(),
            ..OpCounts::default()
        };
        for node in graph.live_nodes() {
            match node {
                Node::Unary(Unary::Neg, _) => counts.add_mul += 1,
                Node::Unary(Unary::Sqrt, _) => counts.sqrt += 1,
                Node::Unary(Unary::Exp | Unary::Ln | Unary::Sin | Unary::Cos, _) => {
                    counts.transcendental += 1
                }
                Node::Unary(Unary::Abs | Unary::Floor, _) => counts.select += 1,
                Node::Binary(Binary::Add | Binary::Sub | Binary::Mul, _, _) => counts.add_mul += 1,
                Node::Binary(Binary::Div, _, _) => counts.div += 1,
                Node::Binary(Binary::Atan2, _, _) => counts.transcendental += 1,
                Node::Binary(Binary::Min | Binary::Max, _, _)
                | Node::Less(..)
                | Node::LessEqual(..)
                | Node::Select(..) => counts.select += 1,
                Node::Input(_)
                | Node::Global(_)
                | Node::Result { .. }
                | Node::Const(_)
                | Node::Named { .. }
                | Node::And(..)
                | Node::Or(..)
                | Node::Not(_)
                | Node::Fetch { .. } => {}
            }
        }
        counts
    }
}
