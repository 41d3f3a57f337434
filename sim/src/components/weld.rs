//! A torsional spring for a weld or heat-affected zone that fails.
//!
//! Intact, its moment follows a curve of angle plus viscous damping,
//! `M = M_intact(θ) + c·θ̇`; when `|M_intact(θ)|` reaches the failure moment
//! (or `|θ|` the failure angle) an event switches it to the post-failure
//! curve and damping for the rest of the run. Its moment and angle are
//! trajectory columns (`NAME.moment [N*m]`, `NAME.angle [rad]`).
//!
//! With `stop_at_kinks` (the default) no step straddles a kink of the curve
//! in use: the weld holds the segment the angle is on, continued past its
//! points, and crossing a kink is an event after which it holds the next
//! one ([`super::held`]).
//!
//! It reports the energy it dissipates: the work it absorbs less the
//! elastic energy its current curve stores, `∫₀^θ M dx`. That is its
//! damper's `∫ c·θ̇² dt`, and at failure the energy the intact curve stored
//! less what the post-failure curve stores at that angle.
//!
//! Its scenario section is `type = "weld"` (`WeldSection`).

use super::held::{self, Crossed, Held};
use super::integral::integral;
use super::{Binder, Column, Component, Event, Port, Report, Section, Smoothness};
use crate::components::section::Ports;
use crate::components::{Dissipation, Events};
use crate::curve::outside;
use crate::curve::{Curve, OutOfRange};
use crate::entry::{EntryError, KeyPath};
use crate::entry::{non_negative, positive};
use crate::ode::Direction;
use serde::Deserialize;

/// The weld and its state during a run.
#[derive(Clone, Debug, PartialEq)]
pub struct Weld {
    /// `M_intact(θ)` [N·m].
    pub intact: Curve,
    /// `c` while intact [N·m·s/rad].
    pub damping: f64,
    /// It fails when `|M_intact(θ)|` reaches this [N·m].
    pub failure_moment: Option<f64>,
    /// It fails when `|θ|` reaches this \[rad\].
    pub failure_angle: Option<f64>,
    /// `None`: no moment after failure.
    pub post_failure: Option<Curve>,
    /// `c` after failure [N·m·s/rad].
    pub post_failure_damping: f64,
    /// No step straddles a kink of the curve in use (see the module
    /// documentation); on unless [`Weld::with_stop_at_kinks`] turns it off.
    pub stop_at_kinks: bool,
    /// The piece of the curve in use held.
    held: Held,
    failed_at: Option<f64>,
}

/// The weld's events: failure by moment, failure by angle.
pub(crate) const EVENTS: &[Event] = &[
    Event {
        name: "weld failure (moment)",
        direction: Direction::Rising,
    },
    Event {
        name: "weld failure (angle)",
        direction: Direction::Rising,
    },
    KINKS[0],
    KINKS[1],
];

/// The held segment ends: the angle crosses a kink of the curve in use.
const KINKS: [Event; 2] = held::events(
    "angle below a kink of the weld's curve",
    "angle above a kink of the weld's curve",
);

/// The weld's columns: its moment and its angle.
const COLUMNS: &[Column] = &[
    Column {
        quantity: "moment",
        unit: "N*m",
    },
    Column {
        quantity: "angle",
        unit: "rad",
    },
];

impl Weld {
    /// An intact weld.
    pub fn new(
        intact: Curve,
        damping: f64,
        failure_moment: Option<f64>,
        failure_angle: Option<f64>,
        post_failure: Option<Curve>,
        post_failure_damping: f64,
    ) -> Weld {
        Weld {
            intact,
            damping,
            failure_moment,
            failure_angle,
            post_failure,
            post_failure_damping,
            stop_at_kinks: true,
            held: Held::NONE,
            failed_at: None,
        }
    }

    /// The weld that holds the segment of its curve within a step (`true`,
    /// the default) or steps across its kinks (`false`).
    pub fn with_stop_at_kinks(self, stop_at_kinks: bool) -> Weld {
        Weld {
            stop_at_kinks,
            ..self
        }
    }

    /// The moment curve in use: the intact one, or after failure the
    /// post-failure one if any.
    fn curve(&self) -> Option<&Curve> {
        match self.failed_at {
            None => Some(&self.intact),
            Some(_) => self.post_failure.as_ref(),
        }
    }

    /// `(M_intact(θ), dM/dθ)` on the held segment, while intact.
    fn intact_moment(&self, angle: f64) -> Result<(f64, f64), OutOfRange> {
        self.held.eval(&self.intact, angle)
    }

    /// Event function `k` at angle `angle` (see [`Weld::event_values`]).
    fn event_at(&self, k: usize, angle: f64) -> Result<f64, OutOfRange> {
        let intact = self.failed_at.is_none();
        Ok(match k {
            0 => match self.failure_moment {
                Some(limit) if intact => self.intact_moment(angle)?.0.abs() - limit,
                _ => -1.0,
            },
            1 => match self.failure_angle {
                Some(limit) if intact => angle.abs() - limit,
                _ => -1.0,
            },
            k => {
                let curve = self.curve().unwrap_or(&self.intact);
                self.held.event_values(curve, angle, f64::NEG_INFINITY)[k - 2]
            }
        })
    }

    /// Fails at time `t` and angle `angle`; holds the post-failure curve's
    /// segment there.
    fn fail(&mut self, t: f64, angle: f64) -> Result<String, OutOfRange> {
        let moment = self.intact_moment(angle)?.0;
        self.failed_at = Some(t);
        self.held = match &self.post_failure {
            Some(curve) => Held::at(curve, angle, self.stop_at_kinks),
            None => Held::NONE,
        };
        Ok(format!(
            "weld fails at θ = {:.3}° (spring moment {:.2} kN·m)",
            angle.to_degrees(),
            moment / 1e3
        ))
    }

    /// Holds the next segment across the kink `crossed`, the angle now at
    /// `angle`; no description.
    fn cross(&mut self, crossed: Crossed, angle: f64) -> String {
        if let Some(curve) = self.curve() {
            let mut held = self.held;
            held.cross(curve, crossed, angle);
            self.held = held;
        }
        String::new()
    }

    /// The time of failure, if the weld failed.
    pub fn failed_at(&self) -> Option<f64> {
        self.failed_at
    }

    /// `(M, ∂M/∂θ, ∂M/∂θ̇)` at arguments `(θ, θ̇)`.
    pub fn moment(&self, args: &[f64]) -> Result<(f64, f64, f64), OutOfRange> {
        let (angle, rate) = (args[0], args[1]);
        if self.failed_at.is_some() {
            let (m, dm) = match &self.post_failure {
                Some(curve) => self.held.eval(curve, angle)?,
                None => (0.0, 0.0),
            };
            return Ok((
                m + self.post_failure_damping * rate,
                dm,
                self.post_failure_damping,
            ));
        }
        let (m, dm) = self.intact_moment(angle)?;
        Ok((m + self.damping * rate, dm, self.damping))
    }
}

impl Component for Weld {
    fn kind(&self) -> &'static str {
        "weld"
    }

    fn arguments(&self) -> Option<(usize, &'static str)> {
        Some((2, "the angle and its rate"))
    }

    fn value(&self, port: Port, args: &[f64]) -> Result<f64, OutOfRange> {
        let (m, dm, dc) = self.moment(args)?;
        Ok(match port {
            Port::Value => m,
            Port::Stiffness => dm,
            Port::Damping => dc,
        })
    }

    capabilities!(events: yes, states: no, energy: yes);

    fn report(&self) -> Report {
        Report {
            failed_at: self.failed_at,
            ..Report::default()
        }
    }

    fn columns(&self) -> &'static [Column] {
        COLUMNS
    }

    /// The moment `M` (damping included) and the angle `θ`.
    fn column_values(&self, args: &[f64], out: &mut [f64]) -> Result<(), OutOfRange> {
        out[0] = self.moment(args)?.0;
        out[1] = args[0];
        Ok(())
    }

    /// Smooth when it holds the segment of its curve (`stop_at_kinks`):
    /// its failure and the kinks of its curve are then events.
    fn smoothness(&self) -> Smoothness {
        match self.stop_at_kinks {
            true => Smoothness::Smooth,
            false => Smoothness::Unknown,
        }
    }
}

impl Events for Weld {
    fn list(&self) -> &'static [Event] {
        EVENTS
    }

    /// `|M_intact(θ)| − M_fail` and `|θ| − θ_fail` while intact; −1 otherwise;
    /// then (stopping at kinks) `θ` less the kinks below (falling) and above
    /// (rising) the held segment of the curve in use.
    fn event_values(&self, args: &[f64], g: &mut [f64]) -> Result<(), OutOfRange> {
        for (k, value) in g[..EVENTS.len()].iter_mut().enumerate() {
            *value = self.event_at(k, args[0])?;
        }
        Ok(())
    }

    /// The one asked for of [`Weld::event_values`].
    fn event_value(&self, k: usize, args: &[f64], _: &mut [f64]) -> Result<f64, OutOfRange> {
        self.event_at(k, args[0])
    }

    /// Events 0 and 1 are the failure; 2 and 3 a kink of the curve crossed
    /// (the next segment held; an empty description: no change of regime).
    fn on_event(&mut self, k: usize, t: f64, args: &[f64]) -> Result<String, OutOfRange> {
        match k {
            0 | 1 => self.fail(t, args[0]),
            2 => Ok(self.cross(Crossed::Below, args[0])),
            _ => Ok(self.cross(Crossed::Above, args[0])),
        }
    }

    /// Intact again, holding the segment of the angle `args` start at.
    fn start(&mut self, args: Option<&[f64]>) -> Result<(), OutOfRange> {
        self.failed_at = None;
        let angle = args.map_or(0.0, |args| args[0]);
        self.held = Held::at(&self.intact, angle, self.stop_at_kinks);
        Ok(())
    }
}

impl Dissipation for Weld {
    /// The power the weld absorbs, `M·θ̇` (damping included), of which
    /// [`Dissipation::stored_energy`] says what its spring stores; NaN where
    /// its curve cannot be evaluated (the moment then reports it).
    fn dissipated_power(&self, args: &[f64]) -> f64 {
        self.moment(args).map_or(f64::NAN, |(m, _, _)| m * args[1])
    }

    /// `∫₀^θ M(x) dx` of the current curve (intact, or post-failure; none
    /// after a failure without one), measured from θ = 0, where the
    /// curves are taken to be unloaded.
    fn stored_energy(&self, args: &[f64]) -> Result<f64, OutOfRange> {
        let curve = match self.failed_at {
            None => Some(&self.intact),
            Some(_) => self.post_failure.as_ref(),
        };
        match curve {
            Some(curve) => {
                let moment = |x| curve.eval(x).map(|(m, _)| m);
                let breaks = curve.xs().iter().flat_map(|&x| [x, -x]);
                integral(moment, 0.0, args[0], breaks)
            }
            None => Ok(0.0),
        }
    }
}

/// `[components.NAME]` with `type = "weld"`: the intact and post-failure
/// curves `[[θ, M], …]`, damping, failure limits, and the inputs it supplies
/// (`moment` and, optionally, its tangent stiffness and damping).
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct WeldSection {
    inputs: Ports,
    curve: Vec<[f64; 2]>,
    #[serde(default)]
    damping: f64,
    failure_moment: Option<f64>,
    failure_angle: Option<f64>,
    post_failure_curve: Option<Vec<[f64; 2]>>,
    #[serde(default)]
    post_failure_damping: f64,
    #[serde(default = "extrapolate")]
    outside: String,
    #[serde(default = "yes")]
    stop_at_kinks: bool,
}

impl super::SectionUnits for WeldSection {
    const UNITS: &'static [(&'static str, super::Measure)] = {
        use super::Measure::{One, Pairs};
        &[
            ("curve", Pairs("rad", "N*m")),
            ("damping", One("N*m*s/rad")),
            ("failure_moment", One("N*m")),
            ("failure_angle", One("rad")),
            ("post_failure_curve", Pairs("rad", "N*m")),
            ("post_failure_damping", One("N*m*s/rad")),
        ]
    };
}

fn yes() -> bool {
    true
}

fn extrapolate() -> String {
    "extrapolate".into()
}

impl Section for WeldSection {
    fn build(&self, name: &str, binder: &mut Binder) -> Result<(), EntryError> {
        let weld = self.weld(name)?;
        let c = binder.add(name.to_string(), Box::new(weld));
        binder.bind_ports(&self.inputs, "moment", c, name)
    }
}

impl WeldSection {
    /// The weld `[components.{name}]` describes.
    fn weld(&self, name: &str) -> Result<Weld, EntryError> {
        let policy = outside(&format!("components.{name}"), &self.outside)?;
        let make = |points: &[[f64; 2]], what: &str| {
            Curve::new(
                points.iter().map(|p| p[0]).collect(),
                points.iter().map(|p| p[1]).collect(),
                policy,
            )
            .map_err(|e| EntryError::at(KeyPath::component(name), format!("{what}: {e}")))
        };
        let key = |entry: &str| format!("components.{name}.{entry}");
        non_negative(key("damping"), self.damping)?;
        non_negative(key("post_failure_damping"), self.post_failure_damping)?;
        if let Some(m) = self.failure_moment {
            positive(key("failure_moment"), m)?;
        }
        if let Some(a) = self.failure_angle {
            positive(key("failure_angle"), a)?;
        }
        let intact = make(&self.curve, "curve")?;
        let post = self
            .post_failure_curve
            .as_deref()
            .map(|p| make(p, "post_failure_curve"))
            .transpose()?;
        Ok(Weld::new(
            intact,
            self.damping,
            self.failure_moment,
            self.failure_angle,
            post,
            self.post_failure_damping,
        )
        .with_stop_at_kinks(self.stop_at_kinks))
    }
}
