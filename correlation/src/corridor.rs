//! The corridor score Z: how much of the comparison lies within corridors
//! around the reference, on the curves as they are (not shifted).
//!
//! With `δᵢ = a₀·max|T|` and `δₒ = b₀·max|T|` the inner and outer
//! half-widths around the reference `T`, each sample of the comparison
//! `C` scores
//!
//! ```text
//! zᵢ = 1                                  where |Cᵢ − Tᵢ| < δᵢ
//!      0                                  where |Cᵢ − Tᵢ| > δₒ
//!      ((δₒ − |Cᵢ − Tᵢ|) / (δₒ − δᵢ))^k_z  between
//! ```
//!
//! and `Z` is their mean (ISO/TS 18571:2014's corridor method;
//! objective_rating_metrics' `corridor_rating`).

use crate::error::{RatingError, Score};

/// The inner corridor's half-width `a₀`, as a share of the reference's
/// largest absolute value: 5 %, the standard's value (objective_rating_metrics'
/// `a_0`).
pub const INNER_WIDTH: f64 = 0.05;

/// The outer corridor's half-width `b₀`, as a share of the reference's
/// largest absolute value: 50 %, the standard's value (objective_rating_metrics'
/// `b_0`).
pub const OUTER_WIDTH: f64 = 0.5;

/// The exponent `k_z` of the score between the corridors: 2, the
/// standard's (objective_rating_metrics' `k_z`).
pub const CORRIDOR_EXPONENT: i32 = 2;

/// The corridor score of `comparison` against `reference`, sample by
/// sample (the same length).
pub fn corridor_score(reference: &[f64], comparison: &[f64]) -> Result<f64, RatingError> {
    let norm = reference.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
    if norm == 0.0 {
        return Err(RatingError::Undefined {
            score: Score::Corridor,
            what: "zero everywhere",
        });
    }
    let (inner, outer) = (INNER_WIDTH * norm, OUTER_WIDTH * norm);
    let sample = |(t, c): (&f64, &f64)| {
        let deviation = (c - t).abs();
        if deviation < inner {
            1.0
        } else if deviation > outer {
            0.0
        } else {
            ((outer - deviation) / (outer - inner)).powi(CORRIDOR_EXPONENT)
        }
    };
    let total: f64 = reference.iter().zip(comparison).map(sample).sum();
    Ok(total / reference.len() as f64)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_constant_offset_scores_its_closed_form() {
        let reference = [1.0, -2.0, 0.5, 2.0];
        // Offset 0.6 by max|T| = 2: inner 0.1, outer 1.0, so every
        // sample scores ((1.0 − 0.6) / 0.9)² .
        let comparison: Vec<f64> = reference.iter().map(|t| t + 0.6).collect();
        let expected = (0.4_f64 / 0.9).powi(2);
        let z = corridor_score(&reference, &comparison).unwrap();
        assert!((z - expected).abs() < 1e-15, "{z}");
        // Inside the inner corridor everywhere: 1; outside the outer: 0.
        let near: Vec<f64> = reference.iter().map(|t| t + 0.09).collect();
        assert_eq!(corridor_score(&reference, &near).unwrap(), 1.0);
        let far: Vec<f64> = reference.iter().map(|t| t + 1.01).collect();
        assert_eq!(corridor_score(&reference, &far).unwrap(), 0.0);
    }

    #[test]
    fn a_zero_reference_has_no_corridor() {
        let e = corridor_score(&[0.0; 4], &[1.0; 4]).unwrap_err();
        assert_eq!(
            e.to_string(),
            "the reference curve is zero everywhere over the common interval, so the corridor score is undefined"
        );
    }
}
