//! What stands between the host and the Rust code: the instance behind an
//! `fmi2Component` (found through [`crate::registry`]), the host's logger,
//! and [`guard`], which every entry point runs its body in: it refuses a
//! handle that is no live instance and a call the state machine
//! ([`crate::machine`]) does not allow in the instance's state, lets no
//! panic unwind into the host (it becomes `fmi2Fatal`), logs every failure
//! and returns it as its status; after an `fmi2Error` the instance is in
//! the standard's error state.

use crate::ffi::{fmi2CallbackLogger, fmi2Component, fmi2ComponentEnvironment, fmi2Status};
use crate::instance::{Failure, Instance, Outcome, Snapshot};
use std::collections::BTreeMap;
use std::ffi::{CString, c_char};
use std::panic::{AssertUnwindSafe, catch_unwind};

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
    /// freed, by handle ([`crate::registry::new_handle`]): a handle of a
    /// freed state, or of another instance's, is refused.
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

/// Runs `body`: its failure is reported with `report` and returned as its
/// status; a panic is reported as an internal error and becomes
/// `fmi2Fatal`.
pub fn shielded(
    call: &str,
    report: &dyn Fn(fmi2Status, &str),
    body: impl FnOnce() -> Outcome,
) -> fmi2Status {
    match catch_unwind(AssertUnwindSafe(body)) {
        Ok(Ok(())) => fmi2Status::fmi2OK,
        Ok(Err(failure)) => {
            report(failure.status, &format!("{call}: {}", failure.message));
            failure.status
        }
        Err(panic) => {
            let why = (panic.downcast_ref::<&str>().map(|s| s.to_string()))
                .or_else(|| panic.downcast_ref::<String>().cloned())
                .unwrap_or_else(|| "unknown cause".to_string());
            report(
                fmi2Status::fmi2Fatal,
                &format!("{call}: internal error (a bug in the FMU): {why}"),
            );
            fmi2Status::fmi2Fatal
        }
    }
}

/// Runs `body` on the component of handle `c` (see [`shielded`]) if the
/// state machine allows `call` in its state. A handle that is no live
/// instance (null, freed, never returned) is `fmi2Error`, said on the
/// standard error (there is no logger to say it to); a component broken by
/// an earlier panic is `fmi2Fatal`; after an `fmi2Error` the instance is
/// in the error state.
pub fn guard(
    c: fmi2Component,
    call: &str,
    body: impl FnOnce(&mut Component) -> Outcome,
) -> fmi2Status {
    let Some(entry) = crate::registry::find(c) else {
        eprintln!("{}", not_an_instance(call, c));
        return fmi2Status::fmi2Error;
    };
    let (logger, name) = (entry.logger, entry.name.clone());
    let report = |status, message: &str| logger.log(&name, status, "logStatusError", message);
    let Some(mut component) = entry.try_lock() else {
        let message = format!("{call}: called while another call on this instance runs");
        report(fmi2Status::fmi2Error, &message);
        return fmi2Status::fmi2Error;
    };
    if component.broken {
        return fmi2Status::fmi2Fatal;
    }
    let status = shielded(call, &report, || {
        let instance = &component.instance;
        crate::machine::check(call, instance.interface, instance.mode()).map_err(Failure::error)?;
        body(&mut component)
    });
    match status {
        fmi2Status::fmi2Fatal => component.broken = true,
        fmi2Status::fmi2Error => component.instance.fail(),
        _ => {}
    }
    status
}

/// Why `c` is not an instance `call` can run on.
pub fn not_an_instance(call: &str, c: fmi2Component) -> String {
    match c.is_null() {
        true => format!("lagrangian FMU: {call}: the instance is null"),
        false => format!(
            "lagrangian FMU: {call}: {c:p} is no live instance of this FMU \
             (freed already, or not returned by its fmi2Instantiate)"
        ),
    }
}

/// The failure of a state handle this instance did not save.
pub fn unknown_state(state: *mut std::ffi::c_void) -> Failure {
    Failure::error(format!(
        "FMU state {state:p} is not one this instance saved (freed already, or another \
         instance's)"
    ))
}

/// `n` values at `p` as a slice (empty for `n == 0`, whatever `p`);
/// `Err` for a null `p` with `n > 0`.
///
/// # Safety
/// A non-null `p` points to `n` valid values that outlive the slice.
pub unsafe fn slice<'a, T>(p: *const T, n: usize, what: &str) -> Outcome<&'a [T]> {
    match (n, p.is_null()) {
        (0, _) => Ok(&[]),
        (_, true) => Err(crate::instance::Failure::error(format!("{what} is null"))),
        // SAFETY: as documented.
        (_, false) => Ok(unsafe { std::slice::from_raw_parts(p, n) }),
    }
}

/// `n` values at `p` as a mutable slice (see [`slice`]).
///
/// # Safety
/// A non-null `p` points to `n` writable values that outlive the slice.
pub unsafe fn slice_mut<'a, T>(p: *mut T, n: usize, what: &str) -> Outcome<&'a mut [T]> {
    match (n, p.is_null()) {
        (0, _) => Ok(&mut []),
        (_, true) => Err(crate::instance::Failure::error(format!("{what} is null"))),
        // SAFETY: as documented.
        (_, false) => Ok(unsafe { std::slice::from_raw_parts_mut(p, n) }),
    }
}

/// A C string argument as text (`None` for null or non-UTF-8).
///
/// # Safety
/// A non-null `p` is a zero-terminated string.
pub unsafe fn text(p: *const c_char) -> Option<String> {
    if p.is_null() {
        return None;
    }
    // SAFETY: as documented.
    let s = unsafe { std::ffi::CStr::from_ptr(p) };
    s.to_str().ok().map(str::to_string)
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::cell::RefCell;

    /// An entry point in the C ABI, as the host calls it: a panic escaping
    /// it would abort the test process.
    extern "C" fn entry_point_that_panics(reported: *const RefCell<Vec<String>>) -> fmi2Status {
        // SAFETY: the test passes a live RefCell.
        let reported = unsafe { &*reported };
        let report = |status: fmi2Status, message: &str| {
            reported.borrow_mut().push(format!("{status:?}: {message}"));
        };
        shielded("fmi2DoStep", &report, || {
            let v: Vec<f64> = Vec::new();
            let _ = v[3]; // out of bounds: panics
            Ok(())
        })
    }

    #[test]
    fn a_panic_in_an_entry_point_is_fatal_not_an_abort() {
        let reported = RefCell::new(Vec::new());
        let status = entry_point_that_panics(&reported);
        assert_eq!(status, fmi2Status::fmi2Fatal);
        let reported = reported.into_inner();
        assert_eq!(reported.len(), 1);
        assert!(
            reported[0].starts_with("fmi2Fatal: fmi2DoStep: internal error"),
            "{reported:?}"
        );
        assert!(reported[0].contains("index out of bounds"), "{reported:?}");
    }

    #[test]
    fn a_failure_is_reported_and_returned_as_its_status() {
        let reported = RefCell::new(Vec::new());
        let report = |status: fmi2Status, message: &str| {
            reported.borrow_mut().push(format!("{status:?}: {message}"));
        };
        let status = shielded("fmi2SetReal", &report, || {
            Err(crate::instance::Failure::error("bad value"))
        });
        assert_eq!(status, fmi2Status::fmi2Error);
        assert_eq!(reported.into_inner(), ["fmi2Error: fmi2SetReal: bad value"]);
        let ok = shielded("fmi2SetReal", &|_, _| panic!("not reported"), || Ok(()));
        assert_eq!(ok, fmi2Status::fmi2OK);
    }
}
