//! External validators for the emitted GLSL and SPIR-V: `glslangValidator` (Debian package
//! `glslang-tools`) and `spirv-val` (`spirv-tools`).
//!
//! A missing tool skips the validation with a message on stderr ([`Validated::Skipped`]), except
//! under `CI=true`, where it panics: CI installs both packages.
//!
//! # naga settings that produce valid output (for the emitter)
//!
//! - Validation: `naga::valid::Validator::new(ValidationFlags::all(), Capabilities::default())`;
//!   the contract's module needs no capability.
//! - GLSL: `back::glsl::Options { version: Version::Desktop(450), writer_flags:
//!   WriterFlags::empty(), binding_map, zero_initialize_workgroup_memory: true }` with
//!   `PipelineOptions { shader_stage: ShaderStage::Compute, entry_point: "hair_main", multiview:
//!   None }` and `BoundsCheckPolicies::default()` (all `Unchecked`: the kernel tests its row
//!   itself). naga's GLSL has no descriptor sets: without a `binding_map` entry a resource gets
//!   no `layout(binding = ...)` at all, which Vulkan GLSL rejects, so every resource is mapped
//!   to a flat binding ([`flat_binding_map`]: group 0's two buffers 0 and 1, group 1's table `i`
//!   2 + i). `ADJUST_COORDINATE_SPACE` only concerns vertex output and is left out. Textures read
//!   with `textureLoad` become `sampler2D` (a combined image sampler) used with `texelFetch`.
//! - glslangValidator: `-V` (Vulkan semantics, SPIR-V output to a temporary file) with
//!   `-S comp` and `--target-env vulkan1.0`; see [`glslang_validate_compute`].
//! - SPIR-V: `back::spv::Options { lang_version: (1, 0), ..Default::default() }` (the default:
//!   bindings are written as the WGSL `@group`/`@binding` through `DescriptorSet`/`Binding`
//!   decorations, no binding map needed) with `PipelineOptions { shader_stage: Compute,
//!   entry_point: "hair_main" }`; `spirv-val --target-env vulkan1.0` accepts it.

use std::path::{Path, PathBuf};
use std::process::Command;
use std::sync::atomic::{AtomicU64, Ordering};

/// What a validation did when it found no error.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Validated {
    /// The tool ran and accepted the input.
    Passed,
    /// The tool is not installed (and `CI` is not `true`): nothing was checked.
    Skipped(String),
}

/// The Vulkan version the validators check against: 1.0, the oldest, so that what passes runs
/// on every Vulkan device.
const TARGET_ENV: &str = "vulkan1.0";

/// A fresh directory under the system's temporary directory, removed when dropped.
struct TempDir(PathBuf);

impl TempDir {
    fn new() -> Result<TempDir, String> {
        static COUNTER: AtomicU64 = AtomicU64::new(0);
        let path = std::env::temp_dir().join(format!(
            "hairmath-shader-{}-{}",
            std::process::id(),
            COUNTER.fetch_add(1, Ordering::Relaxed)
        ));
        std::fs::create_dir_all(&path)
            .map_err(|error| format!("creating {}: {error}", path.display()))?;
        Ok(TempDir(path))
    }

    fn path(&self) -> &Path {
        &self.0
    }
}

impl Drop for TempDir {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.0);
    }
}

/// Runs `program` with `args`. `Ok(None)` when the program is not installed.
fn run_tool(program: &str, args: &[&std::ffi::OsStr]) -> Result<Option<Validated>, String> {
    match Command::new(program).args(args).output() {
        Err(error) if error.kind() == std::io::ErrorKind::NotFound => Ok(None),
        Err(error) => Err(format!("running {program}: {error}")),
        Ok(output) if output.status.success() => Ok(Some(Validated::Passed)),
        Ok(output) => Err(format!(
            "{program} failed ({}):\n{}{}",
            output.status,
            String::from_utf8_lossy(&output.stdout),
            String::from_utf8_lossy(&output.stderr)
        )),
    }
}

/// The outcome for a tool that is not installed: a panic under `CI=true`, else a skip.
fn missing(program: &str, package: &str) -> Validated {
    let message = format!("{program} not found (Debian package {package}): validation skipped");
    if crate::gpu::in_ci() {
        panic!("CI=true but {program} is not installed: apt-get install {package}");
    }
    eprintln!("{message}");
    Validated::Skipped(message)
}

/// Validates a Vulkan GLSL compute shader (naga's `#version 450 core` output) with
/// `glslangValidator -V --target-env vulkan1.0 -S comp <file>.comp -o <temp>.spv`: the source
/// is compiled to SPIR-V under Vulkan rules (which, unlike plain `-S comp`, i.e. OpenGL rules,
/// require a binding on every resource and accept `layout(set = ...)`), and the SPIR-V is
/// discarded. `Err` carries the tool's output.
pub fn glslang_validate_compute(source: &str) -> Result<Validated, String> {
    let dir = TempDir::new()?;
    let file = dir.path().join("shader.comp");
    let output = dir.path().join("shader.spv");
    std::fs::write(&file, source)
        .map_err(|error| format!("writing {}: {error}", file.display()))?;
    let args = [
        "-V".as_ref(),
        "--target-env".as_ref(),
        TARGET_ENV.as_ref(),
        "-S".as_ref(),
        "comp".as_ref(),
        file.as_os_str(),
        "-o".as_ref(),
        output.as_os_str(),
    ];
    Ok(run_tool("glslangValidator", &args)?
        .unwrap_or_else(|| missing("glslangValidator", "glslang-tools")))
}

/// Validates a SPIR-V binary (little-endian bytes, as [`spirv_bytes`] makes them) with
/// `spirv-val --target-env vulkan1.0`. `Err` carries the tool's output.
pub fn spirv_validate(bytes: &[u8]) -> Result<Validated, String> {
    if !bytes.len().is_multiple_of(4) {
        return Err(format!(
            "{} bytes are not a whole number of SPIR-V words",
            bytes.len()
        ));
    }
    let dir = TempDir::new()?;
    let file = dir.path().join("shader.spv");
    std::fs::write(&file, bytes).map_err(|error| format!("writing {}: {error}", file.display()))?;
    let args = [
        "--target-env".as_ref(),
        TARGET_ENV.as_ref(),
        file.as_os_str(),
    ];
    Ok(run_tool("spirv-val", &args)?.unwrap_or_else(|| missing("spirv-val", "spirv-tools")))
}

/// The bytes of SPIR-V words, little-endian (the file format `spirv-val` reads).
pub fn spirv_bytes(words: &[u32]) -> Vec<u8> {
    words.iter().flat_map(|word| word.to_le_bytes()).collect()
}

/// The flat GLSL bindings of the contract's resources: `hair_queries` (group 0, binding 0) -> 0,
/// `hair_values` (0, 1) -> 1, table `i` (group 1, binding i) -> 2 + i for `tables` tables.
pub fn flat_binding_map(tables: u32) -> naga::back::glsl::BindingMap {
    let mut map = naga::back::glsl::BindingMap::default();
    for binding in 0..2 {
        map.insert(naga::ResourceBinding { group: 0, binding }, binding as u8);
    }
    for binding in 0..tables {
        map.insert(
            naga::ResourceBinding { group: 1, binding },
            u8::try_from(2 + binding).expect("fewer than 254 tables"),
        );
    }
    map
}

/// Parses and validates WGSL with naga (the settings of the module docs).
pub fn naga_module(wgsl: &str) -> Result<(naga::Module, naga::valid::ModuleInfo), String> {
    let module = naga::front::wgsl::parse_str(wgsl).map_err(|error| error.emit_to_string(wgsl))?;
    let info = naga::valid::Validator::new(
        naga::valid::ValidationFlags::all(),
        naga::valid::Capabilities::default(),
    )
    .validate(&module)
    .map_err(|error| error.emit_to_string(wgsl))?;
    Ok((module, info))
}

/// naga's Vulkan-flavoured GLSL 450 of the compute entry point `entry`, with
/// [`flat_binding_map`]`(tables)`.
pub fn naga_glsl(
    module: &naga::Module,
    info: &naga::valid::ModuleInfo,
    entry: &str,
    tables: u32,
) -> Result<String, String> {
    use naga::back::glsl;
    let options = glsl::Options {
        version: glsl::Version::Desktop(450),
        writer_flags: glsl::WriterFlags::empty(),
        binding_map: flat_binding_map(tables),
        zero_initialize_workgroup_memory: true,
    };
    let pipeline = glsl::PipelineOptions {
        shader_stage: naga::ShaderStage::Compute,
        entry_point: entry.to_string(),
        multiview: None,
    };
    let mut source = String::new();
    glsl::Writer::new(
        &mut source,
        module,
        info,
        &options,
        &pipeline,
        naga::proc::BoundsCheckPolicies::default(),
    )
    .and_then(|mut writer| writer.write())
    .map_err(|error| format!("naga GLSL: {error}"))?;
    Ok(source)
}

/// naga's SPIR-V 1.0 of the compute entry point `entry` (bindings as declared in WGSL).
pub fn naga_spirv(
    module: &naga::Module,
    info: &naga::valid::ModuleInfo,
    entry: &str,
) -> Result<Vec<u32>, String> {
    use naga::back::spv;
    let options = spv::Options {
        lang_version: (1, 0),
        ..Default::default()
    };
    let pipeline = spv::PipelineOptions {
        shader_stage: naga::ShaderStage::Compute,
        entry_point: entry.to_string(),
    };
    spv::write_vec(module, info, &options, Some(&pipeline))
        .map_err(|error| format!("naga SPIR-V: {error}"))
}

// ---------------------------------------------------------------------------------------------
// Tests

/// A compute module to the binding contract with one 2D table, a `textureLoad`, transcendental
/// functions and the row test: what the emitter's output looks like.
const CONTRACT_MODULE: &str = r#"
@group(0) @binding(0) var<storage, read> hair_queries: array<f32>;
@group(0) @binding(1) var<storage, read_write> hair_values: array<f32>;
@group(1) @binding(0) var hair_table_0: texture_2d<f32>;

fn lobe(cos_theta: f32, v: f32) -> f32 {
    return exp(-cos_theta * cos_theta / (2.0 * v)) * inverseSqrt(6.2831855 * v);
}

@compute @workgroup_size(64)
fn hair_main(@builtin(global_invocation_id) id: vec3<u32>) {
    let row = id.x + id.y * 4194240u;
    if row >= arrayLength(&hair_values) / 3u {
        return;
    }
    let q = row * 7u;
    let wi = vec3<f32>(hair_queries[q], hair_queries[q + 1u], hair_queries[q + 2u]);
    let wo = vec3<f32>(hair_queries[q + 3u], hair_queries[q + 4u], hair_queries[q + 5u]);
    let h = hair_queries[q + 6u];
    let size = vec2<i32>(textureDimensions(hair_table_0));
    let texel = vec2<i32>(clamp(vec2<f32>(h, wi.z) * 0.5 + 0.5, vec2(0.0), vec2(1.0))
        * vec2<f32>(size - 1));
    let table = textureLoad(hair_table_0, texel, 0);
    let phi = atan2(wo.y, wo.x) - atan2(wi.y, wi.x);
    let value = table.rgb * lobe(dot(wi, wo), 0.01 + table.a) * cos(phi * 0.5);
    hair_values[row * 3u] = value.x;
    hair_values[row * 3u + 1u] = value.y;
    hair_values[row * 3u + 2u] = value.z;
}
"#;

/// naga's GLSL and SPIR-V of [`CONTRACT_MODULE`] pass `glslangValidator` and `spirv-val`, and the
/// GLSL carries the flat bindings (so that the validation sees the layout the emitter will use).
#[test]
fn naga_glsl_and_spirv_pass_the_validators() {
    let (module, info) = naga_module(CONTRACT_MODULE).unwrap();
    let glsl = naga_glsl(&module, &info, "hair_main", 1).unwrap();
    assert!(glsl.starts_with("#version 450 core"), "{glsl}");
    for binding in ["binding = 0", "binding = 1", "binding = 2"] {
        assert!(glsl.contains(binding), "{binding} missing:\n{glsl}");
    }
    let outcome = glslang_validate_compute(&glsl).unwrap_or_else(|error| panic!("{error}\n{glsl}"));
    eprintln!("glslangValidator on naga's GLSL: {outcome:?}");

    let words = naga_spirv(&module, &info, "hair_main").unwrap();
    assert_eq!(words[0], 0x0723_0203, "SPIR-V magic number");
    let outcome = spirv_validate(&spirv_bytes(&words)).unwrap();
    eprintln!("spirv-val on naga's SPIR-V: {outcome:?}");
}

/// Broken inputs are rejected: GLSL with a syntax error, GLSL with a resource but no binding
/// (what naga writes without a binding map), a truncated and a corrupted SPIR-V binary.
#[test]
fn broken_shaders_are_rejected() {
    let (module, info) = naga_module(CONTRACT_MODULE).unwrap();
    let glsl = naga_glsl(&module, &info, "hair_main", 1).unwrap();
    let broken = glsl.replacen("void main()", "void main(", 1);
    assert_ne!(broken, glsl);
    match glslang_validate_compute(&broken) {
        Err(message) => {
            assert!(message.contains("ERROR"), "{message}");
            eprintln!("glslangValidator on a syntax error: {message}");
        }
        Ok(Validated::Skipped(_)) => {}
        Ok(Validated::Passed) => panic!("a syntax error passed glslangValidator:\n{broken}"),
    }
    let unbound = naga_glsl(&module, &info, "hair_main", 0).unwrap();
    match glslang_validate_compute(&unbound) {
        Err(message) => {
            assert!(message.contains("requires layout(binding"), "{message}");
            eprintln!("glslangValidator on a table without a binding: {message}");
        }
        Ok(Validated::Skipped(_)) => {}
        Ok(Validated::Passed) => panic!("a texture without a binding passed:\n{unbound}"),
    }

    let words = naga_spirv(&module, &info, "hair_main").unwrap();
    let bytes = spirv_bytes(&words);
    assert!(spirv_validate(&bytes[..bytes.len() - 4]).rejected_or_skipped());
    let mut corrupted = words.clone();
    // The version word: SPIR-V 9.9 does not exist.
    corrupted[1] = 0x0009_0900;
    assert!(spirv_validate(&spirv_bytes(&corrupted)).rejected_or_skipped());
    assert!(spirv_validate(&bytes[..bytes.len() - 1]).is_err());
}

/// `Err`, or a skip (the tool is missing outside CI).
trait RejectedOrSkipped {
    fn rejected_or_skipped(&self) -> bool;
}

impl RejectedOrSkipped for Result<Validated, String> {
    fn rejected_or_skipped(&self) -> bool {
        matches!(self, Err(_) | Ok(Validated::Skipped(_)))
    }
}
