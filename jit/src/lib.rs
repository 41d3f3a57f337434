//! Native code for the routines of an interpreted `lagrangian` model,
//! compiled at run time with Cranelift.
//!
//! [`compile`] turns each routine of a model's [`Tape`], its derived
//! routines too, into one native function (`lower`), once per model;
//! [`accelerate`] installs them in an [`InterpretedModel`], which then runs
//! them in place of the tape's interpreter. The native code computes what
//! the interpreter computes, bit for bit: the same IEEE operations in the
//! same order, never a fused multiply-add, and the transcendental functions
//! through the same `f64` methods (`shims`).
//!
//! Nothing here is required: a routine the compiler declines (too long for
//! [`Options::max_instructions`], or not in the single-assignment form the
//! lowering needs) stays on the tape, and a model whose code cannot be made
//! at all (an unsupported host) keeps interpreting — [`accelerate`] reports
//! why and leaves the model as it was.

mod lower;
mod shims;

use cranelift_codegen::Context;
use cranelift_codegen::settings::{self, Configurable};
use cranelift_frontend::{FunctionBuilder, FunctionBuilderContext};
use cranelift_jit::{JITBuilder, JITModule};
use cranelift_module::{FuncId, Linkage, Module};
use lagrangian_runtime::InterpretedModel;
use lagrangian_runtime::layout::RoutineKind;
use lagrangian_runtime::native::{InputCall, InputTrampoline, NativeRoutines};
use lagrangian_runtime::tape::{DerivedRoutine, Tape, TapeRoutine};
use std::fmt;
use std::sync::Arc;

/// Why native code could not be made for a model or a routine.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct JitError(pub String);

impl fmt::Display for JitError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "native code: {}", self.0)
    }
}

impl std::error::Error for JitError {}

/// What [`compile`] compiles.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Options {
    /// Routines of more instructions stay on the tape: compile time grows
    /// faster than the routine.
    pub max_instructions: usize,
}

impl Default for Options {
    fn default() -> Self {
        Options {
            max_instructions: 50_000,
        }
    }
}

/// A routine's native function: register file, outputs, input context,
/// input trampoline.
type RoutineFunction = unsafe extern "C" fn(*const f64, *mut f64, *const (), InputTrampoline);

/// One routine compiled.
#[derive(Clone, Copy)]
struct Compiled {
    kind: RoutineKind,
    /// Which derived routine it is, for one of the tape's derived routines
    /// (`kind` is then the routine it is derived from).
    derived: Option<DerivedRoutine>,
    function: RoutineFunction,
    outputs: usize,
}

/// The native code of one tape's routines (see the crate documentation).
pub struct NativeCode {
    compiled: Vec<Compiled>,
    /// By [`RoutineKind::index`]: the position in `compiled` of the
    /// routine of that kind (not a derived one), if it was compiled.
    by_kind: [Option<usize>; RoutineKind::ALL.len()],
    /// The routines left to the tape, and why.
    declined: Vec<(RoutineKind, JitError)>,
    /// The size of the tape's register file.
    registers: usize,
    /// Owns the code's memory; freed on drop.
    module: Option<JITModule>,
}

// SAFETY: once finalized the module's code and data are only executed and
// read; the module itself is touched again only by `drop`, which has the
// code to itself.
unsafe impl Send for NativeCode {}
// SAFETY: as above: `&NativeCode` only calls the finalized functions, which
// read the caller's register file and write the caller's output slice.
unsafe impl Sync for NativeCode {}

// `&NativeCode` reads nothing a panic could leave half-written: the module
// is not touched between `compile` and `drop`.
impl std::panic::RefUnwindSafe for NativeCode {}
impl std::panic::UnwindSafe for NativeCode {}

impl Drop for NativeCode {
    fn drop(&mut self) {
        if let Some(module) = self.module.take() {
            // SAFETY: the functions are reachable only through `self`,
            // which is going away.
            unsafe { module.free_memory() };
        }
    }
}

impl fmt::Debug for NativeCode {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("NativeCode")
            .field("compiled", &self.compiled_routines().collect::<Vec<_>>())
            .field("declined", &self.declined)
            .finish()
    }
}

impl NativeCode {
    /// The routines that run as native code.
    pub fn compiled_routines(&self) -> impl Iterator<Item = RoutineKind> + '_ {
        (self.compiled.iter())
            .filter(|c| c.derived.is_none())
            .map(|c| c.kind)
    }

    /// The tape's derived routines that run as native code.
    pub fn compiled_derived_routines(&self) -> impl Iterator<Item = DerivedRoutine> + '_ {
        self.compiled.iter().filter_map(|c| c.derived)
    }

    /// The routines left to the tape, and why (for a derived routine, the
    /// routine it is derived from, and an error that names it).
    pub fn declined(&self) -> &[(RoutineKind, JitError)] {
        &self.declined
    }

    /// Runs `compiled`; `false` when the slices do not fit it.
    fn call(
        &self,
        compiled: &Compiled,
        registers: &[f64],
        out: &mut [f64],
        inputs: InputCall<'_>,
    ) -> bool {
        if registers.len() != self.registers || out.len() < compiled.outputs {
            return false;
        }
        // SAFETY: the function reads registers of a file of
        // `self.registers` values (the lowering reads only registers
        // `Tape::new` checked against that size), writes `outputs` values
        // to `out`, and calls the trampoline with the context it is given,
        // live for this call.
        unsafe {
            (compiled.function)(
                registers.as_ptr(),
                out.as_mut_ptr(),
                inputs.context(),
                inputs.trampoline(),
            )
        };
        true
    }
}

impl NativeRoutines for NativeCode {
    fn run(
        &self,
        kind: RoutineKind,
        registers: &[f64],
        out: &mut [f64],
        inputs: InputCall<'_>,
    ) -> bool {
        let found = self.by_kind[kind.index()].map(|k| &self.compiled[k]);
        found.is_some_and(|compiled| self.call(compiled, registers, out, inputs))
    }

    fn run_derived(
        &self,
        which: DerivedRoutine,
        registers: &[f64],
        out: &mut [f64],
        inputs: InputCall<'_>,
    ) -> bool {
        let found = self.compiled.iter().find(|c| c.derived == Some(which));
        found.is_some_and(|compiled| self.call(compiled, registers, out, inputs))
    }
}

/// Compiles the routines of `tape` that `options` allows; `Err` when no
/// native code can be made on this host.
pub fn compile(tape: &Tape, options: &Options) -> Result<NativeCode, JitError> {
    let mut module = new_module()?;
    let mut defined = Vec::new();
    let mut declined = Vec::new();
    let mut context = module.make_context();
    let mut builder_context = FunctionBuilderContext::new();
    let routines = (tape.routines().iter().map(|routine| (None, routine))).chain(
        tape.derived_routines()
            .map(|(d, routine)| (Some(d), routine)),
    );
    for (k, (derived, routine)) in routines.enumerate() {
        let name = format!("routine_{k}");
        let made = define(
            &mut module,
            &mut context,
            &mut builder_context,
            tape,
            routine,
            &name,
            options,
        );
        module.clear_context(&mut context);
        match (made, derived) {
            (Ok(id), _) => defined.push((derived, routine, id)),
            (Err(error), None) => declined.push((routine.kind, error)),
            (Err(JitError(error)), Some(d)) => {
                declined.push((routine.kind, JitError(format!("derived {d:?}: {error}"))))
            }
        }
    }
    module
        .finalize_definitions()
        .map_err(|e| JitError(format!("finalizing: {e}")))?;
    let compiled = (defined.into_iter())
        .map(|(derived, routine, id)| Compiled {
            kind: routine.kind,
            derived,
            // SAFETY: `id` was defined with `lower::routine_signature`,
            // the signature of `RoutineFunction`, in the host's calling
            // convention.
            function: unsafe {
                std::mem::transmute::<*const u8, RoutineFunction>(module.get_finalized_function(id))
            },
            outputs: routine.outputs.len(),
        })
        .collect::<Vec<_>>();
    let by_kind = RoutineKind::ALL
        .map(|kind| (compiled.iter()).position(|c| c.kind == kind && c.derived.is_none()));
    Ok(NativeCode {
        compiled,
        by_kind,
        declined,
        registers: tape.layout().registers(),
        module: Some(module),
    })
}

/// Compiles `model`'s routines with the default [`Options`] and installs
/// them; on `Err` the model is left as it was, interpreting.
pub fn accelerate(model: &mut InterpretedModel) -> Result<(), JitError> {
    let code = compile(model.tape(), &Options::default())?;
    model.set_native(Arc::new(code));
    Ok(())
}

/// A module for the host, optimizing for speed.
fn new_module() -> Result<JITModule, JitError> {
    let error = |e: &dyn fmt::Display| JitError(format!("setting up the code generator: {e}"));
    let mut flags = settings::builder();
    for (name, value) in [("opt_level", "speed"), ("is_pic", "false")] {
        flags.set(name, value).map_err(|e| error(&e))?;
    }
    let isa = (cranelift_native::builder().map_err(|e| error(&e))?)
        .finish(settings::Flags::new(flags))
        .map_err(|e| error(&e))?;
    let builder = JITBuilder::with_isa(isa, cranelift_module::default_libcall_names());
    Ok(JITModule::new(builder))
}

/// Declares and defines the function of one routine.
fn define(
    module: &mut JITModule,
    context: &mut Context,
    builder_context: &mut FunctionBuilderContext,
    tape: &Tape,
    routine: &TapeRoutine,
    name: &str,
    options: &Options,
) -> Result<FuncId, JitError> {
    if routine.instructions.len() > options.max_instructions {
        return Err(JitError(format!(
            "{} instructions, more than {}",
            routine.instructions.len(),
            options.max_instructions
        )));
    }
    let config = module.target_config();
    let call_conv = module.isa().default_call_conv();
    context.func.signature = lower::routine_signature(config.pointer_type(), call_conv);
    let builder = FunctionBuilder::new(&mut context.func, builder_context);
    lower::lower(builder, routine, tape.layout(), tape.arguments(), config)?;
    let id = (module.declare_function(name, Linkage::Local, &context.func.signature))
        .map_err(|e| JitError(format!("declaring {name}: {e}")))?;
    (module.define_function(id, context))
        .map_err(|e| JitError(format!("compiling {:?}: {e}", routine.kind)))?;
    Ok(id)
}
