//! A Bouc–Wen hysteretic spring: a smooth elastic–plastic force with one
//! internal state, the hysteretic variable `z` (Bouc 1967, Wen 1976; in the
//! normalized form of Ikhouane & Rodellar, *Systems with Hysteresis*, 2007,
//! with the yield force `Fy` and yield deflection `uy` of the peer
//! railway-impact-simulator).
//!
//! With `k = Fy/uy` the initial stiffness and `a` the ratio of the
//! post-yield to the initial stiffness,
//!
//! ```text
//! F  = a·k·u + (1 − a)·Fy·z
//! ż  = (A·u̇ − β·|u̇|·|z|ⁿ⁻¹·z − γ·u̇·|z|ⁿ) / uy
//! ```
//!
//! `u` and `u̇` are the arguments of its input (a deflection and its rate;
//! `F` has the sign of `u`). For `A = 1`, `β + γ = 1`, `|z|` stays below 1 and
//! the hysteretic part of the force saturates at `(1 − a)·Fy`; a larger `n`
//! makes the yield sharper. The energy stored in the hysteretic part is
//! `(1 − a)·Fy·uy·z²/(2A)`, so the power it dissipates is
//!
//! ```text
//! P = (1 − a)·Fy/A · (β·|u̇|·|z|ⁿ⁺¹ + γ·u̇·z·|z|ⁿ)
//! ```
//!
//! (non-negative for `β ≥ |γ|`), whose integral over a closed loop is the
//! loop's area `∮ F du`. Its columns are `NAME.force [N]` and
//! `NAME.deflection [m]`, its state `NAME.z [1]`.
//!
//! Its scenario section is `type = "bouc_wen"` (`BoucWenSection`):
//! `inputs = { force = "F1" }`, `fy`, `uy`, and optionally `a` (0), `A` (1),
//! `beta` (0.5), `gamma` (0.5), `n` (1) and the initial `z0` (0).

use super::{Binder, Column, Component, Port, Section};
use crate::components::section::Ports;
use crate::components::{Dissipation, States};
use crate::curve::OutOfRange;
use crate::entry::EntryError;
use crate::entry::{finite, finite_combination, non_negative, positive};
use serde::Deserialize;

/// The spring's parameters and its hysteretic variable.
#[derive(Clone, Debug, PartialEq)]
pub struct BoucWen {
    /// Yield force `Fy` \[N\].
    pub fy: f64,
    /// Yield deflection `uy` \[m\].
    pub uy: f64,
    /// Post-yield stiffness ratio `a`, in `[0, 1)`.
    pub a: f64,
    /// `A`, the hysteretic variable's elastic rate.
    pub big_a: f64,
    /// `β`.
    pub beta: f64,
    /// `γ`.
    pub gamma: f64,
    /// The exponent `n`.
    pub n: f64,
    /// The initial `z`.
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
        quantity: "deflection",
        unit: "m",
    },
];

impl BoucWen {
    /// A spring at its initial state `z0`.
    #[allow(clippy::too_many_arguments)]
    pub fn new(
        fy: f64,
        uy: f64,
        a: f64,
        big_a: f64,
        beta: f64,
        gamma: f64,
        n: f64,
        z0: f64,
    ) -> Self {
        BoucWen {
            fy,
            uy,
            a,
            big_a,
            beta,
            gamma,
            n,
            z0,
            z: z0,
        }
    }

    /// `F` at deflection `u` and the current `z`.
    pub fn force(&self, u: f64) -> f64 {
        self.a * self.fy / self.uy * u + (1.0 - self.a) * self.fy * self.z
    }

    /// `ż` at rate `du` and the current `z`.
    pub fn z_rate(&self, du: f64) -> f64 {
        let z = self.z;
        let zn = z.abs().powf(self.n);
        (self.big_a * du - self.beta * du.abs() * z.signum() * zn - self.gamma * du * zn) / self.uy
    }
}

impl Component for BoucWen {
    fn kind(&self) -> &'static str {
        "bouc_wen"
    }

    fn arguments(&self) -> Option<(usize, &'static str)> {
        Some((2, "the deflection and its rate"))
    }

    /// `F`; its derivative with respect to `u` at a fixed `z` is `a·k`.
    fn value(&self, port: Port, args: &[f64]) -> Result<f64, OutOfRange> {
        Ok(match port {
            Port::Value => self.force(args[0]),
            Port::Stiffness => self.a * self.fy / self.uy,
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
}

impl States for BoucWen {
    one_state!(z: "z" ["1"], from z0);

    fn state_rates(&self, args: &[f64], rates: &mut [f64]) -> Result<(), OutOfRange> {
        rates[0] = self.z_rate(args[1]);
        Ok(())
    }
}

impl Dissipation for BoucWen {
    fn dissipated_power(&self, args: &[f64]) -> f64 {
        let (du, z) = (args[1], self.z);
        let zn = z.abs().powf(self.n);
        let hysteretic = self.beta * du.abs() * z.abs() * zn + self.gamma * du * z * zn;
        (1.0 - self.a) * self.fy / self.big_a * hysteretic
    }
}

fn one() -> f64 {
    1.0
}

fn half() -> f64 {
    0.5
}

/// `[components.NAME]` with `type = "bouc_wen"`.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct BoucWenSection {
    inputs: Ports,
    fy: f64,
    uy: f64,
    #[serde(default)]
    a: f64,
    #[serde(default = "one", rename = "A")]
    big_a: f64,
    #[serde(default = "half")]
    beta: f64,
    #[serde(default = "half")]
    gamma: f64,
    #[serde(default = "one")]
    n: f64,
    #[serde(default)]
    z0: f64,
}

impl super::SectionUnits for BoucWenSection {
    const UNITS: &'static [(&'static str, super::Measure)] = {
        use super::Measure::One;
        &[("fy", One("N")), ("uy", One("m"))]
    };
}

impl BoucWenSection {
    /// The spring, its entries checked.
    fn spring(&self, name: &str) -> Result<BoucWen, EntryError> {
        let key = |entry: &str| format!("components.{name}.{entry}");
        let a = non_negative(key("a"), self.a)?;
        if a >= 1.0 {
            return Err(EntryError::value(
                key("a").into(),
                format!("{a}"),
                "must be below 1 (the post-yield stiffness ratio)",
            ));
        }
        let (beta, gamma) = (
            finite(key("beta"), self.beta)?,
            finite(key("gamma"), self.gamma)?,
        );
        if beta + gamma <= 0.0 {
            return Err(EntryError::at(
                format!("components.{name}").into(),
                format!(
                    "beta + gamma = {}: must be positive, or the hysteresis loop is unbounded",
                    beta + gamma
                ),
            ));
        }
        let spring = BoucWen::new(
            positive(key("fy"), self.fy)?,
            positive(key("uy"), self.uy)?,
            a,
            positive(key("A"), self.big_a)?,
            beta,
            gamma,
            positive(key("n"), self.n)?,
            finite(key("z0"), self.z0)?,
        );
        spring.check_coefficients(&format!("components.{name}"))?;
        Ok(spring)
    }
}

impl BoucWen {
    /// `Err` naming the entries when a coefficient of `F`, `ż` or `P`
    /// overflows although each entry is finite (a `uy` of 1e-320): the run
    /// would meet it as a force or rate that is not finite at once.
    fn check_coefficients(&self, section: &str) -> Result<(), EntryError> {
        let (fy, uy, big_a) = (self.fy, self.uy, self.big_a);
        let (beta, gamma) = (self.beta, self.gamma);
        let checks = [
            (
                ("fy/uy", "the initial stiffness"),
                vec![("fy", fy), ("uy", uy)],
                fy / uy,
            ),
            (
                ("A/uy", "the rate of z"),
                vec![("A", big_a), ("uy", uy)],
                big_a / uy,
            ),
            (
                ("beta/uy", "the rate of z"),
                vec![("beta", beta), ("uy", uy)],
                beta / uy,
            ),
            (
                ("gamma/uy", "the rate of z"),
                vec![("gamma", gamma), ("uy", uy)],
                gamma / uy,
            ),
            (
                ("fy/A", "the dissipated power"),
                vec![("fy", fy), ("A", big_a)],
                fy / big_a * beta.abs().max(gamma.abs()).max(1.0),
            ),
        ];
        for (formula, entries, value) in checks {
            finite_combination(section, formula, &entries, value)?;
        }
        Ok(())
    }
}

impl Section for BoucWenSection {
    fn build(&self, name: &str, binder: &mut Binder) -> Result<(), EntryError> {
        let spring = self.spring(name)?;
        let c = binder.add(name.to_string(), Box::new(spring));
        binder.bind_ports(&self.inputs, "force", c, name)
    }
}
