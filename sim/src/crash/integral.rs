//! The integral of a component's curve over an interval: the elastic
//! energy a spring stores (`∫ F dx`), asked for at events only.
//!
//! Adaptive Simpson quadrature with Richardson's correction. Simpson's rule
//! is exact for cubics, so on a span where a curve is one polynomial piece
//! (linear, the quadratic force of a secant stiffness, a monotone cubic)
//! it is exact at once; only the spans across a kink of the curve are
//! halved, until the two estimates agree to a relative `1e-13`.

/// How many times a span may be halved.
const DEPTH: u32 = 48;

/// The relative agreement asked of the two estimates of a span.
const TOLERANCE: f64 = 1e-13;

/// `∫_a^b f(x) dx` (negative for `b < a`), or the first error of `f`.
pub(crate) fn integral<E>(f: impl Fn(f64) -> Result<f64, E>, a: f64, b: f64) -> Result<f64, E> {
    if a == b {
        return Ok(0.0);
    }
    let (fa, fm, fb) = (f(a)?, f(0.5 * (a + b))?, f(b)?);
    let whole = simpson(a, b, fa, fm, fb);
    let scale = (fa.abs() + fm.abs() + fb.abs()) * (b - a).abs();
    let span = Span { a, b, fa, fm, fb };
    refine(&f, span, whole, TOLERANCE * scale, DEPTH)
}

/// A span with its ends and middle evaluated.
#[derive(Clone, Copy)]
struct Span {
    a: f64,
    b: f64,
    fa: f64,
    fm: f64,
    fb: f64,
}

/// Simpson's rule on `[a, b]`.
fn simpson(a: f64, b: f64, fa: f64, fm: f64, fb: f64) -> f64 {
    (b - a) / 6.0 * (fa + 4.0 * fm + fb)
}

/// The integral over `span`, whose Simpson estimate is `whole`, to an
/// absolute `tolerance`.
fn refine<E>(
    f: &impl Fn(f64) -> Result<f64, E>,
    span: Span,
    whole: f64,
    tolerance: f64,
    depth: u32,
) -> Result<f64, E> {
    let Span { a, b, fa, fm, fb } = span;
    let m = 0.5 * (a + b);
    let (fl, fr) = (f(0.5 * (a + m))?, f(0.5 * (m + b))?);
    let left = simpson(a, m, fa, fl, fm);
    let right = simpson(m, b, fm, fr, fb);
    let difference = left + right - whole;
    if depth == 0 || difference.abs() <= 15.0 * tolerance {
        return Ok(left + right + difference / 15.0);
    }
    let halves = (
        Span {
            a,
            b: m,
            fa,
            fm: fl,
            fb: fm,
        },
        Span {
            a: m,
            b,
            fa: fm,
            fm: fr,
            fb,
        },
    );
    Ok(refine(f, halves.0, left, tolerance / 2.0, depth - 1)?
        + refine(f, halves.1, right, tolerance / 2.0, depth - 1)?)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn exact(f: impl Fn(f64) -> f64, a: f64, b: f64) -> f64 {
        integral(|x| Ok::<f64, ()>(f(x)), a, b).unwrap()
    }

    #[test]
    fn cubics_are_exact_and_kinks_converge() {
        // ∫_0^2 x³ − x dx = 4 − 2.
        assert!((exact(|x| x * x * x - x, 0.0, 2.0) - 2.0).abs() < 1e-15);
        assert!((exact(|x| x * x * x - x, 2.0, 0.0) + 2.0).abs() < 1e-15);
        // A kink at 1/3 (not a point of any halving): ∫_0^1 |x − 1/3| dx
        // = (1/3)²/2 + (2/3)²/2 = 5/18.
        let kinked = exact(|x| (x - 1.0 / 3.0).abs(), 0.0, 1.0);
        assert!((kinked / (5.0 / 18.0) - 1.0).abs() < 1e-12, "{kinked}");
        assert_eq!(exact(|x| x, 0.5, 0.5), 0.0);
        assert_eq!(
            integral(|_| Err::<f64, &str>("outside"), 0.0, 1.0),
            Err("outside")
        );
    }
}
