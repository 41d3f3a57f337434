//! The paper's full-frontal scenario, 0–150 ms, end to end (equilibrium,
//! integration with events, output samples, summary), compiled and
//! interpreted, at several tolerances.
//!
//! `cargo bench -p lagrangian --bench simulation`

use lagrangian::scenario::{ModelNames, Scenario};
use lagrangian::simulate::simulate;
use lagrangian::{Interpreted, InterpretedModel, LagrangianSystem};
use std::path::Path;
use std::time::Instant;

mod models {
    lagrangian::lagrangian!(file = "specs/yaris_double_pendulum.lpm");
}

/// Median microseconds of `runs` simulations, with the run's step count.
fn time<S: LagrangianSystem<3> + Clone>(
    model: &S,
    scenario: &Scenario,
    runs: usize,
) -> (f64, usize, usize) {
    let first = simulate(model, scenario).unwrap();
    let mut times: Vec<f64> = (0..runs)
        .map(|_| {
            let start = Instant::now();
            std::hint::black_box(simulate(model, scenario).unwrap());
            start.elapsed().as_secs_f64() * 1e6
        })
        .collect();
    times.sort_by(f64::total_cmp);
    (
        times[runs / 2],
        first.stats.accepted_steps,
        first.stats.rhs_evaluations,
    )
}

fn main() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let scenario_path = root.join("specs/scenarios/yaris_full_frontal.toml");
    let compiled = models::YarisDoublePendulum::default();
    let source = std::fs::read_to_string(root.join("specs/yaris_double_pendulum.lpm")).unwrap();
    let interpreted =
        Interpreted::<3>::new(InterpretedModel::from_source(&source).unwrap()).unwrap();
    println!("| model | rtol | output samples | time (median) | steps | right-hand sides |");
    println!("|---|---|---|---|---|---|");
    for rtol in ["1e-6", "1e-8", "1e-9"] {
        for interval in ["1e-4", "1e-3"] {
            let settings = vec![
                format!("simulation.rtol={rtol}"),
                format!("simulation.atol={}", rtol.parse::<f64>().unwrap() * 1e-2),
                format!("simulation.output_interval={interval}"),
            ];
            let scenario =
                Scenario::load(&scenario_path, &ModelNames::of(&compiled), &settings).unwrap();
            let samples = (0.15 / interval.parse::<f64>().unwrap()).round() as usize + 1;
            for (label, result) in [
                ("compiled", time(&compiled, &scenario, 21)),
                ("interpreted", time(&interpreted, &scenario, 11)),
            ] {
                let (us, steps, rhs) = result;
                println!("| {label} | {rtol} | {samples} | {us:.0} µs | {steps} | {rhs} |");
            }
        }
    }
}
