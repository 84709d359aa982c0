use super::path::Refraction;
use crate::absorption::PathLength;
use crate::real::{map_array, pi, safe_sqrt, wrap_angle, Real, ShaderFunction};

/// The azimuthal exit angle of path p (p internal segments) entering at angle gamma_i and
/// refracting to gamma_t: `Phi(p) = 2 p gamma_t - 2 gamma_i + p pi` (Marschner et al. 2003,
/// eq. 3; pbrt-v4 `Phi`), grouped as `p (2 gamma_t + pi) - 2 gamma_i`: each internal segment
/// turns the ray by `2 gamma_t + pi`. `p` is a real so that traced code can select it.
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
        |[p, gamma_i, gamma_t]| [p.mul_add(segment_turn(gamma_t), R::c(-2.0) * gamma_i)],
    )[0]
}

/// `2 gamma_t + pi`: the azimuth by which each internal segment of a path turns the ray
/// (Marschner et al. 2003, eq. 3: `Phi(p) = p (2 gamma_t + pi) - 2 gamma_i`).
#[inline(always)]
fn segment_turn<R: Real>(gamma_t: R) -> R {
    R::c(2.0).mul_add(gamma_t, pi::<R>())
}

/// `phi - Phi(p)` for R, TT and TRT (p = 0, 1, 2), each wrapped into [-pi, pi]
/// ([`wrap_angle`]): with `Phi(p) = p (2 gamma_t + pi) - 2 gamma_i` ([`exit_angle`]) it is
/// `u - p t` for `u = phi + 2 gamma_i` and the [`segment_turn`] t, so the three take four
/// operations before their wrapping (one multiply-add each for u and t, one subtraction and
/// one multiply-add), where three calls of [`exit_angle`] and three subtractions took twelve.
#[inline(always)]
pub(crate) fn azimuths_from_exit_angles<R: Real>(phi: R, gamma_i: R, gamma_t: R) -> [R; 3] {
    const FUNCTION: ShaderFunction = crate::shader_function!(
        exit_azimuths,
        "Marschner et al. 2003, eq. 3: phi - Phi(p) for p = 0, 1, 2, wrapped into [-pi, pi]",
        [phi, gamma_i, gamma_t] -> {r, tt, trt}
    );
    R::call(
        &FUNCTION,
        [phi, gamma_i, gamma_t],
        #[inline(always)]
        |[phi, gamma_i, gamma_t]| {
            let u = R::c(2.0).mul_add(gamma_i, phi);
            let turn = segment_turn(gamma_t);
            map_array(
                [u, u - turn, R::c(-2.0).mul_add(turn, u)],
                #[inline(always)]
                |x| wrap_angle(x),
            )
        },
    )
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
