//! Binding a model's input functions to the scenario's crash components.

use super::ModelNames;
use super::file::{ComponentSection, Ports};
use super::resolve::{finite, index_of, non_negative, outside, positive};
use crate::crash::constant::Constant;
use crate::crash::crush::{CrushElement, Unloading};
use crate::crash::curve::{Characteristic, Curve};
use crate::crash::table::Table;
use crate::crash::tabulated::Tabulated;
use crate::crash::weld::Weld;
use crate::crash::{Binding, BoundInputs, Component, NamedComponent, Port};
use std::collections::BTreeMap;
use std::fmt;

pub(super) fn bind_components(
    sections: &BTreeMap<String, ComponentSection>,
    tables: &BTreeMap<String, Table>,
    names: &ModelNames,
    constants: BTreeMap<String, f64>,
) -> Result<BoundInputs, String> {
    let mut components = Vec::new();
    let mut binder = Binder {
        names,
        bindings: vec![None; names.inputs.len()],
    };
    let mut value_inputs = Vec::new();
    for (name, section) in sections {
        let c = components.len();
        let at = |what: &str, e: &dyn fmt::Display| format!("components.{name}: {what}: {e}");
        let element = match section {
            ComponentSection::Crush {
                inputs,
                compression,
                stiffness_breakpoints,
                stiffness_values,
                damping_breakpoints,
                damping_values,
                unloading,
                unloading_stiffness,
                contact_only,
                outside: policy,
            } => {
                let policy = outside(&format!("components.{name}"), policy)?;
                let stiffness =
                    Characteristic::new(stiffness_breakpoints, stiffness_values, policy)
                        .map_err(|e| at("stiffness table", &e))?;
                let damping = Characteristic::new(damping_breakpoints, damping_values, policy)
                    .map_err(|e| at("damping table", &e))?;
                let unloading = match (unloading.as_str(), unloading_stiffness) {
                    ("elastic", _) => Unloading::Elastic,
                    ("plastic", Some(k)) if *k > 0.0 && k.is_finite() => {
                        Unloading::Plastic { stiffness: *k }
                    }
                    ("plastic", _) => {
                        return Err(format!(
                            "components.{name}: plastic unloading needs a positive unloading_stiffness [N/m]"
                        ));
                    }
                    (other, _) => {
                        return Err(format!(
                            "components.{name}: unloading = `{other}`; use elastic or plastic"
                        ));
                    }
                };
                let sign = match compression.as_str() {
                    "positive" => 1.0,
                    "negative" => -1.0,
                    other => {
                        return Err(format!(
                            "components.{name}: compression = `{other}`; use positive or negative (the sign of the input's first argument under compression)"
                        ));
                    }
                };
                let element: Box<dyn Component> = Box::new(CrushElement::new(
                    stiffness,
                    damping,
                    unloading,
                    sign,
                    *contact_only,
                ));
                binder.bind_ports(inputs, ("force", element.as_ref()), c, name)?;
                value_inputs.push((c, inputs.force.clone()));
                element
            }
            ComponentSection::Weld {
                inputs,
                curve,
                damping,
                failure_moment,
                failure_angle,
                post_failure_curve,
                post_failure_damping,
                outside: policy,
            } => {
                let policy = outside(&format!("components.{name}"), policy)?;
                let make = |points: &[[f64; 2]], what: &str| {
                    Curve::new(
                        points.iter().map(|p| p[0]).collect(),
                        points.iter().map(|p| p[1]).collect(),
                        policy,
                    )
                    .map_err(|e| at(what, &e))
                };
                let key = |entry: &str| format!("components.{name}.{entry}");
                non_negative(&key("damping"), *damping)?;
                non_negative(&key("post_failure_damping"), *post_failure_damping)?;
                if let Some(m) = failure_moment {
                    positive(&key("failure_moment"), *m)?;
                }
                if let Some(a) = failure_angle {
                    positive(&key("failure_angle"), *a)?;
                }
                let intact = make(curve, "curve")?;
                let post = post_failure_curve
                    .as_deref()
                    .map(|p| make(p, "post_failure_curve"))
                    .transpose()?;
                let element: Box<dyn Component> = Box::new(Weld::new(
                    intact,
                    *damping,
                    *failure_moment,
                    *failure_angle,
                    post,
                    *post_failure_damping,
                ));
                binder.bind_ports(inputs, ("moment", element.as_ref()), c, name)?;
                value_inputs.push((c, inputs.force.clone()));
                element
            }
            ComponentSection::Table {
                time_column,
                columns,
                outside: policy,
                ..
            } => {
                let policy = outside(&format!("components.{name}"), policy)?;
                let table = tables
                    .get(name)
                    .ok_or_else(|| format!("components.{name}: its table was not loaded"))?;
                for (input, column) in columns {
                    let curve = table
                        .curve(time_column, column, policy)
                        .map_err(|e| format!("components.{name}: {e}"))?;
                    let element = Tabulated { curve };
                    let key = format!("components.{name}.columns.{input}");
                    binder.bind(&key, input, (components.len(), Port::Value), &element)?;
                    components.push(NamedComponent {
                        name: format!("{name}.{input}"),
                        component: Box::new(element),
                    });
                }
                continue;
            }
            ComponentSection::Constant { values } => {
                for (input, value) in values {
                    let key = format!("components.{name}.values.{input}");
                    let element = Constant {
                        value: finite(&key, *value)?,
                    };
                    binder.bind(&key, input, (components.len(), Port::Value), &element)?;
                    components.push(NamedComponent {
                        name: format!("{name}.{input}"),
                        component: Box::new(element),
                    });
                }
                continue;
            }
        };
        components.push(NamedComponent {
            name: name.clone(),
            component: element,
        });
    }
    let mut bindings = binder.bindings;
    // --set constants override whatever the file binds.
    for (input, value) in constants {
        finite(&format!("--set {input}"), value)?;
        let k = index_of("--set: input", &input, &names.inputs)?;
        bindings[k] = Some(Binding {
            component: components.len(),
            port: Port::Value,
        });
        components.push(NamedComponent {
            name: format!("--set {input}"),
            component: Box::new(Constant { value }),
        });
    }
    // Components with events need the arguments of their one value input.
    let mut event_arguments = vec![None; components.len()];
    for (c, input) in value_inputs {
        let k = index_of("input", &input, &names.inputs)?;
        if bindings[k].map(|b| b.component) != Some(c) {
            continue; // overridden by --set
        }
        let mut offset = 0;
        let mut found = Vec::new();
        for &(site, arity) in &names.input_sites {
            if site == k {
                found.push((offset, arity));
            }
            offset += arity;
        }
        match found.as_slice() {
            [] => {}
            [one] => event_arguments[c] = Some(*one),
            _ => {
                return Err(format!(
                    "component `{}` keeps state (hysteresis, failure), but its input `{input}` is called at {} places with different arguments; give each call its own input function",
                    components[c].name,
                    found.len()
                ));
            }
        }
    }
    Ok(BoundInputs::new(
        components,
        bindings,
        event_arguments,
        names.inputs.clone(),
    ))
}

/// The model's inputs as they get bound, each to one port of a component.
struct Binder<'a> {
    names: &'a ModelNames,
    bindings: Vec<Option<Binding>>,
}

impl Binder<'_> {
    /// Binds the input named at scenario entry `key` to `port` of component
    /// `index`, which is `element`; the input must take the number of
    /// arguments the element reads.
    fn bind(
        &mut self,
        key: &str,
        input: &str,
        (index, port): (usize, Port),
        element: &dyn Component,
    ) -> Result<(), String> {
        let names = self.names;
        let k = index_of(&format!("{key}: input"), input, &names.inputs)?;
        if self.bindings[k].is_some() {
            return Err(format!(
                "{key}: input `{input}` is already supplied by another component"
            ));
        }
        if let (Some((needed, meaning)), Some(has)) = (element.arguments(), names.arity(k))
            && needed != has
        {
            let plural = |n: usize| if n == 1 { "" } else { "s" };
            return Err(format!(
                "{key}: input {} has {has} argument{}, but a {} component needs an input of {needed} argument{} ({meaning})",
                names.signature(k),
                plural(has),
                element.kind(),
                plural(needed),
            ));
        }
        self.bindings[k] = Some(Binding {
            component: index,
            port,
        });
        Ok(())
    }

    /// Binds the value input (written as `inputs.{value}`) and, if given,
    /// the stiffness and damping inputs of component `index` of `owner`.
    fn bind_ports(
        &mut self,
        ports: &Ports,
        (value, element): (&str, &dyn Component),
        index: usize,
        owner: &str,
    ) -> Result<(), String> {
        let key =
            |entry: &str, input: &str| format!("components.{owner}.inputs.{entry} = \"{input}\"");
        let f = &ports.force;
        self.bind(&key(value, f), f, (index, Port::Value), element)?;
        if let Some(s) = &ports.stiffness {
            self.bind(&key("stiffness", s), s, (index, Port::Stiffness), element)?;
        }
        if let Some(d) = &ports.damping {
            self.bind(&key("damping", d), d, (index, Port::Damping), element)?;
        }
        Ok(())
    }
}
