//! Marschner et al. 2003's hair scattering model ("Light Scattering from Human Hair Fibers",
//! eq. 1 and sections 4.1 to 4.3) as a model of the crate's contract: the unit-area Gaussian
//! longitudinal lobes of his Table 1 and his azimuthal N_p ([`crate::azimuthal::marschner_np`]:
//! the roots of his cubic exit angle, his two-index Fresnel, his absorption exponent, the TRT
//! caustic treatment). Reference-only `f64` code (root solving does not trace); the lookup
//! tables of Nguyen and Donnelly and of Gerard ([`crate::lut`]) sample its factors.
//!
//! Marschner writes `L_o = int S_M L_i cos(theta_i) dw_i` with
//! `S_M = sum_p M_p(theta_h) N_p(phi; theta_d) / cos^2(theta_d)`; the crate's S has no cosine
//! factor (radiance is `int S L_i dw_i`), so [`Bcsdf::eval`] returns
//! `S = sum_p M_p N_p cos(theta_i) / cos^2(theta_d)`. The model does not conserve energy (its
//! Gaussians are not normalised over the sphere, and the caustic treatment adds energy).
//!
//! **Varying in shader code:** none; the model has no shader form
//! ([`crate::registry::MARSCHNER_NO_SHADER_FORM`]: its N_p finds the exit offsets by root
//! finding). `nguyen-donnelly` is the same model through lookup textures, and its shader is
//! the baked one.

use super::inputs::{FromInputs, Input, InputKind, InputValues, HAIR_INPUTS};
use super::model::{Bcsdf, Query};
use crate::absorption::Absorption;
use crate::azimuthal::{marschner_np, CausticParams, MarschnerPath};
use crate::error::ParamError;
use crate::geometry::local_fibre_angles;
use crate::lobe::gaussian_lobe;
use crate::params::{AzimuthalRoughness, LobeShift, LobeWidth, MarschnerLobes, RefractiveIndex};

/// The lobes of Marschner's model.
pub const MARSCHNER_LOBES: [&str; 3] = ["R", "TT", "TRT"];

/// Smallest `cos^2(theta_d)` divided by: `1 / cos^2(theta_d)` diverges where both directions
/// graze the fibre from opposite ends (theta_d -> +-90 degrees).
const MIN_COS2_THETA_D: f64 = 1e-12;

/// Marschner et al. 2003's model with validated parameters.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Marschner2003 {
    /// The longitudinal lobes.
    pub lobes: MarschnerLobes,
    /// The relative index of refraction.
    pub eta: RefractiveIndex,
    /// Absorption per unit radius (Marschner's path-length exponent is applied to it).
    pub sigma_a: Absorption,
    /// The TRT caustic treatment (section 4.3), or `None` for the bare root sum.
    pub caustic: Option<CausticParams>,
}

impl MarschnerLobes {
    /// `[M_R, M_TT, M_TRT]` at the half angle theta_h: unit-area Gaussians
    /// [`gaussian_lobe`]`(beta_p, theta_h - alpha_p)` (per radian of theta_h; Marschner 2003,
    /// eq. 6 and Table 1).
    pub fn longitudinal(&self, theta_h: f64) -> [f64; 3] {
        self.lobes()
            .map(|(alpha, beta)| gaussian_lobe(beta, theta_h - alpha))
    }
}

impl Marschner2003 {
    /// `N_p(phi)` per channel for p = R, TT, TRT at relative azimuth `phi` (any real) and
    /// inclination `sin theta_d` ([`marschner_np`]: per radian of phi, without the
    /// `1 / cos^2 theta_d` of eq. 1).
    pub fn azimuthal(&self, phi: f64, sin_theta_d: f64) -> [[f64; 3]; 3] {
        let [r, tt, trt] = [MarschnerPath::R, MarschnerPath::TT, MarschnerPath::TRT];
        [r, tt, trt].map(|path| {
            marschner_np(
                path,
                phi,
                sin_theta_d,
                self.eta.get(),
                self.sigma_a.rgb(),
                self.caustic.as_ref(),
            )
        })
    }
}

impl Bcsdf<f64> for Marschner2003 {
    fn lobe_names(&self) -> &'static [&'static str] {
        &MARSCHNER_LOBES
    }

    /// `M_p(theta_h) N_p(phi) cos(theta_i) / cos^2(theta_d)` per lobe and channel, with
    /// `cos^2(theta_d)` floored at 1e-12.
    fn eval_lobes(&self, query: &Query<f64>) -> Vec<[f64; 3]> {
        let a = local_fibre_angles(query.wi, query.wo);
        let theta_d = a.theta_d();
        let factor = a.cos_theta_i / theta_d.cos().powi(2).max(MIN_COS2_THETA_D);
        let m = self.lobes.longitudinal(a.theta_h());
        let n = self.azimuthal(a.phi, theta_d.sin());
        (0..3).map(|p| n[p].map(|np| m[p] * np * factor)).collect()
    }
}

/// The inputs of [`Marschner2003`].
const MARSCHNER_INPUTS: [Input; 5] = [
    Input {
        name: "alpha_r",
        kind: InputKind::Angle,
        help: "shift alpha_R of Marschner's R lobe, |alpha_R| <= 22.5 degrees (TT and TRT \
               follow by his Table 1)",
        default: Some(-5.0),
        conflicts_with: &[],
    },
    Input {
        name: "beta_r",
        kind: InputKind::Angle,
        help: "width beta_R of Marschner's R lobe, in (0, 45] degrees (TT and TRT follow by \
               his Table 1)",
        default: Some(7.5),
        conflicts_with: &[],
    },
    HAIR_INPUTS[3],
    HAIR_INPUTS[4],
    Input {
        name: "no_caustic",
        kind: InputKind::Switch,
        help: "leave out Marschner's TRT caustic treatment",
        default: None,
        conflicts_with: &[],
    },
];

/// The beta_n with which a colour is inverted to absorption for a model without azimuthal
/// roughness (Chiang et al. 2016's colour mapping at beta_n = 0.3, as Unreal uses it).
pub const COLOR_BETA_N: f64 = 0.3;

impl FromInputs for Marschner2003 {
    const NAME: &'static str = "marschner";
    const SUMMARY: &'static str = "Marschner et al. 2003: Gaussian lobes and his cubic-root N_p \
        with the TRT caustic treatment, S(wi, wo) (a colour is inverted at beta_n = 0.3)";
    const INPUTS: &'static [Input] = &MARSCHNER_INPUTS;

    fn from_inputs(values: &InputValues) -> Result<Self, ParamError> {
        let beta_n = AzimuthalRoughness::new(COLOR_BETA_N)?;
        Ok(Marschner2003 {
            lobes: MarschnerLobes {
                alpha_r: LobeShift::new(values.number("alpha_r")?)?,
                beta_r: LobeWidth::new(values.number("beta_r")?)?,
            },
            eta: RefractiveIndex::new(values.number("eta")?)?,
            sigma_a: values.absorption("sigma_a")?.resolve(beta_n)?,
            caustic: (!values.switch("no_caustic")?).then(CausticParams::default),
        })
    }
}
