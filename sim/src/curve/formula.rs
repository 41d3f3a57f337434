//! The formula of each piece of a curve, chosen once when the curve is
//! made: what [`Curve::eval_on`] evaluates on a held piece, so that a
//! component that holds a piece (a crush element, a weld) neither searches
//! for the piece's segment nor applies the policy outside at every call.

use super::{Curve, OutOfRange, Outside};
use std::sync::Arc;

/// What [`Curve::eval_on`] evaluates on one piece of a curve.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) enum Formula {
    /// The line of one segment, `y + slope·(x − x0)`, continued past its
    /// ends.
    Line {
        /// The segment's first abscissa.
        x0: f64,
        /// The value there.
        y: f64,
        /// The segment's slope.
        slope: f64,
    },
    /// A value with slope 0: an end held (`hold`), or 0 (`zero`).
    Constant(f64),
    /// No value: the piece lies outside a curve whose policy is `error`.
    OutOfRange,
    /// The curve itself: the one piece of a curve without kinks (a smooth
    /// one), whose formula changes with `x`.
    Curve,
}

impl Formula {
    /// `(y, dy/dx)` at `x` on `curve`, whose formula it is.
    pub(super) fn eval(self, curve: &Curve, x: f64) -> Result<(f64, f64), OutOfRange> {
        match self {
            Formula::Line { x0, y, slope } => Ok((y + slope * (x - x0), slope)),
            Formula::Constant(y) => Ok((y, 0.0)),
            Formula::OutOfRange => Err(OutOfRange {
                x,
                min: curve.xs[0],
                max: curve.xs[curve.xs.len() - 1],
            }),
            Formula::Curve => curve.eval(x),
        }
    }
}

impl Curve {
    /// The formula of each of its pieces, in order ([`Curve::piece`]).
    pub(super) fn piece_formulas(&self) -> Arc<[Formula]> {
        (0..=self.kinks().len()).map(|p| self.formula(p)).collect()
    }

    /// The formula of piece `piece`: the one the curve has at a point inside
    /// the piece (the middle of a piece between two kinks, a unit or the
    /// kink's magnitude beyond a kink at an end).
    fn formula(&self, piece: usize) -> Formula {
        let at = match self.piece_ends(piece) {
            (below, above) if below.is_finite() && above.is_finite() => 0.5 * (below + above),
            (below, _) if below.is_finite() => below + below.abs().max(1.0),
            (_, above) if above.is_finite() => above - above.abs().max(1.0),
            _ => return Formula::Curve,
        };
        if self.tangents.is_some() {
            return Formula::Curve;
        }
        let last = self.xs.len() - 1;
        if !(at >= self.xs[0] && at <= self.xs[last]) {
            match self.outside {
                Outside::Hold if at < self.xs[0] => return Formula::Constant(self.ys[0]),
                Outside::Hold => return Formula::Constant(self.ys[last]),
                Outside::Zero => return Formula::Constant(0.0),
                Outside::Error => return Formula::OutOfRange,
                Outside::Extrapolate => {}
            }
        }
        let i = self.segment(at);
        Formula::Line {
            x0: self.xs[i],
            y: self.ys[i],
            slope: self.slopes[i],
        }
    }
}
