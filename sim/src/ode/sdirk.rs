//! TR-BDF2 for stiff mechanical systems (very stiff contact or weld springs).
//!
//! TR-BDF2 is the L-stable, stiffly accurate ESDIRK method of order 2
//! (Bank et al. 1985; Hosea & Shampine 1996): a trapezoidal stage to
//! `t + γh` and a BDF2 stage to `t + h`, `γ = 2 − √2`, with an embedded
//! 3rd-order solution for error control. Both implicit stages share the
//! Newton matrix `I − d h J` (`d = γ/2`).
//!
//! For `y = (q, v, w)` with `q̇ = v`, `v̇ = a(t, q, v)` and the energy
//! integrals `ẇ = P(t, q, v)`, the Newton system reduces to `N × N`:
//! `(I − dh A_v − (dh)² A_q) Δv = r_v + dh A_q r_q`, `Δq = r_q + dh Δv`, with
//! `A_q = ∂a/∂q`, `A_v = ∂a/∂v` from the model's derived Jacobians (or
//! finite differences); `w` follows each stage explicitly.

use super::driver::{Driver, Point, StepEnd};
use super::hermite::Hermite;
use super::lu::Lu;
use super::{
    DenseStep, OdeProblem, OdeVector, Options, Outcome, PhaseState, SolverError, Stats, error_norm,
    evaluate,
};
use nalgebra::{SMatrix, SVector};

const SQRT2: f64 = std::f64::consts::SQRT_2;
const GAMMA: f64 = 2.0 - SQRT2;
const D: f64 = GAMMA / 2.0;
const W: f64 = SQRT2 / 4.0;
// Embedded 3rd-order weights (Hosea & Shampine).
const B1_HAT: f64 = (1.0 - W) / 3.0;
const B2_HAT: f64 = (3.0 * W + 1.0) / 3.0;
const B3_HAT: f64 = D / 3.0;

/// `(∂a/∂q, ∂a/∂v)`.
pub type AccelerationJacobian<const N: usize> = (SMatrix<f64, N, N>, SMatrix<f64, N, N>);

/// The acceleration Jacobians of a mechanical problem.
pub trait AccelerationJacobians<const N: usize> {
    /// `(∂a/∂q, ∂a/∂v)` at `(t, y)`, or `None` when the model has none
    /// (finite differences are used instead).
    fn acceleration_jacobians(
        &mut self,
        t: f64,
        y: &PhaseState<N>,
    ) -> Result<Option<AccelerationJacobian<N>>, SolverError>;
}

/// Integrates a stiff mechanical problem with TR-BDF2.
pub fn integrate<const N: usize, P>(
    problem: &mut P,
    t0: f64,
    y0: PhaseState<N>,
    t_end: f64,
    options: &Options,
    observer: &mut dyn FnMut(&mut P, &dyn DenseStep<PhaseState<N>>),
) -> Result<Outcome<PhaseState<N>>, SolverError>
where
    P: OdeProblem<PhaseState<N>> + AccelerationJacobians<N>,
{
    let (mut t, mut y) = (t0, y0);
    let mut k1 = PhaseState::zeros();
    let mut driver = Driver::start(problem, t, &y, &mut k1, t_end, options)?;
    let mut h = match options.fixed_step.or(options.initial_step) {
        Some(h) => h,
        None => {
            super::dopri5::initial_step(problem, t, &y, &k1, t_end - t, options, &mut driver.stats)?
        }
    }
    .min(options.max_step);
    while let Some(step) = driver.next_step(t, h)? {
        h = step;
        let stats = &mut driver.stats;
        let (a_q, a_v) = jacobians(problem, t, &y, &k1, stats)?;
        let dh = D * h;
        let newton_matrix = SMatrix::<f64, N, N>::identity() - a_v * dh - a_q * (dh * dh);
        let Some(lu) = Lu::new(newton_matrix) else {
            h *= 0.25;
            stats.rejected_steps += 1;
            check_step(h, options, SolverError::SingularIterationMatrix { t, h })?;
            continue;
        };
        let newton = Newton {
            lu: &lu,
            a_q: &a_q,
            dh,
            options,
        };
        // Trapezoidal stage to t + γh, then BDF2 stage to t + h.
        let mut base2 = PhaseState::zeros();
        base2.set_combination(&y, &[(dh, &k1)]);
        let mut guess = PhaseState::zeros();
        guess.set_combination(&y, &[(GAMMA * h, &k1)]);
        let Some((y2, k2)) = newton.solve(problem, t + GAMMA * h, &base2, guess, stats)? else {
            h *= 0.25;
            stats.rejected_steps += 1;
            check_step(h, options, SolverError::NewtonFailure { t, h })?;
            continue;
        };
        let mut base3 = PhaseState::zeros();
        base3.set_combination(&y, &[(W * h, &k1), (W * h, &k2)]);
        guess.set_combination(&y2, &[((1.0 - GAMMA) * h, &k2)]);
        let Some((y3, k3)) = newton.solve(problem, t + h, &base3, guess, stats)? else {
            h *= 0.25;
            stats.rejected_steps += 1;
            check_step(h, options, SolverError::NewtonFailure { t, h })?;
            continue;
        };
        // Error estimate, filtered by the Newton matrix so that stiff
        // components are not overestimated (Shampine).
        let mut error = PhaseState::zeros();
        error.set_sum(&[
            ((W - B1_HAT) * h, &k1),
            ((W - B2_HAT) * h, &k2),
            ((D - B3_HAT) * h, &k3),
        ]);
        let filtered = newton.apply_inverse(&error);
        let norm = if options.fixed_step.is_some() {
            0.0
        } else {
            error_norm(&filtered, &y, &y3, options)
        };
        if norm.is_nan() || norm > 1.0 {
            stats.rejected_steps += 1;
            h *= if norm.is_finite() {
                (0.9 * norm.powf(-1.0 / 3.0)).max(0.2)
            } else {
                0.2
            };
            check_step(h, options, SolverError::StepSizeUnderflow { t, h })?;
            continue;
        }
        stats.accepted_steps += 1;
        let dense = Hermite {
            t0: t,
            h,
            end: t + h,
            y0: y,
            f0: k1,
            y1: y3,
            f1: k3,
        };
        let point = Point {
            t: &mut t,
            y: &mut y,
            f: &mut k1,
        };
        match driver.finish_step(problem, dense, &y3, point, observer)? {
            StepEnd::Next => {}
            StepEnd::Restarted => continue,
            StepEnd::Stopped(k) => return Ok(driver.outcome(t, y, Some(k))),
        }
        t += h;
        y = y3;
        k1 = k3;
        if options.fixed_step.is_none() {
            h = (h * (0.9 * norm.max(1e-10).powf(-1.0 / 3.0)).clamp(0.2, 5.0))
                .min(options.max_step);
        }
    }
    Ok(driver.outcome(t, y, None))
}

/// `Err(failure)` when the shrunk step `h` is below the minimum; `failure`
/// says why the step had to shrink.
fn check_step(h: f64, options: &Options, failure: SolverError) -> Result<(), SolverError> {
    if h < options.min_step {
        Err(failure)
    } else {
        Ok(())
    }
}

/// `(∂a/∂q, ∂a/∂v)`: the problem's own, or forward differences of `a`.
fn jacobians<const N: usize, P>(
    problem: &mut P,
    t: f64,
    y: &PhaseState<N>,
    f: &PhaseState<N>,
    stats: &mut Stats,
) -> Result<AccelerationJacobian<N>, SolverError>
where
    P: OdeProblem<PhaseState<N>> + AccelerationJacobians<N>,
{
    stats.jacobian_evaluations += 1;
    if let Some(j) = problem.acceleration_jacobians(t, y)? {
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

/// Simplified Newton iterations for one implicit stage `Y = base + dh F(t, Y)`.
struct Newton<'a, const N: usize> {
    lu: &'a Lu<N>,
    a_q: &'a SMatrix<f64, N, N>,
    dh: f64,
    options: &'a Options,
}

impl<const N: usize> Newton<'_, N> {
    /// `(I − dh J)⁻¹ r` on `(q, v)`; the energy integrals pass through.
    fn apply_inverse(&self, r: &PhaseState<N>) -> PhaseState<N> {
        let v: SVector<f64, N> = self.lu.solve(&(r.v + self.a_q * r.q * self.dh));
        PhaseState {
            q: r.q + v * self.dh,
            v,
            work: r.work,
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
    ) -> Result<Option<(PhaseState<N>, PhaseState<N>)>, SolverError> {
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
                // The energy integrals follow explicitly from the converged stage.
                y.work[0] = base.work[0] + self.dh * f.work[0];
                y.work[1] = base.work[1] + self.dh * f.work[1];
                return Ok(Some((y, f)));
            }
        }
        Ok(None)
    }
}
