//! The lookup-table type: f32 samples on a regular grid of one to three axes, with
//! clamp-to-edge (bi/tri)linear interpolation.

use super::{LutError, ShapeError};
use crate::real::Real;

/// Largest number of axes of a [`Table`].
pub const MAX_AXES: usize = 3;

/// Largest number of samples along one axis.
pub const MAX_AXIS_SIZE: usize = 1 << 16;

/// Largest number of channels per texel.
pub const MAX_CHANNELS: usize = 16;

/// Largest total number of f32 values in a table (256 Mi values, 1 GiB).
pub const MAX_VALUES: usize = 1 << 28;

/// One axis of a table: `size` samples at the **endpoints** convention, sample `i` at
/// `min + i (max - min) / (size - 1)`, so the first and last samples sit exactly at `min` and
/// `max`. A GPU that samples a texture with texel-centre addressing reads the same value at the
/// normalised coordinate `u = (0.5 + t (size - 1)) / size`, `t = (x - min) / (max - min)`.
#[derive(Clone, Debug, PartialEq)]
pub struct Axis {
    name: String,
    min: f64,
    max: f64,
    size: usize,
}

impl Axis {
    /// An axis named `name` (as the JSON description spells it) from `min` to `max` (finite,
    /// `min < max`) with `size` samples in `2..=65536`.
    ///
    /// # Errors
    /// [`LutError::Axis`] for a non-finite or empty range or a size outside the allowed range.
    pub fn new(name: &str, min: f64, max: f64, size: usize) -> Result<Self, LutError> {
        let bad = |reason: &'static str| LutError::Axis {
            name: name.to_string(),
            min,
            max,
            size,
            reason,
        };
        if !(min.is_finite() && max.is_finite()) || min >= max {
            return Err(bad("the range must be finite with min < max"));
        }
        if !(2..=MAX_AXIS_SIZE).contains(&size) {
            return Err(bad("the size must be in 2..=65536"));
        }
        Ok(Axis {
            name: name.to_string(),
            min,
            max,
            size,
        })
    }

    /// The axis name.
    pub fn name(&self) -> &str {
        &self.name
    }
    /// Coordinate of the first sample.
    pub fn min(&self) -> f64 {
        self.min
    }
    /// Coordinate of the last sample.
    pub fn max(&self) -> f64 {
        self.max
    }
    /// Number of samples.
    pub fn size(&self) -> usize {
        self.size
    }
    /// Coordinate of sample `i`: `min + i (max - min) / (size - 1)`, exactly `max` for the last.
    pub fn sample(&self, i: usize) -> f64 {
        if i + 1 >= self.size {
            self.max
        } else {
            self.min + (self.max - self.min) * i as f64 / (self.size - 1) as f64
        }
    }
}

/// The interpolation cell and weight along one axis, written over [`Real`] so that the same code
/// traces to shader code: with `t = clamp((x - min) / (max - min), 0, 1) (size - 1)`, returns
/// `(i0, f)` with `i0 = min(floor(t), size - 2)` (an integer-valued `R`) and `f = t - i0` in
/// [0, 1]; the value is `(1 - f) v[i0] + f v[i0 + 1]`. Coordinates outside the range clamp to
/// the edge (`f` = 0 at `min`, 1 at `max`). A NaN coordinate is treated as `min`.
/// Requires `min < max` and `size >= 2`.
#[inline(always)]
pub fn axis_cell<R: Real>(x: R, min: f64, max: f64, size: usize) -> (R, R) {
    let last = (size.max(2) - 1) as f64;
    let u = ((x - R::c(min)) * R::c(1.0 / (max - min)))
        .max(R::c(0.0))
        .min(R::c(1.0));
    let t = u * R::c(last);
    let i0 = t.floor().min(R::c(last - 1.0));
    (i0, t - i0)
}

/// The weight of corner `corner` of a cell (axis `d` at its upper sample when bit `d` of
/// `corner` is set) and, in `index`, the corner's sample indices from the cell's lower ones
/// `base`: the product of the factors `frac[d]` (upper) or `1 - frac[d]` (lower) in axis order,
/// starting from the first (1 for a table of no axes). Every interpolation of a table, on the
/// CPU and in shader code, forms its weights so.
#[inline(always)]
pub(crate) fn corner_weight<R: Real>(
    corner: usize,
    base: &[usize],
    frac: &[R],
    index: &mut [usize],
) -> R {
    let mut weight = None;
    for (d, (&f, i)) in frac.iter().zip(index.iter_mut()).enumerate() {
        let upper = (corner >> d) & 1 == 1;
        *i = base[d] + usize::from(upper);
        let factor = if upper { f } else { R::c(1.0) - f };
        weight = Some(weight.map_or(factor, |w: R| w * factor));
    }
    weight.unwrap_or(R::c(1.0))
}

/// The running sum of an interpolation after the term of corner `corner`: the term itself for
/// the first corner, `sum + term` after it (the order of every interpolation of a table).
#[inline(always)]
pub(crate) fn accumulate<R: Real>(corner: usize, sum: R, term: R) -> R {
    if corner == 0 {
        term
    } else {
        sum + term
    }
}

/// A lookup table: `channels` f32 values per grid point of one to three [`Axis`] values.
///
/// Memory layout (also of the raw file): channel fastest, then axis 0, then axis 1, then
/// axis 2; the value of channel `c` at sample `(i, j, k)` is at
/// `((k n1 + j) n0 + i) C + c`. For a 2D table this is a row-major image whose x is axis 0 and
/// whose rows are axis 1.
#[derive(Clone, Debug, PartialEq)]
pub struct Table {
    axes: Vec<Axis>,
    channels: Vec<String>,
    data: Vec<f32>,
    meta: TableMeta,
}

/// A parameter value recorded in a table's JSON description.
#[derive(Clone, Debug, PartialEq)]
pub enum ParamValue {
    /// A number (finite).
    Number(f64),
    /// A list of numbers (for example an RGB absorption).
    Numbers(Vec<f64>),
    /// Free text.
    Text(String),
    /// A yes/no choice.
    Flag(bool),
}

/// What a table is: written to its JSON description.
#[derive(Clone, Debug, PartialEq, Default)]
pub struct TableMeta {
    /// The table kind (for example `gerard`).
    pub kind: String,
    /// What the channels hold, in words.
    pub description: String,
    /// The parameters the table was baked with, in order.
    pub parameters: Vec<(String, ParamValue)>,
    /// Per channel, the value an 8-bit texel of 255 stands for; empty for the default
    /// ([`Table::png_scale`]).
    pub png_scale: Vec<f32>,
}

impl Table {
    /// A table over `axes` (1 to 3) with the named `channels` (1 to 16) and `data` in the
    /// layout described on [`Table`].
    ///
    /// # Errors
    /// [`LutError::Shape`] when the counts do not fit together or exceed the limits.
    pub fn new(axes: Vec<Axis>, channels: Vec<String>, data: Vec<f32>) -> Result<Self, LutError> {
        let expected = Self::value_count(&axes, channels.len())?;
        if data.len() != expected {
            return Err(LutError::Shape(ShapeError::DataLength {
                given: data.len(),
                expected,
            }));
        }
        Ok(Table {
            axes,
            channels,
            data,
            meta: TableMeta::default(),
        })
    }

    /// The table with its description replaced by `meta`.
    ///
    /// # Errors
    /// [`LutError::Shape`] if `meta.png_scale` is neither empty nor one positive finite value
    /// per channel.
    pub fn with_meta(mut self, meta: TableMeta) -> Result<Self, LutError> {
        if !meta.png_scale.is_empty()
            && (meta.png_scale.len() != self.channels.len()
                || meta.png_scale.iter().any(|s| !(s.is_finite() && *s > 0.0)))
        {
            return Err(LutError::Shape(ShapeError::PngScale));
        }
        self.meta = meta;
        Ok(self)
    }

    /// The description.
    pub fn meta(&self) -> &TableMeta {
        &self.meta
    }

    /// Per channel, the value an 8-bit texel of 255 stands for: `meta.png_scale` if given,
    /// else the channel's largest absolute value (1 for an all-zero channel).
    pub fn png_scale(&self) -> Vec<f32> {
        if self.meta.png_scale.len() == self.channels.len() {
            return self.meta.png_scale.clone();
        }
        self.channel_max()
            .into_iter()
            .map(|m| if m > 0.0 && m.is_finite() { m } else { 1.0 })
            .collect()
    }

    /// The number of f32 values a table of these axes and channel count holds.
    ///
    /// # Errors
    /// [`LutError::Shape`] for 0 or more than 3 axes, 0 or more than 16 channels, or more than
    /// [`MAX_VALUES`] values.
    pub fn value_count(axes: &[Axis], channels: usize) -> Result<usize, LutError> {
        if axes.is_empty() || axes.len() > MAX_AXES {
            return Err(LutError::Shape(ShapeError::AxisCount { axes: axes.len() }));
        }
        if channels == 0 || channels > MAX_CHANNELS {
            return Err(LutError::Shape(ShapeError::ChannelCount { channels }));
        }
        let mut total = channels;
        for a in axes {
            total = total
                .checked_mul(a.size)
                .filter(|&t| t <= MAX_VALUES)
                .ok_or(LutError::Shape(ShapeError::TooManyValues))?;
        }
        Ok(total)
    }

    /// The axes.
    pub fn axes(&self) -> &[Axis] {
        &self.axes
    }
    /// The channel names.
    pub fn channels(&self) -> &[String] {
        &self.channels
    }
    /// The samples, in the layout described on [`Table`].
    pub fn data(&self) -> &[f32] {
        &self.data
    }

    /// Flat index of channel 0 at grid point `index` (one entry per axis).
    fn offset(&self, index: &[usize]) -> usize {
        let mut flat = 0;
        for (a, &i) in self.axes.iter().zip(index).rev() {
            flat = flat * a.size + i;
        }
        flat * self.channels.len()
    }

    /// The stored value of `channel` at grid point `index` (one entry per axis), if in range.
    pub fn get(&self, index: &[usize], channel: usize) -> Option<f32> {
        if index.len() != self.axes.len()
            || channel >= self.channels.len()
            || index.iter().zip(&self.axes).any(|(&i, a)| i >= a.size)
        {
            return None;
        }
        Some(self.data[self.offset(index) + channel])
    }

    /// Largest absolute value of each channel (0 for an all-zero channel).
    pub fn channel_max(&self) -> Vec<f32> {
        let c = self.channels.len();
        let mut m = vec![0.0f32; c];
        for (k, v) in self.data.iter().enumerate() {
            m[k % c] = m[k % c].max(v.abs());
        }
        m
    }

    /// Interpolated values of every channel at `coords` (one coordinate per axis, in the axis'
    /// units), written to `out` (one value per channel): linear, bilinear or trilinear
    /// interpolation between the samples, clamp-to-edge outside the axis ranges (infinite
    /// coordinates included). Weights come from [`axis_cell`] evaluated in f32, as a shader
    /// would. The checked entry point: a NaN coordinate is an error here, where the hot path
    /// of the models ([`crate::lut::SharedTable`], shader code) takes it as the axis' minimum.
    ///
    /// # Errors
    /// [`LutError::Shape`] if `coords` or `out` have the wrong length;
    /// [`LutError::Coordinate`] for a NaN coordinate (`out` is then untouched).
    pub fn lookup_into(&self, coords: &[f32], out: &mut [f32]) -> Result<(), LutError> {
        self.check_lookup(coords, out.len())?;
        if let Some((axis, _)) = self.axes.iter().zip(coords).find(|(_, x)| x.is_nan()) {
            return Err(LutError::Coordinate {
                axis: axis.name.clone(),
            });
        }
        self.interpolate_into(coords, out);
        Ok(())
    }

    /// [`LutError::Shape`] unless there is one coordinate per axis and one output per channel.
    fn check_lookup(&self, coords: &[f32], outputs: usize) -> Result<(), LutError> {
        let (dims, nc) = (self.axes.len(), self.channels.len());
        if coords.len() != dims || outputs != nc {
            return Err(LutError::Shape(ShapeError::Lookup {
                coordinates: coords.len(),
                outputs,
                axes: dims,
                channels: nc,
            }));
        }
        Ok(())
    }

    /// The interpolation of [`Table::lookup_into`] for coordinates and outputs of the right
    /// lengths ([`Table::check_lookup`]); a NaN coordinate is taken as the axis' minimum
    /// ([`axis_cell`]), as the hot path and shader code do.
    pub(crate) fn interpolate_into(&self, coords: &[f32], out: &mut [f32]) {
        let dims = self.axes.len();
        let nc = self.channels.len();
        let mut base = [0usize; MAX_AXES];
        let mut frac = [0.0f32; MAX_AXES];
        for (d, (a, &x)) in self.axes.iter().zip(coords).enumerate() {
            let (i0, f) = axis_cell::<f32>(x, a.min, a.max, a.size);
            base[d] = i0 as usize;
            frac[d] = f;
        }
        // The 2^dims corners of the cell, the first term starting the sum.
        let mut index = [0usize; MAX_AXES];
        for corner in 0..(1usize << dims) {
            let w = corner_weight(corner, &base[..dims], &frac[..dims], &mut index[..dims]);
            let at = self.offset(&index[..dims]);
            for (o, v) in out.iter_mut().zip(&self.data[at..at + nc]) {
                *o = accumulate(corner, *o, w * v);
            }
        }
    }

    /// [`Table::lookup_into`] returning a new vector.
    ///
    /// # Errors
    /// [`LutError::Shape`] if `coords` has the wrong length; [`LutError::Coordinate`] for a NaN
    /// coordinate.
    pub fn lookup(&self, coords: &[f32]) -> Result<Vec<f32>, LutError> {
        let mut out = vec![0.0; self.channels.len()];
        self.lookup_into(coords, &mut out)?;
        Ok(out)
    }
}
