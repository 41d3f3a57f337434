//! Name resolution and validation: [`SpecAst`] → [`Model`].

use super::ast::*;
use super::expression::{
    Binding, ExpressionLowering, Lowered, Scope, engine_diagnostic, literal_default,
};
use super::{Coordinate, ForceStatement, Input, Model, Parameter, RESERVED_NAMES, Statement};
use crate::diagnostic::{Diagnostic, SpanRange, SpecErrors};
use crate::expr::{CoordinateSymbols, Evaluator, ExprId, Store, SymbolKind, no_inputs};
use proc_macro2::Span;
use rustc_hash::FxHashMap;

/// Diagnostics collected while lowering; lowering goes on after an error where it can.
#[derive(Default)]
struct Problems(Vec<Diagnostic>);

impl Problems {
    /// Records `d`, unless it only follows from a problem already recorded.
    fn push(&mut self, d: Diagnostic) {
        if !d.is_follow_up() {
            self.0.push(d);
        }
    }

    fn take<T>(&mut self, r: Result<T, Diagnostic>) -> Option<T> {
        r.map_err(|d| self.push(d)).ok()
    }
}

pub(super) fn lower(ast: SpecAst) -> Result<Model, SpecErrors> {
    let mut problems = Problems::default();
    let mut model_name: Option<(syn::Ident, Vec<String>)> = None;
    let mut coordinate_decls = Vec::new();
    let mut parameter_decls = Vec::new();
    let mut input_decls = Vec::new();
    let mut coordinates_keyword = None;
    let mut statements = Vec::new();
    for item in ast.items {
        match item {
            Item::Model { doc, name } => match &model_name {
                Some((first, _)) => problems.push(
                    Diagnostic::new(name.span(), "the model is named twice")
                        .with_note("first named here", first.span()),
                ),
                None => model_name = Some((name, doc)),
            },
            Item::Coordinates { keyword, decls } => {
                coordinates_keyword.get_or_insert(keyword);
                coordinate_decls.extend(decls);
            }
            Item::Parameters { decls, .. } => parameter_decls.extend(decls),
            Item::Inputs { decls, .. } => input_decls.extend(decls),
            other => statements.push(other),
        }
    }
    let Some((name, mut doc)) = model_name else {
        return Err(
            Diagnostic::new(Span::call_site(), "the spec does not name its model")
                .with_help("start the spec with `model Name;`")
                .into(),
        );
    };
    doc.splice(0..0, ast.inner_doc);
    if coordinate_decls.is_empty() {
        let span = coordinates_keyword.unwrap_or(name.span());
        return Err(
            Diagnostic::new(span, "the model declares no generalized coordinates")
                .with_help("add `coordinates { x, theta }` with at least one coordinate")
                .into(),
        );
    }

    let mut store = Store::new();
    let mut scope = Scope {
        names: FxHashMap::default(),
        coordinates: Vec::new(),
        time: store.symbol("t", SymbolKind::Time).0,
        velocities: Vec::new(),
        constants: Default::default(),
    };
    let declare =
        |scope: &mut Scope, ident: &syn::Ident, binding: Binding, problems: &mut Problems| {
            let name = ident.to_string();
            if let Some(reserved) = RESERVED_NAMES.iter().find(|r| **r == name) {
                problems.push(Diagnostic::new(
                    ident.span(),
                    format!("`{reserved}` is reserved by the spec language and cannot be declared"),
                ));
            } else if let Some((_, first)) = scope.names.get(&name) {
                problems.push(
                    Diagnostic::new(ident.span(), format!("`{name}` is declared twice"))
                        .with_note("first declared here", *first),
                );
            } else {
                scope.names.insert(name, (binding, ident.span()));
            }
        };

    // Symbols: coordinates, then velocities, parameters, accelerations (this
    // order fixes the canonical order of terms and of trigonometric arguments).
    let positions: Vec<_> = coordinate_decls
        .iter()
        .enumerate()
        .map(|(i, c)| store.symbol(&c.name.to_string(), SymbolKind::Coordinate(i)))
        .collect();
    let velocities: Vec<_> = coordinate_decls
        .iter()
        .enumerate()
        .map(|(i, c)| store.symbol(&format!("dot({})", c.name), SymbolKind::Velocity(i)))
        .collect();
    let parameter_symbols: Vec<_> = parameter_decls
        .iter()
        .enumerate()
        .map(|(i, p)| store.symbol(&p.decl.name.to_string(), SymbolKind::Parameter(i)))
        .collect();
    let accelerations: Vec<_> = coordinate_decls
        .iter()
        .enumerate()
        .map(|(i, c)| store.symbol(&format!("ddot({})", c.name), SymbolKind::Acceleration(i)))
        .collect();
    let pi = store.symbol("pi", SymbolKind::Pi).1;

    let mut coordinates = Vec::new();
    for (i, decl) in coordinate_decls.into_iter().enumerate() {
        let symbols = CoordinateSymbols {
            position: positions[i].0,
            velocity: velocities[i].0,
            velocity_expr: velocities[i].1,
            acceleration_expr: accelerations[i].1,
        };
        declare(
            &mut scope,
            &decl.name,
            Binding::Value(positions[i].1),
            &mut problems,
        );
        scope.coordinates.push(symbols.clone());
        scope.velocities.push(velocities[i].0);
        coordinates.push(Coordinate {
            name: decl.name.to_string(),
            doc: decl.doc,
            unit: decl.unit,
            span: decl.name.span(),
            position_expr: positions[i].1,
            symbols,
            acceleration: accelerations[i].0,
        });
    }

    let mut parameters = Vec::new();
    for (i, p) in parameter_decls.iter().enumerate() {
        declare(
            &mut scope,
            &p.decl.name,
            Binding::Value(parameter_symbols[i].1),
            &mut problems,
        );
        let default = problems
            .take(constant_value(&mut store, p, pi, scope.time))
            .unwrap_or(0.0);
        parameters.push(Parameter {
            name: p.decl.name.to_string(),
            doc: p.decl.doc.clone(),
            unit: p.decl.unit.clone(),
            span: p.decl.name.span(),
            default,
            symbol: parameter_symbols[i].0,
            expr: parameter_symbols[i].1,
        });
    }

    let input_names: Vec<String> = input_decls
        .iter()
        .map(|d| d.decl.name.to_string())
        .collect();
    let mut inputs = Vec::new();
    for decl in &input_decls {
        let arguments: Vec<String> = decl.arguments.iter().map(|a| a.name.to_string()).collect();
        for (k, a) in decl.arguments.iter().enumerate() {
            if let Some(first) = decl.arguments[..k].iter().find(|b| b.name == a.name) {
                problems.push(
                    Diagnostic::new(
                        a.name.span(),
                        format!("argument `{}` is declared twice", a.name),
                    )
                    .with_note("first declared here", first.name.span()),
                );
            }
        }
        let index = store.declare_input(&decl.decl.name.to_string(), &arguments);
        declare(
            &mut scope,
            &decl.decl.name,
            Binding::Input(index, arguments.len()),
            &mut problems,
        );
        inputs.push(Input {
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
        });
    }
    let time = store.symbol_expr(scope.time);
    scope
        .names
        .insert("t".into(), (Binding::Value(time), Span::call_site()));
    scope
        .names
        .insert("pi".into(), (Binding::Value(pi), Span::call_site()));

    lower_input_derivatives(
        &mut store,
        &scope,
        &input_decls,
        &input_names,
        &mut inputs,
        &mut problems,
    );

    // `let` definitions, in order; each may use the ones before it.
    let mut definitions = Vec::new();
    for item in &statements {
        if let Item::Let {
            name,
            value: syntax,
        } = item
        {
            let lowered = ExpressionLowering::new(&mut store, &scope, &input_names).lower(syntax);
            match problems.take(lowered) {
                Some(Lowered { value, input_calls }) => {
                    if let Ok(Some(c)) = super::constant::evaluate(syntax, &scope.constants) {
                        scope.constants.insert(name.to_string(), c);
                    }
                    declare(
                        &mut scope,
                        name,
                        Binding::Definition(value, input_calls),
                        &mut problems,
                    );
                    definitions.push((name.to_string(), value));
                }
                // Its uses fail quietly: the definition's error says it all.
                None => declare(&mut scope, name, Binding::Failed, &mut problems),
            }
        }
    }

    let mut energies: [Option<Statement>; 3] = [None, None, None];
    let mut forces = Vec::new();
    let mut jacobians_span = None;
    for item in &statements {
        match item {
            Item::Energy {
                kind,
                keyword,
                value,
            } => {
                let slot = &mut energies[*kind as usize];
                if let Some(first) = slot {
                    problems.push(
                        Diagnostic::new(
                            *keyword,
                            format!("the {} is given twice", kind.description()),
                        )
                        .with_note("first given here", first.span)
                        .with_help(
                            "combine the terms into one expression (a `let` can name the parts)",
                        ),
                    );
                    continue;
                }
                let lowered =
                    ExpressionLowering::new(&mut store, &scope, &input_names).lower(value);
                if let Some(l) = problems.take(lowered) {
                    *slot = Some(Statement {
                        value: l.value,
                        span: SpanRange::of(value),
                        input_calls: l.input_calls,
                    });
                }
            }
            Item::GeneralizedForce {
                keyword,
                coordinate,
                value,
            } => {
                let Some(index) = coordinates.iter().position(|c| *coordinate == c.name) else {
                    let names = coordinates.iter().map(|c| c.name.as_str());
                    let mut d = Diagnostic::new(
                        coordinate.span(),
                        format!("`{coordinate}` is not a generalized coordinate"),
                    );
                    if let Some(best) = crate::diagnostic::closest(&coordinate.to_string(), names) {
                        d = d.with_help(format!("did you mean `{best}`?"));
                    }
                    problems.push(d.with_note(
                        "a generalized force acts on a declared coordinate",
                        *keyword,
                    ));
                    continue;
                };
                let lowered =
                    ExpressionLowering::new(&mut store, &scope, &input_names).lower(value);
                if let Some(l) = problems.take(lowered) {
                    forces.push(ForceStatement {
                        span: SpanRange::of(value),
                        generalized: vec![(index, l.value)],
                        input_calls: l.input_calls,
                    });
                }
            }
            Item::PointForce {
                keyword,
                point,
                point_span,
                components,
                components_span,
            } => {
                let force = point_force(
                    &mut store,
                    &scope,
                    &input_names,
                    &coordinates,
                    point,
                    *point_span,
                    components,
                    *components_span,
                    *keyword,
                );
                if let Some(f) = problems.take(force) {
                    forces.push(f);
                }
            }
            Item::Jacobians { keyword } => {
                jacobians_span.get_or_insert(*keyword);
            }
            _ => {}
        }
    }
    // Dimensional consistency, where units are declared.
    let mut unit_problems = Vec::new();
    let mut dimensions =
        super::unit_check::scope(&coordinates, &parameters, &input_decls, &mut unit_problems);
    unit_problems.extend(super::unit_check::check(
        &mut dimensions,
        &statements,
        &input_decls,
        &coordinates,
    ));
    for d in unit_problems {
        problems.push(d);
    }
    let coordinate_dimensions = coordinates
        .iter()
        .map(|c| dimensions.names.get(&c.name).copied().flatten())
        .collect();
    let mut hand_derived = None;
    for item in &statements {
        if let Item::HandDerived(section) = item {
            if hand_derived.is_some() {
                problems.push(Diagnostic::new(
                    section.keyword,
                    "only one `hand_derived` section is allowed",
                ));
                continue;
            }
            let context = super::hand::HandContext {
                store: &mut store,
                scope: &scope,
                input_names: &input_names,
                dimensions: &mut dimensions,
                coordinates: &coordinates,
                parameters: &parameters,
                inputs: &inputs,
            };
            match super::hand::lower(section, context) {
                Ok(h) => hand_derived = Some(h),
                Err(list) => list.into_iter().for_each(|d| problems.push(d)),
            }
        }
    }
    let [kinetic, potential, dissipation] = energies;
    let Some(kinetic) = kinetic else {
        if problems.0.is_empty() {
            problems.push(
                Diagnostic::new(name.span(), format!("model `{name}` has no kinetic energy"))
                    .with_help("add `kinetic = …;` (e.g. `kinetic = 0.5 * m * pow(dot(x), 2);`)"),
            );
        }
        return Err(SpecErrors {
            diagnostics: problems.0,
        });
    };
    if !problems.0.is_empty() {
        return Err(SpecErrors {
            diagnostics: problems.0,
        });
    }
    Ok(Model {
        name: name.to_string(),
        name_span: name.span(),
        doc,
        store,
        coordinates,
        parameters,
        inputs,
        time: scope.time,
        kinetic,
        potential,
        dissipation,
        forces,
        definitions,
        jacobians: jacobians_span.is_some(),
        jacobians_span,
        hand_derived,
        coordinate_dimensions,
    })
}

/// Evaluates a parameter's default value, which must be a constant expression.
fn constant_value(
    store: &mut Store,
    p: &ParameterDecl,
    pi: ExprId,
    time: crate::expr::SymbolId,
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
    };
    scope
        .names
        .insert("pi".into(), (Binding::Value(pi), Span::call_site()));
    let lowered = ExpressionLowering::new(store, &scope, &[]).lower(value)?;
    let free = store.free_symbols(lowered.value);
    if free
        .iter()
        .any(|s| store.symbol_info(*s).kind != SymbolKind::Pi)
    {
        return Err(Diagnostic::new(
            SpanRange::of(value),
            "a parameter default must be a constant",
        ));
    }
    let result = Evaluator::new(store, Vec::new(), &no_inputs).eval(lowered.value);
    if result.is_finite() {
        Ok(result)
    } else {
        Err(Diagnostic::new(
            SpanRange::of(value),
            format!("this default evaluates to {result}"),
        ))
    }
}

fn lower_input_derivatives(
    store: &mut Store,
    scope: &Scope,
    decls: &[InputDecl],
    input_names: &[String],
    inputs: &mut [Input],
    problems: &mut Problems,
) {
    for (index, decl) in decls.iter().enumerate() {
        // A derivative is a function of the input's own arguments, the
        // parameters and other inputs; coordinates and `let`s are out of scope.
        let mut local = Scope {
            names: scope
                .names
                .iter()
                .filter(|(_, (b, _))| !matches!(b, Binding::Definition(..)))
                .filter(|(n, _)| {
                    !scope
                        .coordinates
                        .iter()
                        .any(|c| store.symbol_info(c.position).name == **n)
                })
                .map(|(n, v)| (n.clone(), v.clone()))
                .collect(),
            coordinates: Vec::new(),
            time: scope.time,
            velocities: Vec::new(),
            constants: Default::default(),
        };
        let formal = store.inputs()[index].arguments.clone();
        for (arg, symbol) in decl.arguments.iter().zip(&formal) {
            let e = store.symbol_expr(*symbol);
            local
                .names
                .insert(arg.name.to_string(), (Binding::Value(e), arg.name.span()));
        }
        for (arg, expr) in &decl.derivatives {
            let Some(position) = decl.arguments.iter().position(|a| a.name == *arg) else {
                problems.push(Diagnostic::new(
                    arg.span(),
                    format!("`{}` has no argument named `{arg}`", decl.decl.name),
                ));
                continue;
            };
            if let Some(first) = inputs[index].derivative_spans[position] {
                problems.push(
                    Diagnostic::new(
                        arg.span(),
                        format!("the derivative with respect to `{arg}` is declared twice"),
                    )
                    .with_note("first declared here", first),
                );
                continue;
            }
            let lowered = ExpressionLowering::new(store, &local, input_names).lower(expr);
            if let Some(l) = problems.take(lowered) {
                store.set_input_derivative(index, position, l.value);
                inputs[index].derivative_spans[position] = Some(arg.span());
            }
        }
    }
}

/// `force at (p…) = (F…)`: `Q_i = Σ_k F_k ∂p_k/∂q_i` (virtual work).
#[allow(clippy::too_many_arguments)]
fn point_force(
    store: &mut Store,
    scope: &Scope,
    input_names: &[String],
    coordinates: &[Coordinate],
    point: &[syn::Expr],
    point_span: Span,
    components: &[syn::Expr],
    components_span: Span,
    keyword: Span,
) -> Result<ForceStatement, Diagnostic> {
    let mut input_calls = Vec::new();
    let mut position = Vec::new();
    for p in point {
        let l = ExpressionLowering::new(store, scope, input_names).lower(p)?;
        if let Some(v) = scope
            .velocities
            .iter()
            .find(|v| store.depends_on(l.value, **v))
        {
            return Err(Diagnostic::new(
                SpanRange::of(p),
                format!(
                    "the point of application depends on the velocity `{}`",
                    store.symbol_info(*v).name
                ),
            )
            .with_help("a point is a position: a function of the coordinates and time"));
        }
        input_calls.extend(l.input_calls);
        position.push(l.value);
    }
    let mut force = Vec::new();
    for f in components {
        let l = ExpressionLowering::new(store, scope, input_names).lower(f)?;
        input_calls.extend(l.input_calls);
        force.push(l.value);
    }
    let mut generalized = Vec::new();
    for (i, c) in coordinates.iter().enumerate() {
        let mut terms = Vec::new();
        for (&p, &f) in position.iter().zip(&force) {
            let dp = store.diff(p, c.symbols.position);
            terms.push(store.mul(f, dp));
        }
        if let Some(error) = store.take_errors().into_iter().next() {
            return Err(engine_diagnostic(
                store,
                input_names,
                error,
                point_span.into(),
                "the point force",
            ));
        }
        let q = store.sum(&terms);
        if q != Store::ZERO {
            generalized.push((i, q));
        }
    }
    let _ = keyword;
    Ok(ForceStatement {
        span: SpanRange {
            start: point_span,
            end: components_span,
        },
        generalized,
        input_calls,
    })
}
