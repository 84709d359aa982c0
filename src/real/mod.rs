//! The scalar abstraction every piece of shading math is written against.
//!
//! A function generic over [`Real`] is written once and instantiated as
//!
//! | type | purpose |
//! | --- | --- |
//! | `f64` | the reference: fits, tables, tests, error reports |
//! | `f32` | CPU renderers and benchmarks |
//! | [`wide::f32x8`], [`wide::f32x16`] | eight or sixteen samples per value for batch evaluation ([`BatchReal`]), with the build's instructions |
//! | AVX-512 and AVX2 lanes (crate-private) | batch evaluation on the host's instruction set, chosen at run time ([`crate::bcsdf::HostBatch`]) |
//! | [`Traced`] | records the computation as a graph that prints as WGSL ([`trace`]) |
//!
//! Rules for generic code (they keep the traced graph equal to the CPU computation):
//! no data-dependent control flow (use [`Real::select`], both arms must be safe to evaluate),
//! fixed-count loops, constants written as `R::c(1.55)`. Control flow on the type-level
//! constant [`Real::DOUBLE`] is allowed: it picks reference-grade approximations for `f64`.
//!
//! Lookup tables (textures in a shader) are read with [`Real::sample_table`] from a
//! [`SharedTable`]: multilinear interpolation, clamp to the edge, with the semantics of
//! [`crate::lut::Table::lookup_into`] in every instantiation.

mod dispatch;
mod isa;
mod named;
mod simd;
mod structure;
mod traced;

use core::fmt::Debug;
use core::ops::{Add, AddAssign, BitAnd, BitOr, Div, Mul, MulAssign, Neg, Not, Sub, SubAssign};

use crate::lut::SharedTable;

pub use dispatch::InstructionSet;
#[cfg(target_arch = "x86_64")]
pub(crate) use dispatch::{with_avx2, with_avx512};
#[cfg(target_arch = "x86_64")]
pub(crate) use isa::{Avx2Lanes, Avx512Lanes};
pub use named::{NamedConstant, FOUR_PI, INV_TWO_PI, PI, SQRT_2, SQRT_TWO_PI, TINY, TWO_PI};
pub use simd::BatchReal;
pub use structure::{
    Body, CallKind, CallSite, ConstArray, Function, FunctionKind, ShaderFunction, ShaderLoop, Shape,
};
pub use traced::{
    trace, trace_with, ArgType, Binary, Graph, Node, Parameter, ResultType, Signature, StructType,
    Traced, TracedMask, Unary, NO_COORDINATE, TEXTURE_CHANNELS,
};

/// e^-36 (2.3e-16): the factors in [0, 1] below it are exactly 0 on the SIMD lanes
/// ([`Real::negligible_to_zero`]).
pub const NEGLIGIBLE: f64 = 2.319_522_830_243_569_4e-16;

/// A scalar (or a SIMD vector of scalars, or a symbolic value) shading code computes with.
///
/// Every method is a pure function of its arguments. Methods are named after their WGSL
/// counterparts where one exists, so that the traced code and the CPU code agree.
pub trait Real:
    Copy
    + Debug
    + Add<Output = Self>
    + Sub<Output = Self>
    + Mul<Output = Self>
    + Div<Output = Self>
    + Neg<Output = Self>
    + AddAssign
    + SubAssign
    + MulAssign
{
    /// The result of a comparison: `bool`, a SIMD lane mask, or a traced boolean.
    type Mask: Copy
        + BitAnd<Output = Self::Mask>
        + BitOr<Output = Self::Mask>
        + Not<Output = Self::Mask>;

    /// `true` for `f64`: generic code may then choose reference-grade (slower, more accurate)
    /// approximations. `false` for every single-precision instantiation, traced code included.
    const DOUBLE: bool;

    /// A constant, rounded once to the working precision.
    fn c(value: f64) -> Self;
    /// `sqrt`; callers guarantee a non-negative argument (see [`safe_sqrt`]).
    fn sqrt(self) -> Self;
    /// Natural exponential.
    fn exp(self) -> Self;
    /// `e^self` for `self <= 0`, which callers guarantee: the decays of lobes, distributions
    /// and transmittances. The SIMD lanes drop [`Real::exp`]'s handling of overflow and NaN
    /// there: an argument below -87.34 gives e^-87.34 (1.2e-38, where `f32::exp` gives a
    /// subnormal or 0), and NaN gives 1.2e-38 too; their polynomial is two degrees lower
    /// (the argument's reduction never needs the wider interval of an overflowing `exp`):
    /// 1.9e-7 relative on [-87.33, 0], within the 3e-7 the tests hold `exp` to. Everywhere
    /// else it is [`Real::exp`].
    #[inline(always)]
    fn exp_of_nonpositive(self) -> Self {
        self.exp()
    }
    /// `self`, a factor in [0, 1] of a product (the decay of a lobe or a distribution, a
    /// transmittance, an attenuation), or exactly 0 on the SIMD lanes where it is below
    /// [`NEGLIGIBLE`] (e^-36, 2.3e-16 of the factor's largest value). Two such factors times
    /// the lobes' normalisations (at least 0.02 together) are 0 or above 1e-33, so such
    /// products stay above the smallest normal `f32`, 1.2e-38; only a sum of three-factor
    /// products, S, can still fall below it, where every term is negligible. Products
    /// of decays had come out subnormal, and an x86 core takes a microcode assist of a
    /// hundred cycles or more for every instruction that gives a subnormal (README, speed
    /// section: the Chiang batch spent a fifth of its time so at the speed benchmark's
    /// material). What is dropped is below 2.3e-16 of the lobe's scale; e^-24 was too coarse
    /// (lobes of scale 50 lost more than the batch tests' absolute floor of 1e-6 allows). The
    /// identity in scalar and traced code: the traced graph is the scalar `f32` code bit for
    /// bit, and GPUs flush subnormals themselves.
    #[inline(always)]
    fn negligible_to_zero(self) -> Self {
        self
    }
    /// Natural logarithm; callers guarantee a positive argument.
    fn ln(self) -> Self;
    /// Sine of an angle in radians; callers keep the argument within a few multiples of pi.
    fn sin(self) -> Self;
    /// Cosine of an angle in radians.
    fn cos(self) -> Self;
    /// Four-quadrant arc tangent of `self / x`; callers never pass (0, 0).
    fn atan2(self, x: Self) -> Self;
    /// The angle in [-pi/2, pi/2] whose sine is `self` (in [-1, 1]) and whose cosine is `cos`,
    /// which callers pass as they computed it, `sqrt(1 - self^2)`: `atan2(self, cos)` here, in
    /// `f32`, `f64` and traced code (shader code keeps its `atan2`). The SIMD lanes override it
    /// with a polynomial in the smaller of `|self|` and `cos`, which needs no division (their
    /// `atan2` needs one).
    #[inline(always)]
    fn asin_with_cos(self, cos: Self) -> Self {
        self.atan2(cos)
    }
    /// Absolute value.
    fn abs(self) -> Self;
    /// Smaller of two values.
    fn min(self, other: Self) -> Self;
    /// Larger of two values.
    fn max(self, other: Self) -> Self;
    /// Largest integer not greater than the value.
    fn floor(self) -> Self;
    /// `self < other`.
    fn lt(self, other: Self) -> Self::Mask;
    /// `self <= other`.
    fn le(self, other: Self) -> Self::Mask;
    /// `if mask { on_true } else { on_false }`, lane by lane; both arms are always evaluated.
    fn select(mask: Self::Mask, on_true: Self, on_false: Self) -> Self;
    /// Whether `mask` holds in every lane, as far as the code can know where it runs: the
    /// `bool` itself for `f32` and `f64`, every lane for SIMD lanes, and always `false` in
    /// traced code, which does not branch on data. Callers use it only to skip work whose
    /// result a [`Real::select`] would discard, so every answer gives the same values.
    fn every_lane(mask: Self::Mask) -> bool;
    /// The values of every channel of `table` at `coords` (one coordinate per axis, in the
    /// axes' units): a texture fetch, with the semantics of
    /// [`crate::lut::Table::lookup_into`] (multilinear interpolation between the samples,
    /// weights from [`crate::lut::axis_cell`], clamp to the edge, a NaN coordinate read as
    /// the axis minimum).
    ///
    /// - `f32`: exactly `lookup_into`'s bits ([`SharedTable::lookup_f32`]).
    /// - `f64`: the same interpolation in `f64` from the stored `f32` samples
    ///   ([`SharedTable::lookup_f64`]), so it differs from `f32` by rounding only.
    /// - SIMD lanes: the `f32` lookup lane by lane (a gather), bit for bit the scalar `f32`.
    /// - [`Traced`]: one fetch node per channel, recording the table (kept by the graph,
    ///   deduplicated by pointer), the coordinates and the channel; [`Graph::eval_f32`]
    ///   evaluates it with `lookup_into` and [`Graph::to_wgsl`] prints a `textureSampleLevel`.
    fn sample_table<const D: usize, const C: usize>(
        table: &SharedTable<D, C>,
        coords: [Self; D],
    ) -> [Self; C];

    /// `self * a + b`, for Horner's rule and other sums of products whose error bounds allow
    /// either rounding: fused (rounded once) on the lanes of an instruction set with fused
    /// multiply-adds, the AVX-512 and AVX2 lanes of [`crate::bcsdf::HostBatch`]; rounded twice
    /// everywhere else (`f32`, `f64`, `wide`'s lanes, shader code), so that traced code
    /// evaluates bit for bit as the `f32` code. Results may thus differ in the last bits
    /// between instruction sets.
    #[inline(always)]
    fn mul_add(self, a: Self, b: Self) -> Self {
        self * a + b
    }

    /// Value `index` of the named constant `constant` ([`NamedConstant::get`],
    /// [`NamedConstant::at`]): `Self::c(value)` in every instantiation but the tracer, which
    /// records the name with it so that shader code reads the constant by name.
    ///
    /// # Panics
    /// If `index` is beyond `constant.values`.
    #[inline(always)]
    fn named(constant: &'static NamedConstant, index: usize) -> Self {
        Self::c(constant.values[index])
    }

    /// `self`, named `name` in shader code (`let name = ...;`), so that a value the Rust
    /// code names (`cos_phi`, `cos_theta_d`) keeps its name there: the identity in every
    /// instantiation but the tracer, which records the name with the value's node (the first
    /// name given to a node is kept). Names are lower-case identifiers of the shading
    /// languages; the shader's writer numbers one that is taken (`cos_phi_1`).
    #[inline(always)]
    fn label(self, name: &'static str) -> Self {
        let _ = name;
        self
    }

    /// `body(args)`, marked as the shader function `function`: the `f32`, `f64` and SIMD
    /// instantiations just call `body`; the tracer records `body` once as a named function
    /// of the graph ([`Graph::functions`]) and here a call of it, so the emitted shader calls
    /// a function where the Rust code calls one. `args` are the scalars of
    /// `function.parameters` in order (a `Vec3` parameter as x, y, z). Values of the caller
    /// that `body` uses besides `args` become further parameters of the shader function.
    ///
    /// # Panics
    /// Traced: if `function.parameters` do not have `N` scalars or `function.result` does not
    /// have `M`.
    #[inline(always)]
    fn call<const N: usize, const M: usize>(
        function: &'static ShaderFunction,
        args: [Self; N],
        body: impl FnOnce([Self; N]) -> [Self; M],
    ) -> [Self; M] {
        let _ = function;
        body(args)
    }

    /// `state = body(state, element)` for each of `elements` in order, from `init`; marked
    /// as the loop `info`: the tracer records `body` once as a function of the graph and the
    /// elements as a constant array ([`Graph::arrays`]), so the emitted shader loops over a
    /// `const` array instead of unrolling.
    ///
    /// # Panics
    /// Traced: if the elements are not constants (values of [`Real::c`]), or `info` does
    /// not name `E` fields and `S` state scalars.
    #[inline(always)]
    fn fold<const S: usize, const E: usize>(
        info: &'static ShaderLoop,
        elements: &[[Self; E]],
        init: [Self; S],
        body: impl Fn([Self; S], [Self; E]) -> [Self; S],
    ) -> [Self; S] {
        let _ = info;
        let mut state = init;
        for element in elements {
            state = body(state, *element);
        }
        state
    }

    /// `self > other`.
    #[inline(always)]
    fn gt(self, other: Self) -> Self::Mask {
        other.lt(self)
    }
    /// `self >= other`.
    #[inline(always)]
    fn ge(self, other: Self) -> Self::Mask {
        other.le(self)
    }
    /// `self * self`.
    #[inline(always)]
    fn sqr(self) -> Self {
        self * self
    }
    /// The value clamped to `[lo, hi]`.
    #[inline(always)]
    fn clamp(self, lo: Self, hi: Self) -> Self {
        self.max(lo).min(hi)
    }
}

macro_rules! impl_real_for_float {
    ($t:ty, $double:expr, $lookup:ident) => {
        impl Real for $t {
            type Mask = bool;
            const DOUBLE: bool = $double;
            #[inline(always)]
            fn c(value: f64) -> Self {
                value as $t
            }
            #[inline(always)]
            fn sqrt(self) -> Self {
                <$t>::sqrt(self)
            }
            #[inline(always)]
            fn exp(self) -> Self {
                <$t>::exp(self)
            }
            #[inline(always)]
            fn ln(self) -> Self {
                <$t>::ln(self)
            }
            #[inline(always)]
            fn sin(self) -> Self {
                <$t>::sin(self)
            }
            #[inline(always)]
            fn cos(self) -> Self {
                <$t>::cos(self)
            }
            #[inline(always)]
            fn atan2(self, x: Self) -> Self {
                <$t>::atan2(self, x)
            }
            #[inline(always)]
            fn abs(self) -> Self {
                <$t>::abs(self)
            }
            // Defined by one comparison so the result, the sign of a zero included, depends only
            // on the operands' order: `f32::max(-0.0, 0.0)` may give either zero depending on
            // constant folding, which would break bit-identity with the traced graph. A NaN
            // `self` yields `other`.
            #[inline(always)]
            fn min(self, other: Self) -> Self {
                if self.is_nan() || other < self {
                    other
                } else {
                    self
                }
            }
            #[inline(always)]
            fn max(self, other: Self) -> Self {
                if self.is_nan() || self < other {
                    other
                } else {
                    self
                }
            }
            #[inline(always)]
            fn floor(self) -> Self {
                <$t>::floor(self)
            }
            #[inline(always)]
            fn lt(self, other: Self) -> bool {
                self < other
            }
            #[inline(always)]
            fn le(self, other: Self) -> bool {
                self <= other
            }
            #[inline(always)]
            fn every_lane(mask: bool) -> bool {
                mask
            }
            #[inline(always)]
            fn select(mask: bool, on_true: Self, on_false: Self) -> Self {
                if mask {
                    on_true
                } else {
                    on_false
                }
            }
            #[inline(always)]
            fn sample_table<const D: usize, const C: usize>(
                table: &SharedTable<D, C>,
                coords: [Self; D],
            ) -> [Self; C] {
                table.$lookup(coords)
            }
        }
    };
}

impl_real_for_float!(f64, true, lookup_f64);
impl_real_for_float!(f32, false, lookup_f32);

/// pi as a constant of the working precision ([`PI`]).
#[inline(always)]
pub fn pi<R: Real>() -> R {
    PI.get()
}

/// `sqrt(max(x, 0))`: the square root of a quantity that is non-negative in exact arithmetic
/// but may round slightly below zero.
#[inline(always)]
pub fn safe_sqrt<R: Real>(x: R) -> R {
    x.max(R::c(0.0)).sqrt()
}

/// `asin(x)` for `x` clamped to [-1, 1], written as `atan2(x, sqrt(1 - x^2))`, which GPUs
/// evaluate more accurately than `asin` (see docs/ARCHITECTURE.md). Exact 0 at x = 0, +-pi/2 at +-1.
#[inline(always)]
pub fn safe_asin<R: Real>(x: R) -> R {
    let x = x.clamp(R::c(-1.0), R::c(1.0));
    x.atan2(safe_sqrt(R::c(1.0) - x * x))
}

/// The angle `x` wrapped into [-pi, pi] without loops: `x - 2 pi k` for the whole number of
/// turns `k = floor(x / (2 pi) + 1/2)`, by two multiply-adds and a rounding.
#[inline(always)]
pub fn wrap_angle<R: Real>(x: R) -> R {
    let turns = x.mul_add(INV_TWO_PI.get::<R>(), R::c(0.5)).floor();
    turns.mul_add(-TWO_PI.get::<R>(), x)
}

/// `x^n` for a constant `n >= 1` by binary exponentiation: the product of the squares
/// `x^(2^k)` of the set bits of `n`, lowest first, which is the order of LLVM's expansion of
/// `powi` and of compiler-rt's `__powidf2`, so that in `f64` it is `f64::powi` bit for bit
/// (derivations written with `powi` keep their values when made generic).
///
/// # Panics
/// If `n` is 0 (every caller raises to a positive constant power).
#[inline(always)]
pub(crate) fn powi<R: Real>(x: R, n: u32) -> R {
    assert!(n > 0, "powi needs a positive exponent");
    let (mut result, mut square, mut bits) = (None, x, n);
    while bits > 0 {
        if bits & 1 == 1 {
            result = Some(result.map_or(square, |r: R| r * square));
        }
        bits >>= 1;
        if bits > 0 {
            square = square * square;
        }
    }
    result.unwrap_or_else(|| unreachable!("n > 0 has a set bit"))
}

/// Evaluates the polynomial `c[0] + c[1] x + c[2] x^2 + ...` by Horner's rule.
#[inline(always)]
pub fn horner<R: Real>(x: R, coefficients: &[f64]) -> R {
    horner_by_power(
        x,
        coefficients.len(),
        #[inline(always)]
        |k| R::c(coefficients[k]),
    )
}

/// [`horner`] of a named table of coefficients (lowest power first), which shader code reads
/// by name.
#[inline(always)]
pub fn horner_named<R: Real>(x: R, coefficients: &'static NamedConstant) -> R {
    horner_by_power(
        x,
        coefficients.values.len(),
        #[inline(always)]
        |k| coefficients.at(k),
    )
}

/// Horner's rule over `n` coefficients, `coefficient(k)` that of `x^k` (0 for none): a plain
/// loop, so that batch kernels inline it ([`array_from_fn`]).
#[inline(always)]
fn horner_by_power<R: Real>(x: R, n: usize, coefficient: impl Fn(usize) -> R) -> R {
    let Some(mut power) = n.checked_sub(1) else {
        return R::c(0.0);
    };
    let mut sum = coefficient(power);
    while power > 0 {
        power -= 1;
        sum = sum.mul_add(x, coefficient(power));
    }
    sum
}

/// `core::array::from_fn`, always inlined. Batch kernels are compiled once per instruction set
/// by inlining them into functions with those target features ([`InstructionSet`]); std's
/// `from_fn` and `map` are functions of their own that the inliner may keep, and a function
/// that is not inlined runs with the build's baseline instructions. Kernels use these helpers
/// with `#[inline(always)]` closures on their hot paths.
#[inline(always)]
pub(crate) fn array_from_fn<T: Copy, const N: usize>(mut f: impl FnMut(usize) -> T) -> [T; N] {
    const { assert!(N > 0, "array_from_fn builds non-empty arrays") };
    let mut out = [f(0); N];
    for (k, slot) in out.iter_mut().enumerate().skip(1) {
        *slot = f(k);
    }
    out
}

/// `array.map(f)`, always inlined (see [`array_from_fn`]).
#[inline(always)]
pub(crate) fn map_array<T: Copy, U: Copy, const N: usize>(
    array: [T; N],
    mut f: impl FnMut(T) -> U,
) -> [U; N] {
    array_from_fn(
        #[inline(always)]
        |k| f(array[k]),
    )
}

/// [`map_array`] as a method: `array.map_inline(#[inline(always)] |x| ..)`.
pub(crate) trait MapInline<T, const N: usize> {
    /// `self.map(f)`, always inlined.
    fn map_inline<U: Copy>(self, f: impl FnMut(T) -> U) -> [U; N];
}

impl<T: Copy, const N: usize> MapInline<T, N> for [T; N] {
    #[inline(always)]
    fn map_inline<U: Copy>(self, f: impl FnMut(T) -> U) -> [U; N] {
        map_array(self, f)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn wrap_angle_lands_in_range_and_preserves_the_angle() {
        for k in -40..=40 {
            let x = k as f64 * 0.77;
            let w = wrap_angle(x);
            assert!(
                (-core::f64::consts::PI..=core::f64::consts::PI).contains(&w),
                "{x} -> {w}"
            );
            assert!((w.sin() - x.sin()).abs() < 1e-12 && (w.cos() - x.cos()).abs() < 1e-12);
        }
    }

    #[test]
    fn powi_is_f64_powi_bit_for_bit() {
        let mut x = 0.123_456_789_f64;
        for _ in 0..200 {
            x = (x * 3.7 + 0.31).fract() * 1.7;
            for n in [1, 2, 3, 4, 5, 20, 22] {
                assert_eq!(powi(x, n).to_bits(), x.powi(n as i32).to_bits(), "{x}^{n}");
                let y = x as f32;
                assert_eq!(powi(y, n).to_bits(), y.powi(n as i32).to_bits(), "{y}^{n}");
            }
        }
    }

    #[test]
    fn safe_asin_matches_asin_and_clamps() {
        for k in -100..=100 {
            let x = k as f64 / 100.0;
            assert!((safe_asin(x) - x.asin()).abs() < 1e-15);
        }
        assert_eq!(safe_asin(1.5_f64), core::f64::consts::FRAC_PI_2);
        assert_eq!(safe_asin(-1.5_f32), -core::f32::consts::FRAC_PI_2);
    }
}
