//! Dimensional consistency of the expressions as written.
//!
//! Dimensions are inferred on the syntax tree, so a mismatch is reported at
//! the term the user wrote: in a sum, the terms whose dimension differs from
//! that of most terms. A name without a declared unit has an unknown
//! dimension, and checks involving it are skipped (a spec without any unit
//! is not checked at all: see the lowering's `units`). A literal zero takes
//! whatever dimension its place needs: it has an unknown dimension, and a
//! sum does not count it among its terms.

use super::constant::{self, Constants};
use crate::diagnostic::{Diagnostic, SpanRange};
use crate::expr::Func;
use crate::rational::Rational;
use crate::units::Dimension;
use rustc_hash::FxHashMap;
use syn::{BinOp, Expr, UnOp};

/// The declared dimensions of an input function.
#[derive(Clone, Debug)]
pub(super) struct InputDimensions {
    pub arguments: Vec<Option<Dimension>>,
    pub value: Option<Dimension>,
}

/// Dimensions of the names in scope (`None`: unknown).
#[derive(Default)]
pub(super) struct DimensionScope {
    pub names: FxHashMap<String, Option<Dimension>>,
    pub inputs: FxHashMap<String, InputDimensions>,
    /// Values of the constant `let`s, for exponents (as the lowering sees them).
    pub constants: Constants,
}

/// A dimension that is not the required one.
pub(super) fn mismatch(
    span: SpanRange,
    what: &str,
    found: Dimension,
    expected: Dimension,
) -> Diagnostic {
    Diagnostic::new(
        span,
        format!("{what} has dimension {found}, but must have {expected}"),
    )
}

impl DimensionScope {
    /// The dimension of `f(args…)`: dimensionless arguments for the
    /// functions that need them; otherwise arguments of one dimension,
    /// which `hypot`, `abs`, `min` and `max` return.
    fn function(&self, f: Func, args: &[&Expr]) -> Result<Option<Dimension>, Diagnostic> {
        if args.len() != f.arity() {
            return Ok(None);
        }
        if f.needs_dimensionless() {
            for arg in args {
                self.dimensionless_argument(f.name(), arg)?;
            }
            return Ok(Some(Dimension::NONE));
        }
        let mut common: Option<Dimension> = None;
        for (k, arg) in args.iter().enumerate() {
            let Some(found) = self.infer(arg)? else {
                continue;
            };
            match common {
                Some(first) if first != found => {
                    let what = format!("argument {} of `{}`", k + 1, f.name());
                    return Err(mismatch(SpanRange::of(*arg), &what, found, first)
                        .with_help("the arguments must have the same dimension"));
                }
                _ => common = Some(found),
            }
        }
        Ok(if f.keeps_dimension() {
            common
        } else {
            Some(Dimension::NONE)
        })
    }

    /// Reports an argument of `name` that has a dimension.
    fn dimensionless_argument(&self, name: &str, arg: &Expr) -> Result<(), Diagnostic> {
        match self.infer(arg)? {
            Some(d) if !d.is_none() => Err(Diagnostic::new(
                SpanRange::of(arg),
                format!(
                    "the argument of `{name}` has dimension {d}; it must be dimensionless (an angle in rad, or a ratio)"
                ),
            )),
            _ => Ok(()),
        }
    }

    /// Infers the dimension of `expr` and checks it against `expected`.
    pub fn check(
        &self,
        expr: &Expr,
        expected: Option<Dimension>,
        what: &str,
    ) -> Result<Option<Dimension>, Diagnostic> {
        let found = self.infer(expr)?;
        if let (Some(f), Some(e)) = (found, expected)
            && f != e
        {
            return Err(mismatch(SpanRange::of(expr), what, f, e)
                .with_help("check the units of the parameters and coordinates it uses"));
        }
        Ok(found)
    }

    pub fn infer(&self, expr: &Expr) -> Result<Option<Dimension>, Diagnostic> {
        Ok(match expr {
            Expr::Lit(_) if is_zero(expr) => None,
            Expr::Lit(_) => Some(Dimension::NONE),
            Expr::Paren(p) => self.infer(&p.expr)?,
            Expr::Group(g) => self.infer(&g.expr)?,
            Expr::Unary(u) if matches!(u.op, UnOp::Neg(_)) => self.infer(&u.expr)?,
            Expr::Binary(b) => match b.op {
                BinOp::Add(_) | BinOp::Sub(_) => self.sum(expr)?,
                BinOp::Mul(_) | BinOp::Div(_) => self.product(b)?,
                _ => None,
            },
            Expr::Path(p) => p
                .path
                .get_ident()
                .and_then(|i| self.names.get(&i.to_string()).copied())
                .flatten(),
            Expr::Call(call) => {
                let Expr::Path(p) = &*call.func else {
                    return Ok(None);
                };
                let Some(name) = p.path.get_ident().map(|i| i.to_string()) else {
                    return Ok(None);
                };
                let args: Vec<&Expr> = call.args.iter().collect();
                self.call(&name, &args, SpanRange::of(call))?
            }
            Expr::MethodCall(m) => {
                let mut args = vec![&*m.receiver];
                args.extend(m.args.iter());
                let name = match m.method.to_string().as_str() {
                    "powi" | "powf" => "pow".to_string(),
                    other => other.to_string(),
                };
                self.call(&name, &args, SpanRange::of(m))?
            }
            _ => None,
        })
    }

    /// The dimension of a call of `name` with `args` (a method's receiver
    /// first). A call with the wrong number of arguments has an unknown
    /// dimension: the lowering reports it, at the call.
    fn call(
        &self,
        name: &str,
        args: &[&Expr],
        span: SpanRange,
    ) -> Result<Option<Dimension>, Diagnostic> {
        let declared = self.names.contains_key(name) || self.inputs.contains_key(name);
        if let Some(f) = Func::named(name).filter(|_| !declared) {
            return self.function(f, args);
        }
        let arity = match name {
            "tan" | "cot" | "sec" | "sqrt" | "dot" | "ddot" => Some(1),
            "pow" => Some(2),
            _ => None,
        };
        if arity.is_some_and(|n| n != args.len()) {
            return Ok(None);
        }
        match name {
            "tan" | "cot" | "sec" => {
                self.dimensionless_argument(name, args[0])?;
                Ok(Some(Dimension::NONE))
            }
            "sqrt" => match self.infer(args[0])? {
                Some(d) => exact(d.checked_pow(Rational::HALF), || span),
                None => Ok(None),
            },
            "pow" => {
                let base = self.infer(args[0])?;
                // An exponent that is not constant, or not representable, is
                // reported by the lowering; here its dimension is unknown.
                let exponent = constant::evaluate(args[1], &self.constants).ok().flatten();
                match base.zip(exponent) {
                    Some((d, e)) => exact(d.checked_pow(e), || span),
                    None => Ok(None),
                }
            }
            "dot" | "ddot" => match self.infer(args[0])? {
                Some(d) => {
                    let per = if name == "dot" { 1 } else { 2 };
                    let per_time = Dimension::TIME.checked_pow(Rational::integer(per));
                    exact(per_time.and_then(|t| d.checked_div(t)), || span)
                }
                None => Ok(None),
            },
            _ => {
                let Some(input) = self.inputs.get(name) else {
                    return Ok(None);
                };
                for (k, (arg, declared)) in args.iter().zip(&input.arguments).enumerate() {
                    if let (Some(found), Some(declared)) = (self.infer(arg)?, declared)
                        && found != *declared
                    {
                        return Err(mismatch(
                            SpanRange::of(*arg),
                            &format!("argument {} of `{name}`", k + 1),
                            found,
                            *declared,
                        ));
                    }
                }
                Ok(input.value)
            }
        }
    }

    /// The dimension of `a * b / c …`, walking the left spine of the
    /// (left-deep, as long as the product) tree with a loop.
    fn product(&self, b: &syn::ExprBinary) -> Result<Option<Dimension>, Diagnostic> {
        let (mut spine, mut deepest) = (Vec::new(), b);
        loop {
            spine.push(deepest);
            match &*deepest.left {
                Expr::Binary(inner) if matches!(inner.op, BinOp::Mul(_) | BinOp::Div(_)) => {
                    deepest = inner
                }
                _ => break,
            }
        }
        let mut value = self.infer(&deepest.left)?;
        for node in spine.into_iter().rev() {
            let rhs = self.infer(&node.right)?;
            value = match value.zip(rhs) {
                None => None,
                Some((l, r)) => {
                    let d = if matches!(node.op, BinOp::Div(_)) {
                        l.checked_div(r)
                    } else {
                        l.checked_mul(r)
                    };
                    exact(d, || SpanRange::of(node))?
                }
            };
        }
        Ok(value)
    }

    /// A sum's terms must agree; the ones that differ from most are reported.
    fn sum(&self, expr: &Expr) -> Result<Option<Dimension>, Diagnostic> {
        let mut terms = Vec::new();
        addends(expr, &mut terms);
        terms.retain(|term| !is_zero(term));
        let mut known: Vec<(&Expr, Dimension)> = Vec::new();
        for term in &terms {
            if let Some(d) = self.infer(term)? {
                known.push((term, d));
            }
        }
        let Some(majority) = majority(known.iter().map(|(_, d)| *d)) else {
            return Ok(None);
        };
        if let Some((term, d)) = known.iter().find(|(_, d)| *d != majority) {
            return Err(Diagnostic::new(
                SpanRange::of(*term),
                format!(
                    "this term has dimension {d}, but the other terms of the sum have {majority}"
                ),
            ));
        }
        Ok(if known.len() == terms.len() {
            Some(majority)
        } else {
            None
        })
    }
}

/// Whether `expr` is a literal zero (`0`, `0.0`, `-0.0`, `(0)`): zero in
/// any unit, so of whatever dimension its place needs.
fn is_zero(expr: &Expr) -> bool {
    match expr {
        Expr::Lit(l) => match &l.lit {
            syn::Lit::Int(i) => i.base10_parse::<u128>().is_ok_and(|v| v == 0),
            syn::Lit::Float(f) => f.base10_parse::<f64>().is_ok_and(|v| v == 0.0),
            _ => false,
        },
        Expr::Paren(p) => is_zero(&p.expr),
        Expr::Group(g) => is_zero(&g.expr),
        Expr::Unary(u) if matches!(u.op, UnOp::Neg(_)) => is_zero(&u.expr),
        _ => false,
    }
}

/// The terms of a sum `a + b − c …` (the sign does not matter here), in
/// order. Iterative: a long sum is a tree as deep as it is long.
pub(super) fn addends<'a>(expr: &'a Expr, out: &mut Vec<&'a Expr>) {
    let mut stack = vec![expr];
    while let Some(e) = stack.pop() {
        match e {
            Expr::Binary(b) if matches!(b.op, BinOp::Add(_) | BinOp::Sub(_)) => {
                stack.push(&b.right);
                stack.push(&b.left);
            }
            // A parenthesized sum is one term of the outer sum.
            _ => out.push(e),
        }
    }
}

/// The most frequent value (the first on a tie).
pub(super) fn majority(values: impl Iterator<Item = Dimension>) -> Option<Dimension> {
    let mut counts: Vec<(Dimension, usize)> = Vec::new();
    for v in values {
        match counts.iter_mut().find(|(d, _)| *d == v) {
            Some((_, n)) => *n += 1,
            None => counts.push((v, 1)),
        }
    }
    let mut best: Option<(Dimension, usize)> = None;
    for (d, n) in counts {
        if best.is_none_or(|(_, m)| n > m) {
            best = Some((d, n));
        }
    }
    best.map(|(d, _)| d)
}

/// A computed dimension; `None`, an exponent overflow, is an error at `span`.
fn exact(
    d: Option<Dimension>,
    span: impl FnOnce() -> SpanRange,
) -> Result<Option<Dimension>, Diagnostic> {
    match d {
        Some(d) => Ok(Some(d)),
        None => Err(Diagnostic::new(
            span(),
            "the dimension of this expression has exponents beyond exact 128-bit fractions",
        )),
    }
}
