//! Lowering the bodies of a traced graph to naga functions: the graph's functions (callees
//! first), their calls and loops, and the top-level function.

use super::builder::{Component, FnBuilder};
use super::captures::{self, capture_shapes};
use super::tables::{self, TableHelper};
use super::types;
use super::vectorize;
use super::{constant_values, ShaderError, TextureBinding};
use crate::lut::Table;
use crate::lut::MAX_AXES;
use crate::real::{
    ArgType, Binary, Body, CallKind, CallSite, ConstArray, FunctionKind, Graph, NamedConstant,
    Node, Parameter, ResultType, Shape, Unary,
};
use naga::{
    BinaryOperator, Constant, Expression, Function, Handle, MathFunction, Module, Span, Statement,
    Type, UnaryOperator,
};
use std::collections::{HashMap, HashSet};
use std::sync::Arc;

/// How the callee of a call returns its outputs.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum ResultKind {
    /// `f32`: one output.
    Scalar,
    /// `array<f32, N>`.
    Array(u32),
    /// `vec3<f32>`.
    Vec3,
    /// A struct of `f32` and `vec3<f32>` fields ([`ResultType::Fields`]).
    Struct {
        ty: Handle<Type>,
        fields: &'static [(&'static str, Shape)],
    },
}

impl ResultKind {
    /// The kind of a result of `outputs` values declared as `result` by the function `name`
    /// (a struct result is named after it: `fibre_path` returns a `FibrePath`).
    pub fn of(result: ResultType, outputs: usize, name: &str, module: &mut Module) -> Self {
        match (result, outputs) {
            (ResultType::Vec3, _) => ResultKind::Vec3,
            (ResultType::Fields(fields), _) => {
                let members: Vec<(String, ArgType)> = fields
                    .iter()
                    .map(|&(field, shape)| {
                        let ty = match shape {
                            Shape::Scalar => ArgType::Scalar,
                            Shape::Vec3 => ArgType::Vec3,
                        };
                        (field.to_string(), ty)
                    })
                    .collect();
                let ty = types::arg_type(
                    module,
                    &ArgType::Struct(crate::real::StructType {
                        name: camel_case(name),
                        fields: members,
                    }),
                );
                ResultKind::Struct { ty, fields }
            }
            (ResultType::Scalars, 1) => ResultKind::Scalar,
            (ResultType::Scalars, n) => ResultKind::Array(n as u32),
        }
    }

    /// The naga type.
    pub fn ty(self, module: &mut Module) -> Handle<Type> {
        match self {
            ResultKind::Scalar => types::f32(module),
            ResultKind::Vec3 => types::vec3(module),
            ResultKind::Array(n) => {
                let f = types::f32(module);
                types::array(module, f, Some(n))
            }
            ResultKind::Struct { ty, .. } => ty,
        }
    }

    /// Where scalar output `k` is in a value of this kind: the access indices, and whether
    /// the last one is a `vec3` component. `None` beyond the outputs.
    pub fn output_path(self, k: u32) -> Option<(Vec<u32>, bool)> {
        match self {
            ResultKind::Scalar => (k == 0).then(|| (vec![], false)),
            ResultKind::Array(n) => (k < n).then(|| (vec![k], false)),
            ResultKind::Vec3 => (k < 3).then(|| (vec![k], true)),
            ResultKind::Struct { fields, .. } => {
                let (field, shape, component) = locate(fields.iter().map(|&(_, s)| s), k)?;
                Some(match shape {
                    Shape::Scalar => (vec![field as u32], false),
                    Shape::Vec3 => (vec![field as u32, component], true),
                })
            }
        }
    }
}

/// Where scalar `k` of values of the shapes `shapes` (flattened in order, a `vec3` as three)
/// is: the value's index, its shape and the component within it (0 for a scalar).
fn locate(shapes: impl IntoIterator<Item = Shape>, k: u32) -> Option<(usize, Shape, u32)> {
    let mut first = 0;
    for (index, shape) in shapes.into_iter().enumerate() {
        let width = shape.width() as u32;
        if k < first + width {
            return Some((index, shape, k - first));
        }
        first += width;
    }
    None
}

/// Scalar output `k` of `value`, a result of kind `kind` (see [`ResultKind::output_path`]).
pub(super) fn read_output(
    b: &mut FnBuilder,
    value: Handle<Expression>,
    kind: ResultKind,
    k: u32,
) -> Option<Handle<Expression>> {
    let (path, _) = kind.output_path(k)?;
    Some(path.into_iter().fold(value, |base, index| {
        b.expr(Expression::AccessIndex { base, index })
    }))
}

/// Where a body's scalar parameter is read from: a value, or a component of one (a vector
/// component or a struct field, possibly nested).
#[derive(Clone, Debug)]
pub(super) enum Source {
    /// The expression itself (an `f32` argument).
    Value(Handle<Expression>),
    /// `base.path[0].path[1]...`; `vector` when the last step is a `vec3` component.
    Component {
        base: Handle<Expression>,
        path: Vec<u32>,
        vector: bool,
    },
    /// A component of a module-scope constant (read through `Expression::Constant`).
    Constant {
        constant: Handle<Constant>,
        path: Vec<u32>,
        vector: bool,
    },
}

/// A call site with its callee and array resolved to the module's.
type CallIdentity<'b> = (
    Option<Handle<Function>>,
    &'b [u32],
    Option<Handle<Constant>>,
);

/// A lowered graph function.
#[derive(Clone, Copy, Debug)]
struct Lowered {
    handle: Handle<Function>,
    result: ResultKind,
}

/// The naga constant of a loop's array and how to read an element.
#[derive(Clone, Copy)]
pub(super) struct ArrayConstant {
    /// The constant `array<Element, K>`.
    pub constant: Handle<Constant>,
    /// K.
    pub count: u32,
}

/// What a body's nodes and call sites are used for.
struct Liveness {
    nodes: Vec<bool>,
    sites: Vec<bool>,
}

fn liveness(body: &Body) -> Liveness {
    let mut nodes = vec![false; body.nodes.len()];
    let mut sites = vec![false; body.calls.len()];
    for &o in &body.outputs {
        nodes[o as usize] = true;
    }
    for i in (0..body.nodes.len()).rev() {
        if !nodes[i] {
            continue;
        }
        if let Node::Result { site, .. } = body.nodes[i] {
            if !sites[site as usize] {
                sites[site as usize] = true;
                for &a in &body.calls[site as usize].args {
                    nodes[a as usize] = true;
                }
            }
        }
        for k in operands(&body.nodes[i]) {
            nodes[k as usize] = true;
        }
    }
    Liveness { nodes, sites }
}

/// The operands of a node (a call result's are its site's arguments, handled apart).
fn operands(node: &Node) -> Vec<u32> {
    match *node {
        Node::Input(_)
        | Node::Const(_)
        | Node::Named { .. }
        | Node::Global(_)
        | Node::Result { .. } => vec![],
        Node::Unary(_, a) | Node::Not(a) => vec![a],
        Node::Binary(_, a, b)
        | Node::Less(a, b)
        | Node::LessEqual(a, b)
        | Node::And(a, b)
        | Node::Or(a, b) => vec![a, b],
        Node::Select(m, t, f) => vec![m, t, f],
        Node::Fetch { coords, .. } => coords
            .into_iter()
            .filter(|&c| c != crate::real::NO_COORDINATE)
            .collect(),
    }
}

/// A top-level function of the module.
#[derive(Clone, Debug)]
pub(super) struct Top {
    /// Its name.
    pub name: String,
    /// The naga function.
    pub handle: Handle<Function>,
    /// Its arguments (the signature's parameters that are not constants) and result.
    pub signature: crate::real::Signature,
    /// How it returns its outputs.
    pub result: ResultKind,
}

/// What the graphs lowered into one module share: the module, and the tables, arrays,
/// constants and functions already in it.
#[derive(Default)]
pub(super) struct Shared {
    pub module: Module,
    /// The tables (one per `Arc`) and their helpers.
    pub tables: Vec<(Arc<Table>, TableHelper)>,
    pub bindings: Vec<TextureBinding>,
    arrays: Vec<(ConstArray, ArrayConstant)>,
    /// Constant parameters by name: type, values, the constant and its scalars' sources.
    constants: Vec<(Parameter, Handle<Constant>, Vec<Source>)>,
    /// Named constants ([`Node::Named`]) by name, with their module constants.
    named: Vec<(&'static NamedConstant, Handle<Constant>)>,
    /// Lowered functions by identity (name, kind and body with its references resolved).
    functions: HashMap<String, Lowered>,
    /// Every function name in the module.
    pub names: HashSet<String>,
    pub tops: Vec<Top>,
    /// (shader function name, comment lines) in module order.
    pub comments: Vec<(String, Vec<String>)>,
}

impl Shared {
    /// `base`, or `base_2`, `base_3`, ... if taken; recorded as taken.
    fn unique_name(&mut self, base: &str) -> String {
        let mut name = base.to_string();
        let mut n = 2;
        while self.names.contains(&name) {
            name = format!("{base}_{n}");
            n += 1;
        }
        self.names.insert(name.clone());
        name
    }
}

/// The lowering of one graph into the shared module.
pub(super) struct Lowering<'a> {
    shared: &'a mut Shared,
    view: &'a Graph,
    /// Per table of the graph, its helper in the module.
    tables: Vec<TableHelper>,
    /// Per array of the graph, its constant in the module.
    arrays: Vec<ArrayConstant>,
    /// Per function of the graph, its naga function.
    functions: Vec<Option<Lowered>>,
    /// Per [`Node::Global`] scalar, where it is read.
    globals: Vec<Source>,
    /// Per named constant of the graph, its constant in the module.
    named: Vec<Handle<Constant>>,
    /// Per function, names for its captured parameters (from a call site's arguments).
    capture_names: Vec<Vec<String>>,
    /// Per function, per captured parameter: whether a `vec3<f32>` of three starts there
    /// ([`captures::vector_captures`]).
    capture_vectors: Vec<Vec<bool>>,
    live: Vec<Liveness>,
    top_live: Liveness,
    reachable: Vec<bool>,
}

impl<'a> Lowering<'a> {
    /// Starts the lowering of `view` into `shared`: its tables are found or declared.
    pub fn new(shared: &'a mut Shared, view: &'a Graph) -> Self {
        let live: Vec<Liveness> = view.functions().iter().map(|f| liveness(&f.body)).collect();
        let top_live = liveness(view.body());
        let tables = view
            .tables()
            .iter()
            .map(|t| {
                if let Some((_, helper)) = shared.tables.iter().find(|(u, _)| Arc::ptr_eq(u, t)) {
                    return helper.clone();
                }
                let k = shared.tables.len();
                let helper = tables::declare_table(shared, k, t);
                shared.tables.push((Arc::clone(t), helper.clone()));
                helper
            })
            .collect();
        let mut lowering = Lowering {
            shared,
            view,
            tables,
            arrays: Vec::new(),
            functions: vec![None; view.functions().len()],
            globals: Vec::new(),
            named: Vec::new(),
            capture_names: vec![Vec::new(); view.functions().len()],
            capture_vectors: Vec::new(),
            live,
            top_live,
            reachable: vec![false; view.functions().len()],
        };
        lowering.name_captures();
        let sites: Vec<Vec<bool>> = lowering.live.iter().map(|l| l.sites.clone()).collect();
        lowering.capture_vectors =
            captures::vector_captures(view, &lowering.top_live.sites, &sites, &lowering.reachable);
        lowering
    }

    /// Marks the functions reachable from the top-level body's live calls and names their
    /// captured parameters after the first call site's arguments where they have a name (a
    /// parameter's, a constant's, a struct result's field or a label's,
    /// [`crate::real::Real::label`]).
    fn name_captures(&mut self) {
        let view = self.view;
        let top_names = top_scalar_names(view);
        self.hint_sites(view.body(), &self.top_live.sites.clone(), &top_names);
        for f in (0..view.functions().len()).rev() {
            if !self.reachable[f] {
                continue;
            }
            let function = &view.functions()[f];
            let mut names = explicit_names(function);
            names.extend(self.capture_names[f].iter().cloned());
            let sites = self.live[f].sites.clone();
            self.hint_sites(&function.body, &sites, &names);
        }
    }

    /// For each live site of `body` (whose inputs are named `input_names`): the callee is
    /// reachable, and its captures get names if they have none yet.
    fn hint_sites(&mut self, body: &Body, live_sites: &[bool], input_names: &[String]) {
        let global_names = global_scalar_names(self.view);
        for (site, call) in body.calls.iter().enumerate() {
            if !live_sites[site] {
                continue;
            }
            let callee = call.function as usize;
            self.reachable[callee] = true;
            if !self.capture_names[callee].is_empty() {
                continue;
            }
            let function = &self.view.functions()[callee];
            let mut taken = explicit_names(function);
            let first_capture = call.args.len() - function.captures as usize;
            let mut names = Vec::new();
            for (i, &arg) in call.args[first_capture..].iter().enumerate() {
                let hint = match body.nodes[arg as usize] {
                    Node::Input(k) => input_names.get(k as usize).cloned(),
                    Node::Global(k) => global_names.get(k as usize).cloned(),
                    Node::Result { site, output } => self.result_field(body, site, output),
                    _ => body.label(arg).map(str::to_string),
                };
                let name = match hint {
                    Some(h) if !taken.contains(&h) => h,
                    _ => (i..)
                        .map(|j| format!("c{j}"))
                        .find(|c| !taken.contains(c))
                        .expect("an unused name"),
                };
                taken.push(name.clone());
                names.push(name);
            }
            self.capture_names[callee] = names;
        }
    }

    /// The field name of output `output` of call site `site` of `body`, if its callee returns
    /// a struct and that output is a scalar field of it.
    fn result_field(&self, body: &Body, site: u32, output: u32) -> Option<String> {
        let call = body.calls.get(site as usize)?;
        match self.view.functions().get(call.function as usize)?.kind {
            FunctionKind::Function(f) => f.result.scalar_field(output as usize).map(str::to_string),
            FunctionKind::LoopBody(_) => None,
        }
    }

    /// Declares the signature's constant parameters as module-scope constants named after
    /// the parameter (one constant per name: equal values are shared), and records where
    /// the [`Node::Global`] scalars are read.
    ///
    /// # Errors
    /// [`ShaderError::ConstantConflict`] for a constant of the name of an earlier one with
    /// other values or another type.
    pub fn declare_constants(&mut self) -> Result<(), ShaderError> {
        let view = self.view;
        for p in &view.signature().parameters {
            let Some(values) = constant_values(p) else {
                continue;
            };
            if values.len() != p.ty.width() {
                return Err(ShaderError::Unsupported(format!(
                    "the constant {} has {} values for {} scalars",
                    p.name,
                    values.len(),
                    p.ty.width()
                )));
            }
            if let Some((q, _, sources)) = self
                .shared
                .constants
                .iter()
                .find(|(q, _, _)| q.name == p.name)
            {
                if q != p {
                    return Err(ShaderError::ConstantConflict {
                        name: p.name.clone(),
                    });
                }
                self.globals.extend(sources.iter().cloned());
                continue;
            }
            let ty = types::arg_type(&mut self.shared.module, &p.ty);
            let mut values = values.iter();
            let init = self.constant_expression(&p.ty, &mut values);
            let constant = self.shared.module.constants.append(
                Constant {
                    name: Some(p.name.clone()),
                    ty,
                    init,
                },
                Span::UNDEFINED,
            );
            let mut paths = Vec::new();
            scalar_paths(&p.ty, &mut Vec::new(), &mut paths);
            let sources: Vec<Source> = paths
                .into_iter()
                .map(|(path, vector)| Source::Constant {
                    constant,
                    path,
                    vector,
                })
                .collect();
            self.globals.extend(sources.iter().cloned());
            self.shared.constants.push((p.clone(), constant, sources));
        }
        Ok(())
    }

    /// Declares the graph's named constants as module-scope constants of their names (an
    /// `f32`, or an `array<f32, N>` for a table), each with a comment saying what it is.
    ///
    /// # Errors
    /// [`ShaderError::ConstantConflict`] for a named constant of the name of an earlier one
    /// with other values.
    pub fn declare_named(&mut self) -> Result<(), ShaderError> {
        for &named in self.view.named_constants() {
            if let Some(&(earlier, constant)) =
                self.shared.named.iter().find(|(c, _)| c.name == named.name)
            {
                if earlier.values != named.values {
                    return Err(ShaderError::ConstantConflict {
                        name: named.name.to_string(),
                    });
                }
                self.named.push(constant);
                continue;
            }
            let module = &mut self.shared.module;
            let f32t = types::f32(module);
            let literals: Vec<Handle<Expression>> = named
                .values
                .iter()
                .map(|&v| self_append(module, Expression::Literal(naga::Literal::F32(v as f32))))
                .collect();
            let (ty, init) = match literals[..] {
                [one] => (f32t, one),
                _ => {
                    let ty = types::array(module, f32t, Some(literals.len() as u32));
                    let compose = Expression::Compose {
                        ty,
                        components: literals,
                    };
                    (ty, self_append(module, compose))
                }
            };
            let constant = module.constants.append(
                Constant {
                    name: Some(named.name.to_string()),
                    ty,
                    init,
                },
                Span::UNDEFINED,
            );
            self.shared.names.insert(named.name.to_string());
            self.shared
                .comments
                .push((named.name.to_string(), vec![named.meaning.to_string()]));
            self.shared.named.push((named, constant));
            self.named.push(constant);
        }
        Ok(())
    }

    /// The global expression of a value of type `ty` from the next scalars of `values`.
    fn constant_expression(
        &mut self,
        ty: &ArgType,
        values: &mut std::slice::Iter<'_, f32>,
    ) -> Handle<Expression> {
        let mut global = |e: Expression| self_append(&mut self.shared.module, e);
        match ty {
            ArgType::Scalar => {
                let v = *values.next().expect("one value per scalar");
                global(Expression::Literal(naga::Literal::F32(v)))
            }
            ArgType::Vec3 => {
                let components = (0..3)
                    .map(|_| {
                        let v = *values.next().expect("one value per scalar");
                        global(Expression::Literal(naga::Literal::F32(v)))
                    })
                    .collect();
                let ty = types::vec3(&mut self.shared.module);
                self_append(
                    &mut self.shared.module,
                    Expression::Compose { ty, components },
                )
            }
            ArgType::Struct(s) => {
                let components = s
                    .fields
                    .iter()
                    .map(|(_, t)| self.constant_expression(t, values))
                    .collect();
                let ty = types::arg_type(&mut self.shared.module, ty);
                self_append(
                    &mut self.shared.module,
                    Expression::Compose { ty, components },
                )
            }
        }
    }

    /// Declares the loops' constant arrays: `const NAME: array<Element, K>` with a struct
    /// `Element` of the loop's field names.
    pub fn declare_arrays(&mut self) {
        let view = self.view;
        for array in view.arrays() {
            if let Some((_, constant)) = self.shared.arrays.iter().find(|(a, _)| a == array) {
                self.arrays.push(*constant);
                continue;
            }
            let f = types::f32(&mut self.shared.module);
            let fields: Vec<(String, Handle<Type>)> =
                field_names(array.info.fields, array_width(array))
                    .into_iter()
                    .map(|n| (n, f))
                    .collect();
            let element = types::structure(
                &mut self.shared.module,
                &format!("{}Element", camel_case(array.info.name)),
                &fields,
            );
            let count = array.elements.len() as u32;
            let ty = types::array(&mut self.shared.module, element, Some(count));
            let rows: Vec<Handle<Expression>> = array
                .elements
                .iter()
                .map(|row| {
                    let components = row
                        .iter()
                        .map(|&v| {
                            self_append(
                                &mut self.shared.module,
                                Expression::Literal(naga::Literal::F32(v)),
                            )
                        })
                        .collect();
                    self_append(
                        &mut self.shared.module,
                        Expression::Compose {
                            ty: element,
                            components,
                        },
                    )
                })
                .collect();
            let init = self_append(
                &mut self.shared.module,
                Expression::Compose {
                    ty,
                    components: rows,
                },
            );
            let constant = self.shared.module.constants.append(
                Constant {
                    name: Some(array.info.array.to_string()),
                    ty,
                    init,
                },
                Span::UNDEFINED,
            );
            let constant = ArrayConstant { constant, count };
            self.shared.arrays.push((array.clone(), constant));
            self.arrays.push(constant);
        }
    }

    /// What makes a graph function the same shader function as one already in the module:
    /// its name, kind, parameter counts and body, with the tables, arrays and callees it
    /// refers to resolved to the module's.
    fn identity(&self, function: &crate::real::Function) -> String {
        let nodes: Vec<Node> = function
            .body
            .nodes
            .iter()
            .map(|&n| match n {
                Node::Fetch {
                    table,
                    coords,
                    channel,
                } => Node::Fetch {
                    table: self
                        .shared
                        .tables
                        .iter()
                        .position(|(t, _)| Arc::ptr_eq(t, &self.view.tables()[table as usize]))
                        .unwrap_or(usize::MAX) as u32,
                    coords,
                    channel,
                },
                other => other,
            })
            .collect();
        let globals: Vec<String> = function
            .body
            .nodes
            .iter()
            .filter_map(|n| match n {
                Node::Global(k) => Some(format!("{:?}", self.globals.get(*k as usize))),
                _ => None,
            })
            .collect();
        let calls: Vec<CallIdentity> = function
            .body
            .calls
            .iter()
            .map(|c| {
                let callee = self.functions.get(c.function as usize).copied().flatten();
                let array = match c.kind {
                    CallKind::Call => None,
                    CallKind::Loop { array } => self.arrays.get(array as usize).map(|a| a.constant),
                };
                (callee.map(|l| l.handle), &c.args[..], array)
            })
            .collect();
        format!(
            "{:?}",
            (
                &function.name,
                function.kind,
                function.inputs,
                function.captures,
                nodes,
                globals,
                calls,
                &function.body.outputs
            )
        )
    }

    /// Lowers every reachable graph function, callees first.
    pub fn lower_functions(&mut self) -> Result<(), ShaderError> {
        let view = self.view;
        for (f, function) in view.functions().iter().enumerate() {
            if !self.reachable[f] {
                continue;
            }
            let key = format!("{}{:?}", self.identity(function), self.capture_vectors[f]);
            if let Some(&lowered) = self.shared.functions.get(&key) {
                self.functions[f] = Some(lowered);
                continue;
            }
            let name = self.shared.unique_name(&function.name);
            let mut b = FnBuilder::new(&name);
            let mut inputs = Vec::new();
            let f32t = types::f32(&mut self.shared.module);
            let vec3t = types::vec3(&mut self.shared.module);
            let outputs = function.body.outputs.len();
            let module = &mut self.shared.module;
            let result = match function.kind {
                FunctionKind::Function(info) => {
                    shaped_arguments(&mut b, f32t, vec3t, info.parameters, &mut inputs);
                    ResultKind::of(info.result, outputs, &name, module)
                }
                FunctionKind::LoopBody(info) => {
                    shaped_arguments(&mut b, f32t, vec3t, info.state, &mut inputs);
                    let fields = (function.inputs as usize).saturating_sub(outputs);
                    for name in field_names(info.fields, fields) {
                        inputs.push(Source::Value(b.argument(&name, f32t)));
                    }
                    let result = match info.state {
                        [(_, Shape::Scalar)] => ResultType::Scalars,
                        state => ResultType::Fields(state),
                    };
                    ResultKind::of(result, outputs, &name, module)
                }
            };
            if inputs.len() != function.inputs as usize {
                return Err(ShaderError::Unsupported(format!(
                    "function {} declares {} parameter scalars but its body has {} inputs",
                    function.name,
                    inputs.len(),
                    function.inputs
                )));
            }
            let names = self.capture_names[f].clone();
            let mut first = 0;
            let captured: Vec<(&str, Shape)> = capture_shapes(&self.capture_vectors[f])
                .into_iter()
                .map(|shape| {
                    let name = names[first].as_str();
                    first += shape.width();
                    match shape {
                        Shape::Scalar => (name, shape),
                        Shape::Vec3 => (name.strip_suffix("_x").unwrap_or(name), shape),
                    }
                })
                .collect();
            shaped_arguments(&mut b, f32t, vec3t, &captured, &mut inputs);
            let ty = result.ty(&mut self.shared.module);
            b.result(ty);
            let live = std::mem::replace(
                &mut self.live[f],
                Liveness {
                    nodes: vec![],
                    sites: vec![],
                },
            );
            let outputs = self.lower_body(&mut b, &function.body, &live, &inputs)?;
            self.live[f] = live;
            let value = self.compose_result(&mut b, result, &outputs);
            b.ret(Some(value));
            let handle = self
                .shared
                .module
                .functions
                .append(b.finish(), Span::UNDEFINED);
            let lowered = Lowered { handle, result };
            self.functions[f] = Some(lowered);
            self.shared.functions.insert(key, lowered);
            let (source, equation) = match function.kind {
                FunctionKind::Function(i) => (i.source, i.equation),
                FunctionKind::LoopBody(l) => (l.source, l.equation),
            };
            self.shared
                .comments
                .push((name, vec![format!("{source} -- {equation}")]));
        }
        Ok(())
    }

    /// Lowers the top-level body as the function `name` of the signature's arguments.
    ///
    /// # Errors
    /// [`ShaderError::NameConflict`] if the module has a function `name`.
    pub fn lower_top(&mut self, name: &str) -> Result<(), ShaderError> {
        let view = self.view;
        if !self.shared.names.insert(name.to_string()) {
            return Err(ShaderError::NameConflict {
                name: name.to_string(),
            });
        }
        let mut b = FnBuilder::new(name);
        let mut inputs = Vec::new();
        for p in &view.signature().parameters {
            if constant_values(p).is_some() {
                continue;
            }
            let ty = types::arg_type(&mut self.shared.module, &p.ty);
            let base = b.argument(&p.name, ty);
            let mut paths = Vec::new();
            scalar_paths(&p.ty, &mut Vec::new(), &mut paths);
            inputs.extend(paths.into_iter().map(|(path, vector)| {
                if path.is_empty() {
                    Source::Value(base)
                } else {
                    Source::Component { base, path, vector }
                }
            }));
        }
        let body = view.body();
        let result = ResultKind::of(
            view.signature().result,
            body.outputs.len(),
            name,
            &mut self.shared.module,
        );
        let ty = result.ty(&mut self.shared.module);
        b.result(ty);
        let live = std::mem::replace(
            &mut self.top_live,
            Liveness {
                nodes: vec![],
                sites: vec![],
            },
        );
        let outputs = self.lower_body(&mut b, body, &live, &inputs)?;
        self.top_live = live;
        let value = self.compose_result(&mut b, result, &outputs);
        b.ret(Some(value));
        let handle = self
            .shared
            .module
            .functions
            .append(b.finish(), Span::UNDEFINED);
        let mut signature = view.signature().clone();
        signature
            .parameters
            .retain(|p| constant_values(p).is_none());
        self.shared.tops.push(Top {
            name: name.to_string(),
            handle,
            signature,
            result,
        });
        self.shared.comments.push((
            name.to_string(),
            vec![format!(
                "{name}: the traced function, generated by hairmath::shader"
            )],
        ));
        Ok(())
    }

    /// The function's return value from its output scalars.
    fn compose_result(
        &mut self,
        b: &mut FnBuilder,
        result: ResultKind,
        outputs: &[Handle<Expression>],
    ) -> Handle<Expression> {
        match result {
            ResultKind::Scalar => outputs[0],
            ResultKind::Vec3 => {
                let ty = types::vec3(&mut self.shared.module);
                compose(b, ty, outputs)
            }
            ResultKind::Array(_) => {
                let ty = result.ty(&mut self.shared.module);
                b.expr(Expression::Compose {
                    ty,
                    components: outputs.to_vec(),
                })
            }
            ResultKind::Struct { ty, fields } => {
                let vec3t = types::vec3(&mut self.shared.module);
                let shapes = fields.iter().map(|&(_, shape)| shape);
                let (components, _) = shaped_values(b, vec3t, shapes, outputs);
                b.expr(Expression::Compose { ty, components })
            }
        }
    }

    /// Lowers the live nodes of `body` (whose inputs are read from `inputs`) into `b`;
    /// returns the expressions of its outputs.
    fn lower_body(
        &mut self,
        b: &mut FnBuilder,
        body: &Body,
        live: &Liveness,
        inputs: &[Source],
    ) -> Result<Vec<Handle<Expression>>, ShaderError> {
        let mut ctx = BodyContext {
            values: vec![None; body.nodes.len()],
            paths: HashMap::new(),
            fetches: HashMap::new(),
            sites: HashMap::new(),
            constants: HashMap::new(),
        };
        for (i, node) in body.nodes.iter().enumerate() {
            if !live.nodes[i] {
                continue;
            }
            let v = |k: u32, ctx: &BodyContext| -> Handle<Expression> {
                ctx.values[k as usize].expect("operands come before their use")
            };
            let h = match *node {
                Node::Input(k) => {
                    let source = inputs.get(k as usize).ok_or_else(|| {
                        ShaderError::Unsupported(format!("input {k} beyond the parameters"))
                    })?;
                    ctx.read(b, source)
                }
                Node::Global(k) => {
                    let source = self.globals.get(k as usize).cloned().ok_or_else(|| {
                        ShaderError::Unsupported(format!("constant scalar {k} is not declared"))
                    })?;
                    ctx.read(b, &source)
                }
                Node::Const(bits) => b.f32(f32::from_bits(bits)),
                Node::Named { constant, index } => self.named_value(b, constant, index)?,
                Node::Unary(op, a) => unary(b, op, v(a, &ctx)),
                Node::Binary(op, l, r) => binary(b, op, v(l, &ctx), v(r, &ctx)),
                Node::Less(l, r) => b.expr(Expression::Binary {
                    op: BinaryOperator::Less,
                    left: v(l, &ctx),
                    right: v(r, &ctx),
                }),
                Node::LessEqual(l, r) => b.expr(Expression::Binary {
                    op: BinaryOperator::LessEqual,
                    left: v(l, &ctx),
                    right: v(r, &ctx),
                }),
                Node::And(l, r) => b.expr(Expression::Binary {
                    op: BinaryOperator::LogicalAnd,
                    left: v(l, &ctx),
                    right: v(r, &ctx),
                }),
                Node::Or(l, r) => b.expr(Expression::Binary {
                    op: BinaryOperator::LogicalOr,
                    left: v(l, &ctx),
                    right: v(r, &ctx),
                }),
                Node::Not(a) => b.expr(Expression::Unary {
                    op: UnaryOperator::LogicalNot,
                    expr: v(a, &ctx),
                }),
                Node::Select(m, t, f) => b.expr(Expression::Select {
                    condition: v(m, &ctx),
                    accept: v(t, &ctx),
                    reject: v(f, &ctx),
                }),
                Node::Fetch {
                    table,
                    coords,
                    channel,
                } => self.fetch(b, &mut ctx, table, coords, channel)?,
                Node::Result { site, output } => {
                    let call = body.calls.get(site as usize).ok_or_else(|| {
                        ShaderError::Unsupported(format!("call site {site} does not exist"))
                    })?;
                    self.site_output(b, &mut ctx, site, call, output)?
                }
            };
            if let Some(name) = body.label(i as u32) {
                b.label(h, name);
            }
            ctx.values[i] = Some(h);
        }
        body.outputs
            .iter()
            .map(|&o| {
                ctx.values[o as usize].ok_or_else(|| {
                    ShaderError::Unsupported(format!("output node {o} was not computed"))
                })
            })
            .collect()
    }

    /// Value `index` of the graph's named constant `constant`, read by name.
    fn named_value(
        &self,
        b: &mut FnBuilder,
        constant: u32,
        index: u32,
    ) -> Result<Handle<Expression>, ShaderError> {
        let named = self.view.named_constants().get(constant as usize);
        let (Some(named), Some(&handle)) = (named, self.named.get(constant as usize)) else {
            return Err(ShaderError::Unsupported(format!(
                "named constant {constant} is not declared"
            )));
        };
        let base = b.expr(Expression::Constant(handle));
        Ok(match named.values.len() {
            1 => base,
            _ => b.expr(Expression::AccessIndex { base, index }),
        })
    }

    /// Channel `channel` of the table fetch at `coords`: one helper call per distinct
    /// (table, coordinates).
    fn fetch(
        &mut self,
        b: &mut FnBuilder,
        ctx: &mut BodyContext,
        table: u32,
        coords: [u32; MAX_AXES],
        channel: u32,
    ) -> Result<Handle<Expression>, ShaderError> {
        let helper = self
            .tables
            .get(table as usize)
            .cloned()
            .ok_or_else(|| ShaderError::Unsupported(format!("table {table} does not exist")))?;
        if channel >= helper.channels {
            return Err(ShaderError::Unsupported(format!(
                "channel {channel} of a table of {} channels",
                helper.channels
            )));
        }
        let result = match ctx.fetches.get(&(table, coords)) {
            Some(&r) => r,
            None => {
                let args = coords[..helper.dims]
                    .iter()
                    .map(|&c| ctx.values[c as usize].expect("coordinates come before the fetch"))
                    .collect();
                let r = b.call(helper.function, args);
                ctx.fetches.insert((table, coords), r);
                r
            }
        };
        let texture = channel / super::TEXTURE_CHANNELS as u32;
        let component = channel % super::TEXTURE_CHANNELS as u32;
        let texel = if helper.textures > 1 {
            ctx.path(b, result, &[texture], None)
        } else {
            result
        };
        let texel_size = super::TEXTURE_CHANNELS as u32;
        Ok(ctx.path(b, texel, &[component], Some(texel_size)))
    }

    /// Output `output` of call site `site` (the call or loop lowered at its first use).
    fn site_output(
        &mut self,
        b: &mut FnBuilder,
        ctx: &mut BodyContext,
        site: u32,
        call: &CallSite,
        output: u32,
    ) -> Result<Handle<Expression>, ShaderError> {
        if !ctx.sites.contains_key(&site) {
            let lowered = match call.kind {
                CallKind::Call => self.call(b, ctx, call)?,
                CallKind::Loop { array } => self.run_loop(b, ctx, call, array)?,
            };
            ctx.sites.insert(site, lowered);
        }
        Ok(match ctx.sites[&site] {
            SiteValue::Call { result, kind } => {
                let (path, vector) = kind.output_path(output).ok_or_else(|| {
                    ShaderError::Unsupported(format!("call output {output} beyond its result"))
                })?;
                ctx.path(b, result, &path, vector.then_some(3))
            }
            SiteValue::Loop { ref state } => {
                let shapes = state.iter().map(|&(_, shape)| shape);
                let (entry, shape, component) = locate(shapes, output).ok_or_else(|| {
                    ShaderError::Unsupported(format!("loop output {output} beyond its state"))
                })?;
                let value = state[entry].0;
                match shape {
                    Shape::Scalar => value,
                    Shape::Vec3 => ctx.path(b, value, &[component], Some(3)),
                }
            }
        })
    }

    fn callee(&self, call: &CallSite) -> Result<(Lowered, &'a crate::real::Function), ShaderError> {
        let view = self.view;
        let function = view
            .functions()
            .get(call.function as usize)
            .ok_or_else(|| {
                ShaderError::Unsupported(format!("function {} does not exist", call.function))
            })?;
        let lowered = self.functions[call.function as usize].ok_or_else(|| {
            ShaderError::Unsupported(format!(
                "function {} is called before it is defined",
                function.name
            ))
        })?;
        Ok((lowered, function))
    }

    /// A call: the explicit arguments (vectors composed from their scalars) and the captures.
    fn call(
        &mut self,
        b: &mut FnBuilder,
        ctx: &mut BodyContext,
        call: &CallSite,
    ) -> Result<SiteValue, ShaderError> {
        let (lowered, function) = self.callee(call)?;
        let expected = (function.inputs + function.captures) as usize;
        if call.args.len() != expected {
            return Err(ShaderError::Unsupported(format!(
                "{} is called with {} scalars for {expected} parameters",
                function.name,
                call.args.len()
            )));
        }
        let values: Vec<Handle<Expression>> = call
            .args
            .iter()
            .map(|&a| ctx.values[a as usize].expect("arguments come before the call"))
            .collect();
        let vec3t = types::vec3(&mut self.shared.module);
        let explicit = match function.kind {
            FunctionKind::Function(info) => info.parameters,
            FunctionKind::LoopBody(_) => &[],
        };
        let shapes = explicit.iter().map(|&(_, shape)| shape);
        let (mut args, rest) = shaped_values(b, vec3t, shapes, &values);
        let captures = capture_shapes(&self.capture_vectors[call.function as usize]);
        let (captured, _) = shaped_values(b, vec3t, captures, rest);
        args.extend(captured);
        let result = b.call(lowered.handle, args);
        Ok(SiteValue::Call {
            result,
            kind: lowered.result,
        })
    }

    /// A loop over a constant array: `var` state initialised from the call's first
    /// arguments, then `for (var k = 0u; k < K; k++) { state = body(state, ARRAY[k],
    /// captures); }`.
    fn run_loop(
        &mut self,
        b: &mut FnBuilder,
        ctx: &mut BodyContext,
        call: &CallSite,
        array: u32,
    ) -> Result<SiteValue, ShaderError> {
        let (lowered, function) = self.callee(call)?;
        let constant = *self.arrays.get(array as usize).ok_or_else(|| {
            ShaderError::Unsupported(format!("constant array {array} does not exist"))
        })?;
        let info = self.view.arrays()[array as usize].info;
        let state_len = function.body.outputs.len();
        let width = array_width(&self.view.arrays()[array as usize]);
        if function.inputs as usize != state_len + width
            || call.args.len() != state_len + function.captures as usize
            || info.state_width() != state_len
        {
            return Err(ShaderError::Unsupported(format!(
                "loop {} threads {state_len} state scalars over elements of {width} but takes \
                 {} inputs and is called with {} values",
                function.name,
                function.inputs,
                call.args.len()
            )));
        }
        let f32t = types::f32(&mut self.shared.module);
        let vec3t = types::vec3(&mut self.shared.module);
        let u32t = types::u32(&mut self.shared.module);
        let initial: Vec<Handle<Expression>> = call.args[..state_len]
            .iter()
            .map(|&a| ctx.values[a as usize].expect("arguments come before the loop"))
            .collect();
        let state_shapes = info.state.iter().map(|&(_, shape)| shape);
        let (initial, _) = shaped_values(b, vec3t, state_shapes, &initial);
        let mut state = Vec::with_capacity(info.state.len());
        for (&(name, shape), init) in info.state.iter().zip(initial) {
            let ty = match shape {
                Shape::Scalar => f32t,
                Shape::Vec3 => vec3t,
            };
            let var = b.local(name, ty, None);
            b.store(var, init);
            state.push(var);
        }
        let zero = b.u32(0);
        let k = b.local("k", u32t, Some(zero));
        let captures: Vec<Handle<Expression>> = call.args[state_len..]
            .iter()
            .map(|&a| ctx.values[a as usize].expect("captures come before the loop"))
            .collect();
        let shapes = capture_shapes(&self.capture_vectors[call.function as usize]);
        let (captures, _) = shaped_values(b, vec3t, shapes, &captures);

        b.open_block();
        let index = b.load(k);
        let count = b.u32(constant.count);
        let more = b.expr(Expression::Binary {
            op: BinaryOperator::Less,
            left: index,
            right: count,
        });
        b.open_block();
        let accept = b.close_block();
        b.open_block();
        b.stmt(Statement::Break);
        let reject = b.close_block();
        b.stmt(Statement::If {
            condition: more,
            accept,
            reject,
        });
        let array_value = b.expr(Expression::Constant(constant.constant));
        let index = b.load(k);
        let element = b.expr(Expression::Access {
            base: array_value,
            index,
        });
        let mut args: Vec<Handle<Expression>> = state.iter().map(|&p| b.load(p)).collect();
        for field in 0..width as u32 {
            args.push(b.expr(Expression::AccessIndex {
                base: element,
                index: field,
            }));
        }
        args.extend(captures);
        let result = b.call(lowered.handle, args);
        for (s, &var) in state.iter().enumerate() {
            let value = match lowered.result {
                ResultKind::Scalar => result,
                _ => b.expr(Expression::AccessIndex {
                    base: result,
                    index: s as u32,
                }),
            };
            b.store(var, value);
        }
        let body = b.close_block();

        b.open_block();
        let index = b.load(k);
        let one = b.u32(1);
        let next = b.expr(Expression::Binary {
            op: BinaryOperator::Add,
            left: index,
            right: one,
        });
        b.store(k, next);
        let continuing = b.close_block();
        b.stmt(Statement::Loop {
            body,
            continuing,
            break_if: None,
        });
        let state = state
            .iter()
            .zip(info.state)
            .map(|(&var, &(_, shape))| (b.load(var), shape))
            .collect();
        Ok(SiteValue::Loop { state })
    }
}

/// The values of one call site.
enum SiteValue {
    Call {
        result: Handle<Expression>,
        kind: ResultKind,
    },
    /// The state's values after the loop, with their shapes.
    Loop {
        state: Vec<(Handle<Expression>, Shape)>,
    },
}

/// What the lowering of one body remembers.
struct BodyContext {
    values: Vec<Option<Handle<Expression>>>,
    /// `base.path` expressions already built.
    paths: HashMap<(Handle<Expression>, Vec<u32>), Handle<Expression>>,
    fetches: HashMap<(u32, [u32; MAX_AXES]), Handle<Expression>>,
    sites: HashMap<u32, SiteValue>,
    /// The expression of each module-scope constant read (one, so that its components are
    /// recognised as components of one value).
    constants: HashMap<Handle<Constant>, Handle<Expression>>,
}

impl BodyContext {
    /// The expression reading `source`.
    fn read(&mut self, b: &mut FnBuilder, source: &Source) -> Handle<Expression> {
        match source {
            Source::Value(h) => *h,
            Source::Component { base, path, vector } => {
                self.path(b, *base, path, vector.then_some(3))
            }
            Source::Constant {
                constant,
                path,
                vector,
            } => {
                let base = *self
                    .constants
                    .entry(*constant)
                    .or_insert_with(|| b.expr(Expression::Constant(*constant)));
                self.path(b, base, path, vector.then_some(3))
            }
        }
    }

    /// `base.path[0]...`, each prefix built once; with `vector_size`, the last step is recorded
    /// as a component of a vector of that many components ([`FnBuilder::mark_component`]).
    fn path(
        &mut self,
        b: &mut FnBuilder,
        base: Handle<Expression>,
        path: &[u32],
        vector_size: Option<u32>,
    ) -> Handle<Expression> {
        let mut h = base;
        for depth in 1..=path.len() {
            let key = (base, path[..depth].to_vec());
            let parent = h;
            h = match self.paths.get(&key) {
                Some(&e) => e,
                None => {
                    let e = b.expr(Expression::AccessIndex {
                        base: parent,
                        index: path[depth - 1],
                    });
                    self.paths.insert(key, e);
                    if let (Some(size), true) = (vector_size, depth == path.len()) {
                        let index = path[depth - 1];
                        b.mark_component(
                            e,
                            Component {
                                vector: parent,
                                index,
                                size,
                            },
                        );
                    }
                    e
                }
            };
        }
        h
    }
}

/// The `vec3<f32>` of three scalars, as one vector expression where they are computed alike
/// ([`vectorize::vec3`]).
fn compose(
    b: &mut FnBuilder,
    ty: Handle<Type>,
    scalars: &[Handle<Expression>],
) -> Handle<Expression> {
    vectorize::vec3(b, ty, [scalars[0], scalars[1], scalars[2]])
}

fn unary(b: &mut FnBuilder, op: Unary, a: Handle<Expression>) -> Handle<Expression> {
    let fun = match op {
        Unary::Neg => {
            return b.expr(Expression::Unary {
                op: UnaryOperator::Negate,
                expr: a,
            })
        }
        Unary::Sqrt => MathFunction::Sqrt,
        Unary::Exp => MathFunction::Exp,
        Unary::Ln => MathFunction::Log,
        Unary::Sin => MathFunction::Sin,
        Unary::Cos => MathFunction::Cos,
        Unary::Abs => MathFunction::Abs,
        Unary::Floor => MathFunction::Floor,
    };
    math(b, fun, a, None)
}

fn binary(
    b: &mut FnBuilder,
    op: Binary,
    left: Handle<Expression>,
    right: Handle<Expression>,
) -> Handle<Expression> {
    let op = match op {
        Binary::Add => BinaryOperator::Add,
        Binary::Sub => BinaryOperator::Subtract,
        Binary::Mul => BinaryOperator::Multiply,
        Binary::Div => BinaryOperator::Divide,
        Binary::Atan2 => return math(b, MathFunction::Atan2, left, Some(right)),
        Binary::Min => return math(b, MathFunction::Min, left, Some(right)),
        Binary::Max => return math(b, MathFunction::Max, left, Some(right)),
    };
    b.expr(Expression::Binary { op, left, right })
}

/// `fun(arg)` or `fun(arg, arg1)`.
pub(super) fn math(
    b: &mut FnBuilder,
    fun: MathFunction,
    arg: Handle<Expression>,
    arg1: Option<Handle<Expression>>,
) -> Handle<Expression> {
    b.expr(Expression::Math {
        fun,
        arg,
        arg1,
        arg2: None,
        arg3: None,
    })
}

fn self_append(module: &mut Module, e: Expression) -> Handle<Expression> {
    module.global_expressions.append(e, Span::UNDEFINED)
}

/// The access paths of the scalars of a value of type `ty` (a vector's components, a
/// struct's fields recursively) and whether each ends in a vector component.
pub(super) fn scalar_paths(ty: &ArgType, prefix: &mut Vec<u32>, out: &mut Vec<(Vec<u32>, bool)>) {
    match ty {
        ArgType::Scalar => out.push((prefix.clone(), false)),
        ArgType::Vec3 => {
            for i in 0..3 {
                let mut p = prefix.clone();
                p.push(i);
                out.push((p, true));
            }
        }
        ArgType::Struct(s) => {
            for (i, (_, t)) in s.fields.iter().enumerate() {
                prefix.push(i as u32);
                scalar_paths(t, prefix, out);
                prefix.pop();
            }
        }
    }
}

/// Names of the scalars of a value named `base` of type `ty`: `h`, `wi_x`, and for a struct
/// its fields' names (`eta`, `color_y`).
fn scalar_names(base: &str, ty: &ArgType, out: &mut Vec<String>) {
    match ty {
        ArgType::Scalar => out.push(base.to_string()),
        ArgType::Vec3 => out.extend(["x", "y", "z"].map(|c| format!("{base}_{c}"))),
        ArgType::Struct(s) => {
            for (name, t) in &s.fields {
                scalar_names(name, t, out);
            }
        }
    }
}

/// Names of the top-level body's input scalars.
fn top_scalar_names(view: &Graph) -> Vec<String> {
    let mut out = Vec::new();
    for p in &view.signature().parameters {
        if constant_values(p).is_none() {
            scalar_names(&p.name, &p.ty, &mut out);
        }
    }
    out
}

/// Names of the [`Node::Global`] scalars.
fn global_scalar_names(view: &Graph) -> Vec<String> {
    let mut out = Vec::new();
    for p in &view.signature().parameters {
        if constant_values(p).is_some() {
            scalar_names(&p.name, &p.ty, &mut out);
        }
    }
    out
}

/// Names of a function's explicit parameters, per scalar for a loop body (state, then the
/// element's fields) and per parameter for a function.
fn explicit_names(function: &crate::real::Function) -> Vec<String> {
    match function.kind {
        FunctionKind::Function(info) => {
            let mut out = Vec::new();
            for &(name, shape) in info.parameters {
                match shape {
                    Shape::Scalar => out.push(name.to_string()),
                    Shape::Vec3 => out.extend(["x", "y", "z"].map(|c| format!("{name}_{c}"))),
                }
            }
            out
        }
        FunctionKind::LoopBody(info) => {
            let mut out = shaped_names(info.state);
            let fields = (function.inputs as usize).saturating_sub(out.len());
            out.extend(field_names(info.fields, fields));
            out
        }
    }
}

/// Per scalar of the values `shapes`, its name: `name`, or `name_x`, `name_y`, `name_z`.
fn shaped_names(shapes: &[(&str, Shape)]) -> Vec<String> {
    let mut out = Vec::new();
    for &(name, shape) in shapes {
        match shape {
            Shape::Scalar => out.push(name.to_string()),
            Shape::Vec3 => out.extend(["x", "y", "z"].map(|c| format!("{name}_{c}"))),
        }
    }
    out
}

/// Declares an argument per value of `shapes` and appends where each scalar is read.
fn shaped_arguments(
    b: &mut FnBuilder,
    f32t: Handle<Type>,
    vec3t: Handle<Type>,
    shapes: &[(&str, Shape)],
    inputs: &mut Vec<Source>,
) {
    for &(name, shape) in shapes {
        match shape {
            Shape::Scalar => inputs.push(Source::Value(b.argument(name, f32t))),
            Shape::Vec3 => {
                let base = b.argument(name, vec3t);
                inputs.extend((0..3).map(|i| Source::Component {
                    base,
                    path: vec![i],
                    vector: true,
                }));
            }
        }
    }
}

/// The leading `scalars` as one value per entry of `shapes` (three composed into a
/// `vec3<f32>`), and the scalars after them.
fn shaped_values<'s>(
    b: &mut FnBuilder,
    vec3t: Handle<Type>,
    shapes: impl IntoIterator<Item = Shape>,
    scalars: &'s [Handle<Expression>],
) -> (Vec<Handle<Expression>>, &'s [Handle<Expression>]) {
    let mut rest = scalars;
    let values = shapes
        .into_iter()
        .map(|shape| {
            let (value, tail) = rest.split_at(shape.width());
            rest = tail;
            match shape {
                Shape::Scalar => value[0],
                Shape::Vec3 => compose(b, vec3t, value),
            }
        })
        .collect();
    (values, rest)
}

/// `count` names: `names` if it has that many, else `s0, s1, ...` / `e0, e1, ...`.
fn field_names(names: &[&str], count: usize) -> Vec<String> {
    if names.len() == count {
        names.iter().map(|s| s.to_string()).collect()
    } else {
        (0..count).map(|i| format!("v{i}")).collect()
    }
}

/// Scalars per element of a constant array.
fn array_width(array: &ConstArray) -> usize {
    array
        .elements
        .first()
        .map_or(array.info.fields.len(), |e| e.len())
}

/// `far_field_node` -> `FarFieldNode`.
fn camel_case(name: &str) -> String {
    name.split('_')
        .filter(|w| !w.is_empty())
        .map(|w| {
            let mut c = w.chars();
            match c.next() {
                Some(first) => first.to_ascii_uppercase().to_string() + &c.as_str().to_lowercase(),
                None => String::new(),
            }
        })
        .collect()
}

/// Adds `name(tangent, wi, wo, rest...)`: `local(frame(tangent, wi, wo), rest...)` (see
/// [`super::ModuleBuilder::world_companion`]).
pub(super) fn world_companion(
    shared: &mut Shared,
    name: &str,
    frame: &str,
    local: &str,
) -> Result<(), ShaderError> {
    let find = |n: &str| {
        shared
            .tops
            .iter()
            .find(|t| t.name == n)
            .cloned()
            .ok_or_else(|| ShaderError::Unsupported(format!("no top-level function {n}")))
    };
    let (frame_top, local_top) = (find(frame)?, find(local)?);
    let frame_params = &frame_top.signature.parameters;
    let two_directions = matches!(
        frame_top.result,
        ResultKind::Struct {
            fields: [(_, Shape::Vec3), (_, Shape::Vec3)],
            ..
        }
    );
    if frame_params.len() != 3
        || frame_params.iter().any(|p| p.ty != ArgType::Vec3)
        || !two_directions
    {
        return Err(ShaderError::Unsupported(format!(
            "{frame} does not map three vec3<f32> to a struct of two vec3<f32>"
        )));
    }
    let local_params = &local_top.signature.parameters;
    if local_params.len() < 2 || local_params[..2].iter().any(|p| p.ty != ArgType::Vec3) {
        return Err(ShaderError::Unsupported(format!(
            "{local} does not start with two vec3<f32> arguments"
        )));
    }
    if !shared.names.insert(name.to_string()) {
        return Err(ShaderError::NameConflict {
            name: name.to_string(),
        });
    }
    let module = &mut shared.module;
    let vec3t = types::vec3(module);
    let mut b = FnBuilder::new(name);
    let directions: Vec<Handle<Expression>> = frame_params
        .iter()
        .map(|p| b.argument(&p.name, vec3t))
        .collect();
    let rest: Vec<Handle<Expression>> = local_params[2..]
        .iter()
        .map(|p| {
            let ty = types::arg_type(module, &p.ty);
            b.argument(&p.name, ty)
        })
        .collect();
    let ty = local_top.result.ty(module);
    b.result(ty);
    let local_dirs = b.call(frame_top.handle, directions);
    let mut args: Vec<Handle<Expression>> = (0..2)
        .map(|index| {
            b.expr(Expression::AccessIndex {
                base: local_dirs,
                index,
            })
        })
        .collect();
    args.extend(rest);
    let value = b.call(local_top.handle, args);
    b.ret(Some(value));
    let handle = module.functions.append(b.finish(), Span::UNDEFINED);
    let mut signature = frame_top.signature.clone();
    signature
        .parameters
        .extend(local_params[2..].iter().cloned());
    signature.result = local_top.signature.result;
    shared.tops.push(Top {
        name: name.to_string(),
        handle,
        signature,
        result: local_top.result,
    });
    shared.comments.push((
        name.to_string(),
        vec![format!(
            "{name}: {local} of world-space directions, made local to the fibre by {frame}"
        )],
    ));
    Ok(())
}
