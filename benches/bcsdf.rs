//! Throughput of the Chiang 2016 hair BCSDF: evaluation, sampling and pdf in f64 and f32
//! (scalar), eval/pdf batched over `wide::f32x8` and `wide::f32x16` lanes (eval also from a
//! structure of arrays, `eval_batch_soa`, against the array of structures), and eval on each
//! instruction set the CPU runs (`HostBatch`, chosen at run time: `eval/host/Avx512`, ...;
//! `eval/host soa/Avx512`, ... from a structure of arrays; `eval/host soa black/Avx512`, ...
//! the same for black hair, eumelanin 8).
//!
//! Every benchmark processes the same 1024 deterministic samples per iteration and reports
//! `Throughput::Elements(1024)`, so criterion's time divided by 1024 is the cost of one
//! evaluation. Material: beta_m = beta_n = 0.3, alpha = 2 degrees, eta = 1.55, sigma_a from
//! eumelanin 1.3 (the Mitsuba 3 peer, `benches/peers/mitsuba_hair_bench.py`, uses the same
//! roughness, tilt and index).
//!
//! Run: `cargo bench --bench bcsdf` (or `-- batch` for the batched functions only, `-- host`
//! for the instruction sets; `-- parallel_batch` for the parallel batch on one and two threads
//! against the sequential one, over 2^16 samples).
//!
//! **Benchmark of record.** The Mitsuba 3 peer JIT-compiles its vectorised LLVM backend for the
//! host CPU (AVX-512 where available, 16 lanes). `HostBatch` picks the host's widest
//! instruction set at run time, so the default build (no `RUSTFLAGS`) is the fair comparison:
//! `eval/host/<set>` against the peer's ns/eval from the same session. `wide`'s lanes run the
//! build's instructions: in the default build (x86-64 baseline: SSE2, no FMA, no SSE4.1)
//! `f32x16` is two `f32x8` halves, four SSE registers.

use std::hint::black_box;

use criterion::{criterion_group, BenchmarkId, Criterion, Throughput};
use hairmath::absorption::Absorption;
use hairmath::bcsdf::{
    eval_batch, eval_batch_soa, par_eval_batch, pdf_batch, BatchLanes, BatchReal, Bcsdf,
    ChiangHair, DirectionSlices, HostBatch, Model, Query, RandomNumbers, RgbSlices, SampledBcsdf,
};
use hairmath::geometry::V3;
use hairmath::params::HairParams;
use hairmath::real::{InstructionSet, Real};
use rand::{Rng, SeedableRng};
use rand_pcg::Pcg64Mcg;

const N: usize = 1024;

/// beta_m = beta_n = 0.3, a 2 degree tilt, eta = 1.55, eumelanin 1.3.
fn params() -> HairParams {
    HairParams::default()
}

/// Deterministic inputs: uniform directions on the sphere, h uniform in [-1, 1], and three
/// uniforms for sampling.
struct Inputs {
    wi: Vec<[f32; 3]>,
    wo: Vec<[f32; 3]>,
    h: Vec<f32>,
    u: Vec<[f32; 3]>,
}

fn inputs() -> Inputs {
    let mut rng = Pcg64Mcg::seed_from_u64(2016);
    let unit = |rng: &mut Pcg64Mcg| {
        let z: f32 = rng.random_range(-1.0..=1.0);
        let phi: f32 = rng.random_range(0.0..core::f32::consts::TAU);
        let r = (1.0 - z * z).max(0.0).sqrt();
        [r * phi.cos(), r * phi.sin(), z]
    };
    let mut out = Inputs {
        wi: Vec::with_capacity(N),
        wo: Vec::with_capacity(N),
        h: Vec::with_capacity(N),
        u: Vec::with_capacity(N),
    };
    for _ in 0..N {
        out.wi.push(unit(&mut rng));
        out.wo.push(unit(&mut rng));
        out.h.push(rng.random_range(-1.0..=1.0));
        out.u.push([rng.random(), rng.random(), rng.random()]);
    }
    out
}

fn v3<R: Real>(d: &[[f32; 3]]) -> Vec<V3<R>> {
    d.iter()
        .map(|v| V3::from_f64(v[0] as f64, v[1] as f64, v[2] as f64))
        .collect()
}

/// The scalar path in precision `R` over all N samples.
struct Scalar<R> {
    hair: ChiangHair<R>,
    wi: Vec<V3<R>>,
    wo: Vec<V3<R>>,
    h: Vec<R>,
    u: Vec<[R; 3]>,
}

impl<R: Real> Scalar<R> {
    fn new(p: &HairParams, x: &Inputs) -> Self {
        Scalar {
            hair: ChiangHair::new(p),
            wi: v3(&x.wi),
            wo: v3(&x.wo),
            h: x.h.iter().map(|&h| R::c(h as f64)).collect(),
            u: x.u.iter().map(|u| u.map(|v| R::c(v as f64))).collect(),
        }
    }
}

fn bench_eval(c: &mut Criterion) {
    let p = params();
    let x = inputs();
    let mut g = c.benchmark_group("eval");
    g.throughput(Throughput::Elements(N as u64));

    let s64 = Scalar::<f64>::new(&p, &x);
    let mut out64 = vec![[0.0_f64; 3]; N];
    g.bench_function(BenchmarkId::new("scalar", "f64"), |b| {
        b.iter(|| {
            let hair = black_box(&s64.hair);
            for (k, o) in out64.iter_mut().enumerate() {
                *o = hair.eval(&Query::new(s64.wi[k], s64.wo[k], s64.h[k]));
            }
            black_box(&mut out64);
        })
    });

    let s32 = Scalar::<f32>::new(&p, &x);
    let mut out32 = vec![[0.0_f32; 3]; N];
    g.bench_function(BenchmarkId::new("scalar", "f32"), |b| {
        b.iter(|| {
            let hair = black_box(&s32.hair);
            for (k, o) in out32.iter_mut().enumerate() {
                *o = hair.eval(&Query::new(s32.wi[k], s32.wo[k], s32.h[k]));
            }
            black_box(&mut out32);
        })
    });

    fn batch<L: BatchLanes>(
        g: &mut criterion::BenchmarkGroup<'_, criterion::measurement::WallTime>,
        name: &str,
        p: &HairParams,
        x: &Inputs,
    ) {
        let hair = ChiangHair::<f64>::new(p).instantiate::<L>();
        let mut out = vec![[0.0_f32; 3]; N];
        g.bench_function(BenchmarkId::new("batch", name), |b| {
            b.iter(|| {
                eval_batch(
                    black_box(&hair),
                    black_box(&x.wi),
                    black_box(&x.wo),
                    black_box(&x.h),
                    &mut out,
                )
                .expect("equal lengths");
                black_box(&mut out);
            })
        });
        // The same samples as a structure of arrays (no transposition).
        let (wi, wo) = (components(&x.wi), components(&x.wo));
        let mut rgb = [vec![0.0_f32; N], vec![0.0_f32; N], vec![0.0_f32; N]];
        g.bench_function(BenchmarkId::new("batch soa", name), |b| {
            b.iter(|| {
                let (wi, wo) = (soa(black_box(&wi)), soa(black_box(&wo)));
                let [r, g, b] = &mut rgb;
                let out = RgbSlices { r, g, b };
                eval_batch_soa(black_box(&hair), wi, wo, black_box(&x.h), out)
                    .expect("equal lengths");
                black_box(&mut rgb);
            })
        });
    }
    batch::<wide::f32x8>(&mut g, "f32x8", &p, &x);
    batch::<wide::f32x16>(&mut g, "f32x16", &p, &x);
    let model = ChiangHair::<f64>::new(&p);
    let black = ChiangHair::<f64>::new(&HairParams {
        sigma_a: Absorption::from_melanin(8.0, 0.0).expect("a valid concentration"),
        ..p
    });
    let (wi_soa, wo_soa) = (components(&x.wi), components(&x.wo));
    for set in InstructionSet::ALL.into_iter().filter(|s| s.is_supported()) {
        let host = HostBatch::on(set, &model);
        let mut out = vec![[0.0_f32; 3]; N];
        g.bench_function(BenchmarkId::new("host", format!("{set:?}")), |b| {
            b.iter(|| {
                black_box(&host)
                    .eval(
                        black_box(&x.wi),
                        black_box(&x.wo),
                        black_box(&x.h),
                        &mut out,
                    )
                    .expect("equal lengths");
                black_box(&mut out);
            })
        });
        let mut rgb = [vec![0.0_f32; N], vec![0.0_f32; N], vec![0.0_f32; N]];
        for (name, host) in [
            ("host soa", host),
            ("host soa black", HostBatch::on(set, &black)),
        ] {
            g.bench_function(BenchmarkId::new(name, format!("{set:?}")), |b| {
                b.iter(|| {
                    let (wi, wo) = (soa(black_box(&wi_soa)), soa(black_box(&wo_soa)));
                    let [r, g, b] = &mut rgb;
                    black_box(&host)
                        .eval_soa(wi, wo, black_box(&x.h), RgbSlices { r, g, b })
                        .expect("equal lengths");
                    black_box(&mut rgb);
                })
            });
        }
    }
    g.finish();
}

/// The x, y and z components of `d` as three arrays.
fn components(d: &[[f32; 3]]) -> [Vec<f32>; 3] {
    [0, 1, 2].map(|c| d.iter().map(|w| w[c]).collect())
}

/// Direction components as the slices of a structure-of-arrays batch.
fn soa(d: &[Vec<f32>; 3]) -> DirectionSlices<'_> {
    DirectionSlices {
        x: &d[0],
        y: &d[1],
        z: &d[2],
    }
}

fn bench_sample(c: &mut Criterion) {
    let p = params();
    let x = inputs();
    let mut g = c.benchmark_group("sample");
    g.throughput(Throughput::Elements(N as u64));

    fn run<R: Real>(
        g: &mut criterion::BenchmarkGroup<'_, criterion::measurement::WallTime>,
        name: &str,
        s: &Scalar<R>,
    ) {
        let mut out = Vec::with_capacity(N);
        g.bench_function(BenchmarkId::new("scalar", name), |b| {
            b.iter(|| {
                out.clear();
                let hair = black_box(&s.hair);
                for k in 0..N {
                    let [u0, u1, uc] = s.u[k];
                    let u = RandomNumbers {
                        lobe: uc,
                        longitudinal: u0,
                        cone: u1,
                        offset: R::c(0.0),
                    };
                    out.push(hair.sample(s.wo[k], s.h[k], u));
                }
                black_box(&mut out);
            })
        });
    }
    run(&mut g, "f64", &Scalar::<f64>::new(&p, &x));
    run(&mut g, "f32", &Scalar::<f32>::new(&p, &x));
    g.finish();
}

fn bench_pdf(c: &mut Criterion) {
    let p = params();
    let x = inputs();
    let mut g = c.benchmark_group("pdf");
    g.throughput(Throughput::Elements(N as u64));

    fn run<R: Real>(
        g: &mut criterion::BenchmarkGroup<'_, criterion::measurement::WallTime>,
        name: &str,
        s: &Scalar<R>,
    ) {
        let mut out = vec![R::c(0.0); N];
        g.bench_function(BenchmarkId::new("scalar", name), |b| {
            b.iter(|| {
                let hair = black_box(&s.hair);
                for (k, o) in out.iter_mut().enumerate() {
                    *o = hair.pdf(&Query::new(s.wi[k], s.wo[k], s.h[k]));
                }
                black_box(&mut out);
            })
        });
    }
    run(&mut g, "f64", &Scalar::<f64>::new(&p, &x));
    run(&mut g, "f32", &Scalar::<f32>::new(&p, &x));

    let hair8 = ChiangHair::<f64>::new(&p).instantiate::<wide::f32x8>();
    let mut out = vec![0.0_f32; N];
    g.bench_function(BenchmarkId::new("batch", "f32x8"), |b| {
        b.iter(|| {
            pdf_batch(
                black_box(&hair8),
                black_box(&x.wi),
                black_box(&x.wo),
                black_box(&x.h),
                &mut out,
            )
            .expect("equal lengths");
            black_box(&mut out);
        })
    });
    g.finish();
}

/// `n` samples from the seed `seed`: directions uniform on the sphere (`wi`, then `wo`) and h
/// uniform in [-1, 1].
#[allow(clippy::type_complexity)]
fn random_samples(n: usize, seed: u64) -> (Vec<[f32; 3]>, Vec<[f32; 3]>, Vec<f32>) {
    let mut rng = Pcg64Mcg::seed_from_u64(seed);
    let unit = |rng: &mut Pcg64Mcg| {
        let z: f32 = rng.random_range(-1.0..=1.0);
        let phi: f32 = rng.random_range(0.0..core::f32::consts::TAU);
        let r = (1.0 - z * z).max(0.0).sqrt();
        [r * phi.cos(), r * phi.sin(), z]
    };
    let wi: Vec<[f32; 3]> = (0..n).map(|_| unit(&mut rng)).collect();
    let wo: Vec<[f32; 3]> = (0..n).map(|_| unit(&mut rng)).collect();
    let h: Vec<f32> = (0..n).map(|_| rng.random_range(-1.0..=1.0)).collect();
    (wi, wo, h)
}

/// Samples of the parallel batch's benchmark.
const PARALLEL_N: usize = 1 << 16;

/// The parallel batch ([`par_eval_batch`], lanes of [`BatchReal`]; [`HostBatch::par_eval`] on
/// the host's instruction set) on `PARALLEL_N` samples in pools of one and two threads, against
/// the sequential evaluation of the same samples: the ratios of one run are the scaling.
fn bench_parallel(c: &mut Criterion) {
    let p = params();
    let (wi, wo, h) = random_samples(PARALLEL_N, 7);
    let mut out = vec![[0.0_f32; 3]; PARALLEL_N];
    let hair = ChiangHair::<f64>::new(&p).instantiate::<BatchReal>();
    let host = HostBatch::new(&ChiangHair::<f64>::new(&p));
    let mut g = c.benchmark_group("parallel_batch");
    g.throughput(Throughput::Elements(PARALLEL_N as u64));
    let pools = [1, 2].map(|threads| {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .expect("a thread pool");
        (threads, pool)
    });
    // The sequential evaluation, then the parallel one on each pool: `eval` with the flag set
    // splits the batch on rayon's current pool.
    let mut scaling = |name: &str, eval: &BatchFn<'_>| {
        g.bench_function(format!("{name}sequential"), |b| {
            b.iter(|| {
                eval(&wi, &wo, &h, &mut out, false);
                black_box(&mut out);
            })
        });
        for (threads, pool) in &pools {
            g.bench_function(BenchmarkId::new(format!("{name}threads"), threads), |b| {
                b.iter(|| {
                    pool.install(|| eval(&wi, &wo, &h, &mut out, true));
                    black_box(&mut out);
                })
            });
        }
    };
    scaling("", &|wi, wo, h, out, parallel| {
        let hair = black_box(&hair);
        match parallel {
            false => eval_batch(hair, wi, wo, h, out),
            true => par_eval_batch(hair, wi, wo, h, out),
        }
        .expect("equal lengths")
    });
    scaling("host ", &|wi, wo, h, out, parallel| {
        let host = black_box(&host);
        match parallel {
            false => host.eval(wi, wo, h, out),
            true => host.par_eval(wi, wo, h, out),
        }
        .expect("equal lengths")
    });
    g.finish();
}

criterion_group!(benches, bench_eval, bench_sample, bench_pdf, bench_parallel);

/// A batch evaluation of (wi, wo, h) into out, on rayon's pool if the flag is set.
type BatchFn<'a> = dyn Fn(&[[f32; 3]], &[[f32; 3]], &[f32], &mut [[f32; 3]], bool) + Sync + 'a;

/// The Mitsuba peer's method (`benches/peers/mitsuba_hair_bench.py N threads`): `n` random
/// samples (directions uniform on the sphere, h uniform in [-1, 1]) evaluated in one call on
/// `threads` threads, one warm-up pass, then the best of five timed passes, printed as ns per
/// evaluation. Best-of-five filters the noise of a shared machine the same way for both sides.
fn peer_style(n: usize, threads: usize) {
    // The peer's material: sigma_a (0.5, 0.8, 1.4) as given, the roughness, tilt and index
    // of `params`.
    let p = HairParams {
        sigma_a: Absorption::new([0.5, 0.8, 1.4]).expect("a valid absorption"),
        ..params()
    };
    let (wi, wo, h) = random_samples(n, 3);
    let mut out = vec![[0.0_f32; 3]; n];
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .expect("a thread pool");
    // One thread evaluates sequentially; more split the batch on the pool.
    let best = |eval: &BatchFn, out: &mut [[f32; 3]]| {
        let mut best = f64::INFINITY;
        for pass in 0..6 {
            let t = std::time::Instant::now();
            match threads {
                1 => eval(black_box(&wi), black_box(&wo), black_box(&h), out, false),
                _ => {
                    pool.install(|| eval(black_box(&wi), black_box(&wo), black_box(&h), out, true))
                }
            }
            black_box(&mut *out);
            if pass > 0 {
                best = best.min(t.elapsed().as_secs_f64());
            }
        }
        best * 1e9 / n as f64
    };
    let model = ChiangHair::<f64>::new(&p);
    fn lanes<L: BatchLanes + Sync + 'static>(model: &ChiangHair<f64>) -> Box<BatchFn<'static>> {
        let hair = model.instantiate::<L>();
        Box::new(move |wi, wo, h, out, parallel| {
            match parallel {
                false => eval_batch(&hair, wi, wo, h, out),
                true => par_eval_batch(&hair, wi, wo, h, out),
            }
            .expect("equal lengths")
        })
    }
    let x8 = best(&*lanes::<wide::f32x8>(&model), &mut out);
    let x16 = best(&*lanes::<wide::f32x16>(&model), &mut out);
    // The same samples as a structure of arrays, the layout Mitsuba's arrays have.
    let (wi_soa, wo_soa) = (components(&wi), components(&wo));
    let mut rgb = [vec![0.0_f32; n], vec![0.0_f32; n], vec![0.0_f32; n]];
    let sets: Vec<String> = InstructionSet::ALL
        .into_iter()
        .filter(|set| set.is_supported())
        .map(|set| {
            let batch = HostBatch::on(set, &model);
            let eval: &BatchFn<'_> = &|wi, wo, h, out, parallel| {
                match parallel {
                    false => batch.eval(wi, wo, h, out),
                    true => batch.par_eval(wi, wo, h, out),
                }
                .expect("equal lengths")
            };
            let aos = best(eval, &mut out);
            let soa = best_soa(&batch, &wi_soa, &wo_soa, &h, &mut rgb, &pool);
            format!("{set:?} {aos:.2} ns, {set:?}-soa {soa:.2} ns")
        })
        .collect();
    let mean: f64 = out
        .iter()
        .map(|v| v.iter().map(|&c| c as f64).sum::<f64>())
        .sum::<f64>()
        / (3 * n) as f64;
    println!(
        "hairmath batch eval (N={n}, threads={threads}, best of 5 after warm-up): f32x8 {x8:.2} ns, \
         f32x16 {x16:.2} ns, HostBatch on {} per evaluation (mean value {mean:.5})",
        sets.join(", ")
    );
}

/// [`HostBatch::eval_soa`] (one thread in `pool`) or [`HostBatch::par_eval_soa`] (more) as
/// [`peer_style`] times the array of structures: one warm-up pass, then the best of five, in ns
/// per evaluation.
fn best_soa(
    batch: &HostBatch<ChiangHair<f64>>,
    wi: &[Vec<f32>; 3],
    wo: &[Vec<f32>; 3],
    h: &[f32],
    rgb: &mut [Vec<f32>; 3],
    pool: &rayon::ThreadPool,
) -> f64 {
    let mut best = f64::INFINITY;
    for pass in 0..6 {
        let [r, g, b] = &mut *rgb;
        let out = RgbSlices { r, g, b };
        let (wi, wo, h) = (soa(black_box(wi)), soa(black_box(wo)), black_box(h));
        let t = std::time::Instant::now();
        match pool.current_num_threads() {
            1 => batch.eval_soa(wi, wo, h, out),
            _ => pool.install(|| batch.par_eval_soa(wi, wo, h, out)),
        }
        .expect("equal lengths");
        black_box(&mut *rgb);
        if pass > 0 {
            best = best.min(t.elapsed().as_secs_f64());
        }
    }
    best * 1e9 / h.len() as f64
}

/// `BCSDF_PEER_N=2000000 [BCSDF_PEER_THREADS=2] cargo bench --bench bcsdf` prints the
/// peer-style measurement ([`peer_style`], one thread unless told) instead of running criterion;
/// `benches/peers/compare_mitsuba.sh` runs it against the peer and prints the ratios.
fn main() {
    if let Some(n) = std::env::var("BCSDF_PEER_N")
        .ok()
        .and_then(|v| v.parse().ok())
    {
        let threads = std::env::var("BCSDF_PEER_THREADS")
            .ok()
            .and_then(|v| v.parse().ok())
            .unwrap_or(1);
        peer_style(n, threads);
        return;
    }
    benches();
    Criterion::default().configure_from_args().final_summary();
}
