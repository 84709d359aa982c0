//! `hairmath lut`: bakes a lookup table, writes it as raw f32 + JSON (and PNG for 2D tables),
//! and prints the measured error of lookup against direct evaluation.

use std::io::{self, Write};
use std::path::{Path, PathBuf};

use clap::{Args, ValueEnum};
use hairmath::absorption::Absorption;
use hairmath::azimuthal::CausticParams;
use hairmath::lut::{
    bake_with_progress, check_evaluations, lookup_error_with_progress, write_png, write_raw, Baker,
    FarFieldN, GerardN, NguyenM, NguyenN, Table,
};
use hairmath::params::{AzimuthalRoughness, LobeShift, LobeWidth, MarschnerLobes, RefractiveIndex};

use crate::flags::{parse_floats, parse_rgb};
use crate::{create_dir, with_stdout, CliError};

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

/// Arguments of `hairmath lut`. Flags shared with `hairmath eval` mean the same there.
#[derive(Args, Debug)]
pub struct LutArgs {
    /// The table to bake.
    #[arg(long, value_enum)]
    kind: LutKind,
    /// Samples per axis, comma separated (2 sizes for 2D kinds, 3 for far-field); default
    /// 64,64 (nguyen-m, nguyen-n), 64,32 (gerard), 16,8,4 (far-field). The far field costs
    /// about 0.16 ms per sample and takes at most 65536 samples; the other kinds at most
    /// 16777216 (about 12 s).
    #[arg(long, value_delimiter = ',')]
    size: Vec<usize>,
    /// Relative index of refraction eta, in (1, 3].
    #[arg(long, default_value_t = 1.55)]
    eta: f64,
    /// Absorption per unit fibre radius, linear RGB, or one value for all channels (nguyen-n
    /// and far-field; gerard uses 0).
    #[arg(long, value_name = "R,G,B", value_parser = parse_rgb, default_value = "0.2,0.4,0.8", allow_hyphen_values = true)]
    sigma_a: [f64; 3],
    /// Width beta_R of Marschner's R lobe in degrees, in (0, 45] (nguyen-m); beta_TT =
    /// beta_R/2, beta_TRT = 2 beta_R.
    #[arg(long, value_name = "DEGREES", default_value_t = 7.5)]
    beta_r_deg: f64,
    /// Shift alpha_R of Marschner's R lobe in degrees, |alpha_R| <= 22.5 (nguyen-m); alpha_TT
    /// = -alpha_R/2, alpha_TRT = -3 alpha_R/2.
    #[arg(long, value_name = "DEGREES", default_value_t = -5.0)]
    alpha_r_deg: f64,
    /// The range MIN,MAX of azimuthal roughness beta_n (each in [1e-16, 1]) of the far-field
    /// table's third axis.
    #[arg(long, value_name = "MIN,MAX", value_parser = parse_floats::<2>, default_value = "0.2,0.8", allow_hyphen_values = true)]
    beta_n_range: [f64; 2],
    /// Largest theta_d of the gerard table, degrees, in (0, 90].
    #[arg(long, value_name = "DEGREES", default_value_t = 90.0)]
    theta_d_max_deg: f64,
    /// Relative tolerance of the far-field reference integrals, in [1e-12, 1e-2].
    #[arg(long, default_value_t = 1e-6)]
    rel_tol: f64,
    /// Leave out Marschner's TRT caustic treatment (nguyen-n, gerard).
    #[arg(long)]
    no_caustic: bool,
    /// Number of off-grid points at which lookup is compared with direct evaluation (0: skip);
    /// at most 65536 for far-field, 16777216 for the other kinds (each point costs one
    /// evaluation: 0.16 ms for far-field, up to 3 us for the others).
    #[arg(long, default_value_t = 1000)]
    error_points: usize,
    /// Output directory (created if missing).
    #[arg(long, default_value = ".")]
    out: PathBuf,
}

/// The baker the flags describe, every parameter validated by its type.
fn baker(args: &LutArgs) -> Result<Box<dyn Baker>, CliError> {
    let caustic = (!args.no_caustic).then(CausticParams::default);
    let eta = RefractiveIndex::new(args.eta)?;
    Ok(match args.kind {
        LutKind::NguyenM => Box::new(NguyenM::new(MarschnerLobes {
            alpha_r: LobeShift::new(args.alpha_r_deg.to_radians())?,
            beta_r: LobeWidth::new(args.beta_r_deg.to_radians())?,
        })),
        LutKind::NguyenN => Box::new(NguyenN::new(eta, Absorption::new(args.sigma_a)?, caustic)),
        LutKind::Gerard => Box::new(GerardN::new(
            eta,
            args.theta_d_max_deg.to_radians(),
            caustic,
        )?),
        LutKind::FarField => {
            let [lo, hi] = args.beta_n_range;
            Box::new(FarFieldN::new(
                eta,
                Absorption::new(args.sigma_a)?,
                AzimuthalRoughness::new(lo)?,
                AzimuthalRoughness::new(hi)?,
                args.rel_tol,
            )?)
        }
    })
}

/// Bakes, writes and reports. Every limit (the table's size, the error points) is checked
/// before the bake starts.
pub fn run(args: &LutArgs) -> Result<(), CliError> {
    let baker = baker(args)?;
    let sizes = if args.size.is_empty() {
        baker.default_sizes()
    } else {
        args.size.clone()
    };
    check_evaluations(baker.as_ref(), args.error_points, "error points")?;
    create_dir(&args.out)?;
    let bar = crate::progress::bar("baking (samples)");
    let table = bake_with_progress(baker.as_ref(), &sizes, &crate::progress::callback(&bar));
    bar.finish_and_clear();
    let table = table?;
    with_stdout(|out| write_and_report(args, baker.as_ref(), &sizes, &table, out))
}

/// Writes the table's files and prints what was written, the 8-bit scales and the lookup
/// error to `out` (standard output).
fn write_and_report(
    args: &LutArgs,
    baker: &dyn Baker,
    sizes: &[usize],
    table: &Table,
    out: &mut impl Write,
) -> Result<(), CliError> {
    let stem = baker.kind().replace('-', "_");
    let dims: Vec<String> = sizes.iter().map(usize::to_string).collect();
    let name = format!("{stem}_{}", dims.join("x"));
    let raw = args.out.join(format!("{name}.f32"));
    let json = write_raw(table, &raw)?;
    let mut wrote = |path: &Path| writeln!(out, "wrote {}", path.display());
    wrote(&raw).map_err(CliError::stdout)?;
    wrote(&json).map_err(CliError::stdout)?;
    for (suffix, channels) in png_layout(args.kind) {
        let path = args.out.join(format!("{name}{suffix}.png"));
        write_png(table, channels, &path)?;
        wrote(&path).map_err(CliError::stdout)?;
    }
    print_scales(out, table).map_err(CliError::stdout)?;
    if args.error_points > 0 {
        let bar = crate::progress::bar("lookup error (points)");
        let s = lookup_error_with_progress(
            baker,
            table,
            args.error_points,
            &crate::progress::callback(&bar),
        );
        bar.finish_and_clear();
        let s = s?;
        writeln!(
            out,
            "lookup vs direct at {} off-grid points: max abs {:.3e}, mean abs {:.3e}, \
             max rel {:.3e} (channel {}), mean rel {:.3e} (relative to each channel's maximum)",
            s.points,
            s.max_abs,
            s.mean_abs,
            s.max_rel,
            table.channels()[s.worst_channel],
            s.mean_rel
        )
        .map_err(CliError::stdout)?;
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

fn print_scales(out: &mut impl Write, table: &Table) -> io::Result<()> {
    let scales = table.png_scale();
    let items: Vec<String> = table
        .channels()
        .iter()
        .zip(scales)
        .map(|(c, s)| format!("{c} {s:.6e}"))
        .collect();
    writeln!(out, "8-bit scale (texel 255 = value): {}", items.join(", "))
}
