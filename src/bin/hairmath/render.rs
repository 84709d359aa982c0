//! `hairmath render-gerard`: Gerard's shading of a `.hair` file against the reference render
//! (and Kajiya-Kay), written as PNG images and `errors.json`. This file only parses, calls
//! [`hairmath::render`] and writes what it returns.

use crate::CliError;
use clap::{Args, ValueEnum};
use hairmath::params::HairParams;
use hairmath::render::{
    compare_gerard, kajiya_kay_best_fit, phase_projection_error, Approximations, DirectionalLight,
    GerardComparison, GerardConfig, GerardRender, GerardScene, GerardSources, ImageError,
    MeridianRule, PhaseAbsorption, RenderSettings, Sky,
};
use hairmath::strands::hair_file::read_hair_file;
use hairmath::strands::occluders::Opacity;
use hairmath::strands::transmittance::Baker;
use serde_json::json;
use std::fs;
use std::io::Write;
use std::path::{Path, PathBuf};
use std::sync::Mutex;
use std::time::Instant;

/// The absorption of the phase function, as `--absorption` names it.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum Absorption {
    /// Eq. 14 with Gerard's exponents 4 and 11/2.
    Published,
    /// Eq. 14 with the refit exponents.
    Refit,
    /// Tabulated over sigma_a from Marschner 2003 (no exponents).
    Tabulated,
}

impl From<Absorption> for PhaseAbsorption {
    fn from(a: Absorption) -> Self {
        match a {
            Absorption::Published => PhaseAbsorption::Published,
            Absorption::Refit => PhaseAbsorption::Refit,
            Absorption::Tabulated => PhaseAbsorption::Tabulated,
        }
    }
}

/// Arguments of `hairmath render-gerard`.
#[derive(Args, Debug)]
pub struct RenderArgs {
    /// The `.hair` file.
    file: PathBuf,
    /// The phase function's bands l <= L, L in [1, 4] (Gerard: 1).
    #[arg(long, default_value_t = 1)]
    phase_lmax: usize,
    /// The transmittance's bands l <= L2, L2 in [0, 4] (Gerard: 2).
    #[arg(long, default_value_t = 2)]
    v_lmax: usize,
    /// Pixels per side, in [1, 4096].
    #[arg(long, default_value_t = RenderSettings::default().size)]
    size: usize,
    /// Great circles per pixel of the reference, at least 1: V is integrated exactly along
    /// each, S sampled on an eighth of them at a sixteenth as many points per circle (at least
    /// 4 and 8); its convergence is measured against half of each.
    #[arg(long, default_value_t = RenderSettings::default().reference.circles)]
    circles: usize,
    /// Directions per pixel of Kajiya-Kay's sky integral, in [2, 2^20].
    #[arg(long, default_value_t = RenderSettings::default().classic_directions)]
    directions: usize,
    /// How the phase function handles absorption.
    #[arg(long, value_enum, default_value_t = Absorption::Published)]
    absorption: Absorption,
    /// Read the l <= 1 phase tables from Gerard's 128 x 3 RGBA8 layout (with --phase-lmax 1).
    #[arg(long)]
    rgba8: bool,
    /// The light-leak bias of Gerard's eq. 10, in [0, 1).
    #[arg(long, default_value_t = 0.0)]
    bias: f64,
    /// The opacity of every segment, in [0, 1]; without it, 1 - the file's transparency.
    #[arg(long)]
    opacity: Option<f32>,
    /// Bake the transmittance with the exact baker at this many directions per vertex
    /// (default: the fast baker).
    #[arg(long, value_name = "DIRECTIONS")]
    exact_bake: Option<usize>,
    /// The folder to write the images and errors.json to (created if needed).
    #[arg(long, value_name = "DIR")]
    out: PathBuf,
}

/// Direction pairs of the fits of Kajiya-Kay's and Gerard's inputs.
const FIT_PAIRS: usize = 4096;

/// How much brighter the difference image is shown than the reference.
const DIFFERENCE_GAIN: f64 = 4.0;

/// Runs `hairmath render-gerard`.
pub fn run(args: &RenderArgs) -> Result<(), CliError> {
    let file = read_hair_file(&args.file).map_err(|e| CliError::Strands(e.to_string()))?;
    let hair = HairParams::default();
    let scene = GerardScene {
        strands: &file.strands,
        hair,
        opacity: args
            .opacity
            .map_or(Opacity::FromTransparency, Opacity::Uniform),
        sky: Sky::default(),
        light: DirectionalLight::default(),
    };
    let config = GerardConfig {
        phase_lmax: args.phase_lmax,
        v_lmax: args.v_lmax,
        absorption: args.absorption.into(),
        rgba8: args.rgba8,
        bias: args.bias,
    };
    let defaults = RenderSettings::default();
    let settings = RenderSettings {
        size: args.size,
        reference: MeridianRule::with_circles(args.circles)?,
        classic_directions: args.directions,
        baker: args
            .exact_bake
            .map_or(defaults.baker, |directions| Baker::Exact { directions }),
        ..defaults
    };
    config.check()?;
    let start = Instant::now();
    let kajiya_kay = kajiya_kay_best_fit(&hair, FIT_PAIRS)?;
    // Only the variant this render shades with is fitted (the others are never read).
    let gerard_sources = GerardSources::all(GerardSources::best_fit_of(
        config.absorption,
        &hair,
        FIT_PAIRS,
    )?);
    let models = Approximations {
        gerard_sources: &gerard_sources,
        kajiya_kay: &kajiya_kay,
    };
    let bar = crate::progress::bar("");
    let stage = Mutex::new(None);
    let comparison = compare_gerard(&scene, &[config], &settings, &models, &|s, done, total| {
        let mut current = stage.lock().unwrap_or_else(|e| e.into_inner());
        if *current != Some(s) {
            *current = Some(s);
            bar.set_message(s.name());
            bar.set_position(0);
        }
        crate::progress::update(&bar, done, total);
    });
    bar.finish_and_clear();
    let comparison = comparison?;
    let gerard = &comparison.gerard[0];
    let seconds = start.elapsed().as_secs_f64();
    write_images(&args.out, &comparison, gerard)?;
    let source = gerard_sources.of(config.absorption);
    let projection = PROJECTION_SIN_THETA_R
        .iter()
        .map(|&s| phase_projection_error(source, config.absorption, s, &settings.quadrature))
        .collect::<Result<Vec<_>, _>>()?;
    let mut errors = errors_json(args, &comparison, gerard, (source, &kajiya_kay), seconds);
    errors["phase_projection_error"] = projection_json(&projection);
    let text = serde_json::to_string_pretty(&errors).expect("JSON of plain values");
    write(&args.out.join("errors.json"), text.as_bytes())?;
    let line = |name: &str, e: &ImageError| {
        format!(
            "{name}: rmse {:.5}, relative error {:.4}",
            e.rmse, e.relative_error
        )
    };
    let mut out = std::io::stdout().lock();
    writeln!(
        out,
        "{} pixels covered, phase l <= {}, V l <= {}, environment l <= {}, {} absorption{}: {seconds:.1} s -> {}",
        comparison.covered,
        config.phase_lmax,
        config.v_lmax,
        config.environment_lmax(),
        config.absorption.name(),
        if config.rgba8 { ", RGBA8 tables" } else { "" },
        args.out.display()
    ).map_err(CliError::stdout)?;
    let mean = |image: &hairmath::render::Image| {
        let [r, g, b] = image.mean();
        format!("mean radiance ({r:.4}, {g:.4}, {b:.4})")
    };
    writeln!(out, "reference: {}", mean(&comparison.reference)).map_err(CliError::stdout)?;
    writeln!(
        out,
        "{}, {}",
        line("gerard", &gerard.error),
        mean(&gerard.image)
    )
    .map_err(CliError::stdout)?;
    writeln!(
        out,
        "{}, {}",
        line("kajiya-kay", &comparison.kajiya_kay_error),
        mean(&comparison.kajiya_kay)
    )
    .map_err(CliError::stdout)?;
    let at_l: Vec<String> = projection
        .iter()
        .zip(PROJECTION_SIN_THETA_R)
        .map(|(bands, s)| {
            let [r, tt, trt] = [0, 1, 2].map(|lobe| bands[config.phase_lmax][lobe]);
            format!("{r:.3} / {tt:.3} / {trt:.3} at {s}")
        })
        .collect();
    writeln!(
        out,
        "phase projection error at l <= {} (R / TT / TRT at sin theta_r): {}",
        config.phase_lmax,
        at_l.join(", ")
    )
    .map_err(CliError::stdout)?;
    let half = comparison.reference_rule.halved();
    writeln!(
        out,
        "{} (gerard against it: relative error {:.4})",
        line(
            &format!("reference at {} circles", half.circles),
            &comparison.reference_convergence
        ),
        gerard.error_against_half.relative_error
    )
    .map_err(CliError::stdout)?;
    Ok(())
}

/// reference.png, gerard.png, kajiya_kay.png, difference.png (|gerard - reference| times
/// [`DIFFERENCE_GAIN`]) and side_by_side.png (the reference, Gerard's, the difference), all at
/// the reference's exposure.
fn write_images(dir: &Path, c: &GerardComparison, gerard: &GerardRender) -> Result<(), CliError> {
    fs::create_dir_all(dir).map_err(|e| io_error(dir, e))?;
    let exposure = c.reference.exposure();
    let difference = gerard.image.difference(&c.reference)?;
    let images = [
        ("reference.png", &c.reference, exposure),
        ("gerard.png", &gerard.image, exposure),
        ("kajiya_kay.png", &c.kajiya_kay, exposure),
        ("difference.png", &difference, DIFFERENCE_GAIN * exposure),
    ];
    let mut encoded = Vec::new();
    for (name, image, exposure) in images {
        let rgb = image.to_srgb8(exposure);
        write_png(&dir.join(name), image.size, image.size, &rgb)?;
        encoded.push(rgb);
    }
    let size = c.reference.size;
    let mut side_by_side = Vec::with_capacity(3 * size * size * 3);
    for row in 0..size {
        for image in [0, 1, 3] {
            side_by_side.extend_from_slice(&encoded[image][row * size * 3..(row + 1) * size * 3]);
        }
    }
    write_png(&dir.join("side_by_side.png"), 3 * size, size, &side_by_side)
}

fn write_png(path: &Path, width: usize, height: usize, rgb: &[u8]) -> Result<(), CliError> {
    let file = fs::File::create(path).map_err(|e| io_error(path, e))?;
    let dim = |n: usize| u32::try_from(n).expect("image sides are at most 3 x 4096");
    let mut encoder = png::Encoder::new(std::io::BufWriter::new(file), dim(width), dim(height));
    encoder.set_color(png::ColorType::Rgb);
    encoder.set_depth(png::BitDepth::Eight);
    let fail = |e: png::EncodingError| CliError::Strands(format!("{}: {e}", path.display()));
    let mut writer = encoder.write_header().map_err(fail)?;
    writer.write_image_data(rgb).map_err(fail)?;
    writer.finish().map_err(fail)
}

/// The values of `sin theta_r` at which `errors.json` reports the phase's projection error.
const PROJECTION_SIN_THETA_R: [f64; 4] = [0.0, 0.5, 0.9, 0.99];

/// `phase_projection_error` at [`PROJECTION_SIN_THETA_R`]: per value, per band limit, per lobe.
fn projection_json(projection: &[Vec<Vec<f64>>]) -> serde_json::Value {
    let at: Vec<_> = projection
        .iter()
        .zip(PROJECTION_SIN_THETA_R)
        .map(|(bands, s)| json!({ "sin_theta_r": s, "by_band_limit": bands }))
        .collect();
    json!({
        "definition": "per band limit L = 0..4 (index) and lobe [R, TT, TRT]: sqrt(int (S - S_L)^2 / int S^2), what the expansion truncated to l <= L loses against S",
        "at": at,
    })
}

fn rule_json(rule: &MeridianRule) -> serde_json::Value {
    json!({
        "circles": rule.circles,
        "scattering_circles": rule.scattering_circles,
        "samples": rule.samples,
    })
}

fn error_json(e: &ImageError) -> serde_json::Value {
    json!({ "rmse": e.rmse, "relative_error": e.relative_error })
}

fn errors_json(
    args: &RenderArgs,
    c: &GerardComparison,
    gerard: &GerardRender,
    (gerard_source, kajiya_kay): (
        &hairmath::bcsdf::Marschner2003,
        &hairmath::models::KajiyaKay<f64>,
    ),
    seconds: f64,
) -> serde_json::Value {
    json!({
        "rmse": gerard.error.rmse,
        "relative_error": gerard.error.relative_error,
        "kajiya_kay": error_json(&c.kajiya_kay_error),
        "mean_radiance": {
            "reference": c.reference.mean(),
            "gerard": gerard.image.mean(),
            "kajiya_kay": c.kajiya_kay.mean(),
        },
        "reference_convergence": {
            "against": rule_json(&c.reference_rule.halved()),
            "rmse": c.reference_convergence.rmse,
            "relative_error": c.reference_convergence.relative_error,
            "gerard_relative_error_against_it": gerard.error_against_half.relative_error,
        },
        "file": args.file.display().to_string(),
        "size": args.size,
        "covered_pixels": c.covered,
        "reference_rule": rule_json(&c.reference_rule),
        "kajiya_kay_directions": args.directions,
        "phase_lmax": args.phase_lmax,
        "v_lmax": args.v_lmax,
        "environment_lmax": gerard.config.environment_lmax(),
        "absorption": PhaseAbsorption::from(args.absorption).name(),
        "rgba8": args.rgba8,
        "bias": args.bias,
        "kajiya_kay_best_fit": format!("{kajiya_kay:?}"),
        "gerard_best_fit_source": format!("{gerard_source:?}"),
        "hair": format!("{:?}", HairParams::default()),
        "error_definition": "over covered pixels and RGB: rmse = sqrt(mean (image - reference)^2), relative_error = sqrt(sum (image - reference)^2 / sum reference^2)",
        "seconds": seconds,
    })
}

fn io_error(path: &Path, e: std::io::Error) -> CliError {
    CliError::Strands(format!("{}: {e}", path.display()))
}

fn write(path: &Path, bytes: &[u8]) -> Result<(), CliError> {
    fs::write(path, bytes).map_err(|e| io_error(path, e))
}
