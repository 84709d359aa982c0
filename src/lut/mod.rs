//! Lookup tables: a small table type with (bi/tri)linear lookup, bakers for the tables the
//! real-time hair models use, the measured error of lookup against direct evaluation, and file
//! output (raw little-endian f32 with a JSON description, and 8-bit PNG with the `png` feature).
//!
//! # Tables ([`Table`])
//!
//! f32 samples on a regular grid of 1 to 3 [`Axis`] values, several channels per grid point.
//! Samples sit at the axis **endpoints** (sample `i` of `n` at `min + i (max - min) / (n - 1)`),
//! addressing clamps to the edge, and [`Table::lookup`] interpolates linearly along each axis.
//! The weight computation [`axis_cell`] is generic over [`crate::real::Real`] so it traces to
//! shader code; a GPU sampling the same data as a texture with texel-centre addressing uses
//! `u = (0.5 + t (n - 1)) / n` with `t = (x - min) / (max - min)`.
//!
//! Generic code fetches from a [`SharedTable`] (a table shared by reference counting, its
//! number of axes and channels in its type) with [`crate::real::Real::sample_table`]: `f32`
//! and every SIMD lane compute exactly [`Table::lookup_into`], `f64` interpolates in `f64`,
//! and a trace records the fetch, which prints as a texture sample.
//!
//! # Bakers ([`Baker`])
//!
//! All evaluation is f64, single-threaded and deterministic, so a table regenerates bit for bit
//! from its parameters.
//!
//! | baker | axes (0, 1, 2) | channels |
//! | --- | --- | --- |
//! | [`NguyenM`] | sin theta_i, sin theta_o in [-1, 1] | M_R, M_TT, M_TRT, cos theta_d |
//! | [`NguyenN`] | cos phi in [-1, 1], cos theta_d in [0, 1] | N_TT (r, g, b), N_R, N_TRT (r, g, b) |
//! | [`GerardN`] | phi in [0, pi], theta_d in [0, theta_d max] | N_R, N_TT, N_TRT (sigma_a = 0) |
//! | [`FarFieldN`] | phi in [0, pi], theta_o in [0, pi/2], beta_n | A_p N_p of R, TT, TRT, TRRT+ (r, g, b) |
//!
//! Each baker's documentation states exactly what its channels hold; [`lookup_error`] and
//! [`error_vs_resolution`] measure lookup against direct evaluation at off-grid points.
//!
//! # Files ([`write_raw`], and `write_png` with the `png` feature)
//!
//! `NAME.f32` holds the samples as little-endian f32 in the layout of [`Table`];
//! `NAME.f32.json` describes it (kind, axes with names, ranges and sizes, channels, parameters,
//! the 8-bit scale of each channel, generator version). An 8-bit PNG (RGBA8) stores
//! `round(255 clamp(value / scale, 0, 1))` per channel, `scale` from the JSON, so
//! `value ~ texel / 255 * scale`.

mod bake;
pub(crate) mod io;
mod shared;
mod table;

pub use bake::{
    bake, bake_with_progress, check_evaluations, error_vs_resolution, lookup_error,
    lookup_error_with_progress, Baker, ErrorStats, FarFieldN, GerardN, NguyenM, NguyenN,
    FAR_FIELD_CHANNELS, FAR_FIELD_MAX_EVALUATIONS, MAX_EVALUATIONS,
};
#[cfg(feature = "png")]
pub use io::write_png;
pub use io::{json_description, quantize_rgba8, raw_bytes, read_raw, write_raw, GENERATOR};
pub use shared::SharedTable;
pub use table::{
    axis_cell, Axis, ParamValue, Table, TableMeta, MAX_AXES, MAX_AXIS_SIZE, MAX_CHANNELS,
    MAX_VALUES,
};

use crate::error::ParamError;

/// Counts that do not fit together.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[non_exhaustive]
pub enum ShapeError {
    /// A baker was given a size per axis for the wrong number of axes.
    #[error("{kind} tables have {axes} axes; {sizes} sizes given")]
    Sizes {
        /// The baker's kind.
        kind: &'static str,
        /// Its number of axes.
        axes: usize,
        /// The number of sizes given.
        sizes: usize,
    },
    /// A table needs 1 to [`MAX_AXES`] axes.
    #[error("{axes} axes given, 1 to {MAX_AXES} allowed")]
    AxisCount {
        /// The number of axes given.
        axes: usize,
    },
    /// A table needs 1 to [`MAX_CHANNELS`] channels.
    #[error("{channels} channels given, 1 to {MAX_CHANNELS} allowed")]
    ChannelCount {
        /// The number of channels given.
        channels: usize,
    },
    /// The table would hold more than [`MAX_VALUES`] values.
    #[error("more than {MAX_VALUES} values in the table")]
    TooManyValues,
    /// The data does not have one value per grid point and channel.
    #[error("{given} values given, {expected} expected")]
    DataLength {
        /// Values given.
        given: usize,
        /// Values the axes and channels need.
        expected: usize,
    },
    /// The 8-bit scales are not one positive finite value per channel.
    #[error("png_scale needs one positive finite value per channel")]
    PngScale,
    /// A lookup with the wrong number of coordinates or outputs.
    #[error(
        "lookup with {coordinates} coordinates into {outputs} outputs; the table has {axes} axes \
         and {channels} channels"
    )]
    Lookup {
        /// Coordinates given.
        coordinates: usize,
        /// Output slots given.
        outputs: usize,
        /// The table's axes.
        axes: usize,
        /// The table's channels.
        channels: usize,
    },
    /// A table measured against a baker it was not baked from.
    #[error("the table ({axes} axes, {channels} channels) does not match the baker")]
    BakerMismatch {
        /// The table's axes.
        axes: usize,
        /// The table's channels.
        channels: usize,
    },
    /// A raw file whose length is not a whole number of f32 values.
    #[error("{path}: {bytes} bytes is not a whole number of f32 values")]
    RawLength {
        /// The file.
        path: String,
        /// Its length.
        bytes: usize,
    },
    /// 8-bit images are written for 2D tables only.
    #[error("8-bit images are written for 2D tables; this one has {axes} axes")]
    ImageAxes {
        /// The table's axes.
        axes: usize,
    },
    /// An RGBA8 image takes 1 to 4 existing channels.
    #[error("an RGBA8 image takes 1 to 4 of the table's {channels} channels; {requested:?} given")]
    ImageChannels {
        /// The table's channels.
        channels: usize,
        /// The channels asked for.
        requested: Vec<usize>,
    },
    /// An image side too large for the PNG format.
    #[error("{pixels} pixels is too wide")]
    ImageSize {
        /// The side's length.
        pixels: usize,
    },
}

/// Why a table could not be built, looked up or written.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum LutError {
    /// An invalid axis.
    #[error(
        "axis {name} ({} to {}, {size} samples) is not allowed: {reason}",
        crate::csv::format_number(*.min),
        crate::csv::format_number(*.max)
    )]
    Axis {
        /// The axis name.
        name: String,
        /// The given start of the range.
        min: f64,
        /// The given end of the range.
        max: f64,
        /// The given number of samples.
        size: usize,
        /// What is wrong.
        reason: &'static str,
    },
    /// Counts that do not fit together (axes, channels, sizes, coordinates, data length).
    #[error("table shape: {0}")]
    Shape(ShapeError),
    /// An invalid model parameter.
    #[error(transparent)]
    Param(#[from] ParamError),
    /// A lookup at a NaN coordinate ([`Table::lookup_into`]).
    #[error("the coordinate of axis {axis} is NaN (a coordinate must be a number; out-of-range ones clamp to the edge)")]
    Coordinate {
        /// The axis.
        axis: String,
    },
    /// More evaluations asked of a baker than it allows ([`Baker::max_evaluations`]).
    #[error("{kind} tables allow at most {max} {what} ({cost} each); {asked} asked")]
    TooMuchWork {
        /// The baker's kind.
        kind: &'static str,
        /// What is counted: "samples" (a bake) or "error points" ([`lookup_error`]).
        what: &'static str,
        /// How many were asked for.
        asked: usize,
        /// The baker's limit.
        max: usize,
        /// The measured cost of one evaluation, in words.
        cost: &'static str,
    },
    /// Reading or writing a file failed.
    #[error("I/O error on {path}: {source}")]
    Io {
        /// The file.
        path: String,
        /// The underlying error.
        source: std::io::Error,
    },
}
