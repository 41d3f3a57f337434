//! `lpm metrics TEST`: crash-pulse metrics and injury criteria of a test
//! (ISO-MME) or of a measured or exported pulse (CSV).

use crate::failure::{Failure, Outcome};
use lagrangian_sim::criteria::{Criterion, Rated};
use lagrangian_sim::pulse::PulseMetrics;
use lagrangian_studies::files::Files;
use lagrangian_studies::metrics::{MetricsRequest, TestMetrics, test_metrics};
use std::fmt::Write;
use std::path::{Path, PathBuf};
use std::sync::Arc;

/// Options of `lpm metrics`.
#[derive(clap::Args)]
pub struct Args {
    /// The test: an ISO-MME test (its folder, its `.mme` or a `.zip`: the
    /// vehicle's pulse and every occupant's injury criteria), or the
    /// vehicle's pulse as a CSV file with units in its header.
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
    let request = MetricsRequest {
        test: args.file.clone(),
        v0: args.v0,
    };
    let metrics = test_metrics(&**files, &request).map_err(|e| Failure::from(&e))?;
    let text = match args.format == "json" {
        true => metrics.json(),
        false => text_of(&metrics, &args.file),
    };
    Ok(crate::warnings::outcome(
        text,
        &metrics.warnings,
        args.strict,
    ))
}

/// The text report: the pulse's metrics, then the criteria of the vehicle
/// and of each occupant.
fn text_of(metrics: &TestMetrics, file: &Path) -> String {
    let mut out = match &metrics.pulse {
        Some(pulse) => text(pulse, file),
        None => format!(
            "{}\n  (no vehicle acceleration channel: no pulse metrics)\n",
            file.display()
        ),
    };
    let vehicle: Vec<&Rated> = (metrics.criteria.rated.iter())
        .filter(|r| matches!(r.criterion, Criterion::Thiv | Criterion::Phd))
        .collect();
    for r in vehicle {
        let _ = writeln!(out, "  {:<23}{}", r.criterion.label(), shown(r));
    }
    for occupant in &metrics.occupants {
        let dummy = occupant.dummy.as_deref().unwrap_or("no dummy named");
        let _ = writeln!(
            out,
            "  occupant of test object {}, seat {} ({dummy}):",
            occupant.test_object, occupant.position
        );
        for r in &occupant.criteria.rated {
            let _ = writeln!(out, "    {:<21}{}", r.criterion.label(), shown(r));
        }
    }
    out
}

/// A criterion's value with its unit.
fn shown(r: &Rated) -> String {
    match r.criterion.unit() {
        "" => format!("{:.3}", r.value),
        unit => format!("{:.3} {unit}", r.value),
    }
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
