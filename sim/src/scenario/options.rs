//! The run options a scenario chooses that the run engine reads:
//! `[simulation] time_kinks` and `accelerations`, and the default of
//! `[constraints] alpha` and `beta`. They live here, below the run engine,
//! so that the scenario never reaches up into it; `simulate` re-exports them.

use super::Choice;
use lagrangian_runtime::constrained::Baumgarte;

/// What the stages of a step see of a kink of an input of time inside it
/// (`[simulation] time_kinks` of a scenario).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum TimeKinks {
    /// The input's smooth stand-in over the step.
    #[default]
    Smoothed,
    /// The input as it is.
    Exact,
}

impl Choice for TimeKinks {
    const ALL: &'static [TimeKinks] = &[TimeKinks::Smoothed, TimeKinks::Exact];

    fn name(self) -> &'static str {
        match self {
            TimeKinks::Smoothed => "smoothed",
            TimeKinks::Exact => "exact",
        }
    }
}

/// How the output samples get their accelerations `q̈` (`[simulation]
/// accelerations` of a scenario).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum SampleAccelerations {
    /// From the derivative of the step's dense output where that is
    /// accurate (see the module documentation), else solved.
    #[default]
    Interpolated,
    /// Solved at every sample: `M q̈ = f`.
    Exact,
}

impl Choice for SampleAccelerations {
    const ALL: &'static [SampleAccelerations] = &[
        SampleAccelerations::Interpolated,
        SampleAccelerations::Exact,
    ];

    fn name(self) -> &'static str {
        match self {
            SampleAccelerations::Interpolated => "interpolated",
            SampleAccelerations::Exact => "exact",
        }
    }
}

/// The scenario's default `α` and `β` [1/s]: the residual decays within a
/// few tenths of a second, and the rates stay far below the integrators'
/// stability limits at the steps the models' own dynamics take.
pub const DEFAULT_STABILIZATION: Baumgarte = Baumgarte {
    alpha: 10.0,
    beta: 10.0,
};
