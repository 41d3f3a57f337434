//! Derivatives on the graph by the chain rule: forward (one symbol, or a
//! direction such as the time derivative) and reverse (the gradient of one
//! node). Leaves are differentiated by the canonical engine, and so is
//! every elementary function: the derivative rules live in one place,
//! [`Store::diff`].

use super::{Graph, GraphId, GraphNode};
use crate::expr::{CoordinateSymbols, ExprId, Func, Node, Store, SymbolId};
use crate::rational::Rational;
use rustc_hash::FxHashMap;

impl Graph {
    /// `∂g/∂s`.
    pub fn diff(&mut self, store: &mut Store, g: GraphId, s: SymbolId) -> GraphId {
        if !self.may_depend_on(g, s) {
            return self.leaf(store, Store::ZERO);
        }
        if let Some(&d) = self.diff_memo.get(&(g, s)) {
            return d;
        }
        let d = match self.node(g) {
            GraphNode::Leaf(e) => {
                let d = store.diff(e, s);
                self.leaf(store, d)
            }
            node => {
                let partials = self.partials(store, node);
                let mut terms = Vec::with_capacity(partials.len());
                for (child, partial) in partials {
                    let dc = self.diff(store, child, s);
                    terms.push(self.mul(store, partial, dc));
                }
                self.sum(store, &terms)
            }
        };
        self.diff_memo.insert((g, s), d);
        d
    }

    /// `dg/dt = Σ_i ∂g/∂q_i q̇_i + ∂g/∂t`, without the `∂g/∂q̇ q̈` part:
    /// the time derivative of a position, and of the momenta less `M q̈`.
    /// Memoized for the life of the graph.
    pub fn time_derivative(
        &mut self,
        store: &mut Store,
        g: GraphId,
        coordinates: &[CoordinateSymbols],
    ) -> GraphId {
        let mut seeds: FxHashMap<SymbolId, GraphId> = FxHashMap::default();
        for c in coordinates {
            seeds.insert(c.position, self.leaf(store, c.velocity_expr));
        }
        seeds.insert(self.time, self.leaf(store, Store::ONE));
        let mut memo = std::mem::take(&mut self.dot_memo);
        let d = self.directional(store, g, &seeds, &mut memo);
        self.dot_memo = memo;
        d
    }

    /// `Σ_s ∂g/∂s · seed_s`.
    fn directional(
        &mut self,
        store: &mut Store,
        g: GraphId,
        seeds: &FxHashMap<SymbolId, GraphId>,
        memo: &mut FxHashMap<GraphId, GraphId>,
    ) -> GraphId {
        if let Some(&d) = memo.get(&g) {
            return d;
        }
        let mut terms = Vec::new();
        match self.node(g) {
            GraphNode::Leaf(e) => {
                for &s in self.symbols_of_leaf(store, e).iter() {
                    if let Some(&seed) = seeds.get(&s) {
                        let d = store.diff(e, s);
                        let d = self.leaf(store, d);
                        terms.push(self.mul(store, d, seed));
                    }
                }
            }
            node => {
                for (child, partial) in self.partials(store, node) {
                    let dc = self.directional(store, child, seeds, memo);
                    terms.push(self.mul(store, partial, dc));
                }
            }
        }
        let d = self.sum(store, &terms);
        memo.insert(g, d);
        d
    }

    /// `∂g/∂s` for every `s` of `wrt`, by reverse accumulation: one
    /// backward sweep, in which the adjoints of shared nodes are shared.
    pub fn gradient(&mut self, store: &mut Store, g: GraphId, wrt: &[SymbolId]) -> Vec<GraphId> {
        let zero = self.leaf(store, Store::ZERO);
        let mut gradient = vec![zero; wrt.len()];
        let position: FxHashMap<SymbolId, usize> =
            wrt.iter().enumerate().map(|(k, &s)| (s, k)).collect();
        let mut adjoints: FxHashMap<GraphId, GraphId> = FxHashMap::default();
        let one = self.leaf(store, Store::ONE);
        adjoints.insert(g, one);
        for node in self.reachable(g).into_iter().rev() {
            let Some(&adjoint) = adjoints.get(&node) else {
                continue;
            };
            match self.node(node) {
                GraphNode::Leaf(e) => {
                    for &s in self.symbols_of_leaf(store, e).iter() {
                        if let Some(&k) = position.get(&s) {
                            let d = store.diff(e, s);
                            let d = self.leaf(store, d);
                            let term = self.mul(store, adjoint, d);
                            gradient[k] = self.add(store, gradient[k], term);
                        }
                    }
                }
                other => {
                    for (child, partial) in self.partials(store, other) {
                        let term = self.mul(store, adjoint, partial);
                        let sum = match adjoints.get(&child) {
                            Some(&a) => self.add(store, a, term),
                            None => term,
                        };
                        adjoints.insert(child, sum);
                    }
                }
            }
        }
        gradient
    }

    /// Every node `g` depends on, `g` included, in increasing id order.
    fn reachable(&self, g: GraphId) -> Vec<GraphId> {
        let mut seen = vec![false; g.index() + 1];
        let mut stack = vec![g];
        while let Some(x) = stack.pop() {
            if std::mem::replace(&mut seen[x.index()], true) {
                continue;
            }
            match self.node(x) {
                GraphNode::Leaf(_) => {}
                GraphNode::Add(a, b) | GraphNode::Mul(a, b) => stack.extend([a, b]),
                GraphNode::Pow(a, _) | GraphNode::Func(_, a) => stack.push(a),
            }
        }
        (0..seen.len() as u32)
            .map(GraphId)
            .filter(|x| seen[x.index()])
            .collect()
    }

    /// `(child, ∂node/∂child)` for each operand of an operation node.
    fn partials(&mut self, store: &mut Store, node: GraphNode) -> Vec<(GraphId, GraphId)> {
        match node {
            GraphNode::Leaf(_) => Vec::new(),
            GraphNode::Add(a, b) => {
                let one = self.leaf(store, Store::ONE);
                vec![(a, one), (b, one)]
            }
            GraphNode::Mul(a, b) => vec![(a, b), (b, a)],
            GraphNode::Pow(a, r) => {
                let reduced = r.checked_sub(Rational::ONE).unwrap_or(Rational::ZERO);
                let p = self.pow(store, a, reduced);
                vec![(a, self.scale(store, r, p))]
            }
            GraphNode::Func(f, a) => vec![(a, self.outer_derivative(store, f, a))],
        }
    }

    /// `f′(a)`: the canonical engine's derivative of `f(x)` with respect to
    /// a symbol `x`, with `a` put for `x`. The symbol is the time, which
    /// only stands for the argument here.
    fn outer_derivative(&mut self, store: &mut Store, f: Func, a: GraphId) -> GraphId {
        let x = self.time;
        let x_expr = store.symbol_expr(x);
        let fx = store.apply(f, &[x_expr]);
        let derivative = store.diff(fx, x);
        self.substitute(store, derivative, x, a)
    }

    /// The canonical expression `e` in the graph, with `a` put for the symbol `x`.
    fn substitute(&mut self, store: &mut Store, e: ExprId, x: SymbolId, a: GraphId) -> GraphId {
        if !store.may_depend_on(e, x) {
            return self.leaf(store, e);
        }
        match store.node(e).clone() {
            Node::Sym(_) => a,
            Node::Add(items) => {
                let mut terms = Vec::with_capacity(items.len());
                for &(t, c) in items.iter() {
                    let t = self.substitute(store, t, x, a);
                    terms.push(self.scale(store, c, t));
                }
                self.sum(store, &terms)
            }
            Node::Mul(items) => {
                let mut product = self.leaf(store, Store::ONE);
                for &(b, r) in items.iter() {
                    let b = self.substitute(store, b, x, a);
                    let p = self.pow(store, b, r);
                    product = self.mul(store, product, p);
                }
                product
            }
            Node::Func(f, args) => match *args {
                [u] => {
                    let u = self.substitute(store, u, x, a);
                    self.apply(store, f, u)
                }
                // The graph's functions are those of one argument, whose
                // derivative rules use one-argument functions only.
                _ => unreachable!(
                    "the derivative of a one-argument function calls {f:?} with several"
                ),
            },
            // Numbers depend on no symbol; an input call in a derivative
            // rule would be an input of the argument, which rules do not make.
            Node::Num(_) | Node::Input(..) => self.leaf(store, e),
        }
    }
}
