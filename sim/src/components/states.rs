//! The internal states of a scenario's components, laid out in one vector
//! for the integrator: first each component's own states
//! ([`super::Component::states`]), in component order, then the energy each
//! dissipative component ([`super::Component::energy`]) has
//! dissipated since the start of the run. The energies are quadratures
//! ([`Internal::quadratures`]): integrated with each step, they do not
//! control its size.

use super::NamedComponent;
use crate::ode::{INTERNAL_CAPACITY, Internal};

/// Where each component's internal states lie in the run's vector `z`.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct StateLayout {
    /// `(component, offset, count)` of each component with states.
    states: Vec<(usize, usize, usize)>,
    /// `(component, index)` of each dissipative component's energy.
    energies: Vec<(usize, usize)>,
    /// The length of `z`.
    len: usize,
}

/// The name of a dissipative component's energy column.
pub const DISSIPATED: &str = "dissipated_energy";

impl StateLayout {
    /// The layout of `components`, given the arguments of each one's value
    /// input (`None`: its states and power cannot be evaluated, so it has
    /// none in the run).
    pub fn of(components: &[NamedComponent], arguments: &[Option<(usize, usize)>]) -> StateLayout {
        let mut layout = StateLayout::default();
        for (c, named) in components.iter().enumerate() {
            let count = named.states().len();
            if count > 0 && arguments[c].is_some() {
                layout.states.push((c, layout.len, count));
                layout.len += count;
            }
        }
        for (c, named) in components.iter().enumerate() {
            if arguments[c].is_none() {
                continue;
            }
            if named.component.energy().is_some() {
                layout.energies.push((c, layout.len));
                layout.len += 1;
            }
        }
        layout
    }

    /// The length of `z`.
    pub fn len(&self) -> usize {
        self.len
    }

    /// `true` when the run has no internal states.
    pub fn is_empty(&self) -> bool {
        self.len == 0
    }

    /// The initial `z`: each component's initial states, no energy
    /// dissipated; an error when there are more than the integrator
    /// carries.
    pub fn initial(&self, components: &[NamedComponent]) -> Result<Internal, TooManyStates> {
        let z = Internal::zeros(self.len).ok_or(TooManyStates { states: self.len })?;
        let mut z = z.with_quadratures(self.energies.len());
        for &(c, offset, count) in &self.states {
            let slice = &mut z.as_mut_slice()[offset..offset + count];
            if let Some(states) = components[c].component.states() {
                states.initial_states(slice);
            }
        }
        Ok(z)
    }

    /// Gives each component its states from `z`.
    pub fn load(&self, components: &mut [NamedComponent], z: &Internal) {
        for &(c, offset, count) in &self.states {
            let slice = &z.as_slice()[offset..offset + count];
            if let Some(states) = components[c].component.states_mut() {
                states.set_states(slice);
            }
        }
    }

    /// The components with states, each with its offset in `z`.
    pub fn stateful(&self) -> impl Iterator<Item = (usize, usize)> + '_ {
        self.states.iter().map(|&(c, offset, _)| (c, offset))
    }

    /// The dissipative components, each with the index of its energy in `z`.
    pub fn dissipative(&self) -> impl Iterator<Item = (usize, usize)> + '_ {
        self.energies.iter().copied()
    }

    /// Whose entry `index` of `z` is: `(component, Some(k))` for its state
    /// `k`, `(component, None)` for the energy it dissipated.
    pub fn owner(&self, index: usize) -> Option<(usize, Option<usize>)> {
        let state = (self.states.iter())
            .find(|&&(_, offset, count)| (offset..offset + count).contains(&index))
            .map(|&(c, offset, _)| (c, Some(index - offset)));
        let energy = || {
            (self.energies.iter())
                .find(|&&(_, at)| at == index)
                .map(|&(c, _)| (c, None))
        };
        state.or_else(energy)
    }

    /// The columns of `z`, `(NAME.STATE, unit)`, in its order.
    pub fn columns(&self, components: &[NamedComponent]) -> Vec<(String, Option<String>)> {
        let mut columns = Vec::new();
        for &(c, _, _) in &self.states {
            let named = &components[c];
            columns.extend(named.states().iter().map(|column| {
                let name = format!("{}.{}", named.name, column.quantity);
                (name, Some(column.unit.to_string()))
            }));
        }
        for &(c, _) in &self.energies {
            let name = format!("{}.{DISSIPATED}", components[c].name);
            columns.push((name, Some("J".to_string())));
        }
        columns
    }
}

/// More internal states than a run carries.
#[derive(Clone, Copy, Debug, PartialEq, thiserror::Error)]
#[error(
    "the scenario's components have {states} internal states (with one dissipated energy per dissipative component); a run carries at most {INTERNAL_CAPACITY}"
)]
pub struct TooManyStates {
    /// The states the components have, dissipated energies included.
    pub states: usize,
}
