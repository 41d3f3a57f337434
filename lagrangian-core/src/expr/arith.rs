//! Sums, products and powers in expanded canonical form.

use super::{
    EngineError, ExprId, Func, MAX_EXPANDED_TERMS, MAX_EXPONENT, MAX_PRODUCT_TERMS, Node, Store,
};
use crate::rational::Rational;
use rustc_hash::FxHashMap;

impl Store {
    // ----- checked coefficient arithmetic (overflow is recorded, never wrong) -----

    pub(crate) fn radd(&mut self, a: Rational, b: Rational) -> Rational {
        a.checked_add(b).unwrap_or_else(|| self.overflow())
    }

    pub(crate) fn rmul(&mut self, a: Rational, b: Rational) -> Rational {
        a.checked_mul(b).unwrap_or_else(|| self.overflow())
    }

    fn overflow(&mut self) -> Rational {
        self.record(EngineError::Overflow);
        Rational::ZERO
    }

    // ----- sums -----

    /// `a + b`.
    pub fn add(&mut self, a: ExprId, b: ExprId) -> ExprId {
        if a == Store::ZERO {
            return b;
        }
        if b == Store::ZERO {
            return a;
        }
        let (ta, tb) = (self.terms(a), self.terms(b));
        let mut merged = Vec::with_capacity(ta.len() + tb.len());
        let (mut i, mut j) = (0, 0);
        while i < ta.len() && j < tb.len() {
            match ta[i].0.cmp(&tb[j].0) {
                std::cmp::Ordering::Less => {
                    merged.push(ta[i]);
                    i += 1;
                }
                std::cmp::Ordering::Greater => {
                    merged.push(tb[j]);
                    j += 1;
                }
                std::cmp::Ordering::Equal => {
                    let c = self.radd(ta[i].1, tb[j].1);
                    if !c.is_zero() {
                        merged.push((ta[i].0, c));
                    }
                    i += 1;
                    j += 1;
                }
            }
        }
        merged.extend_from_slice(&ta[i..]);
        merged.extend_from_slice(&tb[j..]);
        self.sum_from_sorted(merged)
    }

    /// `a − b`.
    pub fn sub(&mut self, a: ExprId, b: ExprId) -> ExprId {
        let nb = self.neg(b);
        self.add(a, nb)
    }

    /// `−a`.
    pub fn neg(&mut self, a: ExprId) -> ExprId {
        self.scale(a, Rational::MINUS_ONE)
    }

    /// `c · a`.
    pub fn scale(&mut self, a: ExprId, c: Rational) -> ExprId {
        if c.is_zero() || a == Store::ZERO {
            return Store::ZERO;
        }
        if c.is_one() {
            return a;
        }
        let terms = self
            .terms(a)
            .into_iter()
            .map(|(t, k)| (t, self.rmul(k, c)))
            .filter(|(_, k)| !k.is_zero())
            .collect();
        self.sum_from_sorted(terms)
    }

    /// `Σ items`.
    pub fn sum(&mut self, items: &[ExprId]) -> ExprId {
        let weighted: Vec<_> = items.iter().map(|&e| (e, Rational::ONE)).collect();
        self.linear_combination(&weighted)
    }

    /// `Σ c_k · e_k`.
    pub fn linear_combination(&mut self, items: &[(ExprId, Rational)]) -> ExprId {
        match items {
            [] => Store::ZERO,
            [(e, c)] => self.scale(*e, *c),
            [(a, ca), (b, cb)] => {
                let (a, b) = (self.scale(*a, *ca), self.scale(*b, *cb));
                self.add(a, b)
            }
            _ => {
                let mut acc = TermAccumulator::default();
                for &(e, c) in items {
                    for (t, k) in self.terms(e) {
                        let k = self.rmul(k, c);
                        acc.add(self, t, k);
                    }
                }
                acc.finish(self)
            }
        }
    }

    /// Builds a sum from terms sorted by id, without duplicates or zeros.
    pub(crate) fn sum_from_sorted(&mut self, terms: Vec<(ExprId, Rational)>) -> ExprId {
        match terms.as_slice() {
            [] => Store::ZERO,
            [(t, c)] if c.is_one() => *t,
            [(t, c)] if *t == Store::ONE => self.num(*c),
            _ => self.intern(Node::Add(terms.into_boxed_slice())),
        }
    }

    // ----- products -----

    /// `a · b`, distributed over sums.
    pub fn mul(&mut self, a: ExprId, b: ExprId) -> ExprId {
        if a == Store::ZERO || b == Store::ZERO {
            return Store::ZERO;
        }
        if a == Store::ONE {
            return b;
        }
        if b == Store::ONE {
            return a;
        }
        if let Some(c) = self.as_num(a) {
            return self.scale(b, c);
        }
        if let Some(c) = self.as_num(b) {
            return self.scale(a, c);
        }
        let key = if a <= b { (a, b) } else { (b, a) };
        if let Some(&r) = self.mul_memo.get(&key) {
            return r;
        }
        let (ta, tb) = (self.terms(a), self.terms(b));
        if ta.len().saturating_mul(tb.len()) > MAX_PRODUCT_TERMS {
            self.record(EngineError::ProductTooLarge {
                terms: (ta.len(), tb.len()),
            });
            return Store::ZERO;
        }
        let result = if ta.len() == 1 && tb.len() == 1 {
            let product = self.mul_monomials(ta[0].0, tb[0].0);
            let c = self.rmul(ta[0].1, tb[0].1);
            self.scale(product, c)
        } else {
            let mut acc = TermAccumulator::default();
            for &(t1, c1) in &ta {
                for &(t2, c2) in &tb {
                    let product = self.mul_monomials(t1, t2);
                    let c = self.rmul(c1, c2);
                    for (t, k) in self.terms(product) {
                        let k = self.rmul(k, c);
                        acc.add(self, t, k);
                    }
                }
            }
            acc.finish(self)
        };
        self.mul_memo.insert(key, result);
        result
    }

    /// `Π items`.
    pub fn product(&mut self, items: &[ExprId]) -> ExprId {
        items.iter().fold(Store::ONE, |acc, &e| self.mul(acc, e))
    }

    /// `a / b`.
    pub fn div(&mut self, a: ExprId, b: ExprId) -> ExprId {
        let inv = self.pow(b, Rational::MINUS_ONE);
        self.mul(a, inv)
    }

    /// Product of two monomials (terms without coefficient); may return a sum.
    fn mul_monomials(&mut self, t1: ExprId, t2: ExprId) -> ExprId {
        if t1 == Store::ONE {
            return t2;
        }
        if t2 == Store::ONE {
            return t1;
        }
        let key = if t1 <= t2 { (t1, t2) } else { (t2, t1) };
        if let Some(&r) = self.mul_memo.get(&key) {
            return r;
        }
        let mut factors = self.factors(t1);
        factors.extend(self.factors(t2));
        let result = self.product_of_factors(factors);
        self.mul_memo.insert(key, result);
        result
    }

    /// Normalizes `Π base^exp` into canonical form; may return a sum or a number.
    pub(crate) fn product_of_factors(&mut self, mut factors: Vec<(ExprId, Rational)>) -> ExprId {
        factors.sort_by_key(|(b, _)| *b);
        let mut merged: Vec<(ExprId, Rational)> = Vec::with_capacity(factors.len());
        for (b, e) in factors {
            match merged.last() {
                Some(&(last, exp)) if last == b => {
                    let total = self.radd(exp, e);
                    if let Some(slot) = merged.last_mut() {
                        slot.1 = total;
                    }
                }
                _ => merged.push((b, e)),
            }
        }
        merged.retain(|(_, e)| !e.is_zero());
        if !merged.iter().all(|&(_, e)| self.exponent_in_range(e)) {
            // Reported; not linearized (a sine to a huge power would never finish).
            return self.raw_monomial(merged);
        }

        let mut coefficient = Rational::ONE;
        let mut kept = Vec::with_capacity(merged.len());
        let mut pending: Vec<ExprId> = Vec::new(); // expressions still to multiply in
        let mut trig: Vec<(Func, ExprId, u32)> = Vec::new();
        for (base, exp) in merged {
            match self.node(base).clone() {
                Node::Num(c) => match c.exact_pow(exp) {
                    Some(v) => coefficient = self.rmul(coefficient, v),
                    None => kept.push((base, exp)),
                },
                Node::Add(_) if exp.is_integer() && !exp.is_negative() => {
                    pending.push(self.pow(base, exp));
                }
                Node::Mul(inner) if exp.is_integer() => {
                    let scaled = inner.iter().map(|&(b, e)| (b, self.rmul(e, exp))).collect();
                    pending.push(self.product_of_factors(scaled));
                }
                Node::Func(f @ (Func::Sin | Func::Cos), args)
                    if exp.is_integer() && !exp.is_negative() =>
                {
                    let count = exp.to_i64().and_then(|n| u32::try_from(n).ok());
                    match count {
                        Some(n) => trig.push((f, args[0], n)),
                        None => self.record(EngineError::Overflow),
                    }
                }
                _ => kept.push((base, exp)),
            }
        }
        self.finish_product(coefficient, kept, trig, pending, &[])
    }

    /// `coefficient · Π kept · Π trig · Π pending`, where `kept` holds
    /// factors that stay as they are, `trig` non-negative powers of sines
    /// and cosines to linearize, and `pending` expressions to multiply in.
    ///
    /// A negative power of `sin u` or `cos u` in `kept` is first combined with
    /// the sines and cosines of multiples of `u` (see
    /// [`Store::negative_trig_group`]); `done` lists the arguments already
    /// combined in this product.
    pub(super) fn finish_product(
        &mut self,
        coefficient: Rational,
        mut kept: Vec<(ExprId, Rational)>,
        mut trig: Vec<(Func, ExprId, u32)>,
        mut pending: Vec<ExprId>,
        done: &[ExprId],
    ) -> ExprId {
        if let Some((u, laurent)) = self.negative_trig_group(&mut kept, &mut trig, done) {
            let done: Vec<ExprId> = done.iter().copied().chain([u]).collect();
            let (sin, cos) = (self.func_node(Func::Sin, u), self.func_node(Func::Cos, u));
            let mut acc = TermAccumulator::default();
            for ((i, j), c) in laurent {
                let (mut kept, mut trig) = (kept.clone(), trig.clone());
                if i >= 0 && j >= 0 {
                    // Within the u32 range: the exponents are at most MAX_EXPONENT.
                    trig.extend([(Func::Sin, u, i as u32), (Func::Cos, u, j as u32)]);
                    trig.retain(|t| t.2 > 0);
                } else {
                    // Kept as it is, including a first power of the other function.
                    self.insert_factor(&mut kept, sin, Rational::integer(i));
                    self.insert_factor(&mut kept, cos, Rational::integer(j));
                }
                let c = self.rmul(coefficient, c);
                let part = self.finish_product(c, kept, trig, pending.clone(), &done);
                acc.add_expr(self, part, Rational::ONE);
            }
            return acc.finish(self);
        }
        let trig_count: u32 = trig.iter().map(|t| t.2).sum();
        if trig_count == 1 {
            let (f, arg, _) = trig[0];
            let atom = self.func_node(f, arg);
            self.insert_factor(&mut kept, atom, Rational::ONE);
        } else if trig_count > 1 {
            pending.push(self.trig_product(&trig));
        }
        let monomial = self.raw_monomial(kept);
        let mut result = self.scale(monomial, coefficient);
        for p in pending {
            result = self.mul(result, p);
        }
        result
    }

    /// Multiplies `base^e` into a sorted factor list with distinct bases.
    fn insert_factor(&mut self, factors: &mut Vec<(ExprId, Rational)>, base: ExprId, e: Rational) {
        if e.is_zero() {
            return;
        }
        match factors.binary_search_by_key(&base, |(b, _)| *b) {
            Ok(k) => {
                let total = self.radd(factors[k].1, e);
                if total.is_zero() {
                    factors.remove(k);
                } else {
                    factors[k].1 = total;
                }
            }
            Err(k) => factors.insert(k, (base, e)),
        }
    }

    /// Interns an already-normalized factor list (sorted, merged, nonzero exponents).
    pub(crate) fn raw_monomial(&mut self, factors: Vec<(ExprId, Rational)>) -> ExprId {
        match factors.as_slice() {
            [] => Store::ONE,
            [(b, e)] if e.is_one() => *b,
            _ => self.intern(Node::Mul(factors.into_boxed_slice())),
        }
    }

    // ----- powers -----

    /// `a ^ e` for a rational exponent. `a⁰ = 1` for every `a`, 0 included,
    /// as `f64::powi(0.0, 0)` computes it.
    pub fn pow(&mut self, a: ExprId, e: Rational) -> ExprId {
        if e.is_zero() {
            return Store::ONE;
        }
        if e.is_one() {
            return a;
        }
        if !self.exponent_in_range(e) {
            return self.intern_power(a, e);
        }
        match self.node(a).clone() {
            Node::Num(c) => self.pow_number(c, e),
            Node::Add(items) => {
                if items.len() == 1 && items[0].0 != Store::ONE {
                    let (t, c) = items[0];
                    if e.is_integer() || !c.is_negative() {
                        let ce = self.pow_number(c, e);
                        let te = self.pow(t, e);
                        return self.mul(ce, te);
                    }
                } else if let Some(n) = e.to_i64().filter(|n| *n > 0) {
                    let terms = expanded_terms(items.len(), n);
                    if terms <= MAX_EXPANDED_TERMS {
                        return self.pow_expand(a, n);
                    }
                    self.record(EngineError::ExpansionTooLarge {
                        exponent: e,
                        sum_terms: items.len(),
                    });
                } else if let Some(n) = e.to_i64().filter(|n| *n < 0)
                    && let Some((c, u, k, l)) = self.as_trig_monomial(a)
                {
                    // (c · sin^k u · cos^l u)^n with the powers as atoms.
                    let ce = self.pow_number(c, e);
                    let (sin, cos) = (self.func_node(Func::Sin, u), self.func_node(Func::Cos, u));
                    let factors = vec![
                        (sin, Rational::integer(k * n)),
                        (cos, Rational::integer(l * n)),
                    ];
                    let factors = factors.into_iter().filter(|f| !f.1.is_zero()).collect();
                    let power = self.product_of_factors(factors);
                    return self.mul(ce, power);
                }
                self.intern_power(a, e)
            }
            Node::Mul(items) => {
                if e.is_integer() || (items.len() == 1 && items[0].1.numer().abs() == 1) {
                    let scaled = items.iter().map(|&(b, f)| (b, self.rmul(f, e))).collect();
                    self.product_of_factors(scaled)
                } else {
                    self.intern_power(a, e)
                }
            }
            _ => self.product_of_factors(vec![(a, e)]),
        }
    }

    fn pow_number(&mut self, c: Rational, e: Rational) -> ExprId {
        if c.is_zero() && e.is_negative() {
            self.record(EngineError::DivisionByZero);
            return Store::ZERO;
        }
        if let Some(v) = c.exact_pow(e) {
            return self.num(v);
        }
        let base = self.num(c);
        if c.is_negative() {
            return self.intern_power(base, e);
        }
        // c^(n + f) = c^n · c^f with 0 < f < 1, so equal powers share one atom.
        let whole = e.numer().div_euclid(e.denom());
        let frac = Rational::new(e.numer().rem_euclid(e.denom()), e.denom()).unwrap_or_default();
        let whole_value = c
            .checked_powi(whole as i64)
            .unwrap_or_else(|| self.overflow());
        let atom = self.intern_power(base, frac);
        self.scale(atom, whole_value)
    }

    /// Is `e` within [`MAX_EXPONENT`]? Records [`EngineError::ExponentTooLarge`] if not.
    fn exponent_in_range(&mut self, e: Rational) -> bool {
        let ok = e.numer().unsigned_abs() <= MAX_EXPONENT as u128 && e.denom() <= MAX_EXPONENT;
        if !ok {
            self.record(EngineError::ExponentTooLarge(e));
        }
        ok
    }

    fn intern_power(&mut self, base: ExprId, e: Rational) -> ExprId {
        self.raw_monomial(vec![(base, e)])
    }

    /// `a^n` for a sum `a` and a non-negative integer `n`, by repeated squaring.
    fn pow_expand(&mut self, a: ExprId, n: i64) -> ExprId {
        let mut result = Store::ONE;
        let mut base = a;
        let mut k = n;
        while k > 0 {
            if k & 1 == 1 {
                result = self.mul(result, base);
            }
            k >>= 1;
            if k > 0 {
                base = self.mul(base, base);
            }
        }
        result
    }

    /// `√a`.
    pub fn sqrt(&mut self, a: ExprId) -> ExprId {
        self.pow(a, Rational::HALF)
    }
}

/// The number of monomials of `(a_1 + … + a_k)^n` when none cancel,
/// `C(n + k − 1, k − 1)`, or `MAX_EXPANDED_TERMS + 1` when it is larger.
fn expanded_terms(k: usize, n: i64) -> usize {
    let n = n.unsigned_abs() as u128;
    let mut count: u128 = 1;
    for i in 1..k as u128 {
        // C(n + i, i) = C(n + i − 1, i − 1) · (n + i) / i, exact at each step.
        count = count.saturating_mul(n.saturating_add(i)) / i;
        if count > MAX_EXPANDED_TERMS as u128 {
            return MAX_EXPANDED_TERMS + 1;
        }
    }
    count as usize
}

/// Accumulates `(term, coefficient)` pairs of a large sum.
#[derive(Default)]
pub(crate) struct TermAccumulator {
    coefficients: FxHashMap<ExprId, Rational>,
}

impl TermAccumulator {
    pub(crate) fn add(&mut self, store: &mut Store, term: ExprId, c: Rational) {
        let slot = self.coefficients.entry(term).or_insert(Rational::ZERO);
        *slot = slot.checked_add(c).unwrap_or_else(|| {
            store.record(EngineError::Overflow);
            Rational::ZERO
        });
    }

    pub(crate) fn add_expr(&mut self, store: &mut Store, e: ExprId, c: Rational) {
        for (t, k) in store.terms(e) {
            let k = store.rmul(k, c);
            self.add(store, t, k);
        }
    }

    pub(crate) fn finish(self, store: &mut Store) -> ExprId {
        let mut terms: Vec<_> = self
            .coefficients
            .into_iter()
            .filter(|(_, c)| !c.is_zero())
            .collect();
        terms.sort_by_key(|(t, _)| *t);
        store.sum_from_sorted(terms)
    }
}
