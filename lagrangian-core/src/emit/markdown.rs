//! Equation documents in Markdown with `$$` math (rendered by GitHub).

use super::notation::{Notation, Printer, latex_name};
use crate::Compiled;
use crate::derive::Derivation;
use crate::expr::{ExprId, Store};
use crate::spec::Model;
use std::fmt::Write;

/// Terms per line of a broken equation.
const TERMS_PER_LINE: usize = 3;

/// `lhs = rhs` as a `$$` block, broken over aligned lines when long.
fn equation(p: &mut Printer, lhs: &str, e: ExprId) -> String {
    let terms = p.terms(e);
    if terms.len() <= TERMS_PER_LINE {
        return format!("$$\n{lhs} = {}\n$$\n", p.expr(e));
    }
    let mut lines = Vec::new();
    for (k, chunk) in terms.chunks(TERMS_PER_LINE).enumerate() {
        let mut line = String::new();
        for (j, (negated, text)) in chunk.iter().enumerate() {
            let first = k == 0 && j == 0;
            line.push_str(match (first, negated) {
                (true, true) => "-",
                (true, false) => "",
                (false, true) => " - ",
                (false, false) => " + ",
            });
            line.push_str(text);
        }
        lines.push(if k == 0 {
            format!("{lhs} = {{}} & {line}")
        } else {
            format!("& {line}")
        });
    }
    format!(
        "$$\n\\begin{{aligned}}\n{}\n\\end{{aligned}}\n$$\n",
        lines.join(" \\\\\n")
    )
}

fn unit(u: &Option<crate::spec::UnitText>) -> String {
    u.as_ref()
        .map_or("–".to_string(), |u| format!("`{}`", u.text))
}

fn doc(lines: &[String]) -> String {
    lines.join(" ").replace('|', "\\|")
}

/// The derived equations of a compiled model as a Markdown document.
pub fn render_markdown(compiled: &mut Compiled, source: &str) -> String {
    crate::depth::with_large_stack(|| render_markdown_deep(compiled, source))
}

fn render_markdown_deep(compiled: &mut Compiled, source: &str) -> String {
    let model = &compiled.model;
    let mut out = preamble(model, source);
    out.push_str(&tables(model));
    let names: Vec<String> = (model.coordinates.iter())
        .map(|c| latex_name(&c.name))
        .collect();
    let outputs: Vec<String> = (model.outputs.iter())
        .map(|o| output_name(&o.name))
        .collect();
    let constraints: Vec<String> = (model.constraints.iter())
        .map(|c| output_name(&c.name))
        .collect();
    let d = match compiled.canonical() {
        Ok(d) => d.clone(),
        Err(too_large) => {
            out.push_str(&super::equations::too_large_to_print(&too_large));
            return out;
        }
    };
    let mut p = Printer {
        store: &mut compiled.model.store,
        notation: Notation::Latex,
    };
    out.push_str(&sections(&mut p, &d, &names));
    out.push_str(&outputs_section(&mut p, &d, &outputs));
    out.push_str(&constraints_section(&mut p, &d, &constraints, &names));
    out
}

/// Each constraint's `g`, the nonzero entries of its row of `G` and its
/// `γ` (`names` and `coordinates` in LaTeX); nothing without constraints.
fn constraints_section(
    p: &mut Printer,
    d: &Derivation,
    names: &[String],
    coordinates: &[String],
) -> String {
    let mut out = String::new();
    if names.is_empty() {
        return out;
    }
    let _ = writeln!(
        out,
        "\n## Constraints\n\n$g(q, t) = 0$, held by multipliers $\\lambda$: \
         $M \\ddot q = f + G^T \\lambda$, $G \\ddot q = \\gamma$, with $G = \\partial g / \\partial q$:\n"
    );
    let (n, terms) = (coordinates.len(), &d.constraints);
    for (k, name) in names.iter().enumerate() {
        out.push_str(&equation(p, &format!("g_{{{name}}}"), terms.residual[k]));
        for (j, coordinate) in coordinates.iter().enumerate() {
            let entry = terms.jacobian[k * n + j];
            if entry != crate::expr::Store::ZERO {
                let lhs = format!("G_{{{name},\\,{coordinate}}}");
                out.push_str(&equation(p, &lhs, entry));
            }
        }
        let lhs = format!("\\gamma_{{{name}}}");
        out.push_str(&equation(p, &lhs, terms.acceleration[k]));
    }
    out
}

/// The constraints section of [`render_markdown`] alone (empty without
/// constraints), for the audit.
pub fn render_constraints(compiled: &mut Compiled) -> String {
    // A model with constraints is always derived in the canonical form.
    let Ok(d) = compiled.canonical().cloned() else {
        return String::new();
    };
    let model = &compiled.model;
    let names: Vec<String> = (model.coordinates.iter())
        .map(|c| latex_name(&c.name))
        .collect();
    let constraints: Vec<String> = (model.constraints.iter())
        .map(|c| output_name(&c.name))
        .collect();
    let mut p = Printer {
        store: &mut compiled.model.store,
        notation: Notation::Latex,
    };
    constraints_section(&mut p, &d, &constraints, &names)
}

/// An output's name in LaTeX, upright (a name, not a product of symbols).
fn output_name(name: &str) -> String {
    format!("\\mathrm{{{}}}", name.replace('_', "\\_"))
}

/// The outputs' expressions (`names` in LaTeX); nothing without outputs.
fn outputs_section(p: &mut Printer, d: &Derivation, names: &[String]) -> String {
    let mut out = String::new();
    if names.is_empty() {
        return out;
    }
    let _ = writeln!(
        out,
        "\n## Outputs\n\nEvaluated after the solve, at the accelerations $\\ddot q$ the equations give:\n"
    );
    for (name, &value) in names.iter().zip(&d.outputs) {
        out.push_str(&equation(p, name, value));
    }
    out
}

/// The title, provenance, the model's doc and the form of the equations.
fn preamble(model: &Model, source: &str) -> String {
    let mut out = String::new();
    let _ = writeln!(out, "# Equations of motion of `{}`\n", model.name);
    let _ = writeln!(
        out,
        "Derived from `{source}` by `lpm derive --format markdown`; do not edit.\n"
    );
    for line in &model.doc {
        let _ = writeln!(out, "> {line}");
    }
    let _ = writeln!(
        out,
        "\n$$\nM(q, t)\\,\\ddot q = f(q, \\dot q, t), \\qquad L = T - V\n$$\n"
    );
    out
}

/// The tables of coordinates, parameters, input functions and outputs.
fn tables(model: &Model) -> String {
    let mut out = String::new();
    let _ = writeln!(out, "| coordinate | unit | description |\n|---|---|---|");
    for c in &model.coordinates {
        let _ = writeln!(
            out,
            "| ${}$ | {} | {} |",
            latex_name(&c.name),
            unit(&c.unit),
            doc(&c.doc)
        );
    }
    if !model.parameters.is_empty() {
        let _ = writeln!(
            out,
            "\n| parameter | default | unit | description |\n|---|---|---|---|"
        );
        for p in &model.parameters {
            let _ = writeln!(
                out,
                "| ${}$ | {} | {} | {} |",
                latex_name(&p.name),
                p.default,
                unit(&p.unit),
                doc(&p.doc)
            );
        }
    }
    if !model.inputs.is_empty() {
        let _ = writeln!(
            out,
            "\n| input function | unit | description |\n|---|---|---|"
        );
        for i in &model.inputs {
            let args: Vec<String> = i.arguments.iter().map(|(a, _)| latex_name(a)).collect();
            let _ = writeln!(
                out,
                "| $\\mathrm{{{}}}({})$ | {} | {} |",
                i.name.replace('_', "\\_"),
                args.join(", "),
                unit(&i.unit),
                doc(&i.doc)
            );
        }
    }
    out.push_str(&outputs_table(model));
    out
}

/// The table of outputs; nothing without outputs.
fn outputs_table(model: &Model) -> String {
    let mut out = String::new();
    if model.outputs.is_empty() {
        return out;
    }
    let _ = writeln!(out, "\n| output | unit | description |\n|---|---|---|");
    for o in &model.outputs {
        let (name, unit, doc) = (output_name(&o.name), unit(&o.unit), doc(&o.doc));
        let _ = writeln!(out, "| ${name}$ | {unit} | {doc} |");
    }
    out
}

/// The sections of `M`, `f`, the generalized forces and the energies;
/// `names` are the coordinates in LaTeX.
fn sections(p: &mut Printer, d: &Derivation, names: &[String]) -> String {
    let mut out = String::new();
    let n = names.len();
    let _ = writeln!(out, "\n## Mass matrix\n\nSymmetric; the upper triangle:\n");
    for i in 0..n {
        for j in i..n {
            let lhs = format!("M_{{{} {}}}", names[i], names[j]);
            out.push_str(&equation(p, &lhs, d.mass(i, j)));
        }
    }
    let _ = writeln!(out, "\n## Forcing\n");
    for (i, name) in names.iter().enumerate() {
        out.push_str(&equation(p, &format!("f_{{{name}}}"), d.forcing[i]));
    }
    if d.generalized_forces.iter().any(|&q| q != Store::ZERO) {
        let _ = writeln!(
            out,
            "\n## Generalized forces\n\nFrom the force statements (included in $f$):\n"
        );
        for (i, name) in names.iter().enumerate() {
            let lhs = format!("Q_{{{name}}}");
            out.push_str(&equation(p, &lhs, d.generalized_forces[i]));
        }
    }
    let _ = writeln!(out, "\n## Energies\n");
    for (label, e) in [("T", d.kinetic), ("V", d.potential), ("D", d.dissipation)] {
        out.push_str(&equation(p, label, e));
    }
    out
}
