//! The check of a run's parameters at its initial state, before anything
//! is solved or integrated: a parameter too large for the model's
//! arithmetic (`m = 1e308`: `V = −∞` at the start) is named, rather than
//! found later as a non-finite right-hand side or an energy balance of
//! `∞ − ∞`.

use super::{CrashProblem, SimulationError};
use crate::ode::PhaseState;
use crate::scenario::Scenario;
use lagrangian_runtime::{InputFunctions, LagrangianSystem};
use nalgebra::SVector;

/// The scenario's initial coordinates and velocities (0 where it gives
/// none), before any equilibrium or projection.
pub(super) fn given_state<const N: usize>(scenario: &Scenario) -> PhaseState<N> {
    let mut q = SVector::<f64, N>::zeros();
    let mut v = SVector::<f64, N>::zeros();
    for &(i, value) in &scenario.initial_coordinates {
        q[i] = value;
    }
    for &(i, value) in &scenario.initial_velocities {
        v[i] = value;
    }
    PhaseState::new(q, v)
}

/// What of the model's energies is not finite at `y` (`t = 0`), in words;
/// `None` when both are.
fn non_finite<const N: usize, S: LagrangianSystem<N>, I: InputFunctions + ?Sized>(
    system: &S,
    inputs: &I,
    y: &PhaseState<N>,
) -> Option<String> {
    let energy = system.mechanical_energy(0.0, &y.q, &y.v, inputs);
    if !energy.potential.is_finite() {
        return Some(format!("the potential energy is {}", energy.potential));
    }
    if !energy.kinetic.is_finite() {
        return Some(format!("the kinetic energy is {}", energy.kinetic));
    }
    None
}

/// Refuses a scenario whose parameters make the model's energies at the
/// given initial state (`t = 0`, the components started there) not finite
/// where the values of `original` (the model before the scenario) make
/// them finite, naming those parameters. Any other non-finite start is
/// left to the run, whose errors name the expression at fault.
pub(super) fn check_parameters<const N: usize, S>(
    original: &S,
    problem: &mut CrashProblem<N, S>,
    scenario: &Scenario,
) -> Result<(), SimulationError>
where
    S: LagrangianSystem<N> + Clone,
{
    if scenario.parameters.is_empty() {
        return Ok(());
    }
    let y = given_state::<N>(scenario);
    problem.start(0.0, &y)?;
    let (model, inputs) = (problem.system, &problem.inputs);
    let Some(what) = non_finite(model, inputs, &y) else {
        return Ok(());
    };
    let names = model.parameter_names();
    let defaults = original.parameters();
    let culprits: Vec<String> = (scenario.parameters.iter())
        .filter(|&&(index, _)| {
            let mut restored = model.clone();
            restored
                .set_parameter(names[index], defaults[index])
                .is_ok()
                && non_finite(&restored, inputs, &y).is_none()
        })
        .map(|&(index, value)| format!("parameters.{} = {value:e}", names[index]))
        .collect();
    match culprits.is_empty() {
        true => Ok(()),
        false => Err(SimulationError::InitialState(format!(
            "{}: {what} at the initial state (finite with the spec's value): a value beyond the model's arithmetic",
            culprits.join(", ")
        ))),
    }
}
