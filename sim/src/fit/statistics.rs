//! Standard errors and correlations of fitted parameters from the Jacobian
//! at the optimum: `Cov_u = σ² (JᵀJ)⁺` with `σ² = Σr² / (m − n)`, carried to
//! the physical parameters through the transforms, `Cov_p = D Cov_u Dᵀ`,
//! `D = ∂p/∂u`.

use super::problem::{Outcome, Problem};
use lagrangian_model::LagrangianSystem;
use nalgebra::DMatrix;

pub(super) struct Uncertainty {
    /// Per entry (`None` for the held and the undetermined ones).
    pub standard_errors: Vec<Option<f64>>,
    /// `(i, j, ρ)` with `|ρ| > 0.95`, entry indices.
    pub strong: Vec<(usize, usize, f64)>,
}

/// The standard errors and strong correlations of the fitted entries at
/// `outcome`, from the residuals and Jacobian there (one more round of
/// simulations).
pub(super) fn uncertainty<const N: usize, S>(
    problem: &Problem<'_, S>,
    outcome: &Outcome,
) -> Result<Uncertainty, String>
where
    S: LagrangianSystem<N> + Clone + Send,
{
    let parameters = problem.parameters();
    let entries = parameters.entries.len();
    let r = problem.residuals_at::<N>(&outcome.u)?;
    let m = r.len();
    let n = problem.free.len();
    // Nothing is determined by fewer residuals than free entries.
    let undetermined = Uncertainty {
        standard_errors: vec![None; entries],
        strong: Vec::new(),
    };
    if m <= n {
        return Ok(undetermined);
    }
    let columns = problem.jacobian::<N>(&outcome.u, &r);
    let j = DMatrix::from_fn(m, n, |i, k| columns[k][i]);
    let sigma2 = r.iter().map(|x| x * x).sum::<f64>() / (m - n) as f64;
    let normal = j.transpose() * &j;
    let svd = normal.clone().svd(true, true);
    let largest = svd.singular_values.max();
    let Ok(inverse) = svd.pseudo_inverse(1e-12 * largest) else {
        return Ok(undetermined);
    };
    let cov_u = inverse * sigma2;
    let d = transform_jacobian(problem, outcome);
    let cov = &d * cov_u * d.transpose();
    let mut standard_errors = undetermined.standard_errors;
    let determined: Vec<bool> = (0..n)
        .map(|k| cov[(k, k)] > 0.0 && cov[(k, k)].is_finite())
        .collect();
    for (row, &i) in problem.free.iter().enumerate() {
        if determined[row] {
            standard_errors[i] = Some(cov[(row, row)].sqrt());
        }
    }
    Ok(Uncertainty {
        standard_errors,
        strong: strong_correlations(&cov, &determined, &problem.free),
    })
}

/// `D = ∂p/∂u` for the free entries at the optimum, by central differences
/// of the transforms (exact to rounding for exp and sums of exp).
fn transform_jacobian<S>(problem: &Problem<'_, S>, outcome: &Outcome) -> DMatrix<f64>
where
    S: Clone + Send,
{
    let parameters = problem.parameters();
    let n = problem.free.len();
    let full = |u: &[f64]| {
        let mut f = parameters.to_unconstrained(&outcome.values);
        for (&i, &x) in problem.free.iter().zip(u) {
            f[i] = x;
        }
        f
    };
    let mut d = DMatrix::zeros(n, n);
    for k in 0..n {
        let h = 1e-6;
        let mut up = outcome.u.clone();
        let mut down = outcome.u.clone();
        up[k] += h;
        down[k] -= h;
        let (pu, pd) = (
            parameters.to_physical(&full(&up)),
            parameters.to_physical(&full(&down)),
        );
        for (row, &i) in problem.free.iter().enumerate() {
            d[(row, k)] = (pu[i] - pd[i]) / (2.0 * h);
        }
    }
    d
}

/// `(i, j, ρ)` for the pairs of determined free entries (`free[a]`,
/// `free[b]`) whose correlation in `cov` exceeds 0.95 in magnitude.
fn strong_correlations(
    cov: &DMatrix<f64>,
    determined: &[bool],
    free: &[usize],
) -> Vec<(usize, usize, f64)> {
    let n = free.len();
    let mut strong = Vec::new();
    for a in 0..n {
        for b in a + 1..n {
            if determined[a] && determined[b] {
                let rho = cov[(a, b)] / (cov[(a, a)] * cov[(b, b)]).sqrt();
                if rho.abs() > 0.95 {
                    strong.push((free[a], free[b], rho));
                }
            }
        }
    }
    strong
}
