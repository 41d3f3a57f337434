//! Why a comparison fails, with the file, channel or pair it is about;
//! and what each failure is to a host ([`StudyError`]'s kind, so its exit
//! status).

use crate::error::StudyError;
use lagrangian_correlation::RatingError;
use lagrangian_sim::table::TableError;
use std::path::PathBuf;

/// Why [`super::compare`] gives no comparison.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum CompareError {
    /// A CSV file that cannot be read, or not as a table of numbers with
    /// increasing times.
    #[error("{0}")]
    Table(TableError),
    /// A folder without the trajectory of a simulation run.
    #[error(
        "{}: not a simulation output folder (it has no {})",
        .folder.display(),
        super::source::TRAJECTORY
    )]
    NotRunFolder {
        /// The folder.
        folder: PathBuf,
    },
    /// A CSV file without a time column.
    #[error(
        "{}: no time column `t [s]` or `t [ms]` (columns: {})",
        .file.display(),
        .headers.join(", ")
    )]
    NoTime {
        /// The file.
        file: PathBuf,
        /// Its headers.
        headers: Vec<String>,
    },
    /// A time column whose unit is missing or not a time.
    #[error("{}: time column `{header}` needs a unit of time in brackets, e.g. `t [s]` or `t [ms]`", .file.display())]
    TimeUnit {
        /// The file.
        file: PathBuf,
        /// The header as written.
        header: String,
    },
    /// A CSV file with a time column and nothing else.
    #[error("{}: no channel besides the time column", .file.display())]
    NoChannels {
        /// The file.
        file: PathBuf,
    },
    /// A `--channel` that is not `REF=COMP` (or a name).
    #[error("--channel `{text}`: expected REF=COMP (or NAME for the same name in both)")]
    BadPair {
        /// The text as given.
        text: String,
    },
    /// A channel asked for that the source does not have.
    #[error(
        "{}: no channel `{name}` (channels: {}){}",
        .file.display(),
        .available.join(", "),
        .suggestion.as_ref().map_or(String::new(), |s| format!("; did you mean `{s}`?"))
    )]
    UnknownChannel {
        /// The source's file.
        file: PathBuf,
        /// The name asked for.
        name: String,
        /// The channels it has.
        available: Vec<String>,
        /// The closest of them, when one is close.
        suggestion: Option<String>,
    },
    /// No `--channel` given and no channel name in both sources.
    #[error(
        "{} and {} have no channel of the same name; pair channels with --channel REF=COMP",
        .reference.display(),
        .comparison.display()
    )]
    NothingInCommon {
        /// The reference's file.
        reference: PathBuf,
        /// The comparison's file.
        comparison: PathBuf,
    },
    /// A pair whose units are not of one dimension.
    #[error(
        "`{reference}` is in {reference_unit} but `{comparison}` in {comparison_unit}, which does not convert to it"
    )]
    Units {
        /// The reference channel.
        reference: String,
        /// Its unit.
        reference_unit: String,
        /// The comparison channel.
        comparison: String,
        /// Its unit.
        comparison_unit: String,
    },
    /// A pair that cannot be rated.
    #[error("`{reference}` against `{comparison}`: {error}")]
    Rating {
        /// The reference channel.
        reference: String,
        /// The comparison channel.
        comparison: String,
        /// Why.
        error: RatingError,
    },
    /// An ISO-MME or EV5 test that cannot be read or used (the file, line
    /// and field in the reader's error).
    #[error("{0}")]
    IsoMme(lagrangian_crashdata::ReadError),
    /// Channels paired by name, none of which could be rated.
    #[error("no pair of channels could be rated: {}", .first)]
    NothingRated {
        /// Why the first pair could not.
        first: Box<CompareError>,
    },
}

/// A file that cannot be read is an I/O error; a bad `--channel` a bad
/// request; a file, channel or pair that cannot be used a data file's
/// error.
impl From<CompareError> for StudyError {
    fn from(e: CompareError) -> StudyError {
        match e {
            CompareError::Table(TableError::Read { .. }) | CompareError::NotRunFolder { .. } => {
                StudyError::io(e.to_string())
            }
            CompareError::BadPair { .. }
            | CompareError::UnknownChannel { .. }
            | CompareError::NothingInCommon { .. } => StudyError::usage(e.to_string()),
            CompareError::Table(_)
            | CompareError::NoTime { .. }
            | CompareError::TimeUnit { .. }
            | CompareError::NoChannels { .. }
            | CompareError::Units { .. }
            | CompareError::Rating { .. }
            | CompareError::IsoMme(_)
            | CompareError::NothingRated { .. } => StudyError::data_file(e.to_string()),
        }
    }
}
