//! Errors that point at the user's source: a `syn::Error` with the offending
//! token's span inside the macro, `file:line:col` with a snippet for spec files.

use proc_macro2::{Span, TokenStream};
use quote::{ToTokens, quote_spanned};

/// The source range from the first to the last token of a construct.
///
/// On stable Rust a procedural macro cannot join two spans into one, so a
/// range is kept as its two ends; `syn::Error::new_spanned` underlines both.
#[derive(Clone, Copy, Debug)]
pub struct SpanRange {
    /// The span of the first token.
    pub start: Span,
    /// The span of the last token.
    pub end: Span,
}

impl SpanRange {
    /// The range covered by `tokens`.
    pub fn of(tokens: &impl ToTokens) -> SpanRange {
        let stream = tokens.to_token_stream();
        let mut iter = stream.into_iter();
        let start = iter.next().map_or_else(Span::call_site, |t| t.span());
        let end = iter.last().map_or(start, |t| t.span());
        SpanRange { start, end }
    }

    /// From the start of `self` to the end of `other`.
    pub fn to(self, other: SpanRange) -> SpanRange {
        SpanRange {
            start: self.start,
            end: other.end,
        }
    }
}

impl From<Span> for SpanRange {
    fn from(span: Span) -> SpanRange {
        SpanRange {
            start: span,
            end: span,
        }
    }
}

impl ToTokens for SpanRange {
    fn to_tokens(&self, tokens: &mut TokenStream) {
        let (start, end) = (self.start, self.end);
        tokens.extend(quote_spanned!(start=> __start));
        tokens.extend(quote_spanned!(end=> __end));
    }
}

/// One problem in a spec, located at a range of its source.
#[derive(Clone, Debug)]
pub struct Diagnostic {
    /// What is wrong: the first line of the error.
    pub message: String,
    /// Where: the construct at fault.
    pub span: SpanRange,
    /// How to fix it, when we can say.
    pub help: Option<String>,
    /// A second location that explains the first (e.g. the earlier declaration).
    pub note: Option<Box<(String, SpanRange)>>,
    /// A consequence of a problem already reported (a use of a `let` whose
    /// definition failed), which is not reported again.
    follows_earlier: bool,
}

impl Diagnostic {
    /// A diagnostic at `span` without help or note.
    pub fn new(span: impl Into<SpanRange>, message: impl Into<String>) -> Diagnostic {
        Diagnostic {
            message: message.into(),
            span: span.into(),
            help: None,
            note: None,
            follows_earlier: false,
        }
    }

    /// A use of something whose own error has been reported: the statement
    /// fails, but no second message cascades from the first.
    pub(crate) fn follows_earlier(span: impl Into<SpanRange>) -> Diagnostic {
        Diagnostic {
            follows_earlier: true,
            ..Diagnostic::new(span, "follows an error reported earlier")
        }
    }

    pub(crate) fn is_follow_up(&self) -> bool {
        self.follows_earlier
    }

    /// The name of an "unknown name `x`" error of an expression, so that
    /// a caller that knows where `x` is declared can say so.
    pub(crate) fn unknown_name(&self) -> Option<&str> {
        (self.message.strip_prefix("unknown name `")).and_then(|rest| rest.strip_suffix('`'))
    }

    /// Adds how to fix the problem.
    pub fn with_help(mut self, help: impl Into<String>) -> Diagnostic {
        self.help = Some(help.into());
        self
    }

    /// Adds a second location that explains the first.
    pub fn with_note(mut self, note: impl Into<String>, span: impl Into<SpanRange>) -> Diagnostic {
        self.note = Some(Box::new((note.into(), span.into())));
        self
    }

    /// The message with its note and help lines, as the compiler shows it for
    /// a macro (which can underline only one place: the note gives its line).
    pub fn full_message(&self) -> String {
        let mut text = self.message.clone();
        if let Some((note, span)) = self.note.as_deref() {
            let at = span.start.start();
            if at.line > 0 {
                text.push_str(&format!(
                    "\nnote: {note} (line {}, column {})",
                    at.line,
                    at.column + 1
                ));
            } else {
                text.push_str(&format!("\nnote: {note}"));
            }
        }
        if let Some(help) = &self.help {
            text.push_str(&format!("\nhelp: {help}"));
        }
        text
    }

    /// The diagnostic as a `syn::Error` at its span (for `compile_error!`).
    pub fn to_syn_error(&self) -> syn::Error {
        syn::Error::new_spanned(self.span, self.full_message())
    }

    /// `error: …` / `--> file:line:col` / source line with carets, rustc style.
    /// Positions come from the span, so the source must have been parsed
    /// outside a procedural macro (proc-macro2's own span tracking).
    pub fn render(&self, file: &str, source: &str) -> String {
        self.render_as("error", file, source)
    }

    /// As [`Diagnostic::render`], for a warning: `warning: …`.
    pub fn render_warning(&self, file: &str, source: &str) -> String {
        self.render_as("warning", file, source)
    }

    fn render_as(&self, level: &str, file: &str, source: &str) -> String {
        let mut out = format!("{level}: {}\n", self.message);
        out.push_str(&snippet(file, source, self.span));
        if let Some((note, span)) = self.note.as_deref() {
            out.push_str(&format!("note: {note}\n"));
            out.push_str(&snippet(file, source, *span));
        }
        if let Some(help) = &self.help {
            out.push_str(&format!("  = help: {help}\n"));
        }
        out
    }
}

/// `file:line:col` of a span (1-based line and column; line 0 means unknown).
pub fn location(file: &str, span: impl Into<SpanRange>) -> String {
    let start = span.into().start.start();
    format!("{file}:{}:{}", start.line.max(1), start.column + 1)
}

fn snippet(file: &str, source: &str, span: SpanRange) -> String {
    let (start, end) = (span.start.start(), span.end.end());
    let mut out = format!(" --> {}\n", location(file, span));
    let Some(line_text) = source.lines().nth(start.line.max(1) - 1) else {
        return out;
    };
    let width = start.line.to_string().len();
    let pad = " ".repeat(width);
    let caret_len = if end.line == start.line && end.column > start.column {
        end.column - start.column
    } else {
        line_text
            .chars()
            .count()
            .saturating_sub(start.column)
            .max(1)
    };
    let (shown, column, caret_len) = window(line_text, start.column, caret_len);
    out.push_str(&format!("{pad} |\n"));
    out.push_str(&format!("{} | {}\n", start.line, shown));
    out.push_str(&format!(
        "{pad} | {}{}\n",
        " ".repeat(column),
        "^".repeat(caret_len)
    ));
    out
}

/// The most characters of a source line a snippet shows.
const SHOWN_LINE: usize = 160;

/// `line` as a snippet shows it, with the caret's column and length there:
/// the whole line when it is short, else [`SHOWN_LINE`] characters from a
/// little before `column`, cut ends marked `…` (so that a line of 100 000
/// characters is not printed whole).
fn window(line: &str, column: usize, caret_len: usize) -> (String, usize, usize) {
    let length = line.chars().count();
    if length <= SHOWN_LINE {
        return (line.to_string(), column, caret_len);
    }
    let from = column
        .saturating_sub(SHOWN_LINE / 4)
        .min(length - SHOWN_LINE);
    let to = from + SHOWN_LINE;
    let mut shown: String = line.chars().skip(from).take(SHOWN_LINE).collect();
    let mut column = column - from;
    if from > 0 {
        shown.insert(0, '…');
        column += 1;
    }
    if to < length {
        shown.push('…');
    }
    let caret_len = caret_len
        .min(SHOWN_LINE + 1 - (column.min(SHOWN_LINE)))
        .max(1);
    (shown, column, caret_len)
}

/// All problems found in one spec (at least one).
///
/// It displays as the diagnostics' messages with their notes and help
/// ([`Diagnostic::full_message`]), one after the other, a line apart.
///
/// (`Display` is written out rather than derived: a derive would put a
/// second `syn` into the build of every crate that uses the macro.)
#[derive(Clone, Debug)]
pub struct SpecErrors {
    /// The problems, in the order they were found.
    pub diagnostics: Vec<Diagnostic>,
}

impl SpecErrors {
    /// One problem.
    pub fn single(d: Diagnostic) -> SpecErrors {
        SpecErrors {
            diagnostics: vec![d],
        }
    }

    /// One `syn::Error` carrying every diagnostic, for `compile_error!` output.
    pub fn to_syn_error(&self) -> syn::Error {
        let mut iter = self.diagnostics.iter();
        let mut error = match iter.next() {
            Some(d) => d.to_syn_error(),
            None => syn::Error::new(Span::call_site(), "invalid spec"),
        };
        for d in iter {
            error.combine(d.to_syn_error());
        }
        error
    }

    /// Every diagnostic rendered as [`Diagnostic::render`] does, a blank line
    /// apart.
    pub fn render(&self, file: &str, source: &str) -> String {
        self.diagnostics
            .iter()
            .map(|d| d.render(file, source))
            .collect::<Vec<_>>()
            .join("\n")
    }
}

impl From<syn::Error> for SpecErrors {
    fn from(e: syn::Error) -> SpecErrors {
        SpecErrors {
            diagnostics: e
                .into_iter()
                .map(|e| Diagnostic::new(e.span(), e.to_string()))
                .collect(),
        }
    }
}

impl From<Diagnostic> for SpecErrors {
    fn from(d: Diagnostic) -> SpecErrors {
        SpecErrors::single(d)
    }
}

/// Every diagnostic's full message, one after the other, a line apart.
impl std::fmt::Display for SpecErrors {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let messages: Vec<String> = (self.diagnostics.iter())
            .map(Diagnostic::full_message)
            .collect();
        f.write_str(&messages.join("\n"))
    }
}

impl std::error::Error for SpecErrors {}

pub use lagrangian_runtime::names::closest;

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn spec_errors_display_every_message_a_line_apart() {
        let errors = SpecErrors {
            diagnostics: vec![
                Diagnostic::new(Span::call_site(), "first").with_help("fix it"),
                Diagnostic::new(Span::call_site(), "second")
                    .with_note("declared here", Span::call_site()),
            ],
        };
        assert_eq!(
            errors.to_string(),
            "first\nhelp: fix it\nsecond\nnote: declared here (line 1, column 1)"
        );
    }

    #[test]
    fn renders_file_line_column_with_caret() {
        let source = "model X;\nkinetic = thta1;\n";
        let tokens: proc_macro2::TokenStream = source.parse().unwrap();
        let span = tokens.into_iter().nth(5).unwrap().span(); // `thta1`
        let text = Diagnostic::new(span, "unknown name `thta1`")
            .with_help("did you mean `theta1`?")
            .render("x.lpm", source);
        assert!(text.contains("--> x.lpm:2:11"), "{text}");
        assert!(text.contains("2 | kinetic = thta1;"), "{text}");
        assert!(text.contains("          ^^^^^"), "{text}");
        assert!(text.contains("help: did you mean `theta1`?"), "{text}");
    }

    #[test]
    fn a_long_line_is_shown_around_the_caret() {
        let source = format!("model X;\nkinetic = {} + thta1;\n", "a + ".repeat(1000));
        let tokens: proc_macro2::TokenStream = source.parse().unwrap();
        let span = tokens.into_iter().last().unwrap().span(); // `;`
        let text = Diagnostic::new(span, "here").render("x.lpm", &source);
        let lines: Vec<&str> = text.lines().collect();
        let shown = lines[3].strip_prefix("2 | ").unwrap();
        assert_eq!(shown.chars().count(), SHOWN_LINE + 1, "{text}");
        assert!(
            shown.starts_with('…') && shown.ends_with("thta1;"),
            "{text}"
        );
        let caret = lines[4].strip_prefix("  | ").unwrap();
        assert_eq!(caret.chars().count(), SHOWN_LINE + 1, "{text}");
        assert!(caret.ends_with(" ^"), "{text}");
    }
}
