//! Checking a scenario file against its model and the value ranges of its
//! entries, and resolving names to indices.

use super::bind::bind_components;
use super::choice::parse_choice;
use super::file::{ClassChoice, File, InitialSection, MetricsSection};
use super::iso_mme::resolve_iso_mme;
use super::options::{SampleAccelerations, TimeKinks};
use super::{Channel, Column, ModelNames, Role, Scenario, Signal};
use crate::components::ComponentSection;
use crate::entry::{EntryError, KeyPath, finite, index_of, number, positive, unknown};
use crate::ode::{Method, Options};
use crate::pulse::cfc::{CLASS_BY_MEASUREMENT, DEFAULT_CLASS, STANDARD_CLASSES};
use crate::table::Table;
use lagrangian_runtime::names::closest;
use std::collections::BTreeMap;
use std::path::Path;
use std::sync::Arc;

/// The most output samples a run may ask for (`t_end / output_interval`);
/// each keeps the whole state, so more would exhaust memory.
pub const MAX_SAMPLES: f64 = 1e6;

pub(super) fn resolve(
    file: File,
    base: &Path,
    names: &ModelNames,
    constants: BTreeMap<String, f64>,
    tables: &BTreeMap<String, Arc<Table>>,
) -> Result<Scenario, EntryError> {
    let s = &file.simulation;
    let (method, options) = solver_settings(s)?;
    let accelerations: SampleAccelerations =
        parse_choice("simulation.accelerations", &s.accelerations)?;
    let time_kinks: TimeKinks = parse_choice("simulation.time_kinks", &s.time_kinks)?;

    let parameters = parameter_overrides(&file.parameters, names)?;
    let coordinate = |key: &str, name: &str| index_of(key, "coordinate", name, &names.coordinates);
    // `initial.{section}`: values by coordinate name.
    let initial = |section: &str, values: &BTreeMap<String, f64>| {
        values
            .iter()
            .map(|(n, v)| {
                Ok((
                    coordinate(&format!("initial.{section}"), n)?,
                    initial_value(&format!("initial.{section}.{n}"), *v)?,
                ))
            })
            .collect::<Result<Vec<_>, EntryError>>()
    };
    let initial_coordinates = initial("coordinates", &file.initial.coordinates)?;
    let mut initial_velocities = initial("velocities", &file.initial.velocities)?;
    initial_velocities.extend(moving_with_the_vehicle(&file.initial, names)?);
    absolute_tolerance(s.atol, &initial_coordinates, &initial_velocities)?;
    let equilibrium = file
        .initial
        .equilibrium
        .iter()
        .map(|n| coordinate("initial.equilibrium", n))
        .collect::<Result<_, EntryError>>()?;
    let crush = (file.metrics.crush.as_deref())
        .map(|text| crush_channel(text, names))
        .transpose()?;
    let pitch = file
        .metrics
        .pitch
        .iter()
        .map(|n| coordinate("metrics.pitch", n))
        .collect::<Result<_, EntryError>>()?;
    if let Some(weld) = &file.metrics.weld {
        check_weld_metric(weld, &file.components)?;
    }
    for name in &file.metrics.contact {
        check_contact_metric(name, &file.components)?;
    }
    // The overrides checked that each names an input.
    let constants = (constants.into_iter())
        .filter_map(|(n, v)| Some((names.inputs.iter().position(|i| *i == n)?, v)))
        .collect();
    let inputs = bind_components(&file.components, tables, names, constants)?;
    let with_components = names.with_components(&inputs);
    let channels = channels(&file.metrics, &with_components)?;
    let iso_mme = resolve_iso_mme(
        &file.iso_mme,
        &file.metrics,
        &file.components,
        &with_components,
    )?;
    Ok(Scenario {
        file: None,
        spec: file.spec.as_ref().map(|s| base.join(s)),
        description: file.description,
        t_end: s.t_end,
        method,
        options,
        output_interval: s.output_interval,
        parameters,
        initial_coordinates,
        initial_velocities,
        equilibrium,
        crush,
        channels,
        pitch,
        weld: file.metrics.weld.clone(),
        contact: file.metrics.contact.clone(),
        inputs,
        stabilization: stabilization(&file.constraints)?,
        accelerations,
        time_kinks,
        iso_mme,
    })
}

/// `[constraints] alpha`, `beta`: finite and not negative.
fn stabilization(
    section: &super::file::ConstraintsSection,
) -> Result<lagrangian_runtime::constrained::Baumgarte, EntryError> {
    for (name, value) in [("alpha", section.alpha), ("beta", section.beta)] {
        if !(value.is_finite() && value >= 0.0) {
            return Err(EntryError::sentence(
                KeyPath::new("constraints").join(name),
                format!("must be finite and not negative (a rate in 1/s), not {value}"),
            ));
        }
    }
    Ok(lagrangian_runtime::constrained::Baumgarte {
        alpha: section.alpha,
        beta: section.beta,
    })
}

/// `-name` as `(−1, name)`, `name` or `+name` as `(1, name)`.
fn signed(text: &str) -> (f64, &str) {
    match text.trim().strip_prefix('-') {
        Some(rest) => (-1.0, rest.trim()),
        None => (1.0, text.trim().trim_start_matches('+').trim()),
    }
}

/// The largest magnitude of an initial coordinate or velocity, in its own
/// unit. No mechanical state is meant beyond it (10⁹ m is 2.6 times the
/// distance to the Moon, 10⁹ m/s three times the speed of light, 10⁹ rad
/// 1.6 × 10⁸ turns), and a run from there cannot resolve its motion: the
/// spacing of the numbers there swamps it. Measured on
/// `four_bar_linkage` with θ1 set: energy-balance error 3e-9 at 10⁶ rad,
/// 5e-6 at 10⁹, the step limit at 10¹², errors above 10 from 10¹⁵ on, and
/// no end at 1.7 × 10³⁰⁸.
pub const MAX_INITIAL_MAGNITUDE: f64 = 1e9;

/// An initial coordinate or velocity: finite and at most
/// [`MAX_INITIAL_MAGNITUDE`] in size; else an error naming `key`.
pub(crate) fn initial_value(key: &str, value: f64) -> Result<f64, EntryError> {
    let value = finite(key, value)?;
    if value.abs() <= MAX_INITIAL_MAGNITUDE {
        return Ok(value);
    }
    Err(EntryError::value(
        key.into(),
        number(value),
        format!(
            "beyond ±{MAX_INITIAL_MAGNITUDE:e} (in the coordinate's unit), where no run resolves the motion of a mechanical model (numbers there are {:.1e} apart)",
            spacing(value)
        ),
    ))
}

/// The distance from `x` to the next larger number in magnitude.
fn spacing(x: f64) -> f64 {
    let x = x.abs();
    f64::from_bits(x.to_bits() + 1) - x
}

/// The velocities `initial.speed` gives the coordinates of `initial.moving`
/// (`±speed` by the sign written before each); a coordinate given a
/// velocity both ways, a speed without coordinates or coordinates without
/// a speed is an error.
fn moving_with_the_vehicle(
    initial: &InitialSection,
    names: &ModelNames,
) -> Result<Vec<(usize, f64)>, EntryError> {
    let speed = match (initial.speed, initial.moving.is_empty()) {
        (None, true) => return Ok(Vec::new()),
        (Some(speed), false) => initial_value("initial.speed", speed)?,
        (Some(speed), true) => {
            return Err(EntryError::value(
                KeyPath::new("initial.speed"),
                number(speed),
                format!(
                    "name the coordinates that move with the vehicle in initial.moving (e.g. moving = [\"-{}\"] when the crush coordinate decreases)",
                    names.coordinates.first().map_or("x", String::as_str)
                ),
            ));
        }
        (None, false) => {
            return Err(EntryError::sentence(
                KeyPath::new("initial.moving"),
                "names coordinates but initial.speed gives them no speed",
            ));
        }
    };
    let mut velocities = Vec::new();
    for entry in &initial.moving {
        let (sign, name) = signed(entry);
        let moving = KeyPath::new("initial.moving");
        let k = index_of(&moving, "coordinate", name, &names.coordinates)?;
        if initial.velocities.contains_key(name) {
            return Err(EntryError::sentence(
                KeyPath::new("initial.velocities").join(name),
                format!("and initial.moving both set the velocity of `{name}`; keep one"),
            ));
        }
        if velocities.iter().any(|&(i, _)| i == k) {
            return Err(EntryError::sentence(
                moving,
                format!("names `{name}` twice"),
            ));
        }
        velocities.push((k, sign * speed));
    }
    Ok(velocities)
}

/// `metrics.crush`: a combination of coordinates and of outputs of the
/// position (functions of the coordinates and time), with an offset or not
/// (`"y + 0.977"`, `"intrusion"`), so that its rate and acceleration follow
/// from the motion: exactly for coordinates, by differences along the
/// motion for outputs (`simulate::output_motion`).
fn crush_channel(text: &str, names: &ModelNames) -> Result<Signal, EntryError> {
    let signal = Signal::parse("metrics.crush", text, names)?;
    let bad = |why: String| EntryError::text(KeyPath::new("metrics.crush"), text, why);
    for &(_, column) in &signal.terms {
        match column {
            Column::Coordinate(_) => {}
            Column::Output(k) => output_of_position(k, names).map_err(bad)?,
            _ => return Err(bad(NOT_OF_POSITION.to_string())),
        }
    }
    Ok(signal)
}

/// Why a column that is neither a coordinate nor an output cannot be the
/// crush channel.
const NOT_OF_POSITION: &str = "the crush channel is a combination of coordinates and outputs of the position (e.g. \"-r\", \"xa - xb\", \"y + 0.977\" or an output \"intrusion\"), so that its rate and acceleration follow from the motion; list other columns under metrics.displacement";

/// `Ok` when output `k` is a function of the coordinates and time alone,
/// else why it cannot be a crush channel.
fn output_of_position(k: usize, names: &ModelNames) -> Result<(), String> {
    let name = &names.outputs[k];
    let Some(reads) = names.output_reads.get(k).copied().flatten() else {
        return Err(format!(
            "the model does not say what output `{name}` reads (a model compiled without its tape), so it cannot be the crush channel; run the spec itself (`lpm simulate`), or write the crush as a combination of coordinates"
        ));
    };
    let mut what = Vec::new();
    if reads.velocities {
        what.push("velocities (dot)");
    }
    if reads.accelerations {
        what.push("accelerations (ddot)");
    }
    if reads.inputs {
        what.push("an input function");
    }
    match what.is_empty() {
        true => Ok(()),
        false => Err(format!(
            "output `{name}` reads {}, so its rate and acceleration along the motion are not those of a crush; the crush channel is a combination of coordinates and of outputs of the coordinates and time alone; list `{name}` under metrics.displacement",
            what.join(" and ")
        )),
    }
}

/// The channels of `metrics.displacement`, `velocity`, `acceleration` and
/// `force`; the pitch coordinates are displacement channels too (the
/// summary flags a pitch still growing at the end of the run), unless
/// listed.
fn channels(metrics: &MetricsSection, names: &ModelNames) -> Result<Vec<Channel>, EntryError> {
    let mut channels: Vec<Channel> = Vec::new();
    for pitch in &metrics.pitch {
        if !metrics.displacement.contains(pitch) {
            let signal = Signal::parse("metrics.pitch", pitch, names)?;
            channels.push(Channel {
                role: Role::Displacement,
                signal,
                cfc: DEFAULT_CLASS,
            });
        }
    }
    for role in Role::ALL {
        for text in metrics.channels(role) {
            let key = format!("metrics.{}", role.name());
            let signal = Signal::parse(&key, text, names)?;
            if channels.iter().any(|c| c.signal.name == signal.name) {
                return Err(EntryError::text(
                    key.into(),
                    text,
                    "the channel is listed twice",
                ));
            }
            let cfc = channel_class(metrics, role, text)?;
            channels.push(Channel { role, signal, cfc });
        }
    }
    if let Some(name) = (metrics.classes.keys()).find(|&k| !metrics.acceleration.contains(k)) {
        let key = KeyPath::new("metrics.classes").join_quoted(name);
        return Err(EntryError::at(
            key,
            format!(
                "not a channel of metrics.acceleration ({}); a filter class \
             is given to an acceleration channel, by its name as listed there",
                match metrics.acceleration.is_empty() {
                    true => "there is none".to_string(),
                    false => metrics
                        .acceleration
                        .iter()
                        .map(|c| format!("`{c}`"))
                        .collect::<Vec<_>>()
                        .join(", "),
                }
            ),
        ));
    }
    Ok(channels)
}

/// The filter class of channel `text` of `role`: its `metrics.classes`
/// entry (a J211 class, or what it measures), else [`DEFAULT_CLASS`].
fn channel_class(metrics: &MetricsSection, role: Role, text: &str) -> Result<f64, EntryError> {
    let key = KeyPath::new("metrics.classes").join_quoted(text);
    match metrics
        .classes
        .get(text)
        .filter(|_| role == Role::Acceleration)
    {
        None => Ok(DEFAULT_CLASS),
        Some(ClassChoice::Class(cfc)) if STANDARD_CLASSES.contains(cfc) => Ok(*cfc),
        Some(ClassChoice::Class(cfc)) => Err(EntryError::value(
            key,
            format!("{cfc}"),
            "not a filter class of SAE J211-1 (60, 180, 600 or 1000)",
        )),
        Some(ClassChoice::Measurement(what)) => (CLASS_BY_MEASUREMENT.iter())
            .find(|(name, _)| name == what)
            .map(|&(_, cfc)| cfc)
            .ok_or_else(|| {
                let known = CLASS_BY_MEASUREMENT.map(|(name, cfc)| format!("{name} ({cfc})"));
                EntryError::text(
                    key,
                    what,
                    format!(
                        "not a measurement J211-1 gives a class for; one of {}, or a class number",
                        known.join(", ")
                    ),
                )
            }),
    }
}

/// `metrics.contact` names crush components of the file.
fn check_contact_metric(
    name: &str,
    components: &BTreeMap<String, ComponentSection>,
) -> Result<(), EntryError> {
    let crush: Vec<&str> = (components.iter())
        .filter(|(_, c)| c.kind() == "crush")
        .map(|(n, _)| n.as_str())
        .collect();
    match components.get(name) {
        Some(c) if c.kind() == "crush" => Ok(()),
        Some(c) => Err(EntryError::text(
            KeyPath::new("metrics.contact"),
            name,
            format!(
                "component `{name}` is a {} component; metrics.contact names crush components ({})",
                c.kind(),
                match crush.is_empty() {
                    true => "the scenario has none".to_string(),
                    false => crush.join(", "),
                }
            ),
        )),
        None => Err(EntryError::text(
            KeyPath::new("metrics.contact"),
            name,
            unknown("crush component", name, crush.iter().copied())
                .replace("does not exist in the spec", "is not in the scenario"),
        )),
    }
}

/// `metrics.weld` must name a weld component of the file.
fn check_weld_metric(
    weld: &str,
    components: &BTreeMap<String, ComponentSection>,
) -> Result<(), EntryError> {
    let welds: Vec<&str> = components
        .iter()
        .filter(|(_, c)| matches!(c, ComponentSection::weld(_)))
        .map(|(name, _)| name.as_str())
        .collect();
    let allowed = if welds.is_empty() {
        "the scenario has none".to_string()
    } else {
        format!("weld components: {}", welds.join(", "))
    };
    match components.get(weld) {
        Some(ComponentSection::weld(_)) => Ok(()),
        Some(other) => Err(EntryError::text(
            KeyPath::new("metrics.weld"),
            weld,
            format!(
                "component `{weld}` is a {} component; metrics.weld names a weld component ({allowed})",
                other.kind()
            ),
        )),
        None => {
            let mut message = format!("the scenario has no component `{weld}`");
            match closest(weld, welds.iter().copied()) {
                Some(best) => message.push_str(&format!("; did you mean `{best}`?")),
                None => message.push_str(&format!(" ({allowed})")),
            }
            Err(EntryError::text(
                KeyPath::new("metrics.weld"),
                weld,
                message,
            ))
        }
    }
}

/// The loosest relative tolerance a run may have: beyond it the local
/// error control no longer makes a run accurate to any digit.
pub const LOOSEST_RTOL: f64 = 0.1;

/// The largest absolute tolerance against the state's scale (the largest
/// initial coordinate or velocity, or 1 for a state that starts smaller).
pub const ATOL_PER_SCALE: f64 = 1e-3;

/// `simulation.rtol` in (0, [`LOOSEST_RTOL`]].
fn relative_tolerance(rtol: f64) -> Result<f64, EntryError> {
    if rtol > 0.0 && rtol <= LOOSEST_RTOL {
        return Ok(rtol);
    }
    Err(EntryError::value(
        KeyPath::new("simulation.rtol"),
        number(rtol),
        format!(
            "must be in (0, {LOOSEST_RTOL}]: a looser relative tolerance gives no \
             accurate result (1e-6 to 1e-10 is usual)"
        ),
    ))
}

/// `simulation.atol` (already positive) small against the state's scale:
/// at most [`ATOL_PER_SCALE`] times the largest initial coordinate or
/// velocity (or 1). Above it the error control of the state's smaller
/// components is off.
fn absolute_tolerance(
    atol: f64,
    coordinates: &[(usize, f64)],
    velocities: &[(usize, f64)],
) -> Result<f64, EntryError> {
    let largest = coordinates
        .iter()
        .chain(velocities)
        .fold(0.0f64, |m, &(_, x)| m.max(x.abs()));
    let limit = ATOL_PER_SCALE * largest.max(1.0);
    if atol <= limit {
        return Ok(atol);
    }
    Err(EntryError::value(
        KeyPath::new("simulation.atol"),
        number(atol),
        format!(
            "must be small against the state's scale, at most {limit:.2e} \
             ({ATOL_PER_SCALE:e} × the largest initial coordinate or velocity, {}, or 1)",
            number(largest)
        ),
    ))
}

/// The method and solver options of `[simulation]`, each value checked
/// (positive step sizes and times, rtol in (0, [`LOOSEST_RTOL`]], atol
/// positive, at most [`MAX_SAMPLES`] output samples).
fn solver_settings(s: &super::file::SimulationSection) -> Result<(Method, Options), EntryError> {
    let method: Method = s.method.parse().map_err(|_| {
        let reason = format!("= `{}`; use {}", s.method, Method::NAMES.join(", "));
        EntryError::sentence(KeyPath::new("simulation.method"), reason)
    })?;
    positive("simulation.t_end", s.t_end)?;
    positive("simulation.output_interval", s.output_interval)?;
    let samples = s.t_end / s.output_interval;
    if samples > MAX_SAMPLES {
        return Err(EntryError::value(
            KeyPath::new("simulation.output_interval"),
            number(s.output_interval),
            format!(
                "gives {} samples over t_end = {} s, more than {MAX_SAMPLES:e}; use a longer interval",
                number(samples.round()),
                number(s.t_end)
            ),
        ));
    }
    relative_tolerance(s.rtol)?;
    positive("simulation.atol", s.atol)?;
    if let Some(h) = s.max_step {
        positive("simulation.max_step", h)?;
    }
    if let Some(h) = s.step {
        positive("simulation.step", h)?;
    }
    // The step of a fixed-step method; the first step of the adaptive ones (which
    // otherwise choose it themselves).
    let (fixed_step, initial_step) = if method.is_adaptive() {
        (None, s.step)
    } else {
        (Some(s.step.unwrap_or(1e-5)), None)
    };
    let options = Options {
        rtol: s.rtol,
        atol: s.atol,
        // No limit unless one is given.
        max_step: s.max_step.unwrap_or(f64::INFINITY),
        max_steps: s.max_steps,
        fixed_step,
        initial_step,
        ..Options::default()
    };
    options
        .validate::<std::convert::Infallible>()
        .map_err(|e| EntryError::at(KeyPath::new("simulation"), e.to_string()))?;
    Ok((method, options))
}

/// `[parameters]`: each spec parameter the file sets, by index, with its
/// finite value.
fn parameter_overrides(
    values: &BTreeMap<String, f64>,
    names: &ModelNames,
) -> Result<Vec<(usize, f64)>, EntryError> {
    values
        .iter()
        .map(|(name, value)| {
            Ok((
                index_of("parameters", "parameter", name, &names.parameters)?,
                finite(format!("parameters.{name}"), *value)?,
            ))
        })
        .collect()
}
