//! The Euler–Lagrange equations on the derivation graph ([`crate::graph`]),
//! for the program:
//!
//! ```text
//! p   = ∂L/∂q̇                      (one reverse sweep of L = T − V)
//! M_ij = ∂p_i/∂q̇_j                 (forward, one pass per velocity)
//! f   = ∂L/∂q − (∂p/∂q) q̇ − ∂p/∂t − ∂D/∂q̇ + Q
//! ```
//!
//! `(∂p/∂q) q̇ + ∂p/∂t` is one forward pass in the direction `(q̇, 1)` of
//! `(q, t)`: the time derivative of the momenta without their `M q̈` part.

use crate::diagnostic::SpecErrors;
use crate::expr::{Store, SymbolId};
use crate::graph::GraphId;
use crate::spec::{Model, engine_diagnostic};

/// The equations of motion, energies, powers, Jacobians and outputs as
/// graph nodes: what the optimizer's `build_program_from_graph` emits (a
/// module above this one).
#[derive(Clone, Debug)]
pub struct GraphDerivation {
    /// `n`, the number of generalized coordinates.
    pub dimension: usize,
    /// `M`, row-major `n × n`, symmetric.
    pub mass_matrix: Vec<GraphId>,
    /// `f`.
    pub forcing: Vec<GraphId>,
    /// `T`, `V`, `D`, the damping power and the external power, in the
    /// order of the runtime's energies.
    pub energies: [GraphId; 5],
    /// `∂f/∂q`, `∂f/∂q̇` and `∂(M a)/∂q`, row-major, when the spec asks
    /// for them.
    pub jacobians: Option<[Vec<GraphId>; 3]>,
    /// The outputs, in declaration order.
    pub outputs: Vec<GraphId>,
    /// The switching functions of the non-smooth functions of `M` and `f`
    /// ([`crate::switching::graph_switching_functions`]).
    pub switching: Vec<GraphId>,
}

impl GraphDerivation {
    /// `M_ij`.
    pub fn mass(&self, i: usize, j: usize) -> GraphId {
        self.mass_matrix[i * self.dimension + j]
    }
}

/// Derives the equations of `model` on its graph.
pub fn derive_graph(model: &mut Model) -> Result<GraphDerivation, SpecErrors> {
    let [kinetic, potential, dissipation] = model.energy_nodes();
    let n = model.dimension();
    let positions: Vec<SymbolId> = model
        .coordinates
        .iter()
        .map(|c| c.symbols.position)
        .collect();
    let velocities: Vec<SymbolId> = model
        .coordinates
        .iter()
        .map(|c| c.symbols.velocity)
        .collect();
    let forces = generalized_forces(model);
    let coordinates = model.coordinate_symbols();
    let (graph, store) = (&mut model.graph, &mut model.store);
    let lagrangian = graph.sub(store, kinetic, potential);
    let momenta = graph.gradient(store, lagrangian, &velocities);
    let mut mass_matrix = vec![graph.leaf(store, Store::ZERO); n * n];
    for i in 0..n {
        for j in i..n {
            let m = graph.diff(store, momenta[i], velocities[j]);
            mass_matrix[i * n + j] = m;
            mass_matrix[j * n + i] = m;
        }
    }
    let dl_dq = graph.gradient(store, lagrangian, &positions);
    let momenta_rate: Vec<GraphId> = (momenta.iter())
        .map(|&p| graph.time_derivative(store, p, &coordinates))
        .collect();
    let dd_dqd = graph.gradient(store, dissipation, &velocities);
    let mut forcing = Vec::with_capacity(n);
    let mut damping_terms = Vec::with_capacity(n);
    let mut power_terms = Vec::with_capacity(n);
    for i in 0..n {
        let q = graph.leaf(store, forces[i]);
        let lhs = graph.sub(store, dl_dq[i], momenta_rate[i]);
        let rhs = graph.sub(store, q, dd_dqd[i]);
        forcing.push(graph.add(store, lhs, rhs));
        let velocity = graph.leaf(store, model.coordinates[i].symbols.velocity_expr);
        damping_terms.push(graph.mul(store, dd_dqd[i], velocity));
        power_terms.push(graph.mul(store, q, velocity));
    }
    let damping_power = graph.sum(store, &damping_terms);
    let external_power = graph.sum(store, &power_terms);
    let energies = [
        kinetic,
        potential,
        dissipation,
        damping_power,
        external_power,
    ];
    let jacobians = model
        .jacobians
        .then(|| jacobians(model, &mass_matrix, &forcing));
    let outputs = (model.outputs.iter())
        .map(|o| model.graph.leaf(&model.store, o.statement.value))
        .collect();
    let roots: Vec<GraphId> = mass_matrix.iter().chain(&forcing).copied().collect();
    let switching =
        crate::switching::graph_switching_functions(&mut model.store, &mut model.graph, &roots);
    if let Some(error) = model.store.take_errors().into_iter().next() {
        let names: Vec<String> = model.inputs.iter().map(|i| i.name.clone()).collect();
        let span = model.kinetic.span;
        let what = "the equations of motion";
        return Err(engine_diagnostic(&model.store, &names, error, span, what).into());
    }
    Ok(GraphDerivation {
        dimension: n,
        mass_matrix,
        forcing,
        energies,
        jacobians,
        outputs,
        switching,
    })
}

/// `Q_i`, the sum of the force statements' generalized forces (canonical).
fn generalized_forces(model: &mut Model) -> Vec<crate::expr::ExprId> {
    let mut forces = vec![Store::ZERO; model.dimension()];
    for force in &model.forces {
        for &(i, q) in &force.generalized {
            forces[i] = model.store.add(forces[i], q);
        }
    }
    forces
}

/// `∂f/∂q`, `∂f/∂q̇` and `∂(M a)/∂q = Σ_j ∂M_ij/∂q_k a_j`.
fn jacobians(model: &mut Model, mass: &[GraphId], forcing: &[GraphId]) -> [Vec<GraphId>; 3] {
    let n = model.dimension();
    let coordinates = model.coordinate_symbols();
    let (graph, store) = (&mut model.graph, &mut model.store);
    let mut forcing_q = Vec::with_capacity(n * n);
    let mut forcing_qd = Vec::with_capacity(n * n);
    let mut mass_times_acceleration_q = Vec::with_capacity(n * n);
    for i in 0..n {
        for ck in &coordinates {
            forcing_q.push(graph.diff(store, forcing[i], ck.position));
            forcing_qd.push(graph.diff(store, forcing[i], ck.velocity));
            let mut terms = Vec::with_capacity(n);
            for (j, cj) in coordinates.iter().enumerate() {
                let dm = graph.diff(store, mass[i * n + j], ck.position);
                let a = graph.leaf(store, cj.acceleration_expr);
                terms.push(graph.mul(store, dm, a));
            }
            mass_times_acceleration_q.push(graph.sum(store, &terms));
        }
    }
    [forcing_q, forcing_qd, mass_times_acceleration_q]
}
