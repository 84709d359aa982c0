//! `hairmath shader`: the module's contract (function signatures, varying arguments, the
//! near-field offset), the languages, the tables written beside the module, and the errors.

use std::process::Command;

/// Runs `hairmath shader` with `args`: (success, stdout bytes, stderr).
fn shader(args: &[&str]) -> (bool, Vec<u8>, String) {
    let o = Command::new(env!("CARGO_BIN_EXE_hairmath"))
        .arg("shader")
        .args(args)
        .output()
        .expect("the binary runs");
    (
        o.status.success(),
        o.stdout,
        String::from_utf8_lossy(&o.stderr).into_owned(),
    )
}

/// The text `hairmath shader args` prints (it must succeed).
fn text(args: &[&str]) -> String {
    let (ok, out, err) = shader(args);
    assert!(ok, "hairmath shader {args:?} failed: {err}");
    String::from_utf8(out).expect("text")
}

const KARIS: [&str; 6] = [
    "--model",
    "karis",
    "--color",
    "0.3,0.2,0.1",
    "--roughness",
    "0.4",
];

#[test]
fn the_wgsl_module_has_the_local_and_the_world_functions() {
    let wgsl = text(&KARIS);
    assert!(wgsl.contains("fn hair_bcsdf(wi: vec3<f32>, wo: vec3<f32>) -> vec3<f32> {"));
    assert!(wgsl.contains(
        "fn hair_bcsdf_world(tangent: vec3<f32>, wi: vec3<f32>, wo: vec3<f32>) -> vec3<f32> {"
    ));
    assert!(
        wgsl.contains("const uniforms: KarisUniforms = KarisUniforms("),
        "{wgsl}"
    );
    assert!(
        wgsl.contains("// hairmath::lobe::gaussian::gaussian_lobe -- Marschner et al. 2003, eq. 6")
    );
    assert!(
        !wgsl.contains("@compute"),
        "the library form has no entry point"
    );
}

#[test]
fn varying_inputs_become_arguments_in_the_given_order() {
    let wgsl = text(&[&KARIS[..], &["--varying", "roughness,color"]].concat());
    assert!(
        wgsl.contains(
            "fn hair_bcsdf(wi: vec3<f32>, wo: vec3<f32>, roughness: f32, color: vec3<f32>) -> vec3<f32> {"
        ),
        "{wgsl}"
    );
    let near = text(&[
        "--model",
        "chiang",
        "--beta-m",
        "0.3",
        "--beta-n",
        "0.3",
        "--melanin",
        "1.3,0",
        "--varying",
        "beta_n",
    ]);
    assert!(
        near.contains(
            "fn hair_bcsdf(wi: vec3<f32>, wo: vec3<f32>, h: f32, beta_n: f32) -> vec3<f32> {"
        ),
        "{near}"
    );
}

#[test]
fn every_language_is_written() {
    let glsl = text(&[&KARIS[..], &["--lang", "glsl"]].concat());
    assert!(glsl.starts_with("#version 450"), "{glsl}");
    assert!(text(&[&KARIS[..], &["--lang", "wgsl-compute"]].concat()).contains("@compute"));
    assert!(text(&[&KARIS[..], &["--lang", "wgsl-naga-oil"]].concat())
        .starts_with("#define_import_path hairmath::karis"));
    assert!(text(&[&KARIS[..], &["--lang", "hlsl"]].concat()).contains("[numthreads(64, 1, 1)]"));
    assert!(text(&[&KARIS[..], &["--lang", "msl"]].concat()).contains("kernel void"));
    let (ok, spirv, err) = shader(&[&KARIS[..], &["--lang", "spirv"]].concat());
    assert!(ok, "{err}");
    assert_eq!(
        &spirv[..4],
        &[0x03, 0x02, 0x23, 0x07],
        "the SPIR-V magic number"
    );
}

#[test]
fn tables_are_written_beside_the_module() {
    let gerard = [
        "--model",
        "gerard",
        "--alpha-r-deg",
        "-5",
        "--beta-r-deg",
        "10",
        "--color",
        "0.3,0.2,0.1",
    ];
    let (ok, _, err) = shader(&gerard);
    assert!(!ok && err.contains("give --out FILE"), "{err}");
    let dir = std::env::temp_dir().join(format!("hairmath-cli-shader-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    // The folder of --out is created.
    let out = dir.join("new").join("gerard.wgsl");
    let (ok, _, err) = shader(&[&gerard[..], &["--out", out.to_str().unwrap()]].concat());
    assert!(ok, "{err}");
    let wgsl = std::fs::read_to_string(&out).unwrap();
    assert!(
        wgsl.contains("textureLoad") && !wgsl.contains("textureSample"),
        "{wgsl}"
    );
    let dir = dir.join("new");
    let bindings = std::fs::read_to_string(dir.join("gerard.bindings.json")).unwrap();
    assert!(
        bindings.contains("\"table\": \"gerard.lut0.f32\""),
        "{bindings}"
    );
    let raw = std::fs::metadata(dir.join("gerard.lut0.f32"))
        .unwrap()
        .len();
    assert!(raw > 0 && raw.is_multiple_of(4));
    assert!(dir.join("gerard.lut0.json").exists());
    std::fs::remove_dir_all(dir.parent().unwrap()).unwrap();
}

#[test]
fn models_and_inputs_without_a_shader_form_are_errors_that_say_why() {
    let (ok, _, err) = shader(&["--model", "marschner", "--melanin", "1,0"]);
    assert!(
        !ok && err.contains("shader form") && err.contains("cubic"),
        "{err}"
    );
    let (ok, _, err) = shader(&[&KARIS[..], &["--varying", "wobble"]].concat());
    assert!(
        !ok && err.contains("wobble") && err.contains("roughness"),
        "{err}"
    );
    let (ok, _, err) = shader(&[&KARIS[..], &["--varying", "roughness,roughness"]].concat());
    assert!(!ok && err.contains("roughness"), "{err}");
}
