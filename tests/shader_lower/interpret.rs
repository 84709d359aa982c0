//! An interpreter of the subset of naga's IR the emitter produces, in `f32` with the very
//! operations of the crate's `f32` instantiation (`Real` for `f32`: `sin`, `exp`, `min`, ...),
//! so that a lowered module can be compared with [`Graph::eval_f32`] bit for bit on the CPU.
//!
//! It also checks what the validator cannot: every expression a statement uses was emitted
//! before (in an enclosing block), texel loads stay inside their texture, and the constant
//! arrays' indices in range.
//!
//! [`Graph::eval_f32`]: hairmath::real::Graph::eval_f32

use hairmath::real::Real;
use naga::{
    BinaryOperator, Block, Expression, Function, GlobalVariable, Handle, Literal, MathFunction,
    Module, ScalarKind, Statement, UnaryOperator,
};
use std::collections::HashMap;

/// A value of the interpreted program.
#[derive(Clone, Debug, PartialEq)]
pub enum Value {
    /// `f32`.
    F32(f32),
    /// `i32`.
    I32(i32),
    /// `u32`.
    U32(u32),
    /// `bool`.
    Bool(bool),
    /// A vector, array or struct.
    List(Vec<Value>),
    /// A pointer to local variable `k` of the running function.
    Local(usize),
    /// A texture (a global variable).
    Texture(Handle<GlobalVariable>),
}

impl Value {
    /// The `f32`.
    pub fn f32(&self) -> f32 {
        match self {
            Value::F32(v) => *v,
            other => panic!("not an f32: {other:?}"),
        }
    }

    /// The scalars of an `f32`, a vector or an array of `f32`, in order.
    pub fn flatten(&self) -> Vec<f32> {
        match self {
            Value::F32(v) => vec![*v],
            Value::List(items) => items.iter().flat_map(Value::flatten).collect(),
            other => panic!("not f32 values: {other:?}"),
        }
    }

    fn index(&self) -> usize {
        match self {
            Value::U32(v) => *v as usize,
            Value::I32(v) => usize::try_from(*v).expect("a non-negative index"),
            other => panic!("not an index: {other:?}"),
        }
    }

    fn bool(&self) -> bool {
        match self {
            Value::Bool(b) => *b,
            other => panic!("not a bool: {other:?}"),
        }
    }
}

/// An RGBA texture: texels x fastest, then y, then z.
pub struct Texture {
    /// Width, height, depth.
    pub extent: [u32; 3],
    /// The texels.
    pub texels: Vec<[f32; 4]>,
}

/// The interpreter of one module.
pub struct Interpreter<'m> {
    module: &'m Module,
    textures: HashMap<Handle<GlobalVariable>, Texture>,
}

enum Flow {
    Normal,
    Break,
    Continue,
    Return(Option<Value>),
}

struct Frame<'f> {
    function: &'f Function,
    args: Vec<Value>,
    values: Vec<Option<Value>>,
    locals: Vec<Value>,
}

impl<'m> Interpreter<'m> {
    /// The interpreter of `module` with the textures `textures` (by global variable name).
    pub fn new(module: &'m Module, textures: Vec<(String, Texture)>) -> Self {
        let mut by_handle = HashMap::new();
        for (name, texture) in textures {
            let (h, _) = module
                .global_variables
                .iter()
                .find(|(_, g)| g.name.as_deref() == Some(name.as_str()))
                .unwrap_or_else(|| panic!("no texture {name}"));
            by_handle.insert(h, texture);
        }
        Interpreter {
            module,
            textures: by_handle,
        }
    }

    /// Calls the function `name` with `args`.
    pub fn call(&self, name: &str, args: Vec<Value>) -> Value {
        let (_, f) = self
            .module
            .functions
            .iter()
            .find(|(_, f)| f.name.as_deref() == Some(name))
            .unwrap_or_else(|| panic!("no function {name}"));
        self.run(f, args)
    }

    fn run(&self, function: &Function, args: Vec<Value>) -> Value {
        assert_eq!(args.len(), function.arguments.len(), "{:?}", function.name);
        let mut frame = Frame {
            function,
            args,
            values: vec![None; function.expressions.len()],
            locals: Vec::new(),
        };
        for (_, var) in function.local_variables.iter() {
            let init = match var.init {
                Some(h) => self.get(&frame, h),
                None => Value::F32(f32::NAN),
            };
            frame.locals.push(init);
        }
        match self.block(&mut frame, &function.body) {
            Flow::Return(Some(v)) => v,
            _ => panic!("{:?} returns no value", function.name),
        }
    }

    fn block(&self, frame: &mut Frame, block: &Block) -> Flow {
        // Expressions emitted in this block go out of scope at its end.
        let mut emitted = Vec::new();
        let flow = self.statements(frame, block, &mut emitted);
        for h in emitted {
            frame.values[h] = None;
        }
        flow
    }

    fn statements(&self, frame: &mut Frame, block: &Block, emitted: &mut Vec<usize>) -> Flow {
        for statement in block.iter() {
            match statement {
                Statement::Emit(range) => {
                    for h in range.clone() {
                        let v = self.eval(frame, h);
                        frame.values[h.index()] = Some(v);
                        emitted.push(h.index());
                    }
                }
                Statement::Call {
                    function,
                    arguments,
                    result,
                } => {
                    let args = arguments.iter().map(|&a| self.get(frame, a)).collect();
                    let v = self.run(&self.module.functions[*function], args);
                    if let Some(r) = result {
                        frame.values[r.index()] = Some(v);
                        emitted.push(r.index());
                    }
                }
                Statement::Store { pointer, value } => {
                    let Value::Local(k) = self.get(frame, *pointer) else {
                        panic!("stores go to local variables")
                    };
                    frame.locals[k] = self.get(frame, *value);
                }
                Statement::If {
                    condition,
                    accept,
                    reject,
                } => {
                    let flow = if self.get(frame, *condition).bool() {
                        self.block(frame, accept)
                    } else {
                        self.block(frame, reject)
                    };
                    if !matches!(flow, Flow::Normal) {
                        return flow;
                    }
                }
                Statement::Loop {
                    body,
                    continuing,
                    break_if,
                } => loop {
                    match self.block(frame, body) {
                        Flow::Break => break,
                        Flow::Return(v) => return Flow::Return(v),
                        Flow::Normal | Flow::Continue => {}
                    }
                    // `break_if` sees the continuing block's expressions.
                    let mut inner = Vec::new();
                    let _ = self.statements(frame, continuing, &mut inner);
                    let stop = break_if.is_some_and(|c| self.get(frame, c).bool());
                    for h in inner {
                        frame.values[h] = None;
                    }
                    if stop {
                        break;
                    }
                },
                Statement::Block(b) => {
                    let flow = self.block(frame, b);
                    if !matches!(flow, Flow::Normal) {
                        return flow;
                    }
                }
                Statement::Break => return Flow::Break,
                Statement::Continue => return Flow::Continue,
                Statement::Return { value } => {
                    return Flow::Return(value.map(|v| self.get(frame, v)))
                }
                other => panic!("statement not interpreted: {other:?}"),
            }
        }
        Flow::Normal
    }

    /// The value of `h`: emitted before, or an expression that needs no emitting.
    fn get(&self, frame: &Frame, h: Handle<Expression>) -> Value {
        if let Some(v) = &frame.values[h.index()] {
            return v.clone();
        }
        let e = &frame.function.expressions[h];
        assert!(
            e.needs_pre_emit(),
            "{:?}: expression {h:?} ({e:?}) used outside the block that emitted it",
            frame.function.name
        );
        self.eval(frame, h)
    }

    fn eval(&self, frame: &Frame, h: Handle<Expression>) -> Value {
        let get = |e: Handle<Expression>| self.get(frame, e);
        match &frame.function.expressions[h] {
            Expression::Literal(l) => literal(l),
            Expression::Constant(c) => self.global(self.module.constants[*c].init),
            Expression::FunctionArgument(k) => frame.args[*k as usize].clone(),
            Expression::LocalVariable(v) => Value::Local(v.index()),
            Expression::GlobalVariable(g) => Value::Texture(*g),
            Expression::Load { pointer } => match get(*pointer) {
                Value::Local(k) => frame.locals[k].clone(),
                other => panic!("load from {other:?}"),
            },
            Expression::AccessIndex { base, index } => element(get(*base), *index as usize),
            Expression::Access { base, index } => element(get(*base), get(*index).index()),
            Expression::Compose { components, .. } => {
                Value::List(components.iter().map(|&c| get(c)).collect())
            }
            Expression::Splat { size, value } => Value::List(vec![get(*value); *size as usize]),
            Expression::Swizzle {
                size,
                vector,
                pattern,
            } => {
                let v = get(*vector);
                let picked = pattern[..*size as usize]
                    .iter()
                    .map(|&c| element(v.clone(), c as usize));
                Value::List(picked.collect())
            }
            Expression::Unary { op, expr } => unary(*op, get(*expr)),
            Expression::Binary { op, left, right } => binary(*op, get(*left), get(*right)),
            Expression::Select {
                condition,
                accept,
                reject,
            } => select(get(*condition), get(*accept), get(*reject)),
            Expression::Math {
                fun,
                arg,
                arg1,
                arg2,
                ..
            } => math(*fun, get(*arg), arg1.map(get), arg2.map(get)),
            Expression::As {
                expr,
                kind: ScalarKind::Sint,
                convert: Some(4),
            } => Value::I32(get(*expr).f32() as i32),
            Expression::ImageLoad {
                image,
                coordinate,
                level,
                ..
            } => {
                let Value::Texture(g) = get(*image) else {
                    panic!("a texture")
                };
                assert_eq!(level.map(get), Some(Value::I32(0)), "level 0");
                self.load(g, get(*coordinate))
            }
            other => panic!("expression not interpreted: {other:?}"),
        }
    }

    /// The value of a global (constant) expression.
    fn global(&self, h: Handle<Expression>) -> Value {
        match &self.module.global_expressions[h] {
            Expression::Literal(l) => literal(l),
            Expression::Compose { components, .. } => {
                Value::List(components.iter().map(|&c| self.global(c)).collect())
            }
            other => panic!("global expression not interpreted: {other:?}"),
        }
    }

    fn load(&self, g: Handle<GlobalVariable>, coordinate: Value) -> Value {
        let texture = &self.textures[&g];
        let coords: Vec<i32> = match coordinate {
            Value::I32(x) => vec![x],
            Value::List(items) => items
                .iter()
                .map(|c| match c {
                    Value::I32(v) => *v,
                    other => panic!("texel coordinate {other:?}"),
                })
                .collect(),
            other => panic!("texel coordinate {other:?}"),
        };
        let mut flat = 0usize;
        for (d, &c) in coords.iter().enumerate().rev() {
            assert!(
                c >= 0 && (c as u32) < texture.extent[d],
                "texel coordinate {coords:?} outside {:?}",
                texture.extent
            );
            flat = flat * texture.extent[d] as usize + c as usize;
        }
        Value::List(
            texture.texels[flat]
                .iter()
                .map(|&v| Value::F32(v))
                .collect(),
        )
    }
}

fn literal(l: &Literal) -> Value {
    match *l {
        Literal::F32(v) => Value::F32(v),
        Literal::I32(v) => Value::I32(v),
        Literal::U32(v) => Value::U32(v),
        Literal::Bool(v) => Value::Bool(v),
        other => panic!("literal {other:?}"),
    }
}

fn element(base: Value, index: usize) -> Value {
    match base {
        Value::List(items) => items
            .get(index)
            .cloned()
            .unwrap_or_else(|| panic!("index {index} beyond {} elements", items.len())),
        other => panic!("indexing {other:?}"),
    }
}

fn binary(op: BinaryOperator, a: Value, b: Value) -> Value {
    use BinaryOperator as B;
    match (a, b) {
        (Value::List(a), Value::List(b)) => Value::List(
            a.into_iter()
                .zip(b)
                .map(|(x, y)| binary(op, x, y))
                .collect(),
        ),
        (Value::List(a), b) => {
            Value::List(a.into_iter().map(|x| binary(op, x, b.clone())).collect())
        }
        (a, Value::List(b)) => {
            Value::List(b.into_iter().map(|y| binary(op, a.clone(), y)).collect())
        }
        (Value::F32(x), Value::F32(y)) => match op {
            B::Add => Value::F32(x + y),
            B::Subtract => Value::F32(x - y),
            B::Multiply => Value::F32(x * y),
            B::Divide => Value::F32(x / y),
            B::Less => Value::Bool(x < y),
            B::LessEqual => Value::Bool(x <= y),
            other => panic!("f32 {other:?}"),
        },
        (Value::I32(x), Value::I32(y)) => match op {
            B::Add => Value::I32(x.wrapping_add(y)),
            other => panic!("i32 {other:?}"),
        },
        (Value::U32(x), Value::U32(y)) => match op {
            B::Add => Value::U32(x.wrapping_add(y)),
            B::Less => Value::Bool(x < y),
            B::GreaterEqual => Value::Bool(x >= y),
            other => panic!("u32 {other:?}"),
        },
        (Value::Bool(x), Value::Bool(y)) => match op {
            B::LogicalAnd => Value::Bool(x && y),
            B::LogicalOr => Value::Bool(x || y),
            other => panic!("bool {other:?}"),
        },
        (a, b) => panic!("{op:?} of {a:?} and {b:?}"),
    }
}

/// `op` of a scalar, or of each component of a vector.
fn unary(op: UnaryOperator, v: Value) -> Value {
    match (op, v) {
        (_, Value::List(items)) => Value::List(items.into_iter().map(|x| unary(op, x)).collect()),
        (UnaryOperator::Negate, Value::F32(a)) => Value::F32(-a),
        (UnaryOperator::LogicalNot, Value::Bool(a)) => Value::Bool(!a),
        (op, v) => panic!("{op:?} of {v:?}"),
    }
}

/// WGSL's `select(reject, accept, condition)`: the whole value for a `bool` condition, each
/// component for a vector of them.
fn select(condition: Value, accept: Value, reject: Value) -> Value {
    match (condition, accept, reject) {
        (Value::Bool(c), a, r) => {
            if c {
                a
            } else {
                r
            }
        }
        (Value::List(c), Value::List(a), Value::List(r)) => {
            assert!(
                c.len() == a.len() && a.len() == r.len(),
                "select of unequal sizes"
            );
            let parts = c.into_iter().zip(a).zip(r);
            Value::List(parts.map(|((c, a), r)| select(c, a, r)).collect())
        }
        (c, a, r) => panic!("select({r:?}, {a:?}, {c:?})"),
    }
}

/// `fun` of scalars, or of each component of vectors (every vector argument of one size).
fn math(fun: MathFunction, a: Value, b: Option<Value>, c: Option<Value>) -> Value {
    use MathFunction as M;
    if let Value::List(items) = a {
        let component = |v: &Option<Value>, k: usize| match v {
            Some(Value::List(items)) => Some(items[k].clone()),
            Some(other) => panic!("math {fun:?} of a vector and {other:?}"),
            None => None,
        };
        let parts = items.into_iter().enumerate();
        return Value::List(
            parts
                .map(|(k, x)| math(fun, x, component(&b, k), component(&c, k)))
                .collect(),
        );
    }
    if let (M::Clamp, Value::I32(x)) = (fun, &a) {
        let (Some(Value::I32(lo)), Some(Value::I32(hi))) = (b, c) else {
            panic!("clamp of i32")
        };
        return Value::I32((*x).max(lo).min(hi));
    }
    let x = a.f32();
    let y = || b.as_ref().expect("a second argument").f32();
    Value::F32(match fun {
        M::Sqrt => Real::sqrt(x),
        M::Exp => Real::exp(x),
        M::Log => Real::ln(x),
        M::Sin => Real::sin(x),
        M::Cos => Real::cos(x),
        M::Abs => Real::abs(x),
        M::Floor => Real::floor(x),
        M::Atan2 => Real::atan2(x, y()),
        M::Min => Real::min(x, y()),
        M::Max => Real::max(x, y()),
        other => panic!("math {other:?}"),
    })
}
