//! What a run's output samples must evaluate: only what the summary, the
//! scenario's channels or the kept samples read.
//!
//! A sample always has its motion (`q`, `q̇` interpolated from the dense
//! output), and the rest of its state where something reads it; the
//! model's other quantities cost an evaluation each and are computed only
//! when something reads them — the energies only for a kept sample (the
//! summary's energy balance takes them at the ends of the steps).

use crate::ode::Part;
use crate::scenario::{Column, Scenario};

/// The quantities the samples of one run evaluate beyond the state.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct Needs {
    /// `q̈` (with the constraints' `λ` and `g`): read by the crush
    /// channel's deceleration, a channel of accelerations, outputs,
    /// multipliers or residuals, the constraints' drift, or kept samples.
    pub accelerations: bool,
    /// The model's outputs: read by a channel or the crush channel, or
    /// kept.
    pub outputs: bool,
    /// The outputs' rates and accelerations along the motion: read by a
    /// crush channel of outputs.
    pub output_motion: bool,
    /// The components' columns: read by a channel, or kept.
    pub components: bool,
    /// The samples are kept: everything is evaluated, the energies and the
    /// values of the input calls too.
    pub kept: bool,
}

impl Needs {
    /// What the samples of `scenario` must evaluate for a model with
    /// `constraints` constraints; everything when the samples are `kept`.
    pub(crate) fn of(scenario: &Scenario, kept: bool, constraints: usize) -> Needs {
        let read = |wanted: fn(Column) -> bool| {
            (scenario.channels.iter())
                .flat_map(|channel| &channel.signal.terms)
                .any(|&(_, column)| wanted(column))
        };
        let output_motion = (scenario.crush.as_ref()).is_some_and(|c| c.outputs().next().is_some());
        let outputs = kept || output_motion || read(|c| matches!(c, Column::Output(_)));
        Needs {
            accelerations: kept
                || outputs
                || scenario.crush.is_some()
                || constraints > 0
                || read(reads_accelerations),
            outputs,
            output_motion,
            components: kept || read(|c| matches!(c, Column::Component(_))),
            kept,
        }
    }

    /// The part of the state a sample reads, given whether its `q̈` was
    /// interpolated: the motion alone, unless it solves `M q̈ = f`, or
    /// evaluates the outputs, the components' columns or everything a kept
    /// sample has (which read the components' internal states, or the
    /// work integrals).
    pub(crate) fn state(&self, interpolated: bool) -> Part {
        let solves = self.accelerations && !interpolated;
        match solves || self.outputs || self.components || self.kept {
            true => Part::All,
            false => Part::Motion,
        }
    }
}

/// Whether a channel of `column` reads the solution of `M q̈ = f`.
fn reads_accelerations(column: Column) -> bool {
    match column {
        Column::Acceleration(_) | Column::Multiplier(_) | Column::Residual(_) => true,
        Column::Output(_) => true,
        Column::Coordinate(_) | Column::Velocity(_) | Column::Component(_) => false,
    }
}
