//! `lpm sweep`: run a scenario many times with values varied, in parallel,
//! and write one row of summary metrics per run (CSV or Parquet). The
//! sweep is [`lagrangian_studies::sweeping`]'s; this is its command line,
//! its progress bar and its Ctrl-C.

use crate::failure::{Failure, Outcome};
use crate::status::ExitStatus;
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use lagrangian_studies::files::Files;
use lagrangian_studies::sweep::Design;
use lagrangian_studies::sweeping::envelope::EnvelopeOptions;
use lagrangian_studies::sweeping::{Progress, SweepRequest};
use std::path::PathBuf;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Arc, OnceLock};

/// Options of `lpm sweep`.
#[derive(clap::Args)]
#[command(group(clap::ArgGroup::new("axes").required(true).args(["grid", "samples"])))]
pub struct Args {
    /// The scenario (TOML); its `spec` key names the model.
    pub scenario: PathBuf,
    /// The spec, if not the one the scenario names.
    #[arg(long)]
    pub spec: Option<PathBuf>,
    /// A grid axis: KEY=a,b,c or KEY=low:high:count; every combination of
    /// the axes is run, the last varying fastest.
    #[arg(long, value_name = "KEY=VALUES")]
    pub grid: Vec<String>,
    /// Number of sampled runs (with --vary).
    #[arg(long, requires = "vary")]
    pub samples: Option<usize>,
    /// A sampled axis: KEY=low:high (uniform) or KEY=low:high:log.
    #[arg(long, value_name = "KEY=LOW:HIGH", requires = "samples")]
    pub vary: Vec<String>,
    /// How samples are placed.
    #[arg(long, value_enum, default_value = "latin-hypercube")]
    pub design: DesignArg,
    /// Seed of the sampled design (run i's values depend only on seed and i).
    #[arg(long, default_value_t = 1)]
    pub seed: u64,
    /// A setting for every run, as in `lpm simulate --set`.
    #[arg(long = "set", value_name = "KEY=VALUE")]
    pub set: Vec<String>,
    /// Output table: .csv or .parquet.
    #[arg(long, required_unless_present = "plan_only")]
    pub out: Option<PathBuf>,
    /// Output format (default: from the --out extension).
    #[arg(long, value_parser = ["csv", "parquet"])]
    pub format: Option<String>,
    /// Run only block i of n of the runs (1 ≤ i ≤ n); `auto` reads the
    /// task's index from Slurm (SLURM_ARRAY_TASK_ID, _MIN, _STEP, _COUNT),
    /// a Kubernetes Indexed Job (JOB_COMPLETION_INDEX) or AWS Batch
    /// (AWS_BATCH_JOB_ARRAY_INDEX); the last two need --shard-count.
    #[arg(long, value_name = "I/N|auto")]
    pub shard: Option<String>,
    /// Run only block K of the runs, counted from 0 (with --shard-count),
    /// as HTCondor's $(Process) numbers tasks.
    #[arg(
        long,
        value_name = "K",
        conflicts_with = "shard",
        requires = "shard_count"
    )]
    pub shard_index: Option<usize>,
    /// Into how many blocks the runs are split (with --shard-index or
    /// --shard auto).
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u64).range(1..))]
    pub shard_count: Option<u64>,
    /// Print the number of runs, the time of a run measured on a few runs,
    /// and a suggested split into tasks; runs nothing else.
    #[arg(long = "plan", conflicts_with_all = ["merge", "resume"])]
    pub plan_only: bool,
    /// Merge the tables of the shards of this sweep (same command line,
    /// any order, CSV or Parquet) into --out, checking that every run is
    /// there once with this plan's values.
    #[arg(long, value_name = "PARTS", num_args = 1.., conflicts_with = "resume")]
    pub merge: Vec<PathBuf>,
    /// Worker threads (default: one per core).
    #[arg(long, default_value_t = 0)]
    pub threads: usize,
    /// No progress bar.
    #[arg(long)]
    pub quiet: bool,
    /// Continue an interrupted sweep from its journal (`OUT.partial`):
    /// the same command line with --resume runs only the missing runs.
    #[arg(long)]
    pub resume: bool,
    /// Envelopes and weighted mean histories of chosen channels (boxed:
    /// they are seldom given).
    #[command(flatten)]
    pub envelope: Box<EnvelopeArgs>,
}

/// How a sampled design places its runs.
#[derive(Clone, Copy, clap::ValueEnum)]
pub enum DesignArg {
    /// One run in each of N equal strata of every axis.
    LatinHypercube,
    /// Independent uniform draws.
    Random,
}

/// The envelope flags of `lpm sweep`.
#[derive(clap::Args, Clone, Debug, Default)]
pub struct EnvelopeArgs {
    /// Channels to envelope: columns of trajectory.csv or combinations as
    /// `[metrics]` writes them ("xa - xb"); per output time, the minimum
    /// and maximum over the runs (with the run attaining each) and the
    /// weighted mean.
    #[arg(
        long,
        value_name = "CHANNEL[,CHANNEL…]",
        value_delimiter = ',',
        requires = "envelope_out"
    )]
    pub envelope: Vec<String>,
    /// The envelope table: .csv or .parquet, one row per output time. A
    /// shard writes its partial envelope beside its table instead
    /// (OUT.envelope.json), and --merge of the shards writes this table.
    #[arg(long, value_name = "FILE.csv|FILE.parquet", requires = "envelope")]
    pub envelope_out: Option<PathBuf>,
    /// The envelope plot (SVG): the band between minimum and maximum and
    /// the weighted mean, one panel per channel.
    #[arg(long, value_name = "FILE.svg", requires = "envelope")]
    pub envelope_plot: Option<PathBuf>,
    /// The runs' weights in the mean: KEY=W1,W2,… (one per value of grid
    /// axis KEY) or a CSV file with columns run,weight; default: equal.
    #[arg(long, value_name = "KEY=W1,…|FILE.csv", requires = "envelope")]
    pub weights: Option<String>,
}

impl Args {
    /// The sweep these options ask for.
    pub fn request(&self) -> Result<SweepRequest, Failure> {
        let envelope = &self.envelope;
        Ok(SweepRequest {
            scenario: self.scenario.clone(),
            spec: self.spec.clone(),
            grid: self.grid.clone(),
            samples: self.samples,
            vary: self.vary.clone(),
            design: match self.design {
                DesignArg::LatinHypercube => Design::LatinHypercube,
                DesignArg::Random => Design::Random,
            },
            seed: self.seed,
            set: Failure::overrides(&self.set)?,
            out: self.out.clone(),
            format: self.format.clone(),
            shard: self.shard.clone(),
            shard_index: self.shard_index,
            shard_count: self.shard_count,
            plan_only: self.plan_only,
            merge: self.merge.clone(),
            threads: self.threads,
            resume: self.resume,
            envelope: EnvelopeOptions {
                envelope: envelope.envelope.clone(),
                envelope_out: envelope.envelope_out.clone(),
                envelope_plot: envelope.envelope_plot.clone(),
                weights: envelope.weights.clone(),
            },
        })
    }
}

/// Runs `lpm sweep`: the sweep, or with `--plan` its plan, or with
/// `--merge` the merge of its shards' tables.
pub fn run(options: Args, files: &Arc<dyn Files>) -> Result<Outcome, Failure> {
    let progress = Bar {
        quiet: options.quiet,
        bar: OnceLock::new(),
        stop: OnceLock::new(),
    };
    let text = lagrangian_studies::sweeping::run(&options.request()?, &progress, files)?;
    Ok(Outcome::success(text))
}

/// The progress of `lpm sweep`: a bar on stderr (none with `--quiet`), and
/// a stop on the first signal, installed when the runs start.
struct Bar {
    quiet: bool,
    bar: OnceLock<ProgressBar>,
    stop: OnceLock<Arc<AtomicBool>>,
}

impl Progress for Bar {
    fn start(&self, runs: usize, done: usize) {
        let bar = self.bar.get_or_init(|| progress_bar(self.quiet, runs));
        bar.set_position(done as u64);
        self.stop.get_or_init(stop_on_signal);
    }

    fn run_done(&self) {
        if let Some(bar) = self.bar.get() {
            bar.inc(1);
        }
    }

    fn finish(&self) {
        if let Some(bar) = self.bar.get() {
            bar.finish_and_clear();
        }
    }

    fn stop_requested(&self) -> bool {
        (self.stop.get()).is_some_and(|stop| stop.load(Ordering::Relaxed))
    }
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
