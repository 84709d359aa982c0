//! The shader of a registered model: what `hairmath shader` writes and what `shaders/` holds.
//!
//! [`model_shader`] traces a model of [`crate::registry::MODELS`] at input values (every input
//! baked, or the named ones as arguments) and lowers it with the world-space companion into
//! one module of three public functions:
//!
//! - `hair_bcsdf(wi: vec3<f32>, wo: vec3<f32>[, h: f32][, varying...]) -> vec3<f32>`: S in
//!   the local frame (tangent +X, `wi` towards the light, `wo` towards the viewer), no cosine
//!   factor: what `hairmath eval` returns for the same flags;
//! - `fibre_local_directions(tangent, wi, wo) -> FibreLocalDirections` (`wi`, `wo`): the local frame of
//!   [`crate::geometry::local_directions`];
//! - `hair_bcsdf_world(tangent: vec3<f32>, wi: vec3<f32>, wo: vec3<f32>, ...) -> vec3<f32>`:
//!   `hair_bcsdf` of the directions in the frame of `tangent`.
//!
//! [`committed_shaders`] is the content of the repository's `shaders/` folder: the WGSL (library
//! form) and the GLSL (compute shader) of every model at its example values
//! ([`ModelEntry::example_values`]), the tables the modules bind with their JSON descriptions,
//! a JSON description of the bindings per model, and a README with each model's size and
//! operation counts.

use super::{ShaderError, ShaderModule, TextureBinding, TABLE_GROUP};
use crate::bcsdf::{InputValues, ShaderInputError};
use crate::diagnostics::OpCounts;
use crate::geometry::trace_local_directions;
use crate::lut::io::{json_number, json_string};
use crate::lut::{json_description, raw_bytes};
use crate::real::Graph;
use crate::registry::{ModelEntry, MODELS};
use std::fmt::Write as _;

/// The local-frame function of a model's shader.
pub const BCSDF_FUNCTION: &str = "hair_bcsdf";
/// The frame function of a model's shader.
pub const FRAME_FUNCTION: &str = "fibre_local_directions";
/// The world-space function of a model's shader.
pub const WORLD_FUNCTION: &str = "hair_bcsdf_world";

/// A shading language naga writes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Language {
    /// WGSL, the library form (no entry point).
    Wgsl,
    /// WGSL with the compute entry point `hair_main` of the binding contract.
    WgslCompute,
    /// WGSL importable with naga_oil (`#define_import_path hairmath::<model>`).
    WgslNagaOil,
    /// Vulkan GLSL 4.50, the compute shader.
    Glsl,
    /// HLSL shader model 6.0, the compute shader.
    Hlsl,
    /// Metal Shading Language 2.0, the compute kernel.
    Msl,
    /// SPIR-V 1.0, the compute shader, binary.
    Spirv,
}

impl Language {
    /// Every language with its command-line name and a line of help, in the order the
    /// command line lists them.
    pub const ALL: [(Language, &'static str, &'static str); 7] = [
        (Language::Wgsl, "wgsl", "WGSL functions, no entry point"),
        (
            Language::WgslCompute,
            "wgsl-compute",
            "WGSL with the compute entry point hair_main over a storage buffer of rows",
        ),
        (
            Language::WgslNagaOil,
            "wgsl-naga-oil",
            "WGSL with #define_import_path hairmath::<model>, for naga_oil (Bevy)",
        ),
        (Language::Glsl, "glsl", "Vulkan GLSL 4.50 compute shader"),
        (
            Language::Hlsl,
            "hlsl",
            "HLSL shader model 6.0 compute shader",
        ),
        (
            Language::Msl,
            "msl",
            "Metal Shading Language 2.0 compute kernel",
        ),
        (
            Language::Spirv,
            "spirv",
            "SPIR-V 1.0 compute shader (binary)",
        ),
    ];

    /// The language of a command-line name of [`Language::ALL`].
    pub fn from_name(name: &str) -> Option<Language> {
        Self::ALL
            .iter()
            .find(|(_, n, _)| *n == name)
            .map(|(l, _, _)| *l)
    }
}

/// Why a model's shader cannot be made.
#[derive(Debug, thiserror::Error)]
pub enum ModelShaderError {
    /// The model has no shader form, or the values or the varying names do not fit it.
    #[error(transparent)]
    Input(#[from] ShaderInputError),
    /// The emitter failed.
    #[error(transparent)]
    Shader(#[from] ShaderError),
}

/// A model's shader: the traced graph of `hair_bcsdf` and the module of its three functions.
#[derive(Clone, Debug)]
pub struct ModelShader {
    /// The model's name (`--model`).
    pub model: &'static str,
    /// The traced `hair_bcsdf`.
    pub graph: Graph,
    /// The library module: `hair_bcsdf`, `fibre_local_directions`, `hair_bcsdf_world`.
    pub module: ShaderModule,
}

/// The shader of `entry` at `values`, the inputs `varying` as arguments after wo (and h) in
/// that order, every other input baked.
///
/// # Errors
/// [`ModelShaderError::Input`] for a model with no shader form (saying why) and for values or
/// varying names the model does not accept, [`ModelShaderError::Shader`] if the emitter fails.
///
/// # Examples
///
/// ```
/// use hairmath::registry::find_model;
/// use hairmath::shader::{model_shader, Language};
///
/// let entry = find_model("kajiya-kay").expect("registered");
/// let shader = model_shader(entry, &entry.example_values(), &[])?;
/// let wgsl = String::from_utf8(shader.write(Language::Wgsl)?).expect("text");
/// assert!(wgsl.contains("fn hair_bcsdf_world("));
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn model_shader(
    entry: &ModelEntry,
    values: &InputValues,
    varying: &[&str],
) -> Result<ModelShader, ModelShaderError> {
    let graph = entry.trace_shader(values, varying)?;
    let summary = format!("`hairmath eval --model {}`, {}", entry.name, entry.summary);
    let source =
        "hairmath::registry::MODELS; Bcsdf::eval in the local frame, tangent +X, no cosine factor";
    Ok(graph_shader(entry.name, &summary, source, graph)?)
}

/// The shader module of a traced `hair_bcsdf` `graph` with its frame and world-space
/// companions, named `name` (the import path's last segment), whose comment says what it
/// evaluates (`summary`) and where its Rust code is (`source`).
///
/// # Errors
/// [`ShaderError`] if the emitter fails.
pub fn graph_shader(
    name: &'static str,
    summary: &str,
    source: &str,
    graph: Graph,
) -> Result<ModelShader, ShaderError> {
    let module = super::ModuleBuilder::new()
        .add(&graph, BCSDF_FUNCTION)?
        .comment(
            BCSDF_FUNCTION,
            vec![format!("{BCSDF_FUNCTION}: {summary}"), format!("({source})")],
        )
        .add(&trace_local_directions(), FRAME_FUNCTION)?
        .comment(
            FRAME_FUNCTION,
            vec![format!(
                "{FRAME_FUNCTION}: hairmath::geometry::local_directions -- wi and wo in the fibre's frame"
            )],
        )
        .world_companion(WORLD_FUNCTION, FRAME_FUNCTION, BCSDF_FUNCTION)?
        .build()?;
    Ok(ModelShader {
        model: name,
        graph,
        module,
    })
}

impl ModelShader {
    /// The module with the compute entry point over rows of `hair_bcsdf`'s arguments.
    ///
    /// # Errors
    /// As [`ShaderModule::with_compute_entry`].
    pub fn compute(&self) -> Result<ShaderModule, ShaderError> {
        self.module
            .with_compute_entry(self.module.argument_scalars())
    }

    /// The module written in `lang`: text, or SPIR-V's little-endian words.
    ///
    /// # Errors
    /// [`ShaderError`] from the back end.
    pub fn write(&self, lang: Language) -> Result<Vec<u8>, ShaderError> {
        let text = match lang {
            Language::Wgsl => self.module.wgsl()?,
            Language::WgslCompute => self.compute()?.wgsl()?,
            Language::WgslNagaOil => self.module.naga_oil_wgsl(&self.import_path())?,
            Language::Glsl => self.compute()?.glsl()?,
            Language::Hlsl => self.compute()?.hlsl()?,
            Language::Msl => self.compute()?.msl()?,
            Language::Spirv => return self.compute()?.spirv_bytes(),
        };
        Ok(text.into_bytes())
    }

    /// The naga_oil import path of the module, `hairmath::<model>` (`-` written `_`).
    pub fn import_path(&self) -> String {
        format!("hairmath::{}", self.model.replace('-', "_"))
    }

    /// The traced evaluation's operation counts ([`OpCounts::of`]).
    pub fn counts(&self) -> OpCounts {
        OpCounts::of(&self.graph)
    }

    /// The JSON description of the texture bindings: for each, its group, binding, name,
    /// dimension, size, axes, channels, and the table file its texels come from
    /// (`table_files[binding.table]`, written beside the module).
    pub fn bindings_json(&self, table_files: &[String]) -> String {
        let mut s = String::from("{\n");
        let _ = writeln!(s, "  \"model\": {},", json_string(self.model));
        let _ = writeln!(s, "  \"format\": \"rgba32float\",");
        let _ = writeln!(
            s,
            "  \"read\": \"textureLoad only; interpolation in shader arithmetic\","
        );
        let items: Vec<String> = self
            .module
            .bindings()
            .iter()
            .map(|b| binding_json(b, table_files))
            .collect();
        let _ = writeln!(s, "  \"textures\": [{}]", items.join(","));
        s.push_str("}\n");
        s
    }
}

/// One binding as a JSON object.
fn binding_json(b: &TextureBinding, table_files: &[String]) -> String {
    let axes: Vec<String> = b
        .axes
        .iter()
        .map(|(name, min, max)| {
            format!(
                "{{\"name\": {}, \"min\": {}, \"max\": {}}}",
                json_string(name),
                json_number(*min),
                json_number(*max)
            )
        })
        .collect();
    let channels: Vec<String> = b.channels.iter().map(|c| json_string(c)).collect();
    let file = table_files.get(b.table).map_or("", String::as_str);
    format!(
        "\n    {{\"group\": {}, \"binding\": {}, \"name\": {}, \"dimension\": {}, \"size\": {:?}, \
         \"axes\": [{}], \"channels\": [{}], \"table\": {}, \"first_channel\": {}}}",
        b.group,
        b.binding,
        json_string(&b.name),
        b.dimension,
        b.size,
        axes.join(", "),
        channels.join(", "),
        json_string(file),
        b.texture * super::TEXTURE_CHANNELS,
    )
}

/// One file of `shaders/`: its name in the folder and its bytes.
#[derive(Clone, Debug, PartialEq)]
pub struct CommittedFile {
    /// The file name.
    pub name: String,
    /// The contents.
    pub contents: Vec<u8>,
}

/// The table files of `shader`, `<stem>.lut<k>.f32` and `.json` per table, and the names of
/// the data files (by table index, for [`ModelShader::bindings_json`]).
pub fn table_files(stem: &str, shader: &ModelShader) -> (Vec<String>, Vec<CommittedFile>) {
    let mut names = Vec::new();
    let mut files = Vec::new();
    for (k, table) in shader.module.tables().iter().enumerate() {
        let data = format!("{stem}.lut{k}.f32");
        files.push(CommittedFile {
            name: format!("{stem}.lut{k}.json"),
            contents: json_description(table, &data).into_bytes(),
        });
        files.push(CommittedFile {
            name: data.clone(),
            contents: raw_bytes(table),
        });
        names.push(data);
    }
    (names, files)
}

/// The files of `shaders/` for one model's shader, named after `stem`.
pub fn shader_files(stem: &str, shader: &ModelShader) -> Result<Vec<CommittedFile>, ShaderError> {
    let (tables, mut files) = table_files(stem, shader);
    files.push(CommittedFile {
        name: format!("{stem}.wgsl"),
        contents: shader.write(Language::Wgsl)?,
    });
    files.push(CommittedFile {
        name: format!("{stem}.comp.glsl"),
        contents: shader.write(Language::Glsl)?,
    });
    if !shader.module.bindings().is_empty() {
        files.push(CommittedFile {
            name: format!("{stem}.bindings.json"),
            contents: shader.bindings_json(&tables).into_bytes(),
        });
    }
    Ok(files)
}

/// The shader of every registered model that has one, at its example values, in registry
/// order.
///
/// # Errors
/// As [`model_shader`].
pub fn example_shaders() -> Result<Vec<ModelShader>, ModelShaderError> {
    MODELS
        .iter()
        .filter(|m| m.shader.is_some())
        .map(|m| model_shader(m, &m.example_values(), &[]))
        .collect()
}

/// The contents of the repository's `shaders/` folder (the [`crate::shader`] module documentation), which a test
/// compares with the folder; `hairmath shader --committed shaders` writes it.
///
/// # Errors
/// As [`model_shader`].
pub fn committed_shaders() -> Result<Vec<CommittedFile>, ModelShaderError> {
    let shaders = example_shaders()?;
    let mut files = Vec::new();
    let mut readme = readme_header();
    for shader in &shaders {
        let stem = shader.model.to_string();
        let model_files = shader_files(&stem, shader)?;
        let wgsl = &model_files
            .iter()
            .find(|f| f.name == format!("{stem}.wgsl"))
            .expect("every model has its WGSL")
            .contents;
        readme_row(&mut readme, shader, wgsl);
        files.extend(model_files);
    }
    files.push(CommittedFile {
        name: "README.md".into(),
        contents: readme.into_bytes(),
    });
    Ok(files)
}

/// The README of `shaders/` up to its table's header.
fn readme_header() -> String {
    format!(
        "# Generated shaders\n\n\
         Written by `cargo run --release -- shader --committed shaders` from the Rust code \
         (`hairmath::shader::committed_shaders`); a test (`cargo test --test shader`) \
         regenerates them and fails on any difference. Do not edit them by hand.\n\n\
         Per model at its default parameters (every parameter baked): `<model>.wgsl`, the WGSL \
         library (`{BCSDF_FUNCTION}(wi, wo[, h]) -> vec3<f32>` in the local frame, tangent +X, \
         S with no cosine factor, as `hairmath eval` returns it; `{FRAME_FUNCTION}`; \
         `{WORLD_FUNCTION}(tangent, wi, wo[, h])`), and `<model>.comp.glsl`, the same as a \
         Vulkan GLSL compute shader over a storage buffer of rows. Models with lookup tables \
         bind them in `@group({TABLE_GROUP})` as `rgba32float` textures read with \
         `textureLoad` and interpolated in shader arithmetic (`<model>.bindings.json`; the \
         tables as `<model>.lut<k>.f32` with their JSON descriptions).\n\n\
         Counts are of the traced evaluation per call of `{BCSDF_FUNCTION}`, every function \
         call inlined and loop unrolled (`hairmath::diagnostics::OpCounts`): add/mul (also \
         negation), div, sqrt, transcendental (exp, log, sin, cos, atan2), select (min, max, \
         abs, floor, comparisons, selects) and texture fetches.\n\n\
         | model | WGSL lines | shader functions | add/mul | div | sqrt | transcendental | select | fetches |\n\
         | --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |\n"
    )
}

/// Appends the README row of `shader`, whose WGSL is `wgsl`.
fn readme_row(out: &mut String, shader: &ModelShader, wgsl: &[u8]) {
    let c = shader.counts();
    let lines = wgsl.iter().filter(|&&b| b == b'\n').count();
    let _ = writeln!(
        out,
        "| `{}` | {lines} | {} | {} | {} | {} | {} | {} | {} |",
        shader.model,
        shader.module.module().functions.len(),
        c.add_mul,
        c.div,
        c.sqrt,
        c.transcendental,
        c.select,
        c.fetch
    );
}
