//! The accuracy and cost of the far field's fixed-node integrator against the adaptive
//! reference.

use super::timing::ns_per_call;
use crate::azimuthal::LOBES_WITH_RESIDUAL;
use crate::bcsdf::{ChiangFarField, ChiangHair, FarFieldRule};
use crate::error::ParamError;
use crate::params::{AzimuthalRoughness, HairParams};
use std::hint::black_box;
use std::time::Instant;

/// Relative tolerance of the adaptive reference the fixed rule is compared with.
pub const REFERENCE_TOL: f64 = 1e-11;

/// Relative tolerance of the finer reference that estimates the reference's own error.
pub const REFINED_TOL: f64 = 1e-13;

/// Smallest peak that takes part in the error statistics: a lobe absorbed below it carries no
/// energy worth measuring.
pub const PEAK_FLOOR: f64 = 1e-12;

/// The grid and the rules of an [`integrator_table`].
#[derive(Clone, Debug, PartialEq)]
pub struct IntegratorSettings {
    /// The azimuthal roughnesses, one row each.
    pub beta_n: Vec<f64>,
    /// The inclinations theta_o of the grid, radians.
    pub theta_o: Vec<f64>,
    /// Number of relative azimuths per inclination: the midpoints
    /// `phi_k = -pi + (k + 1/2) 2 pi / phis` of (-pi, pi).
    pub phis: usize,
    /// The reference's own error is measured on every `refine_every`-th grid point.
    pub refine_every: usize,
    /// The node counts of the fixed rule ([`FarFieldRule::gauss_legendre`]), one column each.
    pub nodes: Vec<usize>,
    /// About how many node evaluations each node count's timing loop makes.
    pub timing_node_evals: usize,
}

/// The error of the fixed rule with one node count ([`integrator_table`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct NodeErrors {
    /// The node count.
    pub nodes: usize,
    /// Largest `|fixed - reference| / peak` over grid points, lobes and channels.
    pub max: f64,
    /// Mean of the same over grid points, lobes and channels.
    pub mean: f64,
}

/// One row of an [`IntegratorTable`]: one azimuthal roughness.
#[derive(Clone, Debug, PartialEq)]
pub struct IntegratorRow {
    /// The azimuthal roughness beta_n.
    pub beta_n: f64,
    /// Mean wall-clock microseconds per reference call (indicative).
    pub reference_us: f64,
    /// The reference's own error: the largest difference (relative to the peaks, as the
    /// errors) of the reference at [`REFERENCE_TOL`] from the reference at [`REFINED_TOL`], on
    /// every `refine_every`-th grid point.
    pub reference_refinement: f64,
    /// The fixed rule's error for each node count of the settings, in order.
    pub errors: Vec<NodeErrors>,
}

impl IntegratorRow {
    /// The errors of the rule with `nodes` nodes, if the table has that node count.
    pub fn errors_at(&self, nodes: usize) -> Option<&NodeErrors> {
        self.errors.iter().find(|e| e.nodes == nodes)
    }
}

/// The cost of the fixed rule with one node count.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct NodeTiming {
    /// The node count.
    pub nodes: usize,
    /// Mean wall-clock nanoseconds of one [`ChiangFarField::azimuthal`] call (all lobes and
    /// channels), indicative.
    pub ns: f64,
}

/// The accuracy and cost of [`ChiangFarField`]'s fixed rule against the adaptive reference
/// ([`integrator_table`]).
#[derive(Clone, Debug, PartialEq)]
pub struct IntegratorTable {
    /// One row per azimuthal roughness of the settings, in order.
    pub rows: Vec<IntegratorRow>,
    /// The cost per call for each node count of the settings, in order.
    pub timings: Vec<NodeTiming>,
}

/// `N_p A_p` per lobe and channel at one grid point.
type Azimuthal = [[f64; 3]; LOBES_WITH_RESIDUAL];

/// A grid point: (sin theta_o, cos theta_o, phi).
type GridPoint = (f64, f64, f64);

/// The far-field integrator table of the hair `hair` (its beta_m, tilt, index and absorption;
/// the reference's behaviour is most telling with one clear, one moderate and one strongly
/// absorbing channel).
///
/// For each beta_n of `settings` (replacing `hair`'s), at every grid point (theta_o, phi)
/// ([`IntegratorSettings`]) the reference `N_p A_p` of
/// [`ChiangHair::far_field_azimuthal_reference`] at [`REFERENCE_TOL`] is compared with the
/// fixed rule's ([`ChiangFarField::azimuthal`]) for each node count. The error of lobe p and
/// channel c at a point is `|fixed - reference| / peak`, the peak being the largest
/// `|N_p A_p|` of that lobe and channel over phi at the point's theta_o; (lobe, channel) pairs
/// whose peak is below [`PEAK_FLOOR`] are skipped. The row also has the reference's cost and
/// its own error (against [`REFINED_TOL`]). The timings use `hair` as given.
///
/// # Errors
/// A beta_n outside (0, 1], or a node count outside 1..=512.
pub fn integrator_table(
    hair: &HairParams,
    settings: &IntegratorSettings,
) -> Result<IntegratorTable, ParamError> {
    integrator_table_steps(hair, settings, &mut || {})
}

/// [`integrator_table`], calling `step` after each row and after the timings.
pub(crate) fn integrator_table_steps(
    hair: &HairParams,
    settings: &IntegratorSettings,
    step: &mut dyn FnMut(),
) -> Result<IntegratorTable, ParamError> {
    let grid = grid(&settings.theta_o, settings.phis);
    let mut rows = Vec::with_capacity(settings.beta_n.len());
    for &beta_n in &settings.beta_n {
        let params = HairParams {
            beta_n: AzimuthalRoughness::new(beta_n)?,
            ..*hair
        };
        rows.push(row(&params, &grid, settings)?);
        step();
    }
    let mut timings = Vec::with_capacity(settings.nodes.len());
    for &nodes in &settings.nodes {
        let far = ChiangFarField::<f64>::with_rule(hair, &FarFieldRule::gauss_legendre(nodes)?);
        let calls = (settings.timing_node_evals / nodes).max(grid.len()).max(1);
        let ns = ns_per_call(calls, |k| {
            let (sin_o, cos_o, phi) = grid[k % grid.len().max(1)];
            black_box(far.azimuthal(black_box(sin_o), black_box(cos_o), black_box(phi)));
        });
        timings.push(NodeTiming { nodes, ns });
    }
    step();
    Ok(IntegratorTable { rows, timings })
}

/// The grid: `phis` midpoint azimuths in (-pi, pi) for each theta_o, grouped by theta_o.
fn grid(theta_o: &[f64], phis: usize) -> Vec<GridPoint> {
    let step = core::f64::consts::TAU / phis as f64;
    theta_o
        .iter()
        .flat_map(|t| {
            (0..phis).map(move |k| {
                (
                    t.sin(),
                    t.cos(),
                    -core::f64::consts::PI + (k as f64 + 0.5) * step,
                )
            })
        })
        .collect()
}

/// The row of `params`.
fn row(
    params: &HairParams,
    grid: &[GridPoint],
    settings: &IntegratorSettings,
) -> Result<IntegratorRow, ParamError> {
    let hair = ChiangHair::<f64>::new(params);
    let start = Instant::now();
    let reference = reference_values(&hair, grid, REFERENCE_TOL);
    let reference_us = start.elapsed().as_secs_f64() * 1e6 / grid.len().max(1) as f64;
    let peak = peaks(&reference, settings.phis);
    let every = settings.refine_every.max(1);
    let subset: Vec<usize> = (0..grid.len()).step_by(every).collect();
    let points: Vec<GridPoint> = subset.iter().map(|&i| grid[i]).collect();
    let refined = reference_values(&hair, &points, REFINED_TOL);
    let (reference_refinement, _) = error_stats(subset.into_iter().zip(refined), &reference, &peak);
    let mut errors = Vec::with_capacity(settings.nodes.len());
    for &nodes in &settings.nodes {
        let far = ChiangFarField::<f64>::with_rule(params, &FarFieldRule::gauss_legendre(nodes)?);
        let fixed = grid.iter().map(|&(s, c, phi)| far.azimuthal(s, c, phi).0);
        let (max, mean) = error_stats(fixed.enumerate(), &reference, &peak);
        errors.push(NodeErrors { nodes, max, mean });
    }
    Ok(IntegratorRow {
        beta_n: params.beta_n.get(),
        reference_us,
        reference_refinement,
        errors,
    })
}

/// The reference `N_p A_p` at every point of `grid` with relative tolerance `tol`.
fn reference_values(hair: &ChiangHair<f64>, grid: &[GridPoint], tol: f64) -> Vec<Azimuthal> {
    grid.iter()
        .map(|&(sin_o, cos_o, phi)| hair.far_field_azimuthal_reference(sin_o, cos_o, phi, tol).0)
        .collect()
}

/// For each theta_o group of `phis` consecutive points, the largest `|N_p A_p|` over the group
/// of each lobe and channel, repeated for every point of the group.
fn peaks(values: &[Azimuthal], phis: usize) -> Vec<Azimuthal> {
    let mut out = Vec::with_capacity(values.len());
    for group in values.chunks(phis.max(1)) {
        let mut peak = [[0.0_f64; 3]; LOBES_WITH_RESIDUAL];
        for value in group {
            for (pk, v) in peak.iter_mut().flatten().zip(value.iter().flatten()) {
                *pk = pk.max(v.abs());
            }
        }
        out.extend(std::iter::repeat_n(peak, group.len()));
    }
    out
}

/// Max and mean over the points `(index, value)`, lobes and channels of
/// `|value - reference[index]| / peak[index]`, skipping (lobe, channel) pairs whose peak is
/// below [`PEAK_FLOOR`]; (0, 0) when nothing is measured.
fn error_stats(
    approx: impl Iterator<Item = (usize, Azimuthal)>,
    reference: &[Azimuthal],
    peak: &[Azimuthal],
) -> (f64, f64) {
    let (mut worst, mut sum, mut count) = (0.0_f64, 0.0, 0usize);
    for (i, a) in approx {
        let pairs = a.iter().flatten().zip(reference[i].iter().flatten());
        for ((a, r), p) in pairs.zip(peak[i].iter().flatten()) {
            if *p > PEAK_FLOOR {
                let e = (a - r).abs() / p;
                worst = worst.max(e);
                sum += e;
                count += 1;
            }
        }
    }
    (worst, sum / count.max(1) as f64)
}
