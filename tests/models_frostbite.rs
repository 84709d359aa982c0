//! The Frostbite models (`hairmath::models::{Frostbite, FrostbiteRefit}`): Tafuri 2019's
//! slides 12-21 written again here in plain f64 from the directions (`slides`, below: the
//! Gaussians, Karis' R, the TT table read by its own bilinear interpolation, Chiang's
//! attenuation at one offset with the exact Fresnel term, the scaled TRT distribution) and
//! compared at hand-picked points (grazing, wi = +-wo, phi = 0 and pi, directions along the
//! tangent, beyond the table's axes); finiteness and non-negativity over the whole domain
//! (proptest, f64 and f32); SIMD lanes against the scalar model; the table; the inputs and their
//! validation; the registry and the mapping; the errata of the slides (README 18 and 19).

use hairmath::bcsdf::{
    longitudinal_variance, Bcsdf, ChiangFarField, FarFieldRule, FromInputs, InputValue,
    InputValues, Model, Query, HAIR_INPUTS,
};
use hairmath::geometry::V3;
use hairmath::lobe::deon_lobe;
use hairmath::models::{
    d_trt_frostbite, frostbite_trt_scale, frostbite_tt_table, Approximation, ExpCosCoefficients,
    Frostbite, FrostbiteRefit, FrostbiteVariant, FROSTBITE_LOBES, FROSTBITE_TRT_OFFSET_H,
    FROSTBITE_TT_BETA_N, FROSTBITE_TT_GAUSSIAN_A, FROSTBITE_TT_GAUSSIAN_B, FROSTBITE_TT_OFFSET_H,
    FROSTBITE_TT_THETA_O,
};
use hairmath::params::{AzimuthalRoughness, HairParams, HairValues};
use hairmath::quadrature::{gauss_legendre, integrate};
use hairmath::registry::find_model;
use hairmath::ParamError;
use proptest::prelude::*;
use std::f64::consts::{FRAC_PI_2, PI};

// ---------------------------------------------------------------------------------------------
// The slides, independently.

/// A hair: beta_m, beta_n, alpha (radians), eta, sigma_a per unit radius.
#[derive(Clone, Copy, Debug)]
struct Hair {
    beta_m: f64,
    beta_n: f64,
    alpha: f64,
    eta: f64,
    sigma_a: [f64; 3],
}

impl Hair {
    fn params(&self) -> HairParams {
        HairParams::try_from(HairValues {
            beta_m: self.beta_m,
            beta_n: self.beta_n,
            alpha: self.alpha,
            eta: self.eta,
            sigma_a: self.sigma_a,
        })
        .unwrap()
    }
}

const BROWN: Hair = Hair {
    beta_m: 0.3,
    beta_n: 0.3,
    alpha: 0.034_906_585_039_886_59,
    eta: 1.55,
    sigma_a: [0.545, 0.906, 1.781],
};

/// Brown, a rough blonde, a smooth black hair with no tilt, a hair below the table's beta_n
/// with a negative tilt and an unusual index, and a clear fibre at the roughest beta_n.
const HAIRS: [Hair; 5] = [
    BROWN,
    Hair {
        beta_m: 0.6,
        beta_n: 0.9,
        alpha: 0.05,
        eta: 1.55,
        sigma_a: [0.06, 0.1, 0.2],
    },
    Hair {
        beta_m: 0.15,
        beta_n: 0.3,
        alpha: 0.0,
        eta: 1.55,
        sigma_a: [6.0, 9.0, 14.0],
    },
    Hair {
        beta_m: 0.2,
        beta_n: 0.05,
        alpha: -0.1,
        eta: 1.9,
        sigma_a: [0.0, 0.5, 3.0],
    },
    Hair {
        beta_m: 0.45,
        beta_n: 1.0,
        alpha: 0.03,
        eta: 1.3,
        sigma_a: [0.0; 3],
    },
];

/// Chiang et al. 2016, eq. 7: the variance of the longitudinal lobe.
fn chiang_variance(b: f64) -> f64 {
    (0.726 * b + 0.812 * b * b + 3.7 * b.powi(20)).powi(2)
}

/// The unit-area Gaussian of standard deviation `b`.
fn gauss(b: f64, x: f64) -> f64 {
    (-x * x / (2.0 * b * b)).exp() / (b * (2.0 * PI).sqrt())
}

/// Unpolarised Fresnel reflectance of a dielectric of index `eta` at incidence cosine `c`.
fn fresnel(c: f64, eta: f64) -> f64 {
    let sin2_t = (1.0 - c * c) / (eta * eta);
    let ct = (1.0 - sin2_t).sqrt();
    let rs = (c - eta * ct) / (c + eta * ct);
    let rp = (eta * c - ct) / (eta * c + ct);
    0.5 * (rs * rs + rp * rp)
}

/// Chiang's A_1 and A_2 at offset h for the ray inclined at theta_o, chord transmittance.
fn chiang_a(h: f64, sin_o: f64, cos_o: f64, eta: f64, sigma_a: f64) -> [f64; 2] {
    let f = fresnel(cos_o * (1.0 - h * h).sqrt(), eta);
    // sin gamma_t = h / eta', eta' = sqrt(eta^2 - sin^2) / cos (Bravais), finite at grazing.
    let sin_gt = h * cos_o / (eta * eta - sin_o * sin_o).sqrt();
    let cos_tt = (1.0 - (sin_o / eta).powi(2)).sqrt();
    let t = (-sigma_a * 2.0 * (1.0 - sin_gt * sin_gt).sqrt() / cos_tt).exp();
    let a1 = (1.0 - f).powi(2) * t;
    [a1, a1 * f * t]
}

/// The TT table at (|theta_o|, beta_n): bilinear between the f32-rounded fitted slices,
/// clamped to the axes' ends.
fn tt_table(theta_o: f64, beta_n: f64) -> [f64; 2] {
    let cell = |x: f64, axis: &[f64]| {
        let n = axis.len() - 1;
        let (lo, hi) = (axis[0], axis[n]);
        let t = ((x - lo) / (hi - lo)).clamp(0.0, 1.0) * n as f64;
        let i = (t.floor() as usize).min(n - 1);
        (i, t - i as f64)
    };
    let (i, fi) = cell(theta_o, &FROSTBITE_TT_THETA_O);
    let (j, fj) = cell(beta_n, &FROSTBITE_TT_BETA_N);
    let at = |t: &[[f64; 10]; 9]| {
        let v = |a: usize, b: usize| f64::from(t[a][b] as f32);
        (1.0 - fj) * ((1.0 - fi) * v(i, j) + fi * v(i + 1, j))
            + fj * ((1.0 - fi) * v(i, j + 1) + fi * v(i + 1, j + 1))
    };
    [at(&FROSTBITE_TT_GAUSSIAN_A), at(&FROSTBITE_TT_GAUSSIAN_B)]
}

/// The slides' lobes [R, TT, TRT] per channel for `hair` with the offsets (h_TT, h_TRT).
fn slides(hair: &Hair, wi: [f64; 3], wo: [f64; 3], offsets: (f64, f64)) -> [[f64; 3]; 3] {
    let (sin_i, sin_o) = (wi[0], wo[0]);
    let cos_o = wo[1].hypot(wo[2]);
    let s = sin_i + sin_o;
    // Relative azimuth (0 when a direction is along the tangent).
    let cross = wi[1] * wo[2] - wi[2] * wo[1];
    let dot = wi[1] * wo[1] + wi[2] * wo[2];
    let phi = if cross == 0.0 && dot == 0.0 {
        0.0
    } else {
        cross.atan2(dot)
    };
    // Slide 12, Karis-style: Gaussians in the sum of sines, widths B, B/2, 2B.
    let v = chiang_variance(hair.beta_m);
    let b = (v / (1.0 / v).tanh() - v * v).sqrt().max(1e-6);
    let a = hair.alpha;
    let m_r = gauss(b, s - 2.0 * a.sin());
    let m_tt = gauss(0.5 * b, s + 2.0 * (0.5 * a).sin());
    let m_trt = gauss(2.0 * b, s + 2.0 * (1.5 * a).sin());
    // Slide 14: D_R = cos(phi/2)/4, A_R = Schlick at sqrt((1 + wi.wo)/2).
    let f0 = ((hair.eta - 1.0) / (hair.eta + 1.0)).powi(2);
    let wi_wo = wi[0] * wo[0] + wi[1] * wo[1] + wi[2] * wo[2];
    let c = ((1.0 + wi_wo) / 2.0).clamp(0.0, 1.0).sqrt();
    let n_r = 0.25 * (phi / 2.0).cos() * (f0 + (1.0 - f0) * (1.0 - c).powi(5));
    // Slides 19-20: the Gaussian a exp(-b (|phi| - pi)^2) from the table.
    let [ta, tb] = tt_table(sin_o.atan2(cos_o).abs(), hair.beta_n);
    let d_tt = ta * (-tb * (phi.abs() - PI).powi(2)).exp();
    // Slide 21: s_r exp(s_r (17 cos phi - 16.78)), s_r = clamp(1.5 (1 - beta_n), 0, 1).
    let s_r = (1.5 * (1.0 - hair.beta_n)).clamp(0.0, 1.0);
    let d_trt = s_r * (s_r * (17.0 * phi.cos() - 16.78)).exp();
    let tt = hair
        .sigma_a
        .map(|sa| m_tt * d_tt * chiang_a(offsets.0, sin_o, cos_o, hair.eta, sa)[0]);
    let trt = hair
        .sigma_a
        .map(|sa| m_trt * d_trt * chiang_a(offsets.1, sin_o, cos_o, hair.eta, sa)[1]);
    [[m_r * n_r; 3], tt, trt]
}

/// The published and refitted offsets, written out.
const PUBLISHED_OFFSETS: (f64, f64) = (0.0, 0.866_025_403_784_438_6);
const REFIT_OFFSETS: (f64, f64) = (FROSTBITE_TT_OFFSET_H, FROSTBITE_TRT_OFFSET_H);

fn unit(s: f64, phi: f64) -> [f64; 3] {
    let c = (1.0 - s * s).max(0.0).sqrt();
    [s, c * phi.cos(), c * phi.sin()]
}

/// (label, wi, wo): generic, wi = +-wo, phi = 0 and pi, the peaks, grazing, along the tangent,
/// theta_o beyond the table's 80 degrees.
fn points() -> Vec<(&'static str, [f64; 3], [f64; 3])> {
    vec![
        ("generic", unit(-0.3, 1.2), unit(0.3, -1.8)),
        (
            "README pair",
            [-0.3, 0.2, 0.932_737_905_308_881_5],
            [0.3, 0.1, 0.948_683_298_050_513_8],
        ),
        ("wi = wo", unit(0.3, 0.4), unit(0.3, 0.4)),
        ("wi = -wo", unit(0.3, 0.4), unit(-0.3, 0.4 + PI)),
        ("phi = 0", unit(-0.5, 1.0), unit(0.2, 1.0)),
        ("phi = pi", unit(-0.2, 0.3), unit(0.25, 0.3 + PI)),
        ("R peak", unit(-0.03, 0.0), unit(0.1, 0.0)),
        ("TT peak", unit(-0.25, -1.2), unit(0.22, -1.2 + PI)),
        ("TRT", unit(-0.35, 0.0), unit(0.2, 0.6)),
        (
            "theta_o 85 deg",
            unit(-0.9, 0.5),
            unit(85f64.to_radians().sin(), 2.0),
        ),
        ("grazing wi", unit(0.999_999_9, 1.3), unit(0.1, -0.5)),
        (
            "grazing both, opposite ends",
            unit(-0.999_999_9, 0.5),
            unit(0.999_999_9, -1.1),
        ),
        ("wi along +X", [1.0, 0.0, 0.0], unit(-0.4, 0.9)),
        ("wo along -X", unit(0.2, -2.2), [-1.0, 0.0, 0.0]),
        (
            "wi = -wo along the tangent",
            [1.0, 0.0, 0.0],
            [-1.0, 0.0, 0.0],
        ),
        (
            "wi = wo along the tangent",
            [-1.0, 0.0, 0.0],
            [-1.0, 0.0, 0.0],
        ),
        ("normal plane, phi = 2", [0.0, 1.0, 0.0], unit(0.0, 2.0)),
    ]
}

fn query(wi: [f64; 3], wo: [f64; 3]) -> Query<f64> {
    Query::far(V3::new(wi[0], wi[1], wi[2]), V3::new(wo[0], wo[1], wo[2]))
}

/// `got` against the slides' `want`, lobe by lobe, and the lobes against eval.
fn check_against_slides<M: Bcsdf<f64>>(m: &M, hair: &Hair, offsets: (f64, f64)) {
    for (label, wi, wo) in points() {
        let q = query(wi, wo);
        let want = slides(hair, wi, wo, offsets);
        let lobes = m.eval_lobes(&q);
        let s = m.eval(&q);
        assert_eq!(lobes.len(), 3);
        for p in 0..3 {
            for c in 0..3 {
                let (got, w) = (lobes[p][c], want[p][c]);
                assert!(got.is_finite() && got >= 0.0, "{label}: {lobes:?}");
                assert!(
                    (got - w).abs() <= 1e-12 * w.abs() + 1e-300,
                    "{hair:?} {label}: lobe {p} channel {c}: {got:e} against the slides' {w:e}"
                );
            }
        }
        for c in 0..3 {
            let sum: f64 = lobes.iter().map(|l| l[c]).sum();
            assert!(s[c].is_finite() && s[c] >= 0.0, "{label}: {s:?}");
            assert!((sum - s[c]).abs() <= 1e-15 * s[c], "{label}: {sum} {s:?}");
        }
    }
}

#[test]
fn frostbite_is_the_slides() {
    for hair in &HAIRS {
        let m = Frostbite::new(&hair.params());
        check_against_slides(&m, hair, PUBLISHED_OFFSETS);
    }
}

#[test]
fn frostbite_refit_is_the_slides_at_the_refitted_offsets() {
    for hair in &HAIRS {
        let m = FrostbiteRefit::new(&hair.params());
        check_against_slides(&m, hair, REFIT_OFFSETS);
    }
    assert_eq!(
        (
            <hairmath::models::Refitted as FrostbiteVariant>::TT_OFFSET.get::<f64>(),
            <hairmath::models::Refitted as FrostbiteVariant>::TRT_OFFSET.get::<f64>()
        ),
        REFIT_OFFSETS
    );
    assert!((REFIT_OFFSETS.0 - 0.600).abs() < 1e-3 && (REFIT_OFFSETS.1 - 0.719).abs() < 1e-3);
}

#[test]
fn the_points_are_the_hard_cases_and_the_lobes_where_expected() {
    let m = Frostbite::new(&BROWN.params());
    let at = |label: &str| {
        let (_, wi, wo) = points().into_iter().find(|p| p.0 == label).unwrap();
        m.eval_lobes(&query(wi, wo))
    };
    // On the mirror cone at phi = 0 R is at its peak and TT negligible (TRT, wider and
    // centred nearby, is of the same order for brown hair), TT dominates forward at phi = pi,
    // and TRT is larger at small phi than backwards.
    let (r_peak, tt_peak) = (at("R peak"), at("TT peak"));
    assert!(
        r_peak[0][0] > 1e3 * r_peak[1][0] && r_peak[0][0] > 0.01,
        "{r_peak:?}"
    );
    assert!(tt_peak[1][0] > 10.0 * tt_peak[0][0], "{tt_peak:?}");
    assert!(at("TRT")[2][0] > at("phi = pi")[2][0]);
    // Both directions along the tangent: phi is 0 by convention, everything finite.
    let q = query([1.0, 0.0, 0.0], [1.0, 0.0, 0.0]);
    assert!(m.eval(&q).iter().all(|v| v.is_finite() && *v >= 0.0));
}

#[test]
fn refit_changes_only_the_transmitted_attenuations() {
    let (published, refit) = (
        Frostbite::new(&BROWN.params()),
        FrostbiteRefit::new(&BROWN.params()),
    );
    assert_eq!(published.uniforms(), refit.uniforms());
    for (label, wi, wo) in points() {
        let q = query(wi, wo);
        let (p, r) = (published.eval_lobes(&q), refit.eval_lobes(&q));
        assert_eq!(p[0], r[0], "{label}: R");
        let cos_o = wo[1].hypot(wo[2]);
        for c in 0..3 {
            let a = |h: f64| chiang_a(h, wo[0], cos_o, BROWN.eta, BROWN.sigma_a[c]);
            let (published_tt, published_trt) =
                (a(PUBLISHED_OFFSETS.0)[0], a(PUBLISHED_OFFSETS.1)[1]);
            if published_tt == 0.0 || published_trt == 0.0 {
                // wo along the tangent: total reflection at entry, no transmitted light.
                assert_eq!((p[1][c], p[2][c], r[1][c], r[2][c]), (0.0, 0.0, 0.0, 0.0));
                continue;
            }
            let tt = a(REFIT_OFFSETS.0)[0] / published_tt;
            let trt = a(REFIT_OFFSETS.1)[1] / published_trt;
            assert!(
                (r[1][c] - tt * p[1][c]).abs() <= 1e-12 * r[1][c] + 1e-300,
                "{label}"
            );
            assert!(
                (r[2][c] - trt * p[2][c]).abs() <= 1e-12 * r[2][c] + 1e-300,
                "{label}"
            );
        }
    }
}

// ---------------------------------------------------------------------------------------------
// The table.

#[test]
fn the_tt_table_holds_the_fitted_slices() {
    let t = frostbite_tt_table();
    let table = t.table();
    let axes = table.axes();
    assert_eq!((axes[0].name(), axes[0].size()), ("theta_o", 9));
    assert_eq!((axes[1].name(), axes[1].size()), ("beta_n", 10));
    assert_eq!(table.channels(), ["a", "b"]);
    // The equally spaced axes are the fitted grid (10-degree and 0.1 steps).
    for (i, &theta) in FROSTBITE_TT_THETA_O.iter().enumerate() {
        assert!((axes[0].sample(i) - theta).abs() < 1e-8);
        assert!((theta - (10.0 * i as f64).to_radians()).abs() < 1e-8);
    }
    for (j, &b) in FROSTBITE_TT_BETA_N.iter().enumerate() {
        assert!((axes[1].sample(j) - b).abs() < 1e-12);
    }
    for i in 0..9 {
        for j in 0..10 {
            let (a, b) = (FROSTBITE_TT_GAUSSIAN_A[i][j], FROSTBITE_TT_GAUSSIAN_B[i][j]);
            assert_eq!(table.get(&[i, j], 0), Some(a as f32));
            assert_eq!(table.get(&[i, j], 1), Some(b as f32));
            // Every slice is a positive Gaussian: the TT lobe is never negative.
            assert!(a > 0.0 && b >= 0.0, "({i}, {j}): {a} {b}");
            // At a grid point the f64 lookup is the stored slice.
            let at = t.sample([axes[0].sample(i), axes[1].sample(j)]);
            assert!((at[0] - f64::from(a as f32)).abs() < 1e-12 * a);
        }
    }
    // Every model shares the one table.
    let m = Frostbite::new(&BROWN.params());
    assert!(std::sync::Arc::ptr_eq(m.tt_table().arc(), t.arc()));
    assert!(std::sync::Arc::ptr_eq(
        m.instantiate::<f32>().tt_table().arc(),
        t.arc()
    ));
}

#[test]
fn the_tt_distribution_is_close_to_a_density_on_the_circle() {
    // The fitted Gaussians approximate D_TT, a density in phi: their integral over the circle
    // is near 1 in every slice (the fit is of the shape, so not exactly).
    let rule = gauss_legendre(16);
    for i in 0..9 {
        for j in 0..10 {
            let (a, b) = (FROSTBITE_TT_GAUSSIAN_A[i][j], FROSTBITE_TT_GAUSSIAN_B[i][j]);
            let mass = 2.0 * integrate(&rule, 64, 0.0, PI, |x| a * (-b * (x - PI).powi(2)).exp());
            assert!((mass - 1.0).abs() < 0.08, "({i}, {j}): {mass}");
        }
    }
}

// ---------------------------------------------------------------------------------------------
// Over the whole domain.

/// sin theta of a direction: along the tangent (+-1), grazing, in the normal plane, or any.
fn sin_theta() -> impl Strategy<Value = f64> {
    prop_oneof![
        Just(1.0),
        Just(-1.0),
        Just(0.999_999_9),
        Just(-0.999_999_9),
        Just(0.0),
        -1.0_f64..=1.0,
        -1.0_f64..=1.0,
    ]
}

/// An azimuth, 0 and +-pi included.
fn azimuth() -> impl Strategy<Value = f64> {
    prop_oneof![Just(0.0), Just(PI), Just(-PI), -PI..=PI, -PI..=PI]
}

/// wi and wo: independent, equal, opposite, or at relative azimuth 0 or pi.
fn pair() -> impl Strategy<Value = ([f64; 3], [f64; 3])> {
    (sin_theta(), azimuth(), sin_theta(), azimuth(), 0..5_u8).prop_map(|(s1, p1, s2, p2, k)| {
        let wi = unit(s1, p1);
        let wo = match k {
            0 => wi,
            1 => wi.map(|v| -v),
            2 => unit(s2, p1),
            3 => unit(s2, p1 + PI),
            _ => unit(s2, p2),
        };
        (wi, wo)
    })
}

/// A roughness in (0, 1], its ends included.
fn roughness() -> impl Strategy<Value = f64> {
    prop_oneof![Just(1.0), Just(1e-12), Just(0.1), 1e-6_f64..=1.0]
}

/// Every hair of the inputs' domains: tilts to +-89.9 degrees, eta in (1, 3], absorption from
/// 0 to beyond the 1e30 clamp.
fn any_hair() -> impl Strategy<Value = Hair> {
    let tilt = prop_oneof![Just(0.0), Just(1.569), Just(-1.569), -1.5_f64..=1.5];
    let eta = prop_oneof![
        Just(1.0 + 1e-12),
        Just(1.000_001),
        Just(3.0),
        Just(1.55),
        1.000_001_f64..=3.0
    ];
    let channel = prop_oneof![Just(0.0), Just(1e300), Just(1e4), 0.0_f64..=20.0];
    (
        roughness(),
        roughness(),
        tilt,
        eta,
        [channel.clone(), channel.clone(), channel],
    )
        .prop_map(|(beta_m, beta_n, alpha, eta, sigma_a)| Hair {
            beta_m,
            beta_n,
            alpha,
            eta,
            sigma_a,
        })
}

fn check_everywhere<M: Model>(m: &M, wi: [f64; 3], wo: [f64; 3]) -> Result<(), TestCaseError> {
    let q = query(wi, wo);
    let s = m.eval(&q);
    prop_assert!(
        s.iter().all(|v| v.is_finite() && *v >= 0.0),
        "{wi:?} {wo:?}: {s:?}"
    );
    let lobes = m.eval_lobes(&q);
    prop_assert!(lobes.iter().flatten().all(|v| v.is_finite() && *v >= 0.0));
    for c in 0..3 {
        let sum: f64 = lobes.iter().map(|l| l[c]).sum();
        prop_assert!((sum - s[c]).abs() <= 1e-15 * s[c], "{sum} {s:?}");
    }
    let m32 = m.instantiate::<f32>();
    let f = |v: [f64; 3]| V3::new(v[0] as f32, v[1] as f32, v[2] as f32);
    let q32 = Query::far(f(wi), f(wo));
    let s32 = m32.eval(&q32);
    prop_assert!(
        s32.iter().all(|v| v.is_finite() && *v >= 0.0),
        "f32 {wi:?} {wo:?}: {s32:?}"
    );
    let l32 = m32.eval_lobes(&q32);
    prop_assert!(l32.iter().flatten().all(|v| v.is_finite() && *v >= 0.0));
    Ok(())
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(2048))]

    #[test]
    fn frostbite_is_finite_and_non_negative_everywhere((wi, wo) in pair(), hair in any_hair()) {
        check_everywhere(&Frostbite::new(&hair.params()), wi, wo)?;
    }

    #[test]
    fn frostbite_refit_is_finite_and_non_negative_everywhere(
        (wi, wo) in pair(), hair in any_hair(),
    ) {
        check_everywhere(&FrostbiteRefit::new(&hair.params()), wi, wo)?;
    }

    #[test]
    fn frostbite_is_the_slides_everywhere((wi, wo) in pair(), k in 0..HAIRS.len()) {
        // Away from the points: random pairs for each hair, lobe by lobe.
        let hair = HAIRS[k];
        let lobes = Frostbite::new(&hair.params()).eval_lobes(&query(wi, wo));
        let want = slides(&hair, wi, wo, PUBLISHED_OFFSETS);
        for p in 0..3 {
            for c in 0..3 {
                let (got, w) = (lobes[p][c], want[p][c]);
                prop_assert!((got - w).abs() <= 1e-11 * w + 1e-300, "{p} {c}: {got:e} {w:e}");
            }
        }
    }
}

#[test]
fn simd_lanes_agree_with_the_scalar_f32_model() {
    let f32s = |v: [f64; 3]| v.map(|x| x as f32);
    let pts = points();
    let wi: Vec<[f32; 3]> = pts.iter().map(|p| f32s(p.1)).collect();
    let wo: Vec<[f32; 3]> = pts.iter().map(|p| f32s(p.2)).collect();
    for hair in &HAIRS {
        let m = Frostbite::new(&hair.params());
        let scalar = m.instantiate::<f32>();
        for lanes in [0, 1] {
            let mut out = vec![[0.0_f32; 3]; wi.len()];
            let h = vec![0.0; wi.len()];
            if lanes == 0 {
                let l = m.instantiate::<wide::f32x8>();
                hairmath::bcsdf::eval_batch(&l, &wi, &wo, &h, &mut out).unwrap();
            } else {
                let l = m.instantiate::<wide::f32x16>();
                hairmath::bcsdf::eval_batch(&l, &wi, &wo, &h, &mut out).unwrap();
            }
            for (k, s) in out.iter().enumerate() {
                let q = Query::far(
                    V3::new(wi[k][0], wi[k][1], wi[k][2]),
                    V3::new(wo[k][0], wo[k][1], wo[k][2]),
                );
                let want = scalar.eval(&q);
                for c in 0..3 {
                    let tolerance = 1e-3 * want[c].abs() + 1e-30;
                    assert!(
                        s[c].is_finite() && (s[c] - want[c]).abs() <= tolerance,
                        "{hair:?} {}: {s:?} {want:?}",
                        pts[k].0
                    );
                }
            }
        }
    }
}

#[test]
fn f32_follows_f64() {
    for hair in &HAIRS {
        let m = Frostbite::new(&hair.params());
        let m32 = m.instantiate::<f32>();
        for (label, wi, wo) in points() {
            let want = m.eval(&query(wi, wo));
            let f = |v: [f64; 3]| V3::new(v[0] as f32, v[1] as f32, v[2] as f32);
            let got = m32.eval(&Query::far(f(wi), f(wo)));
            let scale = want.iter().fold(0.0_f64, |a, &b| a.max(b));
            for c in 0..3 {
                // The directions' rounding moves S along its slope; grazing pairs are steep.
                let tolerance = 2e-3 * scale + 1e-30;
                assert!(
                    (f64::from(got[c]) - want[c]).abs() <= tolerance,
                    "{hair:?} {label}: {got:?} {want:?}"
                );
            }
        }
    }
}

// ---------------------------------------------------------------------------------------------
// Inputs, validation, registry, mapping.

fn values_of(hair: &Hair) -> InputValues {
    let mut v = InputValues::new();
    v.set("beta_m", InputValue::Number(hair.beta_m));
    v.set("beta_n", InputValue::Number(hair.beta_n));
    v.set("alpha", InputValue::Number(hair.alpha));
    v.set("eta", InputValue::Number(hair.eta));
    v.set(
        "sigma_a",
        InputValue::Absorption(hairmath::bcsdf::AbsorptionInput::SigmaA(hair.sigma_a)),
    );
    v
}

#[test]
fn the_inputs_are_the_physical_parameters_of_chiang_far() {
    let chiang_far = find_model("chiang-far").unwrap();
    for name in ["frostbite", "frostbite-refit"] {
        let entry = find_model(name).unwrap();
        assert_eq!(entry.inputs, &HAIR_INPUTS[..], "{name}");
        for input in entry.inputs {
            assert!(chiang_far.inputs.contains(input), "{name}: {}", input.name);
        }
        // Built from the values, the registry's model is the model.
        let m = (entry.build)(&values_of(&BROWN)).unwrap();
        let (_, wi, wo) = points()[0];
        let direct = Frostbite::new(&BROWN.params()).eval_lobes(&query(wi, wo));
        let refit = FrostbiteRefit::new(&BROWN.params()).eval_lobes(&query(wi, wo));
        let want = if name == "frostbite" { direct } else { refit };
        assert_eq!(m.eval_lobes(&query(wi, wo)), want, "{name}");
        assert_eq!(m.lobe_names(), &FROSTBITE_LOBES);
        assert!(!m.uses_offset());
    }
    assert_eq!(Frostbite::<f64>::NAME, "frostbite");
    assert_eq!(FrostbiteRefit::<f64>::NAME, "frostbite-refit");
}

#[test]
fn invalid_inputs_give_typed_errors() {
    let chiang_far = find_model("chiang-far").unwrap();
    for (name, value) in [
        ("beta_m", 0.0),
        ("beta_m", 1.5),
        ("beta_n", -0.1),
        ("beta_n", f64::NAN),
        ("alpha", 1.6),
        ("eta", 1.0),
        ("eta", 3.5),
    ] {
        let mut v = values_of(&BROWN);
        v.set(name, InputValue::Number(value));
        let e = Frostbite::from_inputs(&v).unwrap_err();
        assert!(
            matches!(e, ParamError::OutOfRange { name: n, .. } if n == name),
            "{name} {value}: {e:?}"
        );
        // The same message as wherever the input enters.
        let other = (chiang_far.build)(&v).err().unwrap();
        assert_eq!(e.to_string(), other.to_string(), "{name}");
        assert!(FrostbiteRefit::from_inputs(&v).is_err());
    }
    let mut v = values_of(&BROWN);
    v.set(
        "sigma_a",
        InputValue::Absorption(hairmath::bcsdf::AbsorptionInput::SigmaA([-1.0, 0.0, 0.0])),
    );
    assert!(Frostbite::from_inputs(&v).is_err());
    let all = values_of(&BROWN);
    let mut missing = InputValues::new();
    for name in ["beta_m", "alpha", "eta", "sigma_a"] {
        missing.set(name, all.get(name).unwrap());
    }
    assert!(matches!(
        Frostbite::from_inputs(&missing),
        Err(ParamError::Missing { name: "beta_n" })
    ));
}

#[test]
fn both_models_are_registered_approximations_mapped_to_the_hairs_own_parameters() {
    for name in ["frostbite", "frostbite-refit"] {
        let entry = find_model(name).unwrap();
        let approximation = entry.approximation.expect("an approximation");
        assert_eq!(approximation.fitted_inputs, ["beta_m", "beta_n", "sigma_a"]);
        for fitted in approximation.fitted_inputs {
            assert!(entry.inputs.iter().any(|i| i.name == *fitted), "{fitted}");
        }
        for hair in &HAIRS {
            let mapped = (approximation.mapped_inputs)(&hair.params());
            // Every input present and the hair's own value.
            for input in entry.inputs {
                assert!(mapped.get(input.name).is_some(), "{name}: {}", input.name);
            }
            assert_eq!(mapped.get("beta_m"), Some(InputValue::Number(hair.beta_m)));
            assert_eq!(mapped.get("beta_n"), Some(InputValue::Number(hair.beta_n)));
            assert_eq!(mapped.get("alpha"), Some(InputValue::Number(hair.alpha)));
            assert_eq!(mapped.get("eta"), Some(InputValue::Number(hair.eta)));
            let built = (entry.build)(&mapped).unwrap();
            let (_, wi, wo) = points()[1];
            let direct = Frostbite::new(&hair.params());
            if name == "frostbite" {
                assert_eq!(built.eval(&query(wi, wo)), direct.eval(&query(wi, wo)));
            }
            // The f32, SIMD and traced builds work from the mapped inputs too.
            assert!((approximation.build_f32)(&mapped).is_ok());
            assert!((approximation.build_batch)(&mapped).is_ok());
            let wgsl = (approximation.trace)(&mapped).unwrap().to_wgsl("frostbite");
            assert!(wgsl.contains("FrostbiteUniforms"));
        }
    }
    assert_eq!(
        Frostbite::mapped_inputs(&BROWN.params()).get("sigma_a"),
        Some(InputValue::Absorption(
            hairmath::bcsdf::AbsorptionInput::SigmaA(BROWN.sigma_a)
        ))
    );
}

/// The variance of sin(theta_i) under Chiang's (d'Eon's) lobe of variance v at theta_o = 0.
fn deon_second_moment(v: f64) -> f64 {
    let rule = gauss_legendre(16);
    let m = |t: f64, k: i32| deon_lobe(v, t.sin(), t.cos(), 0.0, 1.0) * t.cos() * t.sin().powi(k);
    integrate(&rule, 512, -FRAC_PI_2, FRAC_PI_2, |t| m(t, 2))
}

#[test]
fn the_longitudinal_lobes_are_normalised_and_match_chiangs_r_width() {
    let rule = gauss_legendre(16);
    for beta_m in [0.05, 0.15, 0.3, 0.6, 1.0] {
        let hair = Hair {
            beta_m,
            alpha: 0.0,
            ..BROWN
        };
        let u = Frostbite::new(&hair.params()).uniforms();
        // B^2 is E[sin^2 theta_i] under Chiang's R lobe at normal incidence.
        let moment = deon_second_moment(longitudinal_variance(beta_m));
        assert!(
            (u.width_r * u.width_r - moment).abs() < 1e-9,
            "{beta_m}: {u:?}"
        );
        assert_eq!(
            (u.width_tt, u.width_trt),
            (0.5 * u.width_r, 2.0 * u.width_r)
        );
        // At theta_o = 0 each Gaussian in the sum of sines integrates to 1 over wi's
        // inclination in the measure cos theta_i d theta_i (to its tails beyond |s| = 1).
        for (width, shift) in [(u.width_r, u.shift_r), (u.width_tt, u.shift_tt)] {
            let mass = integrate(&rule, 256, -FRAC_PI_2, FRAC_PI_2, |t| {
                gauss(width, t.sin() - shift) * t.cos()
            });
            let tails = libm_erfc(1.0 / (width * 2f64.sqrt()));
            assert!(
                (mass - (1.0 - tails)).abs() < 1e-9,
                "{beta_m}: {mass} {tails}"
            );
        }
    }
    // Brown hair: B = 0.278, against the slides' literal width beta_m = 0.3 rad of theta_h
    // (0.6 in the sum of sines), 2.2 times wider.
    let u = Frostbite::new(&BROWN.params()).uniforms();
    assert!((u.width_r - 0.2783).abs() < 1e-4, "{}", u.width_r);
    assert!((2.0 * 0.3 / u.width_r - 2.16).abs() < 0.01);
    // The shifts: 2 sin(alpha), -2 sin(alpha/2), -2 sin(3 alpha/2).
    let a = BROWN.alpha;
    assert_eq!(u.shift_r, 2.0 * a.sin());
    assert_eq!(u.shift_tt, -2.0 * (0.5 * a).sin());
    assert_eq!(u.shift_trt, -2.0 * (1.5 * a).sin());
}

/// erfc by its continued fraction (x > 0.5) or 1 - erf's series: an independent evaluation.
fn libm_erfc(x: f64) -> f64 {
    if x < 2.0 {
        // erf series: 2/sqrt(pi) sum (-1)^n x^(2n+1) / (n! (2n+1)).
        let (mut term, mut sum) = (x, x);
        for n in 1..200 {
            term *= -x * x / n as f64;
            sum += term / (2 * n + 1) as f64;
        }
        1.0 - 2.0 / PI.sqrt() * sum
    } else {
        // Lentz's continued fraction: erfc x = exp(-x^2)/sqrt(pi) / (x + 1/2/(x + 1/(x + ...))).
        let mut f = x;
        for k in (1..200).rev() {
            f = x + 0.5 * k as f64 / f;
        }
        (-x * x).exp() / (PI.sqrt() * f)
    }
}

#[test]
fn the_trt_scale_is_the_slides() {
    for (beta_n, want) in [
        (0.1, 1.0),
        (1.0 / 3.0, 1.0),
        (0.5, 0.75),
        (0.9, 0.15),
        (1.0, 0.0),
    ] {
        let got = frostbite_trt_scale(AzimuthalRoughness::new(beta_n).unwrap());
        assert!((got - want).abs() < 1e-15, "{beta_n}: {got}");
        let u = Frostbite::new(&Hair { beta_n, ..BROWN }.params()).uniforms();
        assert_eq!((u.trt_scale, u.beta_n), (got, beta_n));
    }
}

// ---------------------------------------------------------------------------------------------
// Errata (README 18 and 19).

/// README erratum 18: slide 12's unit-area Gaussian in theta_h, read as the longitudinal
/// factor of `S = sum M_p N_p` (slide 13's Chiang N_p), integrates to 2 over theta_i with the
/// solid angle's cos theta_i (theta_h moves at half the rate of theta_i): twice Chiang's lobe,
/// which integrates to 1. hairmath's Karis-style lobe integrates to 1.
#[test]
fn slide_12s_theta_h_gaussian_carries_twice_the_longitudinal_energy() {
    let rule = gauss_legendre(16);
    let literal = |beta: f64, theta_o: f64| {
        integrate(&rule, 512, -FRAC_PI_2, FRAC_PI_2, |t| {
            gauss(beta, 0.5 * (t + theta_o)) * t.cos()
        })
    };
    // Marschner's width for brown hair (sqrt(v)/2 = 0.145) and narrow lobes.
    let brown = 0.5 * chiang_variance(0.3).sqrt();
    let e = literal(brown, 0.0);
    println!("literal theta_h Gaussian, beta = {brown:.4}: {e:.4}");
    assert!((e - 1.917).abs() < 2e-3, "{e}");
    assert!((literal(0.01, 0.0) - 2.0).abs() < 1e-3);
    // Chiang's lobe and the model's lobe at the same roughness.
    let v = chiang_variance(0.3);
    let chiang = integrate(&rule, 512, -FRAC_PI_2, FRAC_PI_2, |t| {
        deon_lobe(v, t.sin(), t.cos(), 0.0, 1.0) * t.cos()
    });
    assert!((chiang - 1.0).abs() < 1e-9, "{chiang}");
    let u = Frostbite::new(
        &Hair {
            alpha: 0.0,
            ..BROWN
        }
        .params(),
    )
    .uniforms();
    let model = integrate(&rule, 512, -FRAC_PI_2, FRAC_PI_2, |t| {
        gauss(u.width_r, t.sin()) * t.cos()
    });
    assert!((model - 1.0).abs() < 1e-3, "{model}");
}

/// `I0` by its power series (an independent evaluation).
fn bessel_i0(x: f64) -> f64 {
    let (mut term, mut sum) = (1.0, 1.0);
    for k in 1..400 {
        term *= (x / 2.0).powi(2) / (k * k) as f64;
        sum += term;
    }
    sum
}

/// README erratum 19: slide 21's `s_r` scales the TRT distribution's height with its
/// exponent, so its integral over phi, `2 pi s_r I0(17 s_r) e^(-16.78 s_r)`, falls from 0.763
/// (beta_n <= 1/3) to 0.544 (0.6), 0.260 (0.9) and 0 (beta_n = 1), while Chiang's far-field
/// TRT distribution keeps its integral at every beta_n (roughness widens it, it does not
/// absorb).
#[test]
fn slide_21s_roughness_factor_removes_trt_energy() {
    let rule = gauss_legendre(16);
    let c = ExpCosCoefficients::PUBLISHED_D_TRT;
    let mass = |beta_n: f64| {
        let s = frostbite_trt_scale(AzimuthalRoughness::new(beta_n).unwrap());
        let numeric = integrate(&rule, 128, -PI, PI, |phi| d_trt_frostbite(phi.cos(), s, c));
        let closed = 2.0 * PI * s * bessel_i0(17.0 * s) * (-16.78 * s).exp();
        assert!(
            (numeric - closed).abs() < 1e-12,
            "{beta_n}: {numeric} {closed}"
        );
        numeric
    };
    for (beta_n, want) in [(0.3, 0.7633), (0.6, 0.5444), (0.9, 0.2600), (1.0, 0.0)] {
        let got = mass(beta_n);
        println!("beta_n {beta_n}: int D_TRT = {got:.4}");
        assert!((got - want).abs() < 1e-4, "{beta_n}: {got}");
    }
    // Chiang's far field: int N_TRT dphi is the h-average of A_TRT, whatever beta_n (the
    // azimuthal distribution is a density); at theta_o = 0 brown hair's TRT energy changes by
    // less than 1e-3 from beta_n = 0.3 to 0.9, where Frostbite's falls to 0.34 of its value.
    let rule64 = FarFieldRule::gauss_legendre(64).unwrap();
    let energy = |beta_n: f64| {
        let far = ChiangFarField::<f64>::with_rule(&Hair { beta_n, ..BROWN }.params(), &rule64);
        integrate(&rule, 256, -PI, PI, |phi| {
            far.azimuthal(0.0, 1.0, phi).0[2][0]
        })
    };
    let (smooth, rough) = (energy(0.3), energy(0.9));
    assert!((rough / smooth - 1.0).abs() < 1e-3, "{smooth} {rough}");
    let ratio = mass(0.9) / mass(0.3);
    assert!((ratio - 0.3406).abs() < 1e-3, "{ratio}");
}
