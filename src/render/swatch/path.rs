//! A CPU path tracer of the swatch with the Chiang model (its near field: `h` from each hit,
//! [`super::offset_of`]).
//!
//! Each pixel's ray (through its centre) is followed from fibre to fibre. At every hit the
//! radiance `int S(wi, wo, h) L(wi) dwi` (the crate's `S` carries no cosine factor) is
//! estimated by **multiple importance sampling** (Veach and Guibas 1995; Veach's thesis,
//! chapter 9) of two strategies: the sphere light sampled uniformly in the cone it subtends
//! ([`super::light`]), and the BCSDF importance-sampled
//! ([`crate::world::WorldSampledBcsdf::sample_world`], d'Eon et al. 2013 and pbrt-v4's
//! `HairBxDF::Sample_f`), combined with the power (exponent 2) or the balance heuristic.
//! The BCSDF sample also continues the path; a path that leaves the swatch collects the
//! environment's (or, weighted, the light's) radiance. Paths end only by **Russian
//! roulette** (Arvo and Kirk 1990) after [`PathSettings::min_bounces`] bounces, surviving
//! with probability `min(max_survival, max channel of the throughput)` and dividing the
//! throughput by it, so the estimate is unbiased; a hard stop at [`MAX_BOUNCES`] bounces
//! (unreachable in practice: the survival probability is at most `max_survival < 1`) only
//! guards against a pathological throughput.
//!
//! Every pixel draws from its own PCG stream seeded by `(seed, pixel)`, so images are
//! reproducible whatever the thread count (rayon over rows of pixels).

use super::light::SwatchLight;
use super::{Swatch, SwatchHit};
use crate::bcsdf::ChiangHair;
use crate::error::ParamError;
use crate::random::{random_numbers, uniform};
use crate::render::camera::Camera;
use crate::render::Image;
use crate::world::{WorldBcsdf, WorldSampledBcsdf};
use glam::DVec3;
use rand_pcg::rand_core::SeedableRng;
use rand_pcg::Pcg64Mcg;
use rayon::prelude::*;

/// The hard stop on a path's length (see the module documentation).
pub const MAX_BOUNCES: usize = 1024;
/// The most samples per pixel.
pub const MAX_SAMPLES: usize = 1 << 20;

/// How the two sampling strategies are combined at each hit.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Strategy {
    /// MIS with the power heuristic, exponent 2 (Veach 1997, section 9.2.4).
    Power,
    /// MIS with the balance heuristic.
    Balance,
    /// The BCSDF's samples only (the light is found by chance).
    BcsdfOnly,
    /// The light's samples only for the light (the environment by the BCSDF's).
    LightOnly,
}

impl Strategy {
    /// The weights of a light-sampled and of a BCSDF-sampled direction towards the light, of
    /// densities `light` and `bcsdf` under the two strategies.
    fn weights(self, light: f64, bcsdf: f64) -> (f64, f64) {
        let share = |a: f64, b: f64| if a + b > 0.0 { a / (a + b) } else { 0.0 };
        match self {
            Strategy::Power => (
                share(light * light, bcsdf * bcsdf),
                share(bcsdf * bcsdf, light * light),
            ),
            Strategy::Balance => (share(light, bcsdf), share(bcsdf, light)),
            Strategy::BcsdfOnly => (0.0, 1.0),
            Strategy::LightOnly => (1.0, 0.0),
        }
    }
}

/// The path tracer's settings. Every field is checked by [`path_trace`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PathSettings {
    /// Paths per pixel, in `[1, 2^20]`.
    pub samples: usize,
    /// The seed of the pixels' random streams.
    pub seed: u64,
    /// Bounces before Russian roulette starts, in `[0, 64]`.
    pub min_bounces: usize,
    /// The largest survival probability of Russian roulette, in `[0.05, 0.99]`.
    pub max_survival: f64,
    /// How the light's and the BCSDF's samples are combined.
    pub strategy: Strategy,
}

impl Default for PathSettings {
    /// 64 paths per pixel, seed 1, roulette after 3 bounces surviving at most 0.95, the power
    /// heuristic.
    fn default() -> Self {
        Self {
            samples: 64,
            seed: 1,
            min_bounces: 3,
            max_survival: 0.95,
            strategy: Strategy::Power,
        }
    }
}

impl PathSettings {
    fn check(&self) -> Result<(), ParamError> {
        ParamError::check(
            "samples",
            self.samples as f64,
            "must be in [1, 2^20]",
            |n| (1.0..=MAX_SAMPLES as f64).contains(&n),
        )?;
        ParamError::check(
            "min_bounces",
            self.min_bounces as f64,
            "must be in [0, 64]",
            |n| n <= 64.0,
        )?;
        ParamError::check(
            "max_survival",
            self.max_survival,
            "must be in [0.05, 0.99]",
            |p| (0.05..=0.99).contains(&p),
        )?;
        Ok(())
    }
}

/// A path-traced image with the variance of each pixel's estimate.
#[derive(Clone, Debug, PartialEq)]
pub struct PathImage {
    /// The mean radiance per pixel (covered: the pixel's ray meets a fibre; the others show
    /// the environment).
    pub image: Image,
    /// Per pixel and channel, the variance of the pixel's mean: the samples' unbiased
    /// variance over their count (infinite with one sample).
    pub variance: Vec<[f64; 3]>,
}

impl PathImage {
    /// The standard error per channel of [`Image::mean`] (over the covered pixels, whose
    /// estimates are independent): `sqrt(sum of their variances) / their count`.
    pub fn mean_standard_error(&self) -> [f64; 3] {
        let covered = self.variance.iter().zip(&self.image.covered);
        let (sum, n) = covered
            .filter(|(_, &c)| c)
            .fold(([0.0; 3], 0usize), |(s, n), (v, _)| {
                ([s[0] + v[0], s[1] + v[1], s[2] + v[2]], n + 1)
            });
        sum.map(|s| if n > 0 { s.sqrt() / n as f64 } else { 0.0 })
    }
}

/// Path-traces `swatch` seen by `camera` with the hair `hair` under `light`.
///
/// # Errors
/// [`ParamError::OutOfRange`] naming a bad setting ([`PathSettings`]) or light
/// ([`SwatchLight::check`]).
pub fn path_trace(
    swatch: &Swatch,
    camera: &Camera,
    hair: &ChiangHair<f64>,
    light: &SwatchLight,
    settings: &PathSettings,
) -> Result<PathImage, ParamError> {
    settings.check()?;
    light.check()?;
    let hits = swatch.camera_hits(camera);
    let tracer = Tracer {
        swatch,
        hair,
        light,
        settings,
    };
    let pixels: Vec<([f64; 3], [f64; 3])> = hits
        .par_iter()
        .enumerate()
        .map(|(k, hit)| tracer.pixel(k, hit.as_ref()))
        .collect();
    Ok(PathImage {
        image: Image {
            size: camera.size,
            pixels: pixels.iter().map(|p| p.0).collect(),
            covered: hits.iter().map(Option::is_some).collect(),
        },
        variance: pixels.iter().map(|p| p.1).collect(),
    })
}

/// What every path of a render shares.
struct Tracer<'a> {
    swatch: &'a Swatch,
    hair: &'a ChiangHair<f64>,
    light: &'a SwatchLight,
    settings: &'a PathSettings,
}

impl Tracer<'_> {
    /// Pixel `k`'s mean radiance and the variance of that mean, per channel.
    fn pixel(&self, k: usize, hit: Option<&SwatchHit>) -> ([f64; 3], [f64; 3]) {
        let Some(hit) = hit else {
            return (self.light.environment, [0.0; 3]);
        };
        let mut rng = Pcg64Mcg::seed_from_u64(
            self.settings.seed ^ (k as u64 + 1).wrapping_mul(0xD1B5_4A32_D192_ED03),
        );
        let (mut sum, mut squares) = ([0.0; 3], [0.0; 3]);
        for _ in 0..self.settings.samples {
            let l = self.path(*hit, &mut rng);
            for c in 0..3 {
                sum[c] += l[c];
                squares[c] += l[c] * l[c];
            }
        }
        let n = self.settings.samples as f64;
        let mean = sum.map(|s| s / n);
        let variance = core::array::from_fn(|c| {
            if self.settings.samples > 1 {
                ((squares[c] - n * mean[c] * mean[c]) / (n - 1.0)).max(0.0) / n
            } else {
                f64::INFINITY
            }
        });
        (mean, variance)
    }

    /// One path's radiance towards the camera (`wo = +Z`) from its first hit.
    fn path(&self, first: SwatchHit, rng: &mut Pcg64Mcg) -> [f64; 3] {
        let (mut hit, mut wo) = (first, DVec3::Z);
        let mut throughput = [1.0; 3];
        let mut radiance = [0.0; 3];
        for bounce in 0..MAX_BOUNCES {
            let direct = self.light_sample(&hit, wo, rng);
            add_product(&mut radiance, throughput, direct);
            let u = random_numbers(rng);
            let sample = self.hair.sample_world(hit.tangent, wo, hit.h, u);
            let weight = sample.weight();
            if sample.pdf.is_nan() || sample.pdf <= 0.0 || weight.iter().all(|&w| w == 0.0) {
                break;
            }
            throughput = core::array::from_fn(|c| throughput[c] * weight[c]);
            let wi = sample.wi.normalize();
            match self.swatch.first_hit(hit.point, wi, Some(hit.strand)) {
                Some(next) => (hit, wo) = (next, -wi),
                None => {
                    add_product(
                        &mut radiance,
                        throughput,
                        self.escaped(&hit, wi, sample.pdf),
                    );
                    break;
                }
            }
            if bounce + 1 >= self.settings.min_bounces {
                let peak = throughput[0].max(throughput[1]).max(throughput[2]);
                let survival = peak.min(self.settings.max_survival);
                if uniform(rng) >= survival {
                    break;
                }
                throughput = throughput.map(|t| t / survival);
            }
        }
        radiance
    }

    /// The light-sampling strategy's estimate at `hit`, MIS-weighted (0 without a light).
    fn light_sample(&self, hit: &SwatchHit, wo: DVec3, rng: &mut Pcg64Mcg) -> [f64; 3] {
        let u = [uniform(rng), uniform(rng)];
        let Some(sphere) = self.light.sphere else {
            return [0.0; 3];
        };
        if self.settings.strategy == Strategy::BcsdfOnly {
            return [0.0; 3];
        }
        let Some(s) = sphere.sample(hit.point, u) else {
            return [0.0; 3];
        };
        if !self.swatch.unoccluded(hit.point, s.direction, hit.strand) {
            return [0.0; 3];
        }
        let value = self.hair.eval_world(hit.tangent, s.direction, wo, hit.h);
        let bcsdf_pdf = self.hair.pdf_world(hit.tangent, s.direction, wo, hit.h);
        let (w, _) = self.settings.strategy.weights(s.pdf, bcsdf_pdf);
        core::array::from_fn(|c| value[c] * sphere.radiance[c] * w / s.pdf)
    }

    /// The radiance a BCSDF-sampled ray leaving the swatch from `hit` along `wi` (density
    /// `pdf`) brings: the environment's, or the light's MIS-weighted.
    fn escaped(&self, hit: &SwatchHit, wi: DVec3, pdf: f64) -> [f64; 3] {
        match self.light.sphere {
            Some(sphere) => {
                let light_pdf = sphere.pdf(hit.point, wi);
                if light_pdf > 0.0 {
                    let (_, w) = self.settings.strategy.weights(light_pdf, pdf);
                    sphere.radiance.map(|l| l * w)
                } else {
                    self.light.environment
                }
            }
            None => self.light.environment,
        }
    }
}

/// `out += a * b`, channel by channel.
fn add_product(out: &mut [f64; 3], a: [f64; 3], b: [f64; 3]) {
    for c in 0..3 {
        out[c] += a[c] * b[c];
    }
}
