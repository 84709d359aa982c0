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
    assert!(code.contains("* PI)"), "{code}");
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
