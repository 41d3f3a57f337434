//! A model's input functions bound to the scenario's components, and the
//! components' events and columns as one list each for the integrator and
//! the trajectory.

use super::stand_in::StandIn;
use super::states::StateLayout;
use super::{Column, Component, Contact, Event, Port};
use crate::curve::OutOfRange;
use crate::fault::Fault;
use crate::ode::{Direction, Internal};
use lagrangian_runtime::InputFunctions;
use std::cell::RefCell;

/// A component with the name it has in the scenario (`front_end`, or
/// `barrier.barrier_x1` for one column of a table).
#[derive(Clone, Debug)]
pub struct NamedComponent {
    /// The name, for messages and the event log.
    pub name: String,
    /// The component, in its current state.
    pub component: Box<dyn Component>,
}

impl NamedComponent {
    /// `bouc_wen component `hinge``, for messages.
    pub fn describe(&self) -> String {
        format!("{} component `{}`", self.component.kind(), self.name)
    }

    /// Its events ([`super::Events::list`]); none for a component without.
    pub fn events(&self) -> &'static [Event] {
        self.component.events().map_or(&[], |events| events.list())
    }

    /// Its internal states ([`super::States::list`]); none for a component without.
    pub fn states(&self) -> &'static [Column] {
        self.component.states().map_or(&[], |states| states.list())
    }
}

/// `0.01, 1` (in `e` notation), for the arguments in messages.
fn listed(values: &[f64]) -> String {
    let values: Vec<String> = values.iter().map(|v| format!("{v:e}")).collect();
    values.join(", ")
}

/// Where a model's input function gets its value.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Binding {
    /// The index of the component in [`BoundInputs::components`].
    pub component: usize,
    /// Which of its values.
    pub port: Port,
}

/// A bound input as a call reads it: the binding, with the number of
/// arguments its component takes (`None`: any) and its value where it is
/// constant ([`Component::constant`]), asked once.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Resolved {
    component: usize,
    port: Port,
    arity: Option<usize>,
    constant: Option<f64>,
}

/// A model's inputs bound to components; implements [`InputFunctions`].
///
/// The bindings are resolved and the components' events counted when the
/// inputs are made ([`BoundInputs::new`]), so that an input call is one
/// indexed call of its component (or none, for a constant one): a change of
/// `bindings`, or a component replaced by one with other events, goes
/// through a new `BoundInputs`; one of the same events, through
/// [`BoundInputs::replace`].
///
/// A value that cannot be produced (a table read outside its range under the
/// `error` policy) is returned as NaN and the reason kept, so the integrator
/// stops with that reason instead of a wrong number.
#[derive(Clone, Debug)]
pub struct BoundInputs {
    /// The components, in the order of the scenario.
    pub components: Vec<NamedComponent>,
    /// One per model input, by input index (`None`: unbound, NaN if called).
    pub bindings: Vec<Option<Binding>>,
    /// For each component with events or columns: the offset and length of
    /// the arguments of its value input among the model's input arguments
    /// (`None`: neither, or an input the dynamics does not call).
    pub event_arguments: Vec<Option<(usize, usize)>>,
    /// The input names, for messages.
    pub input_names: Vec<String>,
    /// `bindings` resolved, by input index.
    resolved: Vec<Option<Resolved>>,
    failure: RefCell<Option<Fault>>,
    /// Where the components' internal states lie in the run's `z`.
    layout: StateLayout,
    /// The `z` last given to the components ([`BoundInputs::load`]).
    loaded: Internal,
    /// By global event: its component and its index among the component's
    /// events, listed when the inputs are made (their number is the number
    /// of event functions of all components together): the integrator asks
    /// for them with every event function of every step.
    event_owners: Vec<(usize, usize)>,
    /// The components with events the integrator watches, each with the
    /// index of its first event among all and its number of events.
    event_blocks: Vec<(usize, usize, usize)>,
    /// The elastic energy each component stored when the run started
    /// ([`super::Dissipation::stored_energy`]; 0 for one without).
    stored_at_start: Vec<f64>,
    /// By input index (one per binding): the smooth stand-in an input of
    /// time takes within the step being tried ([`BoundInputs::stand_in`]).
    stand_ins: Vec<Option<StandIn>>,
    /// Some of `stand_ins` are set.
    standing_in: bool,
}

impl Resolved {
    /// `binding` as a call reads it; `None` for a component that is not
    /// among `components`.
    fn of(binding: Binding, components: &[NamedComponent]) -> Option<Resolved> {
        let named = components.get(binding.component)?;
        Some(Resolved {
            component: binding.component,
            port: binding.port,
            arity: named.component.arguments().map(|(needed, _)| needed),
            constant: named.component.constant(binding.port),
        })
    }
}

impl BoundInputs {
    /// Puts `component` in place of component `c` (an FMU's input given a
    /// new value), the inputs bound to it resolved again; it must have the
    /// events of the one it replaces. `false` when there is no component
    /// `c`.
    pub fn replace(&mut self, c: usize, component: Box<dyn Component>) -> bool {
        let Some(named) = self.components.get_mut(c) else {
            return false;
        };
        named.component = component;
        for (resolved, binding) in self.resolved.iter_mut().zip(&self.bindings) {
            if let Some(binding) = binding
                && binding.component == c
            {
                *resolved = Resolved::of(*binding, &self.components);
            }
        }
        true
    }

    /// Inputs bound to `components` by `bindings` (one per input), with the
    /// `event_arguments` of each component (one per component).
    pub fn new(
        components: Vec<NamedComponent>,
        bindings: Vec<Option<Binding>>,
        event_arguments: Vec<Option<(usize, usize)>>,
        input_names: Vec<String>,
    ) -> BoundInputs {
        let layout = StateLayout::of(&components, &event_arguments);
        let resolved = (bindings.iter())
            .map(|binding| Resolved::of((*binding)?, &components))
            .collect();
        let stand_ins = vec![None; bindings.len()];
        let mut inputs = BoundInputs {
            components,
            bindings,
            event_arguments,
            input_names,
            resolved,
            failure: RefCell::new(None),
            layout,
            loaded: Internal::EMPTY,
            event_owners: Vec::new(),
            event_blocks: Vec::new(),
            stored_at_start: Vec::new(),
            stand_ins,
            standing_in: false,
        };
        inputs.event_owners = (0..inputs.components.len())
            .flat_map(|c| (0..inputs.events_of(c)).map(move |local| (c, local)))
            .collect();
        let mut first = 0;
        for c in 0..inputs.components.len() {
            let count = inputs.events_of(c);
            if count > 0 {
                inputs.event_blocks.push((c, first, count));
                first += count;
            }
        }
        inputs
    }

    /// Has input `input` (one of [`BoundInputs::bindings`]) take the value
    /// of `cubic` instead of its own until [`BoundInputs::end_stand_ins`]:
    /// the smooth stand-in for an input of time over the step being tried.
    pub fn stand_in(&mut self, input: usize, cubic: StandIn) {
        if let Some(slot) = self.stand_ins.get_mut(input) {
            *slot = Some(cubic);
            self.standing_in = true;
        }
    }

    /// The inputs that take a stand-in, with it.
    pub fn stand_ins(&self) -> impl Iterator<Item = (usize, StandIn)> + '_ {
        let set: &[Option<StandIn>] = if self.standing_in {
            &self.stand_ins
        } else {
            &[]
        };
        (set.iter().enumerate()).filter_map(|(input, cubic)| Some((input, (*cubic)?)))
    }

    /// The value of input `input` at time `t` as it is, not its stand-in;
    /// `None` where it has no value there (unresolved, or a component that
    /// fails).
    pub fn own_value_of_time(&self, input: usize, t: f64) -> Option<f64> {
        self.own_value(input, &[t])?.1.ok()
    }

    /// What the component of a resolved input gives for `args` (not the
    /// input's stand-in), with the component; `None` for an input not
    /// resolved or called with a number of arguments its component does
    /// not take.
    #[inline]
    fn own_value(&self, input: usize, args: &[f64]) -> Option<(usize, Result<f64, OutOfRange>)> {
        let r = (*self.resolved.get(input)?)?;
        r.arity.is_none_or(|needed| needed == args.len()).then(|| {
            let value = match r.constant {
                Some(value) if args.iter().all(|x| x.is_finite()) => Ok(value),
                _ => self.components[r.component].component.value(r.port, args),
            };
            (r.component, value)
        })
    }

    /// Every input takes its own value again.
    pub fn end_stand_ins(&mut self) {
        if self.standing_in {
            self.stand_ins.fill(None);
            self.standing_in = false;
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

    /// The arguments of component `c`'s value input among the model's input
    /// `arguments`, if its events and columns see them.
    fn arguments_of<'a>(&self, c: usize, arguments: &'a [f64]) -> Option<&'a [f64]> {
        self.event_arguments[c].map(|(start, len)| &arguments[start..start + len])
    }

    /// Starts the components at the arguments `evaluate` writes into
    /// `arguments` with the components as they stand, `prepare` run after
    /// each start (the internal states loaded). An input called inside
    /// another input's arguments needs its component started, so the start
    /// is repeated until the arguments no longer change: one pass per level
    /// of nesting, at most `sites + 1` (a model without nested inputs starts
    /// once, and evaluates its arguments a second time to see them settled).
    pub fn start_settled(
        &mut self,
        arguments: &mut [f64],
        sites: usize,
        evaluate: impl Fn(&BoundInputs, &mut [f64]),
        mut prepare: impl FnMut(&mut BoundInputs) -> Result<(), Fault>,
    ) -> Result<(), Fault> {
        let mut started: Option<Vec<f64>> = None;
        for _ in 0..=sites + 1 {
            evaluate(self, arguments);
            // A failure of an input not yet started is no failure of the
            // run: the next pass evaluates it started.
            let failure = self.take_failure();
            if started.as_deref().is_some_and(|s| same_bits(s, arguments)) {
                return failure.map_or(Ok(()), Err);
            }
            self.start(arguments)?;
            prepare(self)?;
            started = Some(arguments.to_vec());
        }
        Err(Fault::Component(
            "the arguments of the inputs did not settle at the start: an input inside another input's arguments depends on the other".to_string(),
        ))
    }

    /// Puts every component in its initial state for a run that starts
    /// with the model's input arguments `arguments` (crush elements in
    /// contact or not, welds intact, internal states at their initial
    /// values).
    pub fn start(&mut self, arguments: &[f64]) -> Result<(), Fault> {
        for c in 0..self.components.len() {
            let args = self.arguments_of(c, arguments);
            let component = &mut self.components[c].component;
            if let Some(states) = component.states_mut() {
                let mut z = vec![0.0; states.list().len()];
                states.initial_states(&mut z);
                states.set_states(&z);
            }
            let Some(events) = component.events_mut() else {
                continue;
            };
            let result = events.start(args);
            result.map_err(|e| self.out_of_range(c, None, e))?;
        }
        self.stored_at_start = vec![0.0; self.components.len()];
        for (c, _) in self.layout.dissipative() {
            self.stored_at_start[c] = self.stored(c, arguments)?;
        }
        Ok(())
    }

    /// The elastic energy component `c` stores at the model's input
    /// `arguments` ([`super::Dissipation::stored_energy`]; 0 for one that does
    /// not dissipate).
    fn stored(&self, c: usize, arguments: &[f64]) -> Result<f64, Fault> {
        let Some(energy) = self.components[c].component.energy() else {
            return Ok(0.0);
        };
        let args = self.arguments_of(c, arguments).unwrap_or(&[]);
        let result = energy.stored_energy(args);
        result.map_err(|e| self.out_of_range(c, None, e))
    }

    /// The energy component `c`, whose energy state is `z[index]` in the
    /// states last loaded, has dissipated at the model's input `arguments`
    /// there: that state less the elastic energy the component has stored
    /// since the start.
    fn dissipated(&self, c: usize, index: usize, arguments: &[f64]) -> Result<f64, Fault> {
        let stored = self.stored(c, arguments)? - self.stored_at_start.get(c).unwrap_or(&0.0);
        Ok(self.loaded.as_slice()[index] - stored)
    }

    /// The number of events of component `c` that the integrator watches:
    /// none unless its events see the arguments of its value input.
    fn events_of(&self, c: usize) -> usize {
        match self.event_arguments[c] {
            Some(_) => self.components[c].events().len(),
            None => 0,
        }
    }

    /// `(component, local event)` of global event `k`.
    pub fn event(&self, k: usize) -> Option<(usize, usize)> {
        self.event_owners.get(k).copied()
    }

    /// The number of event functions of all components together.
    pub fn event_count(&self) -> usize {
        self.event_owners.len()
    }

    /// The direction of crossing that triggers global event `k`.
    pub fn event_direction(&self, k: usize) -> Direction {
        match self.event(k) {
            Some((c, local)) => self.components[c].events()[local].direction,
            None => Direction::Either,
        }
    }

    /// All event functions, given the model's input arguments at one state.
    pub fn events(&self, arguments: &[f64], g: &mut [f64]) -> Result<(), Fault> {
        for &(c, first, count) in &self.event_blocks {
            let args = self.arguments_of(c, arguments).unwrap_or(&[]);
            let Some(events) = self.components[c].component.events() else {
                continue;
            };
            let result = events.event_values(args, &mut g[first..first + count]);
            result.map_err(|e| self.out_of_range(c, None, e))?;
        }
        Ok(())
    }

    /// Global event function `k` alone, given the model's input arguments
    /// at one state ([`super::Events::event_value`]); `scratch` holds one value
    /// per event of its component.
    pub fn event_value(
        &self,
        k: usize,
        arguments: &[f64],
        scratch: &mut [f64],
    ) -> Result<f64, Fault> {
        let Some((c, local)) = self.event(k) else {
            return Err(Fault::Component(format!("no event {k}")));
        };
        let args = self.arguments_of(c, arguments).unwrap_or(&[]);
        let Some(events) = self.components[c].component.events() else {
            return Err(Fault::Component(format!("no event {k}")));
        };
        let scratch = &mut scratch[..events.list().len()];
        let result = events.event_value(local, args, scratch);
        result.map_err(|e| self.out_of_range(c, None, e))
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
        let args = self.arguments_of(c, arguments).unwrap_or(&[]);
        let named = &mut self.components[c];
        let name = named.name.clone();
        let Some(events) = named.component.events_mut() else {
            return Err(Fault::Component(format!("no event {k}")));
        };
        let result = events.on_event(local, t, args);
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

    /// The components whose columns are written, each with the index of its
    /// first column: those whose value input's arguments are known.
    fn with_columns(&self) -> impl Iterator<Item = (usize, usize)> + '_ {
        let mut first = 0;
        (0..self.components.len())
            .filter(|&c| self.event_arguments[c].is_some())
            .map(move |c| {
                let at = first;
                first += self.components[c].component.columns().len();
                (c, at)
            })
    }

    /// The components' columns, `(NAME.QUANTITY, unit)`, in the order of
    /// [`BoundInputs::column_values`].
    pub fn columns(&self) -> Vec<(String, Option<String>)> {
        let mut columns = Vec::new();
        for (c, _) in self.with_columns() {
            let named = &self.components[c];
            columns.extend(named.component.columns().iter().map(|column| {
                let name = format!("{}.{}", named.name, column.quantity);
                (name, Some(column.unit.to_string()))
            }));
        }
        columns.extend(self.layout.columns(&self.components));
        columns
    }

    /// The values of the components' columns, given the model's input
    /// arguments at one state.
    pub fn column_values(&self, arguments: &[f64]) -> Result<Vec<f64>, Fault> {
        let columns = |(c, _): (usize, usize)| self.components[c].component.columns().len();
        let own: usize = self.with_columns().map(columns).sum();
        let mut values = Vec::with_capacity(own + self.loaded.len());
        for (c, first) in self.with_columns() {
            let component = &self.components[c].component;
            let args = self.arguments_of(c, arguments).unwrap_or(&[]);
            values.resize(first + component.columns().len(), 0.0);
            let result = component.column_values(args, &mut values[first..]);
            result.map_err(|e| self.out_of_range(c, None, e))?;
        }
        let first = values.len();
        values.extend_from_slice(self.loaded.as_slice());
        for (c, index) in self.layout.dissipative() {
            if index < self.loaded.len() {
                values[first + index] = self.dissipated(c, index, arguments)?;
            }
        }
        Ok(values)
    }

    /// For each crush element with columns: its name and the indices among
    /// [`BoundInputs::columns`] of its force and its deflection, for the
    /// force–crush plot.
    pub fn force_deflection_columns(&self) -> Vec<(String, usize, usize)> {
        self.with_columns()
            .filter_map(|(c, first)| {
                let named = &self.components[c];
                let (force, deflection) = named.component.report().force_deflection?;
                Some((named.name.clone(), first + force, first + deflection))
            })
            .collect()
    }

    /// The end of the crash pulse: when the last of the contact elements
    /// named in `names` (all of them when `names` is empty) lost contact;
    /// `None` while one is still in contact, or when none ever was.
    pub fn end_of_contact(&self, names: &[String]) -> Option<f64> {
        let mut end: Option<f64> = None;
        for c in &self.components {
            if !names.is_empty() && !names.contains(&c.name) {
                continue;
            }
            match c.component.report().contact {
                Some(Contact::Touching) => return None,
                Some(Contact::EndedAt(t)) => end = Some(end.map_or(t, |e| e.max(t))),
                Some(Contact::Never) | None => {}
            }
        }
        end
    }

    /// The number of internal states of the run (see [`StateLayout`]).
    pub fn internal_count(&self) -> usize {
        self.layout.len()
    }

    /// The components' internal states at the start of a run, which it
    /// also gives them.
    pub fn initial_internal(&mut self) -> Result<Internal, Fault> {
        let z =
            (self.layout.initial(&self.components)).map_err(|e| Fault::Component(e.to_string()))?;
        self.load(&z);
        Ok(z)
    }

    /// Gives the components their internal states from `z`; an empty `z`
    /// (a state that does not carry them: the equilibrium, a linearization)
    /// leaves them as they were.
    pub fn load(&mut self, z: &Internal) {
        if z.is_empty() || self.layout.is_empty() {
            return;
        }
        self.layout.load(&mut self.components, z);
        // Only the values in use: a copy of the whole buffer moves its
        // capacity at every evaluation.
        self.loaded.assign(z);
    }

    /// The rates `ż` of the internal states last loaded, given the model's
    /// input `arguments` at the same state, into `rates` (of their length).
    pub fn internal_rates(&self, arguments: &[f64], rates: &mut [f64]) -> Result<(), Fault> {
        for (c, offset) in self.layout.stateful() {
            let Some(states) = self.components[c].component.states() else {
                continue;
            };
            let args = self.arguments_of(c, arguments).unwrap_or(&[]);
            let count = states.list().len();
            let result = states.state_rates(args, &mut rates[offset..offset + count]);
            result.map_err(|e| self.out_of_range(c, None, e))?;
        }
        for (c, index) in self.layout.dissipative() {
            let args = self.arguments_of(c, arguments).unwrap_or(&[]);
            rates[index] = (self.components[c].component.energy())
                .map_or(0.0, |energy| energy.dissipated_power(args));
        }
        Ok(())
    }

    /// The energy each dissipative component dissipated, by name \[J\], at
    /// the state last loaded, whose model's input arguments are
    /// `arguments`: its energy state (the integral of
    /// [`super::Dissipation::dissipated_power`]) less the elastic energy it has
    /// stored since the start ([`super::Dissipation::stored_energy`]).
    pub fn dissipated_energies(&self, arguments: &[f64]) -> Result<Vec<(String, f64)>, Fault> {
        (self.layout.dissipative())
            .filter(|&(_, index)| index < self.loaded.len())
            .map(|(c, index)| {
                let energy = self.dissipated(c, index, arguments)?;
                Ok((self.components[c].name.clone(), energy))
            })
            .collect()
    }

    /// The time a component named `name` (any component, if `None`) failed,
    /// if it did: the weld failure of the summary.
    pub fn weld_failure(&self, name: Option<&str>) -> Option<f64> {
        self.components
            .iter()
            .filter(|c| name.is_none_or(|n| n == c.name))
            .find_map(|c| c.component.report().failed_at)
    }
}

/// The messages that name a component whose value, internal state or event
/// is not finite.
impl BoundInputs {
    /// What entry `index` of the internal states' rates `ż` is, with its
    /// `rate` that is not finite, the state it has and the arguments of its
    /// component's value input among the model's input `arguments`: `the
    /// rate of state `z` of bouc_wen component `hinge` (-inf, at z = 2e0,
    /// arguments 1e-2, 1e0)`.
    pub fn name_internal_rate(&self, index: usize, rate: f64, arguments: &[f64]) -> String {
        let Some((c, state)) = self.layout.owner(index) else {
            return format!("the rate of internal state {index} ({rate})");
        };
        let named = &self.components[c];
        let args = self.arguments_of(c, arguments).unwrap_or(&[]);
        let at = format!("arguments {}", listed(args));
        match state {
            Some(k) => {
                let state = named.states()[k].quantity;
                let z = self
                    .loaded
                    .as_slice()
                    .get(index)
                    .copied()
                    .unwrap_or(f64::NAN);
                format!(
                    "the rate of state `{state}` of {} ({rate:e}, at {state} = {z:e}, {at})",
                    named.describe()
                )
            }
            None => format!(
                "the dissipated power of {} ({rate:e}, at {at})",
                named.describe()
            ),
        }
    }

    /// Global event function `k` with its `value` that is not finite: `the
    /// function of event `peak crush` of crush component `bumper` (NaN)`.
    pub fn name_event(&self, k: usize, value: f64) -> String {
        let Some((c, local)) = self.event(k) else {
            return format!("event function {k} ({value})");
        };
        let named = &self.components[c];
        let event = named.events()[local].name;
        format!(
            "the function of event `{event}` of {} ({value})",
            named.describe()
        )
    }

    /// What input `input` is, called with the finite `args` and giving
    /// `value`, which is not finite: `input `element` (the force of
    /// bouc_wen component `hinge` at arguments 1e-2, 1e0, its states z =
    /// 2e0)`; `None` for an input no component answers.
    pub fn name_input(&self, input: usize, args: &[f64]) -> Option<String> {
        let binding = (*self.bindings.get(input)?)?;
        let named = self.components.get(binding.component)?;
        let quantity = match binding.port {
            Port::Value => (named.component.columns().first()).map_or("value", |c| c.quantity),
            Port::Stiffness => "tangent stiffness",
            Port::Damping => "tangent damping",
        };
        let mut text = format!(
            "input `{}` (the {quantity} of {} at arguments {}",
            self.input_names[input],
            named.describe(),
            listed(args)
        );
        let stateful = self
            .layout
            .stateful()
            .find(|&(c, _)| c == binding.component);
        let states = named.states();
        let loaded = stateful.and_then(|(_, at)| self.loaded.as_slice().get(at..at + states.len()));
        if let Some(z) = loaded {
            let values: Vec<String> = (states.iter().zip(z))
                .map(|(s, v)| format!("{} = {v:e}", s.quantity))
                .collect();
            text.push_str(&format!(", its state {}", values.join(", ")));
        }
        text.push(')');
        Some(text)
    }
}

impl InputFunctions for BoundInputs {
    fn value(&self, input: usize, args: &[f64]) -> f64 {
        if self.standing_in
            && let Some(Some(cubic)) = self.stand_ins.get(input)
        {
            return cubic.at(args[0]);
        }
        match self.own_value(input, args) {
            Some((_, Ok(v))) => v,
            Some((component, Err(e))) => self.fail(self.out_of_range(component, Some(input), e)),
            None => self.unresolved_value(input, args),
        }
    }
}

impl BoundInputs {
    /// The value of an input call that is not resolved: unbound, called
    /// with the wrong number of arguments (both faults), or bound after
    /// [`BoundInputs::new`].
    fn unresolved_value(&self, input: usize, args: &[f64]) -> f64 {
        let name = self.input_names.get(input).map_or("?", String::as_str);
        let Some(Some(binding)) = self.bindings.get(input) else {
            return self.fail(Fault::Component(format!("input function `{name}` has no value: bind it in the scenario or give it with --set {name}=VALUE")));
        };
        let named = &self.components[binding.component];
        if let Some((needed, _)) = named.component.arguments()
            && args.len() != needed
        {
            // The scenario checks this where it knows the input's arguments;
            // a compiled model does not tell them for inputs only its
            // Jacobians call.
            return self.fail(Fault::Component(format!(
                "input `{name}` is called with {} argument{}, but {} component `{}` needs {needed}",
                args.len(),
                if args.len() == 1 { "" } else { "s" },
                named.component.kind(),
                named.name
            )));
        }
        match named.component.value(binding.port, args) {
            Ok(v) => v,
            Err(e) => self.fail(self.out_of_range(binding.component, Some(input), e)),
        }
    }
}

/// Whether two argument lists are the same numbers, NaN included.
fn same_bits(a: &[f64], b: &[f64]) -> bool {
    a.len() == b.len() && a.iter().zip(b).all(|(x, y)| x.to_bits() == y.to_bits())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::components::crush::{CrushElement, LoadingCurve, Unloading};
    use crate::curve::SecantCurve;

    #[test]
    fn an_input_of_the_wrong_arity_fails_instead_of_panicking() {
        // What a compiled model can bring past the scenario check: a crush
        // element's stiffness port on an input of one argument.
        let crush = CrushElement::new(
            LoadingCurve::SecantStiffness(SecantCurve::constant(1.0e6)),
            SecantCurve::constant(1.0e3),
            Unloading::Elastic,
            1.0,
            true,
        );
        let inputs = BoundInputs::new(
            vec![NamedComponent {
                name: "front_end".into(),
                component: Box::new(crush),
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

    /// A column of zeros answers 0 without its component at finite times,
    /// and as its component does elsewhere: NaN at NaN when it extrapolates,
    /// an error outside its rows under `error` (where it is not constant).
    #[test]
    fn a_column_of_zeros_answers_as_its_component_does() {
        use crate::components::tabulated::Tabulated;
        use crate::curve::{Curve, Outside};
        let column = |outside| {
            let curve = Curve::new(vec![0.0, 1.0], vec![0.0, 0.0], outside).unwrap();
            NamedComponent {
                name: format!("barrier.{outside:?}"),
                component: Box::new(Tabulated {
                    curve,
                    stop_at_kinks: false,
                }),
            }
        };
        let value = |c| {
            Some(Binding {
                component: c,
                port: Port::Value,
            })
        };
        let constant = NamedComponent {
            name: "push".into(),
            component: Box::new(crate::components::constant::Constant { value: 3.5 }),
        };
        let inputs = BoundInputs::new(
            vec![
                column(Outside::Extrapolate),
                column(Outside::Error),
                constant,
            ],
            vec![value(0), value(1), value(2)],
            vec![None, None, None],
            vec!["fx".into(), "fz".into(), "push".into()],
        );
        assert_eq!(inputs.resolved[0].unwrap().constant, Some(0.0));
        assert_eq!(inputs.resolved[1].unwrap().constant, None);
        assert_eq!(inputs.resolved[2].unwrap().constant, Some(3.5));
        assert_eq!(inputs.value(2, &[1.0, 2.0]), 3.5);
        // A constant given a new value (an FMU's input) answers it.
        let mut inputs = inputs;
        let new_value = Box::new(crate::components::constant::Constant { value: -1.0 });
        assert!(inputs.replace(2, new_value));
        assert_eq!(inputs.value(2, &[1.0, 2.0]), -1.0);
        assert!(!inputs.replace(
            3,
            Box::new(crate::components::constant::Constant { value: 0.0 })
        ));
        assert_eq!(inputs.value(0, &[7.0]).to_bits(), 0.0f64.to_bits());
        assert!(inputs.value(0, &[f64::NAN]).is_nan());
        assert_eq!(inputs.take_failure(), None);
        assert_eq!(inputs.value(1, &[0.5]).to_bits(), 0.0f64.to_bits());
        assert!(inputs.value(1, &[2.0]).is_nan());
        assert!(matches!(
            inputs.take_failure(),
            Some(Fault::OutOfRange { x, .. }) if x == 2.0
        ));
    }

    /// A crush element on the input `element(u, v)`, with its events seen.
    fn crush_on_element() -> BoundInputs {
        let crush = CrushElement::new(
            LoadingCurve::SecantStiffness(SecantCurve::constant(1.0e6)),
            SecantCurve::constant(1.0e3),
            Unloading::Elastic,
            1.0,
            true,
        );
        let named = NamedComponent {
            name: "bumper".into(),
            component: Box::new(crush),
        };
        let binding = Binding {
            component: 0,
            port: Port::Value,
        };
        let names = vec!["element".into()];
        BoundInputs::new(vec![named], vec![Some(binding)], vec![Some((0, 2))], names)
    }

    /// The messages of a component that is not finite name it by its
    /// section and kind, and say which event, input or quantity, with the
    /// value and the arguments (the strings are the format documented on
    /// each method, written out here).
    #[test]
    fn a_component_that_is_not_finite_is_named() {
        let inputs = crush_on_element();
        assert_eq!(
            inputs.name_event(0, f64::NAN),
            "the function of event `peak crush` of crush component `bumper` (NaN)"
        );
        assert_eq!(
            inputs.name_event(2, f64::INFINITY),
            "the function of event `separation` of crush component `bumper` (inf)"
        );
        assert_eq!(
            inputs.name_event(99, f64::INFINITY),
            "event function 99 (inf)"
        );
        assert_eq!(
            inputs.name_input(0, &[0.01, -2.0]).unwrap(),
            "input `element` (the force of crush component `bumper` at arguments 1e-2, -2e0)"
        );
        // Its dissipated energy is its one internal state.
        assert_eq!(
            inputs.name_internal_rate(0, f64::NAN, &[0.01, -2.0]),
            "the dissipated power of crush component `bumper` (NaN, at arguments 1e-2, -2e0)"
        );
    }

    /// A Bouc–Wen spring's state is named, with its value.
    #[test]
    fn a_state_rate_that_is_not_finite_names_the_state() {
        use crate::components::bouc_wen::BoucWen;
        let spring = BoucWen::new(1e3, 0.01, 0.1, 1.0, 0.5, 0.5, 2.0, 1e200);
        let named = NamedComponent {
            name: "hinge".into(),
            component: Box::new(spring),
        };
        let binding = Binding {
            component: 0,
            port: Port::Value,
        };
        let names = vec!["element".into()];
        let mut inputs =
            BoundInputs::new(vec![named], vec![Some(binding)], vec![Some((0, 2))], names);
        inputs.initial_internal().unwrap();
        assert_eq!(
            inputs.name_internal_rate(0, f64::NEG_INFINITY, &[0.0, 1.0]),
            "the rate of state `z` of bouc_wen component `hinge` (-inf, at z = 1e200, arguments 0e0, 1e0)"
        );
        assert_eq!(
            inputs.name_input(0, &[0.0, 1.0]).unwrap(),
            "input `element` (the force of bouc_wen component `hinge` at arguments 0e0, 1e0, its state z = 1e200)"
        );
    }
}
