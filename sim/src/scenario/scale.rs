//! Factors `KEY*=x`, as `--set` and `sweep --grid` take them: the entry's
//! value (a number, or a list or table of numbers, each multiplied) or a
//! parameter's, times `x`.

use super::ModelNames;

/// The value a factor on `key` multiplies: the scenario `document`'s entry
/// at a dotted key, or for a parameter its `[parameters]` value in the
/// document or else the spec default (`parameter_defaults`, in the
/// model's order of parameters).
pub fn factor_base(
    key: &str,
    document: &toml::Table,
    names: &ModelNames,
    parameter_defaults: &[f64],
) -> Result<toml::Value, ScaleError> {
    let error = |reason: String| ScaleError {
        key: key.to_string(),
        reason,
    };
    let parameter = names.parameters.iter().position(|p| p == key);
    if parameter.is_some() || !key.contains('.') {
        let Some(k) = parameter else {
            return Err(error(format!(
                "a factor applies to a parameter or a dotted scenario entry, and `{key}` is no parameter"
            )));
        };
        let in_file = document
            .get("parameters")
            .and_then(|t| t.get(key))
            .and_then(as_number);
        let base = in_file
            .or(parameter_defaults.get(k).copied())
            .ok_or_else(|| {
                error(format!(
                    "the value of parameter `{key}` is not known to scale it"
                ))
            })?;
        return Ok(toml::Value::Float(base));
    }
    let value = entry_at(document, key)
        .ok_or_else(|| error("the scenario has no such entry to scale".into()))?;
    if all_numbers(value) {
        Ok(value.clone())
    } else {
        Err(error(format!(
            "a factor scales a number, or a list or table of numbers, not `{value}`"
        )))
    }
}

/// The value at dotted `key` of `document`, if it has one.
pub(super) fn entry_at<'a>(document: &'a toml::Table, key: &str) -> Option<&'a toml::Value> {
    let mut value: Option<&toml::Value> = None;
    let mut table = Some(document);
    for part in crate::entry::key_segments(key) {
        value = table.and_then(|t| t.get(&part));
        table = value.and_then(toml::Value::as_table);
    }
    value
}

/// A factor `KEY*=` with nothing to scale: `` `KEY*=`: reason ``.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[error("`{key}*=`: {reason}")]
pub struct ScaleError {
    /// The parameter name or dotted key the factor is on.
    pub key: String,
    /// Why it has nothing to scale.
    pub reason: String,
}

/// `value` with every number multiplied by `x` (a number, or a list or
/// table of numbers, nested).
pub fn scaled_value(value: &toml::Value, x: f64) -> toml::Value {
    match value {
        toml::Value::Array(items) => {
            toml::Value::Array(items.iter().map(|v| scaled_value(v, x)).collect())
        }
        toml::Value::Table(table) => toml::Value::Table(
            (table.iter())
                .map(|(k, v)| (k.clone(), scaled_value(v, x)))
                .collect(),
        ),
        other => number_value(as_number(other).unwrap_or(f64::NAN) * x),
    }
}

/// A number as a TOML value: a whole number as an integer (so that integer
/// entries such as `simulation.max_steps` can be scaled; float entries
/// accept integers), else a float.
pub fn number_value(x: f64) -> toml::Value {
    match x.fract() == 0.0 && x.abs() < 1e15 {
        true => toml::Value::Integer(x as i64),
        false => toml::Value::Float(x),
    }
}

/// `true` when `value` is a number, or a list or table of numbers (nested).
fn all_numbers(value: &toml::Value) -> bool {
    match value {
        toml::Value::Array(items) => items.iter().all(all_numbers),
        toml::Value::Table(table) => table.values().all(all_numbers),
        other => as_number(other).is_some(),
    }
}

/// A TOML float or integer as a number.
pub fn as_number(value: &toml::Value) -> Option<f64> {
    match value {
        toml::Value::Float(x) => Some(*x),
        toml::Value::Integer(i) => Some(*i as f64),
        _ => None,
    }
}
