//! Reusable parts — `part spring_damper(a [m], b [m]) { … }` and its
//! instances, `part front = spring_damper(x[1], x[2]) { k = 2e5 };` —
//! written out into the items each instance stands for, after families are
//! expanded and before names are resolved.
//!
//! Name `k` of instance `front` is `front⁀k` while the spec is lowered and
//! `front.k` to users ([`super::names`]); a port is replaced by the
//! expression the instance gives it; the energies of every instance add to
//! the model's. Parts the spec does not define come from the standard
//! library, `parts.lpm`, its tokens placed at the instance.

use super::ast::*;
use super::names::MEMBER;
use crate::diagnostic::{Diagnostic, SpanRange, SpecErrors};
use proc_macro2::{Group, Ident, Span, TokenStream, TokenTree};
use rustc_hash::{FxHashMap, FxHashSet};
use syn::visit_mut::{self, VisitMut};
use syn::{Expr, Token};

/// The standard library of parts.
const LIBRARY: &str = include_str!("parts.lpm");
/// The most parts one instance may nest (a part instantiating a part …).
const MAX_DEPTH: usize = 16;
/// The most instances a spec may expand into (parts nested in parts
/// multiply).
const MAX_INSTANCES: usize = 100_000;

/// Where the instances of the spec's own parts are, to point at the
/// instance from a problem found later inside a part.
pub(super) struct Instances {
    /// `(the part's first and last token, the note)`, per instance.
    places: Vec<(SpanRange, String, SpanRange)>,
}

/// The spec `ast` with its parts' instances written out; every problem
/// found, each at its span.
pub(super) fn expand(ast: SpecAst) -> Result<(SpecAst, Instances), SpecErrors> {
    let mut parts = Parts::new(&ast.items);
    let mut items = Vec::new();
    for item in ast.items {
        match item {
            Item::PartDef(_) => {}
            Item::PartInstance(instance) => {
                parts.instantiate(instance, &mut Vec::new(), &mut items)
            }
            other => items.push(other),
        }
    }
    parts.add_energies(&mut items);
    parts.spelling_clashes(&items);
    match parts.problems.is_empty() {
        true => Ok((
            SpecAst {
                inner_doc: ast.inner_doc,
                items,
            },
            Instances {
                places: parts.places,
            },
        )),
        false => Err(SpecErrors {
            diagnostics: parts.problems,
        }),
    }
}

impl Instances {
    /// `errors` with a note at the instance on each problem inside one of
    /// the spec's own parts (the first instance, where there are several).
    pub(super) fn noted(&self, mut errors: SpecErrors) -> SpecErrors {
        for d in &mut errors.diagnostics {
            let place = (self.places.iter()).find(|(part, ..)| within(d.span, *part));
            if let (None, Some((_, note, at))) = (&d.note, place) {
                d.note = Some(Box::new((note.clone(), *at)));
            }
        }
        errors
    }
}

/// Whether `span` lies in `range` (where spans have lines: not inside a
/// procedural macro).
fn within(span: SpanRange, range: SpanRange) -> bool {
    let (start, low, high) = (span.start.start(), range.start.start(), range.end.end());
    low.line > 0
        && (low.line, low.column) <= (start.line, start.column)
        && (start.line, start.column) <= (high.line, high.column)
}

struct Parts {
    /// The spec's own parts, by name.
    defined: FxHashMap<String, PartDef>,
    /// The tokens of the standard library's parts, by name (placed at the
    /// instance for each instance).
    library: FxHashMap<String, TokenStream>,
    /// The unit of each coordinate the model declares itself.
    coordinate_units: FxHashMap<String, Option<UnitText>>,
    /// `T`, `V`, `D` of the instances, by kind, with the first's keyword.
    energies: [(Vec<Expr>, Option<Span>); 3],
    /// Every instance's name, where it is given.
    instances: FxHashMap<String, Span>,
    places: Vec<(SpanRange, String, SpanRange)>,
    problems: Vec<Diagnostic>,
}

/// What a part's names become in one instance.
struct Scope {
    /// The instance's name (`front`, `car‿2`), the prefix of its names.
    prefix: String,
    /// The names the part declares.
    locals: FxHashSet<String>,
    /// Each port's expression in the instance.
    ports: FxHashMap<String, Expr>,
    /// `` `front`, an instance of `spring_damper` ``, for messages.
    what: String,
}

impl Parts {
    fn new(items: &[Item]) -> Parts {
        let mut parts = Parts {
            defined: FxHashMap::default(),
            library: FxHashMap::default(),
            coordinate_units: FxHashMap::default(),
            energies: Default::default(),
            instances: FxHashMap::default(),
            places: Vec::new(),
            problems: Vec::new(),
        };
        parts.library = library_parts();
        for item in items {
            match item {
                Item::PartDef(def) => parts.define(def),
                Item::Coordinates { decls, .. } => {
                    for d in decls {
                        (parts.coordinate_units).insert(d.name.to_string(), d.unit.clone());
                    }
                }
                _ => {}
            }
        }
        parts
    }

    fn define(&mut self, def: &PartDef) {
        let name = def.name.to_string();
        if let Some(first) = self.defined.get(&name) {
            let why = format!("part `{name}` is defined twice");
            let note = Diagnostic::new(def.name.span(), why)
                .with_note("first defined here", first.name.span());
            self.problems.push(note);
            return;
        }
        self.defined.insert(name, def.clone());
    }

    /// The part `name`: the spec's own, else the library's with its tokens
    /// at `at`.
    fn definition(&mut self, name: &Ident, at: Span) -> Option<(PartDef, bool)> {
        if let Some(def) = self.defined.get(&name.to_string()) {
            return Some((def.clone(), true));
        }
        if let Some(tokens) = self.library.get(&name.to_string()) {
            let mut parts = parts_of(respanned(tokens.clone(), at));
            return parts.remove(&name.to_string()).map(|d| (d, false));
        }
        let mut known: Vec<&str> = (self.defined.keys())
            .chain(self.library.keys())
            .map(String::as_str)
            .collect();
        known.sort_unstable();
        let why = format!("no part `{name}` is defined");
        let help = format!("the parts here are {}", quoted(&known));
        self.problems
            .push(Diagnostic::new(name.span(), why).with_help(help));
        None
    }

    /// The items `instance` stands for, appended to `out`; `within` holds
    /// the parts being instantiated around it.
    fn instantiate(
        &mut self,
        instance: PartInstance,
        within: &mut Vec<String>,
        out: &mut Vec<Item>,
    ) {
        let name = instance.name.to_string();
        if self.instances.len() >= MAX_INSTANCES {
            if self.instances.len() == MAX_INSTANCES {
                let why = format!("the parts of this spec expand past {MAX_INSTANCES} instances");
                self.problems
                    .push(Diagnostic::new(instance.name.span(), why));
                self.instances.insert(String::new(), instance.name.span());
            }
            return;
        }
        if let Some(first) = self.instances.get(&name) {
            let why = format!(
                "`{}` names two instances",
                super::names::display_name(&name)
            );
            let d =
                Diagnostic::new(instance.name.span(), why).with_note("the first is here", *first);
            self.problems.push(d);
            return;
        }
        self.instances.insert(name, instance.name.span());
        let Some((def, own)) = self.definition(&instance.part, instance.part.span()) else {
            return;
        };
        let part = def.name.to_string();
        if within.contains(&part) || within.len() >= MAX_DEPTH {
            within.push(part);
            let why = format!(
                "part `{}` contains itself: {}",
                within[0],
                within.join(" → ")
            );
            self.problems
                .push(Diagnostic::new(instance.part.span(), why));
            within.pop();
            return;
        }
        let Some(scope) = self.scope(&instance, &def) else {
            return;
        };
        if own {
            let body = part_range(&def);
            let at =
                SpanRange::from(instance.name.span()).to(SpanRange::from(instance.arguments_span));
            self.places.push((body, format!("in {}", scope.what), at));
        }
        let mut settings: FxHashMap<String, Expr> = FxHashMap::default();
        for (name, value) in &instance.settings {
            settings.insert(name.to_string(), value.clone());
        }
        within.push(part);
        for item in def.items {
            self.member(item, &scope, &settings, within, out);
        }
        within.pop();
    }

    /// What `def`'s names become in `instance`, once its ports and settings
    /// are checked.
    fn scope(&mut self, instance: &PartInstance, def: &PartDef) -> Option<Scope> {
        let what = format!(
            "`{}`, an instance of `{}`",
            super::names::display_name(&instance.name.to_string()),
            def.name
        );
        let ports: Vec<String> = def.ports.iter().map(port_text).collect();
        if instance.arguments.len() != def.ports.len() {
            let why = format!(
                "part `{}` has {} port{} ({}), but {} {} given",
                def.name,
                ports.len(),
                if ports.len() == 1 { "" } else { "s" },
                ports.join(", "),
                instance.arguments.len(),
                if instance.arguments.len() == 1 {
                    "is"
                } else {
                    "are"
                },
            );
            let help =
                "give one coordinate (or an expression of coordinates) for each port, in order";
            let d = Diagnostic::new(instance.arguments_span, why).with_help(help);
            self.problems.push(d);
            return None;
        }
        for (port, argument) in def.ports.iter().zip(&instance.arguments) {
            self.check_port_unit(port, argument, def);
        }
        let locals = declared_names(&def.items);
        let parameters = parameter_names(&def.items);
        let mut given = FxHashSet::default();
        for (name, _) in &instance.settings {
            let text = name.to_string();
            if !parameters.contains(&text) {
                let why = format!("part `{}` has no parameter `{text}`", def.name);
                let help = match parameters.is_empty() {
                    true => "it has no parameters".to_string(),
                    false => format!("its parameters are {}", quoted(&sorted(&parameters))),
                };
                self.problems
                    .push(Diagnostic::new(name.span(), why).with_help(help));
            } else if !given.insert(text.clone()) {
                let why = format!("`{text}` is given twice");
                self.problems.push(Diagnostic::new(name.span(), why));
            }
        }
        let ports = (def.ports.iter().zip(&instance.arguments))
            .map(|(p, a)| (p.name.to_string(), a.clone()))
            .collect();
        Some(Scope {
            prefix: instance.name.to_string(),
            locals,
            ports,
            what,
        })
    }

    /// A port of a unit given a coordinate of another dimension is an
    /// error at the argument.
    fn check_port_unit(&mut self, port: &Declaration, argument: &Expr, def: &PartDef) {
        let Some(name) = path_ident(argument) else {
            return;
        };
        let Some(Some(unit)) = self.coordinate_units.get(&name.to_string()) else {
            return;
        };
        let Some(port_unit) = &port.unit else {
            return;
        };
        let dimension = |u: &UnitText| crate::units::Dimension::parse(&u.text).ok();
        if dimension(unit) != dimension(port_unit) {
            let why = format!(
                "port `{}` of part `{}` is in [{}], but `{}` is in [{}]",
                port.name,
                def.name,
                port_unit.text,
                super::names::display_name(&name.to_string()),
                unit.text
            );
            self.problems
                .push(Diagnostic::new(SpanRange::of(argument), why));
        }
    }

    /// One item of a part, as `scope` makes it, appended to `out`.
    fn member(
        &mut self,
        item: Item,
        scope: &Scope,
        settings: &FxHashMap<String, Expr>,
        within: &mut Vec<String>,
        out: &mut Vec<Item>,
    ) {
        let mut rename = Rename {
            scope,
            shadowed: Vec::new(),
        };
        match item {
            Item::Coordinates { keyword, mut decls } => {
                decls
                    .iter_mut()
                    .for_each(|d| d.name = scope.member(&d.name));
                out.push(Item::Coordinates { keyword, decls });
            }
            Item::Parameters { mut decls } => {
                for d in &mut decls {
                    if let Some(value) = settings.get(&d.decl.name.to_string()) {
                        d.value = Some(value.clone());
                    }
                    d.decl.name = scope.member(&d.decl.name);
                }
                out.push(Item::Parameters { decls });
            }
            Item::Inputs { mut decls } => {
                for d in &mut decls {
                    d.decl.name = scope.member(&d.decl.name);
                    rename.shadowed = d.arguments.iter().map(|a| a.name.to_string()).collect();
                    d.derivatives
                        .iter_mut()
                        .for_each(|(_, e)| rename.visit_expr_mut(e));
                }
                out.push(Item::Inputs { decls });
            }
            Item::Let { name, value, .. } => out.push(Item::Let {
                name: scope.member(&name),
                subscript: None,
                value: rename.expr(value),
            }),
            Item::Energy {
                kind,
                keyword,
                value,
            } => {
                let (terms, first) = &mut self.energies[kind as usize];
                terms.push(rename.expr(value));
                first.get_or_insert(keyword);
            }
            Item::GeneralizedForce {
                keyword,
                coordinate,
                value,
                ..
            } => {
                let Some(coordinate) = self.force_target(&coordinate, scope) else {
                    return;
                };
                out.push(Item::GeneralizedForce {
                    keyword,
                    coordinate,
                    subscript: None,
                    value: rename.expr(value),
                });
            }
            Item::PointForce {
                point,
                point_span,
                components,
                components_span,
            } => out.push(Item::PointForce {
                point: point.into_iter().map(|e| rename.expr(e)).collect(),
                point_span,
                components: components.into_iter().map(|e| rename.expr(e)).collect(),
                components_span,
            }),
            Item::Output(mut output) => {
                output.decl.name = scope.member(&output.decl.name);
                output.value = rename.expr(output.value);
                out.push(Item::Output(output));
            }
            Item::Constraint(mut constraint) => {
                constraint.name = scope.member(&constraint.name);
                constraint.value = rename.expr(constraint.value);
                out.push(Item::Constraint(constraint));
            }
            Item::PartInstance(mut inner) => {
                inner.name = scope.member(&inner.name);
                let arguments = std::mem::take(&mut inner.arguments);
                inner.arguments = arguments.into_iter().map(|a| rename.expr(a)).collect();
                for (_, value) in &mut inner.settings {
                    rename.visit_expr_mut(value);
                }
                self.instantiate(inner, within, out);
            }
            Item::PartDef(def) => {
                let why = format!("part `{}` is defined inside another part", def.name);
                let help = "define parts at the top level of the spec";
                self.problems
                    .push(Diagnostic::new(def.name.span(), why).with_help(help));
            }
            Item::Model { name, .. } => self.not_in_part(name.span(), "`model`", scope),
            Item::Jacobians { keyword } => self.not_in_part(keyword, "`jacobians;`", scope),
            Item::HandDerived(section) => {
                self.not_in_part(section.keyword, "`hand_derived`", scope)
            }
            // Families expanded every loop before.
            Item::For { .. } => {}
        }
    }

    fn not_in_part(&mut self, at: Span, what: &str, scope: &Scope) {
        let why = format!(
            "{what} belongs to the model, not to a part ({})",
            scope.what
        );
        self.problems.push(Diagnostic::new(at, why));
    }

    /// The coordinate `force q = …;` acts on in the instance: a port's
    /// coordinate, or the part's own coordinate.
    fn force_target(&mut self, coordinate: &Ident, scope: &Scope) -> Option<Ident> {
        let name = coordinate.to_string();
        let Some(argument) = scope.ports.get(&name) else {
            return Some(match scope.locals.contains(&name) {
                true => scope.member(coordinate),
                false => coordinate.clone(),
            });
        };
        if let Some(target) = path_ident(argument) {
            return Some(target.clone());
        }
        let why = format!(
            "port `{name}` takes a coordinate here: the part applies `force {name} = …;` to it"
        );
        let help = "give a coordinate, or write the part's force as `force at (…) = (…);`";
        let d = Diagnostic::new(SpanRange::of(argument), why)
            .with_help(help)
            .with_note(format!("in {}", scope.what), coordinate.span());
        self.problems.push(d);
        None
    }

    /// The instances' energies added to the model's own (the first of each
    /// kind, a second being the model's error to report).
    fn add_energies(&mut self, items: &mut Vec<Item>) {
        for (kind, (terms, keyword)) in std::mem::take(&mut self.energies).into_iter().enumerate() {
            let Some(keyword) = keyword else {
                continue;
            };
            let kind = [
                EnergyKind::Kinetic,
                EnergyKind::Potential,
                EnergyKind::Dissipation,
            ][kind];
            let own = items.iter_mut().find_map(|item| match item {
                Item::Energy { kind: k, value, .. } if *k == kind => Some(value),
                _ => None,
            });
            match own {
                Some(value) => *value = sum(std::iter::once(value.clone()).chain(terms)),
                None => items.push(Item::Energy {
                    kind,
                    keyword,
                    value: sum(terms),
                }),
            }
        }
    }
}

impl Parts {
    /// A name of an instance that generated code spells as another name
    /// of the model (`front.k` and `front_k` are both `front_k`) is an
    /// error at the later one.
    fn spelling_clashes(&mut self, items: &[Item]) {
        let mut spelled: FxHashMap<String, String> = FxHashMap::default();
        for name in declared_idents(items) {
            let text = super::names::display_name(&name.to_string()).into_owned();
            let spelling = text.replace('[', "_").replace(']', "").replace('.', "_");
            match spelled.get(&spelling) {
                Some(other) if *other != text && (text.contains('.') || other.contains('.')) => {
                    let why =
                        format!("`{text}` and `{other}` are both `{spelling}` in generated code");
                    let help = "rename one of them";
                    self.problems
                        .push(Diagnostic::new(name.span(), why).with_help(help));
                }
                Some(_) => {}
                None => _ = spelled.insert(spelling, text),
            }
        }
    }
}

impl Scope {
    /// `name` of the part as this instance names it: `front⁀k`.
    fn member(&self, name: &Ident) -> Ident {
        Ident::new(&format!("{}{MEMBER}{name}", self.prefix), name.span())
    }
}

/// The renaming of a part's expressions in one instance.
struct Rename<'a> {
    scope: &'a Scope,
    /// Names that mean something else here (an input's arguments in its
    /// derivatives).
    shadowed: Vec<String>,
}

impl Rename<'_> {
    fn expr(&mut self, mut expr: Expr) -> Expr {
        self.visit_expr_mut(&mut expr);
        expr
    }
}

impl VisitMut for Rename<'_> {
    fn visit_expr_mut(&mut self, expr: &mut Expr) {
        let Some(ident) = path_ident(expr).cloned() else {
            return visit_mut::visit_expr_mut(self, expr);
        };
        let name = ident.to_string();
        if self.shadowed.contains(&name) {
            return;
        }
        if let Some(argument) = self.scope.ports.get(&name) {
            *expr = match argument {
                Expr::Path(_) | Expr::Lit(_) | Expr::Paren(_) => argument.clone(),
                other => Expr::Paren(syn::ExprParen {
                    attrs: Vec::new(),
                    paren_token: syn::token::Paren(ident.span()),
                    expr: Box::new(other.clone()),
                }),
            };
        } else if self.scope.locals.contains(&name) {
            let member = self.scope.member(&ident);
            *expr = syn::parse_quote_spanned!(ident.span()=> #member);
        }
    }
}

/// `expr` if it is a plain name.
fn path_ident(expr: &Expr) -> Option<&Ident> {
    match expr {
        Expr::Path(p) if p.qself.is_none() => p.path.get_ident(),
        _ => None,
    }
}

/// `terms` added, each in parentheses.
fn sum(terms: impl IntoIterator<Item = Expr>) -> Expr {
    let mut total: Option<Expr> = None;
    for term in terms {
        let span = SpanRange::of(&term).start;
        let term = Expr::Paren(syn::ExprParen {
            attrs: Vec::new(),
            paren_token: syn::token::Paren(span),
            expr: Box::new(term),
        });
        total = Some(match total {
            None => term,
            Some(left) => Expr::Binary(syn::ExprBinary {
                attrs: Vec::new(),
                left: Box::new(left),
                op: syn::BinOp::Add(Token![+](span)),
                right: Box::new(term),
            }),
        });
    }
    total.unwrap_or_else(|| syn::parse_quote!(0.0))
}

/// The names a part's items declare (coordinates, parameters, inputs,
/// `let`s, outputs, constraints and instances).
fn declared_names(items: &[Item]) -> FxHashSet<String> {
    declared_idents(items).map(|i| i.to_string()).collect()
}

fn declared_idents(items: &[Item]) -> impl Iterator<Item = &Ident> {
    items
        .iter()
        .flat_map(|item| -> Box<dyn Iterator<Item = &Ident> + '_> {
            match item {
                Item::Coordinates { decls, .. } => Box::new(decls.iter().map(|d| &d.name)),
                Item::Parameters { decls } => Box::new(decls.iter().map(|d| &d.decl.name)),
                Item::Inputs { decls } => Box::new(decls.iter().map(|d| &d.decl.name)),
                Item::Let { name, .. } => Box::new(std::iter::once(name)),
                Item::Output(o) => Box::new(std::iter::once(&o.decl.name)),
                Item::Constraint(c) => Box::new(std::iter::once(&c.name)),
                Item::PartInstance(p) => Box::new(std::iter::once(&p.name)),
                _ => Box::new(std::iter::empty()),
            }
        })
}

fn parameter_names(items: &[Item]) -> FxHashSet<String> {
    let mut names = FxHashSet::default();
    for item in items {
        if let Item::Parameters { decls } = item {
            names.extend(decls.iter().map(|d| d.decl.name.to_string()));
        }
    }
    names
}

/// A port as a message names it: `a [m]`.
fn port_text(port: &Declaration) -> String {
    match &port.unit {
        Some(unit) => format!("{} [{}]", port.name, unit.text),
        None => port.name.to_string(),
    }
}

fn sorted(names: &FxHashSet<String>) -> Vec<&str> {
    let mut names: Vec<&str> = names.iter().map(String::as_str).collect();
    names.sort_unstable();
    names
}

fn quoted(names: &[&str]) -> String {
    let names: Vec<String> = names.iter().map(|n| format!("`{n}`")).collect();
    names.join(", ")
}

/// From a part's name to its last token.
fn part_range(def: &PartDef) -> SpanRange {
    let mut last = def.name.span();
    for item in &def.items {
        if let Some(span) = item_end(item) {
            last = span;
        }
    }
    SpanRange {
        start: def.name.span(),
        end: last,
    }
}

/// A span late in `item`, as far as a part's range needs one.
fn item_end(item: &Item) -> Option<Span> {
    Some(match item {
        Item::Let { value, .. } | Item::Energy { value, .. } => SpanRange::of(value).end,
        Item::GeneralizedForce { value, .. } => SpanRange::of(value).end,
        Item::PointForce {
            components_span, ..
        } => *components_span,
        Item::Output(o) => SpanRange::of(&o.value).end,
        Item::Constraint(c) => SpanRange::of(&c.value).end,
        Item::PartInstance(p) => p.arguments_span,
        Item::Coordinates { decls, .. } => decls.last()?.name.span(),
        Item::Parameters { decls } => decls.last()?.decl.name.span(),
        Item::Inputs { decls } => decls.last()?.decl.name.span(),
        _ => return None,
    })
}

/// The tokens of each part of the standard library, `part NAME (…) {…}`
/// (its doc comments left out), by name.
fn library_parts() -> FxHashMap<String, TokenStream> {
    let tokens: TokenStream = LIBRARY.parse().expect("the library of parts lexes");
    let trees: Vec<TokenTree> = tokens.into_iter().collect();
    let mut parts = FxHashMap::default();
    for w in trees.windows(4) {
        if let [
            TokenTree::Ident(part),
            TokenTree::Ident(name),
            TokenTree::Group(_),
            TokenTree::Group(_),
        ] = w
            && part == "part"
        {
            parts.insert(name.to_string(), w.iter().cloned().collect());
        }
    }
    parts
}

fn parts_of(tokens: TokenStream) -> FxHashMap<String, PartDef> {
    let parsed = syn::parse2::<SpecAst>(super::families::sum_syntax(tokens));
    let expanded = parsed
        .ok()
        .and_then(|ast| super::families::expand(ast).ok());
    let items = expanded.map(|ast| ast.items).unwrap_or_default();
    let mut parts = FxHashMap::default();
    for item in items {
        if let Item::PartDef(def) = item {
            parts.insert(def.name.to_string(), def);
        }
    }
    parts
}

fn respanned(tokens: TokenStream, at: Span) -> TokenStream {
    tokens
        .into_iter()
        .map(|tree| match tree {
            TokenTree::Group(g) => {
                let mut group = Group::new(g.delimiter(), respanned(g.stream(), at));
                group.set_span(at);
                TokenTree::Group(group)
            }
            mut other => {
                other.set_span(at);
                other
            }
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_library_parses_whole_and_part_by_part() {
        let tokens: TokenStream = LIBRARY.parse().unwrap();
        let parts = parts_of(tokens);
        for (name, tokens) in library_parts() {
            let alone = parts_of(tokens);
            assert_eq!(alone.len(), 1, "{name}");
            assert_eq!(alone[&name].items.len(), parts[&name].items.len(), "{name}");
        }
        let mut names: Vec<&str> = parts.keys().map(String::as_str).collect();
        names.sort_unstable();
        assert_eq!(
            names,
            [
                "belted_occupant",
                "crush_to_wall",
                "mass",
                "spring_damper",
                "stop"
            ]
        );
    }
}
