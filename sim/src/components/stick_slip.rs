//! Coulomb friction with an event-switched stick: the body sticks while
//! the force applied along the surface stays within the static limit, and
//! slides against the kinetic friction otherwise (Coulomb, C. A., 1785;
//! the switching of Karnopp, D., 1985, "Computer simulation of stick-slip
//! friction in mechanical dynamic systems", Journal of Dynamic Systems,
//! Measurement, and Control 107: 100–103, with events in place of his
//! velocity band).
//!
//! Its input takes the sliding velocity `v` and the force `F_a` applied
//! along it (everything but this friction), and gives the friction force
//! in the sign of `v` (the model subtracts it):
//!
//! * sticking: `F = F_a`, so the body stays at rest, until `|F_a|` reaches
//!   `μ_s·N` (event: breakaway, sliding the way `F_a` pushes);
//! * sliding in direction `s = ±1`: `F = s·μ_k·N` until `v` is back at 0
//!   (event: it sticks there if `|F_a| ≤ μ_s·N`, else slides the other way).
//!
//! Its force and the power it dissipates, `F·v`, are trajectory columns
//! (`NAME.force \[N\]`, `NAME.power \[W\]`).
//!
//! Its scenario section is `type = "stick_slip"` (`StickSlipSection`):
//! `coefficient` `μ_k`, `static_coefficient` `μ_s ≥ μ_k` (default `μ_k`)
//! and `normal_force` `N` \[N\].

use super::{Binder, Column, Component, Event, Port, Section};
use crate::components::section::Ports;
use crate::components::{Dissipation, Events};
use crate::curve::OutOfRange;
use crate::entry::EntryError;
use crate::entry::non_negative;
use crate::ode::Direction;
use serde::Deserialize;

/// The friction and its state during a run.
#[derive(Clone, Debug, PartialEq)]
pub struct StickSlip {
    /// `μ_k`.
    pub kinetic: f64,
    /// `μ_s ≥ μ_k`.
    pub stiction: f64,
    /// `N` \[N\].
    pub normal_force: f64,
    /// `None`: sticking; `Some(s)`: sliding in direction `s = ±1`.
    sliding: Option<f64>,
}

/// Its events: breakaway while sticking, stop while sliding.
const EVENTS: &[Event] = &[
    Event {
        name: "breakaway",
        direction: Direction::Rising,
    },
    Event {
        name: "stop",
        direction: Direction::Falling,
    },
];

/// Its columns: the friction force and the dissipated power.
const COLUMNS: &[Column] = &[
    Column {
        quantity: "force",
        unit: "N",
    },
    Column {
        quantity: "power",
        unit: "W",
    },
];

impl StickSlip {
    /// A friction of coefficients `kinetic` ≤ `stiction` under
    /// `normal_force`, sticking.
    pub fn new(kinetic: f64, stiction: f64, normal_force: f64) -> StickSlip {
        StickSlip {
            kinetic,
            stiction,
            normal_force,
            sliding: None,
        }
    }

    /// `None` while sticking, else the direction of sliding.
    pub fn sliding(&self) -> Option<f64> {
        self.sliding
    }

    /// `(F, ∂F/∂v, ∂F/∂F_a)` at the arguments `(v, F_a)`.
    pub fn force(&self, args: &[f64]) -> (f64, f64, f64) {
        match self.sliding {
            None => (args[1], 0.0, 1.0),
            Some(s) => (s * self.kinetic * self.normal_force, 0.0, 0.0),
        }
    }

    /// Whether a body at rest under `applied` sticks; else the direction it
    /// slides.
    fn regime_at_rest(&self, applied: f64) -> Option<f64> {
        match applied.abs() <= self.stiction * self.normal_force {
            true => None,
            false => Some(applied.signum()),
        }
    }
}

impl Component for StickSlip {
    fn kind(&self) -> &'static str {
        "stick_slip"
    }

    fn arguments(&self) -> Option<(usize, &'static str)> {
        Some((
            2,
            "the sliding velocity and the force applied along it, friction aside",
        ))
    }

    fn value(&self, port: Port, args: &[f64]) -> Result<f64, OutOfRange> {
        let (f, dv, da) = self.force(args);
        Ok(match port {
            Port::Value => f,
            Port::Stiffness => dv,
            Port::Damping => da,
        })
    }

    capabilities!(events: yes, states: no, energy: yes);

    fn columns(&self) -> &'static [Column] {
        COLUMNS
    }

    fn column_values(&self, args: &[f64], out: &mut [f64]) -> Result<(), OutOfRange> {
        out[0] = self.force(args).0;
        out[1] = out[0] * args[0];
        Ok(())
    }
}

impl Events for StickSlip {
    fn list(&self) -> &'static [Event] {
        EVENTS
    }

    /// 0. breakaway (sticking): `|F_a| − μ_s·N`, rising;
    /// 1. stop (sliding in direction `s`): `s·v`, falling.
    fn event_values(&self, args: &[f64], g: &mut [f64]) -> Result<(), OutOfRange> {
        let limit = self.stiction * self.normal_force;
        g[0] = match self.sliding {
            None => args[1].abs() - limit,
            Some(_) => -1.0,
        };
        g[1] = match self.sliding {
            None => 1.0,
            Some(s) => s * args[0],
        };
        Ok(())
    }

    fn on_event(&mut self, k: usize, _t: f64, args: &[f64]) -> Result<String, OutOfRange> {
        let applied = args[1];
        self.sliding = match k {
            0 => Some(applied.signum()),
            _ => self.regime_at_rest(applied),
        };
        Ok(match self.sliding {
            None => format!("sticks under {applied:.4} N"),
            Some(s) => format!("slides towards {s:+} under {applied:.4} N"),
        })
    }

    /// Sliding the way it moves, or at rest as the applied force decides.
    fn start(&mut self, args: Option<&[f64]>) -> Result<(), OutOfRange> {
        let (v, applied) = args.map_or((0.0, 0.0), |a| (a[0], a[1]));
        self.sliding = match v == 0.0 {
            true => self.regime_at_rest(applied),
            false => Some(v.signum()),
        };
        Ok(())
    }
}

impl Dissipation for StickSlip {
    /// `F·v`: 0 while sticking.
    fn dissipated_power(&self, args: &[f64]) -> f64 {
        self.force(args).0 * args[0]
    }
}

/// `[components.NAME]` with `type = "stick_slip"`: `coefficient`,
/// `static_coefficient` (default `coefficient`), `normal_force` and the
/// inputs it supplies.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct StickSlipSection {
    inputs: Ports,
    coefficient: f64,
    static_coefficient: Option<f64>,
    normal_force: f64,
}

impl super::SectionUnits for StickSlipSection {
    const UNITS: &'static [(&'static str, super::Measure)] = {
        use super::Measure::One;
        &[("normal_force", One("N"))]
    };
}

impl Section for StickSlipSection {
    fn build(&self, name: &str, binder: &mut Binder) -> Result<(), EntryError> {
        let key = |entry: &str| format!("components.{name}.{entry}");
        let kinetic = non_negative(key("coefficient"), self.coefficient)?;
        let stiction = self.static_coefficient.unwrap_or(kinetic);
        let stiction = non_negative(key("static_coefficient"), stiction)?;
        if stiction < kinetic {
            return Err(EntryError::value(
                key("static_coefficient").into(),
                format!("{stiction}"),
                format!(
                    "the static coefficient μ_s must be at least the kinetic one (coefficient = {kinetic})"
                ),
            ));
        }
        let normal = non_negative(key("normal_force"), self.normal_force)?;
        let c = binder.add(
            name.to_string(),
            Box::new(StickSlip::new(kinetic, stiction, normal)),
        );
        binder.bind_ports(&self.inputs, "force", c, name)
    }
}
