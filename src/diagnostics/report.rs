//! Every figure of `hairmath report`, computed once as a [`Report`].

use super::energy::{lobe_energies, LobeEnergies};
use super::furnace::{viewing_direction, white_furnace, Furnace};
use super::integrator::{integrator_table_steps, IntegratorSettings, IntegratorTable};
use super::timing::ns_per_eval;
use crate::absorption::Absorption;
use crate::bcsdf::{ChiangFarField, ChiangHair, FarFieldRule};
use crate::error::ParamError;
use crate::params::{HairParams, HairValues};
use crate::quadrature::SphereRule;
use core::fmt;

/// Roughness of the lobe-energy tables and the timings (beta_m = beta_n), and beta_m of the
/// integrator table.
pub const REPORT_BETA: f64 = 0.3;
/// Cuticle tilt of every configuration of the report, degrees.
pub const REPORT_ALPHA_DEG: f64 = 2.0;
/// Relative index of refraction of every configuration of the report.
pub const REPORT_ETA: f64 = 1.55;
/// The hair colours of the lobe-energy tables: name, eumelanin, pheomelanin
/// ([`Absorption::from_melanin`]): every named colour of
/// [`HAIR_COLOURS`](crate::absorption::HAIR_COLOURS).
pub const REPORT_HAIRS: [(&str, f64, f64); 5] = crate::absorption::HAIR_COLOURS;
/// Roughnesses (beta_m = beta_n) of the white-furnace checks.
pub const FURNACE_BETAS: [f64; 5] = [0.1, 0.3, 0.5, 0.7, 0.9];
/// Below this roughness the furnace uses the finer sphere rule
/// ([`ReportSettings::furnace_sphere_sharp`]): its lobes are too narrow for the coarser one.
pub const SHARP_BETA: f64 = 0.2;
/// Node count of the far-field model ([`ChiangFarField`]) in the far-field lobe table and
/// furnace.
pub const FAR_NODES: usize = 64;
/// Absorption of the integrator table: one clear, one moderate and one strongly absorbing
/// channel.
pub const INTEGRATOR_SIGMA_A: [f64; 3] = [0.0, 0.5, 10.0];
/// Node counts of the integrator table.
pub const INTEGRATOR_NODES: [usize; 5] = [8, 16, 32, 64, 128];
/// Absorption of the timed model.
pub const TIMING_SIGMA_A: [f64; 3] = [0.5, 0.8, 1.4];

/// How much work a report does.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ReportDetail {
    /// Coarse quadrature and short timing loops (a few seconds; for tests, the numbers are
    /// rough).
    Quick,
    /// The published report's quadrature (about half a minute in a release build).
    Full,
}

/// The size of a [`SphereRule`]: the arguments of [`SphereRule::new`]. Displayed as
/// `(theta_panels, order, azimuths)`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct SphereSize {
    /// Panels in theta.
    pub theta_panels: usize,
    /// Gauss-Legendre order per panel.
    pub order: usize,
    /// Midpoint nodes in phi.
    pub azimuths: usize,
}

impl SphereSize {
    /// The size `(theta_panels, order, azimuths)`.
    pub const fn new(theta_panels: usize, order: usize, azimuths: usize) -> Self {
        SphereSize {
            theta_panels,
            order,
            azimuths,
        }
    }

    /// The rule of this size.
    pub fn rule(&self) -> SphereRule {
        SphereRule::new(self.theta_panels, self.order, self.azimuths)
    }

    /// `[theta_panels, order, azimuths]`.
    pub fn to_array(&self) -> [usize; 3] {
        [self.theta_panels, self.order, self.azimuths]
    }
}

impl fmt::Display for SphereSize {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "({}, {}, {})",
            self.theta_panels, self.order, self.azimuths
        )
    }
}

/// The quadrature sizes and loop counts of a [`report`].
#[derive(Clone, Debug, PartialEq)]
pub struct ReportSettings {
    /// Which preset these settings are (or were derived from).
    pub detail: ReportDetail,
    /// The sphere rule of the lobe-energy tables.
    pub sphere: SphereSize,
    /// The finer sphere rule of the lobe table's convergence check.
    pub fine_sphere: SphereSize,
    /// Gauss-Legendre nodes in gamma_o = asin(h) of the near-field lobe table
    /// ([`FarFieldRule::gauss_legendre`]).
    pub offset_nodes: usize,
    /// The finer node count of the convergence check.
    pub fine_offset_nodes: usize,
    /// The sphere rule of the furnace for beta >= [`SHARP_BETA`].
    pub furnace_sphere: SphereSize,
    /// The sphere rule of the furnace for beta < [`SHARP_BETA`].
    pub furnace_sphere_sharp: SphereSize,
    /// Inclinations theta_o of the furnace's worst-case search, degrees.
    pub furnace_theta_o_deg: Vec<f64>,
    /// Offsets h of the near-field furnace's worst-case search.
    pub furnace_h: Vec<f64>,
    /// Timed `eval` calls per precision.
    pub timing_calls: usize,
    /// The far-field integrator table.
    pub integrator: IntegratorSettings,
}

/// `quick` or `full` as `detail` says.
fn pick<T>(detail: ReportDetail, quick: T, full: T) -> T {
    match detail {
        ReportDetail::Quick => quick,
        ReportDetail::Full => full,
    }
}

impl ReportSettings {
    /// The settings of `hairmath report` (`Full`) and `hairmath report --quick` (`Quick`).
    pub fn new(detail: ReportDetail) -> Self {
        let p = |quick: (usize, usize, usize), full: (usize, usize, usize)| {
            let (a, b, c) = pick(detail, quick, full);
            SphereSize::new(a, b, c)
        };
        ReportSettings {
            detail,
            sphere: p((8, 4, 32), (32, 8, 256)),
            fine_sphere: p((16, 4, 64), (64, 8, 512)),
            offset_nodes: pick(detail, 4, 16),
            fine_offset_nodes: pick(detail, 8, 32),
            // Half the theta panels of the energy rule, twice its azimuths (the same node
            // count): the trimmed logistic's kink at +-pi makes the midpoint rule in phi
            // converge only as 1/azimuths^2, which is what limits the furnace at large beta.
            furnace_sphere: p((8, 4, 32), (16, 8, 512)),
            furnace_sphere_sharp: p((16, 4, 64), (32, 8, 512)),
            furnace_theta_o_deg: pick(detail, vec![0.0, 60.0], vec![0.0, 30.0, -60.0]),
            furnace_h: pick(detail, vec![-0.5, 0.7], vec![-0.9, 0.0, 0.5, 0.95]),
            timing_calls: pick(detail, 10_000, 1_000_000),
            integrator: IntegratorSettings {
                beta_n: pick(
                    detail,
                    vec![0.05, 0.1, 0.3, 1.0],
                    vec![0.05, 0.1, 0.3, 0.5, 1.0],
                ),
                theta_o: pick(detail, vec![0.0, 1.3], vec![0.0, 0.6, 1.3, 1.55]),
                phis: pick(detail, 8, 32),
                refine_every: 8,
                nodes: INTEGRATOR_NODES.to_vec(),
                timing_node_evals: pick(detail, 100_000, 5_000_000),
            },
        }
    }

    /// The furnace's sphere rule size for roughness `beta`.
    pub fn furnace_sphere_for(&self, beta: f64) -> SphereSize {
        if beta < SHARP_BETA {
            self.furnace_sphere_sharp
        } else {
            self.furnace_sphere
        }
    }
}

/// The lobe energies of one hair colour, near and far field.
#[derive(Clone, Debug, PartialEq)]
pub struct HairEnergies {
    /// The colour's name.
    pub name: &'static str,
    /// Eumelanin concentration.
    pub eumelanin: f64,
    /// Pheomelanin concentration.
    pub pheomelanin: f64,
    /// The absorption of the concentrations ([`Absorption::from_melanin`]).
    pub sigma_a: [f64; 3],
    /// [`ChiangHair`]'s energies, averaged over h with
    /// [`ReportSettings::offset_nodes`] nodes.
    pub near: LobeEnergies,
    /// [`ChiangFarField`]'s energies with [`FAR_NODES`] nodes.
    pub far: LobeEnergies,
    /// `far.max_difference(&near)`: the two differ only by the h quadrature.
    pub far_vs_near: f64,
}

/// The convergence check of the near-field lobe table, on its first hair colour.
#[derive(Clone, Debug, PartialEq)]
pub struct EnergyConvergence {
    /// The hair colour checked.
    pub hair: &'static str,
    /// Largest change over lobes and channels with [`ReportSettings::fine_sphere`].
    pub fine_sphere_change: f64,
    /// Largest change with [`ReportSettings::fine_offset_nodes`] nodes in h.
    pub fine_offset_change: f64,
}

/// The white furnace at one roughness (sigma_a = 0, beta_m = beta_n = beta).
#[derive(Clone, Debug, PartialEq)]
pub struct FurnaceRow {
    /// The roughness.
    pub beta: f64,
    /// The sphere rule used ([`ReportSettings::furnace_sphere_for`]).
    pub sphere: SphereSize,
    /// [`ChiangHair`] over the settings' inclinations and offsets.
    pub near: Furnace,
    /// [`ChiangFarField`] with [`FAR_NODES`] nodes over the settings' inclinations.
    pub far: Furnace,
}

/// The evaluation speed of [`ChiangHair`]'s [`Bcsdf::eval`](crate::bcsdf::Bcsdf::eval) ([`ns_per_eval`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct EvalTiming {
    /// Calls timed per precision.
    pub calls: usize,
    /// Nanoseconds per call in `f64`.
    pub ns_f64: f64,
    /// Nanoseconds per call in `f32`.
    pub ns_f32: f64,
}

/// Every figure `hairmath report` prints.
#[derive(Clone, Debug, PartialEq)]
pub struct Report {
    /// The settings the report was computed with.
    pub settings: ReportSettings,
    /// The lobe energies of each hair of [`REPORT_HAIRS`] (beta_m = beta_n =
    /// [`REPORT_BETA`], wo at theta_o = 0, [`viewing_direction`]), in order.
    pub hairs: Vec<HairEnergies>,
    /// The convergence check of the near-field table.
    pub convergence: EnergyConvergence,
    /// The white furnace for each roughness of [`FURNACE_BETAS`], in order.
    pub furnace: Vec<FurnaceRow>,
    /// The near-field model's evaluation speed (sigma_a = [`TIMING_SIGMA_A`]).
    pub timing: EvalTiming,
    /// The far-field integrator table (beta_m = [`REPORT_BETA`], sigma_a =
    /// [`INTEGRATOR_SIGMA_A`]).
    pub integrator: IntegratorTable,
}

/// The report's hair: roughnesses `beta_m` and `beta_n`, absorption `sigma_a`, tilt
/// [`REPORT_ALPHA_DEG`] and index [`REPORT_ETA`].
///
/// # Errors
/// A roughness outside (0, 1] or a negative or non-finite absorption.
pub fn report_hair(beta_m: f64, beta_n: f64, sigma_a: [f64; 3]) -> Result<HairParams, ParamError> {
    HairParams::try_from(HairValues {
        beta_m,
        beta_n,
        alpha: REPORT_ALPHA_DEG.to_radians(),
        eta: REPORT_ETA,
        sigma_a,
    })
}

/// Computes every figure of `hairmath report` with `settings`: the near- and far-field lobe
/// energies of [`REPORT_HAIRS`] with the near table's convergence check, the white furnace of
/// both models for each of [`FURNACE_BETAS`], the near-field model's evaluation speed in `f64`
/// and `f32`, and the far-field integrator table. [`report_with_progress`] is the same with a
/// progress callback.
///
/// # Errors
/// A parameter of `settings` out of its domain (a node count outside 1..=512, a beta_n of the
/// integrator table outside (0, 1]).
pub fn report(settings: &ReportSettings) -> Result<Report, ParamError> {
    report_with_progress(settings, &|_, _| {})
}

/// The number of steps [`report_with_progress`] reports for `settings`: one per hair colour
/// of the lobe tables, one for their convergence check, one per furnace roughness, one for
/// the timing, one per beta_n of the integrator table and one for its timings.
pub fn report_steps(settings: &ReportSettings) -> usize {
    REPORT_HAIRS.len() + 1 + FURNACE_BETAS.len() + 1 + settings.integrator.beta_n.len() + 1
}

/// [`report`], calling `progress(done, total)` after each of its [`report_steps`] steps (a
/// hair colour's lobe tables, a furnace roughness, a row of the integrator table, ...), from
/// the calling thread, with `done` increasing by one from 1 to `total`. The steps are not of
/// equal cost: the count says where the report is, not how long it has left. The figures are
/// the same as [`report`]'s.
///
/// # Errors
/// As [`report`].
pub fn report_with_progress(
    settings: &ReportSettings,
    progress: &(dyn Fn(usize, usize) + Sync),
) -> Result<Report, ParamError> {
    let total = report_steps(settings);
    let mut done = 0;
    let mut step = || {
        done += 1;
        progress(done, total);
    };
    let (hairs, convergence) = energies(settings, &mut step)?;
    let mut furnace = Vec::with_capacity(FURNACE_BETAS.len());
    for beta in FURNACE_BETAS {
        furnace.push(furnace_row(beta, settings)?);
        step();
    }
    let timed = report_hair(REPORT_BETA, REPORT_BETA, TIMING_SIGMA_A)?;
    let timing = EvalTiming {
        calls: settings.timing_calls,
        ns_f64: ns_per_eval(&ChiangHair::<f64>::new(&timed), settings.timing_calls),
        ns_f32: ns_per_eval(&ChiangHair::<f32>::new(&timed), settings.timing_calls),
    };
    step();
    let integrator_hair = report_hair(REPORT_BETA, REPORT_BETA, INTEGRATOR_SIGMA_A)?;
    let integrator = integrator_table_steps(&integrator_hair, &settings.integrator, &mut step)?;
    Ok(Report {
        settings: settings.clone(),
        hairs,
        convergence,
        furnace,
        timing,
        integrator,
    })
}

/// The lobe tables of every hair and the convergence check of the first, calling `step` after
/// each hair and after the check.
fn energies(
    s: &ReportSettings,
    step: &mut dyn FnMut(),
) -> Result<(Vec<HairEnergies>, EnergyConvergence), ParamError> {
    let sphere = s.sphere.rule();
    let offsets = FarFieldRule::gauss_legendre(s.offset_nodes)?;
    let far_rule = FarFieldRule::gauss_legendre(FAR_NODES)?;
    let wo = viewing_direction(0.0);
    let mut hairs = Vec::with_capacity(REPORT_HAIRS.len());
    let mut convergence = None;
    for (name, eumelanin, pheomelanin) in REPORT_HAIRS {
        let sigma_a = Absorption::from_melanin(eumelanin, pheomelanin)?.rgb();
        let params = report_hair(REPORT_BETA, REPORT_BETA, sigma_a)?;
        let model = ChiangHair::<f64>::new(&params);
        let near = lobe_energies(&model, &sphere, wo, &offsets);
        let far_model = ChiangFarField::<f64>::with_rule(&params, &far_rule);
        let far = lobe_energies(&far_model, &sphere, wo, &far_rule);
        if convergence.is_none() {
            let fine_sphere = lobe_energies(&model, &s.fine_sphere.rule(), wo, &offsets);
            let fine_offsets = FarFieldRule::gauss_legendre(s.fine_offset_nodes)?;
            let fine_h = lobe_energies(&model, &sphere, wo, &fine_offsets);
            convergence = Some(EnergyConvergence {
                hair: name,
                fine_sphere_change: near.max_difference(&fine_sphere),
                fine_offset_change: near.max_difference(&fine_h),
            });
            step();
        }
        hairs.push(HairEnergies {
            name,
            eumelanin,
            pheomelanin,
            sigma_a,
            far_vs_near: far.max_difference(&near),
            near,
            far,
        });
        step();
    }
    let convergence = convergence.unwrap_or_else(|| unreachable!("REPORT_HAIRS is not empty"));
    Ok((hairs, convergence))
}

/// The furnace of both models at roughness `beta`.
fn furnace_row(beta: f64, s: &ReportSettings) -> Result<FurnaceRow, ParamError> {
    let params = report_hair(beta, beta, [0.0; 3])?;
    let sphere = s.furnace_sphere_for(beta);
    let rule = sphere.rule();
    let near = ChiangHair::<f64>::new(&params);
    let far = ChiangFarField::<f64>::with_rule(&params, &FarFieldRule::gauss_legendre(FAR_NODES)?);
    Ok(FurnaceRow {
        beta,
        sphere,
        near: white_furnace(&near, &rule, &s.furnace_theta_o_deg, &s.furnace_h),
        far: white_furnace(&far, &rule, &s.furnace_theta_o_deg, &s.furnace_h),
    })
}
