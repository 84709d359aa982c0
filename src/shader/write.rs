//! Validation and naga's back ends, with the settings each needs, and the comments naga's IR
//! cannot carry, inserted into the written text.

use super::{
    ShaderError, TextureBinding, ENTRY_POINT, QUERY_BINDING, ROW_GROUP, TABLE_GROUP, VALUE_BINDING,
};
use naga::back;
use naga::proc::{BoundsCheckPolicies, BoundsCheckPolicy};
use naga::valid::{Capabilities, ModuleInfo, ValidationError, ValidationFlags, Validator};
use naga::{Module, ResourceBinding, ShaderStage};

/// The bounds-check policies of the GLSL, HLSL, MSL and SPIR-V output: indices into arrays
/// (the loops' constant arrays) clamped into range (`Restrict`), buffer reads beyond the end
/// of `hair_queries` read 0 and writes beyond `hair_values` are skipped (`ReadZeroSkipWrite`),
/// and texel loads unchecked: the table helpers clamp their integer texel coordinates into
/// range themselves (a no-op except for a NaN coordinate), which costs two integer operations
/// per axis instead of the texture-size queries per load the back ends would add.
pub const BOUNDS_CHECKS: BoundsCheckPolicies = BoundsCheckPolicies {
    index: BoundsCheckPolicy::Restrict,
    buffer: BoundsCheckPolicy::ReadZeroSkipWrite,
    image_load: BoundsCheckPolicy::Unchecked,
    binding_array: BoundsCheckPolicy::Unchecked,
};

/// The GLSL texture unit of table texture `k`: after the two storage buffers, so that the
/// bindings are also distinct under Vulkan GLSL's single namespace per set.
pub const GLSL_FIRST_TEXTURE_BINDING: u8 = 2;

/// The MSL buffer slot of the buffer-sizes buffer `arrayLength` reads.
pub const MSL_SIZES_BUFFER: u8 = 2;

/// Validates `module` with every check and the capabilities it needs (none beyond the
/// default set); a failure names the function it is in.
pub(super) fn validate(module: &Module) -> Result<ModuleInfo, ShaderError> {
    Validator::new(ValidationFlags::all(), Capabilities::empty())
        .validate(module)
        .map_err(|e| {
            let (function, message) = match &e.into_inner() {
                ValidationError::Function { name, source, .. } => {
                    (name.clone(), error_chain(source))
                }
                ValidationError::EntryPoint { name, source, .. } => {
                    (name.clone(), error_chain(source))
                }
                other => ("<module scope>".to_string(), error_chain(other)),
            };
            ShaderError::Validation { function, message }
        })
}

/// An error and its sources, `: `-separated.
fn error_chain(e: &dyn std::error::Error) -> String {
    let mut text = e.to_string();
    let mut source = e.source();
    while let Some(s) = source {
        text.push_str(": ");
        text.push_str(&s.to_string());
        source = s.source();
    }
    text
}

fn backend(lang: &'static str) -> impl Fn(&dyn std::error::Error) -> ShaderError {
    move |e| ShaderError::Backend {
        lang,
        message: error_chain(e),
    }
}

/// WGSL (naga's default writer flags).
pub(super) fn wgsl(module: &Module, info: &ModuleInfo) -> Result<String, ShaderError> {
    back::wgsl::write_string(module, info, back::wgsl::WriterFlags::empty())
        .map_err(|e| backend("WGSL")(&e))
}

/// GLSL `#version 450` (desktop core profile), the compute entry point only: storage
/// buffers at bindings 0 and 1, table textures from [`GLSL_FIRST_TEXTURE_BINDING`].
pub(super) fn glsl(
    module: &Module,
    info: &ModuleInfo,
    bindings: &[TextureBinding],
) -> Result<String, ShaderError> {
    let mut binding_map = back::glsl::BindingMap::default();
    binding_map.insert(row_binding(QUERY_BINDING), QUERY_BINDING as u8);
    binding_map.insert(row_binding(VALUE_BINDING), VALUE_BINDING as u8);
    for t in bindings {
        binding_map.insert(
            table_binding(t.binding),
            GLSL_FIRST_TEXTURE_BINDING + t.binding as u8,
        );
    }
    let options = back::glsl::Options {
        version: back::glsl::Version::Desktop(450),
        writer_flags: back::glsl::WriterFlags::empty(),
        binding_map,
        zero_initialize_workgroup_memory: false,
    };
    let pipeline = back::glsl::PipelineOptions {
        shader_stage: ShaderStage::Compute,
        entry_point: ENTRY_POINT.to_string(),
        multiview: None,
    };
    let mut out = String::new();
    let err = backend("GLSL");
    let mut writer =
        back::glsl::Writer::new(&mut out, module, info, &options, &pipeline, BOUNDS_CHECKS)
            .map_err(|e| err(&e))?;
    writer.write().map_err(|e| err(&e))?;
    Ok(out)
}

/// HLSL for shader model 6.0: registers as naga assigns them by default (`register(tN,
/// spaceG)` for binding N of group G; the read-write buffer a `u` register).
pub(super) fn hlsl(module: &Module, info: &ModuleInfo) -> Result<String, ShaderError> {
    let options = back::hlsl::Options {
        shader_model: back::hlsl::ShaderModel::V6_0,
        force_loop_bounding: false,
        ..Default::default()
    };
    let pipeline = back::hlsl::PipelineOptions { entry_point: None };
    let mut out = String::new();
    let err = backend("HLSL");
    let mut writer = back::hlsl::Writer::new(&mut out, &options, &pipeline);
    writer.write(module, info, None).map_err(|e| err(&e))?;
    Ok(out)
}

/// MSL 2.0: `hair_queries` in `buffer(0)`, `hair_values` in `buffer(1)`, the buffer sizes
/// `arrayLength` needs in [`MSL_SIZES_BUFFER`], table textures in `texture(k)`.
pub(super) fn msl(
    module: &Module,
    info: &ModuleInfo,
    bindings: &[TextureBinding],
) -> Result<String, ShaderError> {
    use back::msl::{BindTarget, EntryPointResources};
    let mut resources = back::msl::BindingMap::default();
    resources.insert(
        row_binding(QUERY_BINDING),
        BindTarget {
            buffer: Some(QUERY_BINDING as u8),
            ..Default::default()
        },
    );
    resources.insert(
        row_binding(VALUE_BINDING),
        BindTarget {
            buffer: Some(VALUE_BINDING as u8),
            mutable: true,
            ..Default::default()
        },
    );
    for t in bindings {
        resources.insert(
            table_binding(t.binding),
            BindTarget {
                texture: Some(t.binding as u8),
                ..Default::default()
            },
        );
    }
    let mut per_entry_point_map = back::msl::EntryPointResourceMap::default();
    per_entry_point_map.insert(
        ENTRY_POINT.to_string(),
        EntryPointResources {
            resources,
            immediates_buffer: None,
            sizes_buffer: Some(MSL_SIZES_BUFFER),
        },
    );
    let options = back::msl::Options {
        lang_version: (2, 0),
        per_entry_point_map,
        fake_missing_bindings: false,
        bounds_check_policies: BOUNDS_CHECKS,
        force_loop_bounding: false,
        ..Default::default()
    };
    let pipeline = back::msl::PipelineOptions {
        entry_point: Some((ShaderStage::Compute, ENTRY_POINT.to_string())),
        ..Default::default()
    };
    back::msl::write_string(module, info, &options, &pipeline)
        .map(|(text, _)| text)
        .map_err(|e| backend("MSL")(&e))
}

/// SPIR-V 1.0 words of the compute entry point: descriptor set = group, binding = binding.
pub(super) fn spirv(module: &Module, info: &ModuleInfo) -> Result<Vec<u32>, ShaderError> {
    let options = back::spv::Options {
        lang_version: (1, 0),
        flags: back::spv::WriterFlags::empty(),
        bounds_check_policies: BOUNDS_CHECKS,
        force_loop_bounding: false,
        ..Default::default()
    };
    let pipeline = back::spv::PipelineOptions {
        shader_stage: ShaderStage::Compute,
        entry_point: ENTRY_POINT.to_string(),
    };
    back::spv::write_vec(module, info, &options, Some(&pipeline)).map_err(|e| backend("SPIR-V")(&e))
}

fn row_binding(binding: u32) -> ResourceBinding {
    ResourceBinding {
        group: ROW_GROUP,
        binding,
    }
}

fn table_binding(binding: u32) -> ResourceBinding {
    ResourceBinding {
        group: TABLE_GROUP,
        binding,
    }
}

/// The shading languages whose text gets comments.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Lang {
    Wgsl,
    Glsl,
    Hlsl,
    Msl,
}

/// Inserts `comment` lines above the definition of each function `(name, comment)` and above
/// each texture binding's declaration.
pub(super) fn insert_comments(
    text: &str,
    lang: Lang,
    functions: &[(String, Vec<String>)],
    bindings: &[TextureBinding],
) -> String {
    let mut lines: Vec<String> = text.lines().map(str::to_string).collect();
    let mut inserts: Vec<(usize, Vec<String>)> = Vec::new();
    for (name, comment) in functions {
        if let Some(at) = lines.iter().position(|l| is_definition(l, name, lang)) {
            let at = attribute_start(&lines, at);
            inserts.push((at, comment.clone()));
        }
    }
    for t in bindings {
        if let Some(at) = lines.iter().position(|l| is_texture(l, t, lang)) {
            let at = attribute_start(&lines, at);
            inserts.push((at, vec![t.describe()]));
        }
    }
    inserts.sort_by_key(|(at, _)| std::cmp::Reverse(*at));
    for (at, comment) in inserts {
        let indent: String = lines[at]
            .chars()
            .take_while(|c| c.is_whitespace())
            .collect();
        for line in comment.iter().rev() {
            lines.insert(at, format!("{indent}// {line}"));
        }
    }
    let mut out = lines.join("\n");
    out.push('\n');
    out
}

/// The first line of the attribute lines (WGSL `@group(..)`, `@compute`) directly above
/// line `at`.
fn attribute_start(lines: &[String], mut at: usize) -> usize {
    while at > 0 && lines[at - 1].trim_start().starts_with('@') {
        at -= 1;
    }
    at
}

/// Whether `line` starts the definition of the function or module-scope constant `name` (or
/// of `name_`, naga's spelling of names that end in a digit or are keywords).
pub(super) fn is_definition(line: &str, name: &str, lang: Lang) -> bool {
    if line.starts_with(char::is_whitespace) || line.starts_with('#') {
        return false;
    }
    let statement = line.trim_end().ends_with(';');
    [name.to_string(), format!("{name}_")]
        .iter()
        .any(|n| match lang {
            Lang::Wgsl => {
                line.starts_with(&format!("fn {n}(")) || line.starts_with(&format!("const {n}:"))
            }
            _ if statement => {
                line.contains("const")
                    && (line.contains(&format!(" {n} =")) || line.contains(&format!(" {n}[")))
            }
            _ => line.contains(&format!(" {n}(")),
        })
}

/// Whether `line` declares the texture of `binding`.
fn is_texture(line: &str, binding: &TextureBinding, lang: Lang) -> bool {
    let name = &binding.name;
    match lang {
        Lang::Wgsl => line.contains(&format!("var {name}:")),
        Lang::Glsl => line.contains(&format!(
            "_group_{}_binding_{}_",
            binding.group, binding.binding
        )),
        Lang::Hlsl => line.contains(&format!(" {name} : register(")),
        Lang::Msl => line.contains(&format!(" {name} [[texture(")),
    }
}
