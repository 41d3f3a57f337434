//! One tape routine as a Cranelift function.
//!
//! The function is `fn(file, out, context, trampoline)`: it reads the
//! register file `file` (constants become immediates, the parameters and the
//! state are loaded once, where first read), keeps every temporary in an SSA
//! value, never writes the file, and stores the routine's outputs to `out`.
//! Input calls go through `trampoline(context, index, arguments, count)`
//! (see `lagrangian_runtime::native`).
//!
//! Each tape instruction becomes the one IEEE operation it names, in the
//! tape's order: Cranelift neither reassociates floating-point arithmetic
//! nor fuses a multiplication and an addition, so the function computes
//! what the interpreter computes, bit for bit. The operations without a
//! Cranelift instruction call the `f64` methods the interpreter calls
//! (`shims`).

use crate::JitError;
use crate::shims;
use cranelift_codegen::ir::immediates::Ieee64;
use cranelift_codegen::ir::{
    AbiParam, InstBuilder, MemFlagsData, SigRef, Signature, StackSlotData, StackSlotKind, Type,
    Value, types,
};
use cranelift_codegen::isa::{CallConv, TargetFrontendConfig};
use cranelift_frontend::FunctionBuilder;
use lagrangian_runtime::tape::{Instruction, RegisterLayout, TapeRoutine};

/// The signature of a routine's function.
pub(crate) fn routine_signature(pointer: Type, call_conv: CallConv) -> Signature {
    let mut signature = Signature::new(call_conv);
    signature.params = vec![AbiParam::new(pointer); 4];
    signature
}

/// The signatures of the calls a routine makes.
struct Signatures {
    unary: SigRef,
    binary: SigRef,
    powi: SigRef,
    input: SigRef,
}

impl Signatures {
    fn import(builder: &mut FunctionBuilder<'_>, pointer: Type, call_conv: CallConv) -> Self {
        let mut make = |params: &[Type]| {
            let mut signature = Signature::new(call_conv);
            signature.params = params.iter().map(|&t| AbiParam::new(t)).collect();
            signature.returns = vec![AbiParam::new(types::F64)];
            builder.import_signature(signature)
        };
        let (f, i) = (types::F64, types::I32);
        Signatures {
            unary: make(&[f]),
            binary: make(&[f, f]),
            powi: make(&[f, i]),
            input: make(&[pointer, i, pointer, i]),
        }
    }
}

/// The function's parameters.
struct Parameters {
    file: Value,
    out: Value,
    context: Value,
    trampoline: Value,
}

/// Builds the body of one routine's function.
struct Body<'a, 'b> {
    builder: FunctionBuilder<'b>,
    layout: &'a RegisterLayout,
    arguments: &'a [u32],
    signatures: Signatures,
    parameters: Parameters,
    pointer: Type,
    /// The value each register holds so far, once read or written.
    values: Vec<Option<Value>>,
}

/// Fills `builder`'s function (of [`routine_signature`]) with `routine`.
pub(crate) fn lower(
    mut builder: FunctionBuilder<'_>,
    routine: &TapeRoutine,
    layout: &RegisterLayout,
    arguments: &[u32],
    config: TargetFrontendConfig,
) -> Result<(), JitError> {
    let pointer = config.pointer_type();
    let call_conv = builder.func.signature.call_conv;
    let entry = builder.create_block();
    builder.append_block_params_for_function_params(entry);
    builder.switch_to_block(entry);
    builder.seal_block(entry);
    let &[file, out, context, trampoline] = builder.block_params(entry) else {
        return Err(JitError(
            "a routine's function takes four parameters".into(),
        ));
    };
    let signatures = Signatures::import(&mut builder, pointer, call_conv);
    let mut body = Body {
        builder,
        layout,
        arguments,
        signatures,
        parameters: Parameters {
            file,
            out,
            context,
            trampoline,
        },
        pointer,
        values: vec![None; layout.registers()],
    };
    for &instruction in &routine.instructions {
        body.instruction(instruction)?;
    }
    body.store_outputs(&routine.outputs)?;
    body.builder.ins().return_(&[]);
    body.builder.finalize(config);
    Ok(())
}

impl Body<'_, '_> {
    /// The value of register `r`: the latest written, else the constant or
    /// the file's value. A temporary read before the routine writes it is
    /// refused (its value would be whatever an earlier run left).
    fn read(&mut self, r: u32) -> Result<Value, JitError> {
        if let Some(value) = self.values[r as usize] {
            return Ok(value);
        }
        if r >= self.layout.temporary(0) {
            return Err(JitError(format!(
                "temporary register {r} read before it is written"
            )));
        }
        let value = match self.layout.constants.get(r as usize) {
            Some(c) => self.builder.ins().f64const(Ieee64::with_bits(c.to_bits())),
            None => self.builder.ins().load(
                types::F64,
                MemFlagsData::trusted(),
                self.parameters.file,
                8 * r as i32,
            ),
        };
        self.values[r as usize] = Some(value);
        Ok(value)
    }

    fn write(&mut self, r: u32, value: Value) {
        self.values[r as usize] = Some(value);
    }

    fn instruction(&mut self, instruction: Instruction) -> Result<(), JitError> {
        use Instruction::*;
        let (d, value) = match instruction {
            Add(d, a, b) => (d, self.arithmetic(a, b, |i, x, y| i.fadd(x, y))?),
            Sub(d, a, b) => (d, self.arithmetic(a, b, |i, x, y| i.fsub(x, y))?),
            Mul(d, a, b) => (d, self.arithmetic(a, b, |i, x, y| i.fmul(x, y))?),
            Div(d, a, b) => (d, self.arithmetic(a, b, |i, x, y| i.fdiv(x, y))?),
            Neg(d, a) => (d, self.arithmetic(a, a, |i, x, _| i.fneg(x))?),
            Sqrt(d, a) => (d, self.arithmetic(a, a, |i, x, _| i.sqrt(x))?),
            Sin(d, a) => (d, self.unary(shims::sin, a)?),
            Cos(d, a) => (d, self.unary(shims::cos, a)?),
            Exp(d, a) => (d, self.unary(shims::exp, a)?),
            Ln(d, a) => (d, self.unary(shims::ln, a)?),
            Powi(d, a, k) => (d, self.powi(a, k)?),
            Powf(d, a, b) => (d, self.binary(shims::powf, a, b)?),
            Call {
                function,
                dst,
                args: [a, b],
            } => (dst, self.binary(shims::function(function), a, b)?),
            Input {
                dst,
                index,
                start,
                count,
            } => (dst, self.input(index, start, count)?),
        };
        self.write(d, value);
        Ok(())
    }

    /// `a ∘ b` for an operation Cranelift has.
    fn arithmetic(
        &mut self,
        a: u32,
        b: u32,
        op: impl FnOnce(cranelift_frontend::FuncInstBuilder<'_, '_>, Value, Value) -> Value,
    ) -> Result<Value, JitError> {
        let (x, y) = (self.read(a)?, self.read(b)?);
        Ok(op(self.builder.ins(), x, y))
    }

    /// A call of the function at `address` with signature `signature`.
    fn call(&mut self, signature: SigRef, address: usize, arguments: &[Value]) -> Value {
        let callee = self.builder.ins().iconst(self.pointer, address as i64);
        self.call_value(signature, callee, arguments)
    }

    fn call_value(&mut self, signature: SigRef, callee: Value, arguments: &[Value]) -> Value {
        let call = (self.builder.ins()).call_indirect(signature, callee, arguments);
        self.builder.inst_results(call)[0]
    }

    fn unary(&mut self, shim: shims::Unary, a: u32) -> Result<Value, JitError> {
        let x = self.read(a)?;
        Ok(self.call(self.signatures.unary, shim as usize, &[x]))
    }

    fn binary(&mut self, shim: shims::Binary, a: u32, b: u32) -> Result<Value, JitError> {
        let (x, y) = (self.read(a)?, self.read(b)?);
        Ok(self.call(self.signatures.binary, shim as usize, &[x, y]))
    }

    fn powi(&mut self, a: u32, k: i32) -> Result<Value, JitError> {
        let x = self.read(a)?;
        let k = self.builder.ins().iconst(types::I32, i64::from(k));
        let shim: shims::Powi = shims::powi;
        Ok(self.call(self.signatures.powi, shim as usize, &[x, k]))
    }

    /// Input `index` at the registers `arguments[start..start + count]`,
    /// passed in a stack slot.
    fn input(&mut self, index: u32, start: u32, count: u32) -> Result<Value, JitError> {
        let registers = (self.arguments)
            .get(start as usize..start as usize + count as usize)
            .ok_or_else(|| JitError(format!("input arguments {start}..+{count} missing")))?;
        let size = 8 * count.max(1);
        let slot = (self.builder).create_sized_stack_slot(StackSlotData::new(
            StackSlotKind::ExplicitSlot,
            size,
            3,
        ));
        for (k, &r) in registers.iter().enumerate() {
            let value = self.read(r)?;
            let pointer = self.pointer;
            (self.builder.ins()).stack_store(pointer, value, slot, 8 * k as i32);
        }
        let ins = self.builder.ins();
        let address = ins.stack_addr(self.pointer, slot, 0);
        let index = self.builder.ins().iconst(types::I32, i64::from(index));
        let count = self.builder.ins().iconst(types::I32, i64::from(count));
        let (context, trampoline) = (self.parameters.context, self.parameters.trampoline);
        let arguments = [context, index, address, count];
        Ok(self.call_value(self.signatures.input, trampoline, &arguments))
    }

    /// Stores the output registers' values to `out`, in order.
    fn store_outputs(&mut self, outputs: &[u32]) -> Result<(), JitError> {
        for (k, &r) in outputs.iter().enumerate() {
            let value = self.read(r)?;
            let out = self.parameters.out;
            (self.builder.ins()).store(MemFlagsData::trusted(), value, out, 8 * k as i32);
        }
        Ok(())
    }
}
