//! Merging the tables of a sweep's shards into the table of one full run.
//!
//! The parts may be CSV or Parquet, in any order and any mix. They are
//! checked against the plan — the columns of this sweep, every run exactly
//! once, each run with the plan's values — and their rows are handed out in
//! run order, so that writing them as a single run would gives the same
//! bytes.

use super::plan::Plan;
use super::run::Row;
use super::table::{Layout, columns, parse_record};
use parquet::file::reader::{FileReader, SerializedFileReader};
use parquet::record::Field;
use std::fs::File;
use std::io::{BufReader, Read};
use std::path::{Path, PathBuf};

/// A row and where it was read (`part-2.csv:14`, `part-2.parquet: row 12`).
type Located = Result<(Row, String), String>;

/// The rows of one part, in file order.
struct Part {
    rows: std::iter::Peekable<Box<dyn Iterator<Item = Located>>>,
}

impl Part {
    /// Opens a part written by `lpm sweep` (CSV or Parquet, told apart by
    /// the Parquet magic bytes) and checks its columns.
    fn open(path: &Path, layout: &Layout) -> Result<Part, String> {
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

fn is_parquet(path: &Path) -> Result<bool, String> {
    let mut magic = [0u8; 4];
    let mut file = File::open(path).map_err(|e| format!("cannot read {}: {e}", path.display()))?;
    let read = file
        .read(&mut magic)
        .map_err(|e| format!("cannot read {}: {e}", path.display()))?;
    Ok(read == 4 && &magic == b"PAR1")
}

fn wrong_columns(path: &Path, found: &[String]) -> String {
    format!(
        "{}: the columns are not those of this sweep (`{}` …): it is not a part of this sweep",
        path.display(),
        found.join(",").chars().take(80).collect::<String>()
    )
}

fn csv_rows(path: &Path, layout: &Layout) -> Result<Box<dyn Iterator<Item = Located>>, String> {
    let file = File::open(path).map_err(|e| format!("cannot read {}: {e}", path.display()))?;
    let mut reader = csv::ReaderBuilder::new()
        .has_headers(true)
        .flexible(true)
        .from_reader(BufReader::new(file));
    let header: Vec<String> = (reader.headers())
        .map_err(|e| format!("{}:1: cannot read the header: {e}", path.display()))?
        .iter()
        .map(str::to_string)
        .collect();
    if header != columns(layout) {
        return Err(wrong_columns(path, &header));
    }
    let (path, layout) = (path.display().to_string(), layout.clone());
    Ok(Box::new(reader.into_records().enumerate().map(
        move |(k, record)| {
            let at = format!("{path}:{}", k + 2);
            let row = record
                .map_err(|e| e.to_string())
                .and_then(|r| parse_record(&r, &layout));
            row.map(|row| (row, at.clone()))
                .map_err(|e| format!("{at}: {e}"))
        },
    )))
}

/// The text `lpm sweep` writes in a CSV cell for a Parquet value.
fn cell(field: &Field) -> Result<String, String> {
    match field {
        Field::Null => Ok(String::new()),
        Field::Long(n) => Ok(n.to_string()),
        Field::Double(x) => Ok(format!("{x:?}")),
        Field::Str(s) => Ok(s.clone()),
        other => Err(format!("unexpected value {other}")),
    }
}

fn parquet_rows(path: &Path, layout: &Layout) -> Result<Box<dyn Iterator<Item = Located>>, String> {
    let fail = |e: parquet::errors::ParquetError| format!("{}: {e}", path.display());
    let file = File::open(path).map_err(|e| format!("cannot read {}: {e}", path.display()))?;
    let reader = SerializedFileReader::new(file).map_err(fail)?;
    let schema = reader.metadata().file_metadata().schema_descr_ptr();
    let header: Vec<String> = (schema.columns().iter())
        .map(|c| c.name().to_string())
        .collect();
    if header != columns(layout) {
        return Err(wrong_columns(path, &header));
    }
    let rows = reader.into_iter();
    let (path, layout) = (path.display().to_string(), layout.clone());
    Ok(Box::new(rows.enumerate().map(move |(k, row)| {
        let at = format!("{path}: row {}", k + 1);
        let cells = row.map_err(|e| e.to_string()).and_then(|row| {
            (row.get_column_iter())
                .map(|(_, field)| cell(field))
                .collect::<Result<Vec<String>, String>>()
        });
        cells
            .and_then(|cells| parse_record(&csv::StringRecord::from(cells), &layout))
            .map(|row| (row, at.clone()))
            .map_err(|e| format!("{at}: {e}"))
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
) -> Result<impl Iterator<Item = Result<Row, String>>, String> {
    let mut opened = (parts.iter())
        .map(|path| Part::open(path, layout).map(|mut part| (part.first_run(), part)))
        .collect::<Result<Vec<(Option<usize>, Part)>, String>>()?;
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
            Some(Ok((row, at))) => check(row, &at, next, plan),
            None if next < total => Err(missing(next, total, total)),
            None => return None,
        };
        failed = checked.is_err();
        if checked.is_ok() {
            next += 1;
        }
        Some(checked)
    }))
}

/// `row` (read at `at`) if it is run `expected` of `plan`.
fn check(row: Row, at: &str, expected: usize, plan: &Plan) -> Result<Row, String> {
    let total = plan.len();
    if row.run < expected {
        return Err(format!(
            "{at}: run {} is repeated (an earlier part or row holds it already): give each shard once",
            row.run
        ));
    }
    if row.run >= total {
        return Err(format!(
            "{at}: run {} is beyond this plan's {total} runs: the part belongs to another sweep",
            row.run
        ));
    }
    if row.run > expected {
        return Err(format!("{at}: {}", missing(expected, row.run, total)));
    }
    let values = plan.point(row.run);
    if row.values != values {
        return Err(format!(
            "{at}: run {} has the values {:?}, but this plan's run {} has {values:?}: the part belongs to another sweep",
            row.run, row.values, row.run
        ));
    }
    Ok(row)
}

fn missing(from: usize, to: usize, total: usize) -> String {
    let runs = if to - from == 1 {
        format!("run {from} is missing")
    } else {
        format!("runs {from}..{to} are missing")
    };
    format!("{runs} (of {total}): no part holds them; give every shard's table")
}
