//! Crash components that supply a model's input functions: the crush
//! element (a force–deflection curve or the secant stiffness of eqs 1–2,
//! hysteresis, contact, gap), a failing torsional weld,
//! tabulated time histories and constants, contact laws cited by name,
//! a Kelvin–Voigt element and friction.
//!
//! # The contract of a component
//!
//! A component is a type that implements [`Component`]. A model's input
//! function reads one of its [`Port`]s: its value, or the value's derivative
//! with respect to the input's first argument (tangent stiffness) or second
//! argument (tangent damping). A component
//!
//! * says what it is ([`Component::kind`], the `type` of its scenario
//!   section) and how many arguments the inputs bound to it must take
//!   ([`Component::arguments`]), which the scenario checks;
//! * computes each port at an input's arguments ([`Component::value`]);
//! * lists the quantities worth plotting, with their units
//!   ([`Component::columns`]: a crush element's force and deflection, a
//!   weld's moment and angle; none by default) and gives their values at its
//!   value input's arguments ([`Component::column_values`]): each is a
//!   trajectory column `NAME.QUANTITY [unit]`;
//! * says how smooth its ports are within a step
//!   ([`Component::smoothness`]: smooth, with kinks, or linear between
//!   points at which steps may end);
//! * tells the summary and the plots what they read of its run
//!   ([`Component::report`]: a crush element's force and deflection
//!   columns and its contact, a weld's failure; nothing by default).
//!
//! What a component can do beyond that is a capability, a small trait it
//! implements on itself and hands out from an accessor of [`Component`]
//! (`Some(self)`; `None` for a component without it). The accessors are
//! required, so that a component without events says so in its `impl`:
//!
//! * [`Events`] ([`Component::events`], [`Component::events_mut`]): a
//!   change of regime (peak crush, separation, failure) is an event, so
//!   each port is smooth within a step. The component lists its events
//!   with their directions ([`Events::list`]), gives their functions
//!   ([`Events::event_values`]), applies one when the integrator finds its
//!   zero ([`Events::on_event`]) and starts every run in its initial
//!   regime ([`Events::start`]);
//! * [`States`] ([`Component::states`], [`Component::states_mut`]):
//!   internal states `z` with `ż = g(z, args)` (a hysteretic variable, a
//!   dashpot's displacement), which the integrator carries and every run
//!   starts at their initial values;
//! * [`Dissipation`] ([`Component::energy`]): a damper, contact or
//!   friction gives the power it dissipates
//!   ([`Dissipation::dissipated_power`]), or the power it absorbs with the
//!   elastic energy it stores of it ([`Dissipation::stored_energy`]: a
//!   spring that unloads plastically, separates or breaks).
//!
//! A component with events or states reads them from the arguments
//! of its value input: that input must be called at one place of the
//! dynamics (the scenario checks it), and [`BoundInputs`] passes its
//! arguments to the component's events, states, columns and power.
//!
//! Its scenario section, `[components.NAME]` with `type = "KIND"`, is a
//! struct that implements the crate's `Section` trait: it reads the
//! section's entries (`serde`, `deny_unknown_fields`), checks them, adds the
//! component (or components) to the scenario's `Binder` and binds the
//! model's inputs to their ports (`Binder::bind`, `Binder::bind_ports`).
//!
//! # How to add a component
//!
//! A new component touches one new file and two lines of this one:
//!
//! 1. Write `sim/src/components/KIND.rs` with
//!    * the component: `#[derive(Clone, Debug)]`, `impl Component` with
//!      `kind`, `arguments`, `value` and the five accessors `events`,
//!      `events_mut`, `states`, `states_mut` and `energy`, each `None` or
//!      `Some(self)`, written as one line
//!      `capabilities!(events: yes, states: no, energy: no);`; `constant`,
//!      `columns`, `column_values`, `smoothness`
//!      and `report` have defaults. One with columns lists them in a
//!      `const COLUMNS: &[Column]` and overrides `columns` and
//!      `column_values`;
//!    * for each capability it has, its `impl`: `impl Events` with its
//!      events in a `const EVENTS: &[Event]`; `impl States`, where a single
//!      internal state writes
//!      `one_state!(FIELD: "QUANTITY" ["UNIT"], from INITIAL_FIELD);` for
//!      `list`, `initial_states` and `set_states`, and gives its
//!      `state_rates`; `impl Dissipation`;
//!    * its section: `#[derive(Deserialize)]`,
//!      `#[serde(deny_unknown_fields)]`, a `pub(crate) struct KindSection`
//!      of its entries (with `#[serde(default = …)]` for optional ones) and
//!      `impl Section`. `build` checks the entries (`entry` has `finite`,
//!      `positive` and `non_negative`, `crate::curve` has `outside`, which name
//!      the entry in their messages), adds the component with
//!      `binder.add(name, Box::new(component))` and binds inputs to its
//!      ports: `binder.bind_ports(&self.inputs, "force", c, name)` for an
//!      `inputs = { force, stiffness, damping }` entry (`Ports`), or
//!      `binder.bind(key, input, (c, Port::Value))` for one input.
//!      And `impl SectionUnits` with the unit of each of its number entries
//!      (`("gap", Measure::One("m"))`), in which a scenario may write them
//!      with a unit of their own (`"25 mm"`); an empty list where none has
//!      a fixed unit.
//!
//!    [`weld`] is a short example with events, [`constant`] one without.
//! 2. Here: declare the file (`pub mod KIND;`) and register its section with
//!    one line of the `components!` list below, `KIND => KIND::KindSection,`.
//!    The name before the arrow is the section's `type` in scenario files,
//!    which [`Component::kind`] must return (checked in debug builds).
//!
//! Nothing else names a component: scenario files, the binding of inputs,
//! events, the summary and the plots reach every component through
//! [`Component`], its capabilities and `Section`. `test_spring.rs`, registered for tests only, is a complete
//! example with an event that fires in a simulation.

/// A component's capability accessors, written in its `impl Component`
/// (`capabilities!(events: yes, states: no, energy: yes);`): `yes` returns the
/// component itself as its [`Events`], [`States`] or [`Dissipation`] (which it
/// then implements), `no` returns `None`. One line keeps each choice visible
/// and the shared and mutable accessors of a capability in step.
macro_rules! capabilities {
    (events: $events:ident, states: $states:ident, energy: $energy:ident) => {
        capabilities!(@events $events);
        capabilities!(@states $states);
        capabilities!(@energy $energy);
    };
    (@events yes) => {
        fn events(&self) -> Option<&dyn $crate::components::Events> {
            Some(self)
        }

        fn events_mut(&mut self) -> Option<&mut dyn $crate::components::Events> {
            Some(self)
        }
    };
    (@events no) => {
        fn events(&self) -> Option<&dyn $crate::components::Events> {
            None
        }

        fn events_mut(&mut self) -> Option<&mut dyn $crate::components::Events> {
            None
        }
    };
    (@states yes) => {
        fn states(&self) -> Option<&dyn $crate::components::States> {
            Some(self)
        }

        fn states_mut(&mut self) -> Option<&mut dyn $crate::components::States> {
            Some(self)
        }
    };
    (@states no) => {
        fn states(&self) -> Option<&dyn $crate::components::States> {
            None
        }

        fn states_mut(&mut self) -> Option<&mut dyn $crate::components::States> {
            None
        }
    };
    (@energy yes) => {
        fn energy(&self) -> Option<&dyn $crate::components::Dissipation> {
            Some(self)
        }
    };
    (@energy no) => {
        fn energy(&self) -> Option<&dyn $crate::components::Dissipation> {
            None
        }
    };
}

/// The plumbing of a component with one internal state, written in its
/// `impl States` (`one_state!(z: "z" ["m"], from z0);`): the state's column
/// `NAME.QUANTITY [UNIT]` ([`States::list`]), the field that holds
/// its current value (`z`) and the field of its initial value (`z0`).
/// [`States::initial_states`] gives that value and
/// [`States::set_states`] takes the integrator's.
macro_rules! one_state {
    ($state:ident: $quantity:literal [$unit:literal], from $initial:ident) => {
        fn list(&self) -> &'static [$crate::components::Column] {
            const STATES: &[$crate::components::Column] = &[$crate::components::Column {
                quantity: $quantity,
                unit: $unit,
            }];
            STATES
        }

        fn initial_states(&self, z: &mut [f64]) {
            z[0] = self.$initial;
        }

        fn set_states(&mut self, z: &[f64]) {
            self.$state = z[0];
        }
    };
}

pub mod bouc_wen;
pub mod bound;
pub mod constant;
pub mod contact;
pub mod crush;
pub mod dahl;
pub mod friction;
pub mod held;
mod integral;
pub mod kelvin_voigt;
pub mod lugre;
pub mod maxwell;
pub(crate) mod section;
pub mod stand_in;
pub mod states;
pub mod stick_slip;
pub mod tabulated;
#[cfg(test)]
mod test_spring;
pub mod weld;

use crate::curve::OutOfRange;
use crate::entry::EntryError;
use crate::files::Files;
use crate::ode::Direction;
use crate::table::Table;
pub use bound::{Binding, BoundInputs, NamedComponent};
pub(crate) use section::Binder;
pub use stand_in::StandIn;
use std::fmt;
use std::path::Path;
use std::sync::Arc;

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

/// An event function of a component: a change of regime when it crosses
/// zero in `direction`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Event {
    /// What happens, for messages (`"peak crush"`).
    pub name: &'static str,
    /// The crossings that trigger it.
    pub direction: Direction,
}

/// A quantity of a component worth plotting: the trajectory column
/// `NAME.QUANTITY [UNIT]` of component `NAME`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Column {
    /// What it is (`force`, `deflection`).
    pub quantity: &'static str,
    /// Its unit, as spec files write units (`N`, `N*m`).
    pub unit: &'static str,
}

/// A crash component: the source of one or more of a model's input
/// functions (see the module documentation for the contract).
///
/// The accessors of its capabilities ([`Events`], [`States`],
/// [`Dissipation`]) are required, so that a component with events cannot
/// leave them out by default; a component without says `None`.
pub trait Component: ComponentClone + fmt::Debug + Send {
    /// What the scenario calls this kind of component: the `type` its
    /// section is registered under.
    fn kind(&self) -> &'static str;

    /// How many arguments the input functions bound to this component must
    /// have, and what they are; `None`: any number.
    fn arguments(&self) -> Option<(usize, &'static str)>;

    /// The value of `port` at an input's arguments `args`, which hold as many
    /// values as [`Component::arguments`] asks for. `Stiffness` is the
    /// derivative of the value with respect to the first argument,
    /// `Damping` with respect to the second.
    fn value(&self, port: Port, args: &[f64]) -> Result<f64, OutOfRange>;

    /// The value of `port` where it is the same at every finite argument
    /// and in every state (a table column of zeros): the inputs bound to
    /// it then answer without calling the component. `None` (the default)
    /// otherwise. Asked once, when the inputs are bound.
    fn constant(&self, _port: Port) -> Option<f64> {
        None
    }

    /// Its events, if it changes regime (peak crush, separation,
    /// failure): [`Events`], usually `Some(self)`; `None` for a component
    /// without events. Required, with [`Component::events_mut`], so that a
    /// component's events are never left out by default.
    fn events(&self) -> Option<&dyn Events>;

    /// [`Component::events`], to apply an event or start a run: `Some`
    /// exactly when that is.
    fn events_mut(&mut self) -> Option<&mut dyn Events>;

    /// Its internal states, if it has any (a hysteretic variable, a
    /// dashpot's displacement): [`States`], usually `Some(self)`; `None`
    /// for a component without.
    fn states(&self) -> Option<&dyn States>;

    /// [`Component::states`], to set them: `Some` exactly when that is.
    fn states_mut(&mut self) -> Option<&mut dyn States>;

    /// How it dissipates energy, if it does (a damper, contact, friction):
    /// [`Dissipation`], usually `Some(self)`; `None` for a component that
    /// dissipates nothing, at any arguments. Asked once, to lay out the
    /// run's states (one dissipated energy per dissipative component).
    fn energy(&self) -> Option<&dyn Dissipation>;

    /// The quantities worth plotting, in the order
    /// [`Component::column_values`] writes them; none by default.
    fn columns(&self) -> &'static [Column] {
        &[]
    }

    /// The values of [`Component::columns`] at its value input's arguments
    /// `args`, in its current state, into `out` (one per column).
    fn column_values(&self, _args: &[f64], _out: &mut [f64]) -> Result<(), OutOfRange> {
        Ok(())
    }

    /// What the summary and the plots read of the component's run
    /// ([`Report`]); nothing (the default) for most components.
    fn report(&self) -> Report {
        Report::default()
    }

    /// How smooth the component's ports are within a step of the
    /// integration ([`Smoothness`]): the output samples of a step over
    /// which every input the dynamics calls is smooth take `q̈` from the
    /// step's dense output. [`Smoothness::Unknown`] (the default) has them
    /// solve for it.
    fn smoothness(&self) -> Smoothness {
        Smoothness::Unknown
    }
}

/// The events of a component that changes regime (see
/// [`Component::events`]): a change of regime is an event, so that each
/// port is smooth within a step.
pub trait Events {
    /// The events, in index order, with their directions.
    fn list(&self) -> &'static [Event];

    /// The event functions at its value input's arguments `args`, one per
    /// [`Events::list`] entry, into `g`. One that does not apply in the
    /// current regime is held at a constant of the sign that cannot trigger
    /// it.
    fn event_values(&self, args: &[f64], g: &mut [f64]) -> Result<(), OutOfRange>;

    /// Event function `k` alone at `args`, the same value as
    /// [`Events::event_values`] gives it: what locating a crossing of
    /// it evaluates. `scratch` holds one value per event; by default every
    /// event function, into `scratch`.
    fn event_value(&self, k: usize, args: &[f64], scratch: &mut [f64]) -> Result<f64, OutOfRange> {
        self.event_values(args, scratch)?;
        Ok(scratch[k])
    }

    /// Applies event `k` at time `t` and its value input's arguments `args`;
    /// returns a description of the change, or an empty one for an event
    /// that changes no regime (a kink of a curve crossed, see
    /// [`held`]), which the run's event log leaves out.
    fn on_event(&mut self, k: usize, t: f64, args: &[f64]) -> Result<String, OutOfRange>;

    /// Puts the component in its initial regime for a run that starts with
    /// its value input's arguments `args` (`None` when the dynamics does
    /// not call that input).
    fn start(&mut self, args: Option<&[f64]>) -> Result<(), OutOfRange>;
}

/// The internal states `z` of a component (see [`Component::states`]):
/// first-order states with `ż = g(z, args)` that the integrator carries
/// beside `q` and `q̇`. A run starts them at [`States::initial_states`].
pub trait States {
    /// The states, with their units: each is a trajectory column
    /// `NAME.STATE [unit]`.
    fn list(&self) -> &'static [Column];

    /// The initial values of the states, into `z` (the scenario's, or the
    /// component's documented default).
    fn initial_states(&self, z: &mut [f64]);

    /// Takes the current values of the states, which
    /// [`Component::value`] and the other methods then read. The problem
    /// calls it before every evaluation at a state of the run.
    fn set_states(&mut self, z: &[f64]);

    /// `ż = g(z, args)` at its value input's arguments `args` and the
    /// states last set, into `rates`.
    fn state_rates(&self, args: &[f64], rates: &mut [f64]) -> Result<(), OutOfRange>;
}

/// How a component dissipates energy (see [`Component::energy`]).
pub trait Dissipation {
    /// The power the component dissipates \[W\] at its value input's
    /// arguments `args` (and its internal states, for one that has them).
    /// Its integral, less the growth of [`Dissipation::stored_energy`] for
    /// a component that returns the power it absorbs instead, is the
    /// energy it dissipated, carried as an internal state of the run and
    /// reported by name.
    fn dissipated_power(&self, args: &[f64]) -> f64;

    /// The elastic energy \[J\] a dissipative component stores at its
    /// value input's arguments `args` in its current regime, for one whose
    /// [`Dissipation::dissipated_power`] is the power it absorbs, part of
    /// which it stores and may give back (a crush spring, a weld); 0 (the
    /// default) for one whose power is dissipated as it is absorbed. The
    /// energy reported as dissipated is the integral of that power less
    /// what this energy has grown by since the start: the work absorbed
    /// less the elastic energy still stored. An event may change it (a
    /// spring that separates or breaks releases it); the dissipated energy
    /// then steps by as much.
    fn stored_energy(&self, _args: &[f64]) -> Result<f64, OutOfRange> {
        Ok(0.0)
    }
}

/// How smooth a component's ports are within a step of the integration
/// (see [`Component::smoothness`]): smooth means continuously
/// differentiable in the input's arguments, so that `q̈` is so in time
/// and the derivative of a step's dense output follows it.
#[derive(Clone, Debug, PartialEq)]
pub enum Smoothness {
    /// Not known to be smooth.
    Unknown,
    /// Smooth within every step: in its current state each port is a
    /// smooth function of the arguments, continued past the events that
    /// change it (a held segment of a curve, a regime).
    Smooth,
    /// Smooth except at these values of its first argument, in increasing
    /// order, where a port's slope or value jumps: an input of time is
    /// smooth over a step with none of them inside.
    Kinks(Vec<f64>),
    /// Continuous, and linear in its first argument between these values
    /// of it, in increasing order (the points of a table interpolated
    /// linearly): kinks as [`Smoothness::Kinks`], with straight lines
    /// between them.
    Linear {
        /// The values of the first argument where the slope jumps.
        points: Vec<f64>,
        /// Whether the integrator ends a step at each of them, rather than
        /// step across, for an input whose argument is the time (a table
        /// with `stop_at_kinks`).
        stops: bool,
    },
}

impl Smoothness {
    /// The values of the first argument where a port's slope or value may
    /// jump, for [`Smoothness::Kinks`] and [`Smoothness::Linear`].
    pub fn kinks(&self) -> Option<&[f64]> {
        match self {
            Smoothness::Kinks(points) | Smoothness::Linear { points, .. } => Some(points),
            Smoothness::Unknown | Smoothness::Smooth => None,
        }
    }

    /// The values of the first argument at which the integrator ends a
    /// step, for an input whose argument is the time: the points of a
    /// [`Smoothness::Linear`] that `stops`; none otherwise.
    pub fn stops(&self) -> &[f64] {
        match self {
            Smoothness::Linear {
                points,
                stops: true,
            } => points,
            _ => &[],
        }
    }
}

/// What a component tells the summary and the plots about its run (see
/// [`Component::report`]): each field `None` for a component it does not
/// concern.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Report {
    /// For the force–crush plot: the indices among [`Component::columns`]
    /// of a crush element's force and of its deflection, both positive in
    /// compression.
    pub force_deflection: Option<(usize, usize)>,
    /// The time the component failed in the run, if it did.
    pub failed_at: Option<f64>,
    /// For a contact element (a crush element that only pushes): whether
    /// it is in contact now, or since when it is not.
    pub contact: Option<Contact>,
}

/// The state of a contact element's contact (see [`Report::contact`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Contact {
    /// In contact now.
    Touching,
    /// Out of contact since this time \[s\].
    EndedAt(f64),
    /// Not in contact in this run so far (it started separated and stayed).
    Never,
}

/// Copies a boxed [`Component`]; implemented for every component that is
/// `Clone`, so that [`BoundInputs`] is.
pub trait ComponentClone {
    /// A copy of the component, in its current state.
    fn clone_box(&self) -> Box<dyn Component>;
}

impl<T: Component + Clone + 'static> ComponentClone for T {
    fn clone_box(&self) -> Box<dyn Component> {
        Box::new(self.clone())
    }
}

impl Clone for Box<dyn Component> {
    fn clone(&self) -> Self {
        self.clone_box()
    }
}

/// A `[components.NAME]` section of a scenario file, as read for one kind
/// of component.
pub(crate) trait Section {
    /// Reads the data file the section names, if any, from `files`, and
    /// checks that what
    /// it needs is there — before anything is bound, so that a missing file
    /// is reported as such. The default: no data file.
    fn load_table(
        &self,
        _files: &dyn Files,
        _name: &str,
        _base: &Path,
    ) -> Result<Option<Arc<Table>>, EntryError> {
        Ok(None)
    }

    /// Checks the section `[components.{name}]`, adds its components to
    /// `binder` and binds the model's inputs to their ports.
    fn build(&self, name: &str, binder: &mut Binder) -> Result<(), EntryError>;
}

/// The unit of a number entry of a section, in which it may be written
/// with a unit of its own (`force_values = ["4 MN", "6 MN"]`): see
/// [`crate::quantity`].
pub(crate) enum Measure {
    /// The number, or each number of a list, is in this unit.
    One(&'static str),
    /// A list of pairs, `[[angle, moment], …]`: the first of each pair is
    /// in the first unit, the second in the second.
    Pairs(&'static str, &'static str),
}

/// The units of a section's number entries, by key: the one list a
/// scenario's quantities (`"4 MN"`) are read with. An entry not listed
/// takes a plain number only (a pure number, or one whose unit depends on
/// the model, such as a contact's stiffness of `N/m^n`).
pub(crate) trait SectionUnits {
    /// `(key, its unit)` per number entry.
    const UNITS: &'static [(&'static str, Measure)];
}

/// The registry: from `KIND => module::Section` lines, the serde enum of
/// the sections (tagged by `type = "KIND"`) and their dispatch.
macro_rules! components {
    ($($(#[$attr:meta])* $kind:ident => $section:ty,)*) => {
        /// A `[components.NAME]` section of a scenario file, by its `type`.
        #[derive(serde::Deserialize)]
        #[serde(tag = "type", deny_unknown_fields)]
        #[allow(non_camel_case_types)]
        pub(crate) enum ComponentSection {
            $(
                #[doc = concat!("`type = \"", stringify!($kind), "\"`")]
                $(#[$attr])* $kind($section),
            )*
        }

        impl ComponentSection {
            /// The `type` of the component as written.
            pub(crate) fn kind(&self) -> &'static str {
                match self {
                    $($(#[$attr])* ComponentSection::$kind(_) => stringify!($kind),)*
                }
            }

            /// Every kind of section, as its `type` is written.
            #[cfg(test)]
            pub(crate) const KINDS: &[&str] = &[$($(#[$attr])* stringify!($kind),)*];

            /// The units of the number entries of the section of `kind`
            /// ([`SectionUnits`]); `None` for a kind there is not.
            pub(crate) fn units_of(kind: &str) -> Option<&'static [(&'static str, Measure)]> {
                match kind {
                    $($(#[$attr])* stringify!($kind) => Some(<$section as SectionUnits>::UNITS),)*
                    _ => None,
                }
            }

            /// The section's reading and building.
            pub(crate) fn section(&self) -> &dyn Section {
                match self {
                    $($(#[$attr])* ComponentSection::$kind(section) => section,)*
                }
            }
        }
    };
}

components! {
    crush => crush::CrushSection,
    weld => weld::WeldSection,
    table => tabulated::TableSection,
    constant => constant::ConstantSection,
    contact => contact::ContactSection,
    kelvin_voigt => kelvin_voigt::KelvinVoigtSection,
    friction => friction::FrictionSection,
    stick_slip => stick_slip::StickSlipSection,
    bouc_wen => bouc_wen::BoucWenSection,
    maxwell => maxwell::MaxwellSection,
    lugre => lugre::LuGreSection,
    dahl => dahl::DahlSection,
    #[cfg(test)]
    test_spring => test_spring::SpringSection,
}

impl ComponentSection {
    /// Builds the section `[components.{name}]` into `binder` (see
    /// [`Section::build`]).
    pub(crate) fn build(&self, name: &str, binder: &mut Binder) -> Result<(), EntryError> {
        let first = binder.component_count();
        self.section().build(name, binder)?;
        debug_assert!(
            binder.kinds_from(first).all(|kind| kind == self.kind()),
            "a `{}` section built a component of another kind",
            self.kind()
        );
        Ok(())
    }
}

/// Asserts that [`Events::event_value`] gives each event function of
/// `component` at `args` bit for bit as [`Events::event_values`] does.
#[cfg(test)]
pub(crate) fn assert_event_value_is_event_values(component: &dyn Events, args: &[f64]) {
    let n = component.list().len();
    let mut all = vec![0.0; n];
    component.event_values(args, &mut all).unwrap();
    for (k, value) in all.iter().enumerate() {
        let mut scratch = vec![f64::NAN; n];
        let alone = component.event_value(k, args, &mut scratch).unwrap();
        assert_eq!(alone.to_bits(), value.to_bits(), "event {k} at {args:?}");
    }
}
