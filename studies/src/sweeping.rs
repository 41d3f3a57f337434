//! A sweep as a host runs it (what `lpm sweep` does): a scenario run many
//! times with values varied, in parallel, one row of summary metrics per
//! run written to a table (CSV or Parquet) through a journal that a stopped
//! sweep resumes from; or its plan, or the merge of its shards' tables.
//! [`memory`] makes the same tables in memory, for the Python package.
//! The host sees the runs and asks the sweep to stop through [`Progress`].

use crate::error::StudyError;
pub use crate::progress::Progress;
use crate::spec::compile;
use crate::sweep::{
    Design, Envelope, EnvelopeJob, Journal, Layout, Plan, PlanError, Row, Settings, Shard,
    ShardError, SweepJob, journal_path, merged_rows, read_groups, run_scenario,
    shard_from_environment, stream_envelope, stream_sweep, write_csv, write_parquet,
};
use lagrangian_runtime::{Interpreted, InterpretedModel, WithDimension};
use lagrangian_sim::files::Files;
use lagrangian_sim::report::write_atomically_with;
use lagrangian_sim::scenario::{BaseScenario, ModelNames, Override, spec_named_by};
use std::io::Write as _;
use std::path::{Path, PathBuf};
use std::sync::Arc;
use std::time::Instant;

pub mod envelope;
pub mod memory;

/// What sweep to run, and what to make of it (`lpm sweep`'s options
/// without the progress display's).
#[derive(Clone, Debug)]
pub struct SweepRequest {
    /// The scenario (TOML); its `spec` key names the model.
    pub scenario: PathBuf,
    /// The spec, if not the one the scenario names.
    pub spec: Option<PathBuf>,
    /// Grid axes, `KEY=a,b,c` or `KEY=low:high:count`: every combination
    /// is run, the last varying fastest.
    pub grid: Vec<String>,
    /// Number of sampled runs (with `vary`).
    pub samples: Option<usize>,
    /// Sampled axes, `KEY=low:high` (uniform) or `KEY=low:high:log`.
    pub vary: Vec<String>,
    /// How samples are placed.
    pub design: Design,
    /// Seed of the sampled design (run i's values depend only on seed and i).
    pub seed: u64,
    /// Settings for every run, as `simulate`'s.
    pub set: Vec<Override>,
    /// The output table: .csv or .parquet (needed unless `plan_only`).
    pub out: Option<PathBuf>,
    /// Its format, `csv` or `parquet` (default: from `out`'s extension).
    pub format: Option<String>,
    /// Only block i of n of the runs (`I/N`), or `auto`: from the
    /// environment of a scheduler.
    pub shard: Option<String>,
    /// Only block K of the runs, counted from 0 (with `shard_count`).
    pub shard_index: Option<usize>,
    /// Into how many blocks the runs are split.
    pub shard_count: Option<u64>,
    /// The plan only: the number of runs, the time of a few, a split.
    pub plan_only: bool,
    /// The shards' tables to merge into `out`.
    pub merge: Vec<PathBuf>,
    /// Worker threads (0: one per core).
    pub threads: usize,
    /// Continue an interrupted sweep from its journal.
    pub resume: bool,
    /// Envelopes and weighted mean histories of chosen channels.
    pub envelope: envelope::EnvelopeOptions,
}

/// The spec a scenario names with its `spec` key (relative to the scenario).
fn spec_of(scenario: &Path, text: &str) -> Result<PathBuf, StudyError> {
    spec_named_by(scenario, text)
        .map_err(|e| StudyError::usage(e.to_string()))?
        .ok_or_else(|| {
            StudyError::usage(format!(
                "{} has no `spec = \"…\"` entry; name the spec with --spec",
                scenario.display()
            ))
        })
}

/// The plan of the command line: a grid or a sampled design.
/// The runs `options` asks for, values with units read against `base`.
fn plan(options: &SweepRequest, base: &BaseScenario) -> Result<Plan, PlanError> {
    let design = options.design;
    let units = |key: &str, text: &str| base.si_value(key, text);
    match (options.grid.is_empty(), options.samples) {
        (false, None) if options.vary.is_empty() => Plan::grid_in(&options.grid, &units),
        (true, Some(count)) => Plan::samples_in(count, &options.vary, options.seed, design, &units),
        (true, None) => Err(PlanError::NoDesign),
        _ => Err(PlanError::GridAndSamples),
    }
}

/// Whether the table `out` is Parquet: `--format`, else its extension.
fn wants_parquet(options: &SweepRequest, out: &Path) -> Result<bool, StudyError> {
    match options.format.as_deref() {
        Some(format) => Ok(format == "parquet"),
        None => match out.extension().and_then(|e| e.to_str()) {
            Some("parquet") => Ok(true),
            Some("csv") => Ok(false),
            _ => Err(StudyError::usage(format!(
                "--out {}: name a .csv or .parquet file, or give --format",
                out.display()
            ))),
        },
    }
}

/// The shard of `--shard`, `--shard auto` or `--shard-index`/`--shard-count`.
fn shard(options: &SweepRequest) -> Result<Shard, ShardError> {
    let count = options.shard_count.map(|n| n as usize);
    match (options.shard.as_deref(), options.shard_index, count) {
        (Some("auto"), _, count) => shard_from_environment(&|name| std::env::var(name).ok(), count),
        (Some(_), _, Some(_)) => Err(ShardError::CountWithFraction),
        (Some(text), _, None) => Shard::parse(text),
        (None, Some(index), Some(count)) => Shard::zero_based(index, count),
        (None, None, Some(_)) => Err(ShardError::CountAlone),
        (None, _, None) => Ok(Shard::ALL),
    }
}

/// The model the scenario (or `--spec`) names and the scenario every run
/// starts from.
fn load(
    options: &SweepRequest,
    files: &Arc<dyn Files>,
) -> Result<(InterpretedModel, BaseScenario), StudyError> {
    let text = (files.text(&options.scenario))
        .map_err(|e| StudyError::io(format!("cannot read {}: {e}", options.scenario.display())))?;
    let spec = match &options.spec {
        Some(spec) => spec.clone(),
        None => spec_of(&options.scenario, &text)?,
    };
    let model = crate::spec::interpreted(&compile(&**files, &spec)?);
    let base = BaseScenario {
        text: text.to_string(),
        file: Some(options.scenario.clone()),
        names: ModelNames::of_interpreted(&model),
        settings: options.set.clone(),
        files: Arc::clone(files),
    };
    Ok((model, base))
}

/// What the runs of this invocation came to.
#[derive(Default)]
struct Tally {
    ok: usize,
    failed: usize,
    /// The first failed run and its `kind: message`.
    first_failure: Option<(usize, String)>,
}

impl Tally {
    fn count(&mut self, row: &Row) {
        match &row.outcome {
            Ok(_) => self.ok += 1,
            Err(e) => {
                self.failed += 1;
                (self.first_failure)
                    .get_or_insert((row.run, format!("{}: {}", e.kind.name(), e.message)));
            }
        }
    }
}

/// What every mode of a sweep starts from: the plan, the model, the
/// scenario and the table's columns.
struct Prepared {
    plan: Plan,
    model: InterpretedModel,
    base: BaseScenario,
    settings: Settings,
    layout: Layout,
}

fn prepare(options: &SweepRequest, files: &Arc<dyn Files>) -> Result<Prepared, StudyError> {
    let (model, base) = load(options, files)?;
    let plan = plan(options, &base)?;
    let settings = Settings::new(&plan, &base, model.parameters())?;
    // A key the scenario does not know fails here, before any run starts.
    let first = match plan.is_empty() {
        false => run_scenario(&base, &settings, &plan.point(0)),
        true => base.resolve(&[]),
    };
    let first = first.map_err(|e| StudyError::scenario(&e))?;
    let axes: Vec<String> = plan.axes().iter().map(|a| a.column()).collect();
    let layout = Layout::new(axes, &first);
    Ok(Prepared {
        plan,
        model,
        base,
        settings,
        layout,
    })
}

/// Runs the sweep `options` asks for, or with `plan_only` its plan, or
/// with `merge` the merge of its shards' tables: the text `lpm sweep`
/// prints. `progress` sees the runs of a sweep (not of a plan or a merge);
/// the scenario, its spec and its tables are read from `files`.
pub fn run(
    options: &SweepRequest,
    progress: &dyn Progress,
    files: &Arc<dyn Files>,
) -> Result<String, StudyError> {
    let shard = shard(options)?;
    let out = options.out.clone();
    let parquet = out.as_deref().map(|out| wants_parquet(options, out));
    let prepared = prepare(options, files)?;
    let parquet = parquet.transpose()?;
    let envelope = envelope::request(options, &prepared)?;
    match (out, parquet) {
        _ if options.plan_only => plan_report(prepared),
        (Some(out), Some(parquet)) if !options.merge.is_empty() => match &envelope {
            None => merge(&options.merge, &prepared, &out, parquet),
            Some(request) => {
                let merged = envelope::merged(request, &options.merge, &prepared)?;
                let outcome = merge(&options.merge, &prepared, &out, parquet)?;
                envelope::with_merged(outcome, request, &merged)
            }
        },
        (Some(out), Some(parquet)) => {
            let output = Output {
                table: &out,
                parquet,
                envelope: envelope.as_ref(),
            };
            sweep(options, prepared, shard, output, progress)
        }
        _ => Err(StudyError::usage("give --out FILE")),
    }
}

/// What a sweep writes: its table (Parquet or CSV) and any envelope.
struct Output<'a> {
    table: &'a Path,
    parquet: bool,
    envelope: Option<&'a envelope::EnvelopeRequest>,
}

/// Makes the runs of `shard` and writes their table (and envelope).
fn sweep(
    options: &SweepRequest,
    prepared: Prepared,
    shard: Shard,
    output: Output<'_>,
    progress: &dyn Progress,
) -> Result<String, StudyError> {
    let (out, parquet) = (output.table, output.parquet);
    let Prepared {
        plan,
        model,
        base,
        settings,
        layout,
    } = prepared;
    let runs = shard.runs(plan.len());
    let (plan, base, settings, layout) = (&plan, &base, &settings, &layout);
    let journal_path = journal_path(out);
    let (mut journal, done) = open_journal(options, out, &journal_path, layout, plan, &runs)?;
    let resume = options.resume.then_some(done);
    let mut tracked = (output.envelope)
        .map(|request| envelope::Tracked::start(request, plan, &runs, &journal_path, resume))
        .transpose()?;
    // With an envelope, the runs the journal holds beyond it are made again
    // for their histories (their rows are in the journal already).
    let from = tracked.as_ref().map_or(done, |t| t.done());
    let journaled = runs.start + done;
    progress.start(runs.len(), done);
    let stop = || progress.stop_requested();
    let start = Instant::now();
    let mut tally = Tally::default();
    let mut sink = |row: Row| -> Result<(), StudyError> {
        if row.run < journaled {
            return Ok(());
        }
        journal.append(&row).map_err(|e| {
            StudyError::io(format!("{e}; the runs finished before are kept in it: make room and run the same command with --resume"))
        })?;
        tally.count(&row);
        progress.run_done();
        Ok(())
    };
    let remaining = runs.start + from..runs.end;
    let job = SweepJob {
        base,
        plan,
        settings,
        runs: remaining.clone(),
        threads: options.threads,
    };
    let sweep = Sweep {
        job,
        stop: &stop,
        sink: &mut sink,
        envelope: tracked.as_mut().map(|t| t.streaming()),
    };
    let streamed = model.with_dimension(sweep).map_err(StudyError::model)??;
    progress.finish();
    let elapsed = start.elapsed().as_secs_f64();
    drop(journal);
    let finished = streamed - (done - from).min(streamed);
    if streamed < remaining.len() {
        if let Some(tracked) = &mut tracked {
            tracked.save()?;
        }
        return Err(stopped(done + finished, runs.len(), &journal_path));
    }
    // The envelope's files first: a sweep stopped in between resumes.
    let envelope_line = match &mut tracked {
        Some(tracked) => tracked.finish(shard, out)?,
        None => String::new(),
    };
    finish_output(&journal_path, out, layout, parquet)?;
    if let Some(tracked) = &tracked {
        tracked.remove_checkpoint()?;
    }
    let counts = Counts {
        runs: &runs,
        total: plan.len(),
        shard,
        done,
        finished,
        elapsed,
    };
    let text = report(&counts, &tally, out) + &envelope_line;
    if !runs.is_empty() && tally.ok == 0 && done == 0 {
        return Err(StudyError::EveryRunFailed(format!(
            "every run failed\n{text}"
        )));
    }
    Ok(text)
}

/// The failure of a sweep stopped with `kept` of its `runs` runs in the
/// journal `journal`.
fn stopped(kept: usize, runs: usize, journal: &Path) -> StudyError {
    StudyError::Interrupted {
        message: format!(
            "stopped: {kept} of {runs} runs are done and kept in {}; run the same command with --resume to finish",
            journal.display()
        ),
        journal: Some(journal.to_path_buf()),
    }
}

/// How many runs there were and how long they took.
struct Counts<'a> {
    runs: &'a std::ops::Range<usize>,
    total: usize,
    shard: Shard,
    /// Runs found in the journal.
    done: usize,
    /// Runs made now.
    finished: usize,
    elapsed: f64,
}

/// The lines `lpm sweep` prints when it is done.
fn report(counts: &Counts, tally: &Tally, out: &Path) -> String {
    let Counts {
        runs,
        total,
        shard,
        done,
        finished,
        elapsed,
    } = *counts;
    let rate = finished as f64 / elapsed.max(1e-9);
    let shard_text = if shard == Shard::ALL {
        String::new()
    } else {
        format!(
            " (shard {}/{}: runs {}..{} of {total})",
            shard.index, shard.count, runs.start, runs.end
        )
    };
    let journal_text = if done > 0 {
        format!(" ({done} from the journal, {finished} now)")
    } else {
        String::new()
    };
    let mut text = format!(
        "{} runs{shard_text}{journal_text} in {elapsed:.2} s ({rate:.0} runs/s), {} failed; wrote {}\n",
        runs.len(),
        tally.failed,
        out.display()
    );
    if let Some((run, message)) = &tally.first_failure {
        text.push_str(&format!("  first failure, run {run}: {message}\n"));
    }
    text
}

/// The journal to append to: a new one, or with `--resume` the one an
/// interrupted run of the same sweep left (with the number of runs in it).
fn open_journal(
    options: &SweepRequest,
    out: &Path,
    path: &Path,
    layout: &Layout,
    plan: &Plan,
    runs: &std::ops::Range<usize>,
) -> Result<(Journal, usize), StudyError> {
    let exists = path.exists();
    let resumable = exists && std::fs::metadata(path).is_ok_and(|m| m.len() > 0);
    match (options.resume, resumable) {
        (true, true) => Journal::resume(path, layout, plan, runs)
            .map_err(|e| StudyError::data_file(format!("--resume: {e}"))),
        (true, false) if out.exists() => Err(StudyError::usage(format!(
            "--resume: {} is complete and there is no {} to resume",
            out.display(),
            path.display()
        ))),
        (false, true) => Err(StudyError::usage(format!(
            "{} holds the finished runs of an interrupted sweep: continue it with --resume, or delete it to start again",
            path.display()
        ))),
        _ => Journal::create(path, layout)
            .map(|j| (j, 0))
            .map_err(StudyError::from),
    }
}

/// Turns the finished journal into the output: renamed for CSV, converted
/// one row group at a time (then removed) for Parquet.
fn finish_output(
    journal: &Path,
    out: &Path,
    layout: &Layout,
    parquet: bool,
) -> Result<(), StudyError> {
    if parquet {
        let groups = read_groups(journal, layout, PARQUET_GROUP_ROWS)?;
        let groups = groups.map(|group| group.map_err(StudyError::from));
        write_beside(out, |file| write_parquet(layout, groups, file))?;
        std::fs::remove_file(journal)
            .map_err(|e| StudyError::io(format!("cannot remove {}: {e}", journal.display())))
    } else {
        std::fs::rename(journal, out)
            .map_err(|e| StudyError::io(format!("cannot write {}: {e}", out.display())))
    }
}

/// Writes `out` through a temporary file beside it
/// ([`write_atomically_with`]), renamed into place when `write` succeeds
/// and the bytes are on the disk, removed on any failure (a full disk
/// included): `out` is whole or absent. A failure of `write` is returned
/// as it is, any other is an I/O error.
fn write_beside(
    out: &Path,
    write: impl FnOnce(&mut std::io::BufWriter<&mut std::fs::File>) -> Result<(), StudyError>,
) -> Result<(), StudyError> {
    let mut failure = None;
    write_atomically_with(out, |file| {
        let mut buffered = std::io::BufWriter::new(file);
        if let Err(e) = write(&mut buffered) {
            failure = Some(e);
            return Err(std::io::Error::other("not written"));
        }
        buffered.flush()
    })
    .map_err(|e| {
        failure.unwrap_or_else(|| StudyError::io(format!("cannot write {}: {e}", out.display())))
    })
}

/// `rows` in groups of `size` (the last one shorter); an error ends them.
fn in_groups<E>(
    mut rows: impl Iterator<Item = Result<Row, E>>,
    size: usize,
) -> impl Iterator<Item = Result<Vec<Row>, E>> {
    std::iter::from_fn(move || {
        let mut group = Vec::new();
        for row in rows.by_ref() {
            match row {
                Ok(row) => group.push(row),
                Err(e) => return Some(Err(e)),
            }
            if group.len() == size {
                break;
            }
        }
        (!group.is_empty()).then_some(Ok(group))
    })
}

/// `lpm sweep --merge`: the shards' tables checked against the plan and
/// written as the table of one full run.
fn merge(
    parts: &[PathBuf],
    prepared: &Prepared,
    out: &Path,
    parquet: bool,
) -> Result<String, StudyError> {
    write_beside(out, |file| merge_into(parts, prepared, parquet, file))?;
    Ok(format!(
        "merged {} runs from {} parts into {}\n",
        prepared.plan.len(),
        parts.len(),
        out.display()
    ))
}

/// Writes the merged table of the shards' tables `parts` to `file`.
fn merge_into(
    parts: &[PathBuf],
    prepared: &Prepared,
    parquet: bool,
    file: impl std::io::Write + Send,
) -> Result<(), StudyError> {
    // A part that fails its checks is a data error, one that cannot be
    // written an I/O error (the `From`s of their errors).
    let rows = merged_rows(parts, &prepared.layout, &prepared.plan)?;
    let rows = rows.map(|row| row.map_err(StudyError::from));
    let layout = &prepared.layout;
    match parquet {
        true => write_parquet(layout, in_groups(rows, PARQUET_GROUP_ROWS), file),
        false => write_csv(layout, rows, file),
    }
}

/// Runs timed by `--plan`.
const PLAN_TIMED_RUNS: usize = 10;

/// The time of one task of a suggested split, on one core \[s\].
const TASK_SECONDS: f64 = 600.0;

/// `lpm sweep --plan`: times the first runs on one thread and suggests a
/// split into tasks of about ten minutes of one core.
fn plan_report(prepared: Prepared) -> Result<String, StudyError> {
    let Prepared {
        plan,
        model,
        base,
        settings,
        ..
    } = prepared;
    let timed = 0..plan.len().min(PLAN_TIMED_RUNS);
    let stop = || false;
    let mut sink = |_: Row| Ok(());
    let job = SweepJob {
        base: &base,
        plan: &plan,
        settings: &settings,
        runs: timed.clone(),
        threads: 1,
    };
    let start = Instant::now();
    let sweep = Sweep {
        job,
        stop: &stop,
        sink: &mut sink,
        envelope: None,
    };
    model.with_dimension(sweep).map_err(StudyError::model)??;
    let per_run = start.elapsed().as_secs_f64() / timed.len().max(1) as f64;
    let axes: Vec<String> = plan.axes().iter().map(|a| a.column()).collect();
    Ok(plan_text(plan.len(), &axes, timed.len(), per_run))
}

/// The text of `--plan` for `total` runs of `per_run` seconds each.
fn plan_text(total: usize, axes: &[String], timed: usize, per_run: f64) -> String {
    let all = total as f64 * per_run;
    let mut text = format!(
        "{total} runs over {}\na run takes {:.2} ms on one thread here ({timed} timed); all runs ≈ {} of one core\n",
        axes.join(", "),
        per_run * 1e3,
        duration(all)
    );
    let tasks = ((all / TASK_SECONDS).ceil() as usize).clamp(1, total.max(1));
    if tasks == 1 {
        text.push_str("suggested split: none (the runs take under ten minutes of one core)\n");
    } else {
        let runs = total.div_ceil(tasks);
        text.push_str(&format!(
            "suggested split: {tasks} tasks of ≤ {runs} runs (≈ {} each on one core): --shard auto --shard-count {tasks}\n  (Slurm --array=1-{tasks}; Kubernetes completions: {tasks}; AWS Batch array size {tasks})\n",
            duration(runs as f64 * per_run)
        ));
    }
    text
}

/// `12.3 s`, `4.5 min` or `2.1 h`.
fn duration(seconds: f64) -> String {
    match seconds {
        s if s < 120.0 => format!("{s:.1} s"),
        s if s < 7200.0 => format!("{:.1} min", s / 60.0),
        s => format!("{:.1} h", s / 3600.0),
    }
}

/// Rows per Parquet row group (about 14 MB of values with 30 columns).
const PARQUET_GROUP_ROWS: usize = 1 << 16;

/// `stream_sweep` (or with an envelope `stream_envelope`) on the model at
/// its dimension.
struct Sweep<'a> {
    job: SweepJob<'a>,
    stop: &'a (dyn Fn() -> bool + Sync),
    sink: &'a mut dyn FnMut(Row) -> Result<(), StudyError>,
    envelope: Option<Enveloping<'a>>,
}

/// The envelope a sweep accumulates: the channels and weights, the
/// accumulators, and what to do after each row (save them now and then).
struct Enveloping<'a> {
    job: EnvelopeJob<'a>,
    envelope: &'a mut Envelope,
    after: Option<&'a mut dyn envelope::AfterRow>,
}

impl WithDimension for Sweep<'_> {
    type Output = Result<usize, StudyError>;

    fn run<const N: usize>(self, system: Interpreted<N>) -> Self::Output {
        match self.envelope {
            None => stream_sweep(&system, self.job, self.stop, self.sink),
            Some(Enveloping {
                job,
                envelope,
                mut after,
            }) => {
                let sink = self.sink;
                let mut sink = |row: Row, envelope: &Envelope| {
                    let run = row.run;
                    sink(row)?;
                    match after.as_mut() {
                        Some(checkpoints) => checkpoints.after(run, envelope),
                        None => Ok(()),
                    }
                };
                stream_envelope(&system, self.job, job, envelope, self.stop, &mut sink)
            }
        }
    }
}
