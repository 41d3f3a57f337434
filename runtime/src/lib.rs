//! The model runtime of `lagrangian`: what a derived model is at run time,
//! compiled or interpreted.
//!
//! * [`LagrangianSystem`]: the interface every derived model implements —
//!   `M(q, t)`, `f(q, q̇, t)`, energies, Jacobians — on nalgebra's fixed-size
//!   vectors. The `lagrangian!` macro generates implementations of it.
//! * [`InterpretedModel`]: a spec's compiled program run by the interpreter
//!   ([`tape`]) without recompiling; [`Interpreted<N>`] puts it behind
//!   [`LagrangianSystem<N>`]. `lagrangian_core::Compiled::interpreted` makes one.
//! * [`InputFunctions`]: how run-time inputs (crush characteristics, barrier
//!   force tables) reach a model.
//! * [`layout`]: the order of every routine's outputs, shared by the compiler,
//!   its emitters and the interpreter.
//!
//! The crate depends on nalgebra alone, so that generated code compiles
//! quickly. Without its default `nalgebra` feature it holds what the compiler
//! needs of it (the interpreter, the layout, input functions, [`names`]) and
//! depends on nothing.

#[cfg(feature = "nalgebra")]
pub mod constrained;
mod error;
#[cfg(feature = "nalgebra")]
mod fixed;
pub mod functions;
mod inputs;
mod interpreted;
pub mod layout;
#[cfg(feature = "nalgebra")]
pub mod linalg;
pub mod names;
pub mod native;
#[cfg(feature = "nalgebra")]
mod system;
pub mod tape;

pub use error::ModelError;
#[cfg(feature = "nalgebra")]
pub use fixed::{Interpreted, MAX_INTERPRETED_DIMENSION, WithDimension};
pub use functions::Func;
pub use inputs::{ConstantInputs, InputFunctions, NoInputs};
pub use interpreted::{InterpretedModel, ModelDescription};
pub use layout::{Energies, MechanicalEnergy};
#[cfg(feature = "nalgebra")]
pub use system::{Jacobians, LagrangianSystem, solve_mass_matrix};

/// The linear-algebra crate of the generated code's signatures.
#[cfg(feature = "nalgebra")]
pub use nalgebra;
