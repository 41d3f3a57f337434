//! Model specifications: the spec language, its parser and the resolved [`Model`].

mod ast;
mod constant;
mod dimensions;
mod domain;
mod expression;
mod families;
mod graph_lowering;
mod hand;
mod lower;
mod names;
mod outline;
mod parse;
mod parts;
mod unit_check;

pub use ast::{EnergyKind, UnitText};
pub use domain::{Domain, DomainCheck};
pub(crate) use expression::engine_diagnostic;
pub use hand::{Assumed, Convention, HandDerived, HandEquation, HandTerm};
pub(crate) use outline::Outline;

use crate::diagnostic::{SpanRange, SpecErrors};
use crate::expr::{CoordinateSymbols, ExprId, Store, SymbolId};
use proc_macro2::{Span, TokenStream};

/// A generalized coordinate with its velocity and acceleration symbols.
#[derive(Clone, Debug)]
pub struct Coordinate {
    /// The name, as declared.
    pub name: String,
    /// Its `///` doc lines.
    pub doc: Vec<String>,
    /// Its unit, when declared (`x [m]`).
    pub unit: Option<UnitText>,
    /// Where it is declared.
    pub span: Span,
    /// `q` as an expression.
    pub position_expr: ExprId,
    /// The symbols of `q` and `q̇`, and the expressions of `q̇` and `q̈`.
    pub symbols: CoordinateSymbols,
    /// The symbol `ddot(q)`.
    pub acceleration: SymbolId,
}

/// A parameter: a named constant of the model, settable at run time.
#[derive(Clone, Debug)]
pub struct Parameter {
    /// The name, as declared.
    pub name: String,
    /// Its `///` doc lines.
    pub doc: Vec<String>,
    /// Its unit, when declared (`m [kg] = 1.0`).
    pub unit: Option<UnitText>,
    /// Where it is declared.
    pub span: Span,
    /// The default value, evaluated from its constant expression.
    pub default: f64,
    /// Its symbol.
    pub symbol: SymbolId,
    /// Its symbol as an expression.
    pub expr: ExprId,
}

/// An input function: a value supplied at run time as a function of its
/// arguments (e.g. a measured force as a function of a deflection).
#[derive(Clone, Debug)]
pub struct Input {
    /// The name, as declared.
    pub name: String,
    /// Its `///` doc lines.
    pub doc: Vec<String>,
    /// The unit of its value, when declared.
    pub unit: Option<UnitText>,
    /// Where it is declared.
    pub span: Span,
    /// The formal arguments' names and units, in order.
    pub arguments: Vec<(String, Option<UnitText>)>,
    /// The span of each declared derivative `d(arg) = …`, by argument.
    pub derivative_spans: Vec<Option<Span>>,
}

/// A lowered expression with where it was written and which inputs it calls.
#[derive(Clone, Debug)]
pub struct Statement {
    /// The value, in canonical form.
    pub value: ExprId,
    /// The right-hand side as written.
    pub span: SpanRange,
    /// `(input index, span of a call)` for every input the statement calls,
    /// directly or through `let` definitions.
    pub input_calls: Vec<(usize, SpanRange)>,
}

/// A force statement turned into generalized forces `Q_i`, by coordinate.
#[derive(Clone, Debug)]
pub struct ForceStatement {
    /// The statement's value (for a point force, from point to components).
    pub span: SpanRange,
    /// `(coordinate index, Q_i)` for every coordinate the force acts on.
    pub generalized: Vec<(usize, ExprId)>,
    /// `(input index, span of a call)` for every input the statement calls.
    pub input_calls: Vec<(usize, SpanRange)>,
}

/// An output: `output name [unit] = value;`, computed at `(t, q, q̇, q̈)`
/// after the solve.
#[derive(Clone, Debug)]
pub struct Output {
    /// The name, as declared.
    pub name: String,
    /// Its `///` doc lines.
    pub doc: Vec<String>,
    /// Its unit, when declared.
    pub unit: Option<UnitText>,
    /// Where it is declared.
    pub span: Span,
    /// Its value, which may contain the acceleration symbols.
    pub statement: Statement,
}

/// A holonomic constraint `constraint name = g;`: `g(q, t) = 0`, held by a
/// Lagrange multiplier `λ`, whose generalized force `Gᵀλ` (`G = ∂g/∂q`) is
/// added to `f`.
#[derive(Clone, Debug)]
pub struct Constraint {
    /// The name, as declared.
    pub name: String,
    /// Its `///` doc lines.
    pub doc: Vec<String>,
    /// Where it is declared.
    pub span: Span,
    /// `g`, a function of the coordinates, time, parameters and inputs.
    pub statement: Statement,
    /// The dimension of `g`, when the spec's units are checked.
    pub dimension: Option<crate::units::Dimension>,
}

impl Constraint {
    /// The unit of the multiplier `λ`, energy per unit of `g`, when the
    /// spec's units are checked.
    pub fn multiplier_unit(&self) -> Option<String> {
        let d = crate::units::Dimension::ENERGY.checked_div(self.dimension?)?;
        Some(d.to_string())
    }
}

/// A resolved model: symbols and expressions ready for derivation.
pub struct Model {
    /// The name given by `model Name;`, the emitted type's name.
    pub name: String,
    /// Where it is given.
    pub name_span: Span,
    /// The spec file's `//!` lines, then the `///` lines on `model Name;`.
    pub doc: Vec<String>,
    /// Every symbol and expression of the model.
    pub store: Store,
    /// The generalized coordinates, in declaration order.
    pub coordinates: Vec<Coordinate>,
    /// The parameters, in declaration order (the order of the runtime's
    /// parameter vector).
    pub parameters: Vec<Parameter>,
    /// The input functions, in declaration order.
    pub inputs: Vec<Input>,
    /// The symbol `t`.
    pub time: SymbolId,
    /// The kinetic energy `T`.
    pub kinetic: Statement,
    /// The potential energy `V`, when given.
    pub potential: Option<Statement>,
    /// The Rayleigh dissipation function `D`, when given.
    pub dissipation: Option<Statement>,
    /// The force statements, in order.
    pub forces: Vec<ForceStatement>,
    /// The outputs, in declaration order.
    pub outputs: Vec<Output>,
    /// The holonomic constraints, in declaration order.
    pub constraints: Vec<Constraint>,
    /// `let` definitions, in order, for documentation.
    pub definitions: Vec<(String, ExprId)>,
    /// Whether the spec asks for the Jacobians (`jacobians;`).
    pub jacobians: bool,
    /// Where they are asked for.
    pub jacobians_span: Option<Span>,
    /// Hand-derived equations to audit (`hand_derived { … }`).
    pub hand_derived: Option<HandDerived>,
    /// Dimensions of the coordinates, where declared.
    pub coordinate_dimensions: Vec<Option<crate::units::Dimension>>,
    /// The derivation graph, holding `T`, `V` and `D` as shared nodes
    /// ([`crate::graph`]).
    pub graph: crate::graph::Graph,
    /// `T`, `V`, `D` as nodes of [`Model::graph`], where they lowered to it.
    pub energy_graph: [Option<crate::graph::GraphId>; 3],
    /// Why `T`, `V` or `D` has no canonical form (it would exceed the
    /// engine's limits on expansion): then that statement's value is a
    /// placeholder 0, and only the graph derives the model.
    pub canonical_limit: Option<crate::diagnostic::Diagnostic>,
    /// What does not stop the spec compiling but its author should know
    /// (e.g. names without units among names with units). `lpm` prints
    /// them; the `lagrangian!` macro cannot (a procedural macro has no
    /// warnings on stable Rust), so they show with `lpm derive`.
    pub warnings: Vec<crate::diagnostic::Diagnostic>,
    /// The calls whose arguments have a restricted domain (`acos`, `ln`,
    /// fractional powers, divisors), inner calls first, to name the one
    /// that makes a run non-finite ([`Model::domain_violation`]).
    pub domain_checks: Vec<DomainCheck>,
}

/// The spec `tokens` parsed, its families and parts written out: the
/// scalar spec that lowering resolves.
fn expanded(tokens: TokenStream) -> Result<(ast::SpecAst, parts::Instances), SpecErrors> {
    let ast: ast::SpecAst = syn::parse2(families::sum_syntax(tokens))?;
    parts::expand(families::expand(ast)?)
}

impl Model {
    /// Parses and resolves a spec given as tokens (the macro's inline form).
    ///
    /// Input too deep or too long is an error, and the work runs on a large
    /// stack (see [`crate::depth`]), so no input overflows the stack.
    pub fn from_tokens(tokens: TokenStream) -> Result<Model, SpecErrors> {
        let count = crate::depth::check_tokens(&tokens)?;
        crate::depth::with_stack_for_tokens(count, || {
            let (ast, instances) = expanded(tokens).map_err(families::errors_as_read)?;
            lower::lower(ast)
                .map(families::model_as_read)
                .map_err(|e| families::errors_as_read(instances.noted(e)))
        })
    }

    /// Parses and resolves a spec given as text (a `.lpm` file), as
    /// [`Model::from_tokens`] does.
    pub fn from_source(source: &str) -> Result<Model, SpecErrors> {
        let tokens: TokenStream = source.parse().map_err(syn::Error::from)?;
        Model::from_tokens(tokens)
    }

    /// The number of generalized coordinates.
    pub fn dimension(&self) -> usize {
        self.coordinates.len()
    }

    /// `T`, `V`, `D` as graph nodes: the lowered ones, else leaves of their
    /// canonical values (0 for an energy the spec does not give).
    pub fn energy_nodes(&mut self) -> [crate::graph::GraphId; 3] {
        let values = [
            Some(&self.kinetic),
            self.potential.as_ref(),
            self.dissipation.as_ref(),
        ]
        .map(|s| s.map_or(Store::ZERO, |s| s.value));
        let mut nodes = [None; 3];
        for (k, node) in nodes.iter_mut().enumerate() {
            *node = Some(match self.energy_graph[k] {
                Some(g) => g,
                None => self.graph.leaf(&self.store, values[k]),
            });
        }
        nodes.map(|n| n.expect("set above"))
    }

    /// The symbols of every coordinate, in order.
    pub fn coordinate_symbols(&self) -> Vec<CoordinateSymbols> {
        self.coordinates.iter().map(|c| c.symbols.clone()).collect()
    }
}

/// Names that the spec language gives a meaning of its own.
///
/// The functions added later (`asin`, `abs`, `min`, …, `cot`, `sec`) are not
/// reserved, so that specs that declare such names keep their meaning: a
/// declared name hides the function of the same name.
pub const RESERVED_NAMES: &[&str] = &[
    "t", "pi", "dot", "ddot", "sin", "cos", "tan", "exp", "ln", "sqrt", "pow",
];
