//! `[iso_mme]`: what a run written as an ISO-MME test (`lpm simulate
//! --iso-mme DIR`) holds besides the vehicle's standard channels, each
//! entry checked here — a channel code that is not one is an error naming
//! its key and the code, located like every scenario error.
//!
//! ```toml
//! [iso_mme]
//! name = "YARIS56"                      # the test's name; default: the spec's stem
//! title = "Yaris, 56 km/h, full frontal" # default: the scenario's description
//! laboratory = "Vehicle safety lab"
//! barrier_force = "front_end.force"     # default: the contact elements' force; "" for none
//! [iso_mme.channels]                    # trajectory column (or combination) = channel code
//! "theta2" = "10SEAT000000ANYP"
//! "occupant_deceleration" = "11CHST0000H3ACXP"
//! ```

use super::file::{IsoMmeSection, MetricsSection};
use super::{ModelNames, Signal};
use crate::components::ComponentSection;
use crate::entry::{EntryError, KeyPath};
use lagrangian_crashdata::ChannelCode;
use std::collections::BTreeMap;

/// The resolved `[iso_mme]` section.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct IsoMme {
    /// The test's name, where the section gives one.
    pub name: Option<String>,
    /// The test's title, where the section gives one.
    pub title: Option<String>,
    /// The laboratory's name, where the section gives one.
    pub laboratory: Option<String>,
    /// The barrier force (compression of the contact elements positive
    /// \[N\]): the section's `barrier_force`, else the force of the
    /// components `metrics.contact` names, else of the scenario's one
    /// crush or contact component; `None` for none of these (or `""`).
    pub barrier_force: Option<Signal>,
    /// The further channels, by column name.
    pub channels: Vec<IsoMmeChannel>,
}

/// A channel the section adds: a signal of the run and its code.
#[derive(Clone, Debug, PartialEq)]
pub struct IsoMmeChannel {
    /// What it records (a trajectory column or a combination).
    pub signal: Signal,
    /// Its 16-character code.
    pub code: ChannelCode,
}

/// The section `section` resolved against the model's `names` (with the
/// components' columns), the scenario's `metrics` and `components`.
pub(super) fn resolve_iso_mme(
    section: &IsoMmeSection,
    metrics: &MetricsSection,
    components: &BTreeMap<String, ComponentSection>,
    names: &ModelNames,
) -> Result<IsoMme, EntryError> {
    if let Some(name) = &section.name {
        check_name(name)?;
    }
    let barrier_force = match section.barrier_force.as_deref() {
        Some("") => None,
        Some(text) => Some(Signal::parse("iso_mme.barrier_force", text, names)?),
        None => default_barrier_force(metrics, components)
            .map(|text| Signal::parse("iso_mme.barrier_force", &text, names))
            .transpose()?,
    };
    let mut channels: Vec<IsoMmeChannel> = Vec::new();
    for (column, code) in &section.channels {
        let key = KeyPath::new("iso_mme.channels").join(column);
        let code = ChannelCode::parse(code)
            .map_err(|e| EntryError::text(key.clone(), code, e.to_string()))?;
        if let Some(other) = channels.iter().find(|c| c.code == code) {
            let why = format!("the code is given to `{}` already", other.signal.name);
            return Err(EntryError::text(key, code.as_str(), why));
        }
        let signal = Signal::parse(&key.to_string(), column, names)?;
        channels.push(IsoMmeChannel { signal, code });
    }
    Ok(IsoMme {
        name: section.name.clone(),
        title: section.title.clone(),
        laboratory: section.laboratory.clone(),
        barrier_force,
        channels,
    })
}

/// `iso_mme.name` names a file: not empty, no path separator.
fn check_name(name: &str) -> Result<(), EntryError> {
    let bad =
        name.trim().is_empty() || name == "." || name == ".." || name.contains(['/', '\\', ':']);
    match bad {
        true => Err(EntryError::text(
            KeyPath::new("iso_mme.name"),
            name,
            "the test's name is its files' stem: not empty, without / \\ or :",
        )),
        false => Ok(()),
    }
}

/// The barrier force when the section gives none: the sum of the `force`
/// columns of the components `metrics.contact` names, else of the
/// scenario's one crush or contact component (none when it has several:
/// which of them push on a barrier is the scenario's to say).
fn default_barrier_force(
    metrics: &MetricsSection,
    components: &BTreeMap<String, ComponentSection>,
) -> Option<String> {
    let named: Vec<&str> = match metrics.contact.is_empty() {
        false => metrics.contact.iter().map(String::as_str).collect(),
        true => (components.iter())
            .filter(|(_, c)| matches!(c.kind(), "crush" | "contact"))
            .map(|(name, _)| name.as_str())
            .collect(),
    };
    if named.is_empty() || (metrics.contact.is_empty() && named.len() > 1) {
        return None;
    }
    let columns: Vec<String> = named.iter().map(|name| format!("{name}.force")).collect();
    Some(columns.join(" + "))
}
