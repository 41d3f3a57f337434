//! The exit statuses of `lpm`: its own, and one per failure kind of the
//! simulation library (`lagrangian_sim::failure`, which holds their codes
//! and meanings). Here, below every host, so that `lpm` and the Python
//! package (which names its exception classes after them) share one table
//! (`StudyError::status` gives a service error's).
//! `lpm --help` prints the table from [`ExitStatus::ALL`], and a test holds
//! the book's table, docs/book/reference/errors.md, to it.

use lagrangian_sim::simulate::FailureKind;

/// How `lpm` ended, as its exit status: its own statuses, and one per
/// [`FailureKind`] (whose codes and meanings sim's list holds).
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
    /// The audit found equations that disagree.
    AuditDisagrees,
    /// Generated files are stale.
    Stale,
    /// The model cannot be evaluated at the given state.
    Evaluation,
    /// A run warned, and `--strict` makes warnings errors.
    Warnings,
    /// Every run of a sweep failed.
    EveryRunFailed,
    /// The fit failed.
    FitFailed,
    /// Stopped by a signal.
    Interrupted,
    /// A run failed, or the scenario or a data file it needs does not fit.
    Failed(FailureKind),
}

/// The statuses that are not a [`FailureKind`], in the order of their numbers.
const OWN: [ExitStatus; 11] = [
    ExitStatus::Success,
    ExitStatus::Io,
    ExitStatus::Usage,
    ExitStatus::Spec,
    ExitStatus::AuditDisagrees,
    ExitStatus::Stale,
    ExitStatus::Evaluation,
    ExitStatus::Warnings,
    ExitStatus::EveryRunFailed,
    ExitStatus::FitFailed,
    ExitStatus::Interrupted,
];

/// [`OWN`] and the failure kinds, merged in the order of their numbers.
const fn every_status() -> [ExitStatus; OWN.len() + FailureKind::ALL.len()] {
    let kinds = FailureKind::ALL;
    let mut all = [ExitStatus::Success; OWN.len() + FailureKind::ALL.len()];
    let (mut own, mut kind, mut k) = (0, 0, 0);
    while k < all.len() {
        let take_own =
            kind == kinds.len() || (own < OWN.len() && OWN[own].code() < kinds[kind].code());
        if take_own {
            all[k] = OWN[own];
            own += 1;
        } else {
            all[k] = ExitStatus::Failed(kinds[kind]);
            kind += 1;
        }
        k += 1;
    }
    all
}

impl ExitStatus {
    /// Every status, in the order of their numbers.
    pub const ALL: [ExitStatus; OWN.len() + FailureKind::ALL.len()] = every_status();

    /// The number the process exits with.
    pub const fn code(self) -> u8 {
        match self {
            ExitStatus::Success => 0,
            ExitStatus::Io => 1,
            ExitStatus::Usage => 2,
            ExitStatus::Spec => 3,
            ExitStatus::AuditDisagrees => 5,
            ExitStatus::Stale => 6,
            ExitStatus::Evaluation => 8,
            ExitStatus::Warnings => 9,
            ExitStatus::EveryRunFailed => 18,
            ExitStatus::FitFailed => 19,
            // 128 + SIGINT, as shells report it.
            ExitStatus::Interrupted => 130,
            ExitStatus::Failed(kind) => kind.code(),
        }
    }

    /// What the status means, as the help text and the book say it.
    pub const fn meaning(self) -> &'static str {
        match self {
            ExitStatus::Success => "success",
            ExitStatus::Io => "a file cannot be read or written",
            ExitStatus::Usage => "bad command line",
            ExitStatus::Spec => "the spec does not compile",
            ExitStatus::AuditDisagrees => "the audit found equations that disagree",
            ExitStatus::Stale => "generated files are stale (generate --check)",
            ExitStatus::Evaluation => {
                "the model cannot be evaluated at the given state (eval, linearize)"
            }
            ExitStatus::Warnings => "a run or pulse warned and --strict makes warnings errors",
            ExitStatus::EveryRunFailed => "every run of a sweep failed",
            ExitStatus::FitFailed => "the fit failed",
            ExitStatus::Interrupted => {
                "a sweep stopped by Ctrl-C or a signal (--resume continues it)"
            }
            ExitStatus::Failed(kind) => kind.meaning(),
        }
    }

    /// The status's name in CamelCase (`Spec`, `MaxSteps`): the Python
    /// package names its exception classes after it.
    pub fn name(self) -> String {
        match self {
            ExitStatus::Failed(kind) => format!("{kind:?}"),
            own => format!("{own:?}"),
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
        ExitStatus::Failed(kind)
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

    #[test]
    fn every_failure_kind_is_one_status_and_no_own_status_is_a_kind() {
        for &kind in FailureKind::ALL {
            let statuses = ExitStatus::ALL.iter().filter(|s| s.code() == kind.code());
            assert_eq!(statuses.collect::<Vec<_>>(), [&ExitStatus::Failed(kind)]);
        }
        for status in OWN {
            assert!(
                FailureKind::ALL.iter().all(|k| k.code() != status.code()),
                "{status:?}"
            );
        }
    }

    #[test]
    fn names_are_the_camel_case_of_each_status() {
        let names: Vec<String> = ExitStatus::ALL.iter().map(|s| s.name()).collect();
        assert_eq!(names[..5], ["Success", "Io", "Usage", "Spec", "Scenario"]);
        assert!(names.contains(&"NoEquilibrium".to_string()));
        assert!(
            names.iter().all(|n| n.chars().all(char::is_alphanumeric)),
            "{names:?}"
        );
    }
}
