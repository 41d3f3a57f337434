//! The constraints phase: `constraint name = g;`, a holonomic constraint
//! `g(q, t) = 0`, lowered as a position (no velocities, no accelerations);
//! its name is declared so that a clash is reported at it, and its
//! dimension is inferred once the units are checked (the multiplier's unit
//! is energy per unit of `g`).

use super::Lowering;
use crate::diagnostic::{Diagnostic, SpanRange};
use crate::spec::ast::{ConstraintDecl, Item};
use crate::spec::dimensions::DimensionScope;
use crate::spec::expression::{Binding, ExpressionLowering};
use crate::spec::{Constraint, Statement};

impl Lowering {
    /// Declares every constraint's name, so that a second use of the name
    /// is reported where it is.
    pub(super) fn declare_constraints(&mut self, statements: &[Item]) {
        for constraint in constraint_declarations(statements) {
            self.declare(&constraint.name, Binding::Constraint);
        }
    }

    /// Lowers every constraint, in order.
    pub(super) fn constraints(&mut self, statements: &[Item]) -> Vec<Constraint> {
        constraint_declarations(statements)
            .filter_map(|constraint| self.constraint(constraint))
            .collect()
    }

    fn constraint(&mut self, decl: &ConstraintDecl) -> Option<Constraint> {
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
        | Item::HandDerived(_) => None,
    })
}
