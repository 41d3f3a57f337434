//! The FMI 2.0 state machine: in which states, and for which interface,
//! each call is allowed (the tables of the standard, sections 3.2.3 and
//! 4.2.4, as the Modelica Association's Reference FMUs encode them). One
//! table, read by the guard (`guard::guard`) before every call on an instance
//! and by the instance's methods themselves.

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

/// Every mode of an instance.
const ANY: &[Mode] = &[
    Mode::Instantiated,
    Mode::Initialization,
    Mode::StepComplete,
    Mode::Event,
    Mode::ContinuousTime,
    Mode::Terminated,
    Mode::Failed,
];
/// After initialization: values can be read.
const READ: &[Mode] = &[
    Mode::Initialization,
    Mode::StepComplete,
    Mode::Event,
    Mode::ContinuousTime,
    Mode::Terminated,
    Mode::Failed,
];
/// Before termination: values can be set (which ones, [`settable_in`]).
const SET: &[Mode] = &[
    Mode::Instantiated,
    Mode::Initialization,
    Mode::StepComplete,
    Mode::Event,
    Mode::ContinuousTime,
];
/// Where the Model Exchange values of the states can be read.
const ME_READ: &[Mode] = &[
    Mode::Initialization,
    Mode::Event,
    Mode::ContinuousTime,
    Mode::Terminated,
    Mode::Failed,
];

/// Where `call` is allowed: its modes, and the one interface it belongs
/// to (`None`: both). `None` for a name that is no FMI 2.0 call on an
/// instance.
pub fn rule(call: &str) -> Option<(&'static [Mode], Option<Interface>)> {
    use Interface::{CoSimulation as Cs, ModelExchange as Me};
    use Mode::*;
    let (modes, interface): (&'static [Mode], _) = match call {
        "fmi2SetDebugLogging" | "fmi2FreeInstance" | "fmi2Reset" => (ANY, None),
        "fmi2GetFMUstate" | "fmi2SetFMUstate" | "fmi2FreeFMUstate" => (ANY, None),
        "fmi2SerializedFMUstateSize" | "fmi2SerializeFMUstate" | "fmi2DeSerializeFMUstate" => {
            (ANY, None)
        }
        "fmi2SetupExperiment" | "fmi2EnterInitializationMode" => (&[Instantiated], None),
        "fmi2ExitInitializationMode" => (&[Initialization], None),
        "fmi2Terminate" => (&[StepComplete, Event, ContinuousTime], None),
        "fmi2GetReal" | "fmi2GetInteger" | "fmi2GetBoolean" | "fmi2GetString" => (READ, None),
        "fmi2GetDirectionalDerivative" => (READ, None),
        "fmi2SetReal" => (SET, None),
        "fmi2SetInteger" | "fmi2SetBoolean" | "fmi2SetString" => {
            (&[Instantiated, Initialization, StepComplete, Event], None)
        }
        "fmi2EnterEventMode" => (&[Event, ContinuousTime], Some(Me)),
        "fmi2NewDiscreteStates" | "fmi2EnterContinuousTimeMode" => (&[Event], Some(Me)),
        "fmi2CompletedIntegratorStep" | "fmi2SetContinuousStates" => (&[ContinuousTime], Some(Me)),
        "fmi2SetTime" => (&[Event, ContinuousTime], Some(Me)),
        "fmi2GetEventIndicators" | "fmi2GetContinuousStates" => (ME_READ, Some(Me)),
        "fmi2GetDerivatives" => (&ME_READ[1..], Some(Me)),
        "fmi2GetNominalsOfContinuousStates" => (
            &[Instantiated, Event, ContinuousTime, Terminated, Failed],
            Some(Me),
        ),
        "fmi2SetRealInputDerivatives" => (&[Instantiated, Initialization, StepComplete], Some(Cs)),
        "fmi2GetRealOutputDerivatives" => (&[StepComplete, Terminated, Failed], Some(Cs)),
        "fmi2DoStep" => (&[StepComplete], Some(Cs)),
        // Steps are synchronous: never in stepInProgress.
        "fmi2CancelStep" => (&[], Some(Cs)),
        "fmi2GetStatus" | "fmi2GetRealStatus" | "fmi2GetIntegerStatus" => {
            (&[StepComplete, Terminated], Some(Cs))
        }
        "fmi2GetBooleanStatus" | "fmi2GetStringStatus" => (&[StepComplete, Terminated], Some(Cs)),
        _ => return None,
    };
    Some((modes, interface))
}

/// Why the state machine refuses a call ([`check`]). Each message
/// follows the call's name in the log (`fmi2DoStep: not allowed in state
/// …`).
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum CallError {
    /// A name that is no FMI 2.0 call on an instance.
    #[error("{call} is no FMI 2.0 function on an instance")]
    Unknown {
        /// The name.
        call: String,
    },
    /// A call of the other interface.
    #[error(
        "a {} function, and this instance was instantiated for {}",
        interface_name(*.only),
        interface_name(*.interface)
    )]
    Interface {
        /// The interface the call belongs to.
        only: Interface,
        /// The interface the instance was created for.
        interface: Interface,
    },
    /// A call the instance's state does not allow.
    #[error(
        "not allowed in state {}{} (allowed {})",
        state_name(*.mode),
        failed_hint(*.mode),
        allowed_list(.allowed)
    )]
    State {
        /// The instance's state.
        mode: Mode,
        /// The states that allow the call.
        allowed: &'static [Mode],
    },
}

/// `Err` saying why, unless an instance of `interface` in `mode` may be
/// called with `call`.
pub fn check(call: &str, interface: Interface, mode: Mode) -> Result<(), CallError> {
    let Some((modes, only)) = rule(call) else {
        return Err(CallError::Unknown {
            call: call.to_string(),
        });
    };
    if let Some(only) = only.filter(|&i| i != interface) {
        return Err(CallError::Interface { only, interface });
    }
    match modes.contains(&mode) {
        true => Ok(()),
        false => Err(CallError::State {
            mode,
            allowed: modes,
        }),
    }
}

/// `in A, B, C`, or `in no state of this FMU`.
fn allowed_list(modes: &[Mode]) -> String {
    let allowed: Vec<&str> = modes.iter().map(|&m| state_name(m)).collect();
    match allowed.is_empty() {
        true => "in no state of this FMU".to_string(),
        false => format!("in {}", allowed.join(", ")),
    }
}

/// The standard's name of a mode (`continuousTimeMode`).
pub fn state_name(mode: Mode) -> &'static str {
    match mode {
        Mode::Instantiated => "instantiated",
        Mode::Initialization => "initializationMode",
        Mode::StepComplete => "stepComplete",
        Mode::Event => "eventMode",
        Mode::ContinuousTime => "continuousTimeMode",
        Mode::Terminated => "terminated",
        Mode::Failed => "error",
    }
}

fn failed_hint(mode: Mode) -> &'static str {
    match mode {
        Mode::Failed => " (an earlier call failed: fmi2Reset, fmi2SetFMUstate or fmi2FreeInstance)",
        _ => "",
    }
}

fn interface_name(interface: Interface) -> &'static str {
    match interface {
        Interface::ModelExchange => "Model Exchange",
        Interface::CoSimulation => "Co-Simulation",
    }
}

/// Whether a variable of `causality` may be set in `mode`: parameters
/// (tunable) and inputs before initialization ends and between
/// Co-Simulation steps or in event mode; in continuous-time mode only
/// the (continuous) inputs.
pub fn settable_in(causality: crate::variables::Causality, mode: Mode) -> bool {
    use crate::variables::Causality;
    match causality {
        Causality::Input => SET.contains(&mode),
        Causality::Parameter => SET.contains(&mode) && mode != Mode::ContinuousTime,
        Causality::Output | Causality::Local => false,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_calls_before_initialization_are_those_the_standard_allows() {
        let me = Interface::ModelExchange;
        for call in [
            "fmi2SetupExperiment",
            "fmi2EnterInitializationMode",
            "fmi2SetReal",
        ] {
            assert_eq!(check(call, me, Mode::Instantiated), Ok(()), "{call}");
        }
        let early = check("fmi2GetDerivatives", me, Mode::Instantiated).unwrap_err();
        assert!(matches!(
            early,
            CallError::State {
                mode: Mode::Instantiated,
                ..
            }
        ));
        assert_eq!(
            early.to_string(),
            "not allowed in state instantiated \
             (allowed in eventMode, continuousTimeMode, terminated, error)"
        );
        assert!(check("fmi2GetReal", me, Mode::Instantiated).is_err());
    }

    #[test]
    fn a_call_of_the_other_interface_is_refused_by_name() {
        let wrong = check("fmi2DoStep", Interface::ModelExchange, Mode::Event).unwrap_err();
        assert_eq!(
            wrong.to_string(),
            "a Co-Simulation function, and this instance was instantiated \
             for Model Exchange"
        );
        let cs = Interface::CoSimulation;
        assert!(check("fmi2GetDerivatives", cs, Mode::StepComplete).is_err());
        assert_eq!(check("fmi2DoStep", cs, Mode::StepComplete), Ok(()));
    }

    #[test]
    fn after_a_failure_only_reading_resetting_and_restoring_are_allowed() {
        let cs = Interface::CoSimulation;
        for call in [
            "fmi2GetReal",
            "fmi2Reset",
            "fmi2SetFMUstate",
            "fmi2FreeInstance",
        ] {
            assert_eq!(check(call, cs, Mode::Failed), Ok(()), "{call}");
        }
        let step = check("fmi2DoStep", cs, Mode::Failed)
            .unwrap_err()
            .to_string();
        assert!(step.contains("an earlier call failed"), "{step}");
        assert!(check("fmi2SetReal", cs, Mode::Terminated).is_err());
        let cancel = check("fmi2CancelStep", cs, Mode::StepComplete).unwrap_err();
        assert_eq!(
            cancel.to_string(),
            "not allowed in state stepComplete (allowed in no state of this FMU)"
        );
        let unknown = check("fmi2Nothing", cs, Mode::StepComplete).unwrap_err();
        assert_eq!(
            unknown.to_string(),
            "fmi2Nothing is no FMI 2.0 function on an instance"
        );
    }

    #[test]
    fn parameters_are_not_set_while_the_host_integrates() {
        use crate::variables::Causality;
        assert!(settable_in(Causality::Parameter, Mode::Event));
        assert!(!settable_in(Causality::Parameter, Mode::ContinuousTime));
        assert!(settable_in(Causality::Input, Mode::ContinuousTime));
        assert!(!settable_in(Causality::Output, Mode::Instantiated));
    }

    #[test]
    fn every_entry_point_has_a_rule() {
        let source = [
            include_str!("common.rs"),
            include_str!("cs.rs"),
            include_str!("me.rs"),
        ];
        let mut calls = 0;
        for text in source {
            for (_, rest) in text
                .match_indices("guard(c, \"")
                .map(|(i, _)| text.split_at(i + 10))
            {
                let name = &rest[..rest.find('"').unwrap()];
                assert!(rule(name).is_some(), "{name}");
                calls += 1;
            }
        }
        assert!(calls >= 40, "{calls}");
    }
}
