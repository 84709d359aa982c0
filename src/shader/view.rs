//! The structured graph as the lowering reads it.
//!
//! TEMPORARY: until the tracer keeps the structure of the Rust code (named functions with
//! calls, loops over constant arrays, baked constants), this module mirrors those types and
//! presents today's flat [`Graph`] as a structured graph with one body and no calls. The
//! lowering (`super::body`) is written against exactly these names, so that when the tracer
//! provides them this module shrinks to re-exports.

#![allow(dead_code)] // Until the tracer provides every variant.

use crate::lut::{Table, MAX_AXES};
use crate::real::{Binary, Graph, Node as FlatNode, Parameter, ResultType, Signature, Unary};
use std::sync::Arc;

/// The shape of a parameter of a [`ShaderFunction`].
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Shape {
    Scalar,
    Vec3,
}

/// A generic function marked to become a named shader function.
#[derive(Debug)]
pub(crate) struct ShaderFunction {
    pub name: &'static str,
    pub source: &'static str,
    pub equation: &'static str,
    pub parameters: &'static [(&'static str, Shape)],
    pub result: ResultType,
}

/// A fixed-count loop over a constant array, marked to stay a loop in shader code.
#[derive(Debug)]
pub(crate) struct ShaderLoop {
    pub name: &'static str,
    pub array: &'static str,
    pub fields: &'static [&'static str],
    pub state: &'static [&'static str],
    pub source: &'static str,
    pub equation: &'static str,
}

/// One node of a body (the flat node kinds plus baked constants and call results).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub(crate) enum Node {
    Input(u32),
    Const(u32),
    Unary(Unary, u32),
    Binary(Binary, u32, u32),
    Less(u32, u32),
    LessEqual(u32, u32),
    And(u32, u32),
    Or(u32, u32),
    Not(u32),
    Select(u32, u32, u32),
    Fetch {
        table: u32,
        coords: [u32; MAX_AXES],
        channel: u32,
    },
    Global(u32),
    Result {
        site: u32,
        output: u32,
    },
}

/// The statements of one shader function.
#[derive(Clone, Debug, Default)]
pub(crate) struct Body {
    pub nodes: Vec<Node>,
    pub calls: Vec<CallSite>,
    pub outputs: Vec<u32>,
}

/// One call of a [`Function`] from a [`Body`].
#[derive(Clone, Debug)]
pub(crate) struct CallSite {
    pub function: u32,
    pub args: Vec<u32>,
    pub kind: CallKind,
}

/// How a [`CallSite`] runs its callee.
#[derive(Clone, Copy, Debug)]
pub(crate) enum CallKind {
    Call,
    Loop { array: u32 },
}

/// What a [`Function`] was traced from.
#[derive(Clone, Copy, Debug)]
pub(crate) enum FunctionKind {
    Function(&'static ShaderFunction),
    LoopBody(&'static ShaderLoop),
}

/// A shader function of the graph.
#[derive(Clone, Debug)]
pub(crate) struct Function {
    pub name: String,
    pub kind: FunctionKind,
    pub body: Body,
    pub inputs: u32,
    pub captures: u32,
}

/// The elements of a loop's constant array.
#[derive(Clone, Debug)]
pub(crate) struct ConstArray {
    pub info: &'static ShaderLoop,
    pub elements: Vec<Vec<f32>>,
}

/// A graph seen as structured.
pub(crate) struct View<'g> {
    graph: &'g Graph,
    body: Body,
    functions: Vec<Function>,
    arrays: Vec<ConstArray>,
}

impl<'g> View<'g> {
    /// The view of `graph`.
    pub fn new(graph: &'g Graph) -> Self {
        let nodes = graph.nodes().iter().map(|&n| convert(n)).collect();
        View {
            graph,
            body: Body {
                nodes,
                calls: Vec::new(),
                outputs: flat_outputs(graph),
            },
            functions: Vec::new(),
            arrays: Vec::new(),
        }
    }

    pub fn body(&self) -> &Body {
        &self.body
    }
    pub fn functions(&self) -> &[Function] {
        &self.functions
    }
    pub fn arrays(&self) -> &[ConstArray] {
        &self.arrays
    }
    pub fn signature(&self) -> &Signature {
        self.graph.signature()
    }
    pub fn tables(&self) -> &[Arc<Table>] {
        self.graph.tables()
    }
}

/// `Some(values)` when the parameter is a module-scope constant rather than an argument.
pub(crate) fn constant_values(_parameter: &Parameter) -> Option<&[f32]> {
    None
}

fn convert(node: FlatNode) -> Node {
    match node {
        FlatNode::Input(k) => Node::Input(k),
        FlatNode::Const(b) => Node::Const(b),
        FlatNode::Unary(op, a) => Node::Unary(op, a),
        FlatNode::Binary(op, a, b) => Node::Binary(op, a, b),
        FlatNode::Less(a, b) => Node::Less(a, b),
        FlatNode::LessEqual(a, b) => Node::LessEqual(a, b),
        FlatNode::And(a, b) => Node::And(a, b),
        FlatNode::Or(a, b) => Node::Or(a, b),
        FlatNode::Not(a) => Node::Not(a),
        FlatNode::Select(m, t, f) => Node::Select(m, t, f),
        FlatNode::Fetch {
            table,
            coords,
            channel,
        } => Node::Fetch {
            table,
            coords,
            channel,
        },
    }
}

/// The output nodes of today's graph, which has no accessor for them: read from its `Debug`
/// text (`outputs: [..]`).
fn flat_outputs(graph: &Graph) -> Vec<u32> {
    let text = format!("{graph:?}");
    let start = text
        .rfind("outputs: [")
        .expect("Graph's Debug names its outputs")
        + 10;
    let end = start + text[start..].find(']').expect("closing bracket");
    text[start..end]
        .split(',')
        .filter_map(|s| s.trim().parse().ok())
        .collect()
}
