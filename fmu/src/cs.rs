//! The Co-Simulation entry points: `fmi2DoStep` runs the scenario's
//! integrator (DOPRI5 by default) with the components' events from one
//! communication point to the next.

#![allow(non_snake_case)]

use crate::ffi::*;
use crate::guard::guard;
use crate::instance::{Failure, Outcome};

/// `fmi2LastSuccessfulTime`, the one `fmi2StatusKind` with a Real answer.
const LAST_SUCCESSFUL_TIME: fmi2StatusKind = 2;
/// `fmi2Terminated`, the one `fmi2StatusKind` with a Boolean answer.
const TERMINATED: fmi2StatusKind = 3;

/// Inputs are constant over a step (`canInterpolateInputs="false"`).
pub extern "C" fn fmi2SetRealInputDerivatives(
    c: fmi2Component,
    _vr: *const fmi2ValueReference,
    nvr: usize,
    _order: *const fmi2Integer,
    _value: *const fmi2Real,
) -> fmi2Status {
    guard(c, "fmi2SetRealInputDerivatives", |_| match nvr {
        0 => Ok(()),
        _ => Err(Failure::error(
            "inputs are held constant over a step (canInterpolateInputs=\"false\")",
        )),
    })
}

/// No output derivatives (`maxOutputDerivativeOrder="0"`).
pub extern "C" fn fmi2GetRealOutputDerivatives(
    c: fmi2Component,
    _vr: *const fmi2ValueReference,
    nvr: usize,
    _order: *const fmi2Integer,
    _value: *mut fmi2Real,
) -> fmi2Status {
    guard(c, "fmi2GetRealOutputDerivatives", |_| match nvr {
        0 => Ok(()),
        _ => Err(Failure::error(
            "no output derivatives (maxOutputDerivativeOrder=\"0\")",
        )),
    })
}

/// Integrates from `t` to `t + h`; the events handled are logged (under
/// `logEvents`) when debug logging is on.
pub extern "C" fn fmi2DoStep(
    c: fmi2Component,
    t: fmi2Real,
    h: fmi2Real,
    _no_set_fmu_state_prior: fmi2Boolean,
) -> fmi2Status {
    guard(c, "fmi2DoStep", |c| {
        let result = c.instance.do_step(t, h);
        let events = std::mem::take(&mut c.instance.pending_events);
        if c.instance.logging {
            for event in &events {
                c.log(fmi2Status::fmi2OK, event);
            }
        }
        result
    })
}

/// Steps are synchronous: nothing to cancel.
pub extern "C" fn fmi2CancelStep(c: fmi2Component) -> fmi2Status {
    guard(c, "fmi2CancelStep", |_| {
        Err(Failure::error("steps are synchronous: nothing to cancel"))
    })
}

/// Steps are synchronous: no status to ask for.
fn no_status(kind: fmi2StatusKind) -> Outcome {
    Err(Failure {
        status: fmi2Status::fmi2Discard,
        message: format!("no status of kind {kind}: steps are synchronous"),
    })
}

/// See `no_status`.
pub extern "C" fn fmi2GetStatus(
    c: fmi2Component,
    kind: fmi2StatusKind,
    _value: *mut fmi2Status,
) -> fmi2Status {
    guard(c, "fmi2GetStatus", |_| no_status(kind))
}

/// The time of the last successful step (`fmi2LastSuccessfulTime`).
///
/// # Safety
/// `value` points to a writable Real.
pub unsafe extern "C" fn fmi2GetRealStatus(
    c: fmi2Component,
    kind: fmi2StatusKind,
    value: *mut fmi2Real,
) -> fmi2Status {
    guard(c, "fmi2GetRealStatus", |c| {
        // SAFETY: as documented.
        match (kind, unsafe { value.as_mut() }) {
            (LAST_SUCCESSFUL_TIME, Some(value)) => {
                *value = c.instance.time();
                Ok(())
            }
            _ => no_status(kind),
        }
    })
}

/// See `no_status`.
pub extern "C" fn fmi2GetIntegerStatus(
    c: fmi2Component,
    kind: fmi2StatusKind,
    _value: *mut fmi2Integer,
) -> fmi2Status {
    guard(c, "fmi2GetIntegerStatus", |_| no_status(kind))
}

/// Whether the FMU wants the simulation to end (`fmi2Terminated`): never.
///
/// # Safety
/// `value` points to a writable Boolean.
pub unsafe extern "C" fn fmi2GetBooleanStatus(
    c: fmi2Component,
    kind: fmi2StatusKind,
    value: *mut fmi2Boolean,
) -> fmi2Status {
    guard(c, "fmi2GetBooleanStatus", |_| {
        // SAFETY: as documented.
        match (kind, unsafe { value.as_mut() }) {
            (TERMINATED, Some(value)) => {
                *value = fmi2False;
                Ok(())
            }
            _ => no_status(kind),
        }
    })
}

/// See `no_status`.
pub extern "C" fn fmi2GetStringStatus(
    c: fmi2Component,
    kind: fmi2StatusKind,
    _value: *mut fmi2String,
) -> fmi2Status {
    guard(c, "fmi2GetStringStatus", |_| no_status(kind))
}
