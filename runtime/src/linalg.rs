//! `L D Lᵀ` of the symmetric positive definite mass matrix, for fixed-size
//! matrices, without square roots and without allocation.
//!
//! The factorization is written for a constant `N` over fixed arrays and is
//! always inlined, so that for a model's small `N` the compiler unrolls it
//! into straight-line code. An [`LdltPattern`] says which entries of `L` can
//! be nonzero: the terms it rules out are never computed, and with a pattern
//! known at compile time (a compiled model's `const`) their code vanishes.
//! The interpreter passes the same pattern, read from its tape, so compiled
//! and interpreted models compute the same operations bit for bit.

use nalgebra::{SMatrix, SVector};

/// Which entries below the diagonal of `L` in `M = L D Lᵀ` can be nonzero:
/// those of `M` that are not zero by the model's equations, and their
/// fill-in.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct LdltPattern<const N: usize> {
    /// `lower[i][j]` for `i > j` (the rest unused).
    lower: [[bool; N]; N],
}

impl<const N: usize> LdltPattern<N> {
    /// Every entry can be nonzero.
    pub const DENSE: LdltPattern<N> = LdltPattern {
        lower: [[true; N]; N],
    };

    /// The pattern of `L` for a mass matrix whose entry `M_ij`, `i > j`, can
    /// be nonzero when `nonzero[i][j]` (the lower triangle is read): `L_ij`
    /// can be nonzero when `M_ij` can or when `L_ik` and `L_jk` can for
    /// some `k < j`.
    pub const fn from_mass(nonzero: [[bool; N]; N]) -> LdltPattern<N> {
        let mut lower = [[false; N]; N];
        let mut j = 0;
        while j < N {
            let mut i = j + 1;
            while i < N {
                let mut fill = nonzero[i][j];
                let mut k = 0;
                while k < j {
                    fill |= lower[i][k] && lower[j][k];
                    k += 1;
                }
                lower[i][j] = fill;
                i += 1;
            }
            j += 1;
        }
        LdltPattern { lower }
    }

    /// Whether `L_ij` (`i > j`) can be nonzero.
    #[inline(always)]
    pub fn nonzero(&self, i: usize, j: usize) -> bool {
        self.lower[i][j]
    }
}

/// A pattern with its envelope: each row's first column of `L` that can
/// be nonzero, which fill-in never leaves. For a banded `M` (a chain's)
/// [`solve_in_envelope`] loops over the envelope alone, at a cost of
/// `N·b²` rather than `N³`; dense and small patterns keep
/// [`solve_with_pattern`], whose full loops unroll.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Envelope<const N: usize> {
    pattern: LdltPattern<N>,
    /// The first column of row `i` of `L` that can be nonzero (`i` if none).
    first: [usize; N],
    /// One past the last row of `L` whose envelope reaches column `j`.
    end: [usize; N],
    /// The number of entries below the diagonal inside the envelope.
    size: usize,
}

impl<const N: usize> Envelope<N> {
    /// The envelope of `pattern`.
    pub const fn of(pattern: LdltPattern<N>) -> Envelope<N> {
        let (mut first, mut end, mut size) = ([0; N], [0; N], 0);
        let mut i = 0;
        while i < N {
            let mut j = 0;
            while j < i && !pattern.lower[i][j] {
                j += 1;
            }
            first[i] = j;
            size += i - j;
            i += 1;
        }
        let mut j = 0;
        while j < N {
            end[j] = j + 1;
            let mut i = j + 1;
            while i < N {
                if first[i] <= j {
                    end[j] = i + 1;
                }
                i += 1;
            }
            j += 1;
        }
        Envelope {
            pattern,
            first,
            end,
            size,
        }
    }

    /// The pattern inside.
    pub const fn pattern(&self) -> &LdltPattern<N> {
        &self.pattern
    }

    /// Whether [`solve_in_envelope`] is the faster solve: 16 coordinates or
    /// more, the envelope under half of the lower triangle.
    pub const fn is_narrow(&self) -> bool {
        N >= 16 && 4 * self.size < N * (N - 1)
    }
}

/// [`solve_with_pattern`] over the envelope of `M` alone (see [`Envelope`]).
pub fn solve_in_envelope<const N: usize>(
    mass: &SMatrix<f64, N, N>,
    forcing: &SVector<f64, N>,
    envelope: &Envelope<N>,
) -> Option<SVector<f64, N>> {
    let (l, inverse_d) = factor_in_envelope(mass, envelope)?;
    let x = substitute_in_envelope(&l, &inverse_d, forcing, envelope);
    x.iter().all(|v| v.is_finite()).then(|| SVector::from(x))
}

/// [`factor`] over the envelope.
fn factor_in_envelope<const N: usize>(
    a: &SMatrix<f64, N, N>,
    envelope: &Envelope<N>,
) -> Option<([[f64; N]; N], [f64; N])> {
    let (first, end, pattern) = (&envelope.first, &envelope.end, &envelope.pattern);
    let mut l = [[0.0; N]; N];
    let mut d = [0.0; N];
    let mut inverse_d = [0.0; N];
    // l_jk·d_k for k < j, for column j (read only where written for it).
    let mut ld = [0.0; N];
    for j in 0..N {
        let mut pivot = a[(j, j)];
        for k in first[j]..j {
            if pattern.nonzero(j, k) {
                ld[k] = l[j][k] * d[k];
                pivot -= l[j][k] * ld[k];
            }
        }
        if !(pivot.is_finite() && pivot > N as f64 * f64::EPSILON * a[(j, j)].abs()) {
            return None;
        }
        d[j] = pivot;
        inverse_d[j] = 1.0 / pivot;
        for i in j + 1..end[j] {
            if first[i] <= j && pattern.nonzero(i, j) {
                let mut v = a[(i, j)];
                for k in first[i].max(first[j])..j {
                    if pattern.nonzero(i, k) && pattern.nonzero(j, k) {
                        v -= l[i][k] * ld[k];
                    }
                }
                l[i][j] = v * inverse_d[j];
            }
        }
    }
    Some((l, inverse_d))
}

/// [`substitute`] over the envelope.
fn substitute_in_envelope<const N: usize>(
    l: &[[f64; N]; N],
    inverse_d: &[f64; N],
    b: &SVector<f64, N>,
    envelope: &Envelope<N>,
) -> [f64; N] {
    let (first, end, pattern) = (&envelope.first, &envelope.end, &envelope.pattern);
    let mut x = [0.0; N];
    for i in 0..N {
        x[i] = b[i];
        for k in first[i]..i {
            if pattern.nonzero(i, k) {
                x[i] -= l[i][k] * x[k];
            }
        }
    }
    for i in 0..N {
        x[i] *= inverse_d[i];
    }
    for i in (0..N).rev() {
        for k in i + 1..end[i] {
            if first[k] <= i && pattern.nonzero(k, i) {
                x[i] -= l[k][i] * x[k];
            }
        }
    }
    x
}

/// `A = L D Lᵀ` of a symmetric positive definite matrix, `L` unit lower
/// triangular, `D` diagonal; no square roots.
#[derive(Clone, Copy, Debug)]
pub struct Ldlt<const N: usize> {
    /// `L` below the diagonal, `l[i][j]` (the diagonal and above unused).
    l: [[f64; N]; N],
    inverse_d: [f64; N],
    pattern: LdltPattern<N>,
}

impl<const N: usize> Ldlt<N> {
    /// Factors `a`, reading its lower triangle only; `None` unless every
    /// pivot `d_j` is finite and larger than `N·ε·a_jj` (positive definite
    /// with some margin).
    pub fn new(a: &SMatrix<f64, N, N>) -> Option<Ldlt<N>> {
        Ldlt::with_pattern(a, &LdltPattern::DENSE)
    }

    /// As [`Ldlt::new`], for a matrix with the zeros of `pattern`: the
    /// entries it rules out are taken as zero and not read.
    pub fn with_pattern(a: &SMatrix<f64, N, N>, pattern: &LdltPattern<N>) -> Option<Ldlt<N>> {
        let (l, inverse_d) = factor(a, pattern)?;
        let pattern = *pattern;
        Some(Ldlt {
            l,
            inverse_d,
            pattern,
        })
    }

    /// `A⁻¹ b`.
    pub fn solve(&self, b: &SVector<f64, N>) -> SVector<f64, N> {
        SVector::from(substitute(&self.l, &self.inverse_d, b, &self.pattern))
    }
}

/// Solves `M x = f` by `L D Lᵀ` for an `M` with the zeros of `pattern`;
/// `None` unless `M` is numerically positive definite and the result is
/// finite (see [`crate::solve_mass_matrix`]).
#[inline(always)]
pub fn solve_with_pattern<const N: usize>(
    mass: &SMatrix<f64, N, N>,
    forcing: &SVector<f64, N>,
    pattern: &LdltPattern<N>,
) -> Option<SVector<f64, N>> {
    let (l, inverse_d) = factor(mass, pattern)?;
    let x = substitute(&l, &inverse_d, forcing, pattern);
    let mut finite = true;
    for v in x {
        finite &= v.is_finite();
    }
    finite.then(|| SVector::from(x))
}

/// `L` (below the diagonal) and `D⁻¹` of `a`, as [`Ldlt::new`] describes.
#[inline(always)]
fn factor<const N: usize>(
    a: &SMatrix<f64, N, N>,
    pattern: &LdltPattern<N>,
) -> Option<([[f64; N]; N], [f64; N])> {
    let mut l = [[0.0; N]; N];
    let mut d = [0.0; N];
    let mut inverse_d = [0.0; N];
    for j in 0..N {
        // l_jk·d_k for k < j, used by the whole column below.
        let mut ld = [0.0; N];
        let mut pivot = a[(j, j)];
        for k in 0..j {
            if pattern.nonzero(j, k) {
                ld[k] = l[j][k] * d[k];
                pivot -= l[j][k] * ld[k];
            }
        }
        if !(pivot.is_finite() && pivot > N as f64 * f64::EPSILON * a[(j, j)].abs()) {
            return None;
        }
        d[j] = pivot;
        inverse_d[j] = 1.0 / pivot;
        for i in j + 1..N {
            if pattern.nonzero(i, j) {
                let mut v = a[(i, j)];
                for k in 0..j {
                    if pattern.nonzero(i, k) && pattern.nonzero(j, k) {
                        v -= l[i][k] * ld[k];
                    }
                }
                l[i][j] = v * inverse_d[j];
            }
        }
    }
    Some((l, inverse_d))
}

/// `x = L⁻ᵀ D⁻¹ L⁻¹ b`: forward substitution, scaling, back substitution.
#[inline(always)]
fn substitute<const N: usize>(
    l: &[[f64; N]; N],
    inverse_d: &[f64; N],
    b: &SVector<f64, N>,
    pattern: &LdltPattern<N>,
) -> [f64; N] {
    let mut x = [0.0; N];
    for i in 0..N {
        x[i] = b[i];
        for k in 0..i {
            if pattern.nonzero(i, k) {
                x[i] -= l[i][k] * x[k];
            }
        }
    }
    for i in 0..N {
        x[i] *= inverse_d[i];
    }
    for i in (0..N).rev() {
        for k in i + 1..N {
            if pattern.nonzero(k, i) {
                x[i] -= l[k][i] * x[k];
            }
        }
    }
    x
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A symmetric, diagonally dominant `M` with the zeros of `nonzero`.
    fn matrix<const N: usize>(nonzero: &[[bool; N]; N]) -> SMatrix<f64, N, N> {
        SMatrix::from_fn(|i, j| match (i == j, nonzero[i][j]) {
            (true, _) => N as f64 + 1.0 + (i % 3) as f64,
            (false, true) => 0.7 / (1.0 + (i + j) as f64).sqrt(),
            (false, false) => 0.0,
        })
    }

    #[test]
    fn the_envelope_solve_is_the_pattern_solve_where_it_is_narrow() {
        const N: usize = 24;
        // A band of half-width 2, a chain's wall coupling (row N-1 to
        // column 0: an arrow, whose fill-in fills the last row), and a
        // diagonal.
        let band: [[bool; N]; N] =
            std::array::from_fn(|i| std::array::from_fn(|j| i.abs_diff(j) <= 2));
        let mut arrow = band;
        arrow[N - 1][0] = true;
        arrow[0][N - 1] = true;
        let diagonal: [[bool; N]; N] = std::array::from_fn(|i| std::array::from_fn(|j| i == j));
        let dense = [[true; N]; N];
        let b = SVector::<f64, N>::from_fn(|i, _| (i as f64 * 0.37).sin());
        for (name, nonzero, narrow) in [
            ("band", band, true),
            ("arrow", arrow, true),
            ("diagonal", diagonal, true),
            ("dense", dense, false),
        ] {
            let pattern = LdltPattern::from_mass(nonzero);
            let envelope = Envelope::of(pattern);
            assert_eq!(envelope.is_narrow(), narrow, "{name}");
            let m = matrix(&nonzero);
            let x = solve_in_envelope(&m, &b, &envelope).unwrap();
            let reference = m.cholesky().unwrap().solve(&b);
            assert!((x - reference).amax() < 1e-13, "{name}");
            let by_pattern = solve_with_pattern(&m, &b, &pattern).unwrap();
            assert!((x - by_pattern).amax() < 1e-14, "{name}");
        }
        let mut indefinite = matrix(&band);
        indefinite[(5, 5)] = -1.0;
        let envelope = Envelope::of(LdltPattern::from_mass(band));
        assert!(solve_in_envelope(&indefinite, &b, &envelope).is_none());
    }

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
    fn the_pattern_of_l_is_that_of_m_with_its_fill_in() {
        // M_10 = 0, M_20 ≠ 0, M_21 ≠ 0: L has the zero of M.
        let p = LdltPattern::<3>::from_mass([[true; 3], [false, true, true], [true; 3]]);
        assert!(!p.nonzero(1, 0) && p.nonzero(2, 0) && p.nonzero(2, 1));
        // An arrow pointing up: M_i0 ≠ 0 for all i, nothing else below the
        // diagonal; eliminating x0 fills in every L_ij.
        let mut arrow = [[false; 4]; 4];
        for (i, row) in arrow.iter_mut().enumerate() {
            row[0] = true;
            row[i] = true;
        }
        let filled = LdltPattern::<4>::from_mass(arrow);
        assert!((0..4).all(|i| (0..i).all(|j| filled.nonzero(i, j))));
        // Diagonal: nothing below it.
        let diagonal = LdltPattern::<3>::from_mass([[false; 3]; 3]);
        assert!((0..3).all(|i| (0..i).all(|j| !diagonal.nonzero(i, j))));
    }

    #[test]
    fn a_pattern_skips_only_zero_terms() {
        // The paper model's shape: M_10 = 0. The patterned solve gives the
        // dense solve's numbers and refuses the same matrices.
        let mass = SMatrix::<f64, 3, 3>::new(
            1168.0, 0.0, 312.5, 0.0, 2400.0, -901.25, 312.5, -901.25, 1063.0,
        );
        let pattern = LdltPattern::from_mass([[true; 3], [false, true, true], [true; 3]]);
        let f = SVector::<f64, 3>::new(-2.5e4, 1.25e3, 7.0);
        let dense = solve_with_pattern(&mass, &f, &LdltPattern::DENSE).unwrap();
        assert_eq!(solve_with_pattern(&mass, &f, &pattern).unwrap(), dense);
        assert!((mass * dense - f).amax() < 1e-12 * f.amax());
        let mut indefinite = mass;
        indefinite[(2, 2)] = 1.0;
        assert!(solve_with_pattern(&indefinite, &f, &pattern).is_none());
        assert!(solve_with_pattern(&indefinite, &f, &LdltPattern::DENSE).is_none());
        let infinite = SVector::<f64, 3>::new(f64::INFINITY, 0.0, 0.0);
        assert!(solve_with_pattern(&mass, &infinite, &pattern).is_none());
    }
}
