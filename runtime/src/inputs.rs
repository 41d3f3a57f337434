//! How run-time inputs (a crush characteristic, a barrier force table, a
//! constant) reach a model's input functions.

/// The run-time values of a model's input functions.
///
/// Generated code and the interpreter call `value(index, args)` with the
/// input's number in declaration order and its evaluated arguments. A closure
/// `|index, args| …` implements it, and so do [`NoInputs`] and [`ConstantInputs`].
pub trait InputFunctions {
    /// Value of input function number `input` (declaration order) at `args`.
    fn value(&self, input: usize, args: &[f64]) -> f64;
}

impl<F: Fn(usize, &[f64]) -> f64> InputFunctions for F {
    fn value(&self, input: usize, args: &[f64]) -> f64 {
        self(input, args)
    }
}

/// For models without input functions: any call yields NaN, which the
/// integrators report as a non-finite output rather than a wrong number.
#[derive(Clone, Copy, Debug, Default)]
pub struct NoInputs;

impl InputFunctions for NoInputs {
    fn value(&self, _input: usize, _args: &[f64]) -> f64 {
        f64::NAN
    }
}

/// Every input function is a constant: `values[index]` (NaN beyond the list).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct ConstantInputs(pub Vec<f64>);

impl InputFunctions for ConstantInputs {
    fn value(&self, input: usize, _args: &[f64]) -> f64 {
        self.0.get(input).copied().unwrap_or(f64::NAN)
    }
}
