//! Readable forms of canonical expressions, for equation documents and
//! audits (printed by `emit::Printer`).
//!
//! The canonical form is fully expanded; people read factored forms. This
//! pass regroups a sum without changing its value:
//!
//! 1. terms are grouped by their velocity/acceleration product (`θ̇1²`, `ṙ θ̇1`),
//!    the way mechanical equations are usually written;
//! 2. inside a group, the common monomial factor and rational content come out;
//! 3. what is left is written as a perfect square `(a + b)²` when it is one;
//! 4. otherwise terms are collected by the parameter that occurs (linearly)
//!    in most of them, recursively: `m1 (l0 + r)² + m2 (l0 + l1 + r)²`.

use super::{ExprId, Node, Store, SymbolKind};
use crate::rational::Rational;

/// A display tree: the same value as the expression it came from.
#[derive(Clone, Debug, PartialEq)]
pub enum Tree {
    /// A rational number.
    Num(Rational),
    /// A symbol, function or input call, printed by the notation.
    Atom(ExprId),
    /// A power with a rational exponent.
    Pow(Box<Tree>, Rational),
    /// A product; a rational coefficient, if any, comes first.
    Mul(Vec<Tree>),
    /// A sum of `(negated, term)`.
    Add(Vec<(bool, Tree)>),
}

type Monomial = Vec<(ExprId, Rational)>;

/// The display form of `e`.
pub fn pretty(store: &mut Store, e: ExprId) -> Tree {
    let terms = split_terms(store, e);
    if terms.is_empty() {
        return Tree::Num(Rational::ZERO);
    }
    // Group by the velocity/acceleration part of each term.
    let mut groups: Vec<(Monomial, Vec<(Rational, Monomial)>)> = Vec::new();
    for (c, m) in terms {
        let (motion, rest): (Monomial, Monomial) =
            m.into_iter().partition(|(b, _)| store.is_motion_base(*b));
        match groups.iter_mut().find(|(k, _)| *k == motion) {
            Some((_, members)) => members.push((c, rest)),
            None => groups.push((motion, vec![(c, rest)])),
        }
    }
    groups.sort_by_key(|(motion, _)| std::cmp::Reverse(motion_rank(store, motion)));
    let parts: Vec<(bool, Tree)> = groups
        .into_iter()
        .map(|(motion, members)| {
            let (negated, coefficient) = factor(store, members);
            let mut factors = Vec::new();
            match coefficient {
                Tree::Num(c) if c.is_one() && !motion.is_empty() => {}
                Tree::Mul(items) => factors.extend(items),
                other => factors.push(other),
            }
            factors.extend(monomial_trees(&motion));
            (negated, product(factors))
        })
        .collect();
    sum(parts)
}

fn split_terms(store: &Store, e: ExprId) -> Vec<(Rational, Monomial)> {
    store
        .terms(e)
        .into_iter()
        .map(|(t, c)| (c, store.factors(t)))
        .collect()
}

/// Higher-order motion terms first, then input terms, then the rest.
fn motion_rank(store: &Store, motion: &Monomial) -> (u64, u64, Vec<std::cmp::Reverse<ExprId>>) {
    let kinematic: u64 = motion
        .iter()
        .filter(|(b, _)| matches!(store.node(*b), Node::Sym(_)))
        .map(|(_, e)| e.numer().unsigned_abs() as u64)
        .sum();
    let inputs = motion.len() as u64;
    (
        kinematic,
        inputs,
        motion.iter().map(|(b, _)| std::cmp::Reverse(*b)).collect(),
    )
}

fn monomial_trees(m: &Monomial) -> Vec<Tree> {
    m.iter()
        .map(|&(b, e)| {
            if e.is_one() {
                Tree::Atom(b)
            } else {
                Tree::Pow(Box::new(Tree::Atom(b)), e)
            }
        })
        .collect()
}

fn product(mut factors: Vec<Tree>) -> Tree {
    match factors.len() {
        0 => Tree::Num(Rational::ONE),
        1 => factors.remove(0),
        _ => Tree::Mul(factors),
    }
}

fn sum(mut parts: Vec<(bool, Tree)>) -> Tree {
    if parts.len() == 1 && !parts[0].0 {
        return parts.remove(0).1;
    }
    Tree::Add(parts)
}

/// Factors `Σ c_k m_k` for display; returns whether the whole is negated.
fn factor(store: &mut Store, mut terms: Vec<(Rational, Monomial)>) -> (bool, Tree) {
    terms.retain(|(c, _)| !c.is_zero());
    if terms.is_empty() {
        return (false, Tree::Num(Rational::ZERO));
    }
    if terms.len() == 1 {
        let (c, m) = terms.remove(0);
        let mut factors = Vec::new();
        let magnitude = abs(c);
        if !magnitude.is_one() || m.is_empty() {
            factors.push(Tree::Num(magnitude));
        }
        factors.extend(monomial_trees(&m));
        return (c.is_negative(), product(factors));
    }
    // Common monomial factor and rational content.
    let common = common_monomial(&terms);
    let content = content(&terms);
    let negated = terms.iter().filter(|(c, _)| c.is_negative()).count() * 2 > terms.len();
    let sign = if negated {
        Rational::MINUS_ONE
    } else {
        Rational::ONE
    };
    let scale = content.checked_mul(sign).unwrap_or(Rational::ONE);
    let inner: Vec<(Rational, Monomial)> = terms
        .iter()
        .map(|(c, m)| (c.checked_div(scale).unwrap_or(*c), divide(m, &common)))
        .collect();
    let mut factors = Vec::new();
    if !content.is_one() {
        factors.push(Tree::Num(content));
    }
    let body = match perfect_square(store, &inner) {
        Some(root) => Tree::Pow(Box::new(root), Rational::integer(2)),
        None => collect(store, inner),
    };
    factors.push(body);
    factors.extend(monomial_trees(&common));
    (negated, product(factors))
}

/// Collects terms by the atom occurring linearly in most of them, preferring
/// parameters, then functions (sin, cos, …), then coordinates.
fn collect(store: &mut Store, terms: Vec<(Rational, Monomial)>) -> Tree {
    let tier = |store: &Store, b: ExprId| match store.node(b) {
        Node::Sym(s) => match store.symbol_info(*s).kind {
            SymbolKind::Parameter(_) => Some(0),
            SymbolKind::Coordinate(_) | SymbolKind::Time => Some(2),
            _ => None,
        },
        Node::Func(..) => Some(1),
        _ => None,
    };
    let mut counts: Vec<(u8, ExprId, usize)> = Vec::new();
    for (_, m) in &terms {
        for &(b, e) in m {
            if let (true, Some(t)) = (e.is_one(), tier(store, b)) {
                match counts.iter_mut().find(|(_, x, _)| *x == b) {
                    Some((_, _, n)) => *n += 1,
                    None => counts.push((t, b, 1)),
                }
            }
        }
    }
    let best = counts
        .into_iter()
        .filter(|&(_, _, n)| n >= 2)
        .min_by(|a, b| a.0.cmp(&b.0).then(b.2.cmp(&a.2)).then(a.1.cmp(&b.1)));
    let Some((_, atom, n)) = best else {
        return sum(terms.into_iter().map(|(c, m)| leaf(c, &m)).collect());
    };
    if n == terms.len() {
        // A factor common to every term: take it out (and its companions).
        let (negated, tree) = factor(store, terms);
        return if negated {
            Tree::Add(vec![(true, tree)])
        } else {
            tree
        };
    }
    let (with, rest): (Vec<_>, Vec<_>) = terms
        .into_iter()
        .partition(|(_, m)| m.iter().any(|&(b, e)| b == atom && e.is_one()));
    let with: Vec<(Rational, Monomial)> = with
        .into_iter()
        .map(|(c, m)| (c, m.into_iter().filter(|&(b, _)| b != atom).collect()))
        .collect();
    let (negated, grouped) = factor(store, with);
    let mut parts = vec![(negated, product(prepend(Tree::Atom(atom), grouped)))];
    if !rest.is_empty() {
        match collect(store, rest) {
            Tree::Add(items) => parts.extend(items),
            other => parts.push((false, other)),
        }
    }
    sum(parts)
}

/// `atom · tree`, with the coefficient of `tree` kept in front.
fn prepend(atom: Tree, tree: Tree) -> Vec<Tree> {
    match tree {
        Tree::Mul(mut items) => {
            let at = usize::from(matches!(items.first(), Some(Tree::Num(_))));
            items.insert(at, atom);
            items
        }
        Tree::Num(c) if c.is_one() => vec![atom],
        Tree::Num(c) => vec![Tree::Num(c), atom],
        other => vec![atom, other],
    }
}

fn leaf(c: Rational, m: &Monomial) -> (bool, Tree) {
    let mut factors = Vec::new();
    let magnitude = abs(c);
    if !magnitude.is_one() || m.is_empty() {
        factors.push(Tree::Num(magnitude));
    }
    factors.extend(monomial_trees(m));
    (c.is_negative(), product(factors))
}

fn abs(c: Rational) -> Rational {
    if c.is_negative() {
        c.checked_neg().unwrap_or(c)
    } else {
        c
    }
}

/// The factors (with the smallest positive integer exponent) common to all terms.
fn common_monomial(terms: &[(Rational, Monomial)]) -> Monomial {
    let (_, first) = &terms[0];
    first
        .iter()
        .filter_map(|&(b, e)| {
            if !e.is_integer() || e.is_negative() {
                return None;
            }
            let min = terms.iter().try_fold(e, |acc, (_, m)| {
                m.iter()
                    .find(|(x, f)| *x == b && f.is_integer() && !f.is_negative())
                    .map(|(_, f)| acc.min(*f))
            })?;
            Some((b, min))
        })
        .collect()
}

/// The gcd of the coefficients' numerators over the lcm of their denominators.
fn content(terms: &[(Rational, Monomial)]) -> Rational {
    fn gcd(a: i128, b: i128) -> i128 {
        if b == 0 { a.abs() } else { gcd(b, a % b) }
    }
    let (mut num, mut den) = (0i128, 1i128);
    for (c, _) in terms {
        num = gcd(num, c.numer());
        let g = gcd(den, c.denom()).max(1);
        den = match (den / g).checked_mul(c.denom()) {
            Some(d) => d,
            None => return Rational::ONE,
        };
    }
    Rational::new(num.max(1), den).unwrap_or(Rational::ONE)
}

fn divide(m: &Monomial, by: &Monomial) -> Monomial {
    m.iter()
        .filter_map(|&(b, e)| {
            let d = by
                .iter()
                .find(|(x, _)| *x == b)
                .map_or(Rational::ZERO, |(_, f)| *f);
            let left = e.checked_sub(d)?;
            (!left.is_zero()).then_some((b, left))
        })
        .collect()
}

/// `m / by` when it is a monomial with non-negative exponents.
fn exact_divide(m: &Monomial, by: &Monomial) -> Option<Monomial> {
    let present = by
        .iter()
        .all(|(b, e)| m.iter().any(|(x, f)| x == b && f >= e));
    present.then(|| divide(m, by))
}

/// `Q` with `Q² = Σ terms` (computed in the store, so exactly), if there is one.
fn perfect_square(store: &mut Store, terms: &[(Rational, Monomial)]) -> Option<Tree> {
    if terms.len() < 3
        || terms
            .iter()
            .any(|(_, m)| m.iter().any(|(_, e)| !e.is_integer() || e.is_negative()))
    {
        return None;
    }
    let target = build(store, terms);
    let lead = terms.iter().max_by(|a, b| graded_lex(&a.1, &b.1))?;
    let root_c = lead.0.exact_pow(Rational::HALF)?;
    let root_m: Monomial = lead
        .1
        .iter()
        .map(|&(b, e)| (e.numer() % 2 == 0).then(|| (b, Rational::integer((e.numer() / 2) as i64))))
        .collect::<Option<_>>()?;
    let mut root: Vec<(Rational, Monomial)> = vec![(root_c, root_m)];
    for _ in 0..terms.len() {
        let q = build(store, &root);
        let q2 = store.mul(q, q);
        let residual = store.sub(target, q2);
        if residual == Store::ZERO {
            let tree = sum(root.iter().map(|(c, m)| leaf(*c, m)).collect());
            return Some(tree);
        }
        let rest = split_terms(store, residual);
        let next = rest.iter().max_by(|a, b| graded_lex(&a.1, &b.1))?;
        let (c0, m0) = &root[0];
        let coefficient = next.0.checked_div(c0.checked_mul(Rational::integer(2))?)?;
        root.push((coefficient, exact_divide(&next.1, m0)?));
    }
    None
}

/// Graded lexicographic order of monomials (factor lists sorted by atom):
/// higher total degree first, then the higher power of the first atom.
fn graded_lex(a: &Monomial, b: &Monomial) -> std::cmp::Ordering {
    let degree = |m: &Monomial| m.iter().map(|(_, e)| e.numer()).sum::<i128>();
    degree(a).cmp(&degree(b)).then_with(|| {
        for (x, y) in a.iter().zip(b) {
            if x.0 != y.0 {
                // The monomial containing the earlier atom is the larger.
                return y.0.cmp(&x.0);
            }
            if x.1 != y.1 {
                return x.1.cmp(&y.1);
            }
        }
        a.len().cmp(&b.len())
    })
}

fn build(store: &mut Store, terms: &[(Rational, Monomial)]) -> ExprId {
    let items: Vec<(ExprId, Rational)> = terms
        .iter()
        .map(|(c, m)| {
            let t = store.product_of_factors(m.clone());
            (t, *c)
        })
        .collect();
    store.linear_combination(&items)
}

/// The canonical expression a display tree stands for (the inverse of
/// [`pretty`]: `rebuild(pretty(e)) == e` for every expression).
pub fn rebuild(store: &mut Store, tree: &Tree) -> ExprId {
    match tree {
        Tree::Num(c) => store.num(*c),
        Tree::Atom(e) => *e,
        Tree::Pow(base, e) => {
            let b = rebuild(store, base);
            store.pow(b, *e)
        }
        Tree::Mul(items) => {
            let factors: Vec<ExprId> = items.iter().map(|i| rebuild(store, i)).collect();
            store.product(&factors)
        }
        Tree::Add(parts) => {
            let terms: Vec<(ExprId, Rational)> = parts
                .iter()
                .map(|(negated, t)| {
                    (
                        rebuild(store, t),
                        if *negated {
                            Rational::MINUS_ONE
                        } else {
                            Rational::ONE
                        },
                    )
                })
                .collect();
            store.linear_combination(&terms)
        }
    }
}
