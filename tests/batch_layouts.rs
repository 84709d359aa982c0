//! The structure-of-arrays batch (`eval_batch_soa`) against the array-of-structures one
//! (`eval_batch`) on arbitrary inputs, NaN, infinities and non-unit directions included: it
//! never panics, refuses exactly what `eval_batch` refuses (the same error, the same sample),
//! and otherwise gives the same values bit for bit. And the batch on each instruction set the
//! CPU runs (`HostBatch`) against `eval_batch` on the same inputs: the same errors, values
//! within the single-precision bound, its own two layouts bit for bit.

use hairmath::bcsdf::{
    eval_batch, eval_batch_soa, BatchReal, ChiangHair, DirectionSlices, HostBatch, InstructionSet,
    Model, RgbSlices,
};
use hairmath::params::HairParams;
use proptest::prelude::*;

/// A component: mostly those of unit directions, sometimes anything an `f32` can be.
fn component() -> impl Strategy<Value = f32> {
    prop_oneof![
        4 => -1.0_f32..=1.0,
        1 => any::<f32>(),
        1 => Just(f32::NAN),
    ]
}

/// A direction, normalised unless `raw`.
fn direction() -> impl Strategy<Value = [f32; 3]> {
    ([component(), component(), component()], any::<bool>()).prop_map(|(w, raw)| {
        let length = (w[0] * w[0] + w[1] * w[1] + w[2] * w[2]).sqrt();
        if raw || !(length > 1e-3 && length.is_finite()) {
            w
        } else {
            w.map(|c| c / length)
        }
    })
}

fn column(d: &[[f32; 3]], c: usize) -> Vec<f32> {
    d.iter().map(|w| w[c]).collect()
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(300))]

    #[test]
    fn both_layouts_agree(
        samples in prop::collection::vec((direction(), direction(), component()), 0..40),
    ) {
        let lanes = ChiangHair::<f64>::new(&HairParams::default()).instantiate::<BatchReal>();
        let wi: Vec<[f32; 3]> = samples.iter().map(|s| s.0).collect();
        let wo: Vec<[f32; 3]> = samples.iter().map(|s| s.1).collect();
        let h: Vec<f32> = samples.iter().map(|s| s.2).collect();
        let n = samples.len();
        let mut aos = vec![[0.0_f32; 3]; n];
        let expected = eval_batch(&lanes, &wi, &wo, &h, &mut aos);
        let (wix, wiy, wiz) = (column(&wi, 0), column(&wi, 1), column(&wi, 2));
        let (wox, woy, woz) = (column(&wo, 0), column(&wo, 1), column(&wo, 2));
        let (mut r, mut g, mut b) = (vec![0.0; n], vec![0.0; n], vec![0.0; n]);
        let got = eval_batch_soa(
            &lanes,
            DirectionSlices { x: &wix, y: &wiy, z: &wiz },
            DirectionSlices { x: &wox, y: &woy, z: &woz },
            &h,
            RgbSlices { r: &mut r, g: &mut g, b: &mut b },
        );
        prop_assert_eq!(format!("{got:?}"), format!("{expected:?}"));
        if got.is_ok() {
            for k in 0..n {
                prop_assert_eq!([r[k], g[k], b[k]].map(f32::to_bits), aos[k].map(f32::to_bits));
            }
        }
    }

    #[test]
    fn every_instruction_set_agrees_with_eval_batch(
        samples in prop::collection::vec((direction(), direction(), component()), 0..40),
    ) {
        let model = ChiangHair::<f64>::new(&HairParams::default());
        let lanes = model.instantiate::<BatchReal>();
        let wi: Vec<[f32; 3]> = samples.iter().map(|s| s.0).collect();
        let wo: Vec<[f32; 3]> = samples.iter().map(|s| s.1).collect();
        let h: Vec<f32> = samples.iter().map(|s| s.2).collect();
        let n = samples.len();
        let mut want = vec![[0.0_f32; 3]; n];
        let expected = eval_batch(&lanes, &wi, &wo, &h, &mut want);
        let (wix, wiy, wiz) = (column(&wi, 0), column(&wi, 1), column(&wi, 2));
        let (wox, woy, woz) = (column(&wo, 0), column(&wo, 1), column(&wo, 2));
        for set in InstructionSet::ALL.into_iter().filter(|s| s.is_supported()) {
            let batch = HostBatch::on(set, &model);
            let mut got = vec![[0.0_f32; 3]; n];
            let result = batch.eval(&wi, &wo, &h, &mut got);
            prop_assert_eq!(format!("{result:?}"), format!("{expected:?}"));
            let (mut r, mut g, mut b) = (vec![0.0; n], vec![0.0; n], vec![0.0; n]);
            let soa = batch.eval_soa(
                DirectionSlices { x: &wix, y: &wiy, z: &wiz },
                DirectionSlices { x: &wox, y: &woy, z: &woz },
                &h,
                RgbSlices { r: &mut r, g: &mut g, b: &mut b },
            );
            prop_assert_eq!(format!("{soa:?}"), format!("{expected:?}"));
            if result.is_err() {
                continue;
            }
            for k in 0..n {
                prop_assert_eq!([r[k], g[k], b[k]].map(f32::to_bits), got[k].map(f32::to_bits));
                for (x, y) in got[k].iter().zip(want[k]) {
                    prop_assert!(x.is_finite() && *x >= 0.0, "{set:?}: {x}");
                    prop_assert!(
                        (x - y).abs() <= 2.5e-5 * (y.abs() + 1e-6),
                        "{set:?}, sample {k}: {x} against {y}"
                    );
                }
            }
        }
    }
}
