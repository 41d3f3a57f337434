//! Names of the locals in generated code: the user's names where they are
//! free, suffixed with `_` where they would collide with a name the target
//! reserves (a keyword, an argument of the generated function) or with each
//! other.

use super::schedule::Load;
use crate::spec::Model;
use proc_macro2::{Ident, Span};
use rustc_hash::FxHashSet;

/// The locals of the loads and the temporaries of generated routines.
pub(crate) struct Locals {
    coordinates: Vec<String>,
    velocities: Vec<String>,
    accelerations: Vec<String>,
    parameters: Vec<String>,
    temporary_prefix: String,
}

impl Locals {
    /// Locals for `model` that avoid `reserved`; `spell` writes a spec name
    /// as the target writes it.
    pub fn new(model: &Model, reserved: &[&str], spell: impl Fn(&str) -> String) -> Locals {
        let spell = |name: &str| spell(&identifier(name));
        let mut taken: FxHashSet<String> = reserved.iter().map(|s| s.to_string()).collect();
        let mut fresh = |base: String| {
            let mut name = base;
            while !taken.insert(name.clone()) {
                name.push('_');
            }
            name
        };
        let coordinates: Vec<String> = (model.coordinates.iter())
            .map(|c| fresh(spell(&c.name)))
            .collect();
        let parameters: Vec<String> = (model.parameters.iter())
            .map(|p| fresh(spell(&p.name)))
            .collect();
        let velocities: Vec<String> = (model.coordinates.iter())
            .map(|c| fresh(spell(&format!("{}_dot", c.name))))
            .collect();
        let accelerations: Vec<String> = (model.coordinates.iter())
            .map(|c| fresh(spell(&format!("{}_ddot", c.name))))
            .collect();
        let all: Vec<&String> = (coordinates.iter())
            .chain(&parameters)
            .chain(&velocities)
            .chain(&accelerations)
            .collect();
        let temporary_prefix = temporary_prefix(&all).to_string();
        Locals {
            coordinates,
            velocities,
            accelerations,
            parameters,
            temporary_prefix,
        }
    }

    /// The local holding a load.
    pub fn load(&self, load: Load) -> &str {
        match load {
            Load::Parameter(i) => &self.parameters[i as usize],
            Load::Coordinate(i) => &self.coordinates[i as usize],
            Load::Velocity(i) => &self.velocities[i as usize],
            Load::Acceleration(i) => &self.accelerations[i as usize],
        }
    }

    /// The local holding temporary `k`.
    pub fn temporary(&self, k: usize) -> String {
        format!("{}{k}", self.temporary_prefix)
    }
}

/// A prefix `p` such that no name in `names` is `p` followed by digits.
fn temporary_prefix(names: &[&String]) -> &'static str {
    ["x", "tmp", "v", "w", "e", "x_"]
        .into_iter()
        .find(|p| {
            !names.iter().any(|n| {
                n.strip_prefix(p).is_some_and(|rest| {
                    !rest.is_empty() && rest.chars().all(|c| c.is_ascii_digit())
                })
            })
        })
        .unwrap_or("__x")
}

/// The `INPUT_<NAME>` constant of each input function: its index in
/// `InputFunctions::value` calls (numbered where two names collide).
pub(crate) fn input_constants(inputs: &[String]) -> Vec<Ident> {
    let mut taken = FxHashSet::default();
    (inputs.iter().enumerate())
        .map(|(k, input)| {
            let input = identifier(input);
            let mut name = format!("INPUT_{}", input.trim_start_matches("r#").to_uppercase());
            if !taken.insert(name.clone()) {
                name = format!("{name}_{k}");
                taken.insert(name.clone());
            }
            ident(&name)
        })
        .collect()
}

/// A family's element or a part's name as an identifier: `x[3]` is `x_3`,
/// `car[2].m` is `car_2_m`.
pub(crate) fn identifier(name: &str) -> std::borrow::Cow<'_, str> {
    match name.contains(['[', '.']) {
        true => name
            .replace('[', "_")
            .replace(']', "")
            .replace('.', "_")
            .into(),
        false => name.into(),
    }
}

/// An identifier for `name`, raw (`r#type`) where the spec wrote it so
/// (a family's element `x[3]` as `x_3`).
pub(crate) fn ident(name: &str) -> Ident {
    let name = &*identifier(name);
    match name.strip_prefix("r#") {
        Some(raw) => Ident::new_raw(raw, Span::call_site()),
        None => Ident::new(name, Span::call_site()),
    }
}
