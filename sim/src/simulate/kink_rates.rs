//! The accelerations of the samples inside a step whose stages took the
//! smooth stand-ins of time tables (`[simulation] time_kinks =
//! "smoothed"`, [`super::kinks`]).
//!
//! Such a step's dense output follows the model driven by the stand-in
//! `P` of each input `u` over the step, so the derivative of its
//! interpolant of `q̇` is that model's `q̈`: smooth where the table's own
//! `q̈` has a kink at each of the table's points. The two differ by what the
//! difference of the inputs does at the same state,
//!
//! `q̈(u) − q̈(P) = Σ_i C_i (u_i − P_i) + O((u − P)²)`, `C_i = ∂q̈/∂u_i`,
//!
//! so a sample takes the interpolated `q̈` plus that sum: the table's kinks
//! come back, at the cost of one solve of `M q̈ = f` per step and one per
//! input that differs from its stand-in at a sample, instead of one per
//! sample. `C_i` is the difference quotient at the middle of the step with
//! `P_i` moved by the largest `|u_i − P_i|` of the step's samples, so that
//! the quotient spans the differences it is applied to: exact for an input
//! the forces are affine in, and off by `O((u − P)²)` otherwise, like the
//! sum itself. Over one step `C` changes by `O(h)` of itself, times a
//! difference `u − P` that is already small: the samples agree with those
//! solved at every sample to the accuracy of the interpolation.

use super::CrashProblem;
use crate::components::{BoundInputs, StandIn};
use crate::ode::{DenseStep, PhaseState};
use lagrangian_runtime::LagrangianSystem;
use nalgebra::SVector;

/// What turns a smoothed step's interpolated `q̈` into that of the inputs
/// as they are, sample by sample.
pub(super) struct KinkCorrection<const N: usize> {
    /// `∂q̈/∂u_i` of each input that differs from its stand-in at a sample.
    sensitivities: Vec<SVector<f64, N>>,
    /// `u_i − P_i` by input of `sensitivities` (rows) and by sample.
    gaps: Vec<f64>,
    /// The number of samples.
    samples: usize,
}

impl<const N: usize> KinkCorrection<N> {
    /// The correction of the samples at `times` inside `step`, whose
    /// stages took the stand-ins of `problem`'s inputs of time; `None` when
    /// they did not (another step, or none were taken), or an input or a
    /// solve fails: the samples are then solved, and report the failure.
    pub(super) fn of<S: LagrangianSystem<N>>(
        problem: &mut CrashProblem<N, S>,
        step: &dyn DenseStep<PhaseState<N>>,
        times: &[f64],
    ) -> Option<KinkCorrection<N>> {
        if !problem.retake_stand_ins(step.t0()) {
            return None;
        }
        let correction = Self::with_stand_ins(problem, step, times);
        problem.inputs.end_stand_ins();
        correction
    }

    /// [`KinkCorrection::of`] with the stand-ins of the step taken.
    fn with_stand_ins<S: LagrangianSystem<N>>(
        problem: &mut CrashProblem<N, S>,
        step: &dyn DenseStep<PhaseState<N>>,
        times: &[f64],
    ) -> Option<KinkCorrection<N>> {
        let (moved, gaps) = gaps(&problem.inputs, times)?;
        Some(KinkCorrection {
            sensitivities: sensitivities(problem, step, &moved)?,
            gaps,
            samples: times.len(),
        })
    }

    /// What sample `k` (of the `times` it was made for) adds to its
    /// interpolated `q̈`.
    pub(super) fn at(&self, k: usize) -> SVector<f64, N> {
        let gaps = self.gaps.iter().skip(k).step_by(self.samples);
        (self.sensitivities.iter().zip(gaps)).fold(SVector::zeros(), |sum, (c, gap)| sum + c * *gap)
    }
}

/// An input that differs from its stand-in at a sample.
#[derive(Clone, Copy)]
struct Moved {
    input: usize,
    stand_in: StandIn,
    /// The largest `|u − P|` at the samples.
    by: f64,
}

/// The inputs that differ from their stand-ins at a sample of `times`,
/// and the differences `u − P` by input and by sample; `None` where an
/// input has no finite value.
fn gaps(inputs: &BoundInputs, times: &[f64]) -> Option<(Vec<Moved>, Vec<f64>)> {
    let (mut moved, mut gaps) = (Vec::new(), Vec::new());
    for (input, cubic) in inputs.stand_ins() {
        let mut largest = 0.0f64;
        gaps.reserve(times.len());
        for &t in times {
            let gap = inputs.own_value_of_time(input, t)? - cubic.at(t);
            if !gap.is_finite() {
                return None;
            }
            largest = largest.max(gap.abs());
            gaps.push(gap);
        }
        if largest > 0.0 {
            moved.push(Moved {
                input,
                stand_in: cubic,
                by: largest,
            });
        } else {
            gaps.truncate(gaps.len() - times.len());
        }
    }
    Some((moved, gaps))
}

/// `∂q̈/∂u` of each of the `moved` inputs at the middle of `step`: the
/// difference quotient with its stand-in moved `by`.
fn sensitivities<const N: usize, S: LagrangianSystem<N>>(
    problem: &mut CrashProblem<N, S>,
    step: &dyn DenseStep<PhaseState<N>>,
    moved: &[Moved],
) -> Option<Vec<SVector<f64, N>>> {
    if moved.is_empty() {
        return Some(Vec::new());
    }
    let t = 0.5 * (step.t0() + step.t1());
    let mut y = PhaseState::zeros();
    step.eval(t, &mut y);
    problem.inputs.load(&y.z);
    let base = problem.accelerations(t, &y.q, &y.v).ok()?;
    let mut sensitivities = Vec::with_capacity(moved.len());
    for &Moved {
        input,
        stand_in,
        by,
    } in moved
    {
        problem.inputs.stand_in(input, stand_in.shifted(by));
        let shifted = problem.accelerations(t, &y.q, &y.v);
        problem.inputs.stand_in(input, stand_in);
        sensitivities.push((shifted.ok()? - base) / by);
    }
    Some(sensitivities)
}
