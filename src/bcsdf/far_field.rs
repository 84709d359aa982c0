//! The far-field hair BCSDF: the near-field model of [`ChiangHair`] averaged over the offset h,
//! for renderers that do not know where on the fibre's width light lands.
//!
//! `S(wi, wo) = sum_p M_p(theta_i; theta_o^(p)) N_p(phi)`, with
//! `N_p(phi) = 1/2 int_{-1}^{1} A_p(h) D(phi - Phi(p, h)) dh` (Marschner et al. 2003, eq. 8 with
//! roughness; d'Eon et al. 2011, eq. 12; Chiang et al. 2016, section 3.2).
//!
//! Two integrators for N_p:
//! - [`FarFieldRule`]: fixed nodes, written generically so it runs in f32, f64, SIMD and
//!   traces to shader code. The integral is taken over gamma = asin(h), where the integrand
//!   `A_p(sin gamma) D(...) cos(gamma) / 2` is smooth at the fibre's edges (in h it has
//!   square-root endpoints), with Gauss-Legendre nodes; the weights are renormalised to sum to 1,
//!   so the rule is exact for constant integrands and energy is conserved exactly. The nodes
//!   come in mirrored pairs h, -h, which share one path through the fibre: `A_p` is even in h
//!   and the exit angles odd ([`FarFieldRule::mirrored_pairs`]), so a pair costs one Fresnel
//!   term, one set of transmittances and two sets of logistics (`benches/models.rs` against
//!   the commit before: 44% less time for 64 nodes in `f32`, 30% in `wide`'s lanes).
//! - [`ReferenceFarField`] ([`ReferenceFarField::eval_with_error`]): adaptive, f64, with an error estimate; breakpoints at
//!   the offsets where phi = Phi(p, h) keep the narrow peaks of low roughness resolved, and
//!   breakpoints where phi - Phi(p, h) wraps through pi keep the integrand smooth within every
//!   panel (it has a kink there). Measured against the near field averaged over h by brute
//!   force (2^16 panels) to 1e-9 of the largest channel (tests/far_field.rs).
//!
//! [`crate::bcsdf::HostFarField`] evaluates the fixed-node rule one query at a time with its
//! mirrored pairs of nodes in the SIMD lanes of the host's widest instruction set
//! ([`OffsetNodes`]' spread form), 6 to 9 times faster than scalar `f32` at 32 and 64 nodes.
//!
//! The fast model [`ChiangFarField`] is defined by its rule: evaluation, the pdf and sampling use
//! the same nodes, so `value / pdf` is exactly 1 without absorption and the sampler's density is
//! exactly the returned pdf. Its distance from the exact far field is the rule's integration
//! error, measured against the reference (README).
//!
//! **Varying in shader code** ([`crate::bcsdf::VaryingInputs`], `chiang-far` with its fixed
//! rule): every input of the near field, `beta_m`, `beta_n`, `alpha`, `eta` and the absorption
//! (`sigma_a`, `color` or `eumelanin` and `pheomelanin`, the form it is given in). Baked:
//! `nodes`, the node count, which fixes the loop over the offsets and its constant nodes and
//! weights. `--reference` has no shader form: its adaptive quadrature refines to a tolerance
//! with a data-dependent number of evaluations.

use super::batch::BatchLanes;
use super::chiang::{chiang_uniforms_in, ChiangUniforms, HAIR_VARYING};
use super::chiang::{
    AzimuthalFactors, ChiangHair, LobeTerms, Offsets, OffsetsIn, Outgoing, PairAngles, CHIANG_LOBES,
};
use super::inputs::{FromInputs, Input, InputKind, InputValues, HAIR_INPUTS};
use super::model::{Bcsdf, Query};
use super::varying::{InputsIn, VaryingInputs};
use crate::azimuthal::{exit_angle, refracted_offset, LOBES_WITH_RESIDUAL};
use crate::error::ParamError;
use crate::geometry::V3;
use crate::params::HairParams;
use crate::quadrature::{adaptive, gauss_legendre};
use crate::real::{safe_asin, wrap_angle, Real, ShaderLoop, Shape};

/// Fixed quadrature nodes over the offset: (h_k, P_k) with P_k >= 0 summing to 1.
#[derive(Clone, Debug, PartialEq)]
pub struct FarFieldRule {
    nodes: Vec<(f64, f64)>,
}

/// Measured accuracy of [`FarFieldRule::gauss_legendre`]: `(beta_n, nodes, bound)` where the
/// bound is the largest error of each `N_p A_p` (p = 0, 1, 2, every channel) relative to its peak
/// over phi, against the reference integrator, over inclinations up to grazing, phi including 0
/// and +-pi, sigma_a = 0, 0.5 and 10 (tests/far_field.rs). Each bound is about twice the worst
/// error measured there (1.2e-3, 5.1e-2, 1.6e-2, 1.8e-5, 2.7e-6, 2.6e-4 and 1.3e-5). Low azimuthal roughness needs many
/// nodes because the integrand's peaks in h narrow with the logistic; at beta_n = 1 convergence
/// slows to second order because the wrapped logistic has a kink at +-pi from its centre.
pub const FAR_FIELD_ERROR_BOUNDS: &[(f64, usize, f64)] = &[
    (0.05, 512, 2.5e-3),
    (0.1, 128, 0.1),
    (0.3, 32, 3e-2),
    (0.3, 64, 4e-5),
    (0.5, 32, 6e-6),
    (1.0, 32, 5e-4),
    (1.0, 128, 3e-5),
];

/// Largest node count of a [`FarFieldRule`].
pub const MAX_FAR_FIELD_NODES: usize = 512;

impl FarFieldRule {
    /// `n` Gauss-Legendre nodes in gamma = asin(h) on [-pi/2, pi/2], weights `w_k cos(gamma_k) / 2`
    /// renormalised to sum to 1. The rule is symmetric to the last bit: the nodes gamma_k > 0
    /// and their mirror images -gamma_k with the same weights, and for odd `n` the node 0.
    ///
    /// # Errors
    /// `n` outside 1..=512.
    pub fn gauss_legendre(n: usize) -> Result<Self, ParamError> {
        ParamError::check(
            "nodes",
            n as f64,
            "the node count must be in 1..=512",
            |v| (1.0..=MAX_FAR_FIELD_NODES as f64).contains(&v),
        )?;
        let half_pi = core::f64::consts::FRAC_PI_2;
        let rule = gauss_legendre(n);
        // gauss_legendre lists the nodes from the largest: the first n / 2 are positive, and
        // the middle one of an odd rule is 0 up to rounding.
        let weight = |x: f64, w: f64| half_pi * w * (half_pi * x).cos() * 0.5;
        let positive: Vec<(f64, f64)> = rule[..n / 2]
            .iter()
            .map(|&(x, w)| ((half_pi * x).sin(), weight(x, w)))
            .collect();
        let centre = (n % 2 == 1).then(|| (0.0, weight(0.0, rule[n / 2].1)));
        let total =
            2.0 * positive.iter().map(|&(_, w)| w).sum::<f64>() + centre.map_or(0.0, |(_, w)| w);
        let mirrored = positive.iter().rev().map(|&(h, w)| (-h, w));
        Ok(FarFieldRule {
            nodes: positive
                .iter()
                .copied()
                .chain(centre)
                .chain(mirrored)
                .map(|(h, w)| (h, w / total))
                .collect(),
        })
    }

    /// The (h_k, P_k) pairs, from h = 1 down to h = -1.
    pub fn nodes(&self) -> &[(f64, f64)] {
        &self.nodes
    }

    /// The nodes h_k >= 0 with their weights P_k, each standing for itself and its mirror
    /// image -h_k; the node 0 of an odd rule with half its weight. Counted twice, once per
    /// member of the pair, the weights sum to 1. The far field evaluates a pair with one path
    /// through the fibre: `A_p` is even in h and the exit angle `Phi(p, h)` odd (Marschner et
    /// al. 2003, eq. 3; [`crate::azimuthal::exit_angle`]).
    pub fn mirrored_pairs(&self) -> Vec<(f64, f64)> {
        let n = self.nodes.len();
        let centre = self.nodes[n / 2];
        self.nodes[..n / 2]
            .iter()
            .copied()
            .chain((n % 2 == 1).then_some((centre.0, 0.5 * centre.1)))
            .collect()
    }
}

/// The offsets of the far field: fixed nodes (h_k, P_k) of a [`FarFieldRule`] in the working
/// precision, over which the azimuthal factors are averaged ([`Offsets`]).
#[derive(Clone, Debug, PartialEq)]
pub struct OffsetNodes<R> {
    /// [h_k, P_k], the weights summing to 1, from which sampling chooses a node.
    nodes: Vec<[R; 2]>,
    /// [h_k, P_k] of [`FarFieldRule::mirrored_pairs`], as the loop of evaluation reads them:
    /// one path through the fibre for h_k and -h_k ([`ChiangHair::azimuthal_mirrored_at`]).
    pairs: Vec<[R; 2]>,
}

/// `[h, P]` of each `(h, P)` in `R`.
fn rounded<R: Real>(nodes: impl Iterator<Item = (f64, f64)>) -> Vec<[R; 2]> {
    nodes.map(|(h, p)| [R::c(h), R::c(p)]).collect()
}

impl<R: Real> OffsetNodes<R> {
    /// The nodes of `rule` rounded to `R`.
    pub fn new(rule: &FarFieldRule) -> Self {
        OffsetNodes {
            nodes: rounded(rule.nodes.iter().copied()),
            pairs: rounded(rule.mirrored_pairs().into_iter()),
        }
    }
}

impl<L: BatchLanes> OffsetNodes<L> {
    /// The mirrored pairs of `nodes` spread over the lanes, for one query at a time in every
    /// lane ([`crate::bcsdf::HostFarField`]): lane k of the j-th element holds pair
    /// `j * L::LANES + k`, the lanes past the last pair `h = 0` with weight 0. The far field's
    /// node sum then leaves in lane k the part of the pairs it holds, and the sum over the
    /// lanes is the far field. The nodes themselves, which sampling chooses from, are in
    /// every lane as in [`OffsetNodes::new`].
    pub(crate) fn spread_over_lanes(nodes: &OffsetNodes<f64>) -> Self {
        let lane = |element: usize, k: usize, field: usize| {
            nodes
                .pairs
                .get(element * L::LANES + k)
                .map_or(0.0, |pair| pair[field] as f32)
        };
        let pairs = (0..nodes.pairs.len().div_ceil(L::LANES))
            .map(|j| [0, 1].map(|field| L::from_fn(|k| lane(j, k, field))))
            .collect();
        OffsetNodes {
            nodes: nodes.cast::<L>().nodes,
            pairs,
        }
    }
}

/// The state of the far field's loop over nodes with the lobe-choice weights of sampling:
/// `N_p A_p` per lobe and channel, then `w_p N_p` per lobe.
const NODE_SUMS: [(&str, Shape); 8] = [
    ("r", Shape::Vec3),
    ("tt", Shape::Vec3),
    ("trt", Shape::Vec3),
    ("residual", Shape::Vec3),
    ("w_r", Shape::Scalar),
    ("w_tt", Shape::Scalar),
    ("w_trt", Shape::Scalar),
    ("w_residual", Shape::Scalar),
];

/// The loop of the fixed-node far field over its mirrored pairs of nodes (h_k, P_k):
/// `N_p A_p += P_k A_p(h_k) (N_p(h_k) + N_p(-h_k))`.
const NODES: ShaderLoop = ShaderLoop {
    name: "far_field_node_pair",
    array: "FAR_FIELD_OFFSET_PAIRS",
    fields: &["h", "weight"],
    state: NODE_SUMS.split_at(4).0,
    source: "hairmath::bcsdf::far_field::OffsetNodes::azimuthal",
    equation: "Chiang et al. 2016, eq. 8 (N_p averaged over h), by Gauss-Legendre quadrature, \
        the nodes h and -h sharing A_p",
};

/// [`NODES`] also accumulating the lobe-choice weights `w_p N_p` of sampling.
const NODES_WITH_PDF: ShaderLoop = ShaderLoop {
    name: "far_field_node_pair_with_pdf",
    state: &NODE_SUMS,
    ..NODES
};

/// `sums[k] += weight * values[k]`.
#[inline(always)]
pub(super) fn add_weighted<R: Real>(sums: &mut [R], weight: R, values: &[R]) {
    for (s, &v) in sums.iter_mut().zip(values) {
        *s += weight * v;
    }
}

/// The first twelve sums as `[lobe][channel]`.
#[inline(always)]
fn per_lobe<R: Real>(sums: &[R]) -> [[R; 3]; LOBES_WITH_RESIDUAL] {
    core::array::from_fn(|p| core::array::from_fn(|c| sums[3 * p + c]))
}

impl OffsetsIn for OffsetNodes<f64> {
    type In<S: Real> = OffsetNodes<S>;
    fn cast<S: Real>(&self) -> OffsetNodes<S> {
        let cast = |nodes: &[[f64; 2]]| rounded(nodes.iter().map(|&[h, p]| (h, p)));
        OffsetNodes {
            nodes: cast(&self.nodes),
            pairs: cast(&self.pairs),
        }
    }
}

impl<R: Real> OffsetNodes<R> {
    /// `(N_p A_p per channel, w_p N_p)` averaged over the nodes, a mirrored pair of them at a
    /// time: `N_p` here includes the attenuation, `1/2 int A_p(h) D(phi - Phi(p, h)) dh`;
    /// `at.h` is ignored.
    #[inline(always)]
    pub(crate) fn averaged<O, const WITH_PDF: bool>(
        &self,
        hair: &ChiangHair<R, O>,
        at: Outgoing<R>,
    ) -> AzimuthalFactors<R> {
        // The same for every node: outside the loop, also in shader code.
        let refraction = hair.refraction(at.sin_o, at.cos_o);
        if WITH_PDF {
            let sums = R::fold(
                &NODES_WITH_PDF,
                &self.pairs,
                [R::c(0.0); 16],
                #[inline(always)]
                |mut s, [h, w]| {
                    let (a, wn) =
                        hair.azimuthal_mirrored_at::<WITH_PDF>(&refraction, Outgoing { h, ..at });
                    add_weighted(&mut s[..12], w, a.as_flattened());
                    add_weighted(&mut s[12..], w, &wn);
                    s
                },
            );
            (
                per_lobe(&sums),
                crate::real::array_from_fn(
                    #[inline(always)]
                    |p| sums[12 + p],
                ),
            )
        } else {
            let sums = R::fold(
                &NODES,
                &self.pairs,
                [R::c(0.0); 12],
                #[inline(always)]
                |mut s, [h, w]| {
                    let (a, _) =
                        hair.azimuthal_mirrored_at::<WITH_PDF>(&refraction, Outgoing { h, ..at });
                    add_weighted(&mut s, w, a.as_flattened());
                    s
                },
            );
            (per_lobe(&sums), [R::c(0.0); LOBES_WITH_RESIDUAL])
        }
    }
}

impl<R: Real> Offsets<R> for OffsetNodes<R> {
    const NEAR_FIELD: bool = false;

    /// `weight_p = M_p`, with the averages of `A_p N_p` and `w_p N_p` over the nodes
    /// (`OffsetNodes::averaged`) as the channels and the lobe choice.
    #[inline(always)]
    fn lobe_terms<O, const WITH_PDF: bool>(
        &self,
        hair: &ChiangHair<R, O>,
        at: Outgoing<R>,
        longitudinal: impl FnOnce() -> [R; LOBES_WITH_RESIDUAL],
    ) -> LobeTerms<R> {
        let (channels, choice) = self.averaged::<O, WITH_PDF>(hair, at);
        LobeTerms {
            weight: longitudinal(),
            channels,
            choice,
        }
    }

    /// Node k is chosen with probability P_k: when P_0 + ... + P_{k-1} <= u < P_0 + ... + P_k
    /// (by selects, so it traces).
    fn sample_offset(&self, _h: R, u: R) -> R {
        let [mut h, mut lower] = self.nodes[0];
        for &[node_h, weight] in &self.nodes[1..] {
            h = R::select(lower.le(u), node_h, h);
            lower += weight;
        }
        h
    }
}

/// The far-field Chiang model with a fixed-node integrator over h, in the working precision
/// `R`: the near-field model with its azimuthal factors averaged over the rule's offsets.
pub type ChiangFarField<R> = ChiangHair<R, OffsetNodes<R>>;

impl<R: Real> ChiangHair<R, OffsetNodes<R>> {
    /// The far field of the hair `params` integrated with `rule`: the uniforms of
    /// [`ChiangHair::new`] and the rule's nodes, rounded to `R`.
    ///
    /// # Examples
    ///
    /// ```
    /// use hairmath::bcsdf::{Bcsdf, ChiangFarField, FarFieldRule, Query, ReferenceFarField};
    /// use hairmath::geometry::V3;
    /// use hairmath::params::HairParams;
    ///
    /// let hair = HairParams::default();
    /// // 64 nodes: within 4e-5 of each lobe's peak at beta_n = 0.3 (FAR_FIELD_ERROR_BOUNDS).
    /// let far = ChiangFarField::<f64>::with_rule(&hair, &FarFieldRule::gauss_legendre(64)?);
    /// let query = Query::far(V3::new(-0.6, 0.0, 0.8), V3::new(0.6, 0.8, 0.0));
    /// // Against the adaptive reference (relative tolerance 1e-9).
    /// let reference = ReferenceFarField::new(&hair, 1e-9)?;
    /// let (s, r) = (far.eval(&query), reference.eval(&query));
    /// assert!((s[0] - r[0]).abs() < 1e-3 * r[0], "{s:?} against {r:?}");
    /// # Ok::<(), hairmath::ParamError>(())
    /// ```
    pub fn with_rule(params: &HairParams, rule: &FarFieldRule) -> Self {
        let near = ChiangHair::<R>::new(params);
        ChiangHair::with_offsets(*near.uniforms(), OffsetNodes::new(rule))
    }

    /// The near-field model this averages.
    pub fn near_field(&self) -> ChiangHair<R> {
        ChiangHair::from_uniforms(*self.uniforms())
    }

    /// `(N_p A_p per channel, w_p N_p)` averaged over the rule's offsets, for the relative
    /// azimuth `phi_i_minus_o = phi_i - phi_o` of the lobes (pbrt's and Chiang's convention:
    /// the **negative** of [`crate::geometry::FibreAngles::phi`]) and the inclination of wo.
    /// `N_p` here includes the attenuation: `1/2 int A_p(h) D(phi - Phi(p, h)) dh`.
    pub fn azimuthal(&self, sin_o: R, cos_o: R, phi_i_minus_o: R) -> AzimuthalFactors<R> {
        let at = Outgoing {
            sin_o,
            cos_o,
            phi: phi_i_minus_o,
            h: R::c(0.0),
        };
        self.offsets().averaged::<_, true>(self, at)
    }
}

/// The far field integrated over h by the adaptive reference integrator
/// ([`ChiangHair::far_field_azimuthal_reference`] per azimuth) to a relative tolerance: an `f64`-only model (it
/// solves for the integrand's peaks and refines adaptively, so it neither traces nor
/// vectorises).
#[derive(Clone, Debug, PartialEq)]
pub struct ReferenceFarField {
    hair: ChiangHair<f64>,
    rel_tol: f64,
}

impl ReferenceFarField {
    /// The reference far field of `params` to relative tolerance `rel_tol`.
    ///
    /// # Errors
    /// `rel_tol` outside [1e-13, 1e-2].
    pub fn new(params: &HairParams, rel_tol: f64) -> Result<Self, ParamError> {
        let rel_tol = ParamError::check(
            "rel_tol",
            rel_tol,
            "the relative tolerance must be in [1e-13, 1e-2]",
            |v| (1e-13..=1e-2).contains(&v),
        )?;
        Ok(ReferenceFarField {
            hair: ChiangHair::new(params),
            rel_tol,
        })
    }

    /// The near-field model it averages.
    pub fn near_field(&self) -> &ChiangHair<f64> {
        &self.hair
    }

    /// S at `query` per lobe and in total, with the integrator's error estimate
    /// (the adaptive integral of [`ChiangHair::far_field_azimuthal_reference`] at this
    /// tolerance); [`Bcsdf::eval`] gives the
    /// total alone.
    pub fn eval_with_error(&self, query: &Query<f64>) -> FarFieldReference {
        self.hair
            .far_field_reference(query.wi, query.wo, self.rel_tol)
    }
}

impl Bcsdf<f64> for ReferenceFarField {
    fn lobe_names(&self) -> &'static [&'static str] {
        &CHIANG_LOBES
    }

    fn eval_lobes(&self, query: &Query<f64>) -> Vec<[f64; 3]> {
        self.eval_with_error(query).lobes.to_vec()
    }
}

/// Default node count of the far field built from named inputs.
pub const DEFAULT_FAR_FIELD_NODES: usize = 64;

/// Relative tolerance of the reference far field built from named inputs.
pub const REFERENCE_REL_TOL: f64 = 1e-9;

/// The far field as the command line builds it: the fixed rule of `nodes` nodes, or the
/// adaptive reference integrator (`reference`).
#[derive(Clone, Debug, PartialEq)]
pub enum FarField {
    /// [`ChiangFarField`] with a Gauss-Legendre rule.
    Rule(ChiangFarField<f64>),
    /// [`ReferenceFarField`] to [`REFERENCE_REL_TOL`].
    Reference(ReferenceFarField),
}

impl FarField {
    fn model(&self) -> &dyn Bcsdf<f64> {
        match self {
            FarField::Rule(m) => m,
            FarField::Reference(m) => m,
        }
    }
}

impl Bcsdf<f64> for FarField {
    fn lobe_names(&self) -> &'static [&'static str] {
        self.model().lobe_names()
    }
    fn eval(&self, query: &Query<f64>) -> [f64; 3] {
        self.model().eval(query)
    }
    fn eval_lobes(&self, query: &Query<f64>) -> Vec<[f64; 3]> {
        self.model().eval_lobes(query)
    }
}

/// The far-field integrator inputs: a node count, or the reference.
const FAR_FIELD_INPUTS: [Input; 7] = [
    HAIR_INPUTS[0],
    HAIR_INPUTS[1],
    HAIR_INPUTS[2],
    HAIR_INPUTS[3],
    HAIR_INPUTS[4],
    Input {
        name: "nodes",
        kind: InputKind::Count,
        help: "node count (1..=512) of the fixed Gauss-Legendre rule over h",
        default: Some(DEFAULT_FAR_FIELD_NODES as f64),
        conflicts_with: &["reference"],
    },
    Input {
        name: "reference",
        kind: InputKind::Switch,
        help: "integrate over h with the adaptive reference integrator (relative tolerance \
               1e-9, about 0.2 ms per evaluation) instead of the fixed rule",
        default: None,
        conflicts_with: &["nodes"],
    },
];

impl FromInputs for FarField {
    const NAME: &'static str = "chiang-far";
    const SUMMARY: &'static str = "the far field of Chiang et al. 2016: S(wi, wo) averaged over h \
        uniform in [-1, 1], with a fixed Gauss-Legendre rule over h or the adaptive reference";
    const INPUTS: &'static [Input] = &FAR_FIELD_INPUTS;

    fn from_inputs(values: &InputValues) -> Result<Self, ParamError> {
        let params = HairParams::from_inputs(values)?;
        if values.switch("reference")? {
            return Ok(FarField::Reference(ReferenceFarField::new(
                &params,
                REFERENCE_REL_TOL,
            )?));
        }
        let rule = FarFieldRule::gauss_legendre(values.count("nodes")?)?;
        let uniforms = ChiangFarField::uniforms_in(&InputsIn::constant(values));
        Ok(FarField::Rule(ChiangHair::with_offsets(
            uniforms,
            OffsetNodes::new(&rule),
        )))
    }
}

/// Why `chiang-far --reference` has no shader form.
pub const REFERENCE_NO_SHADER_FORM: &str = "the reference integrator's adaptive quadrature \
    refines to a tolerance with a data-dependent number of evaluations, which shader code \
    cannot do (the fixed rule, --nodes, traces)";

impl VaryingInputs for ChiangFarField<f64> {
    const NAME: &'static str = <FarField as FromInputs>::NAME;
    const INPUTS: &'static [Input] = &FAR_FIELD_INPUTS;
    const VARYING: &'static [&'static str] = &HAIR_VARYING;
    const BAKED: &'static [(&'static str, &'static str)] = &[
        (
            "nodes",
            "the node count fixes the shader's loop over the offsets h and its constant nodes \
             and weights",
        ),
        ("reference", REFERENCE_NO_SHADER_FORM),
    ];

    fn uniforms_in<R: Real>(inputs: &InputsIn<R>) -> ChiangUniforms<R> {
        chiang_uniforms_in(inputs)
    }
}

/// The reference far field at one direction pair: per-lobe `M_p N_p` per channel, the pdf's
/// counterpart, and the integrator's error estimate (absolute, on the largest `N_p` component).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FarFieldReference {
    /// `M_p N_p` per lobe and channel.
    pub lobes: [[f64; 3]; LOBES_WITH_RESIDUAL],
    /// `S` per channel (the sum of the lobes).
    pub value: [f64; 3],
    /// `N_p A_p` per lobe and channel, without `M_p`.
    pub azimuthal: [[f64; 3]; LOBES_WITH_RESIDUAL],
    /// Error estimate of the `N_p` integrals (absolute).
    pub error: f64,
}

impl ChiangHair<f64> {
    /// The offsets h in (-1, 1) where `phi - Phi(p, h)` is 0 or pi (mod 2 pi) for p = 0, 1, 2:
    /// the peaks of the far-field integrand, and its kinks, where the trimmed logistic's
    /// argument wraps from pi to -pi (its slope changes sign there: with a wide lobe, beta_n
    /// near 1, an adaptive rule that straddles a kink can settle on a wrong value with a small
    /// error estimate). Found by scanning gamma = asin h on 512 intervals and bisecting the sign
    /// changes of the wrapped difference, which change sign at both. Returned as gamma.
    fn peak_offsets(&self, sin_o: f64, cos_o: f64, phi: f64) -> Vec<f64> {
        let eta = self.eta();
        let half_pi = core::f64::consts::FRAC_PI_2;
        let residual = |p: usize, gamma: f64| {
            let h = gamma.sin();
            let gamma_t = safe_asin(refracted_offset(h, eta, sin_o, cos_o));
            wrap_angle(phi - exit_angle(p as f64, gamma, gamma_t))
        };
        let mut roots = Vec::new();
        let n = 512;
        let step = 2.0 * half_pi / n as f64;
        for p in 0..3 {
            for k in 0..n {
                let mut lo = -half_pi + k as f64 * step;
                let mut hi = lo + step;
                let (flo, fhi) = (residual(p, lo), residual(p, hi));
                if flo * fhi > 0.0 {
                    continue;
                }
                for _ in 0..60 {
                    let mid = 0.5 * (lo + hi);
                    if residual(p, mid) * flo > 0.0 {
                        lo = mid;
                    } else {
                        hi = mid;
                    }
                }
                roots.push(0.5 * (lo + hi));
            }
        }
        roots
    }

    /// The far-field `N_p A_p` (per lobe and channel) for the relative azimuth of the lobes
    /// `phi_i_minus_o = phi_i - phi_o` (the negative of
    /// [`crate::geometry::FibreAngles::phi`]) and the inclination of wo, by adaptive integration over gamma = asin h with breakpoints at
    /// the peaks, to relative tolerance `rel_tol` of the largest component. Returns the values and
    /// the error estimate.
    pub fn far_field_azimuthal_reference(
        &self,
        sin_o: f64,
        cos_o: f64,
        phi_i_minus_o: f64,
        rel_tol: f64,
    ) -> ([[f64; 3]; LOBES_WITH_RESIDUAL], f64) {
        let phi = phi_i_minus_o;
        let breaks = self.peak_offsets(sin_o, cos_o, phi);
        let half_pi = core::f64::consts::FRAC_PI_2;
        let (flat, error) = adaptive(
            |gamma| {
                let h = gamma.sin();
                let (an, _) = self.azimuthal_at::<false>(Outgoing {
                    sin_o,
                    cos_o,
                    phi,
                    h,
                });
                let weight = 0.5 * gamma.cos();
                let mut out = [0.0; 3 * LOBES_WITH_RESIDUAL];
                for p in 0..LOBES_WITH_RESIDUAL {
                    for c in 0..3 {
                        out[3 * p + c] = weight * an[p][c];
                    }
                }
                out
            },
            -half_pi,
            half_pi,
            &breaks,
            rel_tol,
            1e-300,
        );
        (
            core::array::from_fn(|p| [flat[3 * p], flat[3 * p + 1], flat[3 * p + 2]]),
            error,
        )
    }

    /// The far-field S at (wi, wo) with the reference integrator (see
    /// [`ChiangHair::far_field_azimuthal_reference`]); public as
    /// [`ReferenceFarField::eval_with_error`], the far field's own type.
    pub(crate) fn far_field_reference(
        &self,
        wi: V3<f64>,
        wo: V3<f64>,
        rel_tol: f64,
    ) -> FarFieldReference {
        let angles = PairAngles::of(&Query::far(wi, wo));
        let (azimuthal, error) = self.far_field_azimuthal_reference(
            angles.out.sin_o,
            angles.out.cos_o,
            angles.out.phi,
            rel_tol,
        );
        let terms = LobeTerms {
            weight: self.longitudinal(&angles),
            channels: azimuthal,
            choice: [0.0; LOBES_WITH_RESIDUAL],
        };
        let per_lobe = terms.per_lobe();
        FarFieldReference {
            lobes: core::array::from_fn(|p| per_lobe[p]),
            value: terms.value(),
            azimuthal,
            error,
        }
    }
}
