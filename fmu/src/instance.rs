//! One FMU instance: the FMI 2.0 state machine around a [`Plant`], with
//! every call's checks and effects, free of C types so that it is tested
//! in Rust. The C entry points ([`crate::common`], [`crate::cs`],
//! [`crate::me`]) only convert arguments and report failures.

use crate::ffi::fmi2Status;
use crate::plant::{Plant, PlantFactory, plant};
use crate::resources::Loaded;
use crate::variables::Variables;

/// Which interface an instance was created for.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Interface {
    /// The host integrates `(q, q̇)` and handles the events it locates.
    ModelExchange,
    /// The FMU integrates between communication points.
    CoSimulation,
}

/// Where an instance is in the FMI 2.0 state machine.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Mode {
    /// After `fmi2Instantiate` (and `fmi2Reset`).
    Instantiated,
    /// Between `fmi2EnterInitializationMode` and `fmi2ExitInitializationMode`.
    Initialization,
    /// Co-Simulation, between steps.
    StepComplete,
    /// Model Exchange, handling events.
    Event,
    /// Model Exchange, integrating.
    ContinuousTime,
    /// After `fmi2Terminate`.
    Terminated,
    /// After a call failed: only `fmi2Reset` and `fmi2FreeInstance` help.
    Failed,
}

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
        let variables =
            Variables::new(spec, &loaded.scenario, &loaded.unbound).map_err(Failure::error)?;
        let plant = factory(loaded.model, &loaded.scenario).map_err(Failure::error)?;
        Ok(Instance {
            name: name.to_string(),
            interface,
            variables,
            logging: false,
            mode: Mode::Instantiated,
            fresh: plant.clone_box(),
            plant,
            start_time: 0.0,
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

    /// `Err` unless the instance is in one of `modes` for `call`.
    fn expect(&self, modes: &[Mode], call: &str) -> Outcome {
        if modes.contains(&self.mode) {
            return Ok(());
        }
        Err(Failure::error(format!(
            "{call} is not allowed in mode {:?}",
            self.mode
        )))
    }

    /// Runs a plant operation; its failure puts the instance in [`Mode::Failed`].
    fn run<T>(&mut self, f: impl FnOnce(&mut dyn Plant) -> Result<T, String>) -> Outcome<T> {
        f(self.plant.as_mut()).map_err(|message| {
            self.mode = Mode::Failed;
            Failure::error(message)
        })
    }

    /// `fmi2SetupExperiment`: the start time (the stop time and tolerance
    /// are the scenario's business).
    pub fn setup_experiment(&mut self, start_time: f64) -> Outcome {
        self.expect(&[Mode::Instantiated], "fmi2SetupExperiment")?;
        self.start_time = start_time;
        Ok(())
    }

    /// `fmi2EnterInitializationMode`: the initial state with the parameters
    /// set so far, for the outputs read during initialization.
    pub fn enter_initialization(&mut self) -> Outcome {
        self.expect(&[Mode::Instantiated], "fmi2EnterInitializationMode")?;
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
        self.expect(&[Mode::Initialization], "fmi2ExitInitializationMode")?;
        self.initialize()?;
        self.mode = match self.interface {
            Interface::CoSimulation => Mode::StepComplete,
            Interface::ModelExchange => Mode::Event,
        };
        Ok(())
    }

    /// `fmi2Terminate`.
    pub fn terminate(&mut self) -> Outcome {
        let running = [Mode::StepComplete, Mode::Event, Mode::ContinuousTime];
        self.expect(&running, "fmi2Terminate")?;
        self.mode = Mode::Terminated;
        Ok(())
    }

    /// `fmi2Reset`: back to the state after `fmi2Instantiate`.
    pub fn reset(&mut self) {
        self.plant = self.fresh.clone_box();
        self.mode = Mode::Instantiated;
        self.start_time = 0.0;
        self.pending_events.clear();
    }

    /// `fmi2GetReal`.
    pub fn get_real(&mut self, vrs: &[u32], values: &mut [f64]) -> Outcome {
        self.expect(&READABLE, "fmi2GetReal")?;
        let quantities = (vrs.iter())
            .map(|&vr| self.variables.get(vr).map(|v| v.quantity))
            .collect::<Option<Vec<_>>>()
            .ok_or_else(|| Failure::error(self.unknown(vrs)))?;
        self.run(|p| p.get(&quantities, values))
    }

    /// `fmi2SetReal`: parameters and inputs.
    pub fn set_real(&mut self, vrs: &[u32], values: &[f64]) -> Outcome {
        self.expect(&READABLE, "fmi2SetReal")?;
        for (&vr, &value) in vrs.iter().zip(values) {
            let variable = self
                .variables
                .get(vr)
                .ok_or_else(|| Failure::error(self.unknown(&[vr])))?;
            if !variable.settable() {
                let name = &variable.name;
                return Err(Failure::error(format!(
                    "`{name}` (value reference {vr}) is a {}: it cannot be set",
                    variable.causality().name()
                )));
            }
            let quantity = variable.quantity;
            self.plant.set(quantity, value).map_err(Failure::error)?;
        }
        Ok(())
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

    /// `fmi2DoStep`: integrates from `t` to `t + h`.
    pub fn do_step(&mut self, t: f64, h: f64) -> Outcome {
        self.expect(&[Mode::StepComplete], "fmi2DoStep")?;
        let now = self.plant.time();
        if (t - now).abs() > 1e-9 * now.abs().max(1.0) {
            return Err(Failure::error(format!(
                "fmi2DoStep from t = {t:e} s, but the FMU is at t = {now:e} s"
            )));
        }
        if !(h >= 0.0 && h.is_finite()) {
            return Err(Failure::error(format!("communication step {h:e} s")));
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
        self.expect(&[Mode::ContinuousTime, Mode::Event], "fmi2EnterEventMode")?;
        self.mode = Mode::Event;
        Ok(())
    }

    /// `fmi2NewDiscreteStates`: handles the events whose indicators crossed.
    pub fn new_discrete_states(&mut self) -> Outcome<EventUpdate> {
        self.expect(&[Mode::Event], "fmi2NewDiscreteStates")?;
        let before = self.states();
        let events = self.run(|p| p.handle_events())?;
        Ok(EventUpdate {
            states_changed: self.states() != before,
            events,
        })
    }

    /// `fmi2EnterContinuousTimeMode`.
    pub fn enter_continuous_time_mode(&mut self) -> Outcome {
        self.expect(&[Mode::Event], "fmi2EnterContinuousTimeMode")?;
        self.mode = Mode::ContinuousTime;
        Ok(())
    }

    /// `fmi2SetTime`.
    pub fn set_time(&mut self, t: f64) -> Outcome {
        let modes = [Mode::Event, Mode::ContinuousTime, Mode::Instantiated];
        self.expect(&modes, "fmi2SetTime")?;
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
        self.expect(
            &[Mode::Event, Mode::ContinuousTime],
            "fmi2SetContinuousStates",
        )?;
        self.check_length(x.len(), self.plant.state_count(), "states")?;
        self.plant.set_states(x);
        Ok(())
    }

    /// `fmi2GetDerivatives`.
    pub fn derivatives(&mut self, dx: &mut [f64]) -> Outcome {
        self.expect(&READABLE, "fmi2GetDerivatives")?;
        self.check_length(dx.len(), self.plant.state_count(), "derivatives")?;
        self.run(|p| p.derivatives(dx))
    }

    /// `fmi2GetEventIndicators`.
    pub fn event_indicators(&mut self, g: &mut [f64]) -> Outcome {
        self.expect(&READABLE, "fmi2GetEventIndicators")?;
        self.check_length(g.len(), self.plant.event_count(), "event indicators")?;
        self.run(|p| p.event_indicators(g))
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
        }
    }

    /// Back to a saved state (`fmi2SetFMUstate`).
    pub fn restore(&mut self, snapshot: &Snapshot) {
        self.plant = snapshot.plant.clone_box();
        self.mode = snapshot.mode;
    }
}

/// The modes in which variables can be read and set.
const READABLE: [Mode; 6] = [
    Mode::Instantiated,
    Mode::Initialization,
    Mode::StepComplete,
    Mode::Event,
    Mode::ContinuousTime,
    Mode::Terminated,
];

/// A saved instance state (`fmi2FMUstate`).
pub struct Snapshot {
    plant: Box<dyn Plant>,
    mode: Mode,
}
