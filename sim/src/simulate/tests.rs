//! Runs of small specs under scenarios that once went wrong.

use super::*;
use crate::scenario::ModelNames;
use lagrangian_model::Interpreted;

const SPRING: &str = include_str!("../../../specs/spring_mass_damper.lpm");

fn spring() -> (Interpreted<1>, ModelNames) {
    let model = lagrangian_core::interpret(SPRING).unwrap();
    let names = ModelNames::of_interpreted(&model);
    (Interpreted::new(model).unwrap(), names)
}

#[test]
fn an_output_interval_past_the_scenario_check_still_ends() {
    let (model, names) = spring();
    let text = "[simulation]\nt_end = 0.01\n[components.c]\ntype = \"constant\"\nvalues = { push = 1.0 }\n";
    let mut scenario = Scenario::parse(text, None, &names, &[]).unwrap();
    for interval in [f64::INFINITY, f64::NAN] {
        scenario.output_interval = interval;
        let result = simulate(&model, &scenario).unwrap();
        assert!(
            result.samples.len() <= 2,
            "{interval}: {}",
            result.samples.len()
        );
        assert_eq!(result.samples[0].t, 0.0);
        // A model without a `g` parameter is measured in standard gravity.
        assert_eq!(result.g, 9.80665);
    }
}

const YARIS: &str = include_str!("../../../specs/yaris_double_pendulum.lpm");
const FULL_FRONTAL: &str = concat!(
    env!("CARGO_MANIFEST_DIR"),
    "/../specs/scenarios/yaris_full_frontal.toml"
);

#[test]
fn a_car_that_starts_short_of_the_barrier_is_not_pulled_across_the_gap() {
    let model = lagrangian_core::interpret(YARIS).unwrap();
    let names = ModelNames::of_interpreted(&model);
    let system = Interpreted::<3>::new(model).unwrap();
    // 5 cm short of the barrier (r > 0 is a gap), closing at 15.56 m/s.
    let settings = ["initial.coordinates.r=0.05", "simulation.t_end=0.01"].map(String::from);
    let scenario = Scenario::load(std::path::Path::new(FULL_FRONTAL), &names, &settings).unwrap();
    let result = simulate(&system, &scenario).unwrap();
    let crush = result
        .input_columns
        .iter()
        .position(|c| c == "crush")
        .unwrap();
    let contact = 0.05 / 15.5556;
    for s in &result.samples {
        if s.t < contact {
            assert_eq!(s.inputs[crush], 0.0, "force across the gap at t = {}", s.t);
            assert!(s.a[0].abs() < 5.0, "r̈ = {} at t = {}", s.a[0], s.t);
        } else {
            // In contact the barrier pushes: F = k·r + c·ṙ < 0 for r < 0.
            assert!(s.inputs[crush] < 0.0, "{} at t = {}", s.inputs[crush], s.t);
        }
    }
    let [event] = result.events.as_slice() else {
        panic!("{:?}", result.events)
    };
    assert!(
        event.description.starts_with("contact with the barrier"),
        "{event:?}"
    );
    assert!((event.t - contact).abs() < 2e-6, "{} vs {contact}", event.t);
}

#[test]
fn a_summary_only_run_reports_what_the_full_run_reports() {
    let model = lagrangian_core::interpret(YARIS).unwrap();
    let names = ModelNames::of_interpreted(&model);
    let system = Interpreted::<3>::new(model).unwrap();
    for method in ["dopri5", "tr-bdf2"] {
        let settings = [format!("simulation.method=\"{method}\"")];
        let scenario =
            Scenario::load(std::path::Path::new(FULL_FRONTAL), &names, &settings).unwrap();
        let full = simulate(&system, &scenario).unwrap();
        let summary = simulate_summary(&system, &scenario).unwrap();
        assert_eq!(summary, full.summary, "{method}");
        // The online accumulator agrees with the samples it saw: the peak
        // crush is the largest sampled crush, refined (never smaller).
        let sampled = full
            .samples
            .iter()
            .map(|s| -s.q[0])
            .fold(f64::MIN, f64::max);
        let refined = summary.max_crush_m.unwrap();
        assert!(
            refined >= sampled && refined - sampled < 1e-6,
            "{refined} vs {sampled}"
        );
        let decel = full
            .samples
            .iter()
            .map(|s| s.a[0] / full.g)
            .fold(f64::MIN, f64::max);
        assert_eq!(summary.peak_deceleration_g, Some(decel));
    }
}

const DOUBLE_PENDULUM: &str = include_str!("../../../specs/double_pendulum.lpm");

/// A run that keeps only its summary (a sweep's) evaluates the outputs too,
/// for the metrics, to the values a full run records.
#[test]
fn outputs_are_evaluated_in_summary_only_runs_too() {
    let model = lagrangian_core::interpret(DOUBLE_PENDULUM).unwrap();
    let names = ModelNames::of_interpreted(&model);
    let system = Interpreted::<2>::new(model).unwrap();
    let text = "[simulation]\nt_end = 0.05\n[initial.coordinates]\ntheta1 = 0.5\n";
    let scenario = Scenario::parse(text, None, &names, &[]).unwrap();
    let full = simulate(&system, &scenario).unwrap();
    let columns = ["x2_position", "y2_position", "a2_magnitude"];
    assert_eq!(full.output_columns, columns);
    let last = full.samples.last().unwrap();
    assert_eq!(last.outputs.len(), 3);
    let mut problem = CrashProblem::new(&system, scenario.inputs.clone());
    let q = SVector::from_column_slice(&last.q);
    let v = SVector::from_column_slice(&last.v);
    let (values, inputs) = sample(&mut problem, last.t, &PhaseState::new(q, v), false).unwrap();
    assert!(inputs.is_empty());
    assert_eq!(values.as_view().outputs, &last.outputs[..]);
    // At rest the lower bob hangs 2 m below the pivot, unaccelerated.
    let rest = Scenario::parse("[simulation]\nt_end = 0.01\n", None, &names, &[]).unwrap();
    let at_rest = simulate(&system, &rest).unwrap();
    assert_eq!(at_rest.samples[0].outputs, [0.0, -2.0, 0.0]);
}
