//! The sweep's output table, one row per run: `run`, the swept values,
//! `status`, `error`, then the summary metrics of `summary.json`. Written as
//! CSV or Parquet; pandas and polars read either directly, and the files of
//! the shards of one sweep concatenate into the full table.

use super::run::{Row, RunFailure};
use crate::simulate::Summary;
use parquet::basic::{ConvertedType, Repetition, Type as Physical};
use parquet::data_type::{ByteArray, ByteArrayType, DoubleType, Int64Type};
use parquet::file::properties::WriterProperties;
use parquet::file::writer::SerializedFileWriter;
use parquet::schema::types::Type;
use std::sync::Arc;

/// A metric's value: a measurement or a count.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Metric {
    Real(Option<f64>),
    Count(usize),
}

/// The metrics of a summary in `summary.json` order.
fn metrics(s: &Summary) -> [(&'static str, Metric); 16] {
    use Metric::{Count, Real};
    [
        ("max_crush_m", Real(s.max_crush_m)),
        ("time_of_max_crush_s", Real(s.time_of_max_crush_s)),
        ("time_to_zero_velocity_s", Real(s.time_to_zero_velocity_s)),
        ("max_theta1_deg", Real(s.max_theta1_deg)),
        ("max_theta2_deg", Real(s.max_theta2_deg)),
        ("peak_deceleration_g", Real(s.peak_deceleration_g)),
        ("rebound_velocity_mps", Real(s.rebound_velocity_mps)),
        ("weld_failure_time_s", Real(s.weld_failure_time_s)),
        (
            "peak_deceleration_cfc60_g",
            Real(s.peak_deceleration_cfc60_g),
        ),
        ("equivalent_square_wave_g", Real(s.equivalent_square_wave_g)),
        ("olc_g", Real(s.olc_g)),
        ("asi", Real(s.asi)),
        ("steps", Count(s.steps)),
        ("rejected_steps", Count(s.rejected_steps)),
        ("rhs_evaluations", Count(s.rhs_evaluations)),
        (
            "energy_balance_error_rel",
            Real(Some(s.energy_balance_error_rel)),
        ),
    ]
}

const EMPTY: Summary = Summary {
    max_crush_m: None,
    time_of_max_crush_s: None,
    time_to_zero_velocity_s: None,
    max_theta1_deg: None,
    max_theta2_deg: None,
    peak_deceleration_g: None,
    rebound_velocity_mps: None,
    weld_failure_time_s: None,
    peak_deceleration_cfc60_g: None,
    equivalent_square_wave_g: None,
    olc_g: None,
    asi: None,
    steps: 0,
    rejected_steps: 0,
    rhs_evaluations: 0,
    energy_balance_error_rel: 0.0,
};

/// The column names: `run`, the axes, `status`, `error`, the metrics.
pub fn columns(axes: &[String]) -> Vec<String> {
    let mut names = vec!["run".to_string()];
    names.extend(axes.iter().cloned());
    names.push("status".into());
    names.push("error".into());
    names.extend(metrics(&EMPTY).iter().map(|(n, _)| n.to_string()));
    names
}

/// The CSV cells of a row: the run, its values, `ok` or the failure kind,
/// the error, the metrics (empty where absent). Numbers are written so that
/// they read back exactly.
pub fn record(row: &Row) -> Vec<String> {
    let mut record = vec![row.run.to_string()];
    record.extend(row.values.iter().map(|v| format!("{v:?}")));
    match &row.outcome {
        Ok(summary) => {
            record.push("ok".into());
            record.push(String::new());
            record.extend(metrics(summary).iter().map(|(_, m)| match *m {
                Metric::Real(Some(x)) => format!("{x:?}"),
                Metric::Real(None) => String::new(),
                Metric::Count(n) => n.to_string(),
            }));
        }
        Err(failure) => {
            record.push(failure.kind.clone());
            record.push(failure.message.clone());
            record.extend(std::iter::repeat_n(String::new(), metrics(&EMPTY).len()));
        }
    }
    record
}

/// The row a [`record`] was made from (`axes` values before `status`).
pub fn parse_record(record: &csv::StringRecord, axes: usize) -> Result<Row, String> {
    let expected = 3 + axes + metrics(&EMPTY).len();
    if record.len() != expected {
        return Err(format!("{} cells instead of {expected}", record.len()));
    }
    let number = |k: usize| -> Result<f64, String> {
        record[k]
            .parse::<f64>()
            .map_err(|_| format!("`{}` is not a number", &record[k]))
    };
    let run = record[0]
        .parse::<usize>()
        .map_err(|_| format!("run `{}` is not a run number", &record[0]))?;
    let values = (1..=axes)
        .map(number)
        .collect::<Result<Vec<f64>, String>>()?;
    let status = &record[axes + 1];
    let outcome = if status == "ok" {
        let mut summary = EMPTY;
        let first = axes + 3;
        let cell = |k: usize| &record[first + k];
        let real = |k: usize| -> Result<Option<f64>, String> {
            match cell(k) {
                "" => Ok(None),
                text => text
                    .parse()
                    .map(Some)
                    .map_err(|_| format!("`{text}` is not a number")),
            }
        };
        let count = |k: usize| -> Result<usize, String> {
            cell(k)
                .parse()
                .map_err(|_| format!("`{}` is not a count", cell(k)))
        };
        summary.max_crush_m = real(0)?;
        summary.time_of_max_crush_s = real(1)?;
        summary.time_to_zero_velocity_s = real(2)?;
        summary.max_theta1_deg = real(3)?;
        summary.max_theta2_deg = real(4)?;
        summary.peak_deceleration_g = real(5)?;
        summary.rebound_velocity_mps = real(6)?;
        summary.weld_failure_time_s = real(7)?;
        summary.peak_deceleration_cfc60_g = real(8)?;
        summary.equivalent_square_wave_g = real(9)?;
        summary.olc_g = real(10)?;
        summary.asi = real(11)?;
        summary.steps = count(12)?;
        summary.rejected_steps = count(13)?;
        summary.rhs_evaluations = count(14)?;
        summary.energy_balance_error_rel = real(15)?.unwrap_or(f64::NAN);
        Ok(summary)
    } else {
        Err(RunFailure {
            kind: status.to_string(),
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
pub fn sweep_csv(axes: &[String], rows: &[Row]) -> Result<Vec<u8>, String> {
    let mut writer = csv::Writer::from_writer(Vec::new());
    let fail = |e: csv::Error| format!("cannot write CSV: {e}");
    writer.write_record(columns(axes)).map_err(fail)?;
    for row in rows {
        writer.write_record(record(row)).map_err(fail)?;
    }
    writer
        .into_inner()
        .map_err(|e| format!("cannot write CSV: {e}"))
}

fn column_type(
    name: &str,
    physical: Physical,
    repetition: Repetition,
) -> Result<Arc<Type>, String> {
    let mut builder = Type::primitive_type_builder(name, physical).with_repetition(repetition);
    if physical == Physical::BYTE_ARRAY {
        builder = builder.with_converted_type(ConvertedType::UTF8);
    }
    builder
        .build()
        .map(Arc::new)
        .map_err(|e| format!("Parquet schema: {e}"))
}

/// A Parquet file (one row group, uncompressed). Metrics absent from a run
/// (a failed run, or no crush coordinate) are nulls.
pub fn sweep_parquet(axes: &[String], rows: &[Row]) -> Result<Vec<u8>, String> {
    let mut bytes = Vec::new();
    write_parquet(axes, std::iter::once(Ok(rows.to_vec())), &mut bytes)?;
    Ok(bytes)
}

/// Writes a Parquet file to `out`, one row group per item of `groups`, so
/// that a table of any length is written in the memory of one group.
pub fn write_parquet<W: std::io::Write + Send>(
    axes: &[String],
    groups: impl Iterator<Item = Result<Vec<Row>, String>>,
    out: W,
) -> Result<(), String> {
    let fail = |e: parquet::errors::ParquetError| format!("cannot write Parquet: {e}");
    let mut fields = vec![column_type("run", Physical::INT64, Repetition::REQUIRED)?];
    for axis in axes {
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
    for (name, metric) in metrics(&EMPTY) {
        let physical = match metric {
            Metric::Real(_) => Physical::DOUBLE,
            Metric::Count(_) => Physical::INT64,
        };
        fields.push(column_type(name, physical, Repetition::OPTIONAL)?);
    }
    let schema = Type::group_type_builder("sweep")
        .with_fields(fields)
        .build()
        .map_err(fail)?;
    let properties = Arc::new(WriterProperties::builder().build());
    let mut writer = SerializedFileWriter::new(out, Arc::new(schema), properties).map_err(fail)?;
    for rows in groups {
        let rows = rows?;
        let mut group = writer.next_row_group().map_err(fail)?;
        let mut column = 0usize;
        // Writes the next column: values of the present entries and, for an
        // optional column, the definition levels (1 present, 0 null).
        macro_rules! write_column {
            ($kind:ty, $values:expr, $levels:expr) => {{
                let mut writer = group
                    .next_column()
                    .map_err(fail)?
                    .ok_or_else(|| format!("Parquet: column {column} missing from the schema"))?;
                let levels: Option<Vec<i16>> = $levels;
                writer
                    .typed::<$kind>()
                    .write_batch(&$values, levels.as_deref(), None)
                    .map_err(fail)?;
                writer.close().map_err(fail)?;
                column += 1;
            }};
        }
        let runs: Vec<i64> = rows.iter().map(|r| r.run as i64).collect();
        write_column!(Int64Type, runs, None);
        for k in 0..axes.len() {
            let values: Vec<f64> = rows.iter().map(|r| r.values[k]).collect();
            write_column!(DoubleType, values, None);
        }
        let status: Vec<ByteArray> = rows
            .iter()
            .map(|r| match &r.outcome {
                Ok(_) => ByteArray::from("ok"),
                Err(f) => ByteArray::from(f.kind.as_str()),
            })
            .collect();
        write_column!(ByteArrayType, status, None);
        let errors: Vec<ByteArray> = rows
            .iter()
            .filter_map(|r| {
                r.outcome
                    .as_ref()
                    .err()
                    .map(|e| ByteArray::from(e.message.as_str()))
            })
            .collect();
        let levels = rows.iter().map(|r| i16::from(r.outcome.is_err())).collect();
        write_column!(ByteArrayType, errors, Some(levels));
        for m in 0..metrics(&EMPTY).len() {
            let cells: Vec<Option<Metric>> = rows
                .iter()
                .map(|r| r.outcome.as_ref().ok().map(|s| metrics(s)[m].1))
                .collect();
            let levels: Vec<i16> = cells
                .iter()
                .map(|c| {
                    i16::from(matches!(
                        c,
                        Some(Metric::Real(Some(_))) | Some(Metric::Count(_))
                    ))
                })
                .collect();
            match metrics(&EMPTY)[m].1 {
                Metric::Real(_) => {
                    let values: Vec<f64> = cells
                        .iter()
                        .filter_map(|c| match c {
                            Some(Metric::Real(x)) => *x,
                            _ => None,
                        })
                        .collect();
                    write_column!(DoubleType, values, Some(levels));
                }
                Metric::Count(_) => {
                    let values: Vec<i64> = cells
                        .iter()
                        .filter_map(|c| match c {
                            Some(Metric::Count(n)) => Some(*n as i64),
                            _ => None,
                        })
                        .collect();
                    write_column!(Int64Type, values, Some(levels));
                }
            }
        }
        group.close().map_err(fail)?;
    }
    writer.close().map_err(fail)?;
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
            ..EMPTY
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
                    kind: "step_size_underflow".into(),
                    message: "integration failed: step size too small".into(),
                }),
            },
        ]
    }

    #[test]
    fn metric_columns_are_the_keys_of_summary_json() {
        let json = serde_json::to_value(EMPTY).unwrap();
        let mut keys: Vec<&String> = json.as_object().unwrap().keys().collect();
        let mut ours: Vec<String> = metrics(&EMPTY).iter().map(|(n, _)| n.to_string()).collect();
        keys.sort();
        ours.sort();
        assert_eq!(keys, ours.iter().collect::<Vec<_>>());
    }

    #[test]
    fn csv_has_a_header_and_empty_cells_for_missing_metrics() {
        let axes = vec!["k1".to_string(), "stiffness_values*".to_string()];
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
        let axes = vec!["components.weld.failure_moment".to_string()];
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
        assert_eq!(cell(0, "status"), Field::Str("ok".into()));
        assert_eq!(cell(0, "error"), Field::Null);
        assert_eq!(cell(0, "max_crush_m"), Field::Double(0.5));
        assert_eq!(cell(0, "weld_failure_time_s"), Field::Null);
        assert_eq!(cell(0, "steps"), Field::Long(120));
        assert_eq!(cell(1, "status"), Field::Str("step_size_underflow".into()));
        assert_eq!(
            cell(1, "error"),
            Field::Str("integration failed: step size too small".into())
        );
        assert_eq!(cell(1, "max_crush_m"), Field::Null);
        assert_eq!(cell(1, "steps"), Field::Null);
    }
}
