//! Cubic Hermite interpolation: the dense output of RK4 and TR-BDF2, and the
//! refinement of sampled extrema.

use super::{DenseStep, OdeVector, Part, driver::Truncate};

/// The weights of `(y0, f0, y1, f1)` in the cubic Hermite interpolant on a
/// step of size `h`, at `s = (t − t0)/h`:
/// `y(t) = w0·y0 + w1·f0 + w2·y1 + w3·f1` (`f` the derivatives).
#[inline]
pub fn hermite_weights(s: f64, h: f64) -> [f64; 4] {
    let (s2, s3) = (s * s, s * s * s);
    [
        2.0 * s3 - 3.0 * s2 + 1.0,
        h * (s3 - 2.0 * s2 + s),
        -2.0 * s3 + 3.0 * s2,
        h * (s3 - s2),
    ]
}

/// Cubic Hermite interpolation between `(y0, f0)` at `t0` and `(y1, f1)` at
/// `t0 + h`, reported as covering `[t0, end]` (`end < t0 + h` at an event).
pub struct Hermite<Y> {
    /// Start of the step \[s\].
    pub t0: f64,
    /// Length of the step the interpolant spans \[s\]; positive.
    pub h: f64,
    /// End of the interval it reports covering \[s\], `t0 < end ≤ t0 + h`.
    pub end: f64,
    /// The state at `t0`.
    pub y0: Y,
    /// The derivative of the state at `t0`.
    pub f0: Y,
    /// The state at `t0 + h`.
    pub y1: Y,
    /// The derivative of the state at `t0 + h`.
    pub f1: Y,
}

impl<Y: OdeVector> DenseStep<Y> for Hermite<Y> {
    fn t0(&self) -> f64 {
        self.t0
    }

    fn t1(&self) -> f64 {
        self.end
    }

    fn uncut_end(&self) -> f64 {
        self.t0 + self.h
    }

    fn eval(&self, t: f64, out: &mut Y) {
        self.eval_part(t, Part::All, out);
    }

    fn eval_part(&self, t: f64, part: Part, out: &mut Y) {
        let [w0, w1, w2, w3] = hermite_weights((t - self.t0) / self.h, self.h);
        out.set_part_sum(
            part,
            &[
                (w0, &self.y0),
                (w1, &self.f0),
                (w2, &self.y1),
                (w3, &self.f1),
            ],
        );
    }
}

impl<Y> Truncate for Hermite<Y> {
    fn truncate(self, end: f64) -> Self {
        Hermite { end, ..self }
    }
}
