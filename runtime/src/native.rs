//! Native code for an interpreted model's routines: the extension point a
//! run-time compiler (the `lagrangian-jit` crate) plugs into, so that this
//! crate depends on none.
//!
//! An [`InterpretedModel`](crate::InterpretedModel) given
//! [`NativeRoutines`] (`set_native`) writes the state into its register file
//! as the tape does, then asks the native code to run the routine; a routine
//! the native code declines runs on the tape. Native code must compute what
//! the tape computes, bit for bit.
//!
//! Native code reaches the input functions through an [`InputCall`]: a plain
//! `extern "C"` function and a context pointer, whatever the type of the
//! inputs. A panic in an input function is caught at that boundary, the call
//! returns NaN, and the panic resumes once the native routine has returned.

use crate::InputFunctions;
use crate::layout::RoutineKind;
use crate::tape::DerivedRoutine;
use std::any::Any;
use std::cell::Cell;
use std::fmt;
use std::marker::PhantomData;
use std::panic::{AssertUnwindSafe, RefUnwindSafe, UnwindSafe, catch_unwind, resume_unwind};

/// The routines of one tape as native code: immutable once made, so that a
/// model holding them stays `Send` and unwind-safe.
pub trait NativeRoutines: Send + Sync + RefUnwindSafe + UnwindSafe + fmt::Debug {
    /// Runs routine `kind` over `registers`, a register file of the tape the
    /// code was made for holding the state (see [`crate::tape::Tape::load_state`]),
    /// and writes its outputs to the start of `out`. Returns `false`, having
    /// done nothing, when it has no code for `kind` or the slices do not fit
    /// (the tape then runs the routine).
    fn run(
        &self,
        kind: RoutineKind,
        registers: &[f64],
        out: &mut [f64],
        inputs: InputCall<'_>,
    ) -> bool;

    /// Runs the tape's derived routine `which` as [`NativeRoutines::run`]
    /// runs a routine (see [`crate::tape::Tape::derived_routines`]);
    /// `false`, having done nothing, when it has no code for it.
    fn run_derived(
        &self,
        which: DerivedRoutine,
        registers: &[f64],
        out: &mut [f64],
        inputs: InputCall<'_>,
    ) -> bool {
        let _ = (which, registers, out, inputs);
        false
    }
}

/// The signature native code calls an input function through: context,
/// input index, pointer to the arguments, number of arguments.
pub type InputTrampoline = unsafe extern "C" fn(*const (), u32, *const f64, u32) -> f64;

/// The input functions of one call, as native code calls them (see the
/// module documentation).
#[derive(Clone, Copy)]
pub struct InputCall<'a> {
    context: *const (),
    trampoline: InputTrampoline,
    lifetime: PhantomData<&'a ()>,
}

impl InputCall<'_> {
    /// The context pointer to pass to [`InputCall::trampoline`].
    pub fn context(&self) -> *const () {
        self.context
    }

    /// The function native code calls with [`InputCall::context`], an input
    /// index and `count` arguments at `arguments`; valid while `self` is.
    pub fn trampoline(&self) -> InputTrampoline {
        self.trampoline
    }
}

/// The inputs behind an [`InputCall`], and the panic of one of their calls.
struct Context<'a, I: ?Sized> {
    inputs: &'a I,
    panic: Cell<Option<Box<dyn Any + Send>>>,
}

/// Calls input `index` of the [`Context`] at `context`.
///
/// # Safety
///
/// `context` must point to a live `Context<I>` and `arguments` to `count`
/// values.
unsafe extern "C" fn trampoline<I: InputFunctions + ?Sized>(
    context: *const (),
    index: u32,
    arguments: *const f64,
    count: u32,
) -> f64 {
    // SAFETY: the caller's guarantees.
    let (context, arguments) = unsafe {
        (
            &*(context as *const Context<'_, I>),
            std::slice::from_raw_parts(arguments, count as usize),
        )
    };
    let call = AssertUnwindSafe(|| context.inputs.value(index as usize, arguments));
    catch_unwind(call).unwrap_or_else(|payload| {
        context.panic.set(Some(payload));
        f64::NAN
    })
}

/// Runs `body` with `inputs` as an [`InputCall`]; resumes the panic of an
/// input function it called, if any, once `body` has returned.
pub fn with_input_call<I: InputFunctions + ?Sized, R>(
    inputs: &I,
    body: impl FnOnce(InputCall<'_>) -> R,
) -> R {
    let context = Context {
        inputs,
        panic: Cell::new(None),
    };
    let call = InputCall {
        context: &context as *const Context<'_, I> as *const (),
        trampoline: trampoline::<I>,
        lifetime: PhantomData,
    };
    let result = body(call);
    if let Some(payload) = context.panic.take() {
        resume_unwind(payload);
    }
    result
}

#[cfg(test)]
mod tests {
    use super::*;

    fn call(inputs: InputCall<'_>, index: u32, arguments: &[f64]) -> f64 {
        // SAFETY: the context is live inside `with_input_call`, and the
        // arguments are a slice.
        unsafe {
            (inputs.trampoline())(
                inputs.context(),
                index,
                arguments.as_ptr(),
                arguments.len() as u32,
            )
        }
    }

    #[test]
    fn native_code_calls_the_inputs_through_the_trampoline() {
        let inputs = |index: usize, args: &[f64]| index as f64 * 100.0 + args.iter().sum::<f64>();
        let value = with_input_call(&inputs, |c| call(c, 2, &[1.5, 2.0]));
        assert_eq!(value, 203.5);
    }

    #[test]
    fn a_panic_in_an_input_resumes_after_the_native_code() {
        let inputs = |_: usize, _: &[f64]| -> f64 { panic!("table lookup failed") };
        let mut after = f64::INFINITY;
        let result = catch_unwind(AssertUnwindSafe(|| {
            with_input_call(&inputs, |c| after = call(c, 0, &[]))
        }));
        assert!(after.is_nan(), "the call returns NaN, the body goes on");
        let payload = result.unwrap_err();
        assert_eq!(payload.downcast_ref::<&str>(), Some(&"table lookup failed"));
    }
}
