//! A spec's equations of motion as text (or LaTeX with a second argument):
//! `cargo run -p lagrangian-core --example derive -- SPEC [latex]`.

fn main() {
    let path = std::env::args().nth(1).unwrap();
    let latex = std::env::args().nth(2).is_some();
    let src = std::fs::read_to_string(&path).unwrap();
    let mut c = lagrangian_core::Compiled::from_source(&src).unwrap();
    let n = if latex {
        lagrangian_core::emit::Notation::Latex
    } else {
        lagrangian_core::emit::Notation::Text
    };
    print!("{}", lagrangian_core::emit::render_equations(&mut c, n));
}
