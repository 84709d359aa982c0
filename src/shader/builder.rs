//! Building one naga function: expressions appended to its arena and covered by
//! `Statement::Emit` ranges exactly as naga's validator requires (expressions that need no
//! emitting -- literals, constants, arguments, variables -- close the running range; a call's
//! result is produced by its `Call` statement), statements appended to the innermost open
//! block.

use naga::{
    Block, Expression, Function, FunctionArgument, FunctionResult, Handle, Literal, LocalVariable,
    Span, Statement, Type,
};
use std::collections::HashMap;

/// A naga function under construction.
pub(super) struct FnBuilder {
    function: Function,
    /// The arena length where the running emit range starts.
    emitting: Option<usize>,
    /// Open blocks, the function's body first.
    blocks: Vec<Block>,
    /// Literals already in the arena (they need no emitting, so they are valid everywhere).
    literals: HashMap<LiteralKey, Handle<Expression>>,
    /// `Expression::FunctionArgument(k)` per argument.
    arguments: Vec<Handle<Expression>>,
    /// Expressions that are a component of a vector expression: (vector, index, its size).
    components: HashMap<Handle<Expression>, Component>,
}

/// Component `index` of the vector expression `vector` of `size` components.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) struct Component {
    pub vector: Handle<Expression>,
    pub index: u32,
    pub size: u32,
}

#[derive(Clone, Copy, PartialEq, Eq, Hash)]
enum LiteralKey {
    F32(u32),
    U32(u32),
    I32(i32),
}

impl FnBuilder {
    /// An empty function named `name`.
    pub fn new(name: &str) -> Self {
        FnBuilder {
            function: Function {
                name: Some(name.to_string()),
                ..Function::default()
            },
            emitting: None,
            blocks: vec![Block::new()],
            literals: HashMap::new(),
            arguments: Vec::new(),
            components: HashMap::new(),
        }
    }

    /// Expression `h`.
    pub fn expression(&self, h: Handle<Expression>) -> &Expression {
        &self.function.expressions[h]
    }

    /// Records that `e` is a component of a vector expression.
    pub fn mark_component(&mut self, e: Handle<Expression>, component: Component) {
        self.components.insert(e, component);
    }

    /// The vector expression and the component `e` is, if it is one
    /// ([`FnBuilder::mark_component`]).
    pub fn component(&self, e: Handle<Expression>) -> Option<Component> {
        self.components.get(&e).copied()
    }

    /// Adds an argument `name: ty`; returns its value.
    pub fn argument(&mut self, name: &str, ty: Handle<Type>) -> Handle<Expression> {
        let k = self.function.arguments.len() as u32;
        self.function.arguments.push(FunctionArgument {
            name: Some(name.to_string()),
            ty,
            binding: None,
        });
        let h = self.expr(Expression::FunctionArgument(k));
        self.arguments.push(h);
        h
    }

    /// Adds an argument with a built-in binding (entry points).
    pub fn builtin_argument(
        &mut self,
        name: &str,
        ty: Handle<Type>,
        builtin: naga::BuiltIn,
    ) -> Handle<Expression> {
        let h = self.argument(name, ty);
        if let Some(a) = self.function.arguments.last_mut() {
            a.binding = Some(naga::Binding::BuiltIn(builtin));
        }
        h
    }

    /// Sets the result type.
    pub fn result(&mut self, ty: Handle<Type>) {
        self.function.result = Some(FunctionResult { ty, binding: None });
    }

    /// Appends `e`, emitting it unless it needs no emitting.
    pub fn expr(&mut self, e: Expression) -> Handle<Expression> {
        if e.needs_pre_emit() {
            self.flush();
        } else if self.emitting.is_none() {
            self.emitting = Some(self.function.expressions.len());
        }
        self.function.expressions.append(e, Span::UNDEFINED)
    }

    /// Names an expression in the written code (`let name = ...`).
    pub fn name(&mut self, h: Handle<Expression>, name: &str) {
        self.function.named_expressions.insert(h, name.to_string());
    }

    /// Names `h` for a value the Rust code named ([`crate::real::Real::label`]), unless it
    /// has a name or is not a computed value (an argument, a literal, a constant or a call's
    /// result, which naga's writers name themselves).
    pub fn label(&mut self, h: Handle<Expression>, name: &str) {
        let e = &self.function.expressions[h];
        let computed = !e.needs_pre_emit() && !matches!(e, Expression::CallResult(_));
        if computed && !self.function.named_expressions.contains_key(&h) {
            self.name(h, name);
        }
    }

    fn literal(&mut self, key: LiteralKey, literal: Literal) -> Handle<Expression> {
        if let Some(&h) = self.literals.get(&key) {
            return h;
        }
        let h = self.expr(Expression::Literal(literal));
        self.literals.insert(key, h);
        h
    }

    /// The `f32` literal `v`.
    pub fn f32(&mut self, v: f32) -> Handle<Expression> {
        self.literal(LiteralKey::F32(v.to_bits()), Literal::F32(v))
    }

    /// The `u32` literal `v`.
    pub fn u32(&mut self, v: u32) -> Handle<Expression> {
        self.literal(LiteralKey::U32(v), Literal::U32(v))
    }

    /// The `i32` literal `v`.
    pub fn i32(&mut self, v: i32) -> Handle<Expression> {
        self.literal(LiteralKey::I32(v), Literal::I32(v))
    }

    /// Closes the running emit range, if any, as an `Emit` statement.
    fn flush(&mut self) {
        if let Some(start) = self.emitting.take() {
            if start < self.function.expressions.len() {
                let range = self.function.expressions.range_from(start);
                self.block().push(Statement::Emit(range), Span::UNDEFINED);
            }
        }
    }

    fn block(&mut self) -> &mut Block {
        self.blocks.last_mut().expect("the function body is open")
    }

    /// Appends the statement `s` (after the expressions emitted so far).
    pub fn stmt(&mut self, s: Statement) {
        self.flush();
        self.block().push(s, Span::UNDEFINED);
    }

    /// Calls `function` with `arguments`; returns its result.
    pub fn call(
        &mut self,
        function: Handle<Function>,
        arguments: Vec<Handle<Expression>>,
    ) -> Handle<Expression> {
        self.flush();
        let result = self
            .function
            .expressions
            .append(Expression::CallResult(function), Span::UNDEFINED);
        self.block().push(
            Statement::Call {
                function,
                arguments,
                result: Some(result),
            },
            Span::UNDEFINED,
        );
        result
    }

    /// A local variable `name: ty` (uninitialised); returns its pointer.
    pub fn local(
        &mut self,
        name: &str,
        ty: Handle<Type>,
        init: Option<Handle<Expression>>,
    ) -> Handle<Expression> {
        let var = self.function.local_variables.append(
            LocalVariable {
                name: Some(name.to_string()),
                ty,
                init,
            },
            Span::UNDEFINED,
        );
        self.expr(Expression::LocalVariable(var))
    }

    /// `*pointer`.
    pub fn load(&mut self, pointer: Handle<Expression>) -> Handle<Expression> {
        self.expr(Expression::Load { pointer })
    }

    /// `*pointer = value`.
    pub fn store(&mut self, pointer: Handle<Expression>, value: Handle<Expression>) {
        self.stmt(Statement::Store { pointer, value });
    }

    /// Opens a nested block: later statements go into it until [`FnBuilder::close_block`].
    pub fn open_block(&mut self) {
        self.flush();
        self.blocks.push(Block::new());
    }

    /// Closes the innermost nested block and returns it.
    pub fn close_block(&mut self) -> Block {
        self.flush();
        assert!(self.blocks.len() > 1, "the function body stays open");
        self.blocks.pop().expect("a nested block")
    }

    /// Returns `value` from the function.
    pub fn ret(&mut self, value: Option<Handle<Expression>>) {
        self.stmt(Statement::Return { value });
    }

    /// The finished function.
    pub fn finish(mut self) -> Function {
        self.flush();
        assert_eq!(self.blocks.len(), 1, "every nested block is closed");
        self.function.body = self.blocks.pop().expect("the function body");
        self.function
    }
}
