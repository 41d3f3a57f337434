//! The paper's full-frontal scenario end to end: plausibility of the result,
//! energy balance, the compiled model against the interpreted spec, and the
//! integration methods against each other.

use lagrangian::scenario::{ModelNames, Scenario};
use lagrangian::simulate::{SimulationResult, simulate};
use lagrangian::{Interpreted, LagrangianSystem};
use std::path::Path;

mod models {
    lagrangian::lagrangian!(file = "specs/yaris_double_pendulum.lpm");
}

const SPEC: &str = "specs/yaris_double_pendulum.lpm";
const SCENARIO: &str = "specs/scenarios/yaris_full_frontal.toml";

fn interpreted() -> Interpreted<3> {
    let source = std::fs::read_to_string(SPEC).unwrap();
    Interpreted::new(lagrangian_core::interpret(&source).unwrap()).unwrap()
}

fn run<S: LagrangianSystem<3> + Clone>(model: &S, settings: &[&str]) -> SimulationResult {
    let settings: Vec<String> = settings.iter().map(|s| s.to_string()).collect();
    let scenario = Scenario::load(
        Path::new(SCENARIO),
        &ModelNames::of(model),
        &lagrangian::scenario::Override::parse_all(&settings).unwrap(),
    )
    .unwrap();
    simulate(model, &scenario).unwrap()
}

#[test]
fn the_default_scenario_looks_like_a_small_car_at_56_kmh() {
    let r = run(&interpreted(), &[]);
    let s = &r.summary;
    println!("{}", serde_json::to_string_pretty(s).unwrap());
    // Plausibility ranges of the crash-domain notes (1,100–1,170 kg at 56 km/h).
    let crush = s.max_crush_m.unwrap();
    assert!((0.5..=0.7).contains(&crush), "max crush {crush}");
    let t0 = s.time_to_zero_velocity_s.unwrap();
    assert!((0.060..=0.090).contains(&t0), "time to zero velocity {t0}");
    let rebound = s.rebound_velocity_mps.unwrap();
    assert!((1.0..=2.5).contains(&rebound), "rebound {rebound}");
    // The weld fails during the crush (before the peak), as the paper assumes.
    let failure = s.weld_failure_time_s.expect("weld fails");
    assert!(failure < s.time_of_max_crush_s.unwrap());
    // The crush peak coincides with zero velocity in this polar model.
    assert!((s.time_of_max_crush_s.unwrap() - t0).abs() < 1e-4);
    // Energy: T + V + dissipated − work of the inputs closes at rtol 1e-8.
    assert!(
        s.energy_balance_error_rel <= 1e-6,
        "energy balance {}",
        s.energy_balance_error_rel
    );
    // Peak crush, separation and weld failure were events.
    let kinds: Vec<&str> = r
        .events
        .iter()
        .map(|e| e.description.split(' ').next().unwrap_or(""))
        .collect();
    assert!(
        kinds.contains(&"peak") && kinds.contains(&"separation") && kinds.contains(&"weld"),
        "{kinds:?}"
    );
}

#[test]
fn the_compiled_model_gives_the_same_numbers_as_the_spec_file() {
    let compiled = run(&models::YarisDoublePendulum::default(), &[]);
    let spec = run(&interpreted(), &[]);
    assert_eq!(compiled.samples.len(), spec.samples.len());
    assert_eq!(
        compiled.stats, spec.stats,
        "identical arithmetic, identical steps"
    );
    let a = serde_json::to_value(&compiled.summary).unwrap();
    let b = serde_json::to_value(&spec.summary).unwrap();
    assert_eq!(a, b);
}

#[test]
fn the_methods_agree() {
    let model = interpreted();
    let reference = run(&model, &["simulation.rtol=1e-10", "simulation.atol=1e-12"]).summary;
    let implicit = run(
        &model,
        &["simulation.method=\"tr-bdf2\"", "simulation.rtol=1e-7"],
    )
    .summary;
    let rk4 = run(
        &model,
        &["simulation.method=\"rk4\"", "simulation.step=2e-6"],
    )
    .summary;
    for (name, s) in [("tr-bdf2", &implicit), ("rk4", &rk4)] {
        let crush = (s.max_crush_m.unwrap() - reference.max_crush_m.unwrap()).abs();
        let time = (s.time_of_max_crush_s.unwrap() - reference.time_of_max_crush_s.unwrap()).abs();
        let pitch = (s.max_theta1_deg.unwrap() - reference.max_theta1_deg.unwrap()).abs();
        println!(
            "{name}: max crush off by {crush:.2e} m, its time by {time:.2e} s, pitch by {pitch:.2e}°; energy balance {:.1e}",
            s.energy_balance_error_rel
        );
        assert!(crush < 1e-4 && time < 1e-4 && pitch < 1e-2, "{name}");
        assert!(s.energy_balance_error_rel < 1e-4, "{name}");
    }
}

#[test]
fn the_run_starts_in_static_equilibrium() {
    let model = interpreted();
    let r = run(&model, &["simulation.t_end=1e-4"]);
    let q = lagrangian::nalgebra::Vector3::from_column_slice(&r.initial_q);
    let scenario = Scenario::load(Path::new(SCENARIO), &ModelNames::of(&model), &[]).unwrap();
    let mut model = model;
    scenario.apply_parameters(&mut model).unwrap();
    let f = model.forcing(
        0.0,
        &q,
        &lagrangian::nalgebra::Vector3::zeros(),
        &scenario.inputs,
    );
    println!(
        "static residual {:?} at θ1 = {:.3}°, θ2 = {:.3}°",
        f,
        q[1].to_degrees(),
        q[2].to_degrees()
    );
    assert!(f[1].abs() < 1e-6 && f[2].abs() < 1e-6, "{f}");
    assert!(
        q[1] < -0.05,
        "the suspension sags under gravity: θ1 = {}",
        q[1]
    );
}

#[test]
fn elastic_unloading_returns_the_energy_as_rebound() {
    let model = interpreted();
    let plastic = run(&model, &[]).summary.rebound_velocity_mps.unwrap();
    let elastic = run(&model, &["components.front_end.unloading=\"elastic\""])
        .summary
        .rebound_velocity_mps
        .unwrap();
    println!("rebound: plastic {plastic:.2} m/s, elastic (the paper's spring) {elastic:.2} m/s");
    assert!(elastic > 4.0 * plastic, "{elastic} vs {plastic}");
}
