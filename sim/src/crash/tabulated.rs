//! A tabulated function of one argument: a column of a CSV table against
//! its time column (a barrier force history, say), interpolated linearly.
//!
//! A scenario's `type = "table"` section makes one per column it binds,
//! named `NAME.INPUT`.

use super::curve::{Curve, OutOfRange};
use super::{Component, Event, Port};

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
