//! `output NAME [unit] = expr;`: the errors of a bad output (message and
//! place), and values against a pendulum worked out by hand.

use lagrangian_core::Compiled;
use lagrangian_runtime::NoInputs;

/// A point-mass pendulum on a rod of length `l`.
const PENDULUM: &str = "model Pendulum;
coordinates { theta [rad] }
parameters { m [kg] = 2.0, l [m] = 1.5, g [m/s^2] = 9.81 }
let x = l * sin(theta);
let y = -l * cos(theta);
kinetic = 0.5 * m * (pow(dot(x), 2) + pow(dot(y), 2));
potential = m * g * y;
";

/// The outputs' lines start at line 8 of the spec.
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
fn an_output_named_like_another_name_is_an_error_at_the_output() {
    let first = "note: first declared here";
    for (body, at, first_at) in [
        ("output theta [rad] = theta;", "8:8", "2:15"),
        ("output l [m] = x;", "8:8", "3:28"),
        ("output x [m] = x;", "8:8", "4:5"),
        ("output tip [m] = x;\noutput tip [m] = y;", "9:8", "8:8"),
    ] {
        let name = body[7..].split_whitespace().next().unwrap();
        assert_error(body, &format!("`{name}` is declared twice"), at);
        let error = error_of(body);
        let note = error.find(first).expect(&error);
        assert!(
            error[note..].contains(&format!("p.lpm:{first_at}\n")),
            "{error}"
        );
    }
    assert_error(
        "output t [s] = t;",
        "`t` is reserved by the spec language",
        "8:8",
    );
}

#[test]
fn ddot_outside_an_output_says_why() {
    let why = "`ddot` is only available in `hand_derived` equations and in outputs: \
               accelerations are what the equations of motion solve for, not an input to them";
    assert_error("let a = ddot(theta);", why, "8:9");
    assert_error("dissipation = m * pow(ddot(x), 2);", why, "8:23");
    assert_error("force theta = m * l * ddot(theta);", why, "8:23");
    // Through a `let`, the error is at the `let`, not at the output using it.
    let error = error_of("let a = ddot(x);\noutput ax [m/s^2] = a;");
    assert!(
        error.contains(why) && error.contains("--> p.lpm:8:9\n"),
        "{error}"
    );
    assert!(!error.contains("p.lpm:9:"), "{error}");
}

#[test]
fn an_output_is_checked_against_its_unit() {
    assert_error(
        "output tip [m] = dot(x);",
        "the output `tip` has dimension m·s^-1, but must have m",
        "8:18",
    );
    assert_error(
        "output tangential [m/s^2] = ddot(theta);",
        "the output `tangential` has dimension s^-2, but must have m·s^-2",
        "8:29",
    );
    assert_error(
        "output speed [m/s] = dot(x);\noutput bad [kg/s] = x;",
        "the output `bad` has dimension m, but must have kg·s^-1",
        "9:21",
    );
    assert_error("output tip [furlong] = x;", "furlong", "8:12");
}

#[test]
fn unknown_names_in_an_output_suggest_the_closest() {
    assert_error("output tip [m] = xx;", "unknown name `xx`", "8:18");
    assert!(error_of("output tip [m] = xx;").contains("did you mean `x`?"));
    assert_error(
        "output a [m/s^2] = l * ddot(thetta);",
        "unknown name `thetta`",
        "8:29",
    );
    assert!(error_of("output a [m/s^2] = l * ddot(thetta);").contains("did you mean `theta`?"));
}

#[test]
fn an_output_cannot_be_used_in_an_expression() {
    assert_error(
        "output tip [m] = x;\nforce theta = tip;",
        "`tip` is an output, which expressions cannot use",
        "9:15",
    );
    assert_error(
        "output tip [m] = x;\noutput twice [m] = 2.0 * tip;",
        "`tip` is an output, which expressions cannot use",
        "9:26",
    );
}

/// The tip's position `(l sin θ, −l cos θ)` and, with `θ̈ = −(g/l) sin θ`
/// (Newton along the tangent, worked by hand), its tangential acceleration
/// `l θ̈ = −g sin θ` and horizontal acceleration
/// `ẍ = l (θ̈ cos θ − θ̇² sin θ)`.
#[test]
fn outputs_match_the_pendulum_worked_by_hand() {
    let source = format!(
        "{PENDULUM}
/// Horizontal position of the bob.
output tip_x [m] = x;
output tip_y [m] = y;
output tangential [m/s^2] = l * ddot(theta);
output ax [m/s^2] = ddot(x);
output time_and_speed = t * dot(theta);
"
    );
    let compiled = Compiled::from_source(&source).unwrap();
    let names: Vec<&str> = compiled
        .model
        .outputs
        .iter()
        .map(|o| o.name.as_str())
        .collect();
    assert_eq!(
        names,
        ["tip_x", "tip_y", "tangential", "ax", "time_and_speed"]
    );
    assert_eq!(
        compiled.model.outputs[0].doc,
        ["Horizontal position of the bob."]
    );
    let model = compiled.interpreted();
    assert_eq!(model.output_names(), names);
    let units: Vec<Option<&str>> = model.output_units().iter().map(|u| u.as_deref()).collect();
    assert_eq!(
        units,
        [Some("m"), Some("m"), Some("m/s^2"), Some("m/s^2"), None]
    );
    let (l, g, theta, omega, t) = (1.5, 9.81, 0.4_f64, -0.8_f64, 0.3);
    let (mut mass, mut forcing) = ([0.0], [0.0]);
    let state = ([theta], [omega]);
    model
        .evaluate_dynamics(t, &state.0, &state.1, &NoInputs, &mut mass, &mut forcing)
        .unwrap();
    let qdd = [forcing[0] / mass[0]];
    let mut out = [0.0; 5];
    model
        .evaluate_outputs((t, &state.0, &state.1, &qdd), &NoInputs, &mut out)
        .unwrap();
    let theta_dd = -g / l * theta.sin();
    let expected = [
        l * theta.sin(),
        -l * theta.cos(),
        -g * theta.sin(),
        l * (theta_dd * theta.cos() - omega * omega * theta.sin()),
        t * omega,
    ];
    for (k, (found, expected)) in out.iter().zip(expected).enumerate() {
        assert!(
            (found - expected).abs() <= 1e-12 * expected.abs().max(1.0),
            "output {k}: {found} vs {expected}"
        );
    }
}

/// A spec without outputs gets the program it had: no outputs routine, and
/// the outputs of a spec with them come last.
#[test]
fn outputs_add_a_routine_and_change_no_other() {
    use lagrangian_core::program::RoutineKind;
    let without = Compiled::from_source(PENDULUM).unwrap();
    let with =
        Compiled::from_source(&format!("{PENDULUM}output a [m/s^2] = ddot(x) + ddot(y);")).unwrap();
    assert!(without.program.routine(RoutineKind::Outputs).is_none());
    let outputs = with.program.routine(RoutineKind::Outputs).unwrap();
    assert_eq!(outputs.outputs.len(), 1);
    assert_eq!(
        with.program.ops[..without.program.ops.len()],
        without.program.ops[..]
    );
    for routine in &without.program.routines {
        let same = with.program.routine(routine.kind).unwrap();
        assert_eq!((&same.ops, &same.outputs), (&routine.ops, &routine.outputs));
    }
    assert!(without.interpreted().output_names().is_empty());
}

#[test]
fn an_output_named_as_a_built_in_trajectory_column_is_an_error_at_it() {
    for (body, column) in [
        (
            "output theta_dot [rad/s] = dot(theta);",
            "the velocity of the coordinate `theta`",
        ),
        (
            "output theta_ddot [rad/s^2] = ddot(theta);",
            "the acceleration of the coordinate `theta`",
        ),
        (
            "output kinetic_energy [J] = 0.5 * m * pow(l * dot(theta), 2);",
            "the energy column `kinetic_energy`",
        ),
        (
            "output potential_energy [J] = m * g * l;",
            "the energy column `potential_energy`",
        ),
        (
            "output dissipated_energy [J] = m * g * l;",
            "the energy column `dissipated_energy`",
        ),
        (
            "output external_work [J] = m * g * l;",
            "the energy column `external_work`",
        ),
    ] {
        let name = body.split_whitespace().nth(1).unwrap();
        let message =
            format!("the output `{name}` has the name of a built-in trajectory column, {column}");
        assert_error(body, &message, "8:8");
    }
    // Near names are fine: `theta_dotted`, `energy`.
    let source = format!(
        "{PENDULUM}output theta_dotted [rad/s] = dot(theta);\noutput energy [J] = m * g * l;\n"
    );
    Compiled::from_source(&source).unwrap();
}

#[test]
fn a_coordinate_or_input_named_as_a_built_in_column_is_an_error_at_it() {
    let source = "model Two;
coordinates { x [m], x_dot [m] }
parameters { m [kg] = 1.0 }
inputs { external_work(s [m]) [N] }
kinetic = 0.5 * m * (pow(dot(x), 2) + pow(dot(x_dot), 2));
force x = external_work(x);
";
    let error = match Compiled::from_source(source) {
        Ok(_) => panic!("compiled"),
        Err(e) => e.render("two.lpm", source),
    };
    assert!(error.contains("error: the coordinate `x_dot` has the name of a built-in trajectory column, the velocity of the coordinate `x`\n --> two.lpm:2:22\n"), "{error}");
    assert!(error.contains("error: the input `external_work` has the name of a built-in trajectory column, the energy column `external_work`\n --> two.lpm:4:10\n"), "{error}");
}
