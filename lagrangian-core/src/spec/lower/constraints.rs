//! The constraints phase: `constraint name = g;`, a holonomic constraint
//! `g(q, t) = 0`, lowered as a position (no velocities, no accelerations);
//! its name is declared so that a clash is reported at it, and its
//! dimension is inferred once the units are checked (the multiplier's unit
//! is energy per unit of `g`).

use super::Lowering;
use crate::diagnostic::{Diagnostic, SpanRange};
use crate::expr::{Evaluator, ExprId, Store, SymbolKind};
use crate::spec::ast::{ConstraintDecl, Item};
use crate::spec::dimensions::DimensionScope;
use crate::spec::expression::{Binding, ExpressionLowering};
use crate::spec::{Constraint, Parameter, Statement};

impl Lowering {
    /// Declares every constraint's name, so that a second use of the name
    /// is reported where it is.
    pub(super) fn declare_constraints(&mut self, statements: &[Item]) {
        for constraint in constraint_declarations(statements) {
            self.declare(&constraint.name, Binding::Constraint);
        }
    }

    /// Lowers every constraint, in order (`parameters`: the declared ones,
    /// whose defaults give the residual of a constraint on no coordinate).
    pub(super) fn constraints(
        &mut self,
        statements: &[Item],
        parameters: &[Parameter],
    ) -> Vec<Constraint> {
        constraint_declarations(statements)
            .filter_map(|constraint| self.constraint(constraint, parameters))
            .collect()
    }

    fn constraint(
        &mut self,
        decl: &ConstraintDecl,
        parameters: &[Parameter],
    ) -> Option<Constraint> {
        let lowering = ExpressionLowering::new(&mut self.store, &self.scope, &self.input_names);
        let lowered = self.problems.take(lowering.lower(&decl.value))?;
        let span = SpanRange::of(&decl.value);
        let velocity =
            (self.scope.velocities.iter()).find(|&&v| self.store.depends_on(lowered.value, v));
        if let Some(&v) = velocity {
            let name = self.store.symbol_info(v).name.clone();
            self.problems.push(uses_velocity(&decl.name, &name, span));
            return None;
        }
        let coordinates = &self.scope.coordinates;
        if !(coordinates.iter()).any(|c| self.store.depends_on(lowered.value, c.position)) {
            let residual = residual_at_defaults(&self.store, lowered.value, parameters);
            let on_time = self.store.depends_on(lowered.value, self.scope.time);
            self.problems
                .push(on_no_coordinate(&decl.name, residual, on_time, span));
            return None;
        }
        Some(Constraint {
            name: decl.name.to_string(),
            doc: decl.doc.clone(),
            span: decl.name.span(),
            statement: Statement {
                value: lowered.value,
                span,
                input_calls: lowered.input_calls,
            },
            dimension: None,
        })
    }
}

/// Records the dimension of each constraint, where the spec's units are
/// checked (`checked`; the unit check reports a constraint whose terms
/// disagree).
pub(super) fn dimensions(
    constraints: &mut [Constraint],
    statements: &[Item],
    scope: &DimensionScope,
    checked: bool,
) {
    if !checked {
        return;
    }
    for decl in constraint_declarations(statements) {
        let name = decl.name.to_string();
        if let Some(c) = constraints.iter_mut().find(|c| c.name == name) {
            c.dimension = scope.infer(&decl.value).ok().flatten();
        }
    }
}

/// A constraint that depends on a velocity: only holonomic constraints
/// `g(q, t) = 0` are supported.
fn uses_velocity(name: &syn::Ident, velocity: &str, span: SpanRange) -> Diagnostic {
    Diagnostic::new(
        span,
        format!("the constraint `{name}` uses the velocity `{velocity}`"),
    )
    .with_help(
        "a constraint is holonomic, `g(q, t) = 0`: write it in the coordinates and time \
         (a velocity constraint that integrates to one, such as rolling, is that position \
         relation)",
    )
}

/// The value of `g`, which depends on no coordinate, at `t = 0` with the
/// parameters' defaults (input functions unknown: NaN).
fn residual_at_defaults(store: &Store, g: ExprId, parameters: &[Parameter]) -> f64 {
    let mut values: Vec<f64> = (store.symbols().iter())
        .map(|s| match s.kind {
            SymbolKind::Pi => std::f64::consts::PI,
            _ => 0.0,
        })
        .collect();
    for p in parameters {
        values[p.symbol.index()] = p.default;
    }
    Evaluator::new(store, values, &|_: usize, _: &[f64]| f64::NAN).eval(g)
}

/// A constraint that depends on no coordinate: no motion changes its
/// residual, so it either holds for every state (and constrains nothing)
/// or cannot be satisfied.
fn on_no_coordinate(
    name: &syn::Ident,
    residual: f64,
    on_time: bool,
    span: SpanRange,
) -> Diagnostic {
    let message = if on_time {
        format!(
            "the constraint `{name}` cannot be satisfied: it depends on time but on no coordinate, so no motion can hold it at 0 (its residual is {residual:e} at t = 0 with the default parameters)"
        )
    } else if residual == 0.0 {
        format!(
            "the constraint `{name}` depends on no coordinate: with the default parameters it is 0 for every state, so it constrains nothing"
        )
    } else {
        format!(
            "the constraint `{name}` cannot be satisfied: it depends on no coordinate, and its residual is {residual:e} with the default parameters whatever the state"
        )
    };
    Diagnostic::new(span, message)
        .with_help("a constraint `g(q, t) = 0` relates the coordinates: write it in terms of them, or remove it")
}

/// The constraint statements among `statements`, in order.
fn constraint_declarations(statements: &[Item]) -> impl Iterator<Item = &ConstraintDecl> {
    statements.iter().filter_map(|item| match item {
        Item::Constraint(constraint) => Some(constraint),
        Item::Model { .. }
        | Item::Coordinates { .. }
        | Item::Parameters { .. }
        | Item::Inputs { .. }
        | Item::Let { .. }
        | Item::Energy { .. }
        | Item::GeneralizedForce { .. }
        | Item::PointForce { .. }
        | Item::Output(_)
        | Item::Jacobians { .. }
        | Item::HandDerived(_)
        | Item::For { .. }
        | Item::PartDef(_)
        | Item::PartInstance(_) => None,
    })
}
