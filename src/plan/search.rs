//! The planner: the cheapest [`Composition`] whose error against Chiang et al. 2016's far
//! field stays within a scene's budget over the scene's hair.
//!
//! # What is measured
//!
//! - **The scene's hair** ([`scene_points`]): every corner of the box of the parameters the
//!   scene gives as ranges (or varying), and interior points of a Kronecker sequence in it; a
//!   scene of fixed parameters is one point.
//! - **Error** E at each point and for each of the scene's lights ([`LightMeasure`]), against
//!   the far field with [`PlanSettings::reference_nodes`] Gauss-Legendre nodes: for
//!   directional light the models issue's `E = sqrt(sum (S - S_ref)^2 / sum S_ref^2)` over
//!   direction pairs ([`crate::diagnostics::DirectionPairs::kronecker`], weighted by
//!   `cos theta_i cos theta_o`); for an SH environment of bands `l <= L` the relative error of
//!   the outgoing radiance over the environments of those bands
//!   ([`crate::diagnostics::ShEnvironment`]). A plan's error is the worst over the points and
//!   the lights.
//! - **Cost** ([`OpWeights`]): the traced shader's operation counts
//!   ([`crate::diagnostics::OpCounts`]) weighted per kind, with the scene's non-fixed
//!   parameters as shader arguments (their uniforms computed in the shader).
//!
//! # The search
//!
//! Every lobe option (the lobe's factors, or dropped) is evaluated alone at every point under
//! every light, in `f64`; its difference from the reference's lobe is a vector (both measures
//! are linear in the model), and the error of any combination of options is exactly the norm
//! of the sum of their vectors, which the planner computes for every combination from the
//! vectors' inner products (a Gram matrix per point and light):
//! no combination's error is assumed from its parts' errors. Costs are not additive (lobes
//! share the angles and the far field's loop), so the combinations that meet the budget are
//! ordered by an additive estimate (each option's cost alone, the far field's loop counted
//! once) and the [`PlanSettings::traced_candidates`] first are traced; the cheapest of them by
//! traced cost is the plan, and its error is measured once more as a whole
//! ([`LightMeasure::relative_error`] of the composed model itself, [`worst_error`]).
//!
//! # `cost = "llvmpipe"`
//!
//! The time of a shader on a device cannot be measured for the million or so combinations, so
//! the search above ranks them by weighted operations as for `cost = "ops"`, and its
//! [`PlanSettings::device_candidates`] cheapest by traced cost whose error measured as a whole
//! is within the budget (at most [`PlanSettings::traced_candidates`] of them) are each emitted
//! as the WGSL compute module `hairmath plan --out` writes ([`plan_shader`], the scene's
//! non-fixed parameters as arguments) and timed on Mesa's llvmpipe
//! ([`crate::device::llvmpipe`]): [`PlanSettings::device_rows`] rows of direction pairs (a
//! Kronecker set) with the arguments of the scene's hairs in turn, the median of
//! [`PlanSettings::device_repetitions`] dispatches after a warm-up
//! ([`crate::device::Device::time_per_eval`]). The fastest measured is the plan, and its cost
//! is its time in nanoseconds per evaluation ([`Plan::timing`] keeps every candidate timed).
//! This is the fastest *measured* among the cheapest by operations that meet the budget, not
//! an exhaustive search over times; the times are llvmpipe's on the machine that planned (a
//! CPU rasteriser, sharing the cores with whatever else runs), and differ from run to run by
//! its noise, so candidates within that noise of each other may swap places.

use super::measure::LightMeasure;
use super::scene::{CostMeasure, HairKey, Scene, SceneHair};
use crate::absorption::Absorption;
use crate::bcsdf::{
    AbsorptionInput, ChiangFarField, FarFieldRule, InputValue, InputValues, ShaderInputError,
    ShaderInputs,
};
use crate::device::{llvmpipe, textures_of, Device, DeviceError};
use crate::diagnostics::{DirectionPairs, EnvironmentRule, OpCounts};
use crate::error::ParamError;
use crate::models::{
    Attenuation, Azimuthal, ComposedHair, ComposedLobe, Composition, CompositionError, Constants,
    Distribution, LobeFactors, LobeTableSize, Longitudinal, MarschnerTableSize,
};
use crate::params::{HairParams, HairValues};
use crate::quadrature::kronecker;
use crate::real::Graph;
use crate::shader::{graph_shader, ModelShader, ShaderError};
use rayon::prelude::*;

/// How much each kind of traced operation costs, in units of an addition: the planner's
/// `cost = "ops"`. The defaults follow the relative throughput of current GPUs' shader cores
/// (additions, multiplications and selects at full rate; divisions and square roots as a
/// reciprocal or reciprocal square root at quarter rate plus a multiply; exp, log, sin, cos
/// and atan2 at quarter rate with their range reduction; a texture fetch of four channels
/// with its address arithmetic): a convention, not a measurement of a device.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct OpWeights {
    /// An addition, subtraction, multiplication or negation.
    pub add_mul: f64,
    /// A division.
    pub div: f64,
    /// A square root.
    pub sqrt: f64,
    /// exp, log, sin, cos or atan2.
    pub transcendental: f64,
    /// min, max, abs, floor, a comparison or a select.
    pub select: f64,
    /// A texture sample.
    pub fetch: f64,
}

impl OpWeights {
    /// The defaults (type documentation): 1, 4, 4, 8, 1, 16.
    pub const DEFAULT: OpWeights = OpWeights {
        add_mul: 1.0,
        div: 4.0,
        sqrt: 4.0,
        transcendental: 8.0,
        select: 1.0,
        fetch: 16.0,
    };

    /// The weighted sum of `counts`.
    pub fn cost(&self, counts: &OpCounts) -> f64 {
        self.add_mul * counts.add_mul as f64
            + self.div * counts.div as f64
            + self.sqrt * counts.sqrt as f64
            + self.transcendental * counts.transcendental as f64
            + self.select * counts.select as f64
            + self.fetch * counts.fetch as f64
    }
}

/// The planner's work: how many pairs, points and candidates.
#[derive(Clone, Debug, PartialEq)]
pub struct PlanSettings {
    /// Direction pairs per point ([`DirectionPairs::kronecker`]).
    pub pairs: usize,
    /// Gauss-Legendre nodes of the reference far field.
    pub reference_nodes: usize,
    /// Interior points of the scene's box besides its corners (0 for corners only).
    pub interior_points: usize,
    /// The node counts a composition's far field may take.
    pub far_field_nodes: Vec<usize>,
    /// Combinations meeting the budget that are traced for their exact cost.
    pub traced_candidates: usize,
    /// The cost of each kind of operation.
    pub weights: OpWeights,
    /// The quadrature of an SH environment's error ([`crate::diagnostics::ShEnvironment`]).
    pub environment: EnvironmentRule,
    /// For `cost = "llvmpipe"`: how many of the cheapest compositions by traced cost that meet
    /// the budget are timed on the device (the module documentation).
    pub device_candidates: usize,
    /// For `cost = "llvmpipe"`: the rows of one timed dispatch.
    pub device_rows: usize,
    /// For `cost = "llvmpipe"`: the timed dispatches of each candidate, whose median is its
    /// time.
    pub device_repetitions: usize,
}

impl Default for PlanSettings {
    /// 2^12 pairs, a 64-node reference, 4 interior points, far fields of 4 to 64 nodes, 64
    /// traced candidates, [`OpWeights::DEFAULT`], [`EnvironmentRule::default`]; for
    /// `cost = "llvmpipe"` 8 candidates timed, each over 2^16 rows, the median of 5
    /// dispatches.
    fn default() -> Self {
        PlanSettings {
            pairs: 1 << 12,
            reference_nodes: 64,
            interior_points: 4,
            far_field_nodes: vec![4, 8, 16, 32, 64],
            traced_candidates: 64,
            weights: OpWeights::DEFAULT,
            environment: EnvironmentRule::default(),
            device_candidates: 8,
            device_rows: 1 << 16,
            device_repetitions: 5,
        }
    }
}

impl PlanSettings {
    /// Fewer pairs (2^9), no interior points, far fields of 4 and 16 nodes, 16 traced
    /// candidates and 6 timed: for tests and `hairmath report --quick` (the errors become
    /// rough).
    pub fn quick() -> Self {
        PlanSettings {
            pairs: 1 << 9,
            interior_points: 0,
            far_field_nodes: vec![4, 16],
            traced_candidates: 16,
            device_candidates: 6,
            ..PlanSettings::default()
        }
    }
}

/// A scene the planner cannot plan, or a budget no composition meets.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum PlanError {
    /// No composition meets the budget.
    #[error(
        "no composition meets the budget {budget}: the most accurate one measured has E = \
         {best_error:.4} ({best}); raise the budget"
    )]
    Infeasible {
        /// The scene's budget.
        budget: f64,
        /// The lowest error of any combination.
        best_error: f64,
        /// That combination, described.
        best: String,
    },
    /// Parameters outside their domains at a point of the scene.
    #[error(transparent)]
    Param(#[from] ParamError),
    /// A composition whose factors do not fit together.
    #[error(transparent)]
    Composition(#[from] CompositionError),
    /// A shader argument the composed model does not take.
    #[error(transparent)]
    Argument(#[from] ShaderInputError),
    /// `cost = "llvmpipe"` on a machine without Mesa's llvmpipe.
    #[error(
        "cost = \"llvmpipe\" times the shaders on Mesa's llvmpipe, and no llvmpipe Vulkan \
         device was found ({0}); Debian's mesa-vulkan-drivers provides it (apt-get install \
         mesa-vulkan-drivers)"
    )]
    NoDevice(DeviceError),
    /// A candidate's shader that llvmpipe could not run.
    #[error("timing a candidate on llvmpipe: {0}")]
    Device(#[from] DeviceError),
    /// A candidate whose shader could not be emitted.
    #[error(transparent)]
    Shader(#[from] ShaderError),
}

/// One hair of the scene: the values of its parameters (as the scene file gives them,
/// `alpha_deg` in degrees) and the physical parameters.
#[derive(Clone, Debug, PartialEq)]
pub struct ScenePoint {
    /// `(key, value)` for each parameter, in the order of the file.
    pub values: Vec<(HairKey, f64)>,
    /// The hair.
    pub params: HairParams,
}

impl ScenePoint {
    /// The point's hair from the values of every key.
    fn new(values: Vec<(HairKey, f64)>) -> Result<Self, ParamError> {
        let get = |key: HairKey| values.iter().find(|(k, _)| *k == key).map_or(0.0, |v| v.1);
        let sigma_a = Absorption::from_melanin(get(HairKey::Eumelanin), get(HairKey::Pheomelanin))?;
        let params = HairParams::try_from(HairValues {
            beta_m: get(HairKey::BetaM),
            beta_n: get(HairKey::BetaN),
            alpha: get(HairKey::AlphaDeg).to_radians(),
            eta: get(HairKey::Eta),
            sigma_a: sigma_a.rgb(),
        })?;
        Ok(ScenePoint { values, params })
    }

    /// The values of [`crate::bcsdf::HAIR_INPUTS`] for this hair, the absorption as melanin
    /// (so that its concentrations can be shader arguments).
    pub fn inputs(&self) -> InputValues {
        let get = |key: HairKey| {
            self.values
                .iter()
                .find(|(k, _)| *k == key)
                .map_or(0.0, |v| v.1)
        };
        let mut values = self.params.to_inputs();
        let melanin = AbsorptionInput::Melanin {
            eumelanin: get(HairKey::Eumelanin),
            pheomelanin: get(HairKey::Pheomelanin),
        };
        values.set("sigma_a", InputValue::Absorption(melanin));
        values
    }
}

/// The input of the composed model's shader a scene parameter becomes when it is not fixed:
/// `eumelanin`, `pheomelanin`, `beta_m`, `beta_n`, `alpha` (radians) or `eta`.
pub fn shader_argument(key: HairKey) -> &'static str {
    match key {
        HairKey::Eumelanin => "eumelanin",
        HairKey::Pheomelanin => "pheomelanin",
        HairKey::BetaM => "beta_m",
        HairKey::BetaN => "beta_n",
        HairKey::AlphaDeg => "alpha",
        HairKey::Eta => "eta",
    }
}

/// The hairs the planner measures a scene at (module documentation): the corners of the box
/// of the non-fixed parameters, then `interior` points of the 3-dimensional... d-dimensional
/// [`kronecker`] sequence inside it (none when every parameter is fixed: one point).
///
/// # Errors
/// [`ParamError`] if a point's parameters are outside their domains.
pub fn scene_points(hair: &SceneHair, interior: usize) -> Result<Vec<ScenePoint>, ParamError> {
    let ranged = hair.non_fixed();
    let at = |fractions: &[f64]| -> Vec<(HairKey, f64)> {
        hair.params()
            .iter()
            .map(|&(key, range)| {
                let value = match ranged.iter().position(|k| *k == key) {
                    Some(i) => range.min() + fractions[i] * (range.max() - range.min()),
                    None => range.min(),
                };
                (key, value)
            })
            .collect()
    };
    let mut points = Vec::new();
    for corner in 0..(1usize << ranged.len()) {
        let fractions: Vec<f64> = (0..ranged.len())
            .map(|i| ((corner >> i) & 1) as f64)
            .collect();
        points.push(ScenePoint::new(at(&fractions))?);
    }
    if !ranged.is_empty() {
        let mut u = vec![0.0; ranged.len()];
        for k in 0..interior {
            kronecker(k, ranged.len(), &mut u);
            points.push(ScenePoint::new(at(&u))?);
        }
    }
    Ok(points)
}

/// One lobe's option: its factors (or `None`, dropped) and the far-field node count and
/// table sizes it needs.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) struct LobeOption {
    factors: Option<LobeFactors>,
    nodes: Option<usize>,
    table: Option<LobeTableSize>,
    marschner_table: Option<MarschnerTableSize>,
}

/// An option that needs neither the far field's loop nor the lobe table.
const fn plain(factors: Option<LobeFactors>) -> LobeOption {
    LobeOption {
        factors,
        nodes: None,
        table: None,
        marschner_table: None,
    }
}

/// The lobes a composition chooses options for, in the order of [`Composition`]'s fields:
/// R, TT, TRT and the residual (index 3).
pub(super) const SLOTS: usize = 4;

/// Which tables a scene can use: every table is baked at one index of refraction, and
/// Nguyen and Donnelly's at one absorption too.
#[derive(Clone, Copy, Debug)]
struct TableUse {
    /// The scene's eta is fixed.
    eta_fixed: bool,
    /// Its eta and both melanins are fixed.
    absorption_fixed: bool,
}

impl TableUse {
    fn of(hair: &SceneHair) -> Self {
        let fixed = |key| hair.get(key).is_fixed();
        let eta_fixed = fixed(HairKey::Eta);
        TableUse {
            eta_fixed,
            absorption_fixed: eta_fixed && fixed(HairKey::Eumelanin) && fixed(HairKey::Pheomelanin),
        }
    }
}

/// Every option of each slot (R, TT, TRT, residual), the tables as `tables` allows.
fn slot_options(far_field_nodes: &[usize], tables: TableUse) -> [Vec<LobeOption>; SLOTS] {
    let dropped = plain(None);
    let ms = [
        Longitudinal::Deon,
        Longitudinal::DeonReduced,
        Longitudinal::SineGaussian,
        Longitudinal::ThetaHGaussian,
        Longitudinal::HenyeyGreenstein,
    ];
    let constants = [Constants::Published, Constants::Refit];
    let attenuations: Vec<Attenuation> = constants
        .iter()
        .flat_map(|&c| [Attenuation::Offset(c), Attenuation::Exponential(c)])
        .collect();
    let lobe = |lobe: ComposedLobe| {
        let mut distributions: Vec<Distribution> =
            constants.iter().map(|&c| Distribution::Karis(c)).collect();
        distributions.push(Distribution::FrostbiteTable);
        distributions.push(Distribution::FrostbiteScaled);
        let mut azimuthals = vec![Azimuthal::KarisReflection];
        for &distribution in &distributions {
            for &attenuation in &attenuations {
                azimuthals.push(Azimuthal::Separable {
                    distribution,
                    attenuation,
                });
            }
        }
        let mut options = vec![dropped];
        for &longitudinal in &ms {
            let factors = |azimuthal| {
                Some(LobeFactors {
                    longitudinal,
                    azimuthal,
                })
            };
            for &azimuthal in azimuthals.iter().filter(|&&a| lobe.accepts(a)) {
                options.push(plain(factors(azimuthal)));
            }
            for &n in far_field_nodes {
                options.push(LobeOption {
                    nodes: Some(n),
                    ..plain(factors(Azimuthal::FarField))
                });
            }
            let absorptions: Vec<Option<Attenuation>> = match lobe {
                ComposedLobe::R => vec![None],
                _ => attenuations.iter().map(|&a| Some(a)).collect(),
            };
            for size in LobeTableSize::OFFERED.iter().filter(|_| tables.eta_fixed) {
                for &absorption in &absorptions {
                    options.push(LobeOption {
                        table: Some(*size),
                        ..plain(factors(Azimuthal::Table { absorption }))
                    });
                }
            }
            for size in MarschnerTableSize::OFFERED {
                let mut marschner = Vec::new();
                if tables.eta_fixed {
                    marschner.extend(
                        absorptions
                            .iter()
                            .map(|&absorption| Azimuthal::GerardTable { absorption }),
                    );
                }
                if tables.absorption_fixed {
                    marschner.push(Azimuthal::NguyenDonnellyTable);
                }
                for azimuthal in marschner {
                    options.push(LobeOption {
                        marschner_table: Some(size),
                        ..plain(factors(azimuthal))
                    });
                }
            }
        }
        options
    };
    let residual = core::iter::once(dropped)
        .chain(far_field_nodes.iter().map(|&n| LobeOption {
            nodes: Some(n),
            ..plain(None)
        }))
        .collect();
    [
        lobe(ComposedLobe::R),
        lobe(ComposedLobe::Tt),
        lobe(ComposedLobe::Trt),
        residual,
    ]
}

/// The composition of one option per slot (the residual kept when its option has nodes).
fn compose(options: [&LobeOption; SLOTS]) -> Composition {
    let nodes = options.iter().find_map(|o| o.nodes).unwrap_or(1);
    let table = options.iter().find_map(|o| o.table);
    let marschner_table = options.iter().find_map(|o| o.marschner_table);
    Composition {
        r: options[0].factors,
        tt: options[1].factors,
        trt: options[2].factors,
        residual: options[3].nodes.is_some(),
        far_field_nodes: nodes,
        table: table.unwrap_or(LobeTableSize::OFFERED[0]),
        marschner_table: marschner_table.unwrap_or(MarschnerTableSize::OFFERED[0]),
    }
}

/// The composition of `option` in `slot` alone (every other slot dropped).
fn alone(slot: usize, option: &LobeOption) -> Composition {
    let dropped = plain(None);
    let mut options = [&dropped; SLOTS];
    options[slot] = option;
    compose(options)
}

/// The inner products of the options' differences from the reference at one point.
pub(super) struct Gram {
    /// Offsets of each slot's options in the flat option index.
    start: [usize; SLOTS],
    /// `<d_a, d_b>` for every pair of options (row-major over the flat index).
    products: Vec<f64>,
    size: usize,
    /// `sum w S_ref^2`.
    norm: f64,
}

impl Gram {
    /// The product of option `a` of slot `sa` with option `b` of slot `sb`.
    fn get(&self, sa: usize, a: usize, sb: usize, b: usize) -> f64 {
        self.products[(self.start[sa] + a) * self.size + self.start[sb] + b]
    }

    /// E^2 of one option per slot (`choice[slot]` its index).
    fn squared_error(&self, choice: [usize; SLOTS]) -> f64 {
        let mut sum = 0.0;
        for sa in 0..SLOTS {
            sum += self.get(sa, choice[sa], sa, choice[sa]);
            for sb in sa + 1..SLOTS {
                sum += 2.0 * self.get(sa, choice[sa], sb, choice[sb]);
            }
        }
        sum.max(0.0) / self.norm.max(f64::MIN_POSITIVE)
    }
}

/// The differences of every option's lobe vector from the reference's lobe under `light` at
/// one point (`sqrt(w) (S_option,p - S_ref,p)` for directional light), and their Gram matrix.
fn measure_point(
    point: &ScenePoint,
    light: &LightMeasure,
    reference_nodes: usize,
    options: &[Vec<LobeOption>; SLOTS],
) -> Result<Gram, ParamError> {
    let rule = FarFieldRule::gauss_legendre(reference_nodes)?;
    let reference = light.lobes(&ChiangFarField::<f64>::with_rule(&point.params, &rule));
    let norm = (0..reference[0].len())
        .map(|i| reference.iter().map(|l| l[i]).sum::<f64>().powi(2))
        .sum();
    let mut start = [0; SLOTS];
    let mut flat = Vec::new();
    for (slot, slot_options) in options.iter().enumerate() {
        start[slot] = flat.len();
        flat.extend(slot_options.iter().map(|option| (slot, option)));
    }
    let differences: Vec<Vec<f64>> = flat
        .par_iter()
        .map(|&(slot, option)| {
            let model = ComposedHair::new(&point.params, alone(slot, option))
                .unwrap_or_else(|e| unreachable!("the options fit their lobes: {e}"));
            let values = light.lobes(&model);
            values[slot]
                .iter()
                .zip(&reference[slot])
                .map(|(v, r)| v - r)
                .collect()
        })
        .collect();
    let size = differences.len();
    let mut products = vec![0.0; size * size];
    for a in 0..size {
        for b in a..size {
            let p: f64 = differences[a]
                .iter()
                .zip(&differences[b])
                .map(|(x, y)| x * y)
                .sum();
            products[a * size + b] = p;
            products[b * size + a] = p;
        }
    }
    Ok(Gram {
        start,
        products,
        size,
        norm,
    })
}

/// One chosen factor set of a plan, with its own measurements.
#[derive(Clone, Debug, PartialEq)]
pub struct PlannedLobe {
    /// `R`, `TT`, `TRT` or `residual`.
    pub lobe: &'static str,
    /// The factors (`None`: dropped; the residual's far field is `FarField` with d'Eon's M).
    pub factors: Option<LobeFactors>,
    /// Whether the lobe is kept (the residual has no factors of its own).
    pub kept: bool,
    /// The far field's node count, for an option that integrates it.
    pub far_field_nodes: Option<usize>,
    /// The lobe table's size, for an option that reads it.
    pub table: Option<LobeTableSize>,
    /// Gerard's or Nguyen and Donnelly's table's size, for an option that reads one.
    pub marschner_table: Option<MarschnerTableSize>,
    /// The lobe's own error: `sqrt(sum (S_p - S_ref,p)^2 / sum S_ref^2)` under directional
    /// light, the same of the transfers under an SH environment, the worst over the scene's
    /// points and lights (a dropped lobe's is its share of the reference).
    pub error: f64,
    /// The weighted cost of a shader of this lobe alone.
    pub cost: f64,
}

impl PlannedLobe {
    /// The option in words: its factors with the far field's node count or the table's
    /// size where it uses them (`M d'Eon, N far field (16 nodes)`), `far field with d'Eon's
    /// M (16 nodes)` for the residual, or `dropped`.
    pub fn describe(&self) -> String {
        let mut text = match (self.factors, self.kept) {
            (Some(factors), _) => factors.describe(),
            (None, true) => "far field with d'Eon's M".to_string(),
            (None, false) => return "dropped".to_string(),
        };
        if let Some(n) = self.far_field_nodes {
            text.push_str(&format!(" ({n} nodes)"));
        }
        if let Some(t) = self.table {
            text.push_str(&format!(
                " ({} x {} x {} table)",
                t.phi, t.theta_o, t.beta_n
            ));
        }
        if let Some(t) = self.marschner_table {
            text.push_str(&format!(" ({} x {} Marschner table)", t.phi, t.theta_d));
        }
        text
    }
}

/// The planner's result.
#[derive(Clone, Debug)]
pub struct Plan {
    /// The chosen composition.
    pub composition: Composition,
    /// Its error E, the worst over the scene's points, measured on the composed model as a
    /// whole.
    pub error: f64,
    /// The point with that error.
    pub worst_point: ScenePoint,
    /// Its cost in the scene's measure ([`Plan::measure`]): the weighted traced cost
    /// ([`OpWeights`]) for `cost = "ops"`; for `cost = "llvmpipe"` its measured time in
    /// nanoseconds per evaluation on llvmpipe, the fastest of [`Plan::timing`]'s candidates
    /// (the module documentation).
    pub cost: f64,
    /// What [`Plan::cost`] measures: the scene's `cost`.
    pub measure: CostMeasure,
    /// Its weighted traced cost ([`OpWeights`]) whatever the measure (equal to
    /// [`Plan::cost`] for `cost = "ops"`).
    pub ops_cost: f64,
    /// Its traced operation counts.
    pub ops: OpCounts,
    /// The choice per lobe (R, TT, TRT, residual).
    pub lobes: Vec<PlannedLobe>,
    /// The shader arguments after wo, in the order of the scene file.
    pub arguments: Vec<&'static str>,
    /// The traced shader (`hair_bcsdf`).
    pub graph: Graph,
    /// The points measured.
    pub points: Vec<ScenePoint>,
    /// The scene's lights, measured (the error is the worst over them and the points).
    pub lights: Vec<LightMeasure>,
    /// The combinations evaluated, and how many of them met the budget.
    pub combinations: usize,
    /// Of those, how many met the budget.
    pub feasible: usize,
    /// For `cost = "llvmpipe"`, the candidates timed on the device; `None` for `cost = "ops"`.
    pub timing: Option<DeviceTiming>,
}

/// A composition timed on llvmpipe for `cost = "llvmpipe"`.
#[derive(Clone, Debug, PartialEq)]
pub struct TimedCandidate {
    /// The composition.
    pub composition: Composition,
    /// Its weighted traced cost ([`OpWeights`]).
    pub ops_cost: f64,
    /// Its error E measured as a whole, the worst over the scene's points (within the budget).
    pub error: f64,
    /// Its measured time on llvmpipe, in nanoseconds per evaluation.
    pub ns_per_eval: f64,
}

/// The timings of a `cost = "llvmpipe"` plan (the module documentation): the candidates in
/// increasing weighted traced cost, the plan the fastest of them.
#[derive(Clone, Debug, PartialEq)]
pub struct DeviceTiming {
    /// The device the candidates ran on ([`Device::describe`]).
    pub adapter: String,
    /// Rows per timed dispatch.
    pub rows: usize,
    /// Timed dispatches per candidate (the median is its time).
    pub repetitions: usize,
    /// The candidates timed: the [`PlanSettings::device_candidates`] cheapest by weighted
    /// traced cost whose error measured as a whole is within the budget, in that order.
    pub candidates: Vec<TimedCandidate>,
}

impl DeviceTiming {
    /// The index of the fastest candidate (the first of equal times; 0 when there are none).
    pub fn fastest(&self) -> usize {
        let mut best = 0;
        for (i, c) in self.candidates.iter().enumerate() {
            if c.ns_per_eval < self.candidates[best].ns_per_eval {
                best = i;
            }
        }
        best
    }
}

/// The shader of `composition` for a scene's hair: `hair_bcsdf` with the parameters
/// `arguments` (names of [`shader_argument`], in order) as arguments after wo, every other
/// parameter baked at `point`'s value.
///
/// # Errors
/// [`CompositionError`] if the composition's factors do not fit together, or an argument is
/// no input of the composed model (its message names the model's inputs).
pub fn trace_composition(
    composition: Composition,
    point: &ScenePoint,
    arguments: &[&str],
) -> Result<Graph, PlanError> {
    let model = ComposedHair::new(&point.params, composition)?;
    let inputs = ShaderInputs::new(&model, &point.inputs(), arguments)?;
    Ok(inputs.trace())
}

/// The shader module of a plan's traced `hair_bcsdf` (`graph`, the composition's
/// [`trace_composition`]), as `hairmath plan --out` writes it and `cost = "llvmpipe"` times
/// it; `summary` says what it evaluates in its comment.
///
/// # Errors
/// [`ShaderError`] if the emitter fails.
pub fn plan_shader(summary: &str, graph: Graph) -> Result<ModelShader, ShaderError> {
    graph_shader(
        "plan",
        summary,
        "hairmath::models::ComposedHair, chosen by hairmath::plan::plan",
        graph,
    )
}

/// [`trace_composition`] of a composition the planner built, with its counts and cost.
fn traced(
    composition: Composition,
    point: &ScenePoint,
    arguments: &[&str],
    weights: &OpWeights,
) -> Result<(Graph, OpCounts, f64), PlanError> {
    let graph = trace_composition(composition, point, arguments)?;
    let ops = OpCounts::of(&graph);
    Ok((graph, ops, weights.cost(&ops)))
}

/// A combination of options (indices per slot) with its worst error and estimated cost.
#[derive(Clone, Copy, Debug)]
struct Candidate {
    choice: [usize; SLOTS],
    error: f64,
    estimate: f64,
}

/// The cheapest composition meeting `scene`'s budget (module documentation). `progress` is
/// called with (done, total) as the points are measured.
///
/// # Errors
/// [`PlanError::Infeasible`] when no composition meets the budget, [`PlanError::Param`] for a
/// scene point outside the parameters' domains; for `cost = "llvmpipe"`,
/// [`PlanError::NoDevice`] on a machine without llvmpipe and [`PlanError::Device`] or
/// [`PlanError::Shader`] if a candidate's shader cannot be emitted or run.
pub fn plan(
    scene: &Scene,
    settings: &PlanSettings,
    progress: &(dyn Fn(usize, usize) + Sync),
) -> Result<Plan, PlanError> {
    let measured = SceneMeasurement::new(scene, settings, progress)?;
    measured.plan(scene.budget, settings)
}

/// A scene measured for planning: its hairs, every lobe option, the options' Gram matrices
/// at each hair and their costs. [`SceneMeasurement::plan`] plans any budget from it, and
/// [`super::catalogue`] lists every option and the Pareto front from the same measurements.
pub(super) struct SceneMeasurement {
    pub(super) points: Vec<ScenePoint>,
    pub(super) lights: Vec<LightMeasure>,
    pub(super) arguments: Vec<&'static str>,
    pub(super) options: [Vec<LobeOption>; SLOTS],
    pub(super) grams: Vec<Gram>,
    pub(super) costs: OptionCosts,
    /// The scene's cost measure.
    measure: CostMeasure,
    /// For `cost = "llvmpipe"`, the device the candidates are timed on.
    device: Option<&'static Device>,
}

impl SceneMeasurement {
    /// Measures every option at every point of `scene` (`progress` as in [`plan`]).
    pub(super) fn new(
        scene: &Scene,
        settings: &PlanSettings,
        progress: &(dyn Fn(usize, usize) + Sync),
    ) -> Result<Self, PlanError> {
        // Before the measurements: a missing device is reported at once.
        let device = match scene.cost {
            CostMeasure::Ops => None,
            CostMeasure::Llvmpipe => Some(llvmpipe().map_err(PlanError::NoDevice)?),
        };
        let points = scene_points(&scene.hair, settings.interior_points)?;
        let arguments: Vec<&'static str> = scene
            .hair
            .non_fixed()
            .into_iter()
            .map(shader_argument)
            .collect();
        let lights = LightMeasure::of(scene, settings)?;
        let options = slot_options(&settings.far_field_nodes, TableUse::of(&scene.hair));
        let done = std::sync::atomic::AtomicUsize::new(0);
        let work: Vec<(&ScenePoint, &LightMeasure)> = points
            .iter()
            .flat_map(|point| lights.iter().map(move |light| (point, light)))
            .collect();
        let grams: Vec<Gram> = work
            .par_iter()
            .map(|&(point, light)| {
                let gram = measure_point(point, light, settings.reference_nodes, &options);
                let n = done.fetch_add(1, std::sync::atomic::Ordering::Relaxed) + 1;
                progress(n, work.len());
                gram
            })
            .collect::<Result<_, _>>()?;
        let costs = option_costs(
            &options,
            &points[points.len() - 1],
            &arguments,
            &settings.weights,
        )?;
        Ok(SceneMeasurement {
            points,
            lights,
            arguments,
            options,
            grams,
            costs,
            measure: scene.cost,
            device,
        })
    }

    /// The point the shaders are traced at (every parameter not an argument baked at its
    /// value): the last one measured.
    pub(super) fn centre(&self) -> &ScenePoint {
        &self.points[self.points.len() - 1]
    }

    /// The composition of one option index per slot.
    pub(super) fn composition(&self, choice: [usize; SLOTS]) -> Composition {
        compose(choice_options(&self.options, choice))
    }

    /// The worst error over the points of a choice, from the Gram matrices.
    pub(super) fn choice_error(&self, choice: [usize; SLOTS]) -> f64 {
        self.grams
            .iter()
            .map(|g| g.squared_error(choice))
            .fold(0.0, f64::max)
            .sqrt()
    }

    /// The additive estimate of a choice's cost.
    pub(super) fn estimate(&self, choice: [usize; SLOTS]) -> f64 {
        self.costs
            .estimate(choice_options(&self.options, choice), choice)
    }

    /// Calls `f` with every choice whose options fit together.
    pub(super) fn for_each_choice(&self, f: impl FnMut([usize; SLOTS])) {
        for_each_choice(&self.options, f);
    }

    /// Option `index` of `slot` with its own error (the worst over the points) and cost
    /// alone.
    pub(super) fn planned_lobe(&self, slot: usize, index: usize) -> PlannedLobe {
        const NAMES: [&str; SLOTS] = ["R", "TT", "TRT", "residual"];
        let option = &self.options[slot][index];
        let own = self
            .grams
            .iter()
            .map(|g| g.get(slot, index, slot, index).max(0.0) / g.norm.max(f64::MIN_POSITIVE))
            .fold(0.0, f64::max)
            .sqrt();
        PlannedLobe {
            lobe: NAMES[slot],
            factors: option.factors,
            kept: option.factors.is_some() || option.nodes.is_some(),
            far_field_nodes: option.nodes,
            table: option.table,
            marschner_table: option.marschner_table,
            error: own,
            cost: self.costs.alone[slot][index],
        }
    }

    /// The cheapest composition within `budget` (the module documentation's search).
    pub(super) fn plan(&self, budget: f64, settings: &PlanSettings) -> Result<Plan, PlanError> {
        let (candidates, combinations, best) = self.combinations_within(budget);
        let feasible = candidates.len();
        let wanted = match self.device {
            None => 1,
            Some(_) => settings.device_candidates.max(1),
        };
        let mut ranked = self.cheapest_traced(budget, &candidates, settings, wanted)?;
        if ranked.is_empty() {
            return Err(PlanError::Infeasible {
                budget,
                best_error: best.1,
                best: self.composition(best.0).describe(),
            });
        }
        let (chosen, cost, timing) = match self.device {
            None => (0, ranked[0].cost, None),
            Some(device) => {
                let timing = self.time(device, &ranked, settings)?;
                let fastest = timing.fastest();
                (
                    fastest,
                    timing.candidates[fastest].ns_per_eval,
                    Some(timing),
                )
            }
        };
        let Measured {
            composition,
            graph,
            ops,
            cost: ops_cost,
            error,
            worst,
        } = ranked.swap_remove(chosen);
        let choice = candidates
            .iter()
            .find(|c| self.composition(c.choice) == composition)
            .map(|c| c.choice)
            .unwrap_or_else(|| unreachable!("the plan is one of the candidates"));
        let lobes = (0..SLOTS)
            .map(|s| self.planned_lobe(s, choice[s]))
            .collect();
        Ok(Plan {
            composition,
            error,
            worst_point: self.points[worst].clone(),
            cost,
            measure: self.measure,
            ops_cost,
            ops,
            lobes,
            arguments: self.arguments.clone(),
            graph,
            points: self.points.clone(),
            lights: self.lights.clone(),
            combinations,
            feasible,
            timing,
        })
    }

    /// Of the first [`PlanSettings::traced_candidates`] candidates, the `wanted` cheapest by
    /// traced cost whose error measured as a whole ([`worst_error`]) is within `budget`,
    /// cheapest first.
    fn cheapest_traced(
        &self,
        budget: f64,
        candidates: &[Candidate],
        settings: &PlanSettings,
        wanted: usize,
    ) -> Result<Vec<Measured>, PlanError> {
        let mut traced_candidates: Vec<(Composition, Graph, OpCounts, f64, f64)> = Vec::new();
        for candidate in candidates.iter().take(settings.traced_candidates.max(1)) {
            let composition = self.composition(candidate.choice);
            let (graph, ops, cost) = traced(
                composition,
                self.centre(),
                &self.arguments,
                &settings.weights,
            )?;
            traced_candidates.push((composition, graph, ops, cost, candidate.error));
        }
        traced_candidates.sort_by(|a, b| a.3.total_cmp(&b.3).then(a.4.total_cmp(&b.4)));
        let mut within = Vec::new();
        for (composition, graph, ops, cost, _) in traced_candidates {
            if within.len() == wanted {
                break;
            }
            let (error, worst) = worst_error(
                composition,
                &self.points,
                &self.lights,
                settings.reference_nodes,
            )?;
            if error <= budget {
                within.push(Measured {
                    composition,
                    graph,
                    ops,
                    cost,
                    error,
                    worst,
                });
            }
        }
        Ok(within)
    }

    /// Each of `ranked` timed on `device` (the module documentation).
    fn time(
        &self,
        device: &Device,
        ranked: &[Measured],
        settings: &PlanSettings,
    ) -> Result<DeviceTiming, PlanError> {
        let pairs = DirectionPairs::kronecker(settings.device_rows);
        let arguments: Vec<HairKey> = self
            .arguments
            .iter()
            .filter_map(|&name| {
                HairKey::ALL
                    .into_iter()
                    .find(|&k| shader_argument(k) == name)
            })
            .collect();
        let stride = 6 + arguments.len();
        let mut rows = Vec::with_capacity(pairs.len() * stride);
        for (k, (wi, wo)) in pairs.pairs().iter().enumerate() {
            let point = &self.points[k % self.points.len()];
            rows.extend([wi.x, wi.y, wi.z, wo.x, wo.y, wo.z].map(|x| x as f32));
            rows.extend(
                arguments
                    .iter()
                    .map(|&key| argument_value(point, key) as f32),
            );
        }
        let mut candidates = Vec::with_capacity(ranked.len());
        for m in ranked {
            let shader = plan_shader(&m.composition.describe(), m.graph.clone())?;
            let wgsl = shader.compute()?.wgsl()?;
            let textures = textures_of(&shader.module);
            let seconds = device.time_per_eval(
                &wgsl,
                "hair_main",
                &rows,
                stride,
                &textures,
                settings.device_repetitions,
            )?;
            candidates.push(TimedCandidate {
                composition: m.composition,
                ops_cost: m.cost,
                error: m.error,
                ns_per_eval: seconds * 1e9,
            });
        }
        Ok(DeviceTiming {
            adapter: device.describe(),
            rows: settings.device_rows,
            repetitions: settings.device_repetitions,
            candidates,
        })
    }

    /// Every choice whose worst error is within `budget` (sorted by estimated cost), how
    /// many choices were evaluated, and the most accurate one `(choice, error)`.
    fn combinations_within(&self, budget: f64) -> (Vec<Candidate>, usize, ([usize; SLOTS], f64)) {
        let mut within = Vec::new();
        let mut count = 0;
        let mut best = ([0; SLOTS], f64::INFINITY);
        self.for_each_choice(|choice| {
            count += 1;
            let error = self.choice_error(choice);
            if error < best.1 {
                best = (choice, error);
            }
            if error <= budget {
                within.push(Candidate {
                    choice,
                    error,
                    estimate: self.estimate(choice),
                });
            }
        });
        within.sort_by(|a, b| {
            a.estimate
                .total_cmp(&b.estimate)
                .then(a.error.total_cmp(&b.error))
        });
        (within, count, best)
    }
}

/// The value of the shader argument of `key` at `point` (`alpha` in radians).
fn argument_value(point: &ScenePoint, key: HairKey) -> f64 {
    let value = point
        .values
        .iter()
        .find(|(k, _)| *k == key)
        .map_or(0.0, |v| v.1);
    match key {
        HairKey::AlphaDeg => value.to_radians(),
        _ => value,
    }
}

/// The options of one choice (indices per slot).
fn choice_options(
    options: &[Vec<LobeOption>; SLOTS],
    choice: [usize; SLOTS],
) -> [&LobeOption; SLOTS] {
    core::array::from_fn(|s| &options[s][choice[s]])
}

/// Each option's cost alone, the far field's loop excluded (`(costs per slot, loop cost per
/// node count)`): the additive estimate's terms.
pub(super) struct OptionCosts {
    alone: [Vec<f64>; SLOTS],
    far_field_loop: Vec<(usize, f64)>,
}

impl OptionCosts {
    /// The additive estimate of a combination's cost.
    fn estimate(&self, options: [&LobeOption; SLOTS], choice: [usize; SLOTS]) -> f64 {
        let nodes = options.iter().find_map(|o| o.nodes);
        let far = nodes.map_or(0.0, |n| self.loop_cost(n));
        let sum: f64 = (0..SLOTS).map(|s| self.alone[s][choice[s]]).sum();
        // Each far-field option's cost alone includes the loop: count it once.
        let loops = options.iter().filter(|o| o.nodes.is_some()).count() as f64;
        sum - loops * far + far
    }

    fn loop_cost(&self, n: usize) -> f64 {
        self.far_field_loop
            .iter()
            .find(|(m, _)| *m == n)
            .map_or(0.0, |(_, c)| *c)
    }
}

/// [`OptionCosts`] of every option, traced at `point` with `arguments` varying.
fn option_costs(
    options: &[Vec<LobeOption>; SLOTS],
    point: &ScenePoint,
    arguments: &[&str],
    weights: &OpWeights,
) -> Result<OptionCosts, PlanError> {
    let mut alone_costs: [Vec<f64>; SLOTS] = Default::default();
    for (slot, slot_options) in options.iter().enumerate() {
        for option in slot_options {
            alone_costs[slot].push(traced(alone(slot, option), point, arguments, weights)?.2);
        }
    }
    // The residual alone is the loop and d'Eon's untilted lobe: the loop's cost.
    let far_field_loop = options[3]
        .iter()
        .zip(&alone_costs[3])
        .filter_map(|(o, &c)| o.nodes.map(|n| (n, c)))
        .collect();
    Ok(OptionCosts {
        alone: alone_costs,
        far_field_loop,
    })
}

/// The far-field node count and the table sizes a partial choice has committed to.
type Shared = (
    Option<usize>,
    Option<LobeTableSize>,
    Option<MarschnerTableSize>,
);

/// `shared` with `option`'s needs added, or `None` if they conflict with it.
fn joined(shared: Shared, option: &LobeOption) -> Option<Shared> {
    fn join<T: PartialEq + Copy>(a: Option<T>, b: Option<T>) -> Option<Option<T>> {
        match (a, b) {
            (Some(x), Some(y)) if x != y => None,
            _ => Some(a.or(b)),
        }
    }
    Some((
        join(shared.0, option.nodes)?,
        join(shared.1, option.table)?,
        join(shared.2, option.marschner_table)?,
    ))
}

/// Calls `f` with every choice (an option index per slot) whose far-field options share one
/// node count and whose table options of each kind one table size.
fn for_each_choice(options: &[Vec<LobeOption>; SLOTS], mut f: impl FnMut([usize; SLOTS])) {
    for (i, oi) in options[0].iter().enumerate() {
        let Some(si) = joined((None, None, None), oi) else {
            continue;
        };
        for (j, oj) in options[1].iter().enumerate() {
            let Some(sj) = joined(si, oj) else { continue };
            for (k, ok) in options[2].iter().enumerate() {
                let Some(sk) = joined(sj, ok) else { continue };
                for (l, ol) in options[3].iter().enumerate() {
                    if joined(sk, ol).is_some() {
                        f([i, j, k, l]);
                    }
                }
            }
        }
    }
}

/// A composition measured as a whole: its traced graph, counts and weighted cost, its worst
/// error and the index of the point where it is.
struct Measured {
    composition: Composition,
    graph: Graph,
    ops: OpCounts,
    cost: f64,
    error: f64,
    worst: usize,
}

/// The worst error over `points` and `lights` of the composed model of `composition` as a
/// whole, and the index of the point.
pub fn worst_error(
    composition: Composition,
    points: &[ScenePoint],
    lights: &[LightMeasure],
    reference_nodes: usize,
) -> Result<(f64, usize), PlanError> {
    let rule = FarFieldRule::gauss_legendre(reference_nodes)?;
    // Errors are never negative (nor NaN): no lights is an error of 0 at the first point.
    let mut worst = (0.0, 0);
    for (i, point) in points.iter().enumerate() {
        let reference = ChiangFarField::<f64>::with_rule(&point.params, &rule);
        let model = ComposedHair::new(&point.params, composition)?;
        for light in lights {
            let error = light.relative_error(&model, &light.vector(&reference));
            if error > worst.0 {
                worst = (error, i);
            }
        }
    }
    Ok(worst)
}
