//! The naga types the lowering uses, and their memory layout (WGSL's rules: a `vec3<f32>` is
//! 12 bytes aligned to 16, a struct is aligned to its most aligned member and its size rounded
//! up to that alignment), so that the uniforms struct can live in a uniform or storage buffer.

use crate::real::{ArgType, StructType};
use naga::{
    ArraySize, Handle, ImageClass, ImageDimension, Module, Scalar, Span, StructMember, Type,
    TypeInner, VectorSize,
};
use std::num::NonZeroU32;

/// The handle of the type `inner` (unnamed), added if new.
pub(super) fn unnamed(module: &mut Module, inner: TypeInner) -> Handle<Type> {
    module
        .types
        .insert(Type { name: None, inner }, Span::UNDEFINED)
}

/// `f32`.
pub(super) fn f32(module: &mut Module) -> Handle<Type> {
    unnamed(module, TypeInner::Scalar(Scalar::F32))
}

/// `u32`.
pub(super) fn u32(module: &mut Module) -> Handle<Type> {
    unnamed(module, TypeInner::Scalar(Scalar::U32))
}

/// `vecN<scalar>`.
pub(super) fn vector(module: &mut Module, size: VectorSize, scalar: Scalar) -> Handle<Type> {
    unnamed(module, TypeInner::Vector { size, scalar })
}

/// `vec3<f32>`.
pub(super) fn vec3(module: &mut Module) -> Handle<Type> {
    vector(module, VectorSize::Tri, Scalar::F32)
}

/// `vec4<f32>`.
pub(super) fn vec4(module: &mut Module) -> Handle<Type> {
    vector(module, VectorSize::Quad, Scalar::F32)
}

/// `array<base, count>` (`count` > 0), or the runtime-sized `array<base>` for `None`.
pub(super) fn array(module: &mut Module, base: Handle<Type>, count: Option<u32>) -> Handle<Type> {
    let (size, align) = layout(module, base);
    let stride = round_up(size, align);
    let size = match count {
        Some(n) => ArraySize::Constant(NonZeroU32::new(n).expect("arrays are not empty")),
        None => ArraySize::Dynamic,
    };
    unnamed(module, TypeInner::Array { base, size, stride })
}

/// A named struct of the members `(name, type)`, laid out by WGSL's rules.
pub(super) fn structure(
    module: &mut Module,
    name: &str,
    members: &[(String, Handle<Type>)],
) -> Handle<Type> {
    let mut offset = 0;
    let mut struct_align = 1;
    let mut out = Vec::with_capacity(members.len());
    for (member, ty) in members {
        let (size, align) = layout(module, *ty);
        offset = round_up(offset, align);
        out.push(StructMember {
            name: Some(member.clone()),
            ty: *ty,
            binding: None,
            offset,
        });
        offset += size;
        struct_align = struct_align.max(align);
    }
    let span = round_up(offset, struct_align);
    module.types.insert(
        Type {
            name: Some(name.to_string()),
            inner: TypeInner::Struct { members: out, span },
        },
        Span::UNDEFINED,
    )
}

/// The type of an argument or struct field of a traced signature (structs declared as
/// needed, inner ones first).
pub(super) fn arg_type(module: &mut Module, ty: &ArgType) -> Handle<Type> {
    match ty {
        ArgType::Scalar => f32(module),
        ArgType::Vec3 => vec3(module),
        ArgType::Struct(s) => struct_type(module, s),
    }
}

fn struct_type(module: &mut Module, s: &StructType) -> Handle<Type> {
    let members: Vec<(String, Handle<Type>)> = s
        .fields
        .iter()
        .map(|(name, ty)| (name.clone(), arg_type(module, ty)))
        .collect();
    structure(module, &s.name, &members)
}

/// A sampled `f32` texture of `dims` axes (1 to 3), read with `textureLoad`.
pub(super) fn texture(module: &mut Module, dims: usize) -> Handle<Type> {
    let dim = match dims {
        1 => ImageDimension::D1,
        2 => ImageDimension::D2,
        _ => ImageDimension::D3,
    };
    unnamed(
        module,
        TypeInner::Image {
            dim,
            arrayed: false,
            class: ImageClass::Sampled {
                kind: naga::ScalarKind::Float,
                multi: false,
            },
        },
    )
}

/// (size, alignment) in bytes of a type the lowering creates.
pub(super) fn layout(module: &Module, ty: Handle<Type>) -> (u32, u32) {
    match &module.types[ty].inner {
        TypeInner::Scalar(s) => (u32::from(s.width), u32::from(s.width)),
        TypeInner::Vector { size, scalar } => {
            let n = *size as u32;
            let w = u32::from(scalar.width);
            (n * w, if n == 2 { 2 * w } else { 4 * w })
        }
        TypeInner::Array { base, size, stride } => {
            let (_, align) = layout(module, *base);
            let count = match size {
                ArraySize::Constant(n) => n.get(),
                _ => 1,
            };
            (count * stride, align)
        }
        TypeInner::Struct { members, span } => {
            let align = members
                .iter()
                .map(|m| layout(module, m.ty).1)
                .max()
                .unwrap_or(1);
            (*span, align)
        }
        _ => (0, 1),
    }
}

fn round_up(n: u32, align: u32) -> u32 {
    n.div_ceil(align) * align
}
