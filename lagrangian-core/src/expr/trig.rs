//! Elementary functions, with sines and cosines in linearized canonical form.
//!
//! * `sin(−u) = −sin u`, `cos(−u) = cos u`: the argument is normalized so that
//!   its first non-constant term has a positive coefficient.
//! * A product of sines and cosines becomes a sum of single sines and cosines
//!   of sums and differences of the arguments (product-to-sum identities).

use super::arith::TermAccumulator;
use super::{ExprId, Func, Node, Store};
use crate::rational::Rational;
use lagrangian_runtime::functions::Elementary;
use rustc_hash::FxHashMap;

impl Store {
    /// `sin u`.
    pub fn sin(&mut self, u: ExprId) -> ExprId {
        let (sign, term) = self.trig_term(Func::Sin, u);
        self.scale(term, sign)
    }

    /// `cos u`.
    pub fn cos(&mut self, u: ExprId) -> ExprId {
        let (sign, term) = self.trig_term(Func::Cos, u);
        self.scale(term, sign)
    }

    /// `tan u = sin u · (cos u)⁻¹`.
    pub fn tan(&mut self, u: ExprId) -> ExprId {
        let s = self.sin(u);
        let c = self.cos(u);
        self.div(s, c)
    }

    /// `exp u`.
    pub fn exp(&mut self, u: ExprId) -> ExprId {
        if u == Store::ZERO {
            return Store::ONE;
        }
        if let Some((Func::Ln, inner)) = self.as_func(u) {
            return inner;
        }
        self.func_node(Func::Exp, u)
    }

    /// `ln u`.
    pub fn ln(&mut self, u: ExprId) -> ExprId {
        if u == Store::ONE {
            return Store::ZERO;
        }
        if let Some((Func::Exp, inner)) = self.as_func(u) {
            return inner;
        }
        self.func_node(Func::Ln, u)
    }

    /// Applies `f` to `args` with the canonical simplifications of each
    /// function (`args` has [`Func::arity`] expressions).
    pub fn apply(&mut self, f: Func, args: &[ExprId]) -> ExprId {
        match f.elementary() {
            Some(Elementary::Sin) => self.sin(args[0]),
            Some(Elementary::Cos) => self.cos(args[0]),
            Some(Elementary::Exp) => self.exp(args[0]),
            Some(Elementary::Ln) => self.ln(args[0]),
            None => self.call(f, args),
        }
    }

    /// Interns `f(arg)` as it is; `arg` must already be normalized for sin/cos.
    pub(crate) fn func_node(&mut self, f: Func, arg: ExprId) -> ExprId {
        self.intern(Node::Func(f, Box::new([arg])))
    }

    /// Interns `f(args…)` as it is.
    pub(crate) fn call_node(&mut self, f: Func, args: &[ExprId]) -> ExprId {
        self.intern(Node::Func(f, args.into()))
    }

    /// Does the sum `u` read as a negative quantity (first non-constant term negative)?
    fn has_negative_sign(&self, u: ExprId) -> bool {
        match self.node(u) {
            Node::Num(c) => c.is_negative(),
            Node::Add(items) => items
                .iter()
                .find(|(t, _)| *t != Store::ONE)
                .is_some_and(|(_, c)| c.is_negative()),
            _ => false,
        }
    }

    /// `f(u)` as `sign · atom`, where the atom is a canonical sin/cos node or ONE.
    fn trig_term(&mut self, f: Func, u: ExprId) -> (Rational, ExprId) {
        if u == Store::ZERO {
            return match f {
                Func::Sin => (Rational::ZERO, Store::ONE),
                _ => (Rational::ONE, Store::ONE),
            };
        }
        if self.has_negative_sign(u) {
            let flipped = self.neg(u);
            let sign = if f == Func::Sin {
                Rational::MINUS_ONE
            } else {
                Rational::ONE
            };
            (sign, self.func_node(f, flipped))
        } else {
            (Rational::ONE, self.func_node(f, u))
        }
    }

    /// `Π f_k(u_k)^n_k` for sines and cosines, linearized into a sum.
    ///
    /// Like terms are merged after every multiplication, so `sinⁿ u` costs
    /// O(n²) work and never holds more than `n + 1` terms, instead of the
    /// `2ⁿ` products of the unmerged expansion.
    pub(crate) fn trig_product(&mut self, factors: &[(Func, ExprId, u32)]) -> ExprId {
        // The running product as Σ c · atom, atom ∈ {1, sin v, cos v}.
        let mut terms: Vec<(Rational, ExprId)> = vec![(Rational::ONE, Store::ONE)];
        for &(f, b, n) in factors {
            for _ in 0..n {
                let mut next = Vec::with_capacity(terms.len() * 2);
                for &(c, atom) in &terms {
                    self.multiply_trig_atom(c, atom, f, b, &mut next);
                }
                terms = self.merge_like_terms(next);
            }
        }
        let mut acc = TermAccumulator::default();
        for (c, atom) in terms {
            acc.add(self, atom, c);
        }
        acc.finish(self)
    }

    /// Adds up the coefficients of equal atoms (first occurrence order), dropping zeros.
    fn merge_like_terms(&mut self, terms: Vec<(Rational, ExprId)>) -> Vec<(Rational, ExprId)> {
        let mut position: FxHashMap<ExprId, usize> = FxHashMap::default();
        let mut merged: Vec<(Rational, ExprId)> = Vec::with_capacity(terms.len());
        for (c, atom) in terms {
            match position.get(&atom) {
                Some(&i) => merged[i].0 = self.radd(merged[i].0, c),
                None => {
                    position.insert(atom, merged.len());
                    merged.push((c, atom));
                }
            }
        }
        merged.retain(|(c, _)| !c.is_zero());
        merged
    }

    /// Appends `c · atom · f(b)` as linearized terms to `out`.
    fn multiply_trig_atom(
        &mut self,
        c: Rational,
        atom: ExprId,
        f: Func,
        b: ExprId,
        out: &mut Vec<(Rational, ExprId)>,
    ) {
        if c.is_zero() {
            return;
        }
        let Some((g, a)) = self.as_func(atom) else {
            let (sign, t) = self.trig_term(f, b);
            out.push((self.rmul(c, sign), t));
            return;
        };
        let half = self.rmul(c, Rational::HALF);
        let minus_half = self.rmul(half, Rational::MINUS_ONE);
        let difference = self.sub(a, b);
        let total = self.add(a, b);
        // Product-to-sum identities for g(a) · f(b).
        let parts = match (g, f) {
            (Func::Sin, Func::Sin) => [
                (half, Func::Cos, difference),
                (minus_half, Func::Cos, total),
            ],
            (Func::Cos, Func::Cos) => [(half, Func::Cos, difference), (half, Func::Cos, total)],
            (Func::Sin, Func::Cos) => [(half, Func::Sin, total), (half, Func::Sin, difference)],
            (Func::Cos, Func::Sin) => [
                (half, Func::Sin, total),
                (minus_half, Func::Sin, difference),
            ],
            _ => unreachable!("only sines and cosines are linearized"),
        };
        for (k, h, arg) in parts {
            let (sign, t) = self.trig_term(h, arg);
            let k = self.rmul(k, sign);
            if !k.is_zero() {
                out.push((k, t));
            }
        }
    }
}
