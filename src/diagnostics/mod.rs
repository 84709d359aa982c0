//! Diagnostics of scattering models: the white furnace, lobe energies, the far-field
//! integrator's error table and evaluation timings, returned as structs, and the [`Report`]
//! that gathers every figure `hairmath report` prints (the command line only formats it, as
//! markdown or JSON).
//!
//! - **White furnace** ([`albedo`], [`white_furnace`]): the directional albedo
//!   `rho(wo, h) = int S(wi, wo, h) dwi` per channel over a [`SphereRule`]; with sigma_a = 0 an
//!   energy-conserving model has rho = 1 (the contract of [`Bcsdf::eval`]), so `rho - 1` is the
//!   model's energy error plus the quadrature's.
//! - **Lobe energies** ([`lobe_energies`], [`LobeEnergies`]): per lobe and channel,
//!   `E_p = 1/2 int_{-1}^{1} int S_p(wi, wo, h) dwi dh`, the h-average taken with the nodes of
//!   [`FarFieldRule::gauss_legendre`] for near-field models and skipped (one node h = 0 of
//!   weight 1) for far-field models ([`Bcsdf::uses_offset`]).
//! - **Far-field integrator** ([`integrator_table`]): the error of
//!   [`ChiangFarField::azimuthal`]'s fixed rule against the adaptive reference
//!   [`ChiangHair::far_field_azimuthal_reference`], relative to each lobe's peak over phi.
//! - **Lobe curves** ([`lobe_curves`], and [`theta_curves`] against the inclination): S against the relative azimuth at fixed
//!   inclinations, for plots of a model beside the reference.
//! - **SH environments** ([`ShEnvironment`]): a model's outgoing radiance under every
//!   environment of bands `l <= L` (its transfer), and the relative error of a model's
//!   transfer against a reference's: the error measure of scenes lit by an SH environment.
//! - **Timing** ([`ns_per_eval`]): indicative wall-clock nanoseconds per call of any model, on
//!   deterministic inputs ([`crate::quadrature::kronecker`]).
//!
//! Everything but the timings is deterministic: fixed quadrature rules, no random numbers. The
//! furnace and energy diagnostics take any model through [`Bcsdf<f64>`] (unsized ones too, such
//! as `dyn Bcsdf<f64>`).
//!
//! ```
//! use hairmath::absorption::Absorption;
//! use hairmath::bcsdf::ChiangHair;
//! use hairmath::diagnostics::white_furnace;
//! use hairmath::params::HairParams;
//! use hairmath::quadrature::SphereRule;
//!
//! let white = HairParams { sigma_a: Absorption::NONE, ..HairParams::default() };
//! let furnace = white_furnace(
//!     &ChiangHair::<f64>::new(&white),
//!     &SphereRule::new(16, 8, 128),
//!     &[0.0, 45.0],
//!     &[-0.5, 0.5],
//! );
//! assert!(furnace.worst_error.abs() < 1e-4, "{}", furnace.worst_error);
//! ```
//!
//! [`SphereRule`]: crate::quadrature::SphereRule
//! [`Bcsdf::eval`]: crate::bcsdf::Bcsdf::eval
//! [`Bcsdf::uses_offset`]: crate::bcsdf::Bcsdf::uses_offset
//! [`Bcsdf<f64>`]: crate::bcsdf::Bcsdf
//! [`FarFieldRule::gauss_legendre`]: crate::bcsdf::FarFieldRule::gauss_legendre
//! [`ChiangFarField::azimuthal`]: crate::bcsdf::ChiangFarField::azimuthal
//! [`ChiangHair::far_field_azimuthal_reference`]: crate::bcsdf::ChiangHair::far_field_azimuthal_reference

mod comparison;
mod curves;
mod energy;
mod environment;
mod furnace;
mod integrator;
mod report;
mod timing;

pub use comparison::{DirectionPairs, EnergyReference, ModelError, OpCounts, ReferenceSamples};
pub use curves::{lobe_curves, theta_curves, LobeCurve, ThetaCurve};
pub use energy::{lobe_energies, LobeEnergies};
pub use environment::{relative_norm, EnvironmentRule, ShEnvironment};
pub use furnace::{albedo, viewing_direction, white_furnace, Furnace, FurnaceCase, VIEW_AZIMUTH};
pub use integrator::{
    integrator_table, IntegratorRow, IntegratorSettings, IntegratorTable, NodeErrors, NodeTiming,
    PEAK_FLOOR, REFERENCE_TOL, REFINED_TOL,
};
pub use report::{
    report, report_hair, report_steps, report_with_progress, EnergyConvergence, EvalTiming,
    FurnaceRow, HairEnergies, Report, ReportDetail, ReportSettings, SphereSize, FAR_NODES,
    FURNACE_BETAS, INTEGRATOR_NODES, INTEGRATOR_SIGMA_A, REPORT_ALPHA_DEG, REPORT_BETA, REPORT_ETA,
    REPORT_HAIRS, SHARP_BETA, TIMING_SIGMA_A,
};
pub use timing::{ns_per_batch_eval, ns_per_eval, TimingScalar, TIMING_INPUTS};

/// Adds `weight * value` to `sum`, channel by channel.
fn accumulate(sum: &mut [f64; 3], weight: f64, value: [f64; 3]) {
    for (s, v) in sum.iter_mut().zip(value) {
        *s += weight * v;
    }
}
