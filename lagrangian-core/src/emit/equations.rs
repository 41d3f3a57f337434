//! The derived equations as a document: `lpm derive --format text|latex`.

use super::notation::{Notation, Printer, latex_name};
use crate::Compiled;
use crate::expr::ExprId;
use std::fmt::Write;

/// Renders M, f, T, V, D (and the generalized forces) of a compiled model.
pub fn render_equations(compiled: &mut Compiled, notation: Notation) -> String {
    crate::depth::with_large_stack(|| render_equations_deep(compiled, notation))
}

fn render_equations_deep(compiled: &mut Compiled, notation: Notation) -> String {
    let model = &compiled.model;
    let names: Vec<String> = model.coordinates.iter().map(|c| c.name.clone()).collect();
    let n = names.len();
    let d = compiled.derivation.clone();
    let title = model.name.clone();
    let doc = model.doc.clone();
    let mut p = Printer {
        store: &mut compiled.model.store,
        notation,
    };
    let mut out = String::new();
    let coordinate = |i: usize| match notation {
        Notation::Text => names[i].clone(),
        Notation::Latex => latex_name(&names[i]),
    };
    let equation = |out: &mut String, p: &mut Printer, lhs: String, e: ExprId| {
        let rhs = p.expr(e);
        let _ = match notation {
            Notation::Text => writeln!(out, "  {lhs} = {rhs}"),
            Notation::Latex => writeln!(out, "{lhs} &= {rhs} \\\\"),
        };
    };
    match notation {
        Notation::Text => {
            let _ = writeln!(
                out,
                "{title}: {n} coordinate(s) ({}), M(q) q̈ = f(q, q̇, t)",
                names.join(", ")
            );
            for line in &doc {
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
    let section = |out: &mut String, heading: &str| match notation {
        Notation::Text => {
            let _ = writeln!(out, "\n{heading}");
        }
        Notation::Latex => {
            let _ = writeln!(out, "&\\text{{{heading}}} \\\\");
        }
    };
    section(&mut out, "Mass matrix M (symmetric; upper triangle):");
    for i in 0..n {
        for j in i..n {
            let lhs = match notation {
                Notation::Text => format!("M[{}, {}]", names[i], names[j]),
                Notation::Latex => format!("M_{{{} {}}}", coordinate(i), coordinate(j)),
            };
            equation(&mut out, &mut p, lhs, d.mass(i, j));
        }
    }
    section(&mut out, "Forcing f:");
    for (i, name) in names.iter().enumerate() {
        let lhs = match notation {
            Notation::Text => format!("f[{name}]"),
            Notation::Latex => format!("f_{{{}}}", coordinate(i)),
        };
        equation(&mut out, &mut p, lhs, d.forcing[i]);
    }
    if d.generalized_forces
        .iter()
        .any(|&q| q != crate::expr::Store::ZERO)
    {
        section(
            &mut out,
            "Generalized forces Q (from the force statements, included in f):",
        );
        for (i, name) in names.iter().enumerate() {
            let lhs = match notation {
                Notation::Text => format!("Q[{name}]"),
                Notation::Latex => format!("Q_{{{}}}", coordinate(i)),
            };
            equation(&mut out, &mut p, lhs, d.generalized_forces[i]);
        }
    }
    section(&mut out, "Energies:");
    for (label, e) in [("T", d.kinetic), ("V", d.potential), ("D", d.dissipation)] {
        equation(&mut out, &mut p, label.to_string(), e);
    }
    if notation == Notation::Latex {
        out.push_str("\\end{aligned}\n");
    }
    out
}
