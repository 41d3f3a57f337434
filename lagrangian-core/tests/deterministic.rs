//! The same spec derives to byte-identical output: equations, Markdown and
//! Rust, in one process and across hash-map states (each compile builds
//! fresh stores and maps).

use lagrangian_core::Compiled;
use lagrangian_core::emit::{Notation, RustOptions, emit_file, render_equations, render_markdown};

fn outputs(source: &str) -> (String, String, String) {
    let mut compiled = Compiled::from_source(source).unwrap();
    let text = render_equations(&mut compiled, Notation::Text);
    let markdown = render_markdown(&mut compiled, "spec.lpm");
    let rust = emit_file(compiled, &RustOptions::default(), "");
    (text, markdown, rust)
}

#[test]
fn derivation_is_byte_identical_from_run_to_run() {
    let dir = concat!(env!("CARGO_MANIFEST_DIR"), "/../specs");
    let mut sources: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|x| x == "lpm"))
        .map(|p| std::fs::read_to_string(p).unwrap())
        .collect();
    sources.extend((1..=5).map(lagrangian_core::examples::pendulum_chain));
    assert!(sources.len() >= 10);
    for source in &sources {
        let first = outputs(source);
        for _ in 0..3 {
            assert!(outputs(source) == first, "output differs for\n{source}");
        }
    }
}
