//! The optimized program must compute exactly the derived expressions.

use lagrangian_core::Compiled;
use lagrangian_core::expr::{Evaluator, ExprId, SymbolKind};
use lagrangian_core::program::{EvalContext, RoutineKind};
use lagrangian_core::random::Lcg;

/// Input function `k` evaluates to a smooth function of its arguments.
fn smooth_inputs(input: usize, args: &[f64]) -> f64 {
    args.iter()
        .enumerate()
        .fold(1.0 + input as f64, |acc, (i, a)| {
            acc + (a * (i as f64 + 1.3)).sin()
        })
}

/// The routines to check and the expressions each must compute, in order.
fn expected_outputs(compiled: &Compiled) -> Vec<(RoutineKind, Vec<ExprId>)> {
    let d = compiled
        .derivation
        .as_ref()
        .expect("derived in the canonical form");
    let n = d.dimension;
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
    cases
}

/// The value of every symbol of the store in the state of `ctx`.
fn symbol_values(compiled: &Compiled, ctx: &EvalContext) -> Vec<f64> {
    let store = &compiled.model.store;
    let mut values = vec![0.0; store.symbols().len()];
    for (i, s) in store.symbols().iter().enumerate() {
        values[i] = match s.kind {
            SymbolKind::Coordinate(k) => ctx.q[k],
            SymbolKind::Velocity(k) => ctx.qd[k],
            SymbolKind::Acceleration(k) => ctx.qdd[k],
            SymbolKind::Parameter(k) => ctx.parameters[k],
            SymbolKind::Time => ctx.t,
            _ => 0.0,
        };
    }
    values
}

fn check_spec(path: &str) {
    let source = std::fs::read_to_string(path).unwrap();
    let compiled =
        Compiled::from_source(&source).unwrap_or_else(|e| panic!("{}", e.render(path, &source)));
    let n = compiled.program.dimension;
    let mut random = Lcg::new(42);
    for _ in 0..20 {
        let q: Vec<f64> = (0..n).map(|_| random.symmetric()).collect();
        let qd: Vec<f64> = (0..n).map(|_| 2.0 * random.symmetric()).collect();
        let qdd: Vec<f64> = (0..n).map(|_| random.symmetric()).collect();
        let params: Vec<f64> = compiled
            .default_parameters()
            .iter()
            .map(|p| p * (1.0 + 0.1 * random.symmetric()))
            .collect();
        let t = random.symmetric().abs();
        let ctx = EvalContext {
            t,
            q: &q,
            qd: &qd,
            qdd: &qdd,
            parameters: &params,
            inputs: &smooth_inputs,
        };
        let values = symbol_values(&compiled, &ctx);
        let mut ev = Evaluator::new(&compiled.model.store, values, &smooth_inputs);
        let mut regs = compiled.program.registers();
        for (kind, exprs) in expected_outputs(&compiled) {
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
