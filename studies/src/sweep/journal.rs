//! The journal of a sweep under way: `<out>.partial`, a CSV file to which
//! every finished row is appended (in run order) as soon as it is known.
//!
//! A sweep that is stopped (Ctrl-C, `kill`, a crash, a lost node) leaves its
//! journal with the finished rows; `lpm sweep --resume` reads it back,
//! checks that its rows are the first runs of the same plan, and carries on
//! after them. The finished sweep's output is made from the journal and
//! renamed into place, so `<out>` is either absent or complete.

use super::plan::Plan;
use super::run::Row;
use super::table::{Layout, RecordError, abbreviated, columns, parse_record, record};
use std::fs::{File, OpenOptions};
use std::io::{BufWriter, Seek, SeekFrom};
use std::ops::Range;
use std::path::{Path, PathBuf};

/// Why a journal cannot be made, appended to, or read back: the file, and
/// for a journal read back the line and what is wrong with it.
#[derive(Debug, thiserror::Error)]
pub enum JournalError {
    /// The journal cannot be created.
    #[error("cannot create {}: {source}", .path.display())]
    Create {
        /// The journal.
        path: PathBuf,
        /// Why.
        source: std::io::Error,
    },
    /// A row (or the header) cannot be written.
    #[error("cannot write {}: {source}", .path.display())]
    Write {
        /// The journal.
        path: PathBuf,
        /// Why.
        source: csv::Error,
    },
    /// The journal cannot be read.
    #[error("cannot read {}: {source}", .path.display())]
    Read {
        /// The journal.
        path: PathBuf,
        /// Why.
        source: std::io::Error,
    },
    /// The journal cannot be opened to append to.
    #[error("cannot open {}: {source}", .path.display())]
    Open {
        /// The journal.
        path: PathBuf,
        /// Why.
        source: std::io::Error,
    },
    /// The line cut short by a kill cannot be dropped.
    #[error("cannot truncate {}: {source}", .path.display())]
    Truncate {
        /// The journal.
        path: PathBuf,
        /// Why.
        source: std::io::Error,
    },
    /// A line of the journal that does not belong there.
    #[error("{}:{line}: {problem}", .path.display())]
    Line {
        /// The journal.
        path: PathBuf,
        /// The line, from 1 (the header's).
        line: u64,
        /// What is wrong with it.
        problem: LineProblem,
    },
}

/// What is wrong with a line of a journal ([`JournalError::Line`]).
#[derive(Debug, thiserror::Error)]
pub enum LineProblem {
    /// The header does not read.
    #[error("cannot read the header: {0}")]
    Header(#[source] csv::Error),
    /// The header is not this sweep's.
    #[error(
        "the columns are not those of this sweep (`{}` …); it belongs to another sweep: delete it or choose another --out",
        abbreviated(.0)
    )]
    OtherColumns(Vec<String>),
    /// A record of a journal resumed does not read.
    #[error("cannot read: {0}")]
    Unreadable(#[source] csv::Error),
    /// A record of a finished journal does not read.
    #[error("{0}")]
    Csv(#[source] csv::Error),
    /// A record's cells are not a row of this sweep's table.
    #[error("{0}")]
    Record(#[source] RecordError),
    /// A row that is not the next run of this sweep.
    #[error(
        "run {run} with values {values:?} is not run {expected} of this sweep (values {expected_values:?}); the journal belongs to another sweep"
    )]
    OtherRun {
        /// The row's run.
        run: usize,
        /// The row's values.
        values: Vec<f64>,
        /// The run expected.
        expected: usize,
        /// The plan's values of that run.
        expected_values: Vec<f64>,
    },
}

/// The journal path of an output: `results.csv` → `results.csv.partial`.
pub fn journal_path(out: &Path) -> PathBuf {
    let mut name = out.file_name().unwrap_or_default().to_os_string();
    name.push(".partial");
    out.with_file_name(name)
}

/// An open journal, appending rows.
pub struct Journal {
    path: PathBuf,
    layout: Layout,
    writer: csv::Writer<BufWriter<File>>,
}

impl Journal {
    /// Starts a new journal for a sweep of table `layout`.
    /// A journal that cannot be written whole (a full disk) is removed.
    pub fn create(path: &Path, layout: &Layout) -> Result<Journal, JournalError> {
        let file = File::create(path).map_err(|source| JournalError::Create {
            path: path.to_path_buf(),
            source,
        })?;
        let mut journal = Journal::over(path, layout, file);
        let started = (journal.writer.write_record(columns(layout)))
            .map_err(|source| journal.write_error(source))
            .and_then(|()| journal.flush());
        if let Err(e) = started {
            drop(journal);
            let _ = std::fs::remove_file(path);
            return Err(e);
        }
        Ok(journal)
    }

    /// Opens the journal of an interrupted sweep and checks it against the
    /// plan: its rows must be runs `runs.start`, `runs.start + 1`, … with the
    /// plan's values. A last line cut short by a kill is dropped. Returns
    /// the journal, ready to append, and the number of runs it holds.
    pub fn resume(
        path: &Path,
        layout: &Layout,
        plan: &Plan,
        runs: &Range<usize>,
    ) -> Result<(Journal, usize), JournalError> {
        let at = |line: u64, problem: LineProblem| JournalError::Line {
            path: path.to_path_buf(),
            line,
            problem,
        };
        let text = std::fs::read(path).map_err(|source| JournalError::Read {
            path: path.to_path_buf(),
            source,
        })?;
        // Only whole lines count; a record cut by a kill has no newline yet.
        let whole = text.iter().rposition(|&b| b == b'\n').map_or(0, |k| k + 1);
        let mut reader = csv::ReaderBuilder::new()
            .has_headers(true)
            .flexible(true)
            .from_reader(&text[..whole]);
        let header: Vec<String> = reader
            .headers()
            .map_err(|e| at(1, LineProblem::Header(e)))?
            .iter()
            .map(str::to_string)
            .collect();
        if header != columns(layout) {
            return Err(at(1, LineProblem::OtherColumns(header)));
        }
        let mut count = 0;
        for (k, record) in reader.records().enumerate() {
            let line = k as u64 + 2;
            let record = record.map_err(|e| at(line, LineProblem::Unreadable(e)))?;
            let row =
                parse_record(&record, layout).map_err(|e| at(line, LineProblem::Record(e)))?;
            let expected = runs.start + count;
            if row.run != expected || expected >= runs.end || row.values != plan.point(expected) {
                let problem = LineProblem::OtherRun {
                    run: row.run,
                    values: row.values,
                    expected,
                    expected_values: plan.point(expected),
                };
                return Err(at(line, problem));
            }
            count += 1;
        }
        let mut file = OpenOptions::new()
            .write(true)
            .open(path)
            .map_err(|source| JournalError::Open {
                path: path.to_path_buf(),
                source,
            })?;
        file.set_len(whole as u64)
            .and_then(|()| file.seek(SeekFrom::End(0)).map(|_| ()))
            .map_err(|source| JournalError::Truncate {
                path: path.to_path_buf(),
                source,
            })?;
        Ok((Journal::over(path, layout, file), count))
    }

    fn over(path: &Path, layout: &Layout, file: File) -> Journal {
        Journal {
            path: path.to_path_buf(),
            layout: layout.clone(),
            writer: csv::Writer::from_writer(BufWriter::new(file)),
        }
    }

    /// Appends a row and hands it to the operating system at once (one
    /// `write` per row, microseconds against the milliseconds of a run), so
    /// that even `kill -9` loses no row that was appended.
    pub fn append(&mut self, row: &Row) -> Result<(), JournalError> {
        (self.writer.write_record(record(&self.layout, row)))
            .map_err(|source| self.write_error(source))?;
        self.flush()
    }

    fn flush(&mut self) -> Result<(), JournalError> {
        (self.writer.flush()).map_err(|e| self.write_error(e.into()))
    }

    fn write_error(&self, source: csv::Error) -> JournalError {
        JournalError::Write {
            path: self.path.clone(),
            source,
        }
    }

    /// The journal's file.
    pub fn path(&self) -> &Path {
        &self.path
    }
}

/// Reads a finished journal in groups of `group` rows (for a Parquet
/// output written one row group at a time).
pub fn read_groups(
    path: &Path,
    layout: &Layout,
    group: usize,
) -> Result<impl Iterator<Item = Result<Vec<Row>, JournalError>>, JournalError> {
    let file = File::open(path).map_err(|source| JournalError::Read {
        path: path.to_path_buf(),
        source,
    })?;
    let mut records = csv::ReaderBuilder::new()
        .has_headers(true)
        .from_reader(std::io::BufReader::new(file))
        .into_records()
        .enumerate();
    let path = path.to_path_buf();
    let layout = layout.clone();
    Ok(std::iter::from_fn(move || {
        let mut rows = Vec::new();
        for (k, record) in records.by_ref() {
            let parsed = (record.map_err(LineProblem::Csv))
                .and_then(|r| parse_record(&r, &layout).map_err(LineProblem::Record))
                .map_err(|problem| JournalError::Line {
                    path: path.clone(),
                    line: k as u64 + 2,
                    problem,
                });
            match parsed {
                Ok(row) => rows.push(row),
                Err(e) => return Some(Err(e)),
            }
            if rows.len() == group {
                break;
            }
        }
        (!rows.is_empty()).then_some(Ok(rows))
    }))
}
