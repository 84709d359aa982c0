//! The importance sampler of a renderer's BSDF against its own pdf and S: the sample weights
//! ([`sample_weights`]) and the distribution of the sampled directions (Pearson's chi-square,
//! [`chi_square`]). Samples are drawn from a seeded PCG generator, so a report is reproducible.
//!
//! The two catch different bugs. A sampler whose weight `value / pdf` is not S / pdf at the
//! direction it returns (OSL's SPI hair: weights inconsistent with the pdf) fails
//! [`sample_weights`]; a sampler whose directions do not follow its pdf, or a pdf that does not
//! integrate to 1 (a density off by a constant, in the sampler and the pdf alike, is consistent
//! with itself and passes [`sample_weights`]), fails [`chi_square`].

use super::compare::{compare_values, Comparison};
use crate::bcsdf::{HairSample, Query, RandomNumbers, SampledBcsdf};
use crate::diagnostics::viewing_direction;
use crate::geometry::{local_direction, V3};
use crate::quadrature::gauss_legendre;
use crate::random::random_numbers;
use core::f64::consts::PI;
use core::fmt;
use rand_pcg::rand_core::SeedableRng;
use rand_pcg::Pcg64Mcg;
use statrs::distribution::{ChiSquared, ContinuousCDF};

/// An outgoing direction and offset at which a sampler draws incident directions.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct View {
    /// The direction towards the viewer (unit, local frame).
    pub wo: V3<f64>,
    /// The offset h.
    pub h: f64,
}

impl View {
    /// wo at inclination `theta_o_deg` degrees ([`viewing_direction`]) and offset `h`.
    pub fn at(theta_o_deg: f64, h: f64) -> Self {
        View {
            wo: viewing_direction(theta_o_deg),
            h,
        }
    }
}

/// The views of the sampling harnesses by default: theta_o = 0, 30, -60 and 89 degrees, with
/// offsets from the centre to the edge (h = 0.3, -0.9, 1 and -0.5).
pub fn default_views() -> Vec<View> {
    vec![
        View::at(0.0, 0.3),
        View::at(30.0, -0.9),
        View::at(-60.0, 1.0),
        View::at(89.0, -0.5),
    ]
}

/// The views, sample count and seed of [`sample_weights`].
#[derive(Clone, Debug, PartialEq)]
pub struct WeightSettings {
    /// The views sampled.
    pub views: Vec<View>,
    /// Samples per view.
    pub samples_per_view: usize,
    /// The generator's seed.
    pub seed: u64,
    /// Worst rows kept in the report.
    pub worst_rows: usize,
}

impl Default for WeightSettings {
    /// [`default_views`], 10,000 samples each, seed 1, five worst rows.
    fn default() -> Self {
        WeightSettings {
            views: default_views(),
            samples_per_view: 10_000,
            seed: 1,
            worst_rows: 5,
        }
    }
}

/// The outcome of [`sample_weights`].
#[derive(Clone, Debug, PartialEq)]
pub struct WeightReport {
    /// The sampler's weight `value / pdf` (actual) against `S / pdf` of the model's own
    /// [`SampledBcsdf::pdf`] at the sampled direction (expected), per sample: its rows'
    /// queries are (sampled wi, wo, h).
    pub comparison: Comparison,
    /// The random numbers of each of [`Comparison::worst_rows`], in the same order.
    pub worst_numbers: Vec<RandomNumbers<f64>>,
}

impl WeightReport {
    /// Whether there was a sample and every sample's weight agrees within `tolerance`
    /// (relative, the measure of [`mod@super::compare`]).
    pub fn passes(&self, tolerance: f64) -> bool {
        self.comparison.rows > 0 && self.comparison.passes(tolerance)
    }
}

impl fmt::Display for WeightReport {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        writeln!(
            f,
            "sample weights (the sampler's value / pdf, got) against S / pdf at the sampled wi \
             (expected):"
        )?;
        write!(f, "{}", self.comparison)?;
        for (row, u) in self.comparison.worst_rows.iter().zip(&self.worst_numbers) {
            writeln!(
                f,
                "  row {} drew u = (lobe {}, longitudinal {}, cone {}, offset {})",
                row.index, u.lobe, u.longitudinal, u.cone, u.offset
            )?;
        }
        Ok(())
    }
}

/// Draws `settings.samples_per_view` samples at each view and compares each sample's weight
/// `value / pdf` with `S(wi) / pdf(wi)` from the model's [`Bcsdf::eval`](crate::bcsdf::Bcsdf)
/// and [`SampledBcsdf::pdf`] at the direction it returned. A BSDF given as closures goes
/// through [`from_sampler`](super::from_sampler).
pub fn sample_weights<M: SampledBcsdf<f64> + ?Sized>(
    model: &M,
    settings: &WeightSettings,
) -> WeightReport {
    let mut rng = Pcg64Mcg::seed_from_u64(settings.seed);
    let (mut queries, mut values, mut numbers) = (Vec::new(), Vec::new(), Vec::new());
    for view in &settings.views {
        for _ in 0..settings.samples_per_view {
            let u = random_numbers(&mut rng);
            let sample = model.sample(view.wo, view.h, u);
            let query = Query::new(sample.wi, view.wo, view.h);
            // The sample the model's own S and pdf give at the sampled direction.
            let expected = HairSample {
                wi: sample.wi,
                value: model.eval(&query),
                pdf: model.pdf(&query),
            }
            .weight();
            queries.push(query);
            values.push((expected, sample.weight()));
            numbers.push(u);
        }
    }
    let comparison = compare_values(&queries, &values, settings.worst_rows);
    let worst_numbers = comparison
        .worst_rows
        .iter()
        .map(|r| numbers[r.index])
        .collect();
    WeightReport {
        comparison,
        worst_numbers,
    }
}

/// The view, sample count and histogram of [`chi_square`].
#[derive(Clone, Debug, PartialEq)]
pub struct ChiSquareSettings {
    /// The view sampled.
    pub view: View,
    /// Samples drawn.
    pub samples: usize,
    /// Bins in sin(theta_i) (equal solid angle).
    pub theta_bins: usize,
    /// Bins in phi_i.
    pub phi_bins: usize,
    /// The generator's seed.
    pub seed: u64,
}

impl Default for ChiSquareSettings {
    /// theta_o = 30 degrees, h = 0.3; 200,000 samples in 32 x 64 bins; seed 1.
    fn default() -> Self {
        ChiSquareSettings {
            view: View::at(30.0, 0.3),
            samples: 200_000,
            theta_bins: 32,
            phi_bins: 64,
            seed: 1,
        }
    }
}

/// One histogram bin: its range and counts.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Bin {
    /// The range of sin(theta_i).
    pub sin_theta: [f64; 2],
    /// The range of phi_i, radians.
    pub phi: [f64; 2],
    /// Samples that fell in it.
    pub observed: f64,
    /// Samples the pdf predicts: its integral over the bin times the sample count.
    pub expected: f64,
}

/// The largest deviation of [`ChiSquareReport::pdf_integral`] from 1 that
/// [`ChiSquareReport::passes`] accepts: `1e-3`. The bins' 8 x 8-point Gauss-Legendre rules
/// integrate hairmath's `ChiangHair` pdf to 1 within 2e-5 for beta_m, beta_n >= 0.1 at the
/// default 32 x 64 bins (`tests/testing_harness.rs`).
pub const PDF_INTEGRAL_TOLERANCE: f64 = 1e-3;

/// Expected counts below this are pooled into one bin (Pearson's test needs about 5 per bin).
const MIN_EXPECTED: f64 = 5.0;

/// Gauss-Legendre order per bin and dimension of the pdf's integral.
const BIN_ORDER: usize = 8;

/// The outcome of [`chi_square`].
#[derive(Clone, Debug, PartialEq)]
pub struct ChiSquareReport {
    /// Pearson's statistic `sum (observed - expected)^2 / expected`.
    pub statistic: f64,
    /// Bins after pooling those expecting fewer than 5 samples, minus one.
    pub degrees_of_freedom: usize,
    /// The probability of a statistic at least this large if the sampler follows the pdf
    /// (NaN with fewer than two bins).
    pub p_value: f64,
    /// The pdf's integral over the sphere (1 for a density).
    pub pdf_integral: f64,
    /// Samples drawn.
    pub samples: usize,
    /// Samples with a non-finite direction or a density that is not positive (not binned).
    pub invalid_samples: usize,
    /// The bin with the largest term of the statistic.
    pub worst_bin: Option<Bin>,
}

impl ChiSquareReport {
    /// Whether the sampler follows its pdf at significance `significance` (p-value at least
    /// that), the pdf integrates to 1 within [`PDF_INTEGRAL_TOLERANCE`] and every sample is
    /// valid.
    pub fn passes(&self, significance: f64) -> bool {
        self.p_value >= significance
            && (self.pdf_integral - 1.0).abs() <= PDF_INTEGRAL_TOLERANCE
            && self.invalid_samples == 0
    }
}

impl fmt::Display for ChiSquareReport {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        writeln!(
            f,
            "chi-square of {} samples against the pdf: statistic {:.1} with {} degrees of \
             freedom, p = {:.3e}",
            self.samples, self.statistic, self.degrees_of_freedom, self.p_value
        )?;
        writeln!(
            f,
            "  the pdf integrates to {:.6} over the sphere (a density integrates to 1)",
            self.pdf_integral
        )?;
        if self.invalid_samples > 0 {
            writeln!(
                f,
                "  {} samples had a non-finite direction or a pdf <= 0",
                self.invalid_samples
            )?;
        }
        if let Some(b) = self.worst_bin {
            writeln!(
                f,
                "  worst bin: sin(theta_i) in [{:.4}, {:.4}], phi_i in [{:.4}, {:.4}]: observed \
                 {}, expected {:.1}",
                b.sin_theta[0], b.sin_theta[1], b.phi[0], b.phi[1], b.observed, b.expected
            )?;
        }
        Ok(())
    }
}

/// The histogram's bin ranges: `theta_bins` equal-solid-angle bins in sin(theta_i) (outer)
/// by `phi_bins` in phi_i.
fn bins(settings: &ChiSquareSettings) -> Vec<([f64; 2], [f64; 2])> {
    let (nt, np) = (settings.theta_bins, settings.phi_bins);
    let mut ranges = Vec::new();
    for i in 0..nt {
        let sin = |k: usize| -1.0 + 2.0 * k as f64 / nt as f64;
        for j in 0..np {
            let phi = |k: usize| -PI + 2.0 * PI * k as f64 / np as f64;
            ranges.push(([sin(i), sin(i + 1)], [phi(j), phi(j + 1)]));
        }
    }
    ranges
}

/// The index of the bin of unit direction `wi`, if it is finite (the histogram has at least
/// one bin).
fn bin_of(wi: V3<f64>, settings: &ChiSquareSettings) -> Option<usize> {
    if ![wi.x, wi.y, wi.z].iter().all(|c| c.is_finite()) {
        return None;
    }
    let index = |x: f64, n: usize| ((x * n as f64) as usize).min(n - 1);
    let i = index((wi.x.clamp(-1.0, 1.0) + 1.0) / 2.0, settings.theta_bins);
    let j = index((wi.z.atan2(wi.y) + PI) / (2.0 * PI), settings.phi_bins);
    Some(i * settings.phi_bins + j)
}

/// The pdf's integral over one bin (solid angle: d(sin theta) d(phi)), by a
/// [`BIN_ORDER`]-point Gauss-Legendre rule in each dimension.
fn bin_integral<M: SampledBcsdf<f64> + ?Sized>(
    model: &M,
    view: &View,
    (sin_range, phi_range): ([f64; 2], [f64; 2]),
) -> f64 {
    let rule = gauss_legendre(BIN_ORDER);
    let half = |r: [f64; 2]| 0.5 * (r[1] - r[0]);
    let at = |r: [f64; 2], x: f64| r[0] + half(r) * (x + 1.0);
    let mut sum = 0.0;
    for &(x, wx) in &rule {
        let sin = at(sin_range, x);
        let cos = (1.0 - sin * sin).max(0.0).sqrt();
        for &(y, wy) in &rule {
            let wi = local_direction(sin, cos, at(phi_range, y));
            sum += wx * wy * model.pdf(&Query::new(wi, view.wo, view.h));
        }
    }
    sum * half(sin_range) * half(phi_range)
}

/// Pearson's chi-square test of the directions `model` samples at `settings.view` against
/// its pdf integrated over each bin of a `theta_bins` x `phi_bins` histogram (bins expecting
/// fewer than 5 samples pooled into one), with the pdf's integral over the sphere. A BSDF given
/// as closures goes through [`from_sampler`](super::from_sampler).
///
/// The harness takes the settings as given: with no bins (or no samples) the report has no
/// degrees of freedom and a NaN p-value, and fails.
pub fn chi_square<M: SampledBcsdf<f64> + ?Sized>(
    model: &M,
    settings: &ChiSquareSettings,
) -> ChiSquareReport {
    let ranges = bins(settings);
    let mut observed = vec![0.0; ranges.len()];
    let mut invalid_samples = 0;
    let mut rng = Pcg64Mcg::seed_from_u64(settings.seed);
    for _ in 0..settings.samples {
        let sample = model.sample(settings.view.wo, settings.view.h, random_numbers(&mut rng));
        let bin = (!ranges.is_empty() && sample.pdf > 0.0)
            .then(|| bin_of(sample.wi, settings))
            .flatten();
        match bin {
            Some(k) => observed[k] += 1.0,
            None => invalid_samples += 1,
        }
    }
    let integrals: Vec<f64> = ranges
        .iter()
        .map(|&r| bin_integral(model, &settings.view, r))
        .collect();
    let expected: Vec<f64> = integrals
        .iter()
        .map(|p| p * settings.samples as f64)
        .collect();
    let pearson = pearson(&observed, &expected);
    ChiSquareReport {
        statistic: pearson.statistic,
        degrees_of_freedom: pearson.degrees_of_freedom,
        p_value: pearson.p_value,
        pdf_integral: integrals.iter().sum(),
        samples: settings.samples,
        invalid_samples,
        worst_bin: pearson.worst.map(|k| Bin {
            sin_theta: ranges[k].0,
            phi: ranges[k].1,
            observed: observed[k],
            expected: expected[k],
        }),
    }
}

/// Pearson's statistic, its degrees of freedom and p-value, and the bin of the largest term
/// (not a pooled one).
struct Pearson {
    statistic: f64,
    degrees_of_freedom: usize,
    p_value: f64,
    worst: Option<usize>,
}

/// Pearson's test of `observed` against `expected` counts (Pearson 1900: the statistic
/// `sum (o - e)^2 / e` follows the chi-square distribution with bins - 1 degrees of freedom for
/// large counts), bins expecting fewer than [`MIN_EXPECTED`] pooled into one (Cochran 1954's
/// rule of about five per bin). The p-value is the distribution's survival function (statrs).
fn pearson(observed: &[f64], expected: &[f64]) -> Pearson {
    let term = |o: f64, e: f64| (o - e) * (o - e) / e;
    let (mut statistic, mut bins, mut worst) = (0.0, 0_usize, None::<(usize, f64)>);
    let (mut pooled_o, mut pooled_e) = (0.0, 0.0);
    for (k, (&o, &e)) in observed.iter().zip(expected).enumerate() {
        if e >= MIN_EXPECTED {
            let t = term(o, e);
            statistic += t;
            bins += 1;
            if worst.is_none_or(|(_, w)| t > w) {
                worst = Some((k, t));
            }
        } else {
            pooled_o += o;
            pooled_e += e;
        }
    }
    if pooled_o > 0.0 || pooled_e > 0.0 {
        statistic += if pooled_e > 0.0 {
            term(pooled_o, pooled_e)
        } else {
            f64::INFINITY
        };
        bins += 1;
    }
    let degrees_of_freedom = bins.saturating_sub(1);
    let p_value = ChiSquared::new(degrees_of_freedom as f64)
        .map_or(f64::NAN, |distribution| distribution.sf(statistic));
    Pearson {
        statistic,
        degrees_of_freedom,
        p_value,
        worst: worst.map(|(k, _)| k),
    }
}
