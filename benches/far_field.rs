//! Cost of the far-field N_p integrators and of the far-field BCSDF: the adaptive f64 reference,
//! the fixed-node rule at several node counts in f64 and f32, a baked far-field N_p table's
//! trilinear lookup (the real-time alternative), and full far-field evaluation.
//! Each iteration processes the same 256 deterministic (theta_o, phi) pairs; criterion's time
//! divided by 256 is the cost of one N_p evaluation (all four lobes, three channels).
//!
//! Run: `cargo bench --bench far_field`.

use std::hint::black_box;

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion, Throughput};
use hairmath::absorption::sigma_a_from_melanin;
use hairmath::bcsdf::{ChiangFarField, ChiangHair, ChiangParams, FarFieldRule};
use hairmath::geometry::{local_direction, V3};
use hairmath::lut::{bake, FarFieldN};
use hairmath::real::Real;

const N: usize = 256;

fn params() -> ChiangParams {
    let sigma_a = sigma_a_from_melanin(1.3, 0.0).expect("valid melanin");
    ChiangParams::new(0.3, 0.3, 2f64.to_radians(), 1.55, sigma_a).expect("valid parameters")
}

/// (sin theta_o, cos theta_o, phi) on a deterministic low-discrepancy sequence.
fn angles() -> Vec<(f64, f64, f64)> {
    (0..N)
        .map(|k| {
            let t = (k as f64 + 0.5) / N as f64;
            let theta = (t - 0.5) * 3.0;
            let phi = ((k as f64 * 0.618_033_988_75).fract() - 0.5) * 2.0 * std::f64::consts::PI;
            (theta.sin(), theta.cos(), phi)
        })
        .collect()
}

fn bench_np(c: &mut Criterion) {
    let hair = ChiangHair::<f64>::new(&params());
    let xs = angles();
    let mut g = c.benchmark_group("far_field_np");
    g.throughput(Throughput::Elements(N as u64));
    g.sample_size(10);
    g.bench_function(BenchmarkId::new("reference", "rel_tol 1e-9"), |b| {
        b.iter(|| {
            for &(s, co, phi) in &xs {
                black_box(hair.far_field_azimuthal_reference(s, co, phi, 1e-9));
            }
        })
    });
    for nodes in [16, 32, 64] {
        let rule = FarFieldRule::gauss_legendre(nodes).expect("valid node count");
        fast(
            &mut g,
            &format!("f64 {nodes} nodes"),
            &ChiangFarField::new(hair, &rule),
            &xs,
        );
        let far32 = ChiangFarField::new(ChiangHair::<f32>::new(&params()), &rule);
        fast(&mut g, &format!("f32 {nodes} nodes"), &far32, &xs);
    }
    // The same N_p from a baked 32 x 16 x 4 table over (phi, theta_o, beta_n): 12 channels
    // (four lobes, rgb) per trilinear lookup.
    let baker = FarFieldN::new(1.55, params().sigma_a(), 0.2, 0.5, 1e-6).expect("valid baker");
    let table = bake(&baker, &[32, 16, 4]).expect("valid sizes");
    let coords: Vec<[f32; 3]> = xs
        .iter()
        .map(|&(s, _, phi)| [phi.abs() as f32, s.asin().abs() as f32, 0.3])
        .collect();
    let mut out = vec![0.0_f32; 12];
    g.bench_function(BenchmarkId::new("table", "32x16x4 trilinear"), |b| {
        b.iter(|| {
            for c in &coords {
                table
                    .lookup_into(black_box(c), &mut out)
                    .expect("three coordinates");
                black_box(&out);
            }
        })
    });
    g.finish();
}

fn fast<R: Real>(
    g: &mut criterion::BenchmarkGroup<'_, criterion::measurement::WallTime>,
    name: &str,
    far: &ChiangFarField<R>,
    xs: &[(f64, f64, f64)],
) {
    let xs: Vec<(R, R, R)> = xs
        .iter()
        .map(|&(s, c, p)| (R::c(s), R::c(c), R::c(p)))
        .collect();
    g.bench_function(BenchmarkId::new("fast", name), |b| {
        b.iter(|| {
            for &(s, co, phi) in &xs {
                black_box(far.azimuthal(s, co, phi));
            }
        })
    });
}

fn bench_eval(c: &mut Criterion) {
    let xs = angles();
    let pairs: Vec<(V3<f64>, V3<f64>)> = xs
        .iter()
        .map(|&(s, co, phi)| (local_direction(-s, co, phi), local_direction(s, co, 0.0)))
        .collect();
    let mut g = c.benchmark_group("far_field_eval");
    g.throughput(Throughput::Elements(N as u64));
    let rule = FarFieldRule::gauss_legendre(32).expect("valid node count");
    let far64 = ChiangFarField::new(ChiangHair::<f64>::new(&params()), &rule);
    g.bench_function(BenchmarkId::new("eval", "f64 32 nodes"), |b| {
        b.iter(|| {
            for &(wi, wo) in &pairs {
                black_box(far64.eval(wi, wo));
            }
        })
    });
    let far32 = ChiangFarField::new(ChiangHair::<f32>::new(&params()), &rule);
    let pairs32: Vec<(V3<f32>, V3<f32>)> = pairs
        .iter()
        .map(|(a, b)| (V3::c(a.x, a.y, a.z), V3::c(b.x, b.y, b.z)))
        .collect();
    g.bench_function(BenchmarkId::new("eval", "f32 32 nodes"), |b| {
        b.iter(|| {
            for &(wi, wo) in &pairs32 {
                black_box(far32.eval(wi, wo));
            }
        })
    });
    g.finish();
}

criterion_group!(benches, bench_np, bench_eval);
criterion_main!(benches);
