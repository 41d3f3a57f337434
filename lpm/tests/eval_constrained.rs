//! `lpm eval` on specs with constraints: the constrained `q̈` and the
//! multipliers `λ`, against a closed form (a pendulum in Cartesian
//! coordinates at rest) and against the first sample of `lpm simulate`.

mod common;

use common::{lpm, stderr, stdout, temporary};
use serde_json::Value;

/// A point mass `m` on a massless rod of length `l`, in `x`, `y` (`y` up);
/// the rod a constraint in metres, so its multiplier is a force [N].
const CARTESIAN_PENDULUM: &str = "model CartesianPendulum;
coordinates { x [m], y [m] }
parameters { m [kg] = 2.0, l [m] = 1.5, g [m/s^2] = 9.81 }
kinetic = 0.5 * m * (pow(dot(x), 2) + pow(dot(y), 2));
potential = m * g * y;
constraint rod = sqrt(x * x + y * y) - l;
";

fn numbers(value: &Value) -> Vec<f64> {
    let values = value.as_array().unwrap_or_else(|| panic!("{value}"));
    values.iter().map(|v| v.as_f64().unwrap()).collect()
}

/// `lpm eval` of `spec` at `state`, as JSON.
fn eval(spec: &str, state: &[f64], more: &[&str]) -> Value {
    let state: Vec<String> = state.iter().map(|v| format!("{v:?}")).collect();
    let state = state.join(",");
    let mut args = vec!["eval", spec, "--state", &state];
    args.extend_from_slice(more);
    let out = lpm(&args);
    assert!(out.status.success(), "{}", stderr(&out));
    serde_json::from_str(&stdout(&out)).unwrap()
}

#[test]
fn a_pendulum_at_rest_has_the_closed_form_acceleration_and_rod_tension() {
    let dir = temporary("eval-cartesian-pendulum");
    let spec = dir.join("cartesian_pendulum.lpm");
    std::fs::write(&spec, CARTESIAN_PENDULUM).unwrap();
    let spec = spec.to_str().unwrap();
    let (m, l, g) = (2.0, 1.5, 9.81);
    for theta in [0.0_f64, 0.6, -1.1, 2.0] {
        let (s, c) = theta.sin_cos();
        let json = eval(spec, &[l * s, -l * c, 0.0, 0.0], &[]);
        // At rest only gravity's tangential part accelerates the mass:
        // g sin θ along −(cos θ, sin θ).
        let a = numbers(&json["accelerations"]);
        let expected = [-g * s * c, -g * s * s];
        for (a, e) in a.iter().zip(expected) {
            assert!((a - e).abs() <= 1e-12, "θ = {theta}: {a} vs {e}");
        }
        // The rod pulls inwards with T = m g cos θ; G = (x, y)/l points
        // outwards, so Gᵀλ is that pull for λ = −T.
        let constraints = &json["constraints"];
        assert_eq!(constraints["names"], serde_json::json!(["rod"]));
        let lambda = numbers(&constraints["multipliers"])[0];
        let tension = m * g * c;
        assert!(
            (lambda + tension).abs() <= 1e-12 * tension.abs().max(1.0),
            "θ = {theta}: λ = {lambda}, T = {tension}"
        );
        let residual = numbers(&constraints["residuals"])[0];
        assert!(residual.abs() < 1e-15, "{residual}");
        assert_eq!(numbers(&constraints["rates"]), [0.0]);
    }
    // The text format names each value with its unit.
    let out = lpm(&[
        "eval",
        spec,
        "--state",
        &format!("{:?},{:?},0,0", l * 0.6_f64.sin(), -l * 0.6_f64.cos()),
        "--format",
        "text",
    ]);
    let text = stdout(&out);
    assert!(out.status.success(), "{}", stderr(&out));
    assert!(
        text.contains("x_ddot = ") && text.contains(" m/s^2\n"),
        "{text}"
    );
    // λ = −m g cos 0.6 = −16.193 N.
    assert!(text.contains("rod: λ = -1.6193"), "{text}");
    assert!(text.contains(" N; g = "), "{text}");
}

/// The first row of `trajectory.csv`: each named column's value.
fn first_row(csv: &str) -> Vec<(String, f64)> {
    let mut lines = csv.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    let row: Vec<f64> = (lines.next().unwrap().split(','))
        .map(|v| v.parse().unwrap())
        .collect();
    let name = |h: &str| h.split(" [").next().unwrap().to_string();
    header.iter().map(|h| name(h)).zip(row).collect()
}

fn column(row: &[(String, f64)], name: &str) -> f64 {
    (row.iter().find(|(n, _)| n == name))
        .unwrap_or_else(|| panic!("no column {name}"))
        .1
}

/// `eval` at a run's first state (projected onto the constraints) gives
/// that sample's `q̈` and `λ`.
fn agrees_with_the_first_sample(name: &str, coordinates: &[&str], constraints: &[&str]) {
    let dir = temporary(&format!("eval-first-sample-{name}"));
    let spec = format!("specs/{name}.lpm");
    let out = lpm(&["simulate", &spec, "--t-end", "0.01", "--out"]
        .into_iter()
        .chain([dir.to_str().unwrap()])
        .collect::<Vec<_>>());
    assert!(out.status.success(), "{}", stderr(&out));
    let row = first_row(&std::fs::read_to_string(dir.join("trajectory.csv")).unwrap());
    let of = |suffix: &str| -> Vec<f64> {
        (coordinates.iter())
            .map(|c| column(&row, &format!("{c}{suffix}")))
            .collect()
    };
    let state = [of(""), of("_dot")].concat();
    let scenario = format!("specs/scenarios/{name}.toml");
    let json = eval(&spec, &state, &["--scenario", &scenario]);
    let (a, expected) = (numbers(&json["accelerations"]), of("_ddot"));
    let scale = expected.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
    for (a, e) in a.iter().zip(&expected) {
        assert!(
            (a - e).abs() <= 1e-9 * scale,
            "{name}: {a:?} vs {expected:?}"
        );
    }
    let lambda = numbers(&json["constraints"]["multipliers"]);
    for (k, c) in constraints.iter().enumerate() {
        let e = column(&row, &format!("{c}.lambda"));
        assert!(
            (lambda[k] - e).abs() <= 1e-9 * e.abs().max(1e-3),
            "{name}: {c}.lambda {} vs {e}",
            lambda[k]
        );
    }
}

#[test]
fn the_four_bar_linkage_gives_the_first_sample_of_its_run() {
    agrees_with_the_first_sample(
        "four_bar_linkage",
        &["theta1", "theta2", "theta3"],
        &["loop_x", "loop_y"],
    );
}

#[test]
fn the_slider_crank_gives_the_first_sample_of_its_run() {
    agrees_with_the_first_sample("slider_crank", &["theta", "phi", "x"], &["rod_x", "rod_y"]);
}

#[test]
fn an_unconstrained_spec_reports_its_accelerations_and_no_constraints() {
    let json = eval("specs/double_pendulum.lpm", &[0.3, -0.2, 0.0, 0.0], &[]);
    assert!(json.get("constraints").is_none(), "{json}");
    // M q̈ = f.
    let mass: Vec<Vec<f64>> = (json["mass_matrix"].as_array().unwrap().iter())
        .map(numbers)
        .collect();
    let (f, a) = (numbers(&json["forcing"]), numbers(&json["accelerations"]));
    for i in 0..2 {
        let row: f64 = (0..2).map(|j| mass[i][j] * a[j]).sum();
        assert!(
            (row - f[i]).abs() <= 1e-12 * f[i].abs().max(1.0),
            "{row} vs {}",
            f[i]
        );
    }
}

/// In full precision (the library, not the CSV's 11 digits): the solve of
/// `eval` at the first sample's state gives that sample's `q̈` and `λ`, with
/// the run's stabilization (whose terms, from the projection's residual of
/// 2e-11, are 4e-13 of `q̈`).
#[test]
fn the_solve_of_eval_is_the_first_samples_in_full_precision() {
    use lagrangian_runtime::{ConstantInputs, Interpreted};
    use lagrangian_sim::scenario::{ModelNames, Scenario};
    let root = std::path::Path::new(common::ROOT);
    let spec = std::fs::read_to_string(root.join("specs/four_bar_linkage.lpm")).unwrap();
    let model = lagrangian_core::interpret(&spec).unwrap();
    let names = ModelNames::of_interpreted(&model);
    let file = root.join("specs/scenarios/four_bar_linkage.toml");
    let scenario = Scenario::load(
        &file,
        &names,
        &[lagrangian_sim::scenario::Override::number(
            "simulation.t_end",
            0.01,
        )],
    )
    .unwrap();
    let system = Interpreted::<3>::new(model.clone()).unwrap();
    let result = lagrangian_sim::simulate::simulate(&system, &scenario).unwrap();
    let first = &result.samples[0];
    let state = (first.t, &first.q[..], &first.v[..]);
    let inputs = ConstantInputs(Vec::new());
    let stabilization = scenario.stabilization;
    let Ok(solved) =
        lagrangian_studies::eval::accelerations(&model, &[state], &inputs, stabilization)
    else {
        panic!("the solve failed at {state:?}");
    };
    let scale = first.a.iter().fold(0.0_f64, |m, a| m.max(a.abs()));
    for (a, e) in solved[0].qdd.iter().zip(&first.a) {
        assert!(
            (a - e).abs() <= 1e-13 * scale,
            "{:?} vs {:?}",
            solved[0].qdd,
            first.a
        );
    }
    for (l, e) in solved[0].multipliers.iter().zip(&first.multipliers) {
        assert!(
            (l - e).abs() <= 1e-12 * e.abs(),
            "{:?} vs {:?}",
            solved[0].multipliers,
            first.multipliers
        );
    }
}
