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

#[test]
fn channels_report_the_extremes_of_an_undamped_oscillation() {
    // m = 1 kg, k = 100 N/m, no damping, no force, x(0) = 0, ẋ(0) = 1 m/s:
    // x = 0.1·sin(10t), ẋ = cos(10t), ẍ = −10·sin(10t).
    let (model, names) = spring();
    let text = "[simulation]\nt_end = 0.5\nrtol = 1e-10\natol = 1e-12\n\
        [parameters]\nc = 0.0\n[initial]\nvelocities = { x = 1.0 }\n\
        [metrics]\ndisplacement = [\"x\"]\nvelocity = [\"-x_dot\"]\nacceleration = [\"x_ddot\"]\n\
        [components.c]\ntype = \"constant\"\nvalues = { push = 0.0 }\n";
    let scenario = Scenario::parse(text, None, &names, &[]).unwrap();
    let summary = simulate(&model, &scenario).unwrap().summary;
    let [x, v, a] = &summary.channels.0[..] else {
        panic!("{:?}", summary.channels)
    };
    let quarter = std::f64::consts::PI / 20.0;
    let close = |got: Option<f64>, want: f64, tol: f64| {
        let got = got.unwrap();
        assert!((got - want).abs() < tol, "{got} vs {want}");
    };
    assert_eq!((x.name.as_str(), x.unit.as_deref()), ("x", Some("m")));
    close(x.get("max"), 0.1, 1e-7);
    close(x.get("time_of_max_s"), quarter, 1e-4);
    close(x.get("min"), -0.1, 1e-7);
    close(x.get("time_of_min_s"), 3.0 * quarter, 1e-4);
    assert_eq!(v.unit.as_deref(), Some("m/s"));
    close(v.get("max"), 1.0, 1e-7);
    close(v.get("time_of_max_s"), 2.0 * quarter, 1e-4);
    assert_eq!(v.get("peak_g"), None);
    assert_eq!(a.unit.as_deref(), Some("m/s^2"));
    close(a.get("min"), -10.0, 1e-5);
    close(a.get("max"), 10.0, 1e-5);
    let g = 9.80665;
    close(a.get("peak_g"), 10.0 / g, 1e-6);
    // |ẍ| = 10 at π/20 and 3π/20: either is the peak.
    let peak = a.get("time_of_peak_s").unwrap();
    assert!((peak - quarter).abs() < 1e-4 || (peak - 3.0 * quarter).abs() < 1e-4);
    // 1.6 Hz passes CFC 60 and CFC 180 unchanged.
    close(a.get("cfc60_peak_g"), 10.0 / g, 1e-3);
    close(a.get("cfc180_peak_g"), 10.0 / g, 1e-3);
    // Near each peak |ẍ| ≥ 10·cos(10·Δt): 3 ms in all over the two peaks
    // is 1.5 ms about each, cos(0.0075) → 0.99997 of the peak.
    close(a.get("clip3ms_g"), 10.0 * (0.0075f64).cos() / g, 1e-3);
    // At t = 0.5 s neither x = 0.1·sin 5 nor −ẋ = −cos 5 is an extreme.
    assert!(!x.extreme_at_end && !v.extreme_at_end);
    let json = serde_json::to_value(&summary).unwrap();
    assert_eq!(json["channels"]["x_ddot"]["role"], "acceleration");
    assert_eq!(json["channels"]["-x_dot"]["unit"], "m/s");
}

#[test]
fn a_signal_still_growing_at_the_end_is_flagged() {
    let (model, names) = spring();
    let text = "[simulation]\nt_end = 0.1\n[parameters]\nc = 0.0\n\
        [initial]\nvelocities = { x = 1.0 }\n[metrics]\ndisplacement = [\"x\"]\n\
        [components.c]\ntype = \"constant\"\nvalues = { push = 0.0 }\n";
    let scenario = Scenario::parse(text, None, &names, &[]).unwrap();
    let summary = simulate(&model, &scenario).unwrap().summary;
    assert!(summary.channels.0[0].extreme_at_end);
}
