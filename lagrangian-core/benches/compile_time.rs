//! Time to turn a spec into code (parse → derive → optimize → emit tokens),
//! what every `cargo build` of a crate using `lagrangian!` pays, and the size
//! of the emitted program. `cargo bench -p lagrangian-core --bench compile_time`.

use lagrangian_core::emit::{RustOptions, emit_model};
use lagrangian_core::program::RoutineKind;
use lagrangian_core::{Compiled, Model};
use std::time::{Duration, Instant};

fn compile(source: &str) -> (Compiled, usize) {
    let model = Model::from_source(source).expect("spec compiles");
    let compiled = Compiled::new(model).expect("derives");
    let tokens = emit_model(&compiled, &RustOptions::default());
    let size = tokens.to_string().len();
    (compiled, size)
}

/// Median of `runs` timings (after one warm-up), and the last result.
fn measure(source: &str, runs: usize) -> (Duration, Compiled, usize) {
    let _ = compile(source);
    let mut times = Vec::with_capacity(runs);
    let mut last = None;
    for _ in 0..runs {
        let start = Instant::now();
        let result = compile(source);
        times.push(start.elapsed());
        last = Some(result);
    }
    times.sort();
    let (compiled, size) = last.expect("at least one run");
    (times[times.len() / 2], compiled, size)
}

fn main() {
    let filter = std::env::args().skip(1).find(|a| !a.starts_with('-'));
    let mut cases: Vec<(String, String)> = vec![(
        "yaris_double_pendulum".into(),
        std::fs::read_to_string(concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/../specs/yaris_double_pendulum.lpm"
        ))
        .unwrap(),
    )];
    cases.push((
        "three_link_conical_pendulum".into(),
        std::fs::read_to_string(concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/../tests/specs/three_link_conical_pendulum.lpm"
        ))
        .unwrap(),
    ));
    for n in [1, 2, 3, 5, 8, 10, 15, 20, 40, 100] {
        cases.push((
            format!("pendulum_chain_{n}"),
            lagrangian_core::examples::pendulum_chain(n),
        ));
    }
    println!(
        "| model | path | compile time (median) | ops M,f | ops energies | ops Jacobians | Rust tokens (bytes) |"
    );
    println!("|---|---|---|---|---|---|---|");
    let mut by_kind = Vec::new();
    for (name, source) in cases {
        if filter.as_ref().is_some_and(|f| !name.contains(f.as_str())) {
            continue;
        }
        let runs = if name.ends_with("_40") || name.ends_with("_100") {
            3
        } else if name.ends_with("_20") {
            5
        } else {
            21
        };
        let (time, compiled, size) = measure(&source, runs);
        let ops = |k| {
            compiled.program.routine(k).map_or("–".to_string(), |r| {
                compiled.program.counts(r).total().to_string()
            })
        };
        println!(
            "| {name} | {} | {:.3} ms | {} | {} | {} | {size} |",
            if compiled.derivation.is_some() {
                "canonical"
            } else {
                "graph"
            },
            time.as_secs_f64() * 1e3,
            ops(RoutineKind::Dynamics),
            ops(RoutineKind::Energies),
            ops(RoutineKind::Jacobians),
        );
        if let Some(routine) = compiled.program.routine(RoutineKind::Dynamics) {
            let c = compiled.program.counts(routine);
            by_kind.push(format!(
                "| {name} | {} | {} | {} | {} | {} | {} | {} |",
                c.total(),
                c.add,
                c.mul,
                c.div,
                c.neg,
                c.pow,
                c.transcendental
            ));
        }
    }
    println!();
    println!("Operations of M (upper triangle) and f by kind:");
    println!();
    println!("| model | total | add/sub | mul | div | neg | pow | sin/cos/… |");
    println!("|---|---|---|---|---|---|---|---|");
    for row in by_kind {
        println!("{row}");
    }
}
