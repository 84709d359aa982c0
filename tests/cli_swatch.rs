//! `hairmath render` and `hairmath plot`: each writes a PNG of the requested size that is not
//! all one colour (the SVG plot is SVG), and bad sizes, sample counts and flags end with
//! status 2 and a message naming them.

use std::path::PathBuf;
use std::process::{Command, Output};

fn scratch(name: &str) -> PathBuf {
    std::env::temp_dir().join(format!("hairmath-swatch-{}-{name}", std::process::id()))
}

fn run(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_hairmath"))
        .args(args)
        .output()
        .expect("the binary runs")
}

/// The PNG's width, height and RGB bytes.
fn decode(path: &PathBuf) -> (u32, u32, Vec<u8>) {
    let file = std::io::BufReader::new(std::fs::File::open(path).expect("written"));
    let mut reader = png::Decoder::new(file).read_info().expect("a PNG");
    let mut buffer = vec![0; reader.output_buffer_size().expect("a size")];
    let info = reader.next_frame(&mut buffer).expect("a frame");
    buffer.truncate(info.buffer_size());
    (info.width, info.height, buffer)
}

fn not_one_colour(rgb: &[u8]) {
    assert!(rgb.chunks(3).any(|p| p != &rgb[..3]), "all one colour");
}

#[test]
fn render_writes_the_swatch_with_the_path_tracer_and_single_scattering() {
    for model in ["chiang", "karis"] {
        let path = scratch(&format!("{model}.png"));
        let out = path.to_string_lossy().into_owned();
        let o = run(&[
            "render",
            "--model",
            model,
            "--out",
            &out,
            "--size",
            "20",
            "--samples",
            "2",
        ]);
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        let printed = String::from_utf8_lossy(&o.stdout);
        let renderer = if model == "chiang" {
            "path tracer"
        } else {
            "single scattering"
        };
        assert!(printed.contains(renderer), "{printed}");
        let (w, h, rgb) = decode(&path);
        assert_eq!((w, h), (20, 20));
        not_one_colour(&rgb);
        let _ = std::fs::remove_file(path);
    }
}

#[test]
fn plot_writes_png_and_svg() {
    let png_path = scratch("lobes.png");
    let out = png_path.to_string_lossy().into_owned();
    let o = run(&["plot", "--model", "frostbite", "--out", &out]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let (w, h, rgb) = decode(&png_path);
    assert_eq!((w, h), (960, 440));
    not_one_colour(&rgb);
    let svg_path = scratch("lobes.svg");
    let out = svg_path.to_string_lossy().into_owned();
    let o = run(&["plot", "--model", "chiang", "--out", &out]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let svg = std::fs::read_to_string(&svg_path).expect("written");
    assert!(
        svg.starts_with("<svg") && svg.contains("polyline"),
        "{}",
        &svg[..80]
    );
    for path in [png_path, svg_path] {
        let _ = std::fs::remove_file(path);
    }
}

#[test]
fn bad_sizes_samples_and_flags_are_typed_errors() {
    let out = scratch("bad.png").to_string_lossy().into_owned();
    let cases: [(&[&str], &str); 4] = [
        (&["render", "--out", &out, "--size", "0"], "size = 0"),
        (&["render", "--out", &out, "--size", "5000"], "size = 5e3"),
        (&["render", "--out", &out, "--samples", "0"], "samples = 0"),
        (
            &[
                "render", "--model", "karis", "--beta-m", "0.3", "--out", &out,
            ],
            "--beta-m",
        ),
    ];
    for (args, message) in cases {
        let o = run(args);
        assert_eq!(o.status.code(), Some(2), "{args:?}");
        let stderr = String::from_utf8_lossy(&o.stderr);
        assert!(stderr.contains(message), "{args:?}: {stderr}");
    }
    let o = run(&["plot", "--model", "chiang", "--beta-m", "0", "--out", &out]);
    assert_eq!(o.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&o.stderr).contains("beta_m"));
}
