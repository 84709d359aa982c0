//! A hair swatch path-traced with the Chiang model (`hairmath::render::swatch::path`): brown
//! hair under a constant sky and a spherical key light, MIS with the power heuristic, Russian
//! roulette. Writes the image as a PNG and checks the estimator against itself and a closed
//! form:
//!
//! 1. **Convergence:** the image's mean at 4 paths per pixel is within 5 standard errors
//!    (from the estimator's own per-pixel variances) of the mean at the full sample count,
//!    with an independent seed.
//! 2. **MIS:** the same mean with the BCSDF's samples only (no light sampling) agrees within
//!    5 standard errors: the two strategies estimate the same integral.
//! 3. **White furnace:** with sigma_a = 0 (the Chiang model conserves energy) under a uniform
//!    environment of radiance 1 and no light, every pixel's expectation is 1; the mean over
//!    the fibres is within 5 standard errors of 1.
//!
//! `cargo run --release --features strands,png --example path_tracer [-- OUT.png]` (the
//! default features include both; default OUT: `hairmath-swatch.png` in the temp folder);
//! `cargo test --release --example path_tracer` runs it at a small size.

use hairmath::absorption::Absorption;
use hairmath::bcsdf::ChiangHair;
use hairmath::params::HairParams;
use hairmath::render::side_by_side;
use hairmath::render::swatch::light::SwatchLight;
use hairmath::render::swatch::path::{path_trace, PathImage, PathSettings, Strategy};
use hairmath::render::swatch::{Swatch, SwatchSettings};
use hairmath::render::write_png;
use std::path::{Path, PathBuf};
use std::time::Instant;

/// Standard errors within which two estimates of one expectation must agree.
const SIGMAS: f64 = 5.0;

/// What to render.
struct Run {
    /// Pixels per side.
    size: usize,
    /// Paths per pixel of the written image.
    samples: usize,
    /// Paths per pixel of the furnace and MIS checks.
    check_samples: usize,
    /// The PNG to write.
    out: PathBuf,
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let out = std::env::args_os()
        .nth(1)
        .map(PathBuf::from)
        .unwrap_or_else(|| std::env::temp_dir().join("hairmath-swatch.png"));
    run(&Run {
        size: 160,
        samples: 64,
        check_samples: 8,
        out,
    })
}

fn run(r: &Run) -> Result<(), Box<dyn std::error::Error>> {
    let swatch = Swatch::new(&SwatchSettings::default())?;
    let camera = swatch.camera(r.size)?;
    let hair = ChiangHair::new(&HairParams::default());
    let light = SwatchLight::default();
    let settings = PathSettings {
        samples: r.samples,
        ..PathSettings::default()
    };
    let start = Instant::now();
    let full = path_trace(&swatch, &camera, &hair, &light, &settings)?;
    println!(
        "{0}x{0}, {1} paths per pixel: {2:.2} s",
        r.size,
        r.samples,
        start.elapsed().as_secs_f64()
    );
    check_image(&full, r.size);
    write(&r.out, &full)?;
    report("full", &full);

    let few = PathSettings {
        samples: 4,
        seed: 2,
        ..settings
    };
    let few = path_trace(&swatch, &camera, &hair, &light, &few)?;
    report("4 paths", &few);
    agree("4 paths against the full count", &few, &full);

    let bcsdf_only = PathSettings {
        samples: r.check_samples,
        seed: 3,
        strategy: Strategy::BcsdfOnly,
        ..settings
    };
    let bcsdf_only = path_trace(&swatch, &camera, &hair, &light, &bcsdf_only)?;
    report("BCSDF samples only", &bcsdf_only);
    agree("BCSDF samples only against MIS", &bcsdf_only, &full);

    furnace(&swatch, r)
}

/// The white furnace: sigma_a = 0, environment 1, no light.
fn furnace(swatch: &Swatch, r: &Run) -> Result<(), Box<dyn std::error::Error>> {
    let clear = ChiangHair::new(&HairParams {
        sigma_a: Absorption::grey(0.0)?,
        ..HairParams::default()
    });
    let settings = PathSettings {
        samples: r.check_samples,
        seed: 4,
        ..PathSettings::default()
    };
    let camera = swatch.camera(r.size)?;
    let light = SwatchLight::environment_only([1.0; 3]);
    let image = path_trace(swatch, &camera, &clear, &light, &settings)?;
    check_image(&image, r.size);
    let (mean, se) = (image.image.mean(), image.mean_standard_error());
    for c in 0..3 {
        println!(
            "white furnace, channel {c}: mean {:.6} +- {:.6} (expected 1)",
            mean[c], se[c]
        );
        assert!(
            (mean[c] - 1.0).abs() <= SIGMAS * se[c] + 1e-12,
            "furnace channel {c}: {} +- {}",
            mean[c],
            se[c]
        );
    }
    Ok(())
}

/// The image's size, its pixels finite and non-negative, and some fibres in view.
fn check_image(image: &PathImage, size: usize) {
    assert_eq!(image.image.size, size);
    assert_eq!(image.image.pixels.len(), size * size);
    assert!(image
        .image
        .pixels
        .iter()
        .flatten()
        .all(|v| v.is_finite() && *v >= 0.0));
    let covered = image.image.covered.iter().filter(|&&c| c).count();
    assert!(covered > size * size / 2, "{covered} pixels show fibres");
}

fn report(name: &str, image: &PathImage) {
    let (m, se) = (image.image.mean(), image.mean_standard_error());
    println!(
        "{name}: mean radiance over the fibres {:.5} {:.5} {:.5} (standard error {:.5} {:.5} {:.5})",
        m[0], m[1], m[2], se[0], se[1], se[2]
    );
}

/// Two independent estimates of the same mean agree within [`SIGMAS`] combined standard
/// errors, channel by channel.
fn agree(what: &str, a: &PathImage, b: &PathImage) {
    let (ma, sa, mb, sb) = (
        a.image.mean(),
        a.mean_standard_error(),
        b.image.mean(),
        b.mean_standard_error(),
    );
    for c in 0..3 {
        let tolerance = SIGMAS * (sa[c] * sa[c] + sb[c] * sb[c]).sqrt();
        let gap = (ma[c] - mb[c]).abs();
        println!(
            "{what}, channel {c}: |{:.5} - {:.5}| = {gap:.5} <= {tolerance:.5}",
            ma[c], mb[c]
        );
        assert!(gap <= tolerance, "{what}, channel {c}");
    }
}

fn write(path: &Path, image: &PathImage) -> Result<(), Box<dyn std::error::Error>> {
    let exposure = image.image.exposure();
    write_png(
        path,
        image.image.size,
        image.image.size,
        &side_by_side(&[&image.image], exposure),
    )?;
    println!("wrote {}", path.display());
    Ok(())
}

#[test]
fn path_tracer_runs_and_checks_itself() {
    let dir = std::env::temp_dir().join(format!("hairmath-path-tracer-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let out = dir.join("swatch.png");
    run(&Run {
        size: 40,
        samples: 32,
        check_samples: 8,
        out: out.clone(),
    })
    .unwrap();
    let decoder = png::Decoder::new(std::io::BufReader::new(std::fs::File::open(&out).unwrap()));
    let reader = decoder.read_info().unwrap();
    assert_eq!((reader.info().width, reader.info().height), (40, 40));
    std::fs::remove_dir_all(dir).unwrap();
}
