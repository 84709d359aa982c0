//! A renderer author's test file: checking one's own hair BSDF with `hairmath::testing`.
//!
//! The renderer here is pbrt-like: its `f(wo, wi)` takes pbrt's directions and returns S
//! divided by |cos theta_i| ([`Convention::Pbrt`]); it stands in for the code under test and
//! is written, for the example, on top of hairmath's f32 model. In a renderer's crate the
//! checks in `main` are `#[test]` functions and `my_hair_f` calls the renderer.
//!
//! Run with `cargo run --release --example check_my_bsdf`; each check prints its report.

use hairmath::bcsdf::{Bcsdf, ChiangHair, Model, Query};
use hairmath::geometry::V3;
use hairmath::params::HairParams;
use hairmath::testing::{
    compare_with_model, eval_values, from_eval, furnace, test_queries, Convention, FurnaceSettings,
    ValueSettings,
};

/// The renderer's hair BSDF in pbrt's convention: `f(wo, wi)` at offset `h`, `f = S / |cos
/// theta_i|` to the fibre's normal.
struct MyHair(ChiangHair<f32>);

impl MyHair {
    fn new(params: &HairParams) -> Self {
        MyHair(ChiangHair::<f64>::new(params).instantiate::<f32>())
    }

    fn f(&self, wo: [f64; 3], wi: [f64; 3], h: f64) -> [f64; 3] {
        let v = |w: [f64; 3]| V3::new(w[0] as f32, w[1] as f32, w[2] as f32);
        let s = self.0.eval(&Query::new(v(wi), v(wo), h as f32));
        let cos = wi[2].abs();
        s.map(|s| {
            if cos > 0.0 {
                f64::from(s) / cos
            } else {
                f64::from(s)
            }
        })
    }

    /// The renderer's f at a hairmath query, as hairmath's S: the convention converts the
    /// directions going in and the cosine factor coming out.
    fn s(&self, query: &Query<f64>) -> [f64; 3] {
        let c = Convention::Pbrt.from_hairmath(query);
        let f = self.f(c.wo.to_array(), c.wi.to_array(), c.h.unwrap_or(0.0));
        Convention::Pbrt.s_of_f(f, query)
    }
}

fn main() {
    // 1. Against hairmath's f64 reference on the hard cases and 4,000 quasi-random queries.
    let params = HairParams::default();
    let reference = ChiangHair::<f64>::new(&params);
    let mine = MyHair::new(&params);
    let report = compare_with_model(&reference, &test_queries(4000), |q| mine.s(q), 3);
    println!("against the reference: {report}");
    assert!(report.passes(3e-4), "{report}");

    // 2. The white furnace: with no absorption the renderer's S integrates to 1.
    let white = MyHair::new(&HairParams {
        sigma_a: hairmath::absorption::Absorption::NONE,
        ..params
    });
    let energy = furnace(
        &from_eval(|q| white.s(q), true),
        &FurnaceSettings::default(),
    );
    println!("{energy}");
    assert!(energy.passes(1e-4), "{energy}");

    // 3. Finite and non-negative over the whole parameter domain (hard cases, then proptest).
    let values = eval_values(
        |p: &HairParams| {
            let hair = MyHair::new(p);
            from_eval(move |q| hair.s(q), true)
        },
        &ValueSettings {
            cases: 500,
            seed: 1,
        },
    );
    println!("{values}");
    assert!(values.passes(), "{values}");
}
