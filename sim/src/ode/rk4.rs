//! The classical 4th-order Runge–Kutta method with a fixed step, for
//! reference runs; dense output is the cubic Hermite interpolant of the step.

use super::driver::{Driver, Point, StepEnd};
pub use super::hermite::Hermite;
use super::{DenseStep, OdeProblem, OdeVector, Options, Outcome, SolverError, evaluate};

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
    let (mut t, mut y) = (t0, y0);
    let mut k1 = y.clone();
    let mut driver = Driver::start(problem, t, &y, &mut k1, t_end, options)?;
    let (mut k2, mut k3, mut k4) = (y.clone(), y.clone(), y.clone());
    let (mut stage, mut y1) = (y.clone(), y.clone());
    while let Some(h) = driver.next_step(t, h_fixed)? {
        let stats = &mut driver.stats;
        stage.set_combination(&y, &[(0.5 * h, &k1)]);
        evaluate(problem, t + 0.5 * h, &stage, &mut k2, stats)?;
        stage.set_combination(&y, &[(0.5 * h, &k2)]);
        evaluate(problem, t + 0.5 * h, &stage, &mut k3, stats)?;
        stage.set_combination(&y, &[(h, &k3)]);
        evaluate(problem, t + h, &stage, &mut k4, stats)?;
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
        evaluate(problem, t + h, &y1, &mut f1, stats)?;
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
        let point = Point {
            t: &mut t,
            y: &mut y,
            f: &mut k1,
        };
        match driver.finish_step(problem, dense, &y1, point, observer)? {
            StepEnd::Next => {}
            StepEnd::Restarted => continue,
            StepEnd::Stopped(k) => return Ok(driver.outcome(t, y, Some(k))),
        }
        t += h;
        y = y1.clone();
        k1 = f1;
    }
    Ok(driver.outcome(t, y, None))
}
