//! A partial envelope on disk: the accumulators of an [`Envelope`] over a
//! block of a sweep's runs — a shard's, or the runs a stopped sweep has
//! finished — that merge with the other blocks' into the envelope of the
//! whole sweep, bit for bit that of one run.
//!
//! The file is JSON (`"format": "lagrangian-sweep-envelope"`, `"version":
//! 1`). Besides the accumulators it says which sweep it belongs to: the
//! plan's run count and axes, a digest of the values of the runs it holds,
//! the channels and a digest of those runs' weights. Reading it against another sweep
//! is an error that names the file and what differs. Numbers are written
//! as Rust's shortest round-tripping text (`"0.1"`, `"NaN"`), read back
//! exactly; an exact sum is its [`ExactSum::terms`].

use super::envelope::{Accumulated, ChannelEnvelope, Envelope, EnvelopeError};
use super::exact_sum::ExactSum;
use super::plan::Plan;
use super::weights::Weights;
use serde::{Deserialize, Serialize};
use std::io::Write;
use std::ops::Range;
use std::path::{Path, PathBuf};

/// The `format` entry of every partial envelope.
pub const ENVELOPE_FORMAT: &str = "lagrangian-sweep-envelope";

/// The version this code writes and reads.
pub const ENVELOPE_VERSION: u32 = 1;

/// Why a partial envelope cannot be written, read, or merged into the
/// envelope of the whole sweep.
#[derive(Debug, thiserror::Error)]
pub enum EnvelopeFileError {
    /// The JSON cannot be written.
    #[error("cannot write the envelope: {0}")]
    Write(#[source] serde_json::Error),
    /// A partial envelope that cannot be read, or does not belong to this
    /// sweep or merge with the others.
    #[error("{}: {problem}", .path.display())]
    File {
        /// The file.
        path: PathBuf,
        /// What is wrong with it.
        problem: FileProblem,
    },
    /// Runs in none of the partial envelopes.
    #[error(
        "--envelope: runs {from}..{to} (of {total}) are in no part's envelope: give every shard's table, each with its envelope beside it"
    )]
    Missing {
        /// The first run missing.
        from: usize,
        /// The run after the last missing.
        to: usize,
        /// The plan's number of runs.
        total: usize,
    },
}

/// What is wrong with a partial envelope ([`EnvelopeFileError::File`]).
#[derive(Debug, thiserror::Error)]
pub enum FileProblem {
    /// The file cannot be read.
    #[error("cannot read: {0}")]
    Read(#[source] std::io::Error),
    /// The file is not JSON with a format and a version.
    #[error("not a partial envelope of lpm sweep: {0}")]
    NotJson(#[source] serde_json::Error),
    /// JSON of another format.
    #[error("not a partial envelope of lpm sweep (its format is {format:?}, not {expected:?})", expected = ENVELOPE_FORMAT)]
    Format {
        /// The file's `format`.
        format: String,
    },
    /// A version this code does not read.
    #[error(
        "version {} of the envelope file; this lpm reads version {expected}",
        .version.map_or("none".to_string(), |v| v.to_string()),
        expected = ENVELOPE_VERSION
    )]
    Version {
        /// The file's `version`.
        version: Option<u32>,
    },
    /// The entries after the format and version do not read.
    #[error("cannot read the envelope: {0}")]
    Json(#[source] serde_json::Error),
    /// A block of runs that is not in the sweep.
    #[error("runs {start}..{end} ({done} done) are not a block of this sweep's {runs} runs")]
    NotABlock {
        /// The block's first run.
        start: usize,
        /// The run after its last.
        end: usize,
        /// How many of its runs are done.
        done: usize,
        /// The sweep's runs.
        runs: usize,
    },
    /// The file belongs to another sweep.
    #[error("not a part of this sweep: {0}")]
    OtherSweep(MarkDifference),
    /// A number written as text that does not read back.
    #[error("`{text}` is not a number")]
    NotANumber {
        /// The text.
        text: String,
    },
    /// A channel without one entry per output time.
    #[error("channel {channel} does not have one entry per output time ({points})")]
    Entries {
        /// The channel.
        channel: String,
        /// The output times.
        points: usize,
    },
    /// Accumulators of other channels than the file's.
    #[error("its accumulators are not those of its channels")]
    Accumulators,
    /// A block its shard did not finish.
    #[error(
        "holds {done} of the runs {start}..{end}: its shard did not finish (run it again with --resume)"
    )]
    Unfinished {
        /// How many runs are done.
        done: usize,
        /// The block's first run.
        start: usize,
        /// The run after its last.
        end: usize,
    },
    /// Runs that an earlier file holds too.
    #[error(
        "runs {start}..{end} are also in {}: give each shard once",
        .previous.as_ref().map_or(String::new(), |p| p.display().to_string())
    )]
    Overlap {
        /// The first run held twice.
        start: usize,
        /// The run after the last held twice.
        end: usize,
        /// The file that holds them too.
        previous: Option<PathBuf>,
    },
    /// An envelope that does not merge with the others.
    #[error("{0}")]
    Merge(#[source] EnvelopeError),
}

/// How a partial envelope's sweep differs from the sweep at hand.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum MarkDifference {
    /// Another number of runs, or other axes.
    #[error(
        "it belongs to a sweep of {runs} runs over {}, this one has {expected_runs} runs over {}",
        .axes.join(", "),
        .expected_axes.join(", ")
    )]
    Plan {
        /// The file's plan's runs.
        runs: usize,
        /// The file's plan's axes.
        axes: Vec<String>,
        /// This sweep's runs.
        expected_runs: usize,
        /// This sweep's axes.
        expected_axes: Vec<String>,
    },
    /// The runs held have other values.
    #[error(
        "its runs have other values than this sweep's (another --grid, --samples, --vary, --design or --seed)"
    )]
    Values,
    /// Other channels.
    #[error("its channels are {}, this sweep's {}", .channels.join(","), .expected.join(","))]
    Channels {
        /// The file's channels.
        channels: Vec<String>,
        /// This sweep's channels.
        expected: Vec<String>,
    },
    /// The runs held have other weights.
    #[error("its runs have other --weights than this sweep's")]
    Weights,
}

/// The partial envelope beside a table: `part-1.csv` →
/// `part-1.csv.envelope.json`.
pub fn partial_envelope_path(table: &Path) -> PathBuf {
    let mut name = table.file_name().unwrap_or_default().to_os_string();
    name.push(".envelope.json");
    table.with_file_name(name)
}

/// The sweep a partial envelope belongs to, as far as the runs it holds
/// show.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct SweepMark {
    /// The plan's number of runs.
    pub plan_runs: usize,
    /// The plan's axes (table columns).
    pub axes: Vec<String>,
    /// A digest of the plan's values for the runs held.
    pub values: String,
    /// The channels, as given.
    pub channels: Vec<String>,
    /// A digest of the weights of the runs held.
    pub weights: String,
}

impl SweepMark {
    /// The mark of `plan`, `channels` and `weights` over the runs `held`.
    pub fn of(plan: &Plan, channels: &[String], weights: &Weights, held: &Range<usize>) -> Self {
        let mut mark = SweepMark::empty(plan, channels);
        for run in held.clone() {
            mark.take(plan, weights, run);
        }
        mark
    }

    /// The mark of `plan` and `channels` over no run.
    pub fn empty(plan: &Plan, channels: &[String]) -> SweepMark {
        SweepMark {
            plan_runs: plan.len(),
            axes: plan.axes().iter().map(|a| a.column()).collect(),
            values: Digest::new().hex(),
            channels: channels.to_vec(),
            weights: Digest::new().hex(),
        }
    }

    /// Takes run `run` (the next after those held) into the digests.
    pub fn take(&mut self, plan: &Plan, weights: &Weights, run: usize) {
        let mut values = Digest::from_hex(&self.values);
        plan.point(run).iter().for_each(|x| values.add(x.to_bits()));
        let mut weighed = Digest::from_hex(&self.weights);
        weighed.add(weights.of_run(plan, run).to_bits());
        (self.values, self.weights) = (values.hex(), weighed.hex());
    }

    /// What differs between this mark (of a file) and `expected` (of the
    /// sweep at hand); `None` when they agree.
    fn difference(&self, expected: &SweepMark) -> Option<MarkDifference> {
        if (self.plan_runs, &self.axes) != (expected.plan_runs, &expected.axes) {
            return Some(MarkDifference::Plan {
                runs: self.plan_runs,
                axes: self.axes.clone(),
                expected_runs: expected.plan_runs,
                expected_axes: expected.axes.clone(),
            });
        }
        if self.values != expected.values {
            return Some(MarkDifference::Values);
        }
        if self.channels != expected.channels {
            return Some(MarkDifference::Channels {
                channels: self.channels.clone(),
                expected: expected.channels.clone(),
            });
        }
        if self.weights != expected.weights {
            return Some(MarkDifference::Weights);
        }
        None
    }
}

/// FNV-1a over 64-bit words: a digest to tell sweeps apart, not a
/// safeguard against tampering.
struct Digest(u64);

impl Digest {
    fn new() -> Digest {
        Digest(0xcbf2_9ce4_8422_2325)
    }

    fn add(&mut self, word: u64) {
        for byte in word.to_le_bytes() {
            self.0 = (self.0 ^ u64::from(byte)).wrapping_mul(0x0100_0000_01b3);
        }
    }

    fn hex(&self) -> String {
        format!("{:016x}", self.0)
    }

    /// The digest [`Digest::hex`] wrote; one that does not parse differs
    /// from every digest written.
    fn from_hex(text: &str) -> Digest {
        Digest(u64::from_str_radix(text, 16).unwrap_or(0))
    }
}

/// The accumulators of a block of runs and the sweep they belong to.
#[derive(Clone, Debug, PartialEq)]
pub struct PartialEnvelope {
    /// The sweep the block belongs to.
    pub mark: SweepMark,
    /// The block's runs (a shard's block).
    pub block: Range<usize>,
    /// How many of them, from the first, the envelope holds (finished or
    /// failed); the block is complete when this is its length.
    pub done: usize,
    /// Their envelope.
    pub envelope: Envelope,
}

/// The file's text of one channel; numbers as text.
#[derive(Serialize, Deserialize)]
struct ChannelText {
    name: String,
    min: Vec<String>,
    min_run: Vec<Option<usize>>,
    max: Vec<String>,
    max_run: Vec<Option<usize>>,
    weighted_sum: Vec<Vec<String>>,
}

/// The file's text.
#[derive(Serialize, Deserialize)]
struct FileText {
    format: String,
    version: u32,
    sweep: SweepMark,
    block: [usize; 2],
    done: usize,
    runs_added: usize,
    first_run: Option<usize>,
    total_weight: Vec<String>,
    t: Vec<String>,
    channels: Vec<ChannelText>,
}

/// The two entries read before the rest, to refuse a file of another kind
/// or version with a message that says so.
#[derive(Deserialize)]
struct Header {
    format: Option<String>,
    version: Option<u32>,
}

fn numbers(x: &[f64]) -> Vec<String> {
    x.iter().map(|x| format!("{x:?}")).collect()
}

fn parse_numbers(text: &[String]) -> Result<Vec<f64>, FileProblem> {
    let parse = |s: &String| (s.parse()).map_err(|_| FileProblem::NotANumber { text: s.clone() });
    text.iter().map(parse).collect()
}

impl ChannelText {
    fn of(channel: &ChannelEnvelope) -> ChannelText {
        ChannelText {
            name: channel.name.clone(),
            min: numbers(&channel.min),
            min_run: channel.min_run.clone(),
            max: numbers(&channel.max),
            max_run: channel.max_run.clone(),
            weighted_sum: (channel.weighted_sum.iter())
                .map(|s| numbers(&s.terms()))
                .collect(),
        }
    }

    fn read(self, points: usize) -> Result<ChannelEnvelope, FileProblem> {
        let sums = (self.weighted_sum.iter())
            .map(|terms| parse_numbers(terms).map(|t| ExactSum::from_terms(&t)))
            .collect::<Result<Vec<ExactSum>, FileProblem>>()?;
        let channel = ChannelEnvelope {
            min: parse_numbers(&self.min)?,
            min_run: self.min_run,
            max: parse_numbers(&self.max)?,
            max_run: self.max_run,
            weighted_sum: sums,
            name: self.name,
        };
        let lengths = [
            channel.min.len(),
            channel.min_run.len(),
            channel.max.len(),
            channel.max_run.len(),
            channel.weighted_sum.len(),
        ];
        match lengths.iter().all(|&n| n == points) {
            true => Ok(channel),
            false => Err(FileProblem::Entries {
                channel: channel.name,
                points,
            }),
        }
    }
}

impl PartialEnvelope {
    /// Writes the partial envelope as JSON to `out`.
    pub fn write(&self, out: impl Write) -> Result<(), EnvelopeFileError> {
        let envelope = &self.envelope;
        let text = FileText {
            format: ENVELOPE_FORMAT.to_string(),
            version: ENVELOPE_VERSION,
            sweep: self.mark.clone(),
            block: [self.block.start, self.block.end],
            done: self.done,
            runs_added: envelope.runs,
            first_run: envelope.first_run(),
            total_weight: numbers(&envelope.total_weight.terms()),
            t: numbers(&envelope.t),
            channels: envelope.channels.iter().map(ChannelText::of).collect(),
        };
        serde_json::to_writer(out, &text).map_err(EnvelopeFileError::Write)
    }

    /// Reads the partial envelope in `path` and checks that it belongs to
    /// the sweep of `plan`, `channels` and `weights`; an error names the
    /// file and what differs.
    pub fn read(
        path: &Path,
        plan: &Plan,
        channels: &[String],
        weights: &Weights,
    ) -> Result<PartialEnvelope, EnvelopeFileError> {
        let at = |problem: FileProblem| EnvelopeFileError::File {
            path: path.to_path_buf(),
            problem,
        };
        let bytes = std::fs::read(path).map_err(|e| at(FileProblem::Read(e)))?;
        let text = parse(&bytes).map_err(at)?;
        let [start, end] = text.block;
        if start > end || end > plan.len() || text.done > end - start {
            return Err(at(FileProblem::NotABlock {
                start,
                end,
                done: text.done,
                runs: plan.len(),
            }));
        }
        let block = start..end;
        let held = start..start + text.done;
        let expected = SweepMark::of(plan, channels, weights, &held);
        if let Some(why) = text.sweep.difference(&expected) {
            return Err(at(FileProblem::OtherSweep(why)));
        }
        let done = text.done;
        let envelope = envelope_of(text, channels).map_err(at)?;
        Ok(PartialEnvelope {
            mark: expected,
            block,
            done,
            envelope,
        })
    }
}

/// The file's text, its format and version checked first.
fn parse(bytes: &[u8]) -> Result<FileText, FileProblem> {
    let header: Header = serde_json::from_slice(bytes).map_err(FileProblem::NotJson)?;
    if header.format.as_deref() != Some(ENVELOPE_FORMAT) {
        return Err(FileProblem::Format {
            format: header.format.unwrap_or_default(),
        });
    }
    if header.version != Some(ENVELOPE_VERSION) {
        return Err(FileProblem::Version {
            version: header.version,
        });
    }
    serde_json::from_slice(bytes).map_err(FileProblem::Json)
}

/// The envelope of a file's text.
fn envelope_of(text: FileText, channels: &[String]) -> Result<Envelope, FileProblem> {
    let t = parse_numbers(&text.t)?;
    let read = (text.channels.into_iter())
        .map(|c| c.read(t.len()))
        .collect::<Result<Vec<ChannelEnvelope>, FileProblem>>()?;
    let expected = if text.first_run.is_some() {
        channels.len()
    } else {
        0
    };
    if read.len() != expected || read.iter().zip(channels).any(|(c, name)| c.name != *name) {
        return Err(FileProblem::Accumulators);
    }
    let accumulated = Accumulated {
        t,
        channels: read,
        total_weight: ExactSum::from_terms(&parse_numbers(&text.total_weight)?),
        runs: text.runs_added,
    };
    Ok(Envelope::restore(
        channels.to_vec(),
        accumulated,
        text.first_run,
    ))
}

/// The envelope of the whole sweep from the partial envelopes in `paths`
/// (any order), each read against the sweep of `plan`, `channels` and
/// `weights`: their blocks, each complete, must cover every run once.
pub fn merged_envelope(
    paths: &[PathBuf],
    plan: &Plan,
    channels: &[String],
    weights: &Weights,
) -> Result<Envelope, EnvelopeFileError> {
    let at = |path: &Path, problem: FileProblem| EnvelopeFileError::File {
        path: path.to_path_buf(),
        problem,
    };
    let mut parts = Vec::new();
    for path in paths {
        let part = PartialEnvelope::read(path, plan, channels, weights)?;
        if part.done < part.block.len() {
            let problem = FileProblem::Unfinished {
                done: part.done,
                start: part.block.start,
                end: part.block.end,
            };
            return Err(at(path, problem));
        }
        parts.push((path, part));
    }
    parts.sort_by_key(|(_, part)| (part.block.start, part.block.end));
    check_blocks(&parts, plan.len())?;
    let mut whole = Envelope::named(channels.to_vec());
    for (path, part) in &parts {
        (whole.merge(&part.envelope)).map_err(|e| at(path, FileProblem::Merge(e)))?;
    }
    Ok(whole)
}

/// The blocks, sorted, cover `0..total` each run once.
fn check_blocks(
    parts: &[(&PathBuf, PartialEnvelope)],
    total: usize,
) -> Result<(), EnvelopeFileError> {
    let missing = |from, to| EnvelopeFileError::Missing { from, to, total };
    let mut next = 0;
    let mut previous: Option<&Path> = None;
    for (path, part) in parts.iter().filter(|(_, p)| !p.block.is_empty()) {
        let block = &part.block;
        if block.start < next {
            return Err(EnvelopeFileError::File {
                path: path.to_path_buf(),
                problem: FileProblem::Overlap {
                    start: block.start,
                    end: next.min(block.end),
                    previous: previous.map(Path::to_path_buf),
                },
            });
        }
        if block.start > next {
            return Err(missing(next, block.start));
        }
        next = block.end;
        previous = Some(path.as_path());
    }
    match next < total {
        true => Err(missing(next, total)),
        false => Ok(()),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn plan() -> Plan {
        Plan::grid(&["v=1,2,3,4".to_string()]).unwrap()
    }

    fn channels() -> Vec<String> {
        vec!["x".to_string()]
    }

    /// The partial envelope of `block` with x = v·t at t = 0, 0.1 and a
    /// run that fails (no history) at v = 3.
    fn partial(block: Range<usize>, weights: &Weights) -> PartialEnvelope {
        let plan = plan();
        let mut envelope = Envelope::named(channels());
        for run in block.clone().filter(|&run| run != 2) {
            let v = plan.point(run)[0];
            let history = super::super::envelope::History {
                t: vec![0.0, 0.1],
                values: vec![vec![0.0, 0.1 * v]],
            };
            envelope
                .add(run, weights.of_run(&plan, run), &history)
                .unwrap();
        }
        PartialEnvelope {
            mark: SweepMark::of(&plan, &channels(), weights, &block),
            done: block.len(),
            block,
            envelope,
        }
    }

    fn write(dir: &Path, name: &str, part: &PartialEnvelope) -> PathBuf {
        let path = dir.join(name);
        part.write(std::fs::File::create(&path).unwrap()).unwrap();
        path
    }

    fn directory(name: &str) -> PathBuf {
        let dir = std::env::temp_dir().join(format!("envelope-file-{name}-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        dir
    }

    #[test]
    fn a_written_partial_envelope_reads_back_the_same() {
        let dir = directory("round-trip");
        let weights = Weights::per_value("v=0.1,0.2,0.3,0.4", &plan()).unwrap();
        for block in [0..4, 1..3, 2..3, 0..0] {
            let part = partial(block.clone(), &weights);
            let path = write(&dir, "part.json", &part);
            let read = PartialEnvelope::read(&path, &plan(), &channels(), &weights).unwrap();
            assert_eq!(read, part, "{block:?}");
        }
        std::fs::remove_dir_all(&dir).ok();
    }

    #[test]
    fn shards_merged_in_any_order_are_the_whole_sweep() {
        let dir = directory("merge");
        let w = Weights::per_value("v=0.1,0.2,0.3,0.4", &plan()).unwrap();
        let whole = partial(0..4, &w).envelope;
        let a = write(&dir, "a.json", &partial(0..1, &w));
        let b = write(&dir, "b.json", &partial(1..3, &w));
        let c = write(&dir, "c.json", &partial(3..4, &w));
        let empty = write(&dir, "empty.json", &partial(1..1, &w));
        for paths in [vec![&a, &b, &c], vec![&c, &empty, &a, &b]] {
            let paths: Vec<PathBuf> = paths.into_iter().cloned().collect();
            let merged = merged_envelope(&paths, &plan(), &channels(), &w).unwrap();
            assert_eq!(merged, whole);
        }
        let merge = |paths: &[&PathBuf]| {
            let paths: Vec<PathBuf> = paths.iter().map(|p| p.to_path_buf()).collect();
            (merged_envelope(&paths, &plan(), &channels(), &w))
                .unwrap_err()
                .to_string()
        };
        let missing = merge(&[&a, &c]);
        assert!(
            missing.contains("runs 1..3 (of 4) are in no part's envelope"),
            "{missing}"
        );
        let twice = merge(&[&a, &b, &b, &c]);
        assert!(twice.contains("b.json: runs 1..3 are also in"), "{twice}");
        std::fs::remove_dir_all(&dir).ok();
    }

    #[test]
    fn a_partial_envelope_of_another_sweep_is_refused_naming_the_file_and_the_difference() {
        let dir = directory("refused");
        let equal = Weights::Equal;
        let path = write(&dir, "part.json", &partial(0..2, &equal));
        let read = |plan: &Plan, channels: &[String], weights: &Weights| {
            (PartialEnvelope::read(&path, plan, channels, weights))
                .unwrap_err()
                .to_string()
        };
        let other_values = Plan::grid(&["v=1,5,3,4".to_string()]).unwrap();
        let other_count = Plan::grid(&["v=1,2,3".to_string()]).unwrap();
        let weights = Weights::per_value("v=1,2,3,4", &plan()).unwrap();
        let cases = [
            (
                read(&other_values, &channels(), &equal),
                "its runs have other values",
            ),
            (
                read(&other_count, &channels(), &equal),
                "a sweep of 4 runs over v, this one has 3 runs over v",
            ),
            (
                read(&plan(), &["y".to_string()], &equal),
                "its channels are x, this sweep's y",
            ),
            (read(&plan(), &channels(), &weights), "other --weights"),
        ];
        for (error, what) in cases {
            assert!(
                error.starts_with(&format!("{}: ", path.display())),
                "{error}"
            );
            assert!(error.contains(what), "{error}");
        }
        std::fs::write(
            &path,
            r#"{"format": "lagrangian-sweep-envelope", "version": 9}"#,
        )
        .unwrap();
        let version = read(&plan(), &channels(), &equal);
        assert!(
            version.contains("version 9 of the envelope file"),
            "{version}"
        );
        std::fs::write(&path, "a,b\n1,2\n").unwrap();
        assert!(read(&plan(), &channels(), &equal).contains("not a partial envelope"));
        std::fs::remove_dir_all(&dir).ok();
    }

    #[test]
    fn an_unfinished_block_is_refused_by_the_merge() {
        let dir = directory("unfinished");
        // What a sweep stopped after three runs of four leaves.
        let mut part = partial(0..3, &Weights::Equal);
        part.block = 0..4;
        let path = write(&dir, "part.json", &part);
        let error = merged_envelope(&[path], &plan(), &channels(), &Weights::Equal)
            .unwrap_err()
            .to_string();
        assert!(
            error.contains("holds 3 of the runs 0..4: its shard did not finish"),
            "{error}"
        );
        std::fs::remove_dir_all(&dir).ok();
    }
}
