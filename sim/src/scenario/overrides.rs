//! Overrides of a scenario — `--set KEY=VALUE`, `KEY*=FACTOR`, a sweep's
//! axis value, a fitted parameter, a Python keyword — read once where they
//! come in ([`Override`]) and applied to the scenario document before it is
//! read.

use super::ModelNames;
use super::scale::{factor_base, scaled_value};
use crate::entry::{KeyPath, number, unknown};
use std::collections::BTreeMap;
use std::fmt;
use std::str::FromStr;

/// One change to a scenario: a plain key names a parameter or an input
/// (set to a number), a dotted key an entry of the scenario file.
#[derive(Clone, Debug, PartialEq)]
pub struct Override {
    /// A parameter or input name, or a dotted scenario key.
    pub key: String,
    /// What it does to the key's value.
    pub change: Change,
    /// As written (`k=2`, `k*=1.1`), for messages.
    text: String,
}

/// What an [`Override`] does to its key's value.
#[derive(Clone, Debug, PartialEq)]
pub enum Change {
    /// `KEY=VALUE`: the value, as TOML reads it (a bare word is a string;
    /// a number for a plain key).
    Set(toml::Value),
    /// `KEY*=FACTOR`: every number of the value (a number, or a list or
    /// table of numbers) multiplied by the factor, finite.
    Scale(f64),
}

/// An override that cannot be read or does not fit the model or the
/// scenario: the override as written, and what is wrong.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[error("{message}")]
pub struct OverrideError {
    /// The override as written (`k=two`).
    pub setting: String,
    /// The message, which names it.
    message: String,
}

impl OverrideError {
    fn new(setting: &str, message: String) -> OverrideError {
        OverrideError {
            setting: setting.trim().to_string(),
            message,
        }
    }
}

/// `--set key=value` split at the first `=`, both sides trimmed.
fn split_setting(setting: &str) -> Result<(&str, &str), OverrideError> {
    let (key, value) = setting.split_once('=').ok_or_else(|| {
        OverrideError::new(
            setting,
            format!("--set `{setting}` is not of the form key=value"),
        )
    })?;
    Ok((key.trim(), value.trim()))
}

/// The value of `--set name=value` for a parameter or an input's constant.
fn setting_number(setting: &str, name: &str, value: &str) -> Result<f64, OverrideError> {
    (value.parse()).map_err(|_| {
        OverrideError::new(setting, format!("--set {name}: `{value}` is not a number"))
    })
}

/// `text` (in quotes or not) where it reads as a number with a unit
/// (`850 g`, `"1.2 t"`): a parameter's quantity, read in its unit later.
fn quantity_text(text: &str) -> Option<&str> {
    let bare = text.strip_prefix('"').and_then(|t| t.strip_suffix('"'));
    let text = bare.unwrap_or(text).trim();
    crate::quantity::has_unit(text).then_some(text)
}

/// `text` read as a TOML value, if it is one.
fn toml_value(text: &str) -> Option<toml::Value> {
    format!("v = {text}")
        .parse::<toml::Table>()
        .ok()
        .and_then(|mut t| t.remove("v"))
}

impl Override {
    /// Reads `KEY=VALUE` or `KEY*=FACTOR`: a plain key takes a number (or
    /// a parameter a number with a unit, `m=1.2 t`), a factor a finite
    /// number, a dotted key any TOML value (a bare word is a string).
    pub fn parse(setting: &str) -> Result<Override, OverrideError> {
        let (key, value) = split_setting(setting)?;
        let text = setting.trim().to_string();
        if let Some(key) = key.strip_suffix('*') {
            let key = key.trim();
            let factor = setting_number(setting, &format!("{key}*"), value)?;
            if !factor.is_finite() {
                let message = format!("--set {key}*: `{value}` is not a finite factor");
                return Err(OverrideError::new(setting, message));
            }
            let change = Change::Scale(factor);
            let key = key.to_string();
            return Ok(Override { key, change, text });
        }
        let value = match key.contains('.') {
            true => toml_value(value).unwrap_or_else(|| toml::Value::String(value.to_string())),
            false => match quantity_text(value) {
                Some(quantity) if value.parse::<f64>().is_err() => {
                    toml::Value::String(quantity.to_string())
                }
                _ => toml::Value::Float(setting_number(setting, key, value)?),
            },
        };
        let (key, change) = (key.to_string(), Change::Set(value));
        Ok(Override { key, change, text })
    }

    /// `key=value` for a number: a parameter, an input's constant or a
    /// numeric entry.
    pub fn number(key: &str, value: f64) -> Override {
        Override {
            key: key.to_string(),
            change: Change::Set(toml::Value::Float(value)),
            text: format!("{key}={value}"),
        }
    }

    /// `key=value` for a TOML value of a dotted entry, or a number of a
    /// plain key.
    pub fn value(key: &str, value: toml::Value) -> Override {
        let text = format!("{key}={value}");
        let change = Change::Set(value);
        let key = key.to_string();
        Override { key, change, text }
    }

    /// Each of `settings` read ([`Override::parse`]), the first problem
    /// returned.
    pub fn parse_all<S: AsRef<str>>(settings: &[S]) -> Result<Vec<Override>, OverrideError> {
        settings
            .iter()
            .map(|s| Override::parse(s.as_ref()))
            .collect()
    }

    /// The override as written: `k=2`, `k*=1.1`.
    pub fn text(&self) -> &str {
        &self.text
    }

    /// The scenario entry it changes: a plain key is a parameter's,
    /// `parameters.NAME`.
    pub fn path(&self) -> KeyPath {
        match self.key.contains('.') {
            true => KeyPath::new(&self.key),
            false => KeyPath::new("parameters").join(&self.key),
        }
    }
}

impl FromStr for Override {
    type Err = OverrideError;

    fn from_str(setting: &str) -> Result<Override, OverrideError> {
        Override::parse(setting)
    }
}

impl fmt::Display for Override {
    fn fmt(&self, f: &mut fmt::Formatter) -> fmt::Result {
        f.write_str(&self.text)
    }
}

/// What one override sets, once the model's names are known.
#[derive(Clone, Debug, PartialEq)]
pub enum Setting {
    /// A spec parameter.
    Parameter {
        /// Its name.
        name: String,
        /// The value.
        value: f64,
    },
    /// An input function, given a constant value.
    InputConstant {
        /// Its name.
        name: String,
        /// The value, finite.
        value: f64,
    },
    /// An entry of the scenario file, by its dotted key.
    Entry {
        /// The key, e.g. `simulation.t_end`.
        key: String,
        /// The value as TOML reads it (a bare word is a string).
        value: toml::Value,
    },
    /// `KEY*=FACTOR`: a parameter, or every number of a dotted entry (a
    /// number, or a list or table of numbers), multiplied by `factor`, as
    /// a factor of `sweep --grid` does.
    Scale {
        /// A parameter name or a dotted key.
        key: String,
        /// The factor, finite.
        factor: f64,
    },
}

impl Override {
    /// What it sets in the model named by `names`: a plain key names a
    /// parameter or an input (an error, with a suggestion, if neither).
    pub fn setting(&self, names: &ModelNames) -> Result<Setting, OverrideError> {
        let key = self.key.as_str();
        let error = |message: String| OverrideError::new(&self.text, message);
        let value = match &self.change {
            Change::Scale(factor) => return self.factor(*factor, names),
            Change::Set(value) if key.contains('.') && !names_model(key, names) => {
                let (key, value) = (key.to_string(), value.clone());
                return Ok(Setting::Entry { key, value });
            }
            Change::Set(toml::Value::String(text)) if names_model(key, names) => {
                quantity_of(&self.text, key, text, names)?
            }
            Change::Set(value) => super::as_number(value)
                .ok_or_else(|| error(format!("--set {key}: `{value}` is not a number")))?,
        };
        let name = key.to_string();
        if names.parameters.iter().any(|p| p == key) {
            return Ok(Setting::Parameter { name, value });
        }
        if names.inputs.iter().any(|i| i == key) {
            if !value.is_finite() {
                let value = number(value);
                return Err(error(format!(
                    "--set {key} = {value}: must be a finite number"
                )));
            }
            return Ok(Setting::InputConstant { name, value });
        }
        let known = (names.parameters.iter())
            .chain(&names.inputs)
            .map(String::as_str);
        Err(error(unknown("--set: parameter or input", key, known)))
    }

    /// `KEY*=FACTOR` for a parameter or a dotted entry.
    fn factor(&self, factor: f64, names: &ModelNames) -> Result<Setting, OverrideError> {
        let key = self.key.as_str();
        let parameter = names.parameters.iter().any(|p| p == key);
        if !key.contains('.') && !parameter {
            let known = names.parameters.iter().map(String::as_str);
            let message = unknown(
                "--set: a factor applies to a parameter or a dotted scenario entry; parameter",
                key,
                known,
            );
            return Err(OverrideError::new(&self.text, message));
        }
        let key = key.to_string();
        Ok(Setting::Scale { key, factor })
    }
}

/// Parameter or input `name` set to `text` by `setting`, a quantity in
/// the unit the spec declares for it (`--set m="1.2 t"`), as an SI number.
fn quantity_of(
    setting: &str,
    name: &str,
    text: &str,
    names: &ModelNames,
) -> Result<f64, OverrideError> {
    let unit = declared_unit(name, names);
    let error =
        |why: String| OverrideError::new(setting, format!("--set {name}=\"{text}\": {why}"));
    let Some(unit) = unit.flatten() else {
        return Err(error(format!(
            "the spec declares no unit for `{name}`: write the number in SI units"
        )));
    };
    crate::quantity::value_in(text, &unit).map_err(|e| error(e.problem.to_string()))
}

/// The unit the spec declares for parameter or input `name`: `None` if it
/// is neither, `Some(None)` if it declares none.
pub(super) fn declared_unit(name: &str, names: &ModelNames) -> Option<Option<String>> {
    let unit_of = |all: &[String], units: &[Option<String>]| {
        let index = all.iter().position(|p| p == name)?;
        Some(units.get(index).cloned().flatten())
    };
    (unit_of(&names.parameters, &names.parameter_units))
        .or_else(|| unit_of(&names.inputs, &names.input_units))
}

/// Whether `name` is a parameter or an input of the model.
fn names_model(name: &str, names: &ModelNames) -> bool {
    names
        .parameters
        .iter()
        .chain(&names.inputs)
        .any(|n| n == name)
}

/// Applies one override to the document (input constants go to
/// `constants`, which are not part of it).
fn apply(
    document: &mut toml::Table,
    setting: &Override,
    names: &ModelNames,
    constants: &mut BTreeMap<String, f64>,
) -> Result<(), OverrideError> {
    let error = |message: String| OverrideError::new(setting.text(), message);
    match setting.setting(names)? {
        Setting::Parameter { name, value } => {
            set_parameter(document, name, toml::Value::Float(value));
        }
        Setting::InputConstant { name, value } => {
            constants.insert(name, value);
        }
        Setting::Entry { key, value } => set_entry(document, &key, value).map_err(error)?,
        Setting::Scale { key, factor } => {
            let base = factor_base(&key, document, names, &names.parameter_defaults)
                .map_err(|e| error(format!("--set {e}")))?;
            let value = scaled_value(&base, factor);
            if names.parameters.contains(&key) {
                set_parameter(document, key, value);
            } else {
                set_entry(document, &key, value).map_err(error)?;
            }
        }
    }
    Ok(())
}

/// Sets parameter `name` in the document's `[parameters]` table, made if
/// missing (a `parameters` that is no table is left for the scenario to
/// report).
fn set_parameter(document: &mut toml::Table, name: String, value: toml::Value) {
    let entry = document
        .entry("parameters")
        .or_insert_with(|| toml::Value::Table(toml::Table::new()));
    if let toml::Value::Table(t) = entry {
        t.insert(name, value);
    }
}

/// Sets the entry at dotted `key`, making the tables on the way; else the
/// message of a part of the key that is not a table.
fn set_entry(document: &mut toml::Table, key: &str, value: toml::Value) -> Result<(), String> {
    let mut table = document;
    let parts = crate::entry::key_segments(key);
    for part in &parts[..parts.len() - 1] {
        let entry = table
            .entry(part.clone())
            .or_insert_with(|| toml::Value::Table(toml::Table::new()));
        table = match entry {
            toml::Value::Table(t) => t,
            _ => return Err(format!("--set {key}: `{part}` is not a table")),
        };
    }
    table.insert(parts[parts.len() - 1].clone(), value);
    Ok(())
}

/// The document with the dotted-key and parameter `settings` applied, and
/// the input constants they give (not part of the document).
pub(super) fn with_settings(
    mut document: toml::Table,
    names: &ModelNames,
    settings: &[Override],
) -> Result<(toml::Table, BTreeMap<String, f64>), OverrideError> {
    let mut constants = BTreeMap::new();
    for setting in settings {
        apply(&mut document, setting, names, &mut constants)?;
    }
    Ok((document, constants))
}

impl From<OverrideError> for super::ScenarioError {
    fn from(e: OverrideError) -> super::ScenarioError {
        super::ScenarioError::invalid(None, e.to_string())
    }
}
