//! Holonomic constraints end to end, against independent references:
//! SymPy's nonminimal pendulum (`tests/reference/constraints_reference.py`),
//! a disc rolling down an incline (closed form), the four-bar linkage
//! against its hand-eliminated one-coordinate model (SciPy, same script);
//! the drift and energy balance of the shipped specs' default runs; the
//! errors of constraints that cannot hold.

use lagrangian::constrained::{Baumgarte, ConstraintValues, solve_constrained};
use lagrangian::nalgebra::SVector;
use lagrangian::report::summary_json;
use lagrangian::scenario::{ModelNames, Scenario};
use lagrangian::simulate::{SimulationError, SimulationResult, simulate};
use lagrangian::{Interpreted, LagrangianSystem, NoInputs};
use serde_json::Value;

mod models {
    lagrangian::lagrangian!(file = "specs/four_bar_linkage.lpm");
}

fn reference() -> Value {
    let text = std::fs::read_to_string("tests/reference/constraints_reference.json").unwrap();
    serde_json::from_str(&text).unwrap()
}

fn numbers(v: &Value) -> Vec<f64> {
    v.as_array()
        .unwrap()
        .iter()
        .map(|x| x.as_f64().unwrap())
        .collect()
}

fn model<const N: usize>(source: &str) -> Interpreted<N> {
    Interpreted::new(lagrangian_core::interpret(source).unwrap()).unwrap()
}

/// Runs `system` under `scenario` text with `settings`.
fn run<const N: usize, S: LagrangianSystem<N> + Clone>(
    system: &S,
    scenario: &str,
    settings: &[&str],
) -> Result<SimulationResult, SimulationError> {
    let settings: Vec<String> = settings.iter().map(|s| s.to_string()).collect();
    let names = ModelNames::of(system);
    let scenario = Scenario::parse(
        scenario,
        None,
        &names,
        &lagrangian::scenario::Override::parse_all(&settings).unwrap(),
    )
    .unwrap();
    simulate(system, &scenario)
}

/// `q̈` and `λ` of a model at a state, by the constrained solve without
/// stabilization.
fn solve<const N: usize, S: LagrangianSystem<N>>(
    system: &S,
    q: [f64; N],
    qd: [f64; N],
) -> (SVector<f64, N>, Vec<f64>) {
    let (q, qd) = (SVector::from(q), SVector::from(qd));
    let (mass, forcing) = system.mass_matrix_and_forcing_pair(0.0, &q, &qd, &NoInputs);
    let mut values = ConstraintValues::new(system.constraint_count(), N);
    system.constraints(0.0, &q, &qd, &NoInputs, &mut values.values);
    let gamma = Baumgarte::NONE.acceleration(&values, qd.as_slice());
    solve_constrained(&mass, &forcing, &values, &gamma).unwrap()
}

const PENDULUM: &str = "model NonminimalPendulum;
coordinates { x [m], y [m] }
parameters { m [kg] = 2.0, l [m] = 1.5, g [m/s^2] = 9.81 }
kinetic = 0.5 * m * (pow(dot(x), 2) + pow(dot(y), 2));
potential = m * g * y;
constraint rod = x * x + y * y - l * l;
";

/// SymPy's `LagrangesMethod` with `hol_coneqs` gives the same accelerations
/// and multiplier at a state on the circle.
#[test]
fn the_nonminimal_pendulum_agrees_with_sympy_at_a_state() {
    let r = &reference()["nonminimal_pendulum"]["state"];
    let (q, qd) = (numbers(&r["q"]), numbers(&r["qd"]));
    let system = model::<2>(PENDULUM);
    let (qdd, lambda) = solve(&system, [q[0], q[1]], [qd[0], qd[1]]);
    for (found, expected) in qdd.iter().zip(numbers(&r["qdd"])) {
        assert!((found - expected).abs() < 1e-12, "{qdd} vs {:?}", r["qdd"]);
    }
    let expected = numbers(&r["lambda"])[0];
    assert!(
        (lambda[0] - expected).abs() < 1e-12,
        "{lambda:?} vs {expected}"
    );
}

/// Released at 0.6 rad, the pendulum in `x, y` follows the one-coordinate
/// pendulum SciPy integrates in the angle.
#[test]
fn the_nonminimal_pendulum_swings_as_the_pendulum_in_its_angle() {
    let motion = &reference()["nonminimal_pendulum"]["motion"];
    let theta0 = motion["theta0"].as_f64().unwrap();
    let (x0, y0) = (1.5 * theta0.sin(), -1.5 * theta0.cos());
    let settings = [
        format!("initial.coordinates.x={x0:?}"),
        format!("initial.coordinates.y={y0:?}"),
    ];
    let settings: Vec<&str> = settings.iter().map(String::as_str).collect();
    let scenario = "[simulation]\nt_end = 2.0\nrtol = 1e-10\natol = 1e-12\noutput_interval = 0.5\n";
    let result = run(&model::<2>(PENDULUM), scenario, &settings).unwrap();
    let (xs, ys) = (numbers(&motion["x"]), numbers(&motion["y"]));
    for (k, t) in numbers(&motion["t"]).into_iter().enumerate() {
        let s = &result.samples[k + 1];
        assert!((s.t - t).abs() < 1e-12);
        assert!(
            (s.q[0] - xs[k]).abs() < 1e-7,
            "x({t}) = {} vs {}",
            s.q[0],
            xs[k]
        );
        assert!(
            (s.q[1] - ys[k]).abs() < 1e-7,
            "y({t}) = {} vs {}",
            s.q[1],
            ys[k]
        );
    }
    let constraints = result.constraints.as_ref().unwrap();
    assert!(constraints.drift_max() < 1e-9, "{constraints:?}");
}

/// A disc rolling without slipping down an incline, its rotation and
/// its travel tied by `x = r φ`: `ẍ = g sin α / (1 + I/(m r²))`, and the
/// multiplier is the friction that makes it roll, `m ẍ − m g sin α`.
#[test]
fn a_disc_rolls_down_an_incline_at_the_closed_form_acceleration() {
    let source = "model RollingDisc;
coordinates { x [m], phi [rad] }
parameters { m [kg] = 3.0, r [m] = 0.2, I [kg*m^2] = 0.06, g [m/s^2] = 9.81, alpha [rad] = 0.4 }
kinetic = 0.5 * m * pow(dot(x), 2) + 0.5 * I * pow(dot(phi), 2);
potential = -m * g * sin(alpha) * x;
constraint rolling = x - r * phi;
";
    let system = model::<2>(source);
    let (m, r, inertia, g, alpha) = (3.0, 0.2, 0.06, 9.81_f64, 0.4_f64);
    let expected = g * alpha.sin() / (1.0 + inertia / (m * r * r));
    let (qdd, lambda) = solve(&system, [0.1, 0.5], [0.4, 2.0]);
    assert!((qdd[0] - expected).abs() < 1e-13, "{qdd} vs {expected}");
    assert!((qdd[1] - expected / r).abs() < 1e-12, "{qdd}");
    let friction = m * expected - m * g * alpha.sin();
    assert!(
        (lambda[0] - friction).abs() < 1e-12,
        "{lambda:?} vs {friction}"
    );
    // Over a run from rest: x = ẍ t²/2; the multiplier's column is in N.
    let scenario = "[simulation]\nt_end = 1.0\noutput_interval = 0.25\n";
    let result = run(&system, scenario, &[]).unwrap();
    let last = result.samples.last().unwrap();
    assert!((last.q[0] - 0.5 * expected).abs() < 1e-9, "{}", last.q[0]);
    assert!((last.multipliers[0] - friction).abs() < 1e-9);
}

/// The four-bar linkage of the shipped spec follows its hand-eliminated
/// one-coordinate model (the crank angle, the others from the loop's
/// closed form) from the reference's exact initial angles.
#[test]
fn the_four_bar_follows_its_hand_eliminated_model() {
    let reference = &reference()["four_bar"];
    let initial = numbers(&reference["initial"]);
    let settings = [
        format!("initial.coordinates.theta2={:?}", initial[1]),
        format!("initial.coordinates.theta3={:?}", initial[2]),
        "simulation.t_end=2.0".to_string(),
    ];
    let settings: Vec<&str> = settings.iter().map(String::as_str).collect();
    let scenario = std::fs::read_to_string("specs/scenarios/four_bar_linkage.toml").unwrap();
    let system = models::FourBarLinkage::default();
    let result = run(&system, &scenario, &settings).unwrap();
    let projection = &result.constraints.as_ref().unwrap().projection;
    assert!(projection.coordinate_change < 1e-14, "{projection:?}");
    let angle = |a: f64, b: f64| {
        ((a - b + std::f64::consts::PI).rem_euclid(std::f64::consts::TAU) - std::f64::consts::PI)
            .abs()
    };
    for (k, t) in numbers(&reference["t"]).into_iter().enumerate() {
        let s = &result.samples[(t / 1e-3).round() as usize];
        assert!((s.t - t).abs() < 1e-12);
        for (i, name) in ["theta1", "theta2", "theta3"].into_iter().enumerate() {
            let expected = numbers(&reference[name])[k];
            let error = angle(s.q[i], expected);
            assert!(error < 1e-6, "{name}({t}) = {} vs {expected}", s.q[i]);
        }
    }
}

/// The shipped specs' default runs: the initial state projected (and said
/// so), the constraints held, the energy balance closed, `summary.json`
/// with the drift; the compiled four-bar gives the interpreted numbers.
#[test]
fn the_default_runs_hold_their_constraints_and_balance_energy() {
    for name in ["four_bar_linkage", "slider_crank"] {
        let source = std::fs::read_to_string(format!("specs/{name}.lpm")).unwrap();
        let scenario = std::fs::read_to_string(format!("specs/scenarios/{name}.toml")).unwrap();
        let result = run(&model::<3>(&source), &scenario, &[]).unwrap();
        let constraints = result.constraints.as_ref().unwrap();
        assert_eq!(constraints.names.len(), 2);
        assert!(constraints.drift_max() < 1e-8, "{name}: {constraints:?}");
        let balance = result.summary.energy_balance_error_rel;
        assert!(balance < 1e-7, "{name}: energy balance {balance}");
        let json: Value = serde_json::from_str(&summary_json(&result)).unwrap();
        let drift = json["constraint_drift_max"].as_f64().unwrap();
        assert_eq!(drift, constraints.drift_max());
        assert_eq!(json["constraint_drift"].as_object().unwrap().len(), 2);
        if name == "four_bar_linkage" {
            let p = &constraints.projection;
            assert!(
                p.residual_before > 1e-8 && p.coordinate_change < 1e-5,
                "{p:?}"
            );
            let compiled = run(&models::FourBarLinkage::default(), &scenario, &[]).unwrap();
            assert_eq!(compiled.samples, result.samples);
        }
    }
}

/// A model without constraints gets no new keys in `summary.json`.
#[test]
fn an_unconstrained_summary_has_no_drift() {
    let source = std::fs::read_to_string("specs/double_pendulum.lpm").unwrap();
    let result = run(&model::<2>(&source), "", &["simulation.t_end=0.01"]).unwrap();
    assert!(result.constraints.is_none());
    assert!(!summary_json(&result).contains("constraint_drift"));
}

#[test]
fn a_constraint_that_cannot_hold_at_the_start_is_named_with_its_residual() {
    let source = std::fs::read_to_string("specs/four_bar_linkage.lpm").unwrap();
    let scenario = std::fs::read_to_string("specs/scenarios/four_bar_linkage.toml").unwrap();
    // Coupler and rocker together too short to span the ground link minus
    // the crank, whatever the angles.
    let run = run(&model::<3>(&source), &scenario, &["l2=0.2", "l3=0.05"]);
    let message = run.map(|r| r.constraints).unwrap_err().to_string();
    assert!(
        message.contains("cannot be satisfied near the initial state"),
        "{message}"
    );
    assert!(message.contains("`loop_"), "{message}");
    assert!(message.contains("its residual is"), "{message}");
}

#[test]
fn redundant_constraints_are_named() {
    let source = format!("{PENDULUM}constraint rod_again = 2.0 * (x * x + y * y - l * l);\n");
    let scenario = "[initial.coordinates]\nx = 1.5\n";
    let run = run(&model::<2>(&source), scenario, &[]);
    let message = run.map(|r| r.constraints).unwrap_err().to_string();
    assert!(message.contains("redundant constraints"), "{message}");
    assert!(message.contains("`rod_again`"), "{message}");
    assert!(!message.contains("`rod`"), "{message}");
}

/// A second rod of twice the length: its gradient is the first rod's, as
/// for a redundant constraint, but its residual contradicts the first
/// rod's (no point is at distance l and 2l from the origin), so it is
/// unsatisfiable, not redundant, and named with its residual: x = 1.5,
/// y = 0 is on the first rod (l = 1.5), where x² + y² − 4l² = 2.25 − 9 =
/// −6.75.
#[test]
fn contradicting_constraints_are_unsatisfiable_not_redundant() {
    let source = format!("{PENDULUM}constraint far = x * x + y * y - 4.0 * l * l;\n");
    let scenario = "[initial.coordinates]\nx = 1.5\n";
    let run = run(&model::<2>(&source), scenario, &[]);
    let message = run.map(|r| r.constraints).unwrap_err().to_string();
    assert!(
        message.starts_with("the constraint `far` cannot be satisfied near the initial state: its residual is -6.75e0 at q = [1.5, 0.0]"),
        "{message}"
    );
    assert!(!message.contains("redundant"), "{message}");
}
