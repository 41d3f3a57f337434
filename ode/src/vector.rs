//! State vectors the integrators work on.

use super::internal::Internal;
use nalgebra::{DVector, SVector};

/// The components of a state that a reader of a dense output asks for.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Part {
    /// Every component.
    All,
    /// The motion: a mechanical state's coordinates and velocities; every
    /// component of a vector that holds nothing else.
    Motion,
}

/// A state vector: fixed-size ones live on the stack, so integrating them
/// does not allocate.
pub trait OdeVector: Clone {
    /// The number of components.
    fn len(&self) -> usize;

    /// How many of the first components control the step size: they enter
    /// the error norm. The rest are quadratures, integrated with each step
    /// but not controlling it (their error follows the solution's). All
    /// by default.
    fn controlled_len(&self) -> usize {
        self.len()
    }

    /// `true` for a vector of no components.
    fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// Component `i` (`i < len()`).
    fn get(&self, i: usize) -> f64;

    /// `self ← base + Σ_k c_k · x_k`.
    fn set_combination(&mut self, base: &Self, terms: &[(f64, &Self)]);

    /// `self ← Σ_k c_k · x_k`.
    fn set_sum(&mut self, terms: &[(f64, &Self)]);

    /// [`OdeVector::set_combination`] on the components of `part`; the
    /// others keep their values.
    fn set_part_combination(&mut self, part: Part, base: &Self, terms: &[(f64, &Self)]) {
        let _ = part;
        self.set_combination(base, terms);
    }

    /// [`OdeVector::set_sum`] on the components of `part`; the others keep
    /// their values.
    fn set_part_sum(&mut self, part: Part, terms: &[(f64, &Self)]) {
        let _ = part;
        self.set_sum(terms);
    }

    /// `true` when no component is NaN or ±∞.
    fn all_finite(&self) -> bool {
        (0..self.len()).all(|i| self.get(i).is_finite())
    }
}

impl<const D: usize> OdeVector for SVector<f64, D> {
    fn len(&self) -> usize {
        D
    }

    fn get(&self, i: usize) -> f64 {
        self[i]
    }

    fn set_combination(&mut self, base: &Self, terms: &[(f64, &Self)]) {
        *self = *base;
        for (c, x) in terms {
            self.axpy(*c, x, 1.0);
        }
    }

    fn set_sum(&mut self, terms: &[(f64, &Self)]) {
        self.fill(0.0);
        for (c, x) in terms {
            self.axpy(*c, x, 1.0);
        }
    }
}

impl OdeVector for DVector<f64> {
    fn len(&self) -> usize {
        self.nrows()
    }

    fn get(&self, i: usize) -> f64 {
        self[i]
    }

    fn set_combination(&mut self, base: &Self, terms: &[(f64, &Self)]) {
        self.copy_from(base);
        for (c, x) in terms {
            self.axpy(*c, x, 1.0);
        }
    }

    fn set_sum(&mut self, terms: &[(f64, &Self)]) {
        self.fill(0.0);
        for (c, x) in terms {
            self.axpy(*c, x, 1.0);
        }
    }
}

/// The state of a mechanical model: coordinates `q`, velocities `v = q̇`,
/// two running integrals for energy bookkeeping: `work[0] = ∫ Σ ∂D/∂q̇·q̇ dt`
/// (energy dissipated by `D`) and `work[1] = ∫ Σ Q·q̇ dt` (work of the
/// generalized forces), and the internal states `z` of the scenario's
/// components (none for most runs; see [`Internal`]). Integrating the
/// integrals with the state makes the energy balance as accurate as the
/// solution.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PhaseState<const N: usize> {
    /// Generalized coordinates, in the model's units (\[m\] or \[rad\]).
    pub q: SVector<f64, N>,
    /// Generalized velocities `q̇` ([m/s] or [rad/s]).
    pub v: SVector<f64, N>,
    /// `[dissipated, external work]` since the start of the run \[J\].
    pub work: [f64; 2],
    /// The components' internal states, in the order the problem gives
    /// them; empty when it has none, or holds them fixed.
    pub z: Internal,
}

impl<const N: usize> PhaseState<N> {
    /// The state at coordinates `q` and velocities `v`, with no work done
    /// yet and no internal states.
    pub fn new(q: SVector<f64, N>, v: SVector<f64, N>) -> Self {
        PhaseState {
            q,
            v,
            work: [0.0; 2],
            z: Internal::EMPTY,
        }
    }

    /// All zeros: at rest at `q = 0`, no work done.
    pub fn zeros() -> Self {
        PhaseState::new(SVector::zeros(), SVector::zeros())
    }
}

impl<const N: usize> OdeVector for PhaseState<N> {
    fn len(&self) -> usize {
        2 * N + 2 + self.z.len()
    }

    /// All but the quadratures of `z` (the components' dissipated
    /// energies); the two work integrals control the step as they always
    /// have.
    fn controlled_len(&self) -> usize {
        2 * N + 2 + self.z.controlled_len()
    }

    fn get(&self, i: usize) -> f64 {
        if i < N {
            self.q[i]
        } else if i < 2 * N {
            self.v[i - N]
        } else if i < 2 * N + 2 {
            self.work[i - 2 * N]
        } else {
            self.z.as_slice()[i - 2 * N - 2]
        }
    }

    /// `0·x` is 0 for a finite `x`, NaN otherwise: one sum, no branch per
    /// component.
    fn all_finite(&self) -> bool {
        let mut sum = 0.0;
        for i in 0..N {
            sum += self.q[i] * 0.0 + self.v[i] * 0.0;
        }
        for &x in self.work.iter().chain(self.z.as_slice()) {
            sum += x * 0.0;
        }
        sum == 0.0
    }

    fn set_combination(&mut self, base: &Self, terms: &[(f64, &Self)]) {
        (self.q, self.v, self.work) = (base.q, base.v, base.work);
        self.z.assign(&base.z);
        for &(c, x) in terms {
            self.add(c, x);
        }
    }

    fn set_sum(&mut self, terms: &[(f64, &Self)]) {
        (self.q, self.v, self.work) = (SVector::zeros(), SVector::zeros(), [0.0; 2]);
        self.z.assign(&Internal::EMPTY);
        for &(c, x) in terms {
            self.add(c, x);
        }
    }

    fn set_part_combination(&mut self, part: Part, base: &Self, terms: &[(f64, &Self)]) {
        match part {
            Part::All => self.set_combination(base, terms),
            Part::Motion => {
                (self.q, self.v) = (base.q, base.v);
                for &(c, x) in terms {
                    self.add_motion(c, x);
                }
            }
        }
    }

    fn set_part_sum(&mut self, part: Part, terms: &[(f64, &Self)]) {
        match part {
            Part::All => self.set_sum(terms),
            Part::Motion => {
                (self.q, self.v) = (SVector::zeros(), SVector::zeros());
                for &(c, x) in terms {
                    self.add_motion(c, x);
                }
            }
        }
    }
}

impl<const N: usize> PhaseState<N> {
    /// `self ← self + c·x`.
    #[inline]
    fn add(&mut self, c: f64, x: &Self) {
        self.add_motion(c, x);
        self.work[0] += c * x.work[0];
        self.work[1] += c * x.work[1];
        self.z.add(c, &x.z);
    }

    /// `q ← q + c·x.q`, `v ← v + c·x.v`.
    #[inline]
    fn add_motion(&mut self, c: f64, x: &Self) {
        for i in 0..N {
            self.q[i] += c * x.q[i];
            self.v[i] += c * x.v[i];
        }
    }
}

#[cfg(test)]
mod tests {
    use super::super::{Options, error_norm};
    use super::*;

    /// A state of one coordinate with internal states `z`, the last
    /// `quadratures` of them quadratures.
    fn state(value: f64, z: &[f64], quadratures: usize) -> PhaseState<1> {
        let mut internal = Internal::zeros(z.len()).unwrap();
        internal.as_mut_slice().copy_from_slice(z);
        PhaseState {
            q: SVector::from([value]),
            v: SVector::from([value]),
            work: [value; 2],
            z: internal.with_quadratures(quadratures),
        }
    }

    #[test]
    fn quadratures_stay_out_of_the_error_norm() {
        let options = Options::default();
        let y = state(1.0, &[0.5, 100.0], 1);
        let without = state(1.0, &[0.5], 0);
        // A quadrature's error, however large, changes nothing: the norm
        // is the one of the state without it, to the bit.
        let err = state(1e-7, &[1e-7, 1e3], 1);
        let err_without = state(1e-7, &[1e-7], 0);
        let norm = error_norm(&err, &y, &y, &options);
        assert_eq!(norm, error_norm(&err_without, &without, &without, &options));
        assert_eq!(y.controlled_len(), 5);
        // The same entry as a controlled state does count.
        let controlled = state(1.0, &[0.5, 100.0], 0);
        assert!(error_norm(&err, &controlled, &controlled, &options) > 10.0 * norm);
        // Combinations carry the split.
        let mut sum = PhaseState::zeros();
        sum.set_sum(&[(1.0, &y), (2.0, &err)]);
        assert_eq!(sum.controlled_len(), 5);
    }

    /// The motion alone is the whole combination's `q` and `q̇`, to the
    /// bit, and leaves the work and the internal states as they were.
    #[test]
    fn a_combination_of_the_motion_leaves_the_rest_as_it_was() {
        let (base, x, y) = (
            state(0.3, &[1.0, 2.0], 1),
            state(-1.7, &[4.0, 5.0], 1),
            state(2.9, &[7.0, 8.0], 1),
        );
        let terms = [(0.25, &x), (-1.5, &y)];
        let mut all = PhaseState::zeros();
        all.set_combination(&base, &terms);
        let before = state(9.0, &[9.0], 0);
        let mut motion = before;
        motion.set_part_combination(Part::Motion, &base, &terms);
        assert_eq!((motion.q, motion.v), (all.q, all.v));
        assert_eq!((motion.work, motion.z), (before.work, before.z));
        assert_ne!(all.work, before.work);
        let mut sum = PhaseState::zeros();
        sum.set_sum(&terms);
        let mut motion_sum = before;
        motion_sum.set_part_sum(Part::Motion, &terms);
        assert_eq!((motion_sum.q, motion_sum.v), (sum.q, sum.v));
        assert_eq!((motion_sum.work, motion_sum.z), (before.work, before.z));
        let mut every = before;
        every.set_part_sum(Part::All, &terms);
        assert_eq!(every, sum);
    }

    #[test]
    fn a_state_is_finite_when_every_component_is() {
        let finite = state(1.0e300, &[-1.0e300, 0.0], 1);
        assert!(finite.all_finite());
        for bad in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
            let mut each = vec![finite; 4];
            each[0].q[0] = bad;
            each[1].v[0] = bad;
            each[2].work[1] = bad;
            each[3].z.as_mut_slice()[1] = bad;
            for (k, y) in each.iter().enumerate() {
                assert!(!y.all_finite(), "{bad} in part {k}");
            }
        }
    }
}
