//! Gerard's spherical-harmonic shading, "Fast Real-Time Shading for Polygonal Hair" (seed
//! `gerard-fast-realtime-shading-for-polygonal-hair.txt`), sections 2.4 and 3: the phase
//! function `S_wr(wi)` of each lobe projected to spherical harmonics over `wi` for the viewing
//! direction `wr`, tabulated over `sin theta_r` (eq. 11 to 15).
//!
//! # The frame of the tables
//!
//! The paper stores the coefficients "in a base where the hair tangent u is pointing up": here
//! the *tangent frame* has the tangent along +Z and `wr` in the XZ plane with a positive X
//! component, `wr = (cos theta_r, 0, sin theta_r)`. In the crate's local frame (tangent +X,
//! [`crate::geometry`]) a direction `(x, y, z)` has tangent-frame coordinates `(y, z, x)` (a
//! cyclic permutation, a rotation), so `wr = (sin theta_r, cos theta_r, 0)` locally. The
//! coefficients depend on `theta_r` only: the azimuth of `wr` about the tangent is taken out
//! by the frame, whose rotation to world space carries it back ([`crate::sh::rotation_blocks`]).
//!
//! Every lobe of the hair models here is even in the relative azimuth `phi` (mirroring `wi`
//! across the plane of the tangent and `wr`, the tangent frame's `y -> -y`, leaves `S`
//! unchanged), so the coefficients of `sin(|m| phi)`, `m < 0`, vanish: a table stores the
//! `(L + 1)(L + 2) / 2` coefficients with `m >= 0` ([`phase_index`]); the tests check that the
//! others are zero.
//!
//! # Projection
//!
//! `a_lm = int S(wi) Y_lm(wi) dwi` by the product rule of [`PhaseQuadrature`]: Gauss-Legendre
//! in `z = sin theta_i` and uniform nodes in azimuth. `S` is not band-limited (its longitudinal
//! lobes are a few degrees wide), so the rule is chosen fine enough that doubling it changes
//! the coefficients by less than 1e-6 of their largest (the tests measure it), and
//! [`projection_error`] reports what the truncated expansion loses against `S` itself.

use super::{gerard_attenuation, Gerard, GerardLobe, GerardUniforms};
use crate::absorption::Absorption;
use crate::bcsdf::{Bcsdf, Marschner2003, Model, Query, UniformBlock};
use crate::error::ParamError;
use crate::geometry::{fibre_frame, V3};
use crate::lut::{Axis, SharedTable, Table};
use crate::quadrature::gauss_legendre;
use crate::real::{
    trace_with, ArgType, Graph, Parameter, Real, ResultType, Signature, StructType, Traced,
};
use crate::sh::{
    eval_sh_f64_into, eval_sh_into, lmax_of, rotate_with_blocks, rotation_blocks, ProductPlan,
};
use core::f64::consts::TAU;
use glam::DVec3;

/// The highest band of a phase table (15 coefficients with `m >= 0`, within a table's 16
/// channels).
pub const MAX_PHASE_LMAX: usize = 4;

/// The number of coefficients with `m >= 0` of bands `l <= lmax`: `(lmax + 1)(lmax + 2) / 2`.
pub const fn phase_count(lmax: usize) -> usize {
    (lmax + 1) * (lmax + 2) / 2
}

/// The position of `(l, m)`, `0 <= m <= l`, among a phase table's coefficients: band by band,
/// `m` ascending (`l (l + 1) / 2 + m`).
pub const fn phase_index(l: usize, m: usize) -> usize {
    l * (l + 1) / 2 + m
}

/// The direction with tangent-frame coordinates `t` in the crate's local frame.
pub fn local_of_tangent_frame(t: DVec3) -> V3<f64> {
    V3::new(t.z, t.x, t.y)
}

/// The viewing direction `wr` at `sin theta_r = s` in the crate's local frame:
/// `(s, sqrt(1 - s^2), 0)` (`s` clamped to `[-1, 1]`).
pub fn viewer_at(s: f64) -> V3<f64> {
    let s = s.clamp(-1.0, 1.0);
    V3::new(s, (1.0 - s * s).max(0.0).sqrt(), 0.0)
}

/// The product rule of the projection: `n_z` Gauss-Legendre nodes in `z = sin theta_i` (the
/// tangent frame's z) times `n_phi` uniform nodes in azimuth.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct PhaseQuadrature {
    /// Gauss-Legendre nodes in z, in `[1, 4096]`.
    pub n_z: usize,
    /// Uniform nodes in azimuth, in `[1, 8192]`.
    pub n_phi: usize,
}

impl Default for PhaseQuadrature {
    /// 192 x 384 nodes (the tests show the coefficients converged to 1e-6 relative).
    fn default() -> Self {
        Self {
            n_z: 192,
            n_phi: 384,
        }
    }
}

impl PhaseQuadrature {
    fn check(&self) -> Result<(), ParamError> {
        ParamError::check("n_z", self.n_z as f64, "must be in [1, 4096]", |n| {
            (1.0..=4096.0).contains(&n)
        })?;
        ParamError::check("n_phi", self.n_phi as f64, "must be in [1, 8192]", |n| {
            (1.0..=8192.0).contains(&n)
        })?;
        Ok(())
    }

    /// The nodes (tangent-frame directions) and weights.
    fn nodes(&self) -> Vec<(DVec3, f64)> {
        let dphi = TAU / self.n_phi as f64;
        let mut out = Vec::with_capacity(self.n_z * self.n_phi);
        for (z, wz) in gauss_legendre(self.n_z) {
            let s = (1.0 - z * z).max(0.0).sqrt();
            for j in 0..self.n_phi {
                let phi = (j as f64 + 0.5) * dphi;
                out.push((DVec3::new(s * phi.cos(), s * phi.sin(), z), wz * dphi));
            }
        }
        out
    }
}

/// Per lobe of `model` (its [`Bcsdf::eval_lobes`] order, first channel), the coefficients of
/// `S(wi; wr)` for `wr` at `sin theta_r = s`, all `(lmax + 1)^2` of them (index
/// `l (l + 1) + m`), in the tangent frame; and per lobe `int S^2 dwi` by the same rule.
///
/// # Errors
/// [`ParamError::OutOfRange`] if `lmax > MAX_PHASE_LMAX`, `s` is outside `[-1, 1]` or the
/// quadrature's node counts are out of range.
pub fn project_phase(
    model: &impl Bcsdf<f64>,
    s: f64,
    lmax: usize,
    quadrature: &PhaseQuadrature,
) -> Result<(Vec<Vec<f64>>, Vec<f64>), ParamError> {
    check_lmax(lmax)?;
    ParamError::check("sin theta_r", s, "must be in [-1, 1]", |s| s.abs() <= 1.0)?;
    quadrature.check()?;
    let lobes = model.lobe_names().len();
    let n = (lmax + 1) * (lmax + 1);
    let (mut coefficients, mut squares) = (vec![vec![0.0; n]; lobes], vec![0.0; lobes]);
    let mut y = vec![0.0; n];
    let wo = viewer_at(s);
    for (t, weight) in quadrature.nodes() {
        let values = model.eval_lobes(&Query::far(local_of_tangent_frame(t), wo));
        eval_sh_f64_into(lmax, t, &mut y)?;
        for (lobe, value) in values.iter().enumerate() {
            let v = value[0] * weight;
            squares[lobe] += v * value[0];
            for (c, &yk) in coefficients[lobe].iter_mut().zip(&y) {
                *c += v * yk;
            }
        }
    }
    Ok((coefficients, squares))
}

/// Per band limit `L = 0..=lmax` and per lobe, what the expansion truncated to bands
/// `l <= L` loses against `S` itself, relative: `sqrt(int (S - S_L)^2 / int S^2)`, which
/// Parseval's identity gives as `sqrt(1 - sum_{l <= L} a_lm^2 / int S^2)` (0 for a lobe that
/// is 0 everywhere).
///
/// # Errors
/// As [`project_phase`].
pub fn projection_error(
    model: &impl Bcsdf<f64>,
    s: f64,
    lmax: usize,
    quadrature: &PhaseQuadrature,
) -> Result<Vec<Vec<f64>>, ParamError> {
    let (coefficients, squares) = project_phase(model, s, lmax, quadrature)?;
    Ok((0..=lmax)
        .map(|band| {
            let kept = (band + 1) * (band + 1);
            coefficients
                .iter()
                .zip(&squares)
                .map(|(c, &total)| {
                    let captured: f64 = c[..kept].iter().map(|a| a * a).sum();
                    if total > 0.0 {
                        (1.0 - captured / total).max(0.0).sqrt()
                    } else {
                        0.0
                    }
                })
                .collect()
        })
        .collect())
}

fn check_lmax(lmax: usize) -> Result<(), ParamError> {
    ParamError::check("lmax", lmax as f64, "must be in [0, 4]", |l| {
        l <= MAX_PHASE_LMAX as f64
    })
    .map(|_| ())
}

/// The tables of one lobe's `m >= 0` coefficients over `sin theta_r` in `[-1, 1]`, `C` of them
/// (bands `l <= L` with `C = (L + 1)(L + 2) / 2`): one [`SharedTable`] per lobe, fetched with
/// [`crate::real::Real::sample_table`] in every precision and as a texture in shader code.
#[derive(Clone, Debug, PartialEq)]
pub struct PhaseTable<const C: usize> {
    lobes: Vec<SharedTable<1, C>>,
}

impl<const C: usize> PhaseTable<C> {
    /// The band limit `L` of `C = (L + 1)(L + 2) / 2` coefficients (`None` if `C` is not such
    /// a count with `L <= MAX_PHASE_LMAX`).
    pub const LMAX: Option<usize> = {
        let mut l = 0;
        let mut found = None;
        while l <= MAX_PHASE_LMAX {
            if phase_count(l) == C {
                found = Some(l);
            }
            l += 1;
        }
        found
    };

    /// Bakes the tables of every lobe of `model` at `samples` values of `sin theta_r`
    /// spaced evenly over `[-1, 1]`.
    ///
    /// # Errors
    /// [`ParamError::OutOfRange`] if `C` is not a count of [`PhaseTable::LMAX`], `samples` is
    /// outside `[2, 4096]`, or as [`project_phase`].
    pub fn bake(
        model: &impl Bcsdf<f64>,
        samples: usize,
        quadrature: &PhaseQuadrature,
    ) -> Result<Self, ParamError> {
        let lmax = phase_lmax::<C>()?;
        ParamError::check("samples", samples as f64, "must be in [2, 4096]", |n| {
            (2.0..=4096.0).contains(&n)
        })?;
        let lobes = model.lobe_names().len();
        let mut data = vec![Vec::with_capacity(samples * C); lobes];
        for k in 0..samples {
            let s = -1.0 + 2.0 * k as f64 / (samples - 1) as f64;
            let (coefficients, _) = project_phase(model, s, lmax, quadrature)?;
            for (table, c) in data.iter_mut().zip(&coefficients) {
                for l in 0..=lmax {
                    for m in 0..=l {
                        table.push(c[l * (l + 1) + m] as f32);
                    }
                }
            }
        }
        let tables = data
            .into_iter()
            .map(|values| phase_lobe_table(samples, lmax, values))
            .collect();
        Ok(Self { lobes: tables })
    }

    /// The table of lobe `lobe` (the model's [`Bcsdf::lobe_names`] order), if there is one.
    pub fn lobe(&self, lobe: usize) -> Option<&SharedTable<1, C>> {
        self.lobes.get(lobe)
    }

    /// The number of lobes.
    pub fn lobe_count(&self) -> usize {
        self.lobes.len()
    }
}

/// Gerard's own storage of the `l <= 1` phase tables (his section 3: "a 128x3 8bits
/// normalized RGBA texture, parametrized by `(sin(theta_r) + 1)/2` in x"): one row per lobe
/// (R, TT, TRT), one texel per sample of `sin theta_r`, the four channels the band-1
/// coefficients in the crate's order `Y_00, Y_1-1, Y_10, Y_11` (the second is 0 for every lobe
/// here, which is even in `phi`: module documentation).
///
/// A coefficient `a` of row `p`, channel `c` is stored in offset binary,
/// `t = 128 + round(127 a / scale_pc)` with `scale_pc` the largest `|a|` of that row and
/// channel, so that 0 is exact and the codes are 1 to 255; [`PhaseTable::from_rgba8`] decodes
/// `a = scale_pc (t - 128) / 127` (a renderer passes the twelve scales as uniforms).
#[derive(Clone, Debug, PartialEq)]
pub struct PhaseTextureRgba8 {
    /// Texels per row: the table's samples of `sin theta_r` (128 in Gerard's layout).
    pub width: usize,
    /// Row by row, texel by texel.
    pub texels: Vec<[u8; 4]>,
    /// Per row, the scale of each channel's codes (0 for a channel that is 0 throughout).
    pub scales: Vec<[f32; 4]>,
}

/// Which of Gerard's RGBA channels holds a phase table's `m >= 0` coefficient (`Y_00`,
/// `Y_10`, `Y_11`): the crate's index `l (l + 1) + m`.
const RGBA8_CHANNELS: [usize; 3] = [0, 2, 3];

impl PhaseTable<3> {
    /// The tables in Gerard's 8-bit layout ([`PhaseTextureRgba8`]).
    pub fn to_rgba8(&self) -> PhaseTextureRgba8 {
        let width = self.lobes.first().map_or(0, |t| t.table().axes()[0].size());
        let mut texels = Vec::with_capacity(width * self.lobes.len());
        let mut scales = Vec::with_capacity(self.lobes.len());
        for lobe in &self.lobes {
            let data = lobe.table().data();
            let mut scale = [0f32; 4];
            for sample in data.chunks_exact(3) {
                for (&channel, &a) in RGBA8_CHANNELS.iter().zip(sample) {
                    scale[channel] = scale[channel].max(a.abs());
                }
            }
            for sample in data.chunks_exact(3) {
                let mut texel = [128u8; 4];
                for (&channel, &a) in RGBA8_CHANNELS.iter().zip(sample) {
                    if scale[channel] > 0.0 {
                        let code = 128.0 + (127.0 * a / scale[channel]).round();
                        texel[channel] = code.clamp(1.0, 255.0) as u8;
                    }
                }
                texels.push(texel);
            }
            scales.push(scale);
        }
        PhaseTextureRgba8 {
            width,
            texels,
            scales,
        }
    }

    /// The tables that `texture` stores, decoded (what a shader reads from it).
    ///
    /// # Errors
    /// [`ParamError::OutOfRange`] if the width is outside `[2, 4096]`, the texels are not
    /// `width` per scale, or a scale is negative or not finite.
    pub fn from_rgba8(texture: &PhaseTextureRgba8) -> Result<Self, ParamError> {
        let width = texture.width;
        ParamError::check("width", width as f64, "must be in [2, 4096]", |n| {
            (2.0..=4096.0).contains(&n)
        })?;
        ParamError::check(
            "texels",
            texture.texels.len() as f64,
            "must be width x the number of scales",
            |n| n == (width * texture.scales.len()) as f64,
        )?;
        let lobes = texture
            .scales
            .iter()
            .zip(texture.texels.chunks_exact(width))
            .map(|(scale, row)| {
                for &s in scale {
                    ParamError::check("scale", f64::from(s), "must be finite and >= 0", |s| {
                        s >= 0.0
                    })?;
                }
                let decode = |t: u8, c: usize| scale[c] * (f32::from(t) - 128.0) / 127.0;
                let values = row
                    .iter()
                    .flat_map(|texel| RGBA8_CHANNELS.map(|c| decode(texel[c], c)))
                    .collect();
                Ok(phase_lobe_table(width, 1, values))
            })
            .collect::<Result<Vec<_>, ParamError>>()?;
        Ok(Self { lobes })
    }
}

/// The table of one lobe's coefficients over `sin theta_r` (`samples` of them in `[-1, 1]`),
/// bands `l <= lmax`, `values` sample-major.
fn phase_lobe_table<const C: usize>(
    samples: usize,
    lmax: usize,
    values: Vec<f32>,
) -> SharedTable<1, C> {
    Axis::new("sin_theta_r", -1.0, 1.0, samples)
        .and_then(|axis| Table::new(vec![axis], phase_channel_names(lmax), values))
        .and_then(SharedTable::new)
        .unwrap_or_else(|e| unreachable!("the phase tables' shape is valid: {e}"))
}

/// The channel names of a phase table of bands `l <= lmax`: `a_l_m`, `m >= 0`.
fn phase_channel_names(lmax: usize) -> Vec<String> {
    (0..=lmax)
        .flat_map(|l| (0..=l).map(move |m| format!("a_{l}_{m}")))
        .collect()
}

/// The largest absorption an [`AbsorbingPhaseTable`] bakes, at transmission `e^(-sigma_a)`
/// 0 (per unit fibre radius; `e^(-2 x 30)`, the least attenuation of a transmitted path, is
/// below f32's resolution of 1).
pub const MAX_TABULATED_SIGMA_A: f64 = 30.0;

/// The phase function's coefficients summed over the lobes, tabulated over `sin theta_r` and
/// the transmission `u = e^(-sigma_a)` of one channel's absorption: absorption handled
/// without eq. 14's exponents (the lobes' own attenuation, which depends on the offset and
/// the angles, is projected), at the cost of a 2D table. One fetch per colour channel at
/// `(sin theta_r, e^(-sigma_a))`; `u` in `[0, 1]` covers every `sigma_a >= 0`.
#[derive(Clone, Debug, PartialEq)]
pub struct AbsorbingPhaseTable<const C: usize> {
    table: SharedTable<2, C>,
}

impl<const C: usize> AbsorbingPhaseTable<C> {
    /// Bakes the table of the models `model_at(sigma_a)` (the same hair with the absorption
    /// `sigma_a` in every channel; their first channel is projected) at `samples` values of
    /// `sin theta_r` and `transmissions` values of `u`, each spaced evenly over its range
    /// (`u = 0` baked at [`MAX_TABULATED_SIGMA_A`]).
    ///
    /// # Errors
    /// [`ParamError::OutOfRange`] if `C` is not a count of [`PhaseTable::LMAX`], a count is
    /// outside `[2, 4096]`, or as `model_at` and [`project_phase`].
    pub fn bake<B: Bcsdf<f64>>(
        model_at: impl Fn(f64) -> Result<B, ParamError>,
        [samples, transmissions]: [usize; 2],
        quadrature: &PhaseQuadrature,
    ) -> Result<Self, ParamError> {
        check_counts(samples, transmissions)?;
        let rows = (0..transmissions)
            .map(|j| {
                Self::bake_row(
                    &model_at(Self::sigma_a_of_row(j, transmissions))?,
                    samples,
                    quadrature,
                )
            })
            .collect::<Result<Vec<_>, _>>()?;
        Self::from_rows(samples, rows)
    }

    /// The absorption of row `j` of `transmissions`: `-ln u` at `u = j / (transmissions - 1)`,
    /// at most [`MAX_TABULATED_SIGMA_A`].
    pub fn sigma_a_of_row(j: usize, transmissions: usize) -> f64 {
        let u = j as f64 / (transmissions.max(2) - 1) as f64;
        match u > 0.0 {
            true => (-u.ln()).min(MAX_TABULATED_SIGMA_A),
            false => MAX_TABULATED_SIGMA_A,
        }
    }

    /// One row of the table: the lobes' summed coefficients of `model` (first channel) at
    /// `samples` values of `sin theta_r` (rows are independent: a caller may bake them in
    /// parallel and join them with [`AbsorbingPhaseTable::from_rows`]).
    ///
    /// # Errors
    /// As [`AbsorbingPhaseTable::bake`].
    pub fn bake_row(
        model: &impl Bcsdf<f64>,
        samples: usize,
        quadrature: &PhaseQuadrature,
    ) -> Result<Vec<f32>, ParamError> {
        let lmax = phase_lmax::<C>()?;
        check_counts(samples, 2)?;
        let mut values = Vec::with_capacity(samples * C);
        for k in 0..samples {
            let s = -1.0 + 2.0 * k as f64 / (samples - 1) as f64;
            let (lobes, _) = project_phase(model, s, lmax, quadrature)?;
            for l in 0..=lmax {
                for m in 0..=l {
                    let sum: f64 = lobes.iter().map(|c| c[l * (l + 1) + m]).sum();
                    values.push(sum as f32);
                }
            }
        }
        Ok(values)
    }

    /// The table of `rows` ([`AbsorbingPhaseTable::bake_row`], in order of
    /// [`AbsorbingPhaseTable::sigma_a_of_row`]) of `samples` values each.
    ///
    /// # Errors
    /// [`ParamError::OutOfRange`] if a count is outside `[2, 4096]` or a row is not `samples`
    /// values of `C` coefficients.
    pub fn from_rows(samples: usize, rows: Vec<Vec<f32>>) -> Result<Self, ParamError> {
        let lmax = phase_lmax::<C>()?;
        check_counts(samples, rows.len())?;
        ParamError::check(
            "row length",
            0.0,
            "must be samples x C in every row",
            |_| rows.iter().all(|r| r.len() == samples * C),
        )?;
        let transmissions = rows.len();
        let values = rows.concat();
        let table = Axis::new("sin_theta_r", -1.0, 1.0, samples)
            .and_then(|s| Ok([s, Axis::new("transmission", 0.0, 1.0, transmissions)?]))
            .and_then(|axes| Table::new(axes.to_vec(), phase_channel_names(lmax), values))
            .and_then(SharedTable::new)
            .unwrap_or_else(|e| unreachable!("the phase table's shape is valid: {e}"));
        Ok(Self { table })
    }

    /// The table: axes `sin_theta_r`, `transmission`.
    pub fn table(&self) -> &SharedTable<2, C> {
        &self.table
    }
}

/// Checks the sample counts of an [`AbsorbingPhaseTable`].
fn check_counts(samples: usize, transmissions: usize) -> Result<(), ParamError> {
    for (name, n) in [("samples", samples), ("transmissions", transmissions)] {
        ParamError::check(name, n as f64, "must be in [2, 4096]", |n| {
            (2.0..=4096.0).contains(&n)
        })?;
    }
    Ok(())
}

/// The band limit of phase tables of `C` channels.
fn phase_lmax<const C: usize>() -> Result<usize, ParamError> {
    PhaseTable::<C>::LMAX.ok_or(ParamError::OutOfRange {
        name: "phase table channels",
        value: C as f64,
        allowed: "must be (L + 1)(L + 2) / 2 for some L in [0, 4]: 1, 3, 6, 10 or 15",
    })
}

/// Where [`GerardSh`] takes the phase function's coefficients from.
#[derive(Clone, Debug, PartialEq)]
pub enum PhaseTables<const C: usize> {
    /// Per lobe without absorption, each attenuated per channel by `e^(-k sigma_a)` (eq. 15).
    Lobes(PhaseTable<C>),
    /// Summed over the lobes, with the absorption tabulated ([`AbsorbingPhaseTable`]).
    OverAbsorption(AbsorbingPhaseTable<C>),
}

impl<const C: usize> PhaseTables<C> {
    /// The per-lobe tables, if the absorption is eq. 15's.
    pub fn lobes(&self) -> Option<&PhaseTable<C>> {
        match self {
            PhaseTables::Lobes(tables) => Some(tables),
            PhaseTables::OverAbsorption(_) => None,
        }
    }
}

/// Gerard's shading of a hair point (eq. 3, 9, 10 and 15): the environment integrated against
/// the per-vertex transmittance and the phase function as a triple product of spherical
/// harmonics, plus one directional light.
///
/// - The phase function's coefficients come from [`PhaseTable`]s of the lobes without
///   absorption (baked from the model with `sigma_a = 0`), combined per channel as eq. 15 does:
///   `a_R + a_TT e^(-k_TT sigma_a) + a_TRT e^(-k_TRT sigma_a)` with the model's own exponents
///   and absorption ([`GerardUniforms`]).
/// - They are rotated from the tangent frame (module documentation) to world space by the
///   frame `(x', y', z') = (the part of wo across the tangent, z' x x', the tangent)`
///   ([`rotation_blocks`]), so the azimuth of `wo` needs no table axis.
/// - `int L_env V S dwi = sum T_ijk P_i V_j E_k` with `T` the real Gaunt tensor
///   ([`ProductPlan`]), per channel, over the bands of the three vectors.
/// - The light adds `L_light max(0, (V(wl) - bias) / (1 - bias)) S(wl, wo)` (eq. 9 and 10),
///   `V(wl)` reconstructed from its coefficients and `S` the model itself.
///
/// `S` has no cosine factor (the crate's convention, [`Gerard`]), so these are radiances.
#[derive(Clone, Debug)]
pub struct GerardSh<R, const C: usize> {
    model: Gerard<R>,
    uniforms: GerardUniforms<R>,
    phase: PhaseTables<C>,
    bias: R,
}

/// Where and how a hair point is seen: world-space directions of unit length.
#[derive(Clone, Copy, Debug)]
pub struct ShadedPoint<'a, R> {
    /// The hair's tangent.
    pub tangent: V3<R>,
    /// Towards the viewer.
    pub wo: V3<R>,
    /// The transmittance's coefficients in world space (bands `l <= L_V`, `(L_V + 1)^2`
    /// values; [`crate::strands::transmittance`] bakes them).
    pub transmittance: &'a [R],
}

/// The light reaching a hair point before the hair occludes it.
#[derive(Clone, Copy, Debug)]
pub struct Lighting<'a, R> {
    /// The environment's coefficients per channel in world space (bands `l <= L_E`).
    pub environment: [&'a [R]; 3],
    /// Towards the directional light.
    pub light: V3<R>,
    /// The light's radiance per channel.
    pub light_radiance: [R; 3],
}

/// The model the phase tables of eq. 14 hold: Gerard's model of `source` with its absorption
/// removed, since eq. 14 applies absorption at shading time as `A^k` with the exponents
/// `k_tt`, `k_trt` (which the model keeps for that step).
///
/// # Errors
/// As [`Gerard::new`].
pub fn clear_phase_model(
    source: &Marschner2003,
    lobe: GerardLobe,
    [k_tt, k_trt]: [f64; 2],
) -> Result<Gerard<f64>, ParamError> {
    let clear = Marschner2003 {
        sigma_a: Absorption::new([0.0; 3])?,
        ..*source
    };
    Gerard::new(&clear, lobe, k_tt, k_trt)
}

impl<const C: usize> GerardSh<f64, C> {
    /// The shading of Gerard's model `model` (built from `source` with `lobe` and the
    /// exponents `k_tt`, `k_trt`; [`Gerard::new`]), its phase tables baked at `samples` values
    /// of `sin theta_r` with `quadrature`, and the light-leak `bias` of eq. 10.
    ///
    /// # Errors
    /// [`ParamError`] if `bias` is outside `[0, 1)`, or as [`Gerard::new`] and
    /// [`PhaseTable::bake`].
    pub fn new(
        source: &Marschner2003,
        lobe: GerardLobe,
        [k_tt, k_trt]: [f64; 2],
        bias: f64,
        samples: usize,
        quadrature: &PhaseQuadrature,
    ) -> Result<Self, ParamError> {
        let bias = ParamError::check("bias", bias, "must be in [0, 1)", |b| {
            (0.0..1.0).contains(&b)
        })?;
        let model = Gerard::new(source, lobe, k_tt, k_trt)?;
        let phase = PhaseTable::bake(
            &clear_phase_model(source, lobe, [k_tt, k_trt])?,
            samples,
            quadrature,
        )?;
        Ok(Self {
            uniforms: model.uniforms(),
            model,
            phase: PhaseTables::Lobes(phase),
            bias,
        })
    }

    /// The same shading in precision `R`: the model's uniforms rounded once to `R`.
    pub fn instantiate<R: Real>(&self) -> GerardSh<R, C> {
        let values: Vec<R> = self.uniforms.to_values().into_iter().map(R::c).collect();
        self.with_uniforms(GerardUniforms::from_values(&values))
    }

    /// The same shading in precision `R` reading `uniforms` (rounded, or symbolic in traced
    /// code).
    pub fn with_uniforms<R: Real>(&self, uniforms: GerardUniforms<R>) -> GerardSh<R, C> {
        GerardSh {
            model: self.model.with_uniforms(uniforms),
            uniforms,
            phase: self.phase.clone(),
            bias: R::c(self.bias),
        }
    }
}

impl<R, const C: usize> GerardSh<R, C> {
    /// The phase tables.
    pub fn phase(&self) -> &PhaseTables<C> {
        &self.phase
    }

    /// The same shading with the phase function's coefficients from `phase` (the direct
    /// light's `S` stays Gerard's eq. 4 to 8).
    pub fn with_phase(self, phase: PhaseTables<C>) -> Self {
        Self { phase, ..self }
    }
}

impl<R: Real, const C: usize> GerardSh<R, C> {
    /// The radiance towards the viewer per channel.
    ///
    /// # Errors
    /// [`ParamError::OutOfRange`] if a coefficient vector's length is not `(L + 1)^2` with
    /// `L` at most 5, or `C` is not a phase table's count.
    pub fn shade(
        &self,
        point: &ShadedPoint<R>,
        lighting: &Lighting<R>,
    ) -> Result<[R; 3], ParamError> {
        let lmax = phase_lmax::<C>()?;
        let lengths = [
            point.transmittance,
            lighting.environment[0],
            lighting.environment[1],
            lighting.environment[2],
        ];
        let bands = lengths
            .iter()
            .map(|c| lmax_of(c.len()))
            .try_fold(lmax, |most, l| l.map(|l| most.max(l)))?;
        ParamError::check("band limit", bands as f64, "must be at most 5", |b| {
            b <= 5.0
        })?;
        let frame = tangent_frame(point.tangent, point.wo);
        let phase = self.world_phase(&frame, point.wo.dot(frame[2]), lmax);
        let plan = ProductPlan::cached(bands + 1)?;
        let padded = |c: &[R]| {
            let mut v = vec![R::c(0.0); (bands + 1) * (bands + 1)];
            v[..c.len()].copy_from_slice(c);
            v
        };
        let v = padded(point.transmittance);
        let direct = self.direct(&frame, point, lighting)?;
        let mut out = direct;
        for (channel, o) in out.iter_mut().enumerate() {
            let environment = padded(lighting.environment[channel]);
            let p = padded(&phase[channel]);
            *o += plan.triple(&p, &v, &environment)?;
        }
        Ok(out)
    }

    /// The phase function's world-space coefficients per channel at `sin theta_r = s`.
    fn world_phase(&self, frame: &[V3<R>; 3], s: R, lmax: usize) -> [Vec<R>; 3] {
        let rotation: [[R; 3]; 3] = core::array::from_fn(|i| {
            let component = |v: V3<R>| [v.x, v.y, v.z][i];
            [
                component(frame[0]),
                component(frame[1]),
                component(frame[2]),
            ]
        });
        let blocks = rotation_blocks(&rotation, lmax);
        let rotate = |stored: &[R]| {
            let full = expand_phase(stored, lmax);
            let mut world = vec![R::c(0.0); full.len()];
            rotate_with_blocks(&blocks, &full, &mut world);
            world
        };
        let u = &self.uniforms;
        match &self.phase {
            PhaseTables::Lobes(tables) => {
                let lobes: Vec<Vec<R>> = tables
                    .lobes
                    .iter()
                    .map(|table| rotate(&R::sample_table(table, [s])))
                    .collect();
                core::array::from_fn(|channel| {
                    let sigma = u.sigma_a[channel];
                    let weights = [
                        R::c(1.0),
                        gerard_attenuation(u.k_tt, sigma),
                        gerard_attenuation(u.k_trt, sigma),
                    ];
                    (0..lobes[0].len())
                        .map(|k| {
                            let terms = lobes.iter().zip(weights).map(|(lobe, w)| lobe[k] * w);
                            terms.reduce(|a, b| a + b).expect("three lobes")
                        })
                        .collect()
                })
            }
            PhaseTables::OverAbsorption(table) => core::array::from_fn(|channel| {
                let transmission = (-u.sigma_a[channel]).exp();
                rotate(&R::sample_table(table.table(), [s, transmission]))
            }),
        }
    }

    /// The directional light's contribution per channel (eq. 9 and 10).
    fn direct(
        &self,
        frame: &[V3<R>; 3],
        point: &ShadedPoint<R>,
        lighting: &Lighting<R>,
    ) -> Result<[R; 3], ParamError> {
        let n = point.transmittance.len();
        let bands = lmax_of(n)? + 1;
        let mut y = vec![R::c(0.0); n];
        let l = lighting.light;
        eval_sh_into(bands, l.x, l.y, l.z, &mut y)?;
        let v = point
            .transmittance
            .iter()
            .zip(&y)
            .map(|(&c, &y)| c * y)
            .reduce(|a, b| a + b)
            .unwrap_or(R::c(0.0));
        let one = R::c(1.0);
        let visible = ((v - self.bias) / (one - self.bias)).max(R::c(0.0));
        let local = |w: V3<R>| V3::new(w.dot(frame[2]), w.dot(frame[0]), w.dot(frame[1]));
        let s = self.model.eval(&Query::far(local(l), local(point.wo)));
        Ok(core::array::from_fn(|c| {
            lighting.light_radiance[c] * visible * s[c]
        }))
    }
}

/// The full coefficient vector (`(lmax + 1)^2`, index `l (l + 1) + m`) of a phase table's
/// `m >= 0` values, zeros at `m < 0`.
fn expand_phase<R: Real>(stored: &[R], lmax: usize) -> Vec<R> {
    let mut full = vec![R::c(0.0); (lmax + 1) * (lmax + 1)];
    for l in 0..=lmax {
        for m in 0..=l {
            full[l * (l + 1) + m] = stored[phase_index(l, m)];
        }
    }
    full
}

/// The tangent frame's axes in world space: `x'` the part of `wo` across `tangent`
/// (normalised; where `wo` is along the tangent, the normal of [`fibre_frame`]), `y' = z' x x'`,
/// `z'` the tangent (normalised).
pub fn tangent_frame<R: Real>(tangent: V3<R>, wo: V3<R>) -> [V3<R>; 3] {
    let [t, normal, _] = fibre_frame(tangent);
    let across = wo - t.scale(wo.dot(t));
    let length = across.dot(across).sqrt();
    let degenerate = length.lt(R::c(1e-6));
    let scale = R::c(1.0) / length.max(R::c(1e-6));
    let pick = |a: R, b: R| R::select(degenerate, a, b);
    let x = V3::new(
        pick(normal.x, across.x * scale),
        pick(normal.y, across.y * scale),
        pick(normal.z, across.z * scale),
    );
    [x, t.cross(x), t]
}

/// The name of [`trace_shade`]'s function in shader code.
pub const SHADE_FUNCTION: &str = "gerard_sh_shade";

/// The struct type of `n` SH coefficients as shader arguments: `ShCoefficients{n}` with fields
/// `c0, c1, ...` (index `l (l + 1) + m`).
fn sh_struct(n: usize) -> ArgType {
    ArgType::Struct(StructType {
        name: format!("ShCoefficients{n}"),
        fields: (0..n).map(|k| (format!("c{k}"), ArgType::Scalar)).collect(),
    })
}

/// Gerard's shading ([`GerardSh::shade`] in `f32`) traced for the shader emitter:
///
/// ```wgsl
/// fn gerard_sh_shade(tangent: vec3<f32>, wo: vec3<f32>, light: vec3<f32>,
///                    light_radiance: vec3<f32>, transmittance: ShCoefficients{(L_V + 1)^2})
///     -> vec3<f32>
/// ```
///
/// with the phase tables as textures, the SH vectors and their rotation as shader arithmetic,
/// and the environment's coefficients `environment` (per channel, bands `l <= L_E`) as a
/// module-scope constant `environment` (a renderer's uniform). Its [`crate::real::Graph`]
/// gives the operation counts of the cost column.
///
/// # Errors
/// [`ParamError::OutOfRange`] if `v_lmax` or the environment's band limit exceeds 5 or the
/// environment's channels differ in length, or as [`GerardSh::shade`].
pub fn trace_shade<const C: usize>(
    shading: &GerardSh<f64, C>,
    v_lmax: usize,
    environment: &[Vec<f64>; 3],
) -> Result<Graph, ParamError> {
    ParamError::check("v_lmax", v_lmax as f64, "must be at most 5", |l| l <= 5.0)?;
    let n_env = environment[0].len();
    ParamError::check(
        "environment coefficients",
        n_env as f64,
        "must be (L + 1)^2, L <= 5, the same in every channel",
        |n| lmax_of(n_env).is_ok_and(|l| l <= 5) && environment.iter().all(|c| c.len() as f64 == n),
    )?;
    let n_v = (v_lmax + 1) * (v_lmax + 1);
    let values: Vec<f32> = environment.iter().flatten().map(|&v| v as f32).collect();
    let channel = sh_struct(n_env);
    let signature = Signature {
        parameters: vec![
            Parameter::argument("tangent", ArgType::Vec3),
            Parameter::argument("wo", ArgType::Vec3),
            Parameter::argument("light", ArgType::Vec3),
            Parameter::argument("light_radiance", ArgType::Vec3),
            Parameter::argument("transmittance", sh_struct(n_v)),
            Parameter {
                name: "environment".into(),
                ty: ArgType::Struct(StructType {
                    name: "Environment".into(),
                    fields: ["r", "g", "b"]
                        .map(|c| (c.to_string(), channel.clone()))
                        .to_vec(),
                }),
                constant: Some(values),
            },
        ],
        result: ResultType::Vec3,
    };
    // Checked once outside the trace, so that the traced closure cannot fail.
    let check_point = vec![0.0; n_v];
    let check_environment = environment.each_ref().map(|c| c.as_slice());
    shading.shade(
        &ShadedPoint {
            tangent: V3::new(0.0, 0.0, 1.0),
            wo: V3::new(1.0, 0.0, 0.0),
            transmittance: &check_point,
        },
        &Lighting {
            environment: check_environment,
            light: V3::new(0.0, 1.0, 0.0),
            light_radiance: [1.0; 3],
        },
    )?;
    Ok(trace_with(signature, |x| {
        let shading = shading.instantiate::<Traced>();
        let v3 = |k: usize| V3::new(x[k], x[k + 1], x[k + 2]);
        let (transmittance, environment) = x[12..].split_at(n_v);
        let point = ShadedPoint {
            tangent: v3(0),
            wo: v3(3),
            transmittance,
        };
        let lighting = Lighting {
            environment: [
                &environment[..n_env],
                &environment[n_env..2 * n_env],
                &environment[2 * n_env..],
            ],
            light: v3(6),
            light_radiance: [x[9], x[10], x[11]],
        };
        shading
            .shade(&point, &lighting)
            .unwrap_or_else(|e| unreachable!("checked before the trace: {e}"))
            .to_vec()
    }))
}
