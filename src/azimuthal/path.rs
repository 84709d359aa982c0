//! The path of a ray through the fibre: refraction by an inclined ray (Snell's law along the
//! axis, Bravais' index in the normal plane), the entry and exit angles, the length of each
//! internal segment and the entry Fresnel reflectance. Every model that needs the geometry of
//! a path (the reference BCSDF, the attenuations of the fits and the real-time models) takes it
//! from here.

use super::attenuation::{attenuations_from_fresnel, LOBES_WITH_RESIDUAL};
use crate::absorption::{segment_length, PathLength};
use crate::fresnel::fresnel_of_cosines;
use crate::real::{safe_sqrt, Real, ShaderFunction};

/// Refraction into a fibre of relative index `eta` of a ray inclined at theta to its normal
/// plane, for any offset: the quantities that do not depend on h.
///
/// With `sin theta_t = sin theta / eta` (Snell's law along the axis), Bravais' index
/// `eta' = sqrt(eta^2 - sin^2 theta) / cos theta = eta cos theta_t / cos theta` (Marschner 2003,
/// appendix B) gives the in-plane refraction `sin gamma_t = h / eta' = h cos theta / (eta
/// cos theta_t)`, which is 0 (not 0/0) for grazing rays, cos theta = 0.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Refraction<R> {
    /// cos theta >= 0 of the ray.
    pub cos_theta: R,
    /// cos theta_t of the refracted ray, at least sqrt(1 - 1/eta^2) > 0 for eta > 1.
    pub cos_theta_t: R,
    /// 1 / cos theta_t.
    pub inv_cos_theta_t: R,
    /// The relative index.
    pub eta: R,
    /// 1 / eta.
    pub inv_eta: R,
}

/// The path through the fibre of the ray entering at one offset h (see [`Refraction::path`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FibrePath<R> {
    /// The angle of incidence in the normal plane, gamma_o = asin h.
    pub gamma_o: R,
    /// The refracted angle in the normal plane, gamma_t = asin(h / eta').
    pub gamma_t: R,
    /// The length of one internal segment in fibre radii (see [`segment_length`]).
    pub segment_length: R,
    /// The Fresnel reflectance at the entry point, at the true angle of incidence
    /// cos = cos(theta) cos(gamma_o).
    pub fresnel: R,
}

impl<R: Real> Refraction<R> {
    /// Refraction of the ray with inclination sine `sin_theta` and cosine `cos_theta >= 0` into
    /// a fibre of index `eta > 1`, given `inv_eta = 1 / eta` (models precompute it).
    #[inline(always)]
    pub fn new(sin_theta: R, cos_theta: R, eta: R, inv_eta: R) -> Self {
        let sin_t = sin_theta * inv_eta;
        let cos_theta_t = safe_sqrt((-sin_t).mul_add(sin_t, R::c(1.0))).label("cos_theta_t");
        Refraction {
            cos_theta,
            cos_theta_t,
            inv_cos_theta_t: (R::c(1.0) / cos_theta_t).label("inv_cos_theta_t"),
            eta,
            inv_eta,
        }
    }

    /// sin(gamma_t) of the ray entering at offset h: `h cos theta / (eta cos theta_t)`.
    #[inline(always)]
    pub fn sin_gamma_t(&self, h: R) -> R {
        h * self.cos_theta * self.inv_eta * self.inv_cos_theta_t
    }

    /// The Fresnel reflectance at the entry point of the ray whose in-plane angles of incidence
    /// and refraction have cosines `cos_gamma_o` and `cos_gamma_t`. The cosines of the incident
    /// and refracted directions to the surface normal are the normal components of the Bravais
    /// split (Marschner et al. 2003, section 3): `cos theta cos gamma_o` and `cos theta_t cos
    /// gamma_t`.
    #[inline(always)]
    pub(crate) fn entry_fresnel(&self, cos_gamma_o: R, cos_gamma_t: R) -> R {
        fresnel_of_cosines(
            self.cos_theta * cos_gamma_o,
            self.cos_theta_t * cos_gamma_t,
            self.eta,
        )
    }

    /// The path of the ray entering at offset `h` (clamped to [-1, 1]), with internal segments
    /// of the length model `length`. The asines are written with the cosines the path needs
    /// anyway, `gamma = atan2(sin, cos)` ([`crate::real::safe_asin`] computes them the same
    /// way).
    #[inline(always)]
    pub fn path(&self, h: R, length: PathLength) -> FibrePath<R> {
        const FUNCTION: ShaderFunction = crate::shader_function!(
            fibre_path,
            "Chiang et al. 2016, sections 4.1 and 4.3 (Snell and Bravais; the chord 2 cos gamma_t / cos theta_t)",
            [h] -> {gamma_o, gamma_t, segment_length, fresnel}
        );
        let [gamma_o, gamma_t, segment_length, fresnel] = R::call(
            &FUNCTION,
            [h],
            #[inline(always)]
            |[h]| {
                let one = R::c(1.0);
                let h = h.clamp(-one, one);
                let sin_gamma_t = self.sin_gamma_t(h);
                let cos_gamma_t = safe_sqrt((-sin_gamma_t).mul_add(sin_gamma_t, one));
                let cos_gamma_o = cos_of_offset(h);
                let fresnel = self.entry_fresnel(cos_gamma_o, cos_gamma_t);
                [
                    h.asin_with_cos(cos_gamma_o),
                    sin_gamma_t.asin_with_cos(cos_gamma_t),
                    segment_length(cos_gamma_t, self.inv_cos_theta_t, length),
                    fresnel,
                ]
            },
        );
        FibrePath {
            gamma_o,
            gamma_t,
            segment_length,
            fresnel,
        }
    }
}

/// cos(gamma_o) = sqrt(1 - h^2) of the offset `h` in [-1, 1], with `1 - h^2` formed as
/// `(1 - h)(1 + h)`: as |h| -> 1 the rounding of `h^2` would be most of the difference (in
/// single precision it put up to 7e-5 of S into every lobe, the largest error of the batch
/// tests against `f64`), where `1 - h` is exact (Sterbenz) and the product rounds once. The
/// path's other cosines keep the one multiply-add `1 - s^2`: their sines stay below
/// `1 / eta' < 1`, where the rounding of `s^2` does not dominate.
#[inline(always)]
pub(crate) fn cos_of_offset<R: Real>(h: R) -> R {
    let one = R::c(1.0);
    safe_sqrt((one - h) * (one + h))
}

impl<R: Real> FibrePath<R> {
    /// The transmittance `exp(-sigma_a L)` of one internal segment for absorption `sigma_a`
    /// per unit radius.
    #[inline(always)]
    pub fn transmittance(&self, sigma_a: R) -> R {
        (-sigma_a * self.segment_length)
            .exp_of_nonpositive()
            .negligible_to_zero()
    }

    /// The attenuations `[A_0, A_1, A_2, A_3+]` of the path for absorption `sigma_a` per unit
    /// radius ([`attenuations_from_fresnel`] of the entry reflectance and the transmittance).
    #[inline(always)]
    pub fn attenuations(&self, sigma_a: R) -> [R; LOBES_WITH_RESIDUAL] {
        attenuations_from_fresnel(self.fresnel, self.transmittance(sigma_a))
    }
}
