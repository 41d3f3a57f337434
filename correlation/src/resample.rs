//! The common time base: both curves checked, then interpolated linearly
//! onto one grid of [`Options::sampling_interval`] over the interval they
//! share.
//!
//! ISO/TS 18571 rates curves sampled at 10 kHz over a common interval;
//! the reference implementation (objective_rating_metrics 1.3) takes
//! them already on that grid. The grid here starts at the later of the
//! two first times and steps by the sampling interval up to the earlier
//! of the two last times, that end included where it falls on the grid
//! (within [`GRID_TOLERANCE`] of a step): two curves sampled on the same
//! 10 kHz grid keep every shared sample, as pyisomme's wrapper keeps
//! them (it interpolates linearly as well when they are not).

use crate::error::{Coordinate, CurveRole, RatingError};
use crate::{Curve, Options};

/// The sampling interval of the common time base \[s\]: 10 kHz, the rate
/// ISO/TS 18571 rates curves at (and the `dt` of objective_rating_metrics).
pub const SAMPLING_INTERVAL_S: f64 = 1e-4;

/// The fewest samples the common time base must hold: 11, so that the
/// curves shifted by the largest phase shift (20 %, two samples of
/// eleven) keep the 9 samples the slope's moving average spans.
pub const MIN_SAMPLES: usize = 11;

/// The most samples the common time base may hold: 20 001, 2 s at 10 kHz
/// (a crash test's channels span a few hundred ms). The magnitude's time
/// warping keeps a step per cell of its band, `n × 0.2·n` bytes: 80 MB
/// at this length.
pub const MAX_SAMPLES: usize = 20_001;

/// How far past a whole number of steps (in steps) the interval's end may
/// lie and still be the grid's last point: rounding of times written in
/// decimal, far below a sample.
pub const GRID_TOLERANCE: f64 = 1e-6;

/// The two curves on the common time base.
#[derive(Clone, Debug, PartialEq)]
pub struct Resampled {
    /// The first time of the grid \[s\].
    pub start: f64,
    /// The grid's step \[s\].
    pub step: f64,
    /// The reference's values on the grid.
    pub reference: Vec<f64>,
    /// The comparison's values on the grid.
    pub comparison: Vec<f64>,
}

impl Resampled {
    /// The grid's last time \[s\].
    pub fn end(&self) -> f64 {
        self.start + (self.reference.len() - 1) as f64 * self.step
    }
}

/// Checks both curves and the options and puts the curves on the common
/// time base.
pub fn resample(
    reference: &Curve<'_>,
    comparison: &Curve<'_>,
    options: &Options,
) -> Result<Resampled, RatingError> {
    check(reference, CurveRole::Reference)?;
    check(comparison, CurveRole::Comparison)?;
    let step = options.sampling_interval;
    if !(step.is_finite() && step > 0.0) {
        return Err(RatingError::InvalidOption {
            option: "sampling_interval",
            value: step,
            problem: "is not a finite, positive number of seconds",
        });
    }
    let (start, end) = common_interval(reference, comparison, options.interval)?;
    let samples = ((end - start) / step + GRID_TOLERANCE).floor() as usize + 1;
    if samples < MIN_SAMPLES {
        return Err(RatingError::IntervalTooShort {
            start,
            end,
            samples,
            needed: MIN_SAMPLES,
        });
    }
    if samples > MAX_SAMPLES {
        return Err(RatingError::IntervalTooLong {
            start,
            end,
            samples,
            most: MAX_SAMPLES,
        });
    }
    let grid: Vec<f64> = (0..samples).map(|k| start + k as f64 * step).collect();
    Ok(Resampled {
        start,
        step,
        reference: interpolate(reference, &grid),
        comparison: interpolate(comparison, &grid),
    })
}

/// Same lengths, at least two samples, finite numbers, increasing times.
fn check(curve: &Curve<'_>, role: CurveRole) -> Result<(), RatingError> {
    let (t, y) = (curve.t, curve.y);
    if t.len() != y.len() {
        return Err(RatingError::LengthMismatch {
            curve: role,
            times: t.len(),
            values: y.len(),
        });
    }
    if t.len() < 2 {
        return Err(RatingError::TooShort {
            curve: role,
            samples: t.len(),
        });
    }
    let not_finite = |values: &[f64], what| {
        (values.iter().position(|v| !v.is_finite())).map(|index| RatingError::NotFinite {
            curve: role,
            index,
            what,
        })
    };
    if let Some(e) = not_finite(t, Coordinate::Time).or_else(|| not_finite(y, Coordinate::Value)) {
        return Err(e);
    }
    match (1..t.len()).find(|&i| t[i] <= t[i - 1]) {
        Some(index) => Err(RatingError::NotIncreasing {
            curve: role,
            index,
            time: t[index],
            previous: t[index - 1],
        }),
        None => Ok(()),
    }
}

/// The later first time and the earlier last time of the curves, within
/// `requested`.
fn common_interval(
    reference: &Curve<'_>,
    comparison: &Curve<'_>,
    requested: Option<(f64, f64)>,
) -> Result<(f64, f64), RatingError> {
    let span = |c: &Curve<'_>| (c.t[0], c.t[c.t.len() - 1]);
    let (r, c) = (span(reference), span(comparison));
    let (mut start, mut end) = (r.0.max(c.0), r.1.min(c.1));
    if let Some((a, b)) = requested {
        if let Some(&bad) = [a, b].iter().find(|v| !v.is_finite()) {
            return Err(RatingError::InvalidOption {
                option: "interval",
                value: bad,
                problem: "is not a finite number of seconds",
            });
        }
        (start, end) = (start.max(a), end.min(b));
    }
    if end <= start {
        return Err(RatingError::NoCommonInterval {
            reference: r,
            comparison: c,
            requested,
        });
    }
    Ok((start, end))
}

/// `curve` at the increasing times `grid`, linearly interpolated, its end
/// values held beyond its ends (the grid's last point may lie a rounding
/// error past them).
fn interpolate(curve: &Curve<'_>, grid: &[f64]) -> Vec<f64> {
    let (t, y) = (curve.t, curve.y);
    let mut k = 0;
    grid.iter()
        .map(|&time| {
            while k + 2 < t.len() && t[k + 1] <= time {
                k += 1;
            }
            if time <= t[0] {
                return y[0];
            }
            if time >= t[t.len() - 1] {
                return y[y.len() - 1];
            }
            let slope = (y[k + 1] - y[k]) / (t[k + 1] - t[k]);
            slope * (time - t[k]) + y[k]
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn curve<'a>(t: &'a [f64], y: &'a [f64]) -> Curve<'a> {
        Curve { t, y }
    }

    #[test]
    fn the_grid_spans_the_common_interval_with_its_end() {
        let t1: Vec<f64> = (0..=20).map(|k| k as f64 * 1e-4).collect();
        let t2: Vec<f64> = (0..=40).map(|k| 5e-4 + k as f64 * 5e-5).collect();
        let (y1, y2): (Vec<f64>, Vec<f64>) = (t1.clone(), t2.iter().map(|t| 2.0 * t).collect());
        let r = resample(&curve(&t1, &y1), &curve(&t2, &y2), &Options::default()).unwrap();
        // 0.5 ms to 2.0 ms at 0.1 ms: 16 samples, both ends included.
        assert_eq!(r.reference.len(), 16);
        assert_eq!(r.start, 5e-4);
        assert!((r.end() - 2e-3).abs() < 1e-15);
        // y = t and y = 2 t, linear, so interpolation is exact.
        for (k, (a, b)) in r.reference.iter().zip(&r.comparison).enumerate() {
            let time = 5e-4 + k as f64 * 1e-4;
            assert!((a - time).abs() < 1e-15 && (b - 2.0 * time).abs() < 1e-15);
        }
    }

    #[test]
    fn an_interval_longer_than_the_rating_takes_is_refused() {
        let (t, y) = ([0.0, 2.5], [0.0, 1.0]);
        let e = resample(&curve(&t, &y), &curve(&t, &y), &Options::default()).unwrap_err();
        assert_eq!(
            e,
            RatingError::IntervalTooLong {
                start: 0.0,
                end: 2.5,
                samples: 25_001,
                most: MAX_SAMPLES
            }
        );
    }

    #[test]
    fn bad_curves_are_named_with_their_index() {
        let (t, y) = ([0.0, 1.0, 1.0], [0.0, 1.0, 2.0]);
        let good = ([0.0, 1.0, 2.0], [0.0, 1.0, 2.0]);
        let e = resample(
            &curve(&good.0, &good.1),
            &curve(&t, &y),
            &Options::default(),
        )
        .unwrap_err();
        assert_eq!(
            e.to_string(),
            "the comparison curve's time at index 2 (1 s) does not exceed the one before (1 s)"
        );
        let nan = [0.0, f64::NAN, 2.0];
        let e = resample(
            &curve(&good.0, &nan),
            &curve(&good.0, &good.1),
            &Options::default(),
        )
        .unwrap_err();
        assert_eq!(
            e,
            RatingError::NotFinite {
                curve: CurveRole::Reference,
                index: 1,
                what: Coordinate::Value
            }
        );
        let e = resample(
            &curve(&good.0[..1], &good.1[..1]),
            &curve(&good.0, &good.1),
            &Options::default(),
        )
        .unwrap_err();
        assert_eq!(
            e.to_string(),
            "the reference curve has 1 samples; it needs at least 2"
        );
    }

    #[test]
    fn curves_apart_or_too_short_together_are_refused() {
        let (a, b, y) = ([0.0, 1e-3], [2e-3, 3e-3], [1.0, 2.0]);
        let e = resample(&curve(&a, &y), &curve(&b, &y), &Options::default()).unwrap_err();
        assert!(matches!(e, RatingError::NoCommonInterval { .. }), "{e}");
        // 0 to 0.9 ms: 10 samples, one short.
        let c = [0.0, 9e-4];
        let e = resample(&curve(&a, &y), &curve(&c, &y), &Options::default()).unwrap_err();
        assert_eq!(
            e,
            RatingError::IntervalTooShort {
                start: 0.0,
                end: 9e-4,
                samples: 10,
                needed: MIN_SAMPLES
            }
        );
    }
}
