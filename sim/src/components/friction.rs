//! Friction without internal state: Coulomb's law, smoothed, with a
//! Stribeck effect and viscous friction as options.
//!
//! The friction force against a sliding velocity `v` under a normal force
//! `N ≥ 0` is
//!
//! `F = μ(v)·N·tanh(v/v_ε) + σ·v`, `μ(v) = μ_c + (μ_s − μ_c)·exp(−(|v|/v_s)^δ)`
//!
//! in the sign of `v` (the model subtracts it): Coulomb's kinetic
//! coefficient `μ_c`, falling from the static coefficient `μ_s` at rest
//! over the Stribeck velocity `v_s` (Stribeck, R., 1902; the exponential
//! form of Armstrong-Hélouvry, B., Dupont, P. and Canudas de Wit, C., 1994,
//! "A survey of models, analysis tools and compensation methods for the
//! control of machines with friction", Automatica 30: 1083–1138; `δ = 2`
//! by default, Tustin's 1947 law is `δ = 1`), and the viscous coefficient
//! `σ`. The sign of `v` is smoothed by `tanh(v/v_ε)`: below the smoothing
//! velocity `v_ε` the friction acts as a steep damper `μ_s·N/v_ε`, so a
//! body held by it creeps at a speed of order `v_ε·(applied / μ_s·N)`
//! instead of sticking — choose `v_ε` well below the speeds of interest.
//! Its force and the power it dissipates, `F·v`, are trajectory columns
//! (`NAME.force \[N\]`, `NAME.power \[W\]`).
//!
//! Its scenario section is `type = "friction"` (`FrictionSection`): the
//! normal force is either the entry `normal_force` \[N\], the input then
//! taking the sliding velocity alone, or the input's second argument.

use super::{Binder, Column, Component, Port, Section};
use crate::components::Dissipation;
use crate::components::section::Ports;
use crate::curve::OutOfRange;
use crate::entry::EntryError;
use crate::entry::{non_negative, positive};
use serde::Deserialize;

/// The friction law's coefficients.
#[derive(Clone, Debug, PartialEq)]
pub struct Friction {
    /// `μ_c`, the kinetic (Coulomb) coefficient.
    pub coulomb: f64,
    /// `μ_s ≥ μ_c`, the static coefficient.
    pub stiction: f64,
    /// `v_s` [m/s] (any positive number when `μ_s = μ_c`).
    pub stribeck_velocity: f64,
    /// `δ > 0`.
    pub stribeck_exponent: f64,
    /// `σ` [N·s/m].
    pub viscous: f64,
    /// `v_ε` [m/s].
    pub smoothing_velocity: f64,
    /// `N` \[N\] if fixed; `None`: the input's second argument.
    pub normal_force: Option<f64>,
}

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

impl Friction {
    /// `(μ(v), dμ/dv)`: the Stribeck curve.
    pub fn coefficient(&self, v: f64) -> (f64, f64) {
        let x = v.abs() / self.stribeck_velocity;
        let fall = (self.stiction - self.coulomb) * (-x.powf(self.stribeck_exponent)).exp();
        let slope = match v == 0.0 {
            true => 0.0,
            false => {
                let d = self.stribeck_exponent;
                -fall * d * x.powf(d - 1.0) / self.stribeck_velocity * v.signum()
            }
        };
        (self.coulomb + fall, slope)
    }

    /// `(v, N)` from the input's arguments.
    fn sliding(&self, args: &[f64]) -> (f64, f64) {
        (args[0], self.normal_force.unwrap_or_else(|| args[1]))
    }

    /// `(F, ∂F/∂v, ∂F/∂N)` at the input's arguments.
    pub fn force(&self, args: &[f64]) -> (f64, f64, f64) {
        let (v, normal) = self.sliding(args);
        let (mu, dmu) = self.coefficient(v);
        let sign = (v / self.smoothing_velocity).tanh();
        let dsign = (1.0 - sign * sign) / self.smoothing_velocity;
        let f = mu * normal * sign + self.viscous * v;
        let dv = (dmu * sign + mu * dsign) * normal + self.viscous;
        (f, dv, mu * sign)
    }

    /// `F·v` \[W\].
    pub fn power(&self, args: &[f64]) -> f64 {
        self.force(args).0 * args[0]
    }
}

impl Component for Friction {
    fn kind(&self) -> &'static str {
        "friction"
    }

    fn arguments(&self) -> Option<(usize, &'static str)> {
        Some(match self.normal_force {
            Some(_) => (1, "the sliding velocity"),
            None => (2, "the sliding velocity and the normal force"),
        })
    }

    /// `F`; `Stiffness` is `∂F/∂v`, `Damping` is `∂F/∂N` (the derivatives
    /// by the first and second argument).
    fn value(&self, port: Port, args: &[f64]) -> Result<f64, OutOfRange> {
        let (f, dv, dn) = self.force(args);
        Ok(match port {
            Port::Value => f,
            Port::Stiffness => dv,
            Port::Damping => dn,
        })
    }

    capabilities!(events: no, states: no, energy: yes);

    fn columns(&self) -> &'static [Column] {
        COLUMNS
    }

    fn column_values(&self, args: &[f64], out: &mut [f64]) -> Result<(), OutOfRange> {
        out[0] = self.force(args).0;
        out[1] = self.power(args);
        Ok(())
    }
}

impl Dissipation for Friction {
    fn dissipated_power(&self, args: &[f64]) -> f64 {
        self.power(args)
    }
}

/// `[components.NAME]` with `type = "friction"`: `coefficient` (`μ_c`),
/// `static_coefficient` (`μ_s`, default `μ_c`), `stribeck_velocity`
/// (needed when `μ_s > μ_c`), `stribeck_exponent` (default 2), `viscous`
/// (default 0), `smoothing_velocity`, `normal_force` (optional) and the
/// inputs it supplies.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct FrictionSection {
    inputs: Ports,
    coefficient: f64,
    static_coefficient: Option<f64>,
    stribeck_velocity: Option<f64>,
    #[serde(default = "two")]
    stribeck_exponent: f64,
    #[serde(default)]
    viscous: f64,
    smoothing_velocity: f64,
    normal_force: Option<f64>,
}

impl super::SectionUnits for FrictionSection {
    const UNITS: &'static [(&'static str, super::Measure)] = {
        use super::Measure::One;
        &[
            ("stribeck_velocity", One("m/s")),
            ("viscous", One("N*s/m")),
            ("smoothing_velocity", One("m/s")),
            ("normal_force", One("N")),
        ]
    };
}

fn two() -> f64 {
    2.0
}

impl Section for FrictionSection {
    fn build(&self, name: &str, binder: &mut Binder) -> Result<(), EntryError> {
        let friction = self.friction(name)?;
        let c = binder.add(name.to_string(), Box::new(friction));
        binder.bind_ports(&self.inputs, "force", c, name)
    }
}

impl FrictionSection {
    /// The friction `[components.{name}]` describes.
    fn friction(&self, name: &str) -> Result<Friction, EntryError> {
        let key = |entry: &str| format!("components.{name}.{entry}");
        let coulomb = non_negative(key("coefficient"), self.coefficient)?;
        let stiction = self.static_coefficient.unwrap_or(coulomb);
        let stiction = non_negative(key("static_coefficient"), stiction)?;
        if stiction < coulomb {
            return Err(EntryError::value(
                key("static_coefficient").into(),
                format!("{stiction}"),
                format!(
                    "the static coefficient μ_s must be at least the kinetic one (coefficient = {coulomb})"
                ),
            ));
        }
        let stribeck_velocity = match (self.stribeck_velocity, stiction > coulomb) {
            (Some(v), _) => positive(key("stribeck_velocity"), v)?,
            (None, false) => 1.0,
            (None, true) => {
                return Err(EntryError::sentence(
                    key("stribeck_velocity").into(),
                    format!(
                        "is missing: the friction falls from the static coefficient {stiction} to {coulomb} over it [m/s]"
                    ),
                ));
            }
        };
        Ok(Friction {
            coulomb,
            stiction,
            stribeck_velocity,
            stribeck_exponent: positive(key("stribeck_exponent"), self.stribeck_exponent)?,
            viscous: non_negative(key("viscous"), self.viscous)?,
            smoothing_velocity: positive(key("smoothing_velocity"), self.smoothing_velocity)?,
            normal_force: self
                .normal_force
                .map(|n| non_negative(key("normal_force"), n))
                .transpose()?,
        })
    }
}
