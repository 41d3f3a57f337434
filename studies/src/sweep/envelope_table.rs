//! An [`Envelope`] as a table, one row per output time: `t`, then for each
//! channel `CHANNEL.min`, `CHANNEL.min_run`, `CHANNEL.max`,
//! `CHANNEL.max_run`, `CHANNEL.mean` — CSV (numbers that read back
//! exactly) or Parquet (runs as 64-bit integers, null where no run has a
//! finite value).

use super::envelope::Envelope;
use super::table::{GroupColumns, WriteError, column_type};
use parquet::basic::{Repetition, Type as Physical};
use parquet::data_type::{DoubleType, Int64Type};
use parquet::file::properties::WriterProperties;
use parquet::file::writer::SerializedFileWriter;
use parquet::schema::types::Type;
use std::io::Write;
use std::sync::Arc;

/// What each channel contributes to a row, in column order.
const QUANTITIES: [&str; 5] = ["min", "min_run", "max", "max_run", "mean"];

/// The column names of the table of `envelope`.
pub fn envelope_columns(envelope: &Envelope) -> Vec<String> {
    let mut names = vec!["t".to_string()];
    for channel in &envelope.channels {
        names.extend(QUANTITIES.iter().map(|q| format!("{}.{q}", channel.name)));
    }
    names
}

/// Writes the CSV table of `envelope` to `out`.
pub fn write_envelope_csv(envelope: &Envelope, out: impl Write) -> Result<(), WriteError> {
    let mut writer = csv::Writer::from_writer(out);
    writer.write_record(envelope_columns(envelope))?;
    let means: Vec<Vec<f64>> = (0..envelope.channels.len())
        .map(|k| envelope.mean(k))
        .collect();
    let run = |r: Option<usize>| r.map(|r| r.to_string()).unwrap_or_default();
    for (i, t) in envelope.t.iter().enumerate() {
        let mut record = vec![format!("{t:?}")];
        for (channel, mean) in envelope.channels.iter().zip(&means) {
            record.push(format!("{:?}", channel.min[i]));
            record.push(run(channel.min_run[i]));
            record.push(format!("{:?}", channel.max[i]));
            record.push(run(channel.max_run[i]));
            record.push(format!("{:?}", mean[i]));
        }
        writer.write_record(record)?;
    }
    writer.flush().map_err(|e| WriteError::Csv(e.into()))
}

/// The Parquet schema of [`envelope_columns`].
fn schema(envelope: &Envelope) -> Result<Type, WriteError> {
    let mut fields = Vec::new();
    for name in envelope_columns(envelope) {
        let field = match name.ends_with("_run") {
            true => column_type(&name, Physical::INT64, Repetition::OPTIONAL)?,
            false => column_type(&name, Physical::DOUBLE, Repetition::REQUIRED)?,
        };
        fields.push(field);
    }
    Type::group_type_builder("envelope")
        .with_fields(fields)
        .build()
        .map_err(WriteError::Parquet)
}

/// Writes the Parquet table of `envelope` to `out` (one row group).
pub fn write_envelope_parquet<W: Write + Send>(
    envelope: &Envelope,
    out: W,
) -> Result<(), WriteError> {
    let properties = Arc::new(WriterProperties::builder().build());
    let schema = Arc::new(schema(envelope)?);
    let mut writer = SerializedFileWriter::new(out, schema, properties)?;
    write_group(&mut writer, envelope)?;
    writer.close()?;
    Ok(())
}

/// The envelope's one row group, its columns in schema order.
fn write_group<W: Write + Send>(
    writer: &mut SerializedFileWriter<W>,
    envelope: &Envelope,
) -> Result<(), WriteError> {
    let mut columns = GroupColumns {
        group: writer.next_row_group()?,
        written: 0,
    };
    columns.write::<DoubleType>(&envelope.t, None)?;
    for (k, channel) in envelope.channels.iter().enumerate() {
        columns.write::<DoubleType>(&channel.min, None)?;
        write_runs(&mut columns, &channel.min_run)?;
        columns.write::<DoubleType>(&channel.max, None)?;
        write_runs(&mut columns, &channel.max_run)?;
        columns.write::<DoubleType>(&envelope.mean(k), None)?;
    }
    columns.group.close()?;
    Ok(())
}

/// A column of runs, null where absent.
fn write_runs<W: Write + Send>(
    columns: &mut GroupColumns<'_, W>,
    runs: &[Option<usize>],
) -> Result<(), WriteError> {
    let present: Vec<i64> = runs.iter().flatten().map(|&r| r as i64).collect();
    let levels: Vec<i16> = runs.iter().map(|r| i16::from(r.is_some())).collect();
    columns.write::<Int64Type>(&present, Some(&levels))
}
