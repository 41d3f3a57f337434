//! Rust code for a compiled model: a parameter struct implementing the
//! runtime's `LagrangianSystem<N>`.
//!
//! Each method body is the [`schedule`](super::schedule) of a program routine
//! in Rust's syntax ([`Backend`]), with the outputs placed by their slots
//! (`mass[(i, j)]`, `forcing[i]`, the fields of `Energies` and `Jacobians`).
//! The bodies perform exactly the operations of the optimized program, in the
//! same order, so compiled and interpreted results agree bit for bit up to
//! how the platform's `powi` is expanded.

use super::backend::{self, Backend, Fragment};
use super::names::{Locals, ident, input_constants};
use super::schedule::{BinaryOp, Function, Load, Schedule, schedule};
use crate::Compiled;
use crate::expr::{Func, Precedence};
use crate::program::RoutineKind;
use crate::spec::Model;
use lagrangian_runtime::layout::{Energy, OutputSlot};
use proc_macro2::{Ident, Literal, TokenStream};
use quote::{ToTokens, quote};

/// How generated code refers to its surroundings.
#[derive(Clone, Debug)]
pub struct RustOptions {
    /// Path of the runtime crate (`::lagrangian` for users of the umbrella
    /// crate, `::lagrangian_runtime` or `crate` inside the workspace).
    pub runtime: TokenStream,
}

impl Default for RustOptions {
    fn default() -> Self {
        RustOptions {
            runtime: quote!(::lagrangian),
        }
    }
}

/// The whole generated model: struct, `Default`, constants and trait impl.
pub fn emit_model(compiled: &Compiled, options: &RustOptions) -> TokenStream {
    crate::depth::with_large_stack(|| emit_model_deep(compiled, options))
}

/// Names of the generated methods' parameters, which locals must not shadow.
const TAKEN: &[&str] = &[
    "t", "q", "qd", "qdd", "inputs", "mass", "forcing", "out", "self", "Self", "I", "f64", "value",
    "name",
];

/// The identifiers of a generated model.
struct Names {
    /// Struct fields, one per parameter (the parameter's own name).
    fields: Vec<Ident>,
    /// `INPUT_<NAME>` constants, one per input function.
    input_consts: Vec<Ident>,
    /// The locals of the method bodies.
    locals: Locals,
}

impl Names {
    fn new(model: &Model) -> Names {
        let inputs: Vec<String> = model.inputs.iter().map(|i| i.name.clone()).collect();
        let input_consts = input_constants(&inputs);
        Names {
            fields: model.parameters.iter().map(|p| ident(&p.name)).collect(),
            input_consts,
            locals: Locals::new(model, TAKEN, str::to_string),
        }
    }
}

fn emit_model_deep(compiled: &Compiled, options: &RustOptions) -> TokenStream {
    let model = &compiled.model;
    let names = Names::new(model);
    let ty = ident(&model.name);
    let definition = struct_definition(model, &names, &ty);
    let constants = associated_constants(model, &names, &ty);
    let implementation = trait_impl(compiled, &names, &ty, &options.runtime);
    quote! {
        #definition
        #constants
        #implementation
    }
}

/// The parameter struct and its `Default` (the spec's default values).
fn struct_definition(model: &Model, names: &Names, ty: &Ident) -> TokenStream {
    let mut struct_doc: Vec<String> = model.doc.clone();
    if !struct_doc.is_empty() {
        struct_doc.push(String::new());
    }
    struct_doc.push(format!(
        "Derived by `lagrangian` from the spec: {} coordinate(s) ({}), equations `M(q) q̈ = f(q, q̇, t)`.",
        model.dimension(),
        model.coordinates.iter().map(|c| format!("`{}`", c.name)).collect::<Vec<_>>().join(", ")
    ));
    let fields = model
        .parameters
        .iter()
        .zip(&names.fields)
        .map(|(p, field)| {
            let mut doc = p.doc.clone();
            let unit = (p.unit.as_ref())
                .map(|u| format!(" \\[{}\\]", u.text))
                .unwrap_or_default();
            doc.push(format!("Default: {:?}{unit}.", p.default));
            let doc = doc_lines(&doc);
            quote! { #(#[doc = #doc])* pub #field: f64 }
        });
    let defaults = model
        .parameters
        .iter()
        .zip(&names.fields)
        .map(|(p, field)| {
            let v = float_literal(p.default);
            quote! { #field: #v }
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
    }
}

/// The names of the coordinates, parameters and inputs, and the index
/// constant of each input function.
fn associated_constants(model: &Model, names: &Names, ty: &Ident) -> TokenStream {
    let n = Literal::usize_unsuffixed(model.dimension());
    let input_consts = model.inputs.iter().enumerate().map(|(k, input)| {
        let name = &names.input_consts[k];
        let arguments: Vec<&str> = input.arguments.iter().map(|a| a.0.as_str()).collect();
        let mut doc = vec![format!(
            "Index of input function `{}({})` in `InputFunctions::value` calls.",
            input.name,
            arguments.join(", ")
        )];
        doc.extend(input.doc.iter().cloned());
        let doc = doc_lines(&doc);
        let k = Literal::usize_unsuffixed(k);
        quote! { #(#[doc = #doc])* pub const #name: usize = #k; }
    });
    let coordinate_names = model.coordinates.iter().map(|c| c.name.as_str());
    let parameter_names = model.parameters.iter().map(|p| p.name.as_str());
    let input_names = model.inputs.iter().map(|i| i.name.as_str());
    let outputs = output_names_constant(model);
    let constraints = constraint_names_constant(model);
    quote! {
        #[allow(non_camel_case_types)]
        impl #ty {
            /// Names of the generalized coordinates, in order.
            pub const COORDINATES: [&'static str; #n] = [#(#coordinate_names),*];
            /// Names of the parameters (the fields), in order.
            pub const PARAMETERS: &'static [&'static str] = &[#(#parameter_names),*];
            /// Names of the input functions, in order of their indices.
            pub const INPUTS: &'static [&'static str] = &[#(#input_names),*];
            #outputs
            #constraints
            #(#input_consts)*
        }
    }
}

/// `OUTPUTS`, the names of the outputs, with their units and doc lines in
/// its doc; nothing for a model without outputs (whose code stays as it was).
fn output_names_constant(model: &Model) -> TokenStream {
    if model.outputs.is_empty() {
        return TokenStream::new();
    }
    let mut doc = vec!["Names of the outputs (`LagrangianSystem::outputs`), in order:".to_string()];
    for o in &model.outputs {
        let unit = (o.unit.as_ref())
            .map(|u| format!(" \\[{}\\]", u.text))
            .unwrap_or_default();
        let text = o.doc.join(" ");
        let separator = if text.is_empty() { "" } else { ": " };
        doc.push(format!("- `{}`{unit}{separator}{text}", o.name));
    }
    let doc = doc_lines(&doc);
    let names = model.outputs.iter().map(|o| o.name.as_str());
    quote! {
        #(#[doc = #doc])*
        pub const OUTPUTS: &'static [&'static str] = &[#(#names),*];
    }
}

/// `output_names`, for a model with outputs (the trait's default, no
/// names, is right for the others).
fn output_names_method(model: &Model) -> TokenStream {
    if model.outputs.is_empty() {
        return TokenStream::new();
    }
    quote! {
        fn output_names(&self) -> ::std::vec::Vec<&str> {
            Self::OUTPUTS.to_vec()
        }
    }
}

/// `CONSTRAINTS`, the names of the constraints, with their doc lines in its
/// doc; nothing for a model without constraints (whose code stays as it was).
fn constraint_names_constant(model: &Model) -> TokenStream {
    if model.constraints.is_empty() {
        return TokenStream::new();
    }
    let mut doc = vec![
        "Names of the holonomic constraints (`LagrangianSystem::constraints`), in order:"
            .to_string(),
    ];
    for c in &model.constraints {
        let text = c.doc.join(" ");
        let separator = if text.is_empty() { "" } else { ": " };
        doc.push(format!("- `{}`{separator}{text}", c.name));
    }
    let doc = doc_lines(&doc);
    let names = model.constraints.iter().map(|c| c.name.as_str());
    quote! {
        #(#[doc = #doc])*
        pub const CONSTRAINTS: &'static [&'static str] = &[#(#names),*];
    }
}

/// `constraint_names`, for a model with constraints (the trait's default,
/// no names, is right for the others).
fn constraint_names_method(model: &Model) -> TokenStream {
    if model.constraints.is_empty() {
        return TokenStream::new();
    }
    quote! {
        fn constraint_names(&self) -> ::std::vec::Vec<&str> {
            Self::CONSTRAINTS.to_vec()
        }
    }
}

/// `impl LagrangianSystem<N>`: the names, parameter access and the routines.
fn trait_impl(compiled: &Compiled, names: &Names, ty: &Ident, rt: &TokenStream) -> TokenStream {
    let model = &compiled.model;
    let n = Literal::usize_unsuffixed(model.dimension());
    let model_name = &model.name;
    let field_list = &names.fields;
    let parameter_arms = names.fields.iter().zip(&model.parameters).map(|(f, p)| {
        let p = p.name.as_str();
        quote! { #p => self.#f = value, }
    });
    let sites = compiled.program.input_sites.iter().map(|&(input, arity)| {
        let (input, arity) = (
            Literal::usize_unsuffixed(input),
            Literal::usize_unsuffixed(arity),
        );
        quote!((#input, #arity))
    });
    let routines = [
        RoutineKind::Dynamics,
        RoutineKind::Energies,
        RoutineKind::DynamicsAndPowers,
        RoutineKind::Jacobians,
        RoutineKind::InputArguments,
        RoutineKind::Outputs,
        RoutineKind::Switching,
        RoutineKind::Constraints,
    ]
    .map(|kind| routine_method(compiled, names, kind, rt));
    let output_names = output_names_method(model);
    let constraint_names = constraint_names_method(model);
    let solve = super::solve::solve_mass_method(&compiled.program, rt);
    quote! {
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

            #output_names
            #constraint_names
            #(#routines)*
            #solve
        }
    }
}

/// A `LagrangianSystem` method evaluating one routine of the program (none
/// when the program lacks the routine).
fn routine_method(
    compiled: &Compiled,
    names: &Names,
    kind: RoutineKind,
    rt: &TokenStream,
) -> TokenStream {
    let Some(routine) = compiled.program.routine(kind) else {
        return TokenStream::new();
    };
    let schedule = schedule(&compiled.program, routine);
    let body = backend::body(&RustSyntax { names, runtime: rt }, &schedule);
    let statements = &body.statements;
    let outputs = place_outputs(&schedule, body.outputs);
    let (writes, returned) = (&outputs.writes, outputs.returned.iter().map(|(_, v)| v));
    let dim = Literal::usize_unsuffixed(compiled.model.dimension());
    let vector = quote!(#rt::nalgebra::SVector<f64, #dim>);
    let matrix = quote!(#rt::nalgebra::SMatrix<f64, #dim, #dim>);
    match kind {
        RoutineKind::Dynamics => quote! {
            #[inline]
            fn mass_matrix_and_forcing<I: #rt::InputFunctions + ?Sized>(
                &self, t: f64, q: &#vector, qd: &#vector, inputs: &I,
                mass: &mut #matrix, forcing: &mut #vector,
            ) {
                #(#statements)*
                #(#writes)*
            }
        },
        RoutineKind::DynamicsAndPowers => quote! {
            #[inline]
            fn mass_matrix_forcing_and_powers<I: #rt::InputFunctions + ?Sized>(
                &self, t: f64, q: &#vector, qd: &#vector, inputs: &I,
                mass: &mut #matrix, forcing: &mut #vector,
            ) -> [f64; 2] {
                #(#statements)*
                #(#writes)*
                [#(#returned),*]
            }
        },
        RoutineKind::Energies => {
            let fields = outputs.returned.iter().map(|(e, _)| ident(e.field()));
            quote! {
                fn energies<I: #rt::InputFunctions + ?Sized>(
                    &self, t: f64, q: &#vector, qd: &#vector, inputs: &I,
                ) -> #rt::Energies {
                    #(#statements)*
                    #rt::Energies { #(#fields: #returned,)* }
                }
            }
        }
        RoutineKind::InputArguments => quote! {
            fn input_arguments<I: #rt::InputFunctions + ?Sized>(
                &self, t: f64, q: &#vector, qd: &#vector, inputs: &I, out: &mut [f64],
            ) {
                #(#statements)*
                #(#writes)*
            }
        },
        RoutineKind::Outputs => quote! {
            fn outputs<I: #rt::InputFunctions + ?Sized>(
                &self, t: f64, q: &#vector, qd: &#vector, qdd: &#vector, inputs: &I,
                out: &mut [f64],
            ) {
                #(#statements)*
                #(#writes)*
            }
        },
        RoutineKind::Switching => {
            let count = Literal::usize_unsuffixed(routine.outputs.len());
            quote! {
                fn switching_count(&self) -> usize {
                    #count
                }

                fn switching_functions<I: #rt::InputFunctions + ?Sized>(
                    &self, t: f64, q: &#vector, qd: &#vector, inputs: &I, out: &mut [f64],
                ) {
                    #(#statements)*
                    #(#writes)*
                }
            }
        }
        RoutineKind::Constraints => quote! {
            fn constraints<I: #rt::InputFunctions + ?Sized>(
                &self, t: f64, q: &#vector, qd: &#vector, inputs: &I, out: &mut [f64],
            ) {
                #(#statements)*
                #(#writes)*
            }
        },
        RoutineKind::Jacobians => quote! {
            fn jacobians<I: #rt::InputFunctions + ?Sized>(
                &self, t: f64, q: &#vector, qd: &#vector, qdd: &#vector, inputs: &I,
                out: &mut #rt::Jacobians<#dim>,
            ) -> ::core::result::Result<(), #rt::ModelError> {
                #(#statements)*
                #(#writes)*
                ::core::result::Result::Ok(())
            }
        },
    }
}

/// The outputs of a method: written to the arguments, or returned.
struct PlacedOutputs {
    /// Assignments to `mass`, `forcing` or `out`.
    writes: Vec<TokenStream>,
    /// The energies and powers a method returns, in output order.
    returned: Vec<(Energy, TokenStream)>,
}

/// Each output written to its slot: `M` entries mirrored into the lower
/// triangle, energies and powers returned.
fn place_outputs(schedule: &Schedule, values: Vec<TokenStream>) -> PlacedOutputs {
    let mut placed = PlacedOutputs {
        writes: Vec::new(),
        returned: Vec::new(),
    };
    let index = Literal::usize_unsuffixed;
    for ((slot, _), value) in schedule.outputs.iter().zip(values) {
        match *slot {
            OutputSlot::Mass { row, column } => {
                let (i, j) = (index(row), index(column));
                placed.writes.push(quote! { mass[(#i, #j)] = #value; });
                if row != column {
                    placed
                        .writes
                        .push(quote! { mass[(#j, #i)] = mass[(#i, #j)]; });
                }
            }
            OutputSlot::Forcing(i) => {
                let i = index(i);
                placed.writes.push(quote! { forcing[#i] = #value; });
            }
            OutputSlot::Energy(energy) => placed.returned.push((energy, value)),
            OutputSlot::Jacobian { block, row, column } => {
                let (field, i, k) = (ident(block.field()), index(row), index(column));
                placed
                    .writes
                    .push(quote! { out.#field[(#i, #k)] = #value; });
            }
            OutputSlot::InputArgument(k)
            | OutputSlot::Output(k)
            | OutputSlot::Switching(k)
            | OutputSlot::Constraint(k) => {
                let k = index(k);
                placed.writes.push(quote! { out[#k] = #value; });
            }
        }
    }
    placed
}

/// Rust's syntax for the statements and expressions of a schedule.
struct RustSyntax<'a> {
    names: &'a Names,
    /// The runtime crate's path, for the functions `f64` lacks.
    runtime: &'a TokenStream,
}

impl Backend for RustSyntax<'_> {
    type Code = TokenStream;

    fn constant(&self, value: f64) -> Fragment<TokenStream> {
        Fragment {
            code: float_literal(value),
            precedence: Precedence::Atom,
            literal: true,
        }
    }

    fn time(&self) -> TokenStream {
        quote!(t)
    }

    fn load(&self, load: Load) -> TokenStream {
        ident(self.names.locals.load(load)).into_token_stream()
    }

    fn temporary(&self, k: usize) -> TokenStream {
        ident(&self.names.locals.temporary(k)).into_token_stream()
    }

    fn parenthesize(&self, code: TokenStream) -> TokenStream {
        quote!((#code))
    }

    fn binary(&self, op: BinaryOp, left: TokenStream, right: TokenStream) -> TokenStream {
        match op {
            BinaryOp::Add => quote!(#left + #right),
            BinaryOp::Sub => quote!(#left - #right),
            BinaryOp::Mul => quote!(#left * #right),
            BinaryOp::Div => quote!(#left / #right),
        }
    }

    fn negate(&self, operand: TokenStream) -> TokenStream {
        quote!(-#operand)
    }

    fn call(&self, function: Function, argument: Fragment<TokenStream>) -> TokenStream {
        let x = receiver(argument);
        match function {
            Function::Sin => quote!(#x.sin()),
            Function::Cos => quote!(#x.cos()),
            Function::Exp => quote!(#x.exp()),
            Function::Ln => quote!(#x.ln()),
            Function::Sqrt => quote!(#x.sqrt()),
            Function::Powi(k) => {
                let k = Literal::i32_unsuffixed(k);
                quote!(#x.powi(#k))
            }
            Function::Powf(y) => {
                let y = float_literal(y);
                quote!(#x.powf(#y))
            }
        }
    }

    fn apply(&self, f: Func, arguments: Vec<Fragment<TokenStream>>) -> TokenStream {
        let rt = self.runtime;
        let mut arguments = arguments.into_iter();
        let x = arguments.next().map(receiver).unwrap_or_default();
        let rest: Vec<TokenStream> = arguments.map(|a| a.code).collect();
        // The method of `f64` that computes the function (the one the
        // interpreter calls); `sign`, `min` and `max` are the runtime's.
        let Some(method) = f.f64_method() else {
            let name = ident(f.name());
            return quote!(#rt::functions::#name(#x #(, #rest)*));
        };
        let method = ident(method);
        quote!(#x.#method(#(#rest),*))
    }

    fn input(&self, index: u32, arguments: Vec<TokenStream>) -> TokenStream {
        let index = Literal::usize_unsuffixed(index as usize);
        quote!(inputs.value(#index, &[#(#arguments),*]))
    }

    fn load_statement(&self, load: Load) -> TokenStream {
        let local = ident(self.names.locals.load(load));
        let source = match load {
            Load::Parameter(i) => {
                let field = &self.names.fields[i as usize];
                quote!(self.#field)
            }
            Load::Coordinate(i) => element(quote!(q), i),
            Load::Velocity(i) => element(quote!(qd), i),
            Load::Acceleration(i) => element(quote!(qdd), i),
        };
        quote! { let #local = #source; }
    }

    fn define(&self, k: usize, value: TokenStream) -> TokenStream {
        let name = self.temporary(k);
        quote! { let #name = #value; }
    }

    fn sin_cos(&self, sin: usize, cos: usize, argument: Fragment<TokenStream>) -> TokenStream {
        let (s, c, x) = (self.temporary(sin), self.temporary(cos), receiver(argument));
        quote! { let (#s, #c) = #x.sin_cos(); }
    }
}

/// `x[i]`.
fn element(x: TokenStream, i: u32) -> TokenStream {
    let i = Literal::usize_unsuffixed(i as usize);
    quote!(#x[#i])
}

/// The receiver of a method call: a literal or an operation in parentheses.
fn receiver(x: Fragment<TokenStream>) -> TokenStream {
    let code = x.code;
    if x.precedence == Precedence::Atom && !x.literal {
        code
    } else {
        quote!((#code))
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

/// A float literal that reads back as exactly `v` (π by name).
fn float_literal(v: f64) -> TokenStream {
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
/// is parsed and formatted, which lowers the peak memory of large models.
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
