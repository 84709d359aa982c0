//! Spherical-harmonics benchmarks.
//!
//! - `wigner_3j_small`: every 3-j symbol with integer j <= 5 per iteration (throughput counts
//!   symbols), ours (exact, correctly rounded) against the `wigners` crate, whose LRU cache is
//!   cleared before each pass ("uncached") or kept warm ("cached").
//! - `wigner_3j_large`: 64 fixed pseudo-random symbols with 100 <= j <= 200 per iteration.
//! - `sh_product`: the generated projected product of two SH vectors (Snyder 2006) for 3..6
//!   bands in f32 and f64, one product per iteration.
//!
//! - `sh_eval`: the polynomial SH basis (`eval_sh`, Sloan 2013 recurrences) for 3..8 bands in
//!   f32 and f64, 1024 directions per iteration (throughput counts directions).
//! - `sh_rotation`: the written-out rotation of bands 0..2 (`rotate_bands012`, 45 multiplies)
//!   in f32 and f64, and Ivanic-Ruedenberg (`ShRotation::new` then `apply`) at l = 2, 4, 8;
//!   one rotation per iteration.
//!
//! Run: `cargo bench --no-default-features --bench sh -- wigner` (or `-- sh_product`,
//! `-- sh_eval`, `-- sh_rotation`).

use std::hint::black_box;

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion, Throughput};
use hairmath::sh::eval_sh;
use hairmath::sh::wigner_3j_int;
use hairmath::sh::ProductPlan;
use hairmath::sh::{check_rotation, rotate_bands012, ShRotation};
use rand::{Rng, SeedableRng};

/// (l1, l2, l3, m1, m2, m3) of all non-trivially-allowed symbols with l <= l_max.
fn all_symbols(l_max: i32) -> Vec<(u32, u32, u32, i32, i32, i32)> {
    let mut out = Vec::new();
    for l1 in 0..=l_max {
        for l2 in 0..=l_max {
            for l3 in (l1 - l2).abs()..=(l1 + l2).min(l_max) {
                for m1 in -l1..=l1 {
                    for m2 in -l2..=l2 {
                        let m3 = -m1 - m2;
                        if m3.abs() <= l3 {
                            out.push((l1 as u32, l2 as u32, l3 as u32, m1, m2, m3));
                        }
                    }
                }
            }
        }
    }
    out
}

fn large_symbols() -> Vec<(u32, u32, u32, i32, i32, i32)> {
    let mut rng = rand_pcg::Pcg64::seed_from_u64(1);
    let mut out = Vec::new();
    while out.len() < 64 {
        let l1 = rng.random_range(100..=200i32);
        let l2 = rng.random_range(100..=200i32);
        let l3 = rng.random_range((l1 - l2).abs()..=(l1 + l2).min(200));
        let m1 = rng.random_range(-l1..=l1);
        let m2 = rng.random_range(-l2..=l2);
        let m3 = -m1 - m2;
        if m3.abs() <= l3 {
            out.push((l1 as u32, l2 as u32, l3 as u32, m1, m2, m3));
        }
    }
    out
}

fn bench_wigner_set(c: &mut Criterion, group: &str, symbols: &[(u32, u32, u32, i32, i32, i32)]) {
    let mut g = c.benchmark_group(group);
    g.throughput(Throughput::Elements(symbols.len() as u64));
    g.bench_function("hairmath_exact", |b| {
        b.iter(|| {
            let mut s = 0.0;
            for &(l1, l2, l3, m1, m2, m3) in symbols {
                s += wigner_3j_int(l1, l2, l3, m1, m2, m3).unwrap_or(0.0);
            }
            black_box(s)
        })
    });
    g.bench_function("wigners_uncached", |b| {
        b.iter(|| {
            wigners::clear_wigner_3j_cache();
            let mut s = 0.0;
            for &(l1, l2, l3, m1, m2, m3) in symbols {
                s += wigners::wigner_3j(l1, l2, l3, m1, m2, m3);
            }
            black_box(s)
        })
    });
    g.bench_function("wigners_cached", |b| {
        b.iter(|| {
            let mut s = 0.0;
            for &(l1, l2, l3, m1, m2, m3) in symbols {
                s += wigners::wigner_3j(l1, l2, l3, m1, m2, m3);
            }
            black_box(s)
        })
    });
    g.finish();
}

fn wigner_3j(c: &mut Criterion) {
    bench_wigner_set(c, "wigner_3j_small", &all_symbols(5));
    bench_wigner_set(c, "wigner_3j_large", &large_symbols());
}

fn sh_product(c: &mut Criterion) {
    let mut g = c.benchmark_group("sh_product");
    g.throughput(Throughput::Elements(1));
    let mut rng = rand_pcg::Pcg64::seed_from_u64(2);
    for n_bands in 3..=6 {
        let plan = ProductPlan::cached(n_bands).expect("cached plan");
        let n = n_bands * n_bands;
        let a: Vec<f64> = (0..n).map(|_| rng.random_range(-1.0..1.0)).collect();
        let b: Vec<f64> = (0..n).map(|_| rng.random_range(-1.0..1.0)).collect();
        let af: Vec<f32> = a.iter().map(|&x| x as f32).collect();
        let bf: Vec<f32> = b.iter().map(|&x| x as f32).collect();
        let mut out = vec![0.0f64; n];
        let mut outf = vec![0.0f32; n];
        g.bench_with_input(BenchmarkId::new("f64", n_bands), &n_bands, |bench, _| {
            bench.iter(|| {
                plan.apply_into(black_box(&a), black_box(&b), &mut out)
                    .expect("lengths");
                black_box(out[0])
            })
        });
        g.bench_with_input(BenchmarkId::new("f32", n_bands), &n_bands, |bench, _| {
            bench.iter(|| {
                plan.apply_into(black_box(&af), black_box(&bf), &mut outf)
                    .expect("lengths");
                black_box(outf[0])
            })
        });
    }
    g.finish();
}

/// 1024 deterministic unit vectors (poles included), as f64 triples.
fn eval_directions() -> Vec<[f64; 3]> {
    let mut rng = rand_pcg::Pcg64::seed_from_u64(3);
    let mut dirs: Vec<[f64; 3]> = (0..1022)
        .map(|_| {
            let z: f64 = rng.random_range(-1.0..1.0);
            let phi: f64 = rng.random_range(0.0..std::f64::consts::TAU);
            let s = (1.0 - z * z).sqrt();
            [s * phi.cos(), s * phi.sin(), z]
        })
        .collect();
    dirs.extend([[0.0, 0.0, 1.0], [0.0, 0.0, -1.0]]);
    dirs
}

fn bench_eval_bands<const N: usize>(
    g: &mut criterion::BenchmarkGroup<'_, criterion::measurement::WallTime>,
    bands: usize,
    dirs: &[[f64; 3]],
) {
    let dirs32: Vec<[f32; 3]> = dirs.iter().map(|d| d.map(|v| v as f32)).collect();
    g.bench_with_input(BenchmarkId::new("f64", bands), &bands, |bench, _| {
        bench.iter(|| {
            let mut acc = 0.0f64;
            for d in black_box(dirs) {
                let y: [f64; N] = eval_sh(d[0], d[1], d[2]);
                acc += y[N - 1];
            }
            black_box(acc)
        })
    });
    g.bench_with_input(BenchmarkId::new("f32", bands), &bands, |bench, _| {
        bench.iter(|| {
            let mut acc = 0.0f32;
            for d in black_box(&dirs32) {
                let y: [f32; N] = eval_sh(d[0], d[1], d[2]);
                acc += y[N - 1];
            }
            black_box(acc)
        })
    });
}

fn sh_eval(c: &mut Criterion) {
    let dirs = eval_directions();
    let mut g = c.benchmark_group("sh_eval");
    g.throughput(Throughput::Elements(dirs.len() as u64));
    bench_eval_bands::<9>(&mut g, 3, &dirs);
    bench_eval_bands::<16>(&mut g, 4, &dirs);
    bench_eval_bands::<25>(&mut g, 5, &dirs);
    bench_eval_bands::<36>(&mut g, 6, &dirs);
    bench_eval_bands::<49>(&mut g, 7, &dirs);
    bench_eval_bands::<64>(&mut g, 8, &dirs);
    g.finish();
}

fn sh_rotation(c: &mut Criterion) {
    let mut g = c.benchmark_group("sh_rotation");
    g.throughput(Throughput::Elements(1));
    let rotation = glam::DMat3::from_quat(glam::DQuat::from_xyzw(0.3, -0.5, 0.2, 0.78).normalize());
    let r64 = check_rotation(rotation).expect("a rotation");
    let r32 = r64.map(|row| row.map(|v| v as f32));
    let c64: [f64; 9] = core::array::from_fn(|i| (i as f64 * 0.7).sin());
    let c32 = c64.map(|v| v as f32);
    g.bench_function("band2_written_out/f64", |b| {
        b.iter(|| black_box(rotate_bands012(black_box(&r64), black_box(c64))))
    });
    g.bench_function("band2_written_out/f32", |b| {
        b.iter(|| black_box(rotate_bands012(black_box(&r32), black_box(c32))))
    });
    for lmax in [2usize, 4, 8] {
        let n = (lmax + 1) * (lmax + 1);
        let coeffs: Vec<f64> = (0..n).map(|i| (i as f64 * 0.3).cos()).collect();
        let mut out = vec![0.0; n];
        g.bench_with_input(
            BenchmarkId::new("ivanic_ruedenberg_build_and_apply", lmax),
            &lmax,
            |b, &lmax| {
                b.iter(|| {
                    let rot = ShRotation::new(black_box(rotation), lmax).expect("valid");
                    rot.apply_into(black_box(&coeffs), &mut out)
                        .expect("lengths");
                    black_box(out[n - 1])
                })
            },
        );
    }
    g.finish();
}

criterion_group!(benches, wigner_3j, sh_product, sh_eval, sh_rotation);
criterion_main!(benches);
