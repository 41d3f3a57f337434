//! The internal states of a run's components, carried inline in
//! [`super::PhaseState`].
//!
//! The buffer has a fixed capacity so that a state stays `Copy` and
//! integrating it does not allocate; only its first [`Internal::len`]
//! values take part in the arithmetic, so a run without internal states
//! (the usual case) computes exactly what it did before they existed. A
//! heap vector would allocate with every copy of the state, and a const
//! length would have to be known when the model is compiled, while the
//! scenario decides how many states there are.
//!
//! The last [`Internal::quadratures`] values are quadratures: integrals
//! such as a component's dissipated energy, whose rates depend on the
//! solution but which feed nothing back into it. They are integrated with
//! every step but do not control its size (they stay out of the error
//! norm): a quadrature's error follows the solution's.

/// The most internal states a run can carry.
pub const CAPACITY: usize = 32;

/// Up to [`CAPACITY`] values; those past [`Internal::len`] are zero.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Internal {
    len: usize,
    /// How many of the last values are quadratures.
    quadratures: usize,
    values: [f64; CAPACITY],
}

impl Default for Internal {
    fn default() -> Self {
        Internal::EMPTY
    }
}

impl Internal {
    /// No internal states.
    pub const EMPTY: Internal = Internal {
        len: 0,
        quadratures: 0,
        values: [0.0; CAPACITY],
    };

    /// `len` zeros, or `None` when `len` exceeds [`CAPACITY`].
    pub fn zeros(len: usize) -> Option<Internal> {
        (len <= CAPACITY).then_some(Internal {
            len,
            quadratures: 0,
            values: [0.0; CAPACITY],
        })
    }

    /// The same values, the last `count` of them (at most all) marked as
    /// quadratures.
    pub fn with_quadratures(self, count: usize) -> Internal {
        Internal {
            quadratures: count.min(self.len),
            ..self
        }
    }

    /// How many of the last values are quadratures, which do not control
    /// the step size.
    pub fn quadratures(&self) -> usize {
        self.quadratures
    }

    /// How many of the first values control the step size: all but the
    /// quadratures.
    pub fn controlled_len(&self) -> usize {
        self.len - self.quadratures
    }

    /// The number of values.
    pub fn len(&self) -> usize {
        self.len
    }

    /// `true` without values.
    pub fn is_empty(&self) -> bool {
        self.len == 0
    }

    /// The values.
    pub fn as_slice(&self) -> &[f64] {
        &self.values[..self.len]
    }

    /// The values, to change.
    pub fn as_mut_slice(&mut self) -> &mut [f64] {
        &mut self.values[..self.len]
    }

    /// `self ← other`, copying only the values in use.
    #[inline]
    pub fn assign(&mut self, other: &Internal) {
        // Element by element: the states are short, and a call of `memcpy`
        // would cost more than the copy.
        for i in 0..other.len {
            self.values[i] = other.values[i];
        }
        for i in other.len..self.len {
            self.values[i] = 0.0;
        }
        (self.len, self.quadratures) = (other.len, other.quadratures);
    }

    /// `self ← self + c·x`, taking `x`'s length (and quadratures) where it
    /// is longer.
    #[inline]
    pub(crate) fn add(&mut self, c: f64, x: &Internal) {
        if x.len > self.len {
            (self.len, self.quadratures) = (x.len, x.quadratures);
        }
        for i in 0..x.len {
            self.values[i] += c * x.values[i];
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn only_the_values_in_use_take_part() {
        let mut a = Internal::zeros(2).unwrap();
        a.as_mut_slice().copy_from_slice(&[1.0, 2.0]);
        let mut b = Internal::EMPTY;
        b.add(2.0, &a);
        assert_eq!(b.as_slice(), &[2.0, 4.0]);
        b.assign(&Internal::EMPTY);
        assert_eq!(b, Internal::EMPTY);
        assert_eq!(Internal::zeros(CAPACITY + 1), None);
    }

    #[test]
    fn quadratures_are_the_last_values_and_travel_with_them() {
        let a = Internal::zeros(3).unwrap().with_quadratures(1);
        assert_eq!((a.quadratures(), a.controlled_len()), (1, 2));
        let mut b = Internal::EMPTY;
        b.add(1.0, &a);
        assert_eq!(b.controlled_len(), 2);
        let mut c = Internal::zeros(1).unwrap();
        c.assign(&a);
        assert_eq!((c.len(), c.quadratures()), (3, 1));
        assert_eq!(
            Internal::zeros(2)
                .unwrap()
                .with_quadratures(5)
                .controlled_len(),
            0
        );
    }
}
