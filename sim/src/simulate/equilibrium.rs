//! Static equilibrium before an impact: the chosen coordinates settle where
//! the forcing vanishes at rest, `f_i(q, 0, t) = 0`, the others held fixed.

use super::{CrashProblem, SimulationError};
use crate::ode::SolverError;
use lagrangian_model::LagrangianSystem;
use nalgebra::{DMatrix, DVector, SVector};

/// Solves `f_i(q, 0, t) = 0` for the coordinates `free` by Newton's method
/// with central-difference Jacobian and step halving.
pub fn static_equilibrium<const N: usize, S: LagrangianSystem<N>>(
    problem: &CrashProblem<N, S>,
    t: f64,
    mut q: SVector<f64, N>,
    free: &[usize],
) -> Result<SVector<f64, N>, SimulationError> {
    let rest = SVector::<f64, N>::zeros();
    let residual = |q: &SVector<f64, N>| -> Result<DVector<f64>, SimulationError> {
        let f = problem.system.forcing(t, q, &rest, &problem.inputs);
        if let Some(fault) = problem.inputs.take_failure() {
            return Err(SolverError::Rhs { t, error: fault }.into());
        }
        let r = DVector::from_iterator(free.len(), free.iter().map(|&i| f[i]));
        if r.iter().all(|x| x.is_finite()) {
            Ok(r)
        } else {
            Err(SimulationError::Equilibrium(format!(
                "the forcing is not finite at q = {:?}",
                q.as_slice()
            )))
        }
    };
    let mut r = residual(&q)?;
    let scale = r.amax().max(1.0);
    for _ in 0..50 {
        if r.amax() <= 1e-10 * scale {
            return Ok(q);
        }
        let mut jacobian = DMatrix::zeros(free.len(), free.len());
        for (column, &i) in free.iter().enumerate() {
            let h = 1e-6 * q[i].abs().max(1e-2);
            let (mut plus, mut minus) = (q, q);
            plus[i] += h;
            minus[i] -= h;
            let derivative = (residual(&plus)? - residual(&minus)?) / (2.0 * h);
            jacobian.set_column(column, &derivative);
        }
        let Some(step) = jacobian.lu().solve(&(-&r)) else {
            return Err(SimulationError::Equilibrium(format!(
                "the stiffness matrix of the free coordinates is singular at q = {:?}",
                q.as_slice()
            )));
        };
        let mut lambda = 1.0;
        loop {
            let mut trial = q;
            for (k, &i) in free.iter().enumerate() {
                trial[i] += lambda * step[k];
            }
            let r_trial = residual(&trial)?;
            if r_trial.amax() < r.amax() || lambda < 1e-6 {
                q = trial;
                r = r_trial;
                break;
            }
            lambda *= 0.5;
        }
    }
    Err(SimulationError::Equilibrium(format!(
        "Newton's method did not converge in 50 iterations: residual {:.3e} at q = {:?}",
        r.amax(),
        q.as_slice()
    )))
}
