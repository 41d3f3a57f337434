//! Envelopes of a sweep: for chosen channels, on the runs' common output
//! times, the pointwise maximum and minimum over the runs (with the run
//! attaining each) and the weighted mean history `Σ wᵢ xᵢ(t) / Σ wᵢ`.
//!
//! An [`Envelope`] takes the runs one at a time ([`Envelope::add`]) and
//! keeps only its accumulators — memory grows with the output times and
//! the channels, not with the runs. Envelopes of disjoint sets of runs
//! combine ([`Envelope::merge`]). Neither depends on the order of the runs:
//! an extreme keeps the lowest run attaining it, and the sums are exact
//! ([`ExactSum`]) and rounded once, so one run, any number of threads and
//! any split into shards merged in any order give the same bits.

use super::exact_sum::ExactSum;
use super::plan::Plan;
use super::run::{Row, SweepJob, scenario_of, simulation_failure, stream_runs};
use super::shared::SharedScenario;
use super::weights::Weights;
use lagrangian_runtime::LagrangianSystem;
use lagrangian_sim::scenario::Signal;
use lagrangian_sim::simulate::{SimulationResult, simulate};

/// Why runs, or envelopes, do not add into one envelope.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum EnvelopeError {
    /// A run (or the first run of an envelope merged) on other output
    /// times than the runs added before.
    #[error(
        "--envelope: run {run} has other output times ({times}) than run {first} ({first_times}); envelopes need every run on the same times (do not sweep the end time or the output interval)"
    )]
    OtherTimes {
        /// The run added.
        run: usize,
        /// Its output times.
        times: Times,
        /// The lowest run added before.
        first: usize,
        /// Its output times.
        first_times: Times,
    },
    /// An envelope of other channels merged.
    #[error(
        "--envelope: the channels {} cannot merge with {}",
        .theirs.join(","),
        .ours.join(",")
    )]
    OtherChannels {
        /// The channels of the envelope merged.
        theirs: Vec<String>,
        /// The channels of the envelope merged into.
        ours: Vec<String>,
    },
}

/// Output times in a message: how many, and the last.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Times {
    /// How many output times.
    pub samples: usize,
    /// The last \[s\]; `None` for none.
    pub end: Option<f64>,
}

impl Times {
    fn of(t: &[f64]) -> Times {
        Times {
            samples: t.len(),
            end: t.last().copied(),
        }
    }
}

impl std::fmt::Display for Times {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self.end {
            Some(end) => write!(f, "{} samples to {end} s", self.samples),
            None => f.write_str("no samples"),
        }
    }
}

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
                let at = |s: &lagrangian_sim::simulate::Sample| signal.value(&s.columns());
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
    /// The lowest run attaining `max`; `None` where no run has a finite
    /// value.
    pub max_run: Vec<Option<usize>>,
    /// The smallest value over the runs.
    pub min: Vec<f64>,
    /// The lowest run attaining `min`.
    pub min_run: Vec<Option<usize>>,
    /// `Σ wᵢ xᵢ(t)`, exact.
    pub weighted_sum: Vec<ExactSum>,
}

/// Whether a candidate value beats the kept one (`>` for a maximum).
type Beats = fn(f64, f64) -> bool;

/// Keeps `(x, run)` in `(value, at)` if `x` beats the value kept, or
/// equals it from a lower run: the result does not depend on the order
/// the candidates come in.
fn keep(value: &mut f64, at: &mut Option<usize>, x: f64, run: usize, beats: Beats) {
    let better = match *at {
        None => true,
        Some(kept) => beats(x, *value) || (x == *value && run < kept),
    };
    if better {
        (*value, *at) = (x, Some(run));
    }
}

impl ChannelEnvelope {
    /// The accumulators of channel `name` over `points` output times, with
    /// no run yet.
    pub fn new(name: &str, points: usize) -> ChannelEnvelope {
        ChannelEnvelope {
            name: name.to_string(),
            max: vec![f64::NAN; points],
            max_run: vec![None; points],
            min: vec![f64::NAN; points],
            min_run: vec![None; points],
            weighted_sum: vec![ExactSum::new(); points],
        }
    }

    /// Takes run `run`'s values `x` with weight `w`. Non-finite values
    /// take no part in the extremes (the sum shows them).
    fn add(&mut self, run: usize, w: f64, x: &[f64]) {
        for (k, &x) in x.iter().enumerate() {
            if x.is_finite() {
                keep(&mut self.max[k], &mut self.max_run[k], x, run, |a, b| a > b);
                keep(&mut self.min[k], &mut self.min_run[k], x, run, |a, b| a < b);
            }
            self.weighted_sum[k].add_product(w, x);
        }
    }

    /// Takes the accumulators of `other`, over other runs on the same
    /// output times.
    fn merge(&mut self, other: &ChannelEnvelope) {
        for k in 0..self.max.len() {
            if let Some(run) = other.max_run[k] {
                keep(
                    &mut self.max[k],
                    &mut self.max_run[k],
                    other.max[k],
                    run,
                    |a, b| a > b,
                );
            }
            if let Some(run) = other.min_run[k] {
                keep(
                    &mut self.min[k],
                    &mut self.min_run[k],
                    other.min[k],
                    run,
                    |a, b| a < b,
                );
            }
            self.weighted_sum[k].merge(&other.weighted_sum[k]);
        }
    }
}

/// The envelopes of a sweep's channels, accumulated run by run.
#[derive(Clone, Debug, PartialEq)]
pub struct Envelope {
    /// The output times every run shares (those of the first run added).
    pub t: Vec<f64>,
    /// One per channel, in the order given; none before the first run.
    pub channels: Vec<ChannelEnvelope>,
    /// `Σ wᵢ` over the runs added, exact.
    pub total_weight: ExactSum,
    /// How many runs were added.
    pub runs: usize,
    /// The lowest run added, whose output times the others must share.
    first_run: Option<usize>,
    names: Vec<String>,
}

impl Envelope {
    /// An envelope of `channels` with no run yet.
    pub fn new(channels: &[Signal]) -> Envelope {
        let names: Vec<String> = channels.iter().map(|s| s.name.clone()).collect();
        Envelope::named(names)
    }

    /// An envelope of the channels called `names` with no run yet.
    pub fn named(names: Vec<String>) -> Envelope {
        Envelope {
            t: Vec::new(),
            channels: Vec::new(),
            total_weight: ExactSum::new(),
            runs: 0,
            first_run: None,
            names,
        }
    }

    /// The channels' names, in the order given.
    pub fn names(&self) -> &[String] {
        &self.names
    }

    /// The lowest run added; `None` before the first.
    pub fn first_run(&self) -> Option<usize> {
        self.first_run
    }

    /// Adds run `run` with weight `weight`; its output times must be those
    /// of the runs added before.
    pub fn add(&mut self, run: usize, weight: f64, history: &History) -> Result<(), EnvelopeError> {
        match self.first_run {
            None => self.start(&history.t),
            Some(first) if history.t != self.t => {
                return Err(different_times(run, &history.t, first, &self.t));
            }
            Some(_) => {}
        }
        for (channel, x) in self.channels.iter_mut().zip(&history.values) {
            channel.add(run, weight, x);
        }
        self.total_weight.add(weight);
        self.runs += 1;
        self.first_run = Some(self.first_run.map_or(run, |first| first.min(run)));
        Ok(())
    }

    /// The accumulators over the output times `t`, with no run yet.
    fn start(&mut self, t: &[f64]) {
        self.t = t.to_vec();
        self.channels = (self.names.iter())
            .map(|name| ChannelEnvelope::new(name, t.len()))
            .collect();
    }

    /// Adds the runs of `other`, an envelope of the same channels over
    /// other runs: the result is that of adding its runs one by one.
    pub fn merge(&mut self, other: &Envelope) -> Result<(), EnvelopeError> {
        if other.names != self.names {
            return Err(EnvelopeError::OtherChannels {
                theirs: other.names.clone(),
                ours: self.names.clone(),
            });
        }
        let Some(other_first) = other.first_run else {
            return Ok(());
        };
        match self.first_run {
            None => self.start(&other.t),
            Some(first) if other.t != self.t => {
                return Err(different_times(other_first, &other.t, first, &self.t));
            }
            Some(_) => {}
        }
        for (channel, theirs) in self.channels.iter_mut().zip(&other.channels) {
            channel.merge(theirs);
        }
        self.total_weight.merge(&other.total_weight);
        self.runs += other.runs;
        self.first_run = Some(self.first_run.map_or(other_first, |f| f.min(other_first)));
        Ok(())
    }

    /// An envelope of `names` from its accumulators (as a partial
    /// envelope's file holds them); `first_run` is `None` for no run.
    pub fn restore(
        names: Vec<String>,
        accumulated: Accumulated,
        first_run: Option<usize>,
    ) -> Envelope {
        Envelope {
            t: accumulated.t,
            channels: accumulated.channels,
            total_weight: accumulated.total_weight,
            runs: accumulated.runs,
            first_run,
            names,
        }
    }

    /// The weighted mean history of channel `k`: `Σ wᵢ xᵢ(t) / Σ wᵢ`, each
    /// sum rounded once (NaN when the runs added weigh nothing).
    pub fn mean(&self, k: usize) -> Vec<f64> {
        let w = self.total_weight.value();
        let mean = |s: &ExactSum| if w > 0.0 { s.value() / w } else { f64::NAN };
        self.channels[k].weighted_sum.iter().map(mean).collect()
    }
}

/// What [`Envelope::restore`] restores.
#[derive(Clone, Debug)]
pub struct Accumulated {
    /// The output times (empty for no run).
    pub t: Vec<f64>,
    /// One per channel (none for no run).
    pub channels: Vec<ChannelEnvelope>,
    /// `Σ wᵢ`.
    pub total_weight: ExactSum,
    /// How many runs were added.
    pub runs: usize,
}

fn different_times(run: usize, t: &[f64], first: usize, first_t: &[f64]) -> EnvelopeError {
    EnvelopeError::OtherTimes {
        run,
        times: Times::of(t),
        first,
        first_times: Times::of(first_t),
    }
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
/// runs have no history and stay out of the envelope. `sink` sees each row
/// with the envelope that holds every run up to it. An error of `sink`, or
/// a run whose output times are not those of the runs before, ends it.
pub fn stream_envelope<const N: usize, S, E: From<EnvelopeError>>(
    system: &S,
    job: SweepJob<'_>,
    what: EnvelopeJob<'_>,
    envelope: &mut Envelope,
    stop: &(dyn Fn() -> bool + Sync),
    sink: &mut dyn FnMut(Row, &Envelope) -> Result<(), E>,
) -> Result<usize, E>
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
        sink(row, envelope)
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
        let names = lagrangian_sim::scenario::ModelNames {
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
        assert_eq!((e.runs, e.total_weight.value()), (2, 4.0));
    }

    /// Runs 0..5 of one channel at three output times, with ties.
    fn runs() -> Vec<(usize, f64, History)> {
        let t = [0.0, 0.1, 0.2];
        let x = [
            [0.1, 2.0, -1.0],
            [0.2, 2.0, 1e20],
            [0.3, -3.0, f64::NAN],
            [0.1, 2.0, -1e20],
            [0.7, -3.0, 1.0],
        ];
        let w = [0.2, 0.5, 0.3, 0.1, 0.7];
        (0..5).map(|k| (k, w[k], history(&t, &x[k]))).collect()
    }

    fn of(runs: &[(usize, f64, History)]) -> Envelope {
        let mut e = envelope();
        for (run, w, h) in runs {
            e.add(*run, *w, h).unwrap();
        }
        e
    }

    #[test]
    fn any_order_and_any_split_merged_in_any_order_give_the_same_envelope() {
        let runs = runs();
        let whole = of(&runs);
        let c = &whole.channels[0];
        assert_eq!(
            c.max_run,
            [Some(4), Some(0), Some(1)],
            "ties: the lowest run"
        );
        assert_eq!(c.min_run, [Some(0), Some(2), Some(3)]);
        let mut reversed = runs.clone();
        reversed.reverse();
        assert_eq!(of(&reversed), whole);
        let parts = [of(&runs[..2]), of(&runs[2..3]), of(&runs[3..]), of(&[])];
        for order in [[0, 1, 2, 3], [3, 2, 0, 1], [1, 3, 2, 0]] {
            let mut merged = envelope();
            for k in order {
                merged.merge(&parts[k]).unwrap();
            }
            assert_eq!(merged, whole, "order {order:?}");
        }
    }

    #[test]
    fn the_mean_is_the_exact_weighted_sum_rounded_once() {
        let t = [0.0, 0.1];
        let mut e = envelope();
        for (run, x) in [(0, [1e20, 0.5]), (1, [1.0, 0.25]), (2, [-1e20, 0.25])] {
            e.add(run, 1.0, &history(&t, &x)).unwrap();
        }
        // Added in order, 1e20 + 1 − 1e20 would be 0.
        assert_eq!(e.mean(0), [1.0 / 3.0, 1.0 / 3.0]);
        assert!(of(&runs()).mean(0)[2].is_nan(), "run 2's NaN shows");
    }

    #[test]
    fn merging_other_channels_or_other_times_is_an_error() {
        let mut e = of(&runs()[..1]);
        let mut other = Envelope::named(vec!["y".into()]);
        assert!(
            e.merge(&other)
                .unwrap_err()
                .to_string()
                .contains("the channels y")
        );
        other = envelope();
        other.add(7, 1.0, &history(&[0.0], &[1.0])).unwrap();
        let error = e.merge(&other).unwrap_err().to_string();
        assert!(error.contains("run 7 has other output times"), "{error}");
    }

    #[test]
    fn a_run_on_other_output_times_is_an_error_naming_both_runs() {
        let mut e = envelope();
        e.add(0, 1.0, &history(&[0.0, 0.1], &[1.0, 2.0])).unwrap();
        let error = e
            .add(1, 1.0, &history(&[0.0], &[1.0]))
            .unwrap_err()
            .to_string();
        assert!(
            error.contains(
                "run 1 has other output times (1 samples to 0 s) than run 0 (2 samples to 0.1 s)"
            ),
            "{error}"
        );
    }
}
