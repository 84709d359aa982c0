//! SH rotation: the band-1 closed form, the written-out band 2 (multiply count by tracing),
//! Ivanic-Ruedenberg to l = 30 (orthogonality, determinant, composition, the point identity
//! `g(x) = f(R^T x)`), near-gimbal rotations, zonal rotation, and typed errors.

use glam::{DMat3, DQuat, DVec3};
use hairmath::real::Binary;
use hairmath::real::{trace, Real, Traced};
use hairmath::sh::reconstruct;
use hairmath::sh::{
    check_rotation, rotate_band1, rotate_band2, rotate_bands012, rotate_low_order, rotate_zonal,
    rotate_zonal_into, rotation_z_to, ShRotation, MAX_ROTATION_LMAX,
};
use hairmath::sh::{eval_sh, eval_sh_f64};
use hairmath::ParamError;
use proptest::prelude::*;
use rand::{Rng, SeedableRng};
use rand_pcg::Pcg64;
use std::f64::consts::{FRAC_PI_2, PI};

/// Uniformly distributed rotation (Shoemake's method).
fn random_rotation(rng: &mut Pcg64) -> DMat3 {
    let (u1, u2, u3): (f64, f64, f64) = (rng.random(), rng.random(), rng.random());
    let (a, b) = ((1.0 - u1).sqrt(), u1.sqrt());
    let q = DQuat::from_xyzw(
        a * (2.0 * PI * u2).sin(),
        a * (2.0 * PI * u2).cos(),
        b * (2.0 * PI * u3).sin(),
        b * (2.0 * PI * u3).cos(),
    );
    DMat3::from_quat(q.normalize())
}

fn euler_zyz(a: f64, b: f64, c: f64) -> DMat3 {
    DMat3::from_rotation_z(a) * DMat3::from_rotation_y(b) * DMat3::from_rotation_z(c)
}

/// Random rotations plus near-gimbal ones: tiny angles, exact 90-degree Euler steps, pi.
fn rotations(seed: u64, n: usize) -> Vec<DMat3> {
    let mut rng = Pcg64::seed_from_u64(seed);
    let mut v: Vec<DMat3> = (0..n).map(|_| random_rotation(&mut rng)).collect();
    // Exact 90-degree steps (signed permutation matrices, exactly orthogonal).
    let rx90 = DMat3::from_cols(DVec3::X, DVec3::Z, -DVec3::Y);
    let rz90 = DMat3::from_cols(DVec3::Y, -DVec3::X, DVec3::Z);
    v.extend([
        DMat3::IDENTITY,
        rx90,
        rz90,
        rz90 * rx90 * rz90,
        rx90 * rz90 * rz90 * rx90,
        euler_zyz(0.3, 1e-8, -0.7),
        euler_zyz(1.1, FRAC_PI_2, 0.4),
        euler_zyz(0.0, PI - 1e-8, 2.0),
        euler_zyz(1e-8, 1e-8, 1e-8),
        DMat3::from_axis_angle(DVec3::new(1.0, 2.0, 3.0).normalize(), 1e-8),
        DMat3::from_axis_angle(DVec3::new(-1.0, 0.5, 0.2).normalize(), PI),
    ]);
    v
}

fn rows(r: DMat3) -> [[f64; 3]; 3] {
    check_rotation(r).unwrap()
}

#[test]
fn band1_is_the_permuted_matrix_with_condon_shortley_signs() {
    for r in rotations(1, 20) {
        let rot = ShRotation::new(r, 1).unwrap();
        let d1 = rot.band(1).unwrap();
        let m = rows(r);
        // (y, z, x) order, conjugated by diag(-1, 1, -1).
        let want = [
            m[1][1], -m[1][2], m[1][0], -m[2][1], m[2][2], -m[2][0], m[0][1], -m[0][2], m[0][0],
        ];
        for i in 0..9 {
            assert!((d1[i] - want[i]).abs() < 1e-15, "entry {i}");
        }
        let c = [0.3, -1.2, 0.7];
        let got = rotate_band1(&m, c);
        for i in 0..3 {
            let w: f64 = (0..3).map(|j| want[i * 3 + j] * c[j]).sum();
            assert!((got[i] - w).abs() < 1e-15);
        }
    }
}

#[test]
fn written_out_band2_matches_ivanic_ruedenberg() {
    let mut rng = Pcg64::seed_from_u64(2);
    for r in rotations(2, 50) {
        let rot = ShRotation::new(r, 2).unwrap();
        let c: [f64; 9] = core::array::from_fn(|_| rng.random_range(-1.0..1.0));
        let want = rot.apply(&c).unwrap();
        let got = rotate_bands012(&rows(r), c);
        let low = rotate_low_order(r, c).unwrap();
        for i in 0..9 {
            assert!((got[i] - want[i]).abs() < 1e-14, "coefficient {i}");
            assert_eq!(got[i], low[i]);
        }
        let b2 = rotate_band2(&rows(r), [c[4], c[5], c[6], c[7], c[8]]);
        assert_eq!(&b2[..], &got[4..]);
    }
}

#[test]
fn band2_rotation_multiply_count_beats_published_anchors() {
    let graph = |f: fn(&[[Traced; 3]; 3], &[Traced]) -> Vec<Traced>, n: usize| {
        trace(9 + n, |a| {
            let r = [[a[0], a[1], a[2]], [a[3], a[4], a[5]], [a[6], a[7], a[8]]];
            f(&r, &a[9..])
        })
    };
    let all = graph(
        |r, c| rotate_bands012(r, core::array::from_fn(|i| c[i])).to_vec(),
        9,
    );
    let b2 = graph(
        |r, c| rotate_band2(r, core::array::from_fn(|i| c[i])).to_vec(),
        5,
    );
    let b1 = graph(
        |r, c| rotate_band1(r, core::array::from_fn(|i| c[i])).to_vec(),
        3,
    );
    let (n_all, n2, n1) = (
        all.count_binary(Binary::Mul),
        b2.count_binary(Binary::Mul),
        b1.count_binary(Binary::Mul),
    );
    println!(
        "rotation multiplies: band 1 {n1}, band 2 {n2}, bands 0..2 {n_all} (anchors 57 to 93)"
    );
    assert!(n_all <= 57, "{n_all}");
    assert_eq!((n1, n2, n_all), (9, 36, 45));
    // The traced graph computes exactly what the f32 code computes.
    let mut rng = Pcg64::seed_from_u64(3);
    for r in rotations(3, 10) {
        let m = rows(r);
        let m32: [[f32; 3]; 3] = m.map(|row| row.map(|v| v as f32));
        let c: [f32; 9] = core::array::from_fn(|_| rng.random_range(-1.0..1.0));
        let want = rotate_bands012(&m32, c);
        let mut inputs: Vec<f32> = m32.iter().flatten().copied().collect();
        inputs.extend(c);
        let got = all.eval_f32(&inputs);
        for i in 0..9 {
            assert_eq!(got[i].to_bits(), want[i].to_bits());
        }
    }
    assert!(all.to_wgsl("sh_rotate_9").contains("array<f32, 9>"));
}

fn matmul(a: &[f64], b: &[f64], w: usize) -> Vec<f64> {
    let mut out = vec![0.0; w * w];
    for i in 0..w {
        for k in 0..w {
            let aik = a[i * w + k];
            for j in 0..w {
                out[i * w + j] += aik * b[k * w + j];
            }
        }
    }
    out
}

/// Determinant by Gaussian elimination with partial pivoting.
fn det(mut a: Vec<f64>, w: usize) -> f64 {
    let mut d = 1.0;
    for col in 0..w {
        let p = (col..w)
            .max_by(|&i, &j| a[i * w + col].abs().total_cmp(&a[j * w + col].abs()))
            .unwrap();
        if p != col {
            for j in 0..w {
                a.swap(p * w + j, col * w + j);
            }
            d = -d;
        }
        let piv = a[col * w + col];
        d *= piv;
        for i in col + 1..w {
            let f = a[i * w + col] / piv;
            for j in col..w {
                a[i * w + j] -= f * a[col * w + j];
            }
        }
    }
    d
}

#[test]
fn bands_are_orthogonal_with_unit_determinant_and_compose_to_l_30() {
    let lmax = 30;
    let rs = rotations(4, 6);
    let mut worst_orth = 0.0f64;
    let mut worst_det = 0.0f64;
    let mut worst_comp = 0.0f64;
    for (k, &r1) in rs.iter().enumerate() {
        let r2 = rs[(k * 7 + 3) % rs.len()];
        let d1 = ShRotation::new(r1, lmax).unwrap();
        let d2 = ShRotation::new(r2, lmax).unwrap();
        let d12 = ShRotation::new(r1 * r2, lmax).unwrap();
        for l in 0..=lmax {
            let w = 2 * l + 1;
            let a = d1.band(l).unwrap();
            let at: Vec<f64> = (0..w * w).map(|i| a[(i % w) * w + i / w]).collect();
            let ata = matmul(&at, a, w);
            for i in 0..w {
                for j in 0..w {
                    let want = if i == j { 1.0 } else { 0.0 };
                    worst_orth = worst_orth.max((ata[i * w + j] - want).abs());
                }
            }
            if l <= 30 {
                worst_det = worst_det.max((det(a.to_vec(), w) - 1.0).abs());
            }
            let prod = matmul(a, d2.band(l).unwrap(), w);
            let want = d12.band(l).unwrap();
            for i in 0..w * w {
                worst_comp = worst_comp.max((prod[i] - want[i]).abs());
            }
        }
    }
    println!("l <= 30: |D^T D - I| {worst_orth:.2e}, |det - 1| {worst_det:.2e}, |D(R1 R2) - D(R1) D(R2)| {worst_comp:.2e}");
    assert!(worst_orth < 1e-12 && worst_det < 1e-12 && worst_comp < 1e-12);
}

#[test]
fn rotated_coefficients_satisfy_the_point_identity_to_l_30() {
    let lmax = 30;
    let n = (lmax + 1) * (lmax + 1);
    let mut rng = Pcg64::seed_from_u64(5);
    let mut worst = 0.0f64;
    for r in rotations(6, 8) {
        let raw: Vec<f64> = (0..n).map(|_| rng.random_range(-1.0..1.0)).collect();
        let norm = raw.iter().map(|v| v * v).sum::<f64>().sqrt();
        let c: Vec<f64> = raw.iter().map(|v| v / norm).collect();
        let rotated = ShRotation::new(r, lmax).unwrap().apply(&c).unwrap();
        for _ in 0..20 {
            let x = DVec3::new(
                rng.random_range(-1.0..1.0),
                rng.random_range(-1.0..1.0),
                rng.random_range(-1.0..1.0),
            )
            .normalize();
            let lhs = reconstruct(&rotated, x).unwrap();
            let rhs = reconstruct(&c, r.transpose() * x).unwrap();
            worst = worst.max((lhs - rhs).abs());
        }
        for x in [DVec3::Z, -DVec3::Z, DVec3::X] {
            let lhs = reconstruct(&rotated, x).unwrap();
            let rhs = reconstruct(&c, r.transpose() * x).unwrap();
            worst = worst.max((lhs - rhs).abs());
        }
    }
    println!("point identity at l = 30 (unit coefficient vector): {worst:.2e}");
    assert!(worst < 1e-12, "{worst}");
}

#[test]
fn zonal_rotation_matches_the_full_rotation() {
    let zonal = [1.0, 0.5, -0.25, 0.125, 0.3, -0.1, 0.05];
    let lmax = zonal.len() - 1;
    let mut full = vec![0.0; (lmax + 1) * (lmax + 1)];
    for (l, &z) in zonal.iter().enumerate() {
        full[l * (l + 1)] = z;
    }
    let mut rng = Pcg64::seed_from_u64(7);
    let mut dirs: Vec<DVec3> = (0..20)
        .map(|_| {
            DVec3::new(
                rng.random_range(-1.0..1.0),
                rng.random_range(-1.0..1.0),
                rng.random_range(-1.0..1.0),
            )
            .normalize()
        })
        .collect();
    // (glam's from_rotation_arc snaps directions within about 1e-6 of -z to an exact half turn,
    // so the reference rotation is only tested at -z itself and 1e-3 away.)
    dirs.extend([
        DVec3::Z,
        DVec3::X,
        -DVec3::Z,
        DVec3::new(1e-3, 0.0, -1.0).normalize(),
    ]);
    for d in dirs {
        let fast = rotate_zonal(&zonal, d).unwrap();
        let want = ShRotation::new(rotation_z_to(d).unwrap(), lmax)
            .unwrap()
            .apply(&full)
            .unwrap();
        let mut generic = [0.0f32; 49];
        let z32 = zonal.map(|v| v as f32);
        rotate_zonal_into(&z32, d.x as f32, d.y as f32, d.z as f32, &mut generic).unwrap();
        for i in 0..full.len() {
            assert!((fast[i] - want[i]).abs() < 1e-13, "{i} at {d}");
            assert!((generic[i] as f64 - want[i]).abs() < 1e-5);
        }
        // The rotated lobe is centred on d: its value at d equals the zonal value at +z.
        let at_d = reconstruct(&fast, d).unwrap();
        let at_z = reconstruct(&full, DVec3::Z).unwrap();
        assert!((at_d - at_z).abs() < 1e-13);
    }
}

#[test]
fn invalid_rotations_and_sizes_are_typed_errors() {
    let bad = |r: DMat3| matches!(ShRotation::new(r, 3), Err(ParamError::OutOfRange { .. }));
    assert!(bad(DMat3::from_diagonal(DVec3::new(1.0, 1.0, -1.0)))); // reflection
    assert!(bad(DMat3::from_diagonal(DVec3::new(1.0, 1.0, 1.001)))); // not orthogonal
    assert!(bad(DMat3::from_cols(
        DVec3::X,
        DVec3::Y,
        DVec3::new(0.0, 1e-3, 1.0)
    )));
    assert!(bad(DMat3::from_diagonal(DVec3::new(f64::NAN, 1.0, 1.0))));
    assert!(bad(DMat3::ZERO));
    assert!(ShRotation::new(DMat3::IDENTITY, MAX_ROTATION_LMAX + 1).is_err());
    // Orthogonal within 1e-6 is accepted.
    assert!(ShRotation::new(DMat3::from_diagonal(DVec3::new(1.0, 1.0, 1.0 + 1e-7)), 2).is_ok());
    let rot = ShRotation::new(DMat3::IDENTITY, 2).unwrap();
    assert!(rot.apply(&[0.0; 5]).is_err()); // not a square length
    assert!(rot.apply(&[0.0; 16]).is_err()); // more bands than the rotation holds
    assert_eq!(rot.apply(&[1.0; 4]).unwrap(), vec![1.0; 4]);
    let mut out = [0.0; 3];
    assert!(rot.apply_into(&[0.0; 4], &mut out).is_err());
    assert!(rotate_low_order(DMat3::ZERO, [0.0; 9]).is_err());
    assert!(rotate_zonal(&[], DVec3::Z).is_err());
    assert!(rotate_zonal(&[1.0], DVec3::ZERO).is_err());
    let mut small = [0.0f64; 3];
    assert!(rotate_zonal_into(&[1.0, 1.0], 0.0, 0.0, 1.0, &mut small).is_err());
    assert!(rotation_z_to(DVec3::new(f64::INFINITY, 0.0, 0.0)).is_err());
}

fn quat() -> impl Strategy<Value = DMat3> {
    (-1.0f64..1.0, -1.0f64..1.0, -1.0f64..1.0, -1.0f64..1.0).prop_filter_map(
        "non-zero quaternion",
        |(x, y, z, w)| {
            let q = DQuat::from_xyzw(x, y, z, w);
            (q.length() > 1e-3).then(|| DMat3::from_quat(q.normalize()))
        },
    )
}

proptest! {
    #[test]
    fn any_rotation_gives_finite_orthogonal_blocks(r in quat(), dir in (-1.0f64..1.0, -1.0f64..1.0, -1.0f64..1.0)) {
        let rot = ShRotation::new(r, 6).unwrap();
        for l in 0..=6 {
            let w = 2 * l + 1;
            let a = rot.band(l).unwrap();
            prop_assert!(a.iter().all(|v| v.is_finite()));
            for i in 0..w {
                let norm: f64 = a[i * w..(i + 1) * w].iter().map(|v| v * v).sum();
                prop_assert!((norm - 1.0).abs() < 1e-12);
            }
        }
        // Point identity for bands 0..2 through the written-out path, generic in f32.
        let d = DVec3::new(dir.0, dir.1, dir.2);
        if d.length() > 1e-3 {
            let d = d.normalize();
            let c: [f64; 9] = core::array::from_fn(|i| (i as f64 * 0.37).sin());
            let rotated = rotate_low_order(r, c).unwrap();
            let e: [f64; 9] = eval_sh(d.x, d.y, d.z);
            let back = r.transpose() * d;
            let e0 = eval_sh_f64(2, back).unwrap();
            let lhs: f64 = rotated.iter().zip(&e).map(|(a, b)| a * b).sum();
            let rhs: f64 = c.iter().zip(&e0).map(|(a, b)| a * b).sum();
            prop_assert!((lhs - rhs).abs() < 1e-12);
            let m32 = check_rotation(r).unwrap().map(|row| row.map(|v| v as f32));
            let r32 = rotate_bands012(&m32, c.map(|v| v as f32));
            prop_assert!(r32.iter().all(|v| Real::abs(*v).is_finite()));
        }
    }
}
