//! The statement phases: `let` definitions, then the energies, forces and
//! `jacobians;`.

use super::{Lowering, validate};
use crate::diagnostic::{Diagnostic, SpanRange, closest};
use crate::expr::{ExprId, Store};
use crate::graph::GraphId;
use crate::spec::ast::{EnergyKind, Item};
use crate::spec::constant;
use crate::spec::expression::{Binding, ExpressionLowering, Lowered, engine_diagnostic};
use crate::spec::{Coordinate, ForceStatement, Statement};
use proc_macro2::Span;
use syn::{Expr, Ident};

/// The energies, forces and Jacobian request of a spec.
#[derive(Default)]
pub(super) struct Dynamics {
    /// Kinetic energy, potential energy and dissipation function, indexed by
    /// [`EnergyKind`].
    pub energies: [Option<Statement>; 3],
    /// The energies as graph nodes, where they lowered to the graph.
    pub energy_graph: [Option<GraphId>; 3],
    pub forces: Vec<ForceStatement>,
    /// The first `jacobians;`.
    pub jacobians_span: Option<Span>,
}

impl Lowering {
    /// Lowers the `let` definitions in order (each may use the ones before
    /// it); returns `(name, value)` of each that lowered.
    pub(super) fn definitions(&mut self, statements: &[Item]) -> Vec<(String, ExprId)> {
        let lets: Vec<(&Ident, &Expr)> = (statements.iter())
            .filter_map(|item| match item {
                Item::Let { name, value, .. } => Some((name, value)),
                _ => None,
            })
            .collect();
        let mut definitions = Vec::new();
        for (k, &(name, value)) in lets.iter().enumerate() {
            let below: Vec<&Ident> = lets[k + 1..].iter().map(|(n, _)| *n).collect();
            if let Some(definition) = self.definition(name, value, &below) {
                definitions.push(definition);
            }
        }
        definitions
    }

    /// Lowers `let name = syntax;`; a use of a `let` of `below` (defined
    /// after it) is an error that says where that one is.
    fn definition(
        &mut self,
        name: &Ident,
        syntax: &Expr,
        below: &[&Ident],
    ) -> Option<(String, ExprId)> {
        let lowering = ExpressionLowering::new(&mut self.store, &self.scope, &self.input_names);
        let lowered = lowering.lower(syntax).map_err(|d| defined_below(d, below));
        let Some(Lowered { value, input_calls }) = self.problems.take(lowered) else {
            // Its uses fail quietly: the definition's error says it all.
            self.declare(name, Binding::Failed);
            return None;
        };
        if let Ok(Some(c)) = constant::evaluate(syntax, &self.scope.constants) {
            self.scope.constants.insert(name.to_string(), c);
        }
        self.declare(name, Binding::Definition(value, input_calls));
        if let Some(g) = self.lower_to_graph(syntax) {
            self.graph_lets.insert(name.to_string(), g);
        }
        Some((name.to_string(), value))
    }

    /// Lowers the energies, the force statements and `jacobians;`, in
    /// source order.
    pub(super) fn dynamics(&mut self, statements: &[Item], coordinates: &[Coordinate]) -> Dynamics {
        let mut dynamics = Dynamics::default();
        for item in statements {
            match item {
                Item::Energy {
                    kind,
                    keyword,
                    value,
                } => self.energy(&mut dynamics, *kind, *keyword, value),
                Item::GeneralizedForce {
                    keyword,
                    coordinate,
                    value,
                    ..
                } => {
                    let force = self.generalized_force(coordinates, *keyword, coordinate, value);
                    dynamics.forces.extend(force);
                }
                Item::PointForce {
                    point,
                    point_span,
                    components,
                    components_span,
                } => {
                    let span = SpanRange {
                        start: *point_span,
                        end: *components_span,
                    };
                    let force = self.point_force(coordinates, point, components, span);
                    dynamics.forces.extend(self.problems.take(force));
                }
                Item::Jacobians { keyword } => {
                    dynamics.jacobians_span.get_or_insert(*keyword);
                }
                Item::Let { .. }
                | Item::Output(_)
                | Item::Constraint(_)
                | Item::HandDerived(_)
                | Item::Model { .. }
                | Item::Coordinates { .. }
                | Item::Parameters { .. }
                | Item::Inputs { .. }
                | Item::For { .. }
                | Item::PartDef(_)
                | Item::PartInstance(_) => {}
            }
        }
        dynamics
    }

    /// `kinetic = …;` and the like: lowered to the canonical form within a
    /// budget, and to the graph. An energy too large for the
    /// canonical form is kept on the graph alone (its value a placeholder
    /// 0, the reason in `canonical_limit`).
    fn energy(&mut self, dynamics: &mut Dynamics, kind: EnergyKind, keyword: Span, value: &Expr) {
        let slot = &mut dynamics.energies[kind as usize];
        if let Some(d) = validate::energy_given_twice(kind, keyword, slot.as_ref()) {
            self.problems.push(d);
            return;
        }
        self.store.set_budget(Some(CANONICAL_ENERGY_SIZE));
        self.store.take_size_limit();
        let lowering = ExpressionLowering::new(&mut self.store, &self.scope, &self.input_names);
        let canonical = lowering.lower(value);
        let too_large = self.store.take_size_limit();
        self.store.set_budget(None);
        let graph = self.lower_to_graph(value);
        dynamics.energy_graph[kind as usize] = graph;
        let span = SpanRange::of(value);
        let lowered = match canonical {
            Ok(l) => l,
            Err(d) if too_large && graph.is_some() => {
                self.canonical_limit.get_or_insert(d);
                let (value, input_calls) = (Store::ZERO, Vec::new());
                Lowered { value, input_calls }
            }
            Err(d) => return self.problems.push(d),
        };
        dynamics.energies[kind as usize] = Some(Statement {
            value: lowered.value,
            span,
            input_calls: lowered.input_calls,
        });
    }

    /// `force q = Q;`.
    fn generalized_force(
        &mut self,
        coordinates: &[Coordinate],
        keyword: Span,
        coordinate: &Ident,
        value: &Expr,
    ) -> Option<ForceStatement> {
        let Some(index) = coordinates.iter().position(|c| *coordinate == c.name) else {
            self.problems
                .push(not_a_coordinate(coordinates, keyword, coordinate));
            return None;
        };
        let l = self.lower_expression(value)?;
        Some(ForceStatement {
            span: SpanRange::of(value),
            generalized: vec![(index, l.value)],
            input_calls: l.input_calls,
        })
    }

    /// `force at (p…) = (F…)`: `Q_i = Σ_k F_k ∂p_k/∂q_i` (virtual work).
    /// `span` runs from the point to the components.
    fn point_force(
        &mut self,
        coordinates: &[Coordinate],
        point: &[Expr],
        components: &[Expr],
        span: SpanRange,
    ) -> Result<ForceStatement, Diagnostic> {
        let mut input_calls = Vec::new();
        let mut position = Vec::new();
        for p in point {
            let l = self.point_coordinate(p)?;
            input_calls.extend(l.input_calls);
            position.push(l.value);
        }
        let mut force = Vec::new();
        for f in components {
            let l = ExpressionLowering::new(&mut self.store, &self.scope, &self.input_names)
                .lower(f)?;
            input_calls.extend(l.input_calls);
            force.push(l.value);
        }
        let mut generalized = Vec::new();
        for (i, c) in coordinates.iter().enumerate() {
            let mut terms = Vec::new();
            for (&p, &f) in position.iter().zip(&force) {
                let dp = self.store.diff(p, c.symbols.position);
                terms.push(self.store.mul(f, dp));
            }
            if let Some(error) = self.store.take_errors().into_iter().next() {
                let at = span.start.into();
                let store = &self.store;
                let what = "the point force";
                return Err(engine_diagnostic(store, &self.input_names, error, at, what));
            }
            let q = self.store.sum(&terms);
            if q != Store::ZERO {
                generalized.push((i, q));
            }
        }
        Ok(ForceStatement {
            span,
            generalized,
            input_calls,
        })
    }

    /// One coordinate of a point of application: a position, so it must
    /// not depend on a velocity.
    fn point_coordinate(&mut self, p: &Expr) -> Result<Lowered, Diagnostic> {
        let l =
            ExpressionLowering::new(&mut self.store, &self.scope, &self.input_names).lower(p)?;
        let store = &self.store;
        let mut velocities = self.scope.velocities.iter();
        let Some(v) = velocities.find(|v| store.depends_on(l.value, **v)) else {
            return Ok(l);
        };
        Err(Diagnostic::new(
            SpanRange::of(p),
            format!(
                "the point of application depends on the velocity `{}`",
                store.symbol_info(*v).name
            ),
        )
        .with_help("a point is a position: a function of the coordinates and time"))
    }
}

/// The largest total size ([`Store::set_budget`]) of the nodes that the
/// canonical form of one energy may create; a bigger energy stays on the
/// graph alone. Well above what the shipped specs need (a 20-link chain's
/// kinetic energy stays canonical).
const CANONICAL_ENERGY_SIZE: usize = 50_000;

/// An unknown name that is a `let` defined further down (`below`): said so,
/// with a note at its definition.
fn defined_below(problem: Diagnostic, below: &[&Ident]) -> Diagnostic {
    let name = problem.unknown_name();
    match name.and_then(|name| below.iter().find(|b| **b == name)) {
        Some(definition) => Diagnostic::new(
            problem.span,
            format!("`{definition}` is defined below, by a later `let`"),
        )
        .with_note("defined here", definition.span())
        .with_help(format!(
            "a `let` may use only those before it: move `let {definition}` up"
        )),
        None => problem,
    }
}

/// `force q = …` names something that is not a coordinate.
fn not_a_coordinate(coordinates: &[Coordinate], keyword: Span, coordinate: &Ident) -> Diagnostic {
    let names = coordinates.iter().map(|c| c.name.as_str());
    let mut d = Diagnostic::new(
        coordinate.span(),
        format!("`{coordinate}` is not a generalized coordinate"),
    );
    if let Some(best) = closest(&coordinate.to_string(), names) {
        d = d.with_help(format!("did you mean `{best}`?"));
    }
    d.with_note("a generalized force acts on a declared coordinate", keyword)
}
