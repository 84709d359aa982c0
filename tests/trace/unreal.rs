//! Trace tests of the Unreal models (`hairmath::models::{Karis, KarisRefit}`) and of the
//! cos-phi forms of Karis' closed forms they evaluate.

use super::*;
use hairmath::absorption::Absorption;
use hairmath::models::{
    d_karis_of_cos, h_tt_karis_of_cos, ExpCosCoefficients, HTtCoefficients, Karis, KarisHair,
    KarisRefit, KarisUniforms, KarisVariant, UnrealRoughness, KARIS_D_TRT_TABLE, KARIS_D_TT_TABLE,
    KARIS_H_TT_TABLE, REFIT_D_TRT_TABLE, REFIT_D_TT_TABLE, REFIT_H_TT_TABLE,
};
use hairmath::params::AzimuthalRoughness;

/// `a = 1/eta'`: 0 (grazing), 1/1.55, and just below 1.
const INVERSE_ETA_PRIME: Arg = arg(0.0, 0.9999, &[0.0, 1.0 / 1.55, 0.9999]);

/// (sigma_a, Roughness, beta_n of the colour): brown hair at its mapped Roughness, white below
/// UE's Roughness clamp, very dark and roughest, sigma_a beyond the 1e30 clamp, blonde at a
/// high beta_n.
const UNREAL_MATERIALS: &[([f64; 3], f64, f64)] = &[
    ([0.545, 0.906, 1.781], 0.5276, 0.3),
    ([0.0; 3], 1e-3, 0.3),
    ([10.0, 100.0, 1e4], 1.0, 0.3),
    ([1e300, 0.0, 1.0], 0.2, 0.3),
    ([0.05, 0.1, 0.3], 0.35, 0.9),
];

fn unreal_model<V: KarisVariant>(k: usize) -> KarisHair<f64, V> {
    let (sigma_a, roughness, beta_n) = UNREAL_MATERIALS[k];
    KarisHair::new(
        Absorption::new(sigma_a).unwrap(),
        AzimuthalRoughness::new(beta_n).unwrap(),
        UnrealRoughness::new(roughness).unwrap(),
    )
}

/// The uniforms of each material with each hard pair, then random materials and pairs.
fn unreal_rows<V: KarisVariant>() -> Vec<Vec<f32>> {
    material_rows(UNREAL_MATERIALS.len(), |k| {
        unreal_model::<V>(k).uniforms().to_values()
    })
}

/// Traces eval and eval_lobes of the variant `V` through the model contract and checks them
/// against the `f32` model, and the library's shader entry point.
fn check_unreal<V: KarisVariant>(label: &str) {
    let model = unreal_model::<V>(0);
    let graph = trace_eval(&model);
    let wgsl = graph.to_wgsl("karis_eval");
    assert!(
        wgsl.contains("struct KarisUniforms {")
            && wgsl.contains(
                "fn karis_eval(uniforms: KarisUniforms, wi: vec3<f32>, wo: vec3<f32>) -> vec3<f32>"
            )
            && wgsl.contains("uniforms.log_color.z")
            && wgsl.contains("uniforms.width_r"),
        "{wgsl}"
    );
    let width = KarisUniforms::<f64>::fields()
        .iter()
        .map(|f| f.width)
        .sum::<usize>();
    check(
        &format!("{label}::eval"),
        &unreal_rows::<V>(),
        &graph,
        |row| {
            let m = model.with_uniforms::<f32>(UniformBlock::from_values(&row[..width]));
            m.eval(&query_of(&row[width..])).to_vec()
        },
    );
    let q = [0.0, 1.0, 0.0, 0.0, 0.6, 0.8];
    let cpu = model.instantiate::<f32>().eval(&query_of(&q));
    assert_eq!(graph.eval_f32(&traced_inputs(&model, &q)), cpu.to_vec());
    model_case!(
        format!("{label}::eval_lobes"),
        model,
        query_parameters(false),
        ResultType::Scalars,
        unreal_rows::<V>(),
        |m, x| {
            let flags = [
                m.lobe_names().len() as f64,
                f64::from(u8::from(m.uses_offset())),
            ];
            [m.eval_lobes(&query_of(x)).concat(), consts(&flags)].concat()
        }
    );
}

traced_tests! {
    karis_of_cos ["d_karis_of_cos", "h_tt_karis_of_cos"] {
        for (name, table) in [
            ("published TT", &KARIS_D_TT_TABLE),
            ("published TRT", &KARIS_D_TRT_TABLE),
            ("refit TT", &REFIT_D_TT_TABLE),
            ("refit TRT", &REFIT_D_TRT_TABLE),
        ] {
            case!(format!("d_karis_of_cos ({name})"), scalars(&[SIN]), |x| {
                vec![d_karis_of_cos(x[0], ExpCosCoefficients::named(table))]
            });
        }
        for (name, table) in [("published", &KARIS_H_TT_TABLE), ("refit", &REFIT_H_TT_TABLE)] {
            case!(format!("h_tt_karis_of_cos ({name})"), scalars(&[INVERSE_ETA_PRIME, SIN, UNIT]), |x| {
                vec![h_tt_karis_of_cos(x[0], x[1], x[2], HTtCoefficients::named(table))]
            });
        }
    }
    unreal_karis [
        "KarisHair::eval", "KarisHair::eval_lobes", "KarisHair::lobe_names",
        "KarisHair::with_uniforms"
    ] {
        // Both variants: the constants differ, the structure is the same.
        let _: (Karis<f64>, KarisRefit<f64>) = (unreal_model(0), unreal_model(0));
        check_unreal::<hairmath::models::Published>("Karis");
        check_unreal::<hairmath::models::Refitted>("KarisRefit");
    }
}
