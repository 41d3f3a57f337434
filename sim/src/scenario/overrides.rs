//! `--set key=value` overrides, applied to the scenario document before it is read.

use super::ModelNames;
use super::scale::{factor_base, scaled_inline};
use crate::entry::unknown;
use std::collections::BTreeMap;

/// `--set key=value` split at the first `=`, both sides trimmed.
pub fn split_setting(setting: &str) -> Result<(&str, &str), String> {
    let (key, value) = setting
        .split_once('=')
        .ok_or_else(|| format!("--set `{setting}` is not of the form key=value"))?;
    Ok((key.trim(), value.trim()))
}

/// The value of `--set name=value` for a parameter or an input's constant.
pub fn setting_number(name: &str, value: &str) -> Result<f64, String> {
    value
        .parse()
        .map_err(|_| format!("--set {name}: `{value}` is not a number"))
}

/// `text` read as a TOML value, if it is one.
fn toml_value(text: &str) -> Option<toml::Value> {
    format!("v = {text}")
        .parse::<toml::Table>()
        .ok()
        .and_then(|mut t| t.remove("v"))
}

/// What one `--set key=value` sets.
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
        /// The value.
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

impl Setting {
    /// Reads `key=value`: a plain key names a parameter or an input of
    /// `names` (an error, with a suggestion, if neither), a dotted key a
    /// scenario entry.
    pub fn parse(setting: &str, names: &ModelNames) -> Result<Setting, String> {
        let (key, value) = split_setting(setting)?;
        if let Some(key) = key.strip_suffix('*') {
            return Setting::factor(key.trim(), value, names);
        }
        if key.contains('.') {
            let value = toml_value(value).unwrap_or_else(|| toml::Value::String(value.to_string()));
            return Ok(Setting::Entry {
                key: key.to_string(),
                value,
            });
        }
        let number = setting_number(key, value)?;
        let name = key.to_string();
        if names.parameters.iter().any(|p| p == key) {
            return Ok(Setting::Parameter {
                name,
                value: number,
            });
        }
        if names.inputs.iter().any(|i| i == key) {
            if !number.is_finite() {
                let value = crate::entry::number(number);
                return Err(format!("--set {key} = {value}: must be a finite number"));
            }
            return Ok(Setting::InputConstant {
                name,
                value: number,
            });
        }
        let known = names
            .parameters
            .iter()
            .chain(&names.inputs)
            .map(String::as_str);
        Err(unknown("--set: parameter or input", key, known))
    }
}

impl Setting {
    /// `KEY*=FACTOR` for a parameter or a dotted entry.
    fn factor(key: &str, value: &str, names: &ModelNames) -> Result<Setting, String> {
        let factor = setting_number(&format!("{key}*"), value)?;
        if !factor.is_finite() {
            return Err(format!("--set {key}*: `{value}` is not a finite factor"));
        }
        if !key.contains('.') && !names.parameters.iter().any(|p| p == key) {
            let known = names.parameters.iter().map(String::as_str);
            return Err(unknown(
                "--set: a factor applies to a parameter or a dotted scenario entry; parameter",
                key,
                known,
            ));
        }
        Ok(Setting::Scale {
            key: key.to_string(),
            factor,
        })
    }
}

/// Applies one `--set key=value` to the document (input constants go to
/// `constants`, which are not part of it).
fn apply_setting(
    document: &mut toml::Table,
    setting: &str,
    names: &ModelNames,
    constants: &mut BTreeMap<String, f64>,
) -> Result<(), String> {
    match Setting::parse(setting, names)? {
        Setting::Parameter { name, value } => {
            let parameters = document
                .entry("parameters")
                .or_insert_with(|| toml::Value::Table(toml::Table::new()));
            if let toml::Value::Table(t) = parameters {
                t.insert(name, toml::Value::Float(value));
            }
        }
        Setting::InputConstant { name, value } => {
            constants.insert(name, value);
        }
        Setting::Entry { key, value } => set_entry(document, &key, value)?,
        Setting::Scale { key, factor } => {
            let base = factor_base(&key, document, names, &names.parameter_defaults)
                .map_err(|e| format!("--set {e}"))?;
            let value = toml_value(&scaled_inline(&base, factor))
                .ok_or_else(|| format!("`{key}*=`: the scaled value is not TOML"))?;
            match key.contains('.') {
                true => set_entry(document, &key, value)?,
                false => set_entry(document, &format!("parameters.{key}"), value)?,
            }
        }
    }
    Ok(())
}

/// Sets the entry at dotted `key`, making the tables on the way.
fn set_entry(document: &mut toml::Table, key: &str, value: toml::Value) -> Result<(), String> {
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
    table.insert(parts[parts.len() - 1].to_string(), value);
    Ok(())
}

/// The document with the dotted-key and parameter `settings` applied, and
/// the input constants they give (not part of the document).
pub(super) fn with_settings(
    mut document: toml::Table,
    names: &ModelNames,
    settings: &[String],
) -> Result<(toml::Table, BTreeMap<String, f64>), String> {
    let mut constants = BTreeMap::new();
    for setting in settings {
        apply_setting(&mut document, setting, names, &mut constants)?;
    }
    Ok((document, constants))
}
