//! What stands between the host and the Rust code: [`guard`], which every
//! entry point runs its body in on the component behind an `fmi2Component`
//! ([`crate::component`], found through [`crate::registry`]): it refuses a
//! handle that is no live instance and a call the state machine
//! ([`crate::machine`]) does not allow in the instance's state, lets no
//! panic unwind into the host (it becomes `fmi2Fatal`), logs every failure
//! and returns it as its status; after an `fmi2Error` the instance is in
//! the standard's error state.

use crate::component::Component;
use crate::ffi::{fmi2Component, fmi2Status};
use crate::instance::{Failure, Outcome};
use std::ffi::c_char;
use std::panic::{AssertUnwindSafe, catch_unwind};

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
        crate::machine::check(call, instance.interface, instance.mode())?;
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

/// `n` values at `p` as a slice (empty for `n == 0`, whatever `p`);
/// `Err` for a null `p` with `n > 0`.
///
/// # Safety
/// A non-null `p` points to `n` valid values that outlive the slice.
pub unsafe fn slice<'a, T>(p: *const T, n: usize, what: &str) -> Outcome<&'a [T]> {
    match (n, p.is_null()) {
        (0, _) => Ok(&[]),
        (_, true) => Err(Failure::error(format!("{what} is null"))),
        // SAFETY: as documented.
        (_, false) => Ok(unsafe { std::slice::from_raw_parts(p, n) }),
    }
}

/// `n` values at `p` as a mutable slice (see [`slice()`]).
///
/// # Safety
/// A non-null `p` points to `n` writable values that outlive the slice.
pub unsafe fn slice_mut<'a, T>(p: *mut T, n: usize, what: &str) -> Outcome<&'a mut [T]> {
    match (n, p.is_null()) {
        (0, _) => Ok(&mut []),
        (_, true) => Err(Failure::error(format!("{what} is null"))),
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
