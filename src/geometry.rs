//! Fibre geometry: the scattering angles of a pair of directions about a fibre.
//!
//! Conventions (DESIGN.md): the tangent `u` points from root to tip; `wi` (towards the light)
//! and `wo` (towards the viewer) both point away from the fibre. In the local frame the tangent
//! is +X (as in pbrt), so `sin(theta) = w.x` and the azimuth `phi = atan2(w.z, w.y)` is measured
//! in the YZ normal plane. theta lies in [-pi/2, pi/2]; theta_h = (theta_i + theta_o) / 2,
//! theta_d = (theta_o - theta_i) / 2, and the relative azimuth phi = phi_o - phi_i is wrapped
//! to [-pi, pi] (Marschner 2003, section 2).

use crate::error::ParamError;
use crate::real::{Real, ShaderFunction};

/// A 3-vector of any [`Real`] (glam is used at the API boundary; generic code needs its own).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct V3<R> {
    /// First component (the fibre tangent in the local frame).
    pub x: R,
    /// Second component.
    pub y: R,
    /// Third component.
    pub z: R,
}

impl<R: Real> V3<R> {
    /// A vector from its components.
    pub fn new(x: R, y: R, z: R) -> Self {
        V3 { x, y, z }
    }
    /// A vector from `f64` components rounded to the working precision.
    pub fn c(x: f64, y: f64, z: f64) -> Self {
        V3 {
            x: R::c(x),
            y: R::c(y),
            z: R::c(z),
        }
    }
    /// Dot product.
    pub fn dot(self, o: Self) -> R {
        self.x * o.x + self.y * o.y + self.z * o.z
    }
    /// Cross product.
    pub fn cross(self, o: Self) -> Self {
        V3 {
            x: self.y * o.z - self.z * o.y,
            y: self.z * o.x - self.x * o.z,
            z: self.x * o.y - self.y * o.x,
        }
    }
    /// `self * s`.
    pub fn scale(self, s: R) -> Self {
        V3 {
            x: self.x * s,
            y: self.y * s,
            z: self.z * s,
        }
    }
}

impl<R: Real> core::ops::Sub for V3<R> {
    type Output = V3<R>;
    /// Component-wise difference.
    fn sub(self, o: Self) -> Self {
        V3 {
            x: self.x - o.x,
            y: self.y - o.y,
            z: self.z - o.z,
        }
    }
}

/// The longitudinal and azimuthal angles of a direction pair about a fibre, kept as sines and
/// cosines where that is what the models consume.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FibreAngles<R> {
    /// sin(theta_i) = wi . u, clamped to [-1, 1].
    pub sin_theta_i: R,
    /// cos(theta_i) >= 0.
    pub cos_theta_i: R,
    /// sin(theta_o) = wo . u, clamped to [-1, 1].
    pub sin_theta_o: R,
    /// cos(theta_o) >= 0.
    pub cos_theta_o: R,
    /// phi = phi_o - phi_i in [-pi, pi]; 0 when either direction is along the fibre.
    pub phi: R,
}

impl<R: Real> FibreAngles<R> {
    /// theta_i in [-pi/2, pi/2].
    pub fn theta_i(&self) -> R {
        self.sin_theta_i.atan2(self.cos_theta_i)
    }
    /// theta_o in [-pi/2, pi/2].
    pub fn theta_o(&self) -> R {
        self.sin_theta_o.atan2(self.cos_theta_o)
    }
    /// theta_h = (theta_i + theta_o) / 2.
    pub fn theta_h(&self) -> R {
        (self.theta_i() + self.theta_o()) * R::c(0.5)
    }
    /// theta_d = (theta_o - theta_i) / 2.
    pub fn theta_d(&self) -> R {
        (self.theta_o() - self.theta_i()) * R::c(0.5)
    }
}

/// sin and cos of the angle between a unit direction and the normal plane of a unit `tangent`:
/// `sin = w . u` and `cos = |u x w|`. Taking the cosine from the cross product rather than
/// `sqrt(1 - sin^2)` keeps it accurate for grazing directions (|sin| -> 1), where `1 - sin^2`
/// cancels; both are clamped to their ranges.
pub fn sin_cos_theta<R: Real>(tangent: V3<R>, w: V3<R>) -> (R, R) {
    let s = w.dot(tangent).clamp(R::c(-1.0), R::c(1.0));
    let p = tangent.cross(w);
    (s, p.dot(p).sqrt().min(R::c(1.0)))
}

/// [`sin_cos_theta`] in the local frame (tangent +X): `(w.x, sqrt(w.y^2 + w.z^2))`, clamped.
#[inline(always)]
pub fn local_sin_cos_theta<R: Real>(w: V3<R>) -> (R, R) {
    (
        w.x.clamp(R::c(-1.0), R::c(1.0)),
        (w.y * w.y + w.z * w.z).sqrt().min(R::c(1.0)),
    )
}

/// The signed angle from `a` to `b` about the axis `tangent`: atan2(u . (a x b), a . b),
/// with 0 when the two are not both defined (never atan2(0, 0)).
#[inline(always)]
pub fn azimuth_between<R: Real>(tangent: V3<R>, a: V3<R>, b: V3<R>) -> R {
    let sine = tangent.dot(a.cross(b));
    let cosine = a.dot(b);
    let defined = R::c(0.0).lt(sine.abs() + cosine.abs());
    sine.atan2(R::select(defined, cosine, R::c(1.0)))
}

/// Angles of `wi`, `wo` about a unit `tangent` in any frame. Directions are unit vectors.
pub fn fibre_angles<R: Real>(tangent: V3<R>, wi: V3<R>, wo: V3<R>) -> FibreAngles<R> {
    let (sin_theta_i, cos_theta_i) = sin_cos_theta(tangent, wi);
    let (sin_theta_o, cos_theta_o) = sin_cos_theta(tangent, wo);
    // The projections onto the normal plane need not be normalised: atan2 is scale-free.
    let pi_ = wi - tangent.scale(sin_theta_i);
    let po = wo - tangent.scale(sin_theta_o);
    FibreAngles {
        sin_theta_i,
        cos_theta_i,
        sin_theta_o,
        cos_theta_o,
        phi: azimuth_between(tangent, pi_, po),
    }
}

/// Angles of unit directions given in the local frame (tangent +X).
#[inline(always)]
pub fn local_fibre_angles<R: Real>(wi: V3<R>, wo: V3<R>) -> FibreAngles<R> {
    const FUNCTION: ShaderFunction = crate::shader_function!(
        fibre_angles,
        "the local frame of DESIGN.md: sin theta = w.x, phi in the YZ plane",
        [wi: vec3, wo: vec3]
    );
    let args = [wi.x, wi.y, wi.z, wo.x, wo.y, wo.z];
    let [sin_theta_i, cos_theta_i, sin_theta_o, cos_theta_o, phi] =
        R::call(&FUNCTION, args, |[ix, iy, iz, ox, oy, oz]| {
            let x = V3::c(1.0, 0.0, 0.0);
            let pi_ = V3::new(R::c(0.0), iy, iz);
            let po = V3::new(R::c(0.0), oy, oz);
            // phi_o - phi_i is the signed angle from wi's projection to wo's.
            let (sin_i, cos_i) = local_sin_cos_theta(V3::new(ix, iy, iz));
            let (sin_o, cos_o) = local_sin_cos_theta(V3::new(ox, oy, oz));
            [sin_i, cos_i, sin_o, cos_o, azimuth_between(x, pi_, po)]
        });
    FibreAngles {
        sin_theta_i,
        cos_theta_i,
        sin_theta_o,
        cos_theta_o,
        phi,
    }
}

/// An orthonormal frame about a fibre tangent: `tangent` is local +X; `normal` and `binormal`
/// (local +Y and +Z) complete a right-handed frame.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FibreFrame {
    /// Unit tangent, root to tip (local +X).
    pub tangent: glam::DVec3,
    /// Unit vector perpendicular to the tangent (local +Y).
    pub normal: glam::DVec3,
    /// `tangent x normal` (local +Z).
    pub binormal: glam::DVec3,
}

impl FibreFrame {
    /// The frame of a tangent, which need not be unit length. The normal is chosen
    /// continuously by Duff et al. 2017 ("Building an Orthonormal Basis, Revisited").
    ///
    /// # Errors
    /// [`ParamError::BadVector`] if the tangent is zero or not finite.
    pub fn new(tangent: glam::DVec3) -> Result<Self, ParamError> {
        let len = tangent.length();
        if !(len.is_finite() && len > 0.0) {
            return Err(ParamError::BadVector {
                name: "tangent",
                x: tangent.x,
                y: tangent.y,
                z: tangent.z,
                allowed: "the fibre tangent must be finite and non-zero",
            });
        }
        let t = tangent / len;
        let (normal, binormal) = t.any_orthonormal_pair();
        Ok(FibreFrame {
            tangent: t,
            normal,
            binormal,
        })
    }

    /// A world-space direction expressed in the local frame (tangent +X).
    pub fn to_local(&self, w: glam::DVec3) -> glam::DVec3 {
        glam::DVec3::new(
            w.dot(self.tangent),
            w.dot(self.normal),
            w.dot(self.binormal),
        )
    }

    /// A local-frame direction expressed in world space.
    pub fn to_world(&self, w: glam::DVec3) -> glam::DVec3 {
        self.tangent * w.x + self.normal * w.y + self.binormal * w.z
    }
}

/// The unit direction with longitudinal angle given by `sin_theta`, `cos_theta` and azimuth
/// `phi` in the local frame: (sin theta, cos theta cos phi, cos theta sin phi).
pub fn local_direction<R: Real>(sin_theta: R, cos_theta: R, phi: R) -> V3<R> {
    V3::new(sin_theta, cos_theta * phi.cos(), cos_theta * phi.sin())
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::{FRAC_PI_2, PI};

    fn dir(theta: f64, phi: f64) -> V3<f64> {
        local_direction(theta.sin(), theta.cos(), phi)
    }

    #[test]
    fn local_angles_recover_the_construction() {
        for &(ti, pi_, to, po) in &[
            (0.3, 0.2, -0.5, 1.9),
            (-1.2, -2.9, 0.7, 2.9),
            (0.0, 0.0, 0.0, PI - 1e-9),
        ] {
            let a = local_fibre_angles(dir(ti, pi_), dir(to, po));
            assert!((a.theta_i() - ti).abs() < 1e-12 && (a.theta_o() - to).abs() < 1e-12);
            let want = crate::real::wrap_angle(po - pi_);
            assert!((a.phi - want).abs() < 1e-12, "{} vs {want}", a.phi);
            assert!((a.theta_h() - (ti + to) / 2.0).abs() < 1e-12);
            assert!((a.theta_d() - (to - ti) / 2.0).abs() < 1e-12);
        }
    }

    #[test]
    fn world_angles_match_local_angles_in_any_frame() {
        let frame = FibreFrame::new(glam::DVec3::new(0.3, -2.0, 0.7)).unwrap();
        let wi = glam::DVec3::new(0.2, 0.5, -0.3).normalize();
        let wo = glam::DVec3::new(-0.6, 0.1, 0.4).normalize();
        let g = |v: glam::DVec3| V3::new(v.x, v.y, v.z);
        let world = fibre_angles(g(frame.tangent), g(wi), g(wo));
        let local = local_fibre_angles(g(frame.to_local(wi)), g(frame.to_local(wo)));
        assert!((world.phi - local.phi).abs() < 1e-12);
        assert!((world.sin_theta_i - local.sin_theta_i).abs() < 1e-12);
        assert!((frame.to_world(frame.to_local(wi)) - wi).length() < 1e-12);
    }

    #[test]
    fn grazing_and_degenerate_directions_are_finite() {
        let along = V3::c(1.0, 0.0, 0.0);
        let a = local_fibre_angles(along, dir(0.2, 1.0));
        assert_eq!(a.phi, 0.0);
        assert_eq!(a.theta_i(), FRAC_PI_2);
        let b = local_fibre_angles::<f32>(V3::c(0.0, 1.0, 0.0), V3::c(0.0, -1.0, 0.0));
        assert!((b.phi.abs() - std::f32::consts::PI).abs() < 1e-6);
    }

    #[test]
    fn zero_tangent_is_a_typed_error() {
        let e = FibreFrame::new(glam::DVec3::ZERO).unwrap_err();
        assert!(e.to_string().contains("non-zero"), "{e}");
        assert!(FibreFrame::new(glam::DVec3::new(f64::NAN, 0.0, 1.0)).is_err());
    }
}
