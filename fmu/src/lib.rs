//! The FMI 2.0 logic of lagrangian's FMUs. An FMU's binary is a cdylib
//! that invokes [`export_fmi2!`] once: the generic one (`fmu/binary`,
//! crate `lagrangian-fmu`), built once per platform, interprets the spec
//! and scenario packed in the FMU's `resources/` (`model.lpm`,
//! `scenario.toml`), so that exporting a model (`lpm export-fmu`) needs no
//! compiler; the one `lpm export-fmu --compiled` builds runs the
//! macro-compiled model instead, the scenario still read from the resources.
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
//! ([`plant`]); the instance and its calls ([`instance`]), with the FMI
//! 2.0 state machine's table of which call each state allows
//! ([`machine`]); the live instances by handle ([`registry`]); the 44 C
//! entry points ([`common`], [`cs`], [`me`]), each run inside [`guard`] so
//! that no panic reaches the host, no freed or foreign handle is read and
//! no call runs out of order; and [`export_fmi2!`], which exports them
//! under their C names from an FMU binary ([`export`]).
//!
//! With the feature `export`, the exporter too (`exporter`): the FMU of a
//! spec and scenario, written by `lpm export-fmu` and the Python package.

pub mod common;
pub mod component;
pub mod cs;
pub mod export;
#[cfg(feature = "export")]
pub mod exporter;
pub mod ffi;
pub mod guard;
pub mod instance;
pub mod machine;
pub mod me;
pub mod plant;
pub mod registry;
pub mod resources;
pub mod variables;

#[cfg(test)]
mod c_api_tests;
#[cfg(test)]
mod compiled_tests;
#[cfg(test)]
mod me_tests;
#[cfg(test)]
mod tests;
