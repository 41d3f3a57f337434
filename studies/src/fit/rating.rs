//! The ISO/TS 18571 rating of a fit's simulated channels against the
//! target's (`lagrangian-correlation`, the rating `lpm compare` gives).
//!
//! A channel is rated as `lpm compare` rates the fitted run against the
//! target: the simulated channel at the simulation's own output times
//! (not interpolated to the target's), the target at its times, over the
//! interval both span. The fit's channels are in SI units with the fit's
//! signs (an acceleration negative while decelerating) where the test may
//! hold a deceleration in g: every score is a ratio of differences of the
//! two curves, so the same scale and sign on both leaves it unchanged.

use lagrangian_correlation::{Curve, Options, Rating, RatingError, iso18571};
use serde::ser::{Serialize, SerializeMap, Serializer};

/// A channel's rating, or why it has none (a target too short for the
/// rating's 10 kHz time base, a target that is zero over the interval…):
/// a channel that cannot be rated does not fail the fit.
#[derive(Clone, Debug, PartialEq)]
pub enum ChannelRating {
    /// The four scores, the overall rating and its grade.
    Rated(Rating),
    /// The rating's reason for giving none.
    NotRated(RatingError),
}

impl ChannelRating {
    /// The rating of the simulated channel `(t, y)` against the target
    /// channel `(target_t, target_y)`, over the interval both span.
    pub fn of(target_t: &[f64], target_y: &[f64], t: &[f64], y: &[f64]) -> ChannelRating {
        let reference = Curve {
            t: target_t,
            y: target_y,
        };
        let comparison = Curve { t, y };
        match iso18571(&reference, &comparison, &Options::default()) {
            Ok(rating) => ChannelRating::Rated(rating),
            Err(error) => ChannelRating::NotRated(error),
        }
    }

    /// The rating, where there is one.
    pub fn rating(&self) -> Option<&Rating> {
        match self {
            ChannelRating::Rated(rating) => Some(rating),
            ChannelRating::NotRated(_) => None,
        }
    }
}

/// `{"kind": "rated", "corridor", "phase", "magnitude", "slope",
/// "overall", "grade", "time_shift_s", "interval_s"}` (the keys of a pair
/// of `lpm compare --format json`), or `{"kind": "not_rated", "reason"}`.
impl Serialize for ChannelRating {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        match self {
            ChannelRating::Rated(r) => {
                let mut map = serializer.serialize_map(Some(9))?;
                map.serialize_entry("kind", "rated")?;
                map.serialize_entry("corridor", &r.corridor)?;
                map.serialize_entry("phase", &r.phase)?;
                map.serialize_entry("magnitude", &r.magnitude)?;
                map.serialize_entry("slope", &r.slope)?;
                map.serialize_entry("overall", &r.overall)?;
                map.serialize_entry("grade", r.grade.name())?;
                map.serialize_entry("time_shift_s", &r.time_shift_s)?;
                map.serialize_entry("interval_s", &[r.interval_s.0, r.interval_s.1])?;
                map.end()
            }
            ChannelRating::NotRated(error) => {
                let mut map = serializer.serialize_map(Some(2))?;
                map.serialize_entry("kind", "not_rated")?;
                map.serialize_entry("reason", &error.to_string())?;
                map.end()
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use lagrangian_correlation::Grade;

    /// A half sine of `peak` over `(0, 0.05)` s, sampled every `dt`.
    fn half_sine(peak: f64, dt: f64) -> (Vec<f64>, Vec<f64>) {
        let n = (0.05 / dt).round() as usize;
        let t: Vec<f64> = (0..=n).map(|i| i as f64 * dt).collect();
        let y = t
            .iter()
            .map(|t| peak * (std::f64::consts::PI * t / 0.05).sin())
            .collect();
        (t, y)
    }

    #[test]
    fn a_curve_against_itself_rates_one_on_other_samples() {
        // The target every 0.5 ms, the run every 0.1 ms: the run's curve
        // holds the target's samples and more; linear interpolation of the
        // coarser one keeps the rating near 1.
        let (tt, ty) = half_sine(-300.0, 5e-4);
        let (t, y) = half_sine(-300.0, 1e-4);
        let rating = ChannelRating::of(&tt, &ty, &t, &y);
        let r = rating.rating().expect("rated");
        assert!(r.overall > 0.99 && r.grade == Grade::Excellent, "{r:?}");
        assert_eq!(r.interval_s, (0.0, 0.05));
    }

    #[test]
    fn a_target_shorter_than_the_rating_needs_is_not_rated_and_says_why() {
        // 0.5 ms: six samples of the 10 kHz time base, the rating needs 11.
        let (t, y) = (vec![0.0, 2.5e-4, 5e-4], vec![0.0, 1.0, 0.0]);
        let rating = ChannelRating::of(&t, &y, &t, &y);
        assert!(
            matches!(
                rating,
                ChannelRating::NotRated(RatingError::IntervalTooShort { samples: 6, .. })
            ),
            "{rating:?}"
        );
        let json = serde_json::to_value(&rating).unwrap();
        assert_eq!(json["kind"], "not_rated");
        assert!(json["reason"].as_str().unwrap().contains("at least 11"));
    }

    #[test]
    fn a_rating_serializes_with_the_keys_of_lpm_compare() {
        let (t, y) = half_sine(1.0, 1e-4);
        let scaled: Vec<f64> = y.iter().map(|v| 0.9 * v).collect();
        let rating = ChannelRating::of(&t, &y, &t, &scaled);
        let r = *rating.rating().unwrap();
        let json = serde_json::to_value(&rating).unwrap();
        assert_eq!(json["kind"], "rated");
        assert_eq!(json["overall"].as_f64(), Some(r.overall));
        assert_eq!(json["grade"], r.grade.name());
        assert_eq!(json["interval_s"], serde_json::json!([0.0, 0.05]));
        assert!(r.magnitude < 1.0 && r.corridor < 1.0, "10 % low: {r:?}");
    }
}
