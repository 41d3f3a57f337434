//! Exact rational numbers for the coefficients of symbolic expressions.
//!
//! Coefficients in Lagrangian mechanics stay small (½, 2, ¼ …), so a pair of
//! `i128` is plenty. Construction and every arithmetic operation are checked:
//! an overflow yields `None`, and the expression store turns that into a
//! reported error instead of a wrong coefficient. Only the conversion
//! [`Rational::to_f64`] rounds, and the ordering of values too large to
//! cross-multiply falls back to comparing those rounded values.

use std::cmp::Ordering;
use std::fmt;

/// A normalized fraction `num / den` with `den > 0` and `gcd(num, den) = 1`.
#[derive(Clone, Copy, PartialEq, Eq, Hash, Debug)]
pub struct Rational {
    num: i128,
    den: i128,
}

/// `gcd(|a|, |b|)`, in `u128` so that `|i128::MIN|` does not overflow.
fn gcd(a: i128, b: i128) -> u128 {
    let (mut a, mut b) = (a.unsigned_abs(), b.unsigned_abs());
    while b != 0 {
        let r = a % b;
        a = b;
        b = r;
    }
    a
}

impl Default for Rational {
    fn default() -> Self {
        Rational::ZERO
    }
}

impl Rational {
    /// 0.
    pub const ZERO: Rational = Rational { num: 0, den: 1 };
    /// 1.
    pub const ONE: Rational = Rational { num: 1, den: 1 };
    /// −1.
    pub const MINUS_ONE: Rational = Rational { num: -1, den: 1 };
    /// ½ (the exponent of a square root).
    pub const HALF: Rational = Rational { num: 1, den: 2 };

    /// `num / den`, normalized; `None` when `den == 0` or on overflow.
    pub fn new(num: i128, den: i128) -> Option<Rational> {
        if den == 0 {
            return None;
        }
        let Ok(g) = i128::try_from(gcd(num, den)) else {
            // gcd = 2¹²⁷: den = i128::MIN and num ∈ {0, i128::MIN}.
            return Some(if num == 0 {
                Rational::ZERO
            } else {
                Rational::ONE
            });
        };
        let (mut n, mut d) = (num / g, den / g);
        if d < 0 {
            n = n.checked_neg()?;
            d = d.checked_neg()?;
        }
        Some(Rational { num: n, den: d })
    }

    /// The integer `n` (exact: every `i64` fits).
    pub const fn integer(n: i64) -> Rational {
        Rational {
            num: n as i128,
            den: 1,
        }
    }

    /// The numerator, which carries the sign.
    pub fn numer(self) -> i128 {
        self.num
    }

    /// The denominator, positive and coprime to the numerator.
    pub fn denom(self) -> i128 {
        self.den
    }

    /// Whether the value is 0.
    pub fn is_zero(self) -> bool {
        self.num == 0
    }

    /// Whether the value is 1.
    pub fn is_one(self) -> bool {
        self.num == 1 && self.den == 1
    }

    /// Whether the denominator is 1.
    pub fn is_integer(self) -> bool {
        self.den == 1
    }

    /// Whether the value is below 0.
    pub fn is_negative(self) -> bool {
        self.num < 0
    }

    /// The value as an `i64` when it is an integer that fits.
    pub fn to_i64(self) -> Option<i64> {
        if self.den == 1 {
            i64::try_from(self.num).ok()
        } else {
            None
        }
    }

    /// Correctly rounded when numerator and denominator are below 2⁵³.
    pub fn to_f64(self) -> f64 {
        self.num as f64 / self.den as f64
    }

    /// `self + o`; `None` on overflow.
    pub fn checked_add(self, o: Rational) -> Option<Rational> {
        if self.den == o.den {
            return Rational::new(self.num.checked_add(o.num)?, self.den);
        }
        // Denominators are positive, so their gcd fits.
        let g = gcd(self.den, o.den) as i128;
        let lhs = self.num.checked_mul(o.den / g)?;
        let rhs = o.num.checked_mul(self.den / g)?;
        Rational::new(lhs.checked_add(rhs)?, self.den.checked_mul(o.den / g)?)
    }

    /// `self − o`; `None` on overflow.
    pub fn checked_sub(self, o: Rational) -> Option<Rational> {
        self.checked_add(o.checked_neg()?)
    }

    /// `self · o`; `None` on overflow.
    pub fn checked_mul(self, o: Rational) -> Option<Rational> {
        // At most the positive denominator, so it fits; 1 when a numerator is 0.
        let g1 = (gcd(self.num, o.den) as i128).max(1);
        let g2 = (gcd(o.num, self.den) as i128).max(1);
        let n = (self.num / g1).checked_mul(o.num / g2)?;
        let d = (self.den / g2).checked_mul(o.den / g1)?;
        Rational::new(n, d)
    }

    /// `self / o`; `None` when `o` is 0 or on overflow.
    pub fn checked_div(self, o: Rational) -> Option<Rational> {
        self.checked_mul(o.checked_recip()?)
    }

    /// `−self`; `None` for a numerator of `i128::MIN`.
    pub fn checked_neg(self) -> Option<Rational> {
        Some(Rational {
            num: self.num.checked_neg()?,
            den: self.den,
        })
    }

    /// `1 / self`; `None` for 0 or on overflow.
    pub fn checked_recip(self) -> Option<Rational> {
        Rational::new(self.den, self.num)
    }

    /// `self^e` for an integer exponent.
    pub fn checked_powi(self, e: i64) -> Option<Rational> {
        let base = if e < 0 { self.checked_recip()? } else { self };
        let mut result = Rational::ONE;
        let mut b = base;
        let mut k = e.unsigned_abs();
        while k > 0 {
            if k & 1 == 1 {
                result = result.checked_mul(b)?;
            }
            k >>= 1;
            if k > 0 {
                b = b.checked_mul(b)?;
            }
        }
        Some(result)
    }

    /// The exact rational `p/q`-th power when it exists (e.g. 4^(1/2) = 2).
    pub fn exact_pow(self, e: Rational) -> Option<Rational> {
        if e.is_integer() {
            return self.checked_powi(i64::try_from(e.num).ok()?);
        }
        let root = u32::try_from(e.den).ok()?;
        let num = exact_root(self.num, root)?;
        let den = exact_root(self.den, root)?;
        Rational::new(num, den)?.checked_powi(i64::try_from(e.num).ok()?)
    }

    /// Parses a decimal literal such as `9.81`, `1e-3`, `42` exactly.
    pub fn parse_decimal(text: &str) -> Option<Rational> {
        let text: String = text.chars().filter(|c| *c != '_').collect();
        let (mantissa, exponent) = match text.find(['e', 'E']) {
            Some(i) => (&text[..i], text[i + 1..].parse::<i32>().ok()?),
            None => (text.as_str(), 0),
        };
        let (int_part, frac_part) = match mantissa.find('.') {
            Some(i) => (&mantissa[..i], &mantissa[i + 1..]),
            None => (mantissa, ""),
        };
        if int_part.is_empty() && frac_part.is_empty() {
            return None;
        }
        let digits = format!("{int_part}{frac_part}");
        if !digits.chars().all(|c| c.is_ascii_digit()) {
            return None;
        }
        // Trailing zeros move into the exponent, so `1.000…0` with any number
        // of zeros is 1; only significant digits must fit the numerator.
        let significant = digits.trim_end_matches('0');
        let trailing = i32::try_from(digits.len() - significant.len()).ok()?;
        let significant = significant.trim_start_matches('0');
        if significant.is_empty() {
            return Some(Rational::ZERO);
        }
        // Too many significant digits for an i128 is not zero: it is `None`.
        let mantissa_value: i128 = significant.parse().ok()?;
        let scale = exponent
            .checked_add(trailing)?
            .checked_sub(i32::try_from(frac_part.len()).ok()?)?;
        let ten = Rational::integer(10);
        Rational::new(mantissa_value, 1)?.checked_mul(ten.checked_powi(i64::from(scale))?)
    }
}

/// The integer `root`-th root of `value` when it is exact.
fn exact_root(value: i128, root: u32) -> Option<i128> {
    if value < 0 {
        return if root % 2 == 1 {
            exact_root(value.checked_neg()?, root)?.checked_neg()
        } else {
            None
        };
    }
    if value < 2 {
        return Some(value);
    }
    let guess = (value as f64).powf(1.0 / f64::from(root)).round() as i128;
    [guess - 1, guess, guess + 1]
        .into_iter()
        .find(|&c| c >= 0 && c.checked_pow(root) == Some(value))
}

impl Ord for Rational {
    fn cmp(&self, other: &Self) -> Ordering {
        // Cross-multiplication can overflow i128 for huge coefficients; fall
        // back to the float comparison, then to the raw parts for a total order.
        match (
            self.num.checked_mul(other.den),
            other.num.checked_mul(self.den),
        ) {
            (Some(a), Some(b)) => a.cmp(&b),
            _ => self
                .to_f64()
                .partial_cmp(&other.to_f64())
                .unwrap_or(Ordering::Equal)
                .then((self.num, self.den).cmp(&(other.num, other.den))),
        }
    }
}

impl PartialOrd for Rational {
    fn partial_cmp(&self, other: &Self) -> Option<Ordering> {
        Some(self.cmp(other))
    }
}

impl fmt::Display for Rational {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if self.den == 1 {
            write!(f, "{}", self.num)
        } else {
            write!(f, "{}/{}", self.num, self.den)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn r(n: i128, d: i128) -> Rational {
        Rational::new(n, d).unwrap()
    }

    #[test]
    fn normalizes_sign_and_gcd() {
        assert_eq!(r(2, -4), r(-1, 2));
        assert_eq!(r(0, -7), Rational::ZERO);
        assert_eq!(Rational::new(1, 0), None);
    }

    #[test]
    fn arithmetic_is_exact() {
        assert_eq!(r(1, 2).checked_add(r(1, 3)), Some(r(5, 6)));
        assert_eq!(r(1, 2).checked_sub(r(1, 2)), Some(Rational::ZERO));
        assert_eq!(r(2, 3).checked_mul(r(9, 4)), Some(r(3, 2)));
        assert_eq!(r(2, 3).checked_div(r(4, 9)), Some(r(3, 2)));
        assert_eq!(r(2, 3).checked_powi(-3), Some(r(27, 8)));
        assert_eq!(Rational::ZERO.checked_recip(), None);
    }

    #[test]
    fn overflow_is_reported() {
        let big = Rational::new(i128::MAX / 2, 1).unwrap();
        assert_eq!(big.checked_mul(Rational::integer(3)), None);
        assert_eq!(big.checked_add(big).and_then(|x| x.checked_add(big)), None);
    }

    #[test]
    fn the_most_negative_i128_is_handled_without_overflow() {
        // |i128::MIN| overflowed in gcd: a panic in debug builds.
        let half_min = r(-(1 << 126), 1);
        assert_eq!(half_min.checked_add(half_min), Rational::new(i128::MIN, 1));
        assert_eq!(r(i128::MIN, 2), r(-(1 << 126), 1));
        assert_eq!(r(i128::MIN, i128::MIN), Rational::ONE);
        assert_eq!(r(0, i128::MIN), Rational::ZERO);
        assert_eq!(Rational::new(1, i128::MIN), None);
        assert_eq!(r(i128::MIN, 1).checked_neg(), None);
        assert_eq!(r(i128::MIN, 1).checked_mul(r(1, 2)), Some(half_min));
    }

    #[test]
    fn exact_fractional_powers() {
        assert_eq!(r(9, 4).exact_pow(r(1, 2)), Some(r(3, 2)));
        assert_eq!(r(8, 27).exact_pow(r(-2, 3)), Some(r(9, 4)));
        assert_eq!(r(2, 1).exact_pow(r(1, 2)), None);
        assert_eq!(r(-8, 1).exact_pow(r(1, 3)), Some(r(-2, 1)));
        assert_eq!(r(-4, 1).exact_pow(r(1, 2)), None);
    }

    #[test]
    fn parses_decimal_literals_exactly() {
        assert_eq!(Rational::parse_decimal("0.5"), Some(Rational::HALF));
        assert_eq!(Rational::parse_decimal("9.81"), Some(r(981, 100)));
        assert_eq!(Rational::parse_decimal("1e-3"), Some(r(1, 1000)));
        assert_eq!(Rational::parse_decimal("2.5E2"), Some(r(250, 1)));
        assert_eq!(Rational::parse_decimal("30_000"), Some(r(30000, 1)));
        assert_eq!(Rational::parse_decimal("1e80"), None);
        assert_eq!(Rational::parse_decimal("abc"), None);
        assert_eq!(Rational::parse_decimal("0.000"), Some(Rational::ZERO));
        assert_eq!(Rational::parse_decimal("000120"), Some(r(120, 1)));
    }

    #[test]
    fn literals_beyond_i128_are_rejected_not_zero() {
        // 10^42 and 43 significant digits do not fit a 128-bit numerator.
        let big = format!("1{}.0", "0".repeat(42));
        assert_eq!(Rational::parse_decimal(&big), None);
        let precise = format!("0.{}1", "0".repeat(42));
        assert_eq!(Rational::parse_decimal(&precise), None);
        let long = "1234567890".repeat(5);
        assert_eq!(Rational::parse_decimal(&long), None);
        // Trailing zeros are not significant.
        let one = format!("1.{}", "0".repeat(60));
        assert_eq!(Rational::parse_decimal(&one), Some(Rational::ONE));
        let exact = format!("1{}e-40", "0".repeat(40));
        assert_eq!(Rational::parse_decimal(&exact), Some(Rational::ONE));
    }

    #[test]
    fn ordering_matches_values() {
        assert!(r(1, 3) < r(1, 2));
        assert!(r(-1, 2) < Rational::ZERO);
        assert_eq!(r(2, 4).cmp(&r(1, 2)), Ordering::Equal);
    }
}
