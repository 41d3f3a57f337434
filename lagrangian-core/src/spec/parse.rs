//! Parsing the spec language with `syn`. The grammar, in Rust token syntax:
//!
//! ```text
//! spec        = inner-doc* item*
//! item        = doc* ( "model" IDENT ";"
//!                    | "coordinates" "{" decl,* "}"
//!                    | "parameters"  "{" (decl "=" EXPR),* "}"
//!                    | "inputs"      "{" (IDENT "(" decl,* ")" unit? derivs?),* "}"
//!                    | "let" IDENT "=" EXPR ";"
//!                    | ("kinetic" | "potential" | "dissipation") "=" EXPR ";"
//!                    | "force" IDENT "=" EXPR ";"
//!                    | "force" "at" "(" EXPR,* ")" "=" "(" EXPR,* ")" ";"
//!                    | "torque" "(" EXPR ")" "=" EXPR ";"   (T about the angle EXPR)
//!                    | "output" decl "=" EXPR ";"   (EXPR may use ddot(q))
//!                    | "constraint" IDENT "=" EXPR ";"   (EXPR(q, t) = 0)
//!                    | "jacobians" ";"
//!                    | "hand_derived" "{" hand-entry* "}"
//!                    | "for" IDENT "in" INT-EXPR "..=" INT-EXPR "{" item* "}"
//!                    | "part" IDENT "(" decl,* ")" "{" item* "}"     (a part)
//!                    | "part" IDENT family? "=" IDENT "(" EXPR,* ")"
//!                          ("{" (IDENT "=" EXPR),* "}")? ";"       (an instance) )
//! decl        = doc* IDENT family? unit?
//! family      = "[" INT "]" | "[" IDENT "in" INT-EXPR "..=" INT-EXPR "]"
//!               (in a statement, "[" INT-EXPR "]" names one element)
//! unit        = "[" unit tokens "]"              e.g. [N*s/m], [m/s^2]
//! derivs      = "{" ("d" "(" IDENT ")" ("=" EXPR)?),* "}"   (no EXPR: the
//!               bound component supplies it)
//! hand-entry  = "convention" "=" IDENT ";" | "small_angle_order" "=" INT ";"
//!             | ("symbols" | "assume") "{" (IDENT "=" EXPR),* "}"
//!             | "force"? IDENT "=" EXPR ";"       (EXPR may use ddot(q))
//! ```

use super::ast::*;
use proc_macro2::{Span, TokenStream};
use syn::parse::{Parse, ParseStream};
use syn::spanned::Spanned;
use syn::{Attribute, Expr, Ident, Token, braced, bracketed, parenthesized};

mod kw {
    syn::custom_keyword!(model);
    syn::custom_keyword!(coordinates);
    syn::custom_keyword!(parameters);
    syn::custom_keyword!(inputs);
    syn::custom_keyword!(kinetic);
    syn::custom_keyword!(potential);
    syn::custom_keyword!(dissipation);
    syn::custom_keyword!(force);
    syn::custom_keyword!(at);
    syn::custom_keyword!(jacobians);
    syn::custom_keyword!(output);
    syn::custom_keyword!(constraint);
    syn::custom_keyword!(torque);
    syn::custom_keyword!(d);
    syn::custom_keyword!(hand_derived);
    syn::custom_keyword!(convention);
    syn::custom_keyword!(small_angle_order);
    syn::custom_keyword!(symbols);
    syn::custom_keyword!(assume);
    syn::custom_keyword!(part);
}

impl Parse for SpecAst {
    fn parse(input: ParseStream) -> syn::Result<Self> {
        let inner = input.call(Attribute::parse_inner)?;
        let inner_doc = doc_lines(&inner)?;
        let mut items = Vec::new();
        while !input.is_empty() {
            items.push(parse_item(input)?);
        }
        Ok(SpecAst { inner_doc, items })
    }
}

/// The text of `///` comments; any other attribute is an error.
fn doc_lines(attrs: &[Attribute]) -> syn::Result<Vec<String>> {
    attrs
        .iter()
        .map(|attr| {
            if let syn::Meta::NameValue(nv) = &attr.meta
                && nv.path.is_ident("doc")
                && let Expr::Lit(syn::ExprLit {
                    lit: syn::Lit::Str(s),
                    ..
                }) = &nv.value
            {
                let text = s.value();
                return Ok(text.strip_prefix(' ').unwrap_or(&text).to_string());
            }
            Err(syn::Error::new(
                attr.span(),
                "only doc comments (`///`) may annotate spec items",
            ))
        })
        .collect()
}

fn parse_item(input: ParseStream) -> syn::Result<Item> {
    let attrs = input.call(Attribute::parse_outer)?;
    let doc = doc_lines(&attrs)?;
    let look = input.lookahead1();
    if look.peek(kw::model) {
        input.parse::<kw::model>()?;
        let name = input.parse()?;
        input.parse::<Token![;]>()?;
        Ok(Item::Model { doc, name })
    } else if look.peek(kw::coordinates) {
        let keyword = input.parse::<kw::coordinates>()?.span;
        let decls = parse_braced_list(input, parse_declaration)?;
        Ok(Item::Coordinates { keyword, decls })
    } else if look.peek(kw::parameters) {
        input.parse::<kw::parameters>()?;
        let decls = parse_braced_list(input, parse_parameter)?;
        Ok(Item::Parameters { decls })
    } else if look.peek(kw::inputs) {
        input.parse::<kw::inputs>()?;
        let decls = parse_braced_list(input, parse_input)?;
        Ok(Item::Inputs { decls })
    } else if look.peek(Token![let]) {
        input.parse::<Token![let]>()?;
        let name = input.parse()?;
        let subscript = parse_subscript(input, Place::Name)?;
        input.parse::<Token![=]>()?;
        let value = input.parse()?;
        input.parse::<Token![;]>()?;
        Ok(Item::Let {
            name,
            subscript,
            value,
        })
    } else if look.peek(kw::kinetic) || look.peek(kw::potential) || look.peek(kw::dissipation) {
        let (kind, keyword) = if input.peek(kw::kinetic) {
            (EnergyKind::Kinetic, input.parse::<kw::kinetic>()?.span)
        } else if input.peek(kw::potential) {
            (EnergyKind::Potential, input.parse::<kw::potential>()?.span)
        } else {
            (
                EnergyKind::Dissipation,
                input.parse::<kw::dissipation>()?.span,
            )
        };
        input.parse::<Token![=]>()?;
        let value = input.parse()?;
        input.parse::<Token![;]>()?;
        Ok(Item::Energy {
            kind,
            keyword,
            value,
        })
    } else if look.peek(kw::force) {
        parse_force(input)
    } else if look.peek(kw::torque) {
        parse_torque(input)
    } else if look.peek(kw::output) {
        parse_output(input, doc)
    } else if look.peek(kw::constraint) {
        parse_constraint(input, doc)
    } else if look.peek(kw::jacobians) {
        let keyword = input.parse::<kw::jacobians>()?.span;
        input.parse::<Token![;]>()?;
        Ok(Item::Jacobians { keyword })
    } else if look.peek(kw::hand_derived) {
        parse_hand_section(input, doc)
    } else if look.peek(Token![for]) {
        parse_for(input)
    } else if look.peek(kw::part) {
        parse_part(input)
    } else {
        Err(look.error())
    }
}

fn parse_force(input: ParseStream) -> syn::Result<Item> {
    let keyword = input.parse::<kw::force>()?.span;
    if input.peek(kw::at) {
        input.parse::<kw::at>()?;
        let (point, point_span) = parse_tuple(input)?;
        input.parse::<Token![=]>()?;
        let (components, components_span) = parse_tuple(input)?;
        input.parse::<Token![;]>()?;
        if point.len() != components.len() {
            return Err(syn::Error::new(
                components_span,
                format!(
                    "the force has {} components but the point has {} coordinates",
                    components.len(),
                    point.len()
                ),
            ));
        }
        Ok(Item::PointForce {
            point,
            point_span,
            components,
            components_span,
        })
    } else {
        let coordinate = input.parse()?;
        let subscript = parse_subscript(input, Place::Name)?;
        input.parse::<Token![=]>()?;
        let value = input.parse()?;
        input.parse::<Token![;]>()?;
        Ok(Item::GeneralizedForce {
            keyword,
            coordinate,
            subscript,
            value,
        })
    }
}

/// `torque (φ) = T;`: a torque `T` about the angle `φ(q, t)`, whose virtual
/// work `T·δφ` gives `Q_i = T ∂φ/∂q_i` — a force at a point of one
/// coordinate, the angle.
fn parse_torque(input: ParseStream) -> syn::Result<Item> {
    input.parse::<kw::torque>()?;
    let (angle, point_span) = parse_tuple(input)?;
    if angle.len() != 1 {
        return Err(syn::Error::new(
            point_span,
            format!(
                "a torque acts about one angle, not {} (write `torque (theta2 - theta1) = T;`)",
                angle.len()
            ),
        ));
    }
    input.parse::<Token![=]>()?;
    let value: Expr = input.parse()?;
    let components_span = value.span();
    input.parse::<Token![;]>()?;
    Ok(Item::PointForce {
        point: angle,
        point_span,
        components: vec![value],
        components_span,
    })
}

/// `constraint NAME = EXPR;`, its doc lines already read.
fn parse_constraint(input: ParseStream, doc: Vec<String>) -> syn::Result<Item> {
    input.parse::<kw::constraint>()?;
    let name = input.parse()?;
    let subscript = parse_subscript(input, Place::Name)?;
    input.parse::<Token![=]>()?;
    let value = input.parse()?;
    input.parse::<Token![;]>()?;
    Ok(Item::Constraint(ConstraintDecl {
        doc,
        name,
        subscript,
        value,
    }))
}

/// `output NAME [unit] = EXPR;`, its doc lines already read.
fn parse_output(input: ParseStream, doc: Vec<String>) -> syn::Result<Item> {
    input.parse::<kw::output>()?;
    let name = input.parse()?;
    let subscript = parse_subscript(input, Place::Statement)?;
    let unit = parse_unit(input)?;
    input.parse::<Token![=]>()?;
    let value = input.parse()?;
    input.parse::<Token![;]>()?;
    let decl = Declaration {
        doc,
        name,
        subscript,
        unit,
    };
    Ok(Item::Output(OutputDecl { decl, value }))
}

fn parse_tuple(input: ParseStream) -> syn::Result<(Vec<Expr>, Span)> {
    let content;
    let paren = parenthesized!(content in input);
    let items = content.parse_terminated(Expr::parse, Token![,])?;
    if items.is_empty() {
        return Err(syn::Error::new(
            paren.span.join(),
            "expected at least one component",
        ));
    }
    Ok((items.into_iter().collect(), paren.span.join()))
}

fn parse_braced_list<T>(
    input: ParseStream,
    item: fn(ParseStream) -> syn::Result<T>,
) -> syn::Result<Vec<T>> {
    let content;
    braced!(content in input);
    let mut out = Vec::new();
    while !content.is_empty() {
        out.push(item(&content)?);
        if content.is_empty() {
            break;
        }
        content.parse::<Token![,]>()?;
    }
    Ok(out)
}

fn parse_declaration(input: ParseStream) -> syn::Result<Declaration> {
    let attrs = input.call(Attribute::parse_outer)?;
    let doc = doc_lines(&attrs)?;
    let name = input.parse()?;
    let subscript = parse_subscript(input, Place::Block)?;
    let unit = parse_unit(input)?;
    Ok(Declaration {
        doc,
        name,
        subscript,
        unit,
    })
}

/// Where a `[…]` after a name is read.
#[derive(Clone, Copy, PartialEq)]
enum Place {
    /// In a `coordinates`, `parameters` or `inputs` block: `[N]` and
    /// `[i in a..=b]` declare a family; another bracket is the unit.
    Block,
    /// After an output's name: a subscript unless it reads as a unit.
    Statement,
    /// After a `let`'s, a constraint's or a force's name: a subscript.
    Name,
}

/// `i in a..=b`.
fn ranged(input: ParseStream) -> syn::Result<(Ident, Expr)> {
    let index: Ident = input.parse()?;
    input.parse::<Token![in]>()?;
    Ok((index, input.parse()?))
}

/// `[…]` after a name where it is a subscript rather than a unit: `[N]`,
/// `[i in a..=b]`, a bracket followed by another (the unit), and, after an
/// output's name, a bracket that is no unit.
fn parse_subscript(input: ParseStream, place: Place) -> syn::Result<Option<Subscript>> {
    use syn::parse::Parser;
    if !input.peek(syn::token::Bracket) {
        return Ok(None);
    }
    let fork = input.fork();
    let content;
    bracketed!(content in fork);
    let tokens: TokenStream = content.parse()?;
    let unit_follows = fork.peek(syn::token::Bracket);
    // `[1]` alone is the unit of a pure number (`mu [1] = 0.5`), not a
    // family of one.
    let is_count = syn::parse2::<syn::LitInt>(tokens.clone())
        .is_ok_and(|n| n.base10_digits() != "1" || unit_follows);
    let is_ranged = ranged.parse2(tokens.clone()).is_ok();
    let subscript = match place {
        Place::Block => is_count || is_ranged || unit_follows,
        Place::Statement => is_count || is_ranged || unit_follows || looks_like_index(&tokens),
        Place::Name => true,
    };
    if !subscript {
        return Ok(None);
    }
    let content;
    let bracket = bracketed!(content in input);
    let span = bracket.span.join();
    let tokens: TokenStream = content.parse()?;
    if is_ranged {
        let (index, range) = ranged.parse2(tokens)?;
        return Ok(Some(Subscript::Ranged { index, range, span }));
    }
    if place == Place::Block {
        let count = syn::parse2::<syn::LitInt>(tokens).map_err(|_| {
            syn::Error::new(span, "a family is declared as `x[7]` or `x[i in 1..=7]`")
        })?;
        let count = count.base10_parse::<usize>()?;
        return Ok(Some(Subscript::Count { count, span }));
    }
    Ok(Some(Subscript::Element(syn::parse2(tokens)?)))
}

/// Whether a lone bracket after an output's name reads as an index rather
/// than a unit: a one-letter name that is no unit symbol (`[i]`), or a sum
/// or difference without the `^` and `/` of units (`[i + 1]`).
fn looks_like_index(tokens: &TokenStream) -> bool {
    use proc_macro2::TokenTree;
    let trees: Vec<TokenTree> = tokens.clone().into_iter().collect();
    let punct =
        |c: char| (trees.iter()).any(|t| matches!(t, TokenTree::Punct(p) if p.as_char() == c));
    match trees.as_slice() {
        [TokenTree::Ident(i)] => {
            let name = i.to_string();
            name.len() == 1 && !["m", "s", "g", "N", "J", "W"].contains(&name.as_str())
        }
        _ => (punct('+') || punct('-')) && !punct('^') && !punct('/'),
    }
}

/// `for i in a..=b { statements }`.
fn parse_for(input: ParseStream) -> syn::Result<Item> {
    let keyword = input.parse::<Token![for]>()?.span;
    let index: Ident = input.parse()?;
    input.parse::<Token![in]>()?;
    let range = Expr::parse_without_eager_brace(input)?;
    let body;
    braced!(body in input);
    let mut items = Vec::new();
    while !body.is_empty() {
        items.push(parse_item(&body)?);
    }
    Ok(Item::For {
        keyword,
        index,
        range,
        items,
    })
}

/// A part's definition, `part NAME(PORTS) { items }`, or an instance,
/// `part NAME = PART(ARGS) { SETTINGS };`.
fn parse_part(input: ParseStream) -> syn::Result<Item> {
    input.parse::<kw::part>()?;
    let name: Ident = input.parse()?;
    if input.peek(syn::token::Paren) {
        let content;
        parenthesized!(content in input);
        let ports = content.parse_terminated(parse_declaration, Token![,])?;
        let body;
        braced!(body in input);
        let mut items = Vec::new();
        while !body.is_empty() {
            items.push(parse_item(&body)?);
        }
        let ports = ports.into_iter().collect();
        return Ok(Item::PartDef(PartDef { name, ports, items }));
    }
    let subscript = parse_subscript(input, Place::Name)?;
    input.parse::<Token![=]>()?;
    let part: Ident = input.parse()?;
    let content;
    let paren = parenthesized!(content in input);
    let arguments = content.parse_terminated(Expr::parse, Token![,])?;
    let mut settings = Vec::new();
    if input.peek(syn::token::Brace) {
        settings = parse_braced_list(input, |entry| {
            let name: Ident = entry.parse()?;
            entry.parse::<Token![=]>()?;
            Ok((name, entry.parse()?))
        })?;
    }
    input.parse::<Token![;]>()?;
    Ok(Item::PartInstance(PartInstance {
        name,
        subscript,
        part,
        arguments: arguments.into_iter().collect(),
        arguments_span: paren.span.join(),
        settings,
    }))
}

fn parse_unit(input: ParseStream) -> syn::Result<Option<UnitText>> {
    if !input.peek(syn::token::Bracket) {
        return Ok(None);
    }
    let content;
    let bracket = bracketed!(content in input);
    let tokens: TokenStream = content.parse()?;
    let text = tokens.to_string();
    Ok(Some(UnitText {
        text: text.split_whitespace().collect::<String>(),
        span: bracket.span.join(),
    }))
}

fn parse_parameter(input: ParseStream) -> syn::Result<ParameterDecl> {
    let decl = parse_declaration(input)?;
    let value = if input.peek(Token![=]) {
        input.parse::<Token![=]>()?;
        Some(input.parse()?)
    } else {
        None
    };
    Ok(ParameterDecl { decl, value })
}

fn parse_input(input: ParseStream) -> syn::Result<InputDecl> {
    let attrs = input.call(Attribute::parse_outer)?;
    let doc = doc_lines(&attrs)?;
    let name: Ident = input.parse()?;
    let subscript = parse_subscript(input, Place::Block)?;
    let content;
    parenthesized!(content in input);
    let mut arguments = Vec::new();
    while !content.is_empty() {
        arguments.push(parse_declaration(&content)?);
        if content.is_empty() {
            break;
        }
        content.parse::<Token![,]>()?;
    }
    let unit = parse_unit(input)?;
    let mut derivatives = Vec::new();
    let mut supplied = Vec::new();
    if input.peek(syn::token::Brace) {
        let body;
        braced!(body in input);
        while !body.is_empty() {
            body.parse::<kw::d>()?;
            let arg;
            parenthesized!(arg in body);
            let argument: Ident = arg.parse()?;
            if body.is_empty() || body.peek(Token![,]) {
                supplied.push(argument);
            } else {
                body.parse::<Token![=]>()?;
                let value: Expr = body.parse()?;
                derivatives.push((argument, value));
            }
            if body.is_empty() {
                break;
            }
            body.parse::<Token![,]>()?;
        }
    }
    Ok(InputDecl {
        decl: Declaration {
            doc,
            name,
            subscript,
            unit,
        },
        arguments,
        derivatives,
        supplied,
    })
}

/// `hand_derived { convention = …; small_angle_order = …; symbols {…} assume {…} q = …; force q = …; }`
fn parse_hand_section(input: ParseStream, doc: Vec<String>) -> syn::Result<Item> {
    let keyword = input.parse::<kw::hand_derived>()?.span;
    let body;
    braced!(body in input);
    let mut section = HandSection {
        keyword,
        doc,
        convention: None,
        small_angle_order: None,
        symbols: Vec::new(),
        assumptions: Vec::new(),
        equations: Vec::new(),
        forces: Vec::new(),
    };
    while !body.is_empty() {
        // Comments before entries arrive as doc attributes only for `///`; skip them.
        body.call(Attribute::parse_outer)?;
        if body.peek(kw::convention) {
            body.parse::<kw::convention>()?;
            body.parse::<Token![=]>()?;
            section.convention = Some(body.parse()?);
            body.parse::<Token![;]>()?;
        } else if body.peek(kw::small_angle_order) {
            body.parse::<kw::small_angle_order>()?;
            body.parse::<Token![=]>()?;
            section.small_angle_order = Some(body.parse()?);
            body.parse::<Token![;]>()?;
        } else if body.peek(kw::symbols) || body.peek(kw::assume) {
            let is_symbols = body.peek(kw::symbols);
            if is_symbols {
                body.parse::<kw::symbols>()?;
            } else {
                body.parse::<kw::assume>()?;
            }
            let pairs = parse_braced_list(&body, |s: ParseStream| {
                let name: Ident = s.parse()?;
                s.parse::<Token![=]>()?;
                Ok((name, s.parse::<Expr>()?))
            })?;
            if is_symbols {
                section.symbols.extend(pairs);
            } else {
                section.assumptions.extend(pairs);
            }
        } else if body.peek(kw::force) {
            body.parse::<kw::force>()?;
            let coordinate: Ident = body.parse()?;
            body.parse::<Token![=]>()?;
            section.forces.push((coordinate, body.parse()?));
            body.parse::<Token![;]>()?;
        } else {
            let coordinate: Ident = body.parse()?;
            body.parse::<Token![=]>()?;
            section.equations.push((coordinate, body.parse()?));
            body.parse::<Token![;]>()?;
        }
    }
    Ok(Item::HandDerived(section))
}
