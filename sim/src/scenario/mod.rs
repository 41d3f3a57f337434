//! Scenario files: what to simulate with a model — parameters, initial
//! state, crash components for its input functions, solver settings.
//!
//! ```toml
//! spec = "../yaris_double_pendulum.lpm"   # the spec this scenario is for
//! [simulation]   t_end = 0.15, method = "dopri5", rtol = 1e-8, atol = 1e-10   # or rk4, tr-bdf2
//! [initial]      coordinates = { r = 0.0 }, velocities = { r = -15.56 }, equilibrium = ["theta1"]
//!                # or: speed = 15.56, moving = ["-r"] (the impact speed, given to every
//!                # coordinate that moves with the vehicle, with its sign)
//! [parameters]   k_tor = 0.0
//! [metrics]      crush = "-r", pitch = ["theta1", "theta2"], weld = "weld"
//!                # channels: any trajectory column or combination ("xa - xb"), by role
//!                acceleration = ["occupant_deceleration"], displacement = ["s"],
//!                velocity = ["r_dot"], force = ["belt_force"]
//! [components.front_end]  type = "crush", inputs = { force = "crush", … }, …
//! [components.barrier]    type = "table", file = "../data/forces.csv", columns = { barrier_x1 = "Fx1" }
//! [iso_mme]      name = "YARIS56", title = "…", laboratory = "…", barrier_force = "front_end.force"
//! [iso_mme.channels]  "theta2" = "10SEAT000000ANYP"   # column = ISO-MME channel code ([`iso_mme`])
//! ```
//!
//! Every name is checked against the spec, with a suggestion for typos.
//!
//! A `crush` component (see [`crate::components::crush`]) gives its spring's
//! loading curve in one of two forms, never both:
//!
//! ```toml
//! # A force–deflection curve, as a test gives it: the force [N] at each
//! # breakpoint [m] (0 at 0), linear between; its tangent stiffness is the
//! # slope of the segment.
//! force_breakpoints = [0.1, 0.5]
//! force_values = [170e3, 180e3]
//! # Or the paper's secant stiffness curve (eq 1): k(δ) [N/m] at 0 and at
//! # each breakpoint, linear between, and the force k(δ)·δ (quadratic
//! # between breakpoints).
//! stiffness_breakpoints = [0.05, 0.10, 0.25, 0.45, 0.60, 0.80]
//! stiffness_values = [2.4e6, 2.4e6, 2.1e6, 0.94e6, 0.567e6, 0.50e6, 0.5625e6]
//! ```
//!
//! with the damper's `damping_breakpoints` \[m/s\] and `damping_values`
//! \[N·s/m\] in the secant form (eq 2), and optionally `gap` \[m\] (the
//! contact opens after that much crush, and the curve starts there; needs
//! `contact_only = true`, the default), `unloading = "plastic"` with
//! `unloading_stiffness` \[N/m\], `outside` (what the curves do beyond
//! their last breakpoint: `hold`, `extrapolate`, `zero`, `error`) and
//! `stop_at_kinks` (default `true`: crossing a breakpoint of either curve
//! is an event, so no step straddles a kink). Its force
//! and deflection (compression positive, the deflection measured from the
//! gap) are trajectory columns `NAME.force [N]`, `NAME.deflection [m]`.
//!
//! By phase (private modules): `file` is the file format, `overrides`
//! applies `--set` settings to the document, `resolve` checks values and
//! names, and `bind` binds the model's inputs to crash components.

mod base;
pub(crate) mod bind;
mod choice;
mod discover;
mod families;
mod file;
pub mod iso_mme;
mod locate;
pub mod options;
mod overrides;
mod quantities;
mod resolve;
mod scale;
mod signal;

use crate::components::BoundInputs;
pub use crate::entry::{EntryError, KeyPath};
use crate::failure::FailureKind;
use crate::files::{Disk, Files};
pub use crate::model_names::ModelNames;
use crate::ode::{Method, Options};
use crate::table::Table;
pub use base::BaseScenario;
pub use choice::Choice;
pub use discover::{scenarios_for, spec_named_by};
use file::File;
use lagrangian_runtime::LagrangianSystem;
use locate::Places;
use options::{SampleAccelerations, TimeKinks};
use overrides::with_settings;
pub use overrides::{Change, Override, OverrideError, Setting};
use resolve::resolve;
pub use resolve::{MAX_INITIAL_MAGNITUDE, MAX_SAMPLES};
pub use scale::{ScaleError, as_number, factor_base, number_value, scaled_value};
use serde::Deserialize;
pub use signal::{Channel, Column, Columns, CoordinateCombination, Role, Signal};
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::sync::Arc;

impl ModelNames {
    /// The names with the columns of the components bound in `inputs`.
    pub fn with_components(&self, inputs: &BoundInputs) -> ModelNames {
        ModelNames {
            component_columns: inputs.columns(),
            ..self.clone()
        }
    }
}

/// What is wrong with a scenario.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ScenarioErrorKind {
    /// The scenario file cannot be read.
    Unreadable,
    /// A key, a value or a setting that does not fit the format or the spec.
    Invalid,
    /// A data file it names (a CSV table) cannot be read or is malformed.
    DataFile,
}

impl ScenarioErrorKind {
    /// The kind of failure; `None` for a scenario file that cannot be read
    /// (an I/O error, not a failure of the scenario).
    pub fn failure(self) -> Option<FailureKind> {
        match self {
            ScenarioErrorKind::Unreadable => None,
            ScenarioErrorKind::Invalid => Some(FailureKind::Scenario),
            ScenarioErrorKind::DataFile => Some(FailureKind::DataFile),
        }
    }
}

/// A scenario that does not fit its spec, or a file that cannot be read:
/// `file:line:column: message`, with as much of the place as is known.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[error("{}{message}", place(.file, .location))]
pub struct ScenarioError {
    /// What kind of problem, which decides `lpm`'s exit status.
    pub kind: ScenarioErrorKind,
    /// The scenario file; `None` for a malformed `--set` setting and for
    /// a scenario with no file.
    pub file: Option<PathBuf>,
    /// `(line, column)` in the file, both from 1, where the parser knows it.
    pub location: Option<(usize, usize)>,
    /// What is wrong, on one line, naming the key and the value.
    pub message: String,
    /// The entry of the scenario the problem is in, where it is one.
    pub key: Option<KeyPath>,
}

impl ScenarioError {
    fn invalid(file: Option<&Path>, message: String) -> ScenarioError {
        ScenarioError {
            kind: ScenarioErrorKind::Invalid,
            file: file.map(Path::to_path_buf),
            location: None,
            message,
            key: None,
        }
    }
}

/// `file:line:column: ` before a message (`file: ` without a location,
/// nothing without a file).
fn place(file: &Option<PathBuf>, location: &Option<(usize, usize)>) -> String {
    match (file, location) {
        (None, _) => String::new(),
        (Some(file), None) => format!("{}: ", file.display()),
        (Some(file), Some((line, column))) => format!("{}:{line}:{column}: ", file.display()),
    }
}

/// A scenario resolved against a model.
#[derive(Clone, Debug)]
pub struct Scenario {
    /// The file it was read from (`None` for [`Scenario::defaults`]).
    pub file: Option<PathBuf>,
    /// The spec the file names, resolved relative to the file.
    pub spec: Option<PathBuf>,
    /// The file's free-text `description` (empty when it has none).
    pub description: String,
    /// End time of the run \[s\]; positive and finite.
    pub t_end: f64,
    /// The integration method (`simulation.method`).
    pub method: Method,
    /// Tolerances and step limits of the solver, already validated.
    pub options: Options,
    /// Time between output samples \[s\]; positive, and at most
    /// [`MAX_SAMPLES`] samples over `t_end`.
    pub output_interval: f64,
    /// Parameter overrides by index.
    pub parameters: Vec<(usize, f64)>,
    /// Initial coordinates by index, in the model's units (\[m\] or \[rad\]);
    /// the others start at 0.
    pub initial_coordinates: Vec<(usize, f64)>,
    /// Initial velocities by index ([m/s] or [rad/s]); the others start
    /// at 0.
    pub initial_velocities: Vec<(usize, f64)>,
    /// Coordinates solved for static equilibrium before the run.
    pub equilibrium: Vec<usize>,
    /// The crush channel (`metrics.crush`): a combination of coordinates
    /// and of outputs of the position (functions of the coordinates and
    /// time), with an offset or not, compression positive.
    pub crush: Option<Signal>,
    /// The channels of `metrics.displacement`, `velocity`, `acceleration`
    /// and `force`, in that order.
    pub channels: Vec<Channel>,
    /// Coordinates whose rotation is reported as pitch, relative to the
    /// start.
    pub pitch: Vec<usize>,
    /// The contact elements whose contact ends the pulse
    /// (`metrics.contact`); empty: every contact element.
    pub contact: Vec<String>,
    /// The weld component whose failure time the summary reports
    /// (`metrics.weld`); it names a weld component of the scenario.
    pub weld: Option<String>,
    /// The model's inputs bound to the scenario's crash components (and
    /// `--set` constants).
    pub inputs: BoundInputs,
    /// Baumgarte's stabilization of the model's constraints (`[constraints]
    /// alpha`, `beta`); unused for a model without constraints.
    pub stabilization: lagrangian_runtime::constrained::Baumgarte,
    /// How the output samples get `q̈` (`simulation.accelerations`).
    pub accelerations: SampleAccelerations,
    /// What a step's stages see of a kink of an input of time inside it
    /// (`simulation.time_kinks`).
    pub time_kinks: TimeKinks,
    /// What a run written as an ISO-MME test holds besides the vehicle's
    /// standard channels (`[iso_mme]`).
    pub iso_mme: iso_mme::IsoMme,
}

impl Scenario {
    /// Sets the scenario's parameter overrides on `model` (which must be
    /// the model the scenario was resolved against).
    pub fn apply_parameters<const N: usize, S: LagrangianSystem<N>>(
        &self,
        model: &mut S,
    ) -> Result<(), lagrangian_runtime::ModelError> {
        let names: Vec<String> = (model.parameter_names().iter())
            .map(|s| s.to_string())
            .collect();
        for &(index, value) in &self.parameters {
            let name =
                names
                    .get(index)
                    .ok_or(lagrangian_runtime::ModelError::DimensionMismatch {
                        expected: index + 1,
                        found: names.len(),
                    })?;
            model.set_parameter(name, value)?;
        }
        Ok(())
    }

    /// Reads and resolves a scenario file from the disk, applying
    /// `settings` first: [`Scenario::read`] with [`Disk`].
    pub fn load(
        path: &Path,
        names: &ModelNames,
        settings: &[Override],
    ) -> Result<Scenario, ScenarioError> {
        Scenario::read(&Disk, path, names, settings)
    }

    /// Reads the scenario file `path` and the tables it names from `files`,
    /// and resolves it with `settings` applied first (see
    /// [`Scenario::parse_in`]).
    pub fn read(
        files: &dyn Files,
        path: &Path,
        names: &ModelNames,
        settings: &[Override],
    ) -> Result<Scenario, ScenarioError> {
        let text = files.text(path).map_err(|e| ScenarioError {
            kind: ScenarioErrorKind::Unreadable,
            file: Some(path.to_path_buf()),
            location: None,
            message: format!("cannot read: {e}"),
            key: None,
        })?;
        Scenario::parse_in(files, &text, Some(path), names, settings)
    }

    /// A scenario with nothing but defaults (no file).
    pub fn defaults(names: &ModelNames, settings: &[Override]) -> Result<Scenario, ScenarioError> {
        Scenario::parse("", None, names, settings)
    }

    /// The scenario document `text` with the dotted-key and parameter
    /// `settings` applied (input constants are not part of the document).
    pub fn document(
        text: &str,
        names: &ModelNames,
        settings: &[Override],
    ) -> Result<toml::Table, ScenarioError> {
        let invalid = |e: &dyn std::fmt::Display| ScenarioError::invalid(None, e.to_string());
        let mut document: toml::Table = text.parse().map_err(|e| invalid(&e))?;
        quantities::in_si(&mut document, names).map_err(|e| invalid(&e))?;
        let (mut settled, _) = with_settings(document, names, settings).map_err(|e| invalid(&e))?;
        quantities::in_si(&mut settled, names).map_err(|e| invalid(&e))?;
        Ok(settled)
    }

    /// Resolves scenario `text` (from `file`, which relative paths start
    /// from), reading the tables it names from the disk:
    /// [`Scenario::parse_in`] with [`Disk`].
    pub fn parse(
        text: &str,
        file: Option<&Path>,
        names: &ModelNames,
        settings: &[Override],
    ) -> Result<Scenario, ScenarioError> {
        Scenario::parse_in(&Disk, text, file, names, settings)
    }

    /// Resolves scenario `text` (from `file`, which relative paths start
    /// from), reading the tables it names from `files`.
    ///
    /// `settings` override it: `name=value` sets a spec parameter, or gives
    /// an input function a constant value; a dotted key such as
    /// `simulation.t_end=0.2` or `components.front_end.unloading=elastic`
    /// sets that entry of the file (the value is read as TOML).
    pub fn parse_in(
        files: &dyn Files,
        text: &str,
        file: Option<&Path>,
        names: &ModelNames,
        settings: &[Override],
    ) -> Result<Scenario, ScenarioError> {
        let error = |message: String| ScenarioError::invalid(file, message);
        // The one parse of the text: the document with its spans, from
        // which an error finds the place of its entry.
        let spanned = toml::de::DeTable::parse(text).map_err(|e| toml_error(file, text, &e))?;
        let located = |e: EntryError| match locate::setting_of(&e, settings) {
            Some(setting) => ScenarioError {
                key: Some(e.key.clone()),
                ..ScenarioError::invalid(None, locate::blamed(setting, &e))
            },
            None => ScenarioError {
                // Where it is: needed on this path alone (an element's
                // entry from its family's section is where the family's is).
                location: {
                    let places = Places::new(text, spanned.get_ref());
                    places.locate(&e).or_else(|| {
                        let mut at = e.clone();
                        at.key = families::family_key(&e.key)?;
                        places.locate(&at)
                    })
                },
                key: Some(e.key.clone()),
                ..error(e.to_string())
            },
        };
        let mut document = toml::Table::deserialize(toml::de::Deserializer::from(spanned.clone()))
            .map_err(|e| toml_error(file, text, &e))?;
        // Quantities with units, of the file and then of the settings.
        quantities::in_si(&mut document, names).map_err(located)?;
        // The file with its spans as it is read: numbers for its quantities.
        let mut read = spanned.clone();
        quantities::numbers_in_place(read.get_mut(), &document);
        let positioned = || toml::de::Deserializer::from(read.clone());
        let (mut settled, constants) = with_settings(document.clone(), names, settings)
            .map_err(|e| ScenarioError::invalid(None, e.to_string()))?;
        // A family's sections, one per element.
        families::expand(&mut settled, names).map_err(located)?;
        quantities::in_si(&mut settled, names).map_err(located)?;
        let parsed: File = settled.try_into().map_err(|e: toml::de::Error| {
            // The settled document has no positions; the parsed text has
            // them when the problem is in the file rather than in a setting.
            match File::deserialize(positioned()) {
                Err(located) if located.message() == e.message() => {
                    toml_error(file, text, &located)
                }
                _ => match culprit(document, names, settings, e.message()) {
                    Some(setting) => ScenarioError::invalid(
                        None,
                        format!("--set {setting}: {}", with_suggestion(e.message())),
                    ),
                    None => error(with_suggestion(e.message())),
                },
            }
        })?;
        let base = file.and_then(Path::parent).unwrap_or(Path::new("."));
        let tables = load_tables(files, &parsed.components, base).map_err(|e| ScenarioError {
            kind: ScenarioErrorKind::DataFile,
            ..located(e)
        })?;
        resolve(parsed, base, names, constants, &tables)
            .map_err(located)
            .map(|mut s| {
                s.file = file.map(Path::to_path_buf);
                s
            })
    }
}

/// The first of `settings` after which `document` no longer reads as a
/// scenario, with the error `message` (or any error, when none gives that
/// one): the setting a problem that is not in the file comes from.
fn culprit<'a>(
    document: toml::Table,
    names: &ModelNames,
    settings: &'a [Override],
    message: &str,
) -> Option<&'a str> {
    let mut first_failing = None;
    let mut current = document;
    for setting in settings {
        current = with_settings(current, names, std::slice::from_ref(setting))
            .ok()?
            .0;
        quantities::in_si(&mut current, names).ok()?;
        if let Err(e) = current.clone().try_into::<File>() {
            if e.message() == message {
                return Some(setting.text());
            }
            first_failing.get_or_insert(setting.text());
        }
    }
    first_failing
}

/// Reads every data file a scenario's components name, and checks that
/// what they read is there, before anything is bound.
fn load_tables(
    files: &dyn Files,
    components: &BTreeMap<String, crate::components::ComponentSection>,
    base: &Path,
) -> Result<BTreeMap<String, Arc<Table>>, EntryError> {
    let mut tables = BTreeMap::new();
    for (name, section) in components {
        if let Some(table) = section.section().load_table(files, name, base)? {
            tables.insert(name.clone(), table);
        }
    }
    Ok(tables)
}

/// A TOML error at its `line:column` in `text`, with a suggestion for a
/// misspelt key or value.
fn toml_error(file: Option<&Path>, text: &str, e: &toml::de::Error) -> ScenarioError {
    let location = e.span().map(|span| locate::line_column(text, span.start));
    ScenarioError {
        location,
        ..ScenarioError::invalid(file, with_suggestion(e.message()))
    }
}

/// serde's "unknown field `x`, expected one of `a`, `b`" on one line, with
/// "did you mean `a`?" when one of the expected names is close.
fn with_suggestion(message: &str) -> String {
    let message = message.trim().replace('\n', " ");
    let quoted: Vec<&str> = message.split('`').skip(1).step_by(2).collect();
    let unknown = message.starts_with("unknown field") || message.starts_with("unknown variant");
    if unknown
        && let Some((wanted, expected)) = quoted.split_first()
        && let Some(best) = lagrangian_runtime::names::closest(wanted, expected.iter().copied())
    {
        return format!("{message} (did you mean `{best}`?)");
    }
    message
}

#[cfg(test)]
mod tests;
