//! Wigner 3-j symbols: exact values, correct rounding against an independent big-rational
//! evaluation, symmetries, selection rules, orthogonality, typed errors.

use hairmath::sh::{wigner_3j, wigner_3j_exact, wigner_3j_int, HalfInt};
use hairmath::ParamError;
use num_bigint::{BigInt, BigUint};
use num_traits::{One, Signed, ToPrimitive, Zero};
use proptest::prelude::*;

fn h(twice: i32) -> HalfInt {
    HalfInt::from_twice(twice)
}

/// (j1 j2 j3; m1 m2 m3) with twice-valued arguments.
fn w(t: [i32; 6]) -> f64 {
    wigner_3j(h(t[0]), h(t[1]), h(t[2]), h(t[3]), h(t[4]), h(t[5])).unwrap()
}

fn fact(n: i64) -> BigUint {
    (1..=n.max(0) as u64).fold(BigUint::one(), |acc, k| acc * k)
}

fn gcd(mut a: BigUint, mut b: BigUint) -> BigUint {
    while !b.is_zero() {
        let r = &a % &b;
        a = b;
        b = r;
    }
    a
}

/// Independent exact evaluation: Racah's sum with plain big-integer factorials and fractions.
/// Returns (negative, num, den) with value = ±sqrt(num/den), reduced.
fn reference(t: [i32; 6]) -> (bool, BigUint, BigUint) {
    let [tj1, tj2, tj3, tm1, tm2, tm3] = t.map(i64::from);
    let zero = (false, BigUint::zero(), BigUint::one());
    if tm1 + tm2 + tm3 != 0 || tm1.abs() > tj1 || tm2.abs() > tj2 || tm3.abs() > tj3 {
        return zero;
    }
    if tj3 > tj1 + tj2 || tj3 < (tj1 - tj2).abs() {
        return zero;
    }
    let (j1, j2, j3) = (tj1, tj2, tj3); // twice
    let half = |x: i64| {
        assert!(x % 2 == 0);
        x / 2
    };
    let pre_num = fact(half(j1 + j2 - j3))
        * fact(half(j1 - j2 + j3))
        * fact(half(-j1 + j2 + j3))
        * fact(half(j1 + tm1))
        * fact(half(j1 - tm1))
        * fact(half(j2 + tm2))
        * fact(half(j2 - tm2))
        * fact(half(j3 + tm3))
        * fact(half(j3 - tm3));
    let pre_den = fact(half(j1 + j2 + j3) + 1);
    // Sum over all k where every factorial argument is non-negative.
    let mut s_num = BigInt::zero();
    let mut s_den = BigUint::one();
    for k in 0..=half(j1 + j2 + j3) {
        let args = [
            k,
            half(j3 - j2 + tm1) + k,
            half(j3 - j1 - tm2) + k,
            half(j1 + j2 - j3) - k,
            half(j1 - tm1) - k,
            half(j2 + tm2) - k,
        ];
        if args.iter().any(|&a| a < 0) {
            continue;
        }
        let d: BigUint = args.iter().map(|&a| fact(a)).product();
        // s += (-1)^k / d
        let term = BigInt::from(s_den.clone());
        let term = if k % 2 == 0 { term } else { -term };
        s_num = s_num * BigInt::from(d.clone()) + term;
        s_den *= d;
        let g = gcd(s_num.magnitude().clone(), s_den.clone());
        if !g.is_one() && !g.is_zero() {
            s_num /= BigInt::from(g.clone());
            s_den /= g;
        }
    }
    if s_num.is_zero() {
        return zero;
    }
    let phase = half(j1 - j2 - tm3).rem_euclid(2) == 1;
    let negative = phase != s_num.is_negative();
    let mut num = pre_num * s_num.magnitude() * s_num.magnitude();
    let mut den = pre_den * &s_den * &s_den;
    let g = gcd(num.clone(), den.clone());
    num /= &g;
    den /= &g;
    (negative, num, den)
}

/// True if `y` is the correctly rounded `±sqrt(num/den)` (round to nearest; ties accepted
/// either way, they do not occur here).
fn is_correctly_rounded(y: f64, negative: bool, num: &BigUint, den: &BigUint) -> bool {
    if num.is_zero() {
        return y == 0.0;
    }
    if y == 0.0 || (y < 0.0) != negative {
        return false;
    }
    let y = y.abs();
    // y = m 2^e with m < 2^53.
    let bits = y.to_bits();
    let exp = ((bits >> 52) & 0x7ff) as i64;
    let (m, e) = if exp == 0 {
        (bits & ((1 << 52) - 1), -1074)
    } else {
        ((bits & ((1 << 52) - 1)) | (1 << 52), exp - 1075)
    };
    // Midpoints below and above in units of 2^(e - 2): lower uses a quarter ulp at powers of 2.
    let lo = if m == 1 << 52 && exp > 1 {
        4 * m - 1
    } else {
        4 * m - 2
    };
    let hi = 4 * m + 2;
    // Compare (x 2^(e-2))^2 = x^2 2^(2e-4) with num/den: x^2 2^(2e-4) den vs num.
    let cmp = |x: u64| {
        let lhs = BigUint::from(x) * BigUint::from(x) * den;
        let shift = 2 * (e - 2);
        if shift >= 0 {
            (lhs << shift as u64).cmp(num)
        } else {
            lhs.cmp(&(num << (-shift) as u64))
        }
    };
    cmp(lo).is_le() && cmp(hi).is_ge()
}

/// Twice-valued arguments of all symbols with 2j <= max_twice (m's constrained to sum 0).
fn all_symbols(max_twice: i32) -> Vec<[i32; 6]> {
    let mut out = Vec::new();
    for tj1 in 0..=max_twice {
        for tj2 in 0..=max_twice {
            for tj3 in (tj1 - tj2).abs()..=(tj1 + tj2).min(max_twice) {
                if (tj1 + tj2 + tj3) % 2 != 0 {
                    continue;
                }
                for tm1 in (-tj1..=tj1).step_by(2) {
                    for tm2 in (-tj2..=tj2).step_by(2) {
                        let tm3 = -tm1 - tm2;
                        if tm3.abs() <= tj3 {
                            out.push([tj1, tj2, tj3, tm1, tm2, tm3]);
                        }
                    }
                }
            }
        }
    }
    out
}

#[test]
fn known_exact_values() {
    let s = |t: [i32; 6]| {
        wigner_3j_exact(h(t[0]), h(t[1]), h(t[2]), h(t[3]), h(t[4]), h(t[5]))
            .unwrap()
            .to_string()
    };
    // (1 1 0; 0 0 0) = -1/sqrt(3)
    assert_eq!(s([2, 2, 0, 0, 0, 0]), "-sqrt(1/3)");
    assert_eq!(w([2, 2, 0, 0, 0, 0]), -(1.0f64 / 3.0).sqrt());
    // (1/2 1/2 1; 1/2 -1/2 0) = 1/sqrt(6)
    assert_eq!(s([1, 1, 2, 1, -1, 0]), "sqrt(1/6)");
    // (1/2 1/2 0; 1/2 -1/2 0) = 1/sqrt(2)
    assert_eq!(s([1, 1, 0, 1, -1, 0]), "sqrt(1/2)");
    assert_eq!(w([1, 1, 0, 1, -1, 0]), core::f64::consts::FRAC_1_SQRT_2);
    // (1 1 1; 1 -1 0) = 1/sqrt(6); (1 1 2; 0 0 0) = sqrt(2/15); (2 2 2; 0 0 0) = -sqrt(2/35)
    assert_eq!(s([2, 2, 2, 2, -2, 0]), "sqrt(1/6)");
    assert_eq!(s([2, 2, 4, 0, 0, 0]), "sqrt(2/15)");
    assert_eq!(s([4, 4, 4, 0, 0, 0]), "-sqrt(2/35)");
    // (j j 0; m -m 0) = (-1)^(j-m) / sqrt(2j+1)
    for tj in 0..12 {
        for tm in (-tj..=tj).step_by(2) {
            let v = w([tj, tj, 0, tm, -tm, 0]);
            let negative = ((tj - tm) / 2) % 2 == 1;
            let den = BigUint::from((tj + 1) as u32);
            assert!(
                is_correctly_rounded(v, negative, &BigUint::one(), &den),
                "j = {tj}/2, m = {tm}/2"
            );
        }
    }
    // odd permutation of (1 1 1; 1 -1 0): (-1)^3
    assert_eq!(s([2, 2, 2, -2, 2, 0]), "-sqrt(1/6)");
    assert_eq!(s([0, 0, 0, 0, 0, 0]), "1");
}

/// Closed form for m = 0 (Edmonds 1957, eq. 3.7.17), J = j1 + j2 + j3 even:
/// (-1)^(J/2) sqrt((J-2j1)!(J-2j2)!(J-2j3)!/(J+1)!) (J/2)! / ((J/2-j1)!(J/2-j2)!(J/2-j3)!).
fn closed_form_m0(j1: i64, j2: i64, j3: i64) -> (bool, BigUint, BigUint) {
    let big_j = j1 + j2 + j3;
    let g = big_j / 2;
    let ratio_num = fact(g);
    let ratio_den = fact(g - j1) * fact(g - j2) * fact(g - j3);
    assert!((&ratio_num % &ratio_den).is_zero());
    let r = ratio_num / ratio_den;
    let mut num = fact(big_j - 2 * j1) * fact(big_j - 2 * j2) * fact(big_j - 2 * j3) * &r * &r;
    let mut den = fact(big_j + 1);
    let d = gcd(num.clone(), den.clone());
    num /= &d;
    den /= &d;
    (g % 2 == 1, num, den)
}

#[test]
fn m_zero_closed_form_exact_and_correctly_rounded() {
    let mut cases = vec![];
    for j1 in 0..12 {
        for j2 in 0..12 {
            for j3 in (j1 - j2).abs()..=(j1 + j2) {
                if (j1 + j2 + j3) % 2 == 0 {
                    cases.push((j1, j2, j3));
                }
            }
        }
    }
    cases.extend([
        (200, 200, 200),
        (200, 150, 100),
        (199, 101, 100),
        (200, 200, 0),
        (200, 200, 400),
        (3, 200, 199),
    ]);
    for (j1, j2, j3) in cases {
        let t = [2 * j1 as i32, 2 * j2 as i32, 2 * j3 as i32, 0, 0, 0];
        let (negative, num, den) = closed_form_m0(j1, j2, j3);
        let exact = wigner_3j_exact(h(t[0]), h(t[1]), h(t[2]), h(0), h(0), h(0)).unwrap();
        assert_eq!(
            (exact.negative, &exact.num, &exact.den),
            (negative, &num, &den),
            "{t:?}"
        );
        let y = w(t);
        assert!(
            is_correctly_rounded(y, negative, &num, &den),
            "{t:?}: {y:e}"
        );
    }
    // j = 200, m = 0: factorials overflow f64 (171!), the value is still O(1/j).
    let y = w([400, 400, 400, 0, 0, 0]);
    assert!(y.abs() > 1e-4 && y.abs() < 1e-1, "{y}");
}

#[test]
fn correctly_rounded_against_independent_reference_small() {
    let mut checked = 0;
    for t in all_symbols(8) {
        let (negative, num, den) = reference(t);
        let y = w(t);
        assert!(
            is_correctly_rounded(y, negative, &num, &den),
            "{t:?}: {y:e}"
        );
        let exact = wigner_3j_exact(h(t[0]), h(t[1]), h(t[2]), h(t[3]), h(t[4]), h(t[5])).unwrap();
        assert_eq!(
            (exact.negative, &exact.num, &exact.den),
            (negative, &num, &den),
            "{t:?}"
        );
        checked += 1;
    }
    assert!(checked > 4000, "{checked}");
}

/// Deterministic pseudo-random valid arguments with 2j up to `max_twice`.
fn random_symbols(count: usize, max_twice: i32, seed: u64) -> Vec<[i32; 6]> {
    use rand::{Rng, SeedableRng};
    let mut rng = rand_pcg::Pcg64::seed_from_u64(seed);
    let mut out = Vec::new();
    while out.len() < count {
        let tj1 = rng.random_range(0..=max_twice);
        let tj2 = rng.random_range(0..=max_twice);
        let lo = (tj1 - tj2).abs();
        let hi = (tj1 + tj2).min(max_twice);
        if lo > hi {
            continue;
        }
        let tj3 = lo + 2 * rng.random_range(0..=(hi - lo) / 2);
        let tm1 = -tj1 + 2 * rng.random_range(0..=tj1);
        let tm2 = -tj2 + 2 * rng.random_range(0..=tj2);
        let tm3 = -tm1 - tm2;
        if tm3.abs() > tj3 {
            continue;
        }
        out.push([tj1, tj2, tj3, tm1, tm2, tm3]);
    }
    out
}

#[test]
fn correctly_rounded_at_2j_up_to_400() {
    let mut symbols = random_symbols(60, 400, 7);
    symbols.extend(random_symbols(20, 80, 8));
    symbols.extend([
        [400, 400, 400, 0, 0, 0],
        [400, 400, 400, 2, -4, 2],
        [400, 399, 399, 2, 1, -3],
        [400, 200, 200, 400, -200, -200],
        [400, 400, 2, 400, -400, 0],
        [399, 399, 400, 399, -397, -2],
        [400, 400, 400, 200, -100, -100],
    ]);
    let mut nonzero = 0;
    for t in symbols {
        let (negative, num, den) = reference(t);
        let y = w(t);
        assert!(
            is_correctly_rounded(y, negative, &num, &den),
            "{t:?}: {y:e}"
        );
        if y != 0.0 {
            nonzero += 1;
        }
    }
    assert!(nonzero > 50);
}

#[test]
fn agrees_with_the_wigners_crate() {
    // wigners is not exact (it converts prime factorisations through f64): relative tolerance.
    for t in random_symbols(400, 60, 3) {
        let ours = w(t);
        let theirs = wigners::wigner_3j(
            (t[0] / 2) as u32,
            (t[1] / 2) as u32,
            (t[2] / 2) as u32,
            t[3] / 2,
            t[4] / 2,
            t[5] / 2,
        );
        if t.iter().any(|x| x % 2 != 0) {
            continue;
        }
        assert!(
            (ours - theirs).abs() <= 1e-12 * ours.abs().max(1e-300) + 1e-300,
            "{t:?}: {ours:e} vs {theirs:e}"
        );
    }
}

#[test]
fn selection_rules_give_zero() {
    // m sum, triangle, |m| > j
    assert_eq!(w([2, 2, 2, 2, 0, 0]), 0.0);
    assert_eq!(w([2, 2, 6, 0, 0, 0]), 0.0);
    assert_eq!(w([2, 2, 2, 4, -4, 0]), 0.0);
    assert_eq!(w([1, 1, 2, 3, -3, 0]), 0.0);
    // (j1 j2 j3; 0 0 0) with odd J
    assert_eq!(w([2, 2, 2, 0, 0, 0]), 0.0);
    assert_eq!(w([6, 4, 4, 0, 0, 0]), 0.0);
    assert_eq!(wigner_3j_int(3, 2, 2, 0, 0, 0).unwrap(), 0.0);
}

#[test]
fn malformed_arguments_are_typed_errors() {
    let e =
        |t: [i32; 6]| wigner_3j(h(t[0]), h(t[1]), h(t[2]), h(t[3]), h(t[4]), h(t[5])).unwrap_err();
    let ParamError::OutOfRange { name, .. } = e([-2, 2, 0, 0, 0, 0]) else {
        panic!()
    };
    assert_eq!(name, "j1");
    let err = e([2, 2, 2, 1, -1, 0]);
    assert!(err.to_string().contains("m must be an integer"), "{err}");
    let err = e([1, 2, 2, 1, 0, -1]);
    assert!(err.to_string().contains("must be an integer"), "{err}");
    let err = e([1, 1, 1, 1, 1, -1]);
    assert!(err.to_string().contains("j1 + j2 + j3"), "{err}");
    let err = e([40_002, 40_002, 0, 0, 0, 0]);
    assert!(err.to_string().contains("must not exceed"), "{err}");
    assert!(wigner_3j_int(20_000, 1, 1, 0, 0, 0).is_err());
    assert!("1/3".parse::<HalfInt>().is_err());
    assert_eq!("-1.5".parse::<HalfInt>().unwrap().twice(), -3);
}

#[test]
fn orthogonality_over_m1_m2() {
    // Σ_{m1,m2} (2j3+1) (j1 j2 j3; m1 m2 m3)(j1 j2 j3'; m1 m2 m3') = δ_j3j3' δ_m3m3'
    for (tj1, tj2) in [(1, 2), (3, 5), (4, 4), (7, 6), (12, 9), (40, 31)] {
        let j3s: Vec<i32> = ((tj1 - tj2).abs()..=tj1 + tj2).step_by(2).collect();
        for &tj3 in &j3s {
            for &tj3b in &j3s {
                for tm3 in (-tj3..=tj3).step_by(2) {
                    for tm3b in (-tj3b..=tj3b).step_by(2) {
                        let mut sum = 0.0;
                        for tm1 in (-tj1..=tj1).step_by(2) {
                            let tm2 = -tm1 - tm3;
                            let tm2b = -tm1 - tm3b;
                            if tm2 != tm2b {
                                continue;
                            }
                            sum += w([tj1, tj2, tj3, tm1, tm2, tm3])
                                * w([tj1, tj2, tj3b, tm1, tm2, tm3b]);
                        }
                        sum *= (tj3 + 1) as f64;
                        let expect = if tj3 == tj3b && tm3 == tm3b { 1.0 } else { 0.0 };
                        assert!(
                            (sum - expect).abs() < 1e-13,
                            "{tj1} {tj2} {tj3} {tj3b} {tm3} {tm3b}: {sum}"
                        );
                    }
                }
            }
        }
    }
}

#[test]
fn orthogonality_over_j3_m3() {
    // Σ_{j3,m3} (2j3+1) (j1 j2 j3; m1 m2 m3)(j1 j2 j3; m1' m2' m3) = δ_m1m1' δ_m2m2'
    for (tj1, tj2) in [(1, 1), (2, 3), (5, 4), (8, 8), (11, 6), (30, 27)] {
        for tm1 in (-tj1..=tj1).step_by(2) {
            for tm2 in (-tj2..=tj2).step_by(2) {
                for tm1b in (-tj1..=tj1).step_by(2) {
                    for tm2b in (-tj2..=tj2).step_by(2) {
                        let mut sum = 0.0;
                        for tj3 in ((tj1 - tj2).abs()..=tj1 + tj2).step_by(2) {
                            let tm3 = -tm1 - tm2;
                            if tm3 != -tm1b - tm2b || tm3.abs() > tj3 {
                                continue;
                            }
                            sum += (tj3 + 1) as f64
                                * w([tj1, tj2, tj3, tm1, tm2, tm3])
                                * w([tj1, tj2, tj3, tm1b, tm2b, tm3]);
                        }
                        let expect = if tm1 == tm1b && tm2 == tm2b { 1.0 } else { 0.0 };
                        assert!(
                            (sum - expect).abs() < 1e-13,
                            "{tj1} {tj2} {tm1} {tm2} {tm1b} {tm2b}: {sum}"
                        );
                    }
                }
            }
        }
    }
}

fn valid_args() -> impl Strategy<Value = [i32; 6]> {
    (
        0..=120i32,
        0..=120i32,
        any::<u32>(),
        any::<u32>(),
        any::<u32>(),
    )
        .prop_filter_map("m3 out of range", |(tj1, tj2, r3, r1, r2)| {
            let lo = (tj1 - tj2).abs();
            let tj3 = lo + 2 * (r3 % ((tj1 + tj2 - lo) as u32 / 2 + 1)) as i32;
            let tm1 = -tj1 + 2 * (r1 % (tj1 as u32 + 1)) as i32;
            let tm2 = -tj2 + 2 * (r2 % (tj2 as u32 + 1)) as i32;
            let tm3 = -tm1 - tm2;
            (tm3.abs() <= tj3).then_some([tj1, tj2, tj3, tm1, tm2, tm3])
        })
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(400))]

    /// Correct rounding makes the symmetry relations hold bit for bit.
    #[test]
    fn symmetries_hold_exactly(t in valid_args()) {
        let [a, b, c, x, y, z] = t;
        let v = w(t);
        let odd = if ((a + b + c) / 2) % 2 == 0 { 1.0 } else { -1.0 };
        // even (cyclic) permutations
        prop_assert_eq!(w([b, c, a, y, z, x]), v);
        prop_assert_eq!(w([c, a, b, z, x, y]), v);
        // odd permutations
        prop_assert_eq!(w([b, a, c, y, x, z]), odd * v);
        prop_assert_eq!(w([a, c, b, x, z, y]), odd * v);
        prop_assert_eq!(w([c, b, a, z, y, x]), odd * v);
        // m -> -m
        prop_assert_eq!(w([a, b, c, -x, -y, -z]), odd * v);
    }
}

#[test]
fn exact_and_f64_agree() {
    for t in random_symbols(50, 100, 11) {
        let e = wigner_3j_exact(h(t[0]), h(t[1]), h(t[2]), h(t[3]), h(t[4]), h(t[5])).unwrap();
        assert_eq!(e.to_f64(), w(t));
        let f = e.num.to_f64().unwrap_or(f64::INFINITY) / e.den.to_f64().unwrap_or(f64::INFINITY);
        if f.is_finite() && f > 0.0 {
            assert!((f.sqrt() - w(t).abs()).abs() < 1e-12);
        }
    }
}
