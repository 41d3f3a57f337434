//! Constant values for input functions of any arguments.
//!
//! Its scenario section is `type = "constant"` (`ConstantSection`), one
//! component per input it gives a value, named `NAME.INPUT`; `--set
//! INPUT=VALUE` adds one too.

use super::{Binder, Component, Port, Section, Smoothness};
use crate::components::section::Named;
use crate::curve::OutOfRange;
use crate::entry::finite;
use crate::entry::{EntryError, KeyPath};
use serde::Deserialize;
use std::collections::BTreeMap;

/// A constant value; its derivatives are 0.
#[derive(Clone, Debug, PartialEq)]
pub struct Constant {
    /// The value.
    pub value: f64,
}

impl Constant {
    /// Its [`Component::kind`], the `type` of its scenario section.
    pub const KIND: &'static str = "constant";
}

impl Component for Constant {
    fn kind(&self) -> &'static str {
        Constant::KIND
    }

    fn arguments(&self) -> Option<(usize, &'static str)> {
        None
    }

    fn value(&self, port: Port, _args: &[f64]) -> Result<f64, OutOfRange> {
        match port {
            Port::Value => Ok(self.value),
            Port::Stiffness | Port::Damping => Ok(0.0),
        }
    }

    /// Always: the inputs bound to it need not call it.
    fn constant(&self, port: Port) -> Option<f64> {
        self.value(port, &[]).ok()
    }

    capabilities!(events: no, states: no, energy: no);

    fn smoothness(&self) -> Smoothness {
        Smoothness::Smooth
    }
}

/// `[components.NAME]` with `type = "constant"`: `values = { input = value }`.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct ConstantSection {
    values: BTreeMap<String, f64>,
}

/// No entry of it is a quantity: what it reads is in its file or in the
/// unit of the input it sets.
impl super::SectionUnits for ConstantSection {
    const UNITS: &'static [(&'static str, super::Measure)] = &[];
}

impl Section for ConstantSection {
    fn build(&self, name: &str, binder: &mut Binder) -> Result<(), EntryError> {
        for (input, value) in &self.values {
            let key = KeyPath::new("components")
                .join(name)
                .join("values")
                .join(input);
            let value = finite(&key, *value)?;
            let c = binder.add(format!("{name}.{input}"), Box::new(Constant { value }));
            binder.bind((&key, Named::ByKey), input, (c, Port::Value))?;
        }
        Ok(())
    }
}
