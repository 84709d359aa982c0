//! Conventions at the boundary with other renderers: how each states the directions of one
//! evaluation, the offset h and the cosine factor of its `f`, and the conversions to and
//! from hairmath's.
//!
//! | | hairmath | pbrt (v3, v4 `HairBxDF`) | Mitsuba 3 (`hair` BSDF) |
//! | --- | --- | --- | --- |
//! | fibre tangent | local +X | local +X | local +Y |
//! | `sin theta` | `w.x` | `w.x` | `w.y` |
//! | azimuth | `atan2(w.z, w.y)` | `atan2(w.z, w.y)` | `atan2(w.z, w.x)` |
//! | first direction `wi` | towards the light | towards the light | `si.wi`, towards the camera |
//! | second direction `wo` | towards the viewer | towards the viewer | the `wo` argument, towards the light |
//! | offset `h` | an input | an input (from the curve's v) | implied by `si.wi`: `sin(gamma)`, gamma its angle from the normal +Z in the XZ plane, positive where `x < 0` |
//! | returned `f` | S, no cosine factor | `S / abs(wi.z)` (S where `wi.z = 0`): the integrator multiplies by the cosine to its normal +Z | S, no cosine factor |
//!
//! Both other renderers write the lobes in terms of the relative azimuth from the camera's
//! direction to the light's and `Phi(p, h) = 2 p gamma_t - 2 gamma + p pi` with
//! `h = sin gamma` (Chiang et al. 2016, eq. 8 and pbrt's `Np`; Mitsuba's
//! `azimuthal_scattering`), so the mapping keeps the azimuth's orientation: Mitsuba's
//! `(X, Y, Z)` is hairmath's `(y, x, z)` (a reflection, which swapping the tangent into +Y
//! needs) after a rotation about the tangent that puts the camera's direction where Mitsuba
//! reads hairmath's `h` from it. The rotation changes neither S nor any angle the model uses.

use crate::bcsdf::Query;
use crate::error::ParamError;
use glam::DVec3;

/// A renderer's convention for the arguments and the value of its hair BSDF.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Convention {
    /// hairmath's own ([`Query`], [`crate::bcsdf::Bcsdf::eval`]).
    Hairmath,
    /// pbrt-v3 and pbrt-v4's `HairBxDF::f(wo, wi)`.
    Pbrt,
    /// Mitsuba 3's `hair` BSDF, `eval(ctx, si, wo)`.
    Mitsuba,
}

/// One evaluation's inputs as a renderer of some [`Convention`] states them: `wi` and `wo` in
/// the convention's local frame and meaning (the module's table), and `h` where the
/// convention takes it as an input.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ConventionQuery {
    /// The convention's first direction.
    pub wi: DVec3,
    /// The convention's second direction.
    pub wo: DVec3,
    /// The offset, for the conventions that take it (`None` for Mitsuba's).
    pub h: Option<f64>,
}

impl Convention {
    /// Every convention, with its name on the command line.
    pub const ALL: [(Convention, &'static str); 3] = [
        (Convention::Hairmath, "hairmath"),
        (Convention::Pbrt, "pbrt"),
        (Convention::Mitsuba, "mitsuba"),
    ];

    /// The convention called `name` (`hairmath`, `pbrt`, `mitsuba`).
    pub fn from_name(name: &str) -> Option<Convention> {
        Self::ALL.iter().find(|(_, n)| *n == name).map(|(c, _)| *c)
    }

    /// Its name on the command line.
    pub fn name(self) -> &'static str {
        Self::ALL
            .iter()
            .find(|(c, _)| *c == self)
            .map_or("", |(_, n)| n)
    }

    /// Whether the convention takes `h` as an input (Mitsuba's implies it from the camera's
    /// direction).
    pub fn has_offset(self) -> bool {
        self != Convention::Mitsuba
    }

    /// hairmath's `query` in this convention: the same evaluation, whose S the other renderer
    /// should reproduce (up to the cosine factor of [`Convention::f_of_s`]).
    pub fn from_hairmath(self, query: &Query<f64>) -> ConventionQuery {
        let (wi, wo) = (DVec3::from(query.wi), DVec3::from(query.wo));
        match self {
            Convention::Hairmath | Convention::Pbrt => ConventionQuery {
                wi,
                wo,
                h: Some(query.h),
            },
            Convention::Mitsuba => {
                let h = query.h.clamp(-1.0, 1.0);
                // Where Mitsuba reads h from the camera's direction: azimuth (cos, sin) =
                // (-h, sqrt(1 - h^2)) in hairmath's YZ plane.
                let target = (1.0 - h * h).max(0.0).sqrt().atan2(-h);
                let rotation = target - wo.z.atan2(wo.y);
                let to_mitsuba = |w: DVec3| {
                    let (s, c) = rotation.sin_cos();
                    let (y, z) = (c * w.y - s * w.z, s * w.y + c * w.z);
                    DVec3::new(y, w.x, z)
                };
                ConventionQuery {
                    wi: to_mitsuba(wo),
                    wo: to_mitsuba(wi),
                    h: None,
                }
            }
        }
    }

    /// The hairmath query of `query` given in this convention, checked as
    /// [`Query::checked`] checks untrusted values.
    ///
    /// # Errors
    /// [`ParamError::Missing`] naming `h` if the convention takes it and it is absent,
    /// [`ParamError::OutOfRange`] naming `h` if Mitsuba's convention is given one, or as
    /// [`Query::checked`].
    pub fn to_hairmath(self, query: &ConventionQuery) -> Result<Query<f64>, ParamError> {
        match self {
            Convention::Hairmath | Convention::Pbrt => {
                let h = query.h.ok_or(ParamError::Missing { name: "h" })?;
                Query::checked(query.wi.into(), query.wo.into(), h)
            }
            Convention::Mitsuba => {
                if let Some(h) = query.h {
                    return Err(ParamError::OutOfRange {
                        name: "h",
                        value: h,
                        allowed: "Mitsuba's convention implies h from wi (towards the camera); \
                                  give no h",
                    });
                }
                let from_mitsuba = |w: DVec3| DVec3::new(w.y, w.x, w.z);
                let camera = query.wi;
                let h = mitsuba_offset(camera);
                Query::checked(
                    from_mitsuba(query.wo).into(),
                    from_mitsuba(camera).into(),
                    h,
                )
            }
        }
    }

    /// The convention's `f` from hairmath's `s` at hairmath's `query`: S itself for hairmath
    /// and Mitsuba, `S / abs(cos)` for pbrt with the cosine to pbrt's normal +Z of the light's
    /// direction (S where that cosine is 0, as pbrt's `f` leaves it).
    pub fn f_of_s(self, s: [f64; 3], query: &Query<f64>) -> [f64; 3] {
        let scale = self.cosine_divisor(query);
        s.map(|v| v / scale)
    }

    /// hairmath's S from the convention's `f` at hairmath's `query` (the inverse of
    /// [`Convention::f_of_s`]).
    pub fn s_of_f(self, f: [f64; 3], query: &Query<f64>) -> [f64; 3] {
        let scale = self.cosine_divisor(query);
        f.map(|v| v * scale)
    }

    /// What the convention divides S by: `abs(wi.z)` for pbrt (1 where it is 0), 1 otherwise.
    fn cosine_divisor(self, query: &Query<f64>) -> f64 {
        match self {
            Convention::Pbrt if query.wi.z != 0.0 => query.wi.z.abs(),
            _ => 1.0,
        }
    }
}

/// The offset Mitsuba 3 reads from the camera's direction `w` in its local frame: `sin gamma`
/// with gamma the angle of `w`'s projection on the XZ plane from +Z, positive where `x < 0`
/// (0 for a direction along the tangent).
fn mitsuba_offset(w: DVec3) -> f64 {
    let projection = w.x.hypot(w.z);
    if projection == 0.0 {
        0.0
    } else {
        (-w.x / projection).clamp(-1.0, 1.0)
    }
}

/// The CSV columns of a query in `convention`: `wi_x..wo_z`, and `h` where the convention
/// takes it.
pub fn query_columns(convention: Convention) -> &'static [&'static str] {
    let all = &crate::csv::EVAL_COLUMNS;
    if convention.has_offset() {
        all
    } else {
        &all[..6]
    }
}
