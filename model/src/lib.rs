//! Runtime for `lagrangian` models.
//!
//! * [`LagrangianSystem`]: what every derived model implements — `M(q, t)`,
//!   `f(q, q̇, t)`, energies, Jacobians — whether compiled by the
//!   `lagrangian!` macro or interpreted from a spec file.
//! * [`InterpretedModel`]: a spec file evaluated at run time, without recompiling.
//! * [`InputFunctions`]: how run-time inputs (crush characteristics, barrier
//!   force tables) reach a model.

pub mod crash;
pub mod fault;
pub mod fit;
mod interpreted;
pub mod linalg;
pub mod ode;
pub mod plot;
pub mod pulse;
pub mod report;
pub mod scenario;
pub mod simulate;
pub mod sweep;
mod system;

pub use interpreted::{Interpreted, InterpretedModel};
pub use lagrangian_core::{ConstantInputs, InputFunctions, NoInputs};
pub use system::{Energies, Jacobians, LagrangianSystem, ModelError, solve_mass_matrix};

/// The linear-algebra crate of the generated code's signatures.
pub use nalgebra;
