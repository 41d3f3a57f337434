//! The panels of the scenario's channels: one per role that has channels,
//! titled by the role, each channel in the legend with its unit;
//! accelerations in `g`, as the summary gives their peaks, raw and with
//! their SAE J211 CFC 60 line.

use super::panels::{ms, with_unit};
use super::{Line, Panel, Style};
use lagrangian_sim::pulse::{Pulse, cfc_filter, interpolate};
use lagrangian_sim::scenario::{Channel, Role};
use lagrangian_sim::simulate::SimulationResult;

/// One panel per role of [`Role::ALL`] that has channels, in that order.
pub(super) fn channel_panels(
    result: &SimulationResult,
    channels: &[Channel],
    g: f64,
) -> Vec<Panel> {
    Role::ALL
        .iter()
        .filter_map(|&role| {
            let of_role: Vec<&Channel> = channels.iter().filter(|c| c.role == role).collect();
            (!of_role.is_empty()).then(|| role_panel(result, role, &of_role, g))
        })
        .collect()
}

/// The panel of `channels`, all of `role`.
fn role_panel(result: &SimulationResult, role: Role, channels: &[&Channel], g: f64) -> Panel {
    let t: Vec<f64> = result.samples.iter().map(|x| x.t).collect();
    let accelerations = role == Role::Acceleration;
    let scale = if accelerations { 1.0 / g } else { 1.0 };
    let unit = |c: &Channel| match accelerations {
        true => Some("g".to_string()),
        false => c.signal.unit.clone(),
    };
    let mut lines = Vec::new();
    for (i, channel) in channels.iter().enumerate() {
        let values: Vec<f64> = (result.samples.iter())
            .map(|x| scale * channel.signal.value(&x.columns()))
            .collect();
        let name = with_unit(&channel.signal.name, unit(channel).as_deref());
        match accelerations {
            true => lines.extend(filtered_lines(&name, &t, &values, i)),
            false => lines.push(Line::solid(name, points(&t, &values), i)),
        }
    }
    let first = channels.first().and_then(|c| unit(c));
    let common = channels.iter().all(|c| unit(c) == first);
    let title = capitalized(role.name());
    Panel::time(
        &title,
        &with_unit(role.name(), first.as_deref().filter(|_| common)),
        lines,
    )
}

/// `Displacement` for `displacement`.
fn capitalized(name: &str) -> String {
    let mut chars = name.chars();
    chars.next().map_or(String::new(), |first| {
        first.to_uppercase().chain(chars).collect()
    })
}

/// `(t [ms], value)` pairs.
fn points(t: &[f64], values: &[f64]) -> Vec<(f64, f64)> {
    t.iter().zip(values).map(|(&t, &v)| (ms(t), v)).collect()
}

/// An acceleration `values` over times `t` \[s\], raw (thin and light) and
/// CFC 60 filtered over it, both in color `color`; the raw line alone when
/// the record cannot be filtered (too few samples, sampled too slowly).
pub(super) fn filtered_lines(name: &str, t: &[f64], values: &[f64], color: usize) -> Vec<Line> {
    let raw = Line::new(format!("{name}, raw"), points(t, values), color, Style::Raw);
    match cfc60(t, values) {
        Some(filtered) => vec![
            raw,
            Line::solid(format!("{name}, CFC 60"), points(t, &filtered), color),
        ],
        None => vec![raw],
    }
}

/// `values` over times `t` \[s\] filtered to SAE J211 CFC 60, at the times
/// `t`: filtered on an even grid of the smallest period (events add
/// samples between the output times), then interpolated back.
pub(super) fn cfc60(t: &[f64], values: &[f64]) -> Option<Vec<f64>> {
    let pulse = Pulse::resampled(t, values, 0.0, None).ok()?;
    let dt = pulse.t[1] - pulse.t[0];
    let filtered = cfc_filter(&pulse.acceleration, dt, 60.0).ok()?;
    Some(interpolate(&pulse.t, &filtered, t))
}
