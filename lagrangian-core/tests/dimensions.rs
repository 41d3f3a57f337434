//! Dimensional analysis catches inconsistent terms and names them.

use lagrangian_core::Compiled;
use lagrangian_core::units::Dimension;

const HEADER: &str = "model Cart;
coordinates { x [m], theta [rad] }
parameters { m [kg] = 1.0, k [N/m] = 10.0, c [N*s/m] = 1.0, l [m] = 1.0, g [m/s^2] = 9.81, kt [N*m/rad] = 5.0 }
inputs { push(t [s]) [N], torque(angle [rad]) [N*m] }
kinetic = 0.5 * m * pow(dot(x), 2) + 0.5 * m * pow(l * dot(theta), 2);
";

fn error_of(body: &str) -> String {
    let source = format!("{HEADER}{body}");
    match Compiled::from_source(&source) {
        Ok(_) => panic!("should not compile:\n{body}"),
        Err(e) => e.render("cart.lpm", &source),
    }
}

/// Statements whose dimensions agree with the units of [`HEADER`].
const CONSISTENT: [&str; 5] = [
    "potential = 0.5 * k * pow(x, 2) + 0.5 * kt * pow(theta, 2) + m * g * l * (1.0 - cos(theta));",
    "dissipation = 0.5 * c * pow(dot(x), 2);",
    "force x = push(t);",
    "force theta = torque(theta);",
    "force at (x + l * sin(theta)) = (push(t));",
];

#[test]
fn a_consistent_spec_with_units_compiles() {
    let source = format!(
        "{HEADER}{}\nhand_derived {{ x = m * ddot(x) + k * x; theta = m * pow(l, 2) * ddot(theta) + kt * theta; }}",
        CONSISTENT.join("\n")
    );
    let compiled = Compiled::from_source(&source).unwrap();
    let model = &compiled.model;
    assert_eq!(
        model.coordinate_dimensions,
        vec![Some(Dimension::LENGTH), Some(Dimension::NONE)]
    );
    // The dimensions inferred for the terms as written: forces in the
    // equation of x, torques (N·m = J) in that of theta.
    let hand = model.hand_derived.as_ref().unwrap();
    let inferred: Vec<Vec<Option<Dimension>>> = hand
        .equations
        .iter()
        .map(|e| e.terms.iter().map(|t| t.dimension).collect())
        .collect();
    let (force, torque) = (Some(Dimension::FORCE), Some(Dimension::ENERGY));
    assert_eq!(inferred, vec![vec![force, force], vec![torque, torque]]);
}

#[test]
fn every_statement_of_the_consistent_spec_is_checked() {
    // Each statement times a length no longer has its dimension.
    let messages = [
        "the potential energy has dimension kg·m^3·s^-2, but must have J",
        "the dissipation function has dimension kg·m^3·s^-3, but must have W",
        "the generalized force on `x` has dimension J, but must have N",
        "the generalized force on `theta` has dimension kg·m^3·s^-2, but must have J",
        "this force component (× its point coordinate must be an energy) has dimension J, but must have N",
    ];
    for (k, message) in messages.iter().enumerate() {
        let mut statements = CONSISTENT.map(String::from);
        let statement = statements[k].trim_end_matches(';');
        statements[k] = match statement.strip_suffix(')') {
            Some(point_force) if k == 4 => format!("{point_force} * l);"),
            _ => {
                let (head, value) = statement.split_once(" = ").unwrap();
                format!("{head} = ({value}) * l;")
            }
        };
        let text = error_of(&statements.join("\n"));
        assert!(text.contains(message), "{}: {text}", statements[k]);
    }
}

#[test]
fn a_planted_term_in_the_potential_is_named() {
    let text = error_of("potential = 0.5 * k * pow(x, 2) + m * g * x + k * theta;");
    assert!(
        text.contains("this term has dimension kg·s^-2, but the other terms of the sum have J"),
        "{text}"
    );
    assert!(text.contains("cart.lpm:6:47"), "{text}");
    assert!(
        text.contains("^^^^^^^^^"),
        "the caret spans `k * theta`: {text}"
    );
}

#[test]
fn energies_powers_and_forces_have_their_dimensions() {
    let text = error_of("potential = k * x;");
    assert!(
        text.contains("the potential energy has dimension N, but must have J"),
        "{text}"
    );
    let text = error_of("dissipation = 0.5 * c * pow(dot(x), 2) * l;");
    assert!(
        text.contains("the dissipation function has dimension"),
        "{text}"
    );
    assert!(text.contains("must have W"), "{text}");
    let text = error_of("force theta = push(t);");
    assert!(
        text.contains("the generalized force on `theta` has dimension N, but must have J"),
        "{text}"
    );
    let text = error_of("force at (x) = (torque(theta));");
    assert!(text.contains("this force component"), "{text}");
}

#[test]
fn function_arguments_are_checked() {
    let text = error_of("potential = m * g * l * cos(x);");
    assert!(
        text.contains("the argument of `cos` has dimension m; it must be dimensionless"),
        "{text}"
    );
    let text = error_of("force theta = torque(x);");
    assert!(
        text.contains("argument 1 of `torque` has dimension m, but must have 1 (dimensionless)"),
        "{text}"
    );
}

#[test]
fn unknown_units_are_reported_at_the_unit() {
    let source = "model A; coordinates { x [km] } parameters { m [kg] = 1.0 } kinetic = 0.5 * m * pow(dot(x), 2);";
    let text = Compiled::from_source(source)
        .err()
        .unwrap()
        .render("a.lpm", source);
    assert!(text.contains("unknown unit `km`"), "{text}");
}

#[test]
fn specs_without_units_are_not_checked() {
    // `k * x + m` adds an energy to a mass, once units are declared.
    let body = "kinetic = 0.5 * m * pow(dot(x), 2); potential = k * x + m;";
    let with_units = format!(
        "model A; coordinates {{ x [m] }} parameters {{ m [kg] = 1.0, k [N] = 2.0 }} {body}"
    );
    let text = Compiled::from_source(&with_units)
        .err()
        .unwrap()
        .render("a.lpm", &with_units);
    assert!(
        text.contains("this term has dimension kg, but the other terms of the sum have J"),
        "{text}"
    );
    // Without units nothing has a dimension, and the same spec compiles.
    let without = format!("model A; coordinates {{ x }} parameters {{ m = 1.0, k = 2.0 }} {body}");
    let compiled = Compiled::from_source(&without).unwrap();
    assert_eq!(compiled.model.coordinate_dimensions, vec![None]);
    // A name without a unit makes the terms that use it unknown, and only
    // they go unchecked: `k * x` is unknown, `m` alone is no mismatch.
    let partly =
        format!("model A; coordinates {{ x [m] }} parameters {{ m [kg] = 1.0, k = 2.0 }} {body}");
    let compiled = Compiled::from_source(&partly).unwrap();
    assert_eq!(
        compiled.model.coordinate_dimensions,
        vec![Some(Dimension::LENGTH)]
    );
    // … and says so.
    let warnings = &compiled.model.warnings;
    assert_eq!(warnings.len(), 1);
    assert!(
        warnings[0].message.contains("not for `k`:"),
        "{}",
        warnings[0].message
    );
}

#[test]
fn exponents_are_evaluated_as_the_lowering_evaluates_them() {
    // `1 + 1` is the exponent 2 for the dimension checker too, so l² is not
    // an energy; before, only a plain literal was understood and this passed.
    let text = error_of("potential = m * g * pow(l, 1 + 1);");
    assert!(
        text.contains("the potential energy has dimension kg·m^3·s^-2"),
        "{text}"
    );
    let text = error_of("let two = 2; potential = m * g * pow(l, two);");
    assert!(
        text.contains("the potential energy has dimension"),
        "{text}"
    );
    // The same spelling with a consistent dimension compiles.
    let source = format!("{HEADER}let one = 3 - 2; potential = m * g * pow(l, 2 * one - (1 / 1));");
    Compiled::from_source(&source).unwrap();
}

#[test]
fn wrong_arities_are_reported_not_a_panic_of_the_checker() {
    for call in [
        "sin()",
        "sqrt()",
        "dot()",
        "pow(theta)",
        "theta.powi()",
        "ln(x, x)",
    ] {
        let text = error_of(&format!("potential = m * g * l * {call};"));
        assert!(text.contains("argument(s) but"), "{call}: {text}");
    }
}

#[test]
fn a_literal_zero_takes_the_dimension_its_place_needs() {
    let zeros = [
        "potential = 0.0;",
        "dissipation = 0.0;",
        "dissipation = -0.0;",
        "force x = 0;",
        "force theta = (0.0);",
        "force at (x, l) = (0.0, push(t));",
        "potential = 0.5 * k * pow(x, 2) + 0.0 - 0;",
        "dissipation = 0.0 * pow(dot(x), 2);",
    ];
    for statement in zeros {
        let source = format!("{HEADER}{statement}");
        let compiled = Compiled::from_source(&source)
            .unwrap_or_else(|e| panic!("{statement}: {}", e.render("cart.lpm", &source)));
        assert!(compiled.model.warnings.is_empty(), "{statement}");
    }
    // A zero beside a term of the wrong dimension does not hide it, and a
    // literal that is not zero stays dimensionless.
    let text = error_of("potential = k * x + 0.0;");
    assert!(
        text.contains("the potential energy has dimension N, but must have J"),
        "{text}"
    );
    let text = error_of("dissipation = 1.0;");
    assert!(
        text.contains("the dissipation function has dimension 1 (dimensionless), but must have W"),
        "{text}"
    );
}

#[test]
fn a_spec_without_any_unit_is_not_checked_nor_warned_about() {
    let source = "model P; coordinates { q } parameters { m = 1.0 }
        kinetic = 0.5 * m * pow(dot(q), 2); potential = 1.0 - cos(q); dissipation = 2.0;";
    let compiled = Compiled::from_source(source).unwrap();
    assert!(compiled.model.warnings.is_empty());
    assert_eq!(compiled.model.coordinate_dimensions, vec![None]);
}

#[test]
fn names_without_units_among_names_with_units_are_listed_in_one_warning() {
    let source = "model A;
coordinates { x [m], y }
parameters { m [kg] = 1.0, k = 2.0 }
inputs { push(s) [N] }
kinetic = 0.5 * m * pow(dot(x), 2) + 0.5 * m * pow(dot(y), 2);
potential = 0.5 * k * pow(x, 2);
force x = push(x);";
    let compiled = Compiled::from_source(source).unwrap();
    let warnings = &compiled.model.warnings;
    assert_eq!(warnings.len(), 1, "{warnings:?}");
    let text = warnings[0].render_warning("a.lpm", source);
    assert!(
        text.starts_with(
            "warning: units are declared for some names but not for `y`, `k`, `s` (argument of `push`): \
             the terms that use them are not checked for dimensions\n"
        ),
        "{text}"
    );
    assert!(text.contains("--> a.lpm:2:22"), "at `y`: {text}");
    assert!(
        text.contains("help: declare a unit for each name (e.g. `k [N/m]`), or for none"),
        "{text}"
    );
    // With every unit declared the spec compiles without a warning.
    let full = source
        .replace("y }", "y [m] }")
        .replace("k = 2.0", "k [N/m] = 2.0")
        .replace("push(s)", "push(s [m])");
    assert!(
        Compiled::from_source(&full)
            .unwrap()
            .model
            .warnings
            .is_empty()
    );
}
