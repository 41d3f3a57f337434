//! A sweep's envelopes (`lpm sweep --envelope`): the options that ask for
//! envelopes and weighted mean histories of chosen channels, what they are
//! read into, and the files they write.
//!
//! A whole sweep writes the envelope table (and plot). A shard writes its
//! partial envelope beside its table (`part.csv.envelope.json`), which
//! `--merge` finds beside each part and combines. While the runs go on, the
//! partial envelope of the runs finished so far is saved beside the
//! journal (`OUT.partial.envelope.json`) every few seconds and when the
//! sweep stops, so that `--resume` carries on from it; the runs the journal
//! holds beyond it are made again for their histories.

use super::{Prepared, SweepRequest, write_beside};
use crate::error::StudyError;
use crate::plot::{Band, bands_svg};
use crate::sweep::{
    Envelope, EnvelopeJob, PartialEnvelope, Plan, Shard, SweepMark, Weights, merged_envelope,
    partial_envelope_path, run_scenario, write_envelope_csv, write_envelope_parquet,
};
use lagrangian_sim::scenario::Signal;
use std::ops::Range;
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

/// The envelopes a sweep is asked for (`lpm sweep --envelope` and the
/// flags beside it).
#[derive(Clone, Debug, Default)]
pub struct EnvelopeOptions {
    /// Channels to envelope: columns of trajectory.csv or combinations as
    /// `[metrics]` writes them (`"xa - xb"`); none: no envelope.
    pub envelope: Vec<String>,
    /// The envelope table: .csv or .parquet (a shard writes its partial
    /// envelope beside its table instead).
    pub envelope_out: Option<PathBuf>,
    /// The envelope plot (SVG).
    pub envelope_plot: Option<PathBuf>,
    /// The runs' weights in the mean: `KEY=W1,W2,…` or a CSV file with
    /// columns run,weight; `None`: equal.
    pub weights: Option<String>,
}

/// What `--envelope` and its flags ask for, read and checked.
pub(super) struct EnvelopeRequest {
    /// The channels, read against the scenario's names.
    pub channels: Vec<Signal>,
    /// The weight of each run.
    pub weights: Weights,
    /// The table's file (`None` in memory, for the Python package).
    out: Option<PathBuf>,
    plot: Option<PathBuf>,
}

impl EnvelopeRequest {
    /// What the accumulation needs.
    pub fn job(&self) -> EnvelopeJob<'_> {
        EnvelopeJob {
            channels: &self.channels,
            weights: &self.weights,
        }
    }

    /// The channels' names, as given.
    pub fn names(&self) -> Vec<String> {
        self.channels.iter().map(|s| s.name.clone()).collect()
    }
}

/// The envelope request of `options`, `None` without `--envelope`.
pub(super) fn request(
    options: &SweepRequest,
    prepared: &Prepared,
) -> Result<Option<EnvelopeRequest>, StudyError> {
    let args = &options.envelope;
    if args.envelope.is_empty() {
        return Ok(None);
    }
    let out = args.envelope_out.clone();
    if let Some(out) = &out {
        table_is_parquet(out)?;
    }
    let channels = channels(&args.envelope, prepared)?;
    let weights = match &args.weights {
        None => Weights::Equal,
        Some(text) => weights(text, prepared)?,
    };
    let plot = args.envelope_plot.clone();
    Ok(Some(EnvelopeRequest {
        channels,
        weights,
        out,
        plot,
    }))
}

/// Whether the envelope table is Parquet, from its extension.
fn table_is_parquet(out: &Path) -> Result<bool, StudyError> {
    match out.extension().and_then(|e| e.to_str()) {
        Some("parquet") => Ok(true),
        Some("csv") => Ok(false),
        _ => Err(StudyError::usage(format!(
            "--envelope-out {}: name a .csv or .parquet file",
            out.display()
        ))),
    }
}

/// The channels of `--envelope`, read against the names of the first
/// run's scenario (its components' columns included).
fn channels(names: &[String], prepared: &Prepared) -> Result<Vec<Signal>, StudyError> {
    let Prepared {
        plan,
        base,
        settings,
        ..
    } = prepared;
    let first = match plan.is_empty() {
        false => run_scenario(base, settings, &plan.point(0)),
        true => base.resolve(&[]),
    };
    let first = first.map_err(|e| StudyError::scenario(&e))?;
    let names_of_run = base.names.with_components(&first.inputs);
    (names.iter())
        .map(|name| {
            Signal::parse("--envelope", name, &names_of_run)
                .map_err(|e| StudyError::usage(e.to_string()))
        })
        .collect()
}

/// `--weights`: per grid value, or per run from a CSV file.
fn weights(text: &str, prepared: &Prepared) -> Result<Weights, StudyError> {
    if text.contains('=') {
        return Ok(Weights::per_value(text, &prepared.plan)?);
    }
    let file = (prepared.base.files.text(std::path::Path::new(text)))
        .map_err(|e| StudyError::io(format!("--weights: cannot read {text}: {e}")))?;
    Ok(Weights::per_run_csv(&file, text, &prepared.plan)?)
}

/// Writes the envelope table (whole or not at all) and the plot; returns
/// the line `lpm sweep` reports them with.
pub(super) fn write(request: &EnvelopeRequest, envelope: &Envelope) -> Result<String, StudyError> {
    let Some(out) = &request.out else {
        return Ok(String::new());
    };
    let parquet = table_is_parquet(out)?;
    write_beside(out, |file| match parquet {
        true => Ok(write_envelope_parquet(envelope, file)?),
        false => Ok(write_envelope_csv(envelope, file)?),
    })?;
    let mut line = format!(
        "envelope of {} runs: wrote {}",
        envelope.runs,
        out.display()
    );
    if let Some(plot) = &request.plot {
        let svg = bands_svg("Envelopes over the runs", &bands(envelope))
            .map_err(|e| StudyError::io(e.to_string()))?;
        lagrangian_sim::report::write_atomically(plot, svg.as_bytes())
            .map_err(|e| StudyError::io(format!("cannot write {}: {e}", plot.display())))?;
        line.push_str(&format!(" and {}", plot.display()));
    }
    line.push('\n');
    Ok(line)
}

/// One band per channel of the envelope.
fn bands(envelope: &Envelope) -> Vec<Band> {
    (envelope.channels.iter().enumerate())
        .map(|(k, channel)| Band {
            name: channel.name.clone(),
            t: envelope.t.clone(),
            min: channel.min.clone(),
            max: channel.max.clone(),
            mean: envelope.mean(k),
        })
        .collect()
}

/// How often the partial envelope of a sweep under way is saved.
const CHECKPOINT_EVERY: Duration = Duration::from_secs(2);

/// The partial envelope of a sweep under way, saved beside its journal.
pub(super) struct Checkpoints<'r> {
    plan: &'r Plan,
    weights: &'r Weights,
    path: PathBuf,
    /// The mark of the runs held.
    mark: SweepMark,
    block: Range<usize>,
    /// How many runs of the block, from its first, the envelope holds.
    done: usize,
    saved: Instant,
}

/// What a sweep does after each row it adds to its envelope.
pub(super) trait AfterRow {
    /// Run `run` is done and `envelope` holds every run up to it.
    fn after(&mut self, run: usize, envelope: &Envelope) -> Result<(), StudyError>;
}

impl AfterRow for Checkpoints<'_> {
    /// Takes the run into the mark; saves the envelope when the last save
    /// is a while ago.
    fn after(&mut self, run: usize, envelope: &Envelope) -> Result<(), StudyError> {
        self.mark.take(self.plan, self.weights, run);
        self.done = run + 1 - self.block.start;
        match self.saved.elapsed() >= CHECKPOINT_EVERY {
            true => self.save(envelope, &self.path.clone()),
            false => Ok(()),
        }
    }
}

impl Checkpoints<'_> {
    /// Writes the partial envelope to `path` (whole or not at all).
    fn save(&mut self, envelope: &Envelope, path: &Path) -> Result<(), StudyError> {
        let partial = PartialEnvelope {
            mark: self.mark.clone(),
            block: self.block.clone(),
            done: self.done,
            envelope: envelope.clone(),
        };
        write_beside(path, |file| Ok(partial.write(file)?))?;
        self.saved = Instant::now();
        Ok(())
    }
}

/// The envelope of a sweep under way and where it is saved.
pub(super) struct Tracked<'r> {
    request: &'r EnvelopeRequest,
    /// The runs accumulated so far.
    pub envelope: Envelope,
    /// Its saves beside the journal.
    pub checkpoints: Checkpoints<'r>,
}

impl<'r> Tracked<'r> {
    /// The envelope of the runs `block` of `plan` to accumulate beside the
    /// journal `journal`: when resuming a journal of `resume` runs, the one
    /// saved there (if it holds no more runs than the journal), else an
    /// empty one.
    pub fn start(
        request: &'r EnvelopeRequest,
        plan: &'r Plan,
        block: &Range<usize>,
        journal: &Path,
        resume: Option<usize>,
    ) -> Result<Tracked<'r>, StudyError> {
        let names = request.names();
        let path = partial_envelope_path(journal);
        let saved = match resume {
            Some(journaled) if path.exists() => {
                let saved = PartialEnvelope::read(&path, plan, &names, &request.weights)
                    .map_err(|e| StudyError::data_file(format!("--resume: {e}")))?;
                (saved.block == *block && saved.done <= journaled).then_some(saved)
            }
            _ => None,
        };
        let (envelope, done, mark) = match saved {
            Some(saved) => (saved.envelope, saved.done, saved.mark),
            None => {
                let mark = SweepMark::empty(plan, &names);
                (Envelope::named(names), 0, mark)
            }
        };
        let checkpoints = Checkpoints {
            plan,
            weights: &request.weights,
            path,
            mark,
            block: block.clone(),
            done,
            saved: Instant::now(),
        };
        Ok(Tracked {
            request,
            envelope,
            checkpoints,
        })
    }

    /// What the sweep accumulates into, saving it now and then.
    pub(super) fn streaming(&mut self) -> super::Enveloping<'_> {
        super::Enveloping {
            job: self.request.job(),
            envelope: &mut self.envelope,
            after: Some(&mut self.checkpoints),
        }
    }

    /// How many runs of the block, from its first, the envelope holds.
    pub fn done(&self) -> usize {
        self.checkpoints.done
    }

    /// Saves the envelope beside the journal (a sweep that stops).
    pub fn save(&mut self) -> Result<(), StudyError> {
        let path = self.checkpoints.path.clone();
        self.checkpoints.save(&self.envelope, &path)
    }

    /// The envelope's files once every run is done: the table and plot of
    /// a whole sweep, or a shard's partial envelope beside its table
    /// `out`; returns the line reporting them.
    pub fn finish(&mut self, shard: Shard, out: &Path) -> Result<String, StudyError> {
        if shard == Shard::ALL {
            return write(self.request, &self.envelope);
        }
        let partial = partial_envelope_path(out);
        self.checkpoints.save(&self.envelope, &partial)?;
        Ok(format!(
            "partial envelope of {} runs: wrote {} (--merge the shards for the envelope)\n",
            self.envelope.runs,
            partial.display()
        ))
    }

    /// Removes the envelope saved beside the journal (the sweep is done).
    pub fn remove_checkpoint(&self) -> Result<(), StudyError> {
        let path = &self.checkpoints.path;
        match path.exists() {
            true => std::fs::remove_file(path)
                .map_err(|e| StudyError::io(format!("cannot remove {}: {e}", path.display()))),
            false => Ok(()),
        }
    }
}

/// `--merge` with `--envelope`: the partial envelopes beside the shards'
/// tables `parts`, merged into the envelope of the whole sweep.
pub(super) fn merged(
    request: &EnvelopeRequest,
    parts: &[PathBuf],
    prepared: &Prepared,
) -> Result<Envelope, StudyError> {
    let mut paths = Vec::new();
    for part in parts {
        let path = partial_envelope_path(part);
        if !path.exists() {
            return Err(StudyError::data_file(format!(
                "--envelope: {} is missing: the shard that wrote {} ran without --envelope; run it again with this sweep's --envelope flags",
                path.display(),
                part.display()
            )));
        }
        paths.push(path);
    }
    Ok(merged_envelope(
        &paths,
        &prepared.plan,
        &request.names(),
        &request.weights,
    )?)
}

/// `text` of a merge with the line of the envelope's files appended.
pub(super) fn with_merged(
    text: String,
    request: &EnvelopeRequest,
    envelope: &Envelope,
) -> Result<String, StudyError> {
    let line = write(request, envelope)?;
    Ok(text + &line)
}

/// The partial envelope of the runs `block` of `plan` (all done) as the
/// JSON bytes a shard writes beside its table.
pub(super) fn partial_json(
    request: &EnvelopeRequest,
    plan: &Plan,
    block: &Range<usize>,
    envelope: Envelope,
) -> Result<Vec<u8>, StudyError> {
    let partial = PartialEnvelope {
        mark: SweepMark::of(plan, &request.names(), &request.weights, block),
        block: block.clone(),
        done: block.len(),
        envelope,
    };
    let mut bytes = Vec::new();
    partial.write(&mut bytes)?;
    Ok(bytes)
}
