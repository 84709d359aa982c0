//! Trace tests of the Frostbite models (`hairmath::models::{Frostbite, FrostbiteRefit}`) and of
//! their TRT distribution: the traced graph interpreted in `f32` against the `f32` model bit
//! for bit, over the uniforms of several hairs and the hard direction pairs, and the one fetch
//! of the TT table.

use super::*;
use hairmath::models::{
    d_trt_frostbite, ExpCosCoefficients, Frostbite, FrostbiteHair, FrostbiteRefit,
    FrostbiteUniforms, FrostbiteVariant, Published, Refitted,
};

/// (beta_m, beta_n, alpha, eta, sigma_a): brown, smooth and clear with the index near 1,
/// roughest and opaque with a large tilt, below the table's beta_n with mixed absorption,
/// sigma_a beyond the model's 1e30 clamp, the smallest beta_m (the width floor).
const FROSTBITE_MATERIALS: &[(f64, f64, f64, f64, [f64; 3])] = &[
    (0.3, 0.3, 0.0349, 1.55, [0.545, 0.906, 1.781]),
    (0.0137, 0.01, 0.0, 1.0001, [0.0; 3]),
    (1.0, 1.0, -1.5, 2.4, [10.0; 3]),
    (0.1, 0.05, 1.5, 1.55, [0.0, 1.0, 10.0]),
    (0.6, 0.9, 0.0349, 3.0, [1e300, 0.0, 1e4]),
    (1e-9, 0.6, 0.1, 1.55, [0.2, 0.4, 0.8]),
];

fn frostbite_model<V: FrostbiteVariant>(k: usize) -> FrostbiteHair<f64, V> {
    let (beta_m, beta_n, alpha, eta, sigma_a) = FROSTBITE_MATERIALS[k];
    let values = HairValues {
        beta_m,
        beta_n,
        alpha,
        eta,
        sigma_a,
    };
    FrostbiteHair::new(&HairParams::try_from(values).unwrap())
}

/// The uniforms of each material with each hard pair, then random materials and pairs.
fn frostbite_rows<V: FrostbiteVariant>() -> Vec<Vec<f32>> {
    material_rows(FROSTBITE_MATERIALS.len(), |k| {
        frostbite_model::<V>(k).uniforms().to_values()
    })
}

/// Traces eval and eval_lobes of the variant `V` through the model contract and checks them
/// against the `f32` model; the library's shader entry point; the TT table's single fetch.
fn check_frostbite<V: FrostbiteVariant>(label: &str) {
    let model = frostbite_model::<V>(0);
    let graph = trace_eval(&model);
    // One fetch of the two-channel (a, b) texture: one texture sample.
    assert_eq!(
        (graph.count_fetches(), graph.count_texture_samples()),
        (1, 1)
    );
    assert_eq!(graph.tables().len(), 1);
    assert!(std::sync::Arc::ptr_eq(
        &graph.tables()[0],
        model.tt_table().arc()
    ));
    let wgsl = graph.to_wgsl("frostbite_eval");
    for text in [
        "struct FrostbiteUniforms {",
        "fn frostbite_eval(uniforms: FrostbiteUniforms, wi: vec3<f32>, wo: vec3<f32>) -> vec3<f32>",
        "var lut0_frostbite_tt: texture_2d<f32>;",
        "uniforms.trt_scale",
        "uniforms.beta_n",
        "uniforms.sigma_a.z",
    ] {
        assert!(wgsl.contains(text), "missing {text:?} in\n{wgsl}");
    }
    let width = FrostbiteUniforms::<f64>::fields()
        .iter()
        .map(|f| f.width)
        .sum::<usize>();
    let rows = frostbite_rows::<V>();
    assert!(rows.len() >= 200, "{} rows", rows.len());
    check(&format!("{label}::eval"), &rows, &graph, |row| {
        let m = model.with_uniforms::<f32>(UniformBlock::from_values(&row[..width]));
        m.eval(&query_of(&row[width..])).to_vec()
    });
    let q = [0.0, 1.0, 0.0, 0.0, 0.6, 0.8];
    let cpu = model.instantiate::<f32>().eval(&query_of(&q));
    assert_eq!(graph.eval_f32(&traced_inputs(&model, &q)), cpu.to_vec());
    model_case!(
        format!("{label}::eval_lobes"),
        model,
        query_parameters(false),
        ResultType::Scalars,
        frostbite_rows::<V>(),
        |m, x| {
            let flags = [
                m.lobe_names().len() as f64,
                f64::from(u8::from(m.uses_offset())),
            ];
            [m.eval_lobes(&query_of(x)).concat(), consts(&flags)].concat()
        }
    );
}

/// `s_r` in [0, 1]: 0 (beta_n = 1), 0.15 (beta_n = 0.9), 1 (beta_n <= 1/3).
const TRT_SCALE: Arg = arg(0.0, 1.0, &[0.0, 0.15, 1.0]);

traced_tests! {
    frostbite_d_trt ["d_trt_frostbite"] {
        for (name, c) in [
            ("published", ExpCosCoefficients::PUBLISHED_D_TRT),
            ("refit", ExpCosCoefficients::REFIT_D_TRT),
        ] {
            case!(format!("d_trt_frostbite ({name})"), scalars(&[SIN, TRT_SCALE]), |x| {
                vec![d_trt_frostbite(x[0], x[1], c.to_real())]
            });
        }
    }
    frostbite_models [
        "FrostbiteHair::eval", "FrostbiteHair::eval_lobes", "FrostbiteHair::lobe_names",
        "FrostbiteHair::with_uniforms"
    ] {
        // Both variants: the offsets differ, the structure is the same.
        let _: (Frostbite<f64>, FrostbiteRefit<f64>) = (frostbite_model(0), frostbite_model(0));
        check_frostbite::<Published>("Frostbite");
        check_frostbite::<Refitted>("FrostbiteRefit");
    }
}
