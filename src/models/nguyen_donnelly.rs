//! Nguyen and Donnelly 2005 ("Hair Animation and Rendering in the Nalu Demo", GPU Gems 2,
//! ch. 23): Marschner et al. 2003's model evaluated through lookup textures, as the
//! realtime-slides seed (`realtime-hair-slides-lut-opacity-maps.txt`, "Pseudocode Summarizing
//! the Shaders") lists it:
//!
//! ```text
//! // vertex shader
//! sinThetaI = dot(light, tangent);  sinThetaO = dot(eye, tangent)
//! lightPerp = light - sinThetaI tangent;  eyePerp = eye - sinThetaO tangent
//! cosPhiD = dot(eyePerp, lightPerp) (dot(eyePerp, eyePerp) dot(lightPerp, lightPerp))^-1/2
//! // fragment shader
//! (M_R, M_TT, M_TRT, cosThetaD) = lookup1(sinThetaI, sinThetaO)
//! (N_TT, N_R) = lookup2(cosPhiD, cosThetaD);  N_TRT = lookup3(cosPhiD, cosThetaD)
//! S = M_R N_R + M_TT N_TT + M_TRT N_TRT
//! ```
//!
//! (the slides label the first lookup `(cosThetaI, cosThetaO)`; the texture is indexed by the
//! sines the vertex shader computes: README errata, `lut::NguyenM`).
//!
//! # The tables
//!
//! The M texture is [`crate::lut::NguyenM`] (axes sin theta_i, sin theta_o in [-1, 1];
//! channels M_R, M_TT, M_TRT, cos theta_d) and the two N textures are
//! [`crate::lut::NguyenN`] (axes cos phi in [-1, 1], cos theta_d in [0, 1]; channels N_TT
//! rgb, N_R, N_TRT rgb), baked once in f64 when the model is built
//! ([`NguyenDonnelly::new`]) at [`NGUYEN_DONNELLY_M_SIZES`] and [`NGUYEN_DONNELLY_N_SIZES`]
//! (128 x 128 texels each), and fetched with [`Real::sample_table`], which traces to
//! `textureSampleLevel`. The absorption, the index and the caustic treatment are baked into
//! the N textures (a new hair colour is a new texture, as in the demo); the lobe shift and width
//! into the M texture. The only uniform is the floor of cos^2 theta_d.
//!
//! Lookup error at that resolution against direct evaluation, measured with
//! [`crate::lut::lookup_error`] at 1,000 off-grid points for the default Marschner hair
//! (alpha_R = -5, beta_R = 7.5 degrees, eta 1.55, brown sigma_a, caustic on) and asserted by
//! `tests/models_tables.rs` ([`NguyenDonnelly::lookup_errors`]): M largest error 0.104 of the
//! channel's maximum, mean 4.1e-4; N largest 0.306, mean 2.5e-4. The largest N errors sit on
//! the step of Marschner's two-index Fresnel factor at total internal reflection (README,
//! "Lookup tables").
//!
//! Against [`Marschner2003::eval`] itself (same directions, no cosine factor either side), as
//! the relative L2 error `sqrt(sum (S - S_M)^2 / sum S_M^2)` over 20,000 direction pairs
//! uniform on the product of two spheres: see `tests/models_tables.rs`, which asserts the
//! figures of the deviation below.
//!
//! # Deviation from the slides: cos theta_d from the directions
//!
//! The slides' pseudocode reads cos theta_d from the M texture (its fourth channel, which the
//! baked texture still holds). Near the corner sin theta_i = -+1, sin theta_o = +-1,
//! cos theta_d = cos((asin s_o - asin s_i) / 2) has square-root singularities that no bilinear
//! texture follows, and S grows like 1/cos^2 theta_d there: with the texture's value the
//! relative L2 error against Marschner over all pairs is 0.30 at 128 x 128 texels, and the
//! error against the Chiang far field on the comparison's pairs (`hairmath models`) is 23
//! for dark brown hair, a figure that grows with the number of pairs (31.7 on half of them),
//! dominated by a few pairs near that corner. hairmath computes it from the directions
//! instead, `cos theta_d = sqrt((1 + cos theta_i cos theta_o + sin theta_i sin theta_o) / 2)`
//! (one square root per shading point).
//!
//! # Cosine factors
//!
//! Marschner's S_M = sum_p M_p N_p / cos^2 theta_d is integrated against
//! `L_i cos theta_i dw_i`; the slides' `S` leaves out the 1/cos^2 theta_d (their N textures may
//! include it; hairmath's do not, `lut::NguyenN`) and the cos theta_i. The crate's S has no
//! cosine factor, so [`Bcsdf::eval`] returns, as [`Marschner2003::eval`] does,
//! `S = cos theta_i / max(cos^2 theta_d, min_cos2_theta_d) * sum_p M_p N_p`, with cos theta_d
//! computed from the directions (see "Deviation") and cos theta_i = |wi projected on the
//! normal plane|.
//!
//! # Inputs
//!
//! Those of `marschner` ([`Marschner2003`], declared identically): `alpha_r` (R lobe shift,
//! |alpha_R| <= 22.5 degrees), `beta_r` (R lobe width, (0, 45] degrees; TT and TRT follow by
//! Marschner's Table 1), `eta` ((1, 3]), `sigma_a` (per unit fibre radius; a colour is
//! inverted at beta_n = 0.3), `no_caustic`.
//!
//! # Mapping from the physical parameters ([`marschner_inputs_of`])
//!
//! - `alpha_r = alpha`, clamped to |alpha_R| <= 22.5 degrees. In hairmath's frame Chiang's R
//!   lobe (pbrt-v4: theta_o rotated by -2 alpha) peaks at theta_h = +alpha, his TT at
//!   -alpha/2 and TRT at -2 alpha; Marschner's lobes peak at alpha_R, -alpha_R/2 and
//!   -3 alpha_R/2, so alpha_R = alpha puts R and TT exactly where the reference has them and
//!   TRT within alpha/2.
//! - `beta_r = sqrt(v(beta_m)) / 2`, v = [`crate::bcsdf::longitudinal_variance`] (Chiang
//!   eq. 7), clamped to (0, 45] degrees. d'Eon's lobe of variance v is, as v -> 0, a Gaussian of
//!   standard deviation sqrt(v) in theta_i about the specular cone; Marschner's Gaussian of
//!   width beta in theta_h = (theta_i + theta_o)/2 has standard deviation 2 beta in theta_i.
//!   Chiang's v_TT = v/4 and v_TRT = 4 v then give exactly Marschner's beta_TT = beta_R/2 and
//!   beta_TRT = 2 beta_R. (beta_m = 0.3 gives beta_R = 8.3 degrees, inside Marschner's 5 to 10.)
//! - `eta` as given; `sigma_a` the hair's own, passed as the colour whose inversion at
//!   beta_n = 0.3 gives it back (so a fit can vary it as a colour; see
//!   [`absorption_as_colour`]).
//! - `no_caustic` off: Marschner's caustic treatment stands for the smoothing that the
//!   reference's azimuthal roughness does. beta_n has no counterpart (Marschner's fibre is
//!   smooth in azimuth).
//!
//! [`crate::models::Approximation::FITTED_INPUTS`]: `alpha_r`, `beta_r`, `sigma_a`.
//!
//! **Varying in shader code** ([`crate::bcsdf::VaryingInputs`]): none. Every input is baked
//! into the textures (alpha_r and beta_r into M; eta, the absorption and the caustic treatment
//! into N), which are tabulated in `f64` when the model is built; the shader's only uniform is
//! a constant.

use crate::absorption::Absorption;
use crate::bcsdf::{
    longitudinal_variance, sum_lobes, AbsorptionInput, Bcsdf, FromInputs, Input, InputValue,
    InputValues, InputsIn, Marschner2003, Model, Query, VaryingInputs, COLOR_BETA_N,
    MARSCHNER_LOBES,
};
use crate::error::ParamError;
use crate::geometry::{local_sin_cos_theta, V3};
use crate::lut::{bake, lookup_error, ErrorStats, LutError, NguyenM, NguyenN, SharedTable};
use crate::models::Approximation;
use crate::params::HairParams;
use crate::real::{safe_sqrt, Real};

/// Texels of the M texture (sin theta_i x sin theta_o).
pub const NGUYEN_DONNELLY_M_SIZES: [usize; 2] = [128, 128];

/// Texels of the N textures (cos phi x cos theta_d).
pub const NGUYEN_DONNELLY_N_SIZES: [usize; 2] = [128, 128];

/// The smallest cos^2 theta_d divided by (as [`Marschner2003`]: 1/cos^2 theta_d diverges where
/// both directions graze the fibre from opposite ends).
pub(crate) const MIN_COS2_THETA_D: f64 = 1e-12;

crate::uniform_block! {
    /// The uniforms of [`NguyenDonnelly`]: everything else is in its textures.
    pub struct NguyenDonnellyUniforms<R> {
        /// The smallest cos^2 theta_d the scattering function divides by (1e-12, as
        /// [`Marschner2003`]).
        pub min_cos2_theta_d: R,
    }
}

/// Marschner et al. 2003 through Nguyen and Donnelly's M and N textures (module docs).
#[derive(Clone, Debug, PartialEq)]
pub struct NguyenDonnelly<R> {
    uniforms: NguyenDonnellyUniforms<R>,
    /// M_R, M_TT, M_TRT, cos theta_d over (sin theta_i, sin theta_o).
    m: SharedTable<2, 4>,
    /// N_TT rgb, N_R, N_TRT rgb over (cos phi, cos theta_d).
    n: SharedTable<2, 7>,
    /// The model the tables sample.
    source: Marschner2003,
}

/// The uniforms of [`NguyenDonnelly`], which depend on no input.
fn nguyen_donnelly_uniforms<R: Real>() -> NguyenDonnellyUniforms<R> {
    NguyenDonnellyUniforms {
        min_cos2_theta_d: R::c(MIN_COS2_THETA_D),
    }
}

impl NguyenDonnelly<f64> {
    /// The textures of `source` baked at [`NGUYEN_DONNELLY_M_SIZES`] and
    /// [`NGUYEN_DONNELLY_N_SIZES`] (about 20 ms in an optimised build).
    pub fn new(source: Marschner2003) -> Self {
        Self::with_sizes(source, NGUYEN_DONNELLY_M_SIZES, NGUYEN_DONNELLY_N_SIZES)
            .unwrap_or_else(|e| unreachable!("the default texture sizes are valid: {e}"))
    }

    /// The textures of `source` baked at `m_sizes` and `n_sizes` texels.
    ///
    /// # Errors
    /// [`LutError::Axis`] for a size outside 2 to 65,536.
    pub fn with_sizes(
        source: Marschner2003,
        m_sizes: [usize; 2],
        n_sizes: [usize; 2],
    ) -> Result<Self, LutError> {
        let (m, n) = Self::bakers(&source);
        Ok(NguyenDonnelly {
            uniforms: nguyen_donnelly_uniforms(),
            m: SharedTable::new(bake(&m, &m_sizes)?)?,
            n: SharedTable::new(bake(&n, &n_sizes)?)?,
            source,
        })
    }

    fn bakers(source: &Marschner2003) -> (NguyenM, NguyenN) {
        (
            NguyenM::new(source.lobes),
            NguyenN::new(source.eta, source.sigma_a, source.caustic),
        )
    }

    /// The lookup error of the M and N textures against direct evaluation of Marschner's
    /// factors at `points` off-grid points ([`lookup_error`]).
    ///
    /// # Errors
    /// None in practice (the tables were baked from these bakers).
    pub fn lookup_errors(&self, points: usize) -> Result<[ErrorStats; 2], LutError> {
        let (m, n) = Self::bakers(&self.source);
        Ok([
            lookup_error(&m, self.m.table(), points)?,
            lookup_error(&n, self.n.table(), points)?,
        ])
    }
}

impl<R> NguyenDonnelly<R> {
    /// The Marschner model the textures sample.
    pub fn source(&self) -> &Marschner2003 {
        &self.source
    }
    /// The M texture (M_R, M_TT, M_TRT, cos theta_d over sin theta_i, sin theta_o).
    pub fn m_table(&self) -> &SharedTable<2, 4> {
        &self.m
    }
    /// The N textures as one table (N_TT rgb, N_R, N_TRT rgb over cos phi, cos theta_d).
    pub fn n_table(&self) -> &SharedTable<2, 7> {
        &self.n
    }
}

/// cos phi of the relative azimuth, as the slides' vertex shader computes it: the normalised
/// dot product of the projections of `wi` and `wo` onto the normal plane (local frame: the
/// tangent is +X). Where a projection vanishes (a direction along the tangent) phi is taken
/// as 0, the convention of [`crate::geometry::azimuth_between`], so the result is 1.
#[inline(always)]
fn cos_relative_azimuth<R: Real>(wi: V3<R>, wo: V3<R>) -> R {
    let dot = wi.y * wo.y + wi.z * wo.z;
    let norms = (wi.y * wi.y + wi.z * wi.z) * (wo.y * wo.y + wo.z * wo.z);
    let defined = R::c(0.0).lt(norms);
    let cos_phi = dot / R::select(defined, norms, R::c(1.0)).sqrt();
    R::select(defined, cos_phi, R::c(1.0)).clamp(R::c(-1.0), R::c(1.0))
}

impl<R: Real> NguyenDonnelly<R> {
    /// `[R, TT, TRT]` per channel: the fragment shader of the module docs with the cosine
    /// conversion.
    #[inline(always)]
    fn lobes(&self, query: &Query<R>) -> [[R; 3]; 3] {
        let (sin_i, cos_i) = local_sin_cos_theta(query.wi);
        let (sin_o, cos_o) = local_sin_cos_theta(query.wo);
        let (sin_i, cos_i) = (sin_i.label("sin_theta_i"), cos_i.label("cos_theta_i"));
        let (sin_o, cos_o) = (sin_o.label("sin_theta_o"), cos_o.label("cos_theta_o"));
        // The M texture's fourth channel holds cos theta_d as the slides read it; it is
        // computed from the directions instead (module docs, "Deviation").
        let [m_r, m_tt, m_trt, _] = self.m.sample([sin_i, sin_o]);
        let cos_d =
            safe_sqrt((R::c(1.0) + cos_i * cos_o + sin_i * sin_o) * R::c(0.5)).label("cos_theta_d");
        let cos_phi = cos_relative_azimuth(query.wi, query.wo).label("cos_phi");
        let [tt_r, tt_g, tt_b, n_r, trt_r, trt_g, trt_b] = self.n.sample([cos_phi, cos_d]);
        let factor = (cos_i / (cos_d * cos_d).max(self.uniforms.min_cos2_theta_d)).label("factor");
        let (r, tt, trt) = (m_r * factor, m_tt * factor, m_trt * factor);
        [
            [r * n_r; 3],
            [tt * tt_r, tt * tt_g, tt * tt_b],
            [trt * trt_r, trt * trt_g, trt * trt_b],
        ]
    }
}

impl<R: Real> Bcsdf<R> for NguyenDonnelly<R> {
    fn lobe_names(&self) -> &'static [&'static str] {
        &MARSCHNER_LOBES
    }

    /// `M_p N_p cos(theta_i) / cos^2(theta_d)` per lobe and channel, from the textures.
    fn eval_lobes(&self, query: &Query<R>) -> Vec<[R; 3]> {
        self.lobes(query).to_vec()
    }

    /// The sum of the lobes, without allocating.
    #[inline(always)]
    fn eval(&self, query: &Query<R>) -> [R; 3] {
        sum_lobes(&self.lobes(query))
    }
}

impl Model for NguyenDonnelly<f64> {
    const INLINED_KERNEL: bool = true;
    type Uniforms<R: Real> = NguyenDonnellyUniforms<R>;
    type In<R: Real> = NguyenDonnelly<R>;

    fn uniforms(&self) -> NguyenDonnellyUniforms<f64> {
        self.uniforms
    }

    fn with_uniforms<R: Real>(&self, uniforms: NguyenDonnellyUniforms<R>) -> NguyenDonnelly<R> {
        NguyenDonnelly {
            uniforms,
            m: self.m.clone(),
            n: self.n.clone(),
            source: self.source,
        }
    }
}

impl FromInputs for NguyenDonnelly<f64> {
    const NAME: &'static str = "nguyen-donnelly";
    const SUMMARY: &'static str = "Nguyen and Donnelly 2005 (GPU Gems 2 ch. 23): Marschner 2003 \
        through 128 x 128 M and N lookup textures baked from the inputs, S(wi, wo)";
    const INPUTS: &'static [Input] = Marschner2003::INPUTS;

    fn from_inputs(values: &InputValues) -> Result<Self, ParamError> {
        Ok(Self::new(Marschner2003::from_inputs(values)?))
    }
}

/// Why the inputs of the table-based models are baked: they are tabulated.
const IN_THE_TEXTURES: &str = "it is baked into the lookup textures, which are tabulated in f64 \
    when the model is built (a new value is a new texture)";

impl VaryingInputs for NguyenDonnelly<f64> {
    const NAME: &'static str = <Self as FromInputs>::NAME;
    const INPUTS: &'static [Input] = <Self as FromInputs>::INPUTS;
    const VARYING: &'static [&'static str] = &[];
    const BAKED: &'static [(&'static str, &'static str)] = &[
        ("alpha_r", IN_THE_TEXTURES),
        ("beta_r", IN_THE_TEXTURES),
        ("eta", IN_THE_TEXTURES),
        ("sigma_a", IN_THE_TEXTURES),
        ("no_caustic", IN_THE_TEXTURES),
    ];

    /// The one constant (no input enters the uniforms).
    fn uniforms_in<R: Real>(_inputs: &InputsIn<R>) -> NguyenDonnellyUniforms<R> {
        nguyen_donnelly_uniforms()
    }
}

/// The absorption input that stands for `sigma_a` in a model whose colours are inverted at
/// beta_n = [`COLOR_BETA_N`] (Marschner's inputs): the colour c with
/// `Absorption::from_color(c, 0.3) = sigma_a` (the inversion is
/// `sigma_a = (ln c / d(0.3))^2`, so `c = exp(-d(0.3) sqrt(sigma_a))`), which a fit can vary
/// within (0, 1]; sigma_a itself where that colour would underflow to 0 (sigma_a above about
/// 1.6e4).
pub fn absorption_as_colour(sigma_a: Absorption) -> AbsorptionInput {
    let beta_n = crate::params::AzimuthalRoughness::new(COLOR_BETA_N)
        .unwrap_or_else(|_| unreachable!("0.3 is a valid beta_n"));
    // d(beta_n) from the inversion itself: sigma_a of the colour 1/e is 1/d^2.
    let d = Absorption::from_color([(-1.0f64).exp(); 3], beta_n)
        .map(|a| 1.0 / a.rgb()[0].sqrt())
        .unwrap_or_else(|_| unreachable!("1/e is a valid colour"));
    let colour = sigma_a.rgb().map(|s| (-d * s.sqrt()).exp());
    if colour.iter().all(|&c| c > 0.0 && c <= 1.0) {
        AbsorptionInput::Color(colour)
    } else {
        AbsorptionInput::SigmaA(sigma_a.rgb())
    }
}

/// The inputs of Marschner's model (`marschner`, `nguyen-donnelly`) for the physical hair
/// `hair`, by the mapping of the module docs: alpha_R = alpha, beta_R = sqrt(v(beta_m)) / 2
/// (both clamped to their domains), eta, sigma_a as a colour ([`absorption_as_colour`]),
/// caustic treatment on.
pub fn marschner_inputs_of(hair: &HairParams) -> InputValues {
    let max_shift = core::f64::consts::PI / 8.0;
    let alpha_r = hair.alpha.get().clamp(-max_shift, max_shift);
    let beta_r = (0.5 * longitudinal_variance(hair.beta_m.get()).sqrt())
        .clamp(1e-6, core::f64::consts::FRAC_PI_4);
    let mut values = InputValues::new();
    values.set("alpha_r", InputValue::Number(alpha_r));
    values.set("beta_r", InputValue::Number(beta_r));
    values.set("eta", InputValue::Number(hair.eta.get()));
    values.set(
        "sigma_a",
        InputValue::Absorption(absorption_as_colour(hair.sigma_a)),
    );
    values.set("no_caustic", InputValue::Switch(false));
    values
}

impl Approximation for NguyenDonnelly<f64> {
    fn mapped_inputs(hair: &HairParams) -> InputValues {
        marschner_inputs_of(hair)
    }
    const FITTED_INPUTS: &'static [&'static str] = &["alpha_r", "beta_r", "sigma_a"];
}
