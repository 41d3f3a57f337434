//! The derivation graph: expressions kept as a shared DAG of operations
//! whose leaves are small expressions in the exact canonical form.
//!
//! The canonical form ([`crate::expr`]) expands every product of sums, which
//! is exact and lets terms cancel, but grows without bound on big models:
//! the squared velocity of the tenth body of a chain is a sum over every
//! pair of links. The graph keeps what the spec writes — `let` helpers,
//! positions and their velocities — as shared nodes, and differentiates
//! them by the chain rule (the `calculus` module), so that the mass matrix and the
//! forcing of an `n`-link chain take `O(n²)` nodes. Where the operands of an
//! operation are small canonical expressions, the operation is done in the
//! canonical form (a *leaf*), so that sines and cosines of one angle still
//! combine and cancel there: the graph expands only where that stays small.
//!
//! Nodes are hash-consed: structurally equal nodes share one [`GraphId`].

mod calculus;

use crate::expr::{ExprId, Func, Node, Store, SymbolId};
use crate::rational::Rational;
use rustc_hash::FxHashMap;

/// Index of a node in its [`Graph`].
#[derive(Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord, Debug)]
pub struct GraphId(u32);

impl GraphId {
    fn index(self) -> usize {
        self.0 as usize
    }
}

/// A node of the graph. Operands are earlier nodes, so ids are a
/// topological order.
#[derive(Clone, Copy, PartialEq, Eq, Hash, Debug)]
pub enum GraphNode {
    /// An expression in the canonical form of the model's [`Store`].
    Leaf(ExprId),
    /// `a + b`.
    Add(GraphId, GraphId),
    /// `a · b`.
    Mul(GraphId, GraphId),
    /// `aʳ` for a constant `r` other than 0 and 1.
    Pow(GraphId, Rational),
    /// An elementary function of a node that is not a leaf.
    Func(Func, GraphId),
}

/// The most terms an operation on leaves may give and still be done in the
/// canonical form (a bigger result stays an operation node).
const LEAF_TERMS: usize = 8;

/// A hash-consed DAG of [`GraphNode`]s over the expressions of one store.
pub struct Graph {
    /// The model's time symbol, which also stands for the argument of a
    /// function whose derivative rule is read from the canonical engine.
    time: SymbolId,
    nodes: Vec<GraphNode>,
    /// Bit `s % 64` is set when the node may depend on symbol `s`.
    masks: Vec<u64>,
    index: FxHashMap<GraphNode, GraphId>,
    diff_memo: FxHashMap<(GraphId, SymbolId), GraphId>,
    /// The time derivatives taken so far ([`Graph::time_derivative`]).
    dot_memo: FxHashMap<GraphId, GraphId>,
    /// The symbols each leaf contains, exactly, as they are asked for.
    leaf_symbols: FxHashMap<ExprId, std::rc::Rc<[SymbolId]>>,
}

impl Graph {
    /// An empty graph for a model whose time symbol is `time`.
    pub fn new(time: SymbolId) -> Graph {
        Graph {
            time,
            nodes: Vec::new(),
            masks: Vec::new(),
            index: FxHashMap::default(),
            diff_memo: FxHashMap::default(),
            dot_memo: FxHashMap::default(),
            leaf_symbols: FxHashMap::default(),
        }
    }

    /// The node of `g`.
    pub fn node(&self, g: GraphId) -> GraphNode {
        self.nodes[g.index()]
    }

    /// The number of nodes.
    pub fn len(&self) -> usize {
        self.nodes.len()
    }

    /// Whether the graph has no node yet.
    pub fn is_empty(&self) -> bool {
        self.nodes.is_empty()
    }

    /// The canonical expression `g` is, when it is a leaf.
    pub fn as_leaf(&self, g: GraphId) -> Option<ExprId> {
        match self.node(g) {
            GraphNode::Leaf(e) => Some(e),
            GraphNode::Add(..) | GraphNode::Mul(..) | GraphNode::Pow(..) | GraphNode::Func(..) => {
                None
            }
        }
    }

    /// May `g` depend on `s`? `false` is certain.
    pub fn may_depend_on(&self, g: GraphId, s: SymbolId) -> bool {
        self.masks[g.index()] & (1u64 << (s.index() % 64)) != 0
    }

    /// The symbols leaf `e` contains (exact, unlike the masks).
    fn symbols_of_leaf(&mut self, store: &Store, e: ExprId) -> std::rc::Rc<[SymbolId]> {
        let symbols = self.leaf_symbols.entry(e);
        symbols
            .or_insert_with(|| store.free_symbols(e).into())
            .clone()
    }

    /// Does `g` contain symbol `s`? Exact.
    pub fn depends_on(&self, store: &Store, g: GraphId, s: SymbolId) -> bool {
        if !self.may_depend_on(g, s) {
            return false;
        }
        let mut seen = rustc_hash::FxHashSet::default();
        let mut stack = vec![g];
        while let Some(x) = stack.pop() {
            if !seen.insert(x) || !self.may_depend_on(x, s) {
                continue;
            }
            match self.node(x) {
                GraphNode::Leaf(e) if store.depends_on(e, s) => return true,
                GraphNode::Leaf(_) => {}
                GraphNode::Add(a, b) | GraphNode::Mul(a, b) => stack.extend([a, b]),
                GraphNode::Pow(a, _) | GraphNode::Func(_, a) => stack.push(a),
            }
        }
        false
    }

    fn intern(&mut self, store: &Store, node: GraphNode) -> GraphId {
        if let Some(&id) = self.index.get(&node) {
            return id;
        }
        let mask = match node {
            GraphNode::Leaf(e) => store.mask(e),
            GraphNode::Add(a, b) | GraphNode::Mul(a, b) => {
                self.masks[a.index()] | self.masks[b.index()]
            }
            GraphNode::Pow(a, _) | GraphNode::Func(_, a) => self.masks[a.index()],
        };
        let id = GraphId(self.nodes.len() as u32);
        self.nodes.push(node);
        self.masks.push(mask);
        self.index.insert(node, id);
        id
    }

    /// The canonical expression `e` as a leaf.
    pub fn leaf(&mut self, store: &Store, e: ExprId) -> GraphId {
        self.intern(store, GraphNode::Leaf(e))
    }

    /// The constant `c`.
    pub fn number(&mut self, store: &mut Store, c: Rational) -> GraphId {
        let e = store.num(c);
        self.leaf(store, e)
    }

    fn is_zero(&self, g: GraphId) -> bool {
        self.as_leaf(g) == Some(Store::ZERO)
    }

    /// The number of terms of leaf `g` when it is small enough to combine.
    fn small_leaf(&self, store: &Store, g: GraphId) -> Option<(ExprId, usize)> {
        let e = self.as_leaf(g)?;
        let terms = match store.node(e) {
            Node::Add(items) => items.len(),
            Node::Num(_) | Node::Sym(_) | Node::Mul(_) | Node::Func(..) | Node::Input(..) => 1,
        };
        (terms <= LEAF_TERMS).then_some((e, terms))
    }

    /// `a + b`.
    pub fn add(&mut self, store: &mut Store, a: GraphId, b: GraphId) -> GraphId {
        if self.is_zero(a) {
            return b;
        }
        if self.is_zero(b) {
            return a;
        }
        if let (Some((x, m)), Some((y, n))) = (self.small_leaf(store, a), self.small_leaf(store, b))
            && m + n <= LEAF_TERMS
        {
            let sum = store.add(x, y);
            return self.leaf(store, sum);
        }
        let (a, b) = if b < a { (b, a) } else { (a, b) };
        self.intern(store, GraphNode::Add(a, b))
    }

    /// `Σ terms`.
    pub fn sum(&mut self, store: &mut Store, terms: &[GraphId]) -> GraphId {
        let mut acc = self.leaf(store, Store::ZERO);
        for &t in terms {
            acc = self.add(store, acc, t);
        }
        acc
    }

    /// `a · b`.
    pub fn mul(&mut self, store: &mut Store, a: GraphId, b: GraphId) -> GraphId {
        if self.is_zero(a) || self.is_zero(b) {
            return self.leaf(store, Store::ZERO);
        }
        if self.as_leaf(a) == Some(Store::ONE) {
            return b;
        }
        if self.as_leaf(b) == Some(Store::ONE) {
            return a;
        }
        if let (Some((x, m)), Some((y, n))) = (self.small_leaf(store, a), self.small_leaf(store, b))
            && m * n <= LEAF_TERMS
        {
            let product = store.mul(x, y);
            return self.leaf(store, product);
        }
        if let Some(folded) = self.fold_leaf_factors(store, a, b) {
            return folded;
        }
        let (a, b) = if b < a { (b, a) } else { (a, b) };
        self.intern(store, GraphNode::Mul(a, b))
    }

    /// `x · (y · g)` as `(x y) · g` when `x` and `y` are leaves whose
    /// product is one, so that factors such as `½ · 2` meet.
    fn fold_leaf_factors(&mut self, store: &mut Store, a: GraphId, b: GraphId) -> Option<GraphId> {
        let (x, product) = match (self.small_leaf(store, a), self.small_leaf(store, b)) {
            (Some(_), None) => (a, b),
            (None, Some(_)) => (b, a),
            _ => return None,
        };
        let GraphNode::Mul(p, q) = self.node(product) else {
            return None;
        };
        let (y, g) = match (self.small_leaf(store, p), self.small_leaf(store, q)) {
            (Some(_), _) => (p, q),
            (_, Some(_)) => (q, p),
            _ => return None,
        };
        let (_, m) = self.small_leaf(store, x)?;
        let (_, n) = self.small_leaf(store, y)?;
        if m * n > LEAF_TERMS {
            return None;
        }
        let xy = self.mul(store, x, y);
        Some(self.mul(store, xy, g))
    }

    /// `c · a` for a rational constant `c`.
    pub fn scale(&mut self, store: &mut Store, c: Rational, a: GraphId) -> GraphId {
        let k = self.number(store, c);
        self.mul(store, k, a)
    }

    /// `−a`.
    pub fn neg(&mut self, store: &mut Store, a: GraphId) -> GraphId {
        self.scale(store, Rational::MINUS_ONE, a)
    }

    /// `a − b`.
    pub fn sub(&mut self, store: &mut Store, a: GraphId, b: GraphId) -> GraphId {
        let minus_b = self.neg(store, b);
        self.add(store, a, minus_b)
    }

    /// `aʳ`.
    pub fn pow(&mut self, store: &mut Store, a: GraphId, r: Rational) -> GraphId {
        if r.is_zero() {
            return self.leaf(store, Store::ONE);
        }
        if r.is_one() {
            return a;
        }
        if let Some((x, terms)) = self.small_leaf(store, a)
            && (terms == 1 || expanded_terms(terms, r).is_some_and(|t| t <= LEAF_TERMS))
        {
            let p = store.pow(x, r);
            return self.leaf(store, p);
        }
        self.intern(store, GraphNode::Pow(a, r))
    }

    /// `f(a)`.
    pub fn apply(&mut self, store: &mut Store, f: Func, a: GraphId) -> GraphId {
        if let Some(x) = self.as_leaf(a) {
            let e = store.apply(f, &[x]);
            return self.leaf(store, e);
        }
        self.intern(store, GraphNode::Func(f, a))
    }
}

/// The number of monomials of a `terms`-term sum to a small positive
/// integer power, before any cancel; `None` for other exponents.
fn expanded_terms(terms: usize, r: Rational) -> Option<usize> {
    let n = r.to_i64().filter(|n| (1..=4).contains(n))? as usize;
    // C(n + terms − 1, n)
    let mut c = 1usize;
    for k in 0..n {
        c = c * (terms + k) / (k + 1);
    }
    Some(c)
}
