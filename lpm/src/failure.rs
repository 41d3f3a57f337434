//! What a subcommand returns: the text to print and the exit status, or a
//! failure with its one-line message and the details `-v` adds.

use crate::status::ExitStatus;
use lagrangian_sim::fault::{Fault, named_values};
use lagrangian_sim::pulse::channels::ChannelError;
use lagrangian_sim::scenario::{Override, ScenarioError};
use lagrangian_sim::simulate::{FailureKind, SimulationError};
use lagrangian_sim::table::TableError;

/// A finished subcommand: what it prints on stdout and how `lpm` exits.
pub struct Outcome {
    /// The text for stdout.
    pub text: String,
    /// The exit status (not always success: `audit` and `generate --check`
    /// report findings by status).
    pub status: ExitStatus,
}

impl Outcome {
    /// Success with `text`.
    pub fn success(text: String) -> Outcome {
        Outcome {
            text,
            status: ExitStatus::Success,
        }
    }
}

/// A failure: the message for stderr, the details `-v` adds, the status.
pub struct Failure {
    /// The exit status.
    pub status: ExitStatus,
    message: String,
    /// The message is printed as it is, not after `error: ` (spec
    /// diagnostics, which carry their own).
    rendered: bool,
    /// Lines `-v` prints after the message.
    pub details: Vec<String>,
}

impl Failure {
    /// A failure printed as `error: {message}`.
    pub fn new(status: ExitStatus, message: impl Into<String>) -> Failure {
        Failure {
            status,
            message: message.into(),
            rendered: false,
            details: Vec::new(),
        }
    }

    /// A failure whose text is printed as it is.
    pub fn rendered(status: ExitStatus, text: impl Into<String>) -> Failure {
        Failure {
            rendered: true,
            ..Failure::new(status, text)
        }
    }

    /// A file that cannot be read or written.
    pub fn io(message: impl Into<String>) -> Failure {
        Failure::new(ExitStatus::Io, message)
    }

    /// A bad command line.
    pub fn usage(message: impl Into<String>) -> Failure {
        Failure::new(ExitStatus::Usage, message)
    }

    /// A model that cannot be evaluated.
    pub fn evaluation(message: impl Into<String>) -> Failure {
        Failure::new(ExitStatus::Evaluation, message)
    }

    /// A model the interpreter cannot run as it is (too many coordinates).
    pub fn model(e: lagrangian_runtime::ModelError) -> Failure {
        Failure::usage(e.to_string())
    }

    /// The same failure with `why` after its message (`message: why`).
    pub fn because(mut self, why: &str) -> Failure {
        self.message = format!("{}: {why}", self.message.trim_end());
        self
    }

    /// The message without the `error: ` that stderr gets before it.
    pub fn message(&self) -> &str {
        self.message.trim_end()
    }

    /// What stderr gets (without the details).
    pub fn text(&self) -> String {
        let message = self.message.trim_end();
        if self.rendered {
            message.to_string()
        } else {
            format!("error: {message}")
        }
    }

    /// A scenario that cannot be read (1), does not fit (4), or names a
    /// data file that cannot be used (7).
    pub fn scenario(e: &ScenarioError) -> Failure {
        let status = e.kind.failure().map_or(ExitStatus::Io, ExitStatus::Failed);
        Failure::new(status, e.to_string())
    }

    /// The `--set` overrides, each read once here; one that cannot be read
    /// fails as a scenario entry that does not fit would (4).
    pub fn overrides(set: &[String]) -> Result<Vec<Override>, Failure> {
        Override::parse_all(set).map_err(|e| Failure::scenario(&e.into()))
    }

    /// A time-history file that cannot be read (1) or used (7).
    pub fn channels(e: &ChannelError) -> Failure {
        let status = match e {
            ChannelError::Table(TableError::Read { .. }) => ExitStatus::Io,
            _ => ExitStatus::Failed(FailureKind::DataFile),
        };
        Failure::new(status, e.to_string())
    }

    /// A failed run, with the state it failed at (coordinates named) as
    /// details.
    pub fn simulation(e: &SimulationError, coordinates: &[String]) -> Failure {
        let mut failure = Failure::new(e.kind().into(), e.to_string());
        failure.details.push(format!("kind: {:?}", e.kind()));
        let state = match (e.fault().and_then(Fault::state), e.reached()) {
            (Some(state), _) => Some(state),
            (None, Some(reached)) => {
                let t = reached.t;
                failure
                    .details
                    .push(format!("last accepted step ended at t = {t:e} s"));
                Some((&reached.q[..], &reached.qd[..]))
            }
            (None, None) => None,
        };
        if let Some((q, qd)) = state {
            failure
                .details
                .push(format!("coordinates: {}", named_values(coordinates, q)));
            failure
                .details
                .push(format!("velocities:  {}", named_values(coordinates, qd)));
        }
        failure
    }
}
