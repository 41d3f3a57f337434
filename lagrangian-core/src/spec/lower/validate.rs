//! The checks of names and of things given twice. Each returns the
//! diagnostic of a failed check, for the phase that runs it to record.

use crate::diagnostic::Diagnostic;
use crate::spec::ast::{EnergyKind, HandSection, InputDecl};
use crate::spec::expression::Scope;
use crate::spec::{RESERVED_NAMES, Statement};
use proc_macro2::Span;
use syn::Ident;

/// A second `model Name;` (`first` is the name given first, if any).
pub(super) fn model_named_twice(first: Option<&Ident>, name: &Ident) -> Option<Diagnostic> {
    let first = first?;
    Some(
        Diagnostic::new(name.span(), "the model is named twice")
            .with_note("first named here", first.span()),
    )
}

/// A declaration of one of the names the spec language gives a meaning of
/// its own ([`RESERVED_NAMES`]).
pub(super) fn reserved_name(ident: &Ident) -> Option<Diagnostic> {
    let name = ident.to_string();
    let reserved = RESERVED_NAMES.iter().find(|r| **r == name)?;
    Some(Diagnostic::new(
        ident.span(),
        format!("`{reserved}` is reserved by the spec language and cannot be declared"),
    ))
}

/// A declaration of a name already in `scope`.
pub(super) fn duplicate_name(scope: &Scope, ident: &Ident) -> Option<Diagnostic> {
    let name = ident.to_string();
    let (_, first) = scope.names.get(&name)?;
    Some(
        Diagnostic::new(ident.span(), format!("`{name}` is declared twice"))
            .with_note("first declared here", *first),
    )
}

/// A name that becomes a trajectory column (a coordinate, an input, an
/// output) and is one of the columns every trajectory has
/// ([`lagrangian_runtime::names::builtin_column`]): the trajectory would have
/// two columns of that name.
pub(super) fn builtin_column_name(
    (name, span): (&str, Span),
    what: &str,
    coordinates: &[&str],
) -> Option<Diagnostic> {
    if RESERVED_NAMES.contains(&name) {
        return None; // refused as reserved
    }
    let column = lagrangian_runtime::names::builtin_column(name, coordinates.iter().copied())?;
    Some(
        Diagnostic::new(
            span,
            format!("the {what} `{name}` has the name of a built-in trajectory column, {column}"),
        )
        .with_help("every trajectory has the columns t, each coordinate q with q_dot and q_ddot, kinetic_energy, potential_energy, dissipated_energy and external_work: choose another name"),
    )
}

/// Every formal argument of an input function declared again after its first
/// declaration, in order.
pub(super) fn duplicate_arguments(decl: &InputDecl) -> Vec<Diagnostic> {
    let arguments = &decl.arguments;
    let mut problems = Vec::new();
    for (k, a) in arguments.iter().enumerate() {
        if let Some(first) = arguments[..k].iter().find(|b| b.name == a.name) {
            problems.push(
                Diagnostic::new(
                    a.name.span(),
                    format!("argument `{}` is declared twice", a.name),
                )
                .with_note("first declared here", first.name.span()),
            );
        }
    }
    problems
}

/// A second derivative `d(arg) = …` of an input function with respect to
/// the same argument (`first`: where the first one is declared, if any).
pub(super) fn derivative_declared_twice(arg: &Ident, first: Option<Span>) -> Option<Diagnostic> {
    let first = first?;
    Some(
        Diagnostic::new(
            arg.span(),
            format!("the derivative with respect to `{arg}` is declared twice"),
        )
        .with_note("first declared here", first),
    )
}

/// A second kinetic energy, potential energy or dissipation function
/// (`first`: the one already given, if any).
pub(super) fn energy_given_twice(
    kind: EnergyKind,
    keyword: Span,
    first: Option<&Statement>,
) -> Option<Diagnostic> {
    let first = first?;
    Some(
        Diagnostic::new(
            keyword,
            format!("the {} is given twice", kind.description()),
        )
        .with_note("first given here", first.span)
        .with_help("combine the terms into one expression (a `let` can name the parts)"),
    )
}

/// A second `hand_derived` section (`lowered`: whether an earlier section
/// was lowered without error).
pub(super) fn second_hand_section(lowered: bool, section: &HandSection) -> Option<Diagnostic> {
    lowered.then(|| {
        Diagnostic::new(
            section.keyword,
            "only one `hand_derived` section is allowed",
        )
    })
}
