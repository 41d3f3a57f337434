//! Dahl friction (Dahl, *A solid friction model*, Aerospace Corp.
//! TOR-0158(3107-18)-1, 1968): the friction force as a function of the
//! sliding displacement, rising from zero with a presliding stiffness `σ0`
//! towards the Coulomb force `Fc`, with hysteresis when the motion
//! reverses. In the bristle form, with the internal state `z` (`F = σ0·z`):
//!
//! ```text
//! r = 1 − σ0·z·sign(v)/Fc
//! ż = v·|r|^α·sign(r)
//! F = σ0·z
//! ```
//!
//! `v` is the second argument of its input (the sliding displacement and
//! its velocity). At a steady sliding speed `F = Fc·sign(v)`; for `α = 1`
//! it is LuGre without the Stribeck effect and damping. It stores
//! `σ0·z²/2`, so the power it dissipates is `F·v − σ0·z·ż`. Its columns
//! are `NAME.force [N]` and `NAME.velocity [m/s]`, its state `NAME.z [m]`.
//!
//! Its scenario section is `type = "dahl"` (`DahlSection`):
//! `inputs = { force = "F" }`, `fc`, `sigma0`, and optionally `alpha` (1)
//! and the initial `z0` (0).

use super::{Binder, Column, Component, Port, Section};
use crate::components::section::Ports;
use crate::components::{Dissipation, States};
use crate::curve::OutOfRange;
use crate::entry::EntryError;
use crate::entry::{finite, finite_combination, positive};
use serde::Deserialize;

/// The friction law's parameters and the bristles' deflection.
#[derive(Clone, Debug, PartialEq)]
pub struct Dahl {
    /// Coulomb force `Fc` \[N\].
    pub fc: f64,
    /// Presliding stiffness `σ0` \[N/m\].
    pub sigma0: f64,
    /// The exponent `α`.
    pub alpha: f64,
    /// The initial `z` \[m\].
    pub z0: f64,
    /// The current `z`, as the integrator last set it.
    z: f64,
}

const COLUMNS: &[Column] = &[
    Column {
        quantity: "force",
        unit: "N",
    },
    Column {
        quantity: "velocity",
        unit: "m/s",
    },
];

impl Dahl {
    /// `ż` at velocity `v` and the current `z`.
    pub fn z_rate(&self, v: f64) -> f64 {
        let r = 1.0 - self.sigma0 * self.z * v.signum() / self.fc;
        v * r.abs().powf(self.alpha) * r.signum()
    }

    /// `F` at the current `z`.
    pub fn force(&self) -> f64 {
        self.sigma0 * self.z
    }
}

impl Component for Dahl {
    fn kind(&self) -> &'static str {
        "dahl"
    }

    fn arguments(&self) -> Option<(usize, &'static str)> {
        Some((2, "the sliding displacement and its velocity"))
    }

    /// `F`; at a fixed `z` it depends on neither argument.
    fn value(&self, port: Port, _args: &[f64]) -> Result<f64, OutOfRange> {
        Ok(match port {
            Port::Value => self.force(),
            Port::Stiffness | Port::Damping => 0.0,
        })
    }

    capabilities!(events: no, states: yes, energy: yes);

    fn columns(&self) -> &'static [Column] {
        COLUMNS
    }

    fn column_values(&self, args: &[f64], out: &mut [f64]) -> Result<(), OutOfRange> {
        out[0] = self.force();
        out[1] = args[1];
        Ok(())
    }
}

impl States for Dahl {
    one_state!(z: "z" ["m"], from z0);

    fn state_rates(&self, args: &[f64], rates: &mut [f64]) -> Result<(), OutOfRange> {
        rates[0] = self.z_rate(args[1]);
        Ok(())
    }
}

impl Dissipation for Dahl {
    fn dissipated_power(&self, args: &[f64]) -> f64 {
        let v = args.get(1).copied().unwrap_or(0.0);
        self.force() * v - self.sigma0 * self.z * self.z_rate(v)
    }
}

fn one() -> f64 {
    1.0
}

/// `[components.NAME]` with `type = "dahl"`.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct DahlSection {
    inputs: Ports,
    fc: f64,
    sigma0: f64,
    #[serde(default = "one")]
    alpha: f64,
    #[serde(default)]
    z0: f64,
}

impl super::SectionUnits for DahlSection {
    const UNITS: &'static [(&'static str, super::Measure)] = {
        use super::Measure::One;
        &[("fc", One("N")), ("sigma0", One("N/m")), ("z0", One("m"))]
    };
}

impl Section for DahlSection {
    fn build(&self, name: &str, binder: &mut Binder) -> Result<(), EntryError> {
        let key = |entry: &str| format!("components.{name}.{entry}");
        let z0 = finite(key("z0"), self.z0)?;
        let law = Dahl {
            fc: positive(key("fc"), self.fc)?,
            sigma0: positive(key("sigma0"), self.sigma0)?,
            alpha: positive(key("alpha"), self.alpha)?,
            z0,
            z: z0,
        };
        let (sigma0, fc) = (law.sigma0, law.fc);
        let entries = [("sigma0", sigma0), ("fc", fc)];
        let formula = ("sigma0/fc", "the rate of z");
        finite_combination(format!("components.{name}"), formula, &entries, sigma0 / fc)?;
        let c = binder.add(name.to_string(), Box::new(law));
        binder.bind_ports(&self.inputs, "force", c, name)
    }
}
