//! Symbolic tracing: running generic code on [`Traced`] values records it as a graph.
//!
//! [`trace`] calls a closure with symbolic inputs; every arithmetic operation appends a node
//! to a thread-local graph (identical nodes are shared, so the graph is in SSA form with common
//! subexpressions merged). The finished [`Graph`] prints as a WGSL function
//! ([`Graph::to_wgsl`]) and can be interpreted in `f32` ([`Graph::eval_f32`]) with exactly
//! the operations of the `f32` instantiation, which is how tests prove that the generated
//! shader code computes what the CPU code computes.
//!
//! Traced values have single-precision semantics (`Real::DOUBLE` is false) and constants
//! are rounded to `f32` when recorded.

use super::Real;
use core::cell::RefCell;
use core::ops::{Add, AddAssign, BitAnd, BitOr, Div, Mul, MulAssign, Neg, Not, Sub, SubAssign};
use std::collections::HashMap;
use std::fmt::Write as _;

/// A unary floating-point operation of the graph.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Unary {
    /// `-a`.
    Neg,
    /// `sqrt(a)`.
    Sqrt,
    /// `exp(a)`.
    Exp,
    /// natural logarithm, WGSL `log(a)`.
    Ln,
    /// `sin(a)`.
    Sin,
    /// `cos(a)`.
    Cos,
    /// `abs(a)`.
    Abs,
    /// `floor(a)`.
    Floor,
}

/// A binary floating-point operation of the graph.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Binary {
    /// `a + b`.
    Add,
    /// `a - b`.
    Sub,
    /// `a * b`.
    Mul,
    /// `a / b`.
    Div,
    /// `atan2(a, b)`.
    Atan2,
    /// `min(a, b)`.
    Min,
    /// `max(a, b)`.
    Max,
}

/// One node of a traced computation. Operands are indices of earlier nodes.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Node {
    /// The i-th argument of the traced function.
    Input(u32),
    /// An `f32` constant, stored as its bits.
    Const(u32),
    /// A unary operation of an earlier node.
    Unary(Unary, u32),
    /// A binary operation of two earlier nodes.
    Binary(Binary, u32, u32),
    /// `a < b` (boolean).
    Less(u32, u32),
    /// `a <= b` (boolean).
    LessEqual(u32, u32),
    /// Boolean `a & b`.
    And(u32, u32),
    /// Boolean `a | b`.
    Or(u32, u32),
    /// Boolean `!a`.
    Not(u32),
    /// `if c { t } else { f }` with c boolean: (c, t, f).
    Select(u32, u32, u32),
}

/// A recorded computation: nodes in evaluation order, the number of inputs, and the outputs.
#[derive(Clone, Debug, PartialEq)]
pub struct Graph {
    nodes: Vec<Node>,
    inputs: usize,
    outputs: Vec<u32>,
}

#[derive(Default)]
struct Recorder {
    nodes: Vec<Node>,
    index: HashMap<Node, u32>,
}

thread_local! {
    static RECORDER: RefCell<Option<Recorder>> = const { RefCell::new(None) };
}

fn record(node: Node) -> u32 {
    RECORDER.with(|r| {
        let mut guard = r.borrow_mut();
        let rec = guard
            .as_mut()
            .expect("Traced values can only be used inside hairmath::real::trace");
        if let Some(&id) = rec.index.get(&node) {
            return id;
        }
        let id = rec.nodes.len() as u32;
        rec.nodes.push(node);
        rec.index.insert(node, id);
        id
    })
}

/// A symbolic scalar: the index of a node in the graph being traced.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Traced(u32);

/// A symbolic boolean produced by comparing [`Traced`] values.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct TracedMask(u32);

/// Traces `f` called with `inputs` symbolic arguments and returns the recorded graph.
///
/// # Panics
/// If called while another trace is running on the same thread (traces do not nest).
pub fn trace(inputs: usize, f: impl FnOnce(&[Traced]) -> Vec<Traced>) -> Graph {
    RECORDER.with(|r| {
        let mut guard = r.borrow_mut();
        assert!(guard.is_none(), "hairmath::real::trace does not nest");
        *guard = Some(Recorder::default());
    });
    let args: Vec<Traced> = (0..inputs)
        .map(|i| Traced(record(Node::Input(i as u32))))
        .collect();
    let outputs = f(&args);
    let rec = RECORDER
        .with(|r| r.borrow_mut().take())
        .expect("recorder present");
    Graph {
        nodes: rec.nodes,
        inputs,
        outputs: outputs.iter().map(|t| t.0).collect(),
    }
}

impl Graph {
    /// The recorded nodes in evaluation order.
    pub fn nodes(&self) -> &[Node] {
        &self.nodes
    }

    /// Number of inputs of the traced function.
    pub fn input_count(&self) -> usize {
        self.inputs
    }

    /// Number of outputs of the traced function.
    pub fn output_count(&self) -> usize {
        self.outputs.len()
    }

    /// Marks the nodes the outputs depend on.
    fn live(&self) -> Vec<bool> {
        let mut live = vec![false; self.nodes.len()];
        for &o in &self.outputs {
            live[o as usize] = true;
        }
        for i in (0..self.nodes.len()).rev() {
            if !live[i] {
                continue;
            }
            for operand in operands(&self.nodes[i]) {
                live[operand as usize] = true;
            }
        }
        live
    }

    /// How many live nodes perform the binary operation `op` (for example multiplies).
    pub fn count_binary(&self, op: Binary) -> usize {
        let live = self.live();
        self.nodes
            .iter()
            .zip(&live)
            .filter(|(n, &l)| l && matches!(n, Node::Binary(o, _, _) if *o == op))
            .count()
    }

    /// Interprets the graph in `f32`, applying to each node the same `f32` operation the
    /// `f32` instantiation of the generic code applies, so the result is bit-identical to it.
    ///
    /// # Panics
    /// If `inputs.len()` differs from [`Graph::input_count`].
    pub fn eval_f32(&self, inputs: &[f32]) -> Vec<f32> {
        assert_eq!(
            inputs.len(),
            self.inputs,
            "wrong number of inputs for traced graph"
        );
        let mut value = vec![0.0_f32; self.nodes.len()];
        let mut truth = vec![false; self.nodes.len()];
        for (i, node) in self.nodes.iter().enumerate() {
            let v = |k: u32| value[k as usize];
            let b = |k: u32| truth[k as usize];
            match *node {
                Node::Input(k) => value[i] = inputs[k as usize],
                Node::Const(bits) => value[i] = f32::from_bits(bits),
                Node::Unary(op, a) => value[i] = apply_unary(op, v(a)),
                Node::Binary(op, a, c) => value[i] = apply_binary(op, v(a), v(c)),
                Node::Less(a, c) => truth[i] = Real::lt(v(a), v(c)),
                Node::LessEqual(a, c) => truth[i] = Real::le(v(a), v(c)),
                Node::And(a, c) => truth[i] = b(a) & b(c),
                Node::Or(a, c) => truth[i] = b(a) | b(c),
                Node::Not(a) => truth[i] = !b(a),
                Node::Select(m, t, f) => value[i] = <f32 as Real>::select(b(m), v(t), v(f)),
            }
        }
        self.outputs.iter().map(|&o| value[o as usize]).collect()
    }

    /// Prints the graph as a WGSL function `fn name(x0: f32, ...) -> T` where `T` is `f32`
    /// for one output and `array<f32, N>` for several. Only nodes the outputs depend on
    /// are emitted, one `let` per node, constants inline.
    pub fn to_wgsl(&self, name: &str) -> String {
        let live = self.live();
        let mut out = String::new();
        let params: Vec<String> = (0..self.inputs).map(|i| format!("x{i}: f32")).collect();
        let ret = match self.outputs.len() {
            1 => "f32".to_string(),
            n => format!("array<f32, {n}>"),
        };
        let _ = writeln!(out, "fn {name}({}) -> {ret} {{", params.join(", "));
        for (i, node) in self.nodes.iter().enumerate() {
            if !live[i] || matches!(node, Node::Input(_) | Node::Const(_)) {
                continue;
            }
            let _ = writeln!(out, "    let t{i} = {};", self.expression(node));
        }
        let results: Vec<String> = self.outputs.iter().map(|&o| self.operand(o)).collect();
        if results.len() == 1 {
            let _ = writeln!(out, "    return {};", results[0]);
        } else {
            let _ = writeln!(out, "    return {ret}({});", results.join(", "));
        }
        out.push_str("}\n");
        out
    }

    fn operand(&self, id: u32) -> String {
        match self.nodes[id as usize] {
            Node::Input(k) => format!("x{k}"),
            Node::Const(bits) => wgsl_literal(f32::from_bits(bits)),
            _ => format!("t{id}"),
        }
    }

    fn expression(&self, node: &Node) -> String {
        let o = |k: u32| self.operand(k);
        match *node {
            Node::Input(_) | Node::Const(_) => unreachable!("inlined"),
            Node::Unary(Unary::Neg, a) => format!("-{}", o(a)),
            Node::Unary(op, a) => format!("{}({})", unary_name(op), o(a)),
            Node::Binary(op, a, b) => match binary_symbol(op) {
                Ok(sym) => format!("{} {sym} {}", o(a), o(b)),
                Err(name) => format!("{name}({}, {})", o(a), o(b)),
            },
            Node::Less(a, b) => format!("{} < {}", o(a), o(b)),
            Node::LessEqual(a, b) => format!("{} <= {}", o(a), o(b)),
            Node::And(a, b) => format!("{} & {}", o(a), o(b)),
            Node::Or(a, b) => format!("{} | {}", o(a), o(b)),
            Node::Not(a) => format!("!{}", o(a)),
            Node::Select(m, t, f) => format!("select({}, {}, {})", o(f), o(t), o(m)),
        }
    }
}

fn operands(node: &Node) -> Vec<u32> {
    match *node {
        Node::Input(_) | Node::Const(_) => vec![],
        Node::Unary(_, a) | Node::Not(a) => vec![a],
        Node::Binary(_, a, b)
        | Node::Less(a, b)
        | Node::LessEqual(a, b)
        | Node::And(a, b)
        | Node::Or(a, b) => vec![a, b],
        Node::Select(m, t, f) => vec![m, t, f],
    }
}

fn apply_unary(op: Unary, a: f32) -> f32 {
    match op {
        Unary::Neg => -a,
        Unary::Sqrt => Real::sqrt(a),
        Unary::Exp => Real::exp(a),
        Unary::Ln => Real::ln(a),
        Unary::Sin => Real::sin(a),
        Unary::Cos => Real::cos(a),
        Unary::Abs => Real::abs(a),
        Unary::Floor => Real::floor(a),
    }
}

fn apply_binary(op: Binary, a: f32, b: f32) -> f32 {
    match op {
        Binary::Add => a + b,
        Binary::Sub => a - b,
        Binary::Mul => a * b,
        Binary::Div => a / b,
        Binary::Atan2 => Real::atan2(a, b),
        Binary::Min => Real::min(a, b),
        Binary::Max => Real::max(a, b),
    }
}

fn unary_name(op: Unary) -> &'static str {
    match op {
        Unary::Neg => "-",
        Unary::Sqrt => "sqrt",
        Unary::Exp => "exp",
        Unary::Ln => "log",
        Unary::Sin => "sin",
        Unary::Cos => "cos",
        Unary::Abs => "abs",
        Unary::Floor => "floor",
    }
}

/// `Ok(infix symbol)` or `Err(function name)`.
fn binary_symbol(op: Binary) -> Result<&'static str, &'static str> {
    match op {
        Binary::Add => Ok("+"),
        Binary::Sub => Ok("-"),
        Binary::Mul => Ok("*"),
        Binary::Div => Ok("/"),
        Binary::Atan2 => Err("atan2"),
        Binary::Min => Err("min"),
        Binary::Max => Err("max"),
    }
}

/// A WGSL `f32` literal that parses back to exactly `x` (Rust's shortest round-trip digits).
fn wgsl_literal(x: f32) -> String {
    assert!(
        x.is_finite(),
        "non-finite constant {x} cannot be written in WGSL"
    );
    let digits = format!("{:?}", x.abs());
    if x.is_sign_negative() {
        format!("(-{digits}f)")
    } else {
        format!("{digits}f")
    }
}

macro_rules! traced_binary {
    ($trait:ident, $method:ident, $assign_trait:ident, $assign:ident, $op:expr) => {
        impl $trait for Traced {
            type Output = Traced;
            fn $method(self, rhs: Traced) -> Traced {
                Traced(record(Node::Binary($op, self.0, rhs.0)))
            }
        }
        impl $assign_trait for Traced {
            fn $assign(&mut self, rhs: Traced) {
                *self = $trait::$method(*self, rhs);
            }
        }
    };
}

traced_binary!(Add, add, AddAssign, add_assign, Binary::Add);
traced_binary!(Sub, sub, SubAssign, sub_assign, Binary::Sub);
traced_binary!(Mul, mul, MulAssign, mul_assign, Binary::Mul);

impl Div for Traced {
    type Output = Traced;
    fn div(self, rhs: Traced) -> Traced {
        Traced(record(Node::Binary(Binary::Div, self.0, rhs.0)))
    }
}

impl Neg for Traced {
    type Output = Traced;
    fn neg(self) -> Traced {
        self.unary(Unary::Neg)
    }
}

impl BitAnd for TracedMask {
    type Output = TracedMask;
    fn bitand(self, rhs: TracedMask) -> TracedMask {
        TracedMask(record(Node::And(self.0, rhs.0)))
    }
}

impl BitOr for TracedMask {
    type Output = TracedMask;
    fn bitor(self, rhs: TracedMask) -> TracedMask {
        TracedMask(record(Node::Or(self.0, rhs.0)))
    }
}

impl Not for TracedMask {
    type Output = TracedMask;
    fn not(self) -> TracedMask {
        TracedMask(record(Node::Not(self.0)))
    }
}

impl Traced {
    fn unary(self, op: Unary) -> Traced {
        Traced(record(Node::Unary(op, self.0)))
    }
    fn binary(self, op: Binary, rhs: Traced) -> Traced {
        Traced(record(Node::Binary(op, self.0, rhs.0)))
    }
}

impl Real for Traced {
    type Mask = TracedMask;
    const DOUBLE: bool = false;

    fn c(value: f64) -> Self {
        Traced(record(Node::Const((value as f32).to_bits())))
    }
    fn sqrt(self) -> Self {
        self.unary(Unary::Sqrt)
    }
    fn exp(self) -> Self {
        self.unary(Unary::Exp)
    }
    fn ln(self) -> Self {
        self.unary(Unary::Ln)
    }
    fn sin(self) -> Self {
        self.unary(Unary::Sin)
    }
    fn cos(self) -> Self {
        self.unary(Unary::Cos)
    }
    fn atan2(self, x: Self) -> Self {
        self.binary(Binary::Atan2, x)
    }
    fn abs(self) -> Self {
        self.unary(Unary::Abs)
    }
    fn min(self, other: Self) -> Self {
        self.binary(Binary::Min, other)
    }
    fn max(self, other: Self) -> Self {
        self.binary(Binary::Max, other)
    }
    fn floor(self) -> Self {
        self.unary(Unary::Floor)
    }
    fn lt(self, other: Self) -> TracedMask {
        TracedMask(record(Node::Less(self.0, other.0)))
    }
    fn le(self, other: Self) -> TracedMask {
        TracedMask(record(Node::LessEqual(self.0, other.0)))
    }
    fn select(mask: TracedMask, on_true: Self, on_false: Self) -> Self {
        Traced(record(Node::Select(mask.0, on_true.0, on_false.0)))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn poly<R: Real>(x: R, y: R) -> R {
        let m = x.lt(y);
        R::select(m, x * x + R::c(1.5), (y - x).sqrt()) * R::c(-0.25)
    }

    #[test]
    fn interpreter_reproduces_f32_bit_for_bit() {
        let g = trace(2, |a| vec![poly(a[0], a[1])]);
        for &(x, y) in &[(0.3_f32, 0.7_f32), (2.0, -1.0), (1.0, 1.0)] {
            assert_eq!(g.eval_f32(&[x, y])[0].to_bits(), poly(x, y).to_bits());
        }
    }

    #[test]
    fn common_subexpressions_are_shared() {
        let g = trace(1, |a| vec![a[0] * a[0] + a[0] * a[0]]);
        assert_eq!(g.count_binary(Binary::Mul), 1);
    }

    #[test]
    fn wgsl_text_has_one_let_per_live_operation() {
        let g = trace(2, |a| vec![poly(a[0], a[1]), a[0]]);
        let wgsl = g.to_wgsl("poly");
        assert!(
            wgsl.starts_with("fn poly(x0: f32, x1: f32) -> array<f32, 2> {"),
            "{wgsl}"
        );
        assert!(wgsl.contains("select("), "{wgsl}");
        assert!(wgsl.contains("(-0.25f)"), "{wgsl}");
    }
}
