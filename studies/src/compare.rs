//! A comparison as a host runs it (`lpm compare`): the channels of a
//! reference source (a test) paired with a comparison's (a model run),
//! each pair rated by ISO/TS 18571 (`lagrangian-correlation`), as text,
//! JSON and one overlay plot per pair.
//!
//! Sources are read into named signals ([`source`]); pairs are the ones
//! asked for (`REF=COMP`), or else every channel name the two sources
//! share. A comparison channel in another unit than its reference's is
//! converted to it (`g` and `m/s^2`, `kN` and `N`); a channel without a
//! unit is taken as it is.

mod error;
pub mod source;

pub use error::CompareError;

use crate::error::StudyError;
use crate::plot::{Series, panels_svg};
use lagrangian_correlation::{Curve, Options, Rating, iso18571};
use lagrangian_sim::files::Files;
use lagrangian_sim::quantity::value_in;
use lagrangian_sim::report::write_all_atomically;
use source::{Signal, Signals, Source};
use std::fmt::Write;
use std::path::{Path, PathBuf};

/// What to compare (`lpm compare`'s options without the output's).
#[derive(Clone, Debug, PartialEq)]
pub struct CompareRequest {
    /// The reference (the test): a CSV file or a simulation output folder.
    pub reference: PathBuf,
    /// The comparison (the model), likewise.
    pub comparison: PathBuf,
    /// The pairs to rate; empty: every channel name both sources have.
    pub channels: Vec<ChannelPair>,
    /// The interval to rate `(start, end)` \[s\], within each pair's
    /// common one; `None`: all of it.
    pub interval: Option<(f64, f64)>,
}

/// A reference channel and the comparison channel rated against it.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct ChannelPair {
    /// The reference's channel.
    pub reference: String,
    /// The comparison's channel.
    pub comparison: String,
}

impl ChannelPair {
    /// Reads `REF=COMP`, or `NAME` for the channel of that name in both.
    pub fn parse(text: &str) -> Result<ChannelPair, CompareError> {
        let (reference, comparison) = text.split_once('=').unwrap_or((text, text));
        let (reference, comparison) = (reference.trim(), comparison.trim());
        if reference.is_empty() || comparison.is_empty() || comparison.contains('=') {
            return Err(CompareError::BadPair {
                text: text.to_string(),
            });
        }
        Ok(ChannelPair {
            reference: reference.to_string(),
            comparison: comparison.to_string(),
        })
    }
}

/// One pair, rated.
#[derive(Clone, Debug, PartialEq)]
pub struct PairRating {
    /// The reference channel.
    pub reference: Signal,
    /// The comparison channel, converted to the reference's unit.
    pub comparison: Signal,
    /// Its rating.
    pub rating: Rating,
}

/// A pair of channels of the same name that could not be rated (only
/// when the pairs are found by name: a pair asked for fails the
/// comparison instead).
#[derive(Clone, Debug, PartialEq)]
pub struct Skipped {
    /// The channels' name.
    pub name: String,
    /// Why.
    pub error: CompareError,
}

impl Skipped {
    /// Why, without the pair's names (which the skipped entry has).
    pub fn reason(&self) -> String {
        match &self.error {
            CompareError::Rating { error, .. } => error.to_string(),
            other => other.to_string(),
        }
    }
}

/// A finished comparison.
#[derive(Clone, Debug, PartialEq)]
pub struct Comparison {
    /// The reference's file.
    pub reference: PathBuf,
    /// The comparison's file.
    pub comparison: PathBuf,
    /// The pairs rated, in the order asked for (or the reference's).
    pub pairs: Vec<PairRating>,
    /// The pairs found by name that could not be rated.
    pub skipped: Vec<Skipped>,
}

/// The comparison `request` describes, its files read from `files`.
pub fn compare(request: &CompareRequest, files: &dyn Files) -> Result<Comparison, StudyError> {
    let reference = Source::at(&request.reference).read(files)?;
    let comparison = Source::at(&request.comparison).read(files)?;
    compare_signals(reference, comparison, &request.channels, request.interval)
}

/// The comparison of signals already read: the pairs `channels` asks for
/// (by name where empty), over `interval` where given.
pub fn compare_signals(
    reference: Signals,
    comparison: Signals,
    channels: &[ChannelPair],
    interval: Option<(f64, f64)>,
) -> Result<Comparison, StudyError> {
    let (pairs, skipped) = match channels.is_empty() {
        true => rate_by_name(&reference, &comparison, interval)?,
        false => (
            rate_asked(channels, &reference, &comparison, interval)?,
            Vec::new(),
        ),
    };
    Ok(Comparison {
        reference: reference.file,
        comparison: comparison.file,
        pairs,
        skipped,
    })
}

/// Each pair asked for, rated; the first that cannot be fails them all.
fn rate_asked(
    asked: &[ChannelPair],
    reference: &Signals,
    comparison: &Signals,
    interval: Option<(f64, f64)>,
) -> Result<Vec<PairRating>, CompareError> {
    (asked.iter())
        .map(|pair| {
            let r = reference.get(&pair.reference)?;
            rate(r, comparison.get(&pair.comparison)?, interval)
        })
        .collect()
}

/// The channels of the same name, rated, and those that cannot be (at
/// least one must be).
fn rate_by_name(
    reference: &Signals,
    comparison: &Signals,
    interval: Option<(f64, f64)>,
) -> Result<(Vec<PairRating>, Vec<Skipped>), CompareError> {
    let (mut pairs, mut skipped) = (Vec::new(), Vec::new());
    for (r, c) in same_names(reference, comparison)? {
        match rate(r, c, interval) {
            Ok(pair) => pairs.push(pair),
            Err(error) => skipped.push(Skipped {
                name: r.name.clone(),
                error,
            }),
        }
    }
    match skipped.first() {
        Some(first) if pairs.is_empty() => Err(CompareError::NothingRated {
            first: Box::new(first.error.clone()),
        }),
        _ => Ok((pairs, skipped)),
    }
}

/// The reference's signals that have a namesake in the comparison, with it.
fn same_names<'a>(
    reference: &'a Signals,
    comparison: &'a Signals,
) -> Result<Vec<(&'a Signal, &'a Signal)>, CompareError> {
    let pairs: Vec<_> = (reference.signals.iter())
        .filter_map(|r| Some((r, comparison.signals.iter().find(|c| c.name == r.name)?)))
        .collect();
    match pairs.is_empty() {
        true => Err(CompareError::NothingInCommon {
            reference: reference.file.clone(),
            comparison: comparison.file.clone(),
        }),
        false => Ok(pairs),
    }
}

/// The rating of `comparison` (in the reference's unit) against
/// `reference`, within `interval` where one is given.
fn rate(
    reference: &Signal,
    comparison: &Signal,
    interval: Option<(f64, f64)>,
) -> Result<PairRating, CompareError> {
    let comparison = in_unit_of(comparison, reference)?;
    let rating = iso18571(
        &Curve {
            t: &reference.t,
            y: &reference.y,
        },
        &Curve {
            t: &comparison.t,
            y: &comparison.y,
        },
        &Options {
            interval,
            ..Options::default()
        },
    );
    let rating = rating.map_err(|error| CompareError::Rating {
        reference: reference.name.clone(),
        comparison: comparison.name.clone(),
        error,
    })?;
    Ok(PairRating {
        reference: reference.clone(),
        comparison,
        rating,
    })
}

/// `signal` in the unit of `like`, where both have one.
fn in_unit_of(signal: &Signal, like: &Signal) -> Result<Signal, CompareError> {
    let (Some(from), Some(to)) = (&signal.unit, &like.unit) else {
        return Ok(signal.clone());
    };
    let factor = conversion(from, to).ok_or_else(|| CompareError::Units {
        reference: like.name.clone(),
        reference_unit: to.clone(),
        comparison: signal.name.clone(),
        comparison_unit: from.clone(),
    })?;
    Ok(Signal {
        unit: Some(to.clone()),
        y: signal.y.iter().map(|v| v * factor).collect(),
        ..signal.clone()
    })
}

/// What one `from` is in `to`, where both are units of one dimension (a
/// `g` beside an acceleration is standard gravity).
fn conversion(from: &str, to: &str) -> Option<f64> {
    if from == to {
        return Some(1.0);
    }
    let one_in = |a: &str, b: &str| value_in(&format!("1 {a}"), b).ok();
    one_in(from, to).or_else(|| one_in(to, from).map(|f| 1.0 / f))
}

/// A channel's name with its unit (`force [kN]`).
fn labelled(signal: &Signal) -> String {
    match &signal.unit {
        Some(unit) => format!("{} [{unit}]", signal.name),
        None => signal.name.clone(),
    }
}

/// `{"reference", "comparison", "pairs": [...], "skipped": [...]}`: per
/// pair the channels, the unit, the four scores, the overall rating, the
/// grade, the time shift \[s\] and the interval rated \[s\].
pub fn json(comparison: &Comparison) -> String {
    let pairs: Vec<serde_json::Value> = (comparison.pairs.iter())
        .map(|p| {
            let r = &p.rating;
            serde_json::json!({
                "reference": p.reference.name,
                "comparison": p.comparison.name,
                "unit": p.reference.unit,
                "corridor": r.corridor,
                "phase": r.phase,
                "magnitude": r.magnitude,
                "slope": r.slope,
                "overall": r.overall,
                "grade": r.grade.name(),
                "time_shift_s": r.time_shift_s,
                "interval_s": [r.interval_s.0, r.interval_s.1],
            })
        })
        .collect();
    let skipped: Vec<serde_json::Value> = (comparison.skipped.iter())
        .map(|s| serde_json::json!({"channel": s.name, "reason": s.reason()}))
        .collect();
    let document = serde_json::json!({
        "reference": comparison.reference.display().to_string(),
        "comparison": comparison.comparison.display().to_string(),
        "pairs": pairs,
        "skipped": skipped,
    });
    serde_json::to_string_pretty(&document).unwrap_or_default() + "\n"
}

/// The comparison as a table, one line per pair, then the pairs skipped.
pub fn text_report(comparison: &Comparison) -> String {
    let mut out = String::new();
    let _ = writeln!(
        out,
        "ISO/TS 18571 rating of {} against {} (reference)",
        comparison.comparison.display(),
        comparison.reference.display()
    );
    let names: Vec<String> = comparison.pairs.iter().map(pair_name).collect();
    let width = names
        .iter()
        .map(|n| n.chars().count())
        .max()
        .unwrap_or(0)
        .max(7);
    let _ = writeln!(
        out,
        "  {:width$}  corridor  phase  magnitude  slope  overall  grade",
        "channel"
    );
    for (name, p) in names.iter().zip(&comparison.pairs) {
        let r = &p.rating;
        let _ = writeln!(
            out,
            "  {name:width$}  {:>8.3}  {:>5.3}  {:>9.3}  {:>5.3}  {:>7.3}  {}",
            r.corridor, r.phase, r.magnitude, r.slope, r.overall, r.grade
        );
    }
    for s in &comparison.skipped {
        let _ = writeln!(out, "  skipped {}: {}", s.name, s.reason());
    }
    out
}

/// A pair as the table and the plots name it: `x [m]`, or `a [g] = a_sim
/// [g]` where the names differ.
fn pair_name(pair: &PairRating) -> String {
    match pair.reference.name == pair.comparison.name {
        true => labelled(&pair.reference),
        false => format!("{} = {}", labelled(&pair.reference), pair.comparison.name),
    }
}

/// One overlay figure per pair: its file name (`NAME.svg`, or
/// `REF-vs-COMP.svg`, made safe for a file system and unique) and SVG.
pub fn plots(comparison: &Comparison) -> Result<Vec<(String, String)>, StudyError> {
    let mut names: Vec<String> = Vec::new();
    let mut figures = Vec::new();
    for pair in &comparison.pairs {
        let mut stem = file_stem(pair);
        let base = stem.clone();
        for k in 2.. {
            if !names.contains(&stem) {
                break;
            }
            stem = format!("{base}-{k}");
        }
        names.push(stem.clone());
        figures.push((format!("{stem}.svg"), overlay(comparison, pair)?));
    }
    Ok(figures)
}

/// `NAME`, or `REF-vs-COMP`, with every character but letters, digits,
/// `.`, `_` and `-` replaced by `_`.
fn file_stem(pair: &PairRating) -> String {
    let (r, c) = (&pair.reference.name, &pair.comparison.name);
    let stem = match r == c {
        true => r.clone(),
        false => format!("{r}-vs-{c}"),
    };
    let safe = |ch: char| ch.is_ascii_alphanumeric() || matches!(ch, '.' | '_' | '-');
    let stem: String = stem
        .chars()
        .map(|ch| if safe(ch) { ch } else { '_' })
        .collect();
    match stem.trim_start_matches('.').is_empty() {
        true => "channel".to_string(),
        false => stem,
    }
}

/// The overlay of one pair: both curves against time in ms over the
/// interval rated, the overall rating in the title, the four scores above
/// the panel.
fn overlay(comparison: &Comparison, pair: &PairRating) -> Result<String, StudyError> {
    let r = &pair.rating;
    let title = format!(
        "{}: ISO/TS 18571 overall {:.3} ({})",
        pair_name(pair),
        r.overall,
        r.grade
    );
    let scores = format!(
        "corridor {:.3}, phase {:.3}, magnitude {:.3}, slope {:.3}",
        r.corridor, r.phase, r.magnitude, r.slope
    );
    let points = |s: &Signal| points_within(s, r.interval_s);
    let series: Vec<Series> = vec![
        (
            format!(
                "reference: {} {}",
                source_label(&comparison.reference),
                pair.reference.name
            ),
            points(&pair.reference),
        ),
        (
            format!(
                "comparison: {} {}",
                source_label(&comparison.comparison),
                pair.comparison.name
            ),
            points(&pair.comparison),
        ),
    ];
    let panel = (
        scores,
        "t [ms]".to_string(),
        labelled(&pair.reference),
        series,
    );
    panels_svg(&title, &[panel]).map_err(|e| StudyError::io(format!("plotting failed: {e}")))
}

/// The points `(t [ms], y)` of `signal` over `(start, end)` \[s\], with
/// the sample before and the one after, so that the line reaches both.
fn points_within(signal: &Signal, (start, end): (f64, f64)) -> Vec<(f64, f64)> {
    let t = &signal.t;
    let first = t.partition_point(|&t| t <= start).saturating_sub(1);
    let last = t.partition_point(|&t| t < end).min(t.len() - 1);
    (t[first..=last].iter().map(|t| t * 1e3))
        .zip(signal.y[first..=last].iter().copied())
        .collect()
}

/// A source as a legend names it: a CSV file by its name, a run by its
/// folder's.
fn source_label(file: &Path) -> String {
    let name = |p: &Path| p.file_name().map(|n| n.to_string_lossy().into_owned());
    let folder = file
        .parent()
        .filter(|_| name(file).as_deref() == Some(source::TRAJECTORY));
    (folder.and_then(name).or_else(|| name(file))).unwrap_or_else(|| file.display().to_string())
}

/// Writes [`plots`] into directory `out`, creating it, all or none; returns
/// their paths.
pub fn write_plots(comparison: &Comparison, out: &Path) -> Result<Vec<PathBuf>, StudyError> {
    let io = |path: &Path, e: std::io::Error| {
        StudyError::io(format!("cannot write {}: {e}", path.display()))
    };
    std::fs::create_dir_all(out).map_err(|e| io(out, e))?;
    let figures = plots(comparison)?;
    let paths: Vec<PathBuf> = figures.iter().map(|(name, _)| out.join(name)).collect();
    let contents: Vec<(&Path, &[u8])> = (paths.iter().zip(&figures))
        .map(|(path, (_, svg))| (path.as_path(), svg.as_bytes()))
        .collect();
    write_all_atomically(&contents).map_err(|(path, e)| io(&path, e))?;
    Ok(paths)
}

#[cfg(test)]
mod tests;
