//! `hairmath models`: its JSON has the documented keys and the library's values
//! (`hairmath::fit::compare_models`), its markdown prints them, and `hairmath report`
//! summarises the same rows.

use hairmath::fit::{compare_models, ComparisonSettings, ModelRow};
mod common;

use common::{hairmath, same};
use serde_json::Value;
use std::process::Command;
use std::sync::OnceLock;

/// The library's rows for dark brown hair, computed once (without timings).
fn library() -> &'static [ModelRow] {
    static ROWS: OnceLock<Vec<ModelRow>> = OnceLock::new();
    ROWS.get_or_init(|| {
        let settings = ComparisonSettings {
            timing_calls: 0,
            ..ComparisonSettings::dark_brown()
        };
        compare_models(&settings, &|_, _| {}).unwrap()
    })
}

#[test]
fn models_json_has_the_documented_keys_and_the_library_values() {
    let json: Value =
        serde_json::from_str(&hairmath(&["models", "--dark-brown", "--json"])).unwrap();
    let rows = json.as_array().expect("an array of rows");
    let lib = library();
    assert_eq!(rows.len(), lib.len());
    for (row, r) in rows.iter().zip(lib) {
        let mut keys: Vec<&str> = row
            .as_object()
            .unwrap()
            .keys()
            .map(|k| k.as_str())
            .collect();
        keys.sort_unstable();
        assert_eq!(
            keys,
            [
                "beta_m",
                "beta_n",
                "colour",
                "energy_error",
                "energy_error_fitted",
                "energy_theta_o_deg",
                "error_fitted",
                "error_fitted_half_pairs",
                "error_mapped",
                "error_mapped_half_pairs",
                "eumelanin",
                "fit_iterations",
                "fit_pairs",
                "fit_termination",
                "fitted_inputs",
                "mapped_inputs",
                "model",
                "ns_per_eval_batch",
                "ns_per_eval_f32",
                "ops",
                "pairs",
                "pheomelanin",
            ]
        );
        assert_eq!(row["model"], r.model);
        same(&row["eumelanin"], r.hair.eumelanin);
        same(&row["beta_m"], r.hair.beta_m);
        same(&row["error_mapped"], r.error_mapped.full);
        same(&row["error_mapped_half_pairs"], r.error_mapped.half);
        same(&row["error_fitted"], r.error_fitted.full);
        assert_eq!(row["fit_iterations"], r.fit.minimum.iterations);
        let energy = row["energy_error"].as_array().unwrap();
        assert_eq!(energy.len(), 3);
        for (j, v) in energy.iter().zip(&r.energy_error) {
            same(j, *v);
        }
        // Inputs keyed by flag names: as many as the model has inputs, numbers or arrays.
        let entry = hairmath::registry::find_model(r.model).unwrap();
        for key in ["mapped_inputs", "fitted_inputs"] {
            let inputs = row[key].as_object().unwrap();
            assert_eq!(inputs.len(), entry.inputs.len(), "{}: {inputs:?}", r.model);
        }
        let ops = row["ops"].as_object().unwrap();
        for k in [
            "add_mul",
            "div",
            "sqrt",
            "transcendental",
            "select",
            "fetch",
        ] {
            assert_eq!(
                ops[k].as_u64().unwrap(),
                match k {
                    "add_mul" => r.cost.ops.add_mul,
                    "div" => r.cost.ops.div,
                    "sqrt" => r.cost.ops.sqrt,
                    "transcendental" => r.cost.ops.transcendental,
                    "select" => r.cost.ops.select,
                    _ => r.cost.ops.fetch,
                } as u64
            );
        }
        assert!(row["ns_per_eval_f32"].as_f64().unwrap() > 0.0);
    }
}

#[test]
fn models_markdown_prints_the_library_values() {
    let out = hairmath(&["models", "--dark-brown"]);
    for r in library() {
        let cell = format!(
            "| {} | dark brown | 0.3 | 0.3 | {:.3} ({:.3}) | {:.3} ({:.3}) |",
            r.model,
            r.error_mapped.full,
            r.error_mapped.half,
            r.error_fitted.full,
            r.error_fitted.half
        );
        assert!(out.contains(&cell), "{cell:?} not in:\n{out}");
    }
}

#[test]
fn report_summarises_the_quick_comparison() {
    let json: Value = serde_json::from_str(&hairmath(&["report", "--quick", "--json"])).unwrap();
    let settings = ComparisonSettings {
        timing_calls: 0,
        ..ComparisonSettings::quick()
    };
    let lib = compare_models(&settings, &|_, _| {}).unwrap();
    let rows = json["models"].as_array().expect("the report's models");
    assert_eq!(rows.len(), lib.len());
    for (row, r) in rows.iter().zip(&lib) {
        assert_eq!(row["model"], r.model);
        same(&row["error_mapped"], r.error_mapped.full);
        same(&row["error_fitted"], r.error_fitted.full);
    }
}

#[test]
fn an_unknown_model_is_an_error_naming_the_known_ones() {
    let o = Command::new(env!("CARGO_BIN_EXE_hairmath"))
        .args(["models", "--dark-brown", "--model", "phong"])
        .output()
        .unwrap();
    assert_eq!(o.status.code(), Some(2));
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert!(
        stderr.contains("phong is not a registered real-time model (known: "),
        "{stderr}"
    );
}
