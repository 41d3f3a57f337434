//! Term-by-term comparison of a derived and a hand-derived expression.

use super::small_angle;
use crate::emit::{Notation, Printer};
use crate::expr::{Evaluator, ExprId, Store, SymbolKind};
use crate::random::Lcg;
use crate::rational::Rational;
use rustc_hash::FxHashMap;

/// How one group of terms compares.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum GroupVerdict {
    /// Identical.
    Match,
    /// Equal, but established numerically: the difference does not simplify
    /// to 0 in the canonical form, yet vanishes to round-off at random states.
    NumericalMatch,
    /// Identical after the small-angle approximation.
    SmallAngle,
    /// Both sides have terms here, and they differ.
    Differs,
    /// The derivation has terms here, the hand derivation none.
    MissingByHand,
    /// The hand derivation has terms here, the derivation none.
    ExtraByHand,
}

/// A difference between the two sides after the small-angle approximation.
/// Terms are combined by kind, and the combination printed factored.
#[derive(Clone, Debug, PartialEq)]
pub enum Finding {
    /// Terms of the derivation that the hand derivation lacks.
    Missing {
        /// The missing terms combined, in the store.
        expr: ExprId,
        /// The same, as text.
        term: String,
        /// The same, as LaTeX.
        latex: String,
    },
    /// Terms of the hand derivation that the derivation lacks.
    Extra {
        /// The extra terms combined, in the store.
        expr: ExprId,
        /// The same, as text.
        term: String,
        /// The same, as LaTeX.
        latex: String,
    },
    /// Terms of the derivation that the hand derivation has with the opposite sign.
    Sign {
        /// The derivation's terms of opposite sign, combined, in the store.
        expr: ExprId,
        /// The same, as text.
        term: String,
        /// The same, as LaTeX.
        latex: String,
    },
    /// Terms of the derivation that the hand derivation has `ratio` times.
    Scaled {
        /// The derivation's terms scaled by `ratio` by hand, combined, in the store.
        expr: ExprId,
        /// The same, as text.
        term: String,
        /// The same, as LaTeX.
        latex: String,
        /// The hand coefficient over the derived one.
        ratio: Rational,
    },
}

impl Finding {
    /// The terms concerned (derived side, except for `Extra`), in the store.
    pub fn expr(&self) -> ExprId {
        match self {
            Finding::Missing { expr, .. }
            | Finding::Extra { expr, .. }
            | Finding::Sign { expr, .. }
            | Finding::Scaled { expr, .. } => *expr,
        }
    }

    /// The terms concerned (derived side, except for `Extra`), as text.
    pub fn term(&self) -> &str {
        match self {
            Finding::Missing { term, .. }
            | Finding::Extra { term, .. }
            | Finding::Sign { term, .. }
            | Finding::Scaled { term, .. } => term,
        }
    }
}

/// The terms multiplying one acceleration, velocity product or input.
#[derive(Clone, Debug)]
pub struct GroupAudit {
    /// What the terms multiply (a monomial of velocities, accelerations and inputs).
    pub motion_expr: ExprId,
    /// The derivation's coefficient (0 when it has none here), in the store.
    pub derived_expr: ExprId,
    /// The hand derivation's coefficient (0 when it has none here), in the store.
    pub hand_expr: ExprId,
    /// What the terms multiply, e.g. `dot(r)*dot(theta1)`; `1` for none.
    pub motion: String,
    /// What the terms multiply, as LaTeX.
    pub motion_latex: String,
    /// The derived coefficient, as text.
    pub derived: String,
    /// The derived coefficient, as LaTeX.
    pub derived_latex: String,
    /// The hand coefficient, as text.
    pub hand: String,
    /// The hand coefficient, as LaTeX.
    pub hand_latex: String,
    /// How the two coefficients compare.
    pub verdict: GroupVerdict,
    /// The term-level differences, when the group does not match even under
    /// the small-angle approximation.
    pub findings: Vec<Finding>,
}

type Groups = Vec<(ExprId, ExprId)>;

/// `(motion monomial, coefficient)` pairs of `e`.
fn split(store: &mut Store, e: ExprId) -> Groups {
    let mut map: FxHashMap<ExprId, Vec<(ExprId, Rational)>> = FxHashMap::default();
    let mut order = Vec::new();
    for (t, c) in store.terms(e) {
        let (motion, rest): (Vec<_>, Vec<_>) = store
            .factors(t)
            .into_iter()
            .partition(|(b, _)| store.is_motion_base(*b));
        let key = store.raw_monomial(motion);
        let coefficient = store.raw_monomial(rest);
        if !map.contains_key(&key) {
            order.push(key);
        }
        map.entry(key).or_default().push((coefficient, c));
    }
    order
        .into_iter()
        .map(|key| {
            let items = map.remove(&key).unwrap_or_default();
            (key, store.linear_combination(&items))
        })
        .collect()
}

fn text(store: &mut Store, e: ExprId, notation: Notation) -> String {
    Printer { store, notation }.expr(e)
}

/// The groups of both sides, in the order of the derivation then the hand's extras.
pub fn groups(store: &mut Store, derived: ExprId, hand: ExprId, order: u32) -> Vec<GroupAudit> {
    let d = split(store, derived);
    let h = split(store, hand);
    let mut keys: Vec<ExprId> = d.iter().map(|(k, _)| *k).collect();
    keys.extend(
        h.iter()
            .map(|(k, _)| *k)
            .filter(|k| !d.iter().any(|(x, _)| x == k)),
    );
    let find = |list: &Groups, k: ExprId| {
        list.iter()
            .find(|(x, _)| *x == k)
            .map_or(Store::ZERO, |(_, c)| *c)
    };
    keys.into_iter()
        .map(|key| {
            let (cd, ch) = (find(&d, key), find(&h, key));
            let (sd, sh) = (small_angle(store, cd, order), small_angle(store, ch, order));
            let verdict = if cd == ch {
                GroupVerdict::Match
            } else if vanishes_numerically(store, cd, ch) {
                GroupVerdict::NumericalMatch
            } else if sd == sh {
                GroupVerdict::SmallAngle
            } else if ch == Store::ZERO {
                GroupVerdict::MissingByHand
            } else if cd == Store::ZERO {
                GroupVerdict::ExtraByHand
            } else {
                GroupVerdict::Differs
            };
            let findings = match verdict {
                GroupVerdict::Match | GroupVerdict::NumericalMatch | GroupVerdict::SmallAngle => {
                    Vec::new()
                }
                _ => term_findings(store, sd, sh),
            };
            GroupAudit {
                motion_expr: key,
                derived_expr: cd,
                hand_expr: ch,
                motion: text(store, key, Notation::Text),
                motion_latex: text(store, key, Notation::Latex),
                derived: text(store, cd, Notation::Text),
                derived_latex: text(store, cd, Notation::Latex),
                hand: text(store, ch, Notation::Text),
                hand_latex: text(store, ch, Notation::Latex),
                verdict,
                findings,
            }
        })
        .collect()
}

/// Term-level differences between two (small-angle) coefficients, combined
/// by kind: missing, extra, opposite sign, and each coefficient ratio.
fn term_findings(store: &mut Store, derived: ExprId, hand: ExprId) -> Vec<Finding> {
    let d = store.terms(derived);
    let h = store.terms(hand);
    let mut missing = Vec::new();
    let mut scaled: Vec<(Rational, Vec<(ExprId, Rational)>)> = Vec::new();
    for &(t, cd) in &d {
        match h.iter().find(|(x, _)| *x == t) {
            None => missing.push((t, cd)),
            Some(&(_, ch)) if ch == cd => {}
            Some(&(_, ch)) => {
                let ratio = ch.checked_div(cd).unwrap_or_default();
                match scaled.iter_mut().find(|(r, _)| *r == ratio) {
                    Some((_, list)) => list.push((t, cd)),
                    None => scaled.push((ratio, vec![(t, cd)])),
                }
            }
        }
    }
    let extra: Vec<(ExprId, Rational)> = h
        .iter()
        .filter(|(t, _)| !d.iter().any(|(x, _)| x == t))
        .copied()
        .collect();
    let render = |store: &mut Store, terms: &[(ExprId, Rational)]| {
        let e = store.linear_combination(terms);
        (
            e,
            text(store, e, Notation::Text),
            text(store, e, Notation::Latex),
        )
    };
    let mut findings = Vec::new();
    if !missing.is_empty() {
        let (expr, term, latex) = render(store, &missing);
        findings.push(Finding::Missing { expr, term, latex });
    }
    for (ratio, terms) in scaled {
        let (expr, term, latex) = render(store, &terms);
        findings.push(if ratio == Rational::MINUS_ONE {
            Finding::Sign { expr, term, latex }
        } else {
            Finding::Scaled {
                expr,
                term,
                latex,
                ratio,
            }
        });
    }
    if !extra.is_empty() {
        let (expr, term, latex) = render(store, &extra);
        findings.push(Finding::Extra { expr, term, latex });
    }
    findings
}

/// Random symbol values: coordinates within ±0.1 (the small-angle regime),
/// velocities within ±1, accelerations within ±10, default parameters.
pub fn sample_states(model: &crate::Model, count: usize) -> Vec<Vec<f64>> {
    let mut random = Lcg::new(0x5eed);
    let mut uniform = |low, high| random.uniform(low, high);
    (0..count)
        .map(|_| {
            model
                .store
                .symbols()
                .iter()
                .map(|s| match s.kind {
                    SymbolKind::Coordinate(_) => uniform(-0.1, 0.1),
                    SymbolKind::Velocity(_) => uniform(-1.0, 1.0),
                    SymbolKind::Acceleration(_) => uniform(-10.0, 10.0),
                    SymbolKind::Parameter(i) => model.parameters[i].default,
                    SymbolKind::Time => uniform(0.0, 0.1),
                    SymbolKind::Pi => std::f64::consts::PI,
                    SymbolKind::InputArgument { .. } => 0.0,
                })
                .collect()
        })
        .collect()
}

/// Random states for testing an identity: coordinates within ±3 (large
/// angles too), velocities ±2, accelerations ±10, time in [0, 10] and every
/// parameter in [0.5, 2] (an identity holds for all values, and defaults of
/// 0 would hide the terms they multiply).
fn identity_states(store: &Store, count: usize) -> Vec<Vec<f64>> {
    let mut random = Lcg::new(0x1de7);
    let mut uniform = |low, high| random.uniform(low, high);
    (0..count)
        .map(|_| {
            store
                .symbols()
                .iter()
                .map(|s| match s.kind {
                    SymbolKind::Coordinate(_) => uniform(-3.0, 3.0),
                    SymbolKind::Velocity(_) => uniform(-2.0, 2.0),
                    SymbolKind::Acceleration(_) => uniform(-10.0, 10.0),
                    SymbolKind::Parameter(_) => uniform(0.5, 2.0),
                    SymbolKind::Time => uniform(0.0, 10.0),
                    SymbolKind::Pi => std::f64::consts::PI,
                    SymbolKind::InputArgument { .. } => 0.0,
                })
                .collect()
        })
        .collect()
}

/// Relative size of round-off below which a difference counts as zero.
const ROUND_OFF: f64 = 1e-10;

/// Is `a = b` although the canonical forms differ (the form is not canonical
/// everywhere, see [`crate::expr`])? True when `|a − b|` stays within
/// round-off of `Σ|terms of a| + Σ|terms of b|` at 16 random states, of
/// which at least 8 are regular (states where either side is not finite, at
/// a singularity, are skipped).
pub fn vanishes_numerically(store: &Store, a: ExprId, b: ExprId) -> bool {
    let terms: Vec<(ExprId, Rational)> = store.terms(a).into_iter().chain(store.terms(b)).collect();
    let mut regular = 0;
    for state in identity_states(store, 16) {
        let mut ev = Evaluator::new(store, state, &inputs);
        let (va, vb) = (ev.eval(a), ev.eval(b));
        let scale: f64 = terms
            .iter()
            .map(|&(t, c)| (c.to_f64() * ev.eval(t)).abs())
            .sum();
        if !(va.is_finite() && vb.is_finite() && scale.is_finite()) {
            continue;
        }
        if (va - vb).abs() > ROUND_OFF * scale {
            return false;
        }
        regular += 1;
    }
    regular >= 8
}

/// Input values for the residuals: smooth functions of the arguments.
fn inputs(index: usize, args: &[f64]) -> f64 {
    1.0e3 * (1.0 + index as f64) * (1.0 + args.iter().map(|a| (3.0 * a).sin()).sum::<f64>())
}

/// `(max, median)` of `|derived − hand| / (Σ|derived terms| + Σ|hand terms|)`.
pub fn residuals(
    model: &crate::Model,
    derived: ExprId,
    hand: ExprId,
    states: &[Vec<f64>],
) -> (f64, f64) {
    let store = &model.store;
    let terms: Vec<(ExprId, Rational)> = store
        .terms(derived)
        .into_iter()
        .chain(store.terms(hand))
        .collect();
    let mut values: Vec<f64> = states
        .iter()
        .map(|state| {
            let mut ev = Evaluator::new(store, state.clone(), &inputs);
            let scale: f64 = terms
                .iter()
                .map(|&(t, c)| (c.to_f64() * ev.eval(t)).abs())
                .sum();
            let difference = (ev.eval(derived) - ev.eval(hand)).abs();
            if scale > 0.0 {
                difference / scale
            } else {
                difference
            }
        })
        .collect();
    values.sort_by(f64::total_cmp);
    let max = values.last().copied().unwrap_or(0.0);
    let median = values.get(values.len() / 2).copied().unwrap_or(0.0);
    (max, median)
}
