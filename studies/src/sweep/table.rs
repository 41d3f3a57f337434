//! The sweep's output table, one row per run: `run`, the swept values,
//! `status`, `error`, then the summary metrics of `summary.json`. Written as
//! CSV or Parquet; pandas and polars read either directly, and the files of
//! the shards of one sweep concatenate into the full table.

use super::run::{Row, RunFailure};
use lagrangian_sim::failure::FailureKind;
use lagrangian_sim::scenario::{Role, Scenario};
use lagrangian_sim::simulate::{ChannelSummary, Field, Summary, Value, metric_names};
use parquet::basic::{ConvertedType, Repetition, Type as Physical};
use parquet::data_type::{ByteArray, ByteArrayType, DataType, DoubleType, Int64Type};
use parquet::errors::ParquetError;
use parquet::file::properties::WriterProperties;
use parquet::file::writer::{SerializedFileWriter, SerializedRowGroupWriter};
use parquet::schema::types::Type;
use std::io::Write;
use std::sync::Arc;

/// Why the cells of a row do not read back as the [`Row`] they were made
/// from ([`parse_record`]).
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum RecordError {
    /// The row has another number of cells than the table has columns.
    #[error("{found} cells instead of {expected}")]
    CellCount {
        /// The cells of the row.
        found: usize,
        /// The columns of the table.
        expected: usize,
    },
    /// The `run` cell holds no run number.
    #[error("run `{cell}` is not a run number")]
    RunNumber {
        /// The cell's text.
        cell: String,
    },
    /// An axis' cell holds no number.
    #[error("`{cell}` is not a number")]
    NotANumber {
        /// The axis' column.
        column: String,
        /// The cell's text.
        cell: String,
    },
    /// The `status` cell is neither `ok` nor a failure kind's name.
    #[error("status `{status}` is neither `ok` nor a failure kind")]
    Status {
        /// The cell's text.
        status: String,
    },
    /// A metric's cell does not read as that metric's kind of value.
    #[error("{message}")]
    Metric {
        /// The metric's column.
        column: String,
        /// Why, as the summary's reader says it.
        message: String,
    },
}

/// Why a table (a sweep's or an envelope's) could not be written.
#[derive(Debug, thiserror::Error)]
pub enum WriteError {
    /// Writing CSV failed.
    #[error("cannot write CSV: {0}")]
    Csv(#[from] csv::Error),
    /// Writing Parquet failed.
    #[error("cannot write Parquet: {0}")]
    Parquet(#[from] ParquetError),
    /// A column of the Parquet schema could not be made.
    #[error("Parquet schema: {0}")]
    Schema(#[source] ParquetError),
    /// A row group has fewer columns than the schema.
    #[error("Parquet: column {column} missing from the schema")]
    MissingColumn {
        /// The column written, counted from 0.
        column: usize,
    },
}

/// The first columns of `header` for a message: at most 80 characters of
/// the names joined by commas.
pub(super) fn abbreviated(header: &[String]) -> String {
    header.join(",").chars().take(80).collect()
}

/// The columns of a sweep table: `run`, the axes, `status`, `error`, the
/// summary metrics, then the metrics of each of the scenario's channels.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Layout {
    /// The axes' columns ([`super::Axis::column`]).
    pub axes: Vec<String>,
    /// The channels of the base scenario: name, role, unit, filter class.
    pub channels: Vec<(String, Role, Option<String>, f64)>,
}

impl Layout {
    /// A table of `axes` and no channels.
    pub fn of_axes(axes: Vec<String>) -> Layout {
        Layout {
            axes,
            channels: Vec::new(),
        }
    }

    /// A table of `axes` and the channels of `scenario`.
    pub fn new(axes: Vec<String>, scenario: &Scenario) -> Layout {
        let channels = (scenario.channels.iter())
            .map(|c| (c.signal.name.clone(), c.role, c.signal.unit.clone(), c.cfc))
            .collect();
        Layout { axes, channels }
    }

    /// The metric columns after `error`, with the kind of value of each.
    fn metrics(&self) -> Vec<(String, Value)> {
        let mut metrics: Vec<(String, Value)> = (Summary::METRICS.iter())
            .zip(Summary::EMPTY.values())
            .map(|(m, v)| (m.name.to_string(), v))
            .collect();
        for (name, role, ..) in &self.channels {
            for metric in metric_names(*role) {
                metrics.push((format!("{name}.{metric}"), Value::Real(None)));
            }
            metrics.push((format!("{name}.extreme_at_end"), Value::Count(0)));
        }
        metrics
    }

    /// The values of the metric columns of a run's summary.
    fn values(&self, summary: &Summary) -> Vec<Value> {
        let mut values = summary.values();
        for (name, role, ..) in &self.channels {
            let channel = summary.channels.0.iter().find(|c| c.name == *name);
            for k in 0..metric_names(*role).len() {
                let value = channel.and_then(|c| c.values.get(k).copied().flatten());
                values.push(Value::Real(value));
            }
            let flag = channel.is_some_and(|c| c.extreme_at_end);
            values.push(Value::Count(usize::from(flag)));
        }
        values
    }

    /// The summary from the cells of its metric columns.
    fn summary<'a>(
        &self,
        mut cells: impl Iterator<Item = &'a str>,
    ) -> Result<Summary, RecordError> {
        let bad = |column: String, message: String| RecordError::Metric { column, message };
        let mut summary = Summary::EMPTY;
        for metric in Summary::METRICS {
            (summary.set(metric.name, cells.next().unwrap_or("")))
                .map_err(|e| bad(metric.name.to_string(), e.to_string()))?;
        }
        for (name, role, unit, cfc) in &self.channels {
            let values = (metric_names(*role).iter())
                .map(|metric| {
                    <Option<f64> as Field>::parse(cells.next().unwrap_or(""))
                        .map_err(|e| bad(format!("{name}.{metric}"), e.to_string()))
                })
                .collect::<Result<_, _>>()?;
            let extreme_at_end = cells.next() == Some("1");
            summary.channels.0.push(ChannelSummary {
                name: name.clone(),
                role: *role,
                unit: unit.clone(),
                cfc: *cfc,
                values,
                extreme_at_end,
            });
        }
        Ok(summary)
    }
}

/// The column names: `run`, the axes, `status`, `error`, the metrics.
pub fn columns(layout: &Layout) -> Vec<String> {
    let mut names = vec!["run".to_string()];
    names.extend(layout.axes.iter().cloned());
    names.push("status".into());
    names.push("error".into());
    names.extend(layout.metrics().into_iter().map(|(name, _)| name));
    names
}

/// The `status` of a run that finished; a failed one's is its
/// [`FailureKind::name`].
const OK: &str = "ok";

/// The CSV cells of a row: the run, its values, `ok` or the failure kind,
/// the error, the metrics (empty where absent). Numbers are written so that
/// they read back exactly.
pub fn record(layout: &Layout, row: &Row) -> Vec<String> {
    let mut record = vec![row.run.to_string()];
    record.extend(row.values.iter().map(|v| format!("{v:?}")));
    match &row.outcome {
        Ok(summary) => {
            record.push(OK.into());
            record.push(String::new());
            record.extend(layout.values(summary).into_iter().map(Value::cell));
        }
        Err(failure) => {
            record.push(failure.kind.name().into());
            record.push(failure.message.clone());
            record.extend(std::iter::repeat_n(String::new(), layout.metrics().len()));
        }
    }
    record
}

/// The row a [`record`] was made from: the metrics are read by position
/// from the cells of the columns of [`columns`].
pub fn parse_record(record: &csv::StringRecord, layout: &Layout) -> Result<Row, RecordError> {
    let axes = layout.axes.len();
    let expected = 3 + axes + layout.metrics().len();
    if record.len() != expected {
        return Err(RecordError::CellCount {
            found: record.len(),
            expected,
        });
    }
    let number = |k: usize| -> Result<f64, RecordError> {
        record[k]
            .parse::<f64>()
            .map_err(|_| RecordError::NotANumber {
                column: layout.axes[k - 1].clone(),
                cell: record[k].to_string(),
            })
    };
    let run = record[0]
        .parse::<usize>()
        .map_err(|_| RecordError::RunNumber {
            cell: record[0].to_string(),
        })?;
    let values = (1..=axes)
        .map(number)
        .collect::<Result<Vec<f64>, RecordError>>()?;
    let status = &record[axes + 1];
    let outcome = if status == OK {
        Ok(layout.summary(record.iter().skip(axes + 3))?)
    } else {
        let kind = FailureKind::from_name(status).ok_or_else(|| RecordError::Status {
            status: status.to_string(),
        })?;
        Err(RunFailure {
            kind,
            message: record[axes + 2].to_string(),
        })
    };
    Ok(Row {
        run,
        values,
        outcome,
    })
}

/// CSV with a header line; a failed run has empty metric cells.
pub fn sweep_csv(layout: &Layout, rows: &[Row]) -> Result<Vec<u8>, WriteError> {
    let mut bytes = Vec::new();
    write_csv::<WriteError>(layout, rows.iter().cloned().map(Ok), &mut bytes)?;
    Ok(bytes)
}

/// Writes the CSV table of `rows` to `out` (the bytes of a journal of the
/// same rows); the first error of `rows` stops it, and is what it returns.
pub fn write_csv<E: From<WriteError>>(
    layout: &Layout,
    rows: impl Iterator<Item = Result<Row, E>>,
    out: impl Write,
) -> Result<(), E> {
    let mut writer = csv::Writer::from_writer(out);
    (writer.write_record(columns(layout))).map_err(WriteError::Csv)?;
    for row in rows {
        (writer.write_record(record(layout, &row?))).map_err(WriteError::Csv)?;
    }
    writer.flush().map_err(|e| WriteError::Csv(e.into()))?;
    Ok(())
}

pub(super) fn column_type(
    name: &str,
    physical: Physical,
    repetition: Repetition,
) -> Result<Arc<Type>, WriteError> {
    let mut builder = Type::primitive_type_builder(name, physical).with_repetition(repetition);
    if physical == Physical::BYTE_ARRAY {
        builder = builder.with_converted_type(ConvertedType::UTF8);
    }
    builder.build().map(Arc::new).map_err(WriteError::Schema)
}

/// A Parquet file (one row group, uncompressed). Metrics absent from a run
/// (a failed run, or no crush coordinate) are nulls.
pub fn sweep_parquet(layout: &Layout, rows: &[Row]) -> Result<Vec<u8>, WriteError> {
    let mut bytes = Vec::new();
    write_parquet::<_, WriteError>(layout, std::iter::once(Ok(rows.to_vec())), &mut bytes)?;
    Ok(bytes)
}

/// Writes a Parquet file to `out`, one row group per item of `groups`, so
/// that a table of any length is written in the memory of one group; the
/// first error of `groups` stops it, and is what it returns.
pub fn write_parquet<W: Write + Send, E: From<WriteError>>(
    layout: &Layout,
    groups: impl Iterator<Item = Result<Vec<Row>, E>>,
    out: W,
) -> Result<(), E> {
    let schema = schema(layout)?;
    let properties = Arc::new(WriterProperties::builder().build());
    let mut writer = SerializedFileWriter::new(out, Arc::new(schema), properties)
        .map_err(WriteError::Parquet)?;
    for rows in groups {
        write_group(&mut writer, layout, &rows?)?;
    }
    writer.close().map_err(WriteError::Parquet)?;
    Ok(())
}

/// The Parquet schema of the [`columns`]: `run` and the metric counts as
/// 64-bit integers, the axes and the real metrics as doubles, `status` and
/// `error` as UTF-8; `error` and the metrics may be null.
fn schema(layout: &Layout) -> Result<Type, WriteError> {
    let mut fields = vec![column_type("run", Physical::INT64, Repetition::REQUIRED)?];
    for axis in &layout.axes {
        fields.push(column_type(axis, Physical::DOUBLE, Repetition::REQUIRED)?);
    }
    fields.push(column_type(
        "status",
        Physical::BYTE_ARRAY,
        Repetition::REQUIRED,
    )?);
    fields.push(column_type(
        "error",
        Physical::BYTE_ARRAY,
        Repetition::OPTIONAL,
    )?);
    for (name, value) in layout.metrics() {
        let physical = match value {
            Value::Real(_) => Physical::DOUBLE,
            Value::Count(_) => Physical::INT64,
        };
        fields.push(column_type(&name, physical, Repetition::OPTIONAL)?);
    }
    Type::group_type_builder("sweep")
        .with_fields(fields)
        .build()
        .map_err(WriteError::Parquet)
}

/// The columns of one row group, written one after the other in schema
/// order.
pub(super) struct GroupColumns<'a, W: Write> {
    pub(super) group: SerializedRowGroupWriter<'a, W>,
    /// How many columns are written so far.
    pub(super) written: usize,
}

impl<W: Write + Send> GroupColumns<'_, W> {
    /// Writes the next column: the values of the present entries and, for
    /// an optional column, the definition levels (1 present, 0 null).
    pub(super) fn write<T: DataType>(
        &mut self,
        values: &[T::T],
        levels: Option<&[i16]>,
    ) -> Result<(), WriteError> {
        let column = self.written;
        let mut writer = self
            .group
            .next_column()
            .map_err(WriteError::Parquet)?
            .ok_or(WriteError::MissingColumn { column })?;
        writer
            .typed::<T>()
            .write_batch(values, levels, None)
            .map_err(WriteError::Parquet)?;
        writer.close().map_err(WriteError::Parquet)?;
        self.written += 1;
        Ok(())
    }
}

/// Writes `rows` as one row group: run, axes, status, error, metrics.
fn write_group<W: Write + Send>(
    writer: &mut SerializedFileWriter<W>,
    layout: &Layout,
    rows: &[Row],
) -> Result<(), WriteError> {
    let mut columns = GroupColumns {
        group: writer.next_row_group().map_err(WriteError::Parquet)?,
        written: 0,
    };
    let runs: Vec<i64> = rows.iter().map(|r| r.run as i64).collect();
    columns.write::<Int64Type>(&runs, None)?;
    for k in 0..layout.axes.len() {
        let values: Vec<f64> = rows.iter().map(|r| r.values[k]).collect();
        columns.write::<DoubleType>(&values, None)?;
    }
    let status: Vec<ByteArray> = rows
        .iter()
        .map(|r| match &r.outcome {
            Ok(_) => ByteArray::from(OK),
            Err(f) => ByteArray::from(f.kind.name()),
        })
        .collect();
    columns.write::<ByteArrayType>(&status, None)?;
    let errors: Vec<ByteArray> = rows
        .iter()
        .filter_map(|r| {
            r.outcome
                .as_ref()
                .err()
                .map(|e| ByteArray::from(e.message.as_str()))
        })
        .collect();
    let levels: Vec<i16> = rows.iter().map(|r| i16::from(r.outcome.is_err())).collect();
    columns.write::<ByteArrayType>(&errors, Some(&levels))?;
    write_metric_columns(&mut columns, layout, rows)?;
    columns.group.close().map_err(WriteError::Parquet)?;
    Ok(())
}

/// The metric columns of a row group, in the layout's order: null for a
/// failed run and for a metric the run does not have.
fn write_metric_columns<W: Write + Send>(
    columns: &mut GroupColumns<'_, W>,
    layout: &Layout,
    rows: &[Row],
) -> Result<(), WriteError> {
    let values: Vec<Option<Vec<Value>>> = rows
        .iter()
        .map(|r| r.outcome.as_ref().ok().map(|s| layout.values(s)))
        .collect();
    for (m, (_, empty)) in layout.metrics().into_iter().enumerate() {
        let cells: Vec<Option<Value>> = values.iter().map(|v| v.as_ref().map(|v| v[m])).collect();
        let levels: Vec<i16> = cells
            .iter()
            .map(|c| {
                i16::from(matches!(
                    c,
                    Some(Value::Real(Some(_))) | Some(Value::Count(_))
                ))
            })
            .collect();
        match empty {
            Value::Real(_) => {
                let values: Vec<f64> = cells
                    .iter()
                    .filter_map(|c| match c {
                        Some(Value::Real(x)) => *x,
                        _ => None,
                    })
                    .collect();
                columns.write::<DoubleType>(&values, Some(&levels))?;
            }
            Value::Count(_) => {
                let values: Vec<i64> = cells
                    .iter()
                    .filter_map(|c| match c {
                        Some(Value::Count(n)) => Some(*n as i64),
                        _ => None,
                    })
                    .collect();
                columns.write::<Int64Type>(&values, Some(&levels))?;
            }
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use parquet::file::reader::{FileReader, SerializedFileReader};
    use parquet::record::Field;

    fn summary(crush: f64) -> Summary {
        Summary {
            max_crush_m: Some(crush),
            time_of_max_crush_s: Some(0.066),
            weld_failure_time_s: None,
            steps: 120,
            ..Summary::EMPTY
        }
    }

    fn rows() -> Vec<Row> {
        vec![
            Row {
                run: 4,
                values: vec![1.5, 0.25],
                outcome: Ok(summary(0.5)),
            },
            Row {
                run: 5,
                values: vec![2.0, 0.25],
                outcome: Err(RunFailure {
                    kind: FailureKind::StepSizeUnderflow,
                    message: "integration failed: step size too small".into(),
                }),
            },
        ]
    }

    /// A layout of two axes and an acceleration channel, and a run with
    /// its metrics.
    fn with_channel() -> (Layout, Row) {
        let layout = Layout {
            axes: vec!["a".into(), "b".into()],
            channels: vec![(
                "-x_ddot".into(),
                Role::Acceleration,
                Some("m/s^2".into()),
                1000.0,
            )],
        };
        let mut summary = summary(0.25);
        summary.channels.0.push(ChannelSummary {
            name: "-x_ddot".into(),
            role: Role::Acceleration,
            unit: Some("m/s^2".into()),
            cfc: 1000.0,
            values: vec![
                Some(3.5),
                Some(0.01),
                None,
                None,
                Some(1.0),
                Some(0.01),
                Some(0.9),
                Some(1.0),
                Some(1.1),
                Some(0.8),
            ],
            extreme_at_end: true,
        });
        let row = Row {
            run: 0,
            values: vec![1.0, 2.0],
            outcome: Ok(summary),
        };
        (layout, row)
    }

    #[test]
    fn rows_read_back_from_their_records_by_column() {
        let layout = Layout::of_axes(vec!["a".into(), "b".into()]);
        for row in rows() {
            let record = csv::StringRecord::from(record(&layout, &row));
            assert_eq!(parse_record(&record, &layout), Ok(row));
        }
        let (layout, row) = with_channel();
        let cells = record(&layout, &row);
        let names = columns(&layout);
        assert_eq!(cells.len(), names.len());
        let cell = |name: &str| cells[names.iter().position(|n| n == name).unwrap()].as_str();
        assert_eq!(cell("-x_ddot.max"), "3.5");
        assert_eq!(cell("-x_ddot.min"), "");
        assert_eq!(cell("-x_ddot.clip3ms_g"), "0.8");
        assert_eq!(cell("-x_ddot.extreme_at_end"), "1");
        let record = csv::StringRecord::from(cells);
        assert_eq!(parse_record(&record, &layout), Ok(row));
    }

    #[test]
    fn a_status_that_is_no_failure_kind_is_refused() {
        let layout = Layout::of_axes(vec!["a".into(), "b".into()]);
        let mut cells = record(&layout, &rows()[1]);
        assert_eq!(cells[3], FailureKind::StepSizeUnderflow.name());
        cells[3] = "exploded".into();
        assert_eq!(
            parse_record(&csv::StringRecord::from(cells), &layout),
            Err(RecordError::Status {
                status: "exploded".into()
            })
        );
        assert_eq!(
            RecordError::Status {
                status: "exploded".into()
            }
            .to_string(),
            "status `exploded` is neither `ok` nor a failure kind"
        );
    }

    #[test]
    fn csv_has_a_header_and_empty_cells_for_missing_metrics() {
        let axes = Layout::of_axes(vec!["k1".to_string(), "stiffness_values*".to_string()]);
        let text = String::from_utf8(sweep_csv(&axes, &rows()).unwrap()).unwrap();
        let lines: Vec<&str> = text.lines().collect();
        assert_eq!(lines.len(), 3);
        assert!(lines[0].starts_with("run,k1,stiffness_values*,status,error,max_crush_m,"));
        assert!(lines[1].starts_with("4,1.5,0.25,ok,,0.5,0.066,,"));
        assert!(lines[2].starts_with(
            "5,2.0,0.25,step_size_underflow,integration failed: step size too small,,"
        ));
        assert_eq!(lines[1].split(',').count(), columns(&axes).len());
    }

    #[test]
    fn parquet_reads_back_with_nulls_where_metrics_are_missing() {
        let axes = Layout::of_axes(vec!["components.weld.failure_moment".to_string()]);
        let rows: Vec<Row> = rows()
            .into_iter()
            .map(|mut r| {
                r.values.truncate(1);
                r
            })
            .collect();
        let bytes = sweep_parquet(&axes, &rows).unwrap();
        let reader = SerializedFileReader::new(bytes::Bytes::from(bytes)).unwrap();
        assert_eq!(reader.metadata().file_metadata().num_rows(), 2);
        let read: Vec<Vec<(String, Field)>> = reader
            .get_row_iter(None)
            .unwrap()
            .map(|r| {
                r.unwrap()
                    .get_column_iter()
                    .map(|(n, f)| (n.clone(), f.clone()))
                    .collect()
            })
            .collect();
        let names: Vec<&str> = read[0].iter().map(|(n, _)| n.as_str()).collect();
        assert_eq!(names, columns(&axes));
        let cell =
            |row: usize, name: &str| read[row].iter().find(|(n, _)| n == name).unwrap().1.clone();
        assert_eq!(cell(0, "run"), Field::Long(4));
        assert_eq!(
            cell(0, "components.weld.failure_moment"),
            Field::Double(1.5)
        );
        assert_eq!(cell(0, "status"), Field::Str(OK.into()));
        assert_eq!(cell(0, "error"), Field::Null);
        assert_eq!(cell(0, "max_crush_m"), Field::Double(0.5));
        assert_eq!(cell(0, "weld_failure_time_s"), Field::Null);
        assert_eq!(cell(0, "steps"), Field::Long(120));
        assert_eq!(
            cell(1, "status"),
            Field::Str(FailureKind::StepSizeUnderflow.name().into())
        );
        assert_eq!(
            cell(1, "error"),
            Field::Str("integration failed: step size too small".into())
        );
        assert_eq!(cell(1, "max_crush_m"), Field::Null);
        assert_eq!(cell(1, "steps"), Field::Null);
    }
}
