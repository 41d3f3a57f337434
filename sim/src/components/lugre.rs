//! LuGre friction (Canudas de Wit, Olsson, Åström & Lischinsky, *A new
//! model for control of systems with friction*, IEEE TAC 1995): the
//! contact's bristles deflect by `z`, an internal state, which gives
//! presliding stiffness, stiction with a break-away force, the Stribeck
//! drop of the friction force with speed, and stick–slip.
//!
//! ```text
//! g(v) = Fc + (Fs − Fc)·exp(−(v/vs)²)
//! ż    = v − σ0·|v|·z / g(v)
//! F    = σ0·z + σ1·ż + σ2·v
//! ```
//!
//! `v` is the second argument of its input (the sliding displacement and
//! its velocity); `F` opposes the motion when the model subtracts it. At a
//! steady sliding speed `ż = 0` and `F = g(v)·sign(v) + σ2·v`: the
//! Stribeck curve. The bristles store `σ0·z²/2`, so the power it
//! dissipates is `F·v − σ0·z·ż`. Its columns are `NAME.force [N]` and
//! `NAME.velocity [m/s]`, its state `NAME.z [m]`.
//!
//! Its scenario section is `type = "lugre"` (`LuGreSection`):
//! `inputs = { force = "F" }`, `fc`, `fs`, `vs`, `sigma0`, and optionally
//! `sigma1` (0), `sigma2` (0) and the initial `z0` (0).

use super::{Binder, Column, Component, Port, Section};
use crate::components::section::Ports;
use crate::components::{Dissipation, States};
use crate::curve::OutOfRange;
use crate::entry::EntryError;
use crate::entry::{finite, non_negative, positive};
use serde::Deserialize;

/// The friction law's parameters and the bristles' deflection.
#[derive(Clone, Debug, PartialEq)]
pub struct LuGre {
    /// Coulomb force `Fc` \[N\].
    pub fc: f64,
    /// Static (break-away) force `Fs ≥ Fc` \[N\].
    pub fs: f64,
    /// Stribeck velocity `vs` \[m/s\].
    pub vs: f64,
    /// Bristle stiffness `σ0` \[N/m\].
    pub sigma0: f64,
    /// Bristle damping `σ1` [N·s/m].
    pub sigma1: f64,
    /// Viscous friction `σ2` [N·s/m].
    pub sigma2: f64,
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

impl LuGre {
    /// `g(v)` and `g'(v)`.
    fn stribeck(&self, v: f64) -> (f64, f64) {
        let decay = (-(v / self.vs).powi(2)).exp();
        let g = self.fc + (self.fs - self.fc) * decay;
        (
            g,
            (self.fs - self.fc) * decay * (-2.0 * v / (self.vs * self.vs)),
        )
    }

    /// `ż` at velocity `v` and the current `z`.
    pub fn z_rate(&self, v: f64) -> f64 {
        v - self.sigma0 * v.abs() * self.z / self.stribeck(v).0
    }

    /// `F` at velocity `v`.
    pub fn force(&self, v: f64) -> f64 {
        self.sigma0 * self.z + self.sigma1 * self.z_rate(v) + self.sigma2 * v
    }

    /// `∂F/∂v` at a fixed `z`.
    fn damping(&self, v: f64) -> f64 {
        let (g, dg) = self.stribeck(v);
        let dz = 1.0 - self.sigma0 * self.z * (v.signum() * g - v.abs() * dg) / (g * g);
        self.sigma1 * dz + self.sigma2
    }
}

impl Component for LuGre {
    fn kind(&self) -> &'static str {
        "lugre"
    }

    fn arguments(&self) -> Option<(usize, &'static str)> {
        Some((2, "the sliding displacement and its velocity"))
    }

    /// `F`; at a fixed `z` it does not depend on the displacement.
    fn value(&self, port: Port, args: &[f64]) -> Result<f64, OutOfRange> {
        Ok(match port {
            Port::Value => self.force(args[1]),
            Port::Stiffness => 0.0,
            Port::Damping => self.damping(args[1]),
        })
    }

    capabilities!(events: no, states: yes, energy: yes);

    fn columns(&self) -> &'static [Column] {
        COLUMNS
    }

    fn column_values(&self, args: &[f64], out: &mut [f64]) -> Result<(), OutOfRange> {
        out[0] = self.force(args[1]);
        out[1] = args[1];
        Ok(())
    }
}

impl States for LuGre {
    one_state!(z: "z" ["m"], from z0);

    fn state_rates(&self, args: &[f64], rates: &mut [f64]) -> Result<(), OutOfRange> {
        rates[0] = self.z_rate(args[1]);
        Ok(())
    }
}

impl Dissipation for LuGre {
    fn dissipated_power(&self, args: &[f64]) -> f64 {
        let v = args.get(1).copied().unwrap_or(0.0);
        self.force(v) * v - self.sigma0 * self.z * self.z_rate(v)
    }
}

/// `[components.NAME]` with `type = "lugre"`.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct LuGreSection {
    inputs: Ports,
    fc: f64,
    fs: f64,
    vs: f64,
    sigma0: f64,
    #[serde(default)]
    sigma1: f64,
    #[serde(default)]
    sigma2: f64,
    #[serde(default)]
    z0: f64,
}

impl super::SectionUnits for LuGreSection {
    const UNITS: &'static [(&'static str, super::Measure)] = {
        use super::Measure::One;
        &[
            ("fc", One("N")),
            ("fs", One("N")),
            ("vs", One("m/s")),
            ("sigma0", One("N/m")),
            ("sigma1", One("N*s/m")),
            ("sigma2", One("N*s/m")),
            ("z0", One("m")),
        ]
    };
}

impl LuGreSection {
    /// The friction law, its entries checked.
    fn law(&self, name: &str) -> Result<LuGre, EntryError> {
        let key = |entry: &str| format!("components.{name}.{entry}");
        let fc = positive(key("fc"), self.fc)?;
        let fs = positive(key("fs"), self.fs)?;
        if fs < fc {
            return Err(EntryError::value(
                key("fs").into(),
                format!("{fs}"),
                format!("must be at least fc = {fc} (the break-away force is the largest)"),
            ));
        }
        let z0 = finite(key("z0"), self.z0)?;
        Ok(LuGre {
            fc,
            fs,
            vs: positive(key("vs"), self.vs)?,
            sigma0: positive(key("sigma0"), self.sigma0)?,
            sigma1: non_negative(key("sigma1"), self.sigma1)?,
            sigma2: non_negative(key("sigma2"), self.sigma2)?,
            z0,
            z: z0,
        })
    }
}

impl Section for LuGreSection {
    fn build(&self, name: &str, binder: &mut Binder) -> Result<(), EntryError> {
        let law = self.law(name)?;
        let c = binder.add(name.to_string(), Box::new(law));
        binder.bind_ports(&self.inputs, "force", c, name)
    }
}
