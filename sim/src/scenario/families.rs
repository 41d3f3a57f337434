//! A scenario's sections for the model's indexed families: a component
//! section whose inputs name a family of inputs (`inputs = { force =
//! "spring" }` for `spring[1]` … `spring[6]`) stands for one section per
//! element, `[components."spring[3]"]` and so on, each bound to its
//! elements (`spring[3]`); a section named after an element overrides the
//! family's entries for that element alone. In `initial.moving`, a family
//! of coordinates (`"x"`, `"-x"`) is each of its elements.

use super::ModelNames;
use crate::entry::{EntryError, KeyPath};
use toml::{Table, Value};

/// The indices `k` for which `name[k]` is among `names`, in order.
fn elements(name: &str, names: &[String]) -> Vec<String> {
    let prefix = format!("{name}[");
    (names.iter())
        .filter_map(|n| n.strip_prefix(&prefix)?.strip_suffix(']'))
        .map(str::to_string)
        .collect()
}

/// `document` with its family sections and entries written out per element.
pub(super) fn expand(document: &mut Table, names: &ModelNames) -> Result<(), EntryError> {
    if let Some(Value::Table(initial)) = document.get_mut("initial")
        && let Some(Value::Array(moving)) = initial.get_mut("moving")
    {
        *moving = moving
            .iter()
            .flat_map(|v| moving_elements(v, names))
            .collect();
    }
    let Some(Value::Table(components)) = document.get_mut("components") else {
        return Ok(());
    };
    let sections: Vec<String> = components.keys().cloned().collect();
    let mut expanded: Vec<(String, Vec<String>)> = Vec::new();
    for name in sections {
        let Some(Value::Table(section)) = components.get(&name) else {
            continue;
        };
        let Some(indices) = family_indices(&name, section, names)? else {
            continue;
        };
        let section = section.clone();
        components.remove(&name);
        expanded.push((name.clone(), indices.clone()));
        for k in indices {
            let element = format!("{name}[{k}]");
            let mut made = element_section(&section, &k, names);
            if let Some(Value::Table(own)) = components.get(&element) {
                made.extend(own.iter().map(|(key, v)| (key.clone(), v.clone())));
            }
            components.insert(element, Value::Table(made));
        }
    }
    no_stray_elements(components, &expanded)
}

/// An element section of a family section for an element the family does
/// not have (`[components."spring[9]"]` beside `spring[1..6]`) is an error.
fn no_stray_elements(
    components: &Table,
    expanded: &[(String, Vec<String>)],
) -> Result<(), EntryError> {
    for key in components.keys() {
        let Some((family, rest)) = key.split_once('[') else {
            continue;
        };
        let Some(k) = rest.strip_suffix(']') else {
            continue;
        };
        if let Some((_, indices)) = expanded.iter().find(|(f, _)| f == family)
            && !indices.iter().any(|i| i == k)
        {
            let range = format!("{}…{}", indices[0], indices[indices.len() - 1]);
            let why = format!(
                "`{key}` is not an element of the family section `{family}`, whose elements are {range}"
            );
            return Err(EntryError::at(KeyPath::component(key), why));
        }
    }
    Ok(())
}

/// Where an error about an element's section (`components."spring[3]".fy`)
/// is in the file, when the family's section wrote it: the same key in
/// the family's section (`components.spring.fy`); `None` for any other key.
pub(super) fn family_key(key: &KeyPath) -> Option<KeyPath> {
    let parts: Vec<&str> = key.parts().collect();
    let ["components", element, rest @ ..] = parts.as_slice() else {
        return None;
    };
    let (family, _) = element.strip_suffix(']')?.split_once('[')?;
    let mut path = KeyPath::component(family);
    for part in rest {
        path = path.join(part);
    }
    Some(path)
}

/// A coordinate of `initial.moving`, or each element of a family (with its sign).
fn moving_elements(value: &Value, names: &ModelNames) -> Vec<Value> {
    let Value::String(text) = value else {
        return vec![value.clone()];
    };
    let (sign, name) = match text.strip_prefix('-') {
        Some(name) => ("-", name.trim()),
        None => ("", text.trim()),
    };
    if names.coordinates.iter().any(|c| c == name) {
        return vec![value.clone()];
    }
    match elements(name, &names.coordinates) {
        found if found.is_empty() => vec![value.clone()],
        found => (found.iter())
            .map(|k| Value::String(format!("{sign}{name}[{k}]")))
            .collect(),
    }
}

/// The elements a section stands for, when its inputs name families of
/// inputs (all of the same elements); `None` for a section of its own.
fn family_indices(
    name: &str,
    section: &Table,
    names: &ModelNames,
) -> Result<Option<Vec<String>>, EntryError> {
    let Some(Value::Table(inputs)) = section.get("inputs") else {
        return Ok(None);
    };
    let mut indices: Option<(String, Vec<String>)> = None;
    for value in inputs.values() {
        let Value::String(input) = value else {
            continue;
        };
        if names.inputs.iter().any(|i| i == input) {
            continue;
        }
        let found = elements(input, &names.inputs);
        if found.is_empty() {
            continue;
        }
        match &indices {
            None => indices = Some((input.clone(), found)),
            Some((first, theirs)) if *theirs != found => {
                let key = KeyPath::component(name).join("inputs");
                let why = format!(
                    "the families `{first}` and `{input}` have different elements: bind families of one size"
                );
                return Err(EntryError::at(key, why));
            }
            Some(_) => {}
        }
    }
    Ok(indices.map(|(_, found)| found))
}

/// The family's section for element `k`: each input family it binds
/// replaced by that family's element `k`.
fn element_section(section: &Table, k: &str, names: &ModelNames) -> Table {
    let mut made = section.clone();
    if let Some(Value::Table(inputs)) = made.get_mut("inputs") {
        for (_, value) in inputs.iter_mut() {
            if let Value::String(input) = value {
                let element = format!("{input}[{k}]");
                if names.inputs.contains(&element) {
                    *input = element;
                }
            }
        }
    }
    made
}

#[cfg(test)]
mod tests {
    use super::*;

    fn names() -> ModelNames {
        fn indexed(name: &str, n: usize) -> Vec<String> {
            (1..=n).map(|k| format!("{name}[{k}]")).collect()
        }
        let mut inputs = indexed("spring", 2);
        inputs.extend(indexed("tangent", 2));
        inputs.push("wall".into());
        ModelNames {
            coordinates: indexed("x", 3),
            inputs,
            ..ModelNames::default()
        }
    }

    #[test]
    fn a_family_section_is_one_section_per_element_with_its_overrides() {
        let mut document: Table = r#"
            [initial]
            moving = ["-x", "wall"]
            [components.spring]
            type = "bouc_wen"
            inputs = { force = "spring", stiffness = "tangent" }
            fy = 1.0
            [components."spring[2]"]
            fy = 2.0
            [components.wall]
            type = "crush"
            inputs = { force = "wall" }
        "#
        .parse()
        .unwrap();
        expand(&mut document, &names()).unwrap();
        let moving = document["initial"]["moving"].as_array().unwrap();
        let moving: Vec<&str> = moving.iter().map(|v| v.as_str().unwrap()).collect();
        assert_eq!(moving, ["-x[1]", "-x[2]", "-x[3]", "wall"]);
        let components = document["components"].as_table().unwrap();
        let keys: Vec<&str> = components.keys().map(String::as_str).collect();
        assert_eq!(keys, ["spring[1]", "spring[2]", "wall"]);
        let second = components["spring[2]"].as_table().unwrap();
        assert_eq!(second["fy"].as_float(), Some(2.0));
        assert_eq!(second["type"].as_str(), Some("bouc_wen"));
        assert_eq!(second["inputs"]["stiffness"].as_str(), Some("tangent[2]"));
        assert_eq!(components["spring[1]"]["fy"].as_float(), Some(1.0));
        assert_eq!(components["wall"]["inputs"]["force"].as_str(), Some("wall"));
    }

    #[test]
    fn an_element_section_beyond_the_family_is_an_error() {
        let mut document: Table = r#"
            [components.spring]
            inputs = { force = "spring" }
            [components."spring[3]"]
            fy = 2.0
        "#
        .parse()
        .unwrap();
        let error = expand(&mut document, &names()).unwrap_err().to_string();
        assert!(error.contains("`spring[3]` is not an element of the family section `spring`, whose elements are 1…2"), "{error}");
    }

    #[test]
    fn an_element_s_entry_is_found_in_its_family_s_section() {
        let key = KeyPath::component("spring[3]").join("fy");
        assert_eq!(
            family_key(&key).unwrap().to_string(),
            "components.spring.fy"
        );
        assert!(family_key(&KeyPath::component("wall").join("fy")).is_none());
    }

    #[test]
    fn families_of_different_elements_in_one_section_are_an_error() {
        let mut names = names();
        names.inputs.push("tangent[3]".into());
        let mut document: Table = r#"
            [components.spring]
            inputs = { force = "spring", stiffness = "tangent" }
        "#
        .parse()
        .unwrap();
        let error = expand(&mut document, &names).unwrap_err().to_string();
        assert!(error.contains("components.spring.inputs"), "{error}");
        assert!(error.contains("different elements"), "{error}");
    }
}
