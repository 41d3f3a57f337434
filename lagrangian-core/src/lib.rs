//! The Euler–Lagrange compiler as a plain library.
//!
//! Pipeline: spec text or tokens → [`spec::Model`] (names resolved, expressions
//! in canonical form) → [`derive::Derivation`] (`M q̈ = f`, energies, Jacobians)
//! → [`program::Program`] (optimized straight-line code) → Rust source
//! ([`emit`]) or direct evaluation ([`program::Program::run`]).

pub mod audit;
pub mod depth;
pub mod derive;
pub mod diagnostic;
pub mod emit;
pub mod examples;
pub mod expand;
pub mod expr;
pub mod generate;
pub mod optimize;
pub mod program;
pub mod rational;
pub mod spec;
pub mod tape;
pub mod units;

pub use diagnostic::{Diagnostic, SpecErrors};
pub use expr::{ConstantInputs, InputFunctions, NoInputs};
pub use spec::Model;

use derive::Derivation;
use program::Program;

/// A model with its derived equations and optimized program.
pub struct Compiled {
    pub model: Model,
    pub derivation: Derivation,
    pub program: Program,
}

impl Compiled {
    /// Derives and optimizes `model` (on a large stack, see [`depth`]).
    pub fn new(mut model: Model) -> Result<Compiled, SpecErrors> {
        depth::with_large_stack(|| {
            let derivation = derive::derive(&mut model)?;
            let program = optimize::build_program(&mut model.store, &derivation);
            Ok(Compiled {
                model,
                derivation,
                program,
            })
        })
    }

    /// Parses, derives and optimizes a spec given as text.
    pub fn from_source(source: &str) -> Result<Compiled, SpecErrors> {
        Compiled::new(Model::from_source(source)?)
    }

    /// Default values of the parameters, in declaration order.
    pub fn default_parameters(&self) -> Vec<f64> {
        self.model.parameters.iter().map(|p| p.default).collect()
    }
}
