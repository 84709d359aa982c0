//! The cost of every model's emitted shader on a WebGPU device (Mesa's llvmpipe where there is
//! no GPU): one compute dispatch of the model's `hair_bcsdf` over 2^20 rows of deterministic
//! direction pairs (and offsets h for the near field), at the example values of
//! `hairmath::shader::example_shaders`, timed from submit to completion (no readback).
//! Criterion's time is per dispatch; divided by 2^20 it is the time per evaluation. Compare
//! models by the ratios of one run to Kajiya-Kay's: software rasterisers and these machines are
//! noisy, and llvmpipe's costs are not a GPU's.
//!
//! The group `gerard_sh_device` times Gerard's SH shading (phase and transmittance bands as in
//! the README), per 2^20 rows as well (dispatched over fewer where a row is too wide for one
//! binding of 2^20).
//!
//! Run: `cargo bench --bench shader_device`.

use criterion::{criterion_group, Criterion, Throughput};
use hairmath::device::{textures_of, AdapterChoice, Device, GpuTexture};
use hairmath::diagnostics::DirectionPairs;
use hairmath::models::gerard_sh::SHADE_FUNCTION;
use hairmath::params::HairParams;
use hairmath::render::{
    gerard_graph, GerardConfig, GerardSources, PhaseAbsorption, RenderSettings,
};
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
    let device = match Device::new(AdapterChoice::HighPerformance) {
        Ok(device) => device,
        Err(e) => {
            eprintln!("no WebGPU adapter ({e}): install mesa-vulkan-drivers");
            return;
        }
    };
    eprintln!("timing on {}", device.describe());
    let device = &device;
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
        let textures = textures_of(&shader.module);
        group.bench_function(shader.model, |b| {
            b.iter_custom(|iters| dispatch_time(device, &wgsl, &queries, stride, &textures, iters))
        });
    }
    group.finish();
    gerard_cost(device);
}

/// Gerard's SH shading ([`hairmath::render::gerard_graph`]) in the configurations of the
/// README's table, over rows of (tangent, wo, light, light radiance, transmittance)
/// ([`gerard_rows`]), timed per 2^20 rows, so the times compare with Kajiya-Kay's above.
fn gerard_cost(device: &Device) {
    let mut c = Criterion::default().configure_from_args();
    let mut group = c.benchmark_group("gerard_sh_device");
    group.sample_size(10);
    group.warm_up_time(Duration::from_millis(500));
    group.measurement_time(Duration::from_secs(4));
    group.throughput(Throughput::Elements(ROWS as u64));
    let settings = RenderSettings::default();
    let source = GerardSources::mapped(&HairParams::default())
        .expect("the default hair maps")
        .published;
    let published = PhaseAbsorption::Published;
    let tabulated = PhaseAbsorption::Tabulated;
    for (phase_lmax, v_lmax, absorption) in [
        (1, 2, published),
        (2, 2, published),
        (3, 2, published),
        (4, 2, published),
        (1, 4, published),
        (4, 4, published),
        (1, 2, tabulated),
        (4, 4, tabulated),
    ] {
        let config = GerardConfig {
            phase_lmax,
            v_lmax,
            absorption,
            rgba8: false,
            bias: 0.0,
        };
        let graph = gerard_graph(&source, &config, &settings).expect("traced");
        let module = hairmath::shader::lower(&graph, SHADE_FUNCTION).expect("lowered");
        let stride = module.argument_scalars();
        let wgsl = module
            .with_compute_entry(stride)
            .and_then(|m| m.wgsl())
            .expect("WGSL");
        let queries = gerard_rows(stride);
        let textures = textures_of(&module);
        let name = format!("phase_l{phase_lmax}_v_l{v_lmax}_{}", absorption.name());
        group.bench_function(name, |b| {
            b.iter_custom(|iters| dispatch_time(device, &wgsl, &queries, stride, &textures, iters))
        });
    }
    group.finish();
}

/// The time of `iters` dispatches of `wgsl`'s `hair_main` over `queries` ([`ROWS`] rows).
fn dispatch_time(
    device: &Device,
    wgsl: &str,
    queries: &[f32],
    stride: usize,
    textures: &[GpuTexture],
    iters: u64,
) -> Duration {
    let per_eval = device
        .time_per_eval(wgsl, "hair_main", queries, stride, textures, iters as usize)
        .expect("the dispatch runs");
    Duration::from_secs_f64(per_eval * ROWS as f64 * iters as f64)
}

/// The largest storage-buffer binding wgpu allows by default (128 MiB).
const MAX_BINDING_BYTES: usize = 1 << 27;

/// Rows of Gerard's arguments: the pairs of a Kronecker set as tangent and viewer, the light
/// along their sum, a grey light, and a transmittance of mean 0.6. `ROWS` of them, or half as
/// many as often as the binding limit needs (the wider rows of V at l <= 4): the times are per
/// row, scaled to `ROWS` ([`dispatch_time`]), so they still compare.
fn gerard_rows(stride: usize) -> Vec<f32> {
    let mut rows = ROWS;
    while rows * stride * 4 > MAX_BINDING_BYTES {
        rows /= 2;
    }
    let pairs = DirectionPairs::kronecker(rows);
    pairs
        .pairs()
        .iter()
        .flat_map(|(t, wo)| {
            let sum = glam::DVec3::new(t.x + wo.x, t.y + wo.y, t.z + wo.z);
            let l = sum.normalize_or(glam::DVec3::Y);
            let mut row: Vec<f32> = [
                t.x, t.y, t.z, wo.x, wo.y, wo.z, l.x, l.y, l.z, 1.0, 1.0, 1.0,
            ]
            .map(|v| v as f32)
            .to_vec();
            row.push(2.1);
            row.resize(stride, 0.1);
            row
        })
        .collect()
}

criterion_group!(benches, device_cost);

fn main() {
    benches();
    Criterion::default().configure_from_args().final_summary();
}
