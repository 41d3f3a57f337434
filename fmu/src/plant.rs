//! The simulated model behind an instance, at its dimension `N` but seen
//! through one object-safe trait ([`Plant`]): its time and state `(q, q̇, z)`
//! (`z` the components' internal states: a Bouc–Wen spring's `z`, the
//! energy each dissipative component has dissipated),
//! the derivatives and event indicators Model Exchange asks for, the events
//! it handles, and Co-Simulation's step with our integrator and events.

use crate::variables::Quantity;
use lagrangian_runtime::{
    Interpreted, InterpretedModel, LagrangianSystem, ModelError, WithDimension,
};
use lagrangian_sim::components::BoundInputs;
use lagrangian_sim::components::constant::Constant;
use lagrangian_sim::fault::Fault;
use lagrangian_sim::ode::tr_bdf2::AccelerationJacobians;
use lagrangian_sim::ode::{self, EventAction, OdeProblem, OdeVector, PhaseState};
use lagrangian_sim::scenario::{Columns, Scenario};
use lagrangian_sim::simulate::{CrashProblem, SimulationError, SolverError, stepwise};
use nalgebra::SVector;

/// Why a plant could not be made or do what the host asked. Each message
/// is what the FMU logs after the call's name.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum PlantError {
    /// A compiled model that is not the one of the resources' spec: what
    /// differs (`coordinates`, `parameter values`, …).
    #[error(
        "resources/model.lpm is not the spec this FMU binary was compiled from \
         (its {} differ)",
        .differ.join(", ")
    )]
    NotTheCompiledSpec {
        /// What differs, in words.
        differ: Vec<&'static str>,
    },
    /// The model refused: a dimension the interpreter does not run, a
    /// parameter value.
    #[error("{0}")]
    Model(ModelError),
    /// The components' internal states have no initial values.
    #[error("{0}")]
    Start(Fault),
    /// No initial state (static equilibrium, constraints).
    #[error("{0}")]
    Initialization(SimulationError),
    /// The model or a component failed to evaluate at `t`; `fault` is
    /// `None` for an event handler that stopped the run without saying
    /// why.
    #[error("at t = {t:e} s: {}", .fault.as_ref().map_or(String::new(), Fault::to_string))]
    Fault {
        /// When \[s\].
        t: f64,
        /// What failed.
        fault: Option<Fault>,
    },
    /// The integrator stopped.
    #[error("{0}")]
    Solver(SolverError),
    /// An input the host set that is not bound to a constant.
    #[error("input {input} is not bound to a constant")]
    InputNotBound {
        /// The input's index in the spec.
        input: usize,
    },
    /// A quantity that is neither a parameter nor an input.
    #[error("{quantity:?} cannot be set")]
    NotSettable {
        /// The quantity.
        quantity: Quantity,
    },
}

impl PlantError {
    /// `fault` at `t`.
    fn at(t: f64) -> impl FnOnce(Fault) -> PlantError {
        move |fault| PlantError::Fault {
            t,
            fault: Some(fault),
        }
    }
}

/// A model with its scenario, simulated step by step by a host.
pub trait Plant {
    /// A copy in the same state (for `fmi2GetFMUstate`).
    fn clone_box(&self) -> Box<dyn Plant>;
    /// The number of continuous states, `2N` and the components' internal
    /// states.
    fn state_count(&self) -> usize;
    /// The current time \[s\].
    fn time(&self) -> f64;
    /// Sets the time (Model Exchange).
    fn set_time(&mut self, t: f64);
    /// The states `(q, q̇, z)` into `x`.
    fn states(&self, x: &mut [f64]);
    /// Sets the states `(q, q̇, z)` from `x`.
    fn set_states(&mut self, x: &[f64]);
    /// Puts the model in the scenario's initial state (static equilibrium,
    /// components' start) with the parameters as they are set now.
    fn initialize(&mut self) -> Result<(), PlantError>;
    /// `(q̇, q̈, ż)` into `dx`.
    fn derivatives(&mut self, dx: &mut [f64]) -> Result<(), PlantError>;
    /// The number of event indicators: the components' events, then the
    /// model's switching functions.
    fn event_count(&self) -> usize;
    /// The event indicators into `g`.
    fn event_indicators(&mut self, g: &mut [f64]) -> Result<(), PlantError>;
    /// Handles the events whose indicators crossed (in their direction)
    /// since the last call or [`Plant::initialize`]; returns the
    /// descriptions of the events handled.
    fn handle_events(&mut self) -> Result<Vec<String>, PlantError>;
    /// Integrates to `t_end` with the scenario's method, tolerances and
    /// events; returns the descriptions of the events handled on the way.
    /// Each call starts a new step sequence (its first step estimated
    /// afresh); the components keep their state (contact, unloading, weld
    /// failure) from one call to the next.
    fn advance(&mut self, t_end: f64) -> Result<Vec<String>, PlantError>;
    /// The values of `quantities` at the current state into `out`.
    fn get(&mut self, quantities: &[Quantity], out: &mut [f64]) -> Result<(), PlantError>;
    /// Sets a parameter or an input.
    fn set(&mut self, quantity: Quantity, value: f64) -> Result<(), PlantError>;
}

/// How an FMU binary makes its plant of the model loaded from the
/// resources (compiled by the interpreter) under the scenario: [`plant`]
/// runs that model, [`compiled`] a macro-compiled one checked against it.
pub type PlantFactory = fn(InterpretedModel, &Scenario) -> Result<Box<dyn Plant>, PlantError>;

/// The plant of `model` under `scenario`, with the scenario's parameters,
/// run by the interpreter.
pub fn plant(model: InterpretedModel, scenario: &Scenario) -> Result<Box<dyn Plant>, PlantError> {
    model
        .with_dimension(Build { scenario })
        .map_err(PlantError::Model)?
}

/// The plant of the compiled model `S` (a `lagrangian!` or `lpm generate`
/// model) under `scenario`, with the scenario's parameters. `model`, the
/// spec of the resources, must be the one `S` was compiled from: the same
/// names and parameter values, else the error says what differs.
pub fn compiled<const N: usize, S>(
    model: InterpretedModel,
    scenario: &Scenario,
) -> Result<Box<dyn Plant>, PlantError>
where
    S: LagrangianSystem<N> + Default + Clone + 'static,
{
    let system = S::default();
    same_model(&system, &model)?;
    running(system, scenario)
}

/// `Err` naming what differs unless `compiled` has the names and the
/// parameter values of `model`.
fn same_model<const N: usize, S: LagrangianSystem<N>>(
    compiled: &S,
    model: &InterpretedModel,
) -> Result<(), PlantError> {
    fn names(list: &[String]) -> Vec<&str> {
        list.iter().map(String::as_str).collect()
    }
    let differences = [
        (
            "coordinates",
            compiled.coordinate_names() != names(model.coordinates()),
        ),
        (
            "parameters",
            compiled.parameter_names() != names(model.parameter_names()),
        ),
        (
            "inputs",
            compiled.input_names() != names(model.input_names()),
        ),
        (
            "outputs",
            compiled.output_names() != names(model.output_names()),
        ),
        (
            "parameter values",
            compiled.parameters() != model.parameters(),
        ),
        (
            "switching functions",
            compiled.switching_count() != model.switching_count(),
        ),
    ];
    let differ: Vec<&str> = (differences.iter())
        .filter_map(|&(what, differs)| differs.then_some(what))
        .collect();
    match differ.is_empty() {
        true => Ok(()),
        false => Err(PlantError::NotTheCompiledSpec { differ }),
    }
}

/// The plant of `system` under `scenario`, with the scenario's parameters.
fn running<const N: usize, S>(
    mut system: S,
    scenario: &Scenario,
) -> Result<Box<dyn Plant>, PlantError>
where
    S: LagrangianSystem<N> + Clone + 'static,
{
    (scenario)
        .apply_parameters(&mut system)
        .map_err(PlantError::Model)?;
    let mut inputs = scenario.inputs.clone();
    // The state has the internal states' length from the start, as the
    // count of continuous states the description declares.
    let mut y = PhaseState::zeros();
    y.z = inputs.initial_internal().map_err(PlantError::Start)?;
    Ok(Box::new(Run {
        model: system,
        inputs: Some(inputs),
        scenario: scenario.clone(),
        t: 0.0,
        y,
        armed: Vec::new(),
    }))
}

struct Build<'a> {
    scenario: &'a Scenario,
}

impl WithDimension for Build<'_> {
    type Output = Result<Box<dyn Plant>, PlantError>;

    fn run<const N: usize>(self, system: Interpreted<N>) -> Self::Output {
        running(system, self.scenario)
    }
}

/// [`Plant`] of the model `S` at dimension `N`.
#[derive(Clone)]
struct Run<const N: usize, S> {
    model: S,
    /// The bound inputs with the components' state; lent to a
    /// [`CrashProblem`] while one evaluates (see [`Run::with_problem`]).
    inputs: Option<BoundInputs>,
    scenario: Scenario,
    t: f64,
    y: PhaseState<N>,
    /// The event indicators after the last event (or the start): a crossing
    /// is a change from these.
    armed: Vec<f64>,
}

/// The values a sample derives from the state.
struct Derived<const N: usize> {
    a: SVector<f64, N>,
    outputs: Vec<f64>,
    columns: Vec<f64>,
    /// The multipliers `λ` and residuals of the model's constraints (empty
    /// without constraints).
    multipliers: Vec<f64>,
    residuals: Vec<f64>,
    /// `ż` (empty without internal states).
    internal_rates: Vec<f64>,
}

impl<const N: usize, S> Run<N, S>
where
    S: LagrangianSystem<N> + Clone + 'static,
{
    /// Runs `f` on the problem of the model with the current inputs, the
    /// components given the internal states of the current state.
    fn with_problem<R>(&mut self, f: impl FnOnce(&mut CrashProblem<N, S>) -> R) -> R {
        let mut inputs = (self.inputs.take()).expect("the inputs are put back after every use");
        inputs.load(&self.y.z);
        let mut problem = CrashProblem::new(&self.model, inputs);
        problem.stabilization = self.scenario.stabilization;
        let result = f(&mut problem);
        self.inputs = Some(problem.inputs);
        result
    }

    /// `(q̇, q̈, ż)` at the current state, as the simulator's right-hand
    /// side gives them.
    fn rates(&mut self) -> Result<PhaseState<N>, PlantError> {
        let (t, y) = (self.t, self.y);
        let mut dy = y;
        self.with_problem(|p| p.rhs(t, &y, &mut dy))
            .map_err(PlantError::at(t))?;
        Ok(dy)
    }

    fn derived(&mut self) -> Result<Derived<N>, PlantError> {
        let (t, y) = (self.t, self.y);
        let solved = self.with_problem(|p| p.accelerations_and_multipliers(t, &y.q, &y.v));
        let solved = solved.map_err(PlantError::at(t))?;
        let a = solved.a;
        let mut outputs = vec![0.0; self.model.output_names().len()];
        let columns = self.with_problem(|p| {
            (p.system).outputs(t, &y.q, &y.v, &a, &p.inputs, &mut outputs);
            p.component_values(t, &y.q, &y.v)
        });
        let columns = columns.map_err(PlantError::at(t))?;
        let internal_rates = match y.z.is_empty() {
            true => Vec::new(),
            false => self.rates()?.z.as_slice().to_vec(),
        };
        Ok(Derived {
            a,
            outputs,
            columns,
            internal_rates,
            multipliers: solved.multipliers,
            residuals: solved.residual,
        })
    }

    fn value(&self, quantity: Quantity, d: &Derived<N>) -> f64 {
        let crush = || self.scenario.crush.as_ref();
        let columns = Columns {
            q: self.y.q.as_slice(),
            v: self.y.v.as_slice(),
            a: d.a.as_slice(),
            outputs: &d.outputs,
            components: &d.columns,
            multipliers: &d.multipliers,
            residuals: &d.residuals,
        };
        match quantity {
            Quantity::Coordinate(i) => self.y.q[i],
            Quantity::Rate(i) => self.y.v[i],
            Quantity::Acceleration(i) => d.a[i],
            Quantity::Parameter(i) => self.model.parameters()[i],
            Quantity::Input(i) => self.input_constant(i).unwrap_or(f64::NAN),
            Quantity::Output(i) => d.outputs[i],
            Quantity::Crush => crush().map_or(f64::NAN, |c| c.value(&columns)),
            Quantity::Deceleration => match crush() {
                Some(c) if c.is_of_coordinates() => -c.of_coordinates(d.a.as_slice()),
                _ => f64::NAN,
            },
            Quantity::Column(i) => d.columns[i],
            Quantity::InternalRate(i) => d.internal_rates[i],
        }
    }

    /// Gives the constant an FMU input is bound to the value `value`;
    /// `None` for an input bound to nothing.
    fn set_input_constant(&mut self, input: usize, value: f64) -> Option<()> {
        let inputs = self.inputs.as_mut()?;
        let binding = inputs.bindings.get(input).copied().flatten()?;
        let constant = Box::new(Constant { value });
        inputs.replace(binding.component, constant).then_some(())
    }

    fn input_constant(&self, input: usize) -> Option<f64> {
        let inputs = self.inputs.as_ref()?;
        let binding = inputs.bindings.get(input).copied().flatten()?;
        let component = &inputs.components[binding.component].component;
        component.value(binding.port, &[]).ok()
    }

    /// The event indicators at `(t, y)`.
    fn indicators_at(&mut self, t: f64, y: PhaseState<N>) -> Result<Vec<f64>, PlantError> {
        let mut g = vec![0.0; self.event_count()];
        self.with_problem(|p| p.events(t, &y, &mut g))
            .map_err(PlantError::at(t))?;
        Ok(g)
    }

    /// The event indicators at the current state, each exactly zero given
    /// the sign it takes just after `t` (along `(q̇, q̈, ż)`), as the
    /// simulator's event tracker does at the start of a step sequence
    /// (`lagrangian_sim::ode::events`): an indicator that only touches zero
    /// at a state (a contact that begins at zero force, a crush rate that
    /// is zero at the start) has the sign of where it is going, so that a
    /// crossing is a change of that sign, never a touch of zero.
    fn signed_indicators(&mut self) -> Result<Vec<f64>, PlantError> {
        let mut g = self.indicators_at(self.t, self.y)?;
        if g.contains(&0.0) {
            let delta = 1e-9 * self.t.abs().max(1.0);
            let rates = self.rates()?;
            let mut ahead = self.y;
            ahead.set_combination(&self.y, &[(delta, &rates)]);
            let probe = self.indicators_at(self.t + delta, ahead)?;
            for (g, p) in g.iter_mut().zip(probe) {
                if *g == 0.0 {
                    *g = p;
                }
            }
        }
        Ok(g)
    }

    /// Records the indicators ([`Run::signed_indicators`]) as the reference
    /// for the next crossing, so that the crossing just handled (or a zero
    /// at the start) is not seen again.
    fn arm(&mut self) -> Result<(), PlantError> {
        self.armed = self.signed_indicators()?;
        Ok(())
    }

    /// Events recorded by a problem, in words.
    fn descriptions(records: &[lagrangian_sim::simulate::EventRecord]) -> Vec<String> {
        (records.iter())
            .map(|e| format!("t = {:e} s: {}: {}", e.t, e.component, e.description))
            .collect()
    }
}

impl<const N: usize, S> Plant for Run<N, S>
where
    S: LagrangianSystem<N> + Clone + 'static,
{
    fn clone_box(&self) -> Box<dyn Plant> {
        Box::new(self.clone())
    }

    fn state_count(&self) -> usize {
        2 * N + self.y.z.len()
    }

    fn time(&self) -> f64 {
        self.t
    }

    fn set_time(&mut self, t: f64) {
        self.t = t;
    }

    fn states(&self, x: &mut [f64]) {
        x[..N].copy_from_slice(self.y.q.as_slice());
        x[N..2 * N].copy_from_slice(self.y.v.as_slice());
        x[2 * N..].copy_from_slice(self.y.z.as_slice());
    }

    fn set_states(&mut self, x: &[f64]) {
        self.y.q.copy_from_slice(&x[..N]);
        self.y.v.copy_from_slice(&x[N..2 * N]);
        self.y.z.as_mut_slice().copy_from_slice(&x[2 * N..]);
    }

    fn initialize(&mut self) -> Result<(), PlantError> {
        let scenario = self.scenario.clone();
        let y0 = self.with_problem(|p| stepwise::initial_state(p, &scenario));
        self.y = y0.map_err(PlantError::Initialization)?;
        self.arm()
    }

    fn derivatives(&mut self, dx: &mut [f64]) -> Result<(), PlantError> {
        let rates = self.rates()?;
        dx[..N].copy_from_slice(rates.q.as_slice());
        dx[N..2 * N].copy_from_slice(rates.v.as_slice());
        dx[2 * N..].copy_from_slice(rates.z.as_slice());
        Ok(())
    }

    fn event_count(&self) -> usize {
        let inputs = self.inputs.as_ref().map_or(0, |i| i.event_count());
        inputs + self.model.switching_count()
    }

    /// Signed as [`Run::signed_indicators`] signs them: the host sees an
    /// indicator cross zero where the FMU sees it cross, never one resting
    /// at zero (a contact that begins at zero force, at the start).
    ///
    /// An indicator armed at exactly zero even along the probe (a crush
    /// rate of 1e-12 m/s at a located peak moves the crush by less than its
    /// ulp) takes the first non-zero value the host's integration reads as
    /// its reference: as the simulator's event tracker takes the value at
    /// the end of the first step after an event, so that a crossing from
    /// there (reloading past the peak) is one.
    fn event_indicators(&mut self, g: &mut [f64]) -> Result<(), PlantError> {
        let now = self.signed_indicators()?;
        for (armed, &value) in self.armed.iter_mut().zip(&now) {
            if *armed == 0.0 {
                *armed = value;
            }
        }
        g.copy_from_slice(&now);
        Ok(())
    }

    fn handle_events(&mut self) -> Result<Vec<String>, PlantError> {
        // Signed as the reference was: an indicator that is zero at the
        // state it was armed at (a crush element starting in contact at
        // zero force) has not crossed.
        let now = self.signed_indicators()?;
        let (t, mut y) = (self.t, self.y);
        let armed = std::mem::take(&mut self.armed);
        let handled = self.with_problem(|p| {
            for (k, (&before, &after)) in armed.iter().zip(&now).enumerate() {
                if p.event_direction(k).crosses(before, after)
                    && p.on_event(k, t, &mut y) == EventAction::Stop
                {
                    let fault = p.failure.take();
                    return Err(PlantError::Fault { t, fault });
                }
            }
            // The state after the events, back onto the model's
            // constraints (if it has any) that the integration between
            // events holds only up to the stabilization's drift.
            p.project(t, &mut y).map_err(PlantError::at(t))?;
            Ok(Self::descriptions(&p.events))
        })?;
        self.y = y;
        self.arm()?;
        Ok(handled)
    }

    fn advance(&mut self, t_end: f64) -> Result<Vec<String>, PlantError> {
        let (t, y) = (self.t, self.y);
        let (method, options) = (self.scenario.method, self.scenario.options);
        let (outcome, events) = self.with_problem(|p| {
            let outcome = ode::integrate(method, p, (t, y), t_end, &options, &mut |_, _| {});
            let failure = p.failure.take();
            (outcome.map(|o| (o, failure)), Self::descriptions(&p.events))
        });
        let (outcome, failure) = outcome.map_err(PlantError::Solver)?;
        if let Some(fault) = failure {
            return Err(PlantError::at(outcome.t)(fault));
        }
        self.t = outcome.t;
        self.y = outcome.y;
        Ok(events)
    }

    fn get(&mut self, quantities: &[Quantity], out: &mut [f64]) -> Result<(), PlantError> {
        let derived = self.derived()?;
        for (value, &quantity) in out.iter_mut().zip(quantities) {
            *value = self.value(quantity, &derived);
        }
        Ok(())
    }

    fn set(&mut self, quantity: Quantity, value: f64) -> Result<(), PlantError> {
        match quantity {
            Quantity::Parameter(i) => {
                let name = self.model.parameter_names()[i].to_string();
                self.model
                    .set_parameter(&name, value)
                    .map_err(PlantError::Model)
            }
            Quantity::Input(i) => {
                (self.set_input_constant(i, value)).ok_or(PlantError::InputNotBound { input: i })
            }
            other => Err(PlantError::NotSettable { quantity: other }),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn each_error_reads_as_the_fmu_logs_it() {
        let fault = Fault::NonFinite {
            output: "f[x]".to_string(),
            value: f64::NAN,
            q: vec![0.0],
            qd: vec![0.0],
        };
        let at = |fault| PlantError::Fault { t: 0.5, fault };
        assert_eq!(at(Some(fault)).to_string(), "at t = 5e-1 s: f[x] is NaN");
        assert_eq!(at(None).to_string(), "at t = 5e-1 s: ");
        assert_eq!(
            PlantError::InputNotBound { input: 2 }.to_string(),
            "input 2 is not bound to a constant"
        );
        let crush = PlantError::NotSettable {
            quantity: Quantity::Crush,
        };
        assert_eq!(crush.to_string(), "Crush cannot be set");
    }
}
