//! `hairmath report`: its JSON has the documented keys and the library's values
//! (`hairmath::diagnostics::report`), and its markdown prints the library's numbers.

use hairmath::bcsdf::CHIANG_LOBES;
use hairmath::diagnostics::{
    report, Furnace, LobeEnergies, Report, ReportDetail, ReportSettings, FAR_NODES,
    INTEGRATOR_SIGMA_A, PEAK_FLOOR, REFERENCE_TOL, REFINED_TOL, REPORT_ALPHA_DEG, REPORT_BETA,
    REPORT_ETA, SHARP_BETA,
};
use hairmath::plan::EXAMPLE_SCENES;
mod common;

use common::{hairmath, num, same};
use serde_json::Value;
use std::sync::OnceLock;

/// The library's quick report, computed once for every test.
fn library() -> &'static Report {
    static REPORT: OnceLock<Report> = OnceLock::new();
    REPORT.get_or_init(|| report(&ReportSettings::new(ReportDetail::Quick)).unwrap())
}

/// The JSON list `json` is `values`, element by element as [`same`].
fn same_all(json: &Value, values: &[f64]) {
    let list = json
        .as_array()
        .unwrap_or_else(|| panic!("{json} is not an array"));
    assert_eq!(list.len(), values.len(), "{json}");
    for (j, v) in list.iter().zip(values) {
        same(j, *v);
    }
}

/// The keys of an object, sorted.
fn keys(value: &Value) -> Vec<&str> {
    let mut k: Vec<&str> = value
        .as_object()
        .unwrap_or_else(|| panic!("{value} is not an object"))
        .keys()
        .map(String::as_str)
        .collect();
    k.sort_unstable();
    k
}

/// `keys` of `value` are exactly `expected` (any order).
fn assert_keys(value: &Value, expected: &[&str]) {
    let mut expected = expected.to_vec();
    expected.sort_unstable();
    assert_eq!(keys(value), expected, "in {value}");
}

/// A JSON energy table equals the library's: `lobes` by name and `total`.
fn assert_energies(json: &Value, lib: &LobeEnergies) {
    assert_keys(json, &["lobes", "total"]);
    assert_keys(&json["lobes"], lib.names);
    for (name, value) in lib.names.iter().zip(&lib.lobes) {
        same_all(&json["lobes"][name], value);
    }
    same_all(&json["total"], &lib.total);
}

/// A JSON furnace equals the library's.
fn assert_furnace(json: &Value, lib: &Furnace) {
    assert_keys(json, &["worst_error", "cases"]);
    same(&json["worst_error"], lib.worst_error);
    let cases = json["cases"].as_array().unwrap();
    assert_eq!(cases.len(), lib.cases.len());
    for (j, c) in cases.iter().zip(&lib.cases) {
        assert_keys(j, &["theta_o_deg", "h", "albedo", "error"]);
        same(&j["theta_o_deg"], c.theta_o_deg);
        same(&j["h"], c.h);
        same_all(&j["albedo"], &c.albedo);
        same(&j["error"], c.error);
    }
}

/// A timing: finite and positive (the value itself varies from run to run).
fn assert_timing(value: &Value) {
    let t = num(value);
    assert!(t.is_finite() && t > 0.0, "{value}");
}

/// `--plots DIR` wrote a front and a lobe plot per example scene, each an SVG document.
fn assert_plots(dir: &std::path::Path) {
    for (scene, _) in EXAMPLE_SCENES {
        for kind in ["front", "lobes"] {
            let path = dir.join(format!("{kind}-{scene}.svg"));
            let svg = std::fs::read_to_string(&path)
                .unwrap_or_else(|e| panic!("{} not written: {e}", path.display()));
            assert!(svg.trim_start().starts_with("<svg"), "{}", path.display());
            assert!(svg.contains(scene), "{} has no title", path.display());
        }
    }
    std::fs::remove_dir_all(dir).unwrap();
}

/// The approximations are the library's catalogues of the example scenes.
fn assert_approximations(json: &Value) {
    let scenes = json.as_array().expect("a list of scenes");
    assert_eq!(scenes.len(), EXAMPLE_SCENES.len());
    for ((name, _), scene) in EXAMPLE_SCENES.iter().zip(scenes) {
        assert_keys(
            scene,
            &[
                "scene",
                "budget",
                "combinations",
                "plan",
                "published",
                "options",
                "front",
            ],
        );
        assert_eq!(scene["scene"], *name);
        assert_keys(&scene["plan"], &["composition", "error", "cost"]);
        assert!(num(&scene["plan"]["error"]) <= num(&scene["budget"]));
        let front = scene["front"].as_array().unwrap();
        assert!(front.len() >= 3, "{name}: front {front:?}");
        for pair in front.windows(2) {
            assert!(num(&pair[0]["cost"]) < num(&pair[1]["cost"]));
            assert!(num(&pair[0]["error"]) > num(&pair[1]["error"]));
        }
        let published = scene["published"].as_array().unwrap();
        assert!(published.len() >= 6, "{name}");
        for p in published {
            assert_keys(p, &["model", "error", "cost", "dominated"]);
        }
        let options = scene["options"].as_array().unwrap();
        assert!(options.len() >= 8, "{name}");
        // The example scenes fix eta and the melanins: Gerard's and Nguyen and Donnelly's
        // tables are offered.
        assert!(
            options.iter().any(|o| !o["marschner_table"].is_null()),
            "{name}"
        );
        for o in options {
            assert_keys(
                o,
                &[
                    "lobe",
                    "option",
                    "kept",
                    "far_field_nodes",
                    "table",
                    "marschner_table",
                    "error",
                    "cost",
                ],
            );
            if !o["table"].is_null() {
                assert_keys(&o["table"], &["phi", "theta_o", "beta_n"]);
            }
            if !o["marschner_table"].is_null() {
                assert_keys(&o["marschner_table"], &["phi", "theta_d"]);
            }
        }
    }
}

#[test]
fn report_quick_json_has_the_documented_keys_and_the_library_values() {
    let plots = std::env::temp_dir().join(format!("hairmath-report-plots-{}", std::process::id()));
    let text = hairmath(&[
        "report",
        "--quick",
        "--json",
        "--plots",
        plots.to_str().unwrap(),
    ]);
    let json: Value = serde_json::from_str(&text).expect("the output is JSON");
    assert_plots(&plots);
    assert_approximations(&json["approximations"]);
    let lib = library();
    let s = &lib.settings;
    assert_keys(
        &json,
        &[
            "detail",
            "hair",
            "lobe_energies",
            "furnace",
            "timing",
            "integrator",
            "fitted_constants",
            "models",
            "approximations",
        ],
    );
    assert_eq!(json["detail"], "quick");
    assert_keys(&json["hair"], &["beta", "alpha_deg", "eta"]);
    same(&json["hair"]["beta"], REPORT_BETA);
    same(&json["hair"]["alpha_deg"], REPORT_ALPHA_DEG);
    same(&json["hair"]["eta"], REPORT_ETA);

    // Lobe energies.
    let e = &json["lobe_energies"];
    assert_keys(
        e,
        &[
            "sphere",
            "offset_nodes",
            "far_nodes",
            "theta_o_deg",
            "lobes",
            "hairs",
            "convergence",
        ],
    );
    same_all(&e["sphere"], &s.sphere.to_array().map(|n| n as f64));
    same(&e["offset_nodes"], s.offset_nodes as f64);
    same(&e["far_nodes"], FAR_NODES as f64);
    same(&e["theta_o_deg"], 0.0);
    let lobes: Vec<&str> = e["lobes"]
        .as_array()
        .unwrap()
        .iter()
        .map(|v| v.as_str().unwrap())
        .collect();
    assert_eq!(lobes, CHIANG_LOBES);
    let hairs = e["hairs"].as_array().unwrap();
    assert_eq!(hairs.len(), lib.hairs.len());
    for (j, h) in hairs.iter().zip(&lib.hairs) {
        assert_keys(
            j,
            &[
                "name",
                "eumelanin",
                "pheomelanin",
                "sigma_a",
                "near",
                "far",
                "far_vs_near",
            ],
        );
        assert_eq!(j["name"], h.name);
        same(&j["eumelanin"], h.eumelanin);
        same(&j["pheomelanin"], h.pheomelanin);
        same_all(&j["sigma_a"], &h.sigma_a);
        assert_energies(&j["near"], &h.near);
        assert_energies(&j["far"], &h.far);
        same(&j["far_vs_near"], h.far_vs_near);
    }
    let c = &e["convergence"];
    assert_keys(
        c,
        &[
            "hair",
            "fine_sphere",
            "fine_sphere_change",
            "fine_offset_nodes",
            "fine_offset_change",
        ],
    );
    assert_eq!(c["hair"], lib.convergence.hair);
    same_all(
        &c["fine_sphere"],
        &s.fine_sphere.to_array().map(|n| n as f64),
    );
    same(&c["fine_sphere_change"], lib.convergence.fine_sphere_change);
    same(&c["fine_offset_nodes"], s.fine_offset_nodes as f64);
    same(&c["fine_offset_change"], lib.convergence.fine_offset_change);

    // Furnace.
    let f = &json["furnace"];
    assert_keys(f, &["theta_o_deg", "h", "sharp_beta", "rows"]);
    same_all(&f["theta_o_deg"], &s.furnace_theta_o_deg);
    same_all(&f["h"], &s.furnace_h);
    same(&f["sharp_beta"], SHARP_BETA);
    let rows = f["rows"].as_array().unwrap();
    assert_eq!(rows.len(), lib.furnace.len());
    for (j, row) in rows.iter().zip(&lib.furnace) {
        assert_keys(j, &["beta", "sphere", "near", "far"]);
        same(&j["beta"], row.beta);
        same_all(&j["sphere"], &row.sphere.to_array().map(|n| n as f64));
        assert_furnace(&j["near"], &row.near);
        assert_furnace(&j["far"], &row.far);
    }

    // Timing.
    let t = &json["timing"];
    assert_keys(t, &["calls", "ns_per_call_f64", "ns_per_call_f32"]);
    same(&t["calls"], s.timing_calls as f64);
    assert_timing(&t["ns_per_call_f64"]);
    assert_timing(&t["ns_per_call_f32"]);

    // Integrator.
    let i = &json["integrator"];
    assert_keys(
        i,
        &[
            "beta_m",
            "sigma_a",
            "theta_o",
            "phis",
            "refine_every",
            "reference_rel_tol",
            "refined_rel_tol",
            "peak_floor",
            "nodes",
            "rows",
            "timings",
        ],
    );
    let si = &s.integrator;
    same(&i["beta_m"], REPORT_BETA);
    same_all(&i["sigma_a"], &INTEGRATOR_SIGMA_A);
    same_all(&i["theta_o"], &si.theta_o);
    same(&i["phis"], si.phis as f64);
    same(&i["refine_every"], si.refine_every as f64);
    same(&i["reference_rel_tol"], REFERENCE_TOL);
    same(&i["refined_rel_tol"], REFINED_TOL);
    same(&i["peak_floor"], PEAK_FLOOR);
    let node_counts: Vec<f64> = si.nodes.iter().map(|&n| n as f64).collect();
    same_all(&i["nodes"], &node_counts);
    let rows = i["rows"].as_array().unwrap();
    assert_eq!(rows.len(), lib.integrator.rows.len());
    for (j, row) in rows.iter().zip(&lib.integrator.rows) {
        assert_keys(
            j,
            &["beta_n", "reference_us", "reference_refinement", "errors"],
        );
        same(&j["beta_n"], row.beta_n);
        assert_timing(&j["reference_us"]);
        same(&j["reference_refinement"], row.reference_refinement);
        let errors = j["errors"].as_array().unwrap();
        assert_eq!(errors.len(), row.errors.len());
        for (je, le) in errors.iter().zip(&row.errors) {
            assert_keys(je, &["nodes", "max", "mean"]);
            same(&je["nodes"], le.nodes as f64);
            same(&je["max"], le.max);
            same(&je["mean"], le.mean);
        }
    }
    let timings = i["timings"].as_array().unwrap();
    assert_eq!(timings.len(), si.nodes.len());
    for (j, n) in timings.iter().zip(&si.nodes) {
        assert_keys(j, &["nodes", "ns"]);
        same(&j["nodes"], *n as f64);
        assert_timing(&j["ns"]);
    }

    // The fitted constants: exactly the rows of `hairmath fit --json` (whose keys tests/cli.rs
    // checks).
    let fits = json["fitted_constants"].as_array().unwrap();
    assert!(!fits.is_empty());
    let from_fit: Value = serde_json::from_str(&hairmath(&["fit", "--json"])).unwrap();
    assert_eq!(json["fitted_constants"], from_fit);
}

#[test]
fn report_quick_markdown_prints_the_library_values() {
    let out = hairmath(&["report", "--quick"]);
    let lib = library();
    for needle in [
        "| hair | eu | pheo | sigma_a (R, G, B) | R | TT | TRT | residual | total (R, G, B) |",
        "| hair | R | TT | TRT | residual | total (R, G, B) | vs near |",
        "| beta_n | ref us | ref refinement | N = 8 | N = 16 | N = 32 | N = 64 | N = 128 |",
        "| ns per fast N_p | | | ",
        "## Fitted constants (`hairmath fit`, eta = 1.55)",
        "## Speed against error (`hairmath plan`'s choices)",
        "| kind | approximation | E blonde | cost blonde | E dark-brown | cost dark-brown | E black | cost black |",
        "### black hair: the Pareto front (",
        "| E | cost | composition |",
    ] {
        assert!(out.contains(needle), "{needle:?} not in:\n{out}");
    }
    let triple = |v: [f64; 3]| format!("{:.4}, {:.4}, {:.4}", v[0], v[1], v[2]);
    for h in &lib.hairs {
        // Near-field row: the colour, sigma_a, the green channel of each lobe, the total.
        let near: Vec<String> = h
            .near
            .lobes
            .iter()
            .map(|l| format!("{:.4}", l[1]))
            .collect();
        let s = h.sigma_a;
        let row = format!(
            "| {} | {} | {} | {:.3}, {:.3}, {:.3} | {} | {} |",
            h.name,
            h.eumelanin,
            h.pheomelanin,
            s[0],
            s[1],
            s[2],
            near.join(" | "),
            triple(h.near.total)
        );
        assert!(out.contains(&row), "{row:?} not in:\n{out}");
        let far: Vec<String> = h.far.lobes.iter().map(|l| format!("{:.4}", l[1])).collect();
        let far_row = format!(
            "| {} | {} | {} | {:.1e} |",
            h.name,
            far.join(" | "),
            triple(h.far.total),
            h.far_vs_near
        );
        assert!(out.contains(&far_row), "{far_row:?} not in:\n{out}");
    }
    let near: Vec<String> = lib
        .furnace
        .iter()
        .map(|f| format!("beta {}: {:+.1e}", f.beta, f.near.worst_error))
        .collect();
    let far: Vec<String> = lib
        .furnace
        .iter()
        .map(|f| format!("beta {}: {:+.1e}", f.beta, f.far.worst_error))
        .collect();
    for line in [near.join("; "), far.join("; ")] {
        assert!(out.contains(&line), "{line:?} not in:\n{out}");
    }
    for row in &lib.integrator.rows {
        let errors: Vec<String> = row
            .errors
            .iter()
            .map(|e| format!("{:.1e} / {:.1e}", e.max, e.mean))
            .collect();
        let tail = format!(
            " | {:.0e} | {} |",
            row.reference_refinement,
            errors.join(" | ")
        );
        let line = out
            .lines()
            .find(|l| l.starts_with(&format!("| {} | ", row.beta_n)))
            .unwrap_or_else(|| panic!("no row for beta_n {}", row.beta_n));
        assert!(line.ends_with(&tail), "{line:?} does not end with {tail:?}");
    }
}
