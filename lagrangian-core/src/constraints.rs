//! The terms of holonomic constraints `g(q, t) = 0` that the constrained
//! equations of motion need.
//!
//! With `m` constraints on `n` coordinates, `G = ∂g/∂q` (`m × n`) and
//! `g_t = ∂g/∂t`, the constraint holds along a motion when
//! `ġ = G q̇ + g_t = 0` and `g̈ = G q̈ − γ = 0`, where
//!
//! ```text
//! γ = −(∂ġ/∂q) q̇ − ∂ġ/∂t = −(∂(G q̇)/∂q) q̇ − 2 (∂G/∂t) q̇ − ∂²g/∂t²
//! ```
//!
//! (`∂g_t/∂q = ∂G/∂t`). The runtime solves
//! `[[M, Gᵀ], [G, 0]] [q̈; −λ] = [f; γ]`, that is `M q̈ = f + Gᵀλ`,
//! `G q̈ = γ`: `λ` is the multiplier whose generalized force `Gᵀλ` is added to
//! `f`.

use crate::diagnostic::SpecErrors;
use crate::expr::ExprId;
use crate::spec::{Constraint, Model, engine_diagnostic};

/// `g`, `g_t`, `G` and `γ` of a model's constraints (all empty without
/// constraints), in the order of [`lagrangian_runtime::layout::ConstraintLayout`].
#[derive(Clone, Debug, Default)]
pub struct ConstraintTerms {
    /// `g_k(q, t)`, the residual of each constraint.
    pub residual: Vec<ExprId>,
    /// `∂g_k/∂t`.
    pub time_rate: Vec<ExprId>,
    /// `G_kj = ∂g_k/∂q_j`, row-major `m × n`.
    pub jacobian: Vec<ExprId>,
    /// `γ_k`, with `G q̈ = γ` along a motion that keeps the constraints.
    pub acceleration: Vec<ExprId>,
}

impl ConstraintTerms {
    /// Every term, in output order: `g`, `g_t`, `G`, `γ`.
    pub fn outputs(&self) -> impl Iterator<Item = ExprId> + '_ {
        (self.residual.iter())
            .chain(&self.time_rate)
            .chain(&self.jacobian)
            .chain(&self.acceleration)
            .copied()
    }
}

/// Derives the terms of every constraint of `model`.
pub fn derive(model: &mut Model) -> Result<ConstraintTerms, SpecErrors> {
    let mut terms = ConstraintTerms::default();
    let constraints = std::mem::take(&mut model.constraints);
    let result = constraints
        .iter()
        .try_for_each(|c| constraint_terms(model, c, &mut terms));
    model.constraints = constraints;
    result.map(|()| terms)
}

/// Appends the terms of `constraint` to `terms`.
fn constraint_terms(
    model: &mut Model,
    constraint: &Constraint,
    terms: &mut ConstraintTerms,
) -> Result<(), SpecErrors> {
    let coordinates = model.coordinate_symbols();
    let time = model.time;
    let store = &mut model.store;
    let g = constraint.statement.value;
    let row: Vec<ExprId> = (coordinates.iter())
        .map(|c| store.diff(g, c.position))
        .collect();
    let g_t = store.diff(g, time);
    let mut rate = Vec::with_capacity(row.len() + 1);
    for (c, &dg) in coordinates.iter().zip(&row) {
        rate.push(store.mul(dg, c.velocity_expr));
    }
    rate.push(g_t);
    let g_dot = store.sum(&rate);
    let mut curvature = Vec::with_capacity(row.len() + 1);
    for c in &coordinates {
        let d = store.diff(g_dot, c.position);
        curvature.push(store.mul(d, c.velocity_expr));
    }
    curvature.push(store.diff(g_dot, time));
    let sum = store.sum(&curvature);
    let gamma = store.neg(sum);
    check(model, constraint)?;
    terms.residual.push(g);
    terms.time_rate.push(g_t);
    terms.jacobian.extend(row);
    terms.acceleration.push(gamma);
    Ok(())
}

/// An engine error while differentiating `constraint`, reported at it.
fn check(model: &mut Model, constraint: &Constraint) -> Result<(), SpecErrors> {
    let Some(error) = model.store.take_errors().into_iter().next() else {
        return Ok(());
    };
    let input_names: Vec<String> = model.inputs.iter().map(|i| i.name.clone()).collect();
    let what = format!("the constraint `{}`", constraint.name);
    let span = constraint.statement.span;
    Err(engine_diagnostic(&model.store, &input_names, error, span, &what).into())
}
