//! Crash components that supply a model's input functions: the crush
//! element (eqs 1–2, hysteresis, contact), a failing torsional weld,
//! tabulated time histories and constants.

pub mod crush;
pub mod curve;
pub mod table;
pub mod weld;

use crate::fault::Fault;
use crate::ode::Direction;
use crush::CrushElement;
use curve::{Curve, OutOfRange};
use lagrangian_model::InputFunctions;
use std::cell::RefCell;
use weld::Weld;

/// Which value of a component an input function reads.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Port {
    /// The force or moment itself.
    Value,
    /// Its derivative with respect to the first argument (tangent stiffness).
    Stiffness,
    /// Its derivative with respect to the second argument (tangent damping).
    Damping,
}

/// What a component is.
#[derive(Clone, Debug, PartialEq)]
pub enum Element {
    Crush(CrushElement),
    Weld(Weld),
    /// A function of the input's first argument (a time history).
    Curve(Curve),
    Constant(f64),
}

impl Element {
    /// Number of event functions.
    pub fn event_count(&self) -> usize {
        match self {
            Element::Crush(_) => crush::EVENTS.len(),
            Element::Weld(_) => weld::EVENTS.len(),
            _ => 0,
        }
    }

    /// What the scenario calls this kind of component.
    pub fn kind(&self) -> &'static str {
        match self {
            Element::Crush(_) => "crush",
            Element::Weld(_) => "weld",
            Element::Curve(_) => "table",
            Element::Constant(_) => "constant",
        }
    }

    /// How many arguments the input functions bound to this element must
    /// have, and what they are; `None`: any number (a constant).
    pub fn arguments(&self) -> Option<(usize, &'static str)> {
        match self {
            Element::Crush(_) => Some((2, "the crush coordinate and its rate")),
            Element::Weld(_) => Some((2, "the angle and its rate")),
            Element::Curve(_) => Some((1, "the time or abscissa of the table")),
            Element::Constant(_) => None,
        }
    }

    pub fn event_name(&self, k: usize) -> &'static str {
        match self {
            Element::Crush(_) => crush::EVENTS[k],
            Element::Weld(_) => weld::EVENTS[k],
            _ => "",
        }
    }

    /// The value of `port` at the input's arguments `args`, which hold as
    /// many values as [`Element::arguments`] asks for.
    fn value(&self, port: Port, args: &[f64]) -> Result<f64, OutOfRange> {
        match (self, port) {
            (Element::Crush(c), Port::Value) => c.force(args),
            (Element::Crush(c), Port::Stiffness) => c.force_stiffness(args),
            (Element::Crush(c), Port::Damping) => c.force_damping(args),
            (Element::Weld(w), port) => {
                let (m, dm, dc) = w.moment(args)?;
                Ok(match port {
                    Port::Value => m,
                    Port::Stiffness => dm,
                    Port::Damping => dc,
                })
            }
            (Element::Curve(c), Port::Value) => Ok(c.eval(args[0])?.0),
            (Element::Curve(c), Port::Stiffness) => Ok(c.eval(args[0])?.1),
            (Element::Curve(_), Port::Damping) => Ok(0.0),
            (Element::Constant(v), Port::Value) => Ok(*v),
            (Element::Constant(_), _) => Ok(0.0),
        }
    }
}

/// A named component.
#[derive(Clone, Debug, PartialEq)]
pub struct Component {
    pub name: String,
    pub element: Element,
}

/// Where a model's input function gets its value.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Binding {
    pub component: usize,
    pub port: Port,
}

/// A model's inputs bound to components; implements [`InputFunctions`].
///
/// A value that cannot be produced (a table read outside its range under the
/// `error` policy) is returned as NaN and the reason kept, so the integrator
/// stops with that reason instead of a wrong number.
#[derive(Clone, Debug)]
pub struct BoundInputs {
    pub components: Vec<Component>,
    /// One per model input, by input index (`None`: unbound, NaN if called).
    pub bindings: Vec<Option<Binding>>,
    /// For each component with events: the offset and length of the
    /// arguments of its value input among the model's input arguments.
    pub event_arguments: Vec<Option<(usize, usize)>>,
    /// The input names, for messages.
    pub input_names: Vec<String>,
    failure: RefCell<Option<Fault>>,
}

impl BoundInputs {
    pub fn new(
        components: Vec<Component>,
        bindings: Vec<Option<Binding>>,
        event_arguments: Vec<Option<(usize, usize)>>,
        input_names: Vec<String>,
    ) -> BoundInputs {
        BoundInputs {
            components,
            bindings,
            event_arguments,
            input_names,
            failure: RefCell::new(None),
        }
    }

    /// The first failure since the last call, which clears it.
    pub fn take_failure(&self) -> Option<Fault> {
        self.failure.borrow_mut().take()
    }

    fn fail(&self, fault: Fault) -> f64 {
        let mut slot = self.failure.borrow_mut();
        if slot.is_none() {
            *slot = Some(fault);
        }
        f64::NAN
    }

    /// Puts every component in its initial state for a run that starts
    /// with the model's input arguments `arguments` (crush elements in
    /// contact or not, welds intact).
    pub fn start(&mut self, arguments: &[f64]) -> Result<(), Fault> {
        for c in 0..self.components.len() {
            let args = self.event_arguments[c].map(|(start, len)| &arguments[start..start + len]);
            let result = match (&mut self.components[c].element, args) {
                (Element::Crush(e), Some(args)) => e.start(args),
                // Not called by the dynamics: no events, so it stays as it is at rest.
                (Element::Crush(e), None) => e.start(&[0.0, 0.0]),
                (Element::Weld(w), _) => {
                    w.reset();
                    Ok(())
                }
                _ => Ok(()),
            };
            result.map_err(|e| self.out_of_range(c, None, e))?;
        }
        Ok(())
    }

    /// `(component, local event)` of global event `k`.
    pub fn event(&self, k: usize) -> Option<(usize, usize)> {
        let mut k = k;
        for (c, component) in self.components.iter().enumerate() {
            let n = if self.event_arguments[c].is_some() {
                component.element.event_count()
            } else {
                0
            };
            if k < n {
                return Some((c, k));
            }
            k -= n;
        }
        None
    }

    pub fn event_count(&self) -> usize {
        self.components
            .iter()
            .zip(&self.event_arguments)
            .filter(|(_, a)| a.is_some())
            .map(|(c, _)| c.element.event_count())
            .sum()
    }

    pub fn event_direction(&self, k: usize) -> Direction {
        match self
            .event(k)
            .map(|(c, local)| (&self.components[c].element, local))
        {
            Some((Element::Crush(_), local)) => CrushElement::event_direction(local),
            Some((Element::Weld(_), local)) => Weld::event_direction(local),
            _ => Direction::Either,
        }
    }

    /// All event functions, given the model's input arguments at one state.
    pub fn events(&self, arguments: &[f64], g: &mut [f64]) -> Result<(), Fault> {
        let mut offset = 0;
        for (c, component) in self.components.iter().enumerate() {
            let Some((start, len)) = self.event_arguments[c] else {
                continue;
            };
            let n = component.element.event_count();
            let args = &arguments[start..start + len];
            let result = match &component.element {
                Element::Crush(e) => e.events(args, &mut g[offset..offset + n]),
                Element::Weld(w) => w.events(args, &mut g[offset..offset + n]),
                _ => Ok(()),
            };
            result.map_err(|e| self.out_of_range(c, None, e))?;
            offset += n;
        }
        Ok(())
    }

    /// Applies global event `k` at time `t`; returns `(component, description)`.
    pub fn on_event(
        &mut self,
        k: usize,
        t: f64,
        arguments: &[f64],
    ) -> Result<(String, String), Fault> {
        let Some((c, local)) = self.event(k) else {
            return Err(Fault::Component(format!("no event {k}")));
        };
        let (start, len) = self.event_arguments[c].unwrap_or((0, 0));
        let args = &arguments[start..start + len];
        let name = self.components[c].name.clone();
        let result = match &mut self.components[c].element {
            Element::Crush(e) => e.on_event(local, args),
            Element::Weld(w) => w.on_event(local, t, args),
            _ => Ok(String::new()),
        };
        result
            .map(|d| (name, d))
            .map_err(|e| self.out_of_range(c, None, e))
    }

    fn out_of_range(&self, component: usize, input: Option<usize>, e: OutOfRange) -> Fault {
        Fault::OutOfRange {
            component: self.components[component].name.clone(),
            input: input.map(|i| self.input_names[i].clone()),
            x: e.x,
            min: e.min,
            max: e.max,
        }
    }

    /// The compression sign of the crush element whose force input `input`
    /// is, or `None` when it is not one.
    pub fn crush_force_sign(&self, input: usize) -> Option<f64> {
        let binding = self.bindings.get(input).copied().flatten()?;
        match &self.components[binding.component].element {
            Element::Crush(c) if binding.port == Port::Value => Some(c.compression_sign),
            _ => None,
        }
    }

    /// The time a weld component failed, if it did.
    pub fn weld_failure(&self, name: Option<&str>) -> Option<f64> {
        self.components
            .iter()
            .filter(|c| name.is_none_or(|n| n == c.name))
            .find_map(|c| match &c.element {
                Element::Weld(w) => w.failed_at(),
                _ => None,
            })
    }
}

impl InputFunctions for BoundInputs {
    fn value(&self, input: usize, args: &[f64]) -> f64 {
        let Some(Some(binding)) = self.bindings.get(input) else {
            let name = self.input_names.get(input).map_or("?", String::as_str);
            return self.fail(Fault::Component(format!("input function `{name}` has no value: bind it in the scenario or give it with --set {name}=VALUE")));
        };
        let component = &self.components[binding.component];
        if let Some((needed, _)) = component.element.arguments()
            && args.len() != needed
        {
            // The scenario checks this where it knows the input's arguments;
            // a compiled model does not tell them for inputs only its
            // Jacobians call.
            return self.fail(Fault::Component(format!(
                "input `{}` is called with {} argument{}, but {} component `{}` needs {needed}",
                self.input_names[input],
                args.len(),
                if args.len() == 1 { "" } else { "s" },
                component.element.kind(),
                component.name
            )));
        }
        match component.element.value(binding.port, args) {
            Ok(v) => v,
            Err(e) => self.fail(self.out_of_range(binding.component, Some(input), e)),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::crash::crush::Unloading;
    use crate::crash::curve::Characteristic;

    #[test]
    fn an_input_of_the_wrong_arity_fails_instead_of_panicking() {
        // What a compiled model can bring past the scenario check: a crush
        // element's stiffness port on an input of one argument.
        let crush = CrushElement::new(
            Characteristic::constant(1.0e6),
            Characteristic::constant(1.0e3),
            Unloading::Elastic,
            1.0,
            true,
        );
        let inputs = BoundInputs::new(
            vec![Component {
                name: "front_end".into(),
                element: Element::Crush(crush),
            }],
            vec![Some(Binding {
                component: 0,
                port: Port::Stiffness,
            })],
            vec![None],
            vec!["crush_stiffness".into()],
        );
        assert!(inputs.value(0, &[0.1]).is_nan());
        assert_eq!(
            inputs.take_failure(),
            Some(Fault::Component(
                "input `crush_stiffness` is called with 1 argument, but crush component `front_end` needs 2"
                    .to_string()
            ))
        );
    }
}
