//! Identifiability, standard errors and correlations of fitted parameters,
//! all from the Jacobian `J = ∂r/∂u` at the optimum.
//!
//! A free entry whose column of `J` is zero or negligible against the
//! others ([`NEGLIGIBLE_INFLUENCE`]) has no influence there — a stiffness
//! beyond the fitted crush — and is not identifiable, whatever it did at
//! the start. Of the others, `J = U S Vᵀ`; a singular value below
//! [`RANK_TOLERANCE`] times the largest is a direction the target does not
//! see, and the entries along it are determined only in combination. The
//! rest have `Cov_u = σ² V S⁻² Vᵀ` with `σ² = Σr² / (m − rank)`, carried to
//! the physical parameters through the transforms, `Cov_p = D Cov_u Dᵀ`,
//! `D = ∂p/∂u`. (A pseudo-inverse would give an entry along an unseen
//! direction a small variance instead of none: the opposite of the truth.)

use super::FitError;
use super::problem::{Outcome, Problem};
use lagrangian_runtime::LagrangianSystem;
use nalgebra::DMatrix;

/// A column of `J` at most this fraction of the largest (in norm) has no
/// influence: a 100 % change of that entry moves the residuals a millionth
/// as much as the same change of the most influential one.
pub const NEGLIGIBLE_INFLUENCE: f64 = 1e-6;

/// A singular value of `J` at most this fraction of the largest is a
/// direction the target does not determine.
pub const RANK_TOLERANCE: f64 = 1e-8;

/// How the target determines a free entry at the optimum.
#[derive(Clone, Debug, PartialEq)]
pub(super) enum Determined {
    /// Its standard error is finite.
    Yes,
    /// Its column of `J` is negligible: it has no influence there.
    NoInfluence,
    /// Only a combination of it with these entries (indices) is determined.
    Combination(Vec<usize>),
}

pub(super) struct Uncertainty {
    /// Per entry (`None` for the held and the undetermined ones).
    pub standard_errors: Vec<Option<f64>>,
    /// Per entry: `None` for the held ones.
    pub determined: Vec<Option<Determined>>,
    /// Per entry: its column's norm over the largest column's at the
    /// optimum (`None` for the held ones).
    pub influence: Vec<Option<f64>>,
    /// `(i, j, ρ)` with `|ρ| > 0.95`, entry indices.
    pub strong: Vec<(usize, usize, f64)>,
}

/// The identifiability, standard errors and strong correlations of the
/// fitted entries at `outcome`, from the residuals and Jacobian there (one
/// more round of simulations).
pub(super) fn uncertainty<const N: usize, S>(
    problem: &Problem<'_, S>,
    outcome: &Outcome,
) -> Result<Uncertainty, FitError>
where
    S: LagrangianSystem<N> + Clone + Send,
{
    let entries = problem.parameters().entries.len();
    let r = problem.residuals_at::<N>(&outcome.u)?;
    let columns = problem.jacobian::<N>(&outcome.u, &r);
    let free = &problem.free;
    let norms: Vec<f64> = columns.iter().map(|c| norm(c)).collect();
    let largest = norms.iter().copied().fold(0.0, f64::max);
    let mut result = Uncertainty {
        standard_errors: vec![None; entries],
        determined: vec![None; entries],
        influence: vec![None; entries],
        strong: Vec::new(),
    };
    // Rows (among the free entries) with an influence at the optimum.
    let mut seen = Vec::new();
    for (row, &i) in free.iter().enumerate() {
        let influence = if largest > 0.0 {
            norms[row] / largest
        } else {
            0.0
        };
        result.influence[i] = Some(influence);
        if influence > NEGLIGIBLE_INFLUENCE {
            seen.push(row);
        } else {
            result.determined[i] = Some(Determined::NoInfluence);
        }
    }
    let j = DMatrix::from_fn(r.len(), seen.len(), |i, k| columns[seen[k]][i]);
    let (cov_seen, combinations) = covariance(&j, &r);
    for (k, partners) in combinations.iter().enumerate() {
        let i = free[seen[k]];
        result.determined[i] = Some(match partners {
            None => Determined::Yes,
            Some(with) => Determined::Combination(with.iter().map(|&p| free[seen[p]]).collect()),
        });
    }
    // Cov_u over all free rows: infinite (NaN) where not determined.
    let n = free.len();
    let mut cov_u = DMatrix::from_element(n, n, f64::NAN);
    for (a, &ra) in seen.iter().enumerate() {
        for (b, &rb) in seen.iter().enumerate() {
            if combinations[a].is_none() && combinations[b].is_none() {
                cov_u[(ra, rb)] = cov_seen[(a, b)];
            }
        }
    }
    let cov = physical_covariance(&transform_jacobian(problem, outcome), &cov_u);
    let finite: Vec<bool> = (0..n)
        .map(|k| cov[(k, k)].is_finite() && cov[(k, k)] >= 0.0)
        .collect();
    for (row, &i) in free.iter().enumerate() {
        if finite[row] && result.determined[i] == Some(Determined::Yes) {
            result.standard_errors[i] = Some(cov[(row, row)].sqrt());
        }
    }
    result.strong = strong_correlations(&cov, &finite, free);
    Ok(result)
}

fn norm(x: &[f64]) -> f64 {
    x.iter().map(|v| v * v).sum::<f64>().sqrt()
}

/// `σ² V S⁻² Vᵀ` of `J` (`m × k`) and the residuals `r`, and per column
/// `None` when it is determined, else the other columns it is determined
/// only in combination with (its share in a direction of `J`'s null space).
fn covariance(j: &DMatrix<f64>, r: &[f64]) -> (DMatrix<f64>, Vec<Option<Vec<usize>>>) {
    let (m, k) = j.shape();
    if k == 0 {
        return (DMatrix::zeros(0, 0), Vec::new());
    }
    let svd = j.clone().svd(false, true);
    let v_t = svd.v_t.as_ref().expect("V was asked for");
    let s = &svd.singular_values;
    let largest = s.max();
    // The rows of Vᵀ: the directions, with their singular values (those
    // beyond the first min(m, k) are unseen).
    let unseen: Vec<usize> = (0..k)
        .filter(|&d| d >= s.len() || s[d] <= RANK_TOLERANCE * largest)
        .collect();
    let rank = k - unseen.len().min(k);
    // Completes Vᵀ to a square basis when m < k: the unseen directions are
    // what it lacks, found as the null space of the rows it has.
    let basis = complete_basis(v_t, k);
    let share = |column: usize, d: usize| basis[(d, column)].abs() > 1e-6;
    let combinations: Vec<Option<Vec<usize>>> = (0..k)
        .map(|c| {
            let along: Vec<usize> = unseen.iter().copied().filter(|&d| share(c, d)).collect();
            if along.is_empty() {
                return None;
            }
            let with = (0..k)
                .filter(|&o| o != c && along.iter().any(|&d| share(o, d)))
                .collect();
            Some(with)
        })
        .collect();
    let dof = m.saturating_sub(rank).max(1) as f64;
    let sigma2 = r.iter().map(|x| x * x).sum::<f64>() / dof;
    let mut cov = DMatrix::zeros(k, k);
    for d in (0..s.len()).filter(|d| !unseen.contains(d)) {
        let v = basis.row(d).transpose();
        cov += (&v * v.transpose()) * (sigma2 / (s[d] * s[d]));
    }
    (cov, combinations)
}

/// `Vᵀ` (its rows orthonormal) completed to `k` orthonormal rows.
fn complete_basis(v_t: &DMatrix<f64>, k: usize) -> DMatrix<f64> {
    if v_t.nrows() >= k {
        return v_t.clone();
    }
    // The eigenvectors of I − VVᵀ with eigenvalue 1 span what Vᵀ lacks.
    let projector = DMatrix::identity(k, k) - v_t.transpose() * v_t;
    let eigen = projector.symmetric_eigen();
    let mut order: Vec<usize> = (0..k).collect();
    order.sort_by(|&a, &b| eigen.eigenvalues[b].total_cmp(&eigen.eigenvalues[a]));
    let mut rows: Vec<_> = v_t.row_iter().map(|r| r.into_owned()).collect();
    for &e in order.iter().take(k - v_t.nrows()) {
        rows.push(eigen.eigenvectors.column(e).transpose());
    }
    DMatrix::from_rows(&rows)
}

/// `D Cov_u Dᵀ`, a NaN in `Cov_u` (an undetermined variable) spreading to
/// every parameter that depends on it and to no other.
fn physical_covariance(d: &DMatrix<f64>, cov_u: &DMatrix<f64>) -> DMatrix<f64> {
    let n = d.nrows();
    DMatrix::from_fn(n, n, |a, b| {
        let mut sum = 0.0;
        for i in 0..n {
            for j in 0..n {
                let weight = d[(a, i)] * d[(b, j)];
                if weight != 0.0 {
                    sum += weight * cov_u[(i, j)];
                }
            }
        }
        sum
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

#[cfg(test)]
mod tests {
    use super::*;

    /// `r = J u − y` for a line `y = a + b t` sampled at t = 0…4: the
    /// textbook covariance `σ² (JᵀJ)⁻¹` (here inverted by hand).
    #[test]
    fn a_full_rank_jacobian_gives_the_textbook_covariance() {
        let t = [0.0, 1.0, 2.0, 3.0, 4.0];
        let j = DMatrix::from_fn(5, 2, |i, k| if k == 0 { 1.0 } else { t[i] });
        let r = [0.1, -0.2, 0.05, 0.15, -0.1];
        let (cov, combinations) = covariance(&j, &r);
        assert_eq!(combinations, [None, None]);
        // JᵀJ = [[5, 10], [10, 30]], its inverse [[30, −10], [−10, 5]] / 50.
        let sigma2 = r.iter().map(|x| x * x).sum::<f64>() / 3.0;
        let expected = [[0.6, -0.2], [-0.2, 0.1]];
        for a in 0..2 {
            for b in 0..2 {
                let want = expected[a][b] * sigma2;
                assert!(
                    (cov[(a, b)] - want).abs() < 1e-14,
                    "{a}{b}: {}",
                    cov[(a, b)]
                );
            }
        }
    }

    /// Two columns equal up to a factor: only their combination is seen;
    /// the third column stays determined.
    #[test]
    fn dependent_columns_are_determined_only_in_combination() {
        let j = DMatrix::from_row_slice(
            4,
            3,
            &[
                1.0, 2.0, 0.0, //
                2.0, 4.0, 1.0, //
                3.0, 6.0, 0.0, //
                1.0, 2.0, 2.0,
            ],
        );
        let (_, combinations) = covariance(&j, &[0.1, 0.1, 0.1, 0.1]);
        assert_eq!(combinations, [Some(vec![1]), Some(vec![0]), None]);
        // Fewer residuals than columns: a direction is unseen.
        let wide = DMatrix::from_row_slice(1, 2, &[1.0, 1.0]);
        let (_, combinations) = covariance(&wide, &[0.1]);
        assert_eq!(combinations, [Some(vec![1]), Some(vec![0])]);
    }

    #[test]
    fn an_undetermined_variable_spreads_only_to_what_depends_on_it() {
        let d = DMatrix::from_row_slice(3, 3, &[1.0, 0.0, 0.0, 1.0, 1.0, 0.0, 0.0, 0.0, 2.0]);
        let mut cov_u = DMatrix::identity(3, 3);
        cov_u[(1, 1)] = f64::NAN;
        cov_u[(0, 1)] = f64::NAN;
        cov_u[(1, 0)] = f64::NAN;
        let cov = physical_covariance(&d, &cov_u);
        assert_eq!(cov[(0, 0)], 1.0);
        assert!(cov[(1, 1)].is_nan());
        assert_eq!(cov[(2, 2)], 4.0);
    }
}
