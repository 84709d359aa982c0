use super::bessel::log_i0e;
use crate::real::Real;

/// d'Eon et al. 2011's energy-conserving longitudinal lobe (their eq. 7; pbrt-v4 `Mp`):
///
/// `M(theta_i; theta_o, v) = csch(1/v) / (2v) exp(-sin theta_i sin theta_o / v) I0(cos theta_i cos theta_o / v)`
///
/// normalised so that `int_{-pi/2}^{pi/2} M cos(theta_i) d theta_i = 1` for every theta_o and
/// every variance `v > 0`. It peaks at theta_i = -theta_o (directions point away from the
/// fibre, so that is the mirror direction).
///
/// Evaluated in log space so it is finite for v from 1e-4 to 100 and beyond. With
/// `a = cos_i cos_o / v` and `csch(1/v) / (2v) = e^(-1/v) / (v (1 - e^(-2/v)))`, the exponent is
/// `(cos(theta_i + theta_o) - 1) / v + ln(I0(a) e^-a)`, which is never positive. The
/// cancellation in `1 - cos(theta_i + theta_o)` near the peak is avoided by writing it as
/// `sin^2 / (1 + cos)` there.
pub fn deon_lobe<R: Real>(v: R, sin_i: R, cos_i: R, sin_o: R, cos_o: R) -> R {
    let one = R::c(1.0);
    let cos_sum = cos_i * cos_o - sin_i * sin_o;
    let sin_sum = sin_i * cos_o + cos_i * sin_o;
    let one_minus_cos = R::select(
        R::c(0.0).lt(cos_sum),
        sin_sum * sin_sum / (one + cos_sum.max(R::c(0.0))),
        one - cos_sum,
    );
    let a = cos_i * cos_o / v;
    let exponent = log_i0e(a) - one_minus_cos / v;
    exponent.exp() / (v * one_minus_exp_neg(R::c(2.0) / v))
}

/// `1 - e^(-t)` for `t >= 0`, accurate also for small t (Taylor series below 0.1, 8 terms,
/// truncation below 3e-14 relative).
fn one_minus_exp_neg<R: Real>(t: R) -> R {
    let small = t.min(R::c(0.1));
    // t (1 - t/2 (1 - t/3 (1 - t/4 (...)))) nested, 8 terms.
    let mut acc = R::c(1.0);
    for k in (2..=8).rev() {
        acc = R::c(1.0) - small * acc * R::c(1.0 / k as f64);
    }
    let series = small * acc;
    R::select(t.lt(R::c(0.1)), series, R::c(1.0) - (-t).exp())
}

/// Samples the lobe's cos(theta) about its axis (d'Eon 2013, "Importance sampling for
/// physically-based hair fiber models", eq. 6; pbrt-v4 `SampleMp`):
/// `cos = 1 + v ln(u + (1 - u) e^(-2/v))` for `u` in [0, 1]. `u` is floored at 1e-5 as
/// pbrt-v4 does, which keeps the logarithm finite for tiny v: samples with u < 1e-5 (probability
/// 1e-5) all land on the direction of u = 1e-5, a bias of at most 1e-5 in probability.
pub fn deon_lobe_sample_cos_theta<R: Real>(v: R, u: R) -> R {
    let u = u.max(R::c(1e-5));
    let cos = R::c(1.0) + v * (u + (R::c(1.0) - u) * (R::c(-2.0) / v).exp()).ln();
    cos.clamp(R::c(-1.0), R::c(1.0))
}
