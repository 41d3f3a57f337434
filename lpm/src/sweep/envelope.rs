//! `lpm sweep --envelope`: the flags that ask for envelopes and weighted
//! mean histories of chosen channels, what they are read into, and the
//! files they write.

use super::{Args, Prepared, write_beside};
use crate::failure::Failure;
use lagrangian_sim::plot::{Band, bands_svg};
use lagrangian_sim::scenario::Signal;
use lagrangian_sim::sweep::{
    Envelope, EnvelopeJob, Shard, Weights, run_scenario, write_envelope_csv, write_envelope_parquet,
};
use std::path::{Path, PathBuf};

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
    /// The envelope table: .csv or .parquet, one row per output time.
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
}

/// The envelope request of `options`, `None` without `--envelope`.
pub(super) fn request(
    options: &Args,
    shard: Shard,
    prepared: &Prepared,
) -> Result<Option<EnvelopeRequest>, Failure> {
    let args = &options.envelope;
    if args.envelope.is_empty() {
        return Ok(None);
    }
    refuse_partial_sweeps(options, shard)?;
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

/// Shards, merges and resumed sweeps do not see every run's history.
fn refuse_partial_sweeps(options: &Args, shard: Shard) -> Result<(), Failure> {
    let why = if shard != Shard::ALL {
        "--envelope with a shard: a shard writes no envelope (its runs are a part of the sweep); run the sweep whole for its envelope"
    } else if !options.merge.is_empty() {
        "--envelope with --merge: the shards' tables hold no histories to envelope; run the sweep whole for its envelope"
    } else if options.resume {
        "--envelope with --resume: the journal holds the finished runs' metrics, not their histories; delete it and run the sweep again"
    } else {
        return Ok(());
    };
    Err(Failure::usage(why))
}

/// Whether the envelope table is Parquet, from its extension.
fn table_is_parquet(out: &Path) -> Result<bool, Failure> {
    match out.extension().and_then(|e| e.to_str()) {
        Some("parquet") => Ok(true),
        Some("csv") => Ok(false),
        _ => Err(Failure::usage(format!(
            "--envelope-out {}: name a .csv or .parquet file",
            out.display()
        ))),
    }
}

/// The channels of `--envelope`, read against the names of the first
/// run's scenario (its components' columns included).
fn channels(names: &[String], prepared: &Prepared) -> Result<Vec<Signal>, Failure> {
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
    let first = first.map_err(|e| Failure::scenario(&e))?;
    let names_of_run = base.names.with_components(&first.inputs);
    (names.iter())
        .map(|name| Signal::parse("--envelope", name, &names_of_run).map_err(Failure::usage))
        .collect()
}

/// `--weights`: per grid value, or per run from a CSV file.
fn weights(text: &str, prepared: &Prepared) -> Result<Weights, Failure> {
    if text.contains('=') {
        return Weights::per_value(text, &prepared.plan).map_err(Failure::usage);
    }
    let file = std::fs::read_to_string(text)
        .map_err(|e| Failure::io(format!("--weights: cannot read {text}: {e}")))?;
    Weights::per_run_csv(&file, text, &prepared.plan).map_err(Failure::usage)
}

/// Writes the envelope table (whole or not at all) and the plot; returns
/// the line `lpm sweep` reports them with.
pub(super) fn write(request: &EnvelopeRequest, envelope: &Envelope) -> Result<String, Failure> {
    let Some(out) = &request.out else {
        return Ok(String::new());
    };
    let parquet = table_is_parquet(out)?;
    write_beside(out, |file| match parquet {
        true => write_envelope_parquet(envelope, file),
        false => write_envelope_csv(envelope, file),
    })
    .map_err(Failure::io)?;
    let mut line = format!(
        "envelope of {} runs: wrote {}",
        envelope.runs,
        out.display()
    );
    if let Some(plot) = &request.plot {
        let svg = bands_svg("Envelopes over the runs", &bands(envelope)).map_err(Failure::io)?;
        std::fs::write(plot, svg)
            .map_err(|e| Failure::io(format!("cannot write {}: {e}", plot.display())))?;
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
