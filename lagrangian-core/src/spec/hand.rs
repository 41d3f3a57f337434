//! Lowering the `hand_derived` section: a user's own equations, kept term by
//! term as written so the audit can report them.

use super::ast::HandSection;
use super::dimensions::DimensionScope;
use super::expression::{Binding, ExpressionLowering, Scope};
use super::{Coordinate, Input, Parameter};
use crate::diagnostic::{Diagnostic, SpanRange};
use crate::expr::{ExprId, Store};
use crate::units::Dimension;
use syn::{BinOp, Expr, Ident, UnOp};

/// How the hand-derived expressions relate to the derivation.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Convention {
    /// Equation `q` is `d/dt ∂L/∂q̇ − ∂L/∂q` (`L = T − V`); damping and
    /// external forces are the generalized forces `Q`, given separately.
    EulerLagrange,
}

impl Convention {
    /// The names `convention = …;` accepts, as listed in errors.
    pub const NAMES: &'static str = "euler_lagrange";

    /// What the hand-derived equations are, in words (for the report).
    pub fn description(self) -> &'static str {
        match self {
            Convention::EulerLagrange => {
                "each equation is d/dt ∂L/∂q̇ − ∂L/∂q with L = T − V; dissipation and external forces are the generalized forces Q (−∂D/∂q̇ + forces)"
            }
        }
    }
}

/// What an assumption fixes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Assumed {
    /// An input function (every call of it).
    Input(usize),
    /// A parameter.
    Parameter(crate::expr::SymbolId),
}

/// One term of a hand-derived expression, as written.
#[derive(Clone, Debug)]
pub struct HandTerm {
    /// The term's value (with its sign).
    pub value: ExprId,
    /// Where the term is written.
    pub span: SpanRange,
    /// Its dimension, when every name in it has a unit.
    pub dimension: Option<Dimension>,
}

/// A hand-derived equation or generalized force of one coordinate, `q = …;`.
#[derive(Clone, Debug)]
pub struct HandEquation {
    /// The coordinate's index.
    pub coordinate: usize,
    /// The sum of the terms.
    pub value: ExprId,
    /// Where the right-hand side is written.
    pub span: SpanRange,
    /// Its terms as written, in order.
    pub terms: Vec<HandTerm>,
}

/// The `hand_derived` section of a spec.
#[derive(Clone, Debug)]
pub struct HandDerived {
    /// The section's doc lines.
    pub doc: Vec<String>,
    /// How the equations relate to the derivation.
    pub convention: Convention,
    /// Order of the Taylor polynomials that stand for sin and cos of angles
    /// in the small-angle comparison (1: sin θ ≈ θ, cos θ ≈ 1).
    pub small_angle_order: u32,
    /// `(symbol, its value)`: the hand derivation's names.
    pub symbols: Vec<(String, ExprId)>,
    /// Values assumed for inputs or parameters the hand model does not have.
    pub assumptions: Vec<(Assumed, ExprId)>,
    /// The equations, in the section's order, at most one per coordinate.
    pub equations: Vec<HandEquation>,
    /// The generalized forces (`force q = …;`), likewise.
    pub forces: Vec<HandEquation>,
}

/// The terms of a sum with their signs: `a − (b + c)` is `+a`, `−(b + c)`.
/// Iterative: a long sum is a tree as deep as it is long.
fn signed_terms<'a>(expr: &'a Expr, negated: bool, out: &mut Vec<(&'a Expr, bool)>) {
    let mut stack = vec![(expr, negated)];
    while let Some((e, negated)) = stack.pop() {
        match e {
            Expr::Binary(b) if matches!(b.op, BinOp::Add(_) | BinOp::Sub(_)) => {
                let right_negated = negated != matches!(b.op, BinOp::Sub(_));
                stack.push((&b.right, right_negated));
                stack.push((&b.left, negated));
            }
            Expr::Unary(u)
                if matches!(u.op, UnOp::Neg(_)) && matches!(&*u.expr, Expr::Binary(_)) =>
            {
                stack.push((&u.expr, !negated));
            }
            _ => out.push((e, negated)),
        }
    }
}

/// What the `hand_derived` section may refer to: the spec's lowered
/// declarations, its scope and the dimensions of its names.
pub(super) struct HandContext<'a> {
    pub store: &'a mut Store,
    pub scope: &'a Scope,
    pub input_names: &'a [String],
    pub dimensions: &'a mut DimensionScope,
    pub coordinates: &'a [Coordinate],
    pub parameters: &'a [Parameter],
    pub inputs: &'a [Input],
}

/// Lowers `section`; every problem found, when there is one.
pub(super) fn lower(
    section: &HandSection,
    cx: HandContext,
) -> Result<HandDerived, Vec<Diagnostic>> {
    let mut problems = Vec::new();
    let convention = convention(section, &mut problems);
    let small_angle_order = small_angle_order(section, &mut problems);
    // The hand derivation's own names extend the spec's scope.
    let scope = Scope {
        names: cx.scope.names.clone(),
        coordinates: cx.scope.coordinates.clone(),
        time: cx.scope.time,
        velocities: cx.scope.velocities.clone(),
        constants: cx.scope.constants.clone(),
        domain_checks: Default::default(),
    };
    let mut hand = HandLowering {
        cx,
        scope,
        problems,
    };
    let symbols = hand.symbols(&section.symbols);
    let assumptions = hand.assumptions(&section.assumptions);
    let equations = hand.equations(&section.equations, "equation");
    let forces = hand.equations(&section.forces, "generalized force");
    if !hand.problems.is_empty() {
        return Err(hand.problems);
    }
    Ok(HandDerived {
        doc: section.doc.clone(),
        convention,
        small_angle_order,
        symbols,
        assumptions,
        equations,
        forces,
    })
}

/// `convention = name;` (Euler–Lagrange when absent or unknown).
fn convention(section: &HandSection, problems: &mut Vec<Diagnostic>) -> Convention {
    match &section.convention {
        None => Convention::EulerLagrange,
        Some(name) if name == "euler_lagrange" => Convention::EulerLagrange,
        Some(name) => {
            problems.push(
                Diagnostic::new(name.span(), format!("unknown convention `{name}`"))
                    .with_help(format!("use one of: {}", Convention::NAMES)),
            );
            Convention::EulerLagrange
        }
    }
}

/// `small_angle_order = n;` (1 when absent or out of range).
fn small_angle_order(section: &HandSection, problems: &mut Vec<Diagnostic>) -> u32 {
    let Some(lit) = &section.small_angle_order else {
        return 1;
    };
    match lit.base10_parse::<u32>() {
        Ok(n) if n <= 9 => n,
        _ => {
            problems.push(Diagnostic::new(
                lit.span(),
                "small_angle_order must be an integer from 0 to 9",
            ));
            1
        }
    }
}

/// The state of lowering one section: the spec's context, the scope with
/// the section's own symbols, and the problems found so far.
struct HandLowering<'a> {
    cx: HandContext<'a>,
    scope: Scope,
    problems: Vec<Diagnostic>,
}

impl HandLowering<'_> {
    /// `symbols { name = expression, … }`: each becomes a definition in scope.
    fn symbols(&mut self, list: &[(Ident, Expr)]) -> Vec<(String, ExprId)> {
        let mut symbols = Vec::new();
        for (name, expr) in list {
            if let Some((_, first)) = self.scope.names.get(&name.to_string()) {
                self.problems.push(
                    Diagnostic::new(
                        name.span(),
                        format!("`{name}` is already a name of the spec"),
                    )
                    .with_note("declared here", *first),
                );
                continue;
            }
            match self.lowering().lower(expr) {
                Ok(l) => {
                    self.define(name, expr, l.value, l.input_calls);
                    symbols.push((name.to_string(), l.value));
                }
                Err(d) => self.problems.push(d),
            }
        }
        symbols
    }

    /// Binds symbol `name` to `value`, with its dimension and, for a
    /// constant, its exact value.
    fn define(
        &mut self,
        name: &Ident,
        expr: &Expr,
        value: ExprId,
        input_calls: Vec<(usize, SpanRange)>,
    ) {
        let dimensions = &mut *self.cx.dimensions;
        let dimension = dimensions.infer(expr).ok().flatten();
        dimensions.names.insert(name.to_string(), dimension);
        if let Ok(Some(c)) = super::constant::evaluate(expr, &self.scope.constants) {
            self.scope.constants.insert(name.to_string(), c);
            dimensions.constants.insert(name.to_string(), c);
        }
        self.scope.names.insert(
            name.to_string(),
            (Binding::Definition(value, input_calls), name.span()),
        );
    }

    /// `assume { input = expression, … }`.
    fn assumptions(&mut self, list: &[(Ident, Expr)]) -> Vec<(Assumed, ExprId)> {
        let mut assumptions = Vec::new();
        for (name, expr) in list {
            let Some(assumed) = self.assumed(name) else {
                self.problems.push(Diagnostic::new(
                    name.span(),
                    format!("`{name}` is neither an input function nor a parameter of the spec"),
                ));
                continue;
            };
            match self.lowering().lower(expr) {
                Ok(l) => assumptions.push((assumed, l.value)),
                Err(d) => self.problems.push(d),
            }
        }
        assumptions
    }

    /// The input function or parameter named `name`.
    fn assumed(&self, name: &Ident) -> Option<Assumed> {
        match self.cx.inputs.iter().position(|i| *name == i.name) {
            Some(index) => Some(Assumed::Input(index)),
            None => self
                .cx
                .parameters
                .iter()
                .find(|p| *name == p.name)
                .map(|p| Assumed::Parameter(p.symbol)),
        }
    }

    /// `q = expression;` lines (equations or generalized forces, `kind`),
    /// one per coordinate.
    fn equations(&mut self, list: &[(Ident, Expr)], kind: &str) -> Vec<HandEquation> {
        let mut out: Vec<HandEquation> = Vec::new();
        for (name, expr) in list {
            let Some(coordinate) = self.cx.coordinates.iter().position(|c| *name == c.name) else {
                self.problems.push(Diagnostic::new(
                    name.span(),
                    format!("`{name}` is not a generalized coordinate"),
                ));
                continue;
            };
            if out.iter().any(|e| e.coordinate == coordinate) {
                self.problems.push(Diagnostic::new(
                    name.span(),
                    format!("the {kind} of `{name}` is given twice"),
                ));
                continue;
            }
            let terms = self.terms(expr);
            let values: Vec<ExprId> = terms.iter().map(|t| t.value).collect();
            let value = self.cx.store.sum(&values);
            out.push(HandEquation {
                coordinate,
                value,
                span: SpanRange::of(expr),
                terms,
            });
        }
        out
    }

    /// The terms of `expr` as written, each lowered with its sign.
    fn terms(&mut self, expr: &Expr) -> Vec<HandTerm> {
        let mut written = Vec::new();
        signed_terms(expr, false, &mut written);
        let mut terms = Vec::new();
        for (term, negated) in written {
            match self.lowering().with_accelerations().lower(term) {
                Ok(l) => {
                    let value = if negated {
                        self.cx.store.neg(l.value)
                    } else {
                        l.value
                    };
                    terms.push(HandTerm {
                        value,
                        span: SpanRange::of(term),
                        dimension: self.cx.dimensions.infer(term).ok().flatten(),
                    });
                }
                Err(d) => self.problems.push(d),
            }
        }
        terms
    }

    /// An expression lowering in the section's scope.
    fn lowering(&mut self) -> ExpressionLowering<'_> {
        ExpressionLowering::new(self.cx.store, &self.scope, self.cx.input_names)
    }
}
