//! A Maxwell element: a linear spring and a viscous dashpot in series
//! (Maxwell 1867), the simplest model of stress relaxation, with one
//! internal state, the dashpot's displacement `d`.
//!
//! ```text
//! F = k·(u − d)
//! ḋ = F / c
//! ```
//!
//! `u` is the argument of its input (the element's total deflection; a
//! second argument, its rate, is not needed but may be given). Held at a
//! step deflection `u₀`, its force relaxes as `k·u₀·exp(−k·t/c)`. It stores
//! `k·(u − d)²/2` in the spring and dissipates `P = F²/c` in the dashpot.
//! Its columns are `NAME.force [N]` and `NAME.deflection [m]`, its state
//! `NAME.dashpot [m]`.
//!
//! Its scenario section is `type = "maxwell"` (`MaxwellSection`):
//! `inputs = { force = "F" }`, `stiffness`, `damping` and optionally the
//! initial dashpot displacement `dashpot0` (0).

use super::{Binder, Column, Component, Port, Section, Smoothness};
use crate::components::section::Ports;
use crate::components::{Dissipation, States};
use crate::curve::OutOfRange;
use crate::entry::EntryError;
use crate::entry::{finite, finite_combination, positive};
use serde::Deserialize;

/// The element's parameters and its dashpot's displacement.
#[derive(Clone, Debug, PartialEq)]
pub struct Maxwell {
    /// The spring's stiffness `k` \[N/m\].
    pub stiffness: f64,
    /// The dashpot's damping `c` [N·s/m].
    pub damping: f64,
    /// The initial dashpot displacement \[m\].
    pub dashpot0: f64,
    /// The current dashpot displacement `d`, as the integrator last set it.
    dashpot: f64,
}

const COLUMNS: &[Column] = &[
    Column {
        quantity: "force",
        unit: "N",
    },
    Column {
        quantity: "deflection",
        unit: "m",
    },
];

impl Maxwell {
    /// An element whose dashpot starts at `dashpot0`.
    pub fn new(stiffness: f64, damping: f64, dashpot0: f64) -> Maxwell {
        Maxwell {
            stiffness,
            damping,
            dashpot0,
            dashpot: dashpot0,
        }
    }

    /// `F` at deflection `u`.
    pub fn force(&self, u: f64) -> f64 {
        self.stiffness * (u - self.dashpot)
    }
}

impl Component for Maxwell {
    fn kind(&self) -> &'static str {
        "maxwell"
    }

    fn arguments(&self) -> Option<(usize, &'static str)> {
        None
    }

    /// `F`; its derivative with respect to `u` at a fixed `d` is `k`.
    fn value(&self, port: Port, args: &[f64]) -> Result<f64, OutOfRange> {
        Ok(match port {
            Port::Value => self.force(args[0]),
            Port::Stiffness => self.stiffness,
            Port::Damping => 0.0,
        })
    }

    capabilities!(events: no, states: yes, energy: yes);

    fn columns(&self) -> &'static [Column] {
        COLUMNS
    }

    fn column_values(&self, args: &[f64], out: &mut [f64]) -> Result<(), OutOfRange> {
        out[0] = self.force(args[0]);
        out[1] = args[0];
        Ok(())
    }

    fn smoothness(&self) -> Smoothness {
        Smoothness::Smooth
    }
}

impl States for Maxwell {
    one_state!(dashpot: "dashpot" ["m"], from dashpot0);

    fn state_rates(&self, args: &[f64], rates: &mut [f64]) -> Result<(), OutOfRange> {
        rates[0] = self.force(args[0]) / self.damping;
        Ok(())
    }
}

impl Dissipation for Maxwell {
    fn dissipated_power(&self, args: &[f64]) -> f64 {
        let force = self.force(args.first().copied().unwrap_or(0.0));
        force * force / self.damping
    }
}

/// `[components.NAME]` with `type = "maxwell"`.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct MaxwellSection {
    inputs: Ports,
    stiffness: f64,
    damping: f64,
    #[serde(default)]
    dashpot0: f64,
}

impl super::SectionUnits for MaxwellSection {
    const UNITS: &'static [(&'static str, super::Measure)] = {
        use super::Measure::One;
        &[
            ("stiffness", One("N/m")),
            ("damping", One("N*s/m")),
            ("dashpot0", One("m")),
        ]
    };
}

impl Section for MaxwellSection {
    fn build(&self, name: &str, binder: &mut Binder) -> Result<(), EntryError> {
        let key = |entry: &str| format!("components.{name}.{entry}");
        let element = Maxwell::new(
            positive(key("stiffness"), self.stiffness)?,
            positive(key("damping"), self.damping)?,
            finite(key("dashpot0"), self.dashpot0)?,
        );
        let (k, c) = (element.stiffness, element.damping);
        let entries = [("stiffness", k), ("damping", c)];
        let formula = ("stiffness/damping", "the dashpot's rate");
        finite_combination(format!("components.{name}"), formula, &entries, k / c)?;
        let c = binder.add(name.to_string(), Box::new(element));
        binder.bind_ports(&self.inputs, "force", c, name)
    }
}
