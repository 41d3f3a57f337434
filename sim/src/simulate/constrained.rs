//! Runs of models with holonomic constraints `g(q, t) = 0`: the constrained
//! solve with Baumgarte's stabilization, the projection of the initial state
//! onto the constraints, and the drift of the constraints over a run.
//!
//! Stabilization: the solve asks `g̈ + 2α ġ + β² g = 0` of the constraints
//! ([`Baumgarte`]) instead of `g̈ = 0`, so that what the integration leaves
//! of `g` and `ġ` decays instead of growing; α and β are the scenario's
//! `[constraints] alpha`, `beta` [1/s] (critically damped when equal).
//!
//! Initial state: Gauss–Newton on `g(q, 0) = 0` with the minimum-norm
//! correction `Δq = −Gᵀ (G Gᵀ)⁻¹ g` (the smallest change of `q` in the
//! coordinates' own units, meters and radians alike), then the velocities
//! onto `G q̇ = −g_t` the same way.

use super::SimulationError;
use crate::fault::Fault;
pub use crate::scenario::options::DEFAULT_STABILIZATION;
use lagrangian_runtime::constrained::{
    Baumgarte, ConstrainedSolveError, ConstraintValues, SolveWorkspace, solve_constrained_in,
    solve_positive_definite,
};
use lagrangian_runtime::{InputFunctions, LagrangianSystem};
use nalgebra::{SMatrix, SVector};

/// The accelerations and multipliers at one state, with the constraint
/// terms they came from.
pub struct Solution<const N: usize> {
    /// `q̈`.
    pub a: SVector<f64, N>,
    /// `λ`, one per constraint: the generalized force `Gᵀλ` is added to `f`.
    pub lambda: Vec<f64>,
    /// The constraint terms at the state.
    pub values: ConstraintValues,
    /// `λᵀ G q̇`, the power of the constraint forces (zero on a fixed
    /// constraint that holds; a driven one does work).
    pub power: f64,
}

/// The constraint terms of `system` at `(t, q, q̇)`.
pub fn values<const N: usize, S: LagrangianSystem<N>, I: InputFunctions + ?Sized>(
    system: &S,
    t: f64,
    q: &SVector<f64, N>,
    v: &SVector<f64, N>,
    inputs: &I,
) -> ConstraintValues {
    let mut values = ConstraintValues::new(system.constraint_count(), N);
    system.constraints(t, q, v, inputs, &mut values.values);
    values
}

/// `M q̈ = f + Gᵀλ`, `G q̈ = γ − 2α ġ − β² g`.
#[allow(clippy::too_many_arguments)]
pub fn solve<const N: usize, S: LagrangianSystem<N>, I: InputFunctions + ?Sized>(
    system: &S,
    inputs: &I,
    stabilization: Baumgarte,
    state: (f64, &SVector<f64, N>, &SVector<f64, N>),
    mass: &SMatrix<f64, N, N>,
    forcing: &SVector<f64, N>,
) -> Result<Solution<N>, Fault> {
    let mut workspace = Workspace::new(system.constraint_count());
    let (a, power) = solve_in(
        system,
        inputs,
        stabilization,
        state,
        (mass, forcing),
        &mut workspace,
    )?;
    Ok(Solution {
        a,
        lambda: workspace.lambda,
        values: workspace.values,
        power,
    })
}

/// What a constrained solve needs besides the model, kept between solves
/// (by the problem a run integrates) so that a solve allocates nothing;
/// after a solve, the constraint terms and multipliers it found.
#[derive(Clone, Debug)]
pub struct Workspace<const N: usize> {
    /// The constraint terms at the last state solved.
    pub values: ConstraintValues,
    /// `λ` of the last solve.
    pub lambda: Vec<f64>,
    gamma: Vec<f64>,
    solve: SolveWorkspace<N>,
}

impl<const N: usize> Workspace<N> {
    /// Room for `m` constraints.
    pub fn new(m: usize) -> Workspace<N> {
        Workspace {
            values: ConstraintValues::new(m, N),
            lambda: vec![0.0; m],
            gamma: vec![0.0; m],
            solve: SolveWorkspace::new(m),
        }
    }
}

/// [`solve`] in `workspace` (made for the model's constraints): `q̈` and
/// the power `λᵀ G q̇`, with `g` and `λ` left in the workspace; allocates
/// nothing unless the solve fails.
pub fn solve_in<const N: usize, S: LagrangianSystem<N>, I: InputFunctions + ?Sized>(
    system: &S,
    inputs: &I,
    stabilization: Baumgarte,
    (t, q, v): (f64, &SVector<f64, N>, &SVector<f64, N>),
    (mass, forcing): (&SMatrix<f64, N, N>, &SVector<f64, N>),
    workspace: &mut Workspace<N>,
) -> Result<(SVector<f64, N>, f64), Fault> {
    let values = &mut workspace.values;
    values.values.fill(0.0);
    system.constraints(t, q, v, inputs, &mut values.values);
    let state = || (q.as_slice().to_vec(), v.as_slice().to_vec());
    if let Some(k) = values.values.iter().position(|x| !x.is_finite()) {
        let (q, qd) = state();
        let output = term_name(&system.constraint_names(), values, k);
        let value = values.values[k];
        return Err(Fault::NonFinite {
            output,
            value,
            q,
            qd,
        });
    }
    stabilization.acceleration_into(values, v.as_slice(), &mut workspace.gamma);
    let lambda = &mut workspace.lambda;
    let solution = solve_constrained_in(
        mass,
        forcing,
        values,
        &workspace.gamma,
        &mut workspace.solve,
        lambda,
    );
    match solution {
        Ok(a) => {
            let rate = |k: usize| dot(values.jacobian_row(k), v.as_slice());
            let power = (lambda.iter().enumerate()).map(|(k, l)| l * rate(k)).sum();
            Ok((a, power))
        }
        Err(ConstrainedSolveError::MassMatrix) => {
            let (q, qd) = state();
            Err(Fault::SingularMassMatrix { q, qd })
        }
        Err(ConstrainedSolveError::Redundant(indices)) => {
            let (q, qd) = state();
            let names = named(&system.constraint_names(), &indices);
            Err(Fault::RedundantConstraints { names, q, qd })
        }
    }
}

/// The constraints of a run: their names, what the projection of the
/// initial state changed, the stabilization and the drift.
#[derive(Clone, Debug, PartialEq)]
pub struct ConstraintReport {
    /// The constraints' names, in the model's order.
    pub names: Vec<String>,
    /// What the projection of the initial state changed.
    pub projection: Projection,
    /// The stabilization the run used.
    pub stabilization: Baumgarte,
    /// `max |g_k|` over the samples of the run, by constraint, each in its
    /// constraint's unit.
    pub drift: Vec<f64>,
}

impl ConstraintReport {
    /// The largest of [`ConstraintReport::drift`]: with constraints in
    /// different units, the largest number, whatever its unit (see the
    /// drift by constraint for each).
    pub fn drift_max(&self) -> f64 {
        max_abs(&self.drift)
    }
}

/// What the projection of the initial state changed.
#[derive(Clone, Debug, PartialEq)]
pub struct Projection {
    /// `max |g|` before the projection, each in its constraint's unit.
    pub residual_before: f64,
    /// The size `|Δq|` of the change of the coordinates (Euclidean, over
    /// the coordinates in their own units).
    pub coordinate_change: f64,
    /// `|Δq̇|`, likewise.
    pub velocity_change: f64,
    /// Gauss–Newton steps taken.
    pub iterations: usize,
}

/// Moves `(q, q̇)` onto `g(q, t) = 0`, `G q̇ + g_t = 0` (module docs); an
/// error naming the constraint left with the largest residual when
/// Gauss–Newton does not converge, or the redundant ones.
pub fn project<const N: usize, S: LagrangianSystem<N>, I: InputFunctions + ?Sized>(
    system: &S,
    inputs: &I,
    t: f64,
    q: &mut SVector<f64, N>,
    v: &mut SVector<f64, N>,
) -> Result<Projection, SimulationError> {
    let names = system.constraint_names();
    let (q0, v0) = (*q, *v);
    let first = values(system, t, q, v, inputs);
    let residual_before = max_abs(first.residual());
    let scale = q.amax().max(1.0);
    let mut iterations = 0;
    loop {
        let current = values(system, t, q, v, inputs);
        let finite = current.residual().iter().all(|x| x.is_finite());
        if finite && max_abs(current.residual()) <= 1e-12 * scale {
            break;
        }
        if iterations == 50 || !finite {
            return Err(unsatisfiable(&names, first.residual(), current.residual()));
        }
        let step = minimum_norm(&current, current.residual())
            .map_err(|k| dependent(&names, &current, q, &k, 1e-9 * scale))?;
        *q -= step;
        iterations += 1;
        if step.amax() <= 1e-15 * scale && iterations > 1 {
            break;
        }
    }
    let at = values(system, t, q, v, inputs);
    let rate = at.rate(v.as_slice());
    let step = minimum_norm(&at, &rate).map_err(|k| redundant(&names, &k))?;
    *v -= step;
    Ok(Projection {
        residual_before,
        coordinate_change: (*q - q0).norm(),
        velocity_change: (*v - v0).norm(),
        iterations,
    })
}

/// Moves `(q, q̇)` near the constraints back onto them, as the projection
/// of the initial state does (module docs) with at most three Gauss–Newton
/// steps: the end of a step of an integrator that holds the constraints
/// less tightly than its tolerances ask. A fault names the redundant
/// constraints.
pub fn project_step<const N: usize, S: LagrangianSystem<N>, I: InputFunctions + ?Sized>(
    system: &S,
    inputs: &I,
    t: f64,
    q: &mut SVector<f64, N>,
    v: &mut SVector<f64, N>,
) -> Result<(), Fault> {
    let redundant = |q: &SVector<f64, N>, v: &SVector<f64, N>, indices: Vec<usize>| {
        Fault::RedundantConstraints {
            names: named(&system.constraint_names(), &indices),
            q: q.as_slice().to_vec(),
            qd: v.as_slice().to_vec(),
        }
    };
    let scale = q.amax().max(1.0);
    for _ in 0..3 {
        let at = values(system, t, q, v, inputs);
        if max_abs(at.residual()) <= 1e-14 * scale {
            break;
        }
        let step = minimum_norm(&at, at.residual()).map_err(|k| redundant(q, v, k))?;
        *q -= step;
    }
    let at = values(system, t, q, v, inputs);
    let step = minimum_norm(&at, &at.rate(v.as_slice())).map_err(|k| redundant(q, v, k))?;
    *v -= step;
    Ok(())
}

/// `Gᵀ (G Gᵀ)⁻¹ r`, the smallest `x` with `G x = r`; `Err` with the
/// dependent rows.
fn minimum_norm<const N: usize>(
    values: &ConstraintValues,
    r: &[f64],
) -> Result<SVector<f64, N>, Vec<usize>> {
    let m = values.layout.m;
    let mut normal = vec![0.0; m * m];
    for k in 0..m {
        for l in 0..m {
            normal[k * m + l] = dot(values.jacobian_row(k), values.jacobian_row(l));
        }
    }
    let y = solve_positive_definite(&normal, m, r)?;
    let mut x = SVector::<f64, N>::zeros();
    for (k, yk) in y.iter().enumerate() {
        for (j, g) in values.jacobian_row(k).iter().enumerate() {
            x[j] += g * yk;
        }
    }
    Ok(x)
}

/// The constraint with the largest residual after Gauss–Newton, with its
/// residual before and after.
fn unsatisfiable(names: &[&str], before: &[f64], after: &[f64]) -> SimulationError {
    let k = (0..after.len())
        .max_by(|&a, &b| after[a].abs().total_cmp(&after[b].abs()))
        .unwrap_or(0);
    SimulationError::Constraints(format!(
        "the constraint `{}` cannot be satisfied near the initial state: its residual is \
         {:e} there and still {:e} after 50 Gauss–Newton steps (check the initial coordinates \
         and the parameters it uses)",
        names.get(k).copied().unwrap_or("?"),
        before[k],
        after[k]
    ))
}

/// Constraints `rows` whose gradients depend on those of the others at
/// `q`: redundant when satisfying the others (to first order, by the
/// minimum-norm step of their rows) satisfies them too; else unsatisfiable
/// near `q` — a gradient that vanishes where the residual does not (`x² + 1`,
/// a constant), or one that contradicts the others (`x` and `x − 1`) —
/// named with its residual.
fn dependent<const N: usize>(
    names: &[&str],
    values: &ConstraintValues,
    q: &SVector<f64, N>,
    rows: &[usize],
    tolerance: f64,
) -> SimulationError {
    let independent: Vec<usize> = (0..values.layout.m).filter(|k| !rows.contains(k)).collect();
    let step = minimum_norm_of_rows(values, &independent);
    let residual = values.residual();
    let contradicted = rows.iter().copied().find(|&k| {
        let left = residual[k] - dot(values.jacobian_row(k), &step);
        left.is_nan() || left.abs() > tolerance
    });
    let Some(k) = contradicted else {
        return redundant(names, rows);
    };
    SimulationError::Constraints(format!(
        "the constraint `{}` cannot be satisfied near the initial state: its residual is {:e} at \
         q = {:?}, where no change of the coordinates reduces it (its gradient is zero there, or \
         a combination of the other constraints' gradients, which it contradicts); check the \
         constraint and the parameters it uses",
        names.get(k).copied().unwrap_or("?"),
        residual[k],
        q.as_slice()
    ))
}

/// The minimum-norm `x` with `G_k x = g_k` for the constraints `rows`
/// alone (independent ones), as a vector over the coordinates; zero when
/// even they are dependent.
fn minimum_norm_of_rows(values: &ConstraintValues, rows: &[usize]) -> Vec<f64> {
    let (m, n) = (rows.len(), values.layout.n);
    let mut normal = vec![0.0; m * m];
    for (a, &k) in rows.iter().enumerate() {
        for (b, &l) in rows.iter().enumerate() {
            normal[a * m + b] = dot(values.jacobian_row(k), values.jacobian_row(l));
        }
    }
    let r: Vec<f64> = rows.iter().map(|&k| values.residual()[k]).collect();
    let mut x = vec![0.0; n];
    if let Ok(y) = solve_positive_definite(&normal, m, &r) {
        for (&k, yk) in rows.iter().zip(&y) {
            for (j, g) in values.jacobian_row(k).iter().enumerate() {
                x[j] += g * yk;
            }
        }
    }
    x
}

fn redundant(names: &[&str], indices: &[usize]) -> SimulationError {
    SimulationError::Constraints(format!(
        "redundant constraints at the initial state: {} (each depends on the constraints \
         declared before it; remove it or them)",
        named(names, indices).join(", ")
    ))
}

/// The names of the constraints `indices`, in backticks.
fn named(names: &[&str], indices: &[usize]) -> Vec<String> {
    (indices.iter())
        .map(|&k| format!("`{}`", names.get(k).copied().unwrap_or("?")))
        .collect()
}

/// The name of term `k` of the constraint outputs, e.g. `G[rod, 1]`.
fn term_name(names: &[&str], values: &ConstraintValues, k: usize) -> String {
    let layout = values.layout;
    let name = |i: usize| names.get(i).copied().unwrap_or("?");
    if layout.residual().contains(&k) {
        format!("the constraint `{}`", name(k))
    } else if layout.time_rate().contains(&k) {
        format!("∂/∂t of the constraint `{}`", name(k - layout.m))
    } else if layout.jacobian().contains(&k) {
        let j = k - layout.jacobian().start;
        format!("G[{}, {}]", name(j / layout.n), j % layout.n)
    } else {
        format!(
            "γ of the constraint `{}`",
            name(k - layout.acceleration().start)
        )
    }
}

fn max_abs(values: &[f64]) -> f64 {
    values.iter().fold(0.0, |m, x| m.max(x.abs()))
}

#[inline]
fn dot(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}
