//! What stands between the host and the Rust code: the instance behind an
//! `fmi2Component`, the host's logger, and [`guard`], which every entry
//! point runs its body in so that no panic unwinds into the host (it
//! becomes `fmi2Fatal`) and every failure is logged and returned as its
//! status.

use crate::ffi::{fmi2CallbackLogger, fmi2Component, fmi2ComponentEnvironment, fmi2Status};
use crate::instance::{Instance, Outcome};
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
}

impl Component {
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

/// Runs `body` on the component `c` (see [`shielded`]); a null `c`, or one
/// broken by an earlier panic, is refused.
pub fn guard(
    c: fmi2Component,
    call: &str,
    body: impl FnOnce(&mut Component) -> Outcome,
) -> fmi2Status {
    if c.is_null() {
        return fmi2Status::fmi2Error;
    }
    // SAFETY: a non-null component is one fmi2Instantiate returned and
    // fmi2FreeInstance has not freed (the host's obligation).
    let component = unsafe { &mut *(c as *mut Component) };
    if component.broken {
        return fmi2Status::fmi2Fatal;
    }
    let logger = component.logger;
    let name = component.instance.name.clone();
    let report = |status, message: &str| logger.log(&name, status, "logStatusError", message);
    let status = shielded(call, &report, || body(&mut *component));
    if status == fmi2Status::fmi2Fatal {
        component.broken = true;
    }
    status
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
