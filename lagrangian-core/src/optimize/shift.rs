//! Shifting a coordinate by a parameter before factoring a sum.
//!
//! The canonical form expands every product, so a model written in terms of
//! `a = r + l0` (a crush length added to a rest length) reaches the optimizer
//! as a polynomial in `r` and `l0` with binomial cross terms: `m1 (r + l0)²`
//! arrives as `m1 r² + 2 m1 r l0 + m1 l0²`. Substituting `r = a − l0` into
//! the sum and collecting terms recovers the short form; the sum is then
//! factored in `a`, which is computed once as `r + l0`.
//!
//! A shift `x → a − s·c` (coordinate `x`, parameter `c`, `s = ±1`) is tried
//! for every coordinate and parameter of the sum, and the one leaving the
//! fewest terms is kept if it removes any. This happens at every level of
//! the Horner scheme, so a factor's cofactor can shift again (`a → a' + l3`
//! for a spring attached at `r + l0 − l3`).

use super::{Builder, Term, Var};
use crate::expr::SymbolKind;
use crate::rational::Rational;
use rustc_hash::FxHashMap;

/// Shifts of higher degree than this are not tried (binomials grow quickly).
const MAX_DEGREE: u128 = 6;

/// `x = a − sign·c`, as variable indices of the builder.
#[derive(Clone, Copy, Debug)]
struct Shift {
    x: u32,
    c: u32,
    sign: i64,
}

impl Builder<'_> {
    /// `terms` rewritten with the best coordinate shift, or unchanged.
    pub(super) fn shifted(&mut self, terms: Vec<Term>) -> Vec<Term> {
        if terms.len() < 3 {
            return terms;
        }
        let mut best: Option<(Shift, Vec<Term>)> = None;
        let mut keys = Vec::with_capacity(terms.len());
        for (x, c) in self.shift_candidates(&terms) {
            if !may_collect(&terms, x, c, &mut keys) {
                continue;
            }
            for sign in [1, -1] {
                let shift = Shift { x, c, sign };
                let Some(result) = apply(&terms, shift, u32::MAX) else {
                    continue;
                };
                let limit = best.as_ref().map_or(terms.len(), |(_, b)| b.len());
                if result.len() < limit {
                    best = Some((shift, result));
                }
            }
        }
        let Some((shift, _)) = best else {
            return terms;
        };
        // The new variable a = x + sign·c.
        let (x, c) = (
            self.vars[shift.x as usize].base,
            self.vars[shift.c as usize].base,
        );
        let c = if shift.sign < 0 { self.store.neg(c) } else { c };
        let base = self.store.add(x, c);
        let a = self.var(Var {
            base,
            unit: Rational::ONE,
        });
        self.shifted_vars.insert(a);
        apply(&terms, shift, a).unwrap_or(terms)
    }

    /// Pairs (coordinate or shifted coordinate, parameter) of variables
    /// that occur in the sum, the first at most of degree [`MAX_DEGREE`].
    fn shift_candidates(&self, terms: &[Term]) -> Vec<(u32, u32)> {
        let is_parameter = |v: u32| {
            let var = self.vars[v as usize];
            var.unit.is_one()
                && self.store.as_symbol(var.base).is_some_and(|s| {
                    matches!(self.store.symbol_info(s).kind, SymbolKind::Parameter(_))
                })
        };
        let is_shiftable = |v: u32| {
            let var = self.vars[v as usize];
            self.shifted_vars.contains(&v)
                || var.unit.is_one()
                    && self.store.as_symbol(var.base).is_some_and(|s| {
                        matches!(self.store.symbol_info(s).kind, SymbolKind::Coordinate(_))
                    })
        };
        let mut shiftable: Vec<u32> = Vec::new();
        let mut parameters: Vec<u32> = Vec::new();
        for term in terms {
            for &(v, degree) in &term.vars {
                if degree <= MAX_DEGREE && is_shiftable(v) {
                    if !shiftable.contains(&v) {
                        shiftable.push(v);
                    }
                } else if is_parameter(v) && !parameters.contains(&v) {
                    parameters.push(v);
                }
            }
        }
        let mut pairs = Vec::with_capacity(shiftable.len() * parameters.len());
        for &x in &shiftable {
            for &c in &parameters {
                pairs.push((x, c));
            }
        }
        pairs
    }
}

/// Whether a shift of `x` by `c` can leave fewer terms: only if two terms
/// have the same monomial apart from `x` and `c` and the same total degree
/// `D` in `x` and `c`. (A shift maps each such group, a homogeneous
/// polynomial of degree `D` in `x` and `c`, onto a nonzero one in `a` and
/// `c`, and different groups onto different monomials; so without two terms
/// in one group the count cannot drop.) Compares hashes, so a collision only
/// costs a wasted trial, never a missed one.
fn may_collect(terms: &[Term], x: u32, c: u32, keys: &mut Vec<u64>) -> bool {
    use std::hash::Hasher;
    keys.clear();
    for term in terms {
        let mut hasher = rustc_hash::FxHasher::default();
        let mut degree = 0u128;
        for &(v, d) in &term.vars {
            if v == x || v == c {
                degree += d;
            } else {
                hasher.write_u32(v);
                hasher.write_u128(d);
            }
        }
        hasher.write_u128(degree);
        keys.push(hasher.finish());
    }
    keys.sort_unstable();
    keys.windows(2).any(|w| w[0] == w[1])
}

/// `terms` with `x^d` replaced by `(a − sign·c)^d`, expanded, like terms
/// collected (in order of first appearance) and zeros dropped. `None` when a
/// degree is too high or a coefficient overflows.
fn apply(terms: &[Term], shift: Shift, a: u32) -> Option<Vec<Term>> {
    let mut collected: Vec<Term> = Vec::with_capacity(terms.len());
    let mut index: FxHashMap<Vec<(u32, u128)>, usize> = FxHashMap::default();
    let mut push = |vars: Vec<(u32, u128)>, coefficient: Rational| -> Option<()> {
        match index.get(&vars) {
            Some(&k) => {
                collected[k].coefficient = collected[k].coefficient.checked_add(coefficient)?;
            }
            None => {
                index.insert(vars.clone(), collected.len());
                collected.push(Term { coefficient, vars });
            }
        }
        Some(())
    };
    for term in terms {
        let Some(position) = term.vars.iter().position(|&(v, _)| v == shift.x) else {
            push(term.vars.clone(), term.coefficient)?;
            continue;
        };
        let degree = term.vars[position].1;
        if degree > MAX_DEGREE {
            return None;
        }
        let mut rest = term.vars.clone();
        rest.remove(position);
        // (a − s·c)^d = Σ_k C(d, k) a^(d−k) (−s)^k c^k
        let mut binomial: i128 = 1;
        for k in 0..=degree {
            let sign = if shift.sign > 0 && k % 2 == 1 { -1 } else { 1 };
            let coefficient = term
                .coefficient
                .checked_mul(Rational::new(sign * binomial, 1)?)?;
            let mut vars = rest.clone();
            multiply(&mut vars, a, degree - k);
            multiply(&mut vars, shift.c, k);
            push(vars, coefficient)?;
            binomial = binomial * (degree - k) as i128 / (k + 1) as i128;
        }
    }
    collected.retain(|t| !t.coefficient.is_zero());
    Some(collected)
}

/// Multiplies the monomial `vars` (sorted by variable) by `v^degree`.
fn multiply(vars: &mut Vec<(u32, u128)>, v: u32, degree: u128) {
    if degree == 0 {
        return;
    }
    match vars.binary_search_by_key(&v, |&(w, _)| w) {
        Ok(k) => vars[k].1 += degree,
        Err(k) => vars.insert(k, (v, degree)),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn term(coefficient: i128, vars: &[(u32, u128)]) -> Term {
        Term {
            coefficient: Rational::new(coefficient, 1).unwrap(),
            vars: vars.to_vec(),
        }
    }

    fn show(terms: &[Term]) -> Vec<(i128, Vec<(u32, u128)>)> {
        terms
            .iter()
            .map(|t| (t.coefficient.numer(), t.vars.clone()))
            .collect()
    }

    #[test]
    fn a_binomial_square_collapses_to_one_term() {
        // x = 0, c = 1, m = 2, a = 3: m x² + 2 m x c + m c² = m (x + c)² = m a².
        let terms = [
            term(1, &[(0, 2), (2, 1)]),
            term(2, &[(0, 1), (1, 1), (2, 1)]),
            term(1, &[(1, 2), (2, 1)]),
        ];
        let shifted = apply(
            &terms,
            Shift {
                x: 0,
                c: 1,
                sign: 1,
            },
            3,
        )
        .unwrap();
        assert_eq!(show(&shifted), vec![(1, vec![(2, 1), (3, 2)])]);
        // The other sign: x = a + c gives m (a + 2c)², no shorter.
        let other = apply(
            &terms,
            Shift {
                x: 0,
                c: 1,
                sign: -1,
            },
            3,
        )
        .unwrap();
        assert_eq!(other.len(), 3);
    }

    #[test]
    fn shifting_is_an_identity_on_values() {
        // Random-ish polynomial in x, c, y; evaluate before and after with a = x + s c.
        let terms = [
            term(3, &[(0, 3), (2, 1)]),
            term(-5, &[(0, 1), (1, 2)]),
            term(7, &[(1, 1), (2, 2)]),
            term(2, &[(0, 2), (1, 1)]),
        ];
        let eval = |terms: &[Term], values: &[f64]| -> f64 {
            terms
                .iter()
                .map(|t| {
                    t.coefficient.to_f64()
                        * t.vars
                            .iter()
                            .map(|&(v, d)| values[v as usize].powi(d as i32))
                            .product::<f64>()
                })
                .sum()
        };
        let (x, c, y) = (0.7, -1.3, 2.1);
        for sign in [1i64, -1] {
            let shifted = apply(&terms, Shift { x: 0, c: 1, sign }, 3).unwrap();
            let a = x + sign as f64 * c;
            let before = eval(&terms, &[x, c, y, 0.0]);
            let after = eval(&shifted, &[f64::NAN, c, y, a]);
            assert!(
                (before - after).abs() < 1e-12 * before.abs(),
                "{before} vs {after}"
            );
        }
    }
}
