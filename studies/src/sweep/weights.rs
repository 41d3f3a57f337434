//! The weight of each run in an envelope's mean history (`--weights`):
//! equal, one per value of a grid axis (a traffic mix of impact speeds:
//! `v0=0.2,0.5,0.3`), or one per run from a CSV file (`run,weight`).

use super::plan::Plan;

/// How much each run counts in a weighted mean.
#[derive(Clone, Debug, PartialEq)]
pub enum Weights {
    /// Every run weighs 1.
    Equal,
    /// The weight of the run's value on grid axis `group` (its index among
    /// the grid's axes, tied keys counting once).
    PerValue {
        /// The axis.
        group: usize,
        /// One weight per value of the axis, in the order given.
        weights: Vec<f64>,
    },
    /// One weight per run, in run order.
    PerRun(Vec<f64>),
}

/// Why `--weights` cannot be used: what was given (the list or the
/// file's name) and what is wrong with it.
#[derive(Debug, thiserror::Error)]
#[error("--weights {given}: {problem}")]
pub struct WeightsError {
    /// `KEY=W1,W2,…` as given, or the CSV file's name.
    pub given: String,
    /// What is wrong.
    pub problem: WeightsProblem,
}

/// What is wrong with the weights of [`WeightsError`].
#[derive(Debug, thiserror::Error)]
pub enum WeightsProblem {
    /// Neither `KEY=W1,W2,…` nor a file.
    #[error("write KEY=W1,W2,… or name a CSV file")]
    NotAList,
    /// Weights per value of a sampled design.
    #[error("weights per value need a --grid axis; with --samples give a CSV file of run,weight")]
    NotAGrid,
    /// A key that is no axis of the grid.
    #[error("`{key}` is not an axis of the grid (its axes: {})", .axes.join(", "))]
    NotAnAxis {
        /// The key given.
        key: String,
        /// The grid's axes (columns).
        axes: Vec<String>,
    },
    /// A weight of the list that is no number.
    #[error("`{text}` is not a number")]
    NotANumber {
        /// The weight as given.
        text: String,
    },
    /// Not one weight per value of the axis.
    #[error(
        "{given} weights for the {} values of {key} ({}); give one per value",
        .values.len(),
        listed(.values)
    )]
    Count {
        /// The number of weights given.
        given: usize,
        /// The axis.
        key: String,
        /// Its values.
        values: Vec<f64>,
    },
    /// A weight that is negative, infinite or NaN.
    #[error("the weight of {of} is {weight}; weights must be non-negative and finite")]
    Invalid {
        /// The value or run it belongs to.
        of: WeightOf,
        /// The weight.
        weight: f64,
    },
    /// Every weight 0.
    #[error("every weight is 0; at least one must be positive")]
    AllZero,
    /// The CSV file does not read.
    #[error("{0}")]
    Csv(#[source] csv::Error),
    /// A column of the CSV file missing.
    #[error("no `{name}` column (give columns run,weight)")]
    NoColumn {
        /// `run` or `weight`.
        name: &'static str,
    },
    /// A `run` cell that is no run number.
    #[error("line {line}: run `{text}` is no run number")]
    RunNumber {
        /// The line of the file.
        line: usize,
        /// The cell.
        text: String,
    },
    /// A `weight` cell that is no number.
    #[error("line {line}: `{text}` is not a number")]
    WeightNumber {
        /// The line of the file.
        line: usize,
        /// The cell.
        text: String,
    },
    /// A run beyond the sweep's.
    #[error("line {line}: the sweep has no run {run}")]
    NoSuchRun {
        /// The line of the file.
        line: usize,
        /// The run.
        run: usize,
    },
    /// A run given twice.
    #[error("line {line}: run {run} is there twice")]
    Twice {
        /// The line of the file (the second).
        line: usize,
        /// The run.
        run: usize,
    },
    /// A run without a weight.
    #[error("no weight for run {run}")]
    Missing {
        /// The run.
        run: usize,
    },
}

/// What a weight belongs to, in messages.
#[derive(Clone, Debug, PartialEq)]
pub enum WeightOf {
    /// A value of a grid axis.
    Value {
        /// The axis.
        key: String,
        /// The value.
        value: f64,
    },
    /// A run.
    Run(usize),
}

impl std::fmt::Display for WeightOf {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            WeightOf::Value { key, value } => write!(f, "{key} = {value}"),
            WeightOf::Run(run) => write!(f, "run {run}"),
        }
    }
}

impl Weights {
    /// The weight of run `run` of `plan`.
    pub fn of_run(&self, plan: &Plan, run: usize) -> f64 {
        match self {
            Weights::Equal => 1.0,
            Weights::PerValue { group, weights } => weights[value_index(plan, *group, run)],
            Weights::PerRun(weights) => weights[run],
        }
    }

    /// `KEY=W1,W2,…`: one weight per value of the grid axis `KEY`.
    pub fn per_value(text: &str, plan: &Plan) -> Result<Weights, WeightsError> {
        let bad = |problem: WeightsProblem| WeightsError {
            given: text.to_string(),
            problem,
        };
        let (key, list) = text
            .split_once('=')
            .ok_or_else(|| bad(WeightsProblem::NotAList))?;
        let key = key.trim();
        let (group, values) = grid_axis(plan, key).map_err(bad)?;
        let mut weights = Vec::new();
        for item in list.split(',').map(str::trim) {
            let w: f64 = item.parse().map_err(|_| {
                bad(WeightsProblem::NotANumber {
                    text: item.to_string(),
                })
            })?;
            weights.push(w);
        }
        if weights.len() != values.len() {
            return Err(bad(WeightsProblem::Count {
                given: weights.len(),
                key: key.to_string(),
                values: values.to_vec(),
            }));
        }
        let of = |k: usize| WeightOf::Value {
            key: key.to_string(),
            value: values[k],
        };
        check(&weights, of).map_err(bad)?;
        Ok(Weights::PerValue { group, weights })
    }

    /// A CSV file's text (`file` names it in messages) with columns `run`
    /// and `weight`: one row for every run of `plan`.
    pub fn per_run_csv(text: &str, file: &str, plan: &Plan) -> Result<Weights, WeightsError> {
        let bad = |problem: WeightsProblem| WeightsError {
            given: file.to_string(),
            problem,
        };
        let mut reader = csv::Reader::from_reader(text.as_bytes());
        let headers = (reader.headers())
            .map_err(|e| bad(WeightsProblem::Csv(e)))?
            .clone();
        let column = |name: &'static str| {
            (headers.iter().position(|h| h.trim() == name))
                .ok_or_else(|| bad(WeightsProblem::NoColumn { name }))
        };
        let (run_column, weight_column) = (column("run")?, column("weight")?);
        let mut weights = vec![None; plan.len()];
        for (line, record) in reader.records().enumerate() {
            let record = record.map_err(|e| bad(WeightsProblem::Csv(e)))?;
            let line = line + 2;
            let field = |k: usize| record.get(k).unwrap_or("").trim();
            let text = |k: usize| field(k).to_string();
            let run: usize = (field(run_column).parse()).map_err(|_| {
                bad(WeightsProblem::RunNumber {
                    line,
                    text: text(run_column),
                })
            })?;
            let w: f64 = (field(weight_column).parse()).map_err(|_| {
                bad(WeightsProblem::WeightNumber {
                    line,
                    text: text(weight_column),
                })
            })?;
            match weights.get_mut(run) {
                None => return Err(bad(WeightsProblem::NoSuchRun { line, run })),
                Some(Some(_)) => return Err(bad(WeightsProblem::Twice { line, run })),
                Some(slot) => *slot = Some(w),
            }
        }
        if let Some(run) = weights.iter().position(Option::is_none) {
            return Err(bad(WeightsProblem::Missing { run }));
        }
        let weights: Vec<f64> = weights.into_iter().flatten().collect();
        check(&weights, WeightOf::Run).map_err(bad)?;
        Ok(Weights::PerRun(weights))
    }
}

/// Weights are non-negative and finite, and not all zero; `of` says
/// which value a weight belongs to.
fn check(weights: &[f64], of: impl Fn(usize) -> WeightOf) -> Result<(), WeightsProblem> {
    for (k, &weight) in weights.iter().enumerate() {
        if !(weight.is_finite() && weight >= 0.0) {
            return Err(WeightsProblem::Invalid { of: of(k), weight });
        }
    }
    if weights.iter().all(|&w| w == 0.0) {
        return Err(WeightsProblem::AllZero);
    }
    Ok(())
}

/// The index among the grid's axes of the one named `key` (`KEY` or
/// `KEY*`, any key of tied ones) and its values.
fn grid_axis<'p>(plan: &'p Plan, key: &str) -> Result<(usize, &'p [f64]), WeightsProblem> {
    let Plan::Grid(axes) = plan else {
        return Err(WeightsProblem::NotAGrid);
    };
    let named =
        |tied: &[super::plan::Axis]| (tied.iter()).any(|a| a.key == key || a.column() == key);
    match axes.iter().position(|(tied, _)| named(tied)) {
        Some(group) => Ok((group, &axes[group].1)),
        None => Err(WeightsProblem::NotAnAxis {
            key: key.to_string(),
            axes: plan.axes().iter().map(|a| a.column()).collect(),
        }),
    }
}

/// The index of run `run`'s value on grid axis `group` (the last axis
/// varies fastest).
fn value_index(plan: &Plan, group: usize, run: usize) -> usize {
    let Plan::Grid(axes) = plan else {
        return 0;
    };
    let faster: usize = axes[group + 1..].iter().map(|(_, v)| v.len()).product();
    (run / faster) % axes[group].1.len()
}

fn listed(values: &[f64]) -> String {
    let values: Vec<String> = values.iter().map(|x| x.to_string()).collect();
    values.join(", ")
}

#[cfg(test)]
mod tests {
    use super::*;

    fn grid(axes: &[&str]) -> Plan {
        let axes: Vec<String> = axes.iter().map(|s| s.to_string()).collect();
        Plan::grid(&axes).unwrap()
    }

    #[test]
    fn a_weight_per_value_applies_to_every_run_with_that_value() {
        let plan = grid(&["v0=10,15,20", "m=1,2"]);
        let weights = Weights::per_value("v0=0.2,0.5,0.3", &plan).unwrap();
        let of: Vec<f64> = (0..6).map(|run| weights.of_run(&plan, run)).collect();
        assert_eq!(of, [0.2, 0.2, 0.5, 0.5, 0.3, 0.3]);
        let last = Weights::per_value("m=1,3", &plan).unwrap();
        let of: Vec<f64> = (0..6).map(|run| last.of_run(&plan, run)).collect();
        assert_eq!(of, [1.0, 3.0, 1.0, 3.0, 1.0, 3.0]);
    }

    #[test]
    fn bad_weights_name_the_value_and_the_flag() {
        let plan = grid(&["v0=10,15,20"]);
        let error = |text: &str| Weights::per_value(text, &plan).unwrap_err().to_string();
        let negative = error("v0=0.2,-0.5,0.3");
        assert!(
            negative.starts_with("--weights v0=0.2,-0.5,0.3: the weight of v0 = 15 is -0.5"),
            "{negative}"
        );
        let infinite = error("v0=0.2,inf,0.3");
        assert!(
            infinite.contains("the weight of v0 = 15 is inf"),
            "{infinite}"
        );
        assert!(error("v0=0,0,0").contains("every weight is 0"));
        let count = error("v0=0.5,0.5");
        assert!(
            count.contains("2 weights for the 3 values of v0 (10, 15, 20)"),
            "{count}"
        );
        let axis = error("m=1,2,3");
        assert!(
            axis.contains("`m` is not an axis of the grid (its axes: v0)"),
            "{axis}"
        );
        assert!(error("v0=1,x,2").contains("`x` is not a number"));
    }

    #[test]
    fn weights_per_run_come_from_a_csv_file_with_every_run_once() {
        let plan = grid(&["v0=10,15,20"]);
        let read =
            |text: &str| Weights::per_run_csv(text, "w.csv", &plan).map_err(|e| e.to_string());
        let weights = read("run,weight\n2,3\n0,1\n1,0\n").unwrap();
        assert_eq!(weights, Weights::PerRun(vec![1.0, 0.0, 3.0]));
        let missing = read("run,weight\n0,1\n2,1\n").unwrap_err();
        assert_eq!(missing, "--weights w.csv: no weight for run 1");
        let twice = read("run,weight\n0,1\n0,1\n1,1\n2,1\n").unwrap_err();
        assert!(twice.contains("line 3: run 0 is there twice"), "{twice}");
        let beyond = read("run,weight\n0,1\n1,1\n2,1\n3,1\n").unwrap_err();
        assert!(
            beyond.contains("line 5: the sweep has no run 3"),
            "{beyond}"
        );
        let nan = read("run,weight\n0,1\n1,NaN\n2,1\n").unwrap_err();
        assert!(nan.contains("the weight of run 1 is NaN"), "{nan}");
        let columns = read("run,w\n0,1\n").unwrap_err();
        assert!(columns.contains("no `weight` column"), "{columns}");
    }
}
