//! TR-BDF2 for stiff mechanical systems (very stiff contact or weld springs).
//!
//! TR-BDF2 is the L-stable, stiffly accurate ESDIRK method of order 2
//! (Bank et al. 1985; Hosea & Shampine 1996): a trapezoidal stage to
//! `t + γh` and a BDF2 stage to `t + h`, `γ = 2 − √2`, with an embedded
//! 3rd-order solution for error control. As a Butcher tableau:
//!
//! ```text
//!  0 |
//!  γ |  d     d
//!  1 |  w     w     d
//! ---+-----------------
//!    |  w     w     d          (stiffly accurate: the last row)
//!    | b̂1    b̂2    b̂3         (embedded, 3rd order)
//! ```
//!
//! with `d = γ/2`, `w = √2/4`. Both implicit stages share the Newton matrix
//! `I − d h J`.
//!
//! For `y = (q, v, w)` with `q̇ = v`, `v̇ = a(t, q, v)` and the energy
//! integrals `ẇ = P(t, q, v)`, the Newton system reduces to `N × N`:
//! `(I − dh A_v − (dh)² A_q) Δv = r_v + dh A_q r_q`, `Δq = r_q + dh Δv`, with
//! `A_q = ∂a/∂q`, `A_v = ∂a/∂v` from the model's derived Jacobians (or
//! forward differences of `a`: for a model with constraints, of its
//! constrained accelerations, whose Jacobians are not derived); `w` follows
//! each stage explicitly, as do the quadratures among the internal states
//! (the components' dissipated energies), which stay out of the error
//! norms of the step and of the Newton iterations. The components' other
//! internal states `z`, `ż = g(…)`, take part in the Newton iterations with the diagonal of `∂g/∂z` alone,
//! by forward differences: `Δz_k = r_z,k / (1 − dh ∂g_k/∂z_k)`. Leaving out
//! the coupling of `z` with `(q, v)` makes the iteration a simplified
//! Newton one, which converges to the same stage values (it is checked
//! like the rest) at the cost of more iterations when the coupling is
//! strong. The end of each accepted step is projected onto
//! what the problem keeps invariant ([`AccelerationJacobians::project`]).

use super::driver::{Attempt, Stepper};
use super::hermite::Hermite;
use super::lu::Lu;
use super::{
    Internal, Observer, OdeProblem, OdeVector, Options, Outcome, PhaseState, SolverError, Stats,
    error_norm, evaluate,
};
use nalgebra::{SMatrix, SVector};

const SQRT2: f64 = std::f64::consts::SQRT_2;
/// The node of the trapezoidal stage.
const GAMMA: f64 = 2.0 - SQRT2;
/// The diagonal of the tableau.
const D: f64 = GAMMA / 2.0;
/// The weights of the first two stages in the last row.
const W: f64 = SQRT2 / 4.0;
// Embedded 3rd-order weights (Hosea & Shampine).
const B1_HAT: f64 = (1.0 - W) / 3.0;
const B2_HAT: f64 = (3.0 * W + 1.0) / 3.0;
const B3_HAT: f64 = D / 3.0;

/// `(∂a/∂q, ∂a/∂v)`.
pub type AccelerationJacobian<const N: usize> = (SMatrix<f64, N, N>, SMatrix<f64, N, N>);

/// The acceleration Jacobians of a mechanical problem.
pub trait AccelerationJacobians<const N: usize>: OdeProblem<PhaseState<N>> {
    /// `(∂a/∂q, ∂a/∂v)` at `(t, y)`, or `None` when the model has none
    /// (finite differences are used instead).
    fn acceleration_jacobians(
        &mut self,
        t: f64,
        y: &PhaseState<N>,
    ) -> Result<Option<AccelerationJacobian<N>>, Self::Error>;

    /// Moves the end of an accepted step back onto what the problem keeps
    /// invariant (a model's constraints `g = 0`, `ġ = 0`), which a method of
    /// order 2 holds less tightly than the tolerances ask; `Ok(true)` when
    /// it moved `y`. By default nothing is kept.
    fn project(&mut self, t: f64, y: &mut PhaseState<N>) -> Result<bool, Self::Error> {
        let _ = (t, y);
        Ok(false)
    }
}

/// Integrates a stiff mechanical problem with TR-BDF2.
pub fn integrate<const N: usize, P: AccelerationJacobians<N>>(
    problem: &mut P,
    t0: f64,
    y0: PhaseState<N>,
    t_end: f64,
    options: &Options,
    observer: Observer<'_, P, PhaseState<N>>,
) -> Result<Outcome<PhaseState<N>>, SolverError<P::Error>> {
    let mut stepper = TrBdf2 {
        options: *options,
        end: (PhaseState::zeros(), PhaseState::zeros()),
        norm: 0.0,
    };
    super::driver::run(&mut stepper, problem, (t0, y0), t_end, options, observer)
}

/// The stepper: the end of the last step and its error norm.
struct TrBdf2<const N: usize> {
    options: Options,
    /// `(y3, F(t + h, y3))` of the last accepted step.
    end: (PhaseState<N>, PhaseState<N>),
    norm: f64,
}

impl<const N: usize> TrBdf2<N> {
    /// `Rejected(h/4)`, or `failure` when that is below the minimum step.
    fn retry<E>(
        &self,
        h: f64,
        failure: impl FnOnce(f64) -> SolverError<E>,
    ) -> Result<Attempt<Hermite<PhaseState<N>>>, SolverError<E>> {
        let h = h * 0.25;
        check_step(h, &self.options, failure(h))?;
        Ok(Attempt::Rejected(h))
    }
}

impl<const N: usize, P: AccelerationJacobians<N>> Stepper<PhaseState<N>, P> for TrBdf2<N> {
    type Dense = Hermite<PhaseState<N>>;

    fn attempt(
        &mut self,
        problem: &mut P,
        (t, y, k1): (f64, &PhaseState<N>, &PhaseState<N>),
        h: f64,
        stats: &mut Stats,
    ) -> Result<Attempt<Self::Dense>, SolverError<P::Error>> {
        let (a_q, a_v) = jacobians(problem, t, y, k1, stats)?;
        let g_z = internal_diagonal(problem, t, y, k1, stats)?;
        let dh = D * h;
        let newton_matrix = SMatrix::<f64, N, N>::identity() - a_v * dh - a_q * (dh * dh);
        let Some(lu) = Lu::new(newton_matrix) else {
            return self.retry(h, |h| SolverError::SingularIterationMatrix { t, h });
        };
        let newton = Newton {
            lu: &lu,
            a_q: &a_q,
            g_z: &g_z,
            dh,
            options: &self.options,
        };
        // Trapezoidal stage to t + γh, then BDF2 stage to t + h.
        let mut base2 = PhaseState::zeros();
        base2.set_combination(y, &[(dh, k1)]);
        let mut guess = PhaseState::zeros();
        guess.set_combination(y, &[(GAMMA * h, k1)]);
        let Some((y2, k2)) = newton.solve(problem, t + GAMMA * h, &base2, guess, stats)? else {
            return self.retry(h, |h| SolverError::NewtonFailure { t, h });
        };
        let mut base3 = PhaseState::zeros();
        base3.set_combination(y, &[(W * h, k1), (W * h, &k2)]);
        guess.set_combination(&y2, &[((1.0 - GAMMA) * h, &k2)]);
        let Some((y3, k3)) = newton.solve(problem, t + h, &base3, guess, stats)? else {
            return self.retry(h, |h| SolverError::NewtonFailure { t, h });
        };
        // Error estimate, filtered by the Newton matrix so that stiff
        // components are not overestimated (Shampine).
        let mut error = PhaseState::zeros();
        error.set_sum(&[
            ((W - B1_HAT) * h, k1),
            ((W - B2_HAT) * h, &k2),
            ((D - B3_HAT) * h, &k3),
        ]);
        let filtered = newton.apply_inverse(&error);
        let norm = if self.options.fixed_step.is_some() {
            0.0
        } else {
            error_norm(&filtered, y, &y3, &self.options)
        };
        if norm.is_nan() || norm > 1.0 {
            let h = h * if norm.is_finite() {
                (0.9 * norm.powf(-1.0 / 3.0)).max(0.2)
            } else {
                0.2
            };
            check_step(h, &self.options, SolverError::StepSizeUnderflow { t, h })?;
            return Ok(Attempt::Rejected(h));
        }
        let (mut y3, mut k3) = (y3, k3);
        let projected = (problem.project(t + h, &mut y3))
            .map_err(|error| SolverError::Rhs { t: t + h, error })?;
        if projected {
            evaluate(problem, t + h, &y3, &mut k3, stats)?;
        }
        self.norm = norm;
        self.end = (y3, k3);
        Ok(Attempt::Accepted(Hermite {
            t0: t,
            h,
            end: t + h,
            y0: *y,
            f0: *k1,
            y1: y3,
            f1: k3,
        }))
    }

    fn end(&self) -> &PhaseState<N> {
        &self.end.0
    }

    fn advance(&mut self, y: &mut PhaseState<N>, f: &mut PhaseState<N>, h: f64) -> f64 {
        (*y, *f) = self.end;
        if self.options.fixed_step.is_some() {
            return h;
        }
        (h * (0.9 * self.norm.max(1e-10).powf(-1.0 / 3.0)).clamp(0.2, 5.0))
            .min(self.options.max_step)
    }

    fn restart(&mut self, h: f64) -> f64 {
        h
    }
}

/// `Err(failure)` when the shrunk step `h` is below the minimum; `failure`
/// says why the step had to shrink.
fn check_step<E>(h: f64, options: &Options, failure: SolverError<E>) -> Result<(), SolverError<E>> {
    if h < options.min_step {
        Err(failure)
    } else {
        Ok(())
    }
}

/// `(∂a/∂q, ∂a/∂v)`: the problem's own, or forward differences of `a`.
fn jacobians<const N: usize, P: AccelerationJacobians<N>>(
    problem: &mut P,
    t: f64,
    y: &PhaseState<N>,
    f: &PhaseState<N>,
    stats: &mut Stats,
) -> Result<AccelerationJacobian<N>, SolverError<P::Error>> {
    stats.jacobian_evaluations += 1;
    let own = problem
        .acceleration_jacobians(t, y)
        .map_err(|error| SolverError::Rhs { t, error })?;
    if let Some(j) = own {
        return Ok(j);
    }
    let (mut a_q, mut a_v) = (SMatrix::<f64, N, N>::zeros(), SMatrix::<f64, N, N>::zeros());
    let mut out = PhaseState::zeros();
    for k in 0..N {
        let mut perturbed = *y;
        let step = f64::EPSILON.sqrt() * y.q[k].abs().max(1.0);
        perturbed.q[k] += step;
        evaluate(problem, t, &perturbed, &mut out, stats)?;
        a_q.set_column(k, &((out.v - f.v) / step));
        let mut perturbed = *y;
        let step = f64::EPSILON.sqrt() * y.v[k].abs().max(1.0);
        perturbed.v[k] += step;
        evaluate(problem, t, &perturbed, &mut out, stats)?;
        a_v.set_column(k, &((out.v - f.v) / step));
    }
    Ok((a_q, a_v))
}

/// `∂g_k/∂z_k` for each internal state `z_k`, by forward differences of
/// `F`; 0 for the quadratures, whose rates do not depend on them; empty
/// without internal states.
fn internal_diagonal<const N: usize, P: OdeProblem<PhaseState<N>>>(
    problem: &mut P,
    t: f64,
    y: &PhaseState<N>,
    f: &PhaseState<N>,
    stats: &mut Stats,
) -> Result<Internal, SolverError<P::Error>> {
    let mut diagonal = y.z;
    diagonal.as_mut_slice().fill(0.0);
    let mut out = PhaseState::zeros();
    for k in 0..y.z.controlled_len() {
        let mut perturbed = *y;
        let step = f64::EPSILON.sqrt() * y.z.as_slice()[k].abs().max(1.0);
        perturbed.z.as_mut_slice()[k] += step;
        evaluate(problem, t, &perturbed, &mut out, stats)?;
        diagonal.as_mut_slice()[k] = (out.z.as_slice()[k] - f.z.as_slice()[k]) / step;
    }
    Ok(diagonal)
}

/// Simplified Newton iterations for one implicit stage `Y = base + dh F(t, Y)`.
struct Newton<'a, const N: usize> {
    lu: &'a Lu<N>,
    a_q: &'a SMatrix<f64, N, N>,
    /// `∂g_k/∂z_k` of the internal states.
    g_z: &'a Internal,
    dh: f64,
    options: &'a Options,
}

impl<const N: usize> Newton<'_, N> {
    /// `(I − dh J)⁻¹ r` on `(q, v)`, and on each internal state with its
    /// own diagonal; the energy integrals pass through.
    fn apply_inverse(&self, r: &PhaseState<N>) -> PhaseState<N> {
        let v: SVector<f64, N> = self.lu.solve(&(r.v + self.a_q * r.q * self.dh));
        let mut z = r.z;
        for (zk, gk) in z.as_mut_slice().iter_mut().zip(self.g_z.as_slice()) {
            *zk /= 1.0 - self.dh * gk;
        }
        PhaseState {
            q: r.q + v * self.dh,
            v,
            work: r.work,
            z,
        }
    }

    /// The stage value and its derivative, or `None` if Newton diverges.
    fn solve<P: OdeProblem<PhaseState<N>>>(
        &self,
        problem: &mut P,
        t: f64,
        base: &PhaseState<N>,
        mut y: PhaseState<N>,
        stats: &mut Stats,
    ) -> Result<Option<(PhaseState<N>, PhaseState<N>)>, SolverError<P::Error>> {
        let mut f = PhaseState::zeros();
        let mut previous = f64::INFINITY;
        for _ in 0..10 {
            stats.newton_iterations += 1;
            evaluate(problem, t, &y, &mut f, stats)?;
            // Residual r = base + dh F(Y) − Y; the step solves (I − dh J) Δ = r.
            let mut residual = PhaseState::zeros();
            residual.set_sum(&[(1.0, base), (self.dh, &f), (-1.0, &y)]);
            let delta = self.apply_inverse(&residual);
            y.set_combination(&y.clone(), &[(1.0, &delta)]);
            let size = error_norm(&delta, &y, &y, self.options);
            if size.is_nan() || size > 2.0 * previous {
                return Ok(None);
            }
            previous = size;
            if size < 1e-3 {
                evaluate(problem, t, &y, &mut f, stats)?;
                // The energy integrals and the quadratures follow
                // explicitly from the converged stage.
                y.work[0] = base.work[0] + self.dh * f.work[0];
                y.work[1] = base.work[1] + self.dh * f.work[1];
                let first = y.z.controlled_len();
                let (base_z, f_z) = (base.z.as_slice(), f.z.as_slice());
                for (k, value) in y.z.as_mut_slice().iter_mut().enumerate().skip(first) {
                    *value = base_z[k] + self.dh * f_z[k];
                }
                return Ok(Some((y, f)));
            }
        }
        Ok(None)
    }
}
