//! `constraint NAME = expr;`: the errors of a bad constraint (message and
//! place), and `g`, `∂g/∂t`, `G`, `γ` against a pendulum in Cartesian
//! coordinates worked out by hand.

use lagrangian_core::Compiled;
use lagrangian_runtime::NoInputs;
use lagrangian_runtime::layout::ConstraintLayout;

/// A point mass in the plane held at distance `l` from the origin.
const PENDULUM: &str = "model CartesianPendulum;
coordinates { x [m], y [m] }
parameters { m [kg] = 2.0, l [m] = 1.5, g [m/s^2] = 9.81 }
kinetic = 0.5 * m * (pow(dot(x), 2) + pow(dot(y), 2));
potential = m * g * y;
";

/// The constraints' lines start at line 6 of the spec.
fn error_of(body: &str) -> String {
    let source = format!("{PENDULUM}{body}");
    match Compiled::from_source(&source) {
        Ok(_) => panic!("should not compile:\n{body}"),
        Err(e) => e.render("p.lpm", &source),
    }
}

fn assert_error(body: &str, message: &str, at: &str) {
    let error = error_of(body);
    assert!(error.contains(message), "{error}");
    assert!(error.contains(&format!("--> p.lpm:{at}\n")), "{error}");
}

#[test]
fn a_constraint_with_a_velocity_is_an_error_at_it() {
    assert_error(
        "constraint rod = x * dot(x) + y * dot(y);",
        "the constraint `rod` uses the velocity `dot(x)`",
        "6:18",
    );
}

#[test]
fn unknown_and_duplicate_names_are_errors_at_them() {
    assert_error(
        "constraint rod = x * x + y * y - len * len;",
        "unknown name `len`",
        "6:34",
    );
    assert_error(
        "constraint rod = x * x + y * y - l * l;\nconstraint rod = x;",
        "`rod` is declared twice",
        "7:12",
    );
    assert_error("constraint x = y;", "`x` is declared twice", "6:12");
    assert_error(
        "constraint rod = x * x + y * y - l * l;\nconstraint pin = rod;",
        "`rod` is a constraint, which expressions cannot use",
        "7:18",
    );
}

#[test]
fn a_constraint_whose_terms_disagree_in_units_is_an_error() {
    let error = error_of("constraint rod = x * x + y - l * l;");
    assert!(error.contains("dimension"), "{error}");
    assert!(error.contains("--> p.lpm:6:"), "{error}");
}

/// `g = x² + y² − l²`: `G = (2x, 2y)`, `g_t = 0`, `γ = −2(ẋ² + ẏ²)`; the
/// multiplier is in J/m² (energy per unit of `g`).
#[test]
fn the_terms_of_a_circle() {
    let source = format!("{PENDULUM}/// The rod.\nconstraint rod = x * x + y * y - l * l;\n");
    let compiled = Compiled::from_source(&source).unwrap();
    assert_eq!(
        compiled.model.constraints[0].multiplier_unit().as_deref(),
        Some("kg·s^-2")
    );
    let model = compiled.interpreted();
    assert_eq!(model.constraint_names(), ["rod"]);
    let (q, qd) = ([0.3, -1.1], [0.7, -0.4]);
    let layout = ConstraintLayout { m: 1, n: 2 };
    let mut out = vec![f64::NAN; layout.len()];
    model
        .evaluate_constraints(0.5, &q, &qd, &NoInputs, &mut out)
        .unwrap();
    let expected = [
        0.3 * 0.3 + 1.1 * 1.1 - 1.5 * 1.5,
        0.0,
        0.6,
        -2.2,
        -2.0 * (0.7 * 0.7 + 0.4 * 0.4),
    ];
    for (found, expected) in out.iter().zip(expected) {
        assert!((found - expected).abs() < 1e-14, "{out:?} vs {expected:?}");
    }
}

/// A driven constraint `x − a sin(ω t) = 0`: `g_t = −a ω cos(ω t)` and
/// `γ = −a ω² sin(ω t)`, the acceleration of the drive.
#[test]
fn the_terms_of_a_driven_constraint() {
    let source = PENDULUM
        .replace("[m]", "")
        .replace("[kg]", "")
        .replace("[m/s^2]", "")
        + "constraint drive = x - 0.25 * l * sin(2.0 * t);\n";
    let model = Compiled::from_source(&source).unwrap().interpreted();
    let (t, a) = (0.4_f64, 0.375);
    let mut out = vec![f64::NAN; 5];
    model
        .evaluate_constraints(t, &[0.1, 0.2], &[0.3, 0.4], &NoInputs, &mut out)
        .unwrap();
    let expected = [
        0.1 - a * (2.0 * t).sin(),
        -2.0 * a * (2.0 * t).cos(),
        1.0,
        0.0,
        -4.0 * a * (2.0 * t).sin(),
    ];
    for (found, expected) in out.iter().zip(expected) {
        assert!((found - expected).abs() < 1e-14, "{out:?} vs {expected:?}");
    }
}

/// `lpm derive` (text and Markdown) and the audit show `g`, the nonzero
/// entries of `G` and `γ`; a model without constraints shows none.
#[test]
fn the_equations_and_the_audit_show_the_constraints() {
    use lagrangian_core::audit::{audit, markdown};
    use lagrangian_core::emit::{Notation, render_equations, render_markdown};
    let source = format!("{PENDULUM}constraint rod = x * x + y * y - l * l;\n");
    let mut compiled = Compiled::from_source(&source).unwrap();
    let text = render_equations(&mut compiled, Notation::Text);
    for line in [
        "Constraints g(q, t) = 0, held by multipliers λ",
        "  g[rod] = x^2 + y^2 - l^2\n",
        "  G[rod, x] = 2*x\n",
        "  G[rod, y] = 2*y\n",
        "  γ[rod] = -2*dot(x)^2 - 2*dot(y)^2\n",
    ] {
        assert!(text.contains(line), "{line} in\n{text}");
    }
    let md = render_markdown(&mut compiled, "p.lpm");
    assert!(md.contains("## Constraints"), "{md}");
    assert!(md.contains("\\gamma_{\\mathrm{rod}}"), "{md}");
    let hand = "hand_derived { x = m * ddot(x); y = m * ddot(y) + m * g; }";
    let mut compiled = Compiled::from_source(&format!("{source}{hand}")).unwrap();
    let report = audit(&mut compiled).unwrap();
    assert!(!report.disagrees());
    let md = markdown(&report, "p.lpm");
    assert!(md.contains("without the constraint forces"), "{md}");
    assert!(md.contains("G_{\\mathrm{rod},\\,x}"), "{md}");
    let mut plain = Compiled::from_source(PENDULUM).unwrap();
    assert!(!render_equations(&mut plain, Notation::Text).contains("Constraints"));
}

#[test]
fn a_constraint_on_no_coordinate_is_unsatisfiable_or_void_and_says_so() {
    assert_error(
        "constraint fixed = l;",
        "error: the constraint `fixed` cannot be satisfied: it depends on no coordinate, and its residual is 1.5e0 with the default parameters whatever the state",
        "6:20",
    );
    assert_error(
        "constraint clock = t;",
        "error: the constraint `clock` cannot be satisfied: it depends on time but on no coordinate, so no motion can hold it at 0 (its residual is 0e0 at t = 0 with the default parameters)",
        "6:20",
    );
    assert_error(
        "constraint void = l - 1.5 * l;",
        "cannot be satisfied: it depends on no coordinate, and its residual is -7.5e-1",
        "6:19",
    );
    assert_error(
        "constraint void = l - l;",
        "error: the constraint `void` depends on no coordinate: with the default parameters it is 0 for every state, so it constrains nothing",
        "6:19",
    );
}
