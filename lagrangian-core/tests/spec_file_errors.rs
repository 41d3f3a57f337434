//! Errors in spec files point at `file:line:col` with the source line.

use lagrangian_core::Compiled;
use quote::quote;

fn errors_of(path: &str) -> String {
    let source = std::fs::read_to_string(path).unwrap();
    match Compiled::from_source(&source) {
        Ok(_) => panic!("{path} should not compile"),
        Err(e) => e.render(path, &source),
    }
}

#[test]
fn unknown_name_is_located_with_a_snippet_and_a_suggestion() {
    let text = errors_of("tests/fixtures/unknown_name.lpm");
    assert!(text.starts_with("error: unknown name `kk`\n"), "{text}");
    assert!(
        text.contains(" --> tests/fixtures/unknown_name.lpm:8:19\n"),
        "{text}"
    );
    assert!(
        text.contains("8 | potential = 0.5 * kk * pow(x, 2);\n"),
        "{text}"
    );
    assert!(text.contains("  |                   ^^\n"), "{text}");
    assert!(text.contains("help: did you mean `k`?"), "{text}");
}

#[test]
fn a_second_declaration_points_back_at_the_first() {
    let text = errors_of("tests/fixtures/duplicate_energy.lpm");
    assert!(text.contains("the kinetic energy is given twice"), "{text}");
    assert!(
        text.contains(" --> tests/fixtures/duplicate_energy.lpm:5:1"),
        "{text}"
    );
    assert!(
        text.contains("note: first given here\n --> tests/fixtures/duplicate_energy.lpm:4:11"),
        "{text}"
    );
}

#[test]
fn lexer_errors_in_files_are_located() {
    let source = "model X;\ncoordinates { x }\nkinetic = \"unterminated;\n";
    let err = Compiled::from_source(source).err().expect("must fail");
    let text = err.render("lex.lpm", source);
    assert!(text.contains("lex.lpm:3:"), "{text}");
}

#[test]
fn the_macro_expansion_of_a_bad_file_is_a_located_compile_error() {
    let out = lagrangian_core::expand::expand(quote!(file = "tests/fixtures/unknown_name.lpm"))
        .to_string();
    assert!(out.contains("compile_error"), "{out}");
    assert!(
        out.contains("tests/fixtures/unknown_name.lpm:8:19"),
        "{out}"
    );
    let missing =
        lagrangian_core::expand::expand(quote!(file = "tests/fixtures/absent.lpm")).to_string();
    assert!(
        missing.contains("cannot read spec file `tests/fixtures/absent.lpm`"),
        "{missing}"
    );
}

#[test]
fn the_macro_expansion_of_a_good_file_tracks_it_for_rebuilds() {
    let out = lagrangian_core::expand::expand(quote!(
        file = "../specs/double_pendulum.lpm",
        runtime = ::lagrangian_runtime
    ))
    .to_string();
    assert!(out.contains("include_str"), "{out}");
    assert!(out.contains("double_pendulum.lpm"), "{out}");
    assert!(
        out.contains(":: lagrangian_runtime :: LagrangianSystem < 2 > for DoublePendulum"),
        "{out}"
    );
}
