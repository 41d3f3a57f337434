//! `lpm sweep` without its files, for the Python package: the table of a
//! sweep (or of one shard), the merge of shards' tables and the plan, each
//! made by the code of the command line and handed back as the bytes or
//! text the command would write.
//!
//! Nothing here draws a progress bar, keeps a journal or installs a signal
//! handler (the host process owns its signals): the caller passes a `stop`
//! flag and sees each finished run.

use super::{
    Args, DesignArg, Enveloping, Prepared, Sweep, Tally, envelope, merge, merge_into, plan_report,
    prepare, shard, wants_parquet,
};
use crate::failure::Failure;
use crate::status::ExitStatus;
use clap::ValueEnum;
use lagrangian_studies::sweep::{Envelope, Row, Shard, SweepJob, sweep_csv, write_envelope_csv};
use std::path::PathBuf;
use std::sync::atomic::AtomicBool;

/// The runs of the shard `options` names, as the CSV bytes `lpm sweep
/// --out FILE.csv` writes for the same options (`out`, `format`, `plan`,
/// `merge`, `quiet` and `resume` are not read).
///
/// `each_run` is called on the calling thread after every finished run; it
/// may set `stop`, which ends the sweep like the first Ctrl-C of the command
/// (an `Interrupted` failure). When every run fails the failure is
/// `EveryRunFailed`, as the command's exit status.
pub fn table(
    options: &Args,
    stop: &AtomicBool,
    each_run: &mut dyn FnMut(),
) -> Result<Vec<u8>, Failure> {
    tables(options, stop, each_run).map(|(table, _)| table)
}

/// [`table`], and with `options.envelope`'s channels the envelope table
/// as the CSV bytes `--envelope-out FILE.csv` writes — for a shard, the
/// partial envelope the command writes beside the shard's table (JSON).
pub fn tables(
    options: &Args,
    stop: &AtomicBool,
    each_run: &mut dyn FnMut(),
) -> Result<(Vec<u8>, Option<Vec<u8>>), Failure> {
    check_shard_count(options)?;
    let shard = shard(options).map_err(Failure::usage)?;
    let prepared = prepare(options)?;
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
    let mut sink = |row: Row| -> Result<(), String> {
        tally.count(&row);
        rows.push(row);
        each_run();
        Ok(())
    };
    let job = SweepJob {
        base: &base,
        plan: &plan,
        settings: &settings,
        runs: runs.clone(),
        threads: options.threads,
    };
    let sweep = Sweep {
        job,
        stop,
        sink: &mut sink,
        envelope: (accumulated.as_mut()).map(|(job, envelope)| Enveloping {
            job: *job,
            envelope,
            after: None,
        }),
    };
    let finished = model.with_dimension(sweep).map_err(Failure::model)??;
    check_finished(finished, runs.len(), &tally)?;
    let table = sweep_csv(&layout, &rows).map_err(Failure::io)?;
    let envelope = match (&request, accumulated) {
        (Some(request), Some((_, envelope))) if shard != Shard::ALL => {
            Some(envelope::partial_json(request, &plan, &runs, envelope)?)
        }
        (_, accumulated) => (accumulated.map(|(_, e)| envelope_csv(&e))).transpose()?,
    };
    Ok((table, envelope))
}

/// An interrupted sweep, or one whose every run failed, is a failure.
fn check_finished(finished: usize, runs: usize, tally: &Tally) -> Result<(), Failure> {
    if finished < runs {
        return Err(Failure::new(
            ExitStatus::Interrupted,
            format!("stopped after {finished} of {runs} runs"),
        ));
    }
    if let (0, Some((run, message))) = (tally.ok, &tally.first_failure) {
        return Err(Failure::new(
            ExitStatus::EveryRunFailed,
            format!("every run failed; the first, run {run}: {message}"),
        ));
    }
    Ok(())
}

/// The CSV bytes of an envelope's table.
fn envelope_csv(envelope: &Envelope) -> Result<Vec<u8>, Failure> {
    let mut bytes = Vec::new();
    write_envelope_csv(envelope, &mut bytes).map_err(Failure::io)?;
    Ok(bytes)
}

/// `lpm sweep --merge PARTS --out FILE.csv` in memory: the shards' tables
/// (files, CSV or Parquet) checked against the plan of `options`, as the
/// CSV bytes of one full run's table. With `options.out` the command's
/// merge also writes that file (CSV or Parquet, as `--format` or the
/// extension says).
pub fn merged(options: &Args, parts: &[PathBuf]) -> Result<Vec<u8>, Failure> {
    let prepared = prepare(options)?;
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
    options: &Args,
    parts: &[PathBuf],
) -> Result<(Vec<u8>, Option<Vec<u8>>), Failure> {
    let prepared = prepare(options)?;
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
pub fn plan(options: &Args) -> Result<String, Failure> {
    Ok(plan_report(prepare(options)?)?.text)
}

/// The command line refuses `--shard-count 0` while parsing; so does this.
fn check_shard_count(options: &Args) -> Result<(), Failure> {
    match options.shard_count {
        Some(0) => Err(Failure::usage("shard count 0: split into at least 1 shard")),
        _ => Ok(()),
    }
}

/// The design `--design NAME` names (`latin-hypercube` or `random`).
pub fn design(name: &str) -> Result<DesignArg, Failure> {
    <DesignArg as ValueEnum>::from_str(name, false).map_err(|_| {
        let names: Vec<String> = (DesignArg::value_variants().iter())
            .filter_map(|d| d.to_possible_value())
            .map(|v| v.get_name().to_string())
            .collect();
        Failure::usage(format!("design `{name}`: choose {}", names.join(" or ")))
    })
}
