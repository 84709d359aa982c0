//! Colours as vectors. The Rust code computes a colour channel by channel (`[R; 3]`, `.map`),
//! so the traced graph holds three scalar computations where shader code wants one
//! `vec3<f32>` expression. Where three scalars become a `vec3<f32>` (a result, a struct field,
//! an argument, a loop's state), [`vec3`] rebuilds them as one vector expression as far as the
//! three are computed alike, from the leaves up:
//!
//! - the same scalar in every channel stays a scalar (a factor of a product, a select's
//!   condition) or is splatted (`vec3<f32>(s)`) where the operation needs vectors;
//! - the x, y and z of one vector are that vector (three components of a texel, `texel.xyz`);
//! - the same operation (arithmetic, negation, a component-wise math function, a select) on
//!   operands that are vectors in this sense is that operation on vectors;
//! - anything else is composed (`vec3<f32>(a, b, c)`) from the scalars.
//!
//! Every component of the vector expression is the same operation on the same operands as
//! the scalar it replaces, so the value is the same bit for bit (`tests/shader_lower` checks
//! every module against the traced graph).

use super::builder::FnBuilder;
use naga::{
    BinaryOperator, Expression, Handle, MathFunction, SwizzleComponent, Type, UnaryOperator,
    VectorSize,
};
use std::collections::HashMap;

/// The `vec3<f32>` (type `ty`) of the `f32` expressions `scalars`, as one vector expression
/// where they are computed alike (see the [module docs](self)).
pub(super) fn vec3(
    b: &mut FnBuilder,
    ty: Handle<Type>,
    scalars: [Handle<Expression>; 3],
) -> Handle<Expression> {
    let mut v = Vectorizer {
        b,
        ty,
        done: HashMap::new(),
    };
    let lanes = v.lanes(scalars);
    v.vector(lanes)
}

/// Three lanes as one expression.
#[derive(Clone, Copy)]
enum Lanes {
    /// The same scalar in every lane.
    Uniform(Handle<Expression>),
    /// A `vec3<f32>` (or, for a comparison, `vec3<bool>`) expression.
    Vector(Handle<Expression>),
}

struct Vectorizer<'b> {
    b: &'b mut FnBuilder,
    ty: Handle<Type>,
    /// Triples already rebuilt.
    done: HashMap<[Handle<Expression>; 3], Lanes>,
}

impl Vectorizer<'_> {
    /// The lanes of three `f32` expressions.
    fn lanes(&mut self, s: [Handle<Expression>; 3]) -> Lanes {
        if let Some(&l) = self.done.get(&s) {
            return l;
        }
        let l = self.rebuild(s).unwrap_or_else(|| {
            Lanes::Vector(self.b.expr(Expression::Compose {
                ty: self.ty,
                components: s.to_vec(),
            }))
        });
        self.done.insert(s, l);
        l
    }

    /// The three as one expression, if they are one scalar, one vector's components or the
    /// same operation.
    fn rebuild(&mut self, s: [Handle<Expression>; 3]) -> Option<Lanes> {
        if s[0] == s[1] && s[1] == s[2] {
            return Some(Lanes::Uniform(s[0]));
        }
        if let Some(v) = self.components_of_one_vector(s) {
            return Some(Lanes::Vector(v));
        }
        let e = s.map(|h| self.b.expression(h).clone());
        if let [Some(p0), Some(p1), Some(p2)] = e.clone().map(binary) {
            if p0.0 == p1.0 && p0.0 == p2.0 && arithmetic(p0.0) {
                let left = self.lanes([p0.1, p1.1, p2.1]);
                let right = self.lanes([p0.2, p1.2, p2.2]);
                return self.binary(p0.0, left, right);
            }
            return None;
        }
        match e[0] {
            Expression::Unary { .. } => self.negation(&e),
            Expression::Math { fun, .. } => self.math(fun, &e),
            Expression::Select { .. } => self.select(&e),
            _ => None,
        }
    }

    /// `-v` of three negations.
    fn negation(&mut self, e: &[Expression; 3]) -> Option<Lanes> {
        let inner = e.clone().map(|x| match x {
            Expression::Unary {
                op: UnaryOperator::Negate,
                expr,
            } => Some(expr),
            _ => None,
        });
        let [Some(a), Some(b), Some(c)] = inner else {
            return None;
        };
        let lanes = self.lanes([a, b, c]);
        let expr = self.vector(lanes);
        Some(Lanes::Vector(self.b.expr(Expression::Unary {
            op: UnaryOperator::Negate,
            expr,
        })))
    }

    /// The vector whose x, y and z the three are (or three consecutive components of a
    /// `vec4<f32>`, swizzled: `texel.xyz`), if they are.
    fn components_of_one_vector(
        &mut self,
        s: [Handle<Expression>; 3],
    ) -> Option<Handle<Expression>> {
        let [Some(c0), Some(c1), Some(c2)] = s.map(|h| self.b.component(h)) else {
            return None;
        };
        let same = c0.vector == c1.vector && c1.vector == c2.vector;
        if !same || c1.index != c0.index + 1 || c2.index != c0.index + 2 {
            return None;
        }
        if c0.size == 3 {
            return Some(c0.vector);
        }
        let pattern = [0, 1, 2, 0].map(|k| SWIZZLE[(c0.index + k) as usize % 4]);
        Some(self.b.expr(Expression::Swizzle {
            size: VectorSize::Tri,
            vector: c0.vector,
            pattern,
        }))
    }

    /// `l op r` on lanes: a product keeps a uniform factor scalar, other operations splat it.
    fn binary(&mut self, op: BinaryOperator, l: Lanes, r: Lanes) -> Option<Lanes> {
        let (left, right) = match (op, l, r) {
            (_, Lanes::Uniform(_), Lanes::Uniform(_)) => return None,
            (BinaryOperator::Multiply, Lanes::Uniform(a), Lanes::Vector(v)) => (a, v),
            (BinaryOperator::Multiply, Lanes::Vector(v), Lanes::Uniform(a)) => (v, a),
            _ => (self.vector(l), self.vector(r)),
        };
        Some(Lanes::Vector(self.b.expr(Expression::Binary {
            op,
            left,
            right,
        })))
    }

    /// A component-wise math function of the three, its arguments as vectors.
    fn math(&mut self, fun: MathFunction, e: &[Expression; 3]) -> Option<Lanes> {
        if !component_wise(fun) {
            return None;
        }
        let args = e.clone().map(|x| match x {
            Expression::Math {
                fun: f,
                arg,
                arg1,
                arg2,
                arg3,
            } if f == fun => Some([Some(arg), arg1, arg2, arg3]),
            _ => None,
        });
        let [Some(a0), Some(a1), Some(a2)] = args else {
            return None;
        };
        let args = [a0, a1, a2];
        let mut vectors = [None; 4];
        let mut uniform = true;
        for (k, slot) in vectors.iter_mut().enumerate() {
            match (args[0][k], args[1][k], args[2][k]) {
                (Some(a), Some(b), Some(c)) => {
                    let lanes = self.lanes([a, b, c]);
                    uniform &= matches!(lanes, Lanes::Uniform(_));
                    *slot = Some(lanes);
                }
                (None, None, None) => {}
                _ => return None,
            }
        }
        if uniform {
            return None;
        }
        let [arg, arg1, arg2, arg3] = vectors.map(|l| l.map(|l| self.vector(l)));
        Some(Lanes::Vector(self.b.expr(Expression::Math {
            fun,
            arg: arg?,
            arg1,
            arg2,
            arg3,
        })))
    }

    /// `select(reject, accept, condition)` of the three: a condition the same in every lane
    /// stays a scalar `bool`; conditions that are the same comparison become a vector
    /// comparison; other conditions leave the three as they are.
    fn select(&mut self, e: &[Expression; 3]) -> Option<Lanes> {
        let parts = e.clone().map(|x| match x {
            Expression::Select {
                condition,
                accept,
                reject,
            } => Some((condition, accept, reject)),
            _ => None,
        });
        let [Some(p0), Some(p1), Some(p2)] = parts else {
            return None;
        };
        let parts = [p0, p1, p2];
        let conditions = parts.map(|p| p.0);
        let condition = if conditions[0] == conditions[1] && conditions[1] == conditions[2] {
            conditions[0]
        } else {
            self.comparison(conditions)?
        };
        let accept = self.lanes(parts.map(|p| p.1));
        let reject = self.lanes(parts.map(|p| p.2));
        let (accept, reject) = (self.vector(accept), self.vector(reject));
        Some(Lanes::Vector(self.b.expr(Expression::Select {
            condition,
            accept,
            reject,
        })))
    }

    /// The `vec3<bool>` of three comparisons of one kind of `f32` operands, if they are.
    fn comparison(&mut self, c: [Handle<Expression>; 3]) -> Option<Handle<Expression>> {
        let parts = c.map(|h| binary(self.b.expression(h).clone()));
        let [Some(p0), Some(p1), Some(p2)] = parts else {
            return None;
        };
        if p0.0 != p1.0 || p0.0 != p2.0 || !comparison(p0.0) {
            return None;
        }
        let left = self.lanes([p0.1, p1.1, p2.1]);
        let right = self.lanes([p0.2, p1.2, p2.2]);
        let (left, right) = (self.vector(left), self.vector(right));
        Some(self.b.expr(Expression::Binary {
            op: p0.0,
            left,
            right,
        }))
    }

    /// The lanes as a vector: a uniform scalar splatted.
    fn vector(&mut self, l: Lanes) -> Handle<Expression> {
        match l {
            Lanes::Vector(v) => v,
            Lanes::Uniform(s) => self.b.expr(Expression::Splat {
                size: VectorSize::Tri,
                value: s,
            }),
        }
    }
}

/// The components of a vector, in order.
const SWIZZLE: [SwizzleComponent; 4] = [
    SwizzleComponent::X,
    SwizzleComponent::Y,
    SwizzleComponent::Z,
    SwizzleComponent::W,
];

/// The operator and operands of a binary expression.
fn binary(e: Expression) -> Option<(BinaryOperator, Handle<Expression>, Handle<Expression>)> {
    match e {
        Expression::Binary { op, left, right } => Some((op, left, right)),
        _ => None,
    }
}

/// Arithmetic that applies to `vec3<f32>` component by component.
fn arithmetic(op: BinaryOperator) -> bool {
    matches!(
        op,
        BinaryOperator::Add
            | BinaryOperator::Subtract
            | BinaryOperator::Multiply
            | BinaryOperator::Divide
    )
}

/// Comparisons of `f32` values.
fn comparison(op: BinaryOperator) -> bool {
    matches!(
        op,
        BinaryOperator::Less
            | BinaryOperator::LessEqual
            | BinaryOperator::Greater
            | BinaryOperator::GreaterEqual
            | BinaryOperator::Equal
            | BinaryOperator::NotEqual
    )
}

/// The math functions the lowering writes that apply to `vec3<f32>` component by component.
fn component_wise(fun: MathFunction) -> bool {
    matches!(
        fun,
        MathFunction::Abs
            | MathFunction::Min
            | MathFunction::Max
            | MathFunction::Clamp
            | MathFunction::Sqrt
            | MathFunction::Exp
            | MathFunction::Log
            | MathFunction::Sin
            | MathFunction::Cos
            | MathFunction::Atan2
            | MathFunction::Floor
    )
}
