//! The entry points both interfaces share: creation, initialization,
//! variables, saved states, directional derivatives. (Without
//! `#[no_mangle]`: an FMU binary exports them through
//! [`crate::export_fmi2`].)

#![allow(non_snake_case)]

use crate::component::{Component, Logger};
use crate::ffi::*;
use crate::guard::{guard, shielded, slice, slice_mut, text};
use crate::instance::{Failure, Instance, Interface, Outcome};
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

/// The log categories of modelDescription.xml's `<LogCategories>`.
pub const LOG_CATEGORIES: [&str; 2] = ["logEvents", "logStatusError"];

/// Turns debug messages (the events handled) on or off; the categories
/// named must be this FMU's ([`LOG_CATEGORIES`]).
///
/// # Safety
/// `categories` points to `n_categories` null or zero-terminated strings.
pub unsafe extern "C" fn fmi2SetDebugLogging(
    c: fmi2Component,
    logging_on: fmi2Boolean,
    n_categories: usize,
    categories: *const fmi2String,
) -> fmi2Status {
    guard(c, "fmi2SetDebugLogging", |c| {
        // SAFETY: as documented.
        let categories = unsafe { slice(categories, n_categories, "categories")? };
        for (i, &category) in categories.iter().enumerate() {
            // SAFETY: as documented.
            let name = unsafe { text(category) };
            if !name.as_deref().is_some_and(|n| LOG_CATEGORIES.contains(&n)) {
                return Err(Failure::error(format!(
                    "categories[{i}] = {}: not a log category of this FMU ({})",
                    name.map_or("null".to_string(), |n| format!("`{n}`")),
                    LOG_CATEGORIES.join(", ")
                )));
            }
        }
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
        if instance_name.is_null() {
            return Err(Failure::error("instanceName is null"));
        }
        // SAFETY: as documented.
        let (guid, location) = unsafe { (text(guid), text(resource_location)) };
        let mut instance = instantiate(factory, &name, fmu_type, guid, location)?;
        instance.logging = logging_on != fmi2False;
        created = Some(Component::new(instance, logger));
        Ok(())
    });
    created.map_or(std::ptr::null_mut(), crate::registry::register)
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
    let dir = directory_of(&location)?;
    let loaded = load(&dir)?;
    Instance::with_plant(name, interface, &guid, loaded, factory)
}

/// Frees an instance (and the states saved of it). Null is nothing to
/// free; a handle that is no live instance (freed already) is said on
/// the standard error and otherwise ignored.
pub extern "C" fn fmi2FreeInstance(c: fmi2Component) {
    if c.is_null() {
        return;
    }
    let freed = std::panic::catch_unwind(|| crate::registry::remove(c));
    if matches!(freed, Ok(false)) {
        eprintln!("{}", crate::guard::not_an_instance("fmi2FreeInstance", c));
    }
}

/// Sets the start time and the stop time (the tolerance is the
/// scenario's; one given is checked).
pub extern "C" fn fmi2SetupExperiment(
    c: fmi2Component,
    tolerance_defined: fmi2Boolean,
    tolerance: fmi2Real,
    start_time: fmi2Real,
    stop_time_defined: fmi2Boolean,
    stop_time: fmi2Real,
) -> fmi2Status {
    let tolerance = (tolerance_defined != fmi2False).then_some(tolerance);
    let stop_time = (stop_time_defined != fmi2False).then_some(stop_time);
    guard(c, "fmi2SetupExperiment", |c| {
        c.instance
            .setup_experiment(tolerance, start_time, stop_time)
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

/// `Ok` for no variables, else the error that this FMU has none of `kind`,
/// naming the first value reference asked for.
fn none_of(kind: &str, vr: *const fmi2ValueReference, nvr: usize) -> Outcome {
    // SAFETY: the host's obligation: `vr` is null or points to `nvr` references.
    match unsafe { slice(vr, nvr, "vr")? }.first() {
        None => Ok(()),
        Some(vr) => Err(Failure::error(format!(
            "unknown value reference {vr}: this FMU has no {kind} variables"
        ))),
    }
}

/// This FMU has no Integer variables.
///
/// # Safety
/// `vr` is null or points to `nvr` value references.
pub unsafe extern "C" fn fmi2GetInteger(
    c: fmi2Component,
    vr: *const fmi2ValueReference,
    nvr: usize,
    _value: *mut fmi2Integer,
) -> fmi2Status {
    guard(c, "fmi2GetInteger", |_| none_of("Integer", vr, nvr))
}

/// This FMU has no Boolean variables.
///
/// # Safety
/// `vr` is null or points to `nvr` value references.
pub unsafe extern "C" fn fmi2GetBoolean(
    c: fmi2Component,
    vr: *const fmi2ValueReference,
    nvr: usize,
    _value: *mut fmi2Boolean,
) -> fmi2Status {
    guard(c, "fmi2GetBoolean", |_| none_of("Boolean", vr, nvr))
}

/// This FMU has no String variables.
///
/// # Safety
/// `vr` is null or points to `nvr` value references.
pub unsafe extern "C" fn fmi2GetString(
    c: fmi2Component,
    vr: *const fmi2ValueReference,
    nvr: usize,
    _value: *mut fmi2String,
) -> fmi2Status {
    guard(c, "fmi2GetString", |_| none_of("String", vr, nvr))
}

/// This FMU has no Integer variables.
///
/// # Safety
/// `vr` is null or points to `nvr` value references.
pub unsafe extern "C" fn fmi2SetInteger(
    c: fmi2Component,
    vr: *const fmi2ValueReference,
    nvr: usize,
    _value: *const fmi2Integer,
) -> fmi2Status {
    guard(c, "fmi2SetInteger", |_| none_of("Integer", vr, nvr))
}

/// This FMU has no Boolean variables.
///
/// # Safety
/// `vr` is null or points to `nvr` value references.
pub unsafe extern "C" fn fmi2SetBoolean(
    c: fmi2Component,
    vr: *const fmi2ValueReference,
    nvr: usize,
    _value: *const fmi2Boolean,
) -> fmi2Status {
    guard(c, "fmi2SetBoolean", |_| none_of("Boolean", vr, nvr))
}

/// This FMU has no String variables.
///
/// # Safety
/// `vr` is null or points to `nvr` value references.
pub unsafe extern "C" fn fmi2SetString(
    c: fmi2Component,
    vr: *const fmi2ValueReference,
    nvr: usize,
    _value: *const fmi2String,
) -> fmi2Status {
    guard(c, "fmi2SetString", |_| none_of("String", vr, nvr))
}

/// Saves the instance's state (a copy, freed by `fmi2FreeFMUstate`); a
/// state of this instance's in `*state` is overwritten.
///
/// # Safety
/// `state` points to a writable `fmi2FMUstate`.
pub unsafe extern "C" fn fmi2GetFMUstate(c: fmi2Component, state: *mut fmi2FMUstate) -> fmi2Status {
    guard(c, "fmi2GetFMUstate", |c| {
        // SAFETY: as documented.
        let state = unsafe { state.as_mut() }.ok_or_else(|| Failure::error("FMUstate is null"))?;
        let handle = match state.is_null() {
            true => crate::registry::new_handle(),
            false => c.state(*state).map(|_| *state as usize)?,
        };
        c.states.insert(handle, c.instance.snapshot());
        *state = handle as *mut c_void;
        Ok(())
    })
}

/// Restores a state this instance saved.
pub extern "C" fn fmi2SetFMUstate(c: fmi2Component, state: fmi2FMUstate) -> fmi2Status {
    guard(c, "fmi2SetFMUstate", |c| {
        let snapshot = (c.states.get(&(state as usize)))
            .ok_or_else(|| crate::component::unknown_state(state))?;
        c.instance.restore(snapshot);
        Ok(())
    })
}

/// Frees a saved state and sets `*state` to null (null: nothing to free).
///
/// # Safety
/// `state` is null or points to an `fmi2FMUstate`.
pub unsafe extern "C" fn fmi2FreeFMUstate(
    c: fmi2Component,
    state: *mut fmi2FMUstate,
) -> fmi2Status {
    guard(c, "fmi2FreeFMUstate", |c| {
        // SAFETY: as documented.
        let Some(state) = (unsafe { state.as_mut() }).filter(|s| !s.is_null()) else {
            return Ok(());
        };
        c.state(*state)?;
        c.states.remove(&(*state as usize));
        *state = std::ptr::null_mut();
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
