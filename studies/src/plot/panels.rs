//! What the panels of a run show, in reading order: the crush channel's
//! panels ([`super::crush`]), the channels' ([`super::channels`]), pitch,
//! energies and the crush force–deflection loop.

use super::{Line, Panel, PlotSetup, channels, crush};
use lagrangian_sim::simulate::{Sample, SimulationResult};

/// Seconds to milliseconds, the time axis of the panels.
pub(super) fn ms(t: f64) -> f64 {
    t * 1e3
}

/// `quantity [unit]`, or the quantity alone without a unit.
pub(super) fn with_unit(quantity: &str, unit: Option<&str>) -> String {
    match unit {
        Some(unit) => format!("{quantity} [{unit}]"),
        None => quantity.to_string(),
    }
}

/// The panels of a run, in reading order: the crush channel's panels, one
/// panel per role of the channels (the raw coordinates and velocities when
/// the scenario names neither a crush channel nor channels), pitch,
/// energies, and the crush force–deflection loop.
pub(super) fn panels_of(result: &SimulationResult, setup: &PlotSetup) -> Vec<Panel> {
    let mut panels = match &setup.crush {
        Some(signal) => crush::crush_panels(result, signal, setup.g),
        None => Vec::new(),
    };
    panels.extend(channels::channel_panels(result, &setup.channels, setup.g));
    if panels.is_empty() {
        panels = coordinate_panels(result);
    }
    if !setup.pitch.is_empty() {
        panels.push(pitch_panel(result, &setup.pitch));
    }
    panels.push(energy_panel(result));
    if !setup.force_deflection.is_empty() {
        panels.push(force_deflection_panel(
            &result.samples,
            &setup.force_deflection,
        ));
    }
    panels
}

/// Each crush element's force against its own deflection, from the
/// samples' component columns.
pub(super) fn force_deflection_panel(
    samples: &[Sample],
    elements: &[(String, usize, usize)],
) -> Panel {
    let lines = (elements.iter().enumerate())
        .map(|(i, (name, force, deflection))| {
            let points = samples
                .iter()
                .map(|x| (x.components[*deflection], 1e-3 * x.components[*force]));
            Line::solid(name.clone(), points.collect(), i)
        })
        .collect();
    Panel {
        title: "Crush force against crush".into(),
        x_label: "deflection [m]".into(),
        y_label: "force [kN]".into(),
        lines,
    }
}

/// Every coordinate and every velocity, for a run that names no channel.
fn coordinate_panels(result: &SimulationResult) -> Vec<Panel> {
    let s = &result.samples;
    let line = |k: usize, name: String, value: &dyn Fn(&Sample) -> f64| {
        Line::solid(name, s.iter().map(|x| (ms(x.t), value(x))).collect(), k)
    };
    let names = result.coordinates.iter().enumerate();
    let coordinates = (names.clone())
        .map(|(k, name)| line(k, name.clone(), &|x| x.q[k]))
        .collect();
    let velocities = names
        .map(|(k, name)| line(k, format!("d{name}/dt"), &|x| x.v[k]))
        .collect();
    vec![
        Panel::time("Coordinates", "q", coordinates),
        Panel::time("Velocities", "dq/dt", velocities),
    ]
}

/// The pitch coordinates in degrees, relative to their initial values.
fn pitch_panel(result: &SimulationResult, pitch: &[usize]) -> Panel {
    let lines = (pitch.iter().enumerate())
        .map(|(i, &k)| {
            let q0 = result.initial_q[k];
            let points = (result.samples.iter())
                .map(|x| (ms(x.t), (x.q[k] - q0).to_degrees()))
                .collect();
            Line::solid(result.coordinates[k].clone(), points, i)
        })
        .collect();
    Panel::time("Pitch from static equilibrium", "angle [°]", lines)
}

/// The energy bookkeeping [kJ]: kinetic, potential from its start,
/// dissipated, and absorbed by the inputs.
fn energy_panel(result: &SimulationResult) -> Panel {
    let s = &result.samples;
    let first = s.first().map_or(0.0, |x| x.potential);
    let kj = 1e-3;
    let line = |color: usize, name: &str, value: &dyn Fn(&Sample) -> f64| {
        let points = s.iter().map(|x| (ms(x.t), kj * value(x))).collect();
        Line::solid(name, points, color)
    };
    Panel::time(
        "Energy",
        "energy [kJ]",
        vec![
            line(0, "kinetic", &|x| x.kinetic),
            line(1, "potential − V(0)", &|x| x.potential - first),
            line(2, "dissipated by D", &|x| x.dissipated),
            line(3, "absorbed by inputs", &|x| -x.external_work),
        ],
    )
}
