//! A component defined and registered for tests only, the way every
//! component is (this file and one line of the `components!` list): a
//! linear spring that breaks when its extension reaches a threshold. Its
//! one event must fire in a simulation, which shows that a new component's
//! events reach the integrator without any other change. It has one
//! capability, [`Events`]: its other accessors say `None`.

use super::{Binder, Component, Event, Port, Report, Section};
use crate::components::Events;
use crate::components::section::Ports;
use crate::curve::OutOfRange;
use crate::entry::EntryError;
use crate::entry::positive;
use crate::ode::Direction;
use serde::Deserialize;

/// `F = −k·x` until `x` reaches `breaks_at`, 0 after.
#[derive(Clone, Debug)]
struct Spring {
    stiffness: f64,
    breaks_at: f64,
    broken_at: Option<f64>,
}

const EVENTS: &[Event] = &[Event {
    name: "spring breaks",
    direction: Direction::Rising,
}];

impl Component for Spring {
    fn kind(&self) -> &'static str {
        "test_spring"
    }

    fn arguments(&self) -> Option<(usize, &'static str)> {
        Some((2, "the extension and its rate"))
    }

    fn value(&self, port: Port, args: &[f64]) -> Result<f64, OutOfRange> {
        let k = match self.broken_at {
            Some(_) => 0.0,
            None => self.stiffness,
        };
        Ok(match port {
            Port::Value => -k * args[0],
            Port::Stiffness => -k,
            Port::Damping => 0.0,
        })
    }

    capabilities!(events: yes, states: no, energy: no);

    fn report(&self) -> Report {
        Report {
            failed_at: self.broken_at,
            ..Report::default()
        }
    }
}

impl Events for Spring {
    fn list(&self) -> &'static [Event] {
        EVENTS
    }

    fn event_values(&self, args: &[f64], g: &mut [f64]) -> Result<(), OutOfRange> {
        g[0] = match self.broken_at {
            Some(_) => -1.0,
            None => args[0] - self.breaks_at,
        };
        Ok(())
    }

    fn on_event(&mut self, _k: usize, t: f64, args: &[f64]) -> Result<String, OutOfRange> {
        self.broken_at = Some(t);
        Ok(format!("breaks at x = {:.4} m", args[0]))
    }

    fn start(&mut self, _args: Option<&[f64]>) -> Result<(), OutOfRange> {
        self.broken_at = None;
        Ok(())
    }
}

/// `[components.NAME]` with `type = "test_spring"`.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct SpringSection {
    inputs: Ports,
    stiffness: f64,
    breaks_at: f64,
}

impl super::SectionUnits for SpringSection {
    const UNITS: &'static [(&'static str, super::Measure)] = {
        use super::Measure::One;
        &[("stiffness", One("N/m")), ("breaks_at", One("m"))]
    };
}

impl Section for SpringSection {
    fn build(&self, name: &str, binder: &mut Binder) -> Result<(), EntryError> {
        let spring = Spring {
            stiffness: positive(format!("components.{name}.stiffness"), self.stiffness)?,
            breaks_at: positive(format!("components.{name}.breaks_at"), self.breaks_at)?,
            broken_at: None,
        };
        let c = binder.add(name.to_string(), Box::new(spring));
        binder.bind_ports(&self.inputs, "force", c, name)
    }
}
