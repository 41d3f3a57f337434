//! Integrators for `y' = F(t, y)` with event location.
//!
//! The methods ([`Method`]) share one driver (`driver`): it asks a method's
//! stepper for steps, ends exactly at `t_end`, enforces the step limit and
//! the minimum step, and handles events. A method is a stepper:
//!
//! * explicit Runge–Kutta methods are one implementation ([`explicit`]) fed
//!   by Butcher tableaux as data ([`tableau`]): Dormand–Prince 5(4) with PI
//!   step control and its 4th-order dense output, and the classical
//!   fixed-step RK4;
//! * [`tr_bdf2`]: TR-BDF2, an L-stable, stiffly accurate ESDIRK method for
//!   stiff mechanical systems, with Newton iterations on the model's
//!   Jacobians.
//!
//! Events are zero crossings of functions `g_k(t, y)` with a direction; they
//! are located on the dense output by the Illinois method to
//! `|Δt| ≤ 1e-12`, and the problem decides what happens ([`EventAction`]):
//! stop there, or restart the step sequence from the event after changing
//! its mode, parameters or state.
//!
//! A problem whose `F` has kinks in time (a time table interpolated
//! linearly) may end steps at them ([`OdeProblem::next_stop`]) or, in a
//! step of an adaptive explicit method, stand in a smooth `F` across them
//! ([`OdeProblem::step_window`]).
//!
//! Adding a method: a stepper in its own file (or, for an explicit method, a
//! tableau in [`tableau`]) and one variant of [`Method`].

mod driver;
mod events;
pub mod explicit;
mod hermite;
mod internal;
mod lu;
mod method;
mod stops;
pub mod tableau;
pub mod tr_bdf2;
mod vector;

pub use events::{Direction, EventAction};
pub use hermite::{Hermite, hermite_weights};
pub use internal::{CAPACITY as INTERNAL_CAPACITY, Internal};
pub use method::{Method, UnknownMethod, integrate};
pub use vector::{OdeVector, Part, PhaseState};

/// The problem `y' = F(t, y)` with optional events.
pub trait OdeProblem<Y: OdeVector> {
    /// Why `F` or an event function could not be evaluated (the integrator
    /// reports it as [`SolverError::Rhs`] with the time).
    type Error;

    /// Writes `F(t, y)` into `dy`.
    fn rhs(&mut self, t: f64, y: &Y, dy: &mut Y) -> Result<(), Self::Error>;

    /// Number of event functions.
    fn event_count(&self) -> usize {
        0
    }

    /// Writes `g_k(t, y)` for every event `k` into `g`.
    fn events(&mut self, t: f64, y: &Y, g: &mut [f64]) -> Result<(), Self::Error> {
        let _ = (t, y, g);
        Ok(())
    }

    /// `g_k(t, y)` alone, what locating a crossing of event `k` reads at
    /// each point it tries; `g` (one entry per event) is scratch. By
    /// default every event function, into `g`; a problem whose functions
    /// cost something each evaluates only `g_k`, to the same bits.
    fn event(&mut self, k: usize, t: f64, y: &Y, g: &mut [f64]) -> Result<f64, Self::Error> {
        self.events(t, y, g)?;
        Ok(g[k])
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

    /// The first time after `t` at which `F` is not smooth in time (a
    /// kink of a time table interpolated linearly), if any: an adaptive
    /// step ends there instead of stepping across. `None` by default.
    fn next_stop(&mut self, t: f64) -> Option<f64> {
        let _ = t;
        None
    }

    /// The step an adaptive explicit method is about to try, `[t0, t0 + h]`
    /// (`Some((t0, h))`), or that it is done trying (`None`). In between, a
    /// problem whose `F` has kinks in time inside the step may evaluate a
    /// stand-in that is smooth over the step, equals `F` at both ends of it
    /// and has the same effect on the step's end to the method's order (the
    /// crash problem's time tables: `lagrangian_sim::components::StandIn`), so that
    /// the method's error estimate is not ruined by the kink. Ignored by
    /// default.
    fn step_window(&mut self, window: Option<(f64, f64)>) {
        let _ = window;
    }

    /// Which value of `dy = F(t, y)` is not finite, in words with the
    /// value, for [`SolverError::NonFinite`] (a problem that knows its
    /// components' names says which; "the right-hand side" by default).
    fn name_non_finite(&mut self, t: f64, y: &Y, dy: &Y) -> String {
        let _ = (t, y, dy);
        "the right-hand side".to_string()
    }

    /// The largest value of `dy = F(t, y)`, in words with the value, for a
    /// first step that rates too large to weigh make impossible ("the
    /// right-hand side" by default).
    fn name_largest_rate(&mut self, t: f64, y: &Y, dy: &Y) -> String {
        let _ = (t, y, dy);
        "the right-hand side".to_string()
    }

    /// Event function `k` for messages, with `value`, its value that is
    /// not finite ("event function k (NaN)" by default).
    fn name_event(&self, k: usize, value: f64) -> String {
        format!("event function {k} ({value})")
    }
}

/// Step-size control and limits.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Options {
    /// Relative tolerance of the local error.
    pub rtol: f64,
    /// Absolute tolerance of the local error.
    pub atol: f64,
    /// First step; chosen automatically (Hairer's algorithm) when `None`.
    pub initial_step: Option<f64>,
    /// Largest step.
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
    /// Steps accepted.
    pub accepted_steps: usize,
    /// Steps rejected (error test, Newton failure, singular iteration matrix).
    pub rejected_steps: usize,
    /// Evaluations of `F`.
    pub rhs_evaluations: usize,
    /// Newton iterations (implicit methods).
    pub newton_iterations: usize,
    /// Jacobian evaluations (implicit methods).
    pub jacobian_evaluations: usize,
    /// `(event, time)` of every event handled, in order.
    pub events: Vec<(usize, f64)>,
}

/// Why an integration stopped early; `E` is the problem's own error.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum SolverError<E> {
    /// The step size fell below `Options::min_step`, or below what moves `t`
    /// at all, through rejected or accepted steps.
    #[error("step size underflow at t = {t:e} s (h = {h:e} s)")]
    StepSizeUnderflow {
        /// Where the integration stood.
        t: f64,
        /// The step it would have needed.
        h: f64,
    },
    /// More than `Options::max_steps` steps were attempted.
    #[error("more than {steps} steps before t = {t:e} s")]
    MaxSteps {
        /// Where the integration stood.
        t: f64,
        /// The limit.
        steps: usize,
    },
    /// The right-hand side or an event function produced NaN or ±∞.
    #[error("{what} is not finite at t = {t:e} s")]
    NonFinite {
        /// When.
        t: f64,
        /// Which value.
        what: String,
    },
    /// The right-hand side, an event function or a Jacobian could not be
    /// evaluated: the problem's own error.
    #[error("at t = {t:e} s: {error}")]
    Rhs {
        /// When.
        t: f64,
        /// Why.
        error: E,
    },
    /// Newton's method did not converge, and the steps it was retried with
    /// fell below `Options::min_step`.
    #[error("Newton iterations diverge at t = {t:e} s even with h = {h:e} s")]
    NewtonFailure {
        /// Where the integration stood.
        t: f64,
        /// The last step tried.
        h: f64,
    },
    /// The Newton iteration matrix `I − d·h·J` of an implicit method was
    /// singular or not finite, and the steps it was retried with fell below
    /// `Options::min_step`.
    #[error(
        "the Newton iteration matrix I − d·h·J is singular or not finite at t = {t:e} s even with h = {h:e} s"
    )]
    SingularIterationMatrix {
        /// Where the integration stood.
        t: f64,
        /// The last step tried.
        h: f64,
    },
    /// An event's zero crossing could not be bracketed to the required accuracy.
    #[error("event {event} near t = {t:e} s could not be located")]
    EventNotLocated {
        /// Near when.
        t: f64,
        /// Which event function.
        event: usize,
    },
    /// Invalid options.
    #[error("invalid solver options: {0}")]
    InvalidOptions(String),
}

/// How an integration ended.
#[derive(Clone, Debug)]
pub struct Outcome<Y> {
    /// The time it ended at: `t_end`, or an event that stopped it.
    pub t: f64,
    /// The state there.
    pub y: Y,
    /// What it cost.
    pub stats: Stats,
    /// The event that stopped the integration, if one did.
    pub stopped_by: Option<usize>,
}

/// An accepted step with its continuous extension, as observers see it.
pub trait DenseStep<Y> {
    /// The start of the step.
    fn t0(&self) -> f64;
    /// The end of the step (the event time for a step cut at an event).
    fn t1(&self) -> f64;
    /// The solution at `t ∈ [t0, t1]`, written into `out`.
    fn eval(&self, t: f64, out: &mut Y);

    /// The end of the step as the method took it: [`DenseStep::t1`], or
    /// past it for a step cut at an event. The interpolant depends on `F`
    /// over all of `[t0, uncut_end]`, so a kink of `F` there shows in it
    /// even before `t1`.
    fn uncut_end(&self) -> f64;

    /// The time derivative of the interpolant at `t ∈ [t0, t1]`, written
    /// into `out`, where the method's continuous extension gives one as
    /// accurate as the solution needs: `true` then, `false` (the default,
    /// `out` left as it is) otherwise. Dormand–Prince's gives one: exact at
    /// both ends of the step (the stages `F(t0, y0)` and `F(t1, y1)`) and
    /// within `O(h⁴)` between them where `F` is smooth over the step. The
    /// derivative of a cubic Hermite interpolant (RK4, TR-BDF2) is a
    /// quadratic, an order less accurate: it declines.
    fn eval_derivative(&self, t: f64, out: &mut Y) -> bool {
        let _ = (t, out);
        false
    }

    /// [`DenseStep::eval`] of the components of `part` alone; the others of
    /// `out` keep their values (all are written by default).
    fn eval_part(&self, t: f64, part: Part, out: &mut Y) {
        let _ = part;
        self.eval(t, out);
    }

    /// [`DenseStep::eval_derivative`] of the components of `part` alone;
    /// the others of `out` keep their values (all are written by default).
    fn eval_derivative_part(&self, t: f64, part: Part, out: &mut Y) -> bool {
        let _ = part;
        self.eval_derivative(t, out)
    }
}

/// What the integrators call with every accepted step: the problem and the
/// step's dense output (truncated at events).
pub type Observer<'a, P, Y> = &'a mut dyn FnMut(&mut P, &dyn DenseStep<Y>);

impl Options {
    /// `Err` with the reason when the options cannot be used.
    pub fn validate<E>(&self) -> Result<(), SolverError<E>> {
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
) -> Result<(), SolverError<P::Error>> {
    stats.rhs_evaluations += 1;
    problem
        .rhs(t, y, dy)
        .map_err(|error| SolverError::Rhs { t, error })?;
    if dy.all_finite() {
        Ok(())
    } else {
        Err(SolverError::NonFinite {
            t,
            what: problem.name_non_finite(t, y, dy),
        })
    }
}

/// The weighted RMS norm of the local error estimate `err` (Hairer; SciPy):
/// `sqrt(mean((err_i / (atol + rtol·max(|y0_i|, |y1_i|)))²))` over the
/// components that control the step ([`OdeVector::controlled_len`] of
/// `y0`): quadratures are left out.
pub(crate) fn error_norm<Y: OdeVector>(err: &Y, y0: &Y, y1: &Y, options: &Options) -> f64 {
    let n = y0.controlled_len().min(err.len());
    let mut sum = 0.0;
    for i in 0..n {
        let scale = options.atol + options.rtol * y0.get(i).abs().max(y1.get(i).abs());
        let e = err.get(i) / scale;
        sum += e * e;
    }
    (sum / n.max(1) as f64).sqrt()
}

/// Hairer's starting step for a 5th-order method: `h0 = 0.01‖y0‖/‖f0‖`,
/// refined with one Euler step so that `h^5 · max(‖f0‖, ‖f1 − f0‖/h0) =
/// 0.01` (the same as SciPy's `select_initial_step`). TR-BDF2 starts with it
/// too; its controller adapts the step within the first few.
pub(crate) fn initial_step<Y: OdeVector, P: OdeProblem<Y>>(
    problem: &mut P,
    t: f64,
    y: &Y,
    f0: &Y,
    span: f64,
    options: &Options,
    stats: &mut Stats,
) -> Result<f64, SolverError<P::Error>> {
    // The error norm's weights with the scale of y alone.
    let scaled = |v: &Y| error_norm(v, y, y, options);
    let (d0, d1) = (scaled(y), scaled(f0));
    if !d1.is_finite() {
        // Finite rates whose weighted size overflows (a coefficient of
        // 1e300): no step can be chosen, which says more than h = 0.
        let largest = problem.name_largest_rate(t, y, f0);
        return Err(SolverError::NonFinite {
            t,
            what: format!("the weighted size of the rates (largest: {largest})"),
        });
    }
    // The probe is no shorter than the driver's smallest step. With a loose
    // rtol the weighted size of y saturates (|y|/(atol + rtol|y|) < 1/rtol),
    // while the rate of a component that starts at zero is weighed by atol
    // alone: 0.01·d0/d1 then says nothing about y's time scale (4e-18 s for
    // the paper's crash at rtol 0.9) and 100 such probes, the cap below, is
    // a first step the driver refuses at t = 0.
    let h0 = if d0 < 1e-5 || d1 < 1e-5 {
        1e-6
    } else {
        (0.01 * d0 / d1).max(options.min_step)
    }
    .min(span);
    let mut y1 = y.clone();
    y1.set_combination(y, &[(h0, f0)]);
    let mut f1 = y.clone();
    stats.rhs_evaluations += 1;
    problem
        .rhs(t + h0, &y1, &mut f1)
        .map_err(|error| SolverError::Rhs { t: t + h0, error })?;
    let mut diff = y.clone();
    diff.set_combination(&f1, &[(-1.0, f0)]);
    let d2 = scaled(&diff) / h0;
    if !d2.is_finite() {
        // Their change over the probe step overflows the same way.
        let largest = problem.name_largest_rate(t + h0, &y1, &f1);
        return Err(SolverError::NonFinite {
            t: t + h0,
            what: format!("the change of the rates over the first step (largest: {largest})"),
        });
    }
    let h1 = if d1 <= 1e-15 && d2 <= 1e-15 {
        (h0 * 1e-3).max(1e-6)
    } else {
        (0.01 / d1.max(d2)).powf(0.2)
    };
    Ok((100.0 * h0).min(h1).min(span).min(options.max_step))
}
