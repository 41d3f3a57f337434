//! Exact evaluation of constant expressions on the syntax tree.
//!
//! Exponents must be exact constants, and both the lowering and the
//! dimension checker need their value: this one evaluator serves both, so
//! `pow(l, 1 + 1)` is `l²` for each of them.

use super::expression::literal;
use crate::diagnostic::{Diagnostic, SpanRange};
use crate::rational::Rational;
use rustc_hash::FxHashMap;
use syn::{BinOp, Expr, UnOp};

/// Exact values of the `let` names (and hand-derived symbols) whose
/// expression is constant, by name.
pub(super) type Constants = FxHashMap<String, Rational>;

/// The exact value of `expr` when it is built from numeric literals, names
/// in `constants`, unary minus, parentheses and `+ - * /`; `Ok(None)` when
/// it is not such an expression; an error at the offending part for a
/// literal beyond exact rationals, a division by zero or an overflow.
pub(super) fn evaluate(expr: &Expr, constants: &Constants) -> Result<Option<Rational>, Diagnostic> {
    Ok(match expr {
        Expr::Lit(l) => Some(literal(&l.lit)?),
        Expr::Paren(p) => evaluate(&p.expr, constants)?,
        Expr::Group(g) => evaluate(&g.expr, constants)?,
        Expr::Unary(u) if matches!(u.op, UnOp::Neg(_)) => match evaluate(&u.expr, constants)? {
            Some(v) => Some(v.checked_neg().ok_or_else(|| overflow(expr))?),
            None => None,
        },
        Expr::Path(p) => p
            .path
            .get_ident()
            .filter(|_| p.qself.is_none())
            .and_then(|i| constants.get(&i.to_string()).copied()),
        Expr::Binary(b) => {
            let (Some(lhs), Some(rhs)) = (
                evaluate(&b.left, constants)?,
                evaluate(&b.right, constants)?,
            ) else {
                return Ok(None);
            };
            let value = match b.op {
                BinOp::Add(_) => lhs.checked_add(rhs),
                BinOp::Sub(_) => lhs.checked_sub(rhs),
                BinOp::Mul(_) => lhs.checked_mul(rhs),
                BinOp::Div(_) if rhs.is_zero() => {
                    return Err(Diagnostic::new(SpanRange::of(&b.right), "division by zero"));
                }
                BinOp::Div(_) => lhs.checked_div(rhs),
                _ => return Ok(None),
            };
            Some(value.ok_or_else(|| overflow(expr))?)
        }
        _ => None,
    })
}

fn overflow(expr: &Expr) -> Diagnostic {
    Diagnostic::new(
        SpanRange::of(expr),
        "this constant exceeds exact 128-bit fractions",
    )
}
