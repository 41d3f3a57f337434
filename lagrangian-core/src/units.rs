//! Physical dimensions for consistency checks: exponents of mass, length and
//! time. The radian is dimensionless (SI), so `N*m/rad · rad = N*m = J`.
//!
//! Units are written between brackets in a spec: `[kg]`, `[N*s/m]`,
//! `[m/s^2]`, `[kg*m^2]`, `[s^-1]`. Known names: kg, m, s, N, J, W, Pa, Hz,
//! rad and 1. Only dimensions are checked; values are taken to be in SI units.

use crate::rational::Rational;
use std::fmt;

/// `kg^mass · m^length · s^time`.
#[derive(Clone, Copy, PartialEq, Eq, Hash, Debug)]
pub struct Dimension {
    /// The exponent of the kilogram.
    pub mass: Rational,
    /// The exponent of the metre.
    pub length: Rational,
    /// The exponent of the second.
    pub time: Rational,
}

const fn dim(mass: i64, length: i64, time: i64) -> Dimension {
    Dimension {
        mass: Rational::integer(mass),
        length: Rational::integer(length),
        time: Rational::integer(time),
    }
}

impl Dimension {
    /// Dimensionless: ratios and angles (rad).
    pub const NONE: Dimension = dim(0, 0, 0);
    /// kg.
    pub const MASS: Dimension = dim(1, 0, 0);
    /// m.
    pub const LENGTH: Dimension = dim(0, 1, 0);
    /// s.
    pub const TIME: Dimension = dim(0, 0, 1);
    /// N = kg·m·s⁻².
    pub const FORCE: Dimension = dim(1, 1, -2);
    /// J = N·m, that of `T` and `V`.
    pub const ENERGY: Dimension = dim(1, 2, -2);
    /// W = J/s, that of the dissipation function `D`.
    pub const POWER: Dimension = dim(1, 2, -3);

    /// `self · o^sign`; `None` when an exponent leaves exact 128-bit fractions.
    fn combine(self, o: Dimension, sign: Rational) -> Option<Dimension> {
        let add = |a: Rational, b: Rational| a.checked_add(b.checked_mul(sign)?);
        Some(Dimension {
            mass: add(self.mass, o.mass)?,
            length: add(self.length, o.length)?,
            time: add(self.time, o.time)?,
        })
    }

    /// `self · o`; `None` on exponent overflow.
    pub fn checked_mul(self, o: Dimension) -> Option<Dimension> {
        self.combine(o, Rational::ONE)
    }

    /// `self / o`; `None` on exponent overflow.
    pub fn checked_div(self, o: Dimension) -> Option<Dimension> {
        self.combine(o, Rational::MINUS_ONE)
    }

    /// `self^e`; `None` on exponent overflow.
    pub fn checked_pow(self, e: Rational) -> Option<Dimension> {
        Some(Dimension {
            mass: self.mass.checked_mul(e)?,
            length: self.length.checked_mul(e)?,
            time: self.time.checked_mul(e)?,
        })
    }

    /// Whether it is dimensionless.
    pub fn is_none(self) -> bool {
        self == Dimension::NONE
    }

    /// Parses a unit such as `N*m/rad` or `m/s^2`.
    pub fn parse(text: &str) -> Result<Dimension, UnitError> {
        let tokens = tokenize(text)?;
        let mut parser = Parser { tokens, at: 0 };
        let d = parser.product()?;
        match parser.tokens.get(parser.at) {
            None => Ok(d),
            Some(t) => Err(UnitError::Unexpected {
                token: t.clone(),
                unit: text.to_string(),
            }),
        }
    }
}

/// Why a unit's text is no unit ([`Dimension::parse`]).
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum UnitError {
    /// A character no unit has (`unit` the whole text).
    Character {
        /// The character.
        character: char,
        /// The unit's text.
        unit: String,
    },
    /// A token where the unit should have ended.
    Unexpected {
        /// The token.
        token: String,
        /// The unit's text.
        unit: String,
    },
    /// A `^` followed by no integer (`found` what followed, empty at the
    /// end).
    Exponent {
        /// What followed the `^`.
        found: String,
    },
    /// An integer exponent too large for 64 bits.
    ExponentRange(std::num::ParseIntError),
    /// A `(` never closed.
    MissingParenthesis,
    /// A name that is no known unit.
    Unknown {
        /// The name.
        name: String,
    },
    /// The text ended where a unit was expected.
    Incomplete,
    /// Exponents beyond exact 128-bit fractions.
    Overflow,
}

impl fmt::Display for UnitError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            UnitError::Character { character, unit } => {
                write!(f, "unexpected character `{character}` in unit `{unit}`")
            }
            UnitError::Unexpected { token, unit } => {
                write!(f, "unexpected `{token}` in unit `{unit}`")
            }
            UnitError::Exponent { found } => {
                write!(f, "expected an integer exponent, found `{found}`")
            }
            UnitError::ExponentRange(e) => write!(f, "{e}"),
            UnitError::MissingParenthesis => f.write_str("missing `)` in unit"),
            UnitError::Unknown { name } => write!(
                f,
                "unknown unit `{name}`; use kg, m, s, N, J, W, Pa, Hz or rad (values are SI)"
            ),
            UnitError::Incomplete => f.write_str("incomplete unit"),
            UnitError::Overflow => f.write_str("unit exponents beyond exact 128-bit fractions"),
        }
    }
}

impl std::error::Error for UnitError {}

fn tokenize(text: &str) -> Result<Vec<String>, UnitError> {
    let mut tokens = Vec::new();
    let mut chars = text.chars().peekable();
    while let Some(&c) = chars.peek() {
        if c.is_whitespace() {
            chars.next();
        } else if c.is_alphabetic() {
            let mut word = String::new();
            while let Some(&c) = chars.peek().filter(|c| c.is_alphanumeric() || **c == '_') {
                word.push(c);
                chars.next();
            }
            tokens.push(word);
        } else if c.is_ascii_digit() {
            let mut number = String::new();
            while let Some(&c) = chars.peek().filter(|c| c.is_ascii_digit()) {
                number.push(c);
                chars.next();
            }
            tokens.push(number);
        } else if "*/^()-·".contains(c) {
            tokens.push(if c == '·' {
                "*".to_string()
            } else {
                c.to_string()
            });
            chars.next();
        } else {
            return Err(UnitError::Character {
                character: c,
                unit: text.to_string(),
            });
        }
    }
    Ok(tokens)
}

struct Parser {
    tokens: Vec<String>,
    at: usize,
}

impl Parser {
    fn peek(&self) -> Option<&str> {
        self.tokens.get(self.at).map(String::as_str)
    }

    fn next(&mut self) -> Option<String> {
        let t = self.tokens.get(self.at).cloned();
        self.at += 1;
        t
    }

    fn product(&mut self) -> Result<Dimension, UnitError> {
        let mut d = self.power()?;
        while let Some(op) = self
            .peek()
            .filter(|t| *t == "*" || *t == "/")
            .map(str::to_string)
        {
            self.next();
            let rhs = self.power()?;
            d = if op == "*" {
                d.checked_mul(rhs)
            } else {
                d.checked_div(rhs)
            }
            .ok_or(UnitError::Overflow)?;
        }
        Ok(d)
    }

    fn power(&mut self) -> Result<Dimension, UnitError> {
        let base = self.atom()?;
        if self.peek() != Some("^") {
            return Ok(base);
        }
        self.next();
        let negative = self.peek() == Some("-");
        if negative {
            self.next();
        }
        let exponent = match self.next() {
            Some(n) if n.chars().all(|c| c.is_ascii_digit()) => {
                n.parse::<i64>().map_err(UnitError::ExponentRange)?
            }
            other => {
                return Err(UnitError::Exponent {
                    found: other.unwrap_or_default(),
                });
            }
        };
        let exponent = if negative { -exponent } else { exponent };
        base.checked_pow(Rational::integer(exponent))
            .ok_or(UnitError::Overflow)
    }

    fn atom(&mut self) -> Result<Dimension, UnitError> {
        match self.next().as_deref() {
            Some("(") => {
                let d = self.product()?;
                match self.next().as_deref() {
                    Some(")") => Ok(d),
                    _ => Err(UnitError::MissingParenthesis),
                }
            }
            Some("1") | Some("rad") => Ok(Dimension::NONE),
            Some("kg") => Ok(Dimension::MASS),
            Some("m") => Ok(Dimension::LENGTH),
            Some("s") => Ok(Dimension::TIME),
            Some("N") => Ok(Dimension::FORCE),
            Some("J") => Ok(Dimension::ENERGY),
            Some("W") => Ok(Dimension::POWER),
            Some("Pa") => Ok(dim(1, -1, -2)),
            Some("Hz") => Ok(dim(0, 0, -1)),
            Some(other) => Err(UnitError::Unknown {
                name: other.to_string(),
            }),
            None => Err(UnitError::Incomplete),
        }
    }
}

impl fmt::Display for Dimension {
    /// `N`, `J`, `W` when it is one, else `kg·m²·s⁻²`-style; `1` when dimensionless.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        for (name, d) in [
            ("N", Dimension::FORCE),
            ("J", Dimension::ENERGY),
            ("W", Dimension::POWER),
        ] {
            if *self == d {
                return write!(f, "{name}");
            }
        }
        if self.is_none() {
            return write!(f, "1 (dimensionless)");
        }
        let mut parts = Vec::new();
        for (name, e) in [("kg", self.mass), ("m", self.length), ("s", self.time)] {
            if e.is_zero() {
                continue;
            }
            if e.is_one() {
                parts.push(name.to_string());
            } else {
                parts.push(format!("{name}^{e}"));
            }
        }
        write!(f, "{}", parts.join("·"))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn parses_the_units_of_the_specs() {
        assert_eq!(Dimension::parse("N*m/rad").unwrap(), Dimension::ENERGY);
        assert_eq!(Dimension::parse("N*s/m").unwrap(), dim(1, 0, -1));
        assert_eq!(Dimension::parse("m/s^2").unwrap(), dim(0, 1, -2));
        assert_eq!(Dimension::parse("kg*m^2").unwrap(), dim(1, 2, 0));
        assert_eq!(
            Dimension::parse("s^-1").unwrap(),
            Dimension::parse("Hz").unwrap()
        );
        assert_eq!(
            Dimension::parse("N*m*s/rad").unwrap(),
            Dimension::parse("J*s").unwrap()
        );
        assert_eq!(Dimension::parse("(m/s)^2").unwrap(), dim(0, 2, -2));
        let km = Dimension::parse("km").unwrap_err();
        assert_eq!(
            km,
            UnitError::Unknown {
                name: "km".to_string()
            }
        );
        assert!(km.to_string().contains("unknown unit `km`"), "{km}");
        assert_eq!(
            Dimension::parse("m^x"),
            Err(UnitError::Exponent {
                found: "x".to_string()
            })
        );
    }

    #[test]
    fn exponent_overflow_is_an_error_not_zero() {
        // ((m^i64::MAX)^i64::MAX)^4 ≈ m^(2^128) overflowed to m^0 = 1.
        let huge = format!("((m^{0})^{0})^4", i64::MAX);
        let overflow = Dimension::parse(&huge).unwrap_err();
        assert_eq!(overflow, UnitError::Overflow);
        assert!(overflow.to_string().contains("beyond exact"), "{overflow}");
        let big = Dimension::LENGTH
            .checked_pow(Rational::new(i128::MAX, 1).unwrap())
            .unwrap();
        assert_eq!(big.checked_mul(big), None);
        assert_eq!(
            Dimension::LENGTH.checked_pow(Rational::integer(2)),
            Some(dim(0, 2, 0))
        );
        assert_eq!(
            Dimension::ENERGY.checked_div(Dimension::FORCE),
            Some(Dimension::LENGTH)
        );
    }

    #[test]
    fn each_error_says_what_is_wrong_in_the_unit() {
        let message = |text: &str| Dimension::parse(text).unwrap_err().to_string();
        assert_eq!(message("m%s"), "unexpected character `%` in unit `m%s`");
        assert_eq!(message("m s"), "unexpected `s` in unit `m s`");
        assert_eq!(message("m^"), "expected an integer exponent, found ``");
        assert_eq!(
            message("m^99999999999999999999"),
            "number too large to fit in target type"
        );
        assert_eq!(message("(m/s"), "missing `)` in unit");
        assert_eq!(message("m/"), "incomplete unit");
    }

    #[test]
    fn displays_named_and_compound_dimensions() {
        assert_eq!(Dimension::ENERGY.to_string(), "J");
        assert_eq!(dim(1, 0, -1).to_string(), "kg·s^-1");
        assert_eq!(Dimension::NONE.to_string(), "1 (dimensionless)");
    }
}
