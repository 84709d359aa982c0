//! The compute entry point of the binding contract (see [`super::ShaderModule::with_compute_entry`]).

use super::body::{read_output, ResultKind};
use super::builder::FnBuilder;
use super::types;
use super::{
    constant_values, ENTRY_POINT, QUERY_BINDING, ROW_GROUP, VALUE_BINDING, WORKGROUP_SIZE,
};
use crate::real::{ArgType, Signature};
use naga::{
    AddressSpace, BinaryOperator, BuiltIn, EntryPoint, Expression, Function, GlobalVariable,
    Handle, Module, ResourceBinding, ShaderStage, Span, Statement, StorageAccess,
};

/// Rows per `id.y` step of the dispatch: 65535 workgroups of [`WORKGROUP_SIZE`].
pub(super) const ROWS_PER_Y: u32 = 65535;

/// Adds `hair_queries`, `hair_values` and the entry point `hair_main` calling `top` (of the
/// signature `signature` and result `result`) on each row of `stride` f32.
pub(super) fn add_entry_point(
    module: &mut Module,
    top: Handle<Function>,
    signature: &Signature,
    result: ResultKind,
    stride: u32,
) {
    let f32t = types::f32(module);
    let u32t = types::u32(module);
    let rows = types::array(module, f32t, None);
    let storage = |module: &mut Module, name: &str, binding: u32, access: StorageAccess| {
        module.global_variables.append(
            GlobalVariable {
                name: Some(name.to_string()),
                space: AddressSpace::Storage { access },
                binding: Some(ResourceBinding {
                    group: ROW_GROUP,
                    binding,
                }),
                ty: rows,
                init: None,
                memory_decorations: Default::default(),
            },
            Span::UNDEFINED,
        )
    };
    let queries = storage(module, "hair_queries", QUERY_BINDING, StorageAccess::LOAD);
    let values = storage(
        module,
        "hair_values",
        VALUE_BINDING,
        StorageAccess::LOAD | StorageAccess::STORE,
    );

    let uvec3 = types::vector(module, naga::VectorSize::Tri, naga::Scalar::U32);
    let mut b = FnBuilder::new(ENTRY_POINT);
    let id = b.builtin_argument("id", uvec3, BuiltIn::GlobalInvocationId);
    let x = b.expr(Expression::AccessIndex { base: id, index: 0 });
    let y = b.expr(Expression::AccessIndex { base: id, index: 1 });
    let per_y = b.u32(ROWS_PER_Y);
    let group = b.u32(WORKGROUP_SIZE);
    let y_rows = bin(&mut b, BinaryOperator::Multiply, y, per_y);
    let y_rows = bin(&mut b, BinaryOperator::Multiply, y_rows, group);
    let row = bin(&mut b, BinaryOperator::Add, x, y_rows);
    b.name(row, "row");
    let values_ptr = b.expr(Expression::GlobalVariable(values));
    let length = b.expr(Expression::ArrayLength(values_ptr));
    let three = b.u32(3);
    let count = bin(&mut b, BinaryOperator::Divide, length, three);
    let outside = bin(&mut b, BinaryOperator::GreaterEqual, row, count);
    b.open_block();
    b.ret(None);
    let accept = b.close_block();
    b.open_block();
    let reject = b.close_block();
    b.stmt(Statement::If {
        condition: outside,
        accept,
        reject,
    });

    let stride = b.u32(stride);
    let first = bin(&mut b, BinaryOperator::Multiply, row, stride);
    b.name(first, "first");
    let queries_ptr = b.expr(Expression::GlobalVariable(queries));
    let mut next = 0u32;
    let mut args = Vec::new();
    for p in &signature.parameters {
        if constant_values(p).is_none() {
            let arg = read_value(module, &mut b, &p.ty, queries_ptr, first, &mut next);
            args.push(arg);
        }
    }
    let result_value = b.call(top, args);
    let out_first = bin(&mut b, BinaryOperator::Multiply, row, three);
    for c in 0..3u32 {
        let value = read_output(&mut b, result_value, result, c).unwrap_or_else(|| b.f32(0.0));
        let offset = b.u32(c);
        let index = bin(&mut b, BinaryOperator::Add, out_first, offset);
        let pointer = b.expr(Expression::Access {
            base: values_ptr,
            index,
        });
        b.store(pointer, value);
    }
    let _ = u32t;
    module.entry_points.push(EntryPoint {
        name: ENTRY_POINT.to_string(),
        stage: ShaderStage::Compute,
        early_depth_test: None,
        workgroup_size: [WORKGROUP_SIZE, 1, 1],
        workgroup_size_overrides: None,
        function: b.finish(),
        mesh_info: None,
        task_payload: None,
        incoming_ray_payload: None,
    });
}

/// A value of type `ty` read from `hair_queries[first + next ..]`, advancing `next` by its
/// scalars.
fn read_value(
    module: &mut Module,
    b: &mut FnBuilder,
    ty: &ArgType,
    queries: Handle<Expression>,
    first: Handle<Expression>,
    next: &mut u32,
) -> Handle<Expression> {
    match ty {
        ArgType::Scalar => {
            let offset = b.u32(*next);
            *next += 1;
            let index = bin(b, BinaryOperator::Add, first, offset);
            let pointer = b.expr(Expression::Access {
                base: queries,
                index,
            });
            b.load(pointer)
        }
        ArgType::Vec3 => {
            let components = (0..3)
                .map(|_| read_value(module, b, &ArgType::Scalar, queries, first, next))
                .collect();
            let ty = types::vec3(module);
            b.expr(Expression::Compose { ty, components })
        }
        ArgType::Struct(s) => {
            let components = s
                .fields
                .iter()
                .map(|(_, t)| read_value(module, b, t, queries, first, next))
                .collect();
            let ty = types::arg_type(module, ty);
            b.expr(Expression::Compose { ty, components })
        }
    }
}

fn bin(
    b: &mut FnBuilder,
    op: BinaryOperator,
    left: Handle<Expression>,
    right: Handle<Expression>,
) -> Handle<Expression> {
    b.expr(Expression::Binary { op, left, right })
}
