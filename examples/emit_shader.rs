//! Shader code for a renderer, written to disk: one registered model (Karis, as Unreal ships
//! it, at the default brown hair's mapped inputs) with its roughness (Unreal's one roughness input) as a per-pixel argument,
//! and the shader of a scene plan (the black-hair example scene: the cheapest composition
//! within its error budget, which reads a far-field table), each as WGSL and GLSL with its
//! lookup tables.
//!
//! `cargo run --release --example emit_shader [DIR]` writes into DIR (default
//! `target/emit_shader`); `cargo test` runs it into a temporary directory
//! (`[[example]] test = true`) and it checks its own output: every file written, the WGSL
//! parsed and validated by naga again, the world-space entry `hair_bcsdf_world` present, and
//! the plan within its budget.

use hairmath::plan::{plan, PlanSettings, Scene};
use hairmath::registry::find_model;
use hairmath::shader::{
    graph_shader, model_shader, table_files, Language, ModelShader, WORLD_FUNCTION,
};
use std::path::{Path, PathBuf};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let dir = std::env::args()
        .nth(1)
        .map_or_else(|| PathBuf::from("target/emit_shader"), PathBuf::from);
    emit(&dir, &PlanSettings::default())
}

/// Writes the model's and the plan's shaders into `dir` and checks them.
fn emit(dir: &Path, settings: &PlanSettings) -> Result<(), Box<dyn std::error::Error>> {
    std::fs::create_dir_all(dir)?;

    // One model: `hairmath shader --model karis --varying roughness` as library calls.
    let karis = find_model("karis").ok_or("karis is registered")?;
    let shader = model_shader(karis, &karis.example_values(), &["roughness"])?;
    write(dir, "karis", &shader)?;

    // A scene plan: `hairmath plan examples/scenes/black.toml --out DIR`.
    let scene = Scene::parse(
        include_str!("scenes/black.toml"),
        "examples/scenes/black.toml",
    )?;
    let chosen = plan(&scene, settings, &|_, _| {})?;
    println!(
        "plan for the black-hair scene: {} (error {:.4} within the budget {}, cost {:.0})",
        chosen.composition.describe(),
        chosen.error,
        scene.budget,
        chosen.cost
    );
    assert!(
        chosen.error <= scene.budget,
        "{} > {}",
        chosen.error,
        scene.budget
    );
    let planned = graph_shader(
        "plan",
        "the plan of examples/scenes/black.toml",
        "hairmath::plan::plan",
        chosen.graph.clone(),
    )?;
    write(dir, "plan", &planned)
}

/// `NAME.wgsl` and `NAME.glsl` (the compute shader of the binding contract) in `dir`, with the
/// lookup tables the shader reads (`NAME.lut<k>.f32` and `.json`) and their bindings
/// (`NAME.bindings.json`), as `hairmath shader --out` writes them; the WGSL read back and
/// validated by naga.
fn write(dir: &Path, name: &str, shader: &ModelShader) -> Result<(), Box<dyn std::error::Error>> {
    let mut files = vec![];
    for (language, extension) in [(Language::Wgsl, "wgsl"), (Language::Glsl, "glsl")] {
        files.push((format!("{name}.{extension}"), shader.write(language)?));
    }
    let (tables, table_files) = table_files(name, shader);
    files.extend(table_files.into_iter().map(|f| (f.name, f.contents)));
    if !tables.is_empty() {
        let bindings = shader.bindings_json(&tables).into_bytes();
        files.push((format!("{name}.bindings.json"), bindings));
    }
    for (file, contents) in files {
        std::fs::write(dir.join(&file), contents)?;
        println!("wrote {}", dir.join(file).display());
    }
    assert_eq!(tables.len(), shader.module.tables().len());
    let wgsl = std::fs::read_to_string(dir.join(format!("{name}.wgsl")))?;
    let module = naga::front::wgsl::parse_str(&wgsl)?;
    naga::valid::Validator::new(
        naga::valid::ValidationFlags::all(),
        naga::valid::Capabilities::empty(),
    )
    .validate(&module)?;
    assert!(
        module
            .functions
            .iter()
            .any(|(_, f)| f.name.as_deref() == Some(WORLD_FUNCTION)),
        "{name}: no {WORLD_FUNCTION}"
    );
    Ok(())
}

#[test]
fn emit_shader_writes_valid_shaders() {
    let dir = std::env::temp_dir().join(format!("hairmath-emit-shader-{}", std::process::id()));
    emit(&dir, &PlanSettings::quick()).unwrap();
    std::fs::remove_dir_all(&dir).unwrap();
}
