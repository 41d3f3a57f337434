//! Direct floating-point evaluation of expressions (checks and tests; the fast
//! path is the optimized straight-line program, `program::Program`, a
//! module above this one).

use super::{ExprId, Node, Store, SymbolKind};
use rustc_hash::FxHashMap;

/// The values of a model's input functions: `inputs(index, args)` (any
/// `lagrangian_runtime::InputFunctions` is one through `|i, a| f.value(i, a)`).
pub type Inputs<'a> = &'a dyn Fn(usize, &[f64]) -> f64;

/// Inputs of a model without input functions: every call is NaN.
pub fn no_inputs(_input: usize, _args: &[f64]) -> f64 {
    f64::NAN
}

/// Evaluates expressions of one store at one point, caching shared nodes.
pub struct Evaluator<'a> {
    store: &'a Store,
    symbol_values: Vec<f64>,
    inputs: Inputs<'a>,
    cache: FxHashMap<ExprId, f64>,
}

impl<'a> Evaluator<'a> {
    /// `symbol_values[s]` is the value of symbol `s`; π is filled in automatically.
    pub fn new(store: &'a Store, mut symbol_values: Vec<f64>, inputs: Inputs<'a>) -> Self {
        symbol_values.resize(store.symbols().len(), 0.0);
        for (i, s) in store.symbols().iter().enumerate() {
            if s.kind == SymbolKind::Pi {
                symbol_values[i] = std::f64::consts::PI;
            }
        }
        Evaluator {
            store,
            symbol_values,
            inputs,
            cache: FxHashMap::default(),
        }
    }

    /// The value of `e`, computed in `f64` (so `ln` of a negative number is
    /// NaN); nodes shared between calls are computed once.
    pub fn eval(&mut self, e: ExprId) -> f64 {
        if let Some(&v) = self.cache.get(&e) {
            return v;
        }
        let v = match self.store.node(e) {
            Node::Num(c) => c.to_f64(),
            Node::Sym(s) => self.symbol_values[s.index()],
            Node::Add(items) => items.iter().map(|&(t, c)| c.to_f64() * self.eval(t)).sum(),
            Node::Mul(items) => items
                .iter()
                .map(|&(b, x)| {
                    let base = self.eval(b);
                    match x.to_i64().and_then(|n| i32::try_from(n).ok()) {
                        Some(n) => base.powi(n),
                        None => base.powf(x.to_f64()),
                    }
                })
                .product(),
            Node::Func(f, args) => {
                let a = self.eval(args[0]);
                let b = args.get(1).map_or(a, |&b| self.eval(b));
                f.apply(a, b)
            }
            Node::Input(input, args) => {
                let values: Vec<f64> = args.iter().map(|&a| self.eval(a)).collect();
                (self.inputs)(*input as usize, &values)
            }
        };
        self.cache.insert(e, v);
        v
    }
}
