//! The `lagrangian!` macro's expansion, as a plain function of tokens (the
//! proc-macro crate only forwards to [`expand`]).
//!
//! ```text
//! lagrangian! { model Name; coordinates { … } … }            // inline spec
//! lagrangian! { runtime = ::lagrangian_runtime; model Name; … } // custom runtime path
//! lagrangian!(file = "specs/name.lpm")                        // spec file
//! lagrangian!(file = "specs/name.lpm", runtime = crate)
//! ```
//!
//! A spec file's path is relative to the invoking crate's `CARGO_MANIFEST_DIR`.
//! The expansion includes the file with `include_str!`, so cargo rebuilds when
//! it changes. Errors in a file are reported as `file:line:col` with a snippet,
//! at the span of the path literal.

use crate::emit::{RustOptions, emit_model, emit_stub};
use crate::spec::Outline;
use crate::{Compiled, Model};
use proc_macro2::{Span, TokenStream};
use quote::{ToTokens, quote};
use syn::parse::{ParseStream, Parser};
use syn::{LitStr, Token};

mod kw {
    syn::custom_keyword!(file);
    syn::custom_keyword!(runtime);
}

enum Source {
    Inline(TokenStream),
    File(LitStr),
}

struct Invocation {
    source: Source,
    runtime: Option<TokenStream>,
}

fn parse_runtime(input: ParseStream) -> syn::Result<TokenStream> {
    input.parse::<kw::runtime>()?;
    input.parse::<Token![=]>()?;
    if input.peek(Token![crate]) {
        let krate: Token![crate] = input.parse()?;
        Ok(krate.into_token_stream())
    } else {
        let path: syn::Path = input.parse()?;
        Ok(path.into_token_stream())
    }
}

fn parse_invocation(input: ParseStream) -> syn::Result<Invocation> {
    if input.peek(kw::file) && input.peek2(Token![=]) {
        input.parse::<kw::file>()?;
        input.parse::<Token![=]>()?;
        let path: LitStr = input.parse()?;
        let mut runtime = None;
        while input.peek(Token![,]) {
            input.parse::<Token![,]>()?;
            if input.is_empty() {
                break;
            }
            runtime = Some(parse_runtime(input)?);
        }
        if !input.is_empty() {
            return Err(input.error("expected `, runtime = path` or the end of the macro input"));
        }
        return Ok(Invocation {
            source: Source::File(path),
            runtime,
        });
    }
    let runtime = if input.peek(kw::runtime) && input.peek2(Token![=]) {
        let r = parse_runtime(input)?;
        input.parse::<Token![;]>()?;
        Some(r)
    } else {
        None
    };
    Ok(Invocation {
        source: Source::Inline(input.parse()?),
        runtime,
    })
}

/// Expands the macro input into the model's code, or into `compile_error!`s
/// and, where the spec names its model, a stand-in for the model's type
/// (with its fields, constants and trait impl) so that its uses add no errors
/// of their own.
/// Runs on a large stack (see [`crate::depth`]), still on the compiler's thread.
pub fn expand(input: TokenStream) -> TokenStream {
    crate::depth::with_large_stack(|| match try_expand(input) {
        Ok(tokens) => tokens,
        Err(Failed { error, stub }) => {
            let error = error.to_compile_error();
            quote! { #error #stub }
        }
    })
}

/// An expansion that failed: the errors and the stand-in for the model.
struct Failed {
    error: syn::Error,
    stub: Option<TokenStream>,
}

impl From<syn::Error> for Failed {
    fn from(error: syn::Error) -> Failed {
        Failed { error, stub: None }
    }
}

/// The stand-in for the model of spec `tokens`, if they name one and are
/// within the input limits (beyond them, even reading their outline could
/// overflow the stack: they get their error alone).
fn stub(tokens: TokenStream, options: &RustOptions) -> Option<TokenStream> {
    let count = crate::depth::check_tokens(&tokens).ok()?;
    let outline = crate::depth::with_stack_for_tokens(count, || Outline::of(tokens))?;
    Some(emit_stub(&outline, options))
}

fn try_expand(input: TokenStream) -> Result<TokenStream, Failed> {
    let invocation = parse_invocation.parse2(input)?;
    let options = RustOptions {
        runtime: invocation
            .runtime
            .unwrap_or_else(|| RustOptions::default().runtime),
    };
    match invocation.source {
        Source::Inline(tokens) => {
            let compiled = Model::from_tokens(tokens.clone())
                .and_then(Compiled::new)
                .map_err(|e| Failed {
                    error: e.to_syn_error(),
                    stub: stub(tokens, &options),
                })?;
            Ok(emit_model(&compiled, &options))
        }
        Source::File(path) => expand_file(&path, &options),
    }
}

fn expand_file(path: &LitStr, options: &RustOptions) -> Result<TokenStream, Failed> {
    let manifest = std::env::var("CARGO_MANIFEST_DIR").unwrap_or_else(|_| ".".to_string());
    let full = std::path::Path::new(&manifest).join(path.value());
    let source = std::fs::read_to_string(&full).map_err(|e| {
        syn::Error::new(
            path.span(),
            format!(
                "cannot read spec file `{}`: {e} (the path is relative to the directory of the crate's Cargo.toml)",
                path.value(),
            ),
        )
    })?;
    let compiled = Compiled::from_source(&source).map_err(|_| Failed {
        error: syn::Error::new(path.span(), located_errors(&path.value(), &source)),
        stub: source.parse().ok().and_then(|tokens| stub(tokens, options)),
    })?;
    let model = emit_model(&compiled, options);
    let full_text = full.to_string_lossy().into_owned();
    // Inside a proc macro the model's tokens came from the compiler's own
    // token implementation; re-parse through text so both kinds never mix.
    let model: TokenStream = model.to_string().parse().map_err(|_| {
        syn::Error::new(
            Span::call_site(),
            "internal error: generated code does not lex",
        )
    })?;
    Ok(quote! {
        const _: &str = ::core::include_str!(#full_text);
        #model
    })
}

/// The errors of a spec file rendered with `file:line:col` and snippets.
///
/// Inside a procedural macro, tokens parsed from a string carry no position,
/// so the spec is compiled again with proc-macro2's own implementation, which
/// tracks lines and columns. Only error paths pay for this.
pub fn located_errors(file: &str, source: &str) -> String {
    proc_macro2::fallback::force();
    let result = Compiled::from_source(source).err();
    proc_macro2::fallback::unforce();
    match result {
        Some(errors) => errors.render(file, source),
        None => format!("{file}: the spec failed to compile, but not when compiled again"),
    }
}
