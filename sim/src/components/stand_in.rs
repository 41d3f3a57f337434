//! A smooth stand-in for an input of time over one step of the integration.
//!
//! A time table interpolated linearly has a kink at each of its points: its
//! slope jumps. A Runge–Kutta step across a kink loses its order — the local
//! error of the step's end and of its error estimate grow like `Δslope·h³`
//! — so at a tight tolerance such a step is rejected and retried shorter
//! until the kink hardly matters, and a table with a point every
//! millisecond makes every step near it short.
//!
//! Over a step `[t0, t1]` with kinks of input `u` inside, the stages of the
//! step evaluate instead the cubic `P` with
//!
//! * `P(t0) = u(t0)` and `P(t1) = u(t1)`: the step's first stage, its last
//!   (which the next step reuses) and the ends of its dense output are
//!   those of `u`;
//! * `∫ P = ∫ u` and `∫ t P = ∫ t u` over the step: the step's end responds
//!   to the input through integrals `∫ g(s) u(s) ds` with `g` smooth (how a
//!   force at `s` moves the state at `t1`), and the difference
//!   `∫ g (u − P)` vanishes for linear `g`; what is left is of order
//!   `g''·Δslope·h⁴`, far below the error of the step across the kink.
//!
//! `P` is a cubic, so the method's embedded estimate of order 4 integrates
//! it exactly and the estimate sees no kink. `u` linear over the step gives
//! `P = u`.

/// The nodes and weights of 3-point Gauss–Legendre quadrature on `[−1, 1]`,
/// exact for polynomials of degree ≤ 5: for `x·u` with `u` a piece of
/// degree ≤ 4 between two kinks.
const GAUSS_3: [(f64, f64); 3] = [
    (-0.774_596_669_241_483_4, 5.0 / 9.0),
    (0.0, 8.0 / 9.0),
    (0.774_596_669_241_483_4, 5.0 / 9.0),
];

/// The cubic that stands in for an input over one step (module
/// documentation), `P(x) = c0 + c1 x + c2 x² + c3 x³` in the step's own
/// abscissa `x = 2 (t − t0) / h − 1 ∈ [−1, 1]`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct StandIn {
    t0: f64,
    /// `2 / h`.
    per_half_step: f64,
    c: [f64; 4],
}

impl StandIn {
    /// The stand-in for `u` over `[t0, t0 + h]`, where `kinks` are the kinks
    /// of `u` strictly inside, in increasing order (`u` is smooth between
    /// them: a polynomial of degree ≤ 4 there for the moments to be exact).
    pub fn of(t0: f64, h: f64, kinks: &[f64], u: impl Fn(f64) -> f64) -> StandIn {
        let per_half_step = 2.0 / h;
        let time = |x: f64| t0 + (x + 1.0) / per_half_step;
        // m0 = ∫ u dx and m1 = ∫ x u dx over [−1, 1], piece by piece.
        let (mut m0, mut m1) = (0.0, 0.0);
        let mut from = -1.0;
        let ends = kinks.iter().map(|&k| (k - t0) * per_half_step - 1.0);
        for to in ends.chain([1.0]) {
            let (middle, half) = (0.5 * (from + to), 0.5 * (to - from));
            for (node, weight) in GAUSS_3 {
                let x = middle + half * node;
                let value = half * weight * u(time(x));
                m0 += value;
                m1 += x * value;
            }
            from = to;
        }
        let (u0, u1) = (u(t0), u(t0 + h));
        StandIn::with_moments(t0, per_half_step, (u0, u1), (m0, m1))
    }

    /// [`StandIn::of`] for a `u` that is linear between its `kinks` (a
    /// table interpolated linearly): its moments in closed form from its
    /// values at the ends and at the kinks, one evaluation per kink instead
    /// of the three of each piece's quadrature.
    pub fn of_linear(t0: f64, h: f64, kinks: &[f64], u: impl Fn(f64) -> f64) -> StandIn {
        let per_half_step = 2.0 / h;
        let (u0, u1) = (u(t0), u(t0 + h));
        // On a piece [a, b] through (a, ua) and (b, ub): ∫ u dx =
        // (b − a)(ua + ub)/2 and ∫ x u dx = (b − a)(ua (2a + b) + ub (a + 2b))/6.
        let (mut m0, mut m1) = (0.0, 0.0);
        let (mut a, mut ua) = (-1.0, u0);
        let inside = kinks
            .iter()
            .map(|&k| ((k - t0) * per_half_step - 1.0, u(k)));
        for (b, ub) in inside.chain([(1.0, u1)]) {
            let width = b - a;
            m0 += 0.5 * width * (ua + ub);
            m1 += width * (ua * (2.0 * a + b) + ub * (a + 2.0 * b)) / 6.0;
            (a, ua) = (b, ub);
        }
        StandIn::with_moments(t0, per_half_step, (u0, u1), (m0, m1))
    }

    /// The cubic with `P(t0), P(t1) = ends` and the moments `∫ P dx, ∫ x P
    /// dx = moments` over `x ∈ [−1, 1]`.
    fn with_moments(t0: f64, per_half_step: f64, ends: (f64, f64), moments: (f64, f64)) -> StandIn {
        let ((u0, u1), (m0, m1)) = (ends, moments);
        // P(±1) = u1, u0; ∫P = 2 c0 + 2 c2 / 3 = m0; ∫xP = 2 c1 / 3 + 2 c3 / 5 = m1.
        let (mean, half_rise) = (0.5 * (u0 + u1), 0.5 * (u1 - u0));
        let c2 = 1.5 * (mean - 0.5 * m0);
        let c1 = 3.75 * m1 - 1.5 * half_rise;
        StandIn {
            t0,
            per_half_step,
            c: [mean - c2, c1, c2, half_rise - c1],
        }
    }

    /// `P(t)`.
    #[inline]
    pub fn at(&self, t: f64) -> f64 {
        let x = (t - self.t0) * self.per_half_step - 1.0;
        let [c0, c1, c2, c3] = self.c;
        c0 + x * (c1 + x * (c2 + x * c3))
    }

    /// `P + by`: the same cubic moved by a constant.
    pub fn shifted(self, by: f64) -> StandIn {
        let [c0, c1, c2, c3] = self.c;
        StandIn {
            c: [c0 + by, c1, c2, c3],
            ..self
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A table's linear interpolation through `points`.
    fn linear(points: &[(f64, f64)]) -> impl Fn(f64) -> f64 + '_ {
        move |t| {
            let i = points
                .partition_point(|p| p.0 <= t)
                .clamp(1, points.len() - 1);
            let ((t0, u0), (t1, u1)) = (points[i - 1], points[i]);
            u0 + (u1 - u0) * (t - t0) / (t1 - t0)
        }
    }

    #[test]
    fn it_matches_the_ends_the_integral_and_the_first_moment() {
        // u over [0, 3] through (0, 0), (1, 2), (2, −1), (3, 1), a step
        // with two kinks: ∫u = 1 + 0.5 + 0 = 1.5 by hand, ∫t u from the
        // exact integrals of a line, piece by piece.
        let points = [(0.0, 0.0), (1.0, 2.0), (2.0, -1.0), (3.0, 1.0)];
        let u = linear(&points);
        let p = StandIn::of(0.0, 3.0, &[1.0, 2.0], &u);
        assert!((p.at(0.0) - 0.0).abs() < 1e-14 && (p.at(3.0) - 1.0).abs() < 1e-14);
        // ∫ (α + β t) and ∫ t (α + β t) over each piece, in closed form.
        let (mut integral, mut moment) = (0.0, 0.0);
        for w in points.windows(2) {
            let ((a, ua), (b, ub)) = (w[0], w[1]);
            let beta = (ub - ua) / (b - a);
            let alpha = ua - beta * a;
            integral += alpha * (b - a) + beta * (b * b - a * a) / 2.0;
            moment += alpha * (b * b - a * a) / 2.0 + beta * (b * b * b - a * a * a) / 3.0;
        }
        assert!((integral - 1.5).abs() < 1e-14, "{integral}");
        // The cubic's integrals by a quadrature exact for its degree.
        let gauss = |f: &dyn Fn(f64) -> f64| {
            GAUSS_3
                .iter()
                .map(|&(x, w)| 1.5 * w * f(1.5 + 1.5 * x))
                .sum::<f64>()
        };
        assert!((gauss(&|t| p.at(t)) - integral).abs() < 1e-13);
        assert!((gauss(&|t| t * p.at(t)) - moment).abs() < 1e-13);
        // The closed form for a line between the kinks: the same cubic.
        let linear = StandIn::of_linear(0.0, 3.0, &[1.0, 2.0], &u);
        for (a, b) in linear.c.iter().zip(p.c) {
            assert!((a - b).abs() < 1e-13, "{:?} against {:?}", linear.c, p.c);
        }
        let calls = std::cell::Cell::new(0);
        StandIn::of_linear(0.0, 3.0, &[1.0, 2.0], |t| {
            calls.set(calls.get() + 1);
            u(t)
        });
        assert_eq!(calls.get(), 4, "the ends and the two kinks");
    }

    #[test]
    fn a_line_stands_in_for_itself() {
        let u = |t: f64| 3.0 - 2.0 * t;
        let p = StandIn::of(0.25, 0.5, &[0.4], u);
        for k in 0..=10 {
            let t = 0.25 + 0.05 * k as f64;
            assert!((p.at(t) - u(t)).abs() < 1e-14, "t = {t}");
        }
    }
}
