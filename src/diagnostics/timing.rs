//! Indicative evaluation timings on deterministic inputs.

use crate::bcsdf::{BatchEval, Bcsdf, Query};
use crate::geometry::{local_direction, V3};
use crate::quadrature::kronecker;
use crate::real::Real;
use std::hint::black_box;
use std::time::Instant;

/// The scalar precisions a model can be timed in: `f32` and `f64`, the precisions a CPU caller
/// evaluates in (symbolic [`crate::real::Traced`] values and SIMD lanes are not timed per
/// call).
pub trait TimingScalar: Real {}

impl TimingScalar for f32 {}
impl TimingScalar for f64 {}

/// Number of distinct queries [`ns_per_eval`] cycles through.
pub const TIMING_INPUTS: usize = 1024;

/// The k-th timing query: the 5-dimensional [`kronecker`] point `u` mapped to wi and wo uniform
/// on the sphere (sin theta = 2 u - 1, phi = 2 pi u - pi) and h = 2 u - 1 in [-1, 1], rounded
/// to `R`.
fn timing_query<R: TimingScalar>(k: usize) -> Query<R> {
    let mut u = [0.0; 5];
    kronecker(k, 5, &mut u);
    let direction = |a: f64, b: f64| {
        let sin_theta = 2.0 * a - 1.0;
        let cos_theta = (1.0 - sin_theta * sin_theta).max(0.0).sqrt();
        let w = local_direction(
            sin_theta,
            cos_theta,
            core::f64::consts::TAU * b - core::f64::consts::PI,
        );
        V3::<R>::from_f64(w.x, w.y, w.z)
    };
    Query::new(
        direction(u[0], u[1]),
        direction(u[2], u[3]),
        R::c(2.0 * u[4] - 1.0),
    )
}

/// Mean wall-clock nanoseconds per call of `call(k)` over `calls` calls (`k` = 0, 1, ...); 0
/// when `calls` is 0.
pub(crate) fn ns_per_call(calls: usize, mut call: impl FnMut(usize)) -> f64 {
    if calls == 0 {
        return 0.0;
    }
    let start = Instant::now();
    for k in 0..calls {
        call(k);
    }
    start.elapsed().as_nanos() as f64 / calls as f64
}

/// Mean wall-clock nanoseconds of one [`Bcsdf::eval`] of `model` in precision `R`, over
/// `calls` calls cycling through [`TIMING_INPUTS`] deterministic queries (directions uniform
/// on the sphere and offsets uniform in [-1, 1], from [`kronecker`]). Indicative only: it
/// includes the loop and depends on the machine and its load (`cargo bench` has criterion
/// figures); 0 when `calls` is 0.
pub fn ns_per_eval<R: TimingScalar, M: Bcsdf<R> + ?Sized>(model: &M, calls: usize) -> f64 {
    let queries: Vec<Query<R>> = (0..TIMING_INPUTS).map(timing_query).collect();
    ns_per_call(calls, |k| {
        black_box(model.eval(black_box(&queries[k % TIMING_INPUTS])));
    })
}

/// Mean wall-clock nanoseconds per sample of a batch evaluation ([`BatchEval`], the SIMD
/// lanes of [`crate::real::BatchReal`]), over `samples` samples in batches of
/// [`TIMING_INPUTS`] deterministic queries (those of [`ns_per_eval`], rounded to `f32`).
/// Indicative only, as [`ns_per_eval`]; 0 when `samples` is 0.
pub fn ns_per_batch_eval(model: &dyn BatchEval, samples: usize) -> f64 {
    let queries: Vec<Query<f32>> = (0..TIMING_INPUTS).map(timing_query).collect();
    let wi: Vec<[f32; 3]> = queries.iter().map(|q| [q.wi.x, q.wi.y, q.wi.z]).collect();
    let wo: Vec<[f32; 3]> = queries.iter().map(|q| [q.wo.x, q.wo.y, q.wo.z]).collect();
    let h: Vec<f32> = queries.iter().map(|q| q.h).collect();
    let mut out = vec![[0.0_f32; 3]; TIMING_INPUTS];
    let batches = samples.div_ceil(TIMING_INPUTS);
    let ns = ns_per_call(batches, |_| {
        model
            .eval_batch_lanes(black_box(&wi), &wo, &h, &mut out)
            .expect("the timing batch has equal lengths");
        black_box(&out);
    });
    ns / TIMING_INPUTS as f64
}
