//! Holding one piece of a piecewise-linear curve through the steps of an
//! integration.
//!
//! The slope of a curve interpolated linearly jumps at its kinks: a step
//! across one has a large error and is rejected, again and again, until
//! it is tiny. A component that holds the piece its argument is on
//! evaluates that piece's formula, continued past its ends, so its value
//! is smooth within every step; leaving the piece is an event (the
//! argument falls to the kink below, or rises to the kink above), located
//! on the step's dense output, after which the component holds the next
//! piece and the step sequence restarts there. Within the piece the held
//! formula and the curve agree: only the steps change.

use super::Event;
use crate::curve::{Curve, OutOfRange};
use crate::ode::Direction;

/// The piece of a curve a component's value follows ([`Curve::piece`]),
/// or none: the curve itself.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Held(Option<usize>);

/// Which end of its piece the argument crossed.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Crossed {
    /// The kink below: the piece below comes next.
    Below,
    /// The kink above: the piece above comes next.
    Above,
}

/// The two events of a held piece, in the order of [`Held::event_values`]:
/// the argument falls to the kink below, or rises to the kink above.
pub const fn events(below: &'static str, above: &'static str) -> [Event; 2] {
    [
        Event {
            name: below,
            direction: Direction::Falling,
        },
        Event {
            name: above,
            direction: Direction::Rising,
        },
    ]
}

impl Held {
    /// Nothing held: the curve as it is.
    pub const NONE: Held = Held(None);

    /// The piece of `curve` that `x` is on if `hold`, else nothing.
    pub fn at(curve: &Curve, x: f64, hold: bool) -> Held {
        Held(hold.then(|| curve.piece(x)))
    }

    /// `(y, dy/dx)` of `curve` at `x` on the held piece ([`Curve::eval_on`]).
    pub fn eval(self, curve: &Curve, x: f64) -> Result<(f64, f64), OutOfRange> {
        curve.eval_on(self.0, x)
    }

    /// The piece held, if any.
    pub fn piece(self) -> Option<usize> {
        self.0
    }

    /// The two event functions at argument `x`, which never falls below
    /// `floor` (0 for a curve in `|x|`): `x` less the kink below (falling)
    /// and `x` less the kink above (rising). Where there is no such kink
    /// (above `floor`), or nothing is held, each is a constant of the sign
    /// that cannot trigger it.
    pub fn event_values(self, curve: &Curve, x: f64, floor: f64) -> [f64; 2] {
        let Some(piece) = self.0 else {
            return [1.0, -1.0];
        };
        let (below, above) = curve.piece_ends(piece);
        [
            if below > floor { x - below } else { 1.0 },
            if above.is_finite() { x - above } else { -1.0 },
        ]
    }

    /// Moves across the kink `crossed` of `curve`, the argument now at `x`:
    /// to the next piece, or further if `x` lies beyond it (a crossing
    /// seen late, as by an importer of an FMU that steps across two kinks).
    pub fn cross(&mut self, curve: &Curve, crossed: Crossed, x: f64) {
        if let Some(piece) = &mut self.0 {
            *piece = match crossed {
                Crossed::Below => piece.saturating_sub(1).min(curve.piece(x)),
                Crossed::Above => (*piece + 1).max(curve.piece(x)),
            };
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::curve::Outside;

    /// (0, 0), (1, 1), (2, 1), (3, 4): kinks at 1 and 2, the ends held.
    fn curve() -> Curve {
        Curve::new(
            vec![0.0, 1.0, 2.0, 3.0],
            vec![0.0, 1.0, 1.0, 4.0],
            Outside::Hold,
        )
        .unwrap()
    }

    #[test]
    fn a_held_piece_continues_its_formula_past_its_kinks() {
        let curve = curve();
        assert_eq!(curve.kinks(), [0.0, 1.0, 2.0, 3.0]);
        let held = Held::at(&curve, 0.5, true);
        assert_eq!(held.piece(), Some(1));
        // On its piece, the curve; past the kink at 1, the line y = x.
        assert_eq!(held.eval(&curve, 0.5).unwrap(), curve.eval(0.5).unwrap());
        assert_eq!(held.eval(&curve, 1.5).unwrap(), (1.5, 1.0));
        assert_eq!(curve.eval(1.5).unwrap(), (1.0, 0.0));
        // Below 0 the piece of the held end value, above 3 that of 4.
        assert_eq!(
            Held::at(&curve, -1.0, true).eval(&curve, 0.5).unwrap(),
            (0.0, 0.0)
        );
        assert_eq!(
            Held::at(&curve, 3.5, true).eval(&curve, 2.5).unwrap(),
            (4.0, 0.0)
        );
        // Nothing held: the curve.
        assert_eq!(Held::NONE.eval(&curve, 1.5).unwrap(), (1.0, 0.0));
        assert_eq!(Held::at(&curve, 0.5, false), Held::NONE);
    }

    #[test]
    fn its_events_are_the_kinks_at_its_ends() {
        let curve = curve();
        let mut held = Held::at(&curve, 1.5, true);
        assert_eq!(
            held.event_values(&curve, 1.25, f64::NEG_INFINITY),
            [0.25, -0.75]
        );
        // Crossed on the kink: the next piece.
        held.cross(&curve, Crossed::Above, 2.0);
        assert_eq!(
            held.event_values(&curve, 2.5, f64::NEG_INFINITY),
            [0.5, -0.5]
        );
        held.cross(&curve, Crossed::Above, 3.0);
        // Above the last kink: nothing to rise to.
        assert_eq!(
            held.event_values(&curve, 3.5, f64::NEG_INFINITY),
            [0.5, -1.0]
        );
        // Seen late, beyond the next kink too: the piece the argument is on.
        held.cross(&curve, Crossed::Below, 0.5);
        assert_eq!(held.piece(), Some(1));
        held.cross(&curve, Crossed::Above, 1.0);
        assert_eq!(held.piece(), Some(2));
        // On the first piece of a curve in |x| nothing lies below 0.
        let first = Held::at(&curve, 0.5, true);
        assert_eq!(first.event_values(&curve, 0.5, 0.0), [1.0, -0.5]);
        assert_eq!(
            first.event_values(&curve, 0.5, f64::NEG_INFINITY),
            [0.5, -0.5]
        );
        assert_eq!(Held::NONE.event_values(&curve, 0.5, 0.0), [1.0, -1.0]);
    }
}
