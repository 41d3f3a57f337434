//! `lpm sweep` and `lpm fit` from Python: the command line's own code
//! (`lagrangian_studies::sweeping::memory`, `lagrangian_studies::fitting`),
//! its tables and reports handed back as
//! the text the command writes. The Python layer builds the options (lists
//! of `KEY=VALUES` strings) and shapes the results.

use crate::{FILES, raise};
use lagrangian_sim::scenario::Override;
use lagrangian_studies::error::StudyError;
use lagrangian_studies::fitting::{self, FitRequest};
use lagrangian_studies::sweeping::envelope::EnvelopeOptions;
use lagrangian_studies::sweeping::{Progress, SweepRequest, memory};
use lagrangian_studies::test_data::ChannelRequest;
use pyo3::prelude::*;
use std::path::{Path, PathBuf};
use std::sync::Mutex;
use std::sync::atomic::{AtomicBool, Ordering};

/// The options of `lpm sweep` that choose its runs, as a dict with every
/// key (the Python layer fills in the defaults).
#[derive(FromPyObject)]
#[pyo3(from_item_all)]
pub(crate) struct SweepOptions {
    /// The scenario; by default the one beside `spec` that names it.
    scenario: Option<PathBuf>,
    spec: Option<PathBuf>,
    grid: Vec<String>,
    samples: Option<usize>,
    vary: Vec<String>,
    design: String,
    seed: u64,
    set: Vec<String>,
    shard: Option<String>,
    shard_index: Option<usize>,
    shard_count: Option<u64>,
    threads: usize,
    out: Option<PathBuf>,
    format: Option<String>,
    /// Channels to envelope (`--envelope`).
    envelope: Vec<String>,
    /// The runs' weights in the envelope's mean (`--weights`).
    weights: Option<String>,
}

impl SweepOptions {
    /// The command line's options.
    fn args(self) -> Result<SweepRequest, StudyError> {
        let scenario = match (self.scenario, &self.spec) {
            (Some(scenario), _) => scenario,
            (None, Some(spec)) => lagrangian_studies::spec::find_scenario(&**FILES, spec)?
                .ok_or_else(|| {
                    StudyError::usage(format!(
                        "no scenario names {}; give one with scenario=",
                        spec.display()
                    ))
                })?,
            (None, None) => return Err(StudyError::usage("give a spec, a scenario or both")),
        };
        Ok(SweepRequest {
            scenario,
            spec: self.spec,
            grid: self.grid,
            samples: self.samples,
            vary: self.vary,
            design: memory::design(&self.design)?,
            seed: self.seed,
            set: Override::parse_all(&self.set)?,
            out: self.out,
            format: self.format,
            shard: self.shard,
            shard_index: self.shard_index,
            shard_count: self.shard_count,
            plan_only: false,
            merge: Vec::new(),
            threads: self.threads,
            resume: false,
            envelope: EnvelopeOptions {
                envelope: self.envelope,
                weights: self.weights,
                ..Default::default()
            },
        })
    }
}

/// The bytes of a CSV table as text (the tables are UTF-8).
fn text(bytes: Vec<u8>) -> Result<String, StudyError> {
    String::from_utf8(bytes).map_err(|e| StudyError::io(format!("the table is not UTF-8: {e}")))
}

/// The sweep's table and envelope table (CSV bytes), the GIL released
/// while the runs go on; a signal (Ctrl-C) stops the sweep and raises its
/// exception.
fn sweep_tables(py: Python<'_>, options: SweepOptions) -> PyResult<(Vec<u8>, Option<Vec<u8>>)> {
    let args = options.args().map_err(raise)?;
    let progress = Signals {
        stop: AtomicBool::new(false),
        interrupt: Mutex::new(None),
    };
    let tables = py.detach(|| memory::tables(&args, &progress, &FILES));
    if let Some(e) = (progress.interrupt.into_inner()).unwrap_or_else(|e| e.into_inner()) {
        return Err(e);
    }
    tables.map_err(raise)
}

/// The progress of a sweep from Python: after each run, the signals
/// Python has seen; the first one (Ctrl-C) stops the sweep and is kept, to
/// be raised.
struct Signals {
    stop: AtomicBool,
    interrupt: Mutex<Option<PyErr>>,
}

impl Progress for Signals {
    fn run_done(&self) {
        if let Err(e) = Python::attach(|py| py.check_signals()) {
            self.stop.store(true, Ordering::SeqCst);
            (self.interrupt.lock())
                .unwrap_or_else(|e| e.into_inner())
                .get_or_insert(e);
        }
    }

    fn stop_requested(&self) -> bool {
        self.stop.load(Ordering::SeqCst)
    }
}

/// The CSV table of the sweep (or shard) of `options`, as `lpm sweep --out
/// FILE.csv` writes it. The GIL is released while the runs go on; a signal
/// (Ctrl-C) stops the sweep and raises its exception.
#[pyfunction]
pub(crate) fn sweep_table(py: Python<'_>, options: SweepOptions) -> PyResult<String> {
    let (table, _) = sweep_tables(py, options)?;
    text(table).map_err(raise)
}

/// [`sweep_table`] with the envelope table of `options["envelope"]`'s
/// channels, as `--envelope-out FILE.csv` writes it: `(table, envelope)`;
/// for a shard, the envelope is the partial envelope (JSON) the command
/// writes beside the shard's table.
#[pyfunction]
pub(crate) fn sweep_envelope(py: Python<'_>, options: SweepOptions) -> PyResult<(String, String)> {
    let (table, envelope) = sweep_tables(py, options)?;
    let envelope =
        envelope.ok_or_else(|| raise(StudyError::usage("give the channels to envelope")))?;
    Ok((text(table).map_err(raise)?, text(envelope).map_err(raise)?))
}

/// `lpm sweep --merge PARTS`: the shards' table files checked against the
/// plan of `options` and merged, as the CSV text of one full run's table;
/// with `out` in `options` also written there.
#[pyfunction]
pub(crate) fn sweep_merge(
    py: Python<'_>,
    options: SweepOptions,
    parts: Vec<PathBuf>,
) -> PyResult<String> {
    let args = options.args().map_err(raise)?;
    py.detach(|| memory::merged(&args, &parts, &FILES).and_then(text))
        .map_err(raise)
}

/// [`sweep_merge`] with the envelope of `options["envelope"]`'s channels
/// merged from the partial envelopes beside the parts
/// (`PART.envelope.json`): `(table, envelope)` as CSV text.
#[pyfunction]
pub(crate) fn sweep_merge_envelope(
    py: Python<'_>,
    options: SweepOptions,
    parts: Vec<PathBuf>,
) -> PyResult<(String, String)> {
    let args = options.args().map_err(raise)?;
    let (table, envelope) = py
        .detach(|| memory::merged_tables(&args, &parts, &FILES))
        .map_err(raise)?;
    let envelope =
        envelope.ok_or_else(|| raise(StudyError::usage("give the channels to envelope")))?;
    Ok((text(table).map_err(raise)?, text(envelope).map_err(raise)?))
}

/// What `lpm sweep --plan` prints for `options`.
#[pyfunction]
pub(crate) fn sweep_plan(py: Python<'_>, options: SweepOptions) -> PyResult<String> {
    let args = options.args().map_err(raise)?;
    py.detach(|| memory::plan(&args, &FILES)).map_err(raise)
}

/// The options of `lpm fit`, as a dict with every key.
#[derive(FromPyObject)]
#[pyo3(from_item_all)]
pub(crate) struct FitOptions {
    spec: PathBuf,
    target: PathBuf,
    channel: Vec<String>,
    scenario: Option<PathBuf>,
    fit: Vec<String>,
    set: Vec<String>,
    out: Option<PathBuf>,
    starts: usize,
    seed: u64,
}

/// What `fit` returns: the report `lpm fit` prints (without the line
/// naming its files) and the files `(name, contents)`: `fitted.toml`,
/// `fit.json`, `fit.svg`.
pub(crate) type Fitted = (String, Vec<(String, String)>);

/// `lpm fit`: the printed report and the files, written into `out` when
/// it is given; without it, the fitted scenario's relative paths start
/// from the current directory.
#[pyfunction]
pub(crate) fn fit(py: Python<'_>, options: FitOptions) -> PyResult<Fitted> {
    let request = FitRequest {
        spec: options.spec,
        target: options.target,
        channels: (options.channel.iter())
            .map(|text| ChannelRequest::parse(text))
            .collect::<Result<_, _>>()
            .map_err(raise)?,
        scenario: options.scenario,
        fit: options.fit,
        set: Override::parse_all(&options.set).map_err(raise)?,
        starts: options.starts,
        seed: options.seed,
    };
    let out = options.out;
    let fitted = py.detach(|| -> Result<Fitted, StudyError> {
        let fitting = fitting::fitting(&request, &|_, _| {}, &FILES)?;
        let files = match &out {
            Some(out) => fitting::write_files(&fitting, out)?,
            None => fitting::outputs(&fitting, Path::new("."))?,
        };
        let files = files.map(|(name, contents)| (name.to_string(), contents));
        Ok((fitting::summary_text(&fitting), files.to_vec()))
    });
    fitted.map_err(raise)
}
