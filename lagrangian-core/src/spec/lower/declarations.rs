//! The symbols and declarations phases: coordinates, parameters, input
//! functions with their declared derivatives, and the built-in `t` and `pi`.

use super::{Lowering, validate};
use crate::diagnostic::{Diagnostic, SpanRange};
use crate::expr::{CoordinateSymbols, Evaluator, ExprId, Store, SymbolId, SymbolKind, no_inputs};
use crate::spec::ast::{Declaration, InputDecl, ParameterDecl};
use crate::spec::expression::{Binding, ExpressionLowering, Scope, literal_default};
use crate::spec::{Coordinate, Input, Parameter};
use proc_macro2::Span;
use rustc_hash::FxHashMap;

/// The symbols of the declarations, each with its expression.
pub(super) struct Symbols {
    pub positions: Vec<(SymbolId, ExprId)>,
    pub velocities: Vec<(SymbolId, ExprId)>,
    pub parameters: Vec<(SymbolId, ExprId)>,
    pub accelerations: Vec<(SymbolId, ExprId)>,
    /// The symbol `pi`.
    pub pi: ExprId,
}

/// The declared coordinates, parameters and input functions, resolved.
pub(super) struct Declarations {
    pub coordinates: Vec<Coordinate>,
    pub parameters: Vec<Parameter>,
    pub inputs: Vec<Input>,
}

impl Lowering {
    /// Creates the symbols: coordinates, then velocities, parameters,
    /// accelerations and `pi` (time comes first, with the store). This order
    /// fixes the canonical order of terms and of trigonometric arguments.
    pub(super) fn symbols(
        &mut self,
        coordinates: &[Declaration],
        parameters: &[ParameterDecl],
    ) -> Symbols {
        let store = &mut self.store;
        let coordinate_names = || coordinates.iter().map(|c| c.name.to_string());
        let positions = numbered(store, coordinate_names(), SymbolKind::Coordinate);
        let velocities = numbered(
            store,
            coordinate_names().map(|c| format!("dot({c})")),
            SymbolKind::Velocity,
        );
        let parameters = numbered(
            store,
            parameters.iter().map(|p| p.decl.name.to_string()),
            SymbolKind::Parameter,
        );
        let accelerations = numbered(
            store,
            coordinate_names().map(|c| format!("ddot({c})")),
            SymbolKind::Acceleration,
        );
        let pi = store.symbol("pi", SymbolKind::Pi).1;
        Symbols {
            positions,
            velocities,
            parameters,
            accelerations,
            pi,
        }
    }

    /// Declares the coordinates, parameters and input functions, in that
    /// order, each kind in source order.
    pub(super) fn declarations(
        &mut self,
        coordinates: Vec<Declaration>,
        parameters: &[ParameterDecl],
        inputs: &[InputDecl],
        symbols: &Symbols,
    ) -> Declarations {
        let coordinates = coordinates
            .into_iter()
            .enumerate()
            .map(|(i, decl)| self.coordinate(decl, i, symbols))
            .collect();
        let mut lowered: Vec<Parameter> = Vec::with_capacity(parameters.len());
        for (k, (decl, &symbol)) in parameters.iter().zip(&symbols.parameters).enumerate() {
            let around = (&lowered[..], &parameters[k + 1..]);
            let parameter = self.parameter(decl, symbol, symbols.pi, around);
            lowered.push(parameter);
        }
        let parameters = lowered;
        let inputs = inputs.iter().map(|decl| self.input(decl)).collect();
        Declarations {
            coordinates,
            parameters,
            inputs,
        }
    }

    fn coordinate(&mut self, decl: Declaration, i: usize, symbols: &Symbols) -> Coordinate {
        let (position, velocity) = (symbols.positions[i], symbols.velocities[i]);
        let acceleration = symbols.accelerations[i];
        let coordinate_symbols = CoordinateSymbols {
            position: position.0,
            velocity: velocity.0,
            velocity_expr: velocity.1,
            acceleration_expr: acceleration.1,
        };
        self.declare(&decl.name, Binding::Value(position.1));
        self.scope.coordinates.push(coordinate_symbols.clone());
        self.scope.velocities.push(velocity.0);
        Coordinate {
            name: decl.name.to_string(),
            doc: decl.doc,
            unit: decl.unit,
            span: decl.name.span(),
            position_expr: position.1,
            symbols: coordinate_symbols,
            acceleration: acceleration.0,
        }
    }

    /// Parameter `p`; its default may use the parameters declared before
    /// it (`earlier`), at their defaults, but not those below (`later`).
    fn parameter(
        &mut self,
        p: &ParameterDecl,
        (symbol, expr): (SymbolId, ExprId),
        pi: ExprId,
        (earlier, later): (&[Parameter], &[ParameterDecl]),
    ) -> Parameter {
        self.declare(&p.decl.name, Binding::Value(expr));
        let default = constant_value(&mut self.store, p, pi, self.scope.time, earlier)
            .map_err(|problem| declared_below(problem, later));
        Parameter {
            name: p.decl.name.to_string(),
            doc: p.decl.doc.clone(),
            unit: p.decl.unit.clone(),
            span: p.decl.name.span(),
            default: self.problems.take(default).unwrap_or(0.0),
            symbol,
            expr,
        }
    }

    fn input(&mut self, decl: &InputDecl) -> Input {
        for d in validate::duplicate_arguments(decl) {
            self.problems.push(d);
        }
        let arguments: Vec<String> = decl.arguments.iter().map(|a| a.name.to_string()).collect();
        let index = self
            .store
            .declare_input(&decl.decl.name.to_string(), &arguments);
        self.declare(&decl.decl.name, Binding::Input(index, arguments.len()));
        Input {
            name: decl.decl.name.to_string(),
            doc: decl.decl.doc.clone(),
            unit: decl.decl.unit.clone(),
            span: decl.decl.name.span(),
            arguments: decl
                .arguments
                .iter()
                .map(|a| (a.name.to_string(), a.unit.clone()))
                .collect(),
            derivative_spans: vec![None; arguments.len()],
        }
    }

    /// Binds the built-in names `t` (time) and `pi`.
    pub(super) fn bind_time_and_pi(&mut self, pi: ExprId) {
        let time = self.store.symbol_expr(self.scope.time);
        let names = &mut self.scope.names;
        names.insert("t".into(), (Binding::Value(time), Span::call_site()));
        names.insert("pi".into(), (Binding::Value(pi), Span::call_site()));
    }

    /// Lowers the declared derivatives `d(arg) = …` of the input functions.
    pub(super) fn input_derivatives(&mut self, decls: &[InputDecl], inputs: &mut [Input]) {
        for (index, decl) in decls.iter().enumerate() {
            let local = self.derivative_scope(index, decl);
            for (arg, expr) in &decl.derivatives {
                let Some(position) = decl.arguments.iter().position(|a| a.name == *arg) else {
                    self.problems.push(Diagnostic::new(
                        arg.span(),
                        format!("`{}` has no argument named `{arg}`", decl.decl.name),
                    ));
                    continue;
                };
                let first = inputs[index].derivative_spans[position];
                if let Some(d) = validate::derivative_declared_twice(arg, first) {
                    self.problems.push(d);
                    continue;
                }
                let lowered =
                    ExpressionLowering::new(&mut self.store, &local, &self.input_names).lower(expr);
                if let Some(l) = self.problems.take(lowered) {
                    self.store.set_input_derivative(index, position, l.value);
                    inputs[index].derivative_spans[position] = Some(arg.span());
                }
            }
        }
    }

    /// The names a derivative of input `index` may use: the input's own
    /// arguments, the parameters and other inputs; coordinates and `let`s
    /// are out of scope.
    fn derivative_scope(&mut self, index: usize, decl: &InputDecl) -> Scope {
        let (scope, store) = (&self.scope, &mut self.store);
        let is_coordinate = |name: &String| {
            scope
                .coordinates
                .iter()
                .any(|c| store.symbol_info(c.position).name == *name)
        };
        let mut names: FxHashMap<_, _> = scope
            .names
            .iter()
            .filter(|(_, (b, _))| !matches!(b, Binding::Definition(..)))
            .filter(|(n, _)| !is_coordinate(n))
            .map(|(n, v)| (n.clone(), v.clone()))
            .collect();
        let formal = store.inputs()[index].arguments.clone();
        for (arg, symbol) in decl.arguments.iter().zip(&formal) {
            let e = store.symbol_expr(*symbol);
            names.insert(arg.name.to_string(), (Binding::Value(e), arg.name.span()));
        }
        Scope {
            names,
            coordinates: Vec::new(),
            time: scope.time,
            velocities: Vec::new(),
            constants: Default::default(),
            domain_checks: Default::default(),
        }
    }
}

/// One symbol per name, the `i`-th of kind `kind(i)`.
fn numbered(
    store: &mut Store,
    names: impl Iterator<Item = String>,
    kind: fn(usize) -> SymbolKind,
) -> Vec<(SymbolId, ExprId)> {
    names
        .enumerate()
        .map(|(i, name)| store.symbol(&name, kind(i)))
        .collect()
}

/// Explains an unknown name in a parameter's default that is a parameter
/// declared below it (`later`): a default may use only those above it.
fn declared_below(problem: Diagnostic, later: &[ParameterDecl]) -> Diagnostic {
    let name = problem.unknown_name();
    match name.and_then(|name| later.iter().find(|p| p.decl.name == name)) {
        Some(below) => {
            let name = &below.decl.name;
            Diagnostic::new(
                problem.span,
                format!("parameter `{name}` is declared below"),
            )
            .with_note("declared here", name.span())
            .with_help(format!(
                "a default may use only the parameters declared before it: move `{name}` up"
            ))
        }
        None => problem,
    }
}

/// Evaluates a parameter's default value: a constant expression of
/// numbers, `pi` and the parameters declared before it (`earlier`, at their
/// defaults).
fn constant_value(
    store: &mut Store,
    p: &ParameterDecl,
    pi: ExprId,
    time: SymbolId,
    earlier: &[Parameter],
) -> Result<f64, Diagnostic> {
    let Some(value) = &p.value else {
        return Err(Diagnostic::new(
            p.decl.name.span(),
            format!("parameter `{}` has no default value", p.decl.name),
        )
        .with_help(format!("write `{} = value`", p.decl.name)));
    };
    if let Some(value) = literal_default(value) {
        return value;
    }
    let mut scope = Scope {
        names: FxHashMap::default(),
        coordinates: Vec::new(),
        time,
        velocities: Vec::new(),
        constants: Default::default(),
        domain_checks: Default::default(),
    };
    scope
        .names
        .insert("pi".into(), (Binding::Value(pi), Span::call_site()));
    for e in earlier {
        (scope.names).insert(e.name.clone(), (Binding::Value(e.expr), e.span));
    }
    let lowered = ExpressionLowering::new(store, &scope, &[]).lower(value)?;
    let is_earlier = |s: SymbolId| earlier.iter().any(|e| e.symbol == s);
    let free = store.free_symbols(lowered.value);
    if free
        .iter()
        .any(|s| store.symbol_info(*s).kind != SymbolKind::Pi && !is_earlier(*s))
    {
        return Err(Diagnostic::new(
            SpanRange::of(value),
            "a parameter default must be a constant",
        )
        .with_help("it may use numbers, `pi` and the parameters declared before it"));
    }
    let mut values = vec![0.0; store.symbols().len()];
    for e in earlier {
        values[e.symbol.index()] = e.default;
    }
    let result = Evaluator::new(store, values, &no_inputs).eval(lowered.value);
    if result.is_finite() {
        Ok(result)
    } else {
        Err(Diagnostic::new(
            SpanRange::of(value),
            format!("this default evaluates to {result}"),
        ))
    }
}
