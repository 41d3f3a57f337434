//! The program from the derivation graph ([`crate::graph`]): each
//! operation node becomes one operation, each leaf is optimized as the
//! canonical path optimizes whole expressions (Horner, angle sums), and
//! operations are hash-consed across all outputs as there.

use super::{Builder, RoutineOutputs, Signed, assemble};
use crate::expr::Store;
use crate::graph::{Graph, GraphId, GraphNode};
use crate::graph_derivation::GraphDerivation;
use crate::program::{Op, Program};
use crate::rational::Rational;
use lagrangian_runtime::layout::mass_entries;
use rustc_hash::FxHashMap;

/// Builds the program for all outputs of a derivation on the graph.
pub fn build_program_from_graph(
    store: &mut Store,
    graph: &Graph,
    derivation: &GraphDerivation,
) -> Program {
    let outputs = RoutineOutputs {
        dimension: derivation.dimension,
        mass: mass_entries(derivation.dimension)
            .map(|(i, j)| derivation.mass(i, j))
            .collect(),
        forcing: derivation.forcing.clone(),
        energies: derivation.energies,
        jacobians: (derivation.jacobians.as_ref()).map(|j| j.iter().flatten().copied().collect()),
        outputs: derivation.outputs.clone(),
        switching: derivation.switching.clone(),
        // `Compiled::on_graph` refuses a model with constraints.
        constraints: Vec::new(),
    };
    let mut emitter = GraphEmitter {
        graph,
        memo: FxHashMap::default(),
    };
    let mut builder = Builder::new(store);
    assemble(&mut builder, &outputs, |b, g| {
        let s = emitter.node(b, g);
        b.materialize(s)
    })
}

/// The registers of the graph's nodes, as they are emitted.
struct GraphEmitter<'a> {
    graph: &'a Graph,
    memo: FxHashMap<GraphId, Signed>,
}

impl GraphEmitter<'_> {
    fn node(&mut self, b: &mut Builder, g: GraphId) -> Signed {
        if let Some(&s) = self.memo.get(&g) {
            return s;
        }
        let s = match self.graph.node(g) {
            GraphNode::Leaf(e) => b.expr(e),
            GraphNode::Add(x, y) => {
                let (x, y) = (self.node(b, x), self.node(b, y));
                b.add(x, y)
            }
            GraphNode::Mul(x, y) => match (self.constant(b, x), self.constant(b, y)) {
                (Some(c), _) => self.scaled(b, c, y),
                (None, Some(c)) => self.scaled(b, c, x),
                (None, None) => {
                    let (x, y) = (self.node(b, x), self.node(b, y));
                    b.mul(x, y)
                }
            },
            GraphNode::Pow(x, r) => {
                let x = self.node(b, x);
                power(b, x, r)
            }
            GraphNode::Func(f, x) => {
                let x = self.node(b, x);
                b.apply(f, &[x])
            }
        };
        self.memo.insert(g, s);
        s
    }

    /// The value of `g` when it is a constant leaf.
    fn constant(&self, b: &Builder, g: GraphId) -> Option<Rational> {
        self.graph.as_leaf(g).and_then(|e| b.store.as_num(e))
    }

    /// `c · g`: a sign change alone when `c = ±1`.
    fn scaled(&mut self, b: &mut Builder, c: Rational, g: GraphId) -> Signed {
        let value = self.node(b, g);
        let magnitude = c.to_f64().abs();
        let product = if magnitude == 1.0 {
            value
        } else {
            let k = Signed::plus(b.constant(magnitude));
            b.mul(value, k)
        };
        product.flip(c.is_negative())
    }
}

/// `vʳ`: multiplications for integer powers, `√` for halves, `powf` else;
/// a reciprocal for negative powers.
fn power(b: &mut Builder, v: Signed, r: Rational) -> Signed {
    let magnitude = r.numer().unsigned_abs();
    let positive = match r.denom() {
        1 => b.raise(v, magnitude),
        2 => {
            let a = b.materialize(v);
            let root = Signed::plus(b.op(Op::Sqrt(a)));
            b.raise(root, magnitude)
        }
        d => {
            let a = b.materialize(v);
            let x = magnitude as f64 / d as f64;
            Signed::plus(b.op(Op::powf(a, x)))
        }
    };
    if r.is_negative() {
        let one = b.constant(1.0);
        Signed::plus(b.op(Op::Div(one, positive.reg))).flip(positive.negative)
    } else {
        positive
    }
}
