//! Equation documents in Markdown with `$$` math (rendered by GitHub).

use super::notation::{Notation, Printer, latex_name};
use crate::Compiled;
use crate::expr::{ExprId, Store};
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
    let d = compiled.derivation.clone();
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
    let names: Vec<String> = model
        .coordinates
        .iter()
        .map(|c| latex_name(&c.name))
        .collect();
    let n = names.len();
    let mut p = Printer {
        store: &mut compiled.model.store,
        notation: Notation::Latex,
    };
    let _ = writeln!(out, "\n## Mass matrix\n\nSymmetric; the upper triangle:\n");
    for i in 0..n {
        for j in i..n {
            out.push_str(&equation(
                &mut p,
                &format!("M_{{{} {}}}", names[i], names[j]),
                d.mass(i, j),
            ));
        }
    }
    let _ = writeln!(out, "\n## Forcing\n");
    for (i, name) in names.iter().enumerate() {
        out.push_str(&equation(&mut p, &format!("f_{{{name}}}"), d.forcing[i]));
    }
    if d.generalized_forces.iter().any(|&q| q != Store::ZERO) {
        let _ = writeln!(
            out,
            "\n## Generalized forces\n\nFrom the force statements (included in $f$):\n"
        );
        for (i, name) in names.iter().enumerate() {
            out.push_str(&equation(
                &mut p,
                &format!("Q_{{{name}}}"),
                d.generalized_forces[i],
            ));
        }
    }
    let _ = writeln!(out, "\n## Energies\n");
    for (label, e) in [("T", d.kinetic), ("V", d.potential), ("D", d.dissipation)] {
        out.push_str(&equation(&mut p, label, e));
    }
    out
}
