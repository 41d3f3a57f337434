//! Errors that point at the user's source: a `syn::Error` with the offending
//! token's span inside the macro, `file:line:col` with a snippet for spec files.

use proc_macro2::Span;
use std::fmt;

/// One problem in a spec, located at a span of its source.
#[derive(Clone, Debug)]
pub struct Diagnostic {
    pub message: String,
    pub span: Span,
    /// How to fix it, when we can say.
    pub help: Option<String>,
    /// A second location that explains the first (e.g. the earlier declaration).
    pub note: Option<(String, Span)>,
}

impl Diagnostic {
    pub fn new(span: Span, message: impl Into<String>) -> Diagnostic {
        Diagnostic {
            message: message.into(),
            span,
            help: None,
            note: None,
        }
    }

    pub fn with_help(mut self, help: impl Into<String>) -> Diagnostic {
        self.help = Some(help.into());
        self
    }

    pub fn with_note(mut self, note: impl Into<String>, span: Span) -> Diagnostic {
        self.note = Some((note.into(), span));
        self
    }

    /// The message with its help line, as the compiler shows it for a macro.
    pub fn full_message(&self) -> String {
        let mut text = self.message.clone();
        if let Some((note, _)) = &self.note {
            text.push_str(&format!("\nnote: {note}"));
        }
        if let Some(help) = &self.help {
            text.push_str(&format!("\nhelp: {help}"));
        }
        text
    }

    pub fn to_syn_error(&self) -> syn::Error {
        syn::Error::new(self.span, self.full_message())
    }

    /// `error: …` / `--> file:line:col` / source line with carets, rustc style.
    /// Positions come from the span, so the source must have been parsed
    /// outside a procedural macro (proc-macro2's own span tracking).
    pub fn render(&self, file: &str, source: &str) -> String {
        let mut out = format!("error: {}\n", self.message);
        out.push_str(&snippet(file, source, self.span, ""));
        if let Some((note, span)) = &self.note {
            out.push_str(&format!("note: {note}\n"));
            out.push_str(&snippet(file, source, *span, ""));
        }
        if let Some(help) = &self.help {
            out.push_str(&format!("  = help: {help}\n"));
        }
        out
    }
}

/// `file:line:col` of a span (1-based line and column).
pub fn location(file: &str, span: Span) -> String {
    let start = span.start();
    format!("{file}:{}:{}", start.line, start.column + 1)
}

fn snippet(file: &str, source: &str, span: Span, label: &str) -> String {
    let (start, end) = (span.start(), span.end());
    let mut out = format!(" --> {}\n", location(file, span));
    let Some(line_text) = source.lines().nth(start.line.saturating_sub(1)) else {
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
    out.push_str(&format!("{pad} |\n"));
    out.push_str(&format!("{} | {}\n", start.line, line_text));
    out.push_str(&format!(
        "{pad} | {}{} {}\n",
        " ".repeat(start.column),
        "^".repeat(caret_len),
        label
    ));
    out
}

/// All problems found in one spec (at least one).
#[derive(Clone, Debug)]
pub struct SpecErrors {
    pub diagnostics: Vec<Diagnostic>,
}

impl SpecErrors {
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

impl fmt::Display for SpecErrors {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        for (i, d) in self.diagnostics.iter().enumerate() {
            if i > 0 {
                writeln!(f)?;
            }
            write!(f, "{}", d.full_message())?;
        }
        Ok(())
    }
}

impl std::error::Error for SpecErrors {}

/// The closest name to `wanted` among `candidates`, for "did you mean" hints.
pub fn closest<'a>(wanted: &str, candidates: impl IntoIterator<Item = &'a str>) -> Option<&'a str> {
    candidates
        .into_iter()
        .map(|c| (edit_distance(wanted, c), c))
        .filter(|(d, c)| *d <= (wanted.len().max(c.len()) / 3).max(1))
        .min_by_key(|(d, _)| *d)
        .map(|(_, c)| c)
}

fn edit_distance(a: &str, b: &str) -> usize {
    let b: Vec<char> = b.chars().collect();
    let mut row: Vec<usize> = (0..=b.len()).collect();
    for (i, ca) in a.chars().enumerate() {
        let mut diagonal = row[0];
        row[0] = i + 1;
        for (j, cb) in b.iter().enumerate() {
            let next = (row[j + 1] + 1)
                .min(row[j] + 1)
                .min(diagonal + usize::from(ca != *cb));
            diagonal = row[j + 1];
            row[j + 1] = next;
        }
    }
    row[b.len()]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn suggests_near_names_only() {
        let names = ["theta1", "theta2", "r", "m1"];
        assert_eq!(closest("thta1", names), Some("theta1"));
        assert_eq!(closest("m2", names), Some("m1"));
        assert_eq!(closest("velocity", names), None);
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
}
