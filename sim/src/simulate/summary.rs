//! The summary of a run — the keys of `summary.json`, the metric columns of
//! a sweep table and the lines of the text summary — from one list.
//!
//! Each entry of the `summary!` list below is a field of [`Summary`] and a
//! [`Metric`] of [`Summary::METRICS`] (its name, and how the text summary
//! shows it); everything that lists metrics iterates that table.

use super::channels::Channels;
use crate::criteria::Criteria;
use serde::Serialize;
use std::fmt::Write as _;

/// A metric's value: a measurement (absent when the run cannot say, e.g.
/// no crush coordinate) or a count.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Value {
    /// A real number, or none.
    Real(Option<f64>),
    /// A count.
    Count(usize),
}

/// A summary field's type: how it becomes a [`Value`] and is read back from
/// the text of a table cell.
pub trait Field: Sized {
    /// The value with nothing measured.
    const EMPTY: Self;
    /// The field as a table value.
    fn value(&self) -> Value;
    /// The field from a table cell as [`Value`]'s text writes it (`""` for
    /// a missing measurement).
    fn parse(cell: &str) -> Result<Self, CellError>;
}

/// A table cell that does not read back as a summary field.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum CellError {
    /// A number's cell holds other text.
    #[error("`{0}` is not a number")]
    NotANumber(String),
    /// A count's cell holds other text.
    #[error("`{0}` is not a count")]
    NotACount(String),
    /// The column names no metric.
    #[error("`{0}` is not a metric")]
    UnknownMetric(String),
}

fn parse_real(cell: &str) -> Result<Option<f64>, CellError> {
    match cell {
        "" => Ok(None),
        text => (text.parse().map(Some)).map_err(|_| CellError::NotANumber(text.to_string())),
    }
}

impl Field for Option<f64> {
    const EMPTY: Self = None;
    fn value(&self) -> Value {
        Value::Real(*self)
    }
    fn parse(cell: &str) -> Result<Self, CellError> {
        parse_real(cell)
    }
}

impl Field for f64 {
    const EMPTY: Self = 0.0;
    fn value(&self) -> Value {
        Value::Real(Some(*self))
    }
    fn parse(cell: &str) -> Result<Self, CellError> {
        Ok(parse_real(cell)?.unwrap_or(f64::NAN))
    }
}

impl Field for usize {
    const EMPTY: Self = 0;
    fn value(&self) -> Value {
        Value::Count(*self)
    }
    fn parse(cell: &str) -> Result<Self, CellError> {
        cell.parse()
            .map_err(|_| CellError::NotACount(cell.to_string()))
    }
}

impl Value {
    /// The text of a table cell: numbers that read back exactly, empty
    /// for a missing measurement.
    pub fn cell(self) -> String {
        match self {
            Value::Real(Some(x)) => format!("{x:?}"),
            Value::Real(None) => String::new(),
            Value::Count(n) => n.to_string(),
        }
    }
}

/// How the text summary shows a metric: on a line of its own under `label`,
/// or, without one, after the previous metric on its line.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Text {
    /// The line's label; `None` continues the previous metric's line.
    pub label: Option<&'static str>,
    /// The unit shown (after scaling).
    pub unit: &'static str,
    /// The factor from the stored unit to the one shown (1e3 for s → ms).
    pub scale: f64,
    /// Digits after the decimal point.
    pub digits: usize,
    /// Scientific notation instead of fixed.
    pub scientific: bool,
    /// What stands for a missing value.
    pub missing: &'static str,
    /// Written at the end of the line.
    pub note: &'static str,
}

impl Text {
    const fn line(label: &'static str, unit: &'static str, digits: usize) -> Text {
        Text {
            label: Some(label),
            unit,
            scale: 1.0,
            digits,
            scientific: false,
            missing: "–",
            note: "",
        }
    }

    const fn more(unit: &'static str, digits: usize) -> Text {
        Text {
            label: None,
            ..Text::line("", unit, digits)
        }
    }

    const fn in_ms(self) -> Text {
        Text {
            unit: "ms",
            scale: 1e3,
            ..self
        }
    }

    const fn note(self, note: &'static str) -> Text {
        Text { note, ..self }
    }

    const fn missing(self, missing: &'static str) -> Text {
        Text { missing, ..self }
    }

    const fn scientific(self) -> Text {
        Text {
            scientific: true,
            ..self
        }
    }

    /// The value as shown.
    fn show(&self, value: Value) -> String {
        let x = match value {
            Value::Real(Some(x)) => x * self.scale,
            Value::Real(None) => return self.missing.to_string(),
            Value::Count(n) => n as f64,
        };
        let number = if self.scientific {
            format!("{x:.*e}", self.digits)
        } else {
            format!("{x:.*}", self.digits)
        };
        match self.unit {
            "" => number,
            unit => format!("{number} {unit}"),
        }
    }
}

/// One metric of [`Summary`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Metric {
    /// The key in `summary.json` and the column of a sweep table.
    pub name: &'static str,
    /// How the text summary shows it; `None`: not there (the solver's
    /// counts, which it shows on their own line).
    pub text: Option<Text>,
}

/// Defines [`Summary`] with one field per entry and [`Summary::METRICS`]
/// with the entries in the same order.
macro_rules! summary {
    ($($(#[doc = $doc:literal])* $name:ident: $type:ty => $text:expr,)*) => {
        /// The metrics of a run (`summary.json`), in [`Summary::METRICS`]
        /// order, then the scenario's channels.
        #[derive(Clone, Debug, PartialEq, Serialize)]
        pub struct Summary {
            $($(#[doc = $doc])* pub $name: $type,)*
            /// The metrics of the scenario's channels (`[metrics]
            /// displacement`, `velocity`, `acceleration`, `force`), by name.
            pub channels: Channels,
            /// The injury criteria of the occupant channels the scenario
            /// names (`[iso_mme.channels]` with a dummy's channel codes);
            /// not in `summary.json` when there are none.
            #[serde(skip_serializing_if = "Criteria::is_empty")]
            pub criteria: Criteria,
            /// The energy each dissipative component (a damper, a
            /// hysteretic spring, a contact or friction element) dissipated
            /// over the run, by name, in scenario order \[J\]; not in
            /// `summary.json` when there is none.
            #[serde(
                skip_serializing_if = "Vec::is_empty",
                serialize_with = "by_name"
            )]
            pub dissipated_by: Vec<(String, f64)>,
            /// The crush channel still compresses at the end of the run,
            /// so that its largest crush is not the maximum (the
            /// `still_crushing` warning says so in `summary.json`; the
            /// text summary's headline line says it too).
            #[serde(skip)]
            pub still_crushing: bool,
        }

        impl Summary {
            /// Every metric, in field order.
            pub const METRICS: &'static [Metric] = &[
                $(Metric { name: stringify!($name), text: $text },)*
            ];

            /// A summary with nothing measured.
            pub const EMPTY: Summary = Summary {
                $($name: <$type as Field>::EMPTY,)*
                channels: Channels(Vec::new()),
                criteria: Criteria::EMPTY,
                dissipated_by: Vec::new(),
                still_crushing: false,
            };

            /// The values, in [`Summary::METRICS`] order.
            pub fn values(&self) -> Vec<Value> {
                vec![$(self.$name.value(),)*]
            }

            /// Sets metric `name` from the text of its table cell.
            pub fn set(&mut self, name: &str, cell: &str) -> Result<(), CellError> {
                match name {
                    $(stringify!($name) => self.$name = Field::parse(cell)?,)*
                    _ => return Err(CellError::UnknownMetric(name.to_string())),
                }
                Ok(())
            }
        }
    };
}

summary! {
    /// Largest crush \[m\].
    max_crush_m: Option<f64> => Some(Text::line("max dynamic crush", "m", 3)),
    /// When the crush was largest \[s\].
    time_of_max_crush_s: Option<f64> => Some(Text::line("at", "", 1).in_ms()),
    /// First time the velocity towards the barrier reaches zero \[s\].
    time_to_zero_velocity_s: Option<f64> =>
        Some(Text::line("time to zero velocity", "", 1).in_ms()),
    /// Crush when the contact ended: the permanent crush after unloading
    /// \[m\] (none while still in contact at the end of the run).
    permanent_crush_m: Option<f64> =>
        Some(Text::line("permanent crush, at", "m", 3)),
    /// When the last contact element lost contact: the end of the pulse \[s\].
    end_of_contact_s: Option<f64> => Some(Text::more("", 1).in_ms()),
    /// The first pitch coordinate's deviation of largest magnitude from
    /// equilibrium, signed [°].
    max_theta1_deg: Option<f64> => Some(Text::line("max pitch θ1, θ2", "°", 2)),
    /// The second pitch coordinate's, likewise [°].
    max_theta2_deg: Option<f64> =>
        Some(Text::more("°", 2).note(" (from static equilibrium)")),
    /// The first pitch coordinate's deviation of largest magnitude up to
    /// the end of the contact, signed [°].
    max_theta1_in_pulse_deg: Option<f64> => Some(Text::line("max pitch in the pulse", "°", 2)),
    /// The second pitch coordinate's, likewise [°].
    max_theta2_in_pulse_deg: Option<f64> => Some(Text::more("°", 2)),
    /// Largest deceleration, unfiltered \[g\].
    peak_deceleration_g: Option<f64> =>
        Some(Text::line("peak deceleration", "g", 1).note(" (unfiltered)")),
    /// Largest speed away from the barrier after the peak crush [m/s].
    rebound_velocity_mps: Option<f64> => Some(Text::line("rebound velocity", "m/s", 2)),
    /// When the weld failed \[s\].
    weld_failure_time_s: Option<f64> =>
        Some(Text::line("weld failure", "", 1).in_ms().missing("none")),
    /// Largest deceleration after SAE J211 CFC 60 filtering \[g\].
    peak_deceleration_cfc60_g: Option<f64> => Some(Text::line("CFC 60 peak, ESW", "g", 1)),
    /// `v0² / (2 g C)` with the maximum crush `C` \[g\].
    equivalent_square_wave_g: Option<f64> => Some(Text::more("g", 1)),
    /// Occupant load criterion (Euro NCAP) of the crush coordinate's pulse \[g\].
    olc_g: Option<f64> => Some(Text::line("OLC, ASI", "g", 1)),
    /// Acceleration severity index (EN 1317-1), longitudinal component.
    asi: Option<f64> => Some(Text::more("", 2)),
    /// Accepted steps of the integration.
    steps: usize => None,
    /// Rejected steps.
    rejected_steps: usize => None,
    /// Evaluations of the right-hand side.
    rhs_evaluations: usize => None,
    /// `max |(T + V + dissipated − external work)(t) − (T + V)(0)| / (T(0) + |V(0)|)`
    /// over the start and the ends of the integration's steps.
    energy_balance_error_rel: f64 =>
        Some(Text::line("energy balance error", "", 1).scientific().note(" (relative)")),
}

impl Summary {
    /// The metric lines of the text summary: `  label  value[, value…]note`.
    pub fn text_lines(&self) -> String {
        let mut out = String::new();
        for row in self.rows() {
            let shown: Vec<&str> = row.values.iter().map(|(_, v)| v.as_str()).collect();
            let _ = writeln!(out, "  {:<23}{}{}", row.label, shown.join(", "), row.note);
        }
        for (name, energy) in &self.dissipated_by {
            let _ = writeln!(out, "  dissipated by {name:<8} {energy:.4e} J");
        }
        out
    }

    /// The metrics as the text summary and the report show them, a row a
    /// label: the rows of [`Summary::METRICS`] with a [`Text`].
    pub fn rows(&self) -> Vec<Row> {
        let mut rows: Vec<Row> = Vec::new();
        for (metric, value) in Summary::METRICS.iter().zip(self.values()) {
            let Some(text) = metric.text else { continue };
            let shown = (metric.name, text.show(value));
            match (text.label, rows.last_mut()) {
                (None, Some(row)) => row.values.push(shown),
                (label, _) => rows.push(Row {
                    label: label.unwrap_or(""),
                    values: vec![shown],
                    note: "",
                }),
            }
            if let Some(row) = rows.last_mut() {
                row.note = match metric.name == "max_crush_m" && self.still_crushing {
                    true => " (still crushing at t_end: not the maximum)",
                    false => text.note,
                };
            }
        }
        rows
    }
}

/// A line of the summary: its label, its metrics (their `summary.json`
/// key and their value as shown, with its unit) and a note.
#[derive(Clone, Debug, PartialEq)]
pub struct Row {
    /// What the line shows (`max dynamic crush`).
    pub label: &'static str,
    /// `(key, value as shown)` of each metric on the line.
    pub values: Vec<(&'static str, String)>,
    /// Said after the values (`(unfiltered)`), or empty.
    pub note: &'static str,
}

/// `[(name, energy)]` as the map `{name: energy}`.
fn by_name<S: serde::Serializer>(entries: &[(String, f64)], s: S) -> Result<S::Ok, S::Error> {
    s.collect_map(entries.iter().map(|(name, energy)| (name, energy)))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_metrics_are_the_keys_of_summary_json_in_order() {
        let json = serde_json::to_string(&Summary::EMPTY).unwrap();
        let mut position = 0;
        for metric in Summary::METRICS {
            let key = format!("\"{}\":", metric.name);
            let at = json[position..].find(&key).map(|k| k + position);
            assert!(
                at.is_some(),
                "{} is not after position {position} in {json}",
                metric.name
            );
            position = at.unwrap_or(position);
        }
        let keys = serde_json::to_value(Summary::EMPTY).unwrap();
        let keys = keys.as_object().unwrap();
        assert_eq!(keys.len(), Summary::METRICS.len() + 1);
        assert_eq!(keys["channels"], serde_json::json!({}));
    }

    #[test]
    fn every_metric_reads_back_from_its_cell() {
        let mut summary = Summary::EMPTY;
        for (k, metric) in Summary::METRICS.iter().enumerate() {
            let cell = match Summary::EMPTY.values()[k] {
                Value::Real(_) => format!("{:?}", 0.25 + k as f64),
                Value::Count(_) => (10 + k).to_string(),
            };
            summary.set(metric.name, &cell).unwrap();
            assert_eq!(summary.values()[k].cell(), cell, "{}", metric.name);
        }
        assert_eq!(
            summary.set("max_crush", "1.0"),
            Err(CellError::UnknownMetric("max_crush".into()))
        );
    }

    #[test]
    fn the_text_shows_units_groups_and_missing_values() {
        let summary = Summary {
            max_crush_m: Some(0.5468),
            time_of_max_crush_s: Some(0.06641),
            max_theta1_deg: Some(-13.613),
            max_theta2_deg: None,
            asi: Some(2.114),
            olc_g: Some(29.46),
            energy_balance_error_rel: 3.4e-10,
            ..Summary::EMPTY
        };
        let text = summary.text_lines();
        let lines: Vec<&str> = text.lines().collect();
        assert_eq!(lines[0], "  max dynamic crush      0.547 m");
        assert_eq!(lines[1], "  at                     66.4 ms");
        assert_eq!(lines[2], "  time to zero velocity  –");
        assert_eq!(lines[3], "  permanent crush, at    –, –");
        assert_eq!(
            lines[4],
            "  max pitch θ1, θ2       -13.61 °, – (from static equilibrium)"
        );
        assert_eq!(lines[5], "  max pitch in the pulse –, –");
        assert_eq!(lines[8], "  weld failure           none");
        assert_eq!(lines[10], "  OLC, ASI               29.5 g, 2.11");
        assert_eq!(lines[11], "  energy balance error   3.4e-10 (relative)");
        assert_eq!(lines.len(), 12);
    }
}
