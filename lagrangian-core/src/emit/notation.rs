//! Printing display trees as plain text or LaTeX.

use crate::expr::pretty::{Tree, pretty};
use crate::expr::{ExprId, Func, Node, Precedence, Store, SymbolKind};
use crate::rational::Rational;

/// How symbols and operators are written.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Notation {
    /// The spec's own syntax: `m1*pow(dot(r), 2)`-like, readable in a terminal.
    Text,
    /// LaTeX math: `m_{1} \dot{r}^{2}`.
    Latex,
}

const GREEK: &[&str] = &[
    "alpha", "beta", "gamma", "delta", "epsilon", "zeta", "eta", "theta", "iota", "kappa",
    "lambda", "mu", "nu", "xi", "pi", "rho", "sigma", "tau", "upsilon", "phi", "chi", "psi",
    "omega", "Gamma", "Delta", "Theta", "Lambda", "Xi", "Pi", "Sigma", "Upsilon", "Phi", "Psi",
    "Omega",
];

/// A spec name in LaTeX: `theta1` → `\theta_{1}`, `k_tor` → `k_{\mathrm{tor}}`.
pub fn latex_name(name: &str) -> String {
    let (base, sub) = match name.split_once('_') {
        Some((b, s)) => (b, s.to_string()),
        None => {
            let digits = name.len() - name.trim_end_matches(|c: char| c.is_ascii_digit()).len();
            let split = name.len() - digits;
            (&name[..split], name[split..].to_string())
        }
    };
    let base = if base.is_empty() { name } else { base };
    let base_tex = if GREEK.contains(&base) {
        format!("\\{base}")
    } else if base.chars().count() == 1 {
        base.to_string()
    } else {
        format!("\\mathrm{{{}}}", base.replace('_', "\\_"))
    };
    if sub.is_empty() || base == name {
        return base_tex;
    }
    let sub_tex = if sub.chars().all(|c| c.is_ascii_digit()) || sub.chars().count() == 1 {
        sub
    } else {
        format!("\\mathrm{{{}}}", sub.replace('_', "\\_"))
    };
    format!("{base_tex}_{{{sub_tex}}}")
}

/// Renders display trees in one notation.
pub struct Printer<'a> {
    /// The store of the expressions (regrouping builds new expressions).
    pub store: &'a mut Store,
    /// Text or LaTeX.
    pub notation: Notation,
}

impl Printer<'_> {
    /// `e` in its regrouped display form ([`crate::expr::pretty`]).
    pub fn expr(&mut self, e: ExprId) -> String {
        let tree = pretty(self.store, e);
        self.tree(&tree, Precedence::Sum)
    }

    /// The top-level terms of the display form, each with its sign, for
    /// breaking a long equation over lines.
    pub fn terms(&mut self, e: ExprId) -> Vec<(bool, String)> {
        match pretty(self.store, e) {
            Tree::Add(parts) => parts
                .iter()
                .map(|(negated, t)| (*negated, self.tree(t, Precedence::Product)))
                .collect(),
            other => vec![(false, self.tree(&other, Precedence::Sum))],
        }
    }

    fn tree(&mut self, t: &Tree, min: Precedence) -> String {
        let (text, prec) = match t {
            Tree::Num(c) => (
                self.number(*c),
                if c.is_integer() && !c.is_negative() {
                    Precedence::Power
                } else {
                    Precedence::Product
                },
            ),
            Tree::Atom(e) => (self.atom(*e), Precedence::Power),
            Tree::Pow(base, e) => (self.power(base, *e), Precedence::Power),
            Tree::Mul(items) => {
                let parts: Vec<String> = items
                    .iter()
                    .map(|i| self.tree(i, Precedence::Product))
                    .collect();
                let sep = if self.notation == Notation::Latex {
                    " \\, "
                } else {
                    "*"
                };
                (parts.join(sep), Precedence::Product)
            }
            Tree::Add(parts) => {
                let mut text = String::new();
                for (k, (negated, item)) in parts.iter().enumerate() {
                    let body = self.tree(item, Precedence::Product);
                    match (k, negated) {
                        (0, true) => text.push('-'),
                        (0, false) => {}
                        (_, true) => text.push_str(" - "),
                        (_, false) => text.push_str(" + "),
                    }
                    text.push_str(&body);
                }
                (text, Precedence::Sum)
            }
        };
        if prec.needs_parentheses(min) {
            self.parens(&text)
        } else {
            text
        }
    }

    fn parens(&self, text: &str) -> String {
        match self.notation {
            Notation::Text => format!("({text})"),
            Notation::Latex => format!("\\left({text}\\right)"),
        }
    }

    fn number(&self, c: Rational) -> String {
        match self.notation {
            Notation::Text => c.to_string(),
            Notation::Latex if c.is_integer() => c.to_string(),
            Notation::Latex => {
                let sign = if c.is_negative() { "-" } else { "" };
                format!("{sign}\\frac{{{}}}{{{}}}", c.numer().abs(), c.denom())
            }
        }
    }

    fn power(&mut self, base: &Tree, e: Rational) -> String {
        let latex = self.notation == Notation::Latex;
        if e == Rational::HALF {
            let inner = self.tree(base, Precedence::Sum);
            return if latex {
                format!("\\sqrt{{{inner}}}")
            } else {
                format!("sqrt({inner})")
            };
        }
        let b = self.tree(base, Precedence::Power);
        match (latex, e.is_integer() && !e.is_negative()) {
            (true, _) => format!("{b}^{{{}}}", self.number(e)),
            (false, true) => format!("{b}^{e}"),
            (false, false) => format!("{b}^({e})"),
        }
    }

    fn atom(&mut self, e: ExprId) -> String {
        let latex = self.notation == Notation::Latex;
        match self.store.node(e).clone() {
            Node::Sym(s) => {
                let info = self.store.symbol_info(s).clone();
                let coordinate = |name: &str| {
                    name.trim_start_matches("ddot(")
                        .trim_start_matches("dot(")
                        .trim_end_matches(')')
                        .to_string()
                };
                match (info.kind, latex) {
                    (SymbolKind::Velocity(_), true) => {
                        dotted("\\dot", &latex_name(&coordinate(&info.name)))
                    }
                    (SymbolKind::Acceleration(_), true) => {
                        dotted("\\ddot", &latex_name(&coordinate(&info.name)))
                    }
                    (SymbolKind::Pi, true) => "\\pi".to_string(),
                    (_, true) => latex_name(&info.name),
                    (_, false) => info.name,
                }
            }
            Node::Func(f, args) => {
                let args: Vec<String> = args.iter().map(|a| self.expr(*a)).collect();
                let args = args.join(", ");
                if latex {
                    latex_call(f, &args)
                } else {
                    format!("{}({args})", f.name())
                }
            }
            Node::Input(index, args) => {
                let name = self.store.inputs()[index as usize].name.clone();
                let args: Vec<String> = args.iter().map(|a| self.expr(*a)).collect();
                if latex {
                    format!(
                        "\\mathrm{{{}}}\\left({}\\right)",
                        name.replace('_', "\\_"),
                        args.join(", ")
                    )
                } else {
                    format!("{name}({})", args.join(", "))
                }
            }
            _ => {
                let tree = pretty(self.store, e);
                self.tree(&tree, Precedence::Power)
            }
        }
    }
}

/// `f(args)` in LaTeX: an operator name where LaTeX has one, `|x|` for `abs`.
fn latex_call(f: Func, args: &str) -> String {
    let operator = match f {
        Func::Exp => return format!("e^{{{args}}}"),
        Func::Abs => return format!("\\left|{args}\\right|"),
        Func::Sin => "\\sin",
        Func::Cos => "\\cos",
        Func::Ln => "\\ln",
        Func::Asin => "\\arcsin",
        Func::Acos => "\\arccos",
        Func::Atan => "\\arctan",
        Func::Sinh => "\\sinh",
        Func::Cosh => "\\cosh",
        Func::Tanh => "\\tanh",
        Func::Min => "\\min",
        Func::Max => "\\max",
        Func::Atan2 => "\\operatorname{atan2}",
        Func::Hypot => "\\operatorname{hypot}",
        Func::Sign => "\\operatorname{sgn}",
    };
    format!("{operator}\\left({args}\\right)")
}

/// `\dot{\theta}_{1}` rather than `\dot{\theta_{1}}`.
fn dotted(accent: &str, name: &str) -> String {
    match name.split_once("_{") {
        Some((base, sub)) => format!("{accent}{{{base}}}_{{{sub}"),
        None => format!("{accent}{{{name}}}"),
    }
}

#[cfg(test)]
mod tests {
    use super::latex_name;

    #[test]
    fn latex_names() {
        assert_eq!(latex_name("theta1"), "\\theta_{1}");
        assert_eq!(latex_name("k_tor"), "k_{\\mathrm{tor}}");
        assert_eq!(latex_name("m2"), "m_{2}");
        assert_eq!(latex_name("I1"), "I_{1}");
        assert_eq!(latex_name("crush"), "\\mathrm{crush}");
        assert_eq!(latex_name("g"), "g");
        assert_eq!(latex_name("omega_n"), "\\omega_{n}");
    }
}
