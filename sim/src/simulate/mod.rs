//! Running a scenario: static equilibrium, integration with events, output
//! samples, summary metrics.

mod channels;
pub mod constrained;
mod criteria_channels;
mod equilibrium;
mod initial;
mod kink_rates;
mod kinks;
mod metrics;
mod needs;
pub mod output_motion;
mod problem;
mod rates;
pub mod stepwise;
mod stops;
mod summary;
#[cfg(test)]
mod tests;

pub use crate::failure::FailureKind;
pub use crate::scenario::options::SampleAccelerations;
pub use crate::scenario::options::TimeKinks;
pub use channels::{ACCELERATION_METRICS, CHANNEL_METRICS, ChannelSummary, Channels, metric_names};
pub use constrained::{ConstraintReport, Projection};
pub use equilibrium::static_equilibrium;
pub use metrics::{EnergyPoint, Metrics, SampleView};
pub use problem::{CrashProblem, EventRecord};
pub use summary::{CellError, Field, Metric, Row, Summary, Text, Value};

use crate::fault::Fault;
use crate::ode::{self, DenseStep, Method, Part, PhaseState, Stats};
use crate::scenario::{MAX_SAMPLES, Scenario};
use crate::warning::{self, Warning};
use lagrangian_runtime::{LagrangianSystem, ModelError};
use nalgebra::SVector;

/// Why the integration of a run stopped: the solver's reasons, with the
/// model's [`Fault`] for a failed evaluation.
pub type SolverError = ode::SolverError<Fault>;

/// The state and derived quantities at one output time.
#[derive(Clone, Debug, PartialEq)]
pub struct Sample {
    /// Time since the start of the run \[s\].
    pub t: f64,
    /// Coordinates, in the model's order and units (\[m\] or \[rad\]).
    pub q: Vec<f64>,
    /// Velocities `q̇` ([m/s] or [rad/s]).
    pub v: Vec<f64>,
    /// Accelerations `q̈` ([m/s²] or [rad/s²]): solved, or the derivative
    /// of the step's dense output where that is as accurate (see
    /// [`SampleAccelerations`]).
    pub a: Vec<f64>,
    /// Kinetic energy `T` \[J\].
    pub kinetic: f64,
    /// Potential energy `V` \[J\].
    pub potential: f64,
    /// Energy dissipated by `D` since the start \[J\].
    pub dissipated: f64,
    /// Work of the generalized forces since the start \[J\].
    pub external_work: f64,
    /// Values of the inputs the dynamics calls (see [`SimulationResult::input_columns`]).
    pub inputs: Vec<f64>,
    /// Values of the model's outputs (`output NAME [unit] = expr;`), in the
    /// order of [`SimulationResult::output_columns`], at the accelerations
    /// [`Sample::a`].
    pub outputs: Vec<f64>,
    /// Values of the components' columns (see
    /// [`SimulationResult::component_columns`]).
    pub components: Vec<f64>,
    /// The multiplier `λ` of each of the model's constraints (empty
    /// without constraints), in the order of [`ConstraintReport::names`].
    pub multipliers: Vec<f64>,
    /// The residual `g` of each of the model's constraints (empty without
    /// constraints), likewise.
    pub residuals: Vec<f64>,
    /// The crush channel's crush, rate and acceleration (compression
    /// positive), where the scenario names one: what the summary's crush
    /// metrics read of this sample.
    pub crush: Option<[f64; 3]>,
}

impl Sample {
    /// The crush, rate and acceleration of `crush` (the scenario's crush
    /// channel) at this sample: as the run recorded them
    /// ([`Sample::crush`]), else those of its coordinates (NaN for an
    /// output term, whose rates a sample does not keep).
    pub fn crush_motion(&self, crush: &crate::scenario::Signal) -> [f64; 3] {
        self.crush.unwrap_or_else(|| {
            let [q, v, a] = [&self.q, &self.v, &self.a].map(|x| crush.of_coordinates(x));
            [crush.plus_offset(q), v, a]
        })
    }

    /// The columns a channel's signal reads.
    pub fn columns(&self) -> crate::scenario::Columns<'_> {
        crate::scenario::Columns {
            q: &self.q,
            v: &self.v,
            a: &self.a,
            outputs: &self.outputs,
            components: &self.components,
            multipliers: &self.multipliers,
            residuals: &self.residuals,
        }
    }
}

/// Everything a run produced.
#[derive(Clone, Debug)]
pub struct SimulationResult {
    /// The model's name (the spec's `model` / the system's type).
    pub model: String,
    /// The coordinate names, in the order of [`Sample::q`].
    pub coordinates: Vec<String>,
    /// The input name of each column of [`Sample::inputs`]: one per input
    /// call of the dynamics, so an input called twice is there twice.
    /// Their units travel separately, in `report::Units` (the writer, above this module).
    pub input_columns: Vec<String>,
    /// The name of each of the model's outputs, in the order of
    /// [`Sample::outputs`]; their units travel in `report::Units` (the writer, above this module).
    pub output_columns: Vec<String>,
    /// The name and unit of each column of [`Sample::components`]:
    /// `NAME.QUANTITY` of a scenario component (`front_end.force`, `N`).
    pub component_columns: Vec<(String, Option<String>)>,
    /// The coordinates at the start (after the static-equilibrium solve).
    pub initial_q: Vec<f64>,
    /// The output samples, at multiples of the scenario's output interval
    /// from 0 to the end of the run (one within half an interval of
    /// `t_end` is moved onto it).
    pub samples: Vec<Sample>,
    /// The solver's counts of steps and evaluations.
    pub stats: Stats,
    /// The crash components' events, in time order.
    pub events: Vec<EventRecord>,
    /// The crash metrics of the run.
    pub summary: Summary,
    /// The integration method the scenario chose.
    pub method: Method,
    /// What looked wrong in the run, in the order found (empty for a
    /// clean run).
    pub warnings: Vec<Warning>,
    /// The constraints' projection, stabilization and drift, for a model
    /// with constraints.
    pub constraints: Option<ConstraintReport>,
}

/// Why a run failed.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum SimulationError {
    /// A scenario value does not apply to the model.
    #[error("{0}")]
    Model(ModelError),
    /// Newton's method found no static equilibrium.
    #[error("no static equilibrium: {0}")]
    Equilibrium(String),
    /// The initial state cannot be projected onto the constraints (one is
    /// not satisfiable near it, or some are redundant).
    #[error("{0}")]
    Constraints(String),
    /// The model's energies are not finite at the initial state (a
    /// parameter beyond the model's arithmetic, named where one is).
    #[error("{0}")]
    InitialState(String),
    /// The integration stopped; `reached` is where its last accepted step
    /// ended (`None` when it failed before the first step).
    #[error("integration failed: {error}")]
    Solver {
        /// Why the solver stopped.
        error: SolverError,
        /// The end of the last accepted step, when there was one.
        reached: Option<Box<Reached>>,
    },
}

/// The state at the end of a run's last accepted step.
#[derive(Clone, Debug, PartialEq)]
pub struct Reached {
    /// Where the step ended \[s\].
    pub t: f64,
    /// The coordinates there (\[m\] or \[rad\]).
    pub q: Vec<f64>,
    /// The velocities there ([m/s] or [rad/s]).
    pub qd: Vec<f64>,
}

impl SimulationError {
    /// The kind of failure, which decides `lpm`'s exit status and a
    /// sweep's `status` column.
    pub fn kind(&self) -> FailureKind {
        match self {
            SimulationError::Model(_)
            | SimulationError::Constraints(_)
            | SimulationError::InitialState(_) => FailureKind::Scenario,
            SimulationError::Equilibrium(_) => FailureKind::NoEquilibrium,
            SimulationError::Solver { error, .. } => match error {
                SolverError::StepSizeUnderflow { .. }
                | SolverError::NewtonFailure { .. }
                | SolverError::SingularIterationMatrix { .. } => FailureKind::StepSizeUnderflow,
                SolverError::MaxSteps { .. } => FailureKind::MaxSteps,
                SolverError::NonFinite { .. } => FailureKind::NonFinite,
                SolverError::EventNotLocated { .. } => FailureKind::EventNotLocated,
                SolverError::InvalidOptions(_) => FailureKind::Scenario,
                SolverError::Rhs { error: fault, .. } => FailureKind::of_fault(fault),
            },
        }
    }

    /// The fault inside, when a model evaluation failed.
    pub fn fault(&self) -> Option<&Fault> {
        match self {
            SimulationError::Solver {
                error: SolverError::Rhs { error: fault, .. },
                ..
            } => Some(fault),
            _ => None,
        }
    }

    /// Where a failed integration's last accepted step ended.
    pub fn reached(&self) -> Option<&Reached> {
        match self {
            SimulationError::Solver { reached, .. } => reached.as_deref(),
            _ => None,
        }
    }
}

impl From<SolverError> for SimulationError {
    fn from(e: SolverError) -> Self {
        SimulationError::Solver {
            error: e,
            reached: None,
        }
    }
}

/// Simulates `system` under `scenario` (the scenario's parameter overrides are
/// applied to a copy of `system`).
pub fn simulate<const N: usize, S: LagrangianSystem<N> + Clone>(
    system: &S,
    scenario: &Scenario,
) -> Result<SimulationResult, SimulationError> {
    let (model, run) = run(system, scenario, true)?;
    let input_columns = model
        .input_sites()
        .iter()
        .map(|&(input, _)| model.input_names()[input].to_string())
        .collect();
    Ok(SimulationResult {
        model: model.model_name().to_string(),
        coordinates: model
            .coordinate_names()
            .iter()
            .map(|s| s.to_string())
            .collect(),
        input_columns,
        output_columns: model.output_names().iter().map(|s| s.to_string()).collect(),
        component_columns: scenario.inputs.columns(),
        initial_q: run.initial_q,
        samples: run.samples,
        stats: run.stats,
        events: run.events,
        summary: run.summary,
        method: scenario.method,
        warnings: run.warnings,
        constraints: run.constraints,
    })
}

/// The summary of a run only — what a sweep records: the same numbers as
/// `simulate(…).summary`, without keeping the samples; each sample
/// evaluates only what the summary and the scenario's channels read (the
/// outputs, say, only for a channel of them).
pub fn simulate_summary<const N: usize, S: LagrangianSystem<N> + Clone>(
    system: &S,
    scenario: &Scenario,
) -> Result<Summary, SimulationError> {
    run(system, scenario, false).map(|(_, run)| run.summary)
}

/// What a run produced.
struct Run {
    initial_q: Vec<f64>,
    samples: Vec<Sample>,
    stats: Stats,
    events: Vec<EventRecord>,
    summary: Summary,
    warnings: Vec<Warning>,
    constraints: Option<ConstraintReport>,
}

/// Runs the scenario, keeping the samples if `keep`; returns the model with
/// the scenario's parameters.
fn run<const N: usize, S: LagrangianSystem<N> + Clone>(
    system: &S,
    scenario: &Scenario,
    keep: bool,
) -> Result<(S, Run), SimulationError> {
    let model = with_parameters(system, scenario)?;
    let mut problem = CrashProblem::new(&model, scenario.inputs.clone());
    problem.stabilization = scenario.stabilization;
    problem.time_kinks(scenario.time_kinks);
    initial::check_parameters(system, &mut problem, scenario)?;
    let (y0, projection) = initial_state(&mut problem, scenario)?;
    let metrics = Metrics::new(scenario, y0.q.as_slice());
    let needs = needs::Needs::of(scenario, keep, problem.system.constraint_count());
    let outputs = model.output_names().len();
    let dense = rates::DenseAccelerations::of(&problem, scenario.accelerations);
    let mut sampler = Sampler::new(scenario, metrics, (needs, outputs, dense));
    sampler.start(&mut problem, &y0);
    let outcome = ode::integrate(
        scenario.method,
        &mut problem,
        (0.0, y0),
        scenario.t_end,
        &scenario.options,
        &mut |problem, step| sampler.observe(problem, step),
    )
    .map_err(|error| SimulationError::Solver {
        error,
        reached: sampler.reached(),
    })?;
    if let Some(fault) = problem.failure.take() {
        return Err(SolverError::Rhs {
            t: outcome.t,
            error: fault,
        }
        .into());
    }
    if let Some(e) = sampler.error {
        return Err(e.into());
    }
    let weld = problem.inputs.weld_failure(scenario.weld.as_deref());
    let end_of_contact = problem.inputs.end_of_contact(&scenario.contact);
    let mut summary = sampler.metrics.finish(&outcome.stats, weld, end_of_contact);
    summary.dissipated_by =
        (problem.dissipated_energies(outcome.t, &outcome.y)).map_err(|error| SolverError::Rhs {
            t: outcome.t,
            error,
        })?;
    let mut warnings = run_warnings(scenario, &sampler.metrics, &summary);
    let components: Vec<String> = (scenario.inputs.columns().into_iter())
        .map(|(name, _)| name)
        .collect();
    let non_finite = sampler
        .metrics
        .non_finite_warnings(&model.output_names(), &components);
    warnings.extend(non_finite);
    let constraints = projection.map(|projection| ConstraintReport {
        names: own(model.constraint_names()),
        projection,
        stabilization: scenario.stabilization,
        drift: sampler.drift.clone(),
    });
    let run = Run {
        initial_q: y0.q.as_slice().to_vec(),
        samples: sampler.samples,
        stats: outcome.stats,
        events: problem.events,
        summary,
        warnings,
        constraints,
    };
    Ok((model, run))
}

/// The warnings of a finished run: the crush channel's sign sanity, the
/// filter classes the sample rate cannot give, then the energy balance.
fn run_warnings(scenario: &Scenario, metrics: &Metrics, summary: &Summary) -> Vec<Warning> {
    let mut warnings = Vec::new();
    if let Some(crush) = &scenario.crush {
        let channel = format!("crush channel `{}`", crush.name);
        warnings.extend(metrics.crush_warnings(&channel));
    }
    warnings.extend(metrics.filter_warnings());
    warnings.extend(summary.criteria.warnings.iter().cloned());
    warnings.extend(warning::energy_balance(summary.energy_balance_error_rel));
    warnings
}

/// A copy of `system` with the scenario's parameter overrides.
fn with_parameters<const N: usize, S: LagrangianSystem<N> + Clone>(
    system: &S,
    scenario: &Scenario,
) -> Result<S, SimulationError> {
    let mut model = system.clone();
    scenario
        .apply_parameters(&mut model)
        .map_err(SimulationError::Model)?;
    Ok(model)
}

fn own(names: Vec<&str>) -> Vec<String> {
    names.into_iter().map(str::to_string).collect()
}

/// The state the run starts from: the scenario's initial coordinates and
/// velocities (0 where it gives none), with the equilibrium coordinates
/// solved for, then projected onto the model's constraints (what the
/// projection changed, for a model with constraints); the components are
/// put in the state that goes with it.
fn initial_state<const N: usize, S: LagrangianSystem<N>>(
    problem: &mut CrashProblem<N, S>,
    scenario: &Scenario,
) -> Result<(PhaseState<N>, Option<Projection>), SimulationError> {
    let given = initial::given_state::<N>(scenario);
    let (mut q, mut v) = (given.q, given.v);
    // The components' state (a crush element in contact or not) follows the
    // initial state, for the equilibrium as for the run.
    problem.start(0.0, &given)?;
    if !scenario.equilibrium.is_empty() {
        q = static_equilibrium(problem, 0.0, q, &scenario.equilibrium)?;
    }
    let projection = match problem.system.constraint_count() {
        0 => None,
        _ => Some(constrained::project(
            problem.system,
            &problem.inputs,
            0.0,
            &mut q,
            &mut v,
        )?),
    };
    let mut y0 = PhaseState::new(q, v);
    problem.start(0.0, &y0)?;
    y0.z = problem.initial_internal()?;
    Ok((y0, projection))
}

/// Takes a run's output samples from the dense output of its steps: at
/// `k · interval`, the last one moved onto `t_end` when it falls within
/// half an interval of it.
struct Sampler<const N: usize> {
    metrics: Metrics,
    /// The samples, when the run keeps them.
    samples: Vec<Sample>,
    /// What each sample evaluates.
    needs: needs::Needs,
    /// The number of the model's outputs.
    outputs: usize,
    /// The first sample that could not be evaluated.
    error: Option<SolverError>,
    interval: f64,
    t_end: f64,
    /// The index `k` of the next sample.
    next: usize,
    /// The last index that may be sampled: one or two beyond `t_end`, so
    /// that it bounds the sampling even for an interval the scenario check
    /// would not let through (∞ or NaN, when `k·interval` never passes
    /// t_end, or too small).
    last: usize,
    /// The end of the last accepted step, for the report of a failure.
    reached: Option<(f64, PhaseState<N>)>,
    /// `max |g_k|` over the samples so far, by constraint.
    drift: Vec<f64>,
    /// Which steps' samples take `q̈` from the dense output.
    dense: rates::DenseAccelerations,
    /// The times of the samples within the step being observed.
    times: Vec<f64>,
}

impl<const N: usize> Sampler<N> {
    /// The sampler of `scenario`'s output times, evaluating what `needs`
    /// asks of a model with `outputs` outputs, with `q̈` from the dense
    /// output of the steps `dense` says.
    fn new(
        scenario: &Scenario,
        metrics: Metrics,
        (needs, outputs, dense): (needs::Needs, usize, rates::DenseAccelerations),
    ) -> Self {
        let interval = scenario.output_interval;
        let bound = (scenario.t_end / interval + 1.0).ceil();
        let last = if bound >= 0.0 {
            bound.min(MAX_SAMPLES + 1.0) as usize
        } else {
            0 // NaN
        };
        Sampler {
            metrics,
            samples: Vec::new(),
            needs,
            outputs,
            error: None,
            interval,
            t_end: scenario.t_end,
            next: 0,
            last,
            reached: None,
            drift: Vec::new(),
            dense,
            times: Vec::new(),
        }
    }

    /// Takes the sample at the start of the run.
    fn start<S: LagrangianSystem<N>>(
        &mut self,
        problem: &mut CrashProblem<N, S>,
        y0: &PhaseState<N>,
    ) {
        self.record(problem, 0.0, y0, None);
        self.balance(problem, 0.0, y0);
        self.next = 1;
    }

    /// Adds the energies at `(t, y)`, the start or the end of a step, to
    /// the energy balance.
    fn balance<S: LagrangianSystem<N>>(
        &mut self,
        problem: &mut CrashProblem<N, S>,
        t: f64,
        y: &PhaseState<N>,
    ) {
        problem.inputs.load(&y.z);
        let energy = (problem.system).mechanical_energy(t, &y.q, &y.v, &problem.inputs);
        self.metrics.energy_at(EnergyPoint {
            t,
            kinetic: energy.kinetic,
            potential: energy.potential,
            dissipated: y.work[0],
            external_work: y.work[1],
        });
    }

    /// Takes the samples that fall within an accepted step.
    fn observe<S: LagrangianSystem<N>>(
        &mut self,
        problem: &mut CrashProblem<N, S>,
        step: &dyn DenseStep<PhaseState<N>>,
    ) {
        let mut y = PhaseState::zeros();
        step.eval(step.t1(), &mut y);
        self.balance(problem, step.t1(), &y);
        self.reached = Some((step.t1(), y));
        let times = self.times_within(step);
        let rates = match self.needs.accelerations {
            true => rates::SampleRates::of(&self.dense, problem, step, &times),
            false => rates::SampleRates::Solved,
        };
        let mut rate = PhaseState::zeros();
        for (k, &t) in times.iter().enumerate() {
            let a = rates.at(step, (k, t), &mut rate);
            step.eval_part(t, self.needs.state(a.is_some()), &mut y);
            self.record(problem, t, &y, a);
        }
        self.times = times;
    }

    /// The times of the samples that fall within `step`, from the next
    /// (in a buffer to give back to `self.times`).
    fn times_within(&mut self, step: &dyn DenseStep<PhaseState<N>>) -> Vec<f64> {
        let mut times = std::mem::take(&mut self.times);
        times.clear();
        while self.next <= self.last {
            let t = (self.next as f64 * self.interval).min(self.t_end);
            if t > step.t1() || self.next as f64 * self.interval > self.t_end + 0.5 * self.interval
            {
                break;
            }
            times.push(t);
            self.next += 1;
        }
        times
    }

    /// Adds the sample at `(t, y)` to the metrics (and to the samples, when
    /// kept), or keeps the first error; `q̈` is `interpolated` if given.
    fn record<S: LagrangianSystem<N>>(
        &mut self,
        problem: &mut CrashProblem<N, S>,
        t: f64,
        y: &PhaseState<N>,
        interpolated: Option<SVector<f64, N>>,
    ) {
        if self.needs.state(interpolated.is_some()) == Part::Motion {
            // Nothing but the metrics reads the sample, and they read the
            // motion and `q̈` (NaN where nothing reads it).
            let a = interpolated.unwrap_or(SVector::repeat(f64::NAN));
            let (q, v) = (y.q.as_slice(), y.v.as_slice());
            self.metrics
                .push(SampleView::of_motion(t, q, v, a.as_slice()));
            return;
        }
        match sample(problem, t, y, &self.needs, self.outputs, interpolated) {
            Ok((view, columns)) => {
                self.drift.resize(view.residual.len(), 0.0);
                for (d, g) in self.drift.iter_mut().zip(&view.residual) {
                    *d = d.max(g.abs());
                }
                self.metrics.push(view.as_view());
                if self.needs.kept {
                    let crush = self.metrics.last_crush();
                    self.samples.push(view.into_sample(columns, crush));
                }
            }
            Err(e) => {
                self.error.get_or_insert(e);
            }
        }
    }

    /// Where the last accepted step ended.
    fn reached(&self) -> Option<Box<Reached>> {
        self.reached.map(|(t, y)| {
            Box::new(Reached {
                t,
                q: y.q.as_slice().to_vec(),
                qd: y.v.as_slice().to_vec(),
            })
        })
    }
}

/// The state, accelerations, energies and outputs at one output time.
struct SampleValues<'a, const N: usize> {
    t: f64,
    y: &'a PhaseState<N>,
    a: SVector<f64, N>,
    kinetic: f64,
    potential: f64,
    outputs: Vec<f64>,
    /// The components' columns (for channels that read them).
    components: Vec<f64>,
    /// `λ` and `g` of the constraints.
    multipliers: Vec<f64>,
    residual: Vec<f64>,
    /// The outputs' rates and accelerations along the motion, for a crush
    /// channel of outputs (empty otherwise).
    output_motion: [Vec<f64>; 2],
}

impl<const N: usize> SampleValues<'_, N> {
    fn as_view(&self) -> SampleView<'_> {
        SampleView {
            t: self.t,
            q: self.y.q.as_slice(),
            v: self.y.v.as_slice(),
            a: self.a.as_slice(),
            outputs: &self.outputs,
            components: &self.components,
            multipliers: &self.multipliers,
            residuals: &self.residual,
            output_motion: [&self.output_motion[0], &self.output_motion[1]],
        }
    }

    fn into_sample(self, inputs: Vec<f64>, crush: Option<[f64; 3]>) -> Sample {
        Sample {
            t: self.t,
            q: self.y.q.as_slice().to_vec(),
            v: self.y.v.as_slice().to_vec(),
            a: self.a.as_slice().to_vec(),
            kinetic: self.kinetic,
            potential: self.potential,
            dissipated: self.y.work[0],
            external_work: self.y.work[1],
            inputs,
            outputs: self.outputs,
            components: self.components,
            multipliers: self.multipliers,
            residuals: self.residual,
            crush,
        }
    }
}

/// Evaluates a sample: what `needs` asks for of the energies (a kept
/// sample's), the accelerations (`interpolated` if given, else solved, with the
/// constraints' multipliers and residuals), the `outputs` outputs (at
/// those accelerations), the components' columns and, for a kept sample,
/// the input values; a quantity not asked for is left NaN (or empty).
fn sample<'a, const N: usize, S: LagrangianSystem<N>>(
    problem: &mut CrashProblem<N, S>,
    t: f64,
    y: &'a PhaseState<N>,
    needs: &needs::Needs,
    outputs: usize,
    interpolated: Option<SVector<f64, N>>,
) -> Result<(SampleValues<'a, N>, Vec<f64>), SolverError> {
    let fault = |fault| SolverError::Rhs { t, error: fault };
    if needs.state(interpolated.is_some()) == Part::All {
        problem.inputs.load(&y.z);
    }
    let problem::Accelerations {
        a,
        multipliers,
        residual,
    } = match needs.accelerations {
        true => match interpolated {
            Some(a) => problem::Accelerations {
                a,
                multipliers: Vec::new(),
                residual: Vec::new(),
            },
            None => (problem.accelerations_and_multipliers(t, &y.q, &y.v)).map_err(fault)?,
        },
        false => problem::Accelerations::not_evaluated(),
    };
    // T and V only: the dissipation and the powers are integrated in `y`.
    // The summary's energy balance takes them at the steps' ends
    // (`Sampler::balance`): only a kept sample needs them.
    let (kinetic, potential) = match needs.kept {
        true => {
            let energy = (problem.system).mechanical_energy(t, &y.q, &y.v, &problem.inputs);
            (energy.kinetic, energy.potential)
        }
        false => (f64::NAN, f64::NAN),
    };
    let outputs = match needs.outputs {
        true => {
            let mut values = vec![0.0; outputs];
            (problem.system).outputs(t, &y.q, &y.v, &a, &problem.inputs, &mut values);
            values
        }
        false => Vec::new(),
    };
    let output_motion = match needs.output_motion {
        true => output_motion::output_motion(problem.system, (t, &y.q, &y.v, &a), &outputs),
        false => [Vec::new(), Vec::new()],
    };
    let components = match needs.components {
        true => problem.component_values(t, &y.q, &y.v).map_err(fault)?,
        false => Vec::new(),
    };
    let values = match needs.kept {
        true => problem.input_values(t, &y.q, &y.v),
        false => Vec::new(),
    };
    let sample = SampleValues {
        t,
        y,
        a,
        kinetic,
        potential,
        outputs,
        components,
        multipliers,
        residual,
        output_motion,
    };
    Ok((sample, values))
}
