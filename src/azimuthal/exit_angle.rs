use super::path::Refraction;
use crate::absorption::PathLength;
use crate::real::{pi, safe_sqrt, Real, ShaderFunction};

/// The azimuthal exit angle of path p (p internal segments) entering at angle gamma_i and
/// refracting to gamma_t: `Phi(p) = 2 p gamma_t - 2 gamma_i + p pi` (Marschner et al. 2003,
/// eq. 3; pbrt-v4 `Phi`). `p` is a real so that traced code can select it.
pub fn exit_angle<R: Real>(p: R, gamma_i: R, gamma_t: R) -> R {
    const FUNCTION: ShaderFunction = crate::shader_function!(
        exit_angle,
        "Marschner et al. 2003, eq. 3",
        [p, gamma_i, gamma_t]
    );
    R::call(
        &FUNCTION,
        [p, gamma_i, gamma_t],
        #[inline(always)]
        |[p, gamma_i, gamma_t]| [R::c(2.0) * p * gamma_t - R::c(2.0) * gamma_i + p * pi::<R>()],
    )[0]
}

/// sin(gamma_t) for offset h and a ray inclined at theta (given by its sine and cosine): Snell's
/// law in the normal plane with Bravais' index eta' = sqrt(eta^2 - sin^2 theta) / cos theta,
/// [`Refraction::sin_gamma_t`], which gives 0 for grazing rays (cos theta = 0), not 0/0.
/// Requires eta > 1.
pub fn refracted_offset<R: Real>(h: R, eta: R, sin_theta: R, cos_theta: R) -> R {
    Refraction::new(sin_theta, cos_theta, eta, R::c(1.0) / eta).sin_gamma_t(h)
}

/// Phi(p, h) for offset h in [-1, 1] and a ray inclined at theta (given by its sine):
/// gamma_i = asin h, gamma_t = asin(h / eta') from [`Refraction::path`].
pub fn exit_angle_of_offset<R: Real>(p: R, h: R, eta: R, sin_theta: R) -> R {
    let cos_theta = safe_sqrt(R::c(1.0) - sin_theta * sin_theta);
    let path =
        Refraction::new(sin_theta, cos_theta, eta, R::c(1.0) / eta).path(h, PathLength::Chord);
    exit_angle(p, path.gamma_o, path.gamma_t)
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::PI;

    #[test]
    fn reflection_and_transmission_through_the_centre() {
        // R at h = 0 reflects straight back: Phi = 0; TT at h = 0 goes straight through: pi.
        assert_eq!(exit_angle_of_offset(0.0, 0.0, 1.55, 0.0), 0.0);
        assert!((exit_angle_of_offset(1.0, 0.0, 1.55, 0.3) - PI).abs() < 1e-15);
        // Grazing R at h = 1: Phi = -pi (the ray continues undeflected).
        assert!((exit_angle_of_offset(0.0_f64, 1.0, 1.55, 0.0) + PI).abs() < 1e-15);
        assert!(exit_angle_of_offset(2.0_f32, 1.0, 1.55, 1.0).is_finite());
    }
}
