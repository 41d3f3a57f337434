//! Where an entry of a scenario file is: the `line:column` an
//! [`EntryError`] about `metrics.crush = "x"` points at, found by its key
//! path in the places the one parse of the file recorded; and which
//! `--set` setting gave the value an error is about.

use super::overrides::Override;
use crate::entry::{EntryError, KeyPath};
use std::collections::BTreeMap;
use std::ops::Range;
use toml::de::{DeTable, DeValue};

/// Where each entry of a scenario file is: its key's and its value's byte
/// ranges, and for a list the ranges of its string items, by key path.
pub(super) struct Places<'t> {
    text: &'t str,
    entries: BTreeMap<KeyPath, Place>,
}

/// Where one entry is in the text.
struct Place {
    key: Range<usize>,
    value: Range<usize>,
    /// The string items of a list value, with their ranges.
    items: Vec<(String, Range<usize>)>,
}

impl<'t> Places<'t> {
    /// The places of every entry of `document`, parsed from `text`.
    pub(super) fn new(text: &'t str, document: &DeTable) -> Places<'t> {
        let mut entries = BTreeMap::new();
        record(&KeyPath::default(), document, &mut entries);
        Places { text, entries }
    }

    /// `(line, column)`, from 1, of the entry `error` is about: its string
    /// value (or the list item that is) when the error quotes one, else its
    /// key; `None` when the file has no such entry.
    pub(super) fn locate(&self, error: &EntryError) -> Option<(usize, usize)> {
        let place = self.entries.get(&error.key)?;
        let at = match error.quoted_value() {
            Some(value) if string_at(self.text, &place.value) == Some(value) => place.value.start,
            Some(value) => (place.items.iter())
                .find(|(item, _)| item == value)
                .map_or(place.key.start, |(_, range)| range.start),
            None => place.key.start,
        };
        Some(line_column(self.text, at))
    }
}

/// Records the places of `table`'s entries, below `path`.
fn record(path: &KeyPath, table: &DeTable, entries: &mut BTreeMap<KeyPath, Place>) {
    for (key, value) in table.iter() {
        let path = path.join(key.get_ref());
        let items = match value.get_ref() {
            DeValue::Array(items) => (items.iter())
                .filter_map(|item| match item.get_ref() {
                    DeValue::String(s) => Some((s.to_string(), item.span())),
                    _ => None,
                })
                .collect(),
            _ => Vec::new(),
        };
        if let DeValue::Table(inner) = value.get_ref() {
            record(&path, inner, entries);
        }
        let place = Place {
            key: key.span(),
            value: value.span(),
            items,
        };
        entries.insert(path, place);
    }
}

/// The string a value's range holds, without its quotes, when it is a
/// basic string on one line.
fn string_at<'t>(text: &'t str, range: &Range<usize>) -> Option<&'t str> {
    let value = text.get(range.clone())?;
    value.strip_prefix('"')?.strip_suffix('"')
}

/// `(line, column)`, from 1, of byte `at` of `text`; the column counts
/// characters.
pub(super) fn line_column(text: &str, at: usize) -> (usize, usize) {
    let before = &text[..floor_char_boundary(text, at)];
    let line = before.matches('\n').count() + 1;
    let column = before.rsplit('\n').next().map_or(0, |l| l.chars().count()) + 1;
    (line, column)
}

/// The largest char boundary of `text` at or below `at`.
fn floor_char_boundary(text: &str, at: usize) -> usize {
    let mut at = at.min(text.len());
    while !text.is_char_boundary(at) {
        at -= 1;
    }
    at
}

/// The last of `settings` that set the entry `error` is about, or a table
/// above it: the value it is about is the setting's.
pub(super) fn setting_of<'a>(error: &EntryError, settings: &'a [Override]) -> Option<&'a Override> {
    let set_by = |s: &&Override| s.path().contains(&error.key);
    settings.iter().rev().find(set_by)
}

/// `error`, about an entry that `setting` set, as an error of the
/// setting: `--set KEY=VALUE: what is wrong` in place of the entry and its
/// value when the setting set that very entry, else `--set KEY=VALUE:
/// message` (the message names what the setting made).
pub(super) fn blamed(setting: &Override, error: &EntryError) -> String {
    let plain = setting.path() == error.key && error.names_key_first();
    match plain && !error.reason.is_empty() {
        true => format!("--set {setting}: {}", error.reason),
        false => format!("--set {setting}: {error}"),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn an_entry_is_found_at_its_value_or_its_key() {
        let text = "spec = \"x.lpm\"\n[metrics]\ncrush = \"-r\"\nacceleration = [\n  \"a\",\n  \"occupant\",\n]\n[initial]\nspeed = 3.0\n";
        let document = DeTable::parse(text).unwrap();
        let places = Places::new(text, document.get_ref());
        let at = |e: EntryError| places.locate(&e);
        let key = KeyPath::new;
        assert_eq!(
            at(EntryError::text(key("metrics.crush"), "-r", "bad")),
            Some((3, 9))
        );
        let occupant = EntryError::text(key("metrics.acceleration"), "occupant", "x");
        assert_eq!(at(occupant), Some((6, 3)));
        assert_eq!(
            at(EntryError::value(key("initial.speed"), "3", "x")),
            Some((9, 1))
        );
        assert_eq!(at(EntryError::at(key("initial.moving"), "x")), None);
        // A table is at its header's key.
        assert_eq!(at(EntryError::at(key("metrics"), "x")), Some((2, 2)));
    }

    #[test]
    fn a_setting_is_blamed_for_the_entry_it_set() {
        let set = Override::parse_all(&["initial.speed=4", "k*=2"]).unwrap();
        let speed = EntryError::value(KeyPath::new("initial.speed"), "4", "too fast");
        assert_eq!(setting_of(&speed, &set), Some(&set[0]));
        assert_eq!(blamed(&set[0], &speed), "--set initial.speed=4: too fast");
        let k = EntryError::value(KeyPath::new("parameters.k"), "inf", "must be finite");
        assert_eq!(setting_of(&k, &set), Some(&set[1]));
        let other = EntryError::at(KeyPath::new("initial.moving"), "x");
        assert_eq!(setting_of(&other, &set), None);
    }
}
