//! The scenario file as written: the TOML sections and their defaults.
//! Each kind of component has its own section, in its file of
//! [`crate::components`].

use super::Choice;
use crate::components::ComponentSection;
use serde::Deserialize;
use std::collections::BTreeMap;

#[derive(Deserialize, Default)]
#[serde(deny_unknown_fields)]
pub(super) struct File {
    pub(super) spec: Option<String>,
    #[serde(default)]
    pub(super) description: String,
    #[serde(default)]
    pub(super) simulation: SimulationSection,
    #[serde(default)]
    pub(super) initial: InitialSection,
    #[serde(default)]
    pub(super) parameters: BTreeMap<String, f64>,
    #[serde(default)]
    pub(super) metrics: MetricsSection,
    #[serde(default)]
    pub(super) components: BTreeMap<String, ComponentSection>,
    #[serde(default)]
    pub(super) constraints: ConstraintsSection,
    #[serde(default)]
    pub(super) iso_mme: IsoMmeSection,
}

/// `[iso_mme]`: what `lpm simulate --iso-mme DIR` writes besides the
/// vehicle's standard channels (see [`super::iso_mme`]).
#[derive(Deserialize, Default)]
#[serde(deny_unknown_fields, default)]
pub(super) struct IsoMmeSection {
    /// The test's name (its files' stem); by default the spec's stem.
    pub(super) name: Option<String>,
    /// The `.mme`'s `Title`; by default the scenario's description.
    pub(super) title: Option<String>,
    /// The `.mme`'s `Laboratory name`.
    pub(super) laboratory: Option<String>,
    /// The barrier force channel: a trajectory column or combination, or
    /// `""` for none; by default the force of the contact elements.
    pub(super) barrier_force: Option<String>,
    /// Further channels: a trajectory column (or combination) → its code.
    pub(super) channels: BTreeMap<String, String>,
}

/// `[constraints]`: Baumgarte's stabilization of a model's constraints
/// (the run engine's constrained solve), `α` and `β` [1/s].
#[derive(Deserialize)]
#[serde(deny_unknown_fields, default)]
pub(super) struct ConstraintsSection {
    pub(super) alpha: f64,
    pub(super) beta: f64,
}

impl Default for ConstraintsSection {
    fn default() -> Self {
        let d = super::options::DEFAULT_STABILIZATION;
        ConstraintsSection {
            alpha: d.alpha,
            beta: d.beta,
        }
    }
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields, default)]
pub(super) struct SimulationSection {
    pub(super) t_end: f64,
    pub(super) method: String,
    pub(super) rtol: f64,
    pub(super) atol: f64,
    pub(super) max_step: Option<f64>,
    /// Step of the fixed-step RK4 method; first step of the adaptive ones.
    pub(super) step: Option<f64>,
    pub(super) output_interval: f64,
    pub(super) max_steps: usize,
    /// How the output samples get `q̈` (a `SampleAccelerations`).
    pub(super) accelerations: String,
    /// What a step's stages see of a kink of a time table inside it
    /// (a `TimeKinks`).
    pub(super) time_kinks: String,
}

impl Default for SimulationSection {
    fn default() -> Self {
        SimulationSection {
            t_end: 0.15,
            method: "dopri5".into(),
            rtol: 1e-8,
            atol: 1e-10,
            max_step: None,
            step: None,
            output_interval: 1e-4,
            max_steps: 1_000_000,
            accelerations: super::options::SampleAccelerations::default().name().into(),
            time_kinks: super::options::TimeKinks::default().name().into(),
        }
    }
}

#[derive(Deserialize, Default)]
#[serde(deny_unknown_fields, default)]
pub(super) struct InitialSection {
    pub(super) coordinates: BTreeMap<String, f64>,
    pub(super) velocities: BTreeMap<String, f64>,
    pub(super) equilibrium: Vec<String>,
    /// The impact speed \[m/s\], given to every coordinate of `moving`.
    pub(super) speed: Option<f64>,
    /// The coordinates that move with the vehicle at `speed`, each with a
    /// sign: `"-r"` starts with `ṙ = −speed`.
    pub(super) moving: Vec<String>,
}

#[derive(Deserialize, Default)]
#[serde(deny_unknown_fields, default)]
pub(super) struct MetricsSection {
    pub(super) crush: Option<String>,
    pub(super) pitch: Vec<String>,
    pub(super) weld: Option<String>,
    pub(super) contact: Vec<String>,
    pub(super) displacement: Vec<String>,
    pub(super) velocity: Vec<String>,
    pub(super) acceleration: Vec<String>,
    pub(super) force: Vec<String>,
    /// The filter class of acceleration channels, by channel: a class
    /// (60, 180, 600, 1000) or what the channel measures (`"head"`).
    pub(super) classes: BTreeMap<String, ClassChoice>,
}

/// A channel's filter class as `metrics.classes` gives it.
#[derive(Clone, Debug, PartialEq)]
pub(super) enum ClassChoice {
    /// A class number.
    Class(f64),
    /// What the channel measures, a key of
    /// [`CLASS_BY_MEASUREMENT`](crate::pulse::cfc::CLASS_BY_MEASUREMENT).
    Measurement(String),
}

impl<'de> Deserialize<'de> for ClassChoice {
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        struct Visitor;
        impl serde::de::Visitor<'_> for Visitor {
            type Value = ClassChoice;
            fn expecting(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
                f.write_str("a filter class (60, 180, 600, 1000) or what the channel measures (e.g. \"head\")")
            }
            fn visit_i64<E>(self, v: i64) -> Result<ClassChoice, E> {
                Ok(ClassChoice::Class(v as f64))
            }
            fn visit_u64<E>(self, v: u64) -> Result<ClassChoice, E> {
                Ok(ClassChoice::Class(v as f64))
            }
            fn visit_f64<E>(self, v: f64) -> Result<ClassChoice, E> {
                Ok(ClassChoice::Class(v))
            }
            fn visit_str<E>(self, v: &str) -> Result<ClassChoice, E> {
                Ok(ClassChoice::Measurement(v.to_string()))
            }
        }
        d.deserialize_any(Visitor)
    }
}

impl MetricsSection {
    /// The channels listed under `role`'s key.
    pub(super) fn channels(&self, role: super::Role) -> &[String] {
        match role {
            super::Role::Displacement => &self.displacement,
            super::Role::Velocity => &self.velocity,
            super::Role::Acceleration => &self.acceleration,
            super::Role::Force => &self.force,
        }
    }
}
