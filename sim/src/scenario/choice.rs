//! A scenario setting of a few named values (`[simulation] accelerations =
//! "exact"`): each value's name is its type's one exhaustive `match`; the
//! parsing and the message that lists the names come from it.

use crate::entry::EntryError;

/// A setting of a few named values.
pub trait Choice: Copy + 'static {
    /// Every value, in the order the messages list them.
    const ALL: &'static [Self];

    /// The value's name, as scenarios write it.
    fn name(self) -> &'static str;

    /// The value named `text`, if any.
    fn parse(text: &str) -> Option<Self> {
        Self::ALL
            .iter()
            .copied()
            .find(|choice| choice.name() == text)
    }
}

/// `key = "name"` of a scenario: the value `name` names, or an error that
/// lists the names.
pub(crate) fn parse_choice<C: Choice>(key: &str, name: &str) -> Result<C, EntryError> {
    C::parse(name).ok_or_else(|| {
        let names: Vec<&str> = C::ALL.iter().map(|choice| choice.name()).collect();
        EntryError::sentence(key.into(), format!("= `{name}`; use {}", names.join(", ")))
    })
}
