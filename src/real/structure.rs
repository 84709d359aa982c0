//! The structure a trace keeps of the Rust code: named functions and loops over constant
//! arrays.
//!
//! Generic code marks a function with [`Real::call`](super::Real::call) and a fixed-count
//! loop with [`Real::fold`](super::Real::fold). The `f32`, `f64` and SIMD instantiations just
//! run the closure; the tracer records the closure's body once as a [`Function`] of the graph
//! and a [`CallSite`] where it is called, so that the emitted shader has a named function per
//! marked Rust function and a loop per marked loop. Values of the caller that a body uses are
//! *captured*: they become further parameters of the function, passed at the call site.
//!
//! [`flatten`] inlines every call and unrolls every loop into one flat body; its nodes are
//! exactly those the unstructured trace would have recorded, which is what
//! [`Graph::eval_f32`](super::Graph::eval_f32) interprets and the operation counts count.

use super::traced::{map_operands, Node, ResultType};
use std::collections::HashMap;

/// A [`ShaderFunction`] describing the function `name` of the calling module: its source is
/// `module_path!()::name`, its parameters the listed names (scalars, or `name: vec3` for a
/// `vec3<f32>`), its result `f32` / `array<f32, N>`, with `-> vec3` a `vec3<f32>`, and with
/// `-> {name, name: vec3, ...}` a struct of those fields named after the function
/// ([`ResultType::Fields`]).
///
/// ```
/// use hairmath::real::{Real, ShaderFunction};
/// /// `x^2 + y`.
/// fn square_plus<R: Real>(x: R, y: R) -> R {
///     const FUNCTION: ShaderFunction =
///         hairmath::shader_function!(square_plus, "an example, eq. 1", [x, y]);
///     R::call(&FUNCTION, [x, y], |[x, y]| [x * x + y])[0]
/// }
/// assert_eq!(square_plus(3.0_f32, 1.0), 10.0);
/// ```
#[macro_export]
macro_rules! shader_function {
    ($name:ident, $equation:expr, [$($param:ident $(: $shape:ident)?),* $(,)?]
        -> {$($field:ident $(: $field_shape:ident)?),+ $(,)?}) => {
        $crate::real::ShaderFunction {
            name: stringify!($name),
            source: concat!(module_path!(), "::", stringify!($name)),
            equation: $equation,
            parameters: &[$((stringify!($param), $crate::shader_function!(@shape $($shape)?))),*],
            result: $crate::real::ResultType::Fields(&[$(
                (stringify!($field), $crate::shader_function!(@shape $($field_shape)?))
            ),+]),
        }
    };
    ($name:ident, $equation:expr, [$($param:ident $(: $shape:ident)?),* $(,)?] $(-> $result:ident)?) => {
        $crate::real::ShaderFunction {
            name: stringify!($name),
            source: concat!(module_path!(), "::", stringify!($name)),
            equation: $equation,
            parameters: &[$((stringify!($param), $crate::shader_function!(@shape $($shape)?))),*],
            result: $crate::shader_function!(@result $($result)?),
        }
    };
    (@shape) => { $crate::real::Shape::Scalar };
    (@shape vec3) => { $crate::real::Shape::Vec3 };
    (@result) => { $crate::real::ResultType::Scalars };
    (@result vec3) => { $crate::real::ResultType::Vec3 };
}

/// The shape of a parameter of a [`ShaderFunction`].
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Shape {
    /// `f32`: one scalar.
    Scalar,
    /// `vec3<f32>`: three scalars.
    Vec3,
}

impl Shape {
    /// Number of scalars of the shape.
    pub const fn width(self) -> usize {
        match self {
            Shape::Scalar => 1,
            Shape::Vec3 => 3,
        }
    }
}

/// A generic function marked to become a named function in shader code
/// ([`Real::call`](super::Real::call)).
#[derive(Debug, PartialEq, Eq, Hash)]
pub struct ShaderFunction {
    /// The function's name in shader code.
    pub name: &'static str,
    /// The Rust function it is traced from (a path in the crate).
    pub source: &'static str,
    /// The paper and equation the function implements.
    pub equation: &'static str,
    /// The explicit parameters: name and shape, in order.
    pub parameters: &'static [(&'static str, Shape)],
    /// The result: `f32` for one output and `array<f32, N>` for N ([`ResultType::Scalars`]),
    /// `vec3<f32>` ([`ResultType::Vec3`]) or a struct ([`ResultType::Fields`]).
    pub result: ResultType,
}

impl ShaderFunction {
    /// Number of scalar inputs of the explicit parameters.
    pub fn input_count(&self) -> usize {
        self.parameters.iter().map(|(_, s)| s.width()).sum()
    }
}

/// A fixed-count loop over a constant array, marked to stay a loop in shader code
/// ([`Real::fold`](super::Real::fold)): `state = body(state, element)` for each element.
#[derive(Debug, PartialEq, Eq, Hash)]
pub struct ShaderLoop {
    /// The name of the shader function of the loop's body.
    pub name: &'static str,
    /// The name of the constant array of elements in shader code.
    pub array: &'static str,
    /// The names of one element's scalars.
    pub fields: &'static [&'static str],
    /// The state's values: names and shapes (a `vec3<f32>` is three state scalars).
    pub state: &'static [(&'static str, Shape)],
    /// The Rust function the loop is in (a path in the crate).
    pub source: &'static str,
    /// The paper and equation the loop implements.
    pub equation: &'static str,
}

impl ShaderLoop {
    /// Number of scalars of the state.
    pub fn state_width(&self) -> usize {
        self.state.iter().map(|(_, s)| s.width()).sum()
    }
}

/// The statements of one shader function: nodes in evaluation order, whose operands are
/// indices of earlier nodes of the same body, and the calls they make.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Body {
    /// The nodes, in evaluation order.
    pub nodes: Vec<Node>,
    /// The call sites [`Node::Result`] reads from.
    pub calls: Vec<CallSite>,
    /// The nodes returned, in order.
    pub outputs: Vec<u32>,
    /// Names of values for the written code ([`Real::label`](super::Real::label)): `(node,
    /// name)`, at most one per node, in the order given.
    pub labels: Vec<(u32, &'static str)>,
}

impl Body {
    /// The name [`Real::label`](super::Real::label) gave node `node`, if any.
    pub fn label(&self, node: u32) -> Option<&'static str> {
        self.labels
            .iter()
            .find(|&&(n, _)| n == node)
            .map(|&(_, name)| name)
    }
}

/// One call of a [`Function`] of the graph from a [`Body`].
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub struct CallSite {
    /// The index of the callee in [`Graph::functions`](super::Graph::functions).
    pub function: u32,
    /// Nodes of the calling body: for a [`CallKind::Call`] the callee's explicit inputs then
    /// its captures; for a [`CallKind::Loop`] the initial state then the captures.
    pub args: Vec<u32>,
    /// A call or a loop.
    pub kind: CallKind,
}

/// How a [`CallSite`] runs its callee.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum CallKind {
    /// Once.
    Call,
    /// Once per element of a constant array, threading the state through.
    Loop {
        /// The index of the array in [`Graph::arrays`](super::Graph::arrays).
        array: u32,
    },
}

/// What a [`Function`] was traced from.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum FunctionKind {
    /// A function marked with [`Real::call`](super::Real::call).
    Function(&'static ShaderFunction),
    /// The body of a loop marked with [`Real::fold`](super::Real::fold).
    LoopBody(&'static ShaderLoop),
}

impl FunctionKind {
    /// The name the Rust code gives the function.
    pub fn name(&self) -> &'static str {
        match self {
            FunctionKind::Function(f) => f.name,
            FunctionKind::LoopBody(l) => l.name,
        }
    }
}

/// A shader function of the graph. [`Node::Input`]`(k)` in its body is its scalar parameter
/// `k`: the `inputs` explicit ones first, then the `captures`.
#[derive(Clone, Debug, PartialEq)]
pub struct Function {
    /// The unique shader name: the Rust name, with `_2`, `_3`, ... appended for functions of
    /// the same name whose bodies differ (for example other constants).
    pub name: String,
    /// What it was traced from.
    pub kind: FunctionKind,
    /// Its body.
    pub body: Body,
    /// Explicit scalar parameters: a function's parameters, or a loop body's state followed
    /// by one element.
    pub inputs: u32,
    /// Further scalar parameters: values of the caller the body uses.
    pub captures: u32,
}

/// The elements of a loop's constant array.
#[derive(Clone, Debug, PartialEq)]
pub struct ConstArray {
    /// The loop it belongs to (names of the array and of the fields).
    pub info: &'static ShaderLoop,
    /// The elements, each of `info.fields.len()` scalars.
    pub elements: Vec<Vec<f32>>,
}

/// A flat body under construction: nodes with equal nodes recorded once.
#[derive(Default)]
struct FlatBody {
    nodes: Vec<Node>,
    index: HashMap<Node, u32>,
}

impl FlatBody {
    fn intern(&mut self, node: Node) -> u32 {
        if let Some(&id) = self.index.get(&node) {
            return id;
        }
        let id = self.nodes.len() as u32;
        self.nodes.push(node);
        self.index.insert(node, id);
        id
    }
}

/// `body` (of `inputs` scalar inputs) with every call inlined and every loop unrolled: the
/// nodes (and outputs) of one flat body, the inputs first, equal nodes recorded once, every
/// operand before its use.
pub(super) fn flatten(
    body: &Body,
    inputs: u32,
    functions: &[Function],
    arrays: &[ConstArray],
) -> Body {
    let mut flat = FlatBody::default();
    let inputs: Vec<u32> = (0..inputs).map(|k| flat.intern(Node::Input(k))).collect();
    let outputs = inline(body, &inputs, functions, arrays, &mut flat);
    Body {
        nodes: flat.nodes,
        calls: Vec::new(),
        outputs,
        labels: Vec::new(),
    }
}

/// Records `body`, called with the flat nodes `args` as its inputs, in `flat`; returns the
/// flat nodes of its outputs.
fn inline(
    body: &Body,
    args: &[u32],
    functions: &[Function],
    arrays: &[ConstArray],
    flat: &mut FlatBody,
) -> Vec<u32> {
    let mut map = Vec::with_capacity(body.nodes.len());
    let mut results: HashMap<u32, Vec<u32>> = HashMap::new();
    for node in &body.nodes {
        let id = match *node {
            Node::Input(k) => args[k as usize],
            Node::Result { site, output } => {
                let outputs = results.entry(site).or_insert_with(|| {
                    let call = &body.calls[site as usize];
                    let call_args: Vec<u32> = call.args.iter().map(|&a| map[a as usize]).collect();
                    run_call(call, &call_args, functions, arrays, flat)
                });
                outputs[output as usize]
            }
            other => flat.intern(map_operands(other, |k| map[k as usize])),
        };
        map.push(id);
    }
    body.outputs.iter().map(|&o| map[o as usize]).collect()
}

/// The flat outputs of `call` with the flat arguments `args`: the callee inlined once, or for
/// a loop once per element with the state threaded through.
fn run_call(
    call: &CallSite,
    args: &[u32],
    functions: &[Function],
    arrays: &[ConstArray],
    flat: &mut FlatBody,
) -> Vec<u32> {
    let function = &functions[call.function as usize];
    match call.kind {
        CallKind::Call => inline(&function.body, args, functions, arrays, flat),
        CallKind::Loop { array } => {
            let state_len = function.body.outputs.len();
            let (init, captures) = args.split_at(state_len);
            let mut state = init.to_vec();
            for element in &arrays[array as usize].elements {
                let mut inputs = state.clone();
                inputs.extend(
                    element
                        .iter()
                        .map(|v| flat.intern(Node::Const(v.to_bits()))),
                );
                inputs.extend_from_slice(captures);
                state = inline(&function.body, &inputs, functions, arrays, flat);
            }
            state
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::real::{trace, trace_with, ArgType, Parameter, Real, Signature, Traced};

    const SQUARE_PLUS: ShaderFunction = ShaderFunction {
        name: "square_plus",
        source: "test",
        equation: "none",
        parameters: &[("x", Shape::Scalar)],
        result: ResultType::Scalars,
    };

    const SCALE_SUM: ShaderLoop = ShaderLoop {
        name: "scale_sum",
        array: "WEIGHTS",
        fields: &["weight", "offset"],
        state: &[("sum", Shape::Scalar)],
        source: "test",
        equation: "none",
    };

    /// `x^2 + k`, with `k` a value of the caller (captured by the traced function).
    fn square_plus<R: Real>(x: R, k: R) -> R {
        R::call(&SQUARE_PLUS, [x], |[x]| [x * x + k])[0]
    }

    /// `sum over elements of weight * (x + offset)`, a loop over constants.
    fn weighted<R: Real>(x: R) -> R {
        let elements = [[R::c(0.25), R::c(1.0)], [R::c(0.75), R::c(-2.0)]];
        R::fold(&SCALE_SUM, &elements, [R::c(0.0)], |[sum], [w, o]| {
            [sum + w * square_plus(x + o, R::c(0.5))]
        })[0]
    }

    fn calls_twice<R: Real>(a: R, b: R) -> R {
        square_plus(a, b) - square_plus(b, b) + weighted(a)
    }

    #[test]
    fn a_marked_function_is_recorded_once_and_called_twice() {
        let g = trace(2, |x| vec![calls_twice(x[0], x[1])]);
        let names: Vec<&str> = g.functions().iter().map(|f| f.name.as_str()).collect();
        // square_plus captures b at the top level, and 0.5 (a constant, not captured) in the loop.
        assert_eq!(names, ["square_plus", "square_plus_2", "scale_sum"]);
        let first = &g.functions()[0];
        assert_eq!((first.inputs, first.captures), (1, 1));
        let calls = &g.body().calls;
        assert_eq!(calls.iter().filter(|c| c.function == 0).count(), 2);
        assert!(matches!(calls[2].kind, CallKind::Loop { array: 0 }));
        assert_eq!(
            g.arrays()[0].elements,
            vec![vec![0.25, 1.0], vec![0.75, -2.0]]
        );
    }

    #[test]
    fn the_flat_graph_computes_the_f32_code_bit_for_bit() {
        let g = trace(2, |x| vec![calls_twice(x[0], x[1])]);
        for &(a, b) in &[(0.3_f32, 0.7_f32), (-2.5, 1.25), (1e-3, 4e3)] {
            assert_eq!(
                g.eval_f32(&[a, b])[0].to_bits(),
                calls_twice(a, b).to_bits()
            );
        }
        let flat_calls = g
            .nodes()
            .iter()
            .filter(|n| matches!(n, Node::Result { .. }))
            .count();
        assert_eq!(flat_calls, 0);
    }

    #[test]
    fn flattening_records_what_an_unmarked_trace_records() {
        fn unmarked(a: Traced, b: Traced) -> Traced {
            let sp = |x: Traced, k: Traced| x * x + k;
            let mut sum = Traced::c(0.0);
            for (w, o) in [(0.25, 1.0), (0.75, -2.0)] {
                sum += Traced::c(w) * sp(a + Traced::c(o), Traced::c(0.5));
            }
            sp(a, b) - sp(b, b) + sum
        }
        let marked = trace(2, |x| vec![calls_twice(x[0], x[1])]);
        let plain = trace(2, |x| vec![unmarked(x[0], x[1])]);
        assert_eq!(marked.live_nodes().len(), plain.live_nodes().len());
        // a*a, b*b, and per element (a + o)^2 and w * (...).
        let mul = super::super::Binary::Mul;
        assert_eq!(marked.count_binary(mul), 6);
        assert_eq!(plain.count_binary(mul), 6);
        assert_eq!(marked.eval_f32(&[0.3, 0.7]), plain.eval_f32(&[0.3, 0.7]));
    }

    #[test]
    fn values_of_enclosing_frames_are_captured_through_every_level() {
        const OUTER: ShaderFunction = ShaderFunction {
            name: "outer",
            source: "test",
            equation: "none",
            parameters: &[("y", Shape::Scalar)],
            result: ResultType::Scalars,
        };
        let f = |a: Traced, b: Traced| Traced::call(&OUTER, [a], |[y]| [square_plus(y, b)])[0];
        let g = trace(2, |x| vec![f(x[0], x[1])]);
        // outer captures b to pass it on to square_plus, which captures it from outer.
        let outer = g.functions().iter().find(|f| f.name == "outer").unwrap();
        assert_eq!((outer.inputs, outer.captures), (1, 1));
        assert_eq!(g.eval_f32(&[3.0, 0.5]), vec![9.5]);
    }

    #[test]
    fn constant_parameters_are_globals() {
        let signature = Signature {
            parameters: vec![
                Parameter {
                    constant: Some(vec![2.0, 3.0, 4.0]),
                    ..Parameter::argument("k", ArgType::Vec3)
                },
                Parameter::argument("x", ArgType::Scalar),
            ],
            result: ResultType::Scalars,
        };
        let g = trace_with(signature, |x| vec![x[0] * x[3] + x[2]]);
        assert_eq!(g.input_count(), 1);
        assert_eq!(g.globals(), &[2.0, 3.0, 4.0]);
        assert!(g.body().nodes.contains(&Node::Global(2)));
        assert_eq!(g.eval_f32(&[10.0]), vec![24.0]);
    }

    #[test]
    #[should_panic(expected = "must be constants")]
    fn a_loop_over_traced_values_panics_with_a_message() {
        trace(1, |x| {
            vec![Traced::fold(&SCALE_SUM, &[[x[0], x[0]]], [x[0]], |s, _| s)[0]]
        });
    }
}
