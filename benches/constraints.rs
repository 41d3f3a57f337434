//! The cost of constraints: the four-bar linkage's default run
//! (specs/scenarios/four_bar_linkage.toml: 5 s, DOPRI5, rtol 1e-9) with its
//! drift and energy balance, against the same model with its loop left
//! open (benches/specs/four_bar_open.lpm: the same M and f, no
//! constraints), measured side by side in interleaved batches: per run, and
//! per right-hand side at the four-bar's initial state.
//!
//! `cargo bench -p lagrangian --bench constraints`

use lagrangian::nalgebra::SVector;
use lagrangian::ode::{OdeProblem, PhaseState};
use lagrangian::scenario::{ModelNames, Scenario};
use lagrangian::simulate::{CrashProblem, SimulationResult, simulate, simulate_summary};
use lagrangian::{Interpreted, LagrangianSystem};
use std::path::Path;
use std::time::Instant;

mod models {
    lagrangian::lagrangian!(file = "specs/four_bar_linkage.lpm");
    lagrangian::lagrangian!(file = "benches/specs/four_bar_open.lpm");
}

/// The four-bar's scenario, without its `[constraints]` section for the
/// open model (which has none to stabilize).
fn scenario<const N: usize, S: LagrangianSystem<N>>(model: &S, settings: &[&str]) -> Scenario {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let text = std::fs::read_to_string(root.join("specs/scenarios/four_bar_linkage.toml")).unwrap();
    let text = match model.constraint_count() {
        0 => text[..text.find("[constraints]").unwrap()].to_string(),
        _ => text,
    };
    let settings: Vec<String> = settings.iter().map(|s| s.to_string()).collect();
    Scenario::parse(
        &text,
        None,
        &ModelNames::of(model),
        &lagrangian::scenario::Override::parse_all(&settings).unwrap(),
    )
    .unwrap()
}

/// Microseconds of each call of `f`, one per batch.
fn time(f: &mut dyn FnMut()) -> f64 {
    let start = Instant::now();
    f();
    start.elapsed().as_secs_f64() * 1e6
}

/// Median microseconds of `batches` interleaved calls of each of `fs`.
fn interleaved<const K: usize>(batches: usize, mut fs: [&mut dyn FnMut(); K]) -> [f64; K] {
    let mut times: [Vec<f64>; K] = std::array::from_fn(|_| Vec::new());
    for f in fs.iter_mut() {
        f();
    }
    for _ in 0..batches {
        for (f, times) in fs.iter_mut().zip(times.iter_mut()) {
            times.push(time(*f));
        }
    }
    times.map(|mut t| {
        t.sort_by(f64::total_cmp);
        t[t.len() / 2]
    })
}

/// Nanoseconds per right-hand side at the four-bar's initial state (moving,
/// so that every term counts), `calls` per batch.
fn rhs_ns<const N: usize, S: LagrangianSystem<N>>(
    model: &S,
    scenario: &Scenario,
    y: &PhaseState<N>,
    calls: usize,
) -> impl FnMut() {
    let mut problem = CrashProblem::new(model, scenario.inputs.clone());
    problem.start(0.0, y).unwrap();
    let y = *y;
    move || {
        let mut dy = PhaseState::zeros();
        for _ in 0..calls {
            problem.rhs(0.0, std::hint::black_box(&y), &mut dy).unwrap();
        }
        std::hint::black_box(dy);
    }
}

fn row(label: &str, result: &SimulationResult, us: f64, summary_us: Option<f64>) {
    let summary = summary_us.map_or(String::new(), |us| format!("{:.1} ms", us / 1e3));
    println!(
        "| {label} | {:.1} ms | {summary} | {} | {} |",
        us / 1e3,
        result.stats.accepted_steps,
        result.stats.rhs_evaluations
    );
}

fn main() {
    let four_bar = models::FourBarLinkage::default();
    let open = models::FourBarOpen::default();
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let source = std::fs::read_to_string(root.join("specs/four_bar_linkage.lpm")).unwrap();
    let interpreted = Interpreted::<3>::new(lagrangian_core::interpret(&source).unwrap()).unwrap();
    let (s_four_bar, s_open) = (scenario(&four_bar, &[]), scenario(&open, &[]));
    let s_interpreted = scenario(&interpreted, &[]);

    let result = simulate(&four_bar, &s_four_bar).unwrap();
    let open_result = simulate(&open, &s_open).unwrap();
    let constraints = result.constraints.as_ref().unwrap();
    println!("Four-bar, default run (5 s, DOPRI5, rtol 1e-9, atol 1e-11, α = β = 10 /s):");
    println!("- constraint_drift_max {:.2e} m", constraints.drift_max());
    println!("- drift by constraint {:?}", constraints.drift);
    println!(
        "- energy_balance_error_rel {:.2e}",
        result.summary.energy_balance_error_rel
    );
    println!(
        "- initial projection: residual {:.2e} m, |Δq| {:.2e}",
        constraints.projection.residual_before, constraints.projection.coordinate_change
    );
    let tr_bdf2 = ["simulation.method=tr-bdf2"];
    let implicit = simulate(&four_bar, &scenario(&four_bar, &tr_bdf2)).unwrap();
    println!(
        "- TR-BDF2 at the same tolerances: drift {:.2e} m, energy balance {:.2e}, {} steps",
        implicit.constraints.as_ref().unwrap().drift_max(),
        implicit.summary.energy_balance_error_rel,
        implicit.stats.accepted_steps
    );
    println!();

    let [
        four_bar_us,
        open_us,
        interpreted_us,
        four_bar_summary_us,
        open_summary_us,
    ] = interleaved(
        11,
        [
            &mut || drop(std::hint::black_box(simulate(&four_bar, &s_four_bar))),
            &mut || drop(std::hint::black_box(simulate(&open, &s_open))),
            &mut || drop(std::hint::black_box(simulate(&interpreted, &s_interpreted))),
            &mut || {
                drop(std::hint::black_box(simulate_summary(
                    &four_bar,
                    &s_four_bar,
                )))
            },
            &mut || drop(std::hint::black_box(simulate_summary(&open, &s_open))),
        ],
    );
    let interpreted_result = simulate(&interpreted, &s_interpreted).unwrap();
    println!("| model | run, 5001 samples | summary only | steps | right-hand sides |");
    println!("|---|---|---|---|---|");
    row(
        "four-bar, compiled",
        &result,
        four_bar_us,
        Some(four_bar_summary_us),
    );
    row(
        "four-bar, interpreted",
        &interpreted_result,
        interpreted_us,
        None,
    );
    row(
        "loop open, compiled",
        &open_result,
        open_us,
        Some(open_summary_us),
    );
    println!();

    let first = &result.samples[0];
    let y = PhaseState::new(
        SVector::from_column_slice(&first.q),
        SVector::from([1.0, -0.4, 0.3]),
    );
    let calls = 10_000;
    let [constrained, unconstrained] = interleaved(
        51,
        [
            &mut rhs_ns(&four_bar, &s_four_bar, &y, calls),
            &mut rhs_ns(&open, &s_open, &y, calls),
        ],
    );
    let per_call = |us: f64| us * 1e3 / calls as f64;
    println!(
        "Right-hand side: four-bar {:.0} ns, loop open {:.0} ns ({:.2}×)",
        per_call(constrained),
        per_call(unconstrained),
        constrained / unconstrained
    );
}
