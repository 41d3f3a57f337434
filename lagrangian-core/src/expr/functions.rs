//! The functions kept as atoms beside sin, cos, exp and ln: how they are
//! built and their exact partial derivatives.
//!
//! * Smooth: `asin`, `acos`, `atan`, `atan2`, `sinh`, `cosh`, `tanh`,
//!   `hypot`; each derivative is written in the function's own atoms and
//!   powers of its arguments (`d tanh u = cosh⁻²u du`,
//!   `∂ hypot(x, y)/∂x = x · hypot(x, y)⁻¹`).
//! * Non-smooth, differentiated by branch: `d|u| = sign(u) du`,
//!   `d sign(u) = 0`, and `min`/`max` pick the branch with
//!   `s = sign(a − b)`: `∂min/∂a = (1 − s)/2`, `∂min/∂b = (1 + s)/2` (and
//!   the reverse for `max`). Where the branches meet the derivative is
//!   their mean; the integrator never steps across such a point
//!   (the switching functions are located as events).
//!
//! Only the non-smooth functions of rational constants are folded; the
//! others stay atoms (`asin(1/2)` is not rewritten to `π/6`).

use super::{ExprId, Func, Store};
use crate::rational::Rational;

impl Store {
    /// `f(args…)` for a function other than sin, cos, exp and ln.
    pub(crate) fn call(&mut self, f: Func, args: &[ExprId]) -> ExprId {
        debug_assert_eq!(args.len(), f.arity());
        if let Some(value) = self.fold(f, args) {
            return self.num(value);
        }
        self.call_node(f, args)
    }

    /// The value of a non-smooth function of rational constants (`None`
    /// for the others, and where the comparison would overflow).
    fn fold(&self, f: Func, args: &[ExprId]) -> Option<Rational> {
        let values: Vec<Rational> = args
            .iter()
            .map(|&a| self.as_num(a))
            .collect::<Option<_>>()?;
        let sign = |x: Rational| match (x.is_zero(), x.is_negative()) {
            (true, _) => Rational::ZERO,
            (false, true) => Rational::MINUS_ONE,
            (false, false) => Rational::ONE,
        };
        let below = |x: Rational, y: Rational| Some(x.checked_sub(y)?.is_negative());
        match f {
            Func::Abs if values[0].is_negative() => values[0].checked_neg(),
            Func::Abs => Some(values[0]),
            Func::Sign => Some(sign(values[0])),
            Func::Min => Some(if below(values[1], values[0])? {
                values[1]
            } else {
                values[0]
            }),
            Func::Max => Some(if below(values[0], values[1])? {
                values[1]
            } else {
                values[0]
            }),
            Func::Sin
            | Func::Cos
            | Func::Exp
            | Func::Ln
            | Func::Asin
            | Func::Acos
            | Func::Atan
            | Func::Atan2
            | Func::Sinh
            | Func::Cosh
            | Func::Tanh
            | Func::Hypot => None,
        }
    }

    /// `∂f/∂arg_k` at `args`, for every argument `k`; `call` is `f(args…)`.
    pub(crate) fn partials(&mut self, f: Func, args: &[ExprId], call: ExprId) -> Vec<ExprId> {
        let u = args[0];
        match f {
            Func::Sin => vec![self.cos(u)],
            Func::Cos => {
                let sin = self.sin(u);
                vec![self.neg(sin)]
            }
            Func::Exp => vec![call],
            Func::Ln => vec![self.pow(u, Rational::MINUS_ONE)],
            Func::Asin => vec![self.one_minus_square_root(u, Rational::ONE)],
            Func::Acos => vec![self.one_minus_square_root(u, Rational::MINUS_ONE)],
            Func::Atan => {
                let sum = self.sum_of_squares(Store::ONE, &[u]);
                vec![self.pow(sum, Rational::MINUS_ONE)]
            }
            Func::Atan2 => {
                let (y, x) = (args[0], args[1]);
                let sum = self.sum_of_squares(Store::ZERO, &[y, x]);
                let inverse = self.pow(sum, Rational::MINUS_ONE);
                let minus_y = self.neg(y);
                vec![self.mul(x, inverse), self.mul(minus_y, inverse)]
            }
            Func::Sinh => vec![self.call(Func::Cosh, args)],
            Func::Cosh => vec![self.call(Func::Sinh, args)],
            Func::Tanh => {
                // cosh⁻²u rather than 1 − tanh²u, which cancels for large |u|.
                let cosh = self.call(Func::Cosh, args);
                vec![self.pow(cosh, Rational::integer(-2))]
            }
            Func::Hypot => {
                let inverse = self.pow(call, Rational::MINUS_ONE);
                args.iter().map(|&a| self.mul(a, inverse)).collect()
            }
            Func::Abs => vec![self.call(Func::Sign, args)],
            Func::Sign => vec![Store::ZERO],
            Func::Min | Func::Max => self.branch_partials(f, args),
        }
    }

    /// `c · (1 − u²)^(−1/2)`.
    fn one_minus_square_root(&mut self, u: ExprId, c: Rational) -> ExprId {
        let square = self.pow(u, Rational::integer(2));
        let rest = self.sub(Store::ONE, square);
        let root = self.pow(rest, Rational::new(-1, 2).expect("a nonzero denominator"));
        self.scale(root, c)
    }

    /// `start + Σ a²` over `args`.
    fn sum_of_squares(&mut self, start: ExprId, args: &[ExprId]) -> ExprId {
        let mut sum = start;
        for &a in args {
            let square = self.pow(a, Rational::integer(2));
            sum = self.add(sum, square);
        }
        sum
    }

    /// `(∂/∂a, ∂/∂b)` of `min(a, b)` or `max(a, b)`: `(1 ∓ s)/2` and
    /// `(1 ± s)/2` with `s = sign(a − b)`.
    fn branch_partials(&mut self, f: Func, args: &[ExprId]) -> Vec<ExprId> {
        let difference = self.sub(args[0], args[1]);
        let s = self.call(Func::Sign, &[difference]);
        let half_s = self.scale(s, Rational::HALF);
        let half = self.num(Rational::HALF);
        let (plus, minus) = (self.add(half, half_s), self.sub(half, half_s));
        if f == Func::Max {
            vec![plus, minus]
        } else {
            vec![minus, plus]
        }
    }
}
