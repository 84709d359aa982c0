//! `hairmath report`: the figures of [`hairmath::diagnostics::report`] (lobe energies of a few
//! hair colours, white-furnace checks and an indicative evaluation speed of the near-field
//! model; the same energies and furnace for the far-field model and the accuracy and cost of
//! its fixed-node integrator against the adaptive reference) and the fitted constants, as
//! markdown or JSON on stdout. This file only formats: every number comes from the library.

use crate::approximations;
use crate::{with_stdout, CliError};
use clap::Args;
use hairmath::bcsdf::CHIANG_LOBES;
use hairmath::diagnostics::{
    report_with_progress, EnergyConvergence, EvalTiming, Furnace, FurnaceRow, HairEnergies,
    IntegratorTable, LobeEnergies, Report, ReportDetail, ReportSettings, FAR_NODES,
    INTEGRATOR_SIGMA_A, PEAK_FLOOR, REFERENCE_TOL, REFINED_TOL, REPORT_ALPHA_DEG, REPORT_BETA,
    REPORT_ETA, SHARP_BETA,
};
use hairmath::fit::{compare_models, ComparisonSettings, ConstantFit, ModelRow};
use hairmath::plan::{Catalogue, PlanSettings};
use serde_json::{json, Value};
use std::io::{self, Write};

/// Arguments of `hairmath report`.
#[derive(Args, Debug)]
pub struct ReportArgs {
    /// Shrink every quadrature and the timing loop (for tests; the numbers become rough).
    #[arg(long)]
    quick: bool,
    /// Print the report as one JSON object instead of markdown, for scripts.
    ///
    /// The object's keys (angles in degrees where the key says `_deg`, else radians; RGB
    /// triples as [r, g, b] arrays; sphere rules as [theta_panels, order, azimuths]):
    ///
    /// - `detail`: "quick" or "full".
    /// - `hair`: `beta`, `alpha_deg`, `eta` (the report's roughness, tilt and index).
    /// - `lobe_energies`: `sphere`, `offset_nodes` (near field, Gauss-Legendre in asin h),
    ///   `far_nodes`, `theta_o_deg`, `lobes` (names), `hairs` (one object per colour: `name`,
    ///   `eumelanin`, `pheomelanin`, `sigma_a`, `near` and `far` (each `lobes`, an object of
    ///   RGB energies by lobe name, and `total`), `far_vs_near`), and `convergence` (`hair`,
    ///   `fine_sphere`, `fine_sphere_change`, `fine_offset_nodes`, `fine_offset_change`).
    /// - `furnace`: `theta_o_deg`, `h`, `sharp_beta`, `rows` (one per beta: `beta`, `sphere`,
    ///   `near` and `far`, each `worst_error` and `cases`, a list of `theta_o_deg`, `h`,
    ///   `albedo`, `error`).
    /// - `timing`: `calls`, `ns_per_call_f64`, `ns_per_call_f32`.
    /// - `integrator`: `beta_m`, `sigma_a`, `theta_o`, `phis`, `refine_every`,
    ///   `reference_rel_tol`, `refined_rel_tol`, `peak_floor`, `nodes`, `rows` (one per beta_n:
    ///   `beta_n`, `reference_us`, `reference_refinement`, `errors`, a list of `nodes`, `max`,
    ///   `mean`) and `timings` (a list of `nodes`, `ns`).
    /// - `fitted_constants`: the rows of `hairmath fit --json`.
    /// - `models`: the rows of `hairmath models --dark-brown --json` (with --quick on fewer
    ///   direction pairs).
    /// - `approximations`: one object per example scene (`examples/scenes/`): `scene`,
    ///   `budget`, `combinations`, `plan` (`composition`, `error`, `cost`), `published` (per
    ///   model: `model`, `error`, `cost`, `dominated`), `options` (every lobe option of the
    ///   planner: `lobe`, `option`, `kept`, `far_field_nodes`, `table`, `error`, `cost`) and
    ///   `front` (the Pareto front: `composition`, `error`, `cost`).
    ///
    /// The timings (`ns_per_call_*`, `reference_us`, `ns`) are wall-clock and vary from run
    /// to run; every other value is deterministic.
    #[arg(long, verbatim_doc_comment)]
    json: bool,
    /// Also write SVG plots into this directory (created if missing): for each example
    /// scene, `front-<scene>.svg` (the Pareto front, cost against error, log-log, with the
    /// published models and the plan marked) and `lobes-<scene>.svg` (S against phi at a few
    /// inclinations, every model against the reference).
    #[arg(long, value_name = "DIR")]
    plots: Option<std::path::PathBuf>,
}

/// Runs `hairmath report`.
pub fn run(args: &ReportArgs) -> Result<(), CliError> {
    let detail = if args.quick {
        ReportDetail::Quick
    } else {
        ReportDetail::Full
    };
    // A plot folder that cannot be made is reported before the report's work, not after it.
    if let Some(dir) = &args.plots {
        crate::create_dir(dir)?;
    }
    // One bar per stage on a terminal's stderr (crate::progress); the catalogues are the
    // last stages, one per example scene.
    let bar = crate::progress::bar("report 1/4: figures");
    let report = report_with_progress(
        &ReportSettings::new(detail),
        &crate::progress::callback(&bar),
    );
    bar.finish_and_clear();
    let report = report?;
    let bar = crate::progress::bar("report 2/4: fits");
    let fits = crate::fit::fits_with_progress(REPORT_ETA, &crate::progress::callback(&bar));
    bar.finish_and_clear();
    let (_, fits) = fits?;
    let models = if args.quick {
        ComparisonSettings::quick()
    } else {
        ComparisonSettings::dark_brown()
    };
    let bar = crate::progress::bar("report 3/4: models (rows)");
    let rows = compare_models(&models, &crate::progress::callback(&bar));
    bar.finish_and_clear();
    let rows = rows?;
    let plan_settings = if args.quick {
        PlanSettings::quick()
    } else {
        PlanSettings::default()
    };
    let catalogues = approximations::catalogues(&plan_settings)?;
    if let Some(dir) = &args.plots {
        for file in crate::plots::write(dir, &catalogues)? {
            // A progress note: an unwritable stderr does not fail the report.
            let _ = writeln!(io::stderr(), "wrote {}", file.display());
        }
    }
    with_stdout(|out| {
        let written = if args.json {
            let mut value = json(&report, &fits.records);
            value["models"] = rows
                .iter()
                .map(|r| crate::models::row_json(r, &models))
                .collect();
            value["approximations"] = approximations::json(&catalogues);
            serde_json::to_string_pretty(&value)
                .map_err(io::Error::other)
                .and_then(|text| writeln!(out, "{text}"))
        } else {
            full_markdown(out, &report, &fits.records, &rows, &models, &catalogues)
        };
        written.map_err(CliError::stdout)
    })
}

/// The report, the real-time models and the approximations, as markdown.
fn full_markdown(
    out: &mut impl Write,
    report: &Report,
    fits: &[ConstantFit],
    rows: &[ModelRow],
    models: &ComparisonSettings,
    catalogues: &[(&str, Catalogue)],
) -> io::Result<()> {
    markdown(out, report, fits)?;
    writeln!(
        out,
        "\n## Real-time models (`hairmath models`, dark brown hair, beta_m = beta_n = 0.3)\n"
    )?;
    crate::models::markdown(out, rows, models)?;
    approximations::markdown(out, catalogues)
}

// ---------------------------------------------------------------------------------------------
// Markdown.

/// The whole report as markdown.
fn markdown(out: &mut impl Write, r: &Report, fits: &[ConstantFit]) -> io::Result<()> {
    writeln!(out, "# hairmath report")?;
    if r.settings.detail == ReportDetail::Quick {
        writeln!(out, "\n*--quick: coarse quadrature, numbers are rough.*")?;
    }
    lobe_table(out, r)?;
    furnace(out, r)?;
    speed(out, &r.timing)?;
    writeln!(out, "\n## Far field")?;
    far_lobe_table(out, r)?;
    far_furnace(out, r)?;
    integrator_table(out, r)?;
    writeln!(
        out,
        "\n## Fitted constants (`hairmath fit`, eta = {REPORT_ETA})\n"
    )?;
    crate::fit::table(out, fits)
}

/// One markdown table row: the cells between pipes.
fn row(out: &mut impl Write, cells: &[String]) -> io::Result<()> {
    writeln!(out, "| {} |", cells.join(" | "))
}

/// Three numbers as `a, b, c` with `decimals` decimals.
fn triple(v: [f64; 3], decimals: usize) -> String {
    format!(
        "{:.decimals$}, {:.decimals$}, {:.decimals$}",
        v[0], v[1], v[2]
    )
}

/// The green channel of each lobe (4 decimals), then the total in R, G, B.
fn energy_cells(e: &LobeEnergies) -> Vec<String> {
    let mut cells: Vec<String> = e.lobes.iter().map(|l| format!("{:.4}", l[1])).collect();
    cells.push(triple(e.total, 4));
    cells
}

/// The near-field lobe-energy table, one row per hair colour, and its convergence check.
fn lobe_table(out: &mut impl Write, r: &Report) -> io::Result<()> {
    writeln!(
        out,
        "\n## Lobe energies\n\nChiang 2016 (pbrt-v4): beta_m = beta_n = {REPORT_BETA}, alpha = \
         {REPORT_ALPHA_DEG} deg, eta = {REPORT_ETA}. Energy of lobe p = integral over all wi \
         (solid angle) of S_p(wi, wo, h), averaged over h uniform in [-1, 1], wo at theta_o = 0. \
         Lobe columns are the green channel; `total` is the sum of the lobes in R, G, B.\n"
    )?;
    let mut head: Vec<String> = ["hair", "eu", "pheo", "sigma_a (R, G, B)"]
        .map(String::from)
        .to_vec();
    head.extend(CHIANG_LOBES.map(String::from));
    head.push("total (R, G, B)".into());
    row(out, &head)?;
    writeln!(out, "|---|---:|---:|---|---:|---:|---:|---:|---|")?;
    for hair in &r.hairs {
        let mut cells = vec![
            hair.name.to_string(),
            format!("{}", hair.eumelanin),
            format!("{}", hair.pheomelanin),
            triple(hair.sigma_a, 3),
        ];
        cells.extend(energy_cells(&hair.near));
        row(out, &cells)?;
    }
    let s = &r.settings;
    let c: &EnergyConvergence = &r.convergence;
    writeln!(
        out,
        "\nQuadrature: SphereRule::new{} over wi; {}-node Gauss-Legendre in gamma_o = asin(h). \
         Convergence ({}; largest absolute change over lobes and channels): {:.1e} with \
         SphereRule::new{}, {:.1e} with {} nodes in gamma_o.",
        s.sphere,
        s.offset_nodes,
        c.hair,
        c.fine_sphere_change,
        s.fine_sphere,
        c.fine_offset_change,
        s.fine_offset_nodes,
    )
}

/// `beta B: E; ...` with each row's worst error of `model` (near or far).
fn furnace_cells(rows: &[FurnaceRow], model: impl Fn(&FurnaceRow) -> &Furnace) -> String {
    let cells: Vec<String> = rows
        .iter()
        .map(|f| format!("beta {}: {:+.1e}", f.beta, model(f).worst_error))
        .collect();
    cells.join("; ")
}

/// The near-field white-furnace check.
fn furnace(out: &mut impl Write, r: &Report) -> io::Result<()> {
    let s = &r.settings;
    writeln!(
        out,
        "\n## White furnace\n\nsigma_a = 0, beta_m = beta_n = beta: integral of S over the \
         sphere minus 1, worst over theta_o in {:?} deg and h in {:?}:\n\n{}\n\n\
         (SphereRule::new{}; SphereRule::new{} for beta < {SHARP_BETA}. The deviation at large \
         beta is quadrature error: the trimmed logistic N_p has a kink at +-pi from its centre, \
         so the midpoint rule in phi converges only as 1/azimuths^2.)",
        s.furnace_theta_o_deg,
        s.furnace_h,
        furnace_cells(&r.furnace, |f| &f.near),
        s.furnace_sphere,
        s.furnace_sphere_sharp,
    )
}

/// The evaluation-speed line.
fn speed(out: &mut impl Write, t: &EvalTiming) -> io::Result<()> {
    writeln!(
        out,
        "\n## Evaluation speed\n\n`ChiangHair::eval`: {:.1} ns per call (f64), {:.1} ns per call \
         (f32), over {} calls each; indicative; see `cargo bench` for criterion figures.",
        t.ns_f64, t.ns_f32, t.calls
    )
}

/// The far-field lobe-energy table with the difference from the near-field table.
fn far_lobe_table(out: &mut impl Write, r: &Report) -> io::Result<()> {
    writeln!(
        out,
        "\n### Far-field lobe energies\n\n`ChiangFarField` ({FAR_NODES} Gauss-Legendre nodes in \
         gamma = asin(h)), same hairs, roughness and wo as the near-field table: energy of \
         lobe p = integral over all wi of the far-field S_p(wi, wo). Lobe columns are the green \
         channel; `vs near` is the largest difference from the near-field table over lobes and \
         channels (the two differ only by the h quadrature).\n"
    )?;
    let mut head = vec!["hair".to_string()];
    head.extend(CHIANG_LOBES.map(String::from));
    head.extend(["total (R, G, B)", "vs near"].map(String::from));
    row(out, &head)?;
    writeln!(out, "|---|---:|---:|---:|---:|---|---:|")?;
    for hair in &r.hairs {
        let mut cells = vec![hair.name.to_string()];
        cells.extend(energy_cells(&hair.far));
        cells.push(format!("{:.1e}", hair.far_vs_near));
        row(out, &cells)?;
    }
    Ok(())
}

/// The far-field white-furnace check.
fn far_furnace(out: &mut impl Write, r: &Report) -> io::Result<()> {
    writeln!(
        out,
        "\n### Far-field white furnace\n\nsigma_a = 0: integral of the far-field S over the \
         sphere minus 1, worst over theta_o in {:?} deg (same sphere rules as above; the fixed \
         rule's weights sum to 1, so what remains is the sphere quadrature's error):\n\n{}",
        r.settings.furnace_theta_o_deg,
        furnace_cells(&r.furnace, |f| &f.far),
    )
}

/// The integrator table: accuracy and cost of the fixed rule against the adaptive reference.
fn integrator_table(out: &mut impl Write, r: &Report) -> io::Result<()> {
    let s = &r.settings.integrator;
    writeln!(
        out,
        "\n### Far-field integrator\n\nError of the fixed N-node rule's N_p \
         (`ChiangFarField::azimuthal`) against the adaptive reference \
         (`far_field_azimuthal_reference`, rel_tol {REFERENCE_TOL:e}), relative to the peak over \
         phi of each lobe's N_p: max / mean over lobes R, TT, TRT, residual, channels with \
         sigma_a = {INTEGRATOR_SIGMA_A:?}, {} phi per theta_o and theta_o in {:?} rad (lobes \
         whose peak is below {PEAK_FLOOR:e} are skipped). beta_m = {REPORT_BETA}, alpha = \
         {REPORT_ALPHA_DEG} deg, eta = {REPORT_ETA}. `ref us`: microseconds per reference call. \
         `ref refinement`: the reference's own error, its max difference (same measure) from \
         rel_tol {REFINED_TOL:e} on every {}th grid point. `ns per fast N_p`: one `azimuthal` \
         call (all lobes and channels), indicative.\n",
        s.phis, s.theta_o, s.refine_every,
    )?;
    let table: &IntegratorTable = &r.integrator;
    let mut head: Vec<String> = ["beta_n", "ref us", "ref refinement"]
        .map(String::from)
        .to_vec();
    head.extend(s.nodes.iter().map(|n| format!("N = {n}")));
    row(out, &head)?;
    writeln!(out, "|---:|---:|---:|{}", "---:|".repeat(s.nodes.len()))?;
    for line in &table.rows {
        let mut cells = vec![
            format!("{}", line.beta_n),
            format!("{:.0}", line.reference_us),
            format!("{:.0e}", line.reference_refinement),
        ];
        cells.extend(
            line.errors
                .iter()
                .map(|e| format!("{:.1e} / {:.1e}", e.max, e.mean)),
        );
        row(out, &cells)?;
    }
    let times: Vec<String> = table
        .timings
        .iter()
        .map(|t| format!("{:.0}", t.ns))
        .collect();
    writeln!(out, "| ns per fast N_p | | | {} |", times.join(" | "))
}

// ---------------------------------------------------------------------------------------------
// JSON (keys documented on `ReportArgs::json`).

/// The whole report as one JSON object.
fn json(r: &Report, fits: &[ConstantFit]) -> Value {
    let s = &r.settings;
    let c = &r.convergence;
    json!({
        "detail": match s.detail {
            ReportDetail::Quick => "quick",
            ReportDetail::Full => "full",
        },
        "hair": { "beta": REPORT_BETA, "alpha_deg": REPORT_ALPHA_DEG, "eta": REPORT_ETA },
        "lobe_energies": {
            "sphere": s.sphere.to_array(),
            "offset_nodes": s.offset_nodes,
            "far_nodes": FAR_NODES,
            "theta_o_deg": 0.0,
            "lobes": CHIANG_LOBES,
            "hairs": r.hairs.iter().map(hair_json).collect::<Vec<_>>(),
            "convergence": {
                "hair": c.hair,
                "fine_sphere": s.fine_sphere.to_array(),
                "fine_sphere_change": c.fine_sphere_change,
                "fine_offset_nodes": s.fine_offset_nodes,
                "fine_offset_change": c.fine_offset_change,
            },
        },
        "furnace": {
            "theta_o_deg": s.furnace_theta_o_deg,
            "h": s.furnace_h,
            "sharp_beta": SHARP_BETA,
            "rows": r.furnace.iter().map(|f| json!({
                "beta": f.beta,
                "sphere": f.sphere.to_array(),
                "near": furnace_json(&f.near),
                "far": furnace_json(&f.far),
            })).collect::<Vec<_>>(),
        },
        "timing": {
            "calls": r.timing.calls,
            "ns_per_call_f64": r.timing.ns_f64,
            "ns_per_call_f32": r.timing.ns_f32,
        },
        "integrator": integrator_json(r),
        "fitted_constants": crate::fit::json_rows(fits),
    })
}

/// One hair colour's energies.
fn hair_json(h: &HairEnergies) -> Value {
    json!({
        "name": h.name,
        "eumelanin": h.eumelanin,
        "pheomelanin": h.pheomelanin,
        "sigma_a": h.sigma_a,
        "near": energies_json(&h.near),
        "far": energies_json(&h.far),
        "far_vs_near": h.far_vs_near,
    })
}

/// Lobe energies: `lobes` by name and `total`.
fn energies_json(e: &LobeEnergies) -> Value {
    let lobes: serde_json::Map<String, Value> = e
        .names
        .iter()
        .zip(&e.lobes)
        .map(|(name, v)| (name.to_string(), json!(v)))
        .collect();
    json!({ "lobes": lobes, "total": e.total })
}

/// A furnace check: its worst error and every case.
fn furnace_json(f: &Furnace) -> Value {
    let cases: Vec<Value> = f
        .cases
        .iter()
        .map(|c| {
            json!({
                "theta_o_deg": c.theta_o_deg,
                "h": c.h,
                "albedo": c.albedo,
                "error": c.error,
            })
        })
        .collect();
    json!({ "worst_error": f.worst_error, "cases": cases })
}

/// The integrator table with its settings.
fn integrator_json(r: &Report) -> Value {
    let s = &r.settings.integrator;
    let rows: Vec<Value> = r
        .integrator
        .rows
        .iter()
        .map(|line| {
            let errors: Vec<Value> = line
                .errors
                .iter()
                .map(|e| json!({ "nodes": e.nodes, "max": e.max, "mean": e.mean }))
                .collect();
            json!({
                "beta_n": line.beta_n,
                "reference_us": line.reference_us,
                "reference_refinement": line.reference_refinement,
                "errors": errors,
            })
        })
        .collect();
    let timings: Vec<Value> = r
        .integrator
        .timings
        .iter()
        .map(|t| json!({ "nodes": t.nodes, "ns": t.ns }))
        .collect();
    json!({
        "beta_m": REPORT_BETA,
        "sigma_a": INTEGRATOR_SIGMA_A,
        "theta_o": s.theta_o,
        "phis": s.phis,
        "refine_every": s.refine_every,
        "reference_rel_tol": REFERENCE_TOL,
        "refined_rel_tol": REFINED_TOL,
        "peak_floor": PEAK_FLOOR,
        "nodes": s.nodes,
        "rows": rows,
        "timings": timings,
    })
}
