//! What a study fails with: one error for every service of the crate, which
//! each host turns into its own (`lpm`: a message and an exit status, one
//! conversion; Python: an exception).

use crate::status::ExitStatus;
use lagrangian_sim::fault::{Fault, named_values};
use lagrangian_sim::pulse::channels::ChannelError;
use lagrangian_sim::scenario::{OverrideError, ScenarioError, ScenarioErrorKind};
use lagrangian_sim::simulate::{FailureKind, SimulationError};
use lagrangian_sim::table::TableError;

/// Why a service of this crate failed. Each variant's message is the one
/// line a host prints (after `error: `, except [`StudyError::Spec`]'s,
/// which carries its own).
#[derive(Debug, thiserror::Error)]
pub enum StudyError {
    /// A file that cannot be read or written.
    #[error("{0}")]
    Io(String),
    /// A spec that does not compile: its diagnostics, rendered as
    /// `file:line:col` snippets.
    #[error("{0}")]
    Spec(String),
    /// A scenario that cannot be read, does not fit the spec, or names a
    /// data file that cannot be used (its kind says which).
    #[error(transparent)]
    Scenario(ScenarioError),
    /// A data file (time histories, a journal, weights) that cannot be used.
    #[error("{0}")]
    DataFile(String),
    /// The model cannot be evaluated at the given state.
    #[error("{0}")]
    Evaluation(String),
    /// A run that failed.
    #[error("{message}")]
    Run {
        /// What kind of failure.
        kind: FailureKind,
        /// The one-line message.
        message: String,
        /// Lines a verbose host prints after it (the state it failed at).
        details: Vec<String>,
    },
    /// Every run of a sweep failed.
    #[error("{0}")]
    EveryRunFailed(String),
    /// Stopped on request ([`crate::progress::Progress::stop_requested`]).
    #[error("{message}")]
    Interrupted {
        /// The one-line message.
        message: String,
        /// The journal that keeps the finished runs, to resume from (its
        /// message says so and is printed as it is).
        journal: Option<std::path::PathBuf>,
    },
    /// A fit that failed.
    #[error("{0}")]
    Fit(String),
    /// Code generated from a spec (a compiled FMU binary) that cargo did
    /// not build: the spec's status, printed after `error: `.
    #[error("{0}")]
    Build(String),
    /// A request that does not make sense (what `lpm` calls a bad command
    /// line).
    #[error("{0}")]
    BadRequest(String),
}

impl StudyError {
    /// A file that cannot be read or written.
    pub fn io(message: impl Into<String>) -> StudyError {
        StudyError::Io(message.into())
    }

    /// A bad request.
    pub fn usage(message: impl Into<String>) -> StudyError {
        StudyError::BadRequest(message.into())
    }

    /// A model that cannot be evaluated.
    pub fn evaluation(message: impl Into<String>) -> StudyError {
        StudyError::Evaluation(message.into())
    }

    /// A data file that cannot be used.
    pub fn data_file(message: impl Into<String>) -> StudyError {
        StudyError::DataFile(message.into())
    }

    /// A model the interpreter cannot run as it is (too many coordinates).
    pub fn model(e: lagrangian_runtime::ModelError) -> StudyError {
        StudyError::usage(e.to_string())
    }

    /// A failed run of `kind` with `message` and no details.
    pub fn run(kind: FailureKind, message: impl Into<String>) -> StudyError {
        StudyError::Run {
            kind,
            message: message.into(),
            details: Vec::new(),
        }
    }

    /// A scenario that cannot be read, does not fit, or names a data file
    /// that cannot be used.
    pub fn scenario(e: &ScenarioError) -> StudyError {
        StudyError::Scenario(e.clone())
    }

    /// A scenario that does not fit, said in `message` alone.
    pub fn invalid_scenario(message: impl Into<String>) -> StudyError {
        StudyError::Scenario(ScenarioError {
            kind: ScenarioErrorKind::Invalid,
            file: None,
            location: None,
            message: message.into(),
            key: None,
        })
    }

    /// A time-history file that cannot be read ([`StudyError::Io`]) or
    /// used ([`StudyError::DataFile`]).
    pub fn channels(e: &ChannelError) -> StudyError {
        match e {
            ChannelError::Table(TableError::Read { .. }) => StudyError::Io(e.to_string()),
            _ => StudyError::DataFile(e.to_string()),
        }
    }

    /// A failed run, with the state it failed at (coordinates named) as
    /// details.
    pub fn simulation(e: &SimulationError, coordinates: &[String]) -> StudyError {
        let mut details = vec![format!("kind: {:?}", e.kind())];
        let state = match (e.fault().and_then(Fault::state), e.reached()) {
            (Some(state), _) => Some(state),
            (None, Some(reached)) => {
                let t = reached.t;
                details.push(format!("last accepted step ended at t = {t:e} s"));
                Some((&reached.q[..], &reached.qd[..]))
            }
            (None, None) => None,
        };
        if let Some((q, qd)) = state {
            details.push(format!("coordinates: {}", named_values(coordinates, q)));
            details.push(format!("velocities:  {}", named_values(coordinates, qd)));
        }
        StudyError::Run {
            kind: e.kind(),
            message: e.to_string(),
            details,
        }
    }

    /// The same error with `why` after its message (`message: why`).
    pub fn because(mut self, why: &str) -> StudyError {
        let message = match &mut self {
            StudyError::Scenario(e) => &mut e.message,
            StudyError::Run { message, .. } | StudyError::Interrupted { message, .. } => message,
            StudyError::Io(m)
            | StudyError::Spec(m)
            | StudyError::DataFile(m)
            | StudyError::Evaluation(m)
            | StudyError::EveryRunFailed(m)
            | StudyError::Fit(m)
            | StudyError::Build(m)
            | StudyError::BadRequest(m) => m,
        };
        *message = format!("{}: {why}", message.trim_end());
        self
    }

    /// The exit status of the error's kind (`lpm`'s; the Python package
    /// raises the exception class of its code).
    pub fn status(&self) -> ExitStatus {
        match self {
            StudyError::Spec(_) => ExitStatus::Spec,
            StudyError::Io(_) => ExitStatus::Io,
            StudyError::Scenario(e) => e.kind.failure().map_or(ExitStatus::Io, ExitStatus::Failed),
            StudyError::DataFile(_) => ExitStatus::Failed(FailureKind::DataFile),
            StudyError::Evaluation(_) => ExitStatus::Evaluation,
            StudyError::Run { kind, .. } => ExitStatus::Failed(*kind),
            StudyError::EveryRunFailed(_) => ExitStatus::EveryRunFailed,
            StudyError::Interrupted { .. } => ExitStatus::Interrupted,
            StudyError::Fit(_) => ExitStatus::FitFailed,
            StudyError::Build(_) => ExitStatus::Spec,
            StudyError::BadRequest(_) => ExitStatus::Usage,
        }
    }

    /// The lines a verbose host prints after the message.
    pub fn details(&self) -> &[String] {
        match self {
            StudyError::Run { details, .. } => details,
            _ => &[],
        }
    }
}

// What each error of the libraries below is to a host: the kind of
// failure (and so the exit status), with its message as it is.

/// An override that cannot be read or does not fit: a scenario problem,
/// as a scenario entry that does not fit is.
impl From<OverrideError> for StudyError {
    fn from(e: OverrideError) -> StudyError {
        StudyError::Scenario(e.into())
    }
}

/// A sweep's axes that make no plan: a bad request.
#[cfg(feature = "sweep")]
impl From<crate::sweep::PlanError> for StudyError {
    fn from(e: crate::sweep::PlanError) -> StudyError {
        StudyError::usage(e.to_string())
    }
}

/// A shard that cannot be told: a bad request.
#[cfg(feature = "sweep")]
impl From<crate::sweep::ShardError> for StudyError {
    fn from(e: crate::sweep::ShardError) -> StudyError {
        StudyError::usage(e.to_string())
    }
}

/// Axes that do not fit the scenario: a bad request.
#[cfg(feature = "sweep")]
impl From<crate::sweep::SettingsError> for StudyError {
    fn from(e: crate::sweep::SettingsError) -> StudyError {
        StudyError::usage(e.to_string())
    }
}

/// Weights that cannot be used: a bad request.
#[cfg(feature = "sweep")]
impl From<crate::sweep::WeightsError> for StudyError {
    fn from(e: crate::sweep::WeightsError) -> StudyError {
        StudyError::usage(e.to_string())
    }
}

/// A table that cannot be written: an I/O error.
#[cfg(feature = "sweep")]
impl From<crate::sweep::WriteError> for StudyError {
    fn from(e: crate::sweep::WriteError) -> StudyError {
        StudyError::io(e.to_string())
    }
}

/// A journal that cannot be made, appended to or read: an I/O error (one
/// resumed that belongs to another sweep is a data file's, said where it
/// is read).
#[cfg(feature = "sweep")]
impl From<crate::sweep::JournalError> for StudyError {
    fn from(e: crate::sweep::JournalError) -> StudyError {
        StudyError::io(e.to_string())
    }
}

/// Shards' tables that do not merge: a data file's error.
#[cfg(feature = "sweep")]
impl From<crate::sweep::MergeError> for StudyError {
    fn from(e: crate::sweep::MergeError) -> StudyError {
        StudyError::data_file(e.to_string())
    }
}

/// A run that does not add to the envelope of a sweep under way ends the
/// sweep's stream of rows: an I/O error, as a row that cannot be written.
#[cfg(feature = "sweep")]
impl From<crate::sweep::EnvelopeError> for StudyError {
    fn from(e: crate::sweep::EnvelopeError) -> StudyError {
        StudyError::io(e.to_string())
    }
}

/// A partial envelope that cannot be written (an I/O error), or read and
/// merged (a data file's error).
#[cfg(feature = "sweep")]
impl From<crate::sweep::EnvelopeFileError> for StudyError {
    fn from(e: crate::sweep::EnvelopeFileError) -> StudyError {
        match e {
            crate::sweep::EnvelopeFileError::Write(_) => StudyError::io(e.to_string()),
            _ => StudyError::data_file(e.to_string()),
        }
    }
}

/// `--fit` names that do not resolve: a bad request.
#[cfg(feature = "fit")]
impl From<crate::fit::ParameterError> for StudyError {
    fn from(e: crate::fit::ParameterError) -> StudyError {
        StudyError::usage(e.to_string())
    }
}

/// A fit that failed.
#[cfg(feature = "fit")]
impl From<crate::fit::FitError> for StudyError {
    fn from(e: crate::fit::FitError) -> StudyError {
        StudyError::Fit(e.to_string())
    }
}
