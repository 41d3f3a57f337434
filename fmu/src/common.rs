//! The entry points both interfaces share: creation, initialization,
//! variables, saved states, directional derivatives. (Without
//! `#[no_mangle]`: an FMU binary exports them through
//! [`crate::export_fmi2`].)

#![allow(non_snake_case)]

use crate::ffi::*;
use crate::guard::{Component, Logger, guard, shielded, slice, slice_mut, text};
use crate::instance::{Failure, Instance, Interface, Outcome, Snapshot};
use crate::plant::PlantFactory;
use crate::resources::{directory_of, load};
use std::ffi::{c_char, c_int, c_void};

/// The types platform this FMU was compiled for.
pub extern "C" fn fmi2GetTypesPlatform() -> *const c_char {
    fmi2TypesPlatform.as_ptr()
}

/// The FMI version this FMU implements.
pub extern "C" fn fmi2GetVersion() -> *const c_char {
    fmi2Version.as_ptr()
}

/// Turns debug messages (the events handled) on or off.
pub extern "C" fn fmi2SetDebugLogging(
    c: fmi2Component,
    logging_on: fmi2Boolean,
    _n_categories: usize,
    _categories: *const fmi2String,
) -> fmi2Status {
    guard(c, "fmi2SetDebugLogging", |c| {
        c.instance.logging = logging_on != fmi2False;
        Ok(())
    })
}

/// Creates an instance from the spec and scenario in the FMU's resources,
/// with the interpreter's plant ([`crate::plant::plant`]).
///
/// # Safety
/// As [`instantiate_with`].
#[allow(clippy::too_many_arguments)]
pub unsafe extern "C" fn fmi2Instantiate(
    instance_name: fmi2String,
    fmu_type: c_int,
    guid: fmi2String,
    resource_location: fmi2String,
    functions: *const fmi2CallbackFunctions,
    visible: fmi2Boolean,
    logging_on: fmi2Boolean,
) -> fmi2Component {
    let arguments = (instance_name, fmu_type, guid, resource_location);
    // SAFETY: as documented.
    unsafe {
        instantiate_with(
            crate::plant::plant,
            arguments,
            functions,
            visible,
            logging_on,
        )
    }
}

/// `fmi2Instantiate`'s first four arguments: the instance name, the FMU
/// type, the GUID and the resource location.
pub type InstantiateArguments = (fmi2String, c_int, fmi2String, fmi2String);

/// `fmi2Instantiate` of an FMU binary whose plant `factory` makes: creates
/// an instance from the spec and scenario in the FMU's resources.
///
/// # Safety
/// The strings are null or zero-terminated; `functions` is null or points
/// to the host's callbacks, which outlive the instance.
pub unsafe fn instantiate_with(
    factory: PlantFactory,
    (instance_name, fmu_type, guid, resource_location): InstantiateArguments,
    functions: *const fmi2CallbackFunctions,
    _visible: fmi2Boolean,
    logging_on: fmi2Boolean,
) -> fmi2Component {
    // SAFETY: as documented.
    let logger = match unsafe { functions.as_ref() } {
        Some(f) => Logger {
            callback: f.logger,
            environment: f.componentEnvironment,
        },
        None => Logger {
            callback: None,
            environment: std::ptr::null_mut(),
        },
    };
    // SAFETY: as documented.
    let name = unsafe { text(instance_name) }.unwrap_or_default();
    let mut created = None;
    let report = |status, message: &str| logger.log(&name, status, "logStatusError", message);
    shielded("fmi2Instantiate", &report, || {
        // SAFETY: as documented.
        let (guid, location) = unsafe { (text(guid), text(resource_location)) };
        let mut instance = instantiate(factory, &name, fmu_type, guid, location)?;
        instance.logging = logging_on != fmi2False;
        created = Some(Box::new(Component {
            instance,
            logger,
            broken: false,
        }));
        Ok(())
    });
    created.map_or(std::ptr::null_mut(), |c| Box::into_raw(c) as fmi2Component)
}

fn instantiate(
    factory: PlantFactory,
    name: &str,
    fmu_type: c_int,
    guid: Option<String>,
    location: Option<String>,
) -> Outcome<Instance> {
    let interface = match fmu_type {
        t if t == fmi2ModelExchange => Interface::ModelExchange,
        t if t == fmi2CoSimulation => Interface::CoSimulation,
        other => return Err(Failure::error(format!("unknown fmuType {other}"))),
    };
    let guid = guid.ok_or_else(|| Failure::error("no GUID"))?;
    let location = location.ok_or_else(|| Failure::error("no resource location"))?;
    let dir = directory_of(&location).map_err(Failure::error)?;
    let loaded = load(&dir).map_err(Failure::error)?;
    Instance::with_plant(name, interface, &guid, loaded, factory)
}

/// Frees an instance.
pub extern "C" fn fmi2FreeInstance(c: fmi2Component) {
    if c.is_null() {
        return;
    }
    let _ = std::panic::catch_unwind(|| {
        // SAFETY: a component fmi2Instantiate returned, freed once.
        drop(unsafe { Box::from_raw(c as *mut Component) });
    });
}

/// Sets the start time (the tolerance and stop time are the scenario's).
pub extern "C" fn fmi2SetupExperiment(
    c: fmi2Component,
    _tolerance_defined: fmi2Boolean,
    _tolerance: fmi2Real,
    start_time: fmi2Real,
    _stop_time_defined: fmi2Boolean,
    _stop_time: fmi2Real,
) -> fmi2Status {
    guard(c, "fmi2SetupExperiment", |c| {
        c.instance.setup_experiment(start_time)
    })
}

/// Enters initialization mode.
pub extern "C" fn fmi2EnterInitializationMode(c: fmi2Component) -> fmi2Status {
    guard(c, "fmi2EnterInitializationMode", |c| {
        c.instance.enter_initialization()
    })
}

/// Leaves initialization mode with the scenario's initial state.
pub extern "C" fn fmi2ExitInitializationMode(c: fmi2Component) -> fmi2Status {
    guard(c, "fmi2ExitInitializationMode", |c| {
        c.instance.exit_initialization()
    })
}

/// Ends the run.
pub extern "C" fn fmi2Terminate(c: fmi2Component) -> fmi2Status {
    guard(c, "fmi2Terminate", |c| c.instance.terminate())
}

/// Back to the state after instantiation.
pub extern "C" fn fmi2Reset(c: fmi2Component) -> fmi2Status {
    guard(c, "fmi2Reset", |c| {
        c.instance.reset();
        Ok(())
    })
}

/// Reads Real variables by value reference.
///
/// # Safety
/// `vr` and `value` point to `nvr` elements.
pub unsafe extern "C" fn fmi2GetReal(
    c: fmi2Component,
    vr: *const fmi2ValueReference,
    nvr: usize,
    value: *mut fmi2Real,
) -> fmi2Status {
    guard(c, "fmi2GetReal", |c| {
        // SAFETY: as documented.
        let (vr, value) = unsafe { (slice(vr, nvr, "vr")?, slice_mut(value, nvr, "value")?) };
        c.instance.get_real(vr, value)
    })
}

/// Sets Real parameters and inputs by value reference.
///
/// # Safety
/// `vr` and `value` point to `nvr` elements.
pub unsafe extern "C" fn fmi2SetReal(
    c: fmi2Component,
    vr: *const fmi2ValueReference,
    nvr: usize,
    value: *const fmi2Real,
) -> fmi2Status {
    guard(c, "fmi2SetReal", |c| {
        // SAFETY: as documented.
        let (vr, value) = unsafe { (slice(vr, nvr, "vr")?, slice(value, nvr, "value")?) };
        c.instance.set_real(vr, value)
    })
}

/// `Ok` for no variables, else the error that this FMU has none of `kind`.
fn none_of(kind: &str, nvr: usize) -> Outcome {
    match nvr {
        0 => Ok(()),
        _ => Err(Failure::error(format!("this FMU has no {kind} variables"))),
    }
}

/// This FMU has no Integer variables.
pub extern "C" fn fmi2GetInteger(
    c: fmi2Component,
    _vr: *const fmi2ValueReference,
    nvr: usize,
    _value: *mut fmi2Integer,
) -> fmi2Status {
    guard(c, "fmi2GetInteger", |_| none_of("Integer", nvr))
}

/// This FMU has no Boolean variables.
pub extern "C" fn fmi2GetBoolean(
    c: fmi2Component,
    _vr: *const fmi2ValueReference,
    nvr: usize,
    _value: *mut fmi2Boolean,
) -> fmi2Status {
    guard(c, "fmi2GetBoolean", |_| none_of("Boolean", nvr))
}

/// This FMU has no String variables.
pub extern "C" fn fmi2GetString(
    c: fmi2Component,
    _vr: *const fmi2ValueReference,
    nvr: usize,
    _value: *mut fmi2String,
) -> fmi2Status {
    guard(c, "fmi2GetString", |_| none_of("String", nvr))
}

/// This FMU has no Integer variables.
pub extern "C" fn fmi2SetInteger(
    c: fmi2Component,
    _vr: *const fmi2ValueReference,
    nvr: usize,
    _value: *const fmi2Integer,
) -> fmi2Status {
    guard(c, "fmi2SetInteger", |_| none_of("Integer", nvr))
}

/// This FMU has no Boolean variables.
pub extern "C" fn fmi2SetBoolean(
    c: fmi2Component,
    _vr: *const fmi2ValueReference,
    nvr: usize,
    _value: *const fmi2Boolean,
) -> fmi2Status {
    guard(c, "fmi2SetBoolean", |_| none_of("Boolean", nvr))
}

/// This FMU has no String variables.
pub extern "C" fn fmi2SetString(
    c: fmi2Component,
    _vr: *const fmi2ValueReference,
    nvr: usize,
    _value: *const fmi2String,
) -> fmi2Status {
    guard(c, "fmi2SetString", |_| none_of("String", nvr))
}

/// Saves the instance's state (a copy, freed by `fmi2FreeFMUstate`).
///
/// # Safety
/// `state` points to a writable `fmi2FMUstate`.
pub unsafe extern "C" fn fmi2GetFMUstate(c: fmi2Component, state: *mut fmi2FMUstate) -> fmi2Status {
    guard(c, "fmi2GetFMUstate", |c| {
        // SAFETY: as documented.
        let state = unsafe { state.as_mut() }.ok_or_else(|| Failure::error("state is null"))?;
        let snapshot = Box::new(c.instance.snapshot());
        if !state.is_null() {
            // SAFETY: a state this function returned earlier: reused.
            drop(unsafe { Box::from_raw(*state as *mut Snapshot) });
        }
        *state = Box::into_raw(snapshot) as *mut c_void;
        Ok(())
    })
}

/// Restores a saved state.
pub extern "C" fn fmi2SetFMUstate(c: fmi2Component, state: fmi2FMUstate) -> fmi2Status {
    guard(c, "fmi2SetFMUstate", |c| {
        // SAFETY: null or a state fmi2GetFMUstate returned.
        let snapshot = unsafe { (state as *const Snapshot).as_ref() }
            .ok_or_else(|| Failure::error("state is null"))?;
        c.instance.restore(snapshot);
        Ok(())
    })
}

/// Frees a saved state.
///
/// # Safety
/// `state` points to null or a state `fmi2GetFMUstate` returned.
pub unsafe extern "C" fn fmi2FreeFMUstate(
    c: fmi2Component,
    state: *mut fmi2FMUstate,
) -> fmi2Status {
    guard(c, "fmi2FreeFMUstate", |_| {
        // SAFETY: as documented.
        if let Some(state) = unsafe { state.as_mut() }
            && !state.is_null()
        {
            // SAFETY: a state fmi2GetFMUstate returned, freed once.
            drop(unsafe { Box::from_raw(*state as *mut Snapshot) });
            *state = std::ptr::null_mut();
        }
        Ok(())
    })
}

fn not_serializable() -> Outcome {
    Err(Failure::error(
        "this FMU cannot serialize its state (canSerializeFMUstate=\"false\")",
    ))
}

/// Not supported (`canSerializeFMUstate="false"`).
pub extern "C" fn fmi2SerializedFMUstateSize(
    c: fmi2Component,
    _state: fmi2FMUstate,
    _size: *mut usize,
) -> fmi2Status {
    guard(c, "fmi2SerializedFMUstateSize", |_| not_serializable())
}

/// Not supported (`canSerializeFMUstate="false"`).
pub extern "C" fn fmi2SerializeFMUstate(
    c: fmi2Component,
    _state: fmi2FMUstate,
    _bytes: *mut fmi2Byte,
    _size: usize,
) -> fmi2Status {
    guard(c, "fmi2SerializeFMUstate", |_| not_serializable())
}

/// Not supported (`canSerializeFMUstate="false"`).
pub extern "C" fn fmi2DeSerializeFMUstate(
    c: fmi2Component,
    _bytes: *const fmi2Byte,
    _size: usize,
    _state: *mut fmi2FMUstate,
) -> fmi2Status {
    guard(c, "fmi2DeSerializeFMUstate", |_| not_serializable())
}

/// Not supported (`providesDirectionalDerivative="false"`).
pub extern "C" fn fmi2GetDirectionalDerivative(
    c: fmi2Component,
    _unknown: *const fmi2ValueReference,
    _n_unknown: usize,
    _known: *const fmi2ValueReference,
    _n_known: usize,
    _dv_known: *const fmi2Real,
    _dv_unknown: *mut fmi2Real,
) -> fmi2Status {
    guard(c, "fmi2GetDirectionalDerivative", |_| {
        Err(Failure::error(
            "this FMU provides no directional derivatives (providesDirectionalDerivative=\"false\")",
        ))
    })
}
