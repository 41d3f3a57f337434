//! Where compile time goes, phase by phase, for a spec file or an n-link
//! chain: `cargo run --release -p lagrangian-core --example phase_times -- 40`.

use lagrangian_core::emit::{RustOptions, emit_model};
use lagrangian_core::{Compiled, Model};
use std::time::Instant;

fn main() {
    let arg = std::env::args().nth(1).unwrap_or_else(|| "40".into());
    let source = match arg.parse::<usize>() {
        Ok(n) => lagrangian_core::examples::pendulum_chain(n),
        Err(_) => std::fs::read_to_string(&arg).expect("a spec file or a chain length"),
    };
    let start = Instant::now();
    let model = Model::from_source(&source).unwrap_or_else(|e| panic!("{e:?}"));
    let lowered = start.elapsed();
    let nodes = (model.store.len(), model.store.size());
    let compiled = Compiled::new(model).unwrap_or_else(|e| panic!("{e:?}"));
    let derived = start.elapsed();
    let tokens = emit_model(&compiled, &RustOptions::default());
    let emitted = start.elapsed();
    let ops = compiled.program.ops.len();
    let dynamics = compiled
        .program
        .routine(lagrangian_core::program::RoutineKind::Dynamics)
        .expect("every program has the dynamics routine");
    let counts = compiled.program.counts(dynamics);
    println!(
        "lower {:.1} ms ({nodes:?} nodes, size) | derive+optimize {:.1} ms ({:?} nodes, size, {ops} registers, M+f {} ops, {}) | emit {:.1} ms ({} bytes) | total {:.1} ms",
        lowered.as_secs_f64() * 1e3,
        (derived - lowered).as_secs_f64() * 1e3,
        (compiled.model.store.len(), compiled.model.store.size()),
        counts.total(),
        if compiled.derivation.is_some() {
            "canonical"
        } else {
            "graph"
        },
        (emitted - derived).as_secs_f64() * 1e3,
        tokens.to_string().len(),
        emitted.as_secs_f64() * 1e3,
    );
}
