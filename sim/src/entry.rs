//! Checks of single scenario entries, shared by the scenario and by the
//! components' sections: a value's range (finite, positive, ≥ 0), a name
//! among the model's (with a suggestion for a typo), and how a number is
//! written in a message. Below both, so that neither reaches the other.

use lagrangian_model::names::closest;

pub(crate) fn unknown<'a>(
    what: &str,
    name: &str,
    known: impl Iterator<Item = &'a str> + Clone,
) -> String {
    let mut message = format!("{what} `{name}` does not exist in the spec");
    if let Some(best) = closest(name, known.clone()) {
        message.push_str(&format!("; did you mean `{best}`?"));
    } else {
        let list: Vec<&str> = known.collect();
        message.push_str(&format!(" (known: {})", list.join(", ")));
    }
    message
}

pub(crate) fn index_of(what: &str, name: &str, list: &[String]) -> Result<usize, String> {
    list.iter()
        .position(|n| n == name)
        .ok_or_else(|| unknown(what, name, list.iter().map(String::as_str)))
}

/// `value` as written in a message: plainly in a readable range, else in
/// scientific notation (`1e-300`, not three hundred zeros).
pub(crate) fn number(value: f64) -> String {
    let magnitude = value.abs();
    if value == 0.0 || !value.is_finite() || (1e-4..1e7).contains(&magnitude) {
        format!("{value}")
    } else {
        format!("{value:e}")
    }
}

/// `value` if it is a finite number; else an error naming `key`.
pub(crate) fn finite(key: &str, value: f64) -> Result<f64, String> {
    if value.is_finite() {
        Ok(value)
    } else {
        Err(format!(
            "{key} = {}: must be a finite number",
            number(value)
        ))
    }
}

/// `Ok` if `value`, the combination `formula` of the entries `entries` of
/// the scenario's section `section`, is finite; else an error naming the
/// entries and what the combination is (`meaning`): entries each finite
/// whose quotient or product overflows double precision, which the run
/// would meet as a force or rate that is not finite.
pub(crate) fn finite_combination(
    section: &str,
    (formula, meaning): (&str, &str),
    entries: &[(&str, f64)],
    value: f64,
) -> Result<(), String> {
    if value.is_finite() {
        return Ok(());
    }
    let given: Vec<String> = (entries.iter())
        .map(|(key, v)| format!("{key} = {}", number(*v)))
        .collect();
    Err(format!(
        "{section}: {formula} = {} ({}) is not finite: {meaning} overflows double precision",
        number(value),
        given.join(", ")
    ))
}

/// `value` if it is finite and positive; else an error naming `key`.
pub(crate) fn positive(key: &str, value: f64) -> Result<f64, String> {
    if value.is_finite() && value > 0.0 {
        Ok(value)
    } else {
        Err(format!(
            "{key} = {value}: must be a positive, finite number"
        ))
    }
}

/// `value` if it is finite and not negative; else an error naming `key`.
pub(crate) fn non_negative(key: &str, value: f64) -> Result<f64, String> {
    if value.is_finite() && value >= 0.0 {
        Ok(value)
    } else {
        Err(format!(
            "{key} = {}: must be a finite number ≥ 0",
            number(value)
        ))
    }
}
