//! The committed generated files are what the current compiler produces, and
//! the `lagrangian!` macro expands each spec to the committed code.

use lagrangian_core::generate::{generate_all, specs, stale};
use quote::quote;
use std::path::Path;

fn root() -> &'static Path {
    Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/.."))
}

/// Where `found` first differs from `expected`: the line number and both
/// lines (`None` past the end of a file).
fn first_difference<'a>(
    expected: &'a str,
    found: &'a str,
) -> Option<(usize, Option<&'a str>, Option<&'a str>)> {
    let (mut e, mut f) = (expected.lines(), found.lines());
    for line in 1.. {
        match (e.next(), f.next()) {
            (None, None) => return None,
            (a, b) if a != b => return Some((line, a, b)),
            _ => {}
        }
    }
    None
}

/// A line as the failure messages show it: quoted, or the end of the file.
fn show(line: Option<&str>) -> String {
    line.map_or("(end of file)".to_string(), |l| format!("{l:?}"))
}

#[test]
fn committed_files_are_up_to_date() {
    let files = generate_all(root()).unwrap();
    let mut report = String::new();
    for file in &files {
        let path = file.path.display();
        let Ok(committed) = std::fs::read_to_string(root().join(&file.path)) else {
            report.push_str(&format!("{path}: missing\n"));
            continue;
        };
        if committed == file.contents {
            continue;
        }
        match first_difference(&file.contents, &committed) {
            Some((line, expected, found)) => report.push_str(&format!(
                "{path}:{line}:\n  expected: {}\n  found:    {}\n",
                show(expected),
                show(found)
            )),
            None => report.push_str(&format!("{path}: differs in line endings\n")),
        }
    }
    assert!(
        report.is_empty(),
        "stale generated files (run `cargo generate` and commit); first differences:\n{report}"
    );
    assert!(stale(root()).unwrap().is_empty());
    // Every spec has its code and equations, and the Yaris spec its audit.
    let paths: Vec<String> = files.iter().map(|f| f.path.display().to_string()).collect();
    for (stem, _) in specs(root()).unwrap() {
        assert!(paths.contains(&format!("generated/src/{stem}.rs")));
        assert!(paths.contains(&format!("generated/{stem}/EQUATIONS.md")));
    }
    assert!(paths.contains(&"generated/yaris_double_pendulum/AUDIT.md".to_string()));
}

/// The code of a file formatted by prettyplease, without the macro's
/// `const _ = include_str!(…)` rebuild tracker (comments do not count).
fn items(file: &syn::File) -> String {
    let mut file = file.clone();
    file.items
        .retain(|item| !matches!(item, syn::Item::Const(c) if c.ident == "_"));
    file.attrs.clear();
    prettyplease::unparse(&file)
}

#[test]
fn the_macro_expands_each_spec_to_its_committed_file() {
    for (stem, relative) in specs(root()).unwrap() {
        let path = format!("../{relative}");
        let expansion =
            lagrangian_core::expand::expand(quote!(file = #path, runtime = ::lagrangian_runtime));
        let expanded: syn::File = syn::parse2(expansion).unwrap_or_else(|e| panic!("{stem}: {e}"));
        let committed =
            std::fs::read_to_string(root().join(format!("generated/src/{stem}.rs"))).unwrap();
        let committed: syn::File = syn::parse_file(&committed).unwrap();
        let (expanded, committed) = (items(&expanded), items(&committed));
        if let Some((line, e, c)) = first_difference(&expanded, &committed) {
            panic!(
                "{stem}: the macro and the committed file differ first at line {line} of their items:\n  macro:     {}\n  committed: {}",
                show(e),
                show(c)
            );
        }
        assert_eq!(expanded, committed, "{stem}: line endings differ");
    }
}
