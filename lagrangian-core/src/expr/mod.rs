//! The symbolic expression engine: a hash-consed DAG kept in an *expanded
//! canonical form*.
//!
//! Every expression is a sum of monomials with exact rational coefficients:
//!
//! ```text
//! e = Σ_k c_k · Π_j b_kj^(e_kj)
//! ```
//!
//! where the bases `b` are *atoms* (symbols, `sin u`, `cos u`, `exp u`, `ln u`,
//! input-function calls) or, with a negative or fractional exponent, a sum.
//! Products of sums are distributed as soon as they are built, and products of
//! sines and cosines are linearized (`cos a · cos b = ½cos(a−b) + ½cos(a+b)`),
//! so a monomial without negative trigonometric powers carries at most one
//! sine or cosine, to the first power. Negative integer powers of `sin u` and
//! `cos u` stay atoms; within their monomial the sines and cosines of
//! integer multiples of `u` are rewritten in `sin u`, `cos u` and merged with
//! them, leaving `sin⁻ᵏu` (times at most `cos u`) or `cos⁻ᵏu` (times at most
//! `sin u`); and a sum that is the linearized `c · sinᵏu · cosˡu` raised to a
//! negative power becomes those atoms (module `laurent`).
//!
//! The form is *canonical* when equal expressions are the same node. It is
//! canonical for:
//!
//! * polynomials in the sines and cosines of rational combinations of the
//!   symbols, whatever else multiplies them: the cross terms of a kinetic
//!   energy cancel exactly and `sin² + cos²` folds to 1;
//! * negative powers of `sin u` and `cos u` for one argument `u` per
//!   monomial, next to sines and cosines of multiples of `u`: `sin²θ / sin θ`
//!   is `sin θ`, `tan θ · cos²θ` is `sin θ cos θ`.
//!
//! It is **not** canonical, and equal expressions may be different nodes,
//! for:
//!
//! * a negative power next to a sine or cosine of an unrelated argument
//!   (`sin(θ₁ − θ₂) / sin θ₁`);
//! * negative powers of both `sin u` and `sin 2u`;
//! * sums under fractional powers, or divided by a sum that is not a
//!   sine–cosine monomial (`1 / (1 + cos θ)`);
//! * `exp`/`ln` identities;
//! * `π` inside an argument (a symbol here: `sin(θ + π)` is not `−sin θ`).
//!
//! The audit compares numerically where the symbolic comparison is
//! inconclusive.
//!
//! Nodes are interned, so structurally equal expressions share one [`ExprId`]
//! and comparing expressions is comparing integers.

mod arith;
mod calculus;
mod display;
mod eval;
mod functions;
mod laurent;
pub mod pretty;
mod trig;

pub use calculus::CoordinateSymbols;
pub use display::{DisplayExpr, Precedence};
pub use eval::{Evaluator, Inputs, no_inputs};

use crate::rational::Rational;
use rustc_hash::FxHashMap;

/// Index of an interned expression node in its [`Store`].
#[derive(Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord, Debug)]
pub struct ExprId(u32);

impl ExprId {
    /// The node's position in its store, for tables indexed by expression.
    pub fn index(self) -> usize {
        self.0 as usize
    }
}

/// Index of a symbol in its [`Store`].
#[derive(Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord, Debug)]
pub struct SymbolId(u32);

impl SymbolId {
    /// The symbol's position in its store: its index in [`Store::symbols`]
    /// and in an [`Evaluator`]'s values.
    pub fn index(self) -> usize {
        self.0 as usize
    }
}

/// What a symbol stands for.
#[derive(Clone, Copy, PartialEq, Eq, Hash, Debug)]
pub enum SymbolKind {
    /// Generalized coordinate `q_i`.
    Coordinate(usize),
    /// Generalized velocity `q̇_i`.
    Velocity(usize),
    /// Generalized acceleration `q̈_i` (only in the mass-matrix Jacobian).
    Acceleration(usize),
    /// Model parameter, a constant during a run.
    Parameter(usize),
    /// Time `t`.
    Time,
    /// The constant π.
    Pi,
    /// A formal argument of an input function (used in declared derivatives).
    InputArgument {
        /// The input function's index.
        input: usize,
        /// The argument's position in its declaration.
        position: usize,
    },
}

/// A symbol of a store: the name it prints as and what it stands for.
#[derive(Clone, Debug)]
pub struct Symbol {
    /// The name as written in the spec (`dot(x)` for a velocity, `ddot(x)`
    /// for an acceleration).
    pub name: String,
    /// What the symbol stands for.
    pub kind: SymbolKind,
}

/// Elementary functions kept as atoms (defined with the runtime, which
/// evaluates them the same way).
pub use lagrangian_runtime::functions::Func;

/// An interned node. See the module documentation for the invariants.
#[derive(Clone, PartialEq, Eq, Hash, Debug)]
pub enum Node {
    /// A rational constant (0 and 1 are always [`Store::ZERO`] and
    /// [`Store::ONE`]).
    Num(Rational),
    /// A symbol.
    Sym(SymbolId),
    /// `Σ c_k · term_k`, sorted by term id; the constant term uses [`Store::ONE`].
    Add(Box<[(ExprId, Rational)]>),
    /// `Π base_k ^ e_k`, sorted by base id, with no numeric coefficient.
    Mul(Box<[(ExprId, Rational)]>),
    /// An elementary function of its arguments (as many as its
    /// [`Func::arity`]).
    Func(Func, Box<[ExprId]>),
    /// A call of a run-time input function.
    Input(u32, Box<[ExprId]>),
}

impl Node {
    /// Calls `visit` with every direct operand of the node: the terms of a
    /// sum, the bases of a product, a function's argument, an input call's
    /// arguments (numbers and symbols have none). Exponents and coefficients
    /// are not nodes and are not visited.
    pub fn for_each_child(&self, mut visit: impl FnMut(ExprId)) {
        match self {
            Node::Num(_) | Node::Sym(_) => {}
            Node::Add(items) | Node::Mul(items) => items.iter().for_each(|&(t, _)| visit(t)),
            Node::Func(_, args) | Node::Input(_, args) => args.iter().for_each(|&a| visit(a)),
        }
    }
}

/// A run-time input function: its name, arity and declared partial derivatives.
#[derive(Clone, Debug)]
pub struct InputFunction {
    /// The name declared in the spec's `inputs` block.
    pub name: String,
    /// Formal arguments, as symbols of kind [`SymbolKind::InputArgument`].
    pub arguments: Vec<SymbolId>,
    /// `∂f/∂arg_i` in terms of the formal arguments, when declared.
    pub derivatives: Vec<Option<ExprId>>,
}

/// Problems found while building expressions; reported by the caller with context.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum EngineError {
    /// A coefficient left the range of exact 128-bit rationals.
    Overflow,
    /// A constant was divided by zero.
    DivisionByZero,
    /// An input function had to be differentiated with respect to an argument
    /// whose derivative was not declared.
    MissingDerivative {
        /// The input function's index.
        input: usize,
        /// The position of the argument.
        argument: usize,
    },
    /// An exponent beyond [`MAX_EXPONENT`] (numerator or denominator).
    ExponentTooLarge(Rational),
    /// A power of a sum whose expansion would exceed [`MAX_EXPANDED_TERMS`].
    ExpansionTooLarge {
        /// The exponent.
        exponent: Rational,
        /// The number of terms of the sum.
        sum_terms: usize,
    },
    /// A product of two sums whose expansion would have more than
    /// [`MAX_PRODUCT_TERMS`] terms.
    ProductTooLarge {
        /// The two sums' numbers of terms.
        terms: (usize, usize),
    },
    /// The model needs more than [`MAX_NODES`] distinct expressions.
    ModelTooLarge,
}

/// Errors kept by [`Store::record`] until taken.
const MAX_RECORDED_ERRORS: usize = 8;

/// The largest magnitude of an exponent's numerator and denominator: larger
/// exponents are reported ([`EngineError::ExponentTooLarge`]), so a sine
/// power's linearization and the emitted `powi` stay small and exact.
pub const MAX_EXPONENT: i128 = 1024;

/// The most terms the expansion of a power of a sum may have: `(Σ_k a_k)^n`
/// with `k` terms has `C(n + k − 1, k − 1)` monomials before any cancel
/// ([`EngineError::ExpansionTooLarge`] beyond).
pub const MAX_EXPANDED_TERMS: usize = 4096;

/// The most terms the product of two sums may expand to before any cancel
/// ([`EngineError::ProductTooLarge`] beyond); well above what the shipped
/// specs and the pendulum chains of the benchmarks need.
pub const MAX_PRODUCT_TERMS: usize = 1 << 16;

/// The most distinct expression nodes one model may create, well above what
/// the 40-link pendulum chain of BENCHMARKS.md needs (a model far beyond
/// those this tool is for). A derivation that would exceed it stops with an
/// error instead of exhausting memory.
pub const MAX_NODES: usize = 2_000_000;

/// Owner of all nodes, symbols and input functions of one model.
pub struct Store {
    nodes: Vec<Node>,
    /// Bit `s % 64` is set when the node may depend on symbol `s`.
    masks: Vec<u64>,
    index: FxHashMap<Node, ExprId>,
    symbols: Vec<Symbol>,
    inputs: Vec<InputFunction>,
    diff_memo: FxHashMap<(ExprId, SymbolId), ExprId>,
    mul_memo: FxHashMap<(ExprId, ExprId), ExprId>,
    errors: Vec<EngineError>,
    /// The total size of the nodes created so far: their terms, factors
    /// and arguments.
    size: usize,
    /// The most `size` may reach (unbounded unless a caller
    /// sets a budget, [`Store::set_budget`]).
    size_limit: usize,
    /// Whether an expansion or the budget stopped an operation since
    /// the last [`Store::take_size_limit`].
    size_limit_hit: bool,
}

impl Default for Store {
    fn default() -> Self {
        Store::new()
    }
}

impl Store {
    /// The constant 0; always the first node.
    pub const ZERO: ExprId = ExprId(0);
    /// The constant 1; always the second node. Also the "term" of constants in sums.
    pub const ONE: ExprId = ExprId(1);

    /// An empty store: the constants 0 and 1, no symbol, no input function.
    pub fn new() -> Store {
        let mut store = Store {
            nodes: Vec::new(),
            masks: Vec::new(),
            index: FxHashMap::default(),
            symbols: Vec::new(),
            inputs: Vec::new(),
            diff_memo: FxHashMap::default(),
            mul_memo: FxHashMap::default(),
            errors: Vec::new(),
            size: 0,
            size_limit: usize::MAX,
            size_limit_hit: false,
        };
        let zero = store.intern(Node::Num(Rational::ZERO));
        let one = store.intern(Node::Num(Rational::ONE));
        debug_assert_eq!((zero, one), (Store::ZERO, Store::ONE));
        store
    }

    /// Declares a new symbol and returns the expression standing for it.
    pub fn symbol(&mut self, name: &str, kind: SymbolKind) -> (SymbolId, ExprId) {
        let id = SymbolId(self.symbols.len() as u32);
        self.symbols.push(Symbol {
            name: name.to_string(),
            kind,
        });
        (id, self.intern(Node::Sym(id)))
    }

    /// The expression standing for an existing symbol.
    pub fn symbol_expr(&mut self, s: SymbolId) -> ExprId {
        self.intern(Node::Sym(s))
    }

    /// Renames every symbol and input function `name` to `rename(name)`
    /// where it gives a new name (a family's elements as users read them).
    pub(crate) fn rename(&mut self, rename: impl Fn(&str) -> Option<String>) {
        for symbol in &mut self.symbols {
            if let Some(name) = rename(&symbol.name) {
                symbol.name = name;
            }
        }
        for input in &mut self.inputs {
            if let Some(name) = rename(&input.name) {
                input.name = name;
            }
        }
    }

    /// Declares an input function with `arity` formal arguments named `argument_names`.
    pub fn declare_input(&mut self, name: &str, argument_names: &[String]) -> usize {
        let input = self.inputs.len();
        let arguments = argument_names
            .iter()
            .enumerate()
            .map(|(position, arg)| {
                self.symbol(arg, SymbolKind::InputArgument { input, position })
                    .0
            })
            .collect::<Vec<_>>();
        self.inputs.push(InputFunction {
            name: name.to_string(),
            derivatives: vec![None; arguments.len()],
            arguments,
        });
        input
    }

    /// Declares `∂input/∂argument = derivative` (in terms of the formal arguments).
    pub fn set_input_derivative(&mut self, input: usize, argument: usize, derivative: ExprId) {
        self.inputs[input].derivatives[argument] = Some(derivative);
    }

    /// Every symbol, indexed by [`SymbolId::index`], in declaration order.
    pub fn symbols(&self) -> &[Symbol] {
        &self.symbols
    }

    /// The symbol declared as `name`, if any.
    pub fn symbol_named(&self, name: &str) -> Option<SymbolId> {
        self.symbols
            .iter()
            .position(|s| s.name == name)
            .map(|i| SymbolId(i as u32))
    }

    /// The name and kind of symbol `s`.
    pub fn symbol_info(&self, s: SymbolId) -> &Symbol {
        &self.symbols[s.index()]
    }

    /// Every input function, by index, in declaration order.
    pub fn inputs(&self) -> &[InputFunction] {
        &self.inputs
    }

    /// The node of expression `e`.
    pub fn node(&self, e: ExprId) -> &Node {
        &self.nodes[e.index()]
    }

    /// The number of distinct expression nodes (at most [`MAX_NODES`]).
    pub fn len(&self) -> usize {
        self.nodes.len()
    }

    /// The total size of the nodes created (their terms, factors and
    /// arguments): the measure of [`Store::set_budget`].
    pub fn size(&self) -> usize {
        self.size
    }

    /// Never true for a store made by [`Store::new`], which holds 0 and 1.
    pub fn is_empty(&self) -> bool {
        self.nodes.is_empty()
    }

    /// Errors recorded since the last call, which clears them.
    pub fn take_errors(&mut self) -> Vec<EngineError> {
        std::mem::take(&mut self.errors)
    }

    /// Records an error, unless it is already recorded. Callers report the
    /// first; a few are kept, not one per operation, so that a long
    /// expression that keeps failing stays linear (a 100 000-factor product
    /// records an exponent error at every factor).
    pub(crate) fn record(&mut self, error: EngineError) {
        self.size_limit_hit |= matches!(
            error,
            EngineError::ExpansionTooLarge { .. }
                | EngineError::ProductTooLarge { .. }
                | EngineError::ModelTooLarge
        );
        if self.errors.len() < MAX_RECORDED_ERRORS && !self.errors.contains(&error) {
            self.errors.push(error);
        }
    }

    /// A rational constant.
    pub fn num(&mut self, value: Rational) -> ExprId {
        if value.is_zero() {
            Store::ZERO
        } else if value.is_one() {
            Store::ONE
        } else {
            self.intern(Node::Num(value))
        }
    }

    /// An integer constant.
    pub fn int(&mut self, value: i64) -> ExprId {
        self.num(Rational::integer(value))
    }

    /// The rational value of a constant node.
    pub fn as_num(&self, e: ExprId) -> Option<Rational> {
        match self.node(e) {
            Node::Num(v) => Some(*v),
            _ => None,
        }
    }

    /// The symbol `e` is, when it is a bare symbol.
    pub fn as_symbol(&self, e: ExprId) -> Option<SymbolId> {
        match self.node(e) {
            Node::Sym(s) => Some(*s),
            _ => None,
        }
    }

    /// May `e` depend on `s`? `false` is certain, `true` may be a false positive.
    pub fn may_depend_on(&self, e: ExprId, s: SymbolId) -> bool {
        self.masks[e.index()] & symbol_bit(s) != 0
    }

    /// Does `e` contain symbol `s`? Exact (walks the DAG when the mask says maybe).
    pub fn depends_on(&self, e: ExprId, s: SymbolId) -> bool {
        if !self.may_depend_on(e, s) {
            return false;
        }
        let mut seen = rustc_hash::FxHashSet::default();
        let mut stack = vec![e];
        while let Some(x) = stack.pop() {
            if !seen.insert(x) || !self.may_depend_on(x, s) {
                continue;
            }
            if let Node::Sym(t) = self.node(x)
                && *t == s
            {
                return true;
            }
            self.node(x).for_each_child(|c| stack.push(c));
        }
        false
    }

    /// All symbols `e` contains, sorted.
    pub fn free_symbols(&self, e: ExprId) -> Vec<SymbolId> {
        let mut seen = rustc_hash::FxHashSet::default();
        let mut found = Vec::new();
        let mut stack = vec![e];
        while let Some(x) = stack.pop() {
            if !seen.insert(x) {
                continue;
            }
            if let Node::Sym(t) = self.node(x) {
                found.push(*t);
            }
            self.node(x).for_each_child(|c| stack.push(c));
        }
        found.sort();
        found.dedup();
        found
    }

    /// The number of distinct nodes reachable from `roots`.
    pub fn dag_size(&self, roots: &[ExprId]) -> usize {
        let mut seen = rustc_hash::FxHashSet::default();
        let mut stack = roots.to_vec();
        while let Some(x) = stack.pop() {
            if !seen.insert(x) {
                continue;
            }
            self.node(x).for_each_child(|c| stack.push(c));
        }
        seen.len()
    }

    /// Limits the nodes created from now on to a total size (terms,
    /// factors, arguments) of `extra` (`None`: no limit but [`MAX_NODES`]);
    /// past it, operations record [`EngineError::ModelTooLarge`] as at
    /// [`MAX_NODES`]. The size measures the work that expansion does, so a
    /// long sum written out stays within a budget that a product of long
    /// sums exceeds.
    pub fn set_budget(&mut self, extra: Option<usize>) {
        self.size_limit = extra.map_or(usize::MAX, |e| self.size.saturating_add(e));
    }

    /// Whether an expansion limit or the budget stopped an operation
    /// since the last call (which clears it): the canonical form of what
    /// was being built is incomplete because it is too large, not wrong.
    ///
    /// The operations memoized since may hold results cut short by the
    /// limit, so a hit forgets them all.
    pub fn take_size_limit(&mut self) -> bool {
        let hit = std::mem::take(&mut self.size_limit_hit);
        if hit {
            self.diff_memo.clear();
            self.mul_memo.clear();
        }
        hit
    }

    fn intern(&mut self, node: Node) -> ExprId {
        if let Some(&id) = self.index.get(&node) {
            return id;
        }
        if self.nodes.len() >= MAX_NODES || self.size >= self.size_limit {
            // Past the budget every new node is zero: the work that follows
            // collapses to nodes that exist, and the error is reported.
            self.record(EngineError::ModelTooLarge);
            return Store::ZERO;
        }
        let mut mask = match &node {
            Node::Sym(s) => symbol_bit(*s),
            _ => 0,
        };
        node.for_each_child(|c| mask |= self.masks[c.index()]);
        self.size += match &node {
            Node::Add(items) | Node::Mul(items) => items.len(),
            Node::Input(_, args) => args.len(),
            Node::Num(_) | Node::Sym(_) | Node::Func(..) => 1,
        };
        let id = ExprId(self.nodes.len() as u32);
        self.nodes.push(node.clone());
        self.masks.push(mask);
        self.index.insert(node, id);
        id
    }

    /// The sum viewed as `(term, coefficient)` pairs; a constant is `(ONE, c)`.
    pub fn terms(&self, e: ExprId) -> Vec<(ExprId, Rational)> {
        match self.node(e) {
            Node::Num(c) if c.is_zero() => Vec::new(),
            Node::Num(c) => vec![(Store::ONE, *c)],
            Node::Add(items) => items.to_vec(),
            _ => vec![(e, Rational::ONE)],
        }
    }

    /// A monomial (a term of a sum) viewed as `(base, exponent)` factors.
    pub fn factors(&self, term: ExprId) -> Vec<(ExprId, Rational)> {
        match self.node(term) {
            Node::Mul(items) => items.to_vec(),
            _ if term == Store::ONE => Vec::new(),
            _ => vec![(term, Rational::ONE)],
        }
    }

    /// The one-argument function node `f(u)` as built, if `e` is one.
    pub fn as_func(&self, e: ExprId) -> Option<(Func, ExprId)> {
        match self.node(e) {
            Node::Func(f, args) if args.len() == 1 => Some((*f, args[0])),
            _ => None,
        }
    }

    /// The function node `f(args…)` as built, if `e` is one.
    pub fn as_call(&self, e: ExprId) -> Option<(Func, &[ExprId])> {
        match self.node(e) {
            Node::Func(f, args) => Some((*f, args)),
            _ => None,
        }
    }

    /// Whether `base`, a factor of a monomial, is a velocity, an
    /// acceleration or an input-function value: the factors that head a
    /// group when equations are read by motion. The equation documents
    /// group terms by them ([`pretty`]), and the audit compares hand-derived
    /// equations group by group.
    pub fn is_motion_base(&self, base: ExprId) -> bool {
        match self.node(base) {
            Node::Sym(s) => matches!(
                self.symbol_info(*s).kind,
                SymbolKind::Velocity(_) | SymbolKind::Acceleration(_)
            ),
            Node::Input(..) => true,
            Node::Num(_) | Node::Add(_) | Node::Mul(_) | Node::Func(..) => false,
        }
    }

    /// An input-function call.
    pub fn input_call(&mut self, input: usize, args: Vec<ExprId>) -> ExprId {
        self.intern(Node::Input(input as u32, args.into_boxed_slice()))
    }

    pub(crate) fn mask(&self, e: ExprId) -> u64 {
        self.masks[e.index()]
    }
}

fn symbol_bit(s: SymbolId) -> u64 {
    1u64 << (s.0 % 64)
}

#[cfg(test)]
mod tests;
