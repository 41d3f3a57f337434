//! What can go wrong inside one evaluation of a model during a run.
//!
//! The solver reports a [`Fault`] with the time it happened at
//! ([`crate::ode::SolverError::Rhs`]); the state is kept so that a user can
//! see where the model broke (`lpm … -v` prints it with coordinate names).

/// A failed evaluation of the model or of a component it reads.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum Fault {
    /// `M(q)` has no `L D Lᵀ` factorization with positive pivots (the only
    /// way the mass matrix is solved): singular, or not positive definite,
    /// at coordinates `q`.
    #[error("the mass matrix is singular or not positive definite at q = {q:?}")]
    SingularMassMatrix {
        /// The coordinates the mass matrix was evaluated at, in the model's
        /// order and units (\[m\] or \[rad\]).
        q: Vec<f64>,
        /// The velocities at the same instant ([m/s] or [rad/s]).
        qd: Vec<f64>,
    },
    /// An entry of `M`, `f`, `q̈` or a power is NaN or ±∞.
    #[error("{output} is {value}")]
    NonFinite {
        /// Which value, e.g. `f[theta1]` or `M[r, theta2]`.
        output: String,
        /// The offending value: NaN, `inf` or `-inf`.
        value: f64,
        /// The coordinates the model was evaluated at (\[m\] or \[rad\]).
        q: Vec<f64>,
        /// The velocities at the same instant ([m/s] or [rad/s]).
        qd: Vec<f64>,
    },
    /// A table read outside its range under the `error` policy.
    #[error(
        "{}component `{component}` evaluated at {x} outside its table [{min}, {max}] (policy `error`)",
        read_through(.input)
    )]
    OutOfRange {
        /// The scenario's name of the component (`[components.NAME]`).
        component: String,
        /// The model input that read it, when it was read through one.
        input: Option<String>,
        /// The abscissa it was read at, in the table's units (a time \[s\],
        /// a crush \[m\], …).
        x: f64,
        /// The first abscissa of the table.
        min: f64,
        /// The last abscissa of the table.
        max: f64,
    },
    /// The constraints `names` depend on the ones declared before them at
    /// this state: `G M⁻¹ Gᵀ` (and with it `[[M, Gᵀ], [G, 0]]`) is singular.
    #[error(
        "redundant constraints at q = {q:?}: {} (each depends on the constraints declared before it)",
        names.join(", ")
    )]
    RedundantConstraints {
        /// The redundant constraints' names, in backticks.
        names: Vec<String>,
        /// The coordinates (\[m\] or \[rad\]).
        q: Vec<f64>,
        /// The velocities ([m/s] or [rad/s]).
        qd: Vec<f64>,
    },
    /// Anything else a component reports (an input with no value, an input
    /// called with the wrong number of arguments).
    #[error("{0}")]
    Component(String),
}

/// `input `force`: ` before the message of a table read through an input.
fn read_through(input: &Option<String>) -> String {
    input
        .as_ref()
        .map_or_else(String::new, |input| format!("input `{input}`: "))
}

impl Fault {
    /// The coordinates and velocities at the fault, when it has them.
    pub fn state(&self) -> Option<(&[f64], &[f64])> {
        match self {
            Fault::SingularMassMatrix { q, qd }
            | Fault::NonFinite { q, qd, .. }
            | Fault::RedundantConstraints { q, qd, .. } => Some((q, qd)),
            _ => None,
        }
    }
}

/// `name = value` pairs, for messages: `r = 0.1, theta1 = -0.02`.
pub fn named_values(names: &[String], values: &[f64]) -> String {
    names
        .iter()
        .zip(values)
        .map(|(n, v)| format!("{n} = {v:e}"))
        .collect::<Vec<_>>()
        .join(", ")
}
