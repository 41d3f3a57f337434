//! The `lagrangian!` macro. All the work happens in `lagrangian-core`, so the
//! compiler can be tested as a plain library; see the umbrella crate
//! `lagrangian` for the spec language and examples.

use proc_macro::TokenStream;

/// Derives a model's Euler–Lagrange equations at compile time and generates a
/// parameter struct implementing `LagrangianSystem<N>`.
///
/// ```text
/// lagrangian! { model Name; coordinates { … } parameters { … } kinetic = …; … }
/// lagrangian!(file = "specs/name.lpm")            // relative to CARGO_MANIFEST_DIR
/// lagrangian!(file = "…", runtime = ::lagrangian_runtime)
/// ```
#[proc_macro]
pub fn lagrangian(input: TokenStream) -> TokenStream {
    lagrangian_core::expand::expand(input.into()).into()
}
