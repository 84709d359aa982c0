//! Names in the emitted code: named constants are module-scope constants read by name, and
//! functions of several outputs return structs named after them with named `f32` and
//! `vec3<f32>` fields.

use super::{check_bit_for_bit, lower_and_write_everything, reparse};
use hairmath::bcsdf::{trace_eval, ChiangHair};
use hairmath::params::HairParams;
use hairmath::real::{trace, NamedConstant, Real, ShaderFunction, Traced, PI};
use hairmath::shader::lower;

/// The lines of `text` that are not the declaration of a module-scope constant.
fn code_lines(text: &str) -> Vec<&str> {
    text.lines().filter(|l| !l.starts_with("const ")).collect()
}

#[test]
fn named_constants_are_declared_once_with_their_meaning_and_read_by_name() {
    let graph = trace_eval(&ChiangHair::new(&HairParams::default()));
    let names: Vec<&str> = graph.named_constants().iter().map(|c| c.name).collect();
    for expected in [
        "PI",
        "TWO_PI",
        "INV_TWO_PI",
        "TINY",
        "BESSEL_I0_NEAR",
        "BESSEL_I0_FAR",
    ] {
        assert!(
            names.contains(&expected),
            "{expected} missing from {names:?}"
        );
    }
    let module = lower(&graph, "chiang").unwrap();
    let wgsl = module.wgsl().unwrap();
    reparse(&wgsl).unwrap_or_else(|e| panic!("{e}\n{wgsl}"));
    let lines: Vec<&str> = wgsl.lines().collect();
    let at = lines
        .iter()
        .position(|l| *l == "const PI: f32 = 3.1415927f;")
        .unwrap_or_else(|| panic!("PI is declared\n{wgsl}"));
    assert_eq!(lines[at - 1], "// pi", "{wgsl}");
    assert!(
        wgsl.contains("const BESSEL_I0_NEAR: array<f32, 7> = array<f32, 7>(1f, 3.5156229f"),
        "{wgsl}"
    );
    let code = code_lines(&wgsl).join("\n");
    assert!(code.contains("BESSEL_I0_NEAR[6]"), "{code}");
    assert!(code.contains("+ PI)"), "{code}");
    for literal in [
        "3.1415927f",
        "6.2831855f",
        "0.15915494f",
        "3.5156229f",
        "3.75f",
    ] {
        assert!(!code.contains(literal), "{literal} is read by name\n{code}");
    }
    for (lang, text) in [
        ("GLSL", module.glsl().unwrap()),
        ("HLSL", module.hlsl().unwrap()),
        ("MSL", module.msl().unwrap()),
    ] {
        let lines: Vec<&str> = text.lines().collect();
        let at = lines
            .iter()
            .position(|l| l.contains(" PI = "))
            .unwrap_or_else(|| panic!("{lang}: PI is declared\n{text}"));
        assert_eq!(lines[at - 1], "// pi", "{lang}\n{text}");
    }
}

#[test]
fn a_named_constant_computes_its_value() {
    static HALF_TURN: NamedConstant = NamedConstant {
        name: "HALF_TURN",
        meaning: "pi, by another name",
        values: &[core::f64::consts::PI],
    };
    let graph = trace(1, |x| {
        vec![x[0] * HALF_TURN.get::<Traced>() + PI.get::<Traced>()]
    });
    assert_eq!(graph.named_constants().len(), 2);
    let expected = 0.5_f32 * core::f32::consts::PI + core::f32::consts::PI;
    assert_eq!(graph.eval_f32(&[0.5]), vec![expected]);
    lower_and_write_everything("turns", &graph);
    check_bit_for_bit("turns", &graph, &[vec![0.5], vec![-3.0]]);
}

#[test]
#[should_panic(expected = "two named constants are called TWINS")]
fn two_named_constants_may_not_share_a_name() {
    static ONE: NamedConstant = NamedConstant {
        name: "TWINS",
        meaning: "one",
        values: &[1.0],
    };
    static TWO: NamedConstant = NamedConstant {
        name: "TWINS",
        meaning: "two",
        values: &[2.0],
    };
    let _ = trace(0, |_| vec![ONE.get::<Traced>() + TWO.get::<Traced>()]);
}

/// `(x + y, (x, y, x y))` as a struct of a scalar and a vector.
fn sum_and_vector<R: Real>(x: R, y: R) -> [R; 4] {
    const FUNCTION: ShaderFunction = hairmath::shader_function!(
        sum_and_vector,
        "a test",
        [x, y] -> {sum, v: vec3}
    );
    R::call(&FUNCTION, [x, y], |[x, y]| [x + y, x, y, x * y])
}

#[test]
fn several_outputs_are_a_struct_of_named_scalar_and_vector_fields() {
    let graph = trace(2, |x| {
        let [s, a, b, c] = sum_and_vector(x[0], x[1]);
        vec![s * c, a - b]
    });
    let module = lower_and_write_everything("use_struct", &graph);
    let wgsl = module.wgsl().unwrap();
    assert!(
        wgsl.contains("struct SumAndVector {\n    sum: f32,\n    v: vec3<f32>,\n}"),
        "{wgsl}"
    );
    assert!(wgsl.contains(") -> SumAndVector {"), "{wgsl}");
    assert!(wgsl.contains(".v.z"), "{wgsl}");
    assert_eq!(
        graph.eval_f32(&[1.5, -2.0]),
        vec![(1.5 - 2.0) * (1.5 * -2.0), 3.5]
    );
    check_bit_for_bit("use_struct", &graph, &[vec![1.5, -2.0], vec![0.0, 7.0]]);
}

#[test]
fn the_near_field_returns_named_structs() {
    let graph = trace_eval(&ChiangHair::new(&HairParams::default()));
    let wgsl = lower(&graph, "chiang").unwrap().wgsl().unwrap();
    for expected in [
        "fn fibre_path(",
        ") -> FibrePath {",
        "struct FibreAngles {\n    sin_theta_i: f32,",
        ") -> Attenuations {",
        ".segment_length",
        ".residual",
    ] {
        assert!(wgsl.contains(expected), "{expected}\n{wgsl}");
    }
    assert!(!wgsl.contains("-> array<f32"), "{wgsl}");
}

#[test]
#[should_panic(expected = "declares a result of type")]
fn a_struct_result_needs_one_output_per_scalar() {
    const FUNCTION: ShaderFunction =
        hairmath::shader_function!(short, "a test", [x] -> {a, v: vec3});
    let _ = trace(1, |x| {
        Traced::call(&FUNCTION, [x[0]], |[x]| [x, x]).to_vec()
    });
}

/// `x * y` marked as a shader function (its second factor captured when it is a caller's
/// value).
fn scaled<R: Real>(x: R, y: R) -> R {
    const FUNCTION: ShaderFunction = hairmath::shader_function!(scaled, "a test", [x]);
    R::call(&FUNCTION, [x], |[x]| [x * y])[0]
}

#[test]
fn labels_name_values_and_captured_parameters_without_changing_a_bit() {
    let labelled = trace(2, |x| {
        let sum = (x[0] + x[1]).label("sum_of_both");
        let half = (sum * Traced::c(0.5)).label("half_sum");
        vec![scaled(x[0], half) + sum * sum]
    });
    let plain = trace(2, |x| {
        let sum = x[0] + x[1];
        let half = sum * Traced::c(0.5);
        vec![scaled(x[0], half) + sum * sum]
    });
    // Labels are for the written code only: the same nodes, the same values.
    assert_eq!(labelled.nodes(), plain.nodes());
    let rows = [vec![1.5, -2.0], vec![0.0, 7.0], vec![f32::MAX, 1.0]];
    for row in &rows {
        assert_eq!(labelled.eval_f32(row), plain.eval_f32(row));
    }
    assert_eq!((3.0_f32).label("x"), 3.0);
    assert_eq!((-0.0_f64).label("x").to_bits(), (-0.0_f64).to_bits());
    let module = lower_and_write_everything("labelled", &labelled);
    let wgsl = module.wgsl().unwrap();
    assert!(wgsl.contains("let sum_of_both = "), "{wgsl}");
    // The callee's captured factor is named after the caller's label.
    assert!(
        wgsl.contains("fn scaled(x: f32, half_sum: f32) -> f32"),
        "{wgsl}"
    );
    for (lang, text) in [
        ("GLSL", module.glsl().unwrap()),
        ("HLSL", module.hlsl().unwrap()),
    ] {
        assert!(text.contains("sum_of_both = "), "{lang}\n{text}");
    }
    check_bit_for_bit("labelled", &labelled, &rows);
}

#[test]
fn a_label_taken_by_a_callee_parameter_is_given_back_where_safe() {
    // `cos_phi` is a parameter of Karis' `d_karis` and `h_tt_karis` and a label of the
    // top-level function: naga numbers the later one, the writer gives the name back.
    let graph = model_graph("karis");
    let wgsl = lower(&graph, "karis").unwrap().wgsl().unwrap();
    for expected in [
        "fn d_karis(cos_phi: f32, a: f32, b: f32) -> f32 {",
        "    let cos_phi = ",
        "    let cos_theta_d = ",
        "    let cos_half_phi = ",
    ] {
        assert!(wgsl.contains(expected), "{expected}\n{wgsl}");
    }
    assert!(!wgsl.contains("cos_phi_"), "{wgsl}");
}

/// The baked shader graph of registered model `name` at its example values.
fn model_graph(name: &str) -> hairmath::real::Graph {
    let entry = hairmath::registry::find_model(name).unwrap();
    let shader = entry.shader.as_ref().unwrap();
    (shader.trace)(&entry.example_values(), &[]).unwrap()
}

#[test]
fn karis_coefficients_are_named_tables_passed_to_one_function_per_closed_form() {
    for (model, prefix) in [("karis", "KARIS"), ("karis-refit", "REFIT")] {
        let graph = model_graph(model);
        let wgsl = lower(&graph, model).unwrap().wgsl().unwrap();
        for table in ["ETA_PRIME", "D_TT", "D_TRT", "H_TT"] {
            let name = format!("{prefix}_{table}");
            assert!(
                wgsl.contains(&format!("const {name}: array<f32, 2> = ")),
                "{name}\n{wgsl}"
            );
            assert!(
                wgsl.contains(&format!("{name}[0], {name}[1]")),
                "{name}\n{wgsl}"
            );
        }
        // One d_karis serves TT and TRT.
        assert_eq!(wgsl.matches("\nfn d_karis").count(), 1, "{wgsl}");
        let code = code_lines(&wgsl).join("\n");
        for literal in ["1.19f", "-3.65f", "-16.78f", "0.6f", "0.8f"] {
            assert!(!code.contains(literal), "{literal} is read by name\n{code}");
        }
    }
}

#[test]
fn table_axes_are_named_constants() {
    let graph = model_graph("frostbite");
    let wgsl = lower(&graph, "frostbite").unwrap().wgsl().unwrap();
    for expected in [
        "const LUT0_FROSTBITE_TT_THETA_O_MIN: f32 = 0f;",
        "const LUT0_FROSTBITE_TT_BETA_N_MIN: f32 = 0.1f;",
        "(theta_o - LUT0_FROSTBITE_TT_THETA_O_MIN) * LUT0_FROSTBITE_TT_THETA_O_SCALE",
        "const TRT_OFFSET: f32 = 0.8660254f;",
    ] {
        assert!(wgsl.contains(expected), "{expected}\n{wgsl}");
    }
    // The weights start from the first factor and the sum from the first term.
    assert!(
        !wgsl.contains("vec4(0f)") && !wgsl.contains("(1f * "),
        "{wgsl}"
    );
}
