//! `hairmath plan`: the README's example scene planned from the command line, its JSON, the
//! files `--out` writes, and malformed scene files reported with their line and key.

mod common;

use common::{hairmath, num, same};
use hairmath::plan::{plan, PlanSettings, Scene};
use serde_json::Value;
use std::process::Command;

#[test]
fn the_black_hair_scene_plans_from_the_command_line() {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/examples/scenes/black.toml");
    let out = std::env::temp_dir().join(format!("hairmath-plan-{}", std::process::id()));
    let out_arg = out.to_string_lossy().into_owned();
    let text = hairmath(&["plan", path, "--json", "--out", &out_arg, "--lang", "glsl"]);
    let json: Value = serde_json::from_str(&text).expect("JSON");
    // The same plan from the library.
    let scene = Scene::read(std::path::Path::new(path)).expect("the example scene");
    let library = plan(&scene, &PlanSettings::default(), &|_, _| {}).expect("a plan");
    same(&json["error"], library.error);
    same(&json["cost"], library.cost);
    assert_eq!(json["composition"], library.composition.describe());
    assert!(num(&json["error"]) <= num(&json["budget"]));
    let choices = json["choices"].as_array().expect("choices");
    assert_eq!(choices.len(), 4);
    assert_eq!(choices[1]["lobe"], "TT");
    assert_eq!(choices[1]["kept"], false, "black hair drops TT");
    assert_eq!(json["shader"]["arguments"], serde_json::json!(["wi", "wo"]));
    assert_eq!(json["shader"]["file"], "hair.glsl");
    let published = json["published"].as_array().expect("published");
    assert!(published.iter().any(|p| p["model"] == "karis"));
    for file in ["hair.glsl", "plan.json"] {
        assert!(out.join(file).is_file(), "{file} written");
    }
    let written: Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("plan.json")).expect("read"))
            .expect("JSON");
    assert_eq!(written, json);
    let _ = std::fs::remove_dir_all(&out);
}

#[test]
fn a_malformed_scene_file_names_its_line_and_key() {
    let path = std::env::temp_dir().join(format!("hairmath-bad-{}.toml", std::process::id()));
    std::fs::write(
        &path,
        "budget = 0.1\n[hair]\neumelanin = 1.0\nbeta_m = 0.3\nbeta_n = [0.6, 0.3]\n",
    )
    .expect("write");
    let o = Command::new(env!("CARGO_BIN_EXE_hairmath"))
        .args(["plan", &path.to_string_lossy()])
        .output()
        .expect("the binary runs");
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{stderr}");
    assert!(
        stderr.contains(":5: hair.beta_n: min 0.6 > max 0.3"),
        "{stderr}"
    );
    let _ = std::fs::remove_file(&path);
}
