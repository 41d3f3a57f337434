//! Lowering the `hand_derived` section: a user's own equations, kept term by
//! term as written so the audit can report them.

use super::ast::HandSection;
use super::dimensions::DimensionScope;
use super::expression::{Binding, ExpressionLowering, Scope};
use super::{Coordinate, Input, Parameter};
use crate::diagnostic::{Diagnostic, SpanRange};
use crate::expr::{ExprId, Store};
use crate::units::Dimension;
use syn::{BinOp, Expr, UnOp};

/// How the hand-derived expressions relate to the derivation.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Convention {
    /// Equation `q` is `d/dt ∂L/∂q̇ − ∂L/∂q` (`L = T − V`); damping and
    /// external forces are the generalized forces `Q`, given separately.
    EulerLagrange,
}

impl Convention {
    pub const NAMES: &'static str = "euler_lagrange";

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
    pub span: SpanRange,
    /// Its dimension, when every name in it has a unit.
    pub dimension: Option<Dimension>,
}

#[derive(Clone, Debug)]
pub struct HandEquation {
    pub coordinate: usize,
    pub value: ExprId,
    pub span: SpanRange,
    pub terms: Vec<HandTerm>,
}

/// The `hand_derived` section of a spec.
#[derive(Clone, Debug)]
pub struct HandDerived {
    pub doc: Vec<String>,
    pub convention: Convention,
    /// Order of the Taylor polynomials that stand for sin and cos of angles
    /// in the small-angle comparison (1: sin θ ≈ θ, cos θ ≈ 1).
    pub small_angle_order: u32,
    /// `(symbol, its value)`: the hand derivation's names.
    pub symbols: Vec<(String, ExprId)>,
    /// Values assumed for inputs or parameters the hand model does not have.
    pub assumptions: Vec<(Assumed, ExprId)>,
    pub equations: Vec<HandEquation>,
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

pub(super) struct HandContext<'a> {
    pub store: &'a mut Store,
    pub scope: &'a Scope,
    pub input_names: &'a [String],
    pub dimensions: &'a mut DimensionScope,
    pub coordinates: &'a [Coordinate],
    pub parameters: &'a [Parameter],
    pub inputs: &'a [Input],
}

pub(super) fn lower(
    section: &HandSection,
    cx: HandContext,
) -> Result<HandDerived, Vec<Diagnostic>> {
    let mut problems = Vec::new();
    let convention = match &section.convention {
        None => Convention::EulerLagrange,
        Some(name) if name == "euler_lagrange" => Convention::EulerLagrange,
        Some(name) => {
            problems.push(
                Diagnostic::new(name.span(), format!("unknown convention `{name}`"))
                    .with_help(format!("use one of: {}", Convention::NAMES)),
            );
            Convention::EulerLagrange
        }
    };
    let small_angle_order = match &section.small_angle_order {
        None => 1,
        Some(lit) => match lit.base10_parse::<u32>() {
            Ok(n) if n <= 9 => n,
            _ => {
                problems.push(Diagnostic::new(
                    lit.span(),
                    "small_angle_order must be an integer from 0 to 9",
                ));
                1
            }
        },
    };
    // The hand derivation's own names extend the spec's scope.
    let mut scope = Scope {
        names: cx.scope.names.clone(),
        coordinates: cx.scope.coordinates.clone(),
        time: cx.scope.time,
        velocities: cx.scope.velocities.clone(),
        constants: cx.scope.constants.clone(),
    };
    let mut symbols = Vec::new();
    for (name, expr) in &section.symbols {
        if let Some((_, first)) = scope.names.get(&name.to_string()) {
            problems.push(
                Diagnostic::new(
                    name.span(),
                    format!("`{name}` is already a name of the spec"),
                )
                .with_note("declared here", *first),
            );
            continue;
        }
        let lowered = ExpressionLowering::new(cx.store, &scope, cx.input_names).lower(expr);
        match lowered {
            Ok(l) => {
                let dimension = cx.dimensions.infer(expr).ok().flatten();
                cx.dimensions.names.insert(name.to_string(), dimension);
                if let Ok(Some(c)) = super::constant::evaluate(expr, &scope.constants) {
                    scope.constants.insert(name.to_string(), c);
                    cx.dimensions.constants.insert(name.to_string(), c);
                }
                scope.names.insert(
                    name.to_string(),
                    (Binding::Definition(l.value, l.input_calls), name.span()),
                );
                symbols.push((name.to_string(), l.value));
            }
            Err(d) => problems.push(d),
        }
    }
    let mut assumptions = Vec::new();
    for (name, expr) in &section.assumptions {
        let assumed = match cx.inputs.iter().position(|i| *name == i.name) {
            Some(index) => Assumed::Input(index),
            None => match cx.parameters.iter().find(|p| *name == p.name) {
                Some(p) => Assumed::Parameter(p.symbol),
                None => {
                    problems.push(Diagnostic::new(
                        name.span(),
                        format!(
                            "`{name}` is neither an input function nor a parameter of the spec"
                        ),
                    ));
                    continue;
                }
            },
        };
        match ExpressionLowering::new(cx.store, &scope, cx.input_names).lower(expr) {
            Ok(l) => assumptions.push((assumed, l.value)),
            Err(d) => problems.push(d),
        }
    }
    let mut lower_equations = |list: &[(syn::Ident, Expr)], kind: &str| -> Vec<HandEquation> {
        let mut out: Vec<HandEquation> = Vec::new();
        for (name, expr) in list {
            let Some(coordinate) = cx.coordinates.iter().position(|c| *name == c.name) else {
                problems.push(Diagnostic::new(
                    name.span(),
                    format!("`{name}` is not a generalized coordinate"),
                ));
                continue;
            };
            if out.iter().any(|e| e.coordinate == coordinate) {
                problems.push(Diagnostic::new(
                    name.span(),
                    format!("the {kind} of `{name}` is given twice"),
                ));
                continue;
            }
            let mut written = Vec::new();
            signed_terms(expr, false, &mut written);
            let mut terms = Vec::new();
            for (term, negated) in written {
                match ExpressionLowering::new(cx.store, &scope, cx.input_names)
                    .with_accelerations()
                    .lower(term)
                {
                    Ok(l) => {
                        let value = if negated {
                            cx.store.neg(l.value)
                        } else {
                            l.value
                        };
                        let dimension = cx.dimensions.infer(term).ok().flatten();
                        terms.push(HandTerm {
                            value,
                            span: SpanRange::of(term),
                            dimension,
                        });
                    }
                    Err(d) => problems.push(d),
                }
            }
            let values: Vec<ExprId> = terms.iter().map(|t| t.value).collect();
            let value = cx.store.sum(&values);
            out.push(HandEquation {
                coordinate,
                value,
                span: SpanRange::of(expr),
                terms,
            });
        }
        out
    };
    let equations = lower_equations(&section.equations, "equation");
    let forces = lower_equations(&section.forces, "generalized force");
    if !problems.is_empty() {
        return Err(problems);
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
