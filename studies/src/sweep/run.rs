//! Running the runs of a plan in parallel: each run is the base scenario with
//! the plan's values applied as settings, simulated to its summary metrics.

use super::plan::{Assignment, Axis, Plan};
use super::shared::SharedScenario;
use lagrangian_runtime::LagrangianSystem;
use lagrangian_sim::scenario::ScenarioError;
use lagrangian_sim::scenario::{BaseScenario, ModelNames, Override, Scenario};
use lagrangian_sim::scenario::{as_number, factor_base, number_value, scaled_value};
use lagrangian_sim::simulate::{FailureKind, SimulationError, Summary, simulate_summary};
use std::collections::BTreeMap;
use std::ops::Range;
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use std::sync::mpsc;

/// The result of one run.
#[derive(Clone, Debug, PartialEq)]
pub struct Row {
    /// The run's index in the whole sweep (not the shard).
    pub run: usize,
    /// The plan's values for the run, one per axis.
    pub values: Vec<f64>,
    /// The metrics, or why the run failed.
    pub outcome: Result<Summary, RunFailure>,
}

/// Why a run failed: the kind (the table's `status` column writes its
/// [`FailureKind::name`]) and the one-line message.
#[derive(Clone, Debug, PartialEq)]
pub struct RunFailure {
    /// The kind: a simulation's failure, or [`FailureKind::Scenario`] /
    /// [`FailureKind::DataFile`] for values the scenario rejects.
    pub kind: FailureKind,
    /// What went wrong, on one line, as `lpm simulate` would print it.
    pub message: String,
}

/// Why a plan's axes do not fit the base scenario ([`Settings::new`]).
#[derive(Debug, thiserror::Error)]
pub enum SettingsError {
    /// The scenario's text is not TOML.
    #[error("scenario: {0}")]
    Scenario(#[source] toml::de::Error),
    /// A key both swept and set by `--set`.
    #[error("`{key}` is both swept and fixed by --set; drop one")]
    SweptAndSet {
        /// The key.
        key: String,
    },
    /// A factor (`KEY*=`) of an entry it cannot scale.
    #[error("{message}")]
    Factor {
        /// The axis' key.
        key: String,
        /// Why, as the scenario says it.
        message: String,
    },
}

/// The base value a factor multiplies: a number, or a list or table whose
/// every number it multiplies (`initial.velocities*=…` scales the speed of
/// every coordinate the table names).
#[derive(Clone, Debug)]
struct Scaled(toml::Value);

/// The plan's axes, resolved against the base scenario: turns run values
/// into `key=value` settings.
#[derive(Clone, Debug)]
pub struct Settings {
    axes: Vec<(Axis, Option<Scaled>)>,
}

impl Settings {
    /// Checks the axes against the scenario and the model, reading the base
    /// value of each factor (`KEY*=`): the scenario file's entry, or for a
    /// parameter the file's `[parameters]` value or else the spec default.
    pub fn new(
        plan: &Plan,
        base: &BaseScenario,
        parameter_defaults: &[f64],
    ) -> Result<Settings, SettingsError> {
        let document: toml::Table = base.text.parse().map_err(SettingsError::Scenario)?;
        let mut axes = Vec::new();
        for axis in plan.axes() {
            let overridden = base.settings.iter().any(|s| s.key == axis.key);
            if overridden {
                return Err(SettingsError::SweptAndSet {
                    key: axis.key.clone(),
                });
            }
            let scaled = match axis.assignment {
                Assignment::Set => None,
                Assignment::Scale => Some(scaled_base(
                    axis,
                    &document,
                    &base.names,
                    parameter_defaults,
                )?),
            };
            axes.push((axis.clone(), scaled));
        }
        Ok(Settings { axes })
    }

    /// Per axis: the index among `parameters` of the model parameter it
    /// sets and, for a factor, the value it multiplies; `None` when an axis
    /// sets anything else.
    pub(crate) fn parameter_axes(
        &self,
        parameters: &[String],
    ) -> Option<Vec<(usize, Option<f64>)>> {
        let axis = |(axis, scaled): &(Axis, Option<Scaled>)| {
            let index = parameters.iter().position(|p| *p == axis.key)?;
            match scaled {
                None => Some((index, None)),
                Some(Scaled(base)) => Some((index, Some(as_number(base)?))),
            }
        };
        self.axes.iter().map(axis).collect()
    }

    /// The settings that give the axes `values`.
    pub fn for_values(&self, values: &[f64]) -> Vec<Override> {
        self.axes
            .iter()
            .zip(values)
            .map(|((axis, scaled), &x)| {
                let value = match scaled {
                    None => number_value(x),
                    Some(Scaled(base)) => scaled_value(base, x),
                };
                Override::value(&axis.key, value)
            })
            .collect()
    }
}

fn scaled_base(
    axis: &Axis,
    document: &toml::Table,
    names: &ModelNames,
    parameter_defaults: &[f64],
) -> Result<Scaled, SettingsError> {
    (factor_base(&axis.key, document, names, parameter_defaults).map(Scaled)).map_err(|e| {
        SettingsError::Factor {
            key: axis.key.clone(),
            message: e.to_string(),
        }
    })
}

/// The scenario of one run.
pub fn run_scenario(
    base: &BaseScenario,
    settings: &Settings,
    values: &[f64],
) -> Result<Scenario, ScenarioError> {
    base.resolve(&settings.for_values(values))
}

/// The runs of a sweep and how to make them: what [`stream_sweep`] and
/// [`run_sweep`] are given besides the model.
#[derive(Clone, Debug)]
pub struct SweepJob<'a> {
    /// The scenario every run starts from, with the settings common to all.
    pub base: &'a BaseScenario,
    /// The runs' values.
    pub plan: &'a Plan,
    /// The plan's axes resolved against `base`, from [`Settings::new`].
    pub settings: &'a Settings,
    /// Which runs of the plan to make (a shard's block, or what a resumed
    /// sweep still lacks); within `0..plan.len()`.
    pub runs: Range<usize>,
    /// Worker threads; 0 for one per core.
    pub threads: usize,
}

/// One run: its scenario (from the `shared` one when there is one),
/// simulated to its summary.
fn one_run<const N: usize, S: LagrangianSystem<N> + Clone>(
    model: &S,
    job: &SweepJob<'_>,
    shared: Option<&SharedScenario>,
    run: usize,
) -> Row {
    let values = job.plan.point(run);
    let outcome = scenario_of(job, shared, &values).and_then(|scenario| {
        simulate_summary(model, &scenario).map_err(|e| simulation_failure(&e))
    });
    Row {
        run,
        values,
        outcome,
    }
}

/// The scenario of the run with `values` (from the `shared` one when there
/// is one), or why the scenario rejects them.
pub(crate) fn scenario_of(
    job: &SweepJob<'_>,
    shared: Option<&SharedScenario>,
    values: &[f64],
) -> Result<Scenario, RunFailure> {
    let scenario = match shared.and_then(|s| s.for_values(values)) {
        Some(scenario) => Ok(scenario),
        None => run_scenario(job.base, job.settings, values),
    };
    scenario.map_err(|e| RunFailure {
        // A run's scenario is the base's text with settings, never read from
        // a file here: nothing for `Unreadable` to be but the scenario's.
        kind: e.kind.failure().unwrap_or(FailureKind::Scenario),
        message: e.to_string(),
    })
}

/// The row's failure for a run that did not finish.
pub(crate) fn simulation_failure(e: &SimulationError) -> RunFailure {
    RunFailure {
        kind: e.kind(),
        message: e.to_string(),
    }
}

/// How many runs may finish ahead of the earliest unfinished one, per
/// worker: bounds the rows held back to keep the output in run order.
const AHEAD_PER_WORKER: usize = 256;

/// A worker hands its finished runs over together, this many at most
/// (less than [`AHEAD_PER_WORKER`]): each hand-over wakes the thread that
/// writes the rows, a system call that cost a few percent of a run of the
/// paper's scenario when made for every run.
const BATCH_RUNS: usize = 16;

/// ... or as soon as the first run of the batch is this old, so that slow
/// runs still reach the output (and the journal) one by one.
const BATCH_AGE: std::time::Duration = std::time::Duration::from_millis(20);

/// The finished runs a worker has not handed over yet.
struct Batch<T> {
    runs: Vec<(usize, T)>,
    /// When the first of `runs` finished.
    since: std::time::Instant,
}

impl<T> Batch<T> {
    fn new() -> Batch<T> {
        Batch {
            runs: Vec::with_capacity(BATCH_RUNS),
            since: std::time::Instant::now(),
        }
    }

    /// Adds a finished run; `true` when the batch is due.
    fn push(&mut self, run: usize, made: T) -> bool {
        if self.runs.is_empty() {
            self.since = std::time::Instant::now();
        }
        self.runs.push((run, made));
        self.runs.len() >= BATCH_RUNS || self.since.elapsed() >= BATCH_AGE
    }

    /// Hands the runs over, if any; `false` when the receiver is gone.
    fn send(&mut self, sender: &mpsc::SyncSender<Vec<(usize, T)>>) -> bool {
        if self.runs.is_empty() {
            return true;
        }
        let runs = std::mem::replace(&mut self.runs, Vec::with_capacity(BATCH_RUNS));
        sender.send(runs).is_ok()
    }
}

/// Makes the runs `job.runs` on `job.threads` worker threads and hands
/// every row to `sink` in run order, as soon as the rows before it are
/// done: memory stays bounded whatever the number of runs.
///
/// Workers take runs in order, asking `stop` before each; once it says
/// yes they take no new run, and the runs under way finish and reach
/// `sink`, so the rows delivered are always the runs `runs.start..runs.start + n`. Returns `n`. A failing
/// run is a row with its error, not the end of the sweep; an error of
/// `sink` ends it, and is what it returns.
pub fn stream_sweep<const N: usize, S, E>(
    system: &S,
    job: SweepJob<'_>,
    stop: &(dyn Fn() -> bool + Sync),
    sink: &mut dyn FnMut(Row) -> Result<(), E>,
) -> Result<usize, E>
where
    S: LagrangianSystem<N> + Clone + Send,
{
    stream_runs(system, job, stop, &one_run, sink)
}

/// What a worker makes of run `run`: [`one_run`]'s row, or more.
pub(crate) type MakeRun<'f, S, T> =
    &'f (dyn Fn(&S, &SweepJob<'_>, Option<&SharedScenario>, usize) -> T + Sync);

/// [`stream_sweep`] with what each run makes given by `make`: its results
/// reach `sink` in run order.
pub(crate) fn stream_runs<const N: usize, S, T: Send, E>(
    system: &S,
    job: SweepJob<'_>,
    stop: &(dyn Fn() -> bool + Sync),
    make: MakeRun<'_, S, T>,
    sink: &mut dyn FnMut(T) -> Result<(), E>,
) -> Result<usize, E>
where
    S: LagrangianSystem<N> + Clone + Send,
{
    let runs = job.runs.clone();
    let workers = if job.threads == 0 {
        std::thread::available_parallelism().map_or(1, |n| n.get())
    } else {
        job.threads
    };
    let next = AtomicUsize::new(runs.start);
    let delivered = AtomicUsize::new(runs.start);
    let failed_sink = AtomicBool::new(false);
    let window = AHEAD_PER_WORKER * workers;
    let (sender, receiver) = mpsc::sync_channel::<Vec<(usize, T)>>(window);
    let shared = SharedScenario::new(job.base, job.settings);
    let mut outcome = Ok(0);
    std::thread::scope(|scope| {
        for _ in 0..workers {
            let sender = sender.clone();
            let (next, delivered, failed_sink, job) = (&next, &delivered, &failed_sink, &job);
            // Each worker simulates its own copy (models keep scratch space,
            // a scenario's components their state).
            let model = system.clone();
            let shared = shared.clone();
            scope.spawn(move || {
                let mut batch = Batch::new();
                loop {
                    if stop() || failed_sink.load(Ordering::Relaxed) {
                        break;
                    }
                    let run = next.fetch_add(1, Ordering::Relaxed);
                    if run >= runs.end {
                        break;
                    }
                    if run >= delivered.load(Ordering::Acquire) + window {
                        // The rows awaited may be in this batch.
                        if !batch.send(&sender) {
                            return;
                        }
                        while run >= delivered.load(Ordering::Acquire) + window
                            && !failed_sink.load(Ordering::Relaxed)
                        {
                            std::thread::sleep(std::time::Duration::from_millis(1));
                        }
                    }
                    let made = make(&model, job, shared.as_ref(), run);
                    if batch.push(run, made) && !batch.send(&sender) {
                        return;
                    }
                }
                batch.send(&sender);
            });
        }
        drop(sender);
        // Rows arrive nearly in order; those ahead wait here for the ones
        // before them (at most `window` of them).
        let mut waiting = BTreeMap::new();
        let mut expected = runs.start;
        for (run, made) in receiver.iter().flatten() {
            if failed_sink.load(Ordering::Relaxed) {
                continue;
            }
            waiting.insert(run, made);
            while let Some(row) = waiting.remove(&expected) {
                if let Err(e) = sink(row) {
                    failed_sink.store(true, Ordering::Relaxed);
                    outcome = Err(e);
                    break;
                }
                expected += 1;
                delivered.store(expected, Ordering::Release);
            }
        }
        if outcome.is_ok() {
            outcome = Ok(expected - runs.start);
        }
    });
    outcome
}

/// Makes the runs `job.runs` on `job.threads` worker threads, calling
/// `progress` after each run. Rows come back in run order.
pub fn run_sweep<const N: usize, S>(
    system: &S,
    job: SweepJob<'_>,
    progress: &(dyn Fn() + Sync),
) -> Vec<Row>
where
    S: LagrangianSystem<N> + Clone + Send,
{
    let mut rows = Vec::with_capacity(job.runs.len());
    let streamed = stream_sweep(system, job, &|| false, &mut |row| {
        progress();
        rows.push(row);
        Ok::<(), std::convert::Infallible>(())
    });
    let Ok(_) = streamed;
    rows
}

#[cfg(test)]
mod tests {
    use super::*;

    fn base(text: &str) -> BaseScenario {
        BaseScenario {
            text: text.to_string(),
            file: None,
            names: ModelNames {
                coordinates: vec!["xb".into(), "xe".into()],
                parameters: vec!["m".into(), "k".into()],
                ..ModelNames::default()
            },
            settings: Vec::new(),
            files: std::sync::Arc::new(lagrangian_sim::files::Disk),
        }
    }

    fn settings(text: &str, grid: &[&str]) -> Result<Settings, SettingsError> {
        let grid: Vec<String> = grid.iter().map(|s| s.to_string()).collect();
        Settings::new(&Plan::grid(&grid).unwrap(), &base(text), &[2.0, 100.0])
    }

    #[test]
    fn a_factor_scales_every_number_of_a_table() {
        let text = "[initial]\nvelocities = { xb = 15.5, xe = 15.5 }\n";
        let s = settings(text, &["initial.velocities*=0.5,2"]).unwrap();
        let texts = |values: &[f64]| {
            let overrides = s.for_values(values);
            overrides
                .iter()
                .map(|o| o.text().to_string())
                .collect::<Vec<_>>()
        };
        assert_eq!(texts(&[2.0]), ["initial.velocities={ xb = 31, xe = 31 }"]);
        let scenario = base(text).resolve(&s.for_values(&[0.5])).unwrap();
        assert_eq!(scenario.initial_velocities, [(0, 7.75), (1, 7.75)]);
    }

    #[test]
    fn tied_factors_scale_parameters_from_the_file_or_the_spec_default() {
        let s = settings("[parameters]\nk = 300.0\n", &["m,k*=1:2:2"]).unwrap();
        let texts: Vec<String> = (s.for_values(&[1.5, 1.5]).iter())
            .map(|o| o.text().to_string())
            .collect();
        assert_eq!(texts, ["m=3", "k=450"]);
    }

    #[test]
    fn a_factor_of_something_other_than_numbers_is_an_error() {
        let text = "[metrics]\npitch = [\"xb\"]\n";
        let error = settings(text, &["metrics.pitch*=2"])
            .unwrap_err()
            .to_string();
        assert!(
            error.contains("a factor scales a number, or a list or table of numbers"),
            "{error}"
        );
    }
}
