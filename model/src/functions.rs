//! The elementary functions of the spec language: their names, arities and
//! values, one source for the compiler, its emitters and the interpreter.
//!
//! The compiled Rust and the interpreter evaluate every function the same
//! way ([`Func::apply`] calls the same `f64` methods the emitted code
//! calls, and [`sign`], [`min`] and [`max`] are called by both), so the two
//! agree bit for bit.

/// An elementary function: the sine, cosine, exponential and logarithm the
/// expression engine rewrites, the smooth functions kept as atoms with
/// exact derivatives, and the non-smooth ones differentiated by branch
/// whose kinks are located by the integrator ([`Func::switching`]).
#[derive(Clone, Copy, PartialEq, Eq, Hash, Debug, PartialOrd, Ord)]
pub enum Func {
    /// The sine, of an argument in radians.
    Sin,
    /// The cosine, of an argument in radians.
    Cos,
    /// The exponential.
    Exp,
    /// The natural logarithm.
    Ln,
    /// The arcsine, in `[−π/2, π/2]`, of an argument in `[−1, 1]`.
    Asin,
    /// The arccosine, in `[0, π]`, of an argument in `[−1, 1]`.
    Acos,
    /// The arctangent, in `(−π/2, π/2)`.
    Atan,
    /// `atan2(y, x)`: the angle of the point `(x, y)`, in `(−π, π]`.
    Atan2,
    /// The hyperbolic sine.
    Sinh,
    /// The hyperbolic cosine.
    Cosh,
    /// The hyperbolic tangent.
    Tanh,
    /// `hypot(x, y) = √(x² + y²)`, without overflow.
    Hypot,
    /// The absolute value (non-smooth at 0).
    Abs,
    /// The sign: −1, 0 or 1 (a jump at 0).
    Sign,
    /// The smaller of two values (non-smooth where they are equal).
    Min,
    /// The larger of two values (non-smooth where they are equal).
    Max,
}

/// Where a non-smooth function has its kink: the sign change of which
/// expression of its arguments.
#[derive(Clone, Copy, PartialEq, Eq, Hash, Debug)]
pub enum Switching {
    /// The argument itself (`abs`, `sign`).
    Argument,
    /// The first argument minus the second (`min`, `max`).
    Difference,
}

impl Func {
    /// Every function, in declaration order.
    pub const ALL: [Func; 16] = [
        Func::Sin,
        Func::Cos,
        Func::Exp,
        Func::Ln,
        Func::Asin,
        Func::Acos,
        Func::Atan,
        Func::Atan2,
        Func::Sinh,
        Func::Cosh,
        Func::Tanh,
        Func::Hypot,
        Func::Abs,
        Func::Sign,
        Func::Min,
        Func::Max,
    ];

    /// The name in the spec language.
    pub fn name(self) -> &'static str {
        match self {
            Func::Sin => "sin",
            Func::Cos => "cos",
            Func::Exp => "exp",
            Func::Ln => "ln",
            Func::Asin => "asin",
            Func::Acos => "acos",
            Func::Atan => "atan",
            Func::Atan2 => "atan2",
            Func::Sinh => "sinh",
            Func::Cosh => "cosh",
            Func::Tanh => "tanh",
            Func::Hypot => "hypot",
            Func::Abs => "abs",
            Func::Sign => "sign",
            Func::Min => "min",
            Func::Max => "max",
        }
    }

    /// The function called `name` in the spec language.
    pub fn named(name: &str) -> Option<Func> {
        Func::ALL.into_iter().find(|f| f.name() == name)
    }

    /// The number of arguments.
    pub fn arity(self) -> usize {
        match self {
            Func::Atan2 | Func::Hypot | Func::Min | Func::Max => 2,
            Func::Sin
            | Func::Cos
            | Func::Exp
            | Func::Ln
            | Func::Asin
            | Func::Acos
            | Func::Atan
            | Func::Sinh
            | Func::Cosh
            | Func::Tanh
            | Func::Abs
            | Func::Sign => 1,
        }
    }

    /// Whether the arguments must be dimensionless (all but `hypot`, `abs`,
    /// `sign`, `min`, `max`, and `atan2`, whose two arguments share a
    /// dimension that cancels). The others take arguments of one dimension;
    /// `hypot`, `abs`, `min` and `max` return it.
    pub fn needs_dimensionless(self) -> bool {
        match self {
            Func::Sin
            | Func::Cos
            | Func::Exp
            | Func::Ln
            | Func::Asin
            | Func::Acos
            | Func::Atan
            | Func::Sinh
            | Func::Cosh
            | Func::Tanh => true,
            Func::Atan2 | Func::Hypot | Func::Abs | Func::Sign | Func::Min | Func::Max => false,
        }
    }

    /// Whether the result has the dimension of the arguments (`hypot`,
    /// `abs`, `min`, `max`); otherwise it is dimensionless.
    pub fn keeps_dimension(self) -> bool {
        matches!(self, Func::Hypot | Func::Abs | Func::Min | Func::Max)
    }

    /// The switching function of a non-smooth function; `None` for a smooth one.
    pub fn switching(self) -> Option<Switching> {
        match self {
            Func::Abs | Func::Sign => Some(Switching::Argument),
            Func::Min | Func::Max => Some(Switching::Difference),
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

    /// The value at `a` (and `b`, the second argument of a two-argument
    /// function; ignored by the others).
    #[inline(always)]
    pub fn apply(self, a: f64, b: f64) -> f64 {
        match self {
            Func::Sin => a.sin(),
            Func::Cos => a.cos(),
            Func::Exp => a.exp(),
            Func::Ln => a.ln(),
            Func::Asin => a.asin(),
            Func::Acos => a.acos(),
            Func::Atan => a.atan(),
            Func::Atan2 => a.atan2(b),
            Func::Sinh => a.sinh(),
            Func::Cosh => a.cosh(),
            Func::Tanh => a.tanh(),
            Func::Hypot => a.hypot(b),
            Func::Abs => a.abs(),
            Func::Sign => sign(a),
            Func::Min => min(a, b),
            Func::Max => max(a, b),
        }
    }
}

/// The sign of `x`: 1 above zero, −1 below, `x` itself at ±0 and NaN (so
/// that a NaN argument stays visible).
#[inline(always)]
pub fn sign(x: f64) -> f64 {
    if x > 0.0 {
        1.0
    } else if x < 0.0 {
        -1.0
    } else {
        x
    }
}

/// The smaller of `a` and `b`; NaN when either is (unlike `f64::min`, which
/// would hide a fault).
#[inline(always)]
pub fn min(a: f64, b: f64) -> f64 {
    if a <= b {
        a
    } else if b < a {
        b
    } else {
        a + b
    }
}

/// The larger of `a` and `b`; NaN when either is.
#[inline(always)]
pub fn max(a: f64, b: f64) -> f64 {
    if a >= b {
        a
    } else if b > a {
        b
    } else {
        a + b
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_read_back() {
        for f in Func::ALL {
            assert_eq!(Func::named(f.name()), Some(f));
        }
        assert_eq!(Func::named("arccos"), None);
    }

    #[test]
    fn non_smooth_functions_keep_nan_and_zero() {
        assert_eq!(sign(-3.0), -1.0);
        assert_eq!(sign(2.0), 1.0);
        assert_eq!(sign(0.0), 0.0);
        assert!(sign(f64::NAN).is_nan());
        assert_eq!(min(1.0, 2.0), 1.0);
        assert_eq!(max(1.0, 2.0), 2.0);
        assert!(min(f64::NAN, 2.0).is_nan());
        assert!(max(1.0, f64::NAN).is_nan());
        assert_eq!(Func::Atan2.apply(1.0, -1.0), 0.75 * std::f64::consts::PI);
        assert_eq!(Func::Hypot.apply(3.0, 4.0), 5.0);
    }
}
