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

/// Binding strength of the rendered form, to decide on parentheses.
#[derive(PartialEq, PartialOrd, Clone, Copy)]
enum Prec {
    Sum,
    Product,
    Atom,
}

impl DisplayExpr<'_> {
    fn precedence(&self, e: ExprId) -> Prec {
        match self.store.node(e) {
            Node::Add(items) if items.len() > 1 => Prec::Sum,
            Node::Add(_) => Prec::Product,
            Node::Num(c) if !c.is_integer() || c.is_negative() => Prec::Product,
            Node::Mul(_) => Prec::Product,
            _ => Prec::Atom,
        }
    }

    fn write(&self, f: &mut fmt::Formatter<'_>, e: ExprId, min: Prec) -> fmt::Result {
        let wrap = self.precedence(e) < min;
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
            Node::Func(func, u) => {
                write!(f, "{}(", func.name())?;
                self.write(f, *u, Prec::Sum)?;
                write!(f, ")")?;
            }
            Node::Input(input, args) => {
                write!(f, "{}(", self.store.inputs()[*input as usize].name)?;
                for (i, a) in args.iter().enumerate() {
                    if i > 0 {
                        write!(f, ", ")?;
                    }
                    self.write(f, *a, Prec::Sum)?;
                }
                write!(f, ")")?;
            }
        }
        if wrap {
            write!(f, ")")?;
        }
        Ok(())
    }

    fn write_term(&self, f: &mut fmt::Formatter<'_>, t: ExprId, c: Rational) -> fmt::Result {
        if t == Store::ONE {
            return write!(f, "{c}");
        }
        if !c.is_one() {
            write!(f, "{c}*")?;
        }
        self.write(f, t, Prec::Product)
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
                self.write(f, b, Prec::Atom)?;
            } else if x == Rational::HALF {
                write!(f, "sqrt(")?;
                self.write(f, b, Prec::Sum)?;
                write!(f, ")")?;
            } else {
                self.write(f, b, Prec::Atom)?;
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
        self.write(f, self.expr, Prec::Sum)
    }
}
