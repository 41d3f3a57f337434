//! The derived equations (and the outputs) as a document: `lpm derive
//! --format text|latex`.

use super::notation::{Notation, Printer, latex_name};
use crate::Compiled;
use crate::expr::{ExprId, Store};
use crate::spec::Model;
use std::fmt::Write;

/// Renders M, f, T, V, D (and the generalized forces) of a compiled model.
pub fn render_equations(compiled: &mut Compiled, notation: Notation) -> String {
    crate::depth::with_large_stack(|| render_equations_deep(compiled, notation))
}

fn render_equations_deep(compiled: &mut Compiled, notation: Notation) -> String {
    let model = &compiled.model;
    let names: Vec<String> = (model.coordinates.iter())
        .map(|c| match notation {
            Notation::Text => c.name.clone(),
            Notation::Latex => latex_name(&c.name),
        })
        .collect();
    let n = names.len();
    let outputs = output_labels(model, notation);
    let constraints: Vec<String> = (model.constraints.iter())
        .map(|c| match notation {
            Notation::Text => c.name.clone(),
            Notation::Latex => format!("\\mathrm{{{}}}", c.name.replace('_', "\\_")),
        })
        .collect();
    let mut out = heading(model, notation);
    let d = match compiled.canonical() {
        Ok(d) => d.clone(),
        Err(too_large) => {
            out.push_str(&too_large_to_print(&too_large));
            return out;
        }
    };
    let mut doc = Document {
        printer: Printer {
            store: &mut compiled.model.store,
            notation,
        },
        out,
    };
    doc.section("Mass matrix M (symmetric; upper triangle):");
    for i in 0..n {
        for j in i..n {
            doc.equation(label(notation, "M", &[&names[i], &names[j]]), d.mass(i, j));
        }
    }
    doc.section("Forcing f:");
    for (i, name) in names.iter().enumerate() {
        doc.equation(label(notation, "f", &[name]), d.forcing[i]);
    }
    if d.generalized_forces.iter().any(|&q| q != Store::ZERO) {
        doc.section("Generalized forces Q (from the force statements, included in f):");
        for (i, name) in names.iter().enumerate() {
            doc.equation(label(notation, "Q", &[name]), d.generalized_forces[i]);
        }
    }
    doc.section("Energies:");
    for (label, e) in [("T", d.kinetic), ("V", d.potential), ("D", d.dissipation)] {
        doc.equation(label.to_string(), e);
    }
    if !outputs.is_empty() {
        doc.section(
            "Outputs (evaluated after the solve, at the accelerations the equations give):",
        );
        for (label, &e) in outputs.into_iter().zip(&d.outputs) {
            doc.equation(label, e);
        }
    }
    doc.constraints(&constraints, &names, &d.constraints);
    if notation == Notation::Latex {
        doc.out.push_str("\\end{aligned}\n");
    }
    doc.out
}

/// Why the equations of a model are not printed: they are too large for
/// the canonical form (the model still compiles, from the derivation graph).
pub(crate) fn too_large_to_print(reason: &crate::SpecErrors) -> String {
    let why: Vec<&str> = (reason.diagnostics.iter())
        .map(|d| d.message.as_str())
        .collect();
    format!(
        "The equations are too large to print in the exact canonical form ({}); \
         the model compiles from its derivation graph.\n",
        why.join("; ")
    )
}

/// The model's name, dimension and doc (text), or the opening of the
/// `aligned` block (LaTeX).
fn heading(model: &Model, notation: Notation) -> String {
    let mut out = String::new();
    let title = &model.name;
    match notation {
        Notation::Text => {
            let names: Vec<&str> = model.coordinates.iter().map(|c| c.name.as_str()).collect();
            let _ = writeln!(
                out,
                "{title}: {} coordinate(s) ({}), M(q) q̈ = f(q, q̇, t)",
                names.len(),
                names.join(", ")
            );
            for line in &model.doc {
                let _ = writeln!(out, "  {line}");
            }
        }
        Notation::Latex => {
            let _ = writeln!(
                out,
                "% {title}: M(q) \\ddot q = f(q, \\dot q, t)\n\\begin{{aligned}}"
            );
        }
    }
    out
}

/// Each output's name with its unit: `a2 [m/s^2]` (text) or
/// `\mathrm{a2}\;[\mathrm{m/s^2}]` (LaTeX).
fn output_labels(model: &Model, notation: Notation) -> Vec<String> {
    let label = |o: &crate::spec::Output| {
        let unit = o.unit.as_ref().map(|u| u.text.as_str());
        match notation {
            Notation::Text => match unit {
                Some(u) => format!("{} [{u}]", o.name),
                None => o.name.clone(),
            },
            Notation::Latex => {
                let name = format!("\\mathrm{{{}}}", o.name.replace('_', "\\_"));
                match unit {
                    Some(u) => format!("{name}\\;[\\mathrm{{{u}}}]"),
                    None => name,
                }
            }
        }
    };
    model.outputs.iter().map(label).collect()
}

/// `M[a, b]` (text) or `M_{a b}` (LaTeX).
fn label(notation: Notation, symbol: &str, indices: &[&String]) -> String {
    let indices: Vec<&str> = indices.iter().map(|s| s.as_str()).collect();
    match notation {
        Notation::Text => format!("{symbol}[{}]", indices.join(", ")),
        Notation::Latex => format!("{symbol}_{{{}}}", indices.join(" ")),
    }
}

/// The document being written.
struct Document<'a> {
    printer: Printer<'a>,
    out: String,
}

impl Document<'_> {
    fn section(&mut self, heading: &str) {
        let _ = match self.printer.notation {
            Notation::Text => writeln!(self.out, "\n{heading}"),
            Notation::Latex => writeln!(self.out, "&\\text{{{heading}}} \\\\"),
        };
    }

    /// `g`, the nonzero entries of `G` and `γ` of each constraint
    /// (`constraints` and `coordinates` their names in the notation);
    /// nothing without constraints.
    fn constraints(
        &mut self,
        constraints: &[String],
        coordinates: &[String],
        terms: &crate::constraints::ConstraintTerms,
    ) {
        if constraints.is_empty() {
            return;
        }
        self.section(
            "Constraints g(q, t) = 0, held by multipliers λ: M q̈ = f + Gᵀλ, G q̈ = γ (G = ∂g/∂q):",
        );
        let n = coordinates.len();
        let notation = self.printer.notation;
        let gamma = if notation == Notation::Text {
            "γ"
        } else {
            "\\gamma"
        };
        for (k, name) in constraints.iter().enumerate() {
            self.equation(label(notation, "g", &[name]), terms.residual[k]);
            for (j, coordinate) in coordinates.iter().enumerate() {
                let entry = terms.jacobian[k * n + j];
                if entry != Store::ZERO {
                    self.equation(label(notation, "G", &[name, coordinate]), entry);
                }
            }
            self.equation(label(notation, gamma, &[name]), terms.acceleration[k]);
        }
    }

    fn equation(&mut self, lhs: String, e: ExprId) {
        let rhs = self.printer.expr(e);
        let _ = match self.printer.notation {
            Notation::Text => writeln!(self.out, "  {lhs} = {rhs}"),
            Notation::Latex => writeln!(self.out, "{lhs} &= {rhs} \\\\"),
        };
    }
}
