//! The 3 ms clip of FMVSS 208 (S6.3, chest; also read for the head): the
//! highest level the magnitude of an acceleration stays at or above for a
//! cumulative 3 ms.

/// The cumulative duration of the 3 ms clip \[s\].
pub const CLIP_DURATION: f64 = 0.003;

/// The highest level `L` at which the magnitude of `a`, sampled every `dt`
/// and read as the piecewise-linear interpolant of its samples, spends a
/// cumulative `duration` or more at or above `L` (each crossing between two
/// samples counts its fraction of the interval). The duration above a level
/// falls as the level rises, so `L` is found by bisection between 0 and the
/// peak to the resolution of `f64`. `None` for a record shorter than
/// `duration`, a period that is not positive, or a non-finite sample.
pub fn clip(a: &[f64], dt: f64, duration: f64) -> Option<f64> {
    let record = dt * a.len().saturating_sub(1) as f64;
    if !(dt > 0.0 && dt.is_finite()) || record < duration || a.iter().any(|x| !x.is_finite()) {
        return None;
    }
    let magnitude: Vec<f64> = a.iter().map(|x| x.abs()).collect();
    let (mut low, mut high) = (0.0, magnitude.iter().copied().fold(0.0, f64::max));
    for _ in 0..200 {
        let level = 0.5 * (low + high);
        if level <= low || level >= high {
            break;
        }
        if time_at_or_above(&magnitude, dt, level) >= duration {
            low = level;
        } else {
            high = level;
        }
    }
    Some(low)
}

/// How long the interpolant of `x` is at or above `level`.
fn time_at_or_above(x: &[f64], dt: f64, level: f64) -> f64 {
    let mut total = 0.0;
    for pair in x.windows(2) {
        let (a, b) = (pair[0], pair[1]);
        total += match (a >= level, b >= level) {
            (true, true) => dt,
            (false, false) => 0.0,
            // The fraction of the interval on the side above the level.
            (true, false) => dt * (a - level) / (a - b),
            (false, true) => dt * (b - level) / (b - a),
        };
    }
    total
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::PI;

    #[test]
    fn clip_of_a_half_sine_matches_the_closed_form() {
        // A sin(πt/T) is at or above L for T − (2T/π)·asin(L/A); that is
        // 3 ms at L = A cos(π·3 ms / 2T).
        let (amplitude, duration, dt): (f64, f64, f64) = (50.0, 0.060, 1e-4);
        let n = (duration / dt).round() as usize;
        let a: Vec<f64> = (0..=n)
            .map(|k| -amplitude * (PI * k as f64 * dt / duration).sin())
            .collect();
        let exact = amplitude * (PI * CLIP_DURATION / (2.0 * duration)).cos();
        let got = clip(&a, dt, CLIP_DURATION).unwrap();
        assert!((got - exact).abs() < 1e-4, "{got} against {exact}");
    }

    #[test]
    fn clip_of_a_square_pulse_longer_than_3_ms_is_its_level() {
        let a: Vec<f64> = (0..200)
            .map(|k| if (50..100).contains(&k) { 40.0 } else { 5.0 })
            .collect();
        assert!((clip(&a, 1e-4, CLIP_DURATION).unwrap() - 40.0).abs() < 1e-9);
    }

    #[test]
    fn clip_counts_separate_exceedances_together() {
        // Two 2 ms plateaus at 30 g: 4 ms in all above 30 g, so the clip is
        // 30 g although neither lasts 3 ms.
        let a: Vec<f64> = (0..400)
            .map(|k| {
                if (100..=120).contains(&k) || (300..=320).contains(&k) {
                    30.0
                } else {
                    0.0
                }
            })
            .collect();
        assert!((clip(&a, 1e-4, CLIP_DURATION).unwrap() - 30.0).abs() < 1e-9);
    }

    #[test]
    fn clip_needs_a_record_of_3_ms() {
        assert_eq!(clip(&[1.0; 30], 1e-4, CLIP_DURATION), None);
        assert!(clip(&[1.0; 31], 1e-4, CLIP_DURATION).is_some());
        assert_eq!(clip(&[1.0, f64::NAN, 1.0, 1.0], 0.002, CLIP_DURATION), None);
    }
}
