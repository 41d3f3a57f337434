//! Dormand–Prince 5(4) (Hairer, Nørsett & Wanner, *Solving ODEs I*, §II.5),
//! with FSAL, PI step-size control and the 4th-order dense output of DOPRI5.
//!
//! Step control: the error estimate `‖err‖` is the weighted RMS norm of
//! [`super::error_norm`]; a step is accepted when `‖err‖ ≤ 1`, and the next
//! step is `h · clamp(0.9 · ‖err‖^(−α) · ‖err_prev‖^β, 0.2, 10)` with the Lund
//! stabilization `β = 0.04`, `α = 1/5 − 0.75 β` (no growth right after a
//! rejection). The first step follows Hairer's `hinit` (the same as SciPy's
//! `select_initial_step`).

use super::driver::{Driver, Point, StepEnd, Truncate};
use super::{DenseStep, OdeProblem, OdeVector, Options, SolverError, Stats, error_norm, evaluate};

const C2: f64 = 1.0 / 5.0;
const C3: f64 = 3.0 / 10.0;
const C4: f64 = 4.0 / 5.0;
const C5: f64 = 8.0 / 9.0;
const A21: f64 = 1.0 / 5.0;
const A31: f64 = 3.0 / 40.0;
const A32: f64 = 9.0 / 40.0;
const A41: f64 = 44.0 / 45.0;
const A42: f64 = -56.0 / 15.0;
const A43: f64 = 32.0 / 9.0;
const A51: f64 = 19372.0 / 6561.0;
const A52: f64 = -25360.0 / 2187.0;
const A53: f64 = 64448.0 / 6561.0;
const A54: f64 = -212.0 / 729.0;
const A61: f64 = 9017.0 / 3168.0;
const A62: f64 = -355.0 / 33.0;
const A63: f64 = 46732.0 / 5247.0;
const A64: f64 = 49.0 / 176.0;
const A65: f64 = -5103.0 / 18656.0;
const A71: f64 = 35.0 / 384.0;
const A73: f64 = 500.0 / 1113.0;
const A74: f64 = 125.0 / 192.0;
const A75: f64 = -2187.0 / 6784.0;
const A76: f64 = 11.0 / 84.0;
// Error coefficients: 5th-order minus embedded 4th-order weights.
const E1: f64 = 71.0 / 57600.0;
const E3: f64 = -71.0 / 16695.0;
const E4: f64 = 71.0 / 1920.0;
const E5: f64 = -17253.0 / 339200.0;
const E6: f64 = 22.0 / 525.0;
const E7: f64 = -1.0 / 40.0;
// Dense output (Hairer's contd5).
const D1: f64 = -12715105075.0 / 11282082432.0;
const D3: f64 = 87487479700.0 / 32700410799.0;
const D4: f64 = -10690763975.0 / 1880347072.0;
const D5: f64 = 701980252875.0 / 199316789632.0;
const D6: f64 = -1453857185.0 / 822651844.0;
const D7: f64 = 69997945.0 / 29380423.0;

const SAFETY: f64 = 0.9;
const BETA: f64 = 0.04;
const MIN_FACTOR: f64 = 0.2;
const MAX_FACTOR: f64 = 10.0;

/// The 4th-order continuous extension of one step:
/// `y(t0 + θh) = r0 + θ(r1 + (1−θ)(r2 + θ(r3 + (1−θ) r4)))`.
pub struct Dense<Y> {
    t0: f64,
    t1: f64,
    h: f64,
    r: [Y; 5],
}

impl<Y> Truncate for Dense<Y> {
    fn truncate(self, end: f64) -> Self {
        Dense { t1: end, ..self }
    }
}

impl<Y: OdeVector> DenseStep<Y> for Dense<Y> {
    fn t0(&self) -> f64 {
        self.t0
    }

    fn t1(&self) -> f64 {
        self.t1
    }

    fn eval(&self, t: f64, out: &mut Y) {
        let theta = (t - self.t0) / self.h;
        let theta1 = 1.0 - theta;
        let [r0, r1, r2, r3, r4] = &self.r;
        out.set_combination(
            r0,
            &[
                (theta, r1),
                (theta * theta1, r2),
                (theta * theta * theta1, r3),
                (theta * theta * theta1 * theta1, r4),
            ],
        );
    }
}

/// How an integration ended (the same for every method).
pub use super::Outcome;

/// Integrates from `(t0, y0)` to `t_end`, calling `observer` with the problem
/// and every accepted step (truncated at events).
pub fn integrate<Y: OdeVector, P: OdeProblem<Y>>(
    problem: &mut P,
    t0: f64,
    y0: Y,
    t_end: f64,
    options: &Options,
    observer: &mut dyn FnMut(&mut P, &dyn DenseStep<Y>),
) -> Result<Outcome<Y>, SolverError> {
    let (mut t, mut y) = (t0, y0);
    let mut k1 = y.clone();
    let mut driver = Driver::start(problem, t, &y, &mut k1, t_end, options)?;
    let mut h = match options.fixed_step.or(options.initial_step) {
        Some(h) => h,
        None => initial_step(problem, t, &y, &k1, t_end - t, options, &mut driver.stats)?,
    }
    .min(options.max_step);
    let (mut k2, mut k3, mut k4, mut k5, mut k6, mut k7) = (
        y.clone(),
        y.clone(),
        y.clone(),
        y.clone(),
        y.clone(),
        y.clone(),
    );
    let (mut stage, mut y1, mut err) = (y.clone(), y.clone(), y.clone());
    let mut previous_error: f64 = 1e-4;
    let mut rejected_last = false;
    while let Some(step) = driver.next_step(t, h)? {
        h = step;
        let stats = &mut driver.stats;
        stage.set_combination(&y, &[(h * A21, &k1)]);
        evaluate(problem, t + C2 * h, &stage, &mut k2, stats)?;
        stage.set_combination(&y, &[(h * A31, &k1), (h * A32, &k2)]);
        evaluate(problem, t + C3 * h, &stage, &mut k3, stats)?;
        stage.set_combination(&y, &[(h * A41, &k1), (h * A42, &k2), (h * A43, &k3)]);
        evaluate(problem, t + C4 * h, &stage, &mut k4, stats)?;
        stage.set_combination(
            &y,
            &[
                (h * A51, &k1),
                (h * A52, &k2),
                (h * A53, &k3),
                (h * A54, &k4),
            ],
        );
        evaluate(problem, t + C5 * h, &stage, &mut k5, stats)?;
        stage.set_combination(
            &y,
            &[
                (h * A61, &k1),
                (h * A62, &k2),
                (h * A63, &k3),
                (h * A64, &k4),
                (h * A65, &k5),
            ],
        );
        evaluate(problem, t + h, &stage, &mut k6, stats)?;
        y1.set_combination(
            &y,
            &[
                (h * A71, &k1),
                (h * A73, &k3),
                (h * A74, &k4),
                (h * A75, &k5),
                (h * A76, &k6),
            ],
        );
        evaluate(problem, t + h, &y1, &mut k7, stats)?;
        err.set_sum(&[
            (h * E1, &k1),
            (h * E3, &k3),
            (h * E4, &k4),
            (h * E5, &k5),
            (h * E6, &k6),
            (h * E7, &k7),
        ]);
        let norm = if options.fixed_step.is_some() {
            0.0
        } else {
            error_norm(&err, &y, &y1, options)
        };
        if norm.is_nan() || norm > 1.0 {
            // Rejected (NaN counts as a failure too): shrink and retry.
            stats.rejected_steps += 1;
            let factor = if norm.is_finite() {
                (SAFETY * norm.powf(-0.2)).max(MIN_FACTOR)
            } else {
                MIN_FACTOR
            };
            h *= factor;
            rejected_last = true;
            continue;
        }
        stats.accepted_steps += 1;
        let dense = dense_output(t, h, &y, &y1, &k1, &k3, &k4, &k5, &k6, &k7);
        let point = Point {
            t: &mut t,
            y: &mut y,
            f: &mut k1,
        };
        match driver.finish_step(problem, dense, &y1, point, observer)? {
            StepEnd::Next => {}
            StepEnd::Restarted => {
                rejected_last = false;
                continue;
            }
            StepEnd::Stopped(k) => return Ok(driver.outcome(t, y, Some(k))),
        }
        t += h;
        std::mem::swap(&mut y, &mut y1);
        std::mem::swap(&mut k1, &mut k7);
        if options.fixed_step.is_none() {
            let mut factor =
                SAFETY * norm.max(1e-10).powf(-(0.2 - 0.75 * BETA)) * previous_error.powf(BETA);
            factor = factor.clamp(MIN_FACTOR, MAX_FACTOR);
            if rejected_last {
                factor = factor.min(1.0);
            }
            previous_error = norm.max(1e-4);
            h = (h * factor).min(options.max_step);
        }
        rejected_last = false;
    }
    Ok(driver.outcome(t, y, None))
}

#[allow(clippy::too_many_arguments)]
fn dense_output<Y: OdeVector>(
    t: f64,
    h: f64,
    y0: &Y,
    y1: &Y,
    k1: &Y,
    k3: &Y,
    k4: &Y,
    k5: &Y,
    k6: &Y,
    k7: &Y,
) -> Dense<Y> {
    let mut difference = y0.clone();
    difference.set_combination(y1, &[(-1.0, y0)]);
    let mut slope = y0.clone();
    slope.set_sum(&[(h, k1), (-1.0, &difference)]);
    let mut curvature = y0.clone();
    curvature.set_combination(&difference, &[(-h, k7), (-1.0, &slope)]);
    let mut correction = y0.clone();
    correction.set_sum(&[
        (h * D1, k1),
        (h * D3, k3),
        (h * D4, k4),
        (h * D5, k5),
        (h * D6, k6),
        (h * D7, k7),
    ]);
    Dense {
        t0: t,
        t1: t + h,
        h,
        r: [y0.clone(), difference, slope, curvature, correction],
    }
}

/// Hairer's starting step: `h0 = 0.01‖y0‖/‖f0‖`, refined with one Euler step so
/// that `h^5 · max(‖f0‖, ‖f1 − f0‖/h0) = 0.01`.
pub(crate) fn initial_step<Y: OdeVector, P: OdeProblem<Y>>(
    problem: &mut P,
    t: f64,
    y: &Y,
    f0: &Y,
    span: f64,
    options: &Options,
    stats: &mut Stats,
) -> Result<f64, SolverError> {
    // The error norm's weights with the scale of y alone.
    let scaled = |v: &Y| error_norm(v, y, y, options);
    let (d0, d1) = (scaled(y), scaled(f0));
    let h0 = if d0 < 1e-5 || d1 < 1e-5 {
        1e-6
    } else {
        0.01 * d0 / d1
    }
    .min(span);
    let mut y1 = y.clone();
    y1.set_combination(y, &[(h0, f0)]);
    let mut f1 = y.clone();
    stats.rhs_evaluations += 1;
    problem.rhs(t + h0, &y1, &mut f1)?;
    let mut diff = y.clone();
    diff.set_combination(&f1, &[(-1.0, f0)]);
    let d2 = scaled(&diff) / h0;
    let h1 = if d1 <= 1e-15 && d2 <= 1e-15 {
        (h0 * 1e-3).max(1e-6)
    } else {
        (0.01 / d1.max(d2)).powf(0.2)
    };
    Ok((100.0 * h0).min(h1).min(span).min(options.max_step))
}
