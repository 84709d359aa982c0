use crate::error::ParamError;
use crate::real::{Real, ShaderFunction, FOUR_PI};

/// The Henyey-Greenstein function exactly as Gerard prints it (his eq. 6):
/// `G = (1 / 4 pi) (1 - g^2) / (1 + g^2 - 2 g cos theta)^(3/2)`.
///
/// This is the phase function normalised over the **sphere** (`int G dOmega = 1`). Gerard uses
/// it as a lobe in the single angle `theta_h`, where it is not normalised: its integral over
/// theta in [-pi, pi] is `E(k) / (pi (1 - |g|))` (see [`HenyeyGreenstein`]), 1.32 for his
/// g = 0.752. Kept literally because his fitted g values were computed with it.
/// Requires `|g| < 1`.
#[inline(always)]
pub fn hg_gerard_printed<R: Real>(g: R, cos_theta: R) -> R {
    let d = R::c(1.0) + g * g - R::c(2.0) * g * cos_theta;
    (R::c(1.0) - g * g) / (FOUR_PI.get::<R>() * d * d.sqrt())
}

/// Henyey-Greenstein as a longitudinal lobe in one angle, normalised to unit integral over
/// theta in [-pi, pi]: `M(theta) = (1 - g^2) / (N(g) (1 + g^2 - 2 g cos theta)^(3/2))`.
///
/// The normaliser is closed-form: with `k^2 = 4|g| / (1 + |g|)^2`,
/// `int_{-pi}^{pi} (1 - g^2) / (1 + g^2 - 2g cos t)^(3/2) dt = 4 E(k) / (1 - |g|)`,
/// where `E` is the complete elliptic integral of the second kind (from
/// `int_0^pi dt / (a - b cos t)^(3/2) = 2 E(k) / ((a - b) sqrt(a + b))`, `k^2 = 2b / (a + b)`;
/// the lobe tests confirm the unit integral by quadrature). It is computed once per lobe in
/// `f64` by the arithmetic-geometric mean, so evaluation costs one square root.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct HenyeyGreenstein {
    g: f64,
    inverse_norm: f64,
}

impl HenyeyGreenstein {
    /// The lobe with asymmetry `g`.
    ///
    /// # Errors
    /// `g` outside (-1, 1).
    pub fn new(g: f64) -> Result<Self, ParamError> {
        let g = ParamError::check(
            "g",
            g,
            "the Henyey-Greenstein asymmetry must be in (-1, 1)",
            |v| v.abs() < 1.0,
        )?;
        let a = g.abs();
        let k2 = 4.0 * a / ((1.0 + a) * (1.0 + a));
        let norm = 4.0 * elliptic_e(k2) / (1.0 - a);
        Ok(HenyeyGreenstein {
            g,
            inverse_norm: 1.0 / norm,
        })
    }

    /// The asymmetry parameter g.
    pub fn g(&self) -> f64 {
        self.g
    }

    /// `M(theta)` for theta given by its cosine.
    pub fn eval<R: Real>(&self, cos_theta: R) -> R {
        const FUNCTION: ShaderFunction = crate::shader_function!(
            henyey_greenstein,
            "Henyey and Greenstein 1941, normalised on the hair's circle (Gerard et al. 2023)",
            [cos_theta]
        );
        R::call(
            &FUNCTION,
            [cos_theta],
            #[inline(always)]
            |[cos_theta]| {
                let g = R::c(self.g);
                let d = R::c(1.0) + g * g - R::c(2.0) * g * cos_theta;
                [R::c((1.0 - self.g * self.g) * self.inverse_norm) / (d * d.sqrt())]
            },
        )[0]
    }
}

/// Abramowitz and Stegun 17.3.36: `E(m) = sum_k a_k m1^k + ln(1/m1) sum_k b_k m1^k`,
/// `m1 = 1 - m`, `|error| <= 2e-8` on [0, 1): the coefficients `a_0..a_4`, then `b_1..b_4`.
const ELLIPTIC_E_POLYNOMIAL: ([f64; 5], [f64; 4]) = (
    [
        1.0,
        0.443_251_414_63,
        0.062_606_012_20,
        0.047_573_835_46,
        0.017_365_064_51,
    ],
    [
        0.249_983_683_10,
        0.092_001_800_37,
        0.040_696_975_26,
        0.005_264_496_39,
    ],
);

/// The factor `(1 - g^2) / N(g)` of the Henyey-Greenstein lobe normalised on the circle
/// ([`HenyeyGreenstein`]: `M = factor / (1 + g^2 - 2 g cos theta)^(3/2)`), in precision `R`,
/// so that shader code can normalise a lobe whose g varies: `N(g) = 4 E(k) / (1 - |g|)` with
/// the complete elliptic integral `E(k^2 = 4|g| / (1 + |g|)^2)` by Abramowitz and Stegun's
/// polynomial 17.3.36 (`|error| <= 2e-8` and `E >= 1`, so the factor is within 2e-8 relative
/// of the arithmetic-geometric mean's; 1.6e-8 measured over g in [-0.9999, 0.9999], unit
/// test). Domain: |g| < 1 (|g| is clamped to
/// `1 - 2^-20`); the result is finite and positive.
pub fn hg_circle_factor<R: Real>(g: R) -> R {
    let one = R::c(1.0);
    let a = g.abs().min(R::c(1.0 - 1.0 / 1_048_576.0));
    let ratio = (one - a) / (one + a);
    let m1 = ratio * ratio;
    let (ca, cb) = ELLIPTIC_E_POLYNOMIAL;
    let mut power = m1;
    let (mut pa, mut pb) = (R::c(ca[0]), R::c(0.0));
    for k in 0..4 {
        pa += R::c(ca[k + 1]) * power;
        pb += R::c(cb[k]) * power;
        power *= m1;
    }
    let e = pa - pb * m1.ln();
    (one - g * g) * (one - a) / (R::c(4.0) * e)
}

/// Complete elliptic integral of the second kind E(m), parameter `m = k^2` in [0, 1], by the
/// arithmetic-geometric mean (Abramowitz and Stegun 17.6): with a0 = 1, b0 = sqrt(1 - m),
/// c0^2 = m, `E = K (1 - sum_n 2^(n-1) c_n^2)`, `K = pi / (2 AGM)`.
fn elliptic_e(m: f64) -> f64 {
    if m >= 1.0 {
        return 1.0;
    }
    let (mut a, mut b) = (1.0_f64, (1.0 - m).sqrt());
    let mut sum = 0.5 * m;
    let mut weight = 0.5;
    for _ in 0..64 {
        let c = 0.5 * (a - b);
        (a, b) = (0.5 * (a + b), (a * b).sqrt());
        weight *= 2.0;
        sum += weight * c * c;
        // Quadratic convergence: the next c would be about c^2 / (4a), below 1e-20 here. Going
        // on would add rounding noise times 2^n.
        if c.abs() < 1e-10 * a {
            break;
        }
    }
    core::f64::consts::FRAC_PI_2 / a * (1.0 - sum)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn elliptic_e_known_values() {
        assert!((elliptic_e(0.0) - core::f64::consts::FRAC_PI_2).abs() < 1e-15);
        // E(m = 0.5) = 1.3506438810476755 (Abramowitz and Stegun table 17.6).
        assert!((elliptic_e(0.5) - 1.350_643_881_047_675_5).abs() < 1e-14);
        assert!((elliptic_e(1.0) - 1.0).abs() < 1e-15);
    }

    #[test]
    fn the_shader_factor_matches_the_arithmetic_geometric_mean() {
        let mut worst: f64 = 0.0;
        for i in 0..=2000 {
            let g = -0.9999 + 1.9998 * f64::from(i) / 2000.0;
            let a = g.abs();
            let exact =
                (1.0 - g * g) * (1.0 - a) / (4.0 * elliptic_e(4.0 * a / ((1.0 + a) * (1.0 + a))));
            worst = worst.max((hg_circle_factor(g) / exact - 1.0).abs());
        }
        assert!(worst <= 2e-8, "worst relative error {worst:e}");
        let lobe = HenyeyGreenstein::new(0.7).unwrap();
        let d: f64 = 1.0 + 0.49 - 1.4 * 0.3;
        assert!((hg_circle_factor(0.7) / (d * d.sqrt()) / lobe.eval(0.3) - 1.0).abs() < 2e-8);
    }

    #[test]
    fn invalid_g_is_rejected() {
        assert!(HenyeyGreenstein::new(1.0).is_err());
        assert!(HenyeyGreenstein::new(f64::NAN).is_err());
    }
}
