//! Linearizations of small specs against closed forms.

use super::*;
use crate::scenario::{ModelNames, Override};
use lagrangian_runtime::Interpreted;
use std::f64::consts::TAU;

const PENDULUM: &str = include_str!("../../../specs/simple_pendulum.lpm");
const SPRING: &str = include_str!("../../../specs/spring_mass_damper.lpm");
const KAMAL: &str = include_str!("../../../specs/kamal_1970.lpm");

fn model<const N: usize>(source: &str) -> (Interpreted<N>, ModelNames) {
    let model = lagrangian_core::interpret(source).unwrap();
    let names = ModelNames::of_interpreted(&model);
    (Interpreted::new(model).unwrap(), names)
}

fn close(found: f64, expected: f64, tolerance: f64) {
    assert!(
        (found - expected).abs() <= tolerance * expected.abs().max(1.0),
        "{found} vs {expected}"
    );
}

#[test]
fn a_pendulum_swings_at_the_square_root_of_g_over_l() {
    let (pendulum, names) = model::<1>(PENDULUM);
    let scenario = Scenario::defaults(&names, &[Override::parse("l=0.7").unwrap()]).unwrap();
    let l = linearize(&pendulum, &scenario, &At::Equilibrium).unwrap();
    assert_eq!(l.state_names, ["theta", "dot(theta)"]);
    assert_eq!(l.source, StateMatrixSource::CentralDifferences);
    close(l.a[(2 - 1, 0)], -9.81 / 0.7, 1e-9);
    assert_eq!(l.modes.len(), 1);
    close(l.modes[0].frequency_hz, (9.81_f64 / 0.7).sqrt() / TAU, 1e-9);
    assert_eq!(l.modes[0].kind, ModeKind::Undamped);
    assert_eq!(l.modes[0].damping_ratio, 0.0);
    assert!(l.inputs.is_empty() && l.b.ncols() == 0);
}

#[test]
fn upside_down_the_pendulum_is_unstable() {
    let (pendulum, names) = model::<1>(PENDULUM);
    let scenario = Scenario::defaults(&names, &[]).unwrap();
    let at = At::State {
        q: vec![std::f64::consts::PI],
        qd: vec![0.0],
    };
    let l = linearize(&pendulum, &scenario, &at).unwrap();
    let kinds: Vec<ModeKind> = l.modes.iter().map(|m| m.kind).collect();
    assert_eq!(kinds, [ModeKind::Overdamped, ModeKind::Unstable]);
    for m in &l.modes {
        close(m.frequency_hz, 9.81_f64.sqrt() / TAU, 1e-9);
    }
}

#[test]
fn a_spring_mass_damper_has_its_damping_ratio_and_input_column() {
    let (spring, names) = model::<1>(SPRING);
    let settings = [
        Override::parse("m=2").unwrap(),
        Override::parse("k=50").unwrap(),
        Override::parse("c=3").unwrap(),
    ];
    let scenario = Scenario::defaults(&names, &settings).unwrap();
    let l = linearize(&spring, &scenario, &At::Equilibrium).unwrap();
    let (m, k, c) = (2.0, 50.0, 3.0);
    let expected_a = [0.0, 1.0, -k / m, -c / m];
    for (found, expected) in l.a.transpose().iter().zip(expected_a) {
        close(*found, expected, 1e-12);
    }
    let zeta = c / (2.0 * (k * m).sqrt());
    close(l.modes[0].damping_ratio, zeta, 1e-12);
    let omega = (k / m).sqrt();
    close(l.modes[0].frequency_hz, omega / TAU, 1e-12);
    close(
        l.modes[0].eigenvalue.im,
        omega * (1.0 - zeta * zeta).sqrt(),
        1e-12,
    );
    assert_eq!(l.modes[0].kind, ModeKind::Underdamped);
    // push(t) is unbound: a column of B, held at 0.
    assert_eq!(l.inputs[0].name, "push");
    assert_eq!(
        (l.inputs[0].value, l.inputs[0].source.as_str()),
        (0.0, UNBOUND)
    );
    close(l.b[(0, 0)], 0.0, 0.0);
    close(l.b[(1, 0)], 1.0 / m, 1e-12);
}

#[test]
fn heavy_damping_makes_two_overdamped_modes() {
    let (spring, names) = model::<1>(SPRING);
    let scenario = Scenario::defaults(
        &names,
        &[
            Override::parse("c=25").unwrap(),
            Override::parse("push=3").unwrap(),
        ],
    )
    .unwrap();
    let l = linearize(&spring, &scenario, &At::Equilibrium).unwrap();
    // k = 100, m = 1, c = 25: λ = (−25 ± 15)/2.
    let frequencies: Vec<f64> = l.modes.iter().map(|m| m.frequency_hz * TAU).collect();
    close(frequencies[0], 5.0, 1e-12);
    close(frequencies[1], 20.0, 1e-12);
    assert!(l.modes.iter().all(|m| m.kind == ModeKind::Overdamped));
    // The constant push moves the equilibrium to x = 3/100.
    close(l.operating_point.q[0], 0.03, 1e-12);
    let equilibrium = Equilibrium {
        start: vec![0.0],
        solved: vec![0],
    };
    assert_eq!(l.operating_point.equilibrium, Some(equilibrium));
    assert_eq!(
        (l.inputs[0].value, l.inputs[0].source.as_str()),
        (3.0, "--set push")
    );
}

#[test]
fn two_free_masses_on_a_spring_have_a_rigid_body_mode() {
    // Kamal's car without a scenario: the crush springs are unbound inputs
    // (columns of B, held at 0), so only the engine mounts join the masses.
    let (kamal, names) = model::<2>(KAMAL);
    let scenario = Scenario::defaults(&names, &[Override::parse("c_eb=0").unwrap()]).unwrap();
    let l = linearize(&kamal, &scenario, &At::Equilibrium).unwrap();
    assert_eq!(l.source, StateMatrixSource::DerivedJacobians);
    let kinds: Vec<ModeKind> = l.modes.iter().map(|m| m.kind).collect();
    assert_eq!(
        kinds,
        [ModeKind::RigidBody, ModeKind::RigidBody, ModeKind::Undamped]
    );
    let (mb, me, k): (f64, f64, f64) = (1050.0, 200.0, 1.5e6);
    let omega = (k * (mb + me) / (mb * me)).sqrt();
    close(l.modes[2].frequency_hz, omega / TAU, 1e-12);
    let inputs: Vec<&str> = l.inputs.iter().map(|c| c.name.as_str()).collect();
    assert_eq!(inputs, ["front", "rails"]);
    // ∂ẍe/∂front = −1/me, ∂ẍb/∂rails = −1/mb.
    close(l.b[(3, 0)], -1.0 / me, 1e-12);
    close(l.b[(2, 1)], -1.0 / mb, 1e-12);
    assert!(!l.modes[0].damping_ratio.is_finite());
}

#[test]
fn the_json_report_has_the_keys_of_its_fields_in_order() {
    let (spring, names) = model::<1>(SPRING);
    let scenario = Scenario::defaults(&names, &[]).unwrap();
    let l = linearize(&spring, &scenario, &At::Equilibrium).unwrap();
    let report = json(&l);
    let keys: Vec<&str> = report
        .as_object()
        .unwrap()
        .keys()
        .map(String::as_str)
        .collect();
    let mut expected: Vec<&str> = FIELDS.iter().map(|f| f.0).collect();
    expected.sort_unstable(); // serde_json's map without preserve_order
    let mut keys_sorted = keys.clone();
    keys_sorted.sort_unstable();
    assert_eq!(keys_sorted, expected);
    for key in [
        "A",
        "B",
        "state_names",
        "input_names",
        "operating_point",
        "natural_frequencies_hz",
        "damping_ratios",
        "modes",
    ] {
        assert!(report.get(key).is_some(), "{key}");
    }
    assert_eq!(report["modes"][0]["kind"], "underdamped");
    let text = markdown(&l, "spring");
    assert!(text.contains("| x | 0 | 0 | 0 | 0 |"), "{text}");
    assert!(
        text.contains("∂ẋ/∂push at push = 0 (unbound: held at 0)"),
        "{text}"
    );
}

#[test]
fn the_crush_springs_of_a_scenario_stiffen_the_system() {
    // Kamal's car with its scenario: at zero crush the crush curves rise
    // linearly to 180 kN (rails) and 60 kN (front) at 0.1 m, and their
    // tangent stiffness adds to the engine mounts' in A.
    let (kamal, names) = model::<2>(KAMAL);
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../specs/scenarios/kamal_1970.toml"
    );
    let scenario = Scenario::load(std::path::Path::new(path), &names, &[]).unwrap();
    let l = linearize(&kamal, &scenario, &At::Equilibrium).unwrap();
    let (mb, me, k_eb) = (1050.0, 200.0, 1.5e6);
    close(l.a[(2, 0)], -(k_eb + 180e3 / 0.1) / mb, 1e-12);
    close(l.a[(3, 1)], -(k_eb + 60e3 / 0.1) / me, 1e-12);
    close(l.a[(2, 1)], k_eb / mb, 1e-12);
    assert!(l.inputs.is_empty() && l.b.ncols() == 0);
    assert!(l.modes.iter().all(|m| m.kind == ModeKind::Underdamped));
}

const YARIS: &str = include_str!("../../../specs/yaris_double_pendulum.lpm");
const FULL_FRONTAL: &str = concat!(
    env!("CARGO_MANIFEST_DIR"),
    "/../specs/scenarios/yaris_full_frontal.toml"
);

/// The eigenvalues of `a`, sorted by imaginary then real part.
fn eigenvalues(a: &DMatrix<f64>) -> Vec<nalgebra::Complex<f64>> {
    let mut values: Vec<_> = a.clone().complex_eigenvalues().iter().copied().collect();
    values.sort_by(|x, y| x.im.total_cmp(&y.im).then(x.re.total_cmp(&y.re)));
    values
}

#[test]
fn the_paper_model_about_its_equilibrium_has_the_modes_of_its_differenced_accelerations() {
    let (yaris, names) = model::<3>(YARIS);
    let path = std::path::Path::new(FULL_FRONTAL);
    let scenario = Scenario::load(path, &names, &[]).unwrap();
    let l = linearize(&yaris, &scenario, &At::Equilibrium).unwrap();
    assert_eq!(l.source, StateMatrixSource::DerivedJacobians);
    assert_eq!(l.modes.len(), 3);
    for m in &l.modes {
        assert!(
            m.frequency_hz.is_finite() && m.damping_ratio.is_finite(),
            "{m:?}"
        );
    }
    // A by central differences of the interpreter's q̈ at the same point.
    let mut model = yaris.clone();
    scenario.apply_parameters(&mut model).unwrap();
    let mut problem = CrashProblem::new(&model, held_inputs(&scenario.inputs));
    let (y, _, _) = operating_state(&mut problem, &scenario, &At::Equilibrium).unwrap();
    let (a_q, a_v) = differenced_jacobians(&problem, &y).unwrap();
    let mut differenced = l.a.clone();
    differenced.view_mut((3, 0), (3, 3)).copy_from(&a_q);
    differenced.view_mut((3, 3), (3, 3)).copy_from(&a_v);
    let scale = l.a.amax();
    assert!(
        (&differenced - &l.a).amax() <= 1e-6 * scale,
        "{differenced} vs {}",
        l.a
    );
    for (d, e) in eigenvalues(&differenced).iter().zip(eigenvalues(&l.a)) {
        assert!((d - e).norm() <= 1e-6 * e.norm(), "{d} vs {e}");
    }
}

/// Two coordinates held by two constraints: no motion, an error naming
/// both (it used to panic building an empty tangent basis).
#[test]
fn a_model_without_free_coordinates_is_an_error() {
    let source = include_str!("../../../tests/bad_inputs/fitset_pinned.lpm");
    let (pinned, names) = model::<2>(source);
    let scenario = Scenario::defaults(&names, &[]).unwrap();
    for at in [
        At::Equilibrium,
        At::State {
            q: vec![0.75f64.sqrt(), 0.5],
            qd: vec![0.0, 0.0],
        },
    ] {
        let e = linearize(&pinned, &scenario, &at).unwrap_err();
        assert_eq!(
            e,
            LinearizeError::NoFreeCoordinates {
                coordinates: vec!["x".into(), "y".into()],
                constraints: vec!["circle".into(), "line".into()],
            }
        );
    }
}
