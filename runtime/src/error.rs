//! Why a model could not do what was asked.

use crate::names::closest;
use std::fmt;

/// Why a model could not do what was asked.
#[derive(Clone, Debug, PartialEq)]
pub enum ModelError {
    /// No parameter of that name.
    UnknownParameter {
        /// The name asked for.
        name: String,
        /// The closest existing name, if one is close.
        suggestion: Option<String>,
    },
    /// The spec did not ask for Jacobians (`jacobians;`).
    JacobiansNotDerived,
    /// `M(q)` is singular or not positive definite at this state.
    SingularMassMatrix {
        /// The time.
        t: f64,
        /// The coordinates.
        q: Vec<f64>,
    },
    /// The number of values does not match the model's.
    DimensionMismatch {
        /// How many the model needs.
        expected: usize,
        /// How many were given.
        found: usize,
    },
    /// A model description that does not fit its tape or itself (a list of
    /// the wrong length, routines with the wrong number of outputs): a bug
    /// in whatever built them.
    InconsistentModel(String),
    /// The interpreter's fixed-size interface covers models of up to `max`
    /// coordinates ([`crate::InterpretedModel::with_dimension`]).
    UnsupportedDimension {
        /// The model's number of coordinates.
        found: usize,
        /// The largest supported.
        max: usize,
    },
}

impl ModelError {
    /// An unknown-parameter error suggesting the closest of `candidates`.
    pub fn unknown_parameter(name: &str, candidates: &[&str]) -> ModelError {
        ModelError::UnknownParameter {
            name: name.to_string(),
            suggestion: closest(name, candidates.iter().copied()).map(str::to_string),
        }
    }
}

impl fmt::Display for ModelError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            ModelError::UnknownParameter { name, suggestion } => {
                write!(f, "unknown parameter `{name}`")?;
                if let Some(s) = suggestion {
                    write!(f, " (did you mean `{s}`?)")?;
                }
                Ok(())
            }
            ModelError::JacobiansNotDerived => write!(
                f,
                "the model's spec does not request Jacobians; add `jacobians;` to it"
            ),
            ModelError::SingularMassMatrix { t, q } => write!(
                f,
                "the mass matrix is singular or not positive definite at t = {t}, q = {q:?}"
            ),
            ModelError::DimensionMismatch { expected, found } => {
                write!(f, "expected {expected} values, found {found}")
            }
            ModelError::InconsistentModel(what) => write!(f, "inconsistent model: {what}"),
            ModelError::UnsupportedDimension { found, max } => write!(
                f,
                "the interpreter handles models of up to {max} coordinates; this one has {found} (compile it with the lagrangian! macro instead)"
            ),
        }
    }
}

impl std::error::Error for ModelError {}
