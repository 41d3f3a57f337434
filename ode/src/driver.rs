//! The loop every method runs in: ask the method's [`Stepper`] for steps,
//! end exactly at `t_end`, give up after `Options::max_steps` or below the
//! minimum step, and handle events — locate the earliest crossing in an
//! accepted step, cut the step there, show it to the observer, let the
//! problem act on the event, then stop or restart.
//!
//! The per-step path is generic (no dynamic dispatch of the dense output)
//! and allocates nothing for fixed-size states.

use super::events::{EventAction, EventTracker};
use super::stops;
use super::{
    DenseStep, Observer, OdeProblem, OdeVector, Options, Outcome, SolverError, Stats, evaluate,
    initial_step,
};

/// A step's dense output that can be cut short at an event.
pub(crate) trait Truncate {
    /// The same interpolant, reported as ending at `end`.
    fn truncate(self, end: f64) -> Self;
}

/// What became of an attempted step.
pub(crate) enum Attempt<D> {
    /// Accepted: its dense output; the stepper holds its end state.
    Accepted(D),
    /// Rejected: try again with this step.
    Rejected(f64),
}

/// One method: how it takes a step. The driver owns the state `(t, y)` and
/// `f = F(t, y)`; the stepper owns the end of the step it attempted.
pub(crate) trait Stepper<Y: OdeVector, P: OdeProblem<Y>> {
    /// The dense output of an accepted step.
    type Dense: DenseStep<Y> + Truncate;

    /// Attempts a step of size `h` from `(t, y)` with `F(t, y) = f`.
    fn attempt(
        &mut self,
        problem: &mut P,
        start: (f64, &Y, &Y),
        h: f64,
        stats: &mut Stats,
    ) -> Result<Attempt<Self::Dense>, SolverError<P::Error>>;

    /// The end state of the accepted step and `F` there.
    fn end(&self) -> &Y;

    /// Moves to the end of the accepted step of size `h` (swapping its end
    /// state and `F` there into `y` and `f`) and returns the next step.
    fn advance(&mut self, y: &mut Y, f: &mut Y, h: f64) -> f64;

    /// The step to go on with after an event restarted the step sequence
    /// (the accepted step was `h`).
    fn restart(&mut self, h: f64) -> f64;
}

/// The first step: `Options::fixed_step`, else `Options::initial_step`, else
/// Hairer's estimate; at most `Options::max_step`.
fn first_step<Y: OdeVector, P: OdeProblem<Y>>(
    problem: &mut P,
    (t, y, f): (f64, &Y, &Y),
    span: f64,
    options: &Options,
    stats: &mut Stats,
) -> Result<f64, SolverError<P::Error>> {
    let h = match options.fixed_step.or(options.initial_step) {
        Some(h) => h,
        None => initial_step(problem, t, y, f, span, options, stats)?,
    };
    Ok(h.min(options.max_step))
}

/// Integrates `problem` from `(t0, y0)` to `t_end` with `stepper`, calling
/// `observer` with the problem and every accepted step (truncated at events).
pub(crate) fn run<Y, P, S>(
    stepper: &mut S,
    problem: &mut P,
    (t0, y0): (f64, Y),
    t_end: f64,
    options: &Options,
    observer: Observer<'_, P, Y>,
) -> Result<Outcome<Y>, SolverError<P::Error>>
where
    Y: OdeVector,
    P: OdeProblem<Y>,
    S: Stepper<Y, P>,
{
    let (mut t, mut y) = (t0, y0);
    let mut f = y.clone();
    let mut driver = Driver::start(problem, t, &y, &mut f, t_end, options)?;
    let mut h = first_step(problem, (t, &y, &f), t_end - t, options, &mut driver.stats)?;
    while let Some(step) = driver.next_step(t, h)? {
        h = driver.to_stop(problem, t, step);
        let dense = match stepper.attempt(problem, (t, &y, &f), h, &mut driver.stats)? {
            Attempt::Rejected(shorter) => {
                driver.stats.rejected_steps += 1;
                h = shorter;
                continue;
            }
            Attempt::Accepted(dense) => dense,
        };
        driver.stats.accepted_steps += 1;
        let point = Point {
            t: &mut t,
            y: &mut y,
            f: &mut f,
        };
        match driver.finish_step(problem, dense, stepper.end(), point, observer)? {
            StepEnd::Next => {
                t += h;
                h = stepper.advance(&mut y, &mut f, h);
            }
            StepEnd::Restarted => h = stepper.restart(h),
            StepEnd::Stopped(k) => return Ok(driver.outcome(t, y, Some(k))),
        }
    }
    Ok(driver.outcome(t, y, None))
}

/// Where the integration stands: time, state and `F(t, y)`.
struct Point<'a, Y> {
    t: &'a mut f64,
    y: &'a mut Y,
    f: &'a mut Y,
}

/// How an accepted step ended.
enum StepEnd {
    /// No event: the step was observed; go on from its end.
    Next,
    /// An event restarted the step sequence from the point written back.
    Restarted,
    /// Event `k` stopped the integration at the point written back.
    Stopped(usize),
}

/// What the loop keeps besides the state: statistics, the end of the
/// interval, the step limits and the event functions.
struct Driver<Y> {
    stats: Stats,
    t_end: f64,
    end_tolerance: f64,
    max_steps: usize,
    min_step: f64,
    events: EventTracker,
    scratch: Y,
    /// Steps are fixed: they do not end at the problem's stops.
    fixed: bool,
}

impl<Y: OdeVector> Driver<Y> {
    /// Checks `options`, writes `F(t0, y0)` into `f` and evaluates the event
    /// functions at the start.
    fn start<P: OdeProblem<Y>>(
        problem: &mut P,
        t0: f64,
        y0: &Y,
        f: &mut Y,
        t_end: f64,
        options: &Options,
    ) -> Result<Driver<Y>, SolverError<P::Error>> {
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
            fixed: options.fixed_step.is_some(),
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
    fn next_step<E>(&self, t: f64, h: f64) -> Result<Option<f64>, SolverError<E>> {
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

    /// The step `h` from `t`, ended at the problem's next stop where
    /// [`stops::step`] says so; fixed steps are kept.
    #[inline]
    fn to_stop<P: OdeProblem<Y>>(&self, problem: &mut P, t: f64, h: f64) -> f64 {
        match self.fixed {
            true => h,
            false => stops::step(problem, t, h),
        }
    }

    /// Finishes an accepted step with dense output `dense` from `point` to
    /// `y1`. Without an event the observer sees the step and the caller moves
    /// to its end ([`StepEnd::Next`]). At the earliest event the observer
    /// sees the step cut there, `point` becomes the state at the event as
    /// the problem's [`OdeProblem::on_event`] leaves it, and the integration
    /// stops there or restarts from it (with `F` and the event functions
    /// evaluated anew).
    fn finish_step<P, D>(
        &mut self,
        problem: &mut P,
        dense: D,
        y1: &Y,
        point: Point<'_, Y>,
        observer: Observer<'_, P, Y>,
    ) -> Result<StepEnd, SolverError<P::Error>>
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
    fn outcome(self, t: f64, y: Y, stopped_by: Option<usize>) -> Outcome<Y> {
        Outcome {
            t,
            y,
            stats: self.stats,
            stopped_by,
        }
    }
}
