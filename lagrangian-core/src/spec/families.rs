//! Indexed families — `x[7]`, `m[i in 1..=7] = …`, `for i in 1..=6 { … }`,
//! `x[i + 1]`, `sum(i in 1..=7, …)` — expanded into the scalar spec they
//! stand for before names are resolved. While the spec is lowered, element
//! `k` of family `x` is the name `x‿k` (a connector no spec name has); the
//! model and its messages call it `x[k]` ([`display_name`]).

use super::ast::{Declaration, InputDecl, Item, ParameterDecl, SpecAst, Subscript};
use super::names::{MARK, MEMBER, display_name};
use crate::diagnostic::{Diagnostic, SpanRange, SpecErrors};
use proc_macro2::{Ident, Punct, Spacing, Span, TokenStream, TokenTree};
use rustc_hash::{FxHashMap, FxHashSet};
use std::borrow::Cow;
use syn::visit_mut::{self, VisitMut};
use syn::{BinOp, Expr, Lit, RangeLimits, UnOp};

/// The most elements a family may have.
const MAX_ELEMENTS: i64 = 100_000;
/// The most coordinates families may declare: a derivation's time and
/// memory grow with the square of their number (1000 derive in about 20 s
/// unoptimized).
const MAX_COORDINATES: usize = 1000;
/// The most statements and sum terms the loops of a spec may expand into.
const MAX_EXPANDED: usize = 1_000_000;

/// Element `k` of family `name`, as lowering names it.
fn element(name: &Ident, k: i64) -> Ident {
    Ident::new(&format!("{name}{MARK}{k}"), name.span())
}

/// `sum(i in a..=b, body)` as `syn` reads an expression: `sum(i, a..=b, body)`.
pub(super) fn sum_syntax(tokens: TokenStream) -> TokenStream {
    let mut out: Vec<TokenTree> = Vec::new();
    for tree in tokens {
        let tree = match tree {
            TokenTree::Group(group) => {
                let after_sum = matches!(out.last(), Some(TokenTree::Ident(i)) if i == "sum");
                let mut inner: Vec<TokenTree> = sum_syntax(group.stream()).into_iter().collect();
                let is_sum = after_sum && group.delimiter() == proc_macro2::Delimiter::Parenthesis;
                if is_sum
                    && matches!(inner.first(), Some(TokenTree::Ident(_)))
                    && matches!(inner.get(1), Some(TokenTree::Ident(i)) if i == "in")
                {
                    let mut comma = Punct::new(',', Spacing::Alone);
                    comma.set_span(inner[1].span());
                    inner[1] = TokenTree::Punct(comma);
                }
                let mut new =
                    proc_macro2::Group::new(group.delimiter(), inner.into_iter().collect());
                new.set_span(group.span());
                TokenTree::Group(new)
            }
            other => other,
        };
        out.push(tree);
    }
    out.into_iter().collect()
}

/// What a family is, for messages and range checks.
#[derive(Clone)]
struct Family {
    /// `coordinates`, `parameters`, `inputs`, or a statement's kind.
    kind: &'static str,
    /// The elements 1 to `count`, where the declaration says (statements'
    /// families are as many as they define).
    count: Option<i64>,
    /// Where it is declared.
    span: Span,
}

/// The expansion's state: the families, the loop indices bound, the names
/// the spec declares and the problems found.
struct Expansion {
    families: FxHashMap<String, Family>,
    declared: FxHashSet<String>,
    indices: Vec<(String, i64)>,
    /// An input's formal arguments, which hide families of their names in
    /// its derivatives.
    arguments: Vec<String>,
    problems: Vec<Diagnostic>,
    expanded: usize,
}

/// The spec `ast` with its families, loops and sums written out; every
/// problem found, each at its span.
pub(super) fn expand(ast: SpecAst) -> Result<SpecAst, SpecErrors> {
    let mut expansion = Expansion {
        families: FxHashMap::default(),
        declared: FxHashSet::default(),
        indices: Vec::new(),
        arguments: Vec::new(),
        problems: Vec::new(),
        expanded: 0,
    };
    expansion.collect(&ast.items);
    expansion.identifier_clashes();
    let items = expansion.items(ast.items);
    // A loop's body repeats its problem at one place: reported once.
    let mut seen = FxHashSet::default();
    (expansion.problems).retain(|d| seen.insert(format!("{:?}", d.span.start)));
    match expansion.problems.is_empty() {
        true => Ok(SpecAst {
            inner_doc: ast.inner_doc,
            items,
        }),
        false => Err(SpecErrors {
            diagnostics: expansion.problems,
        }),
    }
}

impl Expansion {
    /// The families and names the blocks declare, and the statements'
    /// families (`let c[i] = …`).
    fn collect(&mut self, items: &[Item]) {
        for item in items {
            match item {
                Item::Coordinates { decls, .. } => {
                    decls.iter().for_each(|d| self.declare(d, "coordinates"));
                }
                Item::Parameters { decls } => {
                    decls
                        .iter()
                        .for_each(|d| self.declare(&d.decl, "parameters"));
                }
                Item::Inputs { decls } => {
                    decls.iter().for_each(|d| self.declare(&d.decl, "inputs"));
                }
                Item::Let {
                    name,
                    subscript: Some(_),
                    ..
                } => self.statement_family(name, "definitions"),
                Item::Output(output) if output.decl.subscript.is_some() => {
                    self.statement_family(&output.decl.name, "outputs")
                }
                Item::Constraint(c) if c.subscript.is_some() => {
                    self.statement_family(&c.name, "constraints")
                }
                Item::PartInstance(p) if p.subscript.is_some() => {
                    self.statement_family(&p.name, "part instances")
                }
                Item::For { items, .. } => self.collect(items),
                _ => {}
            }
        }
    }

    fn declare(&mut self, decl: &Declaration, kind: &'static str) {
        let name = decl.name.to_string();
        if name.contains([MARK, MEMBER]) {
            let why = format!("`{MARK}` and `{MEMBER}` are not allowed in a name");
            self.problems.push(Diagnostic::new(decl.name.span(), why));
        }
        let count = match &decl.subscript {
            Some(Subscript::Count { count, .. }) => Some(*count as i64),
            Some(Subscript::Ranged { range, .. }) => self.range(range).map(|(_, high)| high),
            _ => None,
        };
        match decl.subscript.is_some() {
            true => {
                let span = decl.name.span();
                let family = Family { kind, count, span };
                self.families.insert(name, family);
            }
            false => {
                self.declared.insert(name);
            }
        }
    }

    /// A family whose element `x[k]` generated code spells as a name the
    /// spec declares (`x_k`) is an error at the family.
    fn identifier_clashes(&mut self) {
        let mut clashes = Vec::new();
        for (name, family) in &self.families {
            for k in 1..=family.count.unwrap_or(0) {
                let spelled = format!("{name}_{k}");
                if self.declared.contains(&spelled) {
                    let why = format!(
                        "`{name}[{k}]` is `{spelled}` in generated code, which the spec declares too"
                    );
                    clashes.push(Diagnostic::new(family.span, why).with_help("rename one of them"));
                }
            }
        }
        self.problems.extend(clashes);
    }

    fn statement_family(&mut self, name: &Ident, kind: &'static str) {
        let span = name.span();
        let family = Family {
            kind,
            count: None,
            span,
        };
        self.families.entry(name.to_string()).or_insert(family);
    }

    /// The bounds of `a..=b` in the indices bound now.
    fn range(&mut self, range: &Expr) -> Option<(i64, i64)> {
        let bounds = match range {
            Expr::Range(r) => match (&r.start, &r.end, r.limits) {
                (Some(a), Some(b), RangeLimits::Closed(_)) => Ok((a, b)),
                (Some(_), Some(_), RangeLimits::HalfOpen(_)) => Err(Diagnostic::new(
                    SpanRange::of(range),
                    "a range here includes both ends: write `a..=b`",
                )
                .with_help(
                    "`1..7` reads as 1 to 6 in Rust and as 1 to 7 in mathematics; `1..=7` is 1 to 7",
                )),
                _ => Err(range_expected(range)),
            },
            _ => Err(range_expected(range)),
        };
        let problem = match bounds {
            Ok((a, b)) => match (self.integer(a), self.integer(b)) {
                (Ok(a), Ok(b)) => return Some((a, b)),
                (Err(d), _) | (_, Err(d)) => d,
            },
            Err(d) => d,
        };
        self.problems.push(problem);
        None
    }

    /// `expr` as an integer: literals and the loop indices bound now,
    /// with `+`, `-` and `*`.
    fn integer(&self, expr: &Expr) -> Result<i64, Diagnostic> {
        let overflow = || Diagnostic::new(SpanRange::of(expr), "this index overflows");
        match expr {
            Expr::Lit(syn::ExprLit {
                lit: Lit::Int(i), ..
            }) => i.base10_parse::<i64>().map_err(|_| overflow()),
            Expr::Paren(p) => self.integer(&p.expr),
            Expr::Group(g) => self.integer(&g.expr),
            Expr::Unary(u) if matches!(u.op, UnOp::Neg(_)) => {
                self.integer(&u.expr)?.checked_neg().ok_or_else(overflow)
            }
            Expr::Binary(b) => {
                let (l, r) = (self.integer(&b.left)?, self.integer(&b.right)?);
                let value = match b.op {
                    BinOp::Add(_) => l.checked_add(r),
                    BinOp::Sub(_) => l.checked_sub(r),
                    BinOp::Mul(_) => l.checked_mul(r),
                    _ => return Err(not_an_index(expr)),
                };
                value.ok_or_else(overflow)
            }
            Expr::Path(p) => match p.path.get_ident().and_then(|i| self.index(i)) {
                Some(k) => Ok(k),
                None => Err(not_an_index(expr)),
            },
            _ => Err(not_an_index(expr)),
        }
    }

    /// The value of loop index `ident`, if one is bound.
    fn index(&self, ident: &Ident) -> Option<i64> {
        (self.indices.iter().rev())
            .find(|(name, _)| ident == name)
            .map(|&(_, k)| k)
    }

    /// Counts `n` more expanded statements or terms; `false` (with the
    /// problem at `span`) past the limit.
    fn count(&mut self, n: usize, span: Span) -> bool {
        self.expanded = self.expanded.saturating_add(n);
        if self.expanded <= MAX_EXPANDED {
            return true;
        }
        if self.expanded.saturating_sub(n) <= MAX_EXPANDED {
            let why = format!("the loops and sums of this spec expand past {MAX_EXPANDED} terms");
            self.problems.push(Diagnostic::new(span, why));
        }
        false
    }

    /// The elements `1..=n` of a declaration's family, each with the
    /// loop index it names (for `[i in 1..=n]`); one `None` for a scalar.
    fn elements(&mut self, decl: &Declaration) -> Vec<Option<(Option<String>, i64)>> {
        let (index, count, span) = match &decl.subscript {
            None => return vec![None],
            Some(Subscript::Count { count, span }) => (None, *count as i64, *span),
            Some(Subscript::Ranged { index, range, span }) => match self.range(range) {
                Some((1, high)) => (Some(index.to_string()), high, *span),
                Some(_) => {
                    let why = "a family's elements are numbered from 1: write `1..=n`";
                    self.problems
                        .push(Diagnostic::new(SpanRange::of(range), why));
                    return Vec::new();
                }
                None => return Vec::new(),
            },
            Some(Subscript::Element(e)) => {
                let why = "a family is declared as `x[7]` or `x[i in 1..=7]`";
                self.problems.push(Diagnostic::new(SpanRange::of(e), why));
                return Vec::new();
            }
        };
        if !(1..=MAX_ELEMENTS).contains(&count) {
            let why = format!("a family has 1 to {MAX_ELEMENTS} elements, not {count}");
            self.problems.push(Diagnostic::new(span, why));
            return Vec::new();
        }
        if !self.count(count as usize, span) {
            return Vec::new();
        }
        (1..=count).map(|k| Some((index.clone(), k))).collect()
    }

    /// `decl` for element `k` (or as it is, for a scalar).
    fn declaration(decl: &Declaration, element_of: Option<i64>) -> Declaration {
        let mut out = decl.clone();
        out.subscript = None;
        if let Some(k) = element_of {
            out.name = element(&decl.name, k);
        }
        out
    }

    /// Runs `f` with the loop index `index` bound to `k` (if any).
    fn with_index<T>(
        &mut self,
        index: Option<(Option<String>, i64)>,
        f: impl FnOnce(&mut Self, Option<i64>) -> T,
    ) -> T {
        let (name, k) = match index {
            Some((name, k)) => (name, Some(k)),
            None => (None, None),
        };
        let bound = name
            .map(|n| self.indices.push((n, k.unwrap_or(0))))
            .is_some();
        let out = f(self, k);
        if bound {
            self.indices.pop();
        }
        out
    }

    fn items(&mut self, items: Vec<Item>) -> Vec<Item> {
        let mut out = Vec::with_capacity(items.len());
        for item in items {
            self.item(item, &mut out);
        }
        out
    }

    fn item(&mut self, item: Item, out: &mut Vec<Item>) {
        match item {
            Item::Coordinates { keyword, decls } => {
                let families = decls.iter().any(|d| d.subscript.is_some());
                let decls = self.block_with(&decls, |d| d, |_, d, k| Some(Self::declaration(d, k)));
                if families && decls.len() > MAX_COORDINATES {
                    let why = format!(
                        "{} coordinates: families may declare at most {MAX_COORDINATES}",
                        decls.len()
                    );
                    self.problems.push(Diagnostic::new(keyword, why));
                }
                out.push(Item::Coordinates { keyword, decls });
            }
            Item::Parameters { decls } => {
                let decls = self.block_with(&decls, |d: &ParameterDecl| &d.decl, Self::parameter);
                out.push(Item::Parameters { decls });
            }
            Item::Inputs { decls } => {
                let decls = self.block_with(&decls, |d: &InputDecl| &d.decl, Self::input);
                let decls = decls.into_iter().flat_map(supplied_derivatives).collect();
                out.push(Item::Inputs { decls });
            }
            Item::For {
                keyword,
                index,
                range,
                items,
            } => self.for_loop(keyword, index, &range, items, out),
            Item::PartDef(mut part) => {
                // A part's names are its own: its body expands on its own.
                let body = SpecAst {
                    inner_doc: Vec::new(),
                    items: std::mem::take(&mut part.items),
                };
                match expand(body) {
                    Ok(body) => part.items = body.items,
                    Err(errors) => self.problems.extend(errors.diagnostics),
                }
                out.push(Item::PartDef(part));
            }
            other => {
                if let Some(item) = self.statement(other) {
                    out.push(item);
                }
            }
        }
    }

    /// The declarations of a block, families written out by `make`.
    fn block_with<D>(
        &mut self,
        decls: &[D],
        decl_of: impl Fn(&D) -> &Declaration,
        make: impl Fn(&mut Self, &D, Option<i64>) -> Option<D>,
    ) -> Vec<D> {
        let mut out = Vec::new();
        for d in decls {
            for element_of in self.elements(decl_of(d)) {
                let made = self.with_index(element_of, |s, k| make(s, d, k));
                out.extend(made);
            }
        }
        out
    }

    /// A parameter, or element `k` of a family of them: `= [a, b, …]`
    /// gives each its value, any other default applies to every element.
    fn parameter(&mut self, p: &ParameterDecl, k: Option<i64>) -> Option<ParameterDecl> {
        let decl = Self::declaration(&p.decl, k);
        let value = match (&p.value, k) {
            (Some(Expr::Array(array)), Some(k)) => {
                let family = self.families.get(&p.decl.name.to_string());
                let count = family.and_then(|f| f.count).unwrap_or(1);
                if array.elems.len() as i64 != count {
                    if k == 1 {
                        let why = format!(
                            "`{}` has {count} elements but {} values",
                            p.decl.name,
                            array.elems.len()
                        );
                        self.problems
                            .push(Diagnostic::new(SpanRange::of(array), why));
                    }
                    return None;
                }
                Some(array.elems[k as usize - 1].clone())
            }
            (value, _) => value.clone(),
        };
        let value = value.map(|v| self.expression(v));
        Some(ParameterDecl { decl, value })
    }

    /// An input, or element `k` of a family: its derivatives with the
    /// family's index bound.
    fn input(&mut self, input: &InputDecl, k: Option<i64>) -> Option<InputDecl> {
        let decl = Self::declaration(&input.decl, k);
        self.arguments = input.arguments.iter().map(|a| a.name.to_string()).collect();
        let derivatives = (input.derivatives.iter())
            .map(|(argument, value)| (argument.clone(), self.expression(value.clone())))
            .collect();
        self.arguments.clear();
        Some(InputDecl {
            decl,
            arguments: input.arguments.clone(),
            derivatives,
            supplied: input.supplied.clone(),
        })
    }

    /// `for index in range { items }`: the items once per index value.
    fn for_loop(
        &mut self,
        keyword: Span,
        index: Ident,
        range: &Expr,
        items: Vec<Item>,
        out: &mut Vec<Item>,
    ) {
        let name = index.to_string();
        if self.declared.contains(&name) || self.families.contains_key(&name) {
            let why = format!("the loop index `{name}` hides a name the spec declares");
            let help = "name the index otherwise (`i`, `j`, `k`)";
            self.problems
                .push(Diagnostic::new(index.span(), why).with_help(help));
            return;
        }
        if self.index(&index).is_some() {
            let why = format!("`{name}` is already the index of an enclosing loop");
            self.problems.push(Diagnostic::new(index.span(), why));
            return;
        }
        let Some((low, high)) = self.range(range) else {
            return;
        };
        if let Some(Item::PartDef(def)) = items.iter().find(|i| matches!(i, Item::PartDef(_))) {
            let why = format!("part `{}` is defined inside a loop", def.name);
            let help = "define parts at the top level of the spec; instantiate them in the loop";
            self.problems
                .push(Diagnostic::new(def.name.span(), why).with_help(help));
            return;
        }
        let runs = (high - low + 1).max(0) as usize;
        if !self.count(runs.saturating_mul(items.len().max(1)), keyword) {
            return;
        }
        for k in low..=high {
            self.indices.push((name.clone(), k));
            for item in items.iter().cloned() {
                self.item(item, out);
            }
            self.indices.pop();
        }
    }

    /// A statement with its name's subscript resolved and its expressions
    /// rewritten.
    fn statement(&mut self, item: Item) -> Option<Item> {
        Some(match item {
            Item::Let {
                name,
                subscript,
                value,
            } => Item::Let {
                name: self.named(name, subscript)?,
                subscript: None,
                value: self.expression(value),
            },
            Item::Energy {
                kind,
                keyword,
                value,
            } => Item::Energy {
                kind,
                keyword,
                value: self.expression(value),
            },
            Item::GeneralizedForce {
                keyword,
                coordinate,
                subscript,
                value,
            } => Item::GeneralizedForce {
                keyword,
                coordinate: self.named(coordinate, subscript)?,
                subscript: None,
                value: self.expression(value),
            },
            Item::PointForce {
                point,
                point_span,
                components,
                components_span,
            } => Item::PointForce {
                point: point.into_iter().map(|e| self.expression(e)).collect(),
                point_span,
                components: components.into_iter().map(|e| self.expression(e)).collect(),
                components_span,
            },
            Item::Output(mut output) => {
                let subscript = output.decl.subscript.take();
                output.decl.name = self.named(output.decl.name, subscript)?;
                output.value = self.expression(output.value);
                Item::Output(output)
            }
            Item::Constraint(mut constraint) => {
                let subscript = constraint.subscript.take();
                constraint.name = self.named(constraint.name, subscript)?;
                constraint.value = self.expression(constraint.value);
                Item::Constraint(constraint)
            }
            Item::PartInstance(mut instance) => {
                let subscript = instance.subscript.take();
                instance.name = self.named(instance.name, subscript)?;
                let arguments = std::mem::take(&mut instance.arguments);
                instance.arguments = arguments.into_iter().map(|a| self.expression(a)).collect();
                for (_, value) in &mut instance.settings {
                    *value = self.expression(value.clone());
                }
                Item::PartInstance(instance)
            }
            other => other,
        })
    }

    /// The name a statement defines or acts on: `c[i + 1]` is element
    /// `i + 1` of `c`, a plain name itself.
    fn named(&mut self, name: Ident, subscript: Option<Subscript>) -> Option<Ident> {
        match subscript {
            None => Some(name),
            Some(Subscript::Element(index)) => {
                let k = self
                    .integer(&index)
                    .map_err(|d| self.problems.push(d))
                    .ok()?;
                self.check_range(&name, k, &index)?;
                Some(element(&name, k))
            }
            Some(Subscript::Count { span, .. }) | Some(Subscript::Ranged { span, .. }) => {
                let why = "here `[…]` names one element (`c[i]`); families are declared in blocks";
                self.problems.push(Diagnostic::new(span, why));
                None
            }
        }
    }

    /// `Some` if `k` is an element of `name`'s family (when its size is known).
    fn check_range(&mut self, name: &Ident, k: i64, at: &Expr) -> Option<()> {
        let count = self.families.get(&name.to_string()).and_then(|f| f.count);
        match count {
            None if k < 1 => {
                let why = format!("`{name}[{k}]`: a family's elements are numbered from 1");
                self.problems.push(Diagnostic::new(SpanRange::of(at), why));
                None
            }
            Some(n) if !(1..=n).contains(&k) => {
                let why = format!("`{name}[{k}]` is outside `{name}`, whose elements are 1..={n}");
                self.problems.push(Diagnostic::new(SpanRange::of(at), why));
                None
            }
            _ => Some(()),
        }
    }

    /// `expr` with indexed names, loop indices and sums written out.
    fn expression(&mut self, mut expr: Expr) -> Expr {
        Rewrite { expansion: self }.visit_expr_mut(&mut expr);
        expr
    }
}

/// `input` with each derivative `d(a)` it leaves to its component written
/// `d(a) = input_da(args…)`, followed by the input `input_da` of the same
/// arguments, its unit the input's over `a`'s: the component bound to
/// `input` supplies it (the scenario binds it to the component's tangent).
fn supplied_derivatives(mut input: InputDecl) -> Vec<InputDecl> {
    let supplied = std::mem::take(&mut input.supplied);
    let mut tangents = Vec::new();
    for argument in supplied {
        let name = Ident::new(&format!("{}_d{argument}", input.decl.name), argument.span());
        let of = (input.arguments.iter()).find(|a| a.name == argument);
        let unit = match (&input.decl.unit, of.and_then(|a| a.unit.as_ref())) {
            (Some(value), Some(by)) => Some(super::ast::UnitText {
                text: unit_over(&value.text, &by.text),
                span: value.span,
            }),
            _ => None,
        };
        let arguments: Vec<&Ident> = input.arguments.iter().map(|a| &a.name).collect();
        let call: Expr = syn::parse_quote_spanned!(argument.span()=> #name(#(#arguments),*));
        input.derivatives.push((argument.clone(), call));
        let doc = format!(
            "∂{}/∂{argument}, supplied by the component bound to `{}`.",
            display_name(&input.decl.name.to_string()),
            display_name(&input.decl.name.to_string())
        );
        tangents.push(InputDecl {
            decl: Declaration {
                doc: vec![doc],
                name,
                subscript: None,
                unit,
            },
            arguments: input.arguments.clone(),
            derivatives: Vec::new(),
            supplied: Vec::new(),
        });
    }
    let mut out = vec![input];
    out.extend(tangents);
    out
}

/// The unit `value / by` as units are written: `N/m`, `N*s/m` for `N`
/// over `m/s`, parenthesized where `by` is more than one quotient.
fn unit_over(value: &str, by: &str) -> String {
    let simple = |u: &str| !u.contains(['/', '(', ')']);
    match by.split_once('/') {
        None if simple(by) && !by.contains('*') => format!("{value}/{by}"),
        Some((above, below)) if simple(above) && simple(below) && !above.contains('*') => {
            format!("{value}*{below}/{above}")
        }
        _ => format!("({value})/({by})"),
    }
}

fn range_expected(range: &Expr) -> Diagnostic {
    Diagnostic::new(SpanRange::of(range), "expected a range `a..=b` of integers")
}

fn not_an_index(expr: &Expr) -> Diagnostic {
    Diagnostic::new(
        SpanRange::of(expr),
        "an index is an integer expression of integers and loop indices (`i + 1`)",
    )
}

/// The rewriting of one expression.
struct Rewrite<'a> {
    expansion: &'a mut Expansion,
}

impl Rewrite<'_> {
    /// The replacement of `expr`, where it is a loop index, an element, a
    /// family named whole or a `sum`; `None` to rewrite inside it.
    fn replacement(&mut self, expr: &Expr) -> Option<Expr> {
        let e = &mut *self.expansion;
        match expr {
            Expr::Path(p) => {
                let ident = p.path.get_ident()?;
                if e.arguments.iter().any(|a| ident == a) {
                    return None;
                }
                if let Some(k) = e.index(ident) {
                    let literal =
                        syn::LitFloat::new(&format!("{}.0", k.unsigned_abs()), ident.span());
                    return Some(match k < 0 {
                        true => syn::parse_quote_spanned!(ident.span()=> (-#literal)),
                        false => syn::parse_quote_spanned!(ident.span()=> (#literal)),
                    });
                }
                let family = e.families.get(&ident.to_string())?;
                let range = match family.count {
                    Some(n) => format!(" (`{ident}[1]` … `{ident}[{n}]`)"),
                    None => String::new(),
                };
                let why = format!(
                    "`{ident}` is a family of {}{range}: name one element, `{ident}[i]`",
                    family.kind
                );
                e.problems.push(Diagnostic::new(ident.span(), why));
                Some(syn::parse_quote!(0.0))
            }
            Expr::Index(index) => {
                let base = match &*index.expr {
                    Expr::Path(p) => p.path.get_ident().cloned(),
                    _ => None,
                };
                let family = base
                    .as_ref()
                    .filter(|b| e.families.contains_key(&b.to_string()));
                let Some(base) = family else {
                    let why = "only a family (`x[7]` in a block, `let c[i]`) can be indexed";
                    e.problems
                        .push(Diagnostic::new(SpanRange::of(&*index.expr), why));
                    return Some(syn::parse_quote!(0.0));
                };
                let k = match e.integer(&index.index) {
                    Ok(k) => k,
                    Err(d) => {
                        e.problems.push(d);
                        return Some(syn::parse_quote!(0.0));
                    }
                };
                if e.check_range(base, k, &index.index).is_none() {
                    return Some(syn::parse_quote!(0.0));
                }
                let name = element(base, k);
                Some(syn::parse_quote_spanned!(base.span()=> #name))
            }
            Expr::Call(call) => self.sum(call),
            _ => None,
        }
    }

    /// `sum(i, a..=b, body)`: `(body₍ᵢ₌ₐ₎ + … + body₍ᵢ₌b₎)`, 0 for an empty range.
    fn sum(&mut self, call: &syn::ExprCall) -> Option<Expr> {
        let Expr::Path(f) = &*call.func else {
            return None;
        };
        let e = &mut *self.expansion;
        let is_sum = f.path.is_ident("sum") && !e.declared.contains("sum");
        if !is_sum {
            return None;
        }
        let args: Vec<&Expr> = call.args.iter().collect();
        let index = match args.as_slice() {
            [Expr::Path(i), _, _] => i.path.get_ident().cloned(),
            _ => None,
        };
        let Some(index) = index else {
            let why = "a sum is written `sum(i in a..=b, expression)`";
            e.problems.push(Diagnostic::new(SpanRange::of(call), why));
            return Some(syn::parse_quote!(0.0));
        };
        let (low, high) = e.range(args[1])?;
        let terms = (high - low + 1).max(0) as usize;
        if !e.count(terms, index.span()) {
            return Some(syn::parse_quote!(0.0));
        }
        let mut total: Option<Expr> = None;
        for k in low..=high {
            self.expansion.indices.push((index.to_string(), k));
            let mut term = args[2].clone();
            self.visit_expr_mut(&mut term);
            self.expansion.indices.pop();
            total = Some(match total {
                None => syn::parse_quote!((#term)),
                Some(sum) => syn::parse_quote!(#sum + (#term)),
            });
        }
        Some(match total {
            Some(sum) => syn::parse_quote!((#sum)),
            None => syn::parse_quote!(0.0),
        })
    }
}

impl VisitMut for Rewrite<'_> {
    fn visit_expr_mut(&mut self, expr: &mut Expr) {
        match self.replacement(expr) {
            Some(replacement) => *expr = replacement,
            None => visit_mut::visit_expr_mut(self, expr),
        }
    }
}

/// `name` renamed where it is an element (`x‿3` → `x[3]`).
fn renamed(name: &mut String) {
    if let Cow::Owned(read) = display_name(name) {
        *name = read;
    }
}

/// `d` with its elements named as users read them.
fn diagnostic_as_read(mut d: Diagnostic) -> Diagnostic {
    renamed(&mut d.message);
    if let Some(help) = &mut d.help {
        renamed(help);
    }
    if let Some(note) = &mut d.note {
        renamed(&mut note.0);
    }
    d
}

/// The problems of a spec, its elements named as users read them; one
/// that a loop's body repeats (the same message at the same place) once.
pub(super) fn errors_as_read(errors: SpecErrors) -> SpecErrors {
    let mut seen = FxHashSet::default();
    let diagnostics = (errors.diagnostics.into_iter())
        .filter(|d| seen.insert((d.message.clone(), format!("{:?}", d.span.start))))
        .map(diagnostic_as_read);
    SpecErrors {
        diagnostics: diagnostics.collect(),
    }
}

/// The model with its elements named as users read them: `x[3]` in its
/// coordinates, parameters, inputs, outputs, constraints, definitions,
/// symbols and warnings.
pub(super) fn model_as_read(mut model: super::Model) -> super::Model {
    model
        .coordinates
        .iter_mut()
        .for_each(|c| renamed(&mut c.name));
    model
        .parameters
        .iter_mut()
        .for_each(|p| renamed(&mut p.name));
    model.inputs.iter_mut().for_each(|i| renamed(&mut i.name));
    model.outputs.iter_mut().for_each(|o| renamed(&mut o.name));
    model
        .constraints
        .iter_mut()
        .for_each(|c| renamed(&mut c.name));
    model
        .definitions
        .iter_mut()
        .for_each(|(name, _)| renamed(name));
    model.store.rename(|name| match display_name(name) {
        Cow::Owned(read) => Some(read),
        Cow::Borrowed(_) => None,
    });
    model.warnings = std::mem::take(&mut model.warnings)
        .into_iter()
        .map(diagnostic_as_read)
        .collect();
    model
}
