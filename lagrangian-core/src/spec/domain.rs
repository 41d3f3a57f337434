//! The calls of a spec that are undefined for some arguments — `asin` and
//! `acos` outside `[−1, 1]`, `ln` of a non-positive number, a fractional
//! power of a negative one, a division by zero — kept with where the spec
//! writes them, so that a run that turns non-finite can say which one did.
//!
//! Each is recorded when it is lowered (inner calls first); calls of a
//! constant are checked when the spec is compiled instead.

use super::Model;
use crate::diagnostic::{SpanRange, location};
use crate::expr::{Evaluator, ExprId};

pub use lagrangian_runtime::functions::Domain;

/// One call whose argument has a restricted domain.
#[derive(Clone, Debug)]
pub struct DomainCheck {
    /// What the argument must be.
    pub domain: Domain,
    /// `asin`, `ln`, `a fractional power`, `a divisor`: what the spec calls.
    pub what: &'static str,
    /// The argument (the base of a power, the divisor).
    pub argument: ExprId,
    /// The call as written (the divisor alone, for a division).
    pub span: SpanRange,
}

impl DomainCheck {
    /// `file:line:col: the argument of `acos(2 * x / l)` is 2.5 but must be
    /// in [-1, 1]`, with the call as written in `source`.
    pub fn describe(&self, file: &str, source: &str, value: f64) -> String {
        let text = written(source, self.span);
        format!(
            "{}: {} `{text}` is {value} but {}",
            location(file, self.span),
            self.what,
            self.domain.describe()
        )
    }
}

impl Model {
    /// The first call whose argument is outside its domain at `(t, q, q̇)`
    /// with `parameters` (in declaration order), and that argument; input
    /// functions count as unknown (a call that reads one is skipped).
    pub fn domain_violation(
        &self,
        t: f64,
        q: &[f64],
        qd: &[f64],
        parameters: &[f64],
    ) -> Option<(&DomainCheck, f64)> {
        let mut values = vec![0.0; self.store.symbols().len()];
        values[self.time.index()] = t;
        for (c, (&x, &v)) in self.coordinates.iter().zip(q.iter().zip(qd)) {
            values[c.symbols.position.index()] = x;
            values[c.symbols.velocity.index()] = v;
        }
        for (p, &value) in self.parameters.iter().zip(parameters) {
            values[p.symbol.index()] = value;
        }
        let unknown = |_: usize, _: &[f64]| f64::NAN;
        let mut evaluator = Evaluator::new(&self.store, values, &unknown);
        self.domain_checks.iter().find_map(|check| {
            let x = evaluator.eval(check.argument);
            (!x.is_nan() && !check.domain.contains(x)).then_some((check, x))
        })
    }
}

/// The text of `span` in `source` (to the end of its first line when it
/// spans several).
fn written(source: &str, span: SpanRange) -> String {
    let (start, end) = (span.start.start(), span.end.end());
    let Some(line) = source.lines().nth(start.line.max(1) - 1) else {
        return String::new();
    };
    let chars: Vec<char> = line.chars().collect();
    let stop = if end.line == start.line {
        end.column.min(chars.len())
    } else {
        chars.len()
    };
    chars[start.column.min(stop)..stop].iter().collect()
}
