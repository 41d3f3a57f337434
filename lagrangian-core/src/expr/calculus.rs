//! Differentiation (memoized), total time derivatives and substitution.

use super::arith::TermAccumulator;
use super::{EngineError, ExprId, Func, Node, Store, SymbolId};
use crate::rational::Rational;
use rustc_hash::FxHashMap;

/// The generalized coordinates of a model as symbol triples, for [`Store::time_derivative`].
#[derive(Clone, Debug)]
pub struct CoordinateSymbols {
    /// `q`.
    pub position: SymbolId,
    /// `q̇`, the symbol `dot(q)`.
    pub velocity: SymbolId,
    /// `q̇` as an expression, which `d/dt` turns `q` into.
    pub velocity_expr: ExprId,
    /// `q̈` as an expression, the symbol `ddot(q)`, which `d/dt` turns `q̇` into.
    pub acceleration_expr: ExprId,
}

impl Store {
    /// `∂e/∂s`.
    pub fn diff(&mut self, e: ExprId, s: SymbolId) -> ExprId {
        if !self.may_depend_on(e, s) {
            return Store::ZERO;
        }
        if let Some(&d) = self.diff_memo.get(&(e, s)) {
            return d;
        }
        let d = match self.node(e).clone() {
            Node::Num(_) => Store::ZERO,
            Node::Sym(t) => {
                if t == s {
                    Store::ONE
                } else {
                    Store::ZERO
                }
            }
            Node::Add(items) => {
                let mut acc = TermAccumulator::default();
                for &(t, c) in items.iter() {
                    let dt = self.diff(t, s);
                    acc.add_expr(self, dt, c);
                }
                acc.finish(self)
            }
            Node::Mul(items) => self.diff_product(&items, s),
            Node::Func(f, args) => self.diff_call(f, &args, e, s),
            Node::Input(input, args) => self.diff_input(input as usize, &args, s),
        };
        self.diff_memo.insert((e, s), d);
        d
    }

    /// Chain rule: `Σ_k ∂f/∂arg_k · ∂arg_k/∂s` for `call = f(args…)`.
    fn diff_call(&mut self, f: Func, args: &[ExprId], call: ExprId, s: SymbolId) -> ExprId {
        let derivatives: Vec<ExprId> = args.iter().map(|&a| self.diff(a, s)).collect();
        let partials = self.partials(f, args, call);
        if let ([partial], [derivative]) = (&partials[..], &derivatives[..]) {
            return self.mul(*partial, *derivative);
        }
        let mut acc = TermAccumulator::default();
        for (partial, derivative) in partials.into_iter().zip(derivatives) {
            let term = self.mul(partial, derivative);
            acc.add_expr(self, term, Rational::ONE);
        }
        acc.finish(self)
    }

    /// Product rule: `Σ_k e_k b_k^(e_k−1) ∂b_k · Π_{j≠k} b_j^e_j`.
    fn diff_product(&mut self, items: &[(ExprId, Rational)], s: SymbolId) -> ExprId {
        let mut acc = TermAccumulator::default();
        for (k, &(base, exp)) in items.iter().enumerate() {
            let db = self.diff(base, s);
            if db == Store::ZERO {
                continue;
            }
            let mut rest = items.to_vec();
            let reduced = self.radd(exp, Rational::MINUS_ONE);
            if reduced.is_zero() {
                rest.remove(k);
            } else {
                rest[k].1 = reduced;
            }
            let cofactor = self.raw_monomial(rest);
            let term = self.mul(cofactor, db);
            acc.add_expr(self, term, exp);
        }
        acc.finish(self)
    }

    /// Chain rule through an input function, using its declared partial derivatives.
    fn diff_input(&mut self, input: usize, args: &[ExprId], s: SymbolId) -> ExprId {
        let mut acc = TermAccumulator::default();
        for (position, &arg) in args.iter().enumerate() {
            let da = self.diff(arg, s);
            if da == Store::ZERO {
                continue;
            }
            let Some(template) = self.inputs[input].derivatives[position] else {
                self.record(EngineError::MissingDerivative {
                    input,
                    argument: position,
                });
                continue;
            };
            let formal = self.inputs[input].arguments.clone();
            let binding: FxHashMap<SymbolId, ExprId> =
                formal.into_iter().zip(args.iter().copied()).collect();
            let partial = self.substitute(template, &binding);
            let term = self.mul(partial, da);
            acc.add_expr(self, term, Rational::ONE);
        }
        acc.finish(self)
    }

    /// The total time derivative `de/dt = Σ_i (∂e/∂q_i q̇_i + ∂e/∂q̇_i q̈_i) + ∂e/∂t`.
    pub fn time_derivative(
        &mut self,
        e: ExprId,
        coordinates: &[CoordinateSymbols],
        time: SymbolId,
    ) -> ExprId {
        let mut acc = TermAccumulator::default();
        for c in coordinates {
            let dq = self.diff(e, c.position);
            let term = self.mul(dq, c.velocity_expr);
            acc.add_expr(self, term, Rational::ONE);
            let dv = self.diff(e, c.velocity);
            let term = self.mul(dv, c.acceleration_expr);
            acc.add_expr(self, term, Rational::ONE);
        }
        let dt = self.diff(e, time);
        acc.add_expr(self, dt, Rational::ONE);
        acc.finish(self)
    }

    /// `e` with every node `a` for which `replace(a)` gives a value replaced by
    /// it (outermost first), rebuilt in canonical form.
    pub fn replace_atoms(
        &mut self,
        e: ExprId,
        replace: &mut dyn FnMut(&mut Store, ExprId) -> Option<ExprId>,
    ) -> ExprId {
        let mut memo = FxHashMap::default();
        self.replace_memo(e, replace, &mut memo)
    }

    fn replace_memo(
        &mut self,
        e: ExprId,
        replace: &mut dyn FnMut(&mut Store, ExprId) -> Option<ExprId>,
        memo: &mut FxHashMap<ExprId, ExprId>,
    ) -> ExprId {
        if let Some(&r) = memo.get(&e) {
            return r;
        }
        let r = match replace(self, e) {
            Some(value) => value,
            None => match self.node(e).clone() {
                Node::Num(_) | Node::Sym(_) => e,
                Node::Add(items) => {
                    let mut acc = TermAccumulator::default();
                    for &(t, c) in items.iter() {
                        let rt = self.replace_memo(t, replace, memo);
                        acc.add_expr(self, rt, c);
                    }
                    acc.finish(self)
                }
                Node::Mul(items) => {
                    let mut result = Store::ONE;
                    for &(b, x) in items.iter() {
                        let rb = self.replace_memo(b, replace, memo);
                        let p = self.pow(rb, x);
                        result = self.mul(result, p);
                    }
                    result
                }
                Node::Func(f, args) => {
                    let new_args: Vec<ExprId> = (args.iter())
                        .map(|&a| self.replace_memo(a, replace, memo))
                        .collect();
                    self.apply(f, &new_args)
                }
                Node::Input(input, args) => {
                    let new_args = args
                        .iter()
                        .map(|&a| self.replace_memo(a, replace, memo))
                        .collect();
                    self.input_call(input as usize, new_args)
                }
            },
        };
        memo.insert(e, r);
        r
    }

    /// `e` with symbols replaced by expressions, rebuilt in canonical form.
    pub fn substitute(&mut self, e: ExprId, binding: &FxHashMap<SymbolId, ExprId>) -> ExprId {
        let mask = binding.keys().fold(0u64, |m, s| m | super::symbol_bit(*s));
        let mut memo = FxHashMap::default();
        self.substitute_memo(e, binding, mask, &mut memo)
    }

    fn substitute_memo(
        &mut self,
        e: ExprId,
        binding: &FxHashMap<SymbolId, ExprId>,
        mask: u64,
        memo: &mut FxHashMap<ExprId, ExprId>,
    ) -> ExprId {
        if self.mask(e) & mask == 0 {
            return e;
        }
        if let Some(&r) = memo.get(&e) {
            return r;
        }
        let r = match self.node(e).clone() {
            Node::Num(_) => e,
            Node::Sym(s) => binding.get(&s).copied().unwrap_or(e),
            Node::Add(items) => {
                let mut acc = TermAccumulator::default();
                for &(t, c) in items.iter() {
                    let st = self.substitute_memo(t, binding, mask, memo);
                    acc.add_expr(self, st, c);
                }
                acc.finish(self)
            }
            Node::Mul(items) => {
                let mut result = Store::ONE;
                for &(b, x) in items.iter() {
                    let sb = self.substitute_memo(b, binding, mask, memo);
                    let p = self.pow(sb, x);
                    result = self.mul(result, p);
                }
                result
            }
            Node::Func(f, args) => {
                let new_args: Vec<ExprId> = (args.iter())
                    .map(|&a| self.substitute_memo(a, binding, mask, memo))
                    .collect();
                self.apply(f, &new_args)
            }
            Node::Input(input, args) => {
                let new_args = args
                    .iter()
                    .map(|&a| self.substitute_memo(a, binding, mask, memo))
                    .collect();
                self.input_call(input as usize, new_args)
            }
        };
        memo.insert(e, r);
        r
    }
}
