//! Studies of `lagrangian` crash models, above the simulation library
//! (`lagrangian-sim`): what a host — the `lpm` command line, the Python
//! package — does with many runs of a scenario, or with one run's figure.
//!
//! * [`sweep`] (feature `sweep`): a scenario run many times in parallel, to a
//!   CSV or Parquet table.
//! * [`fit`] (feature `fit`): identification of the crush characteristic by
//!   Levenberg–Marquardt.
//! * [`plot`] (feature `plot`): SVG figures of a run and of a fit.
//!
//! And the services every host calls, failing with [`error::StudyError`]:
//! [`spec`] (compile a spec, find its scenario), [`compare`] (the ISO/TS
//! 18571 rating of a run's channels against a test's), [`simulate`] (one run and
//! its files; [`iso_mme`] the run as an ISO-MME test), [`test_data`] (a
//! crash test's channels in SI units, its occupants, its vehicle channels
//! as a fit's time histories), [`eval`] and [`mass`]
//! (a model at one state), [`fitting`] (a fit and its files), [`sweeping`] (a sweep, its journal, shards and merge,
//! its envelopes; [`progress::Progress`] the host's view of it), and the
//! exit statuses a host ends with ([`status::ExitStatus`]). Every service
//! reads its specs, scenarios and tables from the host's [`files::Files`].

#[cfg(feature = "plot")]
pub mod compare;
pub mod error;
pub mod eval;
#[cfg(feature = "plot")]
pub mod iso_mme;
pub use lagrangian_sim::files;
#[cfg(feature = "fit")]
pub mod fit;
#[cfg(all(feature = "fit", feature = "plot"))]
pub mod fitting;
pub mod mass;
pub mod metrics;
#[cfg(feature = "plot")]
pub mod plot;
pub mod progress;
#[cfg(feature = "plot")]
pub mod report;
#[cfg(feature = "plot")]
pub mod simulate;
pub mod spec;
pub mod status;
#[cfg(feature = "sweep")]
pub mod sweep;
#[cfg(all(feature = "sweep", feature = "plot"))]
pub mod sweeping;
pub mod test_data;
