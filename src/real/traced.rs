//! Symbolic tracing: running generic code on [`Traced`] values records it as a graph.
//!
//! [`trace`] (anonymous scalar arguments) and [`trace_with`] (named arguments of a
//! [`Signature`]: scalars, `vec3<f32>` vectors and named structs such as a model's uniforms)
//! call a closure with symbolic inputs; every arithmetic operation appends a node to a
//! thread-local graph (identical nodes are shared, so the graph is in SSA form with common
//! subexpressions merged). The finished [`Graph`] prints as a WGSL function
//! ([`Graph::to_wgsl`], with the declarations of the structs its arguments use) and can be
//! interpreted in `f32` ([`Graph::eval_f32`]) with exactly the operations of the `f32`
//! instantiation, which is how tests prove that the generated shader code computes what the
//! CPU code computes.
//!
//! Traced values have single-precision semantics (`Real::DOUBLE` is false) and constants
//! are rounded to `f32` when recorded.
//!
//! Table fetches ([`Real::sample_table`]) record one [`Node::Fetch`] per channel; the graph
//! keeps the tables it reads ([`Graph::tables`], one entry per table, identified by the
//! address of its shared pointer), counts the fetches ([`Graph::count_fetches`]), evaluates
//! them with [`Table::lookup_into`] and prints each table as a texture binding read with
//! `textureSampleLevel` ([`Graph::to_wgsl`]).
//!
//! A trace that panics inside its closure leaves nothing behind: the thread can trace again.
//! Using a [`Traced`] value outside the trace that made it (after it ended, or inside another
//! one) panics with a message saying so, rather than recording a wrong graph.

use super::structure::{
    flatten, Body, CallKind, CallSite, ConstArray, Function, FunctionKind, ShaderFunction,
    ShaderLoop, Shape,
};
use super::{NamedConstant, Real};
use crate::lut::{SharedTable, Table, MAX_AXES, MAX_CHANNELS};
use core::cell::RefCell;
use core::ops::{Add, AddAssign, BitAnd, BitOr, Div, Mul, MulAssign, Neg, Not, Sub, SubAssign};
use std::collections::{HashMap, HashSet};
use std::fmt::Write as _;
use std::sync::Arc;

/// The coordinate slot of a [`Node::Fetch`] beyond the table's axes.
pub const NO_COORDINATE: u32 = u32::MAX;

/// Channels per texture in shader code (RGBA): a table of more channels prints as several
/// textures, channel `c` in texture `c / 4`, component `c % 4`.
pub const TEXTURE_CHANNELS: usize = 4;

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
    /// Value `index` of the named constant `constant` of [`Graph::named_constants`]
    /// ([`Real::named`]): a constant that shader code reads by name.
    Named {
        /// The index of the constant in [`Graph::named_constants`].
        constant: u32,
        /// Which of its values.
        index: u32,
    },
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
    /// One channel of a table fetch ([`Real::sample_table`]): multilinear interpolation of
    /// table `table` of [`Graph::tables`] at the coordinates `coords`, as
    /// [`Table::lookup_into`] computes it.
    Fetch {
        /// The index of the table in [`Graph::tables`].
        table: u32,
        /// The nodes of the coordinates, one per axis of the table, then
        /// [`NO_COORDINATE`].
        coords: [u32; MAX_AXES],
        /// The channel read.
        channel: u32,
    },
    /// Scalar `k` of the graph's baked constants ([`Graph::globals`]): the scalars of the
    /// signature's constant parameters ([`Parameter::constant`]), in signature order.
    Global(u32),
    /// Output `output` of call site `site` of the body's [`Body::calls`].
    Result {
        /// The index of the call site in [`Body::calls`].
        site: u32,
        /// Which output of the callee.
        output: u32,
    },
}

/// The shader type of one argument (or struct field) of a traced function.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum ArgType {
    /// `f32`.
    Scalar,
    /// `vec3<f32>`, components `x`, `y`, `z`.
    Vec3,
    /// A named struct, for example a model's uniforms.
    Struct(StructType),
}

/// A named struct of a traced function's arguments: its fields in declaration order.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct StructType {
    /// The struct's name in shader code.
    pub name: String,
    /// (field name, field type) in declaration order.
    pub fields: Vec<(String, ArgType)>,
}

/// One named argument of a traced function.
#[derive(Clone, Debug, PartialEq)]
pub struct Parameter {
    /// The argument's name in shader code.
    pub name: String,
    /// Its type.
    pub ty: ArgType,
    /// `Some(values)`, one per scalar of `ty`: the parameter is not an argument but a
    /// module-scope constant of these values, which the traced closure reads as
    /// [`Node::Global`]s ([`Graph::globals`]) and shader code by name. `None`: an argument.
    pub constant: Option<Vec<f32>>,
}

impl Parameter {
    /// An argument named `name` of type `ty`.
    pub fn argument(name: &str, ty: ArgType) -> Self {
        Parameter {
            name: name.to_string(),
            ty,
            constant: None,
        }
    }
}

/// What a traced function returns.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum ResultType {
    /// `f32` for one output, `array<f32, N>` for N outputs.
    Scalars,
    /// `vec3<f32>` of exactly three outputs (an RGB value, a direction).
    Vec3,
    /// A struct of named `f32` and `vec3<f32>` fields, the outputs in field order (a `vec3`
    /// field as x, y, z), named after the function in upper camel case.
    Fields(&'static [(&'static str, Shape)]),
}

impl ResultType {
    /// Number of outputs the result needs, if the type fixes it (`None` for
    /// [`ResultType::Scalars`]).
    pub fn width(self) -> Option<usize> {
        match self {
            ResultType::Scalars => None,
            ResultType::Vec3 => Some(3),
            ResultType::Fields(fields) => Some(fields.iter().map(|(_, s)| s.width()).sum()),
        }
    }

    /// The name of the field that output `output` is, if it is a scalar field of a
    /// [`ResultType::Fields`] (`None` for a vector's component or another result type).
    pub fn scalar_field(self, output: usize) -> Option<&'static str> {
        let ResultType::Fields(fields) = self else {
            return None;
        };
        let mut first = 0;
        for &(name, shape) in fields {
            if output == first {
                return (shape.width() == 1).then_some(name);
            }
            first += shape.width();
        }
        None
    }
}

/// The arguments and result of a traced function. The closure of [`trace_with`] receives one
/// [`Traced`] input per scalar: the arguments in order, a vector as its x, y, z, a struct as
/// its fields in order (recursively).
#[derive(Clone, Debug, PartialEq)]
pub struct Signature {
    /// The arguments, in order.
    pub parameters: Vec<Parameter>,
    /// The result type.
    pub result: ResultType,
}

impl ArgType {
    /// Number of scalars of the type.
    pub fn width(&self) -> usize {
        match self {
            ArgType::Scalar => 1,
            ArgType::Vec3 => 3,
            ArgType::Struct(s) => s.fields.iter().map(|(_, t)| t.width()).sum(),
        }
    }

    /// The shader expressions of the type's scalars for a value written `base`.
    fn scalar_paths(&self, base: &str, out: &mut Vec<String>) {
        match self {
            ArgType::Scalar => out.push(base.to_string()),
            ArgType::Vec3 => out.extend(["x", "y", "z"].map(|c| format!("{base}.{c}"))),
            ArgType::Struct(s) => {
                for (name, ty) in &s.fields {
                    ty.scalar_paths(&format!("{base}.{name}"), out);
                }
            }
        }
    }

    fn wgsl(&self) -> String {
        match self {
            ArgType::Scalar => "f32".into(),
            ArgType::Vec3 => "vec3<f32>".into(),
            ArgType::Struct(s) => s.name.clone(),
        }
    }

    /// Appends the struct declarations this type needs (inner structs first), once each.
    fn struct_declarations(&self, seen: &mut Vec<String>, out: &mut String) {
        let ArgType::Struct(s) = self else { return };
        for (_, ty) in &s.fields {
            ty.struct_declarations(seen, out);
        }
        if seen.contains(&s.name) {
            return;
        }
        seen.push(s.name.clone());
        let _ = writeln!(out, "struct {} {{", s.name);
        for (name, ty) in &s.fields {
            let _ = writeln!(out, "    {name}: {},", ty.wgsl());
        }
        out.push_str("}\n\n");
    }
}

impl Signature {
    /// `count` anonymous scalar arguments `x0, x1, ...`, scalar results.
    pub fn scalars(count: usize) -> Self {
        Signature {
            parameters: (0..count)
                .map(|i| Parameter::argument(&format!("x{i}"), ArgType::Scalar))
                .collect(),
            result: ResultType::Scalars,
        }
    }

    /// Number of scalar inputs of the traced closure: the scalars of every parameter,
    /// arguments and constants.
    pub fn input_count(&self) -> usize {
        self.parameters.iter().map(|p| p.ty.width()).sum()
    }

    /// Number of scalars of the arguments (the parameters that are not constants): the
    /// inputs of [`Graph::eval_f32`].
    pub fn argument_count(&self) -> usize {
        self.parameters
            .iter()
            .filter(|p| p.constant.is_none())
            .map(|p| p.ty.width())
            .sum()
    }

    /// The shader expressions of the scalars of the arguments ([`Node::Input`] order) and of
    /// the constant parameters ([`Node::Global`] order): `wi.x`, `uniforms.eta`.
    fn input_paths(&self) -> (Vec<String>, Vec<String>) {
        let (mut arguments, mut constants) = (Vec::new(), Vec::new());
        for p in &self.parameters {
            let out = if p.constant.is_some() {
                &mut constants
            } else {
                &mut arguments
            };
            p.ty.scalar_paths(&p.name, out);
        }
        (arguments, constants)
    }
}

/// A recorded computation: the structured top-level body with the functions and constant
/// arrays it uses ([`Graph::body`], [`Graph::functions`], [`Graph::arrays`]), the same
/// computation flattened ([`Graph::nodes`]: every call inlined, every loop unrolled), the
/// signature of the traced function, the baked constants and the tables.
#[derive(Clone, Debug, PartialEq)]
pub struct Graph {
    /// The flattened computation: what [`Graph::eval_f32`] interprets and the counts count.
    nodes: Vec<Node>,
    outputs: Vec<u32>,
    body: Body,
    functions: Vec<Function>,
    arrays: Vec<ConstArray>,
    signature: Signature,
    globals: Vec<f32>,
    tables: Vec<Arc<Table>>,
    named: Vec<&'static NamedConstant>,
}

/// The body being recorded at one level of calls.
struct Frame {
    /// Distinguishes the values of this frame from those of every other frame and trace.
    trace: u32,
    body: Body,
    index: HashMap<Node, u32>,
    call_index: HashMap<CallSite, u32>,
    /// Explicit scalar parameters (the captures follow them).
    inputs: u32,
    /// The captured values: nodes of the enclosing frame, in parameter order.
    captures: Vec<u32>,
    /// Captured node of the enclosing frame -> its input node here.
    capture_index: HashMap<u32, u32>,
}

impl Frame {
    fn new(inputs: u32) -> Self {
        Frame {
            trace: next_trace_id(),
            body: Body::default(),
            index: HashMap::new(),
            call_index: HashMap::new(),
            inputs,
            captures: Vec::new(),
            capture_index: HashMap::new(),
        }
    }

    /// The index of `node` in this frame, recorded if new.
    fn intern(&mut self, node: Node) -> u32 {
        if let Some(&id) = self.index.get(&node) {
            return id;
        }
        let id = self.body.nodes.len() as u32;
        self.body.nodes.push(node);
        self.index.insert(node, id);
        id
    }

    /// The index of `site` in this frame's calls, added if new.
    fn intern_call(&mut self, site: CallSite) -> u32 {
        if let Some(&id) = self.call_index.get(&site) {
            return id;
        }
        let id = self.body.calls.len() as u32;
        self.body.calls.push(site.clone());
        self.call_index.insert(site, id);
        id
    }
}

/// The running trace: a stack of frames (the top-level function first, then one per call
/// being traced) and what they share.
struct Recorder {
    frames: Vec<Frame>,
    functions: Vec<Function>,
    arrays: Vec<ConstArray>,
    /// The tables fetched from, each once (by pointer).
    tables: Vec<Arc<Table>>,
    /// The named constants read, each once (by name).
    named: Vec<&'static NamedConstant>,
}

impl Recorder {
    fn top(&mut self) -> &mut Frame {
        self.frames
            .last_mut()
            .expect("a trace has a top-level frame")
    }

    /// The index in frame `level` of the value `node` of the frame `trace`: the node itself,
    /// or, for a value of an enclosing frame, a capture (literal constants are recorded
    /// again).
    ///
    /// # Panics
    /// If `trace` is no frame of this recorder.
    fn localize(&mut self, level: usize, node: u32, trace: u32) -> u32 {
        if self.frames[level].trace == trace {
            return node;
        }
        assert!(
            level > 0,
            "a Traced value from another trace was used (traced values live only inside the \
             closure of the trace that made them)"
        );
        let outer = self.localize(level - 1, node, trace);
        let outer_node = self.frames[level - 1].body.nodes[outer as usize];
        let frame = &mut self.frames[level];
        // Literals are written again; everything else (baked uniforms included) is passed,
        // so that a function called with different uniforms is one function.
        if matches!(outer_node, Node::Const(_) | Node::Named { .. }) {
            return frame.intern(outer_node);
        }
        if let Some(&local) = frame.capture_index.get(&outer) {
            return local;
        }
        let parameter = frame.inputs + frame.captures.len() as u32;
        frame.captures.push(outer);
        let local = frame.intern(Node::Input(parameter));
        frame.capture_index.insert(outer, local);
        local
    }

    /// Records `node`, whose operands (in [`map_operands`] order) are values of the frames
    /// `traces`, in the top frame.
    fn record(&mut self, node: Node, traces: &[u32]) -> (u32, u32) {
        let level = self.frames.len() - 1;
        let mut k = 0;
        let node = map_operands(node, |id| {
            let local = self.localize(level, id, traces[k]);
            k += 1;
            local
        });
        let frame = self.top();
        (frame.intern(node), frame.trace)
    }

    /// Names the node `node` of the frame `trace` `name`, unless it has a name (a value of no
    /// running frame is left unnamed: names only serve the written code).
    fn label(&mut self, node: u32, trace: u32, name: &'static str) {
        if let Some(frame) = self.frames.iter_mut().find(|f| f.trace == trace) {
            if frame.body.label(node).is_none() {
                frame.body.labels.push((node, name));
            }
        }
    }

    /// The index of a traced body as a function of the graph: an equal earlier function, or
    /// a new one named after `kind` (with `_2`, `_3`, ... for a differing body of that name).
    fn add_function(&mut self, kind: FunctionKind, body: Body, inputs: u32, captures: u32) -> u32 {
        let same = |f: &Function| {
            f.kind == kind && f.body == body && f.inputs == inputs && f.captures == captures
        };
        if let Some(k) = self.functions.iter().position(same) {
            return k as u32;
        }
        let namesakes = self
            .functions
            .iter()
            .filter(|f| f.kind.name() == kind.name())
            .count();
        let name = match namesakes {
            0 => kind.name().to_string(),
            n => format!("{}_{}", kind.name(), n + 1),
        };
        self.functions.push(Function {
            name,
            kind,
            body,
            inputs,
            captures,
        });
        (self.functions.len() - 1) as u32
    }

    /// The index of the named constant `constant` (by name), added if new.
    ///
    /// # Panics
    /// If an earlier constant of that name has other values (two constants may not share a
    /// name in shader code).
    fn add_named(&mut self, constant: &'static NamedConstant) -> u32 {
        let k = match self.named.iter().position(|c| c.name == constant.name) {
            Some(k) => {
                assert!(
                    self.named[k].values == constant.values,
                    "two named constants are called {}",
                    constant.name
                );
                k
            }
            None => {
                self.named.push(constant);
                self.named.len() - 1
            }
        };
        k as u32
    }

    /// The index of the constant array of `info` with `elements`, added if new.
    fn add_array(&mut self, info: &'static ShaderLoop, elements: Vec<Vec<f32>>) -> u32 {
        let array = ConstArray { info, elements };
        let k = match self.arrays.iter().position(|a| *a == array) {
            Some(k) => k,
            None => {
                self.arrays.push(array);
                self.arrays.len() - 1
            }
        };
        k as u32
    }
}

/// A new identifier for a trace or a frame.
fn next_trace_id() -> u32 {
    TRACES.with(|t| {
        let id = t.get().wrapping_add(1);
        t.set(id);
        id
    })
}

/// Runs `f` on the running trace.
///
/// # Panics
/// If no trace is running.
fn with_recorder<T>(f: impl FnOnce(&mut Recorder) -> T) -> T {
    RECORDER.with(|r| {
        let mut guard = r.borrow_mut();
        let rec = guard.as_mut().expect(
            "a Traced value was used outside hairmath::real::trace (traced values live only \
             inside the closure of the trace that made them)",
        );
        f(rec)
    })
}

/// The index of `table` among the tables of the running trace, added if new.
///
/// # Panics
/// If no trace is running.
fn register_table(table: &Arc<Table>) -> u32 {
    with_recorder(|rec| {
        let id = match rec.tables.iter().position(|t| Arc::ptr_eq(t, table)) {
            Some(id) => id,
            None => {
                rec.tables.push(Arc::clone(table));
                rec.tables.len() - 1
            }
        };
        id as u32
    })
}

thread_local! {
    static RECORDER: RefCell<Option<Recorder>> = const { RefCell::new(None) };
    static TRACES: core::cell::Cell<u32> = const { core::cell::Cell::new(0) };
}

/// Records `node`, whose operands (in [`map_operands`] order) are values of the frames
/// `traces`, in the running trace's top frame; returns its index and the frame.
///
/// # Panics
/// If no trace is running, or an operand comes from another trace.
fn record(node: Node, traces: &[u32]) -> (u32, u32) {
    with_recorder(|rec| rec.record(node, traces))
}

/// Traces `body` called with `inputs` as a function of the running trace (see
/// [`Real::call`] and [`Real::fold`]): records it in a new frame whose first `inputs.len()`
/// inputs are `inputs`, makes it a function of the graph and records the call site
/// `site(function, captures)` in the calling frame; returns the site's outputs.
fn record_call(
    kind: FunctionKind,
    inputs: usize,
    body: impl FnOnce(&[Traced]) -> Vec<Traced>,
    site: impl FnOnce(u32, Vec<u32>) -> CallSite,
) -> Vec<Traced> {
    let args: Vec<Traced> = with_recorder(|rec| {
        rec.frames.push(Frame::new(inputs as u32));
        (0..inputs)
            .map(|k| Traced::from_record(rec.record(Node::Input(k as u32), &[])))
            .collect()
    });
    let outputs = body(&args);
    with_recorder(|rec| {
        let level = rec.frames.len() - 1;
        let locals: Vec<u32> = outputs
            .iter()
            .map(|o| rec.localize(level, o.node, o.trace))
            .collect();
        let mut frame = rec.frames.pop().expect("the callee's frame");
        frame.body.outputs = locals;
        let captures = frame.captures.len() as u32;
        let function = rec.add_function(kind, frame.body, inputs as u32, captures);
        let caller = rec.top();
        let s = caller.intern_call(site(function, frame.captures));
        (0..outputs.len() as u32)
            .map(|output| {
                let node = Node::Result { site: s, output };
                Traced::from_record((caller.intern(node), caller.trace))
            })
            .collect()
    })
}

/// The nodes in the top frame of the values `values` (of enclosing frames or the top one).
fn localize_in_top(values: &[Traced]) -> Vec<u32> {
    with_recorder(|rec| {
        let level = rec.frames.len() - 1;
        values
            .iter()
            .map(|v| rec.localize(level, v.node, v.trace))
            .collect()
    })
}

/// The value of a constant node, if `x` is one.
fn constant_value(x: Traced) -> Option<f32> {
    with_recorder(|rec| {
        let level = rec.frames.iter().position(|f| f.trace == x.trace)?;
        match rec.frames[level].body.nodes[x.node as usize] {
            Node::Const(bits) => Some(f32::from_bits(bits)),
            Node::Named { constant, index } => Some(named_value(&rec.named, constant, index)),
            _ => None,
        }
    })
}

/// Value `index` of named constant `constant` of `named`, rounded to `f32`.
fn named_value(named: &[&'static NamedConstant], constant: u32, index: u32) -> f32 {
    named[constant as usize].values[index as usize] as f32
}

/// A symbolic scalar: a node of the graph being traced.
///
/// # Panics
/// Every operation on a traced value panics when no trace is running or when the value was
/// recorded by another trace: traced values live only inside the closure of [`trace`] or
/// [`trace_with`] that made them.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Traced {
    node: u32,
    trace: u32,
}

/// A symbolic boolean produced by comparing [`Traced`] values (same lifetime rule).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct TracedMask {
    node: u32,
    trace: u32,
}

/// Ends the running trace when dropped, also when the traced closure panics, so that the thread
/// can trace again.
struct Session;

impl Drop for Session {
    fn drop(&mut self) {
        RECORDER.with(|r| r.borrow_mut().take());
    }
}

/// Traces `f` called with `inputs` anonymous scalar arguments (`x0, x1, ...` in WGSL) and
/// returns the recorded graph: [`trace_with`] for [`Signature::scalars`].
///
/// # Panics
/// If called while another trace is running on the same thread (traces do not nest).
pub fn trace(inputs: usize, f: impl FnOnce(&[Traced]) -> Vec<Traced>) -> Graph {
    trace_with(Signature::scalars(inputs), f)
}

/// Traces `f` called with one symbolic input per scalar of `signature` (an argument's scalars
/// as [`Node::Input`]s, a constant parameter's as [`Node::Global`]s) and returns the recorded
/// graph. If `f` panics, the trace is discarded and the panic continues.
///
/// # Panics
/// If called while another trace is running on the same thread (traces do not nest), if a
/// constant parameter does not have one value per scalar, or if the result type is
/// [`ResultType::Vec3`] or [`ResultType::Fields`] and `f` does not return one value per
/// scalar of it.
pub fn trace_with(signature: Signature, f: impl FnOnce(&[Traced]) -> Vec<Traced>) -> Graph {
    let top = Frame::new(0);
    let trace = top.trace;
    RECORDER.with(|r| {
        let mut guard = r.borrow_mut();
        assert!(guard.is_none(), "hairmath::real::trace does not nest");
        *guard = Some(Recorder {
            frames: vec![top],
            functions: Vec::new(),
            arrays: Vec::new(),
            tables: Vec::new(),
            named: Vec::new(),
        });
    });
    let session = Session;
    let (args, globals) = signature_inputs(&signature);
    let outputs = f(&args);
    let rec = RECORDER
        .with(|r| r.borrow_mut().take())
        .expect("the recorder lives until the session ends");
    drop(session);
    assert!(
        signature.result.width().is_none_or(|w| w == outputs.len()),
        "a result of type {:?} does not have {} outputs",
        signature.result,
        outputs.len()
    );
    assert!(
        outputs.iter().all(|t| t.trace == trace),
        "a traced function returned a value of another trace"
    );
    let Recorder {
        mut frames,
        functions,
        arrays,
        tables,
        named,
    } = rec;
    let mut body = frames.pop().expect("the top-level frame").body;
    body.outputs = outputs.iter().map(|t| t.node).collect();
    let flat = flatten(
        &body,
        signature.argument_count() as u32,
        &functions,
        &arrays,
    );
    Graph {
        nodes: flat.nodes,
        outputs: flat.outputs,
        body,
        functions,
        arrays,
        signature,
        globals,
        tables,
        named,
    }
}

/// The closure's inputs for `signature` (recorded in the running trace's top frame) and the
/// values of its constant parameters.
fn signature_inputs(signature: &Signature) -> (Vec<Traced>, Vec<f32>) {
    let mut args = Vec::with_capacity(signature.input_count());
    let mut globals = Vec::new();
    let mut arguments = 0;
    for p in &signature.parameters {
        let width = p.ty.width();
        let nodes: Vec<Node> = match &p.constant {
            Some(values) => {
                assert_eq!(
                    values.len(),
                    width,
                    "constant parameter {} needs one value per scalar",
                    p.name
                );
                let first = globals.len() as u32;
                globals.extend_from_slice(values);
                (0..width as u32).map(|k| Node::Global(first + k)).collect()
            }
            None => {
                arguments += width as u32;
                (arguments - width as u32..arguments)
                    .map(Node::Input)
                    .collect()
            }
        };
        args.extend(
            nodes
                .into_iter()
                .map(|n| Traced::from_record(record(n, &[]))),
        );
    }
    (args, globals)
}

impl Graph {
    /// The flattened computation's nodes in evaluation order, every call inlined and every
    /// loop unrolled (live or not; see [`Graph::count_binary`] for counts of what the outputs
    /// depend on).
    pub fn nodes(&self) -> &[Node] {
        &self.nodes
    }

    /// The structured top-level body: its nodes, the calls it makes
    /// ([`Node::Result`] reads their outputs) and its outputs.
    pub fn body(&self) -> &Body {
        &self.body
    }

    /// The functions the bodies call, each once; a function calls only functions of lower
    /// index.
    pub fn functions(&self) -> &[Function] {
        &self.functions
    }

    /// The constant arrays of the loops.
    pub fn arrays(&self) -> &[ConstArray] {
        &self.arrays
    }

    /// The values of the baked constants: the scalars of the signature's constant
    /// parameters in order ([`Node::Global`]).
    pub fn globals(&self) -> &[f32] {
        &self.globals
    }

    /// The signature of the traced function.
    pub fn signature(&self) -> &Signature {
        &self.signature
    }

    /// Number of scalar arguments of the traced function ([`Signature::argument_count`]):
    /// the inputs of [`Graph::eval_f32`].
    pub fn input_count(&self) -> usize {
        self.signature.argument_count()
    }

    /// The flat nodes ([`Graph::nodes`]) the traced function returns, in order.
    pub fn outputs(&self) -> &[u32] {
        &self.outputs
    }

    /// Number of outputs of the traced function.
    pub fn output_count(&self) -> usize {
        self.outputs.len()
    }

    /// The value of `node` if it is a constant: a literal ([`Node::Const`]), a named constant
    /// ([`Node::Named`]) or a baked uniform ([`Node::Global`]).
    pub fn constant(&self, node: &Node) -> Option<f32> {
        match *node {
            Node::Const(bits) => Some(f32::from_bits(bits)),
            Node::Named { constant, index } => Some(named_value(&self.named, constant, index)),
            Node::Global(k) => Some(self.globals[k as usize]),
            _ => None,
        }
    }

    /// The named constants the graph reads ([`Node::Named`]), each once, in the order they
    /// were first read.
    pub fn named_constants(&self) -> &[&'static NamedConstant] {
        &self.named
    }

    /// The tables the graph fetches from, in the order they were first fetched; a
    /// [`Node::Fetch`] names one by its index here. Each table appears once however many
    /// [`SharedTable`]s wrapped its `Arc`.
    pub fn tables(&self) -> &[Arc<Table>] {
        &self.tables
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

    /// The nodes the outputs depend on, in evaluation order (each computed value once: equal
    /// nodes are recorded once).
    pub fn live_nodes(&self) -> Vec<Node> {
        let live = self.live();
        self.nodes
            .iter()
            .zip(&live)
            .filter_map(|(n, &l)| l.then_some(*n))
            .collect()
    }

    /// How many live nodes perform the unary operation `op` (for example exponentials).
    pub fn count_unary(&self, op: Unary) -> usize {
        let live = self.live();
        self.nodes
            .iter()
            .zip(&live)
            .filter(|(n, &l)| l && matches!(n, Node::Unary(o, _) if *o == op))
            .count()
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

    /// How many distinct table fetches the outputs depend on: live [`Node::Fetch`] nodes with
    /// different (table, coordinates); the channels of one fetch count once.
    pub fn count_fetches(&self) -> usize {
        self.live_fetches(|table, _| (table, 0))
    }

    /// How many texture samples the WGSL of [`Graph::to_wgsl`] performs: distinct live
    /// fetches per texture, where a table of more than [`TEXTURE_CHANNELS`] channels is
    /// several textures. Equal to [`Graph::count_fetches`] when every table has at most four
    /// channels.
    pub fn count_texture_samples(&self) -> usize {
        self.live_fetches(|table, channel| (table, channel / TEXTURE_CHANNELS as u32))
    }

    /// The number of distinct (key, coordinates) of the live fetches.
    fn live_fetches(&self, key: impl Fn(u32, u32) -> (u32, u32)) -> usize {
        let live = self.live();
        let mut seen = HashSet::new();
        for (node, &l) in self.nodes.iter().zip(&live) {
            if let (
                true,
                Node::Fetch {
                    table,
                    coords,
                    channel,
                },
            ) = (l, *node)
            {
                seen.insert((key(table, channel), coords));
            }
        }
        seen.len()
    }

    /// Interprets the graph in `f32`, applying to each node the same `f32` operation the
    /// `f32` instantiation of the generic code applies, so the result is bit-identical to it
    /// (a table fetch calls [`Table::lookup_into`], as the `f32` [`Real::sample_table`] does).
    ///
    /// # Panics
    /// If `inputs.len()` differs from [`Graph::input_count`].
    pub fn eval_f32(&self, inputs: &[f32]) -> Vec<f32> {
        assert_eq!(
            inputs.len(),
            self.input_count(),
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
                Node::Named { constant, index } => {
                    value[i] = named_value(&self.named, constant, index)
                }
                Node::Global(k) => value[i] = self.globals[k as usize],
                Node::Result { .. } => unreachable!("the flat graph has no calls"),
                Node::Unary(op, a) => value[i] = apply_unary(op, v(a)),
                Node::Binary(op, a, c) => value[i] = apply_binary(op, v(a), v(c)),
                Node::Less(a, c) => truth[i] = Real::lt(v(a), v(c)),
                Node::LessEqual(a, c) => truth[i] = Real::le(v(a), v(c)),
                Node::And(a, c) => truth[i] = b(a) & b(c),
                Node::Or(a, c) => truth[i] = b(a) | b(c),
                Node::Not(a) => truth[i] = !b(a),
                Node::Select(m, t, f) => value[i] = <f32 as Real>::select(b(m), v(t), v(f)),
                Node::Fetch {
                    table,
                    coords,
                    channel,
                } => {
                    value[i] = self.fetch_f32(
                        table,
                        coords.map(|k| value.get(k as usize).copied()),
                        channel,
                    )
                }
            }
        }
        self.outputs.iter().map(|&o| value[o as usize]).collect()
    }

    /// Channel `channel` of table `table` at the coordinates `coords` (`None` beyond the
    /// table's axes).
    fn fetch_f32(&self, table: u32, coords: [Option<f32>; MAX_AXES], channel: u32) -> f32 {
        let t = &self.tables[table as usize];
        let (dims, nc) = (t.axes().len(), t.channels().len());
        let mut x = [0.0f32; MAX_AXES];
        for (slot, c) in x.iter_mut().zip(coords) {
            *slot = c.unwrap_or(0.0);
        }
        let mut out = [0.0f32; MAX_CHANNELS];
        // A fetch has one coordinate per axis; a NaN one is the axis' minimum, as in f32.
        t.interpolate_into(&x[..dims], &mut out[..nc]);
        out[channel as usize]
    }

    /// A flat debugging dump of the graph as one WGSL function (every call inlined, one `let`
    /// per node), which the trace tests validate with naga. Shader code to ship comes from
    /// `hairmath::shader` (feature `shader`): named functions, loops, baked uniforms, tables
    /// read with `textureLoad`. This dump prints the declarations of the structs its arguments use, then
    /// `fn name(arguments) -> T`, with the arguments of the signature (`x0: f32, ...` for
    /// [`trace`]) and `T` `vec3<f32>` for [`ResultType::Vec3`], else `f32` for one output and
    /// `array<f32, N>` for several. Only nodes the outputs depend on are emitted, one `let` per
    /// node, constants inline; inputs are read from the arguments by name (`wi.x`,
    /// `uniforms.eta`).
    ///
    /// A graph with table fetches starts with one texture binding per table (per group of
    /// [`TEXTURE_CHANNELS`] channels for wider tables), `@group(0) @binding(k)` in the order of
    /// [`Graph::tables`], each with a comment giving its size, axes and channels; then a
    /// `sampler` binding `lut_sampler` (bind a linear-filtering, clamp-to-edge sampler) and the
    /// helper `lut_coordinate`, the texel-centre transform `s = (u (n - 1) + 0.5) / n` of
    /// `u = clamp((x - min) / (max - min), 0, 1)`. A 1D table is a texture of height 1, a 3D
    /// table a `texture_3d`. Each fetch is one `textureSampleLevel(..., 0.0)` per texture,
    /// its channels read as components. (Hardware filtering computes its weights in low
    /// precision: the shader agrees with [`Graph::eval_f32`] to the filtering's precision, not
    /// bit for bit.)
    pub fn to_wgsl(&self, name: &str) -> String {
        let live = self.live();
        let (paths, _) = self.signature.input_paths();
        let mut out = String::new();
        self.texture_declarations(&mut out);
        let mut seen = Vec::new();
        for p in &self.signature.parameters {
            p.ty.struct_declarations(&mut seen, &mut out);
        }
        let params: Vec<String> = self
            .signature
            .parameters
            .iter()
            .filter(|p| p.constant.is_none())
            .map(|p| format!("{}: {}", p.name, p.ty.wgsl()))
            .collect();
        let ret = match (self.signature.result, self.outputs.len()) {
            (ResultType::Vec3, _) => "vec3<f32>".to_string(),
            (_, 1) => "f32".to_string(),
            (_, n) => format!("array<f32, {n}>"),
        };
        let _ = writeln!(out, "fn {name}({}) -> {ret} {{", params.join(", "));
        // The texture sample of each (table, coordinates, texture) already printed.
        let mut samples: HashMap<(u32, [u32; MAX_AXES], u32), usize> = HashMap::new();
        for (i, node) in self.nodes.iter().enumerate() {
            if !live[i]
                || matches!(
                    node,
                    Node::Input(_) | Node::Const(_) | Node::Named { .. } | Node::Global(_)
                )
            {
                continue;
            }
            if let Node::Fetch {
                table,
                coords,
                channel,
            } = *node
            {
                let texture = channel / TEXTURE_CHANNELS as u32;
                let sample = *samples.entry((table, coords, texture)).or_insert_with(|| {
                    let call = self.texture_sample(table, texture, coords, &paths);
                    let _ = writeln!(out, "    let s{i} = {call};");
                    i
                });
                let component = ["x", "y", "z", "w"][channel as usize % TEXTURE_CHANNELS];
                let _ = writeln!(out, "    let t{i} = s{sample}.{component};");
                continue;
            }
            let _ = writeln!(out, "    let t{i} = {};", self.expression(node, &paths));
        }
        let results: Vec<String> = self
            .outputs
            .iter()
            .map(|&o| self.operand(o, &paths))
            .collect();
        if results.len() == 1 && self.signature.result == ResultType::Scalars {
            let _ = writeln!(out, "    return {};", results[0]);
        } else {
            let _ = writeln!(out, "    return {ret}({});", results.join(", "));
        }
        out.push_str("}\n");
        out
    }

    /// The shader name of texture `texture` of table `table`: `lut{table}_{kind}`, with
    /// `_{texture}` appended for a table of more than four channels.
    fn texture_name(&self, table: u32, texture: u32) -> String {
        let t = &self.tables[table as usize];
        let kind: String = t
            .meta()
            .kind
            .chars()
            .map(|c| {
                if c.is_ascii_alphanumeric() {
                    c.to_ascii_lowercase()
                } else {
                    '_'
                }
            })
            .collect();
        let mut name = format!("lut{table}");
        if !kind.is_empty() {
            name = format!("{name}_{kind}");
        }
        if t.channels().len() > TEXTURE_CHANNELS {
            name = format!("{name}_{texture}");
        }
        name
    }

    /// The bindings of the tables' textures and of the sampler, and `lut_coordinate`.
    fn texture_declarations(&self, out: &mut String) {
        if self.tables.is_empty() {
            return;
        }
        let mut binding = 0;
        for (k, t) in self.tables.iter().enumerate() {
            let sizes: Vec<String> = t.axes().iter().map(|a| a.size().to_string()).collect();
            let axes: Vec<String> = t
                .axes()
                .iter()
                .zip(["x", "y", "z"])
                .map(|(a, c)| format!("{} in [{}, {}] along {c}", a.name(), a.min(), a.max()))
                .collect();
            let ty = if t.axes().len() == 3 {
                "texture_3d<f32>"
            } else {
                "texture_2d<f32>"
            };
            let channels = t.channels();
            for (texture, group) in channels.chunks(TEXTURE_CHANNELS).enumerate() {
                let name = self.texture_name(k as u32, texture as u32);
                let _ = writeln!(
                    out,
                    "// {name}: {} texels ({}); {} = {}",
                    sizes.join(" x "),
                    axes.join(", "),
                    ["x", "y", "z", "w"][..group.len()].join(", "),
                    group.join(", ")
                );
                let _ = writeln!(out, "@group(0) @binding({binding}) var {name}: {ty};");
                binding += 1;
            }
        }
        let _ = writeln!(
            out,
            "// Bind a sampler with linear filtering and clamp-to-edge addressing.\n\
             @group(0) @binding({binding}) var lut_sampler: sampler;\n\n\
             // The texel-centre texture coordinate of x on an axis of n samples from lo to hi\n\
             // (the first and last samples sit at lo and hi).\n\
             fn lut_coordinate(x: f32, lo: f32, hi: f32, n: f32) -> f32 {{\n    \
             let u = clamp((x - lo) / (hi - lo), 0.0, 1.0);\n    \
             return (u * (n - 1.0) + 0.5) / n;\n\
             }}\n"
        );
    }

    /// `textureSampleLevel(...)` of texture `texture` of table `table` at the coordinate
    /// nodes `coords`.
    fn texture_sample(
        &self,
        table: u32,
        texture: u32,
        coords: [u32; MAX_AXES],
        paths: &[String],
    ) -> String {
        let t = &self.tables[table as usize];
        let mut uv: Vec<String> = t
            .axes()
            .iter()
            .zip(coords)
            .map(|(a, c)| {
                format!(
                    "lut_coordinate({}, {}, {}, {})",
                    self.operand(c, paths),
                    wgsl_literal(a.min() as f32),
                    wgsl_literal(a.max() as f32),
                    wgsl_literal(a.size() as f32)
                )
            })
            .collect();
        if uv.len() == 1 {
            uv.push(wgsl_literal(0.5));
        }
        format!(
            "textureSampleLevel({}, lut_sampler, vec{}<f32>({}), 0.0)",
            self.texture_name(table, texture),
            uv.len(),
            uv.join(", ")
        )
    }

    fn operand(&self, id: u32, paths: &[String]) -> String {
        match self.nodes[id as usize] {
            Node::Input(k) => paths[k as usize].clone(),
            Node::Global(k) => wgsl_literal(self.globals[k as usize]),
            Node::Const(bits) => wgsl_literal(f32::from_bits(bits)),
            Node::Named { constant, index } => {
                wgsl_literal(named_value(&self.named, constant, index))
            }
            _ => format!("t{id}"),
        }
    }

    fn expression(&self, node: &Node, paths: &[String]) -> String {
        let o = |k: u32| self.operand(k, paths);
        match *node {
            Node::Input(_) | Node::Const(_) | Node::Named { .. } | Node::Global(_) => {
                unreachable!("inlined")
            }
            Node::Result { .. } => unreachable!("the flat graph has no calls"),
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
            Node::Fetch { .. } => unreachable!("printed as texture samples"),
        }
    }
}

fn operands(node: &Node) -> Vec<u32> {
    node.operands()
}

impl Node {
    /// The indices of the nodes this node reads, in operand order (a fetch's coordinates, the
    /// other nodes' operands left to right; none for inputs, constants, globals and
    /// [`Node::Result`], whose call site's arguments are the operands of the call).
    pub fn operands(&self) -> Vec<u32> {
        let mut out = Vec::new();
        map_operands(*self, |k| {
            out.push(k);
            k
        });
        out
    }
}

/// `node` with each operand `k` replaced by `f(k)`, called in operand order (a fetch's
/// coordinates, the other nodes' operands left to right; [`Node::Result`] has none: its call
/// site's arguments are the operands of the call).
pub(super) fn map_operands(node: Node, mut f: impl FnMut(u32) -> u32) -> Node {
    match node {
        Node::Input(_)
        | Node::Const(_)
        | Node::Named { .. }
        | Node::Global(_)
        | Node::Result { .. } => node,
        Node::Unary(op, a) => Node::Unary(op, f(a)),
        Node::Not(a) => Node::Not(f(a)),
        Node::Binary(op, a, b) => {
            let a = f(a);
            Node::Binary(op, a, f(b))
        }
        Node::Less(a, b) => {
            let a = f(a);
            Node::Less(a, f(b))
        }
        Node::LessEqual(a, b) => {
            let a = f(a);
            Node::LessEqual(a, f(b))
        }
        Node::And(a, b) => {
            let a = f(a);
            Node::And(a, f(b))
        }
        Node::Or(a, b) => {
            let a = f(a);
            Node::Or(a, f(b))
        }
        Node::Select(m, t, e) => {
            let m = f(m);
            let t = f(t);
            Node::Select(m, t, f(e))
        }
        Node::Fetch {
            table,
            coords,
            channel,
        } => Node::Fetch {
            table,
            coords: coords.map(|c| if c == NO_COORDINATE { c } else { f(c) }),
            channel,
        },
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
                self.binary($op, rhs)
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
        self.binary(Binary::Div, rhs)
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
        TracedMask::from_record(record(
            Node::And(self.node, rhs.node),
            &[self.trace, rhs.trace],
        ))
    }
}

impl BitOr for TracedMask {
    type Output = TracedMask;
    fn bitor(self, rhs: TracedMask) -> TracedMask {
        TracedMask::from_record(record(
            Node::Or(self.node, rhs.node),
            &[self.trace, rhs.trace],
        ))
    }
}

impl Not for TracedMask {
    type Output = TracedMask;
    fn not(self) -> TracedMask {
        TracedMask::from_record(record(Node::Not(self.node), &[self.trace]))
    }
}

impl Traced {
    fn from_record((node, trace): (u32, u32)) -> Traced {
        Traced { node, trace }
    }
    fn unary(self, op: Unary) -> Traced {
        Traced::from_record(record(Node::Unary(op, self.node), &[self.trace]))
    }
    fn binary(self, op: Binary, rhs: Traced) -> Traced {
        Traced::from_record(record(
            Node::Binary(op, self.node, rhs.node),
            &[self.trace, rhs.trace],
        ))
    }
}

impl TracedMask {
    fn from_record((node, trace): (u32, u32)) -> TracedMask {
        TracedMask { node, trace }
    }
}

impl Real for Traced {
    type Mask = TracedMask;
    const DOUBLE: bool = false;

    fn c(value: f64) -> Self {
        Traced::from_record(record(Node::Const((value as f32).to_bits()), &[]))
    }
    fn named(constant: &'static NamedConstant, index: usize) -> Self {
        assert!(
            index < constant.values.len(),
            "{} has {} values, not {}",
            constant.name,
            constant.values.len(),
            index + 1
        );
        let constant = with_recorder(|rec| rec.add_named(constant));
        let index = index as u32;
        Traced::from_record(record(Node::Named { constant, index }, &[]))
    }
    fn label(self, name: &'static str) -> Self {
        with_recorder(|rec| rec.label(self.node, self.trace, name));
        self
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
        TracedMask::from_record(record(
            Node::Less(self.node, other.node),
            &[self.trace, other.trace],
        ))
    }
    fn le(self, other: Self) -> TracedMask {
        TracedMask::from_record(record(
            Node::LessEqual(self.node, other.node),
            &[self.trace, other.trace],
        ))
    }
    /// Always `false`: shader code evaluates both arms and selects.
    fn every_lane(_mask: TracedMask) -> bool {
        false
    }
    fn select(mask: TracedMask, on_true: Self, on_false: Self) -> Self {
        Traced::from_record(record(
            Node::Select(mask.node, on_true.node, on_false.node),
            &[mask.trace, on_true.trace, on_false.trace],
        ))
    }
    fn sample_table<const D: usize, const C: usize>(
        table: &SharedTable<D, C>,
        coords: [Self; D],
    ) -> [Self; C] {
        let id = register_table(table.arc());
        let mut nodes = [NO_COORDINATE; MAX_AXES];
        let traces = coords.map(|x| x.trace);
        for (d, x) in coords.iter().enumerate() {
            nodes[d] = x.node;
        }
        core::array::from_fn(|channel| {
            let node = Node::Fetch {
                table: id,
                coords: nodes,
                channel: channel as u32,
            };
            Traced::from_record(record(node, &traces))
        })
    }

    fn call<const N: usize, const M: usize>(
        function: &'static ShaderFunction,
        args: [Self; N],
        body: impl FnOnce([Self; N]) -> [Self; M],
    ) -> [Self; M] {
        assert_eq!(
            function.input_count(),
            N,
            "shader function {} declares parameters of {} scalars but is called with {N}",
            function.name,
            function.input_count()
        );
        assert!(
            function.result.width().is_none_or(|w| w == M),
            "shader function {} declares a result of type {:?} but returns {M} scalars",
            function.name,
            function.result
        );
        let explicit = localize_in_top(&args);
        let outputs = record_call(
            FunctionKind::Function(function),
            N,
            |inputs| body(core::array::from_fn(|k| inputs[k])).to_vec(),
            |function, captures| CallSite {
                function,
                args: explicit.into_iter().chain(captures).collect(),
                kind: CallKind::Call,
            },
        );
        core::array::from_fn(|k| outputs[k])
    }

    fn fold<const S: usize, const E: usize>(
        info: &'static ShaderLoop,
        elements: &[[Self; E]],
        init: [Self; S],
        body: impl Fn([Self; S], [Self; E]) -> [Self; S],
    ) -> [Self; S] {
        assert!(
            info.fields.len() == E && info.state_width() == S,
            "loop {} names {} fields and {} state scalars but is called with {E} and {S}",
            info.name,
            info.fields.len(),
            info.state_width()
        );
        if elements.is_empty() {
            return init;
        }
        let values: Vec<Vec<f32>> = elements
            .iter()
            .map(|e| {
                e.iter()
                    .map(|&x| {
                        constant_value(x).unwrap_or_else(|| {
                            panic!(
                                "the elements of the traced loop {} must be constants",
                                info.name
                            )
                        })
                    })
                    .collect()
            })
            .collect();
        let array = with_recorder(|rec| rec.add_array(info, values));
        let init_nodes = localize_in_top(&init);
        let outputs = record_call(
            FunctionKind::LoopBody(info),
            S + E,
            |inputs| {
                body(
                    core::array::from_fn(|k| inputs[k]),
                    core::array::from_fn(|k| inputs[S + k]),
                )
                .to_vec()
            },
            |function, captures| CallSite {
                function,
                args: init_nodes.into_iter().chain(captures).collect(),
                kind: CallKind::Loop { array },
            },
        );
        core::array::from_fn(|k| outputs[k])
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
    fn a_panicking_trace_leaves_the_thread_able_to_trace() {
        let caught = std::panic::catch_unwind(|| {
            trace(1, |a| {
                let _ = a[0] * a[0];
                panic!("inside the traced closure")
            })
        });
        assert!(caught.is_err());
        let g = trace(1, |a| vec![a[0] + a[0]]);
        assert_eq!(g.count_binary(Binary::Add), 1);
        assert_eq!(g.eval_f32(&[1.5]), vec![3.0]);
    }

    #[test]
    fn traced_values_outside_their_trace_panic_with_a_message() {
        let mut escaped = None;
        let _ = trace(1, |a| {
            escaped = Some(a[0]);
            vec![a[0]]
        });
        let x = escaped.expect("captured");
        let text = |payload: Box<dyn std::any::Any + Send>| {
            payload
                .downcast_ref::<String>()
                .cloned()
                .or_else(|| payload.downcast_ref::<&str>().map(|s| s.to_string()))
                .unwrap_or_default()
        };
        let outside = text(std::panic::catch_unwind(move || x + x).unwrap_err());
        assert!(
            outside.contains("outside hairmath::real::trace"),
            "{outside}"
        );
        let inside = std::panic::catch_unwind(move || trace(1, |a| vec![a[0] + x]));
        let inside = text(inside.unwrap_err());
        assert!(inside.contains("another trace"), "{inside}");
        // The failed trace ended cleanly too.
        assert_eq!(trace(0, |_| vec![Traced::c(2.0)]).eval_f32(&[]), vec![2.0]);
    }

    #[test]
    fn named_arguments_print_as_struct_fields_and_vectors() {
        let uniforms = ArgType::Struct(StructType {
            name: "Material".into(),
            fields: vec![
                ("eta".into(), ArgType::Scalar),
                ("sigma_a".into(), ArgType::Vec3),
            ],
        });
        let signature = Signature {
            parameters: vec![
                Parameter::argument("m", uniforms),
                Parameter::argument("wi", ArgType::Vec3),
            ],
            result: ResultType::Vec3,
        };
        assert_eq!(signature.input_count(), 7);
        let g = trace_with(signature, |x| vec![x[0] * x[4], x[2], x[5] + x[6]]);
        let wgsl = g.to_wgsl("shade");
        assert!(
            wgsl.starts_with("struct Material {\n    eta: f32,\n    sigma_a: vec3<f32>,\n}"),
            "{wgsl}"
        );
        assert!(
            wgsl.contains("fn shade(m: Material, wi: vec3<f32>) -> vec3<f32> {"),
            "{wgsl}"
        );
        assert!(
            wgsl.contains("m.eta * wi.x") && wgsl.contains("m.sigma_a.y"),
            "{wgsl}"
        );
        assert!(wgsl.contains("return vec3<f32>("), "{wgsl}");
        assert_eq!(
            g.eval_f32(&[2.0, 1.0, 2.0, 3.0, 4.0, 5.0, 6.0]),
            vec![8.0, 2.0, 11.0]
        );
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
