//! `hairmath groom` and `hairmath bake`: the groom file the command writes is the library's
//! groom, byte for byte reproducible; the bake writes `transmittance.f32` (vertex-major, the
//! library's coefficients) and `transmittance.json`; bad files and arguments end with status 2
//! and a message naming what was wrong.

#[allow(dead_code)] // its JSON helpers serve the other command-line tests
mod common;

use common::hairmath;
use hairmath::strands::groom::{groom, GroomKind, GroomSettings};
use hairmath::strands::hair_file::read_hair_file;
use hairmath::strands::occluders::Opacity;
use hairmath::strands::transmittance::{bake, BakeSettings, Baker};
use serde_json::Value;
use std::path::PathBuf;
use std::process::Command;

fn scratch(name: &str) -> PathBuf {
    std::env::temp_dir().join(format!("hairmath-strands-{}-{name}", std::process::id()))
}

#[test]
fn groom_writes_the_library_groom_reproducibly() {
    let (first, second) = (scratch("a.hair"), scratch("b.hair"));
    for path in [&first, &second] {
        let out = path.to_string_lossy().into_owned();
        let printed = hairmath(&[
            "groom",
            "--kind",
            "curly",
            "--strands",
            "30",
            "--points",
            "12",
            "--seed",
            "5",
            "--out",
            &out,
        ]);
        assert!(printed.contains("30 strands, 360 points"), "{printed}");
    }
    let bytes = std::fs::read(&first).expect("written");
    assert_eq!(
        bytes,
        std::fs::read(&second).expect("written"),
        "same seed, same file"
    );
    let file = read_hair_file(&first).expect("a valid .hair file");
    let library = groom(&GroomSettings::new(GroomKind::Curly, 30, 12, 5)).unwrap();
    assert_eq!(file.strands, library);
    assert!(file.info.contains("curly"), "{}", file.info);
    for path in [first, second] {
        let _ = std::fs::remove_file(path);
    }
}

#[test]
fn bake_writes_the_library_coefficients_and_their_description() {
    let hair = scratch("bake.hair");
    let dir = scratch("bake-out");
    let (hair_arg, dir_arg) = (
        hair.to_string_lossy().into_owned(),
        dir.to_string_lossy().into_owned(),
    );
    hairmath(&[
        "groom",
        "--kind",
        "wavy",
        "--strands",
        "40",
        "--points",
        "8",
        "--seed",
        "2",
        "--out",
        &hair_arg,
    ]);
    let printed = hairmath(&[
        "bake",
        &hair_arg,
        "--exact",
        "--directions",
        "256",
        "--opacity",
        "0.5",
        "--first-strands",
        "3",
        "--out",
        &dir_arg,
    ]);
    assert!(printed.contains("24 vertices"), "{printed}");
    let raw = std::fs::read(dir.join("transmittance.f32")).expect("written");
    assert_eq!(raw.len(), 24 * 9 * 4);
    let values: Vec<f32> = raw
        .chunks_exact(4)
        .map(|b| f32::from_le_bytes([b[0], b[1], b[2], b[3]]))
        .collect();
    let strands = read_hair_file(&hair).unwrap().strands;
    let settings = BakeSettings {
        lmax: 2,
        opacity: Opacity::Uniform(0.5),
        baker: Baker::Exact { directions: 256 },
    };
    let library = bake(&strands, 0..24, &settings, &|_, _| {}).unwrap();
    assert_eq!(values, library.coefficients);
    let json: Value = serde_json::from_str(
        &std::fs::read_to_string(dir.join("transmittance.json")).expect("written"),
    )
    .expect("JSON");
    assert_eq!(json["vertex_count"], 24);
    assert_eq!(json["lmax"], 2);
    assert_eq!(json["baker"], "exact");
    assert_eq!(json["opacity"], 0.5);
    assert!(json["sh_convention"]
        .as_str()
        .unwrap()
        .contains("Condon-Shortley"));
    assert!(json["timing"]["seconds"].as_f64().unwrap() >= 0.0);
    // The fast baker, every vertex, bands l <= 3.
    hairmath(&["bake", &hair_arg, "--lmax", "3", "--out", &dir_arg]);
    let raw = std::fs::read(dir.join("transmittance.f32")).expect("written");
    assert_eq!(raw.len(), 320 * 16 * 4);
    let _ = std::fs::remove_file(hair);
    let _ = std::fs::remove_dir_all(dir);
}

fn fails(args: &[&str]) -> String {
    let o = Command::new(env!("CARGO_BIN_EXE_hairmath"))
        .args(args)
        .output()
        .expect("the binary runs");
    let stderr = String::from_utf8_lossy(&o.stderr).into_owned();
    assert_eq!(o.status.code(), Some(2), "{args:?}: {stderr}");
    stderr
}

#[test]
fn bad_files_and_settings_say_what_was_wrong() {
    let hair = scratch("truncated.hair");
    let mut bytes = b"HAIR".to_vec();
    bytes.extend_from_slice(&[0; 20]);
    std::fs::write(&hair, &bytes).unwrap();
    let dir = scratch("never").to_string_lossy().into_owned();
    let stderr = fails(&["bake", &hair.to_string_lossy(), "--out", &dir]);
    assert!(stderr.contains("file ends at byte 24"), "{stderr}");
    let missing = scratch("missing.hair").to_string_lossy().into_owned();
    let stderr = fails(&["bake", &missing, "--out", &dir]);
    assert!(stderr.contains("missing.hair"), "{stderr}");
    let good = scratch("good.hair").to_string_lossy().into_owned();
    hairmath(&[
        "groom",
        "--kind",
        "straight",
        "--strands",
        "2",
        "--points",
        "4",
        "--out",
        &good,
    ]);
    let stderr = fails(&["bake", &good, "--lmax", "17", "--out", &dir]);
    assert!(stderr.contains("lmax = 17"), "{stderr}");
    let stderr = fails(&["bake", &good, "--first-strands", "3", "--out", &dir]);
    assert!(stderr.contains("the file has 2 strands"), "{stderr}");
    let stderr = fails(&[
        "groom",
        "--kind",
        "wavy",
        "--strands",
        "0",
        "--points",
        "4",
        "--out",
        &good,
    ]);
    assert!(stderr.contains("strands = 0"), "{stderr}");
    for path in [hair, PathBuf::from(good)] {
        let _ = std::fs::remove_file(path);
    }
}

#[test]
fn render_gerard_writes_the_images_and_their_errors() {
    let hair = scratch("render.hair");
    let dir = scratch("render");
    let (hair_arg, dir_arg) = (
        hair.to_string_lossy().into_owned(),
        dir.to_string_lossy().into_owned(),
    );
    hairmath(&[
        "groom",
        "--kind",
        "wavy",
        "--strands",
        "150",
        "--points",
        "8",
        "--seed",
        "2",
        "--out",
        &hair_arg,
    ]);
    let printed = hairmath(&[
        "render-gerard",
        &hair_arg,
        "--phase-lmax",
        "2",
        "--v-lmax",
        "2",
        "--size",
        "16",
        "--circles",
        "32",
        "--directions",
        "128",
        "--out",
        &dir_arg,
    ]);
    assert!(printed.contains("gerard: rmse"), "{printed}");
    let errors: Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("errors.json")).unwrap()).unwrap();
    for value in [
        &errors["rmse"],
        &errors["relative_error"],
        &errors["kajiya_kay"]["rmse"],
        &errors["kajiya_kay"]["relative_error"],
        &errors["reference_convergence"]["relative_error"],
    ] {
        let v = value.as_f64().unwrap_or(f64::NAN);
        assert!(v.is_finite() && v >= 0.0, "{errors}");
    }
    assert_eq!(errors["phase_lmax"], 2);
    // The projection error per band limit: five limits of three lobes, each in [0, 1], and
    // no limit loses more than the one below it (Parseval: each band adds energy).
    let at = errors["phase_projection_error"]["at"].as_array().unwrap();
    assert_eq!(at.len(), 4, "{errors}");
    for point in at {
        let bands = point["by_band_limit"].as_array().unwrap();
        assert_eq!(bands.len(), 5, "{point}");
        let lobe = |l: usize, p: usize| bands[l][p].as_f64().unwrap();
        for p in 0..3 {
            assert!((0.0..=1.0).contains(&lobe(0, p)), "{point}");
            for l in 1..5 {
                assert!(lobe(l, p) <= lobe(l - 1, p) + 1e-12, "{point}");
            }
        }
    }
    assert!(
        printed.contains("phase projection error at l <= 2"),
        "{printed}"
    );
    assert_eq!(errors["environment_lmax"], 4);
    for (name, width) in [
        ("reference.png", 16),
        ("gerard.png", 16),
        ("kajiya_kay.png", 16),
        ("difference.png", 16),
        ("side_by_side.png", 48),
    ] {
        let bytes = std::fs::read(dir.join(name)).unwrap();
        assert_eq!(&bytes[1..4], b"PNG", "{name}");
        // The IHDR chunk's width, big-endian, at byte 16.
        assert_eq!(
            u32::from_be_bytes(bytes[16..20].try_into().unwrap()),
            width,
            "{name}"
        );
    }
    let message = fails(&[
        "render-gerard",
        &hair_arg,
        "--phase-lmax",
        "7",
        "--out",
        &dir_arg,
    ]);
    assert!(
        message.contains("phase_lmax") && message.contains("[1, 4]"),
        "{message}"
    );
    let message = fails(&[
        "render-gerard",
        &hair_arg,
        "--rgba8",
        "--phase-lmax",
        "2",
        "--out",
        &dir_arg,
    ]);
    assert!(message.contains("rgba8"), "{message}");
    let _ = std::fs::remove_dir_all(&dir);
    let _ = std::fs::remove_file(&hair);
}
