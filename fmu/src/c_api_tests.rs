//! The C entry points as a host calls them: instantiation from a `file:`
//! URI (with a space in the path), a Co-Simulation run of a pushed block,
//! saved states, and refusals (wrong GUID, null pointers, variables of
//! types the FMU does not have) returned as status codes.

use crate::common::*;
use crate::cs::*;
use crate::ffi::*;
use crate::resources::{SPEC_FILE, guid};
use std::ffi::CString;
use std::ptr::{null, null_mut};

const BLOCK: &str = "model Block;\ncoordinates { x [m] }\nparameters { m [kg] = 2.0 }\n\
                     inputs { push(t [s]) [N] }\n\
                     kinetic = 0.5 * m * pow(dot(x), 2);\nforce x = push(t);\n";

/// A resource folder holding the block's spec; the URI names it with `%20`.
fn resources() -> (std::path::PathBuf, CString) {
    let dir = std::env::temp_dir().join(format!("lagrangian fmu {}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(dir.join(SPEC_FILE), BLOCK).unwrap();
    let uri = format!("file://{}", dir.display()).replace(' ', "%20");
    (dir, CString::new(uri).unwrap())
}

fn callbacks() -> fmi2CallbackFunctions {
    fmi2CallbackFunctions {
        logger: None,
        allocateMemory: None,
        freeMemory: None,
        stepFinished: None,
        componentEnvironment: null_mut(),
    }
}

fn instantiate(guid: &str, uri: &CString) -> fmi2Component {
    let (name, guid) = (c"block", CString::new(guid).unwrap());
    let functions = callbacks();
    // SAFETY: valid strings and callbacks that outlive the call.
    unsafe {
        fmi2Instantiate(
            name.as_ptr(),
            fmi2CoSimulation,
            guid.as_ptr(),
            uri.as_ptr(),
            &functions,
            fmi2False,
            fmi2False,
        )
    }
}

#[test]
fn a_host_runs_the_block_through_the_c_interface() {
    use fmi2Status::*;
    let (dir, uri) = resources();
    assert!(instantiate("{not its GUID}", &uri).is_null());
    let c = instantiate(&guid(BLOCK, ""), &uri);
    assert!(!c.is_null());
    assert_eq!(
        fmi2SetupExperiment(c, fmi2False, 0.0, 0.0, fmi2False, 0.0),
        fmi2OK
    );
    assert_eq!(fmi2EnterInitializationMode(c), fmi2OK);
    assert_eq!(fmi2ExitInitializationMode(c), fmi2OK);
    // x, der(x), der(der(x)), m, push: the input is value reference 4.
    let (push, force) = ([4u32], [4.0]);
    // SAFETY (all calls below): pointers to live arrays of the lengths given.
    assert_eq!(
        unsafe { fmi2SetReal(c, push.as_ptr(), 1, force.as_ptr()) },
        fmi2OK
    );
    assert_eq!(fmi2DoStep(c, 0.0, 0.5, fmi2True), fmi2OK);
    let mut saved: fmi2FMUstate = null_mut();
    assert_eq!(unsafe { fmi2GetFMUstate(c, &mut saved) }, fmi2OK);
    assert_eq!(fmi2DoStep(c, 0.5, 0.5, fmi2True), fmi2OK);
    let (vrs, mut values) = ([0u32, 1, 2], [0.0; 3]);
    assert_eq!(
        unsafe { fmi2GetReal(c, vrs.as_ptr(), 3, values.as_mut_ptr()) },
        fmi2OK
    );
    // x = ½ (F/m) t², ẋ = (F/m) t, ẍ = F/m at t = 1 s.
    for (value, expected) in values.iter().zip([1.0, 2.0, 2.0]) {
        assert!((value - expected).abs() < 1e-9, "{values:?}");
    }
    let mut time = 0.0;
    assert_eq!(unsafe { fmi2GetRealStatus(c, 2, &mut time) }, fmi2OK);
    assert_eq!(time, 1.0);
    assert_eq!(fmi2SetFMUstate(c, saved), fmi2OK);
    assert_eq!(
        unsafe { fmi2GetReal(c, vrs.as_ptr(), 1, values.as_mut_ptr()) },
        fmi2OK
    );
    assert!((values[0] - 0.25).abs() < 1e-9, "{values:?}");
    assert_eq!(unsafe { fmi2FreeFMUstate(c, &mut saved) }, fmi2OK);
    assert!(saved.is_null());
    assert_eq!(fmi2Terminate(c), fmi2OK);
    // Refusals are statuses, not crashes.
    assert_eq!(
        unsafe { fmi2GetReal(c, vrs.as_ptr(), 1, null_mut()) },
        fmi2Error
    );
    assert_eq!(unsafe { fmi2GetInteger(c, null(), 0, null_mut()) }, fmi2OK);
    assert_eq!(
        unsafe { fmi2GetInteger(c, vrs.as_ptr(), 1, null_mut()) },
        fmi2Error
    );
    assert_eq!(fmi2DoStep(null_mut(), 0.0, 0.1, fmi2True), fmi2Error);
    assert_eq!(
        fmi2SerializeFMUstate(c, null_mut(), null_mut(), 0),
        fmi2Error
    );
    // After an error, the instance is in the error state: only reading,
    // resetting, restoring and freeing are left.
    assert_eq!(fmi2DoStep(c, 1.0, 0.1, fmi2True), fmi2Error);
    assert_eq!(fmi2Reset(c), fmi2OK);
    fmi2FreeInstance(c);
    // A freed instance, freed again or called, is refused, not read.
    fmi2FreeInstance(c);
    assert_eq!(fmi2Reset(c), fmi2Error);
    assert_eq!(fmi2DoStep(c, 0.0, 0.1, fmi2True), fmi2Error);
    std::fs::remove_dir_all(dir).unwrap();
}

#[test]
fn the_version_and_platform_are_the_standards() {
    // SAFETY: static zero-terminated strings.
    let (version, platform) = unsafe {
        (
            std::ffi::CStr::from_ptr(fmi2GetVersion()),
            std::ffi::CStr::from_ptr(fmi2GetTypesPlatform()),
        )
    };
    assert_eq!(
        (version.to_str(), platform.to_str()),
        (Ok("2.0"), Ok("default"))
    );
}
