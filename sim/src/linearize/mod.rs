//! Linearization of a model about an operating point: the state-space form
//! `δẋ = A δx + B δu` of `M(q) q̈ = f(q, q̇, t)` with the state
//! `x = (q, q̇)`, and its modes.
//!
//! `ẋ = (q̇, q̈)` with `q̈ = M⁻¹ f`, so
//! `A = [[0, I], [M⁻¹ (∂f/∂q − ∂(M q̈)/∂q), M⁻¹ ∂f/∂q̇]]` at the operating
//! point, from the model's derived Jacobians (central differences of `q̈`
//! when the model has none). The inputs the scenario binds to components
//! (crush elements, welds, tables) are part of the system: their tangent
//! stiffness and damping enter `A` through the inputs' declared
//! derivatives. Every other input the dynamics calls — unbound (held at 0)
//! or given a constant — is a column of `B`: `∂ẋ/∂u` for its value `u`.
//!
//! A model with constraints is linearized in its coordinates as they are
//! (`A` is `2n × 2n`, of the constrained accelerations without Baumgarte's
//! stabilization, by central differences), about an equilibrium on the
//! constraints; its modes are those of the motion on the constraints
//! (`2(n − m)` eigenvalues, the `manifold` module).

mod manifold;
mod modes;
mod report;

pub use modes::{Mode, ModeKind, modes};
pub use report::{FIELDS, Field, json, markdown, projection_note};

use crate::components::constant::Constant;
use crate::components::{Binding, BoundInputs, NamedComponent, Port};
use crate::fault::Fault;
use crate::ode::PhaseState;
use crate::ode::tr_bdf2::AccelerationJacobians;
use crate::scenario::Scenario;
use crate::simulate::{
    CrashProblem, Projection, SimulationError, SolverError, constrained, static_equilibrium,
};
use lagrangian_runtime::constrained::Baumgarte;
use lagrangian_runtime::{InputFunctions, LagrangianSystem, solve_mass_matrix};
use nalgebra::{DMatrix, SMatrix, SVector};

/// Where to linearize.
#[derive(Clone, Debug, PartialEq)]
pub enum At {
    /// The static equilibrium (`q̇ = 0`, `f(q, 0, 0) = 0`; on the
    /// constraints, `f + Gᵀλ = 0` and `g = 0`, for a model with constraints)
    /// of the scenario's equilibrium coordinates (every coordinate when it
    /// names none), solved from its initial coordinates.
    Equilibrium,
    /// A given state.
    State {
        /// The coordinates.
        q: Vec<f64>,
        /// The velocities.
        qd: Vec<f64>,
    },
}

/// The state a model was linearized about, at `t = 0`.
#[derive(Clone, Debug, PartialEq)]
pub struct OperatingPoint {
    /// The coordinates.
    pub q: Vec<f64>,
    /// The velocities.
    pub qd: Vec<f64>,
    /// The accelerations `q̈ = M⁻¹ f` there (0 at an equilibrium).
    pub qdd: Vec<f64>,
    /// How the equilibrium was found (`None` for a given state).
    pub equilibrium: Option<Equilibrium>,
    /// A given state of a model with constraints, moved onto them as
    /// `simulate` moves its initial state: the state asked for and what
    /// the projection changed (`None` otherwise).
    pub projection: Option<GivenState>,
}

/// A state given to linearize about, and its projection onto the
/// model's constraints.
#[derive(Clone, Debug, PartialEq)]
pub struct GivenState {
    /// The coordinates asked for.
    pub q: Vec<f64>,
    /// The velocities asked for.
    pub qd: Vec<f64>,
    /// What the projection changed (`residual_before` is how far the given
    /// state was off the constraints).
    pub projection: Projection,
}

/// How an operating point at a static equilibrium was found.
#[derive(Clone, Debug, PartialEq)]
pub struct Equilibrium {
    /// The coordinates Newton's method started from.
    pub start: Vec<f64>,
    /// The indices of the coordinates it solved for (the others held).
    pub solved: Vec<usize>,
}

/// One column of `B`: an input of the dynamics held at a value.
#[derive(Clone, Debug, PartialEq)]
pub struct InputColumn {
    /// The input's index, in the model's order of inputs.
    pub input: usize,
    /// The input's name.
    pub name: String,
    /// Its value at the operating point.
    pub value: f64,
    /// Where the value comes from: `unbound` (held at 0), or the name of
    /// the constant that gives it (`--set push`, a scenario component).
    pub source: String,
}

/// How `A` was obtained.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum StateMatrixSource {
    /// From the model's derived Jacobians.
    DerivedJacobians,
    /// By central differences of `q̈` (a model without Jacobians).
    CentralDifferences,
}

impl StateMatrixSource {
    /// The source in words, as the reports write it.
    pub fn name(self) -> &'static str {
        match self {
            StateMatrixSource::DerivedJacobians => "derived Jacobians",
            StateMatrixSource::CentralDifferences => "central differences",
        }
    }
}

/// A model linearized about an operating point.
#[derive(Clone, Debug, PartialEq)]
pub struct Linearization {
    /// The coordinate names, then `dot(NAME)` for each velocity: the rows
    /// and columns of `A`.
    pub state_names: Vec<String>,
    /// `∂ẋ/∂x` (`2n × 2n`).
    pub a: DMatrix<f64>,
    /// `∂ẋ/∂u` (`2n ×` the number of [`Linearization::inputs`]).
    pub b: DMatrix<f64>,
    /// What each column of `B` is.
    pub inputs: Vec<InputColumn>,
    /// Where the model was linearized.
    pub operating_point: OperatingPoint,
    /// How `A` was obtained.
    pub source: StateMatrixSource,
    /// The modes of `A`, by increasing frequency; for a model with
    /// constraints, those of its motion on them (the `manifold` module).
    pub modes: Vec<Mode>,
    /// The model's constraints (empty without): `A` is then that of the
    /// constrained accelerations, and its modes those on the constraints.
    pub constraints: Vec<String>,
}

/// Why a model could not be linearized.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum LinearizeError {
    /// The operating point or an evaluation there failed (no equilibrium,
    /// a singular mass matrix, a value that is not finite, …), as it
    /// would fail a run.
    #[error(transparent)]
    Model(#[from] SimulationError),
    /// `A` is not finite, or its eigenvalues did not converge.
    #[error("no eigenvalues of A: {0}")]
    Eigenvalues(String),
    /// As many constraints as coordinates (or more): nothing moves.
    #[error(
        "the model has no free coordinates: its {} constraints ({}) fix all {} coordinates ({}); there is no motion to linearize",
        .constraints.len(),
        .constraints.join(", "),
        .coordinates.len(),
        .coordinates.join(", ")
    )]
    NoFreeCoordinates {
        /// The model's coordinates.
        coordinates: Vec<String>,
        /// Its constraints.
        constraints: Vec<String>,
    },
}

/// The linearization of `system` under `scenario` (its parameters, its
/// components, its initial coordinates) at `at`.
pub fn linearize<const N: usize, S: LagrangianSystem<N> + Clone>(
    system: &S,
    scenario: &Scenario,
    at: &At,
) -> Result<Linearization, LinearizeError> {
    let own = |names: Vec<&str>| names.into_iter().map(str::to_string).collect::<Vec<_>>();
    if system.constraint_count() >= N {
        return Err(LinearizeError::NoFreeCoordinates {
            coordinates: own(system.coordinate_names()),
            constraints: own(system.constraint_names()),
        });
    }
    let mut model = system.clone();
    (scenario.apply_parameters(&mut model)).map_err(SimulationError::Model)?;
    let mut problem = CrashProblem::new(&model, held_inputs(&scenario.inputs));
    // The dynamics itself: the stabilization only pulls a violated
    // constraint back, a motion off the manifold the modes leave out.
    problem.stabilization = Baumgarte::NONE;
    let (y, equilibrium, projection) = operating_state(&mut problem, scenario, at)?;
    let fault = |fault| {
        SimulationError::from(SolverError::Rhs {
            t: 0.0,
            error: fault,
        })
    };
    let qdd = problem.accelerations(0.0, &y.q, &y.v).map_err(fault)?;
    let (a, source) = state_matrix(&mut problem, &y).map_err(fault)?;
    let inputs = input_columns(&model, &problem.inputs);
    let b = input_matrix(&model, &problem.inputs, &y, &inputs).map_err(fault)?;
    let names = model.coordinate_names();
    let state_names: Vec<String> = (names.iter().map(|n| n.to_string()))
        .chain(names.iter().map(|n| format!("dot({n})")))
        .collect();
    let modes = match model.constraint_count() {
        0 => modes(&a),
        _ => modes(&manifold::restricted(&problem, &y, &a).map_err(fault)?),
    };
    let modes = modes.ok_or_else(|| {
        LinearizeError::Eigenvalues(match a.iter().position(|x| !x.is_finite()) {
            // Column-major: entry k is row k mod 2n of column k / 2n.
            Some(k) => {
                let (i, j) = (k % (2 * N), k / (2 * N));
                let (row, column) = (&state_names[i], &state_names[j]);
                format!("A[{row}, {column}] is {}", a[(i, j)])
            }
            None => "the Schur decomposition did not converge".into(),
        })
    })?;
    Ok(Linearization {
        state_names,
        modes,
        a,
        b,
        inputs,
        operating_point: OperatingPoint {
            q: y.q.as_slice().to_vec(),
            qd: y.v.as_slice().to_vec(),
            qdd: qdd.as_slice().to_vec(),
            equilibrium,
            projection,
        },
        source,
        constraints: model
            .constraint_names()
            .iter()
            .map(|n| n.to_string())
            .collect(),
    })
}

/// The name of the constant that holds an unbound input at 0.
const UNBOUND: &str = "unbound";

/// `inputs` with every unbound input bound to a constant 0 (as is every
/// derivative of an input held constant).
fn held_inputs(inputs: &BoundInputs) -> BoundInputs {
    let mut held = inputs.clone();
    for k in 0..held.bindings.len() {
        if held.bindings[k].is_none() {
            held.bindings[k] = Some(Binding {
                component: held.components.len(),
                port: Port::Value,
            });
            held.components.push(NamedComponent {
                name: UNBOUND.to_string(),
                component: Box::new(Constant { value: 0.0 }),
            });
            held.event_arguments.push(None);
        }
    }
    // Made anew, so that the added bindings are resolved.
    BoundInputs::new(
        held.components,
        held.bindings,
        held.event_arguments,
        held.input_names,
    )
}

/// The operating state, with the start and the solved coordinates of an
/// equilibrium, or the projection of a given state onto the model's
/// constraints (as `simulate` projects its initial state); the components
/// put in the state a run from it starts in.
fn operating_state<const N: usize, S: LagrangianSystem<N>>(
    problem: &mut CrashProblem<N, S>,
    scenario: &Scenario,
    at: &At,
) -> Result<(PhaseState<N>, Option<Equilibrium>, Option<GivenState>), SimulationError> {
    let mut q = SVector::<f64, N>::zeros();
    let mut v = SVector::<f64, N>::zeros();
    let mut given = None;
    let equilibrium = match at {
        At::State { q: q0, qd } => {
            q.copy_from_slice(q0);
            v.copy_from_slice(qd);
            if problem.system.constraint_count() > 0 {
                problem.start(0.0, &PhaseState::new(q, v))?;
                let (system, inputs) = (problem.system, &problem.inputs);
                let projection = constrained::project(system, inputs, 0.0, &mut q, &mut v)?;
                given = Some(GivenState {
                    q: q0.clone(),
                    qd: qd.clone(),
                    projection,
                });
            }
            None
        }
        At::Equilibrium => {
            for &(i, value) in &scenario.initial_coordinates {
                q[i] = value;
            }
            let free = match scenario.equilibrium.is_empty() {
                true => (0..N).collect(),
                false => scenario.equilibrium.clone(),
            };
            problem.start(0.0, &PhaseState::new(q, v))?;
            let start = q.as_slice().to_vec();
            q = static_equilibrium(problem, 0.0, q, &free)?;
            Some(Equilibrium {
                start,
                solved: free,
            })
        }
    };
    let y = PhaseState::new(q, v);
    problem.start(0.0, &y)?;
    Ok((y, equilibrium, given))
}

/// `A` from the derived Jacobians, or by central differences of `q̈`.
fn state_matrix<const N: usize, S: LagrangianSystem<N>>(
    problem: &mut CrashProblem<N, S>,
    y: &PhaseState<N>,
) -> Result<(DMatrix<f64>, StateMatrixSource), Fault> {
    let mut a = DMatrix::zeros(2 * N, 2 * N);
    a.view_mut((0, N), (N, N)).fill_with_identity();
    let (a_q, a_v, source) = match problem.acceleration_jacobians(0.0, y)? {
        Some((a_q, a_v)) => (a_q, a_v, StateMatrixSource::DerivedJacobians),
        None => {
            let (a_q, a_v) = differenced_jacobians(problem, y)?;
            (a_q, a_v, StateMatrixSource::CentralDifferences)
        }
    };
    a.view_mut((N, 0), (N, N)).copy_from(&a_q);
    a.view_mut((N, N), (N, N)).copy_from(&a_v);
    Ok((a, source))
}

/// `(∂q̈/∂q, ∂q̈/∂q̇)` by central differences.
fn differenced_jacobians<const N: usize, S: LagrangianSystem<N>>(
    problem: &CrashProblem<N, S>,
    y: &PhaseState<N>,
) -> Result<(SMatrix<f64, N, N>, SMatrix<f64, N, N>), Fault> {
    let mut a_q = SMatrix::<f64, N, N>::zeros();
    let mut a_v = SMatrix::<f64, N, N>::zeros();
    for k in 0..N {
        let along_q = |h: f64| {
            let mut q = y.q;
            q[k] += h;
            problem.accelerations(0.0, &q, &y.v)
        };
        a_q.set_column(k, &derivative(along_q, y.q[k])?);
        let along_v = |h: f64| {
            let mut v = y.v;
            v[k] += h;
            problem.accelerations(0.0, &y.q, &v)
        };
        a_v.set_column(k, &derivative(along_v, y.v[k])?);
    }
    Ok((a_q, a_v))
}

/// The derivative at 0 of `g(h)`, a function of a shift `h` of a value
/// `x`: central differences at `h` and `h/2` combined by Richardson
/// extrapolation (exact for a cubic, to rounding), `h = 10⁻³ max(1, |x|)`.
fn derivative<const N: usize>(
    g: impl Fn(f64) -> Result<SVector<f64, N>, Fault>,
    x: f64,
) -> Result<SVector<f64, N>, Fault> {
    let h = 1e-3 * x.abs().max(1.0);
    let central = |h: f64| -> Result<SVector<f64, N>, Fault> { Ok((g(h)? - g(-h)?) / (2.0 * h)) };
    let (coarse, fine) = (central(h)?, central(0.5 * h)?);
    Ok((4.0 * fine - coarse) / 3.0)
}

/// The inputs the dynamics calls that are held at a constant: the columns
/// of `B`, in input order.
fn input_columns<const N: usize, S: LagrangianSystem<N>>(
    model: &S,
    inputs: &BoundInputs,
) -> Vec<InputColumn> {
    let names = model.input_names();
    let mut called: Vec<usize> = model.input_sites().iter().map(|&(k, _)| k).collect();
    called.dedup();
    let constant = |k: usize| {
        let binding = inputs.bindings[k]?;
        let named = &inputs.components[binding.component];
        (named.component.kind() == Constant::KIND).then_some(named)
    };
    (called.into_iter())
        .filter_map(|k| {
            let named = constant(k)?;
            Some(InputColumn {
                input: k,
                name: names[k].to_string(),
                value: inputs.value(k, &[]),
                source: named.name.clone(),
            })
        })
        .collect()
}

/// `B`: the rows of `q̇` are 0, those of `q̈` its derivative with respect
/// to each input's value, by central differences.
fn input_matrix<const N: usize, S: LagrangianSystem<N>>(
    model: &S,
    inputs: &BoundInputs,
    y: &PhaseState<N>,
    columns: &[InputColumn],
) -> Result<DMatrix<f64>, Fault> {
    let mut b = DMatrix::zeros(2 * N, columns.len());
    for (j, column) in columns.iter().enumerate() {
        let shifted = |h: f64| {
            let held = Shifted {
                inputs,
                input: column.input,
                value: column.value + h,
            };
            accelerations(model, y, &held)
        };
        let d = derivative(shifted, column.value)?;
        b.view_mut((N, j), (N, 1)).copy_from(&d);
    }
    Ok(b)
}

/// `inputs` with input number `input` given `value`.
struct Shifted<'a> {
    inputs: &'a BoundInputs,
    input: usize,
    value: f64,
}

impl InputFunctions for Shifted<'_> {
    fn value(&self, input: usize, args: &[f64]) -> f64 {
        match input == self.input {
            true => self.value,
            false => self.inputs.value(input, args),
        }
    }
}

/// `q̈` at `y` with `inputs`; with the constraints' forces (without
/// stabilization) for a model with constraints.
fn accelerations<const N: usize, S: LagrangianSystem<N>>(
    model: &S,
    y: &PhaseState<N>,
    inputs: &impl InputFunctions,
) -> Result<SVector<f64, N>, Fault> {
    let (mass, forcing) = model.mass_matrix_and_forcing_pair(0.0, &y.q, &y.v, inputs);
    if model.constraint_count() > 0 {
        let state = (0.0, &y.q, &y.v);
        let solution = constrained::solve(model, inputs, Baumgarte::NONE, state, &mass, &forcing);
        return solution.map(|s| s.a);
    }
    solve_mass_matrix(mass, &forcing).ok_or_else(|| Fault::SingularMassMatrix {
        q: y.q.as_slice().to_vec(),
        qd: y.v.as_slice().to_vec(),
    })
}

#[cfg(test)]
mod tests;
