//! The optimized program must compute exactly the derived expressions.

use lagrangian_core::Compiled;
use lagrangian_core::expr::{Evaluator, SymbolKind};
use lagrangian_core::program::{EvalContext, RoutineKind};

/// Input function `k` evaluates to a smooth function of its arguments.
fn smooth_inputs(input: usize, args: &[f64]) -> f64 {
    args.iter()
        .enumerate()
        .fold(1.0 + input as f64, |acc, (i, a)| {
            acc + (a * (i as f64 + 1.3)).sin()
        })
}

fn lcg(seed: &mut u64) -> f64 {
    *seed = seed
        .wrapping_mul(6364136223846793005)
        .wrapping_add(1442695040888963407);
    ((*seed >> 11) as f64 / (1u64 << 53) as f64) * 2.0 - 1.0
}

fn check_spec(path: &str) {
    let source = std::fs::read_to_string(path).unwrap();
    let compiled =
        Compiled::from_source(&source).unwrap_or_else(|e| panic!("{}", e.render(path, &source)));
    let n = compiled.derivation.dimension;
    let mut seed = 42u64;
    for _ in 0..20 {
        let q: Vec<f64> = (0..n).map(|_| lcg(&mut seed)).collect();
        let qd: Vec<f64> = (0..n).map(|_| 2.0 * lcg(&mut seed)).collect();
        let qdd: Vec<f64> = (0..n).map(|_| lcg(&mut seed)).collect();
        let params: Vec<f64> = compiled
            .default_parameters()
            .iter()
            .map(|p| p * (1.0 + 0.1 * lcg(&mut seed)))
            .collect();
        let t = lcg(&mut seed).abs();
        let store = &compiled.model.store;
        let mut values = vec![0.0; store.symbols().len()];
        for (i, s) in store.symbols().iter().enumerate() {
            values[i] = match s.kind {
                SymbolKind::Coordinate(k) => q[k],
                SymbolKind::Velocity(k) => qd[k],
                SymbolKind::Acceleration(k) => qdd[k],
                SymbolKind::Parameter(k) => params[k],
                SymbolKind::Time => t,
                _ => 0.0,
            };
        }
        let mut ev = Evaluator::new(store, values, &smooth_inputs);
        let ctx = EvalContext {
            t,
            q: &q,
            qd: &qd,
            qdd: &qdd,
            parameters: &params,
            inputs: &smooth_inputs,
        };
        let mut regs = compiled.program.registers();
        let d = &compiled.derivation;
        let mut expected = Vec::new();
        for i in 0..n {
            for j in i..n {
                expected.push(d.mass(i, j));
            }
        }
        expected.extend(&d.forcing);
        let mut cases = vec![(RoutineKind::Dynamics, expected)];
        cases.push((
            RoutineKind::Energies,
            vec![
                d.kinetic,
                d.potential,
                d.dissipation,
                d.damping_power,
                d.external_power,
            ],
        ));
        if let Some(j) = &d.jacobians {
            let all = j
                .forcing_q
                .iter()
                .chain(&j.forcing_qd)
                .chain(&j.mass_times_acceleration_q)
                .copied()
                .collect();
            cases.push((RoutineKind::Jacobians, all));
        }
        for (kind, exprs) in cases {
            let routine = compiled.program.routine(kind).unwrap();
            let mut out = vec![0.0; routine.outputs.len()];
            compiled.program.run(routine, &ctx, &mut regs, &mut out);
            for (k, &e) in exprs.iter().enumerate() {
                let want = ev.eval(e);
                let scale = want.abs().max(1.0);
                assert!(
                    (out[k] - want).abs() <= 1e-11 * scale,
                    "{path} {kind:?} output {k}: program {} vs expression {want}",
                    out[k]
                );
            }
        }
    }
}

#[test]
fn double_pendulum() {
    check_spec("../specs/double_pendulum.lpm");
}

#[test]
fn yaris_double_pendulum() {
    check_spec("../specs/yaris_double_pendulum.lpm");
}
