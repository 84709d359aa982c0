//! Every longitudinal lobe integrates to 1 over its whole parameter range, by composite
//! Gauss-Legendre quadrature fine enough for the narrowest lobe (checked by refinement).

use hairmath::lobe::{deon_lobe, gaussian_lobe, hg_gerard_printed, HenyeyGreenstein};
use hairmath::quadrature::{gauss_legendre, integrate};
use std::f64::consts::{FRAC_PI_2, PI};

/// Integrates with `panels` panels and with twice as many, asserts the two agree to `tol`
/// (1e-9 for f64 integrands, far below the 1e-6 tested; f32 integrands are only smooth to their
/// rounding, so 1e-6 there), and returns the finer value.
fn converged_to(tol: f64, a: f64, b: f64, panels: usize, f: impl Fn(f64) -> f64) -> f64 {
    let rule = gauss_legendre(16);
    let coarse = integrate(&rule, panels, a, b, &f);
    let fine = integrate(&rule, 2 * panels, a, b, &f);
    assert!(
        (coarse - fine).abs() < tol,
        "quadrature not converged: {coarse} vs {fine}"
    );
    fine
}

fn converged(a: f64, b: f64, panels: usize, f: impl Fn(f64) -> f64) -> f64 {
    converged_to(1e-9, a, b, panels, f)
}

#[test]
fn deon_lobe_is_normalised_from_variance_1e_4_to_100() {
    for &v in &[1e-4, 1e-3, 0.0065, 0.08, 0.3, 1.0, 10.0, 100.0] {
        for &theta_o in &[0.0_f64, 0.4, -1.0, 1.5, FRAC_PI_2] {
            let (so, co) = (theta_o.sin(), theta_o.cos());
            let m = converged(-FRAC_PI_2, FRAC_PI_2, 2048, |t: f64| {
                deon_lobe(v, t.sin(), t.cos(), so, co) * t.cos()
            });
            assert!((m - 1.0).abs() < 1e-6, "v {v} theta_o {theta_o}: {m}");
            // Single precision: the same integral of the f32 lobe.
            let m32 = converged_to(1e-6, -FRAC_PI_2, FRAC_PI_2, 2048, |t: f64| {
                deon_lobe(
                    v as f32,
                    t.sin() as f32,
                    t.cos() as f32,
                    so as f32,
                    co as f32,
                ) as f64
                    * t.cos()
            });
            assert!(
                (m32 - 1.0).abs() < 2e-5,
                "f32 v {v} theta_o {theta_o}: {m32}"
            );
        }
    }
}

#[test]
fn gaussian_lobe_is_normalised_on_the_line() {
    for &beta in &[0.005, 0.05, 0.17, 0.5, 1.0] {
        let m = converged(-12.0 * beta, 12.0 * beta, 64, |x| gaussian_lobe(beta, x));
        assert!((m - 1.0).abs() < 1e-6, "beta {beta}: {m}");
    }
}

#[test]
fn henyey_greenstein_lobe_is_normalised_on_the_circle() {
    for &g in &[-0.95, -0.3, 0.0, 0.3, 0.578, 0.752, 0.865, 0.99] {
        let lobe = HenyeyGreenstein::new(g).unwrap();
        let m = converged(-PI, PI, 1024, |t: f64| lobe.eval(t.cos()));
        assert!((m - 1.0).abs() < 1e-6, "g {g}: {m}");
    }
}

/// Gerard's printed lobe (with 1/(4 pi)) is normalised over the sphere, not over the angle it
/// is applied to: its integral over theta in [-pi, pi] is E(k) / (pi (1 - g)), 1.32 at g = 0.752.
#[test]
fn gerard_printed_hg_is_not_a_unit_lobe_in_one_angle() {
    let m = converged(-PI, PI, 1024, |t: f64| hg_gerard_printed(0.752, t.cos()));
    assert!((m - 1.32).abs() < 0.01, "{m}");
    // Over the sphere (theta the angle from the axis) it is normalised.
    let sphere = converged(0.0, PI, 1024, |t: f64| {
        2.0 * PI * t.sin() * hg_gerard_printed(0.752, t.cos())
    });
    assert!((sphere - 1.0).abs() < 1e-9, "{sphere}");
}
