//! Integrators for `y' = F(t, y)` with event location.
//!
//! * [`dopri5`]: Dormand–Prince 5(4) with FSAL, PI step-size control and its
//!   4th-order continuous extension (dense output).
//! * [`rk4`]: the classical fixed-step Runge–Kutta method, for reference.
//! * [`sdirk`]: an L-stable, stiffly accurate SDIRK method for stiff
//!   mechanical systems, with Newton iterations on the model's Jacobians.
//!
//! Events are zero crossings of user functions `g_k(t, y)` with a direction;
//! they are located on the dense output by the Illinois method to
//! `|Δt| ≤ 1e-12`, and the problem decides what happens ([`EventAction`]):
//! stop there, or restart the step sequence from the event after changing
//! its mode, parameters or state.

pub mod dopri5;
mod driver;
mod events;
mod hermite;
mod lu;
pub mod rk4;
pub mod sdirk;
mod vector;

pub use events::{Direction, EventAction};
pub use hermite::{Hermite, hermite_weights};
pub use vector::{OdeVector, PhaseState};

use crate::fault::Fault;
use std::fmt;

/// The problem `y' = F(t, y)` with optional events.
pub trait OdeProblem<Y: OdeVector> {
    /// Writes `F(t, y)` into `dy`.
    fn rhs(&mut self, t: f64, y: &Y, dy: &mut Y) -> Result<(), SolverError>;

    /// Number of event functions.
    fn event_count(&self) -> usize {
        0
    }

    /// Writes `g_k(t, y)` for every event `k` into `g`.
    fn events(&mut self, t: f64, y: &Y, g: &mut [f64]) -> Result<(), SolverError> {
        let _ = (t, y, g);
        Ok(())
    }

    /// Which crossings of `g_k` count.
    fn event_direction(&self, k: usize) -> Direction {
        let _ = k;
        Direction::Either
    }

    /// Called at a located event `k` with the state there; may change the
    /// problem (mode, parameters) or the state.
    fn on_event(&mut self, k: usize, t: f64, y: &mut Y) -> EventAction {
        let _ = (k, t, y);
        EventAction::Stop
    }
}

/// Step-size control and limits.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Options {
    pub rtol: f64,
    pub atol: f64,
    /// First step; chosen automatically (Hairer's algorithm) when `None`.
    pub initial_step: Option<f64>,
    pub max_step: f64,
    /// A step that has to shrink below this is an error, which says why it
    /// shrank (error test, Newton divergence, singular iteration matrix).
    pub min_step: f64,
    /// Maximum number of attempted steps.
    pub max_steps: usize,
    /// Fixed step size for fixed-step methods, or to switch error control off.
    pub fixed_step: Option<f64>,
}

impl Default for Options {
    fn default() -> Self {
        Options {
            rtol: 1e-6,
            atol: 1e-9,
            initial_step: None,
            max_step: f64::INFINITY,
            min_step: 1e-14,
            max_steps: 1_000_000,
            fixed_step: None,
        }
    }
}

/// What an integration cost.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Stats {
    pub accepted_steps: usize,
    pub rejected_steps: usize,
    pub rhs_evaluations: usize,
    /// Newton iterations (implicit methods).
    pub newton_iterations: usize,
    /// Jacobian evaluations (implicit methods).
    pub jacobian_evaluations: usize,
    /// `(event, time)` of every event handled, in order.
    pub events: Vec<(usize, f64)>,
}

/// Why an integration stopped early.
#[derive(Clone, Debug, PartialEq)]
pub enum SolverError {
    /// The step size fell below `Options::min_step`, or below what moves `t`
    /// at all, through rejected or accepted steps.
    StepSizeUnderflow { t: f64, h: f64 },
    /// More than `Options::max_steps` steps were attempted.
    MaxSteps { t: f64, steps: usize },
    /// The right-hand side or an event function produced NaN or ±∞.
    NonFinite { t: f64, what: String },
    /// The right-hand side could not be evaluated: a singular mass matrix,
    /// a non-finite value, a table read outside its range.
    Rhs { t: f64, fault: Fault },
    /// Newton's method did not converge, and the steps it was retried with
    /// fell below `Options::min_step`.
    NewtonFailure { t: f64, h: f64 },
    /// The Newton iteration matrix `I − d·h·J` of an implicit method was
    /// singular or not finite, and the steps it was retried with fell below
    /// `Options::min_step`.
    SingularIterationMatrix { t: f64, h: f64 },
    /// An event's zero crossing could not be bracketed to the required accuracy.
    EventNotLocated { t: f64, event: usize },
    /// Invalid options.
    InvalidOptions(String),
}

impl fmt::Display for SolverError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            SolverError::StepSizeUnderflow { t, h } => {
                write!(f, "step size underflow at t = {t:e} s (h = {h:e} s)")
            }
            SolverError::MaxSteps { t, steps } => {
                write!(f, "more than {steps} steps before t = {t:e} s")
            }
            SolverError::NonFinite { t, what } => write!(f, "{what} is not finite at t = {t:e} s"),
            SolverError::Rhs { t, fault } => write!(f, "at t = {t:e} s: {fault}"),
            SolverError::NewtonFailure { t, h } => {
                write!(
                    f,
                    "Newton iterations diverge at t = {t:e} s even with h = {h:e} s"
                )
            }
            SolverError::SingularIterationMatrix { t, h } => write!(
                f,
                "the Newton iteration matrix I − d·h·J is singular or not finite at t = {t:e} s even with h = {h:e} s"
            ),
            SolverError::EventNotLocated { t, event } => {
                write!(f, "event {event} near t = {t:e} s could not be located")
            }
            SolverError::InvalidOptions(message) => write!(f, "invalid solver options: {message}"),
        }
    }
}

impl std::error::Error for SolverError {}

/// How an integration ended.
#[derive(Clone, Debug)]
pub struct Outcome<Y> {
    pub t: f64,
    pub y: Y,
    pub stats: Stats,
    /// The event that stopped the integration, if one did.
    pub stopped_by: Option<usize>,
}

/// An accepted step with its continuous extension, as observers see it.
pub trait DenseStep<Y> {
    fn t0(&self) -> f64;
    fn t1(&self) -> f64;
    /// The solution at `t ∈ [t0, t1]`, written into `out`.
    fn eval(&self, t: f64, out: &mut Y);
}

impl Options {
    pub(crate) fn validate(&self) -> Result<(), SolverError> {
        let bad = |what: &str| Err(SolverError::InvalidOptions(what.to_string()));
        let non_negative = |x: f64| x >= 0.0; // false for NaN
        if !(non_negative(self.rtol) && non_negative(self.atol)) || self.rtol + self.atol == 0.0 {
            return bad("rtol and atol must be non-negative and not both zero");
        }
        if self.rtol > 0.0 && self.rtol < 100.0 * f64::EPSILON {
            return bad("rtol below 100 ε cannot be met in double precision");
        }
        if !non_negative(self.min_step) || self.max_step.is_nan() || self.min_step >= self.max_step
        {
            return bad("need 0 ≤ min_step < max_step");
        }
        if let Some(h) = self.fixed_step.or(self.initial_step)
            && (h.is_nan() || h <= 0.0 || h.is_infinite())
        {
            return bad("step sizes must be positive and finite");
        }
        Ok(())
    }
}

/// `F(t, y)` into `dy`, counted, with non-finite values reported as errors.
pub(crate) fn evaluate<Y: OdeVector, P: OdeProblem<Y>>(
    problem: &mut P,
    t: f64,
    y: &Y,
    dy: &mut Y,
    stats: &mut Stats,
) -> Result<(), SolverError> {
    stats.rhs_evaluations += 1;
    problem.rhs(t, y, dy)?;
    if dy.all_finite() {
        Ok(())
    } else {
        Err(SolverError::NonFinite {
            t,
            what: "the right-hand side".to_string(),
        })
    }
}

/// The weighted RMS norm of the local error estimate `err` (Hairer; SciPy):
/// `sqrt(mean((err_i / (atol + rtol·max(|y0_i|, |y1_i|)))²))`.
pub(crate) fn error_norm<Y: OdeVector>(err: &Y, y0: &Y, y1: &Y, options: &Options) -> f64 {
    let n = err.len();
    let mut sum = 0.0;
    for i in 0..n {
        let scale = options.atol + options.rtol * y0.get(i).abs().max(y1.get(i).abs());
        let e = err.get(i) / scale;
        sum += e * e;
    }
    (sum / n.max(1) as f64).sqrt()
}
