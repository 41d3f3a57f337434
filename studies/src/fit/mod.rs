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
//!
//! Each channel is also rated by ISO/TS 18571 against the target, with the
//! scenario's own values and with the fitted ones ([`rating`]), as `lpm
//! compare` rates a run against a test.

pub mod parameters;
mod problem;
pub mod rating;
mod statistics;

use lagrangian_runtime::LagrangianSystem;
use lagrangian_sim::pulse::channels::{Quantity, TimeHistories};
use lagrangian_sim::pulse::interpolate;
use lagrangian_sim::scenario::{BaseScenario, Override, ScenarioError};
use lagrangian_sim::simulate::{SimulationError, simulate};
pub use parameters::{ParameterError, Parameters};
use problem::Problem;
pub use rating::ChannelRating;
use serde::Serialize;
use statistics::Determined;
pub use statistics::{NEGLIGIBLE_INFLUENCE, RANK_TOLERANCE};

/// Why a fit cannot be made, or failed: what of the target, the scenario
/// or the simulations is wrong.
#[derive(Debug, thiserror::Error)]
pub enum FitError {
    /// The scenario with the fit's settings does not resolve.
    #[error("{0}")]
    Scenario(Box<ScenarioError>),
    /// The scenario names no crush coordinate, which the target is
    /// compared with.
    #[error(
        "the scenario names no crush coordinate (`[metrics] crush = \"-r\"`): the target channels are its pulse"
    )]
    NoCrush,
    /// A simulation failed.
    #[error("{0}")]
    Simulation(Box<SimulationError>),
    /// A simulation to the target's end with fewer than two samples.
    #[error(
        "the simulation to the target's end (t = {end} s) has {samples} sample: the target is shorter than an output interval"
    )]
    ShortSimulation {
        /// The target's last time \[s\].
        end: f64,
        /// The samples of the simulation.
        samples: usize,
    },
    /// A target of fewer than two times.
    #[error("the target has {samples} sample{}; a fit needs at least 2 times", plural(.samples))]
    TooFewTimes {
        /// The target's times.
        samples: usize,
    },
    /// A target that ends within the scenario's first output interval.
    #[error(
        "the target ends at t = {end} s, within the scenario's first output interval ({interval} s): a fit needs target times after t = {interval} s (or a shorter simulation.output_interval)"
    )]
    WithinFirstInterval {
        /// The target's last time \[s\].
        end: f64,
        /// The scenario's output interval \[s\].
        interval: f64,
    },
    /// A target of no more values than fitted entries.
    #[error(
        "the target has {values} values ({samples} times × {channels} channels) for {entries} fitted entries: a fit needs more values than entries (a finer target or fewer entries)"
    )]
    TooFewValues {
        /// The target's values.
        values: usize,
        /// Its times.
        samples: usize,
        /// Its channels.
        channels: usize,
        /// The fitted entries.
        entries: usize,
    },
    /// A target that starts before 0.
    #[error("the target starts at t = {t} s; the simulation starts at 0 (first contact)")]
    StartsBeforeZero {
        /// The target's first time \[s\].
        t: f64,
    },
    /// A target channel that is zero throughout.
    #[error("target column `{header}` is zero throughout")]
    ZeroChannel {
        /// The channel's column header.
        header: String,
    },
    /// The scenario's own values do not simulate to the target.
    #[error("the scenario's own values do not simulate: {0}")]
    StartFails(#[source] Box<FitError>),
    /// No fitted entry changes the simulated target.
    #[error("none of the parameters changes the simulated target")]
    NoInfluence,
    /// A simulated target with infinite or NaN values.
    #[error("the simulated target is not finite")]
    NotFinite,
    /// The optimizer ran no start.
    #[error("no start")]
    NoStart,
}

/// `s` unless `n` is 1.
fn plural(n: &usize) -> &'static str {
    if *n == 1 { "" } else { "s" }
}

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
    /// `true` when the target determines it at the optimum (its standard
    /// error is then given); see `identifiability` for why not.
    pub identifiable: bool,
    /// How the target determines it, at the optimum.
    pub identifiability: Identifiability,
    /// The norm of its column of the Jacobian at the optimum over the
    /// largest column's (`None` when it was held).
    pub relative_influence: Option<f64>,
}

/// How the target determines a fitted entry.
#[derive(Clone, Debug, PartialEq, Serialize)]
#[serde(rename_all = "snake_case", tag = "kind")]
pub enum Identifiability {
    /// It has an influence at the optimum, and a finite standard error.
    Identifiable,
    /// Changing it did not change the simulated target at the start (e.g.
    /// a stiffness beyond the largest crush): it was held at its value.
    Held,
    /// It changed the target at the start but has no influence at the
    /// optimum (its column of the Jacobian there is zero or negligible,
    /// [`NEGLIGIBLE_INFLUENCE`] of the largest): not identifiable.
    NoInfluenceAtOptimum,
    /// Only a combination of it with the entries `with` is determined (the
    /// Jacobian at the optimum has a direction the target does not see).
    Combination {
        /// The names of the entries it is combined with.
        with: Vec<String>,
    },
}

impl Identifiability {
    /// Why an entry has no standard error, in words (`None` when it has).
    pub fn reason(&self) -> Option<String> {
        match self {
            Identifiability::Identifiable => None,
            Identifiability::Held => Some("held: no influence on the target".into()),
            Identifiability::NoInfluenceAtOptimum => {
                Some("unidentifiable: no influence on the target at the optimum".into())
            }
            Identifiability::Combination { with } => Some(format!(
                "not determined: only its combination with {} is",
                with.join(", ")
            )),
        }
    }
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
    /// The ISO/TS 18571 rating of the simulated channel against the
    /// target's, with the scenario's own values.
    pub rating_initial: ChannelRating,
    /// The same with the fitted values.
    pub rating: ChannelRating,
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

/// The simulated target channels at the simulation's output times.
#[derive(Clone, Debug, PartialEq)]
pub struct SimulatedChannels {
    /// The output times \[s\], from 0 to the target's last time.
    pub t: Vec<f64>,
    /// One per target channel, in its order: the simulated quantity at
    /// `t`, in SI units.
    pub channels: Vec<Vec<f64>>,
}

impl SimulatedChannels {
    /// The channels interpolated linearly to `times` (within `t`).
    pub fn at(&self, times: &[f64]) -> Vec<Vec<f64>> {
        (self.channels.iter())
            .map(|values| interpolate(&self.t, values, times))
            .collect()
    }
}

/// The simulated target channels at the target times, for `settings`.
pub fn simulated_channels<const N: usize, S: LagrangianSystem<N> + Clone>(
    system: &S,
    base: &BaseScenario,
    settings: &[Override],
    target: &TimeHistories,
) -> Result<Vec<Vec<f64>>, FitError> {
    Ok(simulate_channels(system, base, settings, target)?.at(&target.t))
}

/// The simulated target channels for `settings`, at the simulation's own
/// output times up to the target's last time.
pub fn simulate_channels<const N: usize, S: LagrangianSystem<N> + Clone>(
    system: &S,
    base: &BaseScenario,
    settings: &[Override],
    target: &TimeHistories,
) -> Result<SimulatedChannels, FitError> {
    let mut all = settings.to_vec();
    all.push(Override::number(
        "simulation.t_end",
        target.t[target.t.len() - 1],
    ));
    let scenario = base
        .resolve(&all)
        .map_err(|e| FitError::Scenario(Box::new(e)))?;
    let crush = scenario.crush.clone().ok_or(FitError::NoCrush)?;
    let result = simulate(system, &scenario).map_err(|e| FitError::Simulation(Box::new(e)))?;
    let t: Vec<f64> = result.samples.iter().map(|s| s.t).collect();
    if t.len() < 2 {
        return Err(FitError::ShortSimulation {
            end: target.t[target.t.len() - 1],
            samples: t.len(),
        });
    }
    let channels = (target.channels.iter())
        .map(|c| {
            (result.samples.iter())
                .map(|s| {
                    let [value, rate, acceleration] = s.crush_motion(&crush);
                    match c.quantity {
                        Quantity::Acceleration => acceleration,
                        Quantity::Velocity => rate,
                        Quantity::Crush => value,
                    }
                })
                .collect()
        })
        .collect();
    Ok(SimulatedChannels { t, channels })
}

fn rms(x: impl Iterator<Item = f64>) -> f64 {
    let (mut sum, mut n) = (0.0, 0usize);
    for v in x {
        sum += v * v;
        n += 1;
    }
    (sum / n.max(1) as f64).sqrt()
}

/// Checks the target's extent against the scenario and the number of
/// fitted `entries`: at least two times, the last after the scenario's
/// first output interval (a simulation to it has a sample after 0), and
/// more values than entries. A target too short or too coarse is refused
/// before any simulation.
pub fn check_target_extent(
    target: &TimeHistories,
    base: &BaseScenario,
    entries: usize,
) -> Result<(), FitError> {
    let samples = target.t.len();
    if samples < 2 {
        return Err(FitError::TooFewTimes { samples });
    }
    let interval = base
        .resolve(&[])
        .map_err(|e| FitError::Scenario(Box::new(e)))?
        .output_interval;
    let end = target.t[samples - 1];
    if end <= interval {
        return Err(FitError::WithinFirstInterval { end, interval });
    }
    let channels = target.channels.len();
    let values = samples * channels;
    if values <= entries {
        return Err(FitError::TooFewValues {
            values,
            samples,
            channels,
            entries,
        });
    }
    Ok(())
}

/// Checks the target's values: it starts at or after 0, and no channel is
/// zero throughout (each scales its residuals by its RMS).
fn check_target_values(target: &TimeHistories) -> Result<(), FitError> {
    if target.t.first().is_some_and(|&t| t < 0.0) {
        return Err(FitError::StartsBeforeZero { t: target.t[0] });
    }
    for c in &target.channels {
        if rms(c.values.iter().copied()) == 0.0 {
            return Err(FitError::ZeroChannel {
                header: c.header.clone(),
            });
        }
    }
    Ok(())
}

/// The simulated channels of one run: at the target times (what the
/// residuals see) and at the run's own (what the rating sees).
struct Run {
    at_target: Vec<Vec<f64>>,
    own: SimulatedChannels,
}

impl Run {
    fn new(own: SimulatedChannels, target: &TimeHistories) -> Run {
        Run {
            at_target: own.at(&target.t),
            own,
        }
    }

    /// Its channel `k` rated against the target's.
    fn rating(&self, target: &TimeHistories, k: usize) -> ChannelRating {
        let values = &target.channels[k].values;
        ChannelRating::of(&target.t, values, &self.own.t, &self.own.channels[k])
    }
}

/// The fit quality of each target channel, from the runs with the initial
/// and with the fitted values.
fn channel_fits(target: &TimeHistories, initial: &Run, fitted: &Run) -> Vec<ChannelFit> {
    (target.channels.iter().enumerate())
        .map(|(k, c)| {
            let error = |sim: &[f64]| rms(sim.iter().zip(&c.values).map(|(s, y)| s - y));
            let rms_error = error(&fitted.at_target[k]);
            ChannelFit {
                channel: c.header.clone(),
                unit: c.quantity.si_unit().into(),
                rms_error_initial: error(&initial.at_target[k]),
                rms_error,
                relative_rms_error: rms_error / rms(c.values.iter().copied()),
                rating_initial: initial.rating(target, k),
                rating: fitted.rating(target, k),
            }
        })
        .collect()
}

/// What [`statistics::uncertainty`] found of an entry, with names.
fn identifiability(determined: Option<&Determined>, labels: &[String]) -> Identifiability {
    match determined {
        None => Identifiability::Held,
        Some(Determined::Yes) => Identifiability::Identifiable,
        Some(Determined::NoInfluence) => Identifiability::NoInfluenceAtOptimum,
        Some(Determined::Combination(with)) => Identifiability::Combination {
            with: with.iter().map(|&k| labels[k].clone()).collect(),
        },
    }
}

/// Fits `setup.parameters`, calling `progress(simulations, best cost)`.
pub fn fit<const N: usize, S>(
    system: &S,
    setup: &FitSetup,
    progress: &(dyn Fn(usize, f64) + Sync),
) -> Result<FitReport, FitError>
where
    S: LagrangianSystem<N> + Clone + Send,
{
    let clock = std::time::Instant::now();
    check_target_values(&setup.target)?;
    check_target_extent(&setup.target, &setup.base, setup.parameters.entries.len())?;
    let problem = Problem::new(system, setup, progress)?;
    let initial = setup.parameters.base_values();
    let initial_run = Run::new(problem.run_of(&initial)?, &setup.target);
    let outcome = problem.minimize(setup.starts, setup.seed)?;
    let fitted_run = Run::new(problem.run_of(&outcome.values)?, &setup.target);
    let channels = channel_fits(&setup.target, &initial_run, &fitted_run);
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
        .map(|(i, name)| {
            let identifiability = identifiability(stats.determined[i].as_ref(), &labels);
            FittedParameter {
                name: name.clone(),
                initial: initial[i],
                fitted: outcome.values[i],
                standard_error: stats.standard_errors[i],
                identifiable: identifiability == Identifiability::Identifiable
                    && stats.standard_errors[i].is_some(),
                identifiability,
                relative_influence: stats.influence[i],
            }
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
        curves: (initial_run.at_target.into_iter())
            .zip(fitted_run.at_target)
            .collect(),
    })
}
