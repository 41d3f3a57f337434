//! The names a spec declares, read from its syntax alone: what the macro
//! needs to stand in for a model whose spec has errors.

use super::ast::Item;
use proc_macro2::TokenStream;

/// The declared names of a spec that parses, each once, in order.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub(crate) struct Outline {
    /// The model's name.
    pub name: String,
    /// The coordinates.
    pub coordinates: Vec<String>,
    /// The parameters.
    pub parameters: Vec<String>,
    /// The input functions.
    pub inputs: Vec<String>,
}

impl Outline {
    /// The outline of `tokens`; `None` when they do not parse as a spec or
    /// name no model.
    pub(crate) fn of(tokens: TokenStream) -> Option<Outline> {
        let (ast, _) = super::expanded(tokens).ok()?;
        let mut outline = Outline::default();
        for item in &ast.items {
            match item {
                // The first, as lowering takes it (a second is an error).
                Item::Model { name, .. } if outline.name.is_empty() => {
                    outline.name = name.to_string()
                }
                Item::Model { .. } => {}
                Item::Coordinates { decls, .. } => {
                    push_new(&mut outline.coordinates, decls.iter().map(|d| &d.name))
                }
                Item::Parameters { decls } => {
                    push_new(&mut outline.parameters, decls.iter().map(|d| &d.decl.name))
                }
                Item::Inputs { decls } => {
                    push_new(&mut outline.inputs, decls.iter().map(|d| &d.decl.name))
                }
                Item::Let { .. }
                | Item::Energy { .. }
                | Item::GeneralizedForce { .. }
                | Item::PointForce { .. }
                | Item::Output(_)
                | Item::Constraint(_)
                | Item::Jacobians { .. }
                | Item::HandDerived(_)
                | Item::For { .. }
                | Item::PartDef(_)
                | Item::PartInstance(_) => {}
            }
        }
        (!outline.name.is_empty()).then_some(outline)
    }
}

/// Appends the names not already in `list`.
fn push_new<'a>(list: &mut Vec<String>, names: impl Iterator<Item = &'a syn::Ident>) {
    for name in names {
        let name = super::names::display_name(&name.to_string()).into_owned();
        if !list.contains(&name) {
            list.push(name);
        }
    }
}
