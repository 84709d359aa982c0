//! Lookup tables in shader code: one texture binding per group of four channels, read only
//! with `textureLoad`, and one generated helper function per table that interpolates the
//! texels in shader arithmetic in exactly the order of [`Table::lookup_into`].

use super::body::math;
use super::builder::FnBuilder;
use super::types;
use super::{TextureBinding, TABLE_GROUP, TEXTURE_CHANNELS};
use crate::lut::Table;
use naga::{
    AddressSpace, BinaryOperator, Expression, Function, GlobalVariable, Handle, MathFunction,
    Module, ResourceBinding, Scalar, ScalarKind, Span, VectorSize,
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

/// Declares the textures of table `k` of the module (bindings from `first_binding` in
/// [`TABLE_GROUP`]) and its helper function; returns the helper and the bindings.
pub(super) fn declare_table(
    module: &mut Module,
    k: usize,
    table: &Table,
    first_binding: u32,
) -> (TableHelper, Vec<TextureBinding>) {
    let name = table_name(k, table);
    let dims = table.axes().len();
    let channels = table.channels();
    let count = channels.len().div_ceil(TEXTURE_CHANNELS);
    let ty = types::texture(module, dims);
    let mut globals = Vec::with_capacity(count);
    let mut bindings = Vec::with_capacity(count);
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
        bindings.push(TextureBinding {
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
    let function = helper(module, &name, table, &globals);
    let helper = TableHelper {
        function,
        dims,
        channels: channels.len() as u32,
        textures: count,
    };
    (helper, bindings)
}

/// The interpolation helper of `table` reading the textures `globals`:
///
/// per axis `d` ([`crate::lut::axis_cell`] in `f32`): `u = min(max((x - min) * (1 / (max -
/// min)), 0), 1)`, `t = u * (n - 1)`, `i0 = min(floor(t), n - 2)`, `f = t - i0`; then for
/// the corners `c` in 0..2^D (axis `d` upper when bit `d` of `c` is set), `w = 1.0 * (1 - f0
/// or f0) * ...` and `acc += w * textureLoad(texels, i + bits, 0)`, `acc` starting at 0,
/// where `i = clamp(i32(i0), 0, n - 2)` (equal to `i0` for every coordinate but NaN).
fn helper(
    module: &mut Module,
    name: &str,
    table: &Table,
    globals: &[Handle<GlobalVariable>],
) -> Handle<Function> {
    let f32t = types::f32(module);
    let vec4t = types::vec4(module);
    let mut b = FnBuilder::new(name);
    let mut used = Vec::new();
    let coords: Vec<Handle<Expression>> = table
        .axes()
        .iter()
        .enumerate()
        .map(|(d, a)| {
            let mut arg = identifier(a.name());
            if arg.is_empty()
                || arg.starts_with(|c: char| c.is_ascii_digit())
                || used.contains(&arg)
            {
                arg = format!("x{d}");
            }
            used.push(arg.clone());
            b.argument(&arg, f32t)
        })
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
    for (a, &x) in table.axes().iter().zip(&coords) {
        let last = (a.size().max(2) - 1) as f64;
        let min = b.f32(a.min() as f32);
        let scale = b.f32((1.0 / (a.max() - a.min())) as f32);
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
    let zero = b.f32(0.0);
    let mut acc: Vec<Handle<Expression>> = globals
        .iter()
        .map(|_| {
            b.expr(Expression::Splat {
                size: VectorSize::Quad,
                value: zero,
            })
        })
        .collect();
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
        let mut w = b.f32(1.0);
        let mut index = Vec::with_capacity(dims);
        for d in 0..dims {
            let up = (corner >> d) & 1 == 1;
            let factor = if up { frac[d] } else { one_minus[d] };
            w = bin(&mut b, BinaryOperator::Multiply, w, factor);
            index.push(if up { upper[d] } else { lower[d] });
        }
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
            *slot = bin(&mut b, BinaryOperator::Add, *slot, weighted);
        }
    }
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
