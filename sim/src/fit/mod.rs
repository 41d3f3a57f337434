//! Parameter identification (paper §2.1): the crush characteristic — or any
//! listed parameters — fitted so that the simulated pulse matches target
//! time histories, by Levenberg–Marquardt (MINPACK's, from the
//! `levenberg-marquardt` crate) with forward-difference Jacobians computed in
//! parallel, bounds by transformation ([`parameters`]), several starts, and
//! the parameters' standard errors and correlations from the final Jacobian.
//!
//! Least squares on `r = (sim(t_i) − y(t_i)) / (rms(y) √n)` over every target
//! channel (acceleration, velocity, crush of the scenario's crush
//! coordinate), so each channel weighs the same whatever its units.

pub mod parameters;
mod problem;
mod statistics;

use crate::pulse::channels::{Quantity, TimeHistories};
use crate::pulse::interpolate;
use crate::scenario::BaseScenario;
use crate::simulate::simulate;
use lagrangian_model::LagrangianSystem;
pub use parameters::Parameters;
use problem::Problem;
use serde::Serialize;

/// What to fit and how.
#[derive(Clone, Debug)]
pub struct FitSetup {
    /// The scenario the fitted values are applied to, with its `--set`
    /// settings; its `[metrics] crush` coordinate is what the target
    /// channels are compared with.
    pub base: BaseScenario,
    /// The measured (or reference) pulse to match: acceleration, velocity
    /// and/or crush against time, in SI units.
    pub target: TimeHistories,
    /// The entries the fit varies, with their base values and transforms.
    pub parameters: Parameters,
    /// Number of starts: the scenario's values, then random perturbations of
    /// them (factors in [1/1.5, 1.5]).
    pub starts: usize,
    /// Seed of the random perturbations of the starts after the first: the
    /// same seed gives the same starts, and so the same fit.
    pub seed: u64,
}

/// One parameter's result.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct FittedParameter {
    /// The entry's name in reports (`front_end.k3`, `k_f`).
    pub name: String,
    /// Its value in the scenario (the first start), in the entry's own units.
    pub initial: f64,
    /// Its value at the best optimum found, in the same units.
    pub fitted: f64,
    /// Standard error from `σ² (JᵀJ)⁻¹` at the optimum (`None` when the
    /// target does not determine it).
    pub standard_error: Option<f64>,
    /// `false`: changing it does not change the simulated target at all
    /// (e.g. a stiffness beyond the largest crush); it was held fixed.
    pub identifiable: bool,
}

/// Fit quality of one target channel.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct ChannelFit {
    /// The channel's column header in the target file.
    pub channel: String,
    /// The SI unit of the channel and of its errors (`m/s^2`, `m/s`, `m`).
    pub unit: String,
    /// RMS of simulated minus target over the target times, with the
    /// scenario's own values, in `unit`.
    pub rms_error_initial: f64,
    /// The same with the fitted values, in `unit`.
    pub rms_error: f64,
    /// `rms_error / rms(target)`.
    pub relative_rms_error: f64,
}

/// One start of the optimizer.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct StartReport {
    /// `½ Σ r²` (dimensionless: residuals are scaled per channel) where the
    /// start ended.
    pub cost: f64,
    /// The simulations this start ran (residuals and Jacobian columns).
    pub simulations: usize,
    /// Why the optimizer stopped, as the `levenberg-marquardt` crate names
    /// it (`Converged { ftol: true, … }`, `LostPatience`, …).
    pub termination: String,
    /// `true` when it stopped on a tolerance rather than a limit or a failure.
    pub converged: bool,
}

/// Everything a fit produced: the parameters with their standard errors,
/// the fit quality per channel, and how the optimizer got there.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct FitReport {
    /// One per fitted entry, in the order of `--fit`.
    pub parameters: Vec<FittedParameter>,
    /// One per target channel, in the order of the target file.
    pub channels: Vec<ChannelFit>,
    /// Pairs of parameters correlated by more than 0.95 in magnitude.
    pub strong_correlations: Vec<(String, String, f64)>,
    /// `½ Σ r²` with the scenario's own values (where the first start
    /// begins); dimensionless, the residuals being scaled per channel.
    pub cost_initial: f64,
    /// `½ Σ r²` at the optimum of the best start.
    pub cost: f64,
    /// One report per start, in the order they ran (the first from the
    /// scenario's values).
    pub starts: Vec<StartReport>,
    /// All simulations of the fit, starts and statistics together.
    pub simulations: usize,
    /// Wall-clock time of the whole fit \[s\].
    pub seconds: f64,
    /// `key=value` settings that give the fitted scenario.
    pub settings: Vec<String>,
    /// Simulated channels at the target times: initial, fitted.
    #[serde(skip)]
    pub curves: Vec<(Vec<f64>, Vec<f64>)>,
}

/// The simulated target channels at the target times, for `settings`.
pub fn simulated_channels<const N: usize, S: LagrangianSystem<N> + Clone>(
    system: &S,
    base: &BaseScenario,
    settings: &[String],
    target: &TimeHistories,
) -> Result<Vec<Vec<f64>>, String> {
    let mut all = settings.to_vec();
    all.push(format!(
        "simulation.t_end={:?}",
        target.t[target.t.len() - 1]
    ));
    let scenario = base.resolve(&all).map_err(|e| e.to_string())?;
    let crush = scenario.crush.clone().ok_or(
        "the scenario names no crush coordinate (`[metrics] crush = \"-r\"`): the target channels are its pulse",
    )?;
    let result = simulate(system, &scenario).map_err(|e| e.to_string())?;
    let t: Vec<f64> = result.samples.iter().map(|s| s.t).collect();
    Ok(target
        .channels
        .iter()
        .map(|c| {
            let values: Vec<f64> = result
                .samples
                .iter()
                .map(|s| match c.quantity {
                    Quantity::Acceleration => crush.of_coordinates(&s.a),
                    Quantity::Velocity => crush.of_coordinates(&s.v),
                    Quantity::Crush => crush.plus_offset(crush.of_coordinates(&s.q)),
                })
                .collect();
            interpolate(&t, &values, &target.t)
        })
        .collect())
}

fn rms(x: impl Iterator<Item = f64>) -> f64 {
    let (mut sum, mut n) = (0.0, 0usize);
    for v in x {
        sum += v * v;
        n += 1;
    }
    (sum / n.max(1) as f64).sqrt()
}

/// Checks the target against the scenario before any fitting.
fn check_target(target: &TimeHistories) -> Result<(), String> {
    if target.t[0] < 0.0 {
        return Err(format!(
            "the target starts at t = {} s; the simulation starts at 0 (first contact)",
            target.t[0]
        ));
    }
    for c in &target.channels {
        if rms(c.values.iter().copied()) == 0.0 {
            return Err(format!("target column `{}` is zero throughout", c.header));
        }
    }
    Ok(())
}

/// The fit quality of each target channel, from the simulated channels
/// with the initial and with the fitted values.
fn channel_fits(
    target: &TimeHistories,
    initial: &[Vec<f64>],
    fitted: &[Vec<f64>],
) -> Vec<ChannelFit> {
    target
        .channels
        .iter()
        .zip(initial.iter().zip(fitted))
        .map(|(c, (a, b))| {
            let error = |sim: &[f64]| rms(sim.iter().zip(&c.values).map(|(s, y)| s - y));
            let fitted = error(b);
            ChannelFit {
                channel: c.header.clone(),
                unit: c.quantity.si_unit().into(),
                rms_error_initial: error(a),
                rms_error: fitted,
                relative_rms_error: fitted / rms(c.values.iter().copied()),
            }
        })
        .collect()
}

/// Fits `setup.parameters`, calling `progress(simulations, best cost)`.
pub fn fit<const N: usize, S>(
    system: &S,
    setup: &FitSetup,
    progress: &(dyn Fn(usize, f64) + Sync),
) -> Result<FitReport, String>
where
    S: LagrangianSystem<N> + Clone + Send,
{
    let clock = std::time::Instant::now();
    check_target(&setup.target)?;
    let problem = Problem::new(system, setup, progress)?;
    let initial = setup.parameters.base_values();
    let initial_channels = problem.channels_of(&initial)?;
    let outcome = problem.minimize(setup.starts, setup.seed)?;
    let fitted_channels = problem.channels_of(&outcome.values)?;
    let channels = channel_fits(&setup.target, &initial_channels, &fitted_channels);
    let stats = statistics::uncertainty(&problem, &outcome)?;
    let labels: Vec<String> = setup
        .parameters
        .entries
        .iter()
        .map(|e| e.label.clone())
        .collect();
    let parameters = labels
        .iter()
        .enumerate()
        .map(|(i, name)| FittedParameter {
            name: name.clone(),
            initial: initial[i],
            fitted: outcome.values[i],
            standard_error: stats.standard_errors[i],
            identifiable: problem.free.contains(&i),
        })
        .collect();
    Ok(FitReport {
        parameters,
        channels,
        strong_correlations: stats
            .strong
            .iter()
            .map(|&(i, j, r)| (labels[i].clone(), labels[j].clone(), r))
            .collect(),
        cost_initial: outcome.cost_initial,
        cost: outcome.cost,
        starts: outcome.starts,
        simulations: problem.simulations(),
        seconds: clock.elapsed().as_secs_f64(),
        settings: setup.parameters.settings(&outcome.values),
        curves: initial_channels.into_iter().zip(fitted_channels).collect(),
    })
}
