//! A Kelvin–Voigt element: a linear spring and a linear dashpot in
//! parallel, `F = k·u + c·u̇` (Voigt, W., 1892; the standard element of
//! linear viscoelasticity), in the sign of its input's arguments (`u` an
//! extension gives a tension). Unlike a contact it pulls as well as
//! pushes. Its force and the power its dashpot dissipates, `c·u̇²`, are
//! trajectory columns (`NAME.force \[N\]`, `NAME.power \[W\]`).
//!
//! Its scenario section is `type = "kelvin_voigt"` (`KelvinVoigtSection`):
//! `stiffness` `k` [N/m] and `damping` `c` [N·s/m], both ≥ 0.

use super::{Binder, Column, Component, Port, Section, Smoothness};
use crate::components::Dissipation;
use crate::components::section::Ports;
use crate::curve::OutOfRange;
use crate::entry::EntryError;
use crate::entry::non_negative;
use serde::Deserialize;

/// `F = k·u + c·u̇`.
#[derive(Clone, Debug, PartialEq)]
pub struct KelvinVoigt {
    /// `k` [N/m].
    pub stiffness: f64,
    /// `c` [N·s/m].
    pub damping: f64,
}

/// Its columns: the force and the dissipated power.
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

impl KelvinVoigt {
    /// `F` at the arguments `(u, u̇)`.
    pub fn force(&self, args: &[f64]) -> f64 {
        self.stiffness * args[0] + self.damping * args[1]
    }

    /// `c·u̇²` \[W\].
    pub fn power(&self, args: &[f64]) -> f64 {
        self.damping * args[1] * args[1]
    }
}

impl Component for KelvinVoigt {
    fn kind(&self) -> &'static str {
        "kelvin_voigt"
    }

    fn arguments(&self) -> Option<(usize, &'static str)> {
        Some((2, "the extension and its rate"))
    }

    fn value(&self, port: Port, args: &[f64]) -> Result<f64, OutOfRange> {
        Ok(match port {
            Port::Value => self.force(args),
            Port::Stiffness => self.stiffness,
            Port::Damping => self.damping,
        })
    }

    capabilities!(events: no, states: no, energy: yes);

    fn columns(&self) -> &'static [Column] {
        COLUMNS
    }

    fn column_values(&self, args: &[f64], out: &mut [f64]) -> Result<(), OutOfRange> {
        out[0] = self.force(args);
        out[1] = self.power(args);
        Ok(())
    }

    fn smoothness(&self) -> Smoothness {
        Smoothness::Smooth
    }
}

impl Dissipation for KelvinVoigt {
    fn dissipated_power(&self, args: &[f64]) -> f64 {
        self.power(args)
    }
}

/// `[components.NAME]` with `type = "kelvin_voigt"`: `stiffness`,
/// `damping` and the inputs it supplies (force and, optionally, its
/// derivatives).
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct KelvinVoigtSection {
    inputs: Ports,
    stiffness: f64,
    damping: f64,
}

impl super::SectionUnits for KelvinVoigtSection {
    const UNITS: &'static [(&'static str, super::Measure)] = {
        use super::Measure::One;
        &[("stiffness", One("N/m")), ("damping", One("N*s/m"))]
    };
}

impl Section for KelvinVoigtSection {
    fn build(&self, name: &str, binder: &mut Binder) -> Result<(), EntryError> {
        let key = |entry: &str| format!("components.{name}.{entry}");
        let element = KelvinVoigt {
            stiffness: non_negative(key("stiffness"), self.stiffness)?,
            damping: non_negative(key("damping"), self.damping)?,
        };
        let c = binder.add(name.to_string(), Box::new(element));
        binder.bind_ports(&self.inputs, "force", c, name)
    }
}
