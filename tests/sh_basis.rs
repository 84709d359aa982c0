//! Spherical harmonic evaluation, projection and windowing: the convention pinned by golden
//! Cartesian polynomials, multiply counts against Sloan 2013, accuracy at l = 1000,
//! orthonormality by quadrature, exact projection of band-limited functions, environment
//! maps, and the effect of windowing on ringing.

use glam::DVec3;
use hairmath::quadrature::{gauss_legendre, integrate};
use hairmath::real::Binary;
use hairmath::real::{trace, Traced};
use hairmath::sh::{apply_window, hanning, lanczos};
use hairmath::sh::{
    cube_texel_direction, lat_long_direction, project, project_cube_map, project_lat_long,
    project_with_nodes, reconstruct,
};
use hairmath::sh::{
    eval_sh, eval_sh_f64, eval_sh_f64_into, eval_sh_into, MAX_FAST_BANDS, MAX_LMAX,
};
use hairmath::ParamError;
use proptest::prelude::*;
use rand::{Rng, SeedableRng};
use rand_pcg::Pcg64;
use std::f64::consts::PI;

fn random_dirs(n: usize, seed: u64) -> Vec<DVec3> {
    let mut rng = Pcg64::seed_from_u64(seed);
    let mut v: Vec<DVec3> = (0..n)
        .map(|_| {
            let z: f64 = rng.random_range(-1.0..1.0);
            let phi: f64 = rng.random_range(0.0..2.0 * PI);
            let s = (1.0 - z * z).sqrt();
            DVec3::new(s * phi.cos(), s * phi.sin(), z)
        })
        .collect();
    v.extend([DVec3::Z, -DVec3::Z, DVec3::X, DVec3::Y, -DVec3::X]);
    v
}

/// The real SH of bands 0..3 written as Cartesian polynomials with exact constants.
fn golden(d: DVec3) -> [f64; 16] {
    let (x, y, z) = (d.x, d.y, d.z);
    let s = |v: f64| v.sqrt();
    [
        0.5 / s(PI),
        -s(3.0 / (4.0 * PI)) * y,
        s(3.0 / (4.0 * PI)) * z,
        -s(3.0 / (4.0 * PI)) * x,
        0.5 * s(15.0 / PI) * x * y,
        -0.5 * s(15.0 / PI) * y * z,
        0.25 * s(5.0 / PI) * (3.0 * z * z - 1.0),
        -0.5 * s(15.0 / PI) * x * z,
        0.25 * s(15.0 / PI) * (x * x - y * y),
        -0.25 * s(35.0 / (2.0 * PI)) * y * (3.0 * x * x - y * y),
        0.5 * s(105.0 / PI) * x * y * z,
        -0.25 * s(21.0 / (2.0 * PI)) * y * (5.0 * z * z - 1.0),
        0.25 * s(7.0 / PI) * (5.0 * z * z * z - 3.0 * z),
        -0.25 * s(21.0 / (2.0 * PI)) * x * (5.0 * z * z - 1.0),
        0.25 * s(105.0 / PI) * z * (x * x - y * y),
        -0.25 * s(35.0 / (2.0 * PI)) * x * (x * x - 3.0 * y * y),
    ]
}

#[test]
fn golden_cartesian_polynomials_pin_the_convention() {
    // The published decimals (Sloan 2013, google/spherical-harmonics) agree with the exact
    // constants.
    let g = golden(DVec3::new(0.0, 1.0, 0.0));
    assert!((g[1] + 0.4886025).abs() < 1e-7);
    let g = golden(DVec3::new(0.5f64.sqrt(), 0.5f64.sqrt(), 0.0));
    assert!((g[4] - 1.0925484 * 0.5).abs() < 1e-7);
    assert!((golden(DVec3::Z)[0] - 0.2820948).abs() < 1e-7);
    for d in random_dirs(200, 1) {
        let want = golden(d);
        let fast: [f64; 16] = eval_sh(d.x, d.y, d.z);
        let general = eval_sh_f64(3, d).unwrap();
        for i in 0..16 {
            assert!((fast[i] - want[i]).abs() < 1e-14, "fast {i} at {d}");
            assert!((general[i] - want[i]).abs() < 1e-14, "general {i} at {d}");
        }
    }
}

#[test]
fn fast_evaluator_matches_general_recurrence_in_all_precisions() {
    for d in random_dirs(300, 2) {
        let want = eval_sh_f64(MAX_FAST_BANDS - 1, d).unwrap();
        let f64s: [f64; 100] = eval_sh(d.x, d.y, d.z);
        let f32s: [f32; 100] = eval_sh(d.x as f32, d.y as f32, d.z as f32);
        let lanes: [wide::f32x8; 100] = eval_sh(
            wide::f32x8::splat(d.x as f32),
            wide::f32x8::splat(d.y as f32),
            wide::f32x8::splat(d.z as f32),
        );
        for i in 0..100 {
            assert!((f64s[i] - want[i]).abs() < 1e-13, "f64 {i} at {d}");
            assert!((f32s[i] as f64 - want[i]).abs() < 2e-5, "f32 {i} at {d}");
            for lane in lanes[i].to_array() {
                assert!((lane - f32s[i]).abs() <= 1e-6 * (1.0 + f32s[i].abs()));
            }
        }
        let mut buf = [0.0f64; 49];
        eval_sh_into(7, d.x, d.y, d.z, &mut buf).unwrap();
        assert_eq!(&buf[..], &f64s[..49]);
    }
}

fn traced_graph<const N: usize>() -> hairmath::real::Graph {
    trace(3, |a| eval_sh::<Traced, N>(a[0], a[1], a[2]).to_vec())
}

#[test]
fn multiply_counts_are_at_most_sloans() {
    let counts = [
        traced_graph::<1>().count_binary(Binary::Mul),
        traced_graph::<4>().count_binary(Binary::Mul),
        traced_graph::<9>().count_binary(Binary::Mul),
        traced_graph::<16>().count_binary(Binary::Mul),
        traced_graph::<25>().count_binary(Binary::Mul),
        traced_graph::<36>().count_binary(Binary::Mul),
        traced_graph::<49>().count_binary(Binary::Mul),
        traced_graph::<64>().count_binary(Binary::Mul),
        traced_graph::<81>().count_binary(Binary::Mul),
        traced_graph::<100>().count_binary(Binary::Mul),
    ];
    for (b, c) in counts.iter().enumerate() {
        println!("{} bands: {c} multiplies", b + 1);
    }
    // Sloan 2013, table 1: 3, 4, 5, 6 bands.
    for (bands, sloan) in [(3, 14), (4, 28), (5, 47), (6, 71)] {
        assert!(
            counts[bands - 1] <= sloan,
            "{bands} bands: {}",
            counts[bands - 1]
        );
    }
    assert_eq!(&counts[..8], &[0, 3, 14, 28, 46, 69, 97, 130]);
    // No division, no transcendental function in the traced code.
    let g = traced_graph::<64>();
    assert_eq!(g.count_binary(Binary::Div), 0);
    assert!(g
        .nodes()
        .iter()
        .all(|n| !matches!(n, hairmath::real::Node::Unary(op, _)
            if *op != hairmath::real::Unary::Neg)));
}

#[test]
fn traced_graph_reproduces_f32_bit_for_bit_and_prints_wgsl() {
    let g = traced_graph::<64>();
    for d in random_dirs(50, 3) {
        let (x, y, z) = (d.x as f32, d.y as f32, d.z as f32);
        let want: [f32; 64] = eval_sh(x, y, z);
        let got = g.eval_f32(&[x, y, z]);
        for i in 0..64 {
            assert_eq!(got[i].to_bits(), want[i].to_bits(), "coefficient {i}");
        }
    }
    let wgsl = g.to_wgsl("sh_eval_8");
    assert!(wgsl.starts_with("fn sh_eval_8(x0: f32, x1: f32, x2: f32) -> array<f32, 64> {"));
}

/// P_l(t) by the three-term recurrence (an evaluation independent of the normalised one).
/// `gap = 1 - |t|` is passed separately: near the poles `t p` is formed as `+-(p - gap p)`,
/// since merely rounding t there is a systematic error that the recurrence amplifies by l^2.
fn legendre(l: usize, t: f64, gap: f64) -> f64 {
    let (mut p0, mut p1) = (1.0, t);
    if l == 0 {
        return 1.0;
    }
    let t_times = |p: f64| {
        if t > 0.7 {
            p - gap * p
        } else if t < -0.7 {
            gap * p - p
        } else {
            t * p
        }
    };
    for k in 1..l {
        let p2 = ((2 * k + 1) as f64 * t_times(p1) - k as f64 * p0) / (k + 1) as f64;
        p0 = p1;
        p1 = p2;
    }
    p1
}

#[test]
fn general_evaluator_is_accurate_at_l_1000() {
    let lmax = 1000;
    // Poles: only m = 0 survives, Y_l0(+-z) = (+-1)^l sqrt((2l+1)/(4 pi)).
    for (d, sign) in [(DVec3::Z, 1.0), (-DVec3::Z, -1.0)] {
        let y = eval_sh_f64(lmax, d).unwrap();
        for l in 0..=lmax {
            let want = sign_pow(sign, l) * ((2 * l + 1) as f64 / (4.0 * PI)).sqrt();
            let c = l * (l + 1);
            assert!(
                (y[c] - want).abs() <= 1e-11 * want.abs(),
                "l {l}: {} vs {want}, rel {:e}",
                y[c],
                (y[c] - want) / want
            );
            for (i, &v) in y.iter().enumerate().take(c + l + 1).skip(c - l) {
                if i != c {
                    assert_eq!(v, 0.0, "pole, l {l}");
                }
            }
        }
    }
    let mut worst_m0 = 0.0f64;
    let mut worst_add = 0.0f64;
    let mut dirs = random_dirs(6, 4);
    dirs.push(DVec3::new(1e-3, 0.0, 1.0)); // near the pole
    dirs.push(DVec3::new(1.0, 1e-9, 1e-12)); // on the equator
    for d in dirs {
        let y = eval_sh_f64(lmax, d).unwrap();
        let n = d.normalize();
        let t = n.z;
        let gap = (n.x * n.x + n.y * n.y) / (1.0 + t.abs());
        for l in [0, 1, 2, 10, 100, 500, 999, 1000] {
            let scale = ((2 * l + 1) as f64 / (4.0 * PI)).sqrt();
            let want = scale * legendre(l, t, gap);
            worst_m0 = worst_m0.max((y[l * (l + 1)] - want).abs() / scale);
        }
        for l in 0..=lmax {
            let sum: f64 = y[l * l..(l + 1) * (l + 1)].iter().map(|v| v * v).sum();
            let want = (2 * l + 1) as f64 / (4.0 * PI);
            let e = (sum - want).abs() / want;
            worst_add = worst_add.max(e);
        }
    }
    println!("l <= 1000: m = 0 vs Legendre recurrence {worst_m0:.2e} (relative to sqrt((2l+1)/4pi)); addition theorem {worst_add:.2e}");
    assert!(worst_m0 < 1e-11, "{worst_m0}");
    assert!(worst_add < 1e-11, "{worst_add}");
}

fn sign_pow(sign: f64, l: usize) -> f64 {
    if sign < 0.0 && l % 2 == 1 {
        -1.0
    } else {
        1.0
    }
}

#[test]
fn basis_is_orthonormal_by_quadrature_to_l_30() {
    let lmax = 30;
    let n = (lmax + 1) * (lmax + 1);
    let nphi = 2 * lmax + 2;
    let mut gram = vec![0.0; n * n];
    let mut y = vec![0.0; n];
    for (z, wz) in gauss_legendre(lmax + 1) {
        let s = (1.0 - z * z).sqrt();
        for j in 0..nphi {
            let phi = 2.0 * PI * (j as f64 + 0.3) / nphi as f64;
            eval_sh_f64_into(lmax, DVec3::new(s * phi.cos(), s * phi.sin(), z), &mut y).unwrap();
            let w = wz * 2.0 * PI / nphi as f64;
            for a in 0..n {
                let wa = w * y[a];
                for b in a..n {
                    gram[a * n + b] += wa * y[b];
                }
            }
        }
    }
    let mut worst = 0.0f64;
    for a in 0..n {
        for b in a..n {
            let want = if a == b { 1.0 } else { 0.0 };
            worst = worst.max((gram[a * n + b] - want).abs());
        }
    }
    println!("orthonormality error, l <= 30: {worst:.2e}");
    assert!(worst < 1e-12, "{worst}");
}

#[test]
fn projection_recovers_band_limited_coefficients() {
    let mut rng = Pcg64::seed_from_u64(5);
    for lmax in [0, 1, 4, 12] {
        let n = (lmax + 1) * (lmax + 1);
        let c: Vec<f64> = (0..n).map(|_| rng.random_range(-1.0..1.0)).collect();
        let f = |d: DVec3| reconstruct(&c, d).unwrap();
        let got = project(lmax, f).unwrap();
        let err = got
            .iter()
            .zip(&c)
            .fold(0.0f64, |a, (g, w)| a.max((g - w).abs()));
        assert!(err < 1e-12, "lmax {lmax}: {err}");
        // Projecting onto fewer bands than the function has drops the rest exactly
        // (with enough nodes for the product's band limit).
        if lmax >= 4 {
            let low = project_with_nodes(2, lmax + 2, 2 * lmax + 3, f).unwrap();
            let err = low
                .iter()
                .zip(&c)
                .fold(0.0f64, |a, (g, w)| a.max((g - w).abs()));
            assert!(err < 1e-12, "truncated lmax {lmax}: {err}");
        }
    }
}

#[test]
fn constant_environment_maps_give_sqrt_four_pi() {
    let c = 0.75f32;
    let (w, h) = (64, 32);
    let data: Vec<f32> = (0..w * h).flat_map(|_| [c, 2.0 * c, 0.0]).collect();
    let ll = project_lat_long(4, w, h, 3, &data).unwrap();
    let want = (4.0 * PI).sqrt() * c as f64;
    assert!((ll[0][0] - want).abs() < 1e-12, "{}", ll[0][0]);
    assert!((ll[1][0] - 2.0 * want).abs() < 1e-12);
    assert!(ll[2].iter().all(|&v| v == 0.0));
    let leak_ll = ll[0][1..].iter().fold(0.0f64, |a, v| a.max(v.abs()));
    let size = 16;
    let cube: Vec<f32> = vec![c; 6 * size * size];
    let cm = project_cube_map(4, size, 1, &cube).unwrap();
    assert!((cm[0][0] - want).abs() < 1e-12, "{}", cm[0][0]);
    let leak_cm = cm[0][1..].iter().fold(0.0f64, |a, v| a.max(v.abs()));
    println!(
        "constant map: higher-band leakage lat-long 64x32 {leak_ll:.2e}, cube 6x16^2 {leak_cm:.2e}"
    );
    // Discretisation error O((lmax / resolution)^2).
    assert!(leak_ll < 1e-2 && leak_cm < 1e-2);
}

#[test]
fn environment_maps_project_a_band_limited_function_up_to_resolution() {
    // f = Y_2,1 + 0.5 Y_1,-1 sampled into the maps; coefficient errors fall like 1/resolution^2.
    let f = |d: DVec3| {
        let y = eval_sh_f64(2, d).unwrap();
        y[7] + 0.5 * y[1]
    };
    let mut errs = vec![];
    for res in [16usize, 64] {
        let data: Vec<f32> = (0..res)
            .flat_map(|j| (0..2 * res).map(move |i| (i, j)))
            .map(|(i, j)| f(lat_long_direction(2 * res, res, i, j)) as f32)
            .collect();
        let ll = project_lat_long(2, 2 * res, res, 1, &data).unwrap();
        let mut want = vec![0.0; 9];
        want[7] = 1.0;
        want[1] = 0.5;
        let e_ll = ll[0]
            .iter()
            .zip(&want)
            .fold(0.0f64, |a, (g, w)| a.max((g - w).abs()));
        let cube: Vec<f32> = (0..6)
            .flat_map(|face| (0..res).flat_map(move |j| (0..res).map(move |i| (face, i, j))))
            .map(|(face, i, j)| f(cube_texel_direction(face, res, i, j)) as f32)
            .collect();
        let cm = project_cube_map(2, res, 1, &cube).unwrap();
        let e_cm = cm[0]
            .iter()
            .zip(&want)
            .fold(0.0f64, |a, (g, w)| a.max((g - w).abs()));
        println!("resolution {res}: lat-long error {e_ll:.2e}, cube error {e_cm:.2e}");
        errs.push((e_ll, e_cm));
    }
    assert!(errs[1].0 < 2e-3 && errs[1].1 < 2e-3);
    assert!(errs[1].0 < errs[0].0 / 8.0 && errs[1].1 < errs[0].1 / 8.0);
}

#[test]
fn windowing_reduces_the_overshoot_of_a_step() {
    // f = 1 for z > 0, 0 below: zonal, c_l0 = 2 pi int_0^1 Y_l0(z) dz (exact for polynomials).
    let lmax = 8;
    let rule = gauss_legendre(16);
    let n = (lmax + 1) * (lmax + 1);
    let mut c = vec![0.0; n];
    for l in 0..=lmax {
        c[l * (l + 1)] = 2.0
            * PI
            * integrate(&rule, 1, 0.0, 1.0, |z| {
                let y = eval_sh_f64(lmax, DVec3::new((1.0 - z * z).sqrt(), 0.0, z)).unwrap();
                y[l * (l + 1)]
            });
    }
    let overshoot = |coeffs: &[f64]| {
        (0..=2000)
            .map(|k| {
                let z = -1.0 + k as f64 / 1000.0;
                reconstruct(coeffs, DVec3::new((1.0 - z * z).max(0.0).sqrt(), 0.0, z)).unwrap()
            })
            .fold(f64::MIN, f64::max)
            - 1.0
    };
    let raw = overshoot(&c);
    let mut han = c.clone();
    apply_window(&mut han, &hanning(lmax, (lmax + 1) as f64).unwrap()).unwrap();
    let mut lan = c.clone();
    apply_window(&mut lan, &lanczos(lmax, (lmax + 1) as f64).unwrap()).unwrap();
    let (han, lan) = (overshoot(&han), overshoot(&lan));
    println!("step at lmax = 8: overshoot unwindowed {raw:.4}, Hanning {han:.4}, Lanczos {lan:.4}");
    assert!(raw > 0.05, "{raw}");
    assert!(han < raw && lan < raw);
}

#[test]
fn invalid_input_is_a_typed_error() {
    assert!(matches!(
        eval_sh_f64(MAX_LMAX + 1, DVec3::Z),
        Err(ParamError::OutOfRange { .. })
    ));
    assert!(matches!(
        eval_sh_f64(3, DVec3::ZERO),
        Err(ParamError::BadVector { .. })
    ));
    assert!(eval_sh_f64(3, DVec3::new(f64::NAN, 0.0, 1.0)).is_err());
    let mut short = [0.0; 8];
    assert!(eval_sh_f64_into(2, DVec3::Z, &mut short).is_err());
    assert!(eval_sh_into(3, 0.0, 0.0, 1.0, &mut short).is_err());
    let mut big = [0.0f32; 200];
    assert!(eval_sh_into(MAX_FAST_BANDS + 1, 0.0, 0.0, 1.0, &mut big).is_err());
    assert!(reconstruct(&[1.0, 2.0], DVec3::Z).is_err());
    assert!(project_lat_long(2, 4, 2, 3, &[0.0; 23]).is_err());
    assert!(project_lat_long(2, 0, 2, 1, &[]).is_err());
    assert!(project_cube_map(2, 2, 1, &[0.0; 23]).is_err());
    assert!(project_cube_map(2, 0, 1, &[]).is_err());
    assert!(project_with_nodes(2, 0, 5, |_| 1.0).is_err());
    assert!(hanning(2, -1.0).is_err());
}

fn unit_vector() -> impl Strategy<Value = DVec3> {
    prop_oneof![
        (-1.0f64..=1.0, 0.0f64..(2.0 * PI)).prop_map(|(z, phi)| {
            let s = (1.0 - z * z).max(0.0).sqrt();
            DVec3::new(s * phi.cos(), s * phi.sin(), z)
        }),
        Just(DVec3::Z),
        Just(-DVec3::Z),
        (-1e-12f64..1e-12, -1e-12f64..1e-12).prop_map(|(x, y)| DVec3::new(x, y, 1.0).normalize()),
    ]
}

proptest! {
    #[test]
    fn outputs_are_finite_and_bounded(d in unit_vector()) {
        let fast: [f32; 100] = eval_sh(d.x as f32, d.y as f32, d.z as f32);
        let fast64: [f64; 100] = eval_sh(d.x, d.y, d.z);
        let general = eval_sh_f64(60, d).unwrap();
        for l in 0..=60usize {
            // |Y_lm| <= sqrt((2l + 1) / (4 pi)) by the addition theorem.
            let bound = ((2 * l + 1) as f64 / (4.0 * PI)).sqrt() * (1.0 + 1e-6);
            for i in l * l..(l + 1) * (l + 1) {
                prop_assert!(general[i].is_finite() && general[i].abs() <= bound);
                if l < MAX_FAST_BANDS {
                    prop_assert!(fast[i].is_finite() && (fast[i].abs() as f64) <= bound + 1e-5);
                    prop_assert!((fast64[i] - general[i]).abs() < 1e-13);
                }
            }
        }
    }
}
