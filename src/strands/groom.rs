//! Procedural grooms: seeded, deterministic strands on a scalp, the test data of the
//! transmittance bakers ([`super::transmittance`]) and of `hairmath groom`.
//!
//! The head is the unit sphere centred at the origin, +Y up; the scalp is the cap of polar
//! angle at most [`SCALP_CAP_DEGREES`] around +Y. Roots are uniform by area on the cap. A
//! strand's centreline leaves its root along the outward normal and turns, over the first
//! [`GRAVITY_TURN`] of its length, towards its fall: down (-Y) and a little outwards, in the
//! direction of the root's azimuth (as hair parted at the crown falls); it is integrated in
//! equal steps and pushed out of the head where it would enter it, so it hangs along it. Wavy strands add a planar sine displacement
//! across the centreline, curly strands a helix around it, both faded in over the first
//! [`CURL_FADE_IN`] of the length so the roots stay on the scalp. Each strand draws its length,
//! phase, amplitude and wavelength from its own PCG stream seeded by `(seed, strand index)`,
//! so strand `k` is the same whatever the strand count.
//!
//! Units: the head radius is 1 (read it as 10 cm). A real head carries about 100,000 hairs of
//! about 80 um (0.008 head radii would be 800 um); these grooms have ten times fewer strands,
//! and the default thickness [`GroomSettings::DEFAULT_THICKNESS`] is ten times a real hair's
//! so that the groom covers the same projected area and its transmittance is as dark as a
//! real head's.

use super::{PointAttribute, SegmentCounts, Strands};
use crate::error::ParamError;
use core::f32::consts::TAU;
use glam::Vec3;
use rand_pcg::rand_core::{RngCore, SeedableRng};
use rand_pcg::Pcg64Mcg;

/// The scalp: the cap of polar angles up to this many degrees around +Y.
pub const SCALP_CAP_DEGREES: f32 = 75.0;
/// The share of a strand's length over which it turns from the scalp normal to -Y.
pub const GRAVITY_TURN: f32 = 0.35;
/// The share of a strand's length over which waves and curls fade in from the root.
pub const CURL_FADE_IN: f32 = 0.15;
/// The fall's horizontal part, outwards, for a unit downward part.
const FALL_OUTWARDS: f32 = 0.3;
/// Centrelines stay at least this far outside the unit head.
const HEAD_CLEARANCE: f32 = 0.01;

/// The shape of the strands.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum GroomKind {
    /// The centreline alone.
    Straight,
    /// A planar sine wave across the centreline: 3 waves per strand, amplitude 0.04.
    Wavy,
    /// A helix around the centreline: 4 turns per strand, radius 0.05.
    Curly,
}

impl GroomKind {
    /// Every kind, in the order of the command line's help.
    pub const ALL: [GroomKind; 3] = [GroomKind::Straight, GroomKind::Wavy, GroomKind::Curly];

    /// The kind's name on the command line.
    pub fn name(self) -> &'static str {
        match self {
            GroomKind::Straight => "straight",
            GroomKind::Wavy => "wavy",
            GroomKind::Curly => "curly",
        }
    }

    /// The kind named `name` (`straight`, `wavy` or `curly`).
    pub fn from_name(name: &str) -> Option<GroomKind> {
        GroomKind::ALL.into_iter().find(|kind| kind.name() == name)
    }

    /// Waves or turns per strand, and their amplitude (head radii); zero for straight hair.
    fn shape(self) -> (f32, f32) {
        match self {
            GroomKind::Straight => (0.0, 0.0),
            GroomKind::Wavy => (3.0, 0.04),
            GroomKind::Curly => (4.0, 0.05),
        }
    }
}

/// What to grow. Every field is checked by [`groom`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct GroomSettings {
    /// The shape of the strands.
    pub kind: GroomKind,
    /// The number of strands, in `[1, MAX_STRANDS]`.
    pub strands: usize,
    /// Points per strand (segments + 1), in `[2, 65536]`.
    pub points: usize,
    /// The seed of the strands' random streams.
    pub seed: u64,
    /// The thickness (diameter) at the root, in head radii, in `(0, 0.1]`; it tapers linearly
    /// to half that at the tip.
    pub thickness: f32,
    /// The mean strand length in head radii, in `(0, 10]`; each strand's is within 15% of it.
    pub length: f32,
    /// The transparency stored at every point, in `[0, 1]` (0 opaque).
    pub transparency: f32,
}

impl GroomSettings {
    /// The default root thickness, 0.008 head radii (see the module documentation).
    pub const DEFAULT_THICKNESS: f32 = 0.008;
    /// The default mean length, 1.5 head radii.
    pub const DEFAULT_LENGTH: f32 = 1.5;
    /// The most strands a groom may have.
    pub const MAX_STRANDS: usize = 1_000_000;
    /// The most points a groom may have in all.
    pub const MAX_POINTS: usize = 64_000_000;

    /// `strands` strands of `points` points of `kind`, with the default thickness and length,
    /// opaque.
    pub fn new(kind: GroomKind, strands: usize, points: usize, seed: u64) -> Self {
        Self {
            kind,
            strands,
            points,
            seed,
            thickness: Self::DEFAULT_THICKNESS,
            length: Self::DEFAULT_LENGTH,
            transparency: 0.0,
        }
    }

    fn check(&self) -> Result<(), ParamError> {
        let max_strands = Self::MAX_STRANDS as f64;
        ParamError::check(
            "strands",
            self.strands as f64,
            "must be in [1, 1000000]",
            |n| (1.0..=max_strands).contains(&n),
        )?;
        ParamError::check(
            "points",
            self.points as f64,
            "must be in [2, 65536] (a strand has at most 65535 segments)",
            |n| (2.0..=65536.0).contains(&n),
        )?;
        let total = self.strands as f64 * self.points as f64;
        ParamError::check("strands x points", total, "must be at most 64000000", |n| {
            n <= Self::MAX_POINTS as f64
        })?;
        ParamError::check(
            "thickness",
            f64::from(self.thickness),
            "must be in (0, 0.1] head radii",
            |t| t > 0.0 && t <= 0.1,
        )?;
        ParamError::check(
            "length",
            f64::from(self.length),
            "must be in (0, 10] head radii",
            |l| l > 0.0 && l <= 10.0,
        )?;
        ParamError::check(
            "transparency",
            f64::from(self.transparency),
            "must be in [0, 1]",
            |t| (0.0..=1.0).contains(&t),
        )?;
        Ok(())
    }
}

/// Grows the groom `settings` describes: `settings.strands` strands of `settings.points`
/// points each, with per-point thickness, uniform transparency and a brown colour.
///
/// # Errors
/// [`ParamError::OutOfRange`] naming the setting outside its domain (see [`GroomSettings`]).
pub fn groom(settings: &GroomSettings) -> Result<Strands, ParamError> {
    settings.check()?;
    let mut points = Vec::with_capacity(settings.strands * settings.points);
    let mut thickness = Vec::with_capacity(points.capacity());
    for strand in 0..settings.strands {
        let shape = StrandShape::draw(settings, strand);
        for k in 0..settings.points {
            let s = k as f32 / (settings.points - 1) as f32;
            thickness.push(settings.thickness * (1.0 - 0.5 * s));
        }
        shape.grow(settings, &mut points);
    }
    let segments = SegmentCounts::Uniform {
        strands: settings.strands,
        segments: (settings.points - 1) as u16,
    };
    Strands::new(
        segments,
        points,
        PointAttribute::PerPoint(thickness),
        PointAttribute::Uniform(settings.transparency),
        PointAttribute::Uniform(Vec3::new(0.35, 0.22, 0.12)),
    )
    .map_err(|e| unreachable!("a groom is valid by construction: {e}"))
}

/// One strand's random draws.
struct StrandShape {
    root: Vec3,
    /// The direction the strand turns to.
    fall: Vec3,
    length: f32,
    phase: f32,
    amplitude: f32,
    waves: f32,
}

impl StrandShape {
    /// Strand `index`'s draws from its own stream.
    fn draw(settings: &GroomSettings, index: usize) -> Self {
        let mut rng = Pcg64Mcg::seed_from_u64(
            settings.seed ^ (index as u64).wrapping_mul(0x9e37_79b9_7f4a_7c15),
        );
        let mut uniform = || (rng.next_u64() >> 40) as f32 / (1u64 << 24) as f32;
        let cos_cap = SCALP_CAP_DEGREES.to_radians().cos();
        let cos_theta = 1.0 - uniform() * (1.0 - cos_cap);
        let sin_theta = (1.0 - cos_theta * cos_theta).max(0.0).sqrt();
        let azimuth = TAU * uniform();
        let (waves, amplitude) = settings.kind.shape();
        let outwards = Vec3::new(azimuth.cos(), 0.0, azimuth.sin());
        Self {
            root: Vec3::new(
                sin_theta * azimuth.cos(),
                cos_theta,
                sin_theta * azimuth.sin(),
            ),
            fall: (outwards * FALL_OUTWARDS + Vec3::NEG_Y).normalize(),
            length: settings.length * (0.85 + 0.3 * uniform()),
            phase: TAU * uniform(),
            amplitude: amplitude * (0.8 + 0.4 * uniform()),
            waves: waves * (0.8 + 0.4 * uniform()),
        }
    }

    /// Appends the strand's `settings.points` points to `points`.
    fn grow(&self, settings: &GroomSettings, points: &mut Vec<Vec3>) {
        let step = self.length / (settings.points - 1) as f32;
        let mut centre = self.root;
        let mut tangent = self.root;
        // A frame across the centreline, carried along it by projection (rotation-minimising
        // to first order): the wave's direction and the helix's first axis.
        let mut across = Vec3::Y.cross(self.root).try_normalize().unwrap_or(Vec3::X);
        for k in 0..settings.points {
            let s = k as f32 * step / self.length;
            let fade = smoothstep(s / CURL_FADE_IN);
            let angle = TAU * self.waves * s + self.phase;
            let offset = match settings.kind {
                GroomKind::Straight => Vec3::ZERO,
                GroomKind::Wavy => across * angle.sin(),
                GroomKind::Curly => across * angle.cos() + tangent.cross(across) * angle.sin(),
            };
            let point = centre + offset * (self.amplitude * fade);
            points.push(if k == 0 {
                point
            } else {
                push_out_of_head(point)
            });
            let turn = smoothstep(s / GRAVITY_TURN);
            tangent = self
                .root
                .lerp(self.fall, turn)
                .try_normalize()
                .unwrap_or(self.fall);
            across = (across - tangent * across.dot(tangent))
                .try_normalize()
                .unwrap_or_else(|| tangent.any_orthonormal_vector());
            centre = step_along_head(centre, tangent, step);
        }
    }
}

/// `3 t^2 - 2 t^3` for `t` clamped to `[0, 1]`.
fn smoothstep(t: f32) -> f32 {
    let t = t.clamp(0.0, 1.0);
    t * t * (3.0 - 2.0 * t)
}

/// A step of `length` from `centre` along `tangent`; where that would enter the head, along
/// `tangent`'s part across the head's normal instead (the strand slides along the scalp),
/// pushed out of the head.
fn step_along_head(centre: Vec3, tangent: Vec3, length: f32) -> Vec3 {
    let next = centre + tangent * length;
    if next.length() >= 1.0 + HEAD_CLEARANCE {
        return next;
    }
    let normal = centre.try_normalize().unwrap_or(Vec3::Y);
    let along = (tangent - normal * tangent.dot(normal))
        .try_normalize()
        .unwrap_or_else(|| normal.any_orthonormal_vector());
    push_out_of_head(centre + along * length)
}

/// `p`, or its projection onto the sphere of radius `1 + HEAD_CLEARANCE` if it is inside it.
fn push_out_of_head(p: Vec3) -> Vec3 {
    let radius = 1.0 + HEAD_CLEARANCE;
    let length = p.length();
    if length < radius && length > 0.0 {
        p * (radius / length)
    } else {
        p
    }
}
