//! LU with partial pivoting for the Newton iteration matrix of the implicit
//! method, for fixed-size matrices and without allocation (nalgebra's LU
//! needs type-level dimensions that generic const `N` code cannot name).

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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn solves_a_system_that_needs_pivoting() {
        let a = SMatrix::<f64, 3, 3>::new(0.0, 2.0, 1.0, 1.0, 1.0, 0.0, 3.0, 0.0, 1.0);
        let b = SVector::<f64, 3>::new(3.0, 2.0, 4.0);
        let x = Lu::new(a).unwrap().solve(&b);
        assert!((a * x - b).amax() < 1e-14);
        assert!(Lu::new(SMatrix::<f64, 2, 2>::new(1.0, 2.0, 2.0, 4.0)).is_none());
    }
}
