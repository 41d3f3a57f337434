//! Merging the tables of a sweep's shards into the table of one full run.
//!
//! The parts may be CSV or Parquet, in any order and any mix. They are
//! checked against the plan — the columns of this sweep, every run exactly
//! once, each run with the plan's values — and their rows are handed out in
//! run order, so that writing them as a single run would gives the same
//! bytes.

use super::plan::Plan;
use super::run::Row;
use super::table::{Layout, RecordError, abbreviated, columns, parse_record};
use parquet::errors::ParquetError;
use parquet::file::reader::{FileReader, SerializedFileReader};
use parquet::record::Field;
use std::fs::File;
use std::io::{BufReader, Read};
use std::path::{Path, PathBuf};

/// Why the shards' tables do not merge into the table of the sweep: the
/// part and the row at fault, and what is missing, repeated or foreign.
#[derive(Debug, thiserror::Error)]
pub enum MergeError {
    /// A part cannot be read.
    #[error("cannot read {}: {source}", .path.display())]
    Read {
        /// The part.
        path: PathBuf,
        /// Why.
        source: std::io::Error,
    },
    /// A CSV part's header does not read.
    #[error("{}:1: cannot read the header: {source}", .path.display())]
    Header {
        /// The part.
        path: PathBuf,
        /// Why.
        source: csv::Error,
    },
    /// A Parquet part does not read.
    #[error("{}: {source}", .path.display())]
    Parquet {
        /// The part.
        path: PathBuf,
        /// Why.
        source: ParquetError,
    },
    /// A part whose columns are not this sweep's.
    #[error(
        "{}: the columns are not those of this sweep (`{}` …): it is not a part of this sweep",
        .path.display(),
        abbreviated(.columns)
    )]
    NotAPart {
        /// The part.
        path: PathBuf,
        /// Its columns.
        columns: Vec<String>,
    },
    /// A row that does not read, or is not the next run of the plan.
    #[error("{at}: {problem}")]
    Row {
        /// Where it was read.
        at: Location,
        /// What is wrong with it.
        problem: RowProblem,
    },
    /// The last runs of the plan, in no part.
    #[error("{0}")]
    Missing(MissingRuns),
}

/// Where a row was read: `part-2.csv:14`, `part-2.parquet: row 12`.
#[derive(Clone, Debug, PartialEq)]
pub enum Location {
    /// A line of a CSV part, from 1 (the header's).
    Line {
        /// The part.
        path: PathBuf,
        /// The line.
        line: usize,
    },
    /// A row of a Parquet part, from 1.
    Row {
        /// The part.
        path: PathBuf,
        /// The row.
        row: usize,
    },
}

impl std::fmt::Display for Location {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Location::Line { path, line } => write!(f, "{}:{line}", path.display()),
            Location::Row { path, row } => write!(f, "{}: row {row}", path.display()),
        }
    }
}

/// What is wrong with a row of a part ([`MergeError::Row`]).
#[derive(Debug, thiserror::Error)]
pub enum RowProblem {
    /// A CSV record that does not read.
    #[error("{0}")]
    Csv(#[source] csv::Error),
    /// A Parquet row that does not read.
    #[error("{0}")]
    Parquet(#[source] ParquetError),
    /// A Parquet value of a kind `lpm sweep` does not write.
    #[error("unexpected value {value}")]
    UnexpectedValue {
        /// The value, as Parquet writes it.
        value: String,
    },
    /// Cells that are not a row of this sweep's table.
    #[error("{0}")]
    Record(#[source] RecordError),
    /// A run that an earlier part or row holds already.
    #[error(
        "run {run} is repeated (an earlier part or row holds it already): give each shard once"
    )]
    Repeated {
        /// The run.
        run: usize,
    },
    /// A run beyond the plan's.
    #[error("run {run} is beyond this plan's {total} runs: the part belongs to another sweep")]
    Beyond {
        /// The run.
        run: usize,
        /// The plan's number of runs.
        total: usize,
    },
    /// Runs before this row's, in no part.
    #[error("{0}")]
    Missing(MissingRuns),
    /// A run with other values than the plan's.
    #[error(
        "run {run} has the values {values:?}, but this plan's run {run} has {expected:?}: the part belongs to another sweep"
    )]
    OtherValues {
        /// The run.
        run: usize,
        /// Its values in the part.
        values: Vec<f64>,
        /// The plan's values of the run.
        expected: Vec<f64>,
    },
}

/// Runs `from..to` of a plan of `total`, in no part.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MissingRuns {
    /// The first run missing.
    pub from: usize,
    /// The run after the last missing.
    pub to: usize,
    /// The plan's number of runs.
    pub total: usize,
}

impl std::fmt::Display for MissingRuns {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let MissingRuns { from, to, total } = *self;
        if to - from == 1 {
            write!(f, "run {from} is missing")?;
        } else {
            write!(f, "runs {from}..{to} are missing")?;
        }
        write!(
            f,
            " (of {total}): no part holds them; give every shard's table"
        )
    }
}

/// A row and where it was read.
type Located = Result<(Row, Location), MergeError>;

/// The rows of one part, in file order.
struct Part {
    rows: std::iter::Peekable<Box<dyn Iterator<Item = Located>>>,
}

impl Part {
    /// Opens a part written by `lpm sweep` (CSV or Parquet, told apart by
    /// the Parquet magic bytes) and checks its columns.
    fn open(path: &Path, layout: &Layout) -> Result<Part, MergeError> {
        let rows = if is_parquet(path)? {
            parquet_rows(path, layout)?
        } else {
            csv_rows(path, layout)?
        };
        Ok(Part {
            rows: rows.peekable(),
        })
    }

    /// The run of the part's first row; `None` for an empty part (a shard
    /// with no runs) and for one whose first row cannot be read (reported
    /// when it is reached).
    fn first_run(&mut self) -> Option<usize> {
        match self.rows.peek() {
            Some(Ok((row, _))) => Some(row.run),
            _ => None,
        }
    }
}

fn is_parquet(path: &Path) -> Result<bool, MergeError> {
    let unreadable = |source| MergeError::Read {
        path: path.to_path_buf(),
        source,
    };
    let mut magic = [0u8; 4];
    let mut file = File::open(path).map_err(unreadable)?;
    let read = file.read(&mut magic).map_err(unreadable)?;
    Ok(read == 4 && &magic == b"PAR1")
}

/// The error of a part whose columns are `found`, if they are not those
/// of `layout`.
fn check_columns(path: &Path, found: Vec<String>, layout: &Layout) -> Result<(), MergeError> {
    match found == columns(layout) {
        true => Ok(()),
        false => Err(MergeError::NotAPart {
            path: path.to_path_buf(),
            columns: found,
        }),
    }
}

/// `row` read at `at`, or the error of what is wrong with it.
fn located(row: Result<Row, RowProblem>, at: Location) -> Located {
    match row {
        Ok(row) => Ok((row, at)),
        Err(problem) => Err(MergeError::Row { at, problem }),
    }
}

fn csv_rows(path: &Path, layout: &Layout) -> Result<Box<dyn Iterator<Item = Located>>, MergeError> {
    let file = File::open(path).map_err(|source| MergeError::Read {
        path: path.to_path_buf(),
        source,
    })?;
    let mut reader = csv::ReaderBuilder::new()
        .has_headers(true)
        .flexible(true)
        .from_reader(BufReader::new(file));
    let header: Vec<String> = (reader.headers())
        .map_err(|source| MergeError::Header {
            path: path.to_path_buf(),
            source,
        })?
        .iter()
        .map(str::to_string)
        .collect();
    check_columns(path, header, layout)?;
    let (path, layout) = (path.to_path_buf(), layout.clone());
    Ok(Box::new(reader.into_records().enumerate().map(
        move |(k, record)| {
            let at = Location::Line {
                path: path.clone(),
                line: k + 2,
            };
            let row = (record.map_err(RowProblem::Csv))
                .and_then(|r| parse_record(&r, &layout).map_err(RowProblem::Record));
            located(row, at)
        },
    )))
}

/// The text `lpm sweep` writes in a CSV cell for a Parquet value.
fn cell(field: &Field) -> Result<String, RowProblem> {
    match field {
        Field::Null => Ok(String::new()),
        Field::Long(n) => Ok(n.to_string()),
        Field::Double(x) => Ok(format!("{x:?}")),
        Field::Str(s) => Ok(s.clone()),
        other => Err(RowProblem::UnexpectedValue {
            value: other.to_string(),
        }),
    }
}

fn parquet_rows(
    path: &Path,
    layout: &Layout,
) -> Result<Box<dyn Iterator<Item = Located>>, MergeError> {
    let file = File::open(path).map_err(|source| MergeError::Read {
        path: path.to_path_buf(),
        source,
    })?;
    let reader = SerializedFileReader::new(file).map_err(|source| MergeError::Parquet {
        path: path.to_path_buf(),
        source,
    })?;
    let schema = reader.metadata().file_metadata().schema_descr_ptr();
    let header: Vec<String> = (schema.columns().iter())
        .map(|c| c.name().to_string())
        .collect();
    check_columns(path, header, layout)?;
    let rows = reader.into_iter();
    let (path, layout) = (path.to_path_buf(), layout.clone());
    Ok(Box::new(rows.enumerate().map(move |(k, row)| {
        let at = Location::Row {
            path: path.clone(),
            row: k + 1,
        };
        let cells = row.map_err(RowProblem::Parquet).and_then(|row| {
            (row.get_column_iter())
                .map(|(_, field)| cell(field))
                .collect::<Result<Vec<String>, RowProblem>>()
        });
        let row = cells.and_then(|cells| {
            parse_record(&csv::StringRecord::from(cells), &layout).map_err(RowProblem::Record)
        });
        located(row, at)
    })))
}

/// The rows of the parts in run order, each checked against `plan`: every
/// run from 0 to the plan's last exactly once, with the plan's values. An
/// error names the file and row and says what is missing, repeated or
/// foreign; it ends the iteration.
pub fn merged_rows(
    parts: &[PathBuf],
    layout: &Layout,
    plan: &Plan,
) -> Result<impl Iterator<Item = Result<Row, MergeError>>, MergeError> {
    let mut opened = (parts.iter())
        .map(|path| Part::open(path, layout).map(|mut part| (part.first_run(), part)))
        .collect::<Result<Vec<(Option<usize>, Part)>, MergeError>>()?;
    // Parts in the order of their first run; empty parts last.
    opened.sort_by_key(|(first, _)| first.unwrap_or(usize::MAX));
    let opened = opened.into_iter().map(|(_, part)| part);
    let mut rows = opened.flat_map(|part| part.rows);
    let mut next = 0;
    let total = plan.len();
    let mut failed = false;
    Ok(std::iter::from_fn(move || {
        if failed {
            return None;
        }
        let checked = match rows.next() {
            Some(Err(e)) => Err(e),
            Some(Ok((row, at))) => {
                check(row, next, plan).map_err(|problem| MergeError::Row { at, problem })
            }
            None if next < total => Err(MergeError::Missing(MissingRuns {
                from: next,
                to: total,
                total,
            })),
            None => return None,
        };
        failed = checked.is_err();
        if checked.is_ok() {
            next += 1;
        }
        Some(checked)
    }))
}

/// `row` if it is run `expected` of `plan`.
fn check(row: Row, expected: usize, plan: &Plan) -> Result<Row, RowProblem> {
    let (run, total) = (row.run, plan.len());
    if run < expected {
        return Err(RowProblem::Repeated { run });
    }
    if run >= total {
        return Err(RowProblem::Beyond { run, total });
    }
    if run > expected {
        return Err(RowProblem::Missing(MissingRuns {
            from: expected,
            to: run,
            total,
        }));
    }
    let expected = plan.point(run);
    if row.values != expected {
        return Err(RowProblem::OtherValues {
            run,
            values: row.values,
            expected,
        });
    }
    Ok(row)
}
