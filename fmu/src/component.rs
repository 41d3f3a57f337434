//! What an `fmi2Component` handle stands for: the instance, the host's
//! logger, and the states saved from it. The registry keeps the live ones
//! by handle; the guard finds them there for every call.

use crate::ffi::{fmi2CallbackLogger, fmi2ComponentEnvironment, fmi2Status};
use crate::instance::{Failure, Instance, Outcome, Snapshot};
use std::collections::BTreeMap;
use std::ffi::CString;

/// The host's logger and its environment pointer.
#[derive(Clone, Copy)]
pub struct Logger {
    /// The callback (`None`: the host gave none).
    pub callback: fmi2CallbackLogger,
    /// Passed back to the callback.
    pub environment: fmi2ComponentEnvironment,
}

impl Logger {
    /// Sends `message` under `category` with `status` for `instance`; `%`
    /// is doubled, as the message is a `printf` format for the host.
    pub fn log(&self, instance: &str, status: fmi2Status, category: &str, message: &str) {
        let Some(callback) = self.callback else {
            return;
        };
        let text = |s: &str| CString::new(s.replace('\0', " ")).unwrap_or_default();
        let (name, category) = (text(instance), text(category));
        let message = text(&message.replace('%', "%%"));
        // SAFETY: the host's logger with valid zero-terminated strings that
        // live across the call, and no variadic arguments (no `%` left).
        unsafe {
            callback(
                self.environment,
                name.as_ptr(),
                status,
                category.as_ptr(),
                message.as_ptr(),
            )
        }
    }
}

/// What an `fmi2Component` points to.
pub struct Component {
    /// The instance.
    pub instance: Instance,
    /// The host's logger.
    pub logger: Logger,
    /// Set when a call panicked: the instance may be inconsistent, so
    /// every later call is `fmi2Fatal`.
    pub broken: bool,
    /// The states `fmi2GetFMUstate` saved and `fmi2FreeFMUstate` has not
    /// freed, by handle (numbered as the registry numbers instances): a
    /// handle of a freed state, or of another instance's, is refused.
    pub states: BTreeMap<usize, Snapshot>,
}

impl Component {
    /// A component of `instance` that logs to `logger`.
    pub fn new(instance: Instance, logger: Logger) -> Component {
        Component {
            instance,
            logger,
            broken: false,
            states: BTreeMap::new(),
        }
    }

    /// The saved state of handle `state`.
    pub fn state(&self, state: *mut std::ffi::c_void) -> Outcome<&Snapshot> {
        (self.states.get(&(state as usize))).ok_or_else(|| unknown_state(state))
    }

    /// Logs `message` with `status` under the category that goes with it.
    pub fn log(&self, status: fmi2Status, message: &str) {
        let category = match status {
            fmi2Status::fmi2OK => "logEvents",
            _ => "logStatusError",
        };
        self.logger
            .log(&self.instance.name, status, category, message);
    }
}

/// The failure of a state handle this instance did not save.
pub fn unknown_state(state: *mut std::ffi::c_void) -> Failure {
    Failure::error(format!(
        "FMU state {state:p} is not one this instance saved (freed already, or another \
         instance's)"
    ))
}
