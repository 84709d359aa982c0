//! Colours computed channel by channel in Rust are vector expressions in shader code
//! (`hairmath::shader`'s vectorizer), computing the same bits.

use super::{check_bit_for_bit, lower_and_write_everything, parameter, reparse};
use hairmath::real::{trace_with, ArgType, Real, ResultType, Signature, Traced};
use hairmath::shader::lower;

/// `(colour: vec3<f32>, s: f32, t: f32) -> vec3<f32>`, traced from `body`.
fn colour_graph(body: impl FnOnce(&[Traced]) -> Vec<Traced>) -> hairmath::real::Graph {
    let signature = Signature {
        parameters: vec![
            parameter("colour", ArgType::Vec3),
            parameter("s", ArgType::Scalar),
            parameter("t", ArgType::Scalar),
        ],
        result: ResultType::Vec3,
    };
    trace_with(signature, body)
}

/// The body of the written function `name`.
fn body_of<'a>(wgsl: &'a str, name: &str) -> &'a str {
    let start = wgsl
        .find(&format!("fn {name}("))
        .unwrap_or_else(|| panic!("{name}\n{wgsl}"));
    let end = wgsl[start..].find("\n}").expect("the function's end") + start;
    &wgsl[start..end]
}

const ROWS: [[f32; 5]; 4] = [
    [0.25, 0.5, 2.0, 1.5, -0.75],
    [-1.0, 0.0, -0.0, 0.3, 0.3],
    [f32::MAX, 1e-30, -3.0, -2.0, 4.0],
    [0.9, 0.1, 0.5, 0.0, 1.0],
];

#[test]
fn channel_by_channel_arithmetic_is_one_vector_expression() {
    let graph = colour_graph(|x| {
        let (s, t) = (x[3], x[4]);
        // Per channel: max(s * exp(-c * t) + s, 0), as `[R; 3].map` writes it.
        (0..3)
            .map(|c| (s * (-x[c] * t).exp() + s).max(Traced::c(0.0)))
            .collect()
    });
    let module = lower_and_write_everything("tint", &graph);
    let wgsl = module.wgsl().unwrap();
    reparse(&wgsl).unwrap();
    let body = body_of(&wgsl, "tint");
    assert!(
        body.contains("return max(((s * exp((-(colour) * t))) + vec3(s)), vec3(0f));"),
        "{body}"
    );
    let rows: Vec<Vec<f32>> = ROWS.iter().map(|r| r.to_vec()).collect();
    check_bit_for_bit("tint", &graph, &rows);
}

#[test]
fn per_channel_conditions_become_a_vector_comparison() {
    let graph = colour_graph(|x| {
        let (s, t) = (x[3], x[4]);
        (0..3)
            .map(|c| Traced::select(x[c].lt(s), x[c] * t, Traced::c(1.0)))
            .collect()
    });
    let module = lower_and_write_everything("threshold", &graph);
    let body = body_of(&module.wgsl().unwrap(), "threshold").to_string();
    assert!(
        body.contains("select(vec3(1f), (colour * t), (colour < vec3(s)))"),
        "{body}"
    );
    let rows: Vec<Vec<f32>> = ROWS.iter().map(|r| r.to_vec()).collect();
    check_bit_for_bit("threshold", &graph, &rows);
}

#[test]
fn channels_computed_differently_are_composed_where_they_differ() {
    let graph = colour_graph(|x| {
        let (s, t) = (x[3], x[4]);
        // The same product of different factors: s for red, t for green, s t for blue.
        vec![x[0] * s + t, x[1] * t + t, x[2] * (s * t) + t]
    });
    let module = lower_and_write_everything("mixed", &graph);
    let body = body_of(&module.wgsl().unwrap(), "mixed").to_string();
    assert!(body.contains("((colour * vec3<f32>(s, t, "), "{body}");
    assert!(body.contains(")) + vec3(t));"), "{body}");
    let rows: Vec<Vec<f32>> = ROWS.iter().map(|r| r.to_vec()).collect();
    check_bit_for_bit("mixed", &graph, &rows);
}

#[test]
fn the_models_colours_are_vectors() {
    let entry = hairmath::registry::find_model("kajiya-kay").unwrap();
    let shader = entry.shader.as_ref().unwrap();
    let kajiya_kay = (shader.trace)(&entry.example_values(), &[]).unwrap();
    let wgsl = lower(&kajiya_kay, "kajiya_kay").unwrap().wgsl().unwrap();
    let body = body_of(&wgsl, "kajiya_kay");
    assert!(
        body.contains("return ((uniforms.kd * cos_theta_i) + (uniforms.ks * "),
        "{body}"
    );
    for channel in ["uniforms.kd.", "uniforms.ks."] {
        assert!(
            !body.contains(channel),
            "no channel is written alone\n{body}"
        );
    }
}
