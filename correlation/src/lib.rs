//! The ISO/TS 18571:2014 objective rating of a comparison curve (a
//! model's time history) against a reference curve (a test's): four
//! scores in \[0, 1\], their weighted overall rating and its grade.
//!
//! [`iso18571`] puts both curves on a common 10 kHz time base over the
//! interval they share ([`resample`]), then scores
//!
//! * the **corridor** `Z` ([`corridor`]): the share of the comparison
//!   within corridors of 5 % (inner) and 50 % (outer) of the reference's
//!   largest absolute value around it, on the curves as they are;
//! * the **phase** `E_P` ([`phase`]): the time shift, up to 20 % of the
//!   interval, that correlates the curves best;
//! * the **magnitude** `E_M` ([`magnitude`]): the relative L1 difference
//!   of the curves, shifted by that phase and paired by dynamic time
//!   warping;
//! * the **slope** `E_S` ([`slope`]): the relative L1 difference of the
//!   shifted curves' smoothed derivatives;
//!
//! and rates `R = 0.4·Z + 0.2·E_P + 0.2·E_M + 0.2·E_S`, graded excellent
//! (`R > 0.94`), good (`> 0.80`), fair (`> 0.58`) or poor ([`Grade`]).
//!
//! The behaviour follows objective_rating_metrics 1.3 (VSI, TU Graz; the
//! implementation pyisomme and openvt.eu run), which the tests compare
//! against (`tests/reference/`, scores within 1e-9). Where it settles what
//! the standard's text leaves open, each module says how: the tie rules
//! of the phase shift, the DTW variant and band, the slope's derivative
//! and end windows. Two differences from the reference, both outside the
//! scores: it takes curves already on a common 10 kHz grid of equal
//! length, which this crate makes from any two curves ([`resample`]); and
//! it computes a score over a reference that is zero (or flat, for the
//! slope) as NaN, which is an error here ([`RatingError::Undefined`]).

pub mod corridor;
mod error;
mod grade;
pub mod magnitude;
pub mod phase;
pub mod resample;
pub mod slope;

pub use error::{Coordinate, CurveRole, RatingError, Score};
pub use grade::{EXCELLENT_ABOVE, FAIR_ABOVE, GOOD_ABOVE, Grade};
pub use resample::{MAX_SAMPLES, MIN_SAMPLES, SAMPLING_INTERVAL_S};

/// The weight `w_Z` of the corridor score in the overall rating: 0.4
/// (ISO/TS 18571:2014; objective_rating_metrics' `w_z`).
pub const CORRIDOR_WEIGHT: f64 = 0.4;
/// The weight `w_P` of the phase score: 0.2.
pub const PHASE_WEIGHT: f64 = 0.2;
/// The weight `w_M` of the magnitude score: 0.2.
pub const MAGNITUDE_WEIGHT: f64 = 0.2;
/// The weight `w_S` of the slope score: 0.2.
pub const SLOPE_WEIGHT: f64 = 0.2;

/// A time history: times \[s\], strictly increasing, not necessarily
/// evenly spaced, and a value at each.
#[derive(Clone, Copy, Debug)]
pub struct Curve<'a> {
    /// The sample times \[s\].
    pub t: &'a [f64],
    /// The values, one per time, in any unit (the same for both curves of
    /// a rating; every score is a ratio, so the unit does not matter).
    pub y: &'a [f64],
}

/// How to rate.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Options {
    /// The interval to rate `(start, end)` \[s\], within the curves' common
    /// one; `None`: all of the common interval.
    pub interval: Option<(f64, f64)>,
    /// The step of the common time base \[s\]; the standard's is
    /// [`SAMPLING_INTERVAL_S`] (10 kHz), the default.
    pub sampling_interval: f64,
}

impl Default for Options {
    fn default() -> Options {
        Options {
            interval: None,
            sampling_interval: SAMPLING_INTERVAL_S,
        }
    }
}

/// The objective rating of a comparison against a reference.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Rating {
    /// The corridor score `Z`, in \[0, 1\].
    pub corridor: f64,
    /// The phase score `E_P`, in \[0, 1\].
    pub phase: f64,
    /// The magnitude score `E_M`, in \[0, 1\].
    pub magnitude: f64,
    /// The slope score `E_S`, in \[0, 1\].
    pub slope: f64,
    /// The weighted overall rating `R`, in \[0, 1\].
    pub overall: f64,
    /// The grade of `overall`.
    pub grade: Grade,
    /// The time shift that correlates best \[s\], positive where the
    /// comparison lags the reference.
    pub time_shift_s: f64,
    /// The interval rated `(start, end)` \[s\]: the common time base's
    /// first and last time.
    pub interval_s: (f64, f64),
}

/// The ISO/TS 18571 rating of `comparison` against `reference`.
pub fn iso18571(
    reference: &Curve<'_>,
    comparison: &Curve<'_>,
    options: &Options,
) -> Result<Rating, RatingError> {
    let curves = resample::resample(reference, comparison, options)?;
    let (r, c) = (&curves.reference[..], &curves.comparison[..]);
    let corridor = corridor::corridor_score(r, c)?;
    let shift = phase::best_shift(r, c);
    let phase = phase::phase_score(shift, r.len());
    let (r_shifted, c_shifted) = (shift.reference(r), shift.comparison(c));
    let magnitude = magnitude::magnitude_score(r_shifted, c_shifted)?;
    let slope = slope::slope_score(r_shifted, c_shifted, curves.step)?;
    let overall = CORRIDOR_WEIGHT * corridor
        + PHASE_WEIGHT * phase
        + MAGNITUDE_WEIGHT * magnitude
        + SLOPE_WEIGHT * slope;
    Ok(Rating {
        corridor,
        phase,
        magnitude,
        slope,
        overall,
        grade: Grade::of(overall),
        time_shift_s: shift.samples as f64 * curves.step,
        interval_s: (curves.start, curves.end()),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_weights_add_up_to_one() {
        let sum = CORRIDOR_WEIGHT + PHASE_WEIGHT + MAGNITUDE_WEIGHT + SLOPE_WEIGHT;
        assert!((sum - 1.0).abs() < 1e-15);
    }
}
