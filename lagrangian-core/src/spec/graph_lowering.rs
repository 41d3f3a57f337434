//! Translating `syn` expressions into the derivation graph
//! ([`crate::graph`]): sums, products, quotients, constant powers, `dot`
//! and the `let` helpers become graph nodes; every other subexpression
//! (names, numbers, function and input calls) is lowered to the canonical
//! form by [`ExpressionLowering`] and becomes a leaf.
//!
//! It runs on what the canonical lowering accepted, so it reports nothing
//! itself: `None` means "not on the graph", and the canonical result stands.

use super::constant;
use super::expression::{ExpressionLowering, Scope, is_arithmetic};
use crate::expr::Store;
use crate::graph::{Graph, GraphId};
use crate::rational::Rational;
use rustc_hash::FxHashMap;
use syn::{BinOp, Expr, UnOp};

pub(super) struct GraphLowering<'a> {
    pub store: &'a mut Store,
    pub graph: &'a mut Graph,
    pub scope: &'a Scope,
    /// The `let` helpers lowered to the graph so far, by name.
    pub lets: &'a FxHashMap<String, GraphId>,
    pub input_names: &'a [String],
}

impl GraphLowering<'_> {
    /// `expr` as a graph node, or `None` when part of it does not lower.
    pub fn lower(&mut self, expr: &Expr) -> Option<GraphId> {
        let value = self.expr(expr);
        // The canonical lowering of leaves records nothing that matters here.
        self.store.take_errors();
        value
    }

    fn expr(&mut self, expr: &Expr) -> Option<GraphId> {
        match expr {
            Expr::Paren(p) => self.expr(&p.expr),
            Expr::Group(g) => self.expr(&g.expr),
            Expr::Unary(u) if matches!(u.op, UnOp::Neg(_)) => {
                let v = self.expr(&u.expr)?;
                Some(self.graph.neg(self.store, v))
            }
            Expr::Binary(b) if is_arithmetic(b.op) => self.binary(b),
            Expr::Path(p) => match p.path.get_ident().map(|i| self.lets.get(&i.to_string())) {
                Some(Some(&g)) => Some(g),
                _ => self.leaf(expr),
            },
            Expr::Call(call) => {
                let name = match &*call.func {
                    Expr::Path(p) => p.path.get_ident().map(|i| i.to_string()),
                    _ => None,
                };
                let args: Vec<&Expr> = call.args.iter().collect();
                match (name.as_deref(), args.as_slice()) {
                    (Some("dot"), [x]) => self.dot(x),
                    (Some("pow"), [x, e]) => self.power(x, e),
                    (Some("sqrt"), [x]) => self.root(x),
                    _ => self.leaf(expr),
                }
            }
            Expr::MethodCall(m) => {
                let args: Vec<&Expr> = m.args.iter().collect();
                match (m.method.to_string().as_str(), args.as_slice()) {
                    ("powi" | "powf", [e]) => self.power(&m.receiver, e),
                    ("sqrt", []) => self.root(&m.receiver),
                    _ => self.leaf(expr),
                }
            }
            _ => self.leaf(expr),
        }
    }

    /// A left-deep chain `a ± b ± c …` (or `a * b / c …`) walked as a loop.
    fn binary(&mut self, b: &syn::ExprBinary) -> Option<GraphId> {
        let (mut spine, mut deepest) = (Vec::new(), b);
        loop {
            spine.push(deepest);
            match &*deepest.left {
                Expr::Binary(inner) if is_arithmetic(inner.op) => deepest = inner,
                _ => break,
            }
        }
        let mut value = self.expr(&deepest.left)?;
        for node in spine.into_iter().rev() {
            let rhs = self.expr(&node.right)?;
            let (graph, store) = (&mut *self.graph, &mut *self.store);
            value = match node.op {
                BinOp::Add(_) => graph.add(store, value, rhs),
                BinOp::Sub(_) => graph.sub(store, value, rhs),
                BinOp::Mul(_) => graph.mul(store, value, rhs),
                _ => {
                    let inverse = graph.pow(store, rhs, Rational::MINUS_ONE);
                    graph.mul(store, value, inverse)
                }
            };
        }
        Some(value)
    }

    /// The canonical lowering of `expr`, as a leaf.
    fn leaf(&mut self, expr: &Expr) -> Option<GraphId> {
        let lowering = ExpressionLowering::new(self.store, self.scope, self.input_names);
        let value = lowering.lower(expr).ok()?.value;
        Some(self.graph.leaf(self.store, value))
    }

    /// `base` to a constant power.
    fn power(&mut self, base: &Expr, exponent: &Expr) -> Option<GraphId> {
        let exponent = constant::evaluate(exponent, &self.scope.constants).ok()??;
        let base = self.expr(base)?;
        Some(self.graph.pow(self.store, base, exponent))
    }

    /// `√x`.
    fn root(&mut self, x: &Expr) -> Option<GraphId> {
        let x = self.expr(x)?;
        let half = Rational::new(1, 2)?;
        Some(self.graph.pow(self.store, x, half))
    }

    /// `dot(x)`: `Σ_i ∂x/∂q_i q̇_i + ∂x/∂t`, for a position `x`.
    fn dot(&mut self, x: &Expr) -> Option<GraphId> {
        let x = self.expr(x)?;
        let scope = self.scope;
        let store = &*self.store;
        if (scope.velocities.iter()).any(|&v| self.graph.depends_on(store, x, v)) {
            return None;
        }
        Some(
            self.graph
                .time_derivative(self.store, x, &scope.coordinates),
        )
    }
}
