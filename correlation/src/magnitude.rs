//! The magnitude score E_M: the relative L1 difference of the shifted
//! curves once dynamic time warping (DTW) has paired their samples, so
//! that a remaining small phase difference is not counted twice.
//!
//! DTW pairs sample `i` of the comparison `C` with sample `j` of the
//! reference `T` along a path from `(0, 0)` to `(n−1, n−1)` that moves one
//! step down, right or diagonally at a time, stays within a Sakoe–Chiba
//! band `|i − j| ≤ w`, and has the smallest sum of `(Cᵢ − Tⱼ)²`. With
//! `ε* = Σ|Cᵢ − Tⱼ| / Σ|Tⱼ|` over the path's pairs,
//!
//! ```text
//! E_M = ((ε_M − ε*) / ε_M)^k_m  where ε* < ε_M, else 0.
//! ```
//!
//! As objective_rating_metrics 1.3 (`_compute_magnitude`, through dtwalign
//! 0.1.1's `dtw_low`): the step pattern is the plain one (each of the
//! three steps adds the cell's squared difference, weight 1), the band's
//! half-width is `w = ⌈0.1·n⌉ − 1`, and where steps tie on the way back
//! from the end the first of "down" (`i − 1`), "right" (`j − 1`),
//! "diagonal" is taken.

use crate::error::{RatingError, Score};

/// The magnitude error `ε_M` at which the score reaches 0: 50 %, the
/// standard's (objective_rating_metrics' `eps_m`).
pub const MAGNITUDE_LIMIT: f64 = 0.5;

/// The exponent `k_m` of the magnitude score: 1, the standard's.
pub const MAGNITUDE_EXPONENT: i32 = 1;

/// The width of the DTW band as a share of the curves' length: 10 %, as
/// the reference implementation's `window_size`.
pub const WARPING_WINDOW_FRACTION: f64 = 0.1;

/// The magnitude score of `comparison` against `reference`, both already
/// shifted (the same length).
pub fn magnitude_score(reference: &[f64], comparison: &[f64]) -> Result<f64, RatingError> {
    let path = warping_path(comparison, reference);
    let (mut difference, mut size) = (0.0, 0.0);
    for &(i, j) in &path {
        difference += (comparison[i] - reference[j]).abs();
        size += reference[j].abs();
    }
    if size == 0.0 {
        return Err(RatingError::Undefined {
            score: Score::Magnitude,
            what: "zero everywhere",
        });
    }
    let error = difference / size;
    Ok(match error > MAGNITUDE_LIMIT {
        true => 0.0,
        false => ((MAGNITUDE_LIMIT - error) / MAGNITUDE_LIMIT).powi(MAGNITUDE_EXPONENT),
    })
}

/// The half-width `w` of the band for curves of `n` samples.
fn band(n: usize) -> usize {
    ((WARPING_WINDOW_FRACTION * n as f64).ceil() as usize).saturating_sub(1)
}

/// A step of the warping path, back from a cell to the one before it.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Step {
    /// From `(i − 1, j)`.
    Down,
    /// From `(i, j − 1)`.
    Right,
    /// From `(i − 1, j − 1)`.
    Diagonal,
}

/// The cells of the band: row `i` holds `j` from `i − w` to `i + w`, at
/// offsets `j + w − i` of a row of `2w + 1`.
struct Band {
    n: usize,
    w: usize,
}

impl Band {
    fn width(&self) -> usize {
        2 * self.w + 1
    }

    /// The offset of `(i, j)` in row `i`, if the cell is in the band.
    fn offset(&self, i: usize, j: usize) -> Option<usize> {
        let offset = (j + self.w).checked_sub(i)?;
        (offset < self.width() && j < self.n).then_some(offset)
    }
}

/// The DTW path pairing `x` (rows) with `y` (columns), from `(0, 0)` to
/// the last cell.
fn warping_path(x: &[f64], y: &[f64]) -> Vec<(usize, usize)> {
    let band = Band {
        n: x.len(),
        w: band(x.len()),
    };
    let steps = cumulative_steps(x, y, &band);
    let (mut i, mut j) = (band.n - 1, band.n - 1);
    let mut path = vec![(i, j)];
    while (i, j) != (0, 0) {
        let offset = band.offset(i, j).unwrap_or(0);
        match steps[i * band.width() + offset] {
            Step::Down => i -= 1,
            Step::Right => j -= 1,
            Step::Diagonal => (i, j) = (i - 1, j - 1),
        }
        path.push((i, j));
    }
    path.reverse();
    path
}

/// The step into each cell of the band that its smallest cumulative cost
/// comes from (row by row; two rows of costs kept).
fn cumulative_steps(x: &[f64], y: &[f64], band: &Band) -> Vec<Step> {
    let width = band.width();
    let mut steps = vec![Step::Diagonal; band.n * width];
    let (mut previous, mut current) = (vec![f64::INFINITY; width], vec![f64::INFINITY; width]);
    for i in 0..band.n {
        current.fill(f64::INFINITY);
        let first = i.saturating_sub(band.w);
        let last = (i + band.w).min(band.n - 1);
        for (j, &yj) in y.iter().enumerate().take(last + 1).skip(first) {
            let offset = j + band.w - i;
            let cost = (x[i] - yj) * (x[i] - yj);
            if (i, j) == (0, 0) {
                current[offset] = cost;
                continue;
            }
            let before = |row: &[f64], k: Option<usize>| k.and_then(|k| row.get(k).copied());
            let down = if i > 0 {
                before(&previous, Some(offset + 1))
            } else {
                None
            };
            let right = if j > 0 {
                before(&current, offset.checked_sub(1))
            } else {
                None
            };
            let diagonal = if i > 0 && j > 0 {
                before(&previous, Some(offset))
            } else {
                None
            };
            let (step, from) = smallest([
                (Step::Down, down.unwrap_or(f64::INFINITY)),
                (Step::Right, right.unwrap_or(f64::INFINITY)),
                (Step::Diagonal, diagonal.unwrap_or(f64::INFINITY)),
            ]);
            steps[i * width + offset] = step;
            current[offset] = from + cost;
        }
        std::mem::swap(&mut previous, &mut current);
    }
    steps
}

/// The first of the smallest costs, with its step.
fn smallest(candidates: [(Step, f64); 3]) -> (Step, f64) {
    let [first, rest @ ..] = candidates;
    rest.into_iter()
        .fold(first, |best, c| if c.1 < best.1 { c } else { best })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn identical_curves_warp_along_the_diagonal_and_score_1() {
        let y: Vec<f64> = (0..50).map(|k| (k as f64 * 0.2).sin() + 2.0).collect();
        let path = warping_path(&y, &y);
        assert_eq!(path, (0..50).map(|k| (k, k)).collect::<Vec<_>>());
        assert_eq!(magnitude_score(&y, &y).unwrap(), 1.0);
    }

    #[test]
    fn a_constant_ratio_between_constants_scores_its_closed_form() {
        // Constant curves: every cell costs the same, so the path is the
        // diagonal (the fewest cells) and ε* = 0.1 exactly.
        let (reference, comparison) = ([2.0; 30], [1.8; 30]);
        let expected = (MAGNITUDE_LIMIT - 0.1) / MAGNITUDE_LIMIT;
        let score = magnitude_score(&reference, &comparison).unwrap();
        assert!((score - expected).abs() < 1e-12, "{score}");
        assert_eq!(magnitude_score(&reference, &[0.5; 30]).unwrap(), 0.0);
    }

    #[test]
    fn the_path_stays_in_the_band_and_moves_one_step_at_a_time() {
        let x: Vec<f64> = (0..40).map(|k| ((k as f64 - 15.0) / 4.0).tanh()).collect();
        let y: Vec<f64> = (0..40).map(|k| ((k as f64 - 22.0) / 4.0).tanh()).collect();
        let path = warping_path(&x, &y);
        let w = band(40) as isize;
        assert_eq!(w, 3);
        assert_eq!((path[0], *path.last().unwrap()), ((0, 0), (39, 39)));
        for pair in path.windows(2) {
            let (di, dj) = (pair[1].0 - pair[0].0, pair[1].1 - pair[0].1);
            assert!(matches!((di, dj), (1, 0) | (0, 1) | (1, 1)), "{pair:?}");
        }
        assert!(
            path.iter()
                .all(|&(i, j)| (i as isize - j as isize).abs() <= w)
        );
        // The curves differ by a shift of 7 samples, more than the band:
        // the path runs along its edge through the step.
        assert!(path.iter().any(|&(i, j)| j as isize - i as isize == w));
    }
}
