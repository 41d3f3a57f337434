//! Writing an ISO-MME test as a folder: `<dir>/<name>.mme`,
//! `<dir>/Channel/<name>.chn` and `<dir>/Channel/<name>.001 … .NNN`, in
//! ISO-8859-1, all or nothing.
//!
//! Each channel file is its header with the fields pyisomme writes set
//! from the channel (`Channel code`, `Unit`, `Reference channel`
//! implicit, `Sampling interval`, `Time of first sample`, `Number of
//! samples`, `First global maximum value`, `Time of maximum value`, `First
//! global minimum value`, `Time of minimum value`: a line already there
//! keeps its place, a new one goes at the end), then one sample a line
//! (`NOVALUE` for NaN). Numbers are written in their shortest form that
//! reads back to the same `f64`.

use crate::error::WriteError;
use crate::test::{Channel, Test};
use crate::text::{Header, encode};
use std::io::Write as _;
use std::path::{Path, PathBuf};

/// Writes `test` as the folder `dir` (replacing what is there): the whole
/// test is written into a temporary folder beside `dir` and renamed into
/// place, so `dir` is never half-written: on a failure it is as it was.
pub fn write(test: &Test, dir: &Path) -> Result<(), WriteError> {
    let files = files_of(test)?;
    // Absolute, so that `.` has a name and a sibling.
    let dir = &std::path::absolute(dir).map_err(|source| WriteError::Io {
        path: dir.to_path_buf(),
        source,
    })?;
    let temporary = beside(dir, "tmp");
    let written = write_files(&temporary, &files).and_then(|()| replace(dir, &temporary));
    if written.is_err() {
        let _ = std::fs::remove_dir_all(&temporary);
    }
    written
}

/// Each file of the test: its path below the test's folder and its text.
fn files_of(test: &Test) -> Result<Vec<(String, String)>, WriteError> {
    let name = &test.name;
    let separators = |c: char| c == '/' || c == '\\';
    if name.is_empty() || name == "." || name == ".." || name.contains(separators) {
        return Err(WriteError::Name(name.clone()));
    }
    let mut files = vec![
        (format!("{name}.mme"), test.info.to_text()),
        (format!("Channel/{name}.chn"), channel_list(test).to_text()),
    ];
    for (k, channel) in test.channels.iter().enumerate() {
        let text = channel_text(channel).map_err(|problem| WriteError::Channel {
            index: k + 1,
            code: channel.code.to_string(),
            problem,
        })?;
        files.push((format!("Channel/{name}.{:03}", k + 1), text));
    }
    Ok(files)
}

/// The `.chn`: the test's channel header with `Number of channels` and a
/// `Name of channel NNN: CODE[ / name]` line per channel.
fn channel_list(test: &Test) -> Header {
    let mut header = test.channel_info.clone();
    header.remove_where(|name| name.starts_with("Name of channel "));
    header.set("Number of channels", Some(test.channels.len().to_string()));
    for (k, channel) in test.channels.iter().enumerate() {
        let value = match channel.name() {
            Some(name) => format!("{} / {name}", channel.code),
            None => channel.code.to_string(),
        };
        header.push(format!("Name of channel {:03}", k + 1), Some(value));
    }
    header
}

/// A channel file's text, or why the channel cannot be written.
fn channel_text(channel: &Channel) -> Result<String, String> {
    if !(channel.dt.is_finite() && channel.dt > 0.0) {
        return Err(format!("sampling interval {} is not positive", channel.dt));
    }
    if !channel.t0.is_finite() {
        return Err(format!("time of first sample {} is not finite", channel.t0));
    }
    let mut header = channel.header.clone();
    let unit = (!channel.unit.is_empty()).then(|| channel.unit.clone());
    let set: [(&str, Option<String>); 6] = [
        ("Channel code", Some(channel.code.to_string())),
        ("Unit", unit),
        ("Reference channel", Some("implicit".into())),
        ("Sampling interval", Some(number(channel.dt))),
        ("Time of first sample", Some(number(channel.t0))),
        ("Number of samples", Some(channel.values.len().to_string())),
    ];
    for (name, value) in set {
        header.set(name, value);
    }
    let (max, min) = extremes(&channel.values);
    let at = |i: Option<usize>| i.map(|i| number(channel.time(i)));
    header.set(
        "First global maximum value",
        max.map(|i| number(channel.values[i])),
    );
    header.set("Time of maximum value", at(max));
    header.set(
        "First global minimum value",
        min.map(|i| number(channel.values[i])),
    );
    header.set("Time of minimum value", at(min));
    let mut text = header.to_text();
    for &value in &channel.values {
        text.push_str(&number(value));
        text.push('\n');
    }
    Ok(text)
}

/// The first sample of the largest value and the first of the smallest
/// (NaN aside); `None` without a number.
fn extremes(values: &[f64]) -> (Option<usize>, Option<usize>) {
    let mut max: Option<usize> = None;
    let mut min: Option<usize> = None;
    for (i, &x) in values.iter().enumerate() {
        if x.is_nan() {
            continue;
        }
        if max.is_none_or(|m| x > values[m]) {
            max = Some(i);
        }
        if min.is_none_or(|m| x < values[m]) {
            min = Some(i);
        }
    }
    (max, min)
}

/// `x` in the shortest form that reads back to it (`0.0001`, `-9.81`,
/// `1e-7`, `12`; `0` for −0), `NOVALUE` for NaN.
pub(crate) fn number(x: f64) -> String {
    if x.is_nan() {
        return crate::text::NOVALUE.to_string();
    }
    if x == 0.0 {
        return "0".into(); // −0 too
    }
    let text = format!("{x:?}");
    match text.strip_suffix(".0") {
        Some(whole) => whole.to_string(),
        None => text,
    }
}

/// The hidden sibling `.NAME.PID.what` of `dir`.
fn beside(dir: &Path, what: &str) -> PathBuf {
    let name = dir
        .file_name()
        .map_or("test".into(), |n| n.to_string_lossy().into_owned());
    dir.with_file_name(format!(".{name}.{}.{what}", std::process::id()))
}

/// Writes `files` below a new folder `root` (replacing one left there),
/// each on the disk before this returns.
fn write_files(root: &Path, files: &[(String, String)]) -> Result<(), WriteError> {
    let io = |path: &Path| {
        let path = path.to_path_buf();
        move |source| WriteError::Io { path, source }
    };
    if root.exists() {
        std::fs::remove_dir_all(root).map_err(io(root))?;
    }
    let channel = root.join("Channel");
    std::fs::create_dir_all(&channel).map_err(io(&channel))?;
    for (name, text) in files {
        let path = root.join(name);
        let mut file = std::fs::File::create(&path).map_err(io(&path))?;
        file.write_all(&encode(text)).map_err(io(&path))?;
        file.sync_all().map_err(io(&path))?;
    }
    Ok(())
}

/// Puts the written folder `temporary` at `dir`: an old `dir` is moved
/// aside first and removed after, or put back if the rename fails.
fn replace(dir: &Path, temporary: &Path) -> Result<(), WriteError> {
    let io = |path: &Path, source| WriteError::Io {
        path: path.to_path_buf(),
        source,
    };
    if !dir.exists() {
        return std::fs::rename(temporary, dir).map_err(|e| io(dir, e));
    }
    let old = beside(dir, "old");
    if old.exists() {
        std::fs::remove_dir_all(&old).map_err(|e| io(&old, e))?;
    }
    std::fs::rename(dir, &old).map_err(|e| io(dir, e))?;
    if let Err(e) = std::fs::rename(temporary, dir) {
        let _ = std::fs::rename(&old, dir);
        return Err(io(dir, e));
    }
    let _ = std::fs::remove_dir_all(&old);
    Ok(())
}
