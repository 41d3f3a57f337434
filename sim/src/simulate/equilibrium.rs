//! Static equilibrium before an impact: the chosen coordinates settle where
//! the forcing vanishes at rest, `f_i(q, 0, t) = 0`, the others held fixed.
//!
//! With constraints `g(q, t) = 0` the equilibrium lies on them and the
//! constraint forces `Gᵀλ` hold it there: Newton's method solves
//! `f_i(q, 0, t) + (Gᵀλ)_i = 0` for the free coordinates `i` together with
//! `g(q, t) = 0`, in the free coordinates and the multipliers `λ`.

use super::{CrashProblem, SimulationError, constrained};
use crate::ode::SolverError;
use lagrangian_runtime::LagrangianSystem;
use nalgebra::{DMatrix, DVector, SVector};

/// Solves `f_i(q, 0, t) = 0` for the coordinates `free` by Newton's method
/// with central-difference Jacobian and step halving; on the constraints,
/// with their forces, for a model with constraints (module docs).
pub fn static_equilibrium<const N: usize, S: LagrangianSystem<N>>(
    problem: &CrashProblem<N, S>,
    t: f64,
    q: SVector<f64, N>,
    free: &[usize],
) -> Result<SVector<f64, N>, SimulationError> {
    let m = problem.system.constraint_count();
    let mut x = DVector::zeros(free.len() + m);
    for (k, &i) in free.iter().enumerate() {
        x[k] = q[i];
    }
    let equations = Equations {
        problem,
        t,
        q,
        free,
    };
    equations.start_multipliers(&mut x);
    let x = newton(&equations, x)?;
    Ok(equations.coordinates(&x))
}

/// The equilibrium's equations in the unknowns `x = (q_free, λ)`.
struct Equations<'a, 'p, const N: usize, S: LagrangianSystem<N>> {
    problem: &'a CrashProblem<'p, N, S>,
    t: f64,
    /// The coordinates held (and the start of the free ones).
    q: SVector<f64, N>,
    free: &'a [usize],
}

impl<const N: usize, S: LagrangianSystem<N>> Equations<'_, '_, N, S> {
    /// `q` with the free coordinates of `x`.
    fn coordinates(&self, x: &DVector<f64>) -> SVector<f64, N> {
        let mut q = self.q;
        for (k, &i) in self.free.iter().enumerate() {
            q[i] = x[k];
        }
        q
    }

    /// `[f_free + (Gᵀλ)_free, g]` at `x` (`f_free` without constraints).
    fn residual(&self, x: &DVector<f64>) -> Result<DVector<f64>, SimulationError> {
        let (problem, t) = (self.problem, self.t);
        let q = self.coordinates(x);
        let rest = SVector::<f64, N>::zeros();
        let f = problem.system.forcing(t, &q, &rest, &problem.inputs);
        if let Some(fault) = problem.inputs.take_failure() {
            return Err(SolverError::Rhs { t, error: fault }.into());
        }
        let n = self.free.len();
        let mut r = DVector::zeros(x.len());
        for (j, &i) in self.free.iter().enumerate() {
            r[j] = f[i];
        }
        if x.len() > n {
            let values = constrained::values(problem.system, t, &q, &rest, &problem.inputs);
            for (k, lambda) in x.iter().skip(n).enumerate() {
                let row = values.jacobian_row(k);
                for (j, &i) in self.free.iter().enumerate() {
                    r[j] += row[i] * lambda;
                }
                r[n + k] = values.residual()[k];
            }
        }
        if r.iter().all(|x| x.is_finite()) {
            Ok(r)
        } else {
            Err(SimulationError::Equilibrium(format!(
                "the forcing is not finite at q = {:?}",
                q.as_slice()
            )))
        }
    }

    /// `λ` of `x` that balances the forcing best at the start, by least
    /// squares (`G_free G_freeᵀ λ = −G_free f_free`): from `λ = 0` the
    /// Jacobian lacks the constraint forces' stiffness and can be singular
    /// (a point mass on a rod has no other).
    fn start_multipliers(&self, x: &mut DVector<f64>) {
        let n = self.free.len();
        let m = x.len() - n;
        if m == 0 {
            return;
        }
        let Ok(r) = self.residual(x) else { return };
        let q = self.coordinates(x);
        let rest = SVector::<f64, N>::zeros();
        let (problem, t) = (self.problem, self.t);
        let values = constrained::values(problem.system, t, &q, &rest, &problem.inputs);
        let g = DMatrix::from_fn(m, n, |k, j| values.jacobian_row(k)[self.free[j]]);
        let forcing = r.rows(0, n).into_owned();
        if let Some(lambda) = (&g * g.transpose()).lu().solve(&(-(&g * forcing))) {
            x.rows_mut(n, m).copy_from(&lambda);
        }
    }

    /// `∂r/∂x`: central differences in the free coordinates; in `λ`, the
    /// rows of `G` exactly (the residual is linear in `λ`).
    fn jacobian(&self, x: &DVector<f64>) -> Result<DMatrix<f64>, SimulationError> {
        let n = self.free.len();
        let mut jacobian = DMatrix::zeros(x.len(), x.len());
        for column in 0..n {
            let h = 1e-6 * x[column].abs().max(1e-2);
            let (mut plus, mut minus) = (x.clone(), x.clone());
            plus[column] += h;
            minus[column] -= h;
            let derivative = (self.residual(&plus)? - self.residual(&minus)?) / (2.0 * h);
            jacobian.set_column(column, &derivative);
        }
        if x.len() > n {
            let (problem, t) = (self.problem, self.t);
            let q = self.coordinates(x);
            let rest = SVector::<f64, N>::zeros();
            let values = constrained::values(problem.system, t, &q, &rest, &problem.inputs);
            for k in 0..x.len() - n {
                for (j, &i) in self.free.iter().enumerate() {
                    jacobian[(j, n + k)] = values.jacobian_row(k)[i];
                }
            }
        }
        Ok(jacobian)
    }
}

/// Newton's method with step halving from `x`, converged when the largest
/// residual is below `10⁻¹⁰` of the first's (or of 1).
fn newton<const N: usize, S: LagrangianSystem<N>>(
    equations: &Equations<N, S>,
    mut x: DVector<f64>,
) -> Result<DVector<f64>, SimulationError> {
    let at = |x: &DVector<f64>| format!("{:?}", equations.coordinates(x).as_slice());
    let mut r = equations.residual(&x)?;
    let scale = r.amax().max(1.0);
    for _ in 0..50 {
        if r.amax() <= 1e-10 * scale {
            return Ok(x);
        }
        let jacobian = equations.jacobian(&x)?;
        let Some(step) = jacobian.lu().solve(&(-&r)) else {
            return Err(SimulationError::Equilibrium(format!(
                "the stiffness matrix of the free coordinates is singular at q = {}{}",
                at(&x),
                match x.len() > equations.free.len() {
                    true =>
                        " (with the constraints: check that the coordinates they tie \
                             are free, and not held)",
                    false => "",
                }
            )));
        };
        let mut lambda = 1.0;
        loop {
            let trial = &x + lambda * &step;
            let r_trial = equations.residual(&trial)?;
            if r_trial.amax() < r.amax() || lambda < 1e-6 {
                x = trial;
                r = r_trial;
                break;
            }
            lambda *= 0.5;
        }
    }
    Err(SimulationError::Equilibrium(format!(
        "Newton's method did not converge in 50 iterations: residual {:.3e} at q = {}",
        r.amax(),
        at(&x)
    )))
}
