//! A scenario's numbers written with a unit (`initial.speed = "56 km/h"`,
//! `force_values = ["4 MN", "6 MN"]`), replaced by their SI values before
//! the document is read, each checked against the unit its entry needs:
//! the solver's times, the initial speed, a coordinate's, a parameter's and
//! an input's unit as the spec declares it (a constant component's values
//! are in their inputs' units), and a component's entries as its section
//! lists them ([`crate::components::SectionUnits`]).

use super::ModelNames;
use crate::components::{ComponentSection, Measure};
use crate::entry::{EntryError, KeyPath};
use crate::quantity::{Problem, value_in};
use toml::de::{DeTable, DeValue};
use toml::{Table, Value};

/// The entries of `[simulation]` that are times.
const SIMULATION_TIMES: [&str; 4] = ["t_end", "max_step", "step", "output_interval"];

/// `document` with every quantity of a known unit replaced by its SI
/// value; an entry of no known unit keeps its string (which reading the
/// document then refuses as a string where a number belongs).
pub(super) fn in_si(document: &mut Table, names: &ModelNames) -> Result<(), EntryError> {
    if let Some(Value::Table(simulation)) = document.get_mut("simulation") {
        for key in SIMULATION_TIMES {
            convert(
                simulation,
                key,
                &KeyPath::new("simulation"),
                &Measure::One("s"),
            )?;
        }
    }
    if let Some(Value::Table(constraints)) = document.get_mut("constraints") {
        for key in ["alpha", "beta"] {
            convert(
                constraints,
                key,
                &KeyPath::new("constraints"),
                &Measure::One("1/s"),
            )?;
        }
    }
    if let Some(Value::Table(initial)) = document.get_mut("initial") {
        initial_in_si(initial, names)?;
    }
    if let Some(Value::Table(parameters)) = document.get_mut("parameters") {
        let units = names.parameters.iter().zip(&names.parameter_units);
        by_name(parameters, &KeyPath::new("parameters"), units, "")?;
    }
    if let Some(Value::Table(components)) = document.get_mut("components") {
        for (name, section) in components.iter_mut() {
            if let Value::Table(section) = section {
                section_in_si(section, &KeyPath::component(name), names)?;
            }
        }
    }
    Ok(())
}

/// `[initial]`: the speed, and each coordinate and velocity in its
/// coordinate's unit.
fn initial_in_si(initial: &mut Table, names: &ModelNames) -> Result<(), EntryError> {
    let key = KeyPath::new("initial");
    convert(initial, "speed", &key, &Measure::One("m/s"))?;
    let units = || names.coordinates.iter().zip(&names.coordinate_units);
    if let Some(Value::Table(coordinates)) = initial.get_mut("coordinates") {
        by_name(coordinates, &key.join("coordinates"), units(), "")?;
    }
    if let Some(Value::Table(velocities)) = initial.get_mut("velocities") {
        by_name(velocities, &key.join("velocities"), units(), "/s")?;
    }
    Ok(())
}

/// The entries of `table` named as the model names them, each in its
/// declared unit followed by `per` (`/s` for a velocity); one the model
/// declares no unit for takes a number only.
fn by_name<'a>(
    table: &mut Table,
    key: &KeyPath,
    units: impl Iterator<Item = (&'a String, &'a Option<String>)>,
    per: &str,
) -> Result<(), EntryError> {
    for (name, unit) in units {
        match (table.get_mut(name.as_str()), unit) {
            (Some(value), Some(unit)) => in_unit(value, &format!("{unit}{per}"), &key.join(name))?,
            (Some(Value::String(text)), None) if starts_with_number(text) => {
                let reason = format!(
                    "the spec declares no unit for `{name}`: write the number in SI units, without quotes"
                );
                return Err(EntryError::text(key.join(name), text, reason));
            }
            _ => {}
        }
    }
    Ok(())
}

/// Whether `text` reads as a number first (`"25 mm"`, not `"fast"`).
fn starts_with_number(text: &str) -> bool {
    let digits = text.trim().trim_start_matches(['+', '-']);
    digits.starts_with(|c: char| c.is_ascii_digit() || c == '.')
}

/// A `[components.NAME]` section's entries in the units of its kind (a
/// constant's values in their inputs' units).
fn section_in_si(section: &mut Table, key: &KeyPath, names: &ModelNames) -> Result<(), EntryError> {
    let Some(Value::String(kind)) = section.get("type") else {
        return Ok(());
    };
    if kind == "constant" {
        if let Some(Value::Table(values)) = section.get_mut("values") {
            let units = names.inputs.iter().zip(&names.input_units);
            by_name(values, &key.join("values"), units, "")?;
        }
        return Ok(());
    }
    let Some(units) = ComponentSection::units_of(kind) else {
        return Ok(());
    };
    for (entry, measure) in units {
        convert(section, entry, key, measure)?;
    }
    Ok(())
}

/// Entry `name` of `table` (at `key`), a quantity or a list of them, in SI
/// units; numbers stay as they are.
fn convert(
    table: &mut Table,
    name: &str,
    key: &KeyPath,
    measure: &Measure,
) -> Result<(), EntryError> {
    let Some(value) = table.get_mut(name) else {
        return Ok(());
    };
    let key = key.join(name);
    match (value, measure) {
        (Value::Array(items), Measure::Pairs(first, second)) => {
            for item in items.iter_mut() {
                if let Value::Array(pair) = item {
                    for (part, unit) in pair.iter_mut().zip([first, second]) {
                        in_unit(part, unit, &key)?;
                    }
                }
            }
        }
        (Value::Array(items), Measure::One(unit)) => {
            for item in items.iter_mut() {
                in_unit(item, unit, &key)?;
            }
        }
        (value, Measure::One(unit)) => in_unit(value, unit, &key)?,
        _ => {}
    }
    Ok(())
}

/// `value`, where it is a string that starts with a number, as its SI
/// value in `unit`. Another string stays, for the reading of the document
/// to refuse as a string where a number belongs.
fn in_unit(value: &mut Value, unit: &str, key: &KeyPath) -> Result<(), EntryError> {
    let Value::String(text) = value else {
        return Ok(());
    };
    match value_in(text, unit) {
        Ok(si) => *value = Value::Float(si),
        Err(e) if e.problem == Problem::NoNumber => {}
        Err(e) => return Err(EntryError::text(key.clone(), text, e.problem.to_string())),
    }
    Ok(())
}

/// `spanned`, the file as parsed with its spans, with a number in place of
/// each quantity that `converted` (the same file read by [`in_si`]) holds
/// the SI value of: the file as a scenario reads it, where a problem that
/// serde finds elsewhere still has its place.
pub(super) fn numbers_in_place(spanned: &mut DeTable<'_>, converted: &Table) {
    for (key, value) in spanned.iter_mut() {
        if let Some(read) = converted.get(key.get_ref().as_ref()) {
            number_in_place(value.get_mut(), read);
        }
    }
}

/// [`numbers_in_place`] of one value.
fn number_in_place(value: &mut DeValue<'_>, read: &Value) {
    match (value, read) {
        (value @ DeValue::String(_), Value::Float(_)) => {
            // Any number: only its place matters.
            if let Ok(zero) = DeValue::parse("0.0") {
                *value = zero.into_inner();
            }
        }
        (DeValue::Table(table), Value::Table(read)) => numbers_in_place(table, read),
        (DeValue::Array(items), Value::Array(read)) => {
            for (item, read) in items.iter_mut().zip(read) {
                number_in_place(item.get_mut(), read);
            }
        }
        _ => {}
    }
}
