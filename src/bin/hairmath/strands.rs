//! `hairmath groom` (a procedural groom written as a `.hair` file) and `hairmath bake` (the
//! per-vertex SH transmittance of a `.hair` file). This file only parses, calls
//! [`hairmath::strands`] and writes what it returns.

use crate::CliError;
use clap::{Args, ValueEnum};
use hairmath::strands::groom::{groom, GroomKind, GroomSettings};
use hairmath::strands::hair_file::{read_hair_file, write_hair_file, HairFile};
use hairmath::strands::occluders::Opacity;
use hairmath::strands::transmittance::{
    bake, compare, BakeComparison, BakeSettings, Baker, FastSettings, Transmittance,
};
use hairmath::strands::Strands;
use serde_json::json;
use std::fs;
use std::io::Write;
use std::ops::Range;
use std::path::{Path, PathBuf};
use std::time::Instant;

/// The shape of a groom's strands, as `--kind` names it.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum Kind {
    /// Strands that only bend under gravity.
    Straight,
    /// A planar wave across each strand.
    Wavy,
    /// A helix around each strand.
    Curly,
}

impl From<Kind> for GroomKind {
    fn from(kind: Kind) -> Self {
        match kind {
            Kind::Straight => GroomKind::Straight,
            Kind::Wavy => GroomKind::Wavy,
            Kind::Curly => GroomKind::Curly,
        }
    }
}

/// Arguments of `hairmath groom`.
#[derive(Args, Debug)]
pub struct GroomArgs {
    /// The shape of the strands.
    #[arg(long, value_enum)]
    kind: Kind,
    /// The number of strands, in [1, 1000000].
    #[arg(long)]
    strands: usize,
    /// Points per strand, in [2, 65536].
    #[arg(long)]
    points: usize,
    /// The seed: the same seed gives the same file.
    #[arg(long, default_value_t = 0)]
    seed: u64,
    /// Root thickness (diameter) in head radii, in (0, 0.1]; it tapers to half at the tip.
    #[arg(long, default_value_t = GroomSettings::DEFAULT_THICKNESS)]
    thickness: f32,
    /// Mean strand length in head radii, in (0, 10].
    #[arg(long, default_value_t = GroomSettings::DEFAULT_LENGTH)]
    length: f32,
    /// Transparency stored at every point, in [0, 1] (0 opaque).
    #[arg(long, default_value_t = 0.0)]
    transparency: f32,
    /// The `.hair` file to write.
    #[arg(long, value_name = "FILE.hair")]
    out: PathBuf,
}

/// Runs `hairmath groom`.
pub fn run_groom(args: &GroomArgs) -> Result<(), CliError> {
    let settings = GroomSettings {
        kind: args.kind.into(),
        strands: args.strands,
        points: args.points,
        seed: args.seed,
        thickness: args.thickness,
        length: args.length,
        transparency: args.transparency,
    };
    let strands = groom(&settings)?;
    let info = format!(
        "hairmath groom {} {}x{} seed {}",
        settings.kind.name(),
        settings.strands,
        settings.points,
        settings.seed
    );
    let file = HairFile { strands, info };
    write_hair_file(&args.out, &file).map_err(|e| CliError::Strands(e.to_string()))?;
    writeln!(
        std::io::stdout().lock(),
        "{}: {} strands, {} points",
        args.out.display(),
        file.strands.strand_count(),
        file.strands.point_count()
    )
    .map_err(CliError::stdout)?;
    Ok(())
}

/// Arguments of `hairmath bake`.
#[derive(Args, Debug)]
pub struct BakeArgs {
    /// The `.hair` file.
    file: PathBuf,
    /// The highest SH band: (L + 1)^2 coefficients per vertex, L in [0, 16].
    #[arg(long, default_value_t = 2)]
    lmax: usize,
    /// The opacity of every segment, in [0, 1]; without it, 1 - the file's transparency.
    #[arg(long)]
    opacity: Option<f32>,
    /// Bake with the exact baker (rays through the hierarchy) instead of the fast one.
    #[arg(long)]
    exact: bool,
    /// Directions per vertex of the exact baker, in [1, 4194304].
    #[arg(long, default_value_t = Baker::EXACT_DIRECTIONS)]
    directions: usize,
    /// The fast baker's direction cells: 2 n^2 of them, n in [1, 64].
    #[arg(long, default_value_t = FastSettings::default().bands)]
    bands: usize,
    /// Also bake the same vertices with the exact baker at --directions (and at a quarter of
    /// them, to show the reference's convergence) and print how far the bake is from it: the
    /// coefficients' RMS and largest difference, and those of V reconstructed at 64 random
    /// directions per vertex (also under "comparison" in transmittance.json).
    #[arg(long, conflicts_with = "exact")]
    compare: bool,
    /// Bake the vertices of the first N strands only (all strands still occlude).
    #[arg(long, value_name = "N")]
    first_strands: Option<usize>,
    /// The folder to write transmittance.f32 and transmittance.json to (created if needed).
    #[arg(long, value_name = "DIR")]
    out: PathBuf,
}

/// Runs `hairmath bake`.
pub fn run_bake(args: &BakeArgs) -> Result<(), CliError> {
    let file = read_hair_file(&args.file).map_err(|e| CliError::Strands(e.to_string()))?;
    let strands = &file.strands;
    let count = args.first_strands.unwrap_or(strands.strand_count());
    let vertices = match count {
        0 => 0..0,
        n => {
            0..strands
                .strand_points(n - 1)
                .ok_or_else(|| too_many(n, strands.strand_count()))?
                .end
        }
    };
    let settings = BakeSettings {
        lmax: args.lmax,
        opacity: args
            .opacity
            .map_or(Opacity::FromTransparency, Opacity::Uniform),
        baker: if args.exact {
            Baker::Exact {
                directions: args.directions,
            }
        } else {
            Baker::Fast(FastSettings {
                bands: args.bands,
                ..FastSettings::default()
            })
        },
    };
    let bar = crate::progress::bar("baking (vertices)");
    let start = Instant::now();
    let baked = bake(
        strands,
        vertices.clone(),
        &settings,
        &crate::progress::callback(&bar),
    );
    bar.finish_and_clear();
    let baked = baked?;
    let seconds = start.elapsed().as_secs_f64();
    let comparison = args
        .compare
        .then(|| {
            compare_with_exact(
                strands,
                vertices.clone(),
                &settings,
                &baked,
                args.directions,
            )
        })
        .transpose()?;
    fs::create_dir_all(&args.out).map_err(|e| io_error(&args.out, e))?;
    let raw: Vec<u8> = baked
        .coefficients
        .iter()
        .flat_map(|c| c.to_le_bytes())
        .collect();
    write(&args.out.join("transmittance.f32"), &raw)?;
    let description = json!({
        "file": args.file.display().to_string(),
        "vertex_count": vertices.len(),
        "first_vertex": vertices.start,
        "lmax": baked.lmax,
        "coefficients_per_vertex": baked.stride(),
        "layout": "little-endian f32, vertex-major, (lmax + 1)^2 coefficients per vertex, index l (l + 1) + m, vertices in the file's order",
        "sh_convention": "real, orthonormal, Condon-Shortley phase, sin(|m| phi) for m < 0 (hairmath::sh; Y(1,-1) = -0.4886025 y)",
        "baker": settings.baker.name(),
        "baker_settings": format!("{:?}", settings.baker),
        "opacity": args.opacity.map_or(json!("1 - transparency of the file"), |a| json!(a)),
        "timing": { "seconds": seconds, "threads": rayon::current_num_threads() },
        "comparison": comparison.as_ref().map(|c| json!({
            "against": format!("exact, {} directions", args.directions),
            "exact_seconds": c.exact_seconds,
            "bake": comparison_json(&c.bake),
            "reference_convergence": comparison_json(&c.reference),
        })),
    });
    let text = serde_json::to_string_pretty(&description).expect("JSON of plain values");
    write(&args.out.join("transmittance.json"), text.as_bytes())?;
    let mut out = std::io::stdout().lock();
    writeln!(
        out,
        "{} vertices, lmax {}, {} baker: {seconds:.2} s -> {}",
        vertices.len(),
        baked.lmax,
        settings.baker.name(),
        args.out.display()
    )
    .map_err(CliError::stdout)?;
    if let Some(comparison) = &comparison {
        writeln!(out, "{}", comparison_table(comparison, args.directions))
            .map_err(CliError::stdout)?;
    }
    Ok(())
}

/// The bake against the exact baker at `directions`, and the exact baker at a quarter of them
/// against it.
struct Comparison {
    bake: BakeComparison,
    reference: BakeComparison,
    exact_seconds: f64,
}

/// Bakes `vertices` with the exact baker at `directions` and at a quarter of them, and
/// compares `baked` and the quarter bake with the full one.
fn compare_with_exact(
    strands: &Strands,
    vertices: Range<usize>,
    settings: &BakeSettings,
    baked: &Transmittance,
    directions: usize,
) -> Result<Comparison, CliError> {
    let exact = |directions| BakeSettings {
        baker: Baker::Exact { directions },
        ..*settings
    };
    let exact_bake = |directions, message: &'static str| {
        let bar = crate::progress::bar(message);
        let baked = bake(
            strands,
            vertices.clone(),
            &exact(directions),
            &crate::progress::callback(&bar),
        );
        bar.finish_and_clear();
        baked
    };
    let start = Instant::now();
    let reference = exact_bake(directions, "exact bake (vertices)")?;
    let exact_seconds = start.elapsed().as_secs_f64();
    let quarter = exact_bake((directions / 4).max(1), "quarter bake (vertices)")?;
    Ok(Comparison {
        bake: compare(baked, &reference, COMPARISON_DIRECTIONS, 1)?,
        reference: compare(&quarter, &reference, COMPARISON_DIRECTIONS, 1)?,
        exact_seconds,
    })
}

/// Random directions per vertex at which the comparison reconstructs V.
const COMPARISON_DIRECTIONS: usize = 64;

fn comparison_json(c: &BakeComparison) -> serde_json::Value {
    json!({
        "vertices": c.vertices,
        "coefficient_rms": c.coefficient_rms,
        "coefficient_max": c.coefficient_max,
        "v_rms": c.v_rms,
        "v_max": c.v_max,
        "reference_mean_v": c.reference_mean_v,
    })
}

fn comparison_table(c: &Comparison, directions: usize) -> String {
    let row = |name: String, c: &BakeComparison| {
        format!(
            "| {name} | {:.4} | {:.4} | {:.4} | {:.4} |",
            c.coefficient_rms, c.coefficient_max, c.v_rms, c.v_max
        )
    };
    [
        format!(
            "against the exact baker at {directions} directions ({:.1} s; mean V {:.4}):",
            c.exact_seconds, c.reference.reference_mean_v
        ),
        "| bake | coefficient rms | coefficient max | V rms | V max |".into(),
        "|---|---:|---:|---:|---:|".into(),
        row("this bake".into(), &c.bake),
        row(
            format!("exact, {} directions", (directions / 4).max(1)),
            &c.reference,
        ),
    ]
    .join("\n")
}

fn too_many(asked: usize, strands: usize) -> CliError {
    CliError::Strands(format!(
        "--first-strands {asked}: the file has {strands} strands"
    ))
}

fn io_error(path: &Path, e: std::io::Error) -> CliError {
    CliError::Strands(format!("{}: {e}", path.display()))
}

fn write(path: &Path, bytes: &[u8]) -> Result<(), CliError> {
    fs::write(path, bytes).map_err(|e| io_error(path, e))
}
