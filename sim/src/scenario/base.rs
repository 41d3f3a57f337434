//! A scenario file with settings that every run of a sweep or a fit shares.

use super::{EntryError, ModelNames, Override, Scenario, ScenarioError, with_settings};
use crate::files::Files;
use crate::quantity::value_in;
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

    /// The SI number that `text`, a number with a unit (`"56 km/h"`),
    /// gives the entry `key` (a parameter, an input's constant or a dotted
    /// entry), checked against the unit that entry needs as `--set` checks
    /// it: how a sweep's axis values with units become its numbers, once,
    /// before any run.
    pub fn si_value(&self, key: &str, text: &str) -> Result<f64, EntryError> {
        let path = Override::number(key, 0.0).path();
        let why = |reason: String| EntryError::text(path.clone(), text, reason);
        if !key.contains('.') {
            return self.model_quantity(key, text).map_err(why);
        }
        let document: toml::Table = (self.text.parse())
            .map_err(|e| why(format!("the scenario file does not read: {e}")))?;
        let mut settings = self.settings.clone();
        settings.push(Override::value(key, toml::Value::String(text.to_string())));
        let (mut document, _) =
            with_settings(document, &self.names, &settings).map_err(|e| why(e.to_string()))?;
        super::quantities::in_si(&mut document, &self.names)?;
        match super::scale::entry_at(&document, key).and_then(super::as_number) {
            Some(value) => Ok(value),
            None => Err(why("this entry takes no unit: write it as a number".into())),
        }
    }

    /// A parameter's or an input's quantity in the unit the spec declares.
    fn model_quantity(&self, name: &str, text: &str) -> Result<f64, String> {
        let unit = super::overrides::declared_unit(name, &self.names)
            .ok_or_else(|| format!("`{name}` is neither a parameter nor an input of the model"))?
            .ok_or_else(|| {
                format!("the spec declares no unit for `{name}`: write the number in SI units")
            })?;
        value_in(text, &unit).map_err(|e| e.problem.to_string())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::files::Disk;

    fn base(text: &str) -> BaseScenario {
        let names = ModelNames {
            coordinates: vec!["x".into()],
            coordinate_units: vec![Some("m".into())],
            parameters: vec!["m".into(), "c".into()],
            parameter_units: vec![Some("kg".into()), None],
            parameter_defaults: vec![1.0, 2.0],
            ..ModelNames::default()
        };
        BaseScenario {
            text: text.into(),
            file: None,
            names,
            settings: Vec::new(),
            files: Arc::new(Disk),
        }
    }

    #[test]
    fn a_value_with_a_unit_is_the_si_number_its_entry_takes() {
        let base = base("");
        assert_eq!(base.si_value("m", "1.2 t").unwrap(), 1200.0);
        assert_eq!(base.si_value("initial.speed", "72 km/h").unwrap(), 20.0);
        assert_eq!(base.si_value("simulation.t_end", "150 ms").unwrap(), 0.15);
        assert_eq!(
            base.si_value("initial.velocities.x", "-36 km/h").unwrap(),
            -10.0
        );
    }

    #[test]
    fn a_unit_of_another_dimension_or_none_is_refused_naming_the_entry() {
        let base = base("");
        let error = base
            .si_value("initial.speed", "50 km")
            .unwrap_err()
            .to_string();
        assert!(
            error.contains("initial.speed") && error.contains("m/s"),
            "{error}"
        );
        let error = base.si_value("c", "3 N").unwrap_err().to_string();
        assert!(error.contains("declares no unit for `c`"), "{error}");
        let error = base.si_value("z", "3 N").unwrap_err().to_string();
        assert!(
            error.contains("`z` is neither a parameter nor an input"),
            "{error}"
        );
    }
}
