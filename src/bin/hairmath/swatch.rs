//! `hairmath render`: the procedural hair swatch of [`hairmath::render::swatch`] rendered with
//! one model and written as a PNG: the path tracer for the reference `chiang` (its near field,
//! multiple scattering), the single-scattering direct-light shader for every other model.
//! This file only parses, calls the library and writes what it returns.

use crate::flags::{model_names, ModelFlags};
use crate::{with_stdout, CliError};
use clap::builder::PossibleValuesParser;
use clap::Args;
use hairmath::bcsdf::{ChiangHair, FromInputs};
use hairmath::registry::find_model;
use hairmath::render::swatch::direct::{DirectLighting, DirectSettings};
use hairmath::render::swatch::light::SwatchLight;
use hairmath::render::swatch::path::{path_trace, PathSettings, MAX_SAMPLES};
use hairmath::render::swatch::{Swatch, SwatchSettings};
use hairmath::render::{side_by_side, write_png, Image};
use hairmath::ParamError;
use std::io::Write;
use std::path::{Path, PathBuf};
use std::time::Instant;

/// Arguments of `hairmath render`.
#[derive(Args, Debug)]
pub struct SwatchArgs {
    /// The scattering model: `chiang` is path-traced, every other one shaded with single
    /// scattering. Inputs not given take the default hair's values (brown, eumelanin 1.3,
    /// beta_m = beta_n = 0.3; a real-time model's mapped inputs for it).
    #[arg(long, default_value = "chiang", value_parser = PossibleValuesParser::new(model_names()))]
    model: String,
    /// The models' inputs.
    #[command(flatten)]
    flags: ModelFlags,
    /// The PNG file to write.
    #[arg(long)]
    out: PathBuf,
    /// Pixels per side, in [1, 4096].
    #[arg(long, default_value_t = 128)]
    size: usize,
    /// Paths per pixel of the path tracer (chiang), in [1, 2^20]; the single-scattering
    /// shader's quadrature is fixed (256 environment directions, 16 over the light).
    #[arg(long, default_value_t = 16)]
    samples: usize,
    /// The seed of the path tracer and of the swatch's fibres.
    #[arg(long, default_value_t = 1)]
    seed: u64,
}

/// Runs `hairmath render`.
pub fn run(args: &SwatchArgs) -> Result<(), CliError> {
    let entry =
        find_model(&args.model).ok_or_else(|| CliError::UnknownModel(args.model.clone()))?;
    let values = args.flags.values_at_default_hair(entry)?;
    ParamError::check(
        "samples",
        args.samples as f64,
        "must be in [1, 2^20]",
        |n| (1.0..=MAX_SAMPLES as f64).contains(&n),
    )?;
    let swatch = Swatch::new(&SwatchSettings {
        seed: args.seed,
        ..SwatchSettings::default()
    })?;
    let camera = swatch.camera(args.size)?;
    let light = SwatchLight::default();
    let start = Instant::now();
    let (image, renderer) = if entry.name == "chiang" {
        let settings = PathSettings {
            samples: args.samples,
            seed: args.seed,
            ..PathSettings::default()
        };
        let hair = ChiangHair::<f64>::from_inputs(&values)?;
        let traced = path_trace(&swatch, &camera, &hair, &light, &settings)?;
        (traced.image, "path tracer (MIS, Russian roulette)")
    } else {
        let model = (entry.build)(&values)?;
        let lighting = DirectLighting::new(&swatch, &camera, &light, &DirectSettings::default())?;
        (lighting.shade(model.as_ref()), "single scattering")
    };
    let seconds = start.elapsed().as_secs_f64();
    write_image(&args.out, &image)?;
    let m = image.mean();
    with_stdout(|out| {
        let (name, size, path) = (entry.name, args.size, args.out.display());
        writeln!(
            out,
            "{name}: {renderer}, {size}x{size} pixels in {seconds:.2} s; mean radiance over \
             the fibres {:.5} {:.5} {:.5}; wrote {path}",
            m[0], m[1], m[2]
        )
        .map_err(CliError::stdout)
    })
}

/// Writes `image` as an 8-bit sRGB PNG at its own exposure.
pub fn write_image(path: &Path, image: &Image) -> Result<(), CliError> {
    let rgb = side_by_side(&[image], image.exposure());
    write_png(path, image.size, image.size, &rgb).map_err(|e| CliError::io(path, e))
}
