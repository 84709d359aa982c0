//! Gerard, "Fast Real-Time Shading for Polygonal Hair" (seed
//! `gerard-fast-realtime-shading-for-polygonal-hair.txt`), direct lighting, sections 2.1 and
//! 2.3, eq. 4 to 8: Marschner's three lobes with Henyey-Greenstein longitudinal functions and
//! the azimuthal functions of a lookup texture times an absorption factor.
//!
//! # Source equations
//!
//! - Eq. 4: `S = sum_p M_p(theta_h) N_p(theta_d, phi) / cos^2 theta_d`, p = R, TT, TRT.
//! - Eq. 5 and 6: `M_p(theta_h) = G(beta_p, theta_h - alpha_p)`,
//!   `G(beta, cos x) = (1 / 4 pi) (1 - g^2) / (1 + g^2 - 2 g cos x)^(3/2)` with `g = g(beta)`,
//!   and Marschner's Table 1 (`alpha_TT = -alpha_R/2`, `alpha_TRT = -3 alpha_R/2`,
//!   `beta_TT = beta_R/2`, `beta_TRT = 2 beta_R`; [`crate::params::MarschnerLobes::lobes`]).
//!   By default the lobe is eq. 6 as printed ([`crate::lobe::hg_gerard_printed`]) with g from
//!   Gerard's own fit of that lobe to a Gaussian of width beta
//!   ([`crate::models::gerard_hg_g`]); with the input `hg_normalised` it is the lobe normalised
//!   to unit integral in theta ([`crate::lobe::HenyeyGreenstein`]) with the g of that lobe
//!   ([`crate::models::hg_g_normalised`]). The printed lobe is not normalised in theta_h (its
//!   integral is 1.32 at g = 0.752; README errata), the normalised one is.
//! - Eq. 7 and 8: `N_p = N_p,LUT(theta_d, phi) T^p` with `N_p,LUT` Marschner's N_p without
//!   absorption, [`crate::lut::GerardN`] (axes |phi| in [0, pi], |theta_d| in [0, pi/2]),
//!   baked when the model is built at [`GERARD_N_SIZES`] (128 x 64 texels) and fetched with
//!   [`Real::sample_table`]; `N_R` unattenuated, `N_TT` times `e^(-4 sigma_a)`, `N_TRT` times
//!   `e^(-11/2 sigma_a)` (eq. 13's exponent, [`crate::models::GERARD_K_TRT`]; eq. 8's printed
//!   `8 (1 - 3/(2 eta^2))` is a slip, README errata), [`crate::models::gerard_attenuation`].
//!   With the input `refit_absorption` the exponents are hairmath's refits against the exact
//!   lobe energies with the chord path length averaged over directions
//!   ([`crate::models::GERARD_ABSORPTION_K_TT`] and `_TRT`, entry 3: 2.027 and 4.118), the
//!   path length of the reference the model is compared with.
//!
//! The table's lookup error at 128 x 64 (README, "Lookup tables"): largest 0.25 of the
//! channel's maximum (at the total-internal-reflection step of N_R), mean 7.2e-4; it depends
//! only on the index and the caustic setting (baking takes about 8 ms), the absorption being a
//! uniform. Against [`crate::bcsdf::Marschner2003`] of the same inputs (whose Gaussian lobes
//! and exact absorption it approximates) the relative L2 error over uniformly distributed
//! direction pairs is 0.26 for brown hair (alpha_R = -5, beta_R = 7.5 degrees).
//!
//! # Cosine factors
//!
//! Eq. 4 is Marschner's S_M with its 1/cos^2 theta_d, which his rendering equation integrates
//! against `L_i cos theta_i dw_i`; Gerard's eq. 1 writes the integral without the cosine (README
//! errata). The crate's S has no cosine factor, so [`Bcsdf::eval`] returns
//! `S = cos theta_i S_M = cos theta_i / max(cos^2 theta_d, 1e-12) sum_p M_p N_p`, as
//! [`crate::bcsdf::Marschner2003`] does.
//!
//! # Inputs
//!
//! Those of `marschner` (declared identically): `alpha_r`, `beta_r`, `eta` (the index the
//! table is baked with), `sigma_a` (per unit fibre radius; a colour is inverted at
//! beta_n = 0.3), `no_caustic` (Marschner's TRT caustic treatment in the table); and the
//! switches `hg_normalised` and `refit_absorption` (above).
//!
//! # Mapping from the physical parameters
//!
//! [`crate::models::marschner_inputs_of`] (alpha_R = alpha, beta_R = sqrt(v(beta_m)) / 2,
//! eta, sigma_a as a colour, caustic treatment on; its documentation in
//! [`crate::models::NguyenDonnelly`] gives the reasons), with the paper's lobe and exponents
//! (both switches off): the mapping measures Gerard's model as published.
//! [`crate::models::Approximation::FITTED_INPUTS`]: `alpha_r`, `beta_r`, `sigma_a`.
//!
//! **Varying in shader code** ([`crate::bcsdf::VaryingInputs`]): `alpha_r`, `beta_r` (the
//! shader evaluates the g(beta) closed forms and Marschner's Table 1) and the absorption
//! (`sigma_a`, `color` or `eumelanin` and `pheomelanin`, the form it is given in; a colour is
//! inverted at beta_n = 0.3). Baked: `eta` and `no_caustic` (the table is baked with them),
//! the switches `hg_normalised` and `refit_absorption` (they select the lobe and the exponents)
//! and, with `hg_normalised`, `beta_r` too: the normalised lobe's factor is an elliptic
//! integral computed once in `f64`. Out of their domains |alpha_r| is clamped to 22.5 degrees
//! and beta_r to 45 degrees, and beta_r at or below 0 is 1 degree (the closed forms' lower
//! end).

use super::nguyen_donnelly::MIN_COS2_THETA_D;
use crate::bcsdf::{
    clamp_closed, clamp_open_closed, sum_lobes, Bcsdf, FromInputs, Input, InputKind, InputValue,
    InputValues, InputsIn, Marschner2003, Model, Query, VaryingInputs, COLOR_BETA_N,
    MARSCHNER_LOBES,
};
use crate::error::ParamError;
use crate::geometry::local_fibre_angles;
use crate::lobe::{hg_gerard_printed, HenyeyGreenstein};
use crate::lut::{bake, GerardN, SharedTable};
use crate::models::{
    gerard_attenuation, gerard_hg_g, hg_g_normalised, marschner_inputs_of, Approximation,
    GERARD_ABSORPTION_K_TRT, GERARD_ABSORPTION_K_TT, GERARD_K_TRT, GERARD_K_TT, HG_G_BETA_DOMAIN,
};
use crate::params::{marschner_lobes, HairParams, MarschnerLobes};
use crate::real::MapInline;
use crate::real::Real;

/// Texels of the N_p,LUT table (|phi| x |theta_d|).
pub const GERARD_N_SIZES: [usize; 2] = [128, 64];

/// The entry of [`GERARD_ABSORPTION_K_TT`] and [`GERARD_ABSORPTION_K_TRT`] the
/// `refit_absorption` input uses: exact chord path length, averaged over directions.
pub const GERARD_REFIT_ENTRY: usize = 3;

crate::uniform_block! {
    /// The uniforms of [`Gerard`]: per lobe the Henyey-Greenstein asymmetry, its scale and
    /// shift; the absorption and its exponents.
    pub struct GerardUniforms<R> {
        /// g(beta_R).
        pub g_r: R,
        /// g(beta_TT).
        pub g_tt: R,
        /// g(beta_TRT).
        pub g_trt: R,
        /// The factor on eq. 6 of the R lobe: 1 as printed, 4 pi / (the lobe's integral over
        /// theta) when normalised.
        pub lobe_scale_r: R,
        /// The factor on eq. 6 of the TT lobe.
        pub lobe_scale_tt: R,
        /// The factor on eq. 6 of the TRT lobe.
        pub lobe_scale_trt: R,
        /// alpha_R, radians.
        pub alpha_r: R,
        /// alpha_TT = -alpha_R / 2.
        pub alpha_tt: R,
        /// alpha_TRT = -3 alpha_R / 2.
        pub alpha_trt: R,
        /// sigma_a per unit fibre radius and channel.
        pub sigma_a: [R; 3],
        /// The TT absorption exponent k (4, or the refit).
        pub k_tt: R,
        /// The TRT absorption exponent k (11/2, or the refit).
        pub k_trt: R,
        /// The smallest cos^2 theta_d divided by (1e-12).
        pub min_cos2_theta_d: R,
    }
}

/// Gerard's direct-lighting model (module docs).
#[derive(Clone, Debug, PartialEq)]
pub struct Gerard<R> {
    uniforms: GerardUniforms<R>,
    /// N_R, N_TT, N_TRT without absorption over (|phi|, |theta_d|).
    n: SharedTable<2, 3>,
}

/// The Henyey-Greenstein variant of eq. 6.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum GerardLobe {
    /// Eq. 6 as printed, with Gerard's literal g(beta) ([`gerard_hg_g`]).
    Printed,
    /// Normalised to unit integral over theta ([`HenyeyGreenstein`], [`hg_g_normalised`]).
    Normalised,
}

impl GerardLobe {
    /// g of a lobe of width `beta` radians: Gerard's literal closed form ([`gerard_hg_g`]) or
    /// that of the normalised lobe ([`hg_g_normalised`]).
    fn g<R: Real>(self, beta: R) -> R {
        match self {
            GerardLobe::Printed => gerard_hg_g(beta),
            GerardLobe::Normalised => hg_g_normalised(beta),
        }
    }

    /// The factor on eq. 6 of a lobe of width `beta` radians: 1 as printed, the normalised
    /// lobe's ratio to the printed one ([`HenyeyGreenstein`], computed in `f64`).
    ///
    /// # Errors
    /// Never for the closed forms' g (within (0.4, 0.99)); the check of [`HenyeyGreenstein`].
    fn scale(self, beta: f64) -> Result<f64, ParamError> {
        match self {
            GerardLobe::Printed => Ok(1.0),
            GerardLobe::Normalised => {
                let g = self.g(beta);
                // Both lobes share the shape; the ratio is the normalised lobe's factor.
                Ok(HenyeyGreenstein::new(g)?.eval(1.0) / hg_gerard_printed(g, 1.0))
            }
        }
    }

    /// The factors of the R, TT and TRT lobes of Marschner's `lobes`.
    fn scales(self, lobes: &MarschnerLobes) -> Result<[f64; 3], ParamError> {
        let [(_, b_r), (_, b_tt), (_, b_trt)] = lobes.lobes();
        Ok([self.scale(b_r)?, self.scale(b_tt)?, self.scale(b_trt)?])
    }
}

/// Gerard's uniforms in precision `R` from Marschner's R lobe `alpha_r`, `beta_r` (radians;
/// the other lobes by his Table 1, [`marschner_lobes`]), the lobe variant and its factors
/// ([`GerardLobe::scales`]), the absorption and its exponents: the one derivation of
/// [`Gerard::new`] and of shader code with varying inputs.
fn gerard_uniforms<R: Real>(
    alpha_r: R,
    beta_r: R,
    lobe: GerardLobe,
    scales: [R; 3],
    sigma_a: [R; 3],
    [k_tt, k_trt]: [R; 2],
) -> GerardUniforms<R> {
    let [(a_r, b_r), (a_tt, b_tt), (a_trt, b_trt)] = marschner_lobes(alpha_r, beta_r);
    GerardUniforms {
        g_r: lobe.g(b_r),
        g_tt: lobe.g(b_tt),
        g_trt: lobe.g(b_trt),
        lobe_scale_r: scales[0],
        lobe_scale_tt: scales[1],
        lobe_scale_trt: scales[2],
        alpha_r: a_r,
        alpha_tt: a_tt,
        alpha_trt: a_trt,
        sigma_a,
        k_tt,
        k_trt,
        min_cos2_theta_d: R::c(MIN_COS2_THETA_D),
    }
}

/// The lobe variant and the absorption exponents the switches `hg_normalised` and
/// `refit_absorption` select.
fn switched(hg_normalised: bool, refit_absorption: bool) -> (GerardLobe, [f64; 2]) {
    let lobe = match hg_normalised {
        true => GerardLobe::Normalised,
        false => GerardLobe::Printed,
    };
    let k = match refit_absorption {
        true => [
            GERARD_ABSORPTION_K_TT[GERARD_REFIT_ENTRY],
            GERARD_ABSORPTION_K_TRT[GERARD_REFIT_ENTRY],
        ],
        false => [GERARD_K_TT, GERARD_K_TRT],
    };
    (lobe, k)
}

impl Gerard<f64> {
    /// Gerard's model of Marschner's hair `source` (its lobes, index, absorption and caustic
    /// treatment) with the lobe variant `lobe` and the absorption exponents `k_tt`, `k_trt`;
    /// the table is baked at [`GERARD_N_SIZES`].
    ///
    /// # Errors
    /// [`ParamError`] if an exponent is negative or not finite.
    pub fn new(
        source: &Marschner2003,
        lobe: GerardLobe,
        k_tt: f64,
        k_trt: f64,
    ) -> Result<Self, ParamError> {
        let check = |name, k| ParamError::check(name, k, "must be finite and >= 0", |v| v >= 0.0);
        let k = [check("k_tt", k_tt)?, check("k_trt", k_trt)?];
        let scales = lobe.scales(&source.lobes)?;
        let baker = GerardN::new(source.eta, core::f64::consts::FRAC_PI_2, source.caustic)?;
        let table = bake(&baker, &GERARD_N_SIZES)
            .and_then(SharedTable::new)
            .unwrap_or_else(|e| unreachable!("the table sizes are valid: {e}"));
        let (alpha_r, beta_r) = (source.lobes.alpha_r.get(), source.lobes.beta_r.get());
        let sigma_a = source.sigma_a.rgb();
        Ok(Gerard {
            uniforms: gerard_uniforms(alpha_r, beta_r, lobe, scales, sigma_a, k),
            n: table,
        })
    }
}

impl<R> Gerard<R> {
    /// The N_p,LUT table (N_R, N_TT, N_TRT over |phi|, |theta_d|).
    pub fn n_table(&self) -> &SharedTable<2, 3> {
        &self.n
    }
}

impl<R: Real> Gerard<R> {
    /// `[R, TT, TRT]` per channel: eq. 4 to 8 with the cosine conversion.
    #[inline(always)]
    fn lobes(&self, query: &Query<R>) -> [[R; 3]; 3] {
        let u = &self.uniforms;
        let a = local_fibre_angles(query.wi, query.wo);
        let (theta_i, theta_o) = (a.theta_i().label("theta_i"), a.theta_o().label("theta_o"));
        let theta_h = ((theta_i + theta_o) * R::c(0.5)).label("theta_h");
        let theta_d = ((theta_o - theta_i) * R::c(0.5)).label("theta_d");
        #[inline(always)]
        fn lobe<R: Real>(theta_h: R, g: R, scale: R, alpha: R) -> R {
            hg_gerard_printed(g, (theta_h - alpha).cos()) * scale
        }
        let cos_d = theta_d.cos().label("cos_theta_d");
        let factor = (a.cos_theta_i / (cos_d * cos_d).max(u.min_cos2_theta_d)).label("factor");
        let [n_r, n_tt, n_trt] = self.n.sample([a.phi.abs(), theta_d.abs()]);
        let r = lobe(theta_h, u.g_r, u.lobe_scale_r, u.alpha_r) * n_r * factor;
        let tt = lobe(theta_h, u.g_tt, u.lobe_scale_tt, u.alpha_tt) * n_tt * factor;
        let trt = lobe(theta_h, u.g_trt, u.lobe_scale_trt, u.alpha_trt) * n_trt * factor;
        [
            [r; 3],
            u.sigma_a.map_inline(
                #[inline(always)]
                |s| tt * gerard_attenuation(u.k_tt, s),
            ),
            u.sigma_a.map_inline(
                #[inline(always)]
                |s| trt * gerard_attenuation(u.k_trt, s),
            ),
        ]
    }
}

impl<R: Real> Bcsdf<R> for Gerard<R> {
    fn lobe_names(&self) -> &'static [&'static str] {
        &MARSCHNER_LOBES
    }

    /// `M_p N_p cos(theta_i) / cos^2(theta_d)` per lobe and channel (eq. 4 to 8).
    fn eval_lobes(&self, query: &Query<R>) -> Vec<[R; 3]> {
        self.lobes(query).to_vec()
    }

    /// The sum of the lobes, without allocating.
    #[inline(always)]
    fn eval(&self, query: &Query<R>) -> [R; 3] {
        sum_lobes(&self.lobes(query))
    }
}

impl Model for Gerard<f64> {
    const INLINED_KERNEL: bool = true;
    type Uniforms<R: Real> = GerardUniforms<R>;
    type In<R: Real> = Gerard<R>;

    fn uniforms(&self) -> GerardUniforms<f64> {
        self.uniforms
    }

    fn with_uniforms<R: Real>(&self, uniforms: GerardUniforms<R>) -> Gerard<R> {
        Gerard {
            uniforms,
            n: self.n.clone(),
        }
    }
}

/// The inputs of [`Gerard`]: Marschner's, then the two switches.
const GERARD_INPUTS: [Input; 7] = [
    Marschner2003::INPUTS[0],
    Marschner2003::INPUTS[1],
    Marschner2003::INPUTS[2],
    Marschner2003::INPUTS[3],
    Marschner2003::INPUTS[4],
    Input {
        name: "hg_normalised",
        kind: InputKind::Switch,
        help: "Henyey-Greenstein lobes normalised to unit integral in theta_h, with their own \
               g(beta), instead of Gerard's eq. 6 as printed",
        default: None,
        conflicts_with: &[],
    },
    Input {
        name: "refit_absorption",
        kind: InputKind::Switch,
        help: "absorption exponents refitted to the exact lobe energies (chord path, averaged \
               over directions: 2.027 and 4.118) instead of Gerard's 4 and 11/2",
        default: None,
        conflicts_with: &[],
    },
];

impl FromInputs for Gerard<f64> {
    const NAME: &'static str = "gerard";
    const SUMMARY: &'static str = "Gerard's direct lighting (eq. 4-8): Henyey-Greenstein lobes, \
        Marschner's N_p from a 128 x 64 table times e^(-k sigma_a), S(wi, wo)";
    const INPUTS: &'static [Input] = &GERARD_INPUTS;

    fn from_inputs(values: &InputValues) -> Result<Self, ParamError> {
        let source = Marschner2003::from_inputs(values)?;
        let (lobe, [k_tt, k_trt]) = switched(
            values.switch("hg_normalised")?,
            values.switch("refit_absorption")?,
        );
        Gerard::new(&source, lobe, k_tt, k_trt)
    }
}

/// Why the index and the caustic treatment are baked.
const IN_THE_TABLE: &str = "the N_p table is baked with it when the model is built (a new value \
    is a new table)";
/// Why the switches are baked.
const SELECTS: &str = "a switch selects the shader's formulas";
/// Why beta_r is baked with `hg_normalised`.
const NORMALISED_BETA_R: &str = "with hg_normalised the lobes' normalisation is an elliptic \
    integral computed once in f64 (an arithmetic-geometric mean iterated to convergence)";

impl VaryingInputs for Gerard<f64> {
    const NAME: &'static str = <Self as FromInputs>::NAME;
    const INPUTS: &'static [Input] = <Self as FromInputs>::INPUTS;
    const VARYING: &'static [&'static str] = &[
        "alpha_r",
        "beta_r",
        "sigma_a",
        "color",
        "eumelanin",
        "pheomelanin",
    ];
    const BAKED: &'static [(&'static str, &'static str)] = &[
        ("eta", IN_THE_TABLE),
        ("no_caustic", IN_THE_TABLE),
        ("hg_normalised", SELECTS),
        ("refit_absorption", SELECTS),
    ];

    fn baked_for(values: &InputValues, name: &str) -> Option<&'static str> {
        let normalised = values.switch("hg_normalised").unwrap_or(false);
        (name == "beta_r" && normalised).then_some(NORMALISED_BETA_R)
    }

    /// [`Gerard::new`]'s uniforms from the inputs (the module documentation gives the
    /// clamps).
    fn uniforms_in<R: Real>(inputs: &InputsIn<R>) -> GerardUniforms<R> {
        let (lobe, k) = switched(
            inputs.switch("hg_normalised"),
            inputs.switch("refit_absorption"),
        );
        let max_shift = core::f64::consts::PI / 8.0;
        let alpha_r = clamp_closed(inputs.number("alpha_r"), -max_shift, max_shift);
        let beta_r = clamp_open_closed(
            inputs.number("beta_r"),
            0.0,
            core::f64::consts::FRAC_PI_4,
            HG_G_BETA_DOMAIN.0,
        );
        let scales = match lobe {
            GerardLobe::Printed => [R::c(1.0); 3],
            // beta_r does not vary with the normalised lobe (`baked_for`): its given value.
            GerardLobe::Normalised => {
                let lobes = Marschner2003::from_inputs(inputs.given())
                    .unwrap_or_else(|e| panic!("the values the model was built from: {e}"))
                    .lobes;
                lobe.scales(&lobes)
                    .unwrap_or_else(|e| unreachable!("the closed forms' g is valid: {e}"))
                    .map(R::c)
            }
        };
        let sigma_a = inputs.absorption("sigma_a").sigma_a(R::c(COLOR_BETA_N));
        gerard_uniforms(alpha_r, beta_r, lobe, scales, sigma_a, k.map(R::c))
    }
}

impl Approximation for Gerard<f64> {
    fn mapped_inputs(hair: &HairParams) -> InputValues {
        let mut values = marschner_inputs_of(hair);
        values.set("hg_normalised", InputValue::Switch(false));
        values.set("refit_absorption", InputValue::Switch(false));
        values
    }
    const FITTED_INPUTS: &'static [&'static str] = &["alpha_r", "beta_r", "sigma_a"];
}
