//! The committed shaders (`shaders/`) are what the emitter writes today: regenerated and
//! compared byte for byte, and no stale file is left in the folder.

use hairmath::shader::committed_shaders;
use std::collections::BTreeSet;
use std::path::Path;

/// The command that rewrites the folder.
const REGENERATE: &str = "cargo run --release -- shader --committed shaders";

#[test]
fn the_committed_shaders_are_what_the_emitter_writes() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("shaders");
    let files = committed_shaders().expect("every model with a shader form emits");
    let mut differing = Vec::new();
    for f in &files {
        match std::fs::read(dir.join(&f.name)) {
            Ok(bytes) if bytes == f.contents => {}
            Ok(_) => differing.push(format!("{} differs", f.name)),
            Err(e) => differing.push(format!("{} cannot be read: {e}", f.name)),
        }
    }
    let expected: BTreeSet<&str> = files.iter().map(|f| f.name.as_str()).collect();
    for entry in std::fs::read_dir(&dir).into_iter().flatten().flatten() {
        let name = entry.file_name().to_string_lossy().into_owned();
        if !expected.contains(name.as_str()) {
            differing.push(format!("{name} is not generated any more"));
        }
    }
    assert!(
        differing.is_empty(),
        "shaders/ is out of date ({}); rewrite it with `{REGENERATE}` and commit the result",
        differing.join("; ")
    );
}

#[test]
fn every_committed_glsl_compute_shader_passes_glslang() {
    let files = committed_shaders().expect("every model with a shader form emits");
    let mut checked = 0;
    for f in files.iter().filter(|f| f.name.ends_with(".comp.glsl")) {
        let text = std::str::from_utf8(&f.contents).expect("GLSL is text");
        match crate::tools::glslang_validate_compute(text) {
            Ok(crate::tools::Validated::Passed) => checked += 1,
            Ok(crate::tools::Validated::Skipped(why)) => {
                eprintln!("glslangValidator skipped: {why}");
                return;
            }
            Err(e) => panic!("{}: glslangValidator rejects it:\n{e}", f.name),
        }
    }
    assert!(checked >= 10, "only {checked} GLSL shaders");
}
