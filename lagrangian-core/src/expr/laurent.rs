//! Negative powers of sines and cosines, combined with the sines and cosines
//! of multiples of the same argument, so that `sin²u / sin u` is `sin u` and
//! `tan u · cos²u` is `sin u · cos u`.
//!
//! Positive powers arrive linearized (`sin²u = ½ − ½cos 2u`), so a negative
//! power `sin⁻ᵏu` cannot simply merge exponents with them. In a monomial with
//! such a power, the sines and cosines of `m·u` are rewritten as polynomials
//! in `s = sin u` and `c = cos u` and multiplied out, and each resulting
//! `s^i c^j` is normalized with `s² + c² = 1` into one of
//!
//! * `i, j ≥ 0`: linearized again, as any product of sines and cosines;
//! * `i < 0`, `j ∈ {0, 1}`: `s^i`, times `c` when `j = 1`;
//! * `j < 0`, `i ∈ {0, 1}`: `c^j`, times `s` when `i = 1`.
//!
//! That form is unique for expressions in one argument `u` (the terms with
//! poles at `s = 0` and at `c = 0` cannot cancel each other or the regular
//! part). Sines and cosines of other arguments in the same monomial
//! (`sin(u − v) / sin u`) are left as they are, and there the form is not
//! canonical.

use super::{ExprId, Func, Store};
use crate::rational::Rational;
use rustc_hash::FxHashMap;

/// A Laurent polynomial in `s = sin u`, `c = cos u`: `(i, j) ↦` the
/// coefficient of `s^i c^j`.
type Laurent = FxHashMap<(i64, i64), Rational>;

/// `sin(m u)` and `cos(m u)` are expanded for `m · power ≤` this; higher
/// multiples stay atoms (correct, but then the form is not canonical).
const MAX_EXPANDED_DEGREE: i64 = 64;

/// A sum is recognized as `c · sin^k u · cos^l u` up to this `k + l`.
const MAX_RECOGNIZED_DEGREE: i64 = 8;

/// `sin^i u · cos^j u` terms of a normal form: `((i, j), coefficient)`.
type TrigTerms = Vec<((i64, i64), Rational)>;

impl Store {
    /// Takes out of a product the negative powers of `sin u`, `cos u` (from
    /// `kept`) for the first such `u` not in `done`, with the non-negative
    /// powers of sines and cosines of multiples of `u` (from `trig`), and
    /// returns `u` and their product in normal form (module documentation),
    /// as `((i, j), coefficient)` of `sin^i u · cos^j u`, sorted.
    pub(super) fn negative_trig_group(
        &mut self,
        kept: &mut Vec<(ExprId, Rational)>,
        trig: &mut Vec<(Func, ExprId, u32)>,
        done: &[ExprId],
    ) -> Option<(ExprId, TrigTerms)> {
        let u = kept.iter().find_map(|&(base, e)| {
            let (f, u) = self.as_func(base)?;
            let negative = matches!(f, Func::Sin | Func::Cos) && e.is_integer() && e.is_negative();
            (negative && !done.contains(&u)).then_some(u)
        })?;
        let mut product: Laurent = FxHashMap::default();
        product.insert((0, 0), Rational::ONE);
        let mut k = 0;
        while k < kept.len() {
            let (base, e) = kept[k];
            let power = match (self.as_func(base), e.to_i64()) {
                (Some((Func::Sin, v)), Some(n)) if v == u => (n, 0),
                (Some((Func::Cos, v)), Some(n)) if v == u => (0, n),
                _ => {
                    k += 1;
                    continue;
                }
            };
            product = self.laurent_mul(&product, &[(power, Rational::ONE)]);
            kept.remove(k);
        }
        let mut k = 0;
        while k < trig.len() {
            let (f, v, n) = trig[k];
            let expansion = self
                .multiple_of(v, u)
                .filter(|m| m * i64::from(n) <= MAX_EXPANDED_DEGREE)
                .and_then(|m| multiple_angle(f, m));
            let Some(expansion) = expansion else {
                k += 1;
                continue;
            };
            for _ in 0..n {
                product = self.laurent_mul(&product, &expansion);
            }
            trig.remove(k);
        }
        Some((u, self.laurent_normal_form(product)))
    }

    /// `(c, u, k, l)` when the sum `a` is the linearized form of
    /// `c · sin^k u · cos^l u` with `k + l ≤ MAX_RECOGNIZED_DEGREE`, so that
    /// `x / pow(sin(u), 2)` becomes `x · sin⁻²u` rather than `x · (½ − ½cos 2u)⁻¹`.
    pub(super) fn as_trig_monomial(&mut self, a: ExprId) -> Option<(Rational, ExprId, i64, i64)> {
        let terms = self.terms(a);
        // The argument of the highest frequency, M·u for M = k + l.
        let mut top: Option<(ExprId, Rational)> = None;
        for &(t, _) in &terms {
            if t == Store::ONE {
                continue;
            }
            let (Func::Sin | Func::Cos, v) = self.as_func(t)? else {
                return None;
            };
            let size = self.terms(v).first()?.1;
            if top.is_none_or(|(_, s)| size > s) {
                top = Some((v, size));
            }
        }
        let (top, _) = top?;
        let has_constant = terms.iter().any(|(t, _)| *t == Store::ONE);
        for m in 1..=MAX_RECOGNIZED_DEGREE {
            // With M odd every frequency is odd: no constant term.
            if has_constant && m % 2 == 1 {
                continue;
            }
            let u = self.scale(top, Rational::new(1, i128::from(m))?);
            for k in 0..=m {
                let candidate =
                    self.trig_product(&[(Func::Sin, u, k as u32), (Func::Cos, u, (m - k) as u32)]);
                let c = self.terms(candidate);
                if c.len() != terms.len() || c.iter().zip(&terms).any(|(x, y)| x.0 != y.0) {
                    continue;
                }
                let ratio = terms[0].1.checked_div(c[0].1)?;
                if c.iter()
                    .zip(&terms)
                    .all(|(x, y)| x.1.checked_mul(ratio) == Some(y.1))
                {
                    return Some((ratio, u, k, m - k));
                }
            }
        }
        None
    }

    /// `m` when `v = m·u` for an integer `1 ≤ m ≤ MAX_EXPANDED_DEGREE`.
    fn multiple_of(&self, v: ExprId, u: ExprId) -> Option<i64> {
        if v == u {
            return Some(1);
        }
        let (tv, tu) = (self.terms(v), self.terms(u));
        if tv.len() != tu.len() || tv.is_empty() {
            return None;
        }
        let m = tv[0].1.checked_div(tu[0].1)?;
        let scaled = tv
            .iter()
            .zip(&tu)
            .all(|(a, b)| a.0 == b.0 && b.1.checked_mul(m) == Some(a.1));
        let m = m
            .to_i64()
            .filter(|m| (1..=MAX_EXPANDED_DEGREE).contains(m))?;
        scaled.then_some(m)
    }

    /// `a · b`, with checked coefficients.
    fn laurent_mul(&mut self, a: &Laurent, b: &[((i64, i64), Rational)]) -> Laurent {
        let mut out = Laurent::default();
        for (&(i, j), &x) in a {
            for &((k, l), y) in b {
                let c = self.rmul(x, y);
                let slot = out.entry((i + k, j + l)).or_insert(Rational::ZERO);
                *slot = self.radd(*slot, c);
            }
        }
        out.retain(|_, c| !c.is_zero());
        out
    }

    /// Rewrites `p` with `s² + c² = 1` into the normal form of the module
    /// documentation, one step per round, merging like terms between rounds.
    fn laurent_normal_form(&mut self, mut p: Laurent) -> Vec<((i64, i64), Rational)> {
        loop {
            let mut next = Laurent::default();
            let mut changed = false;
            for ((i, j), c) in p {
                let minus = self.rmul(c, Rational::MINUS_ONE);
                let parts: Vec<((i64, i64), Rational)> = match (i, j) {
                    // s^i c^j = s^i c^(j−2) − s^(i+2) c^(j−2)
                    (..0, 2..) => vec![((i, j - 2), c), ((i + 2, j - 2), minus)],
                    // s^i c^j = s^(i−2) c^j − s^(i−2) c^(j+2)
                    (2.., ..0) => vec![((i - 2, j), c), ((i - 2, j + 2), minus)],
                    // s^i c^j = s^(i+2) c^j + s^i c^(j+2)
                    (..0, ..0) => vec![((i + 2, j), c), ((i, j + 2), c)],
                    _ => vec![((i, j), c)],
                };
                changed |= parts.len() > 1;
                for (key, c) in parts {
                    let slot = next.entry(key).or_insert(Rational::ZERO);
                    *slot = self.radd(*slot, c);
                }
            }
            next.retain(|_, c| !c.is_zero());
            p = next;
            if !changed {
                let mut terms: Vec<_> = p.into_iter().collect();
                terms.sort_by_key(|(key, _)| *key);
                return terms;
            }
        }
    }
}

/// `sin(m u)` or `cos(m u)` as a polynomial in `s`, `c`: the imaginary or
/// real part of `(c + i s)^m = Σ_k C(m, k) c^(m−k) (i s)^k`. `None` only if
/// a binomial coefficient left `i64`, which `m ≤ MAX_EXPANDED_DEGREE` rules out.
fn multiple_angle(f: Func, m: i64) -> Option<Vec<((i64, i64), Rational)>> {
    let mut out = Vec::new();
    let mut binomial: i128 = 1; // C(m, k)
    for k in 0..=m {
        let wanted = match f {
            Func::Sin => k % 2 == 1,
            _ => k % 2 == 0,
        };
        if wanted {
            // i^k: 1, i, −1, −i.
            let sign = if (k / 2) % 2 == 0 { 1 } else { -1 };
            let value = Rational::integer(i64::try_from(sign * binomial).ok()?);
            out.push(((k, m - k), value));
        }
        binomial = binomial.checked_mul(i128::from(m - k))? / i128::from(k + 1);
    }
    Some(out)
}
