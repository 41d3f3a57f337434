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

    /// The function as one of the four the compiler does more with than
    /// call it; `None` for a function kept as an atom (a call, with exact
    /// derivatives).
    pub fn elementary(self) -> Option<Elementary> {
        match self {
            Func::Sin => Some(Elementary::Sin),
            Func::Cos => Some(Elementary::Cos),
            Func::Exp => Some(Elementary::Exp),
            Func::Ln => Some(Elementary::Ln),
            Func::Asin
            | Func::Acos
            | Func::Atan
            | Func::Atan2
            | Func::Sinh
            | Func::Cosh
            | Func::Tanh
            | Func::Hypot
            | Func::Abs
            | Func::Sign
            | Func::Min
            | Func::Max => None,
        }
    }

    /// The `f64` method computing the function, which [`Func::apply`] and
    /// the emitted Rust both call; `None` for `sign`, `min` and `max`, which
    /// are this module's functions (they keep NaN).
    pub fn f64_method(self) -> Option<&'static str> {
        match self {
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
            | Func::Hypot
            | Func::Abs => Some(self.name()),
            Func::Sign | Func::Min | Func::Max => None,
        }
    }

    /// Where the (first) argument is defined, for the functions undefined
    /// somewhere: a run that leaves it is reported at the call.
    pub fn domain(self) -> Option<Domain> {
        match self {
            Func::Asin | Func::Acos => Some(Domain::UnitInterval),
            Func::Ln => Some(Domain::Positive),
            Func::Sin
            | Func::Cos
            | Func::Exp
            | Func::Atan
            | Func::Atan2
            | Func::Sinh
            | Func::Cosh
            | Func::Tanh
            | Func::Hypot
            | Func::Abs
            | Func::Sign
            | Func::Min
            | Func::Max => None,
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

/// The functions the expression engine rewrites (angle sums and products,
/// `exp(ln x) = x`) and the program computes with an operation of its own;
/// every other function is an atom and a call ([`Func::elementary`]).
#[derive(Clone, Copy, PartialEq, Eq, Hash, Debug)]
pub enum Elementary {
    /// The sine.
    Sin,
    /// The cosine.
    Cos,
    /// The exponential.
    Exp,
    /// The natural logarithm.
    Ln,
}

/// Where an argument is defined: of a function ([`Func::domain`]), of a
/// square root or fractional power, of a divisor.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Domain {
    /// `[−1, 1]` (`asin`, `acos`).
    UnitInterval,
    /// Positive numbers (`ln`).
    Positive,
    /// Non-negative numbers (`sqrt`, fractional powers).
    NonNegative,
    /// Any number but zero (a divisor, a negative power).
    NonZero,
}

impl Domain {
    /// Whether `x` is in the domain.
    pub fn contains(self, x: f64) -> bool {
        match self {
            Domain::UnitInterval => (-1.0..=1.0).contains(&x),
            Domain::Positive => x > 0.0,
            Domain::NonNegative => x >= 0.0,
            Domain::NonZero => x != 0.0,
        }
    }

    /// The domain in words.
    pub fn describe(self) -> &'static str {
        match self {
            Domain::UnitInterval => "must be in [-1, 1]",
            Domain::Positive => "must be positive",
            Domain::NonNegative => "must not be negative",
            Domain::NonZero => "must not be zero",
        }
    }

    /// Why a constant argument outside the domain is refused (`Positive`
    /// is the logarithm's, the only function defined there).
    pub fn refusal(self) -> &'static str {
        match self {
            Domain::UnitInterval => "it is defined on [-1, 1] only",
            Domain::Positive => "the logarithm is defined for positive numbers only",
            Domain::NonNegative => "it is defined for non-negative numbers only",
            Domain::NonZero => "it is not defined at zero",
        }
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
    fn each_function_has_its_facts() {
        for f in Func::ALL {
            // The f64 method is the one `apply` calls: compare at a point
            // inside every domain.
            let (a, b): (f64, f64) = (0.375, 0.625);
            if let Some(method) = f.f64_method() {
                let direct = match method {
                    "sin" => a.sin(),
                    "cos" => a.cos(),
                    "exp" => a.exp(),
                    "ln" => a.ln(),
                    "asin" => a.asin(),
                    "acos" => a.acos(),
                    "atan" => a.atan(),
                    "atan2" => a.atan2(b),
                    "sinh" => a.sinh(),
                    "cosh" => a.cosh(),
                    "tanh" => a.tanh(),
                    "hypot" => a.hypot(b),
                    "abs" => a.abs(),
                    other => panic!("no f64 method {other}"),
                };
                assert_eq!(f.apply(a, b).to_bits(), direct.to_bits(), "{}", f.name());
            }
            if let Some(domain) = f.domain() {
                assert!(domain.contains(a), "{}", f.name());
                assert!(!domain.contains(-1.5), "{}", f.name());
            }
        }
        let elementary: Vec<&str> = (Func::ALL.into_iter())
            .filter(|f| f.elementary().is_some())
            .map(Func::name)
            .collect();
        assert_eq!(elementary, ["sin", "cos", "exp", "ln"]);
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
