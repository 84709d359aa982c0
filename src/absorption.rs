//! Absorption inside the fibre: the absorption coefficient sigma_a (per unit fibre radius) from
//! a colour or from melanin concentrations, and the transmittance of one internal path.

use crate::error::ParamError;
use crate::params::AzimuthalRoughness;
use crate::real::{powi, Real};

/// Absorption coefficient per unit fibre radius, one value per linear RGB channel.
pub type Rgb = [f64; 3];

/// Eumelanin absorption per unit concentration and radius (Chiang et al. 2016, section 4.2;
/// the values pbrt-v4 uses).
pub const EUMELANIN_SIGMA_A: Rgb = [0.419, 0.697, 1.37];
/// Pheomelanin absorption per unit concentration and radius (same source).
pub const PHEOMELANIN_SIGMA_A: Rgb = [0.187, 0.4, 1.05];

/// The names of hair colours by melanin concentration, `(name, eumelanin, pheomelanin)`
/// ([`Absorption::from_melanin`]), on the scale of Chiang et al. 2016 as pbrt documents it
/// (blonde about 0.3, brown about 1.3, black about 8), with dark brown between brown and black
/// and red a blonde's eumelanin with pheomelanin added. Every named hair of the crate, its
/// command line, tests and README means these concentrations: the report's lobe tables
/// (`diagnostics::REPORT_HAIRS`), the model comparison (`fit::COMPARISON_COLOURS`), the
/// example scenes (`plan::EXAMPLE_SCENES`) and [`HairParams::default`](crate::params::HairParams)
/// (brown).
pub const HAIR_COLOURS: [(&str, f64, f64); 5] = [
    ("blonde", 0.3, 0.0),
    ("red", 0.3, 2.0),
    ("brown", 1.3, 0.0),
    ("dark brown", 3.0, 0.0),
    ("black", 8.0, 0.0),
];

/// The largest melanin concentration [`Absorption::from_melanin`] accepts: 1e300, far above
/// hair's (0 to 8) and below where sigma_a would overflow.
pub const MAX_MELANIN: f64 = 1e300;

/// Absorption sigma_a per unit fibre radius, validated: every channel finite and >= 0. The one
/// type every model, baker and fit takes for absorption, whichever way it was specified
/// (directly, from melanin, or from a colour).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Absorption(Rgb);

impl Absorption {
    /// No absorption (a white fibre: the white-furnace configuration).
    pub const NONE: Absorption = Absorption([0.0; 3]);

    /// sigma_a given per linear RGB channel.
    ///
    /// # Errors
    /// [`ParamError::OutOfRange`] naming `sigma_a` and the first negative or non-finite value.
    pub fn new(sigma_a: Rgb) -> Result<Self, ParamError> {
        for &s in &sigma_a {
            ParamError::check(
                "sigma_a",
                s,
                "absorption must be finite and >= 0 in every channel",
                |v| v >= 0.0,
            )?;
        }
        Ok(Absorption(sigma_a))
    }

    /// The same sigma_a in every channel (checked as [`Absorption::new`]).
    ///
    /// # Errors
    /// As [`Absorption::new`].
    pub fn grey(sigma_a: f64) -> Result<Self, ParamError> {
        Self::new([sigma_a; 3])
    }

    /// sigma_a from melanin concentrations: `eu * EUMELANIN_SIGMA_A + pheo *
    /// PHEOMELANIN_SIGMA_A` (Chiang et al. 2016, section 4.2). Typical human hair has `eu` in
    /// [0, 8]; each concentration may be at most [`MAX_MELANIN`] (1e300), where sigma_a stays
    /// finite (`f64::MAX / 2.42`, the largest channel's coefficients summed, is 7.4e307).
    ///
    /// # Errors
    /// [`ParamError::OutOfRange`] naming the concentration that is negative, not finite or
    /// above [`MAX_MELANIN`].
    pub fn from_melanin(eumelanin: f64, pheomelanin: f64) -> Result<Self, ParamError> {
        let allowed = "melanin concentrations must be in [0, 1e300] (sigma_a must be finite)";
        let ok = |v: f64| (0.0..=MAX_MELANIN).contains(&v);
        let eu = ParamError::check("eumelanin", eumelanin, allowed, ok)?;
        let ph = ParamError::check("pheomelanin", pheomelanin, allowed, ok)?;
        Self::new(sigma_a_of_melanin(eu, ph))
    }

    /// sigma_a that gives a multiply-scattered hair volume approximately the colour `color`,
    /// for azimuthal roughness `beta_n` (Chiang et al. 2016, section 4.2, the inversion pbrt-v4
    /// uses):
    /// `sigma_a = (ln c / (5.969 - 0.215 b + 2.532 b^2 - 10.73 b^3 + 5.574 b^4 + 0.245 b^5))^2`.
    ///
    /// # Errors
    /// A colour channel outside (0, 1] (0 would need infinite absorption).
    pub fn from_color(color: Rgb, beta_n: AzimuthalRoughness) -> Result<Self, ParamError> {
        for &c in &color {
            ParamError::check(
                "color",
                c,
                "colour channels must be in (0, 1] (linear RGB)",
                |v| v > 0.0 && v <= 1.0,
            )?;
        }
        Self::new(color.map(|c| sigma_a_of_color(c, beta_n.get())))
    }

    /// sigma_a per channel.
    pub fn rgb(self) -> Rgb {
        self.0
    }

    /// The natural logarithm of [`Absorption::to_color`], `-sqrt(sigma_a) D(beta_n)` per
    /// channel (D the polynomial of [`Absorption::from_color`]): finite for every absorption,
    /// also where the colour itself underflows.
    pub fn log_color(self, beta_n: AzimuthalRoughness) -> Rgb {
        self.0.map(|s| log_color_of_sigma_a(s, beta_n.get()))
    }

    /// The colour whose inversion [`Absorption::from_color`] at `beta_n` gives this absorption:
    /// Chiang et al. 2016's forward mapping (section 4.2),
    /// `c = exp(-sqrt(sigma_a) (5.969 - 0.215 b + 2.532 b^2 - 10.73 b^3 + 5.574 b^4 +
    /// 0.245 b^5))`, per linear RGB channel, in (0, 1]. A channel so dark that the exponential
    /// underflows (sigma_a above about 1.6e4 at beta_n = 0.3) gives the smallest positive
    /// `f64`, so the result is always a valid colour for [`Absorption::from_color`].
    pub fn to_color(self, beta_n: AzimuthalRoughness) -> Rgb {
        self.log_color(beta_n)
            .map(|l| l.exp().max(f64::MIN_POSITIVE))
    }
}

/// The denominator `D(b) = 5.969 - 0.215 b + 2.532 b^2 - 10.73 b^3 + 5.574 b^4 + 0.245 b^5` of
/// Chiang et al. 2016's colour mapping (section 4.2, eq. 9), `sqrt(sigma_a) = -ln(c) / D(b)`
/// for azimuthal roughness `b = beta_n`. Positive on [0, 1] (its minimum there is 3.38, at
/// b = 1).
fn color_denominator<R: Real>(b: R) -> R {
    R::c(5.969) - R::c(0.215) * b + R::c(2.532) * b * b - R::c(10.73) * powi(b, 3)
        + R::c(5.574) * powi(b, 4)
        + R::c(0.245) * powi(b, 5)
}

/// The smallest colour channel [`sigma_a_of_color`] inverts: a channel at or below 0 (which
/// would need infinite absorption) is taken as this (sigma_a about 100 at beta_n = 0.3).
pub const MIN_COLOR: f64 = 1e-30;

/// sigma_a of one linear RGB channel of colour `color` for azimuthal roughness `beta_n`:
/// Chiang et al. 2016's inversion (section 4.2, eq. 9; pbrt-v4 `SigmaAFromReflectance`),
/// `sigma_a = (ln c / D(beta_n))^2` with `D` the polynomial of [`Absorption::from_color`].
///
/// Domain: `color` in (0, 1] and `beta_n` in [1e-16, 1], which [`Absorption::from_color`]
/// validates. Shader code cannot reject a value, so here a channel above 1 counts as 1 (no
/// absorption) and one at or below 0 (or NaN) as [`MIN_COLOR`]; the result is then finite and
/// non-negative for every `beta_n` in [0, 1] (the caller clamps beta_n).
pub fn sigma_a_of_color<R: Real>(color: R, beta_n: R) -> R {
    let c = R::select(R::c(0.0).lt(color), color.min(R::c(1.0)), R::c(MIN_COLOR));
    (c.ln() / color_denominator(beta_n)).sqr()
}

/// `ln c = -sqrt(sigma_a) D(beta_n)`, the logarithm of the colour whose inversion
/// ([`sigma_a_of_color`]) gives `sigma_a` (Chiang et al. 2016, section 4.2, eq. 9, solved for
/// c), for `sigma_a >= 0`.
pub fn log_color_of_sigma_a<R: Real>(sigma_a: R, beta_n: R) -> R {
    -sigma_a.sqrt() * color_denominator(beta_n)
}

/// sigma_a per linear RGB channel of melanin concentrations:
/// `eu * EUMELANIN_SIGMA_A + pheo * PHEOMELANIN_SIGMA_A` (Chiang et al. 2016, section 4.2).
///
/// Domain: concentrations in [0, [`MAX_MELANIN`]], which [`Absorption::from_melanin`]
/// validates; shader code cannot reject a value, so here a negative concentration (or NaN)
/// counts as 0, and one so large that a channel overflows gives an infinite sigma_a (no light
/// passes through the fibre).
pub fn sigma_a_of_melanin<R: Real>(eumelanin: R, pheomelanin: R) -> [R; 3] {
    let (eu, ph) = (eumelanin.max(R::c(0.0)), pheomelanin.max(R::c(0.0)));
    core::array::from_fn(|c| eu * R::c(EUMELANIN_SIGMA_A[c]) + ph * R::c(PHEOMELANIN_SIGMA_A[c]))
}

/// How the length of the internal path is modelled.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum PathLength {
    /// The exact chord: `2 cos(gamma_t) / cos(theta_t)` radii (pbrt-v4, Chiang et al. 2016).
    Chord,
    /// Marschner et al. 2003's exponent `2 sigma_a (1 + cos 2 gamma_t) / cos(theta_t)`
    /// (their eq. 9 with sigma_a' = sigma_a / cos theta_t). It equals
    /// `4 cos^2(gamma_t) / cos(theta_t)`, which is not a path length: it is twice the chord at
    /// gamma_t = 0 and falls faster than the chord towards the fibre's edge. Kept because
    /// Gerard's exponents are derived from it.
    Marschner2003,
}

/// The length, in fibre radii, of one internal segment under the path model `path`, given
/// cos(gamma_t) and 1 / cos(theta_t) of the refracted ray: `2 cos(gamma_t) / cos(theta_t)`
/// for the chord, `4 cos^2(gamma_t) / cos(theta_t)` for Marschner's exponent (see
/// [`PathLength`]).
#[inline(always)]
pub fn segment_length<R: Real>(cos_gamma_t: R, inv_cos_theta_t: R, path: PathLength) -> R {
    match path {
        PathLength::Chord => R::c(2.0) * cos_gamma_t * inv_cos_theta_t,
        PathLength::Marschner2003 => R::c(4.0) * cos_gamma_t * cos_gamma_t * inv_cos_theta_t,
    }
}

/// Transmittance `exp(-sigma_a * length)` of one internal segment, `length` from
/// [`segment_length`], given cos(gamma_t) and cos(theta_t) of the refracted ray. `cos_theta_t`
/// is positive for every eta > 1 (it is at least sqrt(1 - 1/eta^2)).
pub fn segment_transmittance<R: Real>(
    sigma_a: R,
    cos_gamma_t: R,
    cos_theta_t: R,
    path: PathLength,
) -> R {
    (-sigma_a * segment_length(cos_gamma_t, R::c(1.0) / cos_theta_t, path)).exp()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn melanin_is_linear_and_validated() {
        let s = Absorption::from_melanin(1.3, 0.0).unwrap().rgb();
        assert!((s[0] - 1.3 * 0.419).abs() < 1e-15);
        assert!(Absorption::from_melanin(-0.1, 0.0).is_err());
        assert!(Absorption::from_melanin(0.0, f64::NAN).is_err());
    }

    #[test]
    fn color_inversion_round_trips_and_rejects_black() {
        let b = 0.3;
        let beta_n = AzimuthalRoughness::new(b).unwrap();
        let sa = Absorption::from_color([0.5, 0.25, 1.0], beta_n)
            .unwrap()
            .rgb();
        assert_eq!(sa[2], 0.0);
        let d = 5.969 - 0.215 * b + 2.532 * b * b - 10.73 * b * b * b
            + 5.574 * b.powi(4)
            + 0.245 * b.powi(5);
        // Inverting the fit: c = exp(-sqrt(sigma_a) * d).
        assert!(((-sa[0].sqrt() * d).exp() - 0.5).abs() < 1e-14);
        let e = Absorption::from_color([0.0, 0.5, 0.5], beta_n).unwrap_err();
        assert!(e.to_string().contains("(0, 1]"), "{e}");
    }

    #[test]
    fn chord_length_is_geometric() {
        // A ray through the centre (gamma_t = 0) in the normal plane crosses a diameter: 2 radii.
        assert!(
            (segment_transmittance(0.5_f64, 1.0, 1.0, PathLength::Chord) - (-1.0_f64).exp()).abs()
                < 1e-15
        );
        // Marschner's exponent at the centre is twice that.
        assert!(
            (segment_transmittance(0.5_f64, 1.0, 1.0, PathLength::Marschner2003)
                - (-2.0_f64).exp())
            .abs()
                < 1e-15
        );
        // Chord at offset: cos gamma_t = sqrt(1 - h'^2), the half-chord of a unit circle.
        let h: f64 = 0.6;
        let chord = 2.0 * (1.0 - h * h).sqrt();
        let t = segment_transmittance(1.0, (1.0 - h * h).sqrt(), 1.0, PathLength::Chord);
        assert!((t - (-chord).exp()).abs() < 1e-15);
    }
}
