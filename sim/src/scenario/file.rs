//! The scenario file as written: the TOML sections and their defaults.

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
        }
    }
}

#[derive(Deserialize, Default)]
#[serde(deny_unknown_fields, default)]
pub(super) struct InitialSection {
    pub(super) coordinates: BTreeMap<String, f64>,
    pub(super) velocities: BTreeMap<String, f64>,
    pub(super) equilibrium: Vec<String>,
}

#[derive(Deserialize, Default)]
#[serde(deny_unknown_fields, default)]
pub(super) struct MetricsSection {
    pub(super) crush: Option<String>,
    pub(super) pitch: Vec<String>,
    pub(super) weld: Option<String>,
}

#[derive(Deserialize)]
#[serde(tag = "type", rename_all = "snake_case", deny_unknown_fields)]
pub(super) enum ComponentSection {
    Crush {
        inputs: Ports,
        compression: String,
        stiffness_breakpoints: Vec<f64>,
        stiffness_values: Vec<f64>,
        damping_breakpoints: Vec<f64>,
        damping_values: Vec<f64>,
        #[serde(default = "elastic")]
        unloading: String,
        unloading_stiffness: Option<f64>,
        #[serde(default = "yes")]
        contact_only: bool,
        #[serde(default = "hold")]
        outside: String,
    },
    Weld {
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
    },
    Table {
        file: String,
        #[serde(default = "time")]
        time_column: String,
        columns: BTreeMap<String, String>,
        #[serde(default = "zero")]
        outside: String,
    },
    Constant {
        values: BTreeMap<String, f64>,
    },
}

impl ComponentSection {
    /// The `type` of the component as written.
    pub(super) fn kind(&self) -> &'static str {
        match self {
            ComponentSection::Crush { .. } => "crush",
            ComponentSection::Weld { .. } => "weld",
            ComponentSection::Table { .. } => "table",
            ComponentSection::Constant { .. } => "constant",
        }
    }
}

/// The inputs a component supplies: its value and, optionally, derivatives.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct Ports {
    #[serde(alias = "moment")]
    pub(super) force: String,
    pub(super) stiffness: Option<String>,
    pub(super) damping: Option<String>,
}

fn elastic() -> String {
    "elastic".into()
}
fn yes() -> bool {
    true
}
fn hold() -> String {
    "hold".into()
}
fn extrapolate() -> String {
    "extrapolate".into()
}
fn zero() -> String {
    "zero".into()
}
fn time() -> String {
    "t".into()
}
