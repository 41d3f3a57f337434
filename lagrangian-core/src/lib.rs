//! The Euler–Lagrange compiler as a plain library.
//!
//! Pipeline: spec text or tokens → [`spec::Model`] (names resolved, expressions
//! in canonical form, the energies also on the derivation [`graph`]) →
//! [`derive::Derivation`] (`M q̈ = f`, energies, Jacobians), or
//! [`graph_derivation::GraphDerivation`] for a model too large for the canonical form →
//! [`program::Program`] (optimized straight-line code) → Rust source
//! ([`emit`]) or the runtime's interpreter ([`Compiled::interpreted`], by
//! [`tape::lower`]).

pub mod audit;
pub mod constraints;
pub mod depth;
pub mod derive;
pub mod diagnostic;
pub mod emit;
pub mod examples;
pub mod expand;
pub mod expr;
pub mod generate;
pub mod graph;
pub mod graph_derivation;
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
use lagrangian_runtime::{InterpretedModel, ModelDescription};
use program::Program;

/// A model with its derived equations and optimized program.
pub struct Compiled {
    /// The resolved spec, whose store holds every expression below.
    pub model: Model,
    /// `M q̈ = f`, the energies and powers, and the Jacobians if asked for,
    /// in the exact canonical form: `None` when the model is too large for
    /// it and was derived on the graph ([`graph`]); see
    /// [`Compiled::canonical`].
    pub derivation: Option<Derivation>,
    /// Every output of the derivation as optimized straight-line code.
    pub program: Program,
}

/// The largest total size ([`expr::Store::set_budget`]) of the nodes that
/// the canonical derivation may create before the model is derived on the
/// graph instead (a 20-link chain stays canonical).
const CANONICAL_DERIVATION_SIZE: usize = 200_000;

impl Compiled {
    /// Derives and optimizes `model` (on a large stack, see [`depth`]):
    /// in the canonical form when it stays within its limits, on the
    /// derivation graph otherwise.
    pub fn new(mut model: Model) -> Result<Compiled, SpecErrors> {
        depth::with_large_stack(|| {
            if model.canonical_limit.is_none()
                && let Some(derivation) = derive_canonical(&mut model)?
            {
                let program = optimize::build_program(&mut model.store, &derivation);
                let derivation = Some(derivation);
                return Ok(Compiled {
                    model,
                    derivation,
                    program,
                });
            }
            Compiled::on_graph(model)
        })
    }

    /// Derives and optimizes `model` on the derivation graph whatever its
    /// size (what [`Compiled::new`] does for a model too large for the
    /// canonical form).
    pub fn on_graph(mut model: Model) -> Result<Compiled, SpecErrors> {
        if let Some(constraint) = model.constraints.first() {
            let message =
                "this model is too large for the exact canonical form, which constraints need";
            return Err(Diagnostic::new(constraint.span, message)
                .with_help("write the model with fewer or smaller helper expressions, or eliminate the constraint")
                .into());
        }
        depth::with_large_stack(|| {
            let derivation = graph_derivation::derive_graph(&mut model)?;
            let program =
                optimize::build_program_from_graph(&mut model.store, &model.graph, &derivation);
            derive::check_program_mass(&mut model, &program)?;
            Ok(Compiled {
                model,
                derivation: None,
                program,
            })
        })
    }

    /// The derivation in the exact canonical form, for printing and the
    /// audit: derived now when [`Compiled::new`] took the graph path, or
    /// the reason it cannot be (an energy or the equations would exceed
    /// the canonical form's limits).
    pub fn canonical(&mut self) -> Result<&Derivation, SpecErrors> {
        if self.derivation.is_none() {
            if let Some(limit) = &self.model.canonical_limit {
                return Err(limit.clone().into());
            }
            let derivation = depth::with_large_stack(|| derive::derive(&mut self.model))?;
            self.derivation = Some(derivation);
        }
        Ok(self.derivation.as_ref().expect("set above"))
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
            parameter_units: model.parameters.iter().map(|p| unit(&p.unit)).collect(),
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
            constraints: model.constraints.iter().map(|c| c.name.clone()).collect(),
            multiplier_units: (model.constraints.iter())
                .map(|c| c.multiplier_unit())
                .collect(),
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

/// The canonical derivation of `model` within [`CANONICAL_DERIVATION_SIZE`]:
/// `None` when it would exceed that or the expansion limits.
fn derive_canonical(model: &mut Model) -> Result<Option<Derivation>, SpecErrors> {
    model.store.set_budget(Some(CANONICAL_DERIVATION_SIZE));
    model.store.take_size_limit();
    let derivation = derive::derive(model);
    let too_large = model.store.take_size_limit();
    model.store.set_budget(None);
    match derivation {
        Ok(d) if !too_large => Ok(Some(d)),
        Ok(_) => Ok(None),
        Err(_) if too_large => Ok(None),
        Err(e) => Err(e),
    }
}

/// Parses, derives and optimizes a spec and returns it ready to interpret.
pub fn interpret(source: &str) -> Result<InterpretedModel, SpecErrors> {
    Ok(Compiled::from_source(source)?.interpreted())
}
