//! The equations of motion of a model with holonomic constraints
//! `g(q, t) = 0`: `M q̈ = f + Gᵀλ`, `G q̈ = γ`, solved by the Schur complement
//! on the `L D Lᵀ` of `M`.
//!
//! `λ` is the vector of Lagrange multipliers, one per constraint, and
//! `Gᵀλ` the generalized force of the constraints, added to `f`: a positive
//! `λ_k` pushes the coordinates towards increasing `g_k`. With
//! `q̈ = M⁻¹(f + Gᵀλ)`, `G q̈ = γ` gives
//!
//! ```text
//! (G M⁻¹ Gᵀ) λ = γ − G M⁻¹ f
//! ```
//!
//! `G M⁻¹ Gᵀ` is positive definite when the rows of `G` are independent;
//! a constraint whose row depends on the rows before it is redundant (or the
//! constraints are locally degenerate there), which the solve reports by
//! constraint index.

use crate::layout::ConstraintLayout;
use crate::linalg::Ldlt;
use nalgebra::{SMatrix, SVector};

/// The outputs of a model's constraint routine at one state, split by term
/// ([`ConstraintLayout`]).
#[derive(Clone, Debug, PartialEq)]
pub struct ConstraintValues {
    /// Where each term is in `values`.
    pub layout: ConstraintLayout,
    /// `g`, `g_t`, `G` (row-major), `γ`, concatenated.
    pub values: Vec<f64>,
}

impl ConstraintValues {
    /// Room for `m` constraints on `n` coordinates, zeroed.
    pub fn new(m: usize, n: usize) -> ConstraintValues {
        let layout = ConstraintLayout { m, n };
        ConstraintValues {
            layout,
            values: vec![0.0; layout.len()],
        }
    }

    /// `g`, the residuals.
    #[inline]
    pub fn residual(&self) -> &[f64] {
        &self.values[self.layout.residual()]
    }

    /// `∂g/∂t`.
    #[inline]
    pub fn time_rate(&self) -> &[f64] {
        &self.values[self.layout.time_rate()]
    }

    /// `G`, row-major `m × n`.
    #[inline]
    pub fn jacobian(&self) -> &[f64] {
        &self.values[self.layout.jacobian()]
    }

    /// Row `k` of `G`.
    #[inline]
    pub fn jacobian_row(&self, k: usize) -> &[f64] {
        let n = self.layout.n;
        &self.jacobian()[k * n..(k + 1) * n]
    }

    /// `γ`.
    #[inline]
    pub fn acceleration(&self) -> &[f64] {
        &self.values[self.layout.acceleration()]
    }

    /// `ġ = G q̇ + g_t`, the rate of each residual at the velocities `qd`.
    pub fn rate(&self, qd: &[f64]) -> Vec<f64> {
        (0..self.layout.m)
            .map(|k| dot(self.jacobian_row(k), qd) + self.time_rate()[k])
            .collect()
    }
}

/// Baumgarte's stabilization: the solve asks `g̈ + 2α ġ + β² g = 0` of the
/// constraints instead of `g̈ = 0`, so that a residual left by the
/// integration decays (critically damped when `α = β`) instead of growing.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Baumgarte {
    /// `α` [1/s], the damping of the residual's rate.
    pub alpha: f64,
    /// `β` [1/s], the stiffness of the residual.
    pub beta: f64,
}

impl Baumgarte {
    /// No stabilization: `g̈ = 0` exactly.
    pub const NONE: Baumgarte = Baumgarte {
        alpha: 0.0,
        beta: 0.0,
    };

    /// `γ − 2α ġ − β² g` at the velocities `qd`.
    pub fn acceleration(&self, values: &ConstraintValues, qd: &[f64]) -> Vec<f64> {
        let mut gamma = vec![0.0; values.layout.m];
        self.acceleration_into(values, qd, &mut gamma);
        gamma
    }

    /// [`Baumgarte::acceleration`] into `gamma` (`m` long), allocating
    /// nothing.
    pub fn acceleration_into(&self, values: &ConstraintValues, qd: &[f64], gamma: &mut [f64]) {
        for (k, gamma) in gamma.iter_mut().enumerate() {
            let rate = dot(values.jacobian_row(k), qd) + values.time_rate()[k];
            *gamma = values.acceleration()[k]
                - 2.0 * self.alpha * rate
                - self.beta * self.beta * values.residual()[k];
        }
    }
}

/// Why the constrained solve failed.
#[derive(Clone, Debug, PartialEq)]
pub enum ConstrainedSolveError {
    /// `M` is not numerically positive definite.
    MassMatrix,
    /// These constraints (indices, in order) depend on the ones declared
    /// before them: `G M⁻¹ Gᵀ` is singular.
    Redundant(Vec<usize>),
}

/// `M`'s factorization, the one place the constrained solve factors `M`.
pub fn factor_mass_matrix<const N: usize>(mass: &SMatrix<f64, N, N>) -> Option<Ldlt<N>> {
    Ldlt::new(mass)
}

/// The buffers of the constrained solve of `m` constraints on `N`
/// coordinates, kept between solves so that a solve allocates nothing.
#[derive(Clone, Debug)]
pub struct SolveWorkspace<const N: usize> {
    m: usize,
    /// `M⁻¹ G_kᵀ`, one per constraint.
    rows: Vec<SVector<f64, N>>,
    /// `G M⁻¹ Gᵀ`, row-major `m × m`.
    schur: Vec<f64>,
    /// Its Cholesky factor, row-major.
    factor: Vec<f64>,
    /// `γ − G M⁻¹ f`.
    rhs: Vec<f64>,
}

impl<const N: usize> SolveWorkspace<N> {
    /// Room for `m` constraints.
    pub fn new(m: usize) -> SolveWorkspace<N> {
        SolveWorkspace {
            m,
            rows: vec![SVector::zeros(); m],
            schur: vec![0.0; m * m],
            factor: vec![0.0; m * m],
            rhs: vec![0.0; m],
        }
    }
}

/// `(q̈, λ)` with `M q̈ = f + Gᵀλ` and `G q̈ = gamma` (`G`, `m × N`
/// row-major, from `values`; `gamma` the right-hand side, e.g. from
/// [`Baumgarte::acceleration`]).
pub fn solve_constrained<const N: usize>(
    mass: &SMatrix<f64, N, N>,
    forcing: &SVector<f64, N>,
    values: &ConstraintValues,
    gamma: &[f64],
) -> Result<(SVector<f64, N>, Vec<f64>), ConstrainedSolveError> {
    let mut workspace = SolveWorkspace::new(values.layout.m);
    let mut lambda = vec![0.0; values.layout.m];
    let qdd = solve_constrained_in(mass, forcing, values, gamma, &mut workspace, &mut lambda)?;
    Ok((qdd, lambda))
}

/// [`solve_constrained`] with `λ` written into `lambda` (`m` long) and the
/// buffers of `workspace` (made for `m` constraints): allocates nothing
/// unless the solve fails.
pub fn solve_constrained_in<const N: usize>(
    mass: &SMatrix<f64, N, N>,
    forcing: &SVector<f64, N>,
    values: &ConstraintValues,
    gamma: &[f64],
    workspace: &mut SolveWorkspace<N>,
    lambda: &mut [f64],
) -> Result<SVector<f64, N>, ConstrainedSolveError> {
    let m = values.layout.m;
    debug_assert_eq!(
        workspace.m, m,
        "a workspace made for another number of constraints"
    );
    let ldlt = factor_mass_matrix(mass).ok_or(ConstrainedSolveError::MassMatrix)?;
    let free = ldlt.solve(forcing);
    for (k, row) in workspace.rows.iter_mut().enumerate() {
        *row = ldlt.solve(&SVector::from_column_slice(values.jacobian_row(k)));
    }
    for (k, gamma) in gamma.iter().enumerate().take(m) {
        let g = values.jacobian_row(k);
        for (l, row) in workspace.rows.iter().enumerate() {
            workspace.schur[k * m + l] = dot(g, row.as_slice());
        }
        workspace.rhs[k] = gamma - dot(g, free.as_slice());
    }
    let (schur, factor) = (&workspace.schur, &mut workspace.factor);
    cholesky_solve_in(schur, m, &workspace.rhs, factor, lambda)
        .map_err(ConstrainedSolveError::Redundant)?;
    let mut qdd = free;
    for (row, l) in workspace.rows.iter().zip(lambda.iter()) {
        qdd += row * *l;
    }
    if qdd.iter().chain(lambda.iter()).all(|v| v.is_finite()) {
        Ok(qdd)
    } else {
        Err(ConstrainedSolveError::MassMatrix)
    }
}

/// `x` with `A x = b`, `A` symmetric `m × m` row-major, by Cholesky; `Err`
/// with the rows whose pivot vanishes (relative to the row's diagonal):
/// each depends on the rows before it.
pub fn solve_positive_definite(a: &[f64], m: usize, b: &[f64]) -> Result<Vec<f64>, Vec<usize>> {
    let mut factor = vec![0.0; m * m];
    let mut x = vec![0.0; m];
    cholesky_solve_in(a, m, b, &mut factor, &mut x)?;
    Ok(x)
}

/// [`solve_positive_definite`] into `x`, with `factor` (`m × m`) for the
/// Cholesky factor: allocates nothing unless rows are dependent.
fn cholesky_solve_in(
    a: &[f64],
    m: usize,
    b: &[f64],
    l: &mut [f64],
    x: &mut [f64],
) -> Result<(), Vec<usize>> {
    l.fill(0.0);
    let mut dependent = Vec::new();
    for j in 0..m {
        let mut d = a[j * m + j];
        for k in 0..j {
            d -= l[j * m + k] * l[j * m + k];
        }
        if !(d.is_finite() && d > 1e-10 * a[j * m + j].abs()) {
            dependent.push(j);
            continue;
        }
        let d = d.sqrt();
        l[j * m + j] = d;
        for i in j + 1..m {
            let mut s = a[i * m + j];
            for k in 0..j {
                s -= l[i * m + k] * l[j * m + k];
            }
            l[i * m + j] = s / d;
        }
    }
    if !dependent.is_empty() {
        return Err(dependent);
    }
    x.copy_from_slice(b);
    for i in 0..m {
        for k in 0..i {
            x[i] -= l[i * m + k] * x[k];
        }
        x[i] /= l[i * m + i];
    }
    for i in (0..m).rev() {
        for k in i + 1..m {
            x[i] -= l[k * m + i] * x[k];
        }
        x[i] /= l[i * m + i];
    }
    Ok(())
}

#[inline]
fn dot(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A point mass in the plane on a circle `x² + y² = l²` at `(l, 0)`,
    /// at rest, under gravity `−m g` in `y`: it starts to fall freely
    /// (`q̈ = (0, −g)`), the rod carrying no force (`λ = 0`); moving at `v`
    /// along `y`, the rod pulls it in with `m v²/l` (`λ = −m v²/(2 l²)`
    /// for `g = x² + y² − l²`, whose gradient is `2 l` in `x`).
    #[test]
    fn a_point_on_a_circle_gets_the_centripetal_force() {
        let (mass_kg, l, gravity, v) = (2.0, 1.5, 9.81, 3.0);
        let mass = SMatrix::<f64, 2, 2>::identity() * mass_kg;
        let forcing = SVector::<f64, 2>::new(0.0, -mass_kg * gravity);
        let mut values = ConstraintValues::new(1, 2);
        values
            .values
            .copy_from_slice(&[0.0, 0.0, 2.0 * l, 0.0, -2.0 * v * v]);
        let gamma = values.acceleration().to_vec();
        let (qdd, lambda) = solve_constrained(&mass, &forcing, &values, &gamma).unwrap();
        assert!((qdd[0] + v * v / l).abs() < 1e-12, "{qdd}");
        assert!((qdd[1] + gravity).abs() < 1e-12, "{qdd}");
        assert!((lambda[0] + mass_kg * v * v / (2.0 * l * l)).abs() < 1e-12);
    }

    #[test]
    fn a_constraint_repeated_is_redundant() {
        let mass = SMatrix::<f64, 2, 2>::identity();
        let forcing = SVector::<f64, 2>::new(1.0, 2.0);
        let mut values = ConstraintValues::new(3, 2);
        // G rows: (1, 0), (0, 1), (2, 0).
        let g = [1.0, 0.0, 0.0, 1.0, 2.0, 0.0];
        values.values[values.layout.jacobian()].copy_from_slice(&g);
        let gamma = [0.0; 3];
        let error = solve_constrained(&mass, &forcing, &values, &gamma).unwrap_err();
        assert_eq!(error, ConstrainedSolveError::Redundant(vec![2]));
    }

    #[test]
    fn baumgarte_pulls_the_residual_back() {
        let mut values = ConstraintValues::new(1, 1);
        values.values.copy_from_slice(&[0.5, 0.25, 2.0, 1.0]);
        let stabilized = Baumgarte {
            alpha: 3.0,
            beta: 4.0,
        }
        .acceleration(&values, &[1.5]);
        // ġ = 2·1.5 + 0.25 = 3.25; γ − 2·3·3.25 − 16·0.5.
        assert_eq!(stabilized, vec![1.0 - 19.5 - 8.0]);
        assert_eq!(Baumgarte::NONE.acceleration(&values, &[1.5]), vec![1.0]);
    }
}
