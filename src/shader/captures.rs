//! Which captured parameters of the graph's functions are vectors: three consecutive captures
//! that every live call site passes the x, y and z of one `vec3<f32>` (a vector uniform, a
//! vector argument, or a vector parameter of the calling function) become one `vec3<f32>`
//! parameter, so that a colour or a direction the Rust code uses as a whole stays one value.

use super::body::scalar_paths;
use super::constant_values;
use crate::real::{Body, FunctionKind, Graph, Node, Shape};

/// A `vec3<f32>` value of a body, named by where it lives.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Vector {
    /// The baked uniforms' scalars from `Node::Global(first)`.
    Global(u32),
    /// The top-level arguments' scalars from `Node::Input(first)`.
    Argument(u32),
    /// The parameter scalars of function `function` from its input `first`.
    Input { function: u32, first: u32 },
}

/// A scalar that is component `.1` of the vector `.0`, if it is one.
type Component = Option<(Vector, u32)>;

/// Per function of `view`, per captured parameter: whether a `vec3<f32>` of three captures
/// starts there. `top_sites` and `function_sites` mark the live call sites of the top-level
/// body and of each function; functions that are not `reachable` keep scalar captures.
pub(super) fn vector_captures(
    view: &Graph,
    top_sites: &[bool],
    function_sites: &[Vec<bool>],
    reachable: &[bool],
) -> Vec<Vec<bool>> {
    let functions = view.functions();
    let mut starts: Vec<Option<Vec<bool>>> = vec![None; functions.len()];
    let globals = signature_components(view, true);
    let arguments = signature_components(view, false);
    let top = |node: Node| match node {
        Node::Global(k) => globals.get(k as usize).copied().flatten(),
        Node::Input(k) => arguments.get(k as usize).copied().flatten(),
        _ => None,
    };
    let captures: Vec<u32> = functions.iter().map(|f| f.captures).collect();
    merge_sites(view.body(), top_sites, &captures, top, &mut starts);
    // Callers come after their callees, so a function's own captures are settled before its
    // body's call sites are read.
    for f in (0..functions.len()).rev() {
        if !reachable[f] {
            continue;
        }
        let function = &functions[f];
        let explicit = explicit_components(f as u32, function.kind, function.inputs);
        let own = starts[f].clone().unwrap_or_default();
        let component = |node: Node| match node {
            Node::Global(k) => globals.get(k as usize).copied().flatten(),
            Node::Input(k) if k < function.inputs => explicit.get(k as usize).copied().flatten(),
            Node::Input(k) => capture_component(f as u32, function.inputs, &own, k),
            _ => None,
        };
        merge_sites(
            &function.body,
            &function_sites[f],
            &captures,
            component,
            &mut starts,
        );
    }
    starts
        .into_iter()
        .zip(functions)
        .map(|(s, f)| s.unwrap_or_else(|| vec![false; f.captures as usize]))
        .collect()
}

/// The shapes of a function's captured parameters from their vector starts.
pub(super) fn capture_shapes(starts: &[bool]) -> Vec<Shape> {
    let mut shapes = Vec::new();
    let mut p = 0;
    while p < starts.len() {
        let shape = if starts[p] {
            Shape::Vec3
        } else {
            Shape::Scalar
        };
        shapes.push(shape);
        p += shape.width();
    }
    shapes
}

/// For each live call site of `body`, the captures where a vector starts, combined (all sites
/// must agree) into the callee's entry of `starts`; `captures` is each function's number of
/// captured parameters.
fn merge_sites(
    body: &Body,
    live_sites: &[bool],
    captures: &[u32],
    component: impl Fn(Node) -> Component,
    starts: &mut [Option<Vec<bool>>],
) {
    for (site, call) in body.calls.iter().enumerate() {
        if !live_sites.get(site).copied().unwrap_or(false) {
            continue;
        }
        let callee = call.function as usize;
        let Some(&count) = captures.get(callee) else {
            continue;
        };
        let first = call.args.len().saturating_sub(count as usize);
        let components: Vec<Component> = call.args[first..]
            .iter()
            .map(|&a| component(body.nodes[a as usize]))
            .collect();
        let site_starts: Vec<bool> = (0..components.len())
            .map(|p| match components[p] {
                Some((vector, 0)) => {
                    components.get(p + 1) == Some(&Some((vector, 1)))
                        && components.get(p + 2) == Some(&Some((vector, 2)))
                }
                _ => false,
            })
            .collect();
        starts[callee] = Some(match starts[callee].take() {
            None => site_starts,
            Some(earlier) => earlier
                .iter()
                .zip(&site_starts)
                .map(|(a, b)| *a && *b)
                .collect(),
        });
    }
}

/// Per scalar of the signature's constant parameters (`constants`) or of its arguments, the
/// vector component it is.
fn signature_components(view: &Graph, constants: bool) -> Vec<Component> {
    let mut out = Vec::new();
    for p in &view.signature().parameters {
        if constant_values(p).is_some() != constants {
            continue;
        }
        let mut paths = Vec::new();
        scalar_paths(&p.ty, &mut Vec::new(), &mut paths);
        for (path, vector) in paths {
            let k = out.len() as u32;
            let component = match path.last() {
                Some(&c) if vector => {
                    let first = k - c;
                    let vector = if constants {
                        Vector::Global(first)
                    } else {
                        Vector::Argument(first)
                    };
                    Some((vector, c))
                }
                _ => None,
            };
            out.push(component);
        }
    }
    out
}

/// Per explicit input of function `f`, the vector component it is (a `vec3` parameter, or a
/// `vec3` value of a loop's state).
fn explicit_components(f: u32, kind: FunctionKind, inputs: u32) -> Vec<Component> {
    let shapes = match kind {
        FunctionKind::Function(info) => info.parameters,
        FunctionKind::LoopBody(info) => info.state,
    };
    let mut out = Vec::new();
    for &(_, shape) in shapes {
        let first = out.len() as u32;
        match shape {
            Shape::Scalar => out.push(None),
            Shape::Vec3 => out.extend((0..3).map(|c| {
                let vector = Vector::Input { function: f, first };
                Some((vector, c))
            })),
        }
    }
    out.resize(inputs as usize, None);
    out
}

/// The vector component input `k` (a capture) of function `f` is, from its capture starts.
fn capture_component(f: u32, inputs: u32, starts: &[bool], k: u32) -> Component {
    let q = (k - inputs) as usize;
    (0..3u32).find_map(|c| {
        let start = q.checked_sub(c as usize)?;
        let vector = Vector::Input {
            function: f,
            first: inputs + start as u32,
        };
        starts
            .get(start)
            .copied()
            .unwrap_or(false)
            .then_some((vector, c))
    })
}
