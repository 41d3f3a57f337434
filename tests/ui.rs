//! Compile-fail tests: every diagnostic of the `lagrangian!` macro points at
//! the offending tokens with a message that says how to fix it.

#[test]
fn diagnostics() {
    let t = trybuild::TestCases::new();
    t.compile_fail("tests/ui/*.rs");
}
