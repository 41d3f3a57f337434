//! A tabulated function of one argument: a column of a CSV table against
//! its time column (a barrier force history, say), interpolated linearly,
//! or by a monotone cubic (`interpolation = "pchip"`: C¹, no kinks).
//!
//! The slope of a table interpolated linearly jumps at its points. A step
//! of an adaptive explicit method across such a kink reads, by default, the
//! table's smooth stand-in over the step (`[simulation] time_kinks`,
//! `TimeKinks`), which keeps a finely sampled history
//! from cutting every step short. With `stop_at_kinks = true` the
//! integrator ends a step at each kink instead: a choice for a table of
//! few points with sharp corners (a pulse of straight segments), where the
//! corners themselves matter; for a finely sampled history it makes every
//! step as short as the rows are apart.
//!
//! Its scenario section is `type = "table"` (`TableSection`): one file,
//! and one component per column it binds, named `NAME.INPUT`.

use super::{Binder, Component, Port, Section, Smoothness};
use crate::components::section::Named;
use crate::curve::outside;
use crate::curve::{Curve, OutOfRange, Outside};
use crate::entry::{EntryError, KeyPath};
use crate::files::Files;
use crate::table::Table;
use serde::Deserialize;
use std::collections::BTreeMap;
use std::path::Path;
use std::sync::Arc;

/// `y(x)` from a table: its value and slope at the input's first argument.
#[derive(Clone, Debug, PartialEq)]
pub struct Tabulated {
    /// The curve through the table's rows.
    pub curve: Curve,
    /// Whether the integrator ends a step at each kink of the curve.
    pub stop_at_kinks: bool,
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

    /// 0 for a column of zeros (with a value outside its rows), and for
    /// the derivative by a second argument.
    fn constant(&self, port: Port) -> Option<f64> {
        match port {
            Port::Value | Port::Stiffness => self.curve.is_zero_everywhere().then_some(0.0),
            Port::Damping => Some(0.0),
        }
    }

    capabilities!(events: no, states: no, energy: no);

    /// Linear between the points of a table interpolated linearly (and
    /// beyond its ends); a monotone cubic is smooth between its corners
    /// ([`Curve::corners`]). Steps end at the points of a table
    /// interpolated linearly when it asks for it (`stop_at_kinks`).
    fn smoothness(&self) -> Smoothness {
        match self.curve.is_smooth() {
            true => Smoothness::Kinks(self.curve.corners()),
            false => Smoothness::Linear {
                points: self.curve.corners(),
                stops: self.stop_at_kinks,
            },
        }
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
    /// `linear` (the default) or `pchip`.
    #[serde(default = "linear")]
    interpolation: String,
    /// Steps end at the kinks of the linear interpolation.
    #[serde(default)]
    stop_at_kinks: bool,
}

/// No entry of it is a quantity: what it reads is in its file or in the
/// unit of the input it sets.
impl super::SectionUnits for TableSection {
    const UNITS: &'static [(&'static str, super::Measure)] = &[];
}

fn time() -> String {
    "t".into()
}
fn zero() -> String {
    "zero".into()
}
fn linear() -> String {
    "linear".into()
}

/// Whether `interpolation` asks for the monotone cubic (`pchip`) rather
/// than straight lines (`linear`).
fn smooth(name: &str, interpolation: &str) -> Result<bool, EntryError> {
    match interpolation {
        "linear" => Ok(false),
        "pchip" => Ok(true),
        other => Err(EntryError::text(
            format!("components.{name}.interpolation").into(),
            other,
            "expected one of linear, pchip",
        )),
    }
}

impl Section for TableSection {
    /// Reads the file (relative to `base`) and checks that every column it
    /// names is there, against increasing times.
    fn load_table(
        &self,
        files: &dyn Files,
        name: &str,
        base: &Path,
    ) -> Result<Option<Arc<Table>>, EntryError> {
        let at = |e: &dyn std::fmt::Display| {
            EntryError::at(KeyPath::new("components").join(name), e.to_string())
        };
        let table = files.table(&base.join(&self.file)).map_err(|e| at(&e))?;
        for column in self.columns.values() {
            table
                .curve(&self.time_column, column, Outside::Hold)
                .map_err(|e| at(&e))?;
        }
        Ok(Some(table))
    }

    fn build(&self, name: &str, binder: &mut Binder) -> Result<(), EntryError> {
        let policy = outside(&format!("components.{name}"), &self.outside)?;
        let smooth = smooth(name, &self.interpolation)?;
        let table = binder.table(name)?;
        for (input, column) in &self.columns {
            let curve = table
                .curve(&self.time_column, column, policy)
                .map_err(|e| {
                    EntryError::at(KeyPath::new("components").join(name), e.to_string())
                })?;
            let curve = if smooth { curve.smooth() } else { curve };
            let c = binder.add(
                format!("{name}.{input}"),
                Box::new(Tabulated {
                    curve,
                    stop_at_kinks: self.stop_at_kinks,
                }),
            );
            let key = KeyPath::new("components")
                .join(name)
                .join("columns")
                .join(input);
            binder.bind((&key, Named::ByKey), input, (c, Port::Value))?;
        }
        Ok(())
    }
}
