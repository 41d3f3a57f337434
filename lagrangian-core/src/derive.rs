//! The Euler–Lagrange equations in the form `M(q, t) q̈ = f(q, q̇, t)`.
//!
//! With `L = T − V`, momenta `p_i = ∂L/∂q̇_i`, Rayleigh dissipation `D` and
//! generalized forces `Q_i`,
//!
//! ```text
//! M_ij = ∂p_i/∂q̇_j
//! f_i  = ∂L/∂q_i − Σ_j (∂p_i/∂q_j) q̇_j − ∂p_i/∂t − ∂D/∂q̇_i + Q_i
//! ```
//!
//! Optionally (`jacobians;`) also `∂f/∂q`, `∂f/∂q̇` and `∂(M a)/∂q` for an
//! acceleration vector `a`, which implicit integrators and sensitivity
//! analyses need.

use crate::diagnostic::{Diagnostic, SpanRange, SpecErrors};
use crate::expr::{Evaluator, ExprId, Store, SymbolKind};
use crate::spec::{Model, Statement};

/// The derived equations of motion and energy bookkeeping of a model.
#[derive(Clone, Debug)]
pub struct Derivation {
    pub dimension: usize,
    /// `M`, row-major `n × n`, symmetric.
    pub mass_matrix: Vec<ExprId>,
    /// `f`.
    pub forcing: Vec<ExprId>,
    /// `Q_i` from the force statements (without the dissipation function).
    pub generalized_forces: Vec<ExprId>,
    pub kinetic: ExprId,
    pub potential: ExprId,
    pub dissipation: ExprId,
    /// `Σ_i ∂D/∂q̇_i q̇_i`, the power drawn by the dissipation function.
    pub damping_power: ExprId,
    /// `Σ_i Q_i q̇_i`, the power of the generalized forces.
    pub external_power: ExprId,
    pub jacobians: Option<Jacobians>,
}

/// Row-major `n × n` Jacobians of the equations of motion.
#[derive(Clone, Debug)]
pub struct Jacobians {
    /// `∂f_i/∂q_k`.
    pub forcing_q: Vec<ExprId>,
    /// `∂f_i/∂q̇_k`.
    pub forcing_qd: Vec<ExprId>,
    /// `∂(M a)_i/∂q_k = Σ_j ∂M_ij/∂q_k a_j`, with `a` the acceleration symbols.
    pub mass_times_acceleration_q: Vec<ExprId>,
}

impl Derivation {
    pub fn mass(&self, i: usize, j: usize) -> ExprId {
        self.mass_matrix[i * self.dimension + j]
    }
}

/// Derives the equations of motion of `model`.
pub fn derive(model: &mut Model) -> Result<Derivation, SpecErrors> {
    let n = model.dimension();
    let coordinates = model.coordinate_symbols();
    let time = model.time;
    let kinetic = model.kinetic.value;
    let potential = model.potential.as_ref().map_or(Store::ZERO, |s| s.value);
    let dissipation = model.dissipation.as_ref().map_or(Store::ZERO, |s| s.value);

    let mut momenta = Vec::with_capacity(n);
    for c in &coordinates {
        let dt = model.store.diff(kinetic, c.velocity);
        check(model, Some(&model.kinetic.clone()), "the kinetic energy")?;
        let dv = model.store.diff(potential, c.velocity);
        check(
            model,
            model.potential.clone().as_ref(),
            "the potential energy",
        )?;
        momenta.push(model.store.sub(dt, dv));
    }

    let mut mass_matrix = vec![Store::ZERO; n * n];
    for i in 0..n {
        for j in i..n {
            let m = model.store.diff(momenta[i], coordinates[j].velocity);
            mass_matrix[i * n + j] = m;
            mass_matrix[j * n + i] = m;
        }
    }
    check(model, Some(&model.kinetic.clone()), "the mass matrix")?;

    let mut generalized_forces = vec![Store::ZERO; n];
    for force in model.forces.clone() {
        for (i, q) in force.generalized {
            generalized_forces[i] = model.store.add(generalized_forces[i], q);
        }
    }

    let mut forcing = Vec::with_capacity(n);
    for (i, c) in coordinates.iter().enumerate() {
        let mut terms = Vec::with_capacity(n + 5);
        terms.push(model.store.diff(kinetic, c.position));
        check(model, Some(&model.kinetic.clone()), "the kinetic energy")?;
        let dv = model.store.diff(potential, c.position);
        check(
            model,
            model.potential.clone().as_ref(),
            "the potential energy",
        )?;
        terms.push(model.store.neg(dv));
        for cj in &coordinates {
            let dp = model.store.diff(momenta[i], cj.position);
            let term = model.store.mul(dp, cj.velocity_expr);
            terms.push(model.store.neg(term));
        }
        let dp_dt = model.store.diff(momenta[i], time);
        terms.push(model.store.neg(dp_dt));
        check(model, Some(&model.kinetic.clone()), "the kinetic energy")?;
        let dd = model.store.diff(dissipation, c.velocity);
        check(
            model,
            model.dissipation.clone().as_ref(),
            "the dissipation function",
        )?;
        terms.push(model.store.neg(dd));
        terms.push(generalized_forces[i]);
        forcing.push(model.store.sum(&terms));
    }

    let mut damping_terms = Vec::with_capacity(n);
    let mut power_terms = Vec::with_capacity(n);
    for (i, c) in coordinates.iter().enumerate() {
        let dd = model.store.diff(dissipation, c.velocity);
        damping_terms.push(model.store.mul(dd, c.velocity_expr));
        power_terms.push(model.store.mul(generalized_forces[i], c.velocity_expr));
    }
    let damping_power = model.store.sum(&damping_terms);
    let external_power = model.store.sum(&power_terms);

    check_positive_definite(model, &mass_matrix)?;

    let jacobians = if model.jacobians {
        Some(derive_jacobians(model, &mass_matrix, &forcing)?)
    } else {
        None
    };

    Ok(Derivation {
        dimension: n,
        mass_matrix,
        forcing,
        generalized_forces,
        kinetic,
        potential,
        dissipation,
        damping_power,
        external_power,
        jacobians,
    })
}

fn derive_jacobians(
    model: &mut Model,
    mass: &[ExprId],
    forcing: &[ExprId],
) -> Result<Jacobians, SpecErrors> {
    let n = model.dimension();
    let coordinates = model.coordinate_symbols();
    let mut forcing_q = Vec::with_capacity(n * n);
    let mut forcing_qd = Vec::with_capacity(n * n);
    let mut mass_times_acceleration_q = Vec::with_capacity(n * n);
    for i in 0..n {
        for ck in &coordinates {
            forcing_q.push(model.store.diff(forcing[i], ck.position));
            forcing_qd.push(model.store.diff(forcing[i], ck.velocity));
            let mut terms = Vec::with_capacity(n);
            for (j, cj) in coordinates.iter().enumerate() {
                let dm = model.store.diff(mass[i * n + j], ck.position);
                terms.push(model.store.mul(dm, cj.acceleration_expr));
            }
            mass_times_acceleration_q.push(model.store.sum(&terms));
        }
    }
    check(model, None, "the Jacobians (requested by `jacobians;`)")?;
    Ok(Jacobians {
        forcing_q,
        forcing_qd,
        mass_times_acceleration_q,
    })
}

/// Turns engine errors into a diagnostic pointing into `statement`, or at the
/// input call that caused them.
fn check(model: &mut Model, statement: Option<&Statement>, what: &str) -> Result<(), SpecErrors> {
    let Some(error) = model.store.take_errors().into_iter().next() else {
        return Ok(());
    };
    let input_names: Vec<String> = model.inputs.iter().map(|i| i.name.clone()).collect();
    let span = match &error {
        crate::expr::EngineError::MissingDerivative { input, .. } => {
            locate_input_call(model, statement, *input)
        }
        _ => None,
    }
    .or(statement.map(|s| s.span))
    .or(model.jacobians_span.map(SpanRange::from))
    .unwrap_or(model.name_span.into());
    let mut diagnostic = expression_diagnostic(model, &input_names, error, span, what);
    if statement.is_none()
        && let Some(j) = model.jacobians_span
    {
        diagnostic = diagnostic.with_note("the Jacobians are requested here", j);
    }
    Err(diagnostic.into())
}

fn expression_diagnostic(
    model: &Model,
    input_names: &[String],
    error: crate::expr::EngineError,
    span: SpanRange,
    what: &str,
) -> Diagnostic {
    crate::spec::engine_diagnostic(&model.store, input_names, error, span, what)
}

/// Where `input` is called: inside `statement` if it is, else anywhere.
fn locate_input_call(
    model: &Model,
    statement: Option<&Statement>,
    input: usize,
) -> Option<SpanRange> {
    let in_statement = statement.and_then(|s| s.input_calls.iter().find(|(i, _)| *i == input));
    let anywhere = || {
        std::iter::once(&model.kinetic)
            .chain(model.potential.iter())
            .chain(model.dissipation.iter())
            .flat_map(|s| s.input_calls.iter())
            .chain(model.forces.iter().flat_map(|f| f.input_calls.iter()))
            .find(|(i, _)| *i == input)
    };
    in_statement.or_else(anywhere).map(|(_, span)| *span)
}

/// A deterministic state away from symmetric configurations, used for checks:
/// `q_i = 0.31 + 0.17 i`, `q̇_i = 0.7 − 0.23 i`, `t = 0.25`, default parameters.
pub fn sample_symbol_values(model: &Model) -> Vec<f64> {
    let mut values = vec![0.0; model.store.symbols().len()];
    for (index, s) in model.store.symbols().iter().enumerate() {
        values[index] = match s.kind {
            SymbolKind::Parameter(i) => model.parameters[i].default,
            SymbolKind::Time => 0.25,
            SymbolKind::Pi => std::f64::consts::PI,
            _ => 0.0,
        };
    }
    for (i, c) in model.coordinates.iter().enumerate() {
        values[c.symbols.position.index()] = sample_coordinate(i);
        values[c.symbols.velocity.index()] = 0.7 - 0.23 * i as f64;
    }
    values
}

fn sample_coordinate(i: usize) -> f64 {
    0.31 + 0.17 * i as f64
}

/// The kinetic energy must be positive definite in the velocities: `M` must
/// admit a Cholesky factorization at a sample state with default parameters.
fn check_positive_definite(model: &Model, mass: &[ExprId]) -> Result<(), SpecErrors> {
    let n = model.dimension();
    let values = sample_symbol_values(model);
    let mut evaluator = Evaluator::new(&model.store, values, &|_: usize, _: &[f64]| 1.0);
    let m: Vec<f64> = mass.iter().map(|&e| evaluator.eval(e)).collect();
    let failing = cholesky_failure(&m, n);
    let Some(k) = failing else {
        return Ok(());
    };
    let name = &model.coordinates[k].name;
    let state: Vec<String> = model
        .coordinates
        .iter()
        .enumerate()
        .map(|(i, c)| format!("{} = {:.2}", c.name, sample_coordinate(i)))
        .collect();
    let message = if (0..n).all(|j| m[k * n + j] == 0.0) {
        format!(
            "the kinetic energy does not depend on `dot({name})`, so the mass matrix is singular"
        )
    } else {
        format!(
            "the kinetic energy is not positive definite in the velocities: the mass matrix at the sample state ({}) with default parameters has a non-positive pivot at `{name}`",
            state.join(", ")
        )
    };
    Err(Diagnostic::new(model.kinetic.span, message)
        .with_help("every coordinate needs inertia: check the signs of masses and inertias and that each `dot(q)` appears in T")
        .into())
}

/// The first pivot index at which the Cholesky factorization of the symmetric
/// row-major matrix `m` fails (pivot not positive or not finite).
pub fn cholesky_failure(m: &[f64], n: usize) -> Option<usize> {
    let mut l = vec![0.0; n * n];
    let scale = m
        .iter()
        .fold(0.0f64, |a, b| a.max(b.abs()))
        .max(f64::MIN_POSITIVE);
    for j in 0..n {
        let mut d = m[j * n + j];
        for k in 0..j {
            d -= l[j * n + k] * l[j * n + k];
        }
        if d.is_nan() || d <= 1e-12 * scale || !d.is_finite() {
            return Some(j);
        }
        let d = d.sqrt();
        l[j * n + j] = d;
        for i in j + 1..n {
            let mut s = m[i * n + j];
            for k in 0..j {
                s -= l[i * n + k] * l[j * n + k];
            }
            l[i * n + j] = s / d;
        }
    }
    None
}
