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

/// The flag the weights come from, for messages.
const FLAG: &str = "--weights";

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
    pub fn per_value(text: &str, plan: &Plan) -> Result<Weights, String> {
        let bad = |why: String| format!("{FLAG} {text}: {why}");
        let (key, list) = text
            .split_once('=')
            .ok_or_else(|| bad("write KEY=W1,W2,… or name a CSV file".into()))?;
        let (group, values) = grid_axis(plan, key.trim()).map_err(bad)?;
        let mut weights = Vec::new();
        for item in list.split(',').map(str::trim) {
            let w: f64 = item
                .parse()
                .map_err(|_| bad(format!("`{item}` is not a number")))?;
            weights.push(w);
        }
        if weights.len() != values.len() {
            return Err(bad(format!(
                "{} weights for the {} values of {} ({}); give one per value",
                weights.len(),
                values.len(),
                key.trim(),
                listed(values)
            )));
        }
        let name = |k: usize| format!("{} = {}", key.trim(), values[k]);
        check(&weights, name).map_err(bad)?;
        Ok(Weights::PerValue { group, weights })
    }

    /// A CSV file's text (`file` names it in messages) with columns `run`
    /// and `weight`: one row for every run of `plan`.
    pub fn per_run_csv(text: &str, file: &str, plan: &Plan) -> Result<Weights, String> {
        let bad = |why: String| format!("{FLAG} {file}: {why}");
        let mut reader = csv::Reader::from_reader(text.as_bytes());
        let headers = reader.headers().map_err(|e| bad(e.to_string()))?.clone();
        let column = |name: &str| {
            (headers.iter().position(|h| h.trim() == name))
                .ok_or_else(|| bad(format!("no `{name}` column (give columns run,weight)")))
        };
        let (run_column, weight_column) = (column("run")?, column("weight")?);
        let mut weights = vec![None; plan.len()];
        for (line, record) in reader.records().enumerate() {
            let record = record.map_err(|e| bad(e.to_string()))?;
            let at = format!("line {}", line + 2);
            let field = |k: usize| record.get(k).unwrap_or("").trim();
            let run: usize = (field(run_column).parse()).map_err(|_| {
                bad(format!(
                    "{at}: run `{}` is no run number",
                    field(run_column)
                ))
            })?;
            let w: f64 = (field(weight_column).parse())
                .map_err(|_| bad(format!("{at}: `{}` is not a number", field(weight_column))))?;
            match weights.get_mut(run) {
                None => return Err(bad(format!("{at}: the sweep has no run {run}"))),
                Some(Some(_)) => return Err(bad(format!("{at}: run {run} is there twice"))),
                Some(slot) => *slot = Some(w),
            }
        }
        if let Some(missing) = weights.iter().position(Option::is_none) {
            return Err(bad(format!("no weight for run {missing}")));
        }
        let weights: Vec<f64> = weights.into_iter().flatten().collect();
        check(&weights, |k| format!("run {k}")).map_err(bad)?;
        Ok(Weights::PerRun(weights))
    }
}

/// Weights are non-negative and finite, and not all zero; `name` says
/// which value a weight belongs to.
fn check(weights: &[f64], name: impl Fn(usize) -> String) -> Result<(), String> {
    for (k, &w) in weights.iter().enumerate() {
        if !(w.is_finite() && w >= 0.0) {
            return Err(format!(
                "the weight of {} is {w}; weights must be non-negative and finite",
                name(k)
            ));
        }
    }
    if weights.iter().all(|&w| w == 0.0) {
        return Err("every weight is 0; at least one must be positive".into());
    }
    Ok(())
}

/// The index among the grid's axes of the one named `key` (`KEY` or
/// `KEY*`, any key of tied ones) and its values.
fn grid_axis<'p>(plan: &'p Plan, key: &str) -> Result<(usize, &'p [f64]), String> {
    let Plan::Grid(axes) = plan else {
        return Err(
            "weights per value need a --grid axis; with --samples give a CSV file of run,weight"
                .into(),
        );
    };
    let named =
        |tied: &[super::plan::Axis]| (tied.iter()).any(|a| a.key == key || a.column() == key);
    match axes.iter().position(|(tied, _)| named(tied)) {
        Some(group) => Ok((group, &axes[group].1)),
        None => {
            let keys: Vec<String> = plan.axes().iter().map(|a| a.column()).collect();
            Err(format!(
                "`{key}` is not an axis of the grid (its axes: {})",
                keys.join(", ")
            ))
        }
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
        let error = |text: &str| Weights::per_value(text, &plan).unwrap_err();
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
        let read = |text: &str| Weights::per_run_csv(text, "w.csv", &plan);
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
