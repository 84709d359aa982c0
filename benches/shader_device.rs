//! The cost of every model's emitted shader on a WebGPU device (Mesa's llvmpipe where there is
//! no GPU): one compute dispatch of the model's `hair_bcsdf` over 2^20 rows of deterministic
//! direction pairs (and offsets h for the near field), at the example values of
//! `hairmath::shader::example_shaders`, timed from submit to completion (no readback).
//! Criterion's time is per dispatch; divided by 2^20 it is the time per evaluation. Compare
//! models by the ratios of one run to Kajiya-Kay's: software rasterisers and these machines are
//! noisy, and llvmpipe's costs are not a GPU's.
//!
//! Run: `cargo bench --bench shader_device`.

#[path = "../tests/shader/gpu.rs"]
#[allow(dead_code)]
mod gpu;

use criterion::{criterion_group, Criterion, Throughput};
use hairmath::diagnostics::DirectionPairs;
use hairmath::shader::example_shaders;
use std::time::Duration;

/// Rows per dispatch.
const ROWS: usize = 1 << 20;

/// `ROWS` rows of `stride` f32: the pairs of a Kronecker set, then h in (-1, 1).
fn rows(stride: usize) -> Vec<f32> {
    let pairs = DirectionPairs::kronecker(ROWS);
    pairs
        .pairs()
        .iter()
        .enumerate()
        .flat_map(|(k, (wi, wo))| {
            let mut row = vec![
                wi.x as f32,
                wi.y as f32,
                wi.z as f32,
                wo.x as f32,
                wo.y as f32,
                wo.z as f32,
            ];
            row.resize(stride, ((k as f64 * 0.618_034).fract() * 2.0 - 1.0) as f32);
            row
        })
        .collect()
}

fn device_cost(c: &mut Criterion) {
    let Some(device) = gpu::device() else {
        eprintln!("no WebGPU adapter: install mesa-vulkan-drivers");
        return;
    };
    let mut group = c.benchmark_group("shader_device");
    group.sample_size(10);
    group.warm_up_time(Duration::from_millis(500));
    group.measurement_time(Duration::from_secs(4));
    group.throughput(Throughput::Elements(ROWS as u64));
    for shader in example_shaders().expect("every model emits") {
        let compute = shader.compute().expect("the compute form");
        let stride = compute.stride().expect("a stride");
        let wgsl = compute.wgsl().expect("WGSL");
        let queries = rows(stride);
        let textures = gpu::textures_of(&shader.module);
        group.bench_function(shader.model, |b| {
            b.iter_custom(|iters| {
                let per_eval = device
                    .time_per_eval(
                        &wgsl,
                        "hair_main",
                        &queries,
                        stride,
                        &textures,
                        iters as usize,
                    )
                    .expect("the dispatch runs");
                Duration::from_secs_f64(per_eval * ROWS as f64 * iters as f64)
            })
        });
    }
    group.finish();
}

criterion_group!(benches, device_cost);

fn main() {
    benches();
    Criterion::default().configure_from_args().final_summary();
}
