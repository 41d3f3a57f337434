//! Input beyond what the compiler represents exactly is a located error,
//! never a silently wrong model nor a panic.

use lagrangian_core::Compiled;

const HEADER: &str = "model Spring;
coordinates { x }
parameters { m = 1.0, k = 100.0 }
kinetic = 0.5 * m * pow(dot(x), 2);
";

/// Compiles `HEADER` + `body` and returns the rendered errors.
fn error_of(body: &str) -> String {
    let source = format!("{HEADER}{body}");
    match Compiled::from_source(&source) {
        Ok(_) => panic!("should not compile:\n{body}"),
        Err(e) => e.render("spring.lpm", &source),
    }
}

#[test]
fn a_literal_too_large_for_an_exact_rational_is_an_error_not_zero() {
    let huge = format!("1{}.0", "0".repeat(42));
    let text = error_of(&format!("potential = 0.5 * {huge} * k * pow(x, 2);"));
    assert!(
        text.contains(&format!("the literal `{huge}` is too large")),
        "{text}"
    );
    assert!(text.contains("spring.lpm:5:19"), "{text}");
}

#[test]
fn a_parameter_default_may_be_any_finite_f64() {
    let source = "model Spring;
coordinates { x }
parameters { m = 1.0, k = 1000000000000000000000000000000000000000000.0, c = -1e300 }
kinetic = 0.5 * m * pow(dot(x), 2);
potential = 0.5 * k * pow(x, 2) + c * x;
";
    let compiled = Compiled::from_source(source).unwrap();
    assert_eq!(compiled.default_parameters(), vec![1.0, 1e42, -1e300]);
    let text = match Compiled::from_source(&source.replace("1e300", "1e999")) {
        Ok(_) => panic!("1e999 is not finite"),
        Err(e) => e.to_string(),
    };
    assert!(text.contains("`1e999` is not a finite f64"), "{text}");
}
