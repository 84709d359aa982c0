use super::path::{cos_of_offset, Refraction};
use crate::absorption::PathLength;
use crate::fresnel::fresnel_from_outside;
use crate::real::{Real, ShaderFunction, TINY};

/// Number of attenuations the Chiang model sums: the lobes R, TT and TRT **and** the residual
/// (p >= 3), which is not a lobe of its own but all higher orders together.
pub const LOBES_WITH_RESIDUAL: usize = 4;

/// Attenuations [A_0, A_1, A_2, A_3+] from the Fresnel reflectance `f` at the entry point and
/// the transmittance `t` of one internal segment (Chiang et al. 2016, eqs. 3 and 6; pbrt-v4
/// `Ap`): `A_0 = f`, `A_1 = (1 - f)^2 t`, `A_2 = A_1 f t`, and the geometric series of all
/// longer paths `A_3+ = A_2 f t / (1 - f t)`.
///
/// The residual is written as `(1 - f)^2 f^2 t^3 / max(1 - f t, tiny)`: at h = +-1 with no
/// absorption `f = t = 1` and the true limit is 0, which the numerator gives exactly. For
/// `t = 1` the four terms sum to 1. `A_2` and `A_3+`, which fall with the square and the
/// cube of `t`, are 0 on the SIMD lanes where they are negligible
/// ([`Real::negligible_to_zero`]), as is the transmittance
/// [`FibrePath::transmittance`](crate::azimuthal::FibrePath::transmittance) gives.
#[inline(always)]
pub fn attenuations_from_fresnel<R: Real>(f: R, t: R) -> [R; LOBES_WITH_RESIDUAL] {
    const FUNCTION: ShaderFunction = crate::shader_function!(
        attenuations,
        "Chiang et al. 2016, eqs. 3 and 6",
        [fresnel, transmittance] -> {r, tt, trt, residual}
    );
    R::call(
        &FUNCTION,
        [f, t],
        #[inline(always)]
        |[f, t]| {
            let one = R::c(1.0);
            let a0 = f;
            let a1 = (one - f).sqr() * t;
            let ft = f * t;
            let a2 = (a1 * ft).negligible_to_zero();
            let a3 = (a2 * ft / (one - ft).max(TINY.get())).negligible_to_zero();
            [a0, a1, a2, a3]
        },
    )
}

/// Attenuations for offset `h` of the ray inclined at theta_o (cosine `cos_theta_o`) with
/// relative index `eta >= 1` and segment transmittance `t`: the entry Fresnel term is evaluated
/// at the true angle of incidence, cos = cos(theta_o) cos(gamma_o), gamma_o = asin h
/// ([`crate::fresnel::fresnel_from_outside`]).
pub fn attenuations<R: Real>(cos_theta_o: R, eta: R, h: R, t: R) -> [R; LOBES_WITH_RESIDUAL] {
    let cos_gamma_o = cos_of_offset(h);
    let fresnel = fresnel_from_outside(cos_theta_o * cos_gamma_o, eta, R::c(1.0) / eta);
    attenuations_from_fresnel(fresnel, t)
}

/// Attenuations `[A_0, A_1, A_2, A_3+]` at offset `h` for a ray inclined at theta (given by
/// `sin_theta` and `cos_theta >= 0`) with absorption `sigma_a` per unit radius and internal path
/// model `path`, from the geometry alone: the path of [`Refraction::path`] (Snell's law along
/// the axis, Bravais' index in the normal plane, the segment length, the entry Fresnel term)
/// and [`crate::azimuthal::FibrePath::attenuations`] (Chiang et al. 2016, eqs. 3 and 6). The reference model
/// [`crate::bcsdf::ChiangHair`] takes the same path for its attenuations.
pub fn attenuations_at_offset<R: Real>(
    h: R,
    sin_theta: R,
    cos_theta: R,
    eta: R,
    sigma_a: R,
    path: PathLength,
) -> [R; LOBES_WITH_RESIDUAL] {
    Refraction::new(sin_theta, cos_theta, eta, R::c(1.0) / eta)
        .path(h, path)
        .attenuations(sigma_a)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lossless_attenuations_sum_to_one_even_at_the_edge() {
        for &h in &[0.0, 0.5, 0.99, 1.0, -1.0] {
            for &cos_o in &[1.0, 0.5, 0.0] {
                let a = attenuations(cos_o, 1.55_f64, h, 1.0);
                let sum: f64 = a.iter().sum();
                assert!((sum - 1.0).abs() < 1e-14, "h {h} cos {cos_o}: {a:?}");
                assert!(a.iter().all(|x| x.is_finite() && *x >= 0.0));
            }
        }
        let a = attenuations(1.0_f32, 1.55, 1.0, 1.0);
        assert!(a.iter().all(|x| x.is_finite()), "{a:?}");
    }
}
