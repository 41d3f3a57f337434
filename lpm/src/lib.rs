//! The `lpm` command line as a library: each subcommand's options and
//! `run`, its failures, and the exit statuses ([`status::ExitStatus`], the
//! studies' table, which the Python package shares without depending on
//! `lpm`), for the `lpm` binary and its tests.

pub mod audit;
pub mod chain;
pub mod compare;
pub mod derive;
pub mod eval;
pub mod failure;
pub mod fit;
pub mod fmu;
pub mod generate;
pub mod linearize;
pub mod metrics;
pub mod simulate;
mod study_error;
pub mod sweep;
pub mod warnings;

/// The exit statuses, shared with the Python package (`lagrangian-studies`).
pub use lagrangian_studies::status;
