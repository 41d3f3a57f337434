//! A crash test read from the lab's files into what the studies take: the
//! ISO-MME test ([`lagrangian_crashdata::isomme`]) of a folder, an `.mme`
//! or a `.zip`; its channels in SI units; the occupants' channels as the
//! criteria read them ([`lagrangian_sim::criteria`]); the vehicle's pulse;
//! the vehicle channels a fit is asked for, as its time histories
//! ([`vehicle_histories`], in [`vehicle`]).

pub mod vehicle;

pub use vehicle::{ChannelRequest, TestDataError, vehicle_histories};

use crate::error::StudyError;
use lagrangian_crashdata::code::Dimension;
use lagrangian_crashdata::isomme::{self, Channel, Test};
use lagrangian_sim::criteria::codes::{dummy_of, filtered_at, occupant_of, placement};
use lagrangian_sim::criteria::occupant::{Body, Measure};
use lagrangian_sim::criteria::{Dummy, Measured};
use lagrangian_sim::quantity::value_in;
use std::path::Path;

/// Whether `path` holds an ISO-MME test: an `.mme` file, a `.zip`, or a
/// folder with an `.mme` in it (not a simulation's output folder).
pub fn is_iso_mme(path: &Path) -> bool {
    let extension = |p: &Path| {
        p.extension()
            .map(|e| e.to_string_lossy().to_ascii_lowercase())
    };
    match extension(path).as_deref() {
        Some("mme") | Some("zip") => return true,
        _ => {}
    }
    path.is_dir()
        && std::fs::read_dir(path).is_ok_and(|entries| {
            entries
                .flatten()
                .any(|e| extension(&e.path()).as_deref() == Some("mme"))
        })
}

/// The ISO-MME test at `path`; a path that is not there is a
/// [`StudyError::Io`], a file that cannot be read or used a
/// [`StudyError::DataFile`] naming the file, line and field.
pub fn read_iso_mme(path: &Path) -> Result<Test, StudyError> {
    if !path.exists() {
        let path = path.display();
        return Err(StudyError::io(format!("{path}: no such file or folder")));
    }
    isomme::read(path).map_err(|e| StudyError::data_file(e.to_string()))
}

/// An ISO-MME unit written as the project's units are: `**` a power
/// (`m/s**2` as `m/s^2`), RED B's `m/(s*s)` as `m/s^2` and the factors of
/// another parenthesised denominator each divided by, `Nm` and `N m` as
/// `N*m`, and pint's spelling, which pyisomme writes (`m / s2` as `m/s^2`,
/// `km / h` as `km/h`): spaces beside an operator dropped, a space between
/// two symbols a product, a symbol followed by digits a power.
pub fn unit_text(unit: &str) -> String {
    let unit = joined_words(&unit.replace("**", "^")).replace("(s*s)", "s^2");
    let unit = match unit.split_once("/(") {
        Some((numerator, rest)) if rest.ends_with(')') => {
            let denominator = rest[..rest.len() - 1].replace('*', "/");
            format!("{numerator}/{denominator}")
        }
        _ => unit,
    };
    let (mut out, mut factor) = (String::new(), String::new());
    for c in unit.chars() {
        match c {
            '*' | '/' | '·' => {
                out.push_str(&factor_text(&factor));
                out.push(c);
                factor.clear();
            }
            c => factor.push(c),
        }
    }
    out.push_str(&factor_text(&factor));
    out
}

/// The words of `unit` joined: directly beside an operator, by `*`
/// between two symbols.
fn joined_words(unit: &str) -> String {
    let operator = |c: Option<char>| c.is_some_and(|c| matches!(c, '*' | '/' | '·' | '^'));
    let mut out = String::new();
    for word in unit.split_whitespace() {
        if !out.is_empty() && !operator(out.chars().last()) && !operator(word.chars().next()) {
            out.push('*');
        }
        out.push_str(word);
    }
    out
}

/// One factor of a unit: `Nm` as `N*m`, `s2` as `s^2` (a symbol of
/// letters followed by digits), any other as it is.
fn factor_text(factor: &str) -> String {
    match factor {
        "Nm" => return "N*m".into(),
        "kNm" => return "kN*m".into(),
        _ => {}
    }
    let letters = factor.trim_end_matches(|c: char| c.is_ascii_digit());
    let digits = &factor[letters.len()..];
    let symbol = !letters.is_empty() && letters.chars().all(char::is_alphabetic);
    match symbol && !digits.is_empty() {
        true => format!("{letters}^{digits}"),
        false => factor.to_string(),
    }
}

/// The SI unit of a channel's dimension, as the project writes it.
fn si_unit(dimension: Dimension) -> Option<&'static str> {
    Some(match dimension {
        Dimension::Acceleration => "m/s^2",
        Dimension::Velocity => "m/s",
        Dimension::Displacement | Dimension::Distance => "m",
        Dimension::Force => "N",
        Dimension::Moment => "N*m",
        Dimension::Energy => "J",
        Dimension::Angle => "rad",
        _ => return None,
    })
}

/// `channel`'s samples in the SI unit of its dimension (`g` on an
/// acceleration is standard gravity); a unit of another dimension is an
/// error naming the channel and both units.
pub fn si_values(channel: &Channel) -> Result<Vec<f64>, StudyError> {
    let code = channel.code.as_str();
    let Some(si) = si_unit(channel.code.dimension()) else {
        return Err(StudyError::data_file(format!(
            "channel {code}: its dimension {} has no SI unit here",
            channel.code.dimension().code()
        )));
    };
    let unit = unit_text(&channel.unit);
    let factor = match unit.as_str() {
        "" => 1.0,
        unit => value_in(&format!("1 {unit}"), si).map_err(|e| {
            StudyError::data_file(format!("channel {code}: unit {}: {e}", channel.unit))
        })?,
    };
    Ok(channel.values.iter().map(|x| x * factor).collect())
}

/// One channel of an occupant, in SI units, where a criterion reads it.
#[derive(Clone, Debug, PartialEq)]
pub struct OccupantChannel {
    /// Its code.
    pub code: String,
    /// Where it measures.
    pub body: Body,
    /// What it measures.
    pub measure: Measure,
    /// The time of its first sample \[s\].
    pub t0: f64,
    /// Its sample period \[s\].
    pub dt: f64,
    /// Its samples, in SI units.
    pub values: Vec<f64>,
    /// The CFC class it is already filtered at.
    pub filtered: Option<f64>,
}

/// One occupant of a test: its seat and dummy and the channels the criteria
/// read.
#[derive(Clone, Debug, PartialEq)]
pub struct Occupant {
    /// The test object it sits in (`'1'`).
    pub test_object: char,
    /// Its seat position (`'1'` the driver, `'3'` the front passenger).
    pub position: char,
    /// The dummy its channels' codes name.
    pub dummy: Option<Dummy>,
    /// Its channels.
    pub channels: Vec<OccupantChannel>,
}

impl Occupant {
    /// The channels as the criteria take them.
    pub fn measured(&self) -> Vec<Measured<'_>> {
        (self.channels.iter())
            .map(|c| Measured {
                name: &c.code,
                body: c.body,
                measure: c.measure,
                t0: c.t0,
                dt: c.dt,
                values: &c.values,
                filtered: c.filtered,
            })
            .collect()
    }
}

/// The occupants of `test`, by test object and seat, each with its dummy
/// channels (of more than one filter class of a quantity, the first in the
/// test's order).
pub fn occupants(test: &Test) -> Result<Vec<Occupant>, StudyError> {
    let mut out: Vec<Occupant> = Vec::new();
    for channel in &test.channels {
        let Some((body, measure)) = placement(&channel.code) else {
            continue;
        };
        let (test_object, position) = occupant_of(&channel.code);
        let index = match out
            .iter()
            .position(|o| (o.test_object, o.position) == (test_object, position))
        {
            Some(k) => k,
            None => {
                out.push(Occupant {
                    test_object,
                    position,
                    dummy: None,
                    channels: Vec::new(),
                });
                out.len() - 1
            }
        };
        let occupant = &mut out[index];
        occupant.dummy = occupant.dummy.or_else(|| dummy_of(&channel.code));
        if occupant
            .channels
            .iter()
            .any(|c| c.body == body && c.measure == measure)
        {
            continue;
        }
        occupant.channels.push(OccupantChannel {
            code: channel.code.as_str().to_string(),
            body,
            measure,
            t0: channel.t0,
            dt: channel.dt,
            values: si_values(channel)?,
            filtered: filtered_at(&channel.code),
        });
    }
    out.sort_by_key(|o| (o.test_object, o.position));
    Ok(out)
}

/// The vehicle's longitudinal acceleration of `test`: a vehicle's
/// (test object 1–9) `VEHC` channel of dimension `AC` along `X`,
/// unfiltered or prefiltered ones before filtered ones, then in the test's
/// order.
pub fn vehicle_acceleration(test: &Test) -> Option<&Channel> {
    let candidates = test.channels.iter().filter(|c| {
        let code = c.code.as_str();
        code.as_bytes()[0].is_ascii_digit()
            && c.code.main_location() == "VEHC"
            && c.code.dimension() == Dimension::Acceleration
            && &code[14..15] == "X"
    });
    let (raw, filtered): (Vec<&Channel>, Vec<&Channel>) =
        candidates.partition(|c| filtered_at(&c.code).is_none());
    raw.into_iter().chain(filtered).next()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn iso_mme_units_read_as_the_projects() {
        assert_eq!(unit_text("m/s**2"), "m/s^2");
        assert_eq!(unit_text("m/(s*s)"), "m/s^2");
        assert_eq!(unit_text("Nm"), "N*m");
        assert_eq!(unit_text(" kN "), "kN");
        assert_eq!(unit_text("N m"), "N*m");
        assert_eq!(unit_text("m / s2"), "m/s^2", "pyisomme's (pint's) spelling");
        assert_eq!(unit_text("km / h"), "km/h");
        assert_eq!(unit_text("m/s ** 2"), "m/s^2");
        assert_eq!(unit_text("kg*m/(s*s*s)"), "kg*m/s/s/s");
        assert_eq!(unit_text("N*m"), "N*m");
        assert_eq!(unit_text("g"), "g");
        for unit in ["m/(s*s)", "m/s**2", "m/s^2", "m / s2", "m/s²"] {
            let one = value_in(&format!("1 {}", unit_text(unit)), "m/s^2");
            assert_eq!(one, Ok(1.0), "{unit}");
        }
    }

    #[test]
    fn a_path_that_is_not_there_is_an_io_error() {
        let e = read_iso_mme(Path::new("no/such/test.mme")).unwrap_err();
        assert_eq!(e.status().code(), 1, "{e}");
        let e = read_iso_mme(Path::new("Cargo.toml")).unwrap_err();
        assert_eq!(e.status().code(), 7, "{e}");
    }
}
