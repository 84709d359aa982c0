//! The contract every scattering model implements, and what a model gets from it.
//!
//! - [`Bcsdf`]: evaluation of S in the fibre's local frame with **no cosine factor of any kind**
//!   (with sigma_a = 0 the integral of S over all incident directions is 1 for an
//!   energy-conserving model), on a [`Query`] that carries wi, wo and, for near-field models,
//!   the offset h. [`SampledBcsdf`] adds the pdf and importance sampling where a model has
//!   them.
//! - [`Model`]: a model built (in `f64`) from validated, named parameters derives its constants
//!   once into a named struct, its *uniforms* ([`UniformBlock`], declared with
//!   [`uniform_block!`](crate::uniform_block)); [`Model::instantiate`] rebuilds the same model in
//!   any precision from those uniforms (`f32`, SIMD lanes), and [`trace_model`] with symbolic
//!   uniforms, which the shader code then receives as a named struct.
//!
//! What a model gets for free from implementing these: batch evaluation over SIMD lanes
//! ([`crate::bcsdf::eval_batch`]), tracing to shader code ([`trace_eval`]), the white-furnace
//! and lobe-energy diagnostics ([`crate::diagnostics`]) and, registered in
//! [`crate::registry`], the command line's `eval`.

use crate::error::ParamError;
use crate::geometry::V3;
use crate::real::{
    trace_with, ArgType, Graph, Parameter, Real, ResultType, Signature, StructType, Traced,
};

/// The arguments of one evaluation: unit directions in the fibre's local frame (tangent +X;
/// `wi` towards the light, `wo` towards the viewer, both pointing away from the fibre) and the
/// offset `h` in [-1, 1] across the fibre's width where `wo`'s ray meets it. Far-field models
/// ignore `h`.
///
/// **Validation.** Evaluation is the hot path (and traces to shader code), so [`Query::new`]
/// checks nothing and [`Bcsdf::eval`] and [`SampledBcsdf::pdf`] take its directions as given:
/// a direction of length 2 scales S by a model-dependent factor, and a zero, infinite or NaN
/// one gives meaningless numbers or NaN. Directions from outside a program (a file, a user)
/// go through [`Query::checked`], which rejects them with a typed error or normalises them;
/// the batch functions ([`crate::bcsdf::eval_batch`]) check every sample.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Query<R> {
    /// Direction towards the light.
    pub wi: V3<R>,
    /// Direction towards the viewer.
    pub wo: V3<R>,
    /// Offset across the fibre, in [-1, 1] (near-field models clamp it).
    pub h: R,
}

/// Largest deviation of a direction's length from 1 that [`Query::checked`] and the batch
/// functions accept: `1e-3`, room for directions written with a few digits.
pub const UNIT_TOLERANCE: f64 = 1e-3;

impl Query<f64> {
    /// The query of untrusted values: each direction must have finite components and length 1
    /// within [`UNIT_TOLERANCE`] (it is then normalised, so a direction written as
    /// `0.6,0.8,0.0005` evaluates as the unit vector), and `h` must be in [-1, 1].
    ///
    /// # Errors
    /// [`ParamError::BadVector`] for a direction with a non-finite component,
    /// [`ParamError::NotUnit`] for one of another length (zero included), and
    /// [`ParamError::OutOfRange`] naming `h` outside [-1, 1] (NaN included).
    pub fn checked(wi: V3<f64>, wo: V3<f64>, h: f64) -> Result<Self, ParamError> {
        let h = ParamError::check("h", h, "the offset must be in [-1, 1]", |h| {
            (-1.0..=1.0).contains(&h)
        })?;
        Ok(Query::new(unit("wi", wi)?, unit("wo", wo)?, h))
    }
}

/// `w` normalised, if its components are finite and its length is 1 within
/// [`UNIT_TOLERANCE`].
fn unit(name: &'static str, w: V3<f64>) -> Result<V3<f64>, ParamError> {
    if ![w.x, w.y, w.z].iter().all(|c| c.is_finite()) {
        return Err(ParamError::BadVector {
            name,
            x: w.x,
            y: w.y,
            z: w.z,
            allowed: "a direction's components must be finite",
        });
    }
    let length = w.dot(w).sqrt();
    if (length - 1.0).abs() <= UNIT_TOLERANCE {
        Ok(w.scale(1.0 / length))
    } else {
        Err(ParamError::NotUnit {
            name,
            x: w.x,
            y: w.y,
            z: w.z,
            length,
            tolerance: UNIT_TOLERANCE,
        })
    }
}

impl<R: Real> Query<R> {
    /// The query of a near-field model, unchecked (see [`Query`]; [`Query::checked`] validates).
    pub fn new(wi: V3<R>, wo: V3<R>, h: R) -> Self {
        Query { wi, wo, h }
    }

    /// The query of a far-field model (h = 0, ignored).
    pub fn far(wi: V3<R>, wo: V3<R>) -> Self {
        Query {
            wi,
            wo,
            h: R::c(0.0),
        }
    }
}

/// The uniform random numbers in [0, 1) importance sampling consumes.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RandomNumbers<R> {
    /// Chooses the lobe (and, remapped within the lobe's share, the azimuth).
    pub lobe: R,
    /// The longitudinal angle about the lobe's axis.
    pub longitudinal: R,
    /// The azimuth around the longitudinal cone.
    pub cone: R,
    /// The offset h across the fibre (far-field models, which average over it).
    pub offset: R,
}

/// One importance sample.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct HairSample<R> {
    /// The sampled incident direction (unit, local frame).
    pub wi: V3<R>,
    /// `S(wi, wo, h)` per channel (no cosine factor): the BCSDF's value at `wi`, **not** the
    /// estimator weight ([`HairSample::weight`]).
    pub value: [R; 3],
    /// The solid-angle density of `wi`; the estimator weight is `value / pdf`
    /// ([`HairSample::weight`]).
    pub pdf: R,
}

impl<R: Real> HairSample<R> {
    /// The estimator weight `value / pdf` per channel (the cosine factor of the rendering
    /// equation is the caller's; 0 where the pdf is 0).
    pub fn weight(&self) -> [R; 3] {
        let zero = R::c(0.0);
        let positive = self.pdf.gt(zero);
        let pdf = R::select(positive, self.pdf, R::c(1.0));
        self.value.map(|v| R::select(positive, v / pdf, zero))
    }
}

/// A hair scattering model evaluated in precision `R`.
pub trait Bcsdf<R: Real> {
    /// The names of the lobes [`Bcsdf::eval_lobes`] returns, in order (for example `R`, `TT`,
    /// `TRT`, `residual`).
    fn lobe_names(&self) -> &'static [&'static str];

    /// The contribution of each lobe of [`Bcsdf::lobe_names`] per channel; they sum to
    /// [`Bcsdf::eval`].
    fn eval_lobes(&self, query: &Query<R>) -> Vec<[R; 3]>;

    /// Whether S depends on the offset h: true for near-field models (which override this);
    /// far-field models ignore [`Query::h`].
    fn uses_offset(&self) -> bool {
        false
    }

    /// `S(wi, wo, h)` per linear RGB channel, with no cosine factor: the radiance scattered
    /// towards `wo` is `int S(wi, wo) L(wi) dwi` over solid angle. Finite and non-negative
    /// for every finite query. By default the sum of [`Bcsdf::eval_lobes`] (models override it
    /// to avoid the allocation).
    fn eval(&self, query: &Query<R>) -> [R; 3] {
        let mut sum = [R::c(0.0); 3];
        for lobe in self.eval_lobes(query) {
            for (s, v) in sum.iter_mut().zip(lobe) {
                *s += v;
            }
        }
        sum
    }
}

/// The sum per channel of `N >= 1` lobes, left to right (`lobes[0] + lobes[1] + ...`): what a
/// model's [`Bcsdf::eval`] returns from the terms its [`Bcsdf::eval_lobes`] lists, without
/// allocating.
///
/// # Panics
/// If `N` is 0 (a model has at least one lobe).
#[inline(always)]
pub fn sum_lobes<R: Real, const N: usize>(lobes: &[[R; 3]; N]) -> [R; 3] {
    core::array::from_fn(|c| {
        lobes[1..]
            .iter()
            .fold(lobes[0][c], |sum, lobe| sum + lobe[c])
    })
}

/// A model with importance sampling.
pub trait SampledBcsdf<R: Real>: Bcsdf<R> {
    /// The solid-angle density with which [`SampledBcsdf::sample`] chooses `query.wi` given
    /// `query.wo` (and `query.h`).
    fn pdf(&self, query: &Query<R>) -> R;

    /// Draws wi given `wo` and `h` from the uniform numbers `u`, with the value of S there and
    /// the density ([`HairSample`]). Branch-free, so it traces.
    fn sample(&self, wo: V3<R>, h: R, u: RandomNumbers<R>) -> HairSample<R>;
}

/// A model built in `f64` from validated parameters, which can rebuild itself in any precision
/// from its uniforms: the contract the SIMD batch, the tracer and the shader emitter use.
///
/// Per-model data that is not a uniform (for example the far field's quadrature nodes) comes
/// from `self` in [`Model::with_uniforms`]; in shader code it becomes constants.
pub trait Model: Bcsdf<f64> {
    /// The named struct of the model's derived constants.
    type Uniforms<R: Real>: UniformBlock<R>;
    /// The model in precision `R`.
    type In<R: Real>: Bcsdf<R>;

    /// Whether [`HostBatch`](super::HostBatch) may run the model on AVX-512 or AVX2 lanes:
    /// `true` only when everything its evaluation calls is inlined (`docs/ARCHITECTURE.md`,
    /// "Batch hot paths inline all the way down", says how that is checked). A kernel that is
    /// not inlined calls each of those lanes' intrinsics out of line, several times slower than
    /// the build's own lanes, which `HostBatch` then uses instead.
    const INLINED_KERNEL: bool = false;

    /// The derived constants, computed once in `f64`.
    fn uniforms(&self) -> Self::Uniforms<f64>;

    /// The model in precision `R` reading `uniforms` (rounded or symbolic).
    fn with_uniforms<R: Real>(&self, uniforms: Self::Uniforms<R>) -> Self::In<R>;

    /// The model in precision `R`: the `f64` uniforms rounded once to `R`.
    fn instantiate<R: Real>(&self) -> Self::In<R> {
        let values: Vec<R> = self.uniforms().to_values().into_iter().map(R::c).collect();
        self.with_uniforms(Self::Uniforms::<R>::from_values(&values))
    }
}

/// One field of a [`UniformBlock`].
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct UniformField {
    /// The field's name (Rust and shader code).
    pub name: &'static str,
    /// 1 for a scalar (`f32`), 3 for an RGB or vector field (`vec3<f32>`).
    pub width: usize,
}

/// A `#[repr(C)]` struct of named scalars and 3-vectors that a model derives from its
/// parameters, declared with [`uniform_block!`](crate::uniform_block), which implements this
/// trait. The fields' order is the declaration order, in Rust, in the flat value list and in
/// the shader struct.
pub trait UniformBlock<R>: Copy {
    /// The struct's name (Rust and shader code).
    const NAME: &'static str;

    /// The fields in declaration order.
    fn fields() -> Vec<UniformField>;

    /// The values, flattened in field order (a 3-vector as its three components).
    fn to_values(&self) -> Vec<R>;

    /// The struct from values flattened as [`UniformBlock::to_values`] writes them.
    ///
    /// # Panics
    /// If `values` does not have one entry per scalar of the struct (a programming error: the
    /// values come from `to_values` or from a trace of this very struct).
    fn from_values(values: &[R]) -> Self;

    /// The shader type of the struct.
    fn shader_type() -> ArgType {
        ArgType::Struct(StructType {
            name: Self::NAME.to_string(),
            fields: Self::fields()
                .iter()
                .map(|f| {
                    let ty = if f.width == 3 {
                        ArgType::Vec3
                    } else {
                        ArgType::Scalar
                    };
                    (f.name.to_string(), ty)
                })
                .collect(),
        })
    }
}

/// A field type of a [`UniformBlock`]: a scalar or an array of three.
pub trait UniformValue<R>: Copy {
    /// Scalars per value.
    const WIDTH: usize;
    /// Appends the value's scalars.
    fn push_to(&self, out: &mut Vec<R>);
    /// The value from the next `WIDTH` scalars.
    fn take_from(values: &mut core::slice::Iter<'_, R>) -> Self;
}

impl<R: Real> UniformValue<R> for R {
    const WIDTH: usize = 1;
    fn push_to(&self, out: &mut Vec<R>) {
        out.push(*self);
    }
    fn take_from(values: &mut core::slice::Iter<'_, R>) -> Self {
        *values.next().expect("one value per uniform scalar")
    }
}

impl<R: Real> UniformValue<R> for [R; 3] {
    const WIDTH: usize = 3;
    fn push_to(&self, out: &mut Vec<R>) {
        out.extend_from_slice(self);
    }
    fn take_from(values: &mut core::slice::Iter<'_, R>) -> Self {
        core::array::from_fn(|_| *values.next().expect("one value per uniform scalar"))
    }
}

/// Declares a model's uniforms: a `#[repr(C)]` struct generic over the scalar `R` whose fields
/// are `R` or `[R; 3]`, with its [`UniformBlock`](crate::bcsdf::UniformBlock) implementation.
///
/// ```
/// hairmath::uniform_block! {
///     /// The derived constants of a toy model.
///     pub struct ToyUniforms<R> {
///         /// A scalar.
///         pub gain: R,
///         /// An RGB value (a `vec3<f32>` in shader code).
///         pub tint: [R; 3],
///     }
/// }
/// use hairmath::bcsdf::UniformBlock;
/// let u = ToyUniforms { gain: 2.0_f64, tint: [0.1, 0.2, 0.3] };
/// assert_eq!(u.to_values(), vec![2.0, 0.1, 0.2, 0.3]);
/// assert_eq!(ToyUniforms::<f64>::from_values(&u.to_values()), u);
/// ```
#[macro_export]
macro_rules! uniform_block {
    (
        $(#[$meta:meta])*
        pub struct $name:ident<R> {
            $(
                $(#[$field_meta:meta])*
                pub $field:ident : $ty:ty
            ),* $(,)?
        }
    ) => {
        $(#[$meta])*
        #[repr(C)]
        #[derive(Clone, Copy, Debug, PartialEq)]
        pub struct $name<R> {
            $(
                $(#[$field_meta])*
                pub $field: $ty,
            )*
        }

        impl<R: $crate::real::Real> $crate::bcsdf::UniformBlock<R> for $name<R> {
            const NAME: &'static str = stringify!($name);

            fn fields() -> Vec<$crate::bcsdf::UniformField> {
                vec![$(
                    $crate::bcsdf::UniformField {
                        name: stringify!($field),
                        width: <$ty as $crate::bcsdf::UniformValue<R>>::WIDTH,
                    },
                )*]
            }

            fn to_values(&self) -> Vec<R> {
                let mut out = Vec::new();
                $( $crate::bcsdf::UniformValue::<R>::push_to(&self.$field, &mut out); )*
                out
            }

            fn from_values(values: &[R]) -> Self {
                let width: usize = Self::fields().iter().map(|f| f.width).sum();
                assert_eq!(values.len(), width, "one value per scalar of {}", stringify!($name));
                let mut values = values.iter();
                $name {
                    $( $field: <$ty as $crate::bcsdf::UniformValue<R>>::take_from(&mut values), )*
                }
            }
        }
    };
}

/// How traced shader code receives a model's uniforms.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum UniformsIn {
    /// The first argument, `uniforms: <Name>`: one shader for every parameter set, the
    /// values supplied by the caller.
    Argument,
    /// A module-scope constant `uniforms` of the model's values rounded to `f32`, read by
    /// name (the shader compiler folds it): the shader of one parameter set.
    Constant,
}

/// Traces `f` applied to `model` rebuilt with symbolic uniforms, which the traced function
/// receives as `uniforms` (of the struct type [`UniformBlock::NAME`]): its first argument or
/// a module constant ([`UniformsIn`]). The arguments `extra` follow; `f` receives the traced
/// model and the inputs of `extra` (flattened as [`Signature`] describes).
pub fn trace_model<M: Model>(
    model: &M,
    uniforms: UniformsIn,
    extra: Vec<Parameter>,
    result: ResultType,
    f: impl FnOnce(&M::In<Traced>, &[Traced]) -> Vec<Traced>,
) -> Graph {
    let ty = <M::Uniforms<Traced> as UniformBlock<Traced>>::shader_type();
    let width = ty.width();
    let mut block = Parameter::argument("uniforms", ty);
    if uniforms == UniformsIn::Constant {
        let values = model.uniforms().to_values();
        block.constant = Some(values.into_iter().map(|v| v as f32).collect());
    }
    let mut parameters = vec![block];
    parameters.extend(extra);
    let signature = Signature { parameters, result };
    trace_with(signature, |x| {
        let traced = model.with_uniforms(M::Uniforms::<Traced>::from_values(&x[..width]));
        f(&traced, &x[width..])
    })
}

/// The arguments `wi: vec3<f32>, wo: vec3<f32>` and, for a near-field model, `h: f32`.
pub fn query_parameters(uses_offset: bool) -> Vec<Parameter> {
    let mut p = vec![
        Parameter {
            name: "wi".into(),
            ty: ArgType::Vec3,
            constant: None,
        },
        Parameter {
            name: "wo".into(),
            ty: ArgType::Vec3,
            constant: None,
        },
    ];
    if uses_offset {
        p.push(Parameter {
            name: "h".into(),
            ty: ArgType::Scalar,
            constant: None,
        });
    }
    p
}

/// The query of the inputs of [`query_parameters`] (h = 0 when absent).
pub fn query_of<R: Real>(x: &[R]) -> Query<R> {
    let v3 = |k: usize| V3::new(x[k], x[k + 1], x[k + 2]);
    Query {
        wi: v3(0),
        wo: v3(3),
        h: x.get(6).copied().unwrap_or_else(|| R::c(0.0)),
    }
}

/// The model's [`Bcsdf::eval`] as a shader function
/// `(uniforms: <Uniforms>, wi: vec3<f32>, wo: vec3<f32>[, h: f32]) -> vec3<f32>`.
pub fn trace_eval<M: Model>(model: &M) -> Graph {
    trace_eval_with(model, UniformsIn::Argument)
}

/// The model's [`Bcsdf::eval`] as a shader function `(wi: vec3<f32>, wo: vec3<f32>[, h: f32])
/// -> vec3<f32>` reading its uniforms as received by `uniforms` ([`trace_model`]).
pub fn trace_eval_with<M: Model>(model: &M, uniforms: UniformsIn) -> Graph {
    trace_model(
        model,
        uniforms,
        query_parameters(model.uses_offset()),
        ResultType::Vec3,
        |m, x| m.eval(&query_of(x)).to_vec(),
    )
}

/// The inputs of a graph of [`trace_model`] for the model's uniforms rounded to `f32` followed
/// by `extra`, for [`Graph::eval_f32`].
pub fn traced_inputs<M: Model>(model: &M, extra: &[f32]) -> Vec<f32> {
    let mut values: Vec<f32> = model
        .uniforms()
        .to_values()
        .into_iter()
        .map(|v| v as f32)
        .collect();
    values.extend_from_slice(extra);
    values
}
