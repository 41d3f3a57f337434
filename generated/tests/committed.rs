//! The committed generated files are what the current compiler produces, and
//! the `lagrangian!` macro expands each spec to the committed code.

use lagrangian_core::generate::{generate_all, specs, stale};
use quote::quote;
use std::path::Path;

fn root() -> &'static Path {
    Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/.."))
}

#[test]
fn committed_files_are_up_to_date() {
    let stale = stale(root()).unwrap();
    assert!(
        stale.is_empty(),
        "stale generated files (run `cargo generate` and commit): {stale:?}"
    );
    // Every spec has its code and equations, and the Yaris spec its audit.
    let files = generate_all(root()).unwrap();
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
            lagrangian_core::expand::expand(quote!(file = #path, runtime = ::lagrangian_model));
        let expanded: syn::File = syn::parse2(expansion).unwrap_or_else(|e| panic!("{stem}: {e}"));
        let committed =
            std::fs::read_to_string(root().join(format!("generated/src/{stem}.rs"))).unwrap();
        let committed: syn::File = syn::parse_file(&committed).unwrap();
        assert_eq!(
            items(&expanded),
            items(&committed),
            "{stem}: the macro and the committed file differ"
        );
    }
}
