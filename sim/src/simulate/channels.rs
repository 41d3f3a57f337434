//! The metrics of the scenario's channels (`[metrics] displacement`,
//! `velocity`, `acceleration`, `force`): extremes and their times for every channel;
//! for an acceleration also its peak magnitude, its peaks after SAE J211
//! CFC 60, CFC 180 and its own class's filtering and the 3 ms clip of the
//! latter, in units of `g`: each filtered metric where the samples' rate
//! gives its class.

use crate::pulse::cfc::DEFAULT_CLASS;
use crate::pulse::{Pulse, STANDARD_GRAVITY, cfc_filter, clip_3ms};
use crate::scenario::{Channel, Columns, Role};
use serde::ser::{Serialize, SerializeMap, Serializer};

/// The names of a channel's metrics, in the order of `summary.json` and the
/// columns of a sweep table; the acceleration metrics only for an
/// acceleration channel.
pub const CHANNEL_METRICS: [&str; 4] = ["max", "time_of_max_s", "min", "time_of_min_s"];

/// The further metrics of an acceleration channel.
pub const ACCELERATION_METRICS: [&str; 6] = [
    "peak_g",
    "time_of_peak_s",
    "cfc60_peak_g",
    "cfc180_peak_g",
    "cfc_peak_g",
    "clip3ms_g",
];

/// The metric names of a channel of `role`, in order.
pub fn metric_names(role: Role) -> Vec<&'static str> {
    let mut names = CHANNEL_METRICS.to_vec();
    if role == Role::Acceleration {
        names.extend(ACCELERATION_METRICS);
    }
    names
}

/// The metrics of one channel.
#[derive(Clone, Debug, PartialEq)]
pub struct ChannelSummary {
    /// The channel as the scenario names it (`"xa - xb"`).
    pub name: String,
    /// What it measures.
    pub role: Role,
    /// The unit of its values, where the spec declares it.
    pub unit: Option<String>,
    /// The filter class of its `cfc_peak_g` and `clip3ms_g` (an
    /// acceleration's).
    pub cfc: f64,
    /// The values of [`metric_names`]`(role)`, in order; `None` where the
    /// run cannot say (no samples, a record too short to filter).
    pub values: Vec<Option<f64>>,
    /// `true` when an extreme is the last sample: the signal may still be
    /// growing at the end of the run, and its extreme lies beyond it.
    pub extreme_at_end: bool,
}

impl ChannelSummary {
    /// The value of metric `name`, if the channel has it.
    pub fn get(&self, name: &str) -> Option<f64> {
        let k = metric_names(self.role).iter().position(|n| *n == name)?;
        self.values[k]
    }
}

impl ChannelSummary {
    /// The channel's line of the text summary: extremes with their times,
    /// and for an acceleration its peaks in g.
    pub fn text_line(&self) -> String {
        let value = |name: &str| match self.get(name) {
            Some(x) => format!("{x:.4}"),
            None => "–".into(),
        };
        let ms = |name: &str| match self.get(name) {
            Some(t) => format!("{:.1} ms", t * 1e3),
            None => "–".into(),
        };
        let unit = self
            .unit
            .as_deref()
            .map(|u| format!(" [{u}]"))
            .unwrap_or_default();
        let mut line = format!(
            "{}{unit}: max {} at {}, min {} at {}",
            self.name,
            value("max"),
            ms("time_of_max_s"),
            value("min"),
            ms("time_of_min_s")
        );
        if self.role == Role::Acceleration {
            let g = |name: &str| match self.get(name) {
                Some(x) => format!("{x:.1} g"),
                None => "–".into(),
            };
            let own = match self.cfc == 60.0 || self.cfc == 180.0 {
                true => String::new(),
                false => format!(", CFC {} {}", self.cfc, g("cfc_peak_g")),
            };
            let clip = match self.cfc == DEFAULT_CLASS {
                true => String::new(),
                false => format!(" (CFC {})", self.cfc),
            };
            line.push_str(&format!(
                "; peak {} at {}, CFC 60 {}, CFC 180 {}{own}, 3 ms clip{clip} {}",
                g("peak_g"),
                ms("time_of_peak_s"),
                g("cfc60_peak_g"),
                g("cfc180_peak_g"),
                g("clip3ms_g")
            ));
        }
        if self.extreme_at_end {
            line.push_str(" (still changing at the end: the extreme may lie beyond t_end)");
        }
        line
    }
}

/// The channels of a summary: `summary.json` writes them as an object
/// keyed by channel name.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Channels(pub Vec<ChannelSummary>);

impl Serialize for ChannelSummary {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        let mut map = serializer.serialize_map(None)?;
        map.serialize_entry("role", self.role.name())?;
        map.serialize_entry("unit", &self.unit)?;
        if self.role == Role::Acceleration {
            map.serialize_entry("cfc", &self.cfc)?;
        }
        for (name, value) in metric_names(self.role).iter().zip(&self.values) {
            map.serialize_entry(name, value)?;
        }
        map.serialize_entry("extreme_at_end", &self.extreme_at_end)?;
        map.end()
    }
}

impl Serialize for Channels {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        let mut map = serializer.serialize_map(Some(self.0.len()))?;
        for channel in &self.0 {
            map.serialize_entry(&channel.name, channel)?;
        }
        map.end()
    }
}

/// One channel's samples, kept until the end of the run (filtering needs
/// the whole record); their times are the run's, kept once for all
/// channels.
#[derive(Clone, Debug)]
pub struct ChannelRecord {
    channel: Channel,
    values: Vec<f64>,
}

impl ChannelRecord {
    /// An empty record of `channel`, with room for `samples` samples.
    pub fn new(channel: Channel, samples: usize) -> ChannelRecord {
        ChannelRecord {
            channel,
            values: Vec::with_capacity(samples),
        }
    }

    /// Adds the channel's value at the next sample (in time order).
    #[inline]
    pub fn push(&mut self, columns: &Columns) {
        self.values.push(self.channel.signal.value(columns));
    }

    /// The channel's metrics, its samples taken at `times` (one per
    /// sample); accelerations in units of standard gravity.
    pub fn summary(&self, times: &[f64]) -> ChannelSummary {
        let t = &times[..self.values.len()];
        let (max, min) = self.extremes();
        let at = |k: Option<usize>| k.map(|k| self.values[k]);
        let time = |k: Option<usize>| k.map(|k| t[k]);
        let mut values = vec![at(max), time(max), at(min), time(min)];
        if self.channel.role == Role::Acceleration {
            values.extend(self.acceleration_metrics(t));
        }
        let last = self.values.len().checked_sub(1);
        let moving_at_end = last.is_some_and(|k| k > 0 && self.values[k] != self.values[k - 1]);
        ChannelSummary {
            name: self.channel.signal.name.clone(),
            role: self.channel.role,
            unit: self.channel.signal.unit.clone(),
            cfc: self.channel.cfc,
            values,
            extreme_at_end: moving_at_end && (max == last || min == last),
        }
    }

    /// The indices of the largest and the smallest finite sample, the
    /// first of equals.
    fn extremes(&self) -> (Option<usize>, Option<usize>) {
        let values = &self.values;
        let Some(first) = values.iter().position(|x| x.is_finite()) else {
            return (None, None);
        };
        let (mut max, mut min) = ((first, values[first]), (first, values[first]));
        // A NaN compares false; an infinity passes a comparison but is not
        // finite.
        for (k, &x) in values.iter().enumerate().skip(first + 1) {
            if x > max.1 && x.is_finite() {
                max = (k, x);
            }
            if x < min.1 && x.is_finite() {
                min = (k, x);
            }
        }
        (Some(max.0), Some(min.0))
    }

    /// `[peak_g, time_of_peak_s, cfc60_peak_g, cfc180_peak_g, cfc_peak_g,
    /// clip3ms_g]`: magnitudes, the filtered ones on the record resampled
    /// onto an even grid, each where the rate gives its class; the clip of
    /// the signal of the channel's class, as occupant criteria take it.
    fn acceleration_metrics(&self, t: &[f64]) -> [Option<f64>; 6] {
        let g = STANDARD_GRAVITY;
        let peak = (self.values.iter().enumerate())
            .filter(|(_, x)| x.is_finite())
            .fold(None, |best: Option<(usize, f64)>, (k, &x)| match best {
                Some((_, m)) if m >= x.abs() => best,
                _ => Some((k, x.abs())),
            });
        let peak_g = peak.map(|(_, m)| m / g);
        let time = peak.map(|(k, _)| t[k]);
        let Ok(pulse) = Pulse::resampled(t, &self.values, 0.0, None) else {
            return [peak_g, time, None, None, None, None];
        };
        let dt = pulse.t[1] - pulse.t[0];
        let filtered = |cfc: f64| cfc_filter(&pulse.acceleration, dt, cfc).ok();
        let magnitude = |a: &[f64]| a.iter().fold(0.0f64, |m, x| m.max(x.abs())) / g;
        let cfc60 = filtered(60.0);
        let cfc180 = filtered(180.0);
        let own = match self.channel.cfc {
            60.0 => cfc60.clone(),
            180.0 => cfc180.clone(),
            cfc => filtered(cfc),
        };
        [
            peak_g,
            time,
            cfc60.as_deref().map(magnitude),
            cfc180.as_deref().map(magnitude),
            own.as_deref().map(magnitude),
            own.and_then(|a| clip_3ms(&a, dt)).map(|c| c / g),
        ]
    }

    /// The filter classes the channel's metrics take, each with what goes
    /// without it: `(class, what)` pairs, none for a channel that is not an
    /// acceleration.
    pub fn filter_needs(&self) -> Vec<(f64, String)> {
        if self.channel.role != Role::Acceleration {
            return Vec::new();
        }
        let name = &self.channel.signal.name;
        let mut needs = vec![
            (
                60.0,
                format!("the CFC 60 peak of channel `{name}` is not computed"),
            ),
            (
                180.0,
                format!("the CFC 180 peak of channel `{name}` is not computed"),
            ),
        ];
        let own = format!(
            "the CFC {} peak and 3 ms clip of channel `{name}` are not computed",
            self.channel.cfc
        );
        match needs.iter_mut().find(|(cfc, _)| *cfc == self.channel.cfc) {
            Some(need) => need.1 = own,
            None => needs.push((self.channel.cfc, own)),
        }
        needs
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scenario::{Column, Signal};

    fn record(values: &[f64]) -> ChannelRecord {
        let signal = Signal {
            name: "x".into(),
            terms: vec![(1.0, Column::Coordinate(0))],
            offset: 0.0,
            unit: None,
        };
        let channel = Channel {
            role: Role::Displacement,
            signal,
            cfc: crate::pulse::cfc::DEFAULT_CLASS,
        };
        let mut record = ChannelRecord::new(channel, 0);
        for x in values {
            record.push(&Columns::coordinates(std::slice::from_ref(x)));
        }
        record
    }

    /// The sample times of [`record`]: `k` seconds.
    fn times(count: usize) -> Vec<f64> {
        (0..count).map(|k| k as f64).collect()
    }

    #[test]
    fn extremes_are_the_first_of_equal_finite_samples() {
        let nan = f64::NAN;
        type Extremes = (Option<usize>, Option<usize>);
        let cases: [(&[f64], Extremes); 5] = [
            (&[], (None, None)),
            (&[nan, f64::INFINITY], (None, None)),
            (&[nan, 2.0, -1.0, 2.0, -1.0], (Some(1), Some(2))),
            (&[3.0, 3.0, 3.0], (Some(0), Some(0))),
            (
                &[0.0, f64::NEG_INFINITY, 5.0, nan, -4.0, 5.0],
                (Some(2), Some(4)),
            ),
        ];
        for (values, expected) in cases {
            assert_eq!(record(values).extremes(), expected, "{values:?}");
        }
        let summary = record(&[1.0, 4.0, -2.0, 0.5]).summary(&times(4));
        assert_eq!(
            summary.values,
            [Some(4.0), Some(1.0), Some(-2.0), Some(2.0)]
        );
        assert!(!summary.extreme_at_end);
    }
}
