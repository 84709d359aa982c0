//! The modified Bessel function I0, in the scaled forms the lobes need: `I0(x) e^-x` split
//! into a bounded factor and an exponent ([`i0e_split`]), and `log_i0e(x) = ln(I0(x) e^-x)`.
//! Both are finite and smooth for all finite x >= 0 up to the largest finite value of the
//! precision (`I0(x) e^-x` behaves like `1 / sqrt(2 pi x)` for large x), so lobes of any
//! variance the crate accepts (arguments up to about 1e32) never overflow. `+inf` gives the
//! limits: `log_i0e` is `-inf`, `log_i0` and `i0` are `+inf`.
//!
//! Two approximations, chosen by precision ([`Real::DOUBLE`]) in [`i0e_split`]:
//! - `f64`: the power series `I0(x) = sum_k (x^2/4)^k / (k!)^2` (42 terms) for x < 20 and
//!   the asymptotic series `I0(x) ~ e^x / sqrt(2 pi x) sum_k ((2k-1)!!)^2 / (k! (8x)^k)`
//!   (24 terms) above (Abramowitz and Stegun 9.6.10 and 9.7.1). Measured against direct
//!   quadrature of `I0(x) = (1/pi) int_0^pi e^(x cos t) dt`: relative error below 1e-13.
//! - single precision and traced code: the polynomial fits of Abramowitz and Stegun 9.8.1
//!   (|x| <= 3.75, absolute error < 1.6e-7 on I0 >= 1) and 9.8.2 (x >= 3.75, absolute error
//!   < 1.9e-7 on sqrt(x) e^-x I0(x) >= 0.3989), so relative error below 4.8e-7; evaluated in
//!   f32 the rounding of the logarithms keeps the total below 1e-6 (both measured by the tests).
//!
//! And one reduced form, the same in every precision ([`i0e_split_reduced`], [`BesselForm`]):
//! the same two-branch structure, `I0(x)` a cubic in `(x/s)^2` below `s = 2.65` and
//! `sqrt(x) e^-x I0(x)` a cubic in `s/x` above, each the Chebyshev interpolant of the function
//! at four nodes of its variable on [0, 1] (the switch point balances the two branches'
//! errors). Measured against direct quadrature: relative error at most 1.49e-4 for every
//! x >= 0; it costs 6 multiply-adds where the single-precision form costs 14.

use crate::real::{horner, horner_named, NamedConstant, Real};

const SERIES_END: f64 = 20.0;
const SERIES_TERMS: usize = 42;
const ASYMPTOTIC_TERMS: usize = 24;
/// Above this argument `2 pi x` could overflow, so `sqrt(2 pi x)` is formed as
/// `sqrt(2 pi) sqrt(x)` (below it the one square root of the product is kept).
const HUGE: f64 = 1e300;

/// Power-series coefficients 1/(k!)^2 of I0 in x^2/4.
const SERIES: [f64; SERIES_TERMS] = {
    let mut c = [1.0; SERIES_TERMS];
    let mut k = 1;
    while k < SERIES_TERMS {
        c[k] = c[k - 1] / ((k * k) as f64);
        k += 1;
    }
    c
};

/// Asymptotic-series coefficients ((2k-1)!!)^2 / k! of sqrt(2 pi x) e^-x I0(x) in 1/(8x).
const ASYMPTOTIC: [f64; ASYMPTOTIC_TERMS] = {
    let mut c = [1.0; ASYMPTOTIC_TERMS];
    let mut k = 1;
    while k < ASYMPTOTIC_TERMS {
        c[k] = c[k - 1] * (((2 * k - 1) * (2 * k - 1)) as f64) / (k as f64);
        k += 1;
    }
    c
};

/// `I0(x) e^-x` split as `(scale, shift)` with `I0(x) e^-x = scale * e^shift`, `shift <= 0`,
/// for `x >= 0` (negative arguments and NaN are treated as 0: the lobes' hot path, which never
/// passes them, spends no operation on them). Callers fold `shift` into an exponential they
/// compute anyway, so the lobes need no logarithm: below the switch point the series gives
/// `scale = I0(x)`, `shift = -x`; above it the asymptotic form gives `scale = sqrt(x) e^-x I0(x)
/// / sqrt(x)`, `shift = 0`. Neither part overflows for any finite x, and `scale` is positive
/// for every finite x (it is 0 at `+inf`, the limit).
#[inline(always)]
pub fn i0e_split<R: Real>(x: R) -> (R, R) {
    match R::DOUBLE {
        true => split(
            x,
            R::c(SERIES_END),
            #[inline(always)]
            |small| series_near(small),
            #[inline(always)]
            |large| series_far(large),
        ),
        false => ABRAMOWITZ_STEGUN.split(x),
    }
}

/// [`i0e_split`] by the reduced form (module documentation) in every precision: relative
/// error at most 1.49e-4, for lobes whose error budget is far above the precision's.
#[inline(always)]
pub fn i0e_split_reduced<R: Real>(x: R) -> (R, R) {
    REDUCED.split(x)
}

/// Which approximation of `I0(x) e^-x` a lobe evaluates.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum BesselForm {
    /// [`i0e_split`]: accurate to the precision.
    Full,
    /// [`i0e_split_reduced`]: relative error at most 1.49e-4, 8 fewer multiply-adds in single
    /// precision and shader code.
    Reduced,
}

impl BesselForm {
    /// `I0(x) e^-x` split as [`i0e_split`] does, by this form.
    #[inline(always)]
    pub fn i0e_split<R: Real>(self, x: R) -> (R, R) {
        match self {
            BesselForm::Full => i0e_split(x),
            BesselForm::Reduced => i0e_split_reduced(x),
        }
    }
}

/// `(scale, shift)` (the [`i0e_split`] contract) from the branches on either side of `switch`:
/// `near(min(x, switch))`, I0 itself, and `far(max(x, switch))`, `I0 e^-x`. A branch no lane
/// needs is skipped ([`Real::every_lane`]); the other is evaluated on the same clamped
/// argument as when both are, so every lane's value is the same either way.
#[inline(always)]
fn split<R: Real>(x: R, switch: R, near: impl Fn(R) -> R, far: impl Fn(R) -> R) -> (R, R) {
    let x = x.max(R::c(0.0));
    let is_near = x.lt(switch);
    if R::every_lane(is_near) {
        return (near(x.min(switch)), -x);
    }
    if R::every_lane(!is_near) {
        return (far(x.max(switch)), R::c(0.0));
    }
    (
        R::select(is_near, near(x.min(switch)), far(x.max(switch))),
        R::select(is_near, -x, R::c(0.0)),
    )
}

/// I0 by its power series.
#[inline(always)]
fn series_near<R: Real>(small: R) -> R {
    horner(small * small * R::c(0.25), &SERIES)
}

/// `sqrt(2 pi x) e^-x I0 / sqrt(2 pi x)` by the asymptotic series.
#[inline(always)]
fn series_far<R: Real>(large: R) -> R {
    // sqrt(2 pi x), without overflowing 2 pi x for x above f64::MAX / (2 pi).
    let root = R::select(
        large.lt(R::c(HUGE)),
        (R::c(2.0 * core::f64::consts::PI) * large).sqrt(),
        R::c((2.0 * core::f64::consts::PI).sqrt()) * large.sqrt(),
    );
    horner(R::c(0.125) / large, &ASYMPTOTIC) / root
}

/// A two-branch polynomial form of I0: `I0(x) = near((x/s)^2)` below the switch point `s`
/// and `sqrt(x) e^-x I0(x) = far(s/x)` above it, both polynomials by increasing power.
struct BranchPolynomials {
    /// `s`.
    switch: &'static NamedConstant,
    /// `1 / s`.
    inv_switch: &'static NamedConstant,
    /// The near branch's coefficients.
    near: &'static NamedConstant,
    /// The far branch's.
    far: &'static NamedConstant,
}

impl BranchPolynomials {
    /// `I0(x) e^-x` split as [`i0e_split`] does, by these polynomials.
    #[inline(always)]
    fn split<R: Real>(&self, x: R) -> (R, R) {
        split(
            x,
            self.switch.get::<R>(),
            #[inline(always)]
            |small| self.near(small),
            #[inline(always)]
            |large| self.far(large),
        )
    }

    /// I0 by the near polynomial, for `small` at most the switch point.
    #[inline(always)]
    fn near<R: Real>(&self, small: R) -> R {
        let t = small * self.inv_switch.get::<R>();
        horner_named(t * t, self.near)
    }

    /// `e^-x I0` by the far polynomial, for `large` at least the switch point.
    #[inline(always)]
    fn far<R: Real>(&self, large: R) -> R {
        // One division: s / x and 1 / sqrt(x) both from 1 / x.
        let inv = R::c(1.0) / large;
        horner_named(self.switch.get::<R>() * inv, self.far) * inv.sqrt()
    }
}

/// Abramowitz and Stegun 9.8.1 and 9.8.2.
const ABRAMOWITZ_STEGUN: BranchPolynomials = BranchPolynomials {
    switch: &AS_9_8_SWITCH,
    inv_switch: &AS_9_8_INV_SWITCH,
    near: &AS_9_8_1,
    far: &AS_9_8_2,
};

/// The reduced form (module documentation).
const REDUCED: BranchPolynomials = BranchPolynomials {
    switch: &REDUCED_SWITCH,
    inv_switch: &REDUCED_INV_SWITCH,
    near: &REDUCED_NEAR,
    far: &REDUCED_FAR,
};

/// `ln(I0(x) e^-x)` for `x >= 0` (negative arguments and NaN are treated as 0): finite for
/// every finite x (about `-0.5 ln(2 pi x)` for large x: -355.4 at 1e308 in `f64`), `-inf` at
/// `+inf` (the limit).
pub fn log_i0e<R: Real>(x: R) -> R {
    let (scale, shift) = i0e_split(x);
    scale.ln() + shift
}

/// `ln I0(x)` for `x >= 0` (negative arguments and NaN are treated as 0): finite for every
/// finite x, `+inf` at `+inf` (the logarithm of the scaled form is taken at the largest finite
/// value, so that `-inf + inf` never forms).
pub fn log_i0<R: Real>(x: R) -> R {
    let x = x.max(R::c(0.0));
    log_i0e(x.min(R::c(largest_finite::<R>()))) + x
}

/// `I0(x)` (even in x): finite for `|x|` up to about 713 in `f64` and 91 in `f32`, `+inf`
/// beyond (the true value overflows), never 0 or NaN for a non-NaN x.
pub fn i0<R: Real>(x: R) -> R {
    log_i0(x.abs()).exp()
}

/// The largest finite value of the precision `R` (`f64::MAX`, or `f32::MAX` for the single
/// precision types).
fn largest_finite<R: Real>() -> f64 {
    if R::DOUBLE {
        f64::MAX
    } else {
        f64::from(f32::MAX)
    }
}

/// The switch point 3.75 between Abramowitz and Stegun 9.8.1 and 9.8.2.
const AS_9_8_SWITCH: NamedConstant = NamedConstant {
    name: "BESSEL_I0_SWITCH",
    meaning: "3.75, where I0 switches from Abramowitz and Stegun 9.8.1 to 9.8.2",
    values: &[3.75],
};
/// `1 / 3.75`.
const AS_9_8_INV_SWITCH: NamedConstant = NamedConstant {
    name: "BESSEL_I0_INV_SWITCH",
    meaning: "1 / 3.75, the argument scale of Abramowitz and Stegun 9.8.1",
    values: &[1.0 / 3.75],
};
/// Abramowitz and Stegun 9.8.1: I0(x) = sum a_k (x/3.75)^(2k), |x| <= 3.75.
const AS_9_8_1: NamedConstant = NamedConstant {
    name: "BESSEL_I0_NEAR",
    meaning: "Abramowitz and Stegun 9.8.1: I0(x) = sum a_k (x/3.75)^(2k), |x| <= 3.75",
    values: &[
        1.0, 3.5156229, 3.0899424, 1.2067492, 0.2659732, 0.0360768, 0.0045813,
    ],
};
/// Abramowitz and Stegun 9.8.2: sqrt(x) e^-x I0(x) = sum b_k (3.75/x)^k, x >= 3.75.
const AS_9_8_2: NamedConstant = NamedConstant {
    name: "BESSEL_I0_FAR",
    meaning: "Abramowitz and Stegun 9.8.2: sqrt(x) e^-x I0(x) = sum b_k (3.75/x)^k, x >= 3.75",
    values: &[
        0.39894228,
        0.01328592,
        0.00225319,
        -0.00157565,
        0.00916281,
        -0.02057706,
        0.02635537,
        -0.01647633,
        0.00392377,
    ],
};

/// The reduced form's switch point.
const REDUCED_SWITCH: NamedConstant = NamedConstant {
    name: "BESSEL_I0_REDUCED_SWITCH",
    meaning: "2.65, where the reduced I0 switches from its near cubic to its far one",
    values: &[2.65],
};
/// `1 / 2.65`.
const REDUCED_INV_SWITCH: NamedConstant = NamedConstant {
    name: "BESSEL_I0_REDUCED_INV_SWITCH",
    meaning: "1 / 2.65, the argument scale of the reduced I0's near cubic",
    values: &[1.0 / 2.65],
};
/// The reduced near cubic: the Chebyshev interpolant of `I0(2.65 sqrt(u))` on u in [0, 1] at
/// four nodes, by increasing power of u (`tests::reduced_coefficients_are_the_interpolants`
/// recomputes them).
const REDUCED_NEAR: NamedConstant = NamedConstant {
    name: "BESSEL_I0_REDUCED_NEAR",
    meaning: "reduced I0(x) = sum a_k (x/2.65)^(2k), x <= 2.65 (Chebyshev interpolant, 4 nodes)",
    values: &[
        0.999_851_783_097_226_6,
        1.760_357_964_700_259,
        0.747_158_844_617_489_9,
        0.186_674_186_153_887_87,
    ],
};
/// The reduced far cubic: the Chebyshev interpolant of `sqrt(x) e^-x I0(x)` in `w = 2.65/x`
/// on (0, 1] at four nodes, by increasing power of w.
const REDUCED_FAR: NamedConstant = NamedConstant {
    name: "BESSEL_I0_REDUCED_FAR",
    meaning: "reduced sqrt(x) e^-x I0(x) = sum b_k (2.65/x)^k, x >= 2.65 (Chebyshev interpolant, 4 nodes)",
    values: &[
        0.398_944_575_873_187,
        0.018_769_224_378_367_755,
        0.003_615_894_914_835_937_6,
        0.003_608_975_486_802_279_4,
    ],
};

#[cfg(test)]
mod tests {
    use super::*;

    /// Independent reference: e^-x I0(x) = (1/pi) int_0^pi e^(x (cos t - 1)) dt by the
    /// trapezoid rule, which converges geometrically for this periodic integrand; the node count
    /// is doubled until two estimates agree to 4e-15 relative (then both are at rounding level).
    fn i0e_by_quadrature(x: f64) -> f64 {
        let estimate = |n: usize| {
            let h = std::f64::consts::PI / n as f64;
            let f = |t: f64| (x * (t.cos() - 1.0)).exp();
            let inner: f64 = (1..n).map(|k| f(k as f64 * h)).sum();
            (inner + 0.5 * (f(0.0) + f(std::f64::consts::PI))) * h / std::f64::consts::PI
        };
        let mut n = 64;
        let mut prev = estimate(n);
        loop {
            n *= 2;
            let next = estimate(n);
            if (next - prev).abs() <= 4e-15 * next {
                return next;
            }
            assert!(
                n < 1 << 22,
                "quadrature for x = {x} did not converge: {prev} {next}"
            );
            prev = next;
        }
    }

    fn arguments() -> Vec<f64> {
        let mut xs = vec![
            0.0, 1e-8, 0.3, 1.0, 3.74, 3.75, 3.76, 7.5, 14.99, 19.99, 20.0, 20.01, 40.0,
        ];
        xs.extend([1e2, 1e3, 1e4]);
        xs
    }

    #[test]
    fn double_precision_is_accurate_to_1e_13() {
        for x in arguments() {
            let want = i0e_by_quadrature(x).ln();
            let got = log_i0e(x);
            // ln accuracy relative to I0 accuracy: |d ln I0| = |dI0/I0|.
            assert!((got - want).abs() < 1e-13, "x = {x}: {got} vs {want}");
        }
        assert!((i0(1.0_f64) - 1.266_065_877_752_008_4).abs() < 1e-15);
    }

    #[test]
    fn huge_and_infinite_arguments_give_the_limits() {
        // ln(I0(x) e^-x) ~ -0.5 ln(2 pi x) - (asymptotic terms of order 1/x).
        let want = -0.5 * (2.0 * std::f64::consts::PI).ln() - 0.5 * 1e308_f64.ln();
        assert!(
            (log_i0e(1e308_f64) - want).abs() < 1e-12,
            "{}",
            log_i0e(1e308_f64)
        );
        assert!((log_i0e(1e300_f64) - log_i0e(1.0000001e300_f64)).abs() < 1e-6);
        assert_eq!(log_i0(1e308_f64), 1e308);
        assert_eq!(i0(1e308_f64), f64::INFINITY);
        assert_eq!(log_i0e(f64::INFINITY), f64::NEG_INFINITY);
        assert_eq!(log_i0(f64::INFINITY), f64::INFINITY);
        assert_eq!(i0(f64::NEG_INFINITY), f64::INFINITY);
        assert!(log_i0e(f32::MAX).is_finite() && log_i0(f32::INFINITY) == f32::INFINITY);
        assert_eq!(i0(100.0_f32), f32::INFINITY);
    }

    #[test]
    fn single_precision_polynomials_meet_their_published_bound() {
        for x in arguments() {
            let want = i0e_by_quadrature(x);
            // The polynomials themselves, in f64: A&S's bounds are absolute, 1.6e-7 on I0 >= 1
            // and 1.9e-7 on sqrt(x) e^-x I0 >= 0.3989, so at most 4.8e-7 relative.
            let poly = match x < 3.75 {
                true => ABRAMOWITZ_STEGUN.near(x) * (-x).exp(),
                false => ABRAMOWITZ_STEGUN.far(x),
            };
            assert!(
                ((poly - want) / want).abs() < 4.8e-7,
                "x = {x}: {poly} vs {want}"
            );
            // Evaluated in f32: the bound plus the rounding of ln and exp.
            let got = (log_i0e(x as f32) as f64).exp();
            assert!(
                ((got - want) / want).abs() < 1e-6,
                "x = {x}: {got} vs {want}"
            );
        }
    }

    /// A branch that no lane needs is skipped, and every lane's value is the same whether its
    /// neighbours take the same branch (one evaluated) or not (both and a select): SIMD lanes
    /// of all-near, all-far and mixed arguments give the scalar `f32` bits (`wide`'s lanes
    /// round as `f32` does), in both forms.
    #[test]
    fn skipping_a_branch_changes_no_value() {
        use wide::f32x8;
        let near: [f32; 8] = [0.0, 0.1, 0.5, 1.0, 2.0, 2.6, 3.0, 3.7];
        let far: [f32; 8] = [3.75, 4.0, 5.0, 8.0, 20.0, 100.0, 1e4, 1e30];
        let mixed: [f32; 8] = core::array::from_fn(|k| [near, far][k % 2][k]);
        for form in [BesselForm::Full, BesselForm::Reduced] {
            for x in [near, far, mixed] {
                let (scale, shift) = form.i0e_split(f32x8::from(x));
                for (k, &x) in x.iter().enumerate() {
                    let (want_scale, want_shift) = form.i0e_split(x);
                    assert_eq!(scale.to_array()[k].to_bits(), want_scale.to_bits(), "{x}");
                    assert_eq!(shift.to_array()[k].to_bits(), want_shift.to_bits(), "{x}");
                }
            }
        }
        // The instruction sets' lanes fuse multiply-adds, so only compare them with themselves:
        // each lane of the mixed arguments against the same argument among all-near or all-far.
        #[cfg(target_arch = "x86_64")]
        {
            use crate::real::{Avx2Lanes, Avx512Lanes, InstructionSet};
            fn same_either_way<L: Real + From<[f32; N]>, const N: usize>(
                to_array: impl Fn(L) -> [f32; N],
                [near, far, mixed]: [[f32; 8]; 3],
            ) {
                let bits = |x: [f32; 8]| {
                    let lanes: [f32; N] = core::array::from_fn(|k| x[k % 8]);
                    let (scale, shift) = i0e_split(L::from(lanes));
                    (
                        to_array(scale).map(f32::to_bits),
                        to_array(shift).map(f32::to_bits),
                    )
                };
                let (uniform, both) = ([bits(near), bits(far)], bits(mixed));
                for k in 0..N {
                    let alone = uniform[k % 2];
                    let x = mixed[k % 8];
                    assert_eq!((both.0[k], both.1[k]), (alone.0[k], alone.1[k]), "{x}");
                }
            }
            if InstructionSet::Avx2.is_supported() {
                same_either_way::<Avx2Lanes, 8>(Avx2Lanes::to_array, [near, far, mixed]);
            }
            if InstructionSet::Avx512.is_supported() {
                same_either_way::<Avx512Lanes, 16>(Avx512Lanes::to_array, [near, far, mixed]);
            }
        }
    }

    /// The reduced form's value `I0(x) e^-x` in f64.
    fn reduced(x: f64) -> f64 {
        let (scale, shift) = i0e_split_reduced(x);
        scale * shift.exp()
    }

    #[test]
    fn reduced_form_is_within_its_documented_error() {
        // Quadrature up to 1e3, the full f64 form (1e-13 against quadrature up to 1e4, above)
        // beyond, where the trapezoid rule needs millions of nodes.
        let dense = (0..=1600).map(|k| k as f64 * 0.025);
        let wide = (0..=100).map(|k| 10f64.powf(1.6 + 0.2 * k as f64));
        let worst = dense
            .chain(wide)
            .map(|x| {
                let want = match x <= 1e3 {
                    true => i0e_by_quadrature(x),
                    false => i0e_split(x).0 * i0e_split(x).1.exp(),
                };
                ((reduced(x) - want) / want).abs()
            })
            .fold(0.0, f64::max);
        // The documented maximum, neither exceeded nor loose.
        assert!((1.4e-4..=1.49e-4).contains(&worst), "{worst:e}");
        // In f32 the same bound with the rounding of a few operations.
        for x in [0.0_f32, 0.5, 2.649, 2.65, 2.651, 10.0, 1e3, 1e20] {
            let (scale, shift) = i0e_split_reduced(x);
            let got = f64::from(scale) * f64::from(shift).exp();
            let (scale, shift) = i0e_split(f64::from(x));
            let want = scale * shift.exp();
            assert!(
                ((got - want) / want).abs() < 1.5e-4,
                "x = {x}: {got} vs {want}"
            );
        }
    }

    /// The Chebyshev interpolant of `f` on [0, 1] at `n` nodes, by increasing power.
    fn chebyshev_interpolant(f: impl Fn(f64) -> f64, n: usize) -> Vec<f64> {
        let angle = |j: usize| std::f64::consts::PI * (j as f64 + 0.5) / n as f64;
        let values: Vec<f64> = (0..n).map(|j| f(0.5 + 0.5 * angle(j).cos())).collect();
        // Chebyshev coefficients in t = 2u - 1, then the monomials of t, then of u.
        let mut in_t = vec![0.0; n];
        let mut t_k = vec![vec![1.0], vec![0.0, 1.0]];
        for k in 2..n {
            let mut next = vec![0.0; k + 1];
            for (i, c) in t_k[k - 1].iter().enumerate() {
                next[i + 1] += 2.0 * c;
            }
            for (i, c) in t_k[k - 2].iter().enumerate() {
                next[i] -= c;
            }
            t_k.push(next);
        }
        for (k, polynomial) in t_k.iter().take(n).enumerate() {
            let weight = if k == 0 { 1.0 } else { 2.0 } / n as f64;
            let c: f64 = (0..n)
                .map(|j| values[j] * (k as f64 * angle(j)).cos())
                .sum();
            for (i, p) in polynomial.iter().enumerate() {
                in_t[i] += weight * c * p;
            }
        }
        let binomial =
            |n: usize, k: usize| (0..k).fold(1.0, |b, i| b * (n - i) as f64 / (i + 1) as f64);
        let mut in_u = vec![0.0; n];
        for (i, a) in in_t.iter().enumerate() {
            for (j, u) in in_u.iter_mut().enumerate().take(i + 1) {
                let sign = if (i - j) % 2 == 0 { 1.0 } else { -1.0 };
                *u += a * binomial(i, j) * 2f64.powi(j as i32) * sign;
            }
        }
        in_u
    }

    #[test]
    fn reduced_coefficients_are_the_interpolants() {
        let s = REDUCED_SWITCH.values[0];
        let full = |x: f64| {
            let (scale, shift) = i0e_split(x);
            scale * shift.exp()
        };
        let near = chebyshev_interpolant(|u| full(s * u.sqrt()) * (s * u.sqrt()).exp(), 4);
        // At w = 0 (x infinite) the far function is its limit 1/sqrt(2 pi).
        let far_of = |w: f64| match w > 0.0 {
            true => (s / w).sqrt() * full(s / w),
            false => 1.0 / (2.0 * std::f64::consts::PI).sqrt(),
        };
        let far = chebyshev_interpolant(far_of, 4);
        // Agreement to rounding, relative to the largest coefficient (the conversion to
        // monomials loses a few digits); another node count or degree differs by 1e-4.
        for (got, want) in [(REDUCED_NEAR.values, near), (REDUCED_FAR.values, far)] {
            for (g, w) in got.iter().zip(&want) {
                assert!((g - w).abs() < 1e-13 * want[0], "{got:?} vs {want:?}");
            }
        }
        assert_eq!(REDUCED_INV_SWITCH.values[0], 1.0 / s);
    }

    use proptest::strategy::Strategy;

    proptest::proptest! {
        /// Over the whole domain the reduced form is finite, its shift never positive, and it
        /// is within its error of the full form.
        #[test]
        fn reduced_form_holds_over_the_domain(
            x in proptest::prop_oneof![0.0..40.0_f64, (-3.0..30.0_f64).prop_map(|e| 10f64.powf(e))]
        ) {
            let (scale, shift) = i0e_split_reduced(x);
            let (full_scale, full_shift) = i0e_split(x);
            proptest::prop_assert!(scale.is_finite() && scale > 0.0 && shift <= 0.0);
            let ratio = scale / full_scale * (shift - full_shift).exp();
            proptest::prop_assert!((ratio - 1.0).abs() < 1.5e-4, "x = {}: {}", x, ratio);
        }
    }
}
