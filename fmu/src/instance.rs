//! One FMU instance: the FMI 2.0 state machine around a [`Plant`], with
//! every call's checks and effects, free of C types so that it is tested
//! in Rust. The C entry points above it (the modules `common`, `cs` and
//! `me`) only convert arguments and report failures.

use crate::ffi::fmi2Status;
use crate::machine::CallError;
use crate::plant::{Plant, PlantError, PlantFactory, plant};
use crate::resources::{Loaded, ResourceError};
use crate::variables::{NameClash, Variables};

pub use crate::machine::{Interface, Mode};

/// Why a call failed: the status to return and the message to log.
#[derive(Clone, Debug, PartialEq)]
pub struct Failure {
    /// `fmi2Error` or `fmi2Fatal` (or `fmi2Discard`).
    pub status: fmi2Status,
    /// What went wrong, for the host's logger.
    pub message: String,
}

impl Failure {
    /// An `fmi2Error` with `message`.
    pub fn error(message: impl Into<String>) -> Failure {
        Failure {
            status: fmi2Status::fmi2Error,
            message: message.into(),
        }
    }
}

/// An `fmi2Error` logging the error's message, from each error of this
/// crate.
macro_rules! failure_from {
    ($($error:ty),*) => {$(
        impl From<$error> for Failure {
            fn from(e: $error) -> Failure {
                Failure::error(e.to_string())
            }
        }
    )*};
}

failure_from!(CallError, PlantError, ResourceError, NameClash);

/// The result of an instance's call.
pub type Outcome<T = ()> = Result<T, Failure>;

/// What `fmi2NewDiscreteStates` reports, in Rust terms.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct EventUpdate {
    /// The states jumped at the event.
    pub states_changed: bool,
    /// The events handled, in words.
    pub events: Vec<String>,
}

/// An FMU instance.
pub struct Instance {
    /// The instance name the host gave.
    pub name: String,
    /// The interface it was created for.
    pub interface: Interface,
    /// The variables, by value reference.
    pub variables: Variables,
    /// Whether the host asked for debug messages (`fmi2SetDebugLogging`).
    pub logging: bool,
    mode: Mode,
    plant: Box<dyn Plant>,
    /// The plant as loaded, for `fmi2Reset`.
    fresh: Box<dyn Plant>,
    start_time: f64,
    /// The stop time `fmi2SetupExperiment` defined, if any.
    stop_time: Option<f64>,
    /// The earliest time `fmi2SetTime` accepts: the start, then the time
    /// continuous-time mode was last entered (the last event).
    time_floor: f64,
    /// Handled events not yet reported to the host (Co-Simulation logs
    /// them after each step).
    pub pending_events: Vec<String>,
    guid: String,
}

impl Instance {
    /// An instance of the loaded spec and scenario, run by the interpreter,
    /// checking that `guid` is theirs.
    pub fn new(name: &str, interface: Interface, guid: &str, loaded: Loaded) -> Outcome<Instance> {
        Instance::with_plant(name, interface, guid, loaded, plant)
    }

    /// An instance whose plant `factory` makes of the loaded spec and
    /// scenario (the interpreter's in [`Instance::new`]), checking that
    /// `guid` is theirs.
    pub fn with_plant(
        name: &str,
        interface: Interface,
        guid: &str,
        loaded: Loaded,
        factory: PlantFactory,
    ) -> Outcome<Instance> {
        if guid != loaded.guid {
            return Err(Failure::error(format!(
                "the GUID {guid} is not that of the model in the resources ({}): \
                 modelDescription.xml and resources/ come from different exports",
                loaded.guid
            )));
        }
        let spec = &loaded.compiled.model;
        let variables = Variables::new(spec, &loaded.scenario, &loaded.unbound)?;
        let plant = factory(loaded.model, &loaded.scenario)?;
        Ok(Instance {
            name: name.to_string(),
            interface,
            variables,
            logging: false,
            mode: Mode::Instantiated,
            fresh: plant.clone_box(),
            plant,
            start_time: 0.0,
            stop_time: None,
            time_floor: 0.0,
            pending_events: Vec::new(),
            guid: guid.to_string(),
        })
    }

    /// The GUID of the spec and scenario it runs.
    pub fn guid(&self) -> &str {
        &self.guid
    }

    /// The current mode.
    pub fn mode(&self) -> Mode {
        self.mode
    }

    /// `Err` unless the state machine allows `call` in the current mode
    /// ([`crate::machine`]).
    fn allow(&self, call: &str) -> Outcome {
        Ok(crate::machine::check(call, self.interface, self.mode)?)
    }

    /// Into the standard's error state, after a call returned `fmi2Error`:
    /// only reading, `fmi2Reset`, `fmi2SetFMUstate` and freeing remain.
    pub fn fail(&mut self) {
        self.mode = Mode::Failed;
    }

    /// Runs a plant operation; its failure puts the instance in [`Mode::Failed`].
    fn run<T>(&mut self, f: impl FnOnce(&mut dyn Plant) -> Result<T, PlantError>) -> Outcome<T> {
        f(self.plant.as_mut()).map_err(|error| {
            self.mode = Mode::Failed;
            Failure::from(error)
        })
    }

    /// `fmi2SetupExperiment`: the start time, and the stop time past
    /// which no step goes (the scenario's tolerance stays: a tolerance
    /// given is only checked).
    pub fn setup_experiment(
        &mut self,
        tolerance: Option<f64>,
        start_time: f64,
        stop_time: Option<f64>,
    ) -> Outcome {
        self.allow("fmi2SetupExperiment")?;
        if let Some(tolerance) = tolerance.filter(|t| !(t.is_finite() && *t > 0.0)) {
            return Err(Failure::error(format!(
                "tolerance = {tolerance}: a defined tolerance is a positive number"
            )));
        }
        finite("startTime", start_time)?;
        if let Some(stop) = stop_time.filter(|&stop| !(stop >= start_time && stop.is_finite())) {
            return Err(Failure::error(format!(
                "stopTime = {stop} s is before startTime = {start_time} s"
            )));
        }
        self.start_time = start_time;
        self.time_floor = start_time;
        self.stop_time = stop_time;
        Ok(())
    }

    /// `fmi2EnterInitializationMode`: the initial state with the parameters
    /// set so far, for the outputs read during initialization.
    pub fn enter_initialization(&mut self) -> Outcome {
        self.allow("fmi2EnterInitializationMode")?;
        self.initialize()?;
        self.mode = Mode::Initialization;
        Ok(())
    }

    fn initialize(&mut self) -> Outcome {
        let start = self.start_time;
        self.run(|p| {
            p.initialize()?;
            p.set_time(start);
            Ok(())
        })
    }

    /// `fmi2ExitInitializationMode`: the initial state again (parameters
    /// may have changed during initialization).
    pub fn exit_initialization(&mut self) -> Outcome {
        self.allow("fmi2ExitInitializationMode")?;
        self.initialize()?;
        self.mode = match self.interface {
            Interface::CoSimulation => Mode::StepComplete,
            Interface::ModelExchange => Mode::Event,
        };
        Ok(())
    }

    /// `fmi2Terminate`.
    pub fn terminate(&mut self) -> Outcome {
        self.allow("fmi2Terminate")?;
        self.mode = Mode::Terminated;
        Ok(())
    }

    /// `fmi2Reset`: back to the state after `fmi2Instantiate`.
    pub fn reset(&mut self) {
        self.plant = self.fresh.clone_box();
        self.mode = Mode::Instantiated;
        self.start_time = 0.0;
        self.stop_time = None;
        self.time_floor = 0.0;
        self.pending_events.clear();
    }

    /// `fmi2GetReal`.
    pub fn get_real(&mut self, vrs: &[u32], values: &mut [f64]) -> Outcome {
        self.allow("fmi2GetReal")?;
        let quantities = (vrs.iter())
            .map(|&vr| self.variables.get(vr).map(|v| v.quantity))
            .collect::<Option<Vec<_>>>()
            .ok_or_else(|| Failure::error(self.unknown(vrs)))?;
        self.run(|p| p.get(&quantities, values))
    }

    /// `fmi2SetReal`: parameters and inputs, each a finite number. All are
    /// checked before any is set: a refused call changes nothing.
    pub fn set_real(&mut self, vrs: &[u32], values: &[f64]) -> Outcome {
        self.allow("fmi2SetReal")?;
        let mut quantities = Vec::with_capacity(vrs.len());
        for (&vr, &value) in vrs.iter().zip(values) {
            quantities.push(self.settable(vr, value)?);
        }
        for (quantity, &value) in quantities.into_iter().zip(values) {
            self.plant.set(quantity, value)?;
        }
        Ok(())
    }

    /// The quantity of `vr` if `value` may be set to it now.
    fn settable(&self, vr: u32, value: f64) -> Outcome<crate::variables::Quantity> {
        let variable =
            (self.variables.get(vr)).ok_or_else(|| Failure::error(self.unknown(&[vr])))?;
        let (name, causality) = (&variable.name, variable.causality());
        if !variable.settable() {
            return Err(Failure::error(format!(
                "`{name}` (value reference {vr}) is {}: it cannot be set",
                causality.with_article()
            )));
        }
        if !crate::machine::settable_in(causality, self.mode) {
            return Err(Failure::error(format!(
                "`{name}` (value reference {vr}) is a tunable parameter: it cannot be set in \
                 state {} (only in instantiated, initializationMode, eventMode, stepComplete)",
                crate::machine::state_name(self.mode)
            )));
        }
        if !value.is_finite() {
            return Err(Failure::error(format!(
                "`{name}` (value reference {vr}) = {value}: {} is a finite number",
                causality.with_article()
            )));
        }
        Ok(variable.quantity)
    }

    /// The message for value references of which one is unknown.
    fn unknown(&self, vrs: &[u32]) -> String {
        let bad = vrs.iter().find(|&&vr| self.variables.get(vr).is_none());
        format!(
            "unknown value reference {} (this FMU has {})",
            bad.copied().unwrap_or_default(),
            self.variables.list.len()
        )
    }

    /// `fmi2DoStep`: integrates from `t` (the FMU's time) to `t + h`,
    /// `h ≥ 0`, not past the stop time.
    pub fn do_step(&mut self, t: f64, h: f64) -> Outcome {
        self.allow("fmi2DoStep")?;
        let now = self.plant.time();
        if !(t.is_finite() && (t - now).abs() <= 1e-9 * now.abs().max(1.0)) {
            return Err(Failure::error(format!(
                "currentCommunicationPoint = {t:e} s, but the FMU is at t = {now:e} s"
            )));
        }
        if !(h >= 0.0 && h.is_finite()) {
            return Err(Failure::error(format!(
                "communicationStepSize = {h:e} s: a step is a finite number ≥ 0"
            )));
        }
        if let Some(stop) = self
            .stop_time
            .filter(|&stop| t + h > stop * (1.0 + 1e-12) + 1e-12)
        {
            return Err(Failure::error(format!(
                "a step from t = {t:e} s by {h:e} s ends past stopTime = {stop:e} s"
            )));
        }
        if h == 0.0 {
            return Ok(());
        }
        let events = self.run(|p| p.advance(t + h))?;
        self.pending_events.extend(events);
        Ok(())
    }

    /// The current time.
    pub fn time(&self) -> f64 {
        self.plant.time()
    }

    /// The number of continuous states.
    pub fn state_count(&self) -> usize {
        self.plant.state_count()
    }

    /// The number of event indicators.
    pub fn event_count(&self) -> usize {
        self.plant.event_count()
    }

    /// `fmi2EnterEventMode`.
    pub fn enter_event_mode(&mut self) -> Outcome {
        self.allow("fmi2EnterEventMode")?;
        self.mode = Mode::Event;
        Ok(())
    }

    /// `fmi2NewDiscreteStates`: handles the events whose indicators crossed.
    pub fn new_discrete_states(&mut self) -> Outcome<EventUpdate> {
        self.allow("fmi2NewDiscreteStates")?;
        let before = self.states();
        let events = self.run(|p| p.handle_events())?;
        Ok(EventUpdate {
            states_changed: self.states() != before,
            events,
        })
    }

    /// `fmi2EnterContinuousTimeMode`.
    pub fn enter_continuous_time_mode(&mut self) -> Outcome {
        self.allow("fmi2EnterContinuousTimeMode")?;
        self.mode = Mode::ContinuousTime;
        self.time_floor = self.plant.time();
        Ok(())
    }

    /// `fmi2SetTime`: a finite time, not before the start nor the last
    /// event (the time continuous-time mode was entered).
    pub fn set_time(&mut self, t: f64) -> Outcome {
        self.allow("fmi2SetTime")?;
        if !(t.is_finite() && t >= self.time_floor) {
            return Err(Failure::error(format!(
                "time = {t:e} s: not a finite time at or after t = {:e} s (the start, or the \
                 last event)",
                self.time_floor
            )));
        }
        self.plant.set_time(t);
        Ok(())
    }

    /// The continuous states `(q, q̇)`.
    pub fn states(&self) -> Vec<f64> {
        let mut x = vec![0.0; self.plant.state_count()];
        self.plant.states(&mut x);
        x
    }

    /// `fmi2SetContinuousStates`.
    pub fn set_states(&mut self, x: &[f64]) -> Outcome {
        self.allow("fmi2SetContinuousStates")?;
        self.check_length(x.len(), self.plant.state_count(), "states")?;
        self.check_finite_states(x)?;
        self.plant.set_states(x);
        Ok(())
    }

    /// `fmi2GetDerivatives`.
    pub fn derivatives(&mut self, dx: &mut [f64]) -> Outcome {
        self.allow("fmi2GetDerivatives")?;
        self.check_length(dx.len(), self.plant.state_count(), "derivatives")?;
        self.run(|p| p.derivatives(dx))
    }

    /// `fmi2GetEventIndicators`.
    pub fn event_indicators(&mut self, g: &mut [f64]) -> Outcome {
        self.allow("fmi2GetEventIndicators")?;
        self.check_length(g.len(), self.plant.event_count(), "event indicators")?;
        self.run(|p| p.event_indicators(g))
    }

    /// `Err` naming the first state of `x` that is not a finite number.
    fn check_finite_states(&self, x: &[f64]) -> Outcome {
        let Some((i, value)) = x.iter().enumerate().find(|(_, x)| !x.is_finite()) else {
            return Ok(());
        };
        Err(Failure::error(format!(
            "x[{i}] ({}) = {value}: a state is a finite number",
            self.variables.state_name(i)
        )))
    }

    fn check_length(&self, found: usize, expected: usize, what: &str) -> Outcome {
        match found == expected {
            true => Ok(()),
            false => Err(Failure::error(format!(
                "{found} {what} asked for; the model has {expected}"
            ))),
        }
    }

    /// A copy of the simulation state (`fmi2GetFMUstate`).
    pub fn snapshot(&self) -> Snapshot {
        Snapshot {
            plant: self.plant.clone_box(),
            mode: self.mode,
            time_floor: self.time_floor,
        }
    }

    /// Back to a saved state (`fmi2SetFMUstate`).
    pub fn restore(&mut self, snapshot: &Snapshot) {
        self.plant = snapshot.plant.clone_box();
        self.mode = snapshot.mode;
        self.time_floor = snapshot.time_floor;
    }
}

/// `Err` unless `value` of the argument `name` is a finite number.
fn finite(name: &str, value: f64) -> Outcome {
    match value.is_finite() {
        true => Ok(()),
        false => Err(Failure::error(format!(
            "{name} = {value}: not a finite number"
        ))),
    }
}

/// A saved instance state (`fmi2FMUstate`).
pub struct Snapshot {
    plant: Box<dyn Plant>,
    mode: Mode,
    time_floor: f64,
}
