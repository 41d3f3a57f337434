//! Where an entry of a scenario file is: the `line:column` a message about
//! `metrics.crush = "x"` points at. The TOML document the scenario is
//! resolved from has no positions, so the entry is found in the text.

/// `(line, column)`, from 1, of the entry `message` starts with
/// (`section.key = "value": …` or `section.key: …`): the quoted value when
/// the message quotes one and the text has it on the entry's lines, else
/// the key. `None` when the text has no such entry, or when one of the
/// `settings` (`key=value`) set it: then the value is not the file's.
pub(super) fn locate(text: &str, message: &str, settings: &[String]) -> Option<(usize, usize)> {
    if setting_of(message, settings).is_some() {
        return None;
    }
    let end = message.find([' ', ':'])?;
    let key = &message[..end];
    let (section, name) = key.rsplit_once('.')?;
    let value = quoted_value(&message[end..]);
    let lines: Vec<&str> = text.lines().collect();
    let start = entry_line(&lines, section, name)?;
    if let Some(value) = value {
        let quoted = format!("\"{value}\"");
        // The value may be on a later line of a multi-line array.
        for (k, line) in lines.iter().enumerate().skip(start).take(20) {
            if let Some(column) = line.find(&quoted) {
                return Some((k + 1, line[..column].chars().count() + 1));
            }
        }
    }
    let column = lines[start].len() - lines[start].trim_start().len();
    Some((start + 1, column + 1))
}

/// The last of `settings` (`key=value`, `key*=factor`) that set the entry
/// `message` starts with (`section.key = "value": …`, `section.key: …`),
/// or a table above it: the value it is about is the setting's.
pub(super) fn setting_of<'a>(message: &str, settings: &'a [String]) -> Option<&'a String> {
    let end = message.find([' ', ':'])?;
    let key = &message[..end];
    let set_by = |s: &&String| {
        let set = s
            .split('=')
            .next()
            .unwrap_or("")
            .trim()
            .trim_end_matches('*')
            .trim();
        // A plain key sets a parameter: `parameters.NAME`.
        let set = match set.contains('.') {
            true => set.to_string(),
            false => format!("parameters.{set}"),
        };
        set == key || key.starts_with(&format!("{set}."))
    };
    settings.iter().rev().find(set_by)
}

/// `message` about an entry that `setting` set, as an error of the
/// setting: `--set KEY=VALUE: what is wrong` in place of the entry and its
/// value (`parameters.k = inf: …`) when the setting gave that value, else
/// `--set KEY*=FACTOR: message` (the message names what the setting made).
pub(super) fn blamed(setting: &str, message: &str) -> String {
    let setting = setting.trim();
    let key = setting.split('=').next().unwrap_or("").trim();
    let key = match key.contains('.') {
        true => key.to_string(),
        false => format!("parameters.{key}"),
    };
    let end = message.find([' ', ':']);
    // The message is about the very entry set to that value.
    let plain = end.is_some_and(|end| message[..end] == key);
    let rest = end.map(|end| &message[end..]);
    let reason = rest.map(|rest| {
        let rest = rest.trim_start();
        let rest = rest.strip_prefix('=').map_or(rest, |r| {
            // ` = value: reason`: the reason after the value.
            r.split_once(": ").map_or("", |(_, reason)| reason)
        });
        rest.strip_prefix(':').unwrap_or(rest).trim_start()
    });
    match reason {
        Some(reason) if plain && !reason.is_empty() => format!("--set {setting}: {reason}"),
        _ => format!("--set {setting}: {message}"),
    }
}

/// The value in ` = "value"` at the start of the rest of a message.
fn quoted_value(rest: &str) -> Option<&str> {
    let rest = rest.trim_start().strip_prefix('=')?.trim_start();
    let rest = rest.strip_prefix('"')?;
    rest.find('"').map(|end| &rest[..end])
}

/// The index of the line that sets `name` in `[section]`.
fn entry_line(lines: &[&str], section: &str, name: &str) -> Option<usize> {
    let mut current = String::new();
    for (k, line) in lines.iter().enumerate() {
        let line = line.trim();
        if let Some(header) = line.strip_prefix('[').and_then(|l| l.strip_suffix(']')) {
            current = header.trim().to_string();
            continue;
        }
        let Some((key, _)) = line.split_once('=') else {
            continue;
        };
        if current == section && key.trim().trim_matches('"') == name {
            return Some(k);
        }
    }
    None
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn an_entry_is_found_at_its_value_or_its_key() {
        let text = "spec = \"x.lpm\"\n[metrics]\ncrush = \"-r\"\nacceleration = [\n  \"a\",\n  \"occupant\",\n]\n[initial]\nspeed = 3.0\n";
        let at = |m: &str| locate(text, m, &[]);
        assert_eq!(at("metrics.crush = \"-r\": bad"), Some((3, 9)));
        assert_eq!(at("metrics.acceleration = \"occupant\": x"), Some((6, 3)));
        assert_eq!(at("initial.speed = 3: x"), Some((9, 1)));
        assert_eq!(at("initial.moving: x"), None);
        assert_eq!(at("no key here"), None);
        let set = ["initial.speed=4".to_string()];
        assert_eq!(locate(text, "initial.speed = 4: x", &set), None);
    }
}
