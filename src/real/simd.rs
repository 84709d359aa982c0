//! Eight or sixteen single-precision lanes per value: the same generic code evaluates eight
//! ([`f32x8`]) or sixteen ([`f32x16`]) samples at once. Transcendental functions are
//! vectorised polynomial approximations, so results differ from the scalar `f32`
//! instantiation by a few ulp (the tests bound the difference). The lane algorithms here
//! (`exp`, `atan2`, `floor`) serve the instruction-set lanes of [`super::isa`] too.
//!
//! `wide` maps [`f32x16`] to one AVX-512 register when the crate is compiled with `avx512f`
//! (e.g. `RUSTFLAGS="-C target-cpu=native"` on an AVX-512 machine) and to two [`f32x8`] halves
//! otherwise: `wide`'s types run the instructions of the build, not of the machine.
//! [`crate::bcsdf::HostBatch`] runs those of the machine, chosen at run time.

#[cfg(target_arch = "x86_64")]
use super::isa::{Avx2Lanes, Avx512Lanes};
use super::{Real, NEGLIGIBLE};
use crate::lut::SharedTable;
use wide::{f32x16, f32x8, i32x16, i32x8};

/// The `wide` lane type for the compilation target: [`f32x16`] when the crate is compiled with
/// AVX-512 (one zmm register per value), [`f32x8`] otherwise. [`crate::bcsdf::HostBatch`]
/// evaluates on the baseline with it.
#[cfg(target_feature = "avx512f")]
pub type BatchReal = f32x16;
/// The `wide` lane type for the compilation target: [`f32x16`] when the crate is compiled with
/// AVX-512 (one zmm register per value), [`f32x8`] otherwise. [`crate::bcsdf::HostBatch`]
/// evaluates on the baseline with it.
#[cfg(not(target_feature = "avx512f"))]
pub type BatchReal = f32x8;

/// `2^r` from `r + 2^23 + 127` (r an integer in [-126, 127]): the low bits of that float are
/// the biased exponent `r + 127`, shifted here into the exponent field.
pub(crate) trait ExponentField: Sized {
    /// The float whose bits are `biased`'s shifted left by 23.
    fn shifted_into_exponent(biased: Self) -> Self;
}

macro_rules! exponent_field_through_integers {
    ($t:ident, $i:ident) => {
        impl ExponentField for $t {
            #[inline(always)]
            fn shifted_into_exponent(biased: Self) -> Self {
                let bits: $i = wide::bytemuck::cast(biased);
                wide::bytemuck::cast(bits << 23)
            }
        }
    };
}

exponent_field_through_integers!(f32x8, i32x8);
exponent_field_through_integers!(f32x16, i32x16);

/// `floor` in vector instructions only, equal to `f32::floor` in every lane for every input
/// (signed zeros and NaN included): `|x| < 2^23` is rounded to the nearest integer by adding
/// and subtracting 2^23 (exact: the spacing of floats in [2^23, 2^24) is 1), the sign of x is
/// put back, and 1 is subtracted where that rounded up. Larger magnitudes, infinities and NaN
/// are already integers (or NaN) and pass through.
#[allow(unused_macros)]
macro_rules! floor_without_sse41 {
    ($t:ident, $x:expr) => {{
        let x: $t = $x;
        let two_23 = $t::splat(8_388_608.0);
        let sign = x & $t::splat(-0.0);
        let magnitude = x.abs();
        let nearest = ((magnitude + two_23) - two_23) | sign;
        let floor = nearest - (x.simd_lt(nearest) & $t::ONE);
        magnitude.simd_lt(two_23).select(floor, x)
    }};
}

/// The polynomial with `f32` coefficients `$c`, highest first, at `x` by Horner's rule with the
/// lanes' own `mul_add`: the polynomials of the lanes' `exp`, `atan2` and `asin_with_cos`.
macro_rules! horner_highest_first {
    ($t:ident, $x:expr, $c:expr) => {{
        let x: $t = $x;
        let [highest, lower @ ..] = $c;
        let mut p = $t::splat(highest);
        for c in lower {
            p = p.mul_add(x, $t::splat(c));
        }
        p
    }};
}

/// `exp` with the range reduction and polynomial of `wide`'s `exp` (Cephes: `x = r ln 2 + f`,
/// |f| <= ln 2 / 2, degree-7 polynomial, about 1 ulp) but without its data-dependent branches
/// and its eight special-case selects: the argument is clamped to [-87.34, 88.72] so that
/// `2^r` is one exponent-field shift (r is capped at 127, so above 88.38 the reduced argument
/// grows to ln 2 and the error to about 1e-6 relative), then three selects restore the edges: 0 below -87.34
/// (where `f32::exp` gives subnormals under 1.2e-38), infinity above 88.72, NaN for NaN.
macro_rules! lean_exp {
    ($t:ident, $x:expr) => {{
        let x: $t = $x;
        let lo = $t::splat(LOWEST_EXP_ARGUMENT);
        let hi = $t::splat(88.722_83);
        let c = x.fast_max(lo).fast_min(hi);
        let r = (c * $t::LOG2_E)
            .round_ties_even()
            .fast_min($t::splat(127.0));
        let result = exp_reduced!($t, c, r, EXP_TAYLOR);
        let result = x.simd_lt(lo).select($t::ZERO, result);
        let result = hi.simd_lt(x).select($t::splat(f32::INFINITY), result);
        x.simd_eq(x).select(result, x)
    }};
}

/// P of `e^f = 1 + f + f^2 P(f)` by Taylor's series (degree 7 in all, Cephes' degree), highest
/// coefficient first: about 1 ulp on |f| <= ln 2 / 2, and 7.2e-7 at f = ln 2, where [`lean_exp`]'s
/// cap on the exponent takes f for arguments above 88.38.
const EXP_TAYLOR: [f32; 6] = [
    1.0 / 5040.0,
    1.0 / 720.0,
    1.0 / 120.0,
    1.0 / 24.0,
    1.0 / 6.0,
    1.0 / 2.0,
];

/// `e^f` of degree 5, highest coefficient first (the last two are exactly 1): the minimax fit
/// of relative error on |f| <= ln 2 / 2 with the constant and linear coefficients held at 1
/// (Lawson's iteration, in `f64`), 1.06e-7 with the coefficients rounded to `f32`. Evaluated
/// by Horner's rule in full, five multiply-adds; used where f stays in that interval
/// ([`lean_exp_of_nonpositive`]).
const EXP_MINIMAX: [f32; 6] = [
    0.008_312_526,
    0.041_890_115,
    0.166_671_14,
    0.499_992_3,
    1.0,
    1.0,
];

/// Below this argument `f32::exp` is subnormal or 0.
const LOWEST_EXP_ARGUMENT: f32 = -87.336_54;

/// `2^23 + 127`: a float in [2^23, 2^24) (where the spacing of floats is 1) whose low bits,
/// after an integer r in [-126, 127] is added to it, are the biased exponent `r + 127` of 2^r.
const EXPONENT_BIAS_MAGIC: f32 = 8_388_608.0 + 127.0;

/// [`lean_exp`] for arguments `x <= 0` ([`Real::exp_of_nonpositive`]): clamped below at
/// -87.34 by [`Real::max`], which also turns NaN into the clamp (`maxps` on x86, `fmaxnm` on
/// aarch64: NEON's `fmax` would keep the NaN), no edge selects, and the degree-5
/// [`EXP_MINIMAX`] (r is never capped here, so |f| <= ln 2 / 2). The rounding of c log2(e) to
/// the integer r and the biased exponent of 2^r come from one multiply-add: `c log2(e) +
/// EXPONENT_BIAS_MAGIC`, rounded once, holds r + 127 in its low bits, and r is that minus the
/// constant (exact). Measured on 4 million arguments evenly spaced on [-87.33, 0] against
/// `f64` (the test `exp_of_nonpositive_is_exp_below_zero` prints it): relative error at most
/// 1.75e-7 on the AVX-512 and AVX2 lanes and 1.92e-7 on `wide`'s (8.5e-8 for [`lean_exp`]'s
/// degree 7).
macro_rules! lean_exp_of_nonpositive {
    ($t:ident, $x:expr) => {{
        let c = Real::max($x, $t::splat(LOWEST_EXP_ARGUMENT));
        let magic = $t::splat(EXPONENT_BIAS_MAGIC);
        let biased = c.mul_add($t::LOG2_E, magic);
        let f = cody_waite_reduced!($t, c, biased - magic);
        horner_highest_first!($t, f, EXP_MINIMAX) * ExponentField::shifted_into_exponent(biased)
    }};
}

/// `f = c - r ln 2` for an integer `r` near c log2(e), with ln 2 split in two (Cody and Waite;
/// Cephes' constants) so that `r ln2_hi` is exact.
macro_rules! cody_waite_reduced {
    ($t:ident, $c:expr, $r:expr) => {{
        let (c, r): ($t, $t) = ($c, $r);
        let f = r.mul_neg_add($t::splat(0.693_359_4), c);
        r.mul_neg_add($t::splat(-2.121_944_4e-4), f)
    }};
}

/// `e^c` for `c` in [-87.34, 88.72] and `r` = c log2(e) rounded (at most 127): Cephes' range
/// reduction `c = r ln 2 + f`, `e^f = 1 + f + f^2 P(f)` with the coefficients `$p` of P
/// ([`EXP_TAYLOR`]), times `2^r` by one exponent-field shift.
macro_rules! exp_reduced {
    ($t:ident, $c:expr, $r:expr, $p:expr) => {{
        let (c, r): ($t, $t) = ($c, $r);
        let f = cody_waite_reduced!($t, c, r);
        // e^f = 1 + f + f^2 P(f).
        let z = horner_highest_first!($t, f, $p);
        let z = z.mul_add(f * f, f) + $t::ONE;
        // 2^r for integer r in [-126, 127]: the biased exponent r + 127 shifted into place.
        let scale = ExponentField::shifted_into_exponent(r + $t::splat(EXPONENT_BIAS_MAGIC));
        z * scale
    }};
}

/// [`Real::asin_with_cos`] on lanes: with `a = |sin|`, `u` is the smaller of `a` and `cos`
/// (at most 1/sqrt 2), `asin(u) = u + u z P(z)`, `z = u^2`, and the angle is `asin(u)` or
/// `pi/2 - asin(u)` (where `cos` is the smaller), with the sign of `sin`. P is [`ASIN_MINIMAX`].
/// No division, where `atan2(sin, cos)` divides.
macro_rules! lean_asin_with_cos {
    ($t:ident, $sin:expr, $cos:expr) => {{
        let (sin, cos): ($t, $t) = ($sin, $cos);
        let a = sin.abs();
        let beyond = cos.simd_lt(a);
        let u = beyond.select(cos, a);
        let z = u * u;
        let p = horner_highest_first!($t, z, ASIN_MINIMAX);
        let angle = (p * z).mul_add(u, u);
        let angle = beyond.select($t::FRAC_PI_2 - angle, angle);
        angle | (sin & $t::splat(-0.0))
    }};
}

/// P of `asin(u) = u + u z P(z)`, `z = u^2`, on 0 <= u <= 1/sqrt 2, highest coefficient first:
/// the minimax fit of relative error (Lawson's iteration, in `f64`), 1.9e-8 with the
/// coefficients rounded to `f32` (7.6e-8 evaluated in `f32`).
const ASIN_MINIMAX: [f32; 7] = [
    0.111_238_67,
    -0.092_492_51,
    0.076_891_94,
    0.016_414_227,
    0.046_498_35,
    0.074_885_12,
    0.166_669_06,
];

/// `atan2` with the octant reduction and polynomial of `wide`'s `atan2` (Cephes `atanf`, after
/// Agner Fog's vector class library) but one division instead of two: `wide` divides
/// `t = min / max` and then `(t - 1) / (t + 1)` for t >= sqrt 2 - 1, which equals
/// `(min - max) / (min + max)`, so the numerator and denominator are selected first. It also
/// drops `wide`'s branch for both arguments infinite ([`Real::atan2`] is called with finite
/// arguments). `atan2(+-0, +-0)` follows `wide` (0 or +-pi by the signs).
macro_rules! lean_atan2 {
    ($t:ident, $y:expr, $x:expr) => {{
        let (y, x): ($t, $t) = ($y, $x);
        let (ax, ay) = (x.abs(), y.abs());
        let swap = ay.simd_gt(ax);
        let small = ax.fast_min(ay);
        let large = ax.fast_max(ay);
        let not_small = small.simd_ge(large * $t::splat(core::f32::consts::SQRT_2 - 1.0));
        let z = not_small.select(small - large, small) / not_small.select(small + large, large);
        let offset = not_small & $t::FRAC_PI_4;
        let zz = z * z;
        let p = horner_highest_first!(
            $t,
            zz,
            [
                8.053_744_5e-2,
                -1.387_768_6e-1,
                1.997_771_1e-1,
                -3.333_295e-1
            ]
        );
        let mut re = p.mul_add(zz * z, z) + offset;
        re = swap.select($t::FRAC_PI_2 - re, re);
        re = (x | y).simd_eq($t::ZERO).select($t::ZERO, re);
        re = x.is_sign_negative().select($t::PI - re, re);
        y.is_sign_negative().select(-re, re)
    }};
}

macro_rules! impl_real_for_lanes {
    // `wide`'s lanes, with the build's instructions.
    ($t:ident, $lanes:expr) => {
        impl_real_for_lanes!($t, $lanes, {
            #[inline(always)]
            fn floor(self) -> Self {
                #[cfg(all(
                    any(target_arch = "x86", target_arch = "x86_64"),
                    not(target_feature = "sse4.1")
                ))]
                {
                    // Without SSE4.1 `wide` floors lane by lane through libm.
                    floor_without_sse41!($t, self)
                }
                #[cfg(not(all(
                    any(target_arch = "x86", target_arch = "x86_64"),
                    not(target_feature = "sse4.1")
                )))]
                {
                    $t::floor(self)
                }
            }
        });
    };
    // The lanes of an instruction set, which only run where it is supported: its fused
    // multiply-add and its rounding instruction, whatever the build's target features.
    ($t:ident, $lanes:expr, instruction_set) => {
        impl_real_for_lanes!($t, $lanes, {
            /// Fused: one rounding.
            #[inline(always)]
            fn mul_add(self, a: Self, b: Self) -> Self {
                $t::mul_add(self, a, b)
            }
            #[inline(always)]
            fn floor(self) -> Self {
                $t::floor(self)
            }
        });
    };
    ($t:ident, $lanes:expr, { $($specific:item)* }) => {
        impl Real for $t {
            /// A lane mask: all bits set where the comparison holds.
            type Mask = $t;
            const DOUBLE: bool = false;
            $($specific)*

            #[inline(always)]
            fn c(value: f64) -> Self {
                $t::splat(value as f32)
            }
            #[inline(always)]
            fn sqrt(self) -> Self {
                $t::sqrt(self)
            }
            #[inline(always)]
            fn exp(self) -> Self {
                lean_exp!($t, self)
            }
            #[inline(always)]
            fn exp_of_nonpositive(self) -> Self {
                lean_exp_of_nonpositive!($t, self)
            }
            /// One comparison and one `and` of the lanes; NaN gives 0.
            #[inline(always)]
            fn negligible_to_zero(self) -> Self {
                $t::splat(NEGLIGIBLE as f32).simd_le(self) & self
            }
            #[inline(always)]
            fn ln(self) -> Self {
                $t::ln(self)
            }
            #[inline(always)]
            fn sin(self) -> Self {
                $t::sin(self)
            }
            #[inline(always)]
            fn cos(self) -> Self {
                $t::cos(self)
            }
            #[inline(always)]
            fn atan2(self, x: Self) -> Self {
                lean_atan2!($t, self, x)
            }
            #[inline(always)]
            fn asin_with_cos(self, cos: Self) -> Self {
                lean_asin_with_cos!($t, self, cos)
            }
            #[inline(always)]
            fn abs(self) -> Self {
                $t::abs(self)
            }
            /// A NaN `self` gives `other`, as the scalar [`Real::min`] does: x86's `minps`
            /// (`fast_min`) does so, NEON's `fmin` (`fast_min` there) would give NaN, its
            /// `fminnm` (`wide`'s `min` there, as fast) gives `other`.
            #[inline(always)]
            fn min(self, other: Self) -> Self {
                #[cfg(target_arch = "aarch64")]
                {
                    $t::min(self, other)
                }
                #[cfg(not(target_arch = "aarch64"))]
                {
                    $t::fast_min(self, other)
                }
            }
            /// A NaN `self` gives `other` ([`Real::min`]'s note).
            #[inline(always)]
            fn max(self, other: Self) -> Self {
                #[cfg(target_arch = "aarch64")]
                {
                    $t::max(self, other)
                }
                #[cfg(not(target_arch = "aarch64"))]
                {
                    $t::fast_max(self, other)
                }
            }
            #[inline(always)]
            fn lt(self, other: Self) -> Self {
                self.simd_lt(other)
            }
            #[inline(always)]
            fn le(self, other: Self) -> Self {
                self.simd_le(other)
            }
            #[inline(always)]
            fn select(mask: Self, on_true: Self, on_false: Self) -> Self {
                mask.select(on_true, on_false)
            }
            #[inline(always)]
            fn every_lane(mask: Self) -> bool {
                mask.all()
            }
            /// The scalar `f32` lookup lane by lane (a gather): bit for bit the scalar result.
            fn sample_table<const D: usize, const C: usize>(
                table: &SharedTable<D, C>,
                coords: [Self; D],
            ) -> [Self; C] {
                let lanes = coords.map(|c| c.to_array());
                let mut out = [[0.0f32; $lanes]; C];
                for k in 0..$lanes {
                    let values = table.lookup_f32(core::array::from_fn(|d| lanes[d][k]));
                    for (channel, v) in out.iter_mut().zip(values) {
                        channel[k] = v;
                    }
                }
                out.map($t::from)
            }
        }
    };
}

impl_real_for_lanes!(f32x8, 8);
impl_real_for_lanes!(f32x16, 16);
#[cfg(target_arch = "x86_64")]
impl_real_for_lanes!(Avx512Lanes, 16, instruction_set);
#[cfg(target_arch = "x86_64")]
impl_real_for_lanes!(Avx2Lanes, 8, instruction_set);

#[cfg(test)]
mod tests {
    use super::*;
    use crate::real::wrap_angle;

    /// `$check::<L, N>($args..., L::to_array)` on every lane type the CPU runs: `wide`'s, and
    /// the instruction sets' where supported.
    macro_rules! on_every_lane_type {
        ($check:ident $(, $arg:expr)*) => {{
            $check::<f32x16, 16>($($arg,)* f32x16::to_array);
            $check::<f32x8, 8>($($arg,)* f32x8::to_array);
            #[cfg(target_arch = "x86_64")]
            {
                use crate::real::InstructionSet;
                if InstructionSet::Avx512.is_supported() {
                    $check::<Avx512Lanes, 16>($($arg,)* Avx512Lanes::to_array);
                }
                if InstructionSet::Avx2.is_supported() {
                    $check::<Avx2Lanes, 8>($($arg,)* Avx2Lanes::to_array);
                }
            }
        }};
    }

    #[test]
    fn lanes_agree_with_scalar_code() {
        let xs = [-7.0_f32, -3.2, -0.5, 0.0, 0.25, 1.0, 3.3, 9.9];
        let v = wrap_angle(f32x8::from(xs)).to_array();
        for (x, w) in xs.iter().zip(v) {
            assert!((wrap_angle(*x) - w).abs() < 1e-5, "{x}: {w}");
        }
        let m = <f32x8 as Real>::select(f32x8::from(xs).lt(f32x8::ZERO), f32x8::ONE, f32x8::ZERO);
        assert_eq!(m.to_array(), [1.0, 1.0, 1.0, 0.0, 0.0, 0.0, 0.0, 0.0]);
    }

    #[test]
    fn floor_equals_scalar_floor_bit_for_bit() {
        let mut xs = vec![
            0.0_f32,
            -0.0,
            0.3,
            -0.3,
            0.5,
            -0.5,
            1.0,
            -1.0,
            1.5,
            -1.5,
            2.5,
            -2.5,
            0.999_999_94,
            -0.999_999_94,
            4_194_303.5,
            -4_194_303.5,
            8_388_607.5,
            -8_388_607.5,
            8_388_608.0,
            -8_388_609.0,
            1e30,
            -1e30,
            f32::MIN_POSITIVE,
            -f32::MIN_POSITIVE,
            1e-45,
            -1e-45,
            f32::INFINITY,
            f32::NEG_INFINITY,
            f32::NAN,
        ];
        xs.extend((0..4000).map(|k| (k as f32 - 2000.0) * 0.173_1));
        while !xs.len().is_multiple_of(16) {
            xs.push(7.25);
        }
        fn check<L: Real + From<[f32; N]>, const N: usize>(
            xs: &[f32],
            to_array: impl Fn(L) -> [f32; N],
        ) {
            for chunk in xs.chunks_exact(N) {
                let a: [f32; N] = chunk.try_into().unwrap();
                let got = to_array(L::from(a).floor());
                for (x, g) in a.iter().zip(got) {
                    let want = x.floor();
                    assert!(
                        want.to_bits() == g.to_bits() || (want.is_nan() && g.is_nan()),
                        "floor({x:e}) = {g:e}, want {want:e} ({N} lanes)"
                    );
                }
            }
        }
        on_every_lane_type!(check, &xs);
    }

    #[test]
    fn exp_is_accurate_and_handles_the_edges() {
        let mut xs: Vec<f32> = (0..20_000).map(|k| -100.0 + k as f32 * 0.009_5).collect();
        xs.extend([
            0.0, -0.0, 1e-30, -1e-30, -87.3, -87.4, 88.7, 88.73, 100.0, -1e30, 1e30,
        ]);
        xs.extend([f32::INFINITY, f32::NEG_INFINITY, f32::NAN]);
        while !xs.len().is_multiple_of(16) {
            xs.push(0.5);
        }
        for chunk in xs.chunks_exact(16) {
            let a: [f32; 16] = chunk.try_into().unwrap();
            let got = <f32x16 as Real>::exp(f32x16::from(a)).to_array();
            let lo = <f32x8 as Real>::exp(f32x8::from(<[f32; 8]>::try_from(&a[..8]).unwrap()));
            for (k, (x, g)) in a.iter().zip(got).enumerate() {
                let want = (*x as f64).exp();
                if x.is_nan() {
                    assert!(g.is_nan());
                } else if want > f32::MAX as f64 {
                    assert_eq!(g, f32::INFINITY, "exp({x})");
                } else if want < 1.18e-38 {
                    assert!(
                        g == 0.0 || (g as f64 - want).abs() < 1.2e-38,
                        "exp({x}) = {g}"
                    );
                } else {
                    let rel = (g as f64 - want).abs() / want;
                    // Above 88.38 the reduced argument grows to ln 2 (r is capped at 127).
                    let bound = if *x > 88.38 { 2e-6 } else { 3e-7 };
                    assert!(rel < bound, "exp({x}) = {g}, want {want}: {rel:e}");
                }
                if k < 8 {
                    let l = lo.to_array()[k];
                    assert!(
                        l == g || (l.is_nan() && g.is_nan()) || (l - g).abs() <= 2e-7 * g.abs()
                    );
                }
            }
        }
    }

    #[test]
    fn atan2_is_accurate_in_every_quadrant() {
        let mut pairs = Vec::new();
        for k in 0..4000 {
            let a = -3.2 + k as f32 * 0.0016;
            for r in [1e-3_f32, 0.7, 1.0, 25.0] {
                pairs.push((r * a.sin(), r * a.cos()));
            }
        }
        pairs.extend([
            (0.0, 1.0),
            (-0.0, 1.0),
            (0.0, -1.0),
            (-0.0, -1.0),
            (1.0, 0.0),
            (-1.0, 0.0),
        ]);
        pairs.extend([
            (1.0, -0.0),
            (1e-30, 1.0),
            (1.0, 1e-30),
            (0.5, 0.5),
            (-0.3, -0.3),
        ]);
        while pairs.len() % 16 != 0 {
            pairs.push((0.25, -0.5));
        }
        for chunk in pairs.chunks_exact(16) {
            let y = f32x16::from(core::array::from_fn::<f32, 16, _>(|k| chunk[k].0));
            let x = f32x16::from(core::array::from_fn::<f32, 16, _>(|k| chunk[k].1));
            let got = <f32x16 as Real>::atan2(y, x).to_array();
            for ((y, x), g) in chunk.iter().zip(got) {
                let want = (*y as f64).atan2(*x as f64);
                assert!(
                    (g as f64 - want).abs() < 4e-7,
                    "atan2({y}, {x}) = {g}, want {want}"
                );
                assert_eq!(
                    g.is_sign_negative(),
                    want.is_sign_negative(),
                    "atan2({y}, {x})"
                );
            }
        }
    }

    /// The lanes of each instruction set the CPU runs ([`super::super::isa`]) meet the bounds
    /// of `wide`'s: `exp` and `atan2` against f64, `floor` bit for bit.
    #[cfg(target_arch = "x86_64")]
    #[test]
    fn instruction_set_lanes_meet_the_same_bounds() {
        use crate::real::{Avx2Lanes, Avx512Lanes, InstructionSet};
        fn check<L: Real + From<[f32; N]>, const N: usize>(to_array: impl Fn(L) -> [f32; N]) {
            let xs: [f32; N] = core::array::from_fn(|k| -80.0 + k as f32 * 160.0 / N as f32);
            let angles: [f32; N] = core::array::from_fn(|k| -3.1 + k as f32 * 6.2 / N as f32);
            let (y, x) = (angles.map(|a| 0.7 * a.sin()), angles.map(|a| 0.7 * a.cos()));
            let exp = to_array(L::from(xs).exp());
            let atan2 = to_array(L::from(y).atan2(L::from(x)));
            let floor = to_array(L::from(xs.map(|v| v * 0.37)).floor());
            for k in 0..N {
                let want = (xs[k] as f64).exp();
                assert!((exp[k] as f64 - want).abs() < 3e-7 * want, "exp({})", xs[k]);
                let want = (y[k] as f64).atan2(x[k] as f64);
                assert!((atan2[k] as f64 - want).abs() < 4e-7, "atan2 at {k}");
                assert_eq!(floor[k].to_bits(), (xs[k] * 0.37).floor().to_bits());
            }
        }
        if InstructionSet::Avx512.is_supported() {
            check::<Avx512Lanes, 16>(Avx512Lanes::to_array);
        }
        if InstructionSet::Avx2.is_supported() {
            check::<Avx2Lanes, 8>(Avx2Lanes::to_array);
        }
    }

    /// `exp_of_nonpositive` on every lane type this CPU runs: within `exp`'s 3e-7 of f64 on
    /// [-87.33, 0], e^-87.34 (below 1.2e-38) beneath, at -inf and for NaN (documented). Prints
    /// the largest relative error over 4 million arguments evenly spaced on [-87.33, 0].
    #[test]
    fn exp_of_nonpositive_is_exp_below_zero() {
        fn check<L: Real + From<[f32; N]>, const N: usize>(to_array: impl Fn(L) -> [f32; N]) {
            const DENSE: usize = 1 << 22;
            let step = -87.33 / (DENSE - 1) as f64;
            let mut worst = 0.0_f64;
            for start in (0..DENSE).step_by(N) {
                let a: [f32; N] = core::array::from_fn(|k| ((start + k) as f64 * step) as f32);
                let got = to_array(L::from(a).exp_of_nonpositive());
                for k in 0..N {
                    let want = (a[k] as f64).exp();
                    worst = worst.max((got[k] as f64 - want).abs() / want);
                }
            }
            eprintln!("{N} lanes: exp_of_nonpositive within {worst:.2e} of f64 on [-87.33, 0]");
            assert!(worst < 3e-7, "{worst:e}");
            let mut xs: Vec<f32> = (0..20_000).map(|k| -100.0 + k as f32 * 0.005).collect();
            xs.extend([
                0.0,
                -0.0,
                -1e-30,
                -87.33,
                -87.34,
                -1e30,
                f32::NEG_INFINITY,
                f32::NAN,
            ]);
            while !xs.len().is_multiple_of(N) {
                xs.push(-1.0);
            }
            for chunk in xs.chunks_exact(N) {
                let a: [f32; N] = chunk.try_into().unwrap();
                let got = to_array(L::from(a).exp_of_nonpositive());
                for (x, g) in a.iter().zip(got) {
                    let want = (*x as f64).exp();
                    if x.is_nan() || *x < LOWEST_EXP_ARGUMENT {
                        assert!((0.0..1.2e-38).contains(&g) && g > 0.0, "e^{x} = {g}");
                    } else {
                        let rel = (g as f64 - want).abs() / want;
                        assert!(rel < 3e-7, "e^{x} = {g}, want {want}: {rel:e}");
                    }
                }
            }
        }
        on_every_lane_type!(check);
        // Elsewhere it is exp itself.
        assert_eq!((-3.5_f32).exp_of_nonpositive(), (-3.5_f32).exp());
        assert!(Real::exp_of_nonpositive(f64::NAN).is_nan());
    }

    /// `negligible_to_zero` on every lane type the CPU runs: the value itself, bit for bit,
    /// from `NEGLIGIBLE` (e^-36 rounded to `f32`) up, including 1 and infinity; exactly 0
    /// below it (subnormals and signed zeros included) and for NaN. The identity in scalar
    /// code.
    #[test]
    fn negligible_factors_are_zero_on_lanes() {
        fn check<L: Real + From<[f32; N]>, const N: usize>(to_array: impl Fn(L) -> [f32; N]) {
            let floor = NEGLIGIBLE as f32;
            let mut xs = vec![floor, f32::from_bits(floor.to_bits() + 1), 1e-15, 0.5, 1.0];
            xs.extend([
                f32::INFINITY,
                f32::from_bits(floor.to_bits() - 1),
                1e-20,
                1e-39,
            ]);
            xs.extend([f32::MIN_POSITIVE, 0.0, -0.0, -1.0, f32::NAN]);
            while !xs.len().is_multiple_of(N) {
                xs.push(0.25);
            }
            for chunk in xs.chunks_exact(N) {
                let a: [f32; N] = chunk.try_into().unwrap();
                let got = to_array(L::from(a).negligible_to_zero());
                for (x, g) in a.iter().zip(got) {
                    let want = if *x >= floor { x.to_bits() } else { 0 };
                    assert_eq!(g.to_bits(), want, "{x:e}: {g:e}");
                }
            }
        }
        on_every_lane_type!(check);
        assert_eq!((-36.0_f64).exp(), NEGLIGIBLE);
        assert_eq!(
            Real::negligible_to_zero(1e-39_f32).to_bits(),
            1e-39_f32.to_bits()
        );
        assert_eq!(Real::negligible_to_zero(1e-300_f64), 1e-300);
    }

    /// `asin_with_cos` on every lane type the CPU runs, with the cosine computed in `f32` as
    /// callers do: within 1.6e-7 (absolute, radians) of `f64`'s `asin` of the `f32` sine
    /// beyond the error of the `f32` cosine itself, and the `f32` rounding of the angle at 0
    /// and +-1 (signed zeros kept). Measured on the AMD EPYC (Zen 4): 1.44e-7 on every lane
    /// type, where the lanes' `atan2(sin, cos)` gives 1.30e-7 to 1.32e-7 (both about an ulp
    /// of pi/2, whose `f32` rounding alone is 4.4e-8).
    #[test]
    fn asin_with_cos_is_asin() {
        fn check<L: Real + From<[f32; N]>, const N: usize>(to_array: impl Fn(L) -> [f32; N]) {
            let mut sines: Vec<f32> = (0..=40_000).map(|k| -1.0 + k as f32 * 5e-5).collect();
            sines.extend([0.0, -0.0, 1.0, -1.0, 0.707_106_77, -0.707_106_77, 1e-30]);
            let mut worst = 0.0_f64;
            let mut worst_atan2 = 0.0_f64;
            for chunk in sines.chunks(N) {
                let s: [f32; N] = core::array::from_fn(|k| chunk.get(k).copied().unwrap_or(0.5));
                let c = s.map(|s| (1.0 - s * s).max(0.0).sqrt());
                let got = to_array(L::from(s).asin_with_cos(L::from(c)));
                for ((s, g), c) in s.iter().zip(got).zip(c) {
                    let want = (*s as f64).asin();
                    // The f32 cosine's own error moves the angle by about that much.
                    let from_cos = (c as f64 - (1.0 - (*s as f64).powi(2)).sqrt()).abs();
                    worst = worst.max((g as f64 - want).abs() - from_cos);
                    assert!(
                        (g as f64 - want).abs() <= 1.6e-7 + from_cos,
                        "asin({s}) = {g}"
                    );
                    let a = to_array(L::from([*s; N]).atan2(L::from([c; N])))[0];
                    worst_atan2 = worst_atan2.max((a as f64 - want).abs() - from_cos);
                    if *s == 0.0 || s.abs() == 1.0 {
                        assert_eq!(g.to_bits(), (*s as f64).asin().to_bits_f32(), "asin({s})");
                    }
                }
            }
            eprintln!("{N} lanes: asin_with_cos within {worst:.2e} beyond the cosine's error, atan2 {worst_atan2:.2e}");
        }
        trait F32Bits {
            fn to_bits_f32(self) -> u32;
        }
        impl F32Bits for f64 {
            fn to_bits_f32(self) -> u32 {
                (self as f32).to_bits()
            }
        }
        on_every_lane_type!(check);
        // Elsewhere it is atan2 itself.
        assert_eq!(0.3_f32.asin_with_cos(0.9), 0.3_f32.atan2(0.9));
    }

    /// `mul_add` rounds once on the instruction sets' lanes and twice elsewhere:
    /// (1 + 2^-23)^2 - (1 + 2^-22) is 2^-46 exactly, and 0 with the product rounded first.
    #[test]
    fn mul_add_is_fused_only_on_the_instruction_sets_lanes() {
        let a = 1.0 + f32::EPSILON;
        let c = -(1.0 + 2.0 * f32::EPSILON);
        let fused = 2f32.powi(-46);
        assert_eq!(f32::mul_add(a, a, c), fused, "std's fused multiply-add");
        assert_eq!(Real::mul_add(a, a, c), 0.0);
        let v = f32x16::splat(a);
        assert_eq!(Real::mul_add(v, v, f32x16::splat(c)).to_array(), [0.0; 16]);
        #[cfg(target_arch = "x86_64")]
        {
            use crate::real::InstructionSet;
            if InstructionSet::Avx512.is_supported() {
                let v = Avx512Lanes::splat(a);
                assert_eq!(
                    Real::mul_add(v, v, Avx512Lanes::splat(c)).to_array(),
                    [fused; 16]
                );
            }
            if InstructionSet::Avx2.is_supported() {
                let v = Avx2Lanes::splat(a);
                assert_eq!(
                    Real::mul_add(v, v, Avx2Lanes::splat(c)).to_array(),
                    [fused; 8]
                );
            }
        }
    }

    #[test]
    fn sixteen_lanes_agree_with_eight() {
        let xs: [f32; 16] = core::array::from_fn(|k| k as f32 * 1.37 - 9.0);
        let wide16 = wrap_angle(f32x16::from(xs)).exp().to_array();
        let lo = wrap_angle(f32x8::from(<[f32; 8]>::try_from(&xs[..8]).unwrap())).exp();
        let hi = wrap_angle(f32x8::from(<[f32; 8]>::try_from(&xs[8..]).unwrap())).exp();
        for (a, b) in wide16
            .iter()
            .zip(lo.to_array().iter().chain(&hi.to_array()))
        {
            assert!((a - b).abs() <= 1e-6 * b.abs(), "{a} vs {b}");
        }
        let m =
            <f32x16 as Real>::select(f32x16::from(xs).lt(f32x16::ZERO), f32x16::ONE, f32x16::ZERO);
        assert_eq!(m.to_array().iter().sum::<f32>(), 7.0);
    }
}
