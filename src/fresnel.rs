//! Fresnel reflectance of a dielectric interface, and the Bravais virtual indices that reduce
//! refraction by an inclined ray to refraction in the fibre's normal plane.

use crate::real::{safe_sqrt, Real, ShaderFunction, TINY};

/// Unpolarised Fresnel reflectance of light arriving from outside a dielectric of relative
/// index `eta` at an angle whose cosine to the normal is `cos_i` (Born and Wolf, section 1.5;
/// pbrt-v4 `FrDielectric`). A negative `cos_i` means the light arrives from inside: the
/// relative index is then `1 / eta`. Total internal reflection gives 1.
///
/// `R = (r_par^2 + r_perp^2) / 2` with `r_par = (eta cos_i - cos_t) / (eta cos_i + cos_t)`,
/// `r_perp = (cos_i - eta cos_t) / (cos_i + eta cos_t)` and Snell's law for `cos_t`, evaluated
/// by [`fresnel_from_outside`] on the side the light comes from.
/// Finite `cos_i` is clamped to [-1, 1]; for a finite `eta > 0` the result is in [0, 1]. A
/// NaN or infinite argument, or `eta <= 0`, gives NaN rather than a number (a reference
/// function: clamping would have turned a NaN `cos_i` into -1).
pub fn fresnel_dielectric<R: Real>(cos_i: R, eta: R) -> R {
    // 0 for finite arguments, NaN for a NaN or infinite one: x - x is the NaN probe that
    // every instantiation (shader code included) can compute.
    #[allow(clippy::eq_op)]
    let invalid = (cos_i - cos_i) + (eta - eta);
    let cos_i = cos_i.clamp(R::c(-1.0), R::c(1.0));
    let inside = cos_i.lt(R::c(0.0));
    let inv_eta = R::c(1.0) / eta;
    let (n, inv_n) = (
        R::select(inside, inv_eta, eta),
        R::select(inside, eta, inv_eta),
    );
    let (r, sin2_t) = reflectance(cos_i.abs(), n, inv_n);
    let r = R::select(sin2_t.lt(R::c(1.0)), r, R::c(1.0)) + invalid;
    // 0 / 0 is NaN: an index at or below 0 is no index.
    #[allow(clippy::eq_op)]
    let no_index = invalid / invalid;
    R::select(R::c(0.0).lt(eta), r, no_index)
}

/// [`fresnel_dielectric`] for light arriving from the outside of a fibre with `eta >= 1`, the
/// form the hair models evaluate at every entry point: `cos_i` in [0, 1] and the reciprocal
/// `inv_eta = 1 / eta` given (a model precomputes it). With `eta >= 1` there is no total
/// internal reflection (`cos_t >= sqrt(1 - 1/eta^2)`), and the two amplitude ratios share one
/// division, `(r_par^2 + r_perp^2) / 2 = (a^2 d^2 + c^2 b^2) / (2 b^2 d^2)` with
/// `r_par = a / b`, `r_perp = c / d`.
#[inline(always)]
pub fn fresnel_from_outside<R: Real>(cos_i: R, eta: R, inv_eta: R) -> R {
    const FUNCTION: ShaderFunction = crate::shader_function!(
        fresnel,
        "Born and Wolf, section 1.5 (unpolarised dielectric reflectance)",
        [cos_i, eta, inv_eta]
    );
    R::call(
        &FUNCTION,
        [cos_i, eta, inv_eta],
        #[inline(always)]
        |[cos_i, eta, inv_eta]| [reflectance(cos_i, eta, inv_eta).0],
    )[0]
}

/// [`fresnel_from_outside`] from both cosines, for callers that know the cosine `cos_t` of the
/// transmitted direction already (a fibre's path: `cos theta_t cos gamma_t`, the Bravais split of
/// the refracted direction), so Snell's law costs no square root here. `cos_i` in [0, 1],
/// `cos_t` in (0, 1] (Snell's law gives `cos_t >= sqrt(1 - 1/eta^2) > 0`), `eta >= 1`; the
/// result is in [0, 1] (on the CPU also at `cos_i = cos_t = 0`, where the clamp to 1 takes the
/// 0 / 0 of the grazing limit).
#[inline(always)]
pub fn fresnel_of_cosines<R: Real>(cos_i: R, cos_t: R, eta: R) -> R {
    const FUNCTION: ShaderFunction = crate::shader_function!(
        fresnel_of_cosines,
        "Born and Wolf, section 1.5 (unpolarised dielectric reflectance, both cosines given)",
        [cos_i, cos_t, eta]
    );
    R::call(
        &FUNCTION,
        [cos_i, cos_t, eta],
        #[inline(always)]
        |[cos_i, cos_t, eta]| [amplitude_ratios_squared(cos_i, cos_t, eta)],
    )[0]
}

/// `(R, sin^2 theta_t)` for `cos_i` in [0, 1] on the side of relative index `eta` (reciprocal
/// `inv_eta`); `R` is meaningful only where `sin^2 theta_t < 1` (no total internal reflection).
#[inline(always)]
fn reflectance<R: Real>(cos_i: R, eta: R, inv_eta: R) -> (R, R) {
    let one = R::c(1.0);
    let sin2_t = (one - cos_i * cos_i) * (inv_eta * inv_eta);
    let cos_t = safe_sqrt(one - sin2_t);
    (amplitude_ratios_squared(cos_i, cos_t, eta), sin2_t)
}

/// `min(1, (r_par^2 + r_perp^2) / 2)` with `r_par = (eta cos_i - cos_t) / (eta cos_i + cos_t)`
/// and `r_perp = (cos_i - eta cos_t) / (cos_i + eta cos_t)` (Born and Wolf, section 1.5),
/// sharing one division: `(a^2 d^2 + c^2 b^2) / (2 b^2 d^2)` for `r_par = a / b`, `r_perp = c / d`.
#[inline(always)]
fn amplitude_ratios_squared<R: Real>(cos_i: R, cos_t: R, eta: R) -> R {
    let (a, b) = (eta.mul_add(cos_i, -cos_t), eta.mul_add(cos_i, cos_t));
    let (c, d) = ((-eta).mul_add(cos_t, cos_i), eta.mul_add(cos_t, cos_i));
    let (bb, dd) = (b * b, d * d);
    ((c * c).mul_add(bb, a * a * dd) / (R::c(2.0) * bb * dd)).min(R::c(1.0))
}

/// Schlick's approximation `R0 + (1 - R0)(1 - cos_i)^5` with `R0 = ((eta - 1)/(eta + 1))^2`
/// (Schlick 1994, eq. 24), for light arriving from outside (`cos_i` clamped to [0, 1]).
pub fn fresnel_schlick<R: Real>(cos_i: R, eta: R) -> R {
    const FUNCTION: ShaderFunction =
        crate::shader_function!(fresnel_schlick, "Schlick 1994, eq. 24", [cos_i, eta]);
    R::call(
        &FUNCTION,
        [cos_i, eta],
        #[inline(always)]
        |[cos_i, eta]| {
            let r0 = ((eta - R::c(1.0)) / (eta + R::c(1.0))).sqr();
            let m = R::c(1.0) - cos_i.clamp(R::c(0.0), R::c(1.0));
            let m2 = m * m;
            [r0 + (R::c(1.0) - r0) * m2 * m2 * m]
        },
    )[0]
}

/// Bravais' virtual index for the perpendicular polarisation and the azimuthal (projected)
/// geometry: `eta' = sqrt(eta^2 - sin^2 theta) / cos theta` (Marschner 2003, appendix B;
/// Bravais 1845). Refraction of a ray inclined at `theta` to the normal plane, projected onto
/// that plane, obeys Snell's law with `eta'`. Written as `sqrt(eta^2 - sin^2) / cos` with
/// `cos theta` floored at 1e-30 so that grazing rays give a large finite index, not infinity.
///
/// Gerard (Fast Real-Time Shading for Polygonal Hair, eq. 8) prints `sqrt((1.55^2 - cos^2 theta_d + 1) / cos theta_d)`, which is not
/// this expression (README, errata).
pub fn bravais_eta_perpendicular<R: Real>(eta: R, sin_theta: R) -> R {
    let cos_theta = safe_sqrt(R::c(1.0) - sin_theta * sin_theta).max(TINY.get());
    safe_sqrt(eta * eta - sin_theta * sin_theta) / cos_theta
}

/// Bravais' virtual index for the parallel polarisation:
/// `eta'' = eta^2 cos theta / sqrt(eta^2 - sin^2 theta)` (Marschner 2003, appendix B).
/// Requires `eta > 1`.
pub fn bravais_eta_parallel<R: Real>(eta: R, sin_theta: R) -> R {
    let cos_theta = safe_sqrt(R::c(1.0) - sin_theta * sin_theta);
    eta * eta * cos_theta / safe_sqrt(eta * eta - sin_theta * sin_theta)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn normal_incidence_matches_closed_form() {
        for &eta in &[1.01_f64, 1.33, 1.55, 2.4] {
            let r0: f64 = ((eta - 1.0) / (eta + 1.0)).powi(2);
            assert!((fresnel_dielectric(1.0, eta) - r0).abs() < 1e-15);
            assert!((fresnel_schlick(1.0, eta) - r0).abs() < 1e-15);
            assert!(
                (fresnel_dielectric(-1.0, eta) - r0).abs() < 1e-15,
                "reciprocal at normal"
            );
        }
    }

    #[test]
    fn non_finite_arguments_and_non_positive_indices_give_nan() {
        let eta = 1.55_f64;
        for bad in [
            fresnel_dielectric(f64::NAN, eta),
            fresnel_dielectric(f64::INFINITY, eta),
            fresnel_dielectric(0.5, f64::NAN),
            fresnel_dielectric(0.5, 0.0),
            fresnel_dielectric(0.5, -1.5),
            fresnel_dielectric(0.5, f64::INFINITY),
        ] {
            assert!(bad.is_nan(), "{bad}");
        }
        assert_eq!(fresnel_dielectric(2.0, eta), fresnel_dielectric(1.0, eta));
    }

    #[test]
    fn grazing_total_reflection_and_brewster() {
        let eta = 1.55_f64;
        assert_eq!(fresnel_dielectric(0.0, eta), 1.0);
        // Inside the fibre past the critical angle sin c = 1/eta: total internal reflection.
        let crit_cos = (1.0 - 1.0 / (eta * eta)).sqrt();
        assert_eq!(fresnel_dielectric(-(crit_cos - 1e-6), eta), 1.0);
        // At Brewster's angle tan theta = eta the parallel term vanishes:
        // R = r_perp^2 / 2 with r_perp = cos(theta_i + theta_t) / ... = (1 - eta^2)/(1 + eta^2).
        let cos_b = 1.0 / (1.0 + eta * eta).sqrt();
        let r_perp: f64 = (1.0 - eta * eta) / (1.0 + eta * eta);
        assert!((fresnel_dielectric(cos_b, eta) - 0.5 * r_perp * r_perp).abs() < 1e-14);
    }

    /// From Snell's cosine, the reflectance of both cosines is [`fresnel_dielectric`]'s; and
    /// the cosine a fibre's path passes, cos theta_t cos gamma_t, is that of the refracted
    /// direction from the vector form of Snell's law (the Bravais split of the direction).
    #[test]
    fn fresnel_of_cosines_is_fresnel_with_the_transmitted_cosine() {
        for k in 0..=200 {
            let cos_i = k as f64 / 200.0;
            for eta in [1.0001_f64, 1.33, 1.55, 2.4, 3.0] {
                let cos_t = (1.0 - (1.0 - cos_i * cos_i) / (eta * eta)).sqrt();
                let got = fresnel_of_cosines(cos_i, cos_t, eta);
                let want = fresnel_dielectric(cos_i, eta);
                // Rounding only: near grazing with eta -> 1 the reflectance is steep in cos_t,
                // which the two compute in different orders.
                assert!((got - want).abs() < 1e-12, "{cos_i} {eta}: {got} vs {want}");
                let got32 = fresnel_of_cosines(cos_i as f32, cos_t as f32, eta as f32);
                assert!(
                    (f64::from(got32) - want).abs() < 1e-6,
                    "{cos_i} {eta}: {got32}"
                );
            }
        }
        // Both cosines 0, the grazing limit: total reflection, not 0 / 0.
        assert_eq!(fresnel_of_cosines(0.0_f64, 0.0, 1.55), 1.0);
        assert_eq!(fresnel_of_cosines(0.0_f32, 0.0, 1.55), 1.0);
        let eta = 1.55_f64;
        for &theta in &[0.0_f64, 0.3, 0.9, 1.4, 1.57] {
            for &gamma in &[0.0_f64, 0.1, 0.6, 1.2, 1.57] {
                let d = glam::DVec3::new(
                    theta.sin(),
                    -theta.cos() * gamma.cos(),
                    theta.cos() * gamma.sin(),
                );
                let n = glam::DVec3::new(0.0, 1.0, 0.0);
                let cos_i = -d.dot(n);
                let k = 1.0 / eta;
                let t = d * k + n * (k * cos_i - (1.0 - k * k * (1.0 - cos_i * cos_i)).sqrt());
                let cos_theta_t = (1.0 - (theta.sin() / eta).powi(2)).sqrt();
                let sin_gamma_t = theta.cos() * gamma.sin() / (eta * cos_theta_t);
                let split = cos_theta_t * (1.0 - sin_gamma_t * sin_gamma_t).sqrt();
                assert!((-t.y - split).abs() < 1e-15, "theta {theta} gamma {gamma}");
            }
        }
    }

    proptest::proptest! {
        /// Over the whole domain (cosines in [0, 1], eta in (1, 3]) the reflectance is in
        /// [0, 1], in both precisions.
        #[test]
        fn fresnel_of_cosines_is_a_reflectance(
            cos_i in 0.0..=1.0_f64,
            cos_t in 0.0..=1.0_f64,
            eta in 1.000001..=3.0_f64,
        ) {
            let r = fresnel_of_cosines(cos_i, cos_t, eta);
            proptest::prop_assert!((0.0..=1.0).contains(&r), "{r}");
            let r32 = fresnel_of_cosines(cos_i as f32, cos_t as f32, eta as f32);
            proptest::prop_assert!((0.0..=1.0).contains(&r32), "{r32}");
        }
    }

    #[test]
    fn bravais_indices_reproduce_snell_in_projection() {
        // A ray inclined at theta refracts to theta_t with sin theta_t = sin theta / eta. Its
        // projection onto the normal plane refracts with eta' (Marschner 2003, appendix B):
        // for incidence gamma in the plane, sin gamma = eta' sin gamma_t, where the 3D
        // refracted direction is obtained from the vector form of Snell's law.
        let eta = 1.55_f64;
        for &theta in &[0.0, 0.3, 0.9, 1.4] {
            for &gamma in &[0.1, 0.6, 1.2] {
                let d = glam::DVec3::new(
                    theta.sin(),
                    -theta.cos() * gamma.cos(),
                    theta.cos() * gamma.sin(),
                );
                let n = glam::DVec3::new(0.0, 1.0, 0.0); // surface normal of the cylinder at the hit
                let cos_i = -d.dot(n);
                let k = 1.0 / eta;
                let t = d * k + n * (k * cos_i - (1.0 - k * k * (1.0 - cos_i * cos_i)).sqrt());
                let gamma_t = t.z.atan2(-t.y);
                let ep = bravais_eta_perpendicular(eta, theta.sin());
                assert!(
                    (gamma.sin() - ep * gamma_t.sin()).abs() < 1e-12,
                    "theta {theta} gamma {gamma}"
                );
            }
        }
        assert!(bravais_eta_perpendicular(1.55_f32, 1.0).is_finite());
        assert!((bravais_eta_parallel(1.55_f64, 0.0) - 1.55).abs() < 1e-15);
    }
}
