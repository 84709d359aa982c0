//! Trace tests of the classic real-time models (`hairmath::models`): Kajiya-Kay, its two-cone
//! TressFX form and Scheuermann's shader, each through the model contract (the uniforms as a
//! named struct, then wi and wo), on random inputs of every domain (weights 0 and 1e6,
//! exponents from 1e-3 to 1e6, shifts up to +-pi and tangent shifts up to 1e6, the textures at
//! 0 and 1) and the direction pairs of `Gen::pair` (grazing, along the tangent, wi = +-wo,
//! phi = 0 and pi).

use super::*;
use hairmath::models::{
    KajiyaKay, KajiyaKayParams, Scheuermann, ScheuermannParams, StrandLobe, TressFx, TressFxCone,
    TressFxParams,
};

const WEIGHT: Arg = arg(0.0, 2.0, &[0.0, 1.0, 1e6]);
const EXPONENT: Arg = arg(1e-3, 1e6, &[1e-3, 0.49, 1.0, 1e6]);
const TANGENT_SHIFT: Arg = arg(-3.0, 3.0, &[0.0, -1.0, 1.5, 1e6, -1e6]);

impl Gen {
    fn weights(&mut self) -> [f64; 3] {
        [self.pick(&WEIGHT), self.pick(&WEIGHT), self.pick(&WEIGHT)]
    }
    /// The uniforms of a random Kajiya-Kay model.
    fn kajiya_kay(&mut self) -> Vec<f64> {
        let params = KajiyaKayParams {
            kd: self.weights(),
            ks: self.weights(),
            exponent: self.pick(&EXPONENT),
        };
        KajiyaKay::new(&params).unwrap().uniforms().to_values()
    }
    fn cone(&mut self) -> TressFxCone {
        TressFxCone {
            weight: self.weights(),
            exponent: self.pick(&EXPONENT),
            shift: self.pick(&ANGLE),
        }
    }
    /// The uniforms of a random TressFX model.
    fn tressfx(&mut self) -> Vec<f64> {
        let params = TressFxParams {
            kd: self.weights(),
            primary: self.cone(),
            secondary: self.cone(),
        };
        TressFx::new(&params).unwrap().uniforms().to_values()
    }
    fn strand_lobe(&mut self) -> StrandLobe {
        StrandLobe {
            weight: self.weights(),
            exponent: self.pick(&EXPONENT),
            tangent_shift: self.pick(&TANGENT_SHIFT),
        }
    }
    /// The uniforms of a random Scheuermann model.
    fn scheuermann(&mut self) -> Vec<f64> {
        let params = ScheuermannParams {
            kd: self.weights(),
            primary: self.strand_lobe(),
            secondary: self.strand_lobe(),
            shift_texture: self.pick(&UNIT),
            noise_mask: self.pick(&UNIT),
        };
        Scheuermann::new(&params).unwrap().uniforms().to_values()
    }
}

/// The model's shader entry point (`trace_eval`: uniforms, wi, wo -> vec3) against its `f32`
/// instantiation on `inputs` (uniforms then wi, wo), and its WGSL signature.
fn check_eval<M: Model>(name: &str, model: &M, inputs: &[Vec<f32>]) {
    let graph = trace_eval(model);
    let uniforms = <M::Uniforms<f64> as UniformBlock<f64>>::NAME;
    let wgsl = graph.to_wgsl("eval");
    assert!(
        wgsl.contains(&format!("struct {uniforms} {{"))
            && wgsl.contains(&format!(
                "fn eval(uniforms: {uniforms}, wi: vec3<f32>, wo: vec3<f32>) -> vec3<f32>"
            )),
        "{wgsl}"
    );
    let width = model.uniforms().to_values().len();
    check(name, inputs, &graph, |row| {
        let m = model.with_uniforms::<f32>(UniformBlock::from_values(&row[..width]));
        m.eval(&query_of(&row[width..])).to_vec()
    });
}

traced_tests! {
    kajiya_kay_eval [
        "KajiyaKay::eval", "KajiyaKay::eval_lobes", "KajiyaKay::lobe_names",
        "KajiyaKay::with_uniforms"
    ] {
        let model = KajiyaKay::new(&KajiyaKayParams { kd: [0.1; 3], ks: [0.5; 3], exponent: 11.8 }).unwrap();
        let inputs = rows(|g| [g.kajiya_kay(), g.pair()].concat());
        check_eval("KajiyaKay::eval", &model, &inputs);
        model_case!("KajiyaKay::eval_lobes", model, query_parameters(false), ResultType::Scalars, inputs, |m, x| {
            let q = query_of(x);
            [m.eval_lobes(&q).concat(), consts(&[m.lobe_names().len() as f64])].concat()
        });
    }
    tressfx_eval [
        "TressFx::eval", "TressFx::eval_lobes", "TressFx::lobe_names", "TressFx::with_uniforms"
    ] {
        let params = TressFxParams {
            kd: [0.05, 0.03, 0.02],
            primary: TressFxCone { weight: [0.3; 3], exponent: 12.0, shift: 0.07 },
            secondary: TressFxCone { weight: [0.2, 0.1, 0.05], exponent: 3.0, shift: 0.14 },
        };
        let model = TressFx::new(&params).unwrap();
        let inputs = rows(|g| [g.tressfx(), g.pair()].concat());
        check_eval("TressFx::eval", &model, &inputs);
        model_case!("TressFx::eval_lobes", model, query_parameters(false), ResultType::Scalars, inputs, |m, x| {
            let q = query_of(x);
            [m.eval_lobes(&q).concat(), consts(&[m.lobe_names().len() as f64])].concat()
        });
    }
    scheuermann_eval [
        "Scheuermann::eval", "Scheuermann::eval_lobes", "Scheuermann::lobe_names",
        "Scheuermann::with_uniforms"
    ] {
        let model = Scheuermann::new(&ScheuermannParams::BLOG).unwrap();
        let inputs = rows(|g| [g.scheuermann(), g.pair()].concat());
        check_eval("Scheuermann::eval", &model, &inputs);
        model_case!("Scheuermann::eval_lobes", model, query_parameters(false), ResultType::Scalars, inputs, |m, x| {
            let q = query_of(x);
            [m.eval_lobes(&q).concat(), consts(&[m.lobe_names().len() as f64])].concat()
        });
    }
}
