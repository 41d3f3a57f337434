//! A model with its crash components as an ODE problem in `(q, q̇, work)`.

use super::SolverError;
use super::constrained::Workspace;
use super::kinks::KinkedInputs;
use crate::components::{BoundInputs, StandIn};
use crate::fault::Fault;
use crate::ode::tr_bdf2::{AccelerationJacobian, AccelerationJacobians};
use crate::ode::{Direction, EventAction, Internal, OdeProblem, PhaseState};
use crate::scenario::options::TimeKinks;
use lagrangian_runtime::constrained::Baumgarte;
use lagrangian_runtime::{InputFunctions, Jacobians, LagrangianSystem, ModelError};
use nalgebra::{SMatrix, SVector};
use std::cell::RefCell;

/// An input value of this magnitude or more squares to more than the
/// largest double (`√f64::MAX ≈ 1.34e154`): the input a dynamics that
/// overflowed is blamed on, when none is infinite itself.
const HUGE_INPUT: f64 = 1.3e154;

/// One event handled during a run.
#[derive(Clone, Debug, PartialEq)]
pub struct EventRecord {
    /// When it happened, located on the dense output \[s\].
    pub t: f64,
    /// The scenario's name of the component it changed (`front_end`).
    pub component: String,
    /// What changed, in words with the values at the event (`peak crush
    /// 0.5123 m at 412.3 kN; unloading`).
    pub description: String,
}

/// The accelerations at a state, with the multipliers and residuals of the
/// model's constraints (empty without constraints).
pub struct Accelerations<const N: usize> {
    /// `q̈`.
    pub a: SVector<f64, N>,
    /// `λ`, by constraint.
    pub multipliers: Vec<f64>,
    /// `g`, by constraint.
    pub residual: Vec<f64>,
}

impl<const N: usize> Accelerations<N> {
    /// Accelerations that were not evaluated: NaN, without constraints'
    /// values.
    pub fn not_evaluated() -> Accelerations<N> {
        Accelerations {
            a: SVector::repeat(f64::NAN),
            multipliers: Vec::new(),
            residual: Vec::new(),
        }
    }
}

/// `q̇ = v`, `M(q) v̇ = f(q, v, t)`, `ẇ = (Σ ∂D/∂q̇·q̇, Σ Q·q̇)`, and
/// `ż = g(z, …)` of the components' internal states.
///
/// Every evaluation at a state first gives the components its `z`
/// ([`BoundInputs::load`]); a state without `z` (the static equilibrium, a
/// linearization) holds them at the values last given, which
/// [`CrashProblem::start`] sets to their initial ones.
pub struct CrashProblem<'a, const N: usize, S: LagrangianSystem<N>> {
    /// The model, with the scenario's parameters.
    pub system: &'a S,
    /// The crash components bound to the model's inputs; their state
    /// (contact, loading or unloading, weld intact) changes at events.
    pub inputs: BoundInputs,
    /// The events handled so far, in time order.
    pub events: Vec<EventRecord>,
    /// A failure inside an event handler, reported after the run.
    pub failure: Option<Fault>,
    /// The stabilization of the model's constraints, if it has any.
    pub stabilization: Baumgarte,
    arguments: Vec<f64>,
    /// The model's number of constraints, asked once.
    constraint_count: usize,
    /// The buffers of the constrained solve, kept so that the right-hand
    /// side allocates nothing.
    workspace: RefCell<Workspace<N>>,
    stops: super::stops::TimeStops,
    /// For each input site of the dynamics: whether it passes the time
    /// alone ([`super::stops::time_sites`]), probed once.
    time_sites: Vec<bool>,
    /// The inputs of time with kinks.
    kinked: KinkedInputs,
    /// What the stages of a step see of their kinks inside it.
    time_kinks: TimeKinks,
    /// Where the stages of the last attempt took the stand-ins of
    /// [`CrashProblem::kinked`], under [`TimeKinks::Smoothed`]: the start
    /// of its step, and the stand-ins by input.
    smoothed: (f64, Vec<(usize, StandIn)>),
}

impl<'a, const N: usize, S: LagrangianSystem<N>> CrashProblem<'a, N, S> {
    /// The problem of `system` with its inputs bound to `inputs`; call
    /// [`CrashProblem::start`] before integrating.
    pub fn new(system: &'a S, inputs: BoundInputs) -> Self {
        let arguments = vec![0.0; system.input_sites().iter().map(|s| s.1).sum()];
        let constraint_count = system.constraint_count();
        let time_sites = super::stops::time_sites(system);
        let stops = super::stops::TimeStops::of(system, &inputs, &time_sites);
        let kinked = KinkedInputs::of(system, &inputs, &time_sites);
        CrashProblem {
            system,
            inputs,
            events: Vec::new(),
            failure: None,
            stabilization: super::constrained::DEFAULT_STABILIZATION,
            arguments,
            constraint_count,
            workspace: RefCell::new(Workspace::new(constraint_count)),
            stops,
            time_sites,
            kinked,
            time_kinks: TimeKinks::default(),
            smoothed: (f64::NAN, Vec::new()),
        }
    }

    /// The inputs of time with kinks.
    pub(super) fn kinked(&self) -> &KinkedInputs {
        &self.kinked
    }

    /// Has the inputs take the stand-ins the stages of the last attempt
    /// took, if that attempt was the step from `t0` and took some; `false`
    /// if not. [`BoundInputs::end_stand_ins`] ends them.
    pub(super) fn retake_stand_ins(&mut self, t0: f64) -> bool {
        let (start, stand_ins) = &self.smoothed;
        if *start != t0 || stand_ins.is_empty() {
            return false;
        }
        for &(input, cubic) in stand_ins {
            self.inputs.stand_in(input, cubic);
        }
        true
    }

    /// For each input site of the dynamics: whether it passes the time
    /// alone.
    pub(super) fn time_sites(&self) -> &[bool] {
        &self.time_sites
    }

    /// What the stages of a step see of a kink of an input of time inside
    /// it: by default ([`TimeKinks::Smoothed`]) the input's smooth
    /// stand-in.
    pub fn time_kinks(&mut self, choice: TimeKinks) {
        self.time_kinks = choice;
    }

    /// Puts the crash components in the state a run from `(t, y)` starts
    /// in, with their internal states at `y.z`, or at their initial values
    /// when `y` carries none (see [`BoundInputs::start_settled`] for inputs
    /// inside inputs' arguments).
    pub fn start(&mut self, t: f64, y: &PhaseState<N>) -> Result<(), SolverError> {
        let system = &self.system;
        let sites = system.input_sites().len();
        let evaluate = |inputs: &BoundInputs, out: &mut [f64]| {
            system.input_arguments(t, &y.q, &y.v, inputs, out)
        };
        let prepare = |inputs: &mut BoundInputs| match y.z.is_empty() {
            true => inputs.initial_internal().map(|_| ()),
            false => {
                inputs.load(&y.z);
                Ok(())
            }
        };
        (self.inputs)
            .start_settled(&mut self.arguments, sites, evaluate, prepare)
            .map_err(|fault| SolverError::Rhs { t, error: fault })
    }

    /// The internal states a run starts with (empty for a scenario whose
    /// components have none).
    pub fn initial_internal(&mut self) -> Result<Internal, SolverError> {
        let error = |fault| SolverError::Rhs {
            t: 0.0,
            error: fault,
        };
        self.inputs.initial_internal().map_err(error)
    }

    /// `ż` at `(t, y)`, the components' states loaded, into `rates`.
    fn internal_rates(
        &mut self,
        t: f64,
        y: &PhaseState<N>,
        rates: &mut Internal,
    ) -> Result<(), Fault> {
        self.system
            .input_arguments(t, &y.q, &y.v, &self.inputs, &mut self.arguments);
        rates.assign(&y.z);
        self.inputs
            .internal_rates(&self.arguments, rates.as_mut_slice())?;
        self.input_failure()
    }

    /// The failure an input reported since the last call, if any.
    fn input_failure(&self) -> Result<(), Fault> {
        match self.inputs.take_failure() {
            Some(fault) => Err(fault),
            None => Ok(()),
        }
    }

    /// `q̈` at a state, by the `L D Lᵀ` solution of `M q̈ = f`.
    pub fn accelerations(
        &self,
        t: f64,
        q: &SVector<f64, N>,
        v: &SVector<f64, N>,
    ) -> Result<SVector<f64, N>, Fault> {
        let mut mass = SMatrix::zeros();
        let mut forcing = SVector::zeros();
        self.system
            .mass_matrix_and_forcing(t, q, v, &self.inputs, &mut mass, &mut forcing);
        self.input_failure()?;
        Ok(self.solve_dynamics((t, q, v), &mass, &forcing)?.0)
    }

    /// `q̈`, with the multipliers `λ` and residuals `g` of the model's
    /// constraints (empty without constraints).
    pub fn accelerations_and_multipliers(
        &self,
        t: f64,
        q: &SVector<f64, N>,
        v: &SVector<f64, N>,
    ) -> Result<Accelerations<N>, Fault> {
        let (mass, forcing) = self
            .system
            .mass_matrix_and_forcing_pair(t, q, v, &self.inputs);
        self.input_failure()?;
        if self.constraint_count == 0 {
            return Ok(Accelerations {
                a: self.solve((t, q, v), &mass, &forcing)?,
                multipliers: Vec::new(),
                residual: Vec::new(),
            });
        }
        let state = (t, q, v);
        let solution = self.solve_constrained(state, &mass, &forcing)?;
        Ok(Accelerations {
            residual: solution.values.residual().to_vec(),
            a: solution.a,
            multipliers: solution.lambda,
        })
    }

    /// `q̈` and the power of the constraint forces: `M q̈ = f` (by
    /// [`CrashProblem::solve`]), or with constraints the constrained solve.
    fn solve_dynamics(
        &self,
        state: (f64, &SVector<f64, N>, &SVector<f64, N>),
        mass: &SMatrix<f64, N, N>,
        forcing: &SVector<f64, N>,
    ) -> Result<(SVector<f64, N>, f64), Fault> {
        if self.constraint_count == 0 {
            return Ok((self.solve(state, mass, forcing)?, 0.0));
        }
        let mut workspace = self.workspace.borrow_mut();
        let dynamics = (mass, forcing);
        let solution = super::constrained::solve_in(
            self.system,
            &self.inputs,
            self.stabilization,
            state,
            dynamics,
            &mut workspace,
        );
        self.input_failure()?;
        solution
    }

    fn solve_constrained(
        &self,
        state: (f64, &SVector<f64, N>, &SVector<f64, N>),
        mass: &SMatrix<f64, N, N>,
        forcing: &SVector<f64, N>,
    ) -> Result<super::constrained::Solution<N>, Fault> {
        let solution = super::constrained::solve(
            self.system,
            &self.inputs,
            self.stabilization,
            state,
            mass,
            forcing,
        );
        self.input_failure()?;
        solution
    }

    /// `q̈ = M⁻¹ f`, with a non-finite entry of `M`, `f` or `q̈` or a
    /// singular `M` reported by name and state: the component input that
    /// is not finite, where one is.
    fn solve(
        &self,
        (t, q, v): (f64, &SVector<f64, N>, &SVector<f64, N>),
        mass: &SMatrix<f64, N, N>,
        forcing: &SVector<f64, N>,
    ) -> Result<SVector<f64, N>, Fault> {
        let a = self.system.solve_mass(mass, forcing);
        if let Some(a) = a
            && a.iter().all(|x| x.is_finite())
        {
            return Ok(a);
        }
        // Name the first bad value: a non-finite entry of M or f is the
        // cause of anything that follows from it.
        let names = self.system.coordinate_names();
        let non_finite = |output: String, value: f64| self.non_finite((t, q, v), output, value);
        for i in 0..N {
            for j in 0..N {
                if !mass[(i, j)].is_finite() {
                    let output = format!("M[{}, {}]", names[i], names[j]);
                    return Err(non_finite(output, mass[(i, j)]));
                }
            }
            if !forcing[i].is_finite() {
                return Err(non_finite(format!("f[{}]", names[i]), forcing[i]));
            }
        }
        match a {
            None => Err(Fault::SingularMassMatrix {
                q: q.as_slice().to_vec(),
                qd: v.as_slice().to_vec(),
            }),
            Some(a) => {
                let i = a.iter().position(|x| !x.is_finite()).unwrap_or(0);
                let output = format!("the acceleration of {}", names[i]);
                Err(non_finite(output, a[i]))
            }
        }
    }

    /// `q̈` and the powers `[Σ ∂D/∂q̇·q̇, Σ Q·q̇]` at a state, in one pass
    /// of the model; the power of the constraint forces `λᵀ G q̇` counts
    /// with that of the generalized forces.
    fn accelerations_and_powers(
        &self,
        t: f64,
        q: &SVector<f64, N>,
        v: &SVector<f64, N>,
    ) -> Result<(SVector<f64, N>, [f64; 2]), Fault> {
        let mut mass = SMatrix::zeros();
        let mut forcing = SVector::zeros();
        let powers = self.system.mass_matrix_forcing_and_powers(
            t,
            q,
            v,
            &self.inputs,
            &mut mass,
            &mut forcing,
        );
        self.input_failure()?;
        let (a, constraint_power) = self.solve_dynamics((t, q, v), &mass, &forcing)?;
        let powers = [powers[0], powers[1] + constraint_power];
        for (power, name) in powers
            .iter()
            .zip(["dissipated power", "power of the forces"])
        {
            if !power.is_finite() {
                return Err(self.non_finite((t, q, v), format!("the {name}"), *power));
            }
        }
        Ok((a, powers))
    }

    /// The input the dynamics calls at a state that explains a dynamics
    /// that is not finite there, named with its component and arguments,
    /// and its value: the first whose component gives a value that is not
    /// finite at finite arguments, else the largest beyond
    /// [`HUGE_INPUT`], whose product with another such overflows; `None`
    /// if there is neither (the model's own arithmetic is the cause). For
    /// messages only: it evaluates the inputs again.
    fn blamed_input(
        &self,
        t: f64,
        q: &SVector<f64, N>,
        v: &SVector<f64, N>,
    ) -> Option<(String, f64)> {
        let mut arguments = vec![0.0; self.arguments.len()];
        self.system
            .input_arguments(t, q, v, &self.inputs, &mut arguments);
        let mut offset = 0;
        let mut largest: Option<(usize, (usize, usize), f64)> = None;
        for &(input, arity) in self.system.input_sites() {
            let at = offset;
            offset += arity;
            let args = &arguments[at..at + arity];
            if !args.iter().all(|x| x.is_finite()) {
                continue;
            }
            let value = self.inputs.value(input, args);
            if !value.is_finite() {
                largest = Some((input, (at, arity), value));
                break;
            }
            if value.abs() >= HUGE_INPUT && largest.is_none_or(|(_, _, l)| value.abs() > l.abs()) {
                largest = Some((input, (at, arity), value));
            }
        }
        // What the calls failed on was reported before this one.
        let _ = self.inputs.take_failure();
        let (input, (at, arity), value) = largest?;
        let name = self.inputs.name_input(input, &arguments[at..at + arity])?;
        Some((name, value))
    }

    /// A fault for `output` of the dynamics, whose value `value` is not
    /// finite at `(t, q, v)`: the input that is not finite instead, where
    /// one is, or with the input too large for the arithmetic named.
    fn non_finite(
        &self,
        (t, q, v): (f64, &SVector<f64, N>, &SVector<f64, N>),
        output: String,
        value: f64,
    ) -> Fault {
        let (output, value) = match self.blamed_input(t, q, v) {
            Some((input, value)) if !value.is_finite() => (input, value),
            Some((input, large)) => (format!("{output}, where {input} is {large:e},"), value),
            None => (output, value),
        };
        Fault::NonFinite {
            output,
            value,
            q: q.as_slice().to_vec(),
            qd: v.as_slice().to_vec(),
        }
    }

    /// The value of every input the dynamics calls, in input-site order.
    pub fn input_values(&mut self, t: f64, q: &SVector<f64, N>, v: &SVector<f64, N>) -> Vec<f64> {
        self.system
            .input_arguments(t, q, v, &self.inputs, &mut self.arguments);
        let mut offset = 0;
        let mut values = Vec::with_capacity(self.system.input_sites().len());
        for &(input, arity) in self.system.input_sites() {
            values.push(
                self.inputs
                    .value(input, &self.arguments[offset..offset + arity]),
            );
            offset += arity;
        }
        values
    }

    /// The values of the components' columns at a state (see
    /// [`BoundInputs::columns`]).
    pub fn component_values(
        &mut self,
        t: f64,
        q: &SVector<f64, N>,
        v: &SVector<f64, N>,
    ) -> Result<Vec<f64>, Fault> {
        self.system
            .input_arguments(t, q, v, &self.inputs, &mut self.arguments);
        self.inputs.column_values(&self.arguments)
    }

    /// The energy each dissipative component has dissipated at `(t, y)`
    /// (see [`BoundInputs::dissipated_energies`]).
    pub fn dissipated_energies(
        &mut self,
        t: f64,
        y: &PhaseState<N>,
    ) -> Result<Vec<(String, f64)>, Fault> {
        self.inputs.load(&y.z);
        (self.system).input_arguments(t, &y.q, &y.v, &self.inputs, &mut self.arguments);
        self.inputs.dissipated_energies(&self.arguments)
    }
}

impl<const N: usize, S: LagrangianSystem<N>> OdeProblem<PhaseState<N>> for CrashProblem<'_, N, S> {
    type Error = Fault;

    fn rhs(&mut self, t: f64, y: &PhaseState<N>, dy: &mut PhaseState<N>) -> Result<(), Fault> {
        self.inputs.load(&y.z);
        let (a, work) = self.accelerations_and_powers(t, &y.q, &y.v)?;
        (dy.q, dy.v, dy.work) = (y.v, a, work);
        match y.z.is_empty() {
            true => dy.z.assign(&Internal::EMPTY),
            false => self.internal_rates(t, y, &mut dy.z)?,
        }
        Ok(())
    }

    /// The crash components' events, then one per switching function of
    /// the model (`abs`, `sign`, `min`, `max`), so that no step straddles
    /// a kink of the dynamics.
    fn event_count(&self) -> usize {
        self.inputs.event_count() + self.system.switching_count()
    }

    fn events(&mut self, t: f64, y: &PhaseState<N>, g: &mut [f64]) -> Result<(), Fault> {
        self.inputs.load(&y.z);
        self.system
            .input_arguments(t, &y.q, &y.v, &self.inputs, &mut self.arguments);
        let (components, switching) = g.split_at_mut(self.inputs.event_count());
        // A smooth model has none, and writes nothing.
        if !switching.is_empty() {
            self.system
                .switching_functions(t, &y.q, &y.v, &self.inputs, switching);
        }
        self.inputs.events(&self.arguments, components)
    }

    /// A component's event function without the others or the switching
    /// functions; a switching function without the components' events.
    fn event(&mut self, k: usize, t: f64, y: &PhaseState<N>, g: &mut [f64]) -> Result<f64, Fault> {
        self.inputs.load(&y.z);
        let Some(switch) = k.checked_sub(self.inputs.event_count()) else {
            self.system
                .input_arguments(t, &y.q, &y.v, &self.inputs, &mut self.arguments);
            return self.inputs.event_value(k, &self.arguments, g);
        };
        let switching = &mut g[self.inputs.event_count()..];
        self.system
            .switching_functions(t, &y.q, &y.v, &self.inputs, switching);
        Ok(switching[switch])
    }

    /// The next point of a time table interpolated linearly.
    fn next_stop(&mut self, t: f64) -> Option<f64> {
        self.stops.after(t)
    }

    /// The inputs of time with a kink inside the step take their smooth
    /// stand-ins over it.
    fn step_window(&mut self, window: Option<(f64, f64)>) {
        self.inputs.end_stand_ins();
        if let (Some((t0, h)), TimeKinks::Smoothed) = (window, self.time_kinks) {
            self.kinked.stand_in(&mut self.inputs, t0, h);
            self.smoothed.0 = t0;
            self.smoothed.1.clear();
            self.smoothed.1.extend(self.inputs.stand_ins());
        }
    }

    /// The first entry of `dy` that is not finite, by name: a coordinate's
    /// velocity or acceleration, a power, or a component's state rate or
    /// dissipated power (naming the component).
    fn name_non_finite(&mut self, t: f64, y: &PhaseState<N>, dy: &PhaseState<N>) -> String {
        let names = self.system.coordinate_names();
        let first = |values: &[f64]| values.iter().position(|x| !x.is_finite());
        if let Some(i) = first(dy.q.as_slice()) {
            return format!("the velocity of {} ({})", names[i], dy.q[i]);
        }
        if let Some(i) = first(dy.v.as_slice()) {
            return format!("the acceleration of {} ({})", names[i], dy.v[i]);
        }
        if let Some(i) = first(&dy.work) {
            let power = ["the dissipated power", "the power of the forces"][i];
            return format!("{power} ({})", dy.work[i]);
        }
        let Some(i) = first(dy.z.as_slice()) else {
            return "the right-hand side".to_string();
        };
        self.inputs.load(&y.z);
        (self.system).input_arguments(t, &y.q, &y.v, &self.inputs, &mut self.arguments);
        (self.inputs).name_internal_rate(i, dy.z.as_slice()[i], &self.arguments)
    }

    fn name_largest_rate(&mut self, t: f64, y: &PhaseState<N>, dy: &PhaseState<N>) -> String {
        let names = self.system.coordinate_names();
        let largest = |values: &[f64]| {
            (0..values.len()).max_by(|&i, &j| values[i].abs().total_cmp(&values[j].abs()))
        };
        let size = |values: &[f64], i: Option<usize>| i.map_or(0.0, |i: usize| values[i].abs());
        let (q, v, z) = (dy.q.as_slice(), dy.v.as_slice(), dy.z.as_slice());
        let (iq, iv, iz) = (largest(q), largest(v), largest(z));
        let (sq, sv, sz) = (size(q, iq), size(v, iv), size(z, iz));
        if let Some(i) = iz.filter(|_| sz >= sq.max(sv)) {
            self.inputs.load(&y.z);
            (self.system).input_arguments(t, &y.q, &y.v, &self.inputs, &mut self.arguments);
            return (self.inputs).name_internal_rate(i, z[i], &self.arguments);
        }
        match (iq, iv) {
            (Some(i), _) if sq >= sv => format!("the velocity of {} ({:e})", names[i], q[i]),
            (_, Some(i)) => {
                let cause = match self.blamed_input(t, &y.q, &y.v) {
                    Some((input, large)) => format!(", where {input} is {large:e}"),
                    None => String::new(),
                };
                format!("the acceleration of {} ({:e}){cause}", names[i], v[i])
            }
            _ => "the right-hand side".to_string(),
        }
    }

    /// A component's event by its name and component; a switching function
    /// of the model by its number.
    fn name_event(&self, k: usize, value: f64) -> String {
        match k.checked_sub(self.inputs.event_count()) {
            Some(switch) => format!("switching function {} of the model ({value})", switch + 1),
            None => self.inputs.name_event(k, value),
        }
    }

    fn event_direction(&self, k: usize) -> Direction {
        if k < self.inputs.event_count() {
            self.inputs.event_direction(k)
        } else {
            Direction::Either
        }
    }

    fn on_event(&mut self, k: usize, t: f64, y: &mut PhaseState<N>) -> EventAction {
        if let Some(switch) = k.checked_sub(self.inputs.event_count()) {
            // A kink of the model: the step sequence restarts there.
            self.events.push(EventRecord {
                t,
                component: "model".to_string(),
                description: format!("switching function {} changes sign", switch + 1),
            });
            return EventAction::Restart;
        }
        self.inputs.load(&y.z);
        self.system
            .input_arguments(t, &y.q, &y.v, &self.inputs, &mut self.arguments);
        match self.inputs.on_event(k, t, &self.arguments) {
            // A kink of a component's curve: not a change of regime.
            Ok((_, description)) if description.is_empty() => EventAction::Restart,
            Ok((component, description)) => {
                self.events.push(EventRecord {
                    t,
                    component,
                    description,
                });
                EventAction::Restart
            }
            Err(fault) => {
                self.failure = Some(fault);
                EventAction::Stop
            }
        }
    }
}

impl<const N: usize, S: LagrangianSystem<N>> AccelerationJacobians<N> for CrashProblem<'_, N, S> {
    /// `∂a/∂q = M⁻¹ (∂f/∂q − ∂(M a)/∂q)`, `∂a/∂v = M⁻¹ ∂f/∂q̇` from the
    /// model's derived Jacobians; `None` when the spec did not ask for them
    /// or has constraints: those of the constrained accelerations (with the
    /// derivatives of `G` and `γ`) are not derived, and TR-BDF2 takes
    /// forward differences of the constrained `q̈` instead.
    fn acceleration_jacobians(
        &mut self,
        t: f64,
        y: &PhaseState<N>,
    ) -> Result<Option<AccelerationJacobian<N>>, Fault> {
        if self.constraint_count > 0 {
            // Those of M q̈ = f; the constrained ones are not derived.
            return Ok(None);
        }
        self.inputs.load(&y.z);
        let a = self.accelerations(t, &y.q, &y.v)?;
        let mut j = Jacobians::<N>::default();
        match self
            .system
            .jacobians(t, &y.q, &y.v, &a, &self.inputs, &mut j)
        {
            Err(ModelError::JacobiansNotDerived) => return Ok(None),
            Err(e) => return Err(Fault::Component(e.to_string())),
            Ok(()) => {}
        }
        self.input_failure()?;
        let mass = self.system.mass_matrix(t, &y.q, &y.v, &self.inputs);
        let solve = |m: SMatrix<f64, N, N>| -> Option<SMatrix<f64, N, N>> {
            let mut out = SMatrix::<f64, N, N>::zeros();
            for k in 0..N {
                let column: SVector<f64, N> = m.column(k).into_owned();
                out.set_column(k, &self.system.solve_mass(&mass, &column)?);
            }
            Some(out)
        };
        let singular = || Fault::SingularMassMatrix {
            q: y.q.as_slice().to_vec(),
            qd: y.v.as_slice().to_vec(),
        };
        let a_q = solve(j.forcing_q - j.mass_times_acceleration_q).ok_or_else(singular)?;
        let a_v = solve(j.forcing_qd).ok_or_else(singular)?;
        Ok(Some((a_q, a_v)))
    }

    /// Onto the model's constraints ([`super::constrained::project_step`]).
    fn project(&mut self, t: f64, y: &mut PhaseState<N>) -> Result<bool, Fault> {
        if self.constraint_count == 0 {
            return Ok(false);
        }
        let (system, inputs) = (self.system, &self.inputs);
        super::constrained::project_step(system, inputs, t, &mut y.q, &mut y.v)?;
        self.input_failure()?;
        Ok(true)
    }
}
