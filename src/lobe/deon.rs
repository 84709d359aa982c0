use super::bessel::BesselForm;
use crate::real::{Real, ShaderFunction};

/// d'Eon et al. 2011's energy-conserving longitudinal lobe (their eq. 7; pbrt-v4 `Mp`):
///
/// `M(theta_i; theta_o, v) = csch(1/v) / (2v) exp(-sin theta_i sin theta_o / v) I0(cos theta_i cos theta_o / v)`
///
/// normalised so that `int_{-pi/2}^{pi/2} M cos(theta_i) d theta_i = 1` for every theta_o and
/// every variance `v > 0`. It peaks at theta_i = -theta_o (directions point away from the
/// fibre, so that is the mirror direction). See [`DeonLobe`] for the evaluation.
pub fn deon_lobe<R: Real>(v: R, sin_i: R, cos_i: R, sin_o: R, cos_o: R) -> R {
    DeonLobe::new(v).eval(sin_i, cos_i, sin_o, cos_o)
}

/// d'Eon's lobe of one variance with its normalisation precomputed.
///
/// Evaluated without overflow for v from 1e-4 to 100 and beyond: with `a = cos_i cos_o / v`,
/// `csch(1/v) / (2v) = e^(-1/v) / (v (1 - e^(-2/v)))` and `I0(a) e^-a = scale e^shift`
/// ([`super::i0e_split`]),
///
/// `M = scale exp(shift - (1 - cos(theta_i + theta_o)) / v) / (v (1 - e^(-2/v)))`,
///
/// whose exponent is never positive. The cancellation in `1 - cos(theta_i + theta_o)` near the
/// peak is avoided by writing it as `sin^2 / (1 + |cos|) + (|cos| - cos)`, which is
/// `sin^2 / (1 + cos)` where cos > 0 and `1 - cos` elsewhere, without a select. One exponential,
/// one square root and one division per evaluation in single precision.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DeonLobe<R> {
    /// 1 / v.
    pub inv_v: R,
    /// 1 / (v (1 - e^(-2/v))).
    pub norm: R,
}

impl<R: Real> DeonLobe<R> {
    /// The lobe of variance `v > 0`.
    pub fn new(v: R) -> Self {
        DeonLobe {
            inv_v: R::c(1.0) / v,
            norm: R::c(1.0) / (v * one_minus_exp_neg(R::c(2.0) / v)),
        }
    }

    /// `M(theta_i; theta_o)` from the sines and (non-negative) cosines of both angles.
    #[inline(always)]
    pub fn eval(&self, sin_i: R, cos_i: R, sin_o: R, cos_o: R) -> R {
        self.eval_with(BesselForm::Full, sin_i, cos_i, sin_o, cos_o)
    }

    /// [`DeonLobe::eval`] with the Bessel function by `form`: [`BesselForm::Reduced`] gives
    /// the lobe within a relative 1.49e-4 of [`BesselForm::Full`] (the reduced `I0`'s error;
    /// the rest is shared), in shader code as its own function `deon_lobe_reduced`.
    #[inline(always)]
    pub fn eval_with(&self, form: BesselForm, sin_i: R, cos_i: R, sin_o: R, cos_o: R) -> R {
        const FULL: ShaderFunction = crate::shader_function!(
            deon_lobe,
            "d'Eon et al. 2011, eq. 7",
            [sin_i, cos_i, sin_o, cos_o]
        );
        const REDUCED: ShaderFunction = crate::shader_function!(
            deon_lobe_reduced,
            "d'Eon et al. 2011, eq. 7, with hairmath's reduced I0 (relative error 1.49e-4)",
            [sin_i, cos_i, sin_o, cos_o]
        );
        let function = match form {
            BesselForm::Full => &FULL,
            BesselForm::Reduced => &REDUCED,
        };
        let args = [sin_i, cos_i, sin_o, cos_o];
        R::call(
            function,
            args,
            #[inline(always)]
            |[sin_i, cos_i, sin_o, cos_o]| {
                let one = R::c(1.0);
                let cos_cos = cos_i * cos_o;
                let cos_sum = (-sin_i).mul_add(sin_o, cos_cos);
                let sin_sum = sin_i.mul_add(cos_o, cos_i * sin_o);
                // 1 - cos = sin^2 / (1 + |cos|) + (|cos| - cos): for cos > 0 the first term
                // alone, free of the cancellation of 1 - cos near 0; for cos <= 0 it is
                // 1 - |cos| and the second term adds 2 |cos|. No select.
                let abs_cos = cos_sum.abs();
                let one_minus_cos = sin_sum * sin_sum / (one + abs_cos) + (abs_cos - cos_sum);
                let (scale, shift) = form.i0e_split(cos_cos * self.inv_v);
                let exponent = (-one_minus_cos).mul_add(self.inv_v, shift);
                [self.norm * scale * exponent.exp_of_nonpositive().negligible_to_zero()]
            },
        )[0]
    }
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
