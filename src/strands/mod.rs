//! Hair geometry: strands as polylines of points with per-point thickness, transparency and
//! colour, as Cem Yuksel's `.hair` format stores them ([`hair_file`]); procedural grooms
//! ([`groom`]); and the per-vertex transmittance of Gerard's shading, baked to spherical
//! harmonics ([`transmittance`]) from the segments as cylinders in a bounding-volume hierarchy
//! ([`occluders`]) and, for the fast baker's far field, as a medium ([`density`]).
//!
//! [`Strands`] is the one geometry type every part reads: it is validated once, when it is
//! built, so the readers, generators and bakers never see a NaN point, a negative thickness or a
//! point count that does not match the strands' segment counts.

pub mod density;
pub mod groom;
pub mod hair_file;
pub mod occluders;
pub mod pencil;
pub mod transmittance;

use core::ops::Range;
use glam::Vec3;

/// How many segments each strand has (a strand of `s` segments has `s + 1` points).
#[derive(Clone, Debug, PartialEq)]
pub enum SegmentCounts {
    /// Every strand has the same segment count (the `.hair` header's default).
    Uniform {
        /// The number of strands.
        strands: usize,
        /// Segments per strand.
        segments: u16,
    },
    /// One segment count per strand (the `.hair` segments array).
    PerStrand(Vec<u16>),
}

impl SegmentCounts {
    /// The number of strands.
    pub fn strand_count(&self) -> usize {
        match self {
            Self::Uniform { strands, .. } => *strands,
            Self::PerStrand(counts) => counts.len(),
        }
    }

    /// The segment count of strand `strand` (`strand < strand_count()`).
    fn segments_of(&self, strand: usize) -> u16 {
        match self {
            Self::Uniform { segments, .. } => *segments,
            Self::PerStrand(counts) => counts[strand],
        }
    }
}

/// A per-point attribute: one value for every point (the `.hair` header's default) or one
/// value per point (the file's array).
#[derive(Clone, Debug, PartialEq)]
pub enum PointAttribute<T> {
    /// The same value at every point.
    Uniform(T),
    /// One value per point, in point order.
    PerPoint(Vec<T>),
}

impl<T: Copy> PointAttribute<T> {
    /// The value at point `point` (`point < point_count`, checked when the strands were built).
    pub fn at(&self, point: usize) -> T {
        match self {
            Self::Uniform(value) => *value,
            Self::PerPoint(values) => values[point],
        }
    }

    /// Every value, uniform or per point.
    fn values(&self) -> &[T] {
        match self {
            Self::Uniform(value) => core::slice::from_ref(value),
            Self::PerPoint(values) => values,
        }
    }
}

/// Why a set of strands is invalid: the field, the index of the first bad entry and the rule
/// it breaks.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum StrandsError {
    /// A value outside its domain.
    #[error("{field}[{index}] = {value} is not allowed: {allowed}")]
    BadValue {
        /// The field (`points`, `thickness`, `transparency` or `colour`).
        field: &'static str,
        /// The index of the bad entry (0 for a uniform value).
        index: usize,
        /// The value as text (a point or colour as `(x, y, z)`).
        value: String,
        /// The domain, in words.
        allowed: &'static str,
    },
    /// An array whose length does not match what the segment counts imply.
    #[error("{field} has {found} entries, but the segment counts imply {expected}")]
    WrongLength {
        /// The field.
        field: &'static str,
        /// The length implied by the segment counts.
        expected: usize,
        /// The length given.
        found: usize,
    },
}

/// Strands: polylines of points with thickness (a diameter, in the points' units),
/// transparency (in `[0, 1]`; 0 is opaque) and colour (linear RGB, non-negative) per point.
///
/// Built only by [`Strands::new`], which validates every field.
#[derive(Clone, Debug, PartialEq)]
pub struct Strands {
    segments: SegmentCounts,
    points: Vec<Vec3>,
    thickness: PointAttribute<f32>,
    transparency: PointAttribute<f32>,
    colour: PointAttribute<Vec3>,
    /// `first_point[s]..first_point[s + 1]` are strand `s`'s points.
    first_point: Vec<usize>,
}

impl Strands {
    /// Strands from their segment counts, points and attributes.
    ///
    /// # Errors
    /// [`StrandsError::WrongLength`] if `points` does not hold `sum(segments + 1)` points or a
    /// per-point attribute does not hold one value per point; [`StrandsError::BadValue`] for a
    /// non-finite point, a thickness that is negative or not finite, a transparency outside
    /// `[0, 1]`, or a colour component that is negative or not finite.
    pub fn new(
        segments: SegmentCounts,
        points: Vec<Vec3>,
        thickness: PointAttribute<f32>,
        transparency: PointAttribute<f32>,
        colour: PointAttribute<Vec3>,
    ) -> Result<Self, StrandsError> {
        let point_count = implied_point_count(&segments);
        check_length("points", point_count, points.len())?;
        let first_point = first_points(&segments);
        check_vectors("points", &points, "must be finite", |_| true)?;
        check_attribute("thickness", &thickness, point_count)?;
        check_scalars(
            "thickness",
            thickness.values(),
            "must be finite and >= 0",
            |t| t >= 0.0,
        )?;
        check_attribute("transparency", &transparency, point_count)?;
        check_scalars(
            "transparency",
            transparency.values(),
            "must be in [0, 1]",
            |t| (0.0..=1.0).contains(&t),
        )?;
        check_attribute("colour", &colour, point_count)?;
        check_vectors("colour", colour.values(), "must be finite and >= 0", |c| {
            c.min_element() >= 0.0
        })?;
        Ok(Self {
            segments,
            points,
            thickness,
            transparency,
            colour,
            first_point,
        })
    }

    /// The number of strands.
    pub fn strand_count(&self) -> usize {
        self.segments.strand_count()
    }

    /// The number of points (vertices) over all strands.
    pub fn point_count(&self) -> usize {
        self.points.len()
    }

    /// The point indices of strand `strand`, or `None` if there is no such strand.
    pub fn strand_points(&self, strand: usize) -> Option<Range<usize>> {
        (strand < self.strand_count())
            .then(|| self.first_point[strand]..self.first_point[strand + 1])
    }

    /// The segment counts as given.
    pub fn segments(&self) -> &SegmentCounts {
        &self.segments
    }

    /// Every point, strand after strand.
    pub fn points(&self) -> &[Vec3] {
        &self.points
    }

    /// The thickness (diameter) per point.
    pub fn thickness(&self) -> &PointAttribute<f32> {
        &self.thickness
    }

    /// The transparency per point (0 opaque, 1 invisible).
    pub fn transparency(&self) -> &PointAttribute<f32> {
        &self.transparency
    }

    /// The colour per point.
    pub fn colour(&self) -> &PointAttribute<Vec3> {
        &self.colour
    }

    /// Every segment: the strand it belongs to and its two point indices.
    pub fn segment_iter(&self) -> impl Iterator<Item = Segment> + '_ {
        (0..self.strand_count()).flat_map(move |strand| {
            let first = self.first_point[strand];
            (0..usize::from(self.segments.segments_of(strand))).map(move |k| Segment {
                strand,
                start: first + k,
            })
        })
    }

    /// The strand that point `point` belongs to, or `None` past the last point.
    pub fn strand_of_point(&self, point: usize) -> Option<usize> {
        (point < self.point_count())
            .then(|| self.first_point.partition_point(|&first| first <= point) - 1)
    }
}

/// One segment of a strand: from point `start` to point `start + 1`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Segment {
    /// The strand's index.
    pub strand: usize,
    /// The index of the segment's first point (its second is `start + 1`).
    pub start: usize,
}

/// The number of points the segment counts imply, saturating at `usize::MAX` (which no
/// points vector can match), so a huge uniform strand count is rejected before any work.
fn implied_point_count(segments: &SegmentCounts) -> usize {
    match segments {
        SegmentCounts::Uniform { strands, segments } => {
            strands.saturating_mul(usize::from(*segments) + 1)
        }
        SegmentCounts::PerStrand(counts) => counts.iter().map(|&s| usize::from(s) + 1).sum(),
    }
}

/// Prefix sums of the strands' point counts: `first[s]` is strand `s`'s first point, the last
/// entry the total. Called after the point count was checked against the points given, so its
/// length is bounded by that vector's.
fn first_points(segments: &SegmentCounts) -> Vec<usize> {
    let mut first = Vec::with_capacity(segments.strand_count() + 1);
    first.push(0);
    let mut total = 0;
    for strand in 0..segments.strand_count() {
        total += usize::from(segments.segments_of(strand)) + 1;
        first.push(total);
    }
    first
}

fn check_length(field: &'static str, expected: usize, found: usize) -> Result<(), StrandsError> {
    if expected == found {
        Ok(())
    } else {
        Err(StrandsError::WrongLength {
            field,
            expected,
            found,
        })
    }
}

fn check_attribute<T>(
    field: &'static str,
    attribute: &PointAttribute<T>,
    points: usize,
) -> Result<(), StrandsError> {
    match attribute {
        PointAttribute::Uniform(_) => Ok(()),
        PointAttribute::PerPoint(values) => check_length(field, points, values.len()),
    }
}

fn check_scalars(
    field: &'static str,
    values: &[f32],
    allowed: &'static str,
    ok: impl Fn(f32) -> bool,
) -> Result<(), StrandsError> {
    match values.iter().position(|&v| !(v.is_finite() && ok(v))) {
        None => Ok(()),
        Some(index) => Err(StrandsError::BadValue {
            field,
            index,
            value: values[index].to_string(),
            allowed,
        }),
    }
}

fn check_vectors(
    field: &'static str,
    values: &[Vec3],
    allowed: &'static str,
    ok: impl Fn(Vec3) -> bool,
) -> Result<(), StrandsError> {
    match values.iter().position(|&v| !(v.is_finite() && ok(v))) {
        None => Ok(()),
        Some(index) => Err(StrandsError::BadValue {
            field,
            index,
            value: format!(
                "({}, {}, {})",
                values[index].x, values[index].y, values[index].z
            ),
            allowed,
        }),
    }
}
