//! The slope score E_S: the relative L1 difference of the shifted curves'
//! derivatives.
//!
//! Each curve's derivative is taken by central differences (one-sided at
//! the two ends), then smoothed by a centred moving average of 9 samples;
//! at the first and last four samples the window shrinks to the 1, 3, 5
//! and 7 samples centred on them. With `ε* = Σ|C'ᵢ − T'ᵢ| / Σ|T'ᵢ|`,
//!
//! ```text
//! E_S = ((ε_S − ε*) / ε_S)^k_s  where ε* < ε_S, else 0,
//! ```
//!
//! `k_s` = 1. That is objective_rating_metrics 1.3's `slope_rating`
//! (numpy's `gradient`, then its own end windows and a 9-sample
//! convolution); it has no `k_s` parameter, the score is linear, the
//! standard's value of the exponent.

use crate::error::{RatingError, Score};

/// The slope error `ε_S` at which the score reaches 0: 200 %, the
/// standard's (objective_rating_metrics' `e_s`).
pub const SLOPE_LIMIT: f64 = 2.0;

/// The samples of the moving average the derivative is smoothed with: 9.
pub const SMOOTHING_SAMPLES: usize = 9;

/// The slope score of `comparison` against `reference`, both already
/// shifted (the same length, at least [`SMOOTHING_SAMPLES`]), sampled
/// every `step` seconds.
pub fn slope_score(reference: &[f64], comparison: &[f64], step: f64) -> Result<f64, RatingError> {
    let (r, c) = (
        smoothed(&derivative(reference, step)),
        smoothed(&derivative(comparison, step)),
    );
    let size: f64 = r.iter().map(|v| v.abs()).sum();
    if size == 0.0 {
        return Err(RatingError::Undefined {
            score: Score::Slope,
            what: "flat (its slope is zero)",
        });
    }
    let difference: f64 = r.iter().zip(&c).map(|(a, b)| (b - a).abs()).sum();
    let error = difference / size;
    Ok(match error >= SLOPE_LIMIT {
        true => 0.0,
        false => (SLOPE_LIMIT - error) / SLOPE_LIMIT,
    })
}

/// Central differences inside, one-sided ones at the ends.
fn derivative(y: &[f64], step: f64) -> Vec<f64> {
    let n = y.len();
    (0..n)
        .map(|i| match i {
            0 => (y[1] - y[0]) / step,
            _ if i == n - 1 => (y[n - 1] - y[n - 2]) / step,
            _ => (y[i + 1] - y[i - 1]) / (2.0 * step),
        })
        .collect()
}

/// The centred moving average of [`SMOOTHING_SAMPLES`], narrower near the
/// ends (`d` holds at least that many).
fn smoothed(d: &[f64]) -> Vec<f64> {
    let n = d.len();
    let half = SMOOTHING_SAMPLES / 2;
    let mean = |window: &[f64]| window.iter().sum::<f64>() / window.len() as f64;
    (0..n)
        .map(|i| {
            let reach = half.min(i).min(n - 1 - i);
            mean(&d[i - reach..=i + reach])
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_parabola_has_its_exact_derivative_inside() {
        let y: Vec<f64> = (0..12).map(|k| (k as f64).powi(2)).collect();
        let d = derivative(&y, 1.0);
        assert_eq!(d[0], 1.0);
        assert_eq!(d[11], 21.0);
        assert!((1..11).all(|i| d[i] == 2.0 * i as f64));
        // Nine samples around 5 and 6 lie on the line 2i, and their mean
        // is on it; near the ends the windows shrink and reach the
        // one-sided differences: at 1, (1 + 2 + 4) / 3.
        let s = smoothed(&d);
        assert_eq!((s[5], s[6]), (10.0, 12.0));
        assert_eq!((s[0], s[1], s[11]), (1.0, 7.0 / 3.0, 21.0));
        assert!((s[10] - (18.0 + 20.0 + 21.0) / 3.0).abs() < 1e-14);
    }

    #[test]
    fn a_scaled_copy_scores_its_closed_form() {
        // ε* = 0.3 for a comparison 1.3 times the reference.
        let reference: Vec<f64> = (0..20).map(|k| (k as f64 * 0.3).sin()).collect();
        let comparison: Vec<f64> = reference.iter().map(|v| 1.3 * v).collect();
        let score = slope_score(&reference, &comparison, 1e-4).unwrap();
        assert!((score - (2.0 - 0.3) / 2.0).abs() < 1e-12, "{score}");
        let e = slope_score(&[1.0; 12], &comparison[..12], 1e-4).unwrap_err();
        assert!(e.to_string().contains("flat"), "{e}");
    }
}
