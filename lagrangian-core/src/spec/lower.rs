//! Name resolution and validation: [`SpecAst`] → [`Model`].
//!
//! A pipeline of phases over one [`Lowering`] state: item collection
//! ([`items`]), symbols and declarations ([`declarations`]), `let`
//! definitions, energies and forces ([`statements`]), outputs
//! ([`outputs`]), constraints ([`constraints`]), units, the
//! `hand_derived` section, and assembly. Lowering goes on after an error
//! where it can, so one pass reports every independent problem; the checks
//! of names and of things given twice are in [`validate`].

mod constraints;
mod declarations;
mod items;
mod outputs;
mod statements;
mod validate;

use super::ast::{InputDecl, Item, ParameterDecl, SpecAst};
use super::dimensions::DimensionScope;
use super::expression::{Binding, ExpressionLowering, Lowered, Scope};
use super::{Coordinate, HandDerived, Model, Statement};
use crate::diagnostic::{Diagnostic, SpecErrors};
use crate::expr::{Store, SymbolId, SymbolKind};
use crate::graph::{Graph, GraphId};
use crate::units::Dimension;
use declarations::Declarations;
use items::{Header, Items};
use rustc_hash::FxHashMap;
use syn::{Expr, Ident};

/// Diagnostics collected while lowering.
#[derive(Default)]
struct Problems(Vec<Diagnostic>);

impl Problems {
    /// Records `d`, unless it only follows from a problem already recorded.
    fn push(&mut self, d: Diagnostic) {
        if !d.is_follow_up() {
            self.0.push(d);
        }
    }

    /// The value of `r`, or `None` with its diagnostic recorded.
    fn take<T>(&mut self, r: Result<T, Diagnostic>) -> Option<T> {
        r.map_err(|d| self.push(d)).ok()
    }
}

/// The state the phases share: the expression store, the names in scope
/// and the problems found so far.
struct Lowering {
    store: Store,
    scope: Scope,
    /// The declared input functions' names, by index.
    input_names: Vec<String>,
    problems: Problems,
    /// Warnings: what does not stop the spec compiling but a user should know.
    warnings: Vec<Diagnostic>,
    /// The derivation graph and the `let` helpers lowered to it.
    graph: Graph,
    graph_lets: FxHashMap<String, GraphId>,
    /// Why an energy has no canonical form, when one has none.
    canonical_limit: Option<Diagnostic>,
}

/// Resolves the names of `ast` and validates it: the model, or every
/// problem found.
pub(super) fn lower(ast: SpecAst) -> Result<Model, SpecErrors> {
    let mut problems = Problems::default();
    let items = Items::collect(ast, &mut problems);
    let header = Header::of(&items)?;
    let mut lowering = Lowering::new(problems, &items);
    let symbols = lowering.symbols(&items.coordinates, &items.parameters);
    let mut declared = lowering.declarations(
        items.coordinates,
        &items.parameters,
        &items.inputs,
        &symbols,
    );
    lowering.bind_time_and_pi(symbols.pi);
    lowering.input_derivatives(&items.inputs, &mut declared.inputs);
    let definitions = lowering.definitions(&items.statements);
    lowering.declare_outputs(&items.statements);
    lowering.column_clashes(&declared.coordinates, &items.inputs, &items.statements);
    lowering.declare_constraints(&items.statements);
    let dynamics = lowering.dynamics(&items.statements, &declared.coordinates);
    let outputs = lowering.outputs(&items.statements);
    let mut constraints = lowering.constraints(&items.statements, &declared.parameters);
    let declarations = (&items.inputs[..], &items.parameters[..]);
    let mut dimensions = lowering.units(&items.statements, declarations, &declared);
    let checked = !super::unit_check::UnitCoverage::of(
        &declared.coordinates,
        &declared.parameters,
        &items.inputs,
    )
    .none();
    constraints::dimensions(&mut constraints, &items.statements, &dimensions, checked);
    let coordinate_dimensions = coordinate_dimensions(&dimensions, &declared.coordinates);
    let hand_derived = lowering.hand_derived(&items.statements, &declared, &mut dimensions);
    let [kinetic, potential, dissipation] = dynamics.energies;
    let warnings = std::mem::take(&mut lowering.warnings);
    let graph = std::mem::replace(&mut lowering.graph, Graph::new(lowering.scope.time));
    let canonical_limit = lowering.canonical_limit.take();
    let domain_checks = lowering.scope.domain_checks.take();
    let (store, time, kinetic) = lowering.finish(&header.name, kinetic)?;
    Ok(Model {
        name: header.name.to_string(),
        name_span: header.name.span(),
        doc: header.doc,
        store,
        coordinates: declared.coordinates,
        parameters: declared.parameters,
        inputs: declared.inputs,
        time,
        kinetic,
        potential,
        dissipation,
        forces: dynamics.forces,
        outputs,
        constraints,
        definitions,
        jacobians: dynamics.jacobians_span.is_some(),
        jacobians_span: dynamics.jacobians_span,
        hand_derived,
        coordinate_dimensions,
        graph,
        energy_graph: dynamics.energy_graph,
        canonical_limit,
        warnings,
        domain_checks,
    })
}

impl Lowering {
    /// A fresh store whose first symbol is time, and an empty scope.
    fn new(problems: Problems, items: &Items) -> Lowering {
        let mut store = Store::new();
        let time = store.symbol("t", SymbolKind::Time).0;
        Lowering {
            store,
            scope: Scope {
                names: FxHashMap::default(),
                coordinates: Vec::new(),
                time,
                velocities: Vec::new(),
                constants: Default::default(),
                domain_checks: Default::default(),
            },
            input_names: items
                .inputs
                .iter()
                .map(|d| d.decl.name.to_string())
                .collect(),
            problems,
            warnings: Vec::new(),
            graph: Graph::new(time),
            graph_lets: FxHashMap::default(),
            canonical_limit: None,
        }
    }

    /// Binds `ident` to `binding`, unless the name is reserved or taken.
    fn declare(&mut self, ident: &Ident, binding: Binding) {
        let problem =
            validate::reserved_name(ident).or_else(|| validate::duplicate_name(&self.scope, ident));
        match problem {
            Some(d) => self.problems.push(d),
            None => {
                let entry = (binding, ident.span());
                self.scope.names.insert(ident.to_string(), entry);
            }
        }
    }

    /// Lowers `expr` in the spec's scope; `None` with its diagnostic recorded.
    fn lower_expression(&mut self, expr: &Expr) -> Option<Lowered> {
        let lowering = ExpressionLowering::new(&mut self.store, &self.scope, &self.input_names);
        self.problems.take(lowering.lower(expr))
    }

    /// Lowers `expr` to the graph (see [`super::graph_lowering`]).
    fn lower_to_graph(&mut self, expr: &Expr) -> Option<GraphId> {
        super::graph_lowering::GraphLowering {
            store: &mut self.store,
            graph: &mut self.graph,
            scope: &self.scope,
            lets: &self.graph_lets,
            input_names: &self.input_names,
        }
        .lower(expr)
    }

    /// Checks dimensional consistency where units are declared (nothing
    /// when no name has a unit; a warning when some lack one); returns the
    /// dimensions of the declared and defined names.
    fn units(
        &mut self,
        statements: &[Item],
        (inputs, parameter_decls): (&[InputDecl], &[ParameterDecl]),
        declared: &Declarations,
    ) -> DimensionScope {
        let (coordinates, parameters) = (&declared.coordinates, &declared.parameters);
        let mut unit_problems = Vec::new();
        let mut dimensions =
            super::unit_check::scope(coordinates, parameters, inputs, &mut unit_problems);
        let coverage = super::unit_check::UnitCoverage::of(coordinates, parameters, inputs);
        if coverage.none() {
            return dimensions;
        }
        self.warnings.extend(coverage.warning());
        let checked = super::unit_check::check(&mut dimensions, statements, inputs, coordinates);
        let defaults = super::unit_check::defaults(&dimensions, parameter_decls);
        for d in unit_problems.into_iter().chain(checked).chain(defaults) {
            self.problems.push(d);
        }
        dimensions
    }

    /// Lowers the `hand_derived` section, of which there may be one.
    fn hand_derived(
        &mut self,
        statements: &[Item],
        declared: &Declarations,
        dimensions: &mut DimensionScope,
    ) -> Option<HandDerived> {
        let mut hand_derived = None;
        for item in statements {
            let Item::HandDerived(section) = item else {
                continue;
            };
            if let Some(d) = validate::second_hand_section(hand_derived.is_some(), section) {
                self.problems.push(d);
                continue;
            }
            let context = super::hand::HandContext {
                store: &mut self.store,
                scope: &self.scope,
                input_names: &self.input_names,
                dimensions,
                coordinates: &declared.coordinates,
                parameters: &declared.parameters,
                inputs: &declared.inputs,
            };
            match super::hand::lower(section, context) {
                Ok(h) => hand_derived = Some(h),
                Err(list) => list.into_iter().for_each(|d| self.problems.push(d)),
            }
        }
        hand_derived
    }

    /// The store, the time symbol and the kinetic energy, when the spec has
    /// no problem; else every problem found (and that the kinetic energy is
    /// missing, when it is the only one).
    fn finish(
        mut self,
        name: &Ident,
        kinetic: Option<Statement>,
    ) -> Result<(Store, SymbolId, Statement), SpecErrors> {
        if kinetic.is_none() && self.problems.0.is_empty() {
            self.problems.push(
                Diagnostic::new(name.span(), format!("model `{name}` has no kinetic energy"))
                    .with_help("add `kinetic = …;` (e.g. `kinetic = 0.5 * m * pow(dot(x), 2);`)"),
            );
        }
        match kinetic {
            Some(kinetic) if self.problems.0.is_empty() => {
                Ok((self.store, self.scope.time, kinetic))
            }
            _ => Err(SpecErrors {
                diagnostics: self.problems.0,
            }),
        }
    }
}

/// The dimension of each coordinate, where its unit is declared.
fn coordinate_dimensions(
    dimensions: &DimensionScope,
    coordinates: &[Coordinate],
) -> Vec<Option<Dimension>> {
    coordinates
        .iter()
        .map(|c| dimensions.names.get(&c.name).copied().flatten())
        .collect()
}
