//! Lane types for one instruction set each, whose operations are that set's intrinsics:
//! [`Avx512Lanes`] (sixteen lanes, one zmm register) and [`Avx2Lanes`] (eight lanes, one ymm
//! register), both with fused multiply-adds.
//!
//! `wide`'s types choose their instructions by the target features the crate is compiled
//! with, so a default build runs SSE2 whatever the machine. These types are what batch
//! evaluation instantiates a model with when [`super::InstructionSet::host`] finds AVX-512 or
//! AVX2 at run time ([`crate::bcsdf::HostBatch`]); the kernels are inlined into functions
//! compiled with those features ([`super::dispatch`]), where the intrinsics inline too.
//!
//! **Soundness.** The operations are safe functions that execute AVX-512 or AVX2 and FMA
//! instructions, which is undefined behaviour on a CPU without them. The types are private
//! to the crate, and a value of them is only created on a CPU that supports their instruction
//! set: [`crate::bcsdf::HostBatch`] instantiates a model with them only after the run-time
//! check, and the tests only on a supporting CPU.
//!
//! The transcendental functions of the kernels (`exp`, `atan2`) are the lane algorithms of
//! [`super::simd`], shared by every lane type; `ln`, `sin` and `cos` go through `wide` (the
//! build's instructions), off the hot paths.

#![cfg(target_arch = "x86_64")]

use core::arch::x86_64::*;
use core::ops::{Add, AddAssign, BitAnd, BitOr, Div, Mul, MulAssign, Neg, Not, Sub, SubAssign};

use super::simd::ExponentField;

/// The operations every lane type here has: wide's method names, so the shared lane
/// algorithms apply. `$v` is the register type, `$n` the lanes, `$p` the intrinsics' prefix
/// (`_mm512` or `_mm256`), `$wide` the `wide` type of the same width.
macro_rules! intrinsic_lanes {
    ($t:ident, $v:ty, $n:expr, $wide:ty, {
        set1: $set1:ident, add: $add:ident, sub: $sub:ident, mul: $mul:ident, div: $div:ident,
        sqrt: $sqrt:ident, min: $min:ident, max: $max:ident, fmadd: $fmadd:ident,
        fnmadd: $fnmadd:ident, and: $and:ident, or: $or:ident, xor: $xor:ident,
        cast_to_int: $to_int:ident, cast_from_int: $from_int:ident, shift_left: $slli:ident
    }) => {
        #[derive(Clone, Copy)]
        #[repr(transparent)]
        pub(crate) struct $t($v);

        impl core::fmt::Debug for $t {
            fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
                f.debug_tuple(stringify!($t)).field(&self.to_array()).finish()
            }
        }

        impl From<[f32; $n]> for $t {
            #[inline(always)]
            fn from(lanes: [f32; $n]) -> Self {
                // SAFETY: the register and the array have the same size, every bit pattern
                // is valid for both.
                $t(unsafe { core::mem::transmute::<[f32; $n], $v>(lanes) })
            }
        }

        impl $t {
            pub(crate) const ZERO: Self = $t(unsafe { core::mem::transmute::<[f32; $n], $v>([0.0; $n]) });
            pub(crate) const ONE: Self = $t(unsafe { core::mem::transmute::<[f32; $n], $v>([1.0; $n]) });
            pub(crate) const LOG2_E: Self = $t(unsafe {
                core::mem::transmute::<[f32; $n], $v>([core::f32::consts::LOG2_E; $n])
            });
            pub(crate) const PI: Self =
                $t(unsafe { core::mem::transmute::<[f32; $n], $v>([core::f32::consts::PI; $n]) });
            pub(crate) const FRAC_PI_2: Self = $t(unsafe {
                core::mem::transmute::<[f32; $n], $v>([core::f32::consts::FRAC_PI_2; $n])
            });
            pub(crate) const FRAC_PI_4: Self = $t(unsafe {
                core::mem::transmute::<[f32; $n], $v>([core::f32::consts::FRAC_PI_4; $n])
            });

            #[inline(always)]
            pub(crate) fn splat(value: f32) -> Self {
                // SAFETY: see the module documentation.
                $t(unsafe { $set1(value) })
            }
            #[inline(always)]
            pub(crate) fn to_array(self) -> [f32; $n] {
                // SAFETY: as in `from`.
                unsafe { core::mem::transmute::<$v, [f32; $n]>(self.0) }
            }
            #[inline(always)]
            pub(crate) fn sqrt(self) -> Self {
                // SAFETY: see the module documentation.
                $t(unsafe { $sqrt(self.0) })
            }
            /// `self < other ? self : other` per lane (`other` for NaN), as `wide`'s.
            #[inline(always)]
            pub(crate) fn fast_min(self, other: Self) -> Self {
                // SAFETY: see the module documentation.
                $t(unsafe { $min(self.0, other.0) })
            }
            /// `self > other ? self : other` per lane (`other` for NaN), as `wide`'s.
            #[inline(always)]
            pub(crate) fn fast_max(self, other: Self) -> Self {
                // SAFETY: see the module documentation.
                $t(unsafe { $max(self.0, other.0) })
            }
            /// `self * b + c`, fused.
            #[inline(always)]
            pub(crate) fn mul_add(self, b: Self, c: Self) -> Self {
                // SAFETY: see the module documentation.
                $t(unsafe { $fmadd(self.0, b.0, c.0) })
            }
            /// `c - self * b`, fused.
            #[inline(always)]
            pub(crate) fn mul_neg_add(self, b: Self, c: Self) -> Self {
                // SAFETY: see the module documentation.
                $t(unsafe { $fnmadd(self.0, b.0, c.0) })
            }
            #[inline(always)]
            pub(crate) fn abs(self) -> Self {
                !Self::splat(-0.0) & self
            }
            #[inline(always)]
            pub(crate) fn simd_gt(self, other: Self) -> Self {
                other.simd_lt(self)
            }
            #[inline(always)]
            pub(crate) fn simd_ge(self, other: Self) -> Self {
                other.simd_le(self)
            }
            /// `wide`'s lane function `f`, with the build's instructions.
            #[inline(always)]
            fn through_wide(self, f: impl Fn($wide) -> $wide) -> Self {
                Self::from(f(<$wide>::from(self.to_array())).to_array())
            }
            #[inline(always)]
            pub(crate) fn ln(self) -> Self {
                self.through_wide(<$wide>::ln)
            }
            #[inline(always)]
            pub(crate) fn sin(self) -> Self {
                self.through_wide(<$wide>::sin)
            }
            #[inline(always)]
            pub(crate) fn cos(self) -> Self {
                self.through_wide(<$wide>::cos)
            }
        }

        impl ExponentField for $t {
            #[inline(always)]
            fn shifted_into_exponent(biased: Self) -> Self {
                // SAFETY: see the module documentation.
                $t(unsafe { $from_int($slli::<23>($to_int(biased.0))) })
            }
        }

        intrinsic_lanes!(@binary $t, Add, add, $add, AddAssign, add_assign);
        intrinsic_lanes!(@binary $t, Sub, sub, $sub, SubAssign, sub_assign);
        intrinsic_lanes!(@binary $t, Mul, mul, $mul, MulAssign, mul_assign);

        impl Div for $t {
            type Output = $t;
            #[inline(always)]
            fn div(self, other: $t) -> $t {
                // SAFETY: see the module documentation.
                $t(unsafe { $div(self.0, other.0) })
            }
        }
        impl BitAnd for $t {
            type Output = $t;
            #[inline(always)]
            fn bitand(self, other: $t) -> $t {
                // SAFETY: see the module documentation.
                $t(unsafe { $and(self.0, other.0) })
            }
        }
        impl BitOr for $t {
            type Output = $t;
            #[inline(always)]
            fn bitor(self, other: $t) -> $t {
                // SAFETY: see the module documentation.
                $t(unsafe { $or(self.0, other.0) })
            }
        }
        impl Not for $t {
            type Output = $t;
            #[inline(always)]
            fn not(self) -> $t {
                let all_bits = $t::splat(f32::from_bits(u32::MAX));
                // SAFETY: see the module documentation.
                $t(unsafe { $xor(self.0, all_bits.0) })
            }
        }
        impl Neg for $t {
            type Output = $t;
            #[inline(always)]
            fn neg(self) -> $t {
                // SAFETY: see the module documentation.
                $t(unsafe { $xor(self.0, $t::splat(-0.0).0) })
            }
        }
    };
    (@binary $t:ident, $trait:ident, $method:ident, $intrinsic:ident, $assign_trait:ident, $assign:ident) => {
        impl $trait for $t {
            type Output = $t;
            #[inline(always)]
            fn $method(self, other: $t) -> $t {
                // SAFETY: see the module documentation.
                $t(unsafe { $intrinsic(self.0, other.0) })
            }
        }
        impl $assign_trait for $t {
            #[inline(always)]
            fn $assign(&mut self, other: $t) {
                *self = $trait::$method(*self, other);
            }
        }
    };
}

intrinsic_lanes!(Avx512Lanes, __m512, 16, wide::f32x16, {
    set1: _mm512_set1_ps, add: _mm512_add_ps, sub: _mm512_sub_ps, mul: _mm512_mul_ps,
    div: _mm512_div_ps, sqrt: _mm512_sqrt_ps, min: _mm512_min_ps, max: _mm512_max_ps,
    fmadd: _mm512_fmadd_ps, fnmadd: _mm512_fnmadd_ps, and: _mm512_and_ps, or: _mm512_or_ps,
    xor: _mm512_xor_ps, cast_to_int: _mm512_castps_si512, cast_from_int: _mm512_castsi512_ps,
    shift_left: _mm512_slli_epi32
});

intrinsic_lanes!(Avx2Lanes, __m256, 8, wide::f32x8, {
    set1: _mm256_set1_ps, add: _mm256_add_ps, sub: _mm256_sub_ps, mul: _mm256_mul_ps,
    div: _mm256_div_ps, sqrt: _mm256_sqrt_ps, min: _mm256_min_ps, max: _mm256_max_ps,
    fmadd: _mm256_fmadd_ps, fnmadd: _mm256_fnmadd_ps, and: _mm256_and_ps, or: _mm256_or_ps,
    xor: _mm256_xor_ps, cast_to_int: _mm256_castps_si256, cast_from_int: _mm256_castsi256_ps,
    shift_left: _mm256_slli_epi32
});

/// AVX-512 comparisons give a bit per lane; masks here are lanes with every bit set (as
/// `wide`'s), so the shared algorithms can `&` them with values.
impl Avx512Lanes {
    #[inline(always)]
    fn mask_lanes(mask: __mmask16) -> Self {
        // SAFETY: see the module documentation.
        Avx512Lanes(unsafe { _mm512_castsi512_ps(_mm512_movm_epi32(mask)) })
    }
    #[inline(always)]
    pub(crate) fn simd_lt(self, other: Self) -> Self {
        // SAFETY: see the module documentation.
        Self::mask_lanes(unsafe { _mm512_cmp_ps_mask::<_CMP_LT_OQ>(self.0, other.0) })
    }
    #[inline(always)]
    pub(crate) fn simd_le(self, other: Self) -> Self {
        // SAFETY: see the module documentation.
        Self::mask_lanes(unsafe { _mm512_cmp_ps_mask::<_CMP_LE_OQ>(self.0, other.0) })
    }
    #[inline(always)]
    pub(crate) fn simd_eq(self, other: Self) -> Self {
        // SAFETY: see the module documentation.
        Self::mask_lanes(unsafe { _mm512_cmp_ps_mask::<_CMP_EQ_OQ>(self.0, other.0) })
    }
    /// `on_true` where the mask `self` is set, `on_false` elsewhere.
    #[inline(always)]
    pub(crate) fn select(self, on_true: Self, on_false: Self) -> Self {
        // SAFETY: see the module documentation.
        Avx512Lanes(unsafe {
            let mask = _mm512_movepi32_mask(_mm512_castps_si512(self.0));
            _mm512_mask_blend_ps(mask, on_false.0, on_true.0)
        })
    }
    /// A mask of the lanes whose sign bit is set.
    #[inline(always)]
    pub(crate) fn is_sign_negative(self) -> Self {
        // SAFETY: see the module documentation.
        Self::mask_lanes(unsafe { _mm512_movepi32_mask(_mm512_castps_si512(self.0)) })
    }
    /// Whether the mask `self` is set in every lane.
    #[inline(always)]
    pub(crate) fn all(self) -> bool {
        // SAFETY: see the module documentation.
        unsafe { _mm512_movepi32_mask(_mm512_castps_si512(self.0)) == u16::MAX }
    }
    /// Rounds to the nearest integer, ties to even (`f32::round_ties_even`).
    #[inline(always)]
    pub(crate) fn round_ties_even(self) -> Self {
        // SAFETY: see the module documentation.
        Avx512Lanes(unsafe {
            _mm512_roundscale_ps::<{ _MM_FROUND_TO_NEAREST_INT | _MM_FROUND_NO_EXC }>(self.0)
        })
    }
    /// `f32::floor` per lane.
    #[inline(always)]
    pub(crate) fn floor(self) -> Self {
        // SAFETY: see the module documentation.
        Avx512Lanes(unsafe {
            _mm512_roundscale_ps::<{ _MM_FROUND_TO_NEG_INF | _MM_FROUND_NO_EXC }>(self.0)
        })
    }
}

impl Avx2Lanes {
    #[inline(always)]
    fn compare<const PREDICATE: i32>(self, other: Self) -> Self {
        // SAFETY: see the module documentation.
        Avx2Lanes(unsafe { _mm256_cmp_ps::<PREDICATE>(self.0, other.0) })
    }
    #[inline(always)]
    pub(crate) fn simd_lt(self, other: Self) -> Self {
        self.compare::<_CMP_LT_OQ>(other)
    }
    #[inline(always)]
    pub(crate) fn simd_le(self, other: Self) -> Self {
        self.compare::<_CMP_LE_OQ>(other)
    }
    #[inline(always)]
    pub(crate) fn simd_eq(self, other: Self) -> Self {
        self.compare::<_CMP_EQ_OQ>(other)
    }
    /// `on_true` where the mask `self` is set, `on_false` elsewhere.
    #[inline(always)]
    pub(crate) fn select(self, on_true: Self, on_false: Self) -> Self {
        // SAFETY: see the module documentation.
        Avx2Lanes(unsafe { _mm256_blendv_ps(on_false.0, on_true.0, self.0) })
    }
    /// Whether the mask `self` is set in every lane.
    #[inline(always)]
    pub(crate) fn all(self) -> bool {
        // SAFETY: see the module documentation.
        unsafe { _mm256_movemask_ps(self.0) == 0xFF }
    }
    /// A mask of the lanes whose sign bit is set.
    #[inline(always)]
    pub(crate) fn is_sign_negative(self) -> Self {
        // SAFETY: see the module documentation.
        Avx2Lanes(unsafe {
            _mm256_castsi256_ps(_mm256_srai_epi32::<31>(_mm256_castps_si256(self.0)))
        })
    }
    /// Rounds to the nearest integer, ties to even (`f32::round_ties_even`).
    #[inline(always)]
    pub(crate) fn round_ties_even(self) -> Self {
        // SAFETY: see the module documentation.
        Avx2Lanes(unsafe {
            _mm256_round_ps::<{ _MM_FROUND_TO_NEAREST_INT | _MM_FROUND_NO_EXC }>(self.0)
        })
    }
    /// `f32::floor` per lane.
    #[inline(always)]
    pub(crate) fn floor(self) -> Self {
        // SAFETY: see the module documentation.
        Avx2Lanes(unsafe { _mm256_floor_ps(self.0) })
    }
}
