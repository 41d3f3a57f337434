//! A scenario file with settings that every run of a sweep or a fit shares.

use super::{ModelNames, Override, Scenario, ScenarioError};
use crate::files::Files;
use std::path::PathBuf;
use std::sync::Arc;

/// The scenario every run of a sweep or a fit starts from.
#[derive(Clone, Debug)]
pub struct BaseScenario {
    /// The scenario file's text (empty for the defaults).
    pub text: String,
    /// The file, which relative paths in it start from.
    pub file: Option<PathBuf>,
    /// The names of the model it is resolved against.
    pub names: ModelNames,
    /// `--set` settings applied to every run before a run's own.
    pub settings: Vec<Override>,
    /// Where the tables it names are read from, once per run.
    pub files: Arc<dyn Files>,
}

impl BaseScenario {
    /// The scenario with the base's settings, then `settings`, applied.
    pub fn resolve(&self, settings: &[Override]) -> Result<Scenario, ScenarioError> {
        let mut all = self.settings.clone();
        all.extend_from_slice(settings);
        Scenario::parse_in(
            &*self.files,
            &self.text,
            self.file.as_deref(),
            &self.names,
            &all,
        )
    }
}
