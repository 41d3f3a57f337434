//! The Euler–Lagrange compiler as a plain library.
//!
//! Pipeline: spec text or tokens → [`spec::Model`] (names resolved, expressions
//! in canonical form) → [`derive::Derivation`] (`M q̈ = f`, energies, Jacobians)
//! → [`program::Program`] (optimized straight-line code) → Rust source
//! ([`emit`]) or the runtime's interpreter ([`Compiled::interpreted`], by
//! [`tape::lower`]).

#![warn(missing_docs)]

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
pub mod random;
pub mod rational;
pub mod spec;
pub mod switching;
pub mod tape;
pub mod units;

pub use diagnostic::{Diagnostic, SpecErrors};
pub use spec::Model;

use derive::Derivation;
use lagrangian_model::{InterpretedModel, ModelDescription};
use program::Program;

/// A model with its derived equations and optimized program.
pub struct Compiled {
    /// The resolved spec, whose store holds every expression below.
    pub model: Model,
    /// `M q̈ = f`, the energies and powers, and the Jacobians if asked for.
    pub derivation: Derivation,
    /// Every output of the derivation as optimized straight-line code.
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

    /// The names, units and defaults the interpreter needs.
    pub fn description(&self) -> ModelDescription {
        let model = &self.model;
        let unit = |u: &Option<spec::UnitText>| u.as_ref().map(|u| u.text.clone());
        ModelDescription {
            name: model.name.clone(),
            coordinates: model.coordinates.iter().map(|c| c.name.clone()).collect(),
            coordinate_units: model.coordinates.iter().map(|c| unit(&c.unit)).collect(),
            parameters: model.parameters.iter().map(|p| p.name.clone()).collect(),
            parameter_defaults: self.default_parameters(),
            inputs: model.inputs.iter().map(|i| i.name.clone()).collect(),
            input_arguments: model
                .inputs
                .iter()
                .map(|i| i.arguments.iter().map(|(name, _)| name.clone()).collect())
                .collect(),
            input_units: model.inputs.iter().map(|i| unit(&i.unit)).collect(),
            input_sites: self.program.input_sites.clone(),
            outputs: model.outputs.iter().map(|o| o.name.clone()).collect(),
            output_units: model.outputs.iter().map(|o| unit(&o.unit)).collect(),
        }
    }

    /// The model run by the runtime's interpreter, without recompiling,
    /// with default parameters.
    pub fn interpreted(&self) -> InterpretedModel {
        let description = self.description();
        let tape = tape::lower(&self.program, description.parameters.len());
        InterpretedModel::new(description, tape)
            .expect("the description lists what the program computes")
    }
}

/// Parses, derives and optimizes a spec and returns it ready to interpret.
pub fn interpret(source: &str) -> Result<InterpretedModel, SpecErrors> {
    Ok(Compiled::from_source(source)?.interpreted())
}
