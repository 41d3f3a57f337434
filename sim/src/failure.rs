//! The one list of the ways a run, or the scenario it needs, fails: each
//! [`FailureKind`] has its snake-case name (a sweep's `status` column), the
//! exit status `lpm` gives it, and what that status means (`lpm --help` and
//! the book's table of exit statuses).
//!
//! A new kind is one line of `failure_kinds!` below; `lpm`'s exit statuses
//! and a sweep's rows take it from there.

use crate::fault::Fault;

/// Defines [`FailureKind`] with one variant per entry, and its
/// [`FailureKind::ALL`], [`FailureKind::name`], [`FailureKind::code`] and
/// [`FailureKind::meaning`] from the same entries.
macro_rules! failure_kinds {
    ($($(#[doc = $doc:literal])* $kind:ident = $code:literal, $name:literal, $meaning:literal;)*) => {
        /// What kind of failure ended a run, or kept it from starting: one
        /// exit status of `lpm` each.
        #[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
        pub enum FailureKind {
            $($(#[doc = $doc])* $kind,)*
        }

        impl FailureKind {
            /// Every kind, in the order of their exit codes.
            pub const ALL: &'static [FailureKind] = &[$(FailureKind::$kind,)*];

            /// The kind in snake case, as a sweep's `status` column writes it.
            pub const fn name(self) -> &'static str {
                match self {
                    $(FailureKind::$kind => $name,)*
                }
            }

            /// The exit status `lpm` ends with for this kind.
            pub const fn code(self) -> u8 {
                match self {
                    $(FailureKind::$kind => $code,)*
                }
            }

            /// What the exit status means, as `lpm --help` and the book say it.
            pub const fn meaning(self) -> &'static str {
                match self {
                    $(FailureKind::$kind => $meaning,)*
                }
            }
        }
    };
}

failure_kinds! {
    /// A scenario value that does not apply (unknown key or parameter, a bad
    /// value or option).
    Scenario = 4, "scenario", "the scenario does not fit the spec (unknown key, bad value)";
    /// A data file the scenario names (a CSV table) cannot be used.
    DataFile = 7, "data_file", "a data file (CSV) is missing columns, non-numeric or unsorted";
    /// `M(q)` singular or not positive definite.
    SingularMassMatrix = 10, "singular_mass_matrix", "the mass matrix is singular or not positive definite";
    /// NaN or ±∞ in `M`, `f`, `q̈`, a power or an event function.
    NonFinite = 11, "non_finite", "a NaN or infinite value (M, f, acceleration, power, event)";
    /// Steps rejected (or Newton failing) below the minimum step size.
    StepSizeUnderflow = 12, "step_size_underflow", "the step size fell below the minimum";
    /// The step limit was reached before the end time.
    MaxSteps = 13, "max_steps", "the step limit was reached";
    /// An event's zero crossing could not be bracketed.
    EventNotLocated = 14, "event_not_located", "an event could not be located";
    /// A table read outside its range under the `error` policy.
    TableOutOfRange = 15, "table_out_of_range", "a table was read outside its range (policy `error`)";
    /// No static equilibrium before the impact.
    NoEquilibrium = 16, "no_equilibrium", "no static equilibrium before the impact";
    /// A component could not produce a value (an unbound input).
    Component = 17, "component", "a component could not give a value (an unbound input)";
}

impl FailureKind {
    /// The kind whose [`FailureKind::name`] is `name` (a sweep table's
    /// `status` cell read back).
    pub fn from_name(name: &str) -> Option<FailureKind> {
        FailureKind::ALL
            .iter()
            .copied()
            .find(|kind| kind.name() == name)
    }

    /// The kind of a failed evaluation of the model.
    pub fn of_fault(fault: &Fault) -> FailureKind {
        match fault {
            Fault::SingularMassMatrix { .. } | Fault::RedundantConstraints { .. } => {
                FailureKind::SingularMassMatrix
            }
            Fault::NonFinite { .. } => FailureKind::NonFinite,
            Fault::OutOfRange { .. } => FailureKind::TableOutOfRange,
            Fault::Component(_) => FailureKind::Component,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::collections::HashSet;

    #[test]
    fn every_kind_has_its_own_code_and_name() {
        let codes: HashSet<u8> = FailureKind::ALL.iter().map(|k| k.code()).collect();
        let names: HashSet<&str> = FailureKind::ALL.iter().map(|k| k.name()).collect();
        assert_eq!(codes.len(), FailureKind::ALL.len());
        assert_eq!(names.len(), FailureKind::ALL.len());
    }

    #[test]
    fn all_is_in_the_order_of_the_codes() {
        let codes: Vec<u8> = FailureKind::ALL.iter().map(|k| k.code()).collect();
        assert!(codes.windows(2).all(|w| w[0] < w[1]), "{codes:?}");
    }

    #[test]
    fn a_name_reads_back_as_its_kind() {
        for &kind in FailureKind::ALL {
            assert_eq!(FailureKind::from_name(kind.name()), Some(kind));
            let snake = kind.name();
            assert!(
                snake.chars().all(|c| c.is_ascii_lowercase() || c == '_'),
                "{snake}"
            );
        }
        assert_eq!(FailureKind::from_name("ok"), None);
        assert_eq!(FailureKind::from_name("MaxSteps"), None);
    }
}
