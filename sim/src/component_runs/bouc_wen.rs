//! Runs of the `bouc_wen` component through the simulator (moved out of
//! `components::bouc_wen`, which must not reach the run engine above it).

use crate::scenario::{ModelNames, Scenario};
use crate::simulate::{SimulationResult, simulate};
use lagrangian_runtime::Interpreted;

/// A unit mass whose spring input is driven through
/// `u = U sin(w t)`, whatever the mass does.
const DRIVEN: &str = "model Driven;\n\
    coordinates { x [m], }\n\
    parameters { m [kg] = 1.0, U [m] = 0.02, w [rad/s] = 20.0, }\n\
    inputs { spring(u [m], v [m/s]) [N], }\n\
    kinetic = 0.5 * m * pow(dot(x), 2);\n\
    force x = -spring(U * sin(w * t), U * w * cos(w * t));\n";

/// A unit mass on the spring: `u = x`.
const MASS: &str = "model Mass;\n\
    coordinates { x [m], }\n\
    parameters { m [kg] = 1.0, }\n\
    inputs { spring(u [m], v [m/s]) [N], }\n\
    kinetic = 0.5 * m * pow(dot(x), 2);\n\
    force x = -spring(x, dot(x));\n";

/// The spring of `tests/reference/bouc_wen_loop.py`.
const SPRING: &str = "[components.spring]\ntype = \"bouc_wen\"\n\
    inputs = { force = \"spring\" }\n\
    fy = 1000.0\nuy = 0.01\na = 0.1\nA = 1.0\nbeta = 0.5\ngamma = 0.5\nn = 2.0\n";

fn run(model: &str, simulation: &str) -> Result<SimulationResult, String> {
    let model = lagrangian_core::interpret(model).unwrap();
    let names = ModelNames::of_interpreted(&model);
    let model = Interpreted::<1>::new(model).unwrap();
    let text = format!("{simulation}{SPRING}");
    let scenario = Scenario::parse(&text, None, &names, &[]).map_err(|e| e.message)?;
    simulate(&model, &scenario).map_err(|e| e.to_string())
}

/// The values of component column `name` over the run.
fn column(result: &SimulationResult, name: &str) -> Vec<f64> {
    let k = (result.component_columns.iter())
        .position(|(n, _)| n == name)
        .unwrap_or_else(|| panic!("no column {name}: {:?}", result.component_columns));
    result.samples.iter().map(|s| s.components[k]).collect()
}

/// The loop area of the fourth cycle, by `tests/reference/bouc_wen_loop.py`.
const LOOP_AREA: f64 = 3.274356140008e1;

#[test]
fn the_dissipated_energy_of_a_cycle_is_the_area_of_its_loop() {
    let period = 2.0 * std::f64::consts::PI / 20.0;
    for method in ["dopri5", "tr-bdf2"] {
        let simulation = format!(
            "[simulation]\nt_end = {}\nmethod = \"{method}\"\noutput_interval = {}\n",
            4.0 * period,
            period / 2000.0
        );
        let result = run(DRIVEN, &simulation).unwrap();
        let (force, u) = (
            column(&result, "spring.force"),
            column(&result, "spring.deflection"),
        );
        let dissipated = column(&result, "spring.dissipated_energy");
        let (start, end) = (6000, 8000);
        let trapezoid: f64 = (start..end)
            .map(|i| 0.5 * (force[i] + force[i + 1]) * (u[i + 1] - u[i]))
            .sum();
        let integrated = dissipated[end] - dissipated[start];
        // Against the independent reference: the integrated power;
        // against our own trajectory: the trapezoid area of its samples.
        let tolerance = if method == "dopri5" { 1e-6 } else { 1e-4 };
        assert!(
            (integrated / LOOP_AREA - 1.0).abs() < tolerance,
            "{method}: {integrated} vs {LOOP_AREA}"
        );
        assert!(
            (trapezoid / LOOP_AREA - 1.0).abs() < 1e-5,
            "{method}: {trapezoid}"
        );
        assert_eq!(
            result.summary.dissipated_by,
            [("spring".to_string(), dissipated[8000])]
        );
    }
}

#[test]
fn with_a_large_exponent_the_force_saturates_at_the_yield_force() {
    // β = γ = 0.5, A = 1, a = 0: z → 1 and F → Fy under loading.
    // u = U·w·t at 0.4 m/s: 5 uy at t = 0.125 s.
    let model = DRIVEN.replace("U * sin(w * t), U * w * cos(w * t)", "U * w * t, U * w");
    // Saturated, z is a stiff state (∂ż/∂z = −n·u̇/uy = −1000 /s) that
    // dopri5 holds at its stability limit, where z wanders by about
    // the tolerance: rtol 1e-9 keeps that well inside the bound below.
    let simulation = "[simulation]\nt_end = 0.125\noutput_interval = 0.025\nrtol = 1e-9\n";
    let text = SPRING
        .replace("a = 0.1", "a = 0.0")
        .replace("n = 2.0", "n = 25.0");
    let model = lagrangian_core::interpret(&model).unwrap();
    let names = ModelNames::of_interpreted(&model);
    let model = Interpreted::<1>::new(model).unwrap();
    let scenario = Scenario::parse(&format!("{simulation}{text}"), None, &names, &[]).unwrap();
    let result = simulate(&model, &scenario).unwrap();
    let force = column(&result, "spring.force");
    // From u = 3 uy on, the closed form of the saturated spring: Fy.
    for f in &force[3..] {
        assert!((f / 1000.0 - 1.0).abs() < 1e-3, "{force:?}");
    }
    // z rises to its bound 1 and stays there (to the tolerances).
    assert!(column(&result, "spring.z").iter().all(|z| *z < 1.0 + 1e-8));
}

#[test]
fn the_energy_balance_closes_with_the_hysteretic_energy() {
    // A unit mass at 2 m/s on the spring: T + stored + dissipated = T0.
    let simulation = "[simulation]\nt_end = 0.5\n[initial]\nvelocities = { x = 2.0 }\n";
    let result = run(MASS, simulation).unwrap();
    let (x, z) = (
        column(&result, "spring.deflection"),
        column(&result, "spring.z"),
    );
    let dissipated = column(&result, "spring.dissipated_energy");
    let (k, fy, uy, a) = (1.0e5, 1000.0, 0.01, 0.1);
    for (i, s) in result.samples.iter().enumerate() {
        let stored = 0.5 * a * k * x[i] * x[i] + 0.5 * (1.0 - a) * fy * uy * z[i] * z[i];
        let total = s.kinetic + stored + dissipated[i];
        assert!((total / 2.0 - 1.0).abs() < 1e-6, "t = {}: {total}", s.t);
    }
    assert!(dissipated.last().unwrap() > &0.5, "{dissipated:?}");
}

#[test]
fn parameters_that_make_the_loop_unbounded_are_refused_by_name() {
    let simulation = "[simulation]\nt_end = 0.1\n";
    let refused = |from: &str, to: &str| {
        let model = lagrangian_core::interpret(MASS).unwrap();
        let names = ModelNames::of_interpreted(&model);
        let text = format!("{simulation}{}", SPRING.replace(from, to));
        Scenario::parse(&text, None, &names, &[])
            .unwrap_err()
            .message
    };
    assert_eq!(
        refused("gamma = 0.5", "gamma = -0.5"),
        "components.spring: beta + gamma = 0: must be positive, or the hysteresis loop is unbounded"
    );
    assert_eq!(
        refused("n = 2.0", "n = 0.0"),
        "components.spring.n = 0: must be a positive, finite number"
    );
    assert_eq!(
        refused("uy = 0.01", "uy = -0.01"),
        "components.spring.uy = -0.01: must be a positive, finite number"
    );
}
