//! A forward error bound for the GPU evaluation of a traced graph, derived from the WGSL accuracy
//! rules: per output, how far a device that meets the rules can be from the CPU's `f32` result.
//!
//! [`gpu_error_bound`] walks the flat graph ([`Graph::nodes`]: calls inlined, loops unrolled) in
//! order. For every node it has the CPU's `f32` value `v` (a per-node interpreter mirroring
//! [`Graph::eval_f32`], checked against it bit for bit on every call) and computes, in `f64`, a
//! bound `e` on `|device value - v|` from its operands' values and bounds. Each operation
//! contributes
//!
//! - the propagation of its operands' bounds through the exact operation (rigorous
//!   expressions: the end of the operand's interval that moves the result most for monotone
//!   functions, `|a| eb + |b| ea + ea eb` for `*`, `(|a| eb + |b| ea) / (|b| min|b'|)` for `/`,
//!   the angle subtended by the operands' box for `atan2`);
//! - the device's own error for the operation on its perturbed operands, from
//!   [`AccuracyRules`], in ulps of the largest magnitude the device's exact result can have,
//!   plus the subnormal flush ([`AccuracyRules::flush`]);
//! - the CPU's own rounding of the same operation ([`AccuracyRules::cpu_ulps`] for the correctly
//!   rounded operations, [`AccuracyRules::cpu_libm_ulps`] for `exp`, `log`, `sin`, `cos`,
//!   `atan2`), because the reference is the CPU's rounded `f32` value, not the exact one: two
//!   roundings of nearby exact values can be a whole ulp apart.
//!
//! When the device rounds `+ - *` to nearest as the CPU does
//! ([`AccuracyRules::basic_round_to_nearest`], llvmpipe), such an operation on operands with a
//! zero bound gives the CPU's bits, so its bound stays 0 (or the flush, for a subnormal result).
//!
//! Beside the radius `e`, every node carries the set the device's value lies in, by interval
//! arithmetic over the same rules (each end widened by the device's error): `max(x, 1e-12)` is at
//! least 1e-12 on the device too, so a division by it stays bounded; `exp(-s |x|)` is at most 1
//! whatever `x`'s bound. The bound is the smaller of the radius and the farthest end of that set
//! from `v`. The set is a union of up to [`MAX_PIECES`] intervals: a `floor` whose operand may
//! cross an integer is one of the integers (not the interval between them), so `wrap_angle` near
//! +-pi is near -pi or near pi, and `abs` of that (the logistic's `|x|`) is near pi again.
//!
//! Booleans carry no bound but a "certain" flag: a comparison is certain when the operands'
//! intervals do not overlap (the device decides as the CPU did). A `select` on a certain mask has
//! the chosen arm's bound; on an uncertain one `max(e_chosen, e_other + |t - f|)`.
//!
//! A bound is infinite when no rule covers what the device may do (a `log` or `sqrt` argument
//! that may cross zero, a divisor that may be 0, `exp` that may overflow, `sin`/`cos` beyond the
//! rule's range, a non-finite CPU value); [`RowBound::causes`] names the node kind that made each
//! infinite output infinite.

use std::collections::HashMap;
use std::f64::consts::PI;

use hairmath::lut::Table;
use hairmath::real::{Binary, Graph, Node, Real, Unary};

use super::gpu::{ulp_f32, Tolerance};

/// The smallest normal f32, 2^-126: the most a flushed subnormal is off by.
const FLUSH: f64 = f32::MIN_POSITIVE as f64;

/// ln(f32::MAX): `exp` of a larger argument overflows to infinity.
const LN_F32_MAX: f64 = 88.722_839_052_068_35;

/// The range `|x| <= 100` on which `sin` and `cos` were measured on llvmpipe within the
/// specification's 2^-11 absolute (by [`llvmpipe_sin_cos_beyond_pi`]; the specification itself
/// promises nothing outside [-pi, pi]).
pub const LLVMPIPE_SIN_COS_RANGE: f64 = 100.0;

/// The accuracy of every operation of a traced graph on one device, and of the CPU it is compared
/// with: per operation, the device's error for exact `f32` operands, in ulps of the exact result
/// ([`ulp_f32`]) or absolute.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct AccuracyRules {
    /// `+`, `-`, `*` on the device: ulps of the result. WGSL "correctly rounded" allows either
    /// neighbour of the exact value (under 1 ulp); a round-to-nearest device has 0.5.
    pub basic_ulps: f64,
    /// Whether the device's `+ - *` round to nearest (ties to even) exactly as the CPU's: then the
    /// same operands give the same bits and exact operands keep a zero bound.
    pub basic_round_to_nearest: bool,
    /// `x / y`: ulps, for |y| in [2^-126, 2^126] (outside, the bound is infinite).
    pub division_ulps: f64,
    /// `sqrt`: ulps (WGSL: inherited from `1.0 / inverseSqrt(x)`).
    pub sqrt_ulps: f64,
    /// `exp(x)`: `exp_ulps + exp_ulps_per_x * |x|` ulps.
    pub exp_ulps: f64,
    /// See [`AccuracyRules::exp_ulps`].
    pub exp_ulps_per_x: f64,
    /// `log(x)` for x in [0.5, 2]: absolute.
    pub ln_absolute: f64,
    /// `log(x)` elsewhere: ulps.
    pub ln_ulps: f64,
    /// `sin`, `cos` for |x| <= [`AccuracyRules::sin_cos_range`]: absolute.
    pub sin_cos_absolute: f64,
    /// The argument range of the `sin`/`cos` rule; beyond it the bound is infinite.
    pub sin_cos_range: f64,
    /// `atan2(y, x)`: ulps (never at the origin, where the result is arbitrary).
    pub atan2_ulps: f64,
    /// A constant printed as a decimal literal (a [`Node::Const`] or baked [`Node::Global`]):
    /// ulps between the literal's value and the device's. WGSL converts a literal that is not
    /// exactly representable with "correctly rounded" conversion (either neighbour); naga parses
    /// to the nearest, so the shortest round-trip digits give back the CPU's bits (0).
    pub literal_ulps: f64,
    /// Absolute error every non-exact device result may have on top: subnormal inputs and results
    /// may be flushed to zero (2^-126).
    pub flush: f64,
    /// The CPU's `+ - * / sqrt`: IEEE round to nearest, 0.5 ulp.
    pub cpu_ulps: f64,
    /// The CPU's `f32` `exp`, `ln`, `sin`, `cos`, `atan2` (the platform libm): ulps.
    pub cpu_libm_ulps: f64,
}

impl AccuracyRules {
    /// The WGSL rules as the shader tests apply them on llvmpipe ([`Tolerance`]'s constants in
    /// gpu.rs): `+ - *` 0.5 ulp rounded to nearest (x86 SSE/AVX arithmetic; measured 0.50 ulp),
    /// `/` 2.5 ulp, `sqrt` 9 ulp (inherited), `exp` 3.5 + 2|x| ulp (llvmpipe's measured
    /// exception to the specification's 3 + 2|x|), `log` 2^-21 absolute on [0.5, 2] else 3 ulp,
    /// `sin`/`cos` 2^-11 absolute, extended from [-pi, pi] to |x| <= 100 where llvmpipe was
    /// measured ([`LLVMPIPE_SIN_COS_RANGE`]), `atan2` 4096 ulp, the 2^-126 flush; the CPU
    /// (glibc 2.36's binary32 functions, under 1 ulp for exp/log/sin/cos and about 1.5 for
    /// atan2f by Zimmermann's 2021 survey) 2 ulp for its libm calls.
    pub fn wgsl_on_llvmpipe() -> Self {
        AccuracyRules {
            basic_ulps: Tolerance::CORRECTLY_ROUNDED.ulps,
            basic_round_to_nearest: true,
            division_ulps: Tolerance::DIVISION.ulps,
            sqrt_ulps: Tolerance::SQRT.ulps,
            exp_ulps: Tolerance::exp_llvmpipe(0.0).ulps,
            exp_ulps_per_x: Tolerance::exp_llvmpipe(1.0).ulps - Tolerance::exp_llvmpipe(0.0).ulps,
            ln_absolute: Tolerance::log(1.0).absolute,
            ln_ulps: Tolerance::log(4.0).ulps,
            sin_cos_absolute: Tolerance::SIN_COS.absolute,
            sin_cos_range: LLVMPIPE_SIN_COS_RANGE,
            atan2_ulps: Tolerance::ATAN.ulps,
            literal_ulps: 0.0,
            flush: Tolerance::ulps(0.0).absolute,
            cpu_ulps: 0.5,
            cpu_libm_ulps: 2.0,
        }
    }

    /// The specification alone, for any conforming device: `+ - *` either neighbour (1 ulp, no
    /// bit-identity with the CPU), `exp` 3 + 2|x| ulp, `sin`/`cos` only on [-pi, pi], decimal
    /// literals either neighbour; the rest as [`AccuracyRules::wgsl_on_llvmpipe`].
    pub fn wgsl_spec() -> Self {
        AccuracyRules {
            basic_ulps: 1.0,
            basic_round_to_nearest: false,
            exp_ulps: Tolerance::exp(0.0).ulps,
            exp_ulps_per_x: Tolerance::exp(1.0).ulps - Tolerance::exp(0.0).ulps,
            sin_cos_range: PI,
            literal_ulps: 1.0,
            ..Self::wgsl_on_llvmpipe()
        }
    }

    /// A device result's own error: `ulps` ulps at `magnitude` plus the flush.
    fn device(&self, ulps: f64, magnitude: f64) -> f64 {
        ulps * ulp_f32(magnitude) + self.flush
    }
}

/// Per output of `graph`, at `inputs`, a bound on |GPU result - CPU f32 result| for a device that
/// meets `rules` (the WGSL accuracy rules, with llvmpipe's measured exceptions). Infinite where
/// no rule bounds the device's result.
///
/// # Panics
/// If `inputs.len()` differs from [`Graph::input_count`].
pub fn gpu_error_bound(graph: &Graph, inputs: &[f32], rules: &AccuracyRules) -> Vec<f64> {
    BoundPlan::new(graph).analyse(inputs, rules).bounds
}

/// What [`BoundPlan::analyse`] finds at one input row.
#[derive(Clone, Debug, PartialEq)]
pub struct RowBound {
    /// The CPU's `f32` outputs (bit for bit [`Graph::eval_f32`]).
    pub values: Vec<f32>,
    /// Per output, the bound on |device - CPU|.
    pub bounds: Vec<f64>,
    /// Per output, for an infinite bound, the node kind where the bound first became infinite.
    pub causes: Vec<Option<&'static str>>,
    /// Live `sin`/`cos` nodes whose device argument may leave [-pi, pi] (where the
    /// specification's rule stops).
    pub sin_cos_beyond_pi: usize,
    /// Live `select`s whose mask the device may decide the other way.
    pub uncertain_selects: usize,
    /// Live `floor`s whose operand's interval crosses an integer (the device's result may jump).
    pub floor_jumps: usize,
}

/// The per-graph work of [`gpu_error_bound`], done once for many rows: the flat outputs, the live
/// nodes and the tables' slopes.
pub struct BoundPlan<'g> {
    graph: &'g Graph,
    outputs: Vec<u32>,
    live: Vec<bool>,
    tables: Vec<TableStats>,
}

/// Per channel of a table: the largest |sample|, the smallest sample, and per axis the largest
/// difference of adjacent samples along it (the interpolant's Lipschitz constant in units of the
/// sample index).
struct TableStats {
    max_abs: Vec<f64>,
    min: Vec<f64>,
    step: Vec<[f64; 3]>,
}

/// Largest block of samples (product of the extents) examined for a fetch's local slopes and
/// magnitude; a larger block uses the table's global figures.
const MAX_BLOCK: usize = 4096;

impl TableStats {
    fn new(table: &Table) -> Self {
        let nc = table.channels().len();
        let sizes = sizes(table);
        let mut stats = TableStats {
            max_abs: vec![0.0; nc],
            min: vec![f64::INFINITY; nc],
            step: vec![[0.0; 3]; nc],
        };
        let data = table.data();
        for k in 0..sizes[2] {
            for j in 0..sizes[1] {
                for i in 0..sizes[0] {
                    let index = [i, j, k];
                    let at = flat_index(&sizes, index) * nc;
                    for c in 0..nc {
                        let v = f64::from(data[at + c]);
                        stats.max_abs[c] = stats.max_abs[c].max(v.abs());
                        stats.min[c] = stats.min[c].min(v);
                        for d in 0..3 {
                            if index[d] + 1 < sizes[d] {
                                let mut next = index;
                                next[d] += 1;
                                let w = f64::from(data[flat_index(&sizes, next) * nc + c]);
                                stats.step[c][d] = stats.step[c][d].max((w - v).abs());
                            }
                        }
                    }
                }
            }
        }
        stats
    }
}

/// The sample counts of the table's axes, 1 beyond them.
fn sizes(table: &Table) -> [usize; 3] {
    let mut s = [1; 3];
    for (slot, axis) in s.iter_mut().zip(table.axes()) {
        *slot = axis.size();
    }
    s
}

/// The grid point's index in the layout of [`Table`] (channel 0).
fn flat_index(sizes: &[usize; 3], [i, j, k]: [usize; 3]) -> usize {
    (k * sizes[1] + j) * sizes[0] + i
}

/// Why a bound became infinite.
mod cause {
    pub const NON_FINITE: &str = "non-finite CPU value";
    pub const SQRT: &str = "sqrt of an operand that may be negative";
    pub const EXP: &str = "exp that may overflow";
    pub const LN: &str = "log of an operand that may be <= 0";
    pub const SIN_COS: &str = "sin/cos beyond the rule's range";
    pub const DIVISION: &str = "division by a divisor that may be 0 (or beyond 2^126)";
    pub const FETCH: &str = "fetch at a coordinate without a bound";
}

impl<'g> BoundPlan<'g> {
    /// The plan for `graph`: the flat nodes of its outputs ([`Graph::outputs`]), the live nodes
    /// and the tables' slopes.
    pub fn new(graph: &'g Graph) -> Self {
        let outputs = graph.outputs().to_vec();
        let nodes = graph.nodes();
        let mut live = vec![false; nodes.len()];
        for &o in &outputs {
            live[o as usize] = true;
        }
        for i in (0..nodes.len()).rev() {
            if live[i] {
                for k in nodes[i].operands() {
                    live[k as usize] = true;
                }
            }
        }
        BoundPlan {
            graph,
            outputs,
            live,
            tables: graph.tables().iter().map(|t| TableStats::new(t)).collect(),
        }
    }

    /// The CPU's outputs and their bounds at `inputs` under `rules`.
    ///
    /// # Panics
    /// If `inputs.len()` differs from [`Graph::input_count`], or if the per-node interpreter
    /// does not reproduce [`Graph::eval_f32`] bit for bit.
    pub fn analyse(&self, inputs: &[f32], rules: &AccuracyRules) -> RowBound {
        self.run(inputs, rules).0
    }

    /// [`BoundPlan::analyse`] and every node's value, bound and (for an infinite bound) the node
    /// where it became infinite.
    fn run(&self, inputs: &[f32], rules: &AccuracyRules) -> (RowBound, NodeTrace) {
        let graph = self.graph;
        assert_eq!(inputs.len(), graph.input_count(), "one value per input");
        let nodes = graph.nodes();
        let n = nodes.len();
        let mut value = vec![0.0f32; n];
        let mut truth = vec![false; n];
        let mut err = vec![0.0f64; n];
        // Where the device's value lies by interval arithmetic over the operations (beside the
        // CPU's value and the radius): `max(x, 1e-12) >= 1e-12`, `exp(-|x|) <= 1`, a floor that
        // may jump is one of two integers.
        let mut pieces = vec![Pieces::one(ANY); n];
        let mut certain = vec![true; n];
        let mut cause: Vec<Option<&'static str>> = vec![None; n];
        let mut root = vec![NONE; n];
        let (mut beyond_pi, mut uncertain, mut jumps) = (0, 0, 0);
        // Operand k: its pieces clipped to v +- e, and the hull of those as an `Operand`.
        let operand = |value: &[f32], err: &[f64], pieces: &[Pieces], k: u32| {
            let k = k as usize;
            let (v, e) = (f64::from(value[k]), err[k]);
            let parts = pieces[k].clip(v - e, v + e);
            let (lo, hi) = parts.hull();
            (Operand { v, e, lo, hi }, parts)
        };
        for (i, node) in nodes.iter().enumerate() {
            let op = |k: u32| operand(&value, &err, &pieces, k);
            // The node's CPU value, its bound, the pieces of the device's value, what made the
            // bound infinite (if it did), and the operands whose infinite bounds it inherits
            // (NONE-padded).
            let (v, bound, parts, own, from): (f32, f64, Pieces, Option<&'static str>, [u32; 3]) =
                match *node {
                    Node::Input(k) => {
                        let v = inputs[k as usize];
                        (
                            v,
                            subnormal(f64::from(v)),
                            Pieces::one(ANY),
                            None,
                            [NONE; 3],
                        )
                    }
                    Node::Const(_) | Node::Named { .. } | Node::Global(_) => {
                        let v = graph.constant(node).expect("a constant node");
                        let b = literal(f64::from(v), rules);
                        (v, b, Pieces::one(ANY), None, [NONE; 3])
                    }
                    Node::Result { .. } => unreachable!("the flat graph has no calls"),
                    Node::Unary(unary, a) => {
                        let v = apply_unary(unary, value[a as usize]);
                        let (x, xs) = op(a);
                        if matches!(unary, Unary::Sin | Unary::Cos)
                            && self.live[i]
                            && (x.lo < -PI || x.hi > PI)
                        {
                            beyond_pi += 1;
                        }
                        if unary == Unary::Floor && self.live[i] && x.lo.floor() != x.hi.floor() {
                            jumps += 1;
                        }
                        let whole = unary_bound(unary, x, v, rules);
                        let each =
                            xs.map(|lo, hi| unary_bound(unary, Operand { lo, hi, ..x }, v, rules));
                        let (b, mut parts, own) = joined(whole, each);
                        if unary == Unary::Floor {
                            parts = parts.integers();
                        }
                        (v, b, parts, own, [a, NONE, NONE])
                    }
                    Node::Binary(binary, a, b) => {
                        let v = apply_binary(binary, value[a as usize], value[b as usize]);
                        let ((x, xs), (y, ys)) = (op(a), op(b));
                        let same = a == b;
                        let whole = binary_bound(binary, x, y, same, v, rules);
                        let each = xs.pairs(&ys, same, |(xl, xh), (yl, yh)| {
                            let x = Operand {
                                lo: xl,
                                hi: xh,
                                ..x
                            };
                            let y = Operand {
                                lo: yl,
                                hi: yh,
                                ..y
                            };
                            binary_bound(binary, x, y, same, v, rules)
                        });
                        let (bound, parts, own) = joined(whole, each);
                        (v, bound, parts, own, [a, b, NONE])
                    }
                    Node::Less(a, b) | Node::LessEqual(a, b) => {
                        let ((x, _), (y, _)) = (op(a), op(b));
                        let (va, vb) = (value[a as usize], value[b as usize]);
                        if matches!(node, Node::Less(..)) {
                            truth[i] = va < vb;
                            certain[i] = x.hi < y.lo || x.lo >= y.hi;
                        } else {
                            truth[i] = va <= vb;
                            certain[i] = x.hi <= y.lo || x.lo > y.hi;
                        }
                        continue;
                    }
                    Node::And(a, b) | Node::Or(a, b) => {
                        let (ta, tb) = (truth[a as usize], truth[b as usize]);
                        let (ca, cb) = (certain[a as usize], certain[b as usize]);
                        // A certain false (for `&`) or true (for `|`) operand decides alone.
                        let decisive = matches!(node, Node::Or(..));
                        truth[i] = if decisive { ta | tb } else { ta & tb };
                        let decides = |c: bool, t: bool| c && t == decisive;
                        certain[i] = (ca && cb) || decides(ca, ta) || decides(cb, tb);
                        continue;
                    }
                    Node::Not(a) => {
                        truth[i] = !truth[a as usize];
                        certain[i] = certain[a as usize];
                        continue;
                    }
                    Node::Select(m, t, f) => {
                        let chosen_true = truth[m as usize];
                        let (chosen, other) = if chosen_true { (t, f) } else { (f, t) };
                        let v = <f32 as Real>::select(
                            chosen_true,
                            value[t as usize],
                            value[f as usize],
                        );
                        let ((c, cs), (o, os)) = (op(chosen), op(other));
                        if certain[m as usize] {
                            (v, c.e, cs, None, [chosen, NONE, NONE])
                        } else {
                            if self.live[i] {
                                uncertain += 1;
                            }
                            let b = c.e.max(o.e + (c.v - o.v).abs());
                            (v, b, cs.union(&os), None, [chosen, other, NONE])
                        }
                    }
                    Node::Fetch {
                        table,
                        coords,
                        channel,
                    } => {
                        let t = &graph.tables()[table as usize];
                        let dims = t.axes().len();
                        let mut x = [0.0f32; 3];
                        let mut ex = [0.0f64; 3];
                        let mut from = [NONE; 3];
                        for d in 0..dims {
                            let k = coords[d];
                            (x[d], ex[d], from[d]) = (value[k as usize], err[k as usize], k);
                        }
                        let mut out = [0.0f32; hairmath::lut::MAX_CHANNELS];
                        t.lookup_into(&x[..dims], &mut out[..t.channels().len()])
                            .unwrap_or_else(|_| unreachable!("one coordinate per axis"));
                        let stats = &self.tables[table as usize];
                        // Non-negative weights of non-negative texels.
                        let range = if stats.min[channel as usize] >= 0.0 {
                            (0.0, f64::INFINITY)
                        } else {
                            ANY
                        };
                        let (b, own) =
                            fetch_bound(t, stats, &x[..dims], &ex[..dims], channel as usize, rules);
                        (out[channel as usize], b, Pieces::one(range), own, from)
                    }
                };
            value[i] = v;
            pieces[i] = parts;
            // The device's value lies in the pieces: at most their farther end away.
            let (lo, hi) = parts.hull();
            let span = (f64::from(v) - lo).max(hi - f64::from(v));
            let bound = if span < bound { span } else { bound };
            let mut bound = bound * (1.0 + 1e-12);
            let mut own = own;
            if !v.is_finite() {
                bound = f64::INFINITY;
                own = own.or(Some(cause::NON_FINITE));
            }
            if bound.is_nan() || bound.is_infinite() {
                err[i] = f64::INFINITY;
                let inherited = from
                    .iter()
                    .copied()
                    .find(|&k| k != NONE && cause[k as usize].is_some());
                (cause[i], root[i]) = match inherited {
                    Some(k) => (cause[k as usize], root[k as usize]),
                    None => (own.or(Some("(unnamed)")), i as u32),
                };
            } else {
                err[i] = bound;
            }
        }
        let values: Vec<f32> = self.outputs.iter().map(|&o| value[o as usize]).collect();
        let reference = graph.eval_f32(inputs);
        assert!(
            values
                .iter()
                .zip(&reference)
                .all(|(a, b)| a.to_bits() == b.to_bits() || (a.is_nan() && b.is_nan())),
            "the per-node interpreter differs from Graph::eval_f32: {values:?} vs {reference:?}"
        );
        let row = RowBound {
            values,
            bounds: self.outputs.iter().map(|&o| err[o as usize]).collect(),
            causes: self.outputs.iter().map(|&o| cause[o as usize]).collect(),
            sin_cos_beyond_pi: beyond_pi,
            uncertain_selects: uncertain,
            floor_jumps: jumps,
        };
        (row, NodeTrace { value, err, root })
    }

    /// The nodes along the path from `output` back to the inputs through, at each node, the
    /// operand of the largest relative bound, where the relative bound grows more than tenfold
    /// (the operations that amplify the error), described.
    fn blame(&self, trace: &NodeTrace, output: u32) -> Vec<String> {
        let rel = |k: u32| {
            let (e, v) = (
                trace.err[k as usize],
                f64::from(trace.value[k as usize]).abs(),
            );
            if e == 0.0 {
                0.0
            } else {
                e / v
            }
        };
        let mut lines = Vec::new();
        let mut i = output;
        while let Some(k) = self.graph.nodes()[i as usize]
            .operands()
            .into_iter()
            .max_by(|&a, &b| rel(a).total_cmp(&rel(b)))
        {
            if rel(i) > 10.0 * rel(k) {
                lines.push(self.describe(trace, i));
            }
            i = k;
        }
        lines
    }

    /// A description of node `i` at one row: its kind, and each operand's CPU value and bound.
    fn describe(&self, trace: &NodeTrace, i: u32) -> String {
        let node = self.graph.nodes()[i as usize];
        let operands: Vec<String> = node
            .operands()
            .iter()
            .map(|&k| {
                let kind = format!("{:?}", self.graph.nodes()[k as usize]);
                let kind = kind.split('(').next().unwrap_or("").to_string();
                format!(
                    "{kind} {:e} +- {:.2e}",
                    trace.value[k as usize], trace.err[k as usize]
                )
            })
            .collect();
        format!(
            "{node:?} = {:e} +- {:.2e} of [{}]",
            trace.value[i as usize],
            trace.err[i as usize],
            operands.join(", ")
        )
    }
}

/// Every node's CPU value and bound at one row, and per node with an infinite bound the node where
/// its bound became infinite.
struct NodeTrace {
    value: Vec<f32>,
    err: Vec<f64>,
    root: Vec<u32>,
}

/// No operand (padding of the inherited-operand lists).
const NONE: u32 = u32::MAX;

/// Most pieces a node's device interval is split into.
const MAX_PIECES: usize = 4;

/// The set a device's value lies in: up to [`MAX_PIECES`] disjoint intervals in increasing
/// order. A floor whose operand may cross an integer yields the two integers, not the interval
/// between; operations apply to each piece (each pair of pieces) and `abs` of the two ends of a
/// wrapped angle, -pi and pi, merges them again.
#[derive(Clone, Copy, Debug)]
struct Pieces {
    n: usize,
    p: [(f64, f64); MAX_PIECES],
}

impl Pieces {
    fn one(interval: (f64, f64)) -> Self {
        let mut p = [(0.0, 0.0); MAX_PIECES];
        p[0] = interval;
        Pieces { n: 1, p }
    }

    fn hull(&self) -> (f64, f64) {
        (self.p[0].0, self.p[self.n - 1].1)
    }

    /// The pieces of `list`: sorted, overlapping ones merged, then the closest neighbours merged
    /// until at most [`MAX_PIECES`] remain. An empty list or a NaN end gives everything.
    fn of(list: &mut [(f64, f64)]) -> Self {
        if list.is_empty() || list.iter().any(|(a, b)| a.is_nan() || b.is_nan()) {
            return Pieces::one(ANY);
        }
        list.sort_by(|a, b| a.0.total_cmp(&b.0));
        let mut out: Vec<(f64, f64)> = Vec::with_capacity(list.len());
        for &(lo, hi) in list.iter() {
            match out.last_mut() {
                Some(last) if lo <= last.1 => last.1 = last.1.max(hi),
                _ => out.push((lo, hi)),
            }
        }
        while out.len() > MAX_PIECES {
            let k = (0..out.len() - 1)
                .min_by(|&a, &b| (out[a + 1].0 - out[a].1).total_cmp(&(out[b + 1].0 - out[b].1)))
                .unwrap_or(0);
            out[k].1 = out[k + 1].1;
            out.remove(k + 1);
        }
        let mut pieces = Pieces::one(out[0]);
        pieces.n = out.len();
        pieces.p[..out.len()].copy_from_slice(&out);
        pieces
    }

    /// The pieces intersected with [lo, hi]; [lo, hi] itself if nothing is left (which only
    /// rounding in this analysis could cause: the device's value lies in both).
    fn clip(&self, lo: f64, hi: f64) -> Self {
        let mut list = [(0.0, 0.0); MAX_PIECES];
        let mut m = 0;
        for &(a, b) in &self.p[..self.n] {
            let (a, b) = (a.max(lo), b.min(hi));
            if a <= b {
                list[m] = (a, b);
                m += 1;
            }
        }
        if m == 0 {
            return Pieces::one((lo, hi));
        }
        let mut pieces = Pieces::one(list[0]);
        pieces.n = m;
        pieces.p[..m].copy_from_slice(&list[..m]);
        pieces
    }

    fn union(&self, other: &Pieces) -> Self {
        let mut list: Vec<(f64, f64)> = self.p[..self.n].to_vec();
        list.extend_from_slice(&other.p[..other.n]);
        Pieces::of(&mut list)
    }

    /// Each piece of floor results `[a, b]` spanning at most four integers as those integers.
    fn integers(&self) -> Self {
        let mut list = Vec::new();
        for &(a, b) in &self.p[..self.n] {
            if b - a <= 3.0 {
                let mut k = a;
                while k <= b {
                    list.push((k, k));
                    k += 1.0;
                }
            } else {
                list.push((a, b));
            }
        }
        Pieces::of(&mut list)
    }

    /// `f` of each piece, when there is more than one.
    fn map(&self, f: impl Fn(f64, f64) -> Bound) -> Option<Vec<Bound>> {
        (self.n > 1).then(|| self.p[..self.n].iter().map(|&(a, b)| f(a, b)).collect())
    }

    /// `f` of each pair of pieces (of each piece with itself for the same operand), when either
    /// side has more than one.
    fn pairs(
        &self,
        other: &Pieces,
        same: bool,
        f: impl Fn((f64, f64), (f64, f64)) -> Bound,
    ) -> Option<Vec<Bound>> {
        if self.n == 1 && other.n == 1 {
            return None;
        }
        let mut out = Vec::new();
        for &x in &self.p[..self.n] {
            if same {
                out.push(f(x, x));
                continue;
            }
            for &y in &other.p[..other.n] {
                out.push(f(x, y));
            }
        }
        Some(out)
    }
}

/// A node's bound, pieces and cause from the rule applied to the operands' hulls (`whole`) and,
/// for split operands, to each piece (`each`): the radius of the whole (a valid bound whatever
/// the pieces), the union of the pieces' intervals; infinite only if a piece's rule gives
/// nothing.
fn joined(whole: Bound, each: Option<Vec<Bound>>) -> (f64, Pieces, Option<&'static str>) {
    let Some(each) = each else {
        return (whole.0, Pieces::one(whole.1), whole.2);
    };
    if let Some(why) = each.iter().find_map(|b| b.2) {
        return (f64::INFINITY, Pieces::one(ANY), Some(why));
    }
    let mut list: Vec<(f64, f64)> = each.iter().map(|b| b.1).collect();
    let radius = if whole.2.is_some() {
        f64::INFINITY
    } else {
        whole.0
    };
    (radius, Pieces::of(&mut list), None)
}

/// The flush of a subnormal value (0 for zero and normal values).
fn subnormal(v: f64) -> f64 {
    if v != 0.0 && v.abs() < FLUSH {
        FLUSH
    } else {
        0.0
    }
}

/// The bound of a constant printed as a literal.
fn literal(v: f64, rules: &AccuracyRules) -> f64 {
    if v == 0.0 {
        0.0
    } else {
        rules.literal_ulps * ulp_f32(v) + subnormal(v)
    }
}

/// The bound of a correctly rounded `+ - *` whose exact result moves by at most `prop` with its
/// operands: the propagation, the device's rounding at the largest magnitude its exact result can
/// have, and the CPU's rounding. Exact operands on a round-to-nearest device give the CPU's bits.
fn rounded(prop: f64, v: f64, rules: &AccuracyRules) -> f64 {
    if prop == 0.0 && rules.basic_round_to_nearest {
        return subnormal(v);
    }
    let cpu = rules.cpu_ulps * ulp_f32(v);
    prop + rules.device(rules.basic_ulps, v.abs() + cpu + prop) + cpu
}

/// One operand as the bound rules see it: the CPU's value `v`, the bound `e` on the device's
/// value, and the interval `[lo, hi]` the device's value lies in: `v +- e` intersected with the
/// interval that interval arithmetic gives the device's result of the operation (`max(x, 1e-12)`
/// is at least 1e-12 on the device too, `exp(-|x|)` at most 1).
#[derive(Clone, Copy, Debug)]
struct Operand {
    v: f64,
    e: f64,
    lo: f64,
    hi: f64,
}

/// A node's bound, the interval of the device's value, and what made the bound infinite.
type Bound = (f64, (f64, f64), Option<&'static str>);

/// No structural bound on the device's value.
const ANY: (f64, f64) = (f64::NEG_INFINITY, f64::INFINITY);

/// Infinite, because of `why`.
fn unbounded(why: &'static str) -> Bound {
    (f64::INFINITY, ANY, Some(why))
}

/// The interval `[lo, hi]` of exact results widened by a device's error `error(magnitude)` at
/// each end. With `keeps_sign` (a rounded or ulp-accurate result: `+ - * / sqrt exp`), an end
/// that is 0 keeps its side: rounding and flushing keep a non-negative exact result
/// non-negative (for the ulp rules this assumes, as every implementation does, that an exact 0
/// or a positive subnormal does not come back negative); an absolute rule (`log` near 1,
/// `sin`, `cos`) may cross 0. NaN ends (from 0 * inf) make it unbounded.
fn widen(lo: f64, hi: f64, keeps_sign: bool, error: impl Fn(f64) -> f64) -> (f64, f64) {
    if lo.is_nan() || hi.is_nan() {
        return ANY;
    }
    let down = lo - error(lo.abs());
    let up = hi + error(hi.abs());
    if !keeps_sign {
        return (down, up);
    }
    (
        if lo >= 0.0 { down.max(0.0) } else { down },
        if hi <= 0.0 { up.min(0.0) } else { up },
    )
}

/// The smallest and largest of `values`, NaN if any is NaN.
fn hull(values: [f64; 4]) -> (f64, f64) {
    if values.iter().any(|v| v.is_nan()) {
        return (f64::NAN, f64::NAN);
    }
    (
        values.iter().copied().fold(f64::INFINITY, f64::min),
        values.iter().copied().fold(f64::NEG_INFINITY, f64::max),
    )
}

/// The bound of a unary operation of operand `x` whose CPU result is `v`.
fn unary_bound(op: Unary, x: Operand, v: f32, rules: &AccuracyRules) -> Bound {
    let v = f64::from(v);
    let Operand {
        v: a,
        e: ea,
        lo,
        hi,
    } = x;
    let libm = rules.cpu_libm_ulps * ulp_f32(v);
    match op {
        // Exact on both sides.
        Unary::Neg => (ea, (-hi, -lo), None),
        Unary::Abs => {
            let range = if lo >= 0.0 {
                (lo, hi)
            } else if hi <= 0.0 {
                (-hi, -lo)
            } else {
                (0.0, hi.max(-lo))
            };
            (ea, range, None)
        }
        // Exact: the same integer unless [lo, hi] crosses one; then the largest jump.
        Unary::Floor => {
            let range = (lo.floor(), hi.floor());
            ((v - range.0).max(range.1 - v), range, None)
        }
        Unary::Sqrt => {
            if lo.is_nan() || lo < 0.0 {
                return unbounded(cause::SQRT);
            }
            let prop = (hi.sqrt() - a.sqrt()).max(a.sqrt() - lo.sqrt());
            let cpu = rules.cpu_ulps * ulp_f32(v);
            let device = |m: f64| rules.device(rules.sqrt_ulps, m);
            let b = prop + device(hi.sqrt()) + cpu;
            (b, widen(lo.sqrt(), hi.sqrt(), true, device), None)
        }
        Unary::Exp => {
            if hi > LN_F32_MAX {
                return unbounded(cause::EXP);
            }
            // Increasing and convex: the upper end moves most (exp(hi) itself when the radius is
            // too large for expm1).
            let prop = if hi - a < 700.0 {
                a.exp() * (hi - a).exp_m1()
            } else {
                hi.exp()
            };
            let ulps = rules.exp_ulps + rules.exp_ulps_per_x * lo.abs().max(hi.abs());
            let device = |m: f64| rules.device(ulps, m);
            let b = prop + device(hi.exp()) + libm;
            (b, widen(lo.exp(), hi.exp(), true, device), None)
        }
        Unary::Ln => {
            if lo.is_nan() || lo <= 0.0 {
                return unbounded(cause::LN);
            }
            // Increasing and concave: the lower end moves most.
            let prop = (a.ln() - lo.ln()).max(hi.ln() - a.ln());
            let inside = lo >= 0.5 && hi <= 2.0;
            let outside = hi < 0.5 || lo > 2.0;
            let device = |m: f64| {
                let mut d = rules.flush;
                if !outside {
                    d += rules.ln_absolute;
                }
                if !inside {
                    d += rules.ln_ulps * ulp_f32(m);
                }
                d
            };
            let largest = lo.ln().abs().max(hi.ln().abs());
            (
                prop + device(largest) + libm,
                widen(lo.ln(), hi.ln(), false, |_| device(largest)),
                None,
            )
        }
        Unary::Sin | Unary::Cos => {
            if lo < -rules.sin_cos_range || hi > rules.sin_cos_range {
                return unbounded(cause::SIN_COS);
            }
            // 1-Lipschitz; second order: |f'(a)| ea + ea^2 / 2.
            let slope = if op == Unary::Sin {
                a.cos().abs()
            } else {
                a.sin().abs()
            };
            let prop = ea.min(slope * ea + 0.5 * ea * ea).min(2.0);
            let device = rules.sin_cos_absolute + rules.flush;
            let b = prop + device + libm;
            let (min, max) = sin_cos_extremes(op == Unary::Cos, lo, hi);
            (b, widen(min, max, false, |_| device), None)
        }
    }
}

/// The smallest and largest value of `sin` (`cos` if `cos`) on [lo, hi]: the ends' values and
/// those at the extrema inside (sin's at pi/2 + k pi, cos's at k pi).
fn sin_cos_extremes(cos: bool, lo: f64, hi: f64) -> (f64, f64) {
    if (hi - lo).is_nan() || hi - lo >= 2.0 * PI {
        return (-1.0, 1.0);
    }
    let f = |x: f64| if cos { x.cos() } else { x.sin() };
    let shift = if cos { 0.0 } else { 0.5 * PI };
    let (mut min, mut max) = (f(lo).min(f(hi)), f(lo).max(f(hi)));
    let mut k = ((lo - shift) / PI).ceil();
    while shift + k * PI <= hi {
        let y = f(shift + k * PI);
        (min, max) = (min.min(y), max.max(y));
        k += 1.0;
    }
    (min, max)
}

/// The bound of a binary operation of operands `x`, `y` (the same node if `same`) whose CPU
/// result is `v`.
fn binary_bound(
    op: Binary,
    x: Operand,
    y: Operand,
    same: bool,
    v: f32,
    rules: &AccuracyRules,
) -> Bound {
    let v = f64::from(v);
    let (a, ea, b, eb) = (x.v, x.e, y.v, y.e);
    let basic = |m: f64| rules.device(rules.basic_ulps, m);
    match op {
        Binary::Add => (
            rounded(ea + eb, v, rules),
            widen(x.lo + y.lo, x.hi + y.hi, true, basic),
            None,
        ),
        Binary::Sub => (
            rounded(ea + eb, v, rules),
            widen(x.lo - y.hi, x.hi - y.lo, true, basic),
            None,
        ),
        Binary::Mul => {
            let prop = a.abs() * eb + b.abs() * ea + ea * eb;
            let (lo, hi) = if same {
                let (l2, h2) = (x.lo * x.lo, x.hi * x.hi);
                if x.lo >= 0.0 {
                    (l2, h2)
                } else if x.hi <= 0.0 {
                    (h2, l2)
                } else {
                    (0.0, l2.max(h2))
                }
            } else {
                hull([x.lo * y.lo, x.lo * y.hi, x.hi * y.lo, x.hi * y.hi])
            };
            (rounded(prop, v, rules), widen(lo, hi, true, basic), None)
        }
        Binary::Div => {
            // |a'/b' - a/b| = |(a' - a) b - a (b' - b)| / |b b'|, |b'| >= the divisor's interval's
            // distance from 0.
            let nearest = if y.lo > 0.0 {
                y.lo
            } else if y.hi < 0.0 {
                -y.hi
            } else {
                0.0
            };
            if nearest.is_nan() || nearest < FLUSH || y.lo.abs().max(y.hi.abs()) > 2f64.powi(126) {
                return unbounded(cause::DIVISION);
            }
            let prop = (a.abs() * eb + b.abs() * ea) / (b.abs() * nearest);
            let cpu = rules.cpu_ulps * ulp_f32(v);
            let device = |m: f64| rules.device(rules.division_ulps, m);
            let bound = prop + device(v.abs() + cpu + prop) + cpu;
            let (lo, hi) = hull([x.lo / y.lo, x.lo / y.hi, x.hi / y.lo, x.hi / y.hi]);
            (bound, widen(lo, hi, true, device), None)
        }
        Binary::Atan2 => {
            let reach = PI + rules.device(rules.atan2_ulps, PI);
            (atan2_bound(a, ea, b, eb, v, rules), (-reach, reach), None)
        }
        // Exact; the device's result lies between the extremes of the operands' intervals.
        Binary::Min => (ea.max(eb), (x.lo.min(y.lo), x.hi.min(y.hi)), None),
        Binary::Max => (ea.max(eb), (x.lo.max(y.lo), x.hi.max(y.hi)), None),
    }
}

/// The bound of `atan2(y, x)` (CPU result `v`): the angle the device's point, anywhere in the box
/// of half-widths (ex, ey) about (x, y), can make with the CPU's, plus the rule's 4096 ulp and the
/// CPU's libm error; the whole range 2 pi (plus the rule) when the box reaches the origin or
/// crosses the branch cut on the negative x axis (the interval of the result, [-pi, pi] widened
/// by the rule, may then bound it more tightly).
fn atan2_bound(y: f64, ey: f64, x: f64, ex: f64, v: f64, rules: &AccuracyRules) -> f64 {
    let cpu = rules.cpu_libm_ulps * ulp_f32(v);
    let whole = 2.0 * PI + rules.device(rules.atan2_ulps, PI) + cpu;
    let r = x.hypot(y);
    let d = ex.hypot(ey);
    if d.is_nan() || r.is_nan() || d >= r {
        // The origin (atan2(0, 0) is arbitrary: llvmpipe returns 2.356) is in reach.
        return whole;
    }
    if ey > 0.0 && y.abs() <= ey && x - ex < 0.0 {
        return whole;
    }
    // sin of the angle between p and p' is |p x p'| / (|p| |p'|) <= (|x| ey + |y| ex) / (r (r - d)),
    // and the angle is below pi / 2 since the disk of radius d < r misses the origin; it is also
    // at most asin(d / r).
    let prop = if d == 0.0 {
        0.0
    } else {
        let cross = (x.abs() * ey + y.abs() * ex) / (r * (r - d));
        cross.min(1.0).asin().min((d / r).min(1.0).asin())
    };
    (prop + rules.device(rules.atan2_ulps, v.abs() + cpu + prop) + cpu).min(whole)
}

/// The bound of channel `channel` of a fetch from `table` at the CPU coordinates `at` (bounds
/// `ex`), interpolated in shader arithmetic as [`Table::lookup_into`] does (texels read exactly
/// with `textureLoad`).
///
/// Both sides compute per axis `t = clamp((x - min) * inv, 0, 1) * last` and interpolate the
/// exact texels at `t` with rounded weights. Write J(t) for the exact multilinear interpolant of
/// the samples (continuous across cells). Then
///
/// `|device - CPU| <= sum_d step_d |t_dev,d - t_cpu,d| + R_dev + R_cpu`,
///
/// - `step_d`: the largest difference of adjacent samples along axis d within the block of cells
///   the two t can reach (the table's global figure for a block of more than [`MAX_BLOCK`]
///   samples): J's Lipschitz constant along d there;
/// - `|t_dev - t_cpu|`: the coordinate's bound times `last * inv`, plus the rounding of
///   `x - min`, `* inv` and `* last` on each side (the clamp is exact and 1-Lipschitz, the
///   difference at most `last`; 0 when both sides clamp to the same edge);
/// - `R`: the rounding of the weights and the sum: each of the 2^D terms `w v` passes through at
///   most n = 2D + 2^D - 1 rounded operations (D subtractions `1 - f`, D - 1 products of
///   factors, the product with the texel, 2^D - 1 additions; `f = t - i0` is exact by
///   Sterbenz), so `R <= gamma_n sum |w v| <= gamma_n max |v|` over the cell, with
///   `gamma_n = n u / (1 - n u)`, u the relative rounding of one operation (0.5 ulp: 2^-24).
fn fetch_bound(
    table: &Table,
    stats: &TableStats,
    at: &[f32],
    ex: &[f64],
    channel: usize,
    rules: &AccuracyRules,
) -> (f64, Option<&'static str>) {
    if ex.iter().any(|e| !e.is_finite()) {
        return (f64::INFINITY, Some(cause::FETCH));
    }
    let dims = at.len();
    let sizes = sizes(table);
    let mut spread = [0.0f64; 3];
    let mut t_cpu = [0.0f64; 3];
    for (d, axis) in table.axes().iter().enumerate() {
        let last = (axis.size() - 1) as f64;
        let min32 = axis.min() as f32;
        let inv32 = (1.0 / (axis.max() - axis.min())) as f32;
        let inv = f64::from(inv32);
        // The CPU's f32 steps, as axis_cell computes them.
        let s = at[d] - min32;
        let p = s * inv32;
        let t = <f32 as Real>::min(<f32 as Real>::max(p, 0.0), 1.0) * last as f32;
        t_cpu[d] = f64::from(t);
        // The rounding of p on one side, whose s and p are larger by `grow` and `grow * inv`.
        let p_rounding = |ulps: f64, flush: f64, grow: f64| {
            let es = ulps * ulp_f32(f64::from(s).abs() + grow) + flush;
            inv * es + ulps * ulp_f32(f64::from(p).abs() + grow * inv + es * inv) + flush
        };
        let dev = p_rounding(rules.basic_ulps, rules.flush, ex[d]);
        let cpu = p_rounding(rules.cpu_ulps, 0.0, 0.0);
        let p_spread = inv * ex[d] + dev + cpu;
        let pc = f64::from(p);
        spread[d] = if pc - p_spread > 1.0 || pc + p_spread < 0.0 {
            0.0
        } else {
            let t_mag = (t_cpu[d] + last * p_spread.min(1.0)).min(last);
            let spread = last * p_spread.min(1.0)
                + rules.device(rules.basic_ulps, t_mag)
                + rules.cpu_ulps * ulp_f32(t_cpu[d]);
            spread.min(last)
        };
    }
    // The block of samples the two t can reach.
    let mut lo = [0usize; 3];
    let mut hi = [0usize; 3];
    let mut volume = 1usize;
    for d in 0..dims {
        let last = sizes[d] - 1;
        let t_lo = (t_cpu[d] - spread[d]).max(0.0);
        let t_hi = (t_cpu[d] + spread[d]).min(last as f64);
        lo[d] = (t_lo.floor() as usize).min(last - 1);
        hi[d] = ((t_hi.floor() as usize) + 1).max(lo[d] + 1).min(last);
        volume = volume.saturating_mul(hi[d] - lo[d] + 1);
    }
    let (step, largest) = if volume <= MAX_BLOCK {
        block_stats(table, &sizes, channel, &lo[..dims], &hi[..dims])
    } else {
        (stats.step[channel], stats.max_abs[channel])
    };
    let terms = 2 * dims + (1 << dims) - 1;
    let gamma = |ulps: f64| {
        let u = terms as f64 * ulps * 2f64.powi(-23);
        u / (1.0 - u)
    };
    let moved: f64 = (0..dims).map(|d| step[d] * spread[d]).sum();
    let rounding =
        (gamma(rules.basic_ulps) + gamma(rules.cpu_ulps)) * largest + terms as f64 * rules.flush;
    (moved + rounding, None)
}

/// The largest adjacent difference per axis and the largest |sample| of channel `channel` over
/// the block of grid points `lo..=hi` (per axis).
fn block_stats(
    table: &Table,
    sizes: &[usize; 3],
    channel: usize,
    lo: &[usize],
    hi: &[usize],
) -> ([f64; 3], f64) {
    let nc = table.channels().len();
    let data = table.data();
    let range = |d: usize| {
        if d < lo.len() {
            lo[d]..=hi[d]
        } else {
            0..=0
        }
    };
    let mut step = [0.0f64; 3];
    let mut largest = 0.0f64;
    for k in range(2) {
        for j in range(1) {
            for i in range(0) {
                let index = [i, j, k];
                let v = f64::from(data[flat_index(sizes, index) * nc + channel]);
                largest = largest.max(v.abs());
                for d in 0..lo.len() {
                    if index[d] < hi[d] {
                        let mut next = index;
                        next[d] += 1;
                        let w = f64::from(data[flat_index(sizes, next) * nc + channel]);
                        step[d] = step[d].max((w - v).abs());
                    }
                }
            }
        }
    }
    (step, largest)
}

/// `op` in f32 as [`Graph::eval_f32`] applies it (the `f32` [`Real`] instantiation).
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

/// `op` in f32 as [`Graph::eval_f32`] applies it.
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

// ---------------------------------------------------------------------------------------------
// Reference evaluations for the tests: the graph in f64 (a device with no error), and a simulated
// device that spends each rule's allowance on every operation.

/// How [`device_eval`] evaluates: exactly in f64, or as a simulated f32 device.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Device {
    /// Every operation in f64 on f64 values; fetches interpolated in f64.
    Exact,
    /// f32 values; `+ - *` rounded to nearest, every other operation off its exact value by
    /// almost all its rule allows (a pseudo-random sign, the full allowance three times in four),
    /// subnormal inputs and results flushed to zero if `flush`.
    Simulated { seed: u64, flush: bool },
}

/// A splitmix64 stream.
struct Stream(u64);

impl Stream {
    fn next(&mut self) -> f64 {
        self.0 = self.0.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        ((z ^ (z >> 31)) >> 11) as f64 / (1u64 << 53) as f64
    }
    /// A signed share of an allowance: +-1 three times in four, else uniform in [-1, 1].
    fn share(&mut self) -> f64 {
        let sign = if self.next() < 0.5 { -1.0 } else { 1.0 };
        if self.next() < 0.75 {
            sign
        } else {
            sign * self.next()
        }
    }
}

/// `graph`'s outputs at `inputs` on `device` under `rules` (as f64).
fn device_eval(graph: &Graph, inputs: &[f32], device: Device, rules: &AccuracyRules) -> Vec<f64> {
    let outputs = graph.outputs().to_vec();
    let value = device_nodes(graph, inputs, device, rules);
    outputs.iter().map(|&o| value[o as usize]).collect()
}

/// Every node's value in [`device_eval`] (0 for booleans).
fn device_nodes(graph: &Graph, inputs: &[f32], device: Device, rules: &AccuracyRules) -> Vec<f64> {
    let nodes = graph.nodes();
    let mut value = vec![0.0f64; nodes.len()];
    let mut truth = vec![false; nodes.len()];
    let (mut stream, flush) = match device {
        Device::Exact => (Stream(0), false),
        Device::Simulated { seed, flush } => (Stream(seed), flush),
    };
    let simulated = device != Device::Exact;
    // A simulated result: exact value `x` moved by a share of `allowance` (kept inside it after
    // the rounding to f32, which adds up to half an ulp), flushed if subnormal.
    let settle = |x: f64, allowance: f64, stream: &mut Stream| -> f64 {
        if !simulated {
            return x;
        }
        let room = (allowance - 0.5 * ulp_f32(x)).max(0.0);
        let r = f64::from((x + stream.share() * room) as f32);
        if flush && r.abs() < FLUSH {
            0.0
        } else {
            r
        }
    };
    for (i, node) in nodes.iter().enumerate() {
        let v = |k: u32| value[k as usize];
        value[i] = match *node {
            Node::Input(k) => {
                let x = f64::from(inputs[k as usize]);
                if flush && x.abs() < FLUSH {
                    0.0
                } else {
                    x
                }
            }
            Node::Const(_) | Node::Named { .. } | Node::Global(_) => {
                f64::from(graph.constant(node).expect("a constant node"))
            }
            Node::Result { .. } => unreachable!("flat"),
            Node::Unary(op, a) => {
                let x = v(a);
                let exact = match op {
                    Unary::Neg => -x,
                    Unary::Sqrt => x.sqrt(),
                    Unary::Exp => x.exp(),
                    Unary::Ln => x.ln(),
                    Unary::Sin => x.sin(),
                    Unary::Cos => x.cos(),
                    Unary::Abs => x.abs(),
                    Unary::Floor => x.floor(),
                };
                let allowance = match op {
                    Unary::Neg | Unary::Abs | Unary::Floor => 0.0,
                    Unary::Sqrt => rules.sqrt_ulps * ulp_f32(exact),
                    Unary::Exp => {
                        (rules.exp_ulps + rules.exp_ulps_per_x * x.abs()) * ulp_f32(exact)
                    }
                    Unary::Ln if (0.5..=2.0).contains(&x) => rules.ln_absolute,
                    Unary::Ln => rules.ln_ulps * ulp_f32(exact),
                    Unary::Sin | Unary::Cos => rules.sin_cos_absolute,
                };
                settle(exact, allowance, &mut stream)
            }
            Node::Binary(op, a, b) => {
                let (x, y) = (v(a), v(b));
                if simulated && matches!(op, Binary::Add | Binary::Sub | Binary::Mul) {
                    let r = f64::from(apply_binary(op, x as f32, y as f32));
                    if flush && r.abs() < FLUSH {
                        0.0
                    } else {
                        r
                    }
                } else {
                    let exact = match op {
                        Binary::Add => x + y,
                        Binary::Sub => x - y,
                        Binary::Mul => x * y,
                        Binary::Div => x / y,
                        Binary::Atan2 if simulated && x == 0.0 && y == 0.0 => 2.356,
                        Binary::Atan2 => x.atan2(y),
                        Binary::Min => <f64 as Real>::min(x, y),
                        Binary::Max => <f64 as Real>::max(x, y),
                    };
                    let allowance = match op {
                        Binary::Div => rules.division_ulps * ulp_f32(exact),
                        Binary::Atan2 => rules.atan2_ulps * ulp_f32(exact),
                        _ => 0.0,
                    };
                    settle(exact, allowance, &mut stream)
                }
            }
            Node::Less(a, b) => {
                truth[i] = v(a) < v(b);
                0.0
            }
            Node::LessEqual(a, b) => {
                truth[i] = v(a) <= v(b);
                0.0
            }
            Node::And(a, b) => {
                truth[i] = truth[a as usize] & truth[b as usize];
                0.0
            }
            Node::Or(a, b) => {
                truth[i] = truth[a as usize] | truth[b as usize];
                0.0
            }
            Node::Not(a) => {
                truth[i] = !truth[a as usize];
                0.0
            }
            Node::Select(m, t, f) => {
                if truth[m as usize] {
                    v(t)
                } else {
                    v(f)
                }
            }
            Node::Fetch {
                table,
                coords,
                channel,
            } => {
                let t = &graph.tables()[table as usize];
                let dims = t.axes().len();
                if simulated {
                    // A device interpolating in f32 round-to-nearest arithmetic.
                    let at: Vec<f32> = coords[..dims].iter().map(|&k| v(k) as f32).collect();
                    let mut out = vec![0.0f32; t.channels().len()];
                    t.lookup_into(&at, &mut out).unwrap();
                    f64::from(out[channel as usize])
                } else {
                    let at: Vec<f64> = coords[..dims].iter().map(|&k| v(k)).collect();
                    lookup_f64(t, &at, channel as usize)
                }
            }
        };
    }
    value
}

/// [`Table::lookup_into`]'s interpolation in f64 (weights from `axis_cell::<f64>`).
fn lookup_f64(table: &Table, at: &[f64], channel: usize) -> f64 {
    let dims = at.len();
    let mut base = [0usize; 3];
    let mut frac = [0.0f64; 3];
    for (d, (axis, &x)) in table.axes().iter().zip(at).enumerate() {
        let (i0, f) = hairmath::lut::axis_cell::<f64>(x, axis.min(), axis.max(), axis.size());
        base[d] = i0 as usize;
        frac[d] = f;
    }
    let mut out = 0.0;
    for corner in 0..(1usize << dims) {
        let mut w = 1.0;
        let mut index = [0usize; 3];
        for d in 0..dims {
            let upper = (corner >> d) & 1 == 1;
            index[d] = base[d] + usize::from(upper);
            w *= if upper { frac[d] } else { 1.0 - frac[d] };
        }
        out += w * f64::from(table.get(&index[..dims], channel).unwrap());
    }
    out
}

// ---------------------------------------------------------------------------------------------
// Tests

use super::gpu::device;
use hairmath::bcsdf::{
    trace_eval_with, ChiangFarField, ChiangHair, FarFieldRule, FromInputs, UniformsIn,
    DEFAULT_FAR_FIELD_NODES,
};
use hairmath::lut::{Axis, SharedTable};
use hairmath::models::Approximation;
use hairmath::params::HairParams;
use hairmath::real::{pi, trace, wrap_angle, Traced};
use hairmath::registry::MODELS;
use rand::{Rng, SeedableRng};

/// Checks `bound >= |reference - cpu|` output by output; returns the largest ratio of the
/// difference to the bound and the number of infinite bounds. A NaN reference under a finite
/// bound is a failure.
fn covered(name: &str, row: &[f32], bound: &RowBound, reference: &[f64]) -> (f64, usize) {
    let mut worst = 0.0f64;
    let mut infinite = 0;
    for (k, ((&b, &v), &r)) in bound
        .bounds
        .iter()
        .zip(&bound.values)
        .zip(reference)
        .enumerate()
    {
        if b.is_infinite() {
            infinite += 1;
            continue;
        }
        let diff = (r - f64::from(v)).abs();
        assert!(
            diff <= b,
            "{name}: output {k} at {row:?}: |{r:e} - {v:e}| = {diff:e} exceeds the bound {b:e}"
        );
        if b > 0.0 {
            worst = worst.max(diff / b);
        }
    }
    (worst, infinite)
}

/// A 2D table of a smooth positive function on [-1, 2] x [0, 3], 17 x 9 samples, two channels.
fn smooth_table() -> SharedTable<2, 2> {
    let axes = vec![
        Axis::new("u", -1.0, 2.0, 17).unwrap(),
        Axis::new("v", 0.0, 3.0, 9).unwrap(),
    ];
    let mut data = Vec::new();
    for j in 0..9 {
        for i in 0..17 {
            let (u, v) = (axes[0].sample(i), axes[1].sample(j));
            data.push((2.0 + u.sin() * v.cos()) as f32);
            data.push((u * v - 0.5 * v) as f32);
        }
    }
    SharedTable::new(Table::new(axes, vec!["a".into(), "b".into()], data).unwrap()).unwrap()
}

/// A small expression: its name, graph, input ranges, and whether its bound must be below 1e-5
/// of |value|.
type SmallGraph = (&'static str, Graph, Vec<(f32, f32)>, bool);

/// Small expressions over two or three inputs (name, graph, input ranges, whether the bound must
/// be below 1e-5 of |value|).
fn small_graphs() -> Vec<SmallGraph> {
    let table = smooth_table();
    vec![
        (
            "gaussian",
            trace(2, |a| {
                let (x, b) = (a[0], a[1]);
                vec![(-(x * x) / (Traced::c(2.0) * b * b)).exp() / (b * Traced::c(2.5066))]
            }),
            vec![(-2.0, 2.0), (0.5, 2.0)],
            true,
        ),
        (
            "polynomial and quotient",
            trace(3, |a| {
                let (x, y, z) = (a[0], a[1], a[2]);
                vec![
                    x * x * y + Traced::c(3.0) * z + x / (y + Traced::c(2.0)),
                    (x * x + y * y).sqrt(),
                ]
            }),
            vec![(0.1, 3.0), (0.5, 2.0), (0.2, 1.0)],
            true,
        ),
        (
            "log and exp",
            trace(2, |a| {
                let (x, y) = (a[0], a[1]);
                vec![
                    (Traced::c(1.0) + x * x).ln() + (-y).exp(),
                    (x * y + Traced::c(4.0)).ln(),
                ]
            }),
            vec![(0.3, 4.0), (0.1, 5.0)],
            true,
        ),
        (
            "wrapped angle, sin and cos",
            trace(2, |a| {
                let (x, y) = (a[0], a[1]);
                let w = wrap_angle(x * Traced::c(3.0) + y);
                vec![w.sin() * y + w.cos(), w]
            }),
            vec![(-4.0, 4.0), (-1.0, 1.0)],
            false,
        ),
        (
            "atan2 and select",
            trace(2, |a| {
                let (x, y) = (a[0], a[1]);
                let m = x.lt(y * y);
                vec![Traced::select(
                    m,
                    y.atan2(x) * Traced::c(0.5),
                    (x - y).exp() - Traced::c(1.0),
                )]
            }),
            vec![(-2.0, 2.0), (-2.0, 2.0)],
            false,
        ),
        (
            "table fetch",
            trace(2, |a| {
                let (x, y) = (a[0], a[1]);
                // Inexact coordinates (a quotient, a square root), the first beyond the axis.
                let [p, q] = Traced::sample_table(&table, [x / y, y.sqrt() + Traced::c(0.5)]);
                vec![p, q * x]
            }),
            vec![(0.25, 1.5), (0.5, 2.0)],
            false,
        ),
    ]
}

/// Rows of the input ranges: random, plus the ranges' corners.
fn random_rows(ranges: &[(f32, f32)], count: usize, seed: u64) -> Vec<Vec<f32>> {
    let mut random = rand_pcg::Pcg64::seed_from_u64(seed);
    let mut rows: Vec<Vec<f32>> = (0..1usize << ranges.len())
        .map(|corner| {
            ranges
                .iter()
                .enumerate()
                .map(|(d, &(lo, hi))| if (corner >> d) & 1 == 1 { hi } else { lo })
                .collect()
        })
        .collect();
    while rows.len() < count {
        rows.push(
            ranges
                .iter()
                .map(|&(lo, hi)| random.random_range(lo..=hi))
                .collect(),
        );
    }
    rows
}

/// On small expressions the bound covers the difference between the f32 evaluation and both an
/// exact f64 evaluation and a simulated device that spends almost every rule's full allowance
/// (with and without flushing subnormals); for the well-conditioned ones it is finite and below
/// 1e-5 of |value|. The per-node interpreter matches `Graph::eval_f32` bit for bit (checked on
/// every row by `BoundPlan::analyse`).
#[test]
fn bounds_cover_f64_and_simulated_devices_on_small_graphs() {
    let rules = AccuracyRules::wgsl_on_llvmpipe();
    let unrounded = AccuracyRules {
        basic_round_to_nearest: false,
        ..rules
    };
    for (name, graph, ranges, conditioned) in small_graphs() {
        let plan = BoundPlan::new(&graph);
        let (mut worst_exact, mut worst_sim, mut worst_rel, mut infinite) =
            (0.0f64, 0.0f64, 0.0f64, 0);
        for (r, row) in random_rows(&ranges, 4000, 11).iter().enumerate() {
            let bound = plan.analyse(row, &rules);
            // Exact f64 arithmetic does not round as the CPU does: no bit-identity for exact
            // operands.
            let exact_bound = plan.analyse(row, &unrounded);
            let exact = device_eval(&graph, row, Device::Exact, &rules);
            let (w, inf) = covered(name, row, &exact_bound, &exact);
            worst_exact = worst_exact.max(w);
            infinite += inf;
            let sim = Device::Simulated {
                seed: r as u64,
                flush: r % 2 == 0,
            };
            let simulated = device_eval(&graph, row, sim, &rules);
            worst_sim = worst_sim.max(covered(name, row, &bound, &simulated).0);
            // The spec's rules are never tighter than llvmpipe's where both are finite.
            let spec = plan.analyse(row, &AccuracyRules::wgsl_spec());
            for (s, l) in spec.bounds.iter().zip(&bound.bounds) {
                assert!(
                    s >= l || l.is_infinite(),
                    "{name}: spec {s:e} < llvmpipe {l:e}"
                );
            }
            for (&b, &v) in bound.bounds.iter().zip(&bound.values) {
                if conditioned {
                    let rel = b / f64::from(v).abs();
                    assert!(rel < 1e-5, "{name} at {row:?}: bound {b:e} for {v:e}");
                    worst_rel = worst_rel.max(rel);
                }
            }
        }
        eprintln!(
            "{name:>26}: |f64 - f32| at most {worst_exact:.3} of the bound, simulated device \
             {worst_sim:.3}; {infinite} infinite bounds{}",
            if conditioned {
                format!("; bound at most {worst_rel:.2e} of |value|")
            } else {
                String::new()
            }
        );
        if conditioned {
            assert_eq!(infinite, 0, "{name}");
        }
    }
}

/// Hand-picked cases of the rules: an exact product keeps a zero bound on a round-to-nearest
/// device, a square root of a clamped quantity stays finite, a comparison at a tie makes the
/// select's bound the gap, atan2 across the branch cut is bounded by 2 pi and at the origin by
/// pi (the CPU's 0 against anything in range), a log near zero is infinite (and says why), floor
/// across an integer jumps by 1.
#[test]
fn the_rules_behave_at_their_edges() {
    let rules = AccuracyRules::wgsl_on_llvmpipe();
    let g = trace(2, |a| {
        vec![a[0] * a[1], (a[0] - a[1]).max(Traced::c(0.0)).sqrt()]
    });
    let b = gpu_error_bound(&g, &[1.5, 1.5 + f32::EPSILON], &rules);
    assert_eq!(b[0], 0.0);
    assert!(b[1].is_finite(), "{b:?}");
    assert!(gpu_error_bound(&g, &[1.5, 1.5], &AccuracyRules::wgsl_spec())[0] > 0.0);

    // (x * 3) / 3 compared with x: within the product's rounding of a tie.
    let g = trace(1, |a| {
        let y = a[0] * Traced::c(3.0) / Traced::c(3.0);
        vec![Traced::select(
            y.lt(a[0]),
            Traced::c(10.0),
            Traced::c(-10.0),
        )]
    });
    let b = gpu_error_bound(&g, &[0.1], &rules);
    assert!(b[0] >= 20.0 && b[0] < 21.0, "{b:?}");

    let g = trace(2, |a| vec![a[0].atan2(a[1] - Traced::c(1.0))]);
    // At the origin (after an inexact subtraction) and on the negative x axis with y uncertain.
    let at_origin = gpu_error_bound(&g, &[0.0, 1.0], &rules)[0];
    assert!(at_origin > PI && at_origin < PI + 1e-2, "{at_origin}");
    let g = trace(2, |a| vec![(a[0] * Traced::c(0.1)).atan2(a[1])]);
    let cut = gpu_error_bound(&g, &[0.0, -1.0], &rules)[0];
    assert!(cut < 1.1e-3, "y = 0 exactly: {cut}");
    let cut = gpu_error_bound(&g, &[1e-38, -1.0], &rules)[0];
    assert!(cut >= 2.0 * PI, "y within its bound of 0: {cut}");

    let g = trace(1, |a| vec![(a[0] * Traced::c(0.1)).ln()]);
    let plan = BoundPlan::new(&g);
    let row = plan.analyse(&[1e-38], &rules);
    assert!(row.bounds[0].is_infinite());
    assert_eq!(row.causes[0], Some(cause::LN));
    assert!(plan.analyse(&[0.5], &rules).bounds[0] < 2e-6);

    let g = trace(1, |a| vec![(a[0] / Traced::c(10.0)).floor()]);
    assert!((gpu_error_bound(&g, &[30.0], &rules)[0] - 1.0).abs() < 1e-9);
    assert_eq!(gpu_error_bound(&g, &[35.0], &rules)[0], 0.0);
}

/// The WGSL kernel of the three expressions of [`gpu_graph`] over rows (x, y), written by hand in
/// the operation order of the traced code, constants as exact bit patterns.
fn gpu_kernel() -> String {
    let k = |x: f64| format!("bitcast<f32>({:#010x}u)", (x as f32).to_bits());
    format!(
        "@group(0) @binding(0) var<storage, read> hair_queries: array<f32>;
@group(0) @binding(1) var<storage, read_write> hair_values: array<f32>;

@compute @workgroup_size(64)
fn hair_main(@builtin(global_invocation_id) id: vec3<u32>) {{
    let row = id.x + id.y * 4194240u;
    if row >= arrayLength(&hair_values) / 3u {{
        return;
    }}
    let x = hair_queries[row * 2u];
    let y = hair_queries[row * 2u + 1u];
    let gaussian = exp(-(x * x) / ({two} * y * y)) / (y * {norm});
    let angle = select(exp(x - y) - {one}, atan2(y, x) * {half}, x < y * y);
    let w = x - {two_pi} * floor((x + {pi}) * {inv_two_pi});
    let mixed = cos(w) * sqrt(max(y, {zero})) + log(abs(x) + {quarter});
    hair_values[row * 3u] = gaussian;
    hair_values[row * 3u + 1u] = angle;
    hair_values[row * 3u + 2u] = mixed;
}}
",
        two = k(2.0),
        norm = k(2.5066),
        one = k(1.0),
        half = k(0.5),
        two_pi = k(2.0 * PI),
        pi = k(PI),
        inv_two_pi = k(0.5 * std::f64::consts::FRAC_1_PI),
        zero = k(0.0),
        quarter = k(0.25),
    )
}

/// The traced counterpart of [`gpu_kernel`].
fn gpu_graph() -> Graph {
    trace(2, |a| {
        let (x, y) = (a[0], a[1]);
        let c = Traced::c;
        let gaussian = (-(x * x) / (c(2.0) * y * y)).exp() / (y * c(2.5066));
        let angle = Traced::select(x.lt(y * y), y.atan2(x) * c(0.5), (x - y).exp() - c(1.0));
        let w = wrap_angle(x);
        let mixed = w.cos() * y.max(c(0.0)).sqrt() + (x.abs() + c(0.25)).ln();
        vec![gaussian, angle, mixed]
    })
}

/// Rows (x, y) for [`gpu_kernel`]: random x in [-6, 6] and y in [-3, 3] (y = b of the Gaussian
/// taken away from 0), then ties x = y^2 (rounded, so the comparison may go either way), the
/// negative x axis (atan2's branch cut) with y = 0 and y tiny, the origin, x = +-pi (the wrap).
fn gpu_rows(count: usize) -> Vec<[f32; 2]> {
    let mut random = rand_pcg::Pcg64::seed_from_u64(0xb0b);
    let mut rows = vec![
        [0.0, 0.0],
        [-1.0, 0.0],
        [-1.0, -0.0],
        [-1.0, 1e-30],
        [-2.0, -1e-7],
        [std::f32::consts::PI, 1.0],
        [-std::f32::consts::PI, 1.0],
        [3.141_592_5, 0.5],
    ];
    while rows.len() < count {
        let y: f32 = random.random_range(-3.0..3.0);
        let x = match rows.len() % 4 {
            0 => y * y,
            1 => y * y * (1.0 + f32::EPSILON),
            _ => random.random_range(-6.0..6.0),
        };
        rows.push([x, if y.abs() < 0.05 { 0.05 } else { y }]);
    }
    rows
}

/// On llvmpipe, every row of three hand-written expressions (a Gaussian, an atan2 / select, a
/// wrapped angle through cos, sqrt and log) is within its bound of the CPU's f32 value; prints
/// the largest measured / bound ratio per expression and the number of infinite bounds.
#[test]
fn llvmpipe_results_are_within_the_bound() {
    let Some(gpu) = device() else { return };
    let graph = gpu_graph();
    let plan = BoundPlan::new(&graph);
    let rules = AccuracyRules::wgsl_on_llvmpipe();
    let rows = gpu_rows(1 << 16);
    let queries: Vec<f32> = rows.iter().flatten().copied().collect();
    let values = gpu
        .run(&gpu_kernel(), "hair_main", &queries, 2, &[])
        .unwrap();
    let mut worst = [(0.0f64, [0.0f32; 2]); 3];
    let mut infinite = [0usize; 3];
    let mut failures = Vec::new();
    for (row, gpu_values) in rows.iter().zip(values.chunks_exact(3)) {
        let bound = plan.analyse(row, &rules);
        for k in 0..3 {
            let (b, cpu, dev) = (bound.bounds[k], bound.values[k], gpu_values[k]);
            if b.is_infinite() {
                infinite[k] += 1;
                continue;
            }
            let diff = (f64::from(dev) - f64::from(cpu)).abs();
            if diff.is_nan() || diff > b {
                failures.push(format!(
                    "output {k} at {row:?}: GPU {dev:e}, CPU {cpu:e}, bound {b:e}"
                ));
            }
            let ratio = if b > 0.0 { diff / b } else { 0.0 };
            if ratio > worst[k].0 {
                worst[k] = (ratio, *row);
            }
        }
    }
    for (k, name) in ["gaussian", "atan2/select", "wrap/cos/sqrt/log"]
        .iter()
        .enumerate()
    {
        eprintln!(
            "llvmpipe {name:>18}: largest |gpu - cpu| / bound {:.3} at {:?}; {} infinite bounds \
             of {}",
            worst[k].0,
            worst[k].1,
            infinite[k],
            rows.len()
        );
    }
    assert!(
        failures.is_empty(),
        "{} outside the bound:\n{}",
        failures.len(),
        failures[..failures.len().min(10)].join("\n")
    );
}

/// Measures llvmpipe's `sin` and `cos` beyond [-pi, pi] (where the specification gives no rule)
/// on 2^18 points of [-100, 100] against f64: within 2^-11 absolute, which
/// [`AccuracyRules::wgsl_on_llvmpipe`] adopts on that range ([`LLVMPIPE_SIN_COS_RANGE`]).
#[test]
fn llvmpipe_sin_cos_beyond_pi() {
    let Some(gpu) = device() else { return };
    let n = 1 << 18;
    let r = LLVMPIPE_SIN_COS_RANGE as f32;
    let xs: Vec<f32> = (0..n)
        .map(|i| -r + 2.0 * r * i as f32 / (n - 1) as f32)
        .collect();
    let kernel = "@group(0) @binding(0) var<storage, read> hair_queries: array<f32>;
@group(0) @binding(1) var<storage, read_write> hair_values: array<f32>;
@compute @workgroup_size(64)
fn hair_main(@builtin(global_invocation_id) id: vec3<u32>) {
    let row = id.x + id.y * 4194240u;
    if row >= arrayLength(&hair_values) / 3u { return; }
    let x = hair_queries[row];
    hair_values[row * 3u] = sin(x);
    hair_values[row * 3u + 1u] = cos(x);
    hair_values[row * 3u + 2u] = 0.0;
}";
    let values = gpu.run(kernel, "hair_main", &xs, 1, &[]).unwrap();
    let mut worst = [(0.0f64, 0.0f32); 2];
    for (&x, v) in xs.iter().zip(values.chunks_exact(3)) {
        let exact = [f64::from(x).sin(), f64::from(x).cos()];
        for k in 0..2 {
            let e = (f64::from(v[k]) - exact[k]).abs();
            if e > worst[k].0 || e.is_nan() {
                worst[k] = (e, x);
            }
        }
    }
    eprintln!(
        "llvmpipe on [-{r}, {r}]: sin {:.3e} absolute at {}, cos {:.3e} at {} (2^-11 = {:.3e})",
        worst[0].0,
        worst[0].1,
        worst[1].0,
        worst[1].1,
        Tolerance::SIN_COS.absolute
    );
    for (e, x) in worst {
        assert!(e <= Tolerance::SIN_COS.absolute, "{e:e} at {x}");
    }
}

/// Direction pairs (wi, wo) in the local frame (tangent +X) every model is bounded on first:
/// tests/trace/main.rs's `HARD_PAIRS` (along the tangent equal, opposite, with the other in the
/// normal plane; grazing from opposite ends; phi = 0 and pi in the normal plane; wi = -wo off
/// it).
const HARD_PAIRS: &[[f64; 6]] = &[
    [1.0, 0.0, 0.0, -1.0, 0.0, 0.0],
    [-1.0, 0.0, 0.0, -1.0, 0.0, 0.0],
    [1.0, 0.0, 0.0, 1.0, 0.0, 0.0],
    [1.0, 0.0, 0.0, 0.0, 0.6, 0.8],
    [0.0, 0.6, 0.8, -1.0, 0.0, 0.0],
    [0.999_999_9, 4.47e-4, 0.0, -0.999_999_9, 0.0, 4.47e-4],
    [0.0, 1.0, 0.0, 0.0, 1.0, 0.0],
    [0.0, 1.0, 0.0, 0.0, -1.0, 0.0],
    [-0.3, 0.0, 0.953_939_2, 0.3, 0.0, -0.953_939_2],
];

/// Rows of a model's queries: each of [`HARD_PAIRS`] (with h = -1, -0.5, 0, 0.5, 1 for a
/// near-field model), then random pairs to `count`, one in eight each: wi = wo, wi = -wo,
/// phi = 0, phi = pi, wo grazing (|sin theta| = 1 - 1e-6 or 1), both grazing, and two
/// independent; h uniform in [-1, 1] or one of -1, 0, 1.
fn model_rows(count: usize, offset: bool) -> Vec<Vec<f32>> {
    let mut random = rand_pcg::Pcg64::seed_from_u64(0x05ee_db0d);
    let hs: &[f64] = if offset {
        &[-1.0, -0.5, 0.0, 0.5, 1.0]
    } else {
        &[0.0]
    };
    let mut rows: Vec<Vec<f64>> = Vec::new();
    for p in HARD_PAIRS {
        for &h in hs {
            let mut row = p.to_vec();
            if offset {
                row.push(h);
            }
            rows.push(row);
        }
    }
    let dir = |s: f64, phi: f64| {
        let c = (1.0 - s * s).max(0.0).sqrt();
        [s, c * phi.cos(), c * phi.sin()]
    };
    while rows.len() < count {
        let mut pick = |lo: f64, hi: f64| random.random_range(lo..hi);
        let (s, phi) = (pick(-1.0, 1.0), pick(-PI, PI));
        let grazing = |u: f64| if u < 0.5 { 1.0 - 1e-6 } else { 1.0 };
        let k = rows.len() % 8;
        let (wi, wo) = match k {
            0 => (dir(s, phi), dir(s, phi)),
            1 => (dir(s, phi), dir(-s, phi + PI)),
            2 => (dir(s, phi), dir(pick(-1.0, 1.0), phi)),
            3 => (dir(s, phi), dir(pick(-1.0, 1.0), phi + PI)),
            4 => {
                let g = grazing(pick(0.0, 1.0)) * if pick(0.0, 1.0) < 0.5 { -1.0 } else { 1.0 };
                (dir(s, phi), dir(g, pick(-PI, PI)))
            }
            5 => {
                let g = grazing(pick(0.0, 1.0));
                (dir(g, phi), dir(-g, pick(-PI, PI)))
            }
            _ => (dir(s, phi), dir(pick(-1.0, 1.0), pick(-PI, PI))),
        };
        let mut row = [wi, wo].concat();
        if offset {
            let u = pick(0.0, 1.0);
            row.push(if u < 0.125 {
                [-1.0, 0.0, 1.0][(u * 24.0) as usize % 3]
            } else {
                pick(-1.0, 1.0)
            });
        }
        rows.push(row);
    }
    rows.into_iter()
        .map(|r| r.into_iter().map(|v| v as f32).collect())
        .collect()
}

/// The shader graph of a registered approximation at the mapped inputs of the default hair, its
/// uniforms baked as constants.
fn approximation_graph<M: Approximation>() -> Graph {
    let model = M::from_inputs(&M::mapped_inputs(&HairParams::default())).unwrap();
    trace_eval_with(&model, UniformsIn::Constant)
}

/// Every registered approximation by name, and the two Chiang models; panics on a registered
/// approximation this list does not know, so that a new model is bounded too.
fn model_graphs() -> Vec<(String, Graph)> {
    use hairmath::models::*;
    type Builder = (&'static str, fn() -> Graph);
    let known: &[Builder] = &[
        (Karis::<f64>::NAME, approximation_graph::<Karis<f64>>),
        (
            KarisRefit::<f64>::NAME,
            approximation_graph::<KarisRefit<f64>>,
        ),
        (
            KajiyaKay::<f64>::NAME,
            approximation_graph::<KajiyaKay<f64>>,
        ),
        (TressFx::<f64>::NAME, approximation_graph::<TressFx<f64>>),
        (
            Scheuermann::<f64>::NAME,
            approximation_graph::<Scheuermann<f64>>,
        ),
        (
            NguyenDonnelly::<f64>::NAME,
            approximation_graph::<NguyenDonnelly<f64>>,
        ),
        (Gerard::<f64>::NAME, approximation_graph::<Gerard<f64>>),
        (
            Frostbite::<f64>::NAME,
            approximation_graph::<Frostbite<f64>>,
        ),
        (
            FrostbiteRefit::<f64>::NAME,
            approximation_graph::<FrostbiteRefit<f64>>,
        ),
    ];
    let mut graphs = Vec::new();
    for entry in MODELS.iter().filter(|m| m.approximation.is_some()) {
        let (_, build) = known
            .iter()
            .find(|(name, _)| *name == entry.name)
            .unwrap_or_else(|| {
                panic!(
                    "registered approximation {} is not bounded here",
                    entry.name
                )
            });
        graphs.push((entry.name.to_string(), build()));
    }
    let hair = HairParams::default();
    graphs.push((
        "chiang (near field)".into(),
        trace_eval_with(&ChiangHair::new(&hair), UniformsIn::Constant),
    ));
    let rule = FarFieldRule::gauss_legendre(DEFAULT_FAR_FIELD_NODES).unwrap();
    graphs.push((
        format!("chiang-far ({DEFAULT_FAR_FIELD_NODES} nodes)"),
        trace_eval_with(
            &ChiangFarField::with_rule(&hair, &rule),
            UniformsIn::Constant,
        ),
    ));
    graphs
}

/// The figures of one model over its rows.
#[derive(Default)]
struct ModelFigures {
    rows: usize,
    infinite_rows: usize,
    relative: Vec<f64>,
    zero_values: usize,
    worst: (f64, usize),
    causes: HashMap<&'static str, usize>,
    beyond_pi_rows: usize,
    uncertain_rows: usize,
    /// Rows whose bound is infinite under `wgsl_spec`.
    spec_infinite_rows: usize,
    /// Rows with a floor that may jump, and their values with a bound of at least |value|.
    jump_rows: usize,
    jump_useless: usize,
}

impl ModelFigures {
    fn add(&mut self, row: usize, bound: &RowBound) {
        self.rows += 1;
        if bound.bounds.iter().any(|b| b.is_infinite()) {
            self.infinite_rows += 1;
        }
        for ((&b, &v), c) in bound.bounds.iter().zip(&bound.values).zip(&bound.causes) {
            if let Some(c) = c {
                *self.causes.entry(c).or_default() += 1;
            }
            if b.is_infinite() {
                continue;
            }
            if v == 0.0 {
                self.zero_values += 1;
                continue;
            }
            let rel = b / f64::from(v).abs();
            if rel > self.worst.0 {
                self.worst = (rel, row);
            }
            self.relative.push(rel);
        }
        self.beyond_pi_rows += usize::from(bound.sin_cos_beyond_pi > 0);
        self.uncertain_rows += usize::from(bound.uncertain_selects > 0);
        if bound.floor_jumps > 0 {
            self.jump_rows += 1;
            for (&b, &v) in bound.bounds.iter().zip(&bound.values) {
                self.jump_useless += usize::from(b.is_nan() || b >= f64::from(v).abs());
            }
        }
    }

    /// The share of the finite relative bounds above `limit`.
    fn above(&self, limit: f64) -> f64 {
        self.relative.iter().filter(|&&r| r > limit).count() as f64
            / self.relative.len().max(1) as f64
    }

    fn median(&mut self) -> f64 {
        if self.relative.is_empty() {
            return f64::NAN;
        }
        self.relative.sort_by(f64::total_cmp);
        self.relative[self.relative.len() / 2]
    }
}

/// The bound for every registered approximation (at the mapped inputs of the default hair, its
/// uniforms baked) and for Chiang's near and far field over about 3000 direction pairs, the hard
/// cases first. Prints per model the median and largest bound relative to |value|, the rows with
/// an infinite bound and what made them infinite, the rows where a sin/cos argument may leave
/// [-pi, pi], the rows with an uncertain select or a floor that may jump, and the rows the
/// specification's rules alone ([`AccuracyRules::wgsl_spec`]) leave unbounded; a simulated
/// device spending the rules' allowances stays within the bound on every 16th row. Asserts the
/// bound is finite on at least 95% of the rows of every model.
#[test]
fn bounds_of_every_model() {
    let rules = AccuracyRules::wgsl_on_llvmpipe();
    let mut failures = Vec::new();
    for (name, graph) in model_graphs() {
        let offset = graph.input_count() == 7;
        let plan = BoundPlan::new(&graph);
        let rows = model_rows(3000, offset);
        let mut figures = ModelFigures::default();
        let mut worst_sim = 0.0f64;
        let mut examples: HashMap<&'static str, String> = HashMap::new();
        for (r, row) in rows.iter().enumerate() {
            let (bound, trace) = plan.run(row, &rules);
            figures.add(r, &bound);
            let spec = plan.analyse(row, &AccuracyRules::wgsl_spec());
            figures.spec_infinite_rows += usize::from(spec.bounds.iter().any(|b| b.is_infinite()));
            for (k, c) in bound.causes.iter().enumerate() {
                if let Some(c) = c {
                    examples.entry(c).or_insert_with(|| {
                        let root = trace.root[plan.outputs[k] as usize];
                        let chain: Vec<String> = plan
                            .blame(&trace, root)
                            .into_iter()
                            .skip(1)
                            .take(4)
                            .map(|line| format!("\n        after {line}"))
                            .collect();
                        format!(
                            "row {r} {row:?}: {}{}",
                            plan.describe(&trace, root),
                            chain.concat()
                        )
                    });
                }
            }
            if r % 16 == 0 {
                let sim = Device::Simulated {
                    seed: r as u64,
                    flush: r % 32 == 0,
                };
                let simulated = device_eval(&graph, row, sim, &rules);
                worst_sim = worst_sim.max(covered(&name, row, &bound, &simulated).0);
            }
        }
        let median = figures.median();
        let mut causes: Vec<String> = figures
            .causes
            .iter()
            .map(|(c, n)| format!("{c}: {n} values"))
            .collect();
        causes.sort();
        eprintln!(
            "{name:>24}: {} nodes, {} rows: bound / |value| median {median:.2e}, max {:.2e} \
             (row {:?}), above 1e-3 for {:.1}% and above 1 for {:.1}% of the values; infinite on \
             {} rows{}; {} zero values; sin/cos beyond pi on {} rows; uncertain selects on {} \
             rows; simulated device at most {worst_sim:.3} of the bound; the specification's \
             rules alone: infinite on {} rows; a floor may jump on {} rows ({} of their values \
             bounded by |value| or more)",
            graph.nodes().len(),
            figures.rows,
            figures.worst.0,
            rows[figures.worst.1],
            100.0 * figures.above(1e-3),
            100.0 * figures.above(1.0),
            figures.infinite_rows,
            if causes.is_empty() {
                String::new()
            } else {
                format!(" ({})", causes.join("; "))
            },
            figures.zero_values,
            figures.beyond_pi_rows,
            figures.uncertain_rows,
            figures.spec_infinite_rows,
            figures.jump_rows,
            figures.jump_useless,
        );
        let mut examples: Vec<String> = examples
            .into_iter()
            .map(|(c, e)| format!("    {c}, first at {e}"))
            .collect();
        examples.sort();
        for e in &examples {
            eprintln!("{e}");
        }
        let (worst_trace, worst_output) = {
            let row = &rows[figures.worst.1];
            let (bound, trace) = plan.run(row, &rules);
            let k = (0..3)
                .max_by(|&a, &b| {
                    let rel = |k: usize| bound.bounds[k] / f64::from(bound.values[k]).abs();
                    rel(a).total_cmp(&rel(b))
                })
                .unwrap();
            (trace, plan.outputs[k])
        };
        for line in plan.blame(&worst_trace, worst_output).iter().take(6) {
            eprintln!("    worst row: {line}");
        }
        if figures.infinite_rows * 20 > figures.rows {
            failures.push(format!(
                "{name}: infinite on {} of {} rows: {causes:?}",
                figures.infinite_rows, figures.rows
            ));
        }
    }
    assert!(failures.is_empty(), "{failures:#?}");
}

/// The model graphs without tables, printed by `Graph::to_wgsl` and wrapped in a kernel to the
/// binding contract, run on llvmpipe over the model rows: every value within its bound. Prints
/// the largest measured / bound ratio per model.
#[test]
fn model_graphs_on_llvmpipe_are_within_the_bound() {
    let Some(gpu) = device() else { return };
    let rules = AccuracyRules::wgsl_on_llvmpipe();
    let hair = HairParams::default();
    let rule = FarFieldRule::gauss_legendre(8).unwrap();
    let mut graphs: Vec<(String, Graph)> = model_graphs()
        .into_iter()
        .filter(|(name, g)| g.tables().is_empty() && !name.starts_with("chiang-far"))
        .collect();
    graphs.push((
        "chiang-far (8 nodes)".into(),
        trace_eval_with(
            &ChiangFarField::with_rule(&hair, &rule),
            UniformsIn::Constant,
        ),
    ));
    let mut failures = Vec::new();
    for (name, graph) in graphs {
        let offset = graph.input_count() == 7;
        let stride = graph.input_count();
        let call = if offset {
            "model_eval(wi, wo, hair_queries[q + 6u])"
        } else {
            "model_eval(wi, wo)"
        };
        let kernel = format!(
            "{}
@group(0) @binding(0) var<storage, read> hair_queries: array<f32>;
@group(0) @binding(1) var<storage, read_write> hair_values: array<f32>;

@compute @workgroup_size(64)
fn hair_main(@builtin(global_invocation_id) id: vec3<u32>) {{
    let row = id.x + id.y * 4194240u;
    if row >= arrayLength(&hair_values) / 3u {{
        return;
    }}
    let q = row * {stride}u;
    let wi = vec3<f32>(hair_queries[q], hair_queries[q + 1u], hair_queries[q + 2u]);
    let wo = vec3<f32>(hair_queries[q + 3u], hair_queries[q + 4u], hair_queries[q + 5u]);
    let value = {call};
    hair_values[row * 3u] = value.x;
    hair_values[row * 3u + 1u] = value.y;
    hair_values[row * 3u + 2u] = value.z;
}}
",
            graph.to_wgsl("model_eval")
        );
        let rows = model_rows(3000, offset);
        let queries: Vec<f32> = rows.iter().flatten().copied().collect();
        let values = match gpu.run(&kernel, "hair_main", &queries, stride, &[]) {
            Ok(values) => values,
            Err(error) => {
                failures.push(format!("{name}: {error}"));
                continue;
            }
        };
        let plan = BoundPlan::new(&graph);
        let (mut worst, mut infinite, mut outside) = ((0.0f64, 0usize), 0usize, Vec::new());
        for (r, (row, dev)) in rows.iter().zip(values.chunks_exact(3)).enumerate() {
            let bound = plan.analyse(row, &rules);
            for (k, &gpu_value) in dev.iter().enumerate() {
                let (b, cpu) = (bound.bounds[k], bound.values[k]);
                if b.is_infinite() {
                    infinite += 1;
                    continue;
                }
                let diff = (f64::from(gpu_value) - f64::from(cpu)).abs();
                if diff.is_nan() || diff > b {
                    outside.push(format!(
                        "row {r} {row:?} channel {k}: GPU {gpu_value:e}, CPU {cpu:e}, bound {b:e}"
                    ));
                }
                if b > 0.0 && diff / b > worst.0 {
                    worst = (diff / b, r);
                }
            }
        }
        eprintln!(
            "llvmpipe {name:>22}: largest |gpu - cpu| / bound {:.3} (row {:?}); {infinite} \
             infinite bounds of {} values; {} outside",
            worst.0,
            rows[worst.1],
            rows.len() * 3,
            outside.len()
        );
        if !outside.is_empty() {
            failures.push(format!(
                "{name}: {}",
                outside[..outside.len().min(5)].join("\n")
            ));
        }
    }
    assert!(failures.is_empty(), "{failures:#?}");
}

/// `pi` and `wrap_angle` as the kernels spell them (a guard on the hand-written WGSL's constants).
#[test]
fn kernel_constants_match_the_traced_ones() {
    assert_eq!(pi::<f32>(), PI as f32);
    let g = trace(1, |a| vec![wrap_angle(a[0])]);
    let constants: Vec<f32> = g.nodes().iter().filter_map(|n| g.constant(n)).collect();
    assert!(constants.contains(&((2.0 * PI) as f32)));
    assert!(constants.contains(&((0.5 * std::f64::consts::FRAC_1_PI) as f32)));
}
