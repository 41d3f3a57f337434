//! What a host that advances a run itself needs (an FMU's co-simulation
//! step, a model-exchange solver): the run's initial state, the same as
//! [`super::simulate`] uses.

use super::{CrashProblem, SimulationError};
use crate::ode::PhaseState;
use crate::scenario::Scenario;
use lagrangian_runtime::LagrangianSystem;

/// The state a run of `scenario` starts from, with the components of
/// `problem` put in the state that goes with it: the scenario's initial
/// coordinates and velocities, the equilibrium coordinates solved for, the
/// state projected onto the model's constraints.
pub fn initial_state<const N: usize, S: LagrangianSystem<N>>(
    problem: &mut CrashProblem<N, S>,
    scenario: &Scenario,
) -> Result<PhaseState<N>, SimulationError> {
    super::initial_state(problem, scenario).map(|(y0, _)| y0)
}
