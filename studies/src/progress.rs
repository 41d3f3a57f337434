//! What a host sees of a sweep under way, and how it stops one: `lpm`
//! draws a progress bar and stops on Ctrl-C; the Python package calls back
//! and stops on a signal Python raises.

/// A host's view of a sweep's runs. Shared by the worker threads (they ask
/// [`Progress::stop_requested`] before each new run), hence `Sync` and
/// `&self` throughout.
pub trait Progress: Sync {
    /// The sweep is about to make `runs` runs, of which `done` are in its
    /// journal already.
    fn start(&self, runs: usize, done: usize) {
        let _ = (runs, done);
    }

    /// A run finished; called on the sweep's calling thread, in run order.
    fn run_done(&self);

    /// The runs are all in (or the sweep stopped).
    fn finish(&self) {}

    /// Whether the host asks the sweep to stop: no new run starts, the
    /// runs under way finish and are kept, and the sweep fails as
    /// interrupted.
    fn stop_requested(&self) -> bool;
}

/// No display and no stop.
impl Progress for () {
    fn run_done(&self) {}

    fn stop_requested(&self) -> bool {
        false
    }
}
