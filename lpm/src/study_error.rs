//! The one conversion of a service's error ([`StudyError`]) into what
//! `lpm` prints and exits with: the message, its details for `-v`, and
//! the exit status of its kind.

use crate::failure::Failure;
use crate::status::ExitStatus;
use lagrangian_sim::failure::FailureKind;
use lagrangian_studies::error::StudyError;

impl From<&StudyError> for Failure {
    fn from(e: &StudyError) -> Failure {
        let message = e.to_string();
        let status = match e {
            StudyError::Spec(text) => return Failure::rendered(ExitStatus::Spec, text.clone()),
            StudyError::Io(_) => ExitStatus::Io,
            StudyError::Scenario(e) => e.kind.failure().map_or(ExitStatus::Io, ExitStatus::Failed),
            StudyError::DataFile(_) => ExitStatus::Failed(FailureKind::DataFile),
            StudyError::Evaluation(_) => ExitStatus::Evaluation,
            StudyError::Run { kind, .. } => ExitStatus::Failed(*kind),
            StudyError::EveryRunFailed(_) => ExitStatus::EveryRunFailed,
            StudyError::Interrupted {
                journal: Some(_), ..
            } => return Failure::rendered(ExitStatus::Interrupted, message),
            StudyError::Interrupted { journal: None, .. } => ExitStatus::Interrupted,
            StudyError::Fit(_) => ExitStatus::FitFailed,
            StudyError::BadRequest(_) => ExitStatus::Usage,
        };
        let mut failure = Failure::new(status, message);
        failure.details = e.details().to_vec();
        failure
    }
}

/// For `?`: the conversion above, of an error no longer needed.
impl From<StudyError> for Failure {
    fn from(e: StudyError) -> Failure {
        Failure::from(&e)
    }
}
