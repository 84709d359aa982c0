//! Products of SH functions as straight-line generated code, generic over [`Real`].
//!
//! For real SH coefficient vectors `a`, `b` (bands `l < n`, crate convention), the projection of
//! the product `f g` onto the same bands is `c_k = Σ_ij T_ijk a_i b_j` with `T` the real Gaunt
//! tensor ([`super::gaunt::GauntTensor`]); the integral of a product of three is
//! `∫ f g h = Σ_ijk T_ijk a_i b_j c_k`. This is the operation Snyder 2006 ("Code Generated
//! Evaluation of the Product of Spherical Harmonics", Microsoft Research) generates code for.
//!
//! A [`ProductPlan`] is the optimised evaluation order; `apply` is generic over [`Real`], so
//! with `f32`/`f64` it runs on the CPU and with [`crate::real::Traced`] the fixed-count loops
//! unroll into a straight-line graph that prints as WGSL. Optimisations (counted on the traced
//! graph with `Graph::count_binary(Binary::Mul)`):
//! - every distinct product `a_i b_j` that some output needs is formed once;
//! - `T_ijk = T_jik`, so `a_i b_j` and `a_j b_i` share their coefficient;
//! - in each output, terms whose coefficients are equal in magnitude are summed (with signs)
//!   first and multiplied by the coefficient once. Equal coefficients are found exactly: the
//!   Gaunt coefficients are computed exactly and rounded once, so mathematically equal values
//!   are bitwise equal.
//! - zeros of `T` are skipped (the tensor is sparse).

use super::gaunt::GauntTensor;
use crate::error::ParamError;
use crate::real::Real;
use std::collections::HashMap;
use std::sync::OnceLock;

/// Band counts up to this use cached plans in [`product`] and [`triple_product_integral`].
pub const MAX_CACHED_BANDS: usize = 12;

/// Terms of one output sharing a coefficient: `coef * Σ ±products[index]`.
#[derive(Clone, Debug, PartialEq)]
struct Group {
    coef: f64,
    /// (index into `products`, subtract?)
    terms: Vec<(u32, bool)>,
}

/// The optimised straight-line evaluation of the projected SH product for `n_bands` bands.
#[derive(Clone, Debug, PartialEq)]
pub struct ProductPlan {
    n_bands: usize,
    /// Input index pairs `(i, j)` whose products `a_i b_j` are formed.
    products: Vec<(u32, u32)>,
    /// Per output coefficient: its coefficient groups.
    outputs: Vec<Vec<Group>>,
}

impl ProductPlan {
    /// Builds the plan for bands `l < n_bands` from the exact real Gaunt tensor.
    ///
    /// # Errors
    /// [`ParamError::OutOfRange`] unless `1 <= n_bands <= 16`
    /// ([`crate::sh::MAX_TENSOR_BANDS`], whose documentation states the tensor's cost).
    pub fn new(n_bands: usize) -> Result<Self, ParamError> {
        let tensor = GauntTensor::new(n_bands)?;
        let n = n_bands * n_bands;
        // Output k: list of (i, j, T) over ordered pairs.
        let mut rows: Vec<Vec<(u32, u32, f64)>> = vec![Vec::new(); n];
        for e in tensor.all() {
            rows[e.k as usize].push((e.i, e.j, e.value));
        }
        let mut product_index: HashMap<(u32, u32), u32> = HashMap::new();
        let mut products = Vec::new();
        let mut outputs = Vec::with_capacity(n);
        for row in &mut rows {
            row.sort_by_key(|&(i, j, _)| (i, j));
            let mut groups: Vec<Group> = Vec::new();
            for &(i, j, t) in row.iter() {
                let id = *product_index.entry((i, j)).or_insert_with(|| {
                    products.push((i, j));
                    (products.len() - 1) as u32
                });
                let coef = t.abs();
                let term = (id, t < 0.0);
                match groups.iter_mut().find(|g| g.coef == coef) {
                    Some(g) => g.terms.push(term),
                    None => groups.push(Group {
                        coef,
                        terms: vec![term],
                    }),
                }
            }
            outputs.push(groups);
        }
        Ok(ProductPlan {
            n_bands,
            products,
            outputs,
        })
    }

    /// A cached plan for `1 <= n_bands <= MAX_CACHED_BANDS` (built on first use).
    ///
    /// # Errors
    /// [`ParamError::OutOfRange`] for other band counts.
    pub fn cached(n_bands: usize) -> Result<&'static ProductPlan, ParamError> {
        static PLANS: [OnceLock<ProductPlan>; MAX_CACHED_BANDS + 1] =
            [const { OnceLock::new() }; MAX_CACHED_BANDS + 1];
        if n_bands == 0 || n_bands > MAX_CACHED_BANDS {
            return Err(ParamError::OutOfRange {
                name: "n_bands",
                value: n_bands as f64,
                allowed:
                    "must be in 1..=12 (MAX_CACHED_BANDS); build larger plans with ProductPlan::new",
            });
        }
        let slot = &PLANS[n_bands];
        if let Some(plan) = slot.get() {
            return Ok(plan);
        }
        let plan = ProductPlan::new(n_bands)?;
        Ok(slot.get_or_init(|| plan))
    }

    /// The band count.
    pub fn n_bands(&self) -> usize {
        self.n_bands
    }

    /// The number of coefficients `n_bands^2` of each input and of the output.
    pub fn len(&self) -> usize {
        self.n_bands * self.n_bands
    }

    /// Always `false` (a plan has at least one band).
    pub fn is_empty(&self) -> bool {
        false
    }

    /// Number of multiplies one [`ProductPlan::apply`] performs: distinct products plus one
    /// per coefficient group.
    pub fn multiplies(&self) -> usize {
        self.products.len() + self.outputs.iter().map(Vec::len).sum::<usize>()
    }

    fn check(&self, name: &'static str, len: usize) -> Result<(), ParamError> {
        if len == self.len() {
            Ok(())
        } else {
            Err(ParamError::OutOfRange {
                name,
                value: len as f64,
                allowed: "the slice length must equal n_bands^2",
            })
        }
    }

    /// The projected product `c_k = Σ_ij T_ijk a_i b_j` written into `out` (Snyder 2006).
    ///
    /// # Errors
    /// [`ParamError::OutOfRange`] if a slice length differs from `n_bands^2`.
    pub fn apply_into<R: Real>(&self, a: &[R], b: &[R], out: &mut [R]) -> Result<(), ParamError> {
        self.check("a.len()", a.len())?;
        self.check("b.len()", b.len())?;
        self.check("out.len()", out.len())?;
        let p: Vec<R> = self
            .products
            .iter()
            .map(|&(i, j)| a[i as usize] * b[j as usize])
            .collect();
        for (groups, o) in self.outputs.iter().zip(out.iter_mut()) {
            *o = self.row(groups, &p);
        }
        Ok(())
    }

    #[inline(always)]
    fn row<R: Real>(&self, groups: &[Group], p: &[R]) -> R {
        let mut acc: Option<R> = None;
        for g in groups {
            let mut sum: Option<R> = None;
            for &(id, negative) in &g.terms {
                let v = p[id as usize];
                sum = Some(match (sum, negative) {
                    (None, false) => v,
                    (None, true) => -v,
                    (Some(s), false) => s + v,
                    (Some(s), true) => s - v,
                });
            }
            let term = R::c(g.coef) * sum.unwrap_or(R::c(0.0));
            acc = Some(match acc {
                None => term,
                Some(s) => s + term,
            });
        }
        acc.unwrap_or(R::c(0.0))
    }

    /// The projected product as a new vector (see [`ProductPlan::apply_into`]).
    ///
    /// # Errors
    /// As [`ProductPlan::apply_into`].
    pub fn apply<R: Real>(&self, a: &[R], b: &[R]) -> Result<Vec<R>, ParamError> {
        let mut out = vec![R::c(0.0); self.len()];
        self.apply_into(a, b, &mut out)?;
        Ok(out)
    }

    /// The integral of the product of three SH functions, `Σ_ijk T_ijk a_i b_j c_k`, as
    /// `Σ_k c_k (a b)_k` with the projected product (exact, since every `k` is kept).
    ///
    /// # Errors
    /// [`ParamError::OutOfRange`] if a slice length differs from `n_bands^2`.
    pub fn triple<R: Real>(&self, a: &[R], b: &[R], c: &[R]) -> Result<R, ParamError> {
        self.check("c.len()", c.len())?;
        let ab = self.apply(a, b)?;
        let mut acc: Option<R> = None;
        for (&x, &y) in ab.iter().zip(c) {
            acc = Some(match acc {
                None => x * y,
                Some(s) => s + x * y,
            });
        }
        Ok(acc.unwrap_or(R::c(0.0)))
    }
}

/// The projected product of two SH vectors of `n_bands` bands (Snyder 2006), with the cached
/// [`ProductPlan`]: `c_k = Σ_ij T_ijk a_i b_j`, `T` the real Gaunt tensor.
///
/// # Errors
/// [`ParamError::OutOfRange`] unless `1 <= n_bands <= MAX_CACHED_BANDS` and both slices have
/// `n_bands^2` elements.
pub fn product<R: Real>(n_bands: usize, a: &[R], b: &[R]) -> Result<Vec<R>, ParamError> {
    ProductPlan::cached(n_bands)?.apply(a, b)
}

/// The integral over the sphere of the product of three SH functions of `n_bands` bands,
/// `Σ_ijk T_ijk a_i b_j c_k` (see [`ProductPlan::triple`]).
///
/// # Errors
/// As [`product`], for all three slices.
pub fn triple_product_integral<R: Real>(
    n_bands: usize,
    a: &[R],
    b: &[R],
    c: &[R],
) -> Result<R, ParamError> {
    ProductPlan::cached(n_bands)?.triple(a, b, c)
}
