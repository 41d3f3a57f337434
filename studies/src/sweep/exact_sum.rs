//! Sums of floating-point numbers and of products computed exactly and
//! rounded once, so that the result does not depend on the order of the
//! terms: the weighted sums of an envelope add up to the same bits whether
//! the runs come one by one, from several threads or from shards merged in
//! any order.
//!
//! The finite part is kept as a floating-point expansion (Shewchuk,
//! "Adaptive Precision Floating-Point Arithmetic and Fast Robust Geometric
//! Predicates", 1997): components that do not overlap, in increasing
//! magnitude, whose exact sum is the sum of the terms. A product is split
//! into its rounded value and its exact rounding error with a fused
//! multiply–add. [`ExactSum::value`] rounds the exact sum to the nearest
//! `f64` (ties to even), as Python's `math.fsum` does.
//!
//! Exact as long as no partial sum exceeds the largest `f64` (it is then
//! infinite) and no product falls into the subnormal range (below about
//! 1e-292, where the rounding error of a product is no longer a `f64`).

/// An exact sum of `f64` terms. Two sums are equal when their
/// [`ExactSum::terms`] are (the same value, however it was added up).
#[derive(Clone, Debug, Default)]
pub struct ExactSum {
    /// Components that do not overlap, in increasing magnitude, none zero.
    parts: Vec<f64>,
    /// The sum of the non-finite terms: 0 when there is none, else ±∞ or
    /// NaN (which then is the value).
    special: f64,
}

impl ExactSum {
    /// The empty sum (0).
    pub fn new() -> ExactSum {
        ExactSum::default()
    }

    /// Adds `x`.
    pub fn add(&mut self, x: f64) {
        if !x.is_finite() {
            self.special += x;
            return;
        }
        let mut x = x;
        let mut kept = 0;
        for k in 0..self.parts.len() {
            let mut y = self.parts[k];
            if x.abs() < y.abs() {
                std::mem::swap(&mut x, &mut y);
            }
            let hi = x + y;
            if !hi.is_finite() {
                self.special += hi;
                self.parts.clear();
                return;
            }
            let lo = y - (hi - x);
            if lo != 0.0 {
                self.parts[kept] = lo;
                kept += 1;
            }
            x = hi;
        }
        self.parts.truncate(kept);
        if x != 0.0 {
            self.parts.push(x);
        }
    }

    /// Adds the exact product `a·b`: its rounded value and, from a fused
    /// multiply–add, its rounding error.
    pub fn add_product(&mut self, a: f64, b: f64) {
        let product = a * b;
        self.add(product);
        if product.is_finite() {
            let error = a.mul_add(b, -product);
            if error != 0.0 {
                self.add(error);
            }
        }
    }

    /// Adds every term of `other`.
    pub fn merge(&mut self, other: &ExactSum) {
        for &x in &other.parts {
            self.add(x);
        }
        self.special += other.special;
    }

    /// The sum rounded once to the nearest `f64`, ties to even; the
    /// non-finite terms' sum when there are any.
    pub fn value(&self) -> f64 {
        if self.special != 0.0 {
            return self.special;
        }
        let parts = &self.parts;
        let Some(mut n) = parts.len().checked_sub(1) else {
            return 0.0;
        };
        let mut hi = parts[n];
        let mut lo = 0.0;
        // Add from the largest down while the sum stays exact.
        while n > 0 {
            let x = hi;
            n -= 1;
            let y = parts[n];
            hi = x + y;
            lo = y - (hi - x);
            if lo != 0.0 {
                break;
            }
        }
        // `lo` is exactly half an ulp of `hi` and the parts below push the
        // same way: the tie is not a tie, round away from `hi`.
        let same_sign = |below: f64| (lo < 0.0 && below < 0.0) || (lo > 0.0 && below > 0.0);
        if n > 0 && same_sign(parts[n - 1]) {
            let y = lo * 2.0;
            let x = hi + y;
            if x - hi == y {
                hi = x;
            }
        }
        hi
    }

    /// The sum as few `f64`s that depend only on its exact value: the
    /// value rounded, then what is left rounded, and so on (one non-finite
    /// number when the sum is not finite). [`ExactSum::from_terms`] reads
    /// them back.
    pub fn terms(&self) -> Vec<f64> {
        if self.special != 0.0 {
            return vec![self.special];
        }
        let mut left = self.clone();
        let mut terms = Vec::new();
        while !left.parts.is_empty() {
            let rounded = left.value();
            terms.push(rounded);
            left.add(-rounded);
        }
        terms
    }

    /// The sum of `terms`.
    pub fn from_terms(terms: &[f64]) -> ExactSum {
        let mut sum = ExactSum::new();
        for &x in terms {
            sum.add(x);
        }
        sum
    }
}

impl PartialEq for ExactSum {
    fn eq(&self, other: &ExactSum) -> bool {
        let bits =
            |sum: &ExactSum| -> Vec<u64> { sum.terms().iter().map(|x| x.to_bits()).collect() };
        bits(self) == bits(other)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A small generator of reproducible test values (xorshift).
    struct Draws(u64);

    impl Draws {
        fn next(&mut self) -> u64 {
            self.0 ^= self.0 << 13;
            self.0 ^= self.0 >> 7;
            self.0 ^= self.0 << 17;
            self.0
        }

        /// An integer multiple of 2⁻⁶⁰ with a magnitude below 2⁶⁰ (spread
        /// over many exponents), and the multiple as an integer.
        fn dyadic(&mut self) -> (f64, i128) {
            let bits = 1 + self.next() % 50;
            let mantissa = (self.next() >> (64 - bits)) as i128;
            let shift = (self.next() % 70) as i32;
            let signed = if self.next() % 2 == 0 {
                mantissa
            } else {
                -mantissa
            };
            // signed · 2^(shift − 60): exact in f64 (≤ 50 bits) and in i128
            // as a multiple of 2⁻⁶⁰.
            let x = signed as f64 * 2f64.powi(shift - 60);
            (x, signed << shift)
        }
    }

    fn sum_of(terms: &[f64]) -> ExactSum {
        ExactSum::from_terms(terms)
    }

    #[test]
    fn cancellation_keeps_the_small_terms() {
        assert_eq!(sum_of(&[1e100, 1.0, -1e100]).value(), 1.0);
        assert_eq!(sum_of(&[1e16, 1.0, 1.0, -1e16]).value(), 2.0);
        assert_eq!(sum_of(&[0.1; 10]).value(), 1.0);
        assert_eq!(sum_of(&[]).value(), 0.0);
        assert!(sum_of(&[-0.0]).value().is_sign_positive());
    }

    #[test]
    fn the_value_is_the_exact_sum_rounded_to_nearest_even() {
        // 1 + 2⁻⁵³ is a tie: to even (1); one more 2⁻¹⁰⁶ breaks it upwards.
        let half = 2f64.powi(-53);
        assert_eq!(sum_of(&[1.0, half]).value(), 1.0);
        assert_eq!(
            sum_of(&[1.0, half, 2f64.powi(-106)]).value(),
            1.0 + 2.0 * half
        );
        assert_eq!(sum_of(&[1.0, half, -2f64.powi(-106)]).value(), 1.0);
        // 1 + 3·2⁻⁵³ is a tie between 1 + 2⁻⁵² and 1 + 2·2⁻⁵²: to even.
        assert_eq!(sum_of(&[1.0, 3.0 * half]).value(), 1.0 + 4.0 * half);
    }

    #[test]
    fn sums_of_dyadic_numbers_match_integer_arithmetic_in_any_order() {
        let mut draws = Draws(0x9e37_79b9_7f4a_7c15);
        for _ in 0..200 {
            let count = 1 + (draws.next() % 40) as usize;
            let (mut terms, integers): (Vec<f64>, Vec<i128>) =
                (0..count).map(|_| draws.dyadic()).unzip();
            let exact: i128 = integers.iter().sum();
            // i128 → f64 rounds to nearest even; the scale is exact.
            let expected = exact as f64 * 2f64.powi(-60);
            let forward = sum_of(&terms);
            assert_eq!(forward.value(), expected, "{terms:?}");
            terms.reverse();
            let backward = sum_of(&terms);
            terms.sort_by(|a, b| a.abs().total_cmp(&b.abs()));
            let sorted = sum_of(&terms);
            assert_eq!(backward.value().to_bits(), expected.to_bits());
            assert_eq!(sorted.value().to_bits(), expected.to_bits());
            assert_eq!(forward.terms(), backward.terms());
        }
    }

    #[test]
    fn products_are_added_with_their_rounding_error() {
        // (1 + 2⁻³⁰)² = 1 + 2⁻²⁹ + 2⁻⁶⁰: the last term is lost by rounding
        // the product and kept here.
        let a = 1.0 + 2f64.powi(-30);
        let mut sum = ExactSum::new();
        sum.add_product(a, a);
        sum.add(-1.0);
        sum.add(-2f64.powi(-29));
        assert_eq!(sum.value(), 2f64.powi(-60));
        assert_eq!(
            a * a - 1.0 - 2f64.powi(-29),
            0.0,
            "plain arithmetic loses it"
        );
    }

    #[test]
    fn merged_sums_are_the_sum_of_all_terms() {
        let terms = [0.1, 1e20, 0.2, -1e20, 0.3, 1e-20];
        let (mut left, right) = (sum_of(&terms[..2]), sum_of(&terms[2..]));
        left.merge(&right);
        assert_eq!(left.value(), sum_of(&terms).value());
        assert_eq!(left.terms(), sum_of(&terms).terms());
        let terms = left.terms();
        assert_eq!(ExactSum::from_terms(&terms).terms(), terms);
        assert!(terms.len() > 1, "0.6 and what is below it: {terms:?}");
    }

    #[test]
    fn non_finite_terms_make_the_value_and_overflow_is_infinite() {
        assert!(sum_of(&[1.0, f64::NAN, 2.0]).value().is_nan());
        assert_eq!(sum_of(&[1.0, f64::INFINITY]).value(), f64::INFINITY);
        assert!(sum_of(&[f64::INFINITY, f64::NEG_INFINITY]).value().is_nan());
        assert_eq!(sum_of(&[f64::MAX, f64::MAX]).value(), f64::INFINITY);
        let mut product = ExactSum::new();
        product.add_product(f64::INFINITY, 0.0);
        assert!(product.value().is_nan());
        assert_eq!(sum_of(&[f64::NEG_INFINITY]).terms(), [f64::NEG_INFINITY]);
    }
}
