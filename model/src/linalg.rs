//! Factorizations of small fixed-size matrices, without allocation: `L D Lᵀ`
//! for the symmetric positive definite mass matrix (a few times faster than
//! nalgebra's generic Cholesky at N = 3) and LU with partial pivoting as the
//! fallback (nalgebra's LU needs type-level dimensions that generic const `N`
//! code cannot name).

use nalgebra::{SMatrix, SVector};

/// `P A = L U`, stored in one matrix with the row permutation.
#[derive(Clone, Copy, Debug)]
pub struct Lu<const N: usize> {
    lu: SMatrix<f64, N, N>,
    rows: [usize; N],
}

impl<const N: usize> Lu<N> {
    /// Factors `a`; `None` when a pivot is (numerically) zero or not finite.
    pub fn new(mut a: SMatrix<f64, N, N>) -> Option<Lu<N>> {
        let scale = a.amax();
        if !scale.is_finite() {
            return None;
        }
        let mut rows = [0usize; N];
        for (i, r) in rows.iter_mut().enumerate() {
            *r = i;
        }
        for k in 0..N {
            let mut p = k;
            for i in k + 1..N {
                if a[(i, k)].abs() > a[(p, k)].abs() {
                    p = i;
                }
            }
            let pivot = a[(p, k)].abs();
            if pivot.is_nan() || pivot <= f64::EPSILON * scale * N as f64 {
                return None;
            }
            a.swap_rows(k, p);
            rows.swap(k, p);
            for i in k + 1..N {
                let factor = a[(i, k)] / a[(k, k)];
                a[(i, k)] = factor;
                for j in k + 1..N {
                    a[(i, j)] -= factor * a[(k, j)];
                }
            }
        }
        Some(Lu { lu: a, rows })
    }

    /// `A⁻¹ b`.
    pub fn solve(&self, b: &SVector<f64, N>) -> SVector<f64, N> {
        let mut x = SVector::<f64, N>::from_fn(|i, _| b[self.rows[i]]);
        for i in 0..N {
            for j in 0..i {
                x[i] -= self.lu[(i, j)] * x[j];
            }
        }
        for i in (0..N).rev() {
            for j in i + 1..N {
                x[i] -= self.lu[(i, j)] * x[j];
            }
            x[i] /= self.lu[(i, i)];
        }
        x
    }
}

/// `A = L D Lᵀ` of a symmetric positive definite matrix, `L` unit lower
/// triangular, `D` diagonal; no square roots.
#[derive(Clone, Copy, Debug)]
pub struct Ldlt<const N: usize> {
    /// `L` below the diagonal (the diagonal and above are unused).
    l: SMatrix<f64, N, N>,
    inverse_d: [f64; N],
}

impl<const N: usize> Ldlt<N> {
    /// Factors `a`, reading its lower triangle only; `None` unless every
    /// pivot `d_j` is finite and larger than `N·ε·a_jj` (positive definite
    /// with some margin).
    pub fn new(a: &SMatrix<f64, N, N>) -> Option<Ldlt<N>> {
        let mut l = SMatrix::<f64, N, N>::zeros();
        let mut d = [0.0; N];
        let mut inverse_d = [0.0; N];
        for j in 0..N {
            // l_jk·d_k for k < j, used by the whole column below.
            let mut ld = [0.0; N];
            let mut pivot = a[(j, j)];
            for k in 0..j {
                ld[k] = l[(j, k)] * d[k];
                pivot -= l[(j, k)] * ld[k];
            }
            if !(pivot.is_finite() && pivot > N as f64 * f64::EPSILON * a[(j, j)].abs()) {
                return None;
            }
            d[j] = pivot;
            inverse_d[j] = 1.0 / pivot;
            for i in j + 1..N {
                let mut v = a[(i, j)];
                for k in 0..j {
                    v -= l[(i, k)] * ld[k];
                }
                l[(i, j)] = v * inverse_d[j];
            }
        }
        Some(Ldlt { l, inverse_d })
    }

    /// `A⁻¹ b`.
    pub fn solve(&self, b: &SVector<f64, N>) -> SVector<f64, N> {
        let mut x = *b;
        for i in 0..N {
            for k in 0..i {
                x[i] -= self.l[(i, k)] * x[k];
            }
        }
        for i in 0..N {
            x[i] *= self.inverse_d[i];
        }
        for i in (0..N).rev() {
            for k in i + 1..N {
                x[i] -= self.l[(k, i)] * x[k];
            }
        }
        x
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ldlt_solves_spd_systems_and_refuses_indefinite_ones() {
        // A = Bᵀ B + I for a fixed B is SPD.
        let b = SMatrix::<f64, 4, 4>::from_fn(|i, j| ((i * 7 + j * 3) % 5) as f64 - 2.0);
        let a = b.transpose() * b + SMatrix::<f64, 4, 4>::identity();
        let rhs = SVector::<f64, 4>::new(1.0, -2.0, 0.5, 3.0);
        let x = Ldlt::new(&a).unwrap().solve(&rhs);
        assert!((a * x - rhs).amax() < 1e-12 * a.amax() * x.amax());
        let reference = a.cholesky().unwrap().solve(&rhs);
        assert!((x - reference).amax() < 1e-12 * reference.amax());
        // Indefinite, singular, not finite.
        assert!(Ldlt::new(&SMatrix::<f64, 2, 2>::new(1.0, 2.0, 2.0, 1.0)).is_none());
        assert!(Ldlt::new(&SMatrix::<f64, 2, 2>::new(1.0, 1.0, 1.0, 1.0)).is_none());
        assert!(Ldlt::new(&SMatrix::<f64, 2, 2>::new(f64::NAN, 0.0, 0.0, 1.0)).is_none());
    }

    #[test]
    fn solves_a_system_that_needs_pivoting() {
        let a = SMatrix::<f64, 3, 3>::new(0.0, 2.0, 1.0, 1.0, 1.0, 0.0, 3.0, 0.0, 1.0);
        let b = SVector::<f64, 3>::new(3.0, 2.0, 4.0);
        let x = Lu::new(a).unwrap().solve(&b);
        assert!((a * x - b).amax() < 1e-14);
        assert!(Lu::new(SMatrix::<f64, 2, 2>::new(1.0, 2.0, 2.0, 4.0)).is_none());
    }
}
