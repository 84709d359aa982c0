//! The traced graphs keep the structure of the Rust code: marked functions are shader
//! functions called where the Rust code calls them, marked loops stay loops over constant
//! arrays, and baked uniforms are globals, while the flattened graph still computes the `f32`
//! code bit for bit (the other modules of this test check that for every model).

use hairmath::bcsdf::{trace_eval, trace_eval_with, ChiangFarField, ChiangHair, FarFieldRule};
use hairmath::bcsdf::{traced_inputs, Bcsdf, Model, Query, UniformsIn};
use hairmath::geometry::V3;
use hairmath::params::HairParams;
use hairmath::real::{CallKind, Graph, Node};

/// The number of call sites of the function named `name` in the top-level body and in every
/// function.
fn calls_of(graph: &Graph, name: &str) -> usize {
    let k = graph.functions().iter().position(|f| f.name == name);
    let Some(k) = k else { return 0 };
    let bodies = std::iter::once(graph.body()).chain(graph.functions().iter().map(|f| &f.body));
    bodies
        .flat_map(|b| &b.calls)
        .filter(|c| c.function == k as u32)
        .count()
}

#[test]
fn the_near_field_calls_one_lobe_function_for_its_four_lobes() {
    let graph = trace_eval(&ChiangHair::new(&HairParams::default()));
    let names: Vec<&str> = graph.functions().iter().map(|f| f.name.as_str()).collect();
    for expected in [
        "fibre_angles",
        "deon_lobe",
        "fibre_path",
        "attenuations",
        "exit_azimuths",
    ] {
        assert!(
            names.contains(&expected),
            "{expected} missing from {names:?}"
        );
    }
    assert!(!names.contains(&"deon_lobe_2"), "{names:?}");
    // R, TT and TRT at their tilts, and the residual (TRT's variance, no tilt).
    assert_eq!(calls_of(&graph, "deon_lobe"), 4);
    // One attenuation per colour channel.
    assert_eq!(calls_of(&graph, "attenuations"), 3);
}

#[test]
fn the_far_field_loops_over_its_nodes() {
    for nodes in [4, 5, 16] {
        let rule = FarFieldRule::gauss_legendre(nodes).unwrap();
        let model = ChiangFarField::with_rule(&HairParams::default(), &rule);
        let graph = trace_eval(&model);
        assert_eq!(graph.arrays().len(), 1);
        let array = &graph.arrays()[0];
        // One element per mirrored pair (h, -h), and the middle node of an odd rule.
        assert_eq!(array.info.array, "FAR_FIELD_OFFSET_PAIRS");
        assert_eq!(array.elements.len(), nodes.div_ceil(2));
        let expected: Vec<Vec<f32>> = rule
            .mirrored_pairs()
            .iter()
            .map(|&(h, w)| vec![h as f32, w as f32])
            .collect();
        assert_eq!(array.elements, expected);
        let loops: Vec<_> = graph
            .body()
            .calls
            .iter()
            .filter(|c| matches!(c.kind, CallKind::Loop { .. }))
            .collect();
        assert_eq!(loops.len(), 1, "one loop at the top level");
        let body = &graph.functions()[loops[0].function as usize];
        assert_eq!(body.name, "far_field_node_pair");
        // The loop body is traced once whatever the node count: its size does not grow.
        assert!(body.body.nodes.len() < graph.nodes().len() / 2);
    }
}

#[test]
fn baked_uniforms_are_globals_and_compute_what_the_argument_form_computes() {
    let model = ChiangHair::new(&HairParams::default());
    let baked = trace_eval_with(&model, UniformsIn::Constant);
    let argument = trace_eval(&model);
    assert_eq!(baked.input_count(), 7, "wi, wo and h only");
    assert!(baked
        .body()
        .nodes
        .iter()
        .any(|n| matches!(n, Node::Global(_))));
    let f32_model = model.instantiate::<f32>();
    for (wi, wo, h) in [
        (
            [0.3_f32, 0.4, (1.0_f32 - 0.25).sqrt()],
            [0.0, 1.0, 0.0],
            0.2_f32,
        ),
        ([-0.9, 0.1, 0.4], [0.6, -0.8, 0.0], -0.7),
    ] {
        let x = [wi[0], wi[1], wi[2], wo[0], wo[1], wo[2], h];
        let expected = f32_model.eval(&Query::new(
            V3::new(wi[0], wi[1], wi[2]),
            V3::new(wo[0], wo[1], wo[2]),
            h,
        ));
        let bits = |v: &[f32]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
        assert_eq!(bits(&baked.eval_f32(&x)), bits(&expected));
        assert_eq!(
            bits(&argument.eval_f32(&traced_inputs(&model, &x))),
            bits(&expected)
        );
    }
}
