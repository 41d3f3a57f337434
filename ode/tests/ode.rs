//! The integrators against known solutions.
//!
//! One driver runs every method of `Method::ALL` over the same test problems
//! with closed-form solutions — convergence order, dense output, event times
//! and directions, typed failures — so a new method gets its row in each
//! test by being added to `Method`. Method-specific tests follow: DOPRI5's
//! step counts against SciPy's RK45 (tests/reference/scipy_ode_reference.json,
//! made by the committed script beside it) and TR-BDF2 on a stiff spring.

use lagrangian_ode as ode;
use lagrangian_ode::tableau::DOPRI5;
use lagrangian_ode::tr_bdf2::{AccelerationJacobian, AccelerationJacobians};
use lagrangian_ode::{
    DenseStep, Direction, EventAction, Method, OdeProblem, Options, Outcome, PhaseState,
    SolverError, explicit, tr_bdf2,
};
use nalgebra::{SMatrix, Vector1, Vector4};
use std::convert::Infallible;
use std::f64::consts::PI;

/// `ẍ = a(t, x, ẋ)` with `∂a/∂x`, `∂a/∂ẋ`: what every method takes.
#[derive(Clone, Copy)]
struct Motion {
    acceleration: fn(f64, f64, f64) -> f64,
    jacobian: fn(f64, f64, f64) -> (f64, f64),
}

/// `ẍ = −x`: `x = cos t` from `(1, 0)`.
const OSCILLATOR: Motion = Motion {
    acceleration: |_, x, _| -x,
    jacobian: |_, _, _| (-1.0, 0.0),
};

/// What happens at the `n`-th event (from 1): may change the state.
type OnEvent = fn(&mut PhaseState<1>, usize) -> EventAction;

/// A test problem: a motion, with `g = x` as its one event function when
/// `event` is set, acting as `on_event` says.
struct Problem {
    motion: Motion,
    event: Option<(Direction, OnEvent)>,
    events_seen: usize,
}

impl Problem {
    fn new(motion: Motion) -> Problem {
        Problem {
            motion,
            event: None,
            events_seen: 0,
        }
    }
}

impl OdeProblem<PhaseState<1>> for Problem {
    type Error = Infallible;

    fn rhs(&mut self, t: f64, y: &PhaseState<1>, dy: &mut PhaseState<1>) -> Result<(), Infallible> {
        let a = (self.motion.acceleration)(t, y.q[0], y.v[0]);
        *dy = PhaseState::new(y.v, Vector1::new(a));
        Ok(())
    }

    fn event_count(&self) -> usize {
        usize::from(self.event.is_some())
    }

    fn events(&mut self, _t: f64, y: &PhaseState<1>, g: &mut [f64]) -> Result<(), Infallible> {
        g[0] = y.q[0];
        Ok(())
    }

    fn event_direction(&self, _k: usize) -> Direction {
        self.event.map_or(Direction::Either, |(d, _)| d)
    }

    fn on_event(&mut self, _k: usize, _t: f64, y: &mut PhaseState<1>) -> EventAction {
        self.events_seen += 1;
        self.event
            .map_or(EventAction::Stop, |(_, act)| act(y, self.events_seen))
    }
}

impl AccelerationJacobians<1> for Problem {
    fn acceleration_jacobians(
        &mut self,
        t: f64,
        y: &PhaseState<1>,
    ) -> Result<Option<AccelerationJacobian<1>>, Infallible> {
        let (a_q, a_v) = (self.motion.jacobian)(t, y.q[0], y.v[0]);
        Ok(Some((
            SMatrix::from_element(a_q),
            SMatrix::from_element(a_v),
        )))
    }
}

/// The global error `method` may have with the options of
/// [`accurate`]`(method, accuracy)` on a unit-scale problem over a few units
/// of time. An adaptive method of order `p` keeps the error of each step
/// near `rtol` with steps `h ∝ rtol^(1/(p+1))`, so it takes
/// `∝ rtol^(−1/(p+1))` steps and its global error is
/// `∝ rtol^(p/(p+1))`; a fixed-step one with `h = accuracy^(1/p)` has a
/// global error `∝ h^p = accuracy`. The factor 2 covers the constants.
fn error_bound(method: Method, accuracy: f64) -> f64 {
    let p = method.order() as f64;
    if method.is_adaptive() {
        2.0 * accuracy.powf(p / (p + 1.0))
    } else {
        2.0 * accuracy
    }
}

/// The options that make `method` accurate to about `accuracy`: the
/// tolerances of an adaptive method, the step of a fixed-step one.
fn accurate(method: Method, accuracy: f64) -> Options {
    if method.is_adaptive() {
        Options {
            rtol: accuracy,
            atol: accuracy * 1e-2,
            ..Options::default()
        }
    } else {
        Options {
            fixed_step: Some(accuracy.powf(1.0 / method.order() as f64)),
            ..Options::default()
        }
    }
}

fn solve(
    method: Method,
    problem: &mut Problem,
    y0: (f64, f64),
    t_end: f64,
    options: &Options,
) -> Result<Outcome<PhaseState<1>>, SolverError<Infallible>> {
    let y0 = PhaseState::new(Vector1::new(y0.0), Vector1::new(y0.1));
    ode::integrate(method, problem, (0.0, y0), t_end, options, &mut |_, _| {})
}

#[test]
fn every_method_converges_with_its_order() {
    for method in Method::ALL {
        // The global error at t = 10 of ẍ = −x with fixed steps h and 2h.
        let error = |h: f64| {
            let options = Options {
                fixed_step: Some(h),
                ..Options::default()
            };
            let out = solve(
                method,
                &mut Problem::new(OSCILLATOR),
                (1.0, 0.0),
                10.0,
                &options,
            );
            let y = out.unwrap().y;
            (y.q[0] - 10f64.cos())
                .abs()
                .max((y.v[0] + 10f64.sin()).abs())
        };
        let h = 0.05;
        let observed = (error(2.0 * h) / error(h)).log2();
        let expected = method.order() as f64;
        println!("{method}: observed order {observed:.3} (expected {expected})");
        assert!(
            (expected - 0.1..expected + 0.2).contains(&observed),
            "{method}: order {observed}, expected {expected}"
        );
    }
}

#[test]
fn every_method_has_accurate_dense_output() {
    for method in Method::ALL {
        let accuracy = 1e-10;
        let mut worst = 0.0f64;
        let mut observer = |_: &mut Problem, step: &dyn DenseStep<PhaseState<1>>| {
            let mut y = PhaseState::zeros();
            for k in 1..10 {
                let t = step.t0() + (step.t1() - step.t0()) * k as f64 / 10.0;
                step.eval(t, &mut y);
                worst = worst.max((y.q[0] - t.cos()).abs());
            }
        };
        let y0 = PhaseState::new(Vector1::new(1.0), Vector1::new(0.0));
        let options = accurate(method, accuracy);
        let mut problem = Problem::new(OSCILLATOR);
        ode::integrate(
            method,
            &mut problem,
            (0.0, y0),
            10.0,
            &options,
            &mut observer,
        )
        .unwrap();
        let bound = error_bound(method, accuracy);
        println!("{method}: dense output error {worst:.1e} (bound {bound:.1e})");
        assert!(worst < bound, "{method}: {worst}");
    }
}

#[test]
fn every_method_locates_bounces_at_the_closed_form_times() {
    // A ball dropped from h0, bouncing with restitution e, stopped at the 5th.
    let (g, e, h0): (f64, f64, f64) = (9.81, 0.8, 2.0);
    let falling = Motion {
        acceleration: |_, _, _| -9.81,
        jacobian: |_, _, _| (0.0, 0.0),
    };
    let bounce = |y: &mut PhaseState<1>, seen: usize| {
        y.q[0] = 0.0;
        y.v[0] *= -0.8;
        if seen == 5 {
            EventAction::Stop
        } else {
            EventAction::Restart
        }
    };
    // t1 = √(2 h0 / g); each bounce k then flies 2 eᵏ v1 / g.
    let t1 = (2.0 * h0 / g).sqrt();
    let mut expected = vec![t1];
    for k in 1..5 {
        expected.push(expected[k - 1] + 2.0 * e.powi(k as i32) * g * t1 / g);
    }
    // The flights are quadratic in time, which every method integrates
    // exactly: the times are off by rounding and the location tolerance only.
    for method in Method::ALL {
        let mut ball = Problem {
            event: Some((Direction::Falling, bounce)),
            ..Problem::new(falling)
        };
        let options = accurate(method, 1e-10);
        let out = solve(method, &mut ball, (h0, 0.0), 100.0, &options).unwrap();
        let times: Vec<f64> = out.stats.events.iter().map(|(_, t)| *t).collect();
        assert_eq!(times.len(), 5, "{method}");
        let worst = times
            .iter()
            .zip(&expected)
            .map(|(a, b)| (a - b).abs())
            .fold(0.0, f64::max);
        println!("{method}: bounce times off by at most {worst:.1e} s");
        assert!(worst <= 1e-10, "{method}: {times:?} vs {expected:?}");
        assert_eq!(out.stopped_by, Some(0), "{method}");
        assert!((out.t - expected[4]).abs() <= 1e-10, "{method}");
    }
}

#[test]
fn every_method_respects_event_directions() {
    // x = cos t: falling zeros at π/2 + 2kπ, rising ones at 3π/2 + 2kπ.
    for method in Method::ALL {
        for (direction, expected) in [
            (Direction::Falling, PI / 2.0),
            (Direction::Rising, 1.5 * PI),
            (Direction::Either, PI / 2.0),
        ] {
            let mut crossings = Problem {
                event: Some((direction, |_, _| EventAction::Stop)),
                ..Problem::new(OSCILLATOR)
            };
            let options = accurate(method, 1e-12);
            let out = solve(method, &mut crossings, (1.0, 0.0), 10.0, &options).unwrap();
            // |ẋ| = 1 at the crossings: the time error is the state error.
            let (error, bound) = ((out.t - expected).abs(), error_bound(method, 1e-12));
            println!(
                "{method} {direction:?}: event at {} (error {error:.1e})",
                out.t
            );
            assert!(
                error <= bound,
                "{method} {direction:?}: {} vs {expected}",
                out.t
            );
        }
    }
}

/// DOPRI5, the default method, at tight tolerances: the crossing times
/// to 1e-10.
#[test]
fn dopri5_locates_crossings_to_1e_10() {
    let options = Options {
        rtol: 1e-12,
        atol: 1e-13,
        ..Options::default()
    };
    for (direction, expected) in [
        (Direction::Falling, PI / 2.0),
        (Direction::Rising, 1.5 * PI),
        (Direction::Either, PI / 2.0),
    ] {
        let mut crossings = Problem {
            event: Some((direction, |_, _| EventAction::Stop)),
            ..Problem::new(OSCILLATOR)
        };
        let out = solve(Method::Dopri5, &mut crossings, (1.0, 0.0), 10.0, &options).unwrap();
        let error = (out.t - expected).abs();
        assert!(error <= 1e-10, "{direction:?}: {} vs {expected}", out.t);
    }
}

#[test]
fn every_method_reports_failures_as_typed_errors() {
    // ẍ = 2x³ from (1, 1): x = 1/(1 − t) blows up at t = 1.
    let blow_up = Motion {
        acceleration: |_, x, _| 2.0 * x * x * x,
        jacobian: |_, x, _| (6.0 * x * x, 0.0),
    };
    for method in Method::ALL {
        let options = accurate(method, 1e-6);
        let err = solve(
            method,
            &mut Problem::new(blow_up),
            (1.0, 1.0),
            2.0,
            &options,
        )
        .unwrap_err();
        println!("{method}: {err}");
        // Near t = 1, or a few fixed steps past it.
        let window = 0.99..1.0 + 4.0 * options.fixed_step.unwrap_or(0.0025);
        assert!(
            matches!(
                err,
                SolverError::StepSizeUnderflow { t, .. }
                | SolverError::NonFinite { t, .. } if window.contains(&t)
            ),
            "{method}: {err:?}"
        );
        let few = Options {
            max_steps: 10,
            ..accurate(method, 1e-6)
        };
        let err = solve(
            method,
            &mut Problem::new(OSCILLATOR),
            (1.0, 0.0),
            100.0,
            &few,
        )
        .unwrap_err();
        assert!(
            matches!(err, SolverError::MaxSteps { steps: 10, .. }),
            "{method}: {err:?}"
        );
        let bad = Options {
            rtol: -1.0,
            ..accurate(method, 1e-6)
        };
        let err = solve(method, &mut Problem::new(OSCILLATOR), (0.0, 0.0), 1.0, &bad);
        assert!(
            matches!(err, Err(SolverError::InvalidOptions(_))),
            "{method}"
        );
    }
    // A fixed-step method without a step says so.
    let err = solve(
        Method::Rk4,
        &mut Problem::new(OSCILLATOR),
        (0.0, 0.0),
        1.0,
        &Options::default(),
    )
    .unwrap_err();
    assert_eq!(
        err.to_string(),
        "invalid solver options: rk4 needs a fixed step size"
    );
}

/// The restricted three-body problem (Arenstorf orbit).
struct Arenstorf {
    mu: f64,
}

impl OdeProblem<Vector4<f64>> for Arenstorf {
    type Error = Infallible;

    fn rhs(&mut self, _t: f64, y: &Vector4<f64>, dy: &mut Vector4<f64>) -> Result<(), Infallible> {
        let (mu, mu1) = (self.mu, 1.0 - self.mu);
        let d1 = ((y[0] + mu).powi(2) + y[1].powi(2)).powf(1.5);
        let d2 = ((y[0] - mu1).powi(2) + y[1].powi(2)).powf(1.5);
        *dy = Vector4::new(
            y[2],
            y[3],
            y[0] + 2.0 * y[3] - mu1 * (y[0] + mu) / d1 - mu * (y[0] - mu1) / d2,
            y[1] - 2.0 * y[2] - mu1 * y[1] / d1 - mu * y[1] / d2,
        );
        Ok(())
    }
}

#[test]
fn dopri5_step_counts_on_arenstorf_are_within_ten_percent_of_scipy() {
    let text = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../tests/reference/scipy_ode_reference.json"
    ))
    .unwrap();
    let reference: serde_json::Value = serde_json::from_str(&text).unwrap();
    let arenstorf = &reference["arenstorf"];
    let mu = arenstorf["mu"].as_f64().unwrap();
    let period = arenstorf["period"].as_f64().unwrap();
    let y0: Vec<f64> = arenstorf["y0"]
        .as_array()
        .unwrap()
        .iter()
        .map(|v| v.as_f64().unwrap())
        .collect();
    for run in arenstorf["runs"].as_array().unwrap() {
        let (rtol, atol) = (run["rtol"].as_f64().unwrap(), run["atol"].as_f64().unwrap());
        let scipy_steps = run["accepted"].as_u64().unwrap() as f64;
        let scipy_attempts = scipy_steps + run["rejected"].as_u64().unwrap() as f64;
        let scipy_nfev = run["nfev"].as_u64().unwrap() as f64;
        let options = Options {
            rtol,
            atol,
            ..Options::default()
        };
        let y0 = Vector4::from_column_slice(&y0);
        let mut problem = Arenstorf { mu };
        let out = explicit::integrate(
            &DOPRI5,
            &mut problem,
            0.0,
            y0,
            period,
            &options,
            &mut |_, _| {},
        )
        .unwrap();
        let ratio = out.stats.accepted_steps as f64 / scipy_steps;
        let attempts = (out.stats.accepted_steps + out.stats.rejected_steps) as f64;
        let attempt_ratio = attempts / scipy_attempts;
        let nfev_ratio = out.stats.rhs_evaluations as f64 / scipy_nfev;
        let periodicity = (out.y - y0).amax();
        println!(
            "rtol {rtol:e} atol {atol:e}: {} accepted, {} rejected, {} f-evals (attempts {attempt_ratio:.3}, accepted {ratio:.3}, f-evals {nfev_ratio:.3} of SciPy's); |y(T) − y0| = {periodicity:.2e} (SciPy {:.2e})",
            out.stats.accepted_steps,
            out.stats.rejected_steps,
            out.stats.rhs_evaluations,
            run["periodicity_error"].as_f64().unwrap()
        );
        // Attempted steps measure the cost (six evaluations each): within 10 %.
        // Accepted steps alone run 6–10 % above SciPy's (our PI controller
        // rejects fewer steps and grows more cautiously).
        assert!(
            (0.9..=1.1).contains(&attempt_ratio),
            "rtol {rtol}: {attempts} attempted steps vs SciPy {scipy_attempts}"
        );
        assert!(
            (0.9..=1.12).contains(&ratio),
            "rtol {rtol}: accepted steps {} vs SciPy {scipy_steps}",
            out.stats.accepted_steps
        );
    }
}

/// m ẍ = −k x − c ẋ with a very stiff spring, as a mechanical problem with
/// the dissipated energy integrated.
struct StiffSpring {
    k: f64,
    c: f64,
    analytic_jacobian: bool,
}

impl OdeProblem<PhaseState<1>> for StiffSpring {
    type Error = Infallible;

    fn rhs(
        &mut self,
        _t: f64,
        y: &PhaseState<1>,
        dy: &mut PhaseState<1>,
    ) -> Result<(), Infallible> {
        let a = -self.k * y.q[0] - self.c * y.v[0];
        *dy = PhaseState {
            q: y.v,
            v: Vector1::new(a),
            work: [self.c * y.v[0] * y.v[0], 0.0],
            z: Default::default(),
        };
        Ok(())
    }
}

impl AccelerationJacobians<1> for StiffSpring {
    fn acceleration_jacobians(
        &mut self,
        _t: f64,
        _y: &PhaseState<1>,
    ) -> Result<Option<AccelerationJacobian<1>>, Infallible> {
        Ok(self.analytic_jacobian.then(|| {
            (
                SMatrix::from_element(-self.k),
                SMatrix::from_element(-self.c),
            )
        }))
    }
}

#[test]
fn tr_bdf2_handles_stiffness() {
    // A stiff, overdamped spring (k = 1e8, c = 2.5e4: modes at about −4e3
    // and −2.1e4 s⁻¹): the explicit method is limited by stability, the
    // implicit one is not.
    let options = Options {
        rtol: 1e-6,
        atol: 1e-9,
        ..Options::default()
    };
    let y0 = PhaseState::new(Vector1::new(1e-3), Vector1::new(0.0));
    let mut stiff = StiffSpring {
        k: 1e8,
        c: 2.5e4,
        analytic_jacobian: true,
    };
    let run = |method: Method, problem: &mut StiffSpring| {
        ode::integrate(method, problem, (0.0, y0), 10.0, &options, &mut |_, _| {}).unwrap()
    };
    let implicit = run(Method::TrBdf2, &mut stiff);
    let explicit = run(Method::Dopri5, &mut stiff);
    let mut by_differences = StiffSpring {
        analytic_jacobian: false,
        ..stiff
    };
    let fd = run(Method::TrBdf2, &mut by_differences);
    println!(
        "stiff spring to t = 10 s: TR-BDF2 {} steps ({} with finite-difference Jacobians), DOPRI5 {} steps",
        implicit.stats.accepted_steps, fd.stats.accepted_steps, explicit.stats.accepted_steps
    );
    assert!(implicit.stats.accepted_steps * 20 < explicit.stats.accepted_steps);
    assert!((implicit.y.q[0] - explicit.y.q[0]).abs() < 1e-9);
    // Energy bookkeeping: T + V + dissipated stays at the initial energy.
    let energy =
        |y: &PhaseState<1>| 0.5 * y.v[0] * y.v[0] + 0.5 * 1e8 * y.q[0] * y.q[0] + y.work[0];
    let e0 = energy(&y0);
    assert!(
        (energy(&implicit.y) - e0).abs() < 1e-4 * e0,
        "{} vs {e0}",
        energy(&implicit.y)
    );
}

#[test]
fn tr_bdf2_failures_say_why_the_step_shrank() {
    let run = |acceleration: fn(f64, f64, f64) -> f64,
               jacobian: fn(f64, f64, f64) -> (f64, f64)| {
        let mut problem = Problem::new(Motion {
            acceleration,
            jacobian,
        });
        let y0 = PhaseState::new(Vector1::new(0.0), Vector1::new(1e-3));
        let options = Options {
            initial_step: Some(1e-3),
            ..Options::default()
        };
        tr_bdf2::integrate(&mut problem, 0.0, y0, 2.0, &options, &mut |_, _| {}).unwrap_err()
    };
    let zero = |_, _, _| (0.0, 0.0);
    // A jump of the acceleration at t = 1: Newton converges at every step
    // size, the error test fails at every one.
    let err = run(|t, _, _| if t < 1.0 { 0.0 } else { 1e10 }, zero);
    assert!(
        matches!(err, SolverError::StepSizeUnderflow { t, .. } if (t - 1.0).abs() < 1e-6),
        "{err:?}"
    );
    // Very stiff dry friction: the iterates swing between ±v, at every step size.
    let err = run(|_, _, v| -1e12 * v.signum(), zero);
    assert!(matches!(err, SolverError::NewtonFailure { .. }), "{err:?}");
    assert!(
        err.to_string().contains("Newton iterations diverge"),
        "{err}"
    );
    // A Jacobian that is not finite: no iteration matrix at any step size.
    let err = run(|_, x, _| -x, |_, _, _| (f64::INFINITY, 0.0));
    assert!(
        matches!(err, SolverError::SingularIterationMatrix { t: 0.0, .. }),
        "{err:?}"
    );
    assert!(err.to_string().contains("iteration matrix"), "{err}");
}

#[test]
fn every_adaptive_method_starts_at_loose_tolerances() {
    // `x = 15 sin t` from x = 0: with rtol 0.9 the weighted size of the
    // state is at most 1/rtol, and the rate of the coordinate that starts
    // at zero is weighed by atol alone, so Hairer's probe 0.01‖y‖/‖f‖ came
    // out near 1e-17 s and the first step below the minimum step, at t = 0.
    let options = Options {
        rtol: 0.9,
        atol: 1e-14,
        ..Options::default()
    };
    for method in Method::ALL.into_iter().filter(|m| m.is_adaptive()) {
        let outcome = solve(
            method,
            &mut Problem::new(OSCILLATOR),
            (0.0, 15.0),
            3.0,
            &options,
        )
        .unwrap_or_else(|e| panic!("{method}: {e}"));
        assert_eq!(outcome.t, 3.0, "{method}");
        // Loose, but a solution: within a third of the amplitude.
        let error = (outcome.y.q[0] - 15.0 * 3.0f64.sin()).abs();
        assert!(error < 5.0, "{method}: error {error}");
    }
}
