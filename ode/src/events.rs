//! Detecting zero crossings of event functions within a step and locating
//! them on the dense output.

use super::{DenseStep, OdeProblem, OdeVector, SolverError};

/// Which zero crossings of an event function trigger it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Direction {
    /// From negative to non-negative.
    Rising,
    /// From positive to non-positive.
    Falling,
    /// Both: any change of sign.
    Either,
}

/// What the integration does after an event.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum EventAction {
    /// End the integration at the event.
    Stop,
    /// Go on from the event: the step sequence restarts there (the problem's
    /// mode, parameters or state may have changed).
    Restart,
}

/// The time tolerance of event location: 1e-12 s, or a few ulps of `t`.
fn time_tolerance(t: f64) -> f64 {
    1e-12f64.max(4.0 * f64::EPSILON * t.abs())
}

impl Direction {
    /// Whether a change of an event function from `before` to `after`
    /// is a crossing that triggers it.
    pub fn crosses(self, before: f64, after: f64) -> bool {
        match self {
            Direction::Rising => before < 0.0 && after >= 0.0,
            Direction::Falling => before > 0.0 && after <= 0.0,
            Direction::Either => (before < 0.0 && after >= 0.0) || (before > 0.0 && after <= 0.0),
        }
    }
}

/// Event function values at the start and end of the current step.
pub(crate) struct EventTracker {
    start: Vec<f64>,
    middle: Vec<f64>,
    end: Vec<f64>,
    probe: Vec<f64>,
}

impl EventTracker {
    pub fn new(count: usize) -> EventTracker {
        EventTracker {
            start: vec![0.0; count],
            middle: vec![0.0; count],
            end: vec![0.0; count],
            probe: vec![0.0; count],
        }
    }

    fn is_empty(&self) -> bool {
        self.start.is_empty()
    }

    /// Evaluates the event functions at the start of a step sequence.
    ///
    /// A function that is exactly zero there (typically right after its own
    /// event) takes the sign it has just after `t`, found by an Euler probe
    /// along `f = y'`, so that the crossing it just made is not seen again
    /// and the next one is not missed.
    pub fn reset<Y: OdeVector, P: OdeProblem<Y>>(
        &mut self,
        problem: &mut P,
        t: f64,
        y: &Y,
        f: &Y,
    ) -> Result<(), SolverError<P::Error>> {
        if self.is_empty() {
            return Ok(());
        }
        events_at(problem, t, y, &mut self.start)?;
        check_finite(problem, &self.start, t)?;
        if self.start.contains(&0.0) {
            let delta = 1e-9 * t.abs().max(1.0);
            let mut ahead = y.clone();
            ahead.set_combination(y, &[(delta, f)]);
            events_at(problem, t + delta, &ahead, &mut self.probe)?;
            for (g, probe) in self.start.iter_mut().zip(&self.probe) {
                if *g == 0.0 {
                    *g = *probe;
                }
            }
        }
        Ok(())
    }

    /// The earliest event crossing in the accepted step, located to
    /// `|Δt| ≤ 1e-12`, as `(event, time after the crossing)`.
    pub fn locate<Y: OdeVector, P: OdeProblem<Y>>(
        &mut self,
        problem: &mut P,
        dense: &dyn DenseStep<Y>,
        y_end: &Y,
        scratch: &mut Y,
    ) -> Result<Option<(usize, f64)>, SolverError<P::Error>> {
        if self.is_empty() {
            return Ok(None);
        }
        let (t0, t1) = (dense.t0(), dense.t1());
        events_at(problem, t1, y_end, &mut self.end)?;
        check_finite(problem, &self.end, t1)?;
        // The midpoint catches a function that crosses and returns within one step.
        let tm = 0.5 * (t0 + t1);
        dense.eval(tm, scratch);
        events_at(problem, tm, scratch, &mut self.middle)?;
        check_finite(problem, &self.middle, tm)?;
        let mut earliest: Option<(usize, f64)> = None;
        for k in 0..self.start.len() {
            // Any crossing is a change of sign: the direction is asked
            // only then.
            let (start, middle, end) = (self.start[k], self.middle[k], self.end[k]);
            let either = Direction::Either;
            if !either.crosses(start, middle) && !either.crosses(middle, end) {
                continue;
            }
            let direction = problem.event_direction(k);
            let bracket = if direction.crosses(start, middle) {
                ((t0, start), (tm, middle))
            } else if direction.crosses(middle, end) {
                ((tm, middle), (t1, end))
            } else {
                continue;
            };
            let t = self.illinois(problem, dense, scratch, k, bracket.0, bracket.1)?;
            if earliest.is_none_or(|(_, limit)| t < limit) {
                earliest = Some((k, t));
            }
        }
        Ok(earliest)
    }

    /// Makes the step's end values the next step's start values.
    pub fn advance(&mut self) {
        std::mem::swap(&mut self.start, &mut self.end);
    }

    /// Illinois (modified regula falsi) on `g_k` along the dense output; the
    /// bracket keeps `a` strictly before the crossing and `b` after it.
    #[allow(clippy::too_many_arguments)]
    fn illinois<Y: OdeVector, P: OdeProblem<Y>>(
        &mut self,
        problem: &mut P,
        dense: &dyn DenseStep<Y>,
        scratch: &mut Y,
        k: usize,
        (mut a, mut ga): (f64, f64),
        (mut b, mut gb): (f64, f64),
    ) -> Result<f64, SolverError<P::Error>> {
        let before_sign = ga.signum();
        let mut side = 0i8;
        let (mut halved_at, mut since) = (b - a, 0);
        for _ in 0..200 {
            if b - a <= time_tolerance(b) {
                return Ok(b);
            }
            let mut c = (a * gb - b * ga) / (gb - ga);
            if !(c > a && c < b) {
                c = 0.5 * (a + b);
            }
            // Illinois converges superlinearly, with its new point close to
            // an end of the bracket; where it stalls (one end stuck, the
            // bracket shrinking slowly), bisect: whenever the bracket has
            // not halved in three iterations.
            let width = b - a;
            if width <= 0.5 * halved_at {
                (halved_at, since) = (width, 0);
            } else {
                since += 1;
            }
            if since >= 3 {
                c = 0.5 * (a + b);
                (halved_at, since) = (width, 0);
            }
            dense.eval(c, scratch);
            let gc = problem
                .event(k, c, scratch, &mut self.probe)
                .map_err(|error| SolverError::Rhs { t: c, error })?;
            if !gc.is_finite() {
                return Err(SolverError::NonFinite {
                    t: c,
                    what: problem.name_event(k, gc),
                });
            }
            if gc.signum() == before_sign && gc != 0.0 {
                a = c;
                ga = gc;
                if side == -1 {
                    gb *= 0.5;
                }
                side = -1;
            } else {
                b = c;
                gb = gc;
                if side == 1 {
                    ga *= 0.5;
                }
                side = 1;
            }
        }
        Err(SolverError::EventNotLocated { t: b, event: k })
    }
}

/// The event functions at `(t, y)` into `g`, a failure reported at `t`.
fn events_at<Y: OdeVector, P: OdeProblem<Y>>(
    problem: &mut P,
    t: f64,
    y: &Y,
    g: &mut [f64],
) -> Result<(), SolverError<P::Error>> {
    problem
        .events(t, y, g)
        .map_err(|error| SolverError::Rhs { t, error })
}

/// `Err` naming the first of the event functions `values` at `t` that is
/// not finite, as `problem` names it.
fn check_finite<Y: OdeVector, P: OdeProblem<Y>>(
    problem: &P,
    values: &[f64],
    t: f64,
) -> Result<(), SolverError<P::Error>> {
    match values.iter().position(|g| !g.is_finite()) {
        None => Ok(()),
        Some(k) => Err(SolverError::NonFinite {
            t,
            what: problem.name_event(k, values[k]),
        }),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::PhaseState;

    /// A step from 0 to its end (1 ms unless said) whose dense output is
    /// irrelevant.
    struct Step(f64);
    impl DenseStep<PhaseState<1>> for Step {
        fn t0(&self) -> f64 {
            0.0
        }
        fn t1(&self) -> f64 {
            self.0
        }
        fn uncut_end(&self) -> f64 {
            self.0
        }
        fn eval(&self, _t: f64, out: &mut PhaseState<1>) {
            *out = PhaseState::zeros();
        }
    }

    /// A problem that is one event function `g(t, call number)` (from 1).
    struct OneEvent<G: FnMut(f64, usize) -> f64> {
        g: G,
        calls: usize,
    }
    impl<G: FnMut(f64, usize) -> f64> OdeProblem<PhaseState<1>> for OneEvent<G> {
        type Error = std::convert::Infallible;

        fn rhs(
            &mut self,
            _t: f64,
            _y: &PhaseState<1>,
            dy: &mut PhaseState<1>,
        ) -> Result<(), Self::Error> {
            *dy = PhaseState::zeros();
            Ok(())
        }
        fn event_count(&self) -> usize {
            1
        }
        fn events(&mut self, t: f64, _y: &PhaseState<1>, g: &mut [f64]) -> Result<(), Self::Error> {
            self.calls += 1;
            g[0] = (self.g)(t, self.calls);
            Ok(())
        }
    }

    /// Resets a tracker at t = 0 and locates the crossing in [`Step`].
    fn locate_in_step<G: FnMut(f64, usize) -> f64>(
        problem: &mut OneEvent<G>,
    ) -> Result<Option<(usize, f64)>, SolverError<std::convert::Infallible>> {
        locate_in(problem, &Step(1e-3))
    }

    /// Resets a tracker at t = 0 and locates the crossing in `step`.
    fn locate_in<G: FnMut(f64, usize) -> f64>(
        problem: &mut OneEvent<G>,
        step: &Step,
    ) -> Result<Option<(usize, f64)>, SolverError<std::convert::Infallible>> {
        let mut tracker = EventTracker::new(1);
        let y = PhaseState::<1>::zeros();
        tracker.reset(problem, 0.0, &y, &y)?;
        let mut scratch = y;
        tracker.locate(problem, step, &y, &mut scratch)
    }

    /// An event function that stalls regula falsi: negative at the start
    /// and the midpoint, positive at the end, and at every probe negative and
    /// just small enough that the next regula falsi point lands 3% into the
    /// bracket (Illinois halves the stale end's value each time), so that
    /// regula falsi alone would shrink the bracket by 3% per iteration.
    fn stalling(call: usize) -> f64 {
        let r: f64 = 0.03;
        match call {
            1 => -1.0, // start (reset)
            2 => 1.0,  // end of the step
            3 => -1.0, // midpoint: the crossing is in the second half
            k => -r / (1.0 - r) * 0.5f64.powi(k as i32 - 4),
        }
    }

    /// The root finder bisects when the bracket has not halved in three
    /// iterations: the crossing of [`stalling`] (at the step's end, where it
    /// turns positive) is found to 1e-12 s within four iterations per halving
    /// of the 0.5 ms bracket (three of regula falsi, one of bisection),
    /// 4 · 29.
    #[test]
    fn an_event_that_stalls_regula_falsi_is_located() {
        let mut problem = OneEvent {
            g: |_t, call| stalling(call),
            calls: 0,
        };
        assert_eq!(locate_in_step(&mut problem), Ok(Some((0, 1e-3))));
        // Start, end, midpoint and the iterations.
        assert!(problem.calls <= 3 + 4 * 29, "{} calls", problem.calls);
    }

    /// [`stalling`] mirrored (positive at the midpoint and every probe, so
    /// the bracket closes in on the start) over a step of 1e9 s: 200
    /// iterations, 50 halvings, cannot narrow 5e8 s to 1e-12 s. An error,
    /// not a loop.
    #[test]
    fn an_event_that_cannot_be_bracketed_is_an_error_not_a_loop() {
        let mut problem = OneEvent {
            g: |_t, call| match call {
                1 => -1.0,
                2 | 3 => 1.0,
                k => -stalling(k),
            },
            calls: 0,
        };
        // The error names the bracket's upper end where it stopped: the
        // 5e8 s first half halved at least 50 times, not down to 1e-12 s.
        let result = locate_in(&mut problem, &Step(1e9));
        assert!(
            matches!(
                result,
                Err(SolverError::EventNotLocated { t, event: 0 })
                    if t > 1e-12 && t <= 5e8 * 0.5f64.powi(50)
            ),
            "{result:?}"
        );
        // Start, end, midpoint and the 200 iterations.
        assert_eq!(problem.calls, 203);
    }

    /// A crossing of a smooth function is located to 1e-12 s.
    #[test]
    fn a_smooth_crossing_is_located() {
        let mut problem = OneEvent {
            g: |t, _| (t - 3.3e-4).sinh() * 1e3,
            calls: 0,
        };
        let (k, t) = locate_in_step(&mut problem).unwrap().unwrap();
        assert_eq!(k, 0);
        assert!(t >= 3.3e-4 && t - 3.3e-4 <= 1e-12, "{t}");
    }

    /// An event function that is not finite at the step's end, or at a
    /// point of the bracket, is an error that says which function and its
    /// value, as the problem names it (by default by its index).
    #[test]
    fn an_event_function_that_is_not_finite_is_named() {
        let mut at_end = OneEvent {
            g: |_t, call| if call == 1 { -1.0 } else { f64::NAN },
            calls: 0,
        };
        let result = locate_in_step(&mut at_end);
        let Err(SolverError::NonFinite { t, what }) = result else {
            panic!("{result:?}");
        };
        assert_eq!((t, what.as_str()), (1e-3, "event function 0 (NaN)"));
        // Start, end and midpoint finite, then -inf at the first probe.
        let mut in_bracket = OneEvent {
            g: |_t, call| match call {
                1 | 3 => -1.0,
                2 => 1.0,
                _ => f64::NEG_INFINITY,
            },
            calls: 0,
        };
        let result = locate_in_step(&mut in_bracket);
        let Err(SolverError::NonFinite { t, what }) = result else {
            panic!("{result:?}");
        };
        assert!(t > 0.5e-3 && t < 1e-3, "{t}");
        assert_eq!(what, "event function 0 (-inf)");
    }
}
