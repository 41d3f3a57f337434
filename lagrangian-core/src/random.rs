//! A small deterministic random-number generator for sample states.
//!
//! The audit's residuals, its numerical identity test and the tests that
//! compare the optimized program with the expressions need random states that
//! are the same on every run and every platform: a committed report must not
//! change unless the model does. [`Lcg`] is Knuth's MMIX linear congruential
//! generator (modulus 2⁶⁴), whose top 53 bits give a uniform `f64`.

/// The multiplier of Knuth's MMIX linear congruential generator.
const MULTIPLIER: u64 = 6364136223846793005;
/// Its increment.
const INCREMENT: u64 = 1442695040888963407;

/// A seeded 64-bit linear congruential generator; the same seed gives the
/// same sequence everywhere.
#[derive(Clone, Debug)]
pub struct Lcg {
    state: u64,
}

impl Lcg {
    /// A generator whose first step starts from `seed`.
    pub const fn new(seed: u64) -> Lcg {
        Lcg { state: seed }
    }

    /// The next value, uniform in `[0, 1)`: the state's top 53 bits over 2⁵³.
    pub fn unit(&mut self) -> f64 {
        self.state = self.state.wrapping_mul(MULTIPLIER).wrapping_add(INCREMENT);
        (self.state >> 11) as f64 / (1u64 << 53) as f64
    }

    /// The next value, uniform in `[low, high)`: `low + (high − low)·u` for
    /// `u` = [`Lcg::unit`].
    pub fn uniform(&mut self, low: f64, high: f64) -> f64 {
        low + (high - low) * self.unit()
    }

    /// The next value, uniform in `[-1, 1)`.
    pub fn symmetric(&mut self) -> f64 {
        self.uniform(-1.0, 1.0)
    }
}

#[cfg(test)]
mod tests {
    use super::Lcg;

    /// The audit's seed: values computed independently (Python integers),
    /// which pin the sequence the committed audit reports were made with.
    #[test]
    fn the_sequence_is_the_mmix_recurrence() {
        let mut lcg = Lcg::new(0x5eed);
        assert_eq!(lcg.unit(), 0.935747835263558);
        assert_eq!(lcg.unit(), 0.830394305223855);
        assert_eq!(lcg.unit(), 0.4248929121530529);
    }

    #[test]
    fn symmetric_values_are_twice_the_unit_values_less_one() {
        let (mut a, mut b) = (Lcg::new(42), Lcg::new(42));
        for _ in 0..1000 {
            let (s, u) = (a.symmetric(), b.unit());
            assert_eq!(s.to_bits(), (u * 2.0 - 1.0).to_bits());
            assert!((-1.0..1.0).contains(&s));
        }
    }
}
