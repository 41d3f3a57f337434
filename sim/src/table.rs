//! Time histories from CSV files (barrier forces from a test or FE run).
//!
//! The first row names the columns, optionally with a unit in brackets
//! (`t [s]`, `Fx1 [N]`); a column is found by its full header or by the
//! name before the unit. Times must increase strictly. Values between rows
//! are interpolated linearly; outside the time range the column's
//! [`Outside`] policy applies.

use crate::curve::{Curve, CurveError, Outside};
use std::fmt;
use std::path::{Path, PathBuf};

/// A problem with a table file, located at `file:line` where possible.
#[derive(Clone, Debug, PartialEq)]
pub enum TableError {
    /// The file cannot be read.
    Read {
        /// The file.
        file: PathBuf,
        /// The system's reason.
        message: String,
    },
    /// Not a CSV table (rows of different lengths, say).
    Malformed {
        /// The file.
        file: PathBuf,
        /// The line of the problem, when it has one.
        line: Option<u64>,
        /// The CSV reader's reason.
        message: String,
    },
    /// A cell that is not a finite number.
    NotNumeric {
        /// The file.
        file: PathBuf,
        /// Its line.
        line: u64,
        /// Its column's header.
        column: String,
        /// The cell as written.
        value: String,
    },
    /// A time that does not exceed the one of the row before.
    NotIncreasing {
        /// The file.
        file: PathBuf,
        /// Its line.
        line: u64,
        /// The time.
        time: f64,
        /// The time of the row before.
        previous: f64,
    },
    /// No column of that name.
    MissingColumn {
        /// The file.
        file: PathBuf,
        /// The name asked for.
        column: String,
        /// The headers there are.
        available: Vec<String>,
        /// The closest header, when one is close.
        suggestion: Option<String>,
    },
    /// Fewer than two data rows (this many).
    TooShort {
        /// The file.
        file: PathBuf,
        /// The number of data rows.
        rows: usize,
    },
}

impl fmt::Display for TableError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            TableError::Read { file, message } => {
                write!(f, "{}: cannot read: {message}", file.display())
            }
            TableError::Malformed {
                file,
                line: Some(line),
                message,
            } => write!(f, "{}:{line}: {message}", file.display()),
            TableError::Malformed {
                file,
                line: None,
                message,
            } => write!(f, "{}: {message}", file.display()),
            TableError::NotNumeric {
                file,
                line,
                column,
                value,
            } => {
                write!(
                    f,
                    "{}:{line}: column `{column}`: `{value}` is not a number",
                    file.display()
                )
            }
            TableError::NotIncreasing {
                file,
                line,
                time,
                previous,
            } => write!(
                f,
                "{}:{line}: time {time} does not increase (previous row has {previous}); sort the rows by time",
                file.display()
            ),
            TableError::MissingColumn {
                file,
                column,
                available,
                suggestion,
            } => {
                write!(
                    f,
                    "{}: no column `{column}` (columns: {})",
                    file.display(),
                    available.join(", ")
                )?;
                if let Some(s) = suggestion {
                    write!(f, "; did you mean `{s}`?")?;
                }
                Ok(())
            }
            TableError::TooShort { file, rows } => {
                write!(
                    f,
                    "{}: needs at least 2 data rows, has {rows}",
                    file.display()
                )
            }
        }
    }
}

impl std::error::Error for TableError {}

/// All columns of a CSV file, as numbers.
#[derive(Clone, Debug)]
pub struct Table {
    file: PathBuf,
    headers: Vec<String>,
    columns: Vec<Vec<f64>>,
    /// The file line of each data row.
    lines: Vec<u64>,
}

/// The name of a header without its unit: `Fx1 [N]` → `Fx1`.
fn bare(header: &str) -> &str {
    header.split('[').next().unwrap_or(header).trim()
}

impl Table {
    /// Parses `text`, the contents of `file`: a header row, then rows of
    /// numbers; `#` starts a comment.
    pub fn parse(file: &Path, text: &str) -> Result<Table, TableError> {
        let file = file.to_path_buf();
        let mut reader = csv::ReaderBuilder::new()
            .trim(csv::Trim::All)
            .comment(Some(b'#'))
            .from_reader(text.as_bytes());
        let malformed = |e: csv::Error, file: &PathBuf| TableError::Malformed {
            file: file.clone(),
            line: e.position().map(|p| p.line()),
            message: e.to_string(),
        };
        let headers: Vec<String> = reader
            .headers()
            .map_err(|e| malformed(e, &file))?
            .iter()
            .map(str::to_string)
            .collect();
        let mut columns = vec![Vec::new(); headers.len()];
        let mut lines = Vec::new();
        for record in reader.records() {
            let record = record.map_err(|e| malformed(e, &file))?;
            let line = record.position().map_or(0, |p| p.line());
            lines.push(line);
            for (k, cell) in record.iter().enumerate() {
                let value: f64 = cell.parse().map_err(|_| TableError::NotNumeric {
                    file: file.clone(),
                    line,
                    column: headers[k].clone(),
                    value: cell.to_string(),
                })?;
                if !value.is_finite() {
                    return Err(TableError::NotNumeric {
                        file: file.clone(),
                        line,
                        column: headers[k].clone(),
                        value: cell.to_string(),
                    });
                }
                columns[k].push(value);
            }
        }
        Ok(Table {
            file,
            headers,
            columns,
            lines,
        })
    }

    /// The file it was read from.
    pub fn file(&self) -> &Path {
        &self.file
    }

    /// The header cells as written (with their units).
    pub fn headers(&self) -> &[String] {
        &self.headers
    }

    /// The values of column `k` (a header's position).
    pub fn column(&self, k: usize) -> &[f64] {
        &self.columns[k]
    }

    /// The file line of data row `row`.
    pub fn line(&self, row: usize) -> u64 {
        self.lines.get(row).copied().unwrap_or(0)
    }

    fn column_index(&self, name: &str) -> Result<usize, TableError> {
        self.headers
            .iter()
            .position(|h| h == name)
            .or_else(|| self.headers.iter().position(|h| bare(h) == bare(name)))
            .ok_or_else(|| TableError::MissingColumn {
                file: self.file.clone(),
                column: name.to_string(),
                available: self.headers.clone(),
                suggestion: lagrangian_runtime::names::closest(
                    name,
                    self.headers.iter().map(|h| bare(h)),
                )
                .map(str::to_string),
            })
    }

    /// Column `name` as a function of the time column `time`.
    pub fn curve(&self, time: &str, name: &str, outside: Outside) -> Result<Curve, TableError> {
        let (t, y) = (self.column_index(time)?, self.column_index(name)?);
        let times = &self.columns[t];
        if times.len() < 2 {
            return Err(TableError::TooShort {
                file: self.file.clone(),
                rows: times.len(),
            });
        }
        if let Some(i) = (1..times.len()).find(|&i| times[i] <= times[i - 1]) {
            return Err(TableError::NotIncreasing {
                file: self.file.clone(),
                line: self.lines[i],
                time: times[i],
                previous: times[i - 1],
            });
        }
        Curve::new(times.clone(), self.columns[y].clone(), outside)
            .map_err(|e| self.curve_error(&self.headers[y], e))
    }

    /// A curve's complaint about `column`, at the line of the row it names.
    fn curve_error(&self, column: &str, e: CurveError) -> TableError {
        let row = match e {
            CurveError::NotFinite { index } | CurveError::NotIncreasing { index, .. } => {
                Some(index)
            }
            CurveError::Slope { index, .. } => Some(index + 1),
            CurveError::TooFewPoints(_) | CurveError::LengthMismatch { .. } => None,
        };
        TableError::Malformed {
            file: self.file.clone(),
            line: row.and_then(|i| self.lines.get(i).copied()),
            message: format!("column `{column}`: {e}"),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn table(text: &str) -> Result<Table, TableError> {
        Table::parse(Path::new("forces.csv"), text)
    }

    #[test]
    fn reads_columns_by_header_with_or_without_unit() {
        let t = table("t [s], Fx1 [N], Fz1 [N]\n0, 0, 0\n0.01, 100, 5\n0.02, 300, 10\n").unwrap();
        let fx = t.curve("t", "Fx1", Outside::Zero).unwrap();
        assert_eq!(fx.eval(0.015).unwrap().0, 200.0);
        assert_eq!(fx.eval(0.5).unwrap().0, 0.0);
        assert_eq!(
            t.curve("t [s]", "Fz1 [N]", Outside::Hold)
                .unwrap()
                .eval(1.0)
                .unwrap()
                .0,
            10.0
        );
    }

    #[test]
    fn errors_name_the_line_column_and_value() {
        let e = table("t,F\n0,1\n0.1,abc\n").unwrap_err();
        assert_eq!(
            e.to_string(),
            "forces.csv:3: column `F`: `abc` is not a number"
        );
        let e = table("t,F\n0,1\n0.1,2,3\n").unwrap_err();
        assert!(e.to_string().starts_with("forces.csv:3:"), "{e}");
        let e = table("t,F\n# comment\n0,1\n0.2,1\n0.1,1\n")
            .unwrap()
            .curve("t", "F", Outside::Hold)
            .unwrap_err();
        assert_eq!(
            e.to_string(),
            "forces.csv:5: time 0.1 does not increase (previous row has 0.2); sort the rows by time"
        );
        // What a curve finds wrong is reported at the row's line, not at line 0.
        let t = table("t,F\n# comment\n0,1\n0.1,2\n").unwrap();
        let e = t.curve_error("F", CurveError::NotFinite { index: 1 });
        assert_eq!(
            e.to_string(),
            "forces.csv:4: column `F`: point 2 is not a finite number"
        );
        let e = t.curve_error("F", CurveError::TooFewPoints(1));
        assert_eq!(
            e.to_string(),
            "forces.csv: column `F`: needs at least 2 points, has 1"
        );
        let e = table("t,Fx1\n0,1\n")
            .unwrap()
            .curve("t", "Fx2", Outside::Hold)
            .unwrap_err();
        assert_eq!(
            e.to_string(),
            "forces.csv: no column `Fx2` (columns: t, Fx1); did you mean `Fx1`?"
        );
    }
}
