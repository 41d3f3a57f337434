//! Where a step ends at the problem's stops (the kinks of the time tables
//! that ask for it, see [`super::OdeProblem::next_stop`]): a step across a
//! kink has a large error at a tight tolerance and is rejected, again and
//! again, until it is tiny; ending it at the kink costs at most one short
//! step.

use super::{OdeProblem, OdeVector};

/// The step to attempt from `t` given the step `h` the method wants: `h`
/// when it ends short of the next stop by more than 1 %, else the step onto
/// the stop.
pub(crate) fn step<Y: OdeVector, P: OdeProblem<Y>>(problem: &mut P, t: f64, h: f64) -> f64 {
    // A stop within rounding of `t` is behind it.
    let after = t + 64.0 * f64::EPSILON * t.abs().max(f64::MIN_POSITIVE);
    match problem.next_stop(after) {
        Some(stop) if t + 1.01 * h >= stop => stop - t,
        _ => h,
    }
}
