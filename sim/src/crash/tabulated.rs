//! A tabulated function of one argument: a column of a CSV table against
//! its time column (a barrier force history, say), interpolated linearly.
//!
//! Its scenario section is `type = "table"` (`TableSection`): one file,
//! and one component per column it binds, named `NAME.INPUT`.

use super::curve::{Curve, OutOfRange, Outside};
use super::table::Table;
use super::{Binder, Component, Event, Port, Section};
use crate::scenario::bind::outside;
use serde::Deserialize;
use std::collections::BTreeMap;
use std::path::Path;

/// `y(x)` from a table: its value and slope at the input's first argument.
#[derive(Clone, Debug, PartialEq)]
pub struct Tabulated {
    /// The curve through the table's rows.
    pub curve: Curve,
}

impl Component for Tabulated {
    fn kind(&self) -> &'static str {
        "table"
    }

    fn arguments(&self) -> Option<(usize, &'static str)> {
        Some((1, "the time or abscissa of the table"))
    }

    /// `y`, `dy/dx`, and 0 for the derivative by a second argument it does
    /// not have.
    fn value(&self, port: Port, args: &[f64]) -> Result<f64, OutOfRange> {
        match port {
            Port::Value => Ok(self.curve.eval(args[0])?.0),
            Port::Stiffness => Ok(self.curve.eval(args[0])?.1),
            Port::Damping => Ok(0.0),
        }
    }

    /// None: it keeps no state.
    fn events(&self) -> &'static [Event] {
        &[]
    }

    fn event_values(&self, _args: &[f64], _g: &mut [f64]) -> Result<(), OutOfRange> {
        Ok(())
    }

    fn on_event(&mut self, _k: usize, _t: f64, _args: &[f64]) -> Result<String, OutOfRange> {
        Ok(String::new())
    }

    fn start(&mut self, _args: Option<&[f64]>) -> Result<(), OutOfRange> {
        Ok(())
    }
}

/// `[components.NAME]` with `type = "table"`: a CSV file, its time column,
/// and the model inputs its other columns supply (`columns = { input =
/// "column" }`).
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct TableSection {
    file: String,
    #[serde(default = "time")]
    time_column: String,
    columns: BTreeMap<String, String>,
    #[serde(default = "zero")]
    outside: String,
}

fn time() -> String {
    "t".into()
}
fn zero() -> String {
    "zero".into()
}

impl Section for TableSection {
    /// Reads the file (relative to `base`) and checks that every column it
    /// names is there, against increasing times.
    fn load_table(&self, name: &str, base: &Path) -> Result<Option<Table>, String> {
        let at = |e: &dyn std::fmt::Display| format!("components.{name}: {e}");
        let table = Table::load(&base.join(&self.file)).map_err(|e| at(&e))?;
        for column in self.columns.values() {
            table
                .curve(&self.time_column, column, Outside::Hold)
                .map_err(|e| at(&e))?;
        }
        Ok(Some(table))
    }

    fn build(&self, name: &str, binder: &mut Binder) -> Result<(), String> {
        let policy = outside(&format!("components.{name}"), &self.outside)?;
        let table = binder.table(name)?;
        for (input, column) in &self.columns {
            let curve = table
                .curve(&self.time_column, column, policy)
                .map_err(|e| format!("components.{name}: {e}"))?;
            let c = binder.add(format!("{name}.{input}"), Box::new(Tabulated { curve }));
            let key = format!("components.{name}.columns.{input}");
            binder.bind(&key, input, (c, Port::Value))?;
        }
        Ok(())
    }
}
