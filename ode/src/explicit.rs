//! Explicit Runge–Kutta methods from their tableaux ([`super::tableau`]).
//!
//! With an embedded error estimate and no fixed step, the step size is
//! controlled: the error estimate `‖err‖` is the weighted RMS norm Hairer
//! and SciPy use; a step is accepted when `‖err‖ ≤ 1`, and the next
//! step is `h · clamp(0.9 · ‖err‖^(−α) · ‖err_prev‖^β, 0.2, 10)` with the Lund
//! stabilization `β = 0.04`, `α = 1/p − 0.75 β` for a method of order `p`
//! (no growth right after a rejection). The first step follows Hairer's
//! `hinit` (the same as SciPy's `select_initial_step`). Without an estimate,
//! or with `Options::fixed_step`, steps have the fixed size. A controlled
//! step whose stages reach a state where `F` is not finite is rejected and
//! retried shorter; the error is reported once the step cannot shrink.

use super::driver::{Attempt, Stepper, Truncate};
use super::hermite::Hermite;
use super::tableau::{DenseOutput, Tableau};
use super::{
    DenseStep, Observer, OdeProblem, OdeVector, Options, Outcome, Part, SolverError, Stats,
    error_norm, evaluate,
};

const SAFETY: f64 = 0.9;
const BETA: f64 = 0.04;
const MIN_FACTOR: f64 = 0.2;
const MAX_FACTOR: f64 = 10.0;

/// Integrates from `(t0, y0)` to `t_end` with the explicit method `tableau`,
/// calling `observer` with the problem and every accepted step (truncated
/// at events).
pub fn integrate<Y: OdeVector, P: OdeProblem<Y>>(
    tableau: &'static Tableau,
    problem: &mut P,
    t0: f64,
    y0: Y,
    t_end: f64,
    options: &Options,
    observer: Observer<'_, P, Y>,
) -> Result<Outcome<Y>, SolverError<P::Error>> {
    let mut stepper = ExplicitRk::new(tableau, &y0, options)?;
    super::driver::run(&mut stepper, problem, (t0, y0), t_end, options, observer)
}

/// The non-zero coefficients of a row of a tableau: `(stage, coefficient)`.
type Row = Vec<(usize, f64)>;

/// `(j, w_j)` for the non-zero `w_j`, so that a step skips the terms a
/// method does not have.
fn nonzero(weights: &[f64]) -> Row {
    (weights.iter().copied().enumerate())
        .filter(|&(_, w)| w != 0.0)
        .collect()
}

/// A tableau's rows as a step uses them.
struct Rows {
    /// Stage `i`'s coefficients `a_ij`.
    stages: Vec<Row>,
    /// The weights `b_j` of the solution.
    solution: Row,
    /// The weights of the error estimate.
    error: Option<Row>,
    /// The weights of Dormand–Prince's `r4`.
    dense: Option<Row>,
}

impl Rows {
    fn of(tableau: &Tableau) -> Rows {
        Rows {
            stages: tableau.a.iter().map(|row| nonzero(row)).collect(),
            solution: nonzero(tableau.b),
            error: tableau.error.map(nonzero),
            dense: match tableau.dense {
                DenseOutput::DormandPrince { d } => Some(nonzero(d)),
                DenseOutput::Hermite => None,
            },
        }
    }
}

/// The stepper of an explicit method: its stages and the end of a step.
struct ExplicitRk<Y> {
    tableau: &'static Tableau,
    rows: Rows,
    options: Options,
    /// `Some(h)` for fixed steps.
    fixed: Option<f64>,
    /// Stages `k_1 … k_{s−1}` (`k_0` is the driver's `F(t, y)`).
    k: Vec<Y>,
    stage: Y,
    y1: Y,
    /// `F(t + h, y1)` of a method that is not FSAL.
    f1: Y,
    err: Y,
    /// The error norm of the last accepted step, for the next step size.
    norm: f64,
    previous_error: f64,
    rejected_last: bool,
}

impl<Y: OdeVector> ExplicitRk<Y> {
    fn new<E>(
        tableau: &'static Tableau,
        y0: &Y,
        options: &Options,
    ) -> Result<Self, SolverError<E>> {
        options.validate()?;
        check(tableau)?;
        let fixed = match (options.fixed_step, tableau.error) {
            (Some(h), _) => Some(h),
            (None, Some(_)) => None,
            (None, None) => {
                return Err(SolverError::InvalidOptions(format!(
                    "{} needs a fixed step size",
                    tableau.name
                )));
            }
        };
        Ok(ExplicitRk {
            tableau,
            rows: Rows::of(tableau),
            options: *options,
            fixed,
            k: vec![y0.clone(); tableau.stages()],
            stage: y0.clone(),
            y1: y0.clone(),
            f1: y0.clone(),
            err: y0.clone(),
            norm: 0.0,
            previous_error: 1e-4,
            rejected_last: false,
        })
    }

    /// Stage `i`'s argument `y + h Σ_{j<i} a_ij k_j` (into `y1` for the last
    /// stage of an FSAL method), then `k_i` at `t + c_i h`.
    fn stage<P: OdeProblem<Y>>(
        &mut self,
        problem: &mut P,
        (t, y, f): (f64, &Y, &Y),
        (i, h): (usize, f64),
        stats: &mut Stats,
    ) -> Result<(), SolverError<P::Error>> {
        let (tableau, k) = (self.tableau, &self.k);
        let mut terms = [(0.0, f); MAX_STAGES];
        let m = gather(&mut terms, &self.rows.stages[i], k, f, h);
        let last_is_y1 = tableau.fsal && i + 1 == tableau.stages();
        let argument = if last_is_y1 {
            &mut self.y1
        } else {
            &mut self.stage
        };
        argument.set_combination(y, &terms[..m]);
        let argument = if last_is_y1 { &self.y1 } else { &self.stage };
        evaluate(
            problem,
            t + tableau.c[i] * h,
            argument,
            &mut self.k[i],
            stats,
        )
    }

    /// `Σ h w_j k_j` over the weights `row` (`k_0 = f`) into `out`, added
    /// to `base` when given.
    fn weighted(k: &[Y], f: &Y, row: &[(usize, f64)], h: f64, base: Option<&Y>, out: &mut Y) {
        let mut terms = [(0.0, f); MAX_STAGES];
        let m = gather(&mut terms, row, k, f, h);
        match base {
            Some(base) => out.set_combination(base, &terms[..m]),
            None => out.set_sum(&terms[..m]),
        }
    }

    /// `F(t + h, y1)`: the last stage of an FSAL method, else `f1`.
    fn end_derivative(&self) -> &Y {
        if self.tableau.fsal {
            &self.k[self.tableau.stages() - 1]
        } else {
            &self.f1
        }
    }

    /// The step size factor after a rejection with error norm `norm`.
    fn shrink(&self, norm: f64) -> f64 {
        if norm.is_finite() {
            (SAFETY * norm.powf(-1.0 / self.tableau.order as f64)).max(MIN_FACTOR)
        } else {
            MIN_FACTOR
        }
    }

    /// The dense output of the accepted step from `(t, y, f)`.
    fn dense(&self, (t, y, f): (f64, &Y, &Y), h: f64) -> Dense<Y> {
        match &self.rows.dense {
            None => Dense::Hermite(Hermite {
                t0: t,
                h,
                end: t + h,
                y0: y.clone(),
                f0: f.clone(),
                y1: self.y1.clone(),
                f1: self.end_derivative().clone(),
            }),
            Some(d) => {
                let (y1, last) = (&self.y1, self.end_derivative());
                let mut difference = y.clone();
                difference.set_combination(y1, &[(-1.0, y)]);
                let mut slope = y.clone();
                slope.set_sum(&[(h, f), (-1.0, &difference)]);
                let mut curvature = y.clone();
                curvature.set_combination(&difference, &[(-h, last), (-1.0, &slope)]);
                let mut correction = y.clone();
                Self::weighted(&self.k, f, d, h, None, &mut correction);
                Dense::DormandPrince(DormandPrince {
                    t0: t,
                    t1: t + h,
                    h,
                    r: [y.clone(), difference, slope, curvature, correction],
                })
            }
        }
    }
}

/// The most stages a tableau may have.
const MAX_STAGES: usize = 16;

/// `Err` unless the tableau's lists fit each other and [`MAX_STAGES`].
fn check<E>(tableau: &Tableau) -> Result<(), SolverError<E>> {
    let s = tableau.stages();
    let rows_fit = tableau.a.iter().enumerate().all(|(i, row)| row.len() <= i);
    let weights = [Some(tableau.b), tableau.error].into_iter().flatten();
    let weights_fit = weights.chain(match tableau.dense {
        DenseOutput::DormandPrince { d } => Some(d),
        DenseOutput::Hermite => None,
    });
    if (1..=MAX_STAGES).contains(&s)
        && tableau.a.len() == s
        && rows_fit
        && weights_fit.into_iter().all(|w| w.len() == s)
    {
        Ok(())
    } else {
        Err(SolverError::InvalidOptions(format!(
            "the tableau of {} does not fit its {s} stages (at most {MAX_STAGES})",
            tableau.name
        )))
    }
}

/// Writes `(h w_j, k_j)` for the weights of `row` into `terms` (`k_0 = f`);
/// returns how many.
#[inline]
fn gather<'a, Y>(
    terms: &mut [(f64, &'a Y); MAX_STAGES],
    row: &[(usize, f64)],
    k: &'a [Y],
    f: &'a Y,
    h: f64,
) -> usize {
    for (slot, &(j, w)) in terms.iter_mut().zip(row) {
        *slot = (h * w, if j == 0 { f } else { &k[j] });
    }
    row.len()
}

impl<Y: OdeVector> ExplicitRk<Y> {
    /// The stages of a step of size `h` from `(t, y, f)` and its end `y1`
    /// (and `f1 = F(t + h, y1)` for a method that is not FSAL). `Ok(false)`
    /// when a stage is not finite and a controlled step can shrink.
    fn stages<P: OdeProblem<Y>>(
        &mut self,
        problem: &mut P,
        (t, y, f): (f64, &Y, &Y),
        h: f64,
        stats: &mut Stats,
    ) -> Result<bool, SolverError<P::Error>> {
        let tableau = self.tableau;
        for i in 1..tableau.stages() {
            let stage = self.stage(problem, (t, y, f), (i, h), stats);
            if let Err(SolverError::NonFinite { .. }) = stage
                && self.fixed.is_none()
                && h * MIN_FACTOR >= self.options.min_step
            {
                return Ok(false);
            }
            stage?;
        }
        if !tableau.fsal {
            Self::weighted(&self.k, f, &self.rows.solution, h, Some(y), &mut self.y1);
            evaluate(problem, t + h, &self.y1, &mut self.f1, stats)?;
        }
        Ok(true)
    }
}

impl<Y: OdeVector, P: OdeProblem<Y>> Stepper<Y, P> for ExplicitRk<Y> {
    type Dense = Dense<Y>;

    fn attempt(
        &mut self,
        problem: &mut P,
        (t, y, f): (f64, &Y, &Y),
        h: f64,
        stats: &mut Stats,
    ) -> Result<Attempt<Dense<Y>>, SolverError<P::Error>> {
        // Controlled steps see the problem's smooth stand-ins for kinks in
        // time inside the step (`OdeProblem::step_window`).
        let controlled = self.fixed.is_none();
        if controlled {
            problem.step_window(Some((t, h)));
        }
        let stages = self.stages(problem, (t, y, f), h, stats);
        if controlled {
            problem.step_window(None);
        }
        if !stages? {
            // A step so long that its stages leave the region where F is
            // finite (a stiff internal state that grows without bound once
            // the method is unstable): rejected, like an error estimate
            // that is NaN.
            self.rejected_last = true;
            return Ok(Attempt::Rejected(h * MIN_FACTOR));
        }
        let norm = match (self.fixed, &self.rows.error) {
            (None, Some(e)) => {
                Self::weighted(&self.k, f, e, h, None, &mut self.err);
                error_norm(&self.err, y, &self.y1, &self.options)
            }
            _ => 0.0,
        };
        if norm.is_nan() || norm > 1.0 {
            // Rejected (NaN counts as a failure too): shrink and retry.
            self.rejected_last = true;
            return Ok(Attempt::Rejected(h * self.shrink(norm)));
        }
        self.norm = norm;
        Ok(Attempt::Accepted(self.dense((t, y, f), h)))
    }

    fn end(&self) -> &Y {
        &self.y1
    }

    fn advance(&mut self, y: &mut Y, f: &mut Y, h: f64) -> f64 {
        std::mem::swap(y, &mut self.y1);
        let last = self.tableau.stages() - 1;
        std::mem::swap(
            f,
            if self.tableau.fsal {
                &mut self.k[last]
            } else {
                &mut self.f1
            },
        );
        let next = match self.fixed {
            Some(fixed) => fixed,
            None => {
                let alpha = 1.0 / self.tableau.order as f64 - 0.75 * BETA;
                let mut factor =
                    SAFETY * self.norm.max(1e-10).powf(-alpha) * self.previous_error.powf(BETA);
                factor = factor.clamp(MIN_FACTOR, MAX_FACTOR);
                if self.rejected_last {
                    factor = factor.min(1.0);
                }
                self.previous_error = self.norm.max(1e-4);
                (h * factor).min(self.options.max_step)
            }
        };
        self.rejected_last = false;
        next
    }

    fn restart(&mut self, h: f64) -> f64 {
        self.rejected_last = false;
        self.fixed.unwrap_or(h)
    }
}

/// The dense output of an explicit method's step.
pub enum Dense<Y> {
    /// Cubic Hermite.
    Hermite(Hermite<Y>),
    /// Dormand–Prince's 4th-order extension.
    DormandPrince(DormandPrince<Y>),
}

impl<Y: OdeVector> DenseStep<Y> for Dense<Y> {
    fn t0(&self) -> f64 {
        match self {
            Dense::Hermite(d) => d.t0(),
            Dense::DormandPrince(d) => d.t0,
        }
    }

    fn t1(&self) -> f64 {
        match self {
            Dense::Hermite(d) => d.t1(),
            Dense::DormandPrince(d) => d.t1,
        }
    }

    fn eval(&self, t: f64, out: &mut Y) {
        self.eval_part(t, Part::All, out);
    }

    fn uncut_end(&self) -> f64 {
        match self {
            Dense::Hermite(d) => d.uncut_end(),
            Dense::DormandPrince(d) => d.t0 + d.h,
        }
    }

    fn eval_derivative(&self, t: f64, out: &mut Y) -> bool {
        self.eval_derivative_part(t, Part::All, out)
    }

    fn eval_part(&self, t: f64, part: Part, out: &mut Y) {
        match self {
            Dense::Hermite(d) => d.eval_part(t, part, out),
            Dense::DormandPrince(d) => d.eval(t, part, out),
        }
    }

    fn eval_derivative_part(&self, t: f64, part: Part, out: &mut Y) -> bool {
        match self {
            Dense::Hermite(d) => d.eval_derivative_part(t, part, out),
            Dense::DormandPrince(d) => {
                d.eval_derivative(t, part, out);
                true
            }
        }
    }
}

impl<Y> Truncate for Dense<Y> {
    fn truncate(self, end: f64) -> Self {
        match self {
            Dense::Hermite(d) => Dense::Hermite(d.truncate(end)),
            Dense::DormandPrince(d) => Dense::DormandPrince(DormandPrince { t1: end, ..d }),
        }
    }
}

/// Dormand–Prince's continuous extension of one step:
/// `y(t0 + θh) = r0 + θ(r1 + (1−θ)(r2 + θ(r3 + (1−θ) r4)))`.
pub struct DormandPrince<Y> {
    t0: f64,
    t1: f64,
    h: f64,
    r: [Y; 5],
}

impl<Y: OdeVector> DormandPrince<Y> {
    /// The components of `part` at `t`, into `out`.
    fn eval(&self, t: f64, part: Part, out: &mut Y) {
        let theta = (t - self.t0) / self.h;
        let theta1 = 1.0 - theta;
        let [r0, r1, r2, r3, r4] = &self.r;
        out.set_part_combination(
            part,
            r0,
            &[
                (theta, r1),
                (theta * theta1, r2),
                (theta * theta * theta1, r3),
                (theta * theta * theta1 * theta1, r4),
            ],
        );
    }

    /// `dy/dt = (r1 + (1−2θ) r2 + θ(2−3θ) r3 + 2θ(1−θ)(1−2θ) r4) / h`,
    /// the derivative of [`DormandPrince::eval`]'s polynomial (the
    /// components of `part`).
    fn eval_derivative(&self, t: f64, part: Part, out: &mut Y) {
        let theta = (t - self.t0) / self.h;
        let (theta1, middle) = (1.0 - theta, 1.0 - 2.0 * theta);
        let [_, r1, r2, r3, r4] = &self.r;
        let per_h = 1.0 / self.h;
        out.set_part_sum(
            part,
            &[
                (per_h, r1),
                (middle * per_h, r2),
                (theta * (2.0 - 3.0 * theta) * per_h, r3),
                (2.0 * theta * theta1 * middle * per_h, r4),
            ],
        );
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::tableau::{DOPRI5, RK4};
    use nalgebra::SVector;

    /// `x'' = −x` as `y = (x, x')`: from `(1, 0)`, `x = cos t`.
    struct Oscillator;

    impl OdeProblem<SVector<f64, 2>> for Oscillator {
        type Error = std::convert::Infallible;

        fn rhs(
            &mut self,
            _t: f64,
            y: &SVector<f64, 2>,
            dy: &mut SVector<f64, 2>,
        ) -> Result<(), Self::Error> {
            *dy = SVector::from([y[1], -y[0]]);
            Ok(())
        }
    }

    /// The largest distance, over the steps of `tableau` through 0–10 s,
    /// of the derivative of the dense output from `(−sin t, −cos t)`, at
    /// seven points inside each step; checks that each step's ends give
    /// `F` there, when the method offers the derivative.
    fn derivative_error(tableau: &'static Tableau, options: &Options) -> Option<f64> {
        let (mut worst, mut offered) = (0.0f64, true);
        let y0 = SVector::from([1.0, 0.0]);
        let mut check = |problem: &mut Oscillator, step: &dyn DenseStep<SVector<f64, 2>>| {
            let (mut rate, mut y, mut f) = (SVector::zeros(), SVector::zeros(), SVector::zeros());
            for t in [step.t0(), step.t1()] {
                offered &= step.eval_derivative(t, &mut rate);
                step.eval(t, &mut y);
                problem.rhs(t, &y, &mut f).unwrap();
                assert!(
                    !offered || (rate - f).norm() < 1e-12,
                    "t = {t}: {rate} vs {f}"
                );
            }
            for k in 1..8 {
                let t = step.t0() + k as f64 / 8.0 * (step.t1() - step.t0());
                step.eval_derivative(t, &mut rate);
                let exact = SVector::from([-t.sin(), -t.cos()]);
                worst = worst.max((rate - exact).norm());
            }
        };
        integrate(tableau, &mut Oscillator, 0.0, y0, 10.0, options, &mut check).unwrap();
        offered.then_some(worst)
    }

    #[test]
    fn dormand_prince_gives_the_derivative_of_its_dense_output() {
        let options = Options {
            rtol: 1e-8,
            atol: 1e-10,
            ..Options::default()
        };
        let error = derivative_error(&DOPRI5, &options).unwrap();
        assert!(error < 1e-7, "{error}");
        // Ten times the tolerance, ten times the error, about.
        let loose = Options {
            rtol: 1e-7,
            atol: 1e-9,
            ..options
        };
        let error_loose = derivative_error(&DOPRI5, &loose).unwrap();
        assert!(error_loose > 3.0 * error, "{error_loose} vs {error}");
        // The cubic Hermite of RK4 declines.
        let fixed = Options {
            fixed_step: Some(0.01),
            ..options
        };
        assert_eq!(derivative_error(&RK4, &fixed), None);
    }

    #[test]
    fn a_tableau_that_does_not_fit_its_stages_is_refused() {
        assert_eq!(check::<()>(&DOPRI5), Ok(()));
        assert_eq!(check::<()>(&RK4), Ok(()));
        // Row 1 reaches stage 1 itself: not explicit.
        let implicit_row = Tableau {
            name: "bad",
            a: &[&[], &[0.5, 0.5]],
            c: &[0.0, 1.0],
            b: &[0.5, 0.5],
            ..RK4
        };
        assert_eq!(
            check::<()>(&implicit_row),
            Err(SolverError::InvalidOptions(
                "the tableau of bad does not fit its 2 stages (at most 16)".to_string()
            ))
        );
        let short_weights = Tableau { b: &[1.0], ..RK4 };
        assert!(check::<()>(&short_weights).is_err());
    }
}
