//! A generic FMI 2.0 FMU for lagrangian models: one shared library, built
//! once per platform, that interprets the spec and scenario packed in the
//! FMU's `resources/` (`model.lpm`, `scenario.toml`), so that exporting a
//! model (`lpm export-fmu`) needs no compiler.
//!
//! It serves both interfaces:
//!
//! * Co-Simulation: `fmi2DoStep` runs the scenario's integrator with the
//!   crash components' events, as `lpm simulate` does;
//! * Model Exchange: the continuous states are `(q, q̇)`, their derivatives
//!   `(q̇, q̈)`, and the event indicators the components' event functions
//!   and the model's switching functions.
//!
//! Modules: the C types ([`ffi`]); the variables and their value references
//! ([`variables`]), shared with `lpm export-fmu`; loading the resources
//! ([`resources`]); the model at its dimension behind one trait
//! ([`plant`]); the instance's state machine ([`instance`]); and the 44 C
//! entry points ([`common`], [`cs`], [`me`]), each run inside [`guard`] so
//! that no panic reaches the host.

#![warn(missing_docs)]

pub mod common;
pub mod cs;
pub mod ffi;
pub mod guard;
pub mod instance;
pub mod me;
pub mod plant;
pub mod resources;
pub mod variables;

#[cfg(test)]
mod c_api_tests;
#[cfg(test)]
mod tests;
