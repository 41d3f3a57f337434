//! Scenario files: what to simulate with a model — parameters, initial
//! state, crash components for its input functions, solver settings.
//!
//! ```toml
//! spec = "../yaris_double_pendulum.lpm"   # the spec this scenario is for
//! [simulation]   t_end = 0.15, method = "dopri5", rtol = 1e-8, atol = 1e-10
//! [initial]      coordinates = { r = 0.0 }, velocities = { r = -15.56 }, equilibrium = ["theta1"]
//! [parameters]   k_tor = 0.0
//! [metrics]      crush = "-r", pitch = ["theta1", "theta2"], weld = "weld"
//! [components.front_end]  type = "crush", inputs = { force = "crush", … }, …
//! [components.barrier]    type = "table", file = "../data/forces.csv", columns = { barrier_x1 = "Fx1" }
//! ```
//!
//! Every name is checked against the spec, with a suggestion for typos.

use crate::crash::crush::{CrushElement, Unloading};
use crate::crash::curve::{Characteristic, Curve, Outside};
use crate::crash::table::Table;
use crate::crash::weld::Weld;
use crate::crash::{Binding, BoundInputs, Component, Element, Port};
use crate::ode::Options;
use lagrangian_core::diagnostic::closest;
use serde::Deserialize;
use std::collections::BTreeMap;
use std::fmt;
use std::path::{Path, PathBuf};

/// The names a scenario is resolved against.
#[derive(Clone, Debug)]
pub struct ModelNames {
    pub coordinates: Vec<String>,
    pub parameters: Vec<String>,
    pub inputs: Vec<String>,
    /// `(input, number of arguments)` per input call of the dynamics.
    pub input_sites: Vec<(usize, usize)>,
}

/// Integration method.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Method {
    Dopri5,
    Rk4,
    Implicit,
}

impl Method {
    pub fn parse(text: &str) -> Option<Method> {
        match text {
            "dopri5" => Some(Method::Dopri5),
            "rk4" => Some(Method::Rk4),
            "implicit" | "tr-bdf2" => Some(Method::Implicit),
            _ => None,
        }
    }
}

/// A scenario that does not fit its spec, or a file that cannot be read.
#[derive(Clone, Debug, PartialEq)]
pub struct ScenarioError {
    pub file: Option<PathBuf>,
    pub message: String,
}

impl fmt::Display for ScenarioError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match &self.file {
            Some(file) => write!(f, "{}: {}", file.display(), self.message),
            None => write!(f, "{}", self.message),
        }
    }
}

impl std::error::Error for ScenarioError {}

#[derive(Deserialize, Default)]
#[serde(deny_unknown_fields)]
struct File {
    spec: Option<String>,
    #[serde(default)]
    description: String,
    #[serde(default)]
    simulation: SimulationSection,
    #[serde(default)]
    initial: InitialSection,
    #[serde(default)]
    parameters: BTreeMap<String, f64>,
    #[serde(default)]
    metrics: MetricsSection,
    #[serde(default)]
    components: BTreeMap<String, ComponentSection>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields, default)]
struct SimulationSection {
    t_end: f64,
    method: String,
    rtol: f64,
    atol: f64,
    max_step: Option<f64>,
    /// Step of the fixed-step RK4 method.
    step: Option<f64>,
    output_interval: f64,
    max_steps: usize,
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
struct InitialSection {
    coordinates: BTreeMap<String, f64>,
    velocities: BTreeMap<String, f64>,
    equilibrium: Vec<String>,
}

#[derive(Deserialize, Default)]
#[serde(deny_unknown_fields, default)]
struct MetricsSection {
    crush: Option<String>,
    pitch: Vec<String>,
    weld: Option<String>,
}

#[derive(Deserialize)]
#[serde(tag = "type", rename_all = "snake_case", deny_unknown_fields)]
enum ComponentSection {
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

/// The inputs a component supplies: its value and, optionally, derivatives.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct Ports {
    #[serde(alias = "moment")]
    force: String,
    stiffness: Option<String>,
    damping: Option<String>,
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

/// A scenario resolved against a model.
#[derive(Clone, Debug)]
pub struct Scenario {
    pub file: Option<PathBuf>,
    /// The spec the file names, resolved relative to the file.
    pub spec: Option<PathBuf>,
    pub description: String,
    pub t_end: f64,
    pub method: Method,
    pub options: Options,
    pub output_interval: f64,
    /// Parameter overrides by index.
    pub parameters: Vec<(usize, f64)>,
    pub initial_coordinates: Vec<(usize, f64)>,
    pub initial_velocities: Vec<(usize, f64)>,
    /// Coordinates solved for static equilibrium before the run.
    pub equilibrium: Vec<usize>,
    /// The crush coordinate and the sign that makes compression positive.
    pub crush: Option<(usize, f64)>,
    pub pitch: Vec<usize>,
    pub weld: Option<String>,
    pub inputs: BoundInputs,
}

impl Scenario {
    /// Reads and resolves a scenario file, applying `settings` (`key=value`,
    /// see [`Scenario::parse`]) first.
    pub fn load(
        path: &Path,
        names: &ModelNames,
        settings: &[String],
    ) -> Result<Scenario, ScenarioError> {
        let text = std::fs::read_to_string(path).map_err(|e| ScenarioError {
            file: Some(path.to_path_buf()),
            message: format!("cannot read: {e}"),
        })?;
        Scenario::parse(&text, Some(path), names, settings)
    }

    /// A scenario with nothing but defaults (no file).
    pub fn defaults(names: &ModelNames, settings: &[String]) -> Result<Scenario, ScenarioError> {
        Scenario::parse("", None, names, settings)
    }

    /// Resolves scenario `text` (from `file`, which relative paths start from).
    ///
    /// `settings` override it: `name=value` sets a spec parameter, or gives
    /// an input function a constant value; a dotted key such as
    /// `simulation.t_end=0.2` or `components.front_end.unloading=elastic`
    /// sets that entry of the file (the value is read as TOML).
    pub fn parse(
        text: &str,
        file: Option<&Path>,
        names: &ModelNames,
        settings: &[String],
    ) -> Result<Scenario, ScenarioError> {
        let error = |message: String| ScenarioError {
            file: file.map(Path::to_path_buf),
            message,
        };
        let mut document: toml::Table = text
            .parse()
            .map_err(|e: toml::de::Error| error(e.to_string()))?;
        let mut constants = BTreeMap::new();
        for setting in settings {
            apply_setting(&mut document, setting, names, &mut constants).map_err(|m| {
                ScenarioError {
                    file: None,
                    message: m,
                }
            })?;
        }
        let parsed: File = document
            .try_into()
            .map_err(|e: toml::de::Error| error(e.to_string()))?;
        let base = file.and_then(Path::parent).unwrap_or(Path::new("."));
        resolve(parsed, base, names, constants)
            .map_err(error)
            .map(|mut s| {
                s.file = file.map(Path::to_path_buf);
                s
            })
    }
}

/// Applies one `--set key=value` to the document.
fn apply_setting(
    document: &mut toml::Table,
    setting: &str,
    names: &ModelNames,
    constants: &mut BTreeMap<String, f64>,
) -> Result<(), String> {
    let (key, value) = setting
        .split_once('=')
        .ok_or_else(|| format!("--set `{setting}` is not of the form key=value"))?;
    let (key, value) = (key.trim(), value.trim());
    if !key.contains('.') {
        let number: f64 = value
            .parse()
            .map_err(|_| format!("--set {key}: `{value}` is not a number"))?;
        if names.parameters.iter().any(|p| p == key) {
            let parameters = document
                .entry("parameters")
                .or_insert_with(|| toml::Value::Table(toml::Table::new()));
            if let toml::Value::Table(t) = parameters {
                t.insert(key.to_string(), toml::Value::Float(number));
            }
            return Ok(());
        }
        if names.inputs.iter().any(|i| i == key) {
            constants.insert(key.to_string(), number);
            return Ok(());
        }
        let known = names
            .parameters
            .iter()
            .chain(&names.inputs)
            .map(String::as_str);
        return Err(unknown("--set: parameter or input", key, known));
    }
    let parsed: toml::Value = format!("v = {value}")
        .parse::<toml::Table>()
        .ok()
        .and_then(|mut t| t.remove("v"))
        .unwrap_or_else(|| toml::Value::String(value.to_string()));
    let mut table = document;
    let parts: Vec<&str> = key.split('.').collect();
    for part in &parts[..parts.len() - 1] {
        let entry = table
            .entry(part.to_string())
            .or_insert_with(|| toml::Value::Table(toml::Table::new()));
        table = match entry {
            toml::Value::Table(t) => t,
            _ => return Err(format!("--set {key}: `{part}` is not a table")),
        };
    }
    table.insert(parts[parts.len() - 1].to_string(), parsed);
    Ok(())
}

fn unknown<'a>(what: &str, name: &str, known: impl Iterator<Item = &'a str> + Clone) -> String {
    let mut message = format!("{what} `{name}` does not exist in the spec");
    if let Some(best) = closest(name, known.clone()) {
        message.push_str(&format!("; did you mean `{best}`?"));
    } else {
        let list: Vec<&str> = known.collect();
        message.push_str(&format!(" (known: {})", list.join(", ")));
    }
    message
}

fn index_of(what: &str, name: &str, list: &[String]) -> Result<usize, String> {
    list.iter()
        .position(|n| n == name)
        .ok_or_else(|| unknown(what, name, list.iter().map(String::as_str)))
}

fn outside(what: &str, text: &str) -> Result<Outside, String> {
    Outside::parse(text)
        .ok_or_else(|| format!("{what}: outside = `{text}`; use one of {}", Outside::NAMES))
}

fn resolve(
    file: File,
    base: &Path,
    names: &ModelNames,
    constants: BTreeMap<String, f64>,
) -> Result<Scenario, String> {
    let s = &file.simulation;
    let method = Method::parse(&s.method).ok_or_else(|| {
        format!(
            "simulation.method = `{}`; use dopri5, rk4 or implicit",
            s.method
        )
    })?;
    if s.t_end.is_nan() || s.t_end <= 0.0 || s.t_end.is_infinite() {
        return Err(format!("simulation.t_end = {} must be positive", s.t_end));
    }
    if s.output_interval.is_nan() || s.output_interval <= 0.0 {
        return Err(format!(
            "simulation.output_interval = {} must be positive",
            s.output_interval
        ));
    }
    let fixed_step = match (method, s.step) {
        (Method::Rk4, None) => Some(1e-5),
        (Method::Rk4, Some(h)) => Some(h),
        _ => None,
    };
    let options = Options {
        rtol: s.rtol,
        atol: s.atol,
        max_step: s.max_step.unwrap_or(f64::INFINITY),
        max_steps: s.max_steps,
        fixed_step,
        ..Options::default()
    };
    options.validate().map_err(|e| format!("simulation: {e}"))?;

    let parameters = file
        .parameters
        .iter()
        .map(|(name, value)| {
            Ok((
                index_of("parameters: parameter", name, &names.parameters)?,
                *value,
            ))
        })
        .collect::<Result<_, String>>()?;
    let coordinate = |what: &str, name: &str| index_of(what, name, &names.coordinates);
    let initial_coordinates = file
        .initial
        .coordinates
        .iter()
        .map(|(n, v)| Ok((coordinate("initial.coordinates: coordinate", n)?, *v)))
        .collect::<Result<_, String>>()?;
    let initial_velocities = file
        .initial
        .velocities
        .iter()
        .map(|(n, v)| Ok((coordinate("initial.velocities: coordinate", n)?, *v)))
        .collect::<Result<_, String>>()?;
    let equilibrium = file
        .initial
        .equilibrium
        .iter()
        .map(|n| coordinate("initial.equilibrium: coordinate", n))
        .collect::<Result<_, String>>()?;
    let crush = match &file.metrics.crush {
        None => None,
        Some(text) => {
            let (sign, name) = match text.trim().strip_prefix('-') {
                Some(rest) => (-1.0, rest.trim()),
                None => (1.0, text.trim().trim_start_matches('+')),
            };
            Some((coordinate("metrics.crush: coordinate", name)?, sign))
        }
    };
    let pitch = file
        .metrics
        .pitch
        .iter()
        .map(|n| coordinate("metrics.pitch: coordinate", n))
        .collect::<Result<_, String>>()?;
    if let Some(weld) = &file.metrics.weld
        && !file.components.contains_key(weld)
    {
        return Err(unknown(
            "metrics.weld: component",
            weld,
            file.components.keys().map(String::as_str),
        ));
    }
    let inputs = bind_components(&file.components, base, names, constants)?;
    Ok(Scenario {
        file: None,
        spec: file.spec.as_ref().map(|s| base.join(s)),
        description: file.description,
        t_end: s.t_end,
        method,
        options,
        output_interval: s.output_interval,
        parameters,
        initial_coordinates,
        initial_velocities,
        equilibrium,
        crush,
        pitch,
        weld: file.metrics.weld.clone(),
        inputs,
    })
}

fn bind_components(
    sections: &BTreeMap<String, ComponentSection>,
    base: &Path,
    names: &ModelNames,
    constants: BTreeMap<String, f64>,
) -> Result<BoundInputs, String> {
    let mut components = Vec::new();
    let mut bindings: Vec<Option<Binding>> = vec![None; names.inputs.len()];
    let mut bind = |input: &str, component: usize, port: Port, owner: &str| -> Result<(), String> {
        let k = index_of(&format!("components.{owner}: input"), input, &names.inputs)?;
        if bindings[k].is_some() {
            return Err(format!(
                "components.{owner}: input `{input}` is already supplied by another component"
            ));
        }
        bindings[k] = Some(Binding { component, port });
        Ok(())
    };
    let mut value_inputs = Vec::new();
    for (name, section) in sections {
        let c = components.len();
        let at = |what: &str, e: &dyn fmt::Display| format!("components.{name}: {what}: {e}");
        let element = match section {
            ComponentSection::Crush {
                inputs,
                compression,
                stiffness_breakpoints,
                stiffness_values,
                damping_breakpoints,
                damping_values,
                unloading,
                unloading_stiffness,
                contact_only,
                outside: policy,
            } => {
                let policy = outside(&format!("components.{name}"), policy)?;
                let stiffness =
                    Characteristic::new(stiffness_breakpoints, stiffness_values, policy)
                        .map_err(|e| at("stiffness table", &e))?;
                let damping = Characteristic::new(damping_breakpoints, damping_values, policy)
                    .map_err(|e| at("damping table", &e))?;
                let unloading = match (unloading.as_str(), unloading_stiffness) {
                    ("elastic", _) => Unloading::Elastic,
                    ("plastic", Some(k)) if *k > 0.0 && k.is_finite() => {
                        Unloading::Plastic { stiffness: *k }
                    }
                    ("plastic", _) => {
                        return Err(format!(
                            "components.{name}: plastic unloading needs a positive unloading_stiffness [N/m]"
                        ));
                    }
                    (other, _) => {
                        return Err(format!(
                            "components.{name}: unloading = `{other}`; use elastic or plastic"
                        ));
                    }
                };
                let sign = match compression.as_str() {
                    "positive" => 1.0,
                    "negative" => -1.0,
                    other => {
                        return Err(format!(
                            "components.{name}: compression = `{other}`; use positive or negative (the sign of the input's first argument under compression)"
                        ));
                    }
                };
                bind_ports(inputs, c, name, &mut bind)?;
                value_inputs.push((c, inputs.force.clone()));
                Element::Crush(CrushElement::new(
                    stiffness,
                    damping,
                    unloading,
                    sign,
                    *contact_only,
                ))
            }
            ComponentSection::Weld {
                inputs,
                curve,
                damping,
                failure_moment,
                failure_angle,
                post_failure_curve,
                post_failure_damping,
                outside: policy,
            } => {
                let policy = outside(&format!("components.{name}"), policy)?;
                let make = |points: &[[f64; 2]], what: &str| {
                    Curve::new(
                        points.iter().map(|p| p[0]).collect(),
                        points.iter().map(|p| p[1]).collect(),
                        policy,
                    )
                    .map_err(|e| at(what, &e))
                };
                let intact = make(curve, "curve")?;
                let post = post_failure_curve
                    .as_deref()
                    .map(|p| make(p, "post_failure_curve"))
                    .transpose()?;
                bind_ports(inputs, c, name, &mut bind)?;
                value_inputs.push((c, inputs.force.clone()));
                Element::Weld(Weld::new(
                    intact,
                    *damping,
                    *failure_moment,
                    *failure_angle,
                    post,
                    *post_failure_damping,
                ))
            }
            ComponentSection::Table {
                file,
                time_column,
                columns,
                outside: policy,
            } => {
                let policy = outside(&format!("components.{name}"), policy)?;
                let table =
                    Table::load(&base.join(file)).map_err(|e| format!("components.{name}: {e}"))?;
                for (input, column) in columns {
                    let curve = table
                        .curve(time_column, column, policy)
                        .map_err(|e| format!("components.{name}: {e}"))?;
                    let k = components.len();
                    bind(input, k, Port::Value, name)?;
                    components.push(Component {
                        name: format!("{name}.{input}"),
                        element: Element::Curve(curve),
                    });
                }
                continue;
            }
            ComponentSection::Constant { values } => {
                for (input, value) in values {
                    let k = components.len();
                    bind(input, k, Port::Value, name)?;
                    components.push(Component {
                        name: format!("{name}.{input}"),
                        element: Element::Constant(*value),
                    });
                }
                continue;
            }
        };
        components.push(Component {
            name: name.clone(),
            element,
        });
    }
    // --set constants override whatever the file binds.
    for (input, value) in constants {
        let k = index_of("--set: input", &input, &names.inputs)?;
        bindings[k] = Some(Binding {
            component: components.len(),
            port: Port::Value,
        });
        components.push(Component {
            name: format!("--set {input}"),
            element: Element::Constant(value),
        });
    }
    // Components with events need the arguments of their one value input.
    let mut event_arguments = vec![None; components.len()];
    for (c, input) in value_inputs {
        let k = index_of("input", &input, &names.inputs)?;
        if bindings[k].map(|b| b.component) != Some(c) {
            continue; // overridden by --set
        }
        let mut offset = 0;
        let mut found = Vec::new();
        for &(site, arity) in &names.input_sites {
            if site == k {
                found.push((offset, arity));
            }
            offset += arity;
        }
        match found.as_slice() {
            [] => {}
            [one] => event_arguments[c] = Some(*one),
            _ => {
                return Err(format!(
                    "component `{}` keeps state (hysteresis, failure), but its input `{input}` is called at {} places with different arguments; give each call its own input function",
                    components[c].name,
                    found.len()
                ));
            }
        }
    }
    Ok(BoundInputs::new(
        components,
        bindings,
        event_arguments,
        names.inputs.clone(),
    ))
}

/// Records that input `name` reads `port` of component `index` (of `owner`).
type Bind<'a> = dyn FnMut(&str, usize, Port, &str) -> Result<(), String> + 'a;

fn bind_ports(ports: &Ports, component: usize, owner: &str, bind: &mut Bind) -> Result<(), String> {
    bind(&ports.force, component, Port::Value, owner)?;
    if let Some(s) = &ports.stiffness {
        bind(s, component, Port::Stiffness, owner)?;
    }
    if let Some(d) = &ports.damping {
        bind(d, component, Port::Damping, owner)?;
    }
    Ok(())
}
