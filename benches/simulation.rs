//! The paper's full-frontal scenario, 0–150 ms, end to end (equilibrium,
//! integration with events, output samples, summary), compiled and
//! interpreted, at several tolerances; then the bare integration of the same
//! right-hand side without events by our DOPRI5 and by `ode_solvers`' (a
//! peer).
//!
//! `cargo bench -p lagrangian --bench simulation`

use lagrangian::fault::Fault;
use lagrangian::nalgebra::SVector;
use lagrangian::ode::explicit;
use lagrangian::ode::tableau::DOPRI5;
use lagrangian::ode::{OdeProblem, Options, PhaseState};
use lagrangian::scenario::{ModelNames, Scenario};
use lagrangian::simulate::{CrashProblem, simulate, simulate_summary, static_equilibrium};
use lagrangian::{Interpreted, LagrangianSystem};
use std::cell::RefCell;
use std::path::Path;
use std::time::Instant;

mod models {
    lagrangian::lagrangian!(file = "specs/yaris_double_pendulum.lpm");
}

/// Median microseconds of `runs` calls of `f`.
fn median_us(runs: usize, mut f: impl FnMut()) -> f64 {
    f();
    let mut times: Vec<f64> = (0..runs)
        .map(|_| {
            let start = Instant::now();
            f();
            start.elapsed().as_secs_f64() * 1e6
        })
        .collect();
    times.sort_by(f64::total_cmp);
    times[runs / 2]
}

/// The scenario's ODE without its events: the crush element stays on its
/// loading branch and in contact, the weld never fails. What both
/// integrators of the peer comparison solve.
struct WithoutEvents<'a, S: LagrangianSystem<3>>(CrashProblem<'a, 3, S>);

impl<S: LagrangianSystem<3>> OdeProblem<PhaseState<3>> for WithoutEvents<'_, S> {
    type Error = Fault;

    fn rhs(&mut self, t: f64, y: &PhaseState<3>, dy: &mut PhaseState<3>) -> Result<(), Fault> {
        self.0.rhs(t, y, dy)
    }
}

/// The same problem as an `ode_solvers` system on `(q, q̇, work)`.
struct Peer<'a, S: LagrangianSystem<3>>(RefCell<WithoutEvents<'a, S>>);

type PeerState = ode_solvers::SVector<f64, 8>;

fn phase(y: &PeerState) -> PhaseState<3> {
    PhaseState {
        q: SVector::from_column_slice(&y.as_slice()[0..3]),
        v: SVector::from_column_slice(&y.as_slice()[3..6]),
        work: [y[6], y[7]],
        z: Default::default(),
    }
}

fn peer_state(y: &PhaseState<3>) -> PeerState {
    let mut out = PeerState::zeros();
    out.as_mut_slice()[0..3].copy_from_slice(y.q.as_slice());
    out.as_mut_slice()[3..6].copy_from_slice(y.v.as_slice());
    out[6] = y.work[0];
    out[7] = y.work[1];
    out
}

impl<S: LagrangianSystem<3>> ode_solvers::System<f64, PeerState> for Peer<'_, S> {
    fn system(&self, t: f64, y: &PeerState, dy: &mut PeerState) {
        let mut d = PhaseState::zeros();
        self.0.borrow_mut().rhs(t, &phase(y), &mut d).unwrap();
        *dy = peer_state(&d);
    }
}

/// Our DOPRI5 and `ode_solvers`' on the scenario's right-hand side without
/// events, from the scenario's initial state (equilibrium included).
fn peer_rows<S: LagrangianSystem<3> + Clone>(model: &S, scenario_path: &Path) {
    let names = ModelNames::of(model);
    let reference = {
        let settings = ["simulation.rtol=1e-13", "simulation.atol=1e-15"].map(String::from);
        let scenario = Scenario::load(
            scenario_path,
            &names,
            &lagrangian::scenario::Override::parse_all(&settings).unwrap(),
        )
        .unwrap();
        let (mut problem, y0) = setup(model, &scenario);
        let options = Options {
            max_steps: 10_000_000,
            ..scenario.options
        };
        explicit::integrate(
            &DOPRI5,
            &mut problem,
            0.0,
            y0,
            scenario.t_end,
            &options,
            &mut |_, _| {},
        )
        .unwrap()
        .y
    };
    let error = |y: &PhaseState<3>| {
        (y.q - reference.q)
            .amax()
            .max((y.v - reference.v).amax() * 1e-2)
    };
    for rtol in [1e-6, 1e-8, 1e-9] {
        let settings = [
            format!("simulation.rtol={rtol}"),
            format!("simulation.atol={}", rtol * 1e-2),
        ];
        let scenario = Scenario::load(
            scenario_path,
            &names,
            &lagrangian::scenario::Override::parse_all(&settings).unwrap(),
        )
        .unwrap();
        let options = scenario.options;
        let (_, y0) = setup(model, &scenario);
        let mut ours = None;
        let us = median_us(51, || {
            let (mut problem, _) = setup(model, &scenario);
            ours = Some(
                explicit::integrate(
                    &DOPRI5,
                    &mut problem,
                    0.0,
                    y0,
                    scenario.t_end,
                    &options,
                    &mut |_, _| {},
                )
                .unwrap(),
            );
        });
        let ours = ours.unwrap();
        println!(
            "| lagrangian-sim dopri5 | {rtol:e} | {us:.0} µs | {} | {} | {:.1e} |",
            ours.stats.accepted_steps,
            ours.stats.rhs_evaluations,
            error(&ours.y)
        );
        let mut theirs = None;
        let us = median_us(51, || {
            let (problem, _) = setup(model, &scenario);
            // Dense output every millisecond: with a single interval
            // (dx = t_end), ode_solvers 0.6.2 returned a wrong end state.
            let mut solver = ode_solvers::Dopri5::new(
                Peer(RefCell::new(problem)),
                0.0,
                scenario.t_end,
                1e-3,
                peer_state(&y0),
                options.rtol,
                options.atol,
            );
            let stats = solver.integrate().unwrap();
            theirs = Some((stats, phase(solver.y_out().last().unwrap())));
        });
        let (stats, y) = theirs.unwrap();
        println!(
            "| ode_solvers 0.6 Dopri5 | {rtol:e} | {us:.0} µs | {} | {} | {:.1e} |",
            stats.accepted_steps,
            stats.num_eval,
            error(&y)
        );
    }
}

/// The scenario's problem without events and its initial state.
fn setup<'a, S: LagrangianSystem<3>>(
    model: &'a S,
    scenario: &Scenario,
) -> (WithoutEvents<'a, S>, PhaseState<3>) {
    let mut q = SVector::<f64, 3>::zeros();
    let mut v = SVector::<f64, 3>::zeros();
    for &(i, value) in &scenario.initial_coordinates {
        q[i] = value;
    }
    for &(i, value) in &scenario.initial_velocities {
        v[i] = value;
    }
    let mut problem = CrashProblem::new(model, scenario.inputs.clone());
    problem.start(0.0, &PhaseState::new(q, v)).unwrap();
    let q = static_equilibrium(&problem, 0.0, q, &scenario.equilibrium).unwrap();
    let y0 = PhaseState::new(q, v);
    problem.start(0.0, &y0).unwrap();
    (WithoutEvents(problem), y0)
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
    let interpreted = Interpreted::<3>::new(lagrangian_core::interpret(&source).unwrap()).unwrap();
    println!("| model | rtol | output samples | time (median) | steps | right-hand sides |");
    println!("|---|---|---|---|---|---|");
    for rtol in ["1e-6", "1e-8", "1e-9"] {
        for interval in ["1e-4", "1e-3"] {
            let settings = vec![
                format!("simulation.rtol={rtol}"),
                format!("simulation.atol={}", rtol.parse::<f64>().unwrap() * 1e-2),
                format!("simulation.output_interval={interval}"),
            ];
            let scenario = Scenario::load(
                &scenario_path,
                &ModelNames::of(&compiled),
                &lagrangian::scenario::Override::parse_all(&settings).unwrap(),
            )
            .unwrap();
            let samples = (0.15 / interval.parse::<f64>().unwrap()).round() as usize + 1;
            for (label, result) in [
                ("compiled", time(&compiled, &scenario, 21)),
                ("interpreted", time(&interpreted, &scenario, 11)),
            ] {
                let (us, steps, rhs) = result;
                println!("| {label} | {rtol} | {samples} | {us:.0} µs | {steps} | {rhs} |");
            }
        }
        // What a sweep runs: the summary only, no samples kept.
        let settings = vec![
            format!("simulation.rtol={rtol}"),
            format!("simulation.atol={}", rtol.parse::<f64>().unwrap() * 1e-2),
        ];
        let scenario = Scenario::load(
            &scenario_path,
            &ModelNames::of(&compiled),
            &lagrangian::scenario::Override::parse_all(&settings).unwrap(),
        )
        .unwrap();
        let us = median_us(21, || {
            std::hint::black_box(simulate_summary(&compiled, &scenario).unwrap());
        });
        println!("| compiled, summary only | {rtol} | (1501 seen, none kept) | {us:.0} µs | | |");
    }
    println!();
    println!(
        "Without events (loading branch, always in contact, no weld failure), bare integration:"
    );
    println!();
    println!(
        "| integrator | rtol | time (median) | steps | right-hand sides | error vs rtol 1e-13 |"
    );
    println!("|---|---|---|---|---|---|");
    peer_rows(&compiled, &scenario_path);
}
