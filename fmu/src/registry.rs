//! The live instances, by handle. An `fmi2Component` this FMU returns is
//! not a pointer but a handle, a number never given out twice, that only
//! [`find`] turns into an instance, through the table of live ones. So a
//! handle the host freed already, one of another FMU, or garbage, is
//! recognized and refused (by the guard, `guard::guard`) instead of read as
//! memory: `fmi2FreeInstance` twice, or any call on a freed instance, is
//! harmless. The same numbering names the saved states of `fmi2GetFMUstate`
//! ([`crate::component::Component::states`]).
//!
//! Each instance is behind its own lock, taken with `try_lock`: two calls
//! on one instance at once (which the standard forbids; a logger callback
//! that calls back into the FMU does it) are refused instead of racing or
//! deadlocking, and an instance freed while one of its calls runs on
//! another thread lives until that call returns.

use crate::component::{Component, Logger};
use crate::ffi::fmi2Component;
use std::collections::BTreeMap;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::{Arc, Mutex, MutexGuard, PoisonError, TryLockError};

/// A live instance.
pub struct Entry {
    /// The instance name, for messages about the entry itself.
    pub name: String,
    /// The host's logger, for messages about the entry itself.
    pub logger: Logger,
    component: Mutex<Component>,
}

// SAFETY: the component holds the host's logger and environment pointers
// and the plant; the standard lets the host call an instance from any
// thread, one call at a time, and the component is only reached through
// its lock. Nothing it holds is shared with anything outside it.
unsafe impl Send for Entry {}
// SAFETY: as for `Send`: all access to the component goes through its lock.
unsafe impl Sync for Entry {}

impl Entry {
    /// The component, unless a call on it is running (`None`).
    pub fn try_lock(&self) -> Option<MutexGuard<'_, Component>> {
        match self.component.try_lock() {
            Ok(component) => Some(component),
            // A panic is caught inside each call; if one got past, the
            // component is marked broken, and reading it is still safe.
            Err(TryLockError::Poisoned(poisoned)) => Some(PoisonError::into_inner(poisoned)),
            Err(TryLockError::WouldBlock) => None,
        }
    }
}

static LIVE: Mutex<BTreeMap<usize, Arc<Entry>>> = Mutex::new(BTreeMap::new());
/// The next handle; 0 is null, so handles start at 1.
static NEXT: AtomicUsize = AtomicUsize::new(1);

fn live() -> MutexGuard<'static, BTreeMap<usize, Arc<Entry>>> {
    LIVE.lock().unwrap_or_else(PoisonError::into_inner)
}

/// A number no instance or saved state has had.
pub fn new_handle() -> usize {
    NEXT.fetch_add(1, Ordering::Relaxed)
}

/// Registers `component`; returns its handle.
pub fn register(component: Component) -> fmi2Component {
    let entry = Entry {
        name: component.instance.name.clone(),
        logger: component.logger,
        component: Mutex::new(component),
    };
    let handle = new_handle();
    live().insert(handle, Arc::new(entry));
    handle as fmi2Component
}

/// The live instance of handle `c`, if any.
pub fn find(c: fmi2Component) -> Option<Arc<Entry>> {
    live().get(&(c as usize)).cloned()
}

/// Removes the instance of handle `c` from the live ones; it is freed
/// when the last call on it returns. `false` if it was not live.
pub fn remove(c: fmi2Component) -> bool {
    // Dropped after the table's lock is released.
    let removed = live().remove(&(c as usize));
    removed.is_some()
}

/// The number of live instances.
pub fn count() -> usize {
    live().len()
}
