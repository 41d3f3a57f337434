//! `lpm linearize` against closed forms and SymPy's linearization
//! (`tests/reference/linearize_reference.py`, its JSON committed).

mod common;

use common::{ROOT, lpm, stderr, stdout};
use serde_json::Value;
use std::f64::consts::TAU;

/// The JSON report of `lpm linearize ARGS --format json`.
fn linearize(args: &[&str]) -> Value {
    let mut all = vec!["linearize"];
    all.extend(args);
    all.extend(["--format", "json"]);
    let out = lpm(&all);
    assert!(out.status.success(), "{all:?}: {}", stderr(&out));
    serde_json::from_str(&stdout(&out)).unwrap()
}

fn floats(v: &Value) -> Vec<f64> {
    v.as_array()
        .unwrap()
        .iter()
        .map(|x| x.as_f64().unwrap())
        .collect()
}

fn matrix(v: &Value) -> Vec<Vec<f64>> {
    v.as_array().unwrap().iter().map(floats).collect()
}

fn close(found: f64, expected: f64, tolerance: f64, what: &str) {
    assert!(
        (found - expected).abs() <= tolerance * expected.abs().max(1.0),
        "{what}: {found} vs {expected}"
    );
}

#[test]
fn a_pendulum_swings_at_the_square_root_of_g_over_l_over_two_pi() {
    let report = linearize(&["specs/simple_pendulum.lpm", "--set", "l=0.5"]);
    let frequencies = floats(&report["natural_frequencies_hz"]);
    assert_eq!(frequencies.len(), 1);
    close(frequencies[0], (9.81_f64 / 0.5).sqrt() / TAU, 1e-12, "f");
    assert_eq!(report["modes"][0]["kind"], "undamped");
    assert_eq!(report["A_from"], "derived Jacobians");
    assert_eq!(report["operating_point"]["q"]["theta"], 0.0);
}

#[test]
fn the_double_pendulum_has_its_closed_form_frequencies() {
    // Equal masses and lengths: ω² = (g/l)(2 ∓ √2).
    let report = linearize(&[
        "specs/double_pendulum.lpm",
        "--set",
        "l1=0.5",
        "--set",
        "l2=0.5",
    ]);
    let frequencies = floats(&report["natural_frequencies_hz"]);
    let (g, l) = (9.81_f64, 0.5);
    let expected = [
        ((g / l) * (2.0 - 2.0_f64.sqrt())).sqrt() / TAU,
        ((g / l) * (2.0 + 2.0_f64.sqrt())).sqrt() / TAU,
    ];
    assert_eq!(frequencies.len(), 2);
    for (f, e) in frequencies.iter().zip(expected) {
        close(*f, e, 1e-12, "f");
    }
    assert_eq!(floats(&report["damping_ratios"]), [0.0, 0.0]);
}

#[test]
fn a_spring_mass_damper_has_its_damping_ratio_and_damped_frequency() {
    let (m, k, c) = (2.0_f64, 50.0_f64, 3.0_f64);
    let report = linearize(&[
        "specs/spring_mass_damper.lpm",
        "--set",
        "m=2",
        "--set",
        "k=50",
        "--set",
        "c=3",
    ]);
    let zeta = c / (2.0 * (k * m).sqrt());
    let mode = &report["modes"][0];
    close(mode["damping_ratio"].as_f64().unwrap(), zeta, 1e-12, "ζ");
    let omega_d = (k / m).sqrt() * (1.0 - zeta * zeta).sqrt();
    close(
        mode["eigenvalue"]["im"].as_f64().unwrap(),
        omega_d,
        1e-12,
        "ω_d",
    );
    assert_eq!(mode["kind"], "underdamped");
    assert_eq!(report["input_names"][0], "push");
    let column = report["B_columns"][0].as_str().unwrap();
    assert!(column.contains("push = 0 (unbound: held at 0)"), "{column}");
}

fn reference() -> Value {
    let path = format!("{ROOT}/tests/reference/linearize_reference.json");
    serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap()
}

/// `lpm linearize` of `spec` with the reference case's parameters at
/// `at`, compared with SymPy's `A` and `B`.
fn matches_sympy(case: &str, spec: &str, at: &str) {
    let reference = &reference()[case];
    let settings: Vec<String> = (reference["parameters"].as_object().unwrap().iter())
        .map(|(name, value)| format!("--set={name}={value}"))
        .collect();
    let mut args = vec![spec, "--at", at];
    args.extend(settings.iter().map(String::as_str));
    let report = linearize(&args);
    for key in ["A", "B"] {
        let (found, expected) = (matrix(&report[key]), matrix(&reference[key]));
        assert_eq!(found.len(), expected.len(), "{case} {key}");
        for (i, (row, expected_row)) in found.iter().zip(&expected).enumerate() {
            assert_eq!(row.len(), expected_row.len(), "{case} {key}");
            for (j, (x, e)) in row.iter().zip(expected_row).enumerate() {
                close(*x, *e, 1e-9, &format!("{case} {key}[{i}][{j}]"));
            }
        }
    }
    let inputs: Vec<&Value> = reference["inputs"].as_array().unwrap().iter().collect();
    let found: Vec<&Value> = report["input_names"].as_array().unwrap().iter().collect();
    assert_eq!(found, inputs, "{case}");
}

#[test]
fn the_spring_mass_damper_matches_sympy() {
    matches_sympy(
        "spring_mass_damper",
        "specs/spring_mass_damper.lpm",
        "equilibrium",
    );
}

#[test]
fn the_double_pendulum_at_rest_matches_sympy() {
    matches_sympy(
        "double_pendulum_equilibrium",
        "specs/double_pendulum.lpm",
        "equilibrium",
    );
}

#[test]
fn the_moving_double_pendulum_matches_sympy_in_either_form_of_the_state() {
    let case = "double_pendulum_moving";
    let named = "theta1=0.3,theta2=-0.2,dot(theta1)=0.1,dot(theta2)=0.4";
    matches_sympy(case, "specs/double_pendulum.lpm", named);
    // eval's form: coordinates, then velocities.
    matches_sympy(case, "specs/double_pendulum.lpm", "0.3,-0.2,0.1,0.4");
}

#[test]
fn the_operating_point_is_reported_with_how_far_the_equilibrium_moved() {
    // A constant push of 3 N on k = 100 N/m moves the equilibrium to 0.03 m.
    let report = linearize(&["specs/spring_mass_damper.lpm", "--set", "push=3"]);
    let point = &report["operating_point"];
    close(point["q"]["x"].as_f64().unwrap(), 0.03, 1e-12, "x");
    close(
        point["equilibrium"]["moved"]["x"].as_f64().unwrap(),
        0.03,
        1e-12,
        "moved",
    );
    assert_eq!(point["equilibrium"]["solved_for"][0], "x");
    let column = report["B_columns"][0].as_str().unwrap();
    assert!(
        column.contains("push = 3 (the constant of `--set push`)"),
        "{column}"
    );
}

#[test]
fn markdown_is_the_default_and_out_writes_a_file() {
    let out = lpm(&["linearize", "specs/double_pendulum.lpm"]);
    assert!(out.status.success(), "{}", stderr(&out));
    let text = stdout(&out);
    for heading in [
        "## Operating point",
        "## Modes",
        "## A = ∂ẋ/∂x",
        "## B = ∂ẋ/∂u",
    ] {
        assert!(text.contains(heading), "{heading}: {text}");
    }
    let path = common::temporary("linearize-out").join("modes.json");
    let file = path.to_str().unwrap();
    let out = lpm(&[
        "linearize",
        "specs/double_pendulum.lpm",
        "--format",
        "json",
        "--out",
        file,
    ]);
    assert!(out.status.success(), "{}", stderr(&out));
    let report: Value = serde_json::from_str(&std::fs::read_to_string(&path).unwrap()).unwrap();
    assert_eq!(floats(&report["natural_frequencies_hz"]).len(), 2);
}

#[test]
fn bad_states_and_no_equilibrium_fail_with_their_status() {
    let cases: [(&[&str], i32, &str); 4] = [
        (&["--at", "thta1=0.3"], 2, "did you mean `theta1`?"),
        (&["--at", "0.1,0.2"], 2, "--at needs 4 values"),
        (&["--at", "theta1=x"], 2, "`x` is not a number"),
        (
            &["--at", "dot(theta3)=1"],
            2,
            "`theta3` is not a coordinate",
        ),
    ];
    for (args, status, message) in cases {
        let mut all = vec!["linearize", "specs/double_pendulum.lpm"];
        all.extend(args);
        let out = lpm(&all);
        assert_eq!(
            out.status.code(),
            Some(status),
            "{args:?}: {}",
            stderr(&out)
        );
        assert!(stderr(&out).contains(message), "{args:?}: {}", stderr(&out));
    }
    // A constant force on a mass without a spring: no static equilibrium.
    let out = lpm(&[
        "linearize",
        "specs/spring_mass_damper.lpm",
        "--set",
        "k=0",
        "--set",
        "push=1",
    ]);
    assert_eq!(out.status.code(), Some(16), "{}", stderr(&out));
    assert!(
        stderr(&out).contains("no static equilibrium"),
        "{}",
        stderr(&out)
    );
}

/// The four-bar as a parallelogram (ground and coupler 0.7 m, crank and
/// rocker 0.3 m) hangs with crank and rocker straight down; on its loop it
/// has one mode, that of its one coordinate θ:
/// `ω² = g (m1/2 + m2 + m3/2) / ((m1/3 + m2 + m3/3) l1)`.
#[test]
fn the_parallelogram_four_bar_has_one_mode_on_its_loop() {
    let report = linearize(&[
        "specs/four_bar_linkage.lpm",
        "--set",
        "l2=0.7",
        "--set",
        "l3=0.3",
        "--set",
        "initial.coordinates.theta1=-1.3",
        "--set",
        "initial.coordinates.theta2=0.2",
        "--set",
        "initial.coordinates.theta3=-1.4",
    ]);
    let (l1, m1, m2, m3, g) = (0.3_f64, 1.0, 2.0, 1.5, 9.81);
    let omega2 = g * (m1 / 2.0 + m2 + m3 / 2.0) / ((m1 / 3.0 + m2 + m3 / 3.0) * l1);
    let frequencies = floats(&report["natural_frequencies_hz"]);
    assert_eq!(frequencies.len(), 1, "{frequencies:?}");
    close(frequencies[0], omega2.sqrt() / TAU, 1e-7, "f");
    let q = &report["operating_point"]["q"];
    close(
        q["theta1"].as_f64().unwrap(),
        -std::f64::consts::FRAC_PI_2,
        1e-9,
        "θ1",
    );
    close(q["theta2"].as_f64().unwrap(), 0.0, 1e-9, "θ2");
    assert_eq!(matrix(&report["A"]).len(), 6);
}

/// `--at` a state off the slider–crank's constraints (θ = 1, φ = x = 0):
/// moved onto them as `simulate` moves its initial state, and reported.
/// The residual before is the closed form `r cos 1 + l` of `rod_x`
/// (r = 0.05 m, l = 0.2 m), and the state linearized about satisfies
/// `r cos θ + l cos φ = x`, `r sin θ = l sin φ`.
#[test]
fn a_state_off_the_constraints_is_projected_and_reported() {
    let report = linearize(&["specs/slider_crank.lpm", "--at", "theta=1"]);
    let point = &report["operating_point"];
    let projection = &point["projection"];
    let (r, l) = (0.05_f64, 0.2_f64);
    let before = (r * 1f64.cos() + l).max(r * 1f64.sin());
    close(
        projection["residual_before"].as_f64().unwrap(),
        before,
        1e-12,
        "residual before",
    );
    assert_eq!(projection["given_q"]["theta"], 1.0);
    let q = |name: &str| point["q"][name].as_f64().unwrap();
    let (theta, phi, x) = (q("theta"), q("phi"), q("x"));
    assert!((r * theta.cos() + l * phi.cos() - x).abs() < 1e-12, "rod_x");
    assert!((r * theta.sin() - l * phi.sin()).abs() < 1e-12, "rod_y");
    let moved = ((theta - 1.0).powi(2) + phi.powi(2) + x.powi(2)).sqrt();
    close(
        projection["coordinate_change"].as_f64().unwrap(),
        moved,
        1e-12,
        "|Δq|",
    );
    // Given the projected state itself, nothing moves and the modes agree.
    let at = format!("theta={theta:?},phi={phi:?},x={x:?}");
    let again = linearize(&["specs/slider_crank.lpm", "--at", &at]);
    let residual = again["operating_point"]["projection"]["residual_before"].as_f64();
    assert!(residual.unwrap() < 1e-12, "{residual:?}");
    close(
        floats(&again["natural_frequencies_hz"])[0],
        floats(&report["natural_frequencies_hz"])[0],
        1e-9,
        "frequency",
    );
    // The markdown says so; a model without constraints has no projection.
    let out = lpm(&["linearize", "specs/slider_crank.lpm", "--at", "theta=1"]);
    assert!(
        stdout(&out).contains(
            "The state given was projected onto the constraints (rod_x, rod_y): |g| was 2.3e-1"
        ),
        "{}",
        stdout(&out)
    );
    let free = linearize(&["specs/simple_pendulum.lpm", "--at", "theta=0.1"]);
    assert!(free["operating_point"]["projection"].is_null());
}
