//! The switching functions of a model: where its dynamics are not smooth.
//!
//! `abs`, `sign`, `min` and `max` have a kink or a jump where a function of
//! their arguments changes sign (the argument of `abs` and `sign`, `a − b`
//! for `min(a, b)` and `max(a, b)`: [`Func::switching`]). The equations of
//! motion are smooth between those sign changes, so the program gets a
//! routine ([`RoutineKind::Switching`]) that evaluates each of them, and
//! the integrator locates every sign change as an event instead of stepping
//! across it. Both derivations have them: the canonical one
//! ([`switching_functions`]) and the graph's ([`graph_switching_functions`]).
//!
//! [`RoutineKind::Switching`]: lagrangian_runtime::layout::RoutineKind::Switching

use crate::derive::Derivation;
use crate::expr::{ExprId, Func, Node, Store};
use crate::graph::{Graph, GraphId, GraphNode};
use lagrangian_runtime::functions::Switching;
use rustc_hash::FxHashSet;

/// The distinct switching functions of the dynamics (`M` and `f`), in the
/// order their functions are first met walking the outputs in order; a
/// switching function and its negation count once. Empty for a smooth model.
pub fn switching_functions(store: &mut Store, derivation: &Derivation) -> Vec<ExprId> {
    let roots = derivation.mass_matrix.iter().chain(&derivation.forcing);
    let calls = non_smooth_calls(store, roots.copied());
    distinct_switching(store, calls)
}

/// The distinct switching functions of the dynamics derived on the graph
/// (`roots`: `M` and `f`), as graph nodes: those of the non-smooth calls in
/// its canonical leaves, then those of its function nodes. A model on the
/// graph thus gets its kinks located as the canonical path does.
pub fn graph_switching_functions(
    store: &mut Store,
    graph: &mut Graph,
    roots: &[GraphId],
) -> Vec<GraphId> {
    let (leaves, function_nodes) = graph_leaves_and_functions(graph, roots);
    let calls = non_smooth_calls(store, leaves.into_iter());
    let mut found: Vec<GraphId> = (distinct_switching(store, calls).into_iter())
        .map(|e| graph.leaf(store, e))
        .collect();
    for (f, argument) in function_nodes {
        match f.switching() {
            Some(Switching::Argument) => {
                // A function node's argument is never a leaf, so never a constant.
                let negated = graph.neg(store, argument);
                if !found.contains(&argument) && !found.contains(&negated) {
                    found.push(argument);
                }
            }
            // Function nodes have one argument: a call of a two-argument
            // function is a canonical leaf, whose switching is found above.
            Some(Switching::Difference) | None => {}
        }
    }
    found
}

/// The switching function of each call, less constants and repeats (a
/// function and its negation count once), in the order of the calls.
fn distinct_switching(store: &mut Store, calls: Vec<(Func, Vec<ExprId>)>) -> Vec<ExprId> {
    let mut found: Vec<ExprId> = Vec::new();
    for (f, args) in calls {
        let switching = match f.switching() {
            Some(Switching::Argument) => args[0],
            Some(Switching::Difference) => store.sub(args[0], args[1]),
            None => continue,
        };
        let negated = store.neg(switching);
        if store.as_num(switching).is_none()
            && !found.contains(&switching)
            && !found.contains(&negated)
        {
            found.push(switching);
        }
    }
    found
}

/// The canonical leaves and the function nodes reachable from `roots`, each
/// once, depth first.
fn graph_leaves_and_functions(
    graph: &Graph,
    roots: &[GraphId],
) -> (Vec<ExprId>, Vec<(Func, GraphId)>) {
    let mut seen = FxHashSet::default();
    let (mut leaves, mut functions) = (Vec::new(), Vec::new());
    let mut stack: Vec<GraphId> = Vec::new();
    for &root in roots {
        stack.push(root);
        while let Some(g) = stack.pop() {
            if !seen.insert(g) {
                continue;
            }
            match graph.node(g) {
                GraphNode::Leaf(e) => leaves.push(e),
                GraphNode::Add(a, b) | GraphNode::Mul(a, b) => stack.extend([b, a]),
                GraphNode::Pow(a, _) => stack.push(a),
                GraphNode::Func(f, a) => {
                    functions.push((f, a));
                    stack.push(a);
                }
            }
        }
    }
    (leaves, functions)
}

/// Every call of a non-smooth function reachable from `roots`, depth first.
fn non_smooth_calls(
    store: &Store,
    roots: impl Iterator<Item = ExprId>,
) -> Vec<(Func, Vec<ExprId>)> {
    let mut seen = FxHashSet::default();
    let mut calls = Vec::new();
    let mut stack: Vec<ExprId> = Vec::new();
    for root in roots {
        stack.push(root);
        while let Some(e) = stack.pop() {
            if !seen.insert(e) {
                continue;
            }
            let node = store.node(e);
            if let Node::Func(f, args) = node
                && f.switching().is_some()
            {
                calls.push((*f, args.to_vec()));
            }
            node.for_each_child(|c| stack.push(c));
        }
    }
    calls
}
