//! Binding a model's input functions to the scenario's crash components:
//! each `[components.NAME]` section builds its components into a
//! [`Binder`] (see [`crate::components`]), then `--set` constants override, then
//! the components with events learn where their arguments are.

use crate::components::section::Binder;
use crate::components::{BoundInputs, ComponentSection};
use crate::entry::EntryError;
use crate::model_names::ModelNames;
use crate::table::Table;
use std::collections::BTreeMap;
use std::sync::Arc;

pub(super) fn bind_components(
    sections: &BTreeMap<String, ComponentSection>,
    tables: &BTreeMap<String, Arc<Table>>,
    names: &ModelNames,
    constants: BTreeMap<usize, f64>,
) -> Result<BoundInputs, EntryError> {
    let mut binder = Binder::new(names, tables);
    for (name, section) in sections {
        section.build(name, &mut binder)?;
    }
    // --set constants override whatever the file binds.
    for (k, value) in constants {
        binder.set_constant(k, value);
    }
    binder.finish()
}
