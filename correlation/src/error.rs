//! Why two curves cannot be rated: each error names the curve, and the
//! index or the interval, it is about.

use std::fmt;

/// One of the two curves of a rating.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum CurveRole {
    /// The curve rated against (the test).
    Reference,
    /// The curve rated (the model).
    Comparison,
}

impl fmt::Display for CurveRole {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            CurveRole::Reference => "reference",
            CurveRole::Comparison => "comparison",
        })
    }
}

/// Which of a sample's two numbers.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Coordinate {
    /// Its time.
    Time,
    /// Its value.
    Value,
}

impl fmt::Display for Coordinate {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            Coordinate::Time => "time",
            Coordinate::Value => "value",
        })
    }
}

/// A score of the rating.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Score {
    /// The corridor score.
    Corridor,
    /// The magnitude score.
    Magnitude,
    /// The slope score.
    Slope,
}

impl fmt::Display for Score {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            Score::Corridor => "corridor",
            Score::Magnitude => "magnitude",
            Score::Slope => "slope",
        })
    }
}

/// Why [`crate::iso18571`] gives no rating.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum RatingError {
    /// A curve's time and value arrays differ in length.
    #[error("the {curve} curve has {times} times but {values} values")]
    LengthMismatch {
        /// Which curve.
        curve: CurveRole,
        /// Its number of times.
        times: usize,
        /// Its number of values.
        values: usize,
    },
    /// A curve with fewer than two samples.
    #[error("the {curve} curve has {samples} samples; it needs at least 2")]
    TooShort {
        /// Which curve.
        curve: CurveRole,
        /// Its number of samples.
        samples: usize,
    },
    /// A time or a value that is NaN or infinite.
    #[error("the {curve} curve's {what} at index {index} is not a finite number")]
    NotFinite {
        /// Which curve.
        curve: CurveRole,
        /// The sample's index (from 0).
        index: usize,
        /// Its time or its value.
        what: Coordinate,
    },
    /// A time that does not exceed the one before it.
    #[error(
        "the {curve} curve's time at index {index} ({time} s) does not exceed the one before ({previous} s)"
    )]
    NotIncreasing {
        /// Which curve.
        curve: CurveRole,
        /// The sample's index (from 0).
        index: usize,
        /// Its time \[s\].
        time: f64,
        /// The time of the sample before \[s\].
        previous: f64,
    },
    /// The curves' time ranges (within [`crate::Options::interval`]) do
    /// not overlap.
    #[error(
        "the curves share no time interval (reference {} s to {} s, comparison {} s to {} s{})",
        .reference.0, .reference.1, .comparison.0, .comparison.1,
        .requested.map_or(String::new(), |(a, b)| format!(", requested {a} s to {b} s"))
    )]
    NoCommonInterval {
        /// The reference's first and last time \[s\].
        reference: (f64, f64),
        /// The comparison's first and last time \[s\].
        comparison: (f64, f64),
        /// The interval asked for in the options, if any \[s\].
        requested: Option<(f64, f64)>,
    },
    /// The common interval holds too few samples of the common time base.
    #[error(
        "the common interval {start} s to {end} s holds {samples} samples of the common time base; the rating needs at least {needed}"
    )]
    IntervalTooShort {
        /// Its start \[s\].
        start: f64,
        /// Its end \[s\].
        end: f64,
        /// The samples it holds.
        samples: usize,
        /// The samples the rating needs ([`crate::MIN_SAMPLES`]).
        needed: usize,
    },
    /// The common interval holds more samples of the common time base
    /// than the rating takes ([`crate::MAX_SAMPLES`]).
    #[error(
        "the common interval {start} s to {end} s holds {samples} samples of the common time base; the rating takes at most {most} (narrow the interval)"
    )]
    IntervalTooLong {
        /// Its start \[s\].
        start: f64,
        /// Its end \[s\].
        end: f64,
        /// The samples it holds.
        samples: usize,
        /// The most the rating takes.
        most: usize,
    },
    /// The reference is zero (corridor, magnitude) or constant (slope)
    /// over the common interval: the score divides by zero.
    #[error(
        "the reference curve is {what} over the common interval, so the {score} score is undefined"
    )]
    Undefined {
        /// The score that cannot be computed.
        score: Score,
        /// What it is: `zero everywhere` or `flat (its slope is zero)`.
        what: &'static str,
    },
    /// An option that is not a finite, positive number or an empty
    /// interval.
    #[error("option `{option}`: {value} {problem}")]
    InvalidOption {
        /// The option's field name.
        option: &'static str,
        /// Its value, as written by `{}` of f64 (an interval's first bad
        /// number).
        value: f64,
        /// What is wrong with it.
        problem: &'static str,
    },
}
