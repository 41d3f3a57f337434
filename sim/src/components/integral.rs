//! The integral of a component's curve over an interval: the elastic
//! energy a spring stores (`∫ F dx`).
//!
//! A curve is a polynomial of degree ≤ 3 between its points (linear, the
//! quadratic force of a secant stiffness, a monotone cubic, and their
//! continuations outside), and Simpson's rule is exact for cubics: so the
//! integral is Simpson's rule on each piece between the curve's points,
//! exact but for rounding, in three evaluations a piece.
//!
//! (An adaptive Simpson rule, which found the kinks by halving, asked for a
//! relative 1e-13 and could not get it where the curve's own rounding is
//! larger — a linear piece evaluated near a zero crossing far from its
//! anchor point — and then halved every span down to its depth limit: one
//! weld's stored energy took a minute.)

/// `∫_a^b f(x) dx` (negative for `b < a`), or the first error of `f`, where
/// `f` is a polynomial of degree ≤ 3 between consecutive points of
/// `breaks` (in any order; those outside `(a, b)` are ignored).
pub(crate) fn integral<E>(
    f: impl Fn(f64) -> Result<f64, E>,
    a: f64,
    b: f64,
    breaks: impl IntoIterator<Item = f64>,
) -> Result<f64, E> {
    let (low, high) = if a <= b { (a, b) } else { (b, a) };
    let mut points: Vec<f64> = (breaks.into_iter())
        .filter(|&x| low < x && x < high)
        .collect();
    points.sort_by(f64::total_cmp);
    points.dedup();
    let mut sum = 0.0;
    let mut from = low;
    for to in points.into_iter().chain([high]) {
        sum += simpson(from, to, &f)?;
        from = to;
    }
    Ok(if a <= b { sum } else { -sum })
}

/// Simpson's rule on `[a, b]`.
fn simpson<E>(a: f64, b: f64, f: &impl Fn(f64) -> Result<f64, E>) -> Result<f64, E> {
    if a == b {
        return Ok(0.0);
    }
    Ok((b - a) / 6.0 * (f(a)? + 4.0 * f(0.5 * (a + b))? + f(b)?))
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::cell::Cell;

    fn exact(f: impl Fn(f64) -> f64, a: f64, b: f64, breaks: &[f64]) -> f64 {
        integral(|x| Ok::<f64, ()>(f(x)), a, b, breaks.iter().copied()).unwrap()
    }

    #[test]
    fn cubic_pieces_are_exact() {
        // ∫_0^2 x³ − x dx = 4 − 2.
        assert!((exact(|x| x * x * x - x, 0.0, 2.0, &[]) - 2.0).abs() < 1e-15);
        assert!((exact(|x| x * x * x - x, 2.0, 0.0, &[]) + 2.0).abs() < 1e-15);
        // A kink at 1/3: ∫_0^1 |x − 1/3| dx = (1/3)²/2 + (2/3)²/2 = 5/18;
        // points outside the interval and repeated ones change nothing.
        let kinked = exact(
            |x| (x - 1.0 / 3.0).abs(),
            0.0,
            1.0,
            &[2.0, 1.0 / 3.0, -1.0, 1.0 / 3.0],
        );
        assert!((kinked / (5.0 / 18.0) - 1.0).abs() < 1e-15, "{kinked}");
        assert_eq!(exact(|x| x, 0.5, 0.5, &[]), 0.0);
        assert_eq!(
            integral(|_| Err::<f64, &str>("outside"), 0.0, 1.0, []),
            Err("outside")
        );
    }

    #[test]
    fn a_line_evaluated_with_rounding_is_integrated_in_three_calls() {
        // The weld of the paper's scenario at a tiny angle: a line of slope
        // 1e5 through (−1, −1e5), evaluated from that far anchor, so its
        // values carry rounding of 1e-11 against a result of 1e-6. The
        // adaptive rule took a minute here; ∫_0^θ 1e5 x dx = 5e4 θ².
        let calls = Cell::new(0);
        let line = |x: f64| {
            calls.set(calls.get() + 1);
            Ok::<f64, ()>(-1e5 + (x + 1.0) * 1e5)
        };
        let theta = -4.654_863_632_895_285e-6;
        let value = integral(line, 0.0, theta, [-1.0, 0.0, 1.0]).unwrap();
        assert!(
            (value / (5e4 * theta * theta) - 1.0).abs() < 1e-9,
            "{value}"
        );
        assert_eq!(calls.get(), 3);
    }
}
