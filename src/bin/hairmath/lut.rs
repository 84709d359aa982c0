//! `hairmath lut`: bakes a lookup table, writes it as raw f32 + JSON (and PNG for 2D tables),
//! and prints the measured error of lookup against direct evaluation.

use std::path::PathBuf;

use clap::{Args, ValueEnum};
use hairmath::azimuthal::CausticParams;
use hairmath::lut::{
    bake, lookup_error, write_png, write_raw, Baker, FarFieldN, GerardN, NguyenM, NguyenN, Table,
};

use crate::CliError;

/// Which table to bake.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum LutKind {
    /// Nguyen-Donnelly M texture over (sin theta_i, sin theta_o): M_R, M_TT, M_TRT, cos theta_d.
    NguyenM,
    /// Nguyen-Donnelly N textures over (cos phi, cos theta_d): (N_TT rgb, N_R) and N_TRT rgb.
    NguyenN,
    /// Gerard's N_p,LUT(phi, theta_d) per lobe at zero absorption.
    Gerard,
    /// Chiang far-field A_p N_p over (phi, theta_o, beta_n) at the given absorption.
    FarField,
}

/// Arguments of `hairmath lut`.
#[derive(Args, Debug)]
pub struct LutArgs {
    /// The table to bake.
    #[arg(long, value_enum)]
    kind: LutKind,
    /// Samples per axis, comma separated (2 sizes for 2D kinds, 3 for far-field); default
    /// 64,64 (nguyen-m, nguyen-n), 64,32 (gerard), 16,8,4 (far-field). The far field costs
    /// about 0.2 ms per sample.
    #[arg(long, value_delimiter = ',')]
    size: Vec<usize>,
    /// Relative index of refraction.
    #[arg(long, default_value_t = 1.55)]
    eta: f64,
    /// Absorption per unit fibre radius, R,G,B (nguyen-n and far-field; gerard uses 0).
    #[arg(long, value_delimiter = ',', default_value = "0.2,0.4,0.8")]
    sigma_a: Vec<f64>,
    /// R lobe width beta_R in radians (nguyen-m); beta_TT = beta_R/2, beta_TRT = 2 beta_R.
    #[arg(long, default_value_t = 7.5f64.to_radians())]
    beta_m: f64,
    /// R lobe shift alpha_R in radians (nguyen-m); alpha_TT = -alpha_R/2, alpha_TRT = -3 alpha_R/2.
    #[arg(long, default_value_t = (-5f64).to_radians(), allow_negative_numbers = true)]
    alpha: f64,
    /// beta_n range MIN,MAX of the far-field table's third axis.
    #[arg(long, value_delimiter = ',', default_value = "0.2,0.8")]
    beta_n: Vec<f64>,
    /// Largest theta_d of the gerard table, radians.
    #[arg(long, default_value_t = core::f64::consts::FRAC_PI_2)]
    theta_d_max: f64,
    /// Relative tolerance of the far-field reference integrals.
    #[arg(long, default_value_t = 1e-6)]
    rel_tol: f64,
    /// Leave out Marschner's TRT caustic treatment (nguyen-n, gerard).
    #[arg(long)]
    no_caustic: bool,
    /// Number of off-grid points at which lookup is compared with direct evaluation (0: skip).
    #[arg(long, default_value_t = 1000)]
    error_points: usize,
    /// Output directory (created if missing).
    #[arg(long, default_value = ".")]
    out: PathBuf,
}

fn params(e: impl std::fmt::Display) -> CliError {
    CliError::Params(e.to_string())
}

fn lut_error(e: hairmath::lut::LutError) -> CliError {
    match e {
        hairmath::lut::LutError::Io { source, .. } => CliError::Io(source),
        other => params(other),
    }
}

fn rgb(values: &[f64]) -> Result<[f64; 3], CliError> {
    match values {
        [r, g, b] => Ok([*r, *g, *b]),
        [v] => Ok([*v; 3]),
        _ => Err(CliError::Params(format!(
            "--sigma-a takes 1 or 3 values, {} given",
            values.len()
        ))),
    }
}

/// Bakes, writes and reports.
pub fn run(args: &LutArgs) -> Result<(), CliError> {
    let caustic = (!args.no_caustic).then(CausticParams::default);
    let baker: Box<dyn Baker> = match args.kind {
        LutKind::NguyenM => Box::new(NguyenM::new(args.beta_m, args.alpha).map_err(params)?),
        LutKind::NguyenN => {
            Box::new(NguyenN::new(args.eta, rgb(&args.sigma_a)?, caustic).map_err(params)?)
        }
        LutKind::Gerard => {
            Box::new(GerardN::new(args.eta, args.theta_d_max, caustic).map_err(params)?)
        }
        LutKind::FarField => {
            let [lo, hi] = args.beta_n[..] else {
                return Err(CliError::Params("--beta-n takes MIN,MAX".to_string()));
            };
            Box::new(
                FarFieldN::new(args.eta, rgb(&args.sigma_a)?, lo, hi, args.rel_tol)
                    .map_err(params)?,
            )
        }
    };
    let sizes = if args.size.is_empty() {
        baker.default_sizes()
    } else {
        args.size.clone()
    };
    let table = bake(baker.as_ref(), &sizes).map_err(lut_error)?;
    std::fs::create_dir_all(&args.out)?;
    let stem = baker.kind().replace('-', "_");
    let dims: Vec<String> = sizes.iter().map(usize::to_string).collect();
    let name = format!("{stem}_{}", dims.join("x"));
    let raw = args.out.join(format!("{name}.f32"));
    let json = write_raw(&table, &raw).map_err(lut_error)?;
    println!("wrote {}", raw.display());
    println!("wrote {}", json.display());
    for (suffix, channels) in png_layout(args.kind) {
        let path = args.out.join(format!("{name}{suffix}.png"));
        write_png(&table, channels, &path).map_err(lut_error)?;
        println!("wrote {}", path.display());
    }
    print_scales(&table);
    if args.error_points > 0 {
        let s = lookup_error(baker.as_ref(), &table, args.error_points).map_err(lut_error)?;
        println!(
            "lookup vs direct at {} off-grid points: max abs {:.3e}, mean abs {:.3e}, \
             max rel {:.3e} (channel {}), mean rel {:.3e} (relative to each channel's maximum)",
            s.points,
            s.max_abs,
            s.mean_abs,
            s.max_rel,
            table.channels()[s.worst_channel],
            s.mean_rel
        );
    }
    Ok(())
}

/// The PNG files of each kind: (file suffix, channels to R, G, B, A).
fn png_layout(kind: LutKind) -> Vec<(&'static str, &'static [usize])> {
    match kind {
        LutKind::NguyenM => vec![("", &[0, 1, 2, 3])],
        // GPU Gems 2 ch. 23: N_TT in RGB and N_R in alpha; N_TRT in a second texture.
        LutKind::NguyenN => vec![("_tt_r", &[0, 1, 2, 3]), ("_trt", &[4, 5, 6])],
        LutKind::Gerard => vec![("", &[0, 1, 2])],
        // 3D float data: raw only.
        LutKind::FarField => vec![],
    }
}

fn print_scales(table: &Table) {
    let scales = table.png_scale();
    let items: Vec<String> = table
        .channels()
        .iter()
        .zip(scales)
        .map(|(c, s)| format!("{c} {s:.6e}"))
        .collect();
    println!("8-bit scale (texel 255 = value): {}", items.join(", "));
}
