//! The phase score E_P and the time shift that the magnitude and slope
//! scores are computed after.
//!
//! The comparison is shifted against the reference one sample at a time,
//! up to `ε_P·N` samples either way (`N` the samples of the common time
//! base); at each shift the overlapping parts' Pearson correlation is
//! taken, and the shift `n_ε` with the largest wins. The phase score is
//!
//! ```text
//! E_P = 1                             where n_ε = 0
//!       0                             where n_ε ≥ ε_P·N
//!       ((ε_P·N − n_ε) / (ε_P·N))^k_p  between
//! ```
//!
//! Ties go to the smaller shift, and at one shift to the comparison moved
//! earlier ("left") over later, as the standard asks: the shifts are
//! tried from the smallest, left before right, and only a strictly larger
//! correlation replaces the best so far (objective_rating_metrics
//! `_get_shifted_curve_and_pr`). Where a part is constant its correlation
//! is undefined and never wins; where the unshifted curves' is undefined,
//! the reference keeps them unshifted, and so does this.

/// The largest shift `ε_P`, as a share of the common interval: 20 %, the
/// standard's (objective_rating_metrics' `1 − init_min`, `init_min` 0.8).
pub const MAX_SHIFT_FRACTION: f64 = 0.2;

/// The exponent `k_p` of the phase score: 1, the standard's.
pub const PHASE_EXPONENT: i32 = 1;

/// How the comparison is shifted against the reference: by `samples`,
/// positive where the comparison lags (its sample `samples` is paired
/// with the reference's first).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Shift {
    /// Samples of the common time base.
    pub samples: isize,
}

impl Shift {
    /// The reference's part that overlaps the shifted comparison.
    pub fn reference<'a>(&self, reference: &'a [f64]) -> &'a [f64] {
        let n = self.samples.unsigned_abs();
        match self.samples >= 0 {
            true => &reference[..reference.len() - n],
            false => &reference[n..],
        }
    }

    /// The comparison's part that overlaps the reference, shifted.
    pub fn comparison<'a>(&self, comparison: &'a [f64]) -> &'a [f64] {
        let n = self.samples.unsigned_abs();
        match self.samples >= 0 {
            true => &comparison[n..],
            false => &comparison[..comparison.len() - n],
        }
    }
}

/// The largest shift in samples for curves of `samples` samples:
/// `⌊ε_P·N⌋`.
fn max_shift(samples: usize) -> usize {
    (samples as f64 * MAX_SHIFT_FRACTION).floor() as usize
}

/// The shift of `comparison` that correlates best with `reference` (the
/// same length), ties broken as the module's doc says.
pub fn best_shift(reference: &[f64], comparison: &[f64]) -> Shift {
    let mut best = Shift { samples: 0 };
    let Some(mut best_correlation) = correlation(reference, comparison) else {
        return best;
    };
    for n in 1..=max_shift(reference.len()) as isize {
        for samples in [n, -n] {
            let shift = Shift { samples };
            let r = correlation(shift.reference(reference), shift.comparison(comparison));
            if let Some(r) = r.filter(|&r| r > best_correlation) {
                (best, best_correlation) = (shift, r);
            }
        }
    }
    best
}

/// The phase score of `shift` for curves of `samples` samples.
pub fn phase_score(shift: Shift, samples: usize) -> f64 {
    let limit = samples as f64 * MAX_SHIFT_FRACTION;
    let n = shift.samples.unsigned_abs() as f64;
    if n == 0.0 {
        1.0
    } else if n >= limit {
        0.0
    } else {
        ((limit - n) / limit).powi(PHASE_EXPONENT)
    }
}

/// Pearson's correlation coefficient of `x` and `y` (the same length),
/// clipped to \[−1, 1\]; `None` where either is constant.
fn correlation(x: &[f64], y: &[f64]) -> Option<f64> {
    let mean = |v: &[f64]| v.iter().sum::<f64>() / v.len() as f64;
    let (mx, my) = (mean(x), mean(y));
    let (mut sxy, mut sxx, mut syy) = (0.0, 0.0, 0.0);
    for (a, b) in x.iter().zip(y) {
        let (dx, dy) = (a - mx, b - my);
        sxy += dx * dy;
        sxx += dx * dx;
        syy += dy * dy;
    }
    if sxx == 0.0 || syy == 0.0 {
        return None;
    }
    Some((sxy / sxx.sqrt() / syy.sqrt()).clamp(-1.0, 1.0))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A bump at sample `at` of 101.
    fn bump(at: f64) -> Vec<f64> {
        (0..101)
            .map(|k| (-((k as f64 - at) / 6.0).powi(2)).exp())
            .collect()
    }

    #[test]
    fn a_delayed_copy_is_found_at_its_delay_and_scored_linearly() {
        let reference = bump(40.0);
        let late = bump(47.0);
        let shift = best_shift(&reference, &late);
        assert_eq!(shift, Shift { samples: 7 });
        // ε_P·N = 20.2: (20.2 − 7) / 20.2.
        assert!((phase_score(shift, 101) - 13.2 / 20.2).abs() < 1e-15);
        let early = bump(35.0);
        assert_eq!(best_shift(&reference, &early), Shift { samples: -5 });
        // Past the limit the shift is the largest tried, which scores 0.
        let far = bump(70.0);
        assert_eq!(best_shift(&reference, &far).samples, 20);
        assert_eq!(phase_score(Shift { samples: 20 }, 100), 0.0);
    }

    #[test]
    fn the_shifted_parts_overlap() {
        let (r, c) = ([0.0, 1.0, 2.0, 3.0], [10.0, 11.0, 12.0, 13.0]);
        let late = Shift { samples: 1 };
        assert_eq!(
            (late.reference(&r), late.comparison(&c)),
            (&r[..3], &c[1..])
        );
        let early = Shift { samples: -2 };
        assert_eq!(
            (early.reference(&r), early.comparison(&c)),
            (&r[2..], &c[..2])
        );
    }

    #[test]
    fn a_constant_curve_stays_unshifted() {
        assert_eq!(correlation(&[1.0, 1.0, 1.0], &[0.0, 1.0, 2.0]), None);
        assert_eq!(best_shift(&bump(40.0), &[2.0; 101]).samples, 0);
    }
}
