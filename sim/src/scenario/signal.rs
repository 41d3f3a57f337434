//! Signals: the quantities of a run that `[metrics]` names — a column of
//! `trajectory.csv` (a coordinate `q`, its rate `q_dot` or acceleration
//! `q_ddot`, a declared output, a constraint's multiplier `NAME.lambda`) or
//! a constraint's residual `NAME.residual` (its drift), or a linear
//! combination of them such as `"xa - xb"` or `"-r"`.

use super::ModelNames;
use crate::entry::{EntryError, unknown};

/// A column of a run's samples that a signal reads.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Column {
    /// Coordinate `k`.
    Coordinate(usize),
    /// The rate of coordinate `k`.
    Velocity(usize),
    /// The acceleration of coordinate `k`.
    Acceleration(usize),
    /// Declared output `k` of the spec.
    Output(usize),
    /// Column `k` of the scenario's components (`front_end.force`).
    Component(usize),
    /// The multiplier `λ` of constraint `k` (`NAME.lambda`).
    Multiplier(usize),
    /// The residual `g` of constraint `k` (`NAME.residual`): its drift.
    Residual(usize),
}

impl Column {
    /// The column's value in a sample.
    #[inline]
    pub fn value(self, s: &Columns) -> f64 {
        let at = |values: &[f64], k: usize| values.get(k).copied().unwrap_or(f64::NAN);
        match self {
            Column::Coordinate(k) => at(s.q, k),
            Column::Velocity(k) => at(s.v, k),
            Column::Acceleration(k) => at(s.a, k),
            Column::Output(k) => at(s.outputs, k),
            Column::Component(k) => at(s.components, k),
            Column::Multiplier(k) => at(s.multipliers, k),
            Column::Residual(k) => at(s.residuals, k),
        }
    }
}

/// The columns of one sample that a signal may read.
#[derive(Clone, Copy, Debug)]
pub struct Columns<'a> {
    /// Coordinates.
    pub q: &'a [f64],
    /// Velocities.
    pub v: &'a [f64],
    /// Accelerations.
    pub a: &'a [f64],
    /// The spec's outputs.
    pub outputs: &'a [f64],
    /// The components' columns.
    pub components: &'a [f64],
    /// The constraints' multipliers `λ`.
    pub multipliers: &'a [f64],
    /// The constraints' residuals `g`.
    pub residuals: &'a [f64],
}

impl<'a> Columns<'a> {
    /// The columns of coordinates only: `values` stands for `q`, `q̇` and
    /// `q̈` alike.
    pub fn coordinates(values: &'a [f64]) -> Columns<'a> {
        Columns {
            q: values,
            v: values,
            a: values,
            outputs: &[],
            components: &[],
            multipliers: &[],
            residuals: &[],
        }
    }
}

/// An affine combination of sample columns, as the scenario writes it:
/// terms and a constant (`"y + 0.977"`).
#[derive(Clone, Debug, PartialEq)]
pub struct Signal {
    /// The text in the scenario (`"xa - xb"`): the signal's name in the
    /// summary and the sweep table.
    pub name: String,
    /// `(factor, column)` per term, in the order written.
    pub terms: Vec<(f64, Column)>,
    /// The sum of its constant terms (`0.977` of `"y + 0.977"`), in the
    /// unit of its columns; 0 for most.
    pub offset: f64,
    /// The unit of its columns, where the spec declares them.
    pub unit: Option<String>,
}

impl Signal {
    /// The value in a sample; the first term's product starts the sum, so
    /// that `-r` is exactly `−1·r`.
    #[inline]
    pub fn value(&self, s: &Columns) -> f64 {
        self.plus_offset(self.linear(s))
    }

    /// The sum of the terms in a sample, without the offset.
    #[inline]
    fn linear(&self, s: &Columns) -> f64 {
        let mut terms = self.terms.iter();
        let Some(&(c, first)) = terms.next() else {
            return f64::NAN;
        };
        terms.fold(c * first.value(s), |sum, &(c, column)| {
            sum + c * column.value(s)
        })
    }

    /// `value` plus the signal's offset (`value` itself, bit for bit, for
    /// a signal without one: `−0` stays `−0`).
    #[inline]
    pub fn plus_offset(&self, value: f64) -> f64 {
        match self.offset {
            0.0 => value,
            offset => value + offset,
        }
    }

    /// Reads `text` against the model's names; `key` names the entry in
    /// messages (`metrics.crush`).
    pub fn parse(key: &str, text: &str, names: &ModelNames) -> Result<Signal, EntryError> {
        let mut terms = Vec::new();
        let mut units: Vec<Option<String>> = Vec::new();
        let mut offset = 0.0;
        for (factor, name) in split_terms(key, text)? {
            if let Ok(constant) = name.parse::<f64>() {
                offset += factor * constant;
                continue;
            }
            let (column, unit) = column(key, text, name, names)?;
            terms.push((factor, column));
            units.push(unit);
        }
        if terms.is_empty() {
            return Err(EntryError::text(
                key.into(),
                text,
                "a constant reads no column of the run; name one (e.g. \"y + 0.977\")",
            ));
        }
        if !offset.is_finite() {
            return Err(EntryError::text(
                key.into(),
                text,
                "its constant is not a finite number",
            ));
        }
        let unit = units.first().cloned().flatten();
        if let Some(other) = units.iter().find(|u| **u != units[0]) {
            return Err(EntryError::text(
                key.into(),
                text,
                format!(
                    "adds quantities of different units ({} and {})",
                    units[0].as_deref().unwrap_or("none"),
                    other.as_deref().unwrap_or("none")
                ),
            ));
        }
        Ok(Signal {
            name: text.trim().to_string(),
            terms,
            offset,
            unit,
        })
    }

    /// `true` when every term is a coordinate: then the same combination
    /// of the rates and accelerations, without the offset, is the signal's
    /// exact rate and acceleration ([`Signal::of_coordinates`]).
    pub fn is_of_coordinates(&self) -> bool {
        (self.terms.iter()).all(|(_, column)| matches!(column, Column::Coordinate(_)))
    }

    /// The outputs among its terms, in the order written.
    pub fn outputs(&self) -> impl Iterator<Item = usize> + '_ {
        (self.terms.iter()).filter_map(|&(_, column)| match column {
            Column::Output(k) => Some(k),
            _ => None,
        })
    }

    /// The linear part of a signal of coordinates applied to `values`, one
    /// per coordinate: its rate for `q̇`, its acceleration for `q̈`; for
    /// `q`, the signal less its offset ([`Signal::plus_offset`] adds it).
    pub fn of_coordinates(&self, values: &[f64]) -> f64 {
        self.linear(&Columns::coordinates(values))
    }

    /// The signal as a combination of coordinates and outputs with its
    /// columns resolved once, for a signal read at every sample (the crush
    /// channel: the outputs are functions of the coordinates and time, see
    /// [`CoordinateCombination::of`]).
    pub fn coordinate_combination(&self) -> CoordinateCombination {
        let term = |column: Column| match column {
            Column::Coordinate(k) | Column::Velocity(k) | Column::Acceleration(k) => {
                Term::Coordinate(k)
            }
            Column::Output(k) => Term::Output(k),
            Column::Component(_) | Column::Multiplier(_) | Column::Residual(_) => Term::Other,
        };
        CoordinateCombination {
            terms: (self.terms.iter())
                .map(|&(c, column)| (c, term(column)))
                .collect(),
        }
    }
}

/// A term of a [`CoordinateCombination`]: what it reads.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Term {
    /// Coordinate `k` (its rate, its acceleration).
    Coordinate(usize),
    /// Output `k` of the spec (its rate, its acceleration along the motion).
    Output(usize),
    /// A column that is neither: it reads NaN, as in
    /// [`Signal::of_coordinates`].
    Other,
}

/// A signal's combination of coordinates and outputs, as
/// [`Signal::coordinate_combination`] resolves it: `(factor, term)` per
/// term.
#[derive(Clone, Debug, PartialEq)]
pub struct CoordinateCombination {
    terms: Vec<(f64, Term)>,
}

impl CoordinateCombination {
    /// The combination applied to each of `coordinates` (`q`, `q̇`, `q̈`:
    /// one value per coordinate each) and of `outputs` (the outputs, their
    /// rates and their accelerations along the motion: one value per
    /// output each, or empty where no term reads an output). For a
    /// combination of coordinates it is bit for bit
    /// [`Signal::of_coordinates`]: the first term's product starts each sum.
    #[inline]
    pub fn of<const M: usize>(&self, coordinates: [&[f64]; M], outputs: [&[f64]; M]) -> [f64; M] {
        let at = |m: usize, term: Term| {
            let value = match term {
                Term::Coordinate(k) => coordinates[m].get(k),
                Term::Output(k) => outputs[m].get(k),
                Term::Other => None,
            };
            value.copied().unwrap_or(f64::NAN)
        };
        let Some((&(c, first), rest)) = self.terms.split_first() else {
            return [f64::NAN; M];
        };
        let mut sums: [f64; M] = std::array::from_fn(|m| c * at(m, first));
        for &(c, term) in rest {
            for (m, sum) in sums.iter_mut().enumerate() {
                *sum += c * at(m, term);
            }
        }
        sums
    }

    /// Whether a term reads an output.
    pub fn reads_outputs(&self) -> bool {
        (self.terms.iter()).any(|(_, term)| matches!(term, Term::Output(_)))
    }
}

/// What a channel measures, which decides its metrics and its panel of the
/// plots.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Role {
    /// A displacement or angle: extremes and their times.
    Displacement,
    /// A velocity: extremes and their times.
    Velocity,
    /// An acceleration: extremes, peak, filtered peaks and the 3 ms clip.
    Acceleration,
    /// A force or moment: extremes and their times.
    Force,
}

impl Role {
    /// Every role, in the order of the summary.
    pub const ALL: [Role; 4] = [
        Role::Displacement,
        Role::Velocity,
        Role::Acceleration,
        Role::Force,
    ];

    /// The key of `[metrics]` that lists the channels of this role, and the
    /// role's name in `summary.json`.
    pub fn name(self) -> &'static str {
        match self {
            Role::Displacement => "displacement",
            Role::Velocity => "velocity",
            Role::Acceleration => "acceleration",
            Role::Force => "force",
        }
    }
}

/// A channel of the summary: a signal and what it measures.
#[derive(Clone, Debug, PartialEq)]
pub struct Channel {
    /// What it measures.
    pub role: Role,
    /// What it reads.
    pub signal: Signal,
    /// The SAE J211 filter class of its filtered peak and 3 ms clip (an
    /// acceleration's): `metrics.classes`, or
    /// [`DEFAULT_CLASS`](crate::pulse::cfc::DEFAULT_CLASS).
    pub cfc: f64,
}

/// `a - 2*b + c` as `[(1, "a"), (−2, "b"), (1, "c")]`.
fn split_terms<'t>(key: &str, text: &'t str) -> Result<Vec<(f64, &'t str)>, EntryError> {
    let bad = |why: &str| EntryError::text(key.into(), text, why);
    let mut terms = Vec::new();
    let mut rest = text.trim();
    let mut sign = 1.0;
    loop {
        if let Some(r) = rest.strip_prefix('-') {
            (sign, rest) = (-sign, r.trim_start());
            continue;
        }
        if let Some(r) = rest.strip_prefix('+') {
            rest = r.trim_start();
            continue;
        }
        let end = next_sign(rest);
        let (term, after) = rest.split_at(end);
        let (factor, name) = match term.split_once('*') {
            Some((f, n)) => {
                let f: f64 = f
                    .trim()
                    .parse()
                    .map_err(|_| bad(&format!("`{}` is not a number (write `2 * x`)", f.trim())))?;
                (f, n.trim())
            }
            None => (1.0, term.trim()),
        };
        if name.is_empty() {
            return Err(bad("a term names no column"));
        }
        terms.push((sign * factor, name));
        if after.is_empty() {
            return Ok(terms);
        }
        (sign, rest) = (1.0, after);
    }
}

/// Where the next term starts in `rest`: its first `+` or `-` that is not
/// the sign of a number's exponent (`1e-3 * x`).
fn next_sign(rest: &str) -> usize {
    let bytes = rest.as_bytes();
    (1..bytes.len())
        .find(|&k| {
            let exponent = matches!(bytes[k - 1], b'e' | b'E')
                && k >= 2
                && bytes[k - 2].is_ascii_digit()
                && !rest[..k - 1].ends_with(|c: char| c.is_ascii_alphabetic());
            matches!(bytes[k], b'+' | b'-') && !exponent
        })
        .unwrap_or(rest.len())
}

/// The column `name` reads, with its unit.
fn column(
    key: &str,
    text: &str,
    name: &str,
    names: &ModelNames,
) -> Result<(Column, Option<String>), EntryError> {
    let coordinate = |k: usize, suffix: &str| {
        let unit = names.coordinate_units.get(k).cloned().flatten();
        unit.map(|u| format!("{u}{suffix}"))
    };
    let find = |list: &[String], wanted: &str| list.iter().position(|c| c == wanted);
    if let Some(k) = find(&names.outputs, name) {
        let unit = names.output_units.get(k).cloned().flatten();
        return Ok((Column::Output(k), unit));
    }
    if let Some(k) = names.component_columns.iter().position(|(c, _)| c == name) {
        return Ok((Column::Component(k), names.component_columns[k].1.clone()));
    }
    if let Some(k) = find(&names.coordinates, name) {
        return Ok((Column::Coordinate(k), coordinate(k, "")));
    }
    if let Some(found) = constraint_column(name, names) {
        return Ok(found);
    }
    if let Some(base) = name.strip_suffix("_ddot")
        && let Some(k) = find(&names.coordinates, base)
    {
        return Ok((Column::Acceleration(k), coordinate(k, "/s^2")));
    }
    if let Some(base) = name.strip_suffix("_dot")
        && let Some(k) = find(&names.coordinates, base)
    {
        return Ok((Column::Velocity(k), coordinate(k, "/s")));
    }
    let known = known_columns(names);
    Err(EntryError::text(
        key.into(),
        text,
        unknown("column", name, known.iter().map(String::as_str)),
    ))
}

/// `NAME.lambda` or `NAME.residual` of a constraint `NAME`, with its unit
/// (the residual's is the constraint's own, which the model does not say).
fn constraint_column(name: &str, names: &ModelNames) -> Option<(Column, Option<String>)> {
    let (constraint, quantity) = name.rsplit_once('.')?;
    let k = names.constraints.iter().position(|c| c == constraint)?;
    match quantity {
        "lambda" => Some((
            Column::Multiplier(k),
            names.multiplier_units.get(k).cloned().flatten(),
        )),
        "residual" => Some((Column::Residual(k), None)),
        _ => None,
    }
}

/// Every column name a signal may read, for suggestions.
fn known_columns(names: &ModelNames) -> Vec<String> {
    let mut known = names.outputs.clone();
    known.extend(names.component_columns.iter().map(|(c, _)| c.clone()));
    for c in &names.coordinates {
        known.extend([c.clone(), format!("{c}_dot"), format!("{c}_ddot")]);
    }
    for c in &names.constraints {
        known.extend([format!("{c}.lambda"), format!("{c}.residual")]);
    }
    known
}

#[cfg(test)]
mod tests {
    use super::*;

    fn signal(terms: Vec<(f64, Column)>) -> Signal {
        Signal {
            name: "s".into(),
            terms,
            offset: 0.0,
            unit: None,
        }
    }

    /// The resolved combination reads what `of_coordinates` reads, bit for
    /// bit: sums in the written order, NaN for columns that are not a
    /// coordinate's or lie beyond the values.
    #[test]
    fn a_coordinate_combination_is_of_coordinates_bit_for_bit() {
        let values = [0.1, -2.5e-3, 7.0, -0.0];
        let signals = [
            signal(vec![]),
            signal(vec![(-1.0, Column::Coordinate(3))]),
            signal(vec![
                (1.0, Column::Coordinate(0)),
                (-1.0, Column::Coordinate(1)),
            ]),
            signal(vec![
                (0.3, Column::Coordinate(2)),
                (1e-3, Column::Velocity(1)),
                (-2.0, Column::Acceleration(0)),
            ]),
            signal(vec![(1.0, Column::Coordinate(9))]),
            signal(vec![
                (1.0, Column::Coordinate(0)),
                (1.0, Column::Component(0)),
            ]),
            signal(vec![(2.0, Column::Multiplier(0))]),
        ];
        let rates = [-15.5, 0.25, 1e-9, 3.0];
        for s in &signals {
            let expected = [s.of_coordinates(&values), s.of_coordinates(&rates)];
            let got = (s.coordinate_combination()).of([&values, &rates], [&[], &[]]);
            assert_eq!(
                got.map(f64::to_bits),
                expected.map(f64::to_bits),
                "{:?}",
                s.terms
            );
        }
    }

    /// An output term reads the outputs' values, rates and accelerations
    /// as a coordinate term reads `q`, `q̇`, `q̈`: `2·o₁ − x` by hand.
    #[test]
    fn an_output_term_reads_the_outputs_motion() {
        let s = signal(vec![
            (2.0, Column::Output(1)),
            (-1.0, Column::Coordinate(0)),
        ]);
        let combination = s.coordinate_combination();
        assert!(combination.reads_outputs());
        let (q, v, a) = ([0.5], [3.0], [-40.0]);
        let (o, rate, acceleration) = ([9.0, 0.25], [9.0, -1.5], [9.0, 12.0]);
        let got = combination.of([&q, &v, &a], [&o, &rate, &acceleration]);
        assert_eq!(got, [2.0 * 0.25 - 0.5, 2.0 * -1.5 - 3.0, 2.0 * 12.0 + 40.0]);
        // Without the outputs' values the sum is not a number, never 0.
        assert!(combination.of([&q], [&[]])[0].is_nan());
        assert_eq!(s.outputs().collect::<Vec<_>>(), [1]);
    }
}
