//! The functions of the spec language at compile time: dimensions, names,
//! constant arguments outside their domain, and what `lpm derive` prints.

use lagrangian_core::Compiled;

const HEADER: &str = "model Cart;
coordinates { x [m], y [m], theta [rad] }
parameters { m [kg] = 1.0, k [N/m] = 10.0, l [m] = 1.0, w [s] = 2.0 }
kinetic = 0.5 * m * (pow(dot(x), 2) + pow(dot(y), 2) + pow(l * dot(theta), 2));
";

fn error_of(body: &str) -> String {
    let source = format!("{HEADER}{body}");
    match Compiled::from_source(&source) {
        Ok(_) => panic!("should not compile:\n{body}"),
        Err(e) => e.render("cart.lpm", &source),
    }
}

#[test]
fn functions_with_consistent_dimensions_compile() {
    let body = "potential = k * l * (hypot(x, y) + abs(x) + min(x, y) + max(x, 0.5 * l))
        + k * l * l * (atan2(y, x) + asin(x / (2 * l)) + acos(y / (3 * l)) + atan(x / l)
        + sinh(x / l) + cosh(y / l) + tanh(theta) + sign(x) + cot(theta + 1) + sec(theta));";
    let source = format!("{HEADER}{body}");
    let compiled = Compiled::from_source(&source).unwrap();
    let potential = compiled.model.potential.as_ref().unwrap().value;
    let printed = compiled.model.store.display(potential).to_string();
    // Printed as written, not rewritten in exponentials.
    for call in [
        "hypot(x, y)",
        "atan2(y, x)",
        "tanh(theta)",
        "max(x, 1/2*l)",
        "sign(x)",
    ] {
        assert!(printed.contains(call), "{call} in {printed}");
    }
}

#[test]
fn arguments_must_have_the_dimension_the_function_needs() {
    let cases = [
        (
            "potential = k * l * l * asin(x);",
            "the argument of `asin` has dimension m; it must be dimensionless",
        ),
        (
            "potential = k * l * l * tanh(w);",
            "the argument of `tanh` has dimension s; it must be dimensionless",
        ),
        (
            "potential = k * l * l * atan2(y, w);",
            "argument 2 of `atan2` has dimension s, but must have m",
        ),
        (
            "potential = k * l * min(x, theta);",
            "argument 2 of `min` has dimension 1 (dimensionless), but must have m",
        ),
        // hypot, abs and max return the dimension of their arguments.
        (
            "potential = k * hypot(x, y);",
            "the potential energy has dimension N, but must have J",
        ),
        (
            "potential = k * l * abs(x) * max(x, y);",
            "kg·m^3·s^-2, but must have J",
        ),
    ];
    for (body, message) in cases {
        let error = error_of(body);
        assert!(error.contains(message), "{body}:\n{error}");
    }
}

#[test]
fn did_you_mean_only_for_close_names() {
    // The functions are known now: no suggestion, no advice to declare them.
    let source = format!("{HEADER}potential = k * l * l * (acos(y / l) + atan2(y, x));");
    Compiled::from_source(&source).unwrap();
    let error = error_of("potential = k * l * l * arccos(y / l);");
    assert!(error.contains("did you mean `acos`?"), "{error}");
    let error = error_of("potential = k * l * l * frobnicate(y / l);");
    assert!(error.contains("unknown function `frobnicate`"), "{error}");
    assert!(!error.contains("did you mean"), "{error}");
}

#[test]
fn a_declared_name_hides_a_function_that_is_not_reserved() {
    let source = "model M;
        coordinates { x }
        parameters { m = 1.0, max = 2.0 }
        inputs { sign(s) }
        kinetic = 0.5 * m * pow(dot(x), 2);
        potential = max * x * x;
        force x = sign(x);";
    let compiled = Compiled::from_source(source).unwrap();
    assert_eq!(
        compiled
            .program
            .routine(lagrangian_core::program::RoutineKind::Switching)
            .map(|r| r.outputs.len()),
        None
    );
}

#[test]
fn a_constant_argument_outside_the_domain_is_an_error() {
    let error = error_of("potential = k * l * l * acos(2);");
    assert!(
        error.contains("`acos` of the constant 2: it is defined on [-1, 1] only"),
        "{error}"
    );
    // Folded at compile time: the non-smooth functions of constants.
    let source = format!("{HEADER}potential = k * l * l * (abs(-2) + min(1, 3) + sign(-0.5));");
    let compiled = Compiled::from_source(&source).unwrap();
    let potential = compiled.model.potential.as_ref().unwrap().value;
    assert_eq!(
        compiled.model.store.display(potential).to_string(),
        "2*k*l^2"
    );
}

#[test]
fn calls_with_a_restricted_domain_are_named_at_a_failing_state() {
    let source = format!("{HEADER}potential = k * l * l * (acos(x / l) + ln(y / l));");
    let compiled = Compiled::from_source(&source).unwrap();
    let model = &compiled.model;
    let parameters: Vec<f64> = model.parameters.iter().map(|p| p.default).collect();
    let at = |x: f64, y: f64| model.domain_violation(0.0, &[x, y, 0.0], &[0.0; 3], &parameters);
    assert!(at(0.5, 0.5).is_none());
    let (check, value) = at(1.5, 0.5).unwrap();
    assert_eq!(value, 1.5);
    assert_eq!(
        check.describe("cart.lpm", &source, value),
        "cart.lpm:5:26: the argument of `acos(x / l)` is 1.5 but must be in [-1, 1]"
    );
    let (check, value) = at(0.5, -1.0).unwrap();
    assert_eq!(
        check.describe("cart.lpm", &source, value),
        "cart.lpm:5:40: the argument of `ln(y / l)` is -1 but must be positive"
    );
}
