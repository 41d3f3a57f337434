//! The switching functions of a model: where its dynamics are not smooth.
//!
//! `abs`, `sign`, `min` and `max` have a kink or a jump where a function of
//! their arguments changes sign (the argument of `abs` and `sign`, `a − b`
//! for `min(a, b)` and `max(a, b)`: [`Func::switching`]). The equations of
//! motion are smooth between those sign changes, so the program gets a
//! routine ([`RoutineKind::Switching`]) that evaluates each of them, and
//! the integrator locates every sign change as an event instead of stepping
//! across it.
//!
//! [`RoutineKind::Switching`]: lagrangian_model::layout::RoutineKind::Switching

use crate::derive::Derivation;
use crate::expr::{ExprId, Func, Node, Store};
use lagrangian_model::functions::Switching;
use rustc_hash::FxHashSet;

/// The distinct switching functions of the dynamics (`M` and `f`), in the
/// order their functions are first met walking the outputs in order; a
/// switching function and its negation count once. Empty for a smooth model.
pub fn switching_functions(store: &mut Store, derivation: &Derivation) -> Vec<ExprId> {
    let roots = derivation.mass_matrix.iter().chain(&derivation.forcing);
    let calls = non_smooth_calls(store, roots.copied());
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
