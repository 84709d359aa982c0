//! The shader emitter (`hairmath::shader`): every registered real-time model and the far field
//! lower to a validated naga module and are written as WGSL (which naga's own front end parses
//! and validates again), GLSL, HLSL, MSL and SPIR-V; tables are read with `textureLoad` only;
//! the signature of a hand-made trace; errors name what failed; and, where the tools are
//! installed, `glslangValidator` and `spirv-val` accept one model's output.
//!
//! `interpret` runs the lowered naga module on the CPU with the operations of the `f32`
//! instantiation: every model's module computes exactly what its traced graph computes, bit
//! for bit.
#![cfg(feature = "shader")]

mod interpret;
mod names;
mod vectors;

use hairmath::bcsdf::{
    trace_eval, trace_eval_with, traced_inputs, ChiangFarField, FarFieldRule, FromInputs, Model,
    UniformsIn, DEFAULT_FAR_FIELD_NODES,
};
use hairmath::lut::{Axis, SharedTable, Table, TableMeta};
use hairmath::params::HairParams;
use hairmath::real::{trace, trace_with, ArgType, Graph, Parameter, ResultType, Signature};
use hairmath::real::{Real, Shape, StructType, Traced};
use hairmath::registry::{find_model, MODELS};
use hairmath::shader::{lower, ModuleBuilder, ShaderError, ShaderModule, ENTRY_POINT};
use interpret::{Interpreter, Texture, Value};
use std::io::Write as _;
use std::process::Command;
use std::sync::Arc;

/// The shader name of a model: `karis-refit` -> `karis_refit_eval`.
fn shader_name(model: &str) -> String {
    format!("{}_eval", model.replace('-', "_"))
}

/// Every registered approximation traced at its default inputs, with its shader name.
fn model_graphs() -> Vec<(String, Graph)> {
    MODELS
        .iter()
        .filter_map(|entry| {
            let approximation = entry.approximation?;
            let graph = (approximation.trace)(&entry.example_values())
                .unwrap_or_else(|e| panic!("{}: {e}", entry.name));
            Some((shader_name(entry.name), graph))
        })
        .collect()
}

/// The far field of the default hair with the default node count.
fn far_field_graph() -> Graph {
    let rule = FarFieldRule::gauss_legendre(DEFAULT_FAR_FIELD_NODES).unwrap();
    trace_eval(&ChiangFarField::with_rule(&HairParams::default(), &rule))
}

/// naga's WGSL front end and validator (all checks, all capabilities) on `source`.
fn reparse(source: &str) -> Result<naga::Module, String> {
    use naga::valid::{Capabilities, ValidationFlags, Validator};
    let module = naga::front::wgsl::parse_str(source).map_err(|e| e.emit_to_string(source))?;
    Validator::new(ValidationFlags::all(), Capabilities::all())
        .validate(&module)
        .map_err(|e| e.emit_to_string(source))?;
    Ok(module)
}

/// Lowers `graph` as `name` and writes every language; checks what each must contain.
fn lower_and_write_everything(name: &str, graph: &Graph) -> ShaderModule {
    let library = lower(graph, name).unwrap_or_else(|e| panic!("{name}: {e}"));
    let wgsl = library.wgsl().unwrap_or_else(|e| panic!("{name}: {e}"));
    let reparsed = reparse(&wgsl).unwrap_or_else(|e| panic!("{name}: {e}\n{wgsl}"));
    assert!(
        reparsed.entry_points.is_empty(),
        "{name}: the library form has no entry point"
    );
    assert!(
        wgsl.contains(&format!("fn {name}(")),
        "{name}: the top-level function\n{wgsl}"
    );
    assert!(
        wgsl.contains(&format!("// {name}: the traced function")),
        "{name}: its comment\n{wgsl}"
    );

    let module = library
        .with_compute_entry(library.argument_scalars())
        .unwrap_or_else(|e| panic!("{name}: {e}"));
    let wgsl = module.wgsl().unwrap_or_else(|e| panic!("{name}: {e}"));
    let reparsed = reparse(&wgsl).unwrap_or_else(|e| panic!("{name}: {e}\n{wgsl}"));
    assert_eq!(reparsed.entry_points.len(), 1, "{name}");
    assert_eq!(reparsed.entry_points[0].name, ENTRY_POINT);
    assert_eq!(reparsed.entry_points[0].workgroup_size, [64, 1, 1]);
    for (lang, text, entry) in [
        ("GLSL", library.glsl(), "void main()"),
        ("HLSL", library.hlsl(), ENTRY_POINT),
        ("MSL", library.msl(), ENTRY_POINT),
    ] {
        let text = text.unwrap_or_else(|e| panic!("{name} {lang}: {e}"));
        assert!(
            text.contains(entry),
            "{name} {lang}: the entry point\n{text}"
        );
        assert!(
            text.contains(&format!("// {name}: the traced function")),
            "{name} {lang}: the comment\n{text}"
        );
    }
    let glsl = library.glsl().unwrap();
    assert!(glsl.starts_with("#version 450"), "{name}: {glsl}");
    let words = library
        .spirv()
        .unwrap_or_else(|e| panic!("{name} SPIR-V: {e}"));
    assert_eq!(words[0], 0x0723_0203, "{name}: the SPIR-V magic number");
    module
}

#[test]
fn every_registered_approximation_lowers_validates_and_writes_every_language() {
    let graphs = model_graphs();
    assert!(graphs.len() >= 9, "the registry's approximations");
    for (name, graph) in &graphs {
        lower_and_write_everything(name, graph);
    }
}

#[test]
fn the_far_field_lowers_validates_and_writes_every_language() {
    lower_and_write_everything("chiang_far_eval", &far_field_graph());
}

#[test]
fn tables_are_read_with_texture_load_and_never_sampled() {
    let graphs = model_graphs();
    let with_tables: Vec<&(String, Graph)> = graphs
        .iter()
        .filter(|(_, g)| !g.tables().is_empty())
        .collect();
    assert!(
        with_tables.len() >= 3,
        "nguyen-donnelly, gerard and frostbite fetch tables"
    );
    for (name, graph) in with_tables {
        let module = lower(graph, name).unwrap();
        let textures: usize = graph
            .tables()
            .iter()
            .map(|t| t.channels().len().div_ceil(4))
            .sum();
        assert_eq!(module.bindings().len(), textures, "{name}");
        let wgsl = module
            .with_compute_entry(module.argument_scalars())
            .unwrap()
            .wgsl()
            .unwrap();
        assert!(wgsl.contains("textureLoad("), "{name}\n{wgsl}");
        assert!(!wgsl.contains("textureSample"), "{name}\n{wgsl}");
        assert!(!wgsl.contains("sampler"), "{name}\n{wgsl}");
        for (k, b) in module.bindings().iter().enumerate() {
            assert_eq!(b.binding, k as u32);
            assert_eq!(b.group, 1);
            let ty = format!("texture_{}d<f32>", b.dimension);
            assert!(
                wgsl.contains(&format!("@group(1) @binding({k}) \nvar {}: {ty};", b.name))
                    || wgsl.contains(&format!("@group(1) @binding({k})\nvar {}: {ty};", b.name))
                    || wgsl.contains(&format!("@group(1) @binding({k}) var {}: {ty};", b.name)),
                "{name}: binding {k}\n{wgsl}"
            );
            assert!(
                wgsl.contains(&format!("// {}", b.describe())),
                "{name}\n{wgsl}"
            );
        }
        for lang in [
            module.glsl().unwrap(),
            module.hlsl().unwrap(),
            module.msl().unwrap(),
        ] {
            assert!(!lang.contains("Sample("), "{name}\n{lang}");
        }
    }
}

/// A 3 x 2 table of 5 channels (two textures) with distinct values.
fn small_table() -> Arc<Table> {
    let axes = vec![
        Axis::new("theta", -1.0, 1.0, 3).unwrap(),
        Axis::new("phi", 0.0, 2.0, 2).unwrap(),
    ];
    let channels: Vec<String> = ["a", "b", "c", "d", "e"].map(String::from).to_vec();
    let data: Vec<f32> = (0..30).map(|i| i as f32 * 0.5 + 1.0).collect();
    let meta = TableMeta {
        kind: "small test".into(),
        ..TableMeta::default()
    };
    Arc::new(
        Table::new(axes, channels, data)
            .unwrap()
            .with_meta(meta)
            .unwrap(),
    )
}

#[test]
fn a_table_of_five_channels_is_two_textures_with_their_texels() {
    let table = SharedTable::<2, 5>::from_arc(small_table()).unwrap();
    let graph = trace(2, |x| {
        let v = Traced::sample_table(&table, [x[0], x[1]]);
        vec![v[0] + v[4], v[2]]
    });
    let module = lower(&graph, "two_textures").unwrap();
    let b = module.bindings();
    assert_eq!(b.len(), 2);
    assert_eq!(
        (b[0].name.as_str(), b[1].name.as_str()),
        ("lut0_small_test_texels_a", "lut0_small_test_texels_b")
    );
    assert_eq!(b[0].channels, ["a", "b", "c", "d"]);
    assert_eq!(b[1].channels, ["e"]);
    assert_eq!(b[1].extent(), [3, 2, 1]);
    let texels = b[1].texels(graph.tables()[0].as_ref());
    assert_eq!(texels.len(), 6);
    // Texel (i, j) = sample (i, j): channel e of grid point 4 (i = 1, j = 1) is value 24.
    assert_eq!(texels[4], [(24.0 * 0.5 + 1.0), 0.0, 0.0, 0.0]);
    assert_eq!(
        b[0].texels(graph.tables()[0].as_ref())[1],
        [3.5, 4.0, 4.5, 5.0]
    );
    let wgsl = module.wgsl().unwrap();
    reparse(&wgsl).unwrap_or_else(|e| panic!("{e}\n{wgsl}"));
    assert!(
        wgsl.contains("fn lut0_small_test(theta: f32, phi: f32) -> array<vec4<f32>, 2>"),
        "{wgsl}"
    );
    // One helper call for the three channels read at the same coordinates.
    assert_eq!(wgsl.matches("lut0_small_test(").count(), 2, "{wgsl}");
    assert_eq!(wgsl.matches("textureLoad(").count(), 8, "{wgsl}");
}

#[test]
fn vector_and_struct_arguments_give_the_expected_signature() {
    let material = ArgType::Struct(StructType {
        name: "Material".into(),
        fields: vec![
            ("eta".into(), ArgType::Scalar),
            ("sigma_a".into(), ArgType::Vec3),
            ("gain".into(), ArgType::Scalar),
        ],
    });
    let signature = Signature {
        parameters: vec![
            parameter("m", material),
            parameter("wi", ArgType::Vec3),
            parameter("h", ArgType::Scalar),
        ],
        result: ResultType::Vec3,
    };
    let graph = trace_with(signature, |x| {
        vec![
            x[0] * x[5],
            x[2].max(x[8]),
            (x[3] + x[4]).sqrt() - x[6].atan2(x[7]),
        ]
    });
    let module = lower(&graph, "shade").unwrap();
    let wgsl = module.wgsl().unwrap();
    assert!(
        wgsl.contains(
            "struct Material {\n    eta: f32,\n    sigma_a: vec3<f32>,\n    gain: f32,\n}"
        ),
        "{wgsl}"
    );
    assert!(
        wgsl.contains("fn shade(m: Material, wi: vec3<f32>, h: f32) -> vec3<f32> {"),
        "{wgsl}"
    );
    assert!(wgsl.contains("atan2("), "{wgsl}");
    // WGSL's layout: sigma_a at 16 (vec3 aligned to 16), gain right after it at 28, size 32.
    let ty = module
        .module()
        .types
        .iter()
        .find(|(_, t)| t.name.as_deref() == Some("Material"))
        .expect("the struct type")
        .1;
    let naga::TypeInner::Struct { members, span } = &ty.inner else {
        panic!("a struct")
    };
    let offsets: Vec<u32> = members.iter().map(|m| m.offset).collect();
    assert_eq!((offsets, *span), (vec![0, 16, 28], 32));
    let reparsed = reparse(&wgsl).unwrap();
    let (_, again) = reparsed
        .types
        .iter()
        .find(|(_, t)| t.name.as_deref() == Some("Material"))
        .unwrap();
    assert_eq!(
        again.inner, ty.inner,
        "naga's front end computes the same layout"
    );

    let entry = module.with_compute_entry(9).unwrap().wgsl().unwrap();
    assert!(
        entry.contains(
            "@compute @workgroup_size(64, 1, 1) \n\
             fn hair_main(@builtin(global_invocation_id) id: vec3<u32>) {\n    \
             let row = (id.x + ((id.y * 65535u) * 64u));\n    \
             if (row >= (arrayLength((&hair_values)) / 3u)) {\n        \
             return;\n    }\n"
        ),
        "{entry}"
    );
    // naga writes the default access mode `read` of `var<storage>` implicitly.
    assert!(
        entry.contains("@group(0) @binding(0) \nvar<storage> hair_queries: array<f32>;"),
        "{entry}"
    );
    assert!(
        entry.contains("var<storage, read_write> hair_values: array<f32>;"),
        "{entry}"
    );
}

fn parameter(name: &str, ty: ArgType) -> Parameter {
    Parameter::argument(name, ty)
}

#[test]
fn one_output_is_f32_and_several_an_array() {
    let one = lower(&trace(2, |x| vec![x[0] / x[1]]), "ratio").unwrap();
    assert!(
        one.wgsl()
            .unwrap()
            .contains("fn ratio(x0_: f32, x1_: f32) -> f32 {"),
        "{}",
        one.wgsl().unwrap()
    );
    let two = lower(&trace(1, |x| vec![x[0].exp(), -x[0]]), "pair").unwrap();
    assert!(
        two.wgsl().unwrap().contains("-> array<f32, 2> {"),
        "{}",
        two.wgsl().unwrap()
    );
    // The entry point writes the first outputs and zeros.
    let entry = two.with_compute_entry(4).unwrap().wgsl().unwrap();
    reparse(&entry).unwrap_or_else(|e| panic!("{e}\n{entry}"));
}

#[test]
fn errors_name_what_failed() {
    // An infinite constant is no valid shader literal: the validator's error names the function.
    let graph = trace(1, |x| vec![x[0] * Traced::c(f64::INFINITY)]);
    match lower(&graph, "overflowing") {
        Err(ShaderError::Validation { function, message }) => {
            assert_eq!(function, "overflowing", "{message}");
        }
        other => panic!("{other:?}"),
    }
    let module = lower(&trace(3, |x| vec![x[0] + x[1] + x[2]]), "sum3").unwrap();
    assert_eq!(
        module.with_compute_entry(2).unwrap_err(),
        ShaderError::Stride {
            function: "sum3".into(),
            stride: 2,
            needed: 3
        }
    );
}

#[test]
fn the_naga_oil_form_starts_with_its_import_path() {
    let (name, graph) = model_graphs().remove(0);
    let module = lower(&graph, &name).unwrap();
    let text = module.naga_oil_wgsl("hairmath::karis").unwrap();
    assert!(
        text.starts_with("#define_import_path hairmath::karis\n"),
        "{text}"
    );
    let body = text.split_once('\n').unwrap().1;
    reparse(body).unwrap();
    // Also from a module with the entry point: the import is the library form.
    let with_entry = module
        .with_compute_entry(module.argument_scalars())
        .unwrap();
    assert!(!with_entry
        .naga_oil_wgsl("hairmath::karis")
        .unwrap()
        .contains(ENTRY_POINT));
}

/// Whether the tools must be there (`CI=true`).
fn ci() -> bool {
    std::env::var("CI").is_ok_and(|v| v == "true")
}

/// Runs `tool args file` on `contents` written to a temporary file named `file`; `None` when
/// the tool is missing outside CI.
fn run_tool(tool: &str, args: &[&str], file: &str, contents: &[u8]) -> Option<Result<(), String>> {
    let dir = std::env::temp_dir().join(format!("hairmath-shader-lower-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join(file);
    std::fs::File::create(&path)
        .unwrap()
        .write_all(contents)
        .unwrap();
    let output = Command::new(tool)
        .args(args)
        .arg(&path)
        .current_dir(&dir)
        .output();
    match output {
        Err(e) if e.kind() == std::io::ErrorKind::NotFound && !ci() => {
            eprintln!("skipped: {tool} is not installed (install glslang-tools and spirv-tools)");
            None
        }
        Err(e) => panic!("{tool}: {e}"),
        Ok(o) if o.status.success() => Some(Ok(())),
        Ok(o) => Some(Err(format!(
            "{}{}",
            String::from_utf8_lossy(&o.stdout),
            String::from_utf8_lossy(&o.stderr)
        ))),
    }
}

#[test]
fn glslang_and_spirv_val_accept_models_with_tables_calls_and_loops() {
    let graphs = model_graphs();
    let rule = FarFieldRule::gauss_legendre(DEFAULT_FAR_FIELD_NODES).unwrap();
    let far = ChiangFarField::with_rule(&HairParams::default(), &rule);
    let far = trace_eval_with(&far, UniformsIn::Constant);
    let mut cases: Vec<(&str, &Graph)> = graphs
        .iter()
        .filter(|(n, _)| n == "gerard_eval" || n == "karis_eval" || n == "nguyen_donnelly_eval")
        .map(|(n, g)| (n.as_str(), g))
        .collect();
    cases.push(("chiang_far_eval", &far));
    assert_eq!(cases.len(), 4);
    for (name, graph) in cases {
        let module = lower(graph, name).unwrap();
        let glsl = module.glsl().unwrap();
        let file = format!("{name}.comp");
        let vulkan_out = format!("{name}.glslang.spv");
        for args in [
            &["-S", "comp"][..],
            &[
                "-V",
                "--target-env",
                "vulkan1.0",
                "-o",
                &vulkan_out,
                "-S",
                "comp",
            ][..],
        ] {
            if let Some(result) = run_tool("glslangValidator", args, &file, glsl.as_bytes()) {
                result.unwrap_or_else(|e| {
                    panic!("{name}: glslangValidator {args:?} rejects the GLSL:\n{e}\n{glsl}")
                });
            }
        }
        let spirv = module.spirv_bytes().unwrap();
        for args in [&[][..], &["--target-env", "vulkan1.0"][..]] {
            if let Some(result) = run_tool("spirv-val", args, &format!("{name}.spv"), &spirv) {
                result.unwrap_or_else(|e| {
                    panic!("{name}: spirv-val {args:?} rejects the SPIR-V:\n{e}")
                });
            }
        }
    }
}

// ---------------------------------------------------------------------------------------------
// The lowered module computes what the graph computes, bit for bit (on the CPU).

/// The top-level function's arguments from one input row of [`Graph::eval_f32`].
fn arguments(graph: &Graph, row: &[f32]) -> Vec<Value> {
    fn take(ty: &ArgType, values: &mut std::slice::Iter<'_, f32>) -> Value {
        match ty {
            ArgType::Scalar => Value::F32(*values.next().expect("a value per scalar")),
            ArgType::Vec3 => Value::List((0..3).map(|_| take(&ArgType::Scalar, values)).collect()),
            ArgType::Struct(s) => {
                Value::List(s.fields.iter().map(|(_, t)| take(t, values)).collect())
            }
        }
    }
    let mut values = row.iter();
    let args = graph
        .signature()
        .parameters
        .iter()
        .filter(|p| p.constant.is_none())
        .map(|p| take(&p.ty, &mut values))
        .collect();
    assert!(values.next().is_none(), "one value per argument scalar");
    args
}

/// The textures of `module`'s bindings filled from the graph's tables.
fn textures(module: &ShaderModule, graph: &Graph) -> Vec<(String, Texture)> {
    module
        .bindings()
        .iter()
        .map(|b| {
            let texture = Texture {
                extent: b.extent(),
                texels: b.texels(&graph.tables()[b.table]),
            };
            (b.name.clone(), texture)
        })
        .collect()
}

/// Interprets the lowered `graph` on every row and compares with `graph.eval_f32` bit for bit.
fn check_bit_for_bit(name: &str, graph: &Graph, rows: &[Vec<f32>]) {
    let module = lower(graph, name).unwrap_or_else(|e| panic!("{name}: {e}"));
    let interpreter = Interpreter::new(module.module(), textures(&module, graph));
    let mut failures = Vec::new();
    for row in rows {
        let expected = graph.eval_f32(row);
        let got = interpreter.call(name, arguments(graph, row)).flatten();
        let same = got.len() == expected.len()
            && got
                .iter()
                .zip(&expected)
                .all(|(a, b)| a.to_bits() == b.to_bits());
        if !same {
            failures.push(format!(
                "  {row:?}\n  shader {got:?}\n  graph  {expected:?}"
            ));
        }
    }
    assert!(
        failures.is_empty(),
        "{name}: {} of {} rows differ:\n{}",
        failures.len(),
        rows.len(),
        failures[..failures.len().min(4)].join("\n")
    );
}

/// Unit direction pairs: the hard cases (wi = wo, wi = -wo, along the tangent, grazing,
/// phi = 0 and pi) and a deterministic spread over the sphere.
fn direction_pairs() -> Vec<[f32; 6]> {
    let unit = |x: f64, phi: f64| {
        let r = (1.0 - x * x).max(0.0).sqrt();
        [x as f32, (r * phi.cos()) as f32, (r * phi.sin()) as f32]
    };
    let pair = |a: [f32; 3], b: [f32; 3]| [a[0], a[1], a[2], b[0], b[1], b[2]];
    let mut out = Vec::new();
    for &(x, phi) in &[
        (0.3, 0.4),
        (-0.7, 2.0),
        (0.0, 0.0),
        (0.999_999, 1.0),
        (-1.0, 0.0),
    ] {
        let w = unit(x, phi);
        out.push(pair(w, w));
        out.push(pair(w, w.map(|c| -c)));
        out.push(pair(w, unit(-x, phi)));
        out.push(pair(w, unit(x, phi + std::f64::consts::PI)));
    }
    out.push(pair([1.0, 0.0, 0.0], [-1.0, 0.0, 0.0]));
    out.push(pair([0.0, 1.0, 0.0], [0.0, -1.0, 0.0]));
    let golden = std::f64::consts::PI * (3.0 - 5f64.sqrt());
    for k in 0..160 {
        let x = 1.0 - 2.0 * (k as f64 + 0.5) / 160.0;
        let y = 1.0 - 2.0 * (((k * 37) % 160) as f64 + 0.5) / 160.0;
        out.push(pair(
            unit(x, golden * k as f64),
            unit(y, 0.7 * k as f64 + 1.0),
        ));
    }
    out
}

/// The input rows of `model`'s traced evaluation over [`direction_pairs`].
fn model_rows<M: Model>(model: &M, graph: &Graph) -> Vec<Vec<f32>> {
    direction_pairs()
        .iter()
        .flat_map(|d| {
            let offsets: &[f32] = if model.uses_offset() {
                &[-1.0, 0.3, 1.0]
            } else {
                &[0.0]
            };
            offsets.iter().map(move |&h| {
                let mut extra = d.to_vec();
                if model.uses_offset() {
                    extra.push(h);
                }
                if graph.input_count() == extra.len() {
                    extra
                } else {
                    traced_inputs(model, &extra)
                }
            })
        })
        .collect()
}

/// Builds the registered model `name` at its default inputs and checks its lowered
/// evaluation bit for bit.
fn check_model<M: Model + FromInputs>(name: &str) {
    let entry = find_model(name).unwrap_or_else(|| panic!("{name} is registered"));
    let model = M::from_inputs(&entry.example_values()).unwrap();
    for uniforms in [UniformsIn::Argument, UniformsIn::Constant] {
        let graph = trace_eval_with(&model, uniforms);
        let rows = model_rows(&model, &graph);
        check_bit_for_bit(&shader_name(name), &graph, &rows);
    }
}

#[test]
fn every_model_shader_computes_its_graph_bit_for_bit() {
    use hairmath::models::*;
    check_model::<Karis<f64>>("karis");
    check_model::<KarisRefit<f64>>("karis-refit");
    check_model::<KajiyaKay<f64>>("kajiya-kay");
    check_model::<TressFx<f64>>("tressfx");
    check_model::<Scheuermann<f64>>("scheuermann");
    check_model::<NguyenDonnelly<f64>>("nguyen-donnelly");
    check_model::<Gerard<f64>>("gerard");
    check_model::<Frostbite<f64>>("frostbite");
    check_model::<FrostbiteRefit<f64>>("frostbite-refit");
    let registered = MODELS.iter().filter(|m| m.approximation.is_some()).count();
    assert_eq!(registered, 9, "a new registered model is checked here too");
}

#[test]
fn the_far_field_shader_computes_its_graph_bit_for_bit() {
    let rule = FarFieldRule::gauss_legendre(8).unwrap();
    let model = ChiangFarField::with_rule(&HairParams::default(), &rule);
    for uniforms in [UniformsIn::Argument, UniformsIn::Constant] {
        let graph = trace_eval_with(&model, uniforms);
        assert!(
            !graph.arrays().is_empty(),
            "the far field's nodes are a loop"
        );
        check_bit_for_bit("chiang_far_eval", &graph, &model_rows(&model, &graph));
    }
}

#[test]
fn table_interpolation_matches_lookup_into_bit_for_bit_at_edges_and_outside() {
    let table = SharedTable::<2, 5>::from_arc(small_table()).unwrap();
    let graph = trace(2, |x| Traced::sample_table(&table, [x[0], x[1]]).to_vec());
    let mut rows = Vec::new();
    for x in [-2.0f32, -1.0, -0.999, -0.3, 0.0, 0.5, 0.999_999, 1.0, 1.5] {
        for y in [-0.5f32, 0.0, 0.25, 1.0, 1.999, 2.0, 7.0] {
            rows.push(vec![x, y]);
        }
    }
    check_bit_for_bit("lookup", &graph, &rows);
    // A 1D and a 3D table.
    let line = Table::new(
        vec![Axis::new("u", 0.5, 4.0, 5).unwrap()],
        vec!["v".into()],
        vec![1.0, -2.0, 3.5, 0.25, 9.0],
    )
    .unwrap();
    let line = SharedTable::<1, 1>::new(line).unwrap();
    let cube_data: Vec<f32> = (0..2 * 3 * 4 * 2).map(|i| (i as f32).sin()).collect();
    let cube = Table::new(
        vec![
            Axis::new("a", 0.0, 1.0, 2).unwrap(),
            Axis::new("b", -1.0, 1.0, 3).unwrap(),
            Axis::new("c", 0.0, 3.0, 4).unwrap(),
        ],
        vec!["p".into(), "q".into()],
        cube_data,
    )
    .unwrap();
    let cube = SharedTable::<3, 2>::new(cube).unwrap();
    let graph = trace(3, |x| {
        let [v] = Traced::sample_table(&line, [x[0] * Traced::c(4.0)]);
        let [p, q] = Traced::sample_table(&cube, [x[0], x[1], x[2]]);
        vec![v, p, q]
    });
    let module = lower(&graph, "two_tables").unwrap();
    let wgsl = module.wgsl().unwrap();
    assert!(
        wgsl.contains("texture_1d<f32>") && wgsl.contains("texture_3d<f32>"),
        "{wgsl}"
    );
    reparse(&wgsl).unwrap_or_else(|e| panic!("{e}\n{wgsl}"));
    let rows: Vec<Vec<f32>> = (0..200)
        .map(|k| {
            let t = k as f32 * 0.731;
            vec![t.sin() * 1.2, (t * 1.7).cos() * 1.3, t % 3.5 - 0.2]
        })
        .collect();
    check_bit_for_bit("two_tables", &graph, &rows);
}

// ---------------------------------------------------------------------------------------------
// Several graphs in one module.

/// The default Karis model and its graph with baked uniforms.
fn karis() -> (hairmath::models::Karis<f64>, Graph) {
    let model =
        hairmath::models::Karis::<f64>::from_inputs(&find_model("karis").unwrap().example_values())
            .unwrap();
    let graph = trace_eval_with(&model, UniformsIn::Constant);
    (model, graph)
}

#[test]
fn the_public_names_are_kept_and_every_function_has_its_comment() {
    let (_, graph) = karis();
    let module = lower(&graph, "hair_bcsdf").unwrap();
    let wgsl = module.wgsl().unwrap();
    assert!(
        wgsl.contains("fn hair_bcsdf(wi: vec3<f32>, wo: vec3<f32>) -> vec3<f32> {"),
        "{wgsl}"
    );
    assert!(
        wgsl.contains("const uniforms: KarisUniforms = KarisUniforms("),
        "{wgsl}"
    );
    assert!(wgsl.contains("uniforms.width_r"), "{wgsl}");
    assert!(!graph.functions().is_empty(), "the physics is marked");
    for f in graph.functions() {
        let (source, equation) = match f.kind {
            hairmath::real::FunctionKind::Function(i) => (i.source, i.equation),
            hairmath::real::FunctionKind::LoopBody(l) => (l.source, l.equation),
        };
        // naga writes a name ending in a digit with an underscore: `d_karis_2_`.
        let defined = [format!("fn {}(", f.name), format!("fn {}_(", f.name)]
            .iter()
            .any(|d| wgsl.contains(&format!("// {source} -- {equation}\n{d}")));
        assert!(defined, "{}\n{wgsl}", f.name);
    }
    for text in [
        module.glsl().unwrap(),
        module.hlsl().unwrap(),
        module.msl().unwrap(),
    ] {
        for f in graph.functions() {
            assert!(
                text.contains(&format!(" {}(", f.name)) || text.contains(&format!(" {}_(", f.name)),
                "{}\n{text}",
                f.name
            );
        }
        assert_eq!(
            text.matches("// hairmath::").count(),
            graph.functions().len(),
            "{text}"
        );
    }
}

#[test]
fn graphs_in_one_module_share_equal_functions_tables_and_constants() {
    let (_, graph) = karis();
    let alone = lower(&graph, "hair_bcsdf").unwrap();
    let twice = ModuleBuilder::new()
        .add(&graph, "hair_bcsdf")
        .unwrap()
        .add(&graph, "hair_bcsdf_again")
        .unwrap()
        .build()
        .unwrap();
    assert_eq!(
        twice.module().functions.len(),
        alone.module().functions.len() + 1,
        "the second graph adds only its top-level function"
    );
    assert_eq!(
        twice.module().constants.len(),
        alone.module().constants.len()
    );
    assert_eq!(twice.functions(), ["hair_bcsdf", "hair_bcsdf_again"]);
    reparse(&twice.wgsl().unwrap()).unwrap();
    assert_eq!(
        ModuleBuilder::new()
            .add(&graph, "f")
            .unwrap()
            .add(&graph, "f")
            .err(),
        Some(ShaderError::NameConflict { name: "f".into() })
    );

    // Two models of tables: one binding set per table, every function once.
    let graphs = model_graphs();
    let tabled: Vec<&(String, Graph)> = graphs
        .iter()
        .filter(|(_, g)| !g.tables().is_empty())
        .collect();
    let mut builder = ModuleBuilder::new();
    for (name, g) in &tabled {
        builder = builder.add(g, name).unwrap();
    }
    let together = builder.build().unwrap();
    let tables: usize = tabled
        .iter()
        .flat_map(|(_, g)| {
            g.tables()
                .iter()
                .map(|t| std::sync::Arc::as_ptr(t) as usize)
        })
        .collect::<std::collections::BTreeSet<_>>()
        .len();
    assert_eq!(together.tables().len(), tables);
    let textures: usize = together
        .tables()
        .iter()
        .map(|t| t.channels().len().div_ceil(4))
        .sum();
    assert_eq!(together.bindings().len(), textures);
    for (k, b) in together.bindings().iter().enumerate() {
        assert_eq!(b.binding, k as u32);
    }
    let names: Vec<&str> = together
        .module()
        .functions
        .iter()
        .filter_map(|(_, f)| f.name.as_deref())
        .collect();
    let unique: std::collections::BTreeSet<&str> = names.iter().copied().collect();
    assert_eq!(unique.len(), names.len(), "{names:?}");
    let wgsl = together.wgsl().unwrap();
    reparse(&wgsl).unwrap_or_else(|e| panic!("{e}\n{wgsl}"));
    // The uniforms of the Argument form are arguments; baked ones of two models conflict.
    let frostbite = hairmath::models::Frostbite::<f64>::from_inputs(
        &find_model("frostbite").unwrap().example_values(),
    )
    .unwrap();
    let baked = trace_eval_with(&frostbite, UniformsIn::Constant);
    assert_eq!(
        ModuleBuilder::new()
            .add(&graph, "karis")
            .unwrap()
            .add(&baked, "frostbite")
            .err(),
        Some(ShaderError::ConstantConflict {
            name: "uniforms".into()
        })
    );
}

/// A stand-in for the fibre frame: `(tangent, wi, wo)` -> local wi and wo as a struct of two
/// `vec3<f32>` (here the components of wi and wo in a frame built from the tangent's
/// components).
fn frame_graph() -> Graph {
    let signature = Signature {
        parameters: ["tangent", "wi", "wo"]
            .map(|n| Parameter::argument(n, ArgType::Vec3))
            .to_vec(),
        result: ResultType::Fields(&[("wi", Shape::Vec3), ("wo", Shape::Vec3)]),
    };
    trace_with(signature, |x| {
        let (t, wi, wo) = (&x[0..3], &x[3..6], &x[6..9]);
        let dot = |a: &[Traced], b: &[Traced]| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
        let n = [t[1], -t[0], Traced::c(0.0)];
        let b = [t[2] * t[0], t[2] * t[1], -(t[0] * t[0] + t[1] * t[1])];
        vec![
            dot(wi, t),
            dot(wi, &n),
            dot(wi, &b),
            dot(wo, t),
            dot(wo, &n),
            dot(wo, &b),
        ]
    })
}

#[test]
fn the_world_companion_calls_the_frame_then_the_local_function() {
    world_companion_with(&frame_graph());
    world_companion_with(&hairmath::geometry::trace_local_directions());
}

fn world_companion_with(frame: &Graph) {
    let (_, graph) = karis();
    let module = ModuleBuilder::new()
        .add(&graph, "hair_bcsdf")
        .unwrap()
        .add(frame, "fibre_local_directions")
        .unwrap()
        .world_companion("hair_bcsdf_world", "fibre_local_directions", "hair_bcsdf")
        .unwrap()
        .build()
        .unwrap();
    let wgsl = module.wgsl().unwrap();
    reparse(&wgsl).unwrap_or_else(|e| panic!("{e}\n{wgsl}"));
    for signature in [
        "fn hair_bcsdf(wi: vec3<f32>, wo: vec3<f32>) -> vec3<f32> {",
        "fn fibre_local_directions(tangent: vec3<f32>, wi: vec3<f32>, wo: vec3<f32>) -> FibreLocalDirections {",
        "fn hair_bcsdf_world(tangent: vec3<f32>, wi: vec3<f32>, wo: vec3<f32>) -> vec3<f32> {",
    ] {
        assert!(wgsl.contains(signature), "{signature}\n{wgsl}");
    }
    for text in [
        module.glsl().unwrap(),
        module.hlsl().unwrap(),
        module.msl().unwrap(),
    ] {
        assert!(text.contains("hair_bcsdf_world("), "{text}");
    }
    // The entry point evaluates the local function.
    let entry = module.with_compute_entry(6).unwrap();
    assert_eq!(entry.entry_function(), Some("hair_bcsdf"));
    assert!(entry.wgsl().unwrap().contains("hair_bcsdf(vec3<f32>("));

    let interpreter = Interpreter::new(module.module(), Vec::new());
    for d in direction_pairs().iter().take(60) {
        let t = [d[1], -d[0], 0.5];
        let mut row = t.to_vec();
        row.extend_from_slice(d);
        let local = frame.eval_f32(&row);
        let expected = graph.eval_f32(&local);
        let v3 = |v: &[f32]| Value::List(v.iter().map(|&x| Value::F32(x)).collect());
        let got = interpreter
            .call("hair_bcsdf_world", vec![v3(&t), v3(&d[..3]), v3(&d[3..])])
            .flatten();
        assert_eq!(
            got.iter().map(|v| v.to_bits()).collect::<Vec<_>>(),
            expected.iter().map(|v| v.to_bits()).collect::<Vec<_>>(),
            "{row:?}"
        );
    }
    assert!(matches!(
        ModuleBuilder::new()
            .add(&graph, "a")
            .unwrap()
            .world_companion("w", "a", "a"),
        Err(ShaderError::Unsupported(_))
    ));
}

#[test]
fn the_naga_oil_form_composes_into_a_shader_that_imports_it() {
    use naga_oil::compose::{
        ComposableModuleDescriptor, Composer, NagaModuleDescriptor, ShaderLanguage,
    };
    let (_, karis) = karis();
    let gerard = {
        let entry = find_model("gerard").unwrap();
        let model = hairmath::models::Gerard::<f64>::from_inputs(&entry.example_values()).unwrap();
        trace_eval_with(&model, UniformsIn::Constant)
    };
    for (path, graph) in [("hairmath::karis", &karis), ("hairmath::gerard", &gerard)] {
        let library = lower(graph, "hair_bcsdf")
            .unwrap()
            .naga_oil_wgsl(path)
            .unwrap();
        let mut composer = Composer::default();
        composer
            .add_composable_module(ComposableModuleDescriptor {
                source: &library,
                file_path: "hairmath.wgsl",
                language: ShaderLanguage::Wgsl,
                ..Default::default()
            })
            .unwrap_or_else(|e| panic!("{path}: {e:?}\n{library}"));
        let main = format!(
            "#import {path}::hair_bcsdf\n\
             @group(0) @binding(0) var<storage, read_write> out: array<f32>;\n\
             @compute @workgroup_size(1)\n\
             fn main() {{\n    \
             let v = hair_bcsdf(vec3<f32>(0.0, 1.0, 0.0), vec3<f32>(0.0, 0.0, 1.0));\n    \
             out[0] = v.x + v.y + v.z;\n\
             }}\n"
        );
        let module = composer
            .make_naga_module(NagaModuleDescriptor {
                source: &main,
                file_path: "main.wgsl",
                ..Default::default()
            })
            .unwrap_or_else(|e| panic!("{path}: {e:?}"));
        assert!(module.functions.len() > 1, "{path}");
        assert_eq!(
            module.global_variables.len(),
            1 + graph.tables().len(),
            "{path}: the textures come along"
        );
    }
}
