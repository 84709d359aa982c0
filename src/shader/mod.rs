//! Shader code from traced graphs: a [`Graph`] lowered to a validated [`naga::Module`] and
//! written with naga's back ends as WGSL, GLSL, HLSL, MSL and SPIR-V.
//!
//! [`lower`] builds the module directly in naga's IR (no WGSL text is printed and parsed
//! back):
//!
//! - the struct types of the signature (a model's uniforms: a named struct whose members are
//!   the fields, laid out by WGSL's rules so that it can live in a uniform or storage buffer:
//!   a `vec3<f32>` is aligned to 16 bytes);
//! - the signature's constant parameters as module-scope constants named after the parameter
//!   (`const uniforms: KarisUniforms = KarisUniforms(...)`), read in functions by name;
//! - each function of the graph as a named shader function (its parameters named from the
//!   Rust code, `vec3<f32>` parameters as vectors), callees before callers; each loop's
//!   constant array as `const NAME: array<Element, K>` with a struct `Element` of the loop's
//!   field names, and each loop as a `var` state and a `for` loop calling the body function;
//! - the top-level function `name` with the signature's arguments and result;
//! - per table, one texture binding per group of [`TEXTURE_CHANNELS`] channels in
//!   `@group(1)` ([`TABLE_GROUP`]), read **only** with `textureLoad` (never sampled: hardware
//!   filtering computes its weights in low-precision fixed point), and one helper function that
//!   interpolates the texels in shader arithmetic in exactly the operation order of
//!   [`Table::lookup_into`], called once per distinct fetch.
//!
//! The module is validated with every check of [`naga::valid::Validator`]; a failure is a
//! [`ShaderError::Validation`] naming the function.
//!
//! [`ShaderModule::with_compute_entry`] adds the compute entry point of the binding contract:
//!
//! ```wgsl
//! @group(0) @binding(0) var<storage, read> hair_queries: array<f32>;      // `stride` f32 per row
//! @group(0) @binding(1) var<storage, read_write> hair_values: array<f32>; // 3 f32 per row (RGB)
//! @compute @workgroup_size(64) fn hair_main(@builtin(global_invocation_id) id: vec3<u32>)
//! ```
//!
//! Row `id.x + id.y * 65535 * 64` (dispatch up to 65535 workgroups along x, then more along
//! y); rows at or beyond `arrayLength(&hair_values) / 3` return at once. A row holds the
//! top-level function's arguments in order, each as its scalars (`wi.x, wi.y, wi.z, wo.x,
//! ...`; a struct argument field by field), then anything up to `stride` the shader ignores;
//! the row's result is the function's `vec3<f32>` (or its first three scalars, zeros for
//! missing ones).
//!
//! naga's IR has no comments: after writing text, the writers insert above each generated
//! function a comment `// <Rust source> -- <equation>` and above each texture binding its
//! size, axes and channels ([`TextureBinding::describe`]).
//!
//! The back ends' settings are fixed here: WGSL with naga's default flags; GLSL `#version 450`
//! core (textures bound from [`GLSL_FIRST_TEXTURE_BINDING`]); HLSL shader model 6.0; MSL 2.0
//! (buffer sizes in [`MSL_SIZES_BUFFER`]); SPIR-V 1.0; all with [`BOUNDS_CHECKS`].

mod body;
mod builder;
mod captures;
mod entry;
mod model;
mod names;
mod tables;
mod types;
mod vectorize;
mod write;

pub use crate::real::TEXTURE_CHANNELS;
pub use model::{
    committed_shaders, example_shaders, graph_shader, model_shader, shader_files, table_files,
    CommittedFile, Language, ModelShader, ModelShaderError, BCSDF_FUNCTION, FRAME_FUNCTION,
    WORLD_FUNCTION,
};
pub use write::{BOUNDS_CHECKS, GLSL_FIRST_TEXTURE_BINDING, MSL_SIZES_BUFFER};

use crate::lut::Table;
use crate::real::{Graph, Parameter};
use body::{Lowering, Shared, Top};
use naga::valid::ModuleInfo;
use naga::Module;
use std::sync::Arc;
use write::Lang;

/// `Some(values)` when the parameter is a module-scope constant rather than an argument.
fn constant_values(parameter: &Parameter) -> Option<&[f32]> {
    parameter.constant.as_deref()
}

/// The name of the compute entry point.
pub const ENTRY_POINT: &str = "hair_main";

/// The bind group of the row buffers `hair_queries` and `hair_values`.
pub const ROW_GROUP: u32 = 0;

/// The binding of `hair_queries` (`var<storage, read>`, `stride` f32 per row) in
/// [`ROW_GROUP`].
pub const QUERY_BINDING: u32 = 0;

/// The binding of `hair_values` (`var<storage, read_write>`, 3 f32 per row) in [`ROW_GROUP`].
pub const VALUE_BINDING: u32 = 1;

/// The bind group of the tables' textures (bindings 0, 1, ... in [`ShaderModule::bindings`]
/// order).
pub const TABLE_GROUP: u32 = 1;

/// The compute entry point's workgroup size (along x).
pub const WORKGROUP_SIZE: u32 = 64;

/// Why a graph could not become shader code.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum ShaderError {
    /// naga's validator rejected the lowered module.
    #[error("the generated shader function {function} does not validate: {message}")]
    Validation {
        /// The function (or entry point) the error is in, `<module scope>` for types and
        /// constants.
        function: String,
        /// The validator's message and its causes.
        message: String,
    },
    /// A back end could not write the module.
    #[error("naga's {lang} back end failed: {message}")]
    Backend {
        /// The language (`WGSL`, `GLSL`, `HLSL`, `MSL`, `SPIR-V`).
        lang: &'static str,
        /// The back end's message.
        message: String,
    },
    /// The row stride of the compute entry point is too small for the arguments.
    #[error("a row of {stride} f32 cannot hold the {needed} argument scalars of {function}")]
    Stride {
        /// The top-level function.
        function: String,
        /// The stride asked for.
        stride: usize,
        /// The scalars of the function's arguments.
        needed: usize,
    },
    /// Two top-level functions of one name.
    #[error("the module already has a function {name}")]
    NameConflict {
        /// The name.
        name: String,
    },
    /// Two graphs bake a constant of one name with different values or types.
    #[error("the constant {name} has different values in the graphs of one module")]
    ConstantConflict {
        /// The constant's name.
        name: String,
    },
    /// The graph does not have the shape the lowering expects (a programming error in the
    /// tracer or in a hand-made graph).
    #[error("the traced graph cannot be lowered: {0}")]
    Unsupported(String),
}

/// One texture binding of the tables: [`TEXTURE_CHANNELS`] channels of one table as the
/// RGBA components of a texture of format `Rgba32Float` (components beyond the table's
/// channels are 0), read with `textureLoad` only, texel `(i, j, k)` holding the samples at
/// index `i` of axis 0, `j` of axis 1, `k` of axis 2.
#[derive(Clone, Debug, PartialEq)]
pub struct TextureBinding {
    /// The bind group ([`TABLE_GROUP`]).
    pub group: u32,
    /// The binding in the group.
    pub binding: u32,
    /// The texture's name in shader code.
    pub name: String,
    /// The table's index in [`ShaderModule::tables`] (for one graph, in [`Graph::tables`]).
    pub table: usize,
    /// Which group of [`TEXTURE_CHANNELS`] channels of the table (0 for a table of at most
    /// four channels).
    pub texture: usize,
    /// 1, 2 or 3: `texture_1d<f32>`, `texture_2d<f32>` or `texture_3d<f32>`.
    pub dimension: usize,
    /// Texels along each axis (width, height, depth).
    pub size: Vec<usize>,
    /// Each axis' name and coordinate range (first and last sample).
    pub axes: Vec<(String, f64, f64)>,
    /// The table's channels in the components x, y, z, w, in order.
    pub channels: Vec<String>,
}

impl TextureBinding {
    /// The comment written above the binding: `lut0_gerard_texels: 9 x 5 texels (theta_d in
    /// [0, 1.5] along x, ...); x, y, z = N_R, N_TT, N_TRT`.
    pub fn describe(&self) -> String {
        let sizes: Vec<String> = self.size.iter().map(|s| s.to_string()).collect();
        let axes: Vec<String> = self
            .axes
            .iter()
            .zip(["x", "y", "z"])
            .map(|((name, min, max), c)| format!("{name} in [{min}, {max}] along {c}"))
            .collect();
        format!(
            "{}: {} texels ({}); {} = {}; rgba32float, read with textureLoad",
            self.name,
            sizes.join(" x "),
            axes.join(", "),
            ["x", "y", "z", "w"][..self.channels.len()].join(", "),
            self.channels.join(", ")
        )
    }

    /// The texture's extent `[width, height, depth]` (1 beyond its axes).
    pub fn extent(&self) -> [u32; 3] {
        let mut e = [1u32; 3];
        for (slot, &s) in e.iter_mut().zip(&self.size) {
            *slot = s as u32;
        }
        e
    }

    /// The texels to upload from `table` (the table of [`TextureBinding::table`]), x
    /// fastest, then y, then z; components beyond the table's channels are 0.
    ///
    /// # Panics
    /// If `table` does not have this binding's axes and channels.
    pub fn texels(&self, table: &Table) -> Vec<[f32; 4]> {
        assert_eq!(
            table.axes().len(),
            self.dimension,
            "the table of binding {}",
            self.name
        );
        let c = table.channels().len();
        let first = self.texture * TEXTURE_CHANNELS;
        assert!(first < c, "the table of binding {}", self.name);
        table
            .data()
            .chunks(c)
            .map(|texel| {
                let mut rgba = [0.0f32; 4];
                for (slot, v) in rgba.iter_mut().zip(&texel[first..]) {
                    *slot = *v;
                }
                rgba
            })
            .collect()
    }
}

/// Lowers graphs into one module: [`ModuleBuilder::add`] one graph per top-level function,
/// optionally [`ModuleBuilder::world_companion`], then [`ModuleBuilder::build`].
///
/// The graphs share what is equal: a function of the same name, kind and body (with the same
/// tables, arrays and callees) is one shader function, one of the same name and another body
/// is renamed (`name_2`, ...); a table (by pointer) is one set of texture bindings; equal
/// constant arrays are one constant; constant parameters of the same name must have the same
/// type and values and are one constant.
pub struct ModuleBuilder {
    shared: Shared,
}

impl Default for ModuleBuilder {
    fn default() -> Self {
        Self::new()
    }
}

impl ModuleBuilder {
    /// An empty module.
    pub fn new() -> Self {
        ModuleBuilder {
            shared: Shared::default(),
        }
    }

    /// Adds `graph` as the top-level function `name` (see the [module docs](self)). The first
    /// graph added is the one the compute entry point evaluates.
    ///
    /// # Errors
    /// [`ShaderError::NameConflict`] if the module already has a function `name`,
    /// [`ShaderError::ConstantConflict`] for a constant parameter of the name of an earlier
    /// one with other values, [`ShaderError::Unsupported`] for a graph of a shape the tracer
    /// does not make.
    pub fn add(mut self, graph: &Graph, name: &str) -> Result<Self, ShaderError> {
        let mut lowering = Lowering::new(&mut self.shared, graph);
        lowering.declare_constants()?;
        lowering.declare_named()?;
        lowering.declare_arrays();
        lowering.lower_functions()?;
        lowering.lower_top(name)?;
        Ok(self)
    }

    /// Replaces the comment written above the top-level function `function` (by default it
    /// names the function as traced) with `lines`.
    pub fn comment(mut self, function: &str, lines: Vec<String>) -> Self {
        if let Some(entry) = self.shared.comments.iter_mut().find(|(n, _)| n == function) {
            entry.1 = lines;
        }
        self
    }

    /// Adds the function `name(tangent: vec3<f32>, wi: vec3<f32>, wo: vec3<f32>, rest...)`
    /// for world-space directions: it calls the top-level function `frame` (three `vec3<f32>`
    /// arguments, six scalar outputs: local wi, then local wo, such as
    /// `hairmath::geometry::trace_local_directions`) and returns the top-level function
    /// `local` (whose first two arguments are `vec3<f32>` wi and wo) at the local directions
    /// and the further arguments `rest` of `local`. The first three arguments are named as
    /// `frame`'s.
    ///
    /// # Errors
    /// [`ShaderError::Unsupported`] if `frame` or `local` is not a top-level function of
    /// those shapes, [`ShaderError::NameConflict`] if `name` is taken.
    pub fn world_companion(
        mut self,
        name: &str,
        frame: &str,
        local: &str,
    ) -> Result<Self, ShaderError> {
        body::world_companion(&mut self.shared, name, frame, local)?;
        Ok(self)
    }

    /// The validated module.
    ///
    /// # Errors
    /// [`ShaderError::Validation`] if naga's validator rejects it (naming the function),
    /// [`ShaderError::Unsupported`] if no graph was added.
    pub fn build(self) -> Result<ShaderModule, ShaderError> {
        let Shared {
            mut module,
            tables,
            bindings,
            tops,
            comments,
            ..
        } = self.shared;
        if tops.is_empty() {
            return Err(ShaderError::Unsupported("a module of no function".into()));
        }
        names::protect_public_names(&mut module, &tops);
        let info = write::validate(&module)?;
        Ok(ShaderModule {
            library: module,
            library_info: info,
            entry: None,
            tables: tables.into_iter().map(|(t, _)| t).collect(),
            tops,
            comments,
            bindings,
        })
    }
}

/// A validated naga module of traced graphs, with what its writers need.
#[derive(Clone, Debug)]
pub struct ShaderModule {
    /// The library form: no entry point.
    library: Module,
    library_info: ModuleInfo,
    /// The library with the compute entry point and its row buffers, and the row stride.
    entry: Option<Entry>,
    tables: Vec<Arc<Table>>,
    /// The top-level functions, in the order they were added.
    tops: Vec<Top>,
    /// (shader function name, comment lines) in module order.
    comments: Vec<(String, Vec<String>)>,
    bindings: Vec<TextureBinding>,
}

/// A module with the compute entry point.
#[derive(Clone, Debug)]
struct Entry {
    module: Module,
    info: ModuleInfo,
    stride: usize,
    function: String,
}

/// Lowers `graph` to a validated naga module whose top-level function is `name` (see the
/// [module docs](self)): the library form, without an entry point.
/// `ModuleBuilder::new().add(graph, name)?.build()`.
///
/// # Errors
/// [`ShaderError::Validation`] when naga's validator rejects the module (naming the
/// function), [`ShaderError::Unsupported`] for a graph of a shape the tracer does not make.
pub fn lower(graph: &Graph, name: &str) -> Result<ShaderModule, ShaderError> {
    ModuleBuilder::new().add(graph, name)?.build()
}

impl ShaderModule {
    /// The naga module: with the compute entry point after
    /// [`ShaderModule::with_compute_entry`], else the library form.
    pub fn module(&self) -> &Module {
        self.entry.as_ref().map_or(&self.library, |e| &e.module)
    }

    /// The validator's information on [`ShaderModule::module`].
    pub fn info(&self) -> &ModuleInfo {
        self.entry.as_ref().map_or(&self.library_info, |e| &e.info)
    }

    /// The name of the first top-level function (the one the compute entry point evaluates
    /// by default).
    pub fn name(&self) -> &str {
        &self.tops[0].name
    }

    /// The names of the top-level functions, in the order they were added.
    pub fn functions(&self) -> Vec<&str> {
        self.tops.iter().map(|t| t.name.as_str()).collect()
    }

    /// The tables' texture bindings, in binding order.
    pub fn bindings(&self) -> &[TextureBinding] {
        &self.bindings
    }

    /// The tables the bindings read ([`TextureBinding::table`] indexes this), each once.
    pub fn tables(&self) -> &[Arc<Table>] {
        &self.tables
    }

    fn top(&self, function: &str) -> Result<&Top, ShaderError> {
        self.tops
            .iter()
            .find(|t| t.name == function)
            .ok_or_else(|| ShaderError::Unsupported(format!("no top-level function {function}")))
    }

    /// The number of f32 of the first top-level function's arguments: the smallest row
    /// stride of the compute entry point.
    pub fn argument_scalars(&self) -> usize {
        self.tops[0].signature.argument_count()
    }

    /// The row stride of the compute entry point, if the module has it.
    pub fn stride(&self) -> Option<usize> {
        self.entry.as_ref().map(|e| e.stride)
    }

    /// The module with the compute entry point `hair_main` (see the [module docs](self))
    /// evaluating the first top-level function on rows of `stride` f32; a module that
    /// already has an entry point gets it replaced.
    ///
    /// # Errors
    /// [`ShaderError::Stride`] when `stride` is smaller than
    /// [`ShaderModule::argument_scalars`] (or too large for `u32` indices),
    /// [`ShaderError::Validation`] if the module with the entry point does not validate.
    pub fn with_compute_entry(&self, stride: usize) -> Result<ShaderModule, ShaderError> {
        self.with_compute_entry_of(&self.tops[0].name, stride)
    }

    /// [`ShaderModule::with_compute_entry`] evaluating the top-level function `function`.
    ///
    /// # Errors
    /// As [`ShaderModule::with_compute_entry`], and [`ShaderError::Unsupported`] if there is
    /// no top-level function `function`.
    pub fn with_compute_entry_of(
        &self,
        function: &str,
        stride: usize,
    ) -> Result<ShaderModule, ShaderError> {
        let top = self.top(function)?;
        let needed = top.signature.argument_count();
        if stride < needed || stride > u32::MAX as usize / 4 {
            return Err(ShaderError::Stride {
                function: function.to_string(),
                stride,
                needed,
            });
        }
        let mut module = self.library.clone();
        entry::add_entry_point(
            &mut module,
            top.handle,
            &top.signature,
            top.result,
            stride as u32,
        );
        let info = write::validate(&module)?;
        Ok(ShaderModule {
            entry: Some(Entry {
                module,
                info,
                stride,
                function: function.to_string(),
            }),
            ..self.clone()
        })
    }

    /// The top-level function the entry point evaluates, if the module has it.
    pub fn entry_function(&self) -> Option<&str> {
        self.entry.as_ref().map(|e| e.function.as_str())
    }

    /// This module if it has the entry point, else the module with it at the smallest stride.
    fn with_entry(&self) -> Result<std::borrow::Cow<'_, ShaderModule>, ShaderError> {
        match self.entry {
            Some(_) => Ok(std::borrow::Cow::Borrowed(self)),
            None => Ok(std::borrow::Cow::Owned(
                self.with_compute_entry(self.argument_scalars())?,
            )),
        }
    }

    /// `text` with the names of every function's arguments and labelled values restored
    /// ([`names::restore_names`]), and the comments.
    fn comment(&self, text: &str, lang: Lang) -> String {
        let module = self.module();
        let functions: Vec<(String, Vec<String>)> = module
            .functions
            .iter()
            .filter_map(|(_, f)| {
                let arguments = f.arguments.iter();
                let mut wanted: Vec<String> = arguments.filter_map(|a| a.name.clone()).collect();
                for label in f.named_expressions.values() {
                    if !wanted.contains(label) {
                        wanted.push(label.clone());
                    }
                }
                Some((f.name.clone()?, wanted))
            })
            .collect();
        let text = names::restore_names(text, lang, &functions);
        write::insert_comments(&text, lang, &self.comments, &self.bindings)
    }

    /// WGSL of the module: the library form (functions, constants and bindings) or, after
    /// [`ShaderModule::with_compute_entry`], with the entry point and its buffers.
    ///
    /// # Errors
    /// [`ShaderError::Backend`] if naga's writer fails.
    pub fn wgsl(&self) -> Result<String, ShaderError> {
        Ok(self.comment(&write::wgsl(self.module(), self.info())?, Lang::Wgsl))
    }

    /// The WGSL library form as a naga_oil import module: `#define_import_path
    /// {import_path}` (for example `hairmath::karis`), then [`ShaderModule::wgsl`] of the
    /// module without an entry point.
    ///
    /// # Errors
    /// As [`ShaderModule::wgsl`].
    pub fn naga_oil_wgsl(&self, import_path: &str) -> Result<String, ShaderError> {
        let library = write::wgsl(&self.library, &self.library_info)?;
        Ok(format!(
            "#define_import_path {import_path}\n\n{}",
            self.comment(&library, Lang::Wgsl)
        ))
    }

    /// GLSL `#version 450` compute shader of the entry point (added at the smallest stride
    /// if the module has none).
    ///
    /// # Errors
    /// [`ShaderError::Backend`] if naga's writer fails.
    pub fn glsl(&self) -> Result<String, ShaderError> {
        let m = self.with_entry()?;
        Ok(m.comment(&write::glsl(m.module(), m.info(), &m.bindings)?, Lang::Glsl))
    }

    /// HLSL (shader model 6.0) of the module with the entry point.
    ///
    /// # Errors
    /// [`ShaderError::Backend`] if naga's writer fails.
    pub fn hlsl(&self) -> Result<String, ShaderError> {
        let m = self.with_entry()?;
        Ok(m.comment(&write::hlsl(m.module(), m.info())?, Lang::Hlsl))
    }

    /// MSL 2.0 of the module with the entry point.
    ///
    /// # Errors
    /// [`ShaderError::Backend`] if naga's writer fails.
    pub fn msl(&self) -> Result<String, ShaderError> {
        let m = self.with_entry()?;
        Ok(m.comment(&write::msl(m.module(), m.info(), &m.bindings)?, Lang::Msl))
    }

    /// SPIR-V 1.0 words of the module with the entry point.
    ///
    /// # Errors
    /// [`ShaderError::Backend`] if naga's writer fails.
    pub fn spirv(&self) -> Result<Vec<u32>, ShaderError> {
        let m = self.with_entry()?;
        write::spirv(m.module(), m.info())
    }

    /// [`ShaderModule::spirv`] as little-endian bytes (a `.spv` file).
    ///
    /// # Errors
    /// As [`ShaderModule::spirv`].
    pub fn spirv_bytes(&self) -> Result<Vec<u8>, ShaderError> {
        Ok(self.spirv()?.iter().flat_map(|w| w.to_le_bytes()).collect())
    }
}
