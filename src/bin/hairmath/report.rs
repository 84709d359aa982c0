//! `hairmath report`: lobe energies of a few hair colours, a white-furnace check and an
//! indicative evaluation speed of the near-field model; the same energies and furnace for the
//! far-field model and the accuracy and cost of its fixed-node integrator against the adaptive
//! reference; as markdown on stdout.

use crate::CliError;
use clap::Args;
use hairmath::absorption::Absorption;
use hairmath::bcsdf::{Bcsdf, ChiangFarField, ChiangHair, FarFieldRule, Query};
use hairmath::geometry::{local_direction, V3};
use hairmath::params::{
    AzimuthalRoughness, CuticleTilt, HairParams, LongitudinalRoughness, RefractiveIndex,
};
use hairmath::quadrature::{gauss_legendre, SphereRule};
use hairmath::real::Real;
use std::hint::black_box;
use std::io::{self, BufWriter, Write};
use std::time::Instant;

/// Arguments of `hairmath report`.
#[derive(Args, Debug)]
pub struct ReportArgs {
    /// Shrink every quadrature and the timing loop (for tests; the numbers become rough).
    #[arg(long)]
    quick: bool,
}

/// Roughness of the lobe-energy table (beta_m = beta_n).
const BETA: f64 = 0.3;
/// Cuticle tilt of every configuration, degrees.
const ALPHA_DEG: f64 = 2.0;
/// Relative index of refraction of every configuration.
const ETA: f64 = 1.55;
/// Hair colours: name, eumelanin, pheomelanin.
const HAIRS: [(&str, f64, f64); 5] = [
    ("blonde", 0.3, 0.0),
    ("red", 0.3, 2.0),
    ("auburn", 1.3, 0.0),
    ("brown", 3.0, 0.0),
    ("black", 8.0, 0.0),
];
/// Roughnesses (beta_m = beta_n) of the white-furnace check.
const FURNACE_BETAS: [f64; 5] = [0.1, 0.3, 0.5, 0.7, 0.9];
/// Lobe names in the order of [`ChiangHair::eval_lobes`].
const LOBE_NAMES: [&str; 4] = ["R", "TT", "TRT", "residual"];

/// Node count of the far-field model in the far-field lobe table and furnace.
const FAR_NODES: usize = 64;
/// Absorption of the integrator table: clear, moderate and strong.
const INTEGRATOR_SIGMA_A: [f64; 3] = [0.0, 0.5, 10.0];
/// Node counts of the integrator table.
const INTEGRATOR_NODES: [usize; 5] = [8, 16, 32, 64, 128];
/// Relative tolerance of the reference the fixed rule is compared with, and of the finer
/// reference that estimates the reference's own error.
const REFERENCE_TOL: f64 = 1e-11;
const REFINED_TOL: f64 = 1e-13;

/// A sphere rule: theta panels, Gauss-Legendre order, azimuths.
type SphereSize = (usize, usize, usize);

/// Quadrature sizes and loop counts of one report.
struct Settings {
    /// The sphere rule of the table.
    sphere: SphereSize,
    /// The finer rule the table is compared with.
    fine_sphere: SphereSize,
    /// Gauss-Legendre nodes in gamma_o = asin(h) for the table and for its comparison.
    h_nodes: usize,
    fine_h_nodes: usize,
    /// The sphere rule of the furnace for beta >= 0.2, and for smaller beta.
    furnace_sphere: SphereSize,
    furnace_sphere_sharp: SphereSize,
    /// theta_o (degrees) and h of the furnace's worst case search.
    furnace_theta_o_deg: &'static [f64],
    furnace_h: &'static [f64],
    /// Number of timed `eval` calls per precision.
    timing_calls: usize,
    /// The integrator table: beta_n values, theta_o values (radians), the number of phi
    /// values per theta_o, every how many grid points the reference is refined, and the
    /// number of node evaluations timed per node count.
    integrator_beta_n: &'static [f64],
    integrator_theta_o: &'static [f64],
    integrator_phis: usize,
    refine_every: usize,
    integrator_timing_nodes: usize,
}

impl Settings {
    fn new(quick: bool) -> Self {
        if quick {
            Settings {
                sphere: (8, 4, 32),
                fine_sphere: (16, 4, 64),
                h_nodes: 4,
                fine_h_nodes: 8,
                furnace_sphere: (8, 4, 32),
                furnace_sphere_sharp: (16, 4, 64),
                furnace_theta_o_deg: &[0.0, 60.0],
                furnace_h: &[-0.5, 0.7],
                timing_calls: 10_000,
                integrator_beta_n: &[0.05, 0.1, 0.3, 1.0],
                integrator_theta_o: &[0.0, 1.3],
                integrator_phis: 8,
                refine_every: 8,
                integrator_timing_nodes: 100_000,
            }
        } else {
            Settings {
                sphere: (32, 8, 256),
                fine_sphere: (64, 8, 512),
                h_nodes: 16,
                fine_h_nodes: 32,
                furnace_sphere: (32, 8, 256),
                furnace_sphere_sharp: (32, 8, 512),
                furnace_theta_o_deg: &[0.0, 30.0, -60.0],
                furnace_h: &[-0.9, 0.0, 0.5, 0.95],
                timing_calls: 1_000_000,
                integrator_beta_n: &[0.05, 0.1, 0.3, 0.5, 1.0],
                integrator_theta_o: &[0.0, 0.6, 1.3, 1.55],
                integrator_phis: 32,
                refine_every: 8,
                integrator_timing_nodes: 5_000_000,
            }
        }
    }
}

/// Runs `hairmath report`.
pub fn run(args: &ReportArgs) -> Result<(), CliError> {
    let settings = Settings::new(args.quick);
    let mut out = BufWriter::new(io::stdout().lock());
    writeln!(out, "# hairmath report")?;
    if args.quick {
        writeln!(out, "\n*--quick: coarse quadrature, numbers are rough.*")?;
    }
    let near = lobe_table(&mut out, &settings)?;
    furnace(&mut out, &settings)?;
    speed(&mut out, &settings)?;
    writeln!(out, "\n## Far field")?;
    far_lobe_table(&mut out, &settings, &near)?;
    far_furnace(&mut out, &settings)?;
    integrator_table(&mut out, &settings)?;
    fitted_constants(&mut out)?;
    out.flush()?;
    Ok(())
}

/// The Chiang model with the report's roughness, tilt and index and the given absorption.
fn hair(beta: f64, sigma_a: [f64; 3]) -> Result<HairParams, CliError> {
    hair_with(beta, beta, sigma_a)
}

/// The hair of the report's tilt and index with the given roughnesses and absorption.
fn hair_with(beta_m: f64, beta_n: f64, sigma_a: [f64; 3]) -> Result<HairParams, CliError> {
    Ok(HairParams {
        beta_m: LongitudinalRoughness::new(beta_m)?,
        beta_n: AzimuthalRoughness::new(beta_n)?,
        alpha: CuticleTilt::from_degrees(ALPHA_DEG)?,
        eta: RefractiveIndex::new(ETA)?,
        sigma_a: Absorption::new(sigma_a)?,
    })
}

/// A sphere rule of the given size.
fn sphere((panels, order, azimuths): SphereSize) -> SphereRule {
    SphereRule::new(panels, order, azimuths)
}

/// Averaging weights for h uniform in [-1, 1]: an `n`-node Gauss-Legendre rule in
/// gamma = asin(h) over [-pi/2, pi/2] with the Jacobian cos(gamma) (the integrand then stays
/// smooth near |h| = 1, where it behaves like sqrt(1 - h^2)). Returns (h, weight) pairs whose
/// weights sum to 1.
fn h_rule(n: usize) -> Vec<(f64, f64)> {
    let half_pi = std::f64::consts::FRAC_PI_2;
    gauss_legendre(n)
        .into_iter()
        .map(|(x, w)| {
            let gamma = half_pi * x;
            (gamma.sin(), 0.5 * half_pi * w * gamma.cos())
        })
        .collect()
}

/// Energy of each lobe and channel: the integral over the sphere of S_p(wi, wo, h), averaged
/// over h with the weights of [`h_rule`].
fn lobe_energies(
    hair: &ChiangHair<f64>,
    sphere: &SphereRule,
    h_rule: &[(f64, f64)],
    wo: V3<f64>,
) -> [[f64; 3]; 4] {
    energies(
        |wi, h| {
            let l = hair.eval_lobes(&Query::new(wi, wo, h));
            [l[0], l[1], l[2], l[3]]
        },
        sphere,
        h_rule,
    )
}

/// The integral over the sphere of `lobes(wi, h)` (per lobe and channel), averaged over h with
/// the weights `h_rule`.
fn energies(
    lobes: impl Fn(V3<f64>, f64) -> [[f64; 3]; 4],
    sphere: &SphereRule,
    h_rule: &[(f64, f64)],
) -> [[f64; 3]; 4] {
    let mut energy = [[0.0; 3]; 4];
    for &(h, h_weight) in h_rule {
        for &(wi, weight) in &sphere.nodes {
            let lobes = lobes(wi, h);
            let w = h_weight * weight;
            for (e, lobe) in energy.iter_mut().zip(lobes) {
                for (e, value) in e.iter_mut().zip(lobe) {
                    *e += w * value;
                }
            }
        }
    }
    energy
}

/// Largest absolute difference between two energy tables.
fn max_difference(a: &[[f64; 3]; 4], b: &[[f64; 3]; 4]) -> f64 {
    a.iter()
        .flatten()
        .zip(b.iter().flatten())
        .map(|(x, y)| (x - y).abs())
        .fold(0.0, f64::max)
}

/// The viewing direction at theta_o (degrees), away from the fibre.
fn wo_at(theta_o_deg: f64) -> V3<f64> {
    let t = theta_o_deg.to_radians();
    local_direction(t.sin(), t.cos(), 0.3)
}

/// Three numbers as `a, b, c` with `decimals` decimals.
fn triple(v: [f64; 3], decimals: usize) -> String {
    format!(
        "{:.decimals$}, {:.decimals$}, {:.decimals$}",
        v[0], v[1], v[2]
    )
}

/// The lobe-energy table, one row per hair colour, and its convergence check. Returns the
/// energies of each hair colour.
fn lobe_table(out: &mut impl Write, s: &Settings) -> Result<Vec<[[f64; 3]; 4]>, CliError> {
    let sphere_rule = sphere(s.sphere);
    let h_nodes = h_rule(s.h_nodes);
    let wo = wo_at(0.0);
    writeln!(
        out,
        "\n## Lobe energies\n\nChiang 2016 (pbrt-v4): beta_m = beta_n = {BETA}, alpha = \
         {ALPHA_DEG} deg, eta = {ETA}. Energy of lobe p = integral over all wi (solid angle) \
         of S_p(wi, wo, h), averaged over h uniform in [-1, 1], wo at theta_o = 0. Lobe columns \
         are the green channel; `total` is the sum of the lobes in R, G, B.\n"
    )?;
    writeln!(
        out,
        "| hair | eu | pheo | sigma_a (R, G, B) | {} | total (R, G, B) |",
        LOBE_NAMES.join(" | ")
    )?;
    writeln!(out, "|---|---:|---:|---|---:|---:|---:|---:|---|")?;
    let mut first = None;
    let mut all = Vec::new();
    for (name, eu, pheo) in HAIRS {
        let sigma_a = hair_sigma_a(eu, pheo)?;
        let model = ChiangHair::<f64>::new(&hair(BETA, sigma_a)?);
        let energy = lobe_energies(&model, &sphere_rule, &h_nodes, wo);
        let total: [f64; 3] = core::array::from_fn(|c| energy.iter().map(|e| e[c]).sum());
        let lobes: Vec<String> = energy.iter().map(|e| format!("{:.4}", e[1])).collect();
        writeln!(
            out,
            "| {name} | {eu} | {pheo} | {} | {} | {} |",
            triple(sigma_a, 3),
            lobes.join(" | "),
            triple(total, 4),
        )?;
        all.push(energy);
        first.get_or_insert((name, model, energy));
    }
    if let Some((name, model, energy)) = first {
        let finer_sphere = lobe_energies(&model, &sphere(s.fine_sphere), &h_nodes, wo);
        let finer_h = lobe_energies(&model, &sphere_rule, &h_rule(s.fine_h_nodes), wo);
        writeln!(
            out,
            "\nQuadrature: SphereRule::new{:?} over wi; {}-node Gauss-Legendre in \
             gamma_o = asin(h). Convergence ({name}; largest absolute change over lobes and \
             channels): {:.1e} with SphereRule::new{:?}, {:.1e} with {} nodes in gamma_o.",
            s.sphere,
            s.h_nodes,
            max_difference(&energy, &finer_sphere),
            s.fine_sphere,
            max_difference(&energy, &finer_h),
            s.fine_h_nodes,
        )?;
    }
    Ok(all)
}

/// sigma_a of the given melanin concentrations.
fn hair_sigma_a(eu: f64, pheo: f64) -> Result<[f64; 3], CliError> {
    Ok(Absorption::from_melanin(eu, pheo)?.rgb())
}

/// The white-furnace check: with sigma_a = 0 the integral of S over the sphere is 1.
fn furnace(out: &mut impl Write, s: &Settings) -> Result<(), CliError> {
    let (smooth, sharp) = (sphere(s.furnace_sphere), sphere(s.furnace_sphere_sharp));
    let mut cells = Vec::new();
    for beta in FURNACE_BETAS {
        let model = ChiangHair::<f64>::new(&hair(beta, [0.0; 3])?);
        let rule = if beta < 0.2 { &sharp } else { &smooth };
        let worst = worst_furnace(rule, s.furnace_theta_o_deg, s.furnace_h, |wi, wo, h| {
            model.eval(&Query::new(wi, wo, h))[1]
        });
        cells.push(format!("beta {beta}: {worst:+.1e}"));
    }
    writeln!(
        out,
        "\n## White furnace\n\nsigma_a = 0, beta_m = beta_n = beta: integral of S over the \
         sphere minus 1, worst over theta_o in {:?} deg and h in {:?}:\n\n{}\n\n(SphereRule::new{:?}; \
         SphereRule::new{:?} for beta < 0.2. The deviation at large beta is quadrature error: \
         the trimmed logistic N_p has a kink at +-pi from its centre, so the midpoint rule in \
         phi converges only as 1/azimuths^2.)",
        s.furnace_theta_o_deg,
        s.furnace_h,
        cells.join("; "),
        s.furnace_sphere,
        s.furnace_sphere_sharp
    )?;
    Ok(())
}

/// The furnace error (integral over `rule` of `f(wi, wo, h)` minus 1) of largest magnitude,
/// over wo at each theta_o (degrees) and each h.
fn worst_furnace(
    rule: &SphereRule,
    theta_o_deg: &[f64],
    hs: &[f64],
    f: impl Fn(V3<f64>, V3<f64>, f64) -> f64,
) -> f64 {
    let mut worst = 0.0_f64;
    for &theta_o in theta_o_deg {
        for &h in hs {
            let wo = wo_at(theta_o);
            let error = rule.integrate(|wi| f(wi, wo, h)) - 1.0;
            if error.abs() > worst.abs() {
                worst = error;
            }
        }
    }
    worst
}

/// The evaluation-speed line for f64 and f32.
fn speed(out: &mut impl Write, s: &Settings) -> Result<(), CliError> {
    let params = hair(BETA, [0.5, 0.8, 1.4])?;
    let f64_ns = ns_per_eval::<f64>(&params, s.timing_calls);
    let f32_ns = ns_per_eval::<f32>(&params, s.timing_calls);
    writeln!(
        out,
        "\n## Evaluation speed\n\n`ChiangHair::eval`: {f64_ns:.1} ns per call (f64), {f32_ns:.1} \
         ns per call (f32), over {} calls each; indicative; see `cargo bench` for criterion \
         figures.",
        s.timing_calls
    )?;
    Ok(())
}

/// Deterministic pseudo-random numbers in [0, 1) (SplitMix64).
struct SplitMix(u64);

impl SplitMix {
    fn next(&mut self) -> f64 {
        self.0 = self.0.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        (z ^ (z >> 31)) as f64 / 2f64.powi(64)
    }

    /// A direction uniform on the sphere.
    fn direction(&mut self) -> V3<f64> {
        let sin_theta = 2.0 * self.next() - 1.0;
        let cos_theta = (1.0 - sin_theta * sin_theta).max(0.0).sqrt();
        let phi = std::f64::consts::TAU * self.next() - std::f64::consts::PI;
        local_direction(sin_theta, cos_theta, phi)
    }
}

/// Mean wall-clock nanoseconds of `eval` in precision `R` over `calls` calls cycling through
/// 1024 deterministic inputs.
fn ns_per_eval<R: Real>(params: &HairParams, calls: usize) -> f64 {
    let model = ChiangHair::<R>::new(params);
    let mut rng = SplitMix(0x5eed);
    let to_r = |w: V3<f64>| V3::<R>::c(w.x, w.y, w.z);
    let inputs: Vec<(V3<R>, V3<R>, R)> = (0..1024)
        .map(|_| {
            let (wi, wo) = (rng.direction(), rng.direction());
            (to_r(wi), to_r(wo), R::c(2.0 * rng.next() - 1.0))
        })
        .collect();
    let start = Instant::now();
    for k in 0..calls {
        let (wi, wo, h) = inputs[k % inputs.len()];
        black_box(model.eval(&Query::new(black_box(wi), black_box(wo), black_box(h))));
    }
    start.elapsed().as_nanos() as f64 / calls.max(1) as f64
}

/// The far-field model of the report's tilt and index with `FAR_NODES` nodes.
fn far_model(beta_n: f64, sigma_a: [f64; 3]) -> Result<ChiangFarField<f64>, CliError> {
    let params = hair_with(BETA, beta_n, sigma_a)?;
    let rule = FarFieldRule::gauss_legendre(FAR_NODES)?;
    Ok(ChiangFarField::with_rule(&params, &rule))
}

/// The far-field lobe-energy table, one row per hair colour, with the largest difference
/// from the near-field energies `near` (same order of hair colours).
fn far_lobe_table(
    out: &mut impl Write,
    s: &Settings,
    near: &[[[f64; 3]; 4]],
) -> Result<(), CliError> {
    let sphere_rule = sphere(s.sphere);
    let wo = wo_at(0.0);
    writeln!(
        out,
        "\n### Far-field lobe energies\n\n`ChiangFarField` ({FAR_NODES} Gauss-Legendre nodes in \
         gamma = asin(h)), same hairs, roughness and wo as the near-field table: energy of \
         lobe p = integral over all wi of the far-field S_p(wi, wo). Lobe columns are the green \
         channel; `vs near` is the largest difference from the near-field table over lobes and \
         channels (the two differ only by the h quadrature).\n"
    )?;
    writeln!(
        out,
        "| hair | {} | total (R, G, B) | vs near |",
        LOBE_NAMES.join(" | ")
    )?;
    writeln!(out, "|---|---:|---:|---:|---:|---|---:|")?;
    for ((name, eu, pheo), near) in HAIRS.iter().zip(near) {
        let model = far_model(BETA, hair_sigma_a(*eu, *pheo)?)?;
        let energy = energies(
            |wi, _| {
                let l = model.eval_lobes(&Query::far(wi, wo));
                [l[0], l[1], l[2], l[3]]
            },
            &sphere_rule,
            &[(0.0, 1.0)],
        );
        let total: [f64; 3] = core::array::from_fn(|c| energy.iter().map(|e| e[c]).sum());
        let lobes: Vec<String> = energy.iter().map(|e| format!("{:.4}", e[1])).collect();
        writeln!(
            out,
            "| {name} | {} | {} | {:.1e} |",
            lobes.join(" | "),
            triple(total, 4),
            max_difference(&energy, near),
        )?;
    }
    Ok(())
}

/// The far-field white-furnace check (sigma_a = 0, beta_m = beta_n = beta).
fn far_furnace(out: &mut impl Write, s: &Settings) -> Result<(), CliError> {
    let (smooth, sharp) = (sphere(s.furnace_sphere), sphere(s.furnace_sphere_sharp));
    let mut cells = Vec::new();
    for beta in FURNACE_BETAS {
        let params = hair(beta, [0.0; 3])?;
        let rule = FarFieldRule::gauss_legendre(FAR_NODES)?;
        let model = ChiangFarField::<f64>::with_rule(&params, &rule);
        let sphere_rule = if beta < 0.2 { &sharp } else { &smooth };
        let worst = worst_furnace(sphere_rule, s.furnace_theta_o_deg, &[0.0], |wi, wo, _| {
            model.eval(&Query::far(wi, wo))[1]
        });
        cells.push(format!("beta {beta}: {worst:+.1e}"));
    }
    writeln!(
        out,
        "\n### Far-field white furnace\n\nsigma_a = 0: integral of the far-field S over the \
         sphere minus 1, worst over theta_o in {:?} deg (same sphere rules as above; the fixed \
         rule's weights sum to 1, so what remains is the sphere quadrature's error):\n\n{}",
        s.furnace_theta_o_deg,
        cells.join("; ")
    )?;
    Ok(())
}

/// A point of the integrator grid: (sin theta_o, cos theta_o, phi).
type GridPoint = (f64, f64, f64);

/// `N_p A_p` per lobe and channel.
type Azimuthal = [[f64; 3]; 4];

/// The grid of the integrator table: `phis` midpoint azimuths in (-pi, pi) for each theta_o,
/// grouped by theta_o.
fn integrator_grid(theta_o: &[f64], phis: usize) -> Vec<GridPoint> {
    let tau = std::f64::consts::TAU;
    let mut grid = Vec::with_capacity(theta_o.len() * phis);
    for &t in theta_o {
        for k in 0..phis {
            let phi = -std::f64::consts::PI + (k as f64 + 0.5) * tau / phis as f64;
            grid.push((t.sin(), t.cos(), phi));
        }
    }
    grid
}

/// The reference `N_p A_p` at every grid point with relative tolerance `tol`, and the mean
/// wall-clock microseconds per call.
fn reference_values(hair: &ChiangHair<f64>, grid: &[GridPoint], tol: f64) -> (Vec<Azimuthal>, f64) {
    let start = Instant::now();
    let values: Vec<Azimuthal> = grid
        .iter()
        .map(|&(sin_o, cos_o, phi)| hair.far_field_azimuthal_reference(sin_o, cos_o, phi, tol).0)
        .collect();
    let us = start.elapsed().as_secs_f64() * 1e6 / grid.len().max(1) as f64;
    (values, us)
}

/// For each theta_o group of `phis` grid points, the largest `|N_p|` over phi of each lobe and
/// channel (of the reference `values`), repeated for every point of the group.
fn peaks(values: &[Azimuthal], phis: usize) -> Vec<Azimuthal> {
    let mut out = Vec::with_capacity(values.len());
    for group in values.chunks(phis) {
        let mut peak = [[0.0_f64; 3]; 4];
        for value in group {
            for (pk, v) in peak.iter_mut().flatten().zip(value.iter().flatten()) {
                *pk = pk.max(v.abs());
            }
        }
        out.extend(std::iter::repeat_n(peak, group.len()));
    }
    out
}

/// Smallest peak that takes part in the error statistics (lobes absorbed below it carry no
/// energy worth measuring).
const PEAK_FLOOR: f64 = 1e-12;

/// Max and mean over points, lobes and channels of `|approx - reference| / peak`, skipping
/// (lobe, channel) pairs whose peak is below [`PEAK_FLOOR`].
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

/// The fixed rule's `N_p A_p` with `n` nodes at every grid point.
fn fast_values(
    params: &HairParams,
    n: usize,
    grid: &[GridPoint],
) -> Result<Vec<Azimuthal>, CliError> {
    let rule = FarFieldRule::gauss_legendre(n)?;
    let far = ChiangFarField::<f64>::with_rule(params, &rule);
    Ok(grid
        .iter()
        .map(|&(s, c, phi)| far.azimuthal(s, c, phi).0)
        .collect())
}

/// One row of the integrator table: for `beta_n`, the reference's cost and refinement and the
/// fixed rule's (max, mean) error for each node count.
fn integrator_row(beta_n: f64, grid: &[GridPoint], s: &Settings) -> Result<String, CliError> {
    let params = hair_with(BETA, beta_n, INTEGRATOR_SIGMA_A)?;
    let hair = ChiangHair::<f64>::new(&params);
    let (reference, us) = reference_values(&hair, grid, REFERENCE_TOL);
    let peak = peaks(&reference, s.integrator_phis);
    let refinement = refinement(&hair, grid, &reference, &peak, s.refine_every);
    let mut cells = vec![format!("{beta_n}"), format!("{us:.0}"), refinement];
    for n in INTEGRATOR_NODES {
        let fast = fast_values(&params, n, grid)?;
        let (worst, mean) = error_stats(fast.into_iter().enumerate(), &reference, &peak);
        cells.push(format!("{worst:.1e} / {mean:.1e}"));
    }
    Ok(format!("| {} |", cells.join(" | ")))
}

/// The reference's own error: max over every `every`-th grid point of its difference from the
/// reference at [`REFINED_TOL`], relative to the peaks, formatted.
fn refinement(
    hair: &ChiangHair<f64>,
    grid: &[GridPoint],
    reference: &[Azimuthal],
    peak: &[Azimuthal],
    every: usize,
) -> String {
    let subset: Vec<usize> = (0..grid.len()).step_by(every).collect();
    let points: Vec<GridPoint> = subset.iter().map(|&i| grid[i]).collect();
    let (refined, _) = reference_values(hair, &points, REFINED_TOL);
    let (worst, _) = error_stats(subset.into_iter().zip(refined), reference, peak);
    format!("{worst:.0e}")
}

/// Mean wall-clock nanoseconds of one fixed-rule `N_p` evaluation (`ChiangFarField::azimuthal`,
/// all lobes and channels) with `n` nodes, over about `node_evals / n` calls cycling over `grid`.
fn ns_per_azimuthal(n: usize, grid: &[GridPoint], node_evals: usize) -> Result<f64, CliError> {
    let params = hair_with(BETA, BETA, INTEGRATOR_SIGMA_A)?;
    let rule = FarFieldRule::gauss_legendre(n)?;
    let far = ChiangFarField::<f64>::with_rule(&params, &rule);
    let calls = (node_evals / n).max(grid.len()).max(1);
    let start = Instant::now();
    for k in 0..calls {
        let (sin_o, cos_o, phi) = grid[k % grid.len()];
        black_box(far.azimuthal(black_box(sin_o), black_box(cos_o), black_box(phi)));
    }
    Ok(start.elapsed().as_nanos() as f64 / calls as f64)
}

/// The integrator table: accuracy and cost of the fixed rule against the adaptive reference.
fn integrator_table(out: &mut impl Write, s: &Settings) -> Result<(), CliError> {
    let grid = integrator_grid(s.integrator_theta_o, s.integrator_phis);
    writeln!(
        out,
        "\n### Far-field integrator\n\nError of the fixed N-node rule's N_p \
         (`ChiangFarField::azimuthal`) against the adaptive reference \
         (`far_field_azimuthal_reference`, rel_tol {REFERENCE_TOL:e}), relative to the peak over \
         phi of each lobe's N_p: max / mean over lobes R, TT, TRT, residual, channels with \
         sigma_a = {INTEGRATOR_SIGMA_A:?}, {} phi per theta_o and theta_o in {:?} rad (lobes \
         whose peak is below {PEAK_FLOOR:e} are skipped). beta_m = {BETA}, alpha = {ALPHA_DEG} \
         deg, eta = {ETA}. `ref us`: microseconds per reference call. `ref refinement`: the \
         reference's own error, its max difference (same measure) from rel_tol {REFINED_TOL:e} \
         on every {}th grid point. `ns per fast N_p`: \
         one `azimuthal` call (all lobes and channels), indicative.\n",
        s.integrator_phis, s.integrator_theta_o, s.refine_every,
    )?;
    let heads: Vec<String> = INTEGRATOR_NODES
        .iter()
        .map(|n| format!("N = {n}"))
        .collect();
    writeln!(
        out,
        "| beta_n | ref us | ref refinement | {} |",
        heads.join(" | ")
    )?;
    writeln!(
        out,
        "|---:|---:|---:|{}",
        "---:|".repeat(INTEGRATOR_NODES.len())
    )?;
    for &beta_n in s.integrator_beta_n {
        writeln!(out, "{}", integrator_row(beta_n, &grid, s)?)?;
    }
    let mut times = Vec::new();
    for n in INTEGRATOR_NODES {
        times.push(format!(
            "{:.0}",
            ns_per_azimuthal(n, &grid, s.integrator_timing_nodes)?
        ));
    }
    writeln!(out, "| ns per fast N_p | | | {} |", times.join(" | "))?;
    Ok(())
}

/// The summary of `hairmath fit`: every regenerated constant beside its published value.
fn fitted_constants(out: &mut impl Write) -> Result<(), CliError> {
    writeln!(out, "\n## Fitted constants (`hairmath fit`, eta = {ETA})\n")?;
    let (_, fits) = crate::fit::fits(ETA)?;
    crate::fit::table(out, &fits.records)?;
    Ok(())
}
