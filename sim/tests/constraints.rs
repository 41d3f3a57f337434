//! Models with constraints beyond the explicit run: TR-BDF2 against
//! DOPRI5 on the four-bar, the static equilibrium on the constraints and
//! the modes on them against closed forms (a pendulum written in `x, y`, a
//! parallelogram four-bar hanging at rest), the constraint signals of
//! channels, and the right-hand side without allocation, bit for bit that
//! of the solve written out here as it was. (Those of a sweep:
//! lagrangian-studies' `tests/constraints_sweep.rs`.)

use lagrangian_runtime::constrained::{Baumgarte, ConstraintValues};
use lagrangian_runtime::linalg::Ldlt;
use lagrangian_runtime::{Interpreted, LagrangianSystem};
use lagrangian_sim::linearize::{At, ModeKind, linearize, markdown};
use lagrangian_sim::ode::{OdeProblem, PhaseState};
use lagrangian_sim::scenario::{ModelNames, Override, Scenario};
use lagrangian_sim::simulate::{CrashProblem, SimulationResult, simulate};
use nalgebra::{SMatrix, SVector};
use std::alloc::{GlobalAlloc, Layout, System};
use std::cell::Cell;
use std::f64::consts::{FRAC_PI_2, TAU};

const ROOT: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/..");

/// Counts the allocations of the thread that makes them.
struct Counting;

thread_local! {
    static ALLOCATIONS: Cell<usize> = const { Cell::new(0) };
}

// SAFETY: forwards to the system allocator; the count is a thread-local
// `Cell` of a `const` initializer, which allocates nothing.
unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        ALLOCATIONS.with(|n| n.set(n.get() + 1));
        unsafe { System.alloc(layout) }
    }
    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        unsafe { System.dealloc(ptr, layout) }
    }
}

#[global_allocator]
static COUNTING: Counting = Counting;

fn spec(name: &str) -> String {
    std::fs::read_to_string(format!("{ROOT}/specs/{name}.lpm")).unwrap()
}

fn scenario_text(name: &str) -> String {
    std::fs::read_to_string(format!("{ROOT}/specs/scenarios/{name}.toml")).unwrap()
}

fn model<const N: usize>(source: &str) -> (Interpreted<N>, ModelNames) {
    let model = lagrangian_core::interpret(source).unwrap();
    let names = ModelNames::of_interpreted(&model);
    (Interpreted::new(model).unwrap(), names)
}

fn scenario(text: &str, names: &ModelNames, settings: &[&str]) -> Scenario {
    let settings: Vec<String> = settings.iter().map(|s| s.to_string()).collect();
    Scenario::parse(text, None, names, &Override::parse_all(&settings).unwrap()).unwrap()
}

fn run<const N: usize>(source: &str, text: &str, settings: &[&str]) -> SimulationResult {
    let (system, names) = model::<N>(source);
    simulate(&system, &scenario(text, &names, settings)).unwrap()
}

const PENDULUM: &str = "model NonminimalPendulum;
coordinates { x [m], y [m] }
parameters { m [kg] = 2.0, l [m] = 1.5, g [m/s^2] = 9.81 }
kinetic = 0.5 * m * (pow(dot(x), 2) + pow(dot(y), 2));
potential = m * g * y;
constraint rod = x * x + y * y - l * l;
";

/// The shipped four-bar as a parallelogram: ground and coupler 0.7 m,
/// crank and rocker 0.3 m. It hangs at rest with crank and rocker straight
/// down and the coupler level.
const PARALLELOGRAM: [&str; 2] = ["l2=0.7", "l3=0.3"];

/// The parallelogram's one degree of freedom, the crank angle θ (the
/// rocker's too; the coupler translates): `T = ½ (m1/3 + m2 + m3/3) l1² θ̇²`,
/// `V = g l1 (m1/2 + m2 + m3/2) sin θ`, so about `θ = −π/2`
/// `ω² = g (m1/2 + m2 + m3/2) / ((m1/3 + m2 + m3/3) l1)`.
fn parallelogram_frequency_hz() -> f64 {
    let (l1, m1, m2, m3, g): (f64, f64, f64, f64, f64) = (0.3, 1.0, 2.0, 1.5, 9.81);
    let omega2 = g * (m1 / 2.0 + m2 + m3 / 2.0) / ((m1 / 3.0 + m2 + m3 / 3.0) * l1);
    omega2.sqrt() / TAU
}

/// The smallest difference of two angles, whatever turns lie between.
fn angle_between(a: f64, b: f64) -> f64 {
    ((a - b + std::f64::consts::PI).rem_euclid(TAU) - std::f64::consts::PI).abs()
}

#[test]
fn tr_bdf2_follows_dopri5_on_the_four_bar_and_holds_the_loop() {
    let (source, text) = (spec("four_bar_linkage"), scenario_text("four_bar_linkage"));
    let common = ["simulation.t_end=1.0", "simulation.output_interval=0.01"];
    let dopri5 = run::<3>(&source, &text, &common);
    let mut implicit = common.to_vec();
    implicit.extend([
        "simulation.method=tr-bdf2",
        "simulation.rtol=1e-8",
        "simulation.atol=1e-10",
    ]);
    let tr_bdf2 = run::<3>(&source, &text, &implicit);
    assert_eq!(tr_bdf2.samples.len(), dopri5.samples.len());
    let mut worst = 0.0f64;
    for (a, b) in tr_bdf2.samples.iter().zip(&dopri5.samples) {
        for i in 0..3 {
            let error = angle_between(a.q[i], b.q[i]);
            worst = worst.max(error);
            assert!(
                error < 1e-5,
                "θ{}({}) = {} vs {}",
                i + 1,
                a.t,
                a.q[i],
                b.q[i]
            );
        }
    }
    let drift = tr_bdf2.constraints.as_ref().unwrap().drift_max();
    let balance = tr_bdf2.summary.energy_balance_error_rel;
    println!(
        "TR-BDF2 vs DOPRI5: {worst:e} rad; drift {drift:e}; balance {balance:e}; {:?}",
        tr_bdf2.stats
    );
    // Each step's end projected back onto the loop.
    assert!(drift < 1e-11, "drift {drift}");
    assert!(balance < 1e-5, "energy balance {balance}");
}

/// Released beside the bottom of its circle with the rod too short, the
/// pendulum in `x, y` settles at the bottom, on the circle.
#[test]
fn the_equilibrium_of_a_pendulum_in_x_and_y_is_at_the_bottom_of_its_circle() {
    let text = "[initial]\nequilibrium = [\"x\", \"y\"]\n[initial.coordinates]\nx = 0.3\ny = -1.0\n\
                [simulation]\nt_end = 0.01\n";
    let result = run::<2>(PENDULUM, text, &[]);
    assert!(result.initial_q[0].abs() < 1e-12, "{:?}", result.initial_q);
    assert!(
        (result.initial_q[1] + 1.5).abs() < 1e-12,
        "{:?}",
        result.initial_q
    );
    // At rest there: the rod carries the weight, λ = −m g / (2 l).
    let lambda = result.samples[0].multipliers[0];
    assert!((lambda + 2.0 * 9.81 / 3.0).abs() < 1e-9, "λ = {lambda}");
}

#[test]
fn the_parallelogram_four_bar_hangs_straight_down() {
    let text = "[initial]\nequilibrium = [\"theta1\", \"theta2\", \"theta3\"]\n\
                [initial.coordinates]\ntheta1 = -1.3\ntheta2 = 0.2\ntheta3 = -1.4\n\
                [simulation]\nt_end = 0.01\n";
    let result = run::<3>(&spec("four_bar_linkage"), text, &PARALLELOGRAM);
    let q = &result.initial_q;
    assert!((q[0] + FRAC_PI_2).abs() < 1e-9, "{q:?}");
    assert!(q[1].abs() < 1e-9, "{q:?}");
    assert!((q[2] + FRAC_PI_2).abs() < 1e-9, "{q:?}");
    // It stays there.
    let last = &result.samples.last().unwrap().q;
    assert!((last[0] + FRAC_PI_2).abs() < 1e-9, "{last:?}");
}

#[test]
fn a_pendulum_in_x_and_y_has_one_mode_at_the_square_root_of_g_over_l() {
    let (system, names) = model::<2>(PENDULUM);
    let scenario = scenario("[initial.coordinates]\nx = 0.2\ny = -1.4\n", &names, &[]);
    let l = linearize(&system, &scenario, &At::Equilibrium).unwrap();
    assert_eq!(l.a.nrows(), 4);
    assert_eq!(l.modes.len(), 1, "{:?}", l.modes);
    let expected = (9.81_f64 / 1.5).sqrt() / TAU;
    let mode = &l.modes[0];
    assert!(
        (mode.frequency_hz - expected).abs() < 1e-7 * expected,
        "{mode:?}"
    );
    assert_eq!(mode.kind, ModeKind::Undamped);
    assert_eq!(l.constraints, ["rod"]);
    let report = markdown(&l, "NonminimalPendulum");
    assert!(report.contains("on the constraints (rod)"), "{report}");
}

#[test]
fn the_parallelogram_four_bar_has_the_mode_of_its_one_coordinate() {
    let (system, names) = model::<3>(&spec("four_bar_linkage"));
    let text = "[initial.coordinates]\ntheta1 = -1.3\ntheta2 = 0.2\ntheta3 = -1.4\n";
    let scenario = scenario(text, &names, &PARALLELOGRAM);
    let l = linearize(&system, &scenario, &At::Equilibrium).unwrap();
    assert!((l.operating_point.q[0] + FRAC_PI_2).abs() < 1e-9);
    assert_eq!(l.modes.len(), 1, "{:?}", l.modes);
    let expected = parallelogram_frequency_hz();
    let mode = &l.modes[0];
    assert!(
        (mode.frequency_hz - expected).abs() < 1e-7 * expected,
        "{mode:?} vs {expected}"
    );
    assert_eq!(mode.kind, ModeKind::Undamped);
}

/// `NAME.lambda` and `NAME.residual` as channels: their extremes are those
/// of the trajectory's multipliers and the constraint's drift.
#[test]
fn channels_read_the_multipliers_and_the_residuals() {
    let text = format!(
        "{}\n[metrics]\nforce = [\"loop_x.lambda\"]\ndisplacement = [\"loop_y.residual\"]\n",
        scenario_text("four_bar_linkage")
    );
    let result = run::<3>(&spec("four_bar_linkage"), &text, &["simulation.t_end=0.5"]);
    let channel = |name: &str| {
        (result.summary.channels.0.iter())
            .find(|c| c.name == name)
            .unwrap()
    };
    let lambda = channel("loop_x.lambda");
    let multipliers: Vec<f64> = result.samples.iter().map(|s| s.multipliers[0]).collect();
    let max = multipliers.iter().fold(f64::MIN, |m, x| m.max(*x));
    let min = multipliers.iter().fold(f64::MAX, |m, x| m.min(*x));
    assert_eq!(lambda.get("max"), Some(max));
    assert_eq!(lambda.get("min"), Some(min));
    assert_eq!(lambda.unit.as_deref(), Some("N"));
    let residual = channel("loop_y.residual");
    let drift = result.constraints.as_ref().unwrap().drift[1];
    let extreme = (residual.get("max").unwrap().abs()).max(residual.get("min").unwrap().abs());
    assert_eq!(extreme, drift);
    assert!(drift > 0.0 && drift < 1e-8, "{drift}");
}

#[test]
fn a_constraint_column_that_does_not_exist_gets_a_suggestion() {
    let (_, names) = model::<3>(&spec("four_bar_linkage"));
    let settings: Vec<String> = Vec::new();
    let text = "[metrics]\nforce = [\"loop_x.lamda\"]\n";
    let error =
        Scenario::parse(text, None, &names, &Override::parse_all(&settings).unwrap()).unwrap_err();
    let message = error.to_string();
    assert!(message.contains("loop_x.lambda"), "{message}");
}

/// The constrained solve as it was written before it kept its buffers:
/// everything allocated per call.
fn solve_as_before<const N: usize>(
    mass: &SMatrix<f64, N, N>,
    forcing: &SVector<f64, N>,
    values: &ConstraintValues,
    qd: &[f64],
    stabilization: Baumgarte,
) -> (SVector<f64, N>, Vec<f64>, f64) {
    let dot = |a: &[f64], b: &[f64]| -> f64 { a.iter().zip(b).map(|(x, y)| x * y).sum() };
    let m = values.layout.m;
    let rate = values.rate(qd);
    let gamma: Vec<f64> = (0..m)
        .map(|k| {
            values.acceleration()[k]
                - 2.0 * stabilization.alpha * rate[k]
                - stabilization.beta * stabilization.beta * values.residual()[k]
        })
        .collect();
    let ldlt = Ldlt::new(mass).unwrap();
    let free = ldlt.solve(forcing);
    let rows: Vec<SVector<f64, N>> = (0..m)
        .map(|k| ldlt.solve(&SVector::from_column_slice(values.jacobian_row(k))))
        .collect();
    let mut schur = vec![0.0; m * m];
    let mut rhs = vec![0.0; m];
    for k in 0..m {
        let g = values.jacobian_row(k);
        for (l, row) in rows.iter().enumerate() {
            schur[k * m + l] = dot(g, row.as_slice());
        }
        rhs[k] = gamma[k] - dot(g, free.as_slice());
    }
    let lambda = lagrangian_runtime::constrained::solve_positive_definite(&schur, m, &rhs).unwrap();
    let mut qdd = free;
    for (row, l) in rows.iter().zip(&lambda) {
        qdd += row * *l;
    }
    let velocity_rate: Vec<f64> = (0..m).map(|k| dot(values.jacobian_row(k), qd)).collect();
    let power = dot(&lambda, &velocity_rate);
    (qdd, lambda, power)
}

/// Along the four-bar's default run, the right-hand side allocates nothing
/// and gives the accelerations and the power of the solve as it was.
#[test]
fn the_constrained_right_hand_side_allocates_nothing_and_is_unchanged() {
    let (system, names) = model::<3>(&spec("four_bar_linkage"));
    let text = scenario_text("four_bar_linkage");
    let scenario = scenario(&text, &names, &["simulation.t_end=0.5"]);
    let result = simulate(&system, &scenario).unwrap();
    let mut problem = CrashProblem::new(&system, scenario.inputs.clone());
    let first = &result.samples[0];
    let y0 = PhaseState::new(SVector::from_column_slice(&first.q), SVector::zeros());
    problem.start(0.0, &y0).unwrap();
    let mut dy = PhaseState::zeros();
    for s in result.samples.iter().step_by(25) {
        let y = PhaseState::new(
            SVector::from_column_slice(&s.q),
            SVector::from_column_slice(&s.v),
        );
        let before = ALLOCATIONS.with(Cell::get);
        problem.rhs(s.t, &y, &mut dy).unwrap();
        assert_eq!(
            ALLOCATIONS.with(Cell::get),
            before,
            "allocated at t = {}",
            s.t
        );
        let (mass, forcing) = system.mass_matrix_and_forcing_pair(s.t, &y.q, &y.v, &problem.inputs);
        let mut values = ConstraintValues::new(2, 3);
        system.constraints(s.t, &y.q, &y.v, &problem.inputs, &mut values.values);
        let stabilization = problem.stabilization;
        let (qdd, _, power) = solve_as_before(&mass, &forcing, &values, &s.v, stabilization);
        assert_eq!(dy.v, qdd, "t = {}", s.t);
        let mut powers = [0.0; 2];
        let (mut m2, mut f2) = (SMatrix::zeros(), SVector::zeros());
        let model_powers = system.mass_matrix_forcing_and_powers(
            s.t,
            &y.q,
            &y.v,
            &problem.inputs,
            &mut m2,
            &mut f2,
        );
        powers[0] = model_powers[0];
        powers[1] = model_powers[1] + power;
        assert_eq!(dy.work, powers, "t = {}", s.t);
    }
}
