//! Fibre geometry: the scattering angles of a pair of directions about a fibre.
//!
//! Conventions (docs/ARCHITECTURE.md): the tangent `u` points from root to tip; `wi` (towards the light)
//! and `wo` (towards the viewer) both point away from the fibre. In the local frame the tangent
//! is +X (as in pbrt), so `sin(theta) = w.x` and the azimuth `phi = atan2(w.z, w.y)` is measured
//! in the YZ normal plane. theta lies in [-pi/2, pi/2]; theta_h = (theta_i + theta_o) / 2,
//! theta_d = (theta_o - theta_i) / 2, and the relative azimuth phi = phi_o - phi_i is wrapped
//! to [-pi, pi] (Marschner 2003, section 2).

use crate::error::ParamError;
use crate::real::{Real, ShaderFunction, TINY};

/// A 3-vector of any [`Real`] (glam is used at the API boundary, re-exported as
/// [`crate::glam`]; generic code needs its own): `From` converts to and from [`glam::Vec3`]
/// (`f32`) and [`glam::DVec3`] (`f64`).
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
    /// A vector from `f64` components rounded to the working precision (as [`Real::c`] rounds
    /// a constant).
    pub fn from_f64(x: f64, y: f64, z: f64) -> Self {
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

impl<R: Real> core::ops::Add for V3<R> {
    type Output = V3<R>;
    /// Component-wise sum.
    fn add(self, o: Self) -> Self {
        V3 {
            x: self.x + o.x,
            y: self.y + o.y,
            z: self.z + o.z,
        }
    }
}

impl From<glam::Vec3> for V3<f32> {
    fn from(v: glam::Vec3) -> Self {
        V3::new(v.x, v.y, v.z)
    }
}

impl From<V3<f32>> for glam::Vec3 {
    fn from(v: V3<f32>) -> Self {
        glam::Vec3::new(v.x, v.y, v.z)
    }
}

impl From<glam::DVec3> for V3<f64> {
    fn from(v: glam::DVec3) -> Self {
        V3::new(v.x, v.y, v.z)
    }
}

impl From<V3<f64>> for glam::DVec3 {
    fn from(v: V3<f64>) -> Self {
        glam::DVec3::new(v.x, v.y, v.z)
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
    /// phi = phi_o - phi_i in [-pi, pi]; 0 when either direction is along the fibre. (The
    /// Chiang model's lobes are written in pbrt's phi_i - phi_o, its negative: the far field's
    /// functions name that argument `phi_i_minus_o`.)
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
        w.y.mul_add(w.y, w.z * w.z).sqrt().min(R::c(1.0)),
    )
}

/// The signed angle from `a` to `b` about the axis `tangent`: atan2(u . (a x b), a . b),
/// with 0 when the two are not both defined (never atan2(0, 0)).
#[inline(always)]
pub fn azimuth_between<R: Real>(tangent: V3<R>, a: V3<R>, b: V3<R>) -> R {
    angle_of(tangent.dot(a.cross(b)), a.dot(b))
}

/// [`azimuth_between`] in the local frame (tangent +X) of the normal-plane components
/// `(a_y, a_z)` and `(b_y, b_z)`: `atan2(a_y b_z - a_z b_y, a_y b_y + a_z b_z)`.
#[inline(always)]
fn local_azimuth_between<R: Real>(a_y: R, a_z: R, b_y: R, b_z: R) -> R {
    angle_of(a_y.mul_add(b_z, -(a_z * b_y)), a_y.mul_add(b_y, a_z * b_z))
}

/// The angle whose sine and cosine are proportional to `sine` and `cosine`, `atan2(sine,
/// cosine)` in [-pi, pi], and 0 when both are 0 (never atan2(0, 0)).
#[inline(always)]
fn angle_of<R: Real>(sine: R, cosine: R) -> R {
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
        "the local frame of docs/ARCHITECTURE.md: sin theta = w.x, phi in the YZ plane",
        [wi: vec3, wo: vec3] -> {sin_theta_i, cos_theta_i, sin_theta_o, cos_theta_o, phi}
    );
    let args = [wi.x, wi.y, wi.z, wo.x, wo.y, wo.z];
    let [sin_theta_i, cos_theta_i, sin_theta_o, cos_theta_o, phi] = R::call(
        &FUNCTION,
        args,
        #[inline(always)]
        |[ix, iy, iz, ox, oy, oz]| {
            // phi_o - phi_i is the signed angle from wi's projection to wo's.
            let (sin_i, cos_i) = local_sin_cos_theta(V3::new(ix, iy, iz));
            let (sin_o, cos_o) = local_sin_cos_theta(V3::new(ox, oy, oz));
            [
                sin_i,
                cos_i,
                sin_o,
                cos_o,
                local_azimuth_between(iy, iz, oy, oz),
            ]
        },
    );
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
    /// The frame of a tangent, which need not be unit length: any finite non-zero vector,
    /// however long or short (it is divided by its largest component first, so that its
    /// squared length neither overflows nor underflows). The normal is chosen continuously by
    /// Duff et al. 2017 ("Building an Orthonormal Basis, Revisited").
    ///
    /// # Errors
    /// [`ParamError::BadVector`] if the tangent is zero or has a non-finite component.
    pub fn new(tangent: glam::DVec3) -> Result<Self, ParamError> {
        let largest = tangent.abs().max_element();
        if !(tangent.is_finite() && largest > 0.0) {
            return Err(ParamError::BadVector {
                name: "tangent",
                x: tangent.x,
                y: tangent.y,
                z: tangent.z,
                allowed: "the fibre tangent must be finite and non-zero",
            });
        }
        let t = tangent / largest;
        let [t, n, b] = fibre_frame(V3::new(t.x, t.y, t.z));
        let dvec = |v: V3<f64>| glam::DVec3::new(v.x, v.y, v.z);
        Ok(FibreFrame {
            tangent: dvec(t),
            normal: dvec(n),
            binormal: dvec(b),
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

/// The orthonormal frame `[tangent, normal, binormal]` of a non-zero `tangent` (normalised
/// here): the fibre's local +X, +Y and +Z, right-handed, the normal chosen continuously
/// except across the plane z = 0 by Duff et al. 2017 ("Building an Orthonormal Basis,
/// Revisited", listing 3), branch-free: with `s = sign(t_z)` (+1 at 0), `a = -1 / (s + t_z)`,
/// `b = t_x t_y a`, `normal = (1 + s t_x^2 a, s b, -s t_x)` and `binormal = (b, s + t_y^2 a,
/// -t_y)`. The tangent's length is floored at 1e-30 so that a zero tangent gives a finite
/// (meaningless) frame; [`FibreFrame::new`] rejects it, and takes tangents of any finite
/// length (here the squared length must be finite: components below about 1e154 in `f64`,
/// 1.8e19 in `f32`).
pub fn fibre_frame<R: Real>(tangent: V3<R>) -> [V3<R>; 3] {
    const FUNCTION: ShaderFunction = crate::shader_function!(
        fibre_frame,
        "Duff et al. 2017, listing 3",
        [tangent: vec3] -> {tangent: vec3, normal: vec3, binormal: vec3}
    );
    let args = [tangent.x, tangent.y, tangent.z];
    let frame = R::call(
        &FUNCTION,
        args,
        #[inline(always)]
        |[x, y, z]| {
            let length = (x * x + y * y + z * z).sqrt().max(TINY.get());
            let t = V3::new(x, y, z).scale(R::c(1.0) / length);
            let one = R::c(1.0);
            let s = R::select(t.z.lt(R::c(0.0)), -one, one);
            let a = -one / (s + t.z);
            let b = t.x * t.y * a;
            let n = V3::new(one + s * t.x * t.x * a, s * b, -s * t.x);
            let bn = V3::new(b, s + t.y * t.y * a, -t.y);
            [t.x, t.y, t.z, n.x, n.y, n.z, bn.x, bn.y, bn.z]
        },
    );
    core::array::from_fn(|k| V3::new(frame[3 * k], frame[3 * k + 1], frame[3 * k + 2]))
}

/// `wi` and `wo`, given in any frame, in the local frame of the fibre of direction `tangent`
/// ([`fibre_frame`]): `(w . tangent, w . normal, w . binormal)`. What a world-space shader
/// computes before evaluating a model in the local frame.
pub fn local_directions<R: Real>(tangent: V3<R>, wi: V3<R>, wo: V3<R>) -> [V3<R>; 2] {
    let [t, n, b] = fibre_frame(tangent);
    [wi, wo].map(|w| V3::new(w.dot(t), w.dot(n), w.dot(b)))
}

/// [`local_directions`] traced as the shader function `fibre_local_directions(tangent:
/// vec3<f32>, wi: vec3<f32>, wo: vec3<f32>) -> FibreLocalDirections` (a struct of the local `wi` and `wo`), the
/// frame of a world-space shader's `hair_bcsdf_world`.
pub fn trace_local_directions() -> crate::real::Graph {
    use crate::real::{trace_with, ArgType, Parameter, ResultType, Shape, Signature};
    let signature = Signature {
        parameters: ["tangent", "wi", "wo"]
            .map(|name| Parameter::argument(name, ArgType::Vec3))
            .to_vec(),
        result: ResultType::Fields(&[("wi", Shape::Vec3), ("wo", Shape::Vec3)]),
    };
    trace_with(signature, |x| {
        let v = |k: usize| V3::new(x[k], x[k + 1], x[k + 2]);
        let [wi, wo] = local_directions(v(0), v(3), v(6));
        vec![wi.x, wi.y, wi.z, wo.x, wo.y, wo.z]
    })
}

/// The unit direction with longitudinal angle given by `sin_theta`, `cos_theta` and azimuth
/// `phi` in the local frame: (sin theta, cos theta cos phi, cos theta sin phi).
pub fn local_direction<R: Real>(sin_theta: R, cos_theta: R, phi: R) -> V3<R> {
    V3::new(sin_theta, cos_theta * phi.cos(), cos_theta * phi.sin())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn fibre_frames_are_orthonormal_and_right_handed_at_the_hard_tangents() {
        let tangents = [
            [0.0, 0.0, 1.0],
            [0.0, 0.0, -1.0],
            [1.0, 0.0, 0.0],
            [0.3, -0.2, -0.0],
            [1e-9, -1e-9, -1.0],
            [-3.0, 4.0, 12.0],
            [2.0, -1.0, -1e-12],
        ];
        for t in tangents {
            let [u, n, b] = fibre_frame(V3::new(t[0], t[1], t[2]));
            let len = (t[0] * t[0] + t[1] * t[1] + t[2] * t[2]).sqrt();
            for (k, c) in [u.x, u.y, u.z].iter().enumerate() {
                assert!((c - t[k] / len).abs() < 1e-15, "{t:?}");
            }
            for (a, c) in [(u, u), (n, n), (b, b)] {
                assert!((a.dot(c) - 1.0).abs() < 1e-14, "{t:?}");
            }
            for (a, c) in [(u, n), (u, b), (n, b)] {
                assert!(a.dot(c).abs() < 1e-14, "{t:?}");
            }
            let z = u.cross(n);
            assert!((z.dot(b) - 1.0).abs() < 1e-14, "right-handed at {t:?}");
        }
        // A zero tangent (rejected by FibreFrame::new) still gives finite numbers.
        let zero = fibre_frame(V3::new(0.0_f64, 0.0, -0.0));
        assert!(zero
            .iter()
            .all(|v| v.x.is_finite() && v.y.is_finite() && v.z.is_finite()));
    }

    #[test]
    fn local_directions_put_the_tangent_on_x() {
        let t = V3::new(0.2, -0.9, 0.4);
        let [a, b] = local_directions(t, t, t.scale(-1.0));
        let len = t.dot(t).sqrt();
        assert!((a.x - len).abs() < 1e-14 && a.y.abs() < 1e-14 && a.z.abs() < 1e-14);
        assert!((b.x + len).abs() < 1e-14);
    }
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
        let along = V3::from_f64(1.0, 0.0, 0.0);
        let a = local_fibre_angles(along, dir(0.2, 1.0));
        assert_eq!(a.phi, 0.0);
        assert_eq!(a.theta_i(), FRAC_PI_2);
        let b =
            local_fibre_angles::<f32>(V3::from_f64(0.0, 1.0, 0.0), V3::from_f64(0.0, -1.0, 0.0));
        assert!((b.phi.abs() - std::f32::consts::PI).abs() < 1e-6);
    }

    #[test]
    fn zero_tangent_is_a_typed_error() {
        let e = FibreFrame::new(glam::DVec3::ZERO).unwrap_err();
        assert!(e.to_string().contains("non-zero"), "{e}");
        assert!(FibreFrame::new(glam::DVec3::new(f64::NAN, 0.0, 1.0)).is_err());
    }
}
