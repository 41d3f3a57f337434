//! The shipped variants of the paper's model run by default and give
//! numbers that an independent computation confirms: Kamal's two-mass car
//! against a SciPy integration of its equations written out by hand, the
//! occupant against Newton's law for the occupant, the two cars against
//! the conservation of momentum and energy.

use lagrangian_runtime::{Interpreted, LagrangianSystem};
use lagrangian_sim::scenario::{ModelNames, Override, Scenario};
use lagrangian_sim::simulate::{SimulationResult, simulate};
use std::path::Path;

const ROOT: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/..");

/// Runs `specs/{name}.lpm` under its scenario `specs/scenarios/{name}.toml`
/// with `settings`.
fn run<const N: usize>(name: &str, settings: &[&str]) -> SimulationResult {
    let spec = std::fs::read_to_string(format!("{ROOT}/specs/{name}.lpm")).unwrap();
    let model = lagrangian_core::interpret(&spec).unwrap();
    let names = ModelNames::of_interpreted(&model);
    let system = Interpreted::<N>::new(model).unwrap();
    let settings: Vec<String> = settings.iter().map(|s| s.to_string()).collect();
    let file = format!("{ROOT}/specs/scenarios/{name}.toml");
    let scenario = Scenario::load(
        Path::new(&file),
        &names,
        &Override::parse_all(&settings).unwrap(),
    )
    .unwrap();
    let result = simulate(&system, &scenario).unwrap();
    assert_eq!(result.model, system.model_name());
    result
}

/// The column `name` of the run's outputs, over the samples.
fn output(result: &SimulationResult, name: &str) -> Vec<f64> {
    let k = (result.output_columns.iter())
        .position(|c| c == name)
        .unwrap_or_else(|| panic!("no output {name}"));
    result.samples.iter().map(|s| s.outputs[k]).collect()
}

fn max(values: &[f64]) -> f64 {
    values.iter().copied().fold(f64::NEG_INFINITY, f64::max)
}

fn channel(result: &SimulationResult, name: &str, metric: &str) -> f64 {
    let channels = &result.summary.channels.0;
    let channel = channels.iter().find(|c| c.name == name).unwrap();
    channel.get(metric).unwrap()
}

fn reference() -> serde_json::Value {
    let text = std::fs::read_to_string(format!("{ROOT}/tests/reference/kamal_reference.json"));
    serde_json::from_str(&text.unwrap()).unwrap()
}

#[test]
fn kamal_agrees_with_an_independent_integration_at_two_speeds() {
    for case in reference()["runs"].as_array().unwrap() {
        let speed = case["speed_mps"].as_f64().unwrap();
        let setting = format!("initial.speed={speed}");
        let result = run::<2>("kamal_1970", &[&setting]);
        let s = &result.summary;
        let crush = s.max_crush_m.unwrap();
        let expected = case["max_crush_m"].as_f64().unwrap();
        assert!(
            (crush - expected).abs() < 1e-6,
            "{speed}: {crush} vs {expected}"
        );
        let time = s.time_of_max_crush_s.unwrap();
        let expected = case["time_of_max_crush_s"].as_f64().unwrap();
        assert!(
            (time - expected).abs() < 1e-5,
            "{speed}: {time} vs {expected}"
        );
        // The channel's maximum over 0.1 ms samples, the reference's over 2 µs.
        let deceleration = channel(&result, "body_deceleration", "max");
        let expected = case["peak_body_deceleration_mps2"].as_f64().unwrap();
        assert!(
            (deceleration - expected).abs() < 1e-4 * expected,
            "{speed}: {deceleration} vs {expected}"
        );
        assert!(s.energy_balance_error_rel < 1e-6);
    }
}

#[test]
fn kamal_crushes_more_the_faster_it_hits() {
    let crush = |speed: f64| {
        let setting = format!("initial.speed={speed}");
        run::<2>("kamal_1970", &[&setting])
            .summary
            .max_crush_m
            .unwrap()
    };
    let crushes: Vec<f64> = [10.0, 12.5, 15.0, 17.5].into_iter().map(crush).collect();
    assert!(crushes.windows(2).all(|w| w[0] < w[1]), "{crushes:?}");
}

#[test]
fn the_occupant_obeys_newtons_law_and_its_metrics_are_its_columns() {
    // Solved accelerations obey it to rounding; those from the dense output
    // only to the integration's error.
    let result = run::<4>("yaris_occupant", &["simulation.accelerations=exact"]);
    let mo = 75.0;
    let deceleration = output(&result, "occupant_deceleration");
    let belt = output(&result, "belt_force");
    let seat_column = (result.input_columns.iter())
        .position(|c| c == "seat")
        .unwrap();
    // The occupant's only horizontal forces: belt and seat back.
    for (k, s) in result.samples.iter().enumerate() {
        let force = belt[k] + s.inputs[seat_column];
        assert!(
            (mo * deceleration[k] - force).abs() < 1e-9 * max(&belt),
            "t = {}: {} vs {force}",
            s.t,
            mo * deceleration[k]
        );
    }
    // In units of standard gravity, as the summary's decelerations.
    let g = lagrangian_sim::pulse::STANDARD_GRAVITY;
    let peak = deceleration.iter().fold(0.0f64, |m, a| m.max(a.abs()));
    assert_eq!(
        channel(&result, "occupant_deceleration", "peak_g"),
        peak / g
    );
    assert_eq!(channel(&result, "belt_force", "max"), max(&belt));
    let excursion: Vec<f64> = result.samples.iter().map(|s| s.q[3]).collect();
    assert_eq!(channel(&result, "s", "max"), max(&excursion));
    // Filtered and clipped values lie below the raw peak, and near it for a
    // pulse this smooth.
    for metric in ["cfc60_peak_g", "clip3ms_g"] {
        let value = channel(&result, "occupant_deceleration", metric);
        assert!(
            value > 0.9 * peak / g && value < 1.01 * peak / g,
            "{metric}: {value}"
        );
    }
    // The belt holds the occupant: its excursion is well within the car.
    assert!((0.1..0.4).contains(&max(&excursion)));
}

#[test]
fn two_cars_conserve_momentum_and_energy_and_report_the_crush_column() {
    let result = run::<3>("car_to_car", &[]);
    let (ma, mi, mb) = (1250.0, 20.0, 1600.0);
    let momentum: Vec<f64> = (result.samples.iter())
        .map(|s| ma * s.v[0] + mi * s.v[1] + mb * s.v[2])
        .collect();
    let initial = momentum[0];
    let scale = (ma + mi + mb) * 13.8889;
    assert!((initial - (ma + mi - mb) * 13.8889).abs() < 1e-9 * scale);
    for (p, from_output) in momentum.iter().zip(output(&result, "momentum")) {
        assert!((p - initial).abs() < 1e-6 * scale, "{p} vs {initial}");
        assert!((p - from_output).abs() < 1e-9 * scale);
    }
    let s = &result.summary;
    assert!(
        s.energy_balance_error_rel < 1e-6,
        "{}",
        s.energy_balance_error_rel
    );
    let crush = output(&result, "crush");
    let column_max = max(&crush);
    let max_crush = s.max_crush_m.unwrap();
    // The summary refines the peak between samples: at or just above the column's.
    assert!(
        max_crush >= column_max && max_crush - column_max < 1e-6,
        "{max_crush} vs {column_max}"
    );
    // Each front takes part of it.
    let (a, b) = (
        channel(&result, "crush_a", "max"),
        channel(&result, "crush_b", "max"),
    );
    assert!(a > 0.3 && b > 0.3 && a + b >= column_max - 1e-9);
}
