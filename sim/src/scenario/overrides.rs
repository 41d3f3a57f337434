//! `--set key=value` overrides, applied to the scenario document before it is read.

use super::ModelNames;
use super::resolve::unknown;
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

/// Applies one `--set key=value` to the document.
pub(super) fn apply_setting(
    document: &mut toml::Table,
    setting: &str,
    names: &ModelNames,
    constants: &mut BTreeMap<String, f64>,
) -> Result<(), String> {
    let (key, value) = split_setting(setting)?;
    if !key.contains('.') {
        let number = setting_number(key, value)?;
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
