use crate::real::{map_array, pi, Real, ShaderLoop, Shape};

/// `(e, (1 + e)^2)` with `e = e^(-|x| / s)`, from `inv_scale = 1 / s`: the logistic density
/// is `e / (s (1 + e)^2)`. Written with `|x|` so the exponential never overflows.
#[inline(always)]
fn logistic_parts<R: Real>(x: R, inv_scale: R) -> (R, R) {
    let e = (-x.abs() * inv_scale)
        .exp_of_nonpositive()
        .negligible_to_zero();
    (e, (R::c(1.0) + e).sqr())
}

/// The logistic density `e^(-|x|/s) / (s (1 + e^(-|x|/s))^2)` of scale `s > 0` (Chiang et al.
/// 2016, eq. 12).
pub fn logistic<R: Real>(x: R, s: R) -> R {
    let (e, d) = logistic_parts(x, R::c(1.0) / s);
    e / (s * d)
}

/// The logistic cumulative distribution `1 / (1 + e^(-x/s))`, computed from `e^(-|x|/s)` so it
/// never overflows.
pub fn logistic_cdf<R: Real>(x: R, s: R) -> R {
    let e = (-x.abs() / s).exp();
    let lower = e / (R::c(1.0) + e);
    R::select(x.lt(R::c(0.0)), lower, R::c(1.0) - lower)
}

/// The logistic density restricted to [-pi, pi] and renormalised there (Chiang et al. 2016,
/// eq. 13; pbrt-v4 `TrimmedLogistic` with a = -pi, b = pi), with its constants precomputed:
/// `D(x) = e / (s m (1 + e)^2)`, `e = e^(-|x|/s)`, `m` the logistic's mass on [-pi, pi]
/// ([`trimmed_mass`]). A model stores the four fields as uniforms; [`trimmed_logistic`] and
/// [`sample_trimmed_logistic`] build them from `s`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TrimmedLogistic<R> {
    /// The scale s > 0.
    pub scale: R,
    /// 1 / s.
    pub inv_scale: R,
    /// The mass m of the untrimmed logistic on [-pi, pi].
    pub mass: R,
    /// 1 / (s m), the density's normalisation.
    pub norm: R,
}

impl<R: Real> TrimmedLogistic<R> {
    /// The trimmed logistic of scale `s > 0`.
    #[inline(always)]
    pub fn new(s: R) -> Self {
        let inv_scale = R::c(1.0) / s;
        let mass = trimmed_mass(s);
        TrimmedLogistic {
            scale: s,
            inv_scale,
            mass,
            norm: inv_scale / mass,
        }
    }

    /// The density at `x` in [-pi, pi]: `D(x) = e norm / (1 + e)^2`, `e = e^(-|x|/s)`.
    #[inline(always)]
    pub fn density(&self, x: R) -> R {
        let (e, d) = logistic_parts(x, self.inv_scale);
        e * self.norm / d
    }

    /// The density at `N` points in [-pi, pi], each with its own division: one division shared
    /// by all (`prod_q d_q`, then products of the others) made the batch kernel 6 per cent
    /// slower with AVX-512 (`benches/bcsdf.rs`, `eval/host soa`), its chain of dependent
    /// operations being longer.
    #[inline(always)]
    pub fn densities<const N: usize>(&self, x: [R; N]) -> [R; N] {
        map_array(
            x,
            #[inline(always)]
            |x| self.density(x),
        )
    }

    /// Samples the density from `u` in [0, 1] by inverting its CDF:
    /// `x = -s ln(1 / (u m + CDF(-pi)) - 1)` (pbrt-v4 `SampleTrimmedLogistic`), clamped to
    /// [-pi, pi].
    pub fn sample(&self, u: R) -> R {
        let lower = logistic_cdf(-pi::<R>(), self.scale);
        let p = (u * self.mass + lower).clamp(R::c(1e-30), R::c(1.0 - 1e-7));
        let x = -self.scale * (R::c(1.0) / p - R::c(1.0)).ln();
        x.clamp(-pi::<R>(), pi::<R>())
    }
}

/// The trimmed logistic density of scale `s` at `x` in [-pi, pi] ([`TrimmedLogistic::density`]).
pub fn trimmed_logistic<R: Real>(x: R, s: R) -> R {
    TrimmedLogistic::new(s).density(x)
}

/// The logistic's mass on [-pi, pi]: `CDF(pi) - CDF(-pi) = (1 - e) / (1 + e)` with
/// `e = e^(-pi/s)`.
pub fn trimmed_mass<R: Real>(s: R) -> R {
    let e = (-pi::<R>() / s).exp();
    (R::c(1.0) - e) / (R::c(1.0) + e)
}

/// Samples the trimmed logistic of scale `s` on [-pi, pi] from `u` in [0, 1]
/// ([`TrimmedLogistic::sample`]).
pub fn sample_trimmed_logistic<R: Real>(u: R, s: R) -> R {
    TrimmedLogistic::new(s).sample(u)
}

/// Number of periodic images summed by [`wrapped_gaussian`] (k = -4..=4).
pub const WRAPPED_GAUSSIAN_TERMS: usize = 9;

/// The Gaussian of standard deviation `beta` wrapped onto the circle:
/// `sum_k g(beta, x - 2 pi k)` for k = -4..=4 (d'Eon et al. 2011, eq. 11). For beta <= 3 the
/// omitted images are below e^-44 of the peak. `x` in [-pi, pi].
pub fn wrapped_gaussian<R: Real>(x: R, beta: R) -> R {
    const IMAGES: ShaderLoop = ShaderLoop {
        name: "wrapped_gaussian_image",
        array: "WRAPPED_GAUSSIAN_SHIFTS",
        fields: &["shift"],
        state: &[("sum", Shape::Scalar)],
        source: "hairmath::azimuthal::wrapped_gaussian",
        equation: "d'Eon et al. 2011, eq. 11",
    };
    let two_pi = 2.0 * core::f64::consts::PI;
    let norm = R::c(1.0 / (two_pi).sqrt()) / beta;
    let shifts: [[R; 1]; WRAPPED_GAUSSIAN_TERMS] =
        core::array::from_fn(|i| [R::c(two_pi * (i as f64 - 4.0))]);
    let [sum] = R::fold(&IMAGES, &shifts, [R::c(0.0)], |[sum], [shift]| {
        let z = (x - shift) / beta;
        [sum + (R::c(-0.5) * z * z).exp()]
    });
    sum * norm
}

/// Samples the wrapped Gaussian from two uniforms by the Box-Muller transform, wrapped into
/// [-pi, pi]: a Gaussian sample wrapped onto the circle is distributed exactly as the wrapped
/// density. `u0` is floored at 1e-30 to keep the logarithm finite.
pub fn sample_wrapped_gaussian<R: Real>(u0: R, u1: R, beta: R) -> R {
    let r = (R::c(-2.0) * u0.max(R::c(1e-30)).ln())
        .max(R::c(0.0))
        .sqrt();
    let angle = crate::real::wrap_angle(R::c(2.0 * core::f64::consts::PI) * u1 - pi::<R>());
    crate::real::wrap_angle(beta * r * angle.cos())
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::PI;

    fn integrate(f: impl Fn(f64) -> f64) -> f64 {
        // Composite midpoint rule on [-pi, pi] with 200k nodes (periodic, smooth integrands).
        let n = 200_000;
        let h = 2.0 * PI / n as f64;
        (0..n).map(|k| f(-PI + (k as f64 + 0.5) * h)).sum::<f64>() * h
    }

    #[test]
    fn distributions_are_normalised_on_the_circle() {
        for &s in &[0.01, 0.1, 0.5, 1.0, 2.0] {
            let m = integrate(|x| trimmed_logistic(x, s));
            assert!((m - 1.0).abs() < 1e-9, "logistic s {s}: {m}");
        }
        for &b in &[0.02, 0.3, 1.0, 3.0] {
            let m = integrate(|x| wrapped_gaussian(x, b));
            assert!((m - 1.0).abs() < 1e-9, "gaussian beta {b}: {m}");
        }
    }

    /// Box-Muller on a 600 x 600 grid of stratified (u0, u1) against the wrapped density: the
    /// largest difference between the empirical and the exact CDF (Kolmogorov distance) is below
    /// 3e-3 (a grid, not random: the bound is deterministic).
    #[test]
    fn wrapped_gaussian_sampling_follows_the_density() {
        for &beta in &[0.05, 0.5, 2.0] {
            let n = 600;
            let mut xs: Vec<f64> = (0..n * n)
                .map(|k| {
                    let (i, j) = (k / n, k % n);
                    sample_wrapped_gaussian(
                        (i as f64 + 0.5) / n as f64,
                        (j as f64 + 0.5) / n as f64,
                        beta,
                    )
                })
                .collect();
            xs.sort_by(|a, b| a.total_cmp(b));
            let (mut cdf, mut last, mut worst) = (0.0, -PI, 0.0_f64);
            for (k, &x) in xs.iter().enumerate().step_by(97) {
                // Exact CDF by the midpoint rule on [last, x], 64 nodes per step.
                let h = (x - last) / 64.0;
                cdf += (0..64)
                    .map(|q| wrapped_gaussian(last + (q as f64 + 0.5) * h, beta))
                    .sum::<f64>()
                    * h;
                last = x;
                worst = worst.max((cdf - (k as f64 + 0.5) / xs.len() as f64).abs());
            }
            assert!(worst < 3e-3, "beta {beta}: Kolmogorov distance {worst}");
        }
    }

    #[test]
    fn logistic_sampling_inverts_the_cdf() {
        for &s in &[0.02, 0.3, 1.5] {
            for k in 1..20 {
                let u = k as f64 / 20.0;
                let x = sample_trimmed_logistic(u, s);
                let cdf = (logistic_cdf(x, s) - logistic_cdf(-PI, s)) / trimmed_mass(s);
                assert!((cdf - u).abs() < 1e-9, "s {s} u {u}: x {x} cdf {cdf}");
            }
        }
    }
}
