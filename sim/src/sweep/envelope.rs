//! Envelopes of a sweep: for chosen channels, on the runs' common output
//! times, the pointwise maximum and minimum over the runs (with the run
//! attaining each) and the weighted mean history `Σ wᵢ xᵢ(t) / Σ wᵢ`.
//!
//! An [`Envelope`] takes the runs one at a time ([`Envelope::add`]) and
//! keeps only its accumulators — memory grows with the output times and
//! the channels, not with the runs. Runs are added in run order (as
//! [`stream_envelope`] hands them over), so the sums, and hence the file,
//! do not depend on the number of threads.

use super::plan::Plan;
use super::run::{Row, SweepJob, scenario_of, simulation_failure, stream_runs};
use super::shared::SharedScenario;
use super::weights::Weights;
use crate::scenario::Signal;
use crate::simulate::{SimulationResult, simulate};
use lagrangian_model::LagrangianSystem;
use std::sync::atomic::AtomicBool;

/// One run's channels at its output times.
#[derive(Clone, Debug, PartialEq)]
pub struct History {
    /// The output times \[s\].
    pub t: Vec<f64>,
    /// Per channel, its value at each of `t`.
    pub values: Vec<Vec<f64>>,
}

impl History {
    /// The histories of `channels` in a finished run.
    pub fn of(result: &SimulationResult, channels: &[Signal]) -> History {
        let values = (channels.iter())
            .map(|signal| {
                let at = |s: &crate::simulate::Sample| signal.value(&s.columns());
                result.samples.iter().map(at).collect()
            })
            .collect();
        History {
            t: result.samples.iter().map(|s| s.t).collect(),
            values,
        }
    }
}

/// The accumulators of one channel, one entry per output time.
#[derive(Clone, Debug, PartialEq)]
pub struct ChannelEnvelope {
    /// The channel as given (`"xa - xb"`, `front_end.force`).
    pub name: String,
    /// The largest value over the runs.
    pub max: Vec<f64>,
    /// The first run (in run order) attaining `max`; `None` where no run
    /// has a finite value.
    pub max_run: Vec<Option<usize>>,
    /// The smallest value over the runs.
    pub min: Vec<f64>,
    /// The first run attaining `min`.
    pub min_run: Vec<Option<usize>>,
    /// `Σ wᵢ xᵢ(t)`, summed in run order.
    pub weighted_sum: Vec<f64>,
}

impl ChannelEnvelope {
    fn new(name: &str, points: usize) -> ChannelEnvelope {
        ChannelEnvelope {
            name: name.to_string(),
            max: vec![f64::NAN; points],
            max_run: vec![None; points],
            min: vec![f64::NAN; points],
            min_run: vec![None; points],
            weighted_sum: vec![0.0; points],
        }
    }

    /// Takes run `run`'s values `x` with weight `w`. Non-finite values
    /// take no part in the extremes (the sum shows them).
    fn add(&mut self, run: usize, w: f64, x: &[f64]) {
        for (k, &x) in x.iter().enumerate() {
            if x.is_finite() && (self.max[k].is_nan() || x > self.max[k]) {
                (self.max[k], self.max_run[k]) = (x, Some(run));
            }
            if x.is_finite() && (self.min[k].is_nan() || x < self.min[k]) {
                (self.min[k], self.min_run[k]) = (x, Some(run));
            }
            self.weighted_sum[k] += w * x;
        }
    }
}

/// The envelopes of a sweep's channels, accumulated run by run.
#[derive(Clone, Debug, PartialEq)]
pub struct Envelope {
    /// The output times every run shares (those of the first run added).
    pub t: Vec<f64>,
    /// One per channel, in the order given.
    pub channels: Vec<ChannelEnvelope>,
    /// `Σ wᵢ` over the runs added.
    pub total_weight: f64,
    /// How many runs were added.
    pub runs: usize,
    /// The first run added, whose output times the others must share.
    first_run: Option<usize>,
    names: Vec<String>,
}

impl Envelope {
    /// An envelope of `channels` with no run yet.
    pub fn new(channels: &[Signal]) -> Envelope {
        Envelope {
            t: Vec::new(),
            channels: Vec::new(),
            total_weight: 0.0,
            runs: 0,
            first_run: None,
            names: channels.iter().map(|s| s.name.clone()).collect(),
        }
    }

    /// Adds run `run` with weight `weight`; its output times must be those
    /// of the first run added.
    pub fn add(&mut self, run: usize, weight: f64, history: &History) -> Result<(), String> {
        match self.first_run {
            None => self.start(run, history),
            Some(first) if history.t != self.t => {
                return Err(different_times(run, &history.t, first, &self.t));
            }
            Some(_) => {}
        }
        for (channel, x) in self.channels.iter_mut().zip(&history.values) {
            channel.add(run, weight, x);
        }
        self.total_weight += weight;
        self.runs += 1;
        Ok(())
    }

    fn start(&mut self, run: usize, history: &History) {
        self.first_run = Some(run);
        self.t = history.t.clone();
        self.channels = (self.names.iter())
            .map(|name| ChannelEnvelope::new(name, history.t.len()))
            .collect();
    }

    /// The weighted mean history of channel `k`: `Σ wᵢ xᵢ(t) / Σ wᵢ`
    /// (NaN when the runs added weigh nothing).
    pub fn mean(&self, k: usize) -> Vec<f64> {
        let w = self.total_weight;
        let mean = |s: &f64| if w > 0.0 { s / w } else { f64::NAN };
        self.channels[k].weighted_sum.iter().map(mean).collect()
    }
}

fn different_times(run: usize, t: &[f64], first: usize, first_t: &[f64]) -> String {
    let describe = |t: &[f64]| match t.last() {
        Some(end) => format!("{} samples to {end} s", t.len()),
        None => "no samples".to_string(),
    };
    format!(
        "--envelope: run {run} has other output times ({}) than run {first} ({}); envelopes need every run on the same times (do not sweep the end time or the output interval)",
        describe(t),
        describe(first_t)
    )
}

/// What [`stream_envelope`] needs beyond the runs: the channels and the
/// weight of each run.
#[derive(Clone, Copy, Debug)]
pub struct EnvelopeJob<'a> {
    /// The channels to envelope, read against the scenario's names.
    pub channels: &'a [Signal],
    /// The weight of each run in the mean.
    pub weights: &'a Weights,
}

/// One run simulated in full: its row, and its channels' histories when it
/// finished.
fn run_with_history<const N: usize, S: LagrangianSystem<N> + Clone>(
    model: &S,
    job: &SweepJob<'_>,
    shared: Option<&SharedScenario>,
    run: usize,
    channels: &[Signal],
) -> (Row, Option<History>) {
    let values = job.plan.point(run);
    let result = scenario_of(job, shared, &values)
        .and_then(|scenario| simulate(model, &scenario).map_err(|e| simulation_failure(&e)));
    let (outcome, history) = match result {
        Ok(result) => (
            Ok(result.summary.clone()),
            Some(History::of(&result, channels)),
        ),
        Err(failure) => (Err(failure), None),
    };
    let row = Row {
        run,
        values,
        outcome,
    };
    (row, history)
}

/// [`super::stream_sweep`] that also adds every finished run to
/// `envelope`, in run order, with its weight from `what.weights`. Failed
/// runs have no history and stay out of the envelope.
pub fn stream_envelope<const N: usize, S>(
    system: &S,
    job: SweepJob<'_>,
    what: EnvelopeJob<'_>,
    envelope: &mut Envelope,
    stop: &AtomicBool,
    sink: &mut dyn FnMut(Row) -> Result<(), String>,
) -> Result<usize, String>
where
    S: LagrangianSystem<N> + Clone + Send,
{
    let plan: &Plan = job.plan;
    let make = |model: &S, job: &SweepJob<'_>, shared: Option<&SharedScenario>, run: usize| {
        run_with_history(model, job, shared, run, what.channels)
    };
    stream_runs(system, job, stop, &make, &mut |(row, history)| {
        if let Some(history) = &history {
            envelope.add(row.run, what.weights.of_run(plan, row.run), history)?;
        }
        sink(row)
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn history(t: &[f64], x: &[f64]) -> History {
        History {
            t: t.to_vec(),
            values: vec![x.to_vec()],
        }
    }

    fn envelope() -> Envelope {
        let names = crate::scenario::ModelNames {
            coordinates: vec!["x".into()],
            ..Default::default()
        };
        Envelope::new(&[Signal::parse("--envelope", "x", &names).unwrap()])
    }

    #[test]
    fn extremes_keep_the_first_run_attaining_them_and_the_mean_is_weighted() {
        let mut e = envelope();
        let t = [0.0, 0.1, 0.2];
        e.add(3, 1.0, &history(&t, &[1.0, 5.0, f64::NAN])).unwrap();
        e.add(4, 3.0, &history(&t, &[1.0, -1.0, 2.0])).unwrap();
        let c = &e.channels[0];
        assert_eq!(c.max[..2], [1.0, 5.0]);
        assert_eq!(c.max_run, [Some(3), Some(3), Some(4)]);
        assert_eq!(c.min_run, [Some(3), Some(4), Some(4)]);
        assert_eq!(
            (c.max[2], c.min[2]),
            (2.0, 2.0),
            "NaN takes no part in extremes"
        );
        assert_eq!(e.mean(0)[..2], [1.0, 0.5]);
        assert!(e.mean(0)[2].is_nan(), "the sum shows a NaN");
        assert_eq!((e.runs, e.total_weight), (2, 4.0));
    }

    #[test]
    fn a_run_on_other_output_times_is_an_error_naming_both_runs() {
        let mut e = envelope();
        e.add(0, 1.0, &history(&[0.0, 0.1], &[1.0, 2.0])).unwrap();
        let error = e.add(1, 1.0, &history(&[0.0], &[1.0])).unwrap_err();
        assert!(
            error.contains(
                "run 1 has other output times (1 samples to 0 s) than run 0 (2 samples to 0.1 s)"
            ),
            "{error}"
        );
    }
}
