//! Rust code for a compiled model: a parameter struct implementing the
//! runtime's `LagrangianSystem<N>`.
//!
//! The method bodies perform exactly the operations of the optimized program,
//! in the same order, so compiled and interpreted results agree bit for bit
//! up to how the platform's `powi` is expanded. A temporary used once is
//! written inline; parentheses follow the program's evaluation order.

use super::names::Names;
use crate::Compiled;
use crate::program::{Op, Reg, Routine, RoutineKind};
use lagrangian_model::layout::{Energies, JACOBIAN_BLOCKS, mass_entries};
use proc_macro2::Literal;
use proc_macro2::{Ident, Span, TokenStream};
use quote::{ToTokens, quote};
use rustc_hash::FxHashMap;

/// How generated code refers to its surroundings.
#[derive(Clone, Debug)]
pub struct RustOptions {
    /// Path of the runtime crate (`::lagrangian` for users of the umbrella
    /// crate, `::lagrangian_model` or `crate` inside the workspace).
    pub runtime: TokenStream,
}

impl Default for RustOptions {
    fn default() -> Self {
        RustOptions {
            runtime: quote!(::lagrangian),
        }
    }
}

/// Binding strength of an emitted expression.
#[derive(Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Debug)]
enum Prec {
    Sum,
    Product,
    Unary,
    Atom,
}

#[derive(Clone)]
struct Code {
    tokens: TokenStream,
    prec: Prec,
    /// A literal cannot be a method receiver without parentheses.
    literal: bool,
}

impl Code {
    fn atom(tokens: TokenStream) -> Code {
        Code {
            tokens,
            prec: Prec::Atom,
            literal: false,
        }
    }

    /// The tokens, parenthesized unless they bind at least as tightly as `min`.
    fn at(&self, min: Prec) -> TokenStream {
        let t = &self.tokens;
        if self.prec >= min {
            t.clone()
        } else {
            quote!((#t))
        }
    }

    fn receiver(&self) -> TokenStream {
        let t = &self.tokens;
        if self.prec == Prec::Atom && !self.literal {
            t.clone()
        } else {
            quote!((#t))
        }
    }
}

/// The whole generated model: struct, `Default`, constants and trait impl.
pub fn emit_model(compiled: &Compiled, options: &RustOptions) -> TokenStream {
    crate::depth::with_large_stack(|| emit_model_deep(compiled, options))
}

fn emit_model_deep(compiled: &Compiled, options: &RustOptions) -> TokenStream {
    let model = &compiled.model;
    let names = Names::new(model);
    let rt = &options.runtime;
    let n = Literal::usize_unsuffixed(model.dimension());
    let ty = super::names::ident(&model.name);
    let model_name = &model.name;

    let mut struct_doc: Vec<String> = model.doc.clone();
    if !struct_doc.is_empty() {
        struct_doc.push(String::new());
    }
    struct_doc.push(format!(
        "Derived by `lagrangian` from the spec: {} coordinate(s) ({}), equations `M(q) q̈ = f(q, q̇, t)`.",
        model.dimension(),
        model.coordinates.iter().map(|c| format!("`{}`", c.name)).collect::<Vec<_>>().join(", ")
    ));
    let fields = model.parameters.iter().enumerate().map(|(i, p)| {
        let field = &names.fields[i];
        let mut doc = p.doc.clone();
        let unit = p
            .unit
            .as_ref()
            .map(|u| format!(" [{}]", u.text))
            .unwrap_or_default();
        doc.push(format!("Default: {:?}{unit}.", p.default));
        let doc = doc_lines(&doc);
        quote! { #(#[doc = #doc])* pub #field: f64 }
    });
    let defaults = model.parameters.iter().enumerate().map(|(i, p)| {
        let field = &names.fields[i];
        let v = float_literal(p.default);
        quote! { #field: #v }
    });
    let input_consts = model.inputs.iter().enumerate().map(|(k, input)| {
        let name = &names.input_consts[k];
        let mut doc = vec![format!(
            "Index of input function `{}({})` in `InputFunctions::value` calls.",
            input.name,
            input
                .arguments
                .iter()
                .map(|a| a.0.as_str())
                .collect::<Vec<_>>()
                .join(", ")
        )];
        doc.extend(input.doc.iter().cloned());
        let doc = doc_lines(&doc);
        let k = Literal::usize_unsuffixed(k);
        quote! { #(#[doc = #doc])* pub const #name: usize = #k; }
    });
    let coordinate_names: Vec<&str> = model.coordinates.iter().map(|c| c.name.as_str()).collect();
    let parameter_names: Vec<&str> = model.parameters.iter().map(|p| p.name.as_str()).collect();
    let input_names: Vec<&str> = model.inputs.iter().map(|i| i.name.as_str()).collect();
    let field_list = &names.fields;
    let parameter_arms = names.fields.iter().zip(&parameter_names).map(|(f, p)| {
        quote! { #p => self.#f = value, }
    });

    let dynamics = routine_method(compiled, &names, RoutineKind::Dynamics, rt);
    let energies = routine_method(compiled, &names, RoutineKind::Energies, rt);
    let dynamics_and_powers = routine_method(compiled, &names, RoutineKind::DynamicsAndPowers, rt);
    let jacobians = routine_method(compiled, &names, RoutineKind::Jacobians, rt);
    let arguments = routine_method(compiled, &names, RoutineKind::InputArguments, rt);
    let sites = compiled.program.input_sites.iter().map(|&(input, arity)| {
        let (input, arity) = (
            Literal::usize_unsuffixed(input),
            Literal::usize_unsuffixed(arity),
        );
        quote!((#input, #arity))
    });

    let struct_doc = doc_lines(&struct_doc);
    quote! {
        #(#[doc = #struct_doc])*
        #[derive(Debug, Clone, Copy, PartialEq)]
        #[allow(non_snake_case, non_camel_case_types)]
        pub struct #ty {
            #(#fields,)*
        }

        #[automatically_derived]
        impl ::core::default::Default for #ty {
            fn default() -> Self {
                Self { #(#defaults,)* }
            }
        }

        #[allow(non_camel_case_types)]
        impl #ty {
            /// Names of the generalized coordinates, in order.
            pub const COORDINATES: [&'static str; #n] = [#(#coordinate_names),*];
            /// Names of the parameters (the fields), in order.
            pub const PARAMETERS: &'static [&'static str] = &[#(#parameter_names),*];
            /// Names of the input functions, in order of their indices.
            pub const INPUTS: &'static [&'static str] = &[#(#input_names),*];
            #(#input_consts)*
        }

        #[automatically_derived]
        #[allow(unused_variables, non_snake_case, clippy::all, clippy::pedantic, clippy::nursery)]
        impl #rt::LagrangianSystem<#n> for #ty {
            fn model_name(&self) -> &str {
                #model_name
            }

            fn coordinate_names(&self) -> ::std::vec::Vec<&str> {
                ::std::vec::Vec::from(Self::COORDINATES)
            }

            fn parameter_names(&self) -> ::std::vec::Vec<&str> {
                Self::PARAMETERS.to_vec()
            }

            fn input_names(&self) -> ::std::vec::Vec<&str> {
                Self::INPUTS.to_vec()
            }

            fn parameters(&self) -> ::std::vec::Vec<f64> {
                ::std::vec![#(self.#field_list),*]
            }

            fn set_parameter(&mut self, name: &str, value: f64) -> ::core::result::Result<(), #rt::ModelError> {
                match name {
                    #(#parameter_arms)*
                    _ => return ::core::result::Result::Err(#rt::ModelError::unknown_parameter(name, Self::PARAMETERS)),
                }
                ::core::result::Result::Ok(())
            }

            fn input_sites(&self) -> &'static [(usize, usize)] {
                &[#(#sites),*]
            }

            #dynamics
            #energies
            #dynamics_and_powers
            #jacobians
            #arguments
        }
    }
}

/// A `LagrangianSystem` method evaluating one routine of the program.
fn routine_method(
    compiled: &Compiled,
    names: &Names,
    kind: RoutineKind,
    rt: &TokenStream,
) -> TokenStream {
    let n = compiled.model.dimension();
    let Some(routine) = compiled.program.routine(kind) else {
        return TokenStream::new();
    };
    let dim = Literal::usize_unsuffixed(n);
    let vector = quote!(#rt::nalgebra::SVector<f64, #dim>);
    let matrix = quote!(#rt::nalgebra::SMatrix<f64, #dim, #dim>);
    let (statements, outputs) = routine_body(compiled, names, routine);
    match kind {
        RoutineKind::Dynamics => {
            let writes = dynamics_writes(n, &outputs);
            quote! {
                #[inline]
                fn mass_matrix_and_forcing<I: #rt::InputFunctions + ?Sized>(
                    &self, t: f64, q: &#vector, qd: &#vector, inputs: &I,
                    mass: &mut #matrix, forcing: &mut #vector,
                ) {
                    #(#statements)*
                    #(#writes)*
                }
            }
        }
        RoutineKind::DynamicsAndPowers => {
            let writes = dynamics_writes(n, &outputs);
            let (damping_power, external_power) =
                (&outputs[outputs.len() - 2], &outputs[outputs.len() - 1]);
            quote! {
                #[inline]
                fn mass_matrix_forcing_and_powers<I: #rt::InputFunctions + ?Sized>(
                    &self, t: f64, q: &#vector, qd: &#vector, inputs: &I,
                    mass: &mut #matrix, forcing: &mut #vector,
                ) -> [f64; 2] {
                    #(#statements)*
                    #(#writes)*
                    [#damping_power, #external_power]
                }
            }
        }
        RoutineKind::Energies => {
            let fields = Energies::FIELDS.map(|f| Ident::new(f, Span::call_site()));
            let values = &outputs[..fields.len()];
            quote! {
                fn energies<I: #rt::InputFunctions + ?Sized>(
                    &self, t: f64, q: &#vector, qd: &#vector, inputs: &I,
                ) -> #rt::Energies {
                    #(#statements)*
                    #rt::Energies { #(#fields: #values,)* }
                }
            }
        }
        RoutineKind::InputArguments => {
            let writes = outputs.iter().enumerate().map(|(k, value)| {
                let k = Literal::usize_unsuffixed(k);
                quote! { out[#k] = #value; }
            });
            quote! {
                fn input_arguments(&self, t: f64, q: &#vector, qd: &#vector, out: &mut [f64]) {
                    #(#statements)*
                    #(#writes)*
                }
            }
        }
        RoutineKind::Jacobians => {
            let mut writes = Vec::new();
            for (b, field) in JACOBIAN_BLOCKS.iter().enumerate() {
                let field = Ident::new(field, Span::call_site());
                for i in 0..n {
                    for k in 0..n {
                        let value = &outputs[b * n * n + i * n + k];
                        let (li, lk) = (Literal::usize_unsuffixed(i), Literal::usize_unsuffixed(k));
                        writes.push(quote! { out.#field[(#li, #lk)] = #value; });
                    }
                }
            }
            quote! {
                fn jacobians<I: #rt::InputFunctions + ?Sized>(
                    &self, t: f64, q: &#vector, qd: &#vector, qdd: &#vector, inputs: &I,
                    out: &mut #rt::Jacobians<#dim>,
                ) -> ::core::result::Result<(), #rt::ModelError> {
                    #(#statements)*
                    #(#writes)*
                    ::core::result::Result::Ok(())
                }
            }
        }
    }
}

/// Writes of the dynamics outputs: the upper triangle of `M` (mirrored),
/// then `f`.
fn dynamics_writes(n: usize, outputs: &[TokenStream]) -> Vec<TokenStream> {
    let mut writes = Vec::new();
    let mut k = 0;
    for (i, j) in mass_entries(n) {
        let value = &outputs[k];
        let (li, lj) = (Literal::usize_unsuffixed(i), Literal::usize_unsuffixed(j));
        writes.push(quote! { mass[(#li, #lj)] = #value; });
        if i != j {
            writes.push(quote! { mass[(#lj, #li)] = mass[(#li, #lj)]; });
        }
        k += 1;
    }
    for i in 0..n {
        let value = &outputs[k + i];
        let li = Literal::usize_unsuffixed(i);
        writes.push(quote! { forcing[#li] = #value; });
    }
    writes
}

/// `let` statements of a routine and the expressions of its outputs.
fn routine_body(
    compiled: &Compiled,
    names: &Names,
    routine: &Routine,
) -> (Vec<TokenStream>, Vec<TokenStream>) {
    let ops = &compiled.program.ops;
    let mut uses = vec![0u32; ops.len()];
    for &r in &routine.ops {
        for operand in ops[r as usize].operands() {
            uses[operand as usize] += 1;
        }
    }
    for &r in &routine.outputs {
        uses[r as usize] += 1;
    }
    let mut code: Vec<Option<Code>> = vec![None; ops.len()];
    let mut loads = Vec::new();
    let mut statements = Vec::new();
    let mut temporaries = 0usize;
    // `sin x` and `cos x` of one argument are computed together by `sin_cos`.
    let mut partner: FxHashMap<Reg, Reg> = FxHashMap::default();
    {
        let mut sines = FxHashMap::default();
        let mut cosines = FxHashMap::default();
        for &r in &routine.ops {
            match ops[r as usize] {
                Op::Sin(a) => sines.insert(a, r),
                Op::Cos(a) => cosines.insert(a, r),
                _ => None,
            };
        }
        for (a, &sin) in &sines {
            if let Some(&cos) = cosines.get(a) {
                partner.insert(sin, cos);
                partner.insert(cos, sin);
            }
        }
    }
    for &r in &routine.ops {
        if code[r as usize].is_some() {
            continue; // the cosine or sine of a `sin_cos` pair
        }
        if let (Some(&other), Op::Sin(a) | Op::Cos(a)) = (partner.get(&r), &ops[r as usize]) {
            let (sin, cos) = if matches!(ops[r as usize], Op::Sin(_)) {
                (r, other)
            } else {
                (other, r)
            };
            let argument = code[*a as usize]
                .clone()
                .map_or(quote!(f64::NAN), |c| c.receiver());
            let (s, c) = (
                names.temporary(temporaries),
                names.temporary(temporaries + 1),
            );
            temporaries += 2;
            statements.push(quote! { let (#s, #c) = #argument.sin_cos(); });
            code[sin as usize] = Some(Code::atom(quote!(#s)));
            code[cos as usize] = Some(Code::atom(quote!(#c)));
            continue;
        }
        let get = |code: &[Option<Code>], x: &Reg| {
            code[*x as usize]
                .clone()
                .unwrap_or_else(|| Code::atom(quote!(f64::NAN)))
        };
        let expr = match &ops[r as usize] {
            Op::Const(v) => Code {
                tokens: float_literal(*v),
                prec: Prec::Atom,
                literal: true,
            },
            load @ (Op::Parameter(_)
            | Op::Coordinate(_)
            | Op::Velocity(_)
            | Op::Acceleration(_)) => {
                let (local, source) = names.load(load);
                loads.push((load_order(load), quote! { let #local = #source; }));
                code[r as usize] = Some(Code::atom(quote!(#local)));
                continue;
            }
            Op::Time => Code::atom(quote!(t)),
            Op::Input { index, args } => {
                let index = Literal::usize_unsuffixed(*index as usize);
                let args = args.iter().map(|a| get(&code, a).at(Prec::Sum));
                Code::atom(quote!(inputs.value(#index, &[#(#args),*])))
            }
            Op::Add(a, b) => binary(&get(&code, a), quote!(+), &get(&code, b), Prec::Sum),
            Op::Sub(a, b) => binary(&get(&code, a), quote!(-), &get(&code, b), Prec::Sum),
            Op::Mul(a, b) => binary(&get(&code, a), quote!(*), &get(&code, b), Prec::Product),
            Op::Div(a, b) => binary(&get(&code, a), quote!(/), &get(&code, b), Prec::Product),
            Op::Neg(a) => {
                let x = get(&code, a).at(Prec::Unary);
                Code {
                    tokens: quote!(-#x),
                    prec: Prec::Unary,
                    literal: false,
                }
            }
            Op::Sin(a) => method(&get(&code, a), "sin", None),
            Op::Cos(a) => method(&get(&code, a), "cos", None),
            Op::Exp(a) => method(&get(&code, a), "exp", None),
            Op::Ln(a) => method(&get(&code, a), "ln", None),
            Op::Sqrt(a) => method(&get(&code, a), "sqrt", None),
            Op::Powi(a, k) => method(
                &get(&code, a),
                "powi",
                Some(Literal::i32_unsuffixed(*k).into_token_stream()),
            ),
            Op::Powf(a, x) => method(&get(&code, a), "powf", Some(float_literal(*x))),
        };
        let inline = uses[r as usize] <= 1 && !matches!(ops[r as usize], Op::Input { .. });
        if inline || expr.literal || expr.tokens.to_string() == "t" {
            code[r as usize] = Some(expr);
        } else {
            let name = names.temporary(temporaries);
            temporaries += 1;
            let tokens = &expr.tokens;
            statements.push(quote! { let #name = #tokens; });
            code[r as usize] = Some(Code::atom(quote!(#name)));
        }
    }
    let outputs = routine
        .outputs
        .iter()
        .map(|r| {
            code[*r as usize]
                .as_ref()
                .map_or_else(|| quote!(f64::NAN), |c| c.tokens.clone())
        })
        .collect();
    loads.sort_by_key(|(order, _)| *order);
    let mut body: Vec<TokenStream> = loads.into_iter().map(|(_, s)| s).collect();
    body.extend(statements);
    (body, outputs)
}

/// Parameters first, then coordinates, velocities and accelerations, by index.
fn load_order(op: &Op) -> (u8, u32) {
    match op {
        Op::Parameter(i) => (0, *i),
        Op::Coordinate(i) => (1, *i),
        Op::Velocity(i) => (2, *i),
        Op::Acceleration(i) => (3, *i),
        _ => (4, 0),
    }
}

/// Doc attribute texts: `///` lines read best with a leading space.
fn doc_lines(lines: &[String]) -> Vec<String> {
    lines
        .iter()
        .map(|l| {
            if l.is_empty() {
                String::new()
            } else {
                format!(" {l}")
            }
        })
        .collect()
}

fn binary(a: &Code, op: TokenStream, b: &Code, prec: Prec) -> Code {
    // Left-associative: the right operand must bind strictly tighter.
    let right_min = match prec {
        Prec::Sum => Prec::Product,
        _ => Prec::Unary,
    };
    let (x, y) = (a.at(prec), b.at(right_min));
    Code {
        tokens: quote!(#x #op #y),
        prec,
        literal: false,
    }
}

fn method(receiver: &Code, name: &str, arg: Option<TokenStream>) -> Code {
    let r = receiver.receiver();
    let m = Ident::new(name, Span::call_site());
    Code::atom(match arg {
        Some(a) => quote!(#r.#m(#a)),
        None => quote!(#r.#m()),
    })
}

/// A float literal that reads back as exactly `v` (π by name).
pub(crate) fn float_literal(v: f64) -> TokenStream {
    if v == std::f64::consts::PI {
        return quote!(::core::f64::consts::PI);
    }
    if !v.is_finite() {
        return quote!(f64::NAN);
    }
    let text = format!("{v:?}");
    let text = if text.contains(['.', 'e']) {
        text
    } else {
        format!("{text}.0")
    };
    text.parse().unwrap_or_else(|_| quote!(f64::NAN))
}

/// The generated model formatted as a file, with an `@generated` header.
///
/// Takes the model by value: its expression store is freed before the code
/// is parsed and formatted (at n = 40: 218 → 177 MB peak resident).
pub fn emit_file(compiled: Compiled, options: &RustOptions, header: &str) -> String {
    let text = emit_model(&compiled, options).to_string();
    drop(compiled);
    let body = match syn::parse_str::<syn::File>(&text) {
        Ok(file) => prettyplease::unparse(&file),
        // The emitter produced something that is not a Rust file (a bug):
        // show it unformatted rather than hide it.
        Err(_) => text,
    };
    format!("{header}\n{body}")
}
