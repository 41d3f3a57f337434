//! What a component's section builds into: the [`Binder`] that collects the
//! scenario's components and binds the model's input functions to their
//! ports, and the [`Ports`] a section names. Each `[components.NAME]`
//! section's `build` (see [`crate::components`]) reaches only this module and
//! [`crate::entry`], never the scenario above.

use super::constant::Constant;
use super::{Binding, BoundInputs, Component, NamedComponent, Port};
use crate::entry::{EntryError, KeyPath, index_of};
use crate::model_names::ModelNames;
use crate::table::Table;
use serde::Deserialize;
use std::collections::BTreeMap;
use std::sync::Arc;

/// The inputs a component supplies: its value and, optionally, derivatives
/// (`inputs = { force = "…", stiffness = "…", damping = "…" }`; `moment` for
/// `force` too).
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct Ports {
    #[serde(alias = "moment")]
    force: String,
    stiffness: Option<String>,
    damping: Option<String>,
}

/// Where an entry that binds an input names it: as its value
/// (`inputs = { force = "F" }`) or as its key (`columns = { F = "force" }`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum Named {
    /// `key = "INPUT"`.
    ByValue,
    /// `INPUT = …`.
    ByKey,
}

/// The scenario's components as they are built, and the model's inputs as
/// they get bound, each to one port of a component.
pub(crate) struct Binder<'a> {
    names: &'a ModelNames,
    tables: &'a BTreeMap<String, Arc<Table>>,
    components: Vec<NamedComponent>,
    bindings: Vec<Option<Binding>>,
}

impl<'a> Binder<'a> {
    /// A binder for the inputs of the model named by `names`, with the data
    /// files the sections loaded.
    pub(crate) fn new(
        names: &'a ModelNames,
        tables: &'a BTreeMap<String, Arc<Table>>,
    ) -> Binder<'a> {
        Binder {
            names,
            tables,
            components: Vec::new(),
            bindings: vec![None; names.inputs.len()],
        }
    }

    /// The components and the inputs bound to them, once every section has
    /// built and `--set` constants have overridden.
    pub(crate) fn finish(mut self) -> Result<BoundInputs, EntryError> {
        self.bind_supplied_derivatives();
        let event_arguments = self.event_arguments()?;
        Ok(BoundInputs::new(
            self.components,
            self.bindings,
            event_arguments,
            self.names.inputs.clone(),
        ))
    }

    /// Binds each input a spec leaves to its component (`d(x)` without an
    /// expression makes the input `F_dx` of `F`'s arguments) to the
    /// tangent of the component `F` is bound to: `F`'s first argument's
    /// derivative to its stiffness port, the second's to its damping port.
    /// An input the scenario binds itself keeps that binding.
    fn bind_supplied_derivatives(&mut self) {
        let names = self.names;
        for (k, input) in names.inputs.iter().enumerate() {
            if self.bindings[k].is_some() {
                continue;
            }
            let tangent = (names.inputs.iter().enumerate()).find_map(|(f, value)| {
                let argument = input.strip_prefix(value.as_str())?.strip_prefix("_d")?;
                let arguments = names.input_arguments.get(f)?.as_ref()?;
                let position = arguments.iter().position(|a| a == argument)?;
                let binding = self.bindings[f].filter(|b| b.port == Port::Value)?;
                let port = [Port::Stiffness, Port::Damping].get(position).copied()?;
                Some(Binding { port, ..binding })
            });
            if tangent.is_some() {
                self.bindings[k] = tangent;
            }
        }
    }

    /// Adds `component` under `name`; returns its index, to bind inputs to.
    pub(crate) fn add(&mut self, name: String, component: Box<dyn Component>) -> usize {
        self.components.push(NamedComponent { name, component });
        self.components.len() - 1
    }

    /// The number of components so far.
    pub(crate) fn component_count(&self) -> usize {
        self.components.len()
    }

    /// The kinds of the components from index `first` on.
    pub(crate) fn kinds_from(&self, first: usize) -> impl Iterator<Item = &'static str> + '_ {
        self.components[first..].iter().map(|c| c.component.kind())
    }

    /// The data file that section `[components.{name}]` loaded
    /// ([`crate::components::Section::load_table`]).
    pub(crate) fn table(&self, name: &str) -> Result<&'a Table, EntryError> {
        let tables: &'a BTreeMap<String, Arc<Table>> = self.tables;
        tables.get(name).map(|t| &**t).ok_or_else(|| {
            EntryError::at(
                KeyPath::new("components").join(name),
                "its table was not loaded",
            )
        })
    }

    /// Binds the input named at scenario entry `key` (its value, or its
    /// key's last part when `Named::ByKey`) to `port` of component `index`;
    /// the input must take the number of arguments the component reads.
    pub(crate) fn bind(
        &mut self,
        (key, named): (&KeyPath, Named),
        input: &str,
        (index, port): (usize, Port),
    ) -> Result<(), EntryError> {
        let names = self.names;
        let bad = |reason: String| match named {
            Named::ByValue => EntryError::text(key.clone(), input, reason),
            Named::ByKey => EntryError::at(key.clone(), reason),
        };
        let k = index_of(key, "input", input, &names.inputs).map_err(|e| bad(e.reason))?;
        if self.bindings[k].is_some() {
            return Err(bad(format!(
                "input `{input}` is already supplied by another component"
            )));
        }
        let component = &self.components[index].component;
        if let (Some((needed, meaning)), Some(has)) = (component.arguments(), names.arity(k))
            && needed != has
        {
            let plural = |n: usize| if n == 1 { "" } else { "s" };
            return Err(bad(format!(
                "input {} has {has} argument{}, but a {} component needs an input of {needed} argument{} ({meaning})",
                names.signature(k),
                plural(has),
                component.kind(),
                plural(needed),
            )));
        }
        self.bindings[k] = Some(Binding {
            component: index,
            port,
        });
        Ok(())
    }

    /// Binds the value input (written as `inputs.{value}`) and, if given,
    /// the stiffness and damping inputs of component `index` of section
    /// `[components.{owner}]`.
    pub(crate) fn bind_ports(
        &mut self,
        ports: &Ports,
        value: &str,
        index: usize,
        owner: &str,
    ) -> Result<(), EntryError> {
        let inputs = KeyPath::new("components").join(owner).join("inputs");
        let f = &ports.force;
        self.bind(
            (&inputs.join(value), Named::ByValue),
            f,
            (index, Port::Value),
        )?;
        if let Some(s) = &ports.stiffness {
            self.bind(
                (&inputs.join("stiffness"), Named::ByValue),
                s,
                (index, Port::Stiffness),
            )?;
        }
        if let Some(d) = &ports.damping {
            self.bind(
                (&inputs.join("damping"), Named::ByValue),
                d,
                (index, Port::Damping),
            )?;
        }
        Ok(())
    }

    /// Gives input `k` the constant `value` of `--set input=value`, whatever
    /// the file binds it to (the override checked the name and the value).
    pub(crate) fn set_constant(&mut self, k: usize, value: f64) {
        let input = &self.names.inputs[k];
        let c = self.add(format!("--set {input}"), Box::new(Constant { value }));
        self.bindings[k] = Some(Binding {
            component: c,
            port: Port::Value,
        });
    }

    /// For each component: where its events and columns find the arguments
    /// of its value input (the first input bound to its value port) among
    /// the model's input arguments — `None` for a component with neither,
    /// or whose value input `--set` overrode or the dynamics does not call.
    /// A component with events needs that input called at one place; one
    /// with columns only has none where it is called at several.
    fn event_arguments(&self) -> Result<Vec<Option<(usize, usize)>>, EntryError> {
        let mut arguments = vec![None; self.components.len()];
        for (c, named) in self.components.iter().enumerate() {
            let component = &named.component;
            let stateful = !named.events().is_empty() || !named.states().is_empty();
            if !stateful && component.columns().is_empty() && component.energy().is_none() {
                continue;
            }
            let value = Some(Binding {
                component: c,
                port: Port::Value,
            });
            let Some(k) = self.bindings.iter().position(|b| *b == value) else {
                continue; // overridden by --set
            };
            arguments[c] = match self.only_call(k, &named.name) {
                Err(_) if !stateful => None,
                call => call?,
            };
        }
        Ok(arguments)
    }

    /// The offset and number of the arguments of input `k`'s one call in
    /// the dynamics (`None`: no call), for stateful component `owner`.
    fn only_call(&self, k: usize, owner: &str) -> Result<Option<(usize, usize)>, EntryError> {
        let mut offset = 0;
        let mut found = Vec::new();
        for &(site, arity) in &self.names.input_sites {
            if site == k {
                found.push((offset, arity));
            }
            offset += arity;
        }
        match found.as_slice() {
            [] => Ok(None),
            [one] => Ok(Some(*one)),
            _ => Err(EntryError::about(
                KeyPath::new("components").join(owner),
                format!(
                    "component `{owner}` keeps state (hysteresis, failure), but its input `{}` is called at {} places with different arguments; give each call its own input function",
                    self.names.inputs[k],
                    found.len()
                ),
            )),
        }
    }
}
