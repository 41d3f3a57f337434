//! The modes of a model with constraints: those of its motion on the
//! constraints.
//!
//! A model with `m` constraints moves on the manifold `g(q, t) = 0`,
//! `G q̇ + g_t = 0` of the phase space, of dimension `2(n − m)`. Its state
//! matrix `A` (of the constrained accelerations, without stabilization) has
//! `2m` further eigenvalues along the directions that leave the manifold —
//! zero, since nothing pulls a violated constraint back — which are no
//! motions of the mechanism. At an equilibrium the manifold's tangent space
//! `T` (the null space of the constraints' phase-space Jacobian
//! `[[G, 0], [∂ġ/∂q, G]]`, `ġ = G q̇ + g_t`) is invariant under `A`, and the modes are
//! the eigenvalues of `A` on it: those of `Tᵀ A T` for an orthonormal basis
//! `T`. (At a state in motion, the same projection.)

use super::derivative;
use crate::fault::Fault;
use crate::ode::PhaseState;
use crate::simulate::CrashProblem;
use crate::simulate::constrained::values;
use lagrangian_runtime::LagrangianSystem;
use nalgebra::{DMatrix, SVector};

/// `Tᵀ A T`, `A` restricted to the tangent space of the constraints at `y`.
pub fn restricted<const N: usize, S: LagrangianSystem<N>>(
    problem: &CrashProblem<N, S>,
    y: &PhaseState<N>,
    a: &DMatrix<f64>,
) -> Result<DMatrix<f64>, Fault> {
    let basis = tangent_basis(problem, y)?;
    Ok(basis.transpose() * a * &basis)
}

/// An orthonormal basis (`2n × 2(n − m)`) of the null space of the
/// constraints' phase-space Jacobian at `y`: the eigenvectors of `HᵀH` of
/// its `2(n − m)` smallest eigenvalues.
fn tangent_basis<const N: usize, S: LagrangianSystem<N>>(
    problem: &CrashProblem<N, S>,
    y: &PhaseState<N>,
) -> Result<DMatrix<f64>, Fault> {
    let h = phase_jacobian(problem, y)?;
    let m = h.nrows() / 2;
    let eigen = (h.transpose() * &h).symmetric_eigen();
    let mut order: Vec<usize> = (0..2 * N).collect();
    order.sort_by(|&i, &j| eigen.eigenvalues[i].total_cmp(&eigen.eigenvalues[j]));
    let columns: Vec<_> = (order.iter().take(2 * (N - m)))
        .map(|&k| eigen.eigenvectors.column(k).into_owned())
        .collect();
    Ok(DMatrix::from_columns(&columns))
}

/// `H = [[G, 0], [∂ġ/∂q, G]]` (`2m × 2n`), the Jacobian of
/// `(g, ġ = G q̇ + g_t)` in `(q, q̇)`; `∂ġ/∂q` by central differences.
fn phase_jacobian<const N: usize, S: LagrangianSystem<N>>(
    problem: &CrashProblem<N, S>,
    y: &PhaseState<N>,
) -> Result<DMatrix<f64>, Fault> {
    let (system, inputs) = (problem.system, &problem.inputs);
    let at = values(system, 0.0, &y.q, &y.v, inputs);
    let m = at.layout.m;
    let mut h = DMatrix::zeros(2 * m, 2 * N);
    for k in 0..m {
        for (j, g) in at.jacobian_row(k).iter().enumerate() {
            h[(k, j)] = *g;
            h[(m + k, N + j)] = *g;
        }
    }
    for j in 0..N {
        for k in 0..m {
            let row = |step: f64| -> Result<SVector<f64, 1>, Fault> {
                let mut q = y.q;
                q[j] += step;
                let shifted = values(system, 0.0, &q, &y.v, inputs);
                Ok(SVector::from([shifted.rate(y.v.as_slice())[k]]))
            };
            h[(m + k, j)] = derivative(row, y.q[j])?[0];
        }
    }
    Ok(h)
}
