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
use crate::expr::{CoordinateSymbols, EngineError, Evaluator, ExprId, Store, SymbolId, SymbolKind};
use crate::program::{EvalContext, Program, RoutineKind};
use crate::random::Lcg;
use crate::spec::{ForceStatement, Input, Model, Statement, engine_diagnostic};
use proc_macro2::Span;

/// The derived equations of motion and energy bookkeeping of a model.
#[derive(Clone, Debug)]
pub struct Derivation {
    /// `n`, the number of generalized coordinates.
    pub dimension: usize,
    /// `M`, row-major `n × n`, symmetric.
    pub mass_matrix: Vec<ExprId>,
    /// `f`.
    pub forcing: Vec<ExprId>,
    /// `Q_i` from the force statements (without the dissipation function).
    pub generalized_forces: Vec<ExprId>,
    /// `T`, the kinetic energy.
    pub kinetic: ExprId,
    /// `V`, the potential energy (0 when the spec has none).
    pub potential: ExprId,
    /// `D`, the Rayleigh dissipation function (0 when the spec has none).
    pub dissipation: ExprId,
    /// `Σ_i ∂D/∂q̇_i q̇_i`, the power drawn by the dissipation function.
    pub damping_power: ExprId,
    /// `Σ_i Q_i q̇_i`, the power of the generalized forces.
    pub external_power: ExprId,
    /// The Jacobians, when the spec asks for them (`jacobians;`).
    pub jacobians: Option<Jacobians>,
    /// The value of each output (`output name = …;`), in declaration
    /// order: functions of `t`, `q`, `q̇`, `q̈`, the parameters and inputs.
    pub outputs: Vec<ExprId>,
    /// `g`, `g_t`, `G` and `γ` of the holonomic constraints (empty without).
    pub constraints: crate::constraints::ConstraintTerms,
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
    /// `M_ij`.
    pub fn mass(&self, i: usize, j: usize) -> ExprId {
        self.mass_matrix[i * self.dimension + j]
    }
}

/// Derives the equations of motion of `model`.
pub fn derive(model: &mut Model) -> Result<Derivation, SpecErrors> {
    let mut derivation = Deriver::new(model).equations()?;
    check_positive_definite(model, &derivation.mass_matrix)?;
    if model.jacobians {
        let (mass, forcing) = (&derivation.mass_matrix, &derivation.forcing);
        derivation.jacobians = Some(Deriver::new(model).jacobians(mass, forcing)?);
    }
    derivation.outputs = model.outputs.iter().map(|o| o.statement.value).collect();
    derivation.constraints = crate::constraints::derive(model)?;
    Ok(derivation)
}

/// The derivation's working state: the model's store, which it writes, and
/// the rest of the model, which it reads (the statements that engine errors
/// are reported against), borrowed apart.
struct Deriver<'a> {
    store: &'a mut Store,
    sources: Sources<'a>,
    coordinates: Vec<CoordinateSymbols>,
    time: SymbolId,
}

/// The statements and spans of a model that locate an engine error.
struct Sources<'a> {
    kinetic: &'a Statement,
    potential: Option<&'a Statement>,
    dissipation: Option<&'a Statement>,
    forces: &'a [ForceStatement],
    inputs: &'a [Input],
    jacobians_span: Option<Span>,
    name_span: Span,
}

impl<'a> Deriver<'a> {
    fn new(model: &'a mut Model) -> Deriver<'a> {
        let coordinates = model.coordinate_symbols();
        let Model {
            store,
            kinetic,
            potential,
            dissipation,
            forces,
            inputs,
            jacobians_span,
            name_span,
            time,
            ..
        } = model;
        Deriver {
            store,
            sources: Sources {
                kinetic,
                potential: potential.as_ref(),
                dissipation: dissipation.as_ref(),
                forces,
                inputs,
                jacobians_span: *jacobians_span,
                name_span: *name_span,
            },
            coordinates,
            time: *time,
        }
    }

    /// `M`, `f`, `Q`, the energies and the powers (no Jacobians).
    fn equations(mut self) -> Result<Derivation, SpecErrors> {
        let n = self.coordinates.len();
        let kinetic = self.sources.kinetic.value;
        let potential = self.sources.potential.map_or(Store::ZERO, |s| s.value);
        let dissipation = self.sources.dissipation.map_or(Store::ZERO, |s| s.value);
        let momenta = self.momenta(kinetic, potential)?;
        let mass_matrix = self.mass_matrix(&momenta)?;
        let generalized_forces = self.generalized_forces();
        let mut forcing = Vec::with_capacity(n);
        for (i, &q) in generalized_forces.iter().enumerate() {
            let energies = [kinetic, potential, dissipation];
            forcing.push(self.forcing(i, energies, &momenta, q)?);
        }
        let (damping_power, external_power) = self.powers(dissipation, &generalized_forces);
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
            jacobians: None,
            outputs: Vec::new(),
            constraints: Default::default(),
        })
    }

    /// `p_i = ∂L/∂q̇_i = ∂T/∂q̇_i − ∂V/∂q̇_i`.
    fn momenta(&mut self, kinetic: ExprId, potential: ExprId) -> Result<Vec<ExprId>, SpecErrors> {
        let mut momenta = Vec::with_capacity(self.coordinates.len());
        for i in 0..self.coordinates.len() {
            let velocity = self.coordinates[i].velocity;
            let dt = self.store.diff(kinetic, velocity);
            self.check(Some(self.sources.kinetic), "the kinetic energy")?;
            let dv = self.store.diff(potential, velocity);
            self.check(self.sources.potential, "the potential energy")?;
            momenta.push(self.store.sub(dt, dv));
        }
        Ok(momenta)
    }

    /// `M_ij = ∂p_i/∂q̇_j`, row-major, symmetric.
    fn mass_matrix(&mut self, momenta: &[ExprId]) -> Result<Vec<ExprId>, SpecErrors> {
        let n = self.coordinates.len();
        let mut mass_matrix = vec![Store::ZERO; n * n];
        for i in 0..n {
            for j in i..n {
                let m = self.store.diff(momenta[i], self.coordinates[j].velocity);
                mass_matrix[i * n + j] = m;
                mass_matrix[j * n + i] = m;
            }
        }
        self.check(Some(self.sources.kinetic), "the mass matrix")?;
        Ok(mass_matrix)
    }

    /// `Q_i`, the sum of the force statements' generalized forces.
    fn generalized_forces(&mut self) -> Vec<ExprId> {
        let mut generalized_forces = vec![Store::ZERO; self.coordinates.len()];
        for force in self.sources.forces {
            for &(i, q) in &force.generalized {
                generalized_forces[i] = self.store.add(generalized_forces[i], q);
            }
        }
        generalized_forces
    }

    /// `f_i = ∂L/∂q_i − Σ_j (∂p_i/∂q_j) q̇_j − ∂p_i/∂t − ∂D/∂q̇_i + Q_i`,
    /// `energies` being `[T, V, D]`.
    fn forcing(
        &mut self,
        i: usize,
        [kinetic, potential, dissipation]: [ExprId; 3],
        momenta: &[ExprId],
        generalized_force: ExprId,
    ) -> Result<ExprId, SpecErrors> {
        let (position, velocity) = (self.coordinates[i].position, self.coordinates[i].velocity);
        let mut terms = Vec::with_capacity(momenta.len() + 5);
        terms.push(self.store.diff(kinetic, position));
        self.check(Some(self.sources.kinetic), "the kinetic energy")?;
        let dv = self.store.diff(potential, position);
        self.check(self.sources.potential, "the potential energy")?;
        terms.push(self.store.neg(dv));
        for cj in &self.coordinates {
            let dp = self.store.diff(momenta[i], cj.position);
            let term = self.store.mul(dp, cj.velocity_expr);
            terms.push(self.store.neg(term));
        }
        let dp_dt = self.store.diff(momenta[i], self.time);
        terms.push(self.store.neg(dp_dt));
        self.check(Some(self.sources.kinetic), "the kinetic energy")?;
        let dd = self.store.diff(dissipation, velocity);
        self.check(self.sources.dissipation, "the dissipation function")?;
        terms.push(self.store.neg(dd));
        terms.push(generalized_force);
        Ok(self.store.sum(&terms))
    }

    /// `(Σ_i ∂D/∂q̇_i q̇_i, Σ_i Q_i q̇_i)`: the damping and external powers.
    fn powers(&mut self, dissipation: ExprId, generalized_forces: &[ExprId]) -> (ExprId, ExprId) {
        let n = self.coordinates.len();
        let mut damping_terms = Vec::with_capacity(n);
        let mut power_terms = Vec::with_capacity(n);
        for (c, &q) in self.coordinates.iter().zip(generalized_forces) {
            let dd = self.store.diff(dissipation, c.velocity);
            damping_terms.push(self.store.mul(dd, c.velocity_expr));
            power_terms.push(self.store.mul(q, c.velocity_expr));
        }
        (self.store.sum(&damping_terms), self.store.sum(&power_terms))
    }

    /// `∂f/∂q`, `∂f/∂q̇` and `∂(M a)/∂q`.
    fn jacobians(mut self, mass: &[ExprId], forcing: &[ExprId]) -> Result<Jacobians, SpecErrors> {
        let n = self.coordinates.len();
        let mut forcing_q = Vec::with_capacity(n * n);
        let mut forcing_qd = Vec::with_capacity(n * n);
        let mut mass_times_acceleration_q = Vec::with_capacity(n * n);
        for i in 0..n {
            for ck in &self.coordinates {
                forcing_q.push(self.store.diff(forcing[i], ck.position));
                forcing_qd.push(self.store.diff(forcing[i], ck.velocity));
                let mut terms = Vec::with_capacity(n);
                for (j, cj) in self.coordinates.iter().enumerate() {
                    let dm = self.store.diff(mass[i * n + j], ck.position);
                    terms.push(self.store.mul(dm, cj.acceleration_expr));
                }
                mass_times_acceleration_q.push(self.store.sum(&terms));
            }
        }
        self.check(None, "the Jacobians (requested by `jacobians;`)")?;
        Ok(Jacobians {
            forcing_q,
            forcing_qd,
            mass_times_acceleration_q,
        })
    }

    /// Turns engine errors into a diagnostic pointing into `statement`, or at
    /// the input call that caused them.
    fn check(&mut self, statement: Option<&Statement>, what: &str) -> Result<(), SpecErrors> {
        let Some(error) = self.store.take_errors().into_iter().next() else {
            return Ok(());
        };
        let sources = &self.sources;
        let span = match &error {
            EngineError::MissingDerivative { input, .. } => {
                sources.locate_input_call(statement, *input)
            }
            _ => None,
        }
        .or(statement.map(|s| s.span))
        .or(sources.jacobians_span.map(SpanRange::from))
        .unwrap_or(sources.name_span.into());
        let input_names: Vec<String> = sources.inputs.iter().map(|i| i.name.clone()).collect();
        let mut diagnostic = engine_diagnostic(self.store, &input_names, error, span, what);
        if statement.is_none()
            && let Some(j) = sources.jacobians_span
        {
            diagnostic = diagnostic.with_note("the Jacobians are requested here", j);
        }
        Err(diagnostic.into())
    }
}

impl Sources<'_> {
    /// Where `input` is called: inside `statement` if it is, else anywhere.
    fn locate_input_call(&self, statement: Option<&Statement>, input: usize) -> Option<SpanRange> {
        let in_statement = statement.and_then(|s| s.input_calls.iter().find(|(i, _)| *i == input));
        let anywhere = || {
            std::iter::once(self.kinetic)
                .chain(self.potential)
                .chain(self.dissipation)
                .flat_map(|s| s.input_calls.iter())
                .chain(self.forces.iter().flat_map(|f| f.input_calls.iter()))
                .find(|(i, _)| *i == input)
        };
        in_statement.or_else(anywhere).map(|(_, span)| *span)
    }
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

/// How many sample states the positive-definiteness check tries for one
/// inside every function's domain before it says it could not check.
const MASS_SAMPLES: u64 = 64;

/// Sample state `k` for the positive-definiteness check: `k = 0` is
/// [`sample_symbol_values`]; the others are drawn by [`Lcg`] (seeded with
/// `k`), coordinates uniform in `±s` for a scale `s` of 1, 0.3, 0.1 or 3 in
/// turn, velocities in `±1`.
fn sample_state(model: &Model, k: u64) -> Vec<f64> {
    let mut values = sample_symbol_values(model);
    if k == 0 {
        return values;
    }
    let scale = [1.0, 0.3, 0.1, 3.0][(k % 4) as usize];
    let mut random = Lcg::new(k);
    for c in &model.coordinates {
        values[c.symbols.position.index()] = scale * random.symmetric();
        values[c.symbols.velocity.index()] = random.symmetric();
    }
    values
}

/// Why sample state `values` cannot serve the check: a call outside its
/// domain there (with the argument's value), or a mass matrix `m` that is
/// not finite there.
fn invalid_sample(model: &Model, values: &[f64], m: &[f64]) -> Option<(String, Option<SpanRange>)> {
    let (q, qd) = state_of(model, values);
    let parameters: Vec<f64> = model.parameters.iter().map(|p| p.default).collect();
    let t = values[model.time.index()];
    if let Some((check, x)) = model.domain_violation(t, &q, &qd, &parameters) {
        let what = match check.what.strip_suffix(" of") {
            Some(what) => format!("{what} of the call noted below"),
            None => format!("{} noted below", check.what),
        };
        let reason = format!(
            "a function's argument is outside its domain (at the first, {what} is {x:.3} but {})",
            check.domain.describe()
        );
        return Some((reason, Some(check.span)));
    }
    let infinite = m.iter().any(|x| !x.is_finite());
    infinite.then(|| ("the mass matrix is not finite".to_string(), None))
}

/// The coordinates and velocities of sample state `values`.
fn state_of(model: &Model, values: &[f64]) -> (Vec<f64>, Vec<f64>) {
    (model.coordinates.iter())
        .map(|c| {
            let s = &c.symbols;
            (values[s.position.index()], values[s.velocity.index()])
        })
        .unzip()
}

/// The kinetic energy must be positive definite in the velocities: `M` must
/// admit a Cholesky factorization at a sample state with default parameters.
fn check_positive_definite(model: &mut Model, mass: &[ExprId]) -> Result<(), SpecErrors> {
    check_mass_at_samples(model, |model, values| {
        let mut evaluator =
            Evaluator::new(&model.store, values.to_vec(), &|_: usize, _: &[f64]| 1.0);
        mass.iter().map(|&e| evaluator.eval(e)).collect()
    })
}

/// [`check_positive_definite`] on the mass matrix that `program` computes
/// (at the same sample states, input functions 1).
pub(crate) fn check_program_mass(model: &mut Model, program: &Program) -> Result<(), SpecErrors> {
    check_mass_at_samples(model, |model, values| program_mass(model, program, values))
}

/// The row-major mass matrix that `program` computes at sample state `values`.
fn program_mass(model: &Model, program: &Program, values: &[f64]) -> Vec<f64> {
    let n = model.dimension();
    let (q, qd) = state_of(model, values);
    let parameters: Vec<f64> = model.parameters.iter().map(|p| p.default).collect();
    let ctx = EvalContext {
        t: values[model.time.index()],
        q: &q,
        qd: &qd,
        qdd: &vec![0.0; n],
        parameters: &parameters,
        inputs: &|_: usize, _: &[f64]| 1.0,
    };
    let routine = program
        .routine(RoutineKind::Dynamics)
        .expect("every program has the dynamics routine");
    let mut out = vec![0.0; routine.outputs.len()];
    program.run(routine, &ctx, &mut program.registers(), &mut out);
    let mut m = vec![0.0; n * n];
    for (k, (i, j)) in lagrangian_runtime::layout::mass_entries(n).enumerate() {
        m[i * n + j] = out[k];
        m[j * n + i] = out[k];
    }
    m
}

/// Checks the mass matrix `mass_at(model, state)` at the first sample state
/// inside every function's domain where it is finite; when none of
/// [`MASS_SAMPLES`] is, the model is not refused but warned that the check
/// could not be made, and why.
fn check_mass_at_samples(
    model: &mut Model,
    mass_at: impl Fn(&Model, &[f64]) -> Vec<f64>,
) -> Result<(), SpecErrors> {
    let mut first_reason = None;
    for k in 0..MASS_SAMPLES {
        let values = sample_state(model, k);
        let m = mass_at(model, &values);
        match invalid_sample(model, &values, &m) {
            None => return check_mass_values(model, &m, &values),
            Some(reason) => {
                first_reason.get_or_insert(reason);
            }
        }
    }
    let (reason, at) = first_reason.expect("at least one sample was tried");
    let mut warning = Diagnostic::new(
        model.kinetic.span,
        format!(
            "the kinetic energy could not be checked for positive definiteness: at each of {MASS_SAMPLES} sample states {reason}"
        ),
    )
    .with_help("check the domains of the functions the spec calls (`acos`, `ln`, `sqrt`, divisions) against the coordinates' ranges");
    if let Some(span) = at {
        warning = warning.with_note("the call at the first sample state", span);
    }
    if !model.warnings.iter().any(|w| w.message == warning.message) {
        model.warnings.push(warning); // once, when the model is derived twice
    }
    Ok(())
}

/// The diagnostic of [`check_positive_definite`] for the mass matrix `m`
/// (row-major) at the sample state `values`, if its factorization fails.
fn check_mass_values(model: &Model, m: &[f64], values: &[f64]) -> Result<(), SpecErrors> {
    let n = model.dimension();
    let failing = cholesky_failure(m, n);
    let Some(k) = failing else {
        return Ok(());
    };
    let name = &model.coordinates[k].name;
    let (q, _) = state_of(model, values);
    let state: Vec<String> = (model.coordinates.iter().zip(&q))
        .map(|(c, x)| format!("{} = {x:.2}", c.name))
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
