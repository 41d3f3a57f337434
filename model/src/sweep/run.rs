//! Running the runs of a plan in parallel: each run is the base scenario with
//! the plan's values applied as settings, simulated to its summary metrics.

use super::plan::{Assignment, Axis, Plan};
use crate::LagrangianSystem;
use crate::scenario::{ModelNames, Scenario};
use crate::simulate::{Summary, simulate_summary};
use rayon::prelude::*;
use std::ops::Range;
use std::path::PathBuf;
use std::sync::Mutex;

/// The scenario every run starts from.
#[derive(Clone, Debug)]
pub struct BaseScenario {
    /// The scenario file's text (empty for the defaults).
    pub text: String,
    /// The file, which relative paths in it start from.
    pub file: Option<PathBuf>,
    pub names: ModelNames,
    /// `--set` settings applied to every run before the plan's values.
    pub settings: Vec<String>,
}

/// The result of one run.
#[derive(Clone, Debug, PartialEq)]
pub struct Row {
    /// The run's index in the whole sweep (not the shard).
    pub run: usize,
    /// The plan's values for the run, one per axis.
    pub values: Vec<f64>,
    /// The metrics, or why the run failed.
    pub outcome: Result<Summary, String>,
}

/// The base value a factor multiplies: a number or a list of numbers.
#[derive(Clone, Debug)]
enum Scaled {
    Number(f64),
    List(Vec<f64>),
}

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
    ) -> Result<Settings, String> {
        let document: toml::Table = base
            .text
            .parse()
            .map_err(|e: toml::de::Error| format!("scenario: {e}"))?;
        let mut axes = Vec::new();
        for axis in plan.axes() {
            let overridden = base.settings.iter().any(|s| {
                s.split_once('=')
                    .is_some_and(|(k, _)| k.trim().trim_end_matches('*').trim() == axis.key)
            });
            if overridden {
                return Err(format!(
                    "`{}` is both swept and fixed by --set; drop one",
                    axis.key
                ));
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

    /// The settings that give the axes `values`.
    pub fn for_values(&self, values: &[f64]) -> Vec<String> {
        self.axes
            .iter()
            .zip(values)
            .map(|((axis, scaled), &x)| {
                let value = match scaled {
                    None => toml_number(x),
                    Some(Scaled::Number(b)) => toml_number(b * x),
                    Some(Scaled::List(list)) => {
                        let items: Vec<String> = list.iter().map(|b| toml_number(b * x)).collect();
                        format!("[{}]", items.join(", "))
                    }
                };
                format!("{}={value}", axis.key)
            })
            .collect()
    }
}

/// A number as TOML reads it back exactly: a whole number as an integer
/// (so that integer entries such as `simulation.max_steps` can be swept;
/// float entries accept integers), else the shortest round-tripping float.
fn toml_number(x: f64) -> String {
    if x.fract() == 0.0 && x.abs() < 1e15 {
        format!("{}", x as i64)
    } else {
        format!("{x:?}")
    }
}

fn scaled_base(
    axis: &Axis,
    document: &toml::Table,
    names: &ModelNames,
    parameter_defaults: &[f64],
) -> Result<Scaled, String> {
    let path: Vec<&str> = if axis.key.contains('.') {
        axis.key.split('.').collect()
    } else if let Some(k) = names.parameters.iter().position(|p| *p == axis.key) {
        let in_file = document
            .get("parameters")
            .and_then(|t| t.get(&axis.key))
            .and_then(as_number);
        return Ok(Scaled::Number(in_file.unwrap_or(parameter_defaults[k])));
    } else {
        return Err(format!(
            "`{0}*=`: a factor applies to a parameter or a dotted scenario entry, and `{0}` is no parameter",
            axis.key
        ));
    };
    let mut value: Option<&toml::Value> = None;
    let mut table = Some(document);
    for part in &path {
        value = table.and_then(|t| t.get(*part));
        table = value.and_then(toml::Value::as_table);
    }
    let missing = || format!("`{}*=`: the scenario has no such entry to scale", axis.key);
    match value.ok_or_else(missing)? {
        toml::Value::Array(items) => items
            .iter()
            .map(as_number)
            .collect::<Option<Vec<f64>>>()
            .map(Scaled::List)
            .ok_or_else(|| {
                format!(
                    "`{}*=`: a factor scales a number or a list of numbers, and this list holds something else",
                    axis.key
                )
            }),
        other => as_number(other).map(Scaled::Number).ok_or_else(|| {
            format!(
                "`{}*=`: a factor scales a number or a list of numbers, not `{other}`",
                axis.key
            )
        }),
    }
}

fn as_number(value: &toml::Value) -> Option<f64> {
    match value {
        toml::Value::Float(x) => Some(*x),
        toml::Value::Integer(i) => Some(*i as f64),
        _ => None,
    }
}

/// The scenario of one run.
pub fn run_scenario(
    base: &BaseScenario,
    settings: &Settings,
    values: &[f64],
) -> Result<Scenario, String> {
    let mut all = base.settings.clone();
    all.extend(settings.for_values(values));
    Scenario::parse(&base.text, base.file.as_deref(), &base.names, &all).map_err(|e| e.to_string())
}

/// Runs `runs` of `plan` on `threads` worker threads (0: one per core),
/// calling `progress` after each run. Rows come back in run order.
pub fn run_sweep<const N: usize, S>(
    system: &S,
    base: &BaseScenario,
    plan: &Plan,
    settings: &Settings,
    runs: Range<usize>,
    threads: usize,
    progress: &(dyn Fn() + Sync),
) -> Result<Vec<Row>, String>
where
    S: LagrangianSystem<N> + Clone + Send,
{
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .map_err(|e| format!("cannot start {threads} worker threads: {e}"))?;
    // Each worker simulates its own copy of the model (models keep scratch space).
    let prototype = Mutex::new(system.clone());
    let copy = || prototype.lock().unwrap_or_else(|e| e.into_inner()).clone();
    let rows = pool.install(|| {
        runs.into_par_iter()
            .map_init(copy, |model, run| {
                let values = plan.point(run);
                let outcome = run_scenario(base, settings, &values).and_then(|scenario| {
                    simulate_summary(model, &scenario).map_err(|e| e.to_string())
                });
                progress();
                Row {
                    run,
                    values,
                    outcome,
                }
            })
            .collect()
    });
    Ok(rows)
}
