//! Deep input without stack overflows.
//!
//! Parsing, lowering, differentiation and printing recurse on the syntax tree
//! and on the expression DAG, so a long sum (`a + b + …` is a left-deep tree)
//! or a deep nest of brackets would overflow the stack and abort the process,
//! or, inside `lagrangian!`, the compiler. Two defences:
//!
//! A large stack:
//!
//! * every entry point of the compiler runs its work through
//!   [`with_large_stack`], which moves it to a 256 MiB stack segment when
//!   less than 64 MiB of the current one is left;
//! * parsing and lowering run through [`with_stack_for_tokens`], which sizes
//!   the segment by the number of tokens;
//! * the segment is virtual memory: only the pages used are committed;
//! * it stays on the same thread, so it works inside a procedural macro,
//!   where the compiler's tokens and spans cannot leave the thread.
//!
//! Limits checked before `syn` parses anything: [`check_tokens`] rejects
//! input whose recursion depth even that stack could not hold, with an error
//! at the offending token:
//!
//! * brackets nested deeper than [`MAX_NESTING`], or a longer chain of
//!   method calls (each call nests its receiver);
//! * more than [`MAX_OPERATOR_RUN`] operators in a row (`- - - x` nests a
//!   unary expression per sign);
//! * more than [`MAX_TOKENS`] tokens;
//! * a name longer than [`MAX_NAME_LENGTH`] characters, or a number
//!   longer than [`MAX_LITERAL_LENGTH`] (`syn` reads an integer's digits in
//!   time quadratic in their number: 100 000 digits took over 20 s).
//!
//! A long sum or product is fine: its tree is as deep as it is long, but the
//! compiler walks such chains with loops.

use crate::diagnostic::Diagnostic;
use proc_macro2::{TokenStream, TokenTree};

/// Deepest nesting of `( )`, `[ ]` and `{ }`, and longest method chain.
pub const MAX_NESTING: usize = 256;

/// Most punctuation tokens in a row.
pub const MAX_OPERATOR_RUN: usize = 256;

/// Most tokens in one spec: a sum of 50 000 terms, far more than any model
/// needs; it bounds the stack [`with_stack_for_tokens`] reserves.
pub const MAX_TOKENS: usize = 100_000;

/// The longest name, in characters.
pub const MAX_NAME_LENGTH: usize = 256;

/// The longest number literal, in characters: 17 significant digits give
/// any f64, and an exact coefficient has at most 39 (an `i128`), so 256
/// leaves room for any zeros and separators a number needs.
pub const MAX_LITERAL_LENGTH: usize = 256;

/// The stack left below which [`with_large_stack`] switches stacks.
const RED_ZONE: usize = 64 << 20;

/// The size of the stack segment it switches to.
const STACK_SIZE: usize = 256 << 20;

/// Stack reserved per token for parsing and lowering: `syn` parses some
/// shapes by recursion per operator (`a = b = c …`, right-associative),
/// which takes a few KiB of stack per token in a debug build (a procedural
/// macro's usual build); 16 KiB leaves a wide margin.
const STACK_PER_TOKEN: usize = 16 << 10;

/// Runs `f` on a 256 MiB stack segment when less than 64 MiB of stack is
/// left, else directly (nested entry points reuse the segment).
pub fn with_large_stack<R>(f: impl FnOnce() -> R) -> R {
    stacker::maybe_grow(RED_ZONE, STACK_SIZE, f)
}

/// Runs `f`, which parses and lowers `tokens` tokens, on a stack of at
/// least 256 MiB and 16 KiB per token (at most 1.6 GB, reserved but not
/// committed, for [`MAX_TOKENS`]; a typical spec gets the 256 MiB).
pub fn with_stack_for_tokens<R>(tokens: usize, f: impl FnOnce() -> R) -> R {
    let size = STACK_SIZE.max(tokens.saturating_mul(STACK_PER_TOKEN));
    stacker::maybe_grow(size, size, f)
}

/// Rejects token streams too deep or too long to parse and lower safely,
/// and returns the number of tokens. Iterative, so it cannot overflow on
/// the input it rejects.
pub fn check_tokens(tokens: &TokenStream) -> Result<usize, Diagnostic> {
    // Per bracket level: its tokens, and the length of the method chain
    // (`x.sin().cos()…`, a receiver nested per call) going on at that level.
    let mut stack = vec![(tokens.clone().into_iter(), 0usize)];
    let (mut run, mut count) = (0usize, 0usize);
    while let Some((iter, chain)) = stack.last_mut() {
        let Some(token) = iter.next() else {
            stack.pop();
            continue;
        };
        match &token {
            TokenTree::Punct(p) if p.as_char() == '.' => *chain += 1,
            TokenTree::Punct(_) => *chain = 0,
            _ => {}
        }
        if *chain > MAX_NESTING {
            return Err(Diagnostic::new(
                token.span(),
                format!("a chain of more than {MAX_NESTING} method calls"),
            ));
        }
        count += 1;
        if count > MAX_TOKENS {
            return Err(Diagnostic::new(
                token.span(),
                format!("the spec is too long: more than {MAX_TOKENS} tokens"),
            ));
        }
        match token {
            TokenTree::Group(g) => {
                run = 0;
                if stack.len() > MAX_NESTING {
                    return Err(Diagnostic::new(
                        g.span_open(),
                        format!("brackets nested more than {MAX_NESTING} deep"),
                    )
                    .with_help("name inner parts with `let` to flatten the expression"));
                }
                stack.push((g.stream().into_iter(), 0));
            }
            TokenTree::Ident(ident) => {
                run = 0;
                check_name(&ident)?;
            }
            TokenTree::Literal(literal) => {
                run = 0;
                check_literal(&literal)?;
            }
            TokenTree::Punct(p) => {
                run += 1;
                if run > MAX_OPERATOR_RUN {
                    return Err(Diagnostic::new(
                        p.span(),
                        format!("more than {MAX_OPERATOR_RUN} operators in a row"),
                    ));
                }
            }
        }
    }
    Ok(count)
}

/// A name of at most [`MAX_NAME_LENGTH`] characters.
fn check_name(ident: &proc_macro2::Ident) -> Result<(), Diagnostic> {
    let length = ident.to_string().chars().count();
    if length <= MAX_NAME_LENGTH {
        return Ok(());
    }
    Err(Diagnostic::new(
        ident.span(),
        format!("a name of {length} characters: names are at most {MAX_NAME_LENGTH}"),
    ))
}

/// A number of at most [`MAX_LITERAL_LENGTH`] characters (strings, such as
/// doc comments, may be longer).
fn check_literal(literal: &proc_macro2::Literal) -> Result<(), Diagnostic> {
    let text = literal.to_string();
    let length = text.chars().count();
    if length <= MAX_LITERAL_LENGTH || !text.starts_with(|c: char| c.is_ascii_digit()) {
        return Ok(());
    }
    Err(Diagnostic::new(
        literal.span(),
        format!("a number of {length} characters: numbers are at most {MAX_LITERAL_LENGTH}"),
    )
    .with_help("write a large or small number with an exponent, e.g. `1.5e300` or `2e-12`"))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn check(text: &str) -> Result<(), String> {
        let tokens: TokenStream = text.parse().unwrap();
        check_tokens(&tokens).map(|_| ()).map_err(|d| d.message)
    }

    #[test]
    fn nesting_and_operator_runs_are_limited() {
        let nested = |n: usize| format!("x = {}1{};", "(".repeat(n), ")".repeat(n));
        assert_eq!(check(&nested(MAX_NESTING)), Ok(()));
        assert_eq!(
            check(&nested(MAX_NESTING + 1)),
            Err("brackets nested more than 256 deep".to_string())
        );
        let signs = |n: usize| format!("x = {}1;", "- ".repeat(n));
        assert_eq!(check(&signs(MAX_OPERATOR_RUN - 1)), Ok(()));
        assert_eq!(
            check(&signs(MAX_OPERATOR_RUN + 1)),
            Err("more than 256 operators in a row".to_string())
        );
        let chain = |n: usize| format!("x = y{};", ".sin()".repeat(n));
        assert_eq!(check(&chain(MAX_NESTING)), Ok(()));
        assert_eq!(
            check(&chain(MAX_NESTING + 1)),
            Err("a chain of more than 256 method calls".to_string())
        );
        let long = format!("x = {};", vec!["a"; MAX_TOKENS / 2 + 1].join(" + "));
        assert!(check(&long).unwrap_err().contains("too long"));
    }

    #[test]
    fn names_and_numbers_are_limited_in_length() {
        let name = |n: usize| format!("x = {};", "a".repeat(n));
        assert_eq!(check(&name(MAX_NAME_LENGTH)), Ok(()));
        assert_eq!(
            check(&name(50_000)),
            Err("a name of 50000 characters: names are at most 256".to_string())
        );
        let number = |n: usize| format!("x = 1{};", "0".repeat(n - 1));
        assert_eq!(check(&number(MAX_LITERAL_LENGTH)), Ok(()));
        assert_eq!(
            check(&number(MAX_LITERAL_LENGTH + 1)),
            Err("a number of 257 characters: numbers are at most 256".to_string())
        );
        let doc = format!("/// {}\nx = 1;", "word ".repeat(1000));
        assert_eq!(check(&doc), Ok(()));
    }

    #[test]
    fn a_deep_recursion_runs_on_the_large_stack() {
        fn depth(n: u64) -> u64 {
            let pad = std::hint::black_box([0u8; 512]);
            if n == 0 {
                u64::from(pad[0])
            } else {
                1 + depth(n - 1)
            }
        }
        // About 60 MB of frames: more than a thread's default 8 MiB.
        let n = with_large_stack(|| depth(100_000));
        assert_eq!(n, 100_000);
    }
}
