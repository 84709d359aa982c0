//! Tables for generic code: a [`Table`] shared by reference counting whose shape is part of
//! its type, which [`Real::sample_table`] fetches from in every precision.

use std::sync::Arc;

use super::table::{accumulate, axis_cell, corner_weight, Table, MAX_AXES};
use super::{LutError, ShapeError};
use crate::real::Real;

/// A [`Table`] of `D` axes and `C` channels, shared by reference counting: cloning one is
/// cheap, so a model's instantiation in any precision (its `In<R>`) holds the tables it reads,
/// and the traced graph keeps them for [`crate::real::Graph::eval_f32`] and prints them as
/// texture bindings ([`crate::real::Graph::to_wgsl`]).
///
/// The shape is checked once, when the table is wrapped, so a fetch
/// ([`SharedTable::sample`], [`Real::sample_table`]) takes exactly one coordinate per axis,
/// returns exactly one value per channel, and cannot fail.
#[derive(Clone, Debug, PartialEq)]
pub struct SharedTable<const D: usize, const C: usize> {
    table: Arc<Table>,
}

impl<const D: usize, const C: usize> SharedTable<D, C> {
    /// Wraps `table`.
    ///
    /// # Errors
    /// [`LutError::Shape`] ([`ShapeError::Lookup`]) if the table does not have `D` axes and
    /// `C` channels.
    pub fn new(table: Table) -> Result<Self, LutError> {
        Self::from_arc(Arc::new(table))
    }

    /// Wraps a table that is already shared (fetches from two wrappers of the same `Arc` are
    /// fetches from one table in the traced graph).
    ///
    /// # Errors
    /// As [`SharedTable::new`].
    pub fn from_arc(table: Arc<Table>) -> Result<Self, LutError> {
        let (axes, channels) = (table.axes().len(), table.channels().len());
        if axes != D || channels != C {
            return Err(LutError::Shape(ShapeError::Lookup {
                coordinates: D,
                outputs: C,
                axes,
                channels,
            }));
        }
        Ok(SharedTable { table })
    }

    /// The table.
    pub fn table(&self) -> &Table {
        &self.table
    }

    /// The shared pointer (its address identifies the table in a traced graph).
    pub fn arc(&self) -> &Arc<Table> {
        &self.table
    }

    /// [`Table::lookup_into`] at `coords`: multilinear interpolation with weights from
    /// [`axis_cell`] in `f32`, clamp to the edge. What `f32`, each SIMD lane and the traced
    /// graph's interpreter compute, bit for bit.
    /// A NaN coordinate is taken as the axis' minimum ([`axis_cell`]): the models' hot path
    /// rejects nothing ([`Table::lookup_into`] is the checked entry point).
    pub fn lookup_f32(&self, coords: [f32; D]) -> [f32; C] {
        let mut out = [0.0; C];
        // The shape was checked when the table was wrapped.
        self.table.interpolate_into(&coords, &mut out);
        out
    }

    /// The same interpolation as [`SharedTable::lookup_f32`] carried out in `f64`: the weights
    /// from [`axis_cell`] in `f64`, the stored `f32` samples widened exactly, the sum over the
    /// `2^D` corners of the cell in the same order. It differs from the `f32` lookup only by
    /// the rounding of the `f32` arithmetic (a few ulp of `f32` relative to the largest sample
    /// of the cell; tests/trace/tables.rs bounds it).
    pub fn lookup_f64(&self, coords: [f64; D]) -> [f64; C] {
        let axes = self.table.axes();
        let mut base = [0usize; MAX_AXES];
        let mut frac = [0.0f64; MAX_AXES];
        for (d, (a, &x)) in axes.iter().zip(&coords).enumerate() {
            let (i0, f) = axis_cell::<f64>(x, a.min(), a.max(), a.size());
            base[d] = i0 as usize;
            frac[d] = f;
        }
        let mut out = [0.0; C];
        let mut index = [0usize; MAX_AXES];
        for corner in 0..(1usize << D) {
            let w = corner_weight(corner, &base[..D], &frac[..D], &mut index[..D]);
            for (c, o) in out.iter_mut().enumerate() {
                // In range: axis_cell's cell index is at most size - 2.
                let v = self.table.get(&index[..D], c).unwrap_or(0.0);
                *o = accumulate(corner, *o, w * f64::from(v));
            }
        }
        out
    }

    /// The table's values at `coords` (one per axis, in the axes' units) in precision `R`:
    /// [`Real::sample_table`].
    pub fn sample<R: Real>(&self, coords: [R; D]) -> [R; C] {
        R::sample_table(self, coords)
    }
}
