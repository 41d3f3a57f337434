//! Studies of `lagrangian` crash models, above the simulation library
//! (`lagrangian-sim`): what a host — the `lpm` command line, the Python
//! package — does with many runs of a scenario, or with one run's figure.
//!
//! * [`sweep`] (feature `sweep`): a scenario run many times in parallel, to a
//!   CSV or Parquet table.
//! * [`fit`] (feature `fit`): identification of the crush characteristic by
//!   Levenberg–Marquardt.
//! * [`plot`] (feature `plot`): SVG figures of a run and of a fit.

#![warn(missing_docs)]

#[cfg(feature = "fit")]
pub mod fit;
#[cfg(feature = "plot")]
pub mod plot;
#[cfg(feature = "sweep")]
pub mod sweep;
