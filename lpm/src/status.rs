//! The exit statuses of `lpm`: one list, from which `lpm --help` prints its
//! table (and which a test holds the book's table, docs/book/reference/errors.md, against).

use lagrangian_sim::simulate::FailureKind;

/// How `lpm` ended, as its exit status.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ExitStatus {
    /// Success.
    Success,
    /// A file cannot be read or written.
    Io,
    /// A bad command line.
    Usage,
    /// The spec does not compile.
    Spec,
    /// The scenario does not fit the spec.
    Scenario,
    /// The audit found equations that disagree.
    AuditDisagrees,
    /// Generated files are stale.
    Stale,
    /// A data file cannot be used.
    DataFile,
    /// The model cannot be evaluated at the given state.
    Evaluation,
    /// A run warned, and `--strict` makes warnings errors.
    Warnings,
    /// A singular or indefinite mass matrix.
    SingularMassMatrix,
    /// NaN or ∞.
    NonFinite,
    /// The step size fell below the minimum.
    StepSizeUnderflow,
    /// The step limit.
    MaxSteps,
    /// An event that could not be located.
    EventNotLocated,
    /// A table read outside its range.
    TableOutOfRange,
    /// No static equilibrium.
    NoEquilibrium,
    /// An input without a value.
    Component,
    /// Every run of a sweep failed.
    EveryRunFailed,
    /// The fit failed.
    FitFailed,
    /// Stopped by a signal.
    Interrupted,
}

impl ExitStatus {
    /// Every status, in the order of their numbers.
    pub const ALL: [ExitStatus; 21] = [
        ExitStatus::Success,
        ExitStatus::Io,
        ExitStatus::Usage,
        ExitStatus::Spec,
        ExitStatus::Scenario,
        ExitStatus::AuditDisagrees,
        ExitStatus::Stale,
        ExitStatus::DataFile,
        ExitStatus::Evaluation,
        ExitStatus::Warnings,
        ExitStatus::SingularMassMatrix,
        ExitStatus::NonFinite,
        ExitStatus::StepSizeUnderflow,
        ExitStatus::MaxSteps,
        ExitStatus::EventNotLocated,
        ExitStatus::TableOutOfRange,
        ExitStatus::NoEquilibrium,
        ExitStatus::Component,
        ExitStatus::EveryRunFailed,
        ExitStatus::FitFailed,
        ExitStatus::Interrupted,
    ];

    /// The number the process exits with.
    pub const fn code(self) -> u8 {
        match self {
            ExitStatus::Success => 0,
            ExitStatus::Io => 1,
            ExitStatus::Usage => 2,
            ExitStatus::Spec => 3,
            ExitStatus::Scenario => 4,
            ExitStatus::AuditDisagrees => 5,
            ExitStatus::Stale => 6,
            ExitStatus::DataFile => 7,
            ExitStatus::Evaluation => 8,
            ExitStatus::Warnings => 9,
            ExitStatus::SingularMassMatrix => 10,
            ExitStatus::NonFinite => 11,
            ExitStatus::StepSizeUnderflow => 12,
            ExitStatus::MaxSteps => 13,
            ExitStatus::EventNotLocated => 14,
            ExitStatus::TableOutOfRange => 15,
            ExitStatus::NoEquilibrium => 16,
            ExitStatus::Component => 17,
            ExitStatus::EveryRunFailed => 18,
            ExitStatus::FitFailed => 19,
            // 128 + SIGINT, as shells report it.
            ExitStatus::Interrupted => 130,
        }
    }

    /// What the status means, as the help text and the book say it.
    pub const fn meaning(self) -> &'static str {
        match self {
            ExitStatus::Success => "success",
            ExitStatus::Io => "a file cannot be read or written",
            ExitStatus::Usage => "bad command line",
            ExitStatus::Spec => "the spec does not compile",
            ExitStatus::Scenario => "the scenario does not fit the spec (unknown key, bad value)",
            ExitStatus::AuditDisagrees => "the audit found equations that disagree",
            ExitStatus::Stale => "generated files are stale (generate --check)",
            ExitStatus::DataFile => "a data file (CSV) is missing columns, non-numeric or unsorted",
            ExitStatus::Evaluation => {
                "the model cannot be evaluated at the given state (eval, linearize)"
            }
            ExitStatus::Warnings => "a run or pulse warned and --strict makes warnings errors",
            ExitStatus::SingularMassMatrix => {
                "the mass matrix is singular or not positive definite"
            }
            ExitStatus::NonFinite => "a NaN or infinite value (M, f, acceleration, power, event)",
            ExitStatus::StepSizeUnderflow => "the step size fell below the minimum",
            ExitStatus::MaxSteps => "the step limit was reached",
            ExitStatus::EventNotLocated => "an event could not be located",
            ExitStatus::TableOutOfRange => "a table was read outside its range (policy `error`)",
            ExitStatus::NoEquilibrium => "no static equilibrium before the impact",
            ExitStatus::Component => "a component could not give a value (an unbound input)",
            ExitStatus::EveryRunFailed => "every run of a sweep failed",
            ExitStatus::FitFailed => "the fit failed",
            ExitStatus::Interrupted => {
                "a sweep stopped by Ctrl-C or a signal (--resume continues it)"
            }
        }
    }

    /// The table `lpm --help` ends with.
    pub fn help() -> String {
        let mut text = String::from("Exit status:\n");
        for status in ExitStatus::ALL {
            text.push_str(&format!("{:>4}  {}\n", status.code(), status.meaning()));
        }
        text.push_str(
            "\nA failure prints one line on stderr; -v adds the details (the state it\nhappened at, with coordinate names).",
        );
        text
    }
}

impl From<FailureKind> for ExitStatus {
    fn from(kind: FailureKind) -> ExitStatus {
        match kind {
            FailureKind::Scenario => ExitStatus::Scenario,
            FailureKind::SingularMassMatrix => ExitStatus::SingularMassMatrix,
            FailureKind::NonFinite => ExitStatus::NonFinite,
            FailureKind::StepSizeUnderflow => ExitStatus::StepSizeUnderflow,
            FailureKind::MaxSteps => ExitStatus::MaxSteps,
            FailureKind::EventNotLocated => ExitStatus::EventNotLocated,
            FailureKind::TableOutOfRange => ExitStatus::TableOutOfRange,
            FailureKind::NoEquilibrium => ExitStatus::NoEquilibrium,
            FailureKind::Component => ExitStatus::Component,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The book's table of exit statuses, `| code | meaning |` rows.
    fn readme_table() -> Vec<(u8, String)> {
        let readme = include_str!("../../docs/book/reference/errors.md");
        let start = readme
            .find("| exit status | meaning |")
            .expect("the book has a table of exit statuses");
        readme[start..]
            .lines()
            .skip(2)
            .take_while(|line| line.starts_with('|'))
            .map(|line| {
                let cells: Vec<&str> = line.trim_matches('|').split('|').map(str::trim).collect();
                (cells[0].parse().unwrap(), cells[1].to_string())
            })
            .collect()
    }

    #[test]
    fn the_book_lists_every_exit_status_as_the_help_does() {
        let ours: Vec<(u8, String)> = ExitStatus::ALL
            .iter()
            .map(|s| (s.code(), s.meaning().replace('|', "\\|")))
            .collect();
        assert_eq!(readme_table(), ours);
    }

    #[test]
    fn codes_are_distinct_and_in_order() {
        let codes: Vec<u8> = ExitStatus::ALL.iter().map(|s| s.code()).collect();
        assert!(codes.windows(2).all(|w| w[0] < w[1]), "{codes:?}");
    }
}
