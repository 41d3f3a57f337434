//! A sweep without its files, for the Python package: the table of a
//! sweep (or of one shard), the merge of shards' tables and the plan, each
//! made by the code of `lpm sweep` and handed back as the bytes or text the
//! command would write.
//!
//! Nothing here keeps a journal: the caller's [`Progress`] sees each
//! finished run and may ask the sweep to stop (the host process owns its
//! signals).

use super::{
    Enveloping, Prepared, Progress, Sweep, SweepRequest, Tally, envelope, merge, merge_into,
    plan_report, prepare, shard, wants_parquet,
};
use crate::error::StudyError;
use crate::sweep::{Design, Envelope, Row, Shard, SweepJob, sweep_csv, write_envelope_csv};
use lagrangian_sim::files::Files;
use std::path::PathBuf;
use std::sync::Arc;

/// The runs of the shard `options` names, as the CSV bytes `lpm sweep
/// --out FILE.csv` writes for the same options (`out`, `format`, `plan`,
/// `merge`, `quiet` and `resume` are not read).
///
/// `progress.run_done` is called on the calling thread after every
/// finished run; once `progress.stop_requested` says yes the sweep ends
/// like the first Ctrl-C of the command (an `Interrupted` error). When
/// every run fails the error is `EveryRunFailed`, as the command's exit
/// status.
pub fn table(
    options: &SweepRequest,
    progress: &dyn Progress,
    files: &Arc<dyn Files>,
) -> Result<Vec<u8>, StudyError> {
    tables(options, progress, files).map(|(table, _)| table)
}

/// [`table`], and with `options.envelope`'s channels the envelope table
/// as the CSV bytes `--envelope-out FILE.csv` writes — for a shard, the
/// partial envelope the command writes beside the shard's table (JSON).
pub fn tables(
    options: &SweepRequest,
    progress: &dyn Progress,
    files: &Arc<dyn Files>,
) -> Result<(Vec<u8>, Option<Vec<u8>>), StudyError> {
    check_shard_count(options)?;
    let shard = shard(options)?;
    let prepared = prepare(options, files)?;
    let request = envelope::request(options, &prepared)?;
    let mut accumulated = request
        .as_ref()
        .map(|r| (r.job(), Envelope::new(&r.channels)));
    let Prepared {
        plan,
        model,
        base,
        settings,
        layout,
    } = prepared;
    let runs = shard.runs(plan.len());
    let mut rows = Vec::with_capacity(runs.len());
    let mut tally = Tally::default();
    let mut sink = |row: Row| -> Result<(), StudyError> {
        tally.count(&row);
        rows.push(row);
        progress.run_done();
        Ok(())
    };
    let job = SweepJob {
        base: &base,
        plan: &plan,
        settings: &settings,
        runs: runs.clone(),
        threads: options.threads,
    };
    let stop = || progress.stop_requested();
    let sweep = Sweep {
        job,
        stop: &stop,
        sink: &mut sink,
        envelope: (accumulated.as_mut()).map(|(job, envelope)| Enveloping {
            job: *job,
            envelope,
            after: None,
        }),
    };
    let finished = model.with_dimension(sweep).map_err(StudyError::model)??;
    check_finished(finished, runs.len(), &tally)?;
    let table = sweep_csv(&layout, &rows)?;
    let envelope = match (&request, accumulated) {
        (Some(request), Some((_, envelope))) if shard != Shard::ALL => {
            Some(envelope::partial_json(request, &plan, &runs, envelope)?)
        }
        (_, accumulated) => (accumulated.map(|(_, e)| envelope_csv(&e))).transpose()?,
    };
    Ok((table, envelope))
}

/// An interrupted sweep, or one whose every run failed, is a failure.
fn check_finished(finished: usize, runs: usize, tally: &Tally) -> Result<(), StudyError> {
    if finished < runs {
        return Err(StudyError::Interrupted {
            message: format!("stopped after {finished} of {runs} runs"),
            journal: None,
        });
    }
    if let (0, Some((run, message))) = (tally.ok, &tally.first_failure) {
        return Err(StudyError::EveryRunFailed(format!(
            "every run failed; the first, run {run}: {message}"
        )));
    }
    Ok(())
}

/// The CSV bytes of an envelope's table.
fn envelope_csv(envelope: &Envelope) -> Result<Vec<u8>, StudyError> {
    let mut bytes = Vec::new();
    write_envelope_csv(envelope, &mut bytes)?;
    Ok(bytes)
}

/// `lpm sweep --merge PARTS --out FILE.csv` in memory: the shards' tables
/// (files, CSV or Parquet) checked against the plan of `options`, as the
/// CSV bytes of one full run's table. With `options.out` the command's
/// merge also writes that file (CSV or Parquet, as `--format` or the
/// extension says).
pub fn merged(
    options: &SweepRequest,
    parts: &[PathBuf],
    files: &Arc<dyn Files>,
) -> Result<Vec<u8>, StudyError> {
    let prepared = prepare(options, files)?;
    if let Some(out) = &options.out {
        merge(parts, &prepared, out, wants_parquet(options, out)?)?;
    }
    let mut bytes = Vec::new();
    merge_into(parts, &prepared, false, &mut bytes)?;
    Ok(bytes)
}

/// [`merged`], and with `options.envelope`'s channels the envelope of the
/// whole sweep from the partial envelopes beside the parts
/// (`PART.envelope.json`), as the CSV bytes `--envelope-out FILE.csv`
/// writes.
pub fn merged_tables(
    options: &SweepRequest,
    parts: &[PathBuf],
    files: &Arc<dyn Files>,
) -> Result<(Vec<u8>, Option<Vec<u8>>), StudyError> {
    let prepared = prepare(options, files)?;
    let request = envelope::request(options, &prepared)?;
    let envelope = (request.as_ref())
        .map(|request| envelope::merged(request, parts, &prepared))
        .transpose()?;
    if let Some(out) = &options.out {
        merge(parts, &prepared, out, wants_parquet(options, out)?)?;
    }
    let mut bytes = Vec::new();
    merge_into(parts, &prepared, false, &mut bytes)?;
    Ok((bytes, envelope.as_ref().map(envelope_csv).transpose()?))
}

/// What `lpm sweep --plan` prints for `options`.
pub fn plan(options: &SweepRequest, files: &Arc<dyn Files>) -> Result<String, StudyError> {
    plan_report(prepare(options, files)?)
}

/// The command line refuses `--shard-count 0` while parsing; so does this.
fn check_shard_count(options: &SweepRequest) -> Result<(), StudyError> {
    match options.shard_count {
        Some(0) => Err(StudyError::usage(
            "shard count 0: split into at least 1 shard",
        )),
        _ => Ok(()),
    }
}

/// The design `--design NAME` names (`latin-hypercube` or `random`).
pub fn design(name: &str) -> Result<Design, StudyError> {
    match name {
        "latin-hypercube" => Ok(Design::LatinHypercube),
        "random" => Ok(Design::Random),
        _ => Err(StudyError::usage(format!(
            "design `{name}`: choose latin-hypercube or random"
        ))),
    }
}
