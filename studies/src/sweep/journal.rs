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
use super::table::{Layout, columns, parse_record, record};
use std::fs::{File, OpenOptions};
use std::io::{BufWriter, Seek, SeekFrom};
use std::ops::Range;
use std::path::{Path, PathBuf};

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
    pub fn create(path: &Path, layout: &Layout) -> Result<Journal, String> {
        let file =
            File::create(path).map_err(|e| format!("cannot create {}: {e}", path.display()))?;
        let mut journal = Journal::over(path, layout, file);
        let started = journal
            .writer
            .write_record(columns(layout))
            .map_err(|e| format!("cannot write {}: {e}", path.display()))
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
    ) -> Result<(Journal, usize), String> {
        let at = |line: u64, m: String| format!("{}:{line}: {m}", path.display());
        let text =
            std::fs::read(path).map_err(|e| format!("cannot read {}: {e}", path.display()))?;
        // Only whole lines count; a record cut by a kill has no newline yet.
        let whole = text.iter().rposition(|&b| b == b'\n').map_or(0, |k| k + 1);
        let mut reader = csv::ReaderBuilder::new()
            .has_headers(true)
            .flexible(true)
            .from_reader(&text[..whole]);
        let header: Vec<String> = reader
            .headers()
            .map_err(|e| at(1, format!("cannot read the header: {e}")))?
            .iter()
            .map(str::to_string)
            .collect();
        if header != columns(layout) {
            return Err(at(
                1,
                format!(
                    "the columns are not those of this sweep (`{}` …); it belongs to another sweep: delete it or choose another --out",
                    header.join(",").chars().take(80).collect::<String>()
                ),
            ));
        }
        let mut count = 0;
        for (k, record) in reader.records().enumerate() {
            let line = k as u64 + 2;
            let record = record.map_err(|e| at(line, format!("cannot read: {e}")))?;
            let row = parse_record(&record, layout).map_err(|e| at(line, e))?;
            let expected = runs.start + count;
            if row.run != expected || expected >= runs.end || row.values != plan.point(expected) {
                return Err(at(
                    line,
                    format!(
                        "run {} with values {:?} is not run {expected} of this sweep (values {:?}); the journal belongs to another sweep",
                        row.run,
                        row.values,
                        plan.point(expected)
                    ),
                ));
            }
            count += 1;
        }
        let mut file = OpenOptions::new()
            .write(true)
            .open(path)
            .map_err(|e| format!("cannot open {}: {e}", path.display()))?;
        file.set_len(whole as u64)
            .and_then(|()| file.seek(SeekFrom::End(0)).map(|_| ()))
            .map_err(|e| format!("cannot truncate {}: {e}", path.display()))?;
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
    pub fn append(&mut self, row: &Row) -> Result<(), String> {
        self.writer
            .write_record(record(&self.layout, row))
            .map_err(|e| format!("cannot write {}: {e}", self.path.display()))?;
        self.flush()
    }

    fn flush(&mut self) -> Result<(), String> {
        self.writer
            .flush()
            .map_err(|e| format!("cannot write {}: {e}", self.path.display()))
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
) -> Result<impl Iterator<Item = Result<Vec<Row>, String>>, String> {
    let file = File::open(path).map_err(|e| format!("cannot read {}: {e}", path.display()))?;
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
            let parsed = record
                .map_err(|e| e.to_string())
                .and_then(|r| parse_record(&r, &layout))
                .map_err(|e| format!("{}:{}: {e}", path.display(), k + 2));
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
