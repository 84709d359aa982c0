use crate::real::{Real, ShaderFunction, SQRT_TWO_PI};

/// Marschner et al. 2003's longitudinal lobe: the unit-area Gaussian
/// `g(beta, x) = exp(-x^2 / (2 beta^2)) / (beta sqrt(2 pi))` of standard deviation `beta`,
/// evaluated at `x = theta_h - alpha_p` (Marschner 2003, eq. 6 and section 4.1). Its integral
/// over the real line is 1; over theta_h in [-pi/2, pi/2] it is erf(pi / (2 sqrt 2 beta)),
/// which is 1 - 6e-7 at beta = 0.3. Requires `beta > 0`.
pub fn gaussian_lobe<R: Real>(beta: R, x: R) -> R {
    const FUNCTION: ShaderFunction =
        crate::shader_function!(gaussian_lobe, "Marschner et al. 2003, eq. 6", [beta, x]);
    R::call(
        &FUNCTION,
        [beta, x],
        #[inline(always)]
        |[beta, x]| {
            let z = x / beta;
            [(R::c(-0.5) * z * z).exp() / (beta * SQRT_TWO_PI.get::<R>())]
        },
    )[0]
}
