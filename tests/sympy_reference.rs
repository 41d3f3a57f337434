//! M, f, T, V and D against an independent SymPy derivation
//! (`tests/reference/sympy_reference.py`, LagrangesMethod, evaluated at 30
//! digits; its JSON output is committed). 50 random states per model, with
//! random parameters and input values; both the interpreter and, for the
//! paper's model and the double pendulum, the macro-compiled code.

use lagrangian::nalgebra::SVector;
use lagrangian::{InputFunctions, Interpreted, LagrangianSystem};
use serde_json::Value;
use std::cell::RefCell;

mod models {
    lagrangian::lagrangian!(file = "specs/double_pendulum.lpm");
    lagrangian::lagrangian!(file = "specs/yaris_double_pendulum.lpm");
}

const TOLERANCE: f64 = 1e-12;

fn reference() -> Value {
    let text = std::fs::read_to_string("tests/reference/sympy_reference.json").unwrap();
    serde_json::from_str(&text).unwrap()
}

fn floats(v: &Value) -> Vec<f64> {
    v.as_array()
        .unwrap()
        .iter()
        .map(|x| x.as_f64().unwrap())
        .collect()
}

/// Returns the state's input values and checks each call's arguments:
/// `crush(r, ṙ)` and functions of time `f(t)`.
struct RecordedInputs<'a> {
    names: &'a [String],
    values: Vec<f64>,
    t: f64,
    q: Vec<f64>,
    qd: Vec<f64>,
    calls: RefCell<usize>,
}

impl InputFunctions for RecordedInputs<'_> {
    fn value(&self, input: usize, args: &[f64]) -> f64 {
        *self.calls.borrow_mut() += 1;
        match self.names[input].as_str() {
            "crush" | "crush_stiffness" | "crush_damping" => {
                assert_eq!(args, [self.q[0], self.qd[0]])
            }
            "weld" | "weld_stiffness" | "weld_damping" => {
                assert_eq!(args, [self.q[2], self.qd[2]])
            }
            _ => assert_eq!(
                args,
                [self.t],
                "input {} is a function of time",
                self.names[input]
            ),
        }
        self.values[input]
    }
}

/// `‖a − b‖∞ / ‖b‖∞`.
fn relative_error(a: &[f64], b: &[f64]) -> f64 {
    let scale = b.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    let diff = a
        .iter()
        .zip(b)
        .fold(0.0f64, |m, (x, y)| m.max((x - y).abs()));
    if scale == 0.0 { diff } else { diff / scale }
}

/// Checks every state of `model` with `evaluate(state, inputs) -> (M row-major, f, [T, V, D])`.
fn check_model(
    name: &str,
    reference: &Value,
    mut evaluate: impl FnMut(
        &[f64],
        f64,
        &[f64],
        &[f64],
        &RecordedInputs,
    ) -> (Vec<f64>, Vec<f64>, [f64; 3]),
) -> f64 {
    let model = &reference["models"][name];
    let inputs: Vec<String> = model["inputs"]
        .as_array()
        .unwrap()
        .iter()
        .map(|s| s.as_str().unwrap().to_string())
        .collect();
    let states = model["states"].as_array().unwrap();
    assert!(states.len() >= 50, "{name}: {} states", states.len());
    let mut worst = 0.0f64;
    for (k, state) in states.iter().enumerate() {
        let (t, q, qd) = (
            state["t"].as_f64().unwrap(),
            floats(&state["q"]),
            floats(&state["qd"]),
        );
        let params = floats(&state["parameters"]);
        let recorded = RecordedInputs {
            names: &inputs,
            values: floats(&state["inputs"]),
            t,
            q: q.clone(),
            qd: qd.clone(),
            calls: RefCell::new(0),
        };
        let (m, f, e) = evaluate(&params, t, &q, &qd, &recorded);
        let m_ref: Vec<f64> = state["mass_matrix"]
            .as_array()
            .unwrap()
            .iter()
            .flat_map(floats)
            .collect();
        let f_ref = floats(&state["forcing"]);
        let e_ref = [
            &state["kinetic"],
            &state["potential"],
            &state["dissipation"],
        ]
        .map(|v| v.as_f64().unwrap());
        let errors = [
            ("M", relative_error(&m, &m_ref)),
            ("f", relative_error(&f, &f_ref)),
            ("T", relative_error(&e[..1], &e_ref[..1])),
            ("V", relative_error(&e[1..2], &e_ref[1..2])),
            ("D", relative_error(&e[2..], &e_ref[2..])),
        ];
        for (what, err) in errors {
            assert!(
                err <= TOLERANCE,
                "{name} state {k}: {what} relative error {err:e}\n ours {m:?} {f:?} {e:?}\n sympy {m_ref:?} {f_ref:?} {e_ref:?}"
            );
            worst = worst.max(err);
        }
        if !inputs.is_empty() {
            assert!(*recorded.calls.borrow() > 0, "{name}: inputs never called");
        }
    }
    worst
}

fn interpreted(name: &str, reference: &Value) -> f64 {
    let spec = reference["models"][name]["spec"].as_str().unwrap();
    let source = match spec.strip_prefix("generated:pendulum_chain(") {
        Some(n) => {
            lagrangian_core::examples::pendulum_chain(n.trim_end_matches(')').parse().unwrap())
        }
        None => std::fs::read_to_string(spec).unwrap(),
    };
    let mut model = lagrangian_core::interpret(&source).unwrap();
    let names: Vec<String> = reference["models"][name]["parameters"]
        .as_array()
        .unwrap()
        .iter()
        .map(|s| s.as_str().unwrap().to_string())
        .collect();
    assert_eq!(names, model.parameter_names());
    let n = model.dimension();
    check_model(name, reference, |params, t, q, qd, inputs| {
        for (p, v) in names.iter().zip(params) {
            model.set_parameter(p, *v).unwrap();
        }
        let (mut m, mut f) = (vec![0.0; n * n], vec![0.0; n]);
        model
            .evaluate_dynamics(t, q, qd, inputs, &mut m, &mut f)
            .unwrap();
        let e = model.evaluate_energies(t, q, qd, inputs).unwrap();
        (m, f, [e.kinetic, e.potential, e.dissipation])
    })
}

fn compiled<const N: usize, M: LagrangianSystem<N> + Default>(
    name: &str,
    reference: &Value,
) -> f64 {
    let mut model = M::default();
    let names: Vec<String> = model
        .parameter_names()
        .iter()
        .map(|s| s.to_string())
        .collect();
    check_model(name, reference, |params, t, q, qd, inputs| {
        for (p, v) in names.iter().zip(params) {
            model.set_parameter(p, *v).unwrap();
        }
        let (q, qd) = (
            SVector::<f64, N>::from_column_slice(q),
            SVector::<f64, N>::from_column_slice(qd),
        );
        let (m, f) = model.mass_matrix_and_forcing_pair(t, &q, &qd, inputs);
        let e = model.energies(t, &q, &qd, inputs);
        // nalgebra is column-major; M is symmetric, but transpose to be exact.
        (
            m.transpose().as_slice().to_vec(),
            f.as_slice().to_vec(),
            [e.kinetic, e.potential, e.dissipation],
        )
    })
}

#[test]
fn interpreter_matches_sympy_on_every_model() {
    let reference = reference();
    let mut report = Vec::new();
    for name in [
        "simple_pendulum",
        "double_pendulum",
        "spring_mass_damper",
        "elastic_pendulum",
        "yaris_double_pendulum",
        "pendulum_chain_5",
    ] {
        report.push((name, interpreted(name, &reference)));
    }
    println!("worst relative error per model: {report:?}");
}

#[test]
fn compiled_code_matches_sympy() {
    let reference = reference();
    let yaris = compiled::<3, models::YarisDoublePendulum>("yaris_double_pendulum", &reference);
    let double = compiled::<2, models::DoublePendulum>("double_pendulum", &reference);
    println!("worst relative error: yaris {yaris:e}, double pendulum {double:e}");
}

#[test]
fn the_interpreted_adapter_matches_too() {
    let reference = reference();
    let source = std::fs::read_to_string("specs/yaris_double_pendulum.lpm").unwrap();
    let model = Interpreted::<3>::new(lagrangian_core::interpret(&source).unwrap()).unwrap();
    let mut model = model;
    let names: Vec<String> = model
        .parameter_names()
        .iter()
        .map(|s| s.to_string())
        .collect();
    check_model(
        "yaris_double_pendulum",
        &reference,
        |params, t, q, qd, inputs| {
            for (p, v) in names.iter().zip(params) {
                model.set_parameter(p, *v).unwrap();
            }
            let (q, qd) = (
                SVector::<f64, 3>::from_column_slice(q),
                SVector::<f64, 3>::from_column_slice(qd),
            );
            let (m, f) = model.mass_matrix_and_forcing_pair(t, &q, &qd, inputs);
            let e = model.energies(t, &q, &qd, inputs);
            (
                m.transpose().as_slice().to_vec(),
                f.as_slice().to_vec(),
                [e.kinetic, e.potential, e.dissipation],
            )
        },
    );
}
