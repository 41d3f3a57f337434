//! The outputs phase: `output name [unit] = value;`, lowered with the
//! accelerations `ddot(q)` allowed (they are evaluated after the solve).
//!
//! `ddot` is allowed in the output statements themselves only, not in the
//! `let` definitions they use: a `let` may also be used by the energies or
//! forces, which cannot contain accelerations, so a `let` names a position
//! and the output differentiates it (`output a = ddot(x_tip);`).

use super::{Lowering, validate};
use crate::diagnostic::SpanRange;
use crate::spec::ast::{Declaration, InputDecl, Item, OutputDecl};
use crate::spec::expression::{Binding, ExpressionLowering};
use crate::spec::{Coordinate, Output};

impl Lowering {
    /// Declares every output's name, so that a clash with another name is
    /// reported at the output and a use of it in an expression is explained.
    pub(super) fn declare_outputs(&mut self, statements: &[Item]) {
        for output in output_declarations(statements) {
            self.declare(&output.decl.name, Binding::Output);
        }
    }

    /// Refuses coordinates, inputs and outputs named as a built-in
    /// trajectory column (`x_dot`, `kinetic_energy`, …): each is a column
    /// of the trajectory too.
    pub(super) fn column_clashes(
        &mut self,
        coordinates: &[Coordinate],
        inputs: &[InputDecl],
        statements: &[Item],
    ) {
        let names: Vec<&str> = coordinates.iter().map(|c| c.name.as_str()).collect();
        let declared = |d: &Declaration| (d.name.to_string(), d.name.span());
        let columns = (coordinates
            .iter()
            .map(|c| ((c.name.clone(), c.span), "coordinate")))
        .chain(inputs.iter().map(|i| (declared(&i.decl), "input")))
        .chain(output_declarations(statements).map(|o| (declared(&o.decl), "output")));
        for ((name, span), what) in columns {
            if let Some(d) = validate::builtin_column_name((&name, span), what, &names) {
                self.problems.push(d);
            }
        }
    }

    /// Lowers every output, in order.
    pub(super) fn outputs(&mut self, statements: &[Item]) -> Vec<Output> {
        output_declarations(statements)
            .filter_map(|output| self.output(output))
            .collect()
    }

    fn output(&mut self, output: &OutputDecl) -> Option<Output> {
        let lowering = ExpressionLowering::new(&mut self.store, &self.scope, &self.input_names)
            .with_accelerations();
        let lowered = self.problems.take(lowering.lower(&output.value))?;
        Some(Output {
            name: output.decl.name.to_string(),
            doc: output.decl.doc.clone(),
            unit: output.decl.unit.clone(),
            span: output.decl.name.span(),
            statement: crate::spec::Statement {
                value: lowered.value,
                span: SpanRange::of(&output.value),
                input_calls: lowered.input_calls,
            },
        })
    }
}

/// The output statements among `statements`, in order.
fn output_declarations(statements: &[Item]) -> impl Iterator<Item = &OutputDecl> {
    statements.iter().filter_map(|item| match item {
        Item::Output(output) => Some(output),
        Item::Model { .. }
        | Item::Coordinates { .. }
        | Item::Parameters { .. }
        | Item::Inputs { .. }
        | Item::Let { .. }
        | Item::Energy { .. }
        | Item::GeneralizedForce { .. }
        | Item::PointForce { .. }
        | Item::Constraint(_)
        | Item::Jacobians { .. }
        | Item::HandDerived(_)
        | Item::For { .. }
        | Item::PartDef(_)
        | Item::PartInstance(_) => None,
    })
}
