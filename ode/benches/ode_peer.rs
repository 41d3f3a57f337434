//! Our DOPRI5 against `ode_solvers` (a well-kept Rust DOPRI5) on the same
//! problems and tolerances: wall time (median of repeated solves), steps and
//! right-hand-side evaluations. `cargo bench -p lagrangian-ode --bench ode_peer`.

use lagrangian_ode::tableau::DOPRI5;
use lagrangian_ode::{OdeProblem, Options, explicit};
use nalgebra::Vector4;
use std::convert::Infallible;
use std::time::{Duration, Instant};

const MU: f64 = 0.012277471;
const Y0: [f64; 4] = [0.994, 0.0, 0.0, -2.001_585_106_379_082_5];
const PERIOD: f64 = 17.065_216_560_157_96;

fn arenstorf(y: &[f64]) -> [f64; 4] {
    let mu1 = 1.0 - MU;
    let d1 = ((y[0] + MU).powi(2) + y[1].powi(2)).powf(1.5);
    let d2 = ((y[0] - mu1).powi(2) + y[1].powi(2)).powf(1.5);
    [
        y[2],
        y[3],
        y[0] + 2.0 * y[3] - mu1 * (y[0] + MU) / d1 - MU * (y[0] - mu1) / d2,
        y[1] - 2.0 * y[2] - mu1 * y[1] / d1 - MU * y[1] / d2,
    ]
}

struct Ours;
impl OdeProblem<Vector4<f64>> for Ours {
    type Error = Infallible;

    fn rhs(&mut self, _t: f64, y: &Vector4<f64>, dy: &mut Vector4<f64>) -> Result<(), Infallible> {
        *dy = Vector4::from(arenstorf(y.as_slice()));
        Ok(())
    }
}

struct Theirs;
impl ode_solvers::System<f64, ode_solvers::Vector4<f64>> for Theirs {
    fn system(&self, _t: f64, y: &ode_solvers::Vector4<f64>, dy: &mut ode_solvers::Vector4<f64>) {
        *dy = ode_solvers::Vector4::from(arenstorf(y.as_slice()));
    }
}

fn median(mut f: impl FnMut() -> (usize, usize), runs: usize) -> (Duration, usize, usize) {
    let _ = f();
    let mut times = Vec::with_capacity(runs);
    let mut last = (0, 0);
    for _ in 0..runs {
        let start = Instant::now();
        last = f();
        times.push(start.elapsed());
    }
    times.sort();
    (times[runs / 2], last.0, last.1)
}

fn main() {
    println!("| problem | tolerance | solver | time (median) | steps | f-evals | error at T |");
    println!("|---|---|---|---|---|---|---|");
    for tol in [1e-6, 1e-8, 1e-10] {
        let options = Options {
            rtol: tol,
            atol: tol,
            ..Options::default()
        };
        let mut ours_error = 0.0;
        let (time, steps, evals) = median(
            || {
                let out = explicit::integrate(
                    &DOPRI5,
                    &mut Ours,
                    0.0,
                    Vector4::from(Y0),
                    PERIOD,
                    &options,
                    &mut |_, _| {},
                )
                .unwrap();
                ours_error = (out.y - Vector4::from(Y0)).amax();
                (out.stats.accepted_steps, out.stats.rhs_evaluations)
            },
            51,
        );
        println!(
            "| Arenstorf | {tol:e} | lagrangian-sim dopri5 | {:.1} µs | {steps} | {evals} | {ours_error:.1e} |",
            time.as_secs_f64() * 1e6
        );
        let (time, steps, evals) = median(
            || {
                // Dense output every T/100 (with dx = T its last point is extrapolated).
                let mut solver = ode_solvers::Dopri5::new(
                    Theirs,
                    0.0,
                    PERIOD,
                    PERIOD / 100.0,
                    ode_solvers::Vector4::from(Y0),
                    tol,
                    tol,
                );
                let stats = solver.integrate().unwrap();
                (stats.accepted_steps as usize, stats.num_eval as usize)
            },
            51,
        );
        // Its output holds dense points only, the last one short of T by the
        // accumulated rounding of dx, so its end state is not comparable here.
        println!(
            "| Arenstorf | {tol:e} | ode_solvers 0.6 Dopri5 | {:.1} µs | {steps} | {evals} | – |",
            time.as_secs_f64() * 1e6
        );
    }
}
