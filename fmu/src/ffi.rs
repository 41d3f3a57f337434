//! The C types of the FMI 2.0 interface, with the standard's names and
//! layouts (`fmi2TypesPlatform.h`, `fmi2FunctionTypes.h`).

#![allow(non_camel_case_types, non_upper_case_globals, non_snake_case)]

use std::ffi::{c_char, c_int, c_uint, c_void};

/// An instance, as the host holds it.
pub type fmi2Component = *mut c_void;
/// The host's own pointer, passed back to its callbacks.
pub type fmi2ComponentEnvironment = *mut c_void;
/// A saved state of an instance.
pub type fmi2FMUstate = *mut c_void;
/// A value reference.
pub type fmi2ValueReference = c_uint;
/// A real number.
pub type fmi2Real = f64;
/// An integer.
pub type fmi2Integer = c_int;
/// A boolean: [`fmi2True`] or [`fmi2False`].
pub type fmi2Boolean = c_int;
/// A character of a string.
pub type fmi2Char = c_char;
/// A zero-terminated string.
pub type fmi2String = *const fmi2Char;
/// A byte of a serialized state.
pub type fmi2Byte = c_char;

/// True.
pub const fmi2True: fmi2Boolean = 1;
/// False.
pub const fmi2False: fmi2Boolean = 0;

/// The status every function returns.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
pub enum fmi2Status {
    /// Everything is fine.
    fmi2OK = 0,
    /// Something looked wrong, the result may still be used.
    fmi2Warning = 1,
    /// The call did nothing; the host may retry differently.
    fmi2Discard = 2,
    /// This call failed; the instance may be freed or reset.
    fmi2Error = 3,
    /// The instance cannot be used any more.
    fmi2Fatal = 4,
    /// An asynchronous step is running (not used here).
    fmi2Pending = 5,
}

/// `fmi2ModelExchange` as `fmi2Instantiate` receives it.
pub const fmi2ModelExchange: c_int = 0;
/// `fmi2CoSimulation` as `fmi2Instantiate` receives it.
pub const fmi2CoSimulation: c_int = 1;

/// The host's logger: `printf`-style `message` with variadic arguments.
pub type fmi2CallbackLogger = Option<
    unsafe extern "C" fn(
        fmi2ComponentEnvironment,
        fmi2String,
        fmi2Status,
        fmi2String,
        fmi2String,
        ...
    ),
>;
/// The host's `calloc`.
pub type fmi2CallbackAllocateMemory = Option<unsafe extern "C" fn(usize, usize) -> *mut c_void>;
/// The host's `free`.
pub type fmi2CallbackFreeMemory = Option<unsafe extern "C" fn(*mut c_void)>;
/// The host's notice that an asynchronous step finished (not used here).
pub type fmi2StepFinished = Option<unsafe extern "C" fn(fmi2ComponentEnvironment, fmi2Status)>;

/// The callbacks the host passes to `fmi2Instantiate`.
#[repr(C)]
pub struct fmi2CallbackFunctions {
    /// Where messages go.
    pub logger: fmi2CallbackLogger,
    /// Memory allocation (the FMU allocates with Rust's allocator instead).
    pub allocateMemory: fmi2CallbackAllocateMemory,
    /// Memory release.
    pub freeMemory: fmi2CallbackFreeMemory,
    /// Asynchronous steps.
    pub stepFinished: fmi2StepFinished,
    /// Passed back to the callbacks.
    pub componentEnvironment: fmi2ComponentEnvironment,
}

/// What `fmi2NewDiscreteStates` reports.
#[repr(C)]
pub struct fmi2EventInfo {
    /// Another round of `fmi2NewDiscreteStates` is needed.
    pub newDiscreteStatesNeeded: fmi2Boolean,
    /// The simulation should stop.
    pub terminateSimulation: fmi2Boolean,
    /// The nominal values of the states changed.
    pub nominalsOfContinuousStatesChanged: fmi2Boolean,
    /// The states jumped: the host reads them again.
    pub valuesOfContinuousStatesChanged: fmi2Boolean,
    /// `nextEventTime` is a time event.
    pub nextEventTimeDefined: fmi2Boolean,
    /// The next time event, when defined.
    pub nextEventTime: fmi2Real,
}

/// `fmi2StatusKind` as `fmi2Get*Status` receives it.
pub type fmi2StatusKind = c_int;
/// The platform string `fmi2GetTypesPlatform` returns.
pub const fmi2TypesPlatform: &std::ffi::CStr = c"default";
/// The version string `fmi2GetVersion` returns.
pub const fmi2Version: &std::ffi::CStr = c"2.0";
