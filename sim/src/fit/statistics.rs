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
    let mut standard_errors = vec![None; entries];
    let mut strong = Vec::new();
    if m <= n {
        return Ok(Uncertainty {
            standard_errors,
            strong,
        });
    }
    let columns = problem.jacobian::<N>(&outcome.u, &r);
    let j = DMatrix::from_fn(m, n, |i, k| columns[k][i]);
    let sigma2 = r.iter().map(|x| x * x).sum::<f64>() / (m - n) as f64;
    let normal = j.transpose() * &j;
    let svd = normal.clone().svd(true, true);
    let largest = svd.singular_values.max();
    let Ok(inverse) = svd.pseudo_inverse(1e-12 * largest) else {
        return Ok(Uncertainty {
            standard_errors,
            strong,
        });
    };
    let cov_u = inverse * sigma2;
    // D = ∂p/∂u for the free entries, by central differences of the
    // transforms (exact to rounding for exp and sums of exp).
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
    let cov = &d * cov_u * d.transpose();
    let determined: Vec<bool> = (0..n)
        .map(|k| cov[(k, k)] > 0.0 && cov[(k, k)].is_finite())
        .collect();
    for (row, &i) in problem.free.iter().enumerate() {
        if determined[row] {
            standard_errors[i] = Some(cov[(row, row)].sqrt());
        }
    }
    for a in 0..n {
        for b in a + 1..n {
            if determined[a] && determined[b] {
                let rho = cov[(a, b)] / (cov[(a, a)] * cov[(b, b)]).sqrt();
                if rho.abs() > 0.95 {
                    strong.push((problem.free[a], problem.free[b], rho));
                }
            }
        }
    }
    Ok(Uncertainty {
        standard_errors,
        strong,
    })
}
