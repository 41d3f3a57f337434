//! Piecewise cubic Hermite interpolation that keeps the data's monotonicity
//! (PCHIP, Fritsch and Carlson; the tangents of Fritsch and Butland): C¹
//! through the points, no overshoot between them, a flat tangent at a local
//! extremum of the data. A table interpolated so has no kinks for the
//! integrator to step to.

/// The tangent `dy/dx` at each point of `(xs, ys)` (`xs` increasing, at
/// least two points).
pub(crate) fn tangents(xs: &[f64], ys: &[f64]) -> Vec<f64> {
    let n = xs.len();
    let h: Vec<f64> = xs.windows(2).map(|w| w[1] - w[0]).collect();
    let delta: Vec<f64> = (0..n - 1).map(|k| (ys[k + 1] - ys[k]) / h[k]).collect();
    if n == 2 {
        return vec![delta[0]; 2];
    }
    let mut d = vec![0.0; n];
    for k in 1..n - 1 {
        d[k] = interior(h[k - 1], h[k], delta[k - 1], delta[k]);
    }
    d[0] = end(h[0], h[1], delta[0], delta[1]);
    d[n - 1] = end(h[n - 2], h[n - 3], delta[n - 2], delta[n - 3]);
    d
}

/// The tangent between segments of widths `h0`, `h1` and slopes `d0`, `d1`:
/// their weighted harmonic mean, 0 where the data turns or is flat.
fn interior(h0: f64, h1: f64, d0: f64, d1: f64) -> f64 {
    if d0 == 0.0 || d1 == 0.0 || d0.signum() != d1.signum() {
        return 0.0;
    }
    let (w1, w2) = (2.0 * h1 + h0, h1 + 2.0 * h0);
    (w1 + w2) / (w1 / d0 + w2 / d1)
}

/// The tangent at an end: the three-point estimate from the end segment
/// (width `h0`, slope `d0`) and its neighbour (`h1`, `d1`), limited so that
/// the end segment stays monotone.
fn end(h0: f64, h1: f64, d0: f64, d1: f64) -> f64 {
    let d = ((2.0 * h0 + h1) * d0 - h0 * d1) / (h0 + h1);
    if d.signum() != d0.signum() || d0 == 0.0 {
        0.0
    } else if d0.signum() != d1.signum() && d.abs() > 3.0 * d0.abs() {
        3.0 * d0
    } else {
        d
    }
}

/// `(y(x), dy/dx)` of the cubic on `[x0, x1]` with values `y0`, `y1` and
/// tangents `d0`, `d1` at its ends.
pub(crate) fn hermite(
    x: f64,
    (x0, x1): (f64, f64),
    (y0, y1): (f64, f64),
    (d0, d1): (f64, f64),
) -> (f64, f64) {
    let h = x1 - x0;
    let s = (x - x0) / h;
    let (s2, s3) = (s * s, s * s * s);
    let y = (2.0 * s3 - 3.0 * s2 + 1.0) * y0
        + (s3 - 2.0 * s2 + s) * h * d0
        + (3.0 * s2 - 2.0 * s3) * y1
        + (s3 - s2) * h * d1;
    let slope = (6.0 * s2 - 6.0 * s) * (y0 - y1) / h
        + (3.0 * s2 - 4.0 * s + 1.0) * d0
        + (3.0 * s2 - 2.0 * s) * d1;
    (y, slope)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Checks the tangents at the points and `(x, y, dy/dx)` between them
    /// against reference values.
    fn check(xs: &[f64], ys: &[f64], reference: &[f64], values: &[(f64, f64, f64)]) {
        let d = tangents(xs, ys);
        for (a, b) in d.iter().zip(reference) {
            assert!((a - b).abs() < 1e-12, "{d:?} vs {reference:?}");
        }
        for &(x, y, slope) in values {
            let i = xs.partition_point(|&p| p <= x).clamp(1, xs.len() - 1) - 1;
            let ends = (xs[i], xs[i + 1]);
            let (value, derivative) = hermite(x, ends, (ys[i], ys[i + 1]), (d[i], d[i + 1]));
            assert!(
                (value - y).abs() < 1e-12 && (derivative - slope).abs() < 1e-12,
                "x = {x}: ({value}, {derivative}) vs ({y}, {slope})"
            );
        }
    }

    #[test]
    fn tangents_and_values_match_scipy() {
        // Reference: scipy.interpolate.PchipInterpolator (SciPy 1.17.1) on
        // the same points, its derivative at the points, value and
        // derivative between them.
        check(
            &[0.0, 1.0, 2.0, 4.0, 5.0, 7.0],
            &[0.0, 1.0, 4.0, 4.0, 2.0, 3.0],
            &[0.0, 1.5, 0.0, 0.0, 0.0, 1.5],
            &[
                (0.25, 0.0859375, 0.65625),
                (0.5, 0.3125, 1.125),
                (1.5, 2.6875, 4.125),
                (2.0, 4.0, 0.0),
                (3.1, 4.0, 0.0),
                (4.5, 3.0, -3.0),
                (6.0, 2.125, 0.375),
                (6.9, 2.857375, 1.3537500000000005),
            ],
        );
        // Uneven spacing: the weights of the harmonic mean.
        check(
            &[0.0, 0.3, 1.0, 1.2, 2.5],
            &[0.0, 2.0, 2.5, 4.0, 9.0],
            &[
                8.452380952380953,
                1.4457831325301207,
                1.5399239543726235,
                5.519215044971382,
                0.679487179487178,
            ],
            &[
                (0.1, 0.8620513801236694, 8.406961178045515),
                (0.6, 2.2252834682298013, 0.34211116434165534),
                (1.1, 3.1505177227350325, 9.485215250164003),
                (2.0, 7.874524007749611, 3.601469235098828),
            ],
        );
        // Two points: the line through them.
        assert_eq!(tangents(&[0.0, 2.0], &[1.0, 5.0]), [2.0, 2.0]);
    }
}
