//! An ensemble of 10 000 variants of the paper's scenario — crush stiffness
//! (25 factors) × impact speed (20) × weld failure moment (20) — run by
//! `lagrangian::sweep::run_sweep` (what `lpm sweep` runs) on 1 and 2
//! threads, with the compiled and the interpreted model.
//!
//! `cargo bench -p lagrangian --bench ensemble [-- RUNS]`

use lagrangian::scenario::BaseScenario;
use lagrangian::scenario::ModelNames;
use lagrangian::sweep::{Plan, Settings, SweepJob, run_sweep};
use lagrangian::{Interpreted, LagrangianSystem};
use std::path::Path;
use std::time::Instant;

mod models {
    lagrangian::lagrangian!(file = "specs/yaris_double_pendulum.lpm");
}

/// Runs per second over `runs` runs on `threads` threads, and the failures.
fn throughput<S: LagrangianSystem<3> + Clone + Send>(
    model: &S,
    base: &BaseScenario,
    plan: &Plan,
    runs: usize,
    threads: usize,
) -> (f64, usize) {
    let settings = Settings::new(plan, base, &model.parameters()).unwrap();
    let start = Instant::now();
    let job = SweepJob {
        base,
        plan,
        settings: &settings,
        runs: 0..runs,
        threads,
    };
    let rows = run_sweep(model, job, &|| {});
    let elapsed = start.elapsed().as_secs_f64();
    (
        runs as f64 / elapsed,
        rows.iter().filter(|r| r.outcome.is_err()).count(),
    )
}

fn main() {
    let runs: usize = std::env::args()
        .skip(1)
        .find_map(|a| a.parse().ok())
        .unwrap_or(10_000);
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let scenario = root.join("specs/scenarios/yaris_full_frontal.toml");
    let compiled = models::YarisDoublePendulum::default();
    let source = std::fs::read_to_string(root.join("specs/yaris_double_pendulum.lpm")).unwrap();
    let interpreted = Interpreted::<3>::new(lagrangian_core::interpret(&source).unwrap()).unwrap();
    let base = BaseScenario {
        text: std::fs::read_to_string(&scenario).unwrap(),
        file: Some(scenario),
        names: ModelNames::of(&compiled),
        settings: Vec::new(),
        files: std::sync::Arc::new(lagrangian_sim::files::Cached::default()),
    };
    let grid: Vec<String> = [
        "components.front_end.stiffness_values*=0.7:1.3:25",
        "initial.velocities.r=-17.5:-12.5:20",
        "components.weld.failure_moment=2e3:6e3:20",
    ]
    .map(String::from)
    .to_vec();
    let plan = Plan::grid(&grid).unwrap();
    let runs = runs.min(plan.len());
    println!(
        "{runs} runs of the {}-run grid {}",
        plan.len(),
        grid.join(" × ")
    );
    println!();
    println!("| model | threads | runs/s | speed-up | failed |");
    println!("|---|---|---|---|---|");
    for (label, one, two) in [
        (
            "compiled",
            throughput(&compiled, &base, &plan, runs, 1),
            throughput(&compiled, &base, &plan, runs, 2),
        ),
        (
            "interpreted",
            throughput(&interpreted, &base, &plan, runs, 1),
            throughput(&interpreted, &base, &plan, runs, 2),
        ),
    ] {
        println!("| {label} | 1 | {:.0} | 1.00 | {} |", one.0, one.1);
        println!(
            "| {label} | 2 | {:.0} | {:.2} | {} |",
            two.0,
            two.0 / one.0,
            two.1
        );
    }
}
