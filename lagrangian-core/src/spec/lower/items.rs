//! Item collection: the spec's items sorted by kind, and its header.

use super::{Problems, validate};
use crate::diagnostic::{Diagnostic, SpecErrors};
use crate::spec::ast::{Declaration, InputDecl, Item, ParameterDecl, SpecAst};
use proc_macro2::Span;
use syn::Ident;

/// The items of a spec sorted by kind; each list keeps the source order.
pub(super) struct Items {
    /// `model Name;` with its doc lines, the first time the model is named.
    pub model: Option<(Ident, Vec<String>)>,
    /// `//!` lines at the top of a spec file.
    pub inner_doc: Vec<String>,
    /// The first `coordinates` keyword, where a missing coordinate is reported.
    pub coordinates_keyword: Option<Span>,
    /// Every `coordinates` block's declarations, in order.
    pub coordinates: Vec<Declaration>,
    pub parameters: Vec<ParameterDecl>,
    pub inputs: Vec<InputDecl>,
    /// Everything else: `let`s, energies, forces, `jacobians;`, `hand_derived`.
    pub statements: Vec<Item>,
}

impl Items {
    /// Sorts `ast`'s items; a model named twice is reported in `problems`.
    pub fn collect(ast: SpecAst, problems: &mut Problems) -> Items {
        let mut items = Items {
            model: None,
            inner_doc: ast.inner_doc,
            coordinates_keyword: None,
            coordinates: Vec::new(),
            parameters: Vec::new(),
            inputs: Vec::new(),
            statements: Vec::new(),
        };
        for item in ast.items {
            match item {
                Item::Model { doc, name } => {
                    let first = items.model.as_ref().map(|(first, _)| first);
                    match validate::model_named_twice(first, &name) {
                        Some(d) => problems.push(d),
                        None => items.model = Some((name, doc)),
                    }
                }
                Item::Coordinates { keyword, decls } => {
                    items.coordinates_keyword.get_or_insert(keyword);
                    items.coordinates.extend(decls);
                }
                Item::Parameters { decls, .. } => items.parameters.extend(decls),
                Item::Inputs { decls, .. } => items.inputs.extend(decls),
                other @ (Item::Let { .. }
                | Item::Energy { .. }
                | Item::GeneralizedForce { .. }
                | Item::PointForce { .. }
                | Item::Output(_)
                | Item::Constraint(_)
                | Item::Jacobians { .. }
                | Item::HandDerived(_)
                | Item::For { .. }
                | Item::PartDef(_)
                | Item::PartInstance(_)) => items.statements.push(other),
            }
        }
        items
    }
}

/// The model's name and documentation.
pub(super) struct Header {
    pub name: Ident,
    /// The file's `//!` lines, then the `///` lines on `model Name;`.
    pub doc: Vec<String>,
}

impl Header {
    /// The header of a spec that names its model and declares a coordinate.
    /// Without either nothing else can be lowered, so the error is the only
    /// one reported.
    pub fn of(items: &Items) -> Result<Header, SpecErrors> {
        let Some((name, doc)) = &items.model else {
            return Err(
                Diagnostic::new(Span::call_site(), "the spec does not name its model")
                    .with_help("start the spec with `model Name;`")
                    .into(),
            );
        };
        if items.coordinates.is_empty() {
            let span = items.coordinates_keyword.unwrap_or(name.span());
            return Err(
                Diagnostic::new(span, "the model declares no generalized coordinates")
                    .with_help("add `coordinates { x, theta }` with at least one coordinate")
                    .into(),
            );
        }
        Ok(Header {
            name: name.clone(),
            doc: items.inner_doc.iter().chain(doc).cloned().collect(),
        })
    }
}
