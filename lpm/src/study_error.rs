//! The one conversion of a service's error ([`StudyError`]) into what
//! `lpm` prints and exits with: the message, its details for `-v`, and
//! the exit status of its kind.

use crate::failure::Failure;
use lagrangian_studies::error::StudyError;

impl From<&StudyError> for Failure {
    fn from(e: &StudyError) -> Failure {
        let message = e.to_string();
        let status = e.status();
        match e {
            StudyError::Spec(text) => return Failure::rendered(status, text.clone()),
            StudyError::Interrupted {
                journal: Some(_), ..
            } => return Failure::rendered(status, message),
            _ => {}
        }
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
