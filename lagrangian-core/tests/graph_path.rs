//! The derivation graph computes the equations the canonical form does:
//! every routine of every shipped spec, both paths, at random states; and
//! models too large for the canonical form compile on the graph.

use lagrangian_core::program::{EvalContext, Program, RoutineKind};
use lagrangian_core::random::Lcg;
use lagrangian_core::{Compiled, Model};

/// Input function `k` evaluates to a smooth function of its arguments.
fn smooth_inputs(input: usize, args: &[f64]) -> f64 {
    args.iter()
        .enumerate()
        .fold(1.0 + input as f64, |acc, (i, a)| {
            acc + (a * (i as f64 + 1.3)).sin()
        })
}

fn run(program: &Program, kind: RoutineKind, ctx: &EvalContext) -> Vec<f64> {
    let routine = program.routine(kind).unwrap();
    let mut out = vec![0.0; routine.outputs.len()];
    program.run(routine, ctx, &mut program.registers(), &mut out);
    out
}

fn check_spec(path: &str) {
    let source = std::fs::read_to_string(path).unwrap();
    let canonical = Compiled::from_source(&source).unwrap();
    assert!(
        canonical.derivation.is_some(),
        "{path} is derived canonically"
    );
    let graph = Compiled::on_graph(Model::from_source(&source).unwrap());
    if !canonical.model.constraints.is_empty() {
        // Constraints are derived in the canonical form only: the graph
        // path refuses them rather than drop them.
        let refused = graph.err().expect("the graph path refuses constraints");
        let message = &refused.diagnostics[0].message;
        assert!(
            message.contains("which constraints need"),
            "{path}: {message}"
        );
        return;
    }
    let graph = graph.unwrap();
    let n = canonical.program.dimension;
    let mut random = Lcg::new(7);
    for _ in 0..20 {
        let q: Vec<f64> = (0..n).map(|_| random.symmetric()).collect();
        let qd: Vec<f64> = (0..n).map(|_| 2.0 * random.symmetric()).collect();
        let qdd: Vec<f64> = (0..n).map(|_| random.symmetric()).collect();
        let parameters: Vec<f64> = (canonical.default_parameters().iter())
            .map(|p| p * (1.0 + 0.1 * random.symmetric()))
            .collect();
        let t = random.symmetric().abs();
        let ctx = EvalContext {
            t,
            q: &q,
            qd: &qd,
            qdd: &qdd,
            parameters: &parameters,
            inputs: &smooth_inputs,
        };
        for routine in &canonical.program.routines {
            if routine.kind == RoutineKind::Switching {
                // The same functions in another order: compared up to
                // order and sign by the non-smooth model's test below.
                continue;
            }
            let want = run(&canonical.program, routine.kind, &ctx);
            let got = run(&graph.program, routine.kind, &ctx);
            let scale = want.iter().fold(1.0f64, |m, x| m.max(x.abs()));
            for (k, (a, b)) in got.iter().zip(&want).enumerate() {
                assert!(
                    (a - b).abs() <= 1e-12 * scale,
                    "{path} {:?} output {k}: graph {a} vs canonical {b}",
                    routine.kind
                );
            }
        }
    }
}

#[test]
fn every_shipped_spec_agrees_on_both_paths() {
    let mut paths: Vec<_> = std::fs::read_dir("../specs")
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "lpm"))
        .collect();
    paths.sort();
    assert!(paths.len() >= 8);
    for path in paths {
        check_spec(path.to_str().unwrap());
    }
}

#[test]
fn the_jacobians_agree_on_both_paths() {
    let source =
        lagrangian_core::examples::pendulum_chain(3).replace("kinetic =", "jacobians;\nkinetic =");
    let path = std::path::Path::new(env!("CARGO_TARGET_TMPDIR")).join("graph_path_jacobians.lpm");
    std::fs::write(&path, source).unwrap();
    check_spec(path.to_str().unwrap());
}

#[test]
fn a_chain_too_large_for_the_canonical_form_compiles_on_the_graph() {
    let mut compiled =
        Compiled::from_source(&lagrangian_core::examples::pendulum_chain(40)).unwrap();
    assert!(compiled.derivation.is_none());
    let dynamics = compiled.program.routine(RoutineKind::Dynamics).unwrap();
    assert_eq!(dynamics.outputs.len(), 40 * 41 / 2 + 40);
    // Its equations print from the canonical form, derived on demand.
    assert!(compiled.canonical().is_err());
}

#[test]
fn the_conical_pendulum_prints_that_it_is_too_large() {
    let source = std::fs::read_to_string("../tests/specs/three_link_conical_pendulum.lpm").unwrap();
    let mut compiled = Compiled::from_source(&source).unwrap();
    assert!(compiled.derivation.is_none());
    let text = lagrangian_core::emit::render_equations(
        &mut compiled,
        lagrangian_core::emit::Notation::Text,
    );
    assert!(text.contains("too large to print"), "{text}");
}

/// The switching functions of a model at 20 random states (coordinates in
/// `[−1, 1]`, the domain of the functions spec), one row per state.
fn switching_values(program: &Program, parameters: &[f64]) -> Vec<Vec<f64>> {
    let n = program.dimension;
    let mut random = Lcg::new(11);
    (0..20)
        .map(|_| {
            let q: Vec<f64> = (0..n).map(|_| random.symmetric()).collect();
            let qd: Vec<f64> = (0..n).map(|_| 2.0 * random.symmetric()).collect();
            let ctx = EvalContext {
                t: 0.1,
                q: &q,
                qd: &qd,
                qdd: &[],
                parameters,
                inputs: &smooth_inputs,
            };
            run(program, RoutineKind::Switching, &ctx)
        })
        .collect()
}

#[test]
fn a_non_smooth_model_has_the_same_switching_functions_on_both_paths() {
    let source = std::fs::read_to_string("../tests/functions/all_functions.lpm").unwrap();
    let canonical = Compiled::from_source(&source).unwrap();
    assert!(canonical.derivation.is_some());
    let graph = Compiled::on_graph(Model::from_source(&source).unwrap()).unwrap();
    let parameters = canonical.default_parameters();
    let want = switching_values(&canonical.program, &parameters);
    let got = switching_values(&graph.program, &parameters);
    let count = want[0].len();
    assert!(count >= 5, "{count} switching functions");
    assert_eq!(got[0].len(), count);
    // The same functions, each up to its sign, in whatever order.
    let column = |rows: &[Vec<f64>], k: usize| rows.iter().map(|r| r[k]).collect::<Vec<_>>();
    let same_up_to_sign = |a: &[f64], b: &[f64]| {
        [1.0, -1.0].into_iter().any(|s| {
            a.iter()
                .zip(b)
                .all(|(x, y)| (x - s * y).abs() <= 1e-12 * x.abs().max(1.0))
        })
    };
    for k in 0..count {
        let wanted = column(&want, k);
        assert!(
            (0..count).any(|j| same_up_to_sign(&column(&got, j), &wanted)),
            "canonical switching function {k} ({wanted:?}) is not on the graph path"
        );
    }
    // And the dynamics agree.
    check_spec("../tests/functions/all_functions.lpm");
}
