//! Where an entry of a scenario file is: the `line:column` a message about
//! `metrics.crush = "x"` points at. The TOML document the scenario is
//! resolved from has no positions, so the entry is found in the text.

/// `(line, column)`, from 1, of the entry `message` starts with
/// (`section.key = "value": …` or `section.key: …`): the quoted value when
/// the message quotes one and the text has it on the entry's lines, else
/// the key. `None` when the text has no such entry, or when one of the
/// `settings` (`key=value`) set it: then the value is not the file's.
pub(super) fn locate(text: &str, message: &str, settings: &[String]) -> Option<(usize, usize)> {
    let end = message.find([' ', ':'])?;
    let key = &message[..end];
    let set_by = |s: &String| {
        let set = s
            .split('=')
            .next()
            .unwrap_or("")
            .trim()
            .trim_end_matches('*');
        set == key || key.starts_with(&format!("{set}."))
    };
    if settings.iter().any(set_by) {
        return None;
    }
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
