//! Where the curves of `lpm compare` come from: a [`Source`] read into
//! named [`Signal`]s, each with its own times (an ISO-MME channel has its
//! own time base; a CSV's columns share theirs).
//!
//! A kind of source is one variant of [`Source`]: how [`Source::at`]
//! recognises it and how [`Source::read`] reads it into signals. Pairing,
//! rating and plotting take signals and do not change.

use super::CompareError;
use lagrangian_sim::files::Files;
use lagrangian_sim::quantity::{Dimension, Unit};
use lagrangian_sim::table::{Table, TableError};
use std::path::{Path, PathBuf};
use std::sync::Arc;

/// The dimension of a time column's unit.
const TIME: Dimension = Dimension {
    mass: 0,
    length: 0,
    time: 1,
};

/// The file a simulation output folder holds its time histories in.
pub const TRAJECTORY: &str = "trajectory.csv";

/// A source of curves.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Source {
    /// A CSV file: a time column (`t` or `time`, in `s` or `ms`) and
    /// channels, each unit in brackets in its header (`force [kN]`).
    Csv(PathBuf),
    /// A simulation output folder (`lpm simulate --out`): its
    /// [`TRAJECTORY`].
    RunFolder(PathBuf),
    /// An ISO-MME test (its folder, `.mme` or `.zip`): its channels, named
    /// by their codes, each on its own time base.
    IsoMme(PathBuf),
    /// An NHTSA EV5 test (its `.EV5` card file): its recorded channels,
    /// named by their numbers (`"001"`), each in its own unit.
    Ev5(PathBuf),
}

/// One curve of a source.
#[derive(Clone, Debug, PartialEq)]
pub struct Signal {
    /// Its name: a CSV column's header without the unit.
    pub name: String,
    /// Its unit as written (`kN`, `m/s^2`), if it has one.
    pub unit: Option<String>,
    /// The sample times \[s\], strictly increasing.
    pub t: Arc<[f64]>,
    /// One value per time, in `unit`.
    pub y: Vec<f64>,
}

/// The curves of a source.
#[derive(Clone, Debug, PartialEq)]
pub struct Signals {
    /// The file they were read from, as messages name it.
    pub file: PathBuf,
    /// At least one, in the source's order.
    pub signals: Vec<Signal>,
}

impl Signals {
    /// The signal called `name` (a header with or without its unit).
    pub fn get(&self, name: &str) -> Result<&Signal, CompareError> {
        let bare = bare_name(name);
        (self.signals.iter().find(|s| s.name == bare)).ok_or_else(|| {
            let names = self.signals.iter().map(|s| s.name.as_str());
            CompareError::UnknownChannel {
                file: self.file.clone(),
                name: name.to_string(),
                available: names.clone().map(str::to_string).collect(),
                suggestion: lagrangian_runtime::names::closest(bare, names).map(str::to_string),
            }
        })
    }
}

impl Source {
    /// The source at `path`: an ISO-MME test (an `.mme`, a `.zip`, a
    /// folder holding an `.mme`), else a folder is a simulation output
    /// folder, any other path a CSV file.
    pub fn at(path: &Path) -> Source {
        if crate::test_data::is_iso_mme(path) {
            return Source::IsoMme(path.to_path_buf());
        }
        let extension = path.extension().map(|e| e.to_ascii_lowercase());
        if extension.as_deref() == Some(std::ffi::OsStr::new("ev5")) {
            return Source::Ev5(path.to_path_buf());
        }
        match path.is_dir() {
            true => Source::RunFolder(path.to_path_buf()),
            false => Source::Csv(path.to_path_buf()),
        }
    }

    /// Its signals, read from `files`.
    pub fn read(&self, files: &dyn Files) -> Result<Signals, CompareError> {
        match self {
            Source::Csv(file) => csv_signals(files, file),
            Source::RunFolder(folder) => {
                let file = folder.join(TRAJECTORY);
                if !file.is_file() {
                    return Err(CompareError::NotRunFolder {
                        folder: folder.clone(),
                    });
                }
                csv_signals(files, &file)
            }
            Source::IsoMme(path) => iso_mme_signals(path),
            Source::Ev5(path) => ev5_signals(path),
        }
    }
}

/// The channels of the ISO-MME test at `path`, in its units (written as
/// the project writes units: `m/s^2`, `N*m`).
fn iso_mme_signals(path: &Path) -> Result<Signals, CompareError> {
    let test = lagrangian_crashdata::isomme::read(path).map_err(CompareError::IsoMme)?;
    test_signals(&test, path)
}

/// The recorded channels of the EV5 test at `path`, named by number
/// (`"001"`), in their units as ISO-MME writes them.
fn ev5_signals(path: &Path) -> Result<Signals, CompareError> {
    let test = lagrangian_crashdata::ev5::read(path).map_err(CompareError::IsoMme)?;
    let signals: Vec<Signal> = (test.channels.iter())
        .filter_map(|c| {
            let data = c.data.as_ref()?;
            (data.times.len() >= 2).then(|| Signal {
                name: format!("{:03}", c.number),
                unit: c.unit().map(crate::test_data::unit_text),
                t: data.times.clone().into(),
                y: data.values.clone(),
            })
        })
        .collect();
    if signals.is_empty() {
        return Err(CompareError::NoChannels {
            file: path.to_path_buf(),
        });
    }
    Ok(Signals {
        file: path.to_path_buf(),
        signals,
    })
}

/// The channels of `test` (read from `file`, as messages name it), each
/// named by its code.
pub fn test_signals(
    test: &lagrangian_crashdata::isomme::Test,
    file: &Path,
) -> Result<Signals, CompareError> {
    let signals: Vec<Signal> = (test.channels.iter())
        .filter(|c| c.values.len() >= 2)
        .map(|c| Signal {
            name: c.code.as_str().to_string(),
            unit: Some(crate::test_data::unit_text(&c.unit)).filter(|u| !u.is_empty()),
            t: c.times().into(),
            y: c.values.clone(),
        })
        .collect();
    if signals.is_empty() {
        return Err(CompareError::NoChannels {
            file: file.to_path_buf(),
        });
    }
    Ok(Signals {
        file: file.to_path_buf(),
        signals,
    })
}

/// A header's name without its `[unit]`.
fn bare_name(header: &str) -> &str {
    header.split('[').next().unwrap_or(header).trim()
}

/// A header's unit, inside its brackets.
fn unit_of(header: &str) -> Option<&str> {
    let (_, rest) = header.split_once('[')?;
    Some(rest.trim_end().trim_end_matches(']').trim()).filter(|u| !u.is_empty())
}

/// Whether a header names the time column.
fn is_time(header: &str) -> bool {
    matches!(
        bare_name(header).to_ascii_lowercase().as_str(),
        "t" | "time"
    )
}

/// The channels of the CSV `file`: every column besides the time.
fn csv_signals(files: &dyn Files, file: &Path) -> Result<Signals, CompareError> {
    let table = files.table(file).map_err(CompareError::Table)?;
    let headers = table.headers();
    let Some(time) = headers.iter().position(|h| is_time(h)) else {
        return Err(CompareError::NoTime {
            file: file.to_path_buf(),
            headers: headers.to_vec(),
        });
    };
    let t = times(&table, time)?;
    let signals: Vec<Signal> = (headers.iter().enumerate())
        .filter(|&(k, _)| k != time)
        .map(|(k, header)| Signal {
            name: bare_name(header).to_string(),
            unit: unit_of(header).map(str::to_string),
            t: t.clone(),
            y: table.column(k).to_vec(),
        })
        .collect();
    if signals.is_empty() {
        return Err(CompareError::NoChannels {
            file: file.to_path_buf(),
        });
    }
    Ok(Signals {
        file: file.to_path_buf(),
        signals,
    })
}

/// The time column `k` of `table` in seconds: its unit a time, at least
/// two rows, strictly increasing.
fn times(table: &Table, k: usize) -> Result<Arc<[f64]>, CompareError> {
    let header = &table.headers()[k];
    let file = table.file().to_path_buf();
    let unit = unit_of(header).and_then(|u| Unit::parse(u).ok());
    let Some(unit) = unit.filter(|u| u.dimension == TIME) else {
        return Err(CompareError::TimeUnit {
            file,
            header: header.clone(),
        });
    };
    let t: Vec<f64> = table.column(k).iter().map(|&v| unit.to_si(v)).collect();
    if t.len() < 2 {
        let rows = t.len();
        return Err(CompareError::Table(TableError::TooShort { file, rows }));
    }
    if let Some(i) = (1..t.len()).find(|&i| t[i] <= t[i - 1]) {
        return Err(CompareError::Table(TableError::NotIncreasing {
            file,
            line: table.line(i),
            time: t[i],
            previous: t[i - 1],
        }));
    }
    Ok(t.into())
}
