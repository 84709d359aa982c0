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

use super::Real;
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
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Parameter {
    /// The argument's name in shader code.
    pub name: String,
    /// Its type.
    pub ty: ArgType,
}

/// What a traced function returns.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ResultType {
    /// `f32` for one output, `array<f32, N>` for N outputs.
    Scalars,
    /// `vec3<f32>` of exactly three outputs (an RGB value, a direction).
    Vec3,
}

/// The arguments and result of a traced function. The closure of [`trace_with`] receives one
/// [`Traced`] input per scalar: the arguments in order, a vector as its x, y, z, a struct as
/// its fields in order (recursively).
#[derive(Clone, Debug, PartialEq, Eq)]
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
                .map(|i| Parameter {
                    name: format!("x{i}"),
                    ty: ArgType::Scalar,
                })
                .collect(),
            result: ResultType::Scalars,
        }
    }

    /// Number of scalar inputs of the traced closure.
    pub fn input_count(&self) -> usize {
        self.parameters.iter().map(|p| p.ty.width()).sum()
    }

    /// The shader expression of each scalar input, in input order (`wi.x`, `uniforms.eta`).
    fn input_paths(&self) -> Vec<String> {
        let mut out = Vec::with_capacity(self.input_count());
        for p in &self.parameters {
            p.ty.scalar_paths(&p.name, &mut out);
        }
        out
    }
}

/// A recorded computation: nodes in evaluation order, the signature of the traced function,
/// and the outputs.
#[derive(Clone, Debug, PartialEq)]
pub struct Graph {
    nodes: Vec<Node>,
    signature: Signature,
    outputs: Vec<u32>,
    tables: Vec<Arc<Table>>,
}

struct Recorder {
    /// Distinguishes the values of this trace from those of earlier ones.
    trace: u32,
    nodes: Vec<Node>,
    index: HashMap<Node, u32>,
    /// The tables fetched from, each once (by pointer).
    tables: Vec<Arc<Table>>,
}

/// The index of `table` among the tables of the running trace, added if new, and the trace.
///
/// # Panics
/// If no trace is running.
fn register_table(table: &Arc<Table>) -> (u32, u32) {
    RECORDER.with(|r| {
        let mut guard = r.borrow_mut();
        let rec = guard
            .as_mut()
            .expect("a table was fetched with Traced coordinates outside hairmath::real::trace");
        let id = match rec.tables.iter().position(|t| Arc::ptr_eq(t, table)) {
            Some(id) => id,
            None => {
                rec.tables.push(Arc::clone(table));
                rec.tables.len() - 1
            }
        };
        (id as u32, rec.trace)
    })
}

thread_local! {
    static RECORDER: RefCell<Option<Recorder>> = const { RefCell::new(None) };
    static TRACES: core::cell::Cell<u32> = const { core::cell::Cell::new(0) };
}

/// Records `node`, whose operands are values of the traces `operands`, in the running trace;
/// returns its index.
///
/// # Panics
/// If no trace is running, or an operand comes from another trace.
fn record(node: Node, operands: &[u32]) -> (u32, u32) {
    RECORDER.with(|r| {
        let mut guard = r.borrow_mut();
        let rec = guard.as_mut().expect(
            "a Traced value was used outside hairmath::real::trace (traced values live only \
             inside the closure of the trace that made them)",
        );
        assert!(
            operands.iter().all(|&t| t == rec.trace),
            "a Traced value from another trace was used (traced values live only inside the \
             closure of the trace that made them)"
        );
        if let Some(&id) = rec.index.get(&node) {
            return (id, rec.trace);
        }
        let id = rec.nodes.len() as u32;
        rec.nodes.push(node);
        rec.index.insert(node, id);
        (id, rec.trace)
    })
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

/// Traces `f` called with one symbolic input per scalar of `signature` and returns the
/// recorded graph. If `f` panics, the trace is discarded and the panic continues.
///
/// # Panics
/// If called while another trace is running on the same thread (traces do not nest), or if
/// the result type is [`ResultType::Vec3`] and `f` does not return exactly three values.
pub fn trace_with(signature: Signature, f: impl FnOnce(&[Traced]) -> Vec<Traced>) -> Graph {
    let trace = TRACES.with(|t| {
        let id = t.get().wrapping_add(1);
        t.set(id);
        id
    });
    RECORDER.with(|r| {
        let mut guard = r.borrow_mut();
        assert!(guard.is_none(), "hairmath::real::trace does not nest");
        *guard = Some(Recorder {
            trace,
            nodes: Vec::new(),
            index: HashMap::new(),
            tables: Vec::new(),
        });
    });
    let session = Session;
    let args: Vec<Traced> = (0..signature.input_count())
        .map(|i| Traced::from_record(record(Node::Input(i as u32), &[])))
        .collect();
    let outputs = f(&args);
    let rec = RECORDER
        .with(|r| r.borrow_mut().take())
        .expect("the recorder lives until the session ends");
    drop(session);
    assert!(
        signature.result != ResultType::Vec3 || outputs.len() == 3,
        "a vec3 result needs exactly three outputs, not {}",
        outputs.len()
    );
    assert!(
        outputs.iter().all(|t| t.trace == trace),
        "a traced function returned a value of another trace"
    );
    Graph {
        nodes: rec.nodes,
        signature,
        outputs: outputs.iter().map(|t| t.node).collect(),
        tables: rec.tables,
    }
}

impl Graph {
    /// The recorded nodes in evaluation order (live or not; see [`Graph::count_binary`] for
    /// counts of what the outputs depend on).
    pub fn nodes(&self) -> &[Node] {
        &self.nodes
    }

    /// The signature of the traced function.
    pub fn signature(&self) -> &Signature {
        &self.signature
    }

    /// Number of scalar inputs of the traced function.
    pub fn input_count(&self) -> usize {
        self.signature.input_count()
    }

    /// Number of outputs of the traced function.
    pub fn output_count(&self) -> usize {
        self.outputs.len()
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
        t.lookup_into(&x[..dims], &mut out[..nc])
            .unwrap_or_else(|_| unreachable!("a fetch has one coordinate per axis"));
        out[channel as usize]
    }

    /// Prints the graph as WGSL: the declarations of the structs its arguments use, then
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
        let paths = self.signature.input_paths();
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
            .map(|p| format!("{}: {}", p.name, p.ty.wgsl()))
            .collect();
        let ret = match (self.signature.result, self.outputs.len()) {
            (ResultType::Vec3, _) => "vec3<f32>".to_string(),
            (ResultType::Scalars, 1) => "f32".to_string(),
            (ResultType::Scalars, n) => format!("array<f32, {n}>"),
        };
        let _ = writeln!(out, "fn {name}({}) -> {ret} {{", params.join(", "));
        // The texture sample of each (table, coordinates, texture) already printed.
        let mut samples: HashMap<(u32, [u32; MAX_AXES], u32), usize> = HashMap::new();
        for (i, node) in self.nodes.iter().enumerate() {
            if !live[i] || matches!(node, Node::Input(_) | Node::Const(_)) {
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
            Node::Const(bits) => wgsl_literal(f32::from_bits(bits)),
            _ => format!("t{id}"),
        }
    }

    fn expression(&self, node: &Node, paths: &[String]) -> String {
        let o = |k: u32| self.operand(k, paths);
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
            Node::Fetch { .. } => unreachable!("printed as texture samples"),
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
        Node::Fetch { coords, .. } => coords.into_iter().filter(|&c| c != NO_COORDINATE).collect(),
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
        let (id, trace) = register_table(table.arc());
        let mut nodes = [NO_COORDINATE; MAX_AXES];
        let mut traces = [trace; MAX_AXES];
        for (d, x) in coords.iter().enumerate() {
            (nodes[d], traces[d]) = (x.node, x.trace);
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
                Parameter {
                    name: "m".into(),
                    ty: uniforms,
                },
                Parameter {
                    name: "wi".into(),
                    ty: ArgType::Vec3,
                },
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
