//! The operations native code calls rather than emits: each an
//! `extern "C"` function calling the same `f64` method the interpreter and
//! the compiled models call, so the three agree bit for bit.

use lagrangian_runtime::Func;

/// A one-argument operation (`sin`, `cos`, `exp`, `ln`).
pub(crate) type Unary = extern "C" fn(f64) -> f64;
/// A two-argument operation (`powf` and the spec's functions).
pub(crate) type Binary = extern "C" fn(f64, f64) -> f64;
/// `a^k` for an integer `k`.
pub(crate) type Powi = extern "C" fn(f64, i32) -> f64;

pub(crate) extern "C" fn sin(a: f64) -> f64 {
    a.sin()
}

pub(crate) extern "C" fn cos(a: f64) -> f64 {
    a.cos()
}

pub(crate) extern "C" fn exp(a: f64) -> f64 {
    a.exp()
}

pub(crate) extern "C" fn ln(a: f64) -> f64 {
    a.ln()
}

pub(crate) extern "C" fn powi(a: f64, k: i32) -> f64 {
    a.powi(k)
}

pub(crate) extern "C" fn powf(a: f64, b: f64) -> f64 {
    a.powf(b)
}

/// `Func::ALL[K]` at `(a, b)`, as the interpreter applies it.
extern "C" fn apply<const K: usize>(a: f64, b: f64) -> f64 {
    Func::ALL[K].apply(a, b)
}

/// One shim per function of [`Func::ALL`], in its order (a new function
/// makes this list the wrong length: a compile error).
const FUNCTIONS: [Binary; Func::ALL.len()] = [
    apply::<0>,
    apply::<1>,
    apply::<2>,
    apply::<3>,
    apply::<4>,
    apply::<5>,
    apply::<6>,
    apply::<7>,
    apply::<8>,
    apply::<9>,
    apply::<10>,
    apply::<11>,
    apply::<12>,
    apply::<13>,
    apply::<14>,
    apply::<15>,
];

/// The shim computing `function`.
pub(crate) fn function(function: Func) -> Binary {
    let k =
        (Func::ALL.iter().position(|&f| f == function)).expect("every function is in Func::ALL");
    FUNCTIONS[k]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn each_shim_is_its_function() {
        for f in Func::ALL {
            for (a, b) in [(0.3, -1.2), (-0.7, 2.5), (0.0, 0.0), (f64::NAN, 1.0)] {
                let (shim, direct) = (function(f)(a, b), f.apply(a, b));
                // A NaN's sign is not specified: `ln(-0.7)` from the C
                // library and folded by the optimizer differ in it.
                assert!(
                    shim.to_bits() == direct.to_bits() || (shim.is_nan() && direct.is_nan()),
                    "{f:?}({a}, {b}): {shim} against {direct}"
                );
            }
        }
        assert_eq!(powi(1.1, -3).to_bits(), 1.1f64.powi(-3).to_bits());
    }
}
