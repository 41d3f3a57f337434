//! `lpm compare REFERENCE COMPARISON`: the ISO/TS 18571 rating of each
//! channel pair ([`lagrangian_studies::compare`] does the work).

use crate::failure::{Failure, Outcome};
use lagrangian_sim::quantity::value_in;
use lagrangian_studies::compare::{
    ChannelPair, CompareRequest, compare, json, text_report, write_plots,
};
use lagrangian_studies::error::StudyError;
use lagrangian_studies::files::Files;
use std::fmt::Write;
use std::path::PathBuf;
use std::sync::Arc;

/// Options of `lpm compare`.
#[derive(clap::Args)]
pub struct Args {
    /// The reference (the test): a CSV file with units in its header, or
    /// a simulation output folder (its trajectory.csv).
    pub reference: PathBuf,
    /// The comparison (the model), likewise.
    pub comparison: PathBuf,
    /// A pair to rate: the reference's channel REF against the
    /// comparison's COMP (NAME alone: the same name in both); repeatable.
    /// Default: every channel name both have.
    #[arg(long = "channel", value_name = "REF=COMP")]
    pub channels: Vec<String>,
    /// The interval to rate, within each pair's common one: seconds, or
    /// times with a unit (`0:0.1`, `10 ms:80 ms`). Default: all of it.
    #[arg(long, value_name = "START:END", value_parser = interval, allow_hyphen_values = true)]
    pub interval: Option<(f64, f64)>,
    /// Output format.
    #[arg(long, value_parser = ["text", "json"], default_value = "text")]
    pub format: String,
    /// Write an overlay plot per pair (NAME.svg) into this directory.
    #[arg(long)]
    pub out: Option<PathBuf>,
}

impl Args {
    /// The comparison these options ask for.
    pub fn request(&self) -> Result<CompareRequest, Failure> {
        let channels = (self.channels.iter())
            .map(|text| ChannelPair::parse(text).map_err(StudyError::from))
            .collect::<Result<_, _>>()?;
        Ok(CompareRequest {
            reference: self.reference.clone(),
            comparison: self.comparison.clone(),
            channels,
            interval: self.interval,
        })
    }
}

/// `START:END`, each a number of seconds or a time with a unit.
fn interval(text: &str) -> Result<(f64, f64), String> {
    let time = |t: &str| match t.trim().parse::<f64>() {
        Ok(seconds) if seconds.is_finite() => Ok(seconds),
        Ok(_) => Err(format!("`{t}` is not a finite number of seconds")),
        Err(_) => value_in(t, "s").map_err(|e| e.to_string()),
    };
    let (start, end) =
        (text.split_once(':')).ok_or("expected START:END, e.g. 0:0.1 or 10 ms:80 ms")?;
    let (start, end) = (time(start)?, time(end)?);
    match start < end {
        true => Ok((start, end)),
        false => Err(format!("the start {start} s is not before the end {end} s")),
    }
}

/// Runs `lpm compare`.
pub fn run(args: Args, files: &Arc<dyn Files>) -> Result<Outcome, Failure> {
    let comparison = compare(&args.request()?, &**files)?;
    let written = match &args.out {
        Some(out) => write_plots(&comparison, out)?,
        None => Vec::new(),
    };
    if args.format == "json" {
        return Ok(Outcome::success(json(&comparison)));
    }
    let mut text = text_report(&comparison);
    for path in written {
        let _ = writeln!(text, "  wrote {}", path.display());
    }
    Ok(Outcome::success(text))
}
