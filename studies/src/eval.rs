//! A model evaluated at one state (what `lpm eval` prints): `M`, `f`, the
//! accelerations `q̈` and, for a constrained spec, the multipliers `λ`, by
//! the interpreter.
//!
//! `q̈` comes from the solve `simulate` uses: `M q̈ = f`, or with
//! constraints `M q̈ = f + Gᵀλ`, `G q̈ = γ − 2α ġ − β² g`
//! ([`lagrangian_sim::simulate::constrained::solve`]) with the scenario's
//! Baumgarte stabilization (`[constraints] alpha`, `beta`; without
//! `--scenario` the default a scenario has), so that it is what a run's
//! right-hand side gives at the state: on the constraints (`g = 0`,
//! `ġ = 0`) the stabilization's terms vanish. The residuals `g` and rates
//! `ġ` are reported beside, so that a state off the constraints shows.

use crate::error::StudyError;
use crate::mass;
use lagrangian_runtime::constrained::Baumgarte;
use lagrangian_runtime::nalgebra::{SMatrix, SVector};
use lagrangian_runtime::{
    ConstantInputs, InputFunctions, Interpreted, InterpretedModel, LagrangianSystem, NoInputs,
    WithDimension,
};
use lagrangian_sim::components::BoundInputs;
use lagrangian_sim::fault::Fault;
use lagrangian_sim::files::Files;
use lagrangian_sim::scenario::{ModelNames, Override, Scenario, Setting};
use lagrangian_sim::simulate::FailureKind;
use lagrangian_sim::simulate::constrained;

/// `q̈` at one state and, with constraints, the multipliers `λ` and the
/// constraints' residuals `g` and rates `ġ` there (in the model's order of
/// constraints; empty without).
#[derive(Clone, Debug, PartialEq)]
pub struct Accelerations {
    /// `q̈`, one per coordinate.
    pub qdd: Vec<f64>,
    /// `λ`, one per constraint: `Gᵀλ` is the constraints' generalized force.
    pub multipliers: Vec<f64>,
    /// `g`, one per constraint.
    pub residuals: Vec<f64>,
    /// `ġ = G q̇ + g_t`, one per constraint.
    pub rates: Vec<f64>,
}

/// [`Accelerations`] at each of `states`, by the solve `simulate` uses
/// (see the module's doc): `M q̈ = f`, or with constraints
/// `M q̈ = f + Gᵀλ`, `G q̈ = γ − 2α ġ − β² g` with `stabilization`'s `α`
/// and `β` ([`constrained::DEFAULT_STABILIZATION`] is a scenario's default).
pub fn accelerations(
    model: &InterpretedModel,
    states: &[mass::State],
    inputs: &dyn InputFunctions,
    stabilization: Baumgarte,
) -> Result<Vec<Accelerations>, StudyError> {
    let mut dynamics = Vec::with_capacity(states.len());
    for &state in states {
        dynamics.push(evaluate(model, state, inputs)?);
    }
    let solve = Solve {
        states,
        dynamics: &dynamics,
        inputs,
        stabilization,
        coordinates: model.coordinates(),
    };
    model
        .clone()
        .with_dimension(solve)
        .map_err(StudyError::model)?
}

/// The work of [`accelerations`] on the model as an `Interpreted<N>`.
struct Solve<'a> {
    states: &'a [mass::State<'a>],
    /// `M` (row-major) and `f` at each state.
    dynamics: &'a [(Vec<f64>, Vec<f64>)],
    inputs: &'a dyn InputFunctions,
    stabilization: Baumgarte,
    coordinates: &'a [String],
}

impl WithDimension for Solve<'_> {
    type Output = Result<Vec<Accelerations>, StudyError>;

    fn run<const N: usize>(self, system: Interpreted<N>) -> Self::Output {
        let solve = |(&(t, q, qd), (mass, forcing)): (&mass::State, &(Vec<f64>, Vec<f64>))| {
            let q = SVector::<f64, N>::from_column_slice(q);
            let v = SVector::<f64, N>::from_column_slice(qd);
            let mass = SMatrix::<f64, N, N>::from_row_slice(mass);
            let forcing = SVector::<f64, N>::from_column_slice(forcing);
            if system.constraint_count() == 0 {
                let qdd = (system.solve_mass(&mass, &forcing))
                    .filter(|a| a.iter().all(|x| x.is_finite()))
                    .ok_or_else(|| singular(t, q.as_slice()))?;
                return Ok(Accelerations {
                    qdd: qdd.as_slice().to_vec(),
                    multipliers: Vec::new(),
                    residuals: Vec::new(),
                    rates: Vec::new(),
                });
            }
            let state = (t, &q, &v);
            let solution = constrained::solve(
                &system,
                self.inputs,
                self.stabilization,
                state,
                &mass,
                &forcing,
            )
            .map_err(|fault| fault_failure(&fault, t, self.coordinates))?;
            Ok(Accelerations {
                qdd: solution.a.as_slice().to_vec(),
                residuals: solution.values.residual().to_vec(),
                rates: solution.values.rate(v.as_slice()),
                multipliers: solution.lambda,
            })
        };
        self.states.iter().zip(self.dynamics).map(solve).collect()
    }
}

/// The failure of a singular or indefinite `M` at `q`.
fn singular(t: f64, q: &[f64]) -> StudyError {
    StudyError::run(
        FailureKind::SingularMassMatrix,
        format!("the mass matrix is singular or not positive definite at t = {t}, q = {q:?}"),
    )
}

/// The failure of the constrained solve, of the kind a run's failure on
/// the same fault has.
fn fault_failure(fault: &Fault, t: f64, coordinates: &[String]) -> StudyError {
    let kind = FailureKind::of_fault(fault);
    // A non-finite value's message names no state; the others name `q`.
    let at = match (fault, fault.state()) {
        (Fault::NonFinite { .. }, Some((q, _))) => {
            format!(", {}", lagrangian_sim::fault::named_values(coordinates, q))
        }
        _ => String::new(),
    };
    StudyError::run(
        kind,
        format!("the constrained solve at t = {t}{at}: {fault}"),
    )
}

/// The state `Q1,…,QN,V1,…,VN` given to `flag`: two values per
/// coordinate.
pub fn parse_state(flag: &str, text: &str, coordinates: &[String]) -> Result<Vec<f64>, StudyError> {
    let values = (text.split(','))
        .map(|v| {
            v.trim()
                .parse::<f64>()
                .map_err(|_| StudyError::usage(format!("{flag}: `{}` is not a number", v.trim())))
        })
        .collect::<Result<Vec<f64>, StudyError>>()?;
    let n = coordinates.len();
    if values.len() != 2 * n {
        return Err(StudyError::usage(format!(
            "{flag} needs {} values (coordinates {} then their velocities), got {}",
            2 * n,
            coordinates.join(", "),
            values.len()
        )));
    }
    Ok(values)
}

/// `M` (row-major) and `f` at `state`, finite.
pub fn evaluate(
    model: &InterpretedModel,
    (t, q, qd): mass::State,
    inputs: &dyn InputFunctions,
) -> Result<(Vec<f64>, Vec<f64>), StudyError> {
    let n = model.dimension();
    let (mut mass, mut forcing) = (vec![0.0; n * n], vec![0.0; n]);
    model
        .evaluate_dynamics(t, q, qd, inputs, &mut mass, &mut forcing)
        .map_err(|e| StudyError::evaluation(e.to_string()))?;
    if mass.iter().chain(&forcing).any(|v| !v.is_finite()) {
        return Err(StudyError::evaluation(format!(
            "M or f is not finite at t = {t}, state {q:?}, {qd:?}"
        )));
    }
    Ok((mass, forcing))
}

/// The inputs a state is evaluated with, the indices of the parameters set
/// and the stabilization of the constraints.
pub type Bound = (Box<dyn InputFunctions>, Vec<usize>, Baumgarte);

/// The scenario at `path` (with `settings`) applied to `model`: its
/// parameters set, its components bound to the inputs and put in the state
/// a run from `state` starts in. Returns the inputs, the indices of the
/// parameters it sets and its stabilization of the constraints. The
/// scenario and its tables are read from `files`.
pub fn scenario_inputs(
    files: &dyn Files,
    model: &mut InterpretedModel,
    path: &std::path::Path,
    settings: &[Override],
    (t, q, qd): mass::State,
) -> Result<Bound, StudyError> {
    let names = ModelNames::of_interpreted(model);
    let scenario =
        Scenario::read(files, path, &names, settings).map_err(|e| StudyError::scenario(&e))?;
    for &(i, value) in &scenario.parameters {
        model
            .set_parameter(&names.parameters[i], value)
            .map_err(|e| StudyError::usage(e.to_string()))?;
    }
    let mut arguments = vec![0.0; model.input_sites().iter().map(|s| s.1).sum()];
    // A state of the wrong dimension fails here, before the components start.
    model
        .evaluate_input_arguments(t, q, qd, &NoInputs, &mut arguments)
        .map_err(|e| StudyError::evaluation(e.to_string()))?;
    let evaluate = |inputs: &BoundInputs, out: &mut [f64]| {
        let _ = model.evaluate_input_arguments(t, q, qd, inputs, out);
    };
    let mut inputs = scenario.inputs.clone();
    let sites = model.input_sites().len();
    inputs
        .start_settled(&mut arguments, sites, evaluate, |_| Ok(()))
        .map_err(|fault| StudyError::evaluation(fault.to_string()))?;
    let set = scenario.parameters.iter().map(|&(i, _)| i).collect();
    Ok((Box::new(inputs), set, scenario.stabilization))
}

/// Applies the `--set` settings: parameters to the model, input constants
/// to the inputs returned, with the indices of the parameters set. Every
/// input the dynamics calls needs a value.
pub fn apply_settings(
    model: &mut InterpretedModel,
    settings: &[Override],
) -> Result<(Box<dyn InputFunctions>, Vec<usize>), StudyError> {
    let names = ModelNames::of_interpreted(model);
    let mut inputs = vec![None; names.inputs.len()];
    let mut set = Vec::new();
    for setting in settings {
        match setting
            .setting(&names)
            .map_err(|e| StudyError::usage(e.to_string()))?
        {
            Setting::Parameter { name, value } => {
                model
                    .set_parameter(&name, value)
                    .map_err(|e| StudyError::usage(e.to_string()))?;
                set.extend(names.parameters.iter().position(|p| *p == name));
            }
            Setting::InputConstant { name, value } => {
                if let Some(k) = names.inputs.iter().position(|i| *i == name) {
                    inputs[k] = Some(value);
                }
            }
            Setting::Scale { key, factor } if !key.contains('.') => {
                let k = names.parameters.iter().position(|p| *p == key);
                let value = k.map(|k| model.parameters()[k] * factor);
                model
                    .set_parameter(&key, value.unwrap_or(f64::NAN))
                    .map_err(|e| StudyError::usage(e.to_string()))?;
                set.extend(k);
            }
            Setting::Entry { key, .. } | Setting::Scale { key, .. } => {
                return Err(StudyError::usage(format!(
                    "--set {key}: eval takes parameters and input constants (scenario entries need --scenario)"
                )));
            }
        }
    }
    // The inputs the dynamics calls: those of its input sites.
    let called = |k: usize| model.input_sites().iter().any(|&(input, _)| input == k);
    let missing: Vec<&str> = (names.inputs.iter().enumerate())
        .filter(|&(k, _)| inputs[k].is_none() && called(k))
        .map(|(_, name)| name.as_str())
        .collect();
    if !missing.is_empty() {
        return Err(StudyError::usage(format!(
            "input function(s) {} have no value; give constants with --set NAME=VALUE or use --scenario",
            missing.join(", ")
        )));
    }
    let constants = ConstantInputs(inputs.into_iter().map(|v| v.unwrap_or(f64::NAN)).collect());
    Ok((Box::new(constants), set))
}
