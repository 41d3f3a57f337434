//! The text of ISO-MME files: `Name:value` lines, the name padded to 28
//! characters before the colon, `NOVALUE` for a field without a value, in
//! ISO-8859-1.
//!
//! Reading takes UTF-8 where the bytes are valid UTF-8 (what pyisomme
//! writes, and every ASCII file) and ISO-8859-1 otherwise (what the
//! standard prescribes; any byte sequence decodes), a UTF-8 byte-order mark
//! dropped. Writing is ISO-8859-1: a character outside it becomes its
//! nearest ASCII spelling where it has one (dashes, quotes, ellipsis),
//! else `?`.

/// The value of a field that has none.
pub const NOVALUE: &str = "NOVALUE";

/// How many characters a name is padded to before its colon.
pub const NAME_WIDTH: usize = 28;

/// One `Name:value` line; `value` is `None` for `NOVALUE` (or nothing
/// after the colon).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Entry {
    /// The name, without its padding.
    pub name: String,
    /// The value, trimmed; `None` for no value.
    pub value: Option<String>,
}

/// The `Name:value` lines of a file, every one in the order read; names
/// may repeat (`Comments`).
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Header {
    entries: Vec<Entry>,
}

impl Header {
    /// An empty header.
    pub fn new() -> Header {
        Header::default()
    }

    /// The value of the first line named `name`; `None` where there is no
    /// such line or it has no value.
    pub fn get(&self, name: &str) -> Option<&str> {
        self.entry(name).and_then(|e| e.value.as_deref())
    }

    /// The first line named `name`, with or without a value.
    pub fn entry(&self, name: &str) -> Option<&Entry> {
        self.entries.iter().find(|e| e.name == name)
    }

    /// The values of every line named `name`, in order (`None` for
    /// `NOVALUE`).
    pub fn get_all<'a>(&'a self, name: &'a str) -> impl Iterator<Item = Option<&'a str>> + 'a {
        (self.entries.iter())
            .filter(move |e| e.name == name)
            .map(|e| e.value.as_deref())
    }

    /// Every line, in order.
    pub fn entries(&self) -> &[Entry] {
        &self.entries
    }

    /// Adds a line at the end (also one whose name is there already).
    pub fn push(&mut self, name: impl Into<String>, value: Option<String>) {
        self.entries.push(Entry {
            name: name.into(),
            value,
        });
    }

    /// Sets the first line named `name` to `value`, or adds it at the end.
    pub fn set(&mut self, name: &str, value: Option<String>) {
        match self.entries.iter_mut().find(|e| e.name == name) {
            Some(entry) => entry.value = value,
            None => self.push(name, value),
        }
    }

    /// Removes every line whose name `drop` accepts.
    pub fn remove_where(&mut self, drop: impl Fn(&str) -> bool) {
        self.entries.retain(|e| !drop(&e.name));
    }

    /// The number of lines.
    pub fn len(&self) -> usize {
        self.entries.len()
    }

    /// Whether it has no line.
    pub fn is_empty(&self) -> bool {
        self.entries.is_empty()
    }

    /// The lines as written: each `name` padded to [`NAME_WIDTH`], `:`,
    /// the value or `NOVALUE`, a newline.
    pub fn to_text(&self) -> String {
        let mut text = String::new();
        for entry in &self.entries {
            text.push_str(&line(&entry.name, entry.value.as_deref()));
            text.push('\n');
        }
        text
    }
}

impl FromIterator<Entry> for Header {
    fn from_iter<I: IntoIterator<Item = Entry>>(entries: I) -> Header {
        Header {
            entries: entries.into_iter().collect(),
        }
    }
}

/// One line as written (without its newline).
pub fn line(name: &str, value: Option<&str>) -> String {
    format!("{name:<NAME_WIDTH$}:{}", value.unwrap_or(NOVALUE))
}

/// The `Name:value` of a line, where it is one: a name of at least one
/// character other than space and `:`, then `:`, then the value (`None`
/// for `NOVALUE` or nothing).
pub fn entry_of(line: &str) -> Option<Entry> {
    let (name, value) = line.split_once(':')?;
    let name = name.trim();
    if name.is_empty() {
        return None;
    }
    Some(Entry {
        name: name.to_string(),
        value: value_of(value),
    })
}

/// A field's value: trimmed, `None` for `NOVALUE` or nothing.
pub fn value_of(text: &str) -> Option<String> {
    let text = text.trim();
    match text.is_empty() || text.eq_ignore_ascii_case(NOVALUE) {
        true => None,
        false => Some(text.to_string()),
    }
}

/// The text of a file's bytes (see the module: UTF-8, else ISO-8859-1).
pub fn decode(bytes: &[u8]) -> String {
    let bytes = bytes.strip_prefix(b"\xEF\xBB\xBF").unwrap_or(bytes);
    match std::str::from_utf8(bytes) {
        Ok(text) => text.to_string(),
        Err(_) => bytes.iter().map(|&b| b as char).collect(),
    }
}

/// `text` in ISO-8859-1 (see the module for what is not in it).
pub fn encode(text: &str) -> Vec<u8> {
    let mut bytes = Vec::with_capacity(text.len());
    for c in text.chars() {
        match u8::try_from(u32::from(c)) {
            Ok(b) => bytes.push(b),
            Err(_) => bytes.extend_from_slice(ascii_for(c).as_bytes()),
        }
    }
    bytes
}

/// The nearest ASCII of a character outside ISO-8859-1.
fn ascii_for(c: char) -> &'static str {
    match c {
        '\u{2010}'..='\u{2015}' | '\u{2212}' => "-",
        '\u{2018}' | '\u{2019}' | '\u{201A}' | '\u{2032}' => "'",
        '\u{201C}' | '\u{201D}' | '\u{201E}' | '\u{2033}' => "\"",
        '\u{2026}' => "...",
        '\u{2264}' => "<=",
        '\u{2265}' => ">=",
        _ => "?",
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_line_is_its_name_padded_to_28_then_the_value() {
        assert_eq!(
            line("Sampling interval", Some("0.0001")),
            "Sampling interval           :0.0001"
        );
        assert_eq!(
            line("Comments", None),
            format!("Comments{}:NOVALUE", " ".repeat(20))
        );
        // The colon is at column 29 (the 28 characters of the name, then it).
        assert_eq!(line("Unit", Some("g")).find(':'), Some(NAME_WIDTH));
    }

    #[test]
    fn novalue_and_nothing_are_no_value_and_a_value_may_hold_colons() {
        let e = entry_of("Date of the test            :NOVALUE").unwrap();
        assert_eq!((e.name.as_str(), e.value), ("Date of the test", None));
        assert_eq!(entry_of("Comments :").unwrap().value, None);
        let e = entry_of("Timestamp:2024-01-02 12:30:00").unwrap();
        assert_eq!(e.value.as_deref(), Some("2024-01-02 12:30:00"));
        assert_eq!(entry_of(" : value"), None);
        assert_eq!(entry_of("-0.125"), None);
    }

    #[test]
    fn latin1_bytes_decode_and_encode_back_and_utf8_is_taken_as_utf8() {
        let latin1 = b"Laboratory name             :M\xFCller \xB0C";
        let text = decode(latin1);
        assert_eq!(text, "Laboratory name             :Müller °C");
        assert_eq!(encode(&text), latin1.to_vec());
        assert_eq!(decode("Müller".as_bytes()), "Müller");
        assert_eq!(decode(b"\xEF\xBB\xBFUnit:g"), "Unit:g");
        assert_eq!(
            encode("Hunt\u{2013}Crossley \u{201C}x\u{201D} \u{03C0}"),
            b"Hunt-Crossley \"x\" ?"
        );
    }

    #[test]
    fn a_header_keeps_repeated_names_in_order_and_sets_the_first() {
        let mut h = Header::new();
        h.push("Comments", Some("one".into()));
        h.push("Unit", Some("g".into()));
        h.push("Comments", None);
        h.push("Comments", Some("three".into()));
        let all: Vec<_> = h.get_all("Comments").collect();
        assert_eq!(all, [Some("one"), None, Some("three")]);
        h.set("Unit", Some("m/s".into()));
        h.set("Dimension", Some("AC".into()));
        assert_eq!(h.get("Unit"), Some("m/s"));
        assert_eq!(h.entries().last().unwrap().name, "Dimension");
        assert_eq!(h.len(), 5);
    }
}
