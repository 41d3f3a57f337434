//! Numbers written with a unit — `"56 km/h"`, `"25 mm"`, `"4 MN"`,
//! `"20 g"`, `"1.5 ms"` — read as SI values, checked against the unit an
//! entry needs.
//!
//! A unit is a product of symbols with integer powers: `kN/mm`, `N*s/m`,
//! `m/s^2`, `kN·m`, `m/s²`. A symbol is one of
//!
//! | symbol | quantity | SI value |
//! |---|---|---|
//! | `m`, `g`, `s` | metre, gram, second | 1 m, 10⁻³ kg, 1 s |
//! | `N`, `J`, `W`, `Pa`, `Hz` | newton, joule, watt, pascal, hertz | SI |
//! | `rad`, `deg` (`°`), `1` | angles, a pure number | 1, π/180, 1 |
//! | `min`, `h` | minute, hour | 60 s, 3600 s |
//! | `t` | tonne | 1000 kg |
//! | `mph` | mile per hour | 0.44704 m/s |
//!
//! or one of the first group with an SI prefix `G`, `M`, `k`, `c`, `m`,
//! `u` (`µ`), `n` (`mm`, `kN`, `MN`, `ms`, `kPa`). A bare `g` is the gram,
//! except where the entry needs an acceleration: there `"20 g"` is twenty
//! standard gravities, 9.806 65 m/s² each (ISO 80000-3, as crash data
//! writes decelerations). Angles are dimensionless (SI), so `N*m/rad` is
//! `N*m`.

use std::fmt;

/// Standard gravity \[m/s²\] (ISO 80000-3), the `g` of an acceleration.
pub const STANDARD_GRAVITY: f64 = 9.80665;

/// Exponents of kg, m and s.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Dimension {
    /// Of the kilogram.
    pub mass: i32,
    /// Of the metre.
    pub length: i32,
    /// Of the second.
    pub time: i32,
}

impl Dimension {
    const fn new(mass: i32, length: i32, time: i32) -> Dimension {
        Dimension { mass, length, time }
    }

    /// A pure number (and an angle).
    pub const NONE: Dimension = Dimension::new(0, 0, 0);
    /// m/s².
    pub const ACCELERATION: Dimension = Dimension::new(0, 1, -2);

    fn times(self, o: Dimension, power: i32) -> Dimension {
        Dimension::new(
            self.mass + o.mass * power,
            self.length + o.length * power,
            self.time + o.time * power,
        )
    }

    /// What a quantity of this dimension is called, where it has a
    /// common name.
    pub fn name(self) -> Option<&'static str> {
        const NAMES: [(Dimension, &str); 14] = [
            (Dimension::NONE, "a pure number or an angle"),
            (Dimension::new(1, 0, 0), "a mass"),
            (Dimension::new(0, 1, 0), "a length"),
            (Dimension::new(0, 0, 1), "a time"),
            (Dimension::new(0, 1, -1), "a velocity"),
            (Dimension::ACCELERATION, "an acceleration"),
            (Dimension::new(1, 1, -2), "a force"),
            (Dimension::new(1, 2, -2), "an energy or a moment"),
            (Dimension::new(1, 2, -3), "a power"),
            (Dimension::new(1, -1, -2), "a pressure"),
            (Dimension::new(0, 0, -1), "a frequency or a rate"),
            (Dimension::new(1, 0, -2), "a stiffness"),
            (Dimension::new(1, 0, -1), "a damping coefficient"),
            (Dimension::new(1, 2, -1), "a rotational damping coefficient"),
        ];
        NAMES.iter().find(|(d, _)| *d == self).map(|&(_, n)| n)
    }
}

/// A unit: its size in SI units and its dimension.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Unit {
    /// The product of the sizes of the factors with positive powers (a
    /// value is multiplied by it, then divided by `per`, so that
    /// `56 km/h` is 56·1000/3600 as written rather than 56·0.2777…).
    times: f64,
    /// The product of the sizes of the factors with negative powers.
    per: f64,
    /// Its dimension.
    pub dimension: Dimension,
}

/// Why a text is not a quantity in the unit asked for.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[error("`{text}`: {problem}")]
pub struct QuantityError {
    /// The text.
    pub text: String,
    /// What is wrong with it.
    pub problem: Problem,
}

/// What is wrong with a quantity's text.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum Problem {
    /// No number at the start (`"km/h"`, `"fast"`).
    #[error("does not start with a number")]
    NoNumber,
    /// A number without a unit, in quotes.
    #[error("has no unit: write it in {expected}, or as a number without quotes (SI)")]
    NoUnit {
        /// The unit the entry needs.
        expected: String,
    },
    /// A symbol no unit has.
    #[error(
        "unknown unit `{0}` (known: m, g, s, N, J, W, Pa, Hz with a prefix G, M, k, c, m, u; rad, deg, min, h, t, mph)"
    )]
    UnknownSymbol(String),
    /// A power that is no integer, or a unit that does not parse.
    #[error("{0}")]
    Malformed(String),
    /// A unit of another dimension than the entry's.
    #[error("{unit} is {found}, but this entry needs {expected_name} ({expected})")]
    WrongDimension {
        /// The unit written.
        unit: String,
        /// What it measures.
        found: &'static str,
        /// What the entry's unit measures.
        expected_name: &'static str,
        /// The entry's unit.
        expected: String,
    },
    /// A value that is not finite in SI units.
    #[error("is not finite in SI units")]
    NotFinite,
}

/// How a bare `g` reads.
#[derive(Clone, Copy, PartialEq)]
enum BareG {
    Gram,
    Gravity,
}

/// A symbol without prefix: its SI value, dimension, and whether it takes
/// a prefix.
fn symbol(name: &str, g: BareG) -> Option<(f64, Dimension, bool)> {
    let d = Dimension::new;
    Some(match name {
        "m" => (1.0, d(0, 1, 0), true),
        "g" if g == BareG::Gravity => (STANDARD_GRAVITY, Dimension::ACCELERATION, false),
        "g" => (1e-3, d(1, 0, 0), true),
        "s" => (1.0, d(0, 0, 1), true),
        "N" => (1.0, d(1, 1, -2), true),
        "J" => (1.0, d(1, 2, -2), true),
        "W" => (1.0, d(1, 2, -3), true),
        "Pa" => (1.0, d(1, -1, -2), true),
        "Hz" => (1.0, d(0, 0, -1), true),
        "rad" | "1" => (1.0, Dimension::NONE, false),
        "deg" | "°" => (std::f64::consts::PI / 180.0, Dimension::NONE, false),
        "min" => (60.0, d(0, 0, 1), false),
        "h" => (3600.0, d(0, 0, 1), false),
        "t" => (1000.0, d(1, 0, 0), false),
        "mph" => (0.44704, d(0, 1, -1), false),
        _ => return None,
    })
}

/// A symbol, with an SI prefix where it takes one.
fn prefixed(name: &str, g: BareG) -> Option<(f64, Dimension)> {
    if let Some((factor, dimension, _)) = symbol(name, g) {
        return Some((factor, dimension));
    }
    const PREFIXES: [(&str, f64); 8] = [
        ("G", 1e9),
        ("M", 1e6),
        ("k", 1e3),
        ("c", 1e-2),
        ("m", 1e-3),
        ("u", 1e-6),
        ("µ", 1e-6),
        ("n", 1e-9),
    ];
    PREFIXES.iter().find_map(|&(p, scale)| {
        let rest = name.strip_prefix(p)?;
        // A prefixed `g` is always a gram (`kg`, `mg`).
        match symbol(rest, BareG::Gram)? {
            (factor, dimension, true) => Some((scale * factor, dimension)),
            _ => None,
        }
    })
}

impl Unit {
    /// What one of it is in SI units.
    pub fn factor(&self) -> f64 {
        self.times / self.per
    }

    /// `number` of it in SI units.
    pub fn to_si(&self, number: f64) -> f64 {
        number * self.times / self.per
    }

    /// An SI `value` in this unit.
    pub fn from_si(&self, value: f64) -> f64 {
        value * self.per / self.times
    }

    /// Parses a unit such as `kN/mm`, `N*s/m` or `m/s^2`.
    pub fn parse(text: &str) -> Result<Unit, QuantityError> {
        Unit::parse_as(text, BareG::Gram)
    }

    fn parse_as(text: &str, g: BareG) -> Result<Unit, QuantityError> {
        let malformed = |problem: &str| QuantityError {
            text: text.to_string(),
            problem: Problem::Malformed(problem.to_string()),
        };
        let mut unit = Unit {
            times: 1.0,
            per: 1.0,
            dimension: Dimension::NONE,
        };
        let mut sign = 1;
        let mut rest = text.trim();
        if rest.is_empty() {
            return Err(malformed("no unit"));
        }
        loop {
            let end = rest.find(['*', '/', '·']).unwrap_or(rest.len());
            let (factor, power) = power_of(rest[..end].trim(), text)?;
            let (size, dimension) = prefixed(factor, g).ok_or_else(|| QuantityError {
                text: text.to_string(),
                problem: Problem::UnknownSymbol(factor.to_string()),
            })?;
            let power = sign * power;
            match power > 0 {
                true => unit.times *= size.powi(power),
                false => unit.per *= size.powi(-power),
            }
            unit.dimension = unit.dimension.times(dimension, power);
            let Some(separator) = rest[end..].chars().next() else {
                return Ok(unit);
            };
            sign = if separator == '/' { -1 } else { 1 };
            rest = &rest[end + separator.len_utf8()..];
            if rest.trim().is_empty() {
                return Err(malformed("a unit is missing after the last `*` or `/`"));
            }
        }
    }
}

/// The largest power of a unit's factor (`m^12`).
const MAX_POWER: i32 = 12;

/// A factor `sym^n`, `sym²`, `sym³` or `sym`, split into the symbol and
/// its power.
fn power_of<'a>(factor: &'a str, text: &str) -> Result<(&'a str, i32), QuantityError> {
    let malformed = |problem: String| QuantityError {
        text: text.to_string(),
        problem: Problem::Malformed(problem),
    };
    if let Some((symbol, power)) = factor.split_once('^') {
        let power: i32 = (power.trim().parse())
            .map_err(|_| malformed(format!("the power `{power}` is not an integer")))?;
        if !(-MAX_POWER..=MAX_POWER).contains(&power) {
            return Err(malformed(format!(
                "the power {power} is beyond ±{MAX_POWER}"
            )));
        }
        return Ok((symbol.trim(), power));
    }
    for (superscript, power) in [('²', 2), ('³', 3)] {
        if let Some(symbol) = factor.strip_suffix(superscript) {
            return Ok((symbol, power));
        }
    }
    if factor.is_empty() {
        return Err(malformed("an empty unit between two operators".into()));
    }
    Ok((factor, 1))
}

/// The leading number of `text` and the rest.
fn split_number(text: &str) -> Option<(f64, &str)> {
    let text = text.trim();
    let mut end = 0;
    for (i, c) in text.char_indices() {
        let exponent = matches!(c, 'e' | 'E')
            && text[i + 1..].starts_with(|n: char| n.is_ascii_digit() || n == '-' || n == '+');
        let sign = matches!(c, '-' | '+') && (i == 0 || text[..i].ends_with(['e', 'E']));
        if !(c.is_ascii_digit() || c == '.' || exponent || sign || c == '_') {
            break;
        }
        end = i + c.len_utf8();
    }
    let number: f64 = text[..end].replace('_', "").parse().ok()?;
    Some((number, text[end..].trim()))
}

/// Whether `text` reads as a number followed by a unit (`850 g`,
/// `-56 km/h`) rather than as a number or a word: how `--set` and a
/// sweep's axes tell a quantity from a plain value.
pub fn has_unit(text: &str) -> bool {
    let digits = text.trim_start_matches(['+', '-']);
    let number_first = digits.starts_with(|c: char| c.is_ascii_digit() || c == '.');
    number_first && text.contains(char::is_alphabetic)
}

/// The value of `text`, a number with a unit, in the unit `expected`
/// (SI, as an entry's documentation gives it: `m/s`, `N/m`).
pub fn value_in(text: &str, expected: &str) -> Result<f64, QuantityError> {
    let error = |problem: Problem| QuantityError {
        text: text.to_string(),
        problem,
    };
    let target = Unit::parse(expected)?;
    let (number, unit) = split_number(text).ok_or_else(|| error(Problem::NoNumber))?;
    if unit.is_empty() {
        let expected = expected.to_string();
        return Err(error(Problem::NoUnit { expected }));
    }
    let mut written = Unit::parse(unit).map_err(|e| error(e.problem))?;
    if written.dimension != target.dimension && target.dimension == Dimension::ACCELERATION {
        written = Unit::parse_as(unit, BareG::Gravity).unwrap_or(written);
    }
    if written.dimension != target.dimension {
        let name = |d: Dimension| d.name().unwrap_or("a quantity of another dimension");
        return Err(error(Problem::WrongDimension {
            unit: unit.to_string(),
            found: name(written.dimension),
            expected_name: name(target.dimension),
            expected: expected.to_string(),
        }));
    }
    let value = target.from_si(written.to_si(number));
    match value.is_finite() {
        true => Ok(value),
        false => Err(error(Problem::NotFinite)),
    }
}

impl fmt::Display for Dimension {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "kg^{} m^{} s^{}", self.mass, self.length, self.time)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn close(a: f64, b: f64) -> bool {
        (a - b).abs() <= 1e-12 * b.abs().max(1.0)
    }

    #[test]
    fn quantities_read_as_their_si_values() {
        // Closed forms: 56 km/h = 56/3.6 m/s, 20 g = 20·9.80665 m/s², …
        let cases = [
            ("56 km/h", "m/s", 56.0 / 3.6),
            ("35 mph", "m/s", 35.0 * 0.44704),
            ("25 mm", "m", 0.025),
            ("4 MN", "N", 4e6),
            ("20 g", "m/s^2", 20.0 * 9.80665),
            ("20 g", "m/s²", 20.0 * 9.80665),
            ("1.5 ms", "s", 1.5e-3),
            ("1.2 t", "kg", 1200.0),
            ("850 g", "kg", 0.85),
            ("3 kN/mm", "N/m", 3e6),
            ("2.5 kN*s/m", "N*s/m", 2500.0),
            ("4 kN·m", "N*m", 4000.0),
            ("4 kN*m/rad", "N*m", 4000.0),
            ("90 deg", "rad", std::f64::consts::FRAC_PI_2),
            ("-1.5e3 N", "N", -1500.0),
            ("0.2 s", "s", 0.2),
            ("2 MPa", "Pa", 2e6),
            ("50 Hz", "1/s", 50.0),
        ];
        for (text, unit, expected) in cases {
            let value = value_in(text, unit).unwrap_or_else(|e| panic!("{text}: {e}"));
            assert!(close(value, expected), "{text}: {value} ≠ {expected}");
        }
    }

    #[test]
    fn a_unit_of_another_dimension_is_refused_by_name() {
        assert_eq!(
            value_in("56 km", "m/s").unwrap_err().to_string(),
            "`56 km`: km is a length, but this entry needs a velocity (m/s)"
        );
        // The gram is no acceleration's g where a mass is asked for.
        assert!(matches!(
            value_in("20 g", "N").map_err(|e| e.problem),
            Err(Problem::WrongDimension { .. })
        ));
        let refused = [
            ("56", "m/s"),
            ("km/h", "m/s"),
            ("5 furlong", "m"),
            ("5 m^x", "m"),
            ("5 m/", "m"),
            ("5 kh", "s"),
            ("1e308 GN", "N"),
            ("1 m^2147483647", "m"),
            ("1 m^-2147483648", "m"),
            ("1 m^", "m"),
            ("1 *m", "m"),
            ("1 m**s", "m"),
            ("1 é", "m"),
            ("1e", "m"),
            ("-", "m"),
        ];
        for (text, unit) in refused {
            assert!(value_in(text, unit).is_err(), "{text} accepted");
        }
    }
}
