//! Cost of the far-field N_p integrators and of the far-field BCSDF: the adaptive f64 reference,
//! the nodes placed per lobe (`AlignedFarField`), the fixed-node rule at several node counts in
//! f64 and f32, a baked far-field N_p table's
//! trilinear lookup (the real-time alternative), and full far-field evaluation (also with the
//! node pairs in SIMD lanes, `HostFarField`); at beta_n = 0.05 the aligned rule against the
//! fixed rule at 512 nodes.
//! Each iteration processes the same 256 deterministic (theta_o, phi) pairs; criterion's time
//! divided by 256 is the cost of one N_p evaluation (all four lobes, three channels).
//!
//! Run: `cargo bench --bench far_field`.

use std::hint::black_box;

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion, Throughput};
use hairmath::bcsdf::{
    AlignedFarField, Bcsdf, ChiangFarField, ChiangHair, FarFieldRule, HostFarField, Query,
};
use hairmath::geometry::{local_direction, V3};
use hairmath::lut::{bake, FarFieldN};
use hairmath::params::{AzimuthalRoughness, HairParams};
use hairmath::real::Real;

const N: usize = 256;

/// beta_m = beta_n = 0.3, a 2 degree tilt, eta = 1.55, eumelanin 1.3.
fn params() -> HairParams {
    HairParams::default()
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
    for nodes in [4, 6, 8, 12] {
        let aligned = AlignedFarField::new(&params(), nodes).expect("valid node count");
        g.bench_function(
            BenchmarkId::new("aligned", format!("{nodes} per half-branch")),
            |b| {
                b.iter(|| {
                    for &(s, co, phi) in &xs {
                        black_box(aligned.azimuthal(s, co, phi));
                    }
                })
            },
        );
    }
    for nodes in [16, 32, 64, 128, 512] {
        let rule = FarFieldRule::gauss_legendre(nodes).expect("valid node count");
        fast(
            &mut g,
            &format!("f64 {nodes} nodes"),
            &ChiangFarField::<f64>::with_rule(&params(), &rule),
            &xs,
        );
        let far32 = ChiangFarField::<f32>::with_rule(&params(), &rule);
        fast(&mut g, &format!("f32 {nodes} nodes"), &far32, &xs);
    }
    // The same N_p from a baked 32 x 16 x 4 table over (phi, theta_o, beta_n): 12 channels
    // (four lobes, rgb) per trilinear lookup.
    let p = params();
    let roughness = |b| AzimuthalRoughness::new(b).expect("valid roughness");
    let baker = FarFieldN::new(p.eta, p.sigma_a, roughness(0.2), roughness(0.5), 1e-6)
        .expect("valid baker");
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

/// At beta_n = 0.05, where the fixed rule needs 512 nodes for 1e-3: the aligned rule at 8
/// nodes per half-branch (16 per lobe at most) against the fixed rule at 512.
fn bench_np_low_roughness(c: &mut Criterion) {
    let p = HairParams {
        beta_n: AzimuthalRoughness::new(0.05).expect("valid roughness"),
        ..params()
    };
    let xs = angles();
    let mut g = c.benchmark_group("far_field_np_beta_n_0.05");
    g.throughput(Throughput::Elements(N as u64));
    g.sample_size(10);
    let aligned = AlignedFarField::new(&p, 8).expect("valid node count");
    g.bench_function(BenchmarkId::new("aligned", "8 per half-branch"), |b| {
        b.iter(|| {
            for &(s, co, phi) in &xs {
                black_box(aligned.azimuthal(s, co, phi));
            }
        })
    });
    let rule = FarFieldRule::gauss_legendre(512).expect("valid node count");
    fast(
        &mut g,
        "f64 512 nodes",
        &ChiangFarField::<f64>::with_rule(&p, &rule),
        &xs,
    );
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

/// One far-field evaluation per query, all lobes and channels: the rule in `f64` and `f32`
/// walking its pairs of nodes, and `HostFarField` with the pairs in the lanes of the host's
/// widest instruction set.
fn bench_eval(c: &mut Criterion) {
    let xs = angles();
    let pairs: Vec<(V3<f64>, V3<f64>)> = xs
        .iter()
        .map(|&(s, co, phi)| (local_direction(-s, co, phi), local_direction(s, co, 0.0)))
        .collect();
    let pairs32: Vec<(V3<f32>, V3<f32>)> = pairs
        .iter()
        .map(|(a, b)| (V3::from_f64(a.x, a.y, a.z), V3::from_f64(b.x, b.y, b.z)))
        .collect();
    let mut g = c.benchmark_group("far_field_eval");
    g.throughput(Throughput::Elements(N as u64));
    for nodes in [8, 32, 64, 128, 512] {
        let rule = FarFieldRule::gauss_legendre(nodes).expect("valid node count");
        let far64 = ChiangFarField::<f64>::with_rule(&params(), &rule);
        let lanes = HostFarField::new(&far64);
        let set = lanes.instruction_set();
        eval_each(&mut g, &format!("f64 {nodes} nodes"), &far64, &pairs);
        let far32 = ChiangFarField::<f32>::with_rule(&params(), &rule);
        eval_each(&mut g, &format!("f32 {nodes} nodes"), &far32, &pairs32);
        let name = format!("f32 {nodes} nodes, HostFarField {set:?}");
        eval_each(&mut g, &name, &lanes, &pairs32);
    }
    g.finish();
}

/// `model.eval` of every pair, each value through `black_box`.
fn eval_each<R: Real>(
    g: &mut criterion::BenchmarkGroup<'_, criterion::measurement::WallTime>,
    name: &str,
    model: &impl Bcsdf<R>,
    pairs: &[(V3<R>, V3<R>)],
) {
    g.bench_function(BenchmarkId::new("eval", name), |b| {
        b.iter(|| {
            for &(wi, wo) in pairs {
                black_box(model.eval(&Query::far(wi, wo)));
            }
        })
    });
}

criterion_group!(benches, bench_np, bench_np_low_roughness, bench_eval);
criterion_main!(benches);
