//! Lookup tables in shader code: one texture binding per group of four channels, read only
//! with `textureLoad`, and one generated helper function per table that interpolates the
//! texels in shader arithmetic in exactly the order of [`Table::lookup_into`].

use super::body::{math, Shared};
use super::builder::FnBuilder;
use super::types;
use super::{TextureBinding, TABLE_GROUP, TEXTURE_CHANNELS};
use crate::lut::Table;
use naga::{
    AddressSpace, BinaryOperator, Constant, Expression, Function, GlobalVariable, Handle, Literal,
    MathFunction, Module, ResourceBinding, Scalar, ScalarKind, Span, VectorSize,
};

/// The helper function of one table.
#[derive(Clone, Debug)]
pub(super) struct TableHelper {
    /// `fn lutK_kind(coordinates) -> vec4<f32>` (or `array<vec4<f32>, T>` for T textures).
    pub function: Handle<Function>,
    /// Axes of the table.
    pub dims: usize,
    /// Channels of the table.
    pub channels: u32,
    /// Textures of the table.
    pub textures: usize,
}

/// The shader name of table `k`: `lut{k}` and the table's kind (`lut0_gerard`).
pub(super) fn table_name(k: usize, table: &Table) -> String {
    let kind = identifier(&table.meta().kind);
    if kind.is_empty() {
        format!("lut{k}")
    } else {
        format!("lut{k}_{kind}")
    }
}

/// Lower-case ASCII letters, digits and single underscores of `text`.
fn identifier(text: &str) -> String {
    let mut out = String::new();
    for c in text.chars() {
        if c.is_ascii_alphanumeric() {
            out.push(c.to_ascii_lowercase());
        } else if !out.ends_with('_') && !out.is_empty() {
            out.push('_');
        }
    }
    out.trim_end_matches('_').to_string()
}

/// Declares table `k` of the module in `shared`: its textures (bindings from the next free one
/// in [`TABLE_GROUP`]), its axis constants ([`declare_axes`]) and its helper function, with
/// their comments; returns the helper.
pub(super) fn declare_table(shared: &mut Shared, k: usize, table: &Table) -> TableHelper {
    let name = table_name(k, table);
    let dims = table.axes().len();
    let channels = table.channels();
    let count = channels.len().div_ceil(TEXTURE_CHANNELS);
    let first_binding = shared.bindings.len() as u32;
    let module = &mut shared.module;
    let ty = types::texture(module, dims);
    let mut globals = Vec::with_capacity(count);
    for t in 0..count {
        let texture_name = if count == 1 {
            format!("{name}_texels")
        } else {
            format!("{name}_texels_{}", (b'a' + t as u8) as char)
        };
        let binding = first_binding + t as u32;
        globals.push(module.global_variables.append(
            GlobalVariable {
                name: Some(texture_name.clone()),
                space: AddressSpace::Handle,
                binding: Some(ResourceBinding {
                    group: TABLE_GROUP,
                    binding,
                }),
                ty,
                init: None,
                memory_decorations: Default::default(),
            },
            Span::UNDEFINED,
        ));
        let end = ((t + 1) * TEXTURE_CHANNELS).min(channels.len());
        shared.bindings.push(TextureBinding {
            group: TABLE_GROUP,
            binding,
            name: texture_name,
            table: k,
            texture: t,
            dimension: dims,
            size: table.axes().iter().map(|a| a.size()).collect(),
            axes: table
                .axes()
                .iter()
                .map(|a| (a.name().to_string(), a.min(), a.max()))
                .collect(),
            channels: channels[t * TEXTURE_CHANNELS..end].to_vec(),
        });
    }
    let axes = declare_axes(shared, &name, table);
    let function = helper(&mut shared.module, &name, table, &globals, &axes);
    shared.names.insert(name.clone());
    shared.comments.push((
        name,
        vec![format!(
            "table {k} ({}): {} axes, {} channels; multilinear interpolation of texels read \
             with textureLoad, in the operation order of hairmath::lut::Table::lookup_into: \
             per axis t = clamp((x - MIN) * SCALE, 0, 1) * (n - 1) over its n texels",
            table.meta().kind,
            dims,
            channels.len()
        )],
    ));
    TableHelper {
        function,
        dims,
        channels: channels.len() as u32,
        textures: count,
    }
}

/// The module constants of one axis of a table: its first sample and `1 / (last - first)`.
struct AxisConstants {
    min: Handle<Constant>,
    scale: Handle<Constant>,
}

/// Declares per axis of table `name` the constants `NAME_AXIS_MIN` and `NAME_AXIS_SCALE`
/// (upper case; `X0`, `X1`... for an axis without a usable name), with comments.
fn declare_axes(shared: &mut Shared, name: &str, table: &Table) -> Vec<AxisConstants> {
    let arguments = axis_arguments(table);
    table
        .axes()
        .iter()
        .zip(&arguments)
        .map(|(a, argument)| {
            let prefix = format!("{name}_{argument}").to_ascii_uppercase();
            let mut constant = |suffix: &str, value: f64, meaning: String| {
                let constant_name = format!("{prefix}_{suffix}");
                let module = &mut shared.module;
                let f32t = types::f32(module);
                let init = module.global_expressions.append(
                    Expression::Literal(Literal::F32(value as f32)),
                    Span::UNDEFINED,
                );
                let handle = module.constants.append(
                    Constant {
                        name: Some(constant_name.clone()),
                        ty: f32t,
                        init,
                    },
                    Span::UNDEFINED,
                );
                shared.names.insert(constant_name.clone());
                shared.comments.push((constant_name, vec![meaning]));
                handle
            };
            let (axis, min, max) = (a.name(), a.min(), a.max());
            AxisConstants {
                min: constant("MIN", min, format!("{axis} at the first texel of {name}")),
                scale: constant(
                    "SCALE",
                    1.0 / (max - min),
                    format!("1 / ({max} - {min}), {axis} to [0, 1] across {name}'s texels"),
                ),
            }
        })
        .collect()
}

/// The helper's argument names, one per axis: the axis' name as an identifier, or `x{d}` if it
/// has none, starts with a digit or repeats an earlier one.
fn axis_arguments(table: &Table) -> Vec<String> {
    let mut used: Vec<String> = Vec::new();
    for (d, a) in table.axes().iter().enumerate() {
        let mut arg = identifier(a.name());
        if arg.is_empty() || arg.starts_with(|c: char| c.is_ascii_digit()) || used.contains(&arg) {
            arg = format!("x{d}");
        }
        used.push(arg);
    }
    used
}

/// The interpolation helper of `table` reading the textures `globals`:
///
/// per axis `d` ([`crate::lut::axis_cell`] in `f32`): `u = min(max((x - MIN) * SCALE, 0),
/// 1)` with the axis' constants, `t = u * (n - 1)`, `i0 = min(floor(t), n - 2)`, `f = t - i0`;
/// then for the corners `c` in 0..2^D (axis `d` upper when bit `d` of `c` is set), `w = (1 -
/// f0 or f0) * (1 - f1 or f1) * ...` and `acc = w * textureLoad(texels, i + bits, 0)` for the
/// first corner, `acc + w * textureLoad(...)` after it, where `i = clamp(i32(i0), 0, n - 2)`
/// (equal to `i0` for every coordinate but NaN): the order of `corner_weight` and
/// `accumulate` in `hairmath::lut`.
fn helper(
    module: &mut Module,
    name: &str,
    table: &Table,
    globals: &[Handle<GlobalVariable>],
    axes: &[AxisConstants],
) -> Handle<Function> {
    let f32t = types::f32(module);
    let vec4t = types::vec4(module);
    let mut b = FnBuilder::new(name);
    let coords: Vec<Handle<Expression>> = axis_arguments(table)
        .iter()
        .map(|arg| b.argument(arg, f32t))
        .collect();
    let result = if globals.len() == 1 {
        vec4t
    } else {
        types::array(module, vec4t, Some(globals.len() as u32))
    };
    b.result(result);

    // The cell and weights along each axis.
    let mut lower = Vec::new();
    let mut upper = Vec::new();
    let mut frac = Vec::new();
    let mut one_minus = Vec::new();
    for ((a, &x), constants) in table.axes().iter().zip(&coords).zip(axes) {
        let last = (a.size().max(2) - 1) as f64;
        let min = b.expr(Expression::Constant(constants.min));
        let scale = b.expr(Expression::Constant(constants.scale));
        let shifted = bin(&mut b, BinaryOperator::Subtract, x, min);
        let scaled = bin(&mut b, BinaryOperator::Multiply, shifted, scale);
        let zero = b.f32(0.0);
        let one = b.f32(1.0);
        let low = math(&mut b, MathFunction::Max, scaled, Some(zero));
        let u = math(&mut b, MathFunction::Min, low, Some(one));
        let n1 = b.f32(last as f32);
        let t = bin(&mut b, BinaryOperator::Multiply, u, n1);
        let floor = math(&mut b, MathFunction::Floor, t, None);
        let n2 = b.f32((last - 1.0) as f32);
        let i0 = math(&mut b, MathFunction::Min, floor, Some(n2));
        let f = bin(&mut b, BinaryOperator::Subtract, t, i0);
        let g = bin(&mut b, BinaryOperator::Subtract, one, f);
        let converted = b.expr(Expression::As {
            expr: i0,
            kind: ScalarKind::Sint,
            convert: Some(4),
        });
        // A no-op for every coordinate but NaN, whose conversion is undefined: the texel
        // coordinates stay in range by construction, without the back ends' bounds checks.
        let first = b.i32(0);
        let last_cell = b.i32(a.size().max(2) as i32 - 2);
        let index = b.expr(Expression::Math {
            fun: MathFunction::Clamp,
            arg: converted,
            arg1: Some(first),
            arg2: Some(last_cell),
            arg3: None,
        });
        let step = b.i32(1);
        let next = bin(&mut b, BinaryOperator::Add, index, step);
        lower.push(index);
        upper.push(next);
        frac.push(f);
        one_minus.push(g);
    }

    let dims = table.axes().len();
    let mut acc: Vec<Option<Handle<Expression>>> = vec![None; globals.len()];
    let images: Vec<Handle<Expression>> = globals
        .iter()
        .map(|&g| b.expr(Expression::GlobalVariable(g)))
        .collect();
    let level = b.i32(0);
    let ivec = match dims {
        2 => Some(types::vector(module, VectorSize::Bi, Scalar::I32)),
        3 => Some(types::vector(module, VectorSize::Tri, Scalar::I32)),
        _ => None,
    };
    for corner in 0..(1usize << dims) {
        let mut w = None;
        let mut index = Vec::with_capacity(dims);
        for d in 0..dims {
            let up = (corner >> d) & 1 == 1;
            let factor = if up { frac[d] } else { one_minus[d] };
            w = Some(match w {
                None => factor,
                Some(w) => bin(&mut b, BinaryOperator::Multiply, w, factor),
            });
            index.push(if up { upper[d] } else { lower[d] });
        }
        let w = w.unwrap_or_else(|| b.f32(1.0));
        let coordinate = match ivec {
            Some(ty) => b.expr(Expression::Compose {
                ty,
                components: index,
            }),
            None => index[0],
        };
        for (slot, &image) in acc.iter_mut().zip(&images) {
            let texel = b.expr(Expression::ImageLoad {
                image,
                coordinate,
                array_index: None,
                sample: None,
                level: Some(level),
            });
            let weighted = bin(&mut b, BinaryOperator::Multiply, w, texel);
            *slot = Some(match *slot {
                None => weighted,
                Some(sum) => bin(&mut b, BinaryOperator::Add, sum, weighted),
            });
        }
    }
    let acc: Vec<Handle<Expression>> = acc
        .into_iter()
        .map(|a| a.expect("a table has at least one corner"))
        .collect();
    let value = if acc.len() == 1 {
        acc[0]
    } else {
        b.expr(Expression::Compose {
            ty: result,
            components: acc,
        })
    };
    b.ret(Some(value));
    module.functions.append(b.finish(), Span::UNDEFINED)
}

fn bin(
    b: &mut FnBuilder,
    op: BinaryOperator,
    left: Handle<Expression>,
    right: Handle<Expression>,
) -> Handle<Expression> {
    b.expr(Expression::Binary { op, left, right })
}
