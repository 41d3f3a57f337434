//! PyDy's three-link conical pendulum written directly (positions, `dot()`,
//! squares), too large for the canonical form, against an independent
//! SymPy derivation (`tests/reference/conical_pendulum_reference.py`,
//! frames, rigid bodies and `LagrangesMethod`; its JSON is committed):
//! interpreted and macro-compiled, `M`, `f`, `T` and `V` at 1e-12.

use lagrangian::nalgebra::SVector;
use lagrangian::{LagrangianSystem, NoInputs};
use serde_json::Value;

mod models {
    lagrangian::lagrangian!(file = "tests/specs/three_link_conical_pendulum.lpm");
}

const TOLERANCE: f64 = 1e-12;
const NAME: &str = "three_link_conical_pendulum";

fn reference() -> Value {
    let text = std::fs::read_to_string("tests/reference/conical_pendulum_reference.json").unwrap();
    serde_json::from_str(&text).unwrap()
}

fn floats(v: &Value) -> Vec<f64> {
    (v.as_array().unwrap().iter())
        .map(|x| x.as_f64().unwrap())
        .collect()
}

/// `‖a − b‖∞ / ‖b‖∞`.
fn relative_error(a: &[f64], b: &[f64]) -> f64 {
    let scale = b.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    let diff = (a.iter().zip(b)).fold(0.0f64, |m, (x, y)| m.max((x - y).abs()));
    diff / scale.max(f64::MIN_POSITIVE)
}

/// Checks every state with `evaluate(parameters, q, q̇) -> (M row-major, f, [T, V])`.
fn check(mut evaluate: impl FnMut(&[f64], &[f64], &[f64]) -> (Vec<f64>, Vec<f64>, [f64; 2])) {
    let reference = reference();
    let model = &reference["models"][NAME];
    let states = model["states"].as_array().unwrap();
    assert!(states.len() >= 10);
    for (k, state) in states.iter().enumerate() {
        let (q, qd) = (floats(&state["q"]), floats(&state["qd"]));
        let (m, f, e) = evaluate(&floats(&state["parameters"]), &q, &qd);
        let m_ref: Vec<f64> = (state["mass_matrix"].as_array().unwrap().iter())
            .flat_map(floats)
            .collect();
        let f_ref = floats(&state["forcing"]);
        let e_ref = [&state["kinetic"], &state["potential"]].map(|v| v.as_f64().unwrap());
        for (what, err) in [
            ("M", relative_error(&m, &m_ref)),
            ("f", relative_error(&f, &f_ref)),
            ("T", relative_error(&e[..1], &e_ref[..1])),
            ("V", relative_error(&e[1..], &e_ref[1..])),
        ] {
            assert!(err <= TOLERANCE, "state {k}: {what} relative error {err:e}");
        }
    }
}

fn parameter_names() -> Vec<String> {
    let reference = reference();
    (reference["models"][NAME]["parameters"]
        .as_array()
        .unwrap()
        .iter())
    .map(|s| s.as_str().unwrap().to_string())
    .collect()
}

#[test]
fn interpreted_matches_sympy() {
    let source = std::fs::read_to_string("tests/specs/three_link_conical_pendulum.lpm").unwrap();
    let mut model = lagrangian_core::interpret(&source).unwrap();
    let names = parameter_names();
    assert_eq!(names, model.parameter_names());
    check(|parameters, q, qd| {
        for (p, v) in names.iter().zip(parameters) {
            model.set_parameter(p, *v).unwrap();
        }
        let (mut m, mut f) = (vec![0.0; 36], vec![0.0; 6]);
        model
            .evaluate_dynamics(0.0, q, qd, &NoInputs, &mut m, &mut f)
            .unwrap();
        let e = model.evaluate_energies(0.0, q, qd, &NoInputs).unwrap();
        (m, f, [e.kinetic, e.potential])
    });
}

#[test]
fn compiled_matches_sympy() {
    let mut model = models::ThreeLinkConicalPendulum::default();
    let names = parameter_names();
    check(|parameters, q, qd| {
        for (p, v) in names.iter().zip(parameters) {
            model.set_parameter(p, *v).unwrap();
        }
        let q = SVector::<f64, 6>::from_column_slice(q);
        let qd = SVector::<f64, 6>::from_column_slice(qd);
        let (m, f) = model.mass_matrix_and_forcing_pair(0.0, &q, &qd, &NoInputs);
        let e = model.energies(0.0, &q, &qd, &NoInputs);
        let m = m.transpose().as_slice().to_vec();
        (m, f.as_slice().to_vec(), [e.kinetic, e.potential])
    });
}
