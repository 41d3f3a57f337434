//! `lpm metrics FILE.csv`: crash-pulse metrics of a measured or exported pulse.

use crate::failure::{Failure, Outcome};
use lagrangian_sim::pulse::channels::{Quantity, read_time_histories};
use lagrangian_sim::pulse::{Pulse, PulseMetrics};
use lagrangian_sim::warning::{self, Warning};
use lagrangian_studies::files::Files;
use std::fmt::Write;
use std::path::{Path, PathBuf};
use std::sync::Arc;

/// Options of `lpm metrics`.
#[derive(clap::Args)]
pub struct Args {
    /// The pulse: a CSV file with units in its header.
    file: PathBuf,
    /// Impact velocity [m/s], if the file has no velocity column.
    #[arg(long, allow_negative_numbers = true)]
    v0: Option<f64>,
    #[arg(long, value_parser = ["text", "json"], default_value = "text")]
    format: String,
    /// Make warnings (a flipped acceleration column, a sample rate too low
    /// for a filter class) errors: exit status 9.
    #[arg(long)]
    strict: bool,
}

/// Runs `lpm metrics`.
pub fn run(args: Args, files: &Arc<dyn Files>) -> Result<Outcome, Failure> {
    let (file, v0, json) = (args.file.as_path(), args.v0, args.format == "json");
    let histories = read_time_histories(&**files, file).map_err(|e| Failure::channels(&e))?;
    let Some(acceleration) = histories.channel(Quantity::Acceleration) else {
        return Err(Failure::usage(format!(
            "{}: the metrics need an acceleration (or deceleration) column",
            file.display()
        )));
    };
    let v0 = match (v0, histories.channel(Quantity::Velocity)) {
        (Some(v), _) => v,
        (None, Some(v)) => v.values[0],
        (None, None) => {
            return Err(Failure::usage(format!(
                "{}: no velocity column to take the impact velocity from; give it with --v0 <m/s>",
                file.display()
            )));
        }
    };
    if !v0.is_finite() {
        return Err(Failure::usage(format!(
            "impact velocity {v0} is not a number"
        )));
    }
    let mut warnings: Vec<Warning> =
        warning::flipped_acceleration(&acceleration.header, &histories.t, &acceleration.values, v0)
            .into_iter()
            .collect();
    let crush = histories
        .channel(Quantity::Crush)
        .map(|c| c.values.as_slice());
    let evaluation = |e| Failure::evaluation(format!("{}: {e}", file.display()));
    let pulse =
        Pulse::resampled(&histories.t, &acceleration.values, v0, crush).map_err(evaluation)?;
    let metrics = pulse.metrics().map_err(evaluation)?;
    warnings.extend(pulse.filter_warnings());
    let text = if json {
        json_text(&metrics, &warnings)
    } else {
        text(&metrics, file)
    };
    Ok(crate::warnings::outcome(text, &warnings, args.strict))
}

/// The metrics as JSON, then their `warnings` (`[]` when none).
fn json_text(metrics: &PulseMetrics, warnings: &[Warning]) -> String {
    warning::json_with_warnings(metrics, warnings)
}

fn text(m: &PulseMetrics, file: &Path) -> String {
    let opt = |v: Option<f64>, scale: f64, unit: &str, digits: usize| {
        v.map_or("–".to_string(), |x| {
            format!("{:.*} {unit}", digits, x * scale)
        })
    };
    let mut out = String::new();
    let _ = writeln!(out, "{}", file.display());
    let rows = [
        (
            "impact velocity",
            format!("{:.2} m/s", m.impact_velocity_mps),
        ),
        ("max dynamic crush", opt(m.max_dynamic_crush_m, 1.0, "m", 3)),
        ("at", opt(m.time_of_max_crush_s, 1e3, "ms", 1)),
        (
            "time to zero velocity",
            opt(m.time_to_zero_velocity_s, 1e3, "ms", 1),
        ),
        (
            "rebound velocity",
            opt(m.rebound_velocity_mps, 1.0, "m/s", 2),
        ),
        (
            "peak deceleration",
            format!("{:.1} g (unfiltered)", m.peak_deceleration_g),
        ),
        ("CFC 60 peak", opt(m.peak_deceleration_cfc60_g, 1.0, "g", 1)),
        (
            "equivalent square wave",
            opt(m.equivalent_square_wave_g, 1.0, "g", 1),
        ),
        (
            "OLC",
            match (m.olc_g, m.olc_t1_s, m.olc_t2_s) {
                (Some(o), Some(t1), Some(t2)) => {
                    format!("{o:.1} g (t1 {:.1} ms, t2 {:.1} ms)", t1 * 1e3, t2 * 1e3)
                }
                _ => "– (the pulse ends before the occupant travels 300 mm)".into(),
            },
        ),
        (
            "ASI",
            match (m.asi, m.asi_time_s) {
                (Some(a), Some(t)) => format!("{a:.2} (window ending at {:.1} ms)", t * 1e3),
                _ => "– (the pulse is shorter than 50 ms)".into(),
            },
        ),
    ];
    for (name, value) in rows {
        let _ = writeln!(out, "  {name:<23}{value}");
    }
    out
}
