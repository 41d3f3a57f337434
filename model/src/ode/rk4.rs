//! The classical 4th-order Runge–Kutta method with a fixed step, for
//! reference runs; dense output is the cubic Hermite interpolant of the step.

use super::dopri5::Outcome;
use super::events::{EventAction, EventTracker};
use super::{DenseStep, OdeProblem, OdeVector, Options, SolverError, Stats, evaluate};

/// Cubic Hermite interpolation between `(y0, f0)` at `t0` and `(y1, f1)` at
/// `t0 + h`, reported as covering `[t0, end]` (`end < t0 + h` at an event).
pub struct Hermite<Y> {
    pub t0: f64,
    pub h: f64,
    pub end: f64,
    pub y0: Y,
    pub f0: Y,
    pub y1: Y,
    pub f1: Y,
}

impl<Y: OdeVector> DenseStep<Y> for Hermite<Y> {
    fn t0(&self) -> f64 {
        self.t0
    }

    fn t1(&self) -> f64 {
        self.end
    }

    fn eval(&self, t: f64, out: &mut Y) {
        let h = self.h;
        let s = (t - self.t0) / h;
        let (s2, s3) = (s * s, s * s * s);
        out.set_sum(&[
            (2.0 * s3 - 3.0 * s2 + 1.0, &self.y0),
            (h * (s3 - 2.0 * s2 + s), &self.f0),
            (-2.0 * s3 + 3.0 * s2, &self.y1),
            (h * (s3 - s2), &self.f1),
        ]);
    }
}

/// Integrates with steps of `options.fixed_step` (the last one shortened to
/// land on `t_end`); events are located on the Hermite interpolant.
pub fn integrate<Y: OdeVector, P: OdeProblem<Y>>(
    problem: &mut P,
    t0: f64,
    y0: Y,
    t_end: f64,
    options: &Options,
    observer: &mut dyn FnMut(&mut P, &dyn DenseStep<Y>),
) -> Result<Outcome<Y>, SolverError> {
    options.validate()?;
    let h_fixed = options
        .fixed_step
        .ok_or_else(|| SolverError::InvalidOptions("RK4 needs a fixed step size".to_string()))?;
    let mut stats = Stats::default();
    let (mut t, mut y) = (t0, y0);
    let (mut k1, mut k2, mut k3, mut k4) = (y.clone(), y.clone(), y.clone(), y.clone());
    let (mut stage, mut y1, mut scratch) = (y.clone(), y.clone(), y.clone());
    evaluate(problem, t, &y, &mut k1, &mut stats)?;
    let mut events = EventTracker::new(problem.event_count());
    events.reset(problem, t, &y, &k1)?;
    let end_tolerance = 4.0 * f64::EPSILON * t_end.abs().max(1.0);
    while t_end - t > end_tolerance {
        if stats.accepted_steps >= options.max_steps {
            return Err(SolverError::MaxSteps {
                t,
                steps: options.max_steps,
            });
        }
        let h = if t + 1.01 * h_fixed >= t_end {
            t_end - t
        } else {
            h_fixed
        };
        stage.set_combination(&y, &[(0.5 * h, &k1)]);
        evaluate(problem, t + 0.5 * h, &stage, &mut k2, &mut stats)?;
        stage.set_combination(&y, &[(0.5 * h, &k2)]);
        evaluate(problem, t + 0.5 * h, &stage, &mut k3, &mut stats)?;
        stage.set_combination(&y, &[(h, &k3)]);
        evaluate(problem, t + h, &stage, &mut k4, &mut stats)?;
        y1.set_combination(
            &y,
            &[
                (h / 6.0, &k1),
                (h / 3.0, &k2),
                (h / 3.0, &k3),
                (h / 6.0, &k4),
            ],
        );
        let mut f1 = y.clone();
        evaluate(problem, t + h, &y1, &mut f1, &mut stats)?;
        stats.accepted_steps += 1;
        let dense = Hermite {
            t0: t,
            h,
            end: t + h,
            y0: y.clone(),
            f0: k1.clone(),
            y1: y1.clone(),
            f1: f1.clone(),
        };
        if let Some((k, te)) = events.locate(problem, &dense, &y1, &mut scratch)? {
            let truncated = Hermite { end: te, ..dense };
            observer(problem, &truncated);
            let mut ye = y.clone();
            truncated.eval(te, &mut ye);
            stats.events.push((k, te));
            match problem.on_event(k, te, &mut ye) {
                EventAction::Stop => {
                    return Ok(Outcome {
                        t: te,
                        y: ye,
                        stats,
                        stopped_by: Some(k),
                    });
                }
                EventAction::Restart => {
                    t = te;
                    y = ye;
                    evaluate(problem, t, &y, &mut k1, &mut stats)?;
                    events.reset(problem, t, &y, &k1)?;
                    continue;
                }
            }
        }
        observer(problem, &dense);
        events.advance();
        t += h;
        y = y1.clone();
        k1 = f1;
    }
    Ok(Outcome {
        t,
        y,
        stats,
        stopped_by: None,
    })
}
