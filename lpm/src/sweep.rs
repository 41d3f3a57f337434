//! `lpm sweep`: run a scenario many times with values varied, in parallel,
//! and write one row of summary metrics per run (CSV or Parquet).

use crate::failure::{Failure, Outcome};
use crate::spec::compile;
use crate::status::ExitStatus;
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use lagrangian_model::{Interpreted, InterpretedModel, WithDimension};
use lagrangian_sim::scenario::{BaseScenario, ModelNames, spec_named_by};
use lagrangian_sim::sweep::{
    Design, Journal, Layout, Plan, Row, Settings, Shard, SweepJob, journal_path, read_groups,
    run_scenario, stream_sweep, write_parquet,
};
use std::path::{Path, PathBuf};
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::Instant;

/// Options of `lpm sweep`.
#[derive(clap::Args)]
#[command(group(clap::ArgGroup::new("plan").required(true).args(["grid", "samples"])))]
pub struct Args {
    /// The scenario (TOML); its `spec` key names the model.
    scenario: PathBuf,
    /// The spec, if not the one the scenario names.
    #[arg(long)]
    spec: Option<PathBuf>,
    /// A grid axis: KEY=a,b,c or KEY=low:high:count; every combination of
    /// the axes is run, the last varying fastest.
    #[arg(long, value_name = "KEY=VALUES")]
    grid: Vec<String>,
    /// Number of sampled runs (with --vary).
    #[arg(long, requires = "vary")]
    samples: Option<usize>,
    /// A sampled axis: KEY=low:high (uniform) or KEY=low:high:log.
    #[arg(long, value_name = "KEY=LOW:HIGH", requires = "samples")]
    vary: Vec<String>,
    /// How samples are placed.
    #[arg(long, value_enum, default_value = "latin-hypercube")]
    design: DesignArg,
    /// Seed of the sampled design (run i's values depend only on seed and i).
    #[arg(long, default_value_t = 1)]
    seed: u64,
    /// A setting for every run, as in `lpm simulate --set`.
    #[arg(long = "set", value_name = "KEY=VALUE")]
    set: Vec<String>,
    /// Output table: .csv or .parquet.
    #[arg(long)]
    out: PathBuf,
    /// Output format (default: from the --out extension).
    #[arg(long, value_parser = ["csv", "parquet"])]
    format: Option<String>,
    /// Run only block i of n of the runs (1 ≤ i ≤ n), e.g. a Slurm array
    /// task: `--shard $SLURM_ARRAY_TASK_ID/$SLURM_ARRAY_TASK_COUNT`.
    #[arg(long, value_name = "I/N")]
    shard: Option<String>,
    /// Worker threads (default: one per core).
    #[arg(long, default_value_t = 0)]
    threads: usize,
    /// No progress bar.
    #[arg(long)]
    quiet: bool,
    /// Continue an interrupted sweep from its journal (`OUT.partial`):
    /// the same command line with --resume runs only the missing runs.
    #[arg(long)]
    resume: bool,
}

/// How a sampled design places its runs.
#[derive(Clone, Copy, clap::ValueEnum)]
enum DesignArg {
    /// One run in each of N equal strata of every axis.
    LatinHypercube,
    /// Independent uniform draws.
    Random,
}

/// The spec a scenario names with its `spec` key (relative to the scenario).
fn spec_of(scenario: &Path, text: &str) -> Result<PathBuf, Failure> {
    spec_named_by(scenario, text)
        .map_err(Failure::usage)?
        .ok_or_else(|| {
            Failure::usage(format!(
                "{} has no `spec = \"…\"` entry; name the spec with --spec",
                scenario.display()
            ))
        })
}

/// The plan of the command line: a grid or a sampled design.
fn plan(options: &Args) -> Result<Plan, String> {
    let design = match options.design {
        DesignArg::LatinHypercube => Design::LatinHypercube,
        DesignArg::Random => Design::Random,
    };
    match (options.grid.is_empty(), options.samples) {
        (false, None) if options.vary.is_empty() => Plan::grid(&options.grid),
        (true, Some(count)) => Plan::samples(count, &options.vary, options.seed, design),
        (true, None) => {
            Err("give --grid KEY=VALUES or --samples N with --vary KEY=LOW:HIGH".into())
        }
        _ => Err("--grid cannot be combined with --samples/--vary".into()),
    }
}

/// Whether the table is Parquet: `--format`, else the `--out` extension.
fn wants_parquet(options: &Args) -> Result<bool, Failure> {
    match options.format.as_deref() {
        Some(format) => Ok(format == "parquet"),
        None => match options.out.extension().and_then(|e| e.to_str()) {
            Some("parquet") => Ok(true),
            Some("csv") => Ok(false),
            _ => Err(Failure::usage(format!(
                "--out {}: name a .csv or .parquet file, or give --format",
                options.out.display()
            ))),
        },
    }
}

/// The model the scenario (or `--spec`) names and the scenario every run
/// starts from.
fn load(options: &Args) -> Result<(InterpretedModel, BaseScenario), Failure> {
    let text = std::fs::read_to_string(&options.scenario)
        .map_err(|e| Failure::io(format!("cannot read {}: {e}", options.scenario.display())))?;
    let spec = match &options.spec {
        Some(spec) => spec.clone(),
        None => spec_of(&options.scenario, &text)?,
    };
    let model = compile(&spec)?.interpreted();
    let base = BaseScenario {
        text,
        file: Some(options.scenario.clone()),
        names: ModelNames::of_interpreted(&model),
        settings: options.set.clone(),
    };
    Ok((model, base))
}

/// A progress bar over `runs` runs (hidden with `--quiet`).
fn progress_bar(quiet: bool, runs: usize) -> ProgressBar {
    if quiet {
        return ProgressBar::hidden();
    }
    let bar =
        ProgressBar::with_draw_target(Some(runs as u64), ProgressDrawTarget::stderr_with_hz(4));
    if let Ok(style) =
        ProgressStyle::with_template("{bar:40} {pos}/{len} runs  {per_sec}  eta {eta}")
    {
        bar.set_style(style);
    }
    bar
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
                (self.first_failure).get_or_insert((row.run, format!("{}: {}", e.kind, e.message)));
            }
        }
    }
}

/// Runs `lpm sweep`.
pub fn run(options: Args) -> Result<Outcome, Failure> {
    let plan = plan(&options).map_err(Failure::usage)?;
    let shard = match &options.shard {
        Some(text) => Shard::parse(text).map_err(Failure::usage)?,
        None => Shard::ALL,
    };
    let parquet = wants_parquet(&options)?;
    let (model, base) = load(&options)?;
    let settings = Settings::new(&plan, &base, model.parameters()).map_err(Failure::usage)?;
    // A key the scenario does not know fails here, before any run starts.
    let first = match plan.is_empty() {
        false => run_scenario(&base, &settings, &plan.point(0)),
        true => base.resolve(&[]),
    };
    let first = first.map_err(|e| Failure::scenario(&e))?;
    let runs = shard.runs(plan.len());
    let axes: Vec<String> = plan.axes().iter().map(|a| a.column()).collect();
    let layout = Layout::new(axes, &first);
    let journal_path = journal_path(&options.out);
    let (mut journal, done) = open_journal(&options, &journal_path, &layout, &plan, &runs)?;
    let bar = progress_bar(options.quiet, runs.len());
    bar.set_position(done as u64);
    let stop = stop_on_signal();
    let start = Instant::now();
    let mut tally = Tally::default();
    let mut sink = |row: Row| -> Result<(), String> {
        journal.append(&row)?;
        tally.count(&row);
        bar.inc(1);
        Ok(())
    };
    let remaining = runs.start + done..runs.end;
    let job = SweepJob {
        base: &base,
        plan: &plan,
        settings: &settings,
        runs: remaining.clone(),
        threads: options.threads,
    };
    let sweep = Sweep {
        job,
        stop: &stop,
        sink: &mut sink,
    };
    let finished = model.with_dimension(sweep).map_err(Failure::model)??;
    bar.finish_and_clear();
    let elapsed = start.elapsed().as_secs_f64();
    drop(journal);
    if finished < remaining.len() {
        return Err(Failure::rendered(
            ExitStatus::Interrupted,
            format!(
                "stopped: {} of {} runs are done and kept in {}; run the same command with --resume to finish",
                done + finished,
                runs.len(),
                journal_path.display()
            ),
        ));
    }
    finish_output(&journal_path, &options.out, &layout, parquet)?;
    let counts = Counts {
        runs: &runs,
        total: plan.len(),
        shard,
        done,
        finished,
        elapsed,
    };
    let text = report(&counts, &tally, &options.out);
    if !runs.is_empty() && tally.ok == 0 && done == 0 {
        return Err(Failure::new(
            ExitStatus::EveryRunFailed,
            format!("every run failed\n{text}"),
        ));
    }
    Ok(Outcome::success(text))
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
    options: &Args,
    path: &Path,
    layout: &Layout,
    plan: &Plan,
    runs: &std::ops::Range<usize>,
) -> Result<(Journal, usize), Failure> {
    let exists = path.exists();
    let resumable = exists && std::fs::metadata(path).is_ok_and(|m| m.len() > 0);
    match (options.resume, resumable) {
        (true, true) => Journal::resume(path, layout, plan, runs)
            .map_err(|e| Failure::new(ExitStatus::DataFile, format!("--resume: {e}"))),
        (true, false) if options.out.exists() => Err(Failure::usage(format!(
            "--resume: {} is complete and there is no {} to resume",
            options.out.display(),
            path.display()
        ))),
        (false, true) => Err(Failure::usage(format!(
            "{} holds the finished runs of an interrupted sweep: continue it with --resume, or delete it to start again",
            path.display()
        ))),
        _ => Journal::create(path, layout)
            .map(|j| (j, 0))
            .map_err(Failure::io),
    }
}

/// Turns the finished journal into the output: renamed for CSV, converted
/// one row group at a time (then removed) for Parquet.
fn finish_output(
    journal: &Path,
    out: &Path,
    layout: &Layout,
    parquet: bool,
) -> Result<(), Failure> {
    let io = |e: String| Failure::io(e);
    if parquet {
        let groups = read_groups(journal, layout, PARQUET_GROUP_ROWS).map_err(io)?;
        let temporary = temporary_beside(out);
        let file = std::fs::File::create(&temporary)
            .map_err(|e| io(format!("cannot create {}: {e}", temporary.display())))?;
        let written = write_parquet(layout, groups, std::io::BufWriter::new(file)).and_then(|()| {
            std::fs::rename(&temporary, out)
                .map_err(|e| format!("cannot write {}: {e}", out.display()))
        });
        if let Err(e) = written {
            let _ = std::fs::remove_file(&temporary);
            return Err(io(e));
        }
        std::fs::remove_file(journal)
            .map_err(|e| io(format!("cannot remove {}: {e}", journal.display())))
    } else {
        std::fs::rename(journal, out)
            .map_err(|e| io(format!("cannot write {}: {e}", out.display())))
    }
}

/// Rows per Parquet row group (about 14 MB of values with 30 columns).
const PARQUET_GROUP_ROWS: usize = 1 << 16;

fn temporary_beside(path: &Path) -> PathBuf {
    let name = path.file_name().unwrap_or_default().to_string_lossy();
    path.with_file_name(format!(".{name}.{}.tmp", std::process::id()))
}

/// A flag set by the first SIGINT, SIGTERM or SIGHUP: the sweep takes no
/// new run and stops once the runs under way are written. A second signal
/// exits at once (the journal keeps every row written).
fn stop_on_signal() -> Arc<AtomicBool> {
    let stop = Arc::new(AtomicBool::new(false));
    let flag = stop.clone();
    // Fails only if a handler is already installed (not in this program).
    let _ = ctrlc::set_handler(move || {
        if flag.swap(true, Ordering::SeqCst) {
            std::process::exit(i32::from(ExitStatus::Interrupted.code()));
        }
        eprintln!("\nstopping: finishing the runs under way (again to stop at once)");
    });
    stop
}

/// `stream_sweep` on the model at its dimension.
struct Sweep<'a> {
    job: SweepJob<'a>,
    stop: &'a AtomicBool,
    sink: &'a mut dyn FnMut(Row) -> Result<(), String>,
}

impl WithDimension for Sweep<'_> {
    type Output = Result<usize, Failure>;

    fn run<const N: usize>(self, system: Interpreted<N>) -> Self::Output {
        stream_sweep(&system, self.job, self.stop, self.sink).map_err(Failure::io)
    }
}
