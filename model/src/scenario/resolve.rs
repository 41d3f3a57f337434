//! Checking a scenario file against its model and the value ranges of its
//! entries, and resolving names to indices.

use super::bind::bind_components;
use super::file::File;
use super::{Method, ModelNames, Scenario};
use crate::crash::curve::Outside;
use crate::ode::Options;
use lagrangian_core::diagnostic::closest;
use std::collections::BTreeMap;
use std::path::Path;

pub(super) fn unknown<'a>(
    what: &str,
    name: &str,
    known: impl Iterator<Item = &'a str> + Clone,
) -> String {
    let mut message = format!("{what} `{name}` does not exist in the spec");
    if let Some(best) = closest(name, known.clone()) {
        message.push_str(&format!("; did you mean `{best}`?"));
    } else {
        let list: Vec<&str> = known.collect();
        message.push_str(&format!(" (known: {})", list.join(", ")));
    }
    message
}

pub(super) fn index_of(what: &str, name: &str, list: &[String]) -> Result<usize, String> {
    list.iter()
        .position(|n| n == name)
        .ok_or_else(|| unknown(what, name, list.iter().map(String::as_str)))
}

pub(super) fn outside(what: &str, text: &str) -> Result<Outside, String> {
    Outside::parse(text)
        .ok_or_else(|| format!("{what}: outside = `{text}`; use one of {}", Outside::NAMES))
}

pub(super) fn resolve(
    file: File,
    base: &Path,
    names: &ModelNames,
    constants: BTreeMap<String, f64>,
) -> Result<Scenario, String> {
    let s = &file.simulation;
    let method = Method::parse(&s.method).ok_or_else(|| {
        format!(
            "simulation.method = `{}`; use dopri5, rk4 or implicit",
            s.method
        )
    })?;
    if s.t_end.is_nan() || s.t_end <= 0.0 || s.t_end.is_infinite() {
        return Err(format!("simulation.t_end = {} must be positive", s.t_end));
    }
    if s.output_interval.is_nan() || s.output_interval <= 0.0 {
        return Err(format!(
            "simulation.output_interval = {} must be positive",
            s.output_interval
        ));
    }
    let fixed_step = match (method, s.step) {
        (Method::Rk4, None) => Some(1e-5),
        (Method::Rk4, Some(h)) => Some(h),
        _ => None,
    };
    let options = Options {
        rtol: s.rtol,
        atol: s.atol,
        max_step: s.max_step.unwrap_or(f64::INFINITY),
        max_steps: s.max_steps,
        fixed_step,
        ..Options::default()
    };
    options.validate().map_err(|e| format!("simulation: {e}"))?;

    let parameters = file
        .parameters
        .iter()
        .map(|(name, value)| {
            Ok((
                index_of("parameters: parameter", name, &names.parameters)?,
                *value,
            ))
        })
        .collect::<Result<_, String>>()?;
    let coordinate = |what: &str, name: &str| index_of(what, name, &names.coordinates);
    let initial_coordinates = file
        .initial
        .coordinates
        .iter()
        .map(|(n, v)| Ok((coordinate("initial.coordinates: coordinate", n)?, *v)))
        .collect::<Result<_, String>>()?;
    let initial_velocities = file
        .initial
        .velocities
        .iter()
        .map(|(n, v)| Ok((coordinate("initial.velocities: coordinate", n)?, *v)))
        .collect::<Result<_, String>>()?;
    let equilibrium = file
        .initial
        .equilibrium
        .iter()
        .map(|n| coordinate("initial.equilibrium: coordinate", n))
        .collect::<Result<_, String>>()?;
    let crush = match &file.metrics.crush {
        None => None,
        Some(text) => {
            let (sign, name) = match text.trim().strip_prefix('-') {
                Some(rest) => (-1.0, rest.trim()),
                None => (1.0, text.trim().trim_start_matches('+')),
            };
            Some((coordinate("metrics.crush: coordinate", name)?, sign))
        }
    };
    let pitch = file
        .metrics
        .pitch
        .iter()
        .map(|n| coordinate("metrics.pitch: coordinate", n))
        .collect::<Result<_, String>>()?;
    if let Some(weld) = &file.metrics.weld
        && !file.components.contains_key(weld)
    {
        return Err(unknown(
            "metrics.weld: component",
            weld,
            file.components.keys().map(String::as_str),
        ));
    }
    let inputs = bind_components(&file.components, base, names, constants)?;
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
        pitch,
        weld: file.metrics.weld.clone(),
        inputs,
    })
}
