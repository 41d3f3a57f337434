//! [`export_fmi2!`](crate::export_fmi2): the 44 C entry points of FMI 2.0
//! under their standard names, for the one crate that is an FMU's binary.
//!
//! The entry points of [`crate::common`], [`crate::cs`] and [`crate::me`]
//! carry no `#[no_mangle]`: a library that links this crate (`lpm`, the
//! Python extension) exports no `fmi2*` symbol. An FMU binary invokes the
//! macro once with the [`PlantFactory`](crate::plant::PlantFactory) that
//! makes its plant; the macro defines, for each entry point, an exported
//! function that forwards to it.

/// The 44 functions of the FMI 2.0 standard (`fmi2Functions.h`), which
/// [`export_fmi2!`](crate::export_fmi2) exports: what `lpm export-fmu`
/// checks an FMU binary for.
pub const FMI2_FUNCTIONS: [&str; 44] = [
    "fmi2GetTypesPlatform",
    "fmi2GetVersion",
    "fmi2SetDebugLogging",
    "fmi2Instantiate",
    "fmi2FreeInstance",
    "fmi2SetupExperiment",
    "fmi2EnterInitializationMode",
    "fmi2ExitInitializationMode",
    "fmi2Terminate",
    "fmi2Reset",
    "fmi2GetReal",
    "fmi2GetInteger",
    "fmi2GetBoolean",
    "fmi2GetString",
    "fmi2SetReal",
    "fmi2SetInteger",
    "fmi2SetBoolean",
    "fmi2SetString",
    "fmi2GetFMUstate",
    "fmi2SetFMUstate",
    "fmi2FreeFMUstate",
    "fmi2SerializedFMUstateSize",
    "fmi2SerializeFMUstate",
    "fmi2DeSerializeFMUstate",
    "fmi2GetDirectionalDerivative",
    "fmi2EnterEventMode",
    "fmi2NewDiscreteStates",
    "fmi2EnterContinuousTimeMode",
    "fmi2CompletedIntegratorStep",
    "fmi2SetTime",
    "fmi2SetContinuousStates",
    "fmi2GetDerivatives",
    "fmi2GetEventIndicators",
    "fmi2GetContinuousStates",
    "fmi2GetNominalsOfContinuousStates",
    "fmi2SetRealInputDerivatives",
    "fmi2GetRealOutputDerivatives",
    "fmi2DoStep",
    "fmi2CancelStep",
    "fmi2GetStatus",
    "fmi2GetRealStatus",
    "fmi2GetIntegerStatus",
    "fmi2GetBooleanStatus",
    "fmi2GetStringStatus",
];

/// Exports the FMI 2.0 entry points from the cdylib that invokes it, with
/// `$factory` (a [`PlantFactory`](crate::plant::PlantFactory)) making the
/// plant of each instance: [`plant`](crate::plant::plant) for the
/// interpreter, [`compiled::<N, Model>`](crate::plant::compiled) for a
/// compiled model.
#[macro_export]
macro_rules! export_fmi2 {
    ($factory:expr) => {
        const _: () = {
            use ::std::ffi::{c_char, c_int};
            use $crate::ffi::*;

            /// `fmi2Instantiate` with this binary's plant.
            ///
            /// # Safety
            /// As [`instantiate_with`]($crate::common::instantiate_with).
            #[unsafe(no_mangle)]
            #[allow(non_snake_case, clippy::too_many_arguments)]
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
                // SAFETY: the host's obligations, as documented.
                unsafe {
                    $crate::common::instantiate_with(
                        $factory, arguments, functions, visible, logging_on,
                    )
                }
            }

            $crate::__fmi2_forward! {
                common::fmi2GetTypesPlatform() -> *const c_char;
                common::fmi2GetVersion() -> *const c_char;
                common::fmi2SetDebugLogging(c: fmi2Component, logging_on: fmi2Boolean, n_categories: usize, categories: *const fmi2String) -> fmi2Status;
                common::fmi2FreeInstance(c: fmi2Component) -> ();
                common::fmi2SetupExperiment(c: fmi2Component, tolerance_defined: fmi2Boolean, tolerance: fmi2Real, start_time: fmi2Real, stop_time_defined: fmi2Boolean, stop_time: fmi2Real) -> fmi2Status;
                common::fmi2EnterInitializationMode(c: fmi2Component) -> fmi2Status;
                common::fmi2ExitInitializationMode(c: fmi2Component) -> fmi2Status;
                common::fmi2Terminate(c: fmi2Component) -> fmi2Status;
                common::fmi2Reset(c: fmi2Component) -> fmi2Status;
                common::fmi2GetReal(c: fmi2Component, vr: *const fmi2ValueReference, nvr: usize, value: *mut fmi2Real) -> fmi2Status;
                common::fmi2SetReal(c: fmi2Component, vr: *const fmi2ValueReference, nvr: usize, value: *const fmi2Real) -> fmi2Status;
                common::fmi2GetInteger(c: fmi2Component, vr: *const fmi2ValueReference, nvr: usize, value: *mut fmi2Integer) -> fmi2Status;
                common::fmi2GetBoolean(c: fmi2Component, vr: *const fmi2ValueReference, nvr: usize, value: *mut fmi2Boolean) -> fmi2Status;
                common::fmi2GetString(c: fmi2Component, vr: *const fmi2ValueReference, nvr: usize, value: *mut fmi2String) -> fmi2Status;
                common::fmi2SetInteger(c: fmi2Component, vr: *const fmi2ValueReference, nvr: usize, value: *const fmi2Integer) -> fmi2Status;
                common::fmi2SetBoolean(c: fmi2Component, vr: *const fmi2ValueReference, nvr: usize, value: *const fmi2Boolean) -> fmi2Status;
                common::fmi2SetString(c: fmi2Component, vr: *const fmi2ValueReference, nvr: usize, value: *const fmi2String) -> fmi2Status;
                common::fmi2GetFMUstate(c: fmi2Component, state: *mut fmi2FMUstate) -> fmi2Status;
                common::fmi2SetFMUstate(c: fmi2Component, state: fmi2FMUstate) -> fmi2Status;
                common::fmi2FreeFMUstate(c: fmi2Component, state: *mut fmi2FMUstate) -> fmi2Status;
                common::fmi2SerializedFMUstateSize(c: fmi2Component, state: fmi2FMUstate, size: *mut usize) -> fmi2Status;
                common::fmi2SerializeFMUstate(c: fmi2Component, state: fmi2FMUstate, bytes: *mut fmi2Byte, size: usize) -> fmi2Status;
                common::fmi2DeSerializeFMUstate(c: fmi2Component, bytes: *const fmi2Byte, size: usize, state: *mut fmi2FMUstate) -> fmi2Status;
                common::fmi2GetDirectionalDerivative(c: fmi2Component, unknown: *const fmi2ValueReference, n_unknown: usize, known: *const fmi2ValueReference, n_known: usize, dv_known: *const fmi2Real, dv_unknown: *mut fmi2Real) -> fmi2Status;
                cs::fmi2SetRealInputDerivatives(c: fmi2Component, vr: *const fmi2ValueReference, nvr: usize, order: *const fmi2Integer, value: *const fmi2Real) -> fmi2Status;
                cs::fmi2GetRealOutputDerivatives(c: fmi2Component, vr: *const fmi2ValueReference, nvr: usize, order: *const fmi2Integer, value: *mut fmi2Real) -> fmi2Status;
                cs::fmi2DoStep(c: fmi2Component, t: fmi2Real, h: fmi2Real, no_set_fmu_state_prior: fmi2Boolean) -> fmi2Status;
                cs::fmi2CancelStep(c: fmi2Component) -> fmi2Status;
                cs::fmi2GetStatus(c: fmi2Component, kind: fmi2StatusKind, value: *mut fmi2Status) -> fmi2Status;
                cs::fmi2GetRealStatus(c: fmi2Component, kind: fmi2StatusKind, value: *mut fmi2Real) -> fmi2Status;
                cs::fmi2GetIntegerStatus(c: fmi2Component, kind: fmi2StatusKind, value: *mut fmi2Integer) -> fmi2Status;
                cs::fmi2GetBooleanStatus(c: fmi2Component, kind: fmi2StatusKind, value: *mut fmi2Boolean) -> fmi2Status;
                cs::fmi2GetStringStatus(c: fmi2Component, kind: fmi2StatusKind, value: *mut fmi2String) -> fmi2Status;
                me::fmi2EnterEventMode(c: fmi2Component) -> fmi2Status;
                me::fmi2NewDiscreteStates(c: fmi2Component, info: *mut fmi2EventInfo) -> fmi2Status;
                me::fmi2EnterContinuousTimeMode(c: fmi2Component) -> fmi2Status;
                me::fmi2CompletedIntegratorStep(c: fmi2Component, no_set_fmu_state_prior: fmi2Boolean, enter_event_mode: *mut fmi2Boolean, terminate: *mut fmi2Boolean) -> fmi2Status;
                me::fmi2SetTime(c: fmi2Component, t: fmi2Real) -> fmi2Status;
                me::fmi2SetContinuousStates(c: fmi2Component, x: *const fmi2Real, nx: usize) -> fmi2Status;
                me::fmi2GetDerivatives(c: fmi2Component, dx: *mut fmi2Real, nx: usize) -> fmi2Status;
                me::fmi2GetEventIndicators(c: fmi2Component, g: *mut fmi2Real, ni: usize) -> fmi2Status;
                me::fmi2GetContinuousStates(c: fmi2Component, x: *mut fmi2Real, nx: usize) -> fmi2Status;
                me::fmi2GetNominalsOfContinuousStates(c: fmi2Component, x_nominal: *mut fmi2Real, nx: usize) -> fmi2Status;
            }
        };
    };
}

/// For [`export_fmi2!`](crate::export_fmi2): an exported function under
/// each name given that forwards its arguments to the entry point of that
/// name in the module given.
#[doc(hidden)]
#[macro_export]
macro_rules! __fmi2_forward {
    ($($module:ident :: $name:ident ( $($argument:ident : $type:ty),* ) -> $returns:ty;)*) => {$(
        /// The FMI 2.0 entry point of this name.
        ///
        /// # Safety
        /// As the function it forwards to.
        #[unsafe(no_mangle)]
        #[allow(non_snake_case, unused_unsafe)]
        pub unsafe extern "C" fn $name($($argument: $type),*) -> $returns {
            // SAFETY: the host's obligations, those of the function called.
            unsafe { $crate::$module::$name($($argument),*) }
        }
    )*};
}

#[cfg(test)]
mod tests {
    /// The names `export_fmi2!` exports, read from its text: the
    /// hand-written `fmi2Instantiate` and each forwarded `module::name(`.
    #[test]
    fn the_macro_exports_every_function_of_the_standard_and_no_other() {
        let text = include_str!("export.rs");
        let body = &text[..text.find("#[cfg(test)]").unwrap()];
        let mut exported = vec!["fmi2Instantiate".to_string()];
        for module in ["common::", "cs::", "me::"] {
            for (i, _) in body.match_indices(&format!("{module}fmi2")) {
                let name = &body[i + module.len()..];
                exported.push(name[..name.find('(').unwrap()].to_string());
            }
        }
        exported.sort();
        let mut standard: Vec<String> = super::FMI2_FUNCTIONS.map(String::from).to_vec();
        standard.sort();
        assert_eq!(exported, standard);
    }
}
