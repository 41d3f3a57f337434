//! `L D Lᵀ` of the symmetric positive definite mass matrix, for fixed-size
//! matrices, without square roots and without allocation.

use nalgebra::{SMatrix, SVector};

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
}
