//! Eight single-precision lanes per value: the same generic code evaluates eight samples at
//! once. Transcendental functions are `wide`'s vectorised polynomial approximations, so results
//! differ from the scalar `f32` instantiation by a few ulp (the tests bound the difference).

use super::Real;
use wide::{f32x8, CmpLe, CmpLt};

impl Real for f32x8 {
    /// A lane mask: all bits set where the comparison holds.
    type Mask = f32x8;
    const DOUBLE: bool = false;

    #[inline(always)]
    fn c(value: f64) -> Self {
        f32x8::splat(value as f32)
    }
    #[inline(always)]
    fn sqrt(self) -> Self {
        f32x8::sqrt(self)
    }
    #[inline(always)]
    fn exp(self) -> Self {
        f32x8::exp(self)
    }
    #[inline(always)]
    fn ln(self) -> Self {
        f32x8::ln(self)
    }
    #[inline(always)]
    fn sin(self) -> Self {
        f32x8::sin(self)
    }
    #[inline(always)]
    fn cos(self) -> Self {
        f32x8::cos(self)
    }
    #[inline(always)]
    fn atan2(self, x: Self) -> Self {
        f32x8::atan2(self, x)
    }
    #[inline(always)]
    fn abs(self) -> Self {
        f32x8::abs(self)
    }
    #[inline(always)]
    fn min(self, other: Self) -> Self {
        f32x8::fast_min(self, other)
    }
    #[inline(always)]
    fn max(self, other: Self) -> Self {
        f32x8::fast_max(self, other)
    }
    #[inline(always)]
    fn floor(self) -> Self {
        f32x8::floor(self)
    }
    #[inline(always)]
    fn lt(self, other: Self) -> Self {
        self.cmp_lt(other)
    }
    #[inline(always)]
    fn le(self, other: Self) -> Self {
        self.cmp_le(other)
    }
    #[inline(always)]
    fn select(mask: Self, on_true: Self, on_false: Self) -> Self {
        mask.blend(on_true, on_false)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::real::wrap_angle;

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
}
