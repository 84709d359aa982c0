//! Gaunt coefficients and SH products against quadrature with an independent SH evaluation;
//! traced product code against the f32 instantiation; multiply counts against Snyder 2006.

use hairmath::quadrature::gauss_legendre;
use hairmath::real::Binary;
use hairmath::real::{trace, Traced};
use hairmath::sh::{gaunt_complex, gaunt_real, index_to_lm, GauntTensor};
use hairmath::sh::{product, triple_product_integral, ProductPlan};
use rand::{Rng, SeedableRng};
use std::f64::consts::PI;

// ---------------------------------------------------------------------------------------------
// Independent SH evaluation (associated Legendre recurrences, Numerical Recipes 6.7).

/// P_l^m(x) without the Condon-Shortley phase, m >= 0.
fn legendre(l: i32, m: i32, x: f64) -> f64 {
    let s = (1.0 - x * x).max(0.0).sqrt();
    let mut pmm = 1.0;
    for i in 1..=m {
        pmm *= (2 * i - 1) as f64 * s;
    }
    if l == m {
        return pmm;
    }
    let mut pmm1 = x * (2 * m + 1) as f64 * pmm;
    for ll in (m + 2)..=l {
        let next = (x * (2 * ll - 1) as f64 * pmm1 - (ll + m - 1) as f64 * pmm) / (ll - m) as f64;
        pmm = pmm1;
        pmm1 = next;
    }
    pmm1
}

fn norm(l: i32, m: i32) -> f64 {
    let mut r = (2 * l + 1) as f64 / (4.0 * PI);
    for k in (l - m + 1)..=(l + m) {
        r /= k as f64;
    }
    r.sqrt()
}

/// Complex Y_l^m(theta, phi) with the Condon-Shortley phase, as (re, im).
fn y_complex(l: i32, m: i32, x: f64, phi: f64) -> (f64, f64) {
    let mu = m.abs();
    let mag = norm(l, mu) * legendre(l, mu, x) * if mu % 2 == 1 { -1.0 } else { 1.0 };
    let (re, im) = (mag * (mu as f64 * phi).cos(), mag * (mu as f64 * phi).sin());
    if m >= 0 {
        (re, im)
    } else {
        // Y_l^{-m} = (-1)^m conj(Y_l^m)
        let s = if mu % 2 == 1 { -1.0 } else { 1.0 };
        (s * re, -s * im)
    }
}

/// Real SH of the crate convention: sqrt(2) Re Y_l^|m| (m > 0), sqrt(2) Im Y_l^|m| (m < 0).
fn y_real(l: i32, m: i32, x: f64, phi: f64) -> f64 {
    let (re, im) = y_complex(l, m.abs(), x, phi);
    match m.signum() {
        0 => re,
        1 => 2f64.sqrt() * re,
        _ => 2f64.sqrt() * im,
    }
}

#[test]
fn independent_sh_matches_the_documented_polynomials() {
    let (x, y, z): (f64, f64, f64) = (0.36, -0.48, 0.8);
    let phi = y.atan2(x);
    let c1 = (3.0 / (4.0 * PI)).sqrt();
    assert!((y_real(1, -1, z, phi) + c1 * y).abs() < 1e-15);
    assert!((y_real(1, 0, z, phi) - c1 * z).abs() < 1e-15);
    assert!((y_real(1, 1, z, phi) + c1 * x).abs() < 1e-15);
    let c2 = 0.5 * (15.0 / PI).sqrt();
    assert!((y_real(2, -2, z, phi) - c2 * x * y).abs() < 1e-15);
    assert!((y_real(2, -1, z, phi) + c2 * y * z).abs() < 1e-15);
    assert!((y_real(2, 1, z, phi) + c2 * x * z).abs() < 1e-15);
    assert!((y_real(2, 2, z, phi) - 0.5 * c2 * (x * x - y * y)).abs() < 1e-15);
    assert!((y_real(1, -1, z, phi) - (-0.4886025 * y)).abs() < 1e-7);
}

// ---------------------------------------------------------------------------------------------
// Quadrature: Gauss-Legendre in cos(theta) x uniform phi, exact for the degrees involved.

struct Rule {
    /// (x = cos theta, phi, weight)
    nodes: Vec<(f64, f64, f64)>,
}

/// Exact for products of three SH of degree <= l_max each (degree 3 l_max in x, frequency
/// 3 l_max in phi).
fn rule(l_max: usize) -> Rule {
    let gl = gauss_legendre(3 * l_max / 2 + 2);
    let n_phi = 3 * l_max + 2;
    let mut nodes = Vec::new();
    for &(x, wx) in &gl {
        for p in 0..n_phi {
            let phi = 2.0 * PI * (p as f64 + 0.5) / n_phi as f64;
            nodes.push((x, phi, wx * 2.0 * PI / n_phi as f64));
        }
    }
    Rule { nodes }
}

/// Table of real SH values at the nodes: values[node][index].
fn real_table(rule: &Rule, n_bands: usize) -> Vec<Vec<f64>> {
    rule.nodes
        .iter()
        .map(|&(x, phi, _)| {
            (0..n_bands * n_bands)
                .map(|i| {
                    let (l, m) = index_to_lm(i).unwrap();
                    y_real(l as i32, m, x, phi)
                })
                .collect()
        })
        .collect()
}

#[test]
fn complex_gaunt_matches_quadrature() {
    let l_max = 4;
    let rule = rule(l_max);
    for l1 in 0..=l_max as i32 {
        for l2 in 0..=l_max as i32 {
            for l3 in 0..=l_max as i32 {
                for m1 in -l1..=l1 {
                    for m2 in -l2..=l2 {
                        for m3 in -l3..=l3 {
                            let (mut re, mut im) = (0.0, 0.0);
                            for &(x, phi, wt) in &rule.nodes {
                                let a = y_complex(l1, m1, x, phi);
                                let b = y_complex(l2, m2, x, phi);
                                let c = y_complex(l3, m3, x, phi);
                                let ab = (a.0 * b.0 - a.1 * b.1, a.0 * b.1 + a.1 * b.0);
                                re += wt * (ab.0 * c.0 - ab.1 * c.1);
                                im += wt * (ab.0 * c.1 + ab.1 * c.0);
                            }
                            let g =
                                gaunt_complex(l1 as u32, m1, l2 as u32, m2, l3 as u32, m3).unwrap();
                            assert!(
                                (g - re).abs() < 1e-14 && im.abs() < 1e-14,
                                "({l1} {m1}) ({l2} {m2}) ({l3} {m3}): {g} vs {re} + {im} i"
                            );
                        }
                    }
                }
            }
        }
    }
}

#[test]
fn real_gaunt_tensor_matches_quadrature_entry_by_entry() {
    let n_bands = 6;
    let rule = rule(n_bands - 1);
    let table = real_table(&rule, n_bands);
    let tensor = GauntTensor::new(n_bands).unwrap();
    let n = n_bands * n_bands;
    let mut dense = vec![0.0; n * n * n];
    for e in tensor.all() {
        dense[(e.i as usize * n + e.j as usize) * n + e.k as usize] = e.value;
    }
    // Stored once, i <= j <= k, sorted.
    for w in tensor.entries().windows(2) {
        assert!((w[0].i, w[0].j, w[0].k) < (w[1].i, w[1].j, w[1].k));
    }
    assert!(tensor.entries().iter().all(|e| e.i <= e.j && e.j <= e.k));
    let mut nonzero = 0;
    for i in 0..n {
        for j in 0..n {
            for k in 0..n {
                let q: f64 = rule
                    .nodes
                    .iter()
                    .zip(&table)
                    .map(|(&(_, _, wt), y)| wt * y[i] * y[j] * y[k])
                    .sum();
                let t = dense[(i * n + j) * n + k];
                assert!(
                    (t - q).abs() < 2e-14,
                    "T[{i} {j} {k}] = {t} vs quadrature {q}"
                );
                let (l1, m1) = index_to_lm(i).unwrap();
                let (l2, m2) = index_to_lm(j).unwrap();
                let (l3, m3) = index_to_lm(k).unwrap();
                assert_eq!(t, gaunt_real(l1, m1, l2, m2, l3, m3).unwrap());
                if t != 0.0 {
                    nonzero += 1;
                } else {
                    assert!(q.abs() < 1e-14);
                }
            }
        }
    }
    assert_eq!(nonzero, tensor.all().len());
}

#[test]
fn real_gaunt_is_symmetric_and_exactly_zero_off_the_selection_rules() {
    for (l1, m1, l2, m2, l3, m3) in [
        (3, -2, 4, 1, 5, -3),
        (2, 2, 2, -2, 4, 0),
        (6, 3, 6, -3, 2, 0),
    ] {
        let v = gaunt_real(l1, m1, l2, m2, l3, m3).unwrap();
        assert_eq!(v, gaunt_real(l2, m2, l3, m3, l1, m1).unwrap());
        assert_eq!(v, gaunt_real(l3, m3, l2, m2, l1, m1).unwrap());
    }
    assert_eq!(gaunt_real(2, 2, 2, -2, 4, 0).unwrap(), 0.0);
    assert_eq!(gaunt_real(1, 1, 1, -1, 2, 0).unwrap(), 0.0);
    assert_eq!(gaunt_real(1, 0, 1, 0, 1, 0).unwrap(), 0.0);
    // Y00 Yi Yj = delta_ij / sqrt(4 pi)
    let c = 1.0 / (4.0 * PI).sqrt();
    assert!((gaunt_real(0, 0, 3, -2, 3, -2).unwrap() - c).abs() < 1e-16);
    assert!(gaunt_real(20_000, 0, 1, 0, 1, 0).is_err());
}

fn random_vec(rng: &mut rand_pcg::Pcg64, n: usize) -> Vec<f64> {
    (0..n).map(|_| rng.random_range(-1.0..1.0)).collect()
}

#[test]
fn product_and_triple_integral_match_quadrature() {
    let mut rng = rand_pcg::Pcg64::seed_from_u64(5);
    for n_bands in 1..=7 {
        let n = n_bands * n_bands;
        let rule = rule(n_bands - 1);
        let table = real_table(&rule, n_bands);
        for _ in 0..3 {
            let a = random_vec(&mut rng, n);
            let b = random_vec(&mut rng, n);
            let c = random_vec(&mut rng, n);
            let eval = |v: &[f64], y: &[f64]| v.iter().zip(y).map(|(p, q)| p * q).sum::<f64>();
            let ab = product(n_bands, &a, &b).unwrap();
            for (k, &ck) in ab.iter().enumerate() {
                let q: f64 = rule
                    .nodes
                    .iter()
                    .zip(&table)
                    .map(|(&(_, _, wt), y)| wt * eval(&a, y) * eval(&b, y) * y[k])
                    .sum();
                assert!(
                    (ck - q).abs() < 1e-13,
                    "bands {n_bands}, k {k}: {ck} vs {q}"
                );
            }
            let t = triple_product_integral(n_bands, &a, &b, &c).unwrap();
            let q: f64 = rule
                .nodes
                .iter()
                .zip(&table)
                .map(|(&(_, _, wt), y)| wt * eval(&a, y) * eval(&b, y) * eval(&c, y))
                .sum();
            assert!((t - q).abs() < 1e-12, "bands {n_bands}: {t} vs {q}");
        }
    }
}

#[test]
fn bad_lengths_and_band_counts_are_errors() {
    let a = vec![0.0f64; 9];
    assert!(product(3, &a, &a[..8]).is_err());
    assert!(product(0, &a[..0], &a[..0]).is_err());
    assert!(product(13, &a, &a).is_err());
    assert!(triple_product_integral(3, &a, &a, &a[..4]).is_err());
    assert!(ProductPlan::new(0).is_err());
    assert!(ProductPlan::new(41).is_err());
    assert!(GauntTensor::new(0).is_err());
}

/// Snyder 2006, table 1: multiplies of the generated projected product for 2..6 bands.
const SNYDER: [usize; 5] = [20, 120, 399, 1135, 2527];

fn traced_product(n_bands: usize) -> hairmath::real::Graph {
    let n = n_bands * n_bands;
    trace(2 * n, |x: &[Traced]| {
        product(n_bands, &x[..n], &x[n..]).unwrap()
    })
}

#[test]
fn traced_product_multiply_counts_beat_snyder() {
    let mut report = Vec::new();
    for n_bands in 2..=6 {
        let g = traced_product(n_bands);
        let muls = g.count_binary(Binary::Mul);
        let plan = ProductPlan::cached(n_bands).unwrap();
        assert_eq!(muls, plan.multiplies());
        let n = n_bands * n_bands;
        let t = trace(3 * n, |x: &[Traced]| {
            vec![triple_product_integral(n_bands, &x[..n], &x[n..2 * n], &x[2 * n..]).unwrap()]
        });
        let triple = t.count_binary(Binary::Mul);
        report.push(format!(
            "bands {n_bands}: product {muls} multiplies (Snyder {}), triple integral {triple}",
            SNYDER[n_bands - 2]
        ));
        assert!(muls <= SNYDER[n_bands - 2], "{}", report.join("\n"));
    }
    println!("{}", report.join("\n"));
}

fn validate_wgsl(src: &str) -> Result<(), String> {
    use naga::valid::{Capabilities, ValidationFlags, Validator};
    let module = naga::front::wgsl::parse_str(src).map_err(|e| e.emit_to_string(src))?;
    Validator::new(ValidationFlags::all(), Capabilities::all())
        .validate(&module)
        .map_err(|e| e.emit_to_string(src))?;
    Ok(())
}

#[test]
fn traced_product_equals_f32_bit_for_bit_and_wgsl_validates() {
    let mut rng = rand_pcg::Pcg64::seed_from_u64(9);
    for n_bands in 1..=6 {
        let n = n_bands * n_bands;
        let g = traced_product(n_bands);
        let t = trace(3 * n, |x: &[Traced]| {
            vec![triple_product_integral(n_bands, &x[..n], &x[n..2 * n], &x[2 * n..]).unwrap()]
        });
        if n_bands <= 4 {
            let wgsl = g.to_wgsl("sh_product");
            validate_wgsl(&wgsl).unwrap_or_else(|e| panic!("{e}\n{wgsl}"));
            let wgsl = t.to_wgsl("sh_triple");
            validate_wgsl(&wgsl).unwrap_or_else(|e| panic!("{e}\n{wgsl}"));
        }
        for _ in 0..20 {
            let x: Vec<f32> = (0..3 * n).map(|_| rng.random_range(-2.0..2.0)).collect();
            let cpu = product(n_bands, &x[..n], &x[n..2 * n]).unwrap();
            let traced = g.eval_f32(&x[..2 * n]);
            assert_eq!(
                cpu.iter().map(|v| v.to_bits()).collect::<Vec<_>>(),
                traced.iter().map(|v| v.to_bits()).collect::<Vec<_>>()
            );
            let cpu = triple_product_integral(n_bands, &x[..n], &x[n..2 * n], &x[2 * n..]).unwrap();
            assert_eq!(cpu.to_bits(), t.eval_f32(&x)[0].to_bits());
        }
    }
}
