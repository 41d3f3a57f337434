//! The Model Exchange entry points: the host integrates the states
//! `(q, q̇)` with the derivatives `(q̇, q̈)`, watches the event indicators
//! (the components' event functions and the model's switching functions)
//! and lets the FMU handle the events it finds.

#![allow(non_snake_case)]

use crate::ffi::*;
use crate::guard::{guard, slice, slice_mut};

/// Enters event mode.
pub extern "C" fn fmi2EnterEventMode(c: fmi2Component) -> fmi2Status {
    guard(c, "fmi2EnterEventMode", |c| c.instance.enter_event_mode())
}

/// Handles the events whose indicators crossed (crush peak → unloading,
/// weld failure, contact); logs them when debug logging is on.
///
/// # Safety
/// `info` points to a writable `fmi2EventInfo`.
pub unsafe extern "C" fn fmi2NewDiscreteStates(
    c: fmi2Component,
    info: *mut fmi2EventInfo,
) -> fmi2Status {
    guard(c, "fmi2NewDiscreteStates", |c| {
        // SAFETY: as documented.
        let info = unsafe { info.as_mut() }
            .ok_or_else(|| crate::instance::Failure::error("eventInfo is null"))?;
        let update = c.instance.new_discrete_states()?;
        if c.instance.logging {
            for event in &update.events {
                c.log(fmi2Status::fmi2OK, event);
            }
        }
        *info = fmi2EventInfo {
            newDiscreteStatesNeeded: fmi2False,
            terminateSimulation: fmi2False,
            nominalsOfContinuousStatesChanged: fmi2False,
            valuesOfContinuousStatesChanged: update.states_changed as fmi2Boolean,
            nextEventTimeDefined: fmi2False,
            nextEventTime: 0.0,
        };
        Ok(())
    })
}

/// Enters continuous-time mode.
pub extern "C" fn fmi2EnterContinuousTimeMode(c: fmi2Component) -> fmi2Status {
    guard(c, "fmi2EnterContinuousTimeMode", |c| {
        c.instance.enter_continuous_time_mode()
    })
}

/// Nothing to do after a step: events are found by their indicators.
///
/// # Safety
/// `enter_event_mode` and `terminate` point to writable Booleans.
pub unsafe extern "C" fn fmi2CompletedIntegratorStep(
    c: fmi2Component,
    _no_set_fmu_state_prior: fmi2Boolean,
    enter_event_mode: *mut fmi2Boolean,
    terminate: *mut fmi2Boolean,
) -> fmi2Status {
    guard(c, "fmi2CompletedIntegratorStep", |_| {
        // SAFETY: as documented.
        unsafe {
            if let Some(flag) = enter_event_mode.as_mut() {
                *flag = fmi2False;
            }
            if let Some(flag) = terminate.as_mut() {
                *flag = fmi2False;
            }
        }
        Ok(())
    })
}

/// Sets the time.
pub extern "C" fn fmi2SetTime(c: fmi2Component, t: fmi2Real) -> fmi2Status {
    guard(c, "fmi2SetTime", |c| c.instance.set_time(t))
}

/// Sets the states `(q, q̇)`.
///
/// # Safety
/// `x` points to `nx` Reals.
pub unsafe extern "C" fn fmi2SetContinuousStates(
    c: fmi2Component,
    x: *const fmi2Real,
    nx: usize,
) -> fmi2Status {
    guard(c, "fmi2SetContinuousStates", |c| {
        // SAFETY: as documented.
        let x = unsafe { slice(x, nx, "x")? };
        c.instance.set_states(x)
    })
}

/// The derivatives `(q̇, q̈)`.
///
/// # Safety
/// `dx` points to `nx` writable Reals.
pub unsafe extern "C" fn fmi2GetDerivatives(
    c: fmi2Component,
    dx: *mut fmi2Real,
    nx: usize,
) -> fmi2Status {
    guard(c, "fmi2GetDerivatives", |c| {
        // SAFETY: as documented.
        let dx = unsafe { slice_mut(dx, nx, "derivatives")? };
        c.instance.derivatives(dx)
    })
}

/// The event indicators.
///
/// # Safety
/// `g` points to `ni` writable Reals.
pub unsafe extern "C" fn fmi2GetEventIndicators(
    c: fmi2Component,
    g: *mut fmi2Real,
    ni: usize,
) -> fmi2Status {
    guard(c, "fmi2GetEventIndicators", |c| {
        // SAFETY: as documented.
        let g = unsafe { slice_mut(g, ni, "eventIndicators")? };
        c.instance.event_indicators(g)
    })
}

/// The states `(q, q̇)`.
///
/// # Safety
/// `x` points to `nx` writable Reals.
pub unsafe extern "C" fn fmi2GetContinuousStates(
    c: fmi2Component,
    x: *mut fmi2Real,
    nx: usize,
) -> fmi2Status {
    guard(c, "fmi2GetContinuousStates", |c| {
        // SAFETY: as documented.
        let x = unsafe { slice_mut(x, nx, "x")? };
        let states = c.instance.states();
        if states.len() != nx {
            return Err(crate::instance::Failure::error(format!(
                "{nx} states asked for; the model has {}",
                states.len()
            )));
        }
        x.copy_from_slice(&states);
        Ok(())
    })
}

/// The nominal values of the states: 1.
///
/// # Safety
/// `x_nominal` points to `nx` writable Reals.
pub unsafe extern "C" fn fmi2GetNominalsOfContinuousStates(
    c: fmi2Component,
    x_nominal: *mut fmi2Real,
    nx: usize,
) -> fmi2Status {
    guard(c, "fmi2GetNominalsOfContinuousStates", |_| {
        // SAFETY: as documented.
        let x = unsafe { slice_mut(x_nominal, nx, "x_nominal")? };
        x.fill(1.0);
        Ok(())
    })
}
