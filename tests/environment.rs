//! The SH environment measure (`hairmath::diagnostics::ShEnvironment`): its band-0 transfer is
//! the albedo the furnace computes, the sum over a band of the squared transfers does not
//! depend on the viewer's azimuth (the reduction of the module documentation, checked against
//! transfers integrated here at other azimuths), E_env is 0 for the reference and 1 for
//! nothing, and the default rule has converged (against a rule twice as fine in every
//! direction).

use hairmath::bcsdf::{Bcsdf, ChiangFarField, FarFieldRule, Query};
use hairmath::diagnostics::{albedo, EnvironmentRule, ShEnvironment};
use hairmath::geometry::local_direction;
use hairmath::models::{
    Attenuation, Azimuthal, ComposedHair, Composition, Constants, LobeFactors, LobeTableSize,
    Longitudinal, MarschnerTableSize,
};
use hairmath::params::HairParams;
use hairmath::quadrature::{gauss_legendre, SphereRule};
use hairmath::sh::eval_sh_f64;

fn reference() -> ChiangFarField<f64> {
    let rule = FarFieldRule::gauss_legendre(64).unwrap();
    ChiangFarField::with_rule(&HairParams::default(), &rule)
}

/// A cheap composition: R and TT by Karis' factors, TRT and the residual dropped.
fn cheap() -> ComposedHair<f64> {
    let sine = |azimuthal| {
        Some(LobeFactors {
            longitudinal: Longitudinal::SineGaussian,
            azimuthal,
        })
    };
    let composition = Composition {
        r: sine(Azimuthal::KarisReflection),
        tt: sine(Azimuthal::Separable {
            distribution: hairmath::models::Distribution::Karis(Constants::Refit),
            attenuation: Attenuation::Offset(Constants::Refit),
        }),
        trt: None,
        residual: false,
        far_field_nodes: 1,
        table: LobeTableSize::OFFERED[0],
        marschner_table: MarschnerTableSize::OFFERED[0],
    };
    ComposedHair::new(&HairParams::default(), composition).unwrap()
}

#[test]
fn the_band_0_transfer_is_the_albedo_times_y00() {
    let rule = EnvironmentRule {
        viewers: 5,
        ..EnvironmentRule::default()
    };
    let environment = ShEnvironment::new(0, rule).unwrap();
    let model = reference();
    let transfer = environment.transfer(&model);
    assert_eq!(transfer.len(), 5 * 3);
    let sphere = SphereRule::new(rule.theta_panels, rule.order, rule.azimuths);
    let y00 = 0.5 / std::f64::consts::PI.sqrt();
    let half_pi = std::f64::consts::FRAC_PI_2;
    for (j, (x, w)) in gauss_legendre(5).into_iter().enumerate() {
        let theta = half_pi * x;
        let wo = local_direction(theta.sin(), theta.cos(), 0.0);
        let rho = albedo(&model, &sphere, wo, 0.0);
        // The viewers' rule: 2 pi cos(theta_o) d theta_o, Gauss-Legendre in theta_o.
        let root = (std::f64::consts::TAU * half_pi * w * theta.cos()).sqrt();
        for c in 0..3 {
            let want = root * y00 * rho[c];
            let got = transfer[3 * j + c];
            assert!((got - want).abs() <= 1e-12 * want.abs(), "{got} vs {want}");
        }
    }
}

/// `sum_lm T_lm(wo)^2` at a viewer of azimuth `phi_o`, integrated here directly.
fn band_energy(model: &dyn Bcsdf<f64>, lmax: usize, sin_o: f64, phi_o: f64) -> [f64; 3] {
    let sphere = SphereRule::new(16, 4, 48);
    let wo = local_direction(sin_o, (1.0 - sin_o * sin_o).sqrt(), phi_o);
    let n = (lmax + 1) * (lmax + 1);
    let mut t = vec![[0.0; 3]; n];
    for &(wi, weight) in &sphere.nodes {
        let s = model.eval(&Query::far(wi, wo));
        let y = eval_sh_f64(lmax, glam::DVec3::new(wi.x, wi.y, wi.z)).unwrap();
        for (tk, yk) in t.iter_mut().zip(&y) {
            for c in 0..3 {
                tk[c] += weight * yk * s[c];
            }
        }
    }
    std::array::from_fn(|c| t.iter().map(|tk| tk[c] * tk[c]).sum())
}

#[test]
fn a_bands_transfer_energy_does_not_depend_on_the_viewers_azimuth() {
    let model = reference();
    for sin_o in [-0.7, 0.1, 0.9] {
        let at_zero = band_energy(&model, 2, sin_o, 0.0);
        for phi_o in [0.7, 2.0, -2.9] {
            let rotated = band_energy(&model, 2, sin_o, phi_o);
            for c in 0..3 {
                let (a, b) = (at_zero[c], rotated[c]);
                // The azimuthal rule is not rotated with the viewer: agreement to its error.
                assert!(
                    (a - b).abs() <= 1e-6 * a,
                    "sin_o {sin_o}, phi_o {phi_o}: {a} vs {b}"
                );
            }
        }
    }
}

#[test]
fn the_reference_has_no_error_and_nothing_has_all_of_it() {
    let environment = ShEnvironment::new(2, EnvironmentRule::default()).unwrap();
    let r = reference();
    let t = environment.transfer(&r);
    assert_eq!(environment.relative_error(&r, &t), 0.0);
    let nothing = Composition {
        r: None,
        tt: None,
        trt: None,
        residual: false,
        far_field_nodes: 1,
        table: LobeTableSize::OFFERED[0],
        marschner_table: MarschnerTableSize::OFFERED[0],
    };
    let zero = ComposedHair::new(&HairParams::default(), nothing).unwrap();
    assert_eq!(environment.relative_error(&zero, &t), 1.0);
    // The lobes' transfers add up to the model's.
    let lobes = environment.lobe_transfers(&r);
    let largest = t.iter().fold(0.0_f64, |m, x| m.max(x.abs()));
    for (k, total) in t.iter().enumerate() {
        let sum: f64 = lobes.iter().map(|l| l[k]).sum();
        assert!((sum - total).abs() <= 1e-12 * largest, "{sum} vs {total}");
    }
}

#[test]
fn the_default_rule_has_converged_to_two_per_mille() {
    let finer = EnvironmentRule {
        theta_panels: 32,
        order: 4,
        azimuths: 96,
        viewers: 32,
    };
    for lmax in [0, 2, 8] {
        let error = |rule| {
            let environment = ShEnvironment::new(lmax, rule).unwrap();
            environment.relative_error(&cheap(), &environment.transfer(&reference()))
        };
        let (coarse, fine) = (error(EnvironmentRule::default()), error(finer));
        eprintln!("lmax {lmax}: E_env {coarse:.5} (default rule), {fine:.5} (finer rule)");
        assert!(
            (coarse - fine).abs() <= 2e-3 * fine,
            "lmax {lmax}: {coarse} vs {fine}"
        );
    }
}

#[test]
fn invalid_rules_and_bands_are_errors() {
    assert!(ShEnvironment::new(9, EnvironmentRule::default()).is_err());
    let empty = EnvironmentRule {
        viewers: 0,
        ..EnvironmentRule::default()
    };
    let error = ShEnvironment::new(2, empty).unwrap_err().to_string();
    assert!(error.contains("viewers"), "{error}");
}

#[test]
fn the_relative_norm_is_never_nan() {
    use hairmath::diagnostics::relative_norm;
    assert_eq!(relative_norm(&[3.0, 4.0], &[0.0, 0.0]), f64::INFINITY);
    assert_eq!(relative_norm(&[0.0, 0.0], &[0.0, 0.0]), 0.0);
    assert_eq!(relative_norm(&[f64::NAN, 0.0], &[1.0, 0.0]), f64::INFINITY);
    assert_eq!(relative_norm(&[f64::INFINITY], &[1.0]), f64::INFINITY);
    assert_eq!(relative_norm(&[1.0, 1.0], &[0.0, 1.0]), 1.0);
}
