//! Throughput of every real-time model of the registry (`hairmath::registry::MODELS` entries
//! with an approximation) beside the reference it approximates, Chiang et al. 2016's far field
//! with 64 nodes in h (the comparison's reference) and with 8: `f32` scalar and the SIMD batch
//! (`hairmath::bcsdf::HostBatch`, the lanes of the host's widest instruction set, for every
//! model and the far field alike).
//!
//! Each model is built from its mapped inputs for dark brown hair (eumelanin 3) at beta_m =
//! beta_n = 0.3, alpha = 2 degrees, eta = 1.55 (the README's table). Every benchmark processes
//! the same 1024 deterministic direction pairs per iteration (`Throughput::Elements(1024)`):
//! criterion's time divided by 1024 is the cost of one evaluation. The scalar path calls the model through a
//! `dyn Bcsdf<f32>` as the registry builds it (one indirect call per evaluation, for every model
//! alike).
//!
//! Run: `cargo bench --bench models` (or `-- batch` for the batches only). Compare models by
//! the ratios of one run: these machines are noisy.

use std::hint::black_box;

use criterion::{criterion_group, BenchmarkId, Criterion, Throughput};
use hairmath::bcsdf::{BatchEval, Bcsdf, ChiangFarField, FarFieldRule, HostBatch, Model, Query};
use hairmath::diagnostics::DirectionPairs;
use hairmath::fit::ComparisonSettings;
use hairmath::geometry::V3;
use hairmath::params::HairParams;
use hairmath::registry::MODELS;

const N: usize = 1024;

struct Inputs {
    wi: Vec<[f32; 3]>,
    wo: Vec<[f32; 3]>,
    h: Vec<f32>,
    queries: Vec<Query<f32>>,
}

fn inputs() -> Inputs {
    let pairs = DirectionPairs::kronecker(N);
    let f32s = |w: V3<f64>| [w.x as f32, w.y as f32, w.z as f32];
    let wi: Vec<[f32; 3]> = pairs.pairs().iter().map(|p| f32s(p.0)).collect();
    let wo: Vec<[f32; 3]> = pairs.pairs().iter().map(|p| f32s(p.1)).collect();
    let v3 = |w: [f32; 3]| V3::new(w[0], w[1], w[2]);
    let queries = wi
        .iter()
        .zip(&wo)
        .map(|(&a, &b)| Query::far(v3(a), v3(b)))
        .collect();
    Inputs {
        wi,
        wo,
        h: vec![0.0; N],
        queries,
    }
}

fn dark_brown() -> HairParams {
    ComparisonSettings::dark_brown().hairs[0]
        .params()
        .expect("the README's hair is valid")
}

fn scalar(c: &mut Criterion, name: &str, model: &dyn Bcsdf<f32>, inputs: &Inputs) {
    let mut group = c.benchmark_group("models/f32");
    group.throughput(Throughput::Elements(N as u64));
    group.bench_function(BenchmarkId::from_parameter(name), |b| {
        b.iter(|| {
            let mut sum = 0.0f32;
            for q in &inputs.queries {
                sum += model.eval(black_box(q))[0];
            }
            sum
        })
    });
    group.finish();
}

fn batch(c: &mut Criterion, name: &str, model: &dyn BatchEval, inputs: &Inputs) {
    let mut out = vec![[0.0f32; 3]; N];
    let mut group = c.benchmark_group("models/batch");
    group.throughput(Throughput::Elements(N as u64));
    group.bench_function(BenchmarkId::from_parameter(name), |b| {
        b.iter(|| {
            model
                .eval_batch_lanes(black_box(&inputs.wi), &inputs.wo, &inputs.h, &mut out)
                .expect("equal lengths");
            out[0][0]
        })
    });
    group.finish();
}

fn models(c: &mut Criterion) {
    let inputs = inputs();
    let hair = dark_brown();
    for nodes in [64, 8] {
        let far = ChiangFarField::<f64>::with_rule(
            &hair,
            &FarFieldRule::gauss_legendre(nodes).expect("a valid node count"),
        );
        let name = format!("chiang-far-{nodes}");
        scalar(c, &name, &far.instantiate::<f32>(), &inputs);
        batch(c, &name, &HostBatch::new(&far), &inputs);
    }
    for entry in MODELS {
        let Some(approximation) = entry.approximation else {
            continue;
        };
        let values = (approximation.mapped_inputs)(&hair);
        let f32_model = (approximation.build_f32)(&values).expect("mapped inputs are valid");
        let batch_model = (approximation.build_batch)(&values).expect("mapped inputs are valid");
        scalar(c, entry.name, f32_model.as_ref(), &inputs);
        batch(c, entry.name, batch_model.as_ref(), &inputs);
    }
}

criterion_group!(benches, models);

fn main() {
    benches();
    Criterion::default().configure_from_args().final_summary();
}
