//! Which runs a sweep makes: a full-factorial grid or a sampled design, the
//! values of run `i`, and the block of runs of one shard.

use lagrangian_sim::quantity::has_unit;
use lagrangian_sim::scenario::{EntryError, KeyPath};
use rand_chacha::ChaCha8Rng;
use rand_chacha::rand_core::{Rng, SeedableRng};
use std::fmt;
use std::ops::Range;

/// Why the axes of a sweep do not make a plan: the flag (`--grid`,
/// `--vary`), the axis and the text at fault.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum PlanError {
    /// Neither a grid nor a sampled design.
    #[error("give --grid KEY=VALUES or --samples N with --vary KEY=LOW:HIGH")]
    NoDesign,
    /// A grid and a sampled design at once.
    #[error("--grid cannot be combined with --samples/--vary")]
    GridAndSamples,
    /// An axis without `=`.
    #[error("{flag} `{text}` is not of the form KEY=VALUES or KEY*=VALUES")]
    NotAnAssignment {
        /// `--grid` or `--vary`.
        flag: &'static str,
        /// The axis as given.
        text: String,
    },
    /// An axis with an empty key.
    #[error("{flag} `{text}` names no key before `=` or between commas")]
    EmptyKey {
        /// `--grid` or `--vary`.
        flag: &'static str,
        /// The axis as given.
        text: String,
    },
    /// A value of an axis that is no number.
    #[error("{flag} {axis}: `{text}` is not a number")]
    NotANumber {
        /// `--grid` or `--vary`.
        flag: &'static str,
        /// The axis (its keys, `a,b*`).
        axis: String,
        /// The value as given.
        text: String,
    },
    /// A value with a unit its entry does not take.
    #[error("{flag} {axis}: `{text}`: {reason}")]
    Quantity {
        /// `--grid` or `--vary`.
        flag: &'static str,
        /// The axis (its keys, `a,b*`).
        axis: String,
        /// The value as given.
        text: String,
        /// Why the entry does not take it.
        reason: String,
    },
    /// A factor (`KEY*=`) written with a unit.
    #[error("{flag} {axis}: `{text}` is a factor of the entry: give a pure number")]
    FactorWithUnit {
        /// `--grid` or `--vary`.
        flag: &'static str,
        /// The axis (its keys, `a,b*`).
        axis: String,
        /// The value as given.
        text: String,
    },
    /// A value of an axis that is infinite or NaN.
    #[error("{flag} {axis}: `{text}` is not finite")]
    NotFinite {
        /// `--grid` or `--vary`.
        flag: &'static str,
        /// The axis (its keys, `a,b*`).
        axis: String,
        /// The value as given.
        text: String,
    },
    /// The count of a grid range `low:high:count` that is not 2 or more.
    #[error("--grid {axis}: `{count}` is not a count of at least 2 values")]
    GridCount {
        /// The axis (its keys, `a,b*`).
        axis: String,
        /// The count as given.
        count: String,
    },
    /// Grid values that are neither a list nor a range.
    #[error("--grid {axis}: `{text}` is neither a list `a,b,c` nor a range `low:high:count`")]
    GridValues {
        /// The axis (its keys, `a,b*`).
        axis: String,
        /// The values as given.
        text: String,
    },
    /// A key on two axes.
    #[error("`{key}` is swept twice")]
    SweptTwice {
        /// The key.
        key: String,
    },
    /// `--grid` without an axis.
    #[error("--grid needs at least one KEY=VALUES")]
    NoGridAxis,
    /// A grid of more than 2³² runs.
    #[error("the grid has more than 2³² runs")]
    GridTooLarge,
    /// A sample count of 0 or more than 2³².
    #[error("--samples {count}: give between 1 and 2³² runs")]
    SampleCount {
        /// The count given.
        count: usize,
    },
    /// `--samples` without an axis.
    #[error("--samples needs at least one --vary KEY=LOW:HIGH")]
    NoSampledAxis,
    /// A sampled range that is not `low:high` or `low:high:log`.
    #[error("--vary {axis}: `{range}` is not a range `low:high` or `low:high:log`")]
    NotARange {
        /// The axis (its keys, `a,b*`).
        axis: String,
        /// The range as given.
        range: String,
    },
    /// A logarithmic range with an end at or below 0.
    #[error("--vary {axis}: a logarithmic range needs positive ends, got {low}:{high}")]
    NonPositiveLogRange {
        /// The axis (its keys, `a,b*`).
        axis: String,
        /// The lower end.
        low: f64,
        /// The upper end.
        high: f64,
    },
}

/// Why the shard of a task cannot be told: what was given, or what the
/// scheduler's variables say.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum ShardError {
    /// `--shard` text that is not `i/n` with `1 ≤ i ≤ n`.
    #[error("--shard `{text}` is not of the form i/n with 1 ≤ i ≤ n (e.g. 3/8)")]
    NotAFraction {
        /// The text given.
        text: String,
    },
    /// A 0-based index at or above the count.
    #[error("shard index {index} is not below the shard count {count} (indices count from 0)")]
    IndexBeyondCount {
        /// The index, from 0.
        index: usize,
        /// The number of shards.
        count: usize,
    },
    /// `--shard-count` with `--shard I/N`.
    #[error("--shard-count goes with --shard auto or --shard-index, not --shard I/N")]
    CountWithFraction,
    /// `--shard-count` alone.
    #[error("--shard-count goes with --shard auto or --shard-index")]
    CountAlone,
    /// `--shard auto` outside an array job.
    #[error(
        "--shard auto: none of {} is set; outside an array job give --shard I/N or --shard-index K --shard-count N",
        .variables.join(", ")
    )]
    NoScheduler {
        /// The index variables of the schedulers known.
        variables: Vec<&'static str>,
    },
    /// `--shard auto` where the variables of several schedulers are set.
    #[error(
        "--shard auto: {} are all set; give --shard-index K --shard-count N to say which to use",
        .variables.join(" and ")
    )]
    SeveralSchedulers {
        /// The index variables that are set.
        variables: Vec<&'static str>,
    },
    /// `--shard auto` where the one scheduler's variables do not tell the
    /// shard.
    #[error("--shard auto ({scheduler}): {problem}")]
    Scheduler {
        /// The scheduler's name.
        scheduler: &'static str,
        /// What its variables lack.
        problem: super::scheduler::SchedulerError,
    },
}

/// How an axis changes its scenario entry.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Assignment {
    /// `KEY=…`: the entry takes the value.
    Set,
    /// `KEY*=…`: every number of the entry is multiplied by the value.
    Scale,
}

/// One swept quantity: a `--set` key and how its value is applied.
#[derive(Clone, Debug, PartialEq)]
pub struct Axis {
    /// A parameter or input name, or a dotted scenario key (`components.weld.failure_moment`).
    pub key: String,
    /// Whether a run's value replaces the entry or multiplies it.
    pub assignment: Assignment,
}

impl Axis {
    /// The column name of the axis in the output: `KEY`, or `KEY*` for a factor.
    pub fn column(&self) -> String {
        match self.assignment {
            Assignment::Set => self.key.clone(),
            Assignment::Scale => format!("{}*", self.key),
        }
    }
}

impl fmt::Display for Axis {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.column())
    }
}

/// Axes that take the same value in every run (`KEY1,KEY2=…`): tied
/// quantities, such as two masses scaled together. Each is a column of its own.
pub type Tied = Vec<Axis>;

/// A sampled axis: uniform between `low` and `high`, or log-uniform.
#[derive(Clone, Debug, PartialEq)]
pub struct SampledAxis {
    /// The quantities sampled, tied to one value per run.
    pub axes: Tied,
    /// Lower end of the range, in the entry's own units (or the factor).
    pub low: f64,
    /// Upper end of the range; `low` and `high` may come in either order.
    pub high: f64,
    /// `true`: uniform in `ln x` (both ends positive, `low:high:log`).
    pub logarithmic: bool,
}

/// How sampled designs place their points.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Design {
    /// Latin hypercube: each axis's range is cut into `count` equal strata
    /// and every stratum holds exactly one run.
    LatinHypercube,
    /// Independent uniform draws.
    Random,
}

/// The runs of a sweep. Run `i`'s values depend only on the plan and `i`,
/// so shards computed on different machines agree with a single full run.
#[derive(Clone, Debug)]
pub enum Plan {
    /// Every combination of the axes' values; the last axis varies fastest.
    Grid(Vec<(Tied, Vec<f64>)>),
    /// `count` points drawn from the axes' ranges.
    Samples {
        /// Number of runs, 1 to 2³² − 1.
        count: usize,
        /// The sampled axes, in column order; no key twice.
        axes: Vec<SampledAxis>,
        /// Seed of the draws: run `i`'s values come from stream `i` of a
        /// generator seeded with it, the strata from streams counted down
        /// from `u64::MAX`.
        seed: u64,
        /// How the points are placed.
        design: Design,
        /// For a Latin hypercube: the stratum of each run on each axis.
        strata: Vec<Vec<u32>>,
    },
}

/// Splits `KEY=VALUE` or `KEY*=VALUE`; `KEY1,KEY2=VALUE` ties several keys
/// to the same value (the `*` of `*=` applies to each).
fn split_assignment(text: &str, flag: &'static str) -> Result<(Tied, String), PlanError> {
    let (keys, value) = text
        .split_once('=')
        .ok_or_else(|| PlanError::NotAnAssignment {
            flag,
            text: text.to_string(),
        })?;
    let (keys, assignment) = match keys.trim().strip_suffix('*') {
        Some(k) => (k, Assignment::Scale),
        None => (keys, Assignment::Set),
    };
    let mut tied = Vec::new();
    for key in keys.split(',').map(str::trim) {
        if key.is_empty() {
            return Err(PlanError::EmptyKey {
                flag,
                text: text.to_string(),
            });
        }
        tied.push(Axis {
            key: key.to_string(),
            assignment,
        });
    }
    Ok((tied, value.trim().to_string()))
}

/// The name of tied axes in messages: `a,b*`.
fn tied_name(tied: &[Axis]) -> String {
    let keys: Vec<&str> = tied.iter().map(|a| a.key.as_str()).collect();
    match tied.first().map(|a| a.assignment) {
        Some(Assignment::Scale) => format!("{}*", keys.join(",")),
        _ => keys.join(","),
    }
}

/// Reads an axis value written with a unit (`56 km/h`) for the entry
/// `key` as the SI number that entry takes, or says why it does not: the
/// scenario's [`lagrangian_sim::scenario::BaseScenario::si_value`].
pub type Units<'a> = &'a dyn Fn(&str, &str) -> Result<f64, EntryError>;

/// For a plan made without a scenario: every value with a unit refused.
fn no_units(_key: &str, _text: &str) -> Result<f64, EntryError> {
    Err(EntryError::text(
        KeyPath::new("sweep"),
        "",
        "units need the scenario".to_string(),
    ))
}

/// Where an axis value is read: the flag, the tied axes it sets and how
/// their units are read.
#[derive(Clone, Copy)]
struct Reading<'a> {
    flag: &'static str,
    tied: &'a [Axis],
    units: Units<'a>,
}

impl Reading<'_> {
    /// `text` as a number, or as a number with a unit in SI (every tied
    /// entry reading it alike); finite.
    fn number(&self, text: &str) -> Result<f64, PlanError> {
        let (flag, axis, text) = (self.flag, tied_name(self.tied), text.trim().to_string());
        let value = match text.parse::<f64>() {
            Ok(value) => value,
            Err(_) if has_unit(&text) => self.quantity(&text)?,
            Err(_) => return Err(PlanError::NotANumber { flag, axis, text }),
        };
        if value.is_finite() {
            Ok(value)
        } else {
            Err(PlanError::NotFinite { flag, axis, text })
        }
    }

    fn quantity(&self, text: &str) -> Result<f64, PlanError> {
        let (flag, axis, text) = (self.flag, tied_name(self.tied), text.to_string());
        if self.tied.iter().any(|a| a.assignment == Assignment::Scale) {
            return Err(PlanError::FactorWithUnit { flag, axis, text });
        }
        let mut values = Vec::new();
        for tied in self.tied {
            let value = (self.units)(&tied.key, &text).map_err(|e| PlanError::Quantity {
                flag,
                axis: axis.clone(),
                text: text.clone(),
                reason: match self.tied.len() {
                    1 => e.reason,
                    _ => format!("{}: {}", tied.key, e.reason),
                },
            })?;
            values.push(value);
        }
        match values.windows(2).all(|w| w[0] == w[1]) {
            true => Ok(values[0]),
            false => Err(PlanError::Quantity {
                flag,
                axis,
                text,
                reason: "the tied entries read it as different numbers: tie entries of one unit"
                    .into(),
            }),
        }
    }
}

/// `a,b,c` or `low:high:count` (count evenly spaced values, ends included).
fn grid_values(text: &str, reading: Reading<'_>) -> Result<Vec<f64>, PlanError> {
    let axis = &tied_name(reading.tied);
    let parts: Vec<&str> = text.split(':').collect();
    match parts.as_slice() {
        [low, high, count] => {
            let (low, high) = (reading.number(low)?, reading.number(high)?);
            let count: usize = count
                .trim()
                .parse()
                .ok()
                .filter(|&n| n >= 2)
                .ok_or_else(|| PlanError::GridCount {
                    axis: axis.to_string(),
                    count: count.to_string(),
                })?;
            Ok((0..count)
                .map(|k| low + (high - low) * k as f64 / (count - 1) as f64)
                .collect())
        }
        [list] => list.split(',').map(|v| reading.number(v)).collect(),
        _ => Err(PlanError::GridValues {
            axis: axis.to_string(),
            text: text.to_string(),
        }),
    }
}

/// Rejects an axis named twice.
fn check_distinct<'a>(axes: impl Iterator<Item = &'a Axis>) -> Result<(), PlanError> {
    let mut seen: Vec<&str> = Vec::new();
    for axis in axes {
        if seen.contains(&axis.key.as_str()) {
            return Err(PlanError::SweptTwice {
                key: axis.key.clone(),
            });
        }
        seen.push(&axis.key);
    }
    Ok(())
}

impl Plan {
    /// A grid from `--grid KEY=a,b,c` / `KEY=low:high:count` / `KEY*=…`
    /// arguments of plain numbers.
    pub fn grid(arguments: &[String]) -> Result<Plan, PlanError> {
        Plan::grid_in(arguments, &no_units)
    }

    /// A grid whose values may carry units (`initial.speed=40 km/h,56 km/h`),
    /// read by `units` as the SI numbers of their entries.
    pub fn grid_in(arguments: &[String], units: Units<'_>) -> Result<Plan, PlanError> {
        if arguments.is_empty() {
            return Err(PlanError::NoGridAxis);
        }
        let mut axes = Vec::new();
        for argument in arguments {
            let (tied, values) = split_assignment(argument, "--grid")?;
            let reading = Reading {
                flag: "--grid",
                tied: &tied,
                units,
            };
            let values = grid_values(&values, reading)?;
            axes.push((tied, values));
        }
        check_distinct(axes.iter().flat_map(|(tied, _)| tied))?;
        let total = axes
            .iter()
            .try_fold(1usize, |n, (_, v)| n.checked_mul(v.len()));
        match total {
            Some(n) if n <= u32::MAX as usize => Ok(Plan::Grid(axes)),
            _ => Err(PlanError::GridTooLarge),
        }
    }

    /// `count` runs sampled from `--vary KEY=low:high[:log]` ranges of
    /// plain numbers.
    pub fn samples(
        count: usize,
        arguments: &[String],
        seed: u64,
        design: Design,
    ) -> Result<Plan, PlanError> {
        Plan::samples_in(count, arguments, seed, design, &no_units)
    }

    /// `count` runs sampled from ranges whose ends may carry units
    /// (`k1=50 kN/m:100 kN/m`), read by `units` as their entries' SI numbers.
    pub fn samples_in(
        count: usize,
        arguments: &[String],
        seed: u64,
        design: Design,
        units: Units<'_>,
    ) -> Result<Plan, PlanError> {
        if count == 0 || count > u32::MAX as usize {
            return Err(PlanError::SampleCount { count });
        }
        if arguments.is_empty() {
            return Err(PlanError::NoSampledAxis);
        }
        let mut axes = Vec::new();
        for argument in arguments {
            let (tied, range) = split_assignment(argument, "--vary")?;
            let axis = tied_name(&tied);
            let parts: Vec<&str> = range.split(':').collect();
            let (low, high, logarithmic) = match parts.as_slice() {
                [low, high] => (low, high, false),
                [low, high, "log"] => (low, high, true),
                _ => {
                    return Err(PlanError::NotARange {
                        axis,
                        range: range.clone(),
                    });
                }
            };
            let reading = Reading {
                flag: "--vary",
                tied: &tied,
                units,
            };
            let (low, high) = (reading.number(low)?, reading.number(high)?);
            if logarithmic && (low <= 0.0 || high <= 0.0) {
                return Err(PlanError::NonPositiveLogRange { axis, low, high });
            }
            axes.push(SampledAxis {
                axes: tied,
                low,
                high,
                logarithmic,
            });
        }
        check_distinct(axes.iter().flat_map(|a| &a.axes))?;
        let strata = match design {
            Design::Random => Vec::new(),
            Design::LatinHypercube => (0..axes.len())
                .map(|k| {
                    let mut rng = ChaCha8Rng::seed_from_u64(seed);
                    rng.set_stream(u64::MAX - k as u64);
                    permutation(count, &mut rng)
                })
                .collect(),
        };
        Ok(Plan::Samples {
            count,
            axes,
            seed,
            design,
            strata,
        })
    }

    /// Number of runs.
    pub fn len(&self) -> usize {
        match self {
            Plan::Grid(axes) => axes.iter().map(|(_, v)| v.len()).product(),
            Plan::Samples { count, .. } => *count,
        }
    }

    /// `true` for a plan of no runs.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// The swept quantities, in column order (tied ones one after another).
    pub fn axes(&self) -> Vec<&Axis> {
        self.tied().into_iter().flatten().collect()
    }

    /// The groups of tied axes, in column order: one value each per run.
    fn tied(&self) -> Vec<&Tied> {
        match self {
            Plan::Grid(axes) => axes.iter().map(|(tied, _)| tied).collect(),
            Plan::Samples { axes, .. } => axes.iter().map(|a| &a.axes).collect(),
        }
    }

    /// The values of run `run` (`run < self.len()`), one per axis (tied
    /// axes repeat their group's value).
    pub fn point(&self, run: usize) -> Vec<f64> {
        let values = self.group_values(run);
        (self.tied().iter().zip(values))
            .flat_map(|(tied, x)| std::iter::repeat_n(x, tied.len()))
            .collect()
    }

    /// The value of each group of tied axes in run `run`.
    fn group_values(&self, run: usize) -> Vec<f64> {
        match self {
            Plan::Grid(axes) => {
                let mut rest = run;
                let mut values = vec![0.0; axes.len()];
                for (k, (_, list)) in axes.iter().enumerate().rev() {
                    values[k] = list[rest % list.len()];
                    rest /= list.len();
                }
                values
            }
            Plan::Samples {
                count,
                axes,
                seed,
                design,
                strata,
            } => {
                let mut rng = ChaCha8Rng::seed_from_u64(*seed);
                rng.set_stream(run as u64);
                axes.iter()
                    .enumerate()
                    .map(|(k, a)| {
                        let u = unit_interval(&mut rng);
                        let fraction = match design {
                            Design::Random => u,
                            Design::LatinHypercube => (strata[k][run] as f64 + u) / *count as f64,
                        };
                        if a.logarithmic {
                            (a.low.ln() + fraction * (a.high.ln() - a.low.ln())).exp()
                        } else {
                            a.low + fraction * (a.high - a.low)
                        }
                    })
                    .collect()
            }
        }
    }
}

/// A uniform draw from [0, 1) with 53 random bits.
fn unit_interval(rng: &mut ChaCha8Rng) -> f64 {
    (rng.next_u64() >> 11) as f64 / (1u64 << 53) as f64
}

/// A uniformly random permutation of `0..n` (Fisher–Yates).
fn permutation(n: usize, rng: &mut ChaCha8Rng) -> Vec<u32> {
    let mut p: Vec<u32> = (0..n as u32).collect();
    for i in (1..n).rev() {
        let j = (rng.next_u64() % (i as u64 + 1)) as usize;
        p.swap(i, j);
    }
    p
}

/// Shard `index` of `count` (1-based, as `--shard 3/8`): a contiguous block
/// of runs, so that the shards' outputs concatenated in order are the full sweep.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Shard {
    /// Which block, from 1 to `count`.
    pub index: usize,
    /// Into how many blocks the runs are split; at least 1.
    pub count: usize,
}

impl Shard {
    /// The whole sweep.
    pub const ALL: Shard = Shard { index: 1, count: 1 };

    /// Parses `i/n` with `1 ≤ i ≤ n`.
    pub fn parse(text: &str) -> Result<Shard, ShardError> {
        let parsed = text.split_once('/').and_then(|(i, n)| {
            Some((
                i.trim().parse::<usize>().ok()?,
                n.trim().parse::<usize>().ok()?,
            ))
        });
        match parsed {
            Some((index, count)) if index >= 1 && index <= count => Ok(Shard { index, count }),
            _ => Err(ShardError::NotAFraction {
                text: text.to_string(),
            }),
        }
    }

    /// Block `index` of `count` counted from 0 (`--shard-index 2
    /// --shard-count 8` is `--shard 3/8`), as Kubernetes, AWS Batch and
    /// HTCondor number their tasks.
    pub fn zero_based(index: usize, count: usize) -> Result<Shard, ShardError> {
        if index < count {
            Ok(Shard {
                index: index + 1,
                count,
            })
        } else {
            Err(ShardError::IndexBeyondCount { index, count })
        }
    }

    /// The runs of this shard out of `total`.
    pub fn runs(&self, total: usize) -> Range<usize> {
        let bound = |k: usize| (total as u128 * k as u128 / self.count as u128) as usize;
        bound(self.index - 1)..bound(self.index)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn strings(items: &[&str]) -> Vec<String> {
        items.iter().map(|s| s.to_string()).collect()
    }

    /// A stand-in for a scenario's units: `a` and `b` in kilonewtons
    /// (`N` only), `c` a speed in km/h (`km/h` only).
    fn units(key: &str, text: &str) -> Result<f64, EntryError> {
        let refuse = || EntryError::text(KeyPath::new(key), text, "needs another unit".to_string());
        let number = |unit: &str| {
            text.strip_suffix(unit)
                .and_then(|n| n.trim().parse::<f64>().ok())
        };
        match key {
            "a" | "b" => number("kN").map(|n| n * 1e3).ok_or_else(refuse),
            "c" => number("km/h").map(|n| n / 3.6).ok_or_else(refuse),
            _ => Err(refuse()),
        }
    }

    #[test]
    fn values_with_units_are_read_by_their_entries_once() {
        let grid = strings(&["a,b=2 kN,3e3", "c=36 km/h:72 km/h:2"]);
        let plan = Plan::grid_in(&grid, &units).unwrap();
        let points: Vec<Vec<f64>> = (0..4).map(|i| plan.point(i)).collect();
        assert_eq!(points[0], [2e3, 2e3, 10.0]);
        assert_eq!(points[3], [3e3, 3e3, 20.0]);
        let sampled =
            Plan::samples_in(3, &strings(&["a=1 kN:2 kN:log"]), 1, Design::Random, &units);
        let sampled = sampled.unwrap();
        assert!((0..3).all(|i| (1e3..=2e3).contains(&sampled.point(i)[0])));
    }

    #[test]
    fn a_unit_an_entry_refuses_a_factors_unit_and_tied_readings_that_differ_are_errors() {
        let error = |args: &[&str]| {
            Plan::grid_in(&strings(args), &units)
                .unwrap_err()
                .to_string()
        };
        assert_eq!(error(&["c=2 kN"]), "--grid c: `2 kN`: needs another unit");
        assert_eq!(
            error(&["a,c=2 kN"]),
            "--grid a,c: `2 kN`: c: needs another unit"
        );
        assert_eq!(
            error(&["a*=2 kN"]),
            "--grid a*: `2 kN` is a factor of the entry: give a pure number"
        );
        assert_eq!(error(&["a=two"]), "--grid a: `two` is not a number");
        // Without a scenario, no unit is read.
        let error = Plan::grid(&strings(&["a=2 kN"])).unwrap_err().to_string();
        assert_eq!(error, "--grid a: `2 kN`: units need the scenario");
    }

    #[test]
    fn grid_enumerates_every_combination_last_axis_fastest() {
        let plan = Plan::grid(&strings(&["a=1,2", "b*=0:1:3"])).unwrap();
        assert_eq!(plan.len(), 6);
        let points: Vec<Vec<f64>> = (0..6).map(|i| plan.point(i)).collect();
        assert_eq!(
            points,
            vec![
                vec![1.0, 0.0],
                vec![1.0, 0.5],
                vec![1.0, 1.0],
                vec![2.0, 0.0],
                vec![2.0, 0.5],
                vec![2.0, 1.0]
            ]
        );
        let columns: Vec<String> = plan.axes().iter().map(|a| a.column()).collect();
        assert_eq!(columns, ["a", "b*"]);
    }

    #[test]
    fn tied_axes_take_one_value_each_run_in_columns_of_their_own() {
        let plan = Plan::grid(&strings(&["m1,m2*=0.5,2", "k=1:3:3"])).unwrap();
        assert_eq!(plan.len(), 6);
        let columns: Vec<String> = plan.axes().iter().map(|a| a.column()).collect();
        assert_eq!(columns, ["m1*", "m2*", "k"]);
        assert_eq!(plan.point(0), [0.5, 0.5, 1.0]);
        assert_eq!(plan.point(5), [2.0, 2.0, 3.0]);
        let sampled = Plan::samples(20, &strings(&["a,b=0:1", "c=5:6"]), 9, Design::Random);
        let sampled = sampled.unwrap();
        for run in 0..20 {
            let p = sampled.point(run);
            assert_eq!(p.len(), 3);
            assert_eq!(p[0], p[1]);
            assert!((5.0..6.0).contains(&p[2]));
        }
        let error = Plan::grid(&strings(&["a,b=1,2", "b=3"])).unwrap_err();
        assert_eq!(error, PlanError::SweptTwice { key: "b".into() });
        let error = error.to_string();
        assert!(error.contains("`b` is swept twice"), "{error}");
        let error = Plan::grid(&strings(&["a,,b=1,2"])).unwrap_err().to_string();
        assert!(error.contains("names no key"), "{error}");
        let error = Plan::grid(&strings(&["a,b*=1,x"])).unwrap_err().to_string();
        assert!(
            error.contains("--grid a,b*: `x` is not a number"),
            "{error}"
        );
    }

    #[test]
    fn bad_axes_are_reported_with_the_offending_text() {
        let error = |args: &[&str]| Plan::grid(&strings(args)).unwrap_err().to_string();
        assert!(error(&["a"]).contains("`a`"));
        assert!(error(&["a=1,x"]).contains("`x` is not a number"));
        assert!(error(&["a=1:2:1"]).contains("at least 2"));
        assert!(error(&["a=1,2", "a*=3"]).contains("swept twice"));
        assert!(error(&["a=inf"]).contains("not finite"));
        let vary = |args: &[&str]| {
            (Plan::samples(4, &strings(args), 1, Design::Random))
                .unwrap_err()
                .to_string()
        };
        assert!(vary(&["k=0:1:lin"]).contains("low:high:log"));
        assert!(vary(&["k=-1:1:log"]).contains("positive"));
    }

    #[test]
    fn latin_hypercube_puts_one_run_in_each_stratum() {
        let n = 50;
        let plan = Plan::samples(
            n,
            &strings(&["a=0:1", "b=10:20"]),
            7,
            Design::LatinHypercube,
        )
        .unwrap();
        for (k, (low, high)) in [(0.0, 1.0), (10.0, 20.0)].into_iter().enumerate() {
            let mut strata: Vec<usize> = (0..n)
                .map(|i| {
                    let x = plan.point(i)[k];
                    assert!((low..high).contains(&x));
                    ((x - low) / (high - low) * n as f64) as usize
                })
                .collect();
            strata.sort();
            assert_eq!(strata, (0..n).collect::<Vec<_>>());
        }
    }

    #[test]
    fn samples_depend_only_on_seed_and_run() {
        let args = strings(&["a=1:100:log", "b=0:1"]);
        let plan = Plan::samples(100, &args, 3, Design::Random).unwrap();
        let again = Plan::samples(100, &args, 3, Design::Random).unwrap();
        let other = Plan::samples(100, &args, 4, Design::Random).unwrap();
        assert_eq!(plan.point(42), again.point(42));
        assert_ne!(plan.point(42), other.point(42));
        assert_ne!(plan.point(42), plan.point(43));
        let logs: Vec<f64> = (0..100).map(|i| plan.point(i)[0].log10()).collect();
        assert!(logs.iter().all(|&l| (0.0..2.0).contains(&l)));
        // Log-uniform: about half the runs below 10.
        let below = logs.iter().filter(|&&l| l < 1.0).count();
        assert!((30..70).contains(&below), "{below}");
    }

    #[test]
    fn zero_based_shards_are_the_one_based_shard_after() {
        assert_eq!(Shard::zero_based(2, 8), Shard::parse("3/8"));
        assert_eq!(Shard::zero_based(0, 1), Ok(Shard::ALL));
        let message = Shard::zero_based(8, 8).unwrap_err().to_string();
        assert!(
            message.contains("shard index 8 is not below the shard count 8"),
            "{message}"
        );
    }

    #[test]
    fn shards_partition_the_runs_in_order() {
        for total in [0, 1, 7, 10, 1000] {
            for count in 1..=9 {
                let mut next = 0;
                for index in 1..=count {
                    let runs = Shard { index, count }.runs(total);
                    assert_eq!(runs.start, next);
                    next = runs.end;
                }
                assert_eq!(next, total);
            }
        }
        assert_eq!(Shard::parse("3/8").unwrap(), Shard { index: 3, count: 8 });
        for bad in ["0/4", "5/4", "3", "a/b", "1/0"] {
            assert!(Shard::parse(bad).unwrap_err().to_string().contains(bad));
        }
    }
}
