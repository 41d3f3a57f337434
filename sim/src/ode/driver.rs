//! What every integrator does around its own steps: end exactly at `t_end`,
//! give up after `Options::max_steps`, and handle events — locate the
//! earliest crossing in an accepted step, cut the step there, show it to the
//! observer, let the problem act on the event, then stop or restart.
//!
//! The per-step path is generic (no dynamic dispatch of the dense output)
//! and allocates nothing for fixed-size states.

use super::events::{EventAction, EventTracker};
use super::{DenseStep, OdeProblem, OdeVector, Options, Outcome, SolverError, Stats, evaluate};

/// A step's dense output that can be cut short at an event.
pub(crate) trait Truncate {
    /// The same interpolant, reported as ending at `end`.
    fn truncate(self, end: f64) -> Self;
}

/// Where the integration stands: time, state and `F(t, y)`.
pub(crate) struct Point<'a, Y> {
    pub t: &'a mut f64,
    pub y: &'a mut Y,
    pub f: &'a mut Y,
}

/// How an accepted step ended.
pub(crate) enum StepEnd {
    /// No event: the step was observed; go on from its end.
    Next,
    /// An event restarted the step sequence from the point written back.
    Restarted,
    /// Event `k` stopped the integration at the point written back.
    Stopped(usize),
}

/// The state an integrator shares with the others: its statistics, the
/// end of the interval, the step limit and the event functions.
pub(crate) struct Driver<Y> {
    pub stats: Stats,
    t_end: f64,
    end_tolerance: f64,
    max_steps: usize,
    min_step: f64,
    events: EventTracker,
    scratch: Y,
}

impl<Y: OdeVector> Driver<Y> {
    /// Checks `options`, writes `F(t0, y0)` into `f` and evaluates the event
    /// functions at the start.
    pub fn start<P: OdeProblem<Y>>(
        problem: &mut P,
        t0: f64,
        y0: &Y,
        f: &mut Y,
        t_end: f64,
        options: &Options,
    ) -> Result<Driver<Y>, SolverError> {
        options.validate()?;
        let mut stats = Stats::default();
        evaluate(problem, t0, y0, f, &mut stats)?;
        let mut events = EventTracker::new(problem.event_count());
        events.reset(problem, t0, y0, f)?;
        Ok(Driver {
            stats,
            t_end,
            end_tolerance: 4.0 * f64::EPSILON * t_end.abs().max(1.0),
            max_steps: options.max_steps,
            min_step: options.min_step,
            events,
            scratch: y0.clone(),
        })
    }

    /// The step to attempt from `t` given the step `h` the method wants:
    /// `None` once `t_end` is reached, `h` stretched or shortened to land on
    /// `t_end` when that is within 1% of it (no sliver of a last step), or
    /// an error after `max_steps` attempted steps or when `h` is below
    /// `Options::min_step` or too small to move `t` (`h ≤ 10 ε |t|`, as in
    /// Hairer's DOPRI5): the solution is no longer smooth at this scale, as
    /// near a finite-time blow-up.
    #[inline]
    pub fn next_step(&self, t: f64, h: f64) -> Result<Option<f64>, SolverError> {
        let remaining = self.t_end - t;
        if remaining.is_nan() || remaining <= self.end_tolerance {
            return Ok(None);
        }
        if self.stats.accepted_steps + self.stats.rejected_steps >= self.max_steps {
            return Err(SolverError::MaxSteps {
                t,
                steps: self.max_steps,
            });
        }
        if !(h >= self.min_step && h > 10.0 * f64::EPSILON * t.abs()) {
            return Err(SolverError::StepSizeUnderflow { t, h });
        }
        Ok(Some(if t + 1.01 * h >= self.t_end {
            remaining
        } else {
            h
        }))
    }

    /// Finishes an accepted step with dense output `dense` from `point` to
    /// `y1`. Without an event the observer sees the step and the caller moves
    /// to its end ([`StepEnd::Next`]). At the earliest event the observer
    /// sees the step cut there, `point` becomes the state at the event as
    /// the problem's [`OdeProblem::on_event`] leaves it, and the integration
    /// stops there or restarts from it (with `F` and the event functions
    /// evaluated anew).
    pub fn finish_step<P, D>(
        &mut self,
        problem: &mut P,
        dense: D,
        y1: &Y,
        point: Point<'_, Y>,
        observer: &mut dyn FnMut(&mut P, &dyn DenseStep<Y>),
    ) -> Result<StepEnd, SolverError>
    where
        P: OdeProblem<Y>,
        D: DenseStep<Y> + Truncate,
    {
        let Some((k, te)) = self.events.locate(problem, &dense, y1, &mut self.scratch)? else {
            observer(problem, &dense);
            self.events.advance();
            return Ok(StepEnd::Next);
        };
        let truncated = dense.truncate(te);
        observer(problem, &truncated);
        truncated.eval(te, point.y);
        *point.t = te;
        self.stats.events.push((k, te));
        match problem.on_event(k, te, point.y) {
            EventAction::Stop => Ok(StepEnd::Stopped(k)),
            EventAction::Restart => {
                evaluate(problem, te, point.y, point.f, &mut self.stats)?;
                self.events.reset(problem, te, point.y, point.f)?;
                Ok(StepEnd::Restarted)
            }
        }
    }

    /// The result of the integration, ended at `(t, y)`.
    pub fn outcome(self, t: f64, y: Y, stopped_by: Option<usize>) -> Outcome<Y> {
        Outcome {
            t,
            y,
            stats: self.stats,
            stopped_by,
        }
    }
}
