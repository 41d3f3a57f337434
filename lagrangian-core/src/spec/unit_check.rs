//! The dimensional checks of a spec: T and V are energies, D a power, a
//! generalized force times its coordinate's rate a power, a point force
//! times its point's displacement an energy, a declared derivative the
//! input's value over its argument.

use super::ast::{EnergyKind, InputDecl, Item, UnitText};
use super::dimensions::{DimensionScope, InputDimensions};
use super::{Coordinate, Parameter};
use crate::diagnostic::Diagnostic;
use crate::units::Dimension;

/// The dimension of a declared unit, or a diagnostic at the unit.
fn parse(unit: &Option<UnitText>, problems: &mut Vec<Diagnostic>) -> Option<Dimension> {
    let unit = unit.as_ref()?;
    match Dimension::parse(&unit.text) {
        Ok(d) => Some(d),
        Err(message) => {
            problems.push(Diagnostic::new(unit.span, message));
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

/// Energy per unit of a coordinate of dimension `d` (a generalized force's
/// dimension). `None`, and so no check rather than a wrong one, only when an
/// exponent leaves exact 128-bit fractions, which takes an absurd declared
/// unit such as `(m^-9223372036854775807)^9223372036854775807` twice over.
fn per_unit_of(d: Dimension) -> Option<Dimension> {
    Dimension::ENERGY.checked_div(d)
}

/// Checks every statement; returns the problems found.
pub(super) fn check(
    scope: &mut DimensionScope,
    statements: &[Item],
    inputs: &[InputDecl],
    coordinates: &[Coordinate],
) -> Vec<Diagnostic> {
    let mut problems = Vec::new();
    let mut take =
        |r: Result<Option<Dimension>, Diagnostic>| r.map_err(|d| problems.push(d)).ok().flatten();
    // Declared derivatives: value / argument.
    for input in inputs {
        let dims = scope.inputs.get(&input.decl.name.to_string()).cloned();
        let Some(dims) = dims else { continue };
        let mut local = DimensionScope {
            names: scope.names.clone(),
            inputs: scope.inputs.clone(),
            constants: scope.constants.clone(),
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
            take(local.check(
                expr,
                expected,
                &format!(
                    "the derivative of `{}` with respect to `{arg}`",
                    input.decl.name
                ),
            ));
        }
    }
    let coordinate_dimensions: Vec<(String, Option<Dimension>)> = coordinates
        .iter()
        .map(|c| (c.name.clone(), scope.names.get(&c.name).copied().flatten()))
        .collect();
    let coordinate_dimension = |name: &str| {
        coordinate_dimensions
            .iter()
            .find(|(n, _)| n == name)
            .and_then(|(_, d)| *d)
    };
    for item in statements {
        if let Item::Let { name, value } = item {
            let d = take(scope.infer(value));
            scope.names.insert(name.to_string(), d);
            if let Ok(Some(c)) = super::constant::evaluate(value, &scope.constants) {
                scope.constants.insert(name.to_string(), c);
            }
        }
    }
    for item in statements {
        match item {
            Item::Energy { kind, value, .. } => {
                let expected = match kind {
                    EnergyKind::Kinetic | EnergyKind::Potential => Dimension::ENERGY,
                    EnergyKind::Dissipation => Dimension::POWER,
                };
                take(scope.check(
                    value,
                    Some(expected),
                    &format!("the {}", kind.description()),
                ));
            }
            Item::GeneralizedForce {
                coordinate, value, ..
            } => {
                let expected = coordinate_dimension(&coordinate.to_string()).and_then(per_unit_of);
                take(scope.check(
                    value,
                    expected,
                    &format!("the generalized force on `{coordinate}`"),
                ));
            }
            Item::PointForce {
                point, components, ..
            } => {
                for (p, f) in point.iter().zip(components) {
                    let position = take(scope.infer(p));
                    let expected = position.and_then(per_unit_of);
                    take(scope.check(
                        f,
                        expected,
                        "this force component (× its point coordinate must be an energy)",
                    ));
                }
            }
            _ => {}
        }
    }
    problems
}
