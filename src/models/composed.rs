//! A hair model composed per lobe and per factor: for each of Chiang et al. 2016's lobes R, TT
//! and TRT a longitudinal factor M and an azimuthal factor N (with its attenuation A), or the
//! lobe dropped, and the residual kept or dropped. The published real-time models are made of
//! these factors (Karis 2016: the sine-space Gaussian M, his closed-form distributions and
//! Fresnel; Frostbite 2019: the same M, the per-slice TT Gaussian table, single-offset
//! attenuations); a [`Composition`] takes each factor from whichever source serves the scene
//! best, and the scene planner ([`crate::plan`]) searches the compositions for the cheapest
//! one whose error stays within a budget.
//!
//! # The factors
//!
//! Every lobe is `M_p(theta_i, theta_o) N_p(phi, theta_o)` per channel in the crate's
//! convention (S with no cosine factor, so `M_p` is a density in `sin theta_i`), as in
//! Chiang's far field `S = sum_p M_p N_p`, which every composition approximates:
//!
//! - [`Longitudinal::Deon`]: d'Eon et al. 2011's lobe with Chiang's variances `v`, `v/4`, `4v`
//!   (eq. 7) and tilts `-2 alpha`, `alpha`, `4 alpha` (pbrt-v4), exactly Chiang's M
//!   ([`crate::lobe::DeonLobe`]; its Bessel function in `f32` is Abramowitz and Stegun's
//!   polynomial form).
//! - [`Longitudinal::DeonReduced`]: the same lobe with hairmath's reduced Bessel function
//!   ([`crate::lobe::i0e_split_reduced`]: two cubics, relative error at most 1.49e-4 in
//!   every precision, 8 multiply-adds fewer than the single-precision form).
//! - [`Longitudinal::SineGaussian`]: Karis 2016's unit-area Gaussian in the sum of sines,
//!   `g(B_p; sin theta_i + sin theta_o - c_p)` with `B_R = B`, `B_TT = B/2`, `B_TRT = 2B`,
//!   `B = sqrt(v coth(1/v) - v^2)` (the R lobe's standard deviation in `sin theta_i` at normal
//!   incidence, as [`crate::models::Frostbite`] maps beta_m) and `c_p = 2 sin(alpha_p)` for
//!   Marschner's shifts `alpha_R = alpha`, `alpha_TT = -alpha/2`, `alpha_TRT = -3 alpha/2`.
//! - [`Longitudinal::ThetaHGaussian`]: Marschner 2003's Gaussian in theta_h (eq. 6),
//!   `g(beta_p; theta_h - alpha_p)` with `beta_R = sqrt(v)/2`, `beta_TT = beta_R/2`,
//!   `beta_TRT = 2 beta_R`, converted to a density in `sin theta_i` as Marschner's `S` is:
//!   `M = g cos theta_i / (2 cos^2 theta_d)` (theta_h moves at half the rate of theta_i; his
//!   `1/cos^2 theta_d` floored at 1e-12, where the conversion diverges).
//! - [`Longitudinal::HenyeyGreenstein`]: Gerard's lobe (his eq. 5 and 6) in `theta_h - alpha_p`
//!   normalised on the circle ([`crate::lobe::HenyeyGreenstein`], its factor by
//!   [`crate::lobe::hg_circle_factor`] so that it is computed in shader code too), with
//!   `g = g(beta_p)` of the normalised lobe ([`crate::models::hg_g_normalised`], beta_p
//!   Marschner's widths as above, clamped to [1, 45] degrees) and Marschner's conversion.
//! - [`Azimuthal::FarField`]: Chiang's `N_p = 1/2 int A_p(h) D(phi - Phi(p, h)) dh` (eq. 8
//!   with the trimmed logistic and the chord attenuation), by `n` Gauss-Legendre nodes in h
//!   ([`crate::bcsdf::FarFieldRule`]), one loop shared by every lobe that chooses it and by
//!   the residual (its `N_3 = A_3 / (2 pi)` with d'Eon's M of TRT's variance, untilted).
//! - [`Azimuthal::Table`]: Chiang's far field without absorption from a table over
//!   `(|phi|, |theta_o|, beta_n)` (beta_n in [0.1, 1]; [`far_field_lobe_table`], baked with
//!   the reference integrator at the hair's eta, one fetch of R, TT and TRT together),
//!   times an absorption for TT and TRT (the transmittance `T(h)^p` at Frostbite's offset,
//!   or `e^(-k sigma_a)`). Lookup error, worst over |phi|, |theta_o| and beta_n in {0.3,
//!   0.45, 0.6} relative to each lobe's peak (R, TT, TRT; `tests/composed.rs`): 0.14, 0.031,
//!   0.10 at 16 x 8 x 10 texels; 0.044, 0.020, 0.060 at 32 x 16 x 10; 0.0079, 0.0042, 0.019
//!   at 64 x 32 x 10.
//! - [`Azimuthal::GerardTable`]: Marschner 2003's `N_p` without absorption from Gerard's
//!   `N_p,LUT` over `(|phi|, |theta_d|)` ([`crate::lut::GerardN`], baked at the hair's eta with
//!   Marschner's TRT caustic treatment at its defaults, one fetch of R, TT and TRT together) at
//!   the composition's [`MarschnerTableSize`], times an absorption for TT and TRT as
//!   [`Azimuthal::Table`]'s.
//! - [`Azimuthal::NguyenDonnellyTable`]: Marschner's `N_p` with the hair's absorption baked in,
//!   from Nguyen and Donnelly's N textures over `(cos phi, cos theta_d)`
//!   ([`crate::lut::NguyenN`], Marschner's path length, the caustic treatment as above) at the
//!   composition's [`MarschnerTableSize`]: in shader code whose absorption or eta varies the
//!   table stays that of the hair it was baked for.
//!
//!   Marschner's fibre is smooth in azimuth and his exit angle a cubic, so these tables
//!   approximate Chiang's far field only as well as Marschner's model does. Each lobe alone
//!   against the far field (`hairmath report`, blonde hair at beta_m = beta_n = 0.3, E of the
//!   lobe with d'Eon's M): R 0.110 from Gerard's table at 32 x 16 and 0.117 at 128 x 64,
//!   against 0.00097 from the far-field table at 64 x 32 x 10; TT with the published offset's
//!   absorption 0.099 and 0.103; TT from Nguyen and Donnelly's table 0.29 (Marschner's path
//!   length instead of the chord). `tests/composed.rs` checks that the tables' R and TT carry
//!   the far field's energies at normal incidence.
//! - [`Azimuthal::KarisReflection`] (R only): Karis' `N_R = cos(phi/2)/4 F(eta,
//!   sqrt((1 + wi.wo)/2))`, Schlick's Fresnel at the mirror reflection's angle of incidence.
//! - [`Azimuthal::Separable`] (TT and TRT): a distribution `D(phi)` times an attenuation `A`:
//!   - [`Distribution::Karis`]: `exp(a cos phi + b)` ([`crate::models::d_karis_of_cos`]) with
//!     Karis' published or hairmath's refitted TT or TRT coefficients;
//!   - [`Distribution::FrostbiteTable`] (TT only): Tafuri 2019's per-slice Gaussian
//!     `a exp(-b (|phi| - pi)^2)` with `(a, b)` from the 9 x 10 table over
//!     `(|theta_o|, beta_n)` ([`crate::models::frostbite_tt_table`], one fetch);
//!   - [`Distribution::FrostbiteScaled`] (TRT only): Tafuri's `s_r exp(s_r (17 cos phi -
//!     16.78))` ([`crate::models::d_trt_frostbite`]);
//!   - [`Attenuation::Offset`]: Chiang's `A_p(h)` at one offset for the ray inclined at
//!     theta_o ([`crate::models::offset_attenuation`]), at Frostbite's published offsets
//!     (h_TT = 0, h_TRT = sqrt(3)/2) or hairmath's refits;
//!   - [`Attenuation::Exponential`]: the unabsorbed `A_p` at the refitted offset times
//!     Gerard's `e^(-k sigma_a)` ([`crate::models::gerard_attenuation`]) with his published
//!     exponents (4, 11/2) or hairmath's refits against the exact lobe energies with the chord
//!     path averaged over directions.
//!
//! The error of each factor against its exact counterpart is in the README (fits and lookup
//! tables); the error of a whole composition against the far field is what the planner
//! measures (`hairmath plan`).
//!
//! # Inputs
//!
//! Exactly [`HAIR_INPUTS`] with Chiang's meaning, as [`crate::models::Frostbite`] takes them,
//! every one of them varying in shader code ([`VaryingInputs`]) with the clamps of
//! [`crate::bcsdf::ChiangHair`]; the uniforms hold what every factor reads, and shader code
//! computes and reads only those of the chosen factors.

use super::constants::{GERARD_ABSORPTION_K_TRT, GERARD_ABSORPTION_K_TT};
use super::frostbite::{offset_attenuation, tt_gaussian, Transmitted};
use super::frostbite_hair::{d_trt_frostbite, frostbite_tt_table, trt_scale_of, FrostbiteVariant};
use super::gerard::{gerard_attenuation, hg_g_normalised, GERARD_K_TRT, GERARD_K_TT};
use super::gerard_direct::GERARD_REFIT_ENTRY;
use super::karis::{
    d_karis_of_cos, ExpCosCoefficients, KARIS_D_TRT_TABLE, KARIS_D_TT_TABLE, REFIT_D_TRT_TABLE,
    REFIT_D_TT_TABLE,
};
use super::unreal::{chiang_r_width_in_sines, r_azimuthal, Published, Refitted};
use crate::absorption::{Absorption, PathLength};
use crate::azimuthal::{CausticParams, Refraction};
use crate::bcsdf::{
    eta_in, roughness_in, tilt_in, Bcsdf, ChiangFarField, ChiangUniforms, FarFieldRule, Input,
    InputsIn, Model, OffsetNodes, OffsetsIn, Outgoing, PairAngles, Query, VaryingInputs,
    HAIR_INPUTS, HAIR_VARYING,
};
use crate::geometry::local_fibre_angles;
use crate::lobe::{gaussian_lobe, hg_circle_factor, BesselForm};
use crate::lut::{bake, Baker, FarFieldN, GerardN, NguyenN, SharedTable, Table, TableMeta};
use crate::params::{AzimuthalRoughness, HairParams, RefractiveIndex};
use crate::real::{safe_sqrt, NamedConstant, Real};
use core::f64::consts::FRAC_PI_2;
use std::collections::HashMap;
use std::sync::{Mutex, OnceLock};

/// The lobes of a composed model, in the order of [`Bcsdf::eval_lobes`].
pub const COMPOSED_LOBES: [&str; 4] = ["R", "TT", "TRT", "residual"];

/// The names of the lobes' values in shader code.
const LOBE_LABELS: [&str; 3] = ["r_lobe", "tt_lobe", "trt_lobe"];

/// The sine-space Gaussian's width `B` is floored here, so that the lobe stays finite in `f32`.
const MIN_WIDTH: f64 = 1e-6;
/// Marschner's `cos^2 theta_d` is floored here before it divides.
const MIN_COS2_THETA_D: f64 = 1e-12;

/// Published constants or hairmath's refits.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Constants {
    /// The values the source prints.
    Published,
    /// hairmath's refits (`src/models/constants.rs`, README "Fitted constants").
    Refit,
}

impl Constants {
    /// `published` or `refit`.
    pub fn name(self) -> &'static str {
        match self {
            Constants::Published => "published",
            Constants::Refit => "refit",
        }
    }
}

/// A lobe's longitudinal factor M (module documentation).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Longitudinal {
    /// d'Eon's lobe, Chiang's M.
    Deon,
    /// d'Eon's lobe with the reduced Bessel function.
    DeonReduced,
    /// Karis' Gaussian in the sum of sines.
    SineGaussian,
    /// Marschner's Gaussian in theta_h with his cosine conversion.
    ThetaHGaussian,
    /// Gerard's Henyey-Greenstein lobe in theta_h, normalised, with Marschner's conversion.
    HenyeyGreenstein,
}

/// A transmitted lobe's distribution in phi (module documentation).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Distribution {
    /// Karis' `exp(a cos phi + b)`.
    Karis(Constants),
    /// Frostbite's per-slice TT Gaussian from its table (TT only).
    FrostbiteTable,
    /// Frostbite's TRT distribution scaled by `s_r` (TRT only).
    FrostbiteScaled,
}

/// A transmitted lobe's attenuation (module documentation).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Attenuation {
    /// Chiang's `A_p` at Frostbite's single offset, published or refit.
    Offset(Constants),
    /// The unabsorbed `A_p` at the refitted offset times `e^(-k sigma_a)`, Gerard's k or the
    /// refit.
    Exponential(Constants),
}

/// A lobe's azimuthal factor N with its attenuation (module documentation).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Azimuthal {
    /// Chiang's far field by the composition's Gauss-Legendre nodes.
    FarField,
    /// Karis' `cos(phi/2)/4` times Schlick's Fresnel (R only).
    KarisReflection,
    /// Chiang's far field without absorption from a baked table over `(|phi|, |theta_o|,
    /// beta_n)` at the composition's [`LobeTableSize`], times an absorption (`None` for R,
    /// which has none; TT and TRT take one).
    Table {
        /// How absorption scales the unabsorbed `N_p`: [`Attenuation::Offset`] as the
        /// transmittance `T(h)^p` of the path at that offset, [`Attenuation::Exponential`] as
        /// `e^(-k sigma_a)`.
        absorption: Option<Attenuation>,
    },
    /// Marschner's `N_p` without absorption from Gerard's table over `(|phi|, |theta_d|)` at
    /// the composition's [`MarschnerTableSize`], times an absorption (`None` for R; TT and TRT
    /// take one), as [`Azimuthal::Table`].
    GerardTable {
        /// As [`Azimuthal::Table`]'s.
        absorption: Option<Attenuation>,
    },
    /// Marschner's `N_p` with the hair's absorption from Nguyen and Donnelly's N textures over
    /// `(cos phi, cos theta_d)` at the composition's [`MarschnerTableSize`].
    NguyenDonnellyTable,
    /// A distribution times an attenuation (TT and TRT).
    Separable {
        /// `D(phi)`.
        distribution: Distribution,
        /// `A`.
        attenuation: Attenuation,
    },
}

/// The factors of one kept lobe.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct LobeFactors {
    /// M.
    pub longitudinal: Longitudinal,
    /// N with A.
    pub azimuthal: Azimuthal,
}

/// One of the lobes a composition chooses factors for.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum ComposedLobe {
    /// p = 0.
    R,
    /// p = 1.
    Tt,
    /// p = 2.
    Trt,
}

impl ComposedLobe {
    /// The three, in order.
    pub const ALL: [ComposedLobe; 3] = [ComposedLobe::R, ComposedLobe::Tt, ComposedLobe::Trt];

    /// Chiang's index p.
    pub fn p(self) -> usize {
        match self {
            ComposedLobe::R => 0,
            ComposedLobe::Tt => 1,
            ComposedLobe::Trt => 2,
        }
    }

    /// `R`, `TT` or `TRT`.
    pub fn name(self) -> &'static str {
        COMPOSED_LOBES[self.p()]
    }

    /// Whether `azimuthal` is a factor this lobe can take.
    pub fn accepts(self, azimuthal: Azimuthal) -> bool {
        match (self, azimuthal) {
            (_, Azimuthal::FarField) => true,
            (lobe, Azimuthal::Table { absorption })
            | (lobe, Azimuthal::GerardTable { absorption }) => {
                absorption.is_none() == (lobe == ComposedLobe::R)
            }
            (_, Azimuthal::NguyenDonnellyTable) => true,
            (ComposedLobe::R, a) => a == Azimuthal::KarisReflection,
            (_, Azimuthal::KarisReflection) => false,
            (lobe, Azimuthal::Separable { distribution, .. }) => match distribution {
                Distribution::Karis(_) => true,
                Distribution::FrostbiteTable => lobe == ComposedLobe::Tt,
                Distribution::FrostbiteScaled => lobe == ComposedLobe::Trt,
            },
        }
    }
}

/// A choice of factors per lobe: the model a scene plan emits.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct Composition {
    /// R's factors, or `None`: dropped.
    pub r: Option<LobeFactors>,
    /// TT's.
    pub tt: Option<LobeFactors>,
    /// TRT's.
    pub trt: Option<LobeFactors>,
    /// Whether the residual (p >= 3, far field) is kept.
    pub residual: bool,
    /// Gauss-Legendre nodes in h of the far field, where a lobe or the residual uses it (in
    /// 1..=512; ignored otherwise).
    pub far_field_nodes: usize,
    /// The texels of the far-field lobe table, where a lobe reads it (each at least 2;
    /// ignored otherwise).
    pub table: LobeTableSize,
    /// The texels of Gerard's or Nguyen and Donnelly's table, where a lobe reads one (each
    /// 2 to 4096; ignored otherwise).
    pub marschner_table: MarschnerTableSize,
}

/// The texels of Gerard's or Nguyen and Donnelly's table of Marschner's `N_p`, per axis.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct MarschnerTableSize {
    /// Over |phi| in [0, pi] (Gerard) or cos phi in [-1, 1] (Nguyen and Donnelly).
    pub phi: usize,
    /// Over |theta_d| in [0, pi/2] (Gerard) or cos theta_d in [0, 1] (Nguyen and Donnelly).
    pub theta_d: usize,
}

impl MarschnerTableSize {
    /// The sizes the planner offers: 32 x 16 and Gerard's 128 x 64.
    pub const OFFERED: [MarschnerTableSize; 2] = [
        MarschnerTableSize {
            phi: 32,
            theta_d: 16,
        },
        MarschnerTableSize {
            phi: 128,
            theta_d: 64,
        },
    ];
}

/// The texels of the far-field lobe table ([`far_field_lobe_table`]) per axis.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct LobeTableSize {
    /// Over |phi| in [0, pi].
    pub phi: usize,
    /// Over |theta_o| in [0, pi/2].
    pub theta_o: usize,
    /// Over beta_n in [0.1, 1].
    pub beta_n: usize,
}

impl LobeTableSize {
    /// The sizes the planner offers: 16 x 8, 32 x 16 and 64 x 32, each with 10 beta_n
    /// texels (one per 0.1).
    pub const OFFERED: [LobeTableSize; 3] = [
        LobeTableSize {
            phi: 16,
            theta_o: 8,
            beta_n: 10,
        },
        LobeTableSize {
            phi: 32,
            theta_o: 16,
            beta_n: 10,
        },
        LobeTableSize {
            phi: 64,
            theta_o: 32,
            beta_n: 10,
        },
    ];
}

/// A composition whose factors do not fit together.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[non_exhaustive]
pub enum CompositionError {
    /// A lobe given an azimuthal factor it cannot take.
    #[error(
        "the {lobe} lobe cannot take the azimuthal factor {azimuthal:?}: R takes FarField or \
         KarisReflection, TT and TRT FarField or Separable (FrostbiteTable for TT only, \
         FrostbiteScaled for TRT only); every lobe Table, GerardTable (with an absorption for \
         TT and TRT only) or NguyenDonnellyTable"
    )]
    Azimuthal {
        /// The lobe.
        lobe: &'static str,
        /// The factor.
        azimuthal: Azimuthal,
    },
    /// A lobe table with fewer than two texels on an axis, or more than 4096.
    #[error("table = {0:?} is not allowed: each axis of the lobe table takes 2 to 4096 texels")]
    Table(LobeTableSize),
    /// A Marschner table with fewer than two texels on an axis, or more than 4096.
    #[error(
        "marschner_table = {0:?} is not allowed: each axis of Gerard's and Nguyen and \
         Donnelly's tables takes 2 to 4096 texels"
    )]
    MarschnerTable(MarschnerTableSize),
    /// The lobe table could not be baked (the message says why).
    #[error("the far-field lobe table could not be baked: {0}")]
    Baking(String),
    /// A far field with a node count outside 1..=512.
    #[error("far_field_nodes = {0} is not allowed: the far field's node count must be in 1..=512")]
    Nodes(usize),
}

impl Composition {
    /// The factors of `lobe`.
    pub fn lobe(&self, lobe: ComposedLobe) -> Option<LobeFactors> {
        match lobe {
            ComposedLobe::R => self.r,
            ComposedLobe::Tt => self.tt,
            ComposedLobe::Trt => self.trt,
        }
    }

    /// The composition with `lobe`'s factors replaced by `factors`.
    pub fn with_lobe(mut self, lobe: ComposedLobe, factors: Option<LobeFactors>) -> Self {
        match lobe {
            ComposedLobe::R => self.r = factors,
            ComposedLobe::Tt => self.tt = factors,
            ComposedLobe::Trt => self.trt = factors,
        }
        self
    }

    /// Whether a lobe or the residual reads the far field's loop.
    pub fn uses_far_field(&self) -> bool {
        self.residual
            || ComposedLobe::ALL.iter().any(|&l| {
                self.lobe(l)
                    .is_some_and(|f| f.azimuthal == Azimuthal::FarField)
            })
    }

    /// The composition in words: each lobe's factors or `dropped`, the residual, the far
    /// field's nodes.
    pub fn describe(&self) -> String {
        let mut parts: Vec<String> = ComposedLobe::ALL
            .iter()
            .map(|&lobe| match self.lobe(lobe) {
                Some(f) => format!("{}: {}", lobe.name(), f.describe()),
                None => format!("{}: dropped", lobe.name()),
            })
            .collect();
        parts.push(match self.residual {
            true => "residual: far field".to_string(),
            false => "residual: dropped".to_string(),
        });
        if self.uses_far_field() {
            parts.push(format!("far field: {} nodes", self.far_field_nodes));
        }
        if self.uses_table() {
            let t = self.table;
            parts.push(format!("table: {} x {} x {}", t.phi, t.theta_o, t.beta_n));
        }
        if self.uses_marschner_table() {
            let t = self.marschner_table;
            parts.push(format!("Marschner table: {} x {}", t.phi, t.theta_d));
        }
        parts.join("; ")
    }

    /// Whether a lobe's azimuthal factor satisfies `reads`.
    fn any_azimuthal(&self, reads: impl Fn(Azimuthal) -> bool) -> bool {
        ComposedLobe::ALL
            .iter()
            .any(|&l| self.lobe(l).is_some_and(|f| reads(f.azimuthal)))
    }

    /// Whether a lobe reads the far-field lobe table.
    pub fn uses_table(&self) -> bool {
        self.any_azimuthal(|a| matches!(a, Azimuthal::Table { .. }))
    }

    /// Whether a lobe reads Gerard's or Nguyen and Donnelly's table.
    pub fn uses_marschner_table(&self) -> bool {
        self.any_azimuthal(|a| {
            matches!(
                a,
                Azimuthal::GerardTable { .. } | Azimuthal::NguyenDonnellyTable
            )
        })
    }

    /// Checks that every lobe's factors fit it and the node count, where used, is valid.
    ///
    /// # Errors
    /// [`CompositionError`] naming the first problem.
    pub fn check(&self) -> Result<(), CompositionError> {
        for lobe in ComposedLobe::ALL {
            if let Some(f) = self.lobe(lobe) {
                if !lobe.accepts(f.azimuthal) {
                    let (lobe, azimuthal) = (lobe.name(), f.azimuthal);
                    return Err(CompositionError::Azimuthal { lobe, azimuthal });
                }
            }
        }
        let nodes_ok = (1..=crate::bcsdf::MAX_FAR_FIELD_NODES).contains(&self.far_field_nodes);
        if self.uses_far_field() && !nodes_ok {
            return Err(CompositionError::Nodes(self.far_field_nodes));
        }
        let t = self.table;
        let table_ok = [t.phi, t.theta_o, t.beta_n]
            .iter()
            .all(|n| (2..=4096).contains(n));
        if self.uses_table() && !table_ok {
            return Err(CompositionError::Table(t));
        }
        let m = self.marschner_table;
        let marschner_ok = [m.phi, m.theta_d].iter().all(|n| (2..=4096).contains(n));
        if self.uses_marschner_table() && !marschner_ok {
            return Err(CompositionError::MarschnerTable(m));
        }
        Ok(())
    }
}

impl Longitudinal {
    /// `deon`, `deon_reduced`, `sine_gaussian`, `theta_h_gaussian` or `henyey_greenstein`.
    pub fn name(self) -> &'static str {
        match self {
            Longitudinal::Deon => "deon",
            Longitudinal::DeonReduced => "deon_reduced",
            Longitudinal::SineGaussian => "sine_gaussian",
            Longitudinal::ThetaHGaussian => "theta_h_gaussian",
            Longitudinal::HenyeyGreenstein => "henyey_greenstein",
        }
    }
}

impl Distribution {
    /// `karis_published`, `karis_refit`, `frostbite_table` or `frostbite_scaled`.
    pub fn name(self) -> String {
        match self {
            Distribution::Karis(c) => format!("karis_{}", c.name()),
            Distribution::FrostbiteTable => "frostbite_table".to_string(),
            Distribution::FrostbiteScaled => "frostbite_scaled".to_string(),
        }
    }
}

impl Attenuation {
    /// `offset_published`, `offset_refit`, `exponential_published` or `exponential_refit`.
    pub fn name(self) -> String {
        match self {
            Attenuation::Offset(c) => format!("offset_{}", c.name()),
            Attenuation::Exponential(c) => format!("exponential_{}", c.name()),
        }
    }
}

impl Attenuation {
    /// The attenuation in words (`offset (refit)`, `exp(-k sigma_a) (published)`).
    pub fn describe(self) -> String {
        match self {
            Attenuation::Offset(c) => format!("offset ({})", c.name()),
            Attenuation::Exponential(c) => format!("exp(-k sigma_a) ({})", c.name()),
        }
    }
}

impl Azimuthal {
    /// `far_field`, `karis_reflection`, `table`, `gerard_table`, `nguyen_donnelly_table` or
    /// `separable`.
    pub fn name(self) -> &'static str {
        match self {
            Azimuthal::FarField => "far_field",
            Azimuthal::KarisReflection => "karis_reflection",
            Azimuthal::Table { .. } => "table",
            Azimuthal::GerardTable { .. } => "gerard_table",
            Azimuthal::NguyenDonnellyTable => "nguyen_donnelly_table",
            Azimuthal::Separable { .. } => "separable",
        }
    }
}

impl LobeFactors {
    /// The factors in words (`M sine Gaussian, N Frostbite table x A offset (refit)`).
    pub fn describe(&self) -> String {
        let m = match self.longitudinal {
            Longitudinal::Deon => "d'Eon",
            Longitudinal::DeonReduced => "d'Eon (reduced I0)",
            Longitudinal::SineGaussian => "sine Gaussian",
            Longitudinal::ThetaHGaussian => "theta_h Gaussian",
            Longitudinal::HenyeyGreenstein => "Henyey-Greenstein",
        };
        let n = match self.azimuthal {
            Azimuthal::FarField => "far field".to_string(),
            Azimuthal::KarisReflection => "Karis cos(phi/2)/4 x Schlick".to_string(),
            Azimuthal::Table { absorption: None } => "far-field table".to_string(),
            Azimuthal::Table {
                absorption: Some(a),
            } => format!("far-field table x absorption {}", a.describe()),
            Azimuthal::GerardTable { absorption: None } => "Gerard's Marschner table".to_string(),
            Azimuthal::GerardTable {
                absorption: Some(a),
            } => format!("Gerard's Marschner table x absorption {}", a.describe()),
            Azimuthal::NguyenDonnellyTable => {
                "Nguyen-Donnelly's Marschner table (absorption baked)".to_string()
            }
            Azimuthal::Separable {
                distribution,
                attenuation,
            } => {
                let d = match distribution {
                    Distribution::Karis(c) => format!("Karis ({})", c.name()),
                    Distribution::FrostbiteTable => "Frostbite table".to_string(),
                    Distribution::FrostbiteScaled => "Frostbite s_r".to_string(),
                };
                format!("{d} x A {}", attenuation.describe())
            }
        };
        format!("M {m}, N {n}")
    }
}

crate::uniform_block! {
    /// The derived constants of a composed model: Chiang's ([`ChiangUniforms`], the far field
    /// and d'Eon's lobes read them) and those of the other factors.
    pub struct ComposedUniforms<R> {
        /// Chiang's v_0.
        pub variance_r: R,
        /// v_0 / 4.
        pub variance_tt: R,
        /// 4 v_0.
        pub variance_trt: R,
        /// 1 / v_0.
        pub inv_variance_r: R,
        /// 1 / v_1.
        pub inv_variance_tt: R,
        /// 1 / v_2.
        pub inv_variance_trt: R,
        /// d'Eon's normalisation of R.
        pub lobe_norm_r: R,
        /// Of TT.
        pub lobe_norm_tt: R,
        /// Of TRT and the residual.
        pub lobe_norm_trt: R,
        /// The logistic's scale s (Chiang eq. 8).
        pub logistic_scale: R,
        /// 1 / s.
        pub logistic_inv_scale: R,
        /// The logistic's mass on [-pi, pi].
        pub logistic_mass: R,
        /// 1 / (s mass).
        pub logistic_norm: R,
        /// sin alpha.
        pub sin_alpha: R,
        /// cos alpha.
        pub cos_alpha: R,
        /// sin 2 alpha.
        pub sin_2_alpha: R,
        /// cos 2 alpha.
        pub cos_2_alpha: R,
        /// sin 4 alpha.
        pub sin_4_alpha: R,
        /// cos 4 alpha.
        pub cos_4_alpha: R,
        /// The relative index of refraction.
        pub eta: R,
        /// 1 / eta.
        pub inv_eta: R,
        /// Absorption per unit radius.
        pub sigma_a: [R; 3],
        /// `B`, the sine-space Gaussian's width of R.
        pub sine_width_r: R,
        /// `B / 2`, TT's.
        pub sine_width_tt: R,
        /// `2 B`, TRT's.
        pub sine_width_trt: R,
        /// `2 sin(alpha)`, R's centre in the sum of sines.
        pub sine_shift_r: R,
        /// `-2 sin(alpha / 2)`, TT's.
        pub sine_shift_tt: R,
        /// `-2 sin(3 alpha / 2)`, TRT's.
        pub sine_shift_trt: R,
        /// `sqrt(v) / 2`, Marschner's beta_R in theta_h.
        pub theta_h_width_r: R,
        /// beta_R / 2.
        pub theta_h_width_tt: R,
        /// 2 beta_R.
        pub theta_h_width_trt: R,
        /// alpha, R's shift in theta_h.
        pub theta_h_shift_r: R,
        /// -alpha / 2.
        pub theta_h_shift_tt: R,
        /// -3 alpha / 2.
        pub theta_h_shift_trt: R,
        /// g of R's Henyey-Greenstein lobe.
        pub hg_g_r: R,
        /// Of TT's.
        pub hg_g_tt: R,
        /// Of TRT's.
        pub hg_g_trt: R,
        /// The factor normalising R's lobe ([`crate::lobe::hg_circle_factor`]).
        pub hg_factor_r: R,
        /// TT's.
        pub hg_factor_tt: R,
        /// TRT's.
        pub hg_factor_trt: R,
        /// beta_n, the Frostbite TT table's second coordinate.
        pub beta_n: R,
        /// Frostbite's `s_r` ([`crate::models::frostbite_trt_scale`]).
        pub trt_scale: R,
    }
}

impl<R: Real> ComposedUniforms<R> {
    /// The uniforms of a hair in precision `R` (module documentation): Chiang's derivation
    /// ([`ChiangUniforms`]) and the other factors' widths and shifts. Domain as
    /// [`HairParams`].
    fn derive(beta_m: R, beta_n: R, alpha: R, eta: R, sigma_a: [R; 3]) -> Self {
        let c = ChiangUniforms::derive(beta_m, beta_n, alpha, eta, sigma_a);
        let width = chiang_r_width_in_sines(beta_m).max(R::c(MIN_WIDTH));
        let theta_h_width = R::c(0.5) * safe_sqrt(c.variance_r);
        let (half, two) = (R::c(0.5), R::c(2.0));
        let hg_g = [half * theta_h_width, theta_h_width, two * theta_h_width].map(hg_g_normalised);
        ComposedUniforms {
            variance_r: c.variance_r,
            variance_tt: c.variance_tt,
            variance_trt: c.variance_trt,
            inv_variance_r: c.inv_variance_r,
            inv_variance_tt: c.inv_variance_tt,
            inv_variance_trt: c.inv_variance_trt,
            lobe_norm_r: c.lobe_norm_r,
            lobe_norm_tt: c.lobe_norm_tt,
            lobe_norm_trt: c.lobe_norm_trt,
            logistic_scale: c.logistic_scale,
            logistic_inv_scale: c.logistic_inv_scale,
            logistic_mass: c.logistic_mass,
            logistic_norm: c.logistic_norm,
            sin_alpha: c.sin_alpha,
            cos_alpha: c.cos_alpha,
            sin_2_alpha: c.sin_2_alpha,
            cos_2_alpha: c.cos_2_alpha,
            sin_4_alpha: c.sin_4_alpha,
            cos_4_alpha: c.cos_4_alpha,
            eta: c.eta,
            inv_eta: c.inv_eta,
            sigma_a: c.sigma_a,
            sine_width_r: width,
            sine_width_tt: half * width,
            sine_width_trt: two * width,
            sine_shift_r: two * alpha.sin(),
            sine_shift_tt: -two * (half * alpha).sin(),
            sine_shift_trt: -two * (R::c(1.5) * alpha).sin(),
            theta_h_width_r: theta_h_width,
            theta_h_width_tt: half * theta_h_width,
            theta_h_width_trt: two * theta_h_width,
            theta_h_shift_r: alpha,
            theta_h_shift_tt: -half * alpha,
            theta_h_shift_trt: R::c(-1.5) * alpha,
            hg_g_r: hg_g[1],
            hg_g_tt: hg_g[0],
            hg_g_trt: hg_g[2],
            hg_factor_r: hg_circle_factor(hg_g[1]),
            hg_factor_tt: hg_circle_factor(hg_g[0]),
            hg_factor_trt: hg_circle_factor(hg_g[2]),
            beta_n,
            trt_scale: trt_scale_of(beta_n),
        }
    }

    /// Chiang's uniforms among these.
    fn chiang(&self) -> ChiangUniforms<R> {
        ChiangUniforms {
            variance_r: self.variance_r,
            variance_tt: self.variance_tt,
            variance_trt: self.variance_trt,
            inv_variance_r: self.inv_variance_r,
            inv_variance_tt: self.inv_variance_tt,
            inv_variance_trt: self.inv_variance_trt,
            lobe_norm_r: self.lobe_norm_r,
            lobe_norm_tt: self.lobe_norm_tt,
            lobe_norm_trt: self.lobe_norm_trt,
            logistic_scale: self.logistic_scale,
            logistic_inv_scale: self.logistic_inv_scale,
            logistic_mass: self.logistic_mass,
            logistic_norm: self.logistic_norm,
            sin_alpha: self.sin_alpha,
            cos_alpha: self.cos_alpha,
            sin_2_alpha: self.sin_2_alpha,
            cos_2_alpha: self.cos_2_alpha,
            sin_4_alpha: self.sin_4_alpha,
            cos_4_alpha: self.cos_4_alpha,
            eta: self.eta,
            inv_eta: self.inv_eta,
            sigma_a: self.sigma_a,
        }
    }

    /// `(width, centre)` of `lobe`'s sine-space Gaussian.
    fn sine_gaussian(&self, lobe: ComposedLobe) -> (R, R) {
        match lobe {
            ComposedLobe::R => (self.sine_width_r, self.sine_shift_r),
            ComposedLobe::Tt => (self.sine_width_tt, self.sine_shift_tt),
            ComposedLobe::Trt => (self.sine_width_trt, self.sine_shift_trt),
        }
    }

    /// `(g, factor)` of `lobe`'s Henyey-Greenstein lobe.
    fn henyey_greenstein(&self, lobe: ComposedLobe) -> (R, R) {
        match lobe {
            ComposedLobe::R => (self.hg_g_r, self.hg_factor_r),
            ComposedLobe::Tt => (self.hg_g_tt, self.hg_factor_tt),
            ComposedLobe::Trt => (self.hg_g_trt, self.hg_factor_trt),
        }
    }

    /// `(width, shift)` of `lobe`'s Gaussian in theta_h.
    fn theta_h_gaussian(&self, lobe: ComposedLobe) -> (R, R) {
        match lobe {
            ComposedLobe::R => (self.theta_h_width_r, self.theta_h_shift_r),
            ComposedLobe::Tt => (self.theta_h_width_tt, self.theta_h_shift_tt),
            ComposedLobe::Trt => (self.theta_h_width_trt, self.theta_h_shift_trt),
        }
    }
}

/// The far-field lobe table's beta_n axis.
const TABLE_BETA_N: (f64, f64) = (0.1, 1.0);
/// The relative tolerance of the reference integrals the lobe table samples.
const TABLE_REL_TOL: f64 = 1e-8;

/// Chiang et al. 2016's far-field `N_p` without absorption (sigma_a = 0, so one value per
/// lobe) of R, TT and TRT for index `eta`, over `|phi|` in [0, pi], `|theta_o|` in [0, pi/2]
/// and beta_n in [0.1, 1] at `size` texels: the channels `R_r`, `TT_r`, `TRT_r` of
/// [`crate::lut::FarFieldN`] (reference integrals to relative tolerance 1e-8). Baked once per
/// size and index and shared.
///
/// # Errors
/// [`CompositionError::Table`] for sizes outside 2..=4096.
pub fn far_field_lobe_table(
    size: LobeTableSize,
    eta: RefractiveIndex,
) -> Result<SharedTable<3, 3>, CompositionError> {
    static TABLES: TableCache<(LobeTableSize, u64), SharedTable<3, 3>> = OnceLock::new();
    cached(&TABLES, (size, eta.get().to_bits()), || {
        bake_lobe_table(size, eta)
    })
}

/// Tables baked once per key and shared (a fetch from two copies of one is a fetch from one
/// table in the traced graph).
type TableCache<K, T> = OnceLock<Mutex<HashMap<K, T>>>;

/// The table of `key` in `cache`, baked by `bake` the first time.
fn cached<K: Eq + std::hash::Hash, T: Clone>(
    cache: &TableCache<K, T>,
    key: K,
    bake: impl FnOnce() -> Result<T, CompositionError>,
) -> Result<T, CompositionError> {
    let cache = cache.get_or_init(Mutex::default);
    if let Some(table) = cache.lock().unwrap_or_else(|p| p.into_inner()).get(&key) {
        return Ok(table.clone());
    }
    let table = bake()?;
    let mut tables = cache.lock().unwrap_or_else(|p| p.into_inner());
    Ok(tables.entry(key).or_insert(table).clone())
}

/// Gerard's `N_p,LUT` ([`GerardN`]: Marschner's `N_R`, `N_TT`, `N_TRT` without absorption
/// over |phi| in [0, pi] and |theta_d| in [0, pi/2]) for index `eta` at `size` texels, with
/// Marschner's TRT caustic treatment at its defaults. Baked once per size and index and
/// shared.
///
/// # Errors
/// [`CompositionError::MarschnerTable`] for sizes outside 2..=4096.
pub fn gerard_lobe_table(
    size: MarschnerTableSize,
    eta: RefractiveIndex,
) -> Result<SharedTable<2, 3>, CompositionError> {
    static TABLES: TableCache<(MarschnerTableSize, u64), SharedTable<2, 3>> = OnceLock::new();
    cached(&TABLES, (size, eta.get().to_bits()), || {
        let baker = GerardN::new(eta, FRAC_PI_2, Some(CausticParams::default()))
            .map_err(|e| CompositionError::Baking(e.to_string()))?;
        bake_marschner_table(&baker, size)
    })
}

/// Nguyen and Donnelly's N textures as one table ([`NguyenN`]: Marschner's `N_TT` rgb, `N_R`,
/// `N_TRT` rgb with absorption `sigma_a` over cos phi in [-1, 1] and cos theta_d in [0, 1])
/// for index `eta` at `size` texels, with Marschner's TRT caustic treatment at its defaults.
/// Baked once per size, index and absorption and shared.
///
/// # Errors
/// [`CompositionError::MarschnerTable`] for sizes outside 2..=4096.
pub fn nguyen_donnelly_lobe_table(
    size: MarschnerTableSize,
    eta: RefractiveIndex,
    sigma_a: Absorption,
) -> Result<SharedTable<2, 7>, CompositionError> {
    type Key = (MarschnerTableSize, u64, [u64; 3]);
    static TABLES: TableCache<Key, SharedTable<2, 7>> = OnceLock::new();
    let key = (size, eta.get().to_bits(), sigma_a.rgb().map(f64::to_bits));
    cached(&TABLES, key, || {
        let baker = NguyenN::new(eta, sigma_a, Some(CausticParams::default()));
        bake_marschner_table(&baker, size)
    })
}

/// `baker`'s table at `size`.
fn bake_marschner_table<const C: usize>(
    baker: &dyn Baker,
    size: MarschnerTableSize,
) -> Result<SharedTable<2, C>, CompositionError> {
    if ![size.phi, size.theta_d]
        .iter()
        .all(|n| (2..=4096).contains(n))
    {
        return Err(CompositionError::MarschnerTable(size));
    }
    bake(baker, &[size.phi, size.theta_d])
        .and_then(SharedTable::new)
        .map_err(|e| CompositionError::Baking(e.to_string()))
}

/// [`far_field_lobe_table`], baked.
fn bake_lobe_table(
    size: LobeTableSize,
    eta: RefractiveIndex,
) -> Result<SharedTable<3, 3>, CompositionError> {
    if ![size.phi, size.theta_o, size.beta_n]
        .iter()
        .all(|n| (2..=4096).contains(n))
    {
        return Err(CompositionError::Table(size));
    }
    let baking = |e: &dyn std::fmt::Display| CompositionError::Baking(e.to_string());
    let beta_n = |b| AzimuthalRoughness::new(b).map_err(|e| baking(&e));
    let clear = Absorption::new([0.0; 3]).map_err(|e| baking(&e))?;
    let (lo, hi) = (beta_n(TABLE_BETA_N.0)?, beta_n(TABLE_BETA_N.1)?);
    let baker = FarFieldN::new(eta, clear, lo, hi, TABLE_REL_TOL).map_err(|e| baking(&e))?;
    let full = bake(&baker, &[size.phi, size.theta_o, size.beta_n]).map_err(|e| baking(&e))?;
    // The R, TT and TRT channels of red (at sigma_a = 0 the channels are equal).
    let lobes = [0, 3, 6];
    let stride = full.channels().len();
    let data = full
        .data()
        .chunks(stride)
        .flat_map(|texel| lobes.map(|c| texel[c]))
        .collect();
    let channels = lobes.map(|c| full.channels()[c].clone()).to_vec();
    let meta = TableMeta {
        kind: "far-field-lobes".to_string(),
        description: "Chiang 2016 far-field N_p without absorption (sigma_a = 0) for p = R, TT, \
                      TRT at |phi| = axis 0, |theta_o| = axis 1, beta_n = axis 2"
            .to_string(),
        parameters: full.meta().parameters.clone(),
        png_scale: Vec::new(),
    };
    Table::new(full.axes().to_vec(), channels, data)
        .and_then(|t| t.with_meta(meta))
        .and_then(SharedTable::new)
        .map_err(|e| baking(&e))
}

/// The uniforms from the values of [`HAIR_INPUTS`] in precision `R`, with Chiang's clamps.
fn composed_uniforms_in<R: Real>(inputs: &InputsIn<R>) -> ComposedUniforms<R> {
    let beta_n = roughness_in(inputs.number("beta_n"));
    ComposedUniforms::derive(
        roughness_in(inputs.number("beta_m")),
        beta_n,
        tilt_in(inputs.number("alpha")),
        eta_in(inputs.number("eta")),
        inputs.absorption("sigma_a").sigma_a(beta_n),
    )
}

/// A hair model composed of the factors of a [`Composition`] (module documentation).
#[derive(Clone, Debug, PartialEq)]
pub struct ComposedHair<R> {
    uniforms: ComposedUniforms<R>,
    composition: Composition,
    /// The far field's nodes (empty when no factor reads them).
    nodes: OffsetNodes<R>,
    /// Frostbite's TT Gaussians over (theta_o, beta_n).
    tt_table: SharedTable<2, 2>,
    /// The far-field lobe table, where a lobe reads it.
    lobe_table: Option<SharedTable<3, 3>>,
    /// Gerard's and Nguyen and Donnelly's tables, where a lobe reads them.
    marschner: MarschnerTables,
}

/// The tables of Marschner's `N_p` a composition reads.
#[derive(Clone, Debug, PartialEq)]
struct MarschnerTables {
    /// [`gerard_lobe_table`].
    gerard: Option<SharedTable<2, 3>>,
    /// [`nguyen_donnelly_lobe_table`].
    nguyen_donnelly: Option<SharedTable<2, 7>>,
}

impl MarschnerTables {
    /// Those `composition` reads, for `hair`.
    fn of(composition: &Composition, hair: &HairParams) -> Result<Self, CompositionError> {
        let size = composition.marschner_table;
        let gerard = composition.any_azimuthal(|a| matches!(a, Azimuthal::GerardTable { .. }));
        let nguyen = composition.any_azimuthal(|a| a == Azimuthal::NguyenDonnellyTable);
        Ok(MarschnerTables {
            gerard: match gerard {
                true => Some(gerard_lobe_table(size, hair.eta)?),
                false => None,
            },
            nguyen_donnelly: match nguyen {
                true => Some(nguyen_donnelly_lobe_table(size, hair.eta, hair.sigma_a)?),
                false => None,
            },
        })
    }
}

impl ComposedHair<f64> {
    /// The composed model of the hair `hair`. A lobe table is baked (once per size and index,
    /// [`far_field_lobe_table`], [`gerard_lobe_table`]) at the hair's eta, and Nguyen and
    /// Donnelly's also at its absorption ([`nguyen_donnelly_lobe_table`]): in shader code
    /// whose eta or absorption varies the tables stay those of this hair.
    ///
    /// # Errors
    /// [`CompositionError`] if the composition's factors do not fit together.
    pub fn new(hair: &HairParams, composition: Composition) -> Result<Self, CompositionError> {
        let uniforms = ComposedUniforms::derive(
            hair.beta_m.get(),
            hair.beta_n.get(),
            hair.alpha.get(),
            hair.eta.get(),
            hair.sigma_a.rgb(),
        );
        composition.check()?;
        let lobe_table = match composition.uses_table() {
            true => Some(far_field_lobe_table(composition.table, hair.eta)?),
            false => None,
        };
        let marschner = MarschnerTables::of(&composition, hair)?;
        Ok(Self::checked(uniforms, composition, lobe_table, marschner))
    }

    /// The model of the checked `composition` reading `uniforms`, with its node rule (one
    /// node, never read, when nothing reads the far field).
    fn checked(
        uniforms: ComposedUniforms<f64>,
        composition: Composition,
        lobe_table: Option<SharedTable<3, 3>>,
        marschner: MarschnerTables,
    ) -> Self {
        let nodes = match composition.uses_far_field() {
            true => composition.far_field_nodes,
            false => 1,
        };
        let rule = FarFieldRule::gauss_legendre(nodes)
            .unwrap_or_else(|e| unreachable!("Composition::check bounds the node count: {e}"));
        ComposedHair {
            uniforms,
            composition,
            nodes: OffsetNodes::new(&rule),
            tt_table: frostbite_tt_table(),
            lobe_table,
            marschner,
        }
    }
}

impl<R> ComposedHair<R> {
    /// The composition.
    pub fn composition(&self) -> &Composition {
        &self.composition
    }

    /// Frostbite's TT table ([`frostbite_tt_table`]; read only by
    /// [`Distribution::FrostbiteTable`]).
    pub fn tt_table(&self) -> &SharedTable<2, 2> {
        &self.tt_table
    }
}

/// What the tables a composition reads give at one query: the far-field lobe table's
/// unabsorbed `N_R`, `N_TT`, `N_TRT`, Gerard's the same of Marschner's model, Nguyen and
/// Donnelly's `N_TT` rgb, `N_R`, `N_TRT` rgb.
struct TableValues<R> {
    lobe: [R; 3],
    gerard: [R; 3],
    nguyen_donnelly: [R; 7],
}

/// The angles the factors read, computed once per query.
struct ComposedAngles<R> {
    /// Chiang's (sin and cos of theta_i, and what the far field depends on).
    pair: PairAngles<R>,
    /// `sin theta_i + sin theta_o`.
    sum_of_sines: R,
    /// phi in [-pi, pi].
    phi: R,
    /// theta_i.
    theta_i: R,
    /// theta_o.
    theta_o: R,
    /// `wi . wo`.
    v_dot_l: R,
}

impl<R: Real> ComposedAngles<R> {
    /// theta_h = (theta_i + theta_o) / 2.
    fn theta_h(&self) -> R {
        (R::c(0.5) * (self.theta_i + self.theta_o)).label("theta_h")
    }

    /// Marschner's conversion of a lobe in theta_h to a density in `sin theta_i`,
    /// `cos theta_i / (2 cos^2 theta_d)` (module documentation; `cos^2 theta_d` floored).
    fn marschner_conversion(&self) -> R {
        let cos_d = self.theta_d().cos().label("cos_theta_d");
        R::c(0.5) * self.pair.cos_i / (cos_d * cos_d).max(R::c(MIN_COS2_THETA_D))
    }

    /// theta_d = (theta_o - theta_i) / 2.
    fn theta_d(&self) -> R {
        (R::c(0.5) * (self.theta_o - self.theta_i)).label("theta_d")
    }

    fn of(query: &Query<R>) -> Self {
        let a = local_fibre_angles(query.wi, query.wo);
        let pair = PairAngles {
            sin_i: a.sin_theta_i,
            cos_i: a.cos_theta_i,
            out: Outgoing {
                sin_o: a.sin_theta_o,
                cos_o: a.cos_theta_o,
                phi: -a.phi,
                h: R::c(0.0),
            },
        };
        ComposedAngles {
            pair,
            sum_of_sines: (a.sin_theta_i + a.sin_theta_o).label("sum_of_sines"),
            phi: a.phi,
            theta_i: a.theta_i().label("theta_i"),
            theta_o: a.theta_o().label("theta_o"),
            v_dot_l: query.wi.dot(query.wo).label("v_dot_l"),
        }
    }
}

/// The offset Frostbite's attenuation of `path` is taken at, published or refit.
fn offset_of(path: Transmitted, constants: Constants) -> &'static NamedConstant {
    match (path, constants) {
        (Transmitted::Tt, Constants::Published) => <Published as FrostbiteVariant>::TT_OFFSET,
        (Transmitted::Trt, Constants::Published) => <Published as FrostbiteVariant>::TRT_OFFSET,
        (Transmitted::Tt, Constants::Refit) => <Refitted as FrostbiteVariant>::TT_OFFSET,
        (Transmitted::Trt, Constants::Refit) => <Refitted as FrostbiteVariant>::TRT_OFFSET,
    }
}

/// Gerard's absorption exponent of `path`, published or refit (chord, averaged over
/// directions).
fn exponent_of(path: Transmitted, constants: Constants) -> f64 {
    match (path, constants) {
        (Transmitted::Tt, Constants::Published) => GERARD_K_TT,
        (Transmitted::Trt, Constants::Published) => GERARD_K_TRT,
        (Transmitted::Tt, Constants::Refit) => GERARD_ABSORPTION_K_TT[GERARD_REFIT_ENTRY],
        (Transmitted::Trt, Constants::Refit) => GERARD_ABSORPTION_K_TRT[GERARD_REFIT_ENTRY],
    }
}

/// Karis' coefficient table of `path`'s distribution, published or refit.
fn karis_table(path: Transmitted, constants: Constants) -> &'static NamedConstant {
    match (path, constants) {
        (Transmitted::Tt, Constants::Published) => &KARIS_D_TT_TABLE,
        (Transmitted::Trt, Constants::Published) => &KARIS_D_TRT_TABLE,
        (Transmitted::Tt, Constants::Refit) => &REFIT_D_TT_TABLE,
        (Transmitted::Trt, Constants::Refit) => &REFIT_D_TRT_TABLE,
    }
}

impl<R: Real> ComposedHair<R> {
    /// The far field's Chiang model (the loop and d'Eon's lobes read it).
    fn chiang(&self) -> ChiangFarField<R> {
        ChiangFarField::with_offsets(self.uniforms.chiang(), self.nodes.clone())
    }

    /// `lobe`'s longitudinal factor M; `deon` holds d'Eon's lobes of the four paths, of
    /// `chiang`.
    fn longitudinal(
        &self,
        lobe: ComposedLobe,
        m: Longitudinal,
        a: &ComposedAngles<R>,
        (chiang, deon): (&ChiangFarField<R>, &[R; 4]),
    ) -> R {
        let u = &self.uniforms;
        match m {
            Longitudinal::Deon => deon[lobe.p()],
            Longitudinal::DeonReduced => {
                chiang.longitudinal_lobe(lobe.p(), BesselForm::Reduced, &a.pair)
            }
            Longitudinal::SineGaussian => {
                let (width, centre) = u.sine_gaussian(lobe);
                gaussian_lobe(width, a.sum_of_sines - centre)
            }
            Longitudinal::ThetaHGaussian => {
                let (width, shift) = u.theta_h_gaussian(lobe);
                gaussian_lobe(width, a.theta_h() - shift) * a.marschner_conversion()
            }
            Longitudinal::HenyeyGreenstein => {
                let (_, shift) = u.theta_h_gaussian(lobe);
                let (g, factor) = u.henyey_greenstein(lobe);
                let d = R::c(1.0) + g * g - R::c(2.0) * g * (a.theta_h() - shift).cos();
                factor / (d * d.sqrt()) * a.marschner_conversion()
            }
        }
    }

    /// A transmitted lobe's `D(phi) A` per channel.
    fn separable(
        &self,
        path: Transmitted,
        distribution: Distribution,
        attenuation: Attenuation,
        a: &ComposedAngles<R>,
    ) -> [R; 3] {
        let u = &self.uniforms;
        let cos_phi = a.phi.cos().label("cos_phi");
        let d = match distribution {
            Distribution::Karis(c) => {
                d_karis_of_cos(cos_phi, ExpCosCoefficients::named(karis_table(path, c)))
            }
            Distribution::FrostbiteTable => {
                let abs_theta_o = a.theta_o.abs();
                let [height, sharpness] = self.tt_table.sample([abs_theta_o, u.beta_n]);
                tt_gaussian(a.phi, height, sharpness)
            }
            Distribution::FrostbiteScaled => d_trt_frostbite(
                cos_phi,
                u.trt_scale,
                ExpCosCoefficients::named(&KARIS_D_TRT_TABLE),
            ),
        };
        let (sin_o, cos_o) = (a.pair.out.sin_o, a.pair.out.cos_o);
        let at = |h: R, sigma_a: R| offset_attenuation(path, h, sigma_a, sin_o, cos_o, u.eta);
        match attenuation {
            Attenuation::Offset(c) => {
                let h = offset_of(path, c).get::<R>();
                u.sigma_a.map(|s| d * at(h, s))
            }
            Attenuation::Exponential(c) => {
                let h = offset_of(path, Constants::Refit).get::<R>();
                let unabsorbed = d * at(h, R::c(0.0));
                let k = R::c(exponent_of(path, c));
                u.sigma_a.map(|s| unabsorbed * gerard_attenuation(k, s))
            }
        }
    }

    /// The factor absorption scales a transmitted lobe's unabsorbed `N_p` by, per channel:
    /// the transmittance `T(h)^p` of the path at Frostbite's offset ([`Attenuation::Offset`];
    /// `A_p = (1 - f)^2 f^(p-1) T^p` at one offset, so its ratio to the unabsorbed one is
    /// `T^p`) or Gerard's `e^(-k sigma_a)`.
    fn absorbed(
        &self,
        path: Transmitted,
        absorption: Attenuation,
        a: &ComposedAngles<R>,
    ) -> [R; 3] {
        let u = &self.uniforms;
        match absorption {
            Attenuation::Offset(c) => {
                let h = offset_of(path, c).get::<R>();
                let (sin_o, cos_o) = (a.pair.out.sin_o, a.pair.out.cos_o);
                let through =
                    Refraction::new(sin_o, cos_o, u.eta, u.inv_eta).path(h, PathLength::Chord);
                u.sigma_a.map(|s| {
                    let t = through.transmittance(s);
                    match path {
                        Transmitted::Tt => t,
                        Transmitted::Trt => t * t,
                    }
                })
            }
            Attenuation::Exponential(c) => {
                let k = R::c(exponent_of(path, c));
                u.sigma_a.map(|s| gerard_attenuation(k, s))
            }
        }
    }

    /// The unabsorbed `N` of a table times `absorption` for TT and TRT (`None` for R).
    fn with_absorption(
        &self,
        lobe: ComposedLobe,
        n: R,
        absorption: Option<Attenuation>,
        a: &ComposedAngles<R>,
    ) -> [R; 3] {
        match (absorption, lobe) {
            (Some(absorption), ComposedLobe::Tt) => {
                self.absorbed(Transmitted::Tt, absorption, a).map(|t| n * t)
            }
            (Some(absorption), _) => self
                .absorbed(Transmitted::Trt, absorption, a)
                .map(|t| n * t),
            (None, _) => [n; 3],
        }
    }

    /// `lobe`'s `N A` per channel; `far` holds the far field's `N_p A_p`, `tables` what the
    /// tables gave.
    fn azimuthal(
        &self,
        lobe: ComposedLobe,
        n: Azimuthal,
        a: &ComposedAngles<R>,
        far: &[[R; 3]; 4],
        tables: &TableValues<R>,
    ) -> [R; 3] {
        match (n, lobe) {
            (Azimuthal::FarField, _) => far[lobe.p()],
            (Azimuthal::Table { absorption }, _) => {
                self.with_absorption(lobe, tables.lobe[lobe.p()], absorption, a)
            }
            (Azimuthal::GerardTable { absorption }, _) => {
                self.with_absorption(lobe, tables.gerard[lobe.p()], absorption, a)
            }
            (Azimuthal::NguyenDonnellyTable, _) => {
                let [tt_r, tt_g, tt_b, r, trt_r, trt_g, trt_b] = tables.nguyen_donnelly;
                match lobe {
                    ComposedLobe::R => [r; 3],
                    ComposedLobe::Tt => [tt_r, tt_g, tt_b],
                    ComposedLobe::Trt => [trt_r, trt_g, trt_b],
                }
            }
            (Azimuthal::KarisReflection, _) => {
                let cos_half_phi = (R::c(0.5) * a.phi).cos().max(R::c(0.0));
                [r_azimuthal(cos_half_phi, a.v_dot_l, self.uniforms.eta); 3]
            }
            (Azimuthal::Separable { .. }, ComposedLobe::R) => {
                unreachable!("Composition::check rejects a separable R lobe")
            }
            (
                Azimuthal::Separable {
                    distribution,
                    attenuation,
                },
                _,
            ) => {
                let path = match lobe {
                    ComposedLobe::Tt => Transmitted::Tt,
                    _ => Transmitted::Trt,
                };
                self.separable(path, distribution, attenuation, a)
            }
        }
    }

    /// The fetches of the tables the composition reads (0 for the others).
    fn table_values(&self, a: &ComposedAngles<R>) -> TableValues<R> {
        let zero = R::c(0.0);
        let m = &self.marschner;
        TableValues {
            lobe: match &self.lobe_table {
                Some(t) => t.sample([a.phi.abs(), a.theta_o.abs(), self.uniforms.beta_n]),
                None => [zero; 3],
            },
            gerard: match &m.gerard {
                Some(t) => t.sample([a.phi.abs(), a.theta_d().abs()]),
                None => [zero; 3],
            },
            nguyen_donnelly: match &m.nguyen_donnelly {
                Some(t) => {
                    let cos_phi = a.phi.cos().label("cos_phi");
                    t.sample([cos_phi, a.theta_d().cos().label("cos_theta_d")])
                }
                None => [zero; 7],
            },
        }
    }

    /// `[R, TT, TRT, residual]` per channel (a dropped lobe is 0).
    #[inline(always)]
    fn lobes(&self, query: &Query<R>) -> [[R; 3]; 4] {
        let a = ComposedAngles::of(query);
        let chiang = self.chiang();
        let deon = chiang.longitudinal(&a.pair);
        let zero = [[R::c(0.0); 3]; 4];
        let far = match self.composition.uses_far_field() {
            true => chiang.offsets().averaged::<_, false>(&chiang, a.pair.out).0,
            false => zero,
        };
        let tables = self.table_values(&a);
        let mut lobes = zero;
        for lobe in ComposedLobe::ALL {
            if let Some(f) = self.composition.lobe(lobe) {
                let m = self.longitudinal(lobe, f.longitudinal, &a, (&chiang, &deon));
                let n = self.azimuthal(lobe, f.azimuthal, &a, &far, &tables);
                lobes[lobe.p()] = n.map(|x| (m * x).label(LOBE_LABELS[lobe.p()]));
            }
        }
        if self.composition.residual {
            lobes[3] = far[3].map(|x| deon[3] * x);
        }
        lobes
    }
}

impl<R: Real> Bcsdf<R> for ComposedHair<R> {
    fn lobe_names(&self) -> &'static [&'static str] {
        &COMPOSED_LOBES
    }

    /// `[R, TT, TRT, residual]` per channel, a dropped lobe 0.
    fn eval_lobes(&self, query: &Query<R>) -> Vec<[R; 3]> {
        self.lobes(query).to_vec()
    }

    /// The sum of the kept lobes (no cosine factor).
    #[inline(always)]
    fn eval(&self, query: &Query<R>) -> [R; 3] {
        let lobes = self.lobes(query);
        let mut sum = [R::c(0.0); 3];
        let mut first = true;
        for (p, lobe) in lobes.iter().enumerate() {
            let kept = match p {
                3 => self.composition.residual,
                _ => self.composition.lobe(ComposedLobe::ALL[p]).is_some(),
            };
            if kept {
                sum = match first {
                    true => *lobe,
                    false => core::array::from_fn(|c| sum[c] + lobe[c]),
                };
                first = false;
            }
        }
        sum
    }
}

impl Model for ComposedHair<f64> {
    type Uniforms<R: Real> = ComposedUniforms<R>;
    type In<R: Real> = ComposedHair<R>;

    fn uniforms(&self) -> ComposedUniforms<f64> {
        self.uniforms
    }

    fn with_uniforms<R: Real>(&self, uniforms: ComposedUniforms<R>) -> ComposedHair<R> {
        ComposedHair {
            uniforms,
            composition: self.composition,
            nodes: self.nodes.cast(),
            tt_table: self.tt_table.clone(),
            lobe_table: self.lobe_table.clone(),
            marschner: self.marschner.clone(),
        }
    }
}

impl VaryingInputs for ComposedHair<f64> {
    const NAME: &'static str = "composed";
    const INPUTS: &'static [Input] = &HAIR_INPUTS;
    const VARYING: &'static [&'static str] = &HAIR_VARYING;
    const BAKED: &'static [(&'static str, &'static str)] = &[];

    fn uniforms_in<R: Real>(inputs: &InputsIn<R>) -> ComposedUniforms<R> {
        composed_uniforms_in(inputs)
    }
}
