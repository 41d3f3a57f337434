//! Model specifications: the spec language, its parser and the resolved [`Model`].

mod ast;
mod constant;
mod dimensions;
mod expression;
mod hand;
mod lower;
mod parse;
mod unit_check;

pub use ast::{EnergyKind, UnitText};
pub(crate) use expression::engine_diagnostic;
pub use hand::{Assumed, Convention, HandDerived, HandEquation, HandTerm};

use crate::diagnostic::{SpanRange, SpecErrors};
use crate::expr::{CoordinateSymbols, ExprId, Store, SymbolId};
use proc_macro2::{Span, TokenStream};

/// A generalized coordinate with its velocity and acceleration symbols.
#[derive(Clone, Debug)]
pub struct Coordinate {
    pub name: String,
    pub doc: Vec<String>,
    pub unit: Option<UnitText>,
    pub span: Span,
    pub position_expr: ExprId,
    pub symbols: CoordinateSymbols,
    pub acceleration: SymbolId,
}

#[derive(Clone, Debug)]
pub struct Parameter {
    pub name: String,
    pub doc: Vec<String>,
    pub unit: Option<UnitText>,
    pub span: Span,
    pub default: f64,
    pub symbol: SymbolId,
    pub expr: ExprId,
}

#[derive(Clone, Debug)]
pub struct Input {
    pub name: String,
    pub doc: Vec<String>,
    pub unit: Option<UnitText>,
    pub span: Span,
    pub arguments: Vec<(String, Option<UnitText>)>,
    /// The span of each declared derivative `d(arg) = …`, by argument.
    pub derivative_spans: Vec<Option<Span>>,
}

/// A lowered expression with where it was written and which inputs it calls.
#[derive(Clone, Debug)]
pub struct Statement {
    pub value: ExprId,
    pub span: SpanRange,
    /// `(input index, span of a call)` for every input the statement calls,
    /// directly or through `let` definitions.
    pub input_calls: Vec<(usize, SpanRange)>,
}

/// A force statement turned into generalized forces `Q_i`, by coordinate.
#[derive(Clone, Debug)]
pub struct ForceStatement {
    pub span: SpanRange,
    pub generalized: Vec<(usize, ExprId)>,
    pub input_calls: Vec<(usize, SpanRange)>,
}

/// A resolved model: symbols and expressions ready for derivation.
pub struct Model {
    pub name: String,
    pub name_span: Span,
    pub doc: Vec<String>,
    pub store: Store,
    pub coordinates: Vec<Coordinate>,
    pub parameters: Vec<Parameter>,
    pub inputs: Vec<Input>,
    pub time: SymbolId,
    pub kinetic: Statement,
    pub potential: Option<Statement>,
    pub dissipation: Option<Statement>,
    pub forces: Vec<ForceStatement>,
    /// `let` definitions, in order, for documentation.
    pub definitions: Vec<(String, ExprId)>,
    /// Whether the spec asks for the Jacobians (`jacobians;`).
    pub jacobians: bool,
    pub jacobians_span: Option<Span>,
    /// Hand-derived equations to audit (`hand_derived { … }`).
    pub hand_derived: Option<HandDerived>,
    /// Dimensions of the coordinates, where declared.
    pub coordinate_dimensions: Vec<Option<crate::units::Dimension>>,
}

impl Model {
    /// Parses and resolves a spec given as tokens (the macro's inline form).
    ///
    /// Input too deep or too long is an error, and the work runs on a large
    /// stack (see [`crate::depth`]), so no input overflows the stack.
    pub fn from_tokens(tokens: TokenStream) -> Result<Model, SpecErrors> {
        let count = crate::depth::check_tokens(&tokens)?;
        crate::depth::with_stack_for_tokens(count, || {
            let ast: ast::SpecAst = syn::parse2(tokens)?;
            lower::lower(ast)
        })
    }

    /// Parses and resolves a spec given as text (a `.lpm` file), as
    /// [`Model::from_tokens`] does.
    pub fn from_source(source: &str) -> Result<Model, SpecErrors> {
        let tokens: TokenStream = source.parse().map_err(syn::Error::from)?;
        Model::from_tokens(tokens)
    }

    pub fn dimension(&self) -> usize {
        self.coordinates.len()
    }

    pub fn coordinate_symbols(&self) -> Vec<CoordinateSymbols> {
        self.coordinates.iter().map(|c| c.symbols.clone()).collect()
    }
}

/// Names that the spec language gives a meaning of its own.
pub const RESERVED_NAMES: &[&str] = &[
    "t", "pi", "dot", "ddot", "sin", "cos", "tan", "exp", "ln", "sqrt", "pow",
];
