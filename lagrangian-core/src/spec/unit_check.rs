//! The dimensional checks of a spec: T and V are energies, D a power, a
//! generalized force times its coordinate's rate a power, a point force
//! times its point's displacement an energy, a declared derivative the
//! input's value over its argument, an output its declared unit.

use super::ast::{EnergyKind, InputDecl, Item, OutputDecl, ParameterDecl, UnitText};
use super::dimensions::{DimensionScope, InputDimensions};
use super::{Coordinate, Parameter};
use crate::diagnostic::Diagnostic;
use crate::units::Dimension;

/// The dimension of a declared unit, or a diagnostic at the unit.
fn parse(unit: &Option<UnitText>, problems: &mut Vec<Diagnostic>) -> Option<Dimension> {
    let unit = unit.as_ref()?;
    match Dimension::parse(&unit.text) {
        Ok(d) => Some(d),
        Err(error) => {
            problems.push(Diagnostic::new(unit.span, error.to_string()));
            None
        }
    }
}

/// The scope of dimensions of a spec's declarations.
pub(super) fn scope(
    coordinates: &[Coordinate],
    parameters: &[Parameter],
    inputs: &[InputDecl],
    problems: &mut Vec<Diagnostic>,
) -> DimensionScope {
    let mut scope = DimensionScope::default();
    scope.names.insert("t".into(), Some(Dimension::TIME));
    scope.names.insert("pi".into(), Some(Dimension::NONE));
    for c in coordinates {
        let d = parse(&c.unit, problems);
        scope.names.insert(c.name.clone(), d);
    }
    for p in parameters {
        let d = parse(&p.unit, problems);
        scope.names.insert(p.name.clone(), d);
    }
    for i in inputs {
        let arguments = i
            .arguments
            .iter()
            .map(|a| parse(&a.unit, problems))
            .collect();
        let value = parse(&i.decl.unit, problems);
        scope.inputs.insert(
            i.decl.name.to_string(),
            InputDimensions { arguments, value },
        );
    }
    scope
}

/// The declared names (coordinates, parameters, input functions and their
/// arguments) with and without a unit.
pub(super) struct UnitCoverage {
    /// How many declared names have a unit.
    pub with_unit: usize,
    /// The names without one, as listed in messages, with where each is declared.
    pub without_unit: Vec<(String, proc_macro2::Span)>,
}

impl UnitCoverage {
    /// Sorts the declarations by whether they have a unit.
    pub fn of(coordinates: &[Coordinate], parameters: &[Parameter], inputs: &[InputDecl]) -> Self {
        let mut coverage = UnitCoverage {
            with_unit: 0,
            without_unit: Vec::new(),
        };
        for c in coordinates {
            coverage.add(&c.unit, || format!("`{}`", c.name), c.span);
        }
        for p in parameters {
            coverage.add(&p.unit, || format!("`{}`", p.name), p.span);
        }
        for i in inputs {
            let name = &i.decl.name;
            coverage.add(&i.decl.unit, || format!("`{name}`"), name.span());
            for a in &i.arguments {
                let what = || format!("`{}` (argument of `{name}`)", a.name);
                coverage.add(&a.unit, what, a.name.span());
            }
        }
        coverage
    }

    fn add(
        &mut self,
        unit: &Option<UnitText>,
        name: impl FnOnce() -> String,
        span: proc_macro2::Span,
    ) {
        match unit {
            Some(_) => self.with_unit += 1,
            None => self.without_unit.push((name(), span)),
        }
    }

    /// Whether no name has a unit: then nothing is checked (a literal such
    /// as `1.0` would otherwise be a dimensionless energy).
    pub fn none(&self) -> bool {
        self.with_unit == 0
    }

    /// One warning when some names have units and others not: the terms
    /// that use the latter are not checked, which a user should know.
    pub fn warning(&self) -> Option<Diagnostic> {
        let (_, first) = self.without_unit.first()?;
        if self.none() {
            return None;
        }
        let names: Vec<&str> = self.without_unit.iter().map(|(n, _)| n.as_str()).collect();
        let message = format!(
            "units are declared for some names but not for {}: the terms that use {} are not checked for dimensions",
            names.join(", "),
            if names.len() == 1 { "it" } else { "them" }
        );
        Some(Diagnostic::new(*first, message).with_help(
            "declare a unit for each name (e.g. `k [N/m]`), or for none to switch the check off",
        ))
    }
}

/// Energy per unit of a coordinate of dimension `d` (a generalized force's
/// dimension). `None`, and so no check rather than a wrong one, only when an
/// exponent leaves exact 128-bit fractions, which takes an absurd declared
/// unit such as `(m^-9223372036854775807)^9223372036854775807` twice over.
fn per_unit_of(d: Dimension) -> Option<Dimension> {
    Dimension::ENERGY.checked_div(d)
}

/// Checks each parameter default that uses other names against the
/// parameter's unit (`m [kg] = l * 2` with `l [m]` is wrong); returns the
/// problems found. A default of numbers alone (`k [N/m] = 2.0 * 3e4`) is a
/// value in the declared unit, and `pi` counts as a number.
pub(super) fn defaults(scope: &DimensionScope, parameters: &[ParameterDecl]) -> Vec<Diagnostic> {
    let mut problems = Vec::new();
    for (k, p) in parameters.iter().enumerate() {
        let (Some(value), Some(unit)) = (&p.value, &p.decl.unit) else {
            continue;
        };
        let Ok(expected) = Dimension::parse(&unit.text) else {
            continue; // reported at the unit
        };
        let names = names_in(value);
        // A parameter from here on is an error of its own (declared below).
        let below = |n: &String| parameters[k..].iter().any(|q| q.decl.name == n);
        if names.is_empty() || names.iter().any(below) {
            continue;
        }
        let what = format!("the default of `{}`", p.decl.name);
        if let Err(d) = scope.check(value, Some(expected), &what) {
            problems.push(d);
        }
    }
    problems
}

/// The names `expr` uses but `pi` and the functions it calls (a name
/// followed by its parenthesized arguments, or a method).
fn names_in(expr: &syn::Expr) -> Vec<String> {
    use proc_macro2::{Delimiter, TokenTree};
    use quote::ToTokens;
    let mut names = Vec::new();
    let mut stack = vec![expr.to_token_stream().into_iter().peekable()];
    while let Some(tokens) = stack.last_mut() {
        let Some(token) = tokens.next() else {
            stack.pop();
            continue;
        };
        match token {
            TokenTree::Ident(name) => {
                let called = matches!(tokens.peek(), Some(TokenTree::Group(g)) if g.delimiter() == Delimiter::Parenthesis);
                if !called && name != "pi" {
                    names.push(name.to_string());
                }
            }
            TokenTree::Group(g) => stack.push(g.stream().into_iter().peekable()),
            TokenTree::Punct(_) | TokenTree::Literal(_) => {}
        }
    }
    names
}

/// Checks every statement; returns the problems found.
pub(super) fn check(
    scope: &mut DimensionScope,
    statements: &[Item],
    inputs: &[InputDecl],
    coordinates: &[Coordinate],
) -> Vec<Diagnostic> {
    let mut checker = Checker {
        scope,
        problems: Vec::new(),
    };
    for input in inputs {
        checker.derivatives(input);
    }
    for item in statements {
        if let Item::Let { name, value, .. } = item {
            checker.definition(name, value);
        }
    }
    let coordinate_dimensions: Vec<(String, Option<Dimension>)> = coordinates
        .iter()
        .map(|c| {
            (
                c.name.clone(),
                checker.scope.names.get(&c.name).copied().flatten(),
            )
        })
        .collect();
    for item in statements {
        checker.statement(item, &coordinate_dimensions);
    }
    checker.problems
}

/// The dimensions of the names, and the problems found so far.
struct Checker<'a> {
    scope: &'a mut DimensionScope,
    problems: Vec<Diagnostic>,
}

impl Checker<'_> {
    /// The dimension of a checked expression, or `None` with its problem
    /// recorded.
    fn take(&mut self, r: Result<Option<Dimension>, Diagnostic>) -> Option<Dimension> {
        r.map_err(|d| self.problems.push(d)).ok().flatten()
    }

    /// An input's declared derivatives: the value's dimension over the
    /// argument's.
    fn derivatives(&mut self, input: &InputDecl) {
        let dims = self.scope.inputs.get(&input.decl.name.to_string()).cloned();
        let Some(dims) = dims else { return };
        let mut local = DimensionScope {
            names: self.scope.names.clone(),
            inputs: self.scope.inputs.clone(),
            constants: self.scope.constants.clone(),
        };
        for (arg, d) in input.arguments.iter().zip(&dims.arguments) {
            local.names.insert(arg.name.to_string(), *d);
        }
        for (arg, expr) in &input.derivatives {
            let position = input.arguments.iter().position(|a| a.name == *arg);
            let expected = position
                .and_then(|p| dims.arguments[p])
                .zip(dims.value)
                .and_then(|(a, v)| v.checked_div(a));
            let what = format!(
                "the derivative of `{}` with respect to `{arg}`",
                input.decl.name
            );
            self.take(local.check(expr, expected, &what));
        }
    }

    /// `let name = value;`: its dimension, and its value when constant.
    fn definition(&mut self, name: &syn::Ident, value: &syn::Expr) {
        let d = self.take(self.scope.infer(value));
        self.scope.names.insert(name.to_string(), d);
        if let Ok(Some(c)) = super::constant::evaluate(value, &self.scope.constants) {
            self.scope.constants.insert(name.to_string(), c);
        }
    }

    /// `output name [unit] = value;`: the value against the declared unit.
    fn output(&mut self, output: &OutputDecl) {
        let Some(expected) = parse(&output.decl.unit, &mut self.problems) else {
            return;
        };
        let what = format!("the output `{}`", output.decl.name);
        self.take(self.scope.check(&output.value, Some(expected), &what));
    }

    /// An energy or force statement against the dimension it must have
    /// (`coordinates`: each coordinate's name and dimension).
    fn statement(&mut self, item: &Item, coordinates: &[(String, Option<Dimension>)]) {
        match item {
            Item::Energy { kind, value, .. } => {
                let expected = match kind {
                    EnergyKind::Kinetic | EnergyKind::Potential => Dimension::ENERGY,
                    EnergyKind::Dissipation => Dimension::POWER,
                };
                let what = format!("the {}", kind.description());
                self.take(self.scope.check(value, Some(expected), &what));
            }
            Item::GeneralizedForce {
                coordinate, value, ..
            } => {
                let name = coordinate.to_string();
                let expected = coordinates
                    .iter()
                    .find(|(n, _)| *n == name)
                    .and_then(|(_, d)| *d)
                    .and_then(per_unit_of);
                let what = format!("the generalized force on `{coordinate}`");
                self.take(self.scope.check(value, expected, &what));
            }
            Item::PointForce {
                point, components, ..
            } => {
                for (p, f) in point.iter().zip(components) {
                    let position = self.take(self.scope.infer(p));
                    let expected = position.and_then(per_unit_of);
                    let what = "this force component (× its point coordinate must be an energy)";
                    self.take(self.scope.check(f, expected, what));
                }
            }
            Item::Output(output) => self.output(output),
            Item::Constraint(constraint) => {
                // Any dimension will do; its terms must agree.
                self.take(self.scope.infer(&constraint.value));
            }
            Item::Let { .. }
            | Item::Jacobians { .. }
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
}
