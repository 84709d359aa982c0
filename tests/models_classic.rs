//! The classic real-time models (`hairmath::models`): Kajiya-Kay as the survey seed writes it,
//! its two-cone TressFX form and Scheuermann's shader as the blog seed lists it.
//!
//! - Against independent evaluations of the published formulas: the survey's
//!   `S_M = k_d + k_s cos^n(theta_o + theta_i) / cos theta_i` from the angles (times cos theta_i,
//!   the crate's contract), hand-computed values, and the blog's GLSL rewritten with plain
//!   vectors; grazing directions, wi = wo, wi = -wo, phi = 0 and pi, directions along the
//!   tangent.
//! - proptest over every input's domain and all directions: finite and non-negative, in `f64`
//!   and `f32`, and `eval` the sum of `eval_lobes`.
//! - The mapping from the physical hair: valid for every hair, the cones and lobes placed where
//!   the reference puts R and TRT, and the mapped terms carrying the reference's lobe energies.
//! - Validation (typed errors naming the input), the registry and the command line.
//! - The errata of the two seeds (README).

use hairmath::bcsdf::{
    longitudinal_variance, Bcsdf, ChiangFarField, FarFieldRule, FromInputs, InputKind, InputValue,
    InputValues, Model, Query,
};
use hairmath::diagnostics::{lobe_energies, viewing_direction};
use hairmath::geometry::V3;
use hairmath::models::{
    Approximation, KajiyaKay, KajiyaKayParams, Scheuermann, ScheuermannParams, StrandLobe, TressFx,
    TressFxCone, TressFxParams,
};
use hairmath::params::{HairParams, HairValues};
use hairmath::quadrature::SphereRule;
use hairmath::registry::find_model;
use hairmath::ParamError;
use proptest::prelude::*;
use std::f64::consts::{FRAC_PI_2, PI};
use std::io::Write;
use std::process::{Command, Stdio};

/// The unit direction at inclination theta (from the normal plane) and azimuth phi.
fn dir(theta: f64, phi: f64) -> V3<f64> {
    V3::new(
        theta.sin(),
        theta.cos() * phi.cos(),
        theta.cos() * phi.sin(),
    )
}

fn neg(v: V3<f64>) -> V3<f64> {
    V3::new(-v.x, -v.y, -v.z)
}

fn close(a: f64, b: f64, tol: f64) -> bool {
    (a - b).abs() <= tol * (1.0 + a.abs().max(b.abs()))
}

fn assert_close(a: [f64; 3], b: [f64; 3], tol: f64, what: &str) {
    for c in 0..3 {
        assert!(close(a[c], b[c], tol), "{what}: {a:?} against {b:?}");
    }
}

/// Relative agreement per channel (values of any size).
fn assert_relative(a: [f64; 3], b: [f64; 3], tol: f64, what: &str) {
    for c in 0..3 {
        let ok = (a[c] - b[c]).abs() <= tol * a[c].abs().max(b[c].abs()) + 1e-15;
        assert!(ok, "{what}: {a:?} against {b:?}");
    }
}

fn eval(m: &impl Bcsdf<f64>, wi: V3<f64>, wo: V3<f64>) -> [f64; 3] {
    m.eval(&Query::far(wi, wo))
}

/// The hard direction pairs: grazing both ways, wi = wo, wi = -wo, phi = 0 and pi, along the
/// tangent (+-X), and a few generic pairs.
fn hard_pairs() -> Vec<(V3<f64>, V3<f64>)> {
    let x = V3::new(1.0, 0.0, 0.0);
    let mut pairs = vec![
        (x, x),
        (x, neg(x)),
        (neg(x), x),
        (x, dir(0.3, 1.0)),
        (dir(-0.4, 2.0), x),
        (dir(FRAC_PI_2, 0.0), dir(-FRAC_PI_2, 0.0)),
        (dir(FRAC_PI_2 - 1e-4, 0.3), dir(-1.2, 0.3)),
    ];
    for &(ti, to) in &[
        (0.0, 0.0),
        (0.5, -0.5),
        (0.3, 0.7),
        (-1.2, 0.2),
        (1.5, -1.5),
    ] {
        for &phi in &[0.0, PI, -PI, 1.3] {
            pairs.push((dir(ti, 0.4), dir(to, 0.4 + phi)));
        }
        pairs.push((dir(ti, 0.4), dir(ti, 0.4)));
        pairs.push((dir(ti, 0.4), neg(dir(ti, 0.4))));
    }
    pairs
}

// ---------------------------------------------------------------------------------------------
// Kajiya-Kay and TressFX against the survey's formula.

/// The survey's Kajiya-Kay, `S_M = k_d + k_s cos^n(theta_o + theta_i) / cos theta_i`, from the
/// angles, as printed (Marschner's convention: radiance `int S_M L_i cos theta_i dw_i`).
fn survey_kajiya_kay(kd: f64, ks: f64, n: f64, theta_i: f64, theta_o: f64) -> f64 {
    kd + ks * (theta_o + theta_i).cos().powf(n) / theta_i.cos()
}

fn kajiya_kay(kd: f64, ks: f64, exponent: f64) -> KajiyaKay<f64> {
    KajiyaKay::new(&KajiyaKayParams {
        kd: [kd; 3],
        ks: [ks; 3],
        exponent,
    })
    .unwrap()
}

#[test]
fn kajiya_kay_is_the_survey_formula_times_cos_theta_i() {
    for &(kd, ks, n) in &[
        (0.1, 0.5, 2.0),
        (0.3, 0.05, 11.8),
        (0.0, 1.0, 0.7),
        (0.2, 0.0, 3.0),
    ] {
        let model = kajiya_kay(kd, ks, n);
        for &ti in &[-1.4_f64, -0.6, 0.0, 0.2, 0.9, 1.45] {
            for &to in &[-1.5, -0.9, -0.2, 0.0, 0.4, 1.1] {
                if (ti + to).abs() >= FRAC_PI_2 {
                    continue; // outside the cone's quarter turn: see the erratum test
                }
                let want = survey_kajiya_kay(kd, ks, n, ti, to) * ti.cos();
                // No azimuthal dependence: phi = 0, pi and any other.
                for &phi in &[0.0, PI, -PI, 2.1] {
                    let s = eval(&model, dir(ti, 0.7), dir(to, 0.7 + phi));
                    assert_close(s, [want; 3], 1e-13, &format!("theta {ti}, {to}, phi {phi}"));
                }
            }
        }
    }
}

#[test]
fn kajiya_kay_hand_computed_values() {
    // k_d = 0.1, k_s = 0.5, n = 2: S = 0.1 cos theta_i + 0.5 max(cos(theta_i + theta_o), 0)^2.
    let m = kajiya_kay(0.1, 0.5, 2.0);
    let d30 = 30f64.to_radians();
    let x = V3::new(1.0, 0.0, 0.0);
    let cos30 = 0.75f64.sqrt();
    let cases = [
        // The mirror cone: 0.1 cos 30 + 0.5 = 0.5866025.
        (dir(d30, 0.0), dir(-d30, PI), 0.1 * cos30 + 0.5),
        // wi = wo at 30 degrees: 0.1 cos 30 + 0.5 cos^2 60 = 0.2116025.
        (dir(d30, 1.0), dir(d30, 1.0), 0.1 * cos30 + 0.125),
        // wi = -wo: theta_o = -theta_i, on the mirror cone.
        (dir(d30, 1.0), neg(dir(d30, 1.0)), 0.1 * cos30 + 0.5),
        // wi along the tangent (grazing): no diffuse, 0.5 cos^2(90 - 60) = 0.375.
        (x, dir(-60f64.to_radians(), 0.7), 0.375),
        // Both along +X: cos 180 < 0, clamped: 0. Opposite: on the cone, 0.5.
        (x, x, 0.0),
        (x, neg(x), 0.5),
    ];
    for (wi, wo, want) in cases {
        assert_close(eval(&m, wi, wo), [want; 3], 1e-14, "hand value");
    }
}

/// TressFX from the angles: `k_d cos theta_i + k_1 max(cos(theta_i + theta_o - d_1), 0)^n_1
/// + k_2 max(cos(theta_i + theta_o + d_2), 0)^n_2`.
fn two_cones(p: &TressFxParams, theta_i: f64, theta_o: f64) -> [f64; 3] {
    let cone = |c: &TressFxCone, x: f64| x.cos().max(0.0).powf(c.exponent);
    let sum = theta_i + theta_o;
    let (a, b) = (
        cone(&p.primary, sum - p.primary.shift),
        cone(&p.secondary, sum + p.secondary.shift),
    );
    core::array::from_fn(|c| {
        p.kd[c] * theta_i.cos() + p.primary.weight[c] * a + p.secondary.weight[c] * b
    })
}

fn tressfx_example() -> TressFxParams {
    TressFxParams {
        kd: [0.05, 0.03, 0.02],
        primary: TressFxCone {
            weight: [0.3; 3],
            exponent: 12.0,
            shift: 4f64.to_radians(),
        },
        secondary: TressFxCone {
            weight: [0.2, 0.1, 0.05],
            exponent: 3.0,
            shift: 8f64.to_radians(),
        },
    }
}

#[test]
fn tressfx_is_two_shifted_kajiya_kay_cones() {
    let params = tressfx_example();
    let model = TressFx::new(&params).unwrap();
    for &ti in &[-FRAC_PI_2, -1.0, -0.1, 0.0, 0.07, 0.6, FRAC_PI_2] {
        for &to in &[-FRAC_PI_2, -0.8, 0.0, 0.3, 1.2, FRAC_PI_2] {
            for &phi in &[0.0, PI, 2.0] {
                let s = eval(&model, dir(ti, 0.1), dir(to, 0.1 + phi));
                assert_close(s, two_cones(&params, ti, to), 1e-13, "two cones");
            }
        }
    }
    // The primary peaks at theta_i + theta_o = +4 degrees, the secondary at -8 degrees.
    let lobes = |ti: f64| model.eval_lobes(&Query::far(dir(ti, 0.0), dir(0.0, 0.0)));
    let peak = |lobe: usize| {
        (-900..=900)
            .map(|k| (k as f64 * 0.01).to_radians())
            .max_by(|a, b| lobes(*a)[lobe][0].total_cmp(&lobes(*b)[lobe][0]))
            .unwrap()
            .to_degrees()
    };
    assert!((peak(1) - 4.0).abs() < 0.006 && (peak(2) + 8.0).abs() < 0.006);
    // Grazing wi: finite (no 1 / cos theta_i anywhere).
    let s = eval(&model, V3::new(1.0, 0.0, 0.0), dir(-FRAC_PI_2 + 0.04, 0.0));
    assert!(s.iter().all(|v| v.is_finite() && *v > 0.0), "{s:?}");
}

// ---------------------------------------------------------------------------------------------
// Scheuermann against the blog's listing.

type Vec3 = [f64; 3];

fn dot(a: Vec3, b: Vec3) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}
fn add(a: Vec3, b: Vec3) -> Vec3 {
    [a[0] + b[0], a[1] + b[1], a[2] + b[2]]
}
fn mul(a: Vec3, s: f64) -> Vec3 {
    [a[0] * s, a[1] * s, a[2] * s]
}
fn normalize(a: Vec3) -> Vec3 {
    mul(a, 1.0 / dot(a, a).sqrt())
}
/// GLSL's smoothstep.
fn smoothstep(e0: f64, e1: f64, x: f64) -> f64 {
    let t = ((x - e0) / (e1 - e0)).clamp(0.0, 1.0);
    t * t * (3.0 - 2.0 * t)
}
/// GLSL's mix.
fn mix(a: f64, b: f64, x: f64) -> f64 {
    a * (1.0 - x) + b * x
}

/// The blog's shader (`calcHairColor`) with T = +X, N the viewer's direction across the fibre
/// (or `normal` when given), H = normalize(L + V), the textures as numbers and the light, base
/// colour and AO white.
fn blog_shader(p: &ScheuermannParams, l: Vec3, v: Vec3, normal: Option<Vec3>) -> [f64; 3] {
    let t = [1.0, 0.0, 0.0];
    let n = normal.unwrap_or_else(|| normalize(add(v, mul(t, -dot(t, v)))));
    let shift_tangent = |shift: f64| normalize(add(t, mul(n, shift)));
    let base_shift_amount = p.shift_texture - 0.5;
    let t1 = shift_tangent(p.primary.tangent_shift + base_shift_amount);
    let t2 = shift_tangent(p.secondary.tangent_shift + base_shift_amount);
    let h = normalize(add(l, v));
    let strand = |t: Vec3, exponent: f64| {
        let t_o_h = dot(t, h);
        smoothstep(-1.0, 0.0, t_o_h) * (1.0 - t_o_h * t_o_h).sqrt().powf(exponent)
    };
    let diffuse = mix(0.25, 1.0, dot(n, l)).clamp(0.0, 1.0);
    let (s1, s2) = (
        strand(t1, p.primary.exponent),
        strand(t2, p.secondary.exponent),
    );
    core::array::from_fn(|c| {
        diffuse * p.kd[c] + p.primary.weight[c] * s1 + p.noise_mask * p.secondary.weight[c] * s2
    })
}

fn v(w: V3<f64>) -> Vec3 {
    [w.x, w.y, w.z]
}

fn scheuermann_examples() -> Vec<ScheuermannParams> {
    let mapped = Scheuermann::mapped_inputs(&HairParams::default());
    let rgb = |name: &str| match mapped.get(name) {
        Some(InputValue::Rgb(c)) => c,
        other => panic!("{name}: {other:?}"),
    };
    let num = |name: &str| match mapped.get(name) {
        Some(InputValue::Number(x)) => x,
        other => panic!("{name}: {other:?}"),
    };
    let lobe = |which: &str| StrandLobe {
        weight: rgb(&format!("ks_{which}")),
        exponent: num(&format!("exponent_{which}")),
        tangent_shift: num(&format!("tangent_shift_{which}")),
    };
    vec![
        ScheuermannParams::BLOG,
        ScheuermannParams {
            kd: rgb("kd"),
            primary: lobe("primary"),
            secondary: lobe("secondary"),
            shift_texture: 0.5,
            noise_mask: 1.0,
        },
        ScheuermannParams {
            kd: [0.2, 0.1, 0.0],
            primary: StrandLobe {
                weight: [0.7, 0.6, 0.5],
                exponent: 80.0,
                tangent_shift: -0.1,
            },
            secondary: StrandLobe {
                weight: [0.3, 0.2, 0.1],
                exponent: 20.0,
                tangent_shift: 0.25,
            },
            shift_texture: 0.8,
            noise_mask: 0.4,
        },
    ]
}

#[test]
fn scheuermann_is_the_blog_shader() {
    for params in scheuermann_examples() {
        let model = Scheuermann::new(&params).unwrap();
        for (wi, wo) in hard_pairs() {
            let across = wo.y.hypot(wo.z);
            let opposite = add(v(wi), v(wo)) == [0.0; 3];
            let s = eval(&model, wi, wo);
            assert!(s.iter().all(|x| x.is_finite() && *x >= 0.0), "{s:?}");
            if opposite {
                // wi = -wo: H = 0, t.H = 0, each lobe at its maximum (module docs).
                let n = if across > 0.0 {
                    [0.0, wo.y / across, wo.z / across]
                } else {
                    [0.0, 1.0, 0.0]
                };
                let diffuse = mix(0.25, 1.0, dot(n, v(wi))).clamp(0.0, 1.0);
                let want = core::array::from_fn(|c| {
                    diffuse * params.kd[c]
                        + params.primary.weight[c]
                        + params.noise_mask * params.secondary.weight[c]
                });
                assert_close(s, want, 1e-13, "wi = -wo");
            } else if across < 1e-12 {
                // wo along the tangent: the listing's normal is undefined; N = +Y is taken.
                let want = blog_shader(&params, v(wi), v(wo), Some([0.0, 1.0, 0.0]));
                assert_close(s, want, 1e-12, "wo along the tangent");
            } else {
                let want = blog_shader(&params, v(wi), v(wo), None);
                assert_close(s, want, 1e-12, &format!("{wi:?} {wo:?}"));
            }
        }
        // And on a grid of generic directions.
        for k in 0..400 {
            let (ti, to) = (
                -1.5 + 3.0 * ((k * 7) % 20) as f64 / 19.0,
                -1.5 + 3.0 * (k % 20) as f64 / 19.0,
            );
            let phi = -PI + 2.0 * PI * (k as f64 * 0.618_034).fract();
            let (wi, wo) = (dir(ti, 0.2 + phi), dir(to, 0.2));
            let want = blog_shader(&params, v(wi), v(wo), None);
            assert_close(eval(&model, wi, wo), want, 1e-12, "grid");
        }
    }
}

#[test]
fn scheuermann_hand_computed_values() {
    // kd = 1, lobes off: the scaled-and-biased Lambert term 0.25 + 0.75 N.L with N.L =
    // cos(theta_i) cos(phi).
    let diffuse_only = Scheuermann::new(&ScheuermannParams {
        kd: [1.0; 3],
        primary: StrandLobe {
            weight: [0.0; 3],
            exponent: 1.0,
            tangent_shift: 0.0,
        },
        secondary: StrandLobe {
            weight: [0.0; 3],
            exponent: 1.0,
            tangent_shift: 0.0,
        },
        shift_texture: 0.5,
        noise_mask: 1.0,
    })
    .unwrap();
    let wo = dir(0.3, 0.5);
    for (phi, theta_i, want) in [
        (0.0, 0.0, 1.0),                              // facing the light
        (FRAC_PI_2, 0.0, 0.25),                       // the terminator
        (PI, 0.0, 0.0),                               // facing away: clamped
        ((-1.0f64 / 3.0).acos(), 0.0, 0.0),           // N.L = -1/3: zero
        (0.0, 60f64.to_radians(), 0.25 + 0.75 * 0.5), // cos 60 = 0.5
    ] {
        let s = eval(&diffuse_only, dir(theta_i, 0.5 + phi), wo);
        assert!(
            (s[0] - want).abs() < 1e-12,
            "phi {phi}: {s:?} against {want}"
        );
    }
    // A lobe with exponent 2 and no shift: smoothstep(-1, 0, T.H) (1 - (T.H)^2). With wi and
    // wo in the normal plane at 90 degrees, H is across the fibre: T.H = 0, the lobe is 1.
    let lobe_only = Scheuermann::new(&ScheuermannParams {
        kd: [0.0; 3],
        primary: StrandLobe {
            weight: [1.0; 3],
            exponent: 2.0,
            tangent_shift: 0.0,
        },
        secondary: StrandLobe {
            weight: [0.0; 3],
            exponent: 2.0,
            tangent_shift: 0.0,
        },
        shift_texture: 0.5,
        noise_mask: 1.0,
    })
    .unwrap();
    assert!((eval(&lobe_only, dir(0.0, 0.0), dir(0.0, FRAC_PI_2))[0] - 1.0).abs() < 1e-15);
    // wi = wo at 30 degrees: H = wo, T.H = 0.5: smoothstep(0.5) = 1, 1 - 0.25 = 0.75.
    let w = dir(30f64.to_radians(), 1.0);
    assert!((eval(&lobe_only, w, w)[0] - 0.75).abs() < 1e-12);
    // H pointing to the root, T.H = -0.5: smoothstep = 0.5, so 0.5 * 0.75 = 0.375.
    let w = dir(-30f64.to_radians(), 1.0);
    assert!((eval(&lobe_only, w, w)[0] - 0.375).abs() < 1e-12);
}

// ---------------------------------------------------------------------------------------------
// Every input and direction: finite and non-negative.

fn weight() -> impl Strategy<Value = f64> {
    prop_oneof![Just(0.0), Just(1.0), Just(1e6), 0.0..=2.0_f64]
}
fn rgb() -> impl Strategy<Value = [f64; 3]> {
    [weight(), weight(), weight()]
}
fn exponent() -> impl Strategy<Value = f64> {
    prop_oneof![
        Just(1e-9),
        Just(0.49),
        Just(1.0),
        Just(1e6),
        1e-3..=200.0_f64
    ]
}
fn angle() -> impl Strategy<Value = f64> {
    prop_oneof![Just(0.0), Just(FRAC_PI_2), Just(-PI), Just(100.0), -PI..=PI]
}
fn tangent_shift() -> impl Strategy<Value = f64> {
    prop_oneof![
        Just(0.0),
        Just(-1.0),
        Just(1.5),
        Just(1e300),
        Just(-1e300),
        -5.0..=5.0_f64
    ]
}
fn unit() -> impl Strategy<Value = f64> {
    prop_oneof![Just(0.0), Just(1.0), 0.0..=1.0_f64]
}
/// A unit direction, grazing and along the tangent included.
fn direction() -> impl Strategy<Value = V3<f64>> {
    let theta = prop_oneof![
        Just(FRAC_PI_2),
        Just(-FRAC_PI_2),
        Just(0.0),
        -FRAC_PI_2..=FRAC_PI_2
    ];
    let phi = prop_oneof![Just(0.0), Just(PI), -PI..=PI];
    (theta, phi).prop_map(|(t, p)| dir(t, p))
}
/// wi and wo: independent, equal, opposite, or at relative azimuth 0 or pi.
fn pair() -> impl Strategy<Value = (V3<f64>, V3<f64>)> {
    (direction(), direction(), 0..5_u8, -FRAC_PI_2..=FRAC_PI_2).prop_map(|(a, b, k, t)| {
        let phi = a.z.atan2(a.y);
        match k {
            0 => (a, a),
            1 => (a, neg(a)),
            2 => (a, dir(t, phi)),
            3 => (a, dir(t, phi + PI)),
            _ => (a, b),
        }
    })
}

/// Finite and non-negative in `f64` and `f32`, and `eval` the sum of `eval_lobes`.
fn check_everywhere<M: Model>(model: &M, wi: V3<f64>, wo: V3<f64>) -> Result<(), TestCaseError> {
    let q = Query::far(wi, wo);
    let s = model.eval(&q);
    prop_assert!(s.iter().all(|x| x.is_finite() && *x >= 0.0), "{s:?}");
    let lobes = model.eval_lobes(&q);
    prop_assert_eq!(lobes.len(), model.lobe_names().len());
    for c in 0..3 {
        let sum: f64 = lobes.iter().map(|l| l[c]).sum();
        prop_assert!(
            (sum - s[c]).abs() <= 1e-12 * (1.0 + s[c]),
            "{sum} vs {}",
            s[c]
        );
    }
    let f32_model = model.instantiate::<f32>();
    let q32 = Query::far(
        V3::new(wi.x as f32, wi.y as f32, wi.z as f32),
        V3::new(wo.x as f32, wo.y as f32, wo.z as f32),
    );
    let s32 = f32_model.eval(&q32);
    prop_assert!(s32.iter().all(|x| x.is_finite() && *x >= 0.0), "{s32:?}");
    Ok(())
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(2000))]

    #[test]
    fn kajiya_kay_is_finite_and_non_negative(kd in rgb(), ks in rgb(), n in exponent(), (wi, wo) in pair()) {
        let model = KajiyaKay::new(&KajiyaKayParams { kd, ks, exponent: n }).unwrap();
        check_everywhere(&model, wi, wo)?;
    }

    #[test]
    fn tressfx_is_finite_and_non_negative(
        kd in rgb(), w1 in rgb(), w2 in rgb(), n1 in exponent(), n2 in exponent(),
        d1 in angle(), d2 in angle(), (wi, wo) in pair(),
    ) {
        let params = TressFxParams {
            kd,
            primary: TressFxCone { weight: w1, exponent: n1, shift: d1 },
            secondary: TressFxCone { weight: w2, exponent: n2, shift: d2 },
        };
        check_everywhere(&TressFx::new(&params).unwrap(), wi, wo)?;
    }

    #[test]
    fn scheuermann_is_finite_and_non_negative(
        kd in rgb(), w1 in rgb(), w2 in rgb(), e1 in exponent(), e2 in exponent(),
        s1 in tangent_shift(), s2 in tangent_shift(), texture in unit(), mask in unit(),
        (wi, wo) in pair(),
    ) {
        let params = ScheuermannParams {
            kd,
            primary: StrandLobe { weight: w1, exponent: e1, tangent_shift: s1 },
            secondary: StrandLobe { weight: w2, exponent: e2, tangent_shift: s2 },
            shift_texture: texture,
            noise_mask: mask,
        };
        check_everywhere(&Scheuermann::new(&params).unwrap(), wi, wo)?;
    }
}

// ---------------------------------------------------------------------------------------------
// The mapping from the physical parameters.

fn hair(beta_m: f64, alpha_deg: f64, eumelanin: f64) -> HairParams {
    let sigma_a = hairmath::absorption::Absorption::from_melanin(eumelanin, 0.0).unwrap();
    HairParams::try_from(HairValues {
        beta_m,
        beta_n: 0.3,
        alpha: alpha_deg.to_radians(),
        eta: 1.55,
        sigma_a: sigma_a.rgb(),
    })
    .unwrap()
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(48))]

    /// Every valid hair maps to valid inputs of every model, all present.
    #[test]
    fn every_hair_maps_to_valid_inputs(
        beta_m in prop_oneof![Just(hairmath::params::MIN_BETA), Just(1e-3), Just(1.0), 1e-3..=1.0_f64],
        beta_n in prop_oneof![Just(1e-3), Just(1.0), 1e-3..=1.0_f64],
        alpha in prop_oneof![Just(0.0), Just(FRAC_PI_2 - 1e-4), Just(1e-4 - FRAC_PI_2), Just(FRAC_PI_2 / 2.0), -1.5..=1.5_f64],
        eta in prop_oneof![Just(1.0001), Just(3.0), 1.0001..=3.0_f64],
        sigma_a in prop_oneof![Just(0.0), Just(50.0), 0.0..=10.0_f64],
    ) {
        let hair = HairParams::try_from(HairValues { beta_m, beta_n, alpha, eta, sigma_a: [sigma_a, 0.5 * sigma_a, 0.0] }).unwrap();
        fn all_present<M: Approximation>(hair: &HairParams) -> Result<(), TestCaseError> {
            let values = M::mapped_inputs(hair);
            for input in M::INPUTS {
                prop_assert!(values.get(input.name).is_some(), "{} missing", input.name);
            }
            prop_assert!(M::from_inputs(&values).is_ok(), "{:?}", M::from_inputs(&values).err());
            Ok(())
        }
        all_present::<KajiyaKay<f64>>(&hair)?;
        all_present::<TressFx<f64>>(&hair)?;
        all_present::<Scheuermann<f64>>(&hair)?;
    }
}

/// The theta_i (degrees, 0.05-degree steps) where lobe `lobe` of `model` peaks, for
/// theta_o = 0 and phi = 0.
fn peak_theta_i(model: &dyn Bcsdf<f64>, lobe: usize) -> f64 {
    let value = |k: i32| {
        let t = (k as f64 * 0.05).to_radians();
        model.eval_lobes(&Query::far(dir(t, 0.0), dir(0.0, 0.0)))[lobe][1]
    };
    let best = (-1200..=1200)
        .max_by(|a, b| value(*a).total_cmp(&value(*b)))
        .unwrap();
    best as f64 * 0.05
}

#[test]
fn mapped_lobes_sit_where_the_reference_puts_r_and_trt() {
    for alpha in [2.0, 6.0] {
        let hair = hair(0.3, alpha, 1.3);
        let reference =
            ChiangFarField::with_rule(&hair, &FarFieldRule::gauss_legendre(32).unwrap());
        let (r, trt) = (peak_theta_i(&reference, 0), peak_theta_i(&reference, 2));
        let tressfx = TressFx::from_inputs(&TressFx::mapped_inputs(&hair)).unwrap();
        let scheuermann = Scheuermann::from_inputs(&Scheuermann::mapped_inputs(&hair)).unwrap();
        println!(
            "alpha {alpha}: reference R {r}, TRT {trt}; TressFX {} {}; Scheuermann {} {}",
            peak_theta_i(&tressfx, 1),
            peak_theta_i(&tressfx, 2),
            peak_theta_i(&scheuermann, 1),
            peak_theta_i(&scheuermann, 2)
        );
        // The mapped cones peak exactly at 2 alpha and -4 alpha.
        for model in [&tressfx as &dyn Bcsdf<f64>, &scheuermann] {
            assert!((peak_theta_i(model, 1) - 2.0 * alpha).abs() < 0.06);
            assert!((peak_theta_i(model, 2) + 4.0 * alpha).abs() < 0.06);
        }
        // The reference's peaks are on the same sides, pushed further out by the lobes' width
        // (d'Eon's lobe is not symmetric about the tilted cone; TRT's is four times wider).
        assert!(r > 2.0 * alpha && r < 1.1 * 2.0 * alpha, "R at {r}");
        assert!(
            trt < -4.0 * alpha && trt > -2.0 * 4.0 * alpha,
            "TRT at {trt}"
        );
    }
}

#[test]
fn mapped_terms_carry_the_reference_lobe_energies() {
    // Side-on view, theta_o = 0: each mapped term's albedo is the energy of the reference lobes
    // it stands for, measured here by the same sphere rule on both models (independent of the
    // mapping's own quadratures).
    let sphere = SphereRule::new(96, 8, 256);
    let wo = viewing_direction(0.0);
    let offsets = FarFieldRule::gauss_legendre(64).unwrap();
    for (beta_m, eumelanin) in [(0.3, 1.3), (0.15, 0.3), (0.6, 8.0)] {
        let hair = hair(beta_m, 2.0, eumelanin);
        let reference = ChiangFarField::with_rule(&hair, &offsets);
        let e = lobe_energies(&reference, &sphere, wo, &offsets);
        let [r, tt, trt, residual] = [0, 1, 2, 3].map(|p| e.lobes[p]);
        let sum = |a: [f64; 3], b: [f64; 3]| -> [f64; 3] { core::array::from_fn(|c| a[c] + b[c]) };
        let kk = KajiyaKay::from_inputs(&KajiyaKay::mapped_inputs(&hair)).unwrap();
        let kk_e = lobe_energies(&kk, &sphere, wo, &offsets);
        let tressfx = TressFx::from_inputs(&TressFx::mapped_inputs(&hair)).unwrap();
        let tf_e = lobe_energies(&tressfx, &sphere, wo, &offsets);
        let sch = Scheuermann::from_inputs(&Scheuermann::mapped_inputs(&hair)).unwrap();
        let sch_e = lobe_energies(&sch, &sphere, wo, &offsets);
        let tol = 2e-3;
        let label = format!("beta_m {beta_m}, eumelanin {eumelanin}");
        println!("{label}: reference {:?}", e.lobes);
        println!(
            "  kajiya-kay {:?}\n  tressfx {:?}\n  scheuermann {:?}",
            kk_e.lobes, tf_e.lobes, sch_e.lobes
        );
        assert_relative(kk_e.lobes[0], sum(tt, residual), tol, &label);
        assert_relative(kk_e.lobes[1], sum(r, trt), tol, &label);
        assert_relative(tf_e.lobes[0], sum(tt, residual), tol, &label);
        // Scheuermann's diffuse faces the light: it carries the residual, not TT.
        assert_relative(sch_e.lobes[0], residual, tol, &label);
        for m in [&tf_e, &sch_e] {
            assert_relative(m.lobes[1], r, tol, &label);
            assert_relative(m.lobes[2], trt, tol, &label);
        }
    }
}

#[test]
fn mapped_exponents_match_the_reference_lobe_widths() {
    let hair = hair(0.3, 2.0, 1.3);
    let v0 = longitudinal_variance(0.3);
    let number = |values: &InputValues, name: &str| match values.get(name) {
        Some(InputValue::Number(x)) => x,
        other => panic!("{name}: {other:?}"),
    };
    let kk = KajiyaKay::mapped_inputs(&hair);
    assert!(close(number(&kk, "exponent"), 1.0 / v0, 1e-15));
    let tf = TressFx::mapped_inputs(&hair);
    assert!(close(number(&tf, "exponent_primary"), 1.0 / v0, 1e-15));
    assert!(close(number(&tf, "exponent_secondary"), 0.25 / v0, 1e-15));
    assert!(close(
        number(&tf, "shift_primary"),
        4f64.to_radians(),
        1e-15
    ));
    assert!(close(
        number(&tf, "shift_secondary"),
        8f64.to_radians(),
        1e-15
    ));
    let sch = Scheuermann::mapped_inputs(&hair);
    assert!(close(number(&sch, "exponent_primary"), 4.0 / v0, 1e-15));
    assert!(close(number(&sch, "exponent_secondary"), 1.0 / v0, 1e-15));
    assert!(close(
        number(&sch, "tangent_shift_primary"),
        -(2f64.to_radians().tan()),
        1e-15
    ));
    assert!(close(
        number(&sch, "tangent_shift_secondary"),
        4f64.to_radians().tan(),
        1e-15
    ));
    // Near its peak the cone's cos^n is the Gaussian of d'Eon's lobe to second order: one
    // standard deviation out, their logarithms differ by x^2 / 4 (relative), x^2 = v_0.
    let x = v0.sqrt();
    let cone = (1.0 / v0) * x.cos().ln();
    let deon = -(1.0 - x.cos()) / v0;
    let relative = (cone - deon).abs() / deon.abs();
    assert!(relative < 0.3 * v0, "{cone} vs {deon}");
}

// ---------------------------------------------------------------------------------------------
// Validation, registry, command line.

fn out_of_range(e: ParamError) -> &'static str {
    match e {
        ParamError::OutOfRange { name, .. } => name,
        other => panic!("{other:?}"),
    }
}

#[test]
fn invalid_inputs_are_typed_errors_naming_the_input() {
    let kk = |kd: [f64; 3], exponent: f64| {
        KajiyaKay::new(&KajiyaKayParams {
            kd,
            ks: [0.1; 3],
            exponent,
        })
    };
    assert_eq!(out_of_range(kk([0.1, -0.1, 0.1], 2.0).unwrap_err()), "kd");
    assert_eq!(out_of_range(kk([f64::NAN; 3], 2.0).unwrap_err()), "kd");
    assert_eq!(out_of_range(kk([2e6; 3], 2.0).unwrap_err()), "kd");
    assert_eq!(out_of_range(kk([0.1; 3], 0.0).unwrap_err()), "exponent");
    assert_eq!(
        out_of_range(kk([0.1; 3], f64::INFINITY).unwrap_err()),
        "exponent"
    );
    let e = kk([0.1; 3], -1.0).unwrap_err().to_string();
    assert_eq!(
        e,
        "exponent = -1 is not allowed: exponents must be in (0, 1e6]"
    );

    let mut tf = tressfx_example();
    tf.primary.shift = f64::NAN;
    assert_eq!(
        out_of_range(TressFx::new(&tf).unwrap_err()),
        "shift_primary"
    );
    let mut tf = tressfx_example();
    tf.secondary.exponent = 0.0;
    assert_eq!(
        out_of_range(TressFx::new(&tf).unwrap_err()),
        "exponent_secondary"
    );

    let mut sch = ScheuermannParams::BLOG;
    sch.noise_mask = 1.5;
    assert_eq!(
        out_of_range(Scheuermann::new(&sch).unwrap_err()),
        "noise_mask"
    );
    let mut sch = ScheuermannParams::BLOG;
    sch.shift_texture = -0.1;
    assert_eq!(
        out_of_range(Scheuermann::new(&sch).unwrap_err()),
        "shift_texture"
    );
    let mut sch = ScheuermannParams::BLOG;
    sch.secondary.tangent_shift = f64::INFINITY;
    assert_eq!(
        out_of_range(Scheuermann::new(&sch).unwrap_err()),
        "tangent_shift_secondary"
    );
    let mut sch = ScheuermannParams::BLOG;
    sch.primary.weight = [0.0, -1.0, 0.0];
    assert_eq!(
        out_of_range(Scheuermann::new(&sch).unwrap_err()),
        "ks_primary"
    );

    // A missing input.
    let mut values = InputValues::new();
    values.set("kd", InputValue::Rgb([0.1; 3]));
    assert_eq!(
        KajiyaKay::from_inputs(&values).unwrap_err(),
        ParamError::Missing { name: "ks" }
    );
}

#[test]
fn the_three_models_are_registered_approximations() {
    for name in ["kajiya-kay", "tressfx", "scheuermann"] {
        let entry = find_model(name).unwrap_or_else(|| panic!("{name} not registered"));
        let approximation = entry.approximation.expect("an approximation");
        for fitted in approximation.fitted_inputs {
            let input = entry.inputs.iter().find(|i| i.name == *fitted).unwrap();
            assert!(matches!(
                input.kind,
                InputKind::Number | InputKind::Rgb | InputKind::Angle
            ));
        }
        let values = (approximation.mapped_inputs)(&HairParams::default());
        let f64_model = (entry.build)(&values).unwrap();
        let f32_model = (approximation.build_f32)(&values).unwrap();
        let (wi, wo) = (dir(0.2, 0.3), dir(-0.1, 0.5));
        let a = f64_model.eval(&Query::far(wi, wo));
        let q32 = Query::far(
            V3::new(wi.x as f32, wi.y as f32, wi.z as f32),
            V3::new(wo.x as f32, wo.y as f32, wo.z as f32),
        );
        let b = f32_model.eval(&q32);
        for c in 0..3 {
            assert!(
                (a[c] - f64::from(b[c])).abs() < 1e-5 * (1.0 + a[c]),
                "{name}: {a:?} {b:?}"
            );
        }
        let wgsl = (approximation.trace)(&values).unwrap().to_wgsl("eval");
        assert!(wgsl.contains("wo: vec3<f32>) -> vec3<f32>"), "{wgsl}");
    }
}

fn run_eval(args: &[&str], stdin: &str) -> (bool, String, String) {
    let mut child = Command::new(env!("CARGO_BIN_EXE_hairmath"))
        .arg("eval")
        .args(args)
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let _ = child.stdin.take().unwrap().write_all(stdin.as_bytes());
    let out = child.wait_with_output().unwrap();
    let text = |b: &[u8]| String::from_utf8_lossy(b).into_owned();
    (out.status.success(), text(&out.stdout), text(&out.stderr))
}

#[test]
fn the_command_line_evaluates_the_three_models() {
    // The mirror cone at 30 degrees: 0.1 cos 30 + 0.5 = 0.5866025 (kajiya_kay_hand_computed_values).
    let s = 0.5f64;
    let c = 0.75f64.sqrt();
    let row = format!("wi_x,wi_y,wi_z,wo_x,wo_y,wo_z\n{s},{c},0,{},{},0\n", -s, -c);
    let (ok, out, err) = run_eval(
        &[
            "--model",
            "kajiya-kay",
            "--kd",
            "0.1",
            "--ks",
            "0.5",
            "--exponent",
            "2",
        ],
        &row,
    );
    assert!(ok, "{err}");
    let last = out.lines().nth(1).unwrap();
    let f: Vec<f64> = last
        .split(',')
        .skip(6)
        .map(|x| x.parse().unwrap())
        .collect();
    assert_eq!(f.len(), 3);
    assert!(
        f.iter()
            .all(|x| (x - (0.1 * 0.75f64.sqrt() + 0.5)).abs() < 1e-12),
        "{out}"
    );

    let tf = [
        "--model",
        "tressfx",
        "--kd",
        "0.05,0.03,0.02",
        "--ks-primary",
        "0.3",
        "--exponent-primary",
        "12",
        "--shift-primary-deg",
        "4",
        "--ks-secondary",
        "0.2,0.1,0.05",
        "--exponent-secondary",
        "3",
        "--shift-secondary-deg",
        "8",
    ];
    let (ok, out, err) = run_eval(&tf, &row);
    assert!(ok, "{err}");
    let want = TressFx::new(&tressfx_example())
        .unwrap()
        .eval(&Query::far(V3::new(s, c, 0.0), V3::new(-s, -c, 0.0)));
    let got: Vec<f64> = out
        .lines()
        .nth(1)
        .unwrap()
        .split(',')
        .skip(6)
        .map(|x| x.parse().unwrap())
        .collect();
    for k in 0..3 {
        assert!(
            (got[k] - want[k]).abs() < 1e-12 * (1.0 + want[k]),
            "{out} vs {want:?}"
        );
    }

    let sch = [
        "--model",
        "scheuermann",
        "--kd",
        "0.416,0.424,0.431",
        "--ks-primary",
        "1",
        "--exponent-primary",
        "0.98",
        "--tangent-shift-primary",
        "-1",
        "--ks-secondary",
        "0.416,0.424,0.431",
        "--exponent-secondary",
        "0.49",
        "--tangent-shift-secondary",
        "1.5",
    ];
    let (ok, out, err) = run_eval(&sch, &row);
    assert!(ok, "{err}");
    let want = Scheuermann::new(&ScheuermannParams::BLOG)
        .unwrap()
        .eval(&Query::far(V3::new(s, c, 0.0), V3::new(-s, -c, 0.0)));
    let got: Vec<f64> = out
        .lines()
        .nth(1)
        .unwrap()
        .split(',')
        .skip(6)
        .map(|x| x.parse().unwrap())
        .collect();
    for k in 0..3 {
        assert!(
            (got[k] - want[k]).abs() < 1e-12 * (1.0 + want[k]),
            "{out} vs {want:?}"
        );
    }

    // An invalid value names the input; a missing flag is reported.
    let (ok, _, err) = run_eval(
        &[
            "--model",
            "kajiya-kay",
            "--kd",
            "0.1",
            "--ks",
            "0.5",
            "--exponent",
            "0",
        ],
        &row,
    );
    assert!(!ok && err.contains("exponent = 0 is not allowed"), "{err}");
    let (ok, _, err) = run_eval(
        &["--model", "kajiya-kay", "--kd", "0.1", "--ks", "0.5"],
        &row,
    );
    assert!(!ok && err.contains("--exponent"), "{err}");
}

// ---------------------------------------------------------------------------------------------
// Errata (README).

/// The survey's Kajiya-Kay `S_M = k_d + k_s cos^n(theta_o + theta_i) / cos theta_i` has no
/// clamp: beyond a quarter turn from the mirror cone (|theta_i + theta_o| > 90 degrees) the
/// cosine is negative, so S is negative for odd n and undefined (NaN) for fractional n. The
/// model clamps the cosine at 0.
#[test]
fn erratum_survey_kajiya_kay_goes_negative_without_a_clamp() {
    let t = 60f64.to_radians();
    // k_d = 0.1, k_s = 0.5, n = 1 at theta_i = theta_o = 60: 0.1 + 0.5 cos(120) / cos(60).
    let printed = survey_kajiya_kay(0.1, 0.5, 1.0, t, t);
    assert!((printed + 0.4).abs() < 1e-12, "{printed}");
    assert!(survey_kajiya_kay(0.1, 0.5, 2.5, t, t).is_nan());
    let model = eval(&kajiya_kay(0.1, 0.5, 1.0), dir(t, 0.0), dir(t, 0.0));
    assert!((model[0] - 0.1 * t.cos()).abs() < 1e-15, "{model:?}");
}

/// The blog's tangent `T = normalize(dFdx(P) dFdy(uv).t - dFdy(P) dFdx(uv).t)` is dP/ds
/// times det(d(s, t)/d(x, y)), the orientation of the UV mapping on screen, normalised: the
/// determinant's sign survives. On the back of a two-sided hair card, or with mirrored UVs, T
/// points from tip to root and both highlight shifts go the wrong way (the usual construction
/// divides by the determinant or multiplies by its sign).
#[test]
fn erratum_blog_tangent_flips_with_the_uv_orientation() {
    // A card whose texture coordinate s runs along the strand: P = s Ps + t Pt.
    let (ps, pt) = ([0.0, -1.0, 0.0], [1.0, 0.0, 0.0]);
    let tangent = |ds: [f64; 2], dt: [f64; 2]| {
        // Screen derivatives of P and (s, t) for a map (x, y) -> (s, t) with these gradients.
        let dpdx = add(mul(ps, ds[0]), mul(pt, dt[0]));
        let dpdy = add(mul(ps, ds[1]), mul(pt, dt[1]));
        normalize(add(mul(dpdx, dt[1]), mul(dpdy, -dt[0])))
    };
    let front = tangent([1.0, 0.2], [0.1, 1.0]); // det = 1 - 0.02 > 0
    let back = tangent([-1.0, 0.2], [-0.1, 1.0]); // the same card mirrored: det < 0
    assert!(dot(front, ps) > 0.999, "{front:?}");
    assert!(dot(back, ps) < -0.999, "{back:?}");
}
