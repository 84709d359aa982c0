//! `hairmath shader`: a model's shader module in WGSL, GLSL, HLSL, MSL or SPIR-V
//! ([`hairmath::shader::model_shader`]), or the repository's `shaders/` folder. This file only
//! writes what the library emits.

use crate::flags::{model_names, ModelFlags};
use crate::{create_dir, with_stdout, write_file, CliError};
use clap::builder::{PossibleValue, PossibleValuesParser};
use clap::Args;
use hairmath::registry::find_model;
use hairmath::shader::{committed_shaders, model_shader, table_files, CommittedFile, Language};
use std::io::Write;
use std::path::{Path, PathBuf};

/// The `--lang` values ([`Language::ALL`]), for `shader` and `plan`.
pub fn languages() -> Vec<PossibleValue> {
    Language::ALL
        .iter()
        .map(|(_, name, help)| PossibleValue::new(*name).help(*help))
        .collect()
}

/// Arguments of `hairmath shader`.
#[derive(Args, Debug)]
pub struct ShaderArgs {
    /// The scattering model (`hairmath::registry::MODELS`).
    #[arg(long, value_parser = PossibleValuesParser::new(model_names()),
          required_unless_present = "committed")]
    model: Option<String>,
    /// The models' inputs, as for `eval`; every input not named by --varying is baked.
    #[command(flatten)]
    flags: ModelFlags,
    /// The language: wgsl writes the functions only; the others add the compute entry point.
    #[arg(long, default_value = "wgsl", value_parser = PossibleValuesParser::new(languages()))]
    lang: String,
    /// Model inputs that become arguments of hair_bcsdf after wo (and h), in this order, for
    /// per-pixel values: for example `--varying color,roughness`.
    #[arg(long, value_delimiter = ',', value_name = "NAME,...")]
    varying: Vec<String>,
    /// Write the module to this file instead of standard output; the lookup tables a module
    /// binds, with their JSON descriptions and a JSON description of the bindings, are written
    /// beside it (`<stem>.lut<k>.f32`, `<stem>.lut<k>.json`, `<stem>.bindings.json`).
    #[arg(long, value_name = "FILE")]
    out: Option<PathBuf>,
    /// Write the repository's shaders/ folder (every model at its defaults, WGSL and GLSL,
    /// tables, README) to DIR instead.
    #[arg(long, value_name = "DIR", conflicts_with_all = ["model", "varying", "out"])]
    committed: Option<PathBuf>,
}

/// Runs `hairmath shader`.
pub fn run(args: &ShaderArgs) -> Result<(), CliError> {
    if let Some(dir) = &args.committed {
        return write_files(dir, &committed_shaders()?);
    }
    let name = args.model.as_deref().unwrap_or_default();
    let entry = find_model(name).ok_or_else(|| CliError::UnknownModel(name.to_string()))?;
    let values = args.flags.values_for(entry)?;
    let varying: Vec<&str> = args.varying.iter().map(String::as_str).collect();
    let shader = model_shader(entry, &values, &varying)?;
    let language = Language::from_name(&args.lang).expect("clap checks the name");
    let text = shader.write(language)?;
    let Some(out) = &args.out else {
        if !shader.module.bindings().is_empty() {
            return Err(CliError::Shader(format!(
                "{name} reads lookup tables: give --out FILE so that they are written beside \
                 the module"
            )));
        }
        return with_stdout(|out| out.write_all(&text).map_err(CliError::stdout));
    };
    write_files(
        out.parent().unwrap_or(Path::new(".")),
        &[CommittedFile {
            name: out
                .file_name()
                .map_or_else(|| name.to_string(), |n| n.to_string_lossy().into_owned()),
            contents: text,
        }],
    )?;
    if shader.module.bindings().is_empty() {
        return Ok(());
    }
    let stem = out
        .file_stem()
        .map_or_else(|| name.to_string(), |s| s.to_string_lossy().into_owned());
    let (tables, mut files) = table_files(&stem, &shader);
    files.push(CommittedFile {
        name: format!("{stem}.bindings.json"),
        contents: shader.bindings_json(&tables).into_bytes(),
    });
    write_files(out.parent().unwrap_or(Path::new(".")), &files)
}

/// Writes `files` into `dir` (created if missing).
fn write_files(dir: &Path, files: &[CommittedFile]) -> Result<(), CliError> {
    let dir = if dir.as_os_str().is_empty() {
        Path::new(".")
    } else {
        dir
    };
    create_dir(dir)?;
    for f in files {
        write_file(&dir.join(&f.name), &f.contents)?;
    }
    Ok(())
}
