//! Gerard's shading and Kajiya-Kay against the reference render (Gerard's section 4, figure
//! 3): one scene, three images, two errors.

use super::camera::{first_hits, Camera, Hit};
use super::image::{image_error, render, Image, ImageError};
use super::lighting::{DirectionalLight, Sky};
use super::meridian::{meridian_radiance, MeridianRule};
use super::shading::{gerard_radiance, interpolated_transmittance, ClassicShading};
use crate::absorption::Absorption;
use crate::bcsdf::{Bcsdf, ChiangFarField, FarFieldRule, FromInputs, Marschner2003};
use crate::diagnostics::OpCounts;
use crate::error::ParamError;
use crate::models::gerard_sh::{
    clear_phase_model, projection_error, trace_shade, AbsorbingPhaseTable, GerardSh,
    PhaseQuadrature, PhaseTable, PhaseTables,
};
#[cfg(feature = "fit")]
use crate::models::marschner_inputs_of;
use crate::models::{
    Approximation, Gerard, GerardLobe, GERARD_ABSORPTION_K_TRT, GERARD_ABSORPTION_K_TT,
    GERARD_K_TRT, GERARD_K_TT, GERARD_REFIT_ENTRY,
};
use crate::params::HairParams;
use crate::quadrature::SphereRule;
use crate::real::Graph;
use crate::strands::occluders::{Occluders, Opacity};
use crate::strands::transmittance::{bake, BakeSettings, Baker, FastSettings, Transmittance};
use crate::strands::Strands;
use rayon::prelude::*;

/// What is rendered: the strands, their fibre, and the light.
#[derive(Clone, Copy, Debug)]
pub struct GerardScene<'a> {
    /// The strands.
    pub strands: &'a Strands,
    /// The fibre of every strand (the reference is its Chiang far field).
    pub hair: HairParams,
    /// The segments' opacity.
    pub opacity: Opacity,
    /// The environment.
    pub sky: Sky,
    /// The directional light.
    pub light: DirectionalLight,
}

/// The approximations measured against the reference.
#[derive(Clone, Copy)]
pub struct Approximations<'a> {
    /// The hair of Gerard's model per absorption variant (Marschner's parameters: Gerard's
    /// section 2.1 builds on Marschner et al. 2003): [`GerardSources::mapped`] or
    /// [`GerardSources::best_fit`].
    pub gerard_sources: &'a GerardSources,
    /// The classic model (Kajiya-Kay: [`kajiya_kay_best_fit`]).
    pub kajiya_kay: &'a (dyn Bcsdf<f64> + Sync),
}

/// The hair Gerard's shading is built from, one per [`PhaseAbsorption`] variant, so that each
/// variant can be measured at its own best inputs: the absorption `sigma_a` that minimises E
/// with eq. 14's published exponents is not the one that does with the refit exponents, nor
/// with the attenuation tabulated exactly.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct GerardSources {
    /// For [`PhaseAbsorption::Published`].
    pub published: Marschner2003,
    /// For [`PhaseAbsorption::Refit`].
    pub refit: Marschner2003,
    /// For [`PhaseAbsorption::Tabulated`].
    pub tabulated: Marschner2003,
}

impl GerardSources {
    /// The source of the variant `absorption`.
    pub fn of(&self, absorption: PhaseAbsorption) -> &Marschner2003 {
        match absorption {
            PhaseAbsorption::Published => &self.published,
            PhaseAbsorption::Refit => &self.refit,
            PhaseAbsorption::Tabulated => &self.tabulated,
        }
    }

    /// `source` for every variant.
    pub fn all(source: Marschner2003) -> Self {
        Self {
            published: source,
            refit: source,
            tabulated: source,
        }
    }

    /// Every variant at Gerard's mapping of `hair` ([`Approximation::mapped_inputs`]).
    ///
    /// # Errors
    /// As [`Marschner2003::from_inputs`].
    pub fn mapped(hair: &HairParams) -> Result<Self, ParamError> {
        Ok(Self::all(Marschner2003::from_inputs(
            &Gerard::mapped_inputs(hair),
        )?))
    }

    /// Each variant at its best-fit inputs for `hair` ([`Self::best_fit_of`]). Gerard's
    /// shading at its most accurate, as Kajiya-Kay is compared at its own.
    ///
    /// # Errors
    /// As the fits.
    #[cfg(feature = "fit")]
    pub fn best_fit(hair: &HairParams, pairs: usize) -> Result<Self, crate::fit::FitError> {
        Ok(Self {
            published: Self::best_fit_of(PhaseAbsorption::Published, hair, pairs)?,
            refit: Self::best_fit_of(PhaseAbsorption::Refit, hair, pairs)?,
            tabulated: Self::best_fit_of(PhaseAbsorption::Tabulated, hair, pairs)?,
        })
    }

    /// The source of the variant `absorption` at its best-fit inputs for `hair` (`alpha_r`,
    /// `beta_r` and `sigma_a` fitted by E against the Chiang far field on `pairs` direction
    /// pairs): Gerard's direct model with the published exponents, or with the refit ones (its
    /// switch `refit_absorption`), and Marschner et al. 2003 itself for the tabulated variant
    /// (its Gaussian lobes and exact attenuation are what the table holds). One fit, for a
    /// caller that shades with one variant.
    ///
    /// # Errors
    /// As the fit.
    #[cfg(feature = "fit")]
    pub fn best_fit_of(
        absorption: PhaseAbsorption,
        hair: &HairParams,
        pairs: usize,
    ) -> Result<Marschner2003, crate::fit::FitError> {
        use crate::bcsdf::InputValue;
        let (name, start) = match absorption {
            PhaseAbsorption::Published => (Gerard::NAME, Gerard::<f64>::mapped_inputs(hair)),
            PhaseAbsorption::Refit => {
                let mut refit = Gerard::<f64>::mapped_inputs(hair);
                refit.set("refit_absorption", InputValue::Switch(true));
                (Gerard::NAME, refit)
            }
            PhaseAbsorption::Tabulated => (Marschner2003::NAME, marschner_inputs_of(hair)),
        };
        let fitted = best_fit_inputs(name, Gerard::FITTED_INPUTS, &start, hair, pairs)?;
        Ok(Marschner2003::from_inputs(&fitted)?)
    }
}

/// How Gerard's phase function handles absorption.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum PhaseAbsorption {
    /// Eq. 14 with the published exponents 4 and 11/2.
    Published,
    /// Eq. 14 with the refit exponents ([`GERARD_ABSORPTION_K_TT`], `_TRT`, entry
    /// [`GERARD_REFIT_ENTRY`]).
    Refit,
    /// Tabulated over `sigma_a` ([`AbsorbingPhaseTable`]) from Gerard's source, Marschner et
    /// al. 2003 at the hair's Marschner lobes (its Gaussian lobes and its exact attenuation:
    /// neither eq. 6's Henyey-Greenstein lobes nor eq. 14's exponents).
    Tabulated,
}

impl PhaseAbsorption {
    /// Eq. 14's exponents `[k_TT, k_TRT]` of the variant (the published ones for the
    /// tabulated variant's direct light, which eq. 9 shades with Gerard's model).
    pub fn exponents(self) -> [f64; 2] {
        match self {
            PhaseAbsorption::Refit => [
                GERARD_ABSORPTION_K_TT[GERARD_REFIT_ENTRY],
                GERARD_ABSORPTION_K_TRT[GERARD_REFIT_ENTRY],
            ],
            PhaseAbsorption::Published | PhaseAbsorption::Tabulated => [GERARD_K_TT, GERARD_K_TRT],
        }
    }

    /// Its name in the command line and the JSON (`published`, `refit`, `tabulated`).
    pub fn name(self) -> &'static str {
        match self {
            PhaseAbsorption::Published => "published",
            PhaseAbsorption::Refit => "refit",
            PhaseAbsorption::Tabulated => "tabulated",
        }
    }
}

/// One configuration of Gerard's shading.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct GerardConfig {
    /// The phase function's bands `l <= phase_lmax`, in `[1, 4]` (Gerard: 1).
    pub phase_lmax: usize,
    /// The transmittance's bands `l <= v_lmax`, in `[0, 4]` (Gerard: 2).
    pub v_lmax: usize,
    /// The absorption of the phase function.
    pub absorption: PhaseAbsorption,
    /// The `l <= 1` tables read from Gerard's 8-bit layout ([`PhaseTable::to_rgba8`]); only
    /// with `phase_lmax = 1` and per-lobe tables.
    pub rgba8: bool,
    /// The light-leak bias of eq. 10, in `[0, 1)`.
    pub bias: f64,
}

impl GerardConfig {
    /// The environment's bands: `l <= phase_lmax + v_lmax` (the triple product of higher
    /// bands vanishes, by the Gaunt coefficients' triangle rule), at most 5.
    pub fn environment_lmax(&self) -> usize {
        (self.phase_lmax + self.v_lmax).min(5)
    }

    /// Checks every field against its domain.
    ///
    /// # Errors
    /// [`ParamError::OutOfRange`] naming the first field outside its domain.
    pub fn check(&self) -> Result<(), ParamError> {
        ParamError::check(
            "phase_lmax",
            self.phase_lmax as f64,
            "must be in [1, 4]",
            |l| (1.0..=4.0).contains(&l),
        )?;
        ParamError::check("v_lmax", self.v_lmax as f64, "must be in [0, 4]", |l| {
            l <= 4.0
        })?;
        let lobes = self.absorption != PhaseAbsorption::Tabulated;
        ParamError::check(
            "rgba8",
            f64::from(u8::from(self.rgba8)),
            "Gerard's 8-bit layout holds per-lobe tables of bands l <= 1 only",
            |r| r == 0.0 || (self.phase_lmax == 1 && lobes),
        )?;
        Ok(())
    }
}

/// How much work the comparison does.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RenderSettings {
    /// Pixels per side.
    pub size: usize,
    /// The reference's rule ([`MeridianRule`]); its convergence is measured against
    /// [`MeridianRule::halved`].
    pub reference: MeridianRule,
    /// Directions per pixel of the classic model's sky integral ([`SphereRule`]: the
    /// integrand, with `V` from the transmittance's coefficients, is smooth).
    pub classic_directions: usize,
    /// Nodes of the reference's far field ([`FarFieldRule::gauss_legendre`]).
    pub far_field_nodes: usize,
    /// Samples of `sin theta_r` of the phase tables.
    pub phase_samples: usize,
    /// Samples of `sin theta_r` and of the transmission of [`PhaseAbsorption::Tabulated`].
    pub tabulated_samples: [usize; 2],
    /// The phase tables' projection rule.
    pub quadrature: PhaseQuadrature,
    /// The transmittance baker.
    pub baker: Baker,
}

impl Default for RenderSettings {
    /// 256 x 256 pixels; the default [`MeridianRule`]; 8192 directions for the classic model;
    /// 64 far-field nodes; Gerard's 128 samples of `sin theta_r`, 64 x 16 for the tabulated
    /// absorption; the default phase rule; the fast baker.
    fn default() -> Self {
        Self {
            size: 256,
            reference: MeridianRule::default(),
            classic_directions: 8192,
            far_field_nodes: 64,
            phase_samples: 128,
            tabulated_samples: [64, 16],
            quadrature: PhaseQuadrature::default(),
            baker: Baker::Fast(FastSettings::default()),
        }
    }
}

/// What [`compare_gerard`] is doing, for its progress.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Stage {
    /// Baking the phase tables of a configuration.
    PhaseTables,
    /// Baking the transmittance (vertices).
    Transmittance,
    /// Rendering the reference (rows).
    Reference,
    /// Rendering the reference by the halved rule (rows).
    ReferenceHalf,
    /// Rendering Gerard's shading (rows).
    Gerard,
    /// Rendering Kajiya-Kay (rows).
    KajiyaKay,
}

impl Stage {
    /// Its name in words.
    pub fn name(self) -> &'static str {
        match self {
            Stage::PhaseTables => "phase tables",
            Stage::Transmittance => "transmittance",
            Stage::Reference => "reference",
            Stage::ReferenceHalf => "reference (half)",
            Stage::Gerard => "gerard",
            Stage::KajiyaKay => "kajiya-kay",
        }
    }
}

/// Gerard's image in one configuration and its error.
#[derive(Clone, Debug, PartialEq)]
pub struct GerardRender {
    /// The configuration.
    pub config: GerardConfig,
    /// The image.
    pub image: Image,
    /// Its error against the reference.
    pub error: ImageError,
    /// Its error against the reference by the halved rule (how much the reference's
    /// quadrature moves the figure).
    pub error_against_half: ImageError,
}

/// The images and their errors.
#[derive(Clone, Debug, PartialEq)]
pub struct GerardComparison {
    /// The reference.
    pub reference: Image,
    /// Gerard's shading, per configuration asked for.
    pub gerard: Vec<GerardRender>,
    /// Kajiya-Kay with Gerard's inputs (the first configuration's `V` bands and bias).
    pub kajiya_kay: Image,
    /// Kajiya-Kay's image against the reference.
    pub kajiya_kay_error: ImageError,
    /// The reference's rule.
    pub reference_rule: MeridianRule,
    /// The reference by the halved rule against the reference: its convergence.
    pub reference_convergence: ImageError,
    /// The number of covered pixels.
    pub covered: usize,
}

/// Renders `scene` with the reference, Gerard's shading in each of `configs` and the classic
/// model of `models` (given Gerard's inputs: [`ClassicShading`]), and measures them against
/// the reference. `progress(stage, done, total)` reports each stage.
///
/// # Errors
/// [`ParamError`] for a configuration or setting out of range (naming it), or if `configs`
/// is empty.
pub fn compare_gerard(
    scene: &GerardScene,
    configs: &[GerardConfig],
    settings: &RenderSettings,
    models: &Approximations,
    progress: &(dyn Fn(Stage, usize, usize) + Sync),
) -> Result<GerardComparison, ParamError> {
    ParamError::check(
        "configurations",
        configs.len() as f64,
        "must be at least one",
        |n| n >= 1.0,
    )?;
    for config in configs {
        config.check()?;
    }
    let camera = Camera::framing(scene.strands, settings.size)?;
    let rule = MeridianRule::new(
        settings.reference.circles,
        settings.reference.scattering_circles,
        settings.reference.samples,
    )?;
    let classic_rule = SphereRule::fibonacci(settings.classic_directions)?;
    let occluders = Occluders::new(scene.strands, scene.opacity);
    let hits = first_hits(&occluders, &camera);
    let v_lmax = configs.iter().map(|c| c.v_lmax).max().unwrap_or(0);
    let baked = bake_transmittance(scene, v_lmax, settings.baker, progress)?;
    let far_field = ChiangFarField::with_rule(
        &scene.hair,
        &FarFieldRule::gauss_legendre(settings.far_field_nodes)?,
    );
    let lights = (&scene.sky, &scene.light);
    let size = settings.size;
    let stage = |s: Stage| move |done, total| progress(s, done, total);
    let reference_with = |rule: &MeridianRule, s: Stage| {
        let shade = |hit: &Hit| meridian_radiance(hit, &occluders, &far_field, lights, rule);
        render(size, &hits, shade, &stage(s))
    };
    let reference = reference_with(&rule, Stage::Reference)?;
    let reference_half = reference_with(&rule.halved(), Stage::ReferenceHalf)?;
    let mut gerard = Vec::with_capacity(configs.len());
    for config in configs {
        progress(Stage::PhaseTables, 0, 1);
        let shading = GerardShading::new(
            models.gerard_sources.of(config.absorption),
            config,
            settings,
        )?;
        let sky = scene.sky.coefficients(config.environment_lmax())?;
        let shade = |hit: &Hit| {
            let v = interpolated_transmittance(hit, &baked, config.v_lmax)?;
            shading.radiance(hit, &v, &sky, &scene.light)
        };
        let image = render(size, &hits, shade, &stage(Stage::Gerard))?;
        gerard.push(GerardRender {
            config: *config,
            error: image_error(&image, &reference)?,
            error_against_half: image_error(&image, &reference_half)?,
            image,
        });
    }
    let first = configs[0];
    let classic = ClassicShading::new(
        models.kajiya_kay,
        &classic_rule,
        &scene.sky,
        first.v_lmax,
        first.bias,
    )?;
    let shade = |hit: &Hit| {
        let v = interpolated_transmittance(hit, &baked, first.v_lmax)?;
        classic.radiance(hit, &v, &scene.light)
    };
    let kajiya_kay = render(size, &hits, shade, &stage(Stage::KajiyaKay))?;
    Ok(GerardComparison {
        kajiya_kay_error: image_error(&kajiya_kay, &reference)?,
        reference_convergence: image_error(&reference_half, &reference)?,
        reference_rule: rule,
        covered: reference.covered.iter().filter(|&&c| c).count(),
        reference,
        gerard,
        kajiya_kay,
    })
}

/// The transmittance of every point of the scene's strands, bands `l <= lmax`.
fn bake_transmittance(
    scene: &GerardScene,
    lmax: usize,
    baker: Baker,
    progress: &(dyn Fn(Stage, usize, usize) + Sync),
) -> Result<Transmittance, ParamError> {
    let settings = BakeSettings {
        lmax,
        opacity: scene.opacity,
        baker,
    };
    let points = 0..scene.strands.point_count();
    bake(scene.strands, points, &settings, &|done, total| {
        progress(Stage::Transmittance, done, total)
    })
}

/// Gerard's shading at one of the phase function's band limits.
enum GerardShading {
    L1(GerardSh<f64, 3>),
    L2(GerardSh<f64, 6>),
    L3(GerardSh<f64, 10>),
    L4(GerardSh<f64, 15>),
}

impl GerardShading {
    /// The shading of Gerard's model of `source` in `config`.
    fn new(
        source: &Marschner2003,
        config: &GerardConfig,
        settings: &RenderSettings,
    ) -> Result<Self, ParamError> {
        Ok(match config.phase_lmax {
            1 => {
                let shading = build::<3>(source, config, settings)?;
                match config.rgba8 {
                    true => {
                        let tables = shading.phase().lobes().map(PhaseTable::to_rgba8);
                        let decoded = tables.as_ref().map(PhaseTable::from_rgba8).transpose()?;
                        let phase = decoded.map(PhaseTables::Lobes);
                        Self::L1(phase.map_or(shading.clone(), |p| shading.with_phase(p)))
                    }
                    false => Self::L1(shading),
                }
            }
            2 => Self::L2(build(source, config, settings)?),
            3 => Self::L3(build(source, config, settings)?),
            _ => Self::L4(build(source, config, settings)?),
        })
    }

    fn radiance(
        &self,
        hit: &Hit,
        transmittance: &[f64],
        sky: &[Vec<f64>; 3],
        light: &DirectionalLight,
    ) -> Result<[f64; 3], ParamError> {
        match self {
            Self::L1(s) => gerard_radiance(hit, transmittance, s, sky, light),
            Self::L2(s) => gerard_radiance(hit, transmittance, s, sky, light),
            Self::L3(s) => gerard_radiance(hit, transmittance, s, sky, light),
            Self::L4(s) => gerard_radiance(hit, transmittance, s, sky, light),
        }
    }
}

/// Gerard's shading of Gerard's model of `source` with phase tables of `C` channels.
fn build<const C: usize>(
    source: &Marschner2003,
    config: &GerardConfig,
    settings: &RenderSettings,
) -> Result<GerardSh<f64, C>, ParamError> {
    let shading = GerardSh::new(
        source,
        GerardLobe::Printed,
        config.absorption.exponents(),
        config.bias,
        settings.phase_samples,
        &settings.quadrature,
    )?;
    if config.absorption != PhaseAbsorption::Tabulated {
        return Ok(shading);
    }
    let absorbing = |sigma_a: f64| -> Result<Marschner2003, ParamError> {
        Ok(Marschner2003 {
            sigma_a: Absorption::grey(sigma_a)?,
            ..*source
        })
    };
    let [samples, transmissions] = settings.tabulated_samples;
    let rows = (0..transmissions)
        .into_par_iter()
        .map(|j| {
            let model = absorbing(AbsorbingPhaseTable::<C>::sigma_a_of_row(j, transmissions))?;
            AbsorbingPhaseTable::<C>::bake_row(&model, samples, &settings.quadrature)
        })
        .collect::<Result<Vec<_>, _>>()?;
    let table = AbsorbingPhaseTable::from_rows(samples, rows)?;
    Ok(shading.with_phase(PhaseTables::OverAbsorption(table)))
}

/// Gerard's shading of Gerard's model of `source` in `config` as a traced graph ([`trace_shade`]: the phase
/// fetches, their rotation, the triple product with [`Sky::default`]'s coefficients at
/// [`GerardConfig::environment_lmax`] and the directional light), for the shader emitter.
///
/// # Errors
/// As [`compare_gerard`] for the configuration.
pub fn gerard_graph(
    source: &Marschner2003,
    config: &GerardConfig,
    settings: &RenderSettings,
) -> Result<Graph, ParamError> {
    config.check()?;
    let shading = GerardShading::new(source, config, settings)?;
    let sky = Sky::default().coefficients(config.environment_lmax())?;
    match &shading {
        GerardShading::L1(s) => trace_shade(s, config.v_lmax, &sky),
        GerardShading::L2(s) => trace_shade(s, config.v_lmax, &sky),
        GerardShading::L3(s) => trace_shade(s, config.v_lmax, &sky),
        GerardShading::L4(s) => trace_shade(s, config.v_lmax, &sky),
    }
}

/// The operation counts of [`gerard_graph`].
///
/// # Errors
/// As [`gerard_graph`].
pub fn gerard_ops(
    source: &Marschner2003,
    config: &GerardConfig,
    settings: &RenderSettings,
) -> Result<OpCounts, ParamError> {
    Ok(OpCounts::of(&gerard_graph(source, config, settings)?))
}

/// What the phase function of `config` (from `source`) loses by its truncation to bands
/// `l <= L`, per `L = 0..=4` and per lobe (R, TT, TRT), at `sin theta_r = s`
/// ([`projection_error`]): for eq. 14's variants the lobes of Gerard's model without
/// absorption, which the tables hold (eq. 14 scales them at shading time); for the tabulated
/// variant Marschner et al. 2003 at `source`'s absorption.
///
/// # Errors
/// As [`projection_error`], or if `source`'s model cannot be built.
pub fn phase_projection_error(
    source: &Marschner2003,
    absorption: PhaseAbsorption,
    s: f64,
    quadrature: &PhaseQuadrature,
) -> Result<Vec<Vec<f64>>, ParamError> {
    let lmax = crate::models::gerard_sh::MAX_PHASE_LMAX;
    if absorption == PhaseAbsorption::Tabulated {
        return projection_error(source, s, lmax, quadrature);
    }
    let model = clear_phase_model(source, GerardLobe::Printed, absorption.exponents())?;
    projection_error(&model, s, lmax, quadrature)
}

/// The inputs of the registered model `name` minimising its error E against `hair`'s Chiang
/// far field (64 nodes) on `pairs` direction pairs of a Kronecker set
/// ([`crate::fit::fit_model_inputs`] of the inputs `fitted`, from `start`).
#[cfg(feature = "fit")]
fn best_fit_inputs(
    name: &str,
    fitted: &[&'static str],
    start: &crate::bcsdf::InputValues,
    hair: &HairParams,
    pairs: usize,
) -> Result<crate::bcsdf::InputValues, crate::fit::FitError> {
    use crate::diagnostics::{DirectionPairs, ReferenceSamples};
    let reference = ChiangFarField::with_rule(hair, &FarFieldRule::gauss_legendre(64)?);
    let samples = ReferenceSamples::new(&reference, DirectionPairs::kronecker(pairs));
    let entry = crate::registry::find_model(name).expect("the models measured are registered");
    let fit = crate::fit::fit_model_inputs(entry, fitted, start, &samples)?;
    Ok(fit.values)
}

/// Kajiya-Kay at its best-fit inputs for `hair` (`pairs` direction pairs).
///
/// # Errors
/// As the fit.
#[cfg(feature = "fit")]
pub fn kajiya_kay_best_fit(
    hair: &HairParams,
    pairs: usize,
) -> Result<crate::models::KajiyaKay<f64>, crate::fit::FitError> {
    use crate::models::KajiyaKay;
    let start = KajiyaKay::mapped_inputs(hair);
    let fitted = best_fit_inputs(
        KajiyaKay::NAME,
        KajiyaKay::FITTED_INPUTS,
        &start,
        hair,
        pairs,
    )?;
    Ok(KajiyaKay::from_inputs(&fitted)?)
}
