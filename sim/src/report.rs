//! Writing a run's results: `trajectory.csv`, `summary.json`, a text summary.
//! Files are written to a temporary name and renamed, so a reader never sees
//! a half-written file.

use crate::simulate::SimulationResult;
use lagrangian_runtime::names::{
    ENERGY_COLUMNS, TIME_COLUMN, acceleration_column, velocity_column,
};
use std::fmt::Write as _;
use std::io::{self, Write as _};
use std::path::Path;

/// Writes `contents` to `path` atomically: into a temporary file beside
/// it, flushed to the disk, then renamed over `path`. On any failure — a
/// full disk while writing or flushing included — the temporary is
/// removed and `path` is as it was: whole, or absent.
pub fn write_atomically(path: &Path, contents: &[u8]) -> io::Result<()> {
    write_atomically_with(path, |file| file.write_all(contents))
}

/// [`write_atomically`] of what `write` writes into the file.
pub fn write_atomically_with(
    path: &Path,
    write: impl FnOnce(&mut std::fs::File) -> io::Result<()>,
) -> io::Result<()> {
    let temporary = temporary_beside(path);
    let written = std::fs::File::create(&temporary).and_then(|mut file| {
        write(&mut file)?;
        file.sync_all()
    });
    let renamed = written.and_then(|()| std::fs::rename(&temporary, path));
    if renamed.is_err() {
        let _ = std::fs::remove_file(&temporary);
    }
    renamed
}

/// Writes several files as one output: each into its temporary (as
/// [`write_atomically`] does), then, only when all are written and on the
/// disk, each renamed into place. On a failure every temporary is removed
/// and no file is replaced: the output is whole or as it was.
pub fn write_all_atomically(
    files: &[(&Path, &[u8])],
) -> Result<(), (std::path::PathBuf, io::Error)> {
    let temporaries: Vec<_> = files
        .iter()
        .map(|(path, _)| temporary_beside(path))
        .collect();
    let remove_all = || {
        for temporary in &temporaries {
            let _ = std::fs::remove_file(temporary);
        }
    };
    for ((path, contents), temporary) in files.iter().zip(&temporaries) {
        let written = std::fs::File::create(temporary).and_then(|mut file| {
            file.write_all(contents)?;
            file.sync_all()
        });
        if let Err(e) = written {
            remove_all();
            return Err((path.to_path_buf(), e));
        }
    }
    for ((path, _), temporary) in files.iter().zip(&temporaries) {
        if let Err(e) = std::fs::rename(temporary, path) {
            remove_all();
            return Err((path.to_path_buf(), e));
        }
    }
    Ok(())
}

/// The hidden temporary `.NAME.PID.tmp` beside `path`.
pub fn temporary_beside(path: &Path) -> std::path::PathBuf {
    let file_name = path
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default();
    path.with_file_name(format!(".{file_name}.{}.tmp", std::process::id()))
}

/// Units of the columns, where the spec declares them.
#[derive(Clone, Debug, Default)]
pub struct Units {
    /// The unit of each coordinate (`m`, `rad`), by coordinate index; the
    /// velocity and acceleration columns add `/s` and `/s^2`. `None`, or
    /// an index past the end, writes the column without a unit.
    pub coordinates: Vec<Option<String>>,
    /// The unit of each column of [`SimulationResult::input_columns`], in
    /// the same order.
    pub inputs: Vec<Option<String>>,
    /// The unit of each column of [`SimulationResult::output_columns`], in
    /// the same order.
    pub outputs: Vec<Option<String>>,
    /// The unit of each constraint's multiplier `λ`, in the order of
    /// [`crate::simulate::ConstraintReport::names`].
    pub multipliers: Vec<Option<String>>,
}

fn with_unit(name: &str, unit: Option<&str>) -> String {
    match unit {
        Some(u) => format!("{name} [{u}]"),
        None => name.to_string(),
    }
}

/// `t, q…, q̇…, q̈…, T, V, dissipated, external work, inputs…, outputs…,
/// component columns…, constraint multipliers…` per sample; the multiplier
/// of constraint `NAME` is the column `NAME.lambda`.
pub fn trajectory_csv(result: &SimulationResult, units: &Units) -> String {
    let mut header = vec![format!("{TIME_COLUMN} [s]")];
    let unit = |i: usize, suffix: &str| {
        units
            .coordinates
            .get(i)
            .cloned()
            .flatten()
            .map(|u| format!("{u}{suffix}"))
    };
    for (i, c) in result.coordinates.iter().enumerate() {
        header.push(with_unit(c, unit(i, "").as_deref()));
    }
    for (i, c) in result.coordinates.iter().enumerate() {
        header.push(with_unit(&velocity_column(c), unit(i, "/s").as_deref()));
    }
    for (i, c) in result.coordinates.iter().enumerate() {
        header.push(with_unit(
            &acceleration_column(c),
            unit(i, "/s^2").as_deref(),
        ));
    }
    for name in ENERGY_COLUMNS {
        header.push(format!("{name} [J]"));
    }
    for (k, name) in result.input_columns.iter().enumerate() {
        header.push(with_unit(
            name,
            units.inputs.get(k).cloned().flatten().as_deref(),
        ));
    }
    for (k, name) in result.output_columns.iter().enumerate() {
        let unit = units.outputs.get(k).cloned().flatten();
        header.push(with_unit(name, unit.as_deref()));
    }
    for (name, unit) in &result.component_columns {
        header.push(with_unit(name, unit.as_deref()));
    }
    let constraints = result.constraints.iter().flat_map(|c| &c.names);
    for (k, name) in constraints.enumerate() {
        let unit = units.multipliers.get(k).cloned().flatten();
        header.push(with_unit(&format!("{name}.lambda"), unit.as_deref()));
    }
    let mut out = header.join(",");
    out.push('\n');
    for s in &result.samples {
        let mut row: Vec<String> = vec![format!("{:.7}", s.t)];
        row.extend(
            s.q.iter()
                .chain(&s.v)
                .chain(&s.a)
                .map(|x| format!("{x:.10e}")),
        );
        row.extend(
            [s.kinetic, s.potential, s.dissipated, s.external_work]
                .iter()
                .map(|x| format!("{x:.10e}")),
        );
        row.extend(s.inputs.iter().map(|x| format!("{x:.10e}")));
        row.extend(s.outputs.iter().map(|x| format!("{x:.10e}")));
        row.extend(s.components.iter().map(|x| format!("{x:.10e}")));
        row.extend(s.multipliers.iter().map(|x| format!("{x:.10e}")));
        out.push_str(&row.join(","));
        out.push('\n');
    }
    out
}

/// `summary.json`: the run's [`Summary`](crate::simulate::Summary) as
/// pretty-printed JSON, one line per metric, then its `warnings` (`[]` for
/// a clean run), ending in a newline.
///
/// A model with constraints adds `constraint_drift_max`, the largest
/// `|g|` over the run's samples (each constraint in its own unit), and
/// `constraint_drift`, that of each constraint by name, after the metrics;
/// the summary of a model without constraints has neither.
pub fn summary_json(result: &SimulationResult) -> String {
    let Some(constraints) = &result.constraints else {
        return crate::warning::json_with_warnings(&result.summary, &result.warnings);
    };
    #[derive(serde::Serialize)]
    struct WithDrift<'a> {
        #[serde(flatten)]
        summary: &'a crate::simulate::Summary,
        constraint_drift_max: f64,
        constraint_drift: std::collections::BTreeMap<&'a str, f64>,
    }
    let drift = (constraints.names.iter().map(String::as_str))
        .zip(constraints.drift.iter().copied())
        .collect();
    let with_drift = WithDrift {
        summary: &result.summary,
        constraint_drift_max: constraints.drift_max(),
        constraint_drift: drift,
    };
    crate::warning::json_with_warnings(&with_drift, &result.warnings)
}

/// The lines of the text summary on a model's constraints: the projection
/// of the initial state, the stabilization and the drift.
/// The lines of the text summary on a model's constraints (their
/// projection, stabilization and drift); empty without constraints.
pub fn constraint_lines(result: &SimulationResult) -> String {
    let Some(c) = &result.constraints else {
        return String::new();
    };
    let p = &c.projection;
    let mut out = String::new();
    let _ = writeln!(
        out,
        "  constraints            {}: initial state projected (|g| was {:.1e}; |Δq| = {:.1e}, |Δq̇| = {:.1e})",
        c.names.join(", "),
        p.residual_before,
        p.coordinate_change,
        p.velocity_change
    );
    let _ = writeln!(
        out,
        "  constraint drift       {:.1e} max |g| (Baumgarte α = {} /s, β = {} /s)",
        c.drift_max(),
        c.stabilization.alpha,
        c.stabilization.beta
    );
    out
}

/// The one-screen summary printed after a run.
pub fn text_summary(result: &SimulationResult, scenario_name: &str) -> String {
    let s = &result.summary;
    let mut out = String::new();
    let _ = writeln!(out, "{} — {}", result.model, scenario_name);
    out.push_str(&s.text_lines());
    if !s.channels.0.is_empty() {
        let _ = writeln!(out, "  channels:");
        for channel in &s.channels.0 {
            let _ = writeln!(out, "    {}", channel.text_line());
        }
    }
    out.push_str(&constraint_lines(result));
    let _ = writeln!(
        out,
        "  solver                 {}: {} steps, {} rejected, {} right-hand sides",
        result.method, s.steps, s.rejected_steps, s.rhs_evaluations
    );
    if !result.events.is_empty() {
        let _ = writeln!(out, "  events:");
        for e in &result.events {
            let _ = writeln!(
                out,
                "    {:7.2} ms  {}: {}",
                e.t * 1e3,
                e.component,
                e.description
            );
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A writer that fails part-way (as a full disk does) leaves the old
    /// file as it was and no temporary beside it.
    #[test]
    fn a_failed_write_leaves_the_file_as_it_was_and_no_temporary() {
        let dir = std::env::temp_dir().join(format!("lpm-atomic-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join("out.txt");
        write_atomically(&path, b"old").unwrap();
        let failed = write_atomically_with(&path, |file| {
            file.write_all(b"half")?;
            Err(io::Error::new(io::ErrorKind::StorageFull, "disk full"))
        });
        assert_eq!(failed.unwrap_err().kind(), io::ErrorKind::StorageFull);
        assert_eq!(std::fs::read(&path).unwrap(), b"old");
        // Of several files, none is replaced when one cannot be written.
        let other = dir.join("other.txt");
        let missing = dir.join("no-such-folder").join("x.txt");
        let files: [(&Path, &[u8]); 2] = [(&other, b"new"), (&missing, b"x")];
        let (at, _) = write_all_atomically(&files).unwrap_err();
        assert_eq!(at, missing);
        assert!(!other.exists());
        let left: Vec<_> = std::fs::read_dir(&dir)
            .unwrap()
            .map(|e| e.unwrap().file_name())
            .collect();
        assert_eq!(left, [std::ffi::OsString::from("out.txt")]);
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
