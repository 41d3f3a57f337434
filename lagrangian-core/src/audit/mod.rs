//! Auditing hand-derived equations against the derivation.
//!
//! For each equation (and generalized force) of a spec's `hand_derived`
//! section, both sides are expanded canonically and compared:
//!
//! 1. exactly (the same canonical form), or else numerically: the canonical
//!    form is not canonical everywhere (see [`crate::expr`]), so a difference
//!    that vanishes to round-off at random states counts as agreement, and
//!    the report says it was established numerically;
//! 2. under the small-angle approximation: every sine and cosine of
//!    coordinates replaced by its Taylor polynomial of the section's order
//!    (order 1: `sin θ ≈ θ`, `cos θ ≈ 1`), products kept as they are;
//! 3. term by term, grouped by the acceleration, velocity product or input
//!    they multiply: matching terms, missing and extra terms, coefficient and
//!    sign differences;
//! 4. dimensionally, term by term as written;
//! 5. numerically: the relative residual at random states.

mod compare;
mod report;

pub use compare::{Finding, GroupAudit, GroupVerdict, vanishes_numerically};
pub use report::markdown;

use crate::Compiled;
use crate::expr::{ExprId, Func, Node, Store, SymbolKind};
use crate::rational::Rational;
use crate::spec::{Assumed, HandEquation};
use crate::units::Dimension;

/// What an audited expression is.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Part {
    /// `d/dt ∂L/∂q̇ − ∂L/∂q`.
    Equation,
    /// The generalized force `Q` (with `−∂D/∂q̇`).
    GeneralizedForce,
}

/// How an equation compares overall.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Verdict {
    /// The same canonical expression.
    Exact,
    /// Equal, established numerically: the symbolic difference does not
    /// simplify to 0, but vanishes to round-off at random states.
    Numerical,
    /// Equal once the sines and cosines of the coordinates are replaced by
    /// their Taylor polynomials of the section's `small_angle_order`.
    SmallAngle,
    /// Different even under the small-angle approximation.
    Disagrees,
}

/// A term written with the wrong dimension.
#[derive(Clone, Debug, PartialEq)]
pub struct DimensionFinding {
    /// The term (canonical text).
    pub term: String,
    /// The source line, when known.
    pub line: Option<usize>,
    /// The dimension the term has as written.
    pub found: Dimension,
    /// The dimension every term of the equation must have: energy per unit of
    /// its coordinate.
    pub expected: Dimension,
}

/// The audit of one equation or generalized force.
#[derive(Clone, Debug)]
pub struct EquationAudit {
    /// Whether this is an equation or a generalized force.
    pub part: Part,
    /// The coordinate the equation or force belongs to.
    pub coordinate: String,
    /// How the two sides compare overall.
    pub verdict: Verdict,
    /// The terms of both sides, grouped by what they multiply.
    pub groups: Vec<GroupAudit>,
    /// Terms of the hand side written with the wrong dimension.
    pub dimension_findings: Vec<DimensionFinding>,
    /// Largest `|derived − hand| / Σ|terms|` over the sampled states.
    pub max_residual: f64,
    /// Median of the same.
    pub median_residual: f64,
}

/// The audit of a spec's `hand_derived` section.
#[derive(Clone, Debug)]
pub struct AuditReport {
    /// The model's name.
    pub model: String,
    /// The `hand_derived` section's doc lines.
    pub doc: Vec<String>,
    /// What the hand-derived equations are, in words ([`crate::spec::Convention::description`]).
    pub convention: String,
    /// Order of the Taylor polynomials of the small-angle comparison.
    pub small_angle_order: u32,
    /// `(name, value)` of each assumption, as text.
    pub assumptions: Vec<(String, String)>,
    /// Every equation, then every generalized force, in the section's order.
    pub audits: Vec<EquationAudit>,
    /// Number of random states of the residuals.
    pub states: usize,
    /// The model's constraints `g`, `G` and `γ` as a Markdown section
    /// (empty without constraints): the audited equations are those without
    /// the constraint forces `Gᵀλ`, which the solve adds.
    pub constraints: String,
}

impl AuditReport {
    /// True when an equation or force disagrees beyond the small-angle approximation.
    pub fn disagrees(&self) -> bool {
        self.audits.iter().any(|a| a.verdict == Verdict::Disagrees)
    }

    /// The audit of the equation (or generalized force) of `coordinate`, if
    /// the section gives one.
    pub fn audit(&self, part: Part, coordinate: &str) -> Option<&EquationAudit> {
        self.audits
            .iter()
            .find(|a| a.part == part && a.coordinate == coordinate)
    }
}

/// Audits the hand-derived equations of a compiled spec (`None` without them).
pub fn audit(compiled: &mut Compiled) -> Option<AuditReport> {
    crate::depth::with_large_stack(|| audit_deep(compiled))
}

fn audit_deep(compiled: &mut Compiled) -> Option<AuditReport> {
    let hand = compiled.model.hand_derived.clone()?;
    let constraints = crate::emit::render_constraints(compiled);
    // A model too large for the canonical form has no audit to give.
    let d = compiled.canonical().ok()?.clone();
    let n = d.dimension;
    let model = &mut compiled.model;
    let coordinates = model.coordinate_symbols();
    let dissipation = d.dissipation;
    // Derived counterparts in the section's convention.
    let mut derived_equations = Vec::with_capacity(n);
    let mut derived_forces = Vec::with_capacity(n);
    for i in 0..n {
        let mut terms = Vec::with_capacity(n + 3);
        for (j, c) in coordinates.iter().enumerate() {
            terms.push(model.store.mul(d.mass(i, j), c.acceleration_expr));
        }
        let damping = model.store.diff(dissipation, coordinates[i].velocity);
        // d/dt ∂L/∂q̇ − ∂L/∂q = M q̈ − (f + ∂D/∂q̇ − Q).
        let conservative = model.store.sum(&[d.forcing[i], damping]);
        let conservative = model.store.sub(conservative, d.generalized_forces[i]);
        terms.push(model.store.neg(conservative));
        derived_equations.push(model.store.sum(&terms));
        derived_forces.push(model.store.sub(d.generalized_forces[i], damping));
    }
    let assume = |store: &mut Store, e: ExprId| apply_assumptions(store, e, &hand.assumptions);
    let derived_equations: Vec<ExprId> = derived_equations
        .into_iter()
        .map(|e| assume(&mut model.store, e))
        .collect();
    let derived_forces: Vec<ExprId> = derived_forces
        .into_iter()
        .map(|e| assume(&mut model.store, e))
        .collect();

    let names: Vec<String> = model.coordinates.iter().map(|c| c.name.clone()).collect();
    let states = compare::sample_states(model, 50);
    let mut audits = Vec::new();
    for (part, list, derived) in [
        (Part::Equation, &hand.equations, &derived_equations),
        (Part::GeneralizedForce, &hand.forces, &derived_forces),
    ] {
        for equation in list.iter() {
            let expected = model.coordinate_dimensions[equation.coordinate]
                .and_then(|q| Dimension::ENERGY.checked_div(q));
            let derived = derived[equation.coordinate];
            audits.push(audit_one(
                model,
                part,
                &names,
                equation,
                derived,
                expected,
                hand.small_angle_order,
                &states,
            ));
        }
    }
    let assumptions = hand
        .assumptions
        .iter()
        .map(|(assumed, value)| {
            let name = match assumed {
                Assumed::Input(i) => model.inputs[*i].name.clone(),
                Assumed::Parameter(s) => model.store.symbol_info(*s).name.clone(),
            };
            (name, model.store.to_text(*value))
        })
        .collect();
    Some(AuditReport {
        model: model.name.clone(),
        doc: hand.doc.clone(),
        convention: hand.convention.description().to_string(),
        small_angle_order: hand.small_angle_order,
        assumptions,
        audits,
        constraints,
        states: states.len(),
    })
}

#[allow(clippy::too_many_arguments)]
fn audit_one(
    model: &mut crate::Model,
    part: Part,
    names: &[String],
    equation: &HandEquation,
    derived: ExprId,
    expected: Option<Dimension>,
    order: u32,
    states: &[Vec<f64>],
) -> EquationAudit {
    let hand = equation.value;
    let verdict = if derived == hand {
        Verdict::Exact
    } else if compare::vanishes_numerically(&model.store, derived, hand) {
        Verdict::Numerical
    } else {
        let sd = small_angle(&mut model.store, derived, order);
        let sh = small_angle(&mut model.store, hand, order);
        if sd == sh {
            Verdict::SmallAngle
        } else {
            Verdict::Disagrees
        }
    };
    let groups = compare::groups(&mut model.store, derived, hand, order);
    let dimension_findings = match expected {
        None => Vec::new(),
        Some(expected) => equation
            .terms
            .iter()
            .filter_map(|t| {
                let found = t.dimension?;
                (found != expected).then(|| DimensionFinding {
                    term: model.store.to_text(t.value),
                    line: Some(t.span.start.start().line).filter(|l| *l > 0),
                    found,
                    expected,
                })
            })
            .collect(),
    };
    let (max_residual, median_residual) = compare::residuals(model, derived, hand, states);
    EquationAudit {
        part,
        coordinate: names[equation.coordinate].clone(),
        verdict,
        groups,
        dimension_findings,
        max_residual,
        median_residual,
    }
}

fn apply_assumptions(store: &mut Store, e: ExprId, assumptions: &[(Assumed, ExprId)]) -> ExprId {
    if assumptions.is_empty() {
        return e;
    }
    store.replace_atoms(e, &mut |store, atom| {
        assumptions
            .iter()
            .find_map(|&(assumed, value)| match (assumed, store.node(atom)) {
                (Assumed::Input(k), Node::Input(index, _)) if *index as usize == k => Some(value),
                (Assumed::Parameter(s), Node::Sym(t)) if *t == s => Some(value),
                _ => None,
            })
    })
}

/// Sines and cosines of coordinates replaced by Taylor polynomials of `order`.
pub fn small_angle(store: &mut Store, e: ExprId, order: u32) -> ExprId {
    store.replace_atoms(e, &mut |store, atom| {
        let (f, u) = store.as_func(atom)?;
        if !matches!(f, Func::Sin | Func::Cos) {
            return None;
        }
        let of_coordinates = store
            .free_symbols(u)
            .iter()
            .all(|s| matches!(store.symbol_info(*s).kind, SymbolKind::Coordinate(_)));
        if !of_coordinates {
            return None;
        }
        let start = if f == Func::Sin { 1 } else { 0 };
        let mut terms = Vec::new();
        let mut k = start;
        while k <= order {
            let sign = if (k / 2) % 2 == 0 { 1 } else { -1 };
            let factorial: i64 = (1..=k as i64).product();
            let power = store.pow(u, Rational::integer(k as i64));
            let coefficient = Rational::new(sign, factorial as i128).unwrap_or_default();
            terms.push((power, coefficient));
            k += 2;
        }
        Some(store.linear_combination(&terms))
    })
}
