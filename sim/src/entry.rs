//! Checks of single scenario entries, shared by the scenario and by the
//! components' sections: a value's range (finite, positive, ≥ 0), a name
//! among the model's (with a suggestion for a typo), and how a number is
//! written in a message. Below both, so that neither reaches the other.

use lagrangian_runtime::names::closest;
use std::fmt;

/// The tables of dotted `key`, as TOML reads a dotted key: a part in
/// double quotes may hold dots (`components."front.crush".gap`, a part
/// instance's component), its quotes removed.
pub fn key_segments(key: &str) -> Vec<String> {
    let (mut parts, mut part, mut quoted) = (Vec::new(), String::new(), false);
    for c in key.chars() {
        match c {
            '"' => quoted = !quoted,
            '.' if !quoted => parts.push(std::mem::take(&mut part)),
            c => part.push(c),
        }
    }
    parts.push(part);
    parts
}

/// Where an entry sits in a scenario document: its dotted key, one part
/// per table (`components.front_end.inputs.force`). A part that is not a
/// bare TOML key, or that the message quotes (a channel name in
/// `metrics.classes."-xb_ddot"`), is written in quotes.
#[derive(Clone, Debug, Default, PartialEq, Eq, PartialOrd, Ord)]
pub struct KeyPath {
    parts: Vec<(String, bool)>,
}

impl KeyPath {
    /// The path of dotted `key` (`simulation.t_end`); the empty path for
    /// an empty key.
    pub fn new(key: &str) -> KeyPath {
        let parts = key_segments(key).into_iter().filter(|p| !p.is_empty());
        KeyPath {
            parts: parts.map(|p| (p, false)).collect(),
        }
    }

    /// The section `[components.{name}]`.
    pub fn component(name: &str) -> KeyPath {
        KeyPath::new("components").join(name)
    }

    /// This path with the part `name` below it.
    pub fn join(&self, name: &str) -> KeyPath {
        let mut path = self.clone();
        path.parts.push((name.to_string(), false));
        path
    }

    /// This path with the part `name` below it, written in quotes.
    pub fn join_quoted(&self, name: &str) -> KeyPath {
        let mut path = self.clone();
        path.parts.push((name.to_string(), true));
        path
    }

    /// The parts, from the top table down.
    pub fn parts(&self) -> impl Iterator<Item = &str> {
        self.parts.iter().map(|(p, _)| p.as_str())
    }

    /// Whether `self` is `other` or a table above it.
    pub fn contains(&self, other: &KeyPath) -> bool {
        other.parts.len() >= self.parts.len()
            && (self.parts().zip(other.parts())).all(|(a, b)| a == b)
    }
}

impl fmt::Display for KeyPath {
    fn fmt(&self, f: &mut fmt::Formatter) -> fmt::Result {
        for (k, (part, quoted)) in self.parts.iter().enumerate() {
            if k > 0 {
                f.write_str(".")?;
            }
            let bare = !part.is_empty()
                && (part.chars()).all(|c| c.is_ascii_alphanumeric() || c == '_' || c == '-');
            match *quoted || !bare {
                true => write!(f, "\"{part}\"")?,
                false => f.write_str(part)?,
            }
        }
        Ok(())
    }
}

/// A scenario entry whose value does not fit: the entry's key, the value
/// as the message writes it (a number, or a string in quotes), and why.
/// `key = value: reason`, `key: reason` without a value, or `key reason`
/// for a reason that is a sentence about the key.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[error("{}", self.message())]
pub struct EntryError {
    /// The entry (or the table) the problem is in.
    pub key: KeyPath,
    /// The value as the message writes it: `inf`, `"-r"`.
    pub value: Option<String>,
    /// What is wrong with it.
    pub reason: String,
    /// How the message writes the key.
    style: Style,
}

/// How an [`EntryError`]'s message writes its key.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Style {
    /// `key = value: reason` or `key: reason`.
    Key,
    /// `key reason`.
    Sentence,
    /// `reason` alone: it names the entry in its own words.
    Reason,
}

impl EntryError {
    /// `key = value: reason`.
    pub fn value(key: KeyPath, value: impl Into<String>, reason: impl Into<String>) -> EntryError {
        EntryError {
            key,
            value: Some(value.into()),
            reason: reason.into(),
            style: Style::Key,
        }
    }

    /// `key = "text": reason`: a string value, in quotes.
    pub fn text(key: KeyPath, text: &str, reason: impl Into<String>) -> EntryError {
        EntryError::value(key, format!("\"{text}\""), reason)
    }

    /// `key: reason`.
    pub fn at(key: KeyPath, reason: impl Into<String>) -> EntryError {
        EntryError {
            key,
            value: None,
            reason: reason.into(),
            style: Style::Key,
        }
    }

    /// `key reason`: the reason a sentence that goes on from the key
    /// (`initial.moving names `x` twice`).
    pub fn sentence(key: KeyPath, reason: impl Into<String>) -> EntryError {
        EntryError {
            style: Style::Sentence,
            ..EntryError::at(key, reason)
        }
    }

    /// `reason` alone, about the entry at `key`: a message that names the
    /// entry in its own words.
    pub fn about(key: KeyPath, reason: impl Into<String>) -> EntryError {
        EntryError {
            style: Style::Reason,
            ..EntryError::at(key, reason)
        }
    }

    /// The message: `key = value: reason`, `key: reason` or `key reason`.
    pub fn message(&self) -> String {
        match (&self.value, self.style) {
            (_, Style::Reason) => self.reason.clone(),
            (Some(value), _) => format!("{} = {value}: {}", self.key, self.reason),
            (None, Style::Sentence) => format!("{} {}", self.key, self.reason),
            (None, Style::Key) => format!("{}: {}", self.key, self.reason),
        }
    }

    /// Whether the message is `key = value: reason` or `key: reason`, so
    /// that the reason alone says what is wrong once the key is known.
    pub fn names_key_first(&self) -> bool {
        self.style == Style::Key
    }

    /// The string value in quotes, without them (`"-r"` → `-r`).
    pub fn quoted_value(&self) -> Option<&str> {
        let value = self.value.as_deref()?;
        value.strip_prefix('"')?.strip_suffix('"')
    }
}

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

impl From<&str> for KeyPath {
    fn from(key: &str) -> KeyPath {
        KeyPath::new(key)
    }
}

impl From<&String> for KeyPath {
    fn from(key: &String) -> KeyPath {
        KeyPath::new(key)
    }
}

impl From<String> for KeyPath {
    fn from(key: String) -> KeyPath {
        KeyPath::new(&key)
    }
}

impl From<&KeyPath> for KeyPath {
    fn from(key: &KeyPath) -> KeyPath {
        key.clone()
    }
}

/// The index of `name` in `list`; else an error at `key`: `what` `name`
/// does not exist in the spec (with a suggestion).
pub(crate) fn index_of(
    key: impl Into<KeyPath>,
    what: &str,
    name: &str,
    list: &[String],
) -> Result<usize, EntryError> {
    list.iter().position(|n| n == name).ok_or_else(|| {
        EntryError::at(
            key.into(),
            unknown(what, name, list.iter().map(String::as_str)),
        )
    })
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
pub(crate) fn finite(key: impl Into<KeyPath>, value: f64) -> Result<f64, EntryError> {
    match value.is_finite() {
        true => Ok(value),
        false => Err(EntryError::value(
            key.into(),
            number(value),
            "must be a finite number",
        )),
    }
}

/// `Ok` if `value`, the combination `formula` of the entries `entries` of
/// the scenario's section `section`, is finite; else an error naming the
/// entries and what the combination is (`meaning`): entries each finite
/// whose quotient or product overflows double precision, which the run
/// would meet as a force or rate that is not finite.
pub(crate) fn finite_combination(
    section: impl Into<KeyPath>,
    (formula, meaning): (&str, &str),
    entries: &[(&str, f64)],
    value: f64,
) -> Result<(), EntryError> {
    if value.is_finite() {
        return Ok(());
    }
    let given: Vec<String> = (entries.iter())
        .map(|(key, v)| format!("{key} = {}", number(*v)))
        .collect();
    Err(EntryError::at(
        section.into(),
        format!(
            "{formula} = {} ({}) is not finite: {meaning} overflows double precision",
            number(value),
            given.join(", ")
        ),
    ))
}

/// `value` if it is finite and positive; else an error naming `key`.
pub(crate) fn positive(key: impl Into<KeyPath>, value: f64) -> Result<f64, EntryError> {
    match value.is_finite() && value > 0.0 {
        true => Ok(value),
        // The value as Rust writes it, as this message always has.
        false => Err(EntryError::value(
            key.into(),
            format!("{value}"),
            "must be a positive, finite number",
        )),
    }
}

/// `value` if it is finite and not negative; else an error naming `key`.
pub(crate) fn non_negative(key: impl Into<KeyPath>, value: f64) -> Result<f64, EntryError> {
    match value.is_finite() && value >= 0.0 {
        true => Ok(value),
        false => Err(EntryError::value(
            key.into(),
            number(value),
            "must be a finite number ≥ 0",
        )),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_quoted_part_of_a_key_keeps_its_dots() {
        assert_eq!(key_segments("simulation.t_end"), ["simulation", "t_end"]);
        let key = "components.\"front.crush\".gap";
        assert_eq!(key_segments(key), ["components", "front.crush", "gap"]);
        assert_eq!(key_segments("m[2]"), ["m[2]"]);
    }
}
