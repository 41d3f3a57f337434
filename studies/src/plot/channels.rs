//! The panels of the scenario's channels: one per role that has channels,
//! titled by the role, each channel in the legend with its unit; in the
//! units crash plots use: accelerations in `g`, as the summary gives their
//! peaks, raw and filtered at the channel's SAE J211 class; forces in `N`
//! drawn in `kN`.

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
    let shown = |c: &Channel| match accelerations {
        true => (Some("g".to_string()), 1.0 / g),
        false => drawn_in(c.signal.unit.as_deref()),
    };
    let unit = |c: &Channel| shown(c).0;
    let mut lines = Vec::new();
    for (i, channel) in channels.iter().enumerate() {
        let scale = shown(channel).1;
        let values: Vec<f64> = (result.samples.iter())
            .map(|x| scale * channel.signal.value(&x.columns()))
            .collect();
        let name = with_unit(&channel.signal.name, unit(channel).as_deref());
        match accelerations {
            true => lines.extend(filtered_lines(&name, &t, &values, i, channel.cfc)),
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

/// The unit a channel in `unit` is drawn in, and the factor to it: a force
/// in `N` in `kN`, as crash plots show them; others as they are.
fn drawn_in(unit: Option<&str>) -> (Option<String>, f64) {
    match unit {
        Some("N") => (Some("kN".into()), 1e-3),
        unit => (unit.map(str::to_string), 1.0),
    }
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
/// filtered at SAE J211 class `cfc` over it, both in color `color`; the raw
/// line alone when the record cannot be filtered (too few samples, sampled
/// too slowly).
pub(super) fn filtered_lines(
    name: &str,
    t: &[f64],
    values: &[f64],
    color: usize,
    cfc: f64,
) -> Vec<Line> {
    let raw = Line::new(format!("{name}, raw"), points(t, values), color, Style::Raw);
    match filtered(t, values, cfc) {
        Some(filtered) => vec![
            raw,
            Line::solid(format!("{name}, CFC {cfc}"), points(t, &filtered), color),
        ],
        None => vec![raw],
    }
}

/// `values` over times `t` \[s\] filtered to class `cfc`, at the times `t`:
/// filtered on an even grid of the smallest period (events add samples
/// between the output times), then interpolated back.
pub(super) fn filtered(t: &[f64], values: &[f64], cfc: f64) -> Option<Vec<f64>> {
    let pulse = Pulse::resampled(t, values, 0.0, None).ok()?;
    let dt = pulse.t[1] - pulse.t[0];
    let filtered = cfc_filter(&pulse.acceleration, dt, cfc).ok()?;
    Some(interpolate(&pulse.t, &filtered, t))
}
