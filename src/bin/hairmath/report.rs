//! `hairmath report`: lobe energies of a few hair colours, a white-furnace check and an
//! indicative evaluation speed, as markdown on stdout.

use crate::CliError;
use clap::Args;
use hairmath::absorption::sigma_a_from_melanin;
use hairmath::bcsdf::{ChiangHair, ChiangParams};
use hairmath::geometry::{local_direction, V3};
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
    lobe_table(&mut out, &settings)?;
    furnace(&mut out, &settings)?;
    speed(&mut out, &settings)?;
    out.flush()?;
    Ok(())
}

/// The Chiang model with the report's roughness, tilt and index and the given absorption.
fn hair(beta: f64, sigma_a: [f64; 3]) -> Result<ChiangParams, CliError> {
    ChiangParams::new(beta, beta, ALPHA_DEG.to_radians(), ETA, sigma_a)
        .map_err(|e| CliError::Params(e.to_string()))
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
    let mut energy = [[0.0; 3]; 4];
    for &(h, h_weight) in h_rule {
        for &(wi, weight) in &sphere.nodes {
            let lobes = hair.eval_lobes(wi, wo, h);
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

/// The lobe-energy table, one row per hair colour, and its convergence check.
fn lobe_table(out: &mut impl Write, s: &Settings) -> Result<(), CliError> {
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
    for (name, eu, pheo) in HAIRS {
        let sigma_a =
            sigma_a_from_melanin(eu, pheo).map_err(|e| CliError::Params(e.to_string()))?;
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
    Ok(())
}

/// The white-furnace check: with sigma_a = 0 the integral of S over the sphere is 1.
fn furnace(out: &mut impl Write, s: &Settings) -> Result<(), CliError> {
    let (smooth, sharp) = (sphere(s.furnace_sphere), sphere(s.furnace_sphere_sharp));
    let mut cells = Vec::new();
    for beta in FURNACE_BETAS {
        let model = ChiangHair::<f64>::new(&hair(beta, [0.0; 3])?);
        let rule = if beta < 0.2 { &sharp } else { &smooth };
        let mut worst = 0.0_f64;
        for &theta_o in s.furnace_theta_o_deg {
            for &h in s.furnace_h {
                let wo = wo_at(theta_o);
                let error = rule.integrate(|wi| model.eval(wi, wo, h)[1]) - 1.0;
                if error.abs() > worst.abs() {
                    worst = error;
                }
            }
        }
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
fn ns_per_eval<R: Real>(params: &ChiangParams, calls: usize) -> f64 {
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
        black_box(model.eval(black_box(wi), black_box(wo), black_box(h)));
    }
    start.elapsed().as_nanos() as f64 / calls.max(1) as f64
}
