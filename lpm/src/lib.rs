//! The `lpm` command line as a library: each subcommand's options and
//! `run`, the exit statuses ([`status::ExitStatus`]) and failures, shared by
//! the `lpm` binary and the Python package.

pub mod audit;
pub mod chain;
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
