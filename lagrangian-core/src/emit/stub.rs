//! What the macro emits beside the errors of a spec that does not compile:
//! the model's type with its fields, constants and trait impl, bodies
//! unreachable, so that the user sees the spec's errors and not a cascade of
//! "cannot find type" at every use of the model.

use super::names::{ident, input_constants};
use super::rust::RustOptions;
use crate::spec::Outline;
use proc_macro2::{Literal, TokenStream};
use quote::quote;

/// The stand-in for the model `outline` describes.
pub(crate) fn emit_stub(outline: &Outline, options: &RustOptions) -> TokenStream {
    let rt = &options.runtime;
    let ty = ident(&outline.name);
    let fields: Vec<_> = outline.parameters.iter().map(|p| ident(p)).collect();
    let constants = input_constants(&outline.inputs);
    let indices = (0..outline.inputs.len()).map(Literal::usize_unsuffixed);
    let unreachable = quote!(::core::unreachable!("the spec of this model has errors"));
    let system = (!outline.coordinates.is_empty()).then(|| {
        let n = Literal::usize_unsuffixed(outline.coordinates.len());
        let vector = quote!(#rt::nalgebra::SVector<f64, #n>);
        let matrix = quote!(#rt::nalgebra::SMatrix<f64, #n, #n>);
        quote! {
            #[automatically_derived]
            #[allow(unused_variables)]
            impl #rt::LagrangianSystem<#n> for #ty {
                fn model_name(&self) -> &str { #unreachable }
                fn coordinate_names(&self) -> ::std::vec::Vec<&str> { #unreachable }
                fn parameter_names(&self) -> ::std::vec::Vec<&str> { #unreachable }
                fn input_names(&self) -> ::std::vec::Vec<&str> { #unreachable }
                fn parameters(&self) -> ::std::vec::Vec<f64> { #unreachable }
                fn set_parameter(&mut self, name: &str, value: f64)
                    -> ::core::result::Result<(), #rt::ModelError> { #unreachable }
                fn mass_matrix_and_forcing<I: #rt::InputFunctions + ?Sized>(
                    &self, t: f64, q: &#vector, qd: &#vector, inputs: &I,
                    mass: &mut #matrix, forcing: &mut #vector,
                ) { #unreachable }
                fn energies<I: #rt::InputFunctions + ?Sized>(
                    &self, t: f64, q: &#vector, qd: &#vector, inputs: &I,
                ) -> #rt::Energies { #unreachable }
                fn input_sites(&self) -> &[(usize, usize)] { #unreachable }
                fn input_arguments<I: #rt::InputFunctions + ?Sized>(
                    &self, t: f64, q: &#vector, qd: &#vector, inputs: &I, out: &mut [f64],
                ) { #unreachable }
            }
        }
    });
    let coordinates = &outline.coordinates;
    let n = Literal::usize_unsuffixed(coordinates.len());
    let (parameters, inputs) = (&outline.parameters, &outline.inputs);
    quote! {
        #[derive(Debug, Clone, Copy, PartialEq)]
        #[allow(non_snake_case, non_camel_case_types, dead_code)]
        pub struct #ty { #(pub #fields: f64,)* }

        #[automatically_derived]
        impl ::core::default::Default for #ty {
            fn default() -> Self { #unreachable }
        }

        #[allow(non_camel_case_types, dead_code)]
        impl #ty {
            pub const COORDINATES: [&'static str; #n] = [#(#coordinates),*];
            pub const PARAMETERS: &'static [&'static str] = &[#(#parameters),*];
            pub const INPUTS: &'static [&'static str] = &[#(#inputs),*];
            #(pub const #constants: usize = #indices;)*
        }

        #system
    }
}
