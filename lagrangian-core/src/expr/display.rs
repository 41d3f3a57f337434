//! Plain-text rendering of canonical expressions (`m1*r^2 + 2*m1*l0*r`).

use super::{ExprId, Node, Store};
use crate::rational::Rational;
use std::fmt;

/// Displays an expression of a store; `format!("{}", store.display(e))`.
pub struct DisplayExpr<'a> {
    store: &'a Store,
    expr: ExprId,
}

impl Store {
    /// `expr` as plain text when formatted, terms in canonical order.
    pub fn display(&self, expr: ExprId) -> DisplayExpr<'_> {
        DisplayExpr { store: self, expr }
    }

    /// The expression as text (terms in canonical order).
    pub fn to_text(&self, expr: ExprId) -> String {
        self.display(expr).to_string()
    }
}

/// How tightly a written expression binds, loosest first: the one scale of
/// every printer of expressions and emitter of code, which parenthesizes an
/// operand that binds less tightly than its place requires.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum Precedence {
    /// A sum or difference.
    Sum,
    /// A product or quotient (or a coefficient that prints as one, `-2`, `1/2`).
    Product,
    /// A negation `-x`.
    Unary,
    /// A power `x^2`.
    Power,
    /// A name, number, call or parenthesized expression.
    Atom,
}

impl Precedence {
    /// Whether an expression binding this tightly needs parentheses where
    /// `min` is required.
    pub fn needs_parentheses(self, min: Precedence) -> bool {
        self < min
    }

    /// The next tighter level: what the right operand of a left-associative
    /// operator of this level needs (`a - (b - c)`, `a / (b * c)`).
    pub fn tighter(self) -> Precedence {
        match self {
            Precedence::Sum => Precedence::Product,
            Precedence::Product => Precedence::Unary,
            Precedence::Unary => Precedence::Power,
            Precedence::Power | Precedence::Atom => Precedence::Atom,
        }
    }
}

impl DisplayExpr<'_> {
    fn precedence(&self, e: ExprId) -> Precedence {
        match self.store.node(e) {
            Node::Add(items) if items.len() > 1 => Precedence::Sum,
            Node::Add(_) => Precedence::Product,
            Node::Num(c) if !c.is_integer() || c.is_negative() => Precedence::Product,
            Node::Mul(_) => Precedence::Product,
            _ => Precedence::Atom,
        }
    }

    fn write(&self, f: &mut fmt::Formatter<'_>, e: ExprId, min: Precedence) -> fmt::Result {
        let wrap = self.precedence(e).needs_parentheses(min);
        if wrap {
            write!(f, "(")?;
        }
        match self.store.node(e) {
            Node::Num(c) => write!(f, "{c}")?,
            Node::Sym(s) => write!(f, "{}", self.store.symbol_info(*s).name)?,
            Node::Add(items) => {
                for (i, &(t, c)) in items.iter().enumerate() {
                    let magnitude = if c.is_negative() {
                        c.checked_neg().unwrap_or(c)
                    } else {
                        c
                    };
                    if i == 0 {
                        if c.is_negative() {
                            write!(f, "-")?;
                        }
                    } else if c.is_negative() {
                        write!(f, " - ")?;
                    } else {
                        write!(f, " + ")?;
                    }
                    self.write_term(f, t, magnitude)?;
                }
            }
            Node::Mul(items) => self.write_factors(f, items)?,
            Node::Func(func, args) => self.write_call(f, func.name(), args)?,
            Node::Input(input, args) => {
                self.write_call(f, &self.store.inputs()[*input as usize].name, args)?
            }
        }
        if wrap {
            write!(f, ")")?;
        }
        Ok(())
    }

    /// `name(a, b, …)`.
    fn write_call(&self, f: &mut fmt::Formatter<'_>, name: &str, args: &[ExprId]) -> fmt::Result {
        write!(f, "{name}(")?;
        for (i, a) in args.iter().enumerate() {
            if i > 0 {
                write!(f, ", ")?;
            }
            self.write(f, *a, Precedence::Sum)?;
        }
        write!(f, ")")
    }

    fn write_term(&self, f: &mut fmt::Formatter<'_>, t: ExprId, c: Rational) -> fmt::Result {
        if t == Store::ONE {
            return write!(f, "{c}");
        }
        if !c.is_one() {
            write!(f, "{c}*")?;
        }
        self.write(f, t, Precedence::Product)
    }

    fn write_factors(
        &self,
        f: &mut fmt::Formatter<'_>,
        items: &[(ExprId, Rational)],
    ) -> fmt::Result {
        for (i, &(b, x)) in items.iter().enumerate() {
            if i > 0 {
                write!(f, "*")?;
            }
            if x.is_one() {
                self.write(f, b, Precedence::Atom)?;
            } else if x == Rational::HALF {
                write!(f, "sqrt(")?;
                self.write(f, b, Precedence::Sum)?;
                write!(f, ")")?;
            } else {
                self.write(f, b, Precedence::Atom)?;
                if x.is_integer() && !x.is_negative() {
                    write!(f, "^{x}")?;
                } else {
                    write!(f, "^({x})")?;
                }
            }
        }
        Ok(())
    }
}

impl fmt::Display for DisplayExpr<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        self.write(f, self.expr, Precedence::Sum)
    }
}
